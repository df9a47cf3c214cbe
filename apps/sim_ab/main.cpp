// sim_ab: the paper's A/B experiment (section 6, Figs. 9-14) -- fixed PID vs fuzzy PID, plus a
// fixed PID tuned offline on ITAE -- on the ER50-C20 model, for one scenario or all of them.
//
// Writes, into --out (default out/): trajectory.csv, metrics.csv, endeffector.csv and
// settings.txt. The set is written into a unique temporary directory and replaces --out in one
// rename only when the whole run has succeeded, with --out locked meanwhile (cli::OutputSet): a
// failed or interrupted run leaves the previous set untouched and no temporary behind.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/metrics.hpp"
#include "fuzzypid/sim/scenario.hpp"
#include "output_files.hpp"

namespace {

using namespace fuzzypid;

struct Options {
  std::string scenario = "paper";
  std::string out_dir = "out";
  std::string urdf;
  std::optional<Eigen::Vector3d> start_mm, end_mm;
  sim::ExperimentOptions experiment{};
  bool tune = true;
  bool quiet = false;
};

void usage(std::FILE* f) {
  std::fputs(
      "usage: sim_ab [options]\n"
      "  --scenario NAME|all        scenario to run (default paper; see --list)\n"
      "  --list                     list the scenarios and exit\n"
      "  --out DIR                  output directory (default out)\n"
      "  --urdf FILE                robot description (default: the bundled ER50-C20)\n"
      "  --start X,Y,Z --end X,Y,Z  path end points in mm (default the paper's A and B)\n"
      "  --gain-units acceleration|torque   u is rad/s² scaled by the nominal inertia (default)\n"
      "                             or a torque in N·m\n"
      "  --pid-form per-tick|continuous     units of Ki, Kd (default per-tick)\n"
      "  --derivative rates|difference      de/dt from velocities (default) or from errors\n"
      "  --gain-update absolute|incremental K = K0 + dK (default, Eq. 6) or K += dK\n"
      "  --error-scale KE --error-rate-scale KEC   input scaling (default 1, 1)\n"
      "  --output-scale SP,SI,SD    scaling of dKp, dKi, dKd (default 1,1,1)\n"
      "  --tables printed|corrected rule tables (default printed)\n"
      "  --and min|prod             fuzzy conjunction (default min)\n"
      "  --gains KP,KI,KD           nominal gains (default 4,0.001,100)\n"
      "  --initial-error RAD        joints start this far behind the path (default 0.05)\n"
      "  --seed N                   measurement-noise seed (default 1)\n"
      "  --no-tune                  skip the pid-tuned controller\n"
      "  --quiet                    no metrics table, no progress\n",
      f);
}

bool parse_double(const char* s, double& v) {
  char* end = nullptr;
  v = std::strtod(s, &end);
  return end != s && *end == '\0' && std::isfinite(v);
}

bool parse_triple(const char* s, double (&v)[3]) {
  std::string text(s);
  std::size_t pos = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t comma = text.find(',', pos);
    if ((k < 2) != (comma != std::string::npos)) return false;
    const std::string field = text.substr(pos, comma == std::string::npos ? comma : comma - pos);
    if (!parse_double(field.c_str(), v[k])) return false;
    pos = comma + 1;
  }
  return true;
}

