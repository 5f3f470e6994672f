//! The fixshade side of the conformance suite against Mesa (issue 12,
//! `conformance/README.md`): reads the scene files written by
//! `conformance/scenes.py` and renders each scene through fixshade's one
//! pipeline, in the tiers `f32`, `Q30<3>`, `Q14<2>` and the `f64` reference
//! model (`ref`).
//!
//! ```sh
//! cargo run --release -p fixshade-conformance -- [--scenes DIR] [--out DIR] \
//!     [--mesh-as-triangles] [names…]
//! ```
//!
//! Writes `<out>/fixshade/<scene>.<tier>.rgb` (raw RGB8, row 0 at the top),
//! `<out>/fixshade/<scene>.id` (raw little-endian u16 per pixel: object index + 1,
//! plus 256 for a back face, 0 for the background) and
//! `<out>/fixshade/manifest.json` (per scene and tier: `ok`, or `unsupported` with
//! the reasons: a typed error of the library or a feature it lacks).
//!
//! Two ways in, one pipeline behind them:
//!
//! - **Per triangle** (most objects): the harness computes each vertex's clip
//!   coordinates from the scene's GL matrices ([`Clip`] in
//!   [`ClipSpace::SCREEN`] for orthographic cameras, homogeneous in
//!   [`ClipSpace::perspective`] for perspective ones, so the library clips at
//!   the near plane and interpolates perspective-correctly), its eye-space
//!   position and normal, and draws every triangle with
//!   [`draw_triangle`] into a [`FullFrame`] with a depth buffer.
//! - **Mesh** (objects with `"renderer": "mesh"`): the mesh in fixshade's
//!   format (`i16` positions with `frac` fraction bits, Q14 normals), a
//!   [`Camera`]'s [`MeshTransform`] and [`MeshDraw`], as firmware draws.
//!
//! The lighting comes from the GL state in one call (`GlScene::lighting`,
//! lights transformed by the view with `GlLight::transformed`), Blinn-Phong
//! (OpenGL's model) or Phong specular, an infinite or local viewer, two-sided
//! lighting as two passes (front faces with the front lighting, back faces with
//! `GlScene::back_lighting`). Kernels: the library's
//! [`GouraudShading`] for `GL_SMOOTH` and [`PhongShading`] for
//! per-pixel lighting (wrapped in `SeparateSpecular` for
//! `GL_SEPARATE_SPECULAR_COLOR`), and kernels of this harness for what OpenGL
//! does that the library's modes do not: [`Solid`] (the test kit's kernel of
//! one colour, one per triangle: `GL_FLAT`, the colour lit at the provoking
//! vertex, which the library's [`FlatShading`](fixshade::shade::FlatShading)
//! does not pick: it lights the centroid; and the object ids), [`VertexColors`]
//! (`GL_SMOOTH` with colours the harness lights per vertex:
//! `GL_COLOR_MATERIAL`, separate specular, `GL_NORMALIZE` off) and the `f64`
//! reference ([`RefKernel`]).

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use fixshade::camera::{
    Camera, Clip, ClipSpace, MeshTransform, Orthographic, Perspective, Projection, Viewport,
    SUBPIXEL_BITS,
};
use fixshade::color::{Encoder, Linear, Rgb};
use fixshade::framebuffer::{BandView, DrawBand, FullFrame, Layout};
use fixshade::lighting::gl::{
    GlColorMaterial, GlFace, GlLight, GlLightModel, GlMaterial, GlScene, GlViewer,
};
use fixshade::lighting::{
    AnyLight, BlinnPhong, ColorMaterial, Illuminate, InfiniteViewer, LightDesc, LightKind,
    LocalViewer, MaterialDesc, Model, Phong as PhongModel, SeparateSpecular,
};
use fixshade::mesh::Mesh;
use fixshade::num::Mat4;
use fixshade::num::{point_from_f32, Point3, Scalar, Vec3, Q14, Q30};
use fixshade::raster::Cull;
use fixshade::render::{
    bins_len, draw_triangle, CachedVertex, Corner, DrawOptions, MeshDraw, MeshMemory,
};
use fixshade::shade::{GouraudShading, Kernel, PhongShading, Shader, VertexIn};
use fixshade_testkit::reference::{self, ModelDesc, Reference, VertexOptions, ViewerDesc, V3};
use fixshade_testkit::support::Solid;
use serde_json::{json, Value};

// ------------------------------------------------------------------ scene files

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shade {
    Flat,
    Gouraud,
    Phong,
    Blinn,
}

#[derive(Clone, Debug)]
struct GlMat {
    ambient: [f32; 4],
    diffuse: [f32; 4],
    specular: [f32; 4],
    emission: [f32; 4],
    shininess: f32,
}

#[derive(Clone, Debug)]
struct Object {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    colors: Vec<[f32; 4]>,
    color_material: Option<GlColorMaterial>,
    triangles: Vec<[usize; 3]>,
    model: Mat4,
    front: GlMat,
    back: GlMat,
    shading: Shade,
    cull: bool,
    /// Drawn by the mesh renderer: the positions are `i16` values with `frac`
    /// fraction bits, the normals Q14.
    mesh_frac: Option<u8>,
}

/// The camera's parameters (`glOrtho`: left, right, bottom, top, near, far;
/// `gluPerspective`: fovy in degrees, near, far), for the mesh renderer's
/// [`Camera`].
#[derive(Clone, Copy, Debug)]
enum Lens {
    Ortho([f32; 6]),
    Persp { fovy_deg: f32, near: f32, far: f32 },
}

#[derive(Clone, Debug)]
struct Scene {
    name: String,
    width: u32,
    height: u32,
    projection: Mat4,
    view: Mat4,
    near_w: f32,
    perspective: bool,
    lens: Option<Lens>,
    ambient: [f32; 4],
    local_viewer: bool,
    two_side: bool,
    separate_specular: bool,
    normalize: bool,
    lights: Vec<GlLight>,
    objects: Vec<Object>,
}

fn num(v: &Value) -> f32 {
    v.as_f64().expect("a number") as f32
}

fn arr<const N: usize>(v: &Value) -> [f32; N] {
    let a = v.as_array().expect("an array");
    assert_eq!(a.len(), N, "{v}");
    core::array::from_fn(|i| num(&a[i]))
}

