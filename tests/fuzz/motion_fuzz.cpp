// tests/fuzz/motion_fuzz.cpp: the motion reader, the motion value it becomes, `info` and
// `eval` at both ends of the interval; quaternion-spline files likewise.
#include <qmotion/api/motion_info.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  fuzz::accept_refusals([&] {
    const auto doc = io::parse_json(fuzz::text(data, size), "fuzz.json");
    if (io::is_qspline_document(doc)) {  // a non-rational motion: info and eval read it
      const auto s = io::qspline_from_document(doc, "fuzz.json");
      (void)qmotion::qspline_info(doc, s).dump();
      fuzz::accept_refusals([&] { (void)qmotion::qspline_eval(s, s.a(), {0, 0, 0}, ""); });
      fuzz::accept_refusals([&] { (void)qmotion::qspline_eval(s, s.b(), {1, 2, 3}, ""); });
      return;
    }
    const io::MotionFile f = io::parse_motion(doc, "fuzz.json");
    const kernel::Motion<double> m = io::to_motion(f);
    (void)io::motion_document(m).dump();
    (void)qmotion::motion_info(f).dump();
    fuzz::accept_refusals([&] { (void)qmotion::motion_eval(f, f.range[0].value); });
    fuzz::accept_refusals([&] { (void)qmotion::motion_eval(f, f.range[1].value); });
  });
  return 0;
}
