#!/usr/bin/env python3
"""Whole-frame figures of the standard scene on emulated Cortex-M0 and Cortex-M4F.

    python3 measure/frame.py               # build, measure, write measure/out/frame.json, print the table
    python3 measure/frame.py --breakdown   # also: where each frame's instructions go, by pipeline stage
    python3 measure/frame.py --check       # CI: checksums, no 64-bit mul/div on the M0 frame path,
                                           # bounds of measure/frame_bounds.json; exit 1 on any failure
    python3 measure/frame.py --write-bounds  # measure, then rewrite frame_bounds.json (measured + margin)

`measure/frame/` (a `no_std` crate, its own workspace) is built for
thumbv6m-none-eabi and thumbv7em-none-eabihf (profile `release`: opt-level 3,
LTO, panic=abort), thumbv6m-none-eabi at opt-level "z" (profile `release-z`)
and for the host. Each firmware entry `frame_<config>[_band8]` renders one
complete frame of `fixshade::standard` (lighting and shader built from their
`f32` parameters, vertex stage and binning in `MeshDraw::new`, clears, set-up,
spans, band flushes or the final flush) into a `fixshade::target::Checksum`
display and returns the checksum; Unicorn (measure/cortex.py) runs it once.
The mesh transform is built once before the frames (entry `init`, `f32`) and
is not part of a frame's count (`transform_instr` reports its cost).

Two cores (issue 23, section `m0_2core`, the M0 image): entries `frame_<config>_2core_{v0,v1,
bins,c0,c1}` run the parts of one frame as two RP2040 cores would: each core half of the vertex
stage (`MeshDraw::light_vertices`), core 0 the bins (`MeshDraw::new` with `DrawOptions { lit: true, .. }`), then each core half
of the 8-row bands (`MeshDraw::share`, `Bands::render_bands`: core 0 the upper 15, core 1 the
lower 15) with its own strip, depth strip and records, into one checksum display. The frame =
the slower vertex half + the bins + the slower core's bands; `--check` requires it within
0.55 x the one-core 8-row frame (`<config>_band8`) and the one-core frame's checksum.

Per core section (`m0`, `m4f`, `m0_z` = M0 at opt-level "z", band8 only) and
configuration: instructions of the call; per lit pixel (non-black pixels of
the host's frame); peak stack (lowest written address of a painted stack,
below the initial SP, entry frame included); RAM of the frame's buffers (ELF
symbol sizes of the statics it uses); flash of the code reachable from the
entry (static call graph, see `Image`); the checksum (must equal the host's).

`--breakdown` (M0, M4F, RV32IMC; a Python block hook, a few seconds per
entry) attributes every instruction of a frame to a pipeline stage: scene
(integer transform, shader state, entry), clear, vertex stage, triangle loop /
bins, cull + set-up, clipping, rows (edge walking, span start values), spans
(depth test + colour), flush into the `DrawTarget`, runtime helpers by kind
(division, memcpy/memset, clz, 64-bit multiply, soft float) and "other". An
instruction counts for the innermost function on its call stack that names a
stage (`STAGES`): its inline stack from the DWARF line tables, then the call
sites of the dynamic call stack, so inlining does not move work between
stages. Limits: code the compiler hoists or merges across an inlined
function's boundary carries one function's debug location, and a tail call
leaves the tail-calling function off the stack. It prints the stages per
entry (with the functions that decided each), a markdown table of
`lambert_gouraud` against the floor (`breakdown_markdown`), and writes the
per-stage figures into frame.json's "breakdown" (when all sections run, or
into the existing file for the entries whose instruction counts it already
holds; a later full run keeps an entry's breakdown only while its count is
unchanged).
"""
from __future__ import annotations

import argparse
import bisect
import json
import math
import re
import subprocess
import sys
import time
from collections import Counter, defaultdict, deque
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from cortex import CORES, RETURN, Emulator, Result  # noqa: E402
from counts import callees as direct_callees, insns, is_runtime_lib, rv_indirect, rv_links, rv_relocs_in  # noqa: E402
from elftools.elf.elffile import ELFFile  # noqa: E402

FRAME_DIR = HERE / "frame"
OUT = HERE / "out" / "frame.json"
BOUNDS = HERE / "frame_bounds.json"
RAM_SIZE = 1 << 20  # measure/frame/memory.x
CONFIGS = ["lambert_gouraud", "blinn_gouraud", "blinn_phong", "blinn_phong_inc", "flat",
           "lambert_gouraud_refine"]
ENTRIES = [c + k for c in CONFIGS for k in ("", "_band8")]
# The f32 tier's frames (the RISC-V image only: what fixed point buys without an FPU),
# each against its Q14 configuration
F32_CONFIGS = {"lambert_gouraud_f32": "lambert_gouraud", "blinn_gouraud_f32": "blinn_gouraud",
               "blinn_phong_f32": "blinn_phong", "flat_f32": "flat"}
RV_ENTRIES = ENTRIES + [c + k for c in F32_CONFIGS for k in ("", "_band8")]
ALL_ENTRIES = RV_ENTRIES
# section -> (core, cargo profile, entries measured)
SECTIONS = {
    "m0": ("m0", "release", ENTRIES),
    "m4f": ("m4f", "release", ENTRIES),
    "m0_z": ("m0", "release-z", [e for e in ENTRIES if e.endswith("_band8")]),
    "rv32imc": ("rv32imc", "release", RV_ENTRIES),
}
# Issue 8, deliverable 3: none of these may be reachable from the frame path of
# an orthographic Gouraud or Phong scene on thumbv6m.
FORBIDDEN = ("u64_div_rem", "__aeabi_ldivmod", "__aeabi_uldivmod", "__aeabi_lmul",
             "__udivmoddi4", "__divdi3", "__muldi3")
CROSS_CHECK = "flat_band8"  # --check runs it with both block counters
NO_WIDE = [c + k for c in ("lambert_gouraud", "blinn_gouraud", "blinn_phong", "blinn_phong_inc", "flat")
           for k in ("", "_band8")]
# RV32IMC (issue 22): on the Q14 frame path no soft-float helper and no 64-bit division
# helper (compiler-builtins' RISC-V names; RV32IM multiplies and divides 32-bit in hardware)
RV_WIDE = ("__udivdi3", "__divdi3", "__umoddi3", "__moddi3", "__udivmoddi4", "__divmoddi4",
           "u64_div_rem", "i64_div_rem", "__muldi3")
RV_NO_FLOAT = list(ENTRIES)  # every Q14 entry is checked; RV_ENFORCED's fail, the others are reported
# every NO_WIDE entry (blinn_phong_inc too: its power table and its span set-up are in 32-bit
# multiplications, issue 19)
RV_ENFORCED = NO_WIDE
# Issue 23: the standard scene on two M0 cores in 8-row bands (`<config>_2core`): each core
# half of the vertex stage, core 0 the bins, then each core half of the bands (core 0 the
# upper, core 1 the lower), each with its own strips and records. The frame = the slower
# vertex half + the bins + the slower core's bands; target: <= 0.55 x the one-core 8-row frame.
TWO_CORE = [c for c in CONFIGS if not c.endswith("_refine")]
TWO_CORE_PARTS = ("v0", "v1", "bins", "c0", "c1")
TWO_CORE_TARGET = 0.55
PAINT = 0x4000  # bytes of stack painted below the initial SP
PATTERN = 0xA5C3_5A3C
TIMEOUT_S = 300  # seconds per call before the emulator gives up
_UC_HOOK_BLOCK = 1 << 3  # unicorn.UC_HOOK_BLOCK
# Issue 8's targets for the M0 with 8-row bands (O3 and z); reported, not enforced.
TARGETS = {"stack_bytes": 1024, "ram_plus_stack": 14 * 1024, "code_bytes_lib lambert_gouraud_band8": 12 * 1024}


def log(*a) -> None:
    print(*a, file=sys.stderr, flush=True)


# -- names ---------------------------------------------------------------------------
_LEGACY = {"$LT$": "<", "$GT$": ">", "$u20$": " ", "$C$": ",", "$RF$": "&", "$BP$": "*",
           "$SP$": "@", "$LP$": "(", "$RP$": ")", "$u5b$": "[", "$u5d$": "]", "$u3b$": ";",
           "$u7b$": "{", "$u7d$": "}", "$u27$": "'", "$u22$": '"', "$u7e$": "~", "$u2b$": "+"}


def demangle(sym: str) -> str:
    """Rust legacy (`_ZN…E`) names in Python, v0 (`_R…`) through llvm-cxxfilt;
    the hash and `.llvm.N` suffixes dropped."""
    base = sym.split(".llvm.")[0]
    if base.startswith("_ZN") and base.endswith("E"):
        s, i, parts = base[3:-1], 0, []
        while i < len(s) and s[i].isdigit():
            j = i
            while s[j].isdigit():
                j += 1
            n = int(s[i:j])
            parts.append(s[j:j + n])
            i = j + n
        if parts and re.fullmatch(r"h[0-9a-f]{16}", parts[-1]):
            parts.pop()
        out = "::".join(p[1:] if p.startswith("_$") else p for p in parts)
        for k, v in _LEGACY.items():
            out = out.replace(k, v)
        return out.replace("..", "::")
    if base.startswith("_R"):
        return _cxxfilt(base)
    return base


_CXX: dict[str, str] = {}


def _cxxfilt(sym: str) -> str:
    if sym not in _CXX:
        try:
            r = subprocess.run(["llvm-cxxfilt"], input=sym + "\n", capture_output=True, text=True)
            _CXX[sym] = re.sub(r" \(\.llvm\.\d+\)$", "", r.stdout.strip()) or sym
        except FileNotFoundError:
            _CXX[sym] = sym
    return _CXX[sym]


def is_soft_float(name: str) -> bool:
    """Soft-float and libm code (demangled name)."""
    return (name.startswith(("__aeabi_f", "__aeabi_d", "__aeabi_i2f", "__aeabi_ui2f", "__aeabi_l2f",
                             "__aeabi_ul2f", "__aeabi_i2d", "__aeabi_ui2d", "__aeabi_l2d", "__aeabi_ul2d"))
            or re.match(r"__\w+[sd]f\d?$", name) is not None
            or "compiler_builtins::float" in name or name.startswith("libm::"))


def is_forbidden(name: str) -> bool:
    return any(f in name for f in FORBIDDEN)


def is_rv_float(name: str) -> bool:
    """RISC-V soft float (compiler-builtins: `__addsf3`, `__mulsf3`, `__fixsfsi`,
    `__floatsisf`, `__extendsfdf2`, `__eqsf2`…) and libm."""
    return is_soft_float(name) or re.match(r"__\w*[sdt]f\w*$", name) is not None


def is_rv_wide(name: str) -> bool:
    return any(f in name for f in RV_WIDE)


