#include "fuzzypid/sim/certify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "loop_matrix.hpp"

namespace fuzzypid::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

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
  const bool moving = controller::family_traits(spec.family).supervised();
  if (!moving) {
    auto ctl = controller::JointControllers::create(spec, unlimited, error);
    if (!ctl) return std::nullopt;
    for (std::size_t i = 0; i < robot::kNumJoints; ++i)
      out[i].push_back({controller::pid_config(spec, i, kInf).gains, 0.0, 0.0});
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

// The box of the gains the supervisor produces (continuous SI form). GainUpdate::Incremental
// accumulates its steps: it can reach anything inside the file's gain bounds.
GainBox gain_box(const ControllerSpec& spec, std::size_t joint,
                 const std::vector<GainPoint>& points) {
  GainBox box;
  const supervisor::FuzzyPidConfig<double> fc = controller::fuzzy_pid_config(spec, joint, kInf);
  if (fc.gain_update == supervisor::GainUpdate::Incremental) {
    box.low = fc.gain_min;
    box.high = fc.gain_max;
    return box;
  }
  box.low = box.high = points.front().gains;
  for (const GainPoint& p : points) {
    box.low = {std::min(box.low.kp, p.gains.kp), std::min(box.low.ki, p.gains.ki),
               std::min(box.low.kd, p.gains.kd)};
    box.high = {std::max(box.high.kp, p.gains.kp), std::max(box.high.ki, p.gains.ki),
                std::max(box.high.kd, p.gains.kd)};
  }
  return box;
}

// u in torque per unit of the controller's output: J^ with acceleration gains, 1 with torque.
double torque_per_unit(const ControllerSpec& spec, const PlantGroup& g) {
  return spec.units.gains == controller::GainUnits::Acceleration ? g.nominal_inertia_kgm2 : 1.0;
}

// The loop of joint `joint`'s plant group with the controller's PID options (its derivative
// filter as the joint runs it) and the delay; its gains, plant gain and damping are left to the
// caller.
JointLoop group_loop(const ControllerSpec& spec, std::size_t joint, const PlantGroup& g,
                     double delay_s) {
  JointLoop loop;
  loop.tick_s = g.tick_s;
  loop.derivative_filter_s = controller::pid_config(spec, joint, kInf).derivative_filter_s;
  loop.derivative = spec.pid.derivative;
  loop.observer_bandwidth_hz = spec.pid.observer_bandwidth_hz;
  loop.observer_delay_ticks = spec.pid.observer_delay_ticks;
  // The observer reads u as rad/s² (acceleration units only, validate()): c_m = 1.
  loop.observer_plant_gain = 1.0;
  loop.torque_bandwidth_hz = g.torque_bandwidth_hz;
  set_delay(loop, delay_s);
  return loop;
}

// The group's gear at inertia j (margins.hpp): the motor's share, the free resonance and its
// damping ratio. A rigid group leaves the loop rigid.
void set_gear(JointLoop& loop, const PlantGroup& g, double j) {
  if (!(g.gear_stiffness_nm_per_rad > 0.0)) return;
  const double motor = g.motor_inertia_kgm2, link = j - motor;
  const double reduced = motor * link / j;
  const double omega = std::sqrt(g.gear_stiffness_nm_per_rad / reduced);
  loop.motor_inertia_fraction = motor / j;
  loop.gear_resonance_hz = omega / (2.0 * kPi);
  loop.gear_damping_ratio = g.gear_damping_nms / (2.0 * omega * reduced);
}

// One switching loop per tick, J^ and kind of current loop (ideal or not) among a joint's plant
// groups: the ranges of their plant gains, dampings and bandwidths merged, the gains in `box`.
std::vector<SwitchingLoop> switching_loops(const ControllerSpec& spec, std::size_t joint,
                                           const std::vector<PlantGroup>& groups,
                                           const GainBox& box, double delay_s) {
  std::vector<SwitchingLoop> sets;
  std::vector<double> nominal;  // J^ of each set
  for (const PlantGroup& g : groups) {
    const double c_lo = torque_per_unit(spec, g) / g.inertia_max;
    const double c_hi = torque_per_unit(spec, g) / g.inertia_min;
    const double a_lo = g.damping_min / g.inertia_max, a_hi = g.damping_max / g.inertia_min;
    const double w = g.torque_bandwidth_hz;
    std::size_t k = 0;
    while (k < sets.size() &&
           !(sets[k].loop.tick_s == g.tick_s && nominal[k] == g.nominal_inertia_kgm2 &&
             (sets[k].torque_bandwidth_max_hz > 0.0) == (w > 0.0)))
      ++k;
    if (k == sets.size()) {
      SwitchingLoop set;
      set.loop = group_loop(spec, joint, g, delay_s);
      set.gains = box;
      set.plant_gain_min = c_lo;
      set.plant_gain_max = c_hi;
      set.damping_min_per_s = a_lo;
      set.damping_max_per_s = a_hi;
      set.torque_bandwidth_min_hz = set.torque_bandwidth_max_hz = w;
      sets.push_back(set);
      nominal.push_back(g.nominal_inertia_kgm2);
      continue;
    }
    SwitchingLoop& s = sets[k];
    s.plant_gain_min = std::min(s.plant_gain_min, c_lo);
    s.plant_gain_max = std::max(s.plant_gain_max, c_hi);
    s.damping_min_per_s = std::min(s.damping_min_per_s, a_lo);
    s.damping_max_per_s = std::max(s.damping_max_per_s, a_hi);
    s.torque_bandwidth_min_hz = std::min(s.torque_bandwidth_min_hz, w);
    s.torque_bandwidth_max_hz = std::max(s.torque_bandwidth_max_hz, w);
  }
  return sets;
}

}  // namespace

