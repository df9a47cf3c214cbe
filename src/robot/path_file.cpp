// Paths from files: the format and the interpolation are documented in path_file.hpp.
#include "fuzzypid/robot/path_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <Eigen/Geometry>

#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid_support/bounded_read.hpp"
#include "fuzzypid_support/printable.hpp"

namespace fuzzypid::robot {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr const char* kJointHeader = "t_s,q1_rad,q2_rad,q3_rad,q4_rad,q5_rad,q6_rad";
constexpr const char* kPoseHeader = "t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad";

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t' || s[b] == '\r'))
    ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\r'))
    --e;
  return std::string(s.substr(b, e - b));
}

std::string where(const std::string& source, std::size_t line) {
  return source + ":" + std::to_string(line) + ": ";
}

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

bool is_continuous(const RobotModel& model, std::size_t j) noexcept {
  return std::isinf(model.lower_limits_rad()[j]) && std::isinf(model.upper_limits_rad()[j]);
}

// The Hermite slope at knot k of one joint: the derivative of the parabola through k - 1, k, k + 1
// inside, the one-sided difference at the ends.
double knot_slope(const std::vector<double>& t, const std::vector<JointVector>& q, std::size_t k,
                  std::size_t j) noexcept {
  const std::size_t n = t.size();
  if (k == 0) return (q[1][j] - q[0][j]) / (t[1] - t[0]);
  if (k + 1 == n) return (q[n - 1][j] - q[n - 2][j]) / (t[n - 1] - t[n - 2]);
  const double h0 = t[k] - t[k - 1];
  const double h1 = t[k + 1] - t[k];
  const double s0 = (q[k][j] - q[k - 1][j]) / h0;
  const double s1 = (q[k + 1][j] - q[k][j]) / h1;
  return (h1 * s0 + h0 * s1) / (h0 + h1);
}

}  // namespace

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) noexcept {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

bool parse_path_csv(std::string_view text, const std::string& source, PathTable& table,
                    std::string& error) {
  PathTable out;
  out.source = source;
  bool header = false;
  std::size_t line_no = 0;
  std::size_t pos = 0;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;  // byte-order mark
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string line = trim(text.substr(pos, end - pos));
    ++line_no;
    pos = end + 1;
    if (line.empty() || line[0] == '#') {
      if (end == text.size()) break;
      continue;
    }
    if (line.find('\0') != std::string::npos) {
      error = where(source, line_no) + "a NUL byte";
      return false;
    }
    if (!header) {
      std::string compact;
      for (char c : line)
        if (c != ' ' && c != '\t') compact += c;
      if (compact == kJointHeader) {
        out.kind = PathKind::Joint;
      } else if (compact == kPoseHeader) {
        out.kind = PathKind::Cartesian;
      } else {
        error = where(source, line_no) + "unknown header '" +
                support::printable(line.substr(0, 120)) + "': expected '" + kJointHeader +
                "' or '" + kPoseHeader + "'";
        return false;
      }
      header = true;
      if (end == text.size()) break;
      continue;
    }
    double fields[7];
    std::size_t count = 0;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = line.find(',', start);
      const std::string field = trim(std::string_view(line).substr(
          start, comma == std::string::npos ? std::string::npos : comma - start));
      if (count == 7) {
        error = where(source, line_no) + "more than 7 fields";
        return false;
      }
      char* stop = nullptr;
      errno = 0;
      const double v = std::strtod(field.c_str(), &stop);
      if (field.empty() || stop == field.c_str() || *stop != '\0') {
        error = where(source, line_no) + "field " + std::to_string(count + 1) +
                " is not a number: '" + support::printable(field.substr(0, 40)) + "'";
        return false;
      }
      if (!std::isfinite(v)) {
        error = where(source, line_no) + "field " + std::to_string(count + 1) + " is not finite";
        return false;
      }
      fields[count++] = v;
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    if (count != 7) {
      error = where(source, line_no) + "expected 7 fields, found " + std::to_string(count);
      return false;
    }
    if (!out.time_s.empty() && !(fields[0] > out.time_s.back())) {
      error = where(source, line_no) + "time " + num(fields[0]) +
              " s does not increase (previous row: " + num(out.time_s.back()) + " s)";
      return false;
    }
    // Roll, pitch and yaw are radians: beyond one turn they were almost surely written in degrees
    // (180,0,0 read as radians puts the tool 53 degrees from where 180 degrees would).
    if (out.kind == PathKind::Cartesian)
      for (std::size_t f = 4; f < 7; ++f)
        if (std::fabs(fields[f]) > 2.0 * kPi) {
          static constexpr const char* kAngle[3] = {"roll_rad", "pitch_rad", "yaw_rad"};
          error = where(source, line_no) + kAngle[f - 4] + " " + num(fields[f]) +
                  " is beyond one turn (+-2 pi = +-6.28318531): the angles are radians, not "
                  "degrees";
          return false;
        }
    out.time_s.push_back(fields[0]);
    out.values.push_back({fields[1], fields[2], fields[3], fields[4], fields[5], fields[6]});
    out.line.push_back(line_no);
    if (end == text.size()) break;
  }
  if (!header) {
    error = source + ": empty path file (no header line)";
    return false;
  }
  if (out.time_s.size() < 2) {
    error = source + ": a path needs at least two rows, found " + std::to_string(out.time_s.size());
    return false;
  }
  table = std::move(out);
  return true;
}

