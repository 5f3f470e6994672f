//! The distance functions over their whole legal parameter range and the whole
//! geometry range: the attenuation `1/(a + b·d + c·d²)` and the fog ramp
//! `clamp((end − d)/(end − start), 0, 1)` of every tier against the exact value at
//! the tier's own distance (issue 11, items 4 and 5: tiny coefficients vanished in
//! Q16.16, fog ranges were quantised, `f32` fog over `±f32::MAX` was all fog).
//!
//! The parameters sweep every binade that can matter (coefficients from 10⁻³⁸ to
//! 10³⁸, fog ranges from one `f32` step to `2·f32::MAX`) and the distances every
//! binade of the geometry range plus its ends, and a random search adds
//! log-uniform combinations.

use fixshade::lighting::LinearFog;
use fixshade::lighting::MaterialDesc;
use fixshade::lighting::{Attenuation, LightDesc, LightKind};
use fixshade::num::{F32Fast, Geo16, Scalar, Q14, Q30};
use fixshade_testkit::reference::{FogDesc, ViewerDesc};
use fixshade_testkit::scenes::{lsb_error, reference_u8, tier_u8, ModelKind, Rng, Sample};

/// A tier with the tolerances its documentation states (`Scalar::geo_inv_quadratic`,
/// `Scalar::ramp_at`): the attenuation within `ATT_REL` relative plus the final
/// rounding `ATT_ABS`, the fog factor within `FOG_ABS`.
trait Tier: Scalar {
    const ATT_REL: f64;
    const ATT_ABS: f64;
    const FOG_ABS: f64;
    /// The distances to test: the tier's exact geometry values over its range.
    fn distances() -> Vec<Self::Geo>;
    /// A geometry value exactly (`geo_to_f32` rounds Q16.16 to 24 bits).
    fn geo_f64(g: Self::Geo) -> f64;
}

fn fixed_distances() -> Vec<Geo16> {
    let mut raws = vec![0i32, 1, 2, 3, 7, i32::MAX, i32::MAX - 1, -1, i32::MIN];
    // every binade, with values inside it
    for k in 0..31 {
        let base = 1i64 << k;
        for f in [0i64, 1, base / 3, base / 2, base - 1] {
            let v = base + f;
            if v <= i32::MAX as i64 {
                raws.push(v as i32);
            }
        }
    }
    raws.into_iter().map(Geo16::from_bits).collect()
}

fn float_distances() -> Vec<f32> {
    let mut d = vec![0.0f32, -1.0, 1.0e-30, 1.0e9, 2.0e9, f32::MAX, f32::INFINITY];
    let mut x = 1.0e-6f32;
    while x < 1.0e9 {
        d.extend([x, x * 1.37, x * 1.91]);
        x *= 2.0;
    }
    d
}

impl<const N: u8> Tier for Q14<N> {
    const ATT_REL: f64 = 1.0 / 8192.0;
    const ATT_ABS: f64 = 1.0 / 32768.0;
    const FOG_ABS: f64 = 1.0 / 8192.0;
    fn distances() -> Vec<Geo16> {
        fixed_distances()
    }
    fn geo_f64(g: Geo16) -> f64 {
        g.to_bits() as f64 / 65536.0
    }
}
impl<const N: u8> Tier for Q30<N> {
    const ATT_REL: f64 = 1.0e-6;
    const ATT_ABS: f64 = 1.0e-9;
    const FOG_ABS: f64 = 1.0e-6;
    fn distances() -> Vec<Geo16> {
        fixed_distances()
    }
    fn geo_f64(g: Geo16) -> f64 {
        g.to_bits() as f64 / 65536.0
    }
}
impl Tier for f32 {
    const ATT_REL: f64 = 1.0e-6;
    const ATT_ABS: f64 = 1.0e-9;
    const FOG_ABS: f64 = 1.0e-6;
    fn distances() -> Vec<f32> {
        float_distances()
    }
    fn geo_f64(g: f32) -> f64 {
        g as f64
    }
}
impl<const N: u8> Tier for F32Fast<N> {
    const ATT_REL: f64 = 1.0e-6;
    const ATT_ABS: f64 = 1.0e-9;
    const FOG_ABS: f64 = 1.0e-6;
    fn distances() -> Vec<f32> {
        float_distances()
    }
    fn geo_f64(g: f32) -> f64 {
        g as f64
    }
}

