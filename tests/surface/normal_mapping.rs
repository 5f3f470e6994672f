//! Normal mapping (`PhongShading.normal_mapped(…)`, `IncrementalPhongShading.normal_mapped(…)`):
//! a flat map shades exactly like the general per-pixel kernel
//! (`PhongShading`); the general path (every tier, light kind and
//! specular model) and the Q14 fast path against an f64 reference of the
//! same method (the same interpolation, evaluated in f64), worst cases
//! searched; the mesh renderer's kernels, and which kernel `PhongShading`
//! picks.
//!
//! Single triangles go through the pipeline's per-triangle front
//! (`render::draw_triangle` in `ClipSpace::SCREEN`, from a `DrawBand` of this
//! file) with the inputs the vertex stage hands a kernel: Q14 normals and
//! tangents, Q16.16 eye positions, Q12 texture coordinates. The references
//! read these quantised inputs back (quantising the input is not the kernel's
//! error); everything after them is `f64`.

#![allow(clippy::needless_range_loop)] // index loops over [_; 3] read as the formulas

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::camera::{Clip, ClipSpace};
use fixshade::color::OutputColor;
use fixshade::framebuffer::{BandView, DrawBand};
use fixshade::lighting::{AnyLight, LightDesc, LightKind};
use fixshade::lighting::{Illuminate, Model};
use fixshade::mesh::TEXCOORD_FRAC;
use fixshade::prelude::*;
use fixshade::render::{draw_triangle, Corner};
use fixshade::shade::{IncrementalPhongShading, PhongShading, VertexIn};
use fixshade::texture::{NormalMap, Wrap};
use fixshade_testkit::reference::{self, ModelDesc, Reference, ViewerDesc, V3};

const FB: u32 = 64;

// ---- f64 helpers ------------------------------------------------------------------

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V3) -> V3 {
    reference::normalize(a)
}
fn f64v(a: [f32; 3]) -> V3 {
    a.map(f64::from)
}
fn lerp3(b: [f64; 3], v: [V3; 3]) -> V3 {
    core::array::from_fn(|c| b[0] * v[0][c] + b[1] * v[1][c] + b[2] * v[2][c])
}

/// A deterministic generator.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32) / (1u64 << 24) as f32
    }
    fn range(&mut self, a: f32, b: f32) -> f32 {
        a + (b - a) * self.next()
    }
}

// ---- triangles ----------------------------------------------------------------------

/// A triangle: screen corners (pixels), eye positions, normals, tangents
/// `[t, w]`, texture coordinates.
#[derive(Clone, Copy, Debug)]
struct Tri {
    screen: [[f32; 2]; 3],
    pos: [[f32; 3]; 3],
    n: [[f32; 3]; 3],
    t: [[f32; 4]; 3],
    uv: [[f32; 2]; 3],
}

/// A random triangle on a unit sphere at (0, 0, −3): corners within `spread`
/// radians of a direction, tangents along the parallels (either handedness),
/// texture coordinates an affine map of up to three repeats.
fn random_tri(r: &mut Lcg, spread: f32) -> Tri {
    let screen = [
        [r.range(2.0, 30.0), r.range(2.0, 30.0)],
        [r.range(34.0, 62.0), r.range(2.0, 62.0)],
        [r.range(2.0, 62.0), r.range(34.0, 62.0)],
    ];
    let (th0, ph0) = (r.range(-1.2, 1.2), r.range(-1.2, 1.2));
    let w = if r.next() < 0.5 { -1.0 } else { 1.0 };
    let (su, sv, rot) = (r.range(0.3, 3.0), r.range(0.3, 3.0), r.range(0.0, 6.3));
    let mut t = Tri {
        screen,
        pos: [[0.0; 3]; 3],
        n: [[0.0; 3]; 3],
        t: [[0.0; 4]; 3],
        uv: [[0.0; 2]; 3],
    };
    for i in 0..3 {
        let th = th0 + r.range(-spread, spread);
        let ph = ph0 + r.range(-spread, spread);
        let n = [th.sin() * ph.cos(), ph.sin(), th.cos() * ph.cos()];
        t.n[i] = n;
        t.pos[i] = [n[0], n[1], n[2] - 3.0];
        t.t[i] = [th.cos(), 0.0, -th.sin(), w];
        let (x, y) = (screen[i][0] / 64.0, screen[i][1] / 64.0);
        t.uv[i] = [
            su * (x * rot.cos() - y * rot.sin()) + 0.37,
            sv * (x * rot.sin() + y * rot.cos()) - 0.21,
        ];
    }
    t
}

/// A unit vector (or any non-zero one) in Q14, rounded.
fn q14(v: [f32; 3]) -> [i32; 3] {
    let n = norm(f64v(v));
    n.map(|c| (c * 16384.0).round() as i32)
}

