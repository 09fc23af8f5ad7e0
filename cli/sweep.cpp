// cli/sweep.cpp: `qmotion sweep`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/export.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/kernel/error.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_sweep(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "sweep",
      "Write the kinematic surface M(t) x(v) of a profile as NURBS (JSON, STEP, IGES) or a mesh "
      "(STL, OBJ, PLY) within --deflection: "
      "exact for a q-motion, fitted within --tol for a quaternion spline");
  struct Options {
    std::string motion, profile, deflection;
    qmotion::ExportOptions options;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->motion, "Motion JSON file")->required();
  sub->add_option("--profile", o->profile,
                  "Profile: nurbs_curve .json (or an array of them), .step/.igs (the first "
                  "wire's edges), segment:x0,y0,z0:x1,y1,z1, polyline:x,y,z:x,y,z:..., rect:w,h, "
                  "circle:r, arc:r,a0,a1")
      ->required();
  sub->add_option("-o,--output", o->options.output,
                  "Output .json, .step/.stp, .igs/.iges, or a mesh .stl, .obj, .ply")
      ->required();
  sub->add_option("--deflection", o->deflection,
                  "Mesh: the largest distance of the triangles from the exact surfaces (absolute, "
                  "in the output unit; default 1e-3 of the size), measured and held");
  sub->add_option("--angle", o->options.angle_deg,
                  "Mesh: the mesher's angular deflection in degrees (default 20)");
  sub->add_flag("--ascii", o->options.ascii, "Mesh: ASCII STL or PLY instead of binary");
  add_geometry_options(sub, o->options);
  sub->add_flag("--single-face", o->options.single_face,
                "STEP/IGES: one face per profile edge instead of a shell of C1 faces split at the "
                "C0 knots");
  sub->add_flag("--fail-on-self-intersection", o->options.fail_on_self_intersection,
                "Exit 3 (and write nothing) when the sweep intersects itself; without it a "
                "warning names where");
  sub->add_flag("--solid", o->options.solid,
                "Closed planar profile: add planar caps at both ends and write one closed solid");
  return {
      sub, [o] {
        if (!o->deflection.empty()) {  // given: positive (0 is the library's default)
          o->options.deflection = io::parse_number_text(o->deflection, "--deflection").value;
          if (!(o->options.deflection > 0))
            throw Error(Errc::invalid_input, "--deflection: expected a positive length");
        }
        const Motion m = io::load_motion(o->motion);
        const auto r = qmotion::export_geometry(
            m, qmotion::Geometry::sweep(io::read_profile(o->profile, m.units()), o->profile),
            o->options);
        if (r.self_intersection && r.self_intersection->found())
          std::cerr << "qmotion: warning: the sweep intersects itself ("
                    << r.self_intersection->pairs << " crossing triangle pairs; "
                    << r.self_intersection->ranges() << ")\n";
        if (r.self_intersection_proof)
          std::cerr << (r.self_intersection_proof->proven() ? "qmotion: " : "qmotion: warning: ")
                    << "the sweep " << r.self_intersection_proof->describe() << "\n";
        std::cerr << "qmotion: wrote " << r.path << " (degrees " << r.degree_u << " x "
                  << r.degree_v << ", C" << r.continuity_u << " x C" << r.continuity_v << ", "
                  << r.faces << (r.faces == 1 ? " face, " : " faces, ") << r.poles << " poles, "
                  << r.units
                  << (r.volume ? ", solid of volume " + std::to_string(*r.volume) : std::string(""))
                  << approximation_note(r) << ")\n";
        if (r.mesh)
          std::cerr << "qmotion: mesh of " << r.mesh->triangles.size() << " triangles, "
                    << r.mesh->vertices.size() << " vertices" << (r.mesh->closed ? ", closed" : "")
                    << ", deviation " << r.mesh->max_deviation << " measured at "
                    << r.mesh->deviation_samples
                    << " points against the exact surfaces (mesher deflection "
                    << r.mesh->deflection << ")\n";
        return 0;
      }};
}

}  // namespace qmotion::cli
