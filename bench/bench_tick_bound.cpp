// How fast the 6-joint fuzzy tick could be if it were written for one configuration only: the
// measure behind the "fuzzy tick <= 3x the PID tick" discussion in docs/performance.md.
//
// SpecialisedTick runs exactly the arithmetic of JointController<double, 6> with the paper's
// FuzzyPid as bench_controller.cpp configures it (uniform 7-term partitions, minimum conjunction,
// weighted average, absolute gain update, PID with the derivative from the measured rates, no
// filter, conditional integration), with every configuration test compiled out, no fault
// diagnosis and no per-joint status; of the per-joint state it keeps what the library's
// controller must keep for the next tick and for its user: the integral and this tick's gains
// (Figs. 12-14). It is not a controller to use: it is a floor for the library tick. Two orders of
// the same operations:
//   per_joint  each joint from start to end in turn, as the library's tick runs;
//   lanes      each step for all six joints before the next (locate all inputs, fire all blocks,
//              one division per joint back to back, ...), so the joints' dependency chains
//              overlap on an out-of-order CPU.
// Before timing, each variant runs 2,000 ticks beside the library's controller and reports the
// largest difference of the commands (max_abs_diff; 0 = bit for bit); a difference stops the
// benchmark with an error.
#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>
#include <limits>

#include "bench_inputs.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/scalar.hpp"

namespace {

namespace fp = fuzzypid;
using fp::bench::TickInput;
using fp::detail::clamp;
using fp::detail::max;
using fp::detail::min;

constexpr std::size_t kJoints = 6;
constexpr double kDt = 0.05;  // s
using Output = fp::supervisor::JointOutput<double, kJoints>;
using System = fp::paper::System<double>;

class SpecialisedTick {
 public:
  SpecialisedTick(const System& system, const fp::supervisor::FuzzyPidConfig<double>& config)
      : system_(system),
        e_min_(system.e.min()),
        e_max_(system.e.max()),
        ec_min_(system.ec.min()),
        ec_max_(system.ec.max()),
        e_inverse_step_(inverse_step(e_min_, e_max_)),
        ec_inverse_step_(inverse_step(ec_min_, ec_max_)),
        config_(config) {}

  // True when this tick reproduces the library's configuration (the benchmark checks the
  // commands as well).
  bool matches(const fp::supervisor::FuzzyPidConfig<double>& c) const noexcept {
    using fp::pid::AntiWindup;
    using fp::pid::DerivativeOn;
    using fp::pid::DerivativeSource;
    return system_.e.is_uniform() && system_.ec.is_uniform() &&
           system_.conjunction == fp::fuzzy::Conjunction::Minimum &&
           system_.defuzzifier == fp::fuzzy::TskDefuzzifier::WeightedAverage &&
           c.gain_update == fp::supervisor::GainUpdate::Absolute &&
           c.pid.derivative_source == DerivativeSource::Rates &&
           c.pid.derivative_on == DerivativeOn::Error && c.pid.derivative_filter_s == 0.0 &&
           c.pid.anti_windup == AntiWindup::Clamping;
  }

  [[gnu::flatten]] Output per_joint(const TickInput& in, double dt_s) noexcept {
    Output out;
    for (std::size_t i = 0; i < kJoints; ++i) {
      const double e = in.desired_position_rad[i] - in.measured_position_rad[i];
      const double ec = in.desired_velocity_rad_s[i] - in.measured_velocity_rad_s[i];
      const double x = config_.error_scale * e;
      const double y = config_.error_rate_scale * ec;
      if (!fp::detail::is_finite(x) || !fp::detail::is_finite(y)) return fault();
      const Located a = locate(x, e_min_, e_max_, e_inverse_step_);
      const Located b = locate(y, ec_min_, ec_max_, ec_inverse_step_);
      const Weights w = weights(a, b);
      const double scale = 1.0 / (w.w00 + w.w01 + w.w10 + w.w11);
      out.output[i] = finish(i, in, dt_s, e, ec, a, b, w, scale);
      out.joint_status[i] = fp::Status::Ok;
    }
    out.status = fp::Status::Ok;
    return out;
  }

  [[gnu::flatten]] Output lanes(const TickInput& in, double dt_s) noexcept {
    std::array<double, kJoints> e, ec, scale;
    std::array<Located, kJoints> a, b;
    std::array<Weights, kJoints> w;
    bool finite = true;
    for (std::size_t i = 0; i < kJoints; ++i) {
      e[i] = in.desired_position_rad[i] - in.measured_position_rad[i];
      ec[i] = in.desired_velocity_rad_s[i] - in.measured_velocity_rad_s[i];
      const double x = config_.error_scale * e[i];
      const double y = config_.error_rate_scale * ec[i];
      finite = finite && fp::detail::is_finite(x) && fp::detail::is_finite(y);
      a[i] = locate(x, e_min_, e_max_, e_inverse_step_);
      b[i] = locate(y, ec_min_, ec_max_, ec_inverse_step_);
    }
    if (!finite) return fault();
    for (std::size_t i = 0; i < kJoints; ++i)
      w[i] = weights(a[i], b[i]);
    for (std::size_t i = 0; i < kJoints; ++i)
      scale[i] = 1.0 / (w[i].w00 + w[i].w01 + w[i].w10 + w[i].w11);
    Output out;
    for (std::size_t i = 0; i < kJoints; ++i) {
      out.output[i] = finish(i, in, dt_s, e[i], ec[i], a[i], b[i], w[i], scale[i]);
      out.joint_status[i] = fp::Status::Ok;
    }
    out.status = fp::Status::Ok;
    return out;
  }

 private:
  struct Located {
    int k;
    double lower, upper;
  };
  struct Weights {
    double w00, w01, w10, w11;
  };

