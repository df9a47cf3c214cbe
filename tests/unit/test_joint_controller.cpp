// supervisor::JointController: N independent joints stepped together, faults isolated per joint.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <type_traits>

#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::paper::FuzzyPid;
using fuzzypid::supervisor::JointController;
using fuzzypid::supervisor::JointInput;

// One tick's input from its five vectors.
template <class Scalar, std::size_t N>
JointInput<Scalar, N> input(const std::array<Scalar, N>& qd, const std::array<Scalar, N>& vd,
                            const std::array<Scalar, N>& q, const std::array<Scalar, N>& v,
                            const std::array<Scalar, N>& ff = {}) {
  JointInput<Scalar, N> in;
  in.desired_position_rad = qd;
  in.desired_velocity_rad_s = vd;
  in.measured_position_rad = q;
  in.measured_velocity_rad_s = v;
  in.feed_forward = ff;
  return in;
}

template <class Scalar>
fuzzypid::pid::Pid<Scalar> make_pid(Scalar kp) {
  fuzzypid::pid::Config<Scalar> c;
  c.gains = {kp, Scalar(0.5), Scalar(0.1)};
  c.output_min = Scalar(-50);
  c.output_max = Scalar(50);
  return fuzzypid::pid::Pid<Scalar>(c);
}

template <class Scalar>
FuzzyPid<Scalar> make_fuzzy(Scalar kp) {
  auto config = fuzzypid::paper::paper_config<Scalar>();
  config.pid.gains.kp = kp;
  config.error_scale = Scalar(3);
  return FuzzyPid<Scalar>(&fuzzypid::paper::kSystem<Scalar>, config);
}

template <class Scalar, class Controller>
struct Case {
  using ScalarType = Scalar;
  using ControllerType = Controller;
};

template <class C>
class JointControllerTyped : public ::testing::Test {};

using Cases = ::testing::Types<Case<double, fuzzypid::pid::Pid<double>>,
                               Case<float, fuzzypid::pid::Pid<float>>,
                               Case<double, FuzzyPid<double>>, Case<float, FuzzyPid<float>>>;
TYPED_TEST_SUITE(JointControllerTyped, Cases);

template <class Controller, class Scalar>
Controller make_controller(Scalar kp) {
  if constexpr (std::is_same_v<Controller, fuzzypid::pid::Pid<Scalar>>) {
    return make_pid<Scalar>(kp);
  } else {
    return make_fuzzy<Scalar>(kp);
  }
}

constexpr std::size_t kJoints = 6;

template <class Scalar, class Controller>
std::array<Controller, kJoints> make_joints() {
  std::array<Controller, kJoints> joints{};
  for (std::size_t i = 0; i < kJoints; ++i)
    joints[i] = make_controller<Controller>(Scalar(1) + Scalar(i));
  return joints;
}

TYPED_TEST(JointControllerTyped, EachJointEqualsItsOwnStandaloneController) {
  using Scalar = typename TypeParam::ScalarType;
  using Controller = typename TypeParam::ControllerType;
  const auto joints = make_joints<Scalar, Controller>();
  JointController<Scalar, kJoints, Controller> controller(joints);
  auto standalone = joints;
  const std::uint64_t seed = 61;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<Scalar> u(Scalar(-0.2), Scalar(0.2));
  for (int k = 0; k < 500; ++k) {
    std::array<Scalar, kJoints> qd{}, vd{}, q{}, v{}, ff{};
    for (std::size_t i = 0; i < kJoints; ++i) {
      qd[i] = u(rng);
      vd[i] = u(rng);
      q[i] = u(rng);
      v[i] = u(rng);
      ff[i] = u(rng);
    }
    const auto out = controller.step(input(qd, vd, q, v, ff), Scalar(0.01));
    ASSERT_EQ(out.status, Status::Ok);
    for (std::size_t i = 0; i < kJoints; ++i) {
      fuzzypid::pid::Input<Scalar> in;
      in.setpoint = qd[i];
      in.setpoint_rate = vd[i];
      in.measurement = q[i];
      in.measurement_rate = v[i];
      in.feed_forward = ff[i];
      ASSERT_EQ(standalone[i].update(in, Scalar(0.01)), Status::Ok);
      ASSERT_EQ(out.output[i], standalone[i].output()) << "joint " << i;
      ASSERT_EQ(out.joint_status[i], Status::Ok);
      ASSERT_EQ(controller.joint(i).output(), standalone[i].output());
    }
  }
}

