// A user's program against the installed qmotion (find_package(qmotion), <qmotion/...>):
// the main job through library calls only. Five poses -> elliptic + TR motion -> the
// kinematic surface of a circle as a sewn STEP shell and as a closed solid -> read back
// through OpenCASCADE and checked against the motion; then a quaternion spline's sweep,
// fitted within a tolerance.
// Usage: consumer OUT_DIR   (exit 0 when the files are exact and valid)
#include <cmath>
#include <filesystem>
#include <iostream>
#include <qmotion/qmotion.hpp>

namespace qm = qmotion;

constexpr const char* kPoses = R"({"units":"mm","poses":[
 {"t":0,"position":[0,0,0],"rotation":{"quaternion":[1,0,0,0]}},
 {"t":0.5,"position":[1,0,10],"rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":30}}},
 {"t":1,"position":[0,1,20],"rotation":{"axis_angle":{"axis":[0.1,0,1],"angle_deg":60}}}]})";

int main(int argc, char** argv) {
  const std::filesystem::path out = argc > 1 ? argv[1] : ".";
  try {
    std::filesystem::create_directories(out);
    const qm::io::PoseSet poses = qm::io::parse_poses_json(kPoses, "the consumer's poses");
    const qm::InterpolatedMotion made = qm::interpolate(poses, {});
    // The motion value survives its file: save, load, and the same curve comes back.
    made.save((out / "motion.json").string());
    const qm::Motion motion = qm::io::load_motion((out / "motion.json").string());
    const auto &saved = made.motion.rational().curve.curve.ctrl(),
               &loaded = motion.rational().curve.curve.ctrl();
    bool ok = motion.rational().factors && motion.provenance() &&
              motion.provenance()->poses.size() == 3 && loaded.size() == saved.size();
    for (std::size_t i = 0; ok && i < saved.size(); ++i)
      for (int c = 0; c < 8; ++c) ok = ok && loaded[i][c] == saved[i][c];
    std::cout << "motion.json: " << (ok ? "read back as saved" : "DIFFERS after reading back")
              << "\n";
    const qm::sweep::Profile<double> circle = qm::io::read_profile("circle:3");
    for (const bool solid : {false, true}) {
      qm::ExportOptions opt;
      opt.output = (out / (solid ? "tube_solid.step" : "tube.step")).string();
      opt.solid = solid;
      const qm::ExportResult r = qm::export_surface(motion, circle, "circle:3", opt);
      const nlohmann::json c = qm::check_geometry(opt.output, motion, circle, std::nullopt);
      std::cout << opt.output << ": " << r.faces << " faces, relative deviation "
                << c["relative_deviation"] << ", valid " << c["valid"] << ", closed " << c["closed"]
                << (solid ? ", volume " + c["volume"].dump() : "") << "\n";
      ok = ok && c["relative_deviation"].get<double>() <= 1e-11 && c["valid"].get<bool>() &&
           c["closed"].get<bool>() == solid;
      if (solid) ok = ok && std::abs(c["volume"].get<double>() - *r.volume) <= 1e-6 * *r.volume;
    }
    // The non-rational mode: a KKS quaternion spline through the same poses, its sweep
    // fitted within 1e-5 mm and checked against the spline itself.
    qm::QSplineOptions qo;
    qo.scheme = "kks";
    const qm::Motion q = qm::qspline(poses, qo).motion;
    qm::ExportOptions qopt;
    qopt.output = (out / "tube_kks.step").string();
    qopt.tol = 1e-5;
    const auto qr = qm::export_geometry(q, qm::Geometry::sweep(circle, "circle:3"), qopt);
    const nlohmann::json qc = qm::check(qopt.output, q, qm::Geometry::sweep(circle));
    std::cout << qopt.output << ": " << qr.poles << " poles, fitted within " << *qr.approx_tolerance
              << ", deviation from the spline " << qc["max_deviation"] << "\n";
    ok = ok && qc["max_deviation"].get<double>() <= 1e-5 && qc["valid"].get<bool>();
    std::cout << "OpenCASCADE " << qm::io::occt_version() << (ok ? ": exact\n" : ": FAILED\n");
    return ok ? 0 : 1;
  } catch (const qm::Error& e) {
    std::cerr << "consumer: " << e.what() << "\n";
    return e.exit_code();
  }
}
