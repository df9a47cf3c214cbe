// A PID whose gains a supervisor retunes every tick (sections 5.1-5.3, Eqs. 6-8).
//
// Each update:
//   1. the PID defines e = setpoint - measurement and its rate ec once (pid::Pid::error(): the
//      measured velocities, Eq. 2 and section 5.1, or the difference of e over dt, following the
//      PID's DerivativeSource);
//   2. the supervisor sees the scaled inputs (Ke e, Kec ec) -- the physical error mapped onto the
//      fuzzy universe; outside it the shoulder sets saturate;
//   3. it returns (dKp, dKi, dKd), multiplied by the output scales (Sp, Si, Sd);
//   4. the gains become, by GainUpdate,
//        Absolute:     K = K0 + S dK                    (Eq. 6, memoryless)
//        Incremental:  K = K_prev + S dK                (each tick adds to the last gains)
//      then are clamped into [gain_min, gain_max] (by default [0, inf): no negative gain);
//   5. the PID runs once with these gains (Eq. 7): pid::Pid::update(in, dt, K).
// The gains live here (gains()); K0 is the PID's configured gains. A fault (NaN/inf input, bad
// dt, overflow) leaves gains and PID untouched.
//
// The supervisor (supervisor/supervisor.hpp) is shared and not owned: the controller keeps a pointer
// to it, so it must outlive the controller and all its copies. Its per-joint Workspace lives here.
#pragma once

#include <array>
#include <cstdint>
#include <utility>

#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"
#include "fuzzypid/supervisor/supervisor.hpp"

namespace fuzzypid::supervisor {

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

// Supervisor: see supervisor/supervisor.hpp (paper.hpp has the paper's, with aliases).
// ObserverStorageKind: whether the inner PID can run the velocity observer (pid::ObserverStorage).
template <class Scalar, class Supervisor,
          pid::ObserverStorage ObserverStorageKind = pid::ObserverStorage::Included>
class FuzzyPid {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(is_supervisor_v<Supervisor, Scalar>,
                "Supervisor must fulfil the concept of fuzzypid/supervisor/supervisor.hpp");

 public:
  using Config = FuzzyPidConfig<Scalar>;
  using Input = pid::Input<Scalar>;
  using Gains = pid::Gains<Scalar>;
  using Workspace = typename Supervisor::Workspace;
  using Pid = pid::Pid<Scalar, ObserverStorageKind>;

  // Unconfigured: update() returns InvalidConfig.
  FuzzyPid() = default;

  // `supervisor` is not owned and must outlive this controller and its copies. A null supervisor
  // or an invalid configuration leaves the controller unconfigured (update() returns
  // InvalidConfig). Set-up: builds the supervisor's workspace, which may allocate.
  FuzzyPid(const Supervisor* supervisor, const Config& config) noexcept(
      noexcept(std::declval<const Supervisor&>().make_workspace()))
      : supervisor_(supervisor) {
    if (supervisor_ != nullptr) workspace_ = supervisor_->make_workspace();
    configured_ = configure(config);
  }

  // Replaces the configuration and resets the gains to the nominal K0 (state is kept). Returns
  // InvalidConfig and changes nothing when the configuration is invalid or there is no
  // supervisor.
  [[nodiscard]] Status configure(const Config& config) noexcept {
    if (supervisor_ == nullptr || !config.valid()) return Status::InvalidConfig;
    const Status s = pid_.configure(config.pid);
    if (s != Status::Ok) return s;
    error_scale_ = config.error_scale;
    error_rate_scale_ = config.error_rate_scale;
    output_scale_ = config.output_scale;
    gain_update_ = config.gain_update;
    gain_min_ = config.gain_min;
    gain_max_ = config.gain_max;
    gains_ = clamp_gains(config.pid.gains);
    configured_ = Status::Ok;
    return Status::Ok;
  }

  // One tick: retune the gains from (e, ec), then run the PID. Returns Ok, NoRuleFired (gains
  // left at their nominal/previous value for this tick, PID still run) or a fault.
  // Flattened (GCC/Clang) so the inference and the PID inline into one body.
  [[gnu::flatten]] [[nodiscard]] Status update(const Input& in, Scalar dt_s) noexcept {
    if (configured_ != Status::Ok) return configured_;
    const pid::ErrorSignal<Scalar> err = pid_.error(in, dt_s);
    std::array<Scalar, 3> delta;
    const Status inferred =
        supervisor_->infer(error_scale_ * err.e, error_rate_scale_ * err.ec, workspace_, delta);
    if (is_fault(inferred)) return input_fault(in, dt_s);
    const Gains& base = gain_update_ == GainUpdate::Absolute ? pid_.gains() : gains_;
    const Gains next = retuned(base, delta);
    const Status s = pid_.update(in, dt_s, next);
    if (is_fault(s)) return s == Status::NonFiniteInput ? input_fault(in, dt_s) : s;
    gains_ = next;
    delta_ = delta;
    return inferred;
  }

