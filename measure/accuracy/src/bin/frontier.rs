//! The trade as users make it (issue 19): every configuration of the standard
//! scene (`measure/frame/src/lib.rs`: flat, lambert_gouraud,
//! lambert_gouraud_refine, blinn_gouraud, blinn_phong, blinn_phong_inc and the
//! `f32` tier's lambert_gouraud_f32, blinn_gouraud_f32, blinn_phong_f32,
//! flat_f32) rendered on the host as one whole 240 × 240 `Rgb565` frame, and
//! compared with the *exact image*: the same scene lit per pixel in `f64` by
//! [`fixshade_testkit::reference`] at pixel centres (Blinn-Phong for the Blinn
//! configurations, the Lambert model for the Lambert ones), rounded to the
//! nearest 5-6-5 colour as the `Linear` encoder does.
//!
//! The exact image of a mesh: at each pixel centre inside a front-facing
//! triangle's projection, the triangle's vertex normals interpolated at that
//! point and normalised (the per-pixel limit of every shading method on this
//! mesh). The error of a pixel is its worst channel's difference from the
//! exact image in 8-bit LSBs (one 5-bit step = 255/31 ≈ 8.23 LSB, one 6-bit
//! step = 255/63 ≈ 4.05 LSB): the shading method's error and the tier's
//! together. Statistics over the pixels both cover (max, mean, 99th
//! percentile); pixels only one covers are counted apart.
//!
//! Two meshes: the standard sphere (`fixshade::standard::SPHERE`, 16 × 24) —
//! its frames' checksums are printed, and `measure/frontier.py` checks them
//! against `measure/out/frame.json` — and a coarse UV sphere (6 stacks × 8
//! slices) with the same camera, light and material, whose highlight falls
//! inside a triangle, far from every vertex.
//!
//! ```sh
//! cargo run --release -p fixshade-accuracy --bin frontier            # writes measure/out/frontier_error.json
//! cargo run --release -p fixshade-accuracy --bin frontier -- --no-write   # prints it only
//! ```
//! (`python3 measure/frontier.py` runs it and joins the costs of frame.json.)

use fixshade::camera::{Camera, FixedCamera, MeshTransform, Orthographic, Pose};
use fixshade::error::RenderError;
use fixshade::lighting::{LightDesc, LightKind};
use fixshade::mesh::uv_sphere_counts;
use fixshade::prelude::*;
use fixshade::render::refine::{Refine, RefineBuffers};
use fixshade::render::{CachedVertex, DrawOptions, MeshMemory};
use fixshade::shade::{Kernel, PhongShading};
use fixshade::standard;
use fixshade_testkit::reference::{ModelDesc, Reference, ViewerDesc};
use serde_json::{json, Map, Value};

const W: usize = standard::SIZE as usize;

/// The coarse sphere: 6 stacks × 8 slices (42 vertices, 80 triangles).
const COARSE_SIZE: (usize, usize) = (6, 8);
const COARSE_COUNTS: (usize, usize) = uv_sphere_counts(COARSE_SIZE.0, COARSE_SIZE.1);
static COARSE: MeshData<{ COARSE_COUNTS.0 }, { COARSE_COUNTS.1 }> =
    MeshData::uv_sphere(COARSE_SIZE.0, COARSE_SIZE.1, 14);

/// Silhouette refinement's budget, as `measure/frame`'s `_refine` configuration.
const REFINE_V: usize = 192;
const REFINE_T: usize = 4 * REFINE_V;

/// One rendered frame: colours, and which pixels a triangle covered.
struct Frame {
    color: Vec<Rgb565>,
    covered: Vec<bool>,
    checksum: u32,
}

fn finish(
    draw: &mut MeshDraw<'_, impl Kernel<Color = Rgb565>>,
    color: &mut [Rgb565],
    depth: &mut [u16],
) -> Result<u32, RenderError> {
    let mut frame = FullFrame::new(W as u32, W as u32, color, Some(depth))?;
    frame.render(Rgb565::BLACK, &mut [draw])?;
    let mut sum = Checksum::<Rgb565>::new(Size::new(W as u32, W as u32));
    let Ok(()) = frame.flush(&mut sum);
    Ok(sum.value())
}

