// fuzzypid_soak: millions of ticks of the 6-joint fuzzy PID on the simulated ER50-C20 under
// deliberate abuse, checking after every tick the invariants a controller left running unattended
// must keep.
//
// The loop is the A/B simulation's closed loop, sim::ClosedLoop (docs/reproduction.md), ticked
// on the section 6 path played back and forth (A -> B -> A ..., 101 samples each way, closed-form
// IK; ClosedLoop::cyclic_sample): the paper's fuzzy PID as its controller file describes it
// (per-tick gains converted once by controller::fuzzy_pid_config), torque_i = J^_i u_i, and
// the plant of a condition whose actuator limit is 5 rad/s² x J^_i (so that the paper's weak gains
// do saturate it). On top of that configuration the integral is limited to the output range and
// the gains to [0, 3 K0]; joints 1-3 use the paper's absolute gain update (K = K0 + dK, Eq. 6),
// joints 4-6 the incremental one (K += dK every tick), which drifts until the gain bounds stop it:
// both clamps are exercised. A file cannot say that, so the controller is built with one
// configuration per joint (JointControllers::create) and handed to ClosedLoop::create. The abuse
// reaches between path, controller and plant through the tick's sim::TickInjection (setpoint
// jumps, corrupted measurements, the controller's and the plant's dt, disturbances) and
// ClosedLoop::reset_plant; nothing else steps the controller or the plant.
//
// Abuse, drawn from sim::Random (the project's one seeded generator: the same run for a seed with
// every standard library):
//   - dt jitter of +/-20 % around 50 ms on every tick (the time the plant advances and the dt the
//     controller is given), and about one tick in 1,000 a bad dt (0, negative, NaN or +inf) given
//     to the controller (the plant still advances the jittered time);
//   - about one tick in 500 a NaN, +/-inf or huge (+/-1e300) measured position or velocity on
//     one joint;
//   - disturbance torque pulses of 0.5-10 s, up to 2 rad/s² x J^_i (one in ten up to 1.5x the
//     actuator limit, which the controller cannot hold);
//   - setpoint jumps of up to +/-0.5 rad held 1-20 s, and every ~3 h of simulated time
//     (200,000 ticks) a 3 rad jump held 100-300 s: long saturation periods.
//
// Invariants (any breach prints the tick and exits 1; bad arguments exit 2):
//   - every command is finite;
//   - no allocation after start-up (global operator new is replaced by a counting one in this
//     binary, fuzzypid_support/counting_new.hpp);
//   - an injected NaN/inf measurement is reported as a fault on that joint, and a bad dt on every
//     joint;
//   - every gain stays finite and inside [gain_min, gain_max]; every integral inside its limits;
//   - the plant state stays finite. The abuse can push the plant far off the path (a disturbance
//     above the actuator limit is not recoverable); beyond 20 rad of error or 50 rad/s the plant
//     is reset onto the path and the reset counted.
//
// The last stdout line is `key=value` pairs: ticks nonfinite allocations faults max_abs_integral
// max_abs_gain, then plant_resets, injected counts and saturated_ticks.
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "cli.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/closed_loop.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/random.hpp"
#include "fuzzypid/status.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid_support/counting_new.hpp"  // replaces global operator new: counts allocations

namespace {

namespace controller = fuzzypid::controller;
namespace cli = fuzzypid::cli;
namespace supervisor = fuzzypid::supervisor;
namespace pid = fuzzypid::pid;
namespace robot = fuzzypid::robot;
namespace sim = fuzzypid::sim;
using fuzzypid::Status;

constexpr std::size_t kJoints = robot::kNumJoints;
constexpr double kTickS = 0.05;
constexpr double kHuge = 1e300;
constexpr double kAccelLimit = 5.0;  // rad/s², the condition's actuator limit (see build())
// Beyond these the plant is considered lost to the abuse and put back on the path.
constexpr double kMaxErrorRad = 20.0;
constexpr double kMaxSpeedRadS = 50.0;

struct Options {
  std::uint64_t ticks = 10'000'000;
  std::uint64_t seed = 1;
};

// Parses the command line into `o`; nullopt to run, else the exit code (0 after --help).
std::optional<int> parse_options(int argc, char** argv, Options& o) {
  CLI::App app(
      "Millions of abused ticks of the 6-joint fuzzy PID on the simulated ER50-C20, checking the "
      "invariants after every tick (docs/robustness.md).\nExit codes: 0 every invariant held, "
      "1 a breach (or the model does not load), 2 bad usage.",
      "fuzzypid_soak");
  app.add_option("--ticks", o.ticks,
                 "controller ticks of 50 ms to run (default 10000000, about 5.8 days)")
      ->check(cli::unsigned_in(1, std::numeric_limits<std::uint64_t>::max()))
      ->option_text("N");
  app.add_option("--seed", o.seed, "seed of the abuse schedule (default 1)")
      ->check(cli::unsigned_integer())
      ->option_text("S");
  return cli::parse(app, argc, argv);
}

// The abuse's draws on top of the sim's generator.
class Random {
 public:
  explicit Random(std::uint64_t seed) : random_(seed) {}
  double uniform(double lo, double hi) noexcept { return random_.uniform(lo, hi); }
  // An integer in [0, n).
  std::uint64_t below(std::uint64_t n) noexcept {
    const auto k = static_cast<std::uint64_t>(random_.uniform() * static_cast<double>(n));
    return k < n ? k : n - 1;
  }
  bool chance(double p) noexcept { return random_.uniform() < p; }

