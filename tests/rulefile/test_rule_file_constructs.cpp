// The constructs fuzzylite 6 reads beyond MATLAB's (chained outputs, hybrid and Tsukamoto .fis,
// lock-previous / NC, zero-width unused ranges, empty methods, the Enabled key) as specifications
// of the engine and the readers, and the two places where fuzzylite's .fis importer departs from
// MATLAB (docs/rule_files.md, "Where fuzzylite differs"), each shown against fuzzylite itself.
// The corpus comparison (tests/rulefile/test_corpus.cpp) checks the same files point by point.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/supervisor/engine_supervisor.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::Engine;
using fuzzypid::rulefile::LoadError;
using fuzzypid::rulefile::Model;

std::unique_ptr<Model> load(const std::string& name, const std::string& text) {
  auto model = std::make_unique<Model>();
  LoadError error;
  const std::string ext = name.substr(name.rfind('.'));
  const bool ok = ext == ".fis"   ? fuzzypid::rulefile::parse_fis(text, name, *model, error)
                  : ext == ".fll" ? fuzzypid::rulefile::parse_fll(text, name, *model, error)
                                  : fuzzypid::rulefile::parse_fcl(text, name, *model, error);
  EXPECT_TRUE(ok) << error.to_string();
  return ok ? std::move(model) : nullptr;
}

LoadError refusal(const std::string& name, const std::string& text) {
  auto model = std::make_unique<Model>();
  LoadError error;
  const std::string ext = name.substr(name.rfind('.'));
  const bool ok = ext == ".fis"   ? fuzzypid::rulefile::parse_fis(text, name, *model, error)
                  : ext == ".fll" ? fuzzypid::rulefile::parse_fll(text, name, *model, error)
                                  : fuzzypid::rulefile::parse_fcl(text, name, *model, error);
  EXPECT_FALSE(ok);
  return error;
}

std::string corpus_file(const std::string& name) {
  std::ifstream in(FUZZYPID_RULEFILES_DIR "/corpus/" + name);
  std::ostringstream all;
  all << in.rdbuf();
  EXPECT_FALSE(all.str().empty()) << name;
  return all.str();
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

// One input x on [0, 1] with `lo` (Ramp 1 0) and `hi` (Ramp 0 1); two Sugeno outputs.
const std::string kChain = R"(Engine: chain
InputVariable: x
  range: 0 1
  term: lo Ramp 1 0
  term: hi Ramp 0 1
OutputVariable: a
  range: 0 1
  aggregation: Maximum
  defuzzifier: WeightedAverage TakagiSugeno
  default: nan
  term: one Constant 1
  term: two Constant 2
OutputVariable: b
  range: 0 1
  aggregation: none
  defuzzifier: WeightedAverage TakagiSugeno
  default: nan
  term: k Constant 10
RuleBlock: first
  conjunction: Minimum
  disjunction: Maximum
  activation: General
  rule: if a is one then b is k with 0.5
  rule: if x is lo then a is one
  rule: if x is hi then a is one with 0.5
  rule: if a is one then b is k
RuleBlock: second
  conjunction: Minimum
  activation: General
  rule: if a is one and x is hi then b is k with 0.25
)";

TEST(RuleFileChained, AnAntecedentOnAnOutputReadsTheDegreeOfTheRulesTriggeredBeforeIt) {
  const auto model = load("chain.fll", kChain);
  ASSERT_TRUE(model);
  EXPECT_TRUE(model->chained);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x = 0.25;  // lo = 0.75, hi = 0.25
  double y[2] = {};
  ASSERT_EQ(engine->evaluate(&x, y), Status::Ok);
  // Rule 1 runs before any conclusion on `a`: degree 0, it does not fire. Rules 2 and 3 give
  // `one` the degrees 0.75 and 0.125, folded by a's Maximum: 0.75. Rule 4 reads 0.75; the second
  // block reads it too: min(0.75, 0.25) * 0.25.
  EXPECT_EQ(engine->rule_strength(0), 0.0);
  EXPECT_EQ(engine->rule_strength(3), 0.75);
  EXPECT_EQ(engine->rule_strength(4), 0.0625);
  EXPECT_DOUBLE_EQ(y[0], 1.0);
  EXPECT_DOUBLE_EQ(y[1], 10.0);
}

TEST(RuleFileChained, EqualsFuzzyliteRuleOrderIncluded) {
  fl::fuzzylite::setMachEps(0.0);
  const auto model = load("chain.fll", kChain);
  ASSERT_TRUE(model);
  std::unique_ptr<fl::Engine> oracle(fl::FllImporter().fromString(kChain));
  auto engine = std::make_unique<Engine<double>>(*model);
  for (double x = -0.1; x <= 1.1; x += 0.01) {
    double y[2] = {};
    (void)engine->evaluate(&x, y);
    oracle->getInputVariable(0)->setValue(x);
    oracle->process();
    for (int o = 0; o < 2; ++o) {
      const double expected = oracle->getOutputVariable(o)->getValue();
      EXPECT_EQ(y[o], std::isnan(expected) ? 0.0 : expected) << "x = " << x << ", output " << o;
    }
  }
}

TEST(RuleFileChained, WithoutAggregationTheDegreesOfATermAddUp) {
  // b has no aggregation (none): two activations of k, 0.5 and 0.25, read as 0.75 by a third rule.
  std::string text = replace(kChain, "  rule: if a is one and x is hi then b is k with 0.25\n",
                             "  rule: if x is lo then b is k with 0.5\n"
                             "  rule: if x is lo then b is k with 0.25\n"
                             "  rule: if b is k then a is two\n");
  const auto model = load("sum.fll", text);
  ASSERT_TRUE(model);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x = 0.0;  // lo = 1
  double y[2] = {};
  ASSERT_EQ(engine->evaluate(&x, y), Status::Ok);
  // Rule 4 of the first block already gave k the degree 1 (a is one = 1): 1 + 0.5 + 0.25.
  EXPECT_EQ(engine->rule_strength(6), 1.75);
}

TEST(RuleFileChained, FisRulesWithoutAnInputIndexNeverFireAsInFuzzylite) {
  const std::string fis = R"([System]
Name='export'
Type='mamdani'
NumInputs=1
NumOutputs=2
NumRules=2
AndMethod='min'
OrMethod='max'
ImpMethod='min'
AggMethod='max'
DefuzzMethod='centroid'
[Input1]
Name='x'
Range=[0 1]
NumMFs=1
MF1='all':'trapmf',[0 0 1 1]
[Output1]
Name='y'
Range=[0 1]
NumMFs=1
MF1='mid':'trimf',[0 0.5 1]
[Output2]
Name='z'
Range=[0 1]
NumMFs=1
MF1='mid':'trimf',[0 0.5 1]
[Rules]
1, 1 0 (1) : 1
0, 0 1 (1) : 1
)";
  const auto model = load("export.fis", fis);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->num_rules, 1u);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x = 0.5;
  double y[2] = {};
  EXPECT_EQ(engine->evaluate(&x, y), Status::NoRuleFired);
  EXPECT_NEAR(y[0], 0.5, 1e-12);
  EXPECT_EQ(y[1], 0.0);
}

// Output `y` fires only for x in the term `on` (0.2 .. 0.6); elsewhere it keeps its last value.
const std::string kHold = R"(Engine: hold
InputVariable: x
  range: 0 1
  term: on Triangle 0.2 0.4 0.6
OutputVariable: y
  range: 0 10
  aggregation: none
  defuzzifier: WeightedAverage TakagiSugeno
  default: 3
  lock-previous: true
  term: k Linear 10 0
RuleBlock: rules
  activation: General
  rule: if x is on then y is k
)";

TEST(RuleFileLockPrevious, AnOutputNoRuleFiresForKeepsTheWorkspacesLastValue) {
  const auto model = load("hold.fll", kHold);
  ASSERT_TRUE(model);
  EXPECT_TRUE(model->outputs[0].lock_previous);
  auto engine = std::make_unique<Engine<double>>(*model);
  double y = 0;
  const double outside = 0.9, inside = 0.25, inside2 = 0.5;
  EXPECT_EQ(engine->evaluate(&outside, &y), Status::Ok);
  EXPECT_EQ(y, 3.0);  // nothing to keep yet: the default
  EXPECT_EQ(engine->evaluate(&inside, &y), Status::Ok);
  EXPECT_EQ(y, 2.5);  // 10 * 0.25
  EXPECT_EQ(engine->evaluate(&inside2, &y), Status::Ok);
  EXPECT_EQ(y, 5.0);
  EXPECT_EQ(engine->evaluate(&outside, &y), Status::Ok);
  EXPECT_EQ(y, 5.0);  // kept
  // A second workspace of the same immutable model has its own history.
  fuzzypid::fuzzy::DynamicWorkspace<double> other(*model);
  EXPECT_EQ(fuzzypid::fuzzy::evaluate(*model, other.view(), &outside, &y), Status::Ok);
  EXPECT_EQ(y, 3.0);
  // Setting the model again forgets the history.
  ASSERT_FALSE(engine->set_model(*model));
  EXPECT_EQ(engine->evaluate(&outside, &y), Status::Ok);
  EXPECT_EQ(y, 3.0);
}

