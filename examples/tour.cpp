// The README's C++ tour: poses -> exact motion -> a swept tube as STEP, checked by reading
// the file back. Usage: tour POSES.json OUT_DIR
#include <iostream>
#include <qmotion/qmotion.hpp>
#include <string>

int main(int argc, char** argv) {
  namespace qm = qmotion;
  if (argc != 3) return 2;
  const std::string out = std::string(argv[2]) + "/tour_tube.step";
  try {
    const auto made = qm::interpolate(qm::io::read_poses(argv[1]), {});  // elliptic + TR
    const qm::Motion& motion = made.motion;  // rational here; a qspline is one too
    const auto tube = qm::Geometry::sweep(qm::io::read_profile("circle:3"), "circle:3");
    qm::ExportOptions opt;
    opt.output = out;
    const qm::ExportResult written = qm::export_geometry(motion, tube, opt);
    const auto report = qm::check(out, motion, tube);  // reads the STEP back, evaluates it
    std::cout << "degrees " << written.degree_u << " x " << written.degree_v
              << ", relative deviation " << report["relative_deviation"] << "\n";
    return report["relative_deviation"].get<double>() < 1e-12 ? 0 : 1;
  } catch (const qm::Error& e) {  // bad input (2) or a numerical failure (3)
    std::cerr << e.what() << "\n";
    return e.exit_code();
  }
}