# -- the image: static call graph ----------------------------------------------------
class Image(Emulator):
    """An Emulator plus the image's static call graph.

    Edges of the graph (a conservative over-approximation of what a function
    can call):
    * direct: every `b`/`bl`/`b<cc>` with an immediate target in another
      function (literal pools skipped through the ELF `$t`/`$d` mapping symbols);
    * address taken: the image is linked with `--emit-relocs`, so every word
      of the code that holds an address is known (R_ARM_ABS32 in a literal
      pool, R_ARM_THM_MOVW/MOVT pairs). A function whose address a reachable
      function materialises is reachable from it; an address inside `.rodata`
      names an object (from that address up to the next address any code
      refers to, the next `.rodata` symbol or the end of the section): every
      function whose address that object holds (R_ARM_ABS32 in `.rel.rodata`)
      is reachable. This resolves the `&mut dyn DrawBand` call of
      `Bands::render` (`blx rN`): the vtable is referenced from the literal
      pool of `draw_bands::<K>`. One level only: pointers in `.rodata`
      objects pointing to further `.rodata` objects are not followed.
    The emulated run checks the graph: every function executed must be
    statically reachable from the entry (`frame.py` fails otherwise).
    """

    def __init__(self, elf, core):
        super().__init__(elf, core, ram_size=RAM_SIZE)
        self.names = {n: demangle(n) for n in self.funcs}
        self.objects: dict[str, tuple[int, int]] = {}  # data symbols: name -> (address, size)
        refs: dict[str, set[int]] = {}  # function -> addresses its code materialises
        ro_ptrs: dict[int, int] = {}  # .rodata offset -> code address stored there
        if self.riscv:  # R_RISCV_HI20 / PCREL_HI20: the whole address (cortex.py _riscv_relocs)
            for off, kind, target in self.rv_text:
                if kind in ("hi20", "pcrel_hi20"):
                    refs.setdefault(self.symbol_at(off), set()).add(target)
        with open(self.elf, "rb") as f:
            e = ELFFile(f)
            ro = e.get_section_by_name(".rodata")
            self.rodata = (ro["sh_addr"], ro["sh_addr"] + ro["sh_size"])
            symtab = e.get_section_by_name(".symtab")
            for s in symtab.iter_symbols():
                if s["st_info"]["type"] == "STT_OBJECT" and s["st_size"]:
                    self.objects.setdefault(s.name, (s["st_value"], s["st_size"]))
            movs: dict[tuple, dict] = {}
            rel = e.get_section_by_name(".rel.text")
            for r in (rel.iter_relocations() if rel and not self.riscv else []):
                off, typ = r["r_offset"], r["r_info_type"]
                fn = self.symbol_at(off)
                if typ == 2:  # R_ARM_ABS32: a literal pool word
                    refs.setdefault(fn, set()).add(self._word(off))
                elif typ in (47, 48):  # R_ARM_THM_MOVW_ABS_NC / R_ARM_THM_MOVT_ABS
                    i = next(self.cs.disasm(bytes(self.uc.mem_read(off, 4)), off))
                    reg, imm = i.op_str.split(", #")
                    movs.setdefault((fn, r["r_info_sym"], reg), {})[typ] = int(imm, 0)
            for (fn, _, _), m in movs.items():
                refs.setdefault(fn, set()).add(m.get(47, 0) | m.get(48, 0) << 16)
            rel = e.get_section_by_name(".rela.rodata" if self.riscv else ".rel.rodata")
            for r in (rel.iter_relocations() if rel else []):
                if r["r_info_type"] == (1 if self.riscv else 2):  # R_RISCV_32 / R_ARM_ABS32
                    ro_ptrs[r["r_offset"]] = self._word(r["r_offset"])
        self.refs = refs
        lo, hi = self.rodata
        bounds = {a for v in refs.values() for a in v if lo <= a < hi}
        bounds |= {a for a in ro_ptrs.values() if lo <= a < hi}
        bounds |= {a for a, _ in self.objects.values() if lo <= a < hi}
        self._ro_bounds = sorted(bounds | {hi})
        self._ro_ptrs = sorted(ro_ptrs.items())
        self._edges: dict[str, dict[str, str]] = {}

    def _word(self, addr: int) -> int:
        return int.from_bytes(bytes(self.uc.mem_read(addr, 4)), "little")

    def func_at(self, addr: int) -> str | None:
        """The function starting at code address `addr` (Thumb bit set or not)."""
        name = self.symbol_at(addr & ~1)
        return name if name in self.funcs and self.funcs[name][0] == addr & ~1 else None

    def rodata_object(self, addr: int) -> tuple[int, int]:
        i = bisect.bisect_right(self._ro_bounds, addr)
        return addr, self._ro_bounds[i] if i < len(self._ro_bounds) else self.rodata[1]

    def edges(self, fn: str) -> dict[str, str]:
        """Callee -> how (`call`, `address`, `vtable@0x…`)."""
        if fn not in self._edges:
            out = {g: "call" for g in direct_callees(self, fn)}
            for a in sorted(self.refs.get(fn, ())):
                g = self.func_at(a)
                if g and g != fn:
                    out.setdefault(g, "address")
                elif self.rodata[0] <= a < self.rodata[1]:
                    s, t = self.rodata_object(a)
                    i = bisect.bisect_left(self._ro_ptrs, (s, -1))
                    while i < len(self._ro_ptrs) and self._ro_ptrs[i][0] < t:
                        g = self.func_at(self._ro_ptrs[i][1])
                        if g and g != fn:
                            out.setdefault(g, f"vtable@{s:#x}")
                        i += 1
            self._edges[fn] = out
        return self._edges[fn]

    def reach(self, entry: str) -> dict[str, str | None]:
        """Reachable functions -> their parent on a shortest path (BFS)."""
        parent: dict[str, str | None] = {entry: None}
        todo = deque([entry])
        while todo:
            f = todo.popleft()
            for g in sorted(self.edges(f)):
                if g not in parent:
                    parent[g] = f
                    todo.append(g)
        return parent

    def chain(self, parent: dict, f: str) -> str:
        path = [f]
        while parent[path[-1]] is not None:
            path.append(parent[path[-1]])
        path.reverse()
        out = self.short(path[0])
        for a, b in zip(path, path[1:]):
            out += f" -[{self.edges(a)[b]}]-> {self.short(b)}"
        return out

    def short(self, name: str) -> str:
        d = self.names.get(name, name)
        d = re.sub(r"<[^<>]*(?:<[^<>]*(?:<[^<>]*>[^<>]*)*>[^<>]*)*>", "<…>", d) if len(d) > 90 else d
        return d

    def indirect(self, fs) -> list[str]:
        """Indirect calls (`blx rN`, `bx rN` with N ≠ lr; RISC-V: `jalr ra, rN` that is
        not a call pair) in the functions `fs`."""
        if self.riscv:
            return [f"{self.short(f)}: {i.mnemonic} {i.op_str} @ {i.address:#x}" for f in sorted(fs)
                    for i in rv_indirect(self, f)]
        return [f"{self.short(f)}: {i.mnemonic} {i.op_str} @ {i.address:#x}" for f in sorted(fs)
                for i in insns(self, f) if i.mnemonic in ("blx", "bx") and i.op_str not in ("lr",)
                and not i.op_str.startswith("#")]

    def size_of(self, fs) -> tuple[int, int]:
        total = sum(self.func_size(f) for f in fs)
        return total, total - sum(self.func_size(f) for f in fs if is_runtime_lib(f))

    def object(self, suffix: str) -> tuple[str, int]:
        for n, (_, size) in self.objects.items():
            if n == suffix or demangle(n).endswith(suffix):
                return n, size
        raise KeyError(f"no data symbol {suffix} in {self.elf}")


# -- building ------------------------------------------------------------------------
def elf(core: str, profile: str) -> Path:
    return FRAME_DIR / "target" / CORES[core][1] / profile / "frame"


def cargo(args: list[str]) -> str:
    cmd = ["cargo", *args]
    log(f"$ (cd measure/frame && {' '.join(cmd)})")
    r = subprocess.run(cmd, cwd=FRAME_DIR, capture_output=True, text=True)
    if r.returncode:
        sys.stderr.write(r.stderr)
        raise SystemExit(f"FAIL: cargo {' '.join(args)} exited with {r.returncode}")
    return r.stdout


def build() -> dict:
    t = time.time()
    cargo(["build", "--quiet", "--release", "--target", CORES["m0"][1], "--target", CORES["m4f"][1]])
    # apart: in one invocation with the Arm targets cargo gives the Arm units other -C metadata
    # (other symbol hashes), and LLVM then inlines differently (the M0 image changes)
    cargo(["build", "--quiet", "--release", "--target", CORES["rv32imc"][1]])
    cargo(["build", "--quiet", "--profile", "release-z", "--target", CORES["m0"][1]])
    host = host_reference()
    log(f"built in {time.time() - t:.0f} s")
    return host


def host_reference() -> dict:
    """The host's checksums, lit pixels and buffer needs (profile `host`: no LTO, fast to build)."""
    return json.loads(cargo(["run", "--quiet", "--profile", "host"]))


# -- running -------------------------------------------------------------------------
_NATIVE_SRC = r"""
#include <stdint.h>
/* Unicorn UC_HOOK_BLOCK callback: executions per block, indexed by the block's
   start address (Thumb: 2-byte steps) over [lo, lo + 2n). */
static uint32_t *cnt; static uint16_t *sz; static uint64_t lo, n, bad_at; static uint32_t bad;
void bc_setup(uint32_t *c, uint16_t *s, uint64_t l, uint64_t len) { cnt = c; sz = s; lo = l; n = len; bad = 0; }
uint32_t bc_bad(void) { return bad; }
uint64_t bc_bad_at(void) { return bad_at; }
void bc_block(void *uc, uint64_t addr, uint32_t size, void *user) {
    uint64_t i = (addr - lo) >> 1;
    (void)uc; (void)user;
    if (addr < lo || i >= n || size > 65535 || (sz[i] && sz[i] != size)) { bad++; bad_at = addr; return; }
    sz[i] = (uint16_t)size;
    cnt[i]++;
}
"""


