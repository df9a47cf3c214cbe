// A discrete PID controller in the parallel form of Eq. 2, written for a hard periodic loop.
//
// Each update(in, dt, K) computes, with this tick's gains K = (Kp, Ki, Kd) and e = setpoint -
// measurement,
//
//   P = Kp e
//   I = I_prev + Ki e dt                         (backward Euler; the gain sits inside the sum)
//   D = Kd d,  d = LPF(d_raw)                    (first-order filter, time constant Tf)
//   v = P + I + D + feed_forward,   u = clamp(v, output_min, output_max)
//
// The error rate ec (error()) is the one definition of de/dt, chosen by DerivativeSource:
//   Rates       ec = setpoint_rate - measurement_rate      (Eq. 2 as written)
//   Difference  ec = (e - e_prev) / dt                     (0 without a previous sample)
//   Observer    ec = setpoint_rate - w^                    (w^: the velocity observer below)
// and d_raw is ec with DerivativeOn::Error, or the measurement's part alone with
// DerivativeOn::Measurement (-measurement_rate, -(y - y_prev) / dt or -w^), which gives no
// derivative kick when the setpoint steps.
//
// The velocity observer (DerivativeSource::Observer) is what a drive uses when its encoder is
// coarse for its tick: a rate differenced from a quantised angle moves in steps of one count per
// tick, and the D term passes each step on. The observer follows the measured angle y with a model
// of the joint, a double integrator driven by the PID's own output a = u / observer_output_per_unit
// (rad/s², u of observer_delay_ticks + 1 ticks ago: the command that acted over the last tick):
//   predict  y^- = y^ + w^ dt + a dt^2 / 2,   w^- = w^ + a dt
//   correct  r = y - y^-,   y^ = y^- + l1 r,   w^ = w^- + l2 r / dt
// with l1 = 1 - p^2, l2 = (1 - p)^2: both poles of the estimation error at p = 1 / (1 + 2 pi F
// dt), the backward-Euler image of a double pole at -2 pi F (F = observer_bandwidth_hz; as F dt
// grows, p -> 0, y^ -> y and w^ -> the differenced rate plus a dt / 2). A quantisation step of q
// then moves w^ by l2 q / dt instead of q / dt. The first tick (no previous sample) starts it at
// y^ = y, w^ = measurement_rate. The filter is d = d_prev + dt / (Tf + dt) (d_raw - d_prev)
// (Tf = 0: no filter).
//
// The gains are an argument of the tick: update(in, dt) runs with the configured gains
// (config().gains), update(in, dt, gains) with the caller's -- a fuzzy supervisor passes the
// gains it retuned for this tick and keeps them itself; the PID stores no copy.
//
// The integral is stored as its contribution to the output, I = sum(Ki e dt), not as sum(e dt):
// changing Ki online (a fuzzy supervisor does so every tick) therefore never bumps the output.
// When Ki reaches 0 the integral is frozen, not reset. Anti-windup:
//   None             I is only clamped to [integral_min, integral_max];
//   Clamping         conditional integration: when the output would saturate and the increment
//                    Ki e dt pushes further into that limit, the increment is cut to the part that
//                    brings the output to the limit (none if it is already there), so I stops
//                    growing while saturated (the sign of the increment is compared with the side
//                    of the excess, which stays right for limits that do not straddle zero);
//   BackCalculation  I += Kt (u - v) dt after the step, bleeding the integral while saturated.
// Feed-forward is part of v, so it is covered by both schemes.
//
// Faults: a NaN/inf input or gain, a dt that is not finite and positive, or an overflow leave
// every piece of state untouched, hold the last output and return the fault. Every input that the
// tick reads reaches v, so the tick tests finiteness once, on v (and on I after back-calculation),
// and only a non-finite result looks at the inputs to name the fault. Nothing in update()
// allocates, throws, locks or prints.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::pid {

enum class DerivativeOn : std::uint8_t { Error, Measurement };
enum class DerivativeSource : std::uint8_t { Rates, Difference, Observer };
enum class AntiWindup : std::uint8_t { None, Clamping, BackCalculation };

// The most ticks of computation delay the velocity observer models (Config::observer_delay_ticks).
inline constexpr int kMaxObserverDelayTicks = 3;

