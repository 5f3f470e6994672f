#!/usr/bin/env python3
"""Compares fixshade's renders of the conformance scenes with Mesa's, per scene and
tier, on interior pixels; prints a table and writes ``<out>/report.md`` and
``<out>/report.json``.

    python3 conformance/compare.py [--out DIR] [--scenes DIR] [--check] [--png]

Per scene and tier:

- **interior pixels**: covered by the same object and face in both renderers, and
  at least 2 px (Chebyshev) from any edge of either renderer's coverage (object
  and front/back-face boundaries);
- **|Δ|**: per pixel, the largest channel difference in 8-bit LSBs; reported as
  max, mean, and the shares of interior pixels within 1 and 2 LSB;
- **coverage differences**: pixels covered by a different object/face (or only by
  one renderer); *unexplained* are, in scenes whose vertices are not on the
  1/16-pixel grid, those whose centre is farther than 1/16 px from every projected
  triangle edge (vertex snapping moves an edge by at most 1/32·√2 px in fixshade,
  4 sub-pixel bits, and 1/512·√2 px in Mesa, 8 bits; for a triangle the near
  plane cuts, the edges of its visible polygon); in snapped scenes, all of them
  (both renderers rasterize the same triangles there).

Targets (issue 12): ``f32``, ``q30`` and ``ref`` within 1 LSB on ≥ 99.9 % of
interior pixels and within 2 LSB on all; ``q14`` within the bound the crate
documents for ``Q14<2>`` (README, "the bounds the tests assert": 1 LSB without a
highlight, 2 for shininess ≤ 64, 9 for ≤ 256); no unexplained coverage
difference; the tier supported (the harness reports no unsupported feature).

``q14`` alone leaves out pixels lit within 10⁻³ of a discontinuity of the
lighting equation (a spot cone's edge, the specular switch at N·L = 0), as the
crate's documented bounds do; the harness marks them from the f64 model.

``--check`` exits 1 when a scene/tier that is expected to pass fails (FAIL), or
one marked ``expect_fail`` in ``conformance/scenes.py`` passes (XPASS: support
has landed, remove the mark). Tiers marked ``known_issue`` (an accuracy problem of
a supported feature, close to the target) are reported as KPASS/KFAIL and never
fail the check.
"""

import argparse
import glob
import json
import os
import sys

import numpy as np

TIERS = ("f32", "q30", "q14", "ref")
EDGE_EPS = 1.0 / 16.0


def erode_same(ids, r=2):
    h, w = ids.shape
    pad = np.full((h + 2 * r, w + 2 * r), 0xFFFF, np.uint32)
    pad[r:r + h, r:r + w] = ids
    ok = ids != 0
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            ok &= pad[r + dy:r + dy + h, r + dx:r + dx + w] == ids
    return ok


def near_clipped(c):
    """The polygon of clip-space triangle ``c`` (3 × 4) on the visible side of
    OpenGL's near plane (z_c + w_c ≥ 0), Sutherland–Hodgman."""
    out = []
    for a, b in ((c[0], c[1]), (c[1], c[2]), (c[2], c[0])):
        da, db = a[2] + a[3], b[2] + b[3]
        if da >= 0:
            out.append(a)
        if (da >= 0) != (db >= 0):
            out.append(a + (b - a) * (da / (da - db)))
    return out


def window_edges(sc):
    """Every triangle edge in window coordinates (pixels, y down), float64; the
    edges of triangles the near plane cuts are those of the visible polygon."""
    proj = np.asarray(sc["camera"]["projection"])
    view = np.asarray(sc["camera"]["view"])
    w, h = sc["width"], sc["height"]
    segs = []

    def win(c):
        ndc = c[..., :3] / c[..., 3:4]
        return np.stack([(ndc[..., 0] + 1) * w / 2, (1 - ndc[..., 1]) * h / 2], -1)

    for o in sc["objects"]:
        mvp = proj @ view @ np.asarray(o["model"])
        p = np.asarray(o["mesh"]["positions"], float)
        c = np.c_[p, np.ones(len(p))] @ mvp.T
        t = np.asarray(o["mesh"]["triangles"])
        whole = ((c[t, 2] + c[t, 3]) >= 0).all(1)
        wt = win(c)[t[whole]]
        for a, b in ((0, 1), (1, 2), (2, 0)):
            segs.append(np.c_[wt[:, a], wt[:, b]])
        for tri in t[~whole]:
            poly = near_clipped(c[tri])
            pw = [win(v) for v in poly]
            for k in range(len(pw)):
                segs.append(np.r_[pw[k], pw[(k + 1) % len(pw)]][None, :])
    return np.concatenate(segs)


