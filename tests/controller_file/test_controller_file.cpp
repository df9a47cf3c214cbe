// Controller files (fuzzypid/controller_file): exact round trip, the shipped paper files,
// file:line:column errors for malformed files, and the fuzzy controller that runs a fuzzy-rules
// controller's exported table (controller::fuzzy_from_rule_table).
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fuzzypid/codegen/export_header.hpp"
#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/rulefile/rule_table_export.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

namespace cf = fuzzypid::controller_file;
namespace controller = fuzzypid::controller;
namespace tune = fuzzypid::tune;

// The family a controller file calls `name` (the test fails for a name no family has).
controller::Family named_family(std::string_view name) {
  const std::optional<controller::Family> f = controller::parse_family(name);
  EXPECT_TRUE(f.has_value()) << name;
  return f.value_or(controller::Family{});
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

cf::ControllerFile tuned_example() {
  cf::ControllerFile f{controller::paper_fuzzy(), std::nullopt, std::nullopt};
  controller::ControllerSpec& s = f.controller;
  s.description = "a \"quoted\" description\twith a tab";
  s.gains = {207.02946541923043, 0.0086027041784963332, 421.61049466377909};
  s.supervisor.error_scale = 961.29293435760724;
  s.supervisor.error_rate_scale = 0.1 + 0.2;  // not exactly representable in few digits
  s.supervisor.output_scale = {1038.9657241991415, 4.7364552446661055e-300, 1e300};
  s.supervisor.conjunction = fuzzypid::fuzzy::Conjunction::Product;
  s.supervisor.rule_base = fuzzypid::paper::Tables::Corrected;
  s.gain_max = {1e4, 2.5, std::numeric_limits<double>::infinity()};
  s.pid.derivative = fuzzypid::pid::DerivativeSource::Difference;
  s.pid.anti_windup = fuzzypid::pid::AntiWindup::BackCalculation;
  tune::Tuning t;
  t.conditions = "tuning/robust.toml";
  t.set = "training";
  t.algorithm = "pagmo::sade";
  t.budget = 16000;
  t.evaluations = 15980;
  t.seed = 7;
  t.threads = 2;
  t.population = 40;
  t.training_cost = 0.058396812345678901;
  t.box = {{"kp", -1.0, 4.0},  {"ki", -6.0, 1.0}, {"kd", 0.0, 4.0},  {"ke", -1.0, 4.0},
           {"kec", -3.0, 2.0}, {"sp", 0.0, 6.0},  {"si", -4.0, 3.0}, {"sd", -2.0, 5.0}};
  t.on_bound = {{"kp", true, 3.9987654321}, {"ki", false, -6.0}};
  t.objective.chatter_weight = 0.25;
  t.objective.chatter_limit_pct = 7.5;
  t.objective.effort_weight = 1.0 / 3.0;
  t.trained_on = {{"urdf", "../urdf/ur5_class.urdf", "0123456789abcdef"},
                  {"path", "../paths/contour.csv", "fedcba9876543210"}};
  f.tuning = t;
  s.feedforward.gravity = true;
  return f;
}

void expect_same(const controller::ControllerSpec& a, const controller::ControllerSpec& b) {
  EXPECT_EQ(a.family, b.family);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.gains, b.gains);
  EXPECT_EQ(a.supervisor.error_scale, b.supervisor.error_scale);
  EXPECT_EQ(a.supervisor.error_rate_scale, b.supervisor.error_rate_scale);
  EXPECT_EQ(a.supervisor.output_scale, b.supervisor.output_scale);
  EXPECT_EQ(a.supervisor.conjunction, b.supervisor.conjunction);
  EXPECT_EQ(a.supervisor.rule_base, b.supervisor.rule_base);
  EXPECT_EQ(a.gain_min, b.gain_min);
  EXPECT_EQ(a.gain_max, b.gain_max);
  EXPECT_EQ(a.pid.derivative, b.pid.derivative);
  EXPECT_EQ(a.pid.anti_windup, b.pid.anti_windup);
  EXPECT_EQ(a.feedforward.gravity, b.feedforward.gravity);
}

void expect_same(const cf::ControllerFile& a, const cf::ControllerFile& b) {
  expect_same(a.controller, b.controller);
  ASSERT_EQ(a.tuning.has_value(), b.tuning.has_value());
  if (a.tuning) {
    ASSERT_EQ(a.tuning->trained_on.size(), b.tuning->trained_on.size());
    for (std::size_t k = 0; k < a.tuning->trained_on.size(); ++k) {
      EXPECT_EQ(a.tuning->trained_on[k].kind, b.tuning->trained_on[k].kind);
      EXPECT_EQ(a.tuning->trained_on[k].file, b.tuning->trained_on[k].file);
      EXPECT_EQ(a.tuning->trained_on[k].fnv1a64, b.tuning->trained_on[k].fnv1a64);
    }
    ASSERT_EQ(a.tuning->on_bound.size(), b.tuning->on_bound.size());
    for (std::size_t k = 0; k < a.tuning->on_bound.size(); ++k) {
      EXPECT_EQ(a.tuning->on_bound[k].name, b.tuning->on_bound[k].name);
      EXPECT_EQ(a.tuning->on_bound[k].upper, b.tuning->on_bound[k].upper);
      EXPECT_EQ(a.tuning->on_bound[k].log10, b.tuning->on_bound[k].log10);
    }
    EXPECT_EQ(a.tuning->objective.chatter_weight, b.tuning->objective.chatter_weight);
    EXPECT_EQ(a.tuning->objective.chatter_limit_pct, b.tuning->objective.chatter_limit_pct);
    EXPECT_EQ(a.tuning->objective.effort_weight, b.tuning->objective.effort_weight);
    EXPECT_EQ(a.tuning->training_cost, b.tuning->training_cost);
    EXPECT_EQ(a.tuning->evaluations, b.tuning->evaluations);
    ASSERT_EQ(a.tuning->box.size(), b.tuning->box.size());
    for (std::size_t k = 0; k < a.tuning->box.size(); ++k)
      EXPECT_EQ(a.tuning->box[k].name, b.tuning->box[k].name);
  }
}

