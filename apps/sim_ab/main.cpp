// sim_ab: the paper's A/B experiment (section 6, Figs. 9-14) on the ER50-C20 model -- the
// paper's fixed PID and fuzzy PID, or any controller files (--controller, repeatable), on
// scenarios, single conditions or condition sets (--conditions), or a robustness sweep (--sweep).
//
// Writes, into --out (default out/): trajectory.csv, metrics.csv, endeffector.csv,
// conditions.csv and settings.txt (a sweep: sweep.csv and settings.txt). The set replaces --out as
// a whole only when the whole run has succeeded (cli::OutputSet), so a failed run never leaves a
// half-written CSV that looks complete. Exit status: 0 success, 1 run-time failure (including
// a run with faults -- a controller fault, a joint whose |error| passed --divergence or that left
// its URDF joint limits -- unless --allow-faults; the outputs are written either way), 2 usage
// error.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/condition_set.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/metrics.hpp"
#include "fuzzypid/sim/mismatch.hpp"
#include "fuzzypid/sim/sweep.hpp"
#include "fuzzypid_support/bounded_read.hpp"
#include "options.hpp"
#include "output_files.hpp"
#include "robot_options.hpp"

namespace {

using namespace fuzzypid;
namespace fs = std::filesystem;
namespace cf = controller_file;

// The output files of a run, written and committed as a whole by cli::OutputSet: a unique
// temporary directory that replaces --out in one rename, with --out locked meanwhile, so that a
// failed, interrupted or concurrent run never leaves a mixed set or a temporary behind.
struct Output {
  std::FILE* file = nullptr;
};
struct Outputs {
  std::unique_ptr<cli::OutputSet> set;
  std::vector<Output> files;
  Output& operator[](std::size_t k) { return files[k]; }
};

void discard(Outputs& outs) {
  if (outs.set) outs.set->discard();
}

bool commit(Outputs& outs, std::string& error) {
  return outs.set->commit(error);
}

// Opens every named output for `dir`; prints the reason on failure.
bool open_outputs(const fs::path& dir, const std::vector<const char*>& names, Outputs& outs) {
  std::string error;
  outs.set = cli::OutputSet::open(dir.string(), {names.begin(), names.end()}, error);
  if (!outs.set) {
    std::fprintf(stderr, "sim_ab: %s\n", error.c_str());
    return false;
  }
  for (std::size_t k = 0; k < names.size(); ++k)
    outs.files.push_back({outs.set->file(k)});
  return true;
}

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// A CSV field: as it is, or quoted (quotes doubled) when it holds a comma, a quote or a newline.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string joined(const robot::JointVector& v, const char* separator) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i)
    out += (i == 0 ? "" : separator) + fmt(v[i]);
  return out;
}

// Every file sim_ab may write into --out (a run or a sweep).
const std::vector<std::string> kOutputNames = {"trajectory.csv", "metrics.csv",  "endeffector.csv",
                                               "conditions.csv", "settings.txt", "sweep.csv"};

struct NamedController {
  std::string name;
  std::string source;  // the file, or "built-in"
  controller::ControllerSpec spec;
  std::optional<tune::Tuning> tuning;  // the file's records (none when built in)
  std::optional<controller::MarginRecord> margins;
};

struct Run {
  std::string set;
  sim::Condition condition;
};

// Names each tracking fault of a run on stderr ("sim_ab: fault: CONTROLLER on CONDITION: ...").
void report_faults(const sim::RunResult& r, const sim::Experiment& ex, double divergence_rad,
                   const std::string& controller, const std::string& condition) {
  const std::vector<std::string> lines =
      sim::describe(r.tracking_faults, divergence_rad, ex.model().lower_limits_rad(),
                    ex.model().upper_limits_rad());
  for (const std::string& line : lines) {
    std::fprintf(stderr, "sim_ab: fault: %s on %s: %s\n", controller.c_str(), condition.c_str(),
                 line.c_str());
  }
}

// The exit status of a run with `faulted` faulting runs: 1 unless --allow-faults.
int faults_exit(const sim_ab::Options& o, std::size_t faulted) {
  if (faulted == 0) return 0;
  if (o.allow_faults) {
    std::fprintf(stderr, "sim_ab: %zu run(s) with faults (accepted: --allow-faults)\n", faulted);
    return 0;
  }
  std::fprintf(stderr,
               "sim_ab: %zu run(s) with faults (metrics.csv `faults`; --allow-faults accepts "
               "them)\n",
               faulted);
  return 1;
}

