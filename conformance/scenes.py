#!/usr/bin/env python3
"""The conformance scenes (issue 12): definitions, and the generator that writes
one self-contained JSON file per scene for both renderers.

    python3 conformance/scenes.py [--out target/conformance/scenes] [--list]

Every scene file holds everything both renderers need, exactly:

- ``camera``: ``projection`` and ``view`` (4×4, row-major, applied to column
  vectors as in OpenGL; every element a float32 value), ``near_w`` (the near plane:
  ``w_c`` at the eye-space distance ``near``), ``perspective`` (whether attributes
  are interpolated perspective-correctly), and the parameters the projection was
  made from (``ortho``: glOrtho's six, or ``fovy``, ``near``, ``far`` of
  gluPerspective), from which fixshade's mesh renderer builds its ``Camera``;
- ``width``/``height`` of the viewport (pixel (0, 0) is the top-left one);
- ``light_model``: ``ambient`` (RGBA), ``local_viewer``, ``two_side``,
  ``color_control`` (``"single"`` or ``"separate"``);
- ``normalize``: ``glEnable(GL_NORMALIZE)``;
- ``lights``: every ``glLightfv`` parameter of each enabled light, given in
  world coordinates: both renderers transform ``position`` and
  ``spot_direction`` by ``camera.view`` (the modelview current when
  ``glLightfv`` is called, as OpenGL does);
- ``objects``: a mesh (object-space ``positions``, ``normals``, optional RGBA
  ``colors``, counter-clockwise ``triangles``), its ``model`` matrix (modelview =
  view·model), ``front``/``back`` materials (every ``glMaterialfv`` parameter),
  ``shading`` (``flat`` = GL_FLAT, ``gouraud`` = GL_SMOOTH, ``phong`` and
  ``blinn`` = per-pixel GLSL), ``cull`` (back faces), ``color_material``,
  ``renderer`` (``"triangles"``: fixshade draws it triangle by triangle;
  ``"mesh"``: through its mesh renderer, the mesh in fixshade's format: positions
  multiples of ``2^-frac`` within ``i16``, ``mesh.frac``, normals multiples of
  ``2^-14``);
- ``expect_fail``: tier → reason, for the tiers the library cannot pass yet.

Positions are multiples of 2^-16 (fixshade reads them as Q16.16, exactly) and,
unless a scene sets ``snap: false``, placed so that every vertex projects onto
the 1/16-pixel grid: fixshade (4 sub-pixel bits) and Mesa (8) then rasterize
identical triangles, and interior pixels compare lighting only. Mesh-renderer
objects keep their ``i16`` positions (their scenes are not snapped).
"""

import argparse
import json
import math
import os
import sys

import numpy as np

F32 = np.float32
TIERS = ("f32", "q30", "q14", "ref")


def f32(x):
    """x rounded to float32, as a Python float (exact in JSON)."""
    return float(F32(x))


def f32v(v):
    return [f32(x) for x in v]


# ---------------------------------------------------------------- matrices (row-major)


def translate(t):
    m = np.eye(4)
    m[:3, 3] = t
    return m


def scale(s):
    return np.diag([s[0], s[1], s[2], 1.0])


def rotate(deg, axis):
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    x, y, z = a
    r = np.array(
        [
            [c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s],
            [y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s],
            [z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)],
        ]
    )
    m = np.eye(4)
    m[:3, :3] = r
    return m


def ortho(l, r, b, t, n, f):
    """glOrtho."""
    m = np.zeros((4, 4))
    m[0, 0] = 2 / (r - l)
    m[1, 1] = 2 / (t - b)
    m[2, 2] = -2 / (f - n)
    m[0, 3] = -(r + l) / (r - l)
    m[1, 3] = -(t + b) / (t - b)
    m[2, 3] = -(f + n) / (f - n)
    m[3, 3] = 1
    return m


def perspective(fovy_deg, aspect, n, f):
    """gluPerspective."""
    g = 1 / math.tan(math.radians(fovy_deg) / 2)
    m = np.zeros((4, 4))
    m[0, 0] = g / aspect
    m[1, 1] = g
    m[2, 2] = (f + n) / (n - f)
    m[2, 3] = 2 * f * n / (n - f)
    m[3, 2] = -1
    return m


def look_at(eye, target, up):
    """gluLookAt."""
    eye, target, up = (np.asarray(v, float) for v in (eye, target, up))
    fw = target - eye
    fw /= np.linalg.norm(fw)
    s = np.cross(fw, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, fw)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -fw
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def mat32(m):
    """A matrix rounded to float32 (kept as float64 numbers)."""
    return np.asarray(m, F32).astype(float)


# ---------------------------------------------------------------- meshes


def orient(positions, normals, tris):
    """Makes every triangle counter-clockwise seen from the side its vertex
    normals point to."""
    p, n = np.asarray(positions), np.asarray(normals)
    out = []
    for a, b, c in tris:
        g = np.cross(p[b] - p[a], p[c] - p[a])
        if np.dot(g, n[a] + n[b] + n[c]) < 0:
            b, c = c, b
        out.append([a, b, c])
    return out


def uv_sphere(stacks, slices, r=1.0, theta_max=math.pi):
    """A UV sphere around the origin (+y pole); with theta_max < π an open cap."""
    pos, nrm = [[0.0, r, 0.0]], [[0.0, 1.0, 0.0]]
    closed = theta_max >= math.pi
    rings = stacks - 1 if closed else stacks
    for i in range(1, rings + 1):
        th = theta_max * i / stacks
        for j in range(slices):
            ph = 2 * math.pi * j / slices
            n = [math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)]
            nrm.append(n)
            pos.append([r * c for c in n])
    tris = []
    ring = lambda i, j: 1 + (i - 1) * slices + (j % slices)
    for j in range(slices):
        tris.append([0, ring(1, j), ring(1, j + 1)])
    for i in range(1, rings):
        for j in range(slices):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)
            tris += [[a, c, b], [b, c, d]]
    if closed:
        pos.append([0.0, -r, 0.0])
        nrm.append([0.0, -1.0, 0.0])
        s = len(pos) - 1
        for j in range(slices):
            tris.append([s, ring(rings, j + 1), ring(rings, j)])
    return {"positions": pos, "normals": nrm, "triangles": orient(pos, nrm, tris)}


