// The bundled ER50-C20 URDF and the URDF -> KDL loader.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "fuzzypid/robot/dh_parameters.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "test_support.hpp"

namespace fuzzypid::robot {
namespace {

using test::bundled_model;
using test::coriolis_of;
using test::fk;
using test::inertia_diagonal_of;
using test::jacobian_of;
using test::mass_matrix_of;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Table 1 as modified D-H, written out independently of the library:
// T_{i-1,i} = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i) TransZ(d_i).
Eigen::Matrix4d table1_product(const JointVector& q) {
  const double alpha[6] = {0.0, -90.0 * kDeg, 0.0, -90.0 * kDeg, 90.0 * kDeg, -90.0 * kDeg};
  const double a[6] = {0.0, 0.220, 0.900, 0.160, 0.0, 0.0};
  const double d[6] = {0.563, 0.0, 0.0, 1.014, 0.0, 0.0};
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  for (int i = 0; i < 6; ++i) {
    Eigen::Matrix4d rx = Eigen::Matrix4d::Identity();
    rx.block<3, 3>(0, 0) = Eigen::AngleAxisd(alpha[i], Eigen::Vector3d::UnitX()).toRotationMatrix();
    Eigen::Matrix4d tx = Eigen::Matrix4d::Identity();
    tx(0, 3) = a[i];
    Eigen::Matrix4d rz = Eigen::Matrix4d::Identity();
    rz.block<3, 3>(0, 0) =
        Eigen::AngleAxisd(q[static_cast<std::size_t>(i)], Eigen::Vector3d::UnitZ())
            .toRotationMatrix();
    Eigen::Matrix4d tz = Eigen::Matrix4d::Identity();
    tz(2, 3) = d[i];
    t = t * rx * tx * rz * tz;
  }
  return t;
}

std::string data_path(const char* name) {
  return std::string(FUZZYPID_ROBOT_TEST_DATA) + "/" + name;
}

TEST(RobotModel, LoadsTheBundledUrdfWithoutAPath) {
  const LoadResult r = RobotModel::load(default_urdf_path());
  ASSERT_TRUE(r.model.has_value()) << r.error;
  EXPECT_TRUE(r.error.empty());
  EXPECT_EQ(r.model->root_link(), "base_link");
  EXPECT_EQ(r.model->tip_link(), "flange");
  EXPECT_EQ(r.model->joint_names()[0], "joint1");
  EXPECT_EQ(r.model->joint_names()[5], "joint6");
}

TEST(RobotModel, EnvironmentVariableOverridesTheDefaultUrdf) {
  ASSERT_EQ(::setenv("FUZZYPID_URDF", "/some/where/else.urdf", 1), 0);
  EXPECT_EQ(default_urdf_path(), "/some/where/else.urdf");
  ASSERT_EQ(::unsetenv("FUZZYPID_URDF"), 0);
  EXPECT_NE(default_urdf_path(), "/some/where/else.urdf");
}

TEST(RobotModel, JointLimitsAreTable1Ranges) {
  const RobotModel& m = bundled_model();
  const JointVector lower = {-180 * kDeg, -135 * kDeg, -80 * kDeg,
                             -360 * kDeg, -120 * kDeg, -450 * kDeg};
  const JointVector upper = {180 * kDeg, 80 * kDeg, 225 * kDeg, 360 * kDeg, 120 * kDeg, 450 * kDeg};
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    EXPECT_NEAR(m.lower_limits_rad()[i], lower[i], 1e-15) << "joint " << i + 1;
    EXPECT_NEAR(m.upper_limits_rad()[i], upper[i], 1e-15) << "joint " << i + 1;
    EXPECT_GT(m.velocity_limits_rad_s()[i], 0.0);
    EXPECT_TRUE(std::isfinite(m.effort_limits_nm()[i]));
  }
}

TEST(RobotModel, ForwardKinematicsIsTheProductOfTable1Transforms) {
  const RobotModel& m = bundled_model();
  auto rng = test::seeded_rng(20240601, "ForwardKinematicsIsTheProductOfTable1Transforms");
  for (int n = 0; n < 2000; ++n) {
    const JointVector q = test::random_within(m, rng);
    const Pose p = fk(m, q);
    const Eigen::Matrix4d t = table1_product(q);
    EXPECT_LT((p.position_m - t.block<3, 1>(0, 3)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((p.rotation - t.block<3, 3>(0, 0)).cwiseAbs().maxCoeff(), 1e-12);
    const Pose c = dh_forward_kinematics(er50_c20_dh(), q);
    EXPECT_LT((p.position_m - c.position_m).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((p.rotation - c.rotation).cwiseAbs().maxCoeff(), 1e-12);
  }
}

// At q = 0: frame 2 sits at (a1, 0, d1) with y2 = -z0; frame 3 is a2 further along x0; the
// J4 offset (a3, d4) in frame 3 is a3 along x0 and d4 along -z0. Wrist center = tip =
// (a1 + a2 + a3, 0, d1 - d4) = (1.280, 0, -0.451) m, and the tip axes are x0, -y0, -z0.
TEST(RobotModel, ZeroConfigurationPutsTheWristCenterBelowTheShoulder) {
  const Pose p = fk(bundled_model(), JointVector{});
  EXPECT_NEAR(p.position_m.x(), 1.280, 1e-12);
  EXPECT_NEAR(p.position_m.y(), 0.0, 1e-12);
  EXPECT_NEAR(p.position_m.z(), -0.451, 1e-12);
  EXPECT_LT(
      (p.rotation - Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix()).cwiseAbs().maxCoeff(),
      1e-12);
}

TEST(RobotModel, JacobianMatchesFiniteDifferencesOfForwardKinematics) {
  const RobotModel& m = bundled_model();
  auto rng = test::seeded_rng(77, "JacobianMatchesFiniteDifferencesOfForwardKinematics");
  const double h = 1e-6;
  for (int n = 0; n < 200; ++n) {
    const JointVector q = test::random_within(m, rng);
    const Eigen::Matrix<double, 6, 6> jac = jacobian_of(m, q);
    const Pose p0 = fk(m, q);
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      JointVector qp = q;
      JointVector qm = q;
      qp[j] += h;
      qm[j] -= h;
      const Pose pp = fk(m, qp);
      const Pose pm = fk(m, qm);
      const Eigen::Vector3d v = (pp.position_m - pm.position_m) / (2 * h);
      // Ṙ Rᵀ = [ω]x
      const Eigen::Matrix3d w = (pp.rotation - pm.rotation) / (2 * h) * p0.rotation.transpose();
      const Eigen::Vector3d omega(w(2, 1), w(0, 2), w(1, 0));
      const auto c = static_cast<int>(j);
      EXPECT_LT((jac.block<3, 1>(0, c) - v).norm(), 1e-7) << "column " << j;
      EXPECT_LT((jac.block<3, 1>(3, c) - omega).norm(), 1e-7) << "column " << j;
    }
  }
}

TEST(RobotModel, MassMatrixIsSymmetricPositiveDefiniteWithItsDiagonalExposed) {
  const RobotModel& m = bundled_model();
  auto rng = test::seeded_rng(5, "MassMatrixIsSymmetricPositiveDefinite");
  for (int n = 0; n < 200; ++n) {
    const JointVector q = test::random_within(m, rng);
    const Eigen::Matrix<double, 6, 6> mm = mass_matrix_of(m, q);
    EXPECT_LT((mm - mm.transpose()).cwiseAbs().maxCoeff(), 1e-9);
    const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(mm);
    EXPECT_EQ(llt.info(), Eigen::Success);
    const JointVector d = inertia_diagonal_of(m, q);
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      EXPECT_DOUBLE_EQ(d[i], mm(static_cast<int>(i), static_cast<int>(i)));
    }
  }
}

TEST(RobotModel, GravityDoesNotLoadTheVerticalFirstAxisAndCoriolisVanishesAtRest) {
  const RobotModel& m = bundled_model();
  const JointVector q = {0.3, -0.8, 0.4, 0.2, -0.6, 0.1};
  const JointVector g = m.gravity_torque(q);
  EXPECT_NEAR(g[0], 0.0, 1e-9);
  EXPECT_GT(std::fabs(g[1]), 100.0);  // the shoulder carries the arm
  const JointVector c = coriolis_of(m, q, JointVector{});
  for (double v : c)
    EXPECT_NEAR(v, 0.0, 1e-12);
}

TEST(RobotModel, CopiesAndMovesAreIndependentModels) {
  const RobotModel& m = bundled_model();
  RobotModel copy = m;
  RobotModel moved = std::move(copy);
  const JointVector q = {0.1, -0.2, 0.3, -0.4, 0.5, -0.6};
  EXPECT_EQ(fk(moved, q).position_m, fk(m, q).position_m);
  RobotModel assigned = m;
  assigned = moved;
  EXPECT_EQ(jacobian_of(assigned, q), jacobian_of(m, q));
}

// A RobotData serves the model it was made for; given to another model (a copy, or a model
// assigned to since) every query returns NaN, never the other chain's numbers.
TEST(RobotModel, ARobotDataOfAnotherModelGivesNaN) {
  const RobotModel& m = bundled_model();
  const JointVector q = {0.1, -0.2, 0.3, -0.4, 0.5, -0.6};
  RobotData data(m);
  EXPECT_TRUE(m.forward_kinematics(q, data).position_m.allFinite());
  const RobotModel copy = m.with_payload(0.0);  // an equal copy: another model
  const Pose p = copy.forward_kinematics(q, data);
  EXPECT_TRUE(p.position_m.array().isNaN().all() && p.rotation.array().isNaN().all());
  EXPECT_TRUE(copy.jacobian(q, data).array().isNaN().all());
  EXPECT_TRUE(copy.mass_matrix(q, data).array().isNaN().all());
  for (const double v : copy.inertia_diagonal(q, data))
    EXPECT_TRUE(std::isnan(v));
  for (const double v : copy.coriolis_torque(q, q, data))
    EXPECT_TRUE(std::isnan(v));
  RobotModel assigned = m;
  RobotData assigned_data(assigned);
  assigned = m;  // a new chain: the data made before no longer fits
  EXPECT_TRUE(std::isnan(assigned.inertia_diagonal(q, assigned_data)[0]));
  RobotData fresh(assigned);
  EXPECT_EQ(assigned.inertia_diagonal(q, fresh), m.inertia_diagonal(q, data));
}

// One model, two threads, each with its own RobotData: the same numbers as one thread alone (the
// model holds no scratch, so the threads share nothing they write).
TEST(RobotModel, TwoThreadsQueryOneModelWithTheirOwnData) {
  const RobotModel& m = bundled_model();
  auto rng = test::seeded_rng(20261205, "two threads");
  std::vector<JointVector> qs(2000);
  for (JointVector& q : qs)
    q = test::random_within(m, rng);
  std::vector<Eigen::Matrix<double, 6, 6>> alone(qs.size());
  {
    RobotData data(m);
    for (std::size_t k = 0; k < qs.size(); ++k)
      alone[k] = m.mass_matrix(qs[k], data);
  }
  std::vector<Eigen::Matrix<double, 6, 6>> a(qs.size()), b(qs.size());
  const auto work = [&](std::vector<Eigen::Matrix<double, 6, 6>>& out) {
    RobotData data(m);
    for (std::size_t k = 0; k < qs.size(); ++k)
      out[k] = m.mass_matrix(qs[k], data);
  };
  std::thread t1(work, std::ref(a)), t2(work, std::ref(b));
  t1.join();
  t2.join();
  for (std::size_t k = 0; k < qs.size(); ++k) {
    ASSERT_EQ(a[k], alone[k]) << k;
    ASSERT_EQ(b[k], alone[k]) << k;
  }
}

struct BadUrdfCase {
  const char* file;
  const char* root;
  const char* tip;
  const char* expected_fragment;
};

class RobotModelLoadErrors : public ::testing::TestWithParam<BadUrdfCase> {};

TEST_P(RobotModelLoadErrors, ReportAReasonInsteadOfAModel) {
  const BadUrdfCase& c = GetParam();
  const std::string path = c.file[0] == '/'
                               ? std::string(c.file)
                               : (c.file[0] == '@' ? default_urdf_path() : data_path(c.file));
  const LoadResult r = RobotModel::load(path, c.root, c.tip);
  EXPECT_FALSE(r.model.has_value());
  EXPECT_NE(r.error.find(c.expected_fragment), std::string::npos) << "error was: " << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, RobotModelLoadErrors,
    ::testing::Values(BadUrdfCase{"/nonexistent/robot.urdf", "", "", "cannot open"},
                      BadUrdfCase{"malformed.urdf", "", "", "not a valid URDF"},
                      BadUrdfCase{"dangling_joint.urdf", "", "", "not a valid URDF"},
                      BadUrdfCase{"branching.urdf", "", "", "branches at link 'base'"},
                      BadUrdfCase{"five_joints.urdf", "", "", "has 5 movable joints"},
                      BadUrdfCase{"prismatic.urdf", "", "", "unsupported"},
                      BadUrdfCase{"@", "no_such_link", "", "root link 'no_such_link'"},
                      BadUrdfCase{"@", "", "no_such_link", "tip link 'no_such_link'"},
                      BadUrdfCase{"@", "link6", "link2", "not below root link"},
                      BadUrdfCase{"@", "base_link", "link4", "has 4 movable joints"}));

std::string bundled_urdf_text() {
  std::ifstream in(default_urdf_path());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A URDF that is not UTF-8 is refused before the XML parser sees it, naming the byte: TinyXML
// steps over a multi-byte character by its lead byte's length, so a lead byte without its
// continuation bytes at the end of the text made it read past the buffer (fuzz_urdf found it;
// fuzz/corpus/urdf/truncated_utf8_name.urdf). Well-formed multi-byte text still loads.
TEST(RobotModel, RefusesTextThatIsNotUtf8NamingTheByte) {
  const std::string text = bundled_urdf_text();
  const std::size_t robot_tag = text.find("<robot");
  ASSERT_NE(robot_tag, std::string::npos);
  struct Case {
    const char* name;
    std::string text;
    std::size_t bad;  // npos: loads
  };
  const std::string comment = "<!-- torque in N\xC2\xB7m, 50 \xE2\x80\x93 80 -->\n";
  const std::vector<Case> cases = {
      {"valid_multibyte", text.substr(0, robot_tag) + comment + text.substr(robot_tag),
       std::string::npos},
      {"lone_continuation", text.substr(0, robot_tag) + "<!-- \x80 -->" + text.substr(robot_tag),
       robot_tag + 5},
      {"latin1", text.substr(0, robot_tag) + "<!-- N\xB7m -->" + text.substr(robot_tag),
       robot_tag + 6},
      {"overlong", text.substr(0, robot_tag) + "<!-- \xC0\xAF -->" + text.substr(robot_tag),
       robot_tag + 5},
      {"surrogate", text.substr(0, robot_tag) + "<!-- \xED\xA0\x80 -->" + text.substr(robot_tag),
       robot_tag + 5},
      {"truncated_at_end", text + "\xE1", text.size()},
  };
  for (const Case& c : cases) {
    const std::string path = ::testing::TempDir() + "fuzzypid_utf8_" + c.name + "_" +
                             std::to_string(::getpid()) + ".urdf";
    {
      std::ofstream out(path, std::ios::binary);
      out << c.text;
    }
    const LoadResult r = RobotModel::load(path);
    std::remove(path.c_str());
    if (c.bad == std::string::npos) {
      EXPECT_TRUE(r.model.has_value()) << c.name << ": " << r.error;
      continue;
    }
    EXPECT_FALSE(r.model.has_value()) << c.name;
    EXPECT_NE(r.error.find("is not UTF-8 text: byte " + std::to_string(c.bad) + " (0x"),
              std::string::npos)
        << c.name << ": " << r.error;
  }
}

// Physically meaningless URDF content is refused with the element named: each case edits one
// element of the bundled URDF (first occurrence of `from`) and expects the loader to name it.
struct InvalidElementCase {
  const char* name;
  const char* from;
  const char* to;
  const char* expected_fragment;
};

class RobotModelRefusesInvalidElements : public ::testing::TestWithParam<InvalidElementCase> {};

TEST_P(RobotModelRefusesInvalidElements, NamingTheElement) {
  const InvalidElementCase& c = GetParam();
  std::string text = bundled_urdf_text();
  const std::size_t at = text.find(c.from);
  ASSERT_NE(at, std::string::npos) << "the bundled URDF has no " << c.from;
  text.replace(at, std::string(c.from).size(), c.to);
  const std::string path =
      ::testing::TempDir() + "fuzzypid_" + c.name + "_" + std::to_string(::getpid()) + ".urdf";
  {
    std::ofstream out(path);
    out << text;
  }
  const LoadResult r = RobotModel::load(path);
  std::remove(path.c_str());
  EXPECT_FALSE(r.model.has_value());
  EXPECT_NE(r.error.find(c.expected_fragment), std::string::npos) << "error was: " << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, RobotModelRefusesInvalidElements,
    ::testing::Values(
        InvalidElementCase{"zero_axis", R"(<axis xyz="0 0 1"/>)", R"(<axis xyz="0 0 0"/>)",
                           "joint 'joint1': <axis> must be a finite non-zero vector"},
        InvalidElementCase{"negative_mass", R"(<mass value="180"/>)", R"(<mass value="-1"/>)",
                           "link 'link1': <inertial> <mass> must be finite and non-negative"},
        InvalidElementCase{
            "nan_mass", R"(<mass value="180"/>)", R"(<mass value="nan"/>)",
            "mass [nan] is not a float; Could not parse inertial element for Link [link1]"},
        InvalidElementCase{"indefinite_inertia", R"(ixx="12" ixy="0")", R"(ixx="-12" ixy="0")",
                           "link 'link1': <inertial> <inertia> is not positive definite"},
        InvalidElementCase{"singular_inertia", R"(ixx="12" ixy="0")", R"(ixx="0" ixy="0")",
                           "link 'link1': <inertial> <inertia> is not positive definite"},
        InvalidElementCase{"triangle_inequality", R"(ixx="12" ixy="0")", R"(ixx="30" ixy="0")",
                           "link 'link1': <inertial> <inertia> violates the triangle inequality"},
        InvalidElementCase{"negative_effort", R"(effort="3500")", R"(effort="-3500")",
                           "joint 'joint1': <limit> effort must be non-negative"},
        InvalidElementCase{"negative_velocity", R"(velocity="3.141592653589793" effort="3500")",
                           R"(velocity="-1" effort="3500")",
                           "joint 'joint1': <limit> velocity must be non-negative"},
        InvalidElementCase{"mimic", R"(<axis xyz="0 0 1"/>)",
                           R"(<axis xyz="0 0 1"/><mimic joint="joint2" multiplier="1"/>)",
                           "joint 'joint1': <mimic> (joint 'joint2') is not supported"},
        // Limits written in degrees: refused at load, naming the joint and the value, instead of
        // loading and failing later as an IK error.
        InvalidElementCase{"limits_in_degrees",
                           R"(lower="-3.141592653589793" upper="3.141592653589793")",
                           R"(lower="-180" upper="180")",
                           "joint 'joint1': <limit> lower=\"-180\" rad is beyond two turns"},
        InvalidElementCase{"upper_limit_in_degrees",
                           R"(lower="-3.141592653589793" upper="3.141592653589793")",
                           R"(lower="-3.141592653589793" upper="12.6")",
                           "joint 'joint1': <limit> upper=\"12.6\" rad is beyond two turns"}),
    [](const ::testing::TestParamInfo<InvalidElementCase>& info) { return info.param.name; });

// Two turns is still a limit (the ER50's joint 4 has +-2 pi), a little more than two turns is not.
TEST(RobotModel, AcceptsLimitsOfTwoTurns) {
  std::string text = bundled_urdf_text();
  const std::string from = R"(lower="-3.141592653589793" upper="3.141592653589793")";
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), R"(lower="-12.566370614359172" upper="12.566370614359172")");
  const std::string path =
      ::testing::TempDir() + "fuzzypid_two_turns_" + std::to_string(::getpid()) + ".urdf";
  {
    std::ofstream out(path);
    out << text;
  }
  const LoadResult r = RobotModel::load(path);
  std::remove(path.c_str());
  ASSERT_TRUE(r.model.has_value()) << r.error;
  EXPECT_DOUBLE_EQ(r.model->upper_limits_rad()[0], 4.0 * kPi);
}

// A URDF whose last moving link has no <inertial>: nothing moves with joint 6, whose plant would
// divide by a zero inertia at t = 0 (numerical_error). Refused at load, naming joint and link.
TEST(RobotModel, RefusesAJointThatMovesNoInertia) {
  std::string text = bundled_urdf_text();
  const std::size_t link = text.find("<link name=\"link6\">");
  ASSERT_NE(link, std::string::npos);
  const std::size_t end = text.find("</link>", link);
  text.replace(link, end + 7 - link, "<link name=\"link6\"/>");
  const std::string path =
      ::testing::TempDir() + "fuzzypid_no_inertial_" + std::to_string(::getpid()) + ".urdf";
  {
    std::ofstream out(path);
    out << text;
  }
  const LoadResult r = RobotModel::load(path);
  EXPECT_FALSE(r.model.has_value());
  EXPECT_NE(r.error.find("no inertia moves with joint 6 ('joint6'): link 'link6'"),
            std::string::npos)
      << r.error;
  // A link without <inertial> whose joint still moves the links below it loads.
  std::string inner = bundled_urdf_text();
  const std::size_t l3 = inner.find("<link name=\"link3\">");
  ASSERT_NE(l3, std::string::npos);
  inner.replace(l3, inner.find("</link>", l3) + 7 - l3, "<link name=\"link3\"/>");
  {
    std::ofstream out(path);
    out << inner;
  }
  const LoadResult ok = RobotModel::load(path);
  std::remove(path.c_str());
  EXPECT_TRUE(ok.model.has_value()) << ok.error;
}

// URDF's effort="0" and velocity="0" mean "no limit": the model keeps an infinite limit and says
// so in notes(), one line per joint and limit; the bundled URDF has none.
TEST(RobotModel, NotesTheLimitsAUrdfLeavesOpen) {
  EXPECT_TRUE(bundled_model().notes().empty());
  std::string text = bundled_urdf_text();
  const std::string from = R"(velocity="3.141592653589793" effort="3500")";
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), R"(velocity="0" effort="0")");
  const std::string path =
      ::testing::TempDir() + "fuzzypid_zero_limits_" + std::to_string(::getpid()) + ".urdf";
  {
    std::ofstream out(path);
    out << text;
  }
  const LoadResult r = RobotModel::load(path);
  std::remove(path.c_str());
  ASSERT_TRUE(r.model.has_value()) << r.error;
  EXPECT_TRUE(std::isinf(r.model->effort_limits_nm()[0]));
  EXPECT_TRUE(std::isinf(r.model->velocity_limits_rad_s()[0]));
  ASSERT_EQ(r.model->notes().size(), 2u);
  EXPECT_NE(r.model->notes()[0].find("joint 'joint1': <limit> velocity=\"0\" means no limit"),
            std::string::npos)
      << r.model->notes()[0];
  EXPECT_NE(r.model->notes()[1].find("joint 'joint1': <limit> effort=\"0\" means no limit"),
            std::string::npos)
      << r.model->notes()[1];
}

