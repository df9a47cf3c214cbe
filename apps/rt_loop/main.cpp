// rt_loop: the 6-joint controller against the simulated ER50-C20 in a fixed-period loop, the way
// it would run on a robot controller, with its timing measured.
//
// Each tick: sleep until the absolute deadline (clock_nanosleep, CLOCK_MONOTONIC, TIMER_ABSTIME:
// no drift), read the plant's joint state, run JointController::step against the section 6 path
// sample, apply the torque to the plant for one period. Measured per tick:
//   wake-up latency  time between the deadline and the return of clock_nanosleep;
//   compute time     time from that return to the end of the tick's work (controller + plant);
//   controller time  the JointController::step call alone.
// A tick whose work ends after the next deadline is an overrun; the loop then skips the missed
// deadlines and keeps its phase (it never bursts to catch up).
//
// Real-time rules: the model, path, plant, controllers, histograms and the optional CSV buffer are
// all built before the first tick. Inside the loop nothing allocates, locks, prints or throws: the
// global operator new is replaced in this binary by a counting one and the count over the loop is
// printed as `allocations_in_loop`. Statistics are fixed-bucket histograms; the CSV is written
// after the loop.
//
// Path, plant and controllers are built by sim::Experiment exactly as the A/B simulation builds
// them (sim::ExperimentOptions defaults, the "paper" scenario; see apps/sim_ab and
// docs/reproduction.md): the paper's per-tick gains
// (Kp 4, Ki 0.001, Kd 100) converted to continuous form, acting on an inertia-normalised loop
// (torque = J^_i u_i, J^_i the nominal joint inertia at the path start), derivative from the
// measured rates, output limited to the URDF effort limit, start 0.05 rad behind the path.
#include <sched.h>
#include <signal.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzypid/control/fuzzy_pid.hpp"
#include "fuzzypid/control/joint_controller.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/experiment.hpp"
// Counts every allocation of this process (replaces the global operator new/delete).
#include "fuzzypid_support/counting_new.hpp"

namespace {

namespace robot = fuzzypid::robot;
namespace control = fuzzypid::control;
namespace pid = fuzzypid::pid;
namespace sim = fuzzypid::sim;

constexpr std::size_t kJoints = robot::kNumJoints;
// With --csv every tick is buffered; this caps the buffer at 24 bytes x 50M = 1.2 GB.
constexpr std::uint64_t kMaxCsvTicks = 50'000'000;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_sigint(int) {
  g_stop = 1;
}

// ---------------------------------------------------------------------------------------------
// Fixed-bucket log-linear histogram of durations in ns: exact below 128 ns, then 64 buckets per
// power of two (relative resolution 1/64, about 1.6 %), up to 2^40 ns (18 min). Recording is two
// shifts and an increment; min and max are kept exactly.

class Histogram {
 public:
  static constexpr int kSubBits = 6;
  static constexpr std::uint64_t kSub = 1u << kSubBits;  // 64
  static constexpr int kMaxBits = 40;
  static constexpr std::size_t kBuckets = (kMaxBits - kSubBits + 1) * kSub;

  void record(std::int64_t ns) noexcept {
    const std::uint64_t v = ns < 0 ? 0 : static_cast<std::uint64_t>(ns);
    ++counts_[index(v)];
    ++n_;
    if (v < min_) min_ = v;
    if (v > max_) max_ = v;
  }

  std::uint64_t count() const noexcept { return n_; }
  std::uint64_t min() const noexcept { return n_ == 0 ? 0 : min_; }
  std::uint64_t max() const noexcept { return max_; }

