// Membership functions: the degree to which a crisp value belongs to a fuzzy set.
//
// Every shape of fuzzylite 6 is here, and fuzzylite 8's Arc and SemiEllipse, with fuzzylite's
// formula evaluated in fuzzylite's operation order (its tolerance macheps set to 0), so a loaded
// rule base reproduces fuzzylite bit for bit.
// Each term has a height h (fuzzylite's optional last parameter; 1 unless stated) that scales it.
//
//   shape              parameters p            mu(x) / h                                 MATLAB
//   Triangle           a b c                   0 outside [a, c], 1 at b, (x-a)/(b-a)      trimf
//                                              rising, (c-x)/(c-b) falling
//   Trapezoid          a b c d                 0 outside [a, d], 1 on [b, c], linear      trapmf
//                                              edges (an infinite foot = shoulder)
//   Rectangle          start end               1 on [start, end], else 0                  -
//   Gaussian           mean sigma              exp(-(x-mean)^2 / (2 sigma^2))             gaussmf
//                                                                                  [sigma mean]
//   GaussianProduct    meanA sigmaA            left half of A (x < meanA), 1, right half  gauss2mf
//                      meanB sigmaB            of B (x > meanB)                  [sA mA sB mB]
//   Bell               center width slope      1 / (1 + |(x-center)/width|^(2 slope))     gbellmf
//                                                                        [width slope center]
//   PiShape            a b c d                 S from a to b, 1, Z from c to d            pimf
//   SShape             start end               spline 0 -> 1                              smf
//   ZShape             start end               spline 1 -> 0                              zmf
//   Sigmoid            inflection slope        1 / (1 + exp(-slope (x - infl)))           sigmf
//                                                                                  [slope infl]
//   SigmoidDifference  left rising             |sig(rising, left) - sig(falling, right)|  dsigmf
//                      falling right                                             [a1 c1 a2 c2]
//   SigmoidProduct     left rising             sig(rising, left) sig(falling, right)      psigmf
//                      falling right                                             [a1 c1 a2 c2]
//   Ramp               start end               linear 0 at start -> 1 at end (falling     linsmf/
//                                              when end < start)                          linzmf
//   Cosine             center width            (1 + cos(2 pi (x-center)/width)) / 2 on    -
//                                              [center - width/2, center + width/2]
//   Concave            inflection end          (end-infl) / (2 end - infl - x) for        -
//                                              x < end (increasing; mirrored when
//                                              infl > end), else 1
//   Spike              center width            exp(-|10 (x - center) / width|)            -
//   Binary             start direction         1 on the side of start towards direction   -
//   Discrete           x1 y1 x2 y2 ...         linear interpolation, ends held            -
//   Arc (fuzzylite 8)  start end               sqrt(r^2 - (x-c)^2) / |r| from start to    -
//                                              end, r = end - start, c = start + r;
//                                              1 beyond end, 0 before start
//   SemiEllipse        start end               sqrt(r^2 - (x-c)^2) / r on [s, e] =        -
//     (fuzzylite 8)                            [min, max of start, end], r = (e - s)/2,
//                                              c = s + r; else 0
//   Function           a formula f             f(x) (height not applied, as fuzzylite): x  -
//                                              and the inputs' values; steps of a compiled
//                                              program in the model's pool (formula.hpp),
//                                              evaluated by the engine, 0 from Term alone
//   LeftShoulder, RightShoulder, Singleton: the paper's partitions (no fuzzylite counterpart).
//
// Every function is noexcept and total. A NaN input has membership 0 (fuzzylite returns NaN; the
// engine refuses NaN inputs before fuzzifying, so loaded systems never see the difference), and
// ±infinity follows the formula's limits. The piecewise-linear shapes are constexpr.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

