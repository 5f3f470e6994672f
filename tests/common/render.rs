//! The reference scenes of the source documents (DESIGN §1), rendered by a tier
//! through the real pipeline (mesh → lighting → shading → rasterizer → framebuffer)
//! and by the f64 reference model on exactly the same pixel coverage.
//!
//! Shared by `tests/golden.rs`, `examples/showcase.rs` and `examples/tradeoff.rs`
//! (included with `#[path]`).

#![allow(dead_code)]

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use fixshade::color::{OutputColor, Rgb};
use fixshade::light::{AnyLight, LightDesc, LightKind};
use fixshade::lighting::{BlinnPhong, Lambert, Lighting, Model, Phong as PhongSpec, Terms};
use fixshade::material::{AmbientSource, Material, MaterialDesc};
use fixshade::mesh::{uv_sphere, uv_sphere_counts, Mat4, ScreenTransform, ScreenVertex, Viewport};
use fixshade::num::Scalar;
use fixshade::raster::{draw_triangle, Cull, RasterOptions, SpanShader};
use fixshade::reference::{normalize, ModelDesc, Reference, ViewerDesc, V3};
use fixshade::shade::{
    FlatShading, GouraudShading, Linear, PhongShading, ShadeVertex, Shader, Shading,
};
use fixshade::target::{DepthBuffer, Framebuffer, SliceFramebuffer};

/// Pixels per eye-space unit of the orthographic camera.
pub const PIXELS_PER_UNIT: f32 = 100.0;
/// UV-sphere tessellation of the showcase spheres.
pub const STACKS: usize = 16;
pub const SLICES: usize = 24;

/// The shading method of an object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Flat,
    Gouraud,
    Phong,
}

impl Mode {
    pub fn name(self) -> &'static str {
        match self {
            Mode::Flat => "flat",
            Mode::Gouraud => "gouraud",
            Mode::Phong => "phong",
        }
    }
}

/// The material terms of an object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Terms4 {
    Lambert,
    Brilliance,
    Phong,
    Blinn,
}

/// What is drawn.
#[derive(Clone, Copy, Debug)]
pub enum Shape {
    /// A UV sphere: centre in pixels, radius in pixels.
    Sphere { centre: [f32; 2], radius: f32 },
    /// One triangle: corners in pixels, vertex normals.
    Triangle {
        corners: [[f32; 2]; 3],
        normals: [[f32; 3]; 3],
    },
}

#[derive(Clone, Debug)]
pub struct Object {
    pub shape: Shape,
    pub material: MaterialDesc,
    pub mode: Mode,
    pub terms: Terms4,
}

#[derive(Clone, Debug)]
pub struct Scene {
    pub name: &'static str,
    pub title: &'static str,
    pub width: u32,
    pub height: u32,
    pub lights: Vec<LightDesc>,
    pub global_ambient: [f32; 3],
    pub objects: Vec<Object>,
}

fn white_dir(dir: [f32; 3], k: f32) -> LightDesc {
    LightDesc {
        kind: LightKind::Directional { towards_light: dir },
        ambient: [k; 3],
        diffuse: [k; 3],
        specular: [k; 3],
    }
}

fn row(
    name: &'static str,
    title: &'static str,
    lights: Vec<LightDesc>,
    materials: Vec<(MaterialDesc, Mode, Terms4)>,
) -> Scene {
    let r = 36.0;
    let pitch = 2.0 * r + 8.0;
    let objects = materials
        .into_iter()
        .enumerate()
        .map(|(i, (material, mode, terms))| Object {
            shape: Shape::Sphere {
                centre: [4.0 + r + pitch * i as f32, 4.0 + r],
                radius: r,
            },
            material,
            mode,
            terms,
        })
        .collect::<Vec<_>>();
    Scene {
        name,
        title,
        width: (pitch * objects.len() as f32) as u32,
        height: (2.0 * r + 8.0) as u32,
        lights,
        global_ambient: [0.0; 3],
        objects,
    }
}

const RED: [f32; 3] = [1.0, 0.0, 0.0];
const ORANGE: [f32; 3] = [1.0, 0.55, 0.1];