// The velocity observer's correction gains l1 = 1 - p^2, l2 = (1 - p)^2 for its bandwidth (Hz) at
// tick dt_s, p = 1 / (1 + 2 pi F dt) (see Pid's header comment); sim/margins models the same.
template <class Scalar>
struct ObserverGains {
  Scalar l1;
  Scalar l2;
};
template <class Scalar>
constexpr ObserverGains<Scalar> observer_gains(Scalar bandwidth_hz, Scalar dt_s) noexcept {
  constexpr Scalar kTwoPi = Scalar(6.283185307179586476925286766559L);
  const Scalar p = Scalar(1) / (Scalar(1) + kTwoPi * bandwidth_hz * dt_s);
  return {Scalar(1) - p * p, (Scalar(1) - p) * (Scalar(1) - p)};
}

template <class Scalar>
struct Config {
  Gains<Scalar> gains{Scalar(1), Scalar(0), Scalar(0)};  // used by update(in, dt)
  Scalar derivative_filter_s = Scalar(0);                // Tf, s; 0 disables the filter
  Scalar output_min = -detail::infinity<Scalar>();
  Scalar output_max = detail::infinity<Scalar>();
  Scalar integral_min = -detail::infinity<Scalar>();  // limits on I, in output units
  Scalar integral_max = detail::infinity<Scalar>();
  Scalar tracking_gain_per_s = Scalar(0);  // Kt of back-calculation, 1/s
  // DerivativeSource::Observer only (see the header comment):
  Scalar observer_bandwidth_hz = Scalar(0);     // F, Hz, > 0
  Scalar observer_output_per_unit = Scalar(1);  // output units per rad/s² (1: u is an acceleration)
  int observer_delay_ticks = 1;                 // 0 .. kMaxObserverDelayTicks
  DerivativeOn derivative_on = DerivativeOn::Error;
  DerivativeSource derivative_source = DerivativeSource::Rates;
  AntiWindup anti_windup = AntiWindup::Clamping;

  // Gains finite; limits ordered (infinite allowed); Tf and Kt finite and non-negative; with the
  // observer, F and the output scale finite and positive, the delay within 0 .. 3 ticks.
  constexpr bool valid() const noexcept {
    const auto not_nan = [](Scalar x) { return x == x; };
    const bool observer =
        derivative_source != DerivativeSource::Observer ||
        (detail::is_finite(observer_bandwidth_hz) && observer_bandwidth_hz > Scalar(0) &&
         detail::is_finite(observer_output_per_unit) && observer_output_per_unit > Scalar(0) &&
         observer_delay_ticks >= 0 && observer_delay_ticks <= kMaxObserverDelayTicks);
    return gains.finite() && not_nan(output_min) && not_nan(output_max) &&
           output_min <= output_max && not_nan(integral_min) && not_nan(integral_max) &&
           integral_min <= integral_max && detail::is_finite(derivative_filter_s) &&
           derivative_filter_s >= Scalar(0) && detail::is_finite(tracking_gain_per_s) &&
           tracking_gain_per_s >= Scalar(0) && observer;
  }
};

// One tick's measurements and references. Rates are used only with DerivativeSource::Rates.
template <class Scalar>
struct Input {
  Scalar setpoint = Scalar(0);          // theta_d, e.g. rad
  Scalar measurement = Scalar(0);       // theta
  Scalar setpoint_rate = Scalar(0);     // theta_d dot, e.g. rad/s
  Scalar measurement_rate = Scalar(0);  // theta dot
  Scalar feed_forward = Scalar(0);      // added to the output, in output units
};

// The error e = setpoint - measurement and its rate ec as the PID defines them for one tick (see
// Pid::error()); a fuzzy supervisor reads the same two values.
template <class Scalar>
struct ErrorSignal {
  Scalar e = Scalar(0);
  Scalar ec = Scalar(0);
};

// The three terms of the last successful update, for logging.
template <class Scalar>
struct Terms {
  Scalar p = Scalar(0);
  Scalar i = Scalar(0);
  Scalar d = Scalar(0);
};

// What a Pid stores for the velocity observer: Included, its estimate and the last
// kMaxObserverDelayTicks + 1 commands (six scalars); Omitted, nothing, and configure() refuses
// DerivativeSource::Observer (InvalidConfig). A controller that never uses the observer omits
// it: the paper's controller does, which keeps six double joints within 2 KB.
enum class ObserverStorage : std::uint8_t { Included, Omitted };

