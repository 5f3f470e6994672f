//! `QuadraticPhongShading` against the `f64` reference, pixel by pixel, on
//! random spans: every tier it supports (`Q14<1>`, `Q14<2>`, `f32`,
//! `F32Fast<2>`), every model (Lambert, Blinn-Phong, Phong `R·V`), one and two
//! directional lights, highlights from n = 1 to 1024, grazing light, normals
//! turning fast, every encoder.
//!
//! The bounds are the general path's (`PhongShading`'s) bounds of the same tier,
//! term and exponent band, from `tests/lighting_accuracy.rs`: the incremental
//! kernels must not be less accurate than the per-pixel lighting they replace.
//! Pixels within 10⁻³ of `N·L = 0` are skipped (there the rounding of either
//! side decides whether a specular term exists), as in that test.

#[path = "common/seeded.rs"]
mod seeded;

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor, Rgb565, Rgb888, RgbColor};
use fixshade::color::{GammaTable, Transfer};
use fixshade::light::{LightColors, LightDesc, LightKind};
use fixshade::lighting::{BlinnPhong, Lambert, Model, Phong, Specular};
use fixshade::prelude::*;
use fixshade::raster::SpanShader;
use fixshade::reference::{normalize, to_u8, ModelDesc, Reference, ViewerDesc};
use fixshade::shade::{Dithered, Encoder, ModeState, QuadraticPhongShading, Shader};
use proptest::prelude::*;

/// The kernel's bound (8-bit steps) for a tier, the model's specular term and
/// the exponent `n`: the general path's (`tests/lighting_accuracy.rs`: Q14 1 / 3 / 9
/// for n ≤ 64 / ≤ 256 / above) but for Q14 Phong `R·V`, whose anchors reflect `L`
/// in 32-bit arithmetic: 2 / 9 / 29 (errors of 2 / 4 / 10 found in 4 000 cases per
/// band, `PROPTEST_CASES=4000 cargo test --test quadratic_accuracy`).
fn bound(tier: &str, spec: Specular, n: u32) -> u32 {
    let band = match n {
        0..=64 => 0,
        65..=256 => 1,
        _ => 2,
    };
    match (tier, spec) {
        (_, Specular::None) => 1,
        ("q14_2" | "q14_1", Specular::Phong) => [2, 9, 29][band],
        ("q14_2" | "q14_1", _) => [1, 3, 9][band],
        ("f32fast", _) => [1, 1, 3][band],
        _ => 1,
    }
}

/// A random case: lights, material, the span's end normals and its length.
#[derive(Clone, Debug)]
struct Case {
    lights: Vec<[f32; 3]>,
    colors: Vec<[f32; 3]>,
    kd: [f32; 3],
    ks: [f32; 3],
    ka: f32,
    n: u32,
    a: [f32; 3],
    b: [f32; 3],
    len: usize,
}

fn unit() -> impl Strategy<Value = [f32; 3]> {
    // directions over the whole sphere, some of them grazing the span's normals
    (0.0f32..std::f32::consts::PI, 0.0f32..std::f32::consts::TAU)
        .prop_map(|(t, p)| [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()])
}

fn case(k: usize, band: (u32, u32)) -> impl Strategy<Value = Case> {
    (
        proptest::collection::vec((unit(), [0.2f32..1.0, 0.2f32..1.0, 0.2f32..1.0]), k),
        [0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0],
        [0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0],
        0.0f32..0.4,
        band.0..=band.1,
        // end normals in the upper hemisphere, at most ~100° apart
        (unit(), unit()),
        prop_oneof![1usize..8, 8usize..64, 64usize..=240],
    )
        .prop_map(move |(ls, kd, ks, ka, n, (a, b), len)| {
            let up = |v: [f32; 3]| [v[0] * 0.8, v[1] * 0.8, v[2].abs() + 0.3];
            Case {
                lights: ls.iter().map(|l| l.0).collect(),
                colors: ls.iter().map(|l| l.1.map(|c| c * 0.9 / k as f32)).collect(),
                kd,
                ks,
                ka,
                n,
                a: up(a),
                b: up(b),
                len,
            }
        })
}

