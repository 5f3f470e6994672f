#!/usr/bin/env python3
"""Cortex-M and RV32IMC instruction counts and code sizes of every shading configuration.

Builds measure/kernels for thumbv6m-none-eabi (M0), thumbv7em-none-eabihf
(M4F) and riscv32imc-unknown-none-elf (rv32imc: ESP32-C3 class, no FPU), counts
the span and triangle kernels of measure/kernels/src/shading.rs in Unicorn
(cortex.py), writes measure/out/counts.json and prints a table.

    python3 measure/counts.py              # build, count all 75 configurations, write JSON
    python3 measure/counts.py --check      # count only what measure/bounds.json bounds;
                                           # exit 1 if a count exceeds its bound
    python3 measure/counts.py --no-build   # use the ELFs as they are

Per configuration (tier, shading, light set) and core:

* span_64, span_240: instructions per pixel of `Kernel::span`, (c(n) − c(0))/n, for a
  span of n = 64 and n = 240 pixels (c(0) builds the lighting and shader only);
* setup: c(tri of 1 pixel) − c(no draw call): one one-triangle `MeshDraw`
  covering one pixel (triangle setup, edge walking, per-vertex lighting for
  Gouraud, the centroid lighting for flat, and the one pixel);
* tri_32: (c(tri with legs of 32 pixels) − c(no draw call)) / pixels: whole-triangle
  instructions per pixel (528 pixels);
* span_bytes, tri_bytes: flash bytes of the kernel and every function it reaches
  by direct calls/branches in the image (static call graph; RISC-V: from the
  relocations the image keeps, --emit-relocs), i.e. what a program
  using only this configuration links, without the runtime; *_lib excludes
  compiler-builtins and libm (soft float, 64-bit multiply, division), which any
  program on that core shares;
* check: max |Δ| of the 64 span pixels against the f32 tier of the same shading
  and light set, in Rgb565 steps of the worst channel (validates that the counted
  code computes the right thing).
"""
from __future__ import annotations

import argparse
import bisect
import json
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from cortex import CORES, KERNELS_DIR, Emulator, elf_path  # noqa: E402

OUT = HERE / "out" / "counts.json"
BOUNDS = HERE / "bounds.json"
TIERS = ["q14_1", "q14_2", "q30", "f32", "f32fast"]
SHADINGS = ["flat", "gouraud", "phong"]
SETS = ["dir_diffuse", "dir_blinn", "dir_phong", "point4_blinn", "spot_blinn"]
# IncrementalPhong exists for the Q14 tiers and directional Lambert / Blinn-Phong only
INCREMENTAL = [(t, "phong_inc", l) for t in ("q14_1", "q14_2") for l in ("dir_diffuse", "dir_blinn")]
# QuadraticPhongShading: directional light sets (Lambert, Blinn-Phong, Phong) in every tier but Q30
INCREMENTAL += [(t, "phong_quad", l) for t in ("q14_1", "q14_2", "f32", "f32fast")
                for l in ("dir_diffuse", "dir_blinn", "dir_phong")]
# TexturedGouraudShading (Q14<1>): nearest / bilinear, perspective / affine; dir_diffuse takes
# the 5-6-5 fast path (nearest, no specular), dir_blinn the general path (secondary colour)
INCREMENTAL += [("q14_1", f"tex_{f}_{p}", "dir_diffuse") for f in ("nearest", "bilinear")
                for p in ("persp", "affine")]
INCREMENTAL += [("q14_1", f"tex_nearest_{p}", "dir_blinn") for p in ("persp", "affine")]
# NormalMapShading: the Q14 fast path (one directional light, Lambert / Blinn-Phong)
# and the general path (Q14 and f32, a directional light and four point lights)
NORMAL_MAP = [("q14_1", "nmap", "dir_diffuse"), ("q14_1", "nmap", "dir_blinn")]
NORMAL_MAP += [(t, "nmap_general", l) for t in ("q14_1", "f32") for l in ("dir_blinn", "point4_blinn")]
FB = 64  # framebuffer side of the triangle kernels
BIG = 32  # triangle legs for the whole-triangle figure