template <class Scalar, ObserverStorage ObserverStorageKind = ObserverStorage::Included>
class Pid {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static constexpr bool kHasObserver = ObserverStorageKind == ObserverStorage::Included;

 public:
  using Config = pid::Config<Scalar>;
  using Gains = pid::Gains<Scalar>;
  using Input = pid::Input<Scalar>;
  using ErrorSignal = pid::ErrorSignal<Scalar>;

  constexpr Pid() noexcept = default;
  // An invalid configuration leaves the controller unconfigured: update() then returns
  // InvalidConfig until configure() succeeds.
  explicit constexpr Pid(const Config& config) noexcept { configured_ = configure(config); }

  // Replaces the configuration (keeps the state). Returns InvalidConfig and changes nothing when
  // the configuration is invalid, or asks for the observer that this Pid omits.
  [[nodiscard]] constexpr Status configure(const Config& config) noexcept {
    if (!config.valid()) return Status::InvalidConfig;
    const bool observed = config.derivative_source == DerivativeSource::Observer;
    if constexpr (kHasObserver) {
      // An observer switched on mid-run starts at the last measurement, at rest, with the last
      // output as every past command (its state was not kept while it was off).
      if (observed && config_.derivative_source != DerivativeSource::Observer) {
        observer_.estimate = {previous_measurement_, Scalar(0)};
        observer_.past_output.fill(output_);
      }
    } else if (observed) {
      return Status::InvalidConfig;
    }
    config_ = config;
    configured_ = Status::Ok;
    return Status::Ok;
  }

  // Online change of the configured gains (those of update(in, dt)). The integral term keeps its
  // value, so the output does not jump because of Ki; it moves at the next update only through
  // the new Kp, Ki, Kd acting on new errors.
  [[nodiscard]] constexpr Status set_gains(const Gains& gains) noexcept {
    if (!gains.finite()) return Status::NonFiniteInput;
    config_.gains = gains;
    return Status::Ok;
  }

  // Clears all state (integral, filter, previous samples, output).
  constexpr void reset() noexcept {
    integral_ = derivative_ = output_ = unsaturated_ = Scalar(0);
    previous_error_ = previous_measurement_ = Scalar(0);
    observer_ = {};
    terms_ = {};
    has_previous_ = false;
  }

  // Bumpless start (e.g. manual -> automatic): sets the integral so that the next update with the
  // same input and gains produces `output` (P + I + feed-forward = output, clamped into the
  // integral limits), and records the input as the previous sample so no derivative spike
  // follows. The first form uses the configured gains.
  [[nodiscard]] constexpr Status initialize(Scalar output, const Input& in) noexcept {
    return initialize(output, in, config_.gains);
  }
  [[nodiscard]] constexpr Status initialize(Scalar output, const Input& in,
                                            const Gains& gains) noexcept {
    if (!detail::is_finite(output) || !finite(in) || !gains.finite()) return Status::NonFiniteInput;
    const Scalar e = in.setpoint - in.measurement;
    const Scalar i = detail::clamp(output - gains.kp * e - in.feed_forward, config_.integral_min,
                                   config_.integral_max);
    if (!detail::is_finite(i)) return Status::NonFiniteInput;
    reset();
    integral_ = i;
    output_ = unsaturated_ = output;
    previous_error_ = e;
    previous_measurement_ = in.measurement;
    if constexpr (kHasObserver) {
      observer_.estimate = {in.measurement, in.measurement_rate};
      observer_.past_output.fill(output);
    }
    has_previous_ = true;
    return Status::Ok;
  }

  // e and ec of this input (see the header comment): the one place the derivative source is
  // chosen. Pure; meaningful for finite inputs and a valid dt.
  constexpr ErrorSignal error(const Input& in, Scalar dt_s) const noexcept {
    const Scalar e = in.setpoint - in.measurement;
    Scalar ec = Scalar(0);
    if (config_.derivative_source == DerivativeSource::Rates) {
      ec = in.setpoint_rate - in.measurement_rate;
    } else if (config_.derivative_source == DerivativeSource::Observer) {
      ec = in.setpoint_rate - observe(in, dt_s).velocity;
    } else if (has_previous_) {
      ec = (e - previous_error_) / dt_s;
    }
    return {e, ec};
  }

