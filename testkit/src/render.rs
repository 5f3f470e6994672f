//! The reference scenes of the source documents (DESIGN §1), rendered by a tier
//! through the real pipeline (mesh → vertex stage → bins → set-up → kernel →
//! framebuffer: one [`MeshDraw`] per object, as firmware draws) and by the f64
//! reference model on exactly the same pixel coverage.
//!
//! Each object is a run-time [`Mesh`] (`i16` positions, Q14 normals) with its
//! own model matrix, seen by an orthographic camera of 100 pixels per eye-space
//! unit. The reference takes the inputs the renderer's kernels receive — the
//! screen positions, eye-space normals (Q14) and eye-space positions (Q16.16)
//! of the mesh transform, converted to `f64` exactly — and does everything
//! after them in `f64`: barycentric interpolation at the pixel centres of the
//! analytic triangle, normalisation, lighting. Quantising the input (the mesh
//! format and the fixed-point transform) is therefore not counted as the
//! tier's error; the interpolation, renormalisation, lighting and encoding are.
//! Coverage (which pixel centres a triangle covers, culling, the depth test)
//! comes from the pipeline's own set-up: the reference is drawn by a
//! `MeshDraw` of the same mesh with a kernel of this file.
//!
//! Used by the golden and incremental-Phong tests, `examples/showcase.rs` and
//! `benches/tradeoff.rs`.

#![allow(dead_code)]

use crate::reference::{normalize, ModelDesc, Reference, ViewerDesc, V3};
use core::cell::RefCell;
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use fixshade::camera::{Camera, Clip, ClipSpace, MeshTransform, Orthographic, Viewport};
use fixshade::color::Linear;
use fixshade::color::{OutputColor, Rgb};
use fixshade::error::RenderError;
use fixshade::framebuffer::{BandView, Bands, DrawBand, FullFrame, Layout};
use fixshade::lighting::{AmbientSource, AnyLight, LightDesc, LightKind, Material, MaterialDesc};
use fixshade::lighting::{BlinnPhong, Lambert, Lighting, Phong as PhongSpec, Terms, Viewed};
use fixshade::mesh::{uv_sphere_counts, Mesh, MeshData};
use fixshade::num::Mat4;
use fixshade::num::Scalar;
use fixshade::raster::Cull;
use fixshade::render::{
    bins_len, draw_triangle, CachedVertex, Carry, Corner, DrawOptions, MeshDraw, MeshMemory,
};
use fixshade::shade::{FlatShading, GouraudShading, Kernel, PhongShading, Shader, VertexIn};

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

// ------------------------------------------------------------------ objects as meshes

/// Fraction bits of the big triangles' positions (eye units).
const MESH_FRAC: u8 = 10;

/// The unit sphere of the showcase spheres (scaled and moved by each object's
/// model matrix).
static UNIT_SPHERE: MeshData<
    { uv_sphere_counts(STACKS, SLICES).0 },
    { uv_sphere_counts(STACKS, SLICES).1 },
> = MeshData::uv_sphere(STACKS, SLICES, 14);

/// An object's mesh (owned arrays) and model matrix.
pub struct ObjectMesh {
    pub positions: Vec<[i16; 3]>,
    pub normals: Vec<[i16; 3]>,
    pub triangles: Vec<[u16; 3]>,
    pub frac: u8,
    pub model: Mat4,
}

impl ObjectMesh {
    pub fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.positions, &self.normals, &self.triangles, self.frac).expect("a valid mesh")
    }
}

/// Eye-space position of a pixel position (the scene plane at z = −5).
fn eye(p: [f32; 2]) -> [f32; 3] {
    [p[0] / PIXELS_PER_UNIT, -p[1] / PIXELS_PER_UNIT, -5.0]
}

