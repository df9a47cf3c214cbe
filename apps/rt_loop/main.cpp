// rt_loop: the 6-joint controller against the simulated ER50-C20 in a fixed-period loop, the way
// it would run on a robot controller, with its timing measured.
//
// Each tick: sleep until the absolute deadline (clock_nanosleep, CLOCK_MONOTONIC, TIMER_ABSTIME:
// no drift), then one tick of sim::ClosedLoop -- the same closed loop the A/B simulation runs:
// path sample -> controller -> torque -> plant over one controller period. Measured per tick:
//   wake-up latency  time between the deadline and the return of clock_nanosleep;
//   period error     |time between successive wake-ups - period| (the loop's jitter);
//   compute time     time from the wake-up to the end of the tick's work (controller + plant).
// A tick whose work ends after the next deadline is an overrun; the loop then skips the missed
// deadlines and keeps its phase (it never bursts to catch up). Page faults taken during the loop
// are counted with getrusage.
//
// The controller's period dt follows the loop: dt = --period-ms unless --dt says otherwise (and
// 50 ms when free-running). The path (section 6, A -> B in 5 s) is sampled at dt, and the paper's
// per-tick gains are converted to continuous form once, at the paper's 50 ms tick, so that every
// dt runs the same continuous-time controller (at 50 ms exactly the A/B simulation's).
//
// Real-time rules: the model, path, plant, controllers, histograms, the CSV buffer and the CSV
// file itself are all made before the first tick. Inside the loop nothing allocates, locks, prints
// or throws: the global operator new is replaced in this binary by a counting one and the count
// over the loop is printed as `allocations_in_loop`. The CSV is written after the loop under a
// temporary name (.<name>.rt_loop.<pid>.tmp) and renamed when complete, so a cut-short file never
// looks valid; SIGINT, SIGTERM and SIGHUP end the run early with the same summary and CSV, and the
// temporaries of runs killed outright are removed by the next run writing the same CSV.
//
// Exit codes: 0 success; 1 a run-time failure -- a controller or plant fault, a joint whose |error|
// passed --divergence or that left its URDF joint limits (unless --allow-faults), an allocation in
// the loop, more overruns than --max-overruns, a real-time setting refused under --require-rt, an
// output that cannot be written; 2 bad usage.
#include <sched.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/closed_loop.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/faults.hpp"
#include "fuzzypid/sim/mismatch.hpp"
#include "fuzzypid/status.hpp"
#include "histogram.hpp"
#include "options.hpp"
#include "output_files.hpp"
// Counts every allocation of this process (replaces the global operator new/delete).
#include "fuzzypid_support/counting_new.hpp"

namespace {

namespace cli = fuzzypid::cli;
namespace robot = fuzzypid::robot;
namespace sim = fuzzypid::sim;
namespace cf = fuzzypid::controller_file;
namespace controller = fuzzypid::controller;

using fuzzypid::rt_loop::kTool;
using fuzzypid::rt_loop::Options;

// SIGINT, SIGTERM and SIGHUP all stop the loop at the next tick; the summary is printed and the
// CSV committed as after a complete run. The handlers are installed before the CSV's temporary
// file exists, so no signal of these three can leave it behind.
volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_stop_signal(int) {
  g_stop = 1;
}
void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP})
    sigaction(sig, &sa, nullptr);
}

// ---------------------------------------------------------------------------------------------
// Time.

std::int64_t to_ns(const timespec& t) noexcept {
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}
timespec from_ns(std::int64_t ns) noexcept {
  timespec t{};
  t.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  t.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  return t;
}
std::int64_t now_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return to_ns(t);
}

// ---------------------------------------------------------------------------------------------
// The loop.

struct TickRecord {
  std::int64_t latency_ns;
  std::int64_t period_error_ns;
  std::int64_t compute_ns;
};

struct LoopResult {
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;
  std::uint64_t controller_fault_ticks = 0;
  std::uint64_t plant_fault_ticks = 0;
  std::uint64_t allocations = 0;
  long minor_page_faults = 0;
  long major_page_faults = 0;
  double max_abs_error_rad = 0.0;
  sim::TrackingFaults tracking_faults{};  // joints that diverged or left their limits
  // Per joint: ticks on which the supervisor fired no rule (the gains stayed where they were).
  std::array<std::uint64_t, robot::kNumJoints> no_rule_ticks{};
};

