// The closed loop both Cortex-M4F examples run (main.cpp: the paper's controller;
// rule_file_main.cpp: a controller exported with its rule file): six joints J q'' = u - b q' in
// float, references from a fully specified generator, each tick's six commands printed as IEEE-754
// bits, instructions counted with SysTick under `qemu-system-arm -icount shift=0` (one
// instruction per nanosecond, SysTick at the board's 25 MHz: one count is 40 instructions).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "fuzzypid/status.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"

namespace cortex_m4_example {

constexpr std::size_t kJoints = 6;
constexpr float kDt = 0.05f;  // s, the paper's tick

using Input = fuzzypid::supervisor::JointInput<float, kJoints>;
using Output = fuzzypid::supervisor::JointOutput<float, kJoints>;

// A fully specified generator (no libm, no implementation-defined distribution), so both builds
// see the same references.
struct Lcg {
  std::uint32_t state;
  std::uint32_t next() {
    state = state * 1664525u + 1013904223u;
    return state;
  }
  // Uniform in [-half, half): a 24-bit integer times a power of two, exact in float.
  float symmetric(float half) {
    const auto n = static_cast<std::int32_t>(next() >> 8) - (1 << 23);
    return static_cast<float>(n) * (half * 0x1.0p-23f);
  }
};

// Six joints J q'' = u - b q' (semi-implicit Euler, float): the loop closes through the plant.
struct Plant {
  float position[kJoints] = {};
  float velocity[kJoints] = {};
  void step(const float* u, float dt) {
    // 1/(kg m^2): Kd dt / J stays below 1 with the paper's Kd = 100 at 50 ms, a stable loop.
    constexpr float kInverseInertia[kJoints] = {0.05f, 0.04f, 0.1f, 0.125f, 0.15f, 0.18f};
    constexpr float kDamping = 2.0f;  // N m s
    for (std::size_t i = 0; i < kJoints; ++i) {
      velocity[i] += dt * (u[i] - kDamping * velocity[i]) * kInverseInertia[i];
      position[i] += dt * velocity[i];
    }
  }
};

inline std::uint32_t bits(float x) {
  std::uint32_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

#if defined(__ARM_ARCH_7EM__)
// SysTick (ARMv7-M): a 24-bit down-counter on the processor clock.
inline volatile std::uint32_t& syst_csr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E010u);
inline volatile std::uint32_t& syst_rvr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E014u);
inline volatile std::uint32_t& syst_cvr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E018u);
constexpr std::uint32_t kInstructionsPerCount = 40;  // -icount shift=0 at 25 MHz

inline void start_systick() {
  syst_rvr = 0x00FFFFFFu;
  syst_cvr = 0;
  syst_csr = 5;  // enable, processor clock, no interrupt
}
inline std::uint32_t now() {
  return syst_cvr;
}
inline std::uint32_t elapsed(std::uint32_t from, std::uint32_t to) {
  return (from - to) & 0x00FFFFFFu;
}
#else
inline void start_systick() {}
inline std::uint32_t now() {
  return 0;
}
inline std::uint32_t elapsed(std::uint32_t, std::uint32_t) {
  return 0;
}
#endif

// The measured call: one 6-joint tick, out of line so its code is one symbol to disassemble.
template <class Controller>
[[gnu::noinline]] Output tick(Controller& controller, const Input& in) {
  return controller.step(in, kDt);
}

// Runs `ticks` ticks of `controller` in closed loop; prints each tick's commands unless quiet.
// Returns the SysTick counts spent inside tick() and the worst status.
template <class Controller>
std::uint64_t run(Controller& controller, long ticks, bool print, fuzzypid::Status& worst) {
  Plant plant;
  Lcg rng{12345u};
  Input in;
  std::uint64_t counts = 0;
  for (long k = 0; k < ticks; ++k) {
    if (k % 40 == 0) {  // a new target every 2 s, up to +-0.5 rad, moving at up to +-0.2 rad/s
      for (std::size_t i = 0; i < kJoints; ++i) {
        in.desired_position_rad[i] = rng.symmetric(0.5f);
        in.desired_velocity_rad_s[i] = rng.symmetric(0.2f);
      }
    }
    for (std::size_t i = 0; i < kJoints; ++i) {
      in.desired_position_rad[i] += kDt * in.desired_velocity_rad_s[i];
      in.measured_position_rad[i] = plant.position[i];
      in.measured_velocity_rad_s[i] = plant.velocity[i];
    }
    __asm volatile("" ::: "memory");
    const std::uint32_t t0 = now();
    const Output out = tick(controller, in);
    const std::uint32_t t1 = now();
    __asm volatile("" ::: "memory");
    counts += elapsed(t0, t1);
    worst = fuzzypid::worst(worst, out.status);
    if (print) {
      std::printf("%08lx %08lx %08lx %08lx %08lx %08lx\n",
                  static_cast<unsigned long>(bits(out.output[0])),
                  static_cast<unsigned long>(bits(out.output[1])),
                  static_cast<unsigned long>(bits(out.output[2])),
                  static_cast<unsigned long>(bits(out.output[3])),
                  static_cast<unsigned long>(bits(out.output[4])),
                  static_cast<unsigned long>(bits(out.output[5])));
    }
    plant.step(out.output.data(), kDt);
  }
  return counts;
}

// Empty-measurement overhead: two SysTick reads around nothing, in SysTick counts per pair.
inline std::uint64_t overhead(long pairs) {
  std::uint64_t counts = 0;
  for (long k = 0; k < pairs; ++k) {
    __asm volatile("" ::: "memory");
    const std::uint32_t t0 = now();
    const std::uint32_t t1 = now();
    __asm volatile("" ::: "memory");
    counts += elapsed(t0, t1);
  }
  return counts;
}

}  // namespace cortex_m4_example