fn list<const N: usize>(v: &Value) -> Vec<[f32; N]> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(arr::<N>)
        .collect()
}

fn mat4(v: &Value) -> Mat4 {
    let rows = v.as_array().expect("4 rows");
    Mat4 {
        m: core::array::from_fn(|r| arr::<4>(&rows[r])),
    }
}

fn gl_mat(v: &Value) -> GlMat {
    GlMat {
        ambient: arr(&v["ambient"]),
        diffuse: arr(&v["diffuse"]),
        specular: arr(&v["specular"]),
        emission: arr(&v["emission"]),
        shininess: num(&v["shininess"]),
    }
}

fn gl_material(m: &GlMat) -> GlMaterial {
    GlMaterial {
        ambient: m.ambient,
        diffuse: m.diffuse,
        specular: m.specular,
        emission: m.emission,
        shininess: m.shininess,
    }
}

fn color_material(v: &Value) -> Option<GlColorMaterial> {
    if v.is_null() {
        return None;
    }
    Some(GlColorMaterial {
        face: match v["face"].as_str().unwrap() {
            "front" => GlFace::Front,
            "back" => GlFace::Back,
            _ => GlFace::FrontAndBack,
        },
        mode: match v["mode"].as_str().unwrap() {
            "emission" => ColorMaterial::Emission,
            "ambient" => ColorMaterial::Ambient,
            "diffuse" => ColorMaterial::Diffuse,
            "specular" => ColorMaterial::Specular,
            "ambient_and_diffuse" => ColorMaterial::AmbientAndDiffuse,
            m => panic!("unknown colour material mode {m}"),
        },
    })
}

fn parse(v: &Value) -> Scene {
    let cam = &v["camera"];
    let lm = &v["light_model"];
    let lights = v["lights"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| GlLight {
            ambient: arr(&l["ambient"]),
            diffuse: arr(&l["diffuse"]),
            specular: arr(&l["specular"]),
            position: arr(&l["position"]),
            spot_direction: arr(&l["spot_direction"]),
            spot_exponent: num(&l["spot_exponent"]),
            spot_cutoff: num(&l["spot_cutoff"]),
            constant_attenuation: num(&l["constant_attenuation"]),
            linear_attenuation: num(&l["linear_attenuation"]),
            quadratic_attenuation: num(&l["quadratic_attenuation"]),
        })
        .collect();
    let objects = v["objects"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| {
            let m = &o["mesh"];
            Object {
                positions: list(&m["positions"]),
                normals: list(&m["normals"]),
                colors: m.get("colors").map(list).unwrap_or_default(),
                color_material: color_material(&o["color_material"]),
                triangles: m["triangles"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|t| arr::<3>(t).map(|i| i as usize))
                    .collect(),
                model: mat4(&o["model"]),
                front: gl_mat(&o["front"]),
                back: gl_mat(&o["back"]),
                shading: match o["shading"].as_str().unwrap() {
                    "flat" => Shade::Flat,
                    "gouraud" => Shade::Gouraud,
                    "phong" => Shade::Phong,
                    "blinn" => Shade::Blinn,
                    s => panic!("unknown shading {s}"),
                },
                cull: o["cull"].as_bool().unwrap(),
                mesh_frac: (o.get("renderer").and_then(Value::as_str) == Some("mesh"))
                    .then(|| m["frac"].as_u64().expect("a mesh object's frac") as u8),
            }
        })
        .collect::<Vec<_>>();
    let sc = Scene {
        name: v["name"].as_str().unwrap().to_string(),
        width: v["width"].as_u64().unwrap() as u32,
        height: v["height"].as_u64().unwrap() as u32,
        projection: mat4(&cam["projection"]),
        view: mat4(&cam["view"]),
        near_w: num(&cam["near_w"]),
        perspective: cam["perspective"].as_bool().unwrap(),
        lens: if let Some(o) = cam.get("ortho") {
            Some(Lens::Ortho(arr(o)))
        } else {
            cam.get("fovy").map(|f| Lens::Persp {
                fovy_deg: num(f),
                near: num(&cam["near"]),
                far: num(&cam["far"]),
            })
        },
        ambient: arr(&lm["ambient"]),
        local_viewer: lm["local_viewer"].as_bool().unwrap(),
        two_side: lm["two_side"].as_bool().unwrap(),
        separate_specular: lm["color_control"].as_str() == Some("separate"),
        normalize: v["normalize"].as_bool().unwrap(),
        lights,
        objects,
    };
    for o in &sc.objects {
        assert!(
            o.color_material.is_none() || o.colors.len() == o.positions.len(),
            "colour material without colours"
        );
    }
    sc
}

// ------------------------------------------------------------------ GL state → fixshade

/// What the library cannot express (the object is drawn as well as it can be, or
/// not at all) and typed errors it returns.
#[derive(Default, Debug)]
struct Report {
    unsupported: Vec<String>,
    warnings: Vec<String>,
}

impl Report {
    fn unsupported(&mut self, s: String) {
        if !self.unsupported.contains(&s) {
            self.unsupported.push(s);
        }
    }
}

/// The lights as OpenGL stores them after `glLightfv` with `view` as the modelview.
fn eye_lights(sc: &Scene) -> Vec<GlLight> {
    sc.lights.iter().map(|l| l.transformed(&sc.view)).collect()
}

fn light_model(sc: &Scene) -> GlLightModel {
    GlLightModel {
        ambient: sc.ambient,
        local_viewer: sc.local_viewer,
        two_side: sc.two_side,
        separate_specular: sc.separate_specular,
    }
}

/// The GL state of one object's draw call.
fn gl_scene<'a>(sc: &Scene, o: &Object, lights: &'a [GlLight]) -> GlScene<'a> {
    GlScene {
        lights,
        front: gl_material(&o.front),
        back: gl_material(&o.back),
        model: light_model(sc),
        color_material: o.color_material,
    }
}

/// The passes of an object: (cull, back faces lit as back faces). Two-sided
/// lighting draws front faces with the front lighting and back faces with the
/// back lighting; otherwise one pass lights every face as a front face.
fn passes(sc: &Scene, o: &Object) -> Vec<(Cull, bool)> {
    if o.cull {
        vec![(Cull::Back, false)]
    } else if sc.two_side {
        vec![(Cull::Back, false), (Cull::Front, true)]
    } else {
        vec![(Cull::None, false)]
    }
}