double largest_delay_s(const std::vector<Condition>& conditions) noexcept {
  double d = 0.0;
  for (const Condition& c : conditions)
    d = std::max(d, c.effects.delay_s);
  return d;
}

MarginSummary summarize(const Certificate& cert) {
  MarginSummary s;
  s.gain_margin_db = s.phase_margin_deg = s.delay_margin_ms = s.disk_margin = kInf;
  for (const JointCertificate& j : cert.joints) {
    s.gain_margin_db = std::min(s.gain_margin_db, j.worst_gain.margins.gain_margin_db);
    s.phase_margin_deg = std::min(s.phase_margin_deg, j.worst_phase.margins.phase_margin_deg);
    s.delay_margin_ms = std::min(s.delay_margin_ms, j.worst_delay.margins.delay_margin_s * 1e3);
    s.disk_margin = std::min(s.disk_margin, j.worst_disk.margins.disk_margin);
  }
  if (!std::all_of(cert.joints.begin(), cert.joints.end(),
                   [](const JointCertificate& j) { return j.stable; }))
    s = {};
  return s;
}

controller::MarginRecord margin_record(const Certificate& cert) {
  controller::MarginRecord r;
  r.delay_ms = cert.delay_s * 1e3;
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    const JointCertificate& j = cert.joints[i];
    r.gain_margin_db[i] = j.worst_gain.margins.gain_margin_db;
    r.phase_margin_deg[i] = j.worst_phase.margins.phase_margin_deg;
    r.delay_margin_ms[i] = j.worst_delay.margins.delay_margin_s * 1e3;
    r.disk_margin[i] = j.worst_disk.margins.disk_margin;
    r.inertia_min_kgm2[i] = j.inertia_min_kgm2;
    r.inertia_max_kgm2[i] = j.inertia_max_kgm2;
  }
  r.certified = cert.certified;
  r.verdict = cert.verdict;
  r.assumptions = lyapunov_assumptions();
  return r;
}

std::optional<PlantRanges> plant_ranges(const std::vector<Condition>& conditions,
                                        const std::vector<const Experiment*>& experiments,
                                        std::string& error) {
  if (conditions.empty() || experiments.size() != conditions.size()) {
    error = "no conditions to certify on";
    return std::nullopt;
  }
  PlantRanges ranges;
  ranges.conditions = conditions.size();
  auto& groups = ranges.joints;
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    const Condition& c = conditions[k];
    const Experiment& ex = *experiments[k];
    const robot::JointPathResult* path = ex.path(c, error);
    if (path == nullptr) return std::nullopt;
    const double h = ex.options().tick_s;
    const robot::RobotModel model = ex.plant_model(c);
    robot::RobotData data(model);
    const robot::PlantConfig plant = ex.plant_config(c);
    const double bandwidth = plant.torque_bandwidth_hz;
    // The gear's stiffness and damping as robot::JointPlant fixes them at reset(): from the
    // resonance and the two inertias where the run starts (or at the fixed configuration).
    const robot::JointVector reference =
        plant.fixed_configuration_rad.value_or(ex.initial_position(*path, c));
    const robot::JointVector link_diagonal = model.inertia_diagonal(reference, data);
    for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
      const double nominal = ex.nominal_inertia()[i];
      double stiffness = 0.0, gear_damping = 0.0, motor = 0.0;
      if (plant.joint_resonance_hz[i] > 0.0) {
        motor = plant.armature_kgm2[i];
        const robot::GearCoupling g =
            robot::gear_coupling(plant.joint_resonance_hz[i], plant.joint_damping_ratio, motor,
                                 plant.inertia_scale[i] * link_diagonal[i]);
        stiffness = g.stiffness_nm_per_rad;
        gear_damping = g.damping_nms;
      }
      const double own_delay = stiffness > 0.0 ? c.effects.delay_s : 0.0;
      auto it = std::find_if(groups[i].begin(), groups[i].end(), [&](const PlantGroup& g) {
        return g.tick_s == h && g.nominal_inertia_kgm2 == nominal &&
               g.torque_bandwidth_hz == bandwidth && g.gear_stiffness_nm_per_rad == stiffness &&
               g.gear_damping_nms == gear_damping && g.motor_inertia_kgm2 == motor &&
               g.delay_s == own_delay;
      });
      if (it == groups[i].end()) {
        groups[i].push_back({h, nominal, bandwidth, kInf, 0.0, kInf, 0.0, stiffness, gear_damping,
                             motor, own_delay});
        it = groups[i].end() - 1;
      }
      for (const robot::JointVector& q : path->position_rad) {
        const double j =
            plant.inertia_scale[i] * model.inertia_diagonal(q, data)[i] + plant.armature_kgm2[i];
        it->inertia_min = std::min(it->inertia_min, j);
        it->inertia_max = std::max(it->inertia_max, j);
      }
      it->damping_min = std::min(it->damping_min, plant.damping_nms[i]);
      it->damping_max = std::max(it->damping_max, plant.damping_nms[i]);
    }
  }
  return ranges;
}

