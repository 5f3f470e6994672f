#!/usr/bin/env python3
"""Count Cortex-M and RV32IMC instructions of compiled fixshade kernels in Unicorn.

Library use::

    from cortex import Emulator, i32s
    emu = Emulator("measure/kernels/target/thumbv6m-none-eabi/release/kernels", core="m0")
    r = emu.call("dot_i32", [i32s([1, 2]), i32s([3, 4]), 2])  # bytes -> pointer in RAM
    r.ret, r.insns, r.by_func        # r0, instructions executed, {symbol: instructions}
    emu.per_item("dot_i32", make_args, 64)   # (count(64) - count(0)) / 64
    emu.slope("dot_i32", make_args, 64)      # (count(128) - count(64)) / 64
    emu.func_size("dot_i32"), emu.text_size()  # flash bytes (st_size, .text)

CLI: ``python3 measure/cortex.py`` prints a table for the kernels in KERNELS;
``python3 measure/cortex.py --selftest`` checks the instrument on built ELFs.

Instructions are counted with a block hook: every translated block is decoded
once with capstone and its instruction count cached per (address, size).
Unicorn's per-instruction code hook does not fire for Thumb IT instructions,
so it undercounts on the M4 (``--selftest`` shows by how much).

Core `rv32imc` (`riscv32imc-unknown-none-elf`: ESP32-C3 class, no FPU): Unicorn's
32-bit RISC-V mode with the SiFive E31 model (RV32IMAC: no F/D, so a float
instruction faults), capstone's RISC-V decoder with the C extension (2-byte and
4-byte instructions); ILP32 calls (a0-a7, then the stack; ra = RETURN).
"""
from __future__ import annotations

import argparse
import bisect
import re
import struct
import sys
from collections import Counter
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

import capstone
import unicorn
from elftools.elf.elffile import ELFFile
from unicorn import arm_const as A
from unicorn import riscv_const as RV

HERE = Path(__file__).resolve().parent
KERNELS_DIR = HERE / "kernels"
CORES = {  # core -> (Unicorn CPU model, Rust target)
    "m0": (A.UC_CPU_ARM_CORTEX_M0, "thumbv6m-none-eabi"),
    "m4f": (A.UC_CPU_ARM_CORTEX_M4, "thumbv7em-none-eabihf"),
    # RV32IMC (ESP32-C3 class). The E31 model is RV32IMAC: no F/D (a float
    # instruction would fault), and rv32imc_violations() checks the image for A.
    "rv32imc": (RV.UC_CPU_RISCV32_SIFIVE_E31, "riscv32imc-unknown-none-elf"),
}


def is_riscv(core: str) -> bool:
    return core.startswith("rv")
FLASH, FLASH_SIZE = 0x0000_0000, 4 << 20  # as measure/kernels/memory.x
RAM, RAM_SIZE = 0x2000_0000, 256 << 10
RETURN = 0x1000_0000  # LR target (mapped, outside the image); PC == RETURN ends a call


def short(sym: str) -> str:
    """Last path segment of a Rust v0 symbol (`_RNv...11u32_div_rem.llvm.123` ->
    `u32_div_rem`); other names unchanged."""
    base = sym.split(".llvm.")[0]
    if base.startswith("_R"):
        for m in re.finditer(r"(\d+)(_?)", base):
            if m.end() + int(m[1]) == len(base):
                return base[m.end():]
    return sym


def elf_path(core: str, profile: str = "release") -> Path:
    """Where `cargo build --profile PROFILE --target ...` puts the kernels ELF."""
    return KERNELS_DIR / "target" / CORES[core][1] / profile / "kernels"


def i32s(xs) -> bytes:
    return struct.pack(f"<{len(xs)}i", *xs)


def u32s(xs) -> bytes:
    return struct.pack(f"<{len(xs)}I", *xs)


def f32s(xs) -> bytes:
    return struct.pack(f"<{len(xs)}f", *xs)


