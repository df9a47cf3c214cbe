#include "options.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output_files.hpp"

namespace fuzzypid::rt_loop {

std::optional<int> parse(int argc, const char* const* argv, Options& o) {
  CLI::App app(
      "The 6-joint controller against the simulated arm (the ER50-C20, or --urdf with --path) in "
      "a fixed-period loop, with its "
      "timing measured (docs/performance.md). Ctrl-C (SIGINT), SIGTERM or SIGHUP stops at the "
      "next tick, prints the summary and writes the CSV.\nExit codes: 0 success, 1 a run-time "
      "failure (controller or plant fault, a joint whose |error| passes --divergence or that "
      "leaves its limits unless --allow-faults, allocation in the loop, too many overruns, a "
      "refused "
      "setting under --require-rt, a write error), 2 bad usage (including a --csv that cannot be "
      "written: docs/robustness.md, Outputs).",
      kTool);
  app.add_option("--period-ms", o.period_ms, "tick period, ms (default 50; 0 = free-running)")
      ->check(cli::finite_in(0.0, kMaxPeriodMs))
      ->option_text("MS");
  app.add_option("--dt", o.dt_s,
                 "controller period, s (default: the tick period; 0.05 when free-running)")
      ->check(cli::finite_in(kMinDtS, kMaxDtS))
      ->option_text("S");
  app.add_option("--ticks", o.ticks, "ticks to run (default: one pass of the path)")
      ->check(cli::unsigned_in(1, std::numeric_limits<std::uint64_t>::max()))
      ->option_text("N");
  app.add_option("--controller", o.controller,
                 "the paper's fixed PID (pid) or fuzzy PID (fuzzy), or a controller file "
                 "(*.toml, docs/tuning.md) (default fuzzy)")
      ->check([](const std::string& s) -> std::string {
        const bool file = s.size() > 5 && s.compare(s.size() - 5, 5, ".toml") == 0;
        return s == "pid" || s == "fuzzy" || file ? ""
                                                  : "'" + s + "' is not pid, fuzzy or a .toml file";
      })
      ->option_text("pid|fuzzy|FILE");
  app.add_flag("--loop", o.loop_path,
               "play the path back and forth, A -> B -> A ... (else hold its last point)");
  app.add_option("--csv", o.csv,
                 "write tick,wakeup_latency_ns,period_error_ns,compute_ns after the run")
      ->option_text("FILE");
  const int lo = sched_get_priority_min(SCHED_FIFO);
  const int hi = sched_get_priority_max(SCHED_FIFO);
  app.add_option("--fifo", o.fifo_priority, "SCHED_FIFO at priority PRIO")
      ->check(cli::unsigned_in(static_cast<std::uint64_t>(lo), static_cast<std::uint64_t>(hi)))
      ->option_text("PRIO");
  app.add_flag("--lock-memory", o.lock_memory, "mlockall(MCL_CURRENT | MCL_FUTURE)");
  const long configured = sysconf(_SC_NPROCESSORS_CONF);
  const long last_cpu = std::min<long>(configured, CPU_SETSIZE) - 1;
  app.add_option("--cpu", o.cpu, "pin to CPU K")
      ->check(cli::unsigned_in(0, static_cast<std::uint64_t>(last_cpu < 0 ? 0 : last_cpu)))
      ->option_text("K");
  app.add_flag("--require-rt", o.require_rt,
               "a refused --fifo, --lock-memory or --cpu is an error (else a warning)");
  app.add_flag("--strict-rules", o.strict_rules,
               "a tick on which the supervisor fires no rule is an error (else a warning)");
  app.add_option("--divergence", o.divergence_rad,
                 "a joint whose |error| exceeds this, rad, faults, as does one that leaves its "
                 "URDF joint limits (default 1, as tune's)")
      ->check(cli::finite_in(std::numeric_limits<double>::min(), 1e300))
      ->option_text("RAD");
  app.add_flag("--allow-faults", o.allow_faults,
               "joints that diverge or leave their limits are counted and named but exit 0");
  app.add_option("--max-overruns", o.max_overruns,
                 "exit 1 when more than N ticks overran (default: any number)")
      ->check(cli::unsigned_integer())
      ->option_text("N");
  cli::add_robot_options(app, o.robot, true);
  if (const auto code = cli::parse(app, argc, argv)) return code;
  if (const std::string bad = cli::check_robot_options(o.robot); !bad.empty()) {
    std::fprintf(stderr, "%s: %s (see --help)\n", kTool, bad.c_str());
    return cli::kExitUsage;
  }
  // --tick-ms is the controller period; the loop's period follows it unless given.
  if (o.robot.tick_given) {
    if (o.dt_s) {
      std::fprintf(stderr, "%s: --tick-ms and --dt both set the controller period\n", kTool);
      return cli::kExitUsage;
    }
    o.dt_s = o.robot.setup.tick_s;
    if (app.count("--period-ms") == 0) o.period_ms = o.robot.setup.tick_s * 1000.0;
  }
  o.given = cli::GivenOptions(app);
  const cli::GivenOptions& given = o.given;
  for (const std::string& bad :
       {given.refuse_unused({"--strict-rules"}, o.controller != "pid",
                            "a controller with a supervisor", "--controller pid has none"),
        given.refuse_unused({"--require-rt"}, o.fifo_priority || o.lock_memory || o.cpu,
                            "--fifo, --lock-memory or --cpu", "none of them is given"),
        given.refuse_unused({"--loop"}, o.ticks.has_value(), "--ticks beyond one pass",
                            "without --ticks the run is one pass of the path"),
        given.refuse_unused({"--max-overruns"}, o.period_ms > 0.0, "a timed loop",
                            "--period-ms 0 runs free, without deadlines to overrun")})
    if (!bad.empty()) {
      std::fprintf(stderr, "%s: %s (see --help)\n", kTool, bad.c_str());
      return cli::kExitUsage;
    }
  // Without --dt the controller period is the tick period: it must lie in --dt's range too.
  if (!o.dt_s && o.period_ms > 0.0 &&
      (o.period_ms / 1000.0 < kMinDtS || o.period_ms / 1000.0 > kMaxDtS)) {
    std::fprintf(stderr,
                 "%s: --period-ms %g is outside the controller periods %g-%g ms; give --dt\n",
                 kTool, o.period_ms, kMinDtS * 1000.0, kMaxDtS * 1000.0);
    return cli::kExitUsage;
  }
  // The CSV's path is checked now, before any work (apps/common/output_files.hpp): --csv '' is
  // refused like any other path that cannot be written, and so is the controller file itself.
  if (app.count("--csv") > 0) {
    const bool controller_file = o.controller != "pid" && o.controller != "fuzzy";
    const std::string bad =
        cli::check_output_path(o.csv, {controller_file ? o.controller : std::string()});
    if (!bad.empty()) {
      std::fprintf(stderr, "%s: --csv: %s\n", kTool, bad.c_str());
      return cli::kExitUsage;
    }
  }
  if (!o.csv.empty() && o.ticks && *o.ticks > kMaxCsvTicks) {
    std::fprintf(stderr, "%s: --csv buffers every tick in memory: at most %llu ticks\n", kTool,
                 static_cast<unsigned long long>(kMaxCsvTicks));
    return cli::kExitUsage;
  }
  return std::nullopt;
}

}  // namespace fuzzypid::rt_loop