// What ran: every robot setup (URDF, links, path, tick, armature, nominal inertia) and every
// controller.
void write_settings(std::FILE* f, const sim_ab::Options& o, const sim::ExperimentSet& experiments,
                    const std::vector<NamedController>& controllers) {
  for (std::size_t k = 0; k < experiments.size(); ++k) {
    const sim::Experiment& ex = experiments.experiment(k);
    const std::string prefix = k == 0 ? "" : "robot" + std::to_string(k + 1) + ".";
    std::fprintf(f, "%surdf=%s\n%sbase_link=%s\n%stip_link=%s\n", prefix.c_str(),
                 ex.urdf_file().c_str(), prefix.c_str(), ex.model().root_link().c_str(),
                 prefix.c_str(), ex.model().tip_link().c_str());
    if (ex.setup().path.empty()) {
      const auto& first = ex.path().poses.front().position_m;
      const auto& last = ex.path().poses.back().position_m;
      std::fprintf(f, "%sstart_mm=%s,%s,%s\n%send_mm=%s,%s,%s\n", prefix.c_str(),
                   fmt(first.x() * 1e3).c_str(), fmt(first.y() * 1e3).c_str(),
                   fmt(first.z() * 1e3).c_str(), prefix.c_str(), fmt(last.x() * 1e3).c_str(),
                   fmt(last.y() * 1e3).c_str(), fmt(last.z() * 1e3).c_str());
    } else {
      std::fprintf(f, "%spath=%s fnv1a64=%s\n", prefix.c_str(), ex.setup().path.c_str(),
                   cf::file_hash(ex.setup().path).c_str());
    }
    std::fprintf(f, "%ssamples=%zu\n%stick_s=%s\n", prefix.c_str(), ex.ticks(), prefix.c_str(),
                 fmt(ex.options().tick_s).c_str());
    const auto& A = ex.armature_kgm2();
    std::fprintf(f, "%sarmature_kgm2=%s,%s,%s,%s,%s,%s\n", prefix.c_str(), fmt(A[0]).c_str(),
                 fmt(A[1]).c_str(), fmt(A[2]).c_str(), fmt(A[3]).c_str(), fmt(A[4]).c_str(),
                 fmt(A[5]).c_str());
    const auto& J = ex.nominal_inertia();
    std::fprintf(f, "%snominal_inertia_kgm2=%s,%s,%s,%s,%s,%s\n", prefix.c_str(), fmt(J[0]).c_str(),
                 fmt(J[1]).c_str(), fmt(J[2]).c_str(), fmt(J[3]).c_str(), fmt(J[4]).c_str(),
                 fmt(J[5]).c_str());
  }
  if (!o.conditions_file.empty()) std::fprintf(f, "conditions=%s\n", o.conditions_file.c_str());
  for (const auto& c : controllers) {
    const auto& s = c.spec;
    std::fprintf(f, "controller.%s=%s family=%s units=%s,%s gains=%s,%s,%s", c.name.c_str(),
                 c.source.c_str(), controller::to_string(s.family),
                 controller::to_string(s.units.gains), controller::to_string(s.units.form),
                 fmt(s.gains.kp).c_str(), fmt(s.gains.ki).c_str(), fmt(s.gains.kd).c_str());
    if (s.bandwidth_scale != controller::kUniformBandwidth) {
      const auto& b = s.bandwidth_scale;
      std::fprintf(f, " bandwidth_scale=%s,%s,%s,%s,%s,%s", fmt(b[0]).c_str(), fmt(b[1]).c_str(),
                   fmt(b[2]).c_str(), fmt(b[3]).c_str(), fmt(b[4]).c_str(), fmt(b[5]).c_str());
    }
    const controller::FamilyTraits& traits = controller::family_traits(s.family);
    if (traits.supervised())
      std::fprintf(
          f, " error_scale=%s error_rate_scale=%s output_scale=%s,%s,%s",
          fmt(s.supervisor.error_scale).c_str(), fmt(s.supervisor.error_rate_scale).c_str(),
          fmt(s.supervisor.output_scale[0]).c_str(), fmt(s.supervisor.output_scale[1]).c_str(),
          fmt(s.supervisor.output_scale[2]).c_str());
    if (traits.rule_base && s.supervisor.rule_file.empty())
      std::fprintf(f, " gain_update=%s rule_base=%s and=%s",
                   fuzzypid::name_of(controller::kGainUpdateNames, s.supervisor.gain_update),
                   controller::to_string(s.supervisor.rule_base),
                   fuzzypid::name_of(controller::kConjunctionNames, s.supervisor.conjunction));
    if (traits.rule_base && !s.supervisor.rule_file.empty()) {
      // What ran: the rule file (resolved against the controller file's folder) and its hash.
      const std::string rules =
          (fs::path(c.source).parent_path() / s.supervisor.rule_file).lexically_normal().string();
      std::fprintf(f, " gain_update=%s rule_file=%s rule_file_fnv1a64=%s",
                   fuzzypid::name_of(controller::kGainUpdateNames, s.supervisor.gain_update),
                   rules.c_str(), cf::file_hash(rules).c_str());
    }
    if (s.feedforward.gravity) std::fprintf(f, " feedforward=gravity");
    std::fprintf(f, " derivative=%s",
                 fuzzypid::name_of(controller::kDerivativeSourceNames, s.pid.derivative));
    if (s.pid.derivative == pid::DerivativeSource::Observer)
      std::fprintf(f, " observer_bandwidth_hz=%.17g observer_delay_ticks=%d",
                   s.pid.observer_bandwidth_hz, s.pid.observer_delay_ticks);
    std::fprintf(f, "\n");
  }
}