TEST(RuleFileLockPrevious, WithADefaultOfNanTheFirstEmptyEvaluationReportsNoRuleFired) {
  const auto model = load("hold.fll", replace(kHold, "default: 3", "default: nan"));
  ASSERT_TRUE(model);
  auto engine = std::make_unique<Engine<double>>(*model);
  double y = 1;
  const double outside = 0.9, inside = 0.4;
  EXPECT_EQ(engine->evaluate(&outside, &y), Status::NoRuleFired);
  EXPECT_EQ(y, 0.0);
  EXPECT_EQ(engine->evaluate(&inside, &y), Status::Ok);
  EXPECT_EQ(engine->evaluate(&outside, &y), Status::Ok);
  EXPECT_EQ(y, 4.0);
}

const std::string kFcl = R"(FUNCTION_BLOCK hold
VAR_INPUT
  x : REAL;
END_VAR
VAR_OUTPUT
  y : REAL;
END_VAR
FUZZIFY x
  RANGE := (0 .. 1);
  TERM on := Triangle 0.2 0.4 0.6;
END_FUZZIFY
DEFUZZIFY y
  RANGE := (0 .. 10);
  TERM k := 7;
  METHOD : COGS;
  DEFAULT := NC;
END_DEFUZZIFY
RULEBLOCK rules
  RULE 1 : IF x IS on THEN y IS k;
END_RULEBLOCK
END_FUNCTION_BLOCK
)";

TEST(RuleFileLockPrevious, FclDefaultNcIsTheStandardsNoChange) {
  const auto model = load("hold.fcl", kFcl);
  ASSERT_TRUE(model);
  EXPECT_TRUE(model->outputs[0].lock_previous);
  EXPECT_TRUE(std::isnan(model->outputs[0].default_value));
  auto engine = std::make_unique<Engine<double>>(*model);
  double y = 0;
  const double outside = 0.9, inside = 0.3;
  EXPECT_EQ(engine->evaluate(&outside, &y), Status::NoRuleFired);
  EXPECT_EQ(engine->evaluate(&inside, &y), Status::Ok);
  EXPECT_EQ(engine->evaluate(&outside, &y), Status::Ok);
  EXPECT_EQ(y, 7.0);
  // Exported, it reads back the same (fuzzylite's `DEFAULT := nan | NC`).
  std::string fcl, why;
  ASSERT_TRUE(fuzzypid::rulefile::to_fcl(*model, fcl, why)) << why;
  EXPECT_NE(fcl.find("DEFAULT := nan | NC;"), std::string::npos) << fcl;
  const auto again = load("again.fcl", fcl);
  ASSERT_TRUE(again);
  EXPECT_TRUE(again->outputs[0].lock_previous);
}

const std::string kSugenoFis = R"([System]
Name='s'
Type='sugeno'
NumInputs=2
NumOutputs=1
NumRules=2
AndMethod=''
OrMethod='max'
ImpMethod=''
AggMethod=''
DefuzzMethod='wtaver'
[Input1]
Name='x'
Enabled=1
Range=[0 1]
NumMFs=1
MF1='lo':'trimf',[0 0 1]
[Input2]
Name='z'
Range=[0 1]
NumMFs=1
MF1='lo':'trimf',[0 0 1]
[Output1]
Name='y'
Enabled=1
Range=[0 0]
LockPrevious=0
LockRange=0
Default=nan
NumMFs=1
MF1='c':'constant',[4]
[Rules]
1 0, 1 (1) : 1
1 1, 1 (1) : 2
)";

TEST(RuleFileFis, ZeroWidthUnusedRangeEmptyMethodsAndEnabledKeysLoad) {
  const auto model = load("s.fis", kSugenoFis);
  ASSERT_TRUE(model);
  EXPECT_FALSE(model->blocks[0].has_conjunction);
  EXPECT_FALSE(model->outputs[0].has_aggregation);
  EXPECT_EQ(model->outputs[0].min, model->outputs[0].max);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x[2] = {0.5, 0.5};
  double y = 0;
  EXPECT_EQ(engine->evaluate(x, &y), Status::Ok);
  EXPECT_EQ(y, 4.0);
}

TEST(RuleFileFis, AnEmptyMethodARuleNeedsIsRefusedOnThatRulesLine) {
  const LoadError e = refusal("s.fis", replace(kSugenoFis, "1 1, 1 (1) : 2", "1 1, 1 (1) : 1"));
  EXPECT_EQ(e.line, 34) << e.to_string();
  EXPECT_NE(e.message.find("no conjunction"), std::string::npos) << e.to_string();
}

// A Sugeno output with a 'trimf' term: the cause is the term under Type='sugeno', named on its
// line, not the Tsukamoto terms the engine would take it for. Monotonic terms stay Tsukamoto's.
TEST(RuleFileFis, ANonMonotonicTermOfASugenoOutputIsBlamedOnTheTypeAndTheTerm) {
  const std::string fis = replace(replace(kSugenoFis, "Range=[0 0]", "Range=[0 1]"),
                                  "MF1='c':'constant',[4]", "MF1='c':'trimf',[0 0.5 1]");
  const LoadError e = refusal("s.fis", fis);
  EXPECT_EQ(e.line, 31) << e.to_string();
  EXPECT_NE(e.message.find("MF1 'c': Type='sugeno' outputs take 'constant' or 'linear' terms, "
                           "not 'trimf'"),
            std::string::npos)
      << e.to_string();
  EXPECT_EQ(e.message.find("Tsukamoto terms must be"), std::string::npos) << e.to_string();
  EXPECT_TRUE(load("ramp.fis", replace(fis, "'trimf',[0 0.5 1]", "'rampmf',[0 1]")));
}

TEST(RuleFileFis, AZeroWidthRangeIsRefusedWhereItIsUsed) {
  const LoadError e = refusal("s.fis", replace(kSugenoFis, "LockRange=0", "LockRange=1"));
  EXPECT_NE(e.message.find("output range"), std::string::npos) << e.to_string();
  EXPECT_EQ(e.line, 23) << e.to_string();  // [Output1]
}

TEST(RuleFileFis, EnabledZeroDisablesAVariable) {
  const auto model =
      load("s.fis", replace(kSugenoFis, "Enabled=1\nRange=[0 1]", "Enabled=0\nRange=[0 1]"));
  ASSERT_TRUE(model);
  EXPECT_FALSE(model->inputs[0].enabled);
  EXPECT_TRUE(model->inputs[1].enabled);
  std::string fis, error;
  ASSERT_TRUE(fuzzypid::rulefile::to_fis(*model, fis, error)) << error;
  EXPECT_NE(fis.find("Name='x'\nEnabled=0\n"), std::string::npos) << fis;
  EXPECT_FALSE(fuzzypid::rulefile::to_fcl(*model, fis, error));
  EXPECT_NE(error.find("'x' is disabled"), std::string::npos) << error;
}

// x enabled; z and the output b disabled. Fuzzylite's Antecedent gives a proposition on a disabled
// variable degree 0 before any hedge (`not`, `any` included); its Consequent skips a disabled
// output's conclusion, hedges included, so c's `somewhat` applies to the rule's own strength.
const std::string kDisabled = R"(Engine: disabled
InputVariable: x
  enabled: true
  range: 0 1
  term: lo Ramp 1 0
  term: hi Ramp 0 1
InputVariable: z
  enabled: false
  range: 0 1
  term: lo Ramp 1 0
OutputVariable: a
  range: 0 3
  aggregation: Maximum
  defuzzifier: WeightedAverage TakagiSugeno
  default: nan
  term: one Constant 1
  term: two Constant 2
OutputVariable: b
  enabled: false
  range: 0 20
  aggregation: Maximum
  defuzzifier: WeightedAverage TakagiSugeno
  default: nan
  term: k Constant 10
OutputVariable: c
  range: 0 20
  aggregation: Maximum
  defuzzifier: WeightedAverage TakagiSugeno
  default: nan
  term: k2 Constant 5
  term: k3 Constant 15
RuleBlock: rules
  conjunction: Minimum
  disjunction: Maximum
  activation: General
  rule: if x is lo and z is lo then a is one
  rule: if x is hi or z is not lo then a is two
  rule: if x is lo then b is very k and c is somewhat k2
  rule: if b is k or z is any then c is k3
  rule: if x is hi then c is k3 with 0.5
)";

TEST(RuleFileDisabled, PropositionsOnADisabledVariableAreZeroAndItsConclusionsAreSkipped) {
  const auto model = load("disabled.fll", kDisabled);
  ASSERT_TRUE(model);
  EXPECT_FALSE(model->inputs[1].enabled);
  EXPECT_FALSE(model->outputs[1].enabled);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x[2] = {0.25, 1.0};  // lo = 0.75, hi = 0.25; z's value is never read
  double y[3] = {7, 7, 7};
  ASSERT_EQ(engine->evaluate(x, y), Status::Ok) << "a disabled output raises no NoRuleFired";
  EXPECT_EQ(engine->rule_strength(0), 0.0);   // min(0.75, z: 0)
  EXPECT_EQ(engine->rule_strength(1), 0.25);  // max(0.25, not z: 0): `not` is not applied
  EXPECT_EQ(engine->rule_strength(3), 0.0);   // b (disabled output) and `z is any` are 0
  EXPECT_EQ(y[0], 2.0);
  EXPECT_EQ(y[1], 0.0);                     // disabled: no value (fuzzylite's NaN)
  const double somewhat = std::sqrt(0.75);  // not somewhat(very(0.75)): b's hedge is skipped
  EXPECT_DOUBLE_EQ(y[2], (5 * somewhat + 15 * 0.125) / (somewhat + 0.125));
  // Written back to .fll, the flags and the results stay.
  std::string fll, error;
  ASSERT_TRUE(fuzzypid::rulefile::to_fll(*model, fll, error)) << error;
  const auto again = load("again.fll", fll);
  ASSERT_TRUE(again);
  EXPECT_FALSE(again->inputs[1].enabled);
  EXPECT_FALSE(again->outputs[1].enabled);
  double z[3] = {};
  auto engine_again = std::make_unique<Engine<double>>(*again);
  ASSERT_EQ(engine_again->evaluate(x, z), Status::Ok);
  EXPECT_EQ(z[2], y[2]);
}