def edge_distance(px, segs):
    """Distance from each pixel centre (N × 2: x, y) to the nearest segment."""
    c = px[:, None, :] + 0.5
    a, b = segs[None, :, :2], segs[None, :, 2:]
    ab = b - a
    t = np.clip(((c - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-12), 0, 1)
    d = c - (a + t[..., None] * ab)
    return np.sqrt((d * d).sum(-1)).min(1)


def q14_bound(sc):
    """The documented Q14<2> bound for the scene's largest highlight exponent."""
    spec_lights = any(any(v != 0 for v in l["specular"][:3]) for l in sc["lights"])
    ns = [o[s]["shininess"] for o in sc["objects"] for s in ("front", "back")
          if any(v != 0 for v in o[s]["specular"][:3])]
    if not spec_lights or not ns:
        return 1
    n = max(ns)
    return 2 if n <= 64 else 9 if n <= 256 else 29


def target(tier, sc):
    if tier == "q14":
        b = q14_bound(sc)
        return {"max": b, "share1": None, "text": f"max ≤ {b}"}
    return {"max": 2, "share1": 0.999, "text": "≥ 99.9 % ≤ 1, max ≤ 2"}


def compare_scene(sc, out, man):
    name, w, h = sc["name"], sc["width"], sc["height"]
    mesa = np.load(os.path.join(out, "mesa", name + ".npz"))
    fdir = os.path.join(out, "fixshade")
    fid = np.fromfile(os.path.join(fdir, name + ".id"), "<u2").reshape(h, w)
    mid = mesa["id"]
    interior = mesa["interior"] & erode_same(fid) & (mid == fid)
    disc = np.fromfile(os.path.join(fdir, name + ".disc"), np.uint8).reshape(h, w) != 0
    diff_cov = np.argwhere(mid != fid)
    unexplained = 0
    if len(diff_cov) and not sc["snap"]:
        d = edge_distance(diff_cov[:, ::-1].astype(float), window_edges(sc))
        unexplained = int((d > EDGE_EPS).sum())
    else:
        # vertices on the 1/16-pixel grid: both renderers see the same triangles, so
        # snapping explains nothing (a difference is a fill-rule or setup difference)
        unexplained = int(len(diff_cov))
    rows = {}
    for tier in TIERS:
        info = man["tiers"][tier]
        img = np.fromfile(os.path.join(fdir, f"{name}.{tier}.rgb"), np.uint8).reshape(h, w, 3)
        delta = np.abs(img.astype(int) - mesa["rgb"].astype(int)).max(-1)
        # Q14's documented bounds exclude points within 1e-3 of a discontinuity
        mask = interior & ~disc if tier == "q14" else interior
        d = delta[mask]
        n = int(d.size)
        r = {
            "interior": n,
            "excluded_discontinuity": int((interior & disc).sum()) if tier == "q14" else 0,
            "max": int(d.max()) if n else None,
            "mean": float(d.mean()) if n else None,
            "share1": float((d <= 1).mean()) if n else None,
            "share2": float((d <= 2).mean()) if n else None,
            "coverage_diff": int(len(diff_cov)),
            "coverage_unexplained": unexplained,
            "status": info["status"],
            "unsupported": info["unsupported"],
            "warnings": info["warnings"],
            "target": target(tier, sc)["text"],
        }
        t = target(tier, sc)
        reasons = []
        if info["status"] != "ok":
            reasons.append("unsupported")
        if n < 50:
            reasons.append(f"only {n} interior pixels")
        else:
            if r["max"] > t["max"]:
                reasons.append(f"max {r['max']} > {t['max']}")
            if t["share1"] is not None and r["share1"] < t["share1"]:
                reasons.append(f"{100 * r['share1']:.2f} % ≤ 1 LSB")
        if unexplained:
            reasons.append(f"{unexplained} unexplained coverage differences")
        passed = not reasons
        xfail = sc["expect_fail"].get(tier)
        known = sc.get("known_issue", {}).get(tier)
        r["passed"] = passed
        r["why"] = "; ".join(reasons)
        r["expect_fail"] = xfail
        r["known_issue"] = known
        if xfail:
            r["outcome"] = "XPASS" if passed else "XFAIL"
        elif known:
            r["outcome"] = "KPASS" if passed else "KFAIL"
        else:
            r["outcome"] = "PASS" if passed else "FAIL"
        r["delta"] = delta
        rows[tier] = r
    return rows, interior


def fmt_row(name, tier, r):
    if r["interior"]:
        m = (f"{r['max']:>3} {r['mean']:6.3f} {100 * r['share1']:7.2f} {100 * r['share2']:7.2f}")
    else:
        m = f"{'-':>3} {'-':>6} {'-':>7} {'-':>7}"
    cov = f"{r['coverage_diff']}/{r['coverage_unexplained']}"
    ex = f"-{r['excluded_discontinuity']}" if r["excluded_discontinuity"] else ""
    px = f"{r['interior']}{ex}"
    return f"{name:26} {tier:4} {m} {px:>9} {cov:>7}  {r['outcome']:5} {r['why']}"


def save_png(sc, out, rows, interior):
    from PIL import Image
    name, w, h = sc["name"], sc["width"], sc["height"]
    mesa = np.load(os.path.join(out, "mesa", name + ".npz"))["rgb"]
    tiles = [mesa]
    for tier in TIERS:
        tiles.append(np.fromfile(os.path.join(out, "fixshade", f"{name}.{tier}.rgb"),
                                 np.uint8).reshape(h, w, 3))
    d = rows["f32"]["delta"]
    amp = np.clip(d * 32, 0, 255).astype(np.uint8)
    dimg = np.stack([amp, amp, amp], -1)
    dimg[~interior] //= 4
    tiles.append(dimg)
    sep = np.full((h, 2, 3), 64, np.uint8)
    strip = np.concatenate(sum([[t, sep] for t in tiles], [])[:-1], 1)
    os.makedirs(os.path.join(out, "png"), exist_ok=True)
    Image.fromarray(strip).save(os.path.join(out, "png", name + ".png"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="target/conformance")
    ap.add_argument("--scenes", default="target/conformance/scenes")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--png", action="store_true",
                    help="write <out>/png/<scene>.png: Mesa, f32, q30, q14, ref, |Δ f32|×32")
    a = ap.parse_args()
    with open(os.path.join(a.out, "fixshade", "manifest.json")) as f:
        manifest = json.load(f)
    meta_path = os.path.join(a.out, "mesa", "meta.json")
    meta = json.load(open(meta_path)) if os.path.exists(meta_path) else {}
    results, missing = {}, []
    header = (f"{'scene':26} {'tier':4} {'max':>3} {'mean':>6} {'≤1 %':>7} {'≤2 %':>7} "
              f"{'pixels':>9} {'cov/unx':>7}  result")
    print(header)
    for path in sorted(glob.glob(os.path.join(a.scenes, "*.json"))):
        with open(path) as f:
            sc = json.load(f)
        name = sc["name"]
        if name not in manifest or not os.path.exists(os.path.join(a.out, "mesa", name + ".npz")):
            missing.append(name)
            continue
        rows, interior = compare_scene(sc, a.out, manifest[name])
        if a.png:
            save_png(sc, a.out, rows, interior)
        for tier, r in rows.items():
            print(fmt_row(name, tier, r))
            r.pop("delta")
        results[name] = {"description": sc["description"], "features": sc["features"],
                         "tiers": rows}
    bad = [(s, t, r["outcome"], r["why"] or r["expect_fail"]) for s, v in results.items()
           for t, r in v["tiers"].items() if r["outcome"] in ("FAIL", "XPASS")]
    counts = {}
    for v in results.values():
        for r in v["tiers"].values():
            counts[r["outcome"]] = counts.get(r["outcome"], 0) + 1
    summary = ", ".join(f"{counts.get(k, 0)} {k}" for k in
                        ("PASS", "XFAIL", "KFAIL", "KPASS", "FAIL", "XPASS"))
    with open(os.path.join(a.out, "report.json"), "w") as f:
        json.dump({"mesa": meta, "results": results, "summary": counts}, f, indent=1)
    write_markdown(os.path.join(a.out, "report.md"), results, meta, summary)
    print(f"\n{len(results)} scenes: {summary}; report: {os.path.join(a.out, 'report.md')}")
    if missing:
        print(f"missing renders for: {', '.join(missing)}")
    for s, t, o, why in bad:
        print(f"{o}: {s} {t}: {why}")
    failed = len(bad) + len(missing)
    print(f"conformance: {sum(counts.values()) - len(bad)} passed, {failed} failed")
    if a.check and (bad or missing):
        sys.exit(1)


def write_markdown(path, results, meta, summary):
    gl = meta.get("gl", {})
    v = meta.get("versions", {})
    lines = [
        "# Conformance against Mesa (issue 12)",
        "",
        f"Mesa: {gl.get('renderer', '?')}, OpenGL {gl.get('version', '?')}, "
        f"GLSL {gl.get('glsl', '?')}; libosmesa6 {v.get('libosmesa6', '?')}, "
        f"PyOpenGL {v.get('PyOpenGL', '?')}, numpy {v.get('numpy', '?')}.",
        "",
        f"Result: {summary}.",
        "",
        "|Δ| is the largest channel difference in 8-bit LSBs on interior pixels; "
        "coverage = pixels covered differently / of those unexplained by vertex snapping.",
        "",
        "| scene | tier | max | mean | ≤ 1 LSB | ≤ 2 LSB | interior px | coverage | target | "
        "result |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for s, res in results.items():
        for t, r in res["tiers"].items():
            if r["interior"]:
                m = (f"{r['max']} | {r['mean']:.3f} | {100 * r['share1']:.2f} % | "
                     f"{100 * r['share2']:.2f} %")
            else:
                m = "- | - | - | -"
            why = f" ({r['why']})" if r["why"] else ""
            ex = (f" (−{r['excluded_discontinuity']} near a discontinuity)"
                  if r["excluded_discontinuity"] else "")
            lines.append(f"| {s} | {t} | {m} | {r['interior']}{ex} | {r['coverage_diff']}/"
                         f"{r['coverage_unexplained']} | {r['target']} | {r['outcome']}{why} |")
    lines += ["", "## Expected failures", ""]
    for s, res in results.items():
        xf = {t: r["expect_fail"] for t, r in res["tiers"].items() if r["expect_fail"]}
        if xf:
            reasons = sorted(set(xf.values()))
            lines.append(f"- **{s}** ({', '.join(xf)}): {'; '.join(reasons)}")
    lines += ["", "## Known issues (reported, never fail the check)", ""]
    for s, res in results.items():
        kn = {t: r["known_issue"] for t, r in res["tiers"].items() if r["known_issue"]}
        if kn:
            outcomes = ", ".join(f"{t} {res['tiers'][t]['outcome']}" for t in kn)
            lines.append(f"- **{s}** ({outcomes}): {'; '.join(sorted(set(kn.values())))}")
    lines += ["", "## Unsupported features and warnings reported by the harness", ""]
    for s, res in results.items():
        notes = []
        for t, r in res["tiers"].items():
            for u in r["unsupported"]:
                notes.append(f"unsupported: {u}")
            for wn in r["warnings"]:
                notes.append(f"warning ({t}): {wn}")
        seen = []
        for n in notes:
            if n not in seen:
                seen.append(n)
        for n in seen:
            lines.append(f"- {s}: {n}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
