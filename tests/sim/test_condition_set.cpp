// Condition-set files (fuzzypid/sim/condition_set.hpp): the shipped tuning/robust.toml, Monte-Carlo
// draws, scenario shorthands, and file:line:column errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzzypid/sim/condition_set.hpp"

namespace {

using fuzzypid::sim::Condition;
using fuzzypid::sim::ConditionFile;
using fuzzypid::sim::load_conditions;
using fuzzypid::sim::parse_conditions;

TEST(ConditionSets, TheShippedFileHasTrainingHeldOutAndStressSets) {
  ConditionFile f;
  fuzzypid::FileError e;
  ASSERT_TRUE(load_conditions(FUZZYPID_SOURCE_DIR "/tuning/robust.toml", f, e)) << e.to_string();
  ASSERT_NE(f.find("training"), nullptr);
  ASSERT_NE(f.find("held-out"), nullptr);
  ASSERT_NE(f.find("stress"), nullptr);
  const auto& all = f.find("training")->conditions;
  // Six fixed conditions, then eight draws from the same envelope (the last four are held back
  // for validation by `fuzzypid tune --validation 4`).
  ASSERT_EQ(all.size(), 14u);
  for (std::size_t k = 6; k < all.size(); ++k) {
    EXPECT_GE(all[k].payload_scale, 0.5);
    EXPECT_LE(all[k].payload_scale, 2.0);
    EXPECT_LE(std::abs(all[k].initial_error_rad), 0.08);
    EXPECT_EQ(all[k].friction_per_s, 0.0);
  }
  const std::vector<fuzzypid::sim::Condition> training(all.begin(), all.begin() + 6);
  int ahead = 0, light = 0, heavy = 0;
  for (const auto& c : training) {
    ahead += c.initial_error_rad < 0 ? 1 : 0;
    light += c.payload_scale < 1 ? 1 : 0;
    heavy += c.payload_scale > 1 ? 1 : 0;
    EXPECT_EQ(c.friction_per_s, 0.0);
    EXPECT_FALSE(c.reverse);
  }
  EXPECT_EQ(ahead, 3);
  EXPECT_EQ(light, 2);
  EXPECT_EQ(heavy, 2);
  EXPECT_EQ(f.find("held-out")->conditions.size(), 21u);
}

TEST(ConditionSets, MonteCarloDrawsAreSeededAndInsideTheirRanges) {
  const char* text =
      "[sets.mc.monte_carlo]\ncount = 50\nseed = 9\npayload_scale = [0.5, 2.0]\n"
      "friction = [0.0, 2.0]\ninitial_error = [-0.08, 0.08]\n";
  ConditionFile a, b, c;
  fuzzypid::FileError e;
  ASSERT_TRUE(parse_conditions(text, "mc.toml", a, e)) << e.to_string();
  ASSERT_TRUE(parse_conditions(text, "mc.toml", b, e)) << e.to_string();
  const auto& da = a.find("mc")->conditions;
  ASSERT_EQ(da.size(), 50u);
  for (std::size_t k = 0; k < da.size(); ++k) {
    EXPECT_EQ(da[k].payload_scale, b.find("mc")->conditions[k].payload_scale);
    EXPECT_GE(da[k].payload_scale, 0.5);
    EXPECT_LE(da[k].payload_scale, 2.0);
    EXPECT_GE(da[k].friction_per_s, 0.0);
    EXPECT_LE(da[k].friction_per_s, 2.0);
    EXPECT_GE(da[k].initial_error_rad, -0.08);
    EXPECT_LE(da[k].initial_error_rad, 0.08);
  }
  EXPECT_EQ(da[0].name, "mc-mc001");
  std::string other = text;
  other.replace(other.find("seed = 9"), 8, "seed = 8");
  ASSERT_TRUE(parse_conditions(other, "mc.toml", c, e)) << e.to_string();
  EXPECT_NE(da[0].payload_scale, c.find("mc")->conditions[0].payload_scale);
}

// payload_kg and the keys of what real joints have are drawn from [min, max] from a stream of
// their own: the payload-scale, friction and start-error draws stay as without them.
TEST(ConditionSets, MonteCarloDrawsPayloadKgAndJointEffectsWithoutChangingTheOtherDraws) {
  const std::string plain =
      "[sets.mc.monte_carlo]\ncount = 40\nseed = 9\npayload_scale = [0.5, 2.0]\n"
      "friction = [0.0, 2.0]\ninitial_error = [-0.08, 0.08]\n";
  const std::string with = plain +
                           "payload_kg = [0.0, 5.0]\ndelay_ms = [0.0, 20.0]\n"
                           "encoder_counts = [4096, 65536]\ncoulomb_nm = [0.0, 10.0]\n"
                           "joint_resonance_hz = [15.0, 30.0]\njoint_damping_ratio = 0.05\n";
  ConditionFile a, b, again;
  fuzzypid::FileError e;
  ASSERT_TRUE(parse_conditions(plain, "mc.toml", a, e)) << e.to_string();
  ASSERT_TRUE(parse_conditions(with, "mc.toml", b, e)) << e.to_string();
  ASSERT_TRUE(parse_conditions(with, "mc.toml", again, e)) << e.to_string();
  const auto& da = a.sets[0].conditions;
  const auto& db = b.sets[0].conditions;
  ASSERT_EQ(db.size(), 40u);
  double lo = 1e9, hi = -1e9;
  for (std::size_t k = 0; k < db.size(); ++k) {
    EXPECT_EQ(db[k].payload_scale, da[k].payload_scale);
    EXPECT_EQ(db[k].friction_per_s, da[k].friction_per_s);
    EXPECT_EQ(db[k].initial_error_rad, da[k].initial_error_rad);
    EXPECT_EQ(db[k].effects, again.sets[0].conditions[k].effects);  // seeded
    const fuzzypid::sim::JointEffects& x = db[k].effects;
    EXPECT_GE(db[k].payload_kg, 0.0);
    EXPECT_LE(db[k].payload_kg, 5.0);
    EXPECT_GE(x.delay_s, 0.0);
    EXPECT_LE(x.delay_s, 20e-3);
    EXPECT_GE(x.encoder_counts, 4096u);
    EXPECT_LE(x.encoder_counts, 65536u);
    EXPECT_GE(x.coulomb_nm[0], 0.0);
    EXPECT_LE(x.coulomb_nm[0], 10.0);
    EXPECT_EQ(x.coulomb_nm[5], x.coulomb_nm[0]);  // one draw for every joint
    EXPECT_GE(x.joint_resonance_hz[2], 15.0);
    EXPECT_LE(x.joint_resonance_hz[2], 30.0);
    EXPECT_EQ(x.joint_damping_ratio, 0.05);  // a number sets it
    lo = std::min(lo, x.delay_s);
    hi = std::max(hi, x.delay_s);
  }
  EXPECT_GT(hi - lo, 10e-3);  // the draws spread over the range
  EXPECT_NE(db[0].payload_kg, db[1].payload_kg);
}

// Which of `count` equal strata of [lo, hi] v lies in (log-uniform ranges on log v).
std::size_t stratum_of(double v, double lo, double hi, std::size_t count, bool log_scale) {
  const double f = log_scale ? std::log(v / lo) / std::log(hi / lo) : (v - lo) / (hi - lo);
  return std::min(count - 1, static_cast<std::size_t>(std::floor(f * static_cast<double>(count))));
}

TEST(ConditionSets, LatinHypercubeDrawsPutOneDrawInEachStratumOfEveryRange) {
  struct Key {
    const char* name;
    double lo, hi;
    bool log_scale;
    double (*of)(const fuzzypid::sim::Condition&);
  };
  const Key keys[] = {
      {"payload_scale", 0.5, 2.0, true, [](const auto& c) { return c.payload_scale; }},
      {"friction", 0.0, 2.0, false, [](const auto& c) { return c.friction_per_s; }},
      {"initial_error", -0.08, 0.08, false, [](const auto& c) { return c.initial_error_rad; }},
      {"payload_kg", 0.0, 5.0, false, [](const auto& c) { return c.payload_kg; }},
      {"delay_ms", 0.0, 50.0, false, [](const auto& c) { return c.effects.delay_s * 1e3; }},
      {"torque_bandwidth_hz", 20.0, 100.0, false,
       [](const auto& c) { return c.effects.torque_bandwidth_hz; }},
      {"coulomb_nm", 0.0, 10.0, false, [](const auto& c) { return c.effects.coulomb_nm[3]; }},
      {"joint_resonance_hz", 8.0, 20.0, false,
       [](const auto& c) { return c.effects.joint_resonance_hz[0]; }},
      {"joint_damping_ratio", 0.01, 0.1, false,
       [](const auto& c) { return c.effects.joint_damping_ratio; }},
  };
  for (std::uint64_t seed = 1; seed <= 25; ++seed) {
    for (const std::size_t count : {1u, 2u, 5u, 8u, 13u}) {
      std::string text = "[sets.mc.monte_carlo]\ncount = " + std::to_string(count) +
                         "\nseed = " + std::to_string(seed) + "\nsampling = \"latin-hypercube\"\n";
      for (const Key& k : keys)
        text += std::string(k.name) + " = [" + std::to_string(k.lo) + ", " + std::to_string(k.hi) +
                "]\n";
      ConditionFile f;
      fuzzypid::FileError e;
      ASSERT_TRUE(parse_conditions(text, "mc.toml", f, e)) << e.to_string();
      const auto& draws = f.sets[0].conditions;
      ASSERT_EQ(draws.size(), count);
      for (const Key& k : keys) {
        std::vector<std::size_t> strata;
        for (const auto& c : draws) {
          EXPECT_GE(k.of(c), k.lo) << k.name;
          EXPECT_LE(k.of(c), k.hi) << k.name;
          strata.push_back(stratum_of(k.of(c), k.lo, k.hi, count, k.log_scale));
        }
        std::sort(strata.begin(), strata.end());
        for (std::size_t i = 0; i < count; ++i)
          EXPECT_EQ(strata[i], i) << k.name << ", seed " << seed << ", " << count << " draws";
      }
    }
  }
}

TEST(ConditionSets, LatinHypercubeDrawsAreSeededAndRandomSamplingIsTheDefault) {
  const std::string ranges =
      "count = 12\npayload_scale = [0.5, 2.0]\nfriction = [0.0, 2.0]\n"
      "initial_error = [-0.08, 0.08]\ndelay_ms = [0.0, 50.0]\njoint_resonance_hz = [8.0, 20.0]\n";
  const auto parse = [&](const std::string& extra) {
    ConditionFile f;
    fuzzypid::FileError e;
    EXPECT_TRUE(parse_conditions("[sets.mc.monte_carlo]\n" + ranges + extra, "mc.toml", f, e))
        << e.to_string();
    return f.sets.at(0).conditions;
  };
  const auto same = [](const auto& a, const auto& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k)
      if (a[k].payload_scale != b[k].payload_scale || a[k].friction_per_s != b[k].friction_per_s ||
          a[k].initial_error_rad != b[k].initial_error_rad || a[k].effects != b[k].effects)
        return false;
    return true;
  };
  const auto plain = parse("seed = 3\n");
  EXPECT_TRUE(same(plain, parse("seed = 3\nsampling = \"random\"\n")));
  const auto lhs = parse("seed = 3\nsampling = \"latin-hypercube\"\n");
  EXPECT_TRUE(same(lhs, parse("seed = 3\nsampling = \"latin-hypercube\"\n")));
  EXPECT_FALSE(same(lhs, plain));
  EXPECT_FALSE(same(lhs, parse("seed = 4\nsampling = \"latin-hypercube\"\n")));
}

