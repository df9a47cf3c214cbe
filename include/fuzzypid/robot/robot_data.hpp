// The per-caller workspace of a RobotModel's kinematic and dynamic queries, as pinocchio keeps a
// Data beside its Model: the model is immutable and shared, each caller (each thread, each plant)
// owns a RobotData made for it. Made once (it allocates), then reused by every query without
// allocating.
//
// A RobotData is made for one model and valid while that model lives and is not assigned to. A
// query given a RobotData made for another model (or a copy of it) computes nothing: its result is
// NaN (RobotModel's queries say so), never another robot's numbers.
#pragma once

#include <cstdint>
#include <memory>

namespace fuzzypid::robot {

class RobotModel;

class RobotData {
 public:
  explicit RobotData(const RobotModel& model);
  RobotData(RobotData&& other) noexcept;
  RobotData& operator=(RobotData&& other) noexcept;
  RobotData(const RobotData&) = delete;
  RobotData& operator=(const RobotData&) = delete;
  ~RobotData();

  class Impl;  // defined in src/robot/robot_model_impl.hpp; used by the other robot sources
  Impl& impl() noexcept { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace fuzzypid::robot
