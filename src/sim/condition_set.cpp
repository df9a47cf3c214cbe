#include "fuzzypid/sim/condition_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "fuzzypid/sim/random.hpp"
#include "fuzzypid_support/toml_reader.hpp"

namespace fuzzypid::sim {

namespace {

using support::ReadError;
using support::TableReader;

// A file named in the condition file: relative names resolve against the file's folder.
std::string resolve(const std::string& name, const std::string& condition_file) {
  namespace fs = std::filesystem;
  if (name.empty() || fs::path(name).is_absolute()) return name;
  return (fs::path(condition_file).parent_path() / name).lexically_normal().string();
}

// The plant keys as written: a key left out of a condition takes its set's value, and one left out
// of both the robot's default (default_dynamics, default_gravity), decided once the robot is known.
struct PlantKeys {
  std::optional<robot::PlantCoupling> dynamics;
  std::optional<bool> gravity;

  void read(TableReader& r) {
    if (r.has("dynamics"))
      dynamics = r.choice("dynamics", kDynamicsNames, robot::PlantCoupling::Decoupled);
    if (r.has("gravity")) gravity = r.flag("gravity", false);
  }
  void apply(Condition& c) const {
    c.dynamics = dynamics.value_or(default_dynamics(c.robot));
    c.gravity = gravity.value_or(default_gravity(c.robot, c.dynamics));
  }
};

// Keys a Monte-Carlo table draws ([min, max]) instead of setting (read_monte_carlo).
using DrawnKeys = std::set<std::string>;

bool drawn(const DrawnKeys* keys, const char* key) {
  return keys != nullptr && keys->count(key) > 0;
}

// A key of JointEffects in the range's units, stored times `to_si`; 0 (range.zero) or within the
// range.
void read_effect(TableReader& r, const FieldRange& range, double to_si, double& target,
                 const DrawnKeys* skip = nullptr) {
  if (!r.has(range.key) || drawn(skip, range.key)) return;
  const double v = r.number(range.key);
  if (v != 0.0 && !range.contains(v)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "'%s' must be 0 (%s) or within %g .. %g", range.key, range.zero,
                  range.lo, range.hi);
    r.fail(*r.raw().get(range.key), buf);
  }
  target = v * to_si;
}

// A per-joint key of JointEffects: one number for every joint or six, each within the range.
void read_joint_effect(TableReader& r, const FieldRange& range, robot::JointVector& target,
                       const DrawnKeys* skip = nullptr) {
  if (!r.has(range.key) || drawn(skip, range.key)) return;
  const toml::node& node = *r.raw().get(range.key);
  const auto check = [&](const toml::node& at, double v) {
    if (!range.contains(v)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "'%s' values must be within %g .. %g", range.key, range.lo,
                    range.hi);
      r.fail(at, buf);
    }
    return v;
  };
  if (const toml::array* a = node.as_array()) {
    (void)r.array(range.key, true);
    if (a->size() != robot::kNumJoints)
      r.fail(*a, std::string("'") + range.key + "' must be one number or list 6, found " +
                     std::to_string(a->size()));
    for (std::size_t i = 0; i < robot::kNumJoints; ++i)
      target[i] = check(*a->get(i), support::number_of(r, *a->get(i),
                                                       std::string("'") + range.key + "[" +
                                                           std::to_string(i) + "]'"));
    return;
  }
  target.fill(check(node, r.number(range.key)));
}

