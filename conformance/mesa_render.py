#!/usr/bin/env python3
"""Renders every conformance scene with Mesa's software OpenGL (llvmpipe through
OSMesa) and writes, per scene, ``<out>/mesa/<scene>.npz`` with

- ``rgb``: the image (height × width × 3, uint8, row 0 at the top);
- ``id``: which object covers each pixel (uint16: object index + 1, plus 256 for
  a back face; 0 for the background), from a second pass with the same geometry;
- ``interior``: pixels at least 2 px from any edge of Mesa's coverage (the
  object-id boundaries: silhouettes, occlusion edges, front/back-face edges);

and ``<out>/mesa/meta.json`` (renderer strings and package versions).

    python3 conformance/mesa_render.py [--scenes DIR] [--out DIR] [--png] [names…]
    python3 conformance/mesa_render.py --selftest

``--selftest`` checks the shaders' lighting function against Mesa's fixed-function
lighting: every scene is drawn with GL_SMOOTH twice, lit by fixed function and
by the same GLSL function the per-pixel shader uses, evaluated per vertex (front
and back colours, separate specular, colour material, GL_NORMALIZE); it fails if
a pixel differs by more than 1 LSB.

How the scenes are drawn (see ``conformance/README.md``):

- fixed-function lighting for ``flat`` (GL_FLAT) and ``gouraud`` (GL_SMOOTH), a
  GLSL 1.20 shader that evaluates OpenGL's lighting equation per pixel from the
  built-in ``gl_LightSource[]``/``gl_FrontMaterial`` state for ``phong``
  ((R·V)^s) and ``blinn`` ((N·H)^s);
- the lights are set while ``camera.view`` is the modelview matrix, so OpenGL
  transforms ``GL_POSITION`` and ``GL_SPOT_DIRECTION`` itself;
- the projection is pre-multiplied by a y flip (and ``glFrontFace(GL_CW)``), so
  that GL's window row 0 is the top row: llvmpipe's tie-breaking rule for pixel
  centres exactly on a horizontal edge then agrees with fixshade's top-left
  rule (without the flip, Mesa includes the visually bottom edge). Lighting is
  computed in eye space and is unaffected.
"""

import argparse
import ctypes
import glob
import json
import os
import subprocess
import sys

os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")

import numpy as np  # noqa: E402
from OpenGL import GL as gl  # noqa: E402
from OpenGL import osmesa  # noqa: E402
from OpenGL.GL import shaders  # noqa: E402

FLIP = np.diag([1.0, -1.0, 1.0, 1.0])

VERTEX = """#version 120
varying vec3 v_pos;
varying vec3 v_nrm;
varying vec4 v_col;
void main() {
    vec4 e = gl_ModelViewMatrix * gl_Vertex;
    v_pos = e.xyz / e.w;
    v_nrm = gl_NormalMatrix * gl_Normal;
    v_col = gl_Color;
    gl_Position = ftransform();   // invariant with the fixed-function transform
}
"""

