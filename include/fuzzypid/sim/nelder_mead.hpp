// Derivative-free minimisation by the Nelder-Mead simplex method (standard coefficients:
// reflection 1, expansion 2, contraction 0.5, shrink 0.5). Deterministic: the same start, steps
// and objective always give the same result. Used offline to tune a fixed PID (not in the tick).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace fuzzypid::sim {

template <std::size_t N>
struct NelderMeadResult {
  std::array<double, N> x{};
  double value = 0.0;
  std::size_t evaluations = 0;
  std::size_t iterations = 0;
  bool converged = false;  // simplex values spread below the tolerance
};

// Minimises f from `start` with an initial simplex of start + step_k e_k. Stops when the spread of
// the simplex's values falls below `tolerance` (absolute) or after `max_iterations`. f must
// return a finite value or +infinity for points to reject.
template <std::size_t N, class F>
NelderMeadResult<N> nelder_mead(F&& f, const std::array<double, N>& start,
                                const std::array<double, N>& step, double tolerance,
                                std::size_t max_iterations) {
  using Point = std::array<double, N>;
  std::array<Point, N + 1> p{};
  std::array<double, N + 1> v{};
  NelderMeadResult<N> result;
  auto eval = [&](const Point& x) {
    ++result.evaluations;
    return f(x);
  };
  p[0] = start;
  for (std::size_t k = 0; k < N; ++k) {
    p[k + 1] = start;
    p[k + 1][k] += step[k];
  }
  for (std::size_t k = 0; k <= N; ++k)
    v[k] = eval(p[k]);

  auto lerp = [](const Point& a, const Point& b, double t) {
    Point out{};
    for (std::size_t k = 0; k < N; ++k)
      out[k] = a[k] + t * (b[k] - a[k]);
    return out;
  };

  for (; result.iterations < max_iterations; ++result.iterations) {
    std::array<std::size_t, N + 1> order{};
    for (std::size_t k = 0; k <= N; ++k)
      order[k] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
    const std::size_t best = order[0], worst = order[N], second = order[N - 1];
    if (v[worst] - v[best] <= tolerance) {
      result.converged = true;
      break;
    }
    Point centroid{};
    for (std::size_t k = 0; k <= N; ++k) {
      if (k == worst) continue;
      for (std::size_t d = 0; d < N; ++d)
        centroid[d] += p[k][d] / static_cast<double>(N);
    }
    const Point reflected = lerp(centroid, p[worst], -1.0);
    const double fr = eval(reflected);
    if (fr < v[best]) {
      const Point expanded = lerp(centroid, p[worst], -2.0);
      const double fe = eval(expanded);
      if (fe < fr) {
        p[worst] = expanded;
        v[worst] = fe;
      } else {
        p[worst] = reflected;
        v[worst] = fr;
      }
      continue;
    }
    if (fr < v[second]) {
      p[worst] = reflected;
      v[worst] = fr;
      continue;
    }
    const bool outside = fr < v[worst];
    const Point contracted = lerp(centroid, outside ? reflected : p[worst], 0.5);
    const double fc = eval(contracted);
    if (fc < (outside ? fr : v[worst])) {
      p[worst] = contracted;
      v[worst] = fc;
      continue;
    }
    for (std::size_t k = 0; k <= N; ++k) {
      if (k == best) continue;
      p[k] = lerp(p[best], p[k], 0.5);
      v[k] = eval(p[k]);
    }
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k <= N; ++k)
    if (v[k] < v[best]) best = k;
  result.x = p[best];
  result.value = v[best];
  return result;
}

}  // namespace fuzzypid::sim