// The keys of what real joints have (JointEffects).
void read_effects(TableReader& r, JointEffects& e, const DrawnKeys* skip = nullptr) {
  read_effect(r, kPlantStepMsRange, 1e-3, e.plant_step_s);
  read_effect(r, kDelayMsRange, 1e-3, e.delay_s, skip);
  read_effect(r, kTorqueBandwidthRange, 1.0, e.torque_bandwidth_hz, skip);
  if (r.has(kEncoderCountsRange.key) && !drawn(skip, kEncoderCountsRange.key)) {
    const std::uint64_t n = r.count(kEncoderCountsRange.key);
    if (n != 0 && !kEncoderCountsRange.contains(static_cast<double>(n)))
      r.fail(*r.raw().get(kEncoderCountsRange.key), std::string("'encoder_counts' must be 0 (") +
                                                        kEncoderCountsRange.zero + ") or within " +
                                                        kEncoderCountsRange.text());
    e.encoder_counts = n;
  }
  read_joint_effect(r, kCoulombRange, e.coulomb_nm, skip);
  read_joint_effect(r, kStribeckRange, e.stribeck_nm, skip);
  read_effect(r, kStribeckVelocityRange, 1.0, e.stribeck_velocity_rad_s, skip);
  read_effect(r, kCoulombSmoothingRange, 1.0, e.coulomb_smoothing_rad_s, skip);
  read_joint_effect(r, kJointResonanceRange, e.joint_resonance_hz, skip);
  read_effect(r, kJointDampingRatioRange, 1.0, e.joint_damping_ratio, skip);
  read_effect(r, kBacklashRange, 1.0, e.backlash_rad, skip);
}

// The robot, path and plant keys (set tables and conditions alike).
void read_robot(TableReader& r, Condition& c, PlantKeys& plant, const DrawnKeys* skip = nullptr) {
  RobotSetup& s = c.robot;
  if (r.has("urdf")) s.urdf = resolve(r.text("urdf"), r.file());
  s.base_link = r.text("base_link", s.base_link);
  s.tip_link = r.text("tip_link", s.tip_link);
  if (r.has("path")) s.path = resolve(r.text("path"), r.file());
  if (r.has("tick_ms")) {
    const double ms = r.number("tick_ms");
    if (!kTickMsRange.contains(ms))
      r.fail(*r.raw().get("tick_ms"), "'tick_ms' must be within " + kTickMsRange.text());
    s.tick_s = ms * 1e-3;
  }
  if (r.has("armature")) {
    const toml::array* a = r.array("armature", true);
    if (a->size() != robot::kNumJoints)
      r.fail(*a, "'armature' must list 6 values (kg·m²), found " + std::to_string(a->size()));
    robot::JointVector v{};
    for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
      v[i] = support::number_of(r, *a->get(i), "'armature[" + std::to_string(i) + "]'");
      if (!kArmatureRange.contains(v[i]))
        r.fail(*a->get(i), "'armature' values must be within " + kArmatureRange.text() + " kg·m²");
    }
    s.armature_kgm2 = v;
  }
  if (r.has("ik_seed")) {
    const toml::array* a = r.array("ik_seed", true);
    if (a->size() != robot::kNumJoints)
      r.fail(*a, "'ik_seed' must list 6 joint angles (rad), found " + std::to_string(a->size()));
    robot::JointVector v{};
    for (std::size_t i = 0; i < robot::kNumJoints; ++i)
      v[i] = support::number_of(r, *a->get(i), "'ik_seed[" + std::to_string(i) + "]'");
    s.ik_seed_rad = v;
  }
  if (r.has("payload_kg") && !drawn(skip, "payload_kg")) {
    c.payload_kg = r.number("payload_kg");
    if (!kPayloadKgRange.contains(c.payload_kg))
      r.fail(*r.raw().get("payload_kg"), "'payload_kg' must be within " + kPayloadKgRange.text());
  }
  plant.read(r);
  read_effects(r, c.effects, skip);
}

