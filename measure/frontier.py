#!/usr/bin/env python3
"""The trade as users make it (issue 19): each configuration of the standard scene, its
whole-frame cost on each core against its error to the *exact image*.

Runs `cargo run --release -p fixshade-accuracy --bin frontier` (measure/accuracy/src/bin/
frontier.rs: every configuration rendered on the host, compared with the per-pixel f64
reference at pixel centres, on the standard sphere and on a coarse 6 x 8 UV sphere;
-> measure/out/frontier_error.json), joins
the instructions per lit pixel of the whole frame from measure/out/frame.json (m0, m4f,
rv32imc; on the coarse mesh the cost shown is the standard scene's: nothing new is
measured), and writes measure/out/frontier.json, the Pareto fronts per core as markdown
between the frontier markers of README.md and docs/tradeoff.md, and docs/img/frontier.svg.

    python3 measure/frontier.py           # rewrite the outputs
    python3 measure/frontier.py --check   # recompute; exit 1 if a committed output differs

No dependency beyond the standard library; the outputs are deterministic (a rerun gives
identical bytes).
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path
from xml.sax.saxutils import escape

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "measure" / "out"
ERROR_JSON = OUT / "frontier_error.json"
FRONTIER_JSON = OUT / "frontier.json"
FRAME_JSON = OUT / "frame.json"
README = ROOT / "README.md"
TRADEOFF = ROOT / "docs" / "tradeoff.md"
SVG = ROOT / "docs" / "img" / "frontier.svg"
MARK = ("<!-- frontier:start (python3 measure/frontier.py rewrites this block) -->", "<!-- frontier:end -->")

CORES = [("m0", "M0"), ("m4f", "M4F"), ("rv32imc", "RV32IMC")]
MESHES = [("standard", "standard sphere (16 × 24)"), ("coarse", "coarse sphere (6 × 8)")]
MODELS = [("lambert", "Lambert"), ("blinn_phong", "Blinn-Phong")]
METRICS = ["max", "p99"]
# table order: by model, then as the cost grows (the f32 tier after its Q14 configuration)
ORDER = ["flat", "flat_f32", "lambert_gouraud", "lambert_gouraud_f32", "lambert_gouraud_refine",
         "blinn_gouraud", "blinn_gouraud_f32", "blinn_phong_inc", "blinn_phong", "blinn_phong_f32"]


def run_frontier(write: bool) -> dict:
    cmd = ["cargo", "run", "--quiet", "--release", "-p", "fixshade-accuracy", "--bin", "frontier"]
    if not write:
        cmd += ["--", "--no-write"]
    out = subprocess.run(cmd, cwd=ROOT, check=True, stdout=subprocess.PIPE, text=True).stdout
    return json.loads(out), out


def join(err: dict, frame: dict) -> dict:
    """frontier.json: per mesh and configuration, the error and each core's cost."""
    host = frame.get("host", {})
    bad = [c for c, v in err["standard"]["configs"].items()
           if host.get(c, {}).get("checksum") != v["checksum"]]
    if bad:
        sys.exit(f"frontier.py: host frames differ from measure/out/frame.json's: {', '.join(bad)}"
                 " (rerun python3 measure/frame.py)")
    doc = {"about": "error (measure/accuracy/src/bin/frontier.rs, 8-bit LSB of the worst channel against the exact image)"
                    " against whole-frame instructions per lit pixel (measure/out/frame.json, full frame;"
                    " the coarse mesh carries the standard scene's cost)",
           "meshes": {}}
    for mesh, _ in MESHES:
        m = err[mesh]
        rows = {}
        for c, v in m["configs"].items():
            cost = {core: frame[core][c]["instr_per_lit_px"] for core, _ in CORES if c in frame.get(core, {})}
            rows[c] = {"model": v["model"], "error": v["error"], "cost": cost}
            if "error_vs_blinn_phong" in v:
                rows[c]["error_vs_blinn_phong"] = v["error_vs_blinn_phong"]
        fronts = {}
        for core, _ in CORES:
            for model, _ in MODELS:
                for metric in METRICS:
                    fronts[f"{core}/{model}/{metric}"] = front(rows, core, model, metric)
        doc["meshes"][mesh] = {k: m[k] for k in m if k != "configs"} | {"configs": rows, "fronts": fronts}
    return doc