TEST(RuleFileDisabled, EqualsFuzzylite) {
  fl::fuzzylite::setMachEps(0.0);
  const auto model = load("disabled.fll", kDisabled);
  ASSERT_TRUE(model);
  std::unique_ptr<fl::Engine> oracle(fl::FllImporter().fromString(kDisabled));
  auto engine = std::make_unique<Engine<double>>(*model);
  for (double x = -0.1; x <= 1.1; x += 0.01) {
    const double in[2] = {x, 0.3};
    double y[3] = {};
    const Status s = engine->evaluate(in, y);
    oracle->getInputVariable(0)->setValue(in[0]);
    oracle->getInputVariable(1)->setValue(in[1]);
    oracle->process();
    for (int o = 0; o < 3; ++o) {
      const double expected = oracle->getOutputVariable(o)->getValue();
      if (o == 1) {
        EXPECT_TRUE(std::isnan(expected)) << "fuzzylite never defuzzifies a disabled output";
        EXPECT_EQ(y[o], 0.0);
      } else {
        EXPECT_EQ(y[o], std::isnan(expected) ? 0.0 : expected) << "x = " << x << ", output " << o;
        if (std::isnan(expected)) {
          EXPECT_EQ(s, Status::NoRuleFired) << "x = " << x;
        }
      }
    }
  }
}

TEST(RuleFileFis, HybridConstantsUnderAnIntegralDefuzzifierAreFuzzylitesConstantFunctions) {
  // fuzzylite applies DefuzzMethod to every output; the centroid of the constant functions
  // min(c, w) over the range, sampled, is (nearly) the range's middle whatever fires.
  std::string fis = replace(kSugenoFis, "Type='sugeno'", "Type='hybrid'");
  fis = replace(fis, "DefuzzMethod='wtaver'", "DefuzzMethod='centroid'");
  fis = replace(fis, "AggMethod=''", "AggMethod='max'");
  fis = replace(fis, "ImpMethod=''", "ImpMethod='min'");
  fis = replace(fis, "Range=[0 0]", "Range=[0 8]");
  const auto model = load("h.fis", fis);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->outputs[0].terms[0].membership.shape, fuzzypid::fuzzy::Shape::Rectangle);
  EXPECT_EQ(model->outputs[0].terms[0].membership.height, 4.0);
  fl::fuzzylite::setMachEps(0.0);
  std::unique_ptr<fl::Engine> oracle(fl::FisImporter().fromString(fis));
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x[2] = {0.3, 0.9};
  double y = 0;
  ASSERT_EQ(engine->evaluate(x, &y), Status::Ok);
  oracle->getInputVariable(0)->setValue(x[0]);
  oracle->getInputVariable(1)->setValue(x[1]);
  oracle->process();
  EXPECT_EQ(y, oracle->getOutputVariable(0)->getValue());
  EXPECT_NEAR(y, 4.0, 1e-9);
}

TEST(RuleFileFis, TsukamotoTypeReadsConcaveTermsWithTheirExactInverse) {
  std::string fis = replace(kSugenoFis, "Type='sugeno'", "Type='tsukamoto'");
  fis = replace(fis, "Range=[0 0]", "Range=[0 1]");
  fis = replace(fis, "MF1='c':'constant',[4]", "MF1='c':'concavemf',[0.2 0.6]");
  const auto model = load("t.fis", fis);
  ASSERT_TRUE(model);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x[2] = {0.5, 1.0};  // rule 1 fires with w = 0.5 (rule 2: z is lo = 0)
  double y = 0;
  ASSERT_EQ(engine->evaluate(x, &y), Status::Ok);
  // z = h (i - e) / w + 2e - i, where mu(z) = (e - i) / (2e - i - z) = 0.5 (fuzzylite 8;
  // fuzzylite 6 divides by mu(w) instead of w, giving 0.5 here).
  const double z = (0.2 - 0.6) / 0.5 + 1.2 - 0.2;
  EXPECT_DOUBLE_EQ(model->outputs[0].terms[0].membership(z, nullptr), 0.5);
  EXPECT_DOUBLE_EQ(y, z);
}

// Tsukamoto's z(w) inverts every monotonic term kind, of any height h: mu(z(w)) = w for w in
// (0, h], and z lies within the term's rising (falling) stretch; a degree above h gives the
// point where the term reaches h, a sigmoid's saturation the output range's end.
TEST(Tsukamoto, TheInverseOfEveryMonotonicKindMeetsTheDegreeAndStaysInTheTermsRange) {
  using fuzzypid::fuzzy::Shape;
  using fuzzypid::fuzzy::Term;
  std::mt19937_64 rng(20261203);
  fuzzypid::support::UniformReal<double> u(0.0, 1.0);
  const double lo = -100.0, hi = 100.0;  // the output range
  double worst = 0.0;
  int cases = 0;
  for (const Shape shape :
       {Shape::Ramp, Shape::Sigmoid, Shape::SShape, Shape::ZShape, Shape::Concave, Shape::Arc}) {
    for (int k = 0; k < 20000; ++k) {
      Term<double> t{};
      t.shape = shape;
      const double a = -10.0 + 20.0 * u(rng);
      double b = -10.0 + 20.0 * u(rng);
      // Widths of at least 0.1: a narrower term amplifies the rounding of z (|dmu/dz| ~ h / width).
      if (std::fabs(b - a) < 0.1) b = a + (b < a ? -0.1 : 0.1);
      t.p = {a, b, 0.0, 0.0};
      if (shape == Shape::SShape || shape == Shape::ZShape)  // start < end
        t.p = {std::fmin(a, b), std::fmax(a, b), 0.0, 0.0};
      if (shape == Shape::Sigmoid) t.p[1] = (u(rng) < 0.5 ? -1.0 : 1.0) * (0.1 + 5.0 * u(rng));
      t.height = k % 4 == 0 ? 1.0 : 0.05 + 0.95 * u(rng);
      ASSERT_TRUE(t.valid());
      const double h = t.height;
      const double w = k % 50 == 0 ? h : h * (1.0 - u(rng));  // (0, h], h itself now and then
      if (!(w > 0.0)) continue;
      const double z = fuzzypid::fuzzy::engine_detail::tsukamoto<double>(t, w, lo, hi, nullptr);
      ASSERT_TRUE(std::isfinite(z)) << static_cast<int>(shape) << " w " << w;
      if (shape == Shape::Sigmoid && w == h) {
        EXPECT_EQ(z, t.p[1] > 0 ? hi : lo);  // saturated: the end it tends to
        continue;
      }
      const double d = std::fabs(t(z, nullptr) - w);
      worst = std::fmax(worst, d);
      ++cases;
      ASSERT_LE(d, 1e-12) << "shape " << static_cast<int>(shape) << " p " << t.p[0] << " " << t.p[1]
                          << " h " << h << " w " << w << " z " << z;
      if (shape == Shape::Ramp || shape == Shape::SShape || shape == Shape::ZShape ||
          shape == Shape::Arc) {
        EXPECT_GE(z, std::fmin(t.p[0], t.p[1]));
        EXPECT_LE(z, std::fmax(t.p[0], t.p[1]));
      }
      if (shape == Shape::Concave) {  // the stretch that rises (falls) towards the end e
        if (t.p[0] <= t.p[1])
          EXPECT_LE(z, t.p[1]);
        else
          EXPECT_GE(z, t.p[1]);
      }
    }
    // Above the height: where the term reaches it.
    Term<double> t{};
    t.shape = shape;
    t.p = {2.0, 6.0, 0, 0};
    t.height = 0.5;
    const double z = fuzzypid::fuzzy::engine_detail::tsukamoto<double>(t, 0.9, lo, hi, nullptr);
    EXPECT_EQ(z, shape == Shape::ZShape ? 2.0 : shape == Shape::Sigmoid ? hi : 6.0);
  }
  std::printf("Tsukamoto: %d inverses, max |mu(z(w)) - w| = %.3g\n", cases, worst);
}

