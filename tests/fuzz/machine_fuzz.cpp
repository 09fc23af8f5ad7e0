// tests/fuzz/machine_fuzz.cpp: machine files (`toolpath --machine`) and `--axis-limits`. A
// machine that reads is driven through its inverse and forward kinematics and the bound on
// its interpolation at a few fixed tool axes, so that no accepted machine makes them fail.
#include <qmotion/cam/machine.hpp>
#include <qmotion/io/machine_file.hpp>

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  const std::string text = fuzz::text(data, size);
  fuzz::accept_refusals([&] { (void)io::parse_axis_limits(text, "--axis-limits"); });
  fuzz::accept_refusals([&] {
    const io::MachineFile f = io::parse_machine_file(text, "fuzz.json");
    cam::MachineAxes prev{};
    for (const Eigen::Vector3d& k :
         {Eigen::Vector3d(0.3, 0.2, 0.9), Eigen::Vector3d(-0.5, 0.1, 0.7), Eigen::Vector3d(0, 0, 1),
          Eigen::Vector3d(1, 0, 0)}) {
      const cam::MachineAxes q =
          cam::inverse_kinematics(f.machine, Eigen::Vector3d(10, -20, 5), k, prev, true, "fuzz");
      (void)cam::forward_kinematics(f.machine, q);
      (void)cam::interpolation_bound(f.machine, prev, q);
      prev = q;
    }
  });
  return 0;
}
