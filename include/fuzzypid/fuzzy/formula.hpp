// Formulas of fuzzylite's Function terms, compiled: a postfix program of fixed-size steps that a
// value stack of at most kMaxFormulaDepth entries evaluates, noexcept and without allocation.
// The rule-file readers compile fuzzylite 8's infix grammar into it (docs/rule_files.md,
// "Function terms"); the engine model holds the steps of all its formulas in one pool, and each
// Function term refers to steps [first, first + count) of it, as Discrete terms refer to points.
//
// Each operation computes what fuzzylite 8 (pyfuzzylite 8.0.6, numpy) computes:
//   ! a       1 when a == 0, else 0 (NaN is true: 0)          np.logical_not
//   ~ a, .- a -a                                              np.negative
//   .+ a      a                                               np.positive
//   a ^ b, a ** b, pow(a, b)   pow(a, b)                      np.float_power
//   a % b     a - b floor(a / b): the sign of b (NaN for b = 0) np.remainder
//   fmod(a, b)                 the sign of a                   np.fmod
//   a and b, a or b            1 or 0, NaN is true             np.logical_and, np.logical_or
//   gt lt     a > b, a < b (0 with a NaN)
//   eq neq ge le               a == b, !=, >=, <= with NaN equal to NaN (np.isclose, tolerance 0)
//   min(a, b), max(a, b)       b < a ? b : a, b > a ? b : a    Python's min and max
//   round(a)                   to nearest, ties to even        np.round
//   abs fabs acos asin atan atan2 ceil cos cosh exp floor log log10 log1p sin sinh sqrt tan
//   tanh acosh asinh atanh     the C library's                 numpy's
//   pi                         3.141592653589793
// A domain error gives what IEEE 754 gives (NaN for sqrt(-1), inf for 1 / 0): the engine turns
// a non-finite formula value into a status (fuzzy/engine.hpp).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

// The deepest value stack a formula may need (checked when it is compiled and validated).
inline constexpr std::size_t kMaxFormulaDepth = 32;

enum class FormulaOp : std::uint8_t {
  // operands (arity 0)
  Number,  // push value
  X,       // push the crisp value whose membership is computed
  Input,   // push the value of input `input` (after lock-range)
  Pi,
  // unary
  Not,
  Negate,
  Plus,
  Acos,
  Asin,
  Atan,
  Ceil,
  Cos,
  Cosh,
  Exp,
  Abs,
  Floor,
  Log,
  Log10,
  Round,
  Sin,
  Sinh,
  Sqrt,
  Tan,
  Tanh,
  Log1p,
  Acosh,
  Asinh,
  Atanh,
  // binary: a (pushed first) op b
  Power,
  Multiply,
  Divide,
  Modulo,
  Add,
  Subtract,
  And,
  Or,
  Gt,
  Ge,
  Eq,
  Neq,
  Le,
  Lt,
  Min,
  Max,
  Atan2,
  Fmod,
};

// The number of values an operation pops (it pushes one).
constexpr std::size_t formula_arity(FormulaOp op) noexcept {
  return op <= FormulaOp::Pi ? 0 : op <= FormulaOp::Atanh ? 1 : 2;
}

template <class Scalar>
struct FormulaStep {
  FormulaOp op = FormulaOp::Number;
  std::uint8_t input = 0;    // Input: the input's index
  Scalar value = Scalar(0);  // Number: the constant
  bool operator==(const FormulaStep& o) const noexcept {
    return op == o.op && input == o.input &&
           (value == o.value || (value != value && o.value != o.value));
  }
};

// The deepest stack steps[0 .. count) reach; 0 when they are not one well-formed formula (an
// operation without its operands, more or fewer than one value left, an Input index at or above
// num_inputs, X where `x_allowed` is false) or need more than kMaxFormulaDepth.
template <class Scalar>
constexpr std::size_t formula_depth(const FormulaStep<Scalar>* steps, std::size_t count,
                                    std::size_t num_inputs, bool x_allowed) noexcept {
  std::size_t depth = 0;
  std::size_t deepest = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const FormulaOp op = steps[k].op;
    if (op > FormulaOp::Fmod) return 0;
    if (op == FormulaOp::Input && steps[k].input >= num_inputs) return 0;
    if (op == FormulaOp::X && !x_allowed) return 0;
    const std::size_t arity = formula_arity(op);
    if (depth < arity) return 0;
    depth = depth - arity + 1;
    deepest = depth > deepest ? depth : deepest;
    if (deepest > kMaxFormulaDepth) return 0;
  }
  return depth == 1 ? deepest : 0;
}

