// cli/poses.cpp: `qmotion poses`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/error.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_poses(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "poses",
      "Validate a pose file (JSON, CSV or a KRL, RAPID or URScript robot program); "
      "with -o, write it as canonical pose JSON");
  struct Options {
    std::string poses, output;
    io::RobotOptions robot;
  };
  auto o = std::make_shared<Options>();
  add_poses_argument(sub, o->poses, o->robot);
  sub->add_option("-o,--output", o->output,
                  "Write the poses as JSON (docs/formats.md) to this file");
  return {sub, [o] {
            const io::PoseSet set = read_poses_argument(o->poses, o->robot);
            if (!o->output.empty()) {
              io::write_file_atomic(o->output, io::poses_to_json(set).dump(1) + "\n");
              std::cerr << "qmotion: wrote " << set.poses.size() << " poses to " << o->output
                        << "\n";
            } else {
              const nlohmann::json summary{{"source", o->poses},
                                           {"poses", set.poses.size()},
                                           {"units", set.units},
                                           {"has_t", set.has_t()}};
              std::cout << summary.dump(2) << '\n';
            }
            return 0;
          }};
}

}  // namespace qmotion::cli