/// The corners the pipeline gets for a triangle: sub-pixel screen positions
/// (depth 0, `w = 1`), Q14 normals, Q16.16 eye positions, Q12 texture
/// coordinates and Q14 tangents with the handedness (±16384).
fn corners(t: &Tri) -> [Corner; 3] {
    let q = |c: f32| libm::roundf(c * (1 << SUBPIXEL_BITS) as f32) as i32;
    core::array::from_fn(|i| {
        let mut v = VertexIn::new(
            q14(t.n[i]),
            t.pos[i].map(|c| (f64::from(c) * 65536.0).round() as i32),
        );
        v.uv = t.uv[i].map(|c| (f64::from(c) * f64::from(1u32 << TEXCOORD_FRAC)).round() as i32);
        let tg = q14([t.t[i][0], t.t[i][1], t.t[i][2]]);
        v.tangent = [
            tg[0],
            tg[1],
            tg[2],
            if t.t[i][3] < 0.0 { -16384 } else { 16384 },
        ];
        Corner {
            clip: Clip {
                x: q(t.screen[i][0]),
                y: q(t.screen[i][1]),
                z: 0,
                w: 1,
            },
            vertex: v,
        }
    })
}

/// The quantised inputs of a triangle read back in f64: normals, tangents
/// (Q14), the handedness, eye positions (Q16.16), texture coordinates (Q12).
struct Inputs {
    n: [V3; 3],
    t: [V3; 3],
    hand: [f64; 3],
    pos: [V3; 3],
    uv: [V3; 3],
}

fn inputs(t: &Tri) -> Inputs {
    let c = corners(t);
    let q14 = |v: [i32; 3]| v.map(|x| f64::from(x) / 16384.0);
    Inputs {
        n: c.map(|c| q14(c.vertex.normal)),
        t: c.map(|c| {
            q14([
                c.vertex.tangent[0],
                c.vertex.tangent[1],
                c.vertex.tangent[2],
            ])
        }),
        hand: c.map(|c| f64::from(c.vertex.tangent[3].signum())),
        pos: c.map(|c| c.vertex.eye.map(|x| f64::from(x) / 65536.0)),
        uv: c.map(|c| {
            let k = f64::from(1u32 << TEXCOORD_FRAC);
            [
                f64::from(c.vertex.uv[0]) / k,
                f64::from(c.vertex.uv[1]) / k,
                0.0,
            ]
        }),
    }
}

/// One triangle drawn through the per-triangle front (no culling).
struct One<K> {
    corners: [Corner; 3],
    kernel: K,
}

impl<K: Kernel> DrawBand<K::Color> for One<K> {
    fn draw_band(&mut self, band: &mut BandView<'_, K::Color>) {
        draw_triangle(
            band,
            &ClipSpace::SCREEN,
            &self.kernel,
            &self.corners,
            Cull::None,
        );
    }
}

/// Draws triangle `t` with `kernel` into an `FB × FB` frame (black, depth
/// test on): the pixels and the depth buffer (0 where drawn, `u16::MAX`
/// elsewhere).
fn draw<K: Kernel>(kernel: K, t: &Tri) -> (Vec<K::Color>, Vec<u16>)
where
    K::Color: OutputColor,
{
    let black = K::Color::from_channels([0; 3]);
    let mut px = vec![black; (FB * FB) as usize];
    let mut depth = vec![0u16; (FB * FB) as usize];
    let mut item = One {
        corners: corners(t),
        kernel,
    };
    FullFrame::new(FB, FB, &mut px, Some(&mut depth))
        .unwrap()
        .render(black, &mut [&mut item])
        .unwrap();
    (px, depth)
}

/// Barycentric coordinates of the centre of pixel `(x, y)` (from the
/// sub-pixel corners the rasterizer sees), `None` outside or within `eps`
/// (pixels) of an edge.
fn bary(t: &Tri, x: u32, y: u32, eps: f64) -> Option<[f64; 3]> {
    let q = |c: f32| libm::round(f64::from(c) * 16.0) / 16.0;
    let p: [[f64; 2]; 3] = core::array::from_fn(|i| [q(t.screen[i][0]), q(t.screen[i][1])]);
    let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
    let area =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if area.abs() < 1.0 {
        return None;
    }
    let e = |a: [f64; 2], b: [f64; 2]| {
        ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) / area
    };
    let b = [e(p[1], p[2]), e(p[2], p[0]), e(p[0], p[1])];
    let len = |a: [f64; 2], b: [f64; 2]| ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
    let h = [
        area.abs() / len(p[1], p[2]),
        area.abs() / len(p[2], p[0]),
        area.abs() / len(p[0], p[1]),
    ];
    if (0..3).all(|i| b[i] * h[i] > eps) {
        Some(b)
    } else {
        None
    }
}

/// The texels the nearest sampler may pick at `uv` (f64): the exact one, and
/// its neighbours when `uv` is within `eps` texels of an edge.
fn candidates(map: &NormalMap<'_>, uv: [f64; 2], eps: f64) -> Vec<[i16; 3]> {
    let (w, h) = (f64::from(map.width()), f64::from(map.height()));
    let (x, y) = (uv[0] * w, uv[1] * h);
    let mut out = Vec::new();
    for dx in [-eps, 0.0, eps] {
        for dy in [-eps, 0.0, eps] {
            let t = map.texel((x + dx).floor() as i32, (y + dy).floor() as i32);
            if !out.contains(&t) {
                out.push(t);
            }
        }
    }
    out
}

// ---- maps ----------------------------------------------------------------------------

