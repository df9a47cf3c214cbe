// A tuned rule base that refines a gain schedule: the supervisor of the `fuzzy-rules` family.
//
// FuzzyPid hands every supervisor the scaled inputs (x, y) = (Ke e, Kec ec) and applies
// K = K0 + S dK (Eq. 6). This family uses S = K0 (output_scale = the nominal gains), so the
// supervisor returns the gain ratio minus one, dK_g = K_g / K0_g - 1, with
//
//     ratio_g(x, y) = (1 + (R_g - 1) w(x, y)) rho_g(x, y)
//     w(x, y)       = min(1, |x| + |y|)                       (GainSchedule's ramp)
//     rho_g(x, y)   = sum_ij mu_i(x) nu_j(y) T_g[i][j] / sum_ij mu_i(x) nu_j(y)
//
// rho is a zero-order Takagi-Sugeno system with product AND and weighted average over a strong
// partition of each input: Sets triangles (NB NM NS ZO PS PM PB for 7) whose feet are the
// neighbouring centers, the outermost two shoulders (degree 1 beyond +-c_max: the input
// saturates). At most four rules fire and their degrees sum to 1, so rho is the bilinear
// interpolation of T_g on the grid of centers, equal to T_g[i][j] at node (i, j). T_g are
// positive ratios: T = 1 everywhere is the schedule itself (rho = 1 exactly), T = 0.85 in a cell
// makes that gain 0.85 times the schedule's there.
//
// delta_g is computed as (R_g - 1) w rho + (rho - 1): with T = 1, rho is exactly 1 (the
// weights of each axis are 1 - t and t, and fl(fl(1 - t) + t) = 1 for t in [0, 1]), so delta_g is
// (R_g - 1) w bit for bit and the controller reproduces the `scheduled` family
// K0 + K0 (R - 1) w to rounding (the two differ only in the order of the products).
//
// The model is an immutable aggregate (usable as constexpr data, e.g. in a generated header for
// a microcontroller) with no per-joint state: Workspace is empty. Controllers keep a non-owning
// pointer to it, so it must outlive them. Check valid() once at set-up; infer() assumes it.
#pragma once

#include <array>
#include <cstddef>

#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

// In fuzzypid::detail beside scalar.hpp's helpers (a supervisor::detail would hide fuzzypid::detail
// from the supervisor/ headers included after this one).
namespace fuzzypid::detail {

// Centers 0, +-1/m, ..., +-1 (m = (Sets - 1) / 2): the ramp w saturates at |x| + |y| = 1.
template <class Scalar, std::size_t Sets>
constexpr std::array<Scalar, Sets> rule_table_uniform_centers() noexcept {
  constexpr std::size_t m = (Sets - 1) / 2;
  std::array<Scalar, Sets> c{};
  for (std::size_t k = 0; k < Sets; ++k) {
    const Scalar v = Scalar(k > m ? k - m : m - k) / Scalar(m);
    c[k] = k < m ? -v : v;
  }
  return c;
}

template <class Scalar, std::size_t Sets>
constexpr std::array<std::array<std::array<Scalar, Sets>, Sets>, 3>
rule_table_unit_tables() noexcept {
  std::array<std::array<std::array<Scalar, Sets>, Sets>, 3> t{};
  for (auto& table : t)
    for (auto& row : table)
      for (auto& v : row)
        v = Scalar(1);
  return t;
}

}  // namespace fuzzypid::detail

namespace fuzzypid::supervisor {

template <class Scalar, std::size_t Sets = 7>
struct RuleTable {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(Sets >= 3 && Sets % 2 == 1, "RuleTable needs an odd number of sets (>= 3)");

  using Table = std::array<std::array<Scalar, Sets>, Sets>;  // [i: set of e][j: set of ec]
  struct Workspace {};

  // The four nodes (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1) around an input pair, the
  // degrees of x in sets i, i + 1 (mu) and of y in sets j, j + 1 (nu), and the rules' firing
  // degrees weight[a][b] = mu[a] nu[b]; every other rule has degree 0. The weights sum to 1 (to
  // rounding); a node whose weight is 0 did not fire.
  struct Cell {
    std::size_t i = 0;
    std::size_t j = 0;
    std::array<Scalar, 2> mu{};
    std::array<Scalar, 2> nu{};
    std::array<std::array<Scalar, 2>, 2> weight{};
  };

  // The model, in this order for brace initialisation.
  std::array<Scalar, 3> schedule_ratio{Scalar(1), Scalar(1), Scalar(1)};        // R_p, R_i, R_d
  std::array<Table, 3> table = detail::rule_table_unit_tables<Scalar, Sets>();  // T_p, T_i, T_d
  // Centers of the sets of x = Ke e and y = Kec ec (dimensionless universe units), ascending,
  // symmetric (c_k = -c_{Sets-1-k}); c_max = c_{Sets-1} is where the input saturates.
  std::array<Scalar, Sets> e_centers = detail::rule_table_uniform_centers<Scalar, Sets>();
  std::array<Scalar, Sets> ec_centers = detail::rule_table_uniform_centers<Scalar, Sets>();

  static constexpr std::size_t num_sets() noexcept { return Sets; }
  static constexpr std::array<Scalar, Sets> default_centers() noexcept {
    return detail::rule_table_uniform_centers<Scalar, Sets>();
  }
  static constexpr Table unit_table() noexcept {
    return detail::rule_table_unit_tables<Scalar, Sets>()[0];
  }