namespace shape {

// t^2 as a product: what fuzzylite's std::pow(t, 2) compiles to with optimization (GCC folds it
// into t * t), and exact in every build, unlike a library pow call.
template <class Scalar>
constexpr Scalar sq(Scalar t) noexcept {
  return t * t;
}

template <class Scalar>
constexpr Scalar triangle(Scalar a, Scalar b, Scalar c, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  if (x < a || x > c) return h * Scalar(0);
  if (x == b) return h * Scalar(1);
  if (x < b) return a == -detail::infinity<Scalar>() ? h * Scalar(1) : h * (x - a) / (b - a);
  return c == detail::infinity<Scalar>() ? h * Scalar(1) : h * (c - x) / (c - b);
}

template <class Scalar>
constexpr Scalar trapezoid(Scalar a, Scalar b, Scalar c, Scalar d, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  if (x < a || x > d) return h * Scalar(0);
  if (x < b) {
    if (a == -detail::infinity<Scalar>()) return h * Scalar(1);
    return h * detail::min(Scalar(1), (x - a) / (b - a));
  }
  if (x <= c) return h * Scalar(1);
  if (x < d) return d == detail::infinity<Scalar>() ? h * Scalar(1) : h * (d - x) / (d - c);
  if (d == detail::infinity<Scalar>()) return h * Scalar(1);
  return h * Scalar(0);
}

template <class Scalar>
constexpr Scalar rectangle(Scalar start, Scalar end, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  return x >= start && x <= end ? h * Scalar(1) : h * Scalar(0);
}

template <class Scalar>
constexpr Scalar ramp(Scalar start, Scalar end, Scalar h, Scalar x) noexcept {
  if (x != x || start == end) return Scalar(0);
  if (start < end) {
    if (x <= start) return h * Scalar(0);
    if (x >= end) return h * Scalar(1);
    return h * (x - start) / (end - start);
  }
  if (x >= start) return h * Scalar(0);
  if (x <= end) return h * Scalar(1);
  return h * (start - x) / (start - end);
}

template <class Scalar>
constexpr Scalar binary(Scalar start, Scalar direction, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  if (direction > start && x >= start) return h * Scalar(1);
  if (direction < start && x <= start) return h * Scalar(1);
  return h * Scalar(0);
}

template <class Scalar>
Scalar gaussian(Scalar mean, Scalar sigma, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  return h * std::exp((-(x - mean) * (x - mean)) / (Scalar(2) * sigma * sigma));
}

template <class Scalar>
Scalar gaussian_product(Scalar mean_a, Scalar sigma_a, Scalar mean_b, Scalar sigma_b, Scalar h,
                        Scalar x) noexcept {
  if (x != x) return Scalar(0);
  Scalar a = Scalar(1);
  Scalar b = Scalar(1);
  if (x < mean_a) a = std::exp((-(x - mean_a) * (x - mean_a)) / (Scalar(2) * sigma_a * sigma_a));
  if (x > mean_b) b = std::exp((-(x - mean_b) * (x - mean_b)) / (Scalar(2) * sigma_b * sigma_b));
  return h * a * b;
}

template <class Scalar>
Scalar bell(Scalar center, Scalar width, Scalar slope, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  return h *
         (Scalar(1) / (Scalar(1) + std::pow(std::fabs((x - center) / width), Scalar(2) * slope)));
}

template <class Scalar>
Scalar pi_shape(Scalar a, Scalar b, Scalar c, Scalar d, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  const Scalar a_b_ave = (a + b) / Scalar(2);
  const Scalar b_minus_a = b - a;
  const Scalar c_d_ave = (c + d) / Scalar(2);
  const Scalar d_minus_c = d - c;
  if (x <= a) return h * Scalar(0);
  if (x <= a_b_ave) return h * Scalar(2) * sq((x - a) / b_minus_a);
  if (x < b) return h * (Scalar(1) - Scalar(2) * sq((x - b) / b_minus_a));
  if (x <= c) return h * Scalar(1);
  if (x <= c_d_ave) return h * (Scalar(1) - Scalar(2) * sq((x - c) / d_minus_c));
  if (x < d) return h * Scalar(2) * sq((x - d) / d_minus_c);
  return h * Scalar(0);
}

template <class Scalar>
Scalar s_shape(Scalar start, Scalar end, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  const Scalar average = (start + end) / Scalar(2);
  const Scalar difference = end - start;
  if (x <= start) return h * Scalar(0);
  if (x <= average) return h * Scalar(2) * sq((x - start) / difference);
  if (x < end) return h * (Scalar(1) - Scalar(2) * sq((x - end) / difference));
  return h * Scalar(1);
}

template <class Scalar>
Scalar z_shape(Scalar start, Scalar end, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  const Scalar average = (start + end) / Scalar(2);
  const Scalar difference = end - start;
  if (x <= start) return h * Scalar(1);
  if (x <= average) return h * (Scalar(1) - Scalar(2) * sq((x - start) / difference));
  if (x < end) return h * Scalar(2) * sq((x - end) / difference);
  return h * Scalar(0);
}

template <class Scalar>
Scalar sigmoid(Scalar inflection, Scalar slope, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  return h * Scalar(1) / (Scalar(1) + std::exp(-slope * (x - inflection)));
}

template <class Scalar>
Scalar sigmoid_difference(Scalar left, Scalar rising, Scalar falling, Scalar right, Scalar h,
                          Scalar x) noexcept {
  if (x != x) return Scalar(0);
  const Scalar a = Scalar(1) / (Scalar(1) + std::exp(-rising * (x - left)));
  const Scalar b = Scalar(1) / (Scalar(1) + std::exp(-falling * (x - right)));
  return h * std::fabs(a - b);
}

template <class Scalar>
Scalar sigmoid_product(Scalar left, Scalar rising, Scalar falling, Scalar right, Scalar h,
                       Scalar x) noexcept {
  if (x != x) return Scalar(0);
  const Scalar a = Scalar(1) + std::exp(-rising * (x - left));
  const Scalar b = Scalar(1) + std::exp(-falling * (x - right));
  return h * Scalar(1) / (a * b);
}

template <class Scalar>
Scalar cosine(Scalar center, Scalar width, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  if (x < center - Scalar(0.5) * width || x > center + Scalar(0.5) * width) return h * Scalar(0);
  const Scalar pi = Scalar(4) * std::atan(Scalar(1));
  return h * Scalar(0.5) * (Scalar(1) + std::cos(Scalar(2) / width * pi * (x - center)));
}

template <class Scalar>
constexpr Scalar concave(Scalar inflection, Scalar end, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  if (inflection <= end) {
    if (x < end) return h * (end - inflection) / (Scalar(2) * end - inflection - x);
  } else {
    if (x > end) return h * (inflection - end) / (inflection - Scalar(2) * end + x);
  }
  return h * Scalar(1);
}

template <class Scalar>
Scalar spike(Scalar center, Scalar width, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  return h * std::exp(-std::fabs(Scalar(10) / width * (x - center)));
}

// fuzzylite 8's Arc: a quarter circle of radius r = end - start centered at c = start + r (= end
// up to rounding), rising from 0 at start to h at end (falling when end < start), h beyond end,
// 0 before start; 0 everywhere when start = end. fuzzylite 8 computes c = start + r and takes the
// arc on [start, c]; so do we. Two roundings are kept away: a point within an ulp of the stretch's
// ends where r^2 - (x - c)^2 rounds below 0 (fuzzylite 8: sqrt of a negative, NaN) gives the
// arc's end value, and a point between c and end (an ulp wide, fuzzylite 8: 0) gives h.
template <class Scalar>
Scalar arc(Scalar start, Scalar end, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  const Scalar r = end - start;
  const Scalar c = start + r;
  const bool rising = start < end;
  if (!rising && !(start > end)) return h * Scalar(0);
  if (rising ? x < start : x > start) return h * Scalar(0);
  if (rising ? x > c : x < c) return h * Scalar(1);
  return h * (std::sqrt(detail::max(Scalar(0), r * r - (x - c) * (x - c))) / std::fabs(r));
}

// fuzzylite 8's SemiEllipse: the upper half of an ellipse over [s, e] = [min(start, end),
// max(start, end)] of height h, h sqrt(r^2 - (x - c)^2) / r with r = (e - s) / 2, c = s + r,
// 0 outside [s, e]. A rounding of r^2 - (x - c)^2 below 0 at the ends gives 0 (fuzzylite 8: NaN).
template <class Scalar>
Scalar semi_ellipse(Scalar start, Scalar end, Scalar h, Scalar x) noexcept {
  if (x != x) return Scalar(0);
  const Scalar s = detail::min(start, end);
  const Scalar e = detail::max(start, end);
  if (!(x >= s && x <= e)) return h * Scalar(0);
  const Scalar r = (e - s) / Scalar(2);
  const Scalar c = s + r;
  return h * (std::sqrt(detail::max(Scalar(0), r * r - (x - c) * (x - c))) / r);
}

// xy: count pairs (x ascending).
template <class Scalar>
constexpr Scalar discrete(const Scalar* xy, std::size_t count, Scalar h, Scalar x) noexcept {
  if (x != x || count == 0) return Scalar(0);
  if (x <= xy[0]) return h * xy[1];
  if (x >= xy[2 * (count - 1)]) return h * xy[2 * count - 1];
  std::size_t upper = 1;  // first point with x_k > x (upper bound)
  while (upper < count && !(x < xy[2 * upper]))
    ++upper;
  if (x == xy[2 * upper]) return h * xy[2 * upper + 1];
  const Scalar x0 = xy[2 * (upper - 1)], y0 = xy[2 * (upper - 1) + 1];
  const Scalar x1 = xy[2 * upper], y1 = xy[2 * upper + 1];
  return h * ((y1 - y0) / (x1 - x0) * (x - x0) + y0);
}

}  // namespace shape