/// The mesh of an object: a sphere is the unit UV sphere scaled and moved by
/// its model matrix; a triangle has its corners (eye units, [`MESH_FRAC`]
/// bits) and normals (Q14, normalised) in the mesh, model matrix the identity.
pub fn object_mesh(obj: &Object) -> ObjectMesh {
    match obj.shape {
        Shape::Sphere { centre, radius } => ObjectMesh {
            positions: UNIT_SPHERE.positions.to_vec(),
            normals: UNIT_SPHERE.normals.to_vec(),
            triangles: UNIT_SPHERE.triangles.to_vec(),
            frac: UNIT_SPHERE.frac,
            model: Mat4::translate(eye(centre)).mul(&Mat4::scale([radius / PIXELS_PER_UNIT; 3])),
        },
        Shape::Triangle { corners, normals } => {
            let q = |v: f64, f: u8| (v * f64::from(1u16 << f)).round() as i16;
            ObjectMesh {
                positions: corners
                    .iter()
                    .map(|c| eye(*c).map(|v| q(f64::from(v), MESH_FRAC)))
                    .collect(),
                normals: normals
                    .iter()
                    .map(|n| normalize(n.map(f64::from)).map(|v| q(v, 14)))
                    .collect(),
                triangles: vec![[0, 1, 2]],
                frac: MESH_FRAC,
                model: Mat4::IDENTITY,
            }
        }
    }
}

/// The orthographic camera of a scene: 100 pixels per eye unit, the eye-space
/// origin at the top-left corner, depth 0 at z = −1 to 65535 at z = −20.
pub fn camera(scene: &Scene) -> Camera<Orthographic> {
    let (w, h) = (scene.width, scene.height);
    Camera::orthographic(
        0.0,
        w as f32 / PIXELS_PER_UNIT,
        -(h as f32) / PIXELS_PER_UNIT,
        0.0,
        1.0,
        20.0,
        Viewport::new(0, 0, w, h).unwrap(),
    )
    .unwrap()
}

/// The fixed-point transform of an object's mesh.
pub fn transform(scene: &Scene, m: &ObjectMesh) -> MeshTransform<Orthographic> {
    camera(scene).mesh_transform(&m.model, m.frac).unwrap()
}

/// One vertex as the pipeline's kernels receive it from the vertex stage:
/// clip coordinates (screen space: sub-pixels, depth, `w = 1`), the eye-space
/// normal (Q14, as transformed: not normalised) and the eye-space position
/// (Q16.16).
#[derive(Clone, Copy, Debug)]
pub struct Vert {
    pub clip: Clip,
    pub normal: [i32; 3],
    pub eye: [i32; 3],
}

impl Vert {
    /// The vertex of a mesh position and normal under a transform.
    pub fn of(t: &MeshTransform<Orthographic>, p: [i16; 3], n: [i16; 3]) -> Vert {
        Vert {
            clip: t.clip(p),
            normal: t.normal(n),
            eye: t.eye(p),
        }
    }
    /// The corner for [`draw_triangle`] in [`ClipSpace::SCREEN`].
    pub fn corner(&self) -> Corner {
        Corner {
            clip: self.clip,
            vertex: VertexIn::new(self.normal, self.eye),
        }
    }
    /// Screen position in pixels.
    pub fn screen(&self) -> [f64; 2] {
        let sub = f64::from(1u32 << fixshade::camera::SUBPIXEL_BITS);
        [f64::from(self.clip.x) / sub, f64::from(self.clip.y) / sub]
    }
    /// The normal in f64 (exactly the Q14 value).
    pub fn normal_f64(&self) -> V3 {
        self.normal.map(|c| f64::from(c) / 16384.0)
    }
    /// The eye-space position in f64 (exactly the Q16.16 value).
    pub fn eye_f64(&self) -> V3 {
        self.eye.map(|c| f64::from(c) / 65536.0)
    }
}

/// The triangles of an object as the vertex stage hands them on (the same
/// corners `MeshDraw` draws: `draw_triangle` with them gives its pixels bit for
/// bit).
pub fn triangles(scene: &Scene, obj: &Object) -> Vec<[Vert; 3]> {
    let m = object_mesh(obj);
    let t = transform(scene, &m);
    m.triangles
        .iter()
        .map(|tri| {
            tri.map(|i| {
                let i = usize::from(i);
                Vert::of(&t, m.positions[i], m.normals[i])
            })
        })
        .collect()
}