/// The attenuation coefficients to sweep: 0 and every few binades of f32.
fn coefficients() -> Vec<f32> {
    let mut c = vec![
        0.0f32,
        1.0e-45,
        f32::MIN_POSITIVE,
        2.0e-5,
        1.0e-6,
        0.05,
        0.5,
        1.0,
    ];
    let mut x = 1.0e-38f32;
    while x < 1.0e38 {
        c.extend([x, x * 1.7]);
        x *= 64.0;
    }
    c.push(f32::MAX);
    c
}

fn check_attenuation<S: Tier>(a: f32, b: f32, c: f32, d: S::Geo) {
    let Ok(att) = Attenuation::new::<S>(a, b, c) else {
        assert!(a == 0.0 && b == 0.0 && c == 0.0);
        return;
    };
    let got = att.factor::<S>(d).to_f32() as f64;
    // a distance beyond f32 (∞) counts as f32::MAX, and 0·∞ as 0
    let dd = S::geo_f64(d).clamp(0.0, f32::MAX as f64);
    let q = a as f64 + b as f64 * dd + c as f64 * dd * dd;
    let max = S::MAX.to_f32() as f64;
    let want = if q > 0.0 { (1.0 / q).min(max) } else { max };
    let tol = want * S::ATT_REL + S::ATT_ABS;
    assert!(
        (got - want).abs() <= tol,
        "{}: a={a:e} b={b:e} c={c:e} d={dd}: {got} vs {want}",
        S::NAME
    );
}

#[test]
fn attenuation_over_the_whole_range() {
    fn tier<S: Tier>() {
        let cs = coefficients();
        let ds = S::distances();
        for &a in &cs {
            for &b in &cs {
                for &c in &cs {
                    for &d in ds.iter().step_by(5) {
                        check_attenuation::<S>(a, b, c, d);
                    }
                }
            }
        }
        // every distance with the coefficients of the issue
        for &d in &ds {
            for (a, b, c) in [(1.0, 0.0, 2.0e-5), (1.0, 0.0, 1.0e-6), (0.0, 0.0, 1.0)] {
                check_attenuation::<S>(a, b, c, d);
            }
        }
        // random log-uniform coefficients and distances
        let mut rng = Rng::new(11);
        let mut pick = |lo: f64, hi: f64| (lo + (hi - lo) * rng.f()).exp2() as f32;
        for _ in 0..20_000 {
            let (a, b, c) = (pick(-10.0, 4.0), pick(-40.0, 10.0), pick(-60.0, 10.0));
            let d = S::geo_from_f32(pick(-17.0, 15.0));
            check_attenuation::<S>(a, b, c, d);
        }
    }
    tier::<Q14<2>>();
    tier::<Q30<3>>();
    tier::<f32>();
    tier::<F32Fast<2>>();
}

fn check_fog<S: Tier>(start: f32, end: f32, d: S::Geo) {
    let fog = LinearFog::<S>::new(start, end, [0.0; 3]).unwrap();
    // the fog blends f·direct + (1 − f)·colour: with direct = 1 and colour = 0 the
    // output is f itself
    let got = {
        use fixshade::lighting::FogModel;
        fog.apply(fixshade::color::Rgb::splat(S::ONE), d).r.to_f32() as f64
    };
    let dd = S::geo_f64(d);
    let (s, e) = (start as f64, end as f64);
    let want = ((e - dd) / (e - s)).clamp(0.0, 1.0);
    let want = if dd.is_nan() { 0.0 } else { want };
    assert!(
        (got - want).abs() <= S::FOG_ABS,
        "{}: fog {start:e}..{end:e} at d={dd}: {got} vs {want}",
        S::NAME
    );
}

/// Fog ranges: near the geometry range, beyond it, enormous, tiny.
fn fog_ranges() -> Vec<(f32, f32)> {
    let mut r = vec![
        (0.0, 10_000.0),
        (0.0, 200_000.0),
        (-f32::MAX, f32::MAX),
        (-f32::MAX, 0.0),
        (0.0, f32::MAX),
        (2.0, 9.0),
        (1000.0, 1000.001),
        (0.0, 1.0e-45),
        (-1.0e-45, 0.0),
        (-1.0e30, -1.0e29),
        (1.0e29, 1.0e30),
        (-40_000.0, 40_000.0),
        (30_000.0, 1.0e6),
        (-1.0e6, -30_000.0),
        (32_767.5, 32_768.5),
        (-32_768.5, -32_767.5),
        (-32_768.0, 32_768.0),
        (0.3, 0.30002),
        (-5.0, 1.0e9),
        (-1.0e38, 3.0e38),
    ];
    let mut x = 1.0e-7f32;
    while x < 1.0e38 {
        r.push((-x, x));
        r.push((1000.0, 1000.0 + x));
        r.push((-7.5 - x, -7.5));
        x *= 37.0;
    }
    r.retain(|(s, e)| e > s);
    r
}

