// The checkpoint of a front search (apps/fuzzypid/front_checkpoint.hpp): a state written and read
// back is the same to the last bit, and a checkpoint that is malformed or belongs to other options
// is refused with the line and the reason.
#include "front_checkpoint.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

namespace fuzzypid::cli {
namespace {

const Fingerprint kOptions = {{"family", "pid"}, {"seed", "5"}, {"box", "kp=0:1 ki=-3:0"}};

tune::FrontState random_state(std::uint64_t seed, std::size_t members, std::size_t dim,
                              std::size_t m) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  tune::FrontState s;
  s.generation = rng() % 100;
  s.evaluations = members * (1 + s.generation);
  s.x.assign(members, std::vector<double>(dim));
  s.f.assign(members, std::vector<double>(m));
  for (auto& x : s.x)
    for (double& v : x)
      v = u(rng) * std::pow(10.0, static_cast<double>(rng() % 40) - 20.0);
  for (auto& f : s.f)
    for (double& v : f)
      v = u(rng);
  return s;
}

void expect_same(const tune::FrontState& a, const tune::FrontState& b) {
  EXPECT_EQ(a.generation, b.generation);
  EXPECT_EQ(a.evaluations, b.evaluations);
  ASSERT_EQ(a.x.size(), b.x.size());
  ASSERT_EQ(a.f.size(), b.f.size());
  for (std::size_t k = 0; k < a.x.size(); ++k) {
    ASSERT_EQ(a.x[k].size(), b.x[k].size());
    for (std::size_t i = 0; i < a.x[k].size(); ++i)
      EXPECT_EQ(std::signbit(a.x[k][i]), std::signbit(b.x[k][i]));
    EXPECT_EQ(a.x[k], b.x[k]);
    EXPECT_EQ(a.f[k], b.f[k]);
  }
}

TEST(FrontCheckpoint, SeededRandomStatesReadBackBitForBit) {
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    const tune::FrontState s = random_state(seed, 4 + seed % 9, 1 + seed % 7, 2 + seed % 4);
    std::string error;
    const auto back = parse_checkpoint(checkpoint_text(kOptions, s), "state", kOptions, error);
    ASSERT_TRUE(back) << error;
    expect_same(s, *back);
  }
}

TEST(FrontCheckpoint, ExtremeValuesReadBackExactly) {
  tune::FrontState s;
  s.generation = 3;
  s.evaluations = 8;
  s.x = {{std::numeric_limits<double>::denorm_min(), -0.0, std::numeric_limits<double>::max()},
         {0.1, -1e-310, 1.0 / 3.0}};
  s.f = {{std::numeric_limits<double>::infinity(), 1e300}, {-2.5, 0.0}};
  std::string error;
  const auto back = parse_checkpoint(checkpoint_text(kOptions, s), "state", kOptions, error);
  ASSERT_TRUE(back) << error;
  expect_same(s, *back);
}

// The text of a valid checkpoint with line `line` (1-based, counting the comment) replaced.
std::string with_line(std::size_t line, const std::string& replacement) {
  tune::FrontState s = random_state(7, 2, 2, 2);
  const std::string text = checkpoint_text(kOptions, s);
  std::string out;
  std::size_t begin = 0, n = 0;
  while (begin < text.size()) {
    const std::size_t end = text.find('\n', begin);
    ++n;
    out += (n == line ? replacement : text.substr(begin, end - begin)) + "\n";
    begin = end + 1;
  }
  return out;
}

TEST(FrontCheckpoint, MalformedOrForeignCheckpointsAreRefusedNamingTheLine) {
  // Lines: 1 comment, 2 format, 3-5 options, 6 generation, 7 evaluations, 8 members, 9-10 x,
  // 11-12 f.
  const struct {
    std::size_t line;
    std::string text;
    std::string why;
  } cases[] = {
      {2, "format 2", "state:2: not a fuzzypid tune checkpoint"},
      {4, "option seed 6",
       "state:4: the checkpoint was written by a tune with seed 6, this one has 5"},
      {4, "option budget 5", "state:4: the checkpoint's option budget where this tune has seed"},
      {6, "generation -1", "state:6: expected 'generation G'"},
      {7, "evaluations 1e3", "state:7: expected 'evaluations E'"},
      {8, "members 2000000 parameters 2 objectives 2", "state:8: expected 'members P"},
      {9, "x 0x1p+0", "state:9: an 'x' row of 1 numbers, expected 2"},
      {10, "x 0x1p+0 zero", "state:10: 'zero' is not a number"},
      {11, "y 1 2", "state:11: expected an 'f' row"},
      {12, "f 1 2\nf 3 4", "state:13: unexpected text after the last row"},
  };
  for (const auto& c : cases) {
    std::string error;
    EXPECT_FALSE(parse_checkpoint(with_line(c.line, c.text), "state", kOptions, error)) << c.text;
    EXPECT_EQ(error.rfind(c.why, 0), 0u) << c.text << " -> " << error;
  }
  std::string error;
  const std::string whole = with_line(0, "");
  EXPECT_FALSE(parse_checkpoint(whole.substr(0, whole.size() / 2), "state", kOptions, error));
  EXPECT_NE(error.find("ends"), std::string::npos) << error;
  EXPECT_FALSE(parse_checkpoint("", "state", kOptions, error));
}

}  // namespace
}  // namespace fuzzypid::cli