// ------------------------------------------------------------------ geometry

/// A matrix in `f64`.
type M64 = [[f64; 4]; 4];

fn m64(m: &Mat4) -> M64 {
    m.m.map(|r| r.map(f64::from))
}

fn mul64(a: &M64, b: &M64) -> M64 {
    core::array::from_fn(|r| core::array::from_fn(|c| (0..4).map(|k| a[r][k] * b[k][c]).sum()))
}

fn apply64(m: &M64, v: [f64; 4]) -> [f64; 4] {
    core::array::from_fn(|r| (0..4).map(|c| m[r][c] * v[c]).sum())
}

/// A mesh object in fixshade's format and its transform for this frame.
struct MeshObject {
    positions: Vec<[i16; 3]>,
    normals: Vec<[i16; 3]>,
    triangles: Vec<[u16; 3]>,
    frac: u8,
    transform: AnyTransform,
}

/// A [`MeshTransform`] of either projection.
enum AnyTransform {
    Ortho(MeshTransform<Orthographic>),
    Persp(MeshTransform<Perspective>),
}

/// One object's vertices, shared by every tier: clip coordinates (what the
/// rasterizer sees), the eye-space positions and normals OpenGL lights (`f64`),
/// and what the library's kernels get per vertex.
struct Geometry {
    clip: Vec<Clip>,
    space: ClipSpace,
    /// Eye-space positions.
    eye: Vec<V3>,
    /// `M⁻ᵀ·n`, normalised with `GL_NORMALIZE`, else with its length.
    normal: Vec<V3>,
    /// The kernel input: the normal in Q14 (normalised: the library's kernels
    /// normalise it anyway), the eye position in Q16.16.
    input: Vec<VertexIn>,
    mesh: Option<MeshObject>,
}

/// The fixed-point unit of a perspective scene's clip coordinates: `2^k`
/// with every coordinate of every vertex (`x' = 8W·x_c`, `y' = −8H·y_c`,
/// `z_c`, `w_c`) below `2^28` in magnitude.
fn clip_unit(sc: &Scene) -> i32 {
    let (w8, h8) = (8.0 * f64::from(sc.width), 8.0 * f64::from(sc.height));
    let proj = m64(&sc.projection);
    let mut big = 1e-9f64;
    for o in &sc.objects {
        let mvp = mul64(&proj, &mul64(&m64(&sc.view), &m64(&o.model)));
        for p in &o.positions {
            let c = apply64(&mvp, [p[0], p[1], p[2], 1.0].map(f64::from));
            big = big.max((c[0] * w8).abs()).max((c[1] * h8).abs());
            big = big.max(c[2].abs()).max(c[3].abs());
        }
    }
    (f64::from(1u32 << 28) / big)
        .log2()
        .floor()
        .clamp(0.0, 24.0) as i32
}

/// The clip coordinates of `p` under `mvp`: the screen position in sub-pixels
/// and the depth (orthographic), or the homogeneous coordinates in units of
/// `2^−k` (perspective: `x' = 8W·x_c`, `y' = −8H·y_c`, screen = centre +
/// `x'/w`, `y'/w`).
fn clip_of(sc: &Scene, mvp: &M64, p: [f32; 3], k: i32) -> Clip {
    let c = apply64(mvp, [p[0], p[1], p[2], 1.0].map(f64::from));
    let (w8, h8) = (8.0 * f64::from(sc.width), 8.0 * f64::from(sc.height));
    if sc.perspective {
        let s = f64::from(1u32 << k);
        Clip {
            x: (c[0] * w8 * s).round() as i32,
            y: (-c[1] * h8 * s).round() as i32,
            z: (c[2] * s).round() as i32,
            w: (c[3] * s).round() as i32,
        }
    } else {
        // w_c = 1 for glOrtho
        Clip {
            x: (w8 + w8 * c[0]).round() as i32,
            y: (h8 - h8 * c[1]).round() as i32,
            z: ((c[2] + 1.0) * 0.5 * 65535.0).round().clamp(0.0, 65535.0) as i32,
            w: 1,
        }
    }
}

/// The mesh renderer's view of an object: its mesh in fixshade's format (the
/// scene file's values are exact multiples of `2^−frac` and of `2^−14`) and a
/// [`Camera`]'s transform of it.
fn mesh_object(sc: &Scene, o: &Object, frac: u8) -> MeshObject {
    let raw = |v: f32, one: f32| {
        let r = (v * one).round();
        assert!(
            r == v * one && r.abs() <= 32767.0,
            "{}: {v} is not a raw value",
            sc.name
        );
        r as i16
    };
    let lens = sc
        .lens
        .expect("a mesh object needs the camera's parameters");
    let vp = Viewport::new(0, 0, sc.width, sc.height).unwrap();
    let one = (1u32 << frac) as f32;
    let transform = match lens {
        Lens::Ortho([l, r, b, t, n, f]) => AnyTransform::Ortho(
            Camera::orthographic(l, r, b, t, n, f, vp)
                .unwrap()
                .with_view(sc.view)
                .mesh_transform(&o.model, frac)
                .unwrap(),
        ),
        Lens::Persp {
            fovy_deg,
            near,
            far,
        } => AnyTransform::Persp(
            Camera::perspective(
                fovy_deg.to_radians(),
                sc.width as f32 / sc.height as f32,
                near,
                far,
                vp,
            )
            .unwrap()
            .with_view(sc.view)
            .mesh_transform(&o.model, frac)
            .unwrap(),
        ),
    };
    MeshObject {
        positions: o.positions.iter().map(|p| p.map(|v| raw(v, one))).collect(),
        normals: o
            .normals
            .iter()
            .map(|n| n.map(|v| raw(v, 16384.0)))
            .collect(),
        triangles: o
            .triangles
            .iter()
            .map(|t| t.map(|i| u16::try_from(i).unwrap()))
            .collect(),
        frac,
        transform,
    }
}