class NativeCounter:
    """A block hook in C (compiled once with `cc`, cached under
    measure/frame/target/): counts executions per block start address, about
    ten times faster than a Python hook. Unicorn calls it exactly where it
    would call the Python hook; the counts are decoded afterwards with the
    same capstone block cache, so the figures are identical."""

    def __init__(self, emu: Emulator):
        import ctypes
        import hashlib
        so = FRAME_DIR / "target" / f"blockcount-{hashlib.sha1(_NATIVE_SRC.encode()).hexdigest()[:12]}.so"
        if not so.exists():
            so.parent.mkdir(parents=True, exist_ok=True)
            src = so.with_suffix(".c")
            src.write_text(_NATIVE_SRC)
            subprocess.run(["cc", "-O2", "-shared", "-fPIC", "-o", str(so), str(src)], check=True,
                           capture_output=True)
        self.ct = ctypes
        self.lib = lib = ctypes.CDLL(str(so))
        text = min(a for a, _ in emu._code), max(b for _, b in emu._code)
        self.lo, self.n = text[0] & ~1, (text[1] - (text[0] & ~1) + 1) // 2
        self.cnt = (ctypes.c_uint32 * self.n)()
        self.sz = (ctypes.c_uint16 * self.n)()
        lib.bc_setup.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_uint64, ctypes.c_uint64]
        lib.bc_bad.restype = ctypes.c_uint32
        lib.bc_bad_at.restype = ctypes.c_uint64
        uclib = sys.modules["unicorn.unicorn_py3.unicorn"].uclib
        uc = emu.uc
        uc.hook_del(emu.block_hook)
        h = ctypes.c_size_t()
        err = uclib.uc_hook_add(uc._uch, ctypes.byref(h), _UC_HOOK_BLOCK,
                                ctypes.cast(lib.bc_block, ctypes.c_void_p), None,
                                ctypes.c_uint64(1), ctypes.c_uint64(0))
        if err:
            raise RuntimeError(f"uc_hook_add: {err}")
        uc.ctl_flush_tb()

    def reset(self) -> None:
        self.ct.memset(self.cnt, 0, 4 * self.n)
        self.ct.memset(self.sz, 0, 2 * self.n)
        self.lib.bc_setup(self.cnt, self.sz, self.lo, self.n)

    def counts(self) -> dict[tuple[int, int], int]:
        if self.lib.bc_bad():
            raise RuntimeError(f"{self.lib.bc_bad()} blocks outside .text or with varying sizes"
                               f" (last at {self.lib.bc_bad_at():#x})")
        c = memoryview(self.cnt).cast("B").cast("I")
        return {(self.lo + 2 * i, self.sz[i]): v for i, v in enumerate(c) if v}


_COND = {"", "eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl", "vs", "vc", "hi", "ls", "ge", "lt", "gt", "le", "al"}


