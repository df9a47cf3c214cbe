// The rule-file corpus (tests/rulefile/data/corpus/: MATLAB, MATLAB 1.x, Octave, fuzzylite and
// IEC 61131-7 files as their users write them) against fuzzylite 6's own importers:
//   - every file loads, except those named refuse_*, which must be refused with file, line and
//     the construct;
//   - on sampled inputs (ranges widened by 10 %), every output equals fuzzylite's within 1e-9
//     (fuzzylite's "no value" NaN is 0 with Status::NoRuleFired here), except in files named
//     fuzzylite8_*: they use constructs fuzzylite 6 cannot read (Arc, SemiEllipse, formulas of
//     fuzzylite 8) or mean what fuzzylite 8 computes (grouped weighted outputs), and only the
//     fuzzylite 8 oracle (check_fuzzylite8.py) compares them;
//   - our .fll, .fcl and (where expressible) .fis exports load back to the same outputs, and
//     fuzzylite reading our .fll export gives the same outputs too;
//   - evaluation allocates nothing (global operator new counted around every call).
// Where fuzzylite reads a MATLAB file differently from MATLAB, the oracle gets the file in the
// form fuzzylite understands (documented in docs/rule_files.md): MATLAB 1.x zero padding is
// removed (fuzzylite would take the first pad as the term's height, 0), linsmf/linzmf become
// fuzzylite's rampmf, FCL rule keywords are lower-cased and a RULEBLOCK's ACCU moves into the
// DEFUZZIFY blocks (fuzzylite reads neither), (* *) comments are removed.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid_support/counting_new.hpp"

namespace {

namespace fs = std::filesystem;
using fuzzypid::Status;
using fuzzypid::rulefile::LoadError;
using fuzzypid::rulefile::Model;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string ext(const fs::path& p) {
  return p.extension().string();
}

// MATLAB 1.x padding and MATLAB-only names, rewritten for fuzzylite's FisImporter.
std::string fis_for_fuzzylite(const std::string& text) {
  static const std::map<std::string, std::size_t> count = {
      {"trimf", 3},  {"trapmf", 4},   {"gaussmf", 2}, {"gauss2mf", 4}, {"gbellmf", 3},
      {"pimf", 4},   {"smf", 2},      {"zmf", 2},     {"sigmf", 2},    {"dsigmf", 4},
      {"psigmf", 4}, {"constant", 1}, {"linzmf", 2},  {"linsmf", 2}};
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  const std::regex mf(R"(^(\s*MF\d+\s*=\s*'[^']*'\s*:\s*')([a-z0-9]+)('\s*,\s*\[)([^\]]*)(\].*)$)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, mf)) {
      std::string type = m[2];
      std::istringstream ps(m[4].str());
      std::vector<std::string> p;
      for (std::string w; ps >> w;)
        p.push_back(w);
      const auto it = count.find(type);
      if (it != count.end())
        while (p.size() > it->second && std::stod(p.back()) == 0.0)
          p.pop_back();
      if (type == "linzmf" || type == "linsmf") {
        if (type == "linzmf") std::swap(p[0], p[1]);
        type = "rampmf";
      }
      std::string joined;
      for (const auto& w : p)
        joined += (joined.empty() ? "" : " ") + w;
      line = m[1].str() + type + m[3].str() + joined + m[5].str();
    }
    out << line << "\n";
  }
  return out.str();
}

std::string fcl_for_fuzzylite(std::string text) {
  text = std::regex_replace(text, std::regex(R"(\(\*[\s\S]*?\*\))"), "");
  std::istringstream in(text);
  std::ostringstream out;
  std::string line, block_accu;
  std::vector<std::string> lines;
  while (std::getline(in, line))
    lines.push_back(line);
  bool in_rules = false, in_defuzz = false, defuzz_has_accu = false;
  std::vector<std::string> result;
  std::vector<std::size_t> defuzz_ends_without_accu;
  for (const auto& l0 : lines) {
    std::string l = l0;
    if (std::regex_search(l, std::regex(R"(^\s*RULEBLOCK)"))) in_rules = true;
    if (std::regex_search(l, std::regex(R"(^\s*END_RULEBLOCK)"))) in_rules = false;
    if (std::regex_search(l, std::regex(R"(^\s*DEFUZZIFY)"))) {
      in_defuzz = true;
      defuzz_has_accu = false;
    }
    if (in_defuzz && std::regex_search(l, std::regex(R"(^\s*(ACCU|METHOD\s*:\s*COGS))")))
      defuzz_has_accu = true;
    if (std::regex_search(l, std::regex(R"(^\s*END_DEFUZZIFY)"))) {
      in_defuzz = false;
      if (!defuzz_has_accu) defuzz_ends_without_accu.push_back(result.size());
    }
    if (in_rules && std::regex_search(l, std::regex(R"(^\s*ACCU\s*:)"))) {
      block_accu = l;
      continue;
    }
    if (in_rules && std::regex_search(l, std::regex(R"(^\s*RULE\s)"))) {
      static const char* const words[][2] = {{"IF", "if"},  {"IS", "is"},     {"AND", "and"},
                                             {"OR", "or"},  {"THEN", "then"}, {"WITH", "with"},
                                             {"NOT", "not"}};
      for (const auto& w : words)
        l = std::regex_replace(l, std::regex(std::string("\\b") + w[0] + "\\b"), w[1]);
      l = std::regex_replace(l, std::regex(R"(\s*;\s*$)"), "");
    }
    result.push_back(l);
  }
  if (!block_accu.empty())
    for (auto it = defuzz_ends_without_accu.rbegin(); it != defuzz_ends_without_accu.rend(); ++it)
      result.insert(result.begin() + static_cast<long>(*it), block_accu);
  for (const auto& l : result)
    out << l << "\n";
  return out.str();
}

