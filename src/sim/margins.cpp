#include "fuzzypid/sim/margins.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Dense>

namespace fuzzypid::sim {
namespace {

using Complex = std::complex<double>;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

// The ZOH discretisation of θ̈ = c u − a θ̇ over h: x_{k+1} = [[1, p], [0, q]] x_k + c [bθ, bω] u_k.
struct Zoh {
  double q = 1.0;   // e^{−ah}
  double p = 0.0;   // (1 − e^{−ah}) / a  (h when a = 0)
  double bt = 0.0;  // (h − p) / a        (h² / 2 when a = 0)
  double bw = 0.0;  // p
};

Zoh zoh(double a, double h) {
  Zoh z;
  const double ah = a * h;
  z.q = std::exp(-ah);
  z.p = a > 0.0 ? -std::expm1(-ah) / a : h;
  // (h − p) / a cancels for small ah: its series instead.
  z.bt = ah < 1e-4 ? h * h * (0.5 - ah / 6.0 + ah * ah / 24.0) : (h - z.p) / a;
  z.bw = z.p;
  return z;
}

// A delay of (m + f) ticks: over each tick the plant sees u_{k−m−1} for f h, then u_{k−m}, so
// x_{k+1} = Ad x_k + g1 u_{k−m} + g0 u_{k−m−1} (per unit of c).
struct DelayedInput {
  int m = 0;
  double g1t = 0.0, g1w = 0.0;  // of u_{k−m}: ∫ over the last (1 − f) h
  double g0t = 0.0, g0w = 0.0;  // of u_{k−m−1}: over the first f h, carried to the tick's end
};

DelayedInput delayed_input(double a, double h, int m, double f) {
  const Zoh last = zoh(a, (1.0 - f) * h), first = zoh(a, f * h);
  DelayedInput d;
  d.m = m;
  d.g1t = last.bt;
  d.g1w = last.bw;
  d.g0t = first.bt + last.p * first.bw;
  d.g0w = last.q * first.bw;
  return d;
}

// m whole ticks and a fraction f in [0, 1) of `delay_s` at tick h (a fraction within 1e-9 of a
// whole tick is that tick).
std::pair<int, double> split_delay(double delay_s, double h) {
  const double ticks = delay_s / h;
  const double whole = std::round(ticks);
  if (std::abs(ticks - whole) < 1e-9) return {static_cast<int>(whole), 0.0};
  const double m = std::floor(ticks);
  return {static_cast<int>(m), ticks - m};
}

bool valid(const JointLoop& l) {
  const auto finite = [](double x) { return std::isfinite(x); };
  return finite(l.tick_s) && l.tick_s > 0.0 && finite(l.plant_gain) && l.plant_gain > 0.0 &&
         finite(l.damping_per_s) && l.damping_per_s >= 0.0 && l.gains.finite() &&
         finite(l.derivative_filter_s) && l.derivative_filter_s >= 0.0 && l.delay_ticks >= 0 &&
         l.delay_fraction >= 0.0 && l.delay_fraction < 1.0;
}

// |S − 1/2| = |(1 − L) / (2 (1 + L))|.
double disk_distance(Complex l) {
  return std::abs((1.0 - l) / (2.0 * (1.0 + l)));
}

// Bisection on a sign change of f over [lo, hi] (f(lo) f(hi) < 0).
template <class F>
double bisect(F f, double lo, double hi) {
  double flo = f(lo);
  for (int k = 0; k < 80 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    const double fm = f(mid);
    if ((fm < 0.0) == (flo < 0.0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double to_db(double factor) noexcept {
  return 20.0 * std::log10(factor);
}

Complex loop_response(const JointLoop& loop, double omega_rad_s) {
  const double h = loop.tick_s;
  const Complex z = std::polar(1.0, omega_rad_s * h);
  const Zoh d = zoh(loop.damping_per_s, h);
  const double c = loop.plant_gain;
  // The input vector of the delayed plant: g1 + g0 / z, then z^−m.
  const DelayedInput in = delayed_input(loop.damping_per_s, h, 0, loop.delay_fraction);
  const Complex gt = in.g1t + in.g0t / z, gw = in.g1w + in.g0w / z;
  const Complex p_theta = c * ((z - d.q) * gt + d.p * gw) / ((z - 1.0) * (z - d.q));
  const Complex p_omega = c * gw / (z - d.q);
  const double beta = h / (loop.derivative_filter_s + h);
  const Complex filter = beta * z / (z - 1.0 + beta);
  const Complex integral = loop.gains.ki * h * z / (z - 1.0);
  const Complex derivative =
      loop.derivative == pid::DerivativeSource::Rates ? p_omega : (1.0 - 1.0 / z) / h * p_theta;
  const Complex l = (loop.gains.kp + integral) * p_theta + loop.gains.kd * filter * derivative;
  return l * std::polar(1.0, -omega_rad_s * h * loop.delay_ticks);
}

namespace {

// Spectral radius with the loop's gains scaled and a total delay of m + f ticks.
double spectral_radius(const JointLoop& loop, double gain_scale, int m, double f) {
  const double h = loop.tick_s;
  // State: θ, θ̇, I_{k−1}, d_{k−1}, θ_{k−1}, then u_{k−1} .. u_{k−len}.
  const int len = f > 0.0 ? m + 1 : m;
  const int n = 5 + len;
  const Zoh z = zoh(loop.damping_per_s, h);
  const DelayedInput in = delayed_input(loop.damping_per_s, h, m, f);
  const double s = gain_scale;
  const double beta = h / (loop.derivative_filter_s + h);
  Eigen::RowVectorXd d_raw = Eigen::RowVectorXd::Zero(n);
  if (loop.derivative == pid::DerivativeSource::Rates) {
    d_raw(1) = -1.0;
  } else {
    d_raw(0) = -1.0 / h;
    d_raw(4) = 1.0 / h;
  }
  Eigen::RowVectorXd filtered = beta * d_raw;
  filtered(3) += 1.0 - beta;
  Eigen::RowVectorXd integral = Eigen::RowVectorXd::Zero(n);
  // With Ki = 0 the PID freezes its integral: a constant, not a mode of the loop (its eigenvalue
  // 1 would read as marginal stability).
  integral(2) = loop.gains.ki != 0.0 ? 1.0 : 0.0;
  integral(0) = -s * loop.gains.ki * h;
  Eigen::RowVectorXd u = integral + s * loop.gains.kd * filtered;
  u(0) += -s * loop.gains.kp;
  // u_{k−j} as a row of the state (j = 0: this tick's output).
  const auto past = [&](int j) {
    if (j == 0) return u;
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    r(5 + j - 1) = 1.0;
    return r;
  };
  const Eigen::RowVectorXd v1 = past(m);
  const Eigen::RowVectorXd v0 = f > 0.0 ? past(m + 1) : Eigen::RowVectorXd::Zero(n);

  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  a(0, 0) = 1.0;
  a(0, 1) = z.p;
  a(1, 1) = z.q;
  a.row(0) += loop.plant_gain * (in.g1t * v1 + in.g0t * v0);
  a.row(1) += loop.plant_gain * (in.g1w * v1 + in.g0w * v0);
  a.row(2) = integral;
  a.row(3) = filtered;
  a(4, 0) = 1.0;
  if (len > 0) {
    a.row(5) = u;
    for (int j = 1; j < len; ++j)
      a(5 + j, 5 + j - 1) = 1.0;
  }
  const Eigen::VectorXcd lambda = a.eigenvalues();
  double rho = 0.0;
  for (int k = 0; k < lambda.size(); ++k)
    rho = std::max(rho, std::abs(lambda(k)));
  return rho;
}

}  // namespace

double closed_loop_spectral_radius(const JointLoop& loop, double gain_scale,
                                   int extra_delay_ticks) {
  return spectral_radius(loop, gain_scale, loop.delay_ticks + std::max(0, extra_delay_ticks),
                         loop.delay_fraction);
}

double closed_loop_spectral_radius_at_delay(const JointLoop& loop, double extra_delay_s) {
  const auto [m, f] = split_delay(
      (loop.delay_ticks + loop.delay_fraction) * loop.tick_s + std::max(0.0, extra_delay_s),
      loop.tick_s);
  return spectral_radius(loop, 1.0, m, f);
}

void set_delay(JointLoop& loop, double delay_s) {
  const auto [m, f] = split_delay(delay_s, loop.tick_s);
  loop.delay_ticks = m;
  loop.delay_fraction = f;
}

LoopMargins margins(const JointLoop& loop, const MarginOptions& options) {
  LoopMargins m;
  m.phase_crossover_rad_s = m.gain_crossover_rad_s = m.disk_frequency_rad_s = kNaN;
  if (!valid(loop)) return m;
  m.spectral_radius = closed_loop_spectral_radius(loop);
  m.stable = m.spectral_radius < 1.0 - 1e-12;

  const double nyquist = kPi / loop.tick_s;
  const int n = std::max(16, options.grid_points);
  std::vector<double> w(static_cast<std::size_t>(n));
  std::vector<Complex> l(w.size());
  for (int i = 0; i < n; ++i) {
    w[i] = i == n - 1 ? nyquist : nyquist * std::pow(10.0, -5.0 + 5.0 * i / (n - 1));
    l[i] = loop_response(loop, w[i]);
  }
  const auto at = [&](double omega) { return loop_response(loop, omega); };

  double gm_up = kInf, gm_low = 0.0, pm = kInf, dm = kInf;
  const auto phase_crossing = [&](double omega) {
    const Complex lw = at(omega);
    if (lw.real() >= 0.0) return;
    const double factor = 1.0 / std::abs(lw);
    if (factor > 1.0 && factor < gm_up) {
      gm_up = factor;
      m.phase_crossover_rad_s = omega;
    }
    if (factor < 1.0) gm_low = std::max(gm_low, factor);
  };
  const auto gain_crossing = [&](double omega) {
    const Complex lw = at(omega);
    const double phase = std::arg(-lw);  // (−π, π]
    const double phase_deg = phase * 180.0 / kPi;
    if (phase_deg < pm) {
      pm = phase_deg;
      m.gain_crossover_rad_s = omega;
    }
    const double wrapped = phase < 0.0 ? phase + 2.0 * kPi : phase;
    dm = std::min(dm, wrapped / omega);
  };
  for (int i = 0; i + 1 < n; ++i) {
    const double im0 = l[i].imag(), im1 = l[i + 1].imag();
    if ((im0 < 0.0) != (im1 < 0.0))
      phase_crossing(bisect([&](double o) { return at(o).imag(); }, w[i], w[i + 1]));
    const double g0 = std::abs(l[i]) - 1.0, g1 = std::abs(l[i + 1]) - 1.0;
    if ((g0 < 0.0) != (g1 < 0.0))
      gain_crossing(bisect([&](double o) { return std::abs(at(o)) - 1.0; }, w[i], w[i + 1]));
  }
  // At π/h, z = −1 and L is real: a phase crossover whenever it is negative.
  phase_crossing(nyquist);

  m.gain_margin_db = to_db(gm_up);
  m.gain_margin_low_db = gm_low > 0.0 ? to_db(gm_low) : -kInf;
  m.phase_margin_deg = pm;
  m.delay_margin_s = dm;

  // Disk margin: the peak of |S − 1/2| on the grid, refined by golden section.
  std::size_t peak = 0;
  for (std::size_t i = 1; i < l.size(); ++i)
    if (disk_distance(l[i]) > disk_distance(l[peak])) peak = i;
  double lo = w[peak > 0 ? peak - 1 : 0], hi = w[std::min(peak + 1, w.size() - 1)];
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int k = 0; k < 100 && hi - lo > 1e-13 * hi; ++k) {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (disk_distance(at(x1)) > disk_distance(at(x2)))
      hi = x2;
    else
      lo = x1;
  }
  double omega_peak = 0.5 * (lo + hi);
  double peak_value = disk_distance(at(omega_peak));
  if (disk_distance(l[peak]) > peak_value) {
    omega_peak = w[peak];
    peak_value = disk_distance(l[peak]);
  }
  m.disk_frequency_rad_s = omega_peak;
  m.disk_margin = m.stable && peak_value > 0.0 ? 1.0 / peak_value : 0.0;
  const double half = m.disk_margin / 2.0;
  m.disk_gain_low = (1.0 - half) / (1.0 + half);
  m.disk_gain_high = half < 1.0 ? (1.0 + half) / (1.0 - half) : kInf;
  m.disk_phase_deg = 2.0 * std::atan(half) * 180.0 / kPi;

  if (options.delay_ticks && m.stable && std::isfinite(dm)) {
    // The fewest extra whole ticks that destabilise: near dm / h for the crossover that sets dm;
    // scanned from 1 when that is cheap, else from just below dm / h.
    const int n0 = static_cast<int>(std::floor(dm / loop.tick_s));
    if (n0 <= 400) {
      const int first = n0 + 4 <= 64 ? 1 : std::max(1, n0 - 2);
      for (int extra = first; extra <= n0 + 4; ++extra)
        if (closed_loop_spectral_radius(loop, 1.0, extra) >= 1.0) {
          m.delay_margin_ticks = extra;
          break;
        }
    }
    // The exact extra delay (through the sampled-data model): the first unstable step of h / 16
    // below the whole-tick count, then bisection.
    if (m.delay_margin_ticks > 0) {
      const double h = loop.tick_s;
      const int n_ticks = m.delay_margin_ticks;
      const double step = h / 16.0;
      double lo = n_ticks <= 16 ? 0.0 : (n_ticks - 2) * h;
      double hi = n_ticks * h;
      for (double t = lo + step; t <= hi + 0.5 * step; t += step) {
        if (closed_loop_spectral_radius_at_delay(loop, t) >= 1.0) {
          hi = t;
          break;
        }
        lo = t;
      }
      for (int k = 0; k < 50; ++k) {
        const double mid = 0.5 * (lo + hi);
        if (closed_loop_spectral_radius_at_delay(loop, mid) < 1.0)
          lo = mid;
        else
          hi = mid;
      }
      m.delay_margin_exact_s = 0.5 * (lo + hi);
    }
  }
  return m;
}

}  // namespace fuzzypid::sim
