// cli/check.cpp: `qmotion check`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/exact_check.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/api/volume.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/kernel/error.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_check(CLI::App& app) {
  auto* sub = app.add_subcommand("check",
                                 "Measure the deviation of a written NURBS (JSON, or STEP/IGES "
                                 "read through OpenCASCADE) from the motion; with --body, check "
                                 "a swept-volume mesh; with --exact, verify the motion file "
                                 "itself in exact arithmetic");
  struct Options {
    std::string file, motion, profile, point, body;
    int grid = 41;
    bool exact = false;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("GEOMETRY", o->file,
                  "The .json, .step/.stp or .igs/.iges file to check, or with --body a volume "
                  "mesh (.stl, .obj, .ply, or volume's .json) (not with --exact)");
  sub->add_option("--motion", o->motion, "Motion JSON file")->required();
  sub->add_option("--profile", o->profile, "The profile the surface was swept from");
  sub->add_option("--point", o->point, "The point whose trajectory the curve is");
  sub->add_option("--body", o->body,
                  "The body whose swept volume GEOMETRY encloses: samples of the volume must "
                  "lie inside it (exit 3 otherwise), its vertices' distance is measured");
  sub->add_option("--grid", o->grid, "Lattice size per direction (plus 400 random samples)");
  sub->add_flag("--exact", o->exact,
                "Recompute the motion in exact rationals from the poses its file records: exact "
                "Plucker and interpolation residuals, agreement with the file, and the trajectory "
                "order of --point (default: a general point) by an exact polynomial gcd against "
                "the degree `trajectory` writes. Exit 3 when any of them fails");
  return {sub, [o] {
            if (o->exact) {
              if (!o->file.empty() || !o->profile.empty())
                throw Error(Errc::invalid_input,
                            "check --exact verifies the motion file itself: give --motion (and "
                            "optionally --point), no GEOMETRY or --profile");
#ifdef QMOTION_WITH_CGAL
              std::optional<Eigen::Vector3d> point;
              if (!o->point.empty()) point = io::parse_point(o->point, "--point");
              const auto report = qmotion::check_exact(o->motion, point);
              std::cout << report.dump(2) << "\n";
              if (!report["verified"].get<bool>())
                throw Error(Errc::numerical_failure,
                            o->motion +
                                ": the exact recomputation does not verify the motion "
                                "(see the report above)");
              return 0;
#else
              throw Error(Errc::invalid_input,
                          "--exact: this build has no exact arithmetic (QMOTION_WITH_CGAL=OFF)");
#endif
            }
            if (o->file.empty())
              throw Error(Errc::invalid_input, "check: GEOMETRY is required (or use --exact)");
            if (!o->body.empty()) {
              if (!o->profile.empty() || !o->point.empty())
                throw Error(Errc::invalid_input,
                            "check --body checks a swept volume: no --profile or --point");
#ifdef QMOTION_WITH_CGAL
              const auto report =
                  qmotion::check_volume(o->file, io::load_motion(o->motion), o->body);
              std::cout << report.dump(2) << "\n";
              if (!report["encloses"].get<bool>())
                throw Error(Errc::numerical_failure,
                            o->file + ": " + std::to_string(report["outside"].get<std::size_t>()) +
                                " sampled points of the swept volume lie outside the mesh");
              return 0;
#else
              throw Error(Errc::invalid_input,
                          "--body: this build has no CGAL mesh checks (QMOTION_WITH_CGAL=OFF)");
#endif
            }
            if (o->profile.empty() == o->point.empty())
              throw Error(Errc::invalid_input, "check: give exactly one of --profile and --point");
            const Motion m = io::load_motion(o->motion);
            if (o->grid < 1 || o->grid > 1000)
              throw Error(Errc::invalid_input, "--grid: expected 1 to 1000");
            const qmotion::Geometry g =
                o->profile.empty()
                    ? qmotion::Geometry::trajectory(io::parse_point(o->point, "--point"))
                    : qmotion::Geometry::sweep(io::read_profile(o->profile, m.units()), o->profile);
            std::cout << qmotion::check(o->file, m, g, o->grid).dump(2) << "\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