// Returns 0 on success, 2 after printing a usage error, -1 when the caller should exit 0.
int parse(int argc, char** argv, Options& o) {
  auto& e = o.experiment;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    const auto value = [&]() -> const char* {
      if (k + 1 >= argc) return nullptr;
      return argv[++k];
    };
    const auto bad = [&](const char* v) {
      std::fprintf(stderr, "sim_ab: %s %s: invalid value (see --help)\n", a.c_str(),
                   v ? v : "(missing)");
      return 2;
    };
    if (a == "--help" || a == "-h") {
      usage(stdout);
      return -1;
    } else if (a == "--list") {
      for (const auto& s : sim::scenarios())
        std::printf("%-14s %s\n", s.name.c_str(), s.description.c_str());
      return -1;
    } else if (a == "--no-tune") {
      o.tune = false;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--scenario") {
      const char* v = value();
      if (!v || (std::strcmp(v, "all") != 0 && !sim::find_scenario(v))) {
        std::fprintf(stderr, "sim_ab: unknown scenario '%s' (see --list)\n", v ? v : "");
        return 2;
      }
      o.scenario = v;
    } else if (a == "--out") {
      const char* v = value();
      if (!v || !*v) return bad(v);
      o.out_dir = v;
    } else if (a == "--urdf") {
      const char* v = value();
      if (!v) return bad(v);
      o.urdf = v;
    } else if (a == "--start" || a == "--end") {
      const char* v = value();
      double xyz[3];
      if (!v || !parse_triple(v, xyz)) return bad(v);
      (a == "--start" ? o.start_mm : o.end_mm) = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    } else if (a == "--gain-units") {
      const char* v = value();
      if (v && std::strcmp(v, "acceleration") == 0)
        e.gain_units = sim::GainUnits::Acceleration;
      else if (v && std::strcmp(v, "torque") == 0)
        e.gain_units = sim::GainUnits::Torque;
      else
        return bad(v);
    } else if (a == "--pid-form") {
      const char* v = value();
      if (v && std::strcmp(v, "per-tick") == 0)
        e.pid_form = sim::PidForm::PerTick;
      else if (v && std::strcmp(v, "continuous") == 0)
        e.pid_form = sim::PidForm::Continuous;
      else
        return bad(v);
    } else if (a == "--derivative") {
      const char* v = value();
      if (v && std::strcmp(v, "rates") == 0)
        e.derivative = pid::DerivativeSource::Rates;
      else if (v && std::strcmp(v, "difference") == 0)
        e.derivative = pid::DerivativeSource::Difference;
      else
        return bad(v);
    } else if (a == "--gain-update") {
      const char* v = value();
      if (v && std::strcmp(v, "absolute") == 0)
        e.gain_update = control::GainUpdate::Absolute;
      else if (v && std::strcmp(v, "incremental") == 0)
        e.gain_update = control::GainUpdate::Incremental;
      else
        return bad(v);
    } else if (a == "--tables") {
      const char* v = value();
      if (v && std::strcmp(v, "printed") == 0)
        e.tables = paper::Tables::Printed;
      else if (v && std::strcmp(v, "corrected") == 0)
        e.tables = paper::Tables::Corrected;
      else
        return bad(v);
    } else if (a == "--and") {
      const char* v = value();
      if (v && std::strcmp(v, "min") == 0)
        e.conjunction = fuzzy::Conjunction::Minimum;
      else if (v && std::strcmp(v, "prod") == 0)
        e.conjunction = fuzzy::Conjunction::Product;
      else
        return bad(v);
    } else if (a == "--error-scale" || a == "--error-rate-scale" || a == "--initial-error") {
      const char* v = value();
      double x = 0;
      if (!v || !parse_double(v, x)) return bad(v);
      if (a == "--error-scale")
        e.error_scale = x;
      else if (a == "--error-rate-scale")
        e.error_rate_scale = x;
      else
        e.initial_error_rad = x;
    } else if (a == "--output-scale" || a == "--gains") {
      const char* v = value();
      double t[3];
      if (!v || !parse_triple(v, t)) return bad(v);
      if (a == "--gains") {
        if (t[0] < 0 || t[1] < 0 || t[2] < 0) return bad(v);
        e.gains = {t[0], t[1], t[2]};
      } else {
        e.output_scale = {t[0], t[1], t[2]};
      }
    } else if (a == "--seed") {
      const char* v = value();
      char* end = nullptr;
      if (!v) return bad(v);
      const unsigned long long s = std::strtoull(v, &end, 10);
      if (end == v || *end != '\0') return bad(v);
      e.noise_seed = s;
    } else {
      std::fprintf(stderr, "sim_ab: unknown option '%s' (see --help)\n", a.c_str());
      return 2;
    }
  }
  return 0;
}

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const int rc = parse(argc, argv, o); rc != 0) return rc < 0 ? 0 : rc;

  const std::string urdf = o.urdf.empty() ? robot::default_urdf_path() : o.urdf;
  robot::LoadResult loaded = robot::RobotModel::load(urdf);
  if (!loaded.model) {
    std::fprintf(stderr, "sim_ab: cannot load %s: %s\n", urdf.c_str(), loaded.error.c_str());
    return 1;
  }
  const robot::RobotModel& model = *loaded.model;

  robot::CartesianPathSpec spec = robot::paper_path_spec();
  if (o.start_mm) spec.start_m = *o.start_mm / 1000.0;
  if (o.end_mm) spec.end_m = *o.end_mm / 1000.0;
  std::string error;
  const auto experiment = sim::Experiment::create(model, spec, o.experiment, error);
  if (!experiment) {
    std::fprintf(stderr, "sim_ab: %s\n", error.c_str());
    return 1;
  }

  std::vector<const sim::Scenario*> runs;
  if (o.scenario == "all") {
    for (const auto& s : sim::scenarios())
      runs.push_back(&s);
  } else {
    runs.push_back(sim::find_scenario(o.scenario));
  }

  auto outs = cli::OutputSet::open(
      o.out_dir, {"trajectory.csv", "metrics.csv", "endeffector.csv", "settings.txt"}, error);
  if (!outs) {
    std::fprintf(stderr, "sim_ab: %s\n", error.c_str());
    return 1;
  }
  std::FILE* traj = outs->file(0);
  std::FILE* metrics = outs->file(1);
  std::FILE* tip = outs->file(2);
  std::FILE* settings = outs->file(3);
  std::fputs("scenario,controller,t,joint,theta_d,theta,error,error_rate,u,kp,ki,kd\n", traj);
  std::fputs(
      "scenario,controller,joint,settling_time_s,overshoot_pct,max_abs_error_rad,rms_error_rad,"
      "iae,itae\n",
      metrics);
  std::fputs("scenario,controller,t,x_d,y_d,z_d,x,y,z\n", tip);

  const auto& ex = o.experiment;
  std::fprintf(settings,
               "urdf=%s\nstart_mm=%s,%s,%s\nend_mm=%s,%s,%s\nsamples=%zu\ntick_s=%s\n"
               "gains=%s,%s,%s\ngain_units=%s\npid_form=%s\nderivative=%s\ngain_update=%s\n"
               "error_scale=%s\nerror_rate_scale=%s\noutput_scale=%s,%s,%s\ntables=%s\nand=%s\n"
               "initial_error_rad=%s\nnoise_seed=%llu\n",
               urdf.c_str(), fmt(spec.start_m.x() * 1e3).c_str(),
               fmt(spec.start_m.y() * 1e3).c_str(), fmt(spec.start_m.z() * 1e3).c_str(),
               fmt(spec.end_m.x() * 1e3).c_str(), fmt(spec.end_m.y() * 1e3).c_str(),
               fmt(spec.end_m.z() * 1e3).c_str(), experiment->ticks(), fmt(ex.tick_s).c_str(),
               fmt(ex.gains.kp).c_str(), fmt(ex.gains.ki).c_str(), fmt(ex.gains.kd).c_str(),
               sim::to_string(ex.gain_units), sim::to_string(ex.pid_form),
               ex.derivative == pid::DerivativeSource::Rates ? "rates" : "difference",
               control::to_string(ex.gain_update), fmt(ex.error_scale).c_str(),
               fmt(ex.error_rate_scale).c_str(), fmt(ex.output_scale[0]).c_str(),
               fmt(ex.output_scale[1]).c_str(), fmt(ex.output_scale[2]).c_str(),
               ex.tables == paper::Tables::Printed ? "printed" : "corrected",
               fuzzy::to_string(ex.conjunction), fmt(ex.initial_error_rad).c_str(),
               static_cast<unsigned long long>(ex.noise_seed));
  const auto& J = experiment->nominal_inertia();
  std::fprintf(settings, "nominal_inertia_kgm2=%s,%s,%s,%s,%s,%s\n", fmt(J[0]).c_str(),
               fmt(J[1]).c_str(), fmt(J[2]).c_str(), fmt(J[3]).c_str(), fmt(J[4]).c_str(),
               fmt(J[5]).c_str());

  std::optional<pid::Gains<double>> tuned;
  if (o.tune) {
    if (!o.quiet) std::fprintf(stderr, "sim_ab: tuning pid-tuned on scenario paper (ITAE) ...\n");
    const sim::TuningResult t = sim::tune_pid(*experiment, *sim::find_scenario("paper"));
    tuned = t.gains;
    std::fprintf(settings,
                 "pid_tuned_gains=%s,%s,%s\npid_tuned_itae=%s\npid_tuned_evaluations=%zu\n",
                 fmt(t.gains.kp).c_str(), fmt(t.gains.ki).c_str(), fmt(t.gains.kd).c_str(),
                 fmt(t.itae).c_str(), t.evaluations);
    if (!o.quiet)
      std::fprintf(stderr, "sim_ab: pid-tuned gains Kp=%.6g Ki=%.6g Kd=%.6g (%zu runs)\n",
                   t.gains.kp, t.gains.ki, t.gains.kd, t.evaluations);
  }

  std::vector<sim::ControllerKind> controllers = {sim::ControllerKind::Pid,
                                                  sim::ControllerKind::Fuzzy};
  if (tuned) controllers.push_back(sim::ControllerKind::PidTuned);

  if (!o.quiet)
    std::printf("%-14s %-10s %5s %10s %10s %12s %12s %10s\n", "scenario", "controller", "joint",
                "settle_s", "overshoot%", "max|e|_rad", "rms_e_rad", "itae");
  std::size_t done = 0;
  for (const sim::Scenario* scenario : runs) {
    ++done;
    if (!o.quiet && runs.size() > 1)
      std::fprintf(stderr, "sim_ab: [%zu/%zu] scenario %s\n", done, runs.size(),
                   scenario->name.c_str());
    for (const sim::ControllerKind kind : controllers) {
      const char* cname = sim::to_string(kind);
      const auto gains = kind == sim::ControllerKind::PidTuned ? tuned : std::nullopt;
      const sim::RunResult r = experiment->run(*scenario, kind, gains);
      if (!r.ok) {
        std::fprintf(stderr, "sim_ab: scenario %s, controller %s: %s\n", scenario->name.c_str(),
                     cname, r.error.c_str());
        return 1;
      }
      for (const auto& row : r.rows) {
        std::fprintf(traj, "%s,%s,%s,%d,%s,%s,%s,%s,%s,%s,%s,%s\n", scenario->name.c_str(), cname,
                     fmt(row.t_s).c_str(), row.joint, fmt(row.theta_d).c_str(),
                     fmt(row.theta).c_str(), fmt(row.error).c_str(), fmt(row.error_rate).c_str(),
                     fmt(row.u).c_str(), fmt(row.kp).c_str(), fmt(row.ki).c_str(),
                     fmt(row.kd).c_str());
      }
      // End-effector path (Fig. 9): FK of the reference and of the joint angles at each tick.
      const std::size_t ticks = r.rows.size() / robot::kNumJoints;
      for (std::size_t k = 0; k < ticks; ++k) {
        robot::JointVector qd{}, q{};
        for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
          qd[i] = r.rows[k * robot::kNumJoints + i].theta_d;
          q[i] = r.rows[k * robot::kNumJoints + i].theta;
        }
        const Eigen::Vector3d pd = model.forward_kinematics(qd).position_m;
        const Eigen::Vector3d p = model.forward_kinematics(q).position_m;
        std::fprintf(tip, "%s,%s,%s,%s,%s,%s,%s,%s,%s\n", scenario->name.c_str(), cname,
                     fmt(r.rows[k * robot::kNumJoints].t_s).c_str(), fmt(pd.x()).c_str(),
                     fmt(pd.y()).c_str(), fmt(pd.z()).c_str(), fmt(p.x()).c_str(),
                     fmt(p.y()).c_str(), fmt(p.z()).c_str());
      }
      for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
        std::vector<double> t, theta_d, theta, err;
        for (std::size_t k = 0; k < ticks; ++k) {
          const auto& row = r.rows[k * robot::kNumJoints + i];
          t.push_back(row.t_s);
          theta_d.push_back(row.theta_d);
          theta.push_back(row.theta);
          err.push_back(row.error);
        }
        const sim::JointMetrics m = sim::joint_metrics(t, theta_d, theta, err, ex.tick_s);
        std::fprintf(metrics, "%s,%s,%zu,%s,%s,%s,%s,%s,%s\n", scenario->name.c_str(), cname, i + 1,
                     fmt(m.settling_time_s).c_str(), fmt(m.overshoot_pct).c_str(),
                     fmt(m.max_abs_error_rad).c_str(), fmt(m.rms_error_rad).c_str(),
                     fmt(m.iae).c_str(), fmt(m.itae).c_str());
        if (!o.quiet)
          std::printf("%-14s %-10s %5zu %10.3g %10.3g %12.3e %12.3e %10.3e\n",
                      scenario->name.c_str(), cname, i + 1, m.settling_time_s, m.overshoot_pct,
                      m.max_abs_error_rad, m.rms_error_rad, m.itae);
      }
      if (r.controller_faults != 0)
        std::fprintf(stderr, "sim_ab: warning: %zu controller faults in %s/%s\n",
                     r.controller_faults, scenario->name.c_str(), cname);
    }
  }
  if (!outs->commit(error)) {
    std::fprintf(stderr, "sim_ab: %s\n", error.c_str());
    return 1;
  }
  if (!o.quiet)
    std::fprintf(stderr, "sim_ab: wrote %s/{trajectory,metrics,endeffector}.csv\n",
                 o.out_dir.c_str());
  return 0;
}