# OpenGL 2.1 §2.14.1 for one side of a surface, shared by the per-pixel shader
# and the per-vertex shader of --selftest (which checks it against fixed function).
LIGHTING = """
uniform int u_nlights;
uniform bool u_local_viewer;
uniform bool u_blinn;
uniform int u_cm_mode;      // 0 off, 1 ambient, 2 diffuse, 3 specular, 4 emission, 5 both
uniform bool u_cm_front;
uniform bool u_cm_back;
// The primary colour (emission, ambient, diffuse) at eye-space point pos with
// normal n (as given: not normalised here); the specular sum goes to spec.
vec3 lighting(vec3 pos, vec3 n, bool back, vec4 col, out vec3 spec) {
    vec4 ka = gl_FrontMaterial.ambient, kd = gl_FrontMaterial.diffuse;
    vec4 ks = gl_FrontMaterial.specular, ke = gl_FrontMaterial.emission;
    float sh = gl_FrontMaterial.shininess;
    if (back) {
        ka = gl_BackMaterial.ambient; kd = gl_BackMaterial.diffuse;
        ks = gl_BackMaterial.specular; ke = gl_BackMaterial.emission;
        sh = gl_BackMaterial.shininess;
    }
    if (u_cm_mode != 0 && ((back && u_cm_back) || (!back && u_cm_front))) {
        if (u_cm_mode == 1 || u_cm_mode == 5) ka = col;
        if (u_cm_mode == 2 || u_cm_mode == 5) kd = col;
        if (u_cm_mode == 3) ks = col;
        if (u_cm_mode == 4) ke = col;
    }
    vec3 v = u_local_viewer ? normalize(-pos) : vec3(0.0, 0.0, 1.0);
    vec3 prim = ke.rgb + gl_LightModel.ambient.rgb * ka.rgb;
    spec = vec3(0.0);
    for (int i = 0; i < 8; i++) {
        if (i >= u_nlights) break;
        vec4 lp = gl_LightSource[i].position;
        vec3 l;
        float k = 1.0;
        if (lp.w != 0.0) {
            vec3 d = lp.xyz / lp.w - pos;
            float dist = length(d);
            l = d / dist;
            k = 1.0 / (gl_LightSource[i].constantAttenuation
                       + gl_LightSource[i].linearAttenuation * dist
                       + gl_LightSource[i].quadraticAttenuation * dist * dist);
            if (gl_LightSource[i].spotCutoff != 180.0) {
                float c = dot(-l, normalize(gl_LightSource[i].spotDirection));
                float e = gl_LightSource[i].spotExponent;
                k *= c >= gl_LightSource[i].spotCosCutoff
                     ? (e == 0.0 ? 1.0 : pow(max(c, 0.0), e)) : 0.0;
            }
        } else {
            l = normalize(lp.xyz);
        }
        vec3 c = gl_LightSource[i].ambient.rgb * ka.rgb;
        vec3 s = vec3(0.0);
        float nl = dot(n, l);
        if (nl > 0.0) {
            c += gl_LightSource[i].diffuse.rgb * kd.rgb * nl;
            float x = u_blinn ? dot(n, normalize(l + v)) : dot(2.0 * nl * n - l, v);
            if (x > 0.0)
                s = gl_LightSource[i].specular.rgb * ks.rgb * (sh == 0.0 ? 1.0 : pow(x, sh));
        }
        prim += k * c;
        spec += k * s;
    }
    return prim;
}
"""

# Per pixel: the interpolated eye-space position and the renormalised
# interpolated normal (negated on back faces with two-sided lighting).
FRAGMENT = """#version 120
varying vec3 v_pos;
varying vec3 v_nrm;
varying vec4 v_col;
uniform bool u_two_side;
uniform bool u_separate;
""" + LIGHTING + """
void main() {
    vec3 n = normalize(v_nrm);
    bool back = u_two_side && !gl_FrontFacing;
    vec3 spec;
    vec3 prim = lighting(v_pos, back ? -n : n, back, v_col, spec);
    vec3 col = u_separate ? clamp(prim, 0.0, 1.0) + clamp(spec, 0.0, 1.0) : prim + spec;
    gl_FragColor = vec4(clamp(col, 0.0, 1.0), 1.0);
}
"""

# --selftest: the same function per vertex, as fixed function evaluates it
# (front and back colours, primary and secondary colour clamped per vertex).
SELFTEST_VERTEX = """#version 120
uniform bool u_two_side;
uniform bool u_separate;
uniform bool u_normalize;
""" + LIGHTING + """
void side(vec3 pos, vec3 n, bool back, out vec4 prim_out, out vec4 spec_out) {
    vec3 spec;
    vec3 prim = lighting(pos, n, back, gl_Color, spec);
    if (u_separate) {
        prim_out = vec4(clamp(prim, 0.0, 1.0), 1.0);
        spec_out = vec4(clamp(spec, 0.0, 1.0), 0.0);
    } else {
        prim_out = vec4(clamp(prim + spec, 0.0, 1.0), 1.0);
        spec_out = vec4(0.0);
    }
}
void main() {
    vec4 e = gl_ModelViewMatrix * gl_Vertex;
    vec3 pos = e.xyz / e.w;
    vec3 n = gl_NormalMatrix * gl_Normal;
    if (u_normalize) n = normalize(n);
    side(pos, n, false, gl_FrontColor, gl_FrontSecondaryColor);
    side(pos, -n, true, gl_BackColor, gl_BackSecondaryColor);
    gl_Position = ftransform();
}
"""