/// A 16 × 16 bump map of crossed sine ridges, strongly tilted.
fn bumpy_texels() -> Vec<[i16; 3]> {
    let heights: Vec<u8> = (0..256)
        .map(|i| {
            let (x, y) = ((i % 16) as f32, (i / 16) as f32);
            (128.0 + 60.0 * (x * 0.785).sin() + 60.0 * (y * 1.178 + 0.5).cos()) as u8
        })
        .collect();
    let mut out = vec![[0i16; 3]; 256];
    NormalMap::from_bump(&heights, 4, 4, Wrap::Repeat, 0.05, &mut out).unwrap();
    out
}

/// An 8 × 8 map of normals near the tangent plane (z from 0.02) and near the
/// normal, in every azimuth.
fn extreme_texels() -> Vec<[i16; 3]> {
    (0..64)
        .map(|i| {
            let a = i as f32 * 0.71;
            let z = [0.02, 0.1, 0.3, 0.7, 0.95, 1.0, 0.05, 0.5][i % 8];
            let r = (1.0f32 - z * z).max(0.0).sqrt();
            NormalMap::unit_texel([r * a.cos(), r * a.sin(), z]).unwrap()
        })
        .collect()
}

// ---- a flat map is PhongShading ---------------------------------------------------------

fn material() -> MaterialDesc {
    MaterialDesc::classic([1.0, 0.5, 0.2], AmbientSource::Object, 0.1, 0.7, 0.5, 32.0)
}

fn light_descs() -> Vec<(&'static str, LightDesc)> {
    let white = |kind| LightDesc {
        kind,
        ambient: [0.0; 3],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    };
    vec![
        (
            "directional",
            white(LightKind::Directional {
                towards_light: [-0.3, 0.5, 0.8],
            }),
        ),
        (
            "point",
            white(LightKind::Point {
                position: [1.5, 1.0, -1.0],
                attenuation: [1.0, 0.05, 0.01],
            }),
        ),
        (
            "spot",
            white(LightKind::Spot {
                position: [0.0, 0.5, 0.0],
                axis: [0.0, -0.15, -1.0],
                exponent: 4.0,
                cutoff_deg: 40.0,
                attenuation: [1.0, 0.0, 0.0],
            }),
        ),
    ]
}

/// The general per-pixel kernel and the normal-mapped general kernel with a
/// flat map, per triangle.
fn flat_equals_phong<S: Scalar, M: Model>(desc: &LightDesc, tris: &[Tri]) -> usize {
    let light = AnyLight::<S>::new(desc).unwrap();
    let lit = Lighting::<S, _, M>::new([light], Material::new(&material()).unwrap())
        .with_global_ambient_f32([0.0; 3])
        .eye_space();
    let flat = [NormalMap::FLAT; 4];
    let map = NormalMap::new(&flat, 1, 1, Wrap::Repeat).unwrap();
    let mut compared = 0;
    for t in tris {
        let (a, da) = draw(
            Shader::<_, _, _, Rgb565>::new(PhongShading, &lit, Linear),
            t,
        );
        let (b, db) = draw(
            Shader::<_, _, _, Rgb565>::new(PhongShading.normal_mapped(map), &lit, Linear),
            t,
        );
        assert_eq!(da, db, "the same pixels drawn");
        assert_eq!(a, b, "{} {desc:?}", core::any::type_name::<S>());
        compared += da.iter().filter(|&&d| d == 0).count();
    }
    compared
}

#[test]
fn flat_map_equals_phong_per_triangle_every_tier_and_light() {
    let mut r = Lcg(7);
    let tris: Vec<Tri> = (0..6).map(|_| random_tri(&mut r, 0.4)).collect();
    let mut n = 0;
    for (_, d) in light_descs() {
        n += flat_equals_phong::<Q14<1>, BlinnPhong>(&d, &tris);
        n += flat_equals_phong::<Q14<2>, Phong>(&d, &tris);
        n += flat_equals_phong::<Q30<3>, BlinnPhong>(&d, &tris);
        n += flat_equals_phong::<f32, Phong>(&d, &tris);
        n += flat_equals_phong::<f32, BlinnPhong>(&d, &tris);
        n += flat_equals_phong::<F32Fast<2>, BlinnPhong>(&d, &tris);
    }
    assert!(n > 20_000, "{n}");
}

// ---- the general path against the f64 reference ------------------------------------------

