// <qmotion/qmotion.hpp>: everything a user needs for the whole job, in one include.
// Poses -> motion (kernel) -> trajectories and kinematic surfaces (sweep) -> JSON, STEP,
// IGES and the exactness check (io). Namespaces: qmotion::kernel, qmotion::sweep,
// qmotion::io.
#pragma once

#include <qmotion/api/animate.hpp>
#include <qmotion/api/compare.hpp>
#include <qmotion/api/demo.hpp>
#include <qmotion/api/evaluate.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/api/fit.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/motion_info.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/api/verify.hpp>
#include <qmotion/api/view.hpp>
#include <qmotion/api/volume.hpp>
#include <qmotion/cam/cam_nurbs.hpp>
#include <qmotion/cam/tool_trajectories.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/gcode.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/mesh.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/occt_info.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/io/progress.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/dual_quaternion.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/methods.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/motion_value.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/kernel/quaternion.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/render/canvas.hpp>
#include <qmotion/render/render.hpp>
#include <qmotion/render/view.hpp>
#include <qmotion/sweep/factors.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/shell.hpp>
#include <qmotion/sweep/solid.hpp>
#include <qmotion/sweep/surface.hpp>
#include <qmotion/sweep/trajectory.hpp>
#ifdef QMOTION_WITH_CGAL
#include <qmotion/api/exact_check.hpp>  // check --exact
#endif
