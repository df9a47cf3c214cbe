// Precomputed benchmark inputs. Every benchmark walks a table of a few hundred entries so the
// compiler cannot fold the input into a constant and branch predictors see realistic variation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/gain_schedule.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"
#include "fuzzypid/supervisor/rule_table.hpp"

namespace fuzzypid::bench {

// Table length: a power of two so the index wraps with a mask.
inline constexpr std::size_t kTableSize = 1024;
inline constexpr std::size_t kTableMask = kTableSize - 1;

// splitmix64: a fully specified generator, so every platform benchmarks the same inputs
// (std::uniform_real_distribution is implementation-defined).
class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
  constexpr std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  // Uniform in [lo, hi).
  constexpr double uniform(double lo, double hi) noexcept {
    return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

// (e, ec) pairs in universe units. Mostly inside the paper's universe [-0.3, 0.3], about 14 % just
// outside it so the shoulders' saturation path is exercised as well.
struct ErrorPair {
  double e;
  double ec;
};

inline std::array<ErrorPair, kTableSize> make_error_table(std::uint64_t seed = 42) {
  std::array<ErrorPair, kTableSize> table{};
  SplitMix64 rng(seed);
  for (auto& p : table)
    p = {rng.uniform(-0.35, 0.35), rng.uniform(-0.35, 0.35)};
  return table;
}

// One 6-joint tick's input per entry: tracking errors of up to +-0.35 rad and +-0.35 rad/s around
// a moving reference, so the fuzzy supervisor sees inputs across its whole universe and slightly
// outside it.
using TickInput = supervisor::JointInput<double, 6>;

inline std::array<TickInput, kTableSize> make_tick_table() {
  std::array<TickInput, kTableSize> table{};
  SplitMix64 rng(7);
  for (auto& t : table) {
    for (std::size_t j = 0; j < 6; ++j) {
      t.desired_position_rad[j] = rng.uniform(-1.5, 1.5);
      t.desired_velocity_rad_s[j] = rng.uniform(-0.5, 0.5);
      t.measured_position_rad[j] = t.desired_position_rad[j] + rng.uniform(-0.35, 0.35);
      t.measured_velocity_rad_s[j] = t.desired_velocity_rad_s[j] + rng.uniform(-0.35, 0.35);
    }
  }
  return table;
}

// The PID of the tick benchmarks: the paper's gains (section 5.2) with the derivative taken from
// the measured rates (Eq. 2).
inline pid::Config<double> tick_pid_config() {
  pid::Config<double> c;
  c.gains = paper::kNominalGains<double>;
  c.derivative_source = pid::DerivativeSource::Rates;
  return c;
}

// The supervised families as the tuner builds them (K0 the tick PID's gains, Ke = 12, Kec = 0.7).
inline supervisor::FuzzyPidConfig<double> supervised_config(
    const std::array<double, 3>& output_scale) {
  supervisor::FuzzyPidConfig<double> c;
  c.pid = tick_pid_config();
  c.error_scale = 12.0;
  c.error_rate_scale = 0.7;
  c.output_scale = output_scale;
  return c;
}

// A gain schedule (the default ramp), its output scale S = (R - 1) K0 with R = (0.3, 4, 1.6).
inline supervisor::FuzzyPid<double, supervisor::GainSchedule<double>> scheduled_joint() {
  static constexpr supervisor::GainSchedule<double> kSchedule{};
  const auto k0 = tick_pid_config().gains;
  return {&kSchedule, supervised_config({-0.7 * k0.kp, 3.0 * k0.ki, 0.6 * k0.kd})};
}

// A fuzzy-rules table with the same ramp and cells from 1.0 to 1.2 (the cost of a tick does not
// depend on the cells' values; S = K0).
inline supervisor::FuzzyPid<double, supervisor::RuleTable<double>> fuzzy_rules_joint() {
  using Table = supervisor::RuleTable<double>;
  static const Table kTable = [] {
    Table t;
    t.schedule_ratio = {0.3, 4.0, 1.6};
    for (std::size_t g = 0; g < 3; ++g)
      for (std::size_t i = 0; i < Table::num_sets(); ++i)
        for (std::size_t j = 0; j < Table::num_sets(); ++j)
          t.table[g][i][j] = 1.0 + 0.05 * static_cast<double>((i * 7 + j * 3 + g) % 5);
    return t;
  }();
  const auto k0 = tick_pid_config().gains;
  return {&kTable, supervised_config({k0.kp, k0.ki, k0.kd})};
}

}  // namespace fuzzypid::bench