/// Max |Δ| (8-bit LSB) of the general path (tier `S`, model `M`) against the
/// f64 evaluation of the same method, over `tris`; Rgb888 output. Pixels whose
/// perturbed normal is within [`GATE`] of `n·L = 0`, where the specular term
/// switches on, are not compared (a targeted search found 63 LSB there).
fn general_error<S: Scalar, M: Model>(
    desc: &LightDesc,
    mat: &MaterialDesc,
    texels: &[[i16; 3]],
    log2: u8,
    tris: &[Tri],
) -> (u32, usize) {
    let light = AnyLight::<S>::new(desc).unwrap();
    let lit = Lighting::<S, _, M>::new([light], Material::new(mat).unwrap())
        .with_global_ambient_f32([0.0; 3])
        .eye_space();
    let map = NormalMap::new(texels, log2, log2, Wrap::Repeat).unwrap();
    let lights = [*desc];
    let reference = Reference {
        lights: &lights,
        material: *mat,
        global_ambient: [0.0; 3],
        viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
        fog: None,
        model: ModelDesc::of::<M>(),
    };
    let (mut worst, mut count) = (0u32, 0usize);
    for t in tris {
        let (px, depth) = draw(
            Shader::<_, _, _, Rgb888>::new(PhongShading.normal_mapped(map), &lit, Linear),
            t,
        );
        // the quantised inputs: unit normal and tangent of the Q14 values
        let q = inputs(t);
        let n: [V3; 3] = q.n.map(norm);
        let tg: [V3; 3] = q.t.map(norm);
        let w = if q.hand.iter().sum::<f64>() < 0.0 {
            -1.0
        } else {
            1.0
        };
        let (pos, uv) = (q.pos, q.uv);
        for y in 0..FB {
            for x in 0..FB {
                let Some(b) = bary(t, x, y, 0.02) else {
                    continue;
                };
                let i = (y * FB + x) as usize;
                assert!(depth[i] == 0, "pixel ({x}, {y}) inside but not drawn");
                let (ni, ti) = (lerp3(b, n), lerp3(b, tg));
                let bi = cross(ni, ti).map(|c| c * w);
                let p = lerp3(b, pos);
                let c = lerp3(b, uv);
                let got = px[i];
                let e = candidates(&map, [c[0], c[1]], 2e-3)
                    .into_iter()
                    .map(|m| {
                        let m = m.map(|v| f64::from(v) / 16384.0);
                        let np: V3 =
                            core::array::from_fn(|k| ti[k] * m[0] + bi[k] * m[1] + ni[k] * m[2]);
                        // within GATE of n·L = 0 the specular term switches on
                        // (a jump of up to ks): not compared, as in
                        // tests/lighting/lighting_accuracy.rs
                        let l = match desc.kind {
                            LightKind::Directional { towards_light } => norm(f64v(towards_light)),
                            LightKind::Point { position, .. }
                            | LightKind::Spot { position, .. } => {
                                norm(core::array::from_fn(|k| f64::from(position[k]) - p[k]))
                            }
                        };
                        if dot(norm(np), l).abs() <= GATE {
                            return 0;
                        }
                        let r = reference.shade(p, np).map(reference::to_u8);
                        (got.r() as i32 - r[0] as i32)
                            .abs()
                            .max((got.g() as i32 - r[1] as i32).abs())
                            .max((got.b() as i32 - r[2] as i32).abs())
                            as u32
                    })
                    .min()
                    .unwrap();
                worst = worst.max(e);
                count += 1;
            }
        }
    }
    (worst, count)
}

/// The general path's bounds against the f64 reference of the same method,
/// in 8-bit LSB: Q14 (Q14<1>), f32. See docs/tradeoff.md ("Normal mapping").
const GENERAL_Q14_MAX: u32 = 2;
const GENERAL_F32_MAX: u32 = 1;

#[test]
fn general_path_against_the_reference_every_light_and_model() {
    let mut r = Lcg(11);
    let tris: Vec<Tri> = (0..8).map(|_| random_tri(&mut r, 0.35)).collect();
    let maps = [(bumpy_texels(), 4u8), (extreme_texels(), 3u8)];
    let mut report = Vec::new();
    let mut fails = Vec::new();
    for shin in [8.0, 32.0, 128.0] {
        let mut mat = material();
        mat.shininess = shin;
        for (name, d) in light_descs() {
            for (texels, log2) in &maps {
                let runs = [
                    (
                        "Q14 blinn",
                        general_error::<Q14<1>, BlinnPhong>(&d, &mat, texels, *log2, &tris),
                        GENERAL_Q14_MAX,
                    ),
                    (
                        "Q14 phong",
                        general_error::<Q14<1>, Phong>(&d, &mat, texels, *log2, &tris),
                        GENERAL_Q14_MAX,
                    ),
                    (
                        "f32 blinn",
                        general_error::<f32, BlinnPhong>(&d, &mat, texels, *log2, &tris),
                        GENERAL_F32_MAX,
                    ),
                    (
                        "f32 phong",
                        general_error::<f32, Phong>(&d, &mat, texels, *log2, &tris),
                        GENERAL_F32_MAX,
                    ),
                ];
                for (tier, (e, n), bound) in runs {
                    assert!(n > 1000, "{n} pixels");
                    report.push(format!(
                        "{tier} {name} n={shin} log2={log2}: max {e} LSB over {n} px"
                    ));
                    if e > bound {
                        fails.push(format!("{tier} {name} n={shin} log2={log2}: {e} > {bound}"));
                    }
                }
            }
        }
    }
    println!("{}", report.join("\n"));
    assert!(fails.is_empty(), "{fails:#?}");
}

// ---- the fast path against the f64 reference -----------------------------------------------

