// Uses the installed sim part: the section 6 experiment with the fixed PID on the nominal plant,
// with the installed ER50-C20 description (argv[1]).
#include <cstdio>
#include <string>

#include <fuzzypid/robot/path.hpp>
#include <fuzzypid/robot/robot_model.hpp>
#include <fuzzypid/sim/condition.hpp>
#include <fuzzypid/sim/experiment.hpp>

int main(int argc, char** argv) {
  using namespace fuzzypid;
  if (argc != 2) return 2;
  const robot::LoadResult loaded = robot::RobotModel::load(argv[1]);
  if (!loaded.model) {
    std::fprintf(stderr, "load failed: %s\n", loaded.error.c_str());
    return 1;
  }
  std::string error;
  const auto experiment = sim::Experiment::create(*loaded.model, robot::paper_path_spec(),
                                                  sim::ExperimentOptions{}, error);
  if (!experiment) {
    std::fprintf(stderr, "experiment: %s\n", error.c_str());
    return 1;
  }
  const sim::RunResult run = experiment->run(*sim::find_scenario("paper"), controller::paper_pid());
  const double itae = sim::total_itae(run.rows, experiment->options().tick_s);
  std::printf("summed ITAE of the fixed PID: %.6g\n", itae);
  return run.ok && run.controller_faults == 0 && itae > 0.0 ? 0 : 1;
}