  // Restores the nominal gains and clears the PID state.
  void reset() noexcept {
    pid_.reset();
    gains_ = clamp_gains(pid_.gains());
    delta_ = {};
  }

  // Bumpless start at `output` (see pid::Pid::initialize); gains restart at K0. The next update
  // retunes the gains from this input's (e, ec) before the PID runs, so the integral is set with
  // those retuned gains: that update then reproduces `output` (plus one step Ki' e dt).
  [[nodiscard]] Status initialize(Scalar output, const Input& in) noexcept {
    if (configured_ != Status::Ok) return configured_;
    const Gains nominal = clamp_gains(pid_.gains());
    Pid next_pid = pid_;
    Status s = next_pid.initialize(output, in, nominal);
    if (s != Status::Ok) return s;
    // The (e, ec) the next update sees with this input: the sample is recorded, so a difference
    // source gives ec = 0 whatever dt is.
    const pid::ErrorSignal<Scalar> err = next_pid.error(in, Scalar(1));
    Gains next = nominal;
    std::array<Scalar, 3> delta;
    if (!is_fault(supervisor_->infer(error_scale_ * err.e, error_rate_scale_ * err.ec, workspace_,
                                     delta)))
      next = retuned(pid_.gains(), delta);
    if (!next.finite()) return Status::NumericOverflow;
    s = next_pid.initialize(output, in, next);
    if (s != Status::Ok) return s;
    pid_ = next_pid;
    gains_ = nominal;
    delta_ = {};
    return s;
  }

  Scalar output() const noexcept { return pid_.output(); }
  // The gains used by the last update (Kp, Ki, Kd: the paper's Figs. 12-14).
  const Gains& gains() const noexcept { return gains_; }
  // The nominal gains K0 (the PID's configured gains).
  const Gains& nominal_gains() const noexcept { return pid_.gains(); }
  // The supervisor's last raw outputs (dKp, dKi, dKd), before output scaling.
  const std::array<Scalar, 3>& delta() const noexcept { return delta_; }
  const Pid& pid() const noexcept { return pid_; }
  // The shared supervisor (nullptr when default-constructed).
  const Supervisor* supervisor() const noexcept { return supervisor_; }
  const Workspace& workspace() const noexcept { return workspace_; }
  Config config() const noexcept {
    Config c;
    c.pid = pid_.config();
    c.error_scale = error_scale_;
    c.error_rate_scale = error_rate_scale_;
    c.output_scale = output_scale_;
    c.gain_update = gain_update_;
    c.gain_min = gain_min_;
    c.gain_max = gain_max_;
    return c;
  }

 private:
  // The fault behind a failed inference or a PID fault of NonFiniteInput: the input's own fault
  // when it has one, else an overflow of finite inputs (scaled inputs or retuned gains).
  [[gnu::cold]] [[gnu::noinline]] Status input_fault(Input in, Scalar dt_s) const noexcept {
    const Status s = pid_.check(in, dt_s);
    return s != Status::Ok ? s : Status::NumericOverflow;
  }

  // K = base + S dK, clamped into the gain bounds (Eqs. 6-7; base is K0 or the last gains).
  Gains retuned(const Gains& base, const std::array<Scalar, 3>& delta) const noexcept {
    return clamp_gains({base.kp + output_scale_[0] * delta[0],
                        base.ki + output_scale_[1] * delta[1],
                        base.kd + output_scale_[2] * delta[2]});
  }

  Gains clamp_gains(const Gains& g) const noexcept {
    return {detail::clamp(g.kp, gain_min_.kp, gain_max_.kp),
            detail::clamp(g.ki, gain_min_.ki, gain_max_.ki),
            detail::clamp(g.kd, gain_min_.kd, gain_max_.kd)};
  }

  const Supervisor* supervisor_ = nullptr;
  Workspace workspace_{};
  Pid pid_{};
  Gains gains_{};  // this tick's gains
  std::array<Scalar, 3> delta_{};
  std::array<Scalar, 3> output_scale_{Scalar(1), Scalar(1), Scalar(1)};
  Gains gain_min_{};
  Gains gain_max_{};
  Scalar error_scale_ = Scalar(1);
  Scalar error_rate_scale_ = Scalar(1);
  GainUpdate gain_update_ = GainUpdate::Absolute;
  Status configured_ = Status::InvalidConfig;
};

}  // namespace fuzzypid::supervisor
