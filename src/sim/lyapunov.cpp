#include "fuzzypid/sim/lyapunov.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <mutex>
#include <sstream>
#include <utility>
#include <vector>

#include <sdpa_call.h>
#include <Eigen/Dense>

#include "loop_matrix.hpp"

// OpenBLAS (what Debian's LAPACK alternative usually is) starts a thread per core that spins on
// sched_yield between calls; on matrices this small that is all overhead, and on a loaded
// machine it made one certificate 10× slower. Declared weak: with another BLAS it is absent.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace fuzzypid::sim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The corners of [lo, hi] (one value when lo == hi).
std::vector<double> ends(double lo, double hi) {
  return lo == hi ? std::vector<double>{lo} : std::vector<double>{lo, hi};
}

// A diagonal similarity D (powers of two, so exact) that balances the summed magnitudes of the
// matrices (Osborne's iteration): the LMIs of D⁻¹ A D are far better conditioned when the states
// have different units (rad, rad/s, the command).
Eigen::VectorXd balance(const std::vector<Eigen::MatrixXd>& as) {
  const Eigen::Index n = as.front().rows();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  for (const auto& a : as)
    m += a.cwiseAbs();
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  for (int sweep = 0; sweep < 50; ++sweep) {
    bool changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      double row = 0.0, col = 0.0;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (j == i) continue;
        row += m(i, j) * d(j) / d(i);
        col += m(j, i) * d(i) / d(j);
      }
      if (row == 0.0 || col == 0.0) continue;
      const double f = std::exp2(std::round(0.5 * std::log2(row / col)));
      if (f != 1.0) {
        d(i) *= f;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return d;
}

// ‖A‖_P = σmax(Lᵀ A L⁻ᵀ) with P = L Lᵀ: the square root of the largest eigenvalue of MᵀM.
double p_norm(const Eigen::MatrixXd& a, const Eigen::LLT<Eigen::MatrixXd>& llt) {
  const Eigen::MatrixXd lt = llt.matrixU();  // Lᵀ
  const Eigen::MatrixXd m = lt * a * lt.inverse();
  const Eigen::MatrixXd mtm = m.transpose() * m;
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(mtm, Eigen::EigenvaluesOnly)
                       .eigenvalues()(mtm.rows() - 1));
}

// Solves for P with I ⪯ P ⪯ γ I and P − Aᵀ P A ⪰ δ I at every A, minimising γ. δ, the decrease
// asked for, is half the smallest 1 − ρ(A)² of the matrices: a slow mode (ρ near 1, e.g. a small
// integral gain) then still has a P of order 1, where a fixed δ = 1 would need P ~ 1 / (1 − ρ²)
// and defeat the solver's scaling. Returns an empty matrix and the solver's phase when it finds
// none.
Eigen::MatrixXd solve_lmis(const std::vector<Eigen::MatrixXd>& as, double delta, std::string& phase,
                           bool careful) {
  const auto n = static_cast<int>(as.front().rows());
  const int unknowns = n * (n + 1) / 2;  // the upper triangle of P
  const int m = unknowns + 1;            // and γ
  const auto blocks = static_cast<int>(as.size()) + 2;
  static std::once_flag single_threaded_blas;
  std::call_once(single_threaded_blas, [] {
    if (openblas_set_num_threads != nullptr) openblas_set_num_threads(1);
  });
  SDPA sdpa;
  sdpa.setDisplay(nullptr);
  sdpa.setNumThreads(1);
  if (careful) {
    sdpa.setParameterType(SDPA::PARAMETER_STABLE_BUT_SLOW);
    sdpa.setParameterEpsilonStar(1e-10);
    sdpa.setParameterEpsilonDash(1e-10);
  } else {
    sdpa.setParameterType(SDPA::PARAMETER_DEFAULT);
  }
  sdpa.inputConstraintNumber(m);
  sdpa.inputBlockNumber(blocks);
  for (int l = 1; l <= blocks; ++l) {
    sdpa.inputBlockSize(l, n);
    sdpa.inputBlockType(l, SDPA::SDP);
  }
  sdpa.initializeUpperTriangleSpace();
  sdpa.inputCVec(m, 1.0);  // minimise γ
  // SDPA's form: Σ_k F_k x_k − F_0 ⪰ 0 per block; F_0 = I in the first, δ I in the next |as|.
  for (int l = 1; l <= blocks - 1; ++l)
    for (int i = 1; i <= n; ++i)
      sdpa.inputElement(0, l, i, i, l == 1 ? 1.0 : delta);
  int k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) {
      ++k;
      // E: the symmetric basis matrix of P's entry (i, j).
      Eigen::MatrixXd e = Eigen::MatrixXd::Zero(n, n);
      e(i, j) = e(j, i) = 1.0;
      sdpa.inputElement(k, 1, i + 1, j + 1, 1.0);
      for (std::size_t v = 0; v < as.size(); ++v) {
        const Eigen::MatrixXd f = e - as[v].transpose() * e * as[v];
        for (int r = 0; r < n; ++r)
          for (int c = r; c < n; ++c)
            if (f(r, c) != 0.0)
              sdpa.inputElement(k, static_cast<int>(v) + 2, r + 1, c + 1, f(r, c));
      }
      sdpa.inputElement(k, blocks, i + 1, j + 1, -1.0);
    }
  for (int i = 1; i <= n; ++i)
    sdpa.inputElement(m, blocks, i, i, 1.0);
  sdpa.initializeUpperTriangle();
  // SDPA reports numerical trouble on std::cout; the phase says it all, and a JSON report on
  // stdout must stay clean.
  std::ostringstream ignored;
  std::streambuf* const cout_buffer = std::cout.rdbuf(ignored.rdbuf());
  sdpa.initializeSolve();
  sdpa.solve();
  std::cout.rdbuf(cout_buffer);
  char buf[32] = {};
  sdpa.getPhaseString(buf);
  phase = buf;
  phase.erase(phase.find_last_not_of(' ') + 1);
  const SDPA::PhaseType result = sdpa.getPhaseValue();
  Eigen::MatrixXd p;
  if (result == SDPA::pdOPT || result == SDPA::pFEAS || result == SDPA::pdFEAS ||
      result == SDPA::pFEAS_dINF || result == SDPA::dUNBD) {
    const double* x = sdpa.getResultXVec();
    p = Eigen::MatrixXd::Zero(n, n);
    k = 0;
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) {
        p(i, j) = p(j, i) = x[k];
        ++k;
      }
  }
  sdpa.terminate();
  return p;
}