/// The triangles of every object of a scene.
pub fn prepare(scene: &Scene) -> Vec<Vec<[Vert; 3]>> {
    scene.objects.iter().map(|o| triangles(scene, o)).collect()
}

// ------------------------------------------------------------------ rendering

/// The lightings of a scene's objects in tier `S`, one list per model type
/// (the shaders borrow them).
struct Lightings<S: Scalar> {
    lam: Vec<SceneLighting<S, Lambert>>,
    bri: Vec<SceneLighting<S, Terms<0, true, false, false>>>,
    pho: Vec<SceneLighting<S, PhongSpec>>,
    bli: Vec<SceneLighting<S, BlinnPhong>>,
}

/// A scene object's lighting: up to 4 lights of any kind, seen from the eye.
type SceneLighting<S, M> = Viewed<Lighting<S, heapless::Vec<AnyLight<S>, 4>, M>>;

impl<S: Scalar> Lightings<S> {
    fn new(scene: &Scene) -> Self {
        let lights: heapless::Vec<AnyLight<S>, 4> = scene
            .lights
            .iter()
            .map(|d| AnyLight::new(d).unwrap())
            .collect();
        let g = Rgb::<S>::from_f32(scene.global_ambient);
        let mut l = Lightings {
            lam: vec![],
            bri: vec![],
            pho: vec![],
            bli: vec![],
        };
        for o in &scene.objects {
            let m = Material::<S>::new(&o.material).unwrap();
            let ls = lights.clone();
            match o.terms {
                Terms4::Lambert => l
                    .lam
                    .push(Lighting::new(ls, m).with_global_ambient(g).eye_space()),
                Terms4::Brilliance => l
                    .bri
                    .push(Lighting::new(ls, m).with_global_ambient(g).eye_space()),
                Terms4::Phong => l
                    .pho
                    .push(Lighting::new(ls, m).with_global_ambient(g).eye_space()),
                Terms4::Blinn => l
                    .bli
                    .push(Lighting::new(ls, m).with_global_ambient(g).eye_space()),
            }
        }
        l
    }
}

/// The memory of one object's `MeshDraw` (vertex caches of both payload types
/// the harness's kernels use).
#[derive(Default)]
pub struct ObjectMemory {
    cu: Vec<CachedVertex<[u16; 3]>>,
    ci: Vec<CachedVertex<[i16; 3]>>,
    bins: Vec<u16>,
    carry: Vec<Carry>,
}

impl ObjectMemory {
    fn new(m: &ObjectMesh, layout: &Layout) -> Self {
        let (nv, nt) = (m.positions.len(), m.triangles.len());
        ObjectMemory {
            cu: vec![CachedVertex::default(); nv],
            ci: vec![CachedVertex::default(); nv],
            bins: vec![0; bins_len(nt, layout.bands() as usize)],
            carry: vec![Carry::default(); 2 * nt],
        }
    }
}

/// The memory for a kernel with vertex payload `V`.
pub trait MemoryFor<V> {
    fn memory(&mut self) -> MeshMemory<'_, V>;
}

impl MemoryFor<[u16; 3]> for ObjectMemory {
    fn memory(&mut self) -> MeshMemory<'_, [u16; 3]> {
        MeshMemory {
            vertices: &mut self.cu,
            bins: &mut self.bins,
            carry: &mut self.carry,
        }
    }
}

impl MemoryFor<[i16; 3]> for ObjectMemory {
    fn memory(&mut self) -> MeshMemory<'_, [i16; 3]> {
        MeshMemory {
            vertices: &mut self.ci,
            bins: &mut self.bins,
            carry: &mut self.carry,
        }
    }
}