// `text` cut at every '|'.
std::vector<std::string> split_fields(const std::string& text) {
  std::vector<std::string> out(1);
  for (const char ch : text)
    if (ch == '|')
      out.emplace_back();
    else
      out.back() += ch;
  return out;
}

// What real joints have (sim::JointEffects), as the condition keys name them, in their units:
// `separator` between the fields, `list` between a per-joint key's six values.
std::string effects_text(const sim::JointEffects& e, const char* separator, const char* list) {
  const std::string sep(separator);
  std::string t;
  t += "plant_step_ms=" + fmt(e.plant_step_s * 1e3) + sep;
  t += "delay_ms=" + fmt(e.delay_s * 1e3) + sep;
  t += "torque_bandwidth_hz=" + fmt(e.torque_bandwidth_hz) + sep;
  t += "encoder_counts=" + std::to_string(e.encoder_counts) + sep;
  t += "coulomb_nm=" + joined(e.coulomb_nm, list) + sep;
  t += "stribeck_nm=" + joined(e.stribeck_nm, list) + sep;
  t += "stribeck_velocity=" + fmt(e.stribeck_velocity_rad_s) + sep;
  t += "coulomb_smoothing=" + fmt(e.coulomb_smoothing_rad_s) + sep;
  t += "joint_resonance_hz=" + joined(e.joint_resonance_hz, list) + sep;
  t += "joint_damping_ratio=" + fmt(e.joint_damping_ratio) + sep;
  t += "backlash_rad=" + fmt(e.backlash_rad);
  return t;
}

// What each condition ran on: robot, path, tick, payload, dynamics, gravity, armature and what
// real joints have, one line per condition (conditions[k] runs on experiments.of(k)).
void write_condition_settings(std::FILE* f, const std::vector<Run>& runs,
                              const sim::ExperimentSet& experiments) {
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const sim::Condition& c = runs[k].condition;
    const sim::Experiment& ex = experiments.of(k);
    std::fprintf(f,
                 "condition.%s=set=%s urdf=%s path=%s tick_s=%s payload_kg=%s dynamics=%s "
                 "gravity=%d armature_kgm2=%s %s\n",
                 c.name.c_str(), runs[k].set.c_str(), ex.urdf_file().c_str(),
                 ex.setup().path.empty() ? "line" : ex.setup().path.c_str(),
                 fmt(ex.options().tick_s).c_str(), fmt(c.payload_kg).c_str(),
                 fuzzypid::name_of(sim::kDynamicsNames, c.dynamics), c.gravity ? 1 : 0,
                 joined(ex.armature_kgm2(), ",").c_str(),
                 effects_text(c.effects, " ", ",").c_str());
  }
}

int run_sweep(const sim_ab::Options& o, const sim::ExperimentSet& experiments,
              const std::vector<Run>& runs, const std::vector<NamedController>& controllers) {
  const sim::Experiment& ex = experiments.of(0);
  const sim::Condition& base = runs.front().condition;
  const sim::Sweep& sw = *o.sweep;
  Outputs outs;
  if (!open_outputs(o.out_dir, {"sweep.csv", "settings.txt"}, outs)) return 1;
  std::FILE* csv = outs[0].file;
  write_settings(outs[1].file, o, experiments, controllers);
  write_condition_settings(outs[1].file, runs, experiments);
  std::fprintf(outs[1].file, "sweep=%s=%s:%s:%d\novershoot_bound_pct=%s\nitae_ratio=%s\n",
               fuzzypid::name_of(sim::kSweepParameterNames, sw.parameter), fmt(sw.lo).c_str(),
               fmt(sw.hi).c_str(), sw.count, fmt(o.overshoot_bound_pct).c_str(),
               fmt(o.itae_ratio_bound).c_str());
  std::fprintf(outs[1].file, "divergence_rad=%s\n", fmt(o.divergence_rad).c_str());
  std::size_t faulted_runs = 0;
  std::fputs("controller,parameter,value,itae,max_overshoot_pct,faults,diverged,usable\n", csv);
  if (!o.quiet)
    std::printf("%-22s %-14s %-28s %s\n", "controller", "parameter", "usable range",
                "nominal ITAE");
  sim::SweepBounds bounds;
  bounds.overshoot_pct = o.overshoot_bound_pct;
  bounds.itae_ratio = o.itae_ratio_bound;
  bounds.divergence_rad = o.divergence_rad;
  const std::string parameter = fuzzypid::name_of(sim::kSweepParameterNames, sw.parameter);
  for (const auto& c : controllers) {
    const sim::SweepResult result = sim::run_sweep(ex, base, c.spec, sw, bounds);
    if (!result.ok) {
      std::fprintf(stderr, "sim_ab: %s: %s\n", c.name.c_str(), result.error.c_str());
      discard(outs);
      return 1;
    }
    for (const sim::SweepPoint& p : result.points) {
      if (p.fault_ticks != 0) {
        ++faulted_runs;
        std::fprintf(stderr, "sim_ab: fault: %s on %s=%s: %s\n", c.name.c_str(), parameter.c_str(),
                     fmt(p.value).c_str(), p.first_fault.c_str());
      }
      std::fprintf(csv, "%s,%s,%s,%s,%s,%zu,%d,%d\n", c.name.c_str(), parameter.c_str(),
                   fmt(p.value).c_str(), fmt(p.itae).c_str(), fmt(p.max_overshoot_pct).c_str(),
                   p.fault_ticks, p.diverged ? 1 : 0, p.usable ? 1 : 0);
    }
    if (!o.quiet) {
      char range[64] = "none";
      if (result.usable_count > 0)
        std::snprintf(range, sizeof range, "%.4g .. %.4g", result.points[result.usable_first].value,
                      result.points[result.usable_first + result.usable_count - 1].value);
      std::printf("%-22s %-14s %-28s %.4e\n", c.name.c_str(), parameter.c_str(), range,
                  result.nominal_itae);
    }
  }
  std::string error;
  if (!commit(outs, error)) {
    std::fprintf(stderr, "sim_ab: %s\n", error.c_str());
    discard(outs);
    return 1;
  }
  if (!o.quiet) std::fprintf(stderr, "sim_ab: wrote %s/sweep.csv\n", o.out_dir.c_str());
  return faults_exit(o, faulted_runs);
}

