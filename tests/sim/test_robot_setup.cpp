// A condition's robot, path, tick and plant (sim::RobotSetup, Condition::payload_kg, dynamics,
// gravity): experiments built per setup, condition-file keys, continuous joints, gravity
// feed-forward and the payload mass in the closed loop.
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/sim/closed_loop.hpp"
#include "fuzzypid/sim/condition_set.hpp"
#include "fuzzypid/sim/experiment.hpp"

namespace fuzzypid::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kSource = FUZZYPID_SOURCE_DIR;

RobotSetup ur5_setup() {
  RobotSetup s;
  s.urdf = kSource + "/urdf/ur5_class.urdf";
  s.path = kSource + "/paths/ur5_deburring_contour.csv";
  return s;
}

std::string write_temp(const std::string& name, const std::string& text) {
  std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(RobotSetup, TheDefaultIsTheBundledEr50OnTheSection6LineWithItsArmature) {
  std::string error;
  const auto ex = Experiment::create(RobotSetup{}, ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  EXPECT_EQ(ex->ticks(), 101u);
  EXPECT_EQ(ex->armature_kgm2(), robot::kEr50ArmatureKgm2);
  // The same experiment as the one built from the model and the path spec.
  const auto model = robot::RobotModel::load(robot::default_urdf_path());
  ExperimentOptions options;
  options.plant.armature_kgm2 = robot::kEr50ArmatureKgm2;
  const auto direct = Experiment::create(*model.model, robot::paper_path_spec(), options, error);
  ASSERT_TRUE(direct);
  EXPECT_EQ(ex->path().position_rad, direct->path().position_rad);
  EXPECT_EQ(ex->nominal_inertia(), direct->nominal_inertia());
}

TEST(RobotSetup, TheTickResamplesTheLineAndAnotherUrdfHasNoArmatureUnlessGiven) {
  RobotSetup s;
  s.tick_s = 0.01;
  std::string error;
  const auto fine = Experiment::create(s, ExperimentOptions{}, error);
  ASSERT_TRUE(fine) << error;
  EXPECT_EQ(fine->ticks(), 501u);
  EXPECT_DOUBLE_EQ(fine->options().tick_s, 0.01);

  const auto ur5 = Experiment::create(ur5_setup(), ExperimentOptions{}, error);
  ASSERT_TRUE(ur5) << error;
  EXPECT_EQ(ur5->armature_kgm2(), robot::JointVector{});
  RobotSetup with = ur5_setup();
  with.armature_kgm2 = robot::JointVector{1, 2, 3, 4, 5, 6};
  const auto armed = Experiment::create(with, ExperimentOptions{}, error);
  ASSERT_TRUE(armed) << error;
  EXPECT_EQ(armed->armature_kgm2()[5], 6.0);
  EXPECT_NEAR(armed->nominal_inertia()[5] - ur5->nominal_inertia()[5], 6.0, 1e-12);
}

TEST(RobotSetup, AnotherArmOnTheEr50sLineFailsNamingTheSolverAndAskingForAPath) {
  RobotSetup s = ur5_setup();
  s.path.clear();
  std::string error;
  EXPECT_FALSE(Experiment::create(s, ExperimentOptions{}, error));
  EXPECT_NE(error.find("KDL Newton-Raphson"), std::string::npos) << error;
  EXPECT_NE(error.find("--path FILE"), std::string::npos) << error;
}

TEST(RobotSetup, AUrdfThatIsNotASixJointChainIsRefused) {
  RobotSetup s;
  s.urdf = kSource + "/tests/robot/data/five_joints.urdf";
  std::string error;
  EXPECT_FALSE(Experiment::create(s, ExperimentOptions{}, error));
  EXPECT_NE(error.find("five_joints.urdf"), std::string::npos) << error;
}

// An IK seed changes only the first row of a Cartesian path file: with the built-in line or a
// joint path it would be ignored, so it is refused, naming the path.
TEST(RobotSetup, AnIkSeedIsRefusedWhereNoInverseKinematicsUsesIt) {
  RobotSetup s;
  s.ik_seed_rad = robot::JointVector{0, -1, 1, 0, 0, 0};
  EXPECT_NE(s.validate().find("ik_seed (--ik-seed) applies only to a Cartesian path file"),
            std::string::npos)
      << s.validate();
  std::string error;
  EXPECT_FALSE(Experiment::create(s, ExperimentOptions{}, error));

  RobotSetup joint = ur5_setup();
  joint.path = write_temp("ik_seed_joint.csv",
                          "t_s,q1_rad,q2_rad,q3_rad,q4_rad,q5_rad,q6_rad\n0,0,-1,1,0,0,0\n"
                          "1,0,-1,1.2,0,0,0\n");
  joint.ik_seed_rad = robot::JointVector{0, -1, 1, 0, 0, 0};
  EXPECT_EQ(joint.validate(), "");
  EXPECT_FALSE(Experiment::create(joint, ExperimentOptions{}, error));
  EXPECT_NE(error.find("applies only to a Cartesian path file; " + joint.path + " is a joint path"),
            std::string::npos)
      << error;
  joint.ik_seed_rad.reset();
  EXPECT_TRUE(Experiment::create(joint, ExperimentOptions{}, error)) << error;

  // A Cartesian path (the poses of the joint rows above) takes the seed.
  const auto model = robot::RobotModel::load(ur5_setup().urdf);
  ASSERT_TRUE(model.model) << model.error;
  std::string rows = "t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n";
  robot::RobotData data(*model.model);
  for (const double t : {0.0, 1.0}) {
    const robot::Pose p = model.model->forward_kinematics({0, -1, 1 + 0.2 * t, 0, 0, 0}, data);
    const Eigen::Vector3d rpy = p.rotation.eulerAngles(2, 1, 0);
    char buf[200];
    std::snprintf(buf, sizeof buf, "%g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, p.position_m.x(),
                  p.position_m.y(), p.position_m.z(), rpy[2], rpy[1], rpy[0]);
    rows += buf;
  }
  RobotSetup pose = ur5_setup();
  pose.path = write_temp("ik_seed_pose.csv", rows);
  pose.ik_seed_rad = robot::JointVector{0, -1, 1, 0, 0, 0};
  const auto ex = Experiment::create(pose, ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  EXPECT_NEAR(ex->path().position_rad.front()[2], 1.0, 1e-6);
}

// A path end point is a position within 1 km of the base on every axis, bound included; beyond
// it, or not finite, the setup names what is wrong.
TEST(RobotSetup, PathEndPointsBeyondOneKilometreOrNotFiniteAreRefused) {
  const std::string refused = "path end points must be finite and within ±1 km of the base, m";
  RobotSetup s;
  s.start_m = std::array<double, 3>{1000.0, -1000.0, 0.5};
  s.end_m = std::array<double, 3>{1.6, 0.24, 0.49};
  EXPECT_EQ(s.validate(), "");
  s.start_m = std::array<double, 3>{1.35, std::nextafter(1000.0, 2000.0), 1.25};
  EXPECT_EQ(s.validate(), refused);
  s.start_m.reset();
  s.end_m = std::array<double, 3>{1.6, 0.24, -1e48};
  EXPECT_EQ(s.validate(), refused);
  s.end_m = std::array<double, 3>{std::nan(""), 0.24, 0.49};
  EXPECT_EQ(s.validate(), refused);
}

TEST(ExperimentSet, BuildsOneExperimentPerDistinctSetup) {
  std::vector<Condition> conditions(4);
  conditions[1].robot = ur5_setup();
  conditions[2].payload_kg = 3.0;  // a plant variant: same experiment as condition 0
  conditions[3].robot = ur5_setup();
  std::string error;
  const auto set = ExperimentSet::create(conditions, ExperimentOptions{}, error);
  ASSERT_TRUE(set) << error;
  EXPECT_EQ(set->size(), 2u);
  EXPECT_EQ(&set->of(0), &set->of(2));
  EXPECT_EQ(&set->of(1), &set->of(3));
  EXPECT_NE(&set->of(0), &set->of(1));
}

TEST(ConditionFile, RobotKeysResolveAgainstTheFilesFolderAndSetTablesGiveDefaults) {
  const std::string text = R"(
[sets.training]
urdf = "../urdf/ur5_class.urdf"
path = "../paths/ur5_deburring_contour.csv"
tick_ms = 10.0
dynamics = "coupled"
gravity = true
conditions = [
  { name = "empty" },
  { name = "loaded", payload_kg = 2.5, armature = [1, 1, 1, 0.1, 0.1, 0.1] },
  { name = "flat", dynamics = "decoupled", gravity = false, ik_seed = [0, -1, 1, 0, 0, 0] },
]
)";
  ConditionFile f;
  fuzzypid::FileError e;
  ASSERT_TRUE(parse_conditions(text, "/somewhere/tuning/robot.toml", f, e)) << e.to_string();
  const auto& c = f.sets[0].conditions;
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].robot.urdf, "/somewhere/urdf/ur5_class.urdf");
  EXPECT_EQ(c[0].robot.path, "/somewhere/paths/ur5_deburring_contour.csv");
  EXPECT_DOUBLE_EQ(c[0].robot.tick_s, 0.01);
  EXPECT_EQ(c[0].dynamics, robot::PlantCoupling::Coupled);
  EXPECT_TRUE(c[0].gravity);
  EXPECT_EQ(c[1].payload_kg, 2.5);
  ASSERT_TRUE(c[1].robot.armature_kgm2);
  EXPECT_EQ((*c[1].robot.armature_kgm2)[3], 0.1);
  EXPECT_EQ(c[2].dynamics, robot::PlantCoupling::Decoupled);
  ASSERT_TRUE(c[2].robot.ik_seed_rad);
  EXPECT_EQ((*c[2].robot.ik_seed_rad)[1], -1.0);
}

