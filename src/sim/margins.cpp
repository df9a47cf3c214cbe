#include "fuzzypid/sim/margins.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include "loop_matrix.hpp"

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
// x_{k+1} = Ad x_k + g1 u_{k−m} + g0 u_{k−m−1} (per unit of c; the whole ticks m only shift
// which commands those are).
struct DelayedInput {
  double g1t = 0.0, g1w = 0.0;  // of u_{k−m}: ∫ over the last (1 − f) h
  double g0t = 0.0, g0w = 0.0;  // of u_{k−m−1}: over the first f h, carried to the tick's end
};

DelayedInput delayed_input(double a, double h, double f) {
  const Zoh last = zoh(a, (1.0 - f) * h), first = zoh(a, f * h);
  DelayedInput d;
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
         l.delay_fraction >= 0.0 && l.delay_fraction < 1.0 && finite(l.torque_bandwidth_hz) &&
         l.torque_bandwidth_hz >= 0.0 && finite(l.gear_resonance_hz) &&
         l.gear_resonance_hz >= 0.0 &&
         (l.gear_resonance_hz == 0.0 ||
          (l.motor_inertia_fraction > 0.0 && l.motor_inertia_fraction < 1.0 &&
           finite(l.gear_damping_ratio) && l.gear_damping_ratio >= 0.0)) &&
         (l.derivative != pid::DerivativeSource::Observer ||
          (finite(l.observer_bandwidth_hz) && l.observer_bandwidth_hz > 0.0 &&
           l.observer_delay_ticks >= 0 && l.observer_delay_ticks <= pid::kMaxObserverDelayTicks &&
           finite(l.observer_plant_gain) && l.observer_plant_gain > 0.0));
}

// The observer's correction gains l1, l2 at tick h, as pid::Pid computes them.
std::pair<double, double> observer_gains(const JointLoop& l) {
  const auto k = pid::observer_gains(l.observer_bandwidth_hz, l.tick_s);
  return {k.l1, k.l2};
}

// Φ(t) and Γ(t) = ∫₀ᵗ e^{A s} ds B of the plant with a current loop (states θ, θ̇, v; v̇ = w (u − v),
// θ̈ = c v − a θ̇), from the exponential of [[A, B], [0, 0]] t.
std::pair<Eigen::Matrix3d, Eigen::Vector3d> lagged_segment(double a, double c, double w, double t) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 1) = 1.0;
  m(1, 1) = -a;
  m(1, 2) = c;
  m(2, 2) = -w;
  m(2, 3) = w;
  const Eigen::Matrix4d e = (m * t).exp();
  return {e.topLeftCorner<3, 3>(), e.topRightCorner<3, 1>()};
}

// The continuous plant with an elastic gear (margins.hpp): x = (θ_m, θ̇_m, θ_l, θ̇_l[, v]),
// ẋ = A x + B u; the current loop's state v last when there is one.
std::pair<Eigen::MatrixXd, Eigen::VectorXd> geared_plant(const JointLoop& loop, double c) {
  const bool lagged = loop.torque_bandwidth_hz > 0.0;
  const int n = lagged ? 5 : 4;
  const double r = loop.motor_inertia_fraction, a = loop.damping_per_s;
  const double w = 2.0 * kPi * loop.gear_resonance_hz, zeta = loop.gear_damping_ratio;
  const double stiffness = w * w, damping = 2.0 * zeta * w;  // per unit of r (1 − r) J
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  m(0, 1) = 1.0;
  m(1, 0) = -stiffness * (1.0 - r);
  m(1, 1) = -a / r - damping * (1.0 - r);
  m(1, 2) = stiffness * (1.0 - r);
  m(1, 3) = damping * (1.0 - r);
  m(2, 3) = 1.0;
  m(3, 0) = stiffness * r;
  m(3, 1) = damping * r;
  m(3, 2) = -stiffness * r;
  m(3, 3) = -damping * r;
  if (lagged) {
    const double wc = 2.0 * kPi * loop.torque_bandwidth_hz;
    m(1, 4) = c / r;
    m(4, 4) = -wc;
    b(4) = wc;
  } else {
    b(1) = c / r;
  }
  return {m, b};
}