// The controller files of a front written by `fuzzypid tune --front-out DIR`, in the order of
// DIR/front.csv (its `file` column, each a file in DIR); false with `error` when the folder holds
// no readable front.
bool front_files(const std::string& dir, std::vector<std::string>& files, std::string& error) {
  constexpr std::size_t kMaxFrontBytes = std::size_t{16} << 20;
  const std::string csv = (fs::path(dir) / "front.csv").string();
  std::string text;
  if (!support::read_file_bounded(csv, kMaxFrontBytes, text, error)) {
    error = dir + " is a folder but not a front: " + error;
    return false;
  }
  std::size_t begin = 0, line = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    const std::string row = text.substr(begin, end - begin);
    begin = end + 1;
    ++line;
    if (line == 1) {
      if (row.rfind("point,file,", 0) != 0) {
        error = csv + ": line 1 is not a front's header (point,file,...)";
        return false;
      }
      continue;
    }
    if (row.empty()) continue;
    const std::size_t a = row.find(',');
    const std::size_t b = a == std::string::npos ? a : row.find(',', a + 1);
    const std::string file = b == std::string::npos ? "" : row.substr(a + 1, b - a - 1);
    if (file.empty() || file == "." || file == ".." || file.find('/') != std::string::npos) {
      error = csv + ": line " + std::to_string(line) + ": no file of the front's folder";
      return false;
    }
    files.push_back((fs::path(dir) / file).string());
  }
  if (files.empty()) {
    error = csv + ": a front of no point";
    return false;
  }
  return true;
}

// Replaces each front folder among --controller's files by its points, named FOLDER_point_NNN
// (`prefixes`: each file's name prefix, empty for a file). Empty, or the exit code.
std::optional<int> expand_fronts(sim_ab::Options& o, std::vector<std::string>& prefixes) {
  {
    std::vector<std::string> expanded;
    for (const std::string& path : o.controllers) {
      std::error_code ec;
      if (!fs::is_directory(path, ec)) {
        expanded.push_back(path);
        prefixes.emplace_back();
        continue;
      }
      std::string error;
      std::vector<std::string> points;
      if (!front_files(path, points, error)) {
        std::fprintf(stderr, "sim_ab: --controller: %s\n", error.c_str());
        return 1;
      }
      const std::string folder = fs::path(path).lexically_normal().filename().string();
      for (const std::string& p : points) {
        expanded.push_back(p);
        prefixes.push_back(
            (folder.empty() ? fs::path(path).lexically_normal().parent_path().filename().string()
                            : folder) +
            "_");
      }
    }
    o.controllers = expanded;
  }
  return std::nullopt;
}

// The output folder is checked before any work (apps/common/output_files.hpp): a refused --out
// is a usage error, like a bad option. Empty, or the exit code.
std::optional<int> check_out_dir(const sim_ab::Options& o) {
  {
    std::vector<std::string> inputs = o.controllers;
    inputs.push_back(o.conditions_file);
    inputs.push_back(o.robot.setup.urdf.empty() ? robot::default_urdf_path() : o.robot.setup.urdf);
    if (!o.robot.setup.path.empty()) inputs.push_back(o.robot.setup.path);
    if (const std::string bad = cli::check_output_dir(o.out_dir, kOutputNames, inputs);
        !bad.empty()) {
      std::fprintf(stderr, "sim_ab: --out: %s\n", bad.c_str());
      return 2;
    }
  }

  return std::nullopt;
}

