// The runtime pieces every family builds from: six joints of a fixed PID, or six joints of a
// fuzzy PID sharing one immutable supervisor that the runtime owns. JointControllers holds one of
// them; each has the same step/gains/pid surface so the dispatch needs no family's name.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"

namespace fuzzypid::controller {

inline constexpr std::size_t kJoints = 6;

using Vector = std::array<double, kJoints>;
using Input = supervisor::JointInput<double, kJoints>;
using Command = supervisor::JointOutput<double, kJoints>;
// One configuration per joint (the fixed PID uses configs[i].pid only).
using JointConfigs = std::array<supervisor::FuzzyPidConfig<double>, kJoints>;

// Six fixed PIDs.
struct FixedJoints {
  supervisor::JointController<double, kJoints, pid::Pid<double>> joints;

  [[nodiscard]] Command step(const Input& in, double dt_s) noexcept {
    return joints.step(in, dt_s);
  }
  [[nodiscard]] pid::Gains<double> gains(std::size_t i) const noexcept {
    return joints.joint(i).gains();
  }
  [[nodiscard]] const pid::Pid<double>& pid(std::size_t i) const noexcept {
    return joints.joint(i);
  }
};

// Six fuzzy PIDs on one Supervisor. The supervisor lives on the heap so its address, which the
// joints keep, survives moves of this object; `keep` holds whatever it points into (a rule file's
// model), or nothing.
template <class Supervisor>
struct SupervisedJoints {
  using Joint = supervisor::FuzzyPid<double, Supervisor>;

  std::shared_ptr<const void> keep;
  std::unique_ptr<const Supervisor> supervisor;
  supervisor::JointController<double, kJoints, Joint> joints;

  [[nodiscard]] Command step(const Input& in, double dt_s) noexcept {
    return joints.step(in, dt_s);
  }
  [[nodiscard]] pid::Gains<double> gains(std::size_t i) const noexcept {
    return joints.joint(i).gains();
  }
  [[nodiscard]] const pid::Pid<double>& pid(std::size_t i) const noexcept {
    return joints.joint(i).pid();
  }
};

// fn(alternative) for the alternative `joints` holds: the tick's dispatch over the families'
// runtimes. One comparison per alternative before the held one; unlike std::visit it cannot
// throw (a variant left valueless by a failed set-up is never stepped: JointControllers is not
// created then).
template <std::size_t I = 0, class Variant, class Fn>
[[nodiscard]] decltype(auto) visit_joints(Variant& joints, Fn&& fn) noexcept {
  if constexpr (I + 1 == std::variant_size_v<std::remove_const_t<Variant>>) {
    return fn(*std::get_if<I>(&joints));
  } else {
    if (joints.index() == I) return fn(*std::get_if<I>(&joints));
    return visit_joints<I + 1>(joints, std::forward<Fn>(fn));
  }
}

// The six fixed PIDs of `configs`; false with `error` set when one is invalid.
[[nodiscard]] inline bool make_fixed_joints(const JointConfigs& configs, FixedJoints& out,
                                            std::string& error) {
  std::array<pid::Pid<double>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i) {
    if (!configs[i].pid.valid()) {
      error = "invalid PID configuration";
      return false;
    }
    joints[i] = pid::Pid<double>(configs[i].pid);
  }
  out.joints = decltype(out.joints)(joints);
  return true;
}

// Six fuzzy PIDs of `configs` on `supervisor` (taken over); false with `error` set when a
// configuration is invalid. `what` names the controller in that error.
template <class Supervisor>
[[nodiscard]] bool make_supervised_joints(std::unique_ptr<const Supervisor> supervisor,
                                          const JointConfigs& configs, const char* what,
                                          SupervisedJoints<Supervisor>& out, std::string& error) {
  std::array<supervisor::FuzzyPid<double, Supervisor>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i) {
    if (!configs[i].valid()) {
      error = std::string("invalid ") + what + " configuration";
      return false;
    }
    joints[i] = supervisor::FuzzyPid<double, Supervisor>(supervisor.get(), configs[i]);
  }
  out.supervisor = std::move(supervisor);
  out.joints = decltype(out.joints)(joints);
  return true;
}

}  // namespace fuzzypid::controller
