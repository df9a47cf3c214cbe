// supervisor::RuleTable (the fuzzy-rules family's supervisor) written as a rule file that fuzzypid's
// own readers and fuzzylite 6 evaluate to RuleTable::infer's delta (library fuzzypid::rulefile).
//
// The construction, exact up to rounding (|file - infer| <= 1e-12 measured for .fll and .fcl):
//   inputs `e`, `ec` (x = Ke e, y = Kec ec): NB = Ramp(c1, c0) and PB = Ramp(c5, c6) (shoulders,
//     degree 1 beyond +-c_max), NM .. PM triangles with feet at the neighbouring centers; and
//     neg = Ramp(0, -1), pos = Ramp(0, 1), so that neg + pos = min(1, |x|);
//   outputs dKp, dKi, dKd: Constant terms, WeightedSum (sum w z, no normalisation: the strong
//     partition fires four rules whose degrees sum to 1), aggregation none;
//   block `table` (AND = AlgebraicProduct), one rule per cell:
//     if e is E_i and ec is EC_j then dKp is x<T_p> and dKi is x<T_i> and dKd is x<T_d>
//     where the term x0_85 is the constant 0.85 - 1: "the gain becomes 0.85 x the schedule's";
//   block `schedule_ramp` (AND = AlgebraicProduct, OR = BoundedSum), per cell and per gain with
//     R_g != 1 (a gain with R_g = 1 has no ramp):
//     if e is E_i and ec is EC_j and (e is neg or e is pos or ec is neg or ec is pos)
//       then dKp is ramp with T_p[i][j] / s_p
//     where the bounded sum of the four ramps is min(1, |x| + |y|) exactly and the term `ramp`
//     (`ramp_x2`, ... when s_p = 2, 4, ...) is the constant (R_p - 1) s_p. The cell's ratio is the
//     rule weight (times s_p, the smallest power of two >= max(1, max T_p), so weights stay in
//     [0, 1] and both factors are exact): one ramp term per output instead of one per distinct
//     (R - 1) T, which keeps any 7 x 7 table within the reader's 64 terms per variable.
// Summed: sum_ij mu_i nu_j ((T_ij - 1) + (R - 1) w T_ij) = (R - 1) w rho + (rho - 1) = delta.
// Even tables read shorter: when T[i][j] = T[6 - i][j] (for all three gains in block 1, for gain
// g in its ramp rules) the mirrored rules merge as "(e is NB or e is PB) and ...", likewise in
// ec (block 1 then has disjunction Maximum). Exact: the two sets of a pair never both hold, so
// the merged rule fires exactly the degree of the one that does.
//
// .fis (MATLAB) cannot hold block 2: it has one rule block and rules whose connectives are all
// `and` or all `or` over distinct inputs, and w(x, y) min(1, |x| + |y|) times the cell's degrees
// is no sum of products of per-input memberships. to_fis therefore writes only tables whose ratios
// R are all 1 (block 1 alone, DefuzzMethod 'wtsum', AndMethod 'prod', shoulders as trapmf with
// infinite feet) and refuses the others with a message.
//
// Set-up code: allocates, never throws; the functions return false with `error` set when the
// table is not valid(), a cell or ramp constant lies beyond the float range (FLT_MAX; the error
// names the cell and its value), or the format cannot express it. The ramp term of a scale s is
// `ramp_` + ratio_term_name(s) (ramp_x2, ramp_x1_2676506002282294e30).
#pragma once

#include <string>

#include "fuzzypid/supervisor/rule_table.hpp"

namespace fuzzypid::rulefile {

// `name` is the engine's name (letters, digits, '_'; written as given).
[[nodiscard]] bool rule_table_to_fll(const supervisor::RuleTable<double>& table, std::string& out,
                                     std::string& error, const std::string& name = "fuzzy_rules");
[[nodiscard]] bool rule_table_to_fcl(const supervisor::RuleTable<double>& table, std::string& out,
                                     std::string& error, const std::string& name = "fuzzy_rules");
[[nodiscard]] bool rule_table_to_fis(const supervisor::RuleTable<double>& table, std::string& out,
                                     std::string& error, const std::string& name = "fuzzy_rules");

// The constant term name of a cell ratio: "x" and the shortest decimal that reads back as
// `ratio`, with '.' -> '_', '-' -> 'm', '+' dropped (0.85 -> "x0_85", 1e-05 -> "x1em05").
std::string ratio_term_name(double ratio);

}  // namespace fuzzypid::rulefile
