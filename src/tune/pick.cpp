// Picking a front's point and hypervolumes (pick.hpp).
#include "fuzzypid/tune/pick.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <pagmo/utils/hypervolume.hpp>

#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/tune/front.hpp"
#include "fuzzypid_support/bounded_read.hpp"

namespace fuzzypid::tune {

namespace {

// A front of 10^5 points is far below this.
constexpr std::size_t kMaxFrontBytes = std::size_t{64} << 20;

std::vector<std::string> split(const std::string& row) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = row.find(',', begin);
    out.push_back(row.substr(begin, comma - begin));
    if (comma == std::string::npos) return out;
    begin = comma + 1;
  }
}

// A finite number spelled whole; false otherwise.
bool number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return *end == '\0' && std::isfinite(value);
}

}  // namespace

std::optional<FrontTable> read_front(const std::string& dir, std::string& error) {
  const std::string path = dir + "/front.csv";
  std::string text;
  if (!support::read_file_bounded(path, kMaxFrontBytes, text, error)) return std::nullopt;
  FrontTable t;
  std::size_t line = 0, begin = 0, columns = 0;
  bool validation = false;
  const auto fail = [&](const std::string& why) {
    error = path + ":" + std::to_string(line) + ": " + why;
    return std::nullopt;
  };
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string row = text.substr(begin, end - begin);
    begin = end + 1;
    ++line;
    if (!row.empty() && row.back() == '\r') row.pop_back();
    const std::vector<std::string> f = split(row);
    if (line == 1) {
      if (f.size() < 4 || f[0] != "point" || f[1] != "file")
        return fail("not a front's header (point,file,<objectives>[,validation_<objectives>])");
      std::vector<std::string> names(f.begin() + 2, f.end());
      const std::size_t m = names.size();
      validation = m % 2 == 0 && m >= 4 && names[m / 2].rfind("validation_", 0) == 0;
      const std::size_t own = validation ? m / 2 : m;
      for (std::size_t i = 0; i < own; ++i) {
        if (!fuzzypid::parse_enum(kMetricNames, names[i]))
          return fail("unknown objective '" + names[i] + "' (one of " +
                      fuzzypid::names_of(kMetricNames) + ")");
        if (std::find(t.objectives.begin(), t.objectives.end(), names[i]) != t.objectives.end())
          return fail("objective '" + names[i] + "' given twice");
        if (validation && names[own + i] != "validation_" + names[i])
          return fail("column " + std::to_string(own + i + 3) + " is '" + names[own + i] +
                      "', expected 'validation_" + names[i] + "'");
        t.objectives.push_back(names[i]);
      }
      if (t.objectives.size() < 2) return fail("a front has at least two objectives");
      columns = f.size();
      continue;
    }
    if (row.empty()) continue;
    if (f.size() != columns)
      return fail(std::to_string(f.size()) + " fields, expected " + std::to_string(columns));
    if (f[0] != std::to_string(t.files.size()))
      return fail("point '" + f[0] + "', expected " + std::to_string(t.files.size()));
    if (f[1].empty() || f[1] == "." || f[1] == ".." || f[1].find('/') != std::string::npos)
      return fail("file '" + f[1] + "' is not a file of the front's folder");
    const std::size_t m = t.objectives.size();
    std::vector<double> v(columns - 2);
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!number(f[i + 2], v[i]))
        return fail("column " + std::to_string(i + 3) + " ('" + f[i + 2] +
                    "') is not a finite number");
    t.files.push_back(f[1]);
    t.training.emplace_back(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m));
    if (validation) t.validation.emplace_back(v.begin() + static_cast<std::ptrdiff_t>(m), v.end());
  }
  if (line == 0) return fail("empty");
  if (t.files.empty()) return fail("a front of no point");
  return t;
}

