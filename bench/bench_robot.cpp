// Robot-side costs: one inverse-kinematics solve (closed form against KDL's two iterative solvers),
// one 50 ms tick of the joint plant, and one 5 s closed-loop condition through the decoupled and
// the coupled-with-gravity plant side by side.
#include <benchmark/benchmark.h>

#include <time.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "bench_inputs.hpp"
#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"

namespace {

namespace robot = fuzzypid::robot;
using fuzzypid::bench::SplitMix64;

constexpr std::size_t kPoses = 256;      // a power of two
constexpr double kSeedOffsetRad = 0.05;  // every seed joint this far (+/-) from the answer

const robot::RobotModel* model() {
  static const std::optional<robot::RobotModel> m = [] {
    robot::LoadResult r = robot::RobotModel::load(robot::default_urdf_path());
    if (!r.model) std::fprintf(stderr, "fuzzypid_bench: %s\n", r.error.c_str());
    return std::move(r.model);
  }();
  return m ? &*m : nullptr;
}

struct IkCase {
  robot::Pose target;
  robot::JointVector seed;
};

// Reachable targets: forward kinematics of random configurations inside the joint limits, kept
// 0.2 rad clear of the limits and of the wrist singularity (|q5| >= 0.2), so a seed 0.05 rad away
// is valid for every solver.
std::array<IkCase, kPoses> make_ik_cases(const robot::RobotModel& m) {
  std::array<IkCase, kPoses> cases{};
  SplitMix64 rng(2024);
  const auto& lo = m.lower_limits_rad();
  const auto& hi = m.upper_limits_rad();
  robot::RobotData data(m);
  for (auto& c : cases) {
    robot::JointVector q{};
    do {
      for (std::size_t j = 0; j < robot::kNumJoints; ++j) {
        const double l = lo[j] > -3.0 ? lo[j] : -3.0;
        const double h = hi[j] < 3.0 ? hi[j] : 3.0;
        q[j] = rng.uniform(l + 0.2, h - 0.2);
      }
    } while (q[4] > -0.2 && q[4] < 0.2);
    c.target = m.forward_kinematics(q, data);
    for (std::size_t j = 0; j < robot::kNumJoints; ++j)
      c.seed[j] = q[j] + (rng.next() & 1 ? kSeedOffsetRad : -kSeedOffsetRad);
  }
  return cases;
}

void BM_IK(benchmark::State& state, robot::IkSolver solver) {
  const robot::RobotModel* m = model();
  if (m == nullptr) {
    state.SkipWithError("cannot load the URDF");
    return;
  }
  const robot::InverseKinematics ik(*m);
  if (solver == robot::IkSolver::Analytic && !ik.has_analytic()) {
    state.SkipWithError("no closed form for this model");
    return;
  }
  const auto cases = make_ik_cases(*m);
  std::size_t k = 0;
  std::size_t failures = 0;
  for (auto _ : state) {
    const IkCase& c = cases[k++ & (kPoses - 1)];
    robot::JointVector q{};
    const robot::IkStatus s = ik.solve(solver, c.target, c.seed, q);
    if (s != robot::IkStatus::Ok) ++failures;
    benchmark::DoNotOptimize(q);
  }
  state.SetItemsProcessed(state.iterations());
  // Share of solves that did not return Ok (0 expected for every solver with these seeds).
  state.counters["fail_rate"] =
      static_cast<double>(failures) / static_cast<double>(state.iterations());
}
BENCHMARK_CAPTURE(BM_IK, analytic, robot::IkSolver::Analytic);
BENCHMARK_CAPTURE(BM_IK, kdl_nr, robot::IkSolver::KdlNr);
BENCHMARK_CAPTURE(BM_IK, kdl_lma, robot::IkSolver::KdlLma);

// One 50 ms tick (50 RK4 substeps of 1 ms, inertia re-evaluated once per tick) of the default
// decoupled plant. The state is reset from a table before every tick so it stays in the workspace
// however many iterations run; the reset copies 12 doubles.
void BM_PlantStep6(benchmark::State& state) {
  const robot::RobotModel* m = model();
  if (m == nullptr) {
    state.SkipWithError("cannot load the URDF");
    return;
  }
  robot::JointPlant plant(*m);
  struct Case {
    robot::JointVector q, qd, torque;
  };
  std::array<Case, kPoses> cases{};
  SplitMix64 rng(99);
  for (auto& c : cases) {
    for (std::size_t j = 0; j < robot::kNumJoints; ++j) {
      c.q[j] = rng.uniform(-1.0, 1.0);
      c.qd[j] = rng.uniform(-0.5, 0.5);
      c.torque[j] = rng.uniform(-0.5, 0.5) * m->effort_limits_nm()[j];
    }
  }
  std::size_t k = 0;
  for (auto _ : state) {
    const Case& c = cases[k++ & (kPoses - 1)];
    plant.reset(c.q, c.qd);
    const robot::PlantStatus s = plant.step(c.torque, 0.05);
    benchmark::DoNotOptimize(s);
    benchmark::DoNotOptimize(plant.position());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PlantStep6);

// A PD law toward a moving target, held over each tick (tests/robot/test_plant.cpp measures the
// coupled plant's accuracy on the same loop).
robot::JointVector pd_torque(const robot::JointPlant& plant, const robot::JointVector& center,
                             double t) {
  static constexpr robot::JointVector kp = {6000.0, 12000.0, 3000.0, 300.0, 300.0, 60.0};
  static constexpr robot::JointVector kd = {1200.0, 2400.0, 600.0, 60.0, 60.0, 12.0};
  robot::JointVector tau{};
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    const double target = center[i] + 0.5 * std::sin(1.3 * t + 0.4 * static_cast<double>(i));
    tau[i] = kp[i] * (target - plant.position()[i]) - kd[i] * plant.velocity()[i];
  }
  return tau;
}

// CPU time of the calling thread, s: unlike wall time, it does not count the time other processes
// on a shared machine take the core away.
double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// One 5 s condition: reset, then 5 s / tick ticks of PD torque held over each tick. Returns the
// thread CPU time it took, s.
double run_condition(robot::JointPlant& plant, const robot::JointVector& center, double tick_s,
                     int ticks) {
  const double start = thread_cpu_s();
  plant.reset(center, robot::JointVector{});
  for (int k = 0; k < ticks; ++k) {
    const robot::PlantStatus s = plant.step(pd_torque(plant, center, k * tick_s), tick_s);
    benchmark::DoNotOptimize(s);
  }
  benchmark::DoNotOptimize(plant.position());
  return thread_cpu_s() - start;
}

// Each iteration runs one 5 s condition through the default decoupled plant and then the same
// condition through the coupled plant with gravity (default PlantConfig otherwise, so the coupled
// step is sized by coupled_substep_s and coupled_step_rad), interleaved so that both see the same
// machine state. Counters: decoupled_us and coupled_us, thread CPU time per condition, and their
// ratio coupled / decoupled. The conditions start from a table of configurations around the
// paper's start joints.
void BM_ConditionCost(benchmark::State& state) {
  const robot::RobotModel* m = model();
  if (m == nullptr) {
    state.SkipWithError("cannot load the URDF");
    return;
  }
  const double tick_s = static_cast<double>(state.range(0)) * 1e-3;
  const int ticks = static_cast<int>(std::lround(5.0 / tick_s));
  robot::PlantConfig decoupled_config;
  decoupled_config.armature_kgm2 = robot::kEr50ArmatureKgm2;  // the bundled ER50-C20's motors
  robot::JointPlant decoupled(*m, decoupled_config);
  robot::PlantConfig coupled_config = decoupled_config;
  coupled_config.coupling = robot::PlantCoupling::Coupled;
  coupled_config.gravity = true;
  robot::JointPlant coupled(*m, coupled_config);
  constexpr std::size_t kStarts = 64;  // a power of two
  std::array<robot::JointVector, kStarts> starts{};
  SplitMix64 rng(18);
  for (auto& q : starts) {
    for (std::size_t j = 0; j < robot::kNumJoints; ++j)
      q[j] = robot::kPaperStartJoints[j] + rng.uniform(-0.3, 0.3);
  }
  double decoupled_s = 0.0;
  double coupled_s = 0.0;
  std::size_t k = 0;
  for (auto _ : state) {
    const robot::JointVector& center = starts[k++ & (kStarts - 1)];
    decoupled_s += run_condition(decoupled, center, tick_s, ticks);
    coupled_s += run_condition(coupled, center, tick_s, ticks);
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["decoupled_us"] = 1e6 * decoupled_s / n;
  state.counters["coupled_us"] = 1e6 * coupled_s / n;
  state.counters["ratio"] = coupled_s / decoupled_s;
}
// The coupled plant alone on the same conditions with other step settings: args tick_ms,
// coupled_substep_s in ms, coupled_step_rad in mrad (0: +inf, i.e. fixed substeps). Counter
// coupled_us: thread CPU time per condition. docs/performance.md pairs these with the accuracy
// of each setting.
void BM_CoupledStepCost(benchmark::State& state) {
  const robot::RobotModel* m = model();
  if (m == nullptr) {
    state.SkipWithError("cannot load the URDF");
    return;
  }
  const double tick_s = static_cast<double>(state.range(0)) * 1e-3;
  const int ticks = static_cast<int>(std::lround(5.0 / tick_s));
  robot::PlantConfig config;
  config.armature_kgm2 = robot::kEr50ArmatureKgm2;  // the bundled ER50-C20's motors
  config.coupling = robot::PlantCoupling::Coupled;
  config.gravity = true;
  config.coupled_substep_s = static_cast<double>(state.range(1)) * 1e-3;
  config.coupled_step_rad = state.range(2) == 0 ? std::numeric_limits<double>::infinity()
                                                : static_cast<double>(state.range(2)) * 1e-3;
  robot::JointPlant coupled(*m, config);
  constexpr std::size_t kStarts = 64;  // a power of two
  std::array<robot::JointVector, kStarts> starts{};
  SplitMix64 rng(18);
  for (auto& q : starts) {
    for (std::size_t j = 0; j < robot::kNumJoints; ++j)
      q[j] = robot::kPaperStartJoints[j] + rng.uniform(-0.3, 0.3);
  }
  double coupled_s = 0.0;
  std::size_t k = 0;
  for (auto _ : state)
    coupled_s += run_condition(coupled, starts[k++ & (kStarts - 1)], tick_s, ticks);
  state.counters["coupled_us"] = 1e6 * coupled_s / static_cast<double>(state.iterations());
}
BENCHMARK(BM_CoupledStepCost)
    ->ArgNames({"tick_ms", "substep_ms", "step_mrad"})
    ->Args({50, 1, 0})
    ->Args({50, 10, 0})
    ->Args({50, 25, 0})
    ->Args({50, 50, 0})
    ->Args({50, 50, 10})
    ->Args({50, 50, 15})
    ->Args({50, 50, 20})
    ->Args({50, 50, 30})
    ->Args({10, 1, 0})
    ->Args({10, 10, 0})
    ->Args({10, 50, 15})
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_ConditionCost)->ArgName("tick_ms")->Arg(50)->Arg(10)->Unit(benchmark::kMillisecond);

}  // namespace
