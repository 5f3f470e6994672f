//! The fixshade side of the conformance suite against Mesa (issue 12,
//! `conformance/README.md`): reads the scene files written by
//! `conformance/scenes.py` and renders each scene through fixshade's public
//! per-triangle API, in the tiers `f32`, `Q30<3>`, `Q14<2>` and the `f64`
//! reference model (`ref`).
//!
//! ```sh
//! cargo run --release --example conformance -- [--scenes DIR] [--out DIR] [names…]
//! ```
//!
//! Writes `<out>/fixshade/<scene>.<tier>.rgb` (raw RGB8, row 0 at the top),
//! `<out>/fixshade/<scene>.id` (raw little-endian u16 per pixel: object index + 1,
//! plus 256 for a back face, 0 for the background) and
//! `<out>/fixshade/manifest.json` (per scene and tier: `ok`, or `unsupported` with
//! the reasons: a typed error of the library or a feature it lacks).
//!
//! The path per object is what firmware does: `ScreenTransform` (projection ·
//! view · model, fixed point, 4 sub-pixel bits) for screen positions,
//! `EyeTransform` (view · model) for eye-space positions and normals
//! (`gl::eye_normal` with `GL_NORMALIZE` off), the lighting from the GL state in
//! one call (`gl::GlScene::lighting`, lights transformed by the view with
//! `GlLight::transformed`), Blinn-Phong (OpenGL's model) or Phong specular, an
//! infinite or local viewer, two-sided lighting as two passes (front faces with
//! the front lighting, back faces with `GlScene::back_lighting`), and
//! `GL_FLAT` (`Shader::draw_provoking`/`draw_color`), `GL_SMOOTH`
//! (`Shading::draw`, or `Shader::draw_vertex_colors` for colour material and
//! separate specular) and per-pixel (`PhongShading`, `SeparateSpecular`) shading
//! into an Rgb888 `SliceFramebuffer` with a `DepthBuffer`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use fixshade::color::Rgb;
use fixshade::gl::{
    eye_normal, ColorMaterialMode, GlColorMaterial, GlFace, GlLight, GlLightModel, GlMaterial,
    GlNormals, GlScene,
};
use fixshade::light::{AnyLight, LightDesc};
use fixshade::lighting::{
    BlinnPhong, ColorMaterial, Illuminate, InfiniteViewer, LocalViewer, Model, Phong as PhongModel,
    SeparateSpecular,
};
use fixshade::material::MaterialDesc;
use fixshade::mesh::{EyeTransform, Mat4, ScreenTransform, ScreenVertex, Viewport};
use fixshade::num::{Scalar, Q14, Q30};
use fixshade::raster::{
    draw_triangle, draw_triangle_perspective, Cull, RasterOptions, SpanShader, SUBPIXEL_BITS,
};
use fixshade::reference::{self, ModelDesc, Reference, VertexOptions, ViewerDesc, V3};
use fixshade::shade::{
    FlatShading, GouraudShading, Linear, PhongShading, ShadeVertex, Shader, Shading,
};
use fixshade::target::{DepthBuffer, SliceFramebuffer};
use fixshade::vector::Vec3;
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
            "emission" => ColorMaterialMode::Emission,
            "ambient" => ColorMaterialMode::Ambient,
            "diffuse" => ColorMaterialMode::Diffuse,
            "specular" => ColorMaterialMode::Specular,
            "ambient_and_diffuse" => ColorMaterialMode::AmbientAndDiffuse,
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

/// One object's vertices: screen positions (shared by every tier) and the
/// modelview.
struct Geometry {
    screen: Vec<Option<ScreenVertex>>,
    mv: Mat4,
    mvp: Mat4,
}

fn geometry(sc: &Scene, o: &Object) -> Geometry {
    let mv = sc.view.mul(&o.model);
    let mvp = sc.projection.mul(&mv);
    let vp = Viewport::new(0, 0, sc.width as i32, sc.height as i32).unwrap();
    let st = ScreenTransform::new(&mvp, vp, sc.near_w).unwrap();
    Geometry {
        screen: o.positions.iter().map(|&p| st.project_f32(p)).collect(),
        mv,
        mvp,
    }
}

