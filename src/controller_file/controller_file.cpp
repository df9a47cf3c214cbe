#include "fuzzypid/controller_file/controller_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>

#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/supervisor/engine_supervisor.hpp"
#include "fuzzypid_support/toml_reader.hpp"

namespace fuzzypid::controller_file {

using namespace controller;
using support::number_of;
using support::parse_toml;
using support::read_text;
using support::ReadError;
using support::TableReader;
using tune::BoundHit;
using tune::FrontObjective;
using tune::SearchBox;
using tune::StageRecord;
using tune::TableRegulariser;
using tune::TrainedOn;
using tune::Tuning;

namespace {

// The form file_hash writes: exactly 16 lower-case hex digits.
bool is_fnv1a64(const std::string& text) {
  if (text.size() != 16) return false;
  for (const char c : text)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

std::string triple_text(double a, double b, double c) {
  return "[" + format_double(a) + ", " + format_double(b) + ", " + format_double(c) + "]";
}

// TOML basic string with the characters TOML requires escaped.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

// The rule base named by `written` (relative to the controller file's folder), loaded and checked
// for the two inputs and three outputs FuzzyPid needs.
std::shared_ptr<const fuzzy::EngineModel<double>> load_rule_model(const TableReader& where,
                                                                  const toml::node& node,
                                                                  const std::string& written) {
  namespace fs = std::filesystem;
  if (written.empty()) where.fail(node, "rule_file must name a .fis, .fll or .fcl file");
  const fs::path resolved = fs::path(where.file()).parent_path() / written;
  auto model = std::make_shared<rulefile::Model>();
  rulefile::LoadError error;
  if (!rulefile::load_rule_file(resolved.string(), *model, error))
    where.fail(node, "cannot load the rule file: " + error.to_string());
  // Bound by name (supervisor/engine_supervisor.hpp), so the order of the blocks does not matter;
  // a term name used twice in a variable would make a rule's meaning depend on the reader's
  // resolution rule, so a rule file that drives gains may not have one.
  if (const std::string bad = supervisor::supervisor_binding_error(*model); !bad.empty())
    where.fail(node, "the rule file cannot supervise the gains: " + resolved.string() + ": " + bad);
  if (!error.warnings.empty())
    where.fail(node, "the rule file cannot supervise the gains: " + error.warnings.front());
  if (!supervisor::EngineSupervisor<double>(model.get()).valid())
    where.fail(node, "the rule file cannot supervise the gains: " + resolved.string());
  return model;
}

// n numbers at `key`, each finite.
template <std::size_t N>
std::array<double, N> read_numbers(TableReader& r, const toml::node& node,
                                   const std::string& what) {
  const auto* a = node.as_array();
  if (a == nullptr || a->size() != N)
    r.fail(node, what + " must be an array of " + std::to_string(N) + " numbers");
  std::array<double, N> out{};
  for (std::size_t k = 0; k < N; ++k)
    out[k] = number_of(r, *a->get(k), what + "[" + std::to_string(k) + "]");
  return out;
}

RuleTableSpec::Centers read_centers(TableReader& r, const char* key) {
  const toml::array* a = r.array(key, true);
  const auto c = read_numbers<RuleTableSpec::kSets>(r, *a, std::string("'") + key + "'");
  RuleTableSpec probe;
  probe.error_centers = c;
  if (const std::string bad = validate(probe); !bad.empty()) r.fail(*a, bad);
  return c;
}

// Seven rows of seven ratios: row i is the error's set i (NB..PB), column j the rate's set j.
RuleTableSpec::Table read_ratio_table(TableReader& r, const char* key) {
  const toml::array* rows = r.array(key, true);
  constexpr std::size_t n = RuleTableSpec::kSets;
  if (rows->size() != n) r.fail(*rows, std::string("'") + key + "' must have 7 rows of 7 ratios");
  RuleTableSpec::Table t{};
  for (std::size_t i = 0; i < n; ++i) {
    const std::string what = std::string("'") + key + "[" + std::to_string(i) + "]'";
    t[i] = read_numbers<n>(r, *rows->get(i), what);
    for (double v : t[i])
      if (!(v > 0.0)) r.fail(*rows->get(i), what + ": ratios must be > 0");
  }
  return t;
}

ControllerFile read_file(const toml::table& root, const std::string& file) {
  TableReader r(root, file);
  ControllerFile out;
  ControllerSpec& s = out.controller;
  s.family = r.choice("family", kFamilyNames);
  s.description = r.text("description", std::string());

  auto units = r.table("units", true);
  s.units.gains = units->choice("gains", kGainUnitsNames);
  s.units.form = units->choice("form", kPidFormNames);
  s.units.tick_s = units->number("tick_s");
  if (!(s.units.tick_s > 0.0)) units->fail(*units->raw().get("tick_s"), "'tick_s' must be > 0");
  units->finish();

  auto gains = r.table("gains", true);
  s.gains.kp = gains->number("kp");
  s.gains.ki = gains->number("ki");
  s.gains.kd = gains->number("kd");
  for (const char* k : {"kp", "ki", "kd"})
    if (gains->number(k) < 0.0) gains->fail(*gains->raw().get(k), "gains must be >= 0");
  if (gains->has("bandwidth_scale")) {
    const toml::array* a = gains->array("bandwidth_scale", true);
    if (a->size() != s.bandwidth_scale.size())
      gains->fail(*a, "bandwidth_scale must have 6 numbers (one per joint)");
    for (std::size_t i = 0; i < s.bandwidth_scale.size(); ++i) {
      const double v =
          number_of(*gains, *a->get(i), "bandwidth_scale[" + std::to_string(i) + "]", true);
      if (!(v >= kMinBandwidthScale && v <= kMaxBandwidthScale))
        gains->fail(*a->get(i), "bandwidth_scale[" + std::to_string(i) + "] must be within [" +
                                    format_double(kMinBandwidthScale) + ", " +
                                    format_double(kMaxBandwidthScale) + "]");
      s.bandwidth_scale[i] = v;
    }
  }
  gains->finish();

  const FamilyTraits& traits = family_traits(s.family);
  const bool supervised = traits.supervised();
  auto sup = r.table("supervisor", supervised);
  if (sup && !supervised)
    r.fail(*root.get("supervisor"),
           std::string("a '") + traits.name + "' controller has no [supervisor] table");
  if (sup) {
    s.supervisor.error_scale = sup->number("error_scale");
    s.supervisor.error_rate_scale = sup->number("error_rate_scale");
    s.supervisor.output_scale = sup->triple("output_scale", std::nullopt);
    if (traits.rule_base) {
      s.supervisor.gain_update =
          sup->choice("gain_update", kGainUpdateNames, supervisor::GainUpdate::Absolute);
      if (sup->has("rule_file")) {
        const toml::node& node = *sup->raw().get("rule_file");
        if (sup->has("rule_base") || sup->has("conjunction"))
          sup->fail(node, "rule_file replaces the built-in tables: no rule_base or conjunction");
        s.supervisor.rule_file = sup->text("rule_file");
        s.supervisor.rule_model = load_rule_model(*sup, node, s.supervisor.rule_file);
      } else {
        s.supervisor.rule_base = sup->choice("rule_base", kRuleBaseNames, paper::Tables::Printed);
        s.supervisor.conjunction =
            sup->choice("conjunction", kConjunctionNames, fuzzy::Conjunction::Minimum);
      }
    }
    for (const char* k : {"error_scale", "error_rate_scale"})
      if (!(sup->number(k) > 0.0)) sup->fail(*sup->raw().get(k), std::string(k) + " must be > 0");
    if (traits.output_scale == OutputScale::Ratios)
      for (double ratio : s.supervisor.output_scale)
        if (!(ratio > 0.0))
          sup->fail(*sup->raw().get("output_scale"),
                    std::string("the ") + to_string(s.family) +
                        " family's output_scale holds gain ratios, which must be > 0");
    sup->finish();
  }

  auto table = r.table("rule_table", traits.rule_table);
  if (table && !traits.rule_table)
    r.fail(*root.get("rule_table"),
           std::string("a '") + traits.name + "' controller has no [rule_table]");
  if (table) {
    RuleTableSpec& t = s.supervisor.rule_table;
    t.error_centers = read_centers(*table, "error_centers");
    t.error_rate_centers = read_centers(*table, "error_rate_centers");
    const char* gains[3] = {"kp", "ki", "kd"};
    for (std::size_t g = 0; g < 3; ++g)
      t.ratio[g] = read_ratio_table(*table, gains[g]);
    table->finish();
  }

  if (auto bounds = r.table("bounds", false)) {
    const auto lo = bounds->triple("gain_min", std::array<double, 3>{0.0, 0.0, 0.0}, true);
    const auto hi = bounds->triple(
        "gain_max", std::array<double, 3>{s.gain_max.kp, s.gain_max.ki, s.gain_max.kd}, true);
    for (std::size_t k = 0; k < 3; ++k) {
      if (lo[k] < 0.0 || std::isinf(lo[k]))
        bounds->fail(*bounds->raw().get("gain_min"), "gain_min must be finite and >= 0");
      if (hi[k] < lo[k])
        bounds->fail(bounds->has("gain_max") ? *bounds->raw().get("gain_max")
                                             : *bounds->raw().get("gain_min"),
                     "gain_max must not be below gain_min");
    }
    s.gain_min = {lo[0], lo[1], lo[2]};
    s.gain_max = {hi[0], hi[1], hi[2]};
    bounds->finish();
  }

  if (auto p = r.table("pid", false)) {
    s.pid.derivative = p->choice("derivative", kDerivativeSourceNames, s.pid.derivative);
    s.pid.derivative_on = p->choice("derivative_on", kDerivativeOnNames, s.pid.derivative_on);
    s.pid.anti_windup = p->choice("anti_windup", kAntiWindupNames, s.pid.anti_windup);
    s.pid.derivative_filter_s = p->number("derivative_filter_s", 0.0);
    if (s.pid.derivative_filter_s < 0.0)
      p->fail(*p->raw().get("derivative_filter_s"), "derivative_filter_s must be >= 0");
    s.pid.observer_bandwidth_hz = p->number("observer_bandwidth_hz", 0.0);
    if (p->has("observer_delay_ticks")) {
      const std::uint64_t ticks = p->count("observer_delay_ticks");
      if (ticks > static_cast<std::uint64_t>(pid::kMaxObserverDelayTicks))
        p->fail(*p->raw().get("observer_delay_ticks"),
                "observer_delay_ticks must be 0 .. " + std::to_string(pid::kMaxObserverDelayTicks));
      s.pid.observer_delay_ticks = static_cast<int>(ticks);
    }
    p->finish();
  }

  if (auto ff = r.table("feedforward", false)) {
    s.feedforward.gravity = ff->flag("gravity", false);
    ff->finish();
  }

  if (auto t = r.table("tuning", false)) {
    Tuning tu;
    tu.conditions = t->text("conditions");
    tu.set = t->text("set");
    tu.algorithm = t->text("algorithm");
    tu.budget = t->count("budget");
    tu.evaluations = t->count("evaluations");
    if (tu.evaluations > tu.budget)
      t->fail(*t->raw().get("evaluations"), "evaluations exceed the budget");
    tu.seed = t->count("seed");
    tu.threads = t->count("threads", 0);  // absent: a result that does not depend on it
    tu.population = t->count("population");
    tu.training_cost = t->number("training_cost", std::nullopt, true);
    auto o = t->table("objective", true);
    tu.objective.overshoot_bound_pct = o->number("overshoot_bound_pct");
    tu.objective.overshoot_weight = o->number("overshoot_weight");
    tu.objective.fault_cost = o->number("fault_cost");
    tu.objective.divergence_rad = o->number("divergence_rad");
    tu.objective.chatter_weight = o->number("chatter_weight", 0.0);
    tu.objective.effort_weight = o->number("effort_weight", 0.0);
    tu.objective.chatter_limit_pct = o->number("chatter_limit_pct", 0.0);
    for (const char* key : {"chatter_weight", "effort_weight"})
      if (o->has(key) && !(o->number(key) >= 0.0))
        o->fail(*o->raw().get(key), std::string(key) + " must be >= 0");
    if (o->has("chatter_limit_pct") &&
        !(tu.objective.chatter_limit_pct >= 0.0 && tu.objective.chatter_limit_pct <= 100.0))
      o->fail(*o->raw().get("chatter_limit_pct"), "chatter_limit_pct must be within 0 .. 100");
    tu.objective.min_disk_margin = o->number("min_disk_margin", 0.0);
    tu.objective.min_gain_margin_db = o->number("min_gain_margin_db", 0.0);
    tu.objective.min_phase_margin_deg = o->number("min_phase_margin_deg", 0.0);
    tu.objective.min_delay_margin_ms = o->number("min_delay_margin_ms", 0.0);
    for (const char* key :
         {"min_disk_margin", "min_gain_margin_db", "min_phase_margin_deg", "min_delay_margin_ms"})
      if (o->has(key) && !(o->number(key) >= 0.0))
        o->fail(*o->raw().get(key), std::string(key) + " must be >= 0");
    o->finish();
    const toml::array* box = t->array("box", true);
    for (const toml::node& entry : *box) {
      const auto* bt = entry.as_table();
      if (bt == nullptr)
        t->fail(entry, "box entries must be { name = \"...\", log10 = [min, max] }");
      TableReader br(*bt, file);
      SearchBox b;
      b.name = br.text("name");
      const toml::array* range = br.array("log10", true);
      if (range->size() != 2) br.fail(*range, "log10 must be [min, max]");
      b.log10_min = number_of(br, *range->get(0), "box '" + b.name + "' minimum");
      b.log10_max = number_of(br, *range->get(1), "box '" + b.name + "' maximum");
      if (b.log10_max < b.log10_min) br.fail(*range, "box '" + b.name + "' is reversed");
      br.finish();
      tu.box.push_back(b);
    }
    if (const toml::array* hits = t->array("on_bound", false)) {
      for (const toml::node& entry : *hits) {
        const auto* ht = entry.as_table();
        if (ht == nullptr)
          t->fail(entry,
                  "on_bound entries must be { name = \"...\", side = \"min|max\", log10 = x }");
        TableReader hr(*ht, file);
        BoundHit h;
        h.name = hr.text("name");
        const std::string side = hr.text("side");
        if (side != "min" && side != "max")
          hr.fail(*ht->get("side"), "on_bound side must be \"min\" or \"max\"");
        h.upper = side == "max";
        h.log10 = hr.number("log10");
        hr.finish();
        tu.on_bound.push_back(h);
      }
    }
    if (const toml::array* files = t->array("trained_on", false)) {
      for (const toml::node& entry : *files) {
        const auto* ft = entry.as_table();
        if (ft == nullptr)
          t->fail(entry,
                  "trained_on entries must be { kind = \"conditions|urdf|path\", file = \"...\", "
                  "fnv1a64 = \"...\" }");
        TableReader fr(*ft, file);
        TrainedOn f;
        f.kind = fr.text("kind");
        if (f.kind != "conditions" && f.kind != "urdf" && f.kind != "path")
          fr.fail(*ft->get("kind"), "trained_on kind must be \"conditions\", \"urdf\" or \"path\"");
        f.file = fr.text("file");
        f.fnv1a64 = fr.text("fnv1a64");
        if (!is_fnv1a64(f.fnv1a64))
          fr.fail(*ft->get("fnv1a64"), "trained_on fnv1a64 \"" + f.fnv1a64.substr(0, 40) +
                                           "\" is not a 64-bit FNV-1a hash: expected 16 "
                                           "lower-case hex digits, e.g. \"a7e492482337c9be\"");
        fr.finish();
        tu.trained_on.push_back(f);
      }
    }
    tu.tick_s = t->number("tick_s", 0.0);
    if (!(tu.tick_s >= 0.0))
      t->fail(*t->raw().get("tick_s"), "tick_s (the training tick, s) must be >= 0");
    tu.init = t->text("init", std::string());
    tu.validation_conditions = t->count("validation_conditions", 0);
    tu.validation_cost =
        t->number("validation_cost", std::numeric_limits<double>::quiet_NaN(), true);
    if (const toml::array* stages = t->array("stages", false)) {
      for (const toml::node& entry : *stages) {
        const auto* st = entry.as_table();
        if (st == nullptr)
          t->fail(entry,
                  "stages entries must be { family = \"...\", budget = N, evaluations = N, "
                  "training_cost = x, validation_cost = x }");
        TableReader sr(*st, file);
        StageRecord rec;
        rec.family = sr.choice("family", kFamilyNames);
        rec.budget = sr.count("budget");
        rec.evaluations = sr.count("evaluations");
        rec.training_cost = sr.number("training_cost", std::nullopt, true);
        rec.validation_cost =
            sr.number("validation_cost", std::numeric_limits<double>::quiet_NaN(), true);
        sr.finish();
        tu.stages.push_back(rec);
      }
    }
    if (const toml::array* front = t->array("front", false)) {
      for (const toml::node& entry : *front) {
        const auto* ft = entry.as_table();
        if (ft == nullptr)
          t->fail(entry,
                  "front entries must be { objective = \"...\", training = x, validation = x }");
        TableReader fr(*ft, file);
        FrontObjective f;
        f.name = fr.text("objective");
        f.training = fr.number("training", std::nullopt, true);
        f.validation = fr.number("validation", std::numeric_limits<double>::quiet_NaN(), true);
        fr.finish();
        tu.front.push_back(f);
      }
    }
    if (auto g = t->table("regulariser", false)) {
      TableRegulariser reg;
      reg.symmetry = g->text("symmetry");
      reg.partition = g->flag("partition");
      reg.smoothness = g->number("smoothness");
      reg.monotone = g->number("monotone");
      reg.unvisited = g->text("unvisited");
      reg.visit_threshold = g->number("visit_threshold");
      reg.frozen_cells = g->count("frozen_cells");
      reg.cell_log10 = g->number("cell_log10");
      g->finish();
      tu.regulariser = reg;
    }
    t->finish();
    out.tuning = tu;
  }

  if (auto m = r.table("margins", false)) {
    MarginRecord rec;
    rec.conditions = m->text("conditions");
    rec.set = m->text("set");
    rec.delay_ms = m->number("delay_ms");
    const auto joints = [&](const char* key, MarginRecord::PerJoint& out) {
      const toml::array* a = m->array(key, true);
      if (a->size() != out.size()) m->fail(*a, std::string(key) + " must have 6 numbers");
      for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = number_of(*m, *a->get(i), std::string(key) + "[" + std::to_string(i) + "]", true);
    };
    joints("gain_margin_db", rec.gain_margin_db);
    joints("phase_margin_deg", rec.phase_margin_deg);
    joints("delay_margin_ms", rec.delay_margin_ms);
    joints("disk_margin", rec.disk_margin);
    joints("inertia_min_kgm2", rec.inertia_min_kgm2);
    joints("inertia_max_kgm2", rec.inertia_max_kgm2);
    rec.certified = m->flag("certified");
    rec.verdict = m->text("verdict");
    rec.assumptions = m->text("assumptions");
    m->finish();
    out.margins = rec;
  }
  r.finish();
  return out;
}

}  // namespace

std::string file_hash(const std::string& path) {
  // Through the inputs' checked opener: a FIFO or a device is never opened (it could block).
  std::string refused;
  const int fd = support::open_regular_file(path, refused);
  if (fd < 0) return {};
  std::FILE* f = ::fdopen(fd, "rb");
  if (f == nullptr) {
    ::close(fd);
    return {};
  }
  std::uint64_t h = 14695981039346656037ull;
  unsigned char buf[65536];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
    for (std::size_t i = 0; i < n; ++i) {
      h ^= buf[i];
      h *= 1099511628211ull;
    }
  const bool ok = std::ferror(f) == 0;
  std::fclose(f);
  if (!ok) return {};
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

bool parse(std::string_view text, const std::string& source, ControllerFile& file,
           FileError& error) {
  try {
    const toml::table root = parse_toml(text, source);
    ControllerFile f = read_file(root, source);
    if (const std::string bad = validate(f.controller); !bad.empty()) {
      error = FileError{source, 1, 1, bad};
      return false;
    }
    file = std::move(f);
    return true;
  } catch (const ReadError& e) {
    error = e.error;
    return false;
  }
}

bool load(const std::string& path, ControllerFile& file, FileError& error) {
  try {
    const std::string text = read_text(path);
    return parse(text, path, file, error);
  } catch (const ReadError& e) {
    error = e.error;
    return false;
  }
}

bool parse(std::string_view text, const std::string& source, ControllerSpec& spec,
           FileError& error) {
  ControllerFile file;
  if (!parse(text, source, file, error)) return false;
  spec = std::move(file.controller);
  return true;
}

bool load(const std::string& path, ControllerSpec& spec, FileError& error) {
  ControllerFile file;
  if (!load(path, file, error)) return false;
  spec = std::move(file.controller);
  return true;
}

std::string to_toml(const ControllerSpec& spec) {
  return to_toml(ControllerFile{spec, std::nullopt, std::nullopt});
}

std::string to_toml(const ControllerFile& file) {
  const ControllerSpec& s = file.controller;
  std::string o;
  o += "# fuzzypid controller file (docs/tuning.md). Gains in the units of [units].\n";
  o += "family = " + quoted(to_string(s.family)) + "\n";
  if (!s.description.empty()) o += "description = " + quoted(s.description) + "\n";
  o += "\n[units]\n";
  o += "gains = " + quoted(to_string(s.units.gains)) + "\n";
  o += "form = " + quoted(to_string(s.units.form)) + "\n";
  o += "tick_s = " + format_double(s.units.tick_s) + "\n";
  o += "\n[gains]";
  const FamilyTraits& traits = family_traits(s.family);
  o += traits.supervised() ? "  # the nominal gains K0\n" : "\n";
  o += "kp = " + format_double(s.gains.kp) + "\n";
  o += "ki = " + format_double(s.gains.ki) + "\n";
  o += "kd = " + format_double(s.gains.kd) + "\n";
  if (s.bandwidth_scale != kUniformBandwidth) {
    o += "# joint i runs s_i times faster: Kp s², Ki s³, Kd s, Tf / s (docs/tuning.md)\n";
    o += "bandwidth_scale = [";
    for (std::size_t i = 0; i < s.bandwidth_scale.size(); ++i)
      o += (i == 0 ? "" : ", ") + format_double(s.bandwidth_scale[i]);
    o += "]\n";
  }
  if (traits.supervised()) {
    const auto& sup = s.supervisor;
    o += "\n[supervisor]\n";
    o += "error_scale = " + format_double(sup.error_scale) + "\n";
    o += "error_rate_scale = " + format_double(sup.error_rate_scale) + "\n";
    o += "output_scale = " +
         triple_text(sup.output_scale[0], sup.output_scale[1], sup.output_scale[2]);
    o += traits.output_scale == OutputScale::Scales ? "  # Sp, Si, Sd\n"
                                                    : "  # large-error gain ratios Rp, Ri, Rd\n";
    if (traits.rule_base) {
      o += "gain_update = " + quoted(name_of(kGainUpdateNames, sup.gain_update)) + "\n";
      if (!sup.rule_file.empty()) {
        o += "rule_file = " + quoted(sup.rule_file) + "  # relative to this file's folder\n";
      } else {
        o += "rule_base = " + quoted(to_string(sup.rule_base)) + "\n";
        o += "conjunction = " + quoted(name_of(kConjunctionNames, sup.conjunction)) + "\n";
      }
    }
  }
  if (traits.rule_table) {
    const RuleTableSpec& t = s.supervisor.rule_table;
    o += "\n[rule_table]  # the rule \"x is set i and y is set j\" multiplies the schedule's gain "
         "by "
         "ratio[i][j]\n";
    o += "# sets NB NM NS ZO PS PM PB of x = error_scale e (rows) and y = error_rate_scale ec "
         "(columns)\n";
    const auto list = [](const auto& values) {
      std::string line = "[";
      for (std::size_t k = 0; k < values.size(); ++k)
        line += (k == 0 ? "" : ", ") + format_double(values[k]);
      return line + "]";
    };
    o += "error_centers = " + list(t.error_centers) + "\n";
    o += "error_rate_centers = " + list(t.error_rate_centers) + "\n";
    const char* gains[3] = {"kp", "ki", "kd"};
    for (std::size_t g = 0; g < 3; ++g) {
      o += std::string(gains[g]) + " = [\n";
      for (const auto& row : t.ratio[g])
        o += "  " + list(row) + ",\n";
      o += "]\n";
    }
  }
  o += "\n[bounds]  # on the retuned gains\n";
  o += "gain_min = " + triple_text(s.gain_min.kp, s.gain_min.ki, s.gain_min.kd) + "\n";
  o += "gain_max = " + triple_text(s.gain_max.kp, s.gain_max.ki, s.gain_max.kd) + "\n";
  o += "\n[pid]\n";
  o += "derivative = " + quoted(name_of(kDerivativeSourceNames, s.pid.derivative)) + "\n";
  o += "derivative_on = " + quoted(name_of(kDerivativeOnNames, s.pid.derivative_on)) + "\n";
  o += "anti_windup = " + quoted(name_of(kAntiWindupNames, s.pid.anti_windup)) + "\n";
  o += "derivative_filter_s = " + format_double(s.pid.derivative_filter_s) + "\n";
  if (s.pid.derivative == pid::DerivativeSource::Observer) {
    o += "observer_bandwidth_hz = " + format_double(s.pid.observer_bandwidth_hz) + "\n";
    o += "observer_delay_ticks = " + std::to_string(s.pid.observer_delay_ticks) + "\n";
  }
  if (s.feedforward.gravity) {
    o += "\n[feedforward]\n";
    o += "gravity = true  # tau += g^(q_desired) of the nominal model\n";
  }
  if (file.tuning) {
    const Tuning& t = *file.tuning;
    o += "\n[tuning]  # file names relative to this file's folder\n";
    o += "conditions = " + quoted(t.conditions) + "\n";
    o += "set = " + quoted(t.set) + "\n";
    o += "algorithm = " + quoted(t.algorithm) + "\n";
    o += "budget = " + std::to_string(t.budget) + "\n";
    o += "evaluations = " + std::to_string(t.evaluations) + "\n";
    o += "seed = " + std::to_string(t.seed) + "\n";
    if (t.threads != 0) o += "threads = " + std::to_string(t.threads) + "\n";
    o += "population = " + std::to_string(t.population) + "\n";
    o += "training_cost = " + format_double(t.training_cost) + "\n";
    o += "box = [  # log10 of each searched parameter\n";
    for (const SearchBox& b : t.box)
      o += "  { name = " + quoted(b.name) + ", log10 = [" + format_double(b.log10_min) + ", " +
           format_double(b.log10_max) + "] },\n";
    o += "]\n";
    if (!t.on_bound.empty()) {
      o += "on_bound = [  # parameters that ended on a side of their box: widen it and re-tune\n";
      for (const BoundHit& h : t.on_bound)
        o += "  { name = " + quoted(h.name) + ", side = " + quoted(h.upper ? "max" : "min") +
             ", log10 = " + format_double(h.log10) + " },\n";
      o += "]\n";
    }
    if (!t.trained_on.empty()) {
      o += "trained_on = [  # files the tune read: the condition file, the training robots and "
           "paths\n";
      for (const TrainedOn& f : t.trained_on)
        o += "  { kind = " + quoted(f.kind) + ", file = " + quoted(f.file) +
             ", fnv1a64 = " + quoted(f.fnv1a64) + " },\n";
      o += "]\n";
    }
    if (t.tick_s > 0.0)
      o += "tick_s = " + format_double(t.tick_s) + "  # the training conditions' tick\n";
    if (!t.init.empty())
      o += "init = " + quoted(t.init) + "  # the controller the search started from\n";
    if (t.validation_conditions != 0) {
      o += "validation_conditions = " + std::to_string(t.validation_conditions) +
           "  # held back from the training set\n";
      if (!std::isnan(t.validation_cost))
        o += "validation_cost = " + format_double(t.validation_cost) + "\n";
    }
    if (!t.stages.empty()) {
      o += "stages = [\n";
      for (const StageRecord& st : t.stages)
        o += "  { family = " + quoted(to_string(st.family)) +
             ", budget = " + std::to_string(st.budget) +
             ", evaluations = " + std::to_string(st.evaluations) +
             ", training_cost = " + format_double(st.training_cost) +
             (std::isnan(st.validation_cost)
                  ? std::string()
                  : ", validation_cost = " + format_double(st.validation_cost)) +
             " },\n";
      o += "]\n";
    }
    if (!t.front.empty()) {
      o += "front = [  # this point's objectives (fuzzypid tune --objectives), all minimised\n";
      for (const FrontObjective& f : t.front)
        o += "  { objective = " + quoted(f.name) + ", training = " + format_double(f.training) +
             (std::isnan(f.validation) ? std::string()
                                       : ", validation = " + format_double(f.validation)) +
             " },\n";
      o += "]\n";
    }
    if (t.regulariser) {
      const TableRegulariser& g = *t.regulariser;
      o += "\n[tuning.regulariser]  # how the rule table was kept readable and safe\n";
      o += "symmetry = " + quoted(g.symmetry) + "\n";
      o += std::string("partition = ") + (g.partition ? "true" : "false") + "\n";
      o += "smoothness = " + format_double(g.smoothness) + "\n";
      o += "monotone = " + format_double(g.monotone) + "\n";
      o += "unvisited = " + quoted(g.unvisited) + "\n";
      o += "visit_threshold = " + format_double(g.visit_threshold) + "\n";
      o += "frozen_cells = " + std::to_string(g.frozen_cells) + "\n";
      o += "cell_log10 = " + format_double(g.cell_log10) + "\n";
    }
    o += "\n[tuning.objective]\n";
    o += "overshoot_bound_pct = " + format_double(t.objective.overshoot_bound_pct) + "\n";
    o += "overshoot_weight = " + format_double(t.objective.overshoot_weight) + "\n";
    o += "fault_cost = " + format_double(t.objective.fault_cost) + "\n";
    o += "divergence_rad = " + format_double(t.objective.divergence_rad) + "\n";
    if (t.objective.chatter_weight != 0.0)
      o += "chatter_weight = " + format_double(t.objective.chatter_weight) + "\n";
    if (t.objective.chatter_limit_pct != 0.0)
      o += "chatter_limit_pct = " + format_double(t.objective.chatter_limit_pct) + "\n";
    if (t.objective.effort_weight != 0.0)
      o += "effort_weight = " + format_double(t.objective.effort_weight) + "\n";
    const std::pair<const char*, double> minima[] = {
        {"min_disk_margin", t.objective.min_disk_margin},
        {"min_gain_margin_db", t.objective.min_gain_margin_db},
        {"min_phase_margin_deg", t.objective.min_phase_margin_deg},
        {"min_delay_margin_ms", t.objective.min_delay_margin_ms}};
    for (const auto& [key, value] : minima)
      if (value != 0.0) o += std::string(key) + " = " + format_double(value) + "\n";
  }
  if (file.margins) {
    const MarginRecord& m = *file.margins;
    const auto joints = [](const MarginRecord::PerJoint& v) {
      std::string line = "[";
      for (std::size_t i = 0; i < v.size(); ++i)
        line += (i == 0 ? "" : ", ") + format_double(v[i]);
      return line + "]";
    };
    o += "\n# What `fuzzypid certify` found over these conditions (docs/margins.md): per joint "
         "the\n";
    o += "# worst frozen-gain margins and the inertia range; certified: a common quadratic\n";
    o += "# Lyapunov function covers gains and inertia changing every tick.\n";
    o += "[margins]\n";
    o += "conditions = " + quoted(m.conditions) + "\n";
    o += "set = " + quoted(m.set) + "\n";
    o += "delay_ms = " + format_double(m.delay_ms) + "\n";
    o += "gain_margin_db = " + joints(m.gain_margin_db) + "\n";
    o += "phase_margin_deg = " + joints(m.phase_margin_deg) + "\n";
    o += "delay_margin_ms = " + joints(m.delay_margin_ms) + "\n";
    o += "disk_margin = " + joints(m.disk_margin) + "\n";
    o += "inertia_min_kgm2 = " + joints(m.inertia_min_kgm2) + "\n";
    o += "inertia_max_kgm2 = " + joints(m.inertia_max_kgm2) + "\n";
    o += std::string("certified = ") + (m.certified ? "true" : "false") + "\n";
    o += "verdict = " + quoted(m.verdict) + "\n";
    o += "assumptions = " + quoted(m.assumptions) + "\n";
  }
  return o;
}

std::vector<std::string> trained_on_differences(const Tuning* tuning,
                                                const std::string& controller_path,
                                                const std::string& urdf, const std::string& path,
                                                const std::string& bundled_urdf) {
  std::vector<std::string> out;
  if (tuning == nullptr) return out;
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(controller_path).parent_path();
  // One kind: the run's file (empty: the built-in line) against the recorded ones of that kind.
  const auto compare = [&](const char* kind, const std::string& used, const std::string& absent,
                           const std::string& absent_file) {
    std::vector<const TrainedOn*> recorded;
    for (const TrainedOn& f : tuning->trained_on)
      if (f.kind == kind) recorded.push_back(&f);
    const std::string used_hash = used.empty() ? std::string() : file_hash(used);
    if (recorded.empty()) {
      // Trained on the default: the bundled file (compared by content) or the built-in line.
      if (used.empty()) return;
      if (!absent_file.empty() && used_hash == file_hash(absent_file)) return;
      out.push_back(std::string(kind) + ": trained on " + absent + ", run on " + used +
                    " (fnv1a64 " + used_hash + ")");
      return;
    }
    for (const TrainedOn* f : recorded)
      if (!used.empty() && f->fnv1a64 == used_hash) return;
    std::string line = std::string(kind) + ": trained on ";
    bool changed = false;
    for (std::size_t k = 0; k < recorded.size(); ++k) {
      const TrainedOn& f = *recorded[k];
      const fs::path file = fs::path(f.file).is_absolute() ? fs::path(f.file) : folder / f.file;
      std::error_code ec;
      if (!used.empty() && fs::equivalent(file, used, ec) && !ec) changed = true;
      line += (k == 0 ? "" : ", ") + f.file + " (fnv1a64 " + f.fnv1a64 + ")";
    }
    if (used.empty()) {
      line += ", run on " + absent;
    } else {
      line += ", run on " + used + " (fnv1a64 " + used_hash + ")";
      if (changed) line += ": the file has changed since the controller was tuned";
    }
    out.push_back(line);
  };
  compare("urdf", urdf, "the bundled ER50-C20", bundled_urdf);
  compare("path", path, "the built-in line A -> B", std::string());
  return out;
}

std::string conditions_changed(const Tuning* tuning, const std::string& controller_path,
                               const std::string& conditions) {
  if (tuning == nullptr || conditions.empty()) return {};
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(controller_path).parent_path();
  for (const TrainedOn& f : tuning->trained_on) {
    if (f.kind != "conditions") continue;
    const fs::path file = fs::path(f.file).is_absolute() ? fs::path(f.file) : folder / f.file;
    std::error_code ec;
    if (!fs::equivalent(file, conditions, ec) || ec) continue;
    const std::string now = file_hash(conditions);
    if (now == f.fnv1a64) return {};
    return "tuned on " + f.file + " (fnv1a64 " + f.fnv1a64 + "), which has changed since (now " +
           now + "): its sets may not be the ones the tune read";
  }
  return {};
}

}  // namespace fuzzypid::controller_file