def build(profile: str) -> None:
    for core, (_, target) in CORES.items():
        cmd = ["cargo", "build", "--quiet", "--profile", profile, "--target", target]
        print("$ (cd measure/kernels &&", " ".join(cmd) + ")", file=sys.stderr)
        subprocess.run(cmd, cwd=KERNELS_DIR, check=True)


def num(x: Fraction | int) -> float:
    return round(float(x), 3)


# -- code size: static call graph -------------------------------------------------
def insns(emu: Emulator, name: str):
    """The instructions of function `name`, skipping its literal pools (ELF $d)."""
    start, size = emu.funcs[name]
    if not hasattr(emu, "_code_starts"):
        emu._code_starts = [a for a, _ in emu._code]
    i = max(0, bisect.bisect_right(emu._code_starts, start) - 1)
    for a, b in emu._code[i:]:
        if a >= start + size:
            break
        lo, hi = max(a, start), min(b, start + size)
        if lo < hi:
            yield from emu.cs.disasm(bytes(emu.uc.mem_read(lo, hi - lo)), lo)


def rv_relocs_in(emu: Emulator, name: str, kinds) -> list[tuple[int, str, int]]:
    """RISC-V: the `.rela.text` entries (offset, kind, target) inside function `name`."""
    start, size = emu.funcs[name]
    if not hasattr(emu, "_rv_offs"):
        emu._rv_offs = [o for o, _, _ in emu.rv_text]
    i = bisect.bisect_left(emu._rv_offs, start)
    out = []
    while i < len(emu.rv_text) and emu.rv_text[i][0] < start + size:
        if emu.rv_text[i][1] in kinds:
            out.append(emu.rv_text[i])
        i += 1
    return out


def callees(emu: Emulator, name: str) -> set[str]:
    """Functions that `name` branches to directly (bl/b/b<cc>). Literal pools are
    not scanned for addresses: their constants collide with code addresses, and
    this code makes no indirect calls (`blx reg`), which `indirect_calls` checks.
    RISC-V: the targets of its call, jal and branch relocations (`auipc`+`jalr`
    pairs, `jal`, `b<cc>` to another function; the image keeps them: --emit-relocs)."""
    start, size = emu.funcs[name]
    if emu.riscv:
        out = {emu.symbol_at(t) for _, _, t in rv_relocs_in(emu, name, ("call", "jal", "branch"))
               if not start <= t < start + size}
        out |= {emu.symbol_at(t) for _, t in rv_links(emu, name) if t is not None and not start <= t < start + size}
        out.discard(name)
        return {f for f in out if not f.startswith("?")}
    out = set()
    for i in insns(emu, name):
        if i.mnemonic.split(".")[0].startswith("b") and i.op_str.startswith("#"):
            t = int(i.op_str[1:], 16)
            if not start <= t < start + size:
                out.add(emu.symbol_at(t))
    out.discard(name)
    return {f for f in out if not f.startswith("?")}


def rv_indirect(emu: Emulator, name: str) -> list:
    """RISC-V: the indirect calls in `name`: `jalr`/`c.jalr` that link (rd = ra) and are
    not the `jalr` of an `auipc`+`jalr` call pair (R_RISCV_CALL*). Jumps without link
    through a register other than ra (`c.jr a5`) are switch jump tables inside the
    function (their targets are `.rela.rodata` entries into its own body)."""
    return [i for i, target in rv_links(emu, name) if target is None]


def rv_links(emu: Emulator, name: str) -> list:
    """RISC-V: every linking register jump (`jalr ra, …`, `c.jalr`) in `name` with its
    target: through an R_RISCV_CALL* pair, or an `auipc rX` + `jalr ra, off(rX)` pair
    the assembler resolved itself (a call inside the same section: recursion), else None."""
    out, prev = [], None
    for i in insns(emu, name):
        m = i.mnemonic
        if m == "c.jalr" or (m == "jalr" and i.op_str.startswith("ra")):
            target = None
            if m == "jalr" and prev is not None and prev.mnemonic == "auipc":
                reg, hi = prev.op_str.split(", ")
                ops = i.op_str.split(", ")  # "ra" | "ra, rs, off" (capstone omits rs = ra, off = 0)
                rs, off = (ops[1], int(ops[2], 0)) if len(ops) == 3 else ("ra", 0)
                if rs == reg:
                    target = (prev.address + (int(hi, 0) << 12) + off) & 0xFFFF_FFFF
            out.append((i, target))
        prev = i
    return out


