#include "fuzzypid/sim/certify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "fuzzypid/controller/joint_controllers.hpp"

namespace fuzzypid::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The plants one joint meets at one tick and one nominal inertia J^.
struct PlantGroup {
  double tick_s = 0.0;
  double nominal_inertia_kgm2 = 0.0;
  double inertia_min = kInf, inertia_max = 0.0;
  double damping_min = kInf, damping_max = 0.0;
};

struct GainPoint {
  pid::Gains<double> gains;
  double x = 0.0, y = 0.0;
};

// The scaled inputs of one axis of the grid: n points over [−1, 1] and the shoulders beyond.
std::vector<double> axis(std::size_t n) {
  std::vector<double> v;
  for (std::size_t k = 0; k < n; ++k)
    v.push_back(-1.0 + 2.0 * static_cast<double>(k) / static_cast<double>(n - 1));
  for (double outer : {1.5, 2.0, 3.0, 4.0, 6.0, 8.0}) {
    v.push_back(outer);
    v.push_back(-outer);
  }
  std::sort(v.begin(), v.end());
  return v;
}

// The gains each joint's controller produces at the grid's (x, y), from a fresh start.
std::optional<std::array<std::vector<GainPoint>, robot::kNumJoints>> gain_points(
    const ControllerSpec& spec, const CertifyOptions& options, std::string& error) {
  std::array<std::vector<GainPoint>, robot::kNumJoints> out;
  controller::Vector unlimited;
  unlimited.fill(kInf);
  const bool moving =
      controller::row_of(spec.family).supervisor != controller::SupervisorKind::None;
  if (!moving) {
    auto ctl = controller::JointControllers::create(spec, unlimited, error);
    if (!ctl) return std::nullopt;
    const pid::Gains<double> k = controller::pid_config(spec, kInf).gains;
    for (auto& joint : out)
      joint.push_back({k, 0.0, 0.0});
    return out;
  }
  const double dt = spec.units.tick_s;
  const double ke = spec.supervisor.error_scale, kec = spec.supervisor.error_rate_scale;
  const std::vector<double> values = axis(std::max<std::size_t>(3, options.grid_points));
  for (double x : values)
    for (double y : values) {
      const double e = ke != 0.0 ? x / ke : 0.0;
      const double ec = kec != 0.0 ? y / kec : 0.0;
      auto ctl = controller::JointControllers::create(spec, unlimited, error);
      if (!ctl) return std::nullopt;
      controller::Input in{};
      if (spec.pid.derivative == pid::DerivativeSource::Difference) {
        // The PID takes ec from successive errors: one tick at e − ec dt first.
        in.desired_position_rad.fill(e - ec * dt);
        (void)ctl->step(in, dt);
      } else {
        in.desired_velocity_rad_s.fill(ec);
      }
      in.desired_position_rad.fill(e);
      (void)ctl->step(in, dt);
      for (std::size_t i = 0; i < robot::kNumJoints; ++i)
        out[i].push_back({ctl->gains(i), x, y});
    }
  for (auto& joint : out) {
    const auto key = [](const GainPoint& p) {
      return std::make_tuple(p.gains.kp, p.gains.ki, p.gains.kd);
    };
    std::stable_sort(joint.begin(), joint.end(),
                     [&](const GainPoint& a, const GainPoint& b) { return key(a) < key(b); });
    joint.erase(
        std::unique(joint.begin(), joint.end(),
                    [&](const GainPoint& a, const GainPoint& b) { return key(a) == key(b); }),
        joint.end());
  }
  return out;
}

}  // namespace

