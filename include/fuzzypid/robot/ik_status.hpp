// Outcome of an inverse-kinematics call, shared by the closed-form and the KDL solvers.
#pragma once

#include <cstdint>

namespace fuzzypid::robot {

enum class IkStatus : std::uint8_t {
  Ok,             // out holds a solution within the joint limits; FK(out) equals the target
  Unreachable,    // the target position lies outside the workspace
  JointLimits,    // solutions exist, but none lies within the joint limits
  Singular,       // the target lies on a singularity: out still reaches the target, but a joint
                  // the pose does not determine was taken from the seed (closed-form solver only)
  NoConvergence,  // an iterative solver stopped without reaching the target (KDL solvers only)
  InvalidInput,   // a NaN/inf entry, a rotation that is not orthonormal, or a solver unavailable
};

[[nodiscard]] constexpr const char* to_string(IkStatus s) noexcept {
  switch (s) {
    case IkStatus::Ok:
      return "ok";
    case IkStatus::Unreachable:
      return "unreachable";
    case IkStatus::JointLimits:
      return "joint_limits";
    case IkStatus::Singular:
      return "singular";
    case IkStatus::NoConvergence:
      return "no_convergence";
    case IkStatus::InvalidInput:
      return "invalid_input";
  }
  return "unknown";
}

}  // namespace fuzzypid::robot