/// One triangle through the rasterizer, perspective-correct in perspective scenes.
fn raster<S: SpanShader<N, Color = Rgb888>, const N: usize>(
    persp: bool,
    fb: &mut SliceFramebuffer<'_, Rgb888>,
    db: &mut DepthBuffer<'_>,
    v: &[fixshade::raster::RasterVertex<N>; 3],
    op: &RasterOptions,
    s: &mut S,
) {
    let r = if persp {
        draw_triangle_perspective(fb, Some(db), v, op, s)
    } else {
        draw_triangle(fb, Some(db), v, op, s)
    };
    // memory framebuffers cannot fail
    let Ok(_) = r;
}

/// The screen triangles of an object (triangles with a vertex behind the near
/// plane are skipped: the scenes keep everything in front of it).
fn screen_tris(o: &Object, g: &Geometry) -> Vec<([ScreenVertex; 3], [usize; 3])> {
    o.triangles
        .iter()
        .filter_map(|t| match t.map(|i| g.screen[i]) {
            [Some(a), Some(b), Some(c)] => Some(([a, b, c], *t)),
            _ => None,
        })
        .collect()
}

// ------------------------------------------------------------------ object ids

/// Fills runs with one colour (the id pass).
struct Fill(Rgb888);

impl SpanShader<0> for Fill {
    type Color = Rgb888;
    fn shade_span(&mut self, _x: i32, _y: i32, _s: &[i32; 0], _d: &[i32; 0], out: &mut [Rgb888]) {
        out.fill(self.0);
    }
}

/// Which object (and face) covers each pixel, with the colour pass's rasterizer
/// and depth test: front faces drawn with `Cull::Back`, then, for objects drawn
/// without culling, back faces with `Cull::Front`.
fn ids(sc: &Scene, geos: &[Geometry]) -> Vec<u16> {
    let (w, h) = (sc.width, sc.height);
    let mut px = vec![Rgb888::BLACK; (w * h) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    {
        let mut fb = SliceFramebuffer::new(&mut px, w, h).unwrap();
        let mut db = DepthBuffer::new(&mut depth, w).unwrap();
        for (k, (o, g)) in sc.objects.iter().zip(geos).enumerate() {
            let k = (k + 1) as u8;
            let tris = screen_tris(o, g);
            for (cull, green) in [(Cull::Back, 0u8), (Cull::Front, 255)] {
                if o.cull && cull == Cull::Front {
                    continue;
                }
                let mut s = Fill(Rgb888::new(k, green, 0));
                let op = RasterOptions {
                    cull,
                    ..RasterOptions::default()
                };
                for (t, _) in &tris {
                    raster(
                        sc.perspective,
                        &mut fb,
                        &mut db,
                        &t.map(|v| v.to_raster([])),
                        &op,
                        &mut s,
                    );
                }
            }
        }
    }
    px.iter()
        .map(|c| u16::from(c.r()) + if c.g() > 127 { 256 } else { 0 })
        .collect()
}

// ------------------------------------------------------------------ the tiers

/// One triangle to shade: its vertices and, with colour material, their colours.
type Tri<S> = ([ShadeVertex<S>; 3], Option<[Rgb<S>; 3]>);

/// The colour OpenGL's per-vertex lighting gives `v`: the primary and secondary
/// colours clamped and summed once (`GL_SINGLE_COLOR`) or apart
/// (`GL_SEPARATE_SPECULAR_COLOR`, in [0, 2]: interpolated, clamped per pixel).
fn vertex_color<S: Scalar, I: Illuminate<Scalar = S>>(
    lit: &I,
    v: &ShadeVertex<S>,
    color: Option<Rgb<S>>,
    separate: bool,
) -> Rgb<S> {
    let parts = lit.shade_parts(&v.position, v.normal, color);
    if separate {
        parts.separate()
    } else {
        parts.sum().clamp01()
    }
}

/// Draws `tris` with lighting `lit` in the object's shading mode.
#[allow(clippy::too_many_arguments)]
fn draw_with<S: Scalar, I: Illuminate<Scalar = S> + Clone>(
    lit: &I,
    shading: Shade,
    tris: &[Tri<S>],
    separate: bool,
    fb: &mut SliceFramebuffer<'_, Rgb888>,
    db: &mut DepthBuffer<'_>,
    op: &RasterOptions,
    persp: bool,
    rep: &mut Report,
) {
    fn each<S: Scalar, D: Shading<S, Color = Rgb888>>(
        mut s: D,
        tris: &[Tri<S>],
        fb: &mut SliceFramebuffer<'_, Rgb888>,
        db: &mut DepthBuffer<'_>,
        op: &RasterOptions,
        persp: bool,
    ) {
        for (t, _) in tris {
            let r = if persp {
                s.draw_perspective(fb, Some(db), t, op)
            } else {
                s.draw(fb, Some(db), t, op)
            };
            let Ok(_) = r;
        }
    }
    let colored = tris.iter().any(|t| t.1.is_some());
    match shading {
        // GL_FLAT: the colour lit at the provoking (last) vertex
        Shade::Flat => {
            let mut s = Shader::new(FlatShading, lit, Linear);
            for (t, c) in tris {
                let col = vertex_color(lit, &t[2], c.map(|c| c[2]), separate);
                let Ok(_) = s.draw_color(fb, Some(db), t, col, op, persp);
            }
        }
        Shade::Gouraud if colored || separate => {
            let mut s = Shader::new(GouraudShading, lit, Linear);
            for (t, c) in tris {
                let cols = [0, 1, 2].map(|k| vertex_color(lit, &t[k], c.map(|c| c[k]), separate));
                let Ok(_) = s.draw_vertex_colors(fb, Some(db), t, &cols, op, persp);
            }
        }
        Shade::Gouraud => each(
            Shader::new(GouraudShading, lit, Linear),
            tris,
            fb,
            db,
            op,
            persp,
        ),
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
                each(
                    Shader::new(PhongShading, &sep, Linear),
                    tris,
                    fb,
                    db,
                    op,
                    persp,
                )
            } else {
                each(
                    Shader::new(PhongShading, lit, Linear),
                    tris,
                    fb,
                    db,
                    op,
                    persp,
                )
            }
        }
    }
}

