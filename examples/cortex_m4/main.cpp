// The paper's 6-joint fuzzy PID in float, closed around a simulated plant, on a Cortex-M4F (QEMU
// mps2-an386, semihosting) or on the host. Both builds print the same lines when both are
// compiled with -ffp-contract=off: one line per tick with the six commands' IEEE-754 bits in hex,
// then summary lines starting with '#'. On the Cortex-M4F the summary also gives the instructions
// per tick counted with SysTick under `qemu-system-arm -icount shift=0` (one instruction per
// nanosecond, SysTick at the board's 25 MHz: one count is 40 instructions).
//
// usage: main [ticks] [print|quiet|fuzzy]   (default 10000 print; "quiet" prints only the summary,
//        "fuzzy" runs only the fuzzy controller's loop, for an instruction trace)
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "fuzzypid/fuzzypid.hpp"  // the whole core compiles for the Cortex-M4F (-Werror)

namespace {

constexpr std::size_t kJoints = 6;
constexpr float kDt = 0.05f;  // s, the paper's tick

using Input = fuzzypid::control::JointInput<float, kJoints>;
using Output = fuzzypid::control::JointOutput<float, kJoints>;

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

std::uint32_t bits(float x) {
  std::uint32_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

#if defined(__ARM_ARCH_7EM__)
// SysTick (ARMv7-M): a 24-bit down-counter on the processor clock.
volatile std::uint32_t& syst_csr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E010u);
volatile std::uint32_t& syst_rvr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E014u);
volatile std::uint32_t& syst_cvr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E018u);
constexpr std::uint32_t kInstructionsPerCount = 40;  // -icount shift=0 at 25 MHz

void start_systick() {
  syst_rvr = 0x00FFFFFFu;
  syst_cvr = 0;
  syst_csr = 5;  // enable, processor clock, no interrupt
}
std::uint32_t now() {
  return syst_cvr;
}
std::uint32_t elapsed(std::uint32_t from, std::uint32_t to) {
  return (from - to) & 0x00FFFFFFu;
}
#else
void start_systick() {}
std::uint32_t now() {
  return 0;
}
std::uint32_t elapsed(std::uint32_t, std::uint32_t) {
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
                  static_cast<unsigned long>(bits(out.torque_nm[0])),
                  static_cast<unsigned long>(bits(out.torque_nm[1])),
                  static_cast<unsigned long>(bits(out.torque_nm[2])),
                  static_cast<unsigned long>(bits(out.torque_nm[3])),
                  static_cast<unsigned long>(bits(out.torque_nm[4])),
                  static_cast<unsigned long>(bits(out.torque_nm[5])));
    }
    plant.step(out.torque_nm.data(), kDt);
  }
  return counts;
}

// Empty-measurement overhead: two SysTick reads around nothing, in SysTick counts per pair.
std::uint64_t overhead(long pairs) {
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

}  // namespace

int main(int argc, char** argv) {
  const long ticks = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 10000;
  const char* const mode = argc > 2 ? argv[2] : "print";
  const bool print = std::strcmp(mode, "print") == 0;
  const bool fuzzy_only = std::strcmp(mode, "fuzzy") == 0;
  if (ticks < 1 || (!print && !fuzzy_only && std::strcmp(mode, "quiet") != 0)) {
    std::fprintf(stderr, "usage: main [ticks >= 1] [print|quiet|fuzzy]\n");
    return 2;
  }
  start_systick();

  // The paper's configuration with a torque limit; its rule base is constexpr data in flash.
  auto config = fuzzypid::paper::paper_config<float>();
  config.pid.output_min = -50.0f;
  config.pid.output_max = 50.0f;
  fuzzypid::paper::JointController<float, kJoints> fuzzy(
      fuzzypid::paper::FuzzyPid<float>(&fuzzypid::paper::kSystem<float>, config));
  fuzzypid::control::JointController<float, kJoints, fuzzypid::pid::Pid<float>> fixed(
      fuzzypid::pid::Pid<float>(config.pid));

  fuzzypid::Status worst_fuzzy = fuzzypid::Status::Ok;
  fuzzypid::Status worst_pid = fuzzypid::Status::Ok;
  const std::uint64_t fuzzy_counts = run(fuzzy, ticks, print, worst_fuzzy);
  if (fuzzy_only) return fuzzypid::is_fault(worst_fuzzy) ? 1 : 0;
  const std::uint64_t pid_counts = run(fixed, ticks, false, worst_pid);
  const std::uint64_t empty_counts = overhead(ticks);

  std::printf("# ticks %ld\n", ticks);
  std::printf("# fuzzy status %s, pid status %s\n", fuzzypid::to_string(worst_fuzzy),
              fuzzypid::to_string(worst_pid));
#if defined(__ARM_ARCH_7EM__)
  // Instructions per tick, x100, net of the two SysTick reads (integer arithmetic: no float
  // formatting needed from newlib).
  const auto per_tick_x100 = [&](std::uint64_t counts) {
    const std::uint64_t net = counts > empty_counts ? counts - empty_counts : 0;
    return static_cast<unsigned long>(net * kInstructionsPerCount * 100 /
                                      static_cast<std::uint64_t>(ticks));
  };
  const unsigned long fuzzy_x100 = per_tick_x100(fuzzy_counts);
  const unsigned long pid_x100 = per_tick_x100(pid_counts);
  std::printf("# instructions per 6-joint fuzzy tick %lu.%02lu\n", fuzzy_x100 / 100,
              fuzzy_x100 % 100);
  std::printf("# instructions per 6-joint pid tick %lu.%02lu\n", pid_x100 / 100, pid_x100 % 100);
#else
  (void)fuzzy_counts;
  (void)pid_counts;
  (void)empty_counts;
#endif
  return fuzzypid::is_fault(worst_fuzzy) || fuzzypid::is_fault(worst_pid) ? 1 : 0;
}