// The fields of a condition common to listed conditions and Monte-Carlo sets.
void read_fields(TableReader& r, Condition& c) {
  c.payload_scale = r.number("payload_scale", c.payload_scale);
  c.friction_per_s = r.number("friction", c.friction_per_s);
  c.torque_limit_rad_s2 = r.number("torque_limit", c.torque_limit_rad_s2);
  c.contact_rad_s2 = r.number("contact", c.contact_rad_s2);
  if (r.has("noise")) {
    const toml::array* a = r.array("noise", true);
    if (a->size() != 2) r.fail(*a, "'noise' must be [SIGMA_Q, SIGMA_QD]");
    c.noise_position_rad = support::number_of(r, *a->get(0), "'noise[0]'");
    c.noise_velocity_rad_s = support::number_of(r, *a->get(1), "'noise[1]'");
  }
  c.seed = r.count("seed", c.seed);
  c.reverse = r.flag("reverse", c.reverse);
  c.initial_error_rad = r.number("initial_error", c.initial_error_rad);
}

Condition read_condition(const toml::node& node, const std::string& file, const Condition& defaults,
                         PlantKeys plant) {
  const toml::table* t = node.as_table();
  if (t == nullptr)
    throw ReadError{fuzzypid::FileError{file, static_cast<int>(node.source().begin.line),
                                        static_cast<int>(node.source().begin.column),
                                        "a condition must be a table"}};
  TableReader r(*t, file);
  Condition c = defaults;
  const std::string base = r.text("scenario", std::string());
  if (!base.empty()) {
    const Condition* s = find_scenario(base);
    if (s == nullptr) r.fail(*t->get("scenario"), "unknown scenario '" + base + "'");
    c = *s;
    c.robot = defaults.robot;
    c.payload_kg = defaults.payload_kg;
    c.effects = defaults.effects;
  }
  c.name = r.text("name");
  if (c.name.empty() || c.name.find_first_of(",\n\r\"") != std::string::npos)
    r.fail(*t->get("name"), "a condition name must be non-empty, without commas or quotes");
  c.description = r.text("description", c.description);
  read_fields(r, c);
  read_robot(r, c, plant);
  plant.apply(c);
  r.finish();
  if (const std::string bad = c.validate(); !bad.empty())
    r.fail_here("condition " + c.name + ": " + bad);
  return c;
}

std::pair<double, double> range(TableReader& r, const char* key, double lo, double hi) {
  if (!r.has(key)) {
    (void)r.number(key, 0.0);  // marks the key as known
    return {lo, hi};
  }
  const toml::array* a = r.array(key, true);
  if (a->size() != 2) r.fail(*a, std::string("'") + key + "' must be [min, max]");
  const double mn = support::number_of(r, *a->get(0), std::string("'") + key + "[0]'");
  const double mx = support::number_of(r, *a->get(1), std::string("'") + key + "[1]'");
  if (mx < mn) r.fail(*a, std::string("'") + key + "' is reversed");
  return {mn, mx};
}

// 0 .. n-1 in a random order (Fisher-Yates), from `rng`.
std::vector<std::uint64_t> shuffled(std::uint64_t n, Random& rng) {
  std::vector<std::uint64_t> order(n);
  for (std::uint64_t i = 0; i < n; ++i)
    order[i] = i;
  for (std::uint64_t i = n; i > 1; --i) {
    const auto j = static_cast<std::uint64_t>(rng.uniform() * static_cast<double>(i));
    std::swap(order[i - 1], order[std::min(j, i - 1)]);
  }
  return order;
}