def front(rows: dict, core: str, model: str, metric: str) -> list[str]:
    """The configurations no other one beats in both cost and error (cheapest first)."""
    pts = sorted((r["cost"][core], r["error"][metric], c) for c, r in rows.items()
                 if r["model"] == model and core in r["cost"])
    out, best = [], math.inf
    for cost, e, c in pts:
        if e < best:
            out.append(c)
            best = e
    return out


def lsb(x: float) -> str:
    return f"{x:.1f}"


def markdown(doc: dict) -> str:
    meshes = doc["meshes"]
    std, coarse = meshes["standard"], meshes["coarse"]
    L = []
    L.append("| configuration | model | standard sphere: max / p99 / mean LSB | coarse sphere: max / p99 / mean LSB"
             " | M0 | M4F | RV32IMC |")
    L.append("|---|---|---|---|---|---|---|")
    for c in sorted(std["configs"], key=lambda c: (ORDER + [c]).index(c)):
        r = std["configs"][c]
        cells = [f"`{c}`", dict(MODELS)[r["model"]]]
        for m in (std, coarse):
            e = m["configs"][c]["error"]
            cells.append(f"{lsb(e['max'])} / {lsb(e['p99'])} / {e['mean']:.2f}")
        for core, _ in CORES:
            on = [f"{mesh[0]}{'ᵐ' if metric == 'max' else 'ᵖ'}" for mesh, _ in MESHES for metric in METRICS
                  if c in meshes[mesh]["fronts"][f"{core}/{r['model']}/{metric}"]]
            cost = r["cost"].get(core)
            cells.append("—" if cost is None else (f"**{cost:.1f}**" if on else f"{cost:.1f}"))
        L.append("| " + " | ".join(cells) + " |")
    L.append("")
    L.append("Pareto fronts (cheapest first; cost = instructions per lit pixel of the whole frame, error = max"
             " or p99 LSB; a configuration is on a front when no other of the same model is as cheap and as"
             " accurate):")
    L.append("")
    head = ["core", "model"] + [f"{name}, {metric}" for _, name in MESHES for metric in METRICS]
    L.append("| " + " | ".join(head) + " |")
    L.append("|" + "---|" * len(head))
    for core, cname in CORES:
        for model, mname in MODELS:
            cells = [cname, mname]
            for mesh, _ in MESHES:
                m = meshes[mesh]
                for metric in METRICS:
                    f = m["fronts"][f"{core}/{model}/{metric}"]
                    cells.append(" → ".join(
                        f"`{c}` {m['configs'][c]['cost'][core]:.0f} / {lsb(m['configs'][c]['error'][metric])}"
                        for c in f))
            L.append("| " + " | ".join(cells) + " |")
    L.append("")
    # coverage and the highlight
    both = {mesh: sorted({r["error"]["pixels"] for r in meshes[mesh]["configs"].values()}) for mesh, _ in MESHES}
    odd = []
    for mesh, name in MESHES:
        for c, r in meshes[mesh]["configs"].items():
            e = r["error"]
            odd.append(f"{name} `{c}` +{e['only_frame']} / −{e['only_exact']}")
    refine_std = std["configs"].get("lambert_gouraud_refine", {}).get("error", {})
    vs = [r["error_vs_blinn_phong"]["max"] for m in meshes.values() for r in m["configs"].values()
          if "error_vs_blinn_phong" in r]
    L.append(
        "**Error** (`measure/accuracy/src/bin/frontier.rs`): each configuration's host frame (its checksum equals frame.json's)"
        " against the *exact image*: the same scene lit per pixel by `fixshade_testkit::reference` in `f64` at pixel"
        " centres, with the mesh's vertex normals interpolated there and normalised (Blinn-Phong for the Blinn"
        " configurations, Lambert for the Lambert ones), rounded to the nearest 5-6-5 colour; the shading"
        " method's error and the tier's together, in 8-bit LSBs of the worst channel (one 5-bit step = 8.2,"
        " one 6-bit step = 4.0), over the pixels both cover"
        f" ({', '.join(str(n) for n in both['standard'])} on the standard sphere,"
        f" {', '.join(str(n) for n in both['coarse'])} on the coarse one); *mean* = mean over them."
        " **Cost**: whole-frame instructions per lit pixel from `measure/out/frame.json`"
        " (`python3 measure/frame.py`); on the coarse sphere the standard scene's cost (not measured on it);"
        " the `f32` tier on RV32IMC only. **Bold**: on a front of that core."
        f" The coarse sphere's highlight falls inside a triangle: its nearest vertex sees"
        f" (N·H)³² = {coarse['highlight_nearest_vertex_specular']}"
        f" (standard sphere: {std['highlight_nearest_vertex_specular']}), so Gouraud misses it."
        " Coverage apart (pixels only the frame covers / only the exact image):"
        f" {coverage_summary(meshes)}."
        f" Against the Blinn-Phong image the Lambert configurations miss by up to {max(vs):.0f} LSB (the"
        " highlight they do not draw)."
        " Plot: `docs/img/frontier.svg`.")
    return "\n".join(L)