/// Every reference scene of DESIGN §1.
pub fn scenes() -> Vec<Scene> {
    let key = [-0.4f32, 0.5, 0.77];
    let two_white = vec![
        white_dir([-0.5, 0.5, 0.7], 0.6),
        white_dir([0.6, 0.2, 0.75], 0.6),
    ];
    let one = |k: f32| {
        vec![LightDesc {
            ambient: [k; 3],
            ..white_dir(key, 1.0)
        }]
    };
    let classic = |obj, src, ka, kd, ks, n| MaterialDesc::classic(obj, src, ka, kd, ks, n);
    let mut v = Vec::new();
    // seed 004: six red spheres, two white lights, ka = 0, kd = 0.5, n = 1 … 100 (Phong)
    v.push(row(
        "shininess_six",
        "six red spheres, two white lights, ka 0, kd 0.5, n = 1, 5, 10, 20, 50, 100",
        two_white.clone(),
        [1.0, 5.0, 10.0, 20.0, 50.0, 100.0]
            .iter()
            .map(|&n| {
                (
                    classic(RED, AmbientSource::Object, 0.0, 0.5, 0.6, n),
                    Mode::Phong,
                    Terms4::Phong,
                )
            })
            .collect(),
    ));
    // seed 001: ka = 0, 0.2, 0.4, 0.6 (ambient from the object colour)
    v.push(row(
        "ambient_001",
        "ambient ka = 0, 0.2, 0.4, 0.6 (ka·Io)",
        one(1.0),
        [0.0, 0.2, 0.4, 0.6]
            .iter()
            .map(|&ka| {
                (
                    classic(ORANGE, AmbientSource::Object, ka, 0.4, 0.0, 1.0),
                    Mode::Phong,
                    Terms4::Lambert,
                )
            })
            .collect(),
    ));
    // seed 003: kd = 0 … 1 in steps of 0.2
    v.push(row(
        "diffuse_003",
        "diffuse kd = 0, 0.2, 0.4, 0.6, 0.8, 1.0",
        one(0.0),
        [0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
            .iter()
            .map(|&kd| {
                (
                    classic(ORANGE, AmbientSource::Object, 0.1, kd, 0.0, 1.0),
                    Mode::Phong,
                    Terms4::Lambert,
                )
            })
            .collect(),
    ));
    // seed 003: ka = 0, 0.1, 0.3, 0.5, 0.7 (ambient from the light colour)
    v.push(row(
        "ambient_003",
        "ambient ka = 0, 0.1, 0.3, 0.5, 0.7 (ka·Ia)",
        one(0.5),
        [0.0, 0.1, 0.3, 0.5, 0.7]
            .iter()
            .map(|&ka| {
                (
                    classic(ORANGE, AmbientSource::Light, ka, 0.5, 0.0, 1.0),
                    Mode::Phong,
                    Terms4::Lambert,
                )
            })
            .collect(),
    ));
    // seed 001: brilliance 8, 4, 2, 1
    v.push(row(
        "brilliance_001",
        "diffuse brilliance b = 8, 4, 2, 1",
        one(0.0),
        [8u8, 4, 2, 1]
            .iter()
            .map(|&b| {
                let m = MaterialDesc {
                    brilliance: b,
                    ..classic(ORANGE, AmbientSource::Object, 0.1, 0.9, 0.0, 1.0)
                };
                (m, Mode::Phong, Terms4::Brilliance)
            })
            .collect(),
    ));
    // seed 001: n = 5, 10, 20, 40
    v.push(row(
        "shininess_001",
        "specular n = 5, 10, 20, 40",
        one(0.0),
        [5.0, 10.0, 20.0, 40.0]
            .iter()
            .map(|&n| {
                (
                    classic(RED, AmbientSource::Object, 0.1, 0.6, 0.7, n),
                    Mode::Phong,
                    Terms4::Phong,
                )
            })
            .collect(),
    ));
    // seeds 000, 003: flat vs Gouraud vs Phong on one sphere
    let m = classic(RED, AmbientSource::Object, 0.1, 0.6, 0.7, 20.0);
    v.push(row(
        "flat_gouraud_phong",
        "flat, Gouraud, Phong shading of one sphere (Blinn-Phong n = 20)",
        one(0.0),
        vec![
            (m, Mode::Flat, Terms4::Blinn),
            (m, Mode::Gouraud, Terms4::Blinn),
            (m, Mode::Phong, Terms4::Blinn),
        ],
    ));
    // seed 003: Phong vs Blinn-Phong (n' = 4n gives a similar highlight)
    v.push(row(
        "phong_vs_blinn",
        "Phong (R·V)^10 vs Blinn-Phong (N·H)^40",
        one(0.0),
        vec![
            (
                classic(RED, AmbientSource::Object, 0.1, 0.6, 0.7, 10.0),
                Mode::Phong,
                Terms4::Phong,
            ),
            (
                classic(RED, AmbientSource::Object, 0.1, 0.6, 0.7, 40.0),
                Mode::Phong,
                Terms4::Blinn,
            ),
        ],
    ));
    // seed 002: a large triangle whose highlight is at its centre: Gouraud misses it
    let tri = |x0: f32, mode| Object {
        shape: Shape::Triangle {
            corners: [[x0 + 8.0, 150.0], [x0 + 152.0, 150.0], [x0 + 80.0, 8.0]],
            normals: [[-0.55, -0.4, 0.73], [0.55, -0.4, 0.73], [0.0, 0.6, 0.8]],
        },
        material: classic([0.2, 0.4, 1.0], AmbientSource::Object, 0.1, 0.5, 0.8, 30.0),
        mode,
        terms: Terms4::Blinn,
    };
    v.push(Scene {
        name: "big_triangle",
        title: "one large triangle, highlight at its centre: Gouraud (left) misses it, Phong (right) shows it",
        width: 320,
        height: 160,
        lights: vec![white_dir([0.0, 0.0, 1.0], 1.0)],
        global_ambient: [0.0; 3],
        objects: vec![tri(0.0, Mode::Gouraud), tri(160.0, Mode::Phong)],
    });
    v
}

/// One vertex: its projection and its exact eye-space position and normal.
#[derive(Clone, Copy, Debug)]
pub struct Vert {
    pub screen: ScreenVertex,
    pub pos: [f32; 3],
    pub normal: [f32; 3],
}

fn eye(p: [f32; 2]) -> [f32; 3] {
    [p[0] / PIXELS_PER_UNIT, -p[1] / PIXELS_PER_UNIT, -5.0]
}

/// The triangles of an object, projected by the orthographic camera of a scene.
pub fn triangles(scene: &Scene, obj: &Object) -> Vec<[Vert; 3]> {
    let (w, h) = (
        scene.width as f32 / PIXELS_PER_UNIT,
        scene.height as f32 / PIXELS_PER_UNIT,
    );
    let proj = Mat4::orthographic(0.0, w, -h, 0.0, 1.0, 20.0).unwrap();
    let vp = Viewport::new(0, 0, scene.width as i32, scene.height as i32).unwrap();
    let st = ScreenTransform::new(&proj, vp, 0.5).unwrap();
    let vert = |pos: [f32; 3], normal: [f32; 3]| Vert {
        screen: st.project_f32(pos).unwrap(),
        pos,
        normal,
    };
    match obj.shape {
        Shape::Sphere { centre, radius } => {
            const N: (usize, usize) = uv_sphere_counts(STACKS, SLICES);
            let (mut p, mut n, mut t) = (
                vec![[0.0f32; 3]; N.0],
                vec![[0.0f32; 3]; N.0],
                vec![[0u16; 3]; N.1],
            );
            uv_sphere(
                STACKS,
                SLICES,
                eye(centre),
                radius / PIXELS_PER_UNIT,
                &mut p,
                &mut n,
                &mut t,
            )
            .unwrap();
            t.iter()
                .map(|tri| tri.map(|i| vert(p[i as usize], n[i as usize])))
                .collect()
        }
        Shape::Triangle { corners, normals } => {
            vec![[0, 1, 2].map(|i| vert(eye(corners[i]), normals[i]))]
        }
    }
}

fn opts() -> RasterOptions {
    RasterOptions {
        cull: Cull::Back,
        ..RasterOptions::default()
    }
}

/// The projected triangles of every object of a scene (the per-frame geometry
/// work, done once so that timings measure shading and rasterization only).
pub fn prepare(scene: &Scene) -> Vec<Vec<[Vert; 3]>> {
    scene.objects.iter().map(|o| triangles(scene, o)).collect()
}

/// Renders a scene with tier `S` into colour type `C` (black background).
pub fn render_tier<S: Scalar, C: OutputColor + Default>(scene: &Scene) -> Vec<C> {
    let (w, h) = (scene.width, scene.height);
    let mut pixels = vec![C::from_channels([0; 3]); (w * h) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    draw_prepared::<S, C>(scene, &prepare(scene), &mut pixels, &mut depth);
    pixels
}

/// Draws prepared triangles into `pixels` (the depth buffer must be cleared);
/// returns the number of shaded pixels.
pub fn draw_prepared<S: Scalar, C: OutputColor + Default>(
    scene: &Scene,
    prepared: &[Vec<[Vert; 3]>],
    pixels: &mut [C],
    depth: &mut [u16],
) -> u64 {
    let mut fb = SliceFramebuffer::new(pixels, scene.width, scene.height).unwrap();
    draw_into::<S, C, _>(scene, prepared, &mut fb, depth)
}

/// Draws prepared triangles into any framebuffer (e.g. a `DrawTargetAdapter` over
/// a display); `depth` must be cleared and hold `width × height` values.
pub fn draw_into<
    S: Scalar,
    C: OutputColor + Default,
    F: Framebuffer<Color = C, Error: core::fmt::Debug>,
>(
    scene: &Scene,
    prepared: &[Vec<[Vert; 3]>],
    fb: &mut F,
    depth: &mut [u16],
) -> u64 {
    let mut db = DepthBuffer::new(depth, scene.width).unwrap();
    let mut shaded = 0;
    for (obj, tris) in scene.objects.iter().zip(prepared) {
        shaded += match obj.terms {
            Terms4::Lambert => draw_object::<S, Lambert, C, F>(scene, obj, tris, fb, &mut db),
            Terms4::Brilliance => {
                draw_object::<S, Terms<0, true, false, false>, C, F>(scene, obj, tris, fb, &mut db)
            }
            Terms4::Phong => draw_object::<S, PhongSpec, C, F>(scene, obj, tris, fb, &mut db),
            Terms4::Blinn => draw_object::<S, BlinnPhong, C, F>(scene, obj, tris, fb, &mut db),
        };
    }
    shaded
}

fn draw_object<
    S: Scalar,
    M: Model,
    C: OutputColor + Default,
    F: Framebuffer<Color = C, Error: core::fmt::Debug>,
>(
    scene: &Scene,
    obj: &Object,
    tris: &[[Vert; 3]],
    fb: &mut F,
    db: &mut DepthBuffer<'_>,
) -> u64 {
    let lights: heapless::Vec<AnyLight<S>, 4> = scene
        .lights
        .iter()
        .map(|d| AnyLight::new(d).unwrap())
        .collect();
    let lighting = Lighting::<S, _, M>::new(lights, Material::new(&obj.material).unwrap())
        .with_global_ambient(Rgb::from_f32(scene.global_ambient));
    let sv = |v: &Vert| {
        ShadeVertex::<S>::new(
            [v.screen.x, v.screen.y],
            v.screen.z,
            v.screen.inv_w,
            v.pos,
            v.normal,
        )
    };
    let o = opts();
    let mut shaded = 0u64;
    match obj.mode {
        Mode::Flat => {
            let mut s = Shader::new(FlatShading, &lighting, Linear);
            for t in tris {
                shaded += ok(s.draw(fb, Some(db), &t.each_ref().map(sv), &o)).pixels as u64;
            }
        }
        Mode::Gouraud => {
            let mut s = Shader::new(GouraudShading, &lighting, Linear);
            for t in tris {
                shaded += ok(s.draw(fb, Some(db), &t.each_ref().map(sv), &o)).pixels as u64;
            }
        }
        Mode::Phong => {
            let mut s = Shader::new(PhongShading, &lighting, Linear);
            for t in tris {
                shaded += ok(s.draw(fb, Some(db), &t.each_ref().map(sv), &o)).pixels as u64;
            }
        }
    }
    shaded
}

/// The value of a drawing call whose framebuffer cannot fail, or a panic
/// naming the display error (a test failure).
pub fn ok<T, E: core::fmt::Debug>(r: Result<T, E>) -> T {
    r.expect("display error")
}

/// The f64 reference image: linear RGB per covered pixel, `None` for background.
pub fn render_reference(scene: &Scene) -> Vec<Option<V3>> {
    let (w, h) = (scene.width, scene.height);
    let mut out = vec![None; (w * h) as usize];
    let mut dummy = vec![Rgb888::BLACK; (w * h) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut dummy, w, h).unwrap();
    let mut db = DepthBuffer::new(&mut depth, w).unwrap();
    for obj in &scene.objects {
        let model = match obj.terms {
            Terms4::Lambert => ModelDesc::of::<Lambert>(),
            Terms4::Brilliance => ModelDesc::of::<Terms<0, true, false, false>>(),
            Terms4::Phong => ModelDesc::of::<PhongSpec>(),
            Terms4::Blinn => ModelDesc::of::<BlinnPhong>(),
        };
        let r = Reference {
            lights: &scene.lights,
            material: obj.material,
            global_ambient: scene.global_ambient,
            viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
            fog: None,
            model,
        };
        for t in triangles(scene, obj) {
            let raster = t.map(|v| v.screen.to_raster([]));
            let mut s = RefSpan {
                r: &r,
                tri: t,
                mode: obj.mode,
                out: &mut out,
                width: w,
            };
            ok(draw_triangle(
                &mut fb,
                Some(&mut db),
                &raster,
                &opts(),
                &mut s,
            ));
        }
    }
    out
}

/// Shades covered pixels with the reference model from f64 barycentric
/// coordinates at the pixel centres.
struct RefSpan<'a> {
    r: &'a Reference<'a>,
    tri: [Vert; 3],
    mode: Mode,
    out: &'a mut Vec<Option<V3>>,
    width: u32,
}

fn f64s(v: [f32; 3]) -> V3 {
    v.map(|x| x as f64)
}

impl SpanShader<0> for RefSpan<'_> {
    type Color = Rgb888;
    fn shade_span(&mut self, x: i32, y: i32, _s: &[i32; 0], _d: &[i32; 0], out: &mut [Rgb888]) {
        let sub = (1 << fixshade::raster::SUBPIXEL_BITS) as f64;
        let p = self
            .tri
            .map(|v| [v.screen.x as f64 / sub, v.screen.y as f64 / sub]);
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        let lerp = |l: [f64; 3], a: [V3; 3]| -> V3 {
            [0, 1, 2].map(|c| l[0] * a[0][c] + l[1] * a[1][c] + l[2] * a[2][c])
        };
        let pos = self.tri.map(|v| f64s(v.pos));
        let nrm = self.tri.map(|v| f64s(v.normal));
        let clamp = |c: V3| c.map(|x| x.clamp(0.0, 1.0));
        // per-triangle and per-vertex colours for flat and Gouraud
        let flat = || {
            let n = normalize([0, 1, 2].map(|c| nrm[0][c] + nrm[1][c] + nrm[2][c]));
            let centroid = [0, 1, 2].map(|c| (pos[0][c] + pos[1][c] + pos[2][c]) / 3.0);
            self.r.shade(centroid, n)
        };
        let vertex_colours = || [0, 1, 2].map(|i| clamp(self.r.shade(pos[i], nrm[i])));
        let flat_c = (self.mode == Mode::Flat).then(flat);
        let vc = (self.mode == Mode::Gouraud).then(vertex_colours);
        for (k, _) in out.iter_mut().enumerate() {
            let (cx, cy) = ((x + k as i32) as f64 + 0.5, y as f64 + 0.5);
            // barycentric coordinates of the pixel centre
            let e = |a: [f64; 2], b: [f64; 2]| {
                (b[0] - a[0]) * (cy - a[1]) - (cx - a[0]) * (b[1] - a[1])
            };
            let l = [
                e(p[1], p[2]) / area,
                e(p[2], p[0]) / area,
                e(p[0], p[1]) / area,
            ];
            let c = match self.mode {
                Mode::Flat => flat_c.unwrap(),
                Mode::Gouraud => lerp(l, vc.unwrap()),
                Mode::Phong => self.r.shade(lerp(l, pos), lerp(l, nrm)),
            };
            let idx = (y as u32 * self.width + (x as u32 + k as u32)) as usize;
            self.out[idx] = Some(c);
        }
    }
}

