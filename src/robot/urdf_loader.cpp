// RobotModel::load and default_urdf_path: URDF (urdfdom) -> KDL tree -> KDL chain, checked.
//
// The URDF -> KDL conversion follows the conventions of ROS's kdl_parser (which needs ROS and is
// not used): a joint's origin becomes the segment's tip frame, its axis is expressed in the parent
// link frame, and a link's inertia is moved from its inertial frame to the link frame.
#include "robot_model_impl.hpp"

#include <sys/stat.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <mutex>
#include <utility>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>
#include <Eigen/Eigenvalues>
#include <kdl/tree.hpp>

#include "fuzzypid_support/bounded_read.hpp"
#include "fuzzypid_support/printable.hpp"
#include "fuzzypid_support/utf8.hpp"

#ifndef FUZZYPID_URDF_SOURCE_DIR
#define FUZZYPID_URDF_SOURCE_DIR ""
#endif
#ifndef FUZZYPID_URDF_INSTALL_DIR
#define FUZZYPID_URDF_INSTALL_DIR ""
#endif

namespace fuzzypid::robot {
namespace {

constexpr const char* kDefaultUrdfName = "er50_c20.urdf";
constexpr double kInf = std::numeric_limits<double>::infinity();
// Largest URDF read (the bundled one is 9 kB; meshes are separate files).
constexpr std::size_t kMaxUrdfBytes = 16u << 20;
// The largest |lower| or |upper| of a revolute joint, rad: two turns (a joint limit of 180 written
// in degrees is refused instead of loading and failing later as an unrelated IK error).
constexpr double kMaxRevoluteLimitRad = 4.0 * 3.14159265358979323846;

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

bool file_exists(const std::string& path) {
  struct stat st {};
  return !path.empty() && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

// Collects urdfdom's console_bridge messages during one parse, so that load() can return them
// instead of letting them go to stderr. console_bridge's handler is process-global: the mutex
// serialises concurrent loads.
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_WARN) return;
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors = true;
    if (!messages.empty()) messages += "; ";
    messages += text;
  }
  std::string messages;
  bool errors = false;
};

std::mutex& parse_mutex() {
  static std::mutex m;
  return m;
}

// urdfdom reports some malformed elements (e.g. an unparsable <mass>) as errors yet returns a model
// without them: any error-level message therefore fails the parse here.
urdf::ModelInterfaceSharedPtr parse_captured(const std::string& xml, std::string& messages) {
  std::lock_guard<std::mutex> lock(parse_mutex());
  CapturingHandler handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    handler.messages += std::string(handler.messages.empty() ? "" : "; ") + e.what();
    model.reset();
  } catch (...) {
    handler.messages += "unknown exception in the URDF parser";
    model.reset();
  }
  console_bridge::restorePreviousOutputHandler();
  messages = handler.messages;
  if (handler.errors) model.reset();
  return model;
}

KDL::Vector to_kdl(const urdf::Vector3& v) {
  return KDL::Vector(v.x, v.y, v.z);
}

KDL::Frame to_kdl(const urdf::Pose& p) {
  return KDL::Frame(
      KDL::Rotation::Quaternion(p.rotation.x, p.rotation.y, p.rotation.z, p.rotation.w),
      to_kdl(p.position));
}

// Returns false (and a reason) for joint types the arm model does not support.
bool to_kdl(const urdf::Joint& joint, KDL::Joint& out, std::string& error) {
  const KDL::Frame origin = to_kdl(joint.parent_to_joint_origin_transform);
  switch (joint.type) {
    case urdf::Joint::FIXED:
      out = KDL::Joint(joint.name, KDL::Joint::None);
      return true;
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS:
      out = KDL::Joint(joint.name, origin.p, origin.M * to_kdl(joint.axis), KDL::Joint::RotAxis);
      return true;
    default:
      error = "joint '" + joint.name +
              "' has a type other than revolute, continuous or fixed (unsupported)";
      return false;
  }
}

KDL::RigidBodyInertia to_kdl(const urdf::InertialSharedPtr& inertial) {
  if (!inertial) return KDL::RigidBodyInertia::Zero();
  const KDL::Frame origin = to_kdl(inertial->origin);
  // URDF gives the tensor about the center of mass in the inertial frame; KDL wants it about the
  // center of mass in the link frame. Rotating a zero-mass body at the origin does exactly that.
  const KDL::RotationalInertia in_inertial_frame(inertial->ixx, inertial->iyy, inertial->izz,
                                                 inertial->ixy, inertial->ixz, inertial->iyz);
  const KDL::RigidBodyInertia rotated =
      origin.M * KDL::RigidBodyInertia(0.0, KDL::Vector::Zero(), in_inertial_frame);
  return KDL::RigidBodyInertia(inertial->mass, origin.p, rotated.getRotationalInertia());
}

