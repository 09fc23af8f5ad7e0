// <qmotion/sweep/pipe_poly.hpp>: the polynomial arithmetic of the exact pipe and of its
// proofs: Bernstein coefficients on [0, 1] (real or complex) multiplied, added, raised in
// degree, differentiated and evaluated, and the factorisation |h|^2 = V of a polynomial that
// is positive on the real line (Fejer-Riesz; docs/geometry.md, "Exact pipe surfaces").
#pragma once
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <qmotion/kernel/bernstein.hpp>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <type_traits>
#include <vector>

namespace qmotion::sweep::pipe_detail {

using Poly = std::vector<double>;  // Bernstein coefficients on [0, 1]
using Cx = std::complex<double>;
using CPoly = std::vector<Cx>;

template <typename T>
std::vector<T> elevate_to(std::vector<T> c, std::size_t n) {
  while (c.size() - 1 < n) {
    const std::size_t m = c.size();  // new degree m
    std::vector<T> e(m + 1);
    e[0] = c[0];
    e[m] = c[m - 1];
    for (std::size_t i = 1; i < m; ++i) {
      const double a = static_cast<double>(i) / static_cast<double>(m);
      e[i] = a * c[i - 1] + (1 - a) * c[i];
    }
    c = std::move(e);
  }
  return c;
}

template <typename T>
std::vector<T> mul(const std::vector<T>& a, const std::vector<T>& b) {
  const int k = static_cast<int>(a.size()) - 1, l = static_cast<int>(b.size()) - 1;
  std::vector<T> c(static_cast<std::size_t>(k + l + 1), T(0));
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= l; ++j)
      c[static_cast<std::size_t>(i + j)] +=
          a[static_cast<std::size_t>(i)] * b[static_cast<std::size_t>(j)] *
          (kernel::binomial<double>(k, i) * kernel::binomial<double>(l, j) /
           kernel::binomial<double>(k + l, i + j));
  return c;
}

template <typename T>
std::vector<T> add(std::vector<T> a, std::vector<T> b, double fb = 1) {
  const std::size_t n = std::max(a.size(), b.size()) - 1;
  a = elevate_to(std::move(a), n);
  b = elevate_to(std::move(b), n);
  for (std::size_t i = 0; i <= n; ++i) a[i] += fb * b[i];
  return a;
}

template <typename T>
std::vector<T> derivative(const std::vector<T>& a) {
  const std::size_t n = a.size() - 1;
  if (n == 0) return {T(0)};
  std::vector<T> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = static_cast<double>(n) * (a[i + 1] - a[i]);
  return d;
}

/// de Casteljau at u (real or complex: the recursion is a polynomial identity).
template <typename T, typename U>
auto evaluate(const std::vector<T>& a, const U& u) {
  using R = std::conditional_t<std::is_arithmetic_v<T>, decltype(T() * U()), T>;
  std::vector<R> c(a.begin(), a.end());
  for (std::size_t r = 1; r < c.size(); ++r)
    for (std::size_t i = 0; i + r < c.size(); ++i) c[i] = (U(1) - u) * c[i] + u * c[i + 1];
  return c[0];
}

inline CPoly to_complex(const Poly& a) { return CPoly(a.begin(), a.end()); }
inline Poly real(const CPoly& a) {
  Poly r;
  for (const auto& x : a) r.push_back(x.real());
  return r;
}
inline Poly imag(const CPoly& a) {
  Poly r;
  for (const auto& x : a) r.push_back(x.imag());
  return r;
}
inline CPoly conj(const CPoly& a) {
  CPoly r;
  for (const auto& x : a) r.push_back(std::conj(x));
  return r;
}

/// Strips the degree elevation a polynomial carries (its power-basis top coefficients
/// negligible against its size): the true degree of a derivative's numerator.
inline Poly true_degree(const Poly& a) {
  if (a.size() <= 1) return a;
  const auto r = kernel::reduce_degree(kernel::Bernstein<double>(a), 1e-11);
  return r.coeffs();
}

inline std::string short_number(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", x);
  return b;
}