void read_monte_carlo(TableReader& r, const std::string& set_name, const Condition& defaults,
                      PlantKeys plant, ConditionSet& set) {
  const std::uint64_t count = r.count("count");
  if (count == 0 || count > 10000) r.fail(*r.raw().get("count"), "'count' must be 1..10000");
  const std::uint64_t seed = r.count("seed");
  const auto payload = range(r, "payload_scale", 1.0, 1.0);
  if (!(payload.first > 0.0)) r.fail(*r.raw().get("payload_scale"), "payload_scale must be > 0");
  const auto friction = range(r, "friction", 0.0, 0.0);
  const auto initial = range(r, "initial_error", 0.05, 0.05);
  const Sampling sampling = r.choice("sampling", kSamplingNames, Sampling::Random);
  // payload_kg and the keys of what real joints have: a number sets them, [min, max] draws them
  // uniformly (one value for every joint; encoder_counts rounded to a whole count).
  // coulomb_smoothing, a numerical setting, is not drawn and not on this list: one draw per
  // listed key and condition, so a new entry would move every later draw of every file.
  struct Draw {
    const char* key;
    double lo = 0.0, hi = 0.0;
    bool given = false;
  };
  std::array<Draw, 11> draws = {{{"payload_kg"},
                                 {kDelayMsRange.key},
                                 {kTorqueBandwidthRange.key},
                                 {kEncoderCountsRange.key},
                                 {kCoulombRange.key},
                                 {kStribeckRange.key},
                                 {kStribeckVelocityRange.key},
                                 {kJointResonanceRange.key},
                                 {kJointDampingRatioRange.key},
                                 {kPlantStepMsRange.key},
                                 {kBacklashRange.key}}};
  DrawnKeys ranged;
  for (Draw& d : draws) {
    const toml::node* node = r.raw().get(d.key);
    const toml::array* a = node != nullptr ? node->as_array() : nullptr;
    if (a == nullptr || a->size() != 2) continue;
    if (std::string(d.key) == kPlantStepMsRange.key)
      r.fail(*a, "'plant_step_ms' is a numerical setting: give one value, not a range");
    std::tie(d.lo, d.hi) = range(r, d.key, 0.0, 0.0);
    d.given = true;
    ranged.insert(d.key);
  }
  Condition base = defaults;
  read_robot(r, base, plant, &ranged);
  plant.apply(base);
  base.reverse = r.flag("reverse", false);
  base.contact_rad_s2 = r.number("contact", 0.0);
  base.torque_limit_rad_s2 = r.number("torque_limit", 0.0);
  r.finish();
  Random rng(seed);
  // The draws above come from their own stream, one per key and condition whatever is given, so
  // that adding a range changes no other draw (and the three below stay as they always were).
  Random effects_rng(seed ^ 0x9E3779B97F4A7C15ull);
  // Latin hypercube: per key (the three above, then the list) a seeded permutation of the count
  // strata; draw k of a key lies in stratum strata[key][k], at the place its stream gives it.
  constexpr std::size_t kKeys = 3 + std::tuple_size_v<decltype(draws)>;
  std::array<std::vector<std::uint64_t>, kKeys> strata;
  if (sampling == Sampling::LatinHypercube) {
    Random order_rng(seed ^ 0xD1B54A32D192ED03ull);
    for (auto& order : strata)
      order = shuffled(count, order_rng);
  }
  // u in [0, 1) of draw k of key `key`, moved into its stratum when stratified.
  const auto place = [&](std::size_t key, std::uint64_t k, double u) {
    if (sampling == Sampling::Random) return u;
    return (static_cast<double>(strata[key][k]) + u) / static_cast<double>(count);
  };
  for (std::uint64_t k = 0; k < count; ++k) {
    Condition c = base;
    char name[64];
    std::snprintf(name, sizeof name, "%s-mc%03llu", set_name.c_str(),
                  static_cast<unsigned long long>(k) + 1);
    c.name = name;
    // Three draws per condition, always in this order, whatever the ranges.
    const double u_payload = place(0, k, rng.uniform());
    const double u_friction = place(1, k, rng.uniform());
    const double u_initial = place(2, k, rng.uniform());
    c.payload_scale = payload.first * std::pow(payload.second / payload.first, u_payload);
    c.friction_per_s = friction.first + (friction.second - friction.first) * u_friction;
    c.initial_error_rad = initial.first + (initial.second - initial.first) * u_initial;
    for (std::size_t i = 0; i < draws.size(); ++i) {
      const Draw& d = draws[i];
      const double u = place(3 + i, k, effects_rng.uniform());
      if (!d.given) continue;
      const double v = d.lo + (d.hi - d.lo) * u;
      JointEffects& e = c.effects;
      const std::string key = d.key;
      if (key == "payload_kg")
        c.payload_kg = v;
      else if (key == kDelayMsRange.key)
        e.delay_s = v * 1e-3;
      else if (key == kTorqueBandwidthRange.key)
        e.torque_bandwidth_hz = v;
      else if (key == kEncoderCountsRange.key)
        e.encoder_counts = static_cast<std::uint64_t>(std::llround(std::fmax(v, 0.0)));
      else if (key == kCoulombRange.key)
        e.coulomb_nm.fill(v);
      else if (key == kStribeckRange.key)
        e.stribeck_nm.fill(v);
      else if (key == kStribeckVelocityRange.key)
        e.stribeck_velocity_rad_s = v;
      else if (key == kJointResonanceRange.key)
        e.joint_resonance_hz.fill(v);
      else if (key == kJointDampingRatioRange.key)
        e.joint_damping_ratio = v;
    }
    c.description = "Monte-Carlo draw";
    if (const std::string bad = c.validate(); !bad.empty()) r.fail_here(c.name + ": " + bad);
    set.conditions.push_back(c);
  }
}

}  // namespace