  // The velocity observer's estimate after this input (DerivativeSource::Observer; see the header
  // comment); the measurement itself on the first tick and in a Pid that omits the observer.
  // Pure; meaningful for finite inputs and a valid dt.
  struct Estimate {
    Scalar position = Scalar(0);  // y^, units of the measurement
    Scalar velocity = Scalar(0);  // w^, per second
  };
  constexpr Estimate observe(const Input& in, Scalar dt_s) const noexcept {
    if constexpr (kHasObserver) {
      if (has_previous_) {
        const Estimate& x = observer_.estimate;
        const auto lag = static_cast<std::size_t>(config_.observer_delay_ticks);
        const Scalar a = observer_.past_output[lag] / config_.observer_output_per_unit;
        const Scalar y = x.position + x.velocity * dt_s + Scalar(0.5) * a * dt_s * dt_s;
        const Scalar w = x.velocity + a * dt_s;
        const ObserverGains<Scalar> k = observer_gains(config_.observer_bandwidth_hz, dt_s);
        const Scalar r = in.measurement - y;
        return {y + k.l1 * r, w + k.l2 * r / dt_s};
      }
    }
    static_cast<void>(dt_s);
    return {in.measurement, in.measurement_rate};
  }

  // Whether update() would accept this input and dt: InvalidConfig, InvalidTimeStep,
  // NonFiniteInput (a value the tick reads is NaN or infinite) or Ok. update() makes the same
  // checks itself; this is for callers that need the verdict before running the tick.
  [[nodiscard]] constexpr Status check(const Input& in, Scalar dt_s) const noexcept {
    if (configured_ != Status::Ok) return configured_;
    if (!valid_time_step(dt_s)) return Status::InvalidTimeStep;
    return finite(in) ? Status::Ok : Status::NonFiniteInput;
  }

  // One control step over dt_s seconds with the configured gains.
  [[nodiscard]] constexpr Status update(const Input& in, Scalar dt_s) noexcept {
    return update(in, dt_s, config_.gains);
  }

  // One control step over dt_s seconds with this tick's gains. Returns Ok or a fault (state
  // untouched, output held): InvalidConfig, InvalidTimeStep, NonFiniteInput (an input or a gain),
  // NumericOverflow (finite inputs, non-finite result).
  [[nodiscard]] constexpr Status update(const Input& in, Scalar dt_s, const Gains& g) noexcept {
    if (configured_ != Status::Ok) return configured_;
    if (!valid_time_step(dt_s)) return Status::InvalidTimeStep;
    const ErrorSignal err = error(in, dt_s);
    const Scalar e = err.e;

    const bool observed = config_.derivative_source == DerivativeSource::Observer;
    const Estimate estimate = observed ? observe(in, dt_s) : Estimate{};
    Scalar d_raw = err.ec;
    if (config_.derivative_on == DerivativeOn::Measurement) {
      if (config_.derivative_source == DerivativeSource::Rates) {
        // setpoint_rate * 0 keeps a NaN/inf setpoint rate visible to the check on v below.
        d_raw = in.setpoint_rate * Scalar(0) - in.measurement_rate;
      } else if (observed) {
        d_raw = in.setpoint_rate * Scalar(0) - estimate.velocity;
      } else {
        d_raw = has_previous_ ? -(in.measurement - previous_measurement_) / dt_s : Scalar(0);
      }
    }
    const Scalar tf = config_.derivative_filter_s;
    const Scalar d = (tf > Scalar(0) && has_previous_)
                         ? derivative_ + dt_s / (tf + dt_s) * (d_raw - derivative_)
                         : d_raw;

    const Scalar p_term = g.kp * e;
    const Scalar d_term = g.kd * d;
    const Scalar increment = g.ki * e * dt_s;
    const Scalar lo = config_.output_min;
    const Scalar hi = config_.output_max;

    Scalar integral =
        detail::clamp(integral_ + increment, config_.integral_min, config_.integral_max);
    if (config_.anti_windup == AntiWindup::Clamping) {
      // Keep only the part of the increment that brings the output up to the limit: dropping all
      // of it would leave the output below the limit, unsaturated, with integral action stopped.
      const Scalar rest = p_term + d_term + in.feed_forward;
      const Scalar trial = rest + integral;
      if (trial > hi && increment > Scalar(0))
        integral = detail::clamp(detail::max(integral_, hi - rest), config_.integral_min,
                                 config_.integral_max);
      if (trial < lo && increment < Scalar(0))
        integral = detail::clamp(detail::min(integral_, lo - rest), config_.integral_min,
                                 config_.integral_max);
    }
    // v sums every value the tick read (e through P, ec through D, the feed-forward) with a
    // finite or infinite coefficient: a NaN or infinite input or gain makes it non-finite.
    const Scalar v = p_term + integral + d_term + in.feed_forward;
    if (!detail::is_finite(v)) return fault(in, dt_s, g);
    const Scalar u = detail::clamp(v, lo, hi);
    if (config_.anti_windup == AntiWindup::BackCalculation) {
      integral = detail::clamp(integral + config_.tracking_gain_per_s * (u - v) * dt_s,
                               config_.integral_min, config_.integral_max);
      if (!detail::is_finite(integral)) return Status::NumericOverflow;
    }

    integral_ = integral;
    derivative_ = d;
    previous_error_ = e;
    previous_measurement_ = in.measurement;
    if constexpr (kHasObserver) {
      if (observed) {
        observer_.estimate = estimate;
        auto& past = observer_.past_output;
        for (std::size_t j = past.size() - 1; j > 0; --j)
          past[j] = past[j - 1];
        past[0] = u;
      }
    }
    has_previous_ = true;
    unsaturated_ = v;
    output_ = u;
    terms_ = {p_term, integral, d_term};
    return Status::Ok;
  }