SELFTEST_FRAGMENT = """#version 120
void main() {
    gl_FragColor = vec4(clamp(gl_Color.rgb + gl_SecondaryColor.rgb, 0.0, 1.0), 1.0);
}
"""

CM_MODE = {"ambient": 1, "diffuse": 2, "specular": 3, "emission": 4, "ambient_and_diffuse": 5}
CM_GL = {
    "ambient": gl.GL_AMBIENT,
    "diffuse": gl.GL_DIFFUSE,
    "specular": gl.GL_SPECULAR,
    "emission": gl.GL_EMISSION,
    "ambient_and_diffuse": gl.GL_AMBIENT_AND_DIFFUSE,
}
FACE = {"front": gl.GL_FRONT, "back": gl.GL_BACK, "front_and_back": gl.GL_FRONT_AND_BACK}


def glmat(m):
    """A row-major matrix in OpenGL's column-major memory order."""
    return np.ascontiguousarray(np.asarray(m, np.float32).T)


def erode_same(ids, r=2):
    """Pixels whose (2r+1)² neighbourhood lies inside the image and carries their own
    non-zero id."""
    h, w = ids.shape
    pad = np.full((h + 2 * r, w + 2 * r), 0xFFFF, np.uint32)
    pad[r:r + h, r:r + w] = ids
    ok = ids != 0
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            ok &= pad[r + dy:r + dy + h, r + dx:r + dx + w] == ids
    return ok