/// Renders a scene in tier `S`.
fn render_tier<S: Scalar>(sc: &Scene, geos: &[Geometry], rep: &mut Report) -> Vec<Rgb888> {
    let (w, h) = (sc.width, sc.height);
    let mut px = vec![Rgb888::BLACK; (w * h) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut px, w, h).unwrap();
    let mut db = DepthBuffer::new(&mut depth, w).unwrap();
    let lights = eye_lights(sc);
    for (o, g) in sc.objects.iter().zip(geos) {
        let scene = gl_scene(sc, o, &lights);
        macro_rules! go {
            ($m:ty, $v:ty) => {
                draw_object::<S, $m, $v>(sc, o, g, &scene, rep, &mut fb, &mut db)
            };
        }
        match (o.shading == Shade::Phong, sc.local_viewer) {
            (false, false) => go!(BlinnPhong, InfiniteViewer<S>),
            (false, true) => go!(BlinnPhong, LocalViewer<S>),
            (true, false) => go!(PhongModel, InfiniteViewer<S>),
            (true, true) => go!(PhongModel, LocalViewer<S>),
        }
    }
    px
}

/// Up to 8 lights of any kind.
type GlLights<S> = heapless::Vec<AnyLight<S>, 8>;

/// Draws one object in tier `S` with reflection model `M` and viewer `V`.
fn draw_object<S: Scalar, M: Model, V: fixshade::gl::GlViewer<S> + Clone>(
    sc: &Scene,
    o: &Object,
    g: &Geometry,
    scene: &GlScene<'_>,
    rep: &mut Report,
    fb: &mut SliceFramebuffer<'_, Rgb888>,
    db: &mut DepthBuffer<'_>,
) {
    let et = EyeTransform::new(&g.mv).unwrap();
    let normal = |i: usize| {
        if sc.normalize {
            et.normal::<S>(Vec3::from_f32(o.normals[i]))
        } else {
            // GL_NORMALIZE off: M⁻ᵀ·n with its length
            Vec3::from_f32(eye_normal(&g.mv, o.normals[i], GlNormals::AsGiven))
        }
    };
    let color = |i: usize| {
        o.color_material
            .map(|_| Rgb::from_f32([o.colors[i][0], o.colors[i][1], o.colors[i][2]]))
    };
    let tris: Vec<Tri<S>> = screen_tris(o, g)
        .iter()
        .map(|(s, idx)| {
            let v = core::array::from_fn(|k| ShadeVertex {
                screen: [s[k].x, s[k].y],
                z: s[k].z,
                inv_w: s[k].inv_w,
                position: et.point_f32::<S>(o.positions[idx[k]]),
                normal: normal(idx[k]),
            });
            let c = o.color_material.map(|_| idx.map(|i| color(i).unwrap()));
            (v, c)
        })
        .collect();
    let separate = sc.separate_specular;
    for (cull, back) in passes(sc, o) {
        let op = RasterOptions {
            cull,
            ..RasterOptions::default()
        };
        if back {
            match scene.back_lighting::<S, GlLights<S>, M, V>() {
                Ok(lit) => draw_with(
                    &lit,
                    o.shading,
                    &tris,
                    separate,
                    fb,
                    db,
                    &op,
                    sc.perspective,
                    rep,
                ),
                Err(e) => rep.unsupported(format!("GlScene::back_lighting: {e}")),
            }
        } else {
            match scene.lighting::<S, GlLights<S>, M, V>() {
                Ok(lit) => draw_with(
                    &lit,
                    o.shading,
                    &tris,
                    separate,
                    fb,
                    db,
                    &op,
                    sc.perspective,
                    rep,
                ),
                Err(e) => rep.unsupported(format!("GlScene::lighting: {e}")),
            }
        }
    }
}