// Controllers: the files, or the paper's two. Empty, or the exit code.
std::optional<int> load_controllers(const sim_ab::Options& o,
                                    const std::vector<std::string>& prefixes,
                                    std::vector<NamedController>& controllers) {
  for (std::size_t k = 0; k < o.controllers.size(); ++k) {
    const std::string& path = o.controllers[k];
    NamedController c;
    fuzzypid::FileError err;
    cf::ControllerFile file;
    if (!cf::load(path, file, err)) {
      std::fprintf(stderr, "sim_ab: %s\n", err.to_string().c_str());
      return 1;
    }
    c.spec = std::move(file.controller);
    c.tuning = std::move(file.tuning);
    c.margins = std::move(file.margins);
    c.name = prefixes[k] + fs::path(path).stem().string();
    c.source = path;
    for (const auto& other : controllers) {
      if (other.name == c.name) {
        std::fprintf(stderr, "sim_ab: two controller files named '%s'\n", c.name.c_str());
        return 2;
      }
    }
    controllers.push_back(std::move(c));
  }
  if (controllers.empty()) {
    controllers.push_back({"pid", "built-in",
                           sim::default_controller(o.experiment, controller::paper_pid()),
                           std::nullopt, std::nullopt});
    controllers.push_back({"fuzzy", "built-in",
                           sim::default_controller(o.experiment, controller::paper_fuzzy()),
                           std::nullopt, std::nullopt});
  }

  return std::nullopt;
}

// The runs: a condition file's sets, or the scenario(s) with the overrides; checked against the
// options and the controllers. Empty, or the exit code.
std::optional<int> gather_runs(const sim_ab::Options& o,
                               const std::vector<NamedController>& controllers,
                               std::vector<Run>& runs) {
  if (!o.conditions_file.empty()) {
    sim::ConditionFile file;
    fuzzypid::FileError err;
    if (!sim::load_conditions(o.conditions_file, file, err)) {
      std::fprintf(stderr, "sim_ab: %s\n", err.to_string().c_str());
      return 1;
    }
    std::vector<std::string> sets = o.sets;
    if (sets.empty())
      for (const auto& s : file.sets)
        sets.push_back(s.name);
    for (const std::string& name : sets) {
      const sim::ConditionSet* set = file.find(name);
      if (set == nullptr) {
        std::fprintf(stderr, "sim_ab: %s has no set '%s' (it has: %s)\n", o.conditions_file.c_str(),
                     name.c_str(), file.set_names().c_str());
        return 2;
      }
      for (const auto& c : set->conditions)
        runs.push_back({set->name, c});
    }
  } else {
    for (const auto& c : sim_ab::scenario_conditions(o))
      runs.push_back({"scenario", c});
  }
  // --strict-rules and --seed shape supervisors and measurement noise: refused where none is run.
  bool supervised = false, noisy = false;
  for (const auto& c : controllers)
    supervised = supervised || controller::family_traits(c.spec.family).supervised();
  for (const auto& r : runs)
    noisy = noisy || r.condition.noise_position_rad > 0.0 || r.condition.noise_velocity_rad_s > 0.0;
  for (const std::string& bad :
       {o.given.refuse_unused({"--strict-rules"}, supervised, "a controller with a supervisor",
                              "every --controller is a pid controller, which has none"),
        o.given.refuse_unused({"--seed"}, noisy, "a run with measurement noise",
                              "no selected condition has any (--noise, or --scenario noise)")})
    if (!bad.empty()) {
      std::fprintf(stderr, "sim_ab: %s\n", bad.c_str());
      return 2;
    }
  for (const auto& r : runs) {
    if (const std::string bad = r.condition.validate(); !bad.empty()) {
      std::fprintf(stderr, "sim_ab: condition %s: %s\n", r.condition.name.c_str(), bad.c_str());
      return 2;
    }
  }

  // The robots and paths a condition file names are inputs too.
  for (const Run& r : runs)
    for (const std::string& input : {r.condition.robot.urdf, r.condition.robot.path})
      if (!input.empty()) {
        if (const std::string bad = cli::check_output_dir(o.out_dir, kOutputNames, {input});
            !bad.empty()) {
          std::fprintf(stderr, "sim_ab: --out: %s\n", bad.c_str());
          return 2;
        }
      }
  return std::nullopt;
}

