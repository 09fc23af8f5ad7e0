// <qmotion/sweep/factors.hpp>
#pragma once
#include <qmotion/kernel/motion_factors.hpp>
#include <qmotion/kernel/motion_value.hpp>

namespace qmotion::sweep {

using kernel::factors_match;
using kernel::Motion;
using kernel::MotionFactors;

}  // namespace qmotion::sweep
