#include "terms.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "formula.hpp"
#include "text.hpp"

namespace fuzzypid::rulefile::terms {

namespace {

using fuzzy::Shape;

struct Spec {
  Shape shape;
  const char* fll;              // fuzzylite class name
  const char* fis;              // .fis name (nullptr: no .fis form)
  std::size_t n;                // parameters (without height)
  std::array<int, 4> from_fll;  // internal p[k] = fll[from_fll[k]]
  std::array<int, 4> from_fis;  // internal p[k] = fis[from_fis[k]]
};

// Internal parameter order: membership.hpp's Shape comments.
constexpr Spec kSpecs[] = {
    {Shape::Triangle, "Triangle", "trimf", 3, {0, 1, 2, -1}, {0, 1, 2, -1}},
    {Shape::Trapezoid, "Trapezoid", "trapmf", 4, {0, 1, 2, 3}, {0, 1, 2, 3}},
    {Shape::Rectangle, "Rectangle", "rectmf", 2, {0, 1, -1, -1}, {0, 1, -1, -1}},
    {Shape::Gaussian, "Gaussian", "gaussmf", 2, {0, 1, -1, -1}, {1, 0, -1, -1}},
    {Shape::GaussianProduct, "GaussianProduct", "gauss2mf", 4, {0, 1, 2, 3}, {1, 0, 3, 2}},
    {Shape::Bell, "Bell", "gbellmf", 3, {1, 2, 0, -1}, {0, 1, 2, -1}},
    {Shape::PiShape, "PiShape", "pimf", 4, {0, 1, 2, 3}, {0, 1, 2, 3}},
    {Shape::SShape, "SShape", "smf", 2, {0, 1, -1, -1}, {0, 1, -1, -1}},
    {Shape::ZShape, "ZShape", "zmf", 2, {0, 1, -1, -1}, {0, 1, -1, -1}},
    {Shape::Sigmoid, "Sigmoid", "sigmf", 2, {0, 1, -1, -1}, {1, 0, -1, -1}},
    {Shape::SigmoidDifference, "SigmoidDifference", "dsigmf", 4, {0, 1, 2, 3}, {1, 0, 2, 3}},
    {Shape::SigmoidProduct, "SigmoidProduct", "psigmf", 4, {0, 1, 2, 3}, {1, 0, 2, 3}},
    {Shape::Ramp, "Ramp", "rampmf", 2, {0, 1, -1, -1}, {0, 1, -1, -1}},
    {Shape::Cosine, "Cosine", "cosinemf", 2, {0, 1, -1, -1}, {0, 1, -1, -1}},
    {Shape::Concave, "Concave", "concavemf", 2, {0, 1, -1, -1}, {0, 1, -1, -1}},
    {Shape::Spike, "Spike", "spikemf", 2, {0, 1, -1, -1}, {0, 1, -1, -1}},
    {Shape::Binary, "Binary", "binarymf", 2, {0, 1, -1, -1}, {0, 1, -1, -1}},
    // fuzzylite 8's; neither MATLAB nor fuzzylite's FisImporter has them.
    {Shape::Arc, "Arc", nullptr, 2, {0, 1, -1, -1}, {}},
    {Shape::SemiEllipse, "SemiEllipse", nullptr, 2, {0, 1, -1, -1}, {}},
};

// The spec a file's type name means in that format, or nullptr.
const Spec* find_spec(Format format, std::string_view type) {
  for (const Spec& s : kSpecs) {
    const char* name = format == Format::Fis ? s.fis : s.fll;
    if (name != nullptr && type == name) return &s;
  }
  return nullptr;
}

std::string count_error(std::string_view type, std::size_t expected, std::size_t got) {
  return "'" + std::string(type) + "' takes " + std::to_string(expected) + " parameters, got " +
         std::to_string(got);
}

// Why valid() refused a term, in the file's words.
std::string shape_error(std::string_view type, Shape s) {
  const std::string t = "'" + std::string(type) + "' ";
  switch (s) {
    case Shape::Triangle:
      return t + "needs finite a <= b <= c with a < c";
    case Shape::Trapezoid:
      return t + "needs a <= b <= c <= d and a finite b or c";
    case Shape::Gaussian:
    case Shape::GaussianProduct:
      return t + "needs finite parameters and a positive standard deviation";
    case Shape::Bell:
      return t + "needs finite parameters, a non-zero width and a positive slope";
    case Shape::PiShape:
      return t + "needs finite a < b <= c < d";
    case Shape::SShape:
    case Shape::ZShape:
      return t + "needs finite start < end";
    case Shape::Cosine:
    case Shape::Spike:
      return t + "needs finite parameters and a positive width";
    case Shape::Concave:
      return t + "needs finite parameters with inflection != end";
    case Shape::Rectangle:
      return t + "needs start <= end";
    case Shape::SemiEllipse:
      return t + "needs finite start != end";
    case Shape::Discrete:
      return t + "needs finite (x, y) pairs with x strictly increasing";
    default:
      return t + "needs finite parameters";
  }
}

}  // namespace

bool is_membership_name(Format format, std::string_view type) {
  if (find_spec(format, type) != nullptr) return true;
  if (format == Format::Fis) return type == "linsmf" || type == "linzmf" || type == "discretemf";
  return type == "Discrete";
}

std::string make_membership(Format format, std::string_view type, const std::vector<double>& p,
                            Builder& model, fuzzy::Term<double>& term) {
  const bool fis = format == Format::Fis;
  for (double x : p)
    if (std::isnan(x)) return "NaN parameter in '" + std::string(type) + "'";
  term = fuzzy::Term<double>{};
  // Discrete: x1 y1 x2 y2 ... (+ height in .fll/.fcl when the count is odd).
  if (type == (fis ? "discretemf" : "Discrete")) {
    std::size_t n = p.size();
    if (!fis && n % 2 == 1) {
      term.height = p.back();
      --n;
    }
    if (n < 2 || n % 2 == 1)
      return "'" + std::string(type) + "' takes (x, y) pairs, got " + std::to_string(p.size()) +
             " numbers";
    const std::size_t pairs = n / 2;
    if (model.num_points + pairs > Model::Capacity::points)
      return "Discrete points exceed the capacity (" + std::to_string(Model::Capacity::points) +
             " pairs)";
    term.shape = Shape::Discrete;
    term.first = static_cast<std::uint32_t>(model.num_points);
    term.count = static_cast<std::uint32_t>(pairs);
    for (std::size_t k = 0; k < n; ++k) {
      if (!std::isfinite(p[k])) return shape_error(type, Shape::Discrete);
      if (k % 2 == 0 && k > 0 && !(p[k - 2] < p[k])) return shape_error(type, Shape::Discrete);
      model.points[2 * model.num_points + k] = p[k];
    }
    model.num_points += pairs;
  } else if (fis && (type == "linsmf" || type == "linzmf")) {
    std::size_t n = p.size();
    while (n > 2 && p[n - 1] == 0.0)
      --n;
    if (n != 2) return count_error(type, 2, p.size());
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && p[0] < p[1]))
      return "'" + std::string(type) + "' needs finite a < b";
    term = type == "linsmf" ? fuzzy::Term<double>::make(Shape::Ramp, p[0], p[1])
                            : fuzzy::Term<double>::make(Shape::Ramp, p[1], p[0]);
  } else {
    const Spec* spec = find_spec(format, type);
    if (spec == nullptr) {
      if (fis && type == "function") return std::string(kFisFunction);
      if (fis && (type == "arcmf" || type == "semiellipsemf"))
        return "'" + std::string(type) +
               "': fuzzylite 8's Arc and SemiEllipse have no .fis form (neither MATLAB nor "
               "fuzzylite's FisImporter reads them); write them in .fll or .fcl";
      return "unsupported membership function '" + std::string(type) + "'";
    }
    std::size_t n = p.size();
    if (fis) {
      // MATLAB 1.x wrote every parameter list padded with zeros to the longest one.
      while (n > spec->n && p[n - 1] == 0.0)
        --n;
      if (n != spec->n) return count_error(type, spec->n, p.size());
    } else {
      if (n != spec->n && n != spec->n + 1)
        return "'" + std::string(type) + "' takes " + std::to_string(spec->n) +
               " parameters (and an optional height), got " + std::to_string(n);
      if (n == spec->n + 1) term.height = p[spec->n];
    }
    term.shape = spec->shape;
    const auto& from = fis ? spec->from_fis : spec->from_fll;
    for (std::size_t k = 0; k < spec->n; ++k)
      term.p[k] = p[static_cast<std::size_t>(from[k])];
  }
  // fuzzylite accepts heights above 1 (and writes them for a hybrid's constants, see
  // fis_reader.cpp).
  if (!(std::isfinite(term.height) && term.height >= 0))
    return "term height must be a finite number >= 0";
  if (!term.valid()) return shape_error(type, term.shape);
  return {};
}