  // The smallest recorded value v such that at least q of the samples are <= v, to bucket
  // resolution (the bucket's upper edge, clamped into [min, max]).
  std::uint64_t quantile(double q) const noexcept {
    if (n_ == 0) return 0;
    const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(n_)));
    const std::uint64_t target = rank == 0 ? 1 : rank;
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < kBuckets; ++i) {
      seen += counts_[i];
      if (seen >= target) {
        const std::uint64_t hi = upper_edge(i);
        return hi < min_ ? min_ : (hi > max_ ? max_ : hi);
      }
    }
    return max_;
  }

 private:
  static std::size_t index(std::uint64_t v) noexcept {
    if (v < 2 * kSub) return static_cast<std::size_t>(v);
    if (v >= (std::uint64_t{1} << kMaxBits)) return kBuckets - 1;
    const int msb = 63 - __builtin_clzll(v);
    const int shift = msb - kSubBits;
    return static_cast<std::size_t>((shift + 1) * kSub + ((v >> shift) - kSub));
  }
  static std::uint64_t upper_edge(std::size_t i) noexcept {
    if (i < 2 * kSub) return i;
    const std::uint64_t shift = i / kSub - 1;
    const std::uint64_t sub = i % kSub + kSub;
    return ((sub + 1) << shift) - 1;
  }

  std::array<std::uint64_t, kBuckets> counts_{};
  std::uint64_t n_ = 0;
  std::uint64_t min_ = UINT64_MAX;
  std::uint64_t max_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Options.

enum class ControllerChoice { Pid, Fuzzy };

struct Options {
  double period_ms = 50.0;
  std::optional<std::uint64_t> ticks;  // default: one pass of the path
  ControllerChoice controller = ControllerChoice::Fuzzy;
  std::string csv;
  std::optional<int> fifo_priority;
  bool lock_memory = false;
  std::optional<int> cpu;
  bool loop_path = false;
};

void print_usage(std::FILE* f) {
  std::fputs(
      "usage: rt_loop [options]\n"
      "  --period-ms P        tick period in ms (default 50; 0 = free-running)\n"
      "  --ticks N            ticks to run, N >= 1 (default: one pass of the path)\n"
      "  --controller pid|fuzzy  (default fuzzy)\n"
      "  --loop               restart the path at its end (else hold its last point)\n"
      "  --csv FILE           write tick,wakeup_latency_ns,compute_ns,controller_ns after the run\n"
      "  --fifo PRIO          SCHED_FIFO at priority PRIO\n"
      "  --lock-memory        mlockall(MCL_CURRENT | MCL_FUTURE)\n"
      "  --cpu K              pin to CPU K\n"
      "Ctrl-C stops at the next tick and prints the summary.\n",
      f);
}

bool parse_double(const char* s, double& out) {
  if (s == nullptr || *s == '\0') return false;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (errno != 0 || end == s || *end != '\0' || !std::isfinite(v)) return false;
  out = v;
  return true;
}

bool parse_int(const char* s, long long& out) {
  if (s == nullptr || *s == '\0') return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(s, &end, 10);
  if (errno != 0 || end == s || *end != '\0') return false;
  out = v;
  return true;
}

