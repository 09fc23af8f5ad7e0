// A user's program against the installed qmotion: a pose product satisfies Plucker.
#include <iostream>

#include "io/occt_info.hpp"
#include "kernel/dual_quaternion.hpp"

int main() {
  using DQ = qmotion::kernel::DualQuaternion<double>;
  const DQ a = DQ::pose({1, 2, 3}, {1, 0, 0, 1});
  const DQ b = DQ::pose({-4, 0, 1}, {2, 1, 0, 0});
  const double r = qmotion::kernel::plucker(a * b);
  std::cout << "plucker residual " << r << ", OpenCASCADE " << qmotion::io::occt_version() << "\n";
  return r == 0.0 ? 0 : 1;
}