TYPED_TEST(JointControllerTyped, ANaNOnOneJointFaultsOnlyThatJointAndHoldsItsCommand) {
  using Scalar = typename TypeParam::ScalarType;
  using Controller = typename TypeParam::ControllerType;
  JointController<Scalar, kJoints, Controller> controller(make_joints<Scalar, Controller>());
  std::array<Scalar, kJoints> qd{}, vd{}, q{}, v{};
  qd.fill(Scalar(0.1));
  const auto first = controller.step(input(qd, vd, q, v), Scalar(0.01));
  ASSERT_EQ(first.status, Status::Ok);

  auto twin = controller;
  auto bad_q = q;
  bad_q[2] = std::numeric_limits<Scalar>::quiet_NaN();
  auto bad_v = v;
  bad_v[4] = std::numeric_limits<Scalar>::infinity();
  const auto out = controller.step(input(qd, vd, bad_q, bad_v), Scalar(0.01));
  const auto reference = twin.step(input(qd, vd, q, v), Scalar(0.01));
  EXPECT_EQ(out.status, Status::NonFiniteInput);
  for (std::size_t i = 0; i < kJoints; ++i) {
    if (i == 2 || i == 4) {
      EXPECT_EQ(out.joint_status[i], Status::NonFiniteInput) << "joint " << i;
      EXPECT_EQ(out.output[i], first.output[i]) << "joint " << i;
    } else {
      EXPECT_EQ(out.joint_status[i], Status::Ok) << "joint " << i;
      EXPECT_EQ(out.output[i], reference.output[i]) << "joint " << i;
    }
  }
  // The faulty joints recover on the next good tick.
  const auto next = controller.step(input(qd, vd, q, v), Scalar(0.01));
  EXPECT_EQ(next.status, Status::Ok);
  EXPECT_EQ(next.output[0], twin.step(input(qd, vd, q, v), Scalar(0.01)).output[0]);
}

TYPED_TEST(JointControllerTyped, ABadTimeStepFaultsEveryJointAndHoldsEveryCommand) {
  using Scalar = typename TypeParam::ScalarType;
  using Controller = typename TypeParam::ControllerType;
  JointController<Scalar, kJoints, Controller> controller(make_joints<Scalar, Controller>());
  std::array<Scalar, kJoints> qd{}, vd{}, q{}, v{};
  qd.fill(Scalar(0.1));
  const auto first = controller.step(input(qd, vd, q, v), Scalar(0.01));
  const auto out = controller.step(input(qd, vd, q, v), Scalar(0));
  EXPECT_EQ(out.status, Status::InvalidTimeStep);
  for (std::size_t i = 0; i < kJoints; ++i) {
    EXPECT_EQ(out.joint_status[i], Status::InvalidTimeStep);
    EXPECT_EQ(out.output[i], first.output[i]);
  }
}

TYPED_TEST(JointControllerTyped, ResetClearsEveryJoint) {
  using Scalar = typename TypeParam::ScalarType;
  using Controller = typename TypeParam::ControllerType;
  JointController<Scalar, kJoints, Controller> controller(make_joints<Scalar, Controller>());
  std::array<Scalar, kJoints> qd{}, vd{}, q{}, v{};
  qd.fill(Scalar(0.1));
  for (int k = 0; k < 5; ++k)
    (void)controller.step(input(qd, vd, q, v), Scalar(0.01));
  controller.reset();
  for (std::size_t i = 0; i < kJoints; ++i)
    EXPECT_EQ(controller.joint(i).output(), Scalar(0));
}

TEST(JointController, PrototypeConstructorCopiesOneControllerIntoEveryJoint) {
  JointController<double, 3, fuzzypid::pid::Pid<double>> controller(make_pid<double>(2.0));
  EXPECT_EQ(controller.size(), 3u);
  const auto out = controller.step(JointInput<double, 3>{{1.0, 2.0, 3.0}}, 0.01);
  ASSERT_EQ(out.status, Status::Ok);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(controller.joint(i).gains().kp, 2.0);
    EXPECT_NEAR(out.output[i], 2.0 * (i + 1.0) + 0.5 * (i + 1.0) * 0.01, 1e-12);
  }
}