bool load_path_csv(const std::string& path, PathTable& table, std::string& error) {
  std::string text;
  if (!support::read_file_bounded(path, kMaxPathFileBytes, text, error)) {
    error = "path: " + error;  // as the URDF's "URDF: ": which input the file is
    return false;
  }
  return parse_path_csv(text, path, table, error);
}

JointVector default_ik_seed(const RobotModel& model) noexcept {
  JointVector seed{};
  for (std::size_t j = 0; j < kNumJoints; ++j) {
    const double lo = model.lower_limits_rad()[j];
    const double hi = model.upper_limits_rad()[j];
    seed[j] = std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi) : 0.0;
  }
  return seed;
}

JointPathResult joint_path_from_table(const InverseKinematics& ik, const RobotModel& model,
                                      const PathTable& table, double tick_s,
                                      const JointVector& seed) {
  JointPathResult r;
  const std::size_t n = table.time_s.size();
  const auto fail = [&r](PathStatus status, std::string message) {
    r.status = status;
    r.message = std::move(message);
    return r;
  };
  if (!(tick_s > 0.0) || !std::isfinite(tick_s))
    return fail(PathStatus::InvalidSpec, "the tick must be finite and > 0");
  if (n < 2 || table.values.size() != n || table.line.size() != n)
    return fail(PathStatus::InvalidSpec, table.source + ": a path needs at least two rows");
  const double duration = table.time_s.back() - table.time_s.front();
  // One tick or less is a one-sample run (its ITAE 0 says nothing), not a path.
  if (duration < tick_s * (1.0 - 1e-9))
    return fail(PathStatus::InvalidSpec, table.source + ": the path lasts " + num(duration) +
                                             " s, less than one tick (" + num(tick_s) +
                                             " s): a run needs at least two samples");
  if (duration / tick_s > 1e7)
    return fail(PathStatus::InvalidSpec, table.source + ": more than 1e7 ticks (" + num(duration) +
                                             " s at " + num(tick_s) + " s a tick)");

  // The seed of the first inverse kinematics is the user's (--ik-seed, ik_seed): one outside a
  // joint's limits is blamed on itself, not on the first row the solver then cannot reach.
  if (table.kind == PathKind::Cartesian)
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      const double lo = model.lower_limits_rad()[j];
      const double hi = model.upper_limits_rad()[j];
      if (!is_continuous(model, j) && !(seed[j] >= lo - 1e-9 && seed[j] <= hi + 1e-9))
        return fail(PathStatus::InvalidSpec,
                    "the IK seed (--ik-seed, ik_seed): joint " + std::to_string(j + 1) + " ('" +
                        model.joint_names()[j] + "') at " + num(seed[j]) +
                        " rad is outside its URDF limits [" + num(lo) + ", " + num(hi) + "]");
    }

  // "file:line: row at t = T s: ", for the message of a failing row (built only then).
  const auto row_at = [&table](std::size_t k) {
    return where(table.source, table.line[k]) + "row at t = " + num(table.time_s[k]) + " s: ";
  };

  // 1. Joint samples of the rows.
  std::vector<JointVector> q(n);
  const bool analytic = ik.has_analytic();
  for (std::size_t k = 0; k < n; ++k) {
    const auto& v = table.values[k];
    if (table.kind == PathKind::Joint) {
      for (std::size_t j = 0; j < kNumJoints; ++j)
        q[k][j] = v[j];
      continue;
    }
    Pose target;
    target.position_m = Eigen::Vector3d(v[0], v[1], v[2]);
    target.rotation = rotation_from_rpy(v[3], v[4], v[5]);
    const JointVector& from = k == 0 ? seed : q[k - 1];
    JointVector sol{};
    IkStatus status;
    const char* solver;
    if (analytic) {
      solver = "closed-form IK";
      status = ik.solve(IkSolver::Analytic, target, from, sol);
    } else {
      solver = "KDL Newton-Raphson (joint-limited)";
      status = ik.solve(IkSolver::KdlNr, target, from, sol);
      if (status != IkStatus::Ok) {
        solver = "KDL Newton-Raphson and Levenberg-Marquardt";
        status = ik.solve(IkSolver::KdlLma, target, from, sol);
      }
    }
    if (status != IkStatus::Ok && status != IkStatus::Singular) {
      r.ik_status = status;
      r.first_failure = k;
      return fail(PathStatus::IkFailed, row_at(k) + "pose (" + num(v[0]) + ", " + num(v[1]) + ", " +
                                            num(v[2]) + ") m, rpy (" + num(v[3]) + ", " +
                                            num(v[4]) + ", " + num(v[5]) + ") rad: " + solver +
                                            " refused it: " + to_string(status));
    }
    q[k] = sol;
  }

  // 2. Continuous joints unwrapped; limits and speeds checked row by row.
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      if (is_continuous(model, j)) {
        if (k > 0) q[k][j] -= 2.0 * kPi * std::round((q[k][j] - q[k - 1][j]) / (2.0 * kPi));
        continue;
      }
      const double lo = model.lower_limits_rad()[j];
      const double hi = model.upper_limits_rad()[j];
      if (q[k][j] < lo - 1e-9 || q[k][j] > hi + 1e-9) {
        r.first_failure = k;
        return fail(PathStatus::InvalidSpec,
                    row_at(k) + "joint " + std::to_string(j + 1) + " at " + num(q[k][j]) +
                        " rad is outside its URDF limits [" + num(lo) + ", " + num(hi) + "]");
      }
    }
    if (k == 0) continue;
    const double dt = table.time_s[k] - table.time_s[k - 1];
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      const double speed = std::fabs(q[k][j] - q[k - 1][j]) / dt;
      const double limit = model.velocity_limits_rad_s()[j];
      if (speed > limit * (1.0 + 1e-9)) {
        r.first_failure = k;
        return fail(PathStatus::JointJump,
                    row_at(k) + "joint " + std::to_string(j + 1) + " moves at " + num(speed) +
                        " rad/s from the previous row, above its URDF velocity limit " +
                        num(limit) + " rad/s");
      }
    }
  }

  // 3. Cubic Hermite at the ticks.
  std::vector<JointVector> slope(n);
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < kNumJoints; ++j)
      slope[k][j] = knot_slope(table.time_s, q, k, j);
  const double t0 = table.time_s.front();
  const auto ticks = static_cast<std::size_t>(std::floor(duration / tick_s + 1e-9)) + 1;
  r.time_s.reserve(ticks);
  r.position_rad.reserve(ticks);
  r.velocity_rad_s.reserve(ticks);
  std::size_t seg = 0;
  RobotData data(model);
  for (std::size_t k = 0; k < ticks; ++k) {
    const double t = std::fmin(t0 + static_cast<double>(k) * tick_s, table.time_s.back());
    while (seg + 2 < n && t >= table.time_s[seg + 1])
      ++seg;
    const double ta = table.time_s[seg];
    const double h = table.time_s[seg + 1] - ta;
    const double s = (t - ta) / h;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
                 h11 = s3 - s2;
    const double d00 = (6 * s2 - 6 * s) / h, d10 = 3 * s2 - 4 * s + 1, d01 = (-6 * s2 + 6 * s) / h,
                 d11 = 3 * s2 - 2 * s;
    JointVector pos{}, vel{};
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      const double qa = q[seg][j], qb = q[seg + 1][j];
      const double ma = slope[seg][j], mb = slope[seg + 1][j];
      pos[j] = h00 * qa + h10 * h * ma + h01 * qb + h11 * h * mb;
      vel[j] = d00 * qa + d10 * ma + d01 * qb + d11 * mb;
      r.max_speed_rad_s[j] = std::fmax(r.max_speed_rad_s[j], std::fabs(vel[j]));
    }
    r.time_s.push_back(t);
    r.position_rad.push_back(pos);
    r.velocity_rad_s.push_back(vel);
    r.poses.push_back(model.forward_kinematics(pos, data));
  }
  r.within_velocity_limits = true;
  for (std::size_t j = 0; j < kNumJoints; ++j)
    if (r.max_speed_rad_s[j] > model.velocity_limits_rad_s()[j]) r.within_velocity_limits = false;
  r.status = PathStatus::Ok;
  return r;
}

JointPathResult reversed(const JointPathResult& path) {
  JointPathResult r = path;
  const std::size_t n = path.time_s.size();
  if (n == 0) return r;
  const double t0 = path.time_s.front();
  const double t1 = path.time_s.back();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t from = n - 1 - k;
    r.time_s[k] = t0 + (t1 - path.time_s[from]);
    r.position_rad[k] = path.position_rad[from];
    for (std::size_t j = 0; j < kNumJoints; ++j)
      r.velocity_rad_s[k][j] = -path.velocity_rad_s[from][j];
    if (path.poses.size() == n) r.poses[k] = path.poses[from];
  }
  return r;
}

}  // namespace fuzzypid::robot