TEST(ControllerFile, WritingThenReadingGivesTheSameControllerAndTheSameText) {
  for (const cf::ControllerFile& spec :
       {cf::ControllerFile{controller::paper_pid(), std::nullopt, std::nullopt},
        cf::ControllerFile{controller::paper_fuzzy(), std::nullopt, std::nullopt},
        tuned_example()}) {
    const std::string text = cf::to_toml(spec);
    cf::ControllerFile back;
    fuzzypid::FileError error;
    ASSERT_TRUE(cf::parse(text, "mem.toml", back, error)) << error.to_string() << "\n" << text;
    expect_same(spec, back);
    EXPECT_EQ(cf::to_toml(back), text);
  }
}

// The record of a staged tuning with a validation split and a rule-table regulariser: every
// value written reads back (a stage without a validation set has none).
TEST(ControllerFile, StagesAndTheRegulariserOfATuningRecordReadBack) {
  cf::ControllerFile spec = tuned_example();
  tune::Tuning& t = *spec.tuning;
  t.validation_conditions = 2;
  t.validation_cost = 0.0125;
  tune::StageRecord first, second;
  first.family = named_family("pid");
  first.budget = 100;
  first.evaluations = 100;
  first.training_cost = 0.25;
  first.validation_cost = 0.0625;
  second.family = named_family("fuzzy");
  second.budget = 300;
  second.evaluations = 280;
  second.training_cost = 0.125;
  t.stages = {first, second};
  tune::TableRegulariser g;
  g.symmetry = "odd";
  g.partition = true;
  g.smoothness = 0.25;
  g.monotone = 0.5;
  g.unvisited = "free";
  g.visit_threshold = 0.001;
  g.frozen_cells = 3;
  g.cell_log10 = 1.5;
  t.regulariser = g;
  const std::string text = cf::to_toml(spec);
  cf::ControllerFile back;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::parse(text, "mem.toml", back, error)) << error.to_string() << "\n" << text;
  ASSERT_TRUE(back.tuning);
  const tune::Tuning& b = *back.tuning;
  EXPECT_EQ(b.validation_conditions, 2u);
  EXPECT_EQ(b.validation_cost, 0.0125);
  ASSERT_EQ(b.stages.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(b.stages[k].family, t.stages[k].family) << k;
    EXPECT_EQ(b.stages[k].budget, t.stages[k].budget) << k;
    EXPECT_EQ(b.stages[k].evaluations, t.stages[k].evaluations) << k;
    EXPECT_EQ(b.stages[k].training_cost, t.stages[k].training_cost) << k;
  }
  EXPECT_EQ(b.stages[0].validation_cost, 0.0625);
  EXPECT_TRUE(std::isnan(b.stages[1].validation_cost));
  ASSERT_TRUE(b.regulariser);
  EXPECT_EQ(b.regulariser->symmetry, "odd");
  EXPECT_TRUE(b.regulariser->partition);
  EXPECT_EQ(b.regulariser->smoothness, 0.25);
  EXPECT_EQ(b.regulariser->monotone, 0.5);
  EXPECT_EQ(b.regulariser->unvisited, "free");
  EXPECT_EQ(b.regulariser->visit_threshold, 0.001);
  EXPECT_EQ(b.regulariser->frozen_cells, 3u);
  EXPECT_EQ(b.regulariser->cell_log10, 1.5);
  EXPECT_EQ(cf::to_toml(back), text);
}

// The margins record and the margin requirements of the objective read back value for value
// (an infinite gain margin, no phase crossover, included); a record with five joints is refused.
TEST(ControllerFile, TheMarginsRecordAndTheMarginRequirementsReadBack) {
  cf::ControllerFile spec = tuned_example();
  spec.tuning->objective.min_disk_margin = 0.5;
  spec.tuning->objective.min_delay_margin_ms = 20.0;
  controller::MarginRecord m;
  m.conditions = "../tuning/robust_drive.toml";
  m.set = "training";
  m.delay_ms = 50.0;
  m.gain_margin_db = {6.5, 7.0, std::numeric_limits<double>::infinity(), 8.0, 9.0, 10.0};
  m.phase_margin_deg = {40, 41, 42, 43, 44, 45};
  m.delay_margin_ms = {20, 21, 22, 23, 24, 25.5};
  m.disk_margin = {0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  m.inertia_min_kgm2 = {1, 2, 3, 4, 5, 6};
  m.inertia_max_kgm2 = {2, 3, 4, 5, 6, 7};
  m.certified = true;
  m.verdict = "certified (linear, no saturation; gains may change every tick)";
  m.assumptions = "linear joint";
  spec.margins = m;
  const std::string text = cf::to_toml(spec);
  cf::ControllerFile back;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::parse(text, "mem.toml", back, error)) << error.to_string() << "\n" << text;
  ASSERT_TRUE(back.margins);
  const controller::MarginRecord& b = *back.margins;
  EXPECT_EQ(b.conditions, m.conditions);
  EXPECT_EQ(b.set, m.set);
  EXPECT_EQ(b.delay_ms, 50.0);
  EXPECT_EQ(b.gain_margin_db, m.gain_margin_db);
  EXPECT_EQ(b.phase_margin_deg, m.phase_margin_deg);
  EXPECT_EQ(b.delay_margin_ms, m.delay_margin_ms);
  EXPECT_EQ(b.disk_margin, m.disk_margin);
  EXPECT_EQ(b.inertia_min_kgm2, m.inertia_min_kgm2);
  EXPECT_EQ(b.inertia_max_kgm2, m.inertia_max_kgm2);
  EXPECT_TRUE(b.certified);
  EXPECT_EQ(b.verdict, m.verdict);
  EXPECT_EQ(b.assumptions, m.assumptions);
  EXPECT_EQ(back.tuning->objective.min_disk_margin, 0.5);
  EXPECT_EQ(back.tuning->objective.min_delay_margin_ms, 20.0);
  EXPECT_EQ(back.tuning->objective.min_gain_margin_db, 0.0);
  EXPECT_EQ(cf::to_toml(back), text);

  std::string five = text;
  const std::string row = "disk_margin = [0.5, ";
  const auto at = five.find(row);
  ASSERT_NE(at, std::string::npos);
  five.replace(at, row.size(), "disk_margin = [");
  EXPECT_FALSE(cf::parse(five, "five.toml", back, error));
  EXPECT_NE(error.to_string().find("disk_margin must have 6 numbers"), std::string::npos)
      << error.to_string();
}

