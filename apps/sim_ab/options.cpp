#include "options.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"

namespace fuzzypid::sim_ab {

namespace {

// Finite numbers only (CLI11 would accept "nan" and "inf").
const CLI::Validator kFinite(
    [](std::string& s) -> std::string {
      char* end = nullptr;
      const double v = std::strtod(s.c_str(), &end);
      if (end == s.c_str() || *end != '\0' || !std::isfinite(v)) return "not a finite number: " + s;
      return {};
    },
    "FINITE");

// "a,b,c" (N numbers, finite).
template <std::size_t N>
bool parse_list(const std::string& text, std::array<double, N>& out) {
  std::stringstream in(text);
  std::string field;
  std::size_t k = 0;
  while (std::getline(in, field, ',')) {
    if (k == N) return false;
    char* end = nullptr;
    out[k] = std::strtod(field.c_str(), &end);
    if (field.empty() || end == field.c_str() || *end != '\0' || !std::isfinite(out[k]))
      return false;
    ++k;
  }
  return k == N && (text.empty() || text.back() != ',');
}

template <std::size_t N>
CLI::Option* add_list(CLI::App& app, const std::string& name, std::array<double, N>& target,
                      const std::string& help, bool non_negative = false,
                      const std::function<void()>& then = {}) {
  return app.add_option_function<std::string>(
      name,
      [&target, name, non_negative, then](const std::string& s) {
        std::array<double, N> v{};
        if (!parse_list(s, v))
          throw CLI::ValidationError(
              name, "expected " + std::to_string(N) + " comma-separated finite numbers: " + s);
        for (double x : v)
          if (non_negative && x < 0.0)
            throw CLI::ValidationError(name, "values must be >= 0: " + s);
        target = v;
        if (then) then();
      },
      help);
}

template <class Enum, std::size_t N>
CLI::Option* add_enum(CLI::App& app, const std::string& name, Enum& target,
                      const std::array<fuzzypid::EnumName<Enum>, N>& table,
                      const std::string& help) {
  std::vector<std::string> names;
  names.reserve(N);
  for (const auto& e : table)
    names.emplace_back(e.name);
  return app
      .add_option_function<std::string>(
          name,
          [&target, &table](const std::string& s) { target = *fuzzypid::parse_enum(table, s); },
          help + " (" + fuzzypid::names_of(table) + "; default " +
              fuzzypid::name_of(table, target) + ")")
      ->check(CLI::IsMember(names));
}

bool parse_sweep(const std::string& text, sim::Sweep& sweep) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) return false;
  const auto parameter = fuzzypid::parse_enum(sim::kSweepParameterNames, text.substr(0, eq));
  if (!parameter) return false;
  sweep.parameter = *parameter;
  std::array<double, 3> v{};
  std::string range = text.substr(eq + 1);
  for (char& c : range)
    if (c == ':') c = ',';
  if (!parse_list(range, v)) return false;
  if (!(v[0] > 0.0) || !(v[1] >= v[0]) || v[2] < 1 || v[2] > 1000 || v[2] != std::floor(v[2]))
    return false;
  sweep.lo = v[0];
  sweep.hi = v[1];
  sweep.count = static_cast<int>(v[2]);
  return true;
}

}  // namespace

