#!/usr/bin/python3
"""A rule-file controller exported by export-header, on an emulated Cortex-M4F, against the host.

Builds examples/cortex_m4/rule_file_main.cpp (the controller of tests/sim/data/engine_fuzzy.toml:
rulebases/paper.fll written by export-header as straight-line code) with arm-none-eabi-g++ for
QEMU's mps2-an386 board and with the host compiler (both float, -ffp-contract=off), runs 10,000
closed-loop ticks of six joints on each and requires every command to be equal bit for bit.
Prints the instructions per 6-joint tick (SysTick under -icount shift=0) and flash and RAM use
(arm-none-eabi-size). A missing tool is a failure, never a skip.

usage: check_rule_file_cortex_m4.py SOURCE_DIR WORK_DIR HOST_CXX EXPORTED_HEADER_DIR
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_cortex_m4 as m4  # noqa: E402  (the same flags, board and helpers)

TICKS = 10000
# The paper's rules as a rule file, written out as straight-line code, within twice the
# instructions of the built-in tables (1,958 per 6-joint tick in embedded.cortex_m4_qemu).
MAX_INSTRUCTIONS = 2 * 1958


def main():
    source, work, host_cxx, exported = sys.argv[1:5]
    example = os.path.join(source, "examples", "cortex_m4")
    include = os.path.join(source, "include")
    header = os.path.join(exported, "engine_fuzzy.hpp")
    if not os.path.isfile(header):
        m4.fail(f"{header} missing (built with the test_export_header target)")
    os.makedirs(work, exist_ok=True)
    arm_gxx = m4.tool("arm-none-eabi-g++")
    size = m4.tool("arm-none-eabi-size")
    qemu_bin = m4.tool("qemu-system-arm")

    image = os.path.join(work, "rule_file_cortex_m4.elf")
    m4.run([arm_gxx, *m4.ARM_FLAGS, "-I" + include, "-I" + exported, "--specs=rdimon.specs",
            "-T", os.path.join(example, "linker.ld"), "-Wl,--gc-sections",
            os.path.join(example, "startup.cpp"), os.path.join(example, "rule_file_main.cpp"),
            "-o", image])
    host = os.path.join(work, "rule_file_host_float")
    m4.run([host_cxx, "-std=c++17", "-O2", "-ffp-contract=off", "-Wall", "-Wextra", "-Wpedantic",
            "-Werror", "-I" + include, "-I" + exported, os.path.join(example, "rule_file_main.cpp"),
            "-o", host])

    m4_out = m4.qemu(qemu_bin, image, [str(TICKS)]).splitlines()
    host_out = m4.run([host, str(TICKS)]).splitlines()
    m4_ticks = [line for line in m4_out if not line.startswith("#")]
    host_ticks = [line for line in host_out if not line.startswith("#")]
    if len(m4_ticks) != TICKS or len(host_ticks) != TICKS:
        m4.fail(f"expected {TICKS} ticks, got {len(m4_ticks)} (Cortex-M4F) and "
                f"{len(host_ticks)} (host)")
    for k, (a, b) in enumerate(zip(m4_ticks, host_ticks)):
        if a != b:
            m4.fail(f"tick {k}: Cortex-M4F commands {a} differ from the host's {b}")
    if len(set(m4_ticks)) < TICKS // 2:
        m4.fail("the commands barely change: the loop does not run")
    print(f"commands of {TICKS} ticks x 6 joints: Cortex-M4F == host float, bit for bit")

    status = [line for line in m4_out if line.startswith("# rule-file fuzzy status")]
    if status != ["# rule-file fuzzy status ok"]:
        m4.fail("the controller did not finish without a fault: " + " ".join(status))
    per_tick = None
    for line in m4_out:
        m = re.match(r"# instructions per 6-joint rule-file tick ([0-9.]+)", line)
        if m:
            per_tick = float(m.group(1))
    if per_tick is None:
        m4.fail("the image printed no instruction count:\n" + "\n".join(m4_out[-5:]))
    print(f"instructions per 6-joint rule-file tick: {per_tick:.0f} "
          f"(SysTick, -icount shift=0, 1 count = 40)")
    print(m4.run([size, image]).rstrip())
    if not 0 < per_tick <= MAX_INSTRUCTIONS:
        m4.fail(f"{per_tick:.0f} instructions per tick, budget {MAX_INSTRUCTIONS}")
    print("PASS")


if __name__ == "__main__":
    main()
