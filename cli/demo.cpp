// cli/demo.cpp: `qmotion demo`: the main job on embedded poses.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/demo.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_demo(CLI::App& app) {
  auto* sub = app.add_subcommand("demo", "Run the main job on the embedded five sample poses");
  auto dir = std::make_shared<std::string>("demo-out");
  sub->add_option("-o,--output", *dir, "Output folder");
  return {sub, [dir] {
            const nlohmann::json doc = qmotion::write_demo(*dir);
            std::cout << doc.dump(2) << "\n";
            std::cerr << "qmotion: demo written to " << *dir
                      << " (motion.json, trajectories and surface as JSON/STEP/IGES, demo.svg, "
                         "report.json)\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