/// Renders `mesh` with `kernel` as a whole frame (with silhouette refinement
/// when `refine`), as `measure/frame`'s `draw_full` / `draw_full_refine`.
fn render<K: Kernel<Color = Rgb565>, const NV: usize>(
    mesh: Mesh<'static>,
    t: &MeshTransform<Orthographic>,
    kernel: K,
    refine: bool,
) -> Frame
where
    K::Vertex: fixshade::num::Zeroed,
{
    let nt = mesh.triangle_count();
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); NV];
    let mut bins = vec![0u16; bins_len(nt, 1)];
    let mut color = vec![Rgb565::BLACK; W * W];
    let mut depth = vec![0u16; W * W];
    let layout = Layout::full(W as u32, W as u32).expect("layout");
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut [],
    };
    let mut store = Box::new(RefineBuffers::<K::Vertex, NV, REFINE_V, REFINE_T>::new());
    let checksum = if refine {
        let r = Refine {
            memory: store.memory(),
            threshold: 0,
        };
        let mut draw = MeshDraw::new(
            layout,
            mesh,
            t,
            kernel,
            memory,
            DrawOptions::default().with_refine(r),
        )
        .expect("draw");
        finish(&mut draw, &mut color, &mut depth)
    } else {
        let mut draw =
            MeshDraw::new(layout, mesh, t, kernel, memory, DrawOptions::default()).expect("draw");
        finish(&mut draw, &mut color, &mut depth)
    }
    .expect("frame");
    let covered = depth.iter().map(|&d| d != u16::MAX).collect();
    Frame {
        color,
        covered,
        checksum,
    }
}

/// Every configuration of `measure/frame` on `mesh` (`NV` vertices), in
/// frame.json's names and order.
fn configs<const NV: usize>(
    mesh: Mesh<'static>,
    t: &MeshTransform<Orthographic>,
) -> Result<Vec<(&'static str, bool, Frame)>, ParamError> {
    let lq = standard::lambert::<Q14>()?;
    let bq = standard::blinn::<Q14>()?;
    let lf = standard::lambert::<f32>()?;
    let bf = standard::blinn::<f32>()?;
    // blinn_phong_inc's lighting: the light in an array (measure/frame's inc_lighting)
    let inc = Lighting::<Q14, [DirectionalLight<Q14>; 1], BlinnPhong>::new(
        [standard::light()?],
        Material::new(&standard::material())?,
    )
    .with_global_ambient_f32([0.0; 3])
    .eye_space();
    // (name, Blinn-Phong model?, frame)
    Ok(vec![
        (
            "lambert_gouraud",
            false,
            render::<_, NV>(mesh, t, Shader::new(GouraudShading, &lq, Linear), false),
        ),
        (
            "blinn_gouraud",
            true,
            render::<_, NV>(mesh, t, Shader::new(GouraudShading, &bq, Linear), false),
        ),
        (
            "blinn_phong",
            true,
            render::<_, NV>(mesh, t, Shader::new(PhongShading, &bq, Linear), false),
        ),
        (
            "blinn_phong_inc",
            true,
            render::<_, NV>(
                mesh,
                t,
                Shader::new(IncrementalPhongShading, &inc, Linear),
                false,
            ),
        ),
        (
            "flat",
            false,
            render::<_, NV>(mesh, t, Shader::new(FlatShading, &lq, Linear), false),
        ),
        (
            "lambert_gouraud_refine",
            false,
            render::<_, NV>(mesh, t, Shader::new(GouraudShading, &lq, Linear), true),
        ),
        (
            "lambert_gouraud_f32",
            false,
            render::<_, NV>(mesh, t, Shader::new(GouraudShading, &lf, Linear), false),
        ),
        (
            "blinn_gouraud_f32",
            true,
            render::<_, NV>(mesh, t, Shader::new(GouraudShading, &bf, Linear), false),
        ),
        (
            "blinn_phong_f32",
            true,
            render::<_, NV>(mesh, t, Shader::new(PhongShading, &bf, Linear), false),
        ),
        (
            "flat_f32",
            false,
            render::<_, NV>(mesh, t, Shader::new(FlatShading, &lf, Linear), false),
        ),
    ])
}