/// The constant, diffuse and specular colours of a directional light and
/// material (per channel, from the reference model): `c = A + D·max(0, n·L)
/// + S·max(0, n·H)^shininess` (specular only where `n·L > 0`).
fn coefficients<M: Model>(
    desc: &LightDesc,
    mat: &MaterialDesc,
) -> ([f64; 3], [f64; 3], [f64; 3], V3, V3) {
    let LightKind::Directional { towards_light } = desc.kind else {
        panic!("directional only")
    };
    let l = norm(f64v(towards_light));
    let h = norm([l[0], l[1], l[2] + 1.0]);
    let lights = [*desc];
    let r = Reference {
        lights: &lights,
        material: *mat,
        global_ambient: [0.0; 3],
        viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
        fog: None,
        model: ModelDesc::of::<M>(),
    };
    let o = reference::VertexOptions::default();
    // a normal orthogonal to L: no diffuse, no specular
    let perp = norm(cross(
        l,
        if l[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        },
    ));
    let a = r.shade_parts([0.0; 3], perp, &o).0;
    let d = r.shade_parts([0.0; 3], l, &o).0;
    // a normal facing both L and H (H itself may face away from L when the
    // light is behind the surface)
    let nh = norm([l[0] + h[0], l[1] + h[1], l[2] + h[2]]);
    let k = dot(nh, h).powf(f64::from(mat.shininess));
    let s = r.shade_parts([0.0; 3], nh, &o).1.map(|c| c / k);
    (a, core::array::from_fn(|i| d[i] - a[i]), s, l, h)
}

/// Max |Δ| (8-bit LSB) of the fast path (`Q14<NW>`, model `M`) against the f64
/// evaluation of the same method: per vertex `L`, `H` in the exact tangent
/// frame, interpolated linearly, normalised, dotted with the texel.
fn fast_error<const NW: u8, M: fixshade::shade::IncrementalModel>(
    dir: [f32; 3],
    mat: &MaterialDesc,
    texels: &[[i16; 3]],
    log2: u8,
    wrap: Wrap,
    tris: &[Tri],
) -> (u32, usize) {
    let desc = LightDesc {
        kind: LightKind::Directional { towards_light: dir },
        ambient: [0.0; 3],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    };
    // one directional light: `IncrementalPhongShading.normal_mapped`
    let light = DirectionalLight::<Q14<NW>>::white(dir).unwrap();
    let lit = Lighting::<Q14<NW>, _, M>::new([light], Material::new(mat).unwrap())
        .with_global_ambient_f32([0.0; 3])
        .eye_space();
    let map = NormalMap::new(texels, log2, log2, wrap).unwrap();
    let (a, d, s, l, h) = coefficients::<M>(&desc, mat);
    let spec = M::SPECULAR == fixshade::lighting::Specular::BlinnPhong;
    let (mut worst, mut count) = (0u32, 0usize);
    for t in tris {
        let (px, depth) = draw(
            Shader::<_, _, _, Rgb888>::new(
                IncrementalPhongShading.normal_mapped(map),
                &lit,
                Linear,
            ),
            t,
        );
        // per vertex L, H in the tangent frame of the quantised inputs
        let q = inputs(t);
        let frame = |i: usize| {
            let n = norm(q.n[i]);
            let tt = q.t[i];
            let tt = norm(core::array::from_fn(|k| tt[k] - dot(tt, n) * n[k]));
            let b = cross(n, tt).map(|c| c * q.hand[i]);
            (
                [dot(tt, l), dot(b, l), dot(n, l)],
                [dot(tt, h), dot(b, h), dot(n, h)],
            )
        };
        let fr = [frame(0), frame(1), frame(2)];
        let (ls, hs) = (fr.map(|f| f.0), fr.map(|f| f.1));
        let uv = q.uv;
        for y in 0..FB {
            for x in 0..FB {
                let Some(b) = bary(t, x, y, 0.02) else {
                    continue;
                };
                let i = (y * FB + x) as usize;
                assert!(depth[i] == 0, "pixel ({x}, {y}) inside but not drawn");
                let (lp, hp) = (norm(lerp3(b, ls)), norm(lerp3(b, hs)));
                let c = lerp3(b, uv);
                let got = px[i];
                let e = candidates(&map, [c[0], c[1]], 2e-3)
                    .into_iter()
                    .map(|m| {
                        let m = m.map(|v| f64::from(v) / 16384.0);
                        let nl = dot(m, lp);
                        // the specular switches on at n·L = 0: within GATE of it
                        // either side is accepted
                        let gates: &[bool] = if nl.abs() <= GATE {
                            &[false, true]
                        } else {
                            &[nl > 0.0]
                        };
                        gates
                            .iter()
                            .map(|&on| {
                                let mut col = a;
                                if on {
                                    let sp = if spec {
                                        dot(m, hp).max(0.0).powf(f64::from(mat.shininess))
                                    } else {
                                        0.0
                                    };
                                    for k in 0..3 {
                                        col[k] += d[k] * nl.max(0.0) + s[k] * sp;
                                    }
                                }
                                let r = col.map(reference::to_u8);
                                (got.r() as i32 - r[0] as i32)
                                    .abs()
                                    .max((got.g() as i32 - r[1] as i32).abs())
                                    .max((got.b() as i32 - r[2] as i32).abs())
                                    as u32
                            })
                            .min()
                            .unwrap()
                    })
                    .min()
                    .unwrap();
                worst = worst.max(e);
                count += 1;
            }
        }
    }
    (worst, count)
}

