// The paper's supervisor (section 5, Tables 2-4, Eq. 8) as shipped in fuzzypid/paper.hpp.
#include <gtest/gtest.h>

#include "fuzzypid/paper.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::Conjunction;
namespace paper = fuzzypid::paper;

TEST(PaperSystem, AtEveryPairOfTermCentersReturnsThePrintedCells) {
  for (const auto conjunction : {Conjunction::Minimum, Conjunction::Product}) {
    const auto system = paper::make_system<double>(conjunction);
    for (std::size_t i = 0; i < paper::kNumTerms; ++i) {
      for (std::size_t j = 0; j < paper::kNumTerms; ++j) {
        const double e = -0.3 + 0.1 * static_cast<double>(i);
        const double ec = -0.3 + 0.1 * static_cast<double>(j);
        const auto r = system.infer(e, ec);
        ASSERT_EQ(r.status, Status::Ok);
        EXPECT_NEAR(r.output[paper::kDeltaKp], paper::kDeltaKpPrinted[i][j], 1e-15);
        EXPECT_NEAR(r.output[paper::kDeltaKi], paper::kDeltaKiPrinted[i][j], 1e-15);
        EXPECT_NEAR(r.output[paper::kDeltaKd], paper::kDeltaKdPrinted[i][j], 1e-15);
      }
    }
  }
}

TEST(PaperSystem, BetweenCentersIsTheCenterAverageOfTheFourFiringRules) {
  // e = 0.05: ZE 0.5, PS 0.5; ec = -0.12: NM 0.2, NS 0.8. Minimum conjunction gives strengths
  // (ZE,NM) 0.2, (ZE,NS) 0.5, (PS,NM) 0.2, (PS,NS) 0.5 and Eq. 8 the weighted mean of the cells.
  const auto r = paper::make_system<double>().infer(0.05, -0.12);
  ASSERT_EQ(r.status, Status::Ok);
  const auto& kp = paper::kDeltaKpPrinted;
  const double expected = (0.2 * kp[3][1] + 0.5 * kp[3][2] + 0.2 * kp[4][1] + 0.5 * kp[4][2]) / 1.4;
  EXPECT_NEAR(r.output[paper::kDeltaKp], expected, 1e-15);
  EXPECT_NEAR(r.firing_strength(3, 2), 0.5, 1e-15);
  EXPECT_NEAR(r.firing_strength(4, 1), 0.2, 1e-15);
  EXPECT_EQ(r.firing_strength(0, 0), 0.0);
  EXPECT_NEAR(r.total_strength, 1.4, 1e-15);
}

TEST(PaperSystem, InputsOutsideTheUniverseSaturateAtTheOuterSets) {
  const auto system = paper::make_system<double>();
  const auto far = system.infer(7.0, -1e9);
  const auto edge = system.infer(0.3, -0.3);
  ASSERT_EQ(far.status, Status::Ok);
  EXPECT_EQ(far.output, edge.output);
  EXPECT_EQ(far.output[paper::kDeltaKp], paper::kDeltaKpPrinted[6][0]);
}

TEST(PaperSystem, NonFiniteInputsAreReportedWithZeroOutputs) {
  const auto system = paper::make_system<double>();
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const auto r = system.infer(bad, 0.0);
    EXPECT_EQ(r.status, Status::NonFiniteInput);
    EXPECT_EQ(r.output[0], 0.0);
    EXPECT_EQ(system.infer(0.0, bad).status, Status::NonFiniteInput);
  }
}

TEST(PaperSystem, CorrectedTablesDifferFromThePrintedOnesInExactlyThreeCells) {
  int differences = 0;
  for (std::size_t i = 0; i < paper::kNumTerms; ++i)
    for (std::size_t j = 0; j < paper::kNumTerms; ++j)
      differences += (paper::kDeltaKpCorrected[i][j] != paper::kDeltaKpPrinted[i][j]) +
                     (paper::kDeltaKiCorrected[i][j] != paper::kDeltaKiPrinted[i][j]);
  EXPECT_EQ(differences, 3);
  EXPECT_EQ(paper::kDeltaKiCorrected[5][3], 0.02);
}

}  // namespace
