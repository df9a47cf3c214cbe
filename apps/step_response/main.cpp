// One joint, J theta'' = u, answering a 0.1 rad step under the paper's fixed PID and fuzzy PID.
// J = 10 kg·m² keeps the derivative loop gain Kd dt / J = 0.5 of the paper's gains inside the
// stable range of a 50 ms zero-order hold (it diverges for J below about 2.5 kg·m²).
// Writes t,theta_pid,theta_fuzzy,kp,ki,kd as CSV on stdout: the smallest end-to-end use of the
// core without the robot model.
#include <cstdio>

#include "fuzzypid/fuzzypid.hpp"

int main() {
  using namespace fuzzypid;
  constexpr double kInertia = 10.0;  // kg·m²
  constexpr double kDt = 0.05;       // s, the paper's tick
  constexpr double kStep = 0.1;      // rad
  constexpr int kTicks = 400;        // 20 s

  supervisor::FuzzyPidConfig<double> config = paper::paper_config<double>();
  config.pid.derivative_source = pid::DerivativeSource::Rates;
  pid::Pid<double> fixed(config.pid);
  paper::FuzzyPid<double> fuzzy(&paper::kSystem<double>, config);

  // Exact zero-order-hold integration of J theta'' = u over one tick.
  struct Joint {
    double theta = 0.0, omega = 0.0;
    void advance(double u, double dt) {
      theta += omega * dt + 0.5 * u / kInertia * dt * dt;
      omega += u / kInertia * dt;
    }
  } a, b;

  std::puts("t,theta_pid,theta_fuzzy,kp,ki,kd");
  for (int k = 0; k <= kTicks; ++k) {
    const double t = k * kDt;
    std::printf("%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, a.theta, b.theta, fuzzy.gains().kp,
                fuzzy.gains().ki, fuzzy.gains().kd);
    pid::Input<double> in_a{kStep, a.theta, 0.0, a.omega, 0.0};
    pid::Input<double> in_b{kStep, b.theta, 0.0, b.omega, 0.0};
    if (is_fault(fixed.update(in_a, kDt)) || is_fault(fuzzy.update(in_b, kDt))) {
      std::fputs("step_response: controller fault\n", stderr);
      return 1;
    }
    a.advance(fixed.output(), kDt);
    b.advance(fuzzy.output(), kDt);
  }
  return 0;
}
