// cli/info.cpp: `qmotion info`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/motion_info.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_info(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "info", "Describe a motion file as JSON (degree, order, Plucker residual, poles, ...)");
  auto o = std::make_shared<std::pair<std::string, bool>>("", false);
  sub->add_option("MOTION", o->first, "Motion JSON file")->required();
  sub->add_flag("--exact", o->second,
                "Compute the Plucker residual in exact rational arithmetic from the file's digits");
  return {sub, [o] {
            std::cout << qmotion::info_file(o->first, o->second).dump(2) << '\n';
            return 0;
          }};
}

}  // namespace qmotion::cli