def quad_grid(nx, ny, sx, sy):
    """A plane z = 0, sx × sy, centred, facing +z, nx × ny cells of two triangles."""
    pos, nrm = [], []
    for j in range(ny + 1):
        for i in range(nx + 1):
            pos.append([sx * (i / nx - 0.5), sy * (j / ny - 0.5), 0.0])
            nrm.append([0.0, 0.0, 1.0])
    tris = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            tris += [[a, a + 1, a + nx + 2], [a, a + nx + 2, a + nx + 1]]
    return {"positions": pos, "normals": nrm, "triangles": orient(pos, nrm, tris)}


def flatten(mesh):
    """Every triangle its own three vertices carrying the face normal (for GL_FLAT
    and fixshade's Flat to light the same normal)."""
    p = np.asarray(mesh["positions"])
    pos, nrm, tris = [], [], []
    for a, b, c in mesh["triangles"]:
        g = np.cross(p[b] - p[a], p[c] - p[a])
        g = g / np.linalg.norm(g)
        k = len(pos)
        for v in (a, b, c):
            pos.append(list(p[v]))
            nrm.append(list(g))
        tris.append([k, k + 1, k + 2])
    return {"positions": pos, "normals": nrm, "triangles": tris}


def fill_rule_fan(w=128, h=128, px_per_unit=40.0):
    """Triangles around the centre of pixel (64, 64) with corners on pixel centres
    (for the orthographic camera of a w × h scene); each triangle has its own tilted
    normal, so pixels on a shared edge show which triangle owns them."""
    ring = [(30, 0), (30, 30), (0, 30), (-20, 30), (-30, 10), (-30, -30), (0, -30),
            (7, -30), (25, -30), (30, -11)]
    def eye(dx, dy):  # pixel centre (64.5 + dx, 64.5 + dy), y down
        return [(64.5 + dx - w / 2) / px_per_unit, (h / 2 - (64.5 + dy)) / px_per_unit, 0.0]
    pos, nrm, tris = [], [], []
    for k in range(len(ring)):
        a = 2 * math.pi * k / len(ring)
        n = [0.45 * math.cos(a), 0.45 * math.sin(a), 1.0]
        base = len(pos)
        for dx, dy in ((0, 0), ring[k], ring[(k + 1) % len(ring)]):
            pos.append(eye(dx, dy))
            nrm.append(n)
        tris.append([base, base + 1, base + 2])
    return {"positions": pos, "normals": nrm, "triangles": orient(pos, [[0, 0, 1]] * len(pos), tris)}


def with_normal_length(mesh, length):
    """Normals scaled to a non-unit length (for GL_NORMALIZE off)."""
    m = dict(mesh)
    m["normals"] = [[c * length for c in n] for n in mesh["normals"]]
    return m


def with_colors(mesh, fn):
    m = dict(mesh)
    m["colors"] = [fn(p) for p in mesh["positions"]]
    return m


# ---------------------------------------------------------------- GL parameter sets


def light(**kw):
    """One light with OpenGL's defaults for GL_LIGHT1..7 (index 0 overrides)."""
    d = {
        "ambient": [0.0, 0.0, 0.0, 1.0],
        "diffuse": [0.0, 0.0, 0.0, 1.0],
        "specular": [0.0, 0.0, 0.0, 1.0],
        "position": [0.0, 0.0, 1.0, 0.0],
        "spot_direction": [0.0, 0.0, -1.0],
        "spot_exponent": 0.0,
        "spot_cutoff": 180.0,
        "constant_attenuation": 1.0,
        "linear_attenuation": 0.0,
        "quadratic_attenuation": 0.0,
    }
    for k, v in kw.items():
        if k not in d:
            raise KeyError(k)
        d[k] = v
    return d


def light0(**kw):
    return light(**{"diffuse": [1.0] * 4, "specular": [1.0] * 4, **kw})


def white(k=1.0, **kw):
    return light(**{"diffuse": [k, k, k, 1.0], "specular": [k, k, k, 1.0], **kw})


def rgba(c, a=1.0):
    return list(c) + [a] if len(c) == 3 else list(c)


def material(**kw):
    """OpenGL's default material with overrides."""
    d = {
        "ambient": [0.2, 0.2, 0.2, 1.0],
        "diffuse": [0.8, 0.8, 0.8, 1.0],
        "specular": [0.0, 0.0, 0.0, 1.0],
        "emission": [0.0, 0.0, 0.0, 1.0],
        "shininess": 0.0,
    }
    for k, v in kw.items():
        if k == "ambient_and_diffuse":
            d["ambient"] = d["diffuse"] = rgba(v)
            d["set_ambient_and_diffuse"] = True
        elif k in d:
            d[k] = rgba(v) if isinstance(v, (list, tuple)) else v
        else:
            raise KeyError(k)
    return d


def plastic(color, n, ks=0.6, ka=0.15, kd=0.75):
    return material(
        ambient=[ka * c for c in color],
        diffuse=[kd * c for c in color],
        specular=[ks] * 3,
        shininess=n,
    )


def light_model(**kw):
    d = {"ambient": [0.2, 0.2, 0.2, 1.0], "local_viewer": False, "two_side": False,
         "color_control": "single"}
    for k, v in kw.items():
        if k not in d:
            raise KeyError(k)
        d[k] = rgba(v) if k == "ambient" else v
    return d


# ---------------------------------------------------------------- cameras