class Mesa:
    def __init__(self):
        attrs = [osmesa.OSMESA_FORMAT, osmesa.OSMESA_RGBA, osmesa.OSMESA_DEPTH_BITS, 24,
                 osmesa.OSMESA_STENCIL_BITS, 0, osmesa.OSMESA_PROFILE,
                 osmesa.OSMESA_COMPAT_PROFILE, osmesa.OSMESA_CONTEXT_MAJOR_VERSION, 2,
                 osmesa.OSMESA_CONTEXT_MINOR_VERSION, 1, 0]
        self.ctx = osmesa.OSMesaCreateContextAttribs(attrs, None)
        if not self.ctx:
            sys.exit("OSMesaCreateContextAttribs failed (is libosmesa6 installed?)")
        self.buf = None
        self.size = None
        self.make_current(16, 16)
        names = ("u_nlights", "u_local_viewer", "u_two_side", "u_separate", "u_blinn",
                 "u_cm_mode", "u_cm_front", "u_cm_back", "u_normalize")
        self.programs = {}
        for key, vs, fs in (("pixel", VERTEX, FRAGMENT),
                            ("vertex", SELFTEST_VERTEX, SELFTEST_FRAGMENT)):
            prog = shaders.compileProgram(
                shaders.compileShader(vs, gl.GL_VERTEX_SHADER),
                shaders.compileShader(fs, gl.GL_FRAGMENT_SHADER),
                validate=False,
            )
            self.programs[key] = (prog, {n: gl.glGetUniformLocation(prog, n) for n in names})

    def make_current(self, w, h):
        self.buf = (ctypes.c_ubyte * (w * h * 4))()
        if not osmesa.OSMesaMakeCurrent(self.ctx, self.buf, gl.GL_UNSIGNED_BYTE, w, h):
            sys.exit("OSMesaMakeCurrent failed")
        self.size = (w, h)

    def info(self):
        return {k: gl.glGetString(v).decode() for k, v in (
            ("vendor", gl.GL_VENDOR), ("renderer", gl.GL_RENDERER),
            ("version", gl.GL_VERSION), ("glsl", gl.GL_SHADING_LANGUAGE_VERSION))}

    # -- state ---------------------------------------------------------------

    def setup(self, sc):
        w, h = sc["width"], sc["height"]
        self.make_current(w, h)
        gl.glViewport(0, 0, w, h)
        gl.glPixelStorei(gl.GL_PACK_ALIGNMENT, 1)
        gl.glDisable(gl.GL_DITHER)
        gl.glEnable(gl.GL_DEPTH_TEST)
        gl.glDepthFunc(gl.GL_LESS)
        gl.glClearColor(0.0, 0.0, 0.0, 0.0)
        gl.glClearDepth(1.0)
        gl.glFrontFace(gl.GL_CW)  # counter-clockwise before the y flip
        gl.glCullFace(gl.GL_BACK)
        gl.glMatrixMode(gl.GL_PROJECTION)
        gl.glLoadMatrixf(glmat(FLIP @ np.asarray(sc["camera"]["projection"])))
        gl.glMatrixMode(gl.GL_MODELVIEW)

    def lights(self, sc):
        gl.glLoadMatrixf(glmat(sc["camera"]["view"]))
        for i in range(8):
            gl.glDisable(gl.GL_LIGHT0 + i)
        for i, l in enumerate(sc["lights"]):
            li = gl.GL_LIGHT0 + i
            gl.glLightfv(li, gl.GL_AMBIENT, l["ambient"])
            gl.glLightfv(li, gl.GL_DIFFUSE, l["diffuse"])
            gl.glLightfv(li, gl.GL_SPECULAR, l["specular"])
            gl.glLightfv(li, gl.GL_POSITION, l["position"])
            gl.glLightfv(li, gl.GL_SPOT_DIRECTION, l["spot_direction"])
            gl.glLightf(li, gl.GL_SPOT_EXPONENT, l["spot_exponent"])
            gl.glLightf(li, gl.GL_SPOT_CUTOFF, l["spot_cutoff"])
            gl.glLightf(li, gl.GL_CONSTANT_ATTENUATION, l["constant_attenuation"])
            gl.glLightf(li, gl.GL_LINEAR_ATTENUATION, l["linear_attenuation"])
            gl.glLightf(li, gl.GL_QUADRATIC_ATTENUATION, l["quadratic_attenuation"])
            gl.glEnable(li)
        lm = sc["light_model"]
        gl.glLightModelfv(gl.GL_LIGHT_MODEL_AMBIENT, lm["ambient"])
        gl.glLightModeli(gl.GL_LIGHT_MODEL_LOCAL_VIEWER, int(lm["local_viewer"]))
        gl.glLightModeli(gl.GL_LIGHT_MODEL_TWO_SIDE, int(lm["two_side"]))
        gl.glLightModeli(gl.GL_LIGHT_MODEL_COLOR_CONTROL,
                         gl.GL_SEPARATE_SPECULAR_COLOR if lm["color_control"] == "separate"
                         else gl.GL_SINGLE_COLOR)
        (gl.glEnable if sc["normalize"] else gl.glDisable)(gl.GL_NORMALIZE)

    def material(self, o):
        sides = [(gl.GL_FRONT_AND_BACK, o["front"])] if o["front"] == o["back"] else [
            (gl.GL_FRONT, o["front"]), (gl.GL_BACK, o["back"])]
        for face, m in sides:
            if m.get("set_ambient_and_diffuse"):
                gl.glMaterialfv(face, gl.GL_AMBIENT_AND_DIFFUSE, m["diffuse"])
            else:
                gl.glMaterialfv(face, gl.GL_AMBIENT, m["ambient"])
                gl.glMaterialfv(face, gl.GL_DIFFUSE, m["diffuse"])
            gl.glMaterialfv(face, gl.GL_SPECULAR, m["specular"])
            gl.glMaterialfv(face, gl.GL_EMISSION, m["emission"])
            gl.glMaterialf(face, gl.GL_SHININESS, m["shininess"])

    def arrays(self, mesh, normals=True, colors=False):
        pos = np.asarray(mesh["positions"], np.float32)
        gl.glEnableClientState(gl.GL_VERTEX_ARRAY)
        gl.glVertexPointer(3, gl.GL_FLOAT, 0, pos)
        keep = [pos]
        if normals:
            nrm = np.asarray(mesh["normals"], np.float32)
            gl.glEnableClientState(gl.GL_NORMAL_ARRAY)
            gl.glNormalPointer(gl.GL_FLOAT, 0, nrm)
            keep.append(nrm)
        else:
            gl.glDisableClientState(gl.GL_NORMAL_ARRAY)
        if colors:
            col = np.asarray(mesh["colors"], np.float32)
            gl.glEnableClientState(gl.GL_COLOR_ARRAY)
            gl.glColorPointer(4, gl.GL_FLOAT, 0, col)
            keep.append(col)
        else:
            gl.glDisableClientState(gl.GL_COLOR_ARRAY)
            gl.glColor4f(1.0, 1.0, 1.0, 1.0)
        idx = np.asarray(mesh["triangles"], np.uint32).ravel()
        gl.glDrawElements(gl.GL_TRIANGLES, idx.size, gl.GL_UNSIGNED_INT, idx)
        del keep

    def read(self):
        w, h = self.size
        gl.glFinish()
        px = gl.glReadPixels(0, 0, w, h, gl.GL_RGB, gl.GL_UNSIGNED_BYTE)
        return np.frombuffer(px, np.uint8).reshape(h, w, 3).copy()

    # -- passes --------------------------------------------------------------

    def render(self, sc, selftest=None):
        """The scene's image. ``selftest``: every object drawn GL_SMOOTH with Blinn-Phong,
        lit by fixed function (``"fixed"``) or by ``lighting`` per vertex
        (``"vertex"``)."""
        self.setup(sc)
        gl.glClear(gl.GL_COLOR_BUFFER_BIT | gl.GL_DEPTH_BUFFER_BIT)
        self.lights(sc)
        gl.glEnable(gl.GL_LIGHTING)
        lm = sc["light_model"]
        for o in sc["objects"]:
            gl.glLoadMatrixf(glmat(np.asarray(sc["camera"]["view"]) @ np.asarray(o["model"])))
            gl.glDisable(gl.GL_COLOR_MATERIAL)
            self.material(o)
            cm = o.get("color_material")
            if cm:
                gl.glColorMaterial(FACE[cm["face"]], CM_GL[cm["mode"]])
                gl.glEnable(gl.GL_COLOR_MATERIAL)
            (gl.glEnable if o["cull"] else gl.glDisable)(gl.GL_CULL_FACE)
            sh = o["shading"] if selftest is None else "gouraud"
            program = {None: "pixel", "fixed": None, "vertex": "vertex"}[selftest]
            if sh in ("flat", "gouraud") and selftest != "vertex":
                gl.glUseProgram(0)
                gl.glShadeModel(gl.GL_FLAT if sh == "flat" else gl.GL_SMOOTH)
            else:
                prog, u = self.programs[program]
                gl.glUseProgram(prog)
                gl.glShadeModel(gl.GL_SMOOTH)
                two_side = bool(lm["two_side"])
                (gl.glEnable if two_side else gl.glDisable)(gl.GL_VERTEX_PROGRAM_TWO_SIDE)
                for name, value in (
                    ("u_nlights", len(sc["lights"])),
                    ("u_local_viewer", int(lm["local_viewer"])),
                    ("u_two_side", int(two_side)),
                    ("u_separate", int(lm["color_control"] == "separate")),
                    ("u_blinn", int(sh != "phong")),
                    ("u_cm_mode", CM_MODE[cm["mode"]] if cm else 0),
                    ("u_cm_front", int(bool(cm) and cm["face"] != "back")),
                    ("u_cm_back", int(bool(cm) and cm["face"] != "front")),
                    ("u_normalize", int(sc["normalize"])),
                ):
                    if u[name] >= 0:
                        gl.glUniform1i(u[name], value)
            self.arrays(o["mesh"], normals=True, colors=bool(cm))
            gl.glUseProgram(0)
            gl.glDisable(gl.GL_VERTEX_PROGRAM_TWO_SIDE)
        gl.glDisable(gl.GL_COLOR_MATERIAL)
        return self.read()

    def ids(self, sc):
        """Object ids through emission only: front R = k, back R = k and G = 255."""
        self.setup(sc)
        gl.glClear(gl.GL_COLOR_BUFFER_BIT | gl.GL_DEPTH_BUFFER_BIT)
        gl.glLoadIdentity()
        for i in range(8):
            gl.glDisable(gl.GL_LIGHT0 + i)
        gl.glEnable(gl.GL_LIGHTING)
        gl.glDisable(gl.GL_COLOR_MATERIAL)
        gl.glLightModelfv(gl.GL_LIGHT_MODEL_AMBIENT, [0.0, 0.0, 0.0, 1.0])
        gl.glLightModeli(gl.GL_LIGHT_MODEL_TWO_SIDE, 1)
        gl.glLightModeli(gl.GL_LIGHT_MODEL_COLOR_CONTROL, gl.GL_SINGLE_COLOR)
        gl.glShadeModel(gl.GL_FLAT)
        gl.glUseProgram(0)
        black = [0.0, 0.0, 0.0, 1.0]
        for k, o in enumerate(sc["objects"], start=1):
            gl.glLoadMatrixf(glmat(np.asarray(sc["camera"]["view"]) @ np.asarray(o["model"])))
            for face, g in ((gl.GL_FRONT, 0.0), (gl.GL_BACK, 1.0)):
                gl.glMaterialfv(face, gl.GL_AMBIENT_AND_DIFFUSE, black)
                gl.glMaterialfv(face, gl.GL_SPECULAR, black)
                gl.glMaterialfv(face, gl.GL_EMISSION, [k / 255.0, g, 0.0, 1.0])
            (gl.glEnable if o["cull"] else gl.glDisable)(gl.GL_CULL_FACE)
            self.arrays(o["mesh"], normals=True, colors=False)
        rgb = self.read()
        return rgb[:, :, 0].astype(np.uint16) + np.where(rgb[:, :, 1] > 127, 256, 0).astype(
            np.uint16)