// What a user should hear before the runs: the robots and plants, the model's notes, and what
// the controller files say they were made for against what they now run on.
void print_setup_notes(const sim_ab::Options& o, const sim::ExperimentSet& experiments,
                       const std::vector<Run>& runs,
                       const std::vector<NamedController>& controllers) {
  for (std::size_t k = 0; k < experiments.size(); ++k) {
    const sim::Experiment& ex = experiments.experiment(k);
    if (!o.quiet) {
      cli::print_robot_note("sim_ab", ex);
      // The plants of the conditions on this robot, each with how many conditions run on it.
      std::vector<std::pair<std::string, std::size_t>> plants;
      for (std::size_t i = 0; i < runs.size(); ++i) {
        if (&experiments.of(i) != &ex) continue;
        const std::string note = cli::plant_note(runs[i].condition);
        auto it = std::find_if(plants.begin(), plants.end(),
                               [&note](const auto& p) { return p.first == note; });
        if (it == plants.end()) {
          plants.emplace_back(note, 1);
        } else {
          ++it->second;
        }
      }
      for (const auto& [note, count] : plants)
        std::fprintf(stderr, "sim_ab: plant %s (%zu condition%s)\n", note.c_str(), count,
                     count == 1 ? "" : "s");
    }
    cli::print_model_notes("sim_ab", ex);
    for (const auto& c : controllers)
      if (c.source != "built-in") {
        cli::warn_about_training("sim_ab", c.source, c.tuning ? &*c.tuning : nullptr, ex);
        cli::warn_about_conditions("sim_ab", c.source, c.tuning ? &*c.tuning : nullptr,
                                   o.conditions_file);
      }
    for (const auto& c : controllers)
      if (c.spec.units.form == controller::PidForm::PerTick &&
          std::fabs(c.spec.units.tick_s - ex.options().tick_s) > 1e-12 && !o.quiet)
        std::fprintf(stderr,
                     "sim_ab: note: %s's per-tick gains refer to a %g s tick; they are converted "
                     "to continuous gains and run at a %g s tick\n",
                     c.name.c_str(), c.spec.units.tick_s, ex.options().tick_s);
  }
  // What the controller files say they were made for, against what they now run on.
  for (const auto& c : controllers) {
    for (std::size_t k = 0; k < experiments.size(); ++k)
      if (const std::string why = sim::tick_mismatch(c.tuning ? c.tuning->tick_s : 0.0,
                                                     experiments.experiment(k).options().tick_s);
          !why.empty()) {
        std::fprintf(stderr, "sim_ab: warning: %s: %s\n", c.name.c_str(), why.c_str());
        break;
      }
    std::size_t without_gravity = 0;
    for (const Run& r : runs)
      if (const std::string why = sim::feedforward_mismatch(c.spec, r.condition); !why.empty())
        if (++without_gravity == 1)
          std::fprintf(stderr, "sim_ab: warning: %s: %s\n", c.name.c_str(), why.c_str());
    if (without_gravity > 1)
      std::fprintf(stderr, "sim_ab: warning: %s: the same on %zu conditions in all\n",
                   c.name.c_str(), without_gravity);
  }
  for (std::size_t k = 0; k < runs.size(); ++k)
    cli::warn_about_payload("sim_ab", experiments.of(k), runs[k].condition);
  // The margins a controller file records ([margins], written by `fuzzypid tune`): the worst
  // joint of each, and whether it was certified. `fuzzypid certify` recomputes them for any plant.
  for (const auto& c : controllers) {
    if (!c.margins || o.quiet) continue;
    const controller::MarginRecord& m = *c.margins;
    const auto worst = [](const controller::MarginRecord::PerJoint& v) {
      return *std::min_element(v.begin(), v.end());
    };
    std::fprintf(stderr,
                 "sim_ab: margins of %s (recorded over %s [%s]): disk %.3f, gain %.2f dB, phase "
                 "%.1f deg, delay %.1f ms (worst joint); %s\n",
                 c.name.c_str(), m.conditions.c_str(), m.set.c_str(), worst(m.disk_margin),
                 worst(m.gain_margin_db), worst(m.phase_margin_deg), worst(m.delay_margin_ms),
                 m.verdict.c_str());
  }
}