/// `start`/`step` of a span (Q26 attributes as `Shading::draw` gives them): the
/// normal, then per light `N·L` and `N·H` (`N·V` for Phong).
fn attrs<S: Scalar, const N: usize>(
    c: &Case,
    dirs: &[[f32; 3]],
    seconds: &[[f32; 3]],
) -> ([i32; N], [i32; N]) {
    let at = |v: [f32; 3]| -> [i32; N] {
        let n = Vec3::<S>::from_f32(v).normalize();
        let a = [n.x.to_attr(), n.y.to_attr(), n.z.to_attr()];
        // the kernel takes the tier's directions as unit vectors (Q30)
        let dot = |d: [f32; 3]| {
            let q = normalize(d.map(f64::from)).map(|x| (x * (1u64 << 30) as f64).round() as i64);
            ((a[0] as i64 * q[0] + a[1] as i64 * q[1] + a[2] as i64 * q[2]) >> 30) as i32
        };
        let mut out = [0i32; N];
        out[..3].copy_from_slice(&a);
        for (j, (l, h)) in dirs.iter().zip(seconds).enumerate() {
            out[3 + 2 * j] = dot(*l);
            out[4 + 2 * j] = dot(*h);
        }
        out
    };
    let (s, e) = (at(c.a), at(c.b));
    let len = c.len.max(2) as i64 - 1;
    let step = core::array::from_fn(|i| ((e[i] as i64 - s[i] as i64) / len) as i32);
    (s, step)
}

/// The reference and the normals of the span's pixels.
fn reference(c: &Case, m: ModelDesc) -> (Vec<LightDesc>, MaterialDesc, ModelDesc) {
    let lights = c
        .lights
        .iter()
        .zip(&c.colors)
        .map(|(l, col)| LightDesc {
            kind: LightKind::Directional { towards_light: *l },
            ambient: [0.0; 3],
            diffuse: *col,
            specular: *col,
        })
        .collect();
    let mat = MaterialDesc {
        emission: [0.0; 3],
        ambient: c.kd.map(|k| k * c.ka),
        diffuse: c.kd,
        specular: c.ks,
        shininess: c.n as f32,
        ..MaterialDesc::default()
    };
    (lights, mat, m)
}

/// Runs the incremental span for tier `S`, `K` lights, model `M`, colour `C`
/// and encoder `E`; returns the pixels, the per-pixel normals (f64) and the
/// lights' tier directions.
#[allow(clippy::type_complexity)]
fn run<S, const K: usize, const N: usize, M, C, E>(
    c: &Case,
    enc: E,
) -> Option<(Vec<C>, Vec<[f64; 3]>)>
where
    S: Scalar,
    M: Model,
    C: OutputColor + Default,
    E: Encoder<C>,
    QuadraticPhongShading: ModeState<Lighting<S, [DirectionalLight<S>; K], M>, C>,
    for<'a> Shader<'a, QuadraticPhongShading, Lighting<S, [DirectionalLight<S>; K], M>, E, C>:
        SpanShader<N, Color = C>,
{
    let (lights, mat, _) = reference(c, ModelDesc::of::<M>());
    let dl: [DirectionalLight<S>; K] = core::array::from_fn(|j| {
        let d = &lights[j];
        let LightKind::Directional { towards_light } = d.kind else {
            unreachable!()
        };
        DirectionalLight::new(
            towards_light,
            LightColors::new(d.ambient, d.diffuse, d.specular).unwrap(),
        )
        .unwrap()
    });
    let lighting = Lighting::<S, _, M>::new(dl, Material::new(&mat).ok()?);
    let dirs: Vec<[f32; 3]> = lighting
        .lights()
        .iter()
        .map(|l| l.direction().to_f32())
        .collect();
    let seconds: Vec<[f32; 3]> = lighting
        .lights()
        .iter()
        .map(|l| match M::SPECULAR {
            Specular::Phong => [0.0, 0.0, 1.0],
            Specular::BlinnPhong => l.prepared().half.unwrap().to_f32(),
            Specular::None => [0.0; 3],
        })
        .collect();
    let (start, step) = attrs::<S, N>(c, &dirs, &seconds);
    let mut out = vec![C::default(); c.len];
    Shader::<_, _, _, C>::new(QuadraticPhongShading, &lighting, enc)
        .shade_span(3, 5, &start, &step, &mut out);
    let normals = (0..c.len)
        .map(|k| [0, 1, 2].map(|i| start[i] as f64 + k as f64 * step[i] as f64))
        .collect();
    Some((out, normals))
}

/// Whether a normal is within 10⁻³ of a light's terminator.
fn near_terminator(c: &Case, n: [f64; 3]) -> bool {
    let n = normalize(n);
    c.lights.iter().any(|l| {
        let l = normalize(l.map(|x| x as f64));
        (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]).abs() < 1.0e-3
    })
}