/// The `f64` reference model on the same coverage: per-pixel barycentric
/// coordinates at the pixel centre (perspective-correct for perspective scenes),
/// eye-space positions and normals in `f64`. `GL_FLAT` takes the colour lit at the
/// last vertex, Gouraud interpolates the clamped vertex colours (primary and
/// secondary clamped apart with separate specular), per-pixel shading interpolates
/// position and normal (renormalised, as the GLSL shader does).
struct RefShader<'a> {
    r: &'a Reference<'a>,
    disc: Disc<'a>,
    /// Flat and Gouraud: whether the triangle's colour was lit near a discontinuity.
    tri_near: bool,
    disc_out: &'a mut [u8],
    shading: Shade,
    /// Back faces of two-sided lighting: the normal negated.
    back: bool,
    separate: bool,
    screen: [[f64; 2]; 3],
    inv_w: [f64; 3],
    pos: [V3; 3],
    nrm: [V3; 3],
    flat: V3,
    vcol: [V3; 3],
    out: &'a mut [Option<V3>],
    width: u32,
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

impl SpanShader<0> for RefShader<'_> {
    type Color = Rgb888;
    fn shade_span(&mut self, x: i32, y: i32, _s: &[i32; 0], _d: &[i32; 0], out: &mut [Rgb888]) {
        let p = self.screen;
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        for k in 0..out.len() {
            let (cx, cy) = (f64::from(x + k as i32) + 0.5, f64::from(y) + 0.5);
            let e = |a: [f64; 2], b: [f64; 2]| {
                (b[0] - a[0]) * (cy - a[1]) - (cx - a[0]) * (b[1] - a[1])
            };
            let mut l = [
                e(p[1], p[2]) / area,
                e(p[2], p[0]) / area,
                e(p[0], p[1]) / area,
            ];
            // perspective-correct: weights λᵢ/wᵢ, renormalised
            let q: [f64; 3] = core::array::from_fn(|i| l[i] * self.inv_w[i]);
            let s = q[0] + q[1] + q[2];
            if s != 0.0 {
                l = q.map(|v| v / s);
            }
            let (c, near) = match self.shading {
                Shade::Flat => (self.flat, self.tri_near),
                Shade::Gouraud => (lerp3(l, &self.vcol), self.tri_near),
                Shade::Phong | Shade::Blinn => {
                    let (p, n) = (lerp3(l, &self.pos), lerp3(l, &self.nrm));
                    let n = reference::normalize(n);
                    let n = if self.back { n.map(|c| -c) } else { n };
                    let parts = self.r.shade_parts(p, n, &VertexOptions::default());
                    (combine(parts, self.separate), self.disc.near(p, n))
                }
            };
            let idx = (y as u32 * self.width + (x as u32 + k as u32)) as usize;
            self.out[idx] = Some(c);
            self.disc_out[idx] = u8::from(near);
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
        use fixshade::light::LightKind;
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

fn mul4_64(m: &Mat4, v: [f64; 4]) -> [f64; 4] {
    core::array::from_fn(|r| (0..4).map(|c| f64::from(m.m[r][c]) * v[c]).sum())
}

/// The reference image and the pixels lit near a discontinuity (see [`Disc`]).
fn render_reference(sc: &Scene, geos: &[Geometry], _rep: &mut Report) -> (Vec<Rgb888>, Vec<u8>) {
    let (w, h) = (sc.width, sc.height);
    let mut img: Vec<Option<V3>> = vec![None; (w * h) as usize];
    let mut disc_img = vec![0u8; (w * h) as usize];
    let mut dummy = vec![Rgb888::BLACK; (w * h) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut dummy, w, h).unwrap();
    let mut db = DepthBuffer::new(&mut depth, w).unwrap();
    // the reference takes any f32 colour (no validation)
    let lights = eye_lights(sc);
    let descs: Vec<LightDesc> = lights.iter().map(|l| l.to_desc().unwrap()).collect();
    for (o, g) in sc.objects.iter().zip(geos) {
        let scene = gl_scene(sc, o, &lights);
        let nm = g.mv.normal_matrix();
        // |det M₃|: normal_matrix is |det M₃|·M⁻ᵀ
        let det = {
            let m: [[f64; 3]; 3] =
                core::array::from_fn(|r| core::array::from_fn(|c| f64::from(g.mv.m[r][c])));
            (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
                .abs()
        };
        let eye = |i: usize| -> (V3, V3, f64) {
            let p = o.positions[i].map(f64::from);
            let e = mul4_64(&g.mv, [p[0], p[1], p[2], 1.0]);
            let n = o.normals[i].map(f64::from);
            let ne: V3 = core::array::from_fn(|r| (0..3).map(|c| f64::from(nm[r][c]) * n[c]).sum());
            let ne = if sc.normalize {
                reference::normalize(ne)
            } else {
                ne.map(|c| c / det)
            };
            let clip = mul4_64(&g.mvp, [p[0], p[1], p[2], 1.0]);
            ([e[0], e[1], e[2]], ne, clip[3])
        };
        let sub = f64::from(1u32 << SUBPIXEL_BITS);
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
            let op = RasterOptions {
                cull,
                ..RasterOptions::default()
            };
            for (s, idx) in screen_tris(o, g) {
                let v = idx.map(eye);
                let pos = v.map(|t| t.0);
                let nrm = v.map(|t| t.1);
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
                let tri_near = match o.shading {
                    Shade::Flat => disc.near(pos[2], lit_n(2)),
                    _ => (0..3).any(|k| disc.near(pos[k], lit_n(k))),
                };
                let mut shader = RefShader {
                    r: &r,
                    disc,
                    tri_near,
                    disc_out: &mut disc_img,
                    shading: o.shading,
                    back,
                    separate: sc.separate_specular,
                    screen: s.map(|v| [f64::from(v.x) / sub, f64::from(v.y) / sub]),
                    inv_w: if sc.perspective {
                        v.map(|t| 1.0 / t.2)
                    } else {
                        [1.0; 3]
                    },
                    pos,
                    nrm,
                    flat: vcol[2],
                    vcol,
                    out: &mut img,
                    width: w,
                };
                raster(
                    sc.perspective,
                    &mut fb,
                    &mut db,
                    &s.map(|v| v.to_raster([])),
                    &op,
                    &mut shader,
                );
            }
        }
    }
    let px = img
        .iter()
        .map(|c| match c {
            Some(c) => Rgb888::new(
                reference::to_u8(c[0]),
                reference::to_u8(c[1]),
                reference::to_u8(c[2]),
            ),
            None => Rgb888::BLACK,
        })
        .collect();
    (px, disc_img)
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
        let geos: Vec<Geometry> = sc.objects.iter().map(|o| geometry(&sc, o)).collect();
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
                    let (px, disc) = render_reference(&sc, &geos, &mut rep);
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
