#include "fuzzypid/rulefile/rule_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <tuple>

#include "fuzzypid/fuzzy/engine.hpp"
#include "rules.hpp"
#include "text.hpp"

namespace fuzzypid::rulefile {

namespace {

using fuzzy::Token;

// The bounds scanned for an input: its range, or -10 .. 10 where the file leaves it infinite
// (FCL without RANGE), as the corpus test samples such inputs.
void scan_bounds(const fuzzy::InputSpec<double>& in, double& lo, double& hi) {
  lo = std::isfinite(in.min) ? in.min : -10.0;
  hi = std::isfinite(in.max) ? in.max : 10.0;
  if (!(lo < hi)) hi = lo + 1.0;
}

// Comparable form of an antecedent: the propositions sorted when one connective joins them all
// ("a and b" equals "b and a"), else the postfix sequence as written.
using PropositionKey = std::tuple<int, int, int, std::vector<int>>;
struct AntecedentKey {
  int connective = 0;  // 0: one proposition, 1: all and, 2: all or, 3: mixed (sequence kept)
  std::vector<PropositionKey> items;
  bool operator<(const AntecedentKey& o) const {
    return std::tie(connective, items) < std::tie(o.connective, o.items);
  }
};

AntecedentKey antecedent_key(const Model& m, std::size_t r) {
  const auto& rule = m.rules[r];
  AntecedentKey key;
  for (std::size_t k = 0; k < rule.num_tokens; ++k) {
    const Token& t = m.tokens[rule.first_token + k];
    if (t.kind == Token::Kind::And || t.kind == Token::Kind::Or) {
      const int c = t.kind == Token::Kind::And ? 1 : 2;
      key.connective = key.connective == 0 || key.connective == c ? c : 3;
      key.items.emplace_back(-c, 0, 0, std::vector<int>{});
      continue;
    }
    std::vector<int> hedges;
    for (std::size_t h = 0; h < t.num_hedges; ++h)
      hedges.push_back(static_cast<int>(t.hedges[h]));
    hedges.push_back(1000 + t.power_tenths);  // Octave's power hedge (1000: none)
    key.items.emplace_back(static_cast<int>(t.kind), t.input, t.term, hedges);
  }
  if (key.connective != 3) {
    // One connective: the operands in any order (a left fold of a commutative operator).
    key.items.erase(std::remove_if(key.items.begin(), key.items.end(),
                                   [](const PropositionKey& p) { return std::get<0>(p) < 0; }),
                    key.items.end());
    std::sort(key.items.begin(), key.items.end());
  }
  return key;
}

// The conclusion of rule r on output o: (term, hedges), or term -1 when it has none.
std::pair<int, std::vector<int>> conclusion_on(const Model& m, std::size_t r, std::size_t o) {
  const auto& rule = m.rules[r];
  for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
    const auto& c = m.conclusions[rule.first_conclusion + k];
    if (c.output != o) continue;
    std::vector<int> hedges;
    for (std::size_t h = 0; h < c.num_hedges; ++h)
      hedges.push_back(static_cast<int>(c.hedges[h]));
    hedges.push_back(1000 + c.power_tenths);  // Octave's power hedge (1000: none)
    return {c.term, hedges};
  }
  return {-1, {}};
}

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

std::string point_text(const Model& m, const std::vector<double>& x) {
  std::string s;
  for (std::size_t i = 0; i < x.size(); ++i)
    s += (i ? ", " : "") + std::string(text::name_of(m.inputs[i].name)) + " = " + number(x[i]);
  return s;
}

// Names as the file writes them, for rule text in the report.
rules::ExportNames file_names(const Model& m) {
  rules::ExportNames n;
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    n.inputs.emplace_back(text::name_of(m.inputs[i].name));
    n.input_terms.emplace_back();
    for (std::size_t t = 0; t < m.inputs[i].num_terms; ++t)
      n.input_terms.back().emplace_back(text::name_of(m.inputs[i].term_names[t]));
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    n.outputs.emplace_back(text::name_of(m.outputs[o].name));
    n.output_terms.emplace_back();
    for (std::size_t t = 0; t < m.outputs[o].num_terms; ++t)
      n.output_terms.back().emplace_back(text::name_of(m.outputs[o].term_names[t]));
  }
  return n;
}

}  // namespace