namespace formula_detail {

// NaN equals NaN, as np.isclose(a, b, rtol=0, atol=0, equal_nan=True).
template <class Scalar>
constexpr bool same(Scalar a, Scalar b) noexcept {
  return a == b || (a != a && b != b);
}

template <class Scalar>
constexpr Scalar truth(bool b) noexcept {
  return b ? Scalar(1) : Scalar(0);
}

// np.remainder: the remainder of floored division, with the sign of b.
template <class Scalar>
Scalar remainder(Scalar a, Scalar b) noexcept {
  Scalar mod = std::fmod(a, b);
  if (b == Scalar(0)) return mod;  // NaN
  if (mod != Scalar(0)) {
    if ((b < Scalar(0)) != (mod < Scalar(0))) mod += b;
  } else {
    mod = std::copysign(Scalar(0), b);
  }
  return mod;
}

// np.round: to the nearest integer, ties to even, the sign of a zero kept.
template <class Scalar>
Scalar round_half_even(Scalar a) noexcept {
  const Scalar f = std::floor(a);
  const Scalar d = a - f;  // exact: a and f share the exponent's grid
  Scalar r = f + Scalar(1);
  if (d < Scalar(0.5) || (d == Scalar(0.5) && std::fmod(f, Scalar(2)) == Scalar(0))) r = f;
  return r == Scalar(0) ? std::copysign(Scalar(0), a) : r;
}

}  // namespace formula_detail

// The value of the well-formed formula steps[0 .. count) (formula_depth() > 0) at crisp value x
// and input values inputs[0 ..).
template <class Scalar>
Scalar evaluate_formula(const FormulaStep<Scalar>* steps, std::size_t count, Scalar x,
                        const Scalar* inputs) noexcept {
  using namespace formula_detail;
  Scalar stack[kMaxFormulaDepth];
  std::size_t sp = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const FormulaStep<Scalar>& s = steps[k];
    const std::size_t arity = formula_arity(s.op);
    const Scalar b = arity >= 1 ? stack[sp - 1] : Scalar(0);
    const Scalar a = arity == 2 ? stack[sp - 2] : Scalar(0);
    sp -= arity;
    Scalar r = Scalar(0);
    switch (s.op) {
      case FormulaOp::Number:
        r = s.value;
        break;
      case FormulaOp::X:
        r = x;
        break;
      case FormulaOp::Input:
        r = inputs[s.input];
        break;
      case FormulaOp::Pi:
        r = Scalar(3.141592653589793238462643383279502884L);
        break;
      case FormulaOp::Not:
        r = truth<Scalar>(b == Scalar(0));
        break;
      case FormulaOp::Negate:
        r = -b;
        break;
      case FormulaOp::Plus:
        r = b;
        break;
      case FormulaOp::Acos:
        r = std::acos(b);
        break;
      case FormulaOp::Asin:
        r = std::asin(b);
        break;
      case FormulaOp::Atan:
        r = std::atan(b);
        break;
      case FormulaOp::Ceil:
        r = std::ceil(b);
        break;
      case FormulaOp::Cos:
        r = std::cos(b);
        break;
      case FormulaOp::Cosh:
        r = std::cosh(b);
        break;
      case FormulaOp::Exp:
        r = std::exp(b);
        break;
      case FormulaOp::Abs:
        r = std::fabs(b);
        break;
      case FormulaOp::Floor:
        r = std::floor(b);
        break;
      case FormulaOp::Log:
        r = std::log(b);
        break;
      case FormulaOp::Log10:
        r = std::log10(b);
        break;
      case FormulaOp::Round:
        r = round_half_even(b);
        break;
      case FormulaOp::Sin:
        r = std::sin(b);
        break;
      case FormulaOp::Sinh:
        r = std::sinh(b);
        break;
      case FormulaOp::Sqrt:
        r = std::sqrt(b);
        break;
      case FormulaOp::Tan:
        r = std::tan(b);
        break;
      case FormulaOp::Tanh:
        r = std::tanh(b);
        break;
      case FormulaOp::Log1p:
        r = std::log1p(b);
        break;
      case FormulaOp::Acosh:
        r = std::acosh(b);
        break;
      case FormulaOp::Asinh:
        r = std::asinh(b);
        break;
      case FormulaOp::Atanh:
        r = std::atanh(b);
        break;
      case FormulaOp::Power:
        r = std::pow(a, b);
        break;
      case FormulaOp::Multiply:
        r = a * b;
        break;
      case FormulaOp::Divide:
        r = a / b;
        break;
      case FormulaOp::Modulo:
        r = remainder(a, b);
        break;
      case FormulaOp::Add:
        r = a + b;
        break;
      case FormulaOp::Subtract:
        r = a - b;
        break;
      case FormulaOp::And:
        r = truth<Scalar>(a != Scalar(0) && b != Scalar(0));
        break;
      case FormulaOp::Or:
        r = truth<Scalar>(a != Scalar(0) || b != Scalar(0));
        break;
      case FormulaOp::Gt:
        r = truth<Scalar>(a > b);
        break;
      case FormulaOp::Ge:
        r = truth<Scalar>(a >= b || same(a, b));
        break;
      case FormulaOp::Eq:
        r = truth<Scalar>(same(a, b));
        break;
      case FormulaOp::Neq:
        r = truth<Scalar>(!same(a, b));
        break;
      case FormulaOp::Le:
        r = truth<Scalar>(a <= b || same(a, b));
        break;
      case FormulaOp::Lt:
        r = truth<Scalar>(a < b);
        break;
      case FormulaOp::Min:
        r = b < a ? b : a;
        break;
      case FormulaOp::Max:
        r = b > a ? b : a;
        break;
      case FormulaOp::Atan2:
        r = std::atan2(a, b);
        break;
      case FormulaOp::Fmod:
        r = std::fmod(a, b);
        break;
    }
    stack[sp++] = r;
  }
  return stack[0];
}

}  // namespace fuzzypid::fuzzy
