#!/usr/bin/env python3
"""No panic path in a firmware image that renders the standard scene (issue 11, item 12);
on RV32IMC also no soft float and no 64-bit division on the Q14 frame path (issue 22).

    python3 measure/panics.py              # build measure/frame (release: O3 + LTO; release-z), check
    python3 measure/panics.py --no-build   # check the ELFs as they are (after measure/frame.py)

The images are those of `measure/frame.py` (`measure/frame/`, profile `release`
for thumbv6m-none-eabi, thumbv7em-none-eabihf and riscv32imc-unknown-none-elf,
profile `release-z` for thumbv6m-none-eabi): `no_std`, LTO, `panic = "abort"`,
a panic handler that loops. Each entry `frame_<config>[_band8]` renders one whole frame of
`fixshade::standard` (lighting and shader built from their `f32` parameters,
vertex stage, binning, set-up, spans, flushes).

For every entry the static call graph of `frame.py`'s `Image` (direct
branches, addresses materialised by the code, vtables in `.rodata`; an
over-approximation of what can run) is walked from the entry, and the check
fails if any reachable function is a panic path: `core::panicking::*`
(`panic`, `panic_fmt`, `panic_bounds_check`, `panic_const_*`, …), the
slice-index failures (`slice_index_order_fail`, `slice_*_index_len_fail`,
`copy_from_slice` length mismatch), `unwrap_failed`/`expect_failed`, or the
image's panic handler (`rust_begin_unwind`). With LTO, a panic that cannot
happen is dropped by the optimiser, so the check proves that no panic can be
reached from the rendering path of these images. Each surviving site is
listed with its shortest call chain and the source lines (inline stacks) of
its call sites. Exit 1 on any.

RV32IMC (section `rv32imc`, every entry of the image, the `f32` tier's too):
besides the panic check, each Q14 entry of frame.py's NO_WIDE list (Lambert and
Blinn-Phong Gouraud, Phong, flat; whole and 8-row) must reach no soft-float
helper (compiler-builtins' RISC-V names: `__addsf3`, `__mulsf3`, `__divsf3`,
`__fixsfsi`, `__floatsisf`, `__eqsf2`…, libm) and no 64-bit division helper
(`__udivdi3`, `__divdi3`, `__umoddi3`, `__moddi3`, `u64_div_rem`…; RV32IM
multiplies and divides 32-bit words in hardware, and LLVM multiplies 64-bit
words inline). The other Q14 entries are listed as `known`: `blinn_phong_inc`
builds its power table with `powf` every frame (`Shader::new`), and
`lambert_gouraud_refine` divides in 64 bits. (`frame.py --check` also requires
that nothing of it is executed.)
"""
from __future__ import annotations

import argparse
import re
import sys
import time

from frame import (CORES, NO_WIDE, SECTIONS, Image, call_sites, cargo, elf, is_rv_float, is_rv_wide,  # noqa: E402
                   log, symbolize)

PANIC = re.compile(
    r"^core::panicking::|^core::slice::index::slice_|index_len_fail|index_order_fail"
    r"|copy_from_slice::len_mismatch_fail|unwrap_failed$|expect_failed$|^rust_begin_unwind$"
    r"|panic_bounds_check|panic_fmt|panic_const_|^core::result::unwrap_failed|^core::option::unwrap_failed"
    r"|^core::panic::|::panic$|^std::panicking")


def is_panic(name: str) -> bool:
    return PANIC.search(name) is not None


def build() -> None:
    t = time.time()
    cargo(["build", "--quiet", "--release", "--target", CORES["m0"][1], "--target", CORES["m4f"][1]])
    # apart: in one invocation with the Arm targets cargo gives the Arm units other -C metadata
    # (other symbol hashes), and LLVM then inlines differently (the M0 image changes)
    cargo(["build", "--quiet", "--release", "--target", CORES["rv32imc"][1]])
    cargo(["build", "--quiet", "--profile", "release-z", "--target", CORES["m0"][1]])
    log(f"built in {time.time() - t:.0f} s")


def handler(emu: Image) -> list[str]:
    """The image's panic handler and the panic functions present in the image at all."""
    return sorted(f for f in emu.funcs if is_panic(emu.names[f]))


def check_section(section: str) -> tuple[int, int, list[str]]:
    core, prof, entries = SECTIONS[section]
    if section == "m0_z":  # every frame entry is in every image (KEEP), whole frames and 8-row bands
        entries = SECTIONS["m0"][2]
    emu = Image(elf(core, prof), core)
    present = handler(emu)
    lines = [f"{section} ({CORES[core][1]}, profile {prof}): panic functions present in the image: "
             + (", ".join(emu.short(f) for f in present) or "none")]
    ok = bad = 0
    seen: set[tuple[str, str]] = set()  # (caller, panic function) already listed
    for ent in entries:
        sym = f"frame_{ent}"
        parent = emu.reach(sym)
        if emu.riscv and ent in SECTIONS["m0"][2]:  # a Q14 entry
            fw = sorted({emu.short(f) for f in parent if is_rv_float(emu.names[f]) or is_rv_wide(emu.names[f])})
            if not fw:
                ok += 1
                lines.append(f"ok   {section} {ent}: no soft float or 64-bit division reachable")
            elif ent in NO_WIDE:
                bad += 1
                lines.append(f"FAIL {section} {ent}: soft float / 64-bit division reachable: {fw}")
            else:
                lines.append(f"known {section} {ent}: soft float / 64-bit division reachable (not enforced, as on"
                             f" the M0): {', '.join(f.split('::')[-1] for f in fw)}")
        found = sorted(f for f in parent if is_panic(emu.names[f]))
        if not found:
            ok += 1
            lines.append(f"ok   {section} {ent}: no panic path reachable ({len(parent)} functions)")
            continue
        bad += 1
        callers = sorted((c, f) for f in found for c in parent
                         if f in emu.edges(c) and c != f and not is_panic(emu.names[c]))
        lines.append(f"FAIL {section} {ent}: {len(callers)} callers of "
                     f"{', '.join(emu.short(f).split('::')[-1] for f in found)}"
                     + (" (listed above)" if all(cf in seen for cf in callers) else ""))
        for c, f in callers:
            if (c, f) in seen:
                continue
            seen.add((c, f))
            lines.append(f"     {emu.chain(parent, c)} -> {emu.short(f)}")
            for a, st in symbolize(emu.elf, call_sites(emu, c, f)).items():
                lines.append(f"         {a:#x}: " + " < ".join(
                    f"{emu.short(fn).split('::')[-1]} ({loc})" for fn, loc in st[:4]))
    return ok, bad, lines


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--no-build", action="store_true", help="use the ELFs as they are")
    p.add_argument("--sections", default=",".join(SECTIONS), help="comma-separated subset of " + ",".join(SECTIONS))
    a = p.parse_args(argv)
    t = time.time()
    if not a.no_build:
        build()
    passed = failed = 0
    for section in a.sections.split(","):
        ok, bad, lines = check_section(section)
        print("\n".join(lines))
        passed, failed = passed + ok, failed + bad
    print(f"{passed} passed, {failed} failed ({time.time() - t:.0f} s)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