// Histograms are large (2240 buckets each): static storage, zeroed before main.
cli::Histogram g_latency;
cli::Histogram g_period_error;
cli::Histogram g_compute;

LoopResult run_loop(sim::ClosedLoop& loop, sim::FaultMonitor& faults,
                    const robot::JointVector& torque_limit_nm, const Options& o,
                    std::uint64_t ticks, std::vector<TickRecord>* csv) {
  LoopResult r;
  const std::size_t samples = loop.samples();
  const auto period_ns = static_cast<std::int64_t>(std::llround(o.period_ms * 1e6));
  const bool free_running = period_ns == 0;

  rusage usage_before{};
  getrusage(RUSAGE_SELF, &usage_before);
  const std::uint64_t allocations_before = fuzzypid::support::allocation_count();
  std::int64_t deadline = now_ns() + (free_running ? 0 : period_ns);
  std::int64_t last_woke = 0;
  for (std::uint64_t k = 0; k < ticks && g_stop == 0; ++k) {
    std::int64_t latency = 0;
    if (!free_running) {
      const timespec ts = from_ns(deadline);
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
        if (g_stop != 0) break;
      }
      if (g_stop != 0) break;
    }
    const std::int64_t woke = now_ns();
    if (!free_running) latency = woke - deadline;
    const std::int64_t period_error =
        k == 0 || free_running ? 0 : std::llabs(woke - last_woke - period_ns);
    last_woke = woke;

    // --loop: A -> B -> A ... without a jump; else the path's last point is held.
    const sim::TickResult t =
        o.loop_path ? loop.tick(loop.cyclic_sample(k))
                    : loop.tick(k < samples ? static_cast<std::size_t>(k) : samples - 1);
    if (fuzzypid::is_fault(t.command.status)) ++r.controller_fault_ticks;
    if (t.plant == robot::PlantStatus::InvalidInput ||
        t.plant == robot::PlantStatus::NumericalError)
      ++r.plant_fault_ticks;
    for (std::size_t j = 0; j < robot::kNumJoints; ++j) {
      if (t.command.joint_status[j] == fuzzypid::Status::NoRuleFired) ++r.no_rule_ticks[j];
      const double err = std::fabs(t.theta_d[j] - t.theta[j]);
      if (err > r.max_abs_error_rad) r.max_abs_error_rad = err;
    }
    (void)faults.observe(t.t_s, t.theta_d, t.theta, loop.plant().applied_torque(),
                         sim::at_torque_limit(loop.plant().applied_torque(),
                                              loop.plant().saturated(), torque_limit_nm));
    const std::int64_t done = now_ns();

    g_compute.record(done - woke);
    if (!free_running) {
      g_latency.record(latency);
      if (k > 0) g_period_error.record(period_error);
    }
    if (csv != nullptr) (*csv)[k] = {latency, period_error, done - woke};
    ++r.ticks;

    if (!free_running) {
      deadline += period_ns;
      if (done > deadline) {
        // Overrun: skip the deadlines already missed, keeping the phase.
        ++r.overruns;
        const std::int64_t missed = (done - deadline) / period_ns + 1;
        deadline += missed * period_ns;
      }
    }
  }
  r.allocations = fuzzypid::support::allocation_count() - allocations_before;
  r.tracking_faults = faults.faults();
  rusage usage_after{};
  getrusage(RUSAGE_SELF, &usage_after);
  r.minor_page_faults = usage_after.ru_minflt - usage_before.ru_minflt;
  r.major_page_faults = usage_after.ru_majflt - usage_before.ru_majflt;
  return r;
}

void print_histogram(const char* name, const cli::Histogram& h) {
  const auto us = [](std::uint64_t ns) { return static_cast<double>(ns) / 1000.0; };
  std::printf("%s_us: min %.3f  median %.3f  p99 %.3f  p99.9 %.3f  max %.3f  (n=%llu)\n", name,
              us(h.min()), us(h.quantile(0.5)), us(h.quantile(0.99)), us(h.quantile(0.999)),
              us(h.max()), static_cast<unsigned long long>(h.count()));
}