// Φ(t) and Γ(t) = ∫₀ᵗ e^{A s} ds B from the exponential of [[A, B], [0, 0]] t.
std::pair<Eigen::MatrixXd, Eigen::VectorXd> segment(const Eigen::MatrixXd& a,
                                                    const Eigen::VectorXd& b, double t) {
  const auto n = a.rows();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + 1, n + 1);
  m.topLeftCorner(n, n) = a * t;
  m.topRightCorner(n, 1) = b * t;
  const Eigen::MatrixXd e = m.exp();
  return {e.topLeftCorner(n, n), e.topRightCorner(n, 1)};
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

namespace detail {

DiscretePlant discretise(const JointLoop& loop, double plant_gain, double fraction) {
  const double h = loop.tick_s, a = loop.damping_per_s, c = plant_gain;
  DiscretePlant d;
  if (loop.gear_resonance_hz > 0.0) {
    const auto [a_c, b_c] = geared_plant(loop, c);
    const auto [phi_last, gamma_last] = segment(a_c, b_c, (1.0 - fraction) * h);
    const auto [phi_first, gamma_first] = segment(a_c, b_c, fraction * h);
    d.phi = segment(a_c, b_c, h).first;
    d.g1 = gamma_last;
    d.g0 = phi_last * gamma_first;
    return d;
  }
  if (loop.torque_bandwidth_hz > 0.0) {
    const double w = 2.0 * kPi * loop.torque_bandwidth_hz;
    const auto [phi_last, gamma_last] = lagged_segment(a, c, w, (1.0 - fraction) * h);
    const auto [phi_first, gamma_first] = lagged_segment(a, c, w, fraction * h);
    d.phi = lagged_segment(a, c, w, h).first;
    d.g1 = gamma_last;
    d.g0 = phi_last * gamma_first;
    return d;
  }
  const Zoh z = zoh(a, h);
  const DelayedInput in = delayed_input(a, h, fraction);
  d.phi = Eigen::Matrix2d{{1.0, z.p}, {0.0, z.q}};
  d.g1 = c * Eigen::Vector2d{in.g1t, in.g1w};
  d.g0 = c * Eigen::Vector2d{in.g0t, in.g0w};
  return d;
}

Eigen::MatrixXd closed_loop_matrix(const JointLoop& loop, const pid::Gains<double>& gains,
                                   double plant_gain, int m, double f) {
  const double h = loop.tick_s;
  const DiscretePlant plant = discretise(loop, plant_gain, f);
  const auto np = static_cast<int>(plant.phi.rows());
  // State: the plant's (θ, θ̇[, v]), then I_{k−1}, d_{k−1}, θ_{k−1}, then u_{k−1} .. u_{k−len},
  // then the observer's ŷ_{k−1}, ŵ_{k−1} (with one).
  const bool observed = loop.derivative == pid::DerivativeSource::Observer;
  const int ii = np, id = np + 1, ip = np + 2, iu = np + 3;
  const int len = std::max(f > 0.0 ? m + 1 : m, observed ? loop.observer_delay_ticks + 1 : 0);
  const int io = iu + len;
  const int n = io + (observed ? 2 : 0);
  const double beta = h / (loop.derivative_filter_s + h);
  Eigen::RowVectorXd d_raw = Eigen::RowVectorXd::Zero(n);
  Eigen::RowVectorXd y_hat = Eigen::RowVectorXd::Zero(n), w_hat = Eigen::RowVectorXd::Zero(n);
  if (observed) {
    // Predict with u_{k−1−d_o}, correct with θ_k (pid.hpp).
    const auto [l1, l2] = observer_gains(loop);
    const double cm = loop.observer_plant_gain;
    Eigen::RowVectorXd y_pred = Eigen::RowVectorXd::Zero(n), w_pred = Eigen::RowVectorXd::Zero(n);
    y_pred(io) = 1.0;
    y_pred(io + 1) = h;
    y_pred(iu + loop.observer_delay_ticks) = 0.5 * h * h * cm;
    w_pred(io + 1) = 1.0;
    w_pred(iu + loop.observer_delay_ticks) = h * cm;
    Eigen::RowVectorXd residual = -y_pred;
    residual(0) += 1.0;
    y_hat = y_pred + l1 * residual;
    w_hat = w_pred + (l2 / h) * residual;
    d_raw = -w_hat;
  } else if (loop.derivative == pid::DerivativeSource::Rates) {
    d_raw(1) = -1.0;
  } else {
    d_raw(0) = -1.0 / h;
    d_raw(ip) = 1.0 / h;
  }
  Eigen::RowVectorXd filtered = beta * d_raw;
  filtered(id) += 1.0 - beta;
  Eigen::RowVectorXd integral = Eigen::RowVectorXd::Zero(n);
  // With Ki = 0 the PID freezes its integral: a constant, not a mode of the loop (its eigenvalue
  // 1 would read as marginal stability).
  integral(ii) = gains.ki != 0.0 ? 1.0 : 0.0;
  integral(0) = -gains.ki * h;
  Eigen::RowVectorXd u = integral + gains.kd * filtered;
  u(0) += -gains.kp;
  // u_{k−j} as a row of the state (j = 0: this tick's output).
  const auto past = [&](int j) {
    if (j == 0) return u;
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    r(iu + j - 1) = 1.0;
    return r;
  };
  const Eigen::RowVectorXd v1 = past(m);
  const Eigen::RowVectorXd v0 = f > 0.0 ? past(m + 1) : Eigen::RowVectorXd::Zero(n);

  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  a.topLeftCorner(np, np) = plant.phi;
  a.topRows(np) += plant.g1 * v1 + plant.g0 * v0;
  a.row(ii) = integral;
  a.row(id) = filtered;
  a(ip, 0) = 1.0;
  if (len > 0) {
    a.row(iu) = u;
    for (int j = 1; j < len; ++j)
      a(iu + j, iu + j - 1) = 1.0;
  }
  if (observed) {
    a.row(io) = y_hat;
    a.row(io + 1) = w_hat;
  }
  return a;
}

}  // namespace detail

