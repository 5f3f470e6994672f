#!/usr/bin/env python3
"""The speed/accuracy report: error next to Cortex-M cost for every configuration.

Merges measure/out/host.json (error of a 240×240 lit sphere against the f64
reference, host ns per pixel; written by `cargo bench --bench tradeoff`) with
measure/out/counts.json (Cortex-M0 / M4F / RV32IMC instruction counts and code sizes in
Unicorn; written by `python3 measure/counts.py`) and writes docs/tradeoff.md
(tables, Phong vs Gouraud, the cost of the light set, the targets) and
docs/img/tradeoff.svg (error against M0 / M4F instructions per pixel, Pareto fronts).

    python3 measure/tradeoff.py            # run both producers first (a few minutes), then write
    python3 measure/tradeoff.py --no-run   # use the JSON files as they are

Standard library only. The output is deterministic apart from the date line of
docs/tradeoff.md. A configuration missing from one input shows "—" there.
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import shlex
import subprocess
import sys
from pathlib import Path
from xml.sax.saxutils import escape

ROOT = Path(__file__).resolve().parent.parent
COUNTS = ROOT / "measure" / "out" / "counts.json"
HOST = ROOT / "measure" / "out" / "host.json"
MD = ROOT / "docs" / "tradeoff.md"
SVG = ROOT / "docs" / "img" / "tradeoff.svg"

# Fixed orders; values not listed here (new tiers, shadings, light sets) follow, sorted.
TIERS = ["q14_1", "q14_2", "q30", "f32", "f32fast"]
SHADINGS = ["flat", "gouraud", "phong", "phong_inc"]
LIGHTS = ["dir_diffuse", "dir_blinn", "dir_phong", "point4_blinn", "spot_blinn"]
CORES = ["m0", "m4f"]
CORE_NAME = {"m0": "Cortex-M0", "m4f": "Cortex-M4F", "rv32imc": "RV32IMC"}
# RV32IMC (riscv32imc-unknown-none-elf, no FPU: ESP32-C3 class): a column of the tables and
# the section "Fixed point without an FPU"; not in the plot, the Phong-Gouraud ratios or the M0 targets
RV = "rv32imc"

TIER_DESC = {
    "q14_1": "`Q14<1>`: Q2.14, one Newton step of the inverse square root",
    "q14_2": "`Q14<2>` (= `Q14`, the fast tier): Q2.14, two Newton steps",
    "q30": "`Q30<3>`: Q2.30, three Newton steps",
    "f32": "`f32` with `libm` sqrt and division",
    "f32fast": "`F32Fast<2>`: f32 with a bit-trick inverse square root and two Newton steps",
}
LIGHT_DESC = {
    "dir_diffuse": "one directional light, Lambert diffuse only",
    "dir_blinn": "one directional light, Blinn-Phong specular (n = 32)",
    "dir_phong": "one directional light, Phong (reflection vector) specular",
    "point4_blinn": "four point lights with attenuation (1, 0.05, 0.01), Blinn-Phong",
    "spot_blinn": "one spot light (exponent 8, cutoff 30°), Blinn-Phong",
}

PLOT_LIGHTS = "dir_blinn"  # the light set of the plot and of the targets
FAST_TIERS = ["q14_1", "q14_2"]  # the Q14 tiers the targets are about (Q14 = Q14<2>)
# Targets from the design discussion (measure/bounds.json "target"; instructions per
# pixel of Kernel::span, span_64, Cortex-M0, one directional Blinn-Phong light).
TARGET_PHONG = 40
TARGET_GOURAUD = 10
TARGET_RATIO = 3
REFERENCE = {"phong_inc": "phong"}  # compared with the Phong reference (benches/tradeoff.rs)
SEED_RATIO = "6–8×"  # Phong vs Gouraud cost quoted by the source documents (DESIGN §1)
DASH = "—"


def order(values, preferred):
    """`values` in the order of `preferred`, unknown values after it, sorted."""
    values = set(values)
    return [v for v in preferred if v in values] + sorted(values - set(preferred))


# ----------------------------------------------------------------------------- input


def run_producers() -> None:
    for cmd in (["cargo", "bench", "--bench", "tradeoff"], ["python3", "measure/counts.py"]):
        print("$", " ".join(cmd), file=sys.stderr, flush=True)
        r = subprocess.run(cmd, cwd=ROOT)
        if r.returncode != 0:
            sys.exit(f"tradeoff.py: `{' '.join(cmd)}` failed (exit {r.returncode}); "
                     "fix it or use --no-run with the existing JSON files")


def load():
    """(counts, host, profile): dicts keyed by (tier, shading, lights)."""
    counts, host, profile = {}, {}, "?"
    if COUNTS.exists():
        doc = json.loads(COUNTS.read_text())
        profile = doc.get("profile", "?")
        for key, per_core in doc.get("configs", {}).items():
            parts = key.split()
            if len(parts) == 3:
                counts[tuple(parts)] = per_core
    else:
        print(f"tradeoff.py: {COUNTS.relative_to(ROOT)} missing: counts shown as {DASH}",
              file=sys.stderr)
    if HOST.exists():
        for row in json.loads(HOST.read_text()):
            host[(row["tier"], row["shading"], row["lights"])] = row
    else:
        print(f"tradeoff.py: {HOST.relative_to(ROOT)} missing: errors shown as {DASH}",
              file=sys.stderr)
    return counts, host, profile


class Data:
    def __init__(self, counts, host, profile):
        self.counts, self.host, self.profile = counts, host, profile
        keys = set(counts) | set(host)
        self.tiers = order({k[0] for k in keys}, TIERS)
        self.shadings = order({k[1] for k in keys}, SHADINGS)
        self.lights = order({k[2] for k in keys}, LIGHTS)
        self.keys = keys

    def c(self, tier, shading, lights, core, metric):
        """A counts.json value, or None."""
        v = self.counts.get((tier, shading, lights), {}).get(core, {}).get(metric)
        return v if isinstance(v, (int, float)) else None

    def h(self, tier, shading, lights, metric):
        """A host.json value, or None (also for psnr_db = null: use has_host)."""
        v = self.host.get((tier, shading, lights), {}).get(metric)
        return v if isinstance(v, (int, float)) else None

    def has_host(self, key):
        return key in self.host

    def rows(self, lights):
        """(tier, shading) pairs present in either file for a light set, in fixed order."""
        return [(t, s) for s in self.shadings for t in self.tiers if (t, s, lights) in self.keys]


# ----------------------------------------------------------------------------- format


def f_instr(v):
    if v is None:
        return DASH
    return f"{v:.1f}" if v < 100 else f"{v:.0f}"


def f_int(v):
    return DASH if v is None else f"{v:.0f}"


def f_fix(v, digits):
    return DASH if v is None else f"{v:.{digits}f}"


def f_ratio(a, b):
    if a is None or b is None or b == 0:
        return DASH
    r = a / b
    return f"{r:.1f}×" if r < 100 else f"{r:.0f}×"


def f_psnr(d, key):
    if not d.has_host(key):
        return DASH
    v = d.host[key].get("psnr_db")
    return "∞ (identical)" if v is None else f"{v:.1f}"


def table(header, rows, align=None):
    align = align or ["l"] * len(header)
    sep = ["---" if a == "l" else "---:" for a in align]
    out = ["| " + " | ".join(header) + " |", "| " + " | ".join(sep) + " |"]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(out)


# ----------------------------------------------------------------------------- Pareto


def pareto(points):
    """Indices of the points (cost, error) no other point dominates (≤ in both, < in
    one), in increasing cost."""
    front = []
    for i, (ci, ei) in enumerate(points):
        dominated = any(
            cj <= ci and ej <= ei and (cj < ci or ej < ei)
            for j, (cj, ej) in enumerate(points) if j != i
        )
        if not dominated:
            front.append(i)
    return sorted(front, key=lambda i: (points[i][0], points[i][1]))


def plot_points(d, lights, core):
    """[(tier, shading, cost, error)] with both values present: cost = whole-triangle
    instructions per pixel on `core`, error = mean LSB."""
    pts = []
    for t, s in d.rows(lights):
        cost = d.c(t, s, lights, core, "tri_32")
        err = d.h(t, s, lights, "mean_lsb")
        if cost is not None and err is not None:
            pts.append((t, s, cost, err))
    return pts


def group(shading):
    """The shading method whose f64 reference a shading is compared with (host.json):
    configurations are comparable in error only within one group."""
    return REFERENCE.get(shading, shading)


def fronts(pts):
    """{reference group: [indices]}: the Pareto front within each group of shadings that
    share a reference, and 'all': [indices] over all points."""
    out = {}
    for g in order({group(p[1]) for p in pts}, SHADINGS):
        idx = [i for i, p in enumerate(pts) if group(p[1]) == g]
        out[g] = [idx[k] for k in pareto([(pts[i][2], pts[i][3]) for i in idx])]
    out["all"] = pareto([(p[2], p[3]) for p in pts])
    return out


def group_name(pts, g):
    return " + ".join(order({p[1] for p in pts if group(p[1]) == g}, SHADINGS))


def front_text(pts, idx, with_shading=False):
    with_shading = with_shading or len({pts[i][1] for i in idx}) > 1 or any(
        pts[i][1] != group(pts[i][1]) for i in idx)
    if with_shading:
        return " → ".join(f"{pts[i][1]} {pts[i][0]}" for i in idx)
    return " → ".join(pts[i][0] for i in idx)


# ----------------------------------------------------------------------------- markdown


def marked(mark: tuple[str, str], name: str, render) -> str:
    """`render(doc)` of measure/out/<name> between the markers `mark` that its script rewrites
    (a line naming the command before the first measurement)."""
    path = ROOT / "measure" / "out" / name
    doc = json.loads(path.read_text()) if path.exists() else None
    body = render(doc) if doc is not None else f"Not measured yet: run `python3 measure/{name.split('.')[0]}.py`."
    return f"{mark[0]}\n{body}\n{mark[1]}"


def frame_section() -> str:
    """The whole-frame table from measure/out/frame.json, between the markers frame.py rewrites."""
    import frame  # measure/frame.py
    return marked(frame.MARK, "frame.json", frame.frame_markdown)


def stage_section() -> str:
    """The per-stage table of lambert_gouraud from frame.json's "breakdown", between the
    markers frame.py rewrites."""
    import frame  # measure/frame.py
    return ("Where a Lambert + Gouraud frame goes, stage by stage, beside the floor's (issue 19):\n\n"
            + marked(frame.STAGE_MARK, "frame.json",
                     lambda doc: frame.breakdown_markdown(doc.get("breakdown", {}), frame.CONFIGS[0])))


def frontier_section() -> str:
    """The Pareto fronts from measure/out/frontier.json, between the markers frontier.py rewrites."""
    import frontier  # measure/frontier.py
    return marked(frontier.MARK, "frontier.json", frontier.markdown)


def markdown(d: Data, command: str, ran: bool) -> str:
    today = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")
    pixels = sorted({r.get("pixels") for r in d.host.values() if r.get("pixels")})
    px = ", ".join(str(p) for p in pixels) or DASH
    L = []
    add = L.append
    add("# fixshade: speed against accuracy, per configuration\n")
    add(f"Generated {today} (UTC) by `{command}`"
        + (" (which first ran `cargo bench --bench tradeoff` and `python3 measure/counts.py`)."
           if ran else " from the existing `measure/out/host.json` and `measure/out/counts.json`."))
    add("Do not edit by hand: rerun the command.\n")

    add("## Whole frames (the mesh renderer)\n")
    add(frame_section() + "\n")
    add(stage_section() + "\n")
    add(frontier_section() + "\n")

    add("## How to read\n")
    add(
        "A configuration is a number tier × a shading method × a light set. **Error** "
        f"(`cargo bench --bench tradeoff`): a 240×240 lit sphere ({px} covered pixels) "
        "rendered through the real pipeline and compared with the `f64` reference *of "
        "the same shading method* (`phong_inc`: the Phong reference) — so the error "
        "columns show what the number tier costs in accuracy, not how far flat or "
        "Gouraud shading is from per-pixel lighting. *max LSB* / *mean LSB*: largest and mean difference, in 8-bit "
        "steps of the worst channel, between the Rgb888 output and the rounded "
        "reference. *PSNR* is computed against the unrounded reference, so it "
        "includes the 8-bit rounding of any output (about 60–63 dB here even where "
        "the image equals the rounded reference) and hardly separates the tiers. "
        "*565 identical*: share of Rgb565 pixels equal to the reference rounded to "
        "Rgb565. **Cost** (`python3 measure/counts.py`, Unicorn emulator, "
        f"`{d.profile}` profile): instructions executed, not cycles (M0 loads, "
        "branches and calls, M4 divisions take more than one cycle). *span*: "
        "instructions per pixel of one `Kernel::span` of 64 pixels, (c(64) − c(0))/64 "
        "(`span_64`); *triangle*: a whole one-triangle `MeshDraw` of a right triangle with "
        "32-pixel legs (528 pixels), set-up and edge walking included, per pixel "
        "(`tri_32`); *setup*: instructions of drawing a 1-pixel triangle (set-up, "
        "per-vertex lighting for Gouraud, the one lit point for flat); *code*: "
        "`tri_bytes`, flash bytes of the triangle kernel and every function it "
        "reaches by direct calls (static call graph), compiler-builtins and libm "
        "(soft float, 64-bit multiply, division) included, the runtime excluded. "
        "**Host**: median ns per shaded pixel of the same sphere on the machine that "
        "ran the benchmark, and the ratio to `f32` Phong with `dir_blinn` in the same "
        f"run. {DASH} = not in the input file.\n"
    )
    add("Tiers: " + "; ".join(f"`{t}` = {TIER_DESC[t]}" for t in d.tiers if t in TIER_DESC)
        + ".\n")

    header = ["shading", "tier", "max LSB", "mean LSB", "PSNR dB", "565 identical %",
              "M0 span", "M4F span", "RV32IMC span", "M0 triangle", "M4F triangle", "RV32IMC triangle",
              "M0 setup", "M4F setup", "RV32IMC setup", "M0 code B", "M4F code B", "RV32IMC code B",
              "host ns/px", "host ratio"]
    align = ["l", "l"] + ["r"] * (len(header) - 2)
    add("## Per light set\n")
    add("Instruction columns are per pixel except *setup* (per triangle).\n")
    for lights in d.lights:
        add(f"### `{lights}`" + (f": {LIGHT_DESC[lights]}" if lights in LIGHT_DESC else "")
            + "\n")
        rows = []
        for t, s in d.rows(lights):
            key = (t, s, lights)
            ident = d.h(*key, "identical_565")
            rows.append([
                s, t,
                f_int(d.h(*key, "max_lsb")),
                f_fix(d.h(*key, "mean_lsb"), 4),
                f_psnr(d, key),
                DASH if ident is None else f"{100 * ident:.2f}",
                f_instr(d.c(*key, "m0", "span_64")),
                f_instr(d.c(*key, "m4f", "span_64")),
                f_instr(d.c(*key, RV, "span_64")),
                f_instr(d.c(*key, "m0", "tri_32")),
                f_instr(d.c(*key, "m4f", "tri_32")),
                f_instr(d.c(*key, RV, "tri_32")),
                f_int(d.c(*key, "m0", "setup")),
                f_int(d.c(*key, "m4f", "setup")),
                f_int(d.c(*key, RV, "setup")),
                f_int(d.c(*key, "m0", "tri_bytes")),
                f_int(d.c(*key, "m4f", "tri_bytes")),
                f_int(d.c(*key, RV, "tri_bytes")),
                f_fix(d.h(*key, "host_ns_per_pixel"), 1),
                f_fix(d.h(*key, "host_ratio_to_f32_phong_dir_blinn"), 2),
            ])
        add(table(header, rows, align) + "\n")

    # Phong vs Gouraud
    add("## Phong vs Gouraud\n")
    add(f"Cost of per-pixel lighting relative to Gouraud, `{PLOT_LIGHTS}`: Phong "
        "instructions per pixel ÷ Gouraud instructions per pixel, for the span alone "
        "and for the whole 528-pixel triangle (where Gouraud also pays its per-vertex "
        f"lighting). The source documents quote {SEED_RATIO} (DESIGN §1).\n")
    per_pixel = [s for s in d.shadings if s.startswith("phong")]
    header = ["tier", "shading", "M0 span", "M0 triangle", "M4F span", "M4F triangle"]
    rows = []
    for s in per_pixel:
        for t in d.tiers:
            if (t, s, PLOT_LIGHTS) not in d.keys:
                continue
            cells = [t, f"{s} / gouraud"]
            for core in CORES:
                for m in ("span_64", "tri_32"):
                    cells.append(f_ratio(d.c(t, s, PLOT_LIGHTS, core, m),
                                         d.c(t, "gouraud", PLOT_LIGHTS, core, m)))
            rows.append(cells)
    rows.append(["source documents", "phong / gouraud"] + [SEED_RATIO] * 4)
    add(table(header, rows, ["l", "l", "r", "r", "r", "r"]) + "\n")
    add("Span ratio Phong ÷ Gouraud for every light set (M0 / M4F):\n")
    header = ["tier"] + [f"`{x}`" for x in d.lights]
    rows = []
    for s in per_pixel:
        for t in d.tiers:
            if not any((t, s, x) in d.keys for x in d.lights):
                continue
            cells = [t if s == "phong" else f"{t} ({s})"]
            for x in d.lights:
                cells.append(" / ".join(
                    f_ratio(d.c(t, s, x, core, "span_64"), d.c(t, "gouraud", x, core, "span_64"))
                    for core in CORES))
            rows.append(cells)
    add(table(header, rows, ["l"] + ["r"] * len(d.lights)) + "\n")

    # Paying only for what you use
    add("## Paying only for what you use\n")
    add("The same tier and shading with the smallest light set (`dir_diffuse`: one "
        "directional light, no specular) and the largest (`point4_blinn`: four point "
        "lights with attenuation and Blinn-Phong). *code*: `tri_bytes` (with "
        "compiler-builtins and libm) and, in brackets, `tri_bytes_lib` (without them: "
        "the crate's own code); *triangle*: whole-triangle instructions per pixel; "
        "*setup*: instructions per triangle.\n")
    header = ["tier", "shading", "core", "code B dir_diffuse", "code B point4_blinn", "Δ code B",
              "triangle dir_diffuse", "triangle point4_blinn", "×",
              "setup dir_diffuse", "setup point4_blinn"]
    rows = []
    for t in [x for x in ("q14_2", "f32") if x in d.tiers]:
        for s in d.shadings:
            for core in CORES:
                a, b = (t, s, "dir_diffuse"), (t, s, "point4_blinn")
                if a not in d.keys and b not in d.keys:
                    continue
                ca, cb = d.c(*a, core, "tri_bytes"), d.c(*b, core, "tri_bytes")
                la, lb = d.c(*a, core, "tri_bytes_lib"), d.c(*b, core, "tri_bytes_lib")

                def code(v, lib):
                    return DASH if v is None else f"{v:.0f} ({f_int(lib)})"

                delta = DASH if ca is None or cb is None else f"{cb - ca:+.0f}"
                if delta != DASH and la is not None and lb is not None:
                    delta += f" ({lb - la:+.0f})"
                ta, tb = d.c(*a, core, "tri_32"), d.c(*b, core, "tri_32")
                rows.append([t, s, CORE_NAME[core], code(ca, la), code(cb, lb), delta,
                             f_instr(ta), f_instr(tb), f_ratio(tb, ta),
                             f_int(d.c(*a, core, "setup")), f_int(d.c(*b, core, "setup"))])
    add(table(header, rows, ["l", "l", "l"] + ["r"] * 8) + "\n")

    # Fixed point without an FPU: RV32IMC, Q14 against the f32 tier
    add("## Fixed point without an FPU (RV32IMC)\n")
    add("What the `Q14` tier buys where `f32` is soft float: the same kernels counted on "
        "`riscv32imc-unknown-none-elf` (ESP32-C3 class; Unicorn's RV32 mode, `measure/counts.py`), "
        "`f32` instructions per pixel ÷ `Q14` (`q14_2`), per shading and light set, span and whole "
        "528-pixel triangle. `phong_inc` (`IncrementalPhongShading`, Q14 only) is set against the "
        "`f32` tier's general `phong`. Whole frames of the standard scene: the RV32IMC table under "
        "*Whole frames* above.\n")
    header = ["shading", "light set", "Q14 span", "f32 span", "f32 ÷ Q14 span", "Q14 triangle",
              "f32 triangle", "f32 ÷ Q14 triangle", "Q14 code B", "f32 code B"]
    rows = []
    for s in [x for x in d.shadings if x in ("flat", "gouraud", "phong", "phong_inc", "phong_quad")]:
        for lights in d.lights:
            q, f = ("q14_2", s, lights), ("f32", "phong" if s == "phong_inc" else s, lights)
            if q not in d.keys or f not in d.keys or d.c(*q, RV, "span_64") is None:
                continue
            rows.append([s if s != "phong_inc" else "phong_inc (f32: phong)", f"`{lights}`",
                         f_instr(d.c(*q, RV, "span_64")), f_instr(d.c(*f, RV, "span_64")),
                         f_ratio(d.c(*f, RV, "span_64"), d.c(*q, RV, "span_64")),
                         f_instr(d.c(*q, RV, "tri_32")), f_instr(d.c(*f, RV, "tri_32")),
                         f_ratio(d.c(*f, RV, "tri_32"), d.c(*q, RV, "tri_32")),
                         f_int(d.c(*q, RV, "tri_bytes")), f_int(d.c(*f, RV, "tri_bytes"))])
    add(table(header, rows, ["l", "l"] + ["r"] * 8) + "\n")

    # Targets
    add("## Targets\n")
    add(f"From the design discussion (also the `target` entries of `measure/bounds.json`), "
        f"Cortex-M0, one directional Blinn-Phong light (`{PLOT_LIGHTS}`), the fast tier "
        "(`Q14`; both Newton settings shown), instructions per pixel of the span "
        "(`span_64`, the metric `counts.py --check` bounds). Whole-triangle figures "
        "for comparison.\n")
    header = ["target", "tier", "configuration", "measured (span)", "triangle", "target", "met"]
    rows = []

    def verdict(v, limit, times=True):
        if v is None:
            return DASH
        if v <= limit:
            return "yes"
        return f"no ({v / limit:.1f}× the target)" if times else "no"

    fast = [x for x in FAST_TIERS if x in d.tiers]
    for s in per_pixel:
        for t in fast:
            if (t, s, PLOT_LIGHTS) not in d.keys:
                continue
            v = d.c(t, s, PLOT_LIGHTS, "m0", "span_64")
            rows.append([f"{s} ≤ {TARGET_PHONG} instr/px", t, f"{t} {s} {PLOT_LIGHTS}", f_instr(v),
                         f_instr(d.c(t, s, PLOT_LIGHTS, "m0", "tri_32")), f"≤ {TARGET_PHONG}",
                         verdict(v, TARGET_PHONG)])
    for t in fast:
        v = d.c(t, "gouraud", PLOT_LIGHTS, "m0", "span_64")
        rows.append([f"gouraud ≤ {TARGET_GOURAUD} instr/px", t, f"{t} gouraud {PLOT_LIGHTS}",
                     f_instr(v), f_instr(d.c(t, "gouraud", PLOT_LIGHTS, "m0", "tri_32")),
                     f"≤ {TARGET_GOURAUD}", verdict(v, TARGET_GOURAUD)])
    for s in per_pixel:
        for t in fast:
            if (t, s, PLOT_LIGHTS) not in d.keys:
                continue
            p = d.c(t, s, PLOT_LIGHTS, "m0", "span_64")
            g = d.c(t, "gouraud", PLOT_LIGHTS, "m0", "span_64")
            pt = d.c(t, s, PLOT_LIGHTS, "m0", "tri_32")
            gt = d.c(t, "gouraud", PLOT_LIGHTS, "m0", "tri_32")
            r = None if p is None or g in (None, 0) else p / g
            rows.append([f"{s} ≤ {TARGET_RATIO}× gouraud", t, f"{t} {s} ÷ gouraud",
                         f_ratio(p, g), f_ratio(pt, gt), f"≤ {TARGET_RATIO}×",
                         verdict(r, TARGET_RATIO, times=False)])
    add(table(header, rows, ["l", "l", "l", "r", "r", "r", "l"]) + "\n")

    # Plot
    add("## Plot\n")
    add(f"![error against Cortex-M instructions per pixel, {PLOT_LIGHTS}](img/tradeoff.svg)\n")
    add(f"`docs/img/tradeoff.svg`: mean error (8-bit LSB, log scale; 0 drawn on its own "
        f"line at the bottom) against whole-triangle instructions per pixel (log scale) on "
        f"the Cortex-M0 (left) and the Cortex-M4F (right), one point per tier × shading, "
        f"`{PLOT_LIGHTS}`. Since each method is compared with its own reference, a Pareto "
        "front (no other configuration is at most as costly *and* at most as wrong, and "
        "better in one) is drawn per reference method (`phong_inc` is compared with the "
        "Phong reference, so it shares the Phong front); the front over all "
        "configurations is listed too.\n")
    rows = []
    for core in CORES:
        pts = plot_points(d, PLOT_LIGHTS, core)
        fr = fronts(pts)
        for g, idx in fr.items():
            if g == "all":
                continue
            rows.append([CORE_NAME[core], group_name(pts, g), front_text(pts, idx)])
        rows.append([CORE_NAME[core], "all methods", front_text(pts, fr["all"], True)])
    add(table(["core", "shading", "Pareto front (increasing cost)"], rows) + "\n")
    missing = [f"{t} {s}" for t, s in d.rows(PLOT_LIGHTS)
               if d.h(t, s, PLOT_LIGHTS, "mean_lsb") is None
               or any(d.c(t, s, PLOT_LIGHTS, c, "tri_32") is None for c in CORES)]
    if missing:
        add("Missing from at least one panel (a value is not in one input): " + ", ".join(missing) + ".\n")
    return "\n".join(L)


# ----------------------------------------------------------------------------- SVG

COLOUR = {"flat": "#0072B2", "gouraud": "#E69F00", "phong": "#D55E00", "phong_inc": "#009E73"}
EXTRA_COLOURS = ["#CC79A7", "#56B4E9", "#000000"]
FONT = "DejaVu Sans, Helvetica, Arial, sans-serif"


def colour(s, shadings):
    if s in COLOUR:
        return COLOUR[s]
    extra = [x for x in shadings if x not in COLOUR]
    return EXTRA_COLOURS[extra.index(s) % len(EXTRA_COLOURS)]


def marker(s, x, y, fill, r=5.5):
    shape = {"flat": "square", "gouraud": "triangle", "phong": "circle",
             "phong_inc": "diamond"}.get(s, "cross")
    st = f'fill="{fill}" stroke="#000" stroke-width="0.8"'
    if shape == "square":
        a = r * 0.9
        return f'<rect x="{x - a:.1f}" y="{y - a:.1f}" width="{2 * a:.1f}" height="{2 * a:.1f}" {st}/>'
    if shape == "triangle":
        a = r * 1.2
        return (f'<polygon points="{x:.1f},{y - a:.1f} {x + a * 0.94:.1f},{y + a * 0.6:.1f} '
                f'{x - a * 0.94:.1f},{y + a * 0.6:.1f}" {st}/>')
    if shape == "circle":
        return f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{r:.1f}" {st}/>'
    if shape == "diamond":
        a = r * 1.25
        return (f'<polygon points="{x:.1f},{y - a:.1f} {x + a:.1f},{y:.1f} {x:.1f},{y + a:.1f} '
                f'{x - a:.1f},{y:.1f}" {st}/>')
    return (f'<path d="M{x - r:.1f},{y - r:.1f}L{x + r:.1f},{y + r:.1f}M{x - r:.1f},{y + r:.1f}'
            f'L{x + r:.1f},{y - r:.1f}" stroke="{fill}" stroke-width="2"/>')


def text(x, y, s, size=11, anchor="start", weight="normal", fill="#000", extra=""):
    return (f'<text x="{x:.1f}" y="{y:.1f}" font-size="{size}" text-anchor="{anchor}" '
            f'font-weight="{weight}" fill="{fill}"{extra}>{escape(s)}</text>')


def text_width(s, size):
    return 0.6 * size * len(s)


def fmt_tick(v):
    if v >= 1:
        return f"{v:.0f}"
    return f"{v:g}"


class Panel:
    """One scatter plot: log x (instructions per pixel), log y (mean LSB) with 0 on its
    own line below the lowest decade."""

    def __init__(self, x0, y0, w, h, xlo, xhi, ylo, yhi):
        self.x0, self.y0, self.w, self.h = x0, y0, w, h
        self.lxlo, self.lxhi = math.log10(xlo), math.log10(xhi)
        self.lylo, self.lyhi = math.log10(ylo), math.log10(yhi)
        self.zero_gap = 34  # pixels between the lowest decade and the 0 line

    def X(self, v):
        return self.x0 + (math.log10(v) - self.lxlo) / (self.lxhi - self.lxlo) * self.w

    def Y(self, v):
        top, bottom = self.y0, self.y0 + self.h - self.zero_gap
        if v <= 0:
            return self.y0 + self.h - 8
        lv = max(math.log10(v), self.lylo)
        return bottom - (lv - self.lylo) / (self.lyhi - self.lylo) * (bottom - top)


def svg_panel(out, pts, core, x0, y0, w, h, shadings):
    costs = [p[2] for p in pts] or [10, 1000]
    errs = [p[3] for p in pts if p[3] > 0] or [1e-3, 1e-1]
    xlo = 10 ** math.floor(math.log10(min(costs)))
    xhi = 10 ** math.ceil(math.log10(max(costs)))
    ylo = 10 ** math.floor(math.log10(min(errs)))
    yhi = 10 ** math.ceil(math.log10(max(errs)))
    if yhi <= ylo:
        yhi = ylo * 10
    P = Panel(x0, y0, w, h, xlo, xhi, ylo, yhi)
    bottom = y0 + h
    out.append(f'<rect x="{x0}" y="{y0}" width="{w}" height="{h}" fill="#fff" stroke="#444"/>')
    # x grid and ticks: 1, 2, 5 per decade
    k = math.floor(P.lxlo)
    while 10 ** k <= xhi:
        for m in (1, 2, 5):
            v = m * 10 ** k
            if v < xlo or v > xhi:
                continue
            X = P.X(v)
            major = m == 1
            out.append(f'<line x1="{X:.1f}" y1="{y0}" x2="{X:.1f}" y2="{bottom}" '
                       f'stroke="{"#ccc" if major else "#eee"}"/>')
            out.append(f'<line x1="{X:.1f}" y1="{bottom}" x2="{X:.1f}" y2="{bottom + 5}" stroke="#444"/>')
            out.append(text(X, bottom + 18, fmt_tick(v), 11, "middle"))
        k += 1
    # y grid: decades, and the 0 line below a break
    k = round(P.lylo)
    while k <= round(P.lyhi):
        Y = P.Y(10 ** k)
        out.append(f'<line x1="{x0}" y1="{Y:.1f}" x2="{x0 + w}" y2="{Y:.1f}" stroke="#ccc"/>')
        out.append(text(x0 - 8, Y + 4, fmt_tick(10 ** k), 11, "end"))
        k += 1
    Yz = P.Y(0)
    yb = P.Y(ylo) + P.zero_gap / 2 - 4
    out.append(f'<line x1="{x0}" y1="{Yz:.1f}" x2="{x0 + w}" y2="{Yz:.1f}" stroke="#ccc" '
               f'stroke-dasharray="2,3"/>')
    out.append(text(x0 - 8, Yz + 4, "0", 11, "end"))
    out.append(f'<path d="M{x0 - 6},{yb + 3:.1f}l12,-6M{x0 - 6},{yb + 8:.1f}l12,-6" '
               f'stroke="#444" fill="none"/>')
    out.append(f'<line x1="{x0 - 4}" y1="{yb - 2:.1f}" x2="{x0 + 4}" y2="{yb + 3:.1f}" '
               f'stroke="#fff" stroke-width="3"/>')
    # axis titles
    out.append(text(x0 + w / 2, y0 - 10, f"{CORE_NAME[core]}: {len(pts)} configurations",
                    13, "middle", "bold"))
    out.append(text(x0 + w / 2, bottom + 38,
                    f"{CORE_NAME[core]} instructions per pixel, whole 528-pixel triangle (log)",
                    12, "middle"))
    yc = y0 + h / 2
    out.append(text(x0 - 50, yc, "mean error, 8-bit LSB (log; 0 below the break)", 12,
                    "middle", extra=f' transform="rotate(-90 {x0 - 50} {yc:.1f})"'))

    # Pareto fronts: per shading (solid, shading colour), over all (grey, dashed, wide)
    fr = fronts(pts)

    def polyline(idx, stroke, width, dash=""):
        if len(idx) < 2:
            return
        pts_s = " ".join(f"{P.X(pts[i][2]):.1f},{P.Y(pts[i][3]):.1f}" for i in idx)
        da = f' stroke-dasharray="{dash}"' if dash else ""
        op = ' stroke-opacity="0.45"' if width > 3 else ""
        out.append(f'<polyline points="{pts_s}" fill="none" stroke="{stroke}" '
                   f'stroke-width="{width}" stroke-linejoin="round"{da}{op}/>')

    polyline(fr["all"], "#999", 7, "")
    for g in fr:
        if g != "all":
            polyline(fr[g], colour(g, shadings), 1.8)
    # points (front members get a black ring)
    on_front = {i for s, idx in fr.items() if s != "all" for i in idx}
    occupied = []
    for i, (t, s, c, e) in enumerate(pts):
        X, Y = P.X(c), P.Y(e)
        if i in set(fr["all"]):
            out.append(f'<circle cx="{X:.1f}" cy="{Y:.1f}" r="10" fill="none" stroke="#555" '
                       f'stroke-width="1.2"/>')
        out.append(marker(s, X, Y, colour(s, shadings), 6 if i in on_front else 5))
        occupied.append((X - 7, Y - 7, X + 7, Y + 7))
    # tier labels, placed greedily where they overlap nothing placed so far
    order_i = sorted(range(len(pts)), key=lambda i: (P.X(pts[i][2]), P.Y(pts[i][3])))
    for i in order_i:
        t, s, c, e = pts[i]
        X, Y = P.X(c), P.Y(e)
        tw, th = text_width(t, 10), 10
        cands = [(9, 4), (-9 - tw, 4), (-tw / 2, -10), (-tw / 2, 16), (9, -8), (9, 15),
                 (-9 - tw, -8), (-9 - tw, 15), (-tw / 2, -22), (-tw / 2, 28), (22, 4),
                 (-22 - tw, 4), (9, -20), (9, 27), (-9 - tw, -20), (-9 - tw, 27)]
        best = None
        for dx, dy in cands:
            box = (X + dx, Y + dy - th + 1, X + dx + tw, Y + dy + 2)
            inside = box[0] >= x0 + 2 and box[2] <= x0 + w - 2 and box[1] >= y0 + 2 \
                and box[3] <= bottom - 2
            clash = any(not (box[2] < o[0] or box[0] > o[2] or box[3] < o[1] or box[1] > o[3])
                        for o in occupied)
            if inside and not clash:
                best = (dx, dy, box)
                break
        if best is None:
            dx, dy = cands[0]
            best = (dx, dy, (X + dx, Y + dy - th + 1, X + dx + tw, Y + dy + 2))
        dx, dy, box = best
        occupied.append(box)
        out.append(text(X + dx, Y + dy, t, 10, fill="#222"))
    return fr


def svg(d: Data, command: str) -> str:
    W, H = 1200, 665
    px0, py0, pw, ph = 95, 80, 450, 400
    gap = 150
    shadings = order({p[1] for core in CORES for p in plot_points(d, PLOT_LIGHTS, core)},
                     SHADINGS)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
           f'viewBox="0 0 {W} {H}" font-family="{FONT}">',
           f'<rect width="{W}" height="{H}" fill="#fff"/>',
           text(W / 2, 30, f"fixshade: error against Cortex-M cost per pixel, one directional "
                f"Blinn-Phong light ({PLOT_LIGHTS})", 17, "middle", "bold"),
           text(W / 2, 50, "240×240 lit sphere vs the f64 reference of the same shading "
                "method (phong_inc: Phong); instructions counted in Unicorn (release build)", 12, "middle",
                fill="#333")]
    all_fronts = {}
    for n, core in enumerate(CORES):
        pts = plot_points(d, PLOT_LIGHTS, core)
        all_fronts[core] = (pts, svg_panel(out, pts, core, px0 + n * (pw + gap), py0, pw, ph,
                                           shadings))
    # legend: markers, lines, and the fronts
    ly = py0 + ph + 70
    lx = px0
    out.append(text(lx - 40, ly, "shading:", 12, weight="bold"))
    x = lx + 32
    for s in shadings:
        out.append(marker(s, x, ly - 4, colour(s, shadings)))
        out.append(text(x + 10, ly, s, 12))
        x += 26 + text_width(s, 12)
    x += 10
    out.append(f'<line x1="{x}" y1="{ly - 4}" x2="{x + 30}" y2="{ly - 4}" stroke="#444" '
               f'stroke-width="1.8"/>')
    out.append(text(x + 36, ly, "Pareto front per reference method (bigger markers)", 12))
    x += 36 + text_width("Pareto front per reference method (bigger markers)", 12) + 14
    out.append(f'<line x1="{x}" y1="{ly - 4}" x2="{x + 30}" y2="{ly - 4}" stroke="#999" '
               f'stroke-width="7" stroke-opacity="0.45"/>')
    out.append(f'<circle cx="{x + 15}" cy="{ly - 4}" r="10" fill="none" stroke="#555"/>')
    out.append(text(x + 36, ly, "front over all configurations", 12))
    ly += 28
    block_bottom = ly
    for n, core in enumerate(CORES):
        pts, fr = all_fronts[core]
        bx = px0 + n * (pw + gap) - 40
        limit = (pw + gap - 20) if n + 1 < len(CORES) else (W - bx - 10)
        y = ly
        out.append(text(bx, y, f"Pareto fronts, {CORE_NAME[core]} (increasing cost):", 12,
                        weight="bold"))
        entries = [(group_name(pts, g), front_text(pts, idx)) for g, idx in fr.items()
                   if g != "all"]
        entries.append(("all", front_text(pts, fr["all"], True)))
        for name, chain in entries:
            lines, cur = [], f"{name}: "
            for k, step in enumerate(chain.split(" → ")):
                piece = step if k == 0 else " → " + step
                if k > 0 and text_width(cur + piece, 11) > limit:
                    lines.append(cur)
                    cur = "    → " + step
                else:
                    cur += piece
            lines.append(cur)
            for line in lines:
                y += 17
                out.append(text(bx, y, line, 11))
        block_bottom = max(block_bottom, y)
    ly = block_bottom + 10
    ly += 14
    out.append(text(lx - 40, ly, "Tier labels: q14_1/q14_2 = Q2.14 with 1/2 Newton steps, "
                    "q30 = Q2.30, f32 = libm sqrt, f32fast = bit-trick rsqrt + 2 Newton steps. "
                    "Error is the tier's, not the method's.", 11, fill="#333"))
    ly += 18
    out.append(text(lx - 40, ly, f"Generated by `{command}` from measure/out/host.json "
                    "(cargo bench --bench tradeoff) and measure/out/counts.json "
                    "(python3 measure/counts.py).", 11, fill="#333"))
    out.append("</svg>")
    H = math.ceil(ly + 20)
    out[0] = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
              f'viewBox="0 0 {W} {H}" font-family="{FONT}">')
    out[1] = f'<rect width="{W}" height="{H}" fill="#fff"/>'
    return "\n".join(out) + "\n"


# ----------------------------------------------------------------------------- main


HAND_WRITTEN = "<!-- hand-written sections below: kept by measure/tradeoff.py -->"


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--no-run", action="store_true",
                   help="use measure/out/host.json and counts.json as they are")
    args = p.parse_args(argv)
    argv = sys.argv[1:] if argv is None else argv
    command = shlex.join(["python3", "measure/tradeoff.py", *argv])
    if not args.no_run:
        run_producers()
    counts, host, profile = load()
    if not counts and not host:
        print("tradeoff.py: no input; run without --no-run", file=sys.stderr)
        return 1
    d = Data(counts, host, profile)
    MD.parent.mkdir(parents=True, exist_ok=True)
    SVG.parent.mkdir(parents=True, exist_ok=True)
    # the hand-written sections at the end (from the HAND_WRITTEN marker on) are kept
    kept = ""
    if MD.exists():
        old = MD.read_text()
        i = old.find("\n" + HAND_WRITTEN)
        kept = old[i:] if i >= 0 else ""
    MD.write_text(markdown(d, command, not args.no_run).rstrip("\n") + "\n" + kept)
    SVG.write_text(svg(d, "python3 measure/tradeoff.py"))  # the same file either way
    only_c = sorted(set(counts) - set(host))
    only_h = sorted(set(host) - set(counts))
    print(f"read  {HOST.relative_to(ROOT)} ({len(host)} configurations)")
    print(f"read  {COUNTS.relative_to(ROOT)} ({len(counts)} configurations)")
    if only_c or only_h:
        print(f"      {len(only_c)} only in counts.json, {len(only_h)} only in host.json")
    print(f"wrote {MD.relative_to(ROOT)}")
    print(f"wrote {SVG.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
