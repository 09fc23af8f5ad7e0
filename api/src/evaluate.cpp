// api/src/evaluate.cpp
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <qmotion/api/evaluate.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/surface_eval.hpp>
#include <string>

namespace qmotion {

std::vector<Eigen::Vector3d> evaluate_grid(const sweep::NurbsSurface<double>& s,
                                           const std::vector<double>& us,
                                           const std::vector<double>& vs, bool parallel) {
  const auto check = [](const std::vector<double>& x, double lo, double hi, const char* name) {
    for (std::size_t i = 0; i < x.size(); ++i)
      if (!(x[i] >= lo && x[i] <= hi))
        throw Error(Errc::invalid_input, std::string(name) + "[" + std::to_string(i) +
                                             "] = " + std::to_string(x[i]) +
                                             " is outside the surface's parameter interval [" +
                                             std::to_string(lo) + ", " + std::to_string(hi) + "]");
  };
  check(us, s.knots_u.front(), s.knots_u.back(), "u");
  check(vs, s.knots_v.front(), s.knots_v.back(), "v");
  const sweep::SurfaceEvaluator e(s);
  std::vector<Eigen::Vector3d> out(us.size() * vs.size());
  // About 2^14 points per task: below that the threads cost more than they save.
  const std::size_t grain =
      std::max<std::size_t>(1, (std::size_t(1) << 14) / std::max<std::size_t>(1, vs.size()));
  if (parallel && us.size() > grain) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, us.size(), grain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        e.grid(us, vs, out.data(), r.begin(), r.end());
                      });
  } else {
    e.grid(us, vs, out.data(), 0, us.size());
  }
  return out;
}

}  // namespace qmotion