// fuzzylite 8's Arc and SemiEllipse in .fll (and .fcl, under the same names), as inputs and as
// Tsukamoto outputs; .fis has no form for them. At x = 0.45 in the corpus file:
//   near  = SemiEllipse(0, 0.6):   sqrt(0.3^2 - 0.15^2) / 0.3 = sqrt(3) / 2 = w1
//   far   = Arc(0.3, 1):           sqrt(0.7^2 - 0.55^2) / 0.7, weight 0.75 -> w2
//   down  = Arc(9.5, 0.5), h = 1:  z1 = 0.5 + sqrt(9^2 - (9 w1)^2) = 0.5 + 4.5 = 5
//   up    = Arc(1, 9), h = 0.8:    z2 = 9 - sqrt(8^2 - (8 w2 / 0.8)^2)
//   tsu   = (w1 z1 + w2 z2) / (w1 + w2)
TEST(RuleFileFll, ArcAndSemiEllipseAreFuzzylite8sTermsWithTheArcsExactInverse) {
  const std::string text = corpus_file("fuzzylite8_arc_semi_ellipse.fll");
  const auto model = load("arc.fll", text);
  ASSERT_TRUE(model);
  const double w1 = std::sqrt(3.0) / 2.0;
  const double w2 = 0.75 * std::sqrt(0.49 - 0.55 * 0.55) / 0.7;
  const double z1 = 5.0;
  const double z2 = 9.0 - std::sqrt(64.0 - std::pow(8.0 * w2 / 0.8, 2));
  const auto& up = model->outputs[1].terms[0].membership;
  EXPECT_NEAR(up(z2, nullptr), w2, 1e-15);  // mu(z) = w
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x = 0.45;
  double y[2] = {};
  ASSERT_EQ(engine->evaluate(&x, y), Status::Ok);
  EXPECT_NEAR(y[1], (w1 * z1 + w2 * z2) / (w1 + w2), 1e-14);

  // The same system written as .fcl reads back to the same bits; .fis refuses it by term.
  std::string fcl, fis, why;
  ASSERT_TRUE(fuzzypid::rulefile::to_fcl(*model, fcl, why)) << why;
  EXPECT_NE(fcl.find("TERM near := SemiEllipse 0 0.59999999999999998;"), std::string::npos) << fcl;
  const auto again = load("arc.fcl", fcl);
  ASSERT_TRUE(again);
  auto engine2 = std::make_unique<Engine<double>>(*again);
  for (double xi = -0.1; xi <= 1.1; xi += 0.01) {
    double a[2] = {}, b[2] = {};
    ASSERT_EQ(engine->evaluate(&xi, a), engine2->evaluate(&xi, b));
    EXPECT_EQ(a[0], b[0]);
    EXPECT_EQ(a[1], b[1]);
  }
  // steer alone (.fis has one defuzzifier for all outputs)
  std::string steer = replace(replace(text, " and tsu is down", ""), " and tsu is up", "");
  steer.erase(steer.find("OutputVariable: tsu"),
              steer.find("RuleBlock:") - steer.find("OutputVariable: tsu"));
  const auto steer_only = load("steer.fll", steer);
  ASSERT_TRUE(steer_only);
  EXPECT_FALSE(fuzzypid::rulefile::to_fis(*steer_only, fis, why));
  EXPECT_NE(why.find("input term 'near' has a shape or height .fis cannot express"),
            std::string::npos)
      << why;
  const LoadError error = refusal("arc.fis", R"([System]
Name='arc'
Type='mamdani'
NumInputs=1
NumOutputs=1
NumRules=1
AndMethod='min'
OrMethod='max'
ImpMethod='min'
AggMethod='max'
DefuzzMethod='centroid'

[Input1]
Name='x'
Range=[0 1]
NumMFs=1
MF1='far':'arcmf',[0.3 1]

[Output1]
Name='y'
Range=[0 1]
NumMFs=1
MF1='one':'trimf',[0 0.5 1]

[Rules]
1, 1 (1) : 1
)");
  EXPECT_EQ(error.line, 17) << error.to_string();
  EXPECT_NE(error.message.find("'arcmf': fuzzylite 8's Arc and SemiEllipse have no .fis form"),
            std::string::npos)
      << error.to_string();
}

// Bisector as fuzzylite 8 computes it: the sample where the running area is nearest half the
// total (the mean of such samples when the area stops growing there). On the two plateaus, cut
// at one degree, 60 equal samples: the running area is half after the 30th, x = 3.95, and stays
// so over the zeros up to the 40th sample before `right` starts: (3.95 + ... + 5.95) / 21 = 4.95.
TEST(RuleFileFll, BisectorIsTheSampleNearestHalfTheArea) {
  auto model = std::make_unique<Model>();
  LoadError error;
  std::string text;
  {
    std::ifstream in(FUZZYPID_RULEFILES_DIR "/corpus/handmade_mom_two_plateaus.fll");
    std::ostringstream all;
    all << in.rdbuf();
    text = all.str();
  }
  text = replace(text, "defuzzifier: MeanOfMaximum 100", "defuzzifier: Bisector 100");
  ASSERT_TRUE(fuzzypid::rulefile::parse_fll(text, "bisector.fll", *model, error))
      << error.to_string();
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x = 0.5;
  double y[3] = {};
  ASSERT_EQ(engine->evaluate(&x, y), Status::Ok);
  EXPECT_NEAR(y[0], 4.95, 1e-12);
}

// Two equal plateaus: the mean of maximum over all maximising samples (MATLAB, Octave,
// fuzzylite 8) is their common middle, 5.0 (fuzzylite 6: 2.5, the first plateau's middle);
// smallest and largest of maximum are the first and last maximising samples.
TEST(RuleFileFll, MeanOfMaximumIsTheMeanOfEveryMaximisingSampleAcrossPlateaus) {
  auto model = std::make_unique<Model>();
  LoadError error;
  ASSERT_TRUE(fuzzypid::rulefile::load_fll(
      FUZZYPID_RULEFILES_DIR "/corpus/handmade_mom_two_plateaus.fll", *model, error))
      << error.to_string();
  auto engine = std::make_unique<Engine<double>>(*model);
  for (const double x : {0.4, 0.5, 0.9}) {
    SCOPED_TRACE(x);
    double y[3] = {};
    ASSERT_EQ(engine->evaluate(&x, y), Status::Ok);
    // Samples 0.05 + 0.1 k: 30 in (1, 4) and 30 in (6, 9), mean (sum 75 + 225) / 60.
    EXPECT_NEAR(y[0], 5.0, 1e-12);
    EXPECT_NEAR(y[1], 1.05, 1e-12);
    EXPECT_NEAR(y[2], 8.95, 1e-12);
  }
  const double x = 0.2;  // `right` alone is highest (0.4 > 0.2): one plateau, its middle
  double y[3] = {};
  ASSERT_EQ(engine->evaluate(&x, y), Status::Ok);
  EXPECT_NEAR(y[0], 7.5, 1e-12);
}

// Tsukamoto outputs are weighted averages of the terms' inverses (fuzzylite's Tsukamoto): an
// integral DefuzzMethod does not fit the Type, as for 'sugeno'.
TEST(RuleFileFis, ATsukamotoTypeWithAnIntegralDefuzzifierIsRefusedOnItsLine) {
  std::string fis = replace(kSugenoFis, "Type='sugeno'", "Type='tsukamoto'");
  fis = replace(fis, "Range=[0 0]", "Range=[0 1]");
  fis = replace(fis, "MF1='c':'constant',[4]", "MF1='c':'concavemf',[0.2 0.6]");
  ASSERT_TRUE(load("t.fis", fis));
  fis = replace(fis, "DefuzzMethod='wtaver'", "DefuzzMethod='centroid'");
  fis = replace(fis, "AggMethod=''", "AggMethod='max'");
  fis = replace(fis, "ImpMethod=''", "ImpMethod='min'");
  const LoadError e = refusal("t.fis", fis);
  EXPECT_EQ(e.line, 11) << e.to_string();  // DefuzzMethod='centroid'
  EXPECT_NE(e.message.find("DefuzzMethod"), std::string::npos) << e.to_string();
  EXPECT_NE(e.message.find("tsukamoto"), std::string::npos) << e.to_string();
}

TEST(RuleFileFis, MfLinesAreTheTermsWhateverTheirNumberAndNumMfsSay) {
  // As MATLAB's readfis and fuzzylite: a repeated k and a stale NumMFs do not drop or reorder
  // terms.
  std::string fis =
      replace(kSugenoFis, "NumMFs=1\nMF1='lo':'trimf',[0 0 1]\n[Input2]",
              "NumMFs=1\nMF1='lo':'trimf',[0 0 1]\nMF1='hi':'trimf',[0 1 1]\n[Input2]");
  fis = replace(fis, "1 0, 1 (1) : 1", "2 0, 1 (1) : 1");
  const auto model = load("mfs.fis", fis);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->inputs[0].num_terms, 2u);
  EXPECT_STREQ(model->inputs[0].term_names[1].data(), "hi");
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x[2] = {0.75, 1.0};  // hi = 0.75, z is lo = 0: only rule 1 fires
  double y = 0;
  ASSERT_EQ(engine->evaluate(x, &y), Status::Ok);
  EXPECT_EQ(engine->rule_strength(0), 0.75);
}

// Found by fuzz_fis: a zero-width rampmf (0 everywhere) was written as MATLAB's linzmf, which
// needs a < b, so the export did not read back.
TEST(RuleFileFis, AZeroWidthRampmfIsWrittenBackAsRampmf) {
  std::string fis = replace(kSugenoFis, "Type='sugeno'", "Type='tsukamoto'");
  fis = replace(fis, "Range=[0 0]", "Range=[0 1]");
  fis = replace(fis, "MF1='c':'constant',[4]", "MF1='c':'rampmf',[1 1]");
  const auto model = load("ramp.fis", fis);
  ASSERT_TRUE(model);
  std::string out, why;
  ASSERT_TRUE(fuzzypid::rulefile::to_fis(*model, out, why)) << why;
  EXPECT_NE(out.find("'rampmf',[1 1]"), std::string::npos) << out;
  EXPECT_TRUE(load("again.fis", out));
}