  // 1/h of a 7-term uniform partition on [lo, hi], rounded as LinguisticVariable::uniform() does.
  static double inverse_step(double lo, double hi) noexcept {
    double r = 6.0 / (hi - lo);
    for (int k = 0; k < 4 && (hi - lo) * r > 6.0; ++k)
      r -= r * std::numeric_limits<double>::epsilon();
    return r;
  }

  // LinguisticVariable::locate() for a 7-term uniform partition (a non-finite x is not passed).
  static Located locate(double x, double lo, double hi, double inverse_step) noexcept {
    const double t = (clamp(x, lo, hi) - lo) * inverse_step;
    const int floor_t = static_cast<int>(t);
    const int k = floor_t < 5 ? floor_t : 5;
    const double upper = t - static_cast<double>(k);
    return {k, 1.0 - upper, upper};
  }

  static Weights weights(const Located& a, const Located& b) noexcept {
    return {min(a.lower, b.lower), min(a.lower, b.upper), min(a.upper, b.lower),
            min(a.upper, b.upper)};
  }

  // The defuzzified gain changes, the gain update and the PID of joint i (Eqs. 6-8, Eq. 2).
  double finish(std::size_t i, const TickInput& in, double dt_s, double e, double ec,
                const Located& a, const Located& b, const Weights& w, double scale) noexcept {
    std::array<double, 3> delta;
    for (std::size_t o = 0; o < 3; ++o) {
      const double* row = system_.consequents[o][static_cast<std::size_t>(a.k)].data() + b.k;
      const double* next = system_.consequents[o][static_cast<std::size_t>(a.k) + 1].data() + b.k;
      delta[o] = (w.w00 * row[0] + w.w01 * row[1] + w.w10 * next[0] + w.w11 * next[1]) * scale;
    }
    const fp::pid::Gains<double>& k0 = config_.pid.gains;
    const fp::pid::Gains<double> g{
        clamp(k0.kp + config_.output_scale[0] * delta[0], config_.gain_min.kp, config_.gain_max.kp),
        clamp(k0.ki + config_.output_scale[1] * delta[1], config_.gain_min.ki, config_.gain_max.ki),
        clamp(k0.kd + config_.output_scale[2] * delta[2], config_.gain_min.kd,
              config_.gain_max.kd)};
    const fp::pid::Config<double>& c = config_.pid;
    const double ff = in.feed_forward[i];
    const double p = g.kp * e;
    const double d = g.kd * ec;
    const double increment = g.ki * e * dt_s;
    double integral = clamp(integral_[i] + increment, c.integral_min, c.integral_max);
    const double rest = p + d + ff;
    const double trial = rest + integral;
    if (trial > c.output_max && increment > 0.0)
      integral = clamp(max(integral_[i], c.output_max - rest), c.integral_min, c.integral_max);
    if (trial < c.output_min && increment < 0.0)
      integral = clamp(min(integral_[i], c.output_min - rest), c.integral_min, c.integral_max);
    const double v = p + integral + d + ff;
    const double u = clamp(v, c.output_min, c.output_max);
    integral_[i] = integral;
    gains_[i] = g;
    return u;
  }

  static Output fault() noexcept {
    Output out;
    out.status = fp::Status::NonFiniteInput;
    return out;
  }

  const System& system_;
  double e_min_, e_max_, ec_min_, ec_max_;
  double e_inverse_step_, ec_inverse_step_;
  fp::supervisor::FuzzyPidConfig<double> config_;
  std::array<double, kJoints> integral_{};
  std::array<fp::pid::Gains<double>, kJoints> gains_{};  // this tick's gains, as FuzzyPid::gains()
};

template <bool Lanes>
void run_bound(benchmark::State& state) {
  auto config = fp::paper::paper_config<double>();
  config.pid = fp::bench::tick_pid_config();
  const System& system = fp::paper::kSystem<double>;
  SpecialisedTick tick(system, config);
  if (!tick.matches(config)) {
    state.SkipWithError("the specialised tick does not match the benchmark's configuration");
    return;
  }
  const auto table = fp::bench::make_tick_table();
  {
    SpecialisedTick check(system, config);
    fp::paper::JointController<double, kJoints> library(
        fp::paper::FuzzyPid<double>(&system, config));
    double max_abs_diff = 0.0;
    for (std::size_t k = 0; k < 2000; ++k) {
      const TickInput& t = table[k & fp::bench::kTableMask];
      const Output mine = Lanes ? check.lanes(t, kDt) : check.per_joint(t, kDt);
      const Output theirs = library.step(t, kDt);
      for (std::size_t j = 0; j < kJoints; ++j)
        max_abs_diff = max(max_abs_diff, fp::detail::abs(mine.output[j] - theirs.output[j]));
    }
    state.counters["max_abs_diff"] = max_abs_diff;
    if (max_abs_diff != 0.0) {
      state.SkipWithError("the specialised tick differs from the library's");
      return;
    }
  }
  std::size_t k = 0;
  for (auto _ : state) {
    const TickInput& t = table[k++ & fp::bench::kTableMask];
    const Output out = Lanes ? tick.lanes(t, kDt) : tick.per_joint(t, kDt);
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_ControllerStep6_bound_per_joint(benchmark::State& state) {
  run_bound<false>(state);
}
BENCHMARK(BM_ControllerStep6_bound_per_joint)->Name("BM_ControllerStep6/specialised_per_joint");

void BM_ControllerStep6_bound_lanes(benchmark::State& state) {
  run_bound<true>(state);
}
BENCHMARK(BM_ControllerStep6_bound_lanes)->Name("BM_ControllerStep6/specialised_lanes");

}  // namespace