TEST(ControllerFile, GravityFeedForwardIsWrittenOnlyWhenAskedAndTheHeaderSaysWhatTheTargetAdds) {
  controller::ControllerSpec spec = controller::paper_pid();
  EXPECT_EQ(cf::to_toml(spec).find("[feedforward]"), std::string::npos);
  EXPECT_NE(
      fuzzypid::codegen::export_header(spec, "ns", "x.toml").find("kGravityFeedforward = false"),
      std::string::npos);
  spec.feedforward.gravity = true;
  EXPECT_NE(cf::to_toml(spec).find("[feedforward]\ngravity = true"), std::string::npos);
  const std::string header = fuzzypid::codegen::export_header(spec, "ns", "x.toml");
  EXPECT_NE(header.find("kGravityFeedforward = true"), std::string::npos);
  EXPECT_NE(header.find("the target must add g^_i(q_desired)"), std::string::npos);
}

TEST(ControllerFile, FileHashIsFnv1aOfTheBytes) {
  const std::string path = ::testing::TempDir() + "hash_me.txt";
  std::ofstream(path) << "a";
  EXPECT_EQ(cf::file_hash(path), "af63dc4c8601ec8c");  // FNV-1a 64 of "a"
  EXPECT_EQ(cf::file_hash(path + ".missing"), "");
}

// trained_on hashes have the one form file_hash writes; any other is refused at its key with the
// value and the expected form (a hand-edited record that can never match is not a record).
TEST(ControllerFile, AMalformedTrainedOnHashIsRefusedAtItsKey) {
  const std::string good = cf::to_toml(tuned_example());
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::parse(good, "t.toml", spec, error)) << error.to_string();
  for (const char* bad : {"0123456789ABCDEF", "0123456789abcdeg", "0123456789abcde", "", "xyz"}) {
    std::string text = good;
    const std::size_t at = text.find("\"0123456789abcdef\"");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 18, std::string("\"") + bad + "\"");
    controller::ControllerSpec s;
    fuzzypid::FileError e;
    ASSERT_FALSE(cf::parse(text, "t.toml", s, e)) << bad;
    EXPECT_GT(e.line, 0u) << bad;
    if (*bad == '\0') {  // refused as every empty string is, before its form is looked at
      EXPECT_NE(e.message.find("'fnv1a64' is empty"), std::string::npos) << e.to_string();
      continue;
    }
    EXPECT_NE(e.message.find(std::string("trained_on fnv1a64 \"") + bad + "\" is not a 64-bit"),
              std::string::npos)
        << e.to_string();
    EXPECT_NE(e.message.find("16 lower-case hex digits"), std::string::npos) << e.to_string();
  }
}

// trained_on against the run: by content (a copy agrees, an edit in place does not), relative
// names resolved against the controller file's folder, and an absent entry meaning the bundled
// URDF or the built-in line.
TEST(ControllerFile, TrainedOnIsComparedWithTheRobotAndPathOfARun) {
  const std::string dir = ::testing::TempDir() + "trained_on_" + std::to_string(std::rand()) + "/";
  ASSERT_EQ(std::system(("mkdir -p '" + dir + "copy'").c_str()), 0);
  std::ofstream(dir + "robot.urdf") << "<robot name=\"r\"/>\n";
  std::ofstream(dir + "copy/robot.urdf") << "<robot name=\"r\"/>\n";
  std::ofstream(dir + "other.urdf") << "<robot name=\"other\"/>\n";
  std::ofstream(dir + "path.csv") << "t_s,q1_rad,q2_rad,q3_rad,q4_rad,q5_rad,q6_rad\n";
  cf::ControllerFile spec = tuned_example();
  spec.tuning->trained_on = {{"urdf", "robot.urdf", cf::file_hash(dir + "robot.urdf")},
                             {"path", "path.csv", cf::file_hash(dir + "path.csv")}};
  const std::string controller = dir + "c.toml";
  const std::string bundled = dir + "other.urdf";
  const auto diff = [&](const std::string& urdf, const std::string& path) {
    return cf::trained_on_differences(spec.tuning ? &*spec.tuning : nullptr, controller, urdf, path,
                                      bundled);
  };
  EXPECT_TRUE(diff(dir + "robot.urdf", dir + "path.csv").empty());
  EXPECT_TRUE(diff(dir + "copy/robot.urdf", dir + "path.csv").empty());

  auto d = diff(dir + "other.urdf", dir + "path.csv");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0], "urdf: trained on robot.urdf (fnv1a64 " + cf::file_hash(dir + "robot.urdf") +
                      "), run on " + dir + "other.urdf (fnv1a64 " +
                      cf::file_hash(dir + "other.urdf") + ")");
  d = diff(dir + "robot.urdf", "");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].find("path: trained on path.csv"), std::string::npos) << d[0];
  EXPECT_NE(d[0].find("run on the built-in line A -> B"), std::string::npos) << d[0];

  std::ofstream(dir + "robot.urdf", std::ios::app) << "<!-- edited -->\n";
  d = diff(dir + "robot.urdf", dir + "path.csv");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].find("the file has changed since the controller was tuned"), std::string::npos)
      << d[0];

  // No urdf or path entry: the bundled URDF (by content) on the built-in line.
  spec.tuning->trained_on.clear();
  EXPECT_TRUE(diff(bundled, "").empty());
  d = diff(dir + "copy/robot.urdf", dir + "path.csv");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NE(d[0].find("urdf: trained on the bundled ER50-C20, run on"), std::string::npos) << d[0];
  EXPECT_NE(d[1].find("path: trained on the built-in line A -> B, run on"), std::string::npos)
      << d[1];
  // A controller written by hand has no record to compare.
  spec.tuning.reset();
  EXPECT_TRUE(diff(dir + "copy/robot.urdf", dir + "path.csv").empty());
  std::system(("rm -rf '" + dir + "'").c_str());
}