TEST(RuleFileFis, RuleLinesBeyondAStaleNumRulesAreRead) {
  const auto model = load("stale.fis", replace(kSugenoFis, "NumRules=2", "NumRules=1"));
  ASSERT_TRUE(model);
  EXPECT_EQ(model->num_rules, 2u);
}

// fuzzylite 8 looks a term up by name in a map filled in file order, so of two terms sharing a
// name a rule means the last (fuzzylite 6 took the first). The file loads with a warning naming
// the rule; the value is the last term's (9), not the first's (10 x = 3).
TEST(RuleFileFll, TermsSharingANameAreKeptAndRulesMeanTheLastAsInFuzzylite8) {
  const std::string fll =
      replace(kHold, "  term: k Linear 10 0\n", "  term: k Linear 10 0\n  term: k Constant 9\n");
  auto model = std::make_unique<Model>();
  LoadError error;
  ASSERT_TRUE(fuzzypid::rulefile::parse_fll(fll, "same.fll", *model, error)) << error.to_string();
  ASSERT_EQ(error.warnings.size(), 1u);
  EXPECT_NE(error.warnings[0].find("mean the last, as fuzzylite 8"), std::string::npos)
      << error.warnings[0];
  EXPECT_EQ(model->outputs[0].num_terms, 2u);
  EXPECT_EQ(model->conclusions[0].term, 1u);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x = 0.3;
  double y = 0;
  ASSERT_EQ(engine->evaluate(&x, &y), Status::Ok);
  EXPECT_EQ(y, 9.0);
}

// An integral defuzzifier written without its resolution takes fuzzylite 8's default, 1000
// samples (fuzzylite 6's was 100, but its exporter always writes the number).
TEST(RuleFileFll, AnIntegralDefuzzifierWithoutResolutionTakesFuzzylite8sDefault) {
  const std::string base = R"(Engine: r
InputVariable: x
  range: 0 1
  term: on Triangle 0 0.5 1
OutputVariable: y
  range: 0 1
  aggregation: Maximum
  defuzzifier: Centroid
  default: nan
  term: a Triangle 0 0.3 1
RuleBlock: rules
  implication: Minimum
  activation: General
  rule: if x is on then y is a
)";
  const auto model = load("r.fll", base);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->outputs[0].resolution, 1000);
  const auto explicit_100 = load("r.fll", replace(base, "Centroid\n", "Centroid 100\n"));
  ASSERT_TRUE(explicit_100);
  EXPECT_EQ(explicit_100->outputs[0].resolution, 100);
}

// Where fuzzylite's FisImporter departs from MATLAB, fuzzypid keeps MATLAB's meaning.
const std::string kSigns = R"([System]
Name='signs'
Type='mamdani'
NumInputs=1
NumOutputs=1
NumRules=2
AndMethod='min'
OrMethod='max'
ImpMethod='min'
AggMethod='max'
DefuzzMethod='centroid'
[Input1]
Name='e'
Range=[-1 1]
NumMFs=2
MF1='-P':'trimf',[-2 -1 0]
MF2='P':'trimf',[0 1 2]
[Output1]
Name='u'
Range=[-1 1]
NumMFs=2
MF1='-P':'trimf',[-2 -1 0]
MF2='P':'trimf',[0 1 2]
[Rules]
1, 1 (1) : 1
2, 2 (1) : 1
)";

TEST(RuleFileFuzzyliteDifferences, MinusPAndPStayTwoTermsWhereFuzzyliteMergesThem) {
  fl::fuzzylite::setMachEps(0.0);
  const auto model = load("signs.fis", kSigns);
  ASSERT_TRUE(model);
  EXPECT_STREQ(model->inputs[0].term_names[0].data(), "-P");
  auto engine = std::make_unique<Engine<double>>(*model);
  const double e = 0.5;
  double u = 0;
  ASSERT_EQ(engine->evaluate(&e, &u), Status::Ok);
  EXPECT_GT(u, 0.3);  // "P" fires, "-P" does not: a positive command
  // fuzzylite strips '-' from names: both terms become 'P' and both rules resolve to the first
  // (MATLAB's '-P'), so at e = 0.5 no rule fires.
  std::unique_ptr<fl::Engine> mangled(fl::FisImporter().fromString(kSigns));
  mangled->getInputVariable(0)->setValue(e);
  mangled->process();
  EXPECT_TRUE(std::isnan(mangled->getOutputVariable(0)->getValue()));
  // Renamed so no two names coincide, fuzzylite agrees with us.
  std::string renamed = kSigns;
  while (renamed.find("'-P'") != std::string::npos)
    renamed = replace(renamed, "'-P'", "'N'");
  std::unique_ptr<fl::Engine> fair(fl::FisImporter().fromString(renamed));
  fair->getInputVariable(0)->setValue(e);
  fair->process();
  EXPECT_EQ(fair->getOutputVariable(0)->getValue(), u);
}

TEST(RuleFileFuzzyliteDifferences, Matlab1xZeroPaddingIsNotATermHeight) {
  fl::fuzzylite::setMachEps(0.0);
  // MATLAB 1.x pads every parameter list to the longest (here trapmf's 4).
  const std::string padded =
      replace(replace(kSigns, "[-2 -1 0]", "[-2 -1 0 0]"), "[0 1 2]", "[0 1 2 0]");
  const auto model = load("padded.fis", padded);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->inputs[0].terms[0].height, 1.0);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double e = -0.5;
  double u = 0;
  ASSERT_EQ(engine->evaluate(&e, &u), Status::Ok);
  // fuzzylite takes the pad as the height: every term is 0 everywhere, no rule fires.
  std::unique_ptr<fl::Engine> oracle(fl::FisImporter().fromString(padded));
  oracle->getInputVariable(0)->setValue(e);
  oracle->process();
  EXPECT_TRUE(std::isnan(oracle->getOutputVariable(0)->getValue()));
  // Unpadded, fuzzylite agrees with us.
  std::unique_ptr<fl::Engine> fair(
      fl::FisImporter().fromString(replace(replace(kSigns, "'-P'", "'N'"), "'-P'", "'N'")));
  fair->getInputVariable(0)->setValue(e);
  fair->process();
  EXPECT_EQ(fair->getOutputVariable(0)->getValue(), u);
}

// .fis hedges as Octave's fuzzy-logic-toolkit computes them (MATLAB has none; docs/rule_files.md):
// a code's fraction .dd raises the antecedent's degree to dd/10, then `not`; on a Sugeno
// conclusion it gives the height w^(1/(dd/10)). octave_hedge_powers_sugeno.fis, in closed form:
//   rule 1  x is .3 low                  w1 = low(x)^3                       -> a = 2
//   rule 2  x is .01 high                w2 = high(x)^0.1                    -> b = 6
//   rule 3  y is not .3 high, weight .5  w3 = 0.5 (1 - high(y)^3), .2: sqrt(w3) -> c = x + 2y + 3
//   rule 4  x is .2 low and y is high    w4 = min(low(x)^2, high(y)), .3: w4^(1/3) -> a = 2
// Octave 7.3 with the toolkit 0.4.6 (the command in docs/rule_files.md) gives 4.292353232088578,
// 3.9820679834114792 and 4.8453042715850039 at the three points below.
TEST(RuleFileFisOctave, HedgesArePowersOfTheDegreeAndSugenoConclusionsTakeTheirRoot) {
  const auto model = load("powers.fis", corpus_file("octave_hedge_powers_sugeno.fis"));
  ASSERT_TRUE(model);
  auto engine = std::make_unique<Engine<double>>(*model);
  const auto closed_form = [](double x, double y) {
    const double low_x = 1 - x, high_x = x, high_y = y;
    const double w1 = std::pow(low_x, 3.0), w2 = std::pow(high_x, 0.1);
    const double w3 = std::sqrt(0.5 * (1 - std::pow(high_y, 3.0)));
    const double w4 = std::cbrt(std::fmin(low_x * low_x, high_y));
    return (w1 * 2 + w2 * 6 + w3 * (x + 2 * y + 3) + w4 * 2) / (w1 + w2 + w3 + w4);
  };
  const double octave[3] = {4.292353232088578, 3.9820679834114792, 4.8453042715850039};
  const double points[3][2] = {{0.5, 0.5}, {0.3, 0.8}, {0.9, 0.1}};
  for (int k = 0; k < 3; ++k) {
    double z = 0;
    ASSERT_EQ(engine->evaluate(points[k], &z), Status::Ok);
    EXPECT_NEAR(z, closed_form(points[k][0], points[k][1]), 1e-14) << k;
    EXPECT_NEAR(z, octave[k], 1e-14) << k;
  }
  // A custom hedge .15 is mu^1.5 (fuzzylite has no such code).
  const auto custom = load("custom.fis", replace(corpus_file("octave_hedge_powers_sugeno.fis"),
                                                 "1.2 2, 1.3", "1.15 2, 1.3"));
  ASSERT_TRUE(custom);
  auto engine2 = std::make_unique<Engine<double>>(*custom);
  const double xy[2] = {0.5, 0.5};
  double z = 0;
  ASSERT_EQ(engine2->evaluate(xy, &z), Status::Ok);
  const double w[4] = {0.125, std::pow(0.5, 0.1), std::sqrt(0.4375),
                       std::cbrt(std::fmin(std::pow(0.5, 1.5), 0.5))};
  EXPECT_NEAR(z, (w[0] * 2 + w[1] * 6 + w[2] * 4.5 + w[3] * 2) / (w[0] + w[1] + w[2] + w[3]),
              1e-14);
}

