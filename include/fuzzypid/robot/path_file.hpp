// Paths from files: a CSV of timed joint samples or tool poses, turned into a joint reference
// sampled at the controller tick.
//
// File format (one header line, then one row per sample, comma-separated, '#' starts a comment
// line; blank lines are skipped):
//   t_s,q1_rad,q2_rad,q3_rad,q4_rad,q5_rad,q6_rad          joint samples, or
//   t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad             tool poses in the chain's base frame,
//                                                          URDF fixed-axis roll-pitch-yaw
//                                                          (R = Rz(yaw) Ry(pitch) Rx(roll))
// Times strictly increasing, every value finite, at least two rows lasting at least one tick;
// roll, pitch and yaw within +-2 pi (radians: larger angles are refused as probably degrees).
//
// From rows to ticks:
//   1. Cartesian rows are solved by inverse kinematics row by row, each seeded with the previous
//      row's solution (the first with the given seed), so the path stays on one branch: the
//      closed form where the model is the Table 1 geometry, else KDL's joint-limited
//      Newton-Raphson with Levenberg-Marquardt as the fallback.
//   2. Continuous joints are unwrapped (each sample moved by a multiple of 2 pi to the nearest
//      equivalent of the previous one), so a path crossing +/-pi never asks for a full turn.
//   3. Each joint is interpolated with a piecewise cubic Hermite through the rows, its knot
//      slopes the three-point (parabolic) finite difference of the neighbouring rows and the
//      one-sided difference at both ends; the reference angle at tick k (t = t_0 + k tick) is the
//      cubic's value and the reference velocity its derivative, so angles and velocities agree.
//      The run lasts the path's duration: ticks t_0 .. t_0 + floor((t_end - t_0) / tick) tick.
// Every row must lie within the URDF's joint limits, and the mean speed between two rows within
// its velocity limits; a failure names the row (file line), its time and the pose or joint.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::robot {

class RobotModel;

enum class PathKind : std::uint8_t { Joint, Cartesian };

struct PathTable {
  PathKind kind = PathKind::Joint;
  std::string source;                         // file name, for messages
  std::vector<double> time_s;                 // strictly increasing
  std::vector<std::array<double, 6>> values;  // q1..q6 (rad) or x, y, z (m), roll, pitch, yaw
  std::vector<std::size_t> line;              // file line of each row (1-based)
};

// The largest path file read (rows beyond this are refused, not read).
inline constexpr std::size_t kMaxPathFileBytes = 64u << 20;

// Parses a path CSV. Returns false with "source:line: reason" in `error`.
[[nodiscard]] bool parse_path_csv(std::string_view text, const std::string& source,
                                  PathTable& table, std::string& error);
// Reads and parses `path` (at most kMaxPathFileBytes).
[[nodiscard]] bool load_path_csv(const std::string& path, PathTable& table, std::string& error);

// URDF fixed-axis roll-pitch-yaw (rad) to a rotation: Rz(yaw) Ry(pitch) Rx(roll).
[[nodiscard]] Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) noexcept;

// A seed for the first inverse kinematics of a path on `model`: the middle of each joint's
// limits, 0 for a continuous joint.
[[nodiscard]] JointVector default_ik_seed(const RobotModel& model) noexcept;

// The joint reference of `table` at ticks of `tick_s` (see the file comment). `seed` seeds the
// first Cartesian row. On failure status != Ok and message names the row.
[[nodiscard]] JointPathResult joint_path_from_table(const InverseKinematics& ik,
                                                    const RobotModel& model, const PathTable& table,
                                                    double tick_s, const JointVector& seed);

// The same path played backwards in time: sample k of the result is sample n - 1 - k of `path`,
// times t' = t_end - t (+ t_0), velocities negated.
[[nodiscard]] JointPathResult reversed(const JointPathResult& path);

}  // namespace fuzzypid::robot
