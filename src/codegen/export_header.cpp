#include "fuzzypid/codegen/export_header.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include "export_rule_base.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"

namespace fuzzypid::codegen {

using namespace controller;

namespace {}  // namespace

namespace {

std::string lit(double v) {
  return scalar_literal(v);
}

// What a family's header_code cannot write itself (families.hpp).
struct CodeWriter {
  [[nodiscard]] std::string literal(double v) const { return scalar_literal(v); }
  [[nodiscard]] std::string rule_base(const fuzzy::EngineModel<double>& model,
                                      const std::string& rule_file) const {
    return export_rule_base(model, rule_file);
  }
};

// An exact double literal: hexadecimal, or the infinity of <limits>.
std::string double_literal(double v) {
  if (std::isinf(v))
    return std::string(v < 0 ? "-" : "") + "std::numeric_limits<double>::infinity()";
  char b[64];
  std::snprintf(b, sizeof b, "%a", v);
  return b;
}

// Six doubles as a braced initialiser of exact literals.
std::string six_doubles(const std::array<double, 6>& v) {
  std::string t = "{";
  for (std::size_t i = 0; i < v.size(); ++i)
    t += (i == 0 ? "" : ", ") + double_literal(v[i]);
  return t + "}";
}

std::string gains(const pid::Gains<double>& g) {
  return "{" + lit(g.kp) + ", " + lit(g.ki) + ", " + lit(g.kd) + "}";
}

std::string comment_safe(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

// The body of a C++ string literal holding `s` (one line).
std::string literal_safe(const std::string& s) {
  std::string out;
  for (char c : comment_safe(s)) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

const char* enum_code(pid::DerivativeSource d) {
  switch (d) {
    case pid::DerivativeSource::Rates:
      return "fuzzypid::pid::DerivativeSource::Rates";
    case pid::DerivativeSource::Difference:
      return "fuzzypid::pid::DerivativeSource::Difference";
    case pid::DerivativeSource::Observer:
      return "fuzzypid::pid::DerivativeSource::Observer";
  }
  return "";
}
const char* enum_code(pid::DerivativeOn d) {
  return d == pid::DerivativeOn::Error ? "fuzzypid::pid::DerivativeOn::Error"
                                       : "fuzzypid::pid::DerivativeOn::Measurement";
}
const char* enum_code(pid::AntiWindup a) {
  switch (a) {
    case pid::AntiWindup::None:
      return "fuzzypid::pid::AntiWindup::None";
    case pid::AntiWindup::Clamping:
      return "fuzzypid::pid::AntiWindup::Clamping";
    case pid::AntiWindup::BackCalculation:
      return "fuzzypid::pid::AntiWindup::BackCalculation";
  }
  return "fuzzypid::pid::AntiWindup::Clamping";
}

}  // namespace

namespace {

// C++20 keywords (a superset of C++17's), alternative tokens, and identifiers with a special
// meaning in some places.
constexpr std::array<std::string_view, 109> kRefusedNames = {
    "alignas", "alignof", "asm", "auto", "bool", "break", "case", "catch", "char", "char8_t",
    "char16_t", "char32_t", "class", "concept", "const", "consteval", "constexpr", "constinit",
    "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
    "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false",
    "float", "for", "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new",
    "noexcept", "nullptr", "operator", "private", "protected", "public", "register",
    "reinterpret_cast", "requires", "return", "short", "signed", "sizeof", "static",
    "static_assert", "static_cast", "struct", "switch", "template", "this", "thread_local", "throw",
    "true", "try", "typedef", "typeid", "typename", "union", "unsigned", "using", "virtual", "void",
    "volatile", "wchar_t", "while",
    // alternative tokens
    "and", "and_eq", "bitand", "bitor", "compl", "not", "not_eq", "or", "or_eq", "xor", "xor_eq",
    // special identifiers, reserved or used by the generated code
    "final", "override", "import", "module", "std", "posix", "main", "fuzzypid",
    // lower-case macros of the C and POSIX headers, and of GNU mode (-std=gnu++17)
    "errno", "assert", "offsetof", "stdin", "stdout", "stderr", "linux", "unix", "i386"};

bool is_identifier_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

std::string check_part(std::string_view part, bool global) {
  const std::string name(part);
  if (part.empty()) return "an empty name";
  if (part[0] >= '0' && part[0] <= '9') return "'" + name + "' starts with a digit";
  for (char c : part)
    if (!is_identifier_char(c))
      return "'" + name + "' is not a C++ identifier (letters, digits, _)";
  if (part.find("__") != std::string_view::npos)
    return "'" + name + "' contains '__' (reserved to the implementation)";
  if (part[0] == '_' && part.size() > 1 && part[1] >= 'A' && part[1] <= 'Z')
    return "'" + name + "' starts with '_' and a capital (reserved to the implementation)";
  if (part[0] == '_' && global)
    return "'" + name + "' starts with '_' at global scope (reserved to the implementation)";
  if (std::find(kRefusedNames.begin(), kRefusedNames.end(), part) != kRefusedNames.end())
    return "'" + name + "' is a C++ keyword or a reserved, standard or macro name";
  if (std::none_of(part.begin(), part.end(), [](char c) { return c >= 'a' && c <= 'z'; }))
    return "'" + name + "' has no lower-case letter (such names are left to macros)";
  return {};
}

}  // namespace

std::string check_namespace(const std::string& ns) {
  if (ns.empty()) return "the namespace is empty";
  if (ns.size() > 512) return "the namespace is longer than 512 characters";
  std::string_view rest(ns);
  bool global = true;
  for (;;) {
    const std::size_t sep = rest.find("::");
    const std::string bad = check_part(rest.substr(0, sep), global);
    if (!bad.empty()) return "namespace '" + ns + "': " + bad;
    if (sep == std::string_view::npos) return {};
    rest.remove_prefix(sep + 2);
    global = false;
  }
}

std::string check_float_range(const ControllerSpec& spec) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::pair<const char*, double>> values;
  const FamilyTraits& traits = family_traits(spec.family);
  for (std::size_t joint = 0; joint < kSpecJoints; ++joint) {  // each joint's bandwidth scale
    const pid::Config<double> pc = pid_config(spec, joint, inf);
    values.insert(values.end(), {{"the PID's kp", pc.gains.kp},
                                 {"the PID's ki", pc.gains.ki},
                                 {"the PID's kd", pc.gains.kd},
                                 {"derivative_filter_s", pc.derivative_filter_s},
                                 {"observer_bandwidth_hz", pc.observer_bandwidth_hz}});
    if (!traits.supervised()) continue;
    const supervisor::FuzzyPidConfig<double> fc = fuzzy_pid_config(spec, joint, inf);
    values.insert(values.end(), {{"error_scale", fc.error_scale},
                                 {"error_rate_scale", fc.error_rate_scale},
                                 {"output_scale (kp)", fc.output_scale[0]},
                                 {"output_scale (ki)", fc.output_scale[1]},
                                 {"output_scale (kd)", fc.output_scale[2]},
                                 {"gain_min kp", fc.gain_min.kp},
                                 {"gain_min ki", fc.gain_min.ki},
                                 {"gain_min kd", fc.gain_min.kd},
                                 {"gain_max kp", fc.gain_max.kp},
                                 {"gain_max ki", fc.gain_max.ki},
                                 {"gain_max kd", fc.gain_max.kd}});
  }
  if (traits.rule_table) {
    // The table's cells and centers are written as float literals too: 1e300 would not compile.
    static constexpr const char* kGain[3] = {"kp", "ki", "kd"};
    static constexpr const char* kSet[7] = {"NB", "NM", "NS", "ZO", "PS", "PM", "PB"};
    const RuleTableSpec& t = spec.supervisor.rule_table;
    for (std::size_t g = 0; g < 3; ++g)
      for (std::size_t i = 0; i < RuleTableSpec::kSets; ++i)
        for (std::size_t j = 0; j < RuleTableSpec::kSets; ++j)
          if (std::fabs(t.ratio[g][i][j]) > static_cast<double>(FLT_MAX)) {
            char buf[200];
            std::snprintf(buf, sizeof buf,
                          "rule_table %s[%zu][%zu] (e %s, ec %s) is %.17g, which is not finite as "
                          "a float (|x| <= %g): the header would not compile",
                          kGain[g], i, j, kSet[i], kSet[j], t.ratio[g][i][j],
                          static_cast<double>(FLT_MAX));
            return buf;
          }
    for (const auto* centers : {&t.error_centers, &t.error_rate_centers})
      for (const double c : *centers)
        if (std::fabs(c) > static_cast<double>(FLT_MAX)) {
          char buf[160];
          std::snprintf(buf, sizeof buf,
                        "rule_table %s center %.17g is not finite as a float (|x| <= %g)",
                        centers == &t.error_centers ? "error" : "error_rate", c,
                        static_cast<double>(FLT_MAX));
          return buf;
        }
  }
  if (spec.supervisor.rule_model != nullptr)
    if (std::string bad = check_rule_base_float_range(*spec.supervisor.rule_model); !bad.empty())
      return bad;
  for (const auto& [name, v] : values) {
    if (std::isnan(v) || (std::isfinite(v) && std::fabs(v) > static_cast<double>(FLT_MAX))) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "%s is %.17g in SI units, which is not finite as a float (|x| <= %g): the "
                    "float controller would get an infinite value",
                    name, v, static_cast<double>(FLT_MAX));
      return buf;
    }
  }
  return {};
}

