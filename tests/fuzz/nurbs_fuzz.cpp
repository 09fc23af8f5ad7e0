// tests/fuzz/nurbs_fuzz.cpp: the NURBS JSON readers (curves and surfaces), with an
// evaluation of what they accepted. The first byte chooses curve (even) or surface (odd).
// The tree reader (parse_json, curve_from_json, surface_from_json) and the file reader that
// `check` uses (read_nurbs_file: the scanner, the tree behind it) must agree: what the tree
// accepts, the file reader gives back bit for bit, and what the tree refuses as a curve, the
// file reader refuses too.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/nurbs_json.hpp>

#include "fuzz_util.hpp"

namespace {
using namespace qmotion;

/// The input's text in a file of this process's own.
std::string as_file(const std::string& text) {
  static const std::string path = (std::filesystem::temp_directory_path() /
                                   ("qmotion_fuzz_nurbs_" + std::to_string(::getpid()) + ".json"))
                                      .string();
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  return path;
}

/// Both readers of the same file; aborts when they disagree.
void compare(const std::string& text, bool surface) {
  const std::string path = as_file(text);
  std::optional<io::NurbsFile> file;
  fuzz::accept_refusals([&] { file = io::read_nurbs_file(path, surface); });
  fuzz::accept_refusals([&] {
    const auto doc = io::parse_json(text, "fuzz.json");
    if (surface) {
      const auto s = io::surface_from_json(doc, "fuzz.json");
      (void)io::surface_to_json(s).dump();
      const bool same = file && file->faces.size() == 1 && file->faces[0].points == s.points &&
                        file->faces[0].weights == s.weights &&
                        file->faces[0].knots_u == s.knots_u && file->faces[0].knots_v == s.knots_v;
      if (!same) {
        std::fprintf(stderr, "fuzz: the file reader differs from the tree on a surface\n");
        std::abort();
      }
    } else {
      const auto c = io::curve_from_json(doc, "fuzz.json");
      (void)io::curve_to_json(c).dump();
      if (!file || file->curve.points != c.points || file->curve.weights != c.weights ||
          file->curve.knots != c.knots) {
        std::fprintf(stderr, "fuzz: the file reader differs from the tree on a curve\n");
        std::abort();
      }
      const double mid = 0.5 * (c.knots.front() + c.knots.back());
      fuzz::accept_refusals([&] { (void)sweep::evaluate(c, mid); });
    }
  });
  if (!surface && file) {  // accepted as a curve: the tree must accept it too
    bool tree = false;
    fuzz::accept_refusals([&] {
      (void)io::curve_from_json(io::parse_json(text, "fuzz.json"), "fuzz.json");
      tree = true;
    });
    if (!tree) {
      std::fprintf(stderr, "fuzz: the file reader accepts a curve the tree refuses\n");
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  compare(fuzz::text(data + 1, size - 1), (data[0] & 1) != 0);
  return 0;
}
