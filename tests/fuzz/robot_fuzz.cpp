// tests/fuzz/robot_fuzz.cpp: the robot-program readers (KUKA KRL with and without its .dat,
// ABB RAPID, URScript) and `fit` on the poses they give. The first byte chooses: 0 KRL alone,
// 1 KRL whose .dat follows the first NUL byte, 2 RAPID, 3 URScript.
#include <qmotion/api/fit.hpp>
#include <qmotion/io/robot_programs.hpp>

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  if (size == 0) return 0;
  const int kind = data[0] & 3;
  std::string body = fuzz::text(data + 1, size - 1);
  std::optional<std::string> dat;
  if (kind == 1) {
    const auto nul = body.find('\0');
    dat = nul == std::string::npos ? std::string() : body.substr(nul + 1);
    body = body.substr(0, std::min(nul, body.size()));
  }
  fuzz::accept_refusals([&] {
    const io::PoseSet set = kind == 3   ? io::parse_urscript(body, "fuzz.script")
                            : kind == 2 ? io::parse_rapid(body, "fuzz.mod")
                                        : io::parse_krl(body, "fuzz.src", dat, "fuzz.dat");
    (void)io::poses_to_json(set).dump();
    FitOptions o;
    o.tol = 0.01;
    (void)fit(set, o).report_text();
  });
  return 0;
}