// Touches 256 KiB of stack so the pages exist (and are locked with --lock-memory) before the loop.
void prefault_stack() {
  constexpr std::size_t kBytes = 256 * 1024;
  unsigned char buffer[kBytes];
  std::memset(buffer, 0, kBytes);
  asm volatile("" : : "r"(buffer) : "memory");  // keeps the writes
}

// Applies the requested operating-system settings. Each outcome is described in the returned
// lines; a refusal is a warning, or with --require-rt an error (false).
bool apply_rt_settings(const Options& o, std::string& cpu_state, std::string& lock_state,
                       std::string& fifo_state) {
  bool ok = true;
  const auto refused = [&](std::string& state, const std::string& what, const char* hint) {
    const int err = errno;
    state = "REFUSED (" + std::string(std::strerror(err)) + ")";
    std::fprintf(stderr, "%s: %s: %s refused: %s%s\n", kTool, o.require_rt ? "error" : "warning",
                 what.c_str(), std::strerror(err), hint);
    ok = ok && !o.require_rt;
  };
  cpu_state = "not requested";
  if (o.cpu) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(*o.cpu, &set);
    if (sched_setaffinity(0, sizeof(set), &set) == 0) {
      cpu_state = "pinned to CPU " + std::to_string(*o.cpu);
    } else {
      refused(cpu_state, "pinning to CPU " + std::to_string(*o.cpu), "");
    }
  }
  lock_state = "not requested";
  if (o.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      lock_state = "locked";
    } else {
      refused(lock_state, "mlockall", " (needs CAP_IPC_LOCK or a larger RLIMIT_MEMLOCK)");
    }
  }
  fifo_state = "not requested (SCHED_OTHER)";
  if (o.fifo_priority) {
    sched_param p{};
    p.sched_priority = *o.fifo_priority;
    if (sched_setscheduler(0, SCHED_FIFO, &p) == 0) {
      fifo_state = "SCHED_FIFO priority " + std::to_string(*o.fifo_priority);
    } else {
      refused(fifo_state, "SCHED_FIFO", " (needs CAP_SYS_NICE or an rtprio limit)");
    }
  }
  return ok;
}