/// Errors of an 8-bit tier image against the reference, over covered pixels.
#[derive(Clone, Copy, Debug, Default)]
pub struct Diff {
    pub max: u32,
    pub mean: f64,
    pub psnr: f64,
    pub identical_565: f64,
    pub pixels: usize,
}

pub fn q(x: f64, max: f64) -> u32 {
    (x.clamp(0.0, 1.0) * max).round() as u32
}

/// Compares a tier's Rgb888 and Rgb565 renders with the reference.
pub fn compare(rgb888: &[Rgb888], rgb565: &[Rgb565], reference: &[Option<V3>]) -> Diff {
    let (mut max, mut sum, mut sq, mut same, mut n) = (0u32, 0u64, 0f64, 0usize, 0usize);
    for i in 0..reference.len() {
        let Some(r) = reference[i] else { continue };
        n += 1;
        let t = rgb888[i];
        let want = [q(r[0], 255.0), q(r[1], 255.0), q(r[2], 255.0)];
        let got = [t.r() as u32, t.g() as u32, t.b() as u32];
        let e = (0..3).map(|c| got[c].abs_diff(want[c])).max().unwrap();
        max = max.max(e);
        sum += e as u64;
        sq += (0..3)
            .map(|c| (got[c] as f64 - r[c].clamp(0.0, 1.0) * 255.0).powi(2))
            .sum::<f64>()
            / 3.0;
        let c = rgb565[i];
        if [c.r() as u32, c.g() as u32, c.b() as u32]
            == [q(r[0], 31.0), q(r[1], 63.0), q(r[2], 31.0)]
        {
            same += 1;
        }
    }
    let mse = sq / n.max(1) as f64;
    Diff {
        max,
        mean: sum as f64 / n.max(1) as f64,
        psnr: if mse > 0.0 {
            10.0 * (255.0f64 * 255.0 / mse).log10()
        } else {
            f64::INFINITY
        },
        identical_565: same as f64 / n.max(1) as f64,
        pixels: n,
    }
}