// The moving mass is the links below the first joint: the ER50-C20's URDF masses minus its base.
TEST(RobotModel, MovingMassIsTheLinksBelowTheFirstJoint) {
  std::string text = bundled_urdf_text();
  double total = 0.0, base = 0.0;
  for (std::size_t at = text.find("<link name="); at != std::string::npos;
       at = text.find("<link name=", at + 1)) {
    const std::size_t next = text.find("<link name=", at + 1);
    const std::size_t mass = text.find("<mass value=\"", at);
    if (mass == std::string::npos || (next != std::string::npos && mass > next)) continue;
    const double m = std::strtod(text.c_str() + mass + 13, nullptr);
    total += m;
    if (text.compare(at, 22, "<link name=\"base_link\"") == 0) base = m;
  }
  ASSERT_GT(total, base);
  EXPECT_NEAR(bundled_model().moving_mass_kg(), total - base, 1e-9);
  EXPECT_EQ(bundled_model().with_payload(50.0).moving_mass_kg(), bundled_model().moving_mass_kg());
}

// Only a regular file is read: a device that never ends (or a FIFO that would block) is refused by
// its kind before it is opened, and so is a directory.
// Names quoted in a message are escaped: a control character would act on the user's terminal.
TEST(RobotModel, MessagesQuoteNonPrintableBytesEscaped) {
  const LoadResult r = RobotModel::load(default_urdf_path(), "", "tip\x1b[31m\a");
  EXPECT_FALSE(r.model.has_value());
  EXPECT_NE(r.error.find("tip link 'tip\\x1b[31m\\x07' is not in the URDF"), std::string::npos)
      << r.error;
}

TEST(RobotModel, LoadReadsOnlyRegularFiles) {
  const LoadResult zero = RobotModel::load("/dev/zero");
  EXPECT_FALSE(zero.model.has_value());
  EXPECT_NE(zero.error.find("'/dev/zero' is a character device, not a regular file"),
            std::string::npos)
      << zero.error;
  const LoadResult dir = RobotModel::load(::testing::TempDir());
  EXPECT_FALSE(dir.model.has_value());
  EXPECT_NE(dir.error.find("is a directory"), std::string::npos) << dir.error;
}

}  // namespace
}  // namespace fuzzypid::robot
