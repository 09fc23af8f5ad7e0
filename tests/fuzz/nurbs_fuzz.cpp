// tests/fuzz/nurbs_fuzz.cpp: the NURBS JSON reader (curves and surfaces), with an
// evaluation of what it accepted. The first byte chooses curve (even) or surface (odd).
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/nurbs_json.hpp>

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  if (size == 0) return 0;
  const bool surface = (data[0] & 1) != 0;
  fuzz::accept_refusals([&] {
    const auto doc = io::parse_json(fuzz::text(data + 1, size - 1), "fuzz.json");
    if (surface) {
      const auto s = io::surface_from_json(doc, "fuzz.json");
      (void)io::surface_to_json(s).dump();
    } else {
      const auto c = io::curve_from_json(doc, "fuzz.json");
      (void)io::curve_to_json(c).dump();
      const double mid = 0.5 * (c.knots.front() + c.knots.back());
      fuzz::accept_refusals([&] { (void)sweep::evaluate(c, mid); });
    }
  });
  return 0;
}