def indirect_calls(emu: Emulator, fs: set[str]) -> list[str]:
    """`blx`/`bx` through a register other than lr in the functions `fs`
    (RISC-V: `rv_indirect`)."""
    bad = []
    if emu.riscv:
        return [f"{f}: {i.mnemonic} {i.op_str}" for f in fs for i in rv_indirect(emu, f)]
    for f in fs:
        for i in insns(emu, f):
            if i.mnemonic in ("blx", "bx") and i.op_str != "lr":
                bad.append(f"{f}: {i.mnemonic} {i.op_str}")
    return bad


def closure(emu: Emulator, name: str) -> set[str]:
    if not hasattr(emu, "_callees"):
        emu._callees = {}
    seen, todo = set(), [name]
    while todo:
        f = todo.pop()
        if f in seen:
            continue
        seen.add(f)
        if f not in emu._callees:
            emu._callees[f] = callees(emu, f)
        todo.extend(emu._callees[f])
    return seen


def is_runtime_lib(sym: str) -> bool:
    """compiler-builtins (soft float, 64-bit multiply/shift, division, memcpy) and libm."""
    return sym.startswith("__") or "compiler_builtins" in sym or "4libm" in sym


def code_bytes(emu: Emulator, name: str) -> tuple[int, int]:
    fs = closure(emu, name)
    bad = indirect_calls(emu, fs)
    assert not bad, f"{name}: indirect calls make the call graph incomplete: {bad[:3]}"
    total = sum(emu.func_size(f) for f in fs)
    return total, total - sum(emu.func_size(f) for f in fs if is_runtime_lib(f))


# -- counting -----------------------------------------------------------------------
def span_pixels(emu: Emulator, n: int) -> list[int]:
    raw = bytes(emu.uc.mem_read(emu.arena, 2 * n))
    return [int.from_bytes(raw[2 * i:2 * i + 2], "little") for i in range(n)]


def measure(emu: Emulator, tier: str, shading: str, lights: str, sizes: bool) -> dict:
    span = f"span_{tier}_{shading}_{lights}"
    tri = f"tri_{tier}_{shading}_{lights}"
    c = {}
    for n in (0, 64, 240):
        r = emu.call(span, [n, bytes(2 * max(n, 1))])
        assert r.ret == n, (span, n, r.ret)
        c[n] = r.insns
        if n == 64:
            pixels = span_pixels(emu, 64)
    t = {}
    for s in (0, 1, BIG):
        r = emu.call(tri, [s, bytes(2 * FB * FB)])
        t[s] = (r.ret, r.insns)
    assert t[0][0] == 0 and t[1][0] == 1, (tri, t)
    d = {
        "span_64": num(Fraction(c[64] - c[0], 64)),
        "span_240": num(Fraction(c[240] - c[0], 240)),
        "setup": t[1][1] - t[0][1],
        "tri_pixels": t[BIG][0],
        "tri_32": num(Fraction(t[BIG][1] - t[0][1], t[BIG][0])),
    }
    if sizes:
        d["span_bytes"], d["span_bytes_lib"] = code_bytes(emu, span)
        d["tri_bytes"], d["tri_bytes_lib"] = code_bytes(emu, tri)
    return d, pixels


def rgb565_delta(a: int, b: int) -> int:
    ch = lambda p: (p >> 11, (p >> 5) & 63, p & 31)  # noqa: E731
    return max(abs(x - y) for x, y in zip(ch(a), ch(b)))