/// How close to the `n·L = 0` cut-off the specular may be on or off (it
/// switches on there, a jump of up to `ks` in the colour): 2^-10, several
/// times the Q14 rounding of the fast path's `n·L` (per-vertex Q14 values,
/// Q16 products, the Q14 `1/|L|`).
const GATE: f64 = 1.0 / 1024.0;

/// The fast path's bound against the f64 reference of the same method, in
/// 8-bit LSB (Blinn-Phong up to shininess 128, Lambert). See
/// docs/tradeoff.md ("Normal mapping").
const FAST_MAX: u32 = 2;

#[test]
fn fast_path_against_the_reference_worst_cases() {
    let mut r = Lcg(3);
    // small triangles (tangent frames within ±0.15 rad) and large ones (±0.5 rad:
    // the spans whose L, H shrink fastest)
    let mut tris: Vec<Tri> = (0..10).map(|_| random_tri(&mut r, 0.15)).collect();
    tris.extend((0..6).map(|_| random_tri(&mut r, 0.5)));
    let flat = vec![NormalMap::FLAT; 4];
    let maps = [(bumpy_texels(), 4u8), (extreme_texels(), 3u8), (flat, 1u8)];
    // the light: frontal (highlight centres on the flat map), oblique, grazing
    // (nearly in the tangent plane of most triangles), behind
    let dirs = [
        [0.0, 0.0, 1.0],
        [-0.3, 0.5, 0.8],
        [0.9, 0.1, 0.05],
        [0.05, -0.99, 0.02],
        [0.3, 0.2, -0.6],
    ];
    let mut worst = (0, String::new());
    let mut pixels = 0;
    for shin in [1.0, 8.0, 32.0, 128.0] {
        let mut mat = material();
        mat.shininess = shin;
        for dir in dirs {
            for (texels, log2) in &maps {
                for wrap in [Wrap::Repeat, Wrap::Clamp] {
                    let runs = [
                        (
                            "blinn Q14<1>",
                            fast_error::<1, BlinnPhong>(dir, &mat, texels, *log2, wrap, &tris),
                        ),
                        (
                            "blinn Q14<2>",
                            fast_error::<2, BlinnPhong>(dir, &mat, texels, *log2, wrap, &tris),
                        ),
                        (
                            "lambert Q14<1>",
                            fast_error::<1, Lambert>(dir, &mat, texels, *log2, wrap, &tris),
                        ),
                    ];
                    for (name, (e, n)) in runs {
                        pixels += n;
                        if e > worst.0 {
                            worst = (
                                e,
                                format!("{name} n={shin} dir={dir:?} log2={log2} {wrap:?}"),
                            );
                        }
                    }
                }
            }
        }
    }
    println!(
        "fast path: max {} LSB ({}) over {pixels} pixels",
        worst.0, worst.1
    );
    assert!(pixels > 500_000);
    assert!(worst.0 <= FAST_MAX, "{worst:?}");
}

// ---- the mesh renderer ---------------------------------------------------------------------

mod mesh {
    use super::*;
    use fixshade::framebuffer::{FullFrame, Layout};
    use fixshade::render::{bins_len, CachedVertex, MeshDraw, MeshMemory};
    use fixshade::shade::Kernel;
    use fixshade::standard;

    const W: u32 = standard::SIZE;
    const NV: usize = standard::COUNTS.0;
    const NT: usize = standard::COUNTS.1;

    /// Spherical texture coordinates (Q12, three repeats around, two down)
    /// and tangents along the parallels (Q14) of the standard sphere.
    pub fn uv_tangents() -> (Vec<[i16; 2]>, Vec<[i16; 4]>) {
        let s = &standard::SPHERE;
        let mut uv = Vec::new();
        let mut tg = Vec::new();
        for n in s.normals.iter() {
            let n = n.map(|c| f64::from(c) / 16384.0);
            let phi = n[0].atan2(n[2]);
            let theta = n[1].clamp(-1.0, 1.0).acos();
            uv.push([
                (phi / core::f64::consts::TAU * 3.0 * 4096.0).round() as i16,
                (theta / core::f64::consts::PI * 2.0 * 4096.0).round() as i16,
            ]);
            let t = [phi.cos(), 0.0, -phi.sin()];
            tg.push([
                (t[0] * 16384.0).round() as i16,
                0,
                (t[2] * 16384.0).round() as i16,
                -16384,
            ]);
        }
        (uv, tg)
    }

    pub fn render<K: Kernel<Color = Rgb565>>(
        kernel: K,
        uv: &[[i16; 2]],
        tg: &[[i16; 4]],
    ) -> Vec<Rgb565> {
        let layout = Layout::full(W, W).unwrap();
        let mesh = standard::SPHERE
            .mesh()
            .with_texcoords(uv)
            .unwrap()
            .with_tangents(tg)
            .unwrap();
        let t = standard::transform().unwrap();
        let mut cache = vec![CachedVertex::<K::Vertex>::default(); NV];
        let mut bins = vec![0u16; bins_len(NT, 1)];
        let memory = MeshMemory {
            vertices: &mut cache,
            bins: &mut bins,
            carry: &mut [],
        };
        let mut draw =
            MeshDraw::new(layout, mesh, &t, kernel, memory, DrawOptions::default()).unwrap();
        let mut color = vec![Rgb565::BLACK; (W * W) as usize];
        let mut depth = vec![0u16; (W * W) as usize];
        let mut frame = FullFrame::new(W, W, &mut color, Some(&mut depth)).unwrap();
        frame.render(Rgb565::BLACK, &mut [&mut draw]).unwrap();
        frame.pixels().to_vec()
    }

