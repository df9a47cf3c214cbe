// `fuzzypid fk` and `fuzzypid ik`: forward and inverse kinematics of the robot model over CSV rows.
//
//   fk [--urdf FILE]                                 q1..q6            -> x,y,z,r11..r33
//   ik [--urdf FILE] [--solver analytic|kdl-nr|kdl-lma]
//                                                    x,y,z,r11..r33[,seed q1..q6] -> q1..q6,status
//
// SI units (m, rad); the rotation is row-major, tip axes in the root frame. A row whose IK fails is
// not an input error: it prints the seed (zeros when none is given) and the status word, so the
// output keeps one numeric row per input row. Exit codes (cli.hpp): 0 ok, 1 a malformed input row
// (named on stderr, processing stops there), a URDF that does not load or a write error, 2 bad
// usage.
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli.hpp"
#include "commands.hpp"
#include "csv.hpp"
#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/robot/robot_model.hpp"

namespace fuzzypid::cli {
namespace {

using robot::JointVector;
using robot::kNumJoints;
using robot::Pose;

struct RobotOptions {
  std::string urdf;
  robot::IkSolver solver = robot::IkSolver::Analytic;
};

std::optional<robot::RobotModel> load_model(const char* command, const RobotOptions& options) {
  const std::string path = options.urdf.empty() ? robot::default_urdf_path() : options.urdf;
  robot::LoadResult r = robot::RobotModel::load(path);
  if (!r.model) std::fprintf(stderr, "fuzzypid %s: %s\n", command, r.error.c_str());
  return std::move(r.model);
}

int input_error(const char* command, const std::string& message) {
  std::fprintf(stderr, "fuzzypid %s: %s\n", command, message.c_str());
  return kExitFailure;
}

// The reader's error, else a read error of stdin, else kExitOk.
int input_failure(const char* command, const CsvReader& reader) {
  if (!reader.error().empty()) return input_error(command, reader.error());
  if (const std::string e = stdin_read_error(); !e.empty()) return input_error(command, e);
  return kExitOk;
}

int run_fk(const RobotOptions& options) {
  if (const std::string e = check_stdin_is_data(); !e.empty()) return input_error("fk", e);
  const std::optional<robot::RobotModel> model = load_model("fk", options);
  if (!model) return kExitFailure;

  robot::RobotData data(*model);
  CsvReader reader(std::cin);
  reader.expect_columns(kNumJoints, kNumJoints);
  CsvRow row;
  while (reader.next(row)) {
    JointVector q{};
    for (std::size_t j = 0; j < kNumJoints; ++j)
      q[j] = row.values[j];
    const Pose p = model->forward_kinematics(q, data);
    double out[12] = {p.position_m.x(), p.position_m.y(), p.position_m.z()};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        out[3 + 3 * r + c] = p.rotation(r, c);
    write_row(stdout, out, 12);
  }
  return input_failure("fk", reader);
}

int run_ik(const RobotOptions& options) {
  if (const std::string e = check_stdin_is_data(); !e.empty()) return input_error("ik", e);
  const std::optional<robot::RobotModel> model = load_model("ik", options);
  if (!model) return kExitFailure;
  const robot::InverseKinematics ik(*model);
  if (options.solver == robot::IkSolver::Analytic && !ik.has_analytic()) {
    std::fprintf(stderr,
                 "fuzzypid ik: the model is not the Table 1 geometry; use --solver kdl-nr or "
                 "kdl-lma\n");
    return kExitFailure;
  }

  CsvReader reader(std::cin);
  reader.expect_columns(12, 12 + kNumJoints);
  CsvRow row;
  while (reader.next(row)) {
    if (row.values.size() != 12 && row.values.size() != 12 + kNumJoints) {
      return input_error("ik", "line " + std::to_string(row.line) +
                                   ": expected 12 or 18 columns, got " +
                                   std::to_string(row.values.size()));
    }
    Pose target;
    target.position_m = {row.values[0], row.values[1], row.values[2]};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        target.rotation(r, c) =
            row.values[3 + 3 * static_cast<std::size_t>(r) + static_cast<std::size_t>(c)];
    if (!robot::is_valid_pose(target)) {
      return input_error("ik", "line " + std::to_string(row.line) +
                                   ": the rotation is not orthonormal with determinant +1");
    }
    JointVector seed{};
    if (row.values.size() == 12 + kNumJoints) {
      for (std::size_t j = 0; j < kNumJoints; ++j)
        seed[j] = row.values[12 + j];
    }
    JointVector q = seed;
    const robot::IkStatus status = ik.solve(options.solver, target, seed, q);
    for (std::size_t j = 0; j < kNumJoints; ++j)
      std::printf(j == 0 ? "%.17g" : ",%.17g", q[j]);
    std::printf(",%s\n", robot::to_string(status));
  }
  return input_failure("ik", reader);
}

CLI::Option* add_urdf_option(CLI::App& cmd, RobotOptions& options) {
  return cmd
      .add_option(
          "--urdf", options.urdf,
          "robot description (default: the bundled ER50-C20, " + robot::default_urdf_path() + ")")
      ->option_text("FILE");
}

}  // namespace

void add_fk_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<RobotOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fk", "Forward kinematics: rows q1..q6 (rad) -> x,y,z (m),r11..r33 (row-major rotation)");
  add_urdf_option(*cmd, *options);
  cmd->callback([&run, options] { run = [options] { return run_fk(*options); }; });
}

void add_ik_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<RobotOptions>();
  CLI::App* cmd = app.add_subcommand(
      "ik",
      "Inverse kinematics: rows x,y,z,r11..r33[,seed q1..q6] -> q1..q6,status (the seed, zeros "
      "by default, when no solution is found)");
  add_urdf_option(*cmd, *options);
  add_enum_option(*cmd, "--solver", options->solver, robot::kIkSolverNames, "IK solver");
  cmd->callback([&run, options] { run = [options] { return run_ik(*options); }; });
}

}  // namespace fuzzypid::cli