  // Centers finite, strictly ascending and exactly symmetric about 0; R and T finite and > 0,
  // with max(1, R_g) max(T_g) finite (so no ratio overflows).
  constexpr bool valid() const noexcept {
    if (!centers_valid(e_centers) || !centers_valid(ec_centers)) return false;
    for (std::size_t g = 0; g < 3; ++g) {
      const Scalar r = schedule_ratio[g];
      if (!(detail::is_finite(r) && r > Scalar(0))) return false;
      Scalar t_max = Scalar(0);
      for (const auto& row : table[g])
        for (const Scalar v : row) {
          if (!(detail::is_finite(v) && v > Scalar(0))) return false;
          t_max = detail::max(t_max, v);
        }
      if (!detail::is_finite(detail::max(Scalar(1), r) * t_max)) return false;
    }
    return true;
  }

  Workspace make_workspace() const noexcept { return {}; }

  // delta_g = ratio_g - 1 for g = p, i, d (see the top of the file). Non-finite inputs are a fault
  // (delta = 0), as in GainSchedule. Requires valid().
  [[nodiscard]] Status infer(Scalar x, Scalar y, Workspace& /*ws*/,
                             std::array<Scalar, 3>& delta) const noexcept {
    if (!detail::is_finite(x) || !detail::is_finite(y)) {
      delta = {Scalar(0), Scalar(0), Scalar(0)};
      return Status::NonFiniteInput;
    }
    const Cell c = cell(x, y);
    const Scalar w = ramp(x, y);
    for (std::size_t g = 0; g < 3; ++g) {
      const Scalar rho = interpolate(c, table[g]);
      delta[g] = (schedule_ratio[g] - Scalar(1)) * w * rho + (rho - Scalar(1));
    }
    return Status::Ok;
  }

  // The cell holding (x, y) and its four firing degrees (for "which rules did training visit").
  // Requires finite x and y.
  constexpr Cell cell(Scalar x, Scalar y) const noexcept {
    const Axis a = locate(e_centers, x);
    const Axis b = locate(ec_centers, y);
    Cell c;
    c.i = a.k;
    c.j = b.k;
    c.mu = {a.lower, a.upper};
    c.nu = {b.lower, b.upper};
    c.weight = {{{a.lower * b.lower, a.lower * b.upper}, {a.upper * b.lower, a.upper * b.upper}}};
    return c;
  }

  // w(x, y) = min(1, |x| + |y|), the schedule's ramp.
  static constexpr Scalar ramp(Scalar x, Scalar y) noexcept {
    const Scalar a = detail::abs(x) + detail::abs(y);
    return a < Scalar(1) ? a : Scalar(1);
  }

  // rho_g(x, y): the rule base's refinement of gain g (0 = p, 1 = i, 2 = d). Requires finite x, y.
  constexpr Scalar refinement(Scalar x, Scalar y, std::size_t g) const noexcept {
    return interpolate(cell(x, y), table[g]);
  }

  // ratio_g(x, y) = K_g / K0_g = 1 + delta_g. Requires finite x, y.
  constexpr Scalar ratio(Scalar x, Scalar y, std::size_t g) const noexcept {
    const Scalar rho = refinement(x, y, g);
    return Scalar(1) + ((schedule_ratio[g] - Scalar(1)) * ramp(x, y) * rho + (rho - Scalar(1)));
  }

 private:
  // Node k (the lower of two neighbours) and the degrees of nodes k and k + 1.
  struct Axis {
    std::size_t k;
    Scalar lower;
    Scalar upper;
  };

  static constexpr bool centers_valid(const std::array<Scalar, Sets>& c) noexcept {
    for (std::size_t k = 0; k < Sets; ++k) {
      if (!detail::is_finite(c[k]) || c[k] != -c[Sets - 1 - k]) return false;
      if (k + 1 < Sets && !(c[k] < c[k + 1])) return false;
    }
    return true;
  }

  // By symmetry, |x| is located among the positive centers c_m .. c_max (m = (Sets - 1) / 2):
  // k counts the m - 1 inner centers at or below |x| (compares summed, no data-dependent branch),
  // then one division; a negative x takes the mirrored nodes. Beyond c_max, |x| is clamped to
  // c_max, where t = (c_max - c_k) / (c_max - c_k) = 1 exactly: the shoulder holds x with degree
  // 1 and its neighbour with 0.
  static constexpr Axis locate(const std::array<Scalar, Sets>& c, Scalar x) noexcept {
    constexpr std::size_t m = (Sets - 1) / 2;
    const bool negative = x < Scalar(0);
    const Scalar a = detail::min(negative ? -x : x, c[Sets - 1]);
    std::size_t k = m;
    for (std::size_t q = m + 1; q + 1 < Sets; ++q)
      k += static_cast<std::size_t>(c[q] <= a);  // now c[k] <= a <= c[k + 1], k <= Sets - 2
    const Scalar t = (a - c[k]) / (c[k + 1] - c[k]);
    const Scalar s = Scalar(1) - t;
    // Node of -c[k + 1] is Sets - 2 - k, of -c[k] is Sets - 1 - k.
    return {negative ? Sets - 2 - k : k, negative ? t : s, negative ? s : t};
  }

  // Weighted average of the four nodes; the weights sum to 1, so no division. Factored per axis,
  // nu_0 (mu_0 T + mu_1 T) + nu_1 (mu_0 T + mu_1 T), so that T = 1 gives exactly 1 and a node
  // (degrees 1 and 0) gives T there exactly.
  static constexpr Scalar interpolate(const Cell& c, const Table& t) noexcept {
    const Scalar lower_j = c.mu[0] * t[c.i][c.j] + c.mu[1] * t[c.i + 1][c.j];
    const Scalar upper_j = c.mu[0] * t[c.i][c.j + 1] + c.mu[1] * t[c.i + 1][c.j + 1];
    return c.nu[0] * lower_j + c.nu[1] * upper_j;
  }
};

}  // namespace fuzzypid::supervisor
