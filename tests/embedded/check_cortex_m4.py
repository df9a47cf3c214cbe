#!/usr/bin/python3
"""The core on an emulated Cortex-M4F (examples/cortex_m4/), checked against the host.

Builds examples/cortex_m4 with arm-none-eabi-g++ for QEMU's mps2-an386 board and with the host
compiler (both float, -ffp-contract=off), runs the 6-joint fuzzy controller in closed loop on
both, and requires the commands of every tick to be equal bit for bit. Prints and checks:
  - instructions per 6-joint tick (SysTick under -icount shift=0, counted by the image itself),
  - vdiv.f32 executed per fuzzy tick (QEMU's one-instruction-per-block exec trace of two runs of
    different length, counting the executions of the image's vdiv.f32 addresses),
  - flash and RAM use (arm-none-eabi-size).
A missing tool is a failure, never a skip.

usage: check_cortex_m4.py SOURCE_DIR WORK_DIR HOST_CXX
"""
import os
import re
import shutil
import subprocess
import sys

TICKS = 10000
# The budgets of the issue that introduced this check (per 6-joint float tick).
MAX_INSTRUCTIONS = 2000
MAX_VDIV = 6

ARM_FLAGS = ["-std=c++17", "-mcpu=cortex-m4", "-mthumb", "-mfpu=fpv4-sp-d16",
             "-mfloat-abi=hard", "-O2", "-ffp-contract=off", "-fno-exceptions", "-fno-rtti",
             "-ffunction-sections", "-fdata-sections", "-Wall", "-Wextra", "-Wpedantic",
             "-Wdouble-promotion", "-Werror"]
QEMU = ["-M", "mps2-an386", "-cpu", "cortex-m4", "-nographic", "-monitor", "none",
        "-serial", "none", "-icount", "shift=0"]


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def tool(name):
    path = shutil.which(name)
    if path is None:
        fail(f"{name} not found (scripts/install-deps.sh installs it)")
    return path


def run(cmd, **kwargs):
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=120, **kwargs)
    if result.returncode != 0:
        fail(f"{' '.join(cmd)} exited with {result.returncode}:\n{result.stdout}{result.stderr}")
    return result.stdout


def qemu(qemu_bin, image, args, extra=()):
    semihosting = "enable=on,target=native," + ",".join(f"arg={a}" for a in [image, *args])
    return run([qemu_bin, *QEMU, *extra, "-semihosting-config", semihosting, "-kernel", image])


def vdiv_executions(qemu_bin, image, vdiv_addresses, ticks, log):
    qemu(qemu_bin, image, [str(ticks), "fuzzy"],
         ["-singlestep", "-d", "exec,nochain", "-D", log])
    count = 0
    pc = re.compile(r"^Trace \d+: 0x[0-9a-f]+ \[[0-9a-f]+/([0-9a-f]+)/")
    with open(log) as f:
        for line in f:
            m = pc.match(line)
            if m and int(m.group(1), 16) in vdiv_addresses:
                count += 1
    return count


def main():
    source, work, host_cxx = sys.argv[1:4]
    example = os.path.join(source, "examples", "cortex_m4")
    include = os.path.join(source, "include")
    os.makedirs(work, exist_ok=True)
    arm_gxx = tool("arm-none-eabi-g++")
    objdump = tool("arm-none-eabi-objdump")
    size = tool("arm-none-eabi-size")
    qemu_bin = tool("qemu-system-arm")

    image = os.path.join(work, "cortex_m4.elf")
    run([arm_gxx, *ARM_FLAGS, "-I" + include, "--specs=rdimon.specs",
         "-T", os.path.join(example, "linker.ld"), "-Wl,--gc-sections",
         os.path.join(example, "startup.cpp"), os.path.join(example, "main.cpp"), "-o", image])
    host = os.path.join(work, "host_float")
    run([host_cxx, "-std=c++17", "-O2", "-ffp-contract=off", "-Wall", "-Wextra", "-Wpedantic",
         "-Werror", "-I" + include, os.path.join(example, "main.cpp"), "-o", host])

    m4_out = qemu(qemu_bin, image, [str(TICKS)]).splitlines()
    host_out = run([host, str(TICKS)]).splitlines()
    m4_ticks = [line for line in m4_out if not line.startswith("#")]
    host_ticks = [line for line in host_out if not line.startswith("#")]
    if len(m4_ticks) != TICKS or len(host_ticks) != TICKS:
        fail(f"expected {TICKS} ticks, got {len(m4_ticks)} (Cortex-M4F) and {len(host_ticks)} (host)")
    for k, (a, b) in enumerate(zip(m4_ticks, host_ticks)):
        if a != b:
            fail(f"tick {k}: Cortex-M4F commands {a} differ from the host's {b}")
    print(f"commands of {TICKS} ticks x 6 joints: Cortex-M4F == host float, bit for bit")

    summary = {}
    for line in m4_out:
        m = re.match(r"# instructions per 6-joint (\w+) tick ([0-9.]+)", line)
        if m:
            summary[m.group(1)] = float(m.group(2))
    if "fuzzy" not in summary or "pid" not in summary:
        fail("the image printed no instruction counts:\n" + "\n".join(m4_out[-5:]))

    disassembly = run([objdump, "-d", image])
    # vdiv.f32, or a conditional vdiv<cc>.f32 inside an IT block (counted even when its condition
    # skips it: an upper bound).
    vdiv = {int(m.group(1), 16)
            for m in re.finditer(r"^[ \t]*([0-9a-f]+):[ \t].*\bvdiv(?:[a-z]{2})?\.f32\b",
                                 disassembly, re.M)}
    short = vdiv_executions(qemu_bin, image, vdiv, 10, os.path.join(work, "trace_10.log"))
    long = vdiv_executions(qemu_bin, image, vdiv, 30, os.path.join(work, "trace_30.log"))
    vdiv_per_tick = (long - short) / 20

    print(f"instructions per 6-joint float tick: fuzzy {summary['fuzzy']:.0f}, "
          f"fixed PID {summary['pid']:.0f} (SysTick, -icount shift=0, 1 count = 40)")
    print(f"vdiv.f32 executed per 6-joint fuzzy tick: {vdiv_per_tick:g} "
          f"({len(vdiv)} in the image)")
    print(run([size, image]).rstrip())

    if summary["fuzzy"] > MAX_INSTRUCTIONS:
        fail(f"{summary['fuzzy']:.0f} instructions per fuzzy tick, budget {MAX_INSTRUCTIONS}")
    if not vdiv or vdiv_per_tick < 1:
        fail("no vdiv.f32 found executing: the disassembly or trace parsing is broken")
    if vdiv_per_tick > MAX_VDIV:
        fail(f"{vdiv_per_tick:g} vdiv.f32 per fuzzy tick, budget {MAX_VDIV}")
    print("PASS")


if __name__ == "__main__":
    main()