/// Renders a scene with tier `S` and compares it with the reference.
pub fn diff_tier<S: Scalar>(scene: &Scene, reference: &[Option<V3>]) -> Diff {
    compare(
        &render_tier::<S, Rgb888>(scene),
        &render_tier::<S, Rgb565>(scene),
        reference,
    )
}

/// The reference image quantised to Rgb888 (background black).
pub fn reference_rgb888(reference: &[Option<V3>]) -> Vec<Rgb888> {
    reference
        .iter()
        .map(|c| match c {
            Some(r) => Rgb888::new(
                q(r[0], 255.0) as u8,
                q(r[1], 255.0) as u8,
                q(r[2], 255.0) as u8,
            ),
            None => Rgb888::BLACK,
        })
        .collect()
}

/// The light sets of the speed/accuracy table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSet {
    /// One directional light, Lambert diffuse only.
    DirDiffuse,
    /// One directional light, Blinn-Phong specular.
    DirBlinn,
    /// One directional light, Phong specular.
    DirPhong,
    /// Four point lights with attenuation, Blinn-Phong specular.
    Point4Blinn,
    /// One spot light, Blinn-Phong specular.
    SpotBlinn,
}

pub const LIGHT_SETS: [LightSet; 5] = [
    LightSet::DirDiffuse,
    LightSet::DirBlinn,
    LightSet::DirPhong,
    LightSet::Point4Blinn,
    LightSet::SpotBlinn,
];
pub const MODES: [Mode; 3] = [Mode::Flat, Mode::Gouraud, Mode::Phong];