double spectral_radius(const Eigen::MatrixXd& a) {
  const Eigen::VectorXcd lambda = a.eigenvalues();
  double rho = 0.0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
    rho = std::max(rho, std::abs(lambda(i)));
  return rho;
}

// The largest ρ(A_{s_n} ⋯ A_{s_1})^{1/n} over every sequence of the matrices of period n <=
// max_period (each cycle once up to rotation is enough, but all are cheap at these sizes).
std::pair<double, std::size_t> worst_switching(const std::vector<Eigen::MatrixXd>& as,
                                               std::size_t max_period) {
  double best = 0.0;
  std::size_t period = 1;
  std::vector<std::size_t> s;
  const std::size_t k = as.size();
  for (std::size_t n = 1; n <= max_period; ++n) {
    s.assign(n, 0);
    while (true) {
      Eigen::MatrixXd product = as[s[0]];
      for (std::size_t j = 1; j < n; ++j)
        product = as[s[j]] * product;
      const double r = std::pow(spectral_radius(product), 1.0 / static_cast<double>(n));
      if (r > best) {
        best = r;
        period = n;
      }
      std::size_t j = 0;
      while (j < n && ++s[j] == k)
        s[j++] = 0;
      if (j == n) break;
    }
  }
  return {best, period};
}

bool finite_box(const GainBox& b) {
  return b.low.finite() && b.high.finite() && b.low.kp <= b.high.kp && b.low.ki <= b.high.ki &&
         b.low.kd <= b.high.kd;
}

}  // namespace

const char* lyapunov_assumptions() noexcept {
  return "linear joint (no saturation, Coulomb friction or backlash; with saturation and an "
         "integrator the result is local; an elastic gear in the frozen-gain margins, the joint "
         "rigid in the certificate for moving gains), inertia and viscous friction inside "
         "the ranges given, gains inside the box; the gains may change on every tick, the inertia "
         "too within each of the intervals the certificate names (slowly across them)";
}

