// The fuzzy operators every engine of the library shares: t-norms (AND, implication), s-norms
// (OR, aggregation), hedges, and the defuzzifiers -- one vocabulary, one `apply`, one set of
// names. The formulas are fuzzylite 6's with its tolerance macheps = 0 (so its comparisons are
// the plain ones), and agree with MATLAB's where MATLAB has the operator:
//
//   t-norm              T(a, b)                                   MATLAB   fuzzylite / FCL
//   Minimum             min(a, b)                                 min      Minimum / MIN
//   Product             a b                                       prod     AlgebraicProduct / PROD
//   BoundedDifference   max(0, a + b - 1)                         -        BoundedDifference / BDIF
//   DrasticProduct      min(a, b) if max(a, b) = 1, else 0        -        DrasticProduct / DPROD
//   EinsteinProduct     a b / (2 - (a + b - a b))                 -        EinsteinProduct / EPROD
//   HamacherProduct     a b / (a + b - a b), 0 if a + b = 0       -        HamacherProduct / HPROD
//   NilpotentMinimum    min(a, b) if a + b > 1, else 0            -        NilpotentMinimum / NMIN
//
//   s-norm              S(a, b)
//   Maximum             max(a, b)                                 max      Maximum / MAX
//   AlgebraicSum        a + b - a b                               probor   AlgebraicSum / ASUM
//   BoundedSum          min(1, a + b)                             -        BoundedSum / BSUM
//   DrasticSum          max(a, b) if min(a, b) = 0, else 1        -        DrasticSum / DSUM
//   EinsteinSum         (a + b) / (1 + a b)                       -        EinsteinSum / ESUM
//   HamacherSum         (a + b - 2 a b) / (1 - a b), 1 if a b = 1 -        HamacherSum / HSUM
//   NilpotentMaximum    max(a, b) if a + b < 1, else 1            -        NilpotentMaximum / NMAX
//   NormalizedSum       (a + b) / max(1, a + b)                   -        NormalizedSum / NSUM
//   UnboundedSum        a + b                                     sum      UnboundedSum / SUM
//
//   hedge       h(mu)
//   Not         1 - mu
//   Seldom      sqrt(mu / 2) if mu <= 1/2, else 1 - sqrt((1 - mu) / 2)
//   Somewhat    sqrt(mu)
//   Very        mu^2
//   Extremely   2 mu^2 if mu <= 1/2, else 1 - 2 (1 - mu)^2
//   Any         1 (the proposition holds whatever the term)
#pragma once

#include <cmath>
#include <cstdint>
#include <string_view>

#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

enum class TNorm : std::uint8_t {
  Minimum,
  Product,
  BoundedDifference,
  DrasticProduct,
  EinsteinProduct,
  HamacherProduct,
  NilpotentMinimum,
};

enum class SNorm : std::uint8_t {
  Maximum,
  AlgebraicSum,
  BoundedSum,
  DrasticSum,
  EinsteinSum,
  HamacherSum,
  NilpotentMaximum,
  NormalizedSum,
  UnboundedSum,
};

enum class Hedge : std::uint8_t { Not, Seldom, Somewhat, Very, Extremely, Any };

// How the degrees of a rule's antecedents combine into its firing strength (the table system
// accepts Minimum and Product).
using Conjunction = TNorm;

enum class Defuzzifier : std::uint8_t {
  Centroid,           // integral; sampled, or exact for piecewise-linear terms
  Bisector,           // integral, sampled
  MeanOfMaximum,      // integral, sampled
  SmallestOfMaximum,  // integral, sampled
  LargestOfMaximum,   // integral, sampled
  WeightedAverage,    // Takagi-Sugeno: y = sum(w_r z_r) / sum(w_r)  -- the paper's Eq. 8
  WeightedSum,        // Takagi-Sugeno: y = sum(w_r z_r)
};

// The defuzzifiers of a Takagi-Sugeno table system (a subset of Defuzzifier).
using TskDefuzzifier = Defuzzifier;

constexpr bool is_sugeno(Defuzzifier d) noexcept {
  return d == Defuzzifier::WeightedAverage || d == Defuzzifier::WeightedSum;
}