impl LightSet {
    pub fn name(self) -> &'static str {
        match self {
            LightSet::DirDiffuse => "dir_diffuse",
            LightSet::DirBlinn => "dir_blinn",
            LightSet::DirPhong => "dir_phong",
            LightSet::Point4Blinn => "point4_blinn",
            LightSet::SpotBlinn => "spot_blinn",
        }
    }
}

/// One lit sphere of radius 100 px on a 240×240 display (eye space: centre
/// (1.2, −1.2, −5), radius 1), red plastic (ka 0.1, kd 0.7, ks 0.5, n = 32).
pub fn config_scene(lights: LightSet, mode: Mode) -> Scene {
    let key = [-0.4f32, 0.5, 0.77];
    let centre = [1.2f32, -1.2, -5.0];
    let point = |dx: f32, dy: f32, dz: f32, k: f32| LightDesc {
        kind: LightKind::Point {
            position: [centre[0] + dx, centre[1] + dy, centre[2] + dz],
            attenuation: [1.0, 0.05, 0.01],
        },
        ambient: [0.0; 3],
        diffuse: [k; 3],
        specular: [k; 3],
    };
    let (descs, terms) = match lights {
        LightSet::DirDiffuse => (vec![white_dir(key, 1.0)], Terms4::Lambert),
        LightSet::DirBlinn => (vec![white_dir(key, 1.0)], Terms4::Blinn),
        LightSet::DirPhong => (vec![white_dir(key, 1.0)], Terms4::Phong),
        LightSet::Point4Blinn => (
            vec![
                point(-2.0, 2.0, 3.0, 0.5),
                point(2.5, 1.0, 2.0, 0.4),
                point(0.0, -2.5, 2.5, 0.3),
                point(-1.0, 0.0, 4.0, 0.3),
            ],
            Terms4::Blinn,
        ),
        LightSet::SpotBlinn => (
            vec![LightDesc {
                kind: LightKind::Spot {
                    position: [centre[0] - 1.0, centre[1] + 1.5, centre[2] + 3.0],
                    axis: [1.0, -1.5, -3.0],
                    exponent: 8.0,
                    cutoff_deg: 30.0,
                    attenuation: [1.0, 0.0, 0.0],
                },
                ambient: [0.0; 3],
                diffuse: [1.0; 3],
                specular: [1.0; 3],
            }],
            Terms4::Blinn,
        ),
    };
    Scene {
        name: lights.name(),
        title: "configuration sphere",
        width: 240,
        height: 240,
        lights: descs,
        global_ambient: [0.2; 3],
        objects: vec![Object {
            shape: Shape::Sphere {
                centre: [120.0, 120.0],
                radius: 100.0,
            },
            material: MaterialDesc::classic(RED, AmbientSource::Object, 0.1, 0.7, 0.5, 32.0),
            mode,
            terms,
        }],
    }
}