// Runs every controller on every condition and writes the outputs (all or none). The exit code.
int run_and_write(const sim_ab::Options& o, const sim::ExperimentSet& experiments,
                  const std::vector<Run>& runs, const std::vector<NamedController>& controllers) {
  std::string error;
  Outputs outs;
  if (!open_outputs(
          o.out_dir,
          {"trajectory.csv", "metrics.csv", "endeffector.csv", "conditions.csv", "settings.txt"},
          outs))
    return 1;
  std::FILE* traj = outs[0].file;
  std::FILE* metrics = outs[1].file;
  std::FILE* tip = outs[2].file;
  std::FILE* conds = outs[3].file;
  write_settings(outs[4].file, o, experiments, controllers);
  write_condition_settings(outs[4].file, runs, experiments);
  std::fprintf(outs[4].file, "divergence_rad=%s\n", fmt(o.divergence_rad).c_str());
  std::fputs(
      "scenario,controller,t,joint,theta_d,theta,error,error_rate,u,kp,ki,kd,tau_nm,omega_rad_s\n",
      traj);
  std::fputs(
      "scenario,controller,joint,settling_time_s,overshoot_pct,max_abs_error_rad,rms_error_rad,"
      "iae,itae,max_abs_error_after_1s_rad,faults,no_rule_ticks,clamped_gain_ticks,"
      "reversals_pct,sign_changes_pct,saturated_pct,tau_rms_nm,torque_variation_nm_per_s,"
      "tcp_error_max_mm,tcp_error_rms_mm,divergence_ticks,joint_limit_ticks,limit_cycle_ticks\n",
      metrics);
  std::fputs("scenario,controller,t,x_d,y_d,z_d,x,y,z\n", tip);
  // The robot and plant columns come last (readers by name keep working); the armature is six
  // values separated by ';'.
  std::fputs(
      "scenario,set,payload_scale,friction,torque_limit,contact,noise_q,noise_qd,seed,reverse,"
      "initial_error,urdf,path,tick_s,payload_kg,dynamics,gravity,armature_kgm2,plant_step_ms,"
      "delay_ms,torque_bandwidth_hz,encoder_counts,coulomb_nm,stribeck_nm,stribeck_velocity,"
      "coulomb_smoothing,"
      "joint_resonance_hz,joint_damping_ratio,backlash_rad\n",
      conds);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Run& r = runs[k];
    const auto& c = r.condition;
    const sim::Experiment& ex = experiments.of(k);
    // The effects' values only, in the header's order.
    std::string effects;
    for (const std::string& field : split_fields(effects_text(c.effects, "|", ";")))
      effects += "," + field.substr(field.find('=') + 1);
    std::fprintf(conds, "%s,%s,%s,%s,%s,%s,%s,%s,%llu,%d,%s,%s,%s,%s,%s,%s,%d,%s%s\n",
                 c.name.c_str(), r.set.c_str(), fmt(c.payload_scale).c_str(),
                 fmt(c.friction_per_s).c_str(), fmt(c.torque_limit_rad_s2).c_str(),
                 fmt(c.contact_rad_s2).c_str(), fmt(c.noise_position_rad).c_str(),
                 fmt(c.noise_velocity_rad_s).c_str(), static_cast<unsigned long long>(c.seed),
                 c.reverse ? 1 : 0, fmt(c.initial_error_rad).c_str(),
                 csv_field(ex.urdf_file()).c_str(),
                 csv_field(ex.setup().path.empty() ? "line" : ex.setup().path).c_str(),
                 fmt(ex.options().tick_s).c_str(), fmt(c.payload_kg).c_str(),
                 fuzzypid::name_of(sim::kDynamicsNames, c.dynamics), c.gravity ? 1 : 0,
                 joined(ex.armature_kgm2(), ";").c_str(), effects.c_str());
  }

  if (!o.quiet)
    std::printf("%-10s %-26s %-18s %11s %10s %10s %12s %7s %7s %7s %9s\n", "set", "condition",
                "controller", "ITAE", "overshoot%", "settle_s", "max|e|>1s", "rev%", "sign%",
                "sat%", "tcp_mm");
  std::size_t faulted_runs = 0;
  std::size_t no_rule_runs = 0;
  std::size_t done = 0;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Run& run = runs[k];
    const sim::Experiment& experiment = experiments.of(k);
    const robot::RobotModel& model = experiment.model();
    ++done;
    const sim::Condition& cond = run.condition;
    if (!o.quiet && runs.size() > 1)
      std::fprintf(stderr, "sim_ab: [%zu/%zu] %s\n", done, runs.size(), cond.name.c_str());
    for (const NamedController& ctl : controllers) {
      const char* cname = ctl.name.c_str();
      sim::RunLimits limits;
      limits.divergence_rad = o.divergence_rad;
      const sim::RunResult r = experiment.run(cond, ctl.spec, limits);
      if (!r.ok) {
        std::fprintf(stderr, "sim_ab: condition %s, controller %s: %s\n", cond.name.c_str(), cname,
                     r.error.c_str());
        discard(outs);
        return 1;
      }
      for (const auto& row : r.rows) {
        std::fprintf(traj, "%s,%s,%s,%d,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", cond.name.c_str(), cname,
                     fmt(row.t_s).c_str(), row.joint, fmt(row.theta_d).c_str(),
                     fmt(row.theta).c_str(), fmt(row.error).c_str(), fmt(row.error_rate).c_str(),
                     fmt(row.u).c_str(), fmt(row.kp).c_str(), fmt(row.ki).c_str(),
                     fmt(row.kd).c_str(), fmt(row.tau_nm).c_str(), fmt(row.omega_rad_s).c_str());
      }
      // End-effector path (Fig. 9): FK of the reference and of the joint angles at each tick.
      const sim::TcpTrack track = sim::tcp_track(model, r.rows);
      for (std::size_t k = 0; k < track.t_s.size(); ++k) {
        const Eigen::Vector3d& pd = track.desired_m[k];
        const Eigen::Vector3d& p = track.actual_m[k];
        std::fprintf(tip, "%s,%s,%s,%s,%s,%s,%s,%s,%s\n", cond.name.c_str(), cname,
                     fmt(track.t_s[k]).c_str(), fmt(pd.x()).c_str(), fmt(pd.y()).c_str(),
                     fmt(pd.z()).c_str(), fmt(p.x()).c_str(), fmt(p.y()).c_str(),
                     fmt(p.z()).c_str());
      }
      const sim::TcpErrorMetrics tcp = sim::tcp_error_metrics(track);
      const auto m = sim::run_metrics(r.rows, experiment.options().tick_s);
      const auto d = sim::run_drive_metrics(r.rows);
      const sim::TrackingFaults& tf = r.tracking_faults;
      for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
        std::fprintf(
            metrics,
            "%s,%s,%zu,%s,%s,%s,%s,%s,%s,%s,%zu,%zu,%zu,%s,%s,%s,%s,%s,%s,%s,%zu,%zu,%zu\n",
            cond.name.c_str(), cname, i + 1, fmt(m[i].settling_time_s).c_str(),
            fmt(m[i].overshoot_pct).c_str(), fmt(m[i].max_abs_error_rad).c_str(),
            fmt(m[i].rms_error_rad).c_str(), fmt(m[i].iae).c_str(), fmt(m[i].itae).c_str(),
            fmt(m[i].max_abs_error_after_1s_rad).c_str(), r.fault_ticks, r.no_rule_ticks[i],
            r.clamped_gain_ticks[i], fmt(d[i].reversals_pct).c_str(),
            fmt(d[i].sign_changes_pct).c_str(), fmt(d[i].saturated_pct).c_str(),
            fmt(d[i].tau_rms_nm).c_str(), fmt(d[i].torque_variation_nm_per_s).c_str(),
            fmt(tcp.max_mm).c_str(), fmt(tcp.rms_mm).c_str(), tf.divergence[i].ticks,
            tf.joint_limit[i].ticks, tf.limit_cycle[i].ticks);
      }
      const sim::RunSummary s = sim::summarize(m, d);
      if (!o.quiet)
        std::printf("%-10s %-26s %-18s %11.4e %10.3g %10.3g %12.3e %7.1f %7.1f %7.1f %9.3g\n",
                    run.set.c_str(), cond.name.c_str(), cname, s.itae, s.max_overshoot_pct,
                    s.max_settling_s, s.max_error_after_1s_rad, s.max_reversals_pct,
                    s.max_sign_changes_pct, s.max_saturated_pct, tcp.max_mm);
      std::size_t no_rule = 0;
      for (std::size_t n : r.no_rule_ticks)
        no_rule += n;
      if (no_rule != 0) {
        ++no_rule_runs;
        std::fprintf(stderr,
                     "sim_ab: %s: %s/%s: on %zu joint-ticks the supervisor fired no rule and the "
                     "gains stayed where they were (metrics.csv no_rule_ticks)\n",
                     o.strict_rules ? "error" : "warning", cond.name.c_str(), cname, no_rule);
      }
      if (r.controller_faults != 0)
        std::fprintf(stderr, "sim_ab: fault: %s on %s: %zu controller faults\n", cname,
                     cond.name.c_str(), r.controller_faults);
      report_faults(r, experiment, o.divergence_rad, ctl.name, cond.name);
      if (r.fault_ticks != 0) ++faulted_runs;
    }
  }
  if (!commit(outs, error)) {
    std::fprintf(stderr, "sim_ab: %s\n", error.c_str());
    discard(outs);
    return 1;
  }
  if (!o.quiet)
    std::fprintf(stderr, "sim_ab: wrote %s/{trajectory,metrics,endeffector,conditions}.csv\n",
                 o.out_dir.c_str());
  if (faults_exit(o, faulted_runs) != 0) return 1;
  if (no_rule_runs != 0 && o.strict_rules) {
    std::fprintf(stderr,
                 "sim_ab: %zu run(s) in which a supervisor fired no rule (--strict-rules)\n",
                 no_rule_runs);
    return 1;
  }
  return 0;
}

