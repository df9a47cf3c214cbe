// The tuner's vocabulary: what each controller family searches (its parameters, in log10 inside a
// box), how a point of that space becomes a controller, the exact conversions between families
// (PID -> schedule -> rule table) that let one stage start where the last one ended, and the
// regulariser of the fuzzy-rules family's tables (docs/tuning.md).
//
//   pid:         kp, ki, kd
//   scheduled:   kp, ki, kd (K0, the gains on the path), ke, kec, rp, ri, rd (large-error ratios R)
//   fuzzy:       kp, ki, kd (K0), ke, kec, sp, si, sd (output scales of the paper's tables)
//   fuzzy-rules: the scheduled family's eight, then optionally the partition (e_f2, e_f1, ec_f2,
//                ec_f1: each inner center as a fraction of the next one out), then the log10 ratio
//                of each free class of table cells, "kp[i,j]" etc. (i: set of Ke e, j: set of
//                Kec ec, 0..6 = NB..PB). Classes follow the symmetry: even (16 per gain: T is the
//                same at (+-x, +-y)), odd (24: log T(-x, -y) = -log T(x, y), the center cell 1) or
//                none (49). A class whose nodes training never visits is held at the start's
//                values (unvisited = seed) or searched like the others (free).
//   every family, with the derivative filter searched: tf last (the PID's derivative filter
//                time constant Tf, log10 s), after all of the above.
//
// Library fuzzypid::tune (offline, allocates, never in a control loop).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/tune/record.hpp"

namespace fuzzypid::tune {

using controller::ControllerSpec;
using controller::Family;

// The searched derivative filter's name in a box (the last parameter with --search-filter, or the
// one before the observer's bandwidth).
inline constexpr const char* kFilterParameter = "tf";
// The searched velocity observer's bandwidth (the last parameter with --search-filter when the
// start's derivative is "observer").
inline constexpr const char* kObserverParameter = "observer_hz";
// The searched bandwidth scales of joints 2 .. 6 (ControllerSpec::bandwidth_scale; joint 1's is
// 1, so that the gains stay joint 1's): "bandwidth_j2" .. "bandwidth_j6", after everything else.
inline constexpr const char* kBandwidthParameterPrefix = "bandwidth_j";

enum class Symmetry : std::uint8_t { Even, Odd, None };
inline constexpr std::array<EnumName<Symmetry>, 3> kSymmetryNames{
    {{Symmetry::Even, "even"}, {Symmetry::Odd, "odd"}, {Symmetry::None, "none"}}};

enum class Unvisited : std::uint8_t { Seed, Free };
inline constexpr std::array<EnumName<Unvisited>, 2> kUnvisitedNames{
    {{Unvisited::Seed, "seed"}, {Unvisited::Free, "free"}}};

// The fuzzy-rules family's search and regulariser.
struct TableOptions {
  Symmetry symmetry = Symmetry::Even;
  bool partition = false;  // search the inner set centers too (ordered, symmetric)
  // Penalty added to the cost: smoothness x sum of squared log10 differences of neighbouring
  // cells, and monotone x sum of squared log10 decreases of the total gain ratio along each row
  // and column walked outwards from the center, in the direction of the schedule (R > 1: up).
  double smoothness = 0.0;
  double monotone = 0.0;
  Unvisited unvisited = Unvisited::Seed;
  double visit_threshold = 1e-4;  // a node is visited when it holds this share of the firing
  double cell_log10 = 1.0;        // each cell's box: log10 T in [-cell_log10, cell_log10]
};

using RuleTableSpec = controller::RuleTableSpec;
// The share of the total firing weight each node (i, j) of the table received.
using VisitMap = std::array<std::array<double, RuleTableSpec::kSets>, RuleTableSpec::kSets>;

class ParameterSpace {
 public:
  // The space of `family` around `start`: the result keeps start's units, PID options, bounds,
  // feed-forward and rule base; for fuzzy-rules start's table gives the values of the cells held
  // (start must then be a fuzzy-rules controller; `visits` says which nodes training reaches, and
  // is required when options.unvisited is Seed). Returns nullopt with `error` set otherwise.
  // With search_filter, the last parameter is tf: log10 of the derivative filter's time constant
  // Tf (s), in [-3, 0] at a 0.05 s tick (1 ms, no filter to speak of, .. 20 ticks); a start's
  // Tf below 1 ms enters the space at 1 ms. When start's derivative is "observer" it is followed
  // by observer_hz: log10 of the observer's bandwidth F (Hz), in [-1, 1] at a 0.05 s tick (a tenth
  // of a hertz .. 10 Hz, where the observer is nearly the differenced rate, pid.hpp).
  // With search_bandwidth, five more parameters close the space: log10 of the bandwidth scales of
  // joints 2 .. 6 relative to joint 1, in [-1, 1] (ControllerSpec::bandwidth_scale); start's
  // joint 1 must have scale 1, its other scales enter the space clamped into [0.1, 10]. Without
  // it the result keeps start's scales.
  [[nodiscard]] static std::optional<ParameterSpace> create(
      Family family, const ControllerSpec& start, const TableOptions& options,
      const VisitMap* visits, std::string& error, bool search_filter = false,
      bool search_bandwidth = false);

