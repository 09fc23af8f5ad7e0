// tests/fuzz/gcode_fuzz.cpp: G-code read by `verify` (io::read_gcode). A program that reads
// has moves whose positions and speed bounds are finite, whose ends are where they say,
// and whose arcs turn at most the turns their P allows.
#include <cmath>
#include <qmotion/io/gcode.hpp>

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  const std::string text = fuzz::text(data, size);
  fuzz::accept_refusals([&] {
    const cam::Program p = io::parse_gcode(text, "fuzz.ngc");
    for (const cam::Move& m : p.moves) {
      const double v = cam::speed_bound(m);
      if (!std::isfinite(v) || v < 0) std::abort();
      for (double t : {0.0, 0.5, 1.0})
        if (!cam::position(m, t).allFinite()) std::abort();
      const double scale = 1 + m.from.cwiseAbs().maxCoeff() + m.to.cwiseAbs().maxCoeff();
      if ((cam::position(m, 1) - m.to).norm() > 1e-9 * scale + 1e-6 * v) std::abort();
      if (std::abs(m.turns) > 1000) std::abort();
    }
  });
  return 0;
}