TEST(ConditionSets, AScenarioIsAShorthandTheOtherKeysOverride) {
  ConditionFile f;
  fuzzypid::FileError e;
  ASSERT_TRUE(parse_conditions(
      "[sets.s]\nconditions = [ { name = \"c\", scenario = \"deburring\", initial_error = -0.02,"
      " noise = [1e-4, 2e-3], reverse = true } ]\n",
      "s.toml", f, e))
      << e.to_string();
  const auto& c = f.find("s")->conditions.at(0);
  EXPECT_EQ(c.contact_rad_s2, 0.5);
  EXPECT_EQ(c.initial_error_rad, -0.02);
  EXPECT_EQ(c.noise_velocity_rad_s, 2e-3);
  EXPECT_TRUE(c.reverse);
}

struct Bad {
  const char* text;
  int line;
  int column;
  const char* message;
};

TEST(ConditionSets, MalformedFilesAreRejectedWithLineAndColumn) {
  const Bad cases[] = {
      {"[sets.s]\nconditions = [ { name = \"c\", mass = 2.0 } ]\n", 2, 30, "unknown key 'mass'"},
      {"[sets.s]\nconditions = [ { name = \"c\", payload_scale = -1.0 } ]\n", 2, 16,
       "payload_scale must be within 0.001 .. 1000"},
      // The command line's ranges hold in files too (sim/condition.hpp, FieldRange).
      {"[sets.s]\nconditions = [ { name = \"c\", payload_scale = 1e6 } ]\n", 2, 16,
       "payload_scale must be within 0.001 .. 1000"},
      {"[sets.s]\nconditions = [ { name = \"c\", noise = [1e300, 0.0] } ]\n", 2, 16,
       "noise[0] must be within 0 .. 1"},
      {"[sets.s]\nconditions = [ { name = \"c\", friction = 1e5 } ]\n", 2, 16,
       "friction must be within 0 .. 10000"},
      {"[sets.s]\nconditions = [ { name = \"c\", friction = nan } ]\n", 2, 41, "NaN"},
      {"[sets.s]\nconditions = [ { name = \"c\" }, { name = \"c\" } ]\n", 2, 32, "duplicate"},
      // Outputs key their rows by condition name: a name is unique across sets, drawn ones too.
      {"[sets.a]\nconditions = [ { name = \"c\" } ]\n[sets.b]\nconditions = [ { name = \"c\" } ]\n",
       4, 16, "duplicate condition name 'c' (set 'a' has it too)"},
      {"[sets.a]\nconditions = [ { name = \"b-mc001\" } ]\n[sets.b.monte_carlo]\ncount = 1\nseed = "
       "1\n",
       3, 1, "duplicate condition name 'b-mc001' (set 'a' has it too)"},
      {"[sets.s]\nconditions = [ { name = \"c\", scenario = \"moon\" } ]\n", 2, 41,
       "unknown scenario 'moon'"},
      {"[sets.s.monte_carlo]\ncount = 3\nseed = 1\nfriction = [2.0, 1.0]\n", 4, 12, "reversed"},
      {"[sets.s.monte_carlo]\ncount = 3\nseed = 1\nsampling = \"sobol\"\n", 4, 12,
       "'sampling': unknown value 'sobol' (expected random|latin-hypercube)"},
      {"[sets.s.monte_carlo]\ncount = 3\nseed = 1\ncoulomb_smoothing = [0.01, 0.02]\n", 4, 21,
       "coulomb_smoothing"},
      {"[sets.s]\ndescription = \"empty\"\n", 1, 1, "has no conditions"},
      // What real joints have: 0 (off, or the plant's default: the message says which) or within
      // the key's range, NaN refused.
      {"[sets.s]\nconditions = [ { name = \"c\", plant_step_ms = -1.0 } ]\n", 2, 46,
       "'plant_step_ms' must be 0 (the default step) or within 0.001 .. 1000"},
      {"[sets.s]\nconditions = [ { name = \"c\", plant_step_ms = nan } ]\n", 2, 46, "NaN"},
      {"[sets.s]\nconditions = [ { name = \"c\", delay_ms = -1.0 } ]\n", 2, 41,
       "'delay_ms' must be 0 (none) or within 0 .. 1000"},
      {"[sets.s]\nconditions = [ { name = \"c\", delay_ms = 3001.0 } ]\n", 2, 41,
       "'delay_ms' must be 0 (none) or within 0 .. 1000"},
      {"[sets.s]\nconditions = [ { name = \"c\", tick_ms = 1.0, delay_ms = 61.0 } ]\n", 2, 16,
       "delay_ms must be at most 60 ticks (60 ms at this tick)"},
      {"[sets.s]\nconditions = [ { name = \"c\", torque_bandwidth_hz = 0.01 } ]\n", 2, 52,
       "'torque_bandwidth_hz' must be 0 (ideal) or within 0.1 .. 100000"},
      {"[sets.s]\nconditions = [ { name = \"c\", encoder_counts = 2 } ]\n", 2, 47,
       "'encoder_counts' must be 0 (exact) or within 4 .. 1e+12"},
      {"[sets.s]\nconditions = [ { name = \"c\", encoder_counts = 1.5 } ]\n", 2, 47,
       "non-negative integer"},
      {"[sets.s]\nconditions = [ { name = \"c\", coulomb_nm = -1.0 } ]\n", 2, 43,
       "'coulomb_nm' values must be within 0 .. 1e+06"},
      {"[sets.s]\nconditions = [ { name = \"c\", coulomb_nm = [1.0, 2.0] } ]\n", 2, 43,
       "'coulomb_nm' must be one number or list 6, found 2"},
      {"[sets.s]\nconditions = [ { name = \"c\", stribeck_nm = [1, 2, 3, 4, 5, nan] } ]\n", 2, 60,
       "NaN"},
      {"[sets.s]\nconditions = [ { name = \"c\", stribeck_velocity = -0.1 } ]\n", 2, 50,
       "'stribeck_velocity' must be 0 (the plant's default) or within 1e-05 .. 100"},
      {"[sets.s]\nconditions = [ { name = \"c\", coulomb_smoothing = 2.0 } ]\n", 2, 50,
       "'coulomb_smoothing' must be 0 (the plant's default) or within 1e-05 .. 1"},
      {"[sets.s]\nconditions = [ { name = \"c\", joint_resonance_hz = -20.0 } ]\n", 2, 51,
       "'joint_resonance_hz' values must be within 0 .. 10000"},
      {"[sets.s]\nconditions = [ { name = \"c\", joint_damping_ratio = 11.0 } ]\n", 2, 52,
       "'joint_damping_ratio' must be 0 (undamped) or within 0 .. 10"},
      // The robot and plant keys' ranges, from the same table as the options'.
      {"[sets.s]\nconditions = [ { name = \"c\", tick_ms = 0.05 } ]\n", 2, 40,
       "'tick_ms' must be within 0.1 .. 1000"},
      {"[sets.s]\nconditions = [ { name = \"c\", payload_kg = 2e4 } ]\n", 2, 43,
       "'payload_kg' must be within 0 .. 10000"},
      {"[sets.s]\nconditions = [ { name = \"c\", armature = [1, 1, 1, 1, 1, 2e6] } ]\n", 2, 57,
       "'armature' values must be within 0 .. 1e+06 kg·m²"},
  };
  for (const Bad& b : cases) {
    ConditionFile f;
    fuzzypid::FileError e;
    EXPECT_FALSE(parse_conditions(b.text, "bad.toml", f, e)) << b.text;
    EXPECT_EQ(e.line, b.line) << b.text << e.to_string();
    EXPECT_EQ(e.column, b.column) << b.text << e.to_string();
    EXPECT_NE(e.message.find(b.message), std::string::npos) << e.to_string();
  }
}