def f32_bits(x: float) -> int:
    return struct.unpack("<I", struct.pack("<f", x))[0]


@dataclass
class Result:
    ret: int  # r0 on return
    insns: int  # instructions executed, callees (e.g. __aeabi_lmul) included
    by_func: Counter = field(default_factory=Counter)  # symbol -> instructions


class Emulator:
    gp = 0  # RISC-V: riscv-rt's __global_pointer$ (no linker relaxation uses it; set anyway)

    def __init__(self, elf: str | Path, core: str = "m0", ram_size: int = RAM_SIZE):
        """`ram_size`: bytes mapped at RAM (the image's memory.x: 256 KiB for
        the kernels, 1 MiB for measure/frame); the stack starts at its top."""
        self.core, self.elf = core, Path(elf)
        model, _ = CORES[core]
        self.riscv = is_riscv(core)
        if self.riscv:
            self.uc = uc = unicorn.Uc(unicorn.UC_ARCH_RISCV, unicorn.UC_MODE_RISCV32)
            # registers: return values, stack pointer, link register, program counter
            self.R_RET, self.R_SP, self.R_LR, self.R_PC = (RV.UC_RISCV_REG_A0, RV.UC_RISCV_REG_A1), \
                RV.UC_RISCV_REG_SP, RV.UC_RISCV_REG_RA, RV.UC_RISCV_REG_PC
            self.thumb = 0
        else:
            # Not UC_MODE_MCLASS: with it Unicorn 2 silently forces a Cortex-M33 model.
            # The M0/M4 model itself is M-profile and must be set before first use.
            self.uc = uc = unicorn.Uc(unicorn.UC_ARCH_ARM, unicorn.UC_MODE_THUMB)
            self.R_RET, self.R_SP, self.R_LR, self.R_PC = (A.UC_ARM_REG_R0, A.UC_ARM_REG_R1), \
                A.UC_ARM_REG_SP, A.UC_ARM_REG_LR, A.UC_ARM_REG_PC
            self.thumb = 1
        uc.ctl_set_cpu_model(model)
        assert uc.ctl_get_cpu_model() == model
        uc.mem_map(FLASH, FLASH_SIZE)
        uc.mem_map(RAM, ram_size)
        uc.mem_map(RETURN, 0x1000)
        # `j .` / `b .`, never reached
        uc.mem_write(RETURN, b"\x6f\x00\x00\x00" * 0x400 if self.riscv else b"\xfe\xe7" * 0x800)
        self.funcs: dict[str, tuple[int, int]] = {}  # name -> (address, st_size)
        ram_end = RAM
        with open(self.elf, "rb") as f:
            e = ELFFile(f)
            for seg in e.iter_segments("PT_LOAD"):
                # Load at the VMA: .data is then initialised without running Reset.
                v = seg["p_vaddr"]
                uc.mem_write(v, seg.data() + bytes(seg["p_memsz"] - seg["p_filesz"]))
            for sec in e.iter_sections():  # statics (not riscv-rt's .stack/.heap reservations)
                v = sec["sh_addr"]
                if sec["sh_flags"] & 2 and RAM <= v < RAM + ram_size and sec.name not in (".stack", ".heap"):
                    ram_end = max(ram_end, v + sec["sh_size"])
            self._text = e.get_section_by_name(".text")["sh_size"]
            self._code = []  # code ranges between $t/$d (Arm) or $x/$d (RISC-V) mapping symbols
            maps = []
            text_ndx = next(i for i, sec in enumerate(e.iter_sections()) if sec.name == ".text")
            for s in e.get_section_by_name(".symtab").iter_symbols():
                if s["st_info"]["type"] == "STT_FUNC" and s["st_size"]:
                    self.funcs.setdefault(s.name, (s["st_value"] & ~1, s["st_size"]))
                if s.name[:2] in ("$t", "$d", "$a", "$x") and (not self.riscv or s["st_shndx"] == text_ndx):
                    maps.append((s["st_value"], s.name[1]))  # RISC-V: .text's own ($d of .rodata too)
                if s.name == "__global_pointer$":
                    self.gp = s["st_value"]
            maps.sort()
            text = e.get_section_by_name(".text")
            lo, end = text["sh_addr"], text["sh_addr"] + text["sh_size"]
            for (a, kind), (b, _) in zip(maps, maps[1:] + [(end, "")]):
                if kind in ("t", "x") and lo <= a < end:
                    self._code.append((a, min(b, end)))
        if self.riscv:
            self._riscv_relocs()
        self._starts = sorted((a, n) for n, (a, _) in self.funcs.items())
        self._sizes = {n: s for n, (_, s) in self.funcs.items()}
        self.arena = (ram_end + 7) & ~7  # inputs go here, the stack at the top of RAM
        self.stack_top = RAM + ram_size
        if self.riscv:
            self.cs = capstone.Cs(capstone.CS_ARCH_RISCV, capstone.CS_MODE_RISCV32 | capstone.CS_MODE_RISCVC)
        else:
            self.cs = capstone.Cs(capstone.CS_ARCH_ARM, capstone.CS_MODE_THUMB | capstone.CS_MODE_MCLASS)
        self._blocks: dict[tuple[int, int], tuple[int, str]] = {}
        self._insns, self._by_func, self.limit = 0, Counter(), 0
        self.block_hook = uc.hook_add(unicorn.UC_HOOK_BLOCK, self._on_block)  # handle, for hook_del
        # FPU: Unicorn's Cortex-M4 model executes VFP with no CPACR set-up (and
        # 0xE000ED88 is not mapped); --selftest checks that vmla/vmul.f32 run.

    # RISC-V relocation types (the images are linked with --emit-relocs)
    RV_CALLS = {16: "branch", 17: "jal", 18: "call", 19: "call", 44: "branch", 45: "jal"}
    RV_ADDRS = {23: "pcrel_hi20", 26: "hi20"}  # the upper half names the whole address (S + A)

    def _riscv_relocs(self) -> None:
        """`self.rv_text`: [(offset, kind, target)] of `.rela.text` (kind: call, jal,
        branch, pcrel_hi20, hi20); `self.rv_call_at`: offsets of `auipc`+`jalr`
        call pairs (R_RISCV_CALL*). No relaxation: the objects carry no R_RISCV_RELAX."""
        self.rv_text, self.rv_call_at = [], set()
        with open(self.elf, "rb") as f:
            e = ELFFile(f)
            rel = e.get_section_by_name(".rela.text")
            if rel is None:
                raise SystemExit(f"{self.elf}: no .rela.text: link the RISC-V image with --emit-relocs")
            symtab = e.get_section_by_name(".symtab")
            value = [s["st_value"] for s in symtab.iter_symbols()]
            for r in rel.iter_relocations():
                t = r["r_info_type"]
                assert t != 51, f"{self.elf}: R_RISCV_RELAX: linker relaxation is not handled"
                kind = self.RV_CALLS.get(t) or self.RV_ADDRS.get(t)
                if kind:
                    self.rv_text.append((r["r_offset"], kind, (value[r["r_info_sym"]] + r["r_addend"]) & 0xFFFF_FFFF))
                if t in (18, 19):
                    self.rv_call_at.add(r["r_offset"])
        self.rv_text.sort()

    # -- counting --------------------------------------------------------------
    def _on_block(self, uc, addr, size, _):
        hit = self._blocks.get((addr, size))
        if hit is None:
            code = bytes(uc.mem_read(addr, size))
            insns = list(self.cs.disasm(code, addr))
            assert sum(i.size for i in insns) == size, f"capstone stopped early in block {addr:#x}+{size}"
            hit = self._blocks[(addr, size)] = (len(insns), self.symbol_at(addr))
        self._insns += hit[0]
        self._by_func[hit[1]] += hit[0]
        if self._insns > self.limit:
            uc.emu_stop()

    def symbol_at(self, addr: int) -> str:
        i = bisect.bisect_right(self._starts, (addr, "\uffff")) - 1
        if i >= 0:
            start, name = self._starts[i]
            if addr < start + self._sizes[name]:
                return name
        return f"?{addr:#x}"

    # -- calling ---------------------------------------------------------------
    def call(self, sym: str, args=(), limit: int = 50_000_000) -> Result:
        """Call `sym` (AAPCS: r0-r3, then the stack). An arg is an int or bytes;
        bytes are copied into RAM (8-byte aligned) and passed as a pointer."""
        uc, at, words = self.uc, self.arena, []
        for a in args:
            if isinstance(a, (bytes, bytearray)):
                uc.mem_write(at, bytes(a))
                words.append(at)
                at = (at + len(a) + 7) & ~7
            else:
                words.append(a & 0xFFFF_FFFF)
        nreg = 8 if self.riscv else 4  # argument registers: a0-a7 / r0-r3
        sp = self.stack_top - 4 * max(0, len(words) - nreg)
        sp &= ~15 if self.riscv else ~7
        assert at < sp - 0x1000, "inputs overflow into the stack"
        if len(words) > nreg:
            uc.mem_write(sp, u32s(words[nreg:]))
        self.set_registers(sp, words)
        self._insns, self._by_func, self.limit = 0, Counter(), limit
        start = self.funcs[sym][0]
        uc.emu_start(start | self.thumb, RETURN)
        pc = uc.reg_read(self.R_PC)
        if pc != RETURN:
            raise RuntimeError(f"{sym}: stopped at {pc:#x} ({self.symbol_at(pc)}) after {self._insns} insns")
        return Result(uc.reg_read(self.R_RET[0]), self._insns, self._by_func)

    def set_registers(self, sp: int, words=()) -> None:
        """Every integer register cleared, the first arguments in r0-r3 / a0-a7,
        SP, the return address RETURN (and Thumb state, gp)."""
        uc = self.uc
        if self.riscv:
            for r in range(RV.UC_RISCV_REG_X1, RV.UC_RISCV_REG_X31 + 1):
                uc.reg_write(r, 0)
            for i, w in enumerate(words[:8]):
                uc.reg_write(RV.UC_RISCV_REG_A0 + i, w)
            uc.reg_write(RV.UC_RISCV_REG_GP, self.gp)
            uc.reg_write(RV.UC_RISCV_REG_SP, sp)
            uc.reg_write(RV.UC_RISCV_REG_RA, RETURN)
            return
        for r in range(13):
            uc.reg_write(A.UC_ARM_REG_R0 + r, words[r] if r < min(4, len(words)) else 0)
        uc.reg_write(A.UC_ARM_REG_SP, sp)
        uc.reg_write(A.UC_ARM_REG_LR, RETURN | 1)
        uc.reg_write(A.UC_ARM_REG_XPSR, 1 << 24)  # Thumb state, flags clear

    def count(self, sym: str, args=()) -> int:
        return self.call(sym, args).insns

    def per_item(self, sym: str, make_args, n: int) -> Fraction:
        """(count(n) - count(0)) / n, with make_args(n) -> argument list."""
        return Fraction(self.count(sym, make_args(n)) - self.count(sym, make_args(0)), n)

    def slope(self, sym: str, make_args, n: int) -> Fraction:
        """(count(2n) - count(n)) / n: the loop cost alone, without the fixed
        cost of entering the loop (use n a multiple of the unroll factor)."""
        return Fraction(self.count(sym, make_args(2 * n)) - self.count(sym, make_args(n)), n)

    # -- code size -------------------------------------------------------------
    def func_size(self, sym: str) -> int:
        """Flash bytes of one function (ELF st_size)."""
        return self.funcs[sym][1]

    def text_size(self) -> int:
        return self._text

    # -- checks ----------------------------------------------------------------
    def rv32imc_violations(self) -> list[str]:
        """Instructions in the image's code that RV32IMC lacks (F/D, A), or bytes
        capstone cannot decode as RV32IMC."""
        bad = []
        for a, b in self._code:
            n = a
            for i in self.cs.disasm(bytes(self.uc.mem_read(a, b - a)), a):
                n = i.address + i.size
                m = i.mnemonic.removeprefix("c.")
                if (m.startswith("f") and not m.startswith("fence")) or m.startswith(("amo", "lr.", "sc.")):
                    bad.append(f"{i.address:#x} {self.symbol_at(i.address)}: {i.mnemonic} {i.op_str}")
            if n != b:
                bad.append(f"{n:#x} {self.symbol_at(n)}: not decodable as RV32IMC")
        return bad

    def v6m_violations(self) -> list[str]:
        """Instructions in the image's Thumb code that ARMv6-M (M0) lacks."""
        ok32 = {"bl", "dmb", "dsb", "isb", "mrs", "msr"}
        bad = []
        for a, b in self._code:
            for i in self.cs.disasm(bytes(self.uc.mem_read(a, b - a)), a):
                if (i.size == 4 and i.mnemonic not in ok32) or i.mnemonic.startswith(("it", "cbz", "cbnz")):
                    bad.append(f"{i.address:#x} {self.symbol_at(i.address)}: {i.mnemonic} {i.op_str}")
        return bad


