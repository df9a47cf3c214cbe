// Minimal start-up for QEMU's mps2-an386 board (Cortex-M4F): the vector table and a reset handler
// that switches the FPU on and hands over to newlib's semihosting start-up (rdimon-crt0's _start,
// which sets up the stack and heap, runs the constructors and calls main with the host's argv).
#include <cstdint>

extern "C" {
void _start();                     // rdimon-crt0 (--specs=rdimon.specs)
extern std::uint32_t __stack_top;  // linker.ld

[[noreturn]] void Reset_Handler() {
  // CPACR: full access to coprocessors 10 and 11 (the FPU) before any floating-point instruction.
  auto* const cpacr = reinterpret_cast<volatile std::uint32_t*>(0xE000ED88u);
  *cpacr = *cpacr | (0xFu << 20);
  __asm volatile("dsb\n\tisb" ::: "memory");
  _start();
  for (;;) {
  }
}

[[noreturn]] void Default_Handler() {
  for (;;) {
  }
}

// Initial stack pointer, reset, then NMI .. SysTick (the core's 15 exceptions); no device IRQs.
using Vector = void (*)();
__attribute__((section(".vectors"), used)) const Vector g_vectors[16] = {
    reinterpret_cast<Vector>(&__stack_top),
    Reset_Handler,
    Default_Handler,  // NMI
    Default_Handler,  // HardFault
    Default_Handler,  // MemManage
    Default_Handler,  // BusFault
    Default_Handler,  // UsageFault
    nullptr,
    nullptr,
    nullptr,
    nullptr,
    Default_Handler,  // SVCall
    Default_Handler,  // DebugMonitor
    nullptr,
    Default_Handler,  // PendSV
    Default_Handler,  // SysTick
};
}
