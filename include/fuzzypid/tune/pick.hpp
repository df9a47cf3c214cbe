// Choosing one controller of a front by a stated rule, and measuring fronts by their hypervolume
// (docs/tuning.md, "Picking a point"). A front is the folder `fuzzypid tune --objectives ...
// --front-out DIR` writes; these read its front.csv.
//
// Library fuzzypid::tune (offline, allocates, never in a control loop).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace fuzzypid::tune {

// DIR/front.csv: per point its file (in DIR) and its objectives, all minimised.
struct FrontTable {
  std::vector<std::string> objectives;          // names, in column order
  std::vector<std::string> files;               // per point, relative to the folder
  std::vector<std::vector<double>> training;    // per point
  std::vector<std::vector<double>> validation;  // per point; empty without validation columns
};

// The table of `dir`/front.csv; nullopt with `error` naming the file and line when it is missing
// or malformed (a header other than point,file,<objectives>[,validation_<objectives>], an unknown
// or repeated objective, a row of the wrong length, a point number out of order, a number that is
// not finite, a file that is not a plain name in the folder, no row).
[[nodiscard]] std::optional<FrontTable> read_front(const std::string& dir, std::string& error);

// How to choose:
//   knee       each objective scaled to [0, 1] over the front (min .. max; one that is the same
//              for every point counts 0), the point nearest the ideal point (all 0) in Euclidean
//              distance;
//   min:OBJ    the point with the smallest OBJ;
//   max:OBJ=X  of the points with OBJ <= X, the one with the smallest first objective of the
//              front other than OBJ.
// Ties go to the lowest point number.
struct PickRule {
  enum class Kind { Knee, Min, Max } kind = Kind::Knee;
  std::string objective;  // Min, Max
  double cap = 0.0;       // Max
};

// "knee", "min:itae", "max:effort=0.01"; nullopt with `error` on anything else.
[[nodiscard]] std::optional<PickRule> parse_pick_rule(const std::string& text, std::string& error);

// The index of the point `rule` chooses among `points` (objective vectors named `objectives`);
// nullopt with `error` when the rule names an objective the front lacks or no point is within a
// cap (naming the smallest value there is).
[[nodiscard]] std::optional<std::size_t> pick(const std::vector<std::string>& objectives,
                                              const std::vector<std::vector<double>>& points,
                                              const PickRule& rule, std::string& error);

// The volume dominated by `points` and bounded by `reference` (minimisation), by pagmo2's
// hypervolume algorithms. Points that do not strictly dominate the reference add nothing and are
// left out. Every vector has the reference's length.
[[nodiscard]] double hypervolume(const std::vector<std::vector<double>>& points,
                                 const std::vector<double>& reference);

// One reference point for comparing several fronts: per objective the largest value over all of
// them plus 10 % of its range over all of them (1 when the range is 0), so that every point,
// extremes included, adds volume.
[[nodiscard]] std::vector<double> common_reference(
    const std::vector<std::vector<std::vector<double>>>& fronts);

}  // namespace fuzzypid::tune