/// An object's `MeshDraw` with kernel `k` (back faces culled).
fn mesh_item<'a, K: Kernel + 'a>(
    layout: Layout,
    mesh: Mesh<'a>,
    t: &MeshTransform<Orthographic>,
    k: K,
    mem: &'a mut ObjectMemory,
) -> Box<dyn DrawBand<K::Color> + 'a>
where
    ObjectMemory: MemoryFor<K::Vertex>,
{
    Box::new(
        MeshDraw::new(layout, mesh, t, k, mem.memory(), DrawOptions::default())
            .expect("buffers sized for the mesh"),
    )
}

/// The kernel of a mode (`PhongShading` for Phong: the per-pixel
/// kernel of every tier and light set) lighting with `$lit`, bound to `$k` in
/// `$body`.
macro_rules! with_kernel {
    ($mode:expr, $lit:expr, |$k:ident| $body:expr) => {
        match $mode {
            Mode::Flat => {
                let $k = Shader::new(FlatShading, $lit, Linear);
                $body
            }
            Mode::Gouraud => {
                let $k = Shader::new(GouraudShading, $lit, Linear);
                $body
            }
            Mode::Phong => {
                let $k = Shader::new(PhongShading, $lit, Linear);
                $body
            }
        }
    };
}

/// Builds one `MeshDraw` per object of `scene` in tier `S` and colour `C` for
/// a frame of `layout` (the vertex stage and the bins: the per-frame geometry
/// work) and hands them to `f`, which may render them any number of times.
pub fn with_draws<S: Scalar, C: OutputColor + core::fmt::Debug, R>(
    scene: &Scene,
    layout: Layout,
    f: impl FnOnce(&mut [&mut dyn DrawBand<C>]) -> R,
) -> R {
    let meshes: Vec<ObjectMesh> = scene.objects.iter().map(object_mesh).collect();
    let lit = Lightings::<S>::new(scene);
    let mut mem: Vec<ObjectMemory> = meshes
        .iter()
        .map(|m| ObjectMemory::new(m, &layout))
        .collect();
    let (mut il, mut ib, mut ip, mut iq) = (
        lit.lam.iter(),
        lit.bri.iter(),
        lit.pho.iter(),
        lit.bli.iter(),
    );
    let mut draws: Vec<Box<dyn DrawBand<C> + '_>> = Vec::new();
    for ((o, m), mem) in scene.objects.iter().zip(&meshes).zip(mem.iter_mut()) {
        let t = transform(scene, m);
        let mesh = m.mesh();
        draws.push(match o.terms {
            Terms4::Lambert => {
                with_kernel!(o.mode, il.next().unwrap(), |k| mesh_item(
                    layout, mesh, &t, k, mem
                ))
            }
            Terms4::Brilliance => {
                with_kernel!(o.mode, ib.next().unwrap(), |k| mesh_item(
                    layout, mesh, &t, k, mem
                ))
            }
            Terms4::Phong => {
                with_kernel!(o.mode, ip.next().unwrap(), |k| mesh_item(
                    layout, mesh, &t, k, mem
                ))
            }
            Terms4::Blinn => {
                with_kernel!(o.mode, iq.next().unwrap(), |k| mesh_item(
                    layout, mesh, &t, k, mem
                ))
            }
        });
    }
    let mut items: Vec<&mut dyn DrawBand<C>> = draws
        .iter_mut()
        .map(|d| &mut **d as &mut dyn DrawBand<C>)
        .collect();
    f(&mut items)
}