std::optional<Certificate> certify(const ControllerSpec& controller,
                                   const std::vector<Condition>& conditions,
                                   const ExperimentSet& experiments, const CertifyOptions& options,
                                   std::string& error) {
  if (conditions.empty()) {
    error = "no conditions to certify on";
    return std::nullopt;
  }
  if (!(options.delay_s >= 0.0) || !std::isfinite(options.delay_s)) {
    error = "the delay must be finite and >= 0";
    return std::nullopt;
  }
  Certificate cert;
  cert.family = controller.family;
  cert.moving_gains =
      controller::row_of(controller.family).supervisor != controller::SupervisorKind::None;
  cert.delay_s = options.delay_s;
  cert.conditions = conditions.size();

  // The plants of each joint, grouped by tick and J^.
  std::array<std::vector<PlantGroup>, robot::kNumJoints> groups;
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    const Condition& c = conditions[k];
    const Experiment& ex = experiments.of(k);
    const robot::JointPathResult* path = ex.path(c, error);
    if (path == nullptr) return std::nullopt;
    const double h = ex.options().tick_s;
    const robot::RobotModel model = ex.plant_model(c);
    const robot::PlantConfig plant = ex.plant_config(c);
    for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
      const double nominal = ex.nominal_inertia()[i];
      auto it = std::find_if(groups[i].begin(), groups[i].end(), [&](const PlantGroup& g) {
        return g.tick_s == h && g.nominal_inertia_kgm2 == nominal;
      });
      if (it == groups[i].end()) {
        groups[i].push_back({h, nominal});
        it = groups[i].end() - 1;
      }
      for (const robot::JointVector& q : path->position_rad) {
        const double j =
            plant.inertia_scale[i] * model.inertia_diagonal(q)[i] + plant.armature_kgm2[i];
        it->inertia_min = std::min(it->inertia_min, j);
        it->inertia_max = std::max(it->inertia_max, j);
      }
      it->damping_min = std::min(it->damping_min, plant.damping_nms[i]);
      it->damping_max = std::max(it->damping_max, plant.damping_nms[i]);
    }
  }

  const auto points = gain_points(controller, options, error);
  if (!points) return std::nullopt;
  MarginOptions bulk = options.margin;
  bulk.delay_ticks = false;

  bool all_stable = true;
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    JointCertificate& jc = cert.joints[i];
    jc.inertia_min_kgm2 = kInf;
    jc.damping_min_nms = kInf;
    jc.gain_triples = (*points)[i].size();
    jc.stable = true;
    bool first = true;
    for (const PlantGroup& g : groups[i]) {
      jc.nominal_inertia_kgm2 = std::max(jc.nominal_inertia_kgm2, g.nominal_inertia_kgm2);
      jc.inertia_min_kgm2 = std::min(jc.inertia_min_kgm2, g.inertia_min);
      jc.inertia_max_kgm2 = std::max(jc.inertia_max_kgm2, g.inertia_max);
      jc.damping_min_nms = std::min(jc.damping_min_nms, g.damping_min);
      jc.damping_max_nms = std::max(jc.damping_max_nms, g.damping_max);
      std::vector<double> inertias{g.inertia_min, std::sqrt(g.inertia_min * g.inertia_max),
                                   g.inertia_max};
      inertias.erase(std::unique(inertias.begin(), inertias.end()), inertias.end());
      std::vector<double> dampings{g.damping_min, g.damping_max};
      dampings.erase(std::unique(dampings.begin(), dampings.end()), dampings.end());
      const double torque_per_u = controller.units.gains == controller::GainUnits::Acceleration
                                      ? g.nominal_inertia_kgm2
                                      : 1.0;
      for (double j : inertias)
        for (double b : dampings)
          for (const GainPoint& p : (*points)[i]) {
            JointLoop loop;
            loop.tick_s = g.tick_s;
            loop.plant_gain = torque_per_u / j;
            loop.damping_per_s = b / j;
            loop.gains = p.gains;
            loop.derivative_filter_s = controller.pid.derivative_filter_s;
            loop.derivative = controller.pid.derivative;
            set_delay(loop, options.delay_s);
            MarginCase mc{margins(loop, bulk), loop, j, b, g.tick_s, p.gains, p.x, p.y};
            ++jc.cases;
            jc.stable = jc.stable && mc.margins.stable;
            const LoopMargins& m = mc.margins;
            if (first || m.gain_margin_db < jc.worst_gain.margins.gain_margin_db)
              jc.worst_gain = mc;
            if (first || m.gain_margin_low_db > jc.worst_gain_low.margins.gain_margin_low_db)
              jc.worst_gain_low = mc;
            if (first || m.phase_margin_deg < jc.worst_phase.margins.phase_margin_deg)
              jc.worst_phase = mc;
            if (first || m.delay_margin_s < jc.worst_delay.margins.delay_margin_s)
              jc.worst_delay = mc;
            if (first || m.disk_margin < jc.worst_disk.margins.disk_margin) jc.worst_disk = mc;
            first = false;
          }
    }
    // The whole-tick delay margin of the worst delay case only (it takes eigenvalues).
    if (!first) jc.worst_delay.margins = margins(jc.worst_delay.loop, options.margin);
    all_stable = all_stable && jc.stable && jc.worst_disk.margins.disk_margin > 0.0;
  }
  cert.certified = all_stable && !cert.moving_gains;
  if (cert.moving_gains)
    cert.verdict = "not certified (frozen-gain margins only)";
  else if (!all_stable)
    cert.verdict = "not certified (unstable at frozen gains)";
  else
    cert.verdict = "certified (linear, no saturation)";
  return cert;
}

}  // namespace fuzzypid::sim