bool add_children(const urdf::LinkConstSharedPtr& link, KDL::Tree& tree, std::string& error) {
  for (const urdf::LinkSharedPtr& child : link->child_links) {
    if (!child->parent_joint) {
      error = "link '" + child->name + "' has no parent joint";
      return false;
    }
    KDL::Joint joint;
    if (!to_kdl(*child->parent_joint, joint, error)) return false;
    const KDL::Segment segment(child->name, joint,
                               to_kdl(child->parent_joint->parent_to_joint_origin_transform),
                               to_kdl(child->inertial));
    if (!tree.addSegment(segment, link->name)) {
      error = "KDL rejected segment '" + child->name + "'";
      return false;
    }
    if (!add_children(child, tree, error)) return false;
  }
  return true;
}

bool finite(const urdf::Vector3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite(const urdf::Pose& p) {
  return finite(p.position) && std::isfinite(p.rotation.x) && std::isfinite(p.rotation.y) &&
         std::isfinite(p.rotation.z) && std::isfinite(p.rotation.w);
}

// The physical sense of a link's <inertial>: a finite, non-negative mass and a finite inertia
// tensor that is zero (a point mass) or positive definite with principal moments satisfying the
// triangle inequality (each at most the sum of the other two). Empty when sane, else the reason.
std::string check_inertial(const urdf::Link& link) {
  const urdf::InertialSharedPtr& in = link.inertial;
  if (!in) return {};
  const std::string where = "link '" + link.name + "': <inertial>";
  if (!std::isfinite(in->mass) || in->mass < 0.0)
    return where + " <mass> must be finite and non-negative, got " + std::to_string(in->mass);
  if (!finite(in->origin)) return where + " <origin> is not finite";
  Eigen::Matrix3d tensor;
  tensor << in->ixx, in->ixy, in->ixz, in->ixy, in->iyy, in->iyz, in->ixz, in->iyz, in->izz;
  if (!tensor.allFinite()) return where + " <inertia> is not finite";
  if (tensor.isZero(0.0)) return {};
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(tensor, Eigen::EigenvaluesOnly)
          .eigenvalues();  // ascending
  const double tolerance = 1e-12 * moments.cwiseAbs().maxCoeff();
  if (!(moments[0] > tolerance))
    return where + " <inertia> is not positive definite (smallest principal moment " +
           std::to_string(moments[0]) + " kg m^2)";
  if (moments[2] > moments[0] + moments[1] + tolerance)
    return where + " <inertia> violates the triangle inequality: principal moments " +
           std::to_string(moments[0]) + ", " + std::to_string(moments[1]) + ", " +
           std::to_string(moments[2]) + " kg m^2";
  return {};
}

// A joint the model can use: a finite origin, a non-zero finite axis on a moving joint, limits
// that are numbers with non-negative velocity and effort, and no <mimic> (a coupled joint would be
// silently treated as independent).
std::string check_joint(const urdf::Joint& joint) {
  const std::string where = "joint '" + joint.name + "'";
  if (!finite(joint.parent_to_joint_origin_transform)) return where + ": <origin> is not finite";
  if (joint.type != urdf::Joint::FIXED && joint.type != urdf::Joint::FLOATING) {
    const urdf::Vector3& a = joint.axis;
    const double norm = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    if (!finite(a) || !(norm > 1e-9))
      return where + ": <axis> must be a finite non-zero vector, got (" + std::to_string(a.x) +
             ", " + std::to_string(a.y) + ", " + std::to_string(a.z) + ")";
  }
  if (joint.limits) {
    const urdf::JointLimits& l = *joint.limits;
    if (std::isnan(l.lower) || std::isnan(l.upper))
      return where + ": <limit> lower/upper is not a number";
    if (std::isnan(l.velocity) || l.velocity < 0.0)
      return where + ": <limit> velocity must be non-negative, got " + std::to_string(l.velocity);
    if (std::isnan(l.effort) || l.effort < 0.0)
      return where + ": <limit> effort must be non-negative, got " + std::to_string(l.effort);
  }
  if (joint.mimic)
    return where + ": <mimic> (joint '" + joint.mimic->joint_name +
           "') is not supported: coupled joints cannot be modelled";
  return {};
}

// Every link and joint of the document, in name order: the first problem found, or empty.
std::string check_model(const urdf::ModelInterface& model) {
  for (const auto& [name, link] : model.links_) {
    if (!link) continue;
    if (std::string e = check_inertial(*link); !e.empty()) return e;
  }
  for (const auto& [name, joint] : model.joints_) {
    if (!joint) continue;
    if (std::string e = check_joint(*joint); !e.empty()) return e;
  }
  return {};
}

// The message quotes names and text from the URDF (or the caller): bytes a terminal would act on
// are escaped (\xHH), never printed raw.
LoadResult fail(const std::string& message) {
  LoadResult r;
  r.error = support::printable(message);
  return r;
}

}  // namespace