def coverage_summary(meshes: dict) -> str:
    parts = []
    for mesh, name in MESHES:
        groups: dict[tuple, list] = {}
        for c, r in meshes[mesh]["configs"].items():
            e = r["error"]
            groups.setdefault((e["only_frame"], e["only_exact"]), []).append(c)
        g = "; ".join(f"+{k[0]} / −{k[1]} " + ("every other configuration" if len(v) > 2 else ", ".join(f"`{c}`" for c in v))
                      for k, v in sorted(groups.items(), key=lambda kv: len(kv[1])))
        parts.append(f"{name}: {g}")
    return "; ".join(parts) + " (silhouette refinement rounds the outline towards the true sphere, outside the mesh)"


# ----------------------------------------------------------------------------- SVG

COLORS = {"lambert": "#b03a2e", "blinn_phong": "#1f5fa6"}
SHORT = {"lambert_gouraud": "lg", "blinn_gouraud": "bg", "blinn_phong": "bp", "blinn_phong_inc": "bpi",
         "flat": "flat", "lambert_gouraud_refine": "lg+r", "lambert_gouraud_f32": "lg f32",
         "blinn_gouraud_f32": "bg f32", "blinn_phong_f32": "bp f32", "flat_f32": "flat f32"}


def svg(doc: dict) -> str:
    pw, ph, ml, mt, gap = 300, 220, 50, 40, 30
    W = ml + 3 * (pw + gap) + 10
    H = mt + 2 * (ph + 60) + 40
    o = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}"'
         ' font-family="sans-serif" font-size="10">',
         f'<rect width="{W}" height="{H}" fill="white"/>',
         f'<text x="{W / 2:.0f}" y="16" text-anchor="middle" font-size="13">Whole-frame cost against error to the'
         ' exact image (python3 measure/frontier.py)</text>',
         f'<text x="{W / 2:.0f}" y="30" text-anchor="middle">filled: max LSB, open: p99 LSB; solid line: front'
         ' by max, dashed: by p99; red: Lambert, blue: Blinn-Phong</text>']
    for row, (mesh, mname) in enumerate(MESHES):
        m = doc["meshes"][mesh]
        ymax = max(r["error"]["max"] for r in m["configs"].values())
        ymax = math.ceil(ymax * 1.1 / 25) * 25
        for col, (core, cname) in enumerate(CORES):
            x0, y0 = ml + col * (pw + gap), mt + row * (ph + 60) + 20
            pts = {c: r for c, r in m["configs"].items() if core in r["cost"]}
            costs = [r["cost"][core] for r in pts.values()]
            lo, hi = math.log10(min(costs) / 1.2), math.log10(max(costs) * 1.2)
            X = lambda c: x0 + (math.log10(c) - lo) / (hi - lo) * pw
            Y = lambda e: y0 + ph - e / ymax * ph
            o.append(f'<rect x="{x0}" y="{y0}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>')
            o.append(f'<text x="{x0 + pw / 2:.0f}" y="{y0 - 6}" text-anchor="middle" font-size="11">'
                     f'{cname}, {escape(mname)}</text>')
            for k in range(0, int(ymax) + 1, 25 if ymax <= 100 else 50):
                o.append(f'<line x1="{x0}" y1="{Y(k):.1f}" x2="{x0 + pw}" y2="{Y(k):.1f}" stroke="#eee"/>')
                o.append(f'<text x="{x0 - 4}" y="{Y(k) + 3:.1f}" text-anchor="end">{k}</text>')
            for t in [50, 100, 200, 500, 1000, 2000, 5000]:
                if lo <= math.log10(t) <= hi:
                    o.append(f'<line x1="{X(t):.1f}" y1="{y0 + ph}" x2="{X(t):.1f}" y2="{y0 + ph + 4}" stroke="#888"/>')
                    o.append(f'<text x="{X(t):.1f}" y="{y0 + ph + 14}" text-anchor="middle">{t}</text>')
            o.append(f'<text x="{x0 + pw / 2:.0f}" y="{y0 + ph + 27}" text-anchor="middle">instructions per lit'
                     ' pixel (log)</text>')
            if col == 0:
                o.append(f'<text x="{x0 - 34}" y="{y0 + ph / 2:.0f}" text-anchor="middle" transform="rotate(-90'
                         f' {x0 - 34} {y0 + ph / 2:.0f})">LSB (8-bit, worst channel)</text>')
            for model, _ in MODELS:
                for metric, dash in (("max", ""), ("p99", ' stroke-dasharray="4 3"')):
                    f = m["fronts"][f"{core}/{model}/{metric}"]
                    if len(f) < 2:
                        continue
                    # a staircase: along in cost, then down to the next point's error
                    path = []
                    for i, c in enumerate(f):
                        x, y = X(pts[c]["cost"][core]), Y(pts[c]["error"][metric])
                        path.append(f"H{x:.1f} V{y:.1f}" if i else f"M{x:.1f},{y:.1f}")
                    o.append(f'<path d="{" ".join(path)}" fill="none" stroke="{COLORS[model]}"{dash}/>')
            for c, r in pts.items():
                x, col_ = X(r["cost"][core]), COLORS[r["model"]]
                ya, yb = Y(r["error"]["max"]), Y(r["error"]["p99"])
                o.append(f'<line x1="{x:.1f}" y1="{ya:.1f}" x2="{x:.1f}" y2="{yb:.1f}" stroke="{col_}" stroke-width="0.6"/>')
                o.append(f'<circle cx="{x:.1f}" cy="{yb:.1f}" r="2.5" fill="white" stroke="{col_}"/>')
                o.append(f'<circle cx="{x:.1f}" cy="{ya:.1f}" r="3" fill="{col_}"/>')
                # the f32 tier's labels below their point (they sit beside the Q14 ones)
                ly = ya + 11 if c.endswith("_f32") else ya - 3
                o.append(f'<text x="{x + 4:.1f}" y="{ly:.1f}" fill="{col_}">{escape(SHORT.get(c, c))}</text>')
    o.append(f'<text x="{ml}" y="{H - 10}">lg: lambert_gouraud, lg+r: with silhouette refinement, bg: blinn_gouraud,'
             ' bp: blinn_phong, bpi: blinn_phong_inc; f32: the f32 tier (RV32IMC only); coarse sphere: the'
             ' standard scene\'s cost</text>')
    o.append("</svg>")
    return "\n".join(o) + "\n"


