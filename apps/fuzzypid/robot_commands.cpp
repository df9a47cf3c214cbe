// `fuzzypid fk` and `fuzzypid ik`: forward and inverse kinematics of the robot model over CSV rows.
//
//   fk [--urdf FILE]                                 q1..q6            -> x,y,z,r11..r33
//   ik [--urdf FILE] [--solver analytic|kdl-nr|kdl-lma]
//                                                    x,y,z,r11..r33[,seed q1..q6] -> q1..q6,status
//
// SI units (m, rad); the rotation is row-major, tip axes in the root frame. A row whose IK fails is
// not an input error: it prints the seed (zeros when none is given) and the status word, so the
// output keeps one numeric row per input row. Exit codes: 0 ok, 1 a malformed input row (named on
// stderr, processing stops there), 2 bad usage or a URDF that does not load.
#include <cstdio>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>

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
  std::string solver = "analytic";
};

// Parses --urdf and (for ik) --solver; false after printing a message on a bad argument.
bool parse_options(const char* command, int argc, char** argv, bool allow_solver,
                   RobotOptions& options) {
  for (int i = 0; i < argc; ++i) {
    const char* arg = argv[i];
    const bool is_urdf = std::strcmp(arg, "--urdf") == 0;
    const bool is_solver = allow_solver && std::strcmp(arg, "--solver") == 0;
    if ((is_urdf || is_solver) && i + 1 < argc) {
      (is_urdf ? options.urdf : options.solver) = argv[++i];
    } else {
      std::fprintf(stderr, "fuzzypid %s: unexpected argument '%s'\nusage: fuzzypid %s\n", command,
                   arg,
                   allow_solver ? "ik [--urdf FILE] [--solver analytic|kdl-nr|kdl-lma]"
                                : "fk [--urdf FILE]");
      return false;
    }
  }
  return true;
}

std::optional<robot::RobotModel> load_model(const char* command, const RobotOptions& options) {
  const std::string path = options.urdf.empty() ? robot::default_urdf_path() : options.urdf;
  robot::LoadResult r = robot::RobotModel::load(path);
  if (!r.model) std::fprintf(stderr, "fuzzypid %s: %s\n", command, r.error.c_str());
  return std::move(r.model);
}

int input_error(const char* command, const std::string& message) {
  std::fprintf(stderr, "fuzzypid %s: %s\n", command, message.c_str());
  return 1;
}

}  // namespace

int run_fk(int argc, char** argv) {
  RobotOptions options;
  if (!parse_options("fk", argc, argv, false, options)) return 2;
  const std::optional<robot::RobotModel> model = load_model("fk", options);
  if (!model) return 2;

  CsvReader reader(std::cin);
  reader.expect_columns(kNumJoints, kNumJoints);
  CsvRow row;
  while (reader.next(row)) {
    JointVector q{};
    for (std::size_t j = 0; j < kNumJoints; ++j)
      q[j] = row.values[j];
    const Pose p = model->forward_kinematics(q);
    double out[12] = {p.position_m.x(), p.position_m.y(), p.position_m.z()};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        out[3 + 3 * r + c] = p.rotation(r, c);
    write_row(stdout, out, 12);
  }
  if (!reader.error().empty()) return input_error("fk", reader.error());
  return 0;
}

int run_ik(int argc, char** argv) {
  RobotOptions options;
  if (!parse_options("ik", argc, argv, true, options)) return 2;
  const std::optional<robot::IkSolver> solver = robot::ik_solver_from_string(options.solver);
  if (!solver) {
    std::fprintf(stderr, "fuzzypid ik: unknown solver '%s' (analytic, kdl-nr or kdl-lma)\n",
                 options.solver.c_str());
    return 2;
  }
  const std::optional<robot::RobotModel> model = load_model("ik", options);
  if (!model) return 2;
  const robot::InverseKinematics ik(*model);
  if (*solver == robot::IkSolver::Analytic && !ik.has_analytic()) {
    std::fprintf(stderr,
                 "fuzzypid ik: the model is not the Table 1 geometry; use --solver kdl-nr or "
                 "kdl-lma\n");
    return 2;
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
    const robot::IkStatus status = ik.solve(*solver, target, seed, q);
    for (std::size_t j = 0; j < kNumJoints; ++j)
      std::printf(j == 0 ? "%.17g" : ",%.17g", q[j]);
    std::printf(",%s\n", robot::to_string(status));
  }
  if (!reader.error().empty()) return input_error("ik", reader.error());
  return 0;
}

}  // namespace fuzzypid::cli