  Family family() const noexcept { return family_; }
  // The default box, one entry per searched parameter.
  const std::vector<SearchBox>& box() const noexcept { return box_; }
  // The controller at x (log10 values in box() order); x may lie outside the box.
  [[nodiscard]] ControllerSpec to_spec(const std::vector<double>& x) const;
  // The point of a controller of this family (the inverse of to_spec where the family can say
  // it: held cells and the outer center are the start's).
  [[nodiscard]] std::vector<double> from_spec(const ControllerSpec& spec) const;
  // The regulariser's cost of a controller of this family (0 for all but fuzzy-rules).
  [[nodiscard]] double penalty(const ControllerSpec& spec) const;
  // Cells (of 3 x 49) whose class is held at the start's values.
  std::size_t held_cells() const noexcept { return held_cells_; }
  // What the file's [tuning.regulariser] records (fuzzy-rules only).
  [[nodiscard]] TableRegulariser record() const;

 private:
  // One searched table class: the cells it sets and the sign of each (odd symmetry: -1 on the
  // mirror cell).
  struct CellClass {
    std::size_t gain = 0;
    std::vector<std::array<std::size_t, 2>> cells;
    std::vector<int> sign;
  };

  std::vector<double> from_spec_without_filter(const ControllerSpec& spec) const;

  Family family_{};
  ControllerSpec start_{};
  TableOptions options_{};
  std::vector<SearchBox> box_;
  std::vector<CellClass> classes_;
  std::size_t first_cell_ = 0;  // index of the first cell parameter in x
  std::size_t held_cells_ = 0;
  bool search_filter_ = false;     // tf follows the family's parameters
  bool search_observer_ = false;   // observer_hz follows tf
  bool search_bandwidth_ = false;  // bandwidth_j2 .. bandwidth_j6 close the space
  std::size_t first_option_ = 0;   // index of tf (or of the first after the family's)
};

// The start of a stage: `from` as a controller of family `to`, exactly (the same commands for
// every input, to rounding) -- pid -> scheduled (R = 1), pid or scheduled -> fuzzy-rules (T = 1),
// and any family to itself. Anything else (the paper's tables as a schedule, a schedule as a
// fixed PID) has no exact form: false with `error` saying so.
[[nodiscard]] bool convert(const ControllerSpec& from, Family to, ControllerSpec& out,
                           std::string& error);

// The default box of a family (fuzzy-rules: default TableOptions, all cells free).
[[nodiscard]] std::vector<SearchBox> default_box(Family family);

// `box`, made for per-tick gains at a units_tick_s tick (the default boxes: 0.05 s), moved to a
// loop sampled every tick_s: a loop as fast relative to its tick has a natural frequency
// omega ~ 1/tick_s, so the acceleration gains scale as kp ~ omega^2, ki ~ omega^3, kd ~ omega
// (per-tick kd and ki at units_tick_s are Kd / units_tick_s and Ki * units_tick_s of the
// continuous gains) and the error-rate scale as kec ~ 1/omega. Each such parameter's log10 box
// moves by its exponent times log10(units_tick_s / tick_s): kp, sp by 2, ki, si by 3, kd, sd by
// 1, kec by -1 (sp, si, sd: the fuzzy family's gain increments, in gain units), tf (a time, s)
// by -1; ke, the ratios and the table cells are dimensionless and stay. Equal ticks return the box unchanged.
[[nodiscard]] std::vector<SearchBox> box_for_tick(std::vector<SearchBox> box, Family family,
                                                  double units_tick_s, double tick_s);

}  // namespace fuzzypid::tune
