// supervisor::RuleTable as .fll, .fcl and .fis text (see rule_table_export.hpp for the construction).
#include "fuzzypid/rulefile/rule_table_export.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace fuzzypid::rulefile {
namespace {

using Table = supervisor::RuleTable<double>;
constexpr std::size_t kSets = 7;
constexpr const char* kSetNames[kSets] = {"NB", "NM", "NS", "ZO", "PS", "PM", "PB"};
constexpr const char* kOutputNames[3] = {"dKp", "dKi", "dKd"};
constexpr const char* kGainNames[3] = {"Kp", "Ki", "Kd"};

// The shortest %g form that reads back as x (at most 17 digits).
std::string number(double x) {
  char buf[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

enum class Format { Fll, Fcl, Fis };

// One output's constant terms: the distinct cell ratios of block 1 (value T - 1), ascending,
// and block 2's ramp scale s (a power of two >= max(1, max T)).
struct OutputTerms {
  std::vector<double> ratios;
  double scale = 1.0;
  bool ramp = false;  // R != 1
};

OutputTerms output_terms(const Table& t, std::size_t g) {
  OutputTerms o;
  double t_max = 0.0;
  for (const auto& row : t.table[g])
    for (const double v : row) {
      if (std::find(o.ratios.begin(), o.ratios.end(), v) == o.ratios.end()) o.ratios.push_back(v);
      t_max = std::max(t_max, v);
    }
  while (o.scale < t_max)
    o.scale *= 2.0;
  o.ramp = t.schedule_ratio[g] != 1.0;
  return o;
}

// "ramp" or "ramp_x<s>", with s spelled as ratio_term_name spells a number (2^60 has an exponent:
// ramp_x1_152921504606846976e18, an identifier every reader takes).
std::string ramp_term_name(double scale) {
  return scale == 1.0 ? "ramp" : "ramp_" + ratio_term_name(scale);
}

// The header comment: what the inputs, outputs and term names mean.
std::string header(const Table& t, const std::array<OutputTerms, 3>& terms, const char* c) {
  std::string s;
  const auto line = [&](const std::string& text) { s += std::string(c) + text + "\n"; };
  line("fuzzypid fuzzy-rules supervisor (supervisor::RuleTable): a rule table refining the gain");
  line("schedule K = K0 (1 + (R - 1) min(1, |x| + |y|)) of the `scheduled` family.");
  line(
      "Inputs (dimensionless universe units): e = Ke * error, ec = Kec * error rate, where Ke and");
  line("Kec are the controller's error_scale and error_rate_scale (e.g. per rad, per rad/s). Sets");
  line("NB..PB: triangles between neighbouring centers, NB and PB shoulders (degree 1 beyond the");
  line("outermost center: the input saturates); neg + pos = min(1, |input|).");
  line("Outputs: dK = K / K0 - 1 for K = Kp, Ki, Kd, applied with output_scale S = K0 (K = K0 +");
  line("K0 dK). Term xA_B (e.g. x0_85) is the constant 0.85 - 1: in that cell the gain becomes");
  line("0.85 x the schedule's. Block `table` gives the cell ratios alone; block `schedule_ramp`");
  line("adds the schedule's ramp times the cell ratio: `ramp` is the constant (R - 1) s and the");
  line("rule weight is the cell ratio / s (s = 1 unless the term is named ramp_x<s>).");
  line("Weighted sum (no normalisation): the degrees of the four firing cells sum to 1.");
  std::string r = "Large-error ratios R:";
  for (std::size_t g = 0; g < 3; ++g) {
    r += std::string(" R") + (kGainNames[g] + 1) + " = " + number(t.schedule_ratio[g]);
    if (!terms[g].ramp) r += " (no ramp)";
    r += g < 2 ? "," : ".";
  }
  line(r);
  return s;
}

// Membership terms of one input in `f`'s spelling.
std::string input_terms(const std::array<double, kSets>& c, Format f) {
  std::string s;
  const auto term = [&](const std::string& name, const std::string& type,
                        std::initializer_list<double> p) {
    if (f == Format::Fll) {
      s += "  term: " + name + " " + type;
      for (double v : p)
        s += " " + number(v);
    } else {
      s += "  TERM " + name + " := " + type;
      for (double v : p)
        s += " " + number(v);
      s += ";";
    }
    s += "\n";
  };
  term(kSetNames[0], "Ramp", {c[1], c[0]});
  for (std::size_t k = 1; k + 1 < kSets; ++k)
    term(kSetNames[k], "Triangle", {c[k - 1], c[k], c[k + 1]});
  term(kSetNames[kSets - 1], "Ramp", {c[kSets - 2], c[kSets - 1]});
  term("neg", "Ramp", {0.0, -1.0});
  term("pos", "Ramp", {0.0, 1.0});
  return s;
}

// An output's constants: (name, value) in file order.
std::vector<std::pair<std::string, double>> constants(const Table& t, std::size_t g,
                                                      const OutputTerms& o) {
  std::vector<std::pair<std::string, double>> out;
  for (const double r : o.ratios)
    out.emplace_back(ratio_term_name(r), r - 1.0);
  if (o.ramp) out.emplace_back(ramp_term_name(o.scale), (t.schedule_ratio[g] - 1.0) * o.scale);
  return out;
}

std::pair<double, double> range_of(const std::vector<std::pair<std::string, double>>& c) {
  double lo = -1.0, hi = 1.0;
  for (const auto& [name, v] : c) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return {lo, hi};
}

// Whether gain g's table is even in e (T[i][j] = T[6 - i][j]) or in ec (T[i][j] = T[i][6 - j]).
bool even(const Table& t, std::size_t g, bool in_e) {
  for (std::size_t i = 0; i < kSets; ++i)
    for (std::size_t j = 0; j < kSets; ++j)
      if (t.table[g][i][j] != (in_e ? t.table[g][kSets - 1 - i][j] : t.table[g][i][kSets - 1 - j]))
        return false;
  return true;
}

// Which inputs' mirrored rules may merge: "(e is NB or e is PB)" fires mu_NB + mu_PB, and the
// two never both hold (their supports lie on either side of 0), so under Maximum or BoundedSum
// the merged rule fires exactly what the one of the pair that holds would: exact, and fewer rules.
struct Mirror {
  bool e = false;
  bool ec = false;
};

// The proposition on `var` for set i, or for the pair i, 6 - i when mirrored (i < 3).
std::string proposition(const char* var, std::size_t i, bool mirrored) {
  const std::string v = std::string(var) + " is ";
  if (!mirrored || i == kSets / 2) return v + kSetNames[i];
  return "(" + v + kSetNames[i] + " or " + v + kSetNames[kSets - 1 - i] + ")";
}

// Calls f(i, j) for every cell, or for one representative (i <= 3, j <= 3) of each mirrored group.
template <class F>
void for_each_cell(const Mirror& m, F f) {
  for (std::size_t i = 0; i < (m.e ? kSets / 2 + 1 : kSets); ++i)
    for (std::size_t j = 0; j < (m.ec ? kSets / 2 + 1 : kSets); ++j)
      f(i, j);
}

std::string cell_antecedent(std::size_t i, std::size_t j, const Mirror& m) {
  return "if " + proposition("e", i, m.e) + " and " + proposition("ec", j, m.ec);
}

// Block 1's rules, without keyword or terminator: one per cell (or mirrored group).
std::vector<std::string> table_rules(const Table& t, const Mirror& m) {
  std::vector<std::string> rules;
  for_each_cell(m, [&](std::size_t i, std::size_t j) {
    std::string s = cell_antecedent(i, j, m) + " then ";
    for (std::size_t g = 0; g < 3; ++g) {
      if (g > 0) s += " and ";
      s += std::string(kOutputNames[g]) + " is " + ratio_term_name(t.table[g][i][j]);
    }
    rules.push_back(std::move(s));
  });
  return rules;
}

// Block 2's rules for gain g.
std::vector<std::string> ramp_rules(const Table& t, std::size_t g, const OutputTerms& o,
                                    const Mirror& m) {
  std::vector<std::string> rules;
  for_each_cell(m, [&](std::size_t i, std::size_t j) {
    rules.push_back(cell_antecedent(i, j, m) +
                    " and (e is neg or e is pos or ec is neg or ec is pos) then " +
                    kOutputNames[g] + " is " + ramp_term_name(o.scale) + " with " +
                    number(t.table[g][i][j] / o.scale));
  });
  return rules;
}

// Block 1 merges along an input when all three tables are even in it (its rules conclude on all
// three outputs); block 2's rules of gain g when T_g is.
Mirror table_mirror(const Table& t) {
  Mirror m{true, true};
  for (std::size_t g = 0; g < 3; ++g) {
    m.e = m.e && even(t, g, true);
    m.ec = m.ec && even(t, g, false);
  }
  return m;
}

bool check(const Table& t, std::string& error) {
  if (!t.valid()) {
    error =
        "the rule table is not valid (centers must be finite, ascending and symmetric about 0; "
        "ratios R and T finite and > 0)";
    return false;
  }
  // The readers evaluate in float too (fuzzypid's fixed-capacity engine, fuzzylite's scalar): a
  // cell beyond FLT_MAX, or a ramp term (R - 1) s beyond it, would be infinite there.
  for (std::size_t g = 0; g < 3; ++g)
    for (std::size_t i = 0; i < kSets; ++i)
      for (std::size_t j = 0; j < kSets; ++j)
        if (t.table[g][i][j] > static_cast<double>(FLT_MAX)) {
          error = std::string("rule table ") + kGainNames[g] + " cell [" + std::to_string(i) +
                  "][" + std::to_string(j) + "] (e " + kSetNames[i] + ", ec " + kSetNames[j] +
                  ") is " + number(t.table[g][i][j]) + ", beyond the float range (" +
                  number(static_cast<double>(FLT_MAX)) + ") of the engines that read the file";
          return false;
        }
  for (std::size_t g = 0; g < 3; ++g) {
    const OutputTerms o = output_terms(t, g);
    const double ramp = (t.schedule_ratio[g] - 1.0) * o.scale;
    if (o.ramp && !(std::fabs(ramp) <= static_cast<double>(FLT_MAX))) {
      error = std::string("rule table ") + kGainNames[g] +
              ": the ramp term (R - 1) s = " + number(ramp) +
              " (R = " + number(t.schedule_ratio[g]) + ") is beyond the float range (" +
              number(static_cast<double>(FLT_MAX)) + ") of the engines that read the file";
      return false;
    }
  }
  return true;
}

std::array<OutputTerms, 3> all_terms(const Table& t) {
  return {output_terms(t, 0), output_terms(t, 1), output_terms(t, 2)};
}

bool any_ramp(const std::array<OutputTerms, 3>& terms) {
  return terms[0].ramp || terms[1].ramp || terms[2].ramp;
}

}  // namespace

std::string ratio_term_name(double ratio) {
  std::string s = "x";
  for (const char ch : number(ratio)) {
    if (ch == '.')
      s += '_';
    else if (ch == '-')
      s += 'm';
    else if (ch != '+')
      s += ch;
  }
  return s;
}

bool rule_table_to_fll(const Table& t, std::string& out, std::string& error,
                       const std::string& name) {
  if (!check(t, error)) return false;
  const auto terms = all_terms(t);
  std::string s = header(t, terms, "# ");
  s += "Engine: " + name + "\n";
  const std::array<const std::array<double, kSets>*, 2> centers{&t.e_centers, &t.ec_centers};
  const char* input_names[2] = {"e", "ec"};
  for (std::size_t v = 0; v < 2; ++v) {
    const double c_max = (*centers[v])[kSets - 1];
    s += std::string("InputVariable: ") + input_names[v] +
         "\n  enabled: true\n  range: " + number(-c_max) + " " + number(c_max) +
         "\n  lock-range: false\n";
    s += input_terms(*centers[v], Format::Fll);
  }
  for (std::size_t g = 0; g < 3; ++g) {
    const auto c = constants(t, g, terms[g]);
    const auto [lo, hi] = range_of(c);
    s += std::string("OutputVariable: ") + kOutputNames[g] +
         "\n  enabled: true\n  range: " + number(lo) + " " + number(hi) +
         "\n  lock-range: false\n  aggregation: none\n  defuzzifier: WeightedSum TakagiSugeno\n"
         "  default: nan\n  lock-previous: false\n";
    for (const auto& [term, value] : c)
      s += "  term: " + term + " Constant " + number(value) + "\n";
  }
  const Mirror mirror = table_mirror(t);
  s += std::string("RuleBlock: table\n  enabled: true\n  conjunction: AlgebraicProduct\n") +
       "  disjunction: " + (mirror.e || mirror.ec ? "Maximum" : "none") +
       "\n  implication: none\n  activation: General\n";
  for (const auto& rule : table_rules(t, mirror))
    s += "  rule: " + rule + "\n";
  if (any_ramp(terms)) {
    s += "RuleBlock: schedule_ramp\n  enabled: true\n  conjunction: AlgebraicProduct\n"
         "  disjunction: BoundedSum\n  implication: none\n  activation: General\n";
    for (std::size_t g = 0; g < 3; ++g) {
      if (!terms[g].ramp) continue;
      const Mirror m{even(t, g, true), even(t, g, false)};
      for (const auto& rule : ramp_rules(t, g, terms[g], m))
        s += "  rule: " + rule + "\n";
    }
  }
  out = std::move(s);
  return true;
}

bool rule_table_to_fcl(const Table& t, std::string& out, std::string& error,
                       const std::string& name) {
  if (!check(t, error)) return false;
  const auto terms = all_terms(t);
  // '//' comments: fuzzylite 6's FCL importer strips those (not '(* *)').
  std::string s = header(t, terms, "// ");
  s += "FUNCTION_BLOCK " + name + "\n\nVAR_INPUT\n  e : REAL;\n  ec : REAL;\nEND_VAR\n\n";
  s += "VAR_OUTPUT\n";
  for (const char* o : kOutputNames)
    s += std::string("  ") + o + " : REAL;\n";
  s += "END_VAR\n";
  const std::array<const std::array<double, kSets>*, 2> centers{&t.e_centers, &t.ec_centers};
  const char* input_names[2] = {"e", "ec"};
  for (std::size_t v = 0; v < 2; ++v) {
    const double c_max = (*centers[v])[kSets - 1];
    s += std::string("\nFUZZIFY ") + input_names[v] + "\n";
    s += input_terms(*centers[v], Format::Fcl);
    s += "  RANGE := (" + number(-c_max) + " .. " + number(c_max) + ");\nEND_FUZZIFY\n";
  }
  for (std::size_t g = 0; g < 3; ++g) {
    const auto c = constants(t, g, terms[g]);
    const auto [lo, hi] = range_of(c);
    s += std::string("\nDEFUZZIFY ") + kOutputNames[g] + "\n";
    for (const auto& [term, value] : c)
      s += "  TERM " + term + " := " + number(value) + ";\n";
    s += "  METHOD : COGSS;\n  DEFAULT := nan;\n  RANGE := (" + number(lo) + " .. " + number(hi) +
         ");\nEND_DEFUZZIFY\n";
  }
  const Mirror mirror = table_mirror(t);
  s += "\nRULEBLOCK table\n  AND : PROD;\n";
  if (mirror.e || mirror.ec) s += "  OR : MAX;\n";
  int n = 0;
  for (const auto& rule : table_rules(t, mirror))
    s += "  RULE " + std::to_string(++n) + " : " + rule + ";\n";
  s += "END_RULEBLOCK\n";
  if (any_ramp(terms)) {
    s += "\nRULEBLOCK schedule_ramp\n  AND : PROD;\n  OR : BSUM;\n";
    n = 0;
    for (std::size_t g = 0; g < 3; ++g) {
      if (!terms[g].ramp) continue;
      const Mirror m{even(t, g, true), even(t, g, false)};
      for (const auto& rule : ramp_rules(t, g, terms[g], m))
        s += "  RULE " + std::to_string(++n) + " : " + rule + ";\n";
    }
    s += "END_RULEBLOCK\n";
  }
  s += "\nEND_FUNCTION_BLOCK\n";
  out = std::move(s);
  return true;
}

bool rule_table_to_fis(const Table& t, std::string& out, std::string& error,
                       const std::string& name) {
  if (!check(t, error)) return false;
  const auto terms = all_terms(t);
  if (any_ramp(terms)) {
    error =
        "a .fis file cannot express the schedule's ramp (ratios R other than 1): it has one rule "
        "block and no rule mixing 'and' with 'or'; write .fll or .fcl, or set R = 1";
    return false;
  }
  std::string s = header(t, terms, "% ");
  s += "[System]\nName='" + name +
       "'\nType='sugeno'\nVersion=2.0\nNumInputs=2\nNumOutputs=3\nNumRules=" +
       std::to_string(kSets * kSets) +
       "\nAndMethod='prod'\nOrMethod='max'\nImpMethod='prod'\nAggMethod='sum'\n"
       "DefuzzMethod='wtsum'\n";
  const std::array<const std::array<double, kSets>*, 2> centers{&t.e_centers, &t.ec_centers};
  const char* input_names[2] = {"e", "ec"};
  for (std::size_t v = 0; v < 2; ++v) {
    const auto& c = *centers[v];
    s += "\n[Input" + std::to_string(v + 1) + "]\nName='" + input_names[v] + "'\nRange=[" +
         number(-c[kSets - 1]) + " " + number(c[kSets - 1]) + "]\nNumMFs=" + std::to_string(kSets) +
         "\n";
    // Shoulders as trapezoids with infinite feet (MATLAB has no ramp of fuzzylite's spelling).
    s += std::string("MF1='") + kSetNames[0] + "':'trapmf',[-inf -inf " + number(c[0]) + " " +
         number(c[1]) + "]\n";
    for (std::size_t k = 1; k + 1 < kSets; ++k)
      s += "MF" + std::to_string(k + 1) + "='" + kSetNames[k] + "':'trimf',[" + number(c[k - 1]) +
           " " + number(c[k]) + " " + number(c[k + 1]) + "]\n";
    s += "MF" + std::to_string(kSets) + "='" + kSetNames[kSets - 1] + "':'trapmf',[" +
         number(c[kSets - 2]) + " " + number(c[kSets - 1]) + " inf inf]\n";
  }
  for (std::size_t g = 0; g < 3; ++g) {
    const auto c = constants(t, g, terms[g]);
    const auto [lo, hi] = range_of(c);
    s += "\n[Output" + std::to_string(g + 1) + "]\nName='" + kOutputNames[g] + "'\nRange=[" +
         number(lo) + " " + number(hi) + "]\nNumMFs=" + std::to_string(c.size()) + "\n";
    for (std::size_t k = 0; k < c.size(); ++k)
      s += "MF" + std::to_string(k + 1) + "='" + c[k].first + "':'constant',[" +
           number(c[k].second) + "]\n";
  }
  s += "\n[Rules]\n";
  for (std::size_t i = 0; i < kSets; ++i)
    for (std::size_t j = 0; j < kSets; ++j) {
      s += std::to_string(i + 1) + " " + std::to_string(j + 1) + ",";
      for (std::size_t g = 0; g < 3; ++g) {
        const auto& r = terms[g].ratios;
        const auto k = std::find(r.begin(), r.end(), t.table[g][i][j]) - r.begin();
        s += " " + std::to_string(k + 1);
      }
      s += " (1) : 1\n";
    }
  out = std::move(s);
  return true;
}

}  // namespace fuzzypid::rulefile