// Returns an error message, or nullopt when the arguments are valid. Sets `help` for --help.
std::optional<std::string> parse_options(int argc, char** argv, Options& o, bool& help) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    const auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "--help" || a == "-h") {
      help = true;
      return std::nullopt;
    } else if (a == "--period-ms") {
      const char* v = value();
      if (v == nullptr) return std::string("--period-ms needs a value");
      if (!parse_double(v, o.period_ms))
        return "--period-ms: '" + std::string(v) + "' is not a number";
      if (o.period_ms < 0.0) return "--period-ms must be >= 0 (got " + std::string(v) + ")";
      if (o.period_ms > 60'000.0) return std::string("--period-ms must be at most 60000");
    } else if (a == "--ticks") {
      const char* v = value();
      long long n = 0;
      if (v == nullptr) return std::string("--ticks needs a value");
      if (!parse_int(v, n)) return "--ticks: '" + std::string(v) + "' is not an integer";
      if (n < 1) return "--ticks must be at least 1 (got " + std::string(v) + ")";
      o.ticks = static_cast<std::uint64_t>(n);
    } else if (a == "--controller") {
      const char* v = value();
      if (v == nullptr) return std::string("--controller needs a value (pid or fuzzy)");
      const std::string_view c = v;
      if (c == "pid") {
        o.controller = ControllerChoice::Pid;
      } else if (c == "fuzzy") {
        o.controller = ControllerChoice::Fuzzy;
      } else {
        return "--controller: unknown controller '" + std::string(v) + "' (pid or fuzzy)";
      }
    } else if (a == "--csv") {
      const char* v = value();
      if (v == nullptr || *v == '\0') return std::string("--csv needs a file name");
      o.csv = v;
    } else if (a == "--fifo") {
      const char* v = value();
      long long p = 0;
      if (v == nullptr) return std::string("--fifo needs a priority");
      if (!parse_int(v, p)) return "--fifo: '" + std::string(v) + "' is not an integer";
      const int lo = sched_get_priority_min(SCHED_FIFO);
      const int hi = sched_get_priority_max(SCHED_FIFO);
      if (p < lo || p > hi)
        return "--fifo: priority " + std::string(v) + " outside [" + std::to_string(lo) + ", " +
               std::to_string(hi) + "]";
      o.fifo_priority = static_cast<int>(p);
    } else if (a == "--lock-memory") {
      o.lock_memory = true;
    } else if (a == "--cpu") {
      const char* v = value();
      long long k = 0;
      if (v == nullptr) return std::string("--cpu needs a CPU index");
      if (!parse_int(v, k)) return "--cpu: '" + std::string(v) + "' is not an integer";
      const long configured = sysconf(_SC_NPROCESSORS_CONF);
      if (k < 0 || k >= configured || k >= CPU_SETSIZE)
        return "--cpu: CPU " + std::string(v) + " does not exist (this machine has " +
               std::to_string(configured) + " CPUs, 0.." + std::to_string(configured - 1) + ")";
      o.cpu = static_cast<int>(k);
    } else if (a == "--loop") {
      o.loop_path = true;
    } else {
      return "unknown argument '" + std::string(a) + "' (see --help)";
    }
  }
  if (!o.csv.empty() && o.ticks && *o.ticks > kMaxCsvTicks)
    return "--csv buffers every tick in memory: at most " + std::to_string(kMaxCsvTicks) + " ticks";
  return std::nullopt;
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
  std::int64_t compute_ns;
  std::int64_t controller_ns;
};

struct LoopResult {
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;
  std::uint64_t controller_faults = 0;
  std::uint64_t plant_faults = 0;
  std::uint64_t allocations = 0;
  double max_abs_error_rad = 0.0;
};

// Histograms are large (2240 buckets each): static storage, zeroed before main.
Histogram g_latency;
Histogram g_compute;
Histogram g_controller;

template <class Controller>
LoopResult run_loop(control::JointController<double, kJoints, Controller>& controller,
                    robot::JointPlant& plant, const sim::Experiment& experiment, const Options& o,
                    std::uint64_t ticks, std::vector<TickRecord>* csv) {
  LoopResult r;
  const robot::JointPathResult& path = experiment.path();
  const std::size_t samples = path.time_s.size();
  const double dt_s = experiment.options().tick_s;
  const std::int64_t period_ns = static_cast<std::int64_t>(std::llround(o.period_ms * 1e6));
  const bool free_running = period_ns == 0;
  const robot::JointVector zero{};

  const std::uint64_t allocations_before = fuzzypid::support::allocation_count();
  std::int64_t deadline = now_ns() + (free_running ? 0 : period_ns);
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

    const std::size_t i = o.loop_path ? k % samples : (k < samples ? k : samples - 1);
    const bool holding = !o.loop_path && k >= samples;
    const robot::JointVector& qd = path.position_rad[i];
    const robot::JointVector& vd = holding ? zero : path.velocity_rad_s[i];

    control::JointInput<double, kJoints> in;
    in.desired_position_rad = qd;
    in.desired_velocity_rad_s = vd;
    in.measured_position_rad = plant.position();
    in.measured_velocity_rad_s = plant.velocity();
    const std::int64_t c0 = now_ns();
    const auto command = controller.step(in, dt_s);
    const std::int64_t c1 = now_ns();
    if (fuzzypid::is_fault(command.status)) ++r.controller_faults;

    const robot::JointVector torque = experiment.torque_from_command(command.torque_nm);
    for (std::size_t j = 0; j < kJoints; ++j) {
      const double err = std::fabs(qd[j] - plant.position()[j]);
      if (err > r.max_abs_error_rad) r.max_abs_error_rad = err;
    }
    const robot::PlantStatus ps = plant.step(torque, dt_s);
    if (ps == robot::PlantStatus::InvalidInput || ps == robot::PlantStatus::NumericalError)
      ++r.plant_faults;
    const std::int64_t done = now_ns();

    g_controller.record(c1 - c0);
    g_compute.record(done - woke);
    if (!free_running) g_latency.record(latency);
    if (csv != nullptr) (*csv)[k] = {latency, done - woke, c1 - c0};
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
  return r;
}