// "" never stands for the default: `urdf = ""` would run the bundled robot, `tip_link = ""` the
// end of the unique chain, as if the key were absent. Every string key refuses it, by name.
TEST(ConditionSets, AnEmptyStringIsRefusedNamingTheKey) {
  const Bad cases[] = {
      {"[sets.s]\nurdf = \"\"\nconditions = [ { name = \"c\" } ]\n", 2, 8, "'urdf' is empty"},
      {"[sets.s]\ntip_link = \"\"\nconditions = [ { name = \"c\" } ]\n", 2, 12,
       "'tip_link' is empty"},
      {"[sets.s]\nconditions = [ { name = \"c\", base_link = \"\" } ]\n", 2, 42,
       "'base_link' is empty"},
      {"[sets.s]\nconditions = [ { name = \"c\", path = \"\" } ]\n", 2, 37, "'path' is empty"},
      {"[sets.s]\nconditions = [ { name = \"\" } ]\n", 2, 25, "'name' is empty"},
  };
  for (const Bad& b : cases) {
    ConditionFile f;
    fuzzypid::FileError e;
    EXPECT_FALSE(parse_conditions(b.text, "bad.toml", f, e)) << b.text;
    EXPECT_EQ(e.line, b.line) << b.text << e.to_string();
    EXPECT_EQ(e.column, b.column) << b.text << e.to_string();
    EXPECT_NE(e.message.find(b.message), std::string::npos) << e.to_string();
  }
}