// The condition file a tune read (trained_on kind "conditions"): a run on that file after an edit
// is told so, with both hashes; a run on another condition file, or on an unchanged copy of the
// record's, is not. The entry reads back, and an unknown kind is refused.
TEST(ControllerFile, AnEditedConditionFileIsToldFromTheOneTheTuneRead) {
  const std::string dir = ::testing::TempDir() + "conditions_" + std::to_string(std::rand()) + "/";
  ASSERT_EQ(std::system(("mkdir -p '" + dir + "tuning'").c_str()), 0);
  const std::string conditions = dir + "tuning/drive.toml";
  std::ofstream(conditions) << "[sets.training]\nconditions = [ { name = \"a\" } ]\n";
  std::ofstream(dir + "tuning/other.toml") << "[sets.training]\n";
  const std::string read_hash = cf::file_hash(conditions);
  cf::ControllerFile spec = tuned_example();
  spec.tuning->trained_on = {{"conditions", "tuning/drive.toml", read_hash}};
  const std::string controller = dir + "c.toml";
  const auto changed = [&](const std::string& file) {
    return cf::conditions_changed(spec.tuning ? &*spec.tuning : nullptr, controller, file);
  };
  EXPECT_EQ(changed(conditions), "");
  EXPECT_EQ(changed(dir + "tuning/other.toml"), "");
  EXPECT_EQ(changed(""), "");

  std::ofstream(conditions, std::ios::app) << "# edited\n";
  EXPECT_EQ(changed(conditions), "tuned on tuning/drive.toml (fnv1a64 " + read_hash +
                                     "), which has changed since (now " +
                                     cf::file_hash(conditions) +
                                     "): its sets may not be the ones the tune read");
  EXPECT_EQ(changed(dir + "tuning/other.toml"), "");

  // The entry is written and read back as it was.
  cf::ControllerFile back;
  fuzzypid::FileError e;
  ASSERT_TRUE(cf::parse(cf::to_toml(spec), "c.toml", back, e)) << e.to_string();
  ASSERT_TRUE(back.tuning.has_value());
  ASSERT_EQ(back.tuning->trained_on.size(), 1u);
  EXPECT_EQ(back.tuning->trained_on[0].kind, "conditions");
  EXPECT_EQ(back.tuning->trained_on[0].fnv1a64, read_hash);
  std::string text = cf::to_toml(spec);
  text.replace(text.find("kind = \"conditions\""), 19, "kind = \"robot\"");
  ASSERT_FALSE(cf::parse(text, "c.toml", back, e));
  EXPECT_NE(e.message.find("trained_on kind must be \"conditions\", \"urdf\" or \"path\""),
            std::string::npos)
      << e.to_string();
  // Written by hand: no record to compare.
  spec.tuning.reset();
  EXPECT_EQ(changed(conditions), "");
  std::system(("rm -rf '" + dir + "'").c_str());
}

TEST(ControllerFile, TheShippedPaperFilesAreThePapersControllers) {
  const std::string dir = FUZZYPID_SOURCE_DIR "/controllers/";
  for (const auto& [file, spec] : {std::pair{"paper_pid.toml", controller::paper_pid()},
                                   std::pair{"paper_fuzzy.toml", controller::paper_fuzzy()}}) {
    controller::ControllerSpec loaded;
    fuzzypid::FileError error;
    ASSERT_TRUE(cf::load(dir + file, loaded, error)) << error.to_string();
    expect_same(spec, loaded);
    EXPECT_EQ(read(dir + file), cf::to_toml(spec)) << file;
  }
}

TEST(ControllerFile, ShippedTunedFilesReadBackToTheirOwnText) {
  const std::string dir = FUZZYPID_SOURCE_DIR "/controllers/";
  for (const char* file :
       {"tuned_pid.toml", "tuned_scheduled.toml", "tuned_fuzzy.toml", "tuned_fuzzy_rules.toml",
        "tuned_scheduled_staged.toml", "ur5_class_tuned_pid.toml", "ur5_class_tuned_scheduled.toml",
        "ur5_class_tuned_fuzzy.toml"}) {
    cf::ControllerFile loaded;
    fuzzypid::FileError error;
    ASSERT_TRUE(cf::load(dir + file, loaded, error)) << error.to_string();
    ASSERT_TRUE(loaded.tuning.has_value()) << file;
    EXPECT_LE(loaded.tuning->evaluations, loaded.tuning->budget);
    EXPECT_EQ(read(dir + file), cf::to_toml(loaded)) << file;
  }
}

struct Malformed {
  const char* what;
  const char* text;
  int line;
  int column;
  const char* message;  // a part of the message
};

// A valid pid file with one line replaced (line numbers refer to the result).
const char* const kValid =
    "family = \"pid\"\n"          // 1
    "[units]\n"                   // 2
    "gains = \"acceleration\"\n"  // 3
    "form = \"per-tick\"\n"       // 4
    "tick_s = 0.05\n"             // 5
    "[gains]\n"                   // 6
    "kp = 4.0\n"                  // 7
    "ki = 0.001\n"                // 8
    "kd = 100.0\n";               // 9

void PrintTo(const Malformed& m, std::ostream* os) {
  *os << m.what;
}

class MalformedFile : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedFile, IsRejectedWithFileLineAndColumn) {
  const Malformed& m = GetParam();
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  ASSERT_FALSE(cf::parse(m.text, "bad.toml", spec, error)) << m.what;
  EXPECT_EQ(error.file, "bad.toml");
  EXPECT_EQ(error.line, m.line) << m.what << ": " << error.to_string();
  EXPECT_EQ(error.column, m.column) << m.what << ": " << error.to_string();
  EXPECT_NE(error.message.find(m.message), std::string::npos)
      << m.what << ": " << error.to_string();
  EXPECT_EQ(error.to_string().rfind(
                "bad.toml:" + std::to_string(m.line) + ":" + std::to_string(m.column) + ": ", 0),
            0u);
}