std::optional<PickRule> parse_pick_rule(const std::string& text, std::string& error) {
  PickRule r;
  const auto objective = [&](const std::string& name) {
    if (fuzzypid::parse_enum(kMetricNames, name)) return true;
    error = "'" + text + "': unknown objective '" + name + "' (one of " +
            fuzzypid::names_of(kMetricNames) + ")";
    return false;
  };
  if (text == "knee") return r;
  if (text.rfind("min:", 0) == 0) {
    r.kind = PickRule::Kind::Min;
    r.objective = text.substr(4);
    if (!objective(r.objective)) return std::nullopt;
    return r;
  }
  if (text.rfind("max:", 0) == 0) {
    const std::size_t eq = text.find('=');
    r.kind = PickRule::Kind::Max;
    r.objective = text.substr(4, eq == std::string::npos ? std::string::npos : eq - 4);
    if (!objective(r.objective)) return std::nullopt;
    if (eq == std::string::npos || !number(text.substr(eq + 1), r.cap)) {
      error = "'" + text + "': expected max:OBJECTIVE=X with X a finite number";
      return std::nullopt;
    }
    return r;
  }
  error = "'" + text + "': expected knee, min:OBJECTIVE or max:OBJECTIVE=X";
  return std::nullopt;
}

std::optional<std::size_t> pick(const std::vector<std::string>& objectives,
                                const std::vector<std::vector<double>>& points,
                                const PickRule& rule, std::string& error) {
  if (points.empty()) {
    error = "a front of no point";
    return std::nullopt;
  }
  const std::size_t m = objectives.size();
  std::size_t column = 0;
  if (rule.kind != PickRule::Kind::Knee) {
    const auto it = std::find(objectives.begin(), objectives.end(), rule.objective);
    if (it == objectives.end()) {
      error = "the front has no objective '" + rule.objective + "'";
      return std::nullopt;
    }
    column = static_cast<std::size_t>(it - objectives.begin());
  }
  std::optional<std::size_t> best;
  switch (rule.kind) {
    case PickRule::Kind::Knee: {
      std::vector<double> lo(m, std::numeric_limits<double>::infinity()), hi(m, -lo[0]);
      for (const auto& p : points)
        for (std::size_t i = 0; i < m; ++i) {
          lo[i] = std::min(lo[i], p[i]);
          hi[i] = std::max(hi[i], p[i]);
        }
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < points.size(); ++k) {
        double d2 = 0.0;
        for (std::size_t i = 0; i < m; ++i) {
          const double s = hi[i] > lo[i] ? (points[k][i] - lo[i]) / (hi[i] - lo[i]) : 0.0;
          d2 += s * s;
        }
        if (d2 < nearest) {
          nearest = d2;
          best = k;
        }
      }
      break;
    }
    case PickRule::Kind::Min:
      for (std::size_t k = 0; k < points.size(); ++k)
        if (!best || points[k][column] < points[*best][column]) best = k;
      break;
    case PickRule::Kind::Max: {
      // The first objective other than the capped one decides among the points within the cap.
      const std::size_t by = column == 0 ? 1 : 0;
      double smallest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < points.size(); ++k) {
        smallest = std::min(smallest, points[k][column]);
        if (points[k][column] > rule.cap) continue;
        if (!best || points[k][by] < points[*best][by]) best = k;
      }
      if (!best) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "no point has %s <= %.6g (the smallest is %.6g)",
                      rule.objective.c_str(), rule.cap, smallest);
        error = buf;
      }
      break;
    }
  }
  return best;
}

double hypervolume(const std::vector<std::vector<double>>& points,
                   const std::vector<double>& reference) {
  std::vector<pagmo::vector_double> inside;
  for (const auto& p : points) {
    bool strictly = p.size() == reference.size();
    for (std::size_t i = 0; strictly && i < p.size(); ++i)
      strictly = p[i] < reference[i];
    if (strictly) inside.push_back(p);
  }
  if (inside.empty()) return 0.0;
  const pagmo::hypervolume hv(inside, false);
  return hv.compute(reference);
}

std::vector<double> common_reference(const std::vector<std::vector<std::vector<double>>>& fronts) {
  std::vector<double> lo, hi;
  for (const auto& front : fronts)
    for (const auto& p : front) {
      if (lo.empty()) {
        lo = p;
        hi = p;
      }
      for (std::size_t i = 0; i < p.size() && i < lo.size(); ++i) {
        lo[i] = std::min(lo[i], p[i]);
        hi[i] = std::max(hi[i], p[i]);
      }
    }
  std::vector<double> ref(hi.size());
  for (std::size_t i = 0; i < hi.size(); ++i)
    ref[i] = hi[i] + (hi[i] > lo[i] ? 0.1 * (hi[i] - lo[i]) : 1.0);
  return ref;
}

}  // namespace fuzzypid::tune