/// Renders a scene with tier `S` into colour type `C` (black background, the
/// whole frame in memory).
pub fn render_tier<S: Scalar, C: OutputColor + core::fmt::Debug>(scene: &Scene) -> Vec<C> {
    let (w, h) = (scene.width, scene.height);
    let black = C::from_channels([0; 3]);
    let mut pixels = vec![black; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    with_draws::<S, C, _>(scene, Layout::full(w, h).unwrap(), |items| {
        FullFrame::new(w, h, &mut pixels, Some(&mut depth))
            .unwrap()
            .render(black, items)
            .expect("every item prepared for this layout")
    });
    pixels
}

/// Renders a scene with the mesh renderer in tier `S` as firmware drives a
/// display: 8-row bands (colour and depth strips) flushed to `display`.
pub fn render_mesh<S: Scalar, D>(
    scene: &Scene,
    display: &mut D,
) -> Result<(), RenderError<D::Error>>
where
    D: embedded_graphics_core::draw_target::DrawTarget<Color = Rgb888>,
{
    const ROWS: u32 = 8;
    let (w, h) = (scene.width, scene.height);
    let layout = Layout::banded(w, h, ROWS).unwrap();
    let mut strip = vec![Rgb888::BLACK; (w * ROWS) as usize];
    let mut depth = vec![0u16; (w * ROWS) as usize];
    with_draws::<S, Rgb888, _>(scene, layout, |items| {
        Bands::new(layout, &mut strip, Some(&mut depth))
            .unwrap()
            .render(display, Rgb888::BLACK, items)
    })
}

/// A list of triangles drawn through the per-triangle front
/// ([`draw_triangle`], [`ClipSpace::SCREEN`], back faces culled).
pub struct Triangles<'a, K> {
    pub tris: &'a [[Vert; 3]],
    pub kernel: K,
}

impl<K: Kernel> DrawBand<K::Color> for Triangles<'_, K> {
    fn draw_band(&mut self, band: &mut BandView<'_, K::Color>) {
        for t in self.tris {
            draw_triangle(
                band,
                &ClipSpace::SCREEN,
                &self.kernel,
                &t.map(|v| v.corner()),
                Cull::Back,
            );
        }
    }
}

/// A [`Triangles`] item.
fn tri_item<'a, K: Kernel + 'a>(
    tris: &'a [[Vert; 3]],
    kernel: K,
) -> Box<dyn DrawBand<K::Color> + 'a> {
    Box::new(Triangles { tris, kernel })
}

/// Renders a scene with tier `S` into colour type `C` through the per-triangle
/// front: every object's triangles (see [`triangles`]) drawn with
/// [`draw_triangle`] from a `DrawBand` of this file, the whole frame in memory.
pub fn render_triangles<S: Scalar, C: OutputColor + core::fmt::Debug>(scene: &Scene) -> Vec<C> {
    let (w, h) = (scene.width, scene.height);
    let prepared = prepare(scene);
    let lit = Lightings::<S>::new(scene);
    let (mut il, mut ib, mut ip, mut iq) = (
        lit.lam.iter(),
        lit.bri.iter(),
        lit.pho.iter(),
        lit.bli.iter(),
    );
    let mut draws: Vec<Box<dyn DrawBand<C> + '_>> = Vec::new();
    for (o, tris) in scene.objects.iter().zip(&prepared) {
        draws.push(match o.terms {
            Terms4::Lambert => with_kernel!(o.mode, il.next().unwrap(), |k| tri_item(tris, k)),
            Terms4::Brilliance => with_kernel!(o.mode, ib.next().unwrap(), |k| tri_item(tris, k)),
            Terms4::Phong => with_kernel!(o.mode, ip.next().unwrap(), |k| tri_item(tris, k)),
            Terms4::Blinn => with_kernel!(o.mode, iq.next().unwrap(), |k| tri_item(tris, k)),
        });
    }
    let black = C::from_channels([0; 3]);
    let mut pixels = vec![black; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut items: Vec<&mut dyn DrawBand<C>> = draws
        .iter_mut()
        .map(|d| &mut **d as &mut dyn DrawBand<C>)
        .collect();
    FullFrame::new(w, h, &mut pixels, Some(&mut depth))
        .unwrap()
        .render(black, &mut items)
        .unwrap();
    drop(items);
    drop(draws);
    pixels
}

// ------------------------------------------------------------------ the f64 reference

/// The f64 data of a triangle: screen positions (pixels), eye-space positions
/// and normals, exactly the renderer's inputs.
#[derive(Clone, Copy, Debug, Default)]
struct RefTri {
    p: [[f64; 2]; 3],
    pos: [V3; 3],
    nrm: [V3; 3],
}

/// A kernel that shades the pixels the pipeline covers with the reference
/// model, from f64 barycentric coordinates of the analytic triangle at the
/// pixel centres (it interpolates nothing itself). Its mesh carries every
/// vertex's index as texture coordinates, so that [`Kernel::triangle`] finds
/// the vertex data of [`triangles`].
struct RefKernel<'a> {
    r: Reference<'a>,
    mode: Mode,
    verts: &'a [Vert],
    out: &'a RefCell<Vec<Option<V3>>>,
    width: u32,
}