/// Every pixel of an Rgb888 span within the bound of the reference.
fn check888<S, const K: usize, const N: usize, M>(tier: &str, c: &Case) -> Result<(), TestCaseError>
where
    S: Scalar,
    M: Model,
    QuadraticPhongShading: ModeState<Lighting<S, [DirectionalLight<S>; K], M>, Rgb888>,
    for<'a> Shader<'a, QuadraticPhongShading, Lighting<S, [DirectionalLight<S>; K], M>, Linear, Rgb888>:
        SpanShader<N, Color = Rgb888>,
{
    let Some((px, normals)) = run::<S, K, N, M, Rgb888, Linear>(c, Linear) else {
        return Ok(());
    };
    let (lights, mat, model) = reference(c, ModelDesc::of::<M>());
    let r = Reference {
        lights: &lights,
        material: mat,
        global_ambient: [0.0; 3],
        viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
        fog: None,
        model,
    };
    let b = bound(tier, M::SPECULAR, c.n);
    for (k, (p, n)) in px.iter().zip(&normals).enumerate() {
        if near_terminator(c, *n) {
            continue;
        }
        let want = r.shade([0.0; 3], *n).map(to_u8);
        let got = [p.r(), p.g(), p.b()];
        let e = (0..3).map(|i| got[i].abs_diff(want[i])).max().unwrap();
        prop_assert!(
            u32::from(e) <= b,
            "{tier} {} pixel {k}/{}: got {got:?}, reference {want:?} ({e} > {b})",
            core::any::type_name::<M>(),
            c.len
        );
    }
    Ok(())
}

macro_rules! accuracy_tests {
    ($($name:ident: $S:ty, $tier:literal, $k:literal, $n:literal, $M:ty, $band:expr, $cases:literal;)*) => {$(
        proptest! {
            #![proptest_config(seeded::config(stringify!($name), $cases))]
            #[test]
            fn $name(c in case($k, $band)) {
                check888::<$S, $k, $n, $M>($tier, &c)?;
            }
        }
    )*};
}

const LOW: (u32, u32) = (1, 64);
const MID: (u32, u32) = (65, 256);
const HIGH: (u32, u32) = (257, 1024);

accuracy_tests! {
    q14_2_lambert: Q14<2>, "q14_2", 1, 5, Lambert, LOW, 400;
    q14_2_lambert_two: Q14<2>, "q14_2", 2, 7, Lambert, LOW, 200;
    q14_2_blinn_low: Q14<2>, "q14_2", 1, 5, BlinnPhong, LOW, 400;
    q14_2_blinn_mid: Q14<2>, "q14_2", 1, 5, BlinnPhong, MID, 200;
    q14_2_blinn_high: Q14<2>, "q14_2", 1, 5, BlinnPhong, HIGH, 200;
    q14_2_blinn_two: Q14<2>, "q14_2", 2, 7, BlinnPhong, LOW, 200;
    q14_2_phong_low: Q14<2>, "q14_2", 1, 5, Phong, LOW, 400;
    q14_2_phong_mid: Q14<2>, "q14_2", 1, 5, Phong, MID, 200;
    q14_2_phong_high: Q14<2>, "q14_2", 1, 5, Phong, HIGH, 200;
    q14_1_blinn_low: Q14<1>, "q14_1", 1, 5, BlinnPhong, LOW, 200;
    f32_lambert: f32, "f32", 1, 5, Lambert, LOW, 300;
    f32_blinn_low: f32, "f32", 1, 5, BlinnPhong, LOW, 300;
    f32_blinn_mid: f32, "f32", 1, 5, BlinnPhong, MID, 200;
    f32_blinn_high: f32, "f32", 1, 5, BlinnPhong, HIGH, 200;
    f32_phong_low: f32, "f32", 1, 5, Phong, LOW, 300;
    f32_phong_high: f32, "f32", 1, 5, Phong, HIGH, 200;
    f32_blinn_two: f32, "f32", 2, 7, BlinnPhong, LOW, 200;
    f32fast_blinn_low: F32Fast<2>, "f32fast", 1, 5, BlinnPhong, LOW, 200;
    f32fast_phong_high: F32Fast<2>, "f32fast", 1, 5, Phong, HIGH, 200;
}

