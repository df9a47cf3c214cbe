// Mamdani building blocks of the run-time Engine: the aggregated output set and its
// defuzzification.
//
// An activation is an output term with a degree w (the strength of the rule(s) that name it).
// Implication (any t-norm, operators.hpp) shapes the term by w, aggregation (any s-norm) folds the
// shaped terms into one fuzzy set, e.g.
//   implication  Minimum: f(x) = min(mu(x), w)      Product: f(x) = w mu(x)
//   aggregation  Maximum: F(x) = max_k f_k(x)       UnboundedSum: F(x) = sum_k f_k(x)
// Sampled defuzzifiers follow fuzzylite 6 exactly (same sample points, same comparisons with its
// tolerance macheps set to 0), so results agree with fuzzylite at the same resolution:
//   x_i = min + (i + 1/2) dx, dx = (max - min) / resolution, i = 0 .. resolution - 1.
// The exact centroid integrates F over [min, max] in closed form when every term is piecewise
// linear (triangle, trapezoid, shoulders), the implication Minimum or Product and the aggregation
// Maximum or UnboundedSum.
//
// Nothing here allocates or throws; scratch space is passed in by the caller.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

// One output term shaped by a degree: f(x) = implication(mu(x), degree).
template <class Scalar>
struct Activation {
  const Term<Scalar>* term = nullptr;
  Scalar degree = Scalar(0);
  TNorm implication = TNorm::Minimum;
};

// The aggregated output set F(x) of `count` activations (a view: it does not own them).
// `points` is the pool of (x, y) pairs of Discrete terms (may be null without them).
template <class Scalar>
struct AggregatedSet {
  const Activation<Scalar>* activations = nullptr;
  std::size_t count = 0;
  SNorm aggregation = SNorm::Maximum;
  const Scalar* points = nullptr;

  // F(x), folded in activation order from 0 as fuzzylite's Aggregated::membership does.
  Scalar operator()(Scalar x) const noexcept {
    Scalar mu = Scalar(0);
    for (std::size_t k = 0; k < count; ++k)
      mu = apply(aggregation, mu,
                 apply(activations[k].implication, (*activations[k].term)(x, points),
                       activations[k].degree));
    return mu;
  }
};

// True for the monotonic shapes Tsukamoto's method inverts.
template <class Scalar>
constexpr bool is_monotonic(const Term<Scalar>& t) noexcept {
  return t.shape == Shape::Ramp || t.shape == Shape::Sigmoid || t.shape == Shape::SShape ||
         t.shape == Shape::ZShape || t.shape == Shape::Concave || t.shape == Shape::Arc;
}

// True for the shapes the exact centroid integrates in closed form (at height 1).
template <class Scalar>
constexpr bool is_piecewise_linear(const Term<Scalar>& t) noexcept {
  return (t.shape == Shape::Triangle || t.shape == Shape::Trapezoid ||
          t.shape == Shape::LeftShoulder || t.shape == Shape::RightShoulder) &&
         t.height == Scalar(1);
}

// ---------------------------------------------------------------------------------------------
// Sampled defuzzifiers over [min, max] at `resolution` (>= 1) midpoint samples. Each returns NaN
// when the set has no area there (fuzzylite does the same), so callers can tell "empty" apart.

// Centroid: sum(x_i F(x_i)) / sum(F(x_i)).
template <class Scalar, class Set>
Scalar centroid_sampled(const Set& set, Scalar min, Scalar max, int resolution) noexcept {
  const Scalar dx = (max - min) / Scalar(resolution);
  Scalar area = Scalar(0);
  Scalar moment = Scalar(0);
  for (int i = 0; i < resolution; ++i) {
    const Scalar x = min + (Scalar(i) + Scalar(0.5)) * dx;
    const Scalar y = set(x);
    moment += y * x;
    area += y;
  }
  return area > Scalar(0) ? moment / area : std::numeric_limits<Scalar>::quiet_NaN();
}

// Bisector: the sample where the running area is nearest half the total, as fuzzylite 8 computes
// it: with c_i = y_0 + ... + y_i over the samples x_i and C = c_{n-1}, the mean of the x_i whose
// |c_i / C - 1/2| is least (several when the area stops growing there). fuzzylite 6 swept from
// both ends and interpolated between the two fronts (docs/rule_files.md). NaN without area.
template <class Scalar, class Set>
Scalar bisector_sampled(const Set& set, Scalar min, Scalar max, int resolution) noexcept {
  const Scalar dx = (max - min) / Scalar(resolution);
  Scalar total = Scalar(0);
  for (int i = 0; i < resolution; ++i)
    total += set(min + (Scalar(i) + Scalar(0.5)) * dx);
  if (!(total > Scalar(0))) return std::numeric_limits<Scalar>::quiet_NaN();
  Scalar running = Scalar(0);
  Scalar nearest = std::numeric_limits<Scalar>::infinity();
  Scalar x_sum = Scalar(0);
  int count = 0;
  for (int i = 0; i < resolution; ++i) {
    const Scalar x = min + (Scalar(i) + Scalar(0.5)) * dx;
    running += set(x);
    const Scalar d = detail::abs(running / total - Scalar(0.5));
    if (d < nearest) {
      nearest = d;
      x_sum = x;
      count = 1;
    } else if (d == nearest) {
      x_sum += x;
      ++count;
    }
  }
  return x_sum / Scalar(count);
}