/// Renders a scene with [`fixshade::shade::IncrementalPhongShading`] in `Q14<NW>` (every
/// object Phong-shaded), if the scene has only directional lights (one or two) and
/// Lambert or Blinn-Phong materials; `None` otherwise.
pub fn render_incremental<const NW: u8, C: OutputColor + Default>(scene: &Scene) -> Option<Vec<C>> {
    use fixshade::light::DirectionalLight;
    use fixshade::num::Q14;
    let dirs: Vec<DirectionalLight<Q14<NW>>> = scene
        .lights
        .iter()
        .map(|d| match d.kind {
            LightKind::Directional { towards_light } => {
                fixshade::light::LightColors::new(d.ambient, d.diffuse, d.specular)
                    .and_then(|c| DirectionalLight::new(towards_light, c))
                    .ok()
            }
            _ => None,
        })
        .collect::<Option<_>>()?;
    if scene
        .objects
        .iter()
        .any(|o| !matches!(o.terms, Terms4::Lambert | Terms4::Blinn))
    {
        return None;
    }
    let (w, h) = (scene.width, scene.height);
    let mut pixels = vec![C::from_channels([0; 3]); (w * h) as usize];
    let mut depth = vec![u16::MAX; (w * h) as usize];
    let prepared = prepare(scene);
    {
        let mut fb = SliceFramebuffer::new(&mut pixels, w, h).unwrap();
        let mut db = DepthBuffer::new(&mut depth, w).unwrap();
        for (obj, tris) in scene.objects.iter().zip(&prepared) {
            match (dirs.len(), obj.terms) {
                (1, Terms4::Lambert) => {
                    draw_inc::<NW, 1, Lambert, C>(scene, obj, [dirs[0]], tris, &mut fb, &mut db)
                }
                (1, _) => {
                    draw_inc::<NW, 1, BlinnPhong, C>(scene, obj, [dirs[0]], tris, &mut fb, &mut db)
                }
                (2, Terms4::Lambert) => draw_inc::<NW, 2, Lambert, C>(
                    scene,
                    obj,
                    [dirs[0], dirs[1]],
                    tris,
                    &mut fb,
                    &mut db,
                ),
                (2, _) => draw_inc::<NW, 2, BlinnPhong, C>(
                    scene,
                    obj,
                    [dirs[0], dirs[1]],
                    tris,
                    &mut fb,
                    &mut db,
                ),
                _ => return None,
            };
        }
    }
    Some(pixels)
}

/// Draws one object with incremental Phong shading; returns the shaded pixels.
pub fn draw_inc<
    const NW: u8,
    const K: usize,
    M: fixshade::shade::IncrementalModel,
    C: OutputColor + Default,
>(
    scene: &Scene,
    obj: &Object,
    lights: [fixshade::light::DirectionalLight<fixshade::num::Q14<NW>>; K],
    tris: &[[Vert; 3]],
    fb: &mut SliceFramebuffer<'_, C>,
    db: &mut DepthBuffer<'_>,
) -> u64
where
    for<'a> Shader<
        'a,
        fixshade::shade::IncrementalPhongShading,
        fixshade::shade::DirectionalLighting<NW, K, M>,
        Linear,
        C,
    >: Shading<fixshade::num::Q14<NW>, Color = C>,
    fixshade::shade::IncrementalPhongShading:
        fixshade::shade::ModeState<fixshade::shade::DirectionalLighting<NW, K, M>, C>,
{
    use fixshade::num::Q14;
    let lighting = Lighting::<Q14<NW>, _, M>::new(lights, Material::new(&obj.material).unwrap())
        .with_global_ambient(Rgb::from_f32(scene.global_ambient));
    let mut s = Shader::new(fixshade::shade::IncrementalPhongShading, &lighting, Linear);
    let o = opts();
    tris.iter()
        .map(|t| {
            let sv = t.each_ref().map(|v| {
                ShadeVertex::<Q14<NW>>::new(
                    [v.screen.x, v.screen.y],
                    v.screen.z,
                    v.screen.inv_w,
                    v.pos,
                    v.normal,
                )
            });
            ok(s.draw(fb, Some(db), &sv, &o)).pixels as u64
        })
        .sum()
}

/// The same scene with every object Phong-shaded (for the incremental comparison).
pub fn all_phong(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.objects.iter_mut().for_each(|o| o.mode = Mode::Phong);
    s
}