#[test]
fn fog_over_the_whole_range() {
    fn tier<S: Tier>() {
        let ds = S::distances();
        for (s, e) in fog_ranges() {
            for &d in &ds {
                check_fog::<S>(s, e, d);
                check_fog::<S>(s, e, S::geo_sub(S::geo_from_f32(0.0), d));
            }
            // around both ends
            for end in [s, e] {
                let c = S::geo_from_f32(end);
                for k in [-3.0f32, -1.0, -1.0e-4, 0.0, 1.0e-4, 1.0, 3.0] {
                    check_fog::<S>(s, e, S::geo_add(c, S::geo_from_f32(k)));
                }
            }
        }
        let mut rng = Rng::new(5);
        for _ in 0..20_000 {
            let r = (-20.0 + 147.0 * rng.f()).exp2() as f32;
            let end = ((rng.f() - 0.5) * 80_000.0) as f32;
            let d = S::geo_from_f32(((rng.f() - 0.5) * 70_000.0) as f32);
            if end - r < end {
                check_fog::<S>(end - r, end, d);
            }
        }
    }
    tier::<Q14<2>>();
    tier::<Q30<3>>();
    tier::<f32>();
    tier::<F32Fast<2>>();
}

/// The scenes of the issue through the whole lighting equation, every tier within
/// its 1 LSB bound against the reference: a point light 300 units away with
/// c = 10⁻⁶ and 2·10⁻⁵, fog 0…10 000 seen at 5 000, fog 0…200 000, fog over
/// ±f32::MAX.
#[test]
fn the_cases_of_the_issue() {
    fn point(c: f32) -> Sample {
        Sample {
            lights: vec![LightDesc {
                kind: LightKind::Point {
                    position: [0.0, 0.0, 300.0],
                    attenuation: [1.0, 0.0, c],
                },
                ambient: [0.0; 3],
                diffuse: [0.9; 3],
                specular: [0.0; 3],
            }],
            material: MaterialDesc {
                ambient: [0.0; 3],
                diffuse: [1.0; 3],
                ..MaterialDesc::default()
            },
            global_ambient: [0.0; 3],
            viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
            fog: None,
            p: [0.0; 3],
            n: [0.0, 0.0, 1.0],
            model: ModelKind::Lambert,
        }
    }
    fn fogged(start: f32, end: f32, z: f32) -> Sample {
        Sample {
            lights: vec![LightDesc {
                kind: LightKind::Directional {
                    towards_light: [0.0, 0.0, 1.0],
                },
                ambient: [0.0; 3],
                diffuse: [0.9; 3],
                specular: [0.0; 3],
            }],
            fog: Some(FogDesc {
                start,
                end,
                color: [0.1, 0.2, 0.3],
            }),
            p: [0.0, 0.0, z],
            model: ModelKind::Blinn,
            ..point(0.0)
        }
    }
    let cases = [
        point(1.0e-6),
        point(2.0e-5),
        fogged(0.0, 10_000.0, -5_000.0),
        fogged(0.0, 200_000.0, -20_000.0),
        fogged(0.0, 200_000.0, 20_000.0),
        fogged(-f32::MAX, f32::MAX, -3.0),
        fogged(-f32::MAX, f32::MAX, 30_000.0),
    ];
    fn tier<S: Scalar>(cases: &[Sample]) {
        for s in cases {
            let (got, want) = (tier_u8::<S>(s), reference_u8(s));
            assert!(
                lsb_error(got, want) <= 1,
                "{}: {got:?} vs {want:?}: {s:?}",
                S::NAME
            );
        }
    }
    tier::<Q14<1>>(&cases);
    tier::<Q14<2>>(&cases);
    tier::<Q30<3>>(&cases);
    tier::<f32>(&cases);
    tier::<F32Fast<2>>(&cases);
}
