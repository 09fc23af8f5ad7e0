// tests/fuzz/poses_fuzz.cpp: the pose readers (JSON and CSV) and both conversions.
// The first byte chooses the format (odd: CSV), the rest is the file.
#include <qmotion/io/poses.hpp>

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  if (size == 0) return 0;
  const bool csv = (data[0] & 1) != 0;
  const std::string body = fuzz::text(data + 1, size - 1);
  fuzz::accept_refusals([&] {
    const io::PoseSet set =
        csv ? io::parse_poses_csv(body, "fuzz.csv") : io::parse_poses_json(body, "fuzz.json");
    const auto poses = io::to_poses_double(set);
    (void)io::poses_to_json(set).dump();
    (void)io::poses_to_json(poses, set.units).dump();
#ifdef QMOTION_WITH_CGAL
    fuzz::accept_refusals([&] { (void)io::to_poses_exact(set); });
#endif
  });
  return 0;
}
