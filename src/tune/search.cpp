// The set-up every search shares (search.hpp).
#include "search.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "fuzzypid/controller/families.hpp"

namespace fuzzypid::tune::detail {

namespace {

Split split(const ExperimentOf& ex, const std::vector<sim::Condition>& conditions,
            std::size_t validation) {
  Split s;
  const std::size_t n = conditions.size() - validation;
  s.training_ex.assign(ex.begin(), ex.begin() + static_cast<std::ptrdiff_t>(n));
  s.validation_ex.assign(ex.begin() + static_cast<std::ptrdiff_t>(n), ex.end());
  s.training.assign(conditions.begin(), conditions.begin() + static_cast<std::ptrdiff_t>(n));
  s.validation.assign(conditions.begin() + static_cast<std::ptrdiff_t>(n), conditions.end());
  return s;
}

bool check_options(const Options& options, std::size_t conditions, std::string& error) {
  if (options.validation >= conditions) {
    error = "no training conditions (" + std::to_string(conditions) + " given, " +
            std::to_string(options.validation) + " held back for validation)";
    return false;
  }
  if (const std::string bad = controller::validate(options.base); !bad.empty()) {
    error = "base controller: " + bad;
    return false;
  }
  const Objective& o = options.objective;
  if (!std::isfinite(o.overshoot_bound_pct) || o.overshoot_bound_pct < 0 ||
      !std::isfinite(o.overshoot_weight) || o.overshoot_weight < 0 ||
      !std::isfinite(o.fault_cost) || o.fault_cost < 0 || !(o.divergence_rad > 0) ||
      !(o.chatter_weight >= 0.0 && std::isfinite(o.chatter_weight)) ||
      !(o.effort_weight >= 0.0 && std::isfinite(o.effort_weight)) ||
      !(o.chatter_limit_pct >= 0.0 && o.chatter_limit_pct <= 100.0)) {
    error =
        "objective weights must be finite and >= 0, the divergence bound > 0, the chatter limit "
        "within 0 .. 100 %";
    return false;
  }
  return true;
}

}  // namespace

bool prepare(const ExperimentOf& experiment, const std::vector<sim::Condition>& conditions,
             const Options& options, bool margins, bool validation_margins, Search& search,
             std::string& error) {
  if (!check_options(options, conditions.size(), error)) return false;
  search.data = split(experiment, conditions, options.validation);
  const Split& data = search.data;
  search.threads = std::max(1u, options.threads);
  if (search.threads > 1)
    search.arena = std::make_unique<tbb::task_arena>(static_cast<int>(search.threads));

  // The start, as a controller of the family; it also says which table cells are visited.
  // With --init the start must convert exactly; without one the base is only the template of
  // units, options and rule base (a fuzzy-rules table starts at ones).
  ControllerSpec& start_spec = search.start;
  if (options.init) {
    if (!convert(*options.init, options.family, start_spec, error)) return false;
  } else if (std::string ignored; !convert(options.base, options.family, start_spec, ignored)) {
    start_spec = options.base;
    start_spec.family = options.family;
    if (controller::family_traits(options.family).rule_table) {
      start_spec.supervisor.rule_table = controller::RuleTableSpec{};
      start_spec.supervisor.rule_file.clear();
      start_spec.supervisor.rule_model.reset();
    }
  }
  const ControllerSpec* start = &start_spec;
  VisitMap visit_map{};
  if (controller::family_traits(options.family).rule_table &&
      options.table.unvisited == Unvisited::Seed)
    visit_map = visits_in(search.arena.get(), data.training_ex, data.training, *start);
  search.space = ParameterSpace::create(options.family, *start, options.table, &visit_map, error,
                                        options.search_filter, options.search_bandwidth);
  if (!search.space) return false;

  // The default box moves with the training tick when all training conditions share one.
  std::vector<SearchBox>& box = search.box;
  box = search.space->box();
  if (start->units.form == controller::PidForm::PerTick && !data.training_ex.empty()) {
    const double tick = data.training_ex.front()->options().tick_s;
    bool one_tick = true;
    for (const sim::Experiment* e : data.training_ex)
      one_tick = one_tick && e->options().tick_s == tick;
    if (one_tick) box = box_for_tick(box, options.family, start->units.tick_s, tick);
  }
  for (const SearchBox& b : options.box) {
    const auto it =
        std::find_if(box.begin(), box.end(), [&](const SearchBox& d) { return d.name == b.name; });
    if (it == box.end()) {
      error = "the " + std::string(controller::to_string(options.family)) +
              " family has no parameter '" + b.name + "'";
      return false;
    }
    *it = b;
  }
  search.training = ConditionSet{data.training_ex, data.training, std::nullopt, 0.0};
  search.validation = ConditionSet{data.validation_ex, data.validation, std::nullopt, 0.0};
  if (margins) {
    for (ConditionSet* set : {&search.training, &search.validation}) {
      if (set->conditions.empty() || (set == &search.validation && !validation_margins)) continue;
      set->ranges = sim::plant_ranges(set->conditions, set->experiments, error);
      if (!set->ranges) return false;
      set->delay_s = sim::largest_delay_s(set->conditions);
    }
  }
  return true;
}

}  // namespace fuzzypid::tune::detail
