// Choosing a front's point by a stated rule and hypervolumes (tune/pick.hpp): known answers on
// hand-made fronts, closed forms, and a seeded random property against an exact 2-D sweep.
#include "fuzzypid/tune/pick.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace fuzzypid::tune {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kNames = {"itae", "effort"};
// A staircase: (1, 9) (2, 4) (4, 2) (8, 1).
const std::vector<std::vector<double>> kFront = {{1, 9}, {2, 4}, {4, 2}, {8, 1}};

std::size_t picked(const std::string& rule_text,
                   const std::vector<std::vector<double>>& points = kFront) {
  std::string error;
  const auto rule = parse_pick_rule(rule_text, error);
  EXPECT_TRUE(rule) << error;
  const auto k = pick(kNames, points, *rule, error);
  EXPECT_TRUE(k) << error;
  return k.value_or(99);
}

TEST(Pick, KneeIsTheScaledPointNearestTheIdeal) {
  // Scaled: itae (x - 1) / 7, effort (y - 1) / 8: (0, 1), (1/7, 3/8), (3/7, 1/8), (1, 0);
  // squared distances 1, 0.1610, 0.1993, 1: the second point.
  EXPECT_EQ(picked("knee"), 1u);
  // An objective the same for every point counts 0: the smallest other one decides.
  EXPECT_EQ(picked("knee", {{3, 5}, {2, 5}, {4, 5}}), 1u);
}

TEST(Pick, MinAndMaxFollowTheirDefinitions) {
  EXPECT_EQ(picked("min:itae"), 0u);
  EXPECT_EQ(picked("min:effort"), 3u);
  // effort <= 4: points 1, 2, 3; the smallest itae of them is point 1's.
  EXPECT_EQ(picked("max:effort=4"), 1u);
  EXPECT_EQ(picked("max:effort=3.9"), 2u);
  // Capping the first objective orders by the second: itae <= 4 -> the smallest effort, point 2.
  EXPECT_EQ(picked("max:itae=4"), 2u);
  // Ties go to the lowest point number.
  EXPECT_EQ(picked("min:effort", {{1, 2}, {3, 2}}), 0u);
}

TEST(Pick, RulesAndCapsThatCannotBeMetAreErrors) {
  std::string error;
  for (const char* bad : {"", "knees", "max:effort", "max:effort=", "max:effort=x",
                          "max:effort=nan", "max:effort=inf", "median:itae"}) {
    EXPECT_FALSE(parse_pick_rule(bad, error)) << bad;
    EXPECT_NE(error.find("expected"), std::string::npos) << bad << ": " << error;
  }
  EXPECT_FALSE(parse_pick_rule("min:speed", error));
  EXPECT_NE(error.find("unknown objective 'speed'"), std::string::npos) << error;
  EXPECT_FALSE(parse_pick_rule("min:", error));
  EXPECT_NE(error.find("unknown objective ''"), std::string::npos) << error;
  const auto rule = parse_pick_rule("max:effort=0.5", error);
  ASSERT_TRUE(rule);
  EXPECT_FALSE(pick(kNames, kFront, *rule, error));
  EXPECT_EQ(error, "no point has effort <= 0.5 (the smallest is 1)");
  const auto chatter = parse_pick_rule("min:chatter", error);
  ASSERT_TRUE(chatter);
  EXPECT_FALSE(pick(kNames, kFront, *chatter, error));
  EXPECT_EQ(error, "the front has no objective 'chatter'");
}

TEST(Hypervolume, MatchesClosedForms) {
  // The staircase against (10, 10), strip by strip from the left: 9 x 1 + 8 x 5 + 6 x 2 + 2 x 1.
  EXPECT_DOUBLE_EQ(hypervolume(kFront, {10, 10}), 63.0);
  // One 3-D point: a box.
  EXPECT_DOUBLE_EQ(hypervolume({{1, 2, 3}}, {4, 4, 4}), 3.0 * 2.0 * 1.0);
  // Two 3-D boxes, 2 x 2 x 1 and 1 x 1 x 2, overlapping in a unit cube: 4 + 2 - 1.
  EXPECT_DOUBLE_EQ(hypervolume({{0, 0, 1}, {1, 1, 0}}, {2, 2, 2}), 5.0);
  // A point on or beyond the reference adds nothing.
  EXPECT_DOUBLE_EQ(hypervolume({{1, 1}, {3, 0}, {0, 5}}, {3, 3}), 4.0);
  EXPECT_DOUBLE_EQ(hypervolume({}, {1, 1}), 0.0);
}