const char* to_string(Monotonicity m) noexcept {
  switch (m) {
    case Monotonicity::Constant:
      return "constant";
    case Monotonicity::Increasing:
      return "increasing (non-decreasing)";
    case Monotonicity::Decreasing:
      return "decreasing (non-increasing)";
    case Monotonicity::NotMonotone:
      return "not monotone";
    case Monotonicity::NeverFires:
      return "fires at fewer than two grid points of any line along the input";
  }
  return "?";
}

RuleCheckReport check_rules(const Model& m, const RuleCheckOptions& options) {
  RuleCheckReport report;
  const std::size_t n = m.num_inputs, n_out = m.num_outputs;
  // Points per axis: as asked, fewer while the whole grid exceeds max_points.
  std::size_t k = std::max<std::size_t>(2, options.points_per_input);
  const auto grid_size = [&](std::size_t per_axis) {
    double total = 1;
    for (std::size_t i = 0; i < n; ++i)
      total *= static_cast<double>(per_axis);
    return total;
  };
  while (k > 2 && grid_size(k) > static_cast<double>(std::max<std::size_t>(options.max_points, 4)))
    --k;
  std::size_t total = 1;
  for (std::size_t i = 0; i < n; ++i)
    total *= k;
  report.points_per_input = k;
  report.grid_points = total;

  std::vector<double> lo(n), span(n);
  for (std::size_t i = 0; i < n; ++i) {
    double hi = 0;
    scan_bounds(m.inputs[i], lo[i], hi);
    span[i] = hi - lo[i];
  }
  std::vector<std::size_t> stride(n, 1);
  for (std::size_t i = 1; i < n; ++i)
    stride[i] = stride[i - 1] * k;
  const auto coordinate = [&](std::size_t index, std::size_t i) {
    // (span * j) / (k - 1): grid points such as 0.6 on [0, 1] come out exact.
    return lo[i] +
           span[i] * static_cast<double>((index / stride[i]) % k) / static_cast<double>(k - 1);
  };
  const auto point = [&](std::size_t index) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i)
      x[i] = coordinate(index, i);
    return x;
  };

  // Which outputs each rule concludes on (a bit per output).
  std::vector<unsigned> concludes(m.num_rules, 0);
  for (std::size_t r = 0; r < m.num_rules; ++r)
    for (std::size_t c = 0; c < m.rules[r].num_conclusions; ++c)
      concludes[r] |= 1u << m.conclusions[m.rules[r].first_conclusion + c].output;

  auto engine = std::make_unique<fuzzy::Engine<double>>(m);
  std::vector<double> values(total * n_out);
  std::vector<unsigned> fired(total, 0);
  std::vector<double> x(n);
  for (std::size_t index = 0; index < total; ++index) {
    for (std::size_t i = 0; i < n; ++i)
      x[i] = coordinate(index, i);
    (void)engine->evaluate(x.data(), values.data() + index * n_out);
    for (std::size_t r = 0; r < m.num_rules; ++r)
      if (engine->rule_strength(r) > 0) fired[index] |= concludes[r];
  }
  unsigned all = 0;  // the enabled outputs: a disabled one has no value to cover
  for (std::size_t o = 0; o < n_out && o < 32; ++o)
    if (m.outputs[o].enabled) all |= 1u << o;

  // Gaps: connected sets of grid points where some output has no firing rule.
  std::vector<char> seen(total, 0);
  std::vector<std::size_t> queue;
  for (std::size_t start = 0; start < total; ++start) {
    if (seen[start] || (fired[start] & all) == all) continue;
    CoverageGap gap;
    gap.min.assign(n, INFINITY);
    gap.max.assign(n, -INFINITY);
    unsigned missing = 0;
    queue.assign(1, start);
    seen[start] = 1;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::size_t index = queue[q];
      missing |= all & ~fired[index];
      for (std::size_t i = 0; i < n; ++i) {
        const double c = coordinate(index, i);
        gap.min[i] = std::min(gap.min[i], c);
        gap.max[i] = std::max(gap.max[i], c);
        const std::size_t j = (index / stride[i]) % k;
        const std::size_t neighbours[2] = {j > 0 ? index - stride[i] : index,
                                           j + 1 < k ? index + stride[i] : index};
        for (const std::size_t next : neighbours)
          if (!seen[next] && (fired[next] & all) != all) {
            seen[next] = 1;
            queue.push_back(next);
          }
      }
    }
    gap.points = queue.size();
    // The example: the box's grid point nearest its center.
    double best = INFINITY;
    for (const std::size_t index : queue) {
      double d = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double span = gap.max[i] - gap.min[i];
        const double u =
            span > 0 ? (coordinate(index, i) - (gap.min[i] + gap.max[i]) / 2) / span : 0;
        d += u * u;
      }
      if (d < best) {
        best = d;
        gap.example = point(index);
      }
    }
    for (std::size_t o = 0; o < n_out; ++o)
      if (missing & (1u << o)) gap.outputs.push_back(o);
    report.gaps.push_back(std::move(gap));
  }

  // Repeated and contradictory rules.
  std::map<AntecedentKey, std::vector<std::size_t>> by_antecedent;
  for (std::size_t r = 0; r < m.num_rules; ++r)
    by_antecedent[antecedent_key(m, r)].push_back(r);
  for (const auto& entry : by_antecedent) {
    const auto& group = entry.second;
    for (std::size_t a = 0; a < group.size(); ++a)
      for (std::size_t b = a + 1; b < group.size(); ++b) {
        RulePair pair{group[a], group[b], false, 0};
        bool common = false;
        for (std::size_t o = 0; o < n_out && !pair.contradiction; ++o) {
          const auto ca = conclusion_on(m, pair.first, o), cb = conclusion_on(m, pair.second, o);
          if (ca.first < 0 || cb.first < 0) continue;
          common = true;
          if (ca != cb) {
            pair.contradiction = true;
            pair.output = o;
          }
        }
        if (common) report.pairs.push_back(pair);
      }
  }
  std::sort(report.pairs.begin(), report.pairs.end(), [](const RulePair& a, const RulePair& b) {
    return std::tie(a.first, a.second) < std::tie(b.first, b.second);
  });

  // Monotonicity of each output along each input: successive grid points of a line along the
  // input (the others fixed) where the output fired, across the points where it did not.
  for (std::size_t o = 0; o < n_out; ++o) {
    const auto& out = m.outputs[o];
    const double scale =
        std::isfinite(out.max - out.min) && out.max > out.min ? out.max - out.min : 1.0;
    const double tolerance = 1e-9 * scale;
    for (std::size_t i = 0; i < n; ++i) {
      MonotonicityFinding f;
      f.output = o;
      f.input = i;
      bool compared = false, rise = false, fall = false;
      for (std::size_t start = 0; start < total; ++start) {
        if ((start / stride[i]) % k != 0) continue;  // one line per start on the input's axis
        std::size_t last = total;                    // the previous point that fired
        for (std::size_t j = 0; j < k; ++j) {
          const std::size_t index = start + j * stride[i];
          if (!(fired[index] & (1u << o))) continue;
          if (last != total) {
            compared = true;
            const double d = values[index * n_out + o] - values[last * n_out + o];
            if (d > tolerance && !rise) {
              rise = true;
              f.rise_at = point(last);
            } else if (d < -tolerance && !fall) {
              fall = true;
              f.fall_at = point(last);
            }
          }
          last = index;
        }
      }
      f.kind = !compared      ? Monotonicity::NeverFires
               : rise && fall ? Monotonicity::NotMonotone
               : rise         ? Monotonicity::Increasing
               : fall         ? Monotonicity::Decreasing
                              : Monotonicity::Constant;
      report.monotonicity.push_back(f);
    }
  }
  return report;
}