ParseResult parse(int argc, const char* const* argv, Options& o) {
  CLI::App app{
      "sim_ab: the paper's A/B experiment (section 6) on the ER50-C20 model, or on any six-joint "
      "arm (--urdf) following any path (--path) -- controllers "
      "(the paper's fixed and fuzzy PID, or controller files) on scenarios, conditions and "
      "condition sets; writes trajectory.csv, metrics.csv, endeffector.csv, conditions.csv and "
      "settings.txt into --out.",
      "sim_ab"};
  app.get_formatter()->column_width(34);
  auto& e = o.experiment;

  app.add_option("--scenario", o.scenario, "named scenario or 'all' (default paper; see --list)")
      ->check([](const std::string& s) -> std::string {
        if (s == "all" || sim::find_scenario(s) != nullptr) return {};
        return "unknown scenario '" + s + "' (see --list)";
      });
  app.add_flag("--list", o.list, "list the scenarios and exit");
  auto* conditions = app.add_option("--conditions", o.conditions_file,
                                    "condition-set file (TOML, e.g. tuning/robust.toml)");
  app.add_option("--set", o.sets, "set of --conditions to run (repeatable; default: all sets)")
      ->needs(conditions);
  app.add_option(
      "--controller", o.controllers,
      "controller file, or a front's folder (fuzzypid tune --front-out: each of its points) "
      "(repeatable; default: the paper's pid and fuzzy)");
  app.add_option_function<std::string>(
      "--sweep",
      [&o](const std::string& s) {
        sim::Sweep sw;
        if (!parse_sweep(s, sw))
          throw CLI::ValidationError("--sweep",
                                     "expected payload-scale=LO:HI:N or "
                                     "torque-limit=LO:HI:N with 0 < LO <= HI, "
                                     "1 <= N <= 1000: " +
                                         s);
        o.sweep = sw;
      },
      "robustness sweep of the scenario: payload-scale=LO:HI:N or torque-limit=LO:HI:N");
  app.add_option("--overshoot-bound", o.overshoot_bound_pct,
                 "sweep: usable while overshoot <= this, % (default 20)")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--itae-ratio", o.itae_ratio_bound,
                 "sweep: usable while ITAE <= this x the nominal ITAE (default 3)")
      ->check(CLI::Range(1.0, 1e6));
  app.add_option("--out", o.out_dir, "output directory (default out)")
      ->check([](const std::string& s) { return s.empty() ? std::string("empty path") : ""; });
  cli::add_robot_options(app, o.robot, true);
  std::array<double, 3> start{}, end{};
  // The bound Condition::validate() puts on the path's end points, checked here so that an
  // accepted command line leaves a valid condition.
  const auto within_1_km = [](const std::string& name, const std::array<double, 3>& p_mm) {
    constexpr double kMaxMm = sim::kMaxPathCoordinateM * 1e3;
    static_assert(kMaxMm == 1e6, "the message names the bound");
    for (double x : p_mm)
      if (std::fabs(x) > kMaxMm) throw CLI::ValidationError(name, "values must be within ±1e6 mm");
  };
  add_list(app, "--start", start, "path start X,Y,Z in mm (default the paper's A)", false,
           [&o, &start, within_1_km] {
             within_1_km("--start", start);
             o.start_mm = Eigen::Vector3d(start[0], start[1], start[2]);
           });
  add_list(app, "--end", end, "path end X,Y,Z in mm (default the paper's B)", false,
           [&o, &end, within_1_km] {
             within_1_km("--end", end);
             o.end_mm = Eigen::Vector3d(end[0], end[1], end[2]);
           });

  // Condition overrides.
  const auto opt_number = [&app](const std::string& name, std::optional<double>& target,
                                 const std::string& help, const sim::FieldRange& range) {
    return app
        .add_option_function<double>(
            name, [&target](double v) { target = v; }, help)
        ->check(kFinite)
        ->check(CLI::Range(range.lo, range.hi));
  };
  opt_number("--payload-scale", o.payload_scale,
             "link inertia x S; the controller keeps the nominal inertia", sim::kPayloadScaleRange);
  opt_number("--friction", o.friction, "viscous friction b_i = B J^_i, 1/s", sim::kFrictionRange);
  opt_number("--torque-limit", o.torque_limit,
             "|tau_i| <= L J^_i, rad/s² (0: the URDF effort limits)", sim::kTorqueLimitRange);
  opt_number("--contact", o.contact, "amplitude of the deburring contact pulses, rad/s²",
             sim::kContactRange);
  opt_number("--initial-error", o.initial_error,
             "joints start this far behind the path, rad (< 0: ahead; default 0.05)",
             sim::kInitialErrorRange);
  app.add_option_function<std::string>(
      "--noise",
      [&o](const std::string& s) {
        std::array<double, 2> v{};
        if (!parse_list(s, v) || !sim::kNoisePositionRange.contains(v[0]) ||
            !sim::kNoiseVelocityRange.contains(v[1]))
          throw CLI::ValidationError("--noise",
                                     "expected SIGMA_Q,SIGMA_QD within 0 .. 1 rad and "
                                     "0 .. 100 rad/s: " +
                                         s);
        o.noise = v;
      },
      "Gaussian measurement noise on angles (rad) and velocities (rad/s)");
  app.add_option_function<std::uint64_t>(
         "--seed", [&o](std::uint64_t s) { o.seed = s; }, "measurement-noise seed (default 1)")
      ->check(cli::unsigned_integer());
  app.add_flag("--reverse", o.reverse, "follow the path B -> A");

  // The paper's default controllers.
  add_enum(app, "--gain-units", e.gain_units, controller::kGainUnitsNames,
           "u is rad/s² scaled by the nominal inertia, or a torque in N·m");
  add_enum(app, "--pid-form", e.pid_form, controller::kPidFormNames, "units of Ki, Kd");
  // The paper's controllers take ec from rates or from differences; the observer, which needs a
  // bandwidth, is for controller files.
  static constexpr std::array<fuzzypid::EnumName<pid::DerivativeSource>, 2> kPaperDerivativeNames{
      {controller::kDerivativeSourceNames[0], controller::kDerivativeSourceNames[1]}};
  add_enum(app, "--derivative", e.derivative, kPaperDerivativeNames,
           "de/dt from velocities or from errors");
  add_enum(app, "--gain-update", e.gain_update, controller::kGainUpdateNames,
           "K = K0 + dK (Eq. 6) or K += dK");
  add_enum(app, "--tables", e.tables, controller::kPaperTablesNames, "rule tables");
  add_enum(app, "--and", e.conjunction, controller::kConjunctionNames, "fuzzy conjunction");
  app.add_option("--error-scale", e.error_scale, "Ke (default 1)")->check(kFinite);
  app.add_option("--error-rate-scale", e.error_rate_scale, "Kec (default 1)")->check(kFinite);
  add_list(app, "--output-scale", e.output_scale,
           "Sp,Si,Sd: scaling of dKp, dKi, dKd (default 1,1,1)");
  std::array<double, 3> gains{};
  add_list(app, "--gains", gains, "nominal gains KP,KI,KD (default 4,0.001,100)", true,
           [&e, &gains] {
             e.gains = {gains[0], gains[1], gains[2]};
           });
  app.add_flag("--strict-rules", o.strict_rules,
               "a tick on which a supervisor fires no rule is an error (exit 1; else a warning "
               "and the count in metrics.csv)");
  app.add_option("--divergence", o.divergence_rad,
                 "a joint whose |error| exceeds this, rad, faults, as does one that leaves its "
                 "URDF joint limits (default 1, as tune's)")
      ->check(kFinite)
      ->check([](const std::string& s) {
        return std::strtod(s.c_str(), nullptr) > 0.0 ? std::string() : "must be > 0 rad: " + s;
      });
  app.add_flag("--allow-faults", o.allow_faults,
               "runs with faults (controller faults, |error| > --divergence, a joint outside its "
               "limits) are counted and named but exit 0 (else exit 1)");
  app.add_flag("--quiet", o.quiet, "no table, no progress");

  cli::refuse_empty_values(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return ParseResult::Exit;
  } catch (const CLI::ParseError& err) {
    std::fprintf(stderr, "sim_ab: %s (see --help)\n", err.what());
    return ParseResult::UsageError;
  }
  o.given = cli::GivenOptions(app);
  const cli::GivenOptions& given = o.given;
  if (o.list && given.names().size() > 1) {
    for (const std::string& name : given.names())
      if (name != "--list") {
        std::fprintf(stderr,
                     "sim_ab: %s does nothing with --list, which prints the scenarios "
                     "and exits\n",
                     name.c_str());
        return ParseResult::UsageError;
      }
  }
  if (o.list) {
    for (const auto& s : sim::scenarios())
      std::printf("%-14s %s\n", s.name.c_str(), s.description.c_str());
    return ParseResult::Exit;
  }
  const bool overrides = o.payload_scale || o.friction || o.torque_limit || o.contact ||
                         o.initial_error || o.noise || o.seed || o.reverse;
  if (!o.conditions_file.empty() && (overrides || app.count("--scenario") > 0)) {
    std::fprintf(stderr,
                 "sim_ab: --conditions runs the file's conditions; --scenario and the condition "
                 "options (--payload-scale ...) apply without it (see --help)\n");
    return ParseResult::UsageError;
  }
  if (const std::string bad = cli::check_robot_options(o.robot); !bad.empty()) {
    std::fprintf(stderr, "sim_ab: %s (see --help)\n", bad.c_str());
    return ParseResult::UsageError;
  }
  if (!o.conditions_file.empty() && (o.robot.any() || o.start_mm || o.end_mm)) {
    std::fprintf(stderr,
                 "sim_ab: --conditions runs the file's conditions on the robots and paths they "
                 "name (keys urdf, path, tick_ms, payload_kg, armature, dynamics, gravity and the "
                 "joint effects such as plant_step_ms); "
                 "the robot options apply without it (see --help)\n");
    return ParseResult::UsageError;
  }
  if (!o.robot.setup.path.empty() && (o.start_mm || o.end_mm)) {
    std::fprintf(stderr, "sim_ab: --start and --end move the line A -> B; --path replaces it\n");
    return ParseResult::UsageError;
  }
  // The paper-controller options shape the built-in pid and fuzzy only: with controller files
  // they would be ignored.
  if (!o.controllers.empty()) {
    for (const char* name :
         {"--gain-units", "--pid-form", "--derivative", "--gain-update", "--tables", "--and",
          "--error-scale", "--error-rate-scale", "--output-scale", "--gains"})
      if (app.count(name) > 0) {
        std::fprintf(stderr,
                     "sim_ab: %s sets the built-in paper controllers; with --controller FILE the "
                     "file says it (see --help)\n",
                     name);
        return ParseResult::UsageError;
      }
  }
  for (std::size_t i = 0; i < o.sets.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (o.sets[i] == o.sets[j]) {
        std::fprintf(stderr, "sim_ab: --set %s is given twice\n", o.sets[i].c_str());
        return ParseResult::UsageError;
      }
  if (o.sweep && !o.conditions_file.empty()) {
    std::fprintf(stderr, "sim_ab: --sweep varies the --scenario condition, not a file's sets\n");
    return ParseResult::UsageError;
  }
  if (const std::string bad =
          given.refuse_unused({"--overshoot-bound", "--itae-ratio"}, o.sweep.has_value(), "--sweep",
                              "without it there is no usable range to bound");
      !bad.empty()) {
    std::fprintf(stderr, "sim_ab: %s (see --help)\n", bad.c_str());
    return ParseResult::UsageError;
  }
  if (o.sweep && o.scenario == "all") {
    std::fprintf(stderr, "sim_ab: --sweep needs one scenario, not 'all'\n");
    return ParseResult::UsageError;
  }
  return ParseResult::Run;
}

