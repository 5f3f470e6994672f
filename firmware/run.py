#!/usr/bin/env python3
"""Builds the showcase firmware (firmware/qemu) for every core and
configuration, runs each image in QEMU, checks its checksum against the host
reference, and prints the resources table of the README.

Cores: m0 (QEMU microbit), m4f (mps2-an386), rv32imc (virt, riscv32imc-unknown-none-elf).

    python3 firmware/run.py                 # build, run, print the table (about 2 min when built)
    python3 firmware/run.py --check         # CI: also fail on any mismatch; last line "N passed, N failed"
    python3 firmware/run.py --cores m0 --configs flat,blinn_phong
    python3 firmware/run.py --no-build      # the images as they are (firmware/target/images/)
    python3 firmware/run.py --profile release-z --cores m0   # the same at opt-level "z"

Needs: qemu-system-arm and qemu-system-riscv32 (Debian: apt-get install
qemu-system-arm qemu-system-misc), the rustup targets thumbv6m-none-eabi,
thumbv7em-none-eabihf and riscv32imc-unknown-none-elf, pyelftools.

Configurations `imported` and `imported_textured`: the rocket that
firmware/qemu/build.rs imports from import/assets/rocket.obj (fixshade-import),
Gouraud and textured Gouraud; `imported` runs on the micro:bit in 2-row bands,
`imported_textured` does not fit its RAM and is skipped there. The host
reference also counts the pixels not of the clear colour: every configuration
must light at least 5 % of them and differ from a clear frame.

Per image (one configuration, the standard scene, `fixshade-qemu` built at
opt-level 3 with LTO):
  * checksum: the Checksum display's value after one frame; must equal the
    host's (`cargo run -p fixshade-qemu --profile host`, the same library
    functions compiled for x86-64) and be the same in both frames the image
    renders;
  * instructions per frame: SysTick ticks of the frame, converted with a
    calibration loop of 2^21 instructions; QEMU runs with `-icount shift=0`
    (one instruction = 1 ns of virtual time), so the count is exact to one
    tick (62.5 instructions on the microbit, 40 on the mps2) and
    deterministic; the checker requires 62.5 / 40 instructions per tick;
    rv32imc: the `minstret` CSR, exact under `-icount shift=0` (QEMU returns
    its instruction counter): the checker requires that a loop of 4n
    instructions reads exactly 2n more than one of 2n, and the image that the
    CLINT's mtime (100 instructions per tick) agrees within four ticks (it is
    read at translation-block edges);
  * stack: the painted stack's low-water mark (cortex-m-rt `paint-stack`):
    the image's peak (bytes below the top after start-up, set-up and both
    frames) and the frame's own (below the SP at the call of the frame
    function: the stack is painted again before the frames);
  * flash and RAM: section and symbol sizes of the ELF (pyelftools).
The stack sits below the statics (build.rs writes memory.x): an overflow
faults and the image exits with status 1 (rv32imc: the stack has its own
region, and a locked PMP entry makes the 256 bytes below it inaccessible).
`--check` proves it: it builds the `lambert_gouraud` image of every core with
a 2 KiB stack and requires each to exit 1 with "stack overflow".
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
# cargo runs in firmware/: a relative CARGO_TARGET_DIR is relative to it
TARGET_DIR = HERE / os.environ.get("CARGO_TARGET_DIR", "target")
IMAGES = TARGET_DIR / "images"
CONFIGS = ["lambert_gouraud", "blinn_gouraud", "blinn_phong", "blinn_phong_inc", "flat", "imported",
           "imported_textured"]
# the rocket imported from import/assets/rocket.obj by firmware/qemu/build.rs
IMPORTED = ["imported", "imported_textured"]
# (core, config) not built, and why
SKIP = {("m0", "imported_textured"): "687 textured vertex cache entries of 22 B (15.1 KiB) do not fit 16 KiB of RAM"}
CORES = {
    # core: (rust target, QEMU machine, instructions per SysTick tick, RAM bytes,
    #        clock for frames per second, what that clock is)
    "m0": ("thumbv6m-none-eabi", "microbit", 62.5, 16 * 1024, 133e6, "133 MHz"),
    "m4f": ("thumbv7em-none-eabihf", "mps2-an386", 40.0, 4 * 1024 * 1024, 168e6, "168 MHz"),
    # instructions from minstret (1 per count); RAM: what memory.x gives the image
    "rv32imc": ("riscv32imc-unknown-none-elf", "virt", 1.0, 1024 * 1024, 160e6, "160 MHz"),
}
QEMU_TIMEOUT = 120
# function names (mangled) counted as "fixshade + scene code": fixshade, this
# firmware's scene functions (fixshade_qemu) and fixshade's own dependencies
OURS = ["fixshade", "4libm", "9micromath", "5fixed", "8heapless"]


def cargo(args, env=None):
    cmd = ["cargo"] + args
    r = subprocess.run(cmd, cwd=HERE, env={**os.environ, **(env or {})}, capture_output=True, text=True)
    if r.returncode != 0:
        sys.stderr.write(r.stderr)
        raise SystemExit(f"failed: {' '.join(cmd)}")
    return r.stdout


def build(core, config, profile="release", env=None, name=None):
    target = CORES[core][0]
    cargo(["build", "-q", "-p", "fixshade-qemu", "--profile", profile, "--target", target, "--features", config], env)
    IMAGES.mkdir(parents=True, exist_ok=True)
    dst = IMAGES / f"{name or core + '_' + config + '_' + profile}.elf"
    shutil.copyfile(TARGET_DIR / target / profile / "showcase", dst)
    return dst


def qemu(core, elf):
    machine = CORES[core][1]
    if core.startswith("rv"):
        # no firmware (the reset vector jumps to the ELF at 0x8000_0000); UART on stdout
        cmd = ["timeout", str(QEMU_TIMEOUT), "qemu-system-riscv32", "-M", machine, "-bios", "none",
               "-nographic", "-icount", "shift=0", "-kernel", str(elf)]
    else:
        cmd = ["timeout", str(QEMU_TIMEOUT), "qemu-system-arm", "-M", machine, "-nographic",
               "-semihosting-config", "enable=on,target=native", "-icount", "shift=0", "-kernel", str(elf)]
    t = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL)
    return r.returncode, r.stdout + r.stderr, time.time() - t


def host_reference():
    return json.loads(cargo(["run", "-q", "-p", "fixshade-qemu", "--profile", "host", "--features", ",".join(IMPORTED)]))


def elf_sizes(path):
    """Flash and RAM of the image, by section and by symbol."""
    from elftools.elf.elffile import ELFFile

    with open(path, "rb") as fh:
        f = ELFFile(fh)
        sec = {s.name: s for s in f.iter_sections()}
        riscv = f["e_machine"] == "EM_RISCV"
        size = lambda n: sec[n]["sh_size"] if n in sec else 0
        text_lo, text_hi = sec[".text"]["sh_addr"], sec[".text"]["sh_addr"] + size(".text")
        code = {"fixshade": 0, "builtins": 0, "runtime": 0}
        objects = {}
        for s in f.get_section_by_name(".symtab").iter_symbols():
            n, a, z = s.name, s["st_value"] & ~1, s["st_size"]
            if z == 0:
                continue
            if s["st_info"]["type"] == "STT_FUNC" and text_lo <= a < text_hi:
                if any(k in n for k in OURS):
                    code["fixshade"] += z
                elif "compiler_builtins" in n or n.startswith("__aeabi") or (riscv and n.startswith("__")):
                    code["builtins"] += z
                else:
                    code["runtime"] += z
            elif s["st_info"]["type"] == "STT_OBJECT":
                objects[n] = z
        # what no function symbol covers (padding, literal pools outside functions)
        code["runtime"] += size(".text") - sum(code.values())
        # the standard sphere, or the imported rocket's arrays (with its texture)
        mesh = sum(z for n, z in objects.items() if "8standard6SPHERE" in n or ("5model" in n and "ROCKET" in n))
        # RISC-V: riscv-rt's start-up code is in .init.rust
        flash = size(".vector_table") + size(".text") + size(".init.rust") + size(".rodata") + size(".data")
        buffers = {n: objects.get(n, 0) for n in ["STRIP", "DEPTH", "CACHE", "BINS", "CARRY_RECORDS"]}
        return {
            "flash": flash,
            "code_fixshade": code["fixshade"],
            "code_builtins": code["builtins"],
            "code_runtime": code["runtime"] + size(".vector_table") + size(".init.rust"),
            "mesh": mesh,
            "rodata_other": size(".rodata") - mesh + size(".data"),
            "ram_static": size(".data") + size(".bss") + size(".uninit"),
            "ram_buffers": sum(buffers.values()),
            "buffers": buffers,
        }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="exit 1 on any failure (CI)")
    ap.add_argument("--cores", default="m0,m4f,rv32imc")
    ap.add_argument("--configs", default=",".join(CONFIGS))
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--profile", default="release", help="cargo profile: release (opt-level 3) or release-z")
    ap.add_argument("--json", help="where to write the figures (default firmware/target/resources[-PROFILE].json)")
    args = ap.parse_args()
    cores = args.cores.split(",")
    configs = args.configs.split(",")
    passed, failed = 0, 0

    def check(ok, what):
        nonlocal passed, failed
        if ok:
            passed += 1
        else:
            failed += 1
            print(f"FAILED: {what}", flush=True)
        return ok

    print("== host reference (cargo run -p fixshade-qemu --profile host)", flush=True)
    host = host_reference()
    rows = []
    for core in cores:
        target, machine, per_tick, ram, clock, _ = CORES[core]
        for config in configs:
            if (core, config) in SKIP:
                print(f"{core} {config}: not built: {SKIP[core, config]}", flush=True)
                continue
            elf = IMAGES / f"{core}_{config}_{args.profile}.elf"
            if not args.no_build:
                elf = build(core, config, args.profile)
            code, out, secs = qemu(core, elf)
            line = next((l for l in out.splitlines() if l.startswith("RESULT ")), None)
            what = f"{core} {config} ({machine})"
            if not check(code == 0 and line is not None, f"{what}: exit {code}, output:\n{out.strip()}"):
                continue
            r = json.loads(line[len("RESULT "):])
            want = host[config]["checksum"]
            check(r["checksum"] == want, f"{what}: checksum {r['checksum']}, host {want}")
            # the host's frame is a rendered model: not a clear frame, at least 5 % of the pixels lit
            check(want != host["clear"] and 20 * host[config]["lit"] >= r["pixels"],
                  f"{what}: host frame {want} (clear {host['clear']}), {host[config]['lit']} of {r['pixels']} pixels lit")
            if core.startswith("rv"):
                n, c1, c2 = r["calib_n"], r["calib_instructions"], r["calib_instructions_2n"]
                check(c2 - c1 == 2 * n and 0 <= c1 - 2 * n < 16,
                      f"{what}: minstret read {c1} and {c2} for loops of {2 * n} and {4 * n} instructions")
            else:
                tick = r["calib_instructions"] / r["calib_ticks"]
                check(abs(tick - per_tick) < 0.01 * per_tick,
                      f"{what}: {tick:.3f} instructions per tick, not {per_tick}: is -icount shift=0 in effect?")
            check(0 < r["stack_frame"] < r["stack_peak"] < r["stack_size"],
                  f"{what}: stack: frame {r['stack_frame']}, peak {r['stack_peak']} of {r['stack_size']}")
            r.update(elf_sizes(elf))
            r.update(core=core, machine=machine, profile=args.profile, qemu_seconds=round(secs, 2),
                     fps=clock / r["instructions"])
            check(r["ram_static"] + r["stack_size"] <= ram, f"{what}: RAM {r['ram_static']} + stack over {ram}")
            rows.append(r)
            print(f"{what}: {r['checksum']} (host {want}), {r['instructions']} instructions/frame, "
                  f"stack {r['stack_frame']} B (frame), {r['stack_peak']} B (image), {secs:.1f} s", flush=True)

    if "imported" in host and "imported_textured" in host:
        # the texture shows: the textured rocket is not the untextured one
        check(host["imported"]["checksum"] != host["imported_textured"]["checksum"],
              "imported and imported_textured give the same frame")
        print(f"host: imported {host['imported']['lit']} of {240 * 240} pixels lit, clear frame {host['clear']}",
              flush=True)

    if args.check:
        # a stack overflow must fail loudly: 2 KiB is far too small for a frame
        for core in cores:
            elf = build(core, "lambert_gouraud", args.profile, {"FIXSHADE_STACK": "2048"}, f"{core}_overflow")
            code, out, _ = qemu(core, elf)
            check(code == 1 and "stack overflow" in out,
                  f"{core}: a 2 KiB stack must exit 1 with 'stack overflow'; exit {code}, output:\n{out.strip()}")
            print(f"{core} with a 2 KiB stack: exit {code}: {out.strip()}", flush=True)
            # rebuild the regular image so that the next cargo build is a no-op
            build(core, "lambert_gouraud", args.profile)

    suffix = "" if args.profile == "release" else "-" + args.profile
    out = Path(args.json or TARGET_DIR / f"resources{suffix}.json")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(rows, indent=1) + "\n")
    print_table(rows)
    print(f"{passed} passed, {failed} failed")
    if args.check and failed:
        sys.exit(1)


def kib(b):
    return f"{b / 1024:.1f}"


def print_table(rows):
    print()
    print("| core (QEMU board), opt-level | configuration | band rows | instructions / frame | frames/s (clock) "
          "| flash KiB | fixshade + scene code | compiler builtins | runtime | mesh "
          "| static RAM KiB (frame buffers) | stack B: frame, image peak (reserved) | checksum |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in rows:
        opt = "z" if r["profile"] == "release-z" else "3"
        print(f"| {r['core'].upper()} ({r['machine']}), {opt} | {r['config']} | {r['rows']} | {r['instructions']:,} "
              f"| {r['fps']:.1f} @ {CORES[r['core']][5]} | {kib(r['flash'])} | {kib(r['code_fixshade'])} "
              f"| {kib(r['code_builtins'])} | {kib(r['code_runtime'])} | {kib(r['mesh'])} "
              f"| {kib(r['ram_static'])} ({kib(r['ram_buffers'])}) "
              f"| {r['stack_frame']:,}, {r['stack_peak']:,} ({r['stack_size']:,}) "
              f"| {r['checksum']} |")


if __name__ == "__main__":
    main()