// The hedges survive a .fis round trip; fuzzylite's formats have no power hedge and refuse it,
// and fuzzylite's `seldom` and `extremely` have no .fis code Octave reads as such.
TEST(RuleFileFisOctave, PowerHedgesRoundTripThroughFisOnly) {
  const auto model = load("powers.fis", corpus_file("octave_hedge_powers_sugeno.fis"));
  ASSERT_TRUE(model);
  std::string fis, fll, why;
  ASSERT_TRUE(fuzzypid::rulefile::to_fis(*model, fis, why)) << why;
  EXPECT_NE(fis.find("0 -2.2999999999999998, 3.2000000000000002 (0.5) : 1"), std::string::npos)
      << fis;
  const auto again = load("again.fis", fis);
  ASSERT_TRUE(again);
  auto a = std::make_unique<Engine<double>>(*model);
  auto b = std::make_unique<Engine<double>>(*again);
  for (double x = 0.0; x <= 1.0; x += 0.05)
    for (double y = 0.0; y <= 1.0; y += 0.05) {
      const double in[2] = {x, y};
      double za = 0, zb = 0;
      ASSERT_EQ(a->evaluate(in, &za), b->evaluate(in, &zb));
      ASSERT_EQ(za, zb) << x << " " << y;
    }
  EXPECT_FALSE(fuzzypid::rulefile::to_fll(*model, fll, why));
  EXPECT_EQ(why,
            "rule 1 has Octave's power hedge (a .fis code .dd other than .05, .2, .4), which "
            "fuzzylite's formats cannot express");
  const auto extremely = load("x.fll", R"(Engine: e
InputVariable: x
  range: 0 1
  term: low Triangle -1 0 1
OutputVariable: z
  range: 0 1
  defuzzifier: WeightedAverage
  term: a Constant 2
RuleBlock: b
  activation: General
  rule: if x is extremely low then z is a
)");
  ASSERT_TRUE(extremely);
  EXPECT_FALSE(fuzzypid::rulefile::to_fis(*extremely, fis, why));
  EXPECT_NE(why.find("Octave reads .01 as mu^0.1 and .3 as mu^3"), std::string::npos) << why;
}

// Octave's aggregate_output_sugeno: with AggMethod='max', conclusions at the same value are one
// singleton of the largest height. octave_sugeno_max_aggregation.fis at x = 0.25: low 0.75,
// mid 0.5, high 0.25; `small` (1) from rules 1 and 2 and `also_small` (1) from rule 4 (0.5 * 0.5)
// are one singleton of height 0.75, `big` (9) has 0.25: (0.75 + 2.25) / 1 = 3. At x = 0.6: low
// 0.4, mid 0.8, high 0.6: (0.8 + 5.4) / 1.4. fuzzylite weighs every conclusion:
// (0.75 + 0.5 + 2.25 + 0.25) / 1.75. Octave gives 3 and 4.4285714285714279.
TEST(RuleFileFisOctave, SugenoMaxAggregationMergesSingletonsOfEqualValue) {
  const std::string text = corpus_file("octave_sugeno_max_aggregation.fis");
  const auto model = load("max.fis", text);
  ASSERT_TRUE(model);
  EXPECT_TRUE(model->outputs[0].merge_equal_singletons);
  auto engine = std::make_unique<Engine<double>>(*model);
  double x = 0.25, z = 0;
  ASSERT_EQ(engine->evaluate(&x, &z), Status::Ok);
  EXPECT_NEAR(z, 3.0, 1e-15);
  x = 0.6;
  ASSERT_EQ(engine->evaluate(&x, &z), Status::Ok);
  EXPECT_NEAR(z, 6.2 / 1.4, 1e-15);

  // wtsum: the same merged singletons, summed.
  const auto sum =
      load("wtsum.fis", replace(text, "DefuzzMethod='wtaver'", "DefuzzMethod='wtsum'"));
  ASSERT_TRUE(sum);
  auto engine_sum = std::make_unique<Engine<double>>(*sum);
  ASSERT_EQ(engine_sum->evaluate(&x, &z), Status::Ok);
  EXPECT_NEAR(z, 0.8 * 1 + 0.6 * 9, 1e-15);

  // AggMethod='sum' is the plain weighted average (Octave adds equal singletons up).
  const auto plain = load("sum.fis", replace(text, "\nAggMethod='max'", "\nAggMethod='sum'"));
  ASSERT_TRUE(plain);
  EXPECT_FALSE(plain->outputs[0].merge_equal_singletons);
  auto engine_plain = std::make_unique<Engine<double>>(*plain);
  x = 0.25;
  ASSERT_EQ(engine_plain->evaluate(&x, &z), Status::Ok);
  EXPECT_NEAR(z, 3.75 / 1.75, 1e-15);

  // .fis writes AggMethod back and reads the same system; fuzzylite's formats cannot say it.
  std::string fis, fll, why;
  ASSERT_TRUE(fuzzypid::rulefile::to_fis(*model, fis, why)) << why;
  EXPECT_NE(fis.find("AggMethod='max'"), std::string::npos) << fis;
  const auto again = load("again.fis", fis);
  ASSERT_TRUE(again);
  auto engine_again = std::make_unique<Engine<double>>(*again);
  ASSERT_EQ(engine_again->evaluate(&x, &z), Status::Ok);
  EXPECT_NEAR(z, 3.0, 1e-15);
  EXPECT_FALSE(fuzzypid::rulefile::to_fll(*model, fll, why));
  EXPECT_NE(why.find("output 'z' merges equal singletons"), std::string::npos) << why;
}

// fuzzylite 8's weighted defuzzification (Aggregated::grouped_terms): the activations of a term
// fold into one degree by the output's aggregation (their sum without one), then
// y = sum(w_t z_t) / sum(w_t). At x = 0.25: low 0.75, mid 0.5; `small` is concluded by rules 1
// and 2, `big` by rule 3 at 0.5 * 0.5.
const char* const kGroupedFll = R"(Engine: e
InputVariable: x
  range: 0 1
  term: low Triangle -1 0 1
  term: mid Triangle 0 0.5 1
OutputVariable: z
  range: 0 10
  aggregation: Maximum
  defuzzifier: WeightedAverage
  term: small Constant 1
  term: big Constant 9
RuleBlock: b
  activation: General
  rule: if x is low then z is small
  rule: if x is mid then z is small
  rule: if x is mid then z is big with 0.5
)";

TEST(RuleFileFuzzylite8, AWeightedOutputAggregatesTheActivationsOfEachTermFirst) {
  const double x = 0.25;
  struct Case {
    const char* aggregation;
    double small;  // the degree of `small` after grouping
    bool grouped;
  };
  for (const Case c : {Case{"Maximum", 0.75, true}, Case{"AlgebraicSum", 0.75 + 0.5 - 0.375, true},
                       Case{"BoundedSum", 1.0, true}, Case{"UnboundedSum", 1.25, false},
                       Case{"none", 1.25, false}}) {
    SCOPED_TRACE(c.aggregation);
    const auto model = load("g.fll", replace(kGroupedFll, "aggregation: Maximum",
                                             std::string("aggregation: ") + c.aggregation));
    ASSERT_TRUE(model);
    EXPECT_EQ(model->outputs[0].group_by_term, c.grouped);
    auto engine = std::make_unique<Engine<double>>(*model);
    double z = 0;
    ASSERT_EQ(engine->evaluate(&x, &z), Status::Ok);
    EXPECT_NEAR(z, (c.small * 1 + 0.25 * 9) / (c.small + 0.25), 1e-15);
  }
  // The same system as .fcl (fuzzylite 8 reads none; its .fll meaning is kept).
  const auto model = load("g.fll", kGroupedFll);
  ASSERT_TRUE(model);
  std::string fcl, why;
  ASSERT_TRUE(fuzzypid::rulefile::to_fcl(*model, fcl, why)) << why;
  const auto from_fcl = load("g.fcl", fcl);
  ASSERT_TRUE(from_fcl);
  EXPECT_TRUE(from_fcl->outputs[0].group_by_term);
  auto engine = std::make_unique<Engine<double>>(*from_fcl);
  double z = 0;
  ASSERT_EQ(engine->evaluate(&x, &z), Status::Ok);
  EXPECT_NEAR(z, 3.0, 1e-15);
}