/// h with |h|^2 = V on the real line, for V > 0 there (Fejer-Riesz): the roots of V come in
/// conjugate pairs and h takes the one of each pair above the axis. The roots come from the
/// colleague matrix of V's Chebyshev series, polished by Newton on its Bernstein form; then
/// Gauss-Newton on h's coefficients makes |h|^2 = V on [0, 1] to rounding (roots far from the
/// interval are poorly determined by it, and only |h|^2 on it matters).
inline CPoly sqrt_sum_of_squares(const Poly& V, const std::string& where) {
  const int n = static_cast<int>(V.size()) - 1;
  const double Vmid = evaluate(V, 0.5);
  if (n == 0) return {Cx(std::sqrt(V[0]))};
  if (n % 2 != 0) throw Error(Errc::internal, where + ": |c'|^2 of odd degree");
  const int N = n + 1;
  std::vector<double> c(static_cast<std::size_t>(N)), values;
  for (int k = 0; k < N; ++k)
    values.push_back(evaluate(V, 0.5 * (1 + std::cos(M_PI * (k + 0.5) / N))));
  for (int j = 0; j < N; ++j) {
    double sum = 0;
    for (int k = 0; k < N; ++k)
      sum += values[static_cast<std::size_t>(k)] * std::cos(j * M_PI * (k + 0.5) / N);
    c[static_cast<std::size_t>(j)] = (j == 0 ? 1.0 : 2.0) * sum / N;
  }
  const double cn = c[static_cast<std::size_t>(n)];
  if (!(std::abs(cn) > 0))
    throw Error(Errc::numerical_failure, where + ": the speed's square has a vanishing top term");
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  C(0, 1) = 1;
  for (int i = 1; i < n; ++i) {
    C(i, i - 1) = 0.5;
    if (i + 1 < n) C(i, i + 1) = 0.5;
  }
  for (int j = 0; j < n; ++j) C(n - 1, j) -= c[static_cast<std::size_t>(j)] / (2 * cn);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(C, false);
  std::vector<Cx> roots;
  for (int i = 0; i < n; ++i) roots.push_back(0.5 * (Cx(1) + Cx(es.eigenvalues()(i))));
  // Aberth-Ehrlich: all roots at once, each repelled by the others (Newton alone lets
  // several starts fall into one root).
  const Poly dV = derivative(V);
  for (int it = 0; it < 200; ++it) {
    double moved = 0;
    for (std::size_t k = 0; k < roots.size(); ++k) {
      const Cx z = roots[k], fz = evaluate(V, z), d = evaluate(dV, z);
      if (fz == Cx(0)) continue;
      const Cx ratio = fz / d;
      Cx rep(0);
      for (std::size_t j = 0; j < roots.size(); ++j)
        if (j != k) rep += Cx(1) / (z - roots[j]);
      const Cx step = ratio / (Cx(1) - ratio * rep);
      if (!std::isfinite(step.real()) || !std::isfinite(step.imag())) continue;
      roots[k] = z - step;
      moved = std::max(moved, std::abs(step) / (1 + std::abs(z)));
    }
    if (moved <= 1e-15) break;
  }
  // One root of each pair: the n/2 highest, reflected above the axis (a pair that rounding
  // put on the real line keeps its real part).
  std::sort(roots.begin(), roots.end(), [](Cx x, Cx y) { return x.imag() > y.imag(); });
  CPoly h{Cx(1)};
  for (int k = 0; k < n / 2; ++k) {
    const Cx z0 = roots[static_cast<std::size_t>(k)];
    const Cx z(z0.real(), std::abs(z0.imag()));
    h = mul(h, CPoly{-z, Cx(1) - z});
  }
  const double s = std::sqrt(Vmid) / std::abs(evaluate(h, 0.5));
  for (auto& x : h) x *= s;
  const int d = n / 2, M = 2 * n + 4;
  std::vector<double> us;
  for (int k = 0; k < M; ++k) us.push_back(0.5 * (1 + std::cos(M_PI * (k + 0.5) / M)));
  double Vmax = 0;
  for (double u : us) Vmax = std::max(Vmax, evaluate(V, u));
  // Residual at the points and its Jacobian in (Re, Im) of h's coefficients.
  auto residual = [&](const CPoly& hh, Eigen::MatrixXd* J) {
    Eigen::VectorXd res(M);
    for (int k = 0; k < M; ++k) {
      const double u = us[static_cast<std::size_t>(k)];
      const Cx hk = evaluate(hh, u);
      res(k) = (std::norm(hk) - evaluate(V, u)) / Vmax;
      if (J)
        for (int i = 0; i <= d; ++i) {
          const double b =
              kernel::binomial<double>(d, i) * std::pow(u, i) * std::pow(1 - u, d - i) / Vmax;
          (*J)(k, 2 * i) = 2 * hk.real() * b;
          (*J)(k, 2 * i + 1) = 2 * hk.imag() * b;
        }
    }
    return res;
  };
  Eigen::MatrixXd J(M, 2 * (d + 1));
  Eigen::VectorXd res = residual(h, &J);
  double err = res.cwiseAbs().maxCoeff();
  for (int it = 0; it < 40 && err > 1e-15; ++it) {
    const Eigen::VectorXd step = J.completeOrthogonalDecomposition().solve(-res);
    // Backtracking: the step is taken, halved until the residual falls.
    bool better = false;
    for (double f = 1; f > 1e-4 && !better; f *= 0.5) {
      CPoly trial = h;
      for (int i = 0; i <= d; ++i)
        trial[static_cast<std::size_t>(i)] += f * Cx(step(2 * i), step(2 * i + 1));
      const Eigen::VectorXd r2 = residual(trial, nullptr);
      if (r2.cwiseAbs().maxCoeff() < err) {
        h = std::move(trial);
        better = true;
      }
    }
    if (!better) break;
    res = residual(h, &J);
    err = res.cwiseAbs().maxCoeff();
  }
  // |h|^2 must be V: a wrong pairing or lost roots show here.
  double worst = 0;
  for (int k = 0; k <= 64; ++k) {
    const double u = k / 64.0;
    worst = std::max(worst, std::abs(std::norm(evaluate(h, u)) - evaluate(V, u)) / Vmax);
  }
  if (!(worst <= 1e-6))
    throw Error(Errc::numerical_failure,
                where + ": the path's squared speed could not be written as |h|^2 (off by " +
                    short_number(worst) + " relative)");
  return h;
}

}  // namespace qmotion::sweep::pipe_detail