enum class MaximumKind : std::uint8_t { Smallest, Mean, Largest };

// Smallest, mean or largest of maximum over ALL the samples where the set is largest (MATLAB,
// Octave and fuzzylite 8: the mean is sum(x_i) / n over every maximising sample, so two equal
// plateaus give the mean of both; fuzzylite 6 took the middle of the first plateau). NaN when the
// set is 0 at every sample.
template <class Scalar, class Set>
Scalar of_maximum_sampled(MaximumKind kind, const Set& set, Scalar min, Scalar max,
                          int resolution) noexcept {
  const Scalar dx = (max - min) / Scalar(resolution);
  Scalar y_max = Scalar(-1);
  Scalar x_smallest = min;
  Scalar x_largest = max;
  Scalar x_sum = Scalar(0);
  int count = 0;
  for (int i = 0; i < resolution; ++i) {
    const Scalar x = min + (Scalar(i) + Scalar(0.5)) * dx;
    const Scalar y = set(x);
    if (y > y_max) {
      y_max = y;
      x_smallest = x;
      x_largest = x;
      x_sum = x;
      count = 1;
    } else if (y == y_max) {
      x_largest = x;
      x_sum += x;
      ++count;
    }
  }
  if (!(y_max > Scalar(0))) return std::numeric_limits<Scalar>::quiet_NaN();
  switch (kind) {
    case MaximumKind::Smallest:
      return x_smallest;
    case MaximumKind::Largest:
      return x_largest;
    case MaximumKind::Mean:
      break;
  }
  return x_sum / Scalar(count);
}

// ---------------------------------------------------------------------------------------------
// Exact centroid of a Mamdani set of piecewise-linear terms on [min, max].
//
// Every shaped term f_k is linear between its finite vertices and (for min implication) the two
// points where its edges cross the clip level w. Between consecutive breakpoints of all terms the
// sum of the f_k is linear; their maximum is linear between the pairwise crossings of the lines
// on that interval. On each linear piece from (x0, y0) to (x1, y1):
//   area = dx (y0 + y1) / 2,   moment = dx (x0 (2 y0 + y1) + x1 (y0 + 2 y1)) / 6.
// Scratch: `breakpoints` needs 6 count + 2 entries; `lines` 2 count; `crossings` count (count - 1)
// / 2 (Maximum aggregation only). Returns NaN when the set has no area in [min, max] or a term is
// not piecewise linear or a scratch buffer is too small.
struct ExactCentroidScratch {
  std::size_t breakpoints_capacity = 0;
  std::size_t lines_capacity = 0;
  std::size_t crossings_capacity = 0;
};

namespace defuzzify_detail {

// Appends the breakpoints of one shaped term that lie strictly inside (min, max).
template <class Scalar>
inline std::size_t term_breakpoints(const Term<Scalar>& t, Scalar w, TNorm imp, Scalar min,
                                    Scalar max, Scalar* out) noexcept {
  std::size_t n = 0;
  const auto push = [&](Scalar x) {
    if (x > min && x < max) out[n++] = x;
  };
  const bool clip = imp == TNorm::Minimum && w < Scalar(1);
  const auto& p = t.p;
  switch (t.shape) {
    case Shape::Triangle:
      push(p[0]);
      push(p[1]);
      push(p[2]);
      if (clip) {
        push(p[0] + w * (p[1] - p[0]));
        push(p[2] - w * (p[2] - p[1]));
      }
      break;
    case Shape::Trapezoid:
      for (int k = 0; k < 4; ++k)
        if (detail::is_finite(p[k])) push(p[k]);
      if (clip) {
        if (detail::is_finite(p[0])) push(p[0] + w * (p[1] - p[0]));
        if (detail::is_finite(p[3])) push(p[3] - w * (p[3] - p[2]));
      }
      break;
    case Shape::LeftShoulder:
      push(p[0]);
      push(p[1]);
      if (clip) push(p[1] - w * (p[1] - p[0]));
      break;
    case Shape::RightShoulder:
      push(p[0]);
      push(p[1]);
      if (clip) push(p[0] + w * (p[1] - p[0]));
      break;
    default:
      break;
  }
  return n;
}

}  // namespace defuzzify_detail