std::unique_ptr<fl::Engine> fuzzylite_import(const std::string& extension,
                                             const std::string& text) {
  fl::fuzzylite::setMachEps(1e-6);  // the importers' default (FisImporter decodes hedges with it)
  std::unique_ptr<fl::Engine> e;
  if (extension == ".fis") e.reset(fl::FisImporter().fromString(fis_for_fuzzylite(text)));
  if (extension == ".fll") e.reset(fl::FllImporter().fromString(text));
  if (extension == ".fcl") e.reset(fl::FclImporter().fromString(fcl_for_fuzzylite(text)));
  fl::fuzzylite::setMachEps(0.0);
  return e;
}

struct Comparison {
  double max_diff = 0;
  std::size_t points = 0;
  std::size_t allocations = 0;
  std::size_t skipped = 0;  // output values not compared: fuzzylite 6's known defects
};

// Where fuzzylite 6 and fuzzylite 8 disagree we follow fuzzylite 8 (and MATLAB), so fuzzylite 6 is
// no oracle there (docs/rule_files.md, "fuzzylite 6 and fuzzylite 8"); these cases are skipped:
//  - a Tsukamoto output (weighted defuzzifier over membership terms) with a Concave, SShape or
//    ZShape term or a term of height other than 1: fuzzylite 6's inverses miss mu(z) = w there;
//  - a mean of maximum whose maximising samples are not one run (two or more plateaus at the
//    maximum): fuzzylite 6 takes the middle of the first plateau, fuzzylite 8 and MATLAB the
//    mean of all of them.
//  - a Bisector: fuzzylite 8 takes the sample where the running area is nearest half, fuzzylite 6
//    interpolates between two fronts swept from both ends (they agree only by chance);
//  - a weighted output that groups its activations by term (OutputSpec::group_by_term: Tsukamoto,
//    or an aggregation that is not a sum): fuzzylite 6 weighs every activation.
bool fuzzylite6_tsukamoto_differs(const Model& model, std::size_t o) {
  using fuzzypid::fuzzy::OutputTermKind;
  using fuzzypid::fuzzy::Shape;
  const auto& out = model.outputs[o];
  if (!fuzzypid::fuzzy::is_sugeno(out.defuzzifier)) return false;
  for (std::size_t t = 0; t < out.num_terms; ++t) {
    const auto& term = out.terms[t];
    if (term.kind != OutputTermKind::Membership) continue;
    const Shape s = term.membership.shape;
    if (s == Shape::Concave || s == Shape::SShape || s == Shape::ZShape ||
        term.membership.height != 1.0)
      return true;
  }
  return false;
}

// A .fis as Octave computes it (docs/rule_files.md, ".fis hedges and Sugeno aggregation as
// Octave computes them"): fuzzylite reads the hedge codes .3 and .01 as `extremely` and `seldom`
// (Octave: mu^3, mu^0.1), hedges a Sugeno conclusion's degree (Octave: w^(1/p), for that
// conclusion only) and ignores AggMethod under a weighted defuzzifier (Octave merges equal
// singletons with it). An output is skipped when it merges, or a rule with a power hedge
// concludes on it.
bool octave_differs(const Model& model, std::size_t o) {
  if (model.outputs[o].merge_equal_singletons) return true;
  for (std::size_t r = 0; r < model.num_rules; ++r) {
    const auto& rule = model.rules[r];
    bool power = false, on_o = false;
    for (std::size_t k = 0; k < rule.num_tokens; ++k)
      power = power || model.tokens[rule.first_token + k].power_tenths != 0;
    for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
      const auto& c = model.conclusions[rule.first_conclusion + k];
      power = power || c.power_tenths != 0;
      on_o = on_o || c.output == o;
    }
    if (power && on_o) return true;
  }
  return false;
}

