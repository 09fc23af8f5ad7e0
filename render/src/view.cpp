// render/src/view.cpp: fills the viewer page's per-file marks (render/viewer/embed.py made
// the rest of the page at build time).
#include <qmotion/kernel/error.hpp>
#include <qmotion/render/view.hpp>

#include "drawing.hpp"

#ifdef QMOTION_WITH_VIEWER
namespace qmotion::render::detail {
extern const std::size_t viewer_wasm_bytes;
extern const char* const viewer_page_pieces[];
}  // namespace qmotion::render::detail
#endif

namespace qmotion::render {
namespace {

/// JSON text safe inside a <script> element: every '<' (only ever inside strings) escaped.
std::string script_json(const nlohmann::json& data) {
  std::string out;
  for (const char c : data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace))
    out += c == '<' ? std::string("\\u003c") : std::string(1, c);
  return out;
}

void replace_once(std::string& page, const std::string& mark, const std::string& value) {
  const auto at = page.find(mark);
  if (at == std::string::npos) throw Error(Errc::internal, "viewer page: no " + mark);
  page.replace(at, mark.size(), value);
}

}  // namespace

#ifdef QMOTION_WITH_VIEWER
bool viewer_available() { return true; }
std::size_t viewer_wasm_bytes() { return detail::viewer_wasm_bytes; }
#else
bool viewer_available() { return false; }
std::size_t viewer_wasm_bytes() { return 0; }
#endif

std::string viewer_page(const std::string& title, const std::string& summary,
                        const nlohmann::json& data) {
  std::string page;
#ifdef QMOTION_WITH_VIEWER
  for (const char* const* p = detail::viewer_page_pieces; *p; ++p) page += *p;
#endif
  if (page.empty())
    throw Error(Errc::invalid_input,
                "view: this build has no viewer page: building it needs Debian's emscripten and "
                "npm's three.js (scripts/install-deps.sh installs both), then configure again "
                "(QMOTION_VIEWER=AUTO or ON)");
  // The data first: the title and summary could contain a mark's text.
  replace_once(page, "@QMOTION_DATA@", script_json(data));
  replace_once(page, "@QMOTION_SUMMARY@", detail::escape_xml(summary));
  for (int i = 0; i < 2; ++i) replace_once(page, "@QMOTION_TITLE@", detail::escape_xml(title));
  return page;
}

}  // namespace qmotion::render
