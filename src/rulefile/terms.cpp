#include "terms.hpp"

#include <cmath>

#include "text.hpp"

namespace fuzzypid::io::terms {

namespace {

std::string count_error(std::string_view type, std::size_t expected, std::size_t got) {
  return "term type '" + std::string(type) + "' takes " + std::to_string(expected) +
         " parameters, got " + std::to_string(got);
}

bool all_finite(const std::vector<double>& p) {
  for (double x : p)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

std::string make_membership(Format format, std::string_view type, const std::vector<double>& p,
                            fuzzy::Term<double>& term) {
  const bool fis = format == Format::Fis;
  for (double x : p)
    if (std::isnan(x)) return "NaN parameter in term of type '" + std::string(type) + "'";
  if (type == (fis ? "trimf" : "Triangle")) {
    if (p.size() != 3) return count_error(type, 3, p.size());
    if (!all_finite(p)) return "triangle parameters must be finite";
    if (!(p[0] <= p[1] && p[1] <= p[2] && p[0] < p[2]))
      return "triangle parameters must satisfy a <= b <= c and a < c";
    term = fuzzy::Term<double>::triangle(p[0], p[1], p[2]);
    return {};
  }
  if (type == (fis ? "trapmf" : "Trapezoid")) {
    if (p.size() != 4) return count_error(type, 4, p.size());
    if (!(p[0] <= p[1] && p[1] <= p[2] && p[2] <= p[3]))
      return "trapezoid parameters must satisfy a <= b <= c <= d";
    if (!(std::isfinite(p[1]) || std::isfinite(p[2])))
      return "trapezoid needs a finite plateau edge";
    if (std::isinf(p[1]) && p[0] != p[1]) return "trapezoid with b = -inf needs a = -inf";
    if (std::isinf(p[2]) && p[2] != p[3]) return "trapezoid with c = inf needs d = inf";
    if (p[0] == p[3]) return "trapezoid has zero width";
    term = fuzzy::Term<double>::trapezoid(p[0], p[1], p[2], p[3]);
    return {};
  }
  if (type == (fis ? "gaussmf" : "Gaussian")) {
    if (p.size() != 2) return count_error(type, 2, p.size());
    if (!all_finite(p)) return "gaussian parameters must be finite";
    const double sigma = fis ? p[0] : p[1];
    const double mean = fis ? p[1] : p[0];
    if (!(sigma > 0)) return "gaussian sigma must be > 0";
    term = fuzzy::Term<double>::gaussian(mean, sigma);
    return {};
  }
  if (type == (fis ? "gbellmf" : "Bell")) {
    if (p.size() != 3) return count_error(type, 3, p.size());
    if (!all_finite(p)) return "bell parameters must be finite";
    const double width = fis ? p[0] : p[1];
    const double slope = fis ? p[1] : p[2];
    const double center = fis ? p[2] : p[0];
    if (width == 0) return "bell width must be non-zero";
    if (!(slope > 0)) return "bell slope must be > 0";
    term = fuzzy::Term<double>::bell(width, slope, center);
    return {};
  }
  return "unsupported term type '" + std::string(type) + "'";
}

std::string write_membership(Format format, const fuzzy::Term<double>& t) {
  using fuzzy::Shape;
  const bool fis = format == Format::Fis;
  const auto& p = t.p;
  const auto n = [](double x) { return text::format_number(x); };
  const auto list = [&](std::initializer_list<double> v) {
    std::string s;
    for (double x : v)
      s += (s.empty() ? "" : " ") + n(x);
    return fis ? "[" + s + "]" : s;
  };
  const auto typed = [&](const char* fis_name, const char* fll_name, const std::string& params) {
    return fis ? "'" + std::string(fis_name) + "'," + params : std::string(fll_name) + " " + params;
  };
  const double inf = std::numeric_limits<double>::infinity();
  switch (t.shape) {
    case Shape::Triangle:
      return typed("trimf", "Triangle", list({p[0], p[1], p[2]}));
    case Shape::Trapezoid:
      return typed("trapmf", "Trapezoid", list({p[0], p[1], p[2], p[3]}));
    case Shape::LeftShoulder:
      return typed("trapmf", "Trapezoid", list({-inf, -inf, p[0], p[1]}));
    case Shape::RightShoulder:
      return typed("trapmf", "Trapezoid", list({p[0], p[1], inf, inf}));
    case Shape::Gaussian:
      return fis ? typed("gaussmf", "", list({p[1], p[0]}))
                 : typed("", "Gaussian", list({p[0], p[1]}));
    case Shape::Bell:
      return fis ? typed("gbellmf", "", list({p[0], p[1], p[2]}))
                 : typed("", "Bell", list({p[2], p[0], p[1]}));
    case Shape::Singleton:
      return {};
  }
  return {};
}

}  // namespace fuzzypid::io::terms
