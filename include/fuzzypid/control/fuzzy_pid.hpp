// A PID whose gains a fuzzy supervisor retunes every tick (sections 5.1-5.3, Eqs. 6-8).
//
// Each update:
//   1. e = setpoint - measurement and its rate ec (the measured velocities, Eq. 2 and section
//      5.1, or the difference of e over dt, following the PID's DerivativeSource);
//   2. the supervisor sees the scaled inputs (Ke e, Kec ec) -- the physical error mapped onto the
//      fuzzy universe; outside it the shoulder sets saturate;
//   3. it returns (dKp, dKi, dKd), multiplied by the output scales (Sp, Si, Sd);
//   4. the gains become, by GainUpdate,
//        Absolute:     K = K0 + S dK                    (Eq. 6, memoryless)
//        Incremental:  K = K_prev + S dK                (each tick adds to the last gains)
//      then are clamped into [gain_min, gain_max] (by default [0, inf): no negative gain);
//   5. the inner PID runs with the new gains (Eq. 7).
// A fault (NaN/inf input, bad dt) is detected before step 2 and leaves gains and PID untouched.
#pragma once

#include <array>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::detail {

// Whether System offers infer_outputs(e, ec): infer()'s outputs and status without its other
// fields (fuzzy::TskSystem does).
template <class System, class Scalar, class = void>
struct has_infer_outputs : std::false_type {};
template <class System, class Scalar>
struct has_infer_outputs<System, Scalar,
                         std::void_t<decltype(std::declval<const System&>().infer_outputs(
                             std::declval<Scalar>(), std::declval<Scalar>()))>> : std::true_type {};

}  // namespace fuzzypid::detail

namespace fuzzypid::control {

enum class GainUpdate : std::uint8_t {
  Absolute,     // K = K0 + dK  (Eq. 6)
  Incremental,  // K_k = K_{k-1} + dK
};

[[nodiscard]] constexpr const char* to_string(GainUpdate g) noexcept {
  return g == GainUpdate::Absolute ? "absolute" : "incremental";
}

template <class Scalar>
struct FuzzyPidConfig {
  pid::Config<Scalar> pid{};            // inner PID; pid.gains are the nominal gains K0
  Scalar error_scale = Scalar(1);       // Ke, universe units per unit of e (e.g. per rad)
  Scalar error_rate_scale = Scalar(1);  // Kec, universe units per unit of ec (e.g. per rad/s)
  std::array<Scalar, 3> output_scale{Scalar(1), Scalar(1), Scalar(1)};  // Sp, Si, Sd
  GainUpdate gain_update = GainUpdate::Absolute;
  pid::Gains<Scalar> gain_min{Scalar(0), Scalar(0), Scalar(0)};
  pid::Gains<Scalar> gain_max{detail::infinity<Scalar>(), detail::infinity<Scalar>(),
                              detail::infinity<Scalar>()};

  constexpr bool valid() const noexcept {
    using detail::is_finite;
    const auto ordered = [](Scalar lo, Scalar hi) { return lo == lo && hi == hi && lo <= hi; };
    return pid.valid() && is_finite(error_scale) && is_finite(error_rate_scale) &&
           is_finite(output_scale[0]) && is_finite(output_scale[1]) && is_finite(output_scale[2]) &&
           ordered(gain_min.kp, gain_max.kp) && ordered(gain_min.ki, gain_max.ki) &&
           ordered(gain_min.kd, gain_max.kd);
  }
};

// The paper's configuration: K0 = (4, 0.001, 100), unit scales, absolute update.
template <class Scalar>
constexpr FuzzyPidConfig<Scalar> paper_config() noexcept {
  FuzzyPidConfig<Scalar> c;
  c.pid.gains = paper::kNominalGains<Scalar>;
  return c;
}

// System is any fuzzy system with `infer(e, ec)` returning an object with `output[0..2]`
// (dKp, dKi, dKd) and `status` -- the paper's built-in table system by default.
template <class Scalar, class System = paper::System<Scalar>>
class FuzzyPid {
  FUZZYPID_ASSERT_SCALAR(Scalar);

 public:
  using Config = FuzzyPidConfig<Scalar>;
  using Input = pid::Input<Scalar>;
  using Gains = pid::Gains<Scalar>;

  FuzzyPid() noexcept : FuzzyPid(paper::make_system<Scalar>(), paper_config<Scalar>()) {}

  // An invalid configuration leaves the controller unconfigured: update() returns InvalidConfig.
  FuzzyPid(const System& system, const Config& config) noexcept : system_(system) {
    configured_ = configure(config);
  }

  // Replaces the configuration and resets the gains to the nominal K0 (state is kept).
  Status configure(const Config& config) noexcept {
    if (!config.valid()) return Status::InvalidConfig;
    const Status s = pid_.configure(config.pid);
    if (s != Status::Ok) return s;
    config_ = config;
    gains_ = clamp_gains(config.pid.gains);
    (void)pid_.set_gains(gains_);
    configured_ = Status::Ok;
    return Status::Ok;
  }

