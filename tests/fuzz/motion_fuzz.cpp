// tests/fuzz/motion_fuzz.cpp: the motion reader, the motion value it becomes, `info` and
// `eval` at both ends of the interval.
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_info.hpp>
#include <qmotion/io/motion_json.hpp>

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  fuzz::accept_refusals([&] {
    const io::MotionFile f =
        io::parse_motion(io::parse_json(fuzz::text(data, size), "fuzz.json"), "fuzz.json");
    const kernel::Motion<double> m = io::to_motion(f);
    (void)io::motion_document(m).dump();
    (void)io::motion_info(f).dump();
    fuzz::accept_refusals([&] { (void)io::motion_eval(f, f.range[0].value); });
    fuzz::accept_refusals([&] { (void)io::motion_eval(f, f.range[1].value); });
  });
  return 0;
}