// ------------------------------------------------------------------ the mesh renderer

/// A scene's objects as compact meshes for the mesh renderer: positions in eye
/// units with `MESH_FRAC` fraction bits, Q14 normals.
const MESH_FRAC: u8 = 10;

/// The unit sphere of the showcase spheres (scaled and moved by each object's
/// model matrix).
static UNIT_SPHERE: fixshade::mesh::MeshData<
    { uv_sphere_counts(STACKS, SLICES).0 },
    { uv_sphere_counts(STACKS, SLICES).1 },
> = fixshade::mesh::MeshData::uv_sphere(STACKS, SLICES, 14);

/// An object's mesh and model matrix.
struct ObjectMesh {
    positions: Vec<[i16; 3]>,
    normals: Vec<[i16; 3]>,
    triangles: Vec<[u16; 3]>,
    frac: u8,
    model: Mat4,
}

fn object_mesh(obj: &Object) -> ObjectMesh {
    match obj.shape {
        Shape::Sphere { centre, radius } => ObjectMesh {
            positions: UNIT_SPHERE.positions.to_vec(),
            normals: UNIT_SPHERE.normals.to_vec(),
            triangles: UNIT_SPHERE.triangles.to_vec(),
            frac: UNIT_SPHERE.frac,
            model: Mat4::translate(eye(centre)).mul(&Mat4::scale([radius / PIXELS_PER_UNIT; 3])),
        },
        Shape::Triangle { corners, normals } => {
            let q = |v: f32, f: u8| (v * f32::from(1u16 << f)).round() as i16;
            ObjectMesh {
                positions: corners
                    .iter()
                    .map(|c| eye(*c).map(|v| q(v, MESH_FRAC)))
                    .collect(),
                normals: normals
                    .iter()
                    .map(|n| {
                        normalize([n[0] as f64, n[1] as f64, n[2] as f64]).map(|v| q(v as f32, 14))
                    })
                    .collect(),
                triangles: vec![[0, 1, 2]],
                frac: MESH_FRAC,
                model: Mat4::IDENTITY,
            }
        }
    }
}

/// Renders a scene with the mesh renderer in tier `S`: one `MeshDraw` per
/// object (each with its own model matrix, material and shading mode), all
/// drawn band by band (8-row strip and depth strip) into `display`.
pub fn render_mesh<S: Scalar, D>(scene: &Scene, display: &mut D) -> Result<(), D::Error>
where
    D: embedded_graphics_core::draw_target::DrawTarget<Color = Rgb888>,
{
    use fixshade::camera::Camera;
    use fixshade::render::{
        bins_len, Bands, CachedVertex, Carry, DrawBand, Layout, MeshDraw, MeshMemory,
    };
    const ROWS: u32 = 8;
    let (w, h) = (scene.width, scene.height);
    let layout = Layout::banded(w, h, ROWS).unwrap();
    let cam = Camera::orthographic(
        0.0,
        w as f32 / PIXELS_PER_UNIT,
        -(h as f32) / PIXELS_PER_UNIT,
        0.0,
        1.0,
        20.0,
        Viewport::new(0, 0, w as i32, h as i32).unwrap(),
    )
    .unwrap();
    let meshes: Vec<ObjectMesh> = scene.objects.iter().map(object_mesh).collect();
    let lights: heapless::Vec<AnyLight<S>, 4> = scene
        .lights
        .iter()
        .map(|d| AnyLight::new(d).unwrap())
        .collect();
    let lighting = |o: &Object| {
        (
            lights.clone(),
            Material::<S>::new(&o.material).unwrap(),
            Rgb::<S>::from_f32(scene.global_ambient),
        )
    };
    // storage first (one slot per object and payload type), then the draws borrowing it
    let mut lam: Vec<_> = Vec::new();
    let mut bri: Vec<_> = Vec::new();
    let mut pho: Vec<_> = Vec::new();
    let mut bli: Vec<_> = Vec::new();
    for o in &scene.objects {
        let (l, m, g) = lighting(o);
        match o.terms {
            Terms4::Lambert => {
                lam.push(Lighting::<S, _, Lambert>::new(l, m).with_global_ambient(g))
            }
            Terms4::Brilliance => bri.push(
                Lighting::<S, _, Terms<0, true, false, false>>::new(l, m).with_global_ambient(g),
            ),
            Terms4::Phong => {
                pho.push(Lighting::<S, _, PhongSpec>::new(l, m).with_global_ambient(g))
            }
            Terms4::Blinn => {
                bli.push(Lighting::<S, _, BlinnPhong>::new(l, m).with_global_ambient(g))
            }
        }
    }
    let nv = |m: &ObjectMesh| m.positions.len();
    let mut caches_u: Vec<Vec<CachedVertex<[u16; 3]>>> = meshes
        .iter()
        .map(|m| vec![CachedVertex::default(); nv(m)])
        .collect();
    let mut caches_i: Vec<Vec<CachedVertex<[i16; 3]>>> = meshes
        .iter()
        .map(|m| vec![CachedVertex::default(); nv(m)])
        .collect();
    let mut bins: Vec<Vec<u16>> = meshes
        .iter()
        .map(|m| vec![0; bins_len(m.triangles.len(), layout.bands() as usize)])
        .collect();
    let mut carry: Vec<Vec<Carry>> = meshes
        .iter()
        .map(|m| vec![Carry::default(); 2 * m.triangles.len()])
        .collect();
    let (mut il, mut ib, mut ip, mut iq) = (lam.iter(), bri.iter(), pho.iter(), bli.iter());
    let mut draws: Vec<Box<dyn DrawBand<Rgb888> + '_>> = Vec::new();
    for ((((o, m), (cu, ci)), b), c) in scene
        .objects
        .iter()
        .zip(&meshes)
        .zip(caches_u.iter_mut().zip(caches_i.iter_mut()))
        .zip(bins.iter_mut())
        .zip(carry.iter_mut())
    {
        let mesh =
            fixshade::mesh::Mesh::new(&m.positions, &m.normals, &m.triangles, m.frac).unwrap();
        let t = cam.mesh_transform(&m.model, m.frac).unwrap();
        macro_rules! draw {
            ($lit:expr) => {{
                let lit = $lit;
                match o.mode {
                    Mode::Flat => Box::new(
                        MeshDraw::new(
                            layout,
                            mesh,
                            &t,
                            Shader::new(FlatShading, lit, Linear),
                            MeshMemory {
                                vertices: ci,
                                bins: b,
                                carry: c,
                            },
                        )
                        .unwrap(),
                    ) as Box<dyn DrawBand<Rgb888>>,
                    Mode::Gouraud => Box::new(
                        MeshDraw::new(
                            layout,
                            mesh,
                            &t,
                            Shader::new(GouraudShading, lit, Linear),
                            MeshMemory {
                                vertices: cu,
                                bins: b,
                                carry: c,
                            },
                        )
                        .unwrap(),
                    ),
                    Mode::Phong => Box::new(
                        MeshDraw::new(
                            layout,
                            mesh,
                            &t,
                            Shader::new(PhongShading, lit, Linear),
                            MeshMemory {
                                vertices: ci,
                                bins: b,
                                carry: c,
                            },
                        )
                        .unwrap(),
                    ),
                }
            }};
        }
        draws.push(match o.terms {
            Terms4::Lambert => draw!(il.next().unwrap()),
            Terms4::Brilliance => draw!(ib.next().unwrap()),
            Terms4::Phong => draw!(ip.next().unwrap()),
            Terms4::Blinn => draw!(iq.next().unwrap()),
        });
    }
    let mut strip = vec![Rgb888::BLACK; (w * ROWS) as usize];
    let mut depth = vec![0u16; (w * ROWS) as usize];
    let mut items: Vec<&mut dyn DrawBand<Rgb888>> = draws
        .iter_mut()
        .map(|d| &mut **d as &mut dyn DrawBand<Rgb888>)
        .collect();
    Bands::new(layout, &mut strip, Some(&mut depth))
        .unwrap()
        .render(display, Rgb888::BLACK, &mut items)
}