fn geometry(sc: &Scene, o: &Object, k: i32) -> Geometry {
    let mv = mul64(&m64(&sc.view), &m64(&o.model));
    let mvp = mul64(&m64(&sc.projection), &mv);
    let mv32 = sc.view.mul(&o.model);
    let nm = mv32.normal_matrix();
    // |det M₃|: normal_matrix is |det M₃|·M⁻ᵀ
    let det = {
        let m = mv;
        (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
            .abs()
    };
    let eye: Vec<V3> = o
        .positions
        .iter()
        .map(|p| {
            let e = apply64(&mv, [p[0], p[1], p[2], 1.0].map(f64::from));
            [e[0], e[1], e[2]]
        })
        .collect();
    let normal: Vec<V3> = o
        .normals
        .iter()
        .map(|&n| {
            let n = n.map(f64::from);
            let ne: V3 = core::array::from_fn(|r| (0..3).map(|c| f64::from(nm[r][c]) * n[c]).sum());
            if sc.normalize {
                reference::normalize(ne)
            } else {
                ne.map(|c| c / det)
            }
        })
        .collect();
    let mesh = o.mesh_frac.map(|frac| mesh_object(sc, o, frac));
    let (clip, space, input) = match &mesh {
        // the mesh renderer's own vertex stage: MeshDraw gets exactly these
        Some(m) => {
            let (clip, space) = match &m.transform {
                AnyTransform::Ortho(t) => (
                    m.positions.iter().map(|&p| t.clip(p)).collect(),
                    t.clip_space(),
                ),
                AnyTransform::Persp(t) => (
                    m.positions.iter().map(|&p| t.clip(p)).collect(),
                    t.clip_space(),
                ),
            };
            let input = m
                .positions
                .iter()
                .zip(&m.normals)
                .map(|(&p, &n)| match &m.transform {
                    AnyTransform::Ortho(t) => VertexIn::new(t.normal(n), t.eye(p)),
                    AnyTransform::Persp(t) => VertexIn::new(t.normal(n), t.eye(p)),
                })
                .collect();
            (clip, space, input)
        }
        None => {
            let space = if sc.perspective {
                let (w8, h8) = (8 * sc.width as i32, 8 * sc.height as i32);
                let near = (f64::from(sc.near_w) * f64::from(1u32 << k)).round() as i32;
                ClipSpace::perspective([w8, h8], near)
            } else {
                ClipSpace::SCREEN
            };
            let clip = o
                .positions
                .iter()
                .map(|&p| clip_of(sc, &mvp, p, k))
                .collect();
            let q = |v: f64, one: f64| (v * one).round() as i32;
            let input = eye
                .iter()
                .zip(&normal)
                .map(|(e, n)| {
                    let u = reference::normalize(*n);
                    VertexIn::new(u.map(|c| q(c, 16384.0)), e.map(|c| q(c, 65536.0)))
                })
                .collect();
            (clip, space, input)
        }
    };
    Geometry {
        clip,
        space,
        eye,
        normal,
        input,
        mesh,
    }
}

/// The corners of triangle `t`.
fn corners(g: &Geometry, t: [usize; 3]) -> [Corner; 3] {
    t.map(|i| Corner {
        clip: g.clip[i],
        vertex: g.input[i],
    })
}

// ------------------------------------------------------------------ frames and kernels

/// A frame item that runs a closure on each band (a [`FullFrame`] has one).
struct Pass<F>(F);

impl<F: FnMut(&mut BandView<'_, Rgb888>)> DrawBand<Rgb888> for Pass<F> {
    fn draw_band(&mut self, band: &mut BandView<'_, Rgb888>) {
        (self.0)(band)
    }
}

/// A `w × h` frame with a depth buffer (cleared to black and the far plane)
/// drawn by `draw`.
fn render(w: u32, h: u32, draw: impl FnMut(&mut BandView<'_, Rgb888>)) -> Vec<Rgb888> {
    let mut px = vec![Rgb888::BLACK; (w * h) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    let mut frame = FullFrame::new(w, h, &mut px, Some(&mut depth)).expect("a frame size");
    frame
        .render(Rgb888::BLACK, &mut [&mut Pass(draw)])
        .expect("no item of another layout");
    px
}

/// Every triangle of `o` with `kernel`.
fn draw_tris<K: Kernel<Color = Rgb888, Varyings = [i32; N]>, const N: usize>(
    band: &mut BandView<'_, Rgb888>,
    o: &Object,
    g: &Geometry,
    kernel: &K,
    cull: Cull,
) {
    for t in &o.triangles {
        draw_one(band, g, *t, kernel, cull);
    }
}

/// Triangle `t` of an object with `kernel` (see [`draw_tris`]).
fn draw_one<K: Kernel<Color = Rgb888, Varyings = [i32; N]>, const N: usize>(
    band: &mut BandView<'_, Rgb888>,
    g: &Geometry,
    t: [usize; 3],
    kernel: &K,
    cull: Cull,
) {
    draw_triangle(band, &g.space, kernel, &corners(g, t), cull);
}

/// `--mesh-as-triangles`: draw mesh objects triangle by triangle (with their
/// transform's corners and the same kernels) instead of with [`MeshDraw`]
/// (the same pixels: a check of the one pipeline).
static MESH_AS_TRIANGLES: AtomicBool = AtomicBool::new(false);

/// Homogeneous pixel coordinates `(x·w, y·w, w)` of the corners of triangle
/// `t` (the screen position `x`, `y` in pixels; `w` the clip `w`, 1 under an
/// orthographic projection): from the rounded sub-pixel positions the
/// rasterizer sets up when every corner lies in front of the near plane, else
/// from the clip coordinates (a triangle the near plane cuts).
fn homogeneous(g: &Geometry, t: [usize; 3]) -> [[f64; 3]; 3] {
    let sub = f64::from(1u32 << SUBPIXEL_BITS);
    let clip = t.map(|i| g.clip[i]);
    match clip.map(|c| g.space.project(c)) {
        [Some(a), Some(b), Some(c)] => [(a, clip[0]), (b, clip[1]), (c, clip[2])].map(|(s, c)| {
            let w = f64::from(c.w);
            [f64::from(s.x) / sub * w, f64::from(s.y) / sub * w, w]
        }),
        _ => clip.map(|c| {
            let w = f64::from(c.w);
            let o = g.space.centre().map(f64::from);
            [
                (f64::from(c.x) + o[0] * w) / sub,
                (f64::from(c.y) + o[1] * w) / sub,
                w,
            ]
        }),
    }
}

/// Fraction bits of [`VertexColors`]' channel values (`c·255·2^6`, `c` in
/// [0, 2]: below 2^15).
const COLOR_FRAC: u32 = 6;

/// `GL_SMOOTH` with colours the harness lit per vertex (`GL_COLOR_MATERIAL`,
/// `GL_SEPARATE_SPECULAR_COLOR`, `GL_NORMALIZE` off: what the library's
/// [`GouraudShading`] cannot light, since its vertex stage gets a normal and a
/// position but no colour, and normalises the normal): the corners' colours,
/// each channel in [0, 2] (a clamped sum, or OpenGL's separately clamped
/// primary and secondary colours), interpolated and clamped per pixel. The
/// pipeline's vertex stage carries no colour, so the colours come with the
/// kernel: one kernel per triangle.
#[derive(Clone, Copy, Debug)]
struct VertexColors([[i32; 3]; 3]);

impl VertexColors {
    fn new<S: Scalar>(c: [Rgb<S>; 3]) -> Self {
        // + ½ unit, so that the pixel's shift rounds to nearest
        let half = 1 << (COLOR_FRAC - 1);
        VertexColors(c.map(|c| {
            c.to_f32().map(|v| {
                (f64::from(v.clamp(0.0, 2.0)) * 255.0 * f64::from(1u32 << COLOR_FRAC)).round()
                    as i32
                    + half
            })
        }))
    }
}

impl Kernel for VertexColors {
    type Color = Rgb888;
    type Vertex = ();
    type Varyings = [i32; 3];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;

    fn vertex(&self, _: &VertexIn) {}

    fn triangle(&self, _: [&(); 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 3]; 3]) {
        ((), self.0)
    }

    fn span(&self, _: &(), a: &[i32; 3], d: &[i32; 3], _x: i32, _y: i32, out: &mut [Rgb888]) {
        // channel = min(255, ⌊a / 2^(ATTR_FRAC + COLOR_FRAC)⌋), a with 14 fraction bits
        let sh = fixshade::num::ATTR_FRAC + COLOR_FRAC;
        let ch = |v: i32| (v.max(0) >> sh).min(255) as u8;
        let mut a = *a;
        for c in out.iter_mut() {
            *c = Rgb888::new(ch(a[0]), ch(a[1]), ch(a[2]));
            for (a, d) in a.iter_mut().zip(d) {
                *a = a.wrapping_add(*d);
            }
        }
    }
}

/// The mesh renderer: `kernel` on the mesh of `m` with its transform,
/// prepared for a full frame and drawn into `band` (the frame's one band).
fn draw_mesh<K: Kernel<Color = Rgb888>>(
    band: &mut BandView<'_, Rgb888>,
    sc: &Scene,
    m: &MeshObject,
    kernel: K,
    cull: Cull,
) {
    fn go<K: Kernel<Color = Rgb888>, P: Projection>(
        band: &mut BandView<'_, Rgb888>,
        layout: Layout,
        m: &MeshObject,
        t: &MeshTransform<P>,
        kernel: K,
        cull: Cull,
    ) {
        let mesh = Mesh::new(&m.positions, &m.normals, &m.triangles, m.frac).expect("a mesh");
        let mut cache = vec![CachedVertex::<K::Vertex>::default(); m.positions.len()];
        let mut bins = vec![0u16; bins_len(m.triangles.len(), 1)];
        let memory = MeshMemory {
            vertices: &mut cache,
            bins: &mut bins,
            carry: &mut [],
        };
        let mut draw = MeshDraw::new(
            layout,
            mesh,
            t,
            kernel,
            memory,
            DrawOptions {
                cull,
                ..DrawOptions::default()
            },
        )
        .expect("buffers for a full frame");
        draw.draw_band(band);
    }
    let layout = Layout::full(sc.width, sc.height).expect("a frame size");
    match &m.transform {
        AnyTransform::Ortho(t) => go(band, layout, m, t, kernel, cull),
        AnyTransform::Persp(t) => go(band, layout, m, t, kernel, cull),
    }
}

// ------------------------------------------------------------------ object ids

/// Which object (and face) covers each pixel, with the colour pass's clipping,
/// rasterizer and depth test: front faces drawn with `Cull::Back`, then, for
/// objects drawn without culling, back faces with `Cull::Front`. Mesh objects
/// are drawn triangle by triangle with their transform's corners, which covers
/// the pixels [`MeshDraw`] covers.
fn ids(sc: &Scene, geos: &[Geometry]) -> Vec<u16> {
    let px = render(sc.width, sc.height, |band| {
        for (k, (o, g)) in sc.objects.iter().zip(geos).enumerate() {
            let k = (k + 1) as u8;
            for (cull, green) in [(Cull::Back, 0u8), (Cull::Front, 255)] {
                if o.cull && cull == Cull::Front {
                    continue;
                }
                draw_tris(band, o, g, &Solid(Rgb888::new(k, green, 0)), cull);
            }
        }
    });
    px.iter()
        .map(|c| u16::from(c.r()) + if c.g() > 127 { 256 } else { 0 })
        .collect()
}

// ------------------------------------------------------------------ the tiers

/// An object's vertices in tier `S`, for the lighting the harness evaluates
/// per vertex: eye-space positions, the normals OpenGL lights, and with colour
/// material the vertex colours.
struct TierVertices<S: Scalar> {
    position: Vec<Point3<S>>,
    normal: Vec<Vec3<S>>,
    color: Vec<Option<Rgb<S>>>,
}

impl<S: Scalar> TierVertices<S> {
    fn new(o: &Object, g: &Geometry) -> Self {
        let f = |v: &V3| v.map(|c| c as f32);
        TierVertices {
            position: g.eye.iter().map(|e| point_from_f32::<S>(f(e))).collect(),
            normal: g.normal.iter().map(|n| Vec3::from_f32(f(n))).collect(),
            color: (0..o.positions.len())
                .map(|i| {
                    o.color_material
                        .map(|_| Rgb::from_f32([o.colors[i][0], o.colors[i][1], o.colors[i][2]]))
                })
                .collect(),
        }
    }
}

/// The colour OpenGL's per-vertex lighting gives vertex `k`: the primary and
/// secondary colours clamped and summed once (`GL_SINGLE_COLOR`) or apart
/// (`GL_SEPARATE_SPECULAR_COLOR`, in [0, 2]: interpolated, clamped per pixel).
fn vertex_color<S: Scalar, I: Illuminate<Scalar = S>>(
    lit: &I,
    v: &TierVertices<S>,
    k: usize,
    separate: bool,
) -> Rgb<S> {
    let parts = lit.shade_parts(&v.position[k], v.normal[k], v.color[k]);
    if separate {
        parts.separate()
    } else {
        parts.sum().clamp01()
    }
}

/// Draws object `o` (one pass: `cull`) with lighting `lit` in its shading mode.
#[allow(clippy::too_many_arguments)]
fn draw_with<S: Scalar, I: Illuminate<Scalar = S> + Clone>(
    lit: &I,
    sc: &Scene,
    o: &Object,
    g: &Geometry,
    v: &TierVertices<S>,
    cull: Cull,
    rep: &mut Report,
    band: &mut BandView<'_, Rgb888>,
) {
    let separate = sc.separate_specular;
    let colored = o.color_material.is_some();
    if let Some(m) = g
        .mesh
        .as_ref()
        .filter(|_| !MESH_AS_TRIANGLES.load(Ordering::Relaxed))
    {
        // the mesh renderer: the library's modes as they are
        if colored || separate || !sc.normalize || o.shading == Shade::Flat {
            rep.unsupported(
                "mesh renderer: GL_FLAT, GL_COLOR_MATERIAL, separate specular and \
                 GL_NORMALIZE off are drawn triangle by triangle only (not drawn)"
                    .into(),
            );
            return;
        }
        // `PhongShading` would pick the general kernel for these lightings too
        // (several lights of any kind); it cannot be named here, in code generic
        // over the lighting: its `ModeState` bound needs the lighting's hidden
        // `Fast` flag to implement the unexported `shade::phong::PhongPath`.
        match o.shading {
            Shade::Gouraud => {
                draw_mesh(band, sc, m, Shader::new(GouraudShading, lit, Linear), cull)
            }
            _ => draw_mesh(band, sc, m, Shader::new(PhongShading, lit, Linear), cull),
        }
        return;
    }
    match o.shading {
        // GL_FLAT: the colour lit at the provoking (last) vertex
        Shade::Flat => {
            for t in &o.triangles {
                let c = vertex_color(lit, v, t[2], separate);
                let k = Solid(Encoder::<Rgb888>::encode(&Linear, c, 0, 0));
                draw_one(band, g, *t, &k, cull);
            }
        }
        Shade::Gouraud if colored || separate || !sc.normalize => {
            for t in &o.triangles {
                let k = VertexColors::new(t.map(|i| vertex_color(lit, v, i, separate)));
                draw_one(band, g, *t, &k, cull);
            }
        }
        Shade::Gouraud => draw_tris(band, o, g, &Shader::new(GouraudShading, lit, Linear), cull),
        Shade::Phong | Shade::Blinn => {
            if colored {
                rep.unsupported(
                    "GL_COLOR_MATERIAL with per-pixel shading: PhongShading interpolates no \
                     vertex colours (drawn without them)"
                        .into(),
                );
            }
            if separate {
                let sep = SeparateSpecular(lit.clone());
                let k = Shader::new(PhongShading, &sep, Linear);
                draw_tris(band, o, g, &k, cull)
            } else {
                draw_tris(band, o, g, &Shader::new(PhongShading, lit, Linear), cull)
            }
        }
    }
}

/// Renders a scene in tier `S`.
fn render_tier<S: Scalar>(sc: &Scene, geos: &[Geometry], rep: &mut Report) -> Vec<Rgb888> {
    let lights = eye_lights(sc);
    render(sc.width, sc.height, |band| {
        for (o, g) in sc.objects.iter().zip(geos) {
            let scene = gl_scene(sc, o, &lights);
            macro_rules! go {
                ($m:ty, $v:ty) => {
                    draw_object::<S, $m, $v>(sc, o, g, &scene, rep, band)
                };
            }
            match (o.shading == Shade::Phong, sc.local_viewer) {
                (false, false) => go!(BlinnPhong, InfiniteViewer<S>),
                (false, true) => go!(BlinnPhong, LocalViewer<S>),
                (true, false) => go!(PhongModel, InfiniteViewer<S>),
                (true, true) => go!(PhongModel, LocalViewer<S>),
            }
        }
    })
}

/// Up to 8 lights of any kind.
type GlLights<S> = fixshade::heapless::Vec<AnyLight<S>, 8>;

/// Draws one object in tier `S` with reflection model `M` and viewer `V`.
fn draw_object<S: Scalar, M: Model, V: GlViewer<S> + Clone>(
    sc: &Scene,
    o: &Object,
    g: &Geometry,
    scene: &GlScene<'_>,
    rep: &mut Report,
    band: &mut BandView<'_, Rgb888>,
) {
    let v = TierVertices::<S>::new(o, g);
    for (cull, back) in passes(sc, o) {
        if back {
            match scene.back_lighting::<S, GlLights<S>, M, V>() {
                Ok(lit) => draw_with(&lit, sc, o, g, &v, cull, rep, band),
                Err(e) => rep.unsupported(format!("GlScene::back_lighting: {e}")),
            }
        } else {
            match scene.lighting::<S, GlLights<S>, M, V>() {
                Ok(lit) => draw_with(&lit, sc, o, g, &v, cull, rep, band),
                Err(e) => rep.unsupported(format!("GlScene::lighting: {e}")),
            }
        }
    }
}

// ------------------------------------------------------------------ the f64 reference

/// One triangle for the `f64` reference model.
struct RefTriangle {
    /// Homogeneous pixel coordinates `(x·w, y·w, w)` of the corners (the
    /// screen position `x`, `y` in pixels; `w` the clip `w`, 1 under an
    /// orthographic projection): from the rounded sub-pixel positions the
    /// rasterizer uses when every corner lies in front of the near plane,
    /// else from the clip coordinates.
    h: [[f64; 3]; 3],
    pos: [V3; 3],
    nrm: [V3; 3],
    /// The colour lit at each corner (clamped as OpenGL clamps it).
    vcol: [V3; 3],
    /// Flat and Gouraud: whether the triangle's colour was lit near a discontinuity.
    near: bool,
}

/// The `f64` reference model on the same coverage: per-pixel barycentric
/// coordinates at the pixel centre (perspective-correct for perspective scenes),
/// eye-space positions and normals in `f64`. `GL_FLAT` takes the colour lit at the
/// last vertex, Gouraud interpolates the clamped vertex colours (primary and
/// secondary clamped apart with separate specular), per-pixel shading interpolates
/// position and normal (renormalised, as the GLSL shader does). One kernel per
/// triangle; the pixels it shades also record whether they lie near a
/// discontinuity ([`Disc`]).
struct RefKernel<'a> {
    r: &'a Reference<'a>,
    disc: Disc<'a>,
    disc_out: &'a RefCell<Vec<u8>>,
    width: u32,
    shading: Shade,
    /// Back faces of two-sided lighting: the normal negated.
    back: bool,
    separate: bool,
    t: RefTriangle,
}

fn lerp3(l: [f64; 3], a: &[V3; 3]) -> V3 {
    core::array::from_fn(|c| l[0] * a[0][c] + l[1] * a[1][c] + l[2] * a[2][c])
}

/// OpenGL's colour of primary and secondary parts: summed and clamped, or clamped
/// apart and summed (`GL_SEPARATE_SPECULAR_COLOR`).
fn combine((p, s): (V3, V3), separate: bool) -> V3 {
    let c = |v: f64| v.clamp(0.0, 1.0);
    core::array::from_fn(|i| {
        if separate {
            c(p[i]) + c(s[i])
        } else {
            c(p[i] + s[i])
        }
    })
}

/// The perspective-correct barycentric coordinates of the point `(x, y)`
/// (pixels) in the triangle of homogeneous corners `h`: `λ` with
/// `Σ λᵢ·(hᵢ.x − x·hᵢ.w) = 0`, `Σ λᵢ·(hᵢ.y − y·hᵢ.w) = 0`, `Σ λᵢ = 1` (for
/// corners in front of the eye, the screen weights `βᵢ/wᵢ` renormalised).
fn barycentric(h: &[[f64; 3]; 3], x: f64, y: f64) -> [f64; 3] {
    let a = h.map(|c| c[0] - x * c[2]);
    let b = h.map(|c| c[1] - y * c[2]);
    let l = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let s = l[0] + l[1] + l[2];
    if s != 0.0 {
        l.map(|v| v / s)
    } else {
        [1.0 / 3.0; 3]
    }
}

impl Kernel for RefKernel<'_> {
    type Color = Rgb888;
    type Vertex = ();
    type Varyings = [i32; 0];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;

    fn vertex(&self, _: &VertexIn) {}

    fn triangle(&self, _: [&(); 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 0]; 3]) {
        ((), [[]; 3])
    }

    fn span(&self, _: &(), _: &[i32; 0], _: &[i32; 0], x: i32, y: i32, out: &mut [Rgb888]) {
        let t = &self.t;
        let mut disc = self.disc_out.borrow_mut();
        for (k, px) in out.iter_mut().enumerate() {
            let (cx, cy) = (f64::from(x + k as i32) + 0.5, f64::from(y) + 0.5);
            let l = barycentric(&t.h, cx, cy);
            let (c, near) = match self.shading {
                Shade::Flat => (t.vcol[2], t.near),
                Shade::Gouraud => (lerp3(l, &t.vcol), t.near),
                Shade::Phong | Shade::Blinn => {
                    let (p, n) = (lerp3(l, &t.pos), lerp3(l, &t.nrm));
                    let n = reference::normalize(n);
                    let n = if self.back { n.map(|c| -c) } else { n };
                    let parts = self.r.shade_parts(p, n, &VertexOptions::default());
                    (combine(parts, self.separate), self.disc.near(p, n))
                }
            };
            *px = Rgb888::new(
                reference::to_u8(c[0]),
                reference::to_u8(c[1]),
                reference::to_u8(c[2]),
            );
            disc[(y as u32 * self.width + (x as u32 + k as u32)) as usize] = u8::from(near);
        }
    }
}