template <class Scalar>
constexpr Scalar apply(TNorm op, Scalar a, Scalar b) noexcept {
  switch (op) {
    case TNorm::Minimum:
      return detail::min(a, b);
    case TNorm::Product:
      return a * b;
    case TNorm::BoundedDifference:
      return detail::max(Scalar(0), a + b - Scalar(1));
    case TNorm::DrasticProduct:
      return detail::max(a, b) == Scalar(1) ? detail::min(a, b) : Scalar(0);
    case TNorm::EinsteinProduct:
      return (a * b) / (Scalar(2) - (a + b - a * b));
    case TNorm::HamacherProduct:
      return a + b == Scalar(0) ? Scalar(0) : (a * b) / (a + b - a * b);
    case TNorm::NilpotentMinimum:
      return a + b > Scalar(1) ? detail::min(a, b) : Scalar(0);
  }
  return Scalar(0);
}

template <class Scalar>
constexpr Scalar apply(SNorm op, Scalar a, Scalar b) noexcept {
  switch (op) {
    case SNorm::Maximum:
      return detail::max(a, b);
    case SNorm::AlgebraicSum:
      return a + b - (a * b);
    case SNorm::BoundedSum:
      return detail::min(Scalar(1), a + b);
    case SNorm::DrasticSum:
      return detail::min(a, b) == Scalar(0) ? detail::max(a, b) : Scalar(1);
    case SNorm::EinsteinSum:
      return (a + b) / (Scalar(1) + a * b);
    case SNorm::HamacherSum:
      return a * b == Scalar(1) ? Scalar(1) : (a + b - Scalar(2) * a * b) / (Scalar(1) - a * b);
    case SNorm::NilpotentMaximum:
      return a + b < Scalar(1) ? detail::max(a, b) : Scalar(1);
    case SNorm::NormalizedSum:
      return (a + b) / detail::max(Scalar(1), a + b);
    case SNorm::UnboundedSum:
      return a + b;
  }
  return Scalar(0);
}

template <class Scalar>
Scalar apply(Hedge h, Scalar x) noexcept {
  switch (h) {
    case Hedge::Not:
      return Scalar(1) - x;
    case Hedge::Seldom:
      return x <= Scalar(0.5) ? std::sqrt(Scalar(0.5) * x)
                              : Scalar(1) - std::sqrt(Scalar(0.5) * (Scalar(1) - x));
    case Hedge::Somewhat:
      return std::sqrt(x);
    case Hedge::Very:
      return x * x;
    case Hedge::Extremely:
      return x <= Scalar(0.5) ? Scalar(2) * x * x
                              : Scalar(1) - Scalar(2) * (Scalar(1) - x) * (Scalar(1) - x);
    case Hedge::Any:
      return Scalar(1);
  }
  return x;
}

// ---------------------------------------------------------------------------------------------
// Names: fuzzylite's class names (also what .fll files use), the .fis names (MATLAB's, and
// fuzzylite's FisExporter names for what MATLAB lacks), whether MATLAB has the operator, and the
// IEC 61131-7 FCL names as fuzzylite's FclExporter writes them.

struct OperatorNames {
  const char* fuzzylite;
  const char* fis;
  const char* fcl;
  bool matlab;
};

constexpr OperatorNames kTNormNames[] = {
    {"Minimum", "min", "MIN", true},
    {"AlgebraicProduct", "prod", "PROD", true},
    {"BoundedDifference", "bounded_difference", "BDIF", false},
    {"DrasticProduct", "drastic_product", "DPROD", false},
    {"EinsteinProduct", "einstein_product", "EPROD", false},
    {"HamacherProduct", "hamacher_product", "HPROD", false},
    {"NilpotentMinimum", "nilpotent_minimum", "NMIN", false},
};