LyapunovCertificate common_lyapunov(const SwitchingLoop& set) {
  LyapunovCertificate out;
  const JointLoop& base = set.loop;
  const bool ranges_ok =
      std::isfinite(set.plant_gain_min) && std::isfinite(set.plant_gain_max) &&
      set.plant_gain_min > 0.0 && set.plant_gain_min <= set.plant_gain_max &&
      std::isfinite(set.damping_min_per_s) && std::isfinite(set.damping_max_per_s) &&
      set.damping_min_per_s >= 0.0 && set.damping_min_per_s <= set.damping_max_per_s &&
      finite_box(set.gains) && std::isfinite(base.tick_s) && base.tick_s > 0.0 &&
      std::isfinite(base.derivative_filter_s) && base.derivative_filter_s >= 0.0 &&
      base.delay_ticks >= 0 && base.delay_fraction >= 0.0 && base.delay_fraction < 1.0 &&
      std::isfinite(set.torque_bandwidth_min_hz) && std::isfinite(set.torque_bandwidth_max_hz) &&
      set.torque_bandwidth_min_hz <= set.torque_bandwidth_max_hz &&
      (set.torque_bandwidth_max_hz == 0.0 || set.torque_bandwidth_min_hz > 0.0);
  if (!ranges_ok) {
    out.reason = "invalid loop or ranges";
    return out;
  }
  if (base.gear_resonance_hz != 0.0) {
    out.reason = "an elastic gear (the certificate is of rigid joints)";
    return out;
  }
  if (set.gains.high.ki > 0.0 && set.gains.low.ki <= 0.0) {
    out.reason = "Ki reaches 0 inside the box: there the integral is frozen and holds its value";
    return out;
  }
  // The damping and the current loop's bandwidth: the LMIs at the ends of each, P checked at six
  // values of each across their ranges (ends, geometric middle, quarters).
  struct PlantSample {
    double damping_per_s, bandwidth_hz;
  };
  const auto samples = [](double lo, double hi, bool check) {
    std::vector<double> v = ends(lo, hi);
    if (lo == hi || !check) return v;
    v.push_back(lo > 0.0 ? std::sqrt(lo * hi) : 0.5 * hi);
    for (int k = 1; k < 4; ++k)
      v.push_back(lo + (hi - lo) * k / 4.0);
    return v;
  };
  const auto plant_samples = [&](bool check) {
    std::vector<PlantSample> out_samples;
    for (double a : samples(set.damping_min_per_s, set.damping_max_per_s, check))
      for (double w : samples(set.torque_bandwidth_min_hz, set.torque_bandwidth_max_hz, check))
        out_samples.push_back({a, w});
    return out_samples;
  };
  const std::vector<PlantSample> solve_at = plant_samples(false), check_at = plant_samples(true);
  // The corners of the gain box × [c_lo, c_hi] at the given plant samples.
  const auto corners = [&](double c_lo, double c_hi, const std::vector<PlantSample>& plants) {
    std::vector<Eigen::MatrixXd> as;
    for (const PlantSample& sample : plants)
      for (double c : ends(c_lo, c_hi))
        for (double kp : ends(set.gains.low.kp, set.gains.high.kp))
          for (double ki : ends(set.gains.low.ki, set.gains.high.ki))
            for (double kd : ends(set.gains.low.kd, set.gains.high.kd)) {
              JointLoop loop = base;
              loop.damping_per_s = sample.damping_per_s;
              loop.torque_bandwidth_hz = sample.bandwidth_hz;
              as.push_back(detail::closed_loop_matrix(loop, {kp, ki, kd}, c, base.delay_ticks,
                                                      base.delay_fraction));
            }
    return as;
  };

  // One common P for the box × [c_lo, c_hi]: solved (SDPA) and checked (Eigen).
  struct Attempt {
    bool certified = false;
    double contraction = kNaN, condition_number = kNaN;
    std::string reason;
    std::vector<Eigen::MatrixXd> scaled_corners;
  };
  const auto attempt = [&](double c_lo, double c_hi) {
    Attempt r;
    std::vector<Eigen::MatrixXd> as = corners(c_lo, c_hi, solve_at);
    out.states = static_cast<std::size_t>(as.front().rows());
    out.vertices = as.size();
    const Eigen::VectorXd d = balance(as);
    const auto scaled = [&](const Eigen::MatrixXd& a) {
      return Eigen::MatrixXd(d.cwiseInverse().asDiagonal() * a * d.asDiagonal());
    };
    for (auto& a : as)
      a = scaled(a);
    // A corner that is unstable on its own rules out any common P.
    double rho_max = 0.0;
    for (const auto& a : as)
      rho_max = std::max(rho_max, spectral_radius(a));
    if (!(rho_max < 1.0)) {
      char buf[120];
      std::snprintf(buf, sizeof buf,
                    "a corner of the box is unstable with its gains frozen (spectral radius %.6g)",
                    rho_max);
      r.reason = buf;
      return r;
    }
    r.scaled_corners = as;
    const double delta = 0.5 * (1.0 - rho_max * rho_max);
    const std::vector<Eigen::MatrixXd> checked = [&] {
      std::vector<Eigen::MatrixXd> v = corners(c_lo, c_hi, check_at);
      for (auto& a : v)
        a = scaled(a);
      return v;
    }();
    // SDPA's default parameters first; its slow, stable ones when they give no P that passes.
    for (const bool careful : {false, true}) {
      std::string phase;
      const Eigen::MatrixXd p = solve_lmis(as, delta, phase, careful);
      const Eigen::LLT<Eigen::MatrixXd> llt(p.size() != 0 && p.allFinite() ? p : Eigen::MatrixXd());
      if (p.size() == 0 || !p.allFinite() || llt.info() != Eigen::Success) {
        r.reason = "no common quadratic Lyapunov function (SDPA: " + phase + ")";
        continue;
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(p);
      r.condition_number = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
      // The check, in double precision and independent of the solver's tolerances: at every
      // corner (and plant check point) Q = P − Aᵀ P A must be positive definite by more than the
      // rounding error of forming it, ~ n ε ‖P‖ (1 + ‖A‖²), with a factor of 100 to spare.
      double worst = 0.0;
      bool decreasing = true;
      const double p_norm2 = eig.eigenvalues().maxCoeff();
      const auto n = static_cast<double>(p.rows());
      for (const auto& a : checked) {
        worst = std::max(worst, p_norm(a, llt));
        const Eigen::MatrixXd q = p - a.transpose() * p * a;
        const double a_norm = a.norm();  // Frobenius: above the spectral norm, so safe here
        const double tolerance =
            100.0 * n * std::numeric_limits<double>::epsilon() * p_norm2 * (1.0 + a_norm * a_norm);
        const double q_min = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(
                                 0.5 * (q + q.transpose()), Eigen::EigenvaluesOnly)
                                 .eigenvalues()(0);
        decreasing = decreasing && q_min > tolerance;
      }
      r.contraction = worst;
      r.certified = decreasing && worst < 1.0;
      if (r.certified) {
        r.reason.clear();
        break;
      }
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "no common quadratic Lyapunov function: the best P found contracts by only "
                    "%.9g per tick (SDPA: %s)",
                    worst, phase.c_str());
      r.reason = buf;
    }
    return r;
  };

  // The whole inertia range first (it may change every tick); failing that, the range split
  // geometrically into 4, then 16 intervals with a P each: then the inertia may change every
  // tick within an interval and slowly across them, and every frozen inertia is covered.
  const double c_lo = set.plant_gain_min, c_hi = set.plant_gain_max;
  const Attempt whole = attempt(c_lo, c_hi);
  if (whole.certified) {
    out.certified = true;
    out.contraction = whole.contraction;
    out.condition_number = whole.condition_number;
    out.inertia_intervals = 1;
    return out;
  }
  out.reason = whole.reason;
  if (c_lo < c_hi && !whole.scaled_corners.empty()) {
    for (std::size_t k = 4; k <= 16 && !out.certified; k *= 4) {
      double worst = 0.0, condition = 0.0;
      bool all = true;
      for (std::size_t j = 0; j < k && all; ++j) {
        const double lo = c_lo * std::pow(c_hi / c_lo, static_cast<double>(j) / k);
        const double hi = j + 1 == k ? c_hi : c_lo * std::pow(c_hi / c_lo, (j + 1.0) / k);
        const Attempt part = attempt(lo, hi);
        all = part.certified;
        worst = std::max(worst, part.contraction);
        condition = std::max(condition, part.condition_number);
      }
      if (all) {
        out.certified = true;
        out.contraction = worst;
        out.condition_number = condition;
        out.inertia_intervals = k;
        out.reason.clear();
      }
    }
    if (out.certified) return out;
  }
  // No P: is there a switching sequence of the corners that really diverges? Sequences up to a
  // length whose count stays near 10⁵ products.
  if (!whole.scaled_corners.empty()) {
    const auto& as = whole.scaled_corners;
    std::size_t max_period = 1;
    for (double count = static_cast<double>(as.size());
         max_period < 6 && count * static_cast<double>(as.size()) <= 1e5;
         count *= static_cast<double>(as.size()))
      ++max_period;
    const auto [radius, period] = worst_switching(as, max_period);
    out.switching_radius = radius;
    out.switching_period = period;
    char buf[200];
    if (radius >= 1.0)
      std::snprintf(buf, sizeof buf,
                    "; switching between the box's corners with period %zu diverges (growth "
                    "%.6g per tick)",
                    period, radius);
    else
      std::snprintf(buf, sizeof buf,
                    "; no switching of period <= %zu between the corners diverges (worst growth "
                    "%.9g per tick): the refusal may be conservative",
                    max_period, radius);
    out.reason += buf;
  }
  out.contraction = whole.contraction;
  return out;
}

}  // namespace fuzzypid::sim