std::string to_text(const Model& m, const RuleCheckReport& report) {
  const rules::ExportNames names = file_names(m);
  const auto output_name = [&](std::size_t o) { return "'" + names.outputs[o] + "'"; };
  std::string s;
  std::string grid;
  for (std::size_t i = 0; i < m.num_inputs; ++i)
    grid += (i ? " x " : "") + std::to_string(report.points_per_input);
  s += "rule base: " + std::to_string(m.num_inputs) + " input(s), " +
       std::to_string(m.num_outputs) + " output(s), " + std::to_string(m.num_rules) +
       " rule(s); grid " + grid + " (" + std::to_string(report.grid_points) +
       " points over the input ranges)\n";

  constexpr std::size_t kMaxListed = 20;
  if (report.gaps.empty()) {
    s += "coverage: a rule fires for every output at every grid point\n";
  } else {
    s += "coverage: " + std::to_string(report.gaps.size()) +
         " region(s) where no rule fires for some output\n";
    for (std::size_t g = 0; g < report.gaps.size() && g < kMaxListed; ++g) {
      const auto& gap = report.gaps[g];
      s += "  gap " + std::to_string(g + 1) + ": ";
      for (std::size_t i = 0; i < m.num_inputs; ++i)
        s += (i ? ", " : "") + names.inputs[i] + " in [" + number(gap.min[i]) + ", " +
             number(gap.max[i]) + "]";
      s += " (" + std::to_string(gap.points) + " grid point(s), e.g. " +
           point_text(m, gap.example) + "); no rule for";
      for (std::size_t k = 0; k < gap.outputs.size(); ++k)
        s += (k ? ", " : " ") + output_name(gap.outputs[k]);
      s += "\n";
    }
    if (report.gaps.size() > kMaxListed)
      s += "  ... and " + std::to_string(report.gaps.size() - kMaxListed) + " more\n";
  }

  std::size_t repeats = 0, contradictions = 0;
  for (const auto& p : report.pairs)
    (p.contradiction ? contradictions : repeats) += 1;
  s += "rules: " + std::to_string(repeats) + " repeated pair(s), " +
       std::to_string(contradictions) + " contradictory pair(s)\n";
  std::size_t listed = 0;
  for (const auto& p : report.pairs) {
    if (listed++ == kMaxListed) {
      s += "  ... and " + std::to_string(report.pairs.size() - kMaxListed) + " more\n";
      break;
    }
    s += std::string(p.contradiction ? "  contradiction: " : "  repeat: ") + "rule " +
         std::to_string(p.first + 1) + " and rule " + std::to_string(p.second + 1) +
         (p.contradiction
              ? " conclude differently on " + output_name(p.output) + " from the same antecedent"
              : " have the same antecedent and conclusions") +
         "\n    rule " + std::to_string(p.first + 1) + ": " + rules::write_rule(m, p.first, names) +
         "\n    rule " + std::to_string(p.second + 1) + ": " +
         rules::write_rule(m, p.second, names) + "\n";
  }

  s += "monotonicity (successive grid points along each input where rules fire):\n";
  for (const auto& f : report.monotonicity) {
    s += "  " + output_name(f.output) + " in '" + names.inputs[f.input] + "': " + to_string(f.kind);
    if (f.kind == Monotonicity::NotMonotone)
      s += " (rises after " + point_text(m, f.rise_at) + "; falls after " +
           point_text(m, f.fall_at) + ")";
    s += "\n";
  }
  return s;
}

}  // namespace fuzzypid::rulefile