// Triangle with feet a, c and peak b (a <= b <= c).
template <class Scalar>
struct Triangle {
  Scalar a, b, c;
  constexpr Scalar operator()(Scalar x) const noexcept {
    return shape::triangle(a, b, c, Scalar(1), x);
  }
};

// Trapezoid with feet a, d and plateau [b, c] (a <= b <= c <= d). Infinite a, b (or c, d) give an
// open shoulder, as fuzzylite writes Trapezoid(-inf, -inf, ...).
template <class Scalar>
struct Trapezoid {
  Scalar a, b, c, d;
  constexpr Scalar operator()(Scalar x) const noexcept {
    return shape::trapezoid(a, b, c, d, Scalar(1), x);
  }
};

// Left shoulder: 1 for x <= a, falling linearly to 0 at b, 0 for x >= b (a < b). The outermost
// negative set of a partition, so an input below the universe saturates instead of vanishing.
template <class Scalar>
struct LeftShoulder {
  Scalar a, b;
  constexpr Scalar operator()(Scalar x) const noexcept {
    if (x <= a) return Scalar(1);
    if (!(x < b)) return Scalar(0);
    return (b - x) / (b - a);
  }
};

// Right shoulder: 0 for x <= a, rising linearly to 1 at b, 1 for x >= b (a < b).
template <class Scalar>
struct RightShoulder {
  Scalar a, b;
  constexpr Scalar operator()(Scalar x) const noexcept {
    if (x >= b) return Scalar(1);
    if (!(x > a)) return Scalar(0);
    return (x - a) / (b - a);
  }
};