# Placeholder kernels of measure/kernels/src/main.rs: name -> make_args(n).
def _data(n, seed=1):
    return [((i * 7919 + seed * 104729) % 20001) - 10000 for i in range(n)]


KERNELS = {
    "dot_i32": lambda n: [i32s(_data(n)), i32s(_data(n, 2)), n],
    "dot_q16_i64": lambda n: [i32s(_data(n)), i32s(_data(n, 2)), n],
    "div_i32": lambda n: [i32s(_data(n)), i32s([x | 1 for x in _data(n, 2)]), n],
    "scale_f32": lambda n: [f32s([x / 1000 for x in _data(n)]), n, f32_bits(0.75)],
    "clamp_sum": lambda n: [i32s(_data(n)), n, -5000, 5000],
}

# Kernels whose instruction count does not depend on the data: exactly affine in n
# for n a multiple of 64 (LLVM unrolls by up to 16 at opt-level 3).
LINEAR = {"dot_i32", "dot_q16_i64"}


def table(profile: str, n: int) -> None:
    print(f"profile={profile}  n={n}  per-item = (count(n) - count(0)) / n,"
          f"  slope = (count({2 * n}) - count({n})) / {n}")
    print(f"{'kernel':<12} {'core':<4} {'bytes':>6} {'count(0)':>9} {f'count({n})':>10} {'per-item':>9} {'slope':>7}"
          "  callees at n")
    for core in CORES:
        emu = Emulator(elf_path(core, profile), core)
        for name, make in KERNELS.items():
            r0, rn = emu.call(name, make(0)), emu.call(name, make(n))
            callees = ", ".join(f"{short(k)} {v}" for k, v in rn.by_func.most_common() if k != name)
            print(f"{name:<12} {core:<4} {emu.func_size(name):>6} {r0.insns:>9} {rn.insns:>10} "
                  f"{(rn.insns - r0.insns) / n:>9.2f} {float(emu.slope(name, make, n)):>7.2f}  {callees}")
        print(f"{'.text':<12} {core:<4} {emu.text_size():>6}")