bool fuzzylite6_mean_of_maximum_differs(const Model& model, std::size_t o, fl::Engine& oracle) {
  const auto& out = model.outputs[o];
  if (out.defuzzifier != fuzzypid::fuzzy::Defuzzifier::MeanOfMaximum) return false;
  const fl::OutputVariable* v = oracle.getOutputVariable(o);
  const double dx = (out.max - out.min) / out.resolution;
  double y_max = 0.0;
  for (int i = 0; i < out.resolution; ++i)
    y_max = std::max(y_max, v->fuzzyOutput()->membership(out.min + (i + 0.5) * dx));
  int runs = 0;
  bool in_run = false;
  for (int i = 0; i < out.resolution; ++i) {
    const bool at_max = v->fuzzyOutput()->membership(out.min + (i + 0.5) * dx) == y_max;
    runs += at_max && !in_run;
    in_run = at_max;
  }
  return runs > 1;
}

// Our model and fuzzylite's engine on `n` sampled input vectors (fuzzylite 6's known defects
// skipped, above).
Comparison compare(const Model& model, fl::Engine& oracle, int n, std::uint64_t seed) {
  Comparison c;
  fuzzypid::fuzzy::Engine<double>* engine = new fuzzypid::fuzzy::Engine<double>(model);
  EXPECT_EQ(oracle.numberOfInputVariables(), model.num_inputs);
  EXPECT_EQ(oracle.numberOfOutputVariables(), model.num_outputs);
  std::mt19937_64 rng(seed);
  std::vector<double> in(model.num_inputs), out(model.num_outputs);
  for (int k = 0; k < n; ++k) {
    for (std::size_t i = 0; i < model.num_inputs; ++i) {
      const auto& v = model.inputs[i];
      const double lo = std::isfinite(v.min) ? v.min : -10, hi = std::isfinite(v.max) ? v.max : 10;
      const double margin = 0.1 * (hi - lo);
      // Every 4th point on a grid corner/edge, the others uniform.
      const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
      in[i] = (k % 4 == 0) ? lo + (hi - lo) * static_cast<double>((k / 4) % 11) / 10.0
                           : lo - margin + (hi - lo + 2 * margin) * u;
      oracle.getInputVariable(i)->setValue(in[i]);
    }
    oracle.process();
    const std::size_t before = fuzzypid::support::allocation_count();
    const Status s = engine->evaluate(in.data(), out.data());
    c.allocations += fuzzypid::support::allocation_count() - before;
    EXPECT_FALSE(fuzzypid::is_fault(s));
    ++c.points;
    for (std::size_t o = 0; o < model.num_outputs; ++o) {
      const double expected = oracle.getOutputVariable(o)->getValue();
      if (fuzzylite6_tsukamoto_differs(model, o) || octave_differs(model, o) ||
          model.outputs[o].group_by_term ||
          model.outputs[o].defuzzifier == fuzzypid::fuzzy::Defuzzifier::Bisector ||
          fuzzylite6_mean_of_maximum_differs(model, o, oracle)) {
        ++c.skipped;
        continue;
      }
      if (std::isnan(expected)) {
        EXPECT_EQ(s, Status::NoRuleFired);
        EXPECT_EQ(out[o], 0.0);
        continue;
      }
      const double diff = std::fabs(out[o] - expected);
      c.max_diff = std::max(c.max_diff, diff);
      if (!(diff <= 1e-9)) {
        ADD_FAILURE() << "output " << o << " at point " << k << ": ours " << out[o]
                      << ", fuzzylite " << expected;
        delete engine;
        return c;
      }
    }
  }
  delete engine;
  return c;
}

// Our engine on two models: identical outputs and statuses.
double self_compare(const Model& a, const Model& b, std::uint64_t seed) {
  auto* ea = new fuzzypid::fuzzy::Engine<double>(a);
  auto* eb = new fuzzypid::fuzzy::Engine<double>(b);
  std::mt19937_64 rng(seed);
  std::vector<double> in(a.num_inputs), oa(a.num_outputs), ob(a.num_outputs);
  double worst = 0;
  for (int k = 0; k < 300; ++k) {
    for (std::size_t i = 0; i < a.num_inputs; ++i) {
      const auto& v = a.inputs[i];
      const double lo = std::isfinite(v.min) ? v.min : -10, hi = std::isfinite(v.max) ? v.max : 10;
      in[i] = lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
    }
    EXPECT_EQ(ea->evaluate(in.data(), oa.data()), eb->evaluate(in.data(), ob.data()));
    for (std::size_t o = 0; o < a.num_outputs; ++o)
      worst = std::max(worst, std::fabs(oa[o] - ob[o]));
  }
  delete ea;
  delete eb;
  return worst;
}