def versions():
    v = {}
    try:
        v["libosmesa6"] = subprocess.run(
            ["dpkg-query", "-W", "-f=${Version}", "libosmesa6"], capture_output=True,
            text=True).stdout or "?"
    except OSError:
        v["libosmesa6"] = "?"
    import OpenGL
    v["PyOpenGL"] = OpenGL.__version__
    v["numpy"] = np.__version__
    v["python"] = sys.version.split()[0]
    return v


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", default="target/conformance/scenes")
    ap.add_argument("--out", default="target/conformance")
    ap.add_argument("--png", action="store_true", help="also write PNG images")
    ap.add_argument("--selftest", action="store_true",
                    help="check the shaders' lighting function against fixed function: every "
                         "scene drawn GL_SMOOTH both ways; exit 1 if a pixel differs by more "
                         "than 1 LSB")
    ap.add_argument("names", nargs="*")
    a = ap.parse_args()
    out = os.path.join(a.out, "mesa")
    os.makedirs(out, exist_ok=True)
    mesa = Mesa()
    meta = {"gl": mesa.info(), "versions": versions()}
    print(f"Mesa: {meta['gl']['renderer']}, {meta['gl']['version']}, GLSL {meta['gl']['glsl']}",
          file=sys.stderr)
    files = sorted(glob.glob(os.path.join(a.scenes, "*.json")))
    if not files:
        sys.exit(f"no scenes in {a.scenes} (run conformance/scenes.py first)")
    if a.selftest:
        worst = 0
        for f in files:
            with open(f) as fh:
                sc = json.load(fh)
            if a.names and sc["name"] not in a.names:
                continue
            fixed = mesa.render(sc, "fixed").astype(int)
            vertex = mesa.render(sc, "vertex").astype(int)
            cov = mesa.ids(sc) != 0
            d = np.abs(fixed - vertex).max(-1)[cov]
            worst = max(worst, int(d.max()))
            print(f"selftest {sc['name']:26} max {d.max()} mean {d.mean():.4f} "
                  f"> 1 LSB: {(d > 1).sum()}")
        print(f"selftest: the shaders' lighting function against fixed function: max {worst} "
              "LSB", file=sys.stderr)
        sys.exit(0 if worst <= 1 else 1)
    for f in files:
        with open(f) as fh:
            sc = json.load(fh)
        if a.names and sc["name"] not in a.names:
            continue
        rgb = mesa.render(sc)
        ids = mesa.ids(sc)
        np.savez_compressed(os.path.join(out, sc["name"] + ".npz"), rgb=rgb, id=ids,
                            interior=erode_same(ids))
        if a.png:
            from PIL import Image
            Image.fromarray(rgb).save(os.path.join(out, sc["name"] + ".png"))
    with open(os.path.join(out, "meta.json"), "w") as fh:
        json.dump(meta, fh, indent=1)


if __name__ == "__main__":
    main()