    fn delta(a: Rgb565, b: Rgb565) -> u32 {
        let d = |x: u8, y: u8| (i32::from(x) - i32::from(y)).unsigned_abs();
        d(a.r(), b.r()).max(d(a.g(), b.g())).max(d(a.b(), b.b()))
    }

    /// The general per-pixel kernel and the general normal-mapped one with a
    /// flat map.
    fn flat_mesh<S: Scalar, I: Illuminate<Scalar = S>>(lit: &I) {
        let (uv, tg) = uv_tangents();
        let flat = [NormalMap::FLAT; 1];
        let map = NormalMap::new(&flat, 0, 0, Wrap::Repeat).unwrap();
        let a = render(Shader::new(PhongShading, lit, Linear), &uv, &tg);
        let b = render(
            Shader::new(PhongShading.normal_mapped(map), lit, Linear),
            &uv,
            &tg,
        );
        let lit_px = a.iter().filter(|p| **p != Rgb565::BLACK).count();
        assert!(lit_px > 20_000, "{lit_px}");
        assert_eq!(a, b, "{}", core::any::type_name::<S>());
    }

    #[test]
    fn flat_map_equals_phong_in_the_mesh_renderer() {
        flat_mesh(&standard::blinn::<Q14>().unwrap());
        flat_mesh(&standard::blinn::<f32>().unwrap());
        for (_, d) in light_descs() {
            let light = AnyLight::<Q14>::new(&d).unwrap();
            let lit = Lighting::<Q14, _, Phong>::new([light], Material::new(&material()).unwrap())
                .with_global_ambient_f32([0.0; 3])
                .eye_space();
            flat_mesh(&lit);
        }
    }

    /// The fast path in the mesh renderer (`IncrementalPhongShading.normal_mapped`
    /// with a `Q14` lighting of one `DirectionalLight`) with a flat map against
    /// `IncrementalPhongShading` (the same light as a one-element array; the
    /// normal interpolated instead of L and H in the tangent frame: not the
    /// same method, so only close), and with a bumpy map against the general
    /// Q14 path (`PhongShading.normal_mapped`).
    #[test]
    fn fast_mesh_kernel_is_close_to_the_general_one() {
        let (uv, tg) = uv_tangents();
        let light = DirectionalLight::<Q14>::white([-0.3, 0.5, 0.8]).unwrap();
        let mat = || Material::new(&standard::material()).unwrap();
        let lit = Lighting::<Q14, _, BlinnPhong>::new(light, mat())
            .with_global_ambient_f32([0.0; 3])
            .eye_space();
        let array = Lighting::<Q14, _, BlinnPhong>::new([light], mat())
            .with_global_ambient_f32([0.0; 3])
            .eye_space();
        let flat = [NormalMap::FLAT; 1];
        let map = NormalMap::new(&flat, 0, 0, Wrap::Repeat).unwrap();
        let inc = render(
            Shader::new(IncrementalPhongShading, &array, Linear),
            &uv,
            &tg,
        );
        let fast = render(
            Shader::new(IncrementalPhongShading.normal_mapped(map), &array, Linear),
            &uv,
            &tg,
        );
        let worst = inc
            .iter()
            .zip(&fast)
            .map(|(a, b)| delta(*a, *b))
            .max()
            .unwrap();
        println!("flat map, fast mesh kernel vs incremental Phong: max {worst} Rgb565 steps");
        assert!(worst <= 2, "{worst}");
        let texels = bumpy_texels();
        let map = NormalMap::new(&texels, 4, 4, Wrap::Repeat).unwrap();
        let general = render(
            Shader::new(PhongShading.normal_mapped(map), &lit, Linear),
            &uv,
            &tg,
        );
        let fast = render(
            Shader::new(IncrementalPhongShading.normal_mapped(map), &array, Linear),
            &uv,
            &tg,
        );
        let diffs: Vec<u32> = general
            .iter()
            .zip(&fast)
            .map(|(a, b)| delta(*a, *b))
            .collect();
        let worst = diffs.iter().max().unwrap();
        let mean = diffs.iter().sum::<u32>() as f64 / diffs.len() as f64;
        println!("bumpy map, fast vs general mesh kernel: max {worst} mean {mean:.4} Rgb565 steps");
        // the two interpolate different quantities: close in the mean, a few
        // steps apart where the texel changes between neighbouring pixels
        assert!(mean < 0.05, "{mean}");
        assert_ne!(
            general, fast,
            "the incremental kernel drew the general one's pixels"
        );
    }
}

// ---- targeted worst-case search (issue 21, item 6) -------------------------------------

use fixshade_testkit::worst_case;

/// One search point: a triangle, the light, the shininess, the map.
#[derive(Clone, Debug)]
struct NmCase {
    tri: Tri,
    dir: [f32; 3],
    shininess: f32,
    map: usize,
}