// The exact 2-D hypervolume by a sweep over the points sorted by the first objective.
double sweep(std::vector<std::vector<double>> p, const std::vector<double>& ref) {
  std::sort(p.begin(), p.end());
  double volume = 0.0, ceiling = ref[1];
  for (const auto& q : p) {
    if (q[0] >= ref[0] || q[1] >= ceiling) continue;
    volume += (ref[0] - q[0]) * (ceiling - q[1]);
    ceiling = q[1];
  }
  return volume;
}

TEST(Hypervolume, SeededRandomSetsAgreeWithAnExactSweep) {
  for (unsigned seed = 1; seed <= 200; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::vector<double>> p(1 + seed % 25);
    for (auto& q : p)
      q = {u(rng), u(rng)};
    const std::vector<double> ref = {0.8 + 0.4 * u(rng), 0.8 + 0.4 * u(rng)};
    EXPECT_NEAR(hypervolume(p, ref), sweep(p, ref), 1e-12) << "seed " << seed;
  }
}

TEST(Hypervolume, TheCommonReferenceLiesTenPercentOfTheRangeBeyondTheWorst) {
  const auto ref = common_reference({{{1, 5}, {3, 2}}, {{2, 2}, {0, 5}}});
  ASSERT_EQ(ref.size(), 2u);
  EXPECT_DOUBLE_EQ(ref[0], 3.0 + 0.3);
  EXPECT_DOUBLE_EQ(ref[1], 5.0 + 0.3);
  EXPECT_EQ(common_reference({{{2, 7}}}), (std::vector<double>{3.0, 8.0}));
}

class ReadFront : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("fuzzypid_front_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Writes `text` as front.csv and reads it; the error when refused.
  std::string refused(const std::string& text) {
    std::ofstream(dir_ / "front.csv") << text;
    std::string error;
    EXPECT_FALSE(read_front(dir_.string(), error)) << text;
    return error;
  }
  fs::path dir_;
};

TEST_F(ReadFront, ReadsTheFilesAndBothSetsOfColumns) {
  std::string error;
  const auto t = read_front(FUZZYPID_SOURCE_DIR "/tests/tune/data/front_small", error);
  ASSERT_TRUE(t) << error;
  EXPECT_EQ(t->objectives, kNames);
  EXPECT_EQ(t->files.size(), 4u);
  EXPECT_EQ(t->files[3], "point_003.toml");
  EXPECT_EQ(t->training, kFront);
  EXPECT_EQ(t->validation[3], (std::vector<double>{9, 0.5}));
}

TEST_F(ReadFront, RefusesEachMalformedFrontNamingTheLine) {
  const std::string header = "point,file,itae,effort\n";
  EXPECT_NE(refused("").find("empty"), std::string::npos);
  EXPECT_NE(refused("a,b,c,d\n").find(":1: not a front's header"), std::string::npos);
  EXPECT_NE(refused("point,file,itae,speed\n").find("unknown objective 'speed'"),
            std::string::npos);
  EXPECT_NE(refused("point,file,itae,itae\n").find("given twice"), std::string::npos);
  EXPECT_NE(refused("point,file,itae,effort,validation_effort,validation_itae\n")
                .find("expected 'validation_itae'"),
            std::string::npos);
  EXPECT_NE(refused(header).find("a front of no point"), std::string::npos);
  EXPECT_NE(refused(header + "0,p.toml,1\n").find(":2: 3 fields, expected 4"), std::string::npos);
  EXPECT_NE(refused(header + "1,p.toml,1,2\n").find(":2: point '1', expected 0"),
            std::string::npos);
  EXPECT_NE(refused(header + "0,../p.toml,1,2\n").find("is not a file of the front's folder"),
            std::string::npos);
  EXPECT_NE(refused(header + "0,p.toml,1,nan\n").find("column 4 ('nan') is not a finite"),
            std::string::npos);
  std::string error;
  EXPECT_FALSE(read_front((dir_ / "absent").string(), error));
  EXPECT_NE(error.find("front.csv"), std::string::npos) << error;
}

}  // namespace
}  // namespace fuzzypid::tune