def ortho_camera(w, h, px_per_unit=40.0, eye_dist=5.0):
    hw, hh = w / 2 / px_per_unit, h / 2 / px_per_unit
    return {
        "kind": "orthographic",
        "projection": ortho(-hw, hw, -hh, hh, 1.0, 10.0),
        "view": translate([0.0, 0.0, -eye_dist]),
        "near_w": 0.5,
        "perspective": False,
        "ortho": [-hw, hw, -hh, hh, 1.0, 10.0],
    }


def persp_camera(w, h, eye=(0.0, 0.0, 5.0), target=(0.0, 0.0, 0.0), fovy=40.0, near=1.0,
                 far=20.0):
    return {
        "kind": "perspective",
        "projection": perspective(fovy, w / h, near, far),
        "view": look_at(eye, target, [0.0, 1.0, 0.0]),
        "near_w": near,
        "perspective": True,
        "fovy": fovy,
        "near": near,
        "far": far,
    }


def obj(mesh, mat, shading, model=None, back=None, cull=True, color_material=None,
        renderer="triangles"):
    return {
        "mesh": mesh,
        "model": np.eye(4) if model is None else model,
        "front": mat,
        "back": back if back is not None else mat,
        "shading": shading,
        "cull": cull,
        "color_material": color_material,
        "renderer": renderer,
    }


def mesh_format(mesh, frac):
    """A mesh in fixshade's compact format, as exact floats: positions rounded to
    multiples of 2^-frac (within i16), normals normalised and rounded to Q14."""
    one = 2 ** frac
    pos = [[round(c * one) / one for c in p] for p in mesh["positions"]]
    assert all(abs(c) * one <= 32767 for p in pos for c in p), "positions beyond i16"
    nrm = []
    for n in mesh["normals"]:
        n = np.asarray(n, float) / np.linalg.norm(n)
        nrm.append([round(c * 16384) / 16384 for c in n])
    return {**mesh, "positions": pos, "normals": nrm, "frac": frac}


# ---------------------------------------------------------------- the scenes

SPHERE = uv_sphere(16, 24)
SPHERE_FINE = uv_sphere(24, 36)
RED, BLUE, GREEN, GOLD = [1.0, 0.15, 0.1], [0.2, 0.35, 1.0], [0.2, 0.8, 0.3], [1.0, 0.75, 0.25]
KEY = [-0.4, 0.5, 0.77, 0.0]  # a directional key light from the upper left

ALL_TIERS = {t: None for t in TIERS}


def fail(reason, tiers=TIERS):
    return {t: reason for t in tiers}


def scene(name, desc, features, objects, lights, camera=None, w=128, h=128, lm=None,
          normalize=True, snap=True, expect_fail=None, known_issue=None):
    return {
        "name": name,
        "description": desc,
        "features": features,
        "width": w,
        "height": h,
        "camera": camera or ortho_camera(w, h),
        "light_model": lm or light_model(),
        "normalize": normalize,
        "snap": snap,
        "lights": lights,
        "objects": objects,
        "expect_fail": expect_fail or {},
        "known_issue": known_issue or {},
    }


def row(n, w, h, r, px_per_unit=40.0):
    """Model matrices placing n objects of radius r side by side in a w × h ortho view."""
    pitch = w / n / px_per_unit
    x0 = -w / 2 / px_per_unit + pitch / 2
    return [translate([x0 + i * pitch, 0.0, 0.0]) @ scale([r, r, r]) for i in range(n)]