std::optional<Certificate> certify(const ControllerSpec& controller,
                                   const std::vector<Condition>& conditions,
                                   const ExperimentSet& experiments, const CertifyOptions& options,
                                   std::string& error) {
  std::vector<const Experiment*> ex;
  for (std::size_t k = 0; k < conditions.size(); ++k)
    ex.push_back(&experiments.of(k));
  const auto ranges = plant_ranges(conditions, ex, error);
  if (!ranges) return std::nullopt;
  return certify(controller, *ranges, options, error);
}

std::optional<Certificate> certify(const ControllerSpec& controller, const PlantRanges& ranges,
                                   const CertifyOptions& options, std::string& error) {
  if (!(options.delay_s >= 0.0) || !std::isfinite(options.delay_s)) {
    error = "the delay must be finite and >= 0";
    return std::nullopt;
  }
  Certificate cert;
  cert.family = controller.family;
  cert.moving_gains = controller::family_traits(controller.family).supervised();
  cert.delay_s = options.delay_s;
  cert.conditions = ranges.conditions;
  const auto& groups = ranges.joints;

  const auto points = gain_points(controller, options, error);
  if (!points) return std::nullopt;
  MarginOptions bulk = options.margin;
  bulk.delay_ticks = false;

  // Joint i's certificate; it writes cert.joints[i] and reads nothing another joint writes.
  const auto certify_joint = [&](std::size_t i) {
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
      std::vector<double> delays{options.delay_s};
      if (g.gear_stiffness_nm_per_rad > 0.0 && g.delay_s != options.delay_s)
        delays.push_back(g.delay_s);
      for (double delay : delays)
        for (double j : inertias)
          for (double b : dampings) {
            JointLoop plant = group_loop(controller, i, g, delay);
            plant.plant_gain = torque_per_unit(controller, g) / j;
            plant.damping_per_s = b / j;
            set_gear(plant, g, j);
            // The plant's frequency response once; each gain triple only recombines it.
            const detail::PlantGrid grid = detail::plant_grid(plant, bulk);
            for (const GainPoint& p : (*points)[i]) {
              JointLoop loop = plant;
              loop.gains = p.gains;
              MarginCase mc{
                  detail::margins(loop, bulk, &grid), loop, j, b, g.tick_s, p.gains, p.x, p.y};
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
    }
    // The whole-tick delay margin of the worst delay case only (it takes eigenvalues).
    if (!first) jc.worst_delay.margins = margins(jc.worst_delay.loop, options.margin);

    // The gains may switch every tick inside their box, the inertia anywhere in its range.
    jc.gain_box = gain_box(controller, i, (*points)[i]);
    jc.plant_groups = groups[i].size();
    jc.lyapunov.reason = "not computed";
    if (!options.lyapunov) return;
    bool first_set = true;
    for (const SwitchingLoop& set :
         switching_loops(controller, i, groups[i], jc.gain_box, options.delay_s)) {
      const LyapunovCertificate lc = common_lyapunov(set);
      if (first_set || !lc.certified || lc.contraction > jc.lyapunov.contraction) jc.lyapunov = lc;
      first_set = false;
      if (!lc.certified) break;  // the joint is not certified: the first failing set says why
    }
    jc.certified = jc.stable && jc.worst_disk.margins.disk_margin > 0.0 && jc.lyapunov.certified;
  };
  if (options.for_each_joint)
    options.for_each_joint(robot::kNumJoints, certify_joint);
  else
    for (std::size_t i = 0; i < robot::kNumJoints; ++i)
      certify_joint(i);
  const bool all_stable = std::all_of(
      cert.joints.begin(), cert.joints.end(),
      [](const JointCertificate& j) { return j.stable && j.worst_disk.margins.disk_margin > 0.0; });
  std::string failing;
  for (std::size_t i = 0; i < robot::kNumJoints && failing.empty(); ++i)
    if (!cert.joints[i].lyapunov.certified)
      failing = "joint " + std::to_string(i + 1) + ": " + cert.joints[i].lyapunov.reason;
  cert.certified = all_stable && options.lyapunov && failing.empty();
  if (!all_stable)
    cert.verdict = "not certified (unstable at frozen gains)";
  else if (!options.lyapunov)
    cert.verdict = "not certified (frozen-gain margins only)";
  else if (!failing.empty())
    cert.verdict = "not certified (" + failing + ")";
  else
    cert.verdict = "certified (linear, no saturation; gains may change every tick)";
  return cert;
}

}  // namespace fuzzypid::sim