namespace {

// L(e^{jωh}) with the plant discretised once (margins() evaluates it thousands of times):
// L = Kp a + Ki b + Kd c with gain-independent terms a = Pθ, b = h z / (z − 1) Pθ, c = F D, each
// with the whole ticks of delay z^−d.
class LoopResponse {
 public:
  explicit LoopResponse(const JointLoop& loop)
      : loop_(loop), plant_(detail::discretise(loop, loop.plant_gain, loop.delay_fraction)) {
    if (loop.gear_resonance_hz > 0.0) {
      // Φ = U T U* (complex Schur: T upper triangular, U unitary) once, so that every frequency
      // solves (zI − T) y = U* (g1 + g0 / z) by back substitution: no pivoting per frequency.
      const Eigen::ComplexSchur<Eigen::MatrixXcd> schur(plant_.phi.cast<Complex>());
      schur_t_ = schur.matrixT();
      const Eigen::MatrixXcd& u = schur.matrixU();
      schur_g1_ = u.adjoint() * plant_.g1.cast<Complex>();
      schur_g0_ = u.adjoint() * plant_.g0.cast<Complex>();
      schur_rows_ = u.topRows(2);
    }
  }

  detail::ResponseTerms terms(double omega_rad_s) const {
    const double h = loop_.tick_s;
    const Complex z = std::polar(1.0, omega_rad_s * h);
    Complex p_theta, p_omega;
    if (loop_.gear_resonance_hz > 0.0) {
      // (zI − Φ)⁻¹ (g1 + g0 / z) = U (zI − T)⁻¹ U* (g1 + g0 / z): the motor side's angle and
      // rate are its first two entries.
      const auto n = static_cast<int>(schur_t_.rows());
      const Complex z_inverse = std::conj(z);  // |z| = 1
      std::array<Complex, 6> y{};              // room for the geared plant's 4 or 5 states
      for (int i = n - 1; i >= 0; --i) {
        Complex sum = schur_g1_(i) + schur_g0_(i) * z_inverse;
        for (int k = i + 1; k < n; ++k)
          sum += schur_t_(i, k) * y[static_cast<std::size_t>(k)];
        // sum / (z − T_ii) without the library's scaled complex division: the divisor is far from
        // overflow (|T_ii| <= 1 for a plant that does not grow) and not 0 on the grid (ω > 0).
        const Complex d = z - schur_t_(i, i);
        y[static_cast<std::size_t>(i)] = sum * std::conj(d) / std::norm(d);
      }
      for (int k = 0; k < n; ++k) {
        p_theta += schur_rows_(0, k) * y[static_cast<std::size_t>(k)];
        p_omega += schur_rows_(1, k) * y[static_cast<std::size_t>(k)];
      }
    } else if (loop_.torque_bandwidth_hz > 0.0) {
      // (zI − Φ)⁻¹ (g1 + g0 / z): the transfers from u to θ and θ̇. Φ is upper triangular (so is
      // the continuous plant with its lag), so back substitution solves it.
      const Eigen::MatrixXd& phi = plant_.phi;
      const Complex g2 = plant_.g1(2) + plant_.g0(2) / z;
      const Complex x2 = g2 / (z - phi(2, 2));
      const Complex x1 = (plant_.g1(1) + plant_.g0(1) / z + phi(1, 2) * x2) / (z - phi(1, 1));
      p_omega = x1;
      p_theta =
          (plant_.g1(0) + plant_.g0(0) / z + phi(0, 1) * x1 + phi(0, 2) * x2) / (z - phi(0, 0));
    } else {
      // The same in closed form: Φ = [[1, p], [0, q]].
      const double p = plant_.phi(0, 1), q = plant_.phi(1, 1);
      const Complex gt = plant_.g1(0) + plant_.g0(0) / z, gw = plant_.g1(1) + plant_.g0(1) / z;
      p_theta = ((z - q) * gt + p * gw) / ((z - 1.0) * (z - q));
      p_omega = gw / (z - q);
    }
    const double beta = h / (loop_.derivative_filter_s + h);
    const Complex filter = beta * z / (z - 1.0 + beta);
    const Complex delay = std::polar(1.0, -omega_rad_s * h * loop_.delay_ticks);
    if (loop_.derivative == pid::DerivativeSource::Observer) {
      // ŵ = Gθ θ + Gu u with (I − Φo/z)⁻¹ applied to the gain K and to Γo c_m z^−(1+d_o).
      const auto [l1, l2] = observer_gains(loop_);
      const Eigen::Matrix2d phi_o{{(1.0 - l1), (1.0 - l1) * h}, {-l2 / h, 1.0 - l2}};
      const Eigen::Vector2d gamma_o{(1.0 - l1) * 0.5 * h * h, h - l2 * 0.5 * h};
      const Eigen::Matrix2cd inverse =
          (Eigen::Matrix2cd::Identity() - phi_o.cast<Complex>() / z).inverse();
      const Complex g_theta = (inverse * Eigen::Vector2d{l1, l2 / h}.cast<Complex>())(1);
      const Complex g_u = (inverse * gamma_o.cast<Complex>())(1) * loop_.observer_plant_gain *
                          std::pow(z, -(1 + loop_.observer_delay_ticks));
      return {p_theta * delay, h * z / (z - 1.0) * p_theta * delay,
              filter * g_theta * p_theta * delay, filter * g_u};
    }
    const Complex derivative =
        loop_.derivative == pid::DerivativeSource::Rates ? p_omega : (1.0 - 1.0 / z) / h * p_theta;
    return {p_theta * delay, h * z / (z - 1.0) * p_theta * delay, filter * derivative * delay,
            Complex(0.0)};
  }