def scenes():
    s = []
    sph = lambda m, sh, model=None, **kw: obj(SPHERE, m, sh, model=model, **kw)
    big = scale([1.45] * 3)

    # --- ordinary scenes --------------------------------------------------
    s.append(scene(
        "defaults_light0",
        "GL defaults: GL_LIGHT0 as it is, the default material and light model, Gouraud",
        ["defaults", "GL_SMOOTH"],
        [sph(material(), "gouraud", big)],
        [light0()],
    ))
    s.append(scene(
        "dir_gouraud",
        "one directional light, red plastic n = 32, Gouraud (GL_SMOOTH)",
        ["GL_POSITION w=0", "GL_DIFFUSE", "GL_SPECULAR", "GL_SHININESS", "GL_SMOOTH"],
        [sph(plastic(RED, 32.0), "gouraud", big)],
        [white(1.0, position=KEY)],
    ))
    s.append(scene(
        "dir_flat",
        "two directional lights, GL_FLAT on a sphere with face normals",
        ["GL_FLAT", "2 lights"],
        [obj(flatten(SPHERE), plastic(BLUE, 20.0), "flat", big)],
        [white(0.8, position=KEY), white(0.4, position=[0.7, -0.3, 0.6, 0.0])],
    ))
    s.append(scene(
        "dir_phong_pp",
        "one directional light, per-pixel Phong (R·V)^20",
        ["per-pixel Phong"],
        [sph(plastic(RED, 20.0), "phong", big)],
        [white(1.0, position=KEY)],
    ))
    s.append(scene(
        "dir_blinn_pp",
        "one directional light, per-pixel Blinn-Phong (N·H)^64",
        ["per-pixel Blinn-Phong"],
        [sph(plastic(RED, 64.0), "blinn", big)],
        [white(1.0, position=KEY)],
    ))
    s.append(scene(
        "shininess_int_pp",
        "per-pixel Blinn-Phong, GL_SHININESS = 1, 10, 50, 128",
        ["GL_SHININESS (integers, up to the GL maximum 128)"],
        [sph(plastic(RED, n), "blinn", m)
         for n, m in zip([1.0, 10.0, 50.0, 128.0], row(4, 256, 64, 0.7))],
        [white(1.0, position=KEY)],
        w=256, h=64,
    ))
    s.append(scene(
        "shininess_gouraud",
        "Gouraud, GL_SHININESS = 0, 5, 30, 128 (0: the specular colour wherever N·H > 0)",
        ["GL_SHININESS 0", "GL_SMOOTH"],
        [obj(SPHERE_FINE, plastic(GOLD, n, ks=0.4), "gouraud", m)
         for n, m in zip([0.0, 5.0, 30.0, 128.0], row(4, 256, 64, 0.7))],
        [white(0.9, position=[0.3, 0.4, 0.87, 0.0])],
        w=256, h=64,
    ))
    s.append(scene(
        "point_atten",
        "a point light with constant, linear and quadratic attenuation lighting a sphere "
        "(per-pixel Blinn-Phong) in front of a quad (Gouraud)",
        ["GL_POSITION w=1", "GL_CONSTANT_ATTENUATION", "GL_LINEAR_ATTENUATION",
         "GL_QUADRATIC_ATTENUATION", "light GL_AMBIENT"],
        [sph(plastic(RED, 40.0), "blinn", translate([0.2, 0.2, 0.5]) @ scale([0.9] * 3)),
         obj(quad_grid(16, 16, 3.4, 3.4), plastic(BLUE, 10.0, ks=0.3), "gouraud",
             translate([0.0, 0.0, -1.0]))],
        [white(1.0, position=[-1.0, 1.5, 2.5, 1.0], ambient=[0.1, 0.1, 0.1, 1.0],
               constant_attenuation=0.6, linear_attenuation=0.15,
               quadratic_attenuation=0.04)],
    ))
    s.append(scene(
        "spot_pp",
        "a spot light (cutoff 30°, exponent 20) on a quad and a sphere, per-pixel Blinn-Phong",
        ["GL_SPOT_DIRECTION", "GL_SPOT_EXPONENT", "GL_SPOT_CUTOFF", "per-pixel Blinn-Phong"],
        [obj(quad_grid(4, 4, 3.4, 3.4), plastic([0.9, 0.9, 0.9], 30.0, ks=0.3), "blinn",
             translate([0.0, 0.0, -1.0])),
         sph(plastic(GREEN, 30.0), "blinn", translate([0.6, -0.5, 0.0]) @ scale([0.6] * 3))],
        [white(1.0, position=[-1.2, 1.2, 2.5, 1.0], spot_direction=[0.5, -0.5, -1.0],
               spot_cutoff=30.0, spot_exponent=20.0)],
    ))
    s.append(scene(
        "spot_gouraud",
        "a spot light (cutoff 40°, exponent 8, linear attenuation) on a finely tessellated "
        "quad, Gouraud",
        ["GL_SPOT_CUTOFF", "GL_SPOT_EXPONENT", "GL_LINEAR_ATTENUATION", "GL_SMOOTH"],
        [obj(quad_grid(32, 32, 3.2, 3.2), plastic([0.9, 0.8, 0.6], 16.0, ks=0.4), "gouraud",
             rotate(-20.0, [1.0, 0.0, 0.0]))],
        [white(1.0, position=[0.5, 0.8, 2.0, 1.0], spot_direction=[-0.2, -0.4, -1.0],
               spot_cutoff=40.0, spot_exponent=8.0, linear_attenuation=0.1)],
    ))
    s.append(scene(
        "spot_hemisphere",
        "spot cutoff 90° with exponent 0 (a hemisphere of uniform intensity), Gouraud",
        ["GL_SPOT_CUTOFF 90", "GL_SPOT_EXPONENT 0"],
        [sph(plastic(GOLD, 24.0), "gouraud", big)],
        [white(1.0, position=[0.0, 0.5, 4.0, 1.0], spot_direction=[0.0, -0.1, -1.0],
               spot_cutoff=90.0, spot_exponent=0.0)],
    ))
    s.append(scene(
        "eight_lights",
        "all eight lights: coloured directional, point (attenuated) and spot lights, each "
        "with an ambient colour; per-pixel Blinn-Phong; sums above 1 clamp",
        ["8 lights", "light GL_AMBIENT", "mixed light kinds", "clamping",
         "attenuation ignored for directional lights"],
        [sph(plastic([0.8, 0.8, 0.8], 24.0, ks=0.5, ka=0.2, kd=0.6), "blinn", big)],
        [
            light(diffuse=[0.5, 0.1, 0.1, 1], specular=[0.5, 0.2, 0.2, 1], position=KEY,
                  ambient=[0.05, 0.0, 0.0, 1], linear_attenuation=0.5,
                  quadratic_attenuation=0.5),  # ignored: directional
            light(diffuse=[0.1, 0.4, 0.1, 1], specular=[0.2, 0.4, 0.2, 1],
                  position=[0.6, 0.3, 0.7, 0.0]),
            light(diffuse=[0.1, 0.1, 0.5, 1], specular=[0.2, 0.2, 0.5, 1],
                  position=[0.0, -0.7, 0.7, 0.0], ambient=[0.0, 0.0, 0.05, 1]),
            light(diffuse=[0.4, 0.4, 0.2, 1], specular=[0.4, 0.4, 0.2, 1],
                  position=[1.5, 1.5, 2.0, 1.0], linear_attenuation=0.2),
            light(diffuse=[0.3, 0.2, 0.4, 1], specular=[0.3, 0.2, 0.4, 1],
                  position=[-1.8, -1.0, 1.5, 1.0], quadratic_attenuation=0.1,
                  ambient=[0.03, 0.03, 0.03, 1]),
            light(diffuse=[0.2, 0.3, 0.3, 1], specular=[0.2, 0.3, 0.3, 1],
                  position=[0.0, 2.0, 0.5, 1.0], constant_attenuation=0.8,
                  linear_attenuation=0.1),
            light(diffuse=[0.6, 0.6, 0.6, 1], specular=[0.6, 0.6, 0.6, 1],
                  position=[0.0, 0.0, 3.0, 1.0], spot_direction=[0.1, 0.1, -1.0],
                  spot_cutoff=25.0, spot_exponent=30.0),
            light(diffuse=[0.5, 0.3, 0.0, 1], specular=[0.5, 0.3, 0.0, 1],
                  position=[2.0, -2.0, 1.0, 1.0], spot_direction=[-1.0, 1.0, -0.5],
                  spot_cutoff=45.0, spot_exponent=4.0, quadratic_attenuation=0.05),
        ],
    ))
    s.append(scene(
        "emission_ambient",
        "material emission, GL_AMBIENT_AND_DIFFUSE, light ambient and the global "
        "GL_LIGHT_MODEL_AMBIENT, Gouraud",
        ["GL_EMISSION", "GL_AMBIENT_AND_DIFFUSE", "GL_LIGHT_MODEL_AMBIENT", "light GL_AMBIENT"],
        [sph(material(ambient_and_diffuse=[0.5, 0.3, 0.6], specular=[0.3, 0.3, 0.3],
                      emission=[0.1, 0.05, 0.2], shininess=12.0), "gouraud", big)],
        [white(0.6, position=KEY, ambient=[0.2, 0.1, 0.1, 1.0])],
        lm=light_model(ambient=[0.3, 0.25, 0.2]),
    ))
    s.append(scene(
        "material_channels",
        "per-channel material and light colours that differ in every term, per-pixel "
        "Blinn-Phong and Gouraud",
        ["GL_AMBIENT", "GL_DIFFUSE", "GL_SPECULAR (coloured)"],
        [sph(material(ambient=[0.3, 0.1, 0.05], diffuse=[0.2, 0.6, 0.3],
                      specular=[0.9, 0.5, 0.1], shininess=16.0), m_shade, m)
         for m_shade, m in zip(["blinn", "gouraud"], row(2, 192, 96, 1.1))],
        [light(ambient=[0.2, 0.3, 0.4, 1], diffuse=[0.9, 0.7, 0.5, 1],
               specular=[0.6, 0.8, 1.0, 1], position=KEY)],
        w=192, h=96,
    ))
    s.append(scene(
        "local_viewer_pp",
        "GL_LIGHT_MODEL_LOCAL_VIEWER with a point light, perspective camera, per-pixel "
        "Blinn-Phong",
        ["GL_LIGHT_MODEL_LOCAL_VIEWER", "perspective"],
        [sph(plastic(BLUE, 48.0), "blinn", scale([1.3] * 3))],
        [white(1.0, position=[1.5, 1.0, 3.0, 1.0])],
        camera=persp_camera(128, 128),
        lm=light_model(local_viewer=True),
    ))
    s.append(scene(
        "local_viewer_gouraud",
        "GL_LIGHT_MODEL_LOCAL_VIEWER with a directional light, Gouraud on a quad and a sphere",
        ["GL_LIGHT_MODEL_LOCAL_VIEWER", "GL_SMOOTH"],
        [obj(quad_grid(16, 16, 3.4, 3.4), plastic([0.4, 0.45, 0.5], 40.0, ks=0.6, ka=0.1),
             "gouraud", translate([0.0, 0.0, -1.0])),
         sph(plastic(RED, 20.0), "gouraud", translate([0.4, 0.3, 0.0]) @ scale([0.8] * 3))],
        [white(0.8, position=[0.0, 0.3, 1.0, 0.0])],
        lm=light_model(local_viewer=True),
    ))
    s.append(scene(
        "persp_gouraud",
        "perspective camera, Gouraud sphere over a floor quad (perspective-correct colours)",
        ["perspective", "GL_SMOOTH"],
        [sph(plastic(GOLD, 32.0), "gouraud", translate([0.0, 0.2, 0.0])),
         obj(quad_grid(12, 12, 6.0, 6.0), plastic([0.6, 0.6, 0.7], 8.0, ks=0.2), "gouraud",
             translate([0.0, -0.8, 0.0]) @ rotate(-90.0, [1.0, 0.0, 0.0]))],
        [white(1.0, position=[-0.5, 1.0, 0.6, 0.0])],
        camera=persp_camera(128, 128, eye=(0.0, 1.5, 4.5), target=(0.0, 0.0, 0.0)),
    ))
    s.append(scene(
        "persp_phong_pp",
        "perspective camera, per-pixel Phong (R·V)^30 with a point light",
        ["perspective", "per-pixel Phong", "GL_POSITION w=1"],
        [sph(plastic(GREEN, 30.0), "phong", scale([1.2] * 3))],
        [white(1.0, position=[2.0, 2.0, 3.0, 1.0], quadratic_attenuation=0.02)],
        camera=persp_camera(128, 128, eye=(0.0, 0.0, 4.5)),
    ))
    s.append(scene(
        "camera_orbit",
        "an oblique camera (gluLookAt): light positions and the spot direction are given in "
        "world space and transformed by the modelview at glLightfv time",
        ["GL_POSITION (modelview)", "GL_SPOT_DIRECTION (modelview)", "perspective"],
        [sph(plastic(RED, 24.0), "blinn", translate([0.0, 0.0, 0.0])),
         obj(quad_grid(8, 8, 5.0, 5.0), plastic([0.45, 0.45, 0.45], 12.0, ks=0.3), "blinn",
             translate([0.0, -1.0, 0.0]) @ rotate(-90.0, [1.0, 0.0, 0.0]))],
        [white(0.5, position=[1.0, 1.0, 0.0, 0.0]),
         white(0.9, position=[-1.5, 2.5, 1.0, 1.0], spot_direction=[1.5, -3.5, -1.0],
               spot_cutoff=35.0, spot_exponent=6.0)],
        camera=persp_camera(128, 128, eye=(3.0, 2.0, 3.5), target=(0.0, -0.3, 0.0)),
    ))
    s.append(scene(
        "light_w2",
        "a positional light given with w = 2 (homogeneous GL_POSITION: the light is at xyz/w)",
        ["GL_POSITION w≠1"],
        [sph(plastic(BLUE, 32.0), "blinn", big)],
        [white(1.0, position=[-2.0, 3.0, 6.0, 2.0], linear_attenuation=0.05)],
    ))
    s.append(scene(
        "big_quads",
        "two large quads (two triangles each) with a highlight at their centre: Gouraud "
        "misses it, per-pixel Blinn-Phong shows it",
        ["GL_SMOOTH", "per-pixel Blinn-Phong", "interpolation across large triangles"],
        [obj({"positions": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
              "normals": [[-0.5, -0.5, 0.707], [0.5, -0.5, 0.707], [0.5, 0.5, 0.707],
                          [-0.5, 0.5, 0.707]],
              "triangles": [[0, 1, 2], [0, 2, 3]]},
             plastic(BLUE, 30.0, ks=0.8), sh, translate([x, 0.0, 0.0]) @ scale([1.0] * 3))
         for sh, x in (("gouraud", -1.2), ("blinn", 1.2))],
        [white(1.0, position=[0.0, 0.0, 1.0, 0.0])],
        w=192, h=96,
    ))
    s.append(scene(
        "saturation",
        "two bright lights whose sum exceeds 1: GL clamps the colour after summing",
        ["clamping", "2 lights"],
        [sph(plastic([1.0, 0.6, 0.3], 16.0, ks=0.7, kd=0.9), sh, m)
         for sh, m in zip(["gouraud", "blinn"], row(2, 192, 96, 1.1))],
        [white(0.9, position=KEY), white(0.9, position=[0.5, 0.2, 0.8, 0.0])],
        w=192, h=96,
    ))
    s.append(scene(
        "unsnapped",
        "nine rotated spheres whose vertices are not placed on the 1/16-pixel grid: coverage "
        "and interpolation differences from vertex snapping (4 sub-pixel bits against 8)",
        ["vertex snapping"],
        [sph(plastic(c, 32.0), "gouraud",
             translate([-1.02 + 1.0213 * (k % 3), -1.03 + 1.0197 * (k // 3), 0.0])
             @ rotate(7.0 + 23.0 * k, [0.3, 1.0, 0.2]) @ scale([0.47 + 0.004 * k] * 3))
         for k, c in enumerate([RED, BLUE, GREEN, GOLD, RED, BLUE, GREEN, GOLD, RED])],
        [white(1.0, position=KEY)],
        snap=False,
    ))

    s.append(scene(
        "fill_rule",
        "a fan of triangles whose vertices lie on pixel centres (horizontal, vertical, "
        "diagonal and other edges through pixel centres), each with its own flat colour: "
        "tests that Mesa (after the y flip) and fixshade break ties alike",
        ["rasterization rule", "GL_FLAT"],
        [obj(fill_rule_fan(), plastic([0.9, 0.9, 0.9], 10.0, ks=0.2), "flat")],
        [white(1.0, position=[0.5, 0.4, 0.77, 0.0])],
    ))

    # --- the rows of issue 12's table --------------------------------------
    s.append(scene(
        "light_color_ge2",
        "light colours 2.5 and 3 (GL allows any value) on a dark material",
        ["light GL_DIFFUSE ≥ 2", "light GL_SPECULAR ≥ 2"],
        [sph(plastic([0.3, 0.2, 0.15], 40.0, ks=0.25, ka=0.1, kd=1.0), "blinn", big)],
        [light(diffuse=[2.5, 2.5, 2.5, 1], specular=[3.0, 2.0, 2.0, 1], position=KEY)],
    ))
    s.append(scene(
        "const_atten_quarter",
        "GL_CONSTANT_ATTENUATION 0.25 (the light is 4× brighter than its colour)",
        ["GL_CONSTANT_ATTENUATION < 1"],
        [sph(plastic(GOLD, 20.0), "gouraud", big)],
        [white(0.2, position=[-1.0, 1.5, 3.0, 1.0], constant_attenuation=0.25)],
    ))
    s.append(scene(
        "shininess_fractional",
        "fractional GL_SHININESS 1.5, 12.8 and 27.8974, per-pixel Blinn-Phong",
        ["GL_SHININESS fractional"],
        [sph(plastic(RED, n, ks=0.8), "blinn", m)
         for n, m in zip([1.5, 12.8, 27.8974], row(3, 192, 64, 0.75))],
        [white(1.0, position=KEY)],
        w=192, h=64,
    ))
    s.append(scene(
        "spot_exponent_fractional",
        "fractional GL_SPOT_EXPONENT 2.5 on a quad, per-pixel Blinn-Phong",
        ["GL_SPOT_EXPONENT fractional"],
        [obj(quad_grid(4, 4, 3.4, 3.4), plastic([0.6, 0.6, 0.6], 10.0, ks=0.2), "blinn",
             translate([0.0, 0.0, -1.0]))],
        [white(1.0, position=[0.0, 0.0, 2.0, 1.0], spot_direction=[0.0, 0.0, -1.0],
               spot_cutoff=60.0, spot_exponent=2.5)],
    ))
    s.append(scene(
        "negative_colors",
        "a light with a negative (subtractive) diffuse colour and a material with a negative "
        "ambient channel; GL clamps only the final colour",
        ["negative light GL_DIFFUSE", "negative material GL_AMBIENT"],
        [sph(material(ambient=[0.4, -0.2, 0.3], diffuse=[0.7, 0.7, 0.7],
                      specular=[0.4, 0.4, 0.4], shininess=20.0), "gouraud", big)],
        [white(1.0, position=KEY),
         light(diffuse=[-0.4, 0.0, -0.2, 1], position=[0.6, -0.2, 0.8, 0.0])],
        lm=light_model(ambient=[0.5, 0.5, 0.5]),
    ))
    s.append(scene(
        "normalize_off",
        "GL_NORMALIZE disabled with normals of length 0.7 (GL lights the short normal as it "
        "is: dimmer diffuse, specular (0.7·N·H)^n)",
        ["GL_NORMALIZE off", "non-unit normals"],
        [obj(with_normal_length(SPHERE, 0.7), plastic(RED, 8.0), "gouraud", big)],
        [white(1.0, position=KEY)],
        normalize=False,
    ))
    bowl = uv_sphere(10, 24, theta_max=math.pi / 2)
    s.append(scene(
        "two_side",
        "GL_LIGHT_MODEL_TWO_SIDE: an open hemisphere seen from above shows its inside (back "
        "faces, lit with the back material and the negated normal), no culling",
        ["GL_LIGHT_MODEL_TWO_SIDE", "back material"],
        [obj(bowl, plastic(GOLD, 20.0), "gouraud",
             rotate(35.0, [1.0, 0.0, 0.0]) @ rotate(180.0, [1.0, 0.0, 0.0]) @ big,
             back=plastic(BLUE, 20.0), cull=False)],
        [white(1.0, position=[0.3, 0.6, 0.75, 0.0])],
        lm=light_model(two_side=True),
    ))
    s.append(scene(
        "color_material",
        "GL_COLOR_MATERIAL: per-vertex colours replace the ambient and diffuse material "
        "(GL_AMBIENT_AND_DIFFUSE, Gouraud) and the specular material (per-pixel Blinn-Phong)",
        ["GL_COLOR_MATERIAL", "glColorMaterial"],
        [obj(with_colors(SPHERE, lambda p: [0.5 + 0.5 * p[0], 0.5 + 0.5 * p[1],
                                            0.5 - 0.5 * p[0], 1.0]),
             plastic([0.5, 0.5, 0.5], 24.0), "gouraud", m,
             color_material={"face": "front_and_back", "mode": mode})
         for m, mode in zip(row(2, 192, 96, 1.1), ["ambient_and_diffuse", "specular"])],
        [white(1.0, position=KEY)],
        w=192, h=96,
    ))
    s.append(scene(
        "separate_specular",
        "GL_LIGHT_MODEL_COLOR_CONTROL = GL_SEPARATE_SPECULAR_COLOR with Gouraud: primary and "
        "secondary colours are clamped per vertex and interpolated separately",
        ["GL_LIGHT_MODEL_COLOR_CONTROL"],
        [obj(uv_sphere(8, 12), plastic([1.0, 0.9, 0.8], 6.0, ks=0.9, kd=1.0, ka=0.3),
             "gouraud", big)],
        [white(1.0, position=[0.0, 0.2, 1.0, 0.0])],
        lm=light_model(color_control="separate", ambient=[0.4, 0.4, 0.4]),
    ))
    s.append(scene(
        "flat_provoking",
        "GL_FLAT with smooth vertex normals and a point light: GL uses the colour lit at the "
        "provoking (last) vertex of each triangle",
        ["GL_FLAT provoking vertex", "GL_POSITION w=1"],
        [sph(plastic(GREEN, 16.0), "flat", big)],
        [white(1.0, position=[-1.0, 1.0, 2.0, 1.0])],
    ))

    # --- the mesh renderer (issue 18 item 2) --------------------------------
    # A floor receding from below the camera (its nearest triangles cross the near
    # plane) to 36 units away: big triangles whose depth changes a lot, where
    # screen-affine interpolation was 8 (Gouraud) and 41 (per pixel) LSB off.
    floor = mesh_format(quad_grid(16, 16, 2.0, 2.0), 14)
    floor_model = (translate([0.0, 0.0, -16.0]) @ rotate(-90.0, [1.0, 0.0, 0.0])
                   @ scale([20.0, 20.0, 1.0]))
    floor_cam = persp_camera(128, 128, eye=(0.0, 0.7, 0.5), target=(0.0, 0.3, -8.0),
                             fovy=55.0, near=0.3, far=60.0)
    floor_lights = [white(1.0, position=[1.0, 1.5, -5.0, 1.0], linear_attenuation=0.08),
                    white(0.3, position=[-0.3, 1.0, 0.4, 0.0])]
    for sh, what in (("gouraud", "Gouraud"), ("blinn", "per-pixel Blinn-Phong")):
        s.append(scene(
            f"mesh_floor_{'gouraud' if sh == 'gouraud' else 'pp'}",
            f"the mesh renderer (MeshDraw): a 40 × 40 floor of 512 triangles receding from "
            f"across the near plane to 36 units away, a point light and a local viewer, "
            f"{what}",
            ["mesh renderer", "perspective", "near-plane clipping",
             "perspective-correct interpolation", "GL_LIGHT_MODEL_LOCAL_VIEWER"],
            [obj(floor, plastic([0.55, 0.6, 0.7], 24.0, ks=0.5), sh, floor_model,
                 renderer="mesh")],
            floor_lights,
            camera=floor_cam,
            lm=light_model(local_viewer=True),
            snap=False,
        ))
    # A sphere the near plane cuts: the eye 2 units from its surface, the near plane
    # 2.02 units in front of the eye, the cap it cuts off a little off the centre.
    ball = mesh_format(SPHERE_FINE, 14)
    ball_cam = persp_camera(128, 128, eye=(0.9, 1.1, 2.6), target=(0.15, 0.1, 0.0),
                            fovy=48.0, near=2.02)
    ball_lights = [white(0.8, position=KEY), white(0.6, position=[-1.5, 1.0, 2.0, 1.0])]
    for sh, what in (("gouraud", "Gouraud"), ("phong", "per-pixel Phong (R·V)^32")):
        s.append(scene(
            f"mesh_near_sphere_{'gouraud' if sh == 'gouraud' else 'pp'}",
            f"the mesh renderer (MeshDraw): a sphere of 1656 triangles cut by the near "
            f"plane of a perspective camera, a directional and a point light, {what}",
            ["mesh renderer", "perspective", "near-plane clipping",
             "perspective-correct interpolation"],
            [obj(ball, plastic(GOLD, 32.0), sh, renderer="mesh")],
            ball_lights,
            camera=ball_cam,
            snap=False,
        ))
    return s


# ---------------------------------------------------------------- generation


def snap_positions(positions, modelview, projection, w, h):
    """Moves every vertex (keeping its eye-space depth) so that it projects onto the
    1/16-pixel grid, then rounds object coordinates to multiples of 2^-16."""
    mv, p = np.asarray(modelview), np.asarray(projection)
    inv = np.linalg.inv(mv)
    out = []
    for pos in positions:
        e = mv @ np.array([*pos, 1.0])
        c = p @ e
        ndc = c[:3] / c[3]
        sx = round((ndc[0] + 1) * w / 2 * 16) / 16
        sy = round((1 - ndc[1]) * h / 2 * 16) / 16
        nx, ny = sx * 2 / w - 1, 1 - sy * 2 / h
        # (P0 − nx·P3)·e = 0 and (P1 − ny·P3)·e = 0, solved for ex, ey at fixed ez
        r0, r1 = p[0] - nx * p[3], p[1] - ny * p[3]
        a = np.array([[r0[0], r0[1]], [r1[0], r1[1]]])
        b = -np.array([r0[2] * e[2] + r0[3] * e[3], r1[2] * e[2] + r1[3] * e[3]])
        ex, ey = np.linalg.solve(a, b)
        o = inv @ np.array([ex, ey, e[2], e[3]])
        out.append(o[:3] / o[3])
    return out


def quantize(v):
    return [round(float(c) * 65536) / 65536 for c in v]


def window_coords(positions, mvp, w, h):
    pts = np.c_[np.asarray(positions, float), np.ones(len(positions))] @ np.asarray(mvp).T
    ndc = pts[:, :3] / pts[:, 3:4]
    return np.c_[(ndc[:, 0] + 1) * w / 2, (1 - ndc[:, 1]) * h / 2]


def build(sc):
    cam = sc["camera"]
    proj, view = mat32(cam["projection"]), mat32(cam["view"])
    objects = []
    for o in sc["objects"]:
        model = mat32(o["model"])
        mesh = o["mesh"]
        pos = [quantize(p) for p in mesh["positions"]]
        if o["renderer"] == "mesh":
            assert not sc["snap"], f"{sc['name']}: mesh-renderer objects cannot be snapped"
            assert pos == mesh["positions"], f"{sc['name']}: not a mesh_format mesh"
        elif sc["snap"]:
            mv = view @ model
            pos = [quantize(p) for p in snap_positions(pos, mv, proj, sc["width"], sc["height"])]
            wc = window_coords(pos, proj @ mv, sc["width"], sc["height"])
            err = np.abs(wc * 16 - np.round(wc * 16)).max()
            assert err < 0.02, f"{sc['name']}: snapped vertex {err / 16:.5f} px off the grid"
        m = {
            "positions": pos,
            "normals": [f32v(n) for n in mesh["normals"]],
            "triangles": [list(map(int, t)) for t in mesh["triangles"]],
        }
        if "colors" in mesh:
            m["colors"] = [f32v(c) for c in mesh["colors"]]
        if "frac" in mesh:
            m["frac"] = mesh["frac"]
        objects.append({**o, "mesh": m, "model": model.tolist()})
    out = dict(sc)
    out["camera"] = {**cam, "projection": proj.tolist(), "view": view.tolist()}
    out["objects"] = objects
    for l in out["lights"]:
        for k, v in l.items():
            l[k] = f32v(v) if isinstance(v, list) else f32(v)
    for o in objects:
        for side in ("front", "back"):
            o[side] = {k: (f32v(v) if isinstance(v, list) else (v if isinstance(v, bool)
                                                                  else f32(v)))
                       for k, v in o[side].items()}
    out["light_model"] = {k: (f32v(v) if k == "ambient" else v)
                          for k, v in sc["light_model"].items()}
    for t in list(out["expect_fail"]) + list(out["known_issue"]):
        assert t in TIERS, t
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="target/conformance/scenes")
    ap.add_argument("--list", action="store_true", help="print the scenes and exit")
    ap.add_argument("--markdown", action="store_true",
                    help="print the scene table of conformance/README.md and exit")
    ap.add_argument("--only", nargs="*", help="scene names")
    a = ap.parse_args()
    all_scenes = scenes()
    names = [s["name"] for s in all_scenes]
    assert len(set(names)) == len(names)
    if a.markdown:
        print("| scene | what it draws | GL parameters exercised | shading | camera | "
              "expected to fail |")
        print("|---|---|---|---|---|---|")
        for s in all_scenes:
            shading = ", ".join(dict.fromkeys(
                {"flat": "GL_FLAT", "gouraud": "GL_SMOOTH", "phong": "per-pixel Phong",
                 "blinn": "per-pixel Blinn-Phong"}[o["shading"]] for o in s["objects"]))
            xf = ", ".join(s["expect_fail"]) or "–"
            if s["known_issue"]:
                xf += " (known issue: " + ", ".join(s["known_issue"]) + ")"
            cam = s["camera"]["kind"] + ("" if s["snap"] else ", unsnapped")
            if any(o["renderer"] == "mesh" for o in s["objects"]):
                cam += ", mesh renderer"
            print(f"| `{s['name']}` | {s['description']} | {'; '.join(s['features'])} | "
                  f"{shading} | {cam} | {xf} |")
        return
    if a.list:
        for s in all_scenes:
            xf = ", ".join(f"{t}" for t in s["expect_fail"]) or "-"
            if s["known_issue"]:
                xf += " (known: " + ", ".join(s["known_issue"]) + ")"
            print(f"{s['name']:26} xfail {xf:18} {'; '.join(s['features'])}")
        return
    os.makedirs(a.out, exist_ok=True)
    for old in os.listdir(a.out) if not a.only else []:
        if old.endswith(".json"):
            os.remove(os.path.join(a.out, old))
    for s in all_scenes:
        if a.only and s["name"] not in a.only:
            continue
        with open(os.path.join(a.out, s["name"] + ".json"), "w") as f:
            json.dump(build(s), f, separators=(",", ":"))
    print(f"{len(all_scenes)} scenes -> {a.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
