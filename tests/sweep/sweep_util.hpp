// tests/sweep/sweep_util.hpp: what the sweep tests share.
#pragma once
#include <qmotion/sweep/factors.hpp>

namespace qmotion::test {

/// A motion and its Hurwitz factors, as the sweep functions take them.
struct Built {
  kernel::Motion<double> r;
  sweep::MotionFactors<double> f;
};

}  // namespace qmotion::test