/// Targeted starts: the light at the mirror direction of the triangle's
/// centroid normal (the highlight inside the triangle, `H = N` there) turned
/// by up to two highlight widths, or grazing the centroid's tangent plane; the
/// highest shininess of the stated domain (128) and 32; every map.
fn nm_starts(count: usize, seed: u64) -> Vec<NmCase> {
    let mut r = Lcg(seed);
    let mut rng = worst_case::Rng::new(seed);
    (0..count)
        .map(|k| {
            let tri = random_tri(&mut r, [0.15, 0.5][k % 2]);
            let c = norm(lerp3([1.0 / 3.0; 3], tri.n.map(f64v)));
            let shininess = [128.0f32, 32.0][k % 2];
            let dir = if k % 4 == 3 {
                worst_case::around(
                    c,
                    std::f64::consts::FRAC_PI_2 - rng.range(0.002, 0.05),
                    rng.range(0.0, std::f64::consts::TAU),
                )
            } else {
                let m = worst_case::mirror(c, [0.0, 0.0, 1.0]);
                worst_case::around(
                    m,
                    rng.range(0.0, 2.0) / f64::from(shininess).sqrt(),
                    rng.range(0.0, std::f64::consts::TAU),
                )
            };
            NmCase {
                tri,
                dir: worst_case::f32s(dir),
                shininess,
                map: k % 3,
            }
        })
        .collect()
}

fn nm_perturb(c: &NmCase, amount: f64, rng: &mut worst_case::Rng) -> NmCase {
    let mut t = c.clone();
    t.dir = worst_case::f32s(worst_case::nudge(f64v(c.dir), amount * 0.5, rng));
    if rng.f() < 0.5 {
        for i in 0..3 {
            t.tri.n[i] = worst_case::f32s(worst_case::nudge(f64v(c.tri.n[i]), amount * 0.2, rng));
        }
    }
    if rng.f() < 0.3 {
        for i in 0..3 {
            for a in 0..2 {
                t.tri.uv[i][a] += (amount * rng.range(-1.0, 1.0)) as f32;
            }
        }
    }
    t
}

/// Every bound of this file at targeted worst cases: the fast path (`Q14<1>`,
/// `Q14<2>`, Blinn-Phong, shininess up to 128) and the general path (`Q14`,
/// `f32`; Blinn-Phong and Phong, a directional light) with the highlight
/// inside the triangle or the light grazing it, hill-climbed
/// (`fixshade_testkit::worst_case`). Prints the worst per path.
#[test]
fn targeted_worst_case_search() {
    let flat = vec![NormalMap::FLAT; 4];
    let maps = [(bumpy_texels(), 4u8), (extreme_texels(), 3u8), (flat, 1u8)];
    let starts = nm_starts(24, 21);
    let desc = |c: &NmCase| LightDesc {
        kind: LightKind::Directional {
            towards_light: c.dir,
        },
        ambient: [0.0; 3],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    };
    let mat = |c: &NmCase| MaterialDesc {
        shininess: c.shininess,
        ..material()
    };
    type Run = fn(&NmCase, &MaterialDesc, &LightDesc, &[[i16; 3]], u8) -> u32;
    let runs: [(&str, Run, u32); 6] = [
        (
            "fast Q14<1> blinn",
            |c, m, _, t, l| fast_error::<1, BlinnPhong>(c.dir, m, t, l, Wrap::Repeat, &[c.tri]).0,
            FAST_MAX,
        ),
        (
            "fast Q14<2> blinn",
            |c, m, _, t, l| fast_error::<2, BlinnPhong>(c.dir, m, t, l, Wrap::Clamp, &[c.tri]).0,
            FAST_MAX,
        ),
        (
            "general Q14 blinn",
            |c, m, d, t, l| general_error::<Q14<1>, BlinnPhong>(d, m, t, l, &[c.tri]).0,
            GENERAL_Q14_MAX,
        ),
        (
            "general Q14 phong",
            |c, m, d, t, l| general_error::<Q14<1>, Phong>(d, m, t, l, &[c.tri]).0,
            GENERAL_Q14_MAX,
        ),
        (
            "general f32 blinn",
            |c, m, d, t, l| general_error::<f32, BlinnPhong>(d, m, t, l, &[c.tri]).0,
            GENERAL_F32_MAX,
        ),
        (
            "general f32 phong",
            |c, m, d, t, l| general_error::<f32, Phong>(d, m, t, l, &[c.tri]).0,
            GENERAL_F32_MAX,
        ),
    ];
    let mut fails = Vec::new();
    for (i, (name, run, bound)) in runs.into_iter().enumerate() {
        let w = worst_case::climb(&starts, 30, 40 + i as u64, nm_perturb, |c| {
            let (texels, log2) = &maps[c.map];
            let e = run(c, &mat(c), &desc(c), texels, *log2);
            Some((f64::from(e), e))
        });
        println!(
            "{name}: worst {} LSB (bound {bound}, {} triangles)",
            w.error, w.evaluations
        );
        if w.error > bound {
            fails.push(format!("{name}: {} > {bound} at {:?}", w.error, w.at));
        }
    }
    assert!(fails.is_empty(), "{fails:#?}");
}
