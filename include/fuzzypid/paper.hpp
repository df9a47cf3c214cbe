// The fuzzy supervisor of Tao et al., "Fuzzy PID control method of deburring industrial robots",
// as ready-made constexpr data: its input partition (section 5.1, Fig. 4), its three rule tables
// exactly as printed (Tables 2-4), corrected variants of the two cells that look misprinted, the
// nominal PID gains (section 5.2), the paper's FuzzyPid configuration, and aliases for
// controllers supervised by the paper's system. Nothing in supervisor/, pid/ or fuzzy/ includes this
// header: the generic parts do not know the paper.
#pragma once

#include <cstddef>

#include "fuzzypid/fuzzy/consequent_table.hpp"
#include "fuzzypid/fuzzy/linguistic_variable.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/fuzzy/tsk_system.hpp"
#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"

namespace fuzzypid::paper {

// Seven terms NL, NM, NS, ZE, PS, PM, PL for e and ec.
inline constexpr std::size_t kNumTerms = 7;
inline constexpr const char* kTermNames[kNumTerms] = {"NL", "NM", "NS", "ZE", "PS", "PM", "PL"};

// Universe of e and ec: {-0.3, ..., 0.3} in steps of 0.1 (section 5.1). The paper does not say
// in which unit; the fuzzy PID maps physical errors onto it with scaling factors.
inline constexpr double kUniformMin = -0.3;
inline constexpr double kUniformMax = 0.3;

// Nominal gains found by test in section 5.2: Kp = 4, Ki = 0.001, Kd = 100.
template <class Scalar>
inline constexpr pid::Gains<Scalar> kNominalGains{Scalar(4), Scalar(0.001), Scalar(100)};

using Table = fuzzy::ConsequentTable<double, kNumTerms, kNumTerms>;

// Table 2: Delta Kp, rows e = NL..PL, columns ec = NL..PL, exactly as printed.
inline constexpr Table kDeltaKpPrinted{{
    {{0.03, 0.03, 0.03, 0.03, 0.02, 0.01, 0}},
    {{0.03, 0.03, 0.03, 0.03, 0.02, 0, 0}},
    {{0.02, 0.02, 0.02, 0.02, 0, 0.01, 0.01}},
    {{0.02, 0.02, 0.01, 0, -0.01, -0.01, -0.01}},
    {{0.01, 0.01, 0, -0.02, -0.02, -0.02, -0.02}},
    {{0.01, 0, -0.01, -0.02, -0.02, -0.02, -0.03}},
    {{0, 0, -0.02, -0.02, -0.02, -0.03, -0.03}},
}};

// Table 3: Delta Ki, exactly as printed.
inline constexpr Table kDeltaKiPrinted{{
    {{-0.03, -0.03, -0.02, -0.02, -0.01, 0, 0}},
    {{-0.03, -0.03, -0.02, -0.01, -0.01, 0, 0}},
    {{-0.03, -0.02, -0.01, -0.01, 0, 0.01, 0.01}},
    {{-0.02, -0.02, -0.01, 0, 0.01, 0.02, 0.02}},
    {{-0.02, -0.01, 0, 0.01, 0.01, 0.02, 0.03}},
    {{0, 0, 0.01, -0.02, 0.02, 0.03, 0.03}},
    {{0, 0, 0.01, 0.02, 0.02, 0.03, 0.03}},
}};

// Table 4: Delta Kd, exactly as printed.
inline constexpr Table kDeltaKdPrinted{{
    {{0.1, -0.1, -0.3, -0.3, -0.3, -0.2, 0.1}},
    {{0.1, -0.1, -0.3, -0.2, -0.2, -0.1, 0}},
    {{0, -0.1, -0.2, -0.1, -0.1, -0.1, 0}},
    {{0, -0.1, -0.1, -0.1, -0.1, -0.1, 0}},
    {{0, 0, 0, 0, 0, 0, 0}},
    {{0, 0.1, 0.1, 0.1, 0.1, 0.1, 0.3}},
    {{0.3, 0.2, 0.2, 0.2, 0.1, 0.1, 0.3}},
}};

// Table 2 with row NS made monotone in ec like every other row: the printed (..., 0, 0.01, 0.01)
// turns back up after 0, which reads as two lost minus signs; corrected to (..., 0, -0.01, -0.01).
inline constexpr Table kDeltaKpCorrected{{
    kDeltaKpPrinted[0],
    kDeltaKpPrinted[1],
    {{0.02, 0.02, 0.02, 0.02, 0, -0.01, -0.01}},
    kDeltaKpPrinted[3],
    kDeltaKpPrinted[4],
    kDeltaKpPrinted[5],
    kDeltaKpPrinted[6],
}};

// Table 3 with cell (PM, ZE) printed as -0.02 between +0.01 and +0.02 in its row, and below +0.01
// in its column, read as a lost plus sign: corrected to +0.02, which makes row PM and column ZE
// non-decreasing like the rest of the table.
inline constexpr Table kDeltaKiCorrected{{
    kDeltaKiPrinted[0],
    kDeltaKiPrinted[1],
    kDeltaKiPrinted[2],
    kDeltaKiPrinted[3],
    kDeltaKiPrinted[4],
    {{0, 0, 0.01, 0.02, 0.02, 0.03, 0.03}},
    kDeltaKiPrinted[6],
}};

enum class Tables {
  Printed,    // Tables 2-4 exactly as printed (the default)
  Corrected,  // with the two suspected misprints fixed (see kDeltaKpCorrected, kDeltaKiCorrected)
};

// Output order of the paper's system.
inline constexpr std::size_t kDeltaKp = 0;
inline constexpr std::size_t kDeltaKi = 1;
inline constexpr std::size_t kDeltaKd = 2;

template <class Scalar>
using System = fuzzy::TskSystem<Scalar, kNumTerms, kNumTerms, 3>;

namespace detail {
template <class Scalar>
constexpr fuzzy::ConsequentTable<Scalar, kNumTerms, kNumTerms> cast(const Table& t) noexcept {
  fuzzy::ConsequentTable<Scalar, kNumTerms, kNumTerms> out{};
  for (std::size_t i = 0; i < kNumTerms; ++i)
    for (std::size_t j = 0; j < kNumTerms; ++j)
      out[i][j] = static_cast<Scalar>(t[i][j]);
  return out;
}
}  // namespace detail

// The paper's supervisor: e, ec -> (Delta Kp, Delta Ki, Delta Kd), seven uniform triangular sets
// on [-0.3, 0.3] with shoulders at the ends, center-average defuzzification (Eq. 8). The paper
// does not name its AND operator; minimum is the Mamdani/MATLAB default.
template <class Scalar>
constexpr System<Scalar> make_system(fuzzy::Conjunction conjunction = fuzzy::Conjunction::Minimum,
                                     Tables tables = Tables::Printed) noexcept {
  System<Scalar> s;
  s.e = fuzzy::LinguisticVariable<Scalar, kNumTerms>::uniform(Scalar(kUniformMin),
                                                              Scalar(kUniformMax));
  s.ec = s.e;
  const bool corrected = tables == Tables::Corrected;
  s.consequents[kDeltaKp] = detail::cast<Scalar>(corrected ? kDeltaKpCorrected : kDeltaKpPrinted);
  s.consequents[kDeltaKi] = detail::cast<Scalar>(corrected ? kDeltaKiCorrected : kDeltaKiPrinted);
  s.consequents[kDeltaKd] = detail::cast<Scalar>(kDeltaKdPrinted);
  s.conjunction = conjunction;
  s.defuzzifier = fuzzy::TskDefuzzifier::WeightedAverage;
  return s;
}

// The paper's supervisor with its defaults (minimum, tables as printed) as constexpr data: it
// lives for the whole program, so controllers may point to it from anywhere.
template <class Scalar>
inline constexpr System<Scalar> kSystem = make_system<Scalar>();

// The paper's configuration: K0 = (4, 0.001, 100), unit scales, absolute update (Eq. 6).
template <class Scalar>
constexpr supervisor::FuzzyPidConfig<Scalar> paper_config() noexcept {
  supervisor::FuzzyPidConfig<Scalar> c;
  c.pid.gains = kNominalGains<Scalar>;
  return c;
}

// A PID retuned by the paper's supervisor (or any System<Scalar> the caller owns). The paper's
// derivative is the rates' or the differenced error's, so its PID omits the velocity observer's
// storage (pid::ObserverStorage): six double joints then fit in 2 KB.
template <class Scalar>
using FuzzyPid = supervisor::FuzzyPid<Scalar, System<Scalar>, pid::ObserverStorage::Omitted>;

// N joints, each a paper::FuzzyPid; 6 for the ER50-C20.
template <class Scalar, std::size_t N = 6>
using JointController = supervisor::JointController<Scalar, N, FuzzyPid<Scalar>>;

// A controller on kSystem with `config` (the paper's by default).
template <class Scalar>
FuzzyPid<Scalar> make_fuzzy_pid(
    const supervisor::FuzzyPidConfig<Scalar>& config = paper_config<Scalar>()) noexcept {
  return FuzzyPid<Scalar>(&kSystem<Scalar>, config);
}

// N joints on kSystem with the paper's configuration.
template <class Scalar, std::size_t N = 6>
JointController<Scalar, N> make_joint_controller() noexcept {
  return JointController<Scalar, N>(make_fuzzy_pid<Scalar>());
}

}  // namespace fuzzypid::paper
