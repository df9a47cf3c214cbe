// `fuzzypid certify CONTROLLER`: the frozen-gain margins of each joint's linear loop over the
// inertia range of the conditions (sim/certify.hpp, docs/margins.md), as a table or JSON.
// Exit 0 certified, 1 not certified, 2 bad usage or an input that cannot be read. With --record the
// certificate also replaces the file's [margins] record (1 too when that write fails).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/condition_set.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "output_files.hpp"
#include "robot_options.hpp"

namespace fuzzypid::cli {
namespace {

struct CertifyCli {
  std::string controller;
  std::string conditions;
  std::string set = "held-out";
  bool set_given = false;
  std::size_t grid = 25;
  bool json = false;
  bool record = false;  // write the certificate into the file's [margins]
  RobotOptions robot;
};

// A JSON number, null when not finite (JSON has no infinity).
std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The delay of a case's loop, ms.
double delay_ms(const sim::MarginCase& c) {
  return (c.loop.delay_ticks + c.loop.delay_fraction) * c.loop.tick_s * 1e3;
}

void print_case_json(const char* name, const sim::MarginCase& c, bool last) {
  std::printf(
      "      \"%s\": {\"inertia_kgm2\": %s, \"damping_nms\": %s, \"tick_s\": %s, "
      "\"delay_ms\": %s, \"gear_resonance_hz\": %s, \"kp\": %s, \"ki\": %s, \"kd\": %s, "
      "\"x\": %s, \"y\": %s}%s\n",
      name, num(c.inertia_kgm2).c_str(), num(c.damping_nms).c_str(), num(c.tick_s).c_str(),
      num(delay_ms(c)).c_str(), num(c.loop.gear_resonance_hz).c_str(), num(c.gains.kp).c_str(),
      num(c.gains.ki).c_str(), num(c.gains.kd).c_str(), num(c.x).c_str(), num(c.y).c_str(),
      last ? "" : ",");
}

void print_json(const CertifyCli& o, const sim::Certificate& cert) {
  std::printf("{\n  \"controller\": \"%s\",\n  \"family\": \"%s\",\n  \"moving_gains\": %s,\n",
              o.controller.c_str(), controller::to_string(cert.family),
              cert.moving_gains ? "true" : "false");
  std::printf("  \"delay_ms\": %s,\n  \"conditions\": %zu,\n  \"joints\": [\n",
              num(cert.delay_s * 1e3).c_str(), cert.conditions);
  for (std::size_t i = 0; i < cert.joints.size(); ++i) {
    const sim::JointCertificate& j = cert.joints[i];
    const sim::LoopMargins& disk = j.worst_disk.margins;
    std::printf("    {\n      \"joint\": %zu,\n      \"stable\": %s,\n", i + 1,
                j.stable ? "true" : "false");
    std::printf("      \"inertia_kgm2\": [%s, %s],\n      \"nominal_inertia_kgm2\": %s,\n",
                num(j.inertia_min_kgm2).c_str(), num(j.inertia_max_kgm2).c_str(),
                num(j.nominal_inertia_kgm2).c_str());
    std::printf("      \"damping_nms\": [%s, %s],\n", num(j.damping_min_nms).c_str(),
                num(j.damping_max_nms).c_str());
    std::printf("      \"gain_margin_db\": %s,\n      \"gain_margin_low_db\": %s,\n",
                num(j.worst_gain.margins.gain_margin_db).c_str(),
                num(j.worst_gain_low.margins.gain_margin_low_db).c_str());
    std::printf("      \"phase_margin_deg\": %s,\n      \"delay_margin_ms\": %s,\n",
                num(j.worst_phase.margins.phase_margin_deg).c_str(),
                num(j.worst_delay.margins.delay_margin_s * 1e3).c_str());
    std::printf("      \"delay_margin_exact_ms\": %s,\n      \"delay_margin_ticks\": %d,\n",
                num(j.worst_delay.margins.delay_margin_exact_s * 1e3).c_str(),
                j.worst_delay.margins.delay_margin_ticks);
    std::printf(
        "      \"disk_margin\": %s,\n      \"disk_gain_db\": [%s, %s],\n"
        "      \"disk_phase_deg\": %s,\n",
        num(disk.disk_margin).c_str(), num(sim::to_db(disk.disk_gain_low)).c_str(),
        num(sim::to_db(disk.disk_gain_high)).c_str(), num(disk.disk_phase_deg).c_str());
    std::printf("      \"gain_triples\": %zu,\n      \"cases\": %zu,\n", j.gain_triples, j.cases);
    const sim::GainBox& b = j.gain_box;
    std::printf("      \"gain_box\": {\"kp\": [%s, %s], \"ki\": [%s, %s], \"kd\": [%s, %s]},\n",
                num(b.low.kp).c_str(), num(b.high.kp).c_str(), num(b.low.ki).c_str(),
                num(b.high.ki).c_str(), num(b.low.kd).c_str(), num(b.high.kd).c_str());
    const sim::LyapunovCertificate& l = j.lyapunov;
    std::printf(
        "      \"lyapunov\": {\"certified\": %s, \"contraction_per_tick\": %s, "
        "\"condition_number\": %s, \"states\": %zu, \"vertices\": %zu, \"plant_groups\": %zu, "
        "\"inertia_intervals\": %zu, \"switching_radius\": %s, \"switching_period\": %zu, "
        "\"reason\": \"%s\"},\n",
        l.certified ? "true" : "false", num(l.contraction).c_str(), num(l.condition_number).c_str(),
        l.states, l.vertices, j.plant_groups, l.inertia_intervals, num(l.switching_radius).c_str(),
        l.switching_period, l.reason.c_str());
    std::printf("      \"certified\": %s,\n", j.certified ? "true" : "false");
    print_case_json("worst_gain_at", j.worst_gain, false);
    print_case_json("worst_phase_at", j.worst_phase, false);
    print_case_json("worst_delay_at", j.worst_delay, false);
    print_case_json("worst_disk_at", j.worst_disk, true);
    std::printf("    }%s\n", i + 1 < cert.joints.size() ? "," : "");
  }
  std::printf("  ],\n  \"certified\": %s,\n  \"verdict\": \"%s\",\n  \"assumptions\": \"%s\"\n}\n",
              cert.certified ? "true" : "false", cert.verdict.c_str(), sim::lyapunov_assumptions());
}

void print_table(const CertifyCli& o, const sim::Certificate& cert) {
  std::printf(
      "controller %s (%s), %zu condition(s), extra delay %g ms (elastic gears also at their "
      "conditions' own): frozen-gain margins\n",
      o.controller.c_str(), controller::to_string(cert.family), cert.conditions,
      cert.delay_s * 1e3);
  std::printf("%-5s %-21s %9s %9s %10s %9s %9s %9s %5s %7s %8s %7s %6s\n", "joint", "J kg·m²", "J^",
              "GM dB", "GM low dB", "PM deg", "DM ms", "exact ms", "ticks", "disk α", "±dB", "±deg",
              "stable");
  for (std::size_t i = 0; i < cert.joints.size(); ++i) {
    const sim::JointCertificate& j = cert.joints[i];
    const sim::LoopMargins& disk = j.worst_disk.margins;
    char range[48];
    std::snprintf(range, sizeof range, "%.4g..%.4g", j.inertia_min_kgm2, j.inertia_max_kgm2);
    std::printf("%-5zu %-21s %9.4g %9.3f %10.3f %9.2f %9.2f %9.2f %5d %7.3f %8.2f %7.2f %6s\n",
                i + 1, range, j.nominal_inertia_kgm2, j.worst_gain.margins.gain_margin_db,
                j.worst_gain_low.margins.gain_margin_low_db, j.worst_phase.margins.phase_margin_deg,
                j.worst_delay.margins.delay_margin_s * 1e3,
                j.worst_delay.margins.delay_margin_exact_s * 1e3,
                j.worst_delay.margins.delay_margin_ticks, disk.disk_margin,
                sim::to_db(disk.disk_gain_high), disk.disk_phase_deg, j.stable ? "yes" : "NO");
  }
  std::printf(
      "worst disk margin at (J kg·m², b N·m·s/rad, delay ms, gear Hz, Kp, Ki 1/s, Kd s; x = Ke e, "
      "y = Kec ec):\n");
  for (std::size_t i = 0; i < cert.joints.size(); ++i) {
    const sim::MarginCase& w = cert.joints[i].worst_disk;
    std::printf("  joint %zu: J %.6g, b %.6g, delay %.6g, ", i + 1, w.inertia_kgm2, w.damping_nms,
                delay_ms(w));
    if (w.loop.gear_resonance_hz > 0.0)
      std::printf("gear %.4g, ", w.loop.gear_resonance_hz);
    else
      std::printf("rigid, ");
    std::printf("gains %.6g %.6g %.6g, x %.3g, y %.3g (%zu gain triples, %zu loops)\n", w.gains.kp,
                w.gains.ki, w.gains.kd, w.x, w.y, cert.joints[i].gain_triples,
                cert.joints[i].cases);
  }
  std::printf(
      "gains switching every tick inside their box (Kp, Ki 1/s, Kd s), inertia anywhere in "
      "its range: common quadratic Lyapunov function (docs/margins.md)\n");
  for (std::size_t i = 0; i < cert.joints.size(); ++i) {
    const sim::JointCertificate& j = cert.joints[i];
    const sim::GainBox& b = j.gain_box;
    std::printf("  joint %zu: Kp %.6g..%.6g, Ki %.6g..%.6g, Kd %.6g..%.6g: ", i + 1, b.low.kp,
                b.high.kp, b.low.ki, b.high.ki, b.low.kd, b.high.kd);
    if (j.lyapunov.certified)
      std::printf(
          "certified, |x|_P shrinks by 1 - %.3g per tick (%zu states, %zu vertices, inertia in %zu "
          "interval%s)\n",
          1.0 - j.lyapunov.contraction, j.lyapunov.states, j.lyapunov.vertices,
          j.lyapunov.inertia_intervals, j.lyapunov.inertia_intervals == 1 ? "" : "s");
    else
      std::printf("NOT certified: %s\n", j.lyapunov.reason.c_str());
  }
  std::printf("assumptions: %s\n", sim::lyapunov_assumptions());
  std::printf("%s\n", cert.verdict.c_str());
}

int run_certify(const CertifyCli& o) {
  const char* tool = "fuzzypid certify";
  controller_file::ControllerFile controller_file;
  fuzzypid::FileError err;
  if (!controller_file::load(o.controller, controller_file, err)) {
    std::fprintf(stderr, "%s: %s\n", tool, err.to_string().c_str());
    return kExitUsage;
  }
  const controller::ControllerSpec& spec = controller_file.controller;
  std::vector<sim::Condition> conditions;
  if (!o.conditions.empty()) {
    warn_about_conditions(tool, o.controller,
                          controller_file.tuning ? &*controller_file.tuning : nullptr,
                          o.conditions);
    sim::ConditionFile file;
    if (!sim::load_conditions(o.conditions, file, err)) {
      std::fprintf(stderr, "%s: %s\n", tool, err.to_string().c_str());
      return kExitUsage;
    }
    const sim::ConditionSet* set = file.find(o.set);
    if (set == nullptr) {
      std::fprintf(stderr, "%s: --set: %s has no set '%s' (it has: %s)\n", tool,
                   o.conditions.c_str(), o.set.c_str(), file.set_names().c_str());
      return kExitUsage;
    }
    conditions = set->conditions;
  } else {
    sim::Condition c;
    o.robot.apply(c);
    if (const std::string bad = c.validate(); !bad.empty()) {
      std::fprintf(stderr, "%s: %s\n", tool, bad.c_str());
      return kExitUsage;
    }
    conditions.push_back(c);
  }
  std::string error;
  const auto experiments = sim::ExperimentSet::create(conditions, sim::ExperimentOptions{}, error);
  if (!experiments) {
    std::fprintf(stderr, "%s: %s\n", tool, error.c_str());
    return kExitUsage;
  }
  for (std::size_t k = 0; k < experiments->size(); ++k) {
    const double tick = experiments->experiment(k).options().tick_s;
    if (spec.units.form == controller::PidForm::PerTick &&
        std::fabs(spec.units.tick_s - tick) > 1e-12)
      std::fprintf(stderr,
                   "%s: note: %s's per-tick gains refer to a %g s tick; they are converted to "
                   "continuous gains and run at a %g s tick (as sim_ab runs them)\n",
                   tool, o.controller.c_str(), spec.units.tick_s, tick);
  }
  sim::CertifyOptions options;
  // The delay of the plant (--delay-ms, shared with sim_ab, or the conditions' delay_ms): the
  // largest the conditions have, as the worst case.
  options.delay_s = sim::largest_delay_s(conditions);
  options.grid_points = o.grid;
  const auto cert = sim::certify(spec, conditions, *experiments, options, error);
  if (!cert) {
    std::fprintf(stderr, "%s: %s\n", tool, error.c_str());
    return kExitUsage;
  }
  if (o.json)
    print_json(o, *cert);
  else
    print_table(o, *cert);
  if (o.record) {
    // The record a tune writes, over the conditions named as the file names its files; the rest
    // of the file is rewritten as the tuner writes it.
    controller_file.margins = sim::margin_record(*cert);
    controller_file.margins->conditions = path_from_folder_of(o.controller, o.conditions);
    controller_file.margins->set = o.set;
    if (const std::string bad =
            write_output_file(o.controller, controller_file::to_toml(controller_file), tool);
        !bad.empty()) {
      std::fprintf(stderr, "%s: --record: %s\n", tool, bad.c_str());
      return kExitFailure;
    }
  }
  return cert->certified ? kExitOk : kExitFailure;
}

}  // namespace

void add_certify_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<CertifyCli>();
  CLI::App* cmd = app.add_subcommand(
      "certify",
      "Frozen-gain stability margins (gain, phase, delay, disk; MATLAB's allmargin/diskmargin "
      "definitions) of each joint's linear loop over the inertia range of the conditions, and a "
      "common quadratic Lyapunov function for gains that change every tick inside their box "
      "(docs/margins.md). Exit 0 certified, 1 not certified, 2 bad usage or unreadable input.");
  cmd->add_option("controller", o->controller, "controller file (TOML)")->required();
  CLI::Option* conditions =
      cmd->add_option("--conditions", o->conditions,
                      "condition file (e.g. tuning/robust.toml) instead of the robot options")
          ->option_text("FILE");
  CLI::Option* set = cmd->add_option("--set", o->set, "the set of --conditions (default held-out)")
                         ->option_text("NAME");
  cmd->add_option("--grid", o->grid,
                  "points per axis of the (Ke e, Kec ec) grid over [-1, 1] for moving-gain "
                  "families (default 25)")
      ->check(CLI::Range(3, 201))
      ->option_text("N");
  cmd->add_flag("--json", o->json, "JSON on stdout instead of the table");
  CLI::Option* record = cmd->add_flag(
      "--record", o->record,
      "also write the certificate into the controller file's [margins] record, as `fuzzypid "
      "tune` records it (needs --conditions and the default --grid; the file is rewritten as "
      "the tuner writes it)");
  add_robot_options(*cmd, o->robot, true);
  cmd->callback([&run, o, conditions, set, record] {
    if (const std::string bad = check_robot_options(o->robot); !bad.empty())
      throw CLI::ValidationError(bad);
    if (conditions->count() > 0 && o->robot.any())
      throw CLI::ValidationError("--conditions",
                                 "the conditions name their robots: give no robot options");
    if (set->count() > 0 && conditions->count() == 0)
      throw CLI::ValidationError("--set", "needs --conditions");
    if (record->count() > 0 && conditions->count() == 0)
      throw CLI::ValidationError("--record", "needs --conditions (the record names them)");
    if (record->count() > 0 && o->grid != CertifyCli{}.grid)
      throw CLI::ValidationError("--record",
                                 "records the certificate on the default --grid, as the tuner "
                                 "does: give no --grid");
    run = [o] { return run_certify(*o); };
  });
}

}  // namespace fuzzypid::cli