/// A `DrawTarget` over a `Vec` (the mesh renderer's output for comparisons).
pub struct Pixels(pub Vec<Rgb888>, pub u32, pub u32);

impl embedded_graphics_core::geometry::OriginDimensions for Pixels {
    fn size(&self) -> embedded_graphics_core::geometry::Size {
        embedded_graphics_core::geometry::Size::new(self.1, self.2)
    }
}

impl embedded_graphics_core::draw_target::DrawTarget for Pixels {
    type Color = Rgb888;
    type Error = core::convert::Infallible;
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = embedded_graphics_core::Pixel<Rgb888>>,
    {
        for embedded_graphics_core::Pixel(p, c) in pixels {
            if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.1 && (p.y as u32) < self.2 {
                self.0[(p.y as u32 * self.1 + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

/// The mesh renderer's image of a scene in tier `S`.
pub fn render_mesh_pixels<S: Scalar>(scene: &Scene) -> Vec<Rgb888> {
    let mut p = Pixels(
        vec![Rgb888::BLACK; (scene.width * scene.height) as usize],
        scene.width,
        scene.height,
    );
    let Ok(()) = render_mesh::<S, _>(scene, &mut p);
    p.0
}

/// The mesh renderer against the reference: the error on pixels both cover,
/// and how many pixels only one of them covers (silhouette pixels: the
/// renderer's vertices are rounded from its fixed-point transform, the
/// reference's from `f32`).
pub fn compare_mesh(mesh: &[Rgb888], reference: &[Option<V3>]) -> (u32, f64, usize, usize) {
    let (mut max, mut sum, mut n, mut only) = (0u32, 0u64, 0usize, 0usize);
    for (t, r) in mesh.iter().zip(reference) {
        match r {
            Some(r) if *t != Rgb888::BLACK => {
                let want = [q(r[0], 255.0), q(r[1], 255.0), q(r[2], 255.0)];
                let got = [t.r() as u32, t.g() as u32, t.b() as u32];
                let e = (0..3).map(|c| got[c].abs_diff(want[c])).max().unwrap();
                max = max.max(e);
                sum += u64::from(e);
                n += 1;
            }
            Some(r) if want_black(r) => {}
            None if *t == Rgb888::BLACK => {}
            _ => only += 1,
        }
    }
    (max, sum as f64 / n.max(1) as f64, n, only)
}

fn want_black(r: &V3) -> bool {
    r.iter().all(|c| q(*c, 255.0) == 0)
}