INSTANTIATE_TEST_SUITE_P(
    ControllerFile, MalformedFile,
    ::testing::Values(
        Malformed{"missing key",
                  "family = \"pid\"\n[units]\ngains = \"acceleration\"\n"
                  "form = \"per-tick\"\n[gains]\nkp = 1.0\nki = 0.0\nkd = 1.0\n",
                  2, 1, "missing key 'tick_s'"},
        Malformed{"unknown key",
                  "family = \"pid\"\nbogus = 1\n[units]\ngains = \"acceleration\"\n"
                  "form = \"per-tick\"\ntick_s = 0.05\n[gains]\nkp = 4.0\nki = 0.001\nkd = 100.0\n",
                  2, 1, "unknown key 'bogus'"},
        Malformed{"wrong type",
                  "family = \"pid\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
                  "tick_s = 0.05\n[gains]\nkp = \"four\"\nki = 0.001\nkd = 100.0\n",
                  7, 6, "'kp' must be a number"},
        Malformed{"NaN",
                  "family = \"pid\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
                  "tick_s = 0.05\n[gains]\nkp = 4.0\nki = nan\nkd = 100.0\n",
                  8, 6, "NaN"},
        Malformed{"negative gain",
                  "family = \"pid\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
                  "tick_s = 0.05\n[gains]\nkp = 4.0\nki = 0.001\nkd = -100.0\n",
                  9, 6, ">= 0"},
        Malformed{"reversed bounds",
                  "family = \"pid\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
                  "tick_s = 0.05\n[gains]\nkp = 4.0\nki = 0.001\nkd = 100.0\n[bounds]\n"
                  "gain_min = [0.0, 0.0, 5.0]\ngain_max = [10.0, 10.0, 1.0]\n",
                  12, 12, "gain_max must not be below gain_min"},
        Malformed{"negative bound",
                  "family = \"pid\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
                  "tick_s = 0.05\n[gains]\nkp = 4.0\nki = 0.001\nkd = 100.0\n[bounds]\n"
                  "gain_min = [0.0, -1.0, 0.0]\n",
                  11, 12, "gain_min must be finite and >= 0"},
        Malformed{"unknown family", "family = \"lqr\"\n", 1, 10, "unknown value 'lqr'"},
        Malformed{"unknown rule base",
                  "family = \"fuzzy\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
                  "tick_s = 0.05\n[gains]\nkp = 4.0\nki = 0.001\nkd = 100.0\n[supervisor]\n"
                  "error_scale = 1.0\nerror_rate_scale = 1.0\noutput_scale = [1.0, 1.0, 1.0]\n"
                  "rule_base = \"rules/missing.fll\"\n",
                  14, 13, "unknown value 'rules/missing.fll'"},
        Malformed{"supervisor missing for fuzzy",
                  "family = \"fuzzy\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
                  "tick_s = 0.05\n[gains]\nkp = 4.0\nki = 0.001\nkd = 100.0\n",
                  1, 1, "missing key 'supervisor'"},
        Malformed{"syntax error", "family = \"pid\n", 1, 14, "unescaped control character"},
        Malformed{"zero tick",
                  "family = \"pid\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
                  "tick_s = 0.0\n[gains]\nkp = 4.0\nki = 0.001\nkd = 100.0\n",
                  5, 10, "'tick_s' must be > 0"}),
    [](const ::testing::TestParamInfo<Malformed>& info) {
      std::string name = info.param.what;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

TEST(ControllerFile, ARuleFileIsResolvedFromTheFilesFolderAndWrittenBackAsGiven) {
  const std::string path = FUZZYPID_SOURCE_DIR "/tests/sim/data/engine_fuzzy.toml";
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::load(path, spec, error)) << error.to_string();
  EXPECT_EQ(spec.supervisor.rule_file, "../../../rulebases/paper.fll");
  ASSERT_NE(spec.supervisor.rule_model, nullptr);
  EXPECT_EQ(spec.supervisor.rule_model->num_inputs, 2u);
  // Written back and read again from the same folder: the same text.
  const std::string text = cf::to_toml(spec);
  cf::ControllerFile back;
  ASSERT_TRUE(cf::parse(text, path, back, error)) << error.to_string();
  EXPECT_EQ(cf::to_toml(back), text);
}

TEST(ControllerFile, AMissingRuleFileIsAnErrorAtItsKey) {
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  ASSERT_FALSE(
      cf::load(FUZZYPID_SOURCE_DIR "/tests/sim/data/bad_missing_rule_file.toml", spec, error));
  EXPECT_EQ(error.line, 14);
  EXPECT_EQ(error.column, 13);
  EXPECT_NE(error.message.find("missing.fll"), std::string::npos) << error.to_string();
}

TEST(ControllerFile, AValidFileIsAccepted) {
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::parse(kValid, "ok.toml", spec, error)) << error.to_string();
  EXPECT_EQ(spec.family, named_family("pid"));
  EXPECT_EQ(spec.gains.kd, 100.0);
}

TEST(ControllerFile, AFileThatCannotBeReadIsAnError) {
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  EXPECT_FALSE(cf::load("/nonexistent/controller.toml", spec, error));
  EXPECT_NE(error.to_string().find("/nonexistent/controller.toml"), std::string::npos);
}

// A file over 1 MiB is refused after a bounded read, never read until memory runs out; a device
// that never ends and a directory are refused by their kind, before they are opened.
TEST(ControllerFile, AFileIsReadWithABoundedSize) {
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  EXPECT_FALSE(cf::load("/dev/zero", spec, error));
  EXPECT_NE(error.message.find("is a character device, not a regular file"), std::string::npos)
      << error.to_string();
  const std::string big = ::testing::TempDir() + "fuzzypid_oversized.toml";
  std::FILE* f = std::fopen(big.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(std::fseek(f, 1L << 20, SEEK_SET), 0);  // 1 MiB of zeros, then one more byte
  ASSERT_EQ(std::fputc('x', f), 'x');
  ASSERT_EQ(std::fclose(f), 0);
  EXPECT_FALSE(cf::load(big, spec, error));
  EXPECT_NE(error.message.find("is larger than 1048576 bytes"), std::string::npos)
      << error.to_string();
  std::remove(big.c_str());
  EXPECT_FALSE(cf::load("/", spec, error));
  EXPECT_NE(error.message.find("is a directory"), std::string::npos) << error.to_string();
}

TEST(ControllerFile, ANominalGainOutsideItsOwnBoundsIsRefusedAtLoad) {
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  EXPECT_FALSE(
      cf::load(FUZZYPID_SOURCE_DIR "/tests/sim/data/bad_k0_outside_bounds.toml", spec, error));
  EXPECT_NE(error.message.find("gains.kp = 50.0 lies outside [bounds] 0.0 .. 10.0"),
            std::string::npos)
      << error.to_string();
}

// Every [pid] choice of a file reaches the controller, non-default values included.
TEST(ControllerFile, NonDefaultPidChoicesAreReadAndReachTheController) {
  const std::string text = std::string(kValid) +
                           "[pid]\nderivative = \"difference\"\nderivative_on = \"measurement\"\n"
                           "anti_windup = \"back-calculation\"\n";
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::parse(text, "ok.toml", spec, error)) << error.to_string();
  EXPECT_EQ(spec.pid.derivative_on, fuzzypid::pid::DerivativeOn::Measurement);
  EXPECT_EQ(spec.pid.derivative, fuzzypid::pid::DerivativeSource::Difference);
  EXPECT_EQ(spec.pid.anti_windup, fuzzypid::pid::AntiWindup::BackCalculation);
  const auto pc = controller::pid_config(spec, 0, 1.0);
  EXPECT_EQ(pc.derivative_on, fuzzypid::pid::DerivativeOn::Measurement);
  EXPECT_EQ(pc.derivative_source, fuzzypid::pid::DerivativeSource::Difference);
}