// Tsukamoto: z depends on the degree, so grouping matters without an aggregation too. Ramp
// 0 -> 10 reaches w at z = 10 w. At x = 0.25 the two rules give `up` 0.75 * 0.5 and 0.5 * 0.5:
// fuzzylite 8 sums them (0.625, z = 6.25) and y = z; fuzzylite 6 weighed each:
// (0.375 * 3.75 + 0.25 * 2.5) / 0.625 = 3.25.
TEST(RuleFileFuzzylite8, ATsukamotoTermConcludedTwiceIsInvertedAtItsSummedDegree) {
  const auto model = load("t.fll", R"(Engine: e
InputVariable: x
  range: 0 1
  term: low Triangle -1 0 1
  term: mid Triangle 0 0.5 1
OutputVariable: z
  range: 0 10
  aggregation: none
  defuzzifier: WeightedAverage Tsukamoto
  term: up Ramp 0 10
RuleBlock: b
  activation: General
  rule: if x is low then z is up with 0.5
  rule: if x is mid then z is up with 0.5
)");
  ASSERT_TRUE(model);
  EXPECT_TRUE(model->outputs[0].group_by_term);
  auto engine = std::make_unique<Engine<double>>(*model);
  const double x = 0.25;
  double z = 0;
  ASSERT_EQ(engine->evaluate(&x, &z), Status::Ok);
  EXPECT_NEAR(z, 6.25, 1e-14);

  // The same model weighing every activation (a Tsukamoto .fis, read as fuzzylite 6 reads it)
  // gives fuzzylite 6's value, and fuzzylite's formats refuse to write it.
  Model per_activation = *model;
  per_activation.outputs[0].group_by_term = false;
  auto engine6 = std::make_unique<Engine<double>>(per_activation);
  ASSERT_EQ(engine6->evaluate(&x, &z), Status::Ok);
  EXPECT_NEAR(z, 3.25, 1e-14);
  std::string text, why;
  EXPECT_FALSE(fuzzypid::rulefile::to_fll(per_activation, text, why));
  EXPECT_NE(why.find("output 'z' weighs every activation of a term concluded more than once"),
            std::string::npos)
      << why;
  EXPECT_FALSE(fuzzypid::rulefile::to_fcl(per_activation, text, why));
  // .fis reads Tsukamoto per activation: a grouped output with a term concluded twice is refused.
  EXPECT_FALSE(fuzzypid::rulefile::to_fis(*model, text, why));
  EXPECT_NE(why.find("output 'z' aggregates the activations of each term"), std::string::npos)
      << why;
}

// Written to .fis, a grouped output of constants of distinct values is Octave's merging of equal
// values with the same aggregation; an output grouping nothing (no term concluded twice) is the
// plain weighted average, 'sum'; other grouped outputs are refused.
TEST(RuleFileFisOctave, AFuzzylite8WeightedOutputIsWrittenToFisAsOctaveMergesOrRefused) {
  const auto model = load("g.fll", kGroupedFll);
  ASSERT_TRUE(model);
  std::string fis, why;
  ASSERT_TRUE(fuzzypid::rulefile::to_fis(*model, fis, why)) << why;
  EXPECT_NE(fis.find("AggMethod='max'"), std::string::npos) << fis;
  const auto again = load("again.fis", fis);
  ASSERT_TRUE(again);
  EXPECT_TRUE(again->outputs[0].merge_equal_singletons);
  auto a = std::make_unique<Engine<double>>(*model);
  auto b = std::make_unique<Engine<double>>(*again);
  for (const double x : {0.0, 0.1, 0.25, 0.5, 0.8, 0.95}) {
    double za = 0, zb = 0;
    ASSERT_EQ(a->evaluate(&x, &za), Status::Ok);
    ASSERT_EQ(b->evaluate(&x, &zb), Status::Ok);
    EXPECT_NEAR(za, zb, 1e-15) << x;
  }

  const auto once =
      load("once.fll", replace(kGroupedFll, "  rule: if x is mid then z is small\n", ""));
  ASSERT_TRUE(once);
  ASSERT_TRUE(fuzzypid::rulefile::to_fis(*once, fis, why)) << why;
  EXPECT_NE(fis.find("AggMethod='sum'"), std::string::npos) << fis;

  const auto equal = load("equal.fll", replace(kGroupedFll, "big Constant 9", "big Constant 1"));
  ASSERT_TRUE(equal);
  EXPECT_FALSE(fuzzypid::rulefile::to_fis(*equal, fis, why));
  EXPECT_NE(why.find("only for constant terms of distinct values"), std::string::npos) << why;
  const auto linear =
      load("linear.fll", replace(kGroupedFll, "small Constant 1", "small Linear 2 1"));
  ASSERT_TRUE(linear);
  EXPECT_FALSE(fuzzypid::rulefile::to_fis(*linear, fis, why));
}

// Octave raises a Mamdani output's set to the hedge's power (evalmf on the output range); the
// engine hedges degrees, so such a conclusion is refused on its rule's line.
TEST(RuleFileFisOctave, AHedgeOnAMamdaniConclusionIsRefusedOnItsLine) {
  std::string text = corpus_file("octave_sugeno_max_aggregation.fis");
  text = replace(text, "Type='sugeno'", "Type='mamdani'");
  text = replace(text, "DefuzzMethod='wtaver'", "DefuzzMethod='centroid'");
  text = replace(text, "MF1='small':'constant',[1]", "MF1='small':'trimf',[0 1 2]");
  text = replace(text, "MF2='big':'constant',[9]", "MF2='big':'trimf',[8 9 10]");
  text = replace(text, "MF3='also_small':'constant',[1]", "MF3='also_small':'trimf',[0 1 2]");
  ASSERT_TRUE(load("mamdani.fis", text));
  const LoadError error = refusal("mamdani.fis", replace(text, "3, 1 (1) : 1", "3, 1.2 (1) : 1"));
  EXPECT_EQ(error.line, 36) << error.to_string();
  EXPECT_NE(error.message.find("a hedge on a Mamdani conclusion (1.2: Octave raises the output's "
                               "set to the power) is not supported"),
            std::string::npos)
      << error.to_string();
}

// --- Function terms: fuzzylite 8's formulas -----------------------------------------------------

// Inputs a on [-5, 5] and b on [-2, 2]; input term f of `a` is the formula `input`, output z
// (WeightedSum) concludes Function `output` when a is f (and `one` = Constant 1 when a is all).
std::string formula_file(const std::string& input, const std::string& output) {
  return "Engine: formulas\nInputVariable: a\n  range: -5 5\n  term: f Function " + input +
         "\n  term: all Rectangle -1e9 1e9\nInputVariable: b\n  range: -2 2\n  term: any_b "
         "Rectangle -1e9 1e9\nOutputVariable: z\n  range: -1e9 1e9\n  aggregation: none\n  "
         "defuzzifier: WeightedSum TakagiSugeno\n  default: nan\n  term: g Function " +
         output +
         "\n  term: one Constant 1\nRuleBlock: rules\n  conjunction: Minimum\n  implication: none\n"
         "  rule: if a is f then z is one\n  rule: if a is all then z is g\n";
}

// z = mu_f(a) * 1 + g(a, b) (a rule of strength <= 0 does not fire: formulas here are > 0).
double evaluate_at(const Model& model, double a, double b, Status* status = nullptr) {
  Engine<double> engine(model);
  const double in[2] = {a, b};
  double out[1] = {};
  const Status s = engine.evaluate(in, out);
  if (status != nullptr) *status = s;
  return out[0];
}

std::string refusal_of(const std::string& input, const std::string& output = "a + b") {
  return refusal("f.fll", formula_file(input, output)).to_string();
}

// The precedence and associativity of fuzzylite 8's FunctionFactory: ! ~ (100, right), ^ ** .-
// .+ (90, right), * / % (80), + - (70), and (60), or (50); functions bind as prefix operators.
TEST(RuleFileFunction, FormulasFollowFuzzylite8sPrecedenceAndAssociativity) {
  const struct {
    const char* formula;
    double at_a_2;  // input term's value at a = 2 (b = 0.5), + 1 for the output's g = 1
  } cases[] = {
      {"1 + 2 * x", 5},
      {"(1 + 2) * x", 6},
      {"2 ^ 3 ^ 0.5 / x", 1.6609985427419565},
      {"x ^ 2 ^ 0", 2},
      {"x ** 3", 8},
      {"10 - x - 3", 5},
      {"12 / x / 3", 2},
      {".- x ^ 2 + 10", 6},
      {"~ x + 5", 3},
      {"~ x ^ 2 + 5", 9},
      {".+ x", 2},
      {"7 % x * 2", 2},
      {"sin x + 1", 1.9092974268256817},
      {"max(x, b) + min(1, 2)", 3},
      {"max 3 x", 3},
      {"pi + x", 5.1415926535897931},
      {"x + b * 2", 3},
      {"gt(x, 1) or 0 and 0", 1},
      {"atan2(b, x) + 1", 1.2449786631268641},
      {"1e1 / x", 5},
      {"0.25 + .5 + x", 2.75},
  };
  for (const auto& c : cases) {
    const auto model = load("f.fll", formula_file(c.formula, "1"));
    ASSERT_TRUE(model) << c.formula;
    EXPECT_NEAR(evaluate_at(*model, 2, 0.5), c.at_a_2 + 1, 1e-15) << c.formula;
  }
}

