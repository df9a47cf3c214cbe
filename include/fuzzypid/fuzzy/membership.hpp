// Membership functions: the degree, in [0, 1], to which a crisp value belongs to a fuzzy set.
//
// Every function is noexcept and total: a NaN input has membership 0 (it belongs to no set), and
// ±infinity is handled by the shape's limits (a shoulder keeps 1 on its open side, bounded shapes
// give 0). The piecewise-linear shapes are constexpr so tests can static_assert them; gaussian and
// generalized bell need exp/pow, which are not constexpr in C++17.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

// Triangle with feet a, c and peak b (a <= b <= c):
//   mu(x) = 0 for x <= a or x >= c, (x - a) / (b - a) on (a, b], (c - x) / (c - b) on [b, c).
// a == b or b == c gives a vertical edge (degree 1 at the peak).
template <class Scalar>
struct Triangle {
  Scalar a, b, c;
  constexpr Scalar operator()(Scalar x) const noexcept {
    if (x == b) return Scalar(1);
    if (!(x > a) || !(x < c)) return Scalar(0);  // also catches NaN
    return x < b ? (x - a) / (b - a) : (c - x) / (c - b);
  }
};

// Trapezoid with feet a, d and plateau [b, c] (a <= b <= c <= d). Infinite a, b (or c, d) give an
// open shoulder, as fuzzylite writes Trapezoid(-inf, -inf, ...).
template <class Scalar>
struct Trapezoid {
  Scalar a, b, c, d;
  constexpr Scalar operator()(Scalar x) const noexcept {
    if (x >= b && x <= c) return Scalar(1);
    if (!(x > a) || !(x < d)) return Scalar(0);
    if (x < b) return a == -detail::infinity<Scalar>() ? Scalar(1) : (x - a) / (b - a);
    return d == detail::infinity<Scalar>() ? Scalar(1) : (d - x) / (d - c);
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
  Scalar operator()(Scalar x) const noexcept {
    if (x != x) return Scalar(0);
    // Evaluated in MATLAB's and fuzzylite's operation order, so loaded rule bases reproduce their
    // results bit for bit (a sampled maximum can otherwise flip between near-equal samples).
    const Scalar d = x - mean;
    return std::exp(-d * d / (Scalar(2) * sigma * sigma));
  }
};

// Generalized bell (MATLAB gbellmf): mu(x) = 1 / (1 + |(x - center) / width|^(2 slope)),
// width != 0, slope > 0.
template <class Scalar>
struct Bell {
  Scalar width, slope, center;
  Scalar operator()(Scalar x) const noexcept {
    if (x != x) return Scalar(0);
    return Scalar(1) / (Scalar(1) + std::pow(std::fabs((x - center) / width), Scalar(2) * slope));
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
  Triangle,       // p = {a, b, c}
  Trapezoid,      // p = {a, b, c, d}
  LeftShoulder,   // p = {a, b}
  RightShoulder,  // p = {a, b}
  Gaussian,       // p = {mean, sigma}
  Bell,           // p = {width, slope, center}
  Singleton,      // p = {x0}
};

// A membership function chosen at run time: one of the shapes above with its parameters. Used
// where a set's shape comes from configuration (linguistic variables, Mamdani output terms).
template <class Scalar>
struct Term {
  Shape shape = Shape::Triangle;
  std::array<Scalar, 4> p{};

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

  // Degree of membership of x (see the shape structs for the formulas).
  Scalar operator()(Scalar x) const noexcept {
    switch (shape) {
      case Shape::Triangle:
        return Triangle<Scalar>{p[0], p[1], p[2]}(x);
      case Shape::Trapezoid:
        return Trapezoid<Scalar>{p[0], p[1], p[2], p[3]}(x);
      case Shape::LeftShoulder:
        return LeftShoulder<Scalar>{p[0], p[1]}(x);
      case Shape::RightShoulder:
        return RightShoulder<Scalar>{p[0], p[1]}(x);
      case Shape::Gaussian:
        return Gaussian<Scalar>{p[0], p[1]}(x);
      case Shape::Bell:
        return Bell<Scalar>{p[0], p[1], p[2]}(x);
      case Shape::Singleton:
        return Singleton<Scalar>{p[0]}(x);
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
        return (p[1] + p[2]) / Scalar(2);
      case Shape::LeftShoulder:
        return p[0];
      case Shape::RightShoulder:
        return p[1];
      case Shape::Gaussian:
        return p[0];
      case Shape::Bell:
        return p[2];
      case Shape::Singleton:
        return p[0];
    }
    return Scalar(0);
  }

  // True when the parameters describe a valid shape (finite where they must be, ordered, positive
  // widths). Shoulders of a trapezoid may be infinite.
  constexpr bool valid() const noexcept {
    using detail::is_finite;
    switch (shape) {
      case Shape::Triangle:
        return is_finite(p[0]) && is_finite(p[1]) && is_finite(p[2]) && p[0] <= p[1] &&
               p[1] <= p[2] && p[0] < p[2];
      case Shape::Trapezoid:
        return p[0] == p[0] && p[1] == p[1] && p[2] == p[2] && p[3] == p[3] && p[0] <= p[1] &&
               p[1] <= p[2] && p[2] <= p[3] && (is_finite(p[1]) || is_finite(p[2]));
      case Shape::LeftShoulder:
      case Shape::RightShoulder:
        return is_finite(p[0]) && is_finite(p[1]) && p[0] < p[1];
      case Shape::Gaussian:
        return is_finite(p[0]) && is_finite(p[1]) && p[1] > Scalar(0);
      case Shape::Bell:
        return is_finite(p[0]) && is_finite(p[1]) && is_finite(p[2]) && p[0] != Scalar(0) &&
               p[1] > Scalar(0);
      case Shape::Singleton:
        return is_finite(p[0]);
    }
    return false;
  }
};

}  // namespace fuzzypid::fuzzy