// derivative = "observer" with its bandwidth and modelled delay reads, reaches the PID, and is
// written back as read; settings it cannot run with are refused naming the key.
TEST(ControllerFile, AVelocityObserverIsReadWrittenBackAndReachesThePid) {
  const std::string observer = std::string(kValid) +
                               "[pid]\nderivative = \"observer\"\nobserver_bandwidth_hz = 1.5\n"
                               "observer_delay_ticks = 0\n";
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::parse(observer, "ok.toml", spec, error)) << error.to_string();
  EXPECT_EQ(spec.pid.derivative, fuzzypid::pid::DerivativeSource::Observer);
  EXPECT_EQ(spec.pid.observer_bandwidth_hz, 1.5);
  EXPECT_EQ(spec.pid.observer_delay_ticks, 0);
  const auto pc = controller::pid_config(spec, 0, 1.0);
  EXPECT_EQ(pc.derivative_source, fuzzypid::pid::DerivativeSource::Observer);
  EXPECT_EQ(pc.observer_bandwidth_hz, 1.5);
  EXPECT_EQ(pc.observer_delay_ticks, 0);
  EXPECT_TRUE(pc.valid());
  const std::string text = cf::to_toml(spec);
  EXPECT_NE(text.find("derivative = \"observer\"\n"), std::string::npos) << text;
  EXPECT_NE(text.find("observer_bandwidth_hz = 1.5\nobserver_delay_ticks = 0\n"), std::string::npos)
      << text;
  controller::ControllerSpec back;
  ASSERT_TRUE(cf::parse(text, "back.toml", back, error)) << error.to_string();
  EXPECT_EQ(cf::to_toml(back), text);
  // Without the observer its keys are not written.
  EXPECT_EQ(cf::to_toml(controller::paper_pid()).find("observer"), std::string::npos);

  const auto refused = [](const std::string& text) {
    controller::ControllerSpec s;
    fuzzypid::FileError e;
    EXPECT_FALSE(cf::parse(text, "bad.toml", s, e)) << text;
    return e.to_string();
  };
  const std::string pid = std::string(kValid) + "[pid]\n";
  EXPECT_NE(refused(pid + "derivative = \"observer\"\n")
                .find("observer_bandwidth_hz must be within (0, 1e6] Hz"),
            std::string::npos);
  EXPECT_NE(refused(pid + "observer_bandwidth_hz = 2.0\n")
                .find("observer_bandwidth_hz applies only to derivative = \"observer\""),
            std::string::npos);
  EXPECT_NE(
      refused(pid +
              "derivative = \"observer\"\nobserver_bandwidth_hz = 2.0\nobserver_delay_ticks = 4\n")
          .find("bad.toml:13:24: observer_delay_ticks must be 0 .. 3"),
      std::string::npos);
  std::string torque = pid + "derivative = \"observer\"\nobserver_bandwidth_hz = 2.0\n";
  torque.replace(torque.find("\"acceleration\""), 14, "\"torque\"");
  EXPECT_NE(refused(torque).find("needs gains in acceleration units"), std::string::npos);
}

// gain_update = "incremental" reaches the runtime fuzzy controller's configuration.
TEST(ControllerFile, IncrementalGainUpdateReachesTheFuzzyController) {
  controller::ControllerSpec spec = controller::paper_fuzzy();
  spec.supervisor.gain_update = fuzzypid::supervisor::GainUpdate::Incremental;
  controller::ControllerSpec back;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::parse(cf::to_toml(spec), "inc.toml", back, error)) << error.to_string();
  EXPECT_EQ(back.supervisor.gain_update, fuzzypid::supervisor::GainUpdate::Incremental);
  EXPECT_EQ(controller::fuzzy_pid_config(back, 0, 1.0).gain_update,
            fuzzypid::supervisor::GainUpdate::Incremental);
  EXPECT_EQ(controller::fuzzy_pid_config(controller::paper_fuzzy(), 0, 1.0).gain_update,
            fuzzypid::supervisor::GainUpdate::Absolute);
}

// A fuzzy-rules controller with an uneven table, non-uniform centers, R != 1, bounds that clamp
// and non-default PID options, in the given form.
controller::ControllerSpec fuzzy_rules_example(controller::PidForm form) {
  controller::ControllerSpec s;
  s.family = named_family("fuzzy-rules");
  s.units.form = form;
  s.gains = {548.2, 6.56, 360.5};
  s.supervisor.error_scale = 84.3;
  s.supervisor.error_rate_scale = 1.76;
  s.supervisor.output_scale = {0.294, 0.0101, 1.152};
  auto& t = s.supervisor.rule_table;
  t.error_centers = {-1.5, -0.8, -0.3, 0.0, 0.3, 0.8, 1.5};
  t.error_rate_centers = {-1.0, -0.6, -0.2, 0.0, 0.2, 0.6, 1.0};
  for (std::size_t i = 0; i < 7; ++i)
    for (std::size_t j = 0; j < 7; ++j) {
      t.ratio[0][i][j] = 0.7 + 0.05 * i + 0.03 * j;
      t.ratio[1][i][j] = 1.0 + 0.1 * (i > 3 ? i - 3 : 3 - i) - 0.04 * j;
      t.ratio[2][i][j] = 1.2 - 0.04 * static_cast<double>(i * j % 5);
    }
  s.gain_min = {50.0, 0.0, 0.0};
  s.gain_max = {600.0, std::numeric_limits<double>::infinity(), 420.0};
  s.pid.derivative_on = fuzzypid::pid::DerivativeOn::Measurement;
  s.pid.anti_windup = fuzzypid::pid::AntiWindup::BackCalculation;
  s.pid.derivative_filter_s = 0.02;
  s.feedforward.gravity = true;
  return s;
}

