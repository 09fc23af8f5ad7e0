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
  auto* sub = app.add_subcommand("poses",
                                 "Validate a pose file (JSON, CSV or a KRL/RAPID robot program); "
                                 "with -o, write it as canonical pose JSON");
  auto o = std::make_shared<std::pair<std::string, std::string>>();
  sub->add_option("POSES", o->first, "Pose file (.json, .csv, KUKA KRL .src, ABB RAPID .mod/.prg)")
      ->required();
  sub->add_option("-o,--output", o->second,
                  "Write the poses as JSON (docs/formats.md) to this file");
  return {sub, [o] {
            const io::PoseSet set = io::read_poses(o->first);
            if (!o->second.empty()) {
              io::write_file_atomic(o->second, io::poses_to_json(set).dump(1) + "\n");
              std::cerr << "qmotion: wrote " << set.poses.size() << " poses to " << o->second
                        << "\n";
            } else {
              const nlohmann::json summary{{"source", o->first},
                                           {"poses", set.poses.size()},
                                           {"units", set.units},
                                           {"has_t", set.has_t()}};
              std::cout << summary.dump(2) << '\n';
            }
            return 0;
          }};
}

}  // namespace qmotion::cli