TEST(JointController, ThePapersControllerRunsThePapersFuzzyPidOnEveryJoint) {
  auto controller = fuzzypid::paper::make_joint_controller<double, 6>();
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(controller.joint(i).gains(), fuzzypid::paper::kNominalGains<double>);
    EXPECT_EQ(controller.joint(i).supervisor(), &fuzzypid::paper::kSystem<double>);
  }
  const auto out = controller.step(JointInput<double, 6>{{0.1, 0.1, 0.1, 0.1, 0.1, 0.1}}, 0.05);
  EXPECT_EQ(out.status, Status::Ok);
}

TEST(JointController, SixPaperJointsShareOneRuleBaseAndFitIn2KB) {
  // Per-joint state only (integrator, previous error, gains, filter; not the velocity observer's
  // estimate and commands, which the paper's PID omits); the rule base is shared.
  static_assert(sizeof(fuzzypid::paper::JointController<double, 6>) <= 2048);
  static_assert(sizeof(fuzzypid::paper::JointController<double, 6>) <
                sizeof(fuzzypid::paper::System<double>) + 2048);
  // A fuzzy PID whose inner PID can run the observer carries it: six scalars per joint.
  using WithObserver = fuzzypid::supervisor::FuzzyPid<double, fuzzypid::paper::System<double>>;
  static_assert(sizeof(WithObserver) >= sizeof(fuzzypid::paper::FuzzyPid<double>) + 6 * 8);
  const auto controller = fuzzypid::paper::make_joint_controller<double, 6>();
  for (std::size_t i = 1; i < 6; ++i)
    EXPECT_EQ(controller.joint(i).supervisor(), controller.joint(0).supervisor());
}

TEST(JointController, StatusIsTheWorstOfTheJoints) {
  // Joint 1 has a supervisor with no rule for large errors: NoRuleFired (a note), while joint 0
  // faults on NaN: the fault wins.
  using Gappy = fuzzypid::fuzzy::TskSystem<double, 2, 2, 3>;
  Gappy gappy;
  const std::array<fuzzypid::fuzzy::Term<double>, 2> terms{
      fuzzypid::fuzzy::Term<double>::triangle(-1.0, 0.0, 1.0),
      fuzzypid::fuzzy::Term<double>::triangle(0.0, 1.0, 2.0)};
  gappy.e = fuzzypid::fuzzy::LinguisticVariable<double, 2>::custom(-1.0, 2.0, terms);
  gappy.ec = gappy.e;
  using Joint = fuzzypid::supervisor::FuzzyPid<double, Gappy>;
  const Joint joint(&gappy, fuzzypid::paper::paper_config<double>());
  JointController<double, 2, Joint> controller(joint);
  auto out = controller.step(JointInput<double, 2>{{0.5, 5.0}}, 0.05);
  EXPECT_EQ(out.joint_status[0], Status::Ok);
  EXPECT_EQ(out.joint_status[1], Status::NoRuleFired);
  EXPECT_EQ(out.status, Status::NoRuleFired);
  out =
      controller.step(JointInput<double, 2>{{std::numeric_limits<double>::quiet_NaN(), 5.0}}, 0.05);
  EXPECT_EQ(out.joint_status[0], Status::NonFiniteInput);
  EXPECT_EQ(out.joint_status[1], Status::NoRuleFired);
  EXPECT_EQ(out.status, Status::NonFiniteInput);
}

TEST(Status, WorstOrdersFaultsAboveNotesAboveOk) {
  using fuzzypid::worst;
  EXPECT_EQ(worst(Status::Ok, Status::NoRuleFired), Status::NoRuleFired);
  EXPECT_EQ(worst(Status::NonFiniteInput, Status::NoRuleFired), Status::NonFiniteInput);
  EXPECT_FALSE(fuzzypid::is_fault(Status::NoRuleFired));
  EXPECT_TRUE(fuzzypid::is_fault(Status::InvalidTimeStep));
  EXPECT_STREQ(fuzzypid::to_string(Status::NumericOverflow), "numeric_overflow");
}

}  // namespace