  // Last output (held through faults), in output units.
  constexpr Scalar output() const noexcept { return output_; }
  // Last output before clamping.
  constexpr Scalar unsaturated_output() const noexcept { return unsaturated_; }
  constexpr bool saturated() const noexcept { return output_ != unsaturated_; }
  // Integral term I (output units).
  constexpr Scalar integral() const noexcept { return integral_; }
  // Filtered derivative signal d (units of e per second).
  constexpr Scalar derivative() const noexcept { return derivative_; }
  constexpr const Terms<Scalar>& terms() const noexcept { return terms_; }
  // The configured gains (those of update(in, dt)).
  constexpr const Gains& gains() const noexcept { return config_.gains; }
  constexpr const Config& config() const noexcept { return config_; }
  // Whether a previous sample exists (false after construction and reset()).
  constexpr bool has_previous() const noexcept { return has_previous_; }
  constexpr Scalar previous_error() const noexcept { return previous_error_; }

 private:
  static constexpr bool valid_time_step(Scalar dt_s) noexcept {
    return dt_s > Scalar(0) && dt_s <= std::numeric_limits<Scalar>::max();  // NaN fails both
  }

  // Names the fault behind a non-finite result; out of the tick's straight path.
  [[gnu::cold]] [[gnu::noinline]] constexpr Status fault(Input in, Scalar dt_s,
                                                         Gains g) const noexcept {
    if (!valid_time_step(dt_s)) return Status::InvalidTimeStep;
    if (!finite(in) || !g.finite()) return Status::NonFiniteInput;
    return Status::NumericOverflow;
  }

  // The inputs the tick reads are finite: the setpoint rate with Rates and Observer, the
  // measured rate with Rates and on the observer's first tick only (it starts from it).
  constexpr bool finite(const Input& in) const noexcept {
    using detail::is_finite;
    const bool rates = config_.derivative_source == DerivativeSource::Rates;
    const bool observed = config_.derivative_source == DerivativeSource::Observer;
    return is_finite(in.setpoint) && is_finite(in.measurement) && is_finite(in.feed_forward) &&
           (!(rates || observed) || is_finite(in.setpoint_rate)) &&
           (!(rates || (observed && !has_previous_)) || is_finite(in.measurement_rate));
  }

  Config config_{};
  Scalar integral_ = Scalar(0);
  Scalar derivative_ = Scalar(0);
  Scalar output_ = Scalar(0);
  Scalar unsaturated_ = Scalar(0);
  Scalar previous_error_ = Scalar(0);
  Scalar previous_measurement_ = Scalar(0);
  Terms<Scalar> terms_{};
  Status configured_ = Status::Ok;
  bool has_previous_ = false;
  struct ObserverState {
    Estimate estimate{};  // y^, w^ after the last tick
    std::array<Scalar, kMaxObserverDelayTicks + 1>
        past_output{};  // u of the last ticks, newest first
  };
  struct NoObserverState {};  // last, so that it takes a byte of the flags' padding
  std::conditional_t<kHasObserver, ObserverState, NoObserverState> observer_{};
};

}  // namespace fuzzypid::pid