/// The exact image of `mesh` under `r`: per pixel centre, the 5-6-5 channels
/// (unrounded, in steps) of the reference colour, or `None` off the mesh.
fn exact(
    mesh: &Mesh<'_>,
    camera: &Camera<Orthographic>,
    r: &Reference<'_>,
) -> Vec<Option<[f64; 3]>> {
    let mvp = camera.projection().mul(camera.view());
    let m = mvp.m.map(|row| row.map(f64::from));
    let vp = camera.viewport();
    let (w, h) = (f64::from(vp.width()), f64::from(vp.height()));
    let (x0, y0) = (f64::from(vp.x0()), f64::from(vp.y0()));
    // orthographic (w_c = 1): pixel coordinates of a model point
    let screen = |p: [f64; 3]| {
        let c = |i: usize| m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3];
        [x0 + 0.5 * w * (1.0 + c(0)), y0 + 0.5 * h * (1.0 - c(1))]
    };
    let f = |a: [f32; 3]| a.map(f64::from);
    let mut out = vec![None; W * W];
    for tri in mesh.triangles() {
        let i = tri.map(usize::from);
        let p = i.map(|k| f(mesh.position(k).expect("index")));
        let n = i.map(|k| f(mesh.normal(k).expect("index")));
        // front-facing in eye space (the view is a translation; viewer at +z)
        let (e1, e2) = (sub(p[1], p[0]), sub(p[2], p[0]));
        if e1[0] * e2[1] - e1[1] * e2[0] <= 0.0 {
            continue;
        }
        let s = p.map(screen);
        let area =
            (s[1][0] - s[0][0]) * (s[2][1] - s[0][1]) - (s[2][0] - s[0][0]) * (s[1][1] - s[0][1]);
        let lo = |k: usize| s.iter().map(|v| v[k]).fold(f64::INFINITY, f64::min);
        let hi = |k: usize| s.iter().map(|v| v[k]).fold(f64::NEG_INFINITY, f64::max);
        let (xa, xb) = (
            lo(0).floor().max(0.0) as usize,
            (hi(0).ceil() as usize).min(W),
        );
        let (ya, yb) = (
            lo(1).floor().max(0.0) as usize,
            (hi(1).ceil() as usize).min(W),
        );
        for y in ya..yb {
            for x in xa..xb {
                if out[y * W + x].is_some() {
                    continue;
                }
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let edge = |a: [f64; 2], b: [f64; 2]| {
                    ((b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1])) / area
                };
                // barycentric weights of vertices 0, 1, 2
                let b = [edge(s[1], s[2]), edge(s[2], s[0]), edge(s[0], s[1])];
                if b.iter().any(|&v| v < 0.0) {
                    continue;
                }
                let lerp = |v: [[f64; 3]; 3]| {
                    core::array::from_fn(|k| b[0] * v[0][k] + b[1] * v[1][k] + b[2] * v[2][k])
                };
                let c = r.shade(lerp(p), lerp(n));
                out[y * W + x] = Some(core::array::from_fn(|k| {
                    c[k].clamp(0.0, 1.0) * if k == 1 { 63.0 } else { 31.0 }
                }));
            }
        }
    }
    out
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Worst-channel error of `got` against the exact channels `want`, in 8-bit
/// LSBs, `want` rounded to the nearest 5-6-5 colour first.
fn error(got: Rgb565, want: [f64; 3]) -> f64 {
    let g = [got.r(), got.g(), got.b()].map(f64::from);
    (0..3)
        .map(|k| {
            let max = if k == 1 { 63.0 } else { 31.0 };
            (g[k] - want[k].round()).abs() * 255.0 / max
        })
        .fold(0.0, f64::max)
}

fn r3(x: f64) -> Value {
    json!((x * 1000.0).round() / 1000.0)
}

/// max / mean / p99 and coverage of `frame` against `want`.
fn stats(frame: &Frame, want: &[Option<[f64; 3]>]) -> Value {
    let mut e = Vec::new();
    let (mut only_frame, mut only_exact) = (0, 0);
    for (i, w) in want.iter().enumerate() {
        match (frame.covered[i], w) {
            (true, Some(w)) => e.push(error(frame.color[i], *w)),
            (true, None) => only_frame += 1,
            (false, Some(_)) => only_exact += 1,
            (false, None) => {}
        }
    }
    e.sort_by(f64::total_cmp);
    let n = e.len();
    // nearest rank
    let p99 = e[(n * 99).div_ceil(100) - 1];
    let mean = e.iter().sum::<f64>() / n as f64;
    let exact_px = e.iter().filter(|&&v| v == 0.0).count();
    json!({
        "max": r3(e[n - 1]),
        "mean": r3(mean),
        "p99": r3(p99),
        "pixels": n,
        "exact_pixels": exact_px,
        "only_frame": only_frame,
        "only_exact": only_exact,
    })
}