std::string default_urdf_path() {
  if (const char* env = std::getenv("FUZZYPID_URDF"); env != nullptr && env[0] != '\0') return env;
  std::string source = std::string(FUZZYPID_URDF_SOURCE_DIR) + "/" + kDefaultUrdfName;
  if (file_exists(source)) return source;
  std::string installed = std::string(FUZZYPID_URDF_INSTALL_DIR) + "/" + kDefaultUrdfName;
  if (file_exists(installed)) return installed;
  return source;  // loading it reports the missing file by name
}

LoadResult RobotModel::load(const std::string& urdf_path, const std::string& root_link,
                            const std::string& tip_link) {
  try {
    std::string text;
    std::string read_error;
    if (!support::read_file_bounded(urdf_path, kMaxUrdfBytes, text, read_error))
      return fail("URDF: " + read_error);

    // urdfdom hands the text to TinyXML 2.6, which steps over a multi-byte character by its lead
    // byte's length alone: a lead byte whose continuation bytes are missing at the end of the text
    // made it read past the buffer (found by fuzz_urdf, docs/robustness.md). Refusing malformed
    // UTF-8 first keeps every sequence it steps over whole.
    if (const std::size_t bad = support::first_invalid_utf8(text); bad != std::string::npos) {
      char where[96];
      std::snprintf(where, sizeof where, "byte %zu (0x%02X) is not part of a UTF-8 character", bad,
                    static_cast<unsigned>(static_cast<unsigned char>(text[bad])));
      return fail("'" + urdf_path + "' is not UTF-8 text: " + where);
    }
    std::string messages;
    const urdf::ModelInterfaceSharedPtr urdf_model = parse_captured(text, messages);
    if (!urdf_model) {
      return fail("'" + urdf_path + "' is not a valid URDF" +
                  (messages.empty() ? std::string() : ": " + messages));
    }
    if (std::string invalid = check_model(*urdf_model); !invalid.empty())
      return fail("'" + urdf_path + "': " + invalid);
    const urdf::LinkConstSharedPtr urdf_root = urdf_model->getRoot();
    if (!urdf_root) return fail("'" + urdf_path + "' has no root link");

    KDL::Tree tree(urdf_root->name);
    std::string error;
    if (!add_children(urdf_root, tree, error)) return fail("'" + urdf_path + "': " + error);

    const std::string root = root_link.empty() ? urdf_root->name : root_link;
    if (!urdf_model->getLink(root)) return fail("root link '" + root + "' is not in the URDF");
    std::string tip = tip_link;
    if (tip.empty()) {
      urdf::LinkConstSharedPtr link = urdf_model->getLink(root);
      // Every walk below is bounded by the number of links, so even a cyclic model that slipped
      // past urdfdom and KDL could not make the loader loop forever.
      std::size_t steps = 0;
      while (!link->child_links.empty()) {
        if (++steps > urdf_model->links_.size()) return fail("the URDF's link tree has a cycle");
        if (link->child_links.size() > 1) {
          return fail("the URDF branches at link '" + link->name +
                      "'; name the tip link explicitly");
        }
        link = link->child_links.front();
      }
      tip = link->name;
    } else if (!urdf_model->getLink(tip)) {
      return fail("tip link '" + tip + "' is not in the URDF");
    }

    ChainDescription desc;
    desc.robot_name = urdf_model->getName();
    desc.root_link = root;
    desc.tip_link = tip;
    if (!tree.getChain(root, tip, desc.chain)) {
      return fail("no chain from root link '" + root + "' to tip link '" + tip + "'");
    }
    // KDL's getChain also walks up the tree; require tip to lie below root, as an arm does.
    std::size_t steps = 0;
    for (urdf::LinkConstSharedPtr link = urdf_model->getLink(tip);; link = link->getParent()) {
      if (link->name == root) break;
      if (++steps > urdf_model->links_.size()) return fail("the URDF's link tree has a cycle");
      if (!link->getParent()) {
        return fail("tip link '" + tip + "' is not below root link '" + root + "'");
      }
    }
    if (desc.chain.getNrOfJoints() != kNumJoints) {
      return fail("the chain '" + root + "' -> '" + tip + "' has " +
                  std::to_string(desc.chain.getNrOfJoints()) + " movable joints, expected " +
                  std::to_string(kNumJoints));
    }

    // Per moving joint: the limits, and whether any mass or inertia lies below it (the links of
    // its segment and of every later one). A joint that moves nothing has zero inertia, and the
    // plant's J theta'' = tau would divide by it at the first tick.
    std::array<std::size_t, kNumJoints> first_segment{};
    std::size_t j = 0;
    for (std::size_t k = 0; k < desc.chain.segments.size(); ++k) {
      const KDL::Segment& segment = desc.chain.segments[k];
      if (segment.getJoint().getType() == KDL::Joint::None) continue;
      first_segment[j] = k;
      const std::string& name = segment.getJoint().getName();
      const urdf::JointConstSharedPtr joint = urdf_model->getJoint(name);
      desc.joint_names[j] = name;
      desc.lower[j] = -kInf;
      desc.upper[j] = kInf;
      desc.velocity[j] = kInf;
      desc.effort[j] = kInf;
      desc.continuous[j] = joint && joint->type == urdf::Joint::CONTINUOUS;
      if (joint && joint->limits) {
        if (joint->type == urdf::Joint::REVOLUTE) {
          desc.lower[j] = joint->limits->lower;
          desc.upper[j] = joint->limits->upper;
          if (!(desc.lower[j] <= desc.upper[j])) {
            return fail("joint '" + name + "' has lower limit above upper limit");
          }
          // Limits are radians; a bound beyond two turns is almost surely written in degrees.
          for (const auto& [which, v] : {std::pair<const char*, double>{"lower", desc.lower[j]},
                                         std::pair<const char*, double>{"upper", desc.upper[j]}})
            if (std::fabs(v) > kMaxRevoluteLimitRad)
              return fail("'" + urdf_path + "': joint '" + name + "': <limit> " + which + "=\"" +
                          number(v) + "\" rad is beyond two turns (+-" +
                          number(kMaxRevoluteLimitRad) +
                          " rad): URDF limits are radians, not degrees");
        }
        // URDF uses 0 for "not given" in velocity and effort: no limit, said once at load.
        if (joint->limits->velocity > 0.0) {
          desc.velocity[j] = joint->limits->velocity;
        } else {
          desc.notes.push_back("joint '" + name +
                               "': <limit> velocity=\"0\" means no limit: the path's speed is "
                               "not checked against it");
        }
        if (joint->limits->effort > 0.0) {
          desc.effort[j] = joint->limits->effort;
        } else {
          desc.notes.push_back("joint '" + name +
                               "': <limit> effort=\"0\" means no limit: its torque is never "
                               "clamped (torque_limit = 0 conditions run unclamped)");
        }
      }
      ++j;
    }
    for (std::size_t k = first_segment[0]; k < desc.chain.segments.size(); ++k)
      desc.moving_mass_kg += desc.chain.segments[k].getInertia().getMass();
    for (std::size_t m = 0; m < kNumJoints; ++m) {
      bool moves_inertia = false;
      for (std::size_t k = first_segment[m]; k < desc.chain.segments.size(); ++k) {
        const KDL::RigidBodyInertia in = desc.chain.segments[k].getInertia();
        const KDL::RotationalInertia rotational = in.getRotationalInertia();
        const Eigen::Map<const Eigen::Matrix3d> tensor(rotational.data);
        if (in.getMass() > 0.0 || !tensor.isZero(0.0)) moves_inertia = true;
      }
      if (!moves_inertia)
        return fail("'" + urdf_path + "': no inertia moves with joint " + std::to_string(m + 1) +
                    " ('" + desc.joint_names[m] + "'): link '" +
                    desc.chain.segments[first_segment[m]].getName() +
                    "' and the links below it have no <inertial> (or zero mass and inertia)");
    }
    return LoadResult{RobotModel(std::make_unique<Impl>(std::move(desc))), {}};
  } catch (const std::exception& e) {
    return fail("loading '" + urdf_path + "' failed: " + e.what());
  } catch (...) {
    return fail("loading '" + urdf_path + "' failed");
  }
}

}  // namespace fuzzypid::robot