  // One tick: retune the gains from (e, ec), then run the PID. Returns Ok, NoRuleFired (gains
  // left at their nominal/previous value for this tick, PID still run) or a fault.
  // Flattened (GCC/Clang) so the inference and the PID inline into one body: the compiler then
  // drops the parts of the inference result the tick does not read (bench/README.md).
  [[gnu::flatten]] Status update(const Input& in, Scalar dt_s) noexcept {
    if (configured_ != Status::Ok) return configured_;
    if (!(dt_s > Scalar(0)) || !detail::is_finite(dt_s)) return Status::InvalidTimeStep;
    if (!pid_.finite(in)) return Status::NonFiniteInput;  // the PID's own input check

    const Scalar e = in.setpoint - in.measurement;
    Scalar ec = Scalar(0);
    if (config_.pid.derivative_source == pid::DerivativeSource::Rates) {
      ec = in.setpoint_rate - in.measurement_rate;
    } else if (pid_.has_previous()) {
      ec = (e - pid_.previous_error()) / dt_s;
    }
    const auto inference = infer_tick(config_.error_scale * e, config_.error_rate_scale * ec);
    if (is_fault(inference.status)) return Status::NumericOverflow;

    const Gains& base = config_.gain_update == GainUpdate::Absolute ? config_.pid.gains : gains_;
    const Gains next = retuned(base, inference.output);
    if (!next.finite()) return Status::NumericOverflow;
    // The inputs and dt passed the PID's own checks above (same conditions, same derivative
    // source), and pid_ is always configured (configure() only accepts a configuration it took),
    // so the step runs unchecked; it adopts `next` only on success, as set_gains() + update()
    // with a restore on fault did.
    const Status s = pid_.template step<true>(in, dt_s, next);
    if (is_fault(s)) return s;
    gains_ = next;
    delta_ = inference.output;
    return inference.status == Status::NoRuleFired ? Status::NoRuleFired : s;
  }

  // Restores the nominal gains and clears the PID state.
  void reset() noexcept {
    pid_.reset();
    gains_ = clamp_gains(config_.pid.gains);
    (void)pid_.set_gains(gains_);
    delta_ = {};
  }

  // Bumpless start at `output` (see pid::Pid::initialize); gains restart at K0. The next update
  // retunes the gains from this input's (e, ec) before the PID runs, so the integral is set with
  // those retuned gains: that update then reproduces `output` (plus one step Ki' e dt).
  Status initialize(Scalar output, const Input& in) noexcept {
    const Gains nominal = clamp_gains(config_.pid.gains);
    Gains next = nominal;
    const Scalar e = in.setpoint - in.measurement;
    const Scalar ec = config_.pid.derivative_source == pid::DerivativeSource::Rates
                          ? in.setpoint_rate - in.measurement_rate
                          : Scalar(0);  // the difference source sees e twice: ec = 0
    if (detail::is_finite(e) && detail::is_finite(ec)) {
      const auto inference = system_.infer(config_.error_scale * e, config_.error_rate_scale * ec);
      if (!is_fault(inference.status)) next = retuned(config_.pid.gains, inference.output);
    }
    const Gains previous = pid_.gains();
    if (pid_.set_gains(next) != Status::Ok) return Status::NumericOverflow;
    const Status s = pid_.initialize(output, in);
    if (s != Status::Ok) {
      (void)pid_.set_gains(previous);
      return s;
    }
    gains_ = nominal;
    (void)pid_.set_gains(gains_);
    delta_ = {};
    return s;
  }

  Scalar output() const noexcept { return pid_.output(); }
  // The gains used by the last update (Kp, Ki, Kd: the paper's Figs. 12-14).
  const Gains& gains() const noexcept { return gains_; }
  // The supervisor's last raw outputs (dKp, dKi, dKd), before output scaling.
  const std::array<Scalar, 3>& delta() const noexcept { return delta_; }
  const pid::Pid<Scalar>& pid() const noexcept { return pid_; }
  const System& system() const noexcept { return system_; }
  const Config& config() const noexcept { return config_; }

 private:
  // The inference of one tick: only its outputs and status are read, so use the system's
  // infer_outputs() where it has one (same values, no fuzzified inputs to build).
  auto infer_tick(Scalar e, Scalar ec) const noexcept {
    if constexpr (detail::has_infer_outputs<System, Scalar>::value) {
      return system_.infer_outputs(e, ec);
    } else {
      return system_.infer(e, ec);
    }
  }

  // K = base + S dK, clamped into the gain bounds (Eqs. 6-7; base is K0 or the last gains).
  Gains retuned(const Gains& base, const std::array<Scalar, 3>& delta) const noexcept {
    return clamp_gains({base.kp + config_.output_scale[0] * delta[0],
                        base.ki + config_.output_scale[1] * delta[1],
                        base.kd + config_.output_scale[2] * delta[2]});
  }

  Gains clamp_gains(const Gains& g) const noexcept {
    return {detail::clamp(g.kp, config_.gain_min.kp, config_.gain_max.kp),
            detail::clamp(g.ki, config_.gain_min.ki, config_.gain_max.ki),
            detail::clamp(g.kd, config_.gain_min.kd, config_.gain_max.kd)};
  }

  System system_;
  Config config_{};
  Status configured_ = Status::Ok;
  pid::Pid<Scalar> pid_{};
  Gains gains_{};
  std::array<Scalar, 3> delta_{};
};

}  // namespace fuzzypid::control