// The fuzzy controller that runs a fuzzy-rules controller's table exported as .fll keeps every
// setting but the supervisor's, and ticks like the original on random inputs (per-tick and
// continuous gains).
TEST(FuzzyFromRuleTable, RunsTheExportedRuleFileLikeTheFuzzyRulesController) {
  for (const controller::PidForm form :
       {controller::PidForm::PerTick, controller::PidForm::Continuous}) {
    SCOPED_TRACE(controller::to_string(form));
    controller::ControllerSpec rules = fuzzy_rules_example(form);
    rules.description = "tuned";
    ASSERT_EQ(controller::validate(rules), "");
    std::string text, error;
    ASSERT_TRUE(fuzzypid::rulefile::rule_table_to_fll(controller::rule_table(rules), text, error))
        << error;
    auto model = std::make_shared<fuzzypid::rulefile::Model>();
    fuzzypid::rulefile::LoadError load_error;
    ASSERT_TRUE(fuzzypid::rulefile::parse_fll(text, "t.fll", *model, load_error))
        << load_error.to_string();
    const controller::ControllerSpec fuzzy =
        controller::fuzzy_from_rule_table(rules, "../rules/t.fll", model, "exported");
    ASSERT_EQ(controller::validate(fuzzy), "");
    EXPECT_EQ(fuzzy.family, named_family("fuzzy"));
    EXPECT_EQ(fuzzy.description, "exported");
    EXPECT_EQ(fuzzy.units.form, form);
    EXPECT_EQ(fuzzy.gains, rules.gains);
    EXPECT_EQ(fuzzy.supervisor.error_scale, rules.supervisor.error_scale);
    EXPECT_EQ(fuzzy.supervisor.error_rate_scale, rules.supervisor.error_rate_scale);
    EXPECT_EQ(fuzzy.supervisor.output_scale,
              (std::array<double, 3>{rules.gains.kp, rules.gains.ki, rules.gains.kd}));
    EXPECT_EQ(fuzzy.supervisor.gain_update, fuzzypid::supervisor::GainUpdate::Absolute);
    EXPECT_EQ(fuzzy.supervisor.rule_file, "../rules/t.fll");
    EXPECT_EQ(fuzzy.gain_min, rules.gain_min);
    EXPECT_EQ(fuzzy.gain_max, rules.gain_max);
    EXPECT_EQ(fuzzy.pid.derivative_on, rules.pid.derivative_on);
    EXPECT_EQ(fuzzy.pid.anti_windup, rules.pid.anti_windup);
    EXPECT_EQ(fuzzy.pid.derivative_filter_s, rules.pid.derivative_filter_s);
    EXPECT_TRUE(fuzzy.feedforward.gravity);

    controller::Vector limit;
    limit.fill(5.0);  // saturates now and then: the anti-windup paths run too
    auto a = controller::JointControllers::create(rules, limit, error);
    ASSERT_TRUE(a) << error;
    auto b = controller::JointControllers::create(fuzzy, limit, error);
    ASSERT_TRUE(b) << error;
    const std::uint64_t seed = 20261202;
    std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
    std::mt19937_64 rng(seed);
    // Errors across the universe (|Ke e| up to 2 c_max), rates likewise.
    fuzzypid::support::UniformReal<double> e(-0.035, 0.035), ec(-1.2, 1.2);
    double worst = 0.0;
    for (int tick = 0; tick < 4000; ++tick) {
      controller::Input in;
      for (std::size_t j = 0; j < controller::kJoints; ++j) {
        in.desired_position_rad[j] = 0.1 * static_cast<double>(j);
        in.measured_position_rad[j] =
            in.desired_position_rad[j] - e(rng) * (tick % 7 == 0 ? 0.01 : 1);
        in.measured_velocity_rad_s[j] = ec(rng) * (tick % 5 == 0 ? 0.01 : 1);
      }
      const controller::Command ca = a->step(in, rules.units.tick_s);
      const controller::Command cb = b->step(in, rules.units.tick_s);
      ASSERT_EQ(ca.status, cb.status) << "tick " << tick;
      for (std::size_t j = 0; j < controller::kJoints; ++j) {
        const double d =
            std::fabs(ca.output[j] - cb.output[j]) / std::fmax(1.0, std::fabs(ca.output[j]));
        worst = std::fmax(worst, d);
        const auto ga = a->gains(j), gb = b->gains(j);
        EXPECT_NEAR(gb.kp, ga.kp, 1e-9 * ga.kp) << "tick " << tick;
        EXPECT_NEAR(gb.ki, ga.ki, 1e-9 * ga.ki) << "tick " << tick;
        EXPECT_NEAR(gb.kd, ga.kd, 1e-9 * ga.kd) << "tick " << tick;
      }
    }
    std::printf("max |command difference| %.3g (relative above 1)\n", worst);
    EXPECT_LE(worst, 1e-9);
  }
}

// The blocks of a .fll text (its header, then each InputVariable, OutputVariable and RuleBlock
// with its lines), in file order.
std::vector<std::string> fll_blocks(const std::string& text) {
  std::vector<std::string> blocks(1);
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("InputVariable:", 0) == 0 || line.rfind("OutputVariable:", 0) == 0 ||
        line.rfind("RuleBlock:", 0) == 0)
      blocks.emplace_back();
    blocks.back() += line + "\n";
  }
  return blocks;
}

// A folder under the temporary directory holding `fll` as t.fll and a fuzzy controller file
// ctl.toml that names it; returns the controller file's path.
std::string write_controller_with_rule_file(const std::string& folder, const std::string& fll,
                                            const controller::ControllerSpec& spec) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / folder;
  fs::create_directories(dir);
  std::ofstream((dir / "t.fll").string()) << fll;
  std::ofstream((dir / "ctl.toml").string()) << cf::to_toml(spec);
  return (dir / "ctl.toml").string();
}