std::string export_header(const ControllerSpec& spec, const std::string& ns,
                          const std::string& source, const PlantRecord* plant,
                          const MarginRecord* margins) {
  const double inf = std::numeric_limits<double>::infinity();
  const pid::Config<double> pc = pid_config(spec, 0, inf);
  // With a bandwidth scale per joint the configuration functions take the joint (0 .. 5) and
  // give each its own gains; without, one configuration serves every joint.
  const bool per_joint = spec.bandwidth_scale != kUniformBandwidth;
  const std::string joint_param = per_joint ? "std::size_t joint, " : "";
  const std::string joint_arg = per_joint ? "joint, " : "";
  std::string h;
  h += "// Generated by `fuzzypid export-header` from " + comment_safe(source) + "; do not edit.\n";
  if (!spec.description.empty()) h += "// " + comment_safe(spec.description) + "\n";
  h += "// Family " + std::string(to_string(spec.family)) +
       "; the file's units: " + to_string(spec.units.gains) + " gains, " +
       to_string(spec.units.form) + " at " + format_double(spec.units.tick_s) +
       " s. Below: the continuous-time SI configuration fuzzypid builds from the file, as\n"
       "// exact hexadecimal literals (the double controller equals the file's bit for bit).\n";
  if (spec.units.gains == GainUnits::Acceleration)
    h +=
        "// The output u is an acceleration (rad/s^2): apply the torque J^_i u_i with the joint's\n"
        "// nominal inertia J^_i; pass output_limit in rad/s^2.\n";
  if (spec.feedforward.gravity)
    h +=
        "// Gravity feed-forward ([feedforward] gravity = true): this header holds the feedback\n"
        "// part only. Each tick the target must add g^_i(q_desired) to joint i's torque, in N·m:\n"
        "// the gravity torque of its nominal rigid-body model (no payload) at the reference\n"
        "// angles, e.g. from a recursive Newton-Euler pass with zero velocity "
        "(kGravityFeedforward).\n";
  h += per_joint ? "#pragma once\n\n#include <cstddef>\n#include <limits>\n\n"
                 : "#pragma once\n\n#include <limits>\n\n";
  h += "#include \"fuzzypid/pid/pid.hpp\"\n";
  const SupervisorCode supervisor = with_family(
      spec.family,
      [&spec](auto family) { return decltype(family)::header_code(spec, CodeWriter{}); },
      SupervisorCode{});
  h += supervisor.includes;
  h += "\nnamespace " + ns + " {\n\n";
  h += "inline constexpr const char* kFamily = \"" + std::string(to_string(spec.family)) + "\";\n";
  h += "inline constexpr double kTickS = " + double_literal(spec.units.tick_s) +
       ";  // the tick the file's gains refer to\n";
  h += std::string("inline constexpr bool kGravityFeedforward = ") +
       (spec.feedforward.gravity ? "true" : "false") +
       ";  // add g^(q_desired), N·m, to the torque\n\n";
  if (plant != nullptr) {
    const bool acceleration = spec.units.gains == GainUnits::Acceleration;
    std::array<double, 6> output_limit = plant->torque_limit_nm;
    if (acceleration)
      for (std::size_t i = 0; i < output_limit.size(); ++i)
        output_limit[i] = plant->torque_limit_nm[i] / plant->nominal_inertia_kgm2[i];
    h += "// The plant the command was simulated on: " + plant->robot + ".\n";
    h += acceleration ? "// Apply tau_i = kNominalInertiaKgm2[i] * u_i and clamp |tau_i| <= "
                        "kTorqueLimitNm[i] to get\n// the simulated torque.\n"
                      : "// u_i is the torque; clamp |u_i| <= kTorqueLimitNm[i].\n";
    h += "inline constexpr double kNominalInertiaKgm2[6] = " +
         six_doubles(plant->nominal_inertia_kgm2) + ";  // J^_i, kg·m²\n";
    h += "inline constexpr double kTorqueLimitNm[6] = " + six_doubles(plant->torque_limit_nm) +
         ";  // N·m\n";
    h += std::string("inline constexpr double kOutputLimit[6] = ") + six_doubles(output_limit) +
         (acceleration ? ";  // rad/s^2: the output_limit of joint i\n\n"
                       : ";  // N·m: the output_limit of joint i\n\n");
  }
  if (margins != nullptr) {
    // Margins are written in decimal (they are read by people, not used as gains); +inf (no
    // crossover) as the infinity of <limits>.
    const auto six = [](const MarginRecord::PerJoint& v) {
      std::string t = "{";
      for (std::size_t i = 0; i < v.size(); ++i) {
        char b[64];
        if (std::isinf(v[i]))
          std::snprintf(b, sizeof b, "%sstd::numeric_limits<double>::infinity()",
                        v[i] < 0 ? "-" : "");
        else
          std::snprintf(b, sizeof b, "%.6g", v[i]);
        t += (i == 0 ? "" : ", ") + std::string(b);
      }
      return t + "}";
    };
    h += "// Stability margins of each joint's linear loop (`fuzzypid certify`, docs/margins.md),\n"
         "// the worst case over " +
         comment_safe(margins->conditions) + " [" + comment_safe(margins->set) + "] with " +
         format_double(margins->delay_ms) +
         " ms of delay: frozen-gain margins at every\n"
         "// gain triple the controller produces over the joint's inertia range, and the "
         "certificate for\n// gains that change every tick.\n";
    h += "// Verdict: " + comment_safe(margins->verdict) + ".\n";
    h += "// Assumptions: " + comment_safe(margins->assumptions) + ".\n";
    h += "inline constexpr double kGainMarginDb[6] = " + six(margins->gain_margin_db) + ";\n";
    h += "inline constexpr double kPhaseMarginDeg[6] = " + six(margins->phase_margin_deg) + ";\n";
    h += "inline constexpr double kDelayMarginMs[6] = " + six(margins->delay_margin_ms) + ";\n";
    h += "inline constexpr double kDiskMargin[6] = " + six(margins->disk_margin) +
         ";  // alpha (balanced)\n";
    h += "inline constexpr double kCertifiedInertiaMinKgm2[6] = " + six(margins->inertia_min_kgm2) +
         ";\n";
    h += "inline constexpr double kCertifiedInertiaMaxKgm2[6] = " + six(margins->inertia_max_kgm2) +
         ";\n";
    h += std::string("inline constexpr bool kCertified = ") +
         (margins->certified ? "true" : "false") + ";\n";
    h += "inline constexpr const char* kCertificate = \"" + literal_safe(margins->verdict) +
         "\";\n\n";
  }
  if (per_joint) {
    h += "// Joint i runs the file's loop kBandwidthScale[i] times faster: its gains are Kp s^2,\n"
         "// Ki s^3, Kd s and its derivative filter Tf / s (docs/tuning.md), as written below.\n";
    h += "inline constexpr double kBandwidthScale[6] = " + six_doubles(spec.bandwidth_scale) +
         ";\n\n";
    h +=
        "// The inner PID of joint `joint` (0 .. 5; any other joint gets NaN gains, which the PID\n"
        "// refuses with Status::InvalidConfig); |u| <= output_limit.\n";
  } else {
    h += "// The inner PID; |u| <= output_limit.\n";
  }
  h += "template <class Scalar>\nconstexpr fuzzypid::pid::Config<Scalar> pid_config(" +
       joint_param + "Scalar output_limit) noexcept {\n";
  h += "  fuzzypid::pid::Config<Scalar> c;\n";
  if (per_joint) {
    h += "  switch (joint) {\n";
    for (std::size_t i = 0; i < kSpecJoints; ++i) {
      const pid::Config<double> pj = pid_config(spec, i, inf);
      h += "    case " + std::to_string(i) + ":\n";
      h += "      c.gains = " + gains(pj.gains) + ";\n";
      h += "      c.derivative_filter_s = " + lit(pj.derivative_filter_s) + ";\n";
      h += "      break;\n";
    }
    h += "    default:\n";
    h += "      c.gains.kp = c.gains.ki = c.gains.kd = "
         "std::numeric_limits<Scalar>::quiet_NaN();\n";
    h += "  }\n";
  } else {
    h += "  c.gains = " + gains(pc.gains) + ";\n";
  }
  h += "  c.derivative_on = " + std::string(enum_code(pc.derivative_on)) + ";\n";
  h += "  c.derivative_source = " + std::string(enum_code(pc.derivative_source)) + ";\n";
  if (!per_joint) h += "  c.derivative_filter_s = " + lit(pc.derivative_filter_s) + ";\n";
  if (pc.derivative_source == pid::DerivativeSource::Observer) {
    h += "  c.observer_bandwidth_hz = " + lit(pc.observer_bandwidth_hz) + ";\n";
    h += "  c.observer_delay_ticks = " + std::to_string(pc.observer_delay_ticks) + ";\n";
  }
  h += "  c.anti_windup = " + std::string(enum_code(pc.anti_windup)) + ";\n";
  h += "  c.output_min = -output_limit;\n  c.output_max = output_limit;\n  return c;\n}\n\n";
  // A controller without the velocity observer omits its storage (pid::ObserverStorage).
  const std::string storage = pc.derivative_source == pid::DerivativeSource::Observer
                                  ? ""
                                  : ", fuzzypid::pid::ObserverStorage::Omitted";
  if (!family_traits(spec.family).supervised()) {
    h += "template <class Scalar>\nusing Controller = fuzzypid::pid::Pid<Scalar" + storage +
         ">;\n\n";
    h += "template <class Scalar>\nconstexpr Controller<Scalar> make_controller(" + joint_param +
         "Scalar output_limit) noexcept {\n  return Controller<Scalar>(pid_config<Scalar>(" +
         joint_arg + "output_limit));\n}\n\n";
  } else {
    const supervisor::FuzzyPidConfig<double> fc = fuzzy_pid_config(spec, 0, inf);
    const auto scales_and_bounds = [&](const supervisor::FuzzyPidConfig<double>& f,
                                       const char* indent) {
      return std::string(indent) + "c.output_scale = {" + lit(f.output_scale[0]) + ", " +
             lit(f.output_scale[1]) + ", " + lit(f.output_scale[2]) + "};\n" + indent +
             "c.gain_min = " + gains(f.gain_min) + ";\n" + indent +
             "c.gain_max = " + gains(f.gain_max) + ";\n";
    };
    h += "template <class Scalar>\nconstexpr fuzzypid::supervisor::FuzzyPidConfig<Scalar> "
         "config(" +
         joint_param + "Scalar output_limit) noexcept {\n";
    h += "  fuzzypid::supervisor::FuzzyPidConfig<Scalar> c;\n";
    h += "  c.pid = pid_config<Scalar>(" + joint_arg + "output_limit);\n";
    h += "  c.error_scale = " + lit(fc.error_scale) + ";\n";
    h += "  c.error_rate_scale = " + lit(fc.error_rate_scale) + ";\n";
    h += std::string("  c.gain_update = fuzzypid::supervisor::GainUpdate::") +
         (fc.gain_update == supervisor::GainUpdate::Absolute ? "Absolute" : "Incremental") + ";\n";
    if (per_joint) {
      h += "  switch (joint) {\n";
      for (std::size_t i = 0; i < kSpecJoints; ++i) {
        h += "    case " + std::to_string(i) + ":\n";
        h += scales_and_bounds(fuzzy_pid_config(spec, i, inf), "      ");
        h += "      break;\n";
      }
      h += "    default:  // pid_config() gave NaN gains: the controller refuses the joint\n"
           "      break;\n  }\n";
    } else {
      h += scales_and_bounds(fc, "  ");
    }
    h += "  return c;\n}\n\n";
    h += supervisor.definitions;
    h += "template <class Scalar>\nusing Controller = fuzzypid::supervisor::FuzzyPid<Scalar, "
         "Supervisor<Scalar>" +
         storage + ">;\n\n";
    h += "template <class Scalar>\nController<Scalar> make_controller(" + joint_param +
         "Scalar output_limit) noexcept {\n  return Controller<Scalar>(&kSupervisor<Scalar>, "
         "config<Scalar>(" +
         joint_arg + "output_limit));\n}\n\n";
  }
  h += "}  // namespace " + ns + "\n";
  return h;
}

}  // namespace fuzzypid::codegen