TEST(RuleFileCorpus, LoadsAndEqualsFuzzyliteOnEveryFile) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(FUZZYPID_CORPUS_DIR))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 40u);
  std::size_t loaded = 0, refused = 0, points = 0, allocations = 0, skipped = 0;
  double worst = 0;
  std::string worst_file;
  std::uint64_t seed = 1;
  for (const fs::path& path : files) {
    SCOPED_TRACE(path.filename().string());
    const std::string name = path.filename().string();
    const std::string text = read(path);
    auto model = std::make_unique<Model>();
    LoadError error;
    const bool ok = fuzzypid::rulefile::load_rule_file(path.string(), *model, error);
    if (name.rfind("refuse_", 0) == 0) {
      EXPECT_FALSE(ok) << "expected a refusal";
      EXPECT_GT(error.line, 0) << error.to_string();
      std::cout << "  refused  " << error.to_string().substr(error.to_string().find(name)) << "\n";
      ++refused;
      continue;
    }
    ASSERT_TRUE(ok) << error.to_string();
    ++loaded;
    const bool fuzzylite6_reads = name.rfind("fuzzylite8_", 0) != 0;
    if (fuzzylite6_reads) {
      auto oracle = fuzzylite_import(ext(path), text);
      ASSERT_TRUE(oracle);
      std::string status;
      ASSERT_TRUE(oracle->isReady(&status)) << status;
      const Comparison c = compare(*model, *oracle, 2000, seed++);
      points += c.points;
      allocations += c.allocations;
      skipped += c.skipped;
      if (c.max_diff > worst) {
        worst = c.max_diff;
        worst_file = name;
      }
      std::cout << "  loaded   " << name << ": " << c.points
                << " points, max |ours - fuzzylite| = " << c.max_diff;
      if (c.skipped > 0)
        std::cout << " (" << c.skipped
                  << " values skipped: fuzzylite 6 is not the reference there)";
      std::cout << "\n";
    } else {
      std::cout << "  loaded   " << name << ": fuzzylite 8 only (check_fuzzylite8.py)\n";
    }

    // Round trips through our three writers, and fuzzylite reading our .fll.
    std::string fll, fcl, fis, why;
    auto again = std::make_unique<Model>();
    if (fuzzypid::rulefile::to_fll(*model, fll, why)) {
      ASSERT_TRUE(fuzzypid::rulefile::parse_fll(fll, "export.fll", *again, error))
          << error.to_string() << "\n"
          << fll;
      EXPECT_EQ(self_compare(*model, *again, seed), 0.0) << "via .fll";
      if (fuzzylite6_reads) {
        auto fl_again = fuzzylite_import(".fll", fll);
        ASSERT_TRUE(fl_again);
        const Comparison d = compare(*model, *fl_again, 300, seed++);
        EXPECT_LE(d.max_diff, 1e-9) << "fuzzylite on our .fll";
      }
    } else {
      // Only what a .fis means beyond fuzzylite 8 has no .fll form: Octave's constructs, and
      // Tsukamoto read per activation (fuzzylite 6, the one reader of Tsukamoto .fis files).
      EXPECT_TRUE(why.find("Octave's") != std::string::npos ||
                  why.find("a .fis read as fuzzylite 6 reads it") != std::string::npos)
          << why;
      std::cout << "    (.fll export: " << why << ")\n";
    }
    if (fuzzypid::rulefile::to_fcl(*model, fcl, why)) {
      ASSERT_TRUE(fuzzypid::rulefile::parse_fcl(fcl, "export.fcl", *again, error))
          << error.to_string() << "\n"
          << fcl;
      EXPECT_EQ(self_compare(*model, *again, seed), 0.0) << "via .fcl";
    } else {
      std::cout << "    (.fcl export: " << why << ")\n";
    }
    if (fuzzypid::rulefile::to_fis(*model, fis, why)) {
      ASSERT_TRUE(fuzzypid::rulefile::parse_fis(fis, "export.fis", *again, error))
          << error.to_string() << "\n"
          << fis;
      EXPECT_EQ(self_compare(*model, *again, seed), 0.0) << "via .fis";
    } else {
      std::cout << "    (.fis export: " << why << ")\n";
    }
  }
  std::cout
      << "corpus: " << loaded << " of " << files.size() << " files load ("
      << 100.0 * static_cast<double>(loaded) / static_cast<double>(files.size()) << " %), "
      << refused << " refused with a message; " << points
      << " points, largest |ours - fuzzylite| = " << worst << " (" << worst_file << "); "
      << allocations << " allocations in our evaluations; " << skipped
      << " output values skipped where fuzzylite 6 is not the reference (fuzzylite 8, Octave)\n";
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