fn light() -> LightDesc {
    // standard::light: white, towards (1, 1, 1), ambient = diffuse = specular = 1
    LightDesc {
        kind: LightKind::Directional {
            towards_light: [1.0; 3],
        },
        ambient: [1.0; 3],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    }
}

fn scene<const NV: usize>(
    name: &str,
    mesh: Mesh<'static>,
    camera: &Camera<Orthographic>,
    t: &MeshTransform<Orthographic>,
) -> Result<Value, ParamError> {
    let lights = [light()];
    let reference = |model| Reference {
        lights: &lights,
        material: standard::material(),
        global_ambient: [0.0; 3],
        viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
        fog: None,
        model,
    };
    let blinn = exact(&mesh, camera, &reference(ModelDesc::of::<BlinnPhong>()));
    let lambert = exact(&mesh, camera, &reference(ModelDesc::of::<Lambert>()));
    // the highlight's nearest vertex: (N·H)^32 there says what Gouraud can see
    let h = fixshade_testkit::reference::normalize([
        1.0 / 3f64.sqrt(),
        1.0 / 3f64.sqrt(),
        1.0 + 1.0 / 3f64.sqrt(),
    ]);
    let best = (0..mesh.vertex_count())
        .filter_map(|i| mesh.normal(i))
        .map(|n| {
            let n = fixshade_testkit::reference::normalize(n.map(f64::from));
            n[0] * h[0] + n[1] * h[1] + n[2] * h[2]
        })
        .fold(f64::NEG_INFINITY, f64::max);
    let mut configs_out = Map::new();
    for (config, is_blinn, frame) in configs::<NV>(mesh, t)? {
        let own = if is_blinn { &blinn } else { &lambert };
        let mut v = json!({
            "model": if is_blinn { "blinn_phong" } else { "lambert" },
            "checksum": format!("{:#010x}", frame.checksum),
            "error": stats(&frame, own),
        });
        if !is_blinn {
            // what dropping the highlight costs: against the Blinn-Phong image
            v["error_vs_blinn_phong"] = stats(&frame, &blinn);
        }
        configs_out.insert(config.into(), v);
    }
    Ok(json!({
        "mesh": name,
        "vertices": mesh.vertex_count(),
        "triangles": mesh.triangle_count(),
        "exact_pixels_covered": blinn.iter().filter(|p| p.is_some()).count(),
        "highlight_nearest_vertex_nh": r3(best),
        "highlight_nearest_vertex_specular": r3(best.powi(32)),
        "configs": configs_out,
    }))
}

fn main() -> Result<(), ParamError> {
    let camera = standard::camera()?;
    // the transform the measured frames use: built in integers from the camera
    let fixed = FixedCamera::new(&camera)?;
    let t = standard::fixed_transform(&fixed)?;
    let tc = fixed.mesh_transform(&Pose::IDENTITY, COARSE.frac)?;
    let out = json!({
        "about": "error of each configuration's host frame against the exact image (per-pixel f64 reference at pixel centres, rounded to 5-6-5), worst channel in 8-bit LSB; measure/accuracy/src/bin/frontier.rs",
        "standard": scene::<{ standard::COUNTS.0 }>(
            "standard sphere 16x24",
            standard::SPHERE.mesh(),
            &camera,
            &t
        )?,
        "coarse": scene::<{ COARSE_COUNTS.0 }>(
            &format!("uv sphere {}x{}", COARSE_SIZE.0, COARSE_SIZE.1),
            COARSE.mesh(),
            &camera,
            &tc
        )?,
    });
    let text = serde_json::to_string_pretty(&out).expect("json") + "\n";
    print!("{text}");
    if !std::env::args().any(|a| a == "--no-write") {
        // measure/out/ beside this package (measure/accuracy/)
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../out/frontier_error.json");
        std::fs::write(&path, &text).expect("write frontier_error.json");
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
