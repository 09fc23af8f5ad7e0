// <qmotion/api/demo.hpp>: the main job on embedded poses (what `qmotion demo` runs).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace qmotion {

/// The demo: five embedded poses -> elliptic + TR Bezier motion -> the trajectories of the
/// origin and of (0,0,1) and the kinematic surface of a parabola -> JSON, STEP and IGES,
/// each checked against the motion, plus demo.svg and report.json, written into `dir`
/// (created if missing). All or nothing: the files are built in a scratch folder and
/// published together; on any failure `dir` is left as it was. Returns the report (the
/// content of report.json).
nlohmann::json write_demo(const std::string& dir);

}  // namespace qmotion