# ----------------------------------------------------------------------------- blocks


def with_block(text: str, block: str, anchors: list[str]) -> str:
    """`text` with the frontier block replaced, or inserted before the first anchor found."""
    a, b = MARK
    full = f"{a}\n{block}\n{b}"
    if a in text:
        i, j = text.index(a), text.index(b) + len(b)
        return text[:i] + full + text[j:]
    for anchor in anchors:
        if anchor in text:
            i = text.index(anchor)
            return text[:i] + full + "\n\n" + text[i:]
    sys.exit(f"frontier.py: no place for the block ({anchors})")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true",
                    help="recompute and compare with the committed outputs; exit 1 on a difference")
    args = ap.parse_args()
    err, err_text = run_frontier(write=not args.check)
    doc = join(err, json.loads(FRAME_JSON.read_text()))
    block = markdown(doc)
    outputs = {
        ERROR_JSON: err_text,
        FRONTIER_JSON: json.dumps(doc, indent=2, ensure_ascii=False) + "\n",
        SVG: svg(doc),
        # README: at the end of "Whole frames"; docs/tradeoff.md: after the frame and stage tables
        README: with_block(README.read_text(), block, ["## Number tiers and their error"]),
        TRADEOFF: with_block(TRADEOFF.read_text(), block, ["## How to read"]),
    }
    if args.check:
        bad = [str(p.relative_to(ROOT)) for p, t in outputs.items() if not p.exists() or p.read_text() != t]
        if bad:
            print("frontier.py --check: differ from a fresh run: " + ", ".join(bad), file=sys.stderr)
            return 1
        print("frontier.py --check: the committed outputs equal a fresh run")
        return 0
    for p, t in outputs.items():
        p.write_text(t)
        print(f"wrote {p.relative_to(ROOT)}")
    print(block)
    return 0


if __name__ == "__main__":
    sys.exit(main())