// Gaussian: mu(x) = exp(-(x - mean)^2 / (2 sigma^2)), sigma > 0.
template <class Scalar>
struct Gaussian {
  Scalar mean, sigma;
  Scalar operator()(Scalar x) const noexcept { return shape::gaussian(mean, sigma, Scalar(1), x); }
};

// Generalized bell (MATLAB gbellmf): mu(x) = 1 / (1 + |(x - center) / width|^(2 slope)).
template <class Scalar>
struct Bell {
  Scalar width, slope, center;
  Scalar operator()(Scalar x) const noexcept {
    return shape::bell(center, width, slope, Scalar(1), x);
  }
};

// Singleton: 1 exactly at x0, 0 elsewhere.
template <class Scalar>
struct Singleton {
  Scalar x0;
  constexpr Scalar operator()(Scalar x) const noexcept { return x == x0 ? Scalar(1) : Scalar(0); }
};

// The shape of a run-time term (a tagged union without virtual calls).
enum class Shape : std::uint8_t {
  Triangle,           // p = {a, b, c}
  Trapezoid,          // p = {a, b, c, d}
  LeftShoulder,       // p = {a, b}
  RightShoulder,      // p = {a, b}
  Gaussian,           // p = {mean, sigma}
  Bell,               // p = {width, slope, center}
  Singleton,          // p = {x0}
  Rectangle,          // p = {start, end}
  GaussianProduct,    // p = {meanA, sigmaA, meanB, sigmaB}
  PiShape,            // p = {a, b, c, d}
  SShape,             // p = {start, end}
  ZShape,             // p = {start, end}
  Sigmoid,            // p = {inflection, slope}
  SigmoidDifference,  // p = {left, rising, falling, right}
  SigmoidProduct,     // p = {left, rising, falling, right}
  Ramp,               // p = {start, end}
  Cosine,             // p = {center, width}
  Concave,            // p = {inflection, end}
  Spike,              // p = {center, width}
  Binary,             // p = {start, direction}
  Discrete,           // points[first .. first + count) of a pool of (x, y) pairs
  Arc,                // p = {start, end}
  SemiEllipse,        // p = {start, end}
  Function,           // steps[first .. first + count) of the model's formula pool (formula.hpp)
};