 private:
  fuzzypid::sim::Random random_;
};

// The gain bounds: [0, 3 K0] on every gain. The absolute update stays well inside; the incremental
// one walks into them.
pid::Gains<double> gain_max_of(const pid::Gains<double>& k0) {
  return {3.0 * k0.kp, 3.0 * k0.ki, 3.0 * k0.kd};
}

// The soak's closed loop and the bounds it is checked against. The loop points into the
// experiment, which must outlive it.
struct Soak {
  sim::ClosedLoop loop;
  robot::JointVector nominal_inertia{};  // J^_i, kg·m²
  robot::JointVector u_max{};            // controller output limit, rad/s² (actuator limit / J^_i)
  pid::Gains<double> gain_min{};
  pid::Gains<double> gain_max{};  // continuous SI form
};

std::optional<sim::Experiment> make_experiment(const robot::RobotModel& model, std::string& error) {
  sim::ExperimentOptions options;  // the A/B simulation's defaults: per-tick paper gains
  options.tick_s = kTickS;
  options.plant.armature_kgm2 = robot::kEr50ArmatureKgm2;  // the bundled ER50-C20's motors
  return sim::Experiment::create(model, robot::paper_path_spec(), options, error);
}

std::optional<Soak> build(const sim::Experiment& experiment, std::string& error) {
  // The paper scenario with an actuator limit of kAccelLimit x J^_i (as the sim's "saturation"
  // scenario limits it, there to 0.1): the URDF effort limits allow ~100 rad/s², which the
  // paper's Kp = 4 /s² never reaches.
  sim::Condition condition = *sim::find_scenario("paper");
  condition.torque_limit_rad_s2 = kAccelLimit;
  // The paper's fuzzy PID as sim_ab runs it, with gain bounds [0, 3 K0] (in the file's per-tick
  // units, converted with the gains).
  controller::ControllerSpec spec =
      sim::default_controller(experiment.options(), controller::paper_fuzzy());
  spec.gain_min = {0.0, 0.0, 0.0};
  spec.gain_max = gain_max_of(spec.gains);
  const robot::JointVector u_max = experiment.output_limit(condition, spec.units.gains);
  std::array<supervisor::FuzzyPidConfig<double>, kJoints> configs;
  for (std::size_t i = 0; i < kJoints; ++i) {
    configs[i] = controller::fuzzy_pid_config(spec, i, u_max[i]);
    configs[i].pid.integral_min = -u_max[i];
    configs[i].pid.integral_max = u_max[i];
    configs[i].gain_update =
        i < 3 ? supervisor::GainUpdate::Absolute : supervisor::GainUpdate::Incremental;
  }
  auto controller = controller::JointControllers::create(spec, configs, error);
  if (!controller) return std::nullopt;
  auto loop = sim::ClosedLoop::create(experiment, condition, std::move(*controller), error);
  if (!loop) return std::nullopt;
  return Soak{std::move(*loop), experiment.nominal_inertia(), u_max, configs[0].gain_min,
              configs[0].gain_max};
}

// Running figures of the soak, printed as the last line.
struct Counters {
  std::uint64_t ticks = 0;
  std::uint64_t nonfinite = 0;
  std::uint64_t allocations = 0;
  std::uint64_t faults = 0;  // joint-ticks that returned a fault
  double max_abs_integral = 0.0;
  double max_abs_gain = 0.0;
  std::uint64_t plant_resets = 0;
  std::uint64_t injected_measurements = 0;  // NaN/inf (must fault) and huge (may not)
  std::uint64_t injected_bad_dt = 0;
  std::uint64_t saturated_ticks = 0;  // ticks in which a controller output was clamped
};

void print(const Counters& c, std::uint64_t seed, double seconds) {
  std::printf(
      "ticks=%llu nonfinite=%llu allocations=%llu faults=%llu max_abs_integral=%.6g "
      "max_abs_gain=%.6g plant_resets=%llu injected_measurements=%llu injected_bad_dt=%llu "
      "saturated_ticks=%llu seed=%llu wall_s=%.1f\n",
      static_cast<unsigned long long>(c.ticks), static_cast<unsigned long long>(c.nonfinite),
      static_cast<unsigned long long>(c.allocations), static_cast<unsigned long long>(c.faults),
      c.max_abs_integral, c.max_abs_gain, static_cast<unsigned long long>(c.plant_resets),
      static_cast<unsigned long long>(c.injected_measurements),
      static_cast<unsigned long long>(c.injected_bad_dt),
      static_cast<unsigned long long>(c.saturated_ticks), static_cast<unsigned long long>(seed),
      seconds);
}

bool all_finite(const robot::JointVector& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

// Runs the soak; returns the first invariant breach (a static string) or nullptr.
const char* run(Soak& s, const Options& o, Counters& c) {
  Random rng(o.seed);
  sim::ClosedLoop& loop = s.loop;
  loop.reset_plant(loop.path().position_rad.front(), robot::JointVector{});

  // Abuse schedule: remaining ticks of the current pulse / jump and their values.
  std::uint64_t pulse_left = 0;
  std::uint64_t jump_left = 0;
  robot::JointVector pulse{};
  robot::JointVector jump{};
  const std::uint64_t allocations_at_start = fuzzypid::support::allocation_count();

  for (std::uint64_t tick = 0; tick < o.ticks; ++tick) {
    // Reference: the path played forwards then backwards, plus any setpoint jump.
    const sim::PathSample sample = loop.cyclic_sample(tick);
    sim::TickInjection injection;
    injection.reference_offset_rad = jump;

    if (jump_left > 0) {
      --jump_left;
    } else if (tick % 200'000 == 100'000) {  // long saturation: 3 rad held 100-300 s
      jump_left = 2'000 + rng.below(4'000);
      for (double& j : jump)
        j = rng.chance(0.5) ? 3.0 : -3.0;
    } else if (rng.chance(1.0 / 2'000)) {
      jump_left = 20 + rng.below(380);
      for (double& j : jump)
        j = rng.uniform(-0.5, 0.5);
    } else {
      jump.fill(0.0);
    }
    if (pulse_left > 0) {
      --pulse_left;
    } else if (rng.chance(1.0 / 1'000)) {
      pulse_left = 10 + rng.below(190);
      // Mostly contact-like pushes of up to 2 rad/s² x J^_i (four times the sim's deburring
      // scenario, an error of ~0.5 rad against Kp = 4 /s²); one pulse in ten up to 1.5x the
      // actuator limit, which the controller cannot hold.
      const bool beyond = rng.chance(0.1);
      for (std::size_t i = 0; i < kJoints; ++i) {
        const double amplitude = (beyond ? 1.5 * s.u_max[i] : 2.0) * s.nominal_inertia[i];
        pulse[i] = rng.uniform(-amplitude, amplitude);
      }
    } else {
      pulse.fill(0.0);
    }
    injection.disturbance_torque_nm = pulse;

    // Measurements, possibly corrupted on one joint.
    std::size_t bad_joint = kJoints;  // none
    if (rng.chance(1.0 / 500)) {
      const std::size_t j = rng.below(kJoints);
      const std::uint64_t kind = rng.below(5);
      const double value = kind == 0   ? std::numeric_limits<double>::quiet_NaN()
                           : kind == 1 ? std::numeric_limits<double>::infinity()
                           : kind == 2 ? -std::numeric_limits<double>::infinity()
                           : kind == 3 ? kHuge
                                       : -kHuge;
      (rng.chance(0.5) ? injection.measured_position_rad : injection.measured_velocity_rad_s)[j] =
          value;
      ++c.injected_measurements;
      if (!std::isfinite(value)) bad_joint = j;
    }

    // The clock: jittered, occasionally nonsense for the controller only.
    const double dt = kTickS * rng.uniform(0.8, 1.2);
    injection.plant_dt_s = dt;
    injection.controller_dt_s = dt;
    bool bad_dt = false;
    if (rng.chance(1.0 / 1'000)) {
      const std::uint64_t kind = rng.below(4);
      injection.controller_dt_s = kind == 0   ? 0.0
                                  : kind == 1 ? -dt
                                  : kind == 2 ? std::numeric_limits<double>::quiet_NaN()
                                              : std::numeric_limits<double>::infinity();
      bad_dt = true;
      ++c.injected_bad_dt;
    }

    const sim::TickResult r = loop.tick(sample, injection);

    const controller::JointControllers& controller = loop.controller();
    for (std::size_t i = 0; i < kJoints; ++i) {
      const Status st = r.command.joint_status[i];
      if (fuzzypid::is_fault(st)) ++c.faults;
      if (bad_dt && st != Status::InvalidTimeStep)
        return "bad dt not reported as invalid_time_step";
      if (!bad_dt && i == bad_joint && st != Status::NonFiniteInput)
        return "NaN/inf measurement not reported as non_finite_input";
      const double u = r.command.output[i];
      if (!std::isfinite(u)) {
        ++c.nonfinite;
        return "non-finite command";
      }
      if (std::fabs(u) > s.u_max[i]) return "command outside the output limits";
      const pid::Gains<double> g = controller.gains(i);
      if (!g.finite() || g.kp < s.gain_min.kp || g.kp > s.gain_max.kp || g.ki < s.gain_min.ki ||
          g.ki > s.gain_max.ki || g.kd < s.gain_min.kd || g.kd > s.gain_max.kd)
        return "gain outside its bounds";
      const double integral = controller.pid(i).integral();
      if (!std::isfinite(integral) || std::fabs(integral) > s.u_max[i])
        return "integral outside its limits";
      c.max_abs_integral = std::fmax(c.max_abs_integral, std::fabs(integral));
      c.max_abs_gain = std::fmax(c.max_abs_gain, std::fmax(g.kp, std::fmax(g.ki, g.kd)));
    }

    bool saturated = false;
    for (std::size_t i = 0; i < kJoints; ++i)
      saturated = saturated || controller.pid(i).saturated();
    if (saturated) ++c.saturated_ticks;

    const robot::JointPlant& plant = loop.plant();
    if (r.plant == robot::PlantStatus::InvalidInput) return "the plant rejected a finite torque";
    if (!all_finite(plant.position()) || !all_finite(plant.velocity()))
      return "non-finite plant state";
    bool lost = r.plant == robot::PlantStatus::NumericalError;
    for (std::size_t i = 0; i < kJoints; ++i) {
      lost = lost || std::fabs(plant.position()[i] - r.theta_d[i]) > kMaxErrorRad ||
             std::fabs(plant.velocity()[i]) > kMaxSpeedRadS;
    }
    if (lost) {
      loop.reset_plant(sample.theta_d, robot::JointVector{});
      ++c.plant_resets;
    }

    c.ticks = tick + 1;
    c.allocations = fuzzypid::support::allocation_count() - allocations_at_start;
    if (c.allocations != 0) return "allocation in the control loop";
  }
  return nullptr;
}

int run_soak(int argc, char** argv) {
  Options o;
  if (const auto code = parse_options(argc, argv, o)) return *code;

  std::string error;
  robot::LoadResult loaded = robot::RobotModel::load(robot::default_urdf_path());
  if (!loaded.model) error = "cannot load the URDF: " + loaded.error;
  // The loop points into the experiment: both stay here until the end.
  const std::optional<sim::Experiment> experiment =
      loaded.model ? make_experiment(*loaded.model, error) : std::nullopt;
  std::optional<Soak> soak = experiment ? build(*experiment, error) : std::nullopt;
  if (!soak) {
    std::fprintf(stderr, "fuzzypid_soak: %s\n", error.c_str());
    return cli::kExitFailure;
  }
  std::printf("fuzzypid_soak: %llu ticks of 50 ms (%.2f days simulated), seed %llu\n",
              static_cast<unsigned long long>(o.ticks),
              static_cast<double>(o.ticks) * kTickS / 86'400.0,
              static_cast<unsigned long long>(o.seed));
  std::fflush(stdout);

  Counters c;
  const auto start = std::chrono::steady_clock::now();
  const char* breach = run(*soak, o, c);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (breach != nullptr)
    std::fprintf(stderr, "fuzzypid_soak: invariant broken at tick %llu: %s\n",
                 static_cast<unsigned long long>(c.ticks), breach);
  print(c, o.seed, seconds);
  const int written = cli::finish_stdout("fuzzypid_soak");
  return breach != nullptr ? cli::kExitFailure : written;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_main("fuzzypid_soak", [&] { return run_soak(argc, argv); });
}