// A supervisor's rule file is bound by name: an exported .fll whose input and output blocks are
// reordered (the same system to fuzzylite) gives the same controller, bit for bit; names that do
// not bind are refused at load, naming the names the file has and the names it needs.
TEST(ControllerFile, ASupervisorRuleFileIsReadByNameWhateverTheOrderOfItsBlocks) {
  const controller::ControllerSpec rules = fuzzy_rules_example(controller::PidForm::PerTick);
  std::string fll, error;
  ASSERT_TRUE(fuzzypid::rulefile::rule_table_to_fll(controller::rule_table(rules), fll, error))
      << error;
  const std::vector<std::string> b = fll_blocks(fll);
  ASSERT_GE(b.size(), 7u);  // header, e, ec, dKp, dKi, dKd, the rule blocks
  ASSERT_EQ(b[1].rfind("InputVariable: e\n", 0), 0u);
  ASSERT_EQ(b[3].rfind("OutputVariable: dKp\n", 0), 0u);
  // ec before e; dKd, dKp, dKi; the rule blocks as they were.
  std::string reordered = b[0] + b[2] + b[1] + b[5] + b[3] + b[4];
  for (std::size_t k = 6; k < b.size(); ++k)
    reordered += b[k];
  const controller::ControllerSpec spec =
      controller::fuzzy_from_rule_table(rules, "t.fll", nullptr, "exported");

  controller::ControllerSpec original, shuffled;
  fuzzypid::FileError file_error;
  ASSERT_TRUE(cf::load(write_controller_with_rule_file("fuzzypid_by_name_a", fll, spec), original,
                       file_error))
      << file_error.to_string();
  ASSERT_TRUE(cf::load(write_controller_with_rule_file("fuzzypid_by_name_b", reordered, spec),
                       shuffled, file_error))
      << file_error.to_string();
  EXPECT_STREQ(shuffled.supervisor.rule_model->inputs[0].name.data(), "ec");
  EXPECT_STREQ(shuffled.supervisor.rule_model->outputs[0].name.data(), "dKd");

  controller::Vector limit;
  limit.fill(5.0);
  auto a = controller::JointControllers::create(original, limit, error);
  ASSERT_TRUE(a) << error;
  auto c = controller::JointControllers::create(shuffled, limit, error);
  ASSERT_TRUE(c) << error;
  std::mt19937_64 rng(20261203);
  fuzzypid::support::UniformReal<double> e(-0.035, 0.035), ec(-1.2, 1.2);
  int differing = 0;
  for (int tick = 0; tick < 2000; ++tick) {
    controller::Input in;
    for (std::size_t j = 0; j < controller::kJoints; ++j) {
      in.desired_position_rad[j] = 0.1 * static_cast<double>(j);
      in.measured_position_rad[j] = in.desired_position_rad[j] - e(rng);
      in.measured_velocity_rad_s[j] = ec(rng);
    }
    const controller::Command ca = a->step(in, rules.units.tick_s);
    const controller::Command cc = c->step(in, rules.units.tick_s);
    ASSERT_EQ(ca.status, cc.status) << "tick " << tick;
    for (std::size_t j = 0; j < controller::kJoints; ++j) {
      differing += ca.output[j] != cc.output[j];
      const auto ga = a->gains(j), gc = c->gains(j);
      differing += ga.kp != gc.kp || ga.ki != gc.ki || ga.kd != gc.kd;
    }
  }
  EXPECT_EQ(differing, 0);

  // Names that do not bind: an input and an output swapped, a gain under another name.
  struct Bad {
    std::string from, to, has;
  };
  for (const Bad& bad :
       {Bad{"InputVariable: ec\n", "InputVariable: dKi\n", "inputs (e, dKi) and outputs (dKp, ec"},
        Bad{"OutputVariable: dKp\n", "OutputVariable: Kp\n", "outputs (Kp, dKi, dKd)"}}) {
    std::string text = fll;
    text.replace(text.find(bad.from), bad.from.size(), bad.to);
    if (bad.to.find("dKi") != std::string::npos) {
      const std::string out = "OutputVariable: dKi\n";
      text.replace(text.find(out), out.size(), "OutputVariable: ec\n");
      // The rules name the variables too: rename them so that the file itself is valid.
      std::string::size_type k = 0;
      while ((k = text.find("ec is", k)) != std::string::npos)
        text.replace(k, 5, "@@ is");
      while ((k = text.find("dKi is")) != std::string::npos)
        text.replace(k, 6, "ec is");
      while ((k = text.find("@@ is")) != std::string::npos)
        text.replace(k, 5, "dKi is");
    } else {
      std::string::size_type k = 0;
      while ((k = text.find("dKp is", k)) != std::string::npos)
        text.replace(k, 6, "Kp is");
    }
    fuzzypid::rulefile::Model model;
    fuzzypid::rulefile::LoadError load_error;
    ASSERT_TRUE(fuzzypid::rulefile::parse_fll(text, "t.fll", model, load_error))
        << load_error.to_string();
    controller::ControllerSpec refused;
    const std::string path = write_controller_with_rule_file("fuzzypid_by_name_bad", text, spec);
    ASSERT_FALSE(cf::load(path, refused, file_error));
    EXPECT_EQ(file_error.file, path);
    EXPECT_GT(file_error.line, 0);
    EXPECT_NE(file_error.message.find(bad.has), std::string::npos) << file_error.to_string();
    EXPECT_NE(file_error.message.find("needs inputs (e, ec) and outputs (dKp, dKi, dKd)"),
              std::string::npos)
        << file_error.to_string();
  }

  // A term name used twice in a variable: the rules' meaning would rest on the reader's rule.
  std::string twice = fll;
  const std::string first_term = "  term: ";
  const std::size_t at = twice.find(first_term, twice.find("InputVariable: ec\n"));
  const std::size_t end = twice.find('\n', at);
  const std::string line = twice.substr(at, end - at + 1);  // ec's first term
  twice.insert(end + 1, line);
  fuzzypid::rulefile::Model model;
  fuzzypid::rulefile::LoadError load_error;
  ASSERT_TRUE(fuzzypid::rulefile::parse_fll(twice, "t.fll", model, load_error));
  ASSERT_EQ(load_error.warnings.size(), 1u);
  controller::ControllerSpec refused;
  const std::string path = write_controller_with_rule_file("fuzzypid_by_name_twice", twice, spec);
  ASSERT_FALSE(cf::load(path, refused, file_error));
  EXPECT_NE(file_error.message.find("t.fll:"), std::string::npos) << file_error.to_string();
  EXPECT_NE(file_error.message.find("repeats the name of an earlier term"), std::string::npos)
      << file_error.to_string();
}

}  // namespace