constexpr OperatorNames kSNormNames[] = {
    {"Maximum", "max", "MAX", true},
    {"AlgebraicSum", "probor", "ASUM", true},
    {"BoundedSum", "bounded_sum", "BSUM", false},
    {"DrasticSum", "drastic_sum", "DSUM", false},
    {"EinsteinSum", "einstein_sum", "ESUM", false},
    {"HamacherSum", "hamacher_sum", "HSUM", false},
    {"NilpotentMaximum", "nilpotent_maximum", "NMAX", false},
    {"NormalizedSum", "normalized_sum", "NSUM", false},
    {"UnboundedSum", "sum", "UnboundedSum", true},
};

// FCL's LM/RM are the leftmost/rightmost maximum (smallest/largest), as fuzzylite reads them.
constexpr OperatorNames kDefuzzifierNames[] = {
    {"Centroid", "centroid", "COG", true},   {"Bisector", "bisector", "COA", true},
    {"MeanOfMaximum", "mom", "MM", true},    {"SmallestOfMaximum", "som", "LM", true},
    {"LargestOfMaximum", "lom", "RM", true}, {"WeightedAverage", "wtaver", "COGS", true},
    {"WeightedSum", "wtsum", "COGSS", true},
};

// Hedges are written the same way in .fll and .fcl rules (lower case).
constexpr const char* kHedgeNames[] = {"not", "seldom", "somewhat", "very", "extremely", "any"};

[[nodiscard]] constexpr const OperatorNames& names(TNorm t) noexcept {
  return kTNormNames[static_cast<int>(t)];
}
[[nodiscard]] constexpr const OperatorNames& names(SNorm s) noexcept {
  return kSNormNames[static_cast<int>(s)];
}
[[nodiscard]] constexpr const OperatorNames& names(Defuzzifier d) noexcept {
  return kDefuzzifierNames[static_cast<int>(d)];
}

// The short name used in logs and the command line: MATLAB's where it exists, else fuzzylite's.
[[nodiscard]] constexpr const char* to_string(TNorm t) noexcept {
  return names(t).matlab ? names(t).fis : names(t).fuzzylite;
}
[[nodiscard]] constexpr const char* to_string(SNorm s) noexcept {
  return names(s).matlab ? names(s).fis : names(s).fuzzylite;
}
[[nodiscard]] constexpr const char* to_string(Defuzzifier d) noexcept {
  return names(d).fis;
}
[[nodiscard]] constexpr const char* to_string(Hedge h) noexcept {
  return kHedgeNames[static_cast<int>(h)];
}

// Which naming a lookup uses.
enum class Naming : std::uint8_t { Fuzzylite, Fis, Fcl };

namespace operators_detail {
constexpr const char* pick(const OperatorNames& n, Naming naming) noexcept {
  return naming == Naming::Fuzzylite ? n.fuzzylite : naming == Naming::Fis ? n.fis : n.fcl;
}
}  // namespace operators_detail

// Parse tables: true and `out` set when `name` is an operator of that naming.
[[nodiscard]] constexpr bool parse(std::string_view name, Naming naming, TNorm& out) noexcept {
  for (int k = 0; k < 7; ++k) {
    const char* n = operators_detail::pick(kTNormNames[k], naming);
    if (n != nullptr && name == n) {
      out = static_cast<TNorm>(k);
      return true;
    }
  }
  return false;
}
[[nodiscard]] constexpr bool parse(std::string_view name, Naming naming, SNorm& out) noexcept {
  for (int k = 0; k < 9; ++k) {
    const char* n = operators_detail::pick(kSNormNames[k], naming);
    if (n != nullptr && name == n) {
      out = static_cast<SNorm>(k);
      return true;
    }
  }
  return false;
}
[[nodiscard]] constexpr bool parse(std::string_view name, Naming naming,
                                   Defuzzifier& out) noexcept {
  for (int k = 0; k < 7; ++k) {
    const char* n = operators_detail::pick(kDefuzzifierNames[k], naming);
    if (n != nullptr && name == n) {
      out = static_cast<Defuzzifier>(k);
      return true;
    }
  }
  return false;
}
[[nodiscard]] constexpr bool parse(std::string_view name, Hedge& out) noexcept {
  for (int k = 0; k < 6; ++k) {
    if (name == kHedgeNames[k]) {
      out = static_cast<Hedge>(k);
      return true;
    }
  }
  return false;
}

}  // namespace fuzzypid::fuzzy