const ConditionSet* ConditionFile::find(const std::string& name) const {
  for (const auto& s : sets)
    if (s.name == name) return &s;
  return nullptr;
}

std::string ConditionFile::set_names() const {
  std::string out;
  for (const auto& s : sets)
    out += (out.empty() ? "" : ", ") + s.name;
  return out;
}

bool parse_conditions(std::string_view text, const std::string& source, ConditionFile& file,
                      fuzzypid::FileError& error) {
  try {
    const toml::table root = support::parse_toml(text, source);
    TableReader r(root, source);
    auto sets = r.table("sets", true);
    ConditionFile out;
    out.path = source;
    // Every output (conditions.csv, metrics.csv, trajectory.csv) keys its rows by condition name,
    // so a name is unique across the file's sets, not only within one.
    std::map<std::string, std::string> set_of;
    for (auto&& [key, node] : sets->raw()) {
      const std::string name(key.str());
      auto st = sets->table(name, true);
      ConditionSet set;
      set.name = name;
      set.description = st->text("description", std::string());
      Condition defaults;
      PlantKeys plant;
      read_robot(*st, defaults, plant);
      const auto duplicate = [&](const std::string& c) {
        const auto [it, fresh] = set_of.emplace(c, name);
        if (fresh) return std::string();
        return "duplicate condition name '" + c + "'" +
               (it->second == name ? std::string() : " (set '" + it->second + "' has it too)");
      };
      if (const toml::array* list = st->array("conditions", false)) {
        for (const toml::node& n : *list) {
          Condition c = read_condition(n, source, defaults, plant);
          if (const std::string e = duplicate(c.name); !e.empty()) st->fail(n, e);
          set.conditions.push_back(std::move(c));
        }
      }
      if (auto mc = st->table("monte_carlo", false)) {
        const std::size_t named = set.conditions.size();
        read_monte_carlo(*mc, name, defaults, plant, set);
        for (std::size_t i = named; i < set.conditions.size(); ++i)
          if (const std::string e = duplicate(set.conditions[i].name); !e.empty()) mc->fail_here(e);
      }
      st->finish();
      if (set.conditions.empty()) st->fail_here("set '" + name + "' has no conditions");
      out.sets.push_back(std::move(set));
    }
    sets->finish();
    r.finish();
    if (out.sets.empty()) r.fail_here("no condition sets");
    file = std::move(out);
    return true;
  } catch (const ReadError& e) {
    error = e.error;
    return false;
  }
}

bool load_conditions(const std::string& path, ConditionFile& file, fuzzypid::FileError& error) {
  try {
    const std::string text = support::read_text(path);
    return parse_conditions(text, path, file, error);
  } catch (const ReadError& e) {
    error = e.error;
    return false;
  }
}

}  // namespace fuzzypid::sim