/// Where the lighting equation jumps: the edge of a spot cone (`cos φ = cos
/// cutoff`) and, where a highlight would be visible, the specular switch at
/// `N·L = 0`. A point within 10⁻³ of either is "near a discontinuity": any rounding
/// may flip a whole term there, and the crate's documented bounds exclude such
/// samples (README, "Samples within 10⁻³ of a discontinuity …").
#[derive(Clone, Copy)]
struct Disc<'a> {
    lights: &'a [LightDesc],
    material: &'a MaterialDesc,
    local_viewer: bool,
    blinn: bool,
}

impl Disc<'_> {
    fn near(&self, p: V3, n: V3) -> bool {
        const EPS: f64 = 1e-3;
        let n = reference::normalize(n);
        let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let v = if self.local_viewer {
            reference::normalize(p.map(|c| -c))
        } else {
            [0.0, 0.0, 1.0]
        };
        self.lights.iter().any(|ld| {
            let to = |q: [f32; 3]| {
                reference::normalize(core::array::from_fn(|c| f64::from(q[c]) - p[c]))
            };
            let l = match ld.kind {
                LightKind::Directional { towards_light } => {
                    reference::normalize(towards_light.map(f64::from))
                }
                LightKind::Point { position, .. } => to(position),
                LightKind::Spot {
                    position,
                    axis,
                    cutoff_deg,
                    ..
                } => {
                    let l = to(position);
                    let cos_phi = -dot(reference::normalize(axis.map(f64::from)), l);
                    if (cos_phi - f64::from(cutoff_deg).to_radians().cos()).abs() < EPS {
                        return true;
                    }
                    l
                }
            };
            let nl = dot(n, l);
            if nl.abs() >= EPS {
                return false;
            }
            let x = if self.blinn {
                dot(
                    n,
                    reference::normalize(core::array::from_fn(|c| l[c] + v[c])),
                )
            } else {
                dot(core::array::from_fn(|c| 2.0 * nl * n[c] - l[c]), v)
            };
            let ks = (0..3)
                .map(|c| (f64::from(ld.specular[c]) * f64::from(self.material.specular[c])).abs())
                .fold(0.0, f64::max);
            x > 0.0 && ks * x.powf(f64::from(self.material.shininess)) > 0.5 / 255.0
        })
    }
}