template <class Scalar>
Scalar centroid_exact(const AggregatedSet<Scalar>& set, Scalar min, Scalar max, Scalar* breakpoints,
                      Scalar* lines, Scalar* crossings,
                      const ExactCentroidScratch& capacity) noexcept {
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  const std::size_t count = set.count;
  const bool need_crossings = set.aggregation == SNorm::Maximum;
  if (set.aggregation != SNorm::Maximum && set.aggregation != SNorm::UnboundedSum) return nan;
  if (capacity.breakpoints_capacity < 6 * count + 2 || capacity.lines_capacity < 2 * count ||
      (need_crossings && count > 1 && capacity.crossings_capacity < count * (count - 1) / 2))
    return nan;
  std::size_t n = 0;
  breakpoints[n++] = min;
  breakpoints[n++] = max;
  for (std::size_t k = 0; k < count; ++k) {
    const Activation<Scalar>& a = set.activations[k];
    if (!is_piecewise_linear(*a.term) ||
        (a.implication != TNorm::Minimum && a.implication != TNorm::Product))
      return nan;
    n += defuzzify_detail::term_breakpoints(*a.term, a.degree, a.implication, min, max,
                                            breakpoints + n);
  }
  std::sort(breakpoints, breakpoints + n);

  Scalar area = Scalar(0);
  Scalar moment = Scalar(0);
  const auto piece = [&](Scalar x0, Scalar y0, Scalar x1, Scalar y1) {
    const Scalar dx = x1 - x0;
    area += dx * (y0 + y1) / Scalar(2);
    moment += dx * (x0 * (Scalar(2) * y0 + y1) + x1 * (y0 + Scalar(2) * y1)) / Scalar(6);
  };
  for (std::size_t b = 0; b + 1 < n; ++b) {
    const Scalar x0 = breakpoints[b];
    const Scalar x1 = breakpoints[b + 1];
    if (!(x1 > x0)) continue;
    // Each shaped term is linear on (x0, x1): read it at the quarter points (away from any jump
    // at the ends) and extend the line to the ends.
    const Scalar dx = x1 - x0;
    const Scalar q1 = x0 + dx / Scalar(4);
    const Scalar q3 = x0 + Scalar(3) * dx / Scalar(4);
    Scalar sum0 = Scalar(0);
    Scalar sum1 = Scalar(0);
    for (std::size_t k = 0; k < count; ++k) {
      const Activation<Scalar>& a = set.activations[k];
      const Scalar f1 = apply(a.implication, (*a.term)(q1), a.degree);
      const Scalar f3 = apply(a.implication, (*a.term)(q3), a.degree);
      const Scalar half = (f3 - f1) / Scalar(2);
      lines[2 * k] = f1 - half;
      lines[2 * k + 1] = f3 + half;
      sum0 += lines[2 * k];
      sum1 += lines[2 * k + 1];
    }
    if (!need_crossings) {
      piece(x0, sum0, x1, sum1);
      continue;
    }
    // Upper envelope of the lines: linear between the (sorted) crossings of any two of them.
    std::size_t m = 0;
    for (std::size_t i = 0; i < count; ++i) {
      for (std::size_t j = i + 1; j < count; ++j) {
        const Scalar d0 = lines[2 * i] - lines[2 * j];
        const Scalar d1 = lines[2 * i + 1] - lines[2 * j + 1];
        if ((d0 < Scalar(0) && d1 > Scalar(0)) || (d0 > Scalar(0) && d1 < Scalar(0)))
          crossings[m++] = d0 / (d0 - d1);
      }
    }
    std::sort(crossings, crossings + m);
    const auto envelope = [&](Scalar t) {
      Scalar y = Scalar(0);
      for (std::size_t k = 0; k < count; ++k)
        y = detail::max(y, lines[2 * k] + t * (lines[2 * k + 1] - lines[2 * k]));
      return y;
    };
    Scalar t_prev = Scalar(0);
    Scalar y_prev = envelope(Scalar(0));
    for (std::size_t c = 0; c <= m; ++c) {
      const Scalar t = c < m ? crossings[c] : Scalar(1);
      if (t <= t_prev) continue;
      const Scalar y = envelope(t);
      piece(x0 + t_prev * dx, y_prev, x0 + t * dx, y);
      t_prev = t;
      y_prev = y;
    }
  }
  return area > Scalar(0) ? moment / area : nan;
}

}  // namespace fuzzypid::fuzzy