/// 5-6-5 output (the fast kernels: the diffuse table, the packed loops) and the
/// dithering and gamma encoders: against the reference encoded the same way,
/// allowing the 8-bit bound of the tier before encoding.
fn check_encoded<S, const N: usize, M>(tier: &str, c: &Case) -> Result<(), TestCaseError>
where
    S: Scalar,
    M: Model,
    QuadraticPhongShading: ModeState<Lighting<S, [DirectionalLight<S>; 1], M>, Rgb565>
        + ModeState<Lighting<S, [DirectionalLight<S>; 1], M>, Gray8>,
    for<'a> Shader<'a, QuadraticPhongShading, Lighting<S, [DirectionalLight<S>; 1], M>, Linear, Rgb565>:
        SpanShader<N, Color = Rgb565>,
    for<'a> Shader<'a, QuadraticPhongShading, Lighting<S, [DirectionalLight<S>; 1], M>, Dithered, Rgb565>:
        SpanShader<N, Color = Rgb565>,
    for<'a, 't> Shader<
        'a,
        QuadraticPhongShading,
        Lighting<S, [DirectionalLight<S>; 1], M>,
        Gamma<'t, 1024>,
        Gray8,
    >: SpanShader<N, Color = Gray8>,
{
    let (lights, mat, model) = reference(c, ModelDesc::of::<M>());
    let r = Reference {
        lights: &lights,
        material: mat,
        global_ambient: [0.0; 3],
        viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
        fog: None,
        model,
    };
    let tol = f64::from(bound(tier, M::SPECULAR, c.n)) / 255.0;
    // a channel value `got` is right if some linear value within `tol` of the
    // reference encodes to it (every encoder is monotone)
    let within = |got: u32, v: f64, enc: &dyn Fn(f64) -> u32| {
        let (lo, hi) = (
            enc((v - tol).clamp(0.0, 1.0)),
            enc((v + tol).clamp(0.0, 1.0)),
        );
        (lo.min(hi)..=lo.max(hi)).contains(&got)
    };
    let round = |max: u32| move |v: f64| (v * max as f64).round() as u32;
    if let Some((px, normals)) = run::<S, 1, N, M, Rgb565, Linear>(c, Linear) {
        for (k, (p, n)) in px.iter().zip(&normals).enumerate() {
            if near_terminator(c, *n) {
                continue;
            }
            let v = r.shade([0.0; 3], *n);
            let got = [p.r(), p.g(), p.b()].map(u32::from);
            for (i, max) in [31u32, 63, 31].into_iter().enumerate() {
                prop_assert!(
                    within(got[i], v[i], &round(max)),
                    "565 pixel {k}: {got:?} vs {v:?}"
                );
            }
        }
    }
    if let Some((px, normals)) = run::<S, 1, N, M, Rgb565, Dithered>(c, Dithered) {
        for (k, (p, n)) in px.iter().zip(&normals).enumerate() {
            if near_terminator(c, *n) {
                continue;
            }
            let v = r.shade([0.0; 3], *n);
            let got = [p.r(), p.g(), p.b()].map(u32::from);
            // the Bayer threshold at (3 + k, 5): between 1/32 and 31/32 of a step
            for (i, max) in [31u32, 63, 31].into_iter().enumerate() {
                let floor = |t: f64| move |v: f64| ((v * max as f64 + t).floor() as u32).min(max);
                let ok = within(got[i], v[i], &floor(1.0 / 32.0))
                    || within(got[i], v[i], &floor(31.0 / 32.0))
                    || (got[i] as f64 - v[i] * max as f64).abs() <= 1.0 + tol * max as f64;
                prop_assert!(ok, "dithered pixel {k}: {got:?} vs {v:?}");
            }
        }
    }
    let table = GammaTable::<1024>::new(Transfer::Power(2.2)).unwrap();
    if let Some((px, normals)) = run::<S, 1, N, M, Gray8, Gamma<'_, 1024>>(c, Gamma(&table)) {
        for (k, (p, n)) in px.iter().zip(&normals).enumerate() {
            if near_terminator(c, *n) {
                continue;
            }
            let v = r.shade([0.0; 3], *n);
            let lum = 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
            let enc = |v: f64| u32::from(table.apply_unorm16((v * 65535.0).round() as u32));
            prop_assert!(
                within(u32::from(p.luma()), lum, &enc),
                "gamma pixel {k}: {} vs {lum}",
                p.luma()
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(seeded::config("quadratic_accuracy encoded", 300))]

    #[test]
    fn q14_encoded_lambert(c in case(1, LOW)) {
        check_encoded::<Q14<2>, 5, Lambert>("q14_2", &c)?;
    }

    #[test]
    fn q14_encoded_blinn(c in case(1, LOW)) {
        check_encoded::<Q14<2>, 5, BlinnPhong>("q14_2", &c)?;
    }

    #[test]
    fn f32_encoded_phong(c in case(1, LOW)) {
        check_encoded::<f32, 5, Phong>("f32", &c)?;
    }
}