/// The reference image and the pixels lit near a discontinuity (see [`Disc`]).
fn render_reference(sc: &Scene, geos: &[Geometry]) -> (Vec<Rgb888>, Vec<u8>) {
    let (w, h) = (sc.width, sc.height);
    let disc_img = RefCell::new(vec![0u8; (w * h) as usize]);
    // the reference takes any f32 colour (no validation)
    let lights = eye_lights(sc);
    let descs: Vec<LightDesc> = lights.iter().map(|l| l.to_desc().unwrap()).collect();
    let px = render(w, h, |band| {
        for (o, g) in sc.objects.iter().zip(geos) {
            let scene = gl_scene(sc, o, &lights);
            for (cull, back) in passes(sc, o) {
                let m = if back { &o.back } else { &o.front };
                let material = gl_material(m).to_desc().unwrap();
                let face = if back { GlFace::Back } else { GlFace::Front };
                let cm = scene.color_material_on(face);
                let r = Reference {
                    lights: &descs,
                    material,
                    global_ambient: [sc.ambient[0], sc.ambient[1], sc.ambient[2]],
                    viewer: if sc.local_viewer {
                        ViewerDesc::Local([0.0; 3])
                    } else {
                        ViewerDesc::Infinite([0.0, 0.0, 1.0])
                    },
                    fog: None,
                    model: if o.shading == Shade::Phong {
                        ModelDesc::of::<PhongModel>()
                    } else {
                        ModelDesc::of::<BlinnPhong>()
                    },
                };
                let disc = Disc {
                    lights: &descs,
                    material: &r.material,
                    local_viewer: sc.local_viewer,
                    blinn: o.shading != Shade::Phong,
                };
                for &idx in &o.triangles {
                    let pos = idx.map(|i| g.eye[i]);
                    let nrm = idx.map(|i| g.normal[i]);
                    // the normal lit at a vertex (negated for back faces)
                    let lit_n = |k: usize| {
                        if back {
                            nrm[k].map(|c| -c)
                        } else {
                            nrm[k]
                        }
                    };
                    let vopts = |k: usize| VertexOptions {
                        normalize: sc.normalize,
                        color_material: if o.color_material.is_some() {
                            cm
                        } else {
                            ColorMaterial::Off
                        },
                        color: o
                            .colors
                            .get(idx[k])
                            .map_or([1.0; 3], |c| [c[0], c[1], c[2]]),
                    };
                    let vcol = [0, 1, 2].map(|k| {
                        combine(
                            r.shade_parts(pos[k], lit_n(k), &vopts(k)),
                            sc.separate_specular,
                        )
                    });
                    let near = match o.shading {
                        Shade::Flat => disc.near(pos[2], lit_n(2)),
                        _ => (0..3).any(|k| disc.near(pos[k], lit_n(k))),
                    };
                    let h = homogeneous(g, idx);
                    let kernel = RefKernel {
                        r: &r,
                        disc,
                        disc_out: &disc_img,
                        width: w,
                        shading: o.shading,
                        back,
                        separate: sc.separate_specular,
                        t: RefTriangle {
                            h,
                            pos,
                            nrm,
                            vcol,
                            near,
                        },
                    };
                    draw_triangle(band, &g.space, &kernel, &corners(g, idx), cull);
                }
            }
        }
    });
    (px, disc_img.into_inner())
}