// A membership function chosen at run time: one of the shapes above with its parameters and
// height. Discrete terms refer to a pool of points held by their owner (the engine model), Function
// terms to a pool of formula steps (evaluated by the engine, which knows the inputs' values).
template <class Scalar>
struct Term {
  Shape shape = Shape::Triangle;
  std::array<Scalar, 4> p{};
  Scalar height = Scalar(1);
  std::uint32_t first = 0;  // Discrete: index of its first (x, y) pair in the pool; Function:
                            // of its first formula step
  std::uint32_t count = 0;  // Discrete: number of pairs; Function: number of steps

  static constexpr Term triangle(Scalar a, Scalar b, Scalar c) noexcept {
    return {Shape::Triangle, {a, b, c, Scalar(0)}};
  }
  static constexpr Term trapezoid(Scalar a, Scalar b, Scalar c, Scalar d) noexcept {
    return {Shape::Trapezoid, {a, b, c, d}};
  }
  static constexpr Term left_shoulder(Scalar a, Scalar b) noexcept {
    return {Shape::LeftShoulder, {a, b, Scalar(0), Scalar(0)}};
  }
  static constexpr Term right_shoulder(Scalar a, Scalar b) noexcept {
    return {Shape::RightShoulder, {a, b, Scalar(0), Scalar(0)}};
  }
  static constexpr Term gaussian(Scalar mean, Scalar sigma) noexcept {
    return {Shape::Gaussian, {mean, sigma, Scalar(0), Scalar(0)}};
  }
  static constexpr Term bell(Scalar width, Scalar slope, Scalar center) noexcept {
    return {Shape::Bell, {width, slope, center, Scalar(0)}};
  }
  static constexpr Term singleton(Scalar x0) noexcept {
    return {Shape::Singleton, {x0, Scalar(0), Scalar(0), Scalar(0)}};
  }
  static constexpr Term make(Shape s, Scalar p0, Scalar p1 = Scalar(0), Scalar p2 = Scalar(0),
                             Scalar p3 = Scalar(0), Scalar h = Scalar(1)) noexcept {
    return {s, {p0, p1, p2, p3}, h};
  }

  // Degree of membership of x (see the table at the top for the formulas). `points` is the pool
  // of (x, y) pairs Discrete terms refer to (unused by the other shapes). A Function term is 0
  // here: its formula reads the inputs' values, which only the engine holds (fuzzy/engine.hpp).
  Scalar operator()(Scalar x, const Scalar* points = nullptr) const noexcept {
    const Scalar h = height;
    switch (shape) {
      case Shape::Triangle:
        return shape::triangle(p[0], p[1], p[2], h, x);
      case Shape::Trapezoid:
        return shape::trapezoid(p[0], p[1], p[2], p[3], h, x);
      case Shape::LeftShoulder:
        return LeftShoulder<Scalar>{p[0], p[1]}(x);
      case Shape::RightShoulder:
        return RightShoulder<Scalar>{p[0], p[1]}(x);
      case Shape::Gaussian:
        return shape::gaussian(p[0], p[1], h, x);
      case Shape::Bell:
        return shape::bell(p[2], p[0], p[1], h, x);
      case Shape::Singleton:
        return Singleton<Scalar>{p[0]}(x);
      case Shape::Rectangle:
        return shape::rectangle(p[0], p[1], h, x);
      case Shape::GaussianProduct:
        return shape::gaussian_product(p[0], p[1], p[2], p[3], h, x);
      case Shape::PiShape:
        return shape::pi_shape(p[0], p[1], p[2], p[3], h, x);
      case Shape::SShape:
        return shape::s_shape(p[0], p[1], h, x);
      case Shape::ZShape:
        return shape::z_shape(p[0], p[1], h, x);
      case Shape::Sigmoid:
        return shape::sigmoid(p[0], p[1], h, x);
      case Shape::SigmoidDifference:
        return shape::sigmoid_difference(p[0], p[1], p[2], p[3], h, x);
      case Shape::SigmoidProduct:
        return shape::sigmoid_product(p[0], p[1], p[2], p[3], h, x);
      case Shape::Ramp:
        return shape::ramp(p[0], p[1], h, x);
      case Shape::Cosine:
        return shape::cosine(p[0], p[1], h, x);
      case Shape::Concave:
        return shape::concave(p[0], p[1], h, x);
      case Shape::Spike:
        return shape::spike(p[0], p[1], h, x);
      case Shape::Binary:
        return shape::binary(p[0], p[1], h, x);
      case Shape::Discrete:
        return points == nullptr ? Scalar(0) : shape::discrete(points + 2 * first, count, h, x);
      case Shape::Arc:
        return shape::arc(p[0], p[1], h, x);
      case Shape::SemiEllipse:
        return shape::semi_ellipse(p[0], p[1], h, x);
      case Shape::Function:
        return Scalar(0);
    }
    return Scalar(0);
  }