TEST(ConditionFile, BadRobotKeysAreErrorsWithTheirPosition) {
  const auto error_of = [](const std::string& condition) {
    ConditionFile f;
    fuzzypid::FileError e;
    EXPECT_FALSE(
        parse_conditions("[sets.s]\nconditions = [\n  " + condition + "\n]\n", "c.toml", f, e))
        << condition;
    return e.to_string();
  };
  EXPECT_NE(error_of("{ name = \"g\", gravity = true }").find("c.toml:3:"), std::string::npos);
  EXPECT_NE(error_of("{ name = \"g\", gravity = true }").find("gravity needs the coupled"),
            std::string::npos);
  EXPECT_NE(error_of("{ name = \"a\", armature = [1, 2, 3] }").find("6 values"), std::string::npos);
  EXPECT_NE(error_of("{ name = \"p\", payload_kg = -1.0 }").find("'payload_kg' must be within"),
            std::string::npos);
  EXPECT_NE(error_of("{ name = \"t\", tick_ms = 0.0 }").find("'tick_ms' must be within"),
            std::string::npos);
  EXPECT_NE(error_of("{ name = \"d\", dynamics = \"rigid\" }").find("decoupled|coupled"),
            std::string::npos);
}

TEST(ClosedLoop, AContinuousJointFollowsAPathThroughPiWithoutUnwinding) {
  const std::string path = write_temp("wrap.csv",
                                      "t_s,q1_rad,q2_rad,q3_rad,q4_rad,q5_rad,q6_rad\n"
                                      "0,0,-1.3,1.6,-0.9,-1.2,2.9\n"
                                      "1,0,-1.3,1.6,-0.9,-1.2,-2.9\n"
                                      "2,0,-1.3,1.6,-0.9,-1.2,-2.6\n");
  RobotSetup s;
  s.urdf = kSource + "/tests/robot/data/continuous_wrist.urdf";
  s.path = path;
  std::string error;
  const auto ex = Experiment::create(s, ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  Condition c;
  c.robot = s;
  c.initial_error_rad = 0.0;
  const controller::ControllerSpec pid =
      default_controller(ExperimentOptions{}, controller::paper_pid());
  // The plant starts at 2.9 rad; the reference, unwrapped, ends at 2 pi - 2.6 = 3.68 rad.
  auto loop = ClosedLoop::create(*ex, c, pid, error);
  ASSERT_TRUE(loop) << error;
  double worst = 0.0;
  for (std::size_t k = 0; k < loop->samples(); ++k) {
    const TickResult r = loop->tick(k, k + 1 < loop->samples());
    worst = std::fmax(worst, std::fabs(r.theta_d[5] - r.theta[5]));
  }
  EXPECT_LT(worst, 0.2);
  EXPECT_GT(loop->plant().position()[5], 3.0);  // went forwards through pi

  // A measurement one turn away gives the same command: the error is wrapped.
  auto a = ClosedLoop::create(*ex, c, pid, error);
  auto b = ClosedLoop::create(*ex, c, pid, error);
  TickInjection turned;
  turned.measured_position_offset_rad[5] = 2 * kPi;
  const TickResult ra = a->tick(a->sample(3), {}, false);
  const TickResult rb = b->tick(b->sample(3), turned, false);
  EXPECT_NEAR(ra.command.output[5], rb.command.output[5], 1e-9);
}

TEST(ClosedLoop, GravityFeedForwardCarriesTheLoadTheIntegralOtherwiseMust) {
  RobotSetup s = ur5_setup();
  s.tick_s = 0.01;
  std::string error;
  const auto ex = Experiment::create(s, ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  Condition c;
  c.robot = s;
  c.dynamics = robot::PlantCoupling::Coupled;
  c.gravity = true;
  controller::ControllerSpec pid = controller::paper_pid();
  pid.units.gains = controller::GainUnits::Acceleration;  // torque = J^_i u_i
  pid.units.form = controller::PidForm::Continuous;
  pid.gains = {400.0, 40.0, 40.0};  // 1/s², 1/s³, 1/s
  RunLimits limits;
  limits.max_error_rad = 1.0;
  const RunResult without = ex->run(c, pid, limits);
  pid.feedforward.gravity = true;
  const RunResult with = ex->run(c, pid, limits);
  ASSERT_TRUE(without.ok) << without.error;
  ASSERT_TRUE(with.ok) << with.error;
  const double itae_without = total_itae(without.rows, 0.01);
  const double itae_with = total_itae(with.rows, 0.01);
  std::printf("ITAE without feed-forward %.6g, with %.6g\n", itae_without, itae_with);
  EXPECT_LT(itae_with, 0.2 * itae_without);
  // Without gravity in the plant the feed-forward would be a disturbance: it is only added when
  // the file asks for it, whatever the plant.
  c.dynamics = robot::PlantCoupling::Decoupled;
  c.gravity = false;
  const RunResult flat_ff = ex->run(c, pid, limits);
  pid.feedforward.gravity = false;
  const RunResult flat = ex->run(c, pid, limits);
  EXPECT_GT(total_itae(flat_ff.rows, 0.01), total_itae(flat.rows, 0.01));
}

TEST(ClosedLoop, APayloadMassLoadsThePlantNotTheControllersModel) {
  std::string error;
  const auto ex = Experiment::create(RobotSetup{}, ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  Condition light, heavy;
  heavy.payload_kg = 50.0;
  const auto q = ex->path().position_rad.front();
  const robot::RobotModel light_model = ex->plant_model(light);
  const robot::RobotModel heavy_model = ex->plant_model(heavy);
  robot::RobotData light_data(light_model), heavy_data(heavy_model);
  const robot::JointVector j0 = light_model.inertia_diagonal(q, light_data);
  const robot::JointVector j1 = heavy_model.inertia_diagonal(q, heavy_data);
  EXPECT_GT(j1[0], j0[0] + 1.0);  // 50 kg about 1.5 m from the base axis
  EXPECT_EQ(j1[5], j0[5]);        // a point mass on the last axis adds nothing to it
  const controller::ControllerSpec pid =
      default_controller(ExperimentOptions{}, controller::paper_pid());
  const RunResult a = ex->run(light, pid);
  const RunResult b = ex->run(heavy, pid);
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_NE(total_itae(a.rows, 0.05), total_itae(b.rows, 0.05));
  // The controller sees the same first tick: its model has no payload.
  for (std::size_t i = 0; i < robot::kNumJoints; ++i)
    EXPECT_EQ(a.rows[i].u, b.rows[i].u);
}

}  // namespace
}  // namespace fuzzypid::sim
