// <qmotion/render/view.hpp>: the viewer page `qmotion view` writes (docs/guide/view.md): one
// self-contained HTML file with three.js, the kernel in WebAssembly and the motion's data.
#pragma once
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace qmotion::render {

/// Whether this build carries the page (CMake option QMOTION_VIEWER).
bool viewer_available();

/// Bytes of the kernel's WebAssembly module the page carries (0 without the page).
std::size_t viewer_wasm_bytes();

/// The page for `data` (the object the page reads: docs/guide/view.md lists its members),
/// titled `title`, with `summary` under the title. Errc::invalid_input when the build has no
/// page.
std::string viewer_page(const std::string& title, const std::string& summary,
                        const nlohmann::json& data);

}  // namespace qmotion::render