TEST(RuleFileFunction, MalformedFormulasAreRefusedWithTheReason) {
  const struct {
    std::string formula, why;
  } cases[] = {
      {"- x", "'-' takes 2 operands but has 1"},  // fuzzylite's minus is binary: write .- or ~
      {"x * -1", "'*' takes 2 operands"},
      {"(x + 1", "mismatching parentheses"},
      {"x + 1)", "mismatching parentheses"},
      {"max(1, 2, 3)", "2 values where one expression was expected"},
      {"x b", "2 values where one"},
      {"1, 2", "',' outside the parentheses"},
      {"y + 1", "unknown name 'y'"},
      {"x > 0", "unknown name '>'"},
      {"1e-3 * x", "unknown name '1e'"},  // the exponent's sign is an operator, as in fuzzylite
      {"inf + x", "unknown name 'inf'"},
      {"z + x", "names output 'z'"},
      {"", "needs a formula"},
      {std::string(4097, '1'), "longer than 4096 bytes"},
  };
  for (const auto& c : cases) {
    const std::string e = refusal_of(c.formula);
    EXPECT_NE(e.find("f.fll:4: term 'f': "), std::string::npos) << c.formula << ": " << e;
    EXPECT_NE(e.find(c.why), std::string::npos) << c.formula << ": " << e;
  }
  // 40 nested right operands need 41 values at once: deeper than the evaluation's stack.
  std::string deep = "x";
  for (int k = 0; k < 40; ++k)
    deep = "1 + (" + deep + ")";
  EXPECT_NE(refusal_of(deep).find("needs more than 32 values"), std::string::npos);
  std::string left_deep = "x";  // 300 left-nested operations need 2 values: read
  for (int k = 0; k < 300; ++k)
    left_deep = "(" + left_deep + " + 0.001)";
  const auto model = load("f.fll", formula_file(left_deep, "1"));
  ASSERT_TRUE(model);
  EXPECT_NEAR(evaluate_at(*model, 2, 0), 3.3, 1e-12);
  // The pool holds 4096 steps in all.
  std::string huge = "x";
  for (int k = 0; k < 1100; ++k)
    huge += " + 1";
  EXPECT_NE(refusal_of(huge).find("longer than 4096 bytes"), std::string::npos);
  std::string many = "1";  // 2,999 steps in each of two formulas
  for (int k = 0; k < 1499; ++k)
    many += "+1";
  EXPECT_NE(refusal_of(many, many).find("formulas exceed the capacity (4096 steps"),
            std::string::npos);
  // An output's x is its activation degree, where fuzzylite 6 and 8 differ.
  EXPECT_NE(refusal_of("x", "x + a").find("x in an output's formula"), std::string::npos);
  // A variable named x would hide it (fuzzylite raises when evaluating).
  EXPECT_NE(
      refusal("f.fll", replace(formula_file("x", "a"), "InputVariable: b", "InputVariable: x"))
          .to_string()
          .find("hides the formula's x"),
      std::string::npos);
}

// Formulas over 100,000 seeded random inputs against their closed forms: input terms read x (their
// input's value) and the other inputs, output terms the inputs.
TEST(RuleFileFunction, LoadedFormulasEvaluateToTheirClosedForms) {
  const auto model = load("f.fll", formula_file("exp(~((x - b) ^ 2) / 2) + abs(sin(x * b)) + 0.001",
                                                "a * b - cos(a) / (2 + b) + sqrt(a ^ 2 + 1)"));
  ASSERT_TRUE(model);
  Engine<double> engine(*model);
  std::uint64_t state = 977;  // splitmix64, the same sequence everywhere
  const auto uniform = [&](double lo, double hi) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
  };
  for (int n = 0; n < 100000; ++n) {
    const double in[2] = {uniform(-6, 6), uniform(-2.5, 2.5)};
    const double a = in[0], b = in[1];
    const double mu = std::exp(-std::pow(a - b, 2.0) / 2) + std::fabs(std::sin(a * b)) + 0.001;
    const double g = a * b - std::cos(a) / (2 + b) + std::sqrt(std::pow(a, 2.0) + 1);
    double out[1] = {};
    ASSERT_EQ(engine.evaluate(in, out), Status::Ok);
    ASSERT_NEAR(out[0], mu + g, 1e-12 * (1 + std::fabs(mu + g)))
        << "seed 977, sample " << n << ": a = " << a << ", b = " << b;
  }
}

// A formula that is not finite (a domain error) is a fault: NumericOverflow with the outputs 0.
TEST(RuleFileFunction, ANonFiniteFormulaValueIsNumericOverflow) {
  Status s = Status::Ok;
  const auto input_side = load("f.fll", formula_file("sqrt(x)", "1"));
  ASSERT_TRUE(input_side);
  EXPECT_EQ(evaluate_at(*input_side, 4, 0, &s), 3.0);
  EXPECT_EQ(s, Status::Ok);
  EXPECT_EQ(evaluate_at(*input_side, -1, 0, &s), 0.0);
  EXPECT_EQ(s, Status::NumericOverflow);
  const auto output_side = load("f.fll", formula_file("1", "1 / b"));
  ASSERT_TRUE(output_side);
  EXPECT_EQ(evaluate_at(*output_side, 1, 0.5, &s), 3.0);
  EXPECT_EQ(evaluate_at(*output_side, 1, 0, &s), 0.0);
  EXPECT_EQ(s, Status::NumericOverflow);
}

// .fll and .fcl write formulas back fully parenthesised; they read back to the same steps.
TEST(RuleFileFunction, FormulasRoundTripThroughFllAndFclButNotFis) {
  const auto model =
      load("f.fll", formula_file("(.- x) % 3 + 2 ^ .5 ^ 2 * pi + !(x) - fabs(b) / 1e7",
                                 "round(a / 2) + atan2(b, a) * 0.1 - max(a, b) ** 2"));
  ASSERT_TRUE(model);
  for (const char* ext : {".fll", ".fcl"}) {
    std::string text, error;
    ASSERT_TRUE(ext == std::string(".fll") ? fuzzypid::rulefile::to_fll(*model, text, error)
                                           : fuzzypid::rulefile::to_fcl(*model, text, error))
        << error;
    const auto back = load(std::string("back") + ext, text);
    ASSERT_TRUE(back) << text;
    ASSERT_EQ(back->num_steps, model->num_steps) << text;
    for (std::size_t k = 0; k < model->num_steps; ++k)
      EXPECT_EQ(back->steps[k], model->steps[k]) << ext << " step " << k << "\n" << text;
    for (double a = -5.5; a <= 5.5; a += 0.37)
      EXPECT_EQ(evaluate_at(*back, a, 0.3), evaluate_at(*model, a, 0.3)) << ext << " a = " << a;
  }
  std::string text, error;
  EXPECT_FALSE(fuzzypid::rulefile::to_fis(*model, text, error));
  EXPECT_NE(error.find("input term 'f': 'function' (a fuzzylite formula) is not read from a .fis"),
            std::string::npos)
      << error;
}

TEST(RuleFileFunction, FclReadsFunctionTerms) {
  const auto model = load("f.fcl", R"(FUNCTION_BLOCK f
VAR_INPUT
  a : REAL;
  b : REAL;
END_VAR
VAR_OUTPUT
  z : REAL;
END_VAR
FUZZIFY a
  TERM f := Function max(0, 1 - abs(x - b));
  RANGE := (-5 .. 5);
END_FUZZIFY
FUZZIFY b
  TERM all := Rectangle -1e9 1e9;
END_FUZZIFY
DEFUZZIFY z
  TERM g := Function 2 * a + b;
  METHOD : COGS;
  DEFAULT := 0;
END_DEFUZZIFY
RULEBLOCK rules
  AND : MIN;
  RULE 1 : IF a IS f AND b IS all THEN z IS g;
END_RULEBLOCK
END_FUNCTION_BLOCK
)");
  ASSERT_TRUE(model);
  EXPECT_DOUBLE_EQ(evaluate_at(*model, 1.0, 0.5), 2.5);  // one rule: z = g = 2 a + b
  Engine<double> engine(*model);
  const double in[2] = {1.0, 0.5};
  double out[1] = {};
  ASSERT_EQ(engine.evaluate(in, out), Status::Ok);
  EXPECT_DOUBLE_EQ(engine.rule_strength(0), 0.5);  // mu_f(1) = 1 - |1 - 0.5|
}

TEST(RuleFileFunction, FisFunctionTermsAreRefusedWithTheReason) {
  const std::string e = refusal("f.fis", corpus_file("refuse_function_mf.fis")).to_string();
  EXPECT_NE(e.find("fuzzylite's FisImporter removes its blanks"), std::string::npos) << e;
  EXPECT_NE(e.find("write Function terms in .fll or .fcl"), std::string::npos) << e;
}

TEST(RuleFileFunction, AFunctionTermOfAMamdaniOutputIsRefused) {
  std::string text = formula_file("x", "a");
  text = replace(text, "WeightedSum TakagiSugeno", "Centroid 100");
  text = replace(text, "aggregation: none", "aggregation: Maximum");
  text = replace(text, "implication: none", "implication: Minimum");
  text = replace(text, "term: one Constant 1", "term: one Triangle 0 1 2");
  const std::string e = refusal("f.fll", text).to_string();
  EXPECT_NE(e.find("output 'z': integral defuzzifiers need membership terms, not "
                   "constant/linear/function ones"),
            std::string::npos)
      << e;
}

// mu(z) = w has no solution for a term of height 0 (fuzzylite 8 divides by it: inf or NaN).
TEST(RuleFileTsukamoto, ATermOfHeightZeroIsRefusedAtLoad) {
  const std::string e = refusal("t.fll", R"(Engine: t
InputVariable: a
  range: 0 1
  term: lo Ramp 1 0
OutputVariable: z
  range: 0 1
  aggregation: none
  defuzzifier: WeightedAverage Tsukamoto
  default: nan
  term: up Ramp 0 1 0
RuleBlock: rules
  implication: none
  rule: if a is lo then z is up
)")
                            .to_string();
  EXPECT_NE(e.find("t.fll:5: output 'z': a Tsukamoto term needs a height > 0"), std::string::npos)
      << e;
}

}  // namespace