TEST(ConditionSets, JointEffectKeysSetTheirFieldsInSIUnitsForSetsAndScenarios) {
  const char* text =
      "[sets.s]\nplant_step_ms = 0.25\nconditions = [ { name = \"a\" }, { name = \"b\", "
      "scenario = \"friction\" }, { name = \"c\", plant_step_ms = 0.0 } ]\n";
  ConditionFile f;
  fuzzypid::FileError e;
  ASSERT_TRUE(parse_conditions(text, "effects.toml", f, e)) << e.to_string();
  const auto& c = f.sets[0].conditions;
  ASSERT_EQ(c.size(), 3u);
  EXPECT_DOUBLE_EQ(c[0].effects.plant_step_s, 0.25e-3);
  EXPECT_DOUBLE_EQ(c[1].effects.plant_step_s, 0.25e-3);  // a scenario keeps the set's effects
  EXPECT_EQ(c[2].effects.plant_step_s, 0.0);

  const char* all =
      "[sets.s]\nconditions = [ { name = \"a\", delay_ms = 12.5, torque_bandwidth_hz = 150.0, "
      "encoder_counts = 131072, coulomb_nm = [1, 2, 3, 4, 5, 6], stribeck_nm = 9.0, "
      "stribeck_velocity = 0.02, coulomb_smoothing = 0.03, joint_resonance_hz = [20, 20, 30, 0, 0, "
      "0], "
      "joint_damping_ratio = 0.05 } ]\n";
  ASSERT_TRUE(parse_conditions(all, "effects.toml", f, e)) << e.to_string();
  const fuzzypid::sim::JointEffects& x = f.sets[0].conditions[0].effects;
  EXPECT_DOUBLE_EQ(x.delay_s, 12.5e-3);
  EXPECT_EQ(x.torque_bandwidth_hz, 150.0);
  EXPECT_EQ(x.encoder_counts, 131072u);
  EXPECT_EQ(x.coulomb_nm, (fuzzypid::robot::JointVector{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(x.stribeck_nm, (fuzzypid::robot::JointVector{9, 9, 9, 9, 9, 9}));
  EXPECT_EQ(x.stribeck_velocity_rad_s, 0.02);
  EXPECT_EQ(x.coulomb_smoothing_rad_s, 0.03);
  EXPECT_EQ(x.joint_resonance_hz, (fuzzypid::robot::JointVector{20, 20, 30, 0, 0, 0}));
  EXPECT_EQ(x.joint_damping_ratio, 0.05);
}

// Payload and friction are independent draws: with payload_scale in [1, 2] (log-uniform) and
// friction in [0, 1] (uniform), friction = log2(payload) on every draw would mean one number
// drives both.
TEST(ConditionSets, MonteCarloPayloadAndFrictionAreIndependentDraws) {
  const char* text =
      "[sets.mc.monte_carlo]\ncount = 20\nseed = 3\npayload_scale = [1.0, 2.0]\n"
      "friction = [0.0, 1.0]\ninitial_error = [0.0, 1.0]\n";
  ConditionFile f;
  fuzzypid::FileError e;
  ASSERT_TRUE(parse_conditions(text, "mc.toml", f, e)) << e.to_string();
  std::size_t coupled_friction = 0, coupled_initial = 0;
  for (const auto& c : f.find("mc")->conditions) {
    const double u_payload = std::log2(c.payload_scale);
    if (std::fabs(c.friction_per_s - u_payload) < 1e-9) ++coupled_friction;
    if (std::fabs(c.initial_error_rad - u_payload) < 1e-9) ++coupled_initial;
  }
  EXPECT_EQ(coupled_friction, 0u);
  EXPECT_EQ(coupled_initial, 0u);
  // Friction and the initial error, both drawn on [0, 1], are independent of each other too.
  std::size_t initial_is_friction = 0;
  for (const auto& c : f.find("mc")->conditions)
    if (std::fabs(c.initial_error_rad - c.friction_per_s) < 1e-9) ++initial_is_friction;
  EXPECT_EQ(initial_is_friction, 0u);
}

// A condition built on a scenario still runs on its set's robot: the set's robot keys (here
// coupled dynamics with gravity) are not the scenario's defaults.
TEST(ConditionSets, AScenarioKeepsTheSetsRobotDynamicsAndGravity) {
  ConditionFile f;
  fuzzypid::FileError e;
  ASSERT_TRUE(
      parse_conditions("[sets.s]\ndynamics = \"coupled\"\ngravity = true\npayload_kg = 3.0\n"
                       "conditions = [ { name = \"c\", scenario = \"deburring\" } ]\n",
                       "s.toml", f, e))
      << e.to_string();
  const auto& c = f.find("s")->conditions.at(0);
  EXPECT_EQ(c.contact_rad_s2, 0.5);  // the scenario's
  EXPECT_EQ(c.dynamics, fuzzypid::robot::PlantCoupling::Coupled);
  EXPECT_TRUE(c.gravity);
  EXPECT_EQ(c.payload_kg, 3.0);
}

TEST(ConditionSets, AUsersUrdfRunsCoupledWithGravityUnlessTheFileSaysOtherwise) {
  using fuzzypid::robot::PlantCoupling;
  // The file's own URDF name is never opened by the parser: only the keys are read here.
  const std::string text = R"(
[sets.a]
urdf = "arm.urdf"
conditions = [
  { name = "default" },
  { name = "decoupled", dynamics = "decoupled" },
  { name = "no-gravity", gravity = false },
  { name = "scenario", scenario = "payload-heavy" },
]
monte_carlo = { count = 2, seed = 1 }
[sets.b]
urdf = "arm.urdf"
dynamics = "decoupled"
conditions = [ { name = "inherited" }, { name = "own", dynamics = "coupled" } ]
[sets.paper]
conditions = [ { name = "bundled" }, { name = "bundled-coupled", dynamics = "coupled" } ]
)";
  ConditionFile f;
  fuzzypid::FileError e;
  ASSERT_TRUE(parse_conditions(text, "plants.toml", f, e)) << e.to_string();
  const auto& a = f.find("a")->conditions;
  ASSERT_EQ(a.size(), 6u);
  for (std::size_t k : {0u, 3u, 4u, 5u}) {  // defaults, a scenario, the Monte-Carlo draws
    EXPECT_EQ(a[k].dynamics, PlantCoupling::Coupled) << a[k].name;
    EXPECT_TRUE(a[k].gravity) << a[k].name;
  }
  EXPECT_EQ(a[1].dynamics, PlantCoupling::Decoupled);
  EXPECT_FALSE(a[1].gravity);
  EXPECT_EQ(a[2].dynamics, PlantCoupling::Coupled);
  EXPECT_FALSE(a[2].gravity);
  const auto& b = f.find("b")->conditions;
  EXPECT_EQ(b[0].dynamics, PlantCoupling::Decoupled);  // the set's key, not the robot's default
  EXPECT_FALSE(b[0].gravity);
  EXPECT_EQ(b[1].dynamics, PlantCoupling::Coupled);
  EXPECT_TRUE(b[1].gravity);
  // The bundled ER50-C20 keeps the paper's plant, coupled or not.
  const auto& paper = f.find("paper")->conditions;
  EXPECT_EQ(paper[0].dynamics, PlantCoupling::Decoupled);
  EXPECT_FALSE(paper[0].gravity);
  EXPECT_EQ(paper[1].dynamics, PlantCoupling::Coupled);
  EXPECT_FALSE(paper[1].gravity);
}

// Loads a shipped drive condition file, which has a training, a held-out and a stress set.
void load_drive_file(const char* path, ConditionFile& f) {
  fuzzypid::FileError e;
  ASSERT_TRUE(load_conditions(path, f, e)) << e.to_string();
  for (const char* set : {"training", "held-out", "stress"})
    ASSERT_NE(f.find(set), nullptr) << set;
}

int coulomb_conditions(const ConditionFile& f, const char* set) {
  int n = 0;
  for (const auto& c : f.find(set)->conditions)
    n += c.effects.coulomb_nm[0] > 0.0 ? 1 : 0;
  return n;
}

// The training envelope has in kind what the held-out set has, Coulomb friction aside: the path
// run backwards and viscous friction.
void expect_backwards_and_friction(const ConditionFile& f) {
  for (const char* set : {"training", "held-out"}) {
    const auto& cs = f.find(set)->conditions;
    EXPECT_GE(std::count_if(cs.begin(), cs.end(), [](const auto& c) { return c.reverse; }), 2)
        << set;
    EXPECT_GE(
        std::count_if(cs.begin(), cs.end(), [](const auto& c) { return c.friction_per_s > 0.0; }),
        2)
        << set;
  }
}

double longest_delay_s(const ConditionFile& f, const char* set) {
  double longest = 0.0;
  for (const auto& c : f.find(set)->conditions)
    longest = std::max(longest, c.effects.delay_s);
  return longest;
}

// tuning/robust_drive.toml: robust.toml's sets with what real joints have; every training
// condition has one tick of delay or less, a current loop, a gear and an encoder, and the stress
// set goes beyond one tick.
TEST(ConditionSets, TheDriveFileTrainsOnRealJointsWithinOneTickOfDelay) {
  ConditionFile f;
  ASSERT_NO_FATAL_FAILURE(load_drive_file(FUZZYPID_SOURCE_DIR "/tuning/robust_drive.toml", f));
  const auto& training = f.find("training")->conditions;
  ASSERT_EQ(training.size(), 16u);
  for (const auto& c : training) {
    EXPECT_LE(c.effects.delay_s, 0.05 + 1e-12) << c.name;
    EXPECT_GE(c.effects.torque_bandwidth_hz, 20.0) << c.name;
    EXPECT_GE(c.effects.joint_resonance_hz[0], 8.0) << c.name;
    EXPECT_EQ(c.effects.encoder_counts, 131072u) << c.name;
  }
  // Coulomb friction only in held-out: it is the plant's stiffest term (the file says why).
  EXPECT_EQ(coulomb_conditions(f, "training"), 0);
  EXPECT_GE(coulomb_conditions(f, "held-out"), 1);
  EXPECT_GT(longest_delay_s(f, "stress"), 0.05);
  expect_backwards_and_friction(f);
}

bool same_condition(const Condition& a, const Condition& b) {
  return a.name == b.name && a.payload_scale == b.payload_scale &&
         a.friction_per_s == b.friction_per_s && a.torque_limit_rad_s2 == b.torque_limit_rad_s2 &&
         a.contact_rad_s2 == b.contact_rad_s2 && a.noise_position_rad == b.noise_position_rad &&
         a.noise_velocity_rad_s == b.noise_velocity_rad_s && a.seed == b.seed &&
         a.reverse == b.reverse && a.initial_error_rad == b.initial_error_rad &&
         a.robot == b.robot && a.payload_kg == b.payload_kg && a.dynamics == b.dynamics &&
         a.gravity == b.gravity && a.effects == b.effects;
}

void expect_same_conditions(const std::vector<Condition>& a, const std::vector<Condition>& b,
                            const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_TRUE(same_condition(a[i], b[i])) << what << ": " << a[i].name << " / " << b[i].name;
}

// A drive file with the first three conditions of its soft-gears set moved into training after its
// `listed` named conditions, before the seeded draws: the draws -- and the four that --validation
// 4 holds back -- are the drive file's, and so is every set it is judged on.
void expect_soft_corners_in_training(const char* drive_path, const char* soft_path,
                                     std::size_t listed) {
  ConditionFile drive;
  ConditionFile soft;
  ASSERT_NO_FATAL_FAILURE(load_drive_file(drive_path, drive));
  ASSERT_NO_FATAL_FAILURE(load_drive_file(soft_path, soft));
  const auto& corners = drive.find("soft-gears")->conditions;
  ASSERT_EQ(corners.size(), 5u);
  std::vector<Condition> expected = drive.find("training")->conditions;
  ASSERT_GT(expected.size(), listed);
  expected.insert(expected.begin() + static_cast<std::ptrdiff_t>(listed), corners.begin(),
                  corners.begin() + 3);
  expect_same_conditions(soft.find("training")->conditions, expected, "training");
  expect_same_conditions(soft.find("soft-gears")->conditions,
                         std::vector<Condition>(corners.begin() + 3, corners.end()), "soft-gears");
  ASSERT_EQ(soft.set_names(), drive.set_names());
  for (const auto& set : drive.sets)
    if (set.name != "training" && set.name != "soft-gears")
      expect_same_conditions(soft.find(set.name)->conditions, set.conditions, set.name);
}

// tuning/robust_drive_soft.toml (the ER50's trials 7 to 10; trial 10's fixed PID is shipped).
TEST(ConditionSets, TheSoftGearDriveFileIsTheDriveFileWithTheSoftCornersInTraining) {
  expect_soft_corners_in_training(FUZZYPID_SOURCE_DIR "/tuning/robust_drive.toml",
                                  FUZZYPID_SOURCE_DIR "/tuning/robust_drive_soft.toml", 8);
}

// tuning/ur5_class_drive_soft.toml (the UR5-class trials on the soft end of its ranges).
TEST(ConditionSets, TheUr5SoftGearDriveFileIsTheUr5DriveFileWithTheSoftEndInTraining) {
  expect_soft_corners_in_training(FUZZYPID_SOURCE_DIR "/tuning/ur5_class_drive.toml",
                                  FUZZYPID_SOURCE_DIR "/tuning/ur5_class_drive_soft.toml", 6);
}

// The Monte-Carlo draws of a file stay as they were when a key is added: the effects' stream takes
// one draw per drawn key and condition, so a new key on that list would move every later draw
// (and every result tuned or documented on them). Pinned: held-out-mc007 of the drive file.
TEST(ConditionSets, MonteCarloDrawsOfTheDriveFileStayAsTheyWere) {
  ConditionFile f;
  ASSERT_NO_FATAL_FAILURE(load_drive_file(FUZZYPID_SOURCE_DIR "/tuning/robust_drive.toml", f));
  const auto& held_out = f.find("held-out")->conditions;
  const auto c = std::find_if(held_out.begin(), held_out.end(),
                              [](const auto& x) { return x.name == "held-out-mc007"; });
  ASSERT_NE(c, held_out.end());
  EXPECT_DOUBLE_EQ(c->payload_scale, 0.51814819265665879);
  EXPECT_DOUBLE_EQ(c->effects.delay_s, 37.958860907778885e-3);
  EXPECT_DOUBLE_EQ(c->effects.torque_bandwidth_hz, 62.140073074221043);
  EXPECT_DOUBLE_EQ(c->effects.joint_resonance_hz[0], 19.002648324714425);
}

// tuning/ur5_class_drive.toml: the UR5-class sets with a real joint's effects, one 10 ms tick of
// delay or less in training, Coulomb friction in held-out only, more than a tick in stress.
TEST(ConditionSets, TheUr5DriveFileTrainsWithinOneTickOfDelay) {
  ConditionFile f;
  ASSERT_NO_FATAL_FAILURE(load_drive_file(FUZZYPID_SOURCE_DIR "/tuning/ur5_class_drive.toml", f));
  const auto& training = f.find("training")->conditions;
  ASSERT_EQ(training.size(), 12u);
  for (const auto& c : training) {
    EXPECT_LE(c.effects.delay_s, 0.01 + 1e-12) << c.name;
    EXPECT_GE(c.effects.torque_bandwidth_hz, 50.0) << c.name;
    EXPECT_GE(c.effects.joint_resonance_hz[0], 15.0) << c.name;
    EXPECT_EQ(c.effects.encoder_counts, 131072u) << c.name;
  }
  EXPECT_EQ(coulomb_conditions(f, "training"), 0);
  EXPECT_EQ(coulomb_conditions(f, "held-out"), 2);
  EXPECT_GT(longest_delay_s(f, "stress"), 0.01);
  expect_backwards_and_friction(f);
}

}  // namespace
