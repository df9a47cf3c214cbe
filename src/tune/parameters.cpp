#include "fuzzypid/tune/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "fuzzypid/controller/families.hpp"

namespace fuzzypid::tune {

namespace {

constexpr std::size_t kSets = RuleTableSpec::kSets;
constexpr std::size_t kMid = kSets / 2;
const char* const kGainNames[3] = {"kp", "ki", "kd"};

using controller::family_traits;
using controller::OutputScale;

// log10 bounds, acceleration units, per tick at 0.05 s (docs/tuning.md explains each).
constexpr double kPidBox[3][2] = {{-1.0, 4.0}, {-6.0, 1.0}, {0.0, 4.0}};
constexpr double kScaleBox[2][2] = {{-1.0, 4.0}, {-3.0, 2.0}};               // ke, kec
constexpr double kRatioBox[2] = {-2.0, 2.0};                                 // rp, ri, rd
constexpr double kOutputBox[3][2] = {{0.0, 6.0}, {-4.0, 3.0}, {-2.0, 5.0}};  // sp, si, sd
// The derivative filter's time constant, s: 1 ms (no filter to speak of at a 50 ms tick) .. 1 s.
constexpr double kFilterBox[2] = {-3.0, 0.0};
constexpr double kObserverBox[2] = {-1.0, 1.0};
// A joint's bandwidth relative to joint 1's: a tenth .. ten times.
constexpr double kBandwidthBox[2] = {-1.0, 1.0};
// An inner center as a fraction of the next one out: 0.1 .. 0.955.
constexpr double kFractionBox[2] = {-1.0, -0.02};

std::vector<SearchBox> fixed_box(Family family) {
  std::vector<SearchBox> box;
  for (std::size_t k = 0; k < 3; ++k)
    box.push_back({kGainNames[k], kPidBox[k][0], kPidBox[k][1]});
  const controller::FamilyTraits& traits = family_traits(family);
  if (!traits.supervised()) return box;
  box.push_back({"ke", kScaleBox[0][0], kScaleBox[0][1]});
  box.push_back({"kec", kScaleBox[1][0], kScaleBox[1][1]});
  const bool ratios = traits.output_scale == OutputScale::Ratios;
  const char* names[2][3] = {{"sp", "si", "sd"}, {"rp", "ri", "rd"}};
  for (std::size_t k = 0; k < 3; ++k)
    box.push_back({names[ratios ? 1 : 0][k], ratios ? kRatioBox[0] : kOutputBox[k][0],
                   ratios ? kRatioBox[1] : kOutputBox[k][1]});
  return box;
}

std::size_t mirror(std::size_t i) {
  return kSets - 1 - i;
}

// The total log10 gain ratio at node (i, j): the schedule's ramp there times the table.
double node_log_ratio(const ControllerSpec& s, std::size_t g, std::size_t i, std::size_t j) {
  const RuleTableSpec& t = s.supervisor.rule_table;
  const double w =
      std::min(1.0, std::fabs(t.error_centers[i]) + std::fabs(t.error_rate_centers[j]));
  return std::log10((1.0 + (s.supervisor.output_scale[g] - 1.0) * w) * t.ratio[g][i][j]);
}

}  // namespace

std::vector<SearchBox> default_box(Family family) {
  if (!family_traits(family).rule_table) return fixed_box(family);
  std::string error;
  ControllerSpec start;
  (void)convert(controller::paper_pid(), family, start, error);
  TableOptions o;
  o.unvisited = Unvisited::Free;
  return ParameterSpace::create(family, start, o, nullptr, error)->box();
}

std::vector<SearchBox> box_for_tick(std::vector<SearchBox> box, Family family, double units_tick_s,
                                    double tick_s) {
  if (!(units_tick_s > 0.0) || !(tick_s > 0.0) || units_tick_s == tick_s) return box;
  const double decades = std::log10(units_tick_s / tick_s);
  const bool scales = family_traits(family).output_scale == OutputScale::Scales;
  for (SearchBox& b : box) {
    double exponent = 0.0;
    if (b.name == "kp" || (scales && b.name == "sp")) exponent = 2.0;
    if (b.name == "ki" || (scales && b.name == "si")) exponent = 3.0;
    if (b.name == "kd" || (scales && b.name == "sd")) exponent = 1.0;
    if (b.name == "kec" || b.name == kFilterParameter) exponent = -1.0;
    if (b.name == kObserverParameter) exponent = 1.0;
    b.log10_min += exponent * decades;
    b.log10_max += exponent * decades;
  }
  return box;
}

std::optional<ParameterSpace> ParameterSpace::create(Family family, const ControllerSpec& start,
                                                     const TableOptions& options,
                                                     const VisitMap* visits, std::string& error,
                                                     bool search_filter, bool search_bandwidth) {
  ParameterSpace p;
  p.search_filter_ = search_filter;
  p.search_bandwidth_ = search_bandwidth;
  p.search_observer_ = search_filter && start.pid.derivative == pid::DerivativeSource::Observer;
  p.family_ = family;
  p.start_ = start;
  p.start_.family = family;
  p.options_ = options;
  p.box_ = fixed_box(family);
  if (search_bandwidth && start.bandwidth_scale[0] != 1.0) {
    error =
        "searching the bandwidth scales starts from a controller whose joint 1 has scale 1 "
        "(the gains are joint 1's; the other joints' scales are relative to it)";
    return std::nullopt;
  }
  const auto with_filter = [&p]() -> std::optional<ParameterSpace> {
    p.first_option_ = p.box_.size();
    if (p.search_filter_) p.box_.push_back({kFilterParameter, kFilterBox[0], kFilterBox[1]});
    if (p.search_observer_)
      p.box_.push_back({kObserverParameter, kObserverBox[0], kObserverBox[1]});
    if (p.search_bandwidth_) {
      for (std::size_t j = 1; j < p.start_.bandwidth_scale.size(); ++j)
        p.box_.push_back({kBandwidthParameterPrefix + std::to_string(j + 1), kBandwidthBox[0],
                          kBandwidthBox[1]});
    }
    return p;
  };
  if (!family_traits(family).rule_table) return with_filter();

  if (start.family != family) {
    error = std::string("the ") + controller::to_string(family) + " family starts from a " +
            controller::to_string(family) + " controller (tune::convert)";
    return std::nullopt;
  }
  if (!(options.cell_log10 > 0.0) || !std::isfinite(options.cell_log10) ||
      !(options.smoothness >= 0.0) || !std::isfinite(options.smoothness) ||
      !(options.monotone >= 0.0) || !std::isfinite(options.monotone) ||
      !(options.visit_threshold >= 0.0) || !(options.visit_threshold < 1.0)) {
    error =
        "table options: cell_log10 > 0, smoothness and monotone >= 0 and finite, "
        "0 <= visit_threshold < 1";
    return std::nullopt;
  }
  if (options.unvisited == Unvisited::Seed && visits == nullptr) {
    error = "holding unvisited cells needs the visits of the start's training runs";
    return std::nullopt;
  }
  if (options.partition) {
    for (const char* axis : {"e", "ec"})
      for (const char* f : {"_f2", "_f1"})
        p.box_.push_back({std::string(axis) + f, kFractionBox[0], kFractionBox[1]});
  }
  p.first_cell_ = p.box_.size();

  // Classes of cells by symmetry; a class is searched when any of its nodes is visited.
  const auto key = [&](std::size_t i, std::size_t j) -> std::array<std::size_t, 2> {
    switch (options.symmetry) {
      case Symmetry::Even:
        return {i < kMid ? mirror(i) : i, j < kMid ? mirror(j) : j};
      case Symmetry::Odd:
        if (i * kSets + j > mirror(i) * kSets + mirror(j)) return {mirror(i), mirror(j)};
        return {i, j};
      case Symmetry::None:
        break;
    }
    return {i, j};
  };
  for (std::size_t g = 0; g < 3; ++g) {
    std::map<std::array<std::size_t, 2>, CellClass> classes;
    for (std::size_t i = 0; i < kSets; ++i)
      for (std::size_t j = 0; j < kSets; ++j) {
        if (options.symmetry == Symmetry::Odd && i == kMid && j == kMid) continue;  // T = 1
        const auto k = key(i, j);
        CellClass& c = classes[k];
        c.gain = g;
        c.cells.push_back({i, j});
        c.sign.push_back(
            options.symmetry == Symmetry::Odd && k != std::array<std::size_t, 2>{i, j} ? -1 : 1);
      }
    for (auto& [k, c] : classes) {
      bool visited = options.unvisited == Unvisited::Free;
      for (const auto& cell : c.cells)
        if (visits != nullptr && (*visits)[cell[0]][cell[1]] > options.visit_threshold)
          visited = true;
      if (!visited) {
        p.held_cells_ += c.cells.size();
        continue;
      }
      const double v = std::log10(start.supervisor.rule_table.ratio[g][k[0]][k[1]]);
      p.box_.push_back({std::string(kGainNames[g]) + "[" + std::to_string(k[0]) + "," +
                            std::to_string(k[1]) + "]",
                        std::min(-options.cell_log10, v), std::max(options.cell_log10, v)});
      p.classes_.push_back(c);
    }
  }
  if (options.symmetry == Symmetry::Odd) p.held_cells_ += 3;  // the center cells
  return with_filter();
}

ControllerSpec ParameterSpace::to_spec(const std::vector<double>& x) const {
  ControllerSpec s = start_;
  const auto p = [&x](std::size_t k) { return std::pow(10.0, x[k]); };
  s.gains = {p(0), p(1), p(2)};
  std::size_t k = first_option_;
  if (search_filter_) s.pid.derivative_filter_s = p(k++);
  if (search_observer_) s.pid.observer_bandwidth_hz = p(k++);
  if (search_bandwidth_) {
    s.bandwidth_scale[0] = 1.0;
    for (std::size_t j = 1; j < s.bandwidth_scale.size(); ++j)
      s.bandwidth_scale[j] = p(k++);
  }
  const controller::FamilyTraits& traits = family_traits(family_);
  if (traits.supervised()) {
    s.supervisor.error_scale = p(3);
    s.supervisor.error_rate_scale = p(4);
    s.supervisor.output_scale = {p(5), p(6), p(7)};
  }
  if (traits.output_scale == OutputScale::Ratios)
    s.supervisor.gain_update = supervisor::GainUpdate::Absolute;
  if (!traits.rule_base) {  // a rule file only means something to a family with a rule base
    s.supervisor.rule_file.clear();
    s.supervisor.rule_model.reset();
  }
  if (!traits.rule_table) return s;
  RuleTableSpec& t = s.supervisor.rule_table;
  if (options_.partition) {
    for (std::size_t axis = 0; axis < 2; ++axis) {
      RuleTableSpec::Centers& c = axis == 0 ? t.error_centers : t.error_rate_centers;
      const double f2 = p(8 + 2 * axis);
      const double f1 = p(9 + 2 * axis);
      c[kMid + 2] = f2 * c[kMid + 3];
      c[kMid + 1] = f1 * c[kMid + 2];
      c[kMid - 2] = -c[kMid + 2];
      c[kMid - 1] = -c[kMid + 1];
    }
  }
  for (std::size_t k = 0; k < classes_.size(); ++k) {
    const CellClass& c = classes_[k];
    for (std::size_t n = 0; n < c.cells.size(); ++n)
      t.ratio[c.gain][c.cells[n][0]][c.cells[n][1]] =
          std::pow(10.0, c.sign[n] * x[first_cell_ + k]);
  }
  return s;
}

std::vector<double> ParameterSpace::from_spec(const ControllerSpec& s) const {
  std::vector<double> x = from_spec_without_filter(s);
  if (search_filter_) x.push_back(std::log10(std::fmax(s.pid.derivative_filter_s, 1e-3)));
  if (search_observer_) x.push_back(std::log10(s.pid.observer_bandwidth_hz));
  if (search_bandwidth_)
    for (std::size_t j = 1; j < s.bandwidth_scale.size(); ++j)
      x.push_back(std::clamp(std::log10(s.bandwidth_scale[j]), kBandwidthBox[0], kBandwidthBox[1]));
  return x;
}

std::vector<double> ParameterSpace::from_spec_without_filter(const ControllerSpec& s) const {
  std::vector<double> x = {std::log10(s.gains.kp), std::log10(s.gains.ki), std::log10(s.gains.kd)};
  const controller::FamilyTraits& traits = family_traits(family_);
  if (traits.supervised()) {
    x.push_back(std::log10(s.supervisor.error_scale));
    x.push_back(std::log10(s.supervisor.error_rate_scale));
    for (double v : s.supervisor.output_scale)
      x.push_back(std::log10(v));
  }
  if (!traits.rule_table) return x;
  const RuleTableSpec& t = s.supervisor.rule_table;
  if (options_.partition) {
    for (const auto* c : {&t.error_centers, &t.error_rate_centers}) {
      x.push_back(std::log10((*c)[kMid + 2] / (*c)[kMid + 3]));
      x.push_back(std::log10((*c)[kMid + 1] / (*c)[kMid + 2]));
    }
  }
  for (const CellClass& c : classes_)
    x.push_back(c.sign[0] * std::log10(t.ratio[c.gain][c.cells[0][0]][c.cells[0][1]]));
  return x;
}

double ParameterSpace::penalty(const ControllerSpec& s) const {
  if (!family_traits(family_).rule_table) return 0.0;
  double cost = 0.0;
  const auto& ratio = s.supervisor.rule_table.ratio;
  for (std::size_t g = 0; g < 3; ++g) {
    if (options_.smoothness > 0.0) {
      double sum = 0.0;
      for (std::size_t i = 0; i < kSets; ++i)
        for (std::size_t j = 0; j < kSets; ++j) {
          const double v = std::log10(ratio[g][i][j]);
          if (i + 1 < kSets) sum += std::pow(std::log10(ratio[g][i + 1][j]) - v, 2);
          if (j + 1 < kSets) sum += std::pow(std::log10(ratio[g][i][j + 1]) - v, 2);
        }
      cost += options_.smoothness * sum;
    }
    if (options_.monotone > 0.0) {
      // Outwards from the center along rows and columns: the total ratio moves the way the
      // schedule's does (R >= 1: never down; R < 1: never up).
      const double direction = s.supervisor.output_scale[g] >= 1.0 ? 1.0 : -1.0;
      double sum = 0.0;
      for (std::size_t a = 0; a < kSets; ++a)
        for (std::size_t k = kMid; k + 1 < kSets; ++k)
          for (int side : {1, -1}) {
            const std::size_t from = side > 0 ? k : mirror(k);
            const std::size_t to = side > 0 ? k + 1 : mirror(k + 1);
            const double along_x = node_log_ratio(s, g, to, a) - node_log_ratio(s, g, from, a);
            const double along_y = node_log_ratio(s, g, a, to) - node_log_ratio(s, g, a, from);
            sum += std::pow(std::max(0.0, -direction * along_x), 2);
            sum += std::pow(std::max(0.0, -direction * along_y), 2);
          }
      cost += options_.monotone * sum;
    }
  }
  return cost;
}

TableRegulariser ParameterSpace::record() const {
  TableRegulariser r;
  r.symmetry = name_of(kSymmetryNames, options_.symmetry);
  r.partition = options_.partition;
  r.smoothness = options_.smoothness;
  r.monotone = options_.monotone;
  r.unvisited = name_of(kUnvisitedNames, options_.unvisited);
  r.visit_threshold = options_.visit_threshold;
  r.frozen_cells = held_cells_;
  r.cell_log10 = options_.cell_log10;
  return r;
}

bool convert(const ControllerSpec& from, Family to, ControllerSpec& out, std::string& error) {
  // Exact: a family into itself; a fixed PID into a schedule (R = 1 moves nothing); a schedule
  // into a schedule refined by a rule table (T = 1).
  const controller::FamilyTraits& a = family_traits(from.family);
  const controller::FamilyTraits& b = family_traits(to);
  const bool pid = !a.supervised();
  const bool exact = from.family == to || (b.output_scale == OutputScale::Ratios && pid) ||
                     (b.output_scale == OutputScale::Ratios && b.rule_table &&
                      a.output_scale == OutputScale::Ratios && !a.rule_table && !a.rule_base);
  if (!exact) {
    error = std::string("a ") + a.name + " controller has no exact " + b.name +
            " form (exact: pid -> scheduled -> fuzzy-rules)";
    return false;
  }
  out = from;
  if (from.family == to) return true;
  out.family = to;
  // pid -> scheduled: R = 1 moves nothing, whatever Ke and Kec. pid or scheduled -> fuzzy-rules:
  // the schedule's Ke, Kec and R with T = 1, the schedule itself.
  controller::SupervisorSpec s;
  if (!pid) {
    s.error_scale = from.supervisor.error_scale;
    s.error_rate_scale = from.supervisor.error_rate_scale;
    s.output_scale = from.supervisor.output_scale;
  }
  out.supervisor = s;
  return true;
}

}  // namespace fuzzypid::tune
