// cli/info.cpp: `qmotion info`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/motion_info.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/kernel/error.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_info(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "info", "Describe a motion file as JSON (degree, order, Plucker residual, poles, ...)");
  auto o = std::make_shared<std::pair<std::string, bool>>("", false);
  sub->add_option("MOTION", o->first, "Motion JSON file")->required();
  sub->add_flag("--exact", o->second,
                "Compute the Plucker residual in exact rational arithmetic from the file's digits");
  return {
      sub, [o] {
        std::string text = io::read_text_file(o->first);
        if (auto f = io::parse_motion_fast(text, o->first)) {
          std::string().swap(text);  // read: its megabytes go before the work
          std::cout << qmotion::motion_info(*f, o->second).dump(2) << '\n';
          return 0;
        }
        nlohmann::json doc = io::parse_json(text, o->first, "method");
        if (io::is_qspline_document(doc)) {
          if (o->second)
            throw Error(Errc::invalid_input,
                        o->first +
                            ": --exact is for rational motions (q-motion files); a "
                            "quaternion spline is not rational");
          std::cout << qmotion::qspline_info(doc, io::qspline_from_document(doc, o->first)).dump(2)
                    << '\n';
          return 0;
        }
        std::cout
            << qmotion::motion_info(io::parse_motion(std::move(doc), o->first), o->second).dump(2)
            << '\n';
        return 0;
      }};
}

}  // namespace qmotion::cli