void print_histogram(const char* name, const Histogram& h) {
  const auto us = [](std::uint64_t ns) { return static_cast<double>(ns) / 1000.0; };
  std::printf("%s_us: min %.3f  median %.3f  p99 %.3f  p99.9 %.3f  max %.3f  (n=%llu)\n", name,
              us(h.min()), us(h.quantile(0.5)), us(h.quantile(0.99)), us(h.quantile(0.999)),
              us(h.max()), static_cast<unsigned long long>(h.count()));
}

// Touches `bytes` of stack so the pages exist (and are locked with --lock-memory) before the loop.
void prefault_stack() {
  constexpr std::size_t kBytes = 256 * 1024;
  unsigned char buffer[kBytes];
  std::memset(buffer, 0, kBytes);
  asm volatile("" : : "r"(buffer) : "memory");  // keeps the writes
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  bool help = false;
  if (const auto error = parse_options(argc, argv, o, help)) {
    std::fprintf(stderr, "rt_loop: %s\n", error->c_str());
    return 2;
  }
  if (help) {
    print_usage(stdout);
    return 0;
  }

  // --- Model, path and plant (allocating; all before the loop).
  robot::LoadResult loaded = robot::RobotModel::load(robot::default_urdf_path());
  if (!loaded.model) {
    std::fprintf(stderr, "rt_loop: cannot load the robot model: %s\n", loaded.error.c_str());
    return 1;
  }
  const robot::RobotModel& model = *loaded.model;
  // The A/B simulation's experiment (scenario "paper"): same path, plant and controllers.
  std::string error;
  const auto experiment =
      sim::Experiment::create(model, robot::paper_path_spec(), sim::ExperimentOptions{}, error);
  if (!experiment) {
    std::fprintf(stderr, "rt_loop: %s\n", error.c_str());
    return 1;
  }
  const sim::Scenario& scenario = *sim::find_scenario("paper");
  const robot::JointVector torque_limit = experiment->torque_limit(scenario);

  robot::JointPlant plant(model, experiment->plant_config(scenario));
  if (!plant.valid()) {
    std::fprintf(stderr, "rt_loop: invalid plant configuration\n");
    return 1;
  }
  plant.reset(experiment->initial_position(), robot::JointVector{});

  using Fuzzy = fuzzypid::paper::FuzzyPid<double>;
  control::JointController<double, kJoints, Fuzzy> fuzzy_controller(
      experiment->make_fuzzy_pid(torque_limit));
  control::JointController<double, kJoints, pid::Pid<double>> pid_controller(
      experiment->make_pid(torque_limit));

  const std::uint64_t ticks = o.ticks.value_or(experiment->path().time_s.size());
  std::vector<TickRecord> csv;
  if (!o.csv.empty()) csv.assign(ticks, TickRecord{0, 0, 0});

  // --- Operating-system settings, each reported; a refusal is a warning, not an error.
  std::string cpu_state = "not requested";
  if (o.cpu) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(*o.cpu, &set);
    if (sched_setaffinity(0, sizeof(set), &set) == 0) {
      cpu_state = "pinned to CPU " + std::to_string(*o.cpu);
    } else {
      cpu_state = "REFUSED (" + std::string(std::strerror(errno)) + ")";
      std::fprintf(stderr, "rt_loop: warning: pinning to CPU %d refused: %s; running unpinned\n",
                   *o.cpu, std::strerror(errno));
    }
  }
  std::string lock_state = "not requested";
  if (o.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      lock_state = "locked";
    } else {
      lock_state = "REFUSED (" + std::string(std::strerror(errno)) + ")";
      std::fprintf(stderr,
                   "rt_loop: warning: mlockall refused: %s (needs CAP_IPC_LOCK or a larger "
                   "RLIMIT_MEMLOCK); memory not locked\n",
                   std::strerror(errno));
    }
  }
  std::string fifo_state = "not requested (SCHED_OTHER)";
  if (o.fifo_priority) {
    sched_param p{};
    p.sched_priority = *o.fifo_priority;
    if (sched_setscheduler(0, SCHED_FIFO, &p) == 0) {
      fifo_state = "SCHED_FIFO priority " + std::to_string(*o.fifo_priority);
    } else {
      fifo_state = "REFUSED (" + std::string(std::strerror(errno)) + ")";
      std::fprintf(stderr,
                   "rt_loop: warning: SCHED_FIFO refused: %s (needs CAP_SYS_NICE or an rtprio "
                   "limit); running at normal priority\n",
                   std::strerror(errno));
    }
  }
  prefault_stack();

  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);

  const char* controller_name = o.controller == ControllerChoice::Fuzzy ? "fuzzy" : "pid";
  std::printf("rt_loop: controller %s, period %.3f ms%s, ticks %llu, path %zu samples%s\n",
              controller_name, o.period_ms, o.period_ms == 0.0 ? " (free-running)" : "",
              static_cast<unsigned long long>(ticks), experiment->path().time_s.size(),
              o.loop_path ? " (looped)" : " (held at its end)");
  std::printf("cpu: %s\nmemory: %s\nscheduler: %s\n", cpu_state.c_str(), lock_state.c_str(),
              fifo_state.c_str());
  std::fflush(stdout);

  std::vector<TickRecord>* csv_buffer = o.csv.empty() ? nullptr : &csv;
  const LoopResult r = o.controller == ControllerChoice::Fuzzy
                           ? run_loop(fuzzy_controller, plant, *experiment, o, ticks, csv_buffer)
                           : run_loop(pid_controller, plant, *experiment, o, ticks, csv_buffer);

  // --- After the loop: summary and CSV.
  if (g_stop != 0) std::printf("interrupted: stopped at the next tick\n");
  std::printf("ticks_run: %llu\n", static_cast<unsigned long long>(r.ticks));
  std::printf("overruns: %llu\n", static_cast<unsigned long long>(r.overruns));
  if (o.period_ms == 0.0) {
    std::printf("wakeup_latency_us: n/a (free-running)\n");
  } else {
    print_histogram("wakeup_latency", g_latency);
  }
  print_histogram("compute", g_compute);
  print_histogram("controller", g_controller);
  std::printf("controller_faults: %llu\nplant_faults: %llu\nmax_abs_error_rad: %.6g\n",
              static_cast<unsigned long long>(r.controller_faults),
              static_cast<unsigned long long>(r.plant_faults), r.max_abs_error_rad);
  std::printf("allocations_in_loop: %llu\n", static_cast<unsigned long long>(r.allocations));

  if (csv_buffer != nullptr) {
    std::FILE* f = std::fopen(o.csv.c_str(), "w");
    if (f == nullptr) {
      std::fprintf(stderr, "rt_loop: cannot write %s: %s\n", o.csv.c_str(), std::strerror(errno));
      return 1;
    }
    std::fputs("tick,wakeup_latency_ns,compute_ns,controller_ns\n", f);
    for (std::uint64_t k = 0; k < r.ticks; ++k)
      std::fprintf(f, "%llu,%lld,%lld,%lld\n", static_cast<unsigned long long>(k),
                   static_cast<long long>(csv[k].latency_ns),
                   static_cast<long long>(csv[k].compute_ns),
                   static_cast<long long>(csv[k].controller_ns));
    if (std::fclose(f) != 0) {
      std::fprintf(stderr, "rt_loop: error writing %s\n", o.csv.c_str());
      return 1;
    }
    std::printf("csv: %s (%llu rows)\n", o.csv.c_str(), static_cast<unsigned long long>(r.ticks));
  }
  if (r.allocations != 0 || r.controller_faults != 0 || r.plant_faults != 0) return 3;
  return 0;
}