def run(configs: list[tuple[str, str, str]], profile: str, sizes: bool = True) -> dict:
    res: dict = {}
    for core in CORES:
        emu = Emulator(elf_path(core, profile), core)
        if core == "m0":
            bad = emu.v6m_violations()
            assert not bad, f"ARMv7-M instructions in the M0 image: {bad[:3]}"
        if core == "rv32imc":
            bad = emu.rv32imc_violations()
            assert not bad, f"instructions beyond RV32IMC in the rv32imc image: {bad[:3]}"
        ref = {}
        for tier, shading, lights in sorted(configs, key=lambda c: c[0] != "f32"):
            d, px = measure(emu, tier, shading, lights, sizes)
            if tier == "f32":
                ref[(shading, lights)] = px
            if (shading, lights) in ref:
                d["check"] = max(rgb565_delta(a, b) for a, b in zip(px, ref[(shading, lights)]))
            res.setdefault(f"{tier} {shading} {lights}", {})[core] = d
    return {k: res[k] for k in sorted(res)}


def table(res: dict) -> None:
    cores = list(CORES)
    hdr = f"{'tier':<8} {'shading':<8} {'lights':<13}"
    for c in cores:
        hdr += f" | {c + ' span64':>11} {'span240':>8} {'setup':>6} {'tri32':>7} {'bytes':>6} {'lib':>6} {'Δ':>2}"
    print(hdr)
    for key, per in res.items():
        tier, shading, lights = key.split()
        row = f"{tier:<8} {shading:<8} {lights:<13}"
        for c in cores:
            d = per[c]
            row += (f" | {d['span_64']:>11.2f} {d['span_240']:>8.2f} {d['setup']:>6} {d['tri_32']:>7.2f}"
                    f" {d.get('tri_bytes', 0):>6} {d.get('tri_bytes_lib', 0):>6} {d.get('check', 0):>2}")
        print(row)


def check(res: dict, bounds: dict) -> int:
    passed = failed = 0
    for b in bounds["bounds"]:
        key, core, metric, limit = b["config"], b["core"], b["metric"], b["max"]
        got = res[key][core][metric]
        ok = got <= limit
        passed += ok
        failed += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {key} {core} {metric} = {got} (bound {limit})")
    # a scene pays only for what it uses: the smaller model must cost less
    for r in bounds.get("cheaper", []):
        core, metric = r["core"], r["metric"]
        a, b = res[r["config"]][core][metric], res[r["than"]][core][metric]
        ok = a < b
        passed += ok
        failed += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {r['config']} ({a}) < {r['than']} ({b}) {core} {metric}")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--profile", default="release")
    p.add_argument("--no-build", action="store_true", help="count the ELFs as they are")
    p.add_argument("--check", action="store_true",
                   help=f"count only the configurations in {BOUNDS.name}; exit 1 if a bound is exceeded")
    a = p.parse_args(argv)
    if a.check:
        bounds = json.loads(BOUNDS.read_text())
        if not a.no_build:
            try:
                build(a.profile)
            except subprocess.CalledProcessError as e:
                print(f"FAIL build: {e}")
                print(f"0 passed, {len(bounds['bounds'])} failed")
                return 1
        configs = sorted({tuple(b["config"].split()) for b in bounds["bounds"]}
                         | {tuple(r[k].split()) for r in bounds.get("cheaper", []) for k in ("config", "than")})
        res = run(configs, a.profile, sizes=False)
        table(res)
        return check(res, bounds)
    if not a.no_build:
        build(a.profile)
    res = run([(t, s, l) for t in TIERS for s in SHADINGS for l in SETS] + INCREMENTAL + NORMAL_MAP, a.profile)
    OUT.parent.mkdir(exist_ok=True)
    doc = {
        "about": __doc__.split("\n\n", 2)[2].strip().splitlines(),
        "profile": a.profile,
        "cores": {c: CORES[c][1] for c in CORES},
        "configs": res,
    }
    OUT.write_text(json.dumps(doc, indent=1, sort_keys=False, ensure_ascii=False) + "\n")
    table(res)
    print(f"wrote {OUT.relative_to(HERE.parent)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