int run_sim_ab(int argc, char** argv) {
  sim_ab::Options o;
  switch (sim_ab::parse(argc, argv, o)) {
    case sim_ab::ParseResult::Exit:
      return 0;
    case sim_ab::ParseResult::UsageError:
      return 2;
    case sim_ab::ParseResult::Run:
      break;
  }
  std::vector<std::string> prefixes;
  if (const auto exit = expand_fronts(o, prefixes)) return *exit;
  if (const auto exit = check_out_dir(o)) return *exit;
  std::vector<NamedController> controllers;
  if (const auto exit = load_controllers(o, prefixes, controllers)) return *exit;
  std::vector<Run> runs;
  if (const auto exit = gather_runs(o, controllers, runs)) return *exit;
  // One experiment per robot setup (URDF, path, tick): built before any output is opened.
  std::vector<sim::Condition> conditions;
  conditions.reserve(runs.size());
  for (const auto& r : runs)
    conditions.push_back(r.condition);
  std::string error;
  const auto experiments = sim::ExperimentSet::create(conditions, o.experiment, error);
  if (!experiments) {
    std::fprintf(stderr, "sim_ab: %s\n", error.c_str());
    return 1;
  }
  print_setup_notes(o, *experiments, runs, controllers);
  if (o.sweep) return run_sweep(o, *experiments, runs, controllers);
  return run_and_write(o, *experiments, runs, controllers);
}

}  // namespace

// A run whose messages on standard error did not all reach it (a lost fault or warning) exits 1.
int main(int argc, char** argv) {
  return fuzzypid::cli::run_main("sim_ab", [&] { return run_sim_ab(argc, argv); });
}