  Complex operator()(double omega_rad_s) const { return combine(terms(omega_rad_s)); }

  Complex combine(const detail::ResponseTerms& t) const {
    return (loop_.gains.kp * t.a + loop_.gains.ki * t.b + loop_.gains.kd * t.c) /
           (1.0 + loop_.gains.kd * t.g);
  }

 private:
  JointLoop loop_;
  detail::DiscretePlant plant_;
  // With a gear: Φ's Schur form (T, U* g1, U* g0 and U's first two rows).
  Eigen::MatrixXcd schur_t_;
  Eigen::VectorXcd schur_g1_, schur_g0_;
  Eigen::MatrixXcd schur_rows_;
};

// The logarithmic grid margins() scans: n points up to π/h.
std::vector<double> frequency_grid(double tick_s, int grid_points) {
  const double nyquist = kPi / tick_s;
  const int n = std::max(16, grid_points);
  std::vector<double> w(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    w[static_cast<std::size_t>(i)] =
        i == n - 1 ? nyquist : nyquist * std::pow(10.0, -5.0 + 5.0 * i / (n - 1));
  return w;
}

}  // namespace

namespace detail {

PlantGrid plant_grid(const JointLoop& loop, const MarginOptions& options) {
  PlantGrid g;
  g.omega_rad_s = frequency_grid(loop.tick_s, options.grid_points);
  const LoopResponse response(loop);
  g.terms.reserve(g.omega_rad_s.size());
  for (double w : g.omega_rad_s)
    g.terms.push_back(response.terms(w));
  return g;
}

}  // namespace detail

Complex loop_response(const JointLoop& loop, double omega_rad_s) {
  return LoopResponse(loop)(omega_rad_s);
}

namespace {

// Spectral radius with the loop's gains scaled and a total delay of m + f ticks.
// With an observer the loop gain is the plant's (the PID's gains also act on the observer's own
// path, so scaling them is another change).
double spectral_radius(const JointLoop& loop, double gain_scale, int m, double f) {
  const bool observed = loop.derivative == pid::DerivativeSource::Observer;
  const double s = observed ? 1.0 : gain_scale;
  const pid::Gains<double> k{s * loop.gains.kp, s * loop.gains.ki, s * loop.gains.kd};
  const double c = observed ? gain_scale * loop.plant_gain : loop.plant_gain;
  const Eigen::VectorXcd lambda = detail::closed_loop_matrix(loop, k, c, m, f).eigenvalues();
  double rho = 0.0;
  for (int i = 0; i < lambda.size(); ++i)
    rho = std::max(rho, std::abs(lambda(i)));
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
  return detail::margins(loop, options, nullptr);
}

LoopMargins detail::margins(const JointLoop& loop, const MarginOptions& options,
                            const PlantGrid* grid) {
  LoopMargins m;
  m.phase_crossover_rad_s = m.gain_crossover_rad_s = m.disk_frequency_rad_s = kNaN;
  if (!valid(loop)) return m;
  m.spectral_radius = closed_loop_spectral_radius(loop);
  m.stable = m.spectral_radius < 1.0 - 1e-12;

  const LoopResponse response(loop);
  const double nyquist = kPi / loop.tick_s;
  const std::vector<double> w =
      grid != nullptr ? grid->omega_rad_s : frequency_grid(loop.tick_s, options.grid_points);
  const int n = static_cast<int>(w.size());
  std::vector<Complex> l(w.size());
  for (std::size_t i = 0; i < w.size(); ++i)
    l[i] = grid != nullptr ? response.combine(grid->terms[i]) : response(w[i]);
  const auto at = [&](double omega) { return response(omega); };

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