impl Kernel for RefKernel<'_> {
    type Color = Rgb888;
    /// The vertex index.
    type Vertex = i32;
    type Varyings = [i32; 0];
    type Triangle = RefTri;
    const NEEDS_POSITION: bool = false;
    const NEEDS_TEXCOORD: bool = true;

    fn vertex(&self, v: &VertexIn) -> i32 {
        v.uv[0]
    }

    fn triangle(&self, v: [&i32; 3], _: &[[i32; 3]; 3]) -> (RefTri, [[i32; 0]; 3]) {
        let t = v.map(|&i| self.verts[i as usize]);
        let tri = RefTri {
            p: t.map(|v| v.screen()),
            pos: t.map(|v| v.eye_f64()),
            nrm: t.map(|v| v.normal_f64()),
        };
        (tri, [[]; 3])
    }

    fn span(&self, t: &RefTri, _: &[i32; 0], _: &[i32; 0], x: i32, y: i32, out: &mut [Rgb888]) {
        let RefTri { p, pos, nrm } = *t;
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        let lerp = |l: [f64; 3], a: [V3; 3]| -> V3 {
            [0, 1, 2].map(|c| l[0] * a[0][c] + l[1] * a[1][c] + l[2] * a[2][c])
        };
        let clamp = |c: V3| c.map(|x| x.clamp(0.0, 1.0));
        // flat: the normalised sum of the unit vertex normals, at the centroid
        let flat = || {
            let u = nrm.map(normalize);
            let n = normalize([0, 1, 2].map(|c| u[0][c] + u[1][c] + u[2][c]));
            let centroid = [0, 1, 2].map(|c| (pos[0][c] + pos[1][c] + pos[2][c]) / 3.0);
            self.r.shade(centroid, n)
        };
        // Gouraud: the vertex colours (clamped), interpolated
        let vertex_colours = || [0, 1, 2].map(|i| clamp(self.r.shade(pos[i], nrm[i])));
        let flat_c = (self.mode == Mode::Flat).then(flat);
        let vc = (self.mode == Mode::Gouraud).then(vertex_colours);
        let mut o = self.out.borrow_mut();
        for k in 0..out.len() {
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
            o[(y as u32 * self.width + (x as u32 + k as u32)) as usize] = Some(c);
        }
    }
}