  // The point of greatest membership, used as the term's crisp value by center-average
  // defuzzification (Eq. 8). Shoulders and trapezoids use the middle of their plateau's finite
  // edge(s).
  constexpr Scalar center() const noexcept {
    switch (shape) {
      case Shape::Triangle:
        return p[1];
      case Shape::Trapezoid:
      case Shape::PiShape:
        return (p[1] + p[2]) / Scalar(2);
      case Shape::LeftShoulder:
      case Shape::Gaussian:
      case Shape::Singleton:
      case Shape::Cosine:
      case Shape::Spike:
        return p[0];
      case Shape::RightShoulder:
      case Shape::Arc:
        return p[1];
      case Shape::Bell:
        return p[2];
      case Shape::GaussianProduct:
        return (p[0] + p[2]) / Scalar(2);
      case Shape::Rectangle:
      case Shape::SemiEllipse:
        return (p[0] + p[1]) / Scalar(2);
      default:
        return p[0];
    }
  }

  // True when the parameters describe a shape that evaluates to a number in [0, height] for every
  // input (finite where they must be, ordered, non-zero widths) and the height is in [0, 1].
  constexpr bool valid() const noexcept {
    using detail::is_finite;
    const bool all4 = is_finite(p[0]) && is_finite(p[1]) && is_finite(p[2]) && is_finite(p[3]);
    const bool two = is_finite(p[0]) && is_finite(p[1]);
    if (!(height == height && height >= Scalar(0) && is_finite(height))) return false;
    switch (shape) {
      case Shape::Triangle:
        return is_finite(p[0]) && is_finite(p[1]) && is_finite(p[2]) && p[0] <= p[1] &&
               p[1] <= p[2] && p[0] < p[2];
      case Shape::Trapezoid:
        return p[0] == p[0] && p[1] == p[1] && p[2] == p[2] && p[3] == p[3] && p[0] <= p[1] &&
               p[1] <= p[2] && p[2] <= p[3] && (is_finite(p[1]) || is_finite(p[2]));
      case Shape::LeftShoulder:
      case Shape::RightShoulder:
        return two && p[0] < p[1];
      case Shape::Gaussian:
        return two && p[1] > Scalar(0);
      case Shape::Bell:
        return two && is_finite(p[2]) && p[0] != Scalar(0) && p[1] > Scalar(0);
      case Shape::Singleton:
        return is_finite(p[0]);
      case Shape::Rectangle:
        return p[0] == p[0] && p[1] == p[1] && p[0] <= p[1];
      case Shape::GaussianProduct:
        return all4 && p[1] > Scalar(0) && p[3] > Scalar(0);
      case Shape::PiShape:
        return all4 && p[0] < p[1] && p[1] <= p[2] && p[2] < p[3];
      case Shape::SShape:
      case Shape::ZShape:
        return two && p[0] < p[1];
      case Shape::Sigmoid:
      case Shape::Ramp:
        return two;
      case Shape::Binary:  // the direction may be +-inf, as fuzzylite writes it
        return is_finite(p[0]) && p[1] == p[1] && p[1] != p[0];
      case Shape::SigmoidDifference:
      case Shape::SigmoidProduct:
        return all4;
      case Shape::Cosine:
      case Shape::Spike:
        return two && p[1] > Scalar(0);
      case Shape::Concave:
        return two && p[0] != p[1];
      case Shape::Discrete:
        return count >= 1;
      case Shape::Arc:  // start = end is 0 everywhere, as fuzzylite 8 computes it
        return two;
      case Shape::SemiEllipse:  // start = end would divide 0 by 0 (fuzzylite 8: NaN at start)
        return two && p[0] != p[1];
      case Shape::Function:  // the steps are checked by the model that holds them
        return count >= 1;
    }
    return false;
  }
};

}  // namespace fuzzypid::fuzzy
