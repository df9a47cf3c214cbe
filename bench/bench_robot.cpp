// Robot-side costs: one inverse-kinematics solve (closed form against KDL's two iterative solvers)
// and one 50 ms tick of the joint plant.
#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>
#include <cstdio>
#include <optional>
#include <string>

#include "bench_inputs.hpp"
#include "fuzzypid/robot/ik.hpp"
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
  for (auto& c : cases) {
    robot::JointVector q{};
    do {
      for (std::size_t j = 0; j < robot::kNumJoints; ++j) {
        const double l = lo[j] > -3.0 ? lo[j] : -3.0;
        const double h = hi[j] < 3.0 ? hi[j] : 3.0;
        q[j] = rng.uniform(l + 0.2, h - 0.2);
      }
    } while (q[4] > -0.2 && q[4] < 0.2);
    c.target = m.forward_kinematics(q);
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

}  // namespace