class Frame(Image):
    """Runs one frame entry. Counting: a native block hook (`NativeCounter`),
    or with `profile` the Python hook, which also records the stack at the
    deepest block entry and, per executed block, the dynamic call stack it
    ran under (for `--breakdown`: a shadow stack of call sites, pushed when a
    block ending in a call — `bl`/`blx`, RISC-V `jal`/`jalr` linking `ra` —
    is followed by a block at a function's entry, popped when a block starts
    at the innermost pending return address; a run fails unless every call
    returned). Both count every executed block's instructions (decoded once
    with capstone), so the figures are the same."""

    def __init__(self, elf, core, profile: bool = False):
        super().__init__(elf, core)
        self.profile = profile
        self.native = None
        self._ends_call: dict[tuple[int, int], tuple[int, int] | None] = {}
        self._ctxs: list[tuple[int, ...]] = [()]  # call stacks (call sites, outermost first), by id
        self._ctx_ids: dict[tuple[int, ...], int] = {(): 0}
        self._entries = {a for a, _ in self.funcs.values()}  # function entries: where a call lands
        if not profile:
            try:
                self.native = NativeCounter(self)
            except (OSError, subprocess.CalledProcessError, RuntimeError, KeyError) as err:
                log(f"  (no native block counter, {err!r}: counting in Python, slower)")

    def _on_block(self, uc, addr, size, user):
        key = (addr, size)
        self._bc[key] += 1
        if self.profile:
            # the call stack: a call ends its block; the callee's first block follows
            # (not a conditional call not taken, nor a Thumb-1 far branch `bl` inside a function)
            if self._call is not None and addr != self._call[1] and addr in self._entries:
                self._calls.append((self._call[1], self._cid))
                ctx = self._ctxs[self._cid] + (self._call[0],)
                cid = self._ctx_ids.get(ctx)
                if cid is None:
                    cid = self._ctx_ids[ctx] = len(self._ctxs)
                    self._ctxs.append(ctx)
                self._cid = cid
            elif self._calls and addr == self._calls[-1][0]:  # returned
                self._cid = self._calls.pop()[1]
            self._ctx_blocks[(addr, size, self._cid)] += 1
            call = self._ends_call.get(key, False)
            if call is False:
                call = self._ends_call[key] = self._call_at_end(addr, size)
            self._call = call
            sp = uc.reg_read(self.R_SP)
            if sp < self.min_sp[0]:  # the deepest block entry: keep the stack for a backtrace
                self.min_sp = (sp, addr, bytes(uc.mem_read(sp, self.stack_top - sp)))

    def _call_at_end(self, addr: int, size: int) -> tuple[int, int] | None:
        """(call site, return address) when the block's last instruction is a call."""
        last = list(self.cs.disasm(bytes(self.uc.mem_read(addr, size)), addr))[-1]
        m, ops = last.mnemonic, last.op_str
        if self.riscv:
            # `jal off` / `jalr rs` (one operand) link ra; `jal zero, …` is printed `j`
            rd = ops.split(",")[0].strip() if "," in ops else "ra"
            call = m in ("c.jal", "c.jalr") or (m in ("jal", "jalr") and rd == "ra")
        else:  # `bl`, `blx`, and in an IT block `blne` …, not `bls`/`blt`/`ble`/`blo` (`b` + condition)
            m = m.split(".")[0]
            call = m[1:] not in _COND and (m[:2] == "bl" and m[2:] in _COND or m[:3] == "blx" and m[3:] in _COND)
        return (last.address, last.address + last.size) if call else None

    def _block(self, addr: int, size: int) -> tuple[int, str]:
        hit = self._blocks.get((addr, size))
        if hit is None:
            code = bytes(self.uc.mem_read(addr, size))
            n = len(list(self.cs.disasm(code, addr)))
            assert sum(i.size for i in self.cs.disasm(code, addr)) == size, f"capstone stopped early at {addr:#x}"
            hit = self._blocks[(addr, size)] = (n, self.symbol_at(addr))
        return hit

    def run(self, sym: str) -> tuple[Result, int, int]:
        """(result, status word r1, peak stack bytes) of one call of `sym()`."""
        uc, top = self.uc, self.stack_top
        uc.mem_write(top - PAINT, PATTERN.to_bytes(4, "little") * (PAINT // 4))
        self.set_registers(top)
        self._bc = defaultdict(int)
        self._ctx_blocks, self._calls, self._cid, self._call = Counter(), [], 0, None
        self.min_sp = (top, 0, b"")
        if self.native:
            self.native.reset()
        uc.emu_start(self.funcs[sym][0] | self.thumb, RETURN, timeout=TIMEOUT_S * 1_000_000)
        pc = uc.reg_read(self.R_PC)
        if pc != RETURN:
            raise SystemExit(f"FAIL {self.elf.parent.parent.name} {sym}: stopped at {pc:#x} "
                             f"({self.short(self.symbol_at(pc))}) after {TIMEOUT_S} s or a fault")
        self.blocks = self.native.counts() if self.native else dict(self._bc)
        if self.profile and self._calls:  # every call returned: the shadow stack held
            raise SystemExit(f"FAIL {sym}: {len(self._calls)} calls of the shadow call stack never returned"
                             f" (innermost call site {self._ctxs[self._cid][-1]:#x})")
        insns, by_func = 0, Counter()
        for (a, n), times in self.blocks.items():
            k, name = self._block(a, n)
            insns += k * times
            by_func[name] += k * times
        raw = bytes(uc.mem_read(top - PAINT, PAINT))
        low = next((top - PAINT + i for i in range(0, PAINT, 4)
                    if int.from_bytes(raw[i:i + 4], "little") != PATTERN), top)
        if low <= top - PAINT + 64:
            raise SystemExit(f"FAIL {sym}: the stack went below the {PAINT} painted bytes")
        return Result(uc.reg_read(self.R_RET[0]), insns, by_func), uc.reg_read(self.R_RET[1]), top - low


def measure_section(section: str, host: dict, profile: set[str]) -> tuple[dict, dict]:
    """Runs the section's entries (those in `profile` with the profiling hook)."""
    core, prof, entries = SECTIONS[section]
    path = elf(core, prof)
    emu = Frame(path, core)
    if core == "m0":
        bad = emu.v6m_violations()
        if bad:
            raise SystemExit(f"FAIL {section}: ARMv7-M instructions in the M0 image: {bad[:3]}")
    if core == "rv32imc":
        bad = emu.rv32imc_violations()
        if bad:
            raise SystemExit(f"FAIL {section}: instructions beyond RV32IMC in the image: {bad[:3]}")
    r, _, _ = emu.run("init")
    if r.ret != 0:
        raise SystemExit(f"FAIL {section}: init (standard::transform) returned {r.ret}")
    transform_instr = r.insns
    # soft float and the forbidden 64-bit helpers, by the core's compiler-builtins names
    floaty, wide = (is_rv_float, is_rv_wide) if emu.riscv else (is_soft_float, is_forbidden)
    mesh_bytes = emu.object("fixshade::standard::SPHERE")[1]
    res, prof_data, profiled, slow = {}, {}, {}, None
    for ent in entries:
        t0 = time.time()
        cfg, band = ent.removesuffix("_band8"), ent.endswith("_band8")
        sym = f"frame_{ent}"
        r, status, stack = emu.run(sym)
        if ent in profile:
            if slow is None:
                slow = Frame(path, core, profile=True)
                slow.run("init")
            rp, _, _ = slow.run(sym)
            if (rp.insns, rp.by_func) != (r.insns, r.by_func):
                raise SystemExit(f"FAIL {section} {ent}: the profiling run counted {rp.insns} instructions,"
                                 f" the native counter {r.insns}")
            profiled[ent] = {"min_sp": slow.min_sp, "ctx_blocks": slow._ctx_blocks, "ctxs": list(slow._ctxs)}
        if status:
            raise SystemExit(f"FAIL {section} {ent}: status {status:#x} (1 lighting, 2 render, "
                             f"3 | needed << 8 buffer too small, 4 pixels missing)")
        checksum = f"{r.ret:#010x}"
        want = host[ent]["checksum"]
        if checksum != want:
            raise SystemExit(f"FAIL {section} {ent}: checksum {checksum} != host {want}: the emulated "
                             "frame's pixels differ from the host's (a library bug on this target)")
        # static call graph from the entry and from the per-frame path
        parent = emu.reach(sym)
        draw = [g for g in emu.edges(sym) if emu.names[g].startswith("fixshade_frame::draw_")]
        if len(draw) != 1:
            raise SystemExit(f"FAIL {section} {ent}: expected one draw_full/draw_bands callee, got {draw}")
        frame_parent = emu.reach(draw[0])
        ran = set(r.by_func)
        unreached = sorted(emu.short(f) for f in ran - set(parent))
        if unreached:
            raise SystemExit(f"FAIL {section} {ent}: executed but not statically reachable (the call "
                             f"graph misses an edge): {unreached}")
        # RAM: the statics this entry uses (ELF symbol sizes)
        ram = {
            "color": emu.object("STRIP_COLOR" if band else "FRAME_COLOR")[1],
            "depth": emu.object("STRIP_DEPTH" if band else "FRAME_DEPTH")[1],
            "cache": emu.object(f"CACHE_{cfg}")[1],
            "bins": emu.object(f"{'BINS_BAND' if band else 'BINS_FULL'}_{cfg}")[1],
            "carry": emu.object(f"CARRY_BAND_{cfg}")[1] if band else 0,
            # silhouette refinement's memory (linked by the `_refine` configurations only)
            "refine": emu.object(f"REFINE_{cfg}")[1] if cfg.endswith("_refine") else 0,
        }
        ram_min = (ram["color"] + ram["depth"] + ram["cache"] + ram["refine"] + 2 * host[ent]["bins_needed"]
                   + 6 * host[ent]["carry_needed"])
        code, code_lib = emu.size_of(parent)
        code_frame, code_frame_lib = emu.size_of(frame_parent)
        lit = host[ent]["lit_px"]
        a, _ = emu.objects[emu.object(f"TYPES_{cfg}")[0]]
        types = dict(zip(("lighting", "shader", "mesh_draw"), (emu._word(a + 4 * i) for i in range(3))))
        d = {
            "instructions": r.insns,
            "instr_per_lit_px": round(r.insns / lit, 2),
            "lit_px": lit,
            "stack_bytes": stack,
            "ram_bytes": sum(ram.values()),
            "ram": ram,
            "ram_min_bytes": ram_min,
            "code_bytes": code,
            "code_bytes_lib": code_lib,
            "code_bytes_frame": code_frame,
            "code_bytes_frame_lib": code_frame_lib,
            "mesh_bytes": mesh_bytes,
            "type_bytes": types,
            "transform_instr": transform_instr,
            "soft_float": sorted({emu.short(f) for f in parent if floaty(emu.names[f])}),
            "soft_float_frame": sorted({emu.short(f) for f in frame_parent if floaty(emu.names[f])}),
            "wide_reachable": sorted({emu.short(f) for f in parent if wide(emu.names[f])}),
            **({"wide_reachable_frame": sorted({emu.short(f) for f in frame_parent if wide(emu.names[f])})}
               if emu.riscv else {}),
            "wide_executed": {emu.short(f): n for f, n in sorted(r.by_func.items()) if wide(emu.names[f])},
            "checksum": checksum,
        }
        res[ent] = d
        prof_data[ent] = {"parent": parent, "by_func": r.by_func, "indirect": emu.indirect(parent),
                          **profiled.get(ent, {})}
        log(f"  {section:<5} {ent:<22} {r.insns:>10} instr  {time.time() - t0:5.1f} s")
    return res, {"emu": emu, "slow": slow, "entries": prof_data, "profiled": sorted(profiled)}


def measure_2core(emu: "Frame", host: dict, one: dict) -> dict:
    """The `_2core` frames on the M0 image `emu` (after the section's run: `init` done)."""
    res = {}
    for cfg in TWO_CORE:
        t0 = time.time()
        parts, stacks, reach = {}, {}, {}
        for part in TWO_CORE_PARTS:
            sym = f"frame_{cfg}_2core_{part}"
            r, status, stack = emu.run(sym)
            if status:
                raise SystemExit(f"FAIL m0 {cfg}_2core {part}: status {status:#x}")
            parts[part], stacks[part] = r.insns, stack
            reach.update(emu.reach(sym))
            ran = set(r.by_func) - set(emu.reach(sym))
            if ran:
                raise SystemExit(f"FAIL m0 {cfg}_2core {part}: executed but not statically reachable:"
                                 f" {sorted(emu.short(f) for f in ran)}")
        checksum = f"{r.ret:#010x}"
        want = host[cfg + "_band8"]["two_core"]
        if checksum != want or want != host[cfg + "_band8"]["checksum"]:
            raise SystemExit(f"FAIL m0 {cfg}_2core: checksum {checksum}, host {want}, banded frame"
                             f" {host[cfg + '_band8']['checksum']}: the two cores' frame differs")
        insns = max(parts["v0"], parts["v1"]) + parts["bins"] + max(parts["c0"], parts["c1"])
        one_core = one[cfg + "_band8"]["instructions"]
        lit = host[cfg + "_band8"]["lit_px"]
        ram = {
            "color": 2 * emu.object("STRIP_COLOR")[1],
            "depth": 2 * emu.object("STRIP_DEPTH")[1],
            "cache": emu.object(f"CACHE_{cfg}")[1],
            "bins": emu.object(f"BINS_BAND_{cfg}")[1],
            "carry": emu.object(f"CARRY_BAND_{cfg}")[1] + emu.object(f"CARRY2_{cfg}")[1],
        }
        ram_min = (ram["color"] + ram["depth"] + ram["cache"] + 2 * host[cfg + "_band8"]["bins_needed"]
                   + 2 * 6 * host[cfg + "_band8"]["carry_needed"])
        stack = {"core0": max(stacks[p] for p in ("v0", "bins", "c0")),
                 "core1": max(stacks[p] for p in ("v1", "c1"))}
        code, code_lib = emu.size_of(reach)
        res[cfg + "_2core"] = {
            "instructions": insns,
            "instr_per_lit_px": round(insns / lit, 2),
            "lit_px": lit,
            "one_core_band8_instructions": one_core,
            "ratio": round(insns / one_core, 4),
            "parts": parts,
            "stack_bytes": max(stack.values()),
            "stack": stack,
            "ram_bytes": sum(ram.values()),
            "ram": ram,
            "ram_min_bytes": ram_min,
            "code_bytes": code,
            "code_bytes_lib": code_lib,
            "code_bytes_frame_lib": code_lib,
            "soft_float_frame": sorted({emu.short(f) for f in reach if is_soft_float(emu.names[f])}),
            "wide_reachable": sorted({emu.short(f) for f in reach if is_forbidden(emu.names[f])}),
            "checksum": checksum,
        }
        log(f"  m0    {cfg + '_2core':<22} {insns:>10} instr ({insns / one_core:.3f} x one core) "
            f"{time.time() - t0:5.1f} s")
    return res


def two_core_check(res: dict) -> tuple[int, int, list[str]]:
    """Issue 23's target, and no 64-bit multiply/divide helper reachable from the two cores' frames."""
    ok = bad = 0
    lines = []
    for ent, d in res.items():
        good = d["ratio"] <= TWO_CORE_TARGET
        lines.append(f"{'ok  ' if good else 'FAIL'} m0 {ent}: {d['instructions']} instructions = "
                     f"{d['ratio']:.4f} x the one-core 8-row frame {d['one_core_band8_instructions']}"
                     f" (target <= {TWO_CORE_TARGET})")
        ok, bad = ok + good, bad + (not good)
        good = not d["wide_reachable"]
        lines.append(f"{'ok  ' if good else 'FAIL'} m0 {ent}: no 64-bit multiply/divide reachable"
                     f"{'' if good else ': ' + ', '.join(d['wide_reachable'])}")
        ok, bad = ok + good, bad + (not good)
    return ok, bad, lines


# -- breakdown -------------------------------------------------------------------------
# Where a frame's instructions go. Every executed instruction is attributed to the
# innermost *named* function on its call stack: first the instruction's inline stack
# (llvm-symbolizer --inlining: the functions inlined at that address, innermost first,
# up to the symbol that holds it), then the inline stack of each call site of the
# dynamic call stack the block ran under (`Frame`'s shadow stack), innermost first.
# The first function matching a stage's pattern decides. So a helper that matches
# nothing (`Plane::at`, `MeshTransform::clip`, a lighting function, `core::…`) counts
# for whatever called it, inlined or not: `MeshTransform::clip` for the vertex stage
# from `vertex::stage`, for binning from the classification closure. A function
# inlined into another keeps its own name in the inline stack, so inlining does not
# move instructions between stages; only code the compiler merges from two functions
# into one instruction would be attributed to the innermost of them.
# Names are matched with trailing `::{{closure}}`s removed (a closure counts as its
# function). Patterns name stage-defining functions only, robust to the span code's
# new names (`fill565_depth`, `span_depth`, … count as spans).
# Runtime helpers (compiler-builtins, libm) are reported apart, by kind, under the
# stage of their fixshade caller in `builtins_by_stage`; a memset/memclr called from
# the clear *is* the clear and counts there.
# Stage pairs one function holds (by design, not by inlining): `tri::classify` (the
# facing test and the row bounds, twice per triangle from `bins::sort`) counts as
# cull + set-up; `Affine::run` (a run's start values) as rows; `depth_runs` (cutting a
# row into passing runs) as spans.
STAGES = [
    ("clear", r"fixshade::framebuffer::(fill|clear)\w*$|fixshade::render::fill$"),
    ("vertex", r"fixshade::render::vertex::(stage|window)$|(^|<)fixshade::shade::.*::vertex$"),
    # (not `Refined::replaced`: the binning's test whether a triangle was replaced)
    ("refine", r"fixshade::render::refine::(?!Refined<.*>::replaced$)|render::draw::refinement::"),
    ("clip", r"(MeshDraw|Binned)<K,P>::clipped$|render::tri::(draw_clipped|pieces|clipped_bounds|outline|convex)$"
             r"|fixshade::raster::clip::"),
    ("setup", r"render::tri::(classify|draw|front|draw_triangle)$"
              r"|fixshade::raster::setup::Setup::|fixshade::raster::setup::Plane::(skip_rows|absolute)$"
              r"|fixshade::raster::interp::(within|oriented|corner|inverse_w)$"
              r"|fixshade::raster::interp::(Affine|Persp)<V>::(new|skip_rows)$"
              r"|fixshade::raster::edge::Walker::(new|resume|unpositioned|edge_near|edge_from|place)$"
              r"|fixshade::raster::edge::Edge::(new|guess)$"
              r"|(^|<)fixshade::shade::.*::triangle$"),
    ("rows", r"fixshade::span::rows::(rows|draw_rows|perspective_run)$|fixshade::span::rows::Runs<K>>::"
             r"|fixshade::raster::edge::Walker::(next|switch_row|more|snapshot)$"
             r"|fixshade::raster::interp::(Affine|Persp)<V>::(next_row|run|at)$"
             r"|fixshade::raster::setup::Plane::(next_row|clamped\w*)$"),
    ("spans", r"fixshade::span::depth::\w+$"
              r"|(^|<)fixshade::shade::.*::(span\w*|shade_run|run|fill\w*|pixel|walk\w*)$"),
    ("flush", r"fixshade::framebuffer::checksum::Checksum<C>::fill_contiguous\w*$"
              r"|Checksum<C> as embedded_graphics_core::draw_target::DrawTarget>::(fill_contiguous|draw_iter"
              r"|fill_solid|clear)$|fixshade::framebuffer::FullFrame<C>::flush$"
              r"|as fixshade::framebuffer::BandSink<C>>::(start|finish)$"),
    ("loop", r"fixshade::render::bins::|fixshade::render::draw::(MeshDraw|Binned)<K,P>::"
             r"|as fixshade::framebuffer::DrawBand<.*>>::draw_band$"
             r"|fixshade::framebuffer::(Bands<C>::render(_bands)?|FullFrame<C>::render|Buffers<C>::draw|check_items)$"),
    ("scene", r"^fixshade::standard::|^fixshade_frame::|^frame_\w+$|^init$|fixshade::shade::Shader<.*>::new$"
              r"|(^|<)fixshade::shade::.*::state$|fixshade::lighting::.*::(new|build|prepare|validate)$"),
]
# runtime helpers by kind (the outermost helper called from fixshade code decides)
RUNTIME = [
    ("rt_float", r"float|libm|__aeabi_[fd]|2[fd]$|[sd]f\d?$|__fix|__(pow|sqrt|fmod)"),
    ("rt_mem", r"mem(cpy|set|clr|move|cmp)"),
    ("rt_clz", r"clz"),
    ("rt_mul64", r"lmul|muldi3|int::mul::"),
    ("rt_div", r"div|mod"),
    ("rt_other", r""),
]
# in the order of a frame (the patterns' order above only settles a name two of them match)
STAGE_NAMES = ["scene", "clear", "vertex", "refine", "loop", "setup", "clip", "rows", "spans", "flush",
               *(k for k, _ in RUNTIME), "other"]
assert sorted(STAGE_NAMES) == sorted([s for s, _ in STAGES] + [k for k, _ in RUNTIME] + ["other"])
LABELS = {
    "clear": "clear", "vertex": "vertex stage", "refine": "silhouette refinement",
    "clip": "clipping", "setup": "cull + set-up", "rows": "rows (edge walking, span start values)",
    "spans": "spans (depth test + colour)", "flush": "flush into the DrawTarget",
    "loop": "triangle loop / bins", "scene": "scene (transform, shader state, entry)",
    "rt_float": "runtime: soft float, libm", "rt_mem": "runtime: memcpy/memset",
    "rt_clz": "runtime: clz", "rt_mul64": "runtime: 64-bit multiply", "rt_div": "runtime: division",
    "rt_other": "runtime: other (64-bit shifts)", "other": "other",
}
_CLOSURE = re.compile(r"(::\{\{closure\}\})+$")
_STAGE_RX = [(name, re.compile(rx)) for name, rx in STAGES]
_RUNTIME_RX = [(name, re.compile(rx)) for name, rx in RUNTIME]


def stage_of_frame(fn: str) -> str | None:
    """The stage a function name (demangled) defines, or None."""
    fn = _CLOSURE.sub("", fn)
    for name, rx in _STAGE_RX:
        if rx.search(fn):
            return name
    return None


def runtime_kind(fn: str) -> str:
    return next(name for name, rx in _RUNTIME_RX if rx.search(fn))


def _symbol_file(path: Path) -> Path:
    """RISC-V images: a copy without relocations and `.L*` local symbols (the images keep
    `.L0` labels for their relocations, and llvm-symbolizer would name the outermost
    function after them)."""
    with open(path, "rb") as f:
        if ELFFile(f)["e_machine"] != "EM_RISCV":
            return path
    out = path.with_name(path.name + ".sym")
    if not out.exists() or out.stat().st_mtime < path.stat().st_mtime:
        subprocess.run(["llvm-objcopy", "-w", "-R", ".rela*", "-N", ".L*", str(path), str(out)], check=True)
    return out


def symbolize(path: Path, addrs: list[int]) -> dict[int, list[tuple[str, str]]]:
    """address -> inline stack [(function, file:line)], innermost first."""
    inp = "".join(f"{a:#x}\n" for a in addrs)
    path = _symbol_file(path)
    out = subprocess.run(["llvm-symbolizer", "--obj", str(path), "--inlining", "--functions=linkage",
                          "--no-demangle"], input=inp, capture_output=True, text=True, check=True).stdout
    res = {}
    for a, blk in zip(addrs, out.strip("\n").split("\n\n")):
        lines = blk.splitlines()
        frames = []
        for fn, loc in zip(lines[0::2], lines[1::2]):
            fn = demangle(fn) if fn.startswith(("_ZN", "_R")) else fn
            m = re.search(r"(?:/src/|/library/)(.*)$", loc)
            frames.append((fn, m[1].rsplit(":", 1)[0] if m else loc))
        res[a] = frames
    return res


def stage_of(stack: list[tuple[str, str]]) -> str | None:
    """The stage of the innermost matching function of an inline stack (innermost first)."""
    for fn, _ in stack:
        st = stage_of_frame(fn)
        if st:
            return st
    return None


def breakdown(section: str, data: dict) -> dict:
    """entry -> {stage: instructions} (+ `builtins`: {name: instructions}, `builtins_by_stage`,
    `unattributed`: the inline stacks of what landed in "other", and diagnostics)."""
    emu = data["emu"]
    addrs = set()
    dis: dict[tuple, list[int]] = {}
    for ent in data["profiled"]:
        d = data["entries"][ent]
        for (addr, size, cid), times in d["ctx_blocks"].items():
            if (addr, size) not in dis:
                dis[(addr, size)] = [i.address for i in emu.cs.disasm(bytes(emu.uc.mem_read(addr, size)), addr)]
                addrs.update(dis[(addr, size)])
        for ctx in d["ctxs"]:
            addrs.update(ctx)
    stacks = symbolize(emu.elf, sorted(addrs))
    own: dict[int, str | None] = {}  # address -> stage of its inline stack alone

    def at(a: int) -> str | None:
        if a not in own:
            own[a] = stage_of(stacks[a])
        return own[a]

    rt = {a: is_runtime_lib(emu.symbol_at(a)) for a in addrs}
    out = {}
    for ent in data["profiled"]:
        d = data["entries"][ent]
        ctxs = d["ctxs"]
        memo: dict[tuple[int, int], tuple[str, str | None, str | None]] = {}

        def attribute(a: int, cid: int) -> tuple[str, str | None, str | None]:
            """(stage, runtime helper or None, the caller's stage for a helper)."""
            key = (a, cid)
            if key not in memo:
                chain = [a] + list(reversed(ctxs[cid]))  # the instruction, then call sites, innermost first
                helper, k = None, 0
                while k < len(chain) and rt[chain[k]]:  # a runtime helper: skip to its fixshade caller
                    helper, k = emu.symbol_at(chain[k]), k + 1
                caller = next((s for s in map(at, chain[k:]) if s), None)
                if helper is None:
                    memo[key] = (caller or "other", None, None)
                elif caller == "clear":  # the clear's memset/memclr
                    memo[key] = ("clear", helper, caller)
                else:
                    memo[key] = (runtime_kind(emu.names.get(helper, helper)), helper, caller)
            return memo[key]

        def deciding(a: int, cid: int) -> str:
            """The function whose name decided the stage (not for a runtime helper)."""
            for c in [a] + list(reversed(ctxs[cid])):
                for fn, _ in stacks[c]:
                    if stage_of_frame(fn):
                        return _CLOSURE.sub("", fn)
            return "-"

        s, by_site, lost = Counter(), Counter(), Counter()
        named: dict[str, Counter] = defaultdict(Counter)  # stage -> the function that named it
        for (addr, size, cid), times in d["ctx_blocks"].items():
            for a in dis[(addr, size)]:
                st, helper, caller = attribute(a, cid)
                s[st] += times
                named[st][emu.short(helper) if helper else deciding(a, cid)] += times
                if helper:
                    by_site[f"{caller or 'other'}: {emu.short(helper)}"] += times
                if st == "other":
                    chain = [a] + list(reversed(ctxs[cid]))
                    lost[" < ".join(fn.split("::")[-1] if len(fn) > 60 else fn
                                    for c in chain[:4] for fn, _ in stacks[c][:3])[:300]] += times
        total = sum(s.values())
        assert total == d["by_func"].total(), (ent, total, d["by_func"].total())
        b = {k: s[k] for k in STAGE_NAMES if s[k]}
        b["builtins"] = {emu.short(f): n for f, n in d["by_func"].most_common() if is_runtime_lib(f)}
        b["builtins_by_stage"] = dict(by_site.most_common())
        b["unattributed"] = dict(lost.most_common(8))
        b["stage_functions"] = {k: dict(named[k].most_common(6)) for k in STAGE_NAMES if k in named}
        b["top_functions"] = {emu.short(f)[:100]: n for f, n in d["by_func"].most_common(12)}
        b["deepest_stack"] = backtrace(emu, *d["min_sp"])
        parent = d["parent"]
        b["largest_functions"] = {emu.short(f)[:100]: emu.func_size(f) for f in
                                  sorted(parent, key=lambda f: (-emu.func_size(f), f))[:12]}
        out[ent] = b
    return out


def backtrace(emu: Image, sp: int, addr: int, mem: bytes) -> list[str]:
    """The call chain at the deepest block entry of a run, outermost first,
    each function with its approximate frame size (the distance between the
    return addresses its callee and it pushed). A stack word is taken as the
    return address into the caller when the instruction before it is a `bl`
    to the current function (or to a function that branches to it) or a `blx rN`."""
    cur, frames = emu.symbol_at(addr), [(addr, sp)]
    if emu.riscv:
        return rv_backtrace(emu, sp, addr, mem)
    for i in range(0, len(mem) - 3, 4):
        w = int.from_bytes(mem[i:i + 4], "little")
        if not w & 1 or emu.symbol_at(w & ~1)[:1] == "?":
            continue
        ret = w & ~1
        bl = next(emu.cs.disasm(bytes(emu.uc.mem_read(ret - 4, 4)), ret - 4), None)
        blx = next(emu.cs.disasm(bytes(emu.uc.mem_read(ret - 2, 2)), ret - 2), None)
        if bl is not None and bl.mnemonic == "bl":
            target = emu.symbol_at(int(bl.op_str[1:], 16))
            ok, site = target == cur or emu.edges(target).get(cur) == "call", ret - 4
        elif blx is not None and blx.mnemonic == "blx" and not blx.op_str.startswith("#"):
            ok, site = True, ret - 2
        else:
            ok = False
        if ok:
            frames.append((site, sp + i))
            cur = emu.symbol_at(site)
    st = symbolize(emu.elf, sorted({a for a, _ in frames}))
    out, below = [], emu.stack_top
    for a, at in reversed(frames):  # outermost first
        inl = " < ".join(fn.split("::")[-1] for fn, _ in st[a][:3])
        out.append(f"{emu.short(emu.symbol_at(a))} [{inl}] ~{below - at} B")
        below = at
    return out


def rv_backtrace(emu: Image, sp: int, addr: int, mem: bytes) -> list[str]:
    """`backtrace` on RISC-V: a stack word is a return address when the instruction
    before it is a call (`jalr ra, …` of an auipc+jalr pair or `c.jalr`) whose target,
    when known, is the current function or one that branches to it."""
    cur, frames = emu.symbol_at(addr), [(addr, sp)]
    for i in range(0, len(mem) - 3, 4):
        ret = int.from_bytes(mem[i:i + 4], "little")
        if ret & 1 or emu.symbol_at(ret)[:1] == "?":
            continue
        site, target = None, None
        for k in (4, 2):
            ins = next(emu.cs.disasm(bytes(emu.uc.mem_read(ret - k, k)), ret - k), None)
            if ins is not None and ins.size == k and ins.mnemonic in ("jalr", "c.jalr", "jal", "c.jal") \
                    and (k == 2 or ins.op_str.startswith("ra")):
                site = ret - k
                break
        if site is None:
            continue
        if site - 4 in emu.rv_call_at:  # auipc+jalr call: its relocation names the target
            target = next((emu.symbol_at(t) for o, kind, t in emu.rv_text if o == site - 4 and kind == "call"), None)
        if target is None or target == cur or emu.edges(target).get(cur) == "call":
            frames.append((site, sp + i))
            cur = emu.symbol_at(site)
    st = symbolize(emu.elf, sorted({a for a, _ in frames}))
    out, below = [], emu.stack_top
    for a, at in reversed(frames):  # outermost first
        inl = " < ".join(fn.split("::")[-1] for fn, _ in st[a][:3])
        out.append(f"{emu.short(emu.symbol_at(a))} [{inl}] ~{below - at} B")
        below = at
    return out


def _short_fn(fn: str) -> str:
    """A demangled name without generic arguments and crate prefix, for listings."""
    prev = None
    while prev != fn:
        prev = fn
        fn = re.sub(r"<impl [^<>]* for ([^<>]*)>", r"\1", fn)
        fn = re.sub(r"<([^<>]*) as [^<>]*>", r"\1", fn)
        fn = re.sub(r"<(?!impl )[^<>]*>", lambda m: m[0] if " as " in m[0] else "", fn)
    return fn.replace("fixshade::", "")


def print_breakdown(section: str, bd: dict, res: dict) -> None:
    print(f"\n{section}: instructions per frame by stage (the innermost function on the call stack that"
          " names a stage, inlined or not; runtime helpers rt_* apart, by kind; a memset of the clear"
          " counts as clear)")
    cols = [s for s in STAGE_NAMES if any(s in b for b in bd.values())]
    w = max(9, *(len(c) + 1 for c in cols))
    print(f"{'config':<29}" + "".join(f"{c:>{w}}" for c in cols) + f"{'total':>{w + 1}}{'other':>8}")
    for ent, b in bd.items():
        tot = res[ent]["instructions"]
        print(f"{ent:<29}" + "".join(f"{b.get(c, 0):>{w}}" for c in cols) + f"{tot:>{w + 1}}"
              f"{100 * b.get('other', 0) / tot:>7.2f}%")
    print("stages: " + "; ".join(f"{c} = {LABELS[c]}" for c in cols))
    for ent, b in bd.items():
        lit = res[ent]["lit_px"]
        print(f"\n  {section} {ent}: per lit pixel " + ", ".join(
            f"{c} {b[c] / lit:.2f}" for c in cols if c in b) + f"; total {res[ent]['instructions'] / lit:.2f}")
        top = list(b["builtins_by_stage"].items())
        print("    runtime helpers by caller stage: " + ", ".join(f"{k} {v}" for k, v in top[:8])
              + (f", … ({len(top) - 8} more, {sum(v for _, v in top[8:])} instr)" if len(top) > 8 else ""))
        if b["unattributed"]:
            print("    other (no stage on the call stack; instruction's inline stack < call sites'): "
                  + "; ".join(f"{v} {k}" for k, v in b["unattributed"].items()))
        for k, fs in b["stage_functions"].items():
            print(f"    {k}: " + "; ".join(f"{_short_fn(f)} {v}" for f, v in fs.items()))
        print("    top functions (instructions, callees excluded): "
              + "; ".join(f"{k} {v}" for k, v in b["top_functions"].items()))
        print(f"    deepest stack (outermost first; peak {res[ent]['stack_bytes']} B): "
              + " -> ".join(b["deepest_stack"]))
        print("    largest reachable functions (bytes): " + "; ".join(
            f"{k} {v}" for k, v in b["largest_functions"].items()))


def breakdown_json(bd: dict, res: dict) -> dict:
    """The machine-readable part of one section's breakdown (frame.json's "breakdown"):
    per entry, the frame's instructions and lit pixels, the instructions of each
    stage and the same per lit pixel. Deterministic: the counts of one build."""
    out = {}
    for ent, b in bd.items():
        lit, tot = res[ent]["lit_px"], res[ent]["instructions"]
        stages = {k: b[k] for k in STAGE_NAMES if k in b}
        out[ent] = {"instructions": tot, "lit_px": lit, "stages": stages,
                    "per_lit_px": {k: round(n / lit, 2) for k, n in stages.items()}}
    return out


def merge_breakdown(old: dict, new: dict, res: dict) -> tuple[dict, list[str]]:
    """frame.json's "breakdown": `new` (this run's) over `old` (the file's), each entry kept
    only while its instruction count equals the frame's in `res` (the figures it sits
    beside): a breakdown from another build is dropped, not mixed in. (merged, dropped)"""
    out: dict = {}
    dropped = []
    for src in (old, new):
        for section, per in src.items():
            for ent, d in per.items():
                if res.get(section, {}).get(ent, {}).get("instructions") == d["instructions"]:
                    out.setdefault(section, {})[ent] = d
                elif src is old:
                    dropped.append((section, ent))
    order = {s: i for i, s in enumerate(SECTIONS)}
    out = {s: dict(sorted(out[s].items(), key=lambda kv: ALL_ENTRIES.index(kv[0])))
           for s in sorted(out, key=lambda s: order.get(s, len(order)))}
    return out, [f"{s} {e}" for s, e in dropped if e not in out.get(s, {})]


# The floor's whole frame per stage, instructions per lit pixel (32 480), M0 (`m0-asm`) and
# M4F (`m4f`): from `bash ../shared/floor/run.sh` (table "The whole frame, per stage" of
# ../shared/floor/README.md; run.sh writes them to build/limit.json, which is not kept).
# The floor has no flush (it draws into its own frame buffer) and no per-frame scene set-up.
FLOOR = {"clear": (2.44, 1.55), "vertex": (1.89, 1.38), "loop": (0.42, 0.27), "setup": (8.20, 5.62),
         "rows": (13.23, 9.34), "spans": (18.99, 17.99), "total": (45.17, 36.15)}


def breakdown_markdown(bd: dict, config: str = "lambert_gouraud") -> str:
    """The per-stage table of `config` (frame.json's "breakdown" form): instructions per lit
    pixel of each stage, M0 and M4F, whole frame and 8-row bands, beside the floor's."""
    cols = [("m0", config), ("m0", config + "_band8"), ("m4f", config), ("m4f", config + "_band8")]
    got = [bd.get(s, {}).get(e) for s, e in cols]
    stages = [k for k in STAGE_NAMES if any(g and k in g["stages"] for g in got) or k in FLOOR]
    f = lambda v: "—" if v is None else f"{v:.2f}"  # noqa: E731
    head = ["per lit pixel", "M0 full", "M0 8-row", "M4F full", "M4F 8-row", "floor M0", "floor M4F"]
    out = ["| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 1)]
    for k in stages:
        row = [f(g["per_lit_px"].get(k, 0.0)) if g else "—" for g in got]
        out.append(f"| {LABELS[k]} | " + " | ".join(row + [f(v) for v in FLOOR.get(k, (None, None))]) + " |")
    tot = [f"**{g['instructions'] / g['lit_px']:.2f}**" if g else "—" for g in got]
    out.append("| **frame** | " + " | ".join(tot + [f"**{v:.2f}**" for v in FLOOR["total"]]) + " |")
    out.append("")
    out.append(
        f"`{config}`: each stage's instructions per lit pixel of the standard frame, counted in Unicorn"
        f" (`python3 measure/frame.py --breakdown {config},{config}_band8`; \"—\": not measured on this"
        " build). An instruction counts for the innermost function on"
        " its call stack, inlined or not, that names a stage; runtime helpers (compiler-builtins) are"
        " listed apart by kind, except the clear's memset. *floor*: the C/assembly reference of"
        " `../shared/floor` (`bash ../shared/floor/run.sh`), which has no flush and no per-frame scene"
        " set-up; its cull runs in set-up, the crate's in binning (`tri::classify`, counted as cull +"
        " set-up).")
    return "\n".join(out)


# -- checks ----------------------------------------------------------------------------
def call_sites(emu: Image, caller: str, callee: str) -> list[int]:
    start = emu.funcs[callee][0]
    if emu.riscv:
        return sorted({o for o, _, t in rv_relocs_in(emu, caller, ("call", "jal", "branch")) if t == start}
                      | {i.address for i, t in rv_links(emu, caller) if t == start})
    return [i.address for i in insns(emu, caller)
            if i.mnemonic.split(".")[0].startswith("b") and i.op_str == f"#{start:#x}"]


def wide_check(section: str, data: dict, res: dict) -> tuple[int, int, list[str]]:
    """No forbidden 64-bit symbol reachable from (statically) or executed by (dynamically)
    the NO_WIDE entries of an M0 section. (passed, failed, report lines): for each
    forbidden symbol, every reachable caller, a shortest chain from the entry to it
    and the source lines of its calls (inline stacks)."""
    emu, lines, ok, bad = data["emu"], [], 0, 0
    for ent in NO_WIDE:
        if ent not in data["entries"]:
            continue
        parent = data["entries"][ent]["parent"]
        found = sorted(f for f in parent if is_forbidden(emu.names[f]))
        ran = res[ent]["wide_executed"]
        if found or ran:
            bad += 1
            lines.append(f"FAIL {section} {ent}: 64-bit multiply/divide reachable: "
                         f"{[emu.short(f) for f in found]}; executed: {ran or 'none'}")
            for f in found:
                for c in sorted(c for c in parent if f in emu.edges(c) and c != f):
                    lines.append(f"     {emu.chain(parent, c)} -> {emu.short(f)}")
                    if is_runtime_lib(c):
                        continue
                    sites = call_sites(emu, c, f)
                    for a, st in symbolize(emu.elf, sites).items():
                        lines.append(f"         {a:#x}: " + " < ".join(
                            f"{emu.short(fn).split('::')[-1]} ({loc})" for fn, loc in st[:4]))
        else:
            ok += 1
            lines.append(f"ok   {section} {ent}: no 64-bit multiply/divide reachable ({len(parent)} functions) "
                         "or executed")
        ind = data["entries"][ent]["indirect"]
        if ind:
            lines.append(f"     (indirect calls `blx/bx rN`, resolved through the addresses and vtables the code refers to: {ind})")
    return ok, bad, lines


def rv_check(data: dict, res: dict) -> tuple[int, int, list[str]]:
    """RV32IMC, issue 22: no soft-float helper (`__addsf3`, `__mulsf3`, `__fixsfsi`…, libm) and
    no 64-bit division helper (`__udivdi3`, `__divdi3`, `__umoddi3`, `u64_div_rem`…) reachable
    from the entry (static call graph) or executed by the frame, for the Q14 configurations of
    the M0's rule (RV_ENFORCED = NO_WIDE: Lambert/Blinn-Phong Gouraud, both Phong kernels, flat;
    whole and 8-row). The other Q14 entries are reported as `known` (not failed):
    `lambert_gouraud_refine` divides in 64 bits."""
    emu, lines, ok, bad = data["emu"], [], 0, 0
    for ent in RV_NO_FLOAT:
        if ent not in res:
            continue
        d, e = res[ent], data["entries"][ent]
        ran = {emu.short(f): n for f, n in e["by_func"].items()
               if is_rv_float(emu.names[f]) or is_rv_wide(emu.names[f])}
        found = sorted(set(d["soft_float"]) | set(d["wide_reachable"]))
        if not found and not ran:
            ok += 1
            lines.append(f"ok   rv32imc {ent}: no soft float or 64-bit division reachable ({len(e['parent'])}"
                         " functions) or executed")
            continue
        enforced = ent in RV_ENFORCED
        bad += enforced
        per_frame = sum(ran.values())
        lines.append(f"{'FAIL' if enforced else 'known'} rv32imc {ent}: reachable {found}; executed"
                     f" {per_frame} instructions in {len(ran)} functions"
                     + ("" if enforced else " (not enforced, as on the M0)"))
        parent = e["parent"]
        for f in sorted(f for f in parent if emu.short(f) in found and not is_runtime_lib(f) or
                        emu.short(f) in found and f in emu.funcs and not any(
                            emu.short(c) in found for c in parent if f in emu.edges(c) and c != f)):
            for c in sorted(c for c in parent if f in emu.edges(c) and c != f and not is_runtime_lib(c)):
                lines.append(f"     {emu.chain(parent, c)} -> {emu.short(f)}")
    return ok, bad, lines


def bounds_check(res: dict, bounds: dict) -> tuple[int, int, list[str]]:
    ok = bad = 0
    lines = []
    for b in bounds["bounds"]:
        got = res.get(b["section"], {}).get(b["config"], {}).get(b["metric"])
        if got is None:
            bad += 1
            lines.append(f"FAIL {b['section']} {b['config']} {b['metric']}: not measured")
            continue
        good = got <= b["max"]
        ok += good
        bad += not good
        lines.append(f"{'ok  ' if good else 'FAIL'} {b['section']} {b['config']} {b['metric']} = {got}"
                     f" (bound {b['max']})")
    return ok, bad, lines


def write_bounds(res: dict) -> None:
    margin = {"instructions": 0.02, "stack_bytes": 0.10, "code_bytes": 0.05}
    # sections not measured in this run (--sections) keep their bounds
    bounds = [b for b in json.loads(BOUNDS.read_text())["bounds"] if b["section"] not in res] \
        if BOUNDS.exists() else []
    for section, per in res.items():
        if section == "host":
            continue
        for ent, d in per.items():
            for metric, m in margin.items():
                bounds.append({"section": section, "config": ent, "metric": metric,
                               "measured": d[metric], "max": math.ceil(d[metric] * (1 + m))})
    doc = {
        "about": [
            "Upper bounds for `python3 measure/frame.py --check` (exit 1 if a figure exceeds its bound).",
            "instructions: whole frame of the standard scene (one call), measured + 2 %;"
            " stack_bytes: peak stack + 10 %; code_bytes: flash reachable from the entry + 5 %; rounded up.",
            "Rewrite with `python3 measure/frame.py --write-bounds` in the commit that changes a figure"
            " (lower the bounds when an optimisation lands).",
            "The check also requires every checksum to equal the host's, and no 64-bit multiply or divide"
            " reachable from or executed by the Gouraud, Phong and flat frames on the M0 (issue 8, deliverable 3),"
            " and on rv32imc no soft float and no 64-bit division (issue 22).",
        ],
        "bounds": bounds,
    }
    BOUNDS.write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n")
    log(f"wrote {BOUNDS.relative_to(HERE.parent)} ({len(bounds)} bounds)")


# -- output ----------------------------------------------------------------------------
def table(res: dict) -> None:
    print(f"{'section':<6} {'config':<22} {'instr':>10} {'/lit px':>8} {'stack':>6} {'ram':>7} {'ram min':>7}"
          f" {'code':>6} {'lib':>6} {'frame':>6} {'checksum':>10}  soft-float in frame path / 64-bit")
    for section, per in res.items():
        if section == "host":
            continue
        for ent, d in per.items():
            print(f"{section:<6} {ent:<22} {d['instructions']:>10} {d['instr_per_lit_px']:>8.2f}"
                  f" {d['stack_bytes']:>6} {d['ram_bytes']:>7} {d['ram_min_bytes']:>7} {d['code_bytes']:>6}"
                  f" {d['code_bytes_lib']:>6} {d['code_bytes_frame_lib']:>6} {d['checksum']:>10}"
                  f"  {','.join(d['soft_float_frame']) or '-'} / {','.join(d['wide_reachable']) or '-'}")
    any_sec = next(s for s in res if s != "host")
    ent0 = next(iter(res[any_sec].values()))
    print(f"mesh (SPHERE, flash): {ent0['mesh_bytes']} B; camera converted once (f32, init; the frames build their transform in integers): "
          + ", ".join(f"{s} {next(iter(p.values()))['transform_instr']} instr" for s, p in res.items() if s not in ("host", "m0_2core")))
    print("columns: stack = peak bytes below the initial SP; ram = frame buffers as allocated (bins at"
          " bins_len, 64 resume records); ram min = bins and records at the frame's exact need; code = flash"
          " reachable from the entry; lib = without compiler-builtins/libm; frame = lib, per-frame path only"
          " (draw_full/draw_bands: no lighting construction)")
    print("\nissue 8 targets, M0 with 8-row bands (reported, not enforced):")
    for section in ("m0", "m0_z"):
        for ent, d in res.get(section, {}).items():
            if not ent.endswith("_band8"):
                continue
            s, tot = d["stack_bytes"], d["ram_bytes"] + d["stack_bytes"]
            tmin = d["ram_min_bytes"] + s
            line = (f"  {section:<5} {ent:<22} stack {s:>5} {'ok' if s <= 1024 else 'OVER'} (≤ 1024);"
                    f" buffers + stack {tot:>6} {'ok' if tot <= 14336 else 'OVER'}"
                    f" (exact-need buffers {tmin} {'ok' if tmin <= 14336 else 'OVER'}) (≤ 14336)")
            if ent == "lambert_gouraud_band8":
                c = d["code_bytes_lib"]
                line += f"; fixshade code {c} {'ok' if c <= 12288 else 'OVER'} (≤ 12288)"
            print(line)


# Issue 8's per-configuration targets (instructions per lit pixel, whole frame, O3).
# Issue 19's targets, whole frame (instructions per lit pixel, O3): (M0, M4F); its 8-row
# targets are 6-20 above these (the README's text)
PX_TARGETS = {"lambert_gouraud": (60, 45), "blinn_gouraud": (62, 46), "blinn_phong_inc": (190, 125),
              "blinn_phong": (400, 250)}
README = HERE.parent / "README.md"
TRADEOFF = HERE.parent / "docs" / "tradeoff.md"
MARK = ("<!-- frame-table:start (python3 measure/frame.py rewrites this block) -->", "<!-- frame-table:end -->")


def frame_markdown(doc: dict) -> str:
    """The whole-frame table of `measure/out/frame.json` (README and docs/tradeoff.md)."""
    m0, m4, z, rv = doc.get("m0", {}), doc.get("m4f", {}), doc.get("m0_z", {}), doc.get("rv32imc", {})
    rows = []
    for c in CONFIGS:
        b = c + "_band8"
        f = lambda d, e, k="instr_per_lit_px": (f"{d[e][k]:.0f}" if isinstance(d.get(e, {}).get(k), float)
                                               else str(d.get(e, {}).get(k, "—")))
        tgt = PX_TARGETS.get(c)
        mhz = 133e6
        fps = (f"{mhz / m0[b]['instructions']:.1f}" if b in m0 else "—")
        rows.append([f"`{c}`", f(m0, c), f(m0, b), f(m4, c), f(m4, b), f(rv, c), f(rv, b),
                     f"≤ {tgt[0]} / ≤ {tgt[1]}" if tgt else "—",
                     f(m0, b, "stack_bytes"), f(z, b, "stack_bytes"),
                     str(m0[b]["ram_min_bytes"]) if b in m0 else "—",
                     f(m0, b, "code_bytes_lib"), f(z, b, "code_bytes_lib"), fps])
    head = ["configuration", "M0 full", "M0 8-row", "M4F full", "M4F 8-row", "RV32IMC full", "RV32IMC 8-row",
            "target M0 / M4F (full)",
            "M0 stack B (O3)", "M0 stack B (z)", "M0 buffers B", "M0 code B (O3)", "M0 code B (z)",
            "fps, 133 MHz M0"]
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    ent = next(iter(m0.values()), {})
    out.append("")
    out.append(
        "Instructions per lit pixel of one whole frame of the standard scene (240 × 240 Rgb565, the 362-vertex"
        f" sphere, {ent.get('lit_px', '—')} lit pixels): clears, vertex stage, bins, set-up, spans, flushes into a"
        " checksumming `DrawTarget`; counted in Unicorn on the crate's compiled code (O3; *z*: opt-level z);"
        " every checksum equals the host's. *8-row*: through an 8-row strip and depth strip; *buffers*:"
        " strip + depth strip + vertex cache + bins + resume records at the frame's exact need; *code*: fixshade's"
        " flash reachable from the frame entry (compiler-builtins excluded); *fps*: 133 MHz ÷ instructions per"
        " frame (8-row bands), i.e. assuming one instruction per cycle — optimistic on a Cortex-M0+ (loads,"
        " branches and calls take two cycles). Mesh in flash: "
        f"{ent.get('mesh_bytes', '—')} B. Measured by `python3 measure/frame.py` (→ `measure/out/frame.json`).")
    if rv:
        out += ["", rv_markdown(rv)]
    return "\n".join(out)


# Issue 22's targets on RV32IMC (instructions per lit pixel: whole frame, 8-row bands; O3).
RV_TARGETS = {"lambert_gouraud": (60, 66), "blinn_phong_inc": (190, 205)}
RV_MHZ = 160e6  # ESP32-C3


def rv_markdown(rv: dict) -> str:
    """RV32IMC (no FPU): every Q14 configuration against the issue's targets, and what fixed
    point buys: the f32 tier's frame of the same scene, the ratio f32 ÷ Q14 (issue 22)."""
    px = lambda e: rv[e]["instr_per_lit_px"]  # noqa: E731
    head = ["configuration (Q14)", "full", "8-row", "target full / 8-row", "stack B (8-row)", "code B (8-row)",
            "`f32` tier", "`f32` full", "`f32` 8-row", "`f32` ÷ Q14 full", "`f32` ÷ Q14 8-row",
            "fps, 160 MHz (8-row)"]
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    f32_of = {q: f for f, q in F32_CONFIGS.items()}
    f32_of["blinn_phong_inc"] = "blinn_phong_f32"  # the fastest Q14 per-pixel path against f32 per pixel
    for c in CONFIGS:
        b = c + "_band8"
        if c not in rv or b not in rv:
            continue
        tgt = RV_TARGETS.get(c)
        row = [f"`{c}`", f"{px(c):.1f}", f"{px(b):.1f}", f"≤ {tgt[0]} / ≤ {tgt[1]}" if tgt else "—",
               str(rv[b]["stack_bytes"]), str(rv[b]["code_bytes_lib"])]
        g = f32_of.get(c)
        if g in rv and g + "_band8" in rv:
            gb = g + "_band8"
            row += [f"`{g}`", f"{px(g):.1f}", f"{px(gb):.1f}",
                    f"**{rv[g]['instructions'] / rv[c]['instructions']:.2f}×**",
                    f"{rv[gb]['instructions'] / rv[b]['instructions']:.2f}×"]
        else:
            row += ["—"] * 5
        row.append(f"{RV_MHZ / rv[b]['instructions']:.1f}")
        out.append("| " + " | ".join(row) + " |")
    out.append("")
    out.append(
        "**RV32IMC** (`riscv32imc-unknown-none-elf`: ESP32-C3 class, no FPU), the same frames counted in"
        " Unicorn's 32-bit RISC-V mode: instructions per lit pixel, O3; every checksum equals the host's."
        " *target*: issue 22's (not met yet: they depend on the pipeline rewrite). *`f32` tier*: the same scene"
        " lit in `f32` (soft float: compiler-builtins' `__mulsf3`, `__addsf3`, libm's `powf`, `sqrtf`) through"
        " the same pipeline; *`f32` ÷ Q14*: instructions per frame of the `f32` tier over the Q14 configuration's"
        " (`blinn_phong_inc`, the Q14 fast per-pixel path, is compared with the `f32` tier's `PhongShading`, which"
        " has no incremental form). Gouraud and flat light per vertex or per triangle (362 vertices, 360 front"
        " triangles), so the tier changes only that part of the frame; per-pixel Phong lights all 32 480 pixels."
        " *stack*, *code*: peak stack and fixshade's flash reachable from the 8-row entry (compiler-builtins"
        " excluded); *fps*: 160 MHz ÷ instructions per 8-row frame (one instruction per cycle: optimistic).")
    return "\n".join(out)


# The per-stage table of lambert_gouraud (issue 19): rewritten from frame.json's "breakdown"
# by every run that writes frame.json ("—" where an entry's breakdown is missing or stale).
STAGE_MARK = ("<!-- stage-table:start (python3 measure/frame.py --breakdown lambert_gouraud,"
              "lambert_gouraud_band8 rewrites this block) -->", "<!-- stage-table:end -->")


def rewrite_marked(path: Path, body: str, mark: tuple[str, str] = MARK) -> bool:
    """Replaces the block between `mark` in `path`; False when the markers are missing."""
    if not path.exists():
        return False
    text = path.read_text()
    a, b = mark
    i, j = text.find(a), text.find(b)
    if i < 0 or j < i:
        return False
    path.write_text(text[: i + len(a)] + "\n" + body + "\n" + text[j:])
    return True


TWO_CORE_MARK = ("<!-- two-core-table:start (python3 measure/frame.py rewrites this block) -->",
                 "<!-- two-core-table:end -->")


def two_core_markdown(doc: dict) -> str:
    """The `_2core` frames of frame.json (issue 23) as a table."""
    two = doc.get("m0_2core", {})
    n = lambda x: f"{x:,}".replace(",", " ")  # noqa: E731
    head = ["configuration", "one core, 8-row", "vertex half core 0 / core 1", "bins (core 0)",
            "bands core 0 / core 1", "two cores", "÷ one core", "per lit px", "stack B core 0 / core 1"]
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for ent, d in two.items():
        p = d["parts"]
        out.append("| " + " | ".join([
            f"`{ent.removesuffix('_2core')}`", n(d["one_core_band8_instructions"]),
            f"{n(p['v0'])} / {n(p['v1'])}", n(p["bins"]), f"{n(p['c0'])} / {n(p['c1'])}",
            f"**{n(d['instructions'])}**", f"**{d['ratio']:.3f}**", f"{d['instr_per_lit_px']:.1f}",
            f"{d['stack']['core0']} / {d['stack']['core1']}"]) + " |")
    if two:
        d = next(iter(two.values()))
        r = d["ram"]
        out += ["", "Instructions on the emulated M0 (O3), standard scene, 8-row bands; the frame = the slower"
                " vertex half + the bins + the slower core's bands (target ≤ "
                f"{TWO_CORE_TARGET} × one core: `python3 measure/frame.py --check`). Every two-core frame's"
                " checksum equals the one-core frame's. RAM of the two-core frame:"
                f" {n(d['ram_bytes'])} B as allocated ({n(r['color'])} B colour strips and {n(r['depth'])} B"
                f" depth strips for the two cores, {n(r['cache'])} B vertex cache, {n(r['bins'])} B bins,"
                f" {n(r['carry'])} B resume records), {n(d['ram_min_bytes'])} B at the exact need, plus the two"
                " stacks. Not counted: the handoff between the cores (a few FIFO messages per frame on the"
                " RP2040)."]
    return "\n".join(out)


def write_stage_tables(doc: dict) -> None:
    """The per-stage table of frame.json's "breakdown" into the README and docs/tradeoff.md."""
    for path in (README, TRADEOFF):
        if rewrite_marked(path, breakdown_markdown(doc.get("breakdown", {}), CONFIGS[0]), STAGE_MARK):
            log(f"wrote the per-stage table in {path.relative_to(HERE.parent)}")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--no-build", action="store_true", help="use the ELFs as they are (host: still run)")
    p.add_argument("--check", action="store_true", help=f"CI: checksums, 64-bit symbols, {BOUNDS.name}")
    p.add_argument("--breakdown", nargs="?", const="all", metavar="ENTRIES",
                   help="instructions per pipeline stage, M0 and M4F (slow: a Python block hook);"
                        " optionally a comma-separated list of entries, e.g. lambert_gouraud_band8,blinn_phong")
    p.add_argument("--write-bounds", action="store_true",
                   help=f"rewrite {BOUNDS.name} from this run (the sections measured; the others keep theirs)")
    p.add_argument("--sections", default=",".join(SECTIONS), help="comma-separated subset of " + ",".join(SECTIONS))
    a = p.parse_args(argv)
    t = time.time()
    host = host_reference() if a.no_build else build()
    res: dict = {}
    runs: dict = {}
    bd = set(ALL_ENTRIES if a.breakdown == "all" else (a.breakdown or "").split(",")) - {""}
    if bd - set(ALL_ENTRIES):
        p.error(f"unknown entries {sorted(bd - set(ALL_ENTRIES))}: choose from {ALL_ENTRIES}")
    for section in a.sections.split(","):
        prof = set() if section == "m0_z" else set(bd)
        if a.check and section in ("m0", "rv32imc"):
            prof.add(CROSS_CHECK)  # the native counter against the Python hook (measure_section compares)
        res[section], runs[section] = measure_section(section, host, prof)
        if section == "m0":
            res["m0_2core"] = measure_2core(runs["m0"]["emu"], host, res["m0"])
    res["host"] = {ent: {"checksum": host[ent]["checksum"]} for ent in ALL_ENTRIES}
    table(res)
    bd_doc: dict = {}
    if bd:
        for section in runs:
            if runs[section]["profiled"]:
                b = breakdown(section, runs[section])
                print_breakdown(section, b, res[section])
                bd_doc[section] = breakdown_json(b, res[section])
        if any(CONFIGS[0] in bd_doc.get(s, {}) or CONFIGS[0] + "_band8" in bd_doc.get(s, {})
               for s in ("m0", "m4f")):
            print(f"\nper stage, {CONFIGS[0]}, against the floor:\n")
            print(breakdown_markdown(bd_doc, CONFIGS[0]))
    passed = failed = 0
    lines = []
    for section in runs:
        if SECTIONS[section][0] == "m0":
            ok, bad, ls = wide_check(section, runs[section], res[section])
            passed, failed, lines = passed + ok, failed + bad, lines + ls
    print("\nno 64-bit multiply/divide on the M0 frame path (static call graph and executed):")
    print("\n".join(lines))
    if "rv32imc" in runs:
        ok, bad, ls = rv_check(runs["rv32imc"], res["rv32imc"])
        passed, failed = passed + ok, failed + bad
        print("\nRV32IMC: no soft float and no 64-bit division helper on the Q14 frame path"
              " (static call graph from the entry, and executed):")
        print("\n".join(ls))
    if "m0_2core" in res:
        ok, bad, ls = two_core_check(res["m0_2core"])
        passed, failed = passed + ok, failed + bad
        print("\ntwo M0 cores, 8-row bands (issue 23):")
        print("\n".join(ls))
    if a.check:
        ok, bad, ls = bounds_check(res, json.loads(BOUNDS.read_text()))
        print("\n".join(ls))
        passed, failed = passed + ok, failed + bad
        n = sum(len(p) for s, p in res.items() if s != "host")
        print(f"ok   {n} emulated checksums equal the host's")
        passed += n
        for section in ("m0", "rv32imc"):
            if CROSS_CHECK in runs.get(section, {}).get("profiled", []):
                passed += 1
                print(f"ok   {section} {CROSS_CHECK}: the native block counter and the Python block hook count"
                      " the same instructions per function")
        print(f"{passed} passed, {failed} failed ({time.time() - t:.0f} s)")
        return 1 if failed else 0
    if a.write_bounds:
        write_bounds(res)
    if set(a.sections.split(",")) == set(SECTIONS):
        doc = {s: res[s] for s in ("m0", "m0_2core", "m4f", "host", "m0_z", "rv32imc")}
        old = json.loads(OUT.read_text()).get("breakdown", {}) if OUT.exists() else {}
        merged, dropped = merge_breakdown(old, bd_doc, res)
        if dropped:
            log(f"  dropped the breakdown of {', '.join(dropped)} (another build: rerun with --breakdown)")
        if merged:
            doc["breakdown"] = merged
        OUT.parent.mkdir(exist_ok=True)
        OUT.write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n")
        log(f"wrote {OUT.relative_to(HERE.parent)} ({time.time() - t:.0f} s)")
        for path in (README, TRADEOFF):
            if rewrite_marked(path, frame_markdown(doc)):
                log(f"wrote the frame table in {path.relative_to(HERE.parent)}")
        if rewrite_marked(README, two_core_markdown(doc), TWO_CORE_MARK):
            log("wrote the two-core table in README.md")
        write_stage_tables(doc)
    elif bd_doc and OUT.exists():
        # a subset of the sections: only frame.json's "breakdown", for the entries whose
        # instruction counts equal the file's (the same build)
        doc = json.loads(OUT.read_text())
        merged, _ = merge_breakdown(doc.get("breakdown", {}), bd_doc, doc)
        skipped = [f"{s} {e}" for s, per in bd_doc.items() for e in per if e not in merged.get(s, {})]
        if skipped:
            log(f"  not written to {OUT.name} (its figures are from another build: run all sections):"
                f" {', '.join(skipped)}")
        if merged != doc.get("breakdown", {}):
            doc["breakdown"] = merged
            OUT.write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n")
            log(f"wrote the breakdown into {OUT.relative_to(HERE.parent)}")
            write_stage_tables(doc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