std::vector<sim::Condition> scenario_conditions(const Options& o) {
  std::vector<sim::Condition> out;
  if (o.scenario == "all") {
    out = sim::scenarios();
  } else {
    out.push_back(*sim::find_scenario(o.scenario));
  }
  for (sim::Condition& c : out) {
    c.initial_error_rad = o.experiment.initial_error_rad;
    c.seed = o.experiment.noise_seed;
    if (o.payload_scale) c.payload_scale = *o.payload_scale;
    if (o.friction) c.friction_per_s = *o.friction;
    if (o.torque_limit) c.torque_limit_rad_s2 = *o.torque_limit;
    if (o.contact) c.contact_rad_s2 = *o.contact;
    if (o.initial_error) c.initial_error_rad = *o.initial_error;
    if (o.noise) {
      c.noise_position_rad = (*o.noise)[0];
      c.noise_velocity_rad_s = (*o.noise)[1];
    }
    if (o.seed) c.seed = *o.seed;
    c.reverse = c.reverse || o.reverse;
    o.robot.apply(c);
    if (o.start_mm)
      c.robot.start_m = {{o.start_mm->x() / 1e3, o.start_mm->y() / 1e3, o.start_mm->z() / 1e3}};
    if (o.end_mm) c.robot.end_m = {{o.end_mm->x() / 1e3, o.end_mm->y() / 1e3, o.end_mm->z() / 1e3}};
  }
  return out;
}

}  // namespace fuzzypid::sim_ab
