// The record a controller file keeps of a certificate: what `fuzzypid certify` found for a
// controller over a set of conditions (sim::margin_record builds it from a sim::Certificate).
#pragma once

#include <array>
#include <string>

namespace fuzzypid::controller {

// What `fuzzypid certify` found for the controller (sim/certify.hpp, docs/margins.md) over the
// conditions named, as `fuzzypid tune` records it for its training conditions: per joint the
// worst frozen-gain margins and the inertia range, and whether a common quadratic Lyapunov
// function covers gains switching every tick (the certificate) under `assumptions`.
struct MarginRecord {
  using PerJoint = std::array<double, 6>;
  std::string conditions;  // the condition file (relative to the controller file's folder)
  std::string set;         // its set
  double delay_ms = 0.0;   // the delay the loops were analysed with
  PerJoint gain_margin_db{}, phase_margin_deg{}, delay_margin_ms{}, disk_margin{};
  PerJoint inertia_min_kgm2{}, inertia_max_kgm2{};
  bool certified = false;
  std::string verdict;
  std::string assumptions;
};

}  // namespace fuzzypid::controller