def code_hook_count(emu: Emulator, sym: str, args) -> tuple[int, Counter]:
    """The naive UC_HOOK_CODE count, and what it missed ({mnemonic: times})
    relative to decoding every executed block, for comparison only."""
    seen, ran = Counter(), Counter()

    def on_block(uc, addr, size, _):
        for i in emu.cs.disasm(bytes(uc.mem_read(addr, size)), addr):
            ran[(i.address, i.mnemonic)] += 1

    h = [emu.uc.hook_add(unicorn.UC_HOOK_CODE, lambda uc, addr, *_: seen.update((addr,))),
         emu.uc.hook_add(unicorn.UC_HOOK_BLOCK, on_block)]
    emu.uc.ctl_flush_tb()  # blocks translated before the hooks existed would not call them
    try:
        emu.call(sym, args)
    finally:
        for x in h:
            emu.uc.hook_del(x)
        emu.uc.ctl_flush_tb()
    missed = Counter()
    for (addr, mnem), times in ran.items():
        if times > seen[addr]:
            missed[mnem] += times - seen[addr]
    return sum(seen.values()), missed


def selftest(profile: str) -> int:
    failed = passed = 0

    def check(ok, what):
        nonlocal failed, passed
        failed += not ok
        passed += bool(ok)
        print(f"{'ok  ' if ok else 'FAIL'} {what}")

    for core in CORES:
        path = elf_path(core, profile)
        emu, emu2 = Emulator(path, core), Emulator(path, core)
        ns = (0, 64, 128, 192, 256, 512)
        for name, make in KERNELS.items():
            c = [emu.count(name, make(n)) for n in ns]
            again = [emu2.count(name, make(n)) for n in ns] + [emu.count(name, make(n)) for n in ns]
            check(again == c + c, f"{core} {name}: deterministic {c}")
            if name in LINEAR:  # data-independent control flow
                slope = Fraction(c[-1] - c[1], ns[-1] - ns[1])
                fixed = c[1] - c[0] - slope * ns[1]
                check(all(ci - c[0] == fixed + slope * n for ci, n in zip(c[1:], ns[1:])),
                      f"{core} {name}: count(n) - count(0) == {fixed} + {slope}*n for n = 64..512")
        # Results agree with Python on the slow paths (soft/hard float, library calls).
        a, b = _data(64), [x | 1 for x in _data(64, 2)]
        want = sum(int(x / y) for x, y in zip(a, b)) & 0xFFFF_FFFF
        check(emu.call("div_i32", KERNELS["div_i32"](64)).ret == want, f"{core} div_i32 result")
        want = sum(((x * y) >> 16) for x, y in zip(_data(64), _data(64, 2))) & 0xFFFF_FFFF
        check(emu.call("dot_q16_i64", KERNELS["dot_q16_i64"](64)).ret == want, f"{core} dot_q16_i64 result")
        fk = emu.call("scale_f32", [f32s([1.5, 2.0, -0.25]), 3, f32_bits(2.0)])
        check(fk.ret == f32_bits(6.5), f"{core} scale_f32 result (FPU/soft-float executes)")
        naive, missed = code_hook_count(emu, "clamp_sum", KERNELS["clamp_sum"](64))
        block = emu.count("clamp_sum", KERNELS["clamp_sum"](64))
        check(block == naive + sum(missed.values()),
              f"{core} clamp_sum(64): block hook {block}, code hook {naive}, missed {dict(missed)}")
        if core == "rv32imc":
            check(naive == block and not missed, f"rv32imc: code hook == block hook ({naive}, nothing predicated)")
            bad = emu.rv32imc_violations()
            check(not bad and emu._code, f"rv32imc: only RV32IMC instructions in {len(emu._code)} code ranges {bad[:3]}")
            # compressed instructions: both sizes execute and each counts once; dot_i32 by hand
            # (llvm-objdump of the release image): loop c.lw, c.lw, c.addi, mul, c.add, c.addi, bne
            ran = Counter()
            h = emu.uc.hook_add(unicorn.UC_HOOK_CODE, lambda uc, addr, size, _: ran.update((size,)))
            emu.uc.ctl_flush_tb()
            try:
                c0, c64 = (emu.count("dot_i32", KERNELS["dot_i32"](n)) for n in (0, 64))
            finally:
                emu.uc.hook_del(h)
                emu.uc.ctl_flush_tb()
            check(ran[2] > 0 and ran[4] > 0 and ran[2] + ran[4] == c0 + c64,
                  f"rv32imc: dot_i32 ran {ran[2]} 2-byte (C) and {ran[4]} 4-byte instructions = block count {c0 + c64}")
            body = [i.mnemonic for i in emu.cs.disasm(bytes(emu.uc.mem_read(*emu.funcs["dot_i32"])),
                                                        emu.funcs["dot_i32"][0])]
            loop = body[body.index("c.lw"):body.index("bne") + 1] if "bne" in body and "c.lw" in body else []
            check(len(loop) == 7 and (c64 - c0) % 64 in (0, 6, 7, 8) and (c64 - c0) // 64 == 7,
                  f"rv32imc: dot_i32 loop {loop}: count(64) - count(0) = {c64 - c0} = 64 x 7 + {(c64 - c0) - 448}")
            sf = emu.call("scale_f32", KERNELS["scale_f32"](8)).by_func
            check(any("mulsf3" in k for k in sf) and any("addsf3" in k for k in sf),
                  f"rv32imc: scale_f32 calls soft float {sorted(short(k) for k in sf if k != 'scale_f32')}")
            # the E31 model has no FPU: fadd.s must fault
            at = emu.arena + 0x100
            emu.uc.mem_write(at, (0x00107053).to_bytes(4, "little") + b"\x82\x80")  # fadd.s f0,f0,f1; ret
            try:
                emu.set_registers(emu.stack_top)
                emu.uc.emu_start(at, RETURN, count=2)
                check(False, "rv32imc: the E31 model faults on fadd.s (no F extension)")
            except unicorn.UcError as err:
                check(True, f"rv32imc: the E31 model faults on fadd.s ({err})")
        elif core == "m0":
            check(naive == block, "m0: code hook == block hook (no IT on v6-M)")
            bad = emu.v6m_violations()
            check(not bad and emu._code, f"m0: no ARMv7-M instructions in {len(emu._code)} Thumb ranges {bad[:3]}")
            lm = emu.call("dot_q16_i64", KERNELS["dot_q16_i64"](8)).by_func
            dv = emu.call("div_i32", KERNELS["div_i32"](8)).by_func
            check(lm["__aeabi_lmul"] > 0 and dv["__aeabi_idiv"] > 0,
                  f"m0: __aeabi_lmul ({lm['__aeabi_lmul']}) and __aeabi_idiv ({dv['__aeabi_idiv']}) counted")
        else:
            cond = ("eq", "ne", "hs", "lo", "mi", "pl", "vs", "vc", "hi", "ls", "ge", "lt", "gt", "le")
            check(missed and all(m.split(".")[0].endswith(cond) for m in missed),
                  "m4f: the code hook misses only predicated (IT-block) instructions")
            sf = emu.call("scale_f32", KERNELS["scale_f32"](8)).by_func
            check(len(emu.v6m_violations()) > 0, "m4f image: the v6-M check does flag Thumb-2")
            check(set(sf) == {"scale_f32"}, f"m4f: scale_f32 calls nothing (hard float) {dict(sf)}")
            ran = {i.mnemonic for (a, n) in emu._blocks for i in emu.cs.disasm(bytes(emu.uc.mem_read(a, n)), a)}
            check({"vmla.f32", "vmul.f32", "vfma.f32"} & ran, "m4f: an FPU multiply executed")
            try:
                Emulator(path, "m0").call("dot_q16_i64", KERNELS["dot_q16_i64"](8))
                check(False, "m0 model rejects this M4 image's Thumb-2 (smull)")
            except unicorn.UcError as err:
                check(True, f"m0 model rejects this M4 image's Thumb-2 ({err})")
    print(f"selftest: {passed} passed, {failed} failed")
    return 1 if failed else 0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--profile", default="release", help="cargo profile: release (opt 3) or release-s")
    p.add_argument("-n", type=int, default=64, help="items per call")
    p.add_argument("--selftest", action="store_true")
    a = p.parse_args(argv)
    if a.selftest:
        return selftest(a.profile)
    table(a.profile, a.n)
    return 0


if __name__ == "__main__":
    sys.exit(main())
