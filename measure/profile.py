#!/usr/bin/env python3
"""Where the instructions of one kernel go: an instruction-level profile of
count(n) − count(0), attributed to source lines through the ELF's debug info
(llvm-symbolizer, inlined frames included).

    python3 measure/profile.py span_q14_2_phong_dir_blinn            # M0, n = 64
    python3 measure/profile.py span_q14_2_phong_dir_blinn --core m4f -n 64 --top 40
    python3 measure/profile.py span_q14_2_phong_dir_blinn --asm      # hot instructions

Prints, per pixel (divided by n): instructions per called function (symbol),
per innermost source location (file:line function), and per library function in
the inline stack (every frame of the stack is credited, so the rows of that
table overlap: `powi` includes the `mul`s it inlines).
"""
from __future__ import annotations

import argparse
import subprocess
import sys
from collections import Counter
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from cortex import Emulator, elf_path, short  # noqa: E402


class Profiler(Emulator):
    """An Emulator that also counts executions per block."""

    def __init__(self, *a, **k):
        super().__init__(*a, **k)
        self.blocks = Counter()

    def _on_block(self, uc, addr, size, user):
        self.blocks[(addr, size)] += 1
        super()._on_block(uc, addr, size, user)


def per_insn(emu: Profiler, sym: str, args) -> Counter:
    emu.blocks = Counter()
    emu.call(sym, args)
    c = Counter()
    for (addr, size), times in emu.blocks.items():
        for i in emu.cs.disasm(bytes(emu.uc.mem_read(addr, size)), addr):
            c[(i.address, i.mnemonic, i.op_str)] += times
    return c


def symbolize(elf: Path, addrs: list[int]) -> dict[int, list[tuple[str, str]]]:
    """address -> inline stack [(function, file:line)], innermost first."""
    inp = "".join(f"{a:#x}\n" for a in addrs)
    out = subprocess.run(["llvm-symbolizer", "--obj", str(elf), "--inlining", "--demangle",
                          "--relative-address", "--functions=short"],
                         input=inp, capture_output=True, text=True, check=True).stdout
    res, blocks = {}, out.strip("\n").split("\n\n")
    for a, blk in zip(addrs, blocks):
        lines = blk.splitlines()
        frames = []
        for f, loc in zip(lines[0::2], lines[1::2]):
            path, *rest = loc.rsplit(":", 2)
            p = Path(path)
            parts = p.parts
            if "src" in parts:  # fixshade/src/num/q14.rs -> num/q14.rs
                k = len(parts) - 1 - parts[::-1].index("src")
                tag = "/".join(parts[k - 1:]) if "kernels" in parts[k - 1] else "/".join(parts[k + 1:])
                crate = parts[k - 1]
                tag = tag if crate in ("main", "kernels") else f"{crate}:{tag}"
            else:
                tag = p.name
            frames.append((f, f"{tag}:{rest[0] if rest else '?'}"))
        res[a] = frames
    return res


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("sym")
    p.add_argument("--core", default="m0")
    p.add_argument("--profile", default="release")
    p.add_argument("-n", type=int, default=64)
    p.add_argument("--top", type=int, default=25)
    p.add_argument("--asm", action="store_true", help="also list the hottest instructions")
    a = p.parse_args(argv)
    elf = elf_path(a.core, a.profile)
    emu = Profiler(elf, a.core)
    buf = bytes(2 * max(a.n, 64 * 64))
    c0, cn = per_insn(emu, a.sym, [0, buf]), per_insn(emu, a.sym, [a.n, buf])
    diff = Counter({k: v - c0.get(k, 0) for k, v in cn.items() if v != c0.get(k, 0)})
    total = sum(diff.values())
    print(f"{a.sym} on {a.core}: {total} instructions for n = {a.n}: {total / a.n:.2f} per item")
    stacks = symbolize(elf, sorted({k[0] for k in diff}))

    def show(title, counter):
        print(f"\n{title}")
        for k, v in counter.most_common(a.top):
            print(f"  {v / a.n:8.2f}  {k}")

    by_sym, by_line, by_frame, by_mnem = Counter(), Counter(), Counter(), Counter()
    for (addr, mnem, ops), v in diff.items():
        by_sym[short(emu.symbol_at(addr))[:80]] += v
        fr = stacks[addr]
        by_line[f"{fr[0][1]}  {fr[0][0][:60]}"] += v
        for f in {f for f, _ in fr}:
            by_frame[f[:100]] += v
        by_mnem[mnem] += v
    show("per called function (per item)", by_sym)
    show("per innermost source line (per item)", by_line)
    show("per function in the inline stack, inclusive (per item)", by_frame)
    show("per mnemonic (per item)", by_mnem)
    if a.asm:
        print("\nhottest instructions (per item): address, symbol, instruction, innermost source")
        for (addr, mnem, ops), v in diff.most_common(a.top * 3):
            print(f"  {v / a.n:6.2f}  {addr:#07x} {short(emu.symbol_at(addr))[:30]:<30} {mnem} {ops:<28} "
                  f"{stacks[addr][0][1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