std::string write_membership(Format format, const fuzzy::Term<double>& t, const Model& model) {
  const bool fis = format == Format::Fis;
  const auto& p = t.p;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> values;
  std::string type;
  if (t.shape == Shape::Function) {
    if (fis) return {};  // kFisFunction
    const std::string f = formula::write(t, model);
    return f.empty() ? std::string() : "Function " + f;
  }
  if (t.shape == Shape::Discrete) {
    type = fis ? "discretemf" : "Discrete";
    for (std::size_t k = 0; k < 2 * t.count; ++k)
      values.push_back(model.points[2 * t.first + k]);
  } else if (t.shape == Shape::LeftShoulder || t.shape == Shape::RightShoulder) {
    type = fis ? "trapmf" : "Trapezoid";
    values = t.shape == Shape::LeftShoulder ? std::vector<double>{-inf, -inf, p[0], p[1]}
                                            : std::vector<double>{p[0], p[1], inf, inf};
  } else if (fis && t.shape == Shape::Ramp && p[0] != p[1]) {
    // MATLAB's names; a Ramp of zero width (0 everywhere) has none and stays fuzzylite's rampmf.
    type = p[0] < p[1] ? "linsmf" : "linzmf";
    values = p[0] < p[1] ? std::vector<double>{p[0], p[1]} : std::vector<double>{p[1], p[0]};
  } else {
    const Spec* spec = nullptr;
    for (const Spec& s : kSpecs)
      if (s.shape == t.shape) spec = &s;
    if (spec == nullptr || (fis && spec->fis == nullptr)) return {};  // Singleton; Arc in .fis
    type = fis ? spec->fis : spec->fll;
    values.assign(spec->n, 0.0);
    const auto& from = fis ? spec->from_fis : spec->from_fll;
    for (std::size_t k = 0; k < spec->n; ++k)
      values[static_cast<std::size_t>(from[k])] = p[k];
  }
  if (t.height != 1.0) {
    if (fis) return {};
    values.push_back(t.height);
  }
  std::string s;
  if (format == Format::Fcl && t.shape == Shape::Discrete) {
    for (std::size_t k = 0; k + 1 < values.size(); k += 2)
      s += (s.empty() ? "(" : " (") + text::format_number(values[k]) + ", " +
           text::format_number(values[k + 1]) + ")";
    if (t.height != 1.0) return {};
    return s;
  }
  for (double x : values)
    s += (s.empty() ? "" : " ") + text::format_number(x);
  return fis ? "'" + type + "',[" + s + "]" : type + " " + s;
}

}  // namespace fuzzypid::rulefile::terms