// ------------------------------------------------------------------ main

fn write_rgb(path: &Path, px: &[Rgb888]) {
    let bytes: Vec<u8> = px.iter().flat_map(|c| [c.r(), c.g(), c.b()]).collect();
    std::fs::write(path, bytes).unwrap();
}

fn main() {
    let mut scenes_dir = PathBuf::from("target/conformance/scenes");
    let mut out = PathBuf::from("target/conformance");
    let mut names = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--scenes" => scenes_dir = args.next().expect("--scenes DIR").into(),
            "--out" => out = args.next().expect("--out DIR").into(),
            "--mesh-as-triangles" => MESH_AS_TRIANGLES.store(true, Ordering::Relaxed),
            _ => names.push(a),
        }
    }
    let dir = out.join("fixshade");
    std::fs::create_dir_all(&dir).unwrap();
    let mut files: Vec<PathBuf> = std::fs::read_dir(&scenes_dir)
        .unwrap_or_else(|e| {
            panic!(
                "{}: {e} (run conformance/scenes.py first)",
                scenes_dir.display()
            )
        })
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    let mut manifest = BTreeMap::new();
    let t0 = Instant::now();
    for f in files {
        let v: Value = serde_json::from_str(&std::fs::read_to_string(&f).unwrap()).unwrap();
        let sc = parse(&v);
        if !names.is_empty() && !names.contains(&sc.name) {
            continue;
        }
        let k = if sc.perspective { clip_unit(&sc) } else { 0 };
        let geos: Vec<Geometry> = sc.objects.iter().map(|o| geometry(&sc, o, k)).collect();
        let id = ids(&sc, &geos);
        let bytes: Vec<u8> = id.iter().flat_map(|v| v.to_le_bytes()).collect();
        std::fs::write(dir.join(format!("{}.id", sc.name)), bytes).unwrap();
        let mut tiers = BTreeMap::new();
        for tier in ["f32", "q30", "q14", "ref"] {
            let mut rep = Report::default();
            let t = Instant::now();
            let px = match tier {
                "f32" => render_tier::<f32>(&sc, &geos, &mut rep),
                "q30" => render_tier::<Q30<3>>(&sc, &geos, &mut rep),
                "q14" => render_tier::<Q14<2>>(&sc, &geos, &mut rep),
                _ => {
                    let (px, disc) = render_reference(&sc, &geos);
                    std::fs::write(dir.join(format!("{}.disc", sc.name)), disc).unwrap();
                    px
                }
            };
            let ms = t.elapsed().as_secs_f64() * 1e3;
            write_rgb(&dir.join(format!("{}.{tier}.rgb", sc.name)), &px);
            tiers.insert(
                tier,
                json!({
                    "status": if rep.unsupported.is_empty() { "ok" } else { "unsupported" },
                    "unsupported": rep.unsupported,
                    "warnings": rep.warnings,
                    "ms": (ms * 10.0).round() / 10.0,
                }),
            );
        }
        manifest.insert(
            sc.name.clone(),
            json!({"width": sc.width, "height": sc.height, "tiers": tiers}),
        );
    }
    std::fs::write(
        dir.join("manifest.json"),
        serde_json::to_string_pretty(&manifest).unwrap(),
    )
    .unwrap();
    eprintln!(
        "fixshade: {} scenes × 4 tiers in {:.2} s -> {}",
        manifest.len(),
        t0.elapsed().as_secs_f64(),
        dir.display()
    );
}