int run(int argc, char** argv) {
  Options o;
  if (const auto code = fuzzypid::rt_loop::parse(argc, argv, o)) return *code;
  install_stop_handlers();

  // --- Model, path, closed loop and outputs (allocating; all before the loop).
  const double dt_s = o.controller_dt_s();
  // The A/B simulation's settings ("paper" scenario) with the controller period dt and the robot
  // options; the paper's per-tick gains keep referring to its 50 ms tick (see the file comment).
  sim::ExperimentOptions options;
  const double paper_tick_s = options.tick_s;
  sim::Condition condition = *sim::find_scenario("paper");
  o.robot.apply(condition);
  condition.robot.tick_s = dt_s;
  if (const std::string bad = condition.validate(); !bad.empty()) {
    std::fprintf(stderr, "%s: %s\n", kTool, bad.c_str());
    return cli::kExitUsage;
  }
  // The options checked --csv against the controller file; the robot model and the path are
  // inputs too.
  if (!o.csv.empty()) {
    const std::string urdf =
        condition.robot.urdf.empty() ? robot::default_urdf_path() : condition.robot.urdf;
    std::vector<std::string> inputs = {urdf};
    if (!condition.robot.path.empty()) inputs.push_back(condition.robot.path);
    if (const std::string bad = cli::check_output_path(o.csv, inputs); !bad.empty()) {
      std::fprintf(stderr, "%s: --csv: %s\n", kTool, bad.c_str());
      return cli::kExitUsage;
    }
  }
  std::string error;
  const auto experiment = sim::Experiment::create(condition.robot, options, error);
  if (!experiment) {
    std::fprintf(stderr, "%s: %s\n", kTool, error.c_str());
    return cli::kExitFailure;
  }
  cli::print_robot_note(kTool, *experiment);
  std::fprintf(stderr, "%s: plant %s\n", kTool, cli::plant_note(condition).c_str());
  cli::print_model_notes(kTool, *experiment);
  cli::warn_about_payload(kTool, *experiment, condition);
  controller::ControllerSpec spec = sim::default_controller(
      options, o.controller == "fuzzy" ? controller::paper_fuzzy() : controller::paper_pid());
  spec.units.tick_s = paper_tick_s;
  double tuned_tick_s = 0.0;  // the tick the file's [tuning] records (0: none)
  if (o.controller != "pid" && o.controller != "fuzzy") {
    fuzzypid::FileError file_error;
    cf::ControllerFile file;
    if (!cf::load(o.controller, file, file_error)) {
      std::fprintf(stderr, "%s: %s\n", kTool, file_error.to_string().c_str());
      return cli::kExitFailure;
    }
    spec = std::move(file.controller);
    if (file.tuning) tuned_tick_s = file.tuning->tick_s;
    cli::warn_about_training(kTool, o.controller, file.tuning ? &*file.tuning : nullptr,
                             *experiment);
    if (const std::string bad = o.given.refuse_unused(
            {"--strict-rules"}, controller::family_traits(spec.family).supervised(),
            "a controller with a supervisor",
            o.controller + " is a " + controller::to_string(spec.family) +
                " controller, which has none");
        !bad.empty()) {
      std::fprintf(stderr, "%s: %s\n", kTool, bad.c_str());
      return cli::kExitUsage;
    }
  }
  for (const std::string& why :
       {sim::tick_mismatch(tuned_tick_s, dt_s), sim::feedforward_mismatch(spec, condition)})
    if (!why.empty())
      std::fprintf(stderr, "%s: warning: %s: %s\n", kTool, o.controller.c_str(), why.c_str());
  auto loop = sim::ClosedLoop::create(*experiment, condition, spec, error);
  if (!loop) {
    std::fprintf(stderr, "%s: %s\n", kTool, error.c_str());
    return cli::kExitFailure;
  }

  const std::uint64_t ticks = o.ticks.value_or(loop->samples());
  if (o.loop_path && ticks <= loop->samples()) {
    std::fprintf(stderr,
                 "%s: --loop applies only to --ticks beyond one pass; --ticks %llu is within the "
                 "path's %zu samples\n",
                 kTool, static_cast<unsigned long long>(ticks), loop->samples());
    return cli::kExitUsage;
  }
  std::unique_ptr<cli::OutputFile> csv_file;
  std::vector<TickRecord> csv;
  if (!o.csv.empty()) {
    csv_file = cli::OutputFile::open(o.csv, error, kTool);
    if (!csv_file) {
      std::fprintf(stderr, "%s: --csv: %s\n", kTool, error.c_str());
      return cli::kExitFailure;
    }
    csv.assign(ticks, TickRecord{0, 0, 0});
  }

  std::string cpu_state, lock_state, fifo_state;
  if (!apply_rt_settings(o, cpu_state, lock_state, fifo_state)) return cli::kExitFailure;
  prefault_stack();

  std::printf(
      "rt_loop: controller %s, period %.3f ms%s, controller dt %.3f ms, ticks %llu, path %zu "
      "samples over %.3f s%s\n",
      o.controller.c_str(), o.period_ms, o.period_ms == 0.0 ? " (free-running)" : "", dt_s * 1000.0,
      static_cast<unsigned long long>(ticks), loop->samples(), loop->path().time_s.back(),
      o.loop_path ? " (played back and forth)" : " (held at its end)");
  std::printf("cpu: %s\nmemory: %s\nscheduler: %s\n", cpu_state.c_str(), lock_state.c_str(),
              fifo_state.c_str());
  std::fflush(stdout);

  sim::FaultMonitor faults(o.divergence_rad, experiment->model().lower_limits_rad(),
                           experiment->model().upper_limits_rad());
  const LoopResult r = run_loop(*loop, faults, experiment->torque_limit(condition), o, ticks,
                                csv_file ? &csv : nullptr);

  // --- After the loop: summary and CSV.
  if (g_stop != 0) std::printf("interrupted: stopped at the next tick\n");
  std::printf("ticks_run: %llu ticks\n", static_cast<unsigned long long>(r.ticks));
  std::printf("overruns: %llu ticks\n", static_cast<unsigned long long>(r.overruns));
  if (o.period_ms == 0.0) {
    std::printf("wakeup_latency_us: n/a (free-running)\nperiod_error_us: n/a (free-running)\n");
  } else {
    print_histogram("wakeup_latency", g_latency);
    print_histogram("period_error", g_period_error);
  }
  print_histogram("compute", g_compute);
  std::printf(
      "controller_fault_ticks: %llu ticks\nplant_fault_ticks: %llu ticks\n"
      "max_abs_error_rad: %.6g rad\n",
      static_cast<unsigned long long>(r.controller_fault_ticks),
      static_cast<unsigned long long>(r.plant_fault_ticks), r.max_abs_error_rad);
  std::printf("tracking_fault_ticks: %llu ticks (|error| > %g rad or outside the joint limits)\n",
              static_cast<unsigned long long>(r.tracking_faults.ticks), o.divergence_rad);
  for (const std::string& line :
       sim::describe(r.tracking_faults, o.divergence_rad, experiment->model().lower_limits_rad(),
                     experiment->model().upper_limits_rad()))
    std::fprintf(stderr, "%s: fault: %s\n", kTool, line.c_str());
  std::printf("page_faults_in_loop: minor %ld, major %ld\n", r.minor_page_faults,
              r.major_page_faults);
  std::printf("allocations_in_loop: %llu\n", static_cast<unsigned long long>(r.allocations));
  std::uint64_t no_rule = 0;
  std::printf("no_rule_ticks:");
  for (std::size_t j = 0; j < robot::kNumJoints; ++j) {
    std::printf("%s%llu", j == 0 ? " " : ",", static_cast<unsigned long long>(r.no_rule_ticks[j]));
    no_rule += r.no_rule_ticks[j];
  }
  std::printf(" ticks (joints 1-6)\n");
  if (no_rule != 0)
    std::fprintf(stderr,
                 "%s: warning: on %llu joint-ticks the supervisor fired no rule and the gains "
                 "stayed where they were (a coverage gap of the rule base)%s\n",
                 kTool, static_cast<unsigned long long>(no_rule),
                 o.strict_rules ? "" : "; --strict-rules makes this an error");

  int code = cli::kExitOk;
  if (csv_file) {
    std::FILE* f = csv_file->file();
    std::fputs("tick,wakeup_latency_ns,period_error_ns,compute_ns\n", f);
    for (std::uint64_t k = 0; k < r.ticks; ++k)
      std::fprintf(f, "%llu,%lld,%lld,%lld\n", static_cast<unsigned long long>(k),
                   static_cast<long long>(csv[k].latency_ns),
                   static_cast<long long>(csv[k].period_error_ns),
                   static_cast<long long>(csv[k].compute_ns));
    if (csv_file->commit(error)) {
      std::printf("csv: %s (%llu rows)\n", o.csv.c_str(), static_cast<unsigned long long>(r.ticks));
    } else {
      std::fprintf(stderr, "%s: --csv: %s\n", kTool, error.c_str());
      code = cli::kExitFailure;
    }
  }
  const auto failure = [&](const char* what) {
    std::fprintf(stderr, "%s: %s\n", kTool, what);
    code = cli::kExitFailure;
  };
  if (r.allocations != 0) failure("the loop allocated");
  if (r.controller_fault_ticks != 0) failure("the controller reported faults");
  if (r.plant_fault_ticks != 0) failure("the plant reported faults");
  if (r.tracking_faults.any()) {
    if (o.allow_faults) {
      std::fprintf(stderr, "%s: joints faulted (accepted: --allow-faults)\n", kTool);
    } else {
      failure(
          "joints faulted: |error| > --divergence or outside their limits (--allow-faults "
          "accepts it)");
    }
  }
  if (no_rule != 0 && o.strict_rules) failure("the supervisor fired no rule (--strict-rules)");
  if (o.max_overruns && r.overruns > *o.max_overruns) failure("more overruns than --max-overruns");
  const int written = cli::finish_stdout(kTool);
  return code != cli::kExitOk ? code : written;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_main(kTool, [&] { return run(argc, argv); });
}