/// The f64 reference image: linear RGB per covered pixel, `None` for
/// background. The coverage is the mesh renderer's: every object drawn by a
/// `MeshDraw` of the same mesh and transform (the whole frame, depth test on,
/// back faces culled) with the reference kernel.
pub fn render_reference(scene: &Scene) -> Vec<Option<V3>> {
    let (w, h) = (scene.width, scene.height);
    let layout = Layout::full(w, h).unwrap();
    let out = RefCell::new(vec![None; (w * h) as usize]);
    let meshes: Vec<ObjectMesh> = scene.objects.iter().map(object_mesh).collect();
    let verts: Vec<Vec<Vert>> = meshes
        .iter()
        .map(|m| {
            let t = transform(scene, m);
            m.positions
                .iter()
                .zip(&m.normals)
                .map(|(&p, &n)| Vert::of(&t, p, n))
                .collect()
        })
        .collect();
    let index: Vec<[i16; 2]> = (0..meshes.iter().map(|m| m.positions.len()).max().unwrap_or(0))
        .map(|i| [i as i16, 0])
        .collect();
    let mut caches: Vec<Vec<CachedVertex<i32>>> = meshes
        .iter()
        .map(|m| vec![CachedVertex::default(); m.positions.len()])
        .collect();
    let mut bins: Vec<Vec<u16>> = meshes
        .iter()
        .map(|m| vec![0; bins_len(m.triangles.len(), 1)])
        .collect();
    let mut draws = Vec::new();
    for (((obj, m), (vs, cache)), bins) in scene
        .objects
        .iter()
        .zip(&meshes)
        .zip(verts.iter().zip(caches.iter_mut()))
        .zip(bins.iter_mut())
    {
        let kernel = RefKernel {
            r: Reference {
                lights: &scene.lights,
                material: obj.material,
                global_ambient: scene.global_ambient,
                viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
                fog: None,
                model: match obj.terms {
                    Terms4::Lambert => ModelDesc::of::<Lambert>(),
                    Terms4::Brilliance => ModelDesc::of::<Terms<0, true, false, false>>(),
                    Terms4::Phong => ModelDesc::of::<PhongSpec>(),
                    Terms4::Blinn => ModelDesc::of::<BlinnPhong>(),
                },
            },
            mode: obj.mode,
            verts: vs,
            out: &out,
            width: w,
        };
        let mesh = m
            .mesh()
            .with_texcoords(&index[..m.positions.len()])
            .unwrap();
        let memory = MeshMemory {
            vertices: cache,
            bins,
            carry: &mut [],
        };
        draws.push(
            MeshDraw::new(
                layout,
                mesh,
                &transform(scene, m),
                kernel,
                memory,
                DrawOptions::default(),
            )
            .unwrap(),
        );
    }
    let mut dummy = vec![Rgb888::BLACK; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut items: Vec<&mut dyn DrawBand<Rgb888>> = draws
        .iter_mut()
        .map(|d| d as &mut dyn DrawBand<Rgb888>)
        .collect();
    FullFrame::new(w, h, &mut dummy, Some(&mut depth))
        .unwrap()
        .render(Rgb888::BLACK, &mut items)
        .unwrap();
    drop(items);
    drop(draws);
    out.into_inner()
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

/// The directional lights of a scene in `Q14<NW>`, if it has only directional
/// lights and every object a Lambert or Blinn-Phong material.
fn directional<const NW: u8>(
    scene: &Scene,
) -> Option<Vec<fixshade::lighting::DirectionalLight<fixshade::num::Q14<NW>>>> {
    use fixshade::lighting::{DirectionalLight, LightColors};
    if scene
        .objects
        .iter()
        .any(|o| !matches!(o.terms, Terms4::Lambert | Terms4::Blinn))
    {
        return None;
    }
    scene
        .lights
        .iter()
        .map(|d| match d.kind {
            LightKind::Directional { towards_light } => {
                LightColors::new(d.ambient, d.diffuse, d.specular)
                    .and_then(|c| DirectionalLight::new(towards_light, c))
                    .ok()
            }
            _ => None,
        })
        .collect()
}

/// Builds one `MeshDraw` per object with [`fixshade::shade::IncrementalPhongShading`]
/// in `Q14<NW>` (every object Phong-shaded, lit by the scene's `K` directional
/// lights as an array: `Lighting<Q14<NW>, [DirectionalLight<Q14<NW>>; K], M>`) for a frame of
/// `layout` and hands them to `f`; `None` unless the scene has one or two
/// directional lights only and Lambert or Blinn-Phong materials.
pub fn with_incremental_draws<const NW: u8, C: OutputColor, R>(
    scene: &Scene,
    layout: Layout,
    f: impl FnOnce(&mut [&mut dyn DrawBand<C>]) -> R,
) -> Option<R> {
    use fixshade::lighting::DirectionalLight;
    use fixshade::num::Q14;
    use fixshade::shade::IncrementalPhongShading as Inc;
    type L<const NW: u8, const K: usize, M> = Lighting<Q14<NW>, [DirectionalLight<Q14<NW>>; K], M>;
    let dirs = directional::<NW>(scene)?;
    if !(1..=2).contains(&dirs.len()) {
        return None;
    }
    let meshes: Vec<ObjectMesh> = scene.objects.iter().map(object_mesh).collect();
    let g = Rgb::from_f32(scene.global_ambient);
    let mat = |o: &Object| Material::new(&o.material).unwrap();
    let (mut l1, mut b1, mut l2, mut b2) = (vec![], vec![], vec![], vec![]);
    for o in &scene.objects {
        match (dirs.len(), o.terms) {
            (1, Terms4::Lambert) => l1.push(
                L::<NW, 1, Lambert>::new([dirs[0]], mat(o))
                    .with_global_ambient(g)
                    .eye_space(),
            ),
            (1, _) => b1.push(
                L::<NW, 1, BlinnPhong>::new([dirs[0]], mat(o))
                    .with_global_ambient(g)
                    .eye_space(),
            ),
            (_, Terms4::Lambert) => l2.push(
                L::<NW, 2, Lambert>::new([dirs[0], dirs[1]], mat(o))
                    .with_global_ambient(g)
                    .eye_space(),
            ),
            _ => b2.push(
                L::<NW, 2, BlinnPhong>::new([dirs[0], dirs[1]], mat(o))
                    .with_global_ambient(g)
                    .eye_space(),
            ),
        }
    }
    let mut mem: Vec<ObjectMemory> = meshes
        .iter()
        .map(|m| ObjectMemory::new(m, &layout))
        .collect();
    let (mut il1, mut ib1, mut il2, mut ib2) = (l1.iter(), b1.iter(), l2.iter(), b2.iter());
    let mut draws: Vec<Box<dyn DrawBand<C> + '_>> = Vec::new();
    for ((o, m), mem) in scene.objects.iter().zip(&meshes).zip(mem.iter_mut()) {
        let t = transform(scene, m);
        let mesh = m.mesh();
        draws.push(match (dirs.len(), o.terms) {
            (1, Terms4::Lambert) => mesh_item(
                layout,
                mesh,
                &t,
                Shader::new(Inc, il1.next().unwrap(), Linear),
                mem,
            ),
            (1, _) => mesh_item(
                layout,
                mesh,
                &t,
                Shader::new(Inc, ib1.next().unwrap(), Linear),
                mem,
            ),
            (_, Terms4::Lambert) => mesh_item(
                layout,
                mesh,
                &t,
                Shader::new(Inc, il2.next().unwrap(), Linear),
                mem,
            ),
            _ => mesh_item(
                layout,
                mesh,
                &t,
                Shader::new(Inc, ib2.next().unwrap(), Linear),
                mem,
            ),
        });
    }
    let mut items: Vec<&mut dyn DrawBand<C>> = draws
        .iter_mut()
        .map(|d| &mut **d as &mut dyn DrawBand<C>)
        .collect();
    Some(f(&mut items))
}

/// Renders a scene with [`fixshade::shade::IncrementalPhongShading`] in
/// `Q14<NW>` (see [`with_incremental_draws`]); `None` for an unsupported
/// scene.
pub fn render_incremental<const NW: u8, C: OutputColor>(scene: &Scene) -> Option<Vec<C>> {
    let (w, h) = (scene.width, scene.height);
    let black = C::from_channels([0; 3]);
    let mut pixels = vec![black; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    with_incremental_draws::<NW, C, _>(scene, Layout::full(w, h).unwrap(), |items| {
        FullFrame::new(w, h, &mut pixels, Some(&mut depth))
            .unwrap()
            .render(black, items)
            .unwrap()
    })?;
    Some(pixels)
}

/// The same scene with every object Phong-shaded (for the incremental comparison).
pub fn all_phong(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.objects.iter_mut().for_each(|o| o.mode = Mode::Phong);
    s
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
    render_mesh::<S, _>(scene, &mut p).expect("a display that cannot fail, items of its layout");
    p.0
}

/// The mesh renderer against the reference: the error on pixels both cover,
/// and how many pixels only one of them covers (the reference takes its
/// coverage from the same vertices and set-up: none, unless the renderer drew
/// a pixel black that the reference does not, or the reverse).
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
