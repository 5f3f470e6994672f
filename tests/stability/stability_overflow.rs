//! Every operation of every tier at the ends of its range: no panic, no wrapping
//! (these tests run with overflow checks on: the `test` profile keeps
//! debug assertions), and results within their documented ranges.
//!
//! The values are the extremes of each representation (raw `i32`/`i16` limits,
//! ±2, ±1, the smallest steps, NaN and infinities for the float tiers) and all
//! their combinations for the vector operations, plus random raw values.

use fixshade::num::Vec3;
use fixshade::num::{F32Fast, Geo16, Scalar, Q14, Q30};
use fixshade_testkit::seeded;

/// The range of the float tiers (±10⁹, documented in `fixshade::num`).
const F32_LIMIT: f32 = 1.0e9;
use proptest::prelude::*;

/// A tier together with the extreme values of its representation.
trait Extremes: Scalar {
    /// How far from 1 a normalised vector's components may reach: the relative
    /// error of the tier's inverse square root (1.6·10⁻² for the 48-entry seed alone,
    /// 3.4·10⁻² for micromath's bit trick alone).
    const UNIT_TOL: f32 = 1.0e-3;
    /// Raw limits, ±1, ±2, the smallest steps, zero.
    fn extremes() -> Vec<Self>;
    /// A value from an arbitrary 64-bit pattern (every representable value reachable).
    fn from_bits(b: u64) -> Self;
}

impl<const N: u8> Extremes for Q14<N> {
    const UNIT_TOL: f32 = if N == 0 { 1.7e-2 } else { 1.0e-3 };
    fn extremes() -> Vec<Self> {
        [
            i32::MIN,
            -32768,
            -32767,
            -16385,
            -16384,
            -1,
            0,
            1,
            2,
            11585,
            16383,
            16384,
            16385,
            32766,
            32767,
            i32::MAX,
        ]
        .map(Q14::from_raw)
        .to_vec()
    }
    fn from_bits(b: u64) -> Self {
        Q14::from_raw(b as u16 as i16 as i32)
    }
}

impl<const N: u8> Extremes for Q30<N> {
    const UNIT_TOL: f32 = if N == 0 { 1.7e-2 } else { 1.0e-3 };
    fn extremes() -> Vec<Self> {
        [
            i32::MIN,
            i32::MIN + 1,
            -(1 << 30) - 1,
            -(1 << 30),
            -(1 << 29),
            -1,
            0,
            1,
            2,
            759_250_125,
            (1 << 30) - 1,
            1 << 30,
            (1 << 30) + 1,
            i32::MAX - 1,
            i32::MAX,
        ]
        .map(Q30::from_raw)
        .to_vec()
    }
    fn from_bits(b: u64) -> Self {
        Q30::from_raw(b as u32 as i32)
    }
}

fn float_extremes() -> Vec<f32> {
    vec![
        f32::NAN,
        f32::NEG_INFINITY,
        -f32::MAX,
        -F32_LIMIT,
        -2.0,
        -1.0,
        -f32::MIN_POSITIVE,
        -1.0e-45,
        0.0,
        -0.0,
        1.0e-45,
        f32::MIN_POSITIVE,
        1.0e-20,
        0.5,
        1.0,
        2.0,
        1.0e20,
        F32_LIMIT,
        f32::MAX,
        f32::INFINITY,
    ]
}

impl Extremes for f32 {
    fn extremes() -> Vec<Self> {
        float_extremes()
    }
    fn from_bits(b: u64) -> Self {
        f32::from_bits(b as u32)
    }
}

impl<const N: u8> Extremes for F32Fast<N> {
    const UNIT_TOL: f32 = if N == 0 { 3.5e-2 } else { 2.0e-3 };
    fn extremes() -> Vec<Self> {
        float_extremes().into_iter().map(F32Fast).collect()
    }
    fn from_bits(b: u64) -> Self {
        F32Fast(f32::from_bits(b as u32))
    }
}

/// Geometry values at the ends of the geometry range.
fn geo_extremes<S: Scalar>() -> Vec<S::Geo> {
    let mut g: Vec<S::Geo> = [
        -1.0e30f32, -32768.0, -32767.99, -1.0, -1.5e-5, 0.0, 1.5e-5, 0.5, 1.0, 2.0, 300.0,
        32767.99, 32768.0, 1.0e30,
    ]
    .iter()
    .map(|&x| S::geo_from_f32(x))
    .collect();
    g.push(S::geo_from_f32(f32::NAN));
    g
}

/// Not NaN.
fn sane<S: Scalar>(x: S) -> bool {
    !x.to_f32().is_nan()
}

/// A value the tier's own conversions can produce (the float tiers' values are
/// plain `f32`s that can also hold NaN or values beyond ±F32_LIMIT; arithmetic on
/// those follows IEEE 754 and is only required not to panic).
fn in_range<S: Scalar>(x: S) -> bool {
    x.to_f32().abs() <= F32_LIMIT
}

fn check_unary<S: Extremes>(x: S) {
    for y in S::extremes() {
        for r in [x.add(y), x.sub(y), x.mul(y), x.div(y)] {
            let ok = sane(r) || !(in_range(x) && in_range(y));
            assert!(ok, "{} {x:?} {y:?}", S::NAME);
        }
        if y.to_f32() > 0.0 && x.to_f32() > 0.0 {
            assert!(x.div(y).to_f32() >= 0.0, "{} {x:?}/{y:?}", S::NAME);
        }
    }
    let s = x.sqrt();
    assert!(s.to_f32() >= 0.0 || !in_range(x), "{} sqrt {x:?}", S::NAME);
    for bits in [1, 5, 8, 16, 0, 17, 32, 100] {
        let u = x.to_unorm(bits);
        let max = (1u32 << bits.clamp(1, 16)) - 1;
        assert!(u <= max, "{} {x:?} to_unorm({bits}) = {u}", S::NAME);
    }
    let b = x.max0().min1();
    for n in [0u16, 1, 2, 3, 255, 256, 1023, 65535] {
        let p = b.powi(n).to_f32();
        assert!((0.0..=1.0).contains(&p), "{} {b:?}^{n} = {p}", S::NAME);
    }
    assert!(sane(S::from_attr(x.to_attr())));
}

fn check_vectors<S: Extremes>() {
    let xs = S::extremes();
    for &x in &xs {
        check_unary(x);
        for &y in &xs {
            for &z in &xs {
                let v = Vec3::new(x, y, z);
                for n in [
                    S::normalize(v),
                    S::normalize_precise(v),
                    S::normalize_interpolated(v),
                ] {
                    for c in n.to_f32() {
                        // a unit vector (or zero), whatever the input
                        assert!(c.abs() <= 1.0 + S::UNIT_TOL, "{} {v:?} -> {n:?}", S::NAME);
                    }
                }
                let u = Vec3::new(y, z, x);
                let finite = [x, y, z].iter().all(|&c| in_range(c));
                assert!(sane(v.dot(u)) || !finite, "{} {v:?}·{u:?}", S::NAME);
                let r = v.reflect(u);
                let ok = r.to_f32().iter().all(|c| !c.is_nan()) || !finite;
                assert!(ok, "{} {v:?}", S::NAME);
                // the cosines of the lighting equation, with any lengths
                let w = Vec3::new(z, x, y);
                for c in [
                    S::cos_normal(v, u),
                    S::reflect_dot(v, u, w),
                    x.twice_mul_sub(y, z),
                    S::dot3(v, w),
                ] {
                    assert!(sane(c) || !finite, "{} {v:?} {u:?} {w:?}", S::NAME);
                }
            }
        }
    }
}

fn check_geo<S: Extremes>() {
    let gs = geo_extremes::<S>();
    for &a in &gs {
        let u = S::geo_to_unit(a).to_f32();
        assert!((0.0..=1.0).contains(&u), "{} geo_to_unit {a:?}", S::NAME);
        let r = S::geo_recip(a).to_f32();
        assert!(r >= 0.0, "{} geo_recip {a:?}", S::NAME);
        assert!(!S::geo_to_f32(S::geo_from_attr(S::geo_to_attr(a))).is_nan());
        for &b in &gs {
            for g in [S::geo_add(a, b), S::geo_sub(a, b), S::geo_mul(a, b)] {
                let _ = S::geo_to_f32(g);
            }
            for &c in &gs {
                let (u, d) = S::geo_direction(Vec3::new(a, b, c));
                for x in u.to_f32() {
                    let ok = x.abs() <= 1.0 + S::UNIT_TOL;
                    assert!(ok, "{} {a:?} {b:?} {c:?} -> {u:?}", S::NAME);
                }
                assert!(S::geo_to_f32(d) >= 0.0, "{} {a:?} {b:?} {c:?}", S::NAME);
            }
        }
    }
}

macro_rules! tiers {
    ($f:ident) => {{
        $f::<Q14<0>>();
        $f::<Q14<1>>();
        $f::<Q14<2>>();
        $f::<Q14<3>>();
        $f::<Q30<0>>();
        $f::<Q30<1>>();
        $f::<Q30<3>>();
        $f::<Q30<4>>();
        $f::<f32>();
        $f::<F32Fast<0>>();
        $f::<F32Fast<1>>();
        $f::<F32Fast<2>>();
    }};
}

#[test]
fn every_operation_at_the_extremes() {
    tiers!(check_vectors);
}

#[test]
fn geometry_at_the_extremes() {
    tiers!(check_geo);
}

/// The regression of issue 11, item 2: `Q14::normalize_near_unit` summed the three
/// squares in an `i32`, which overflows for components near ±2 (a vertex normal
/// longer than about 2.8 reaches it through `Phong` shading).
#[test]
fn near_unit_normalisation_of_long_vectors() {
    for raw in [23170, 26000, 30000, 32767, -32768] {
        let c = Q14::<2>::from_raw(raw);
        let v = Vec3::new(c, c, c);
        let n = Q14::<2>::normalize_near_unit(v);
        assert_eq!(n, Q14::<2>::normalize(v), "{raw}");
        let want = if raw > 0 { 9459 } else { -9459 }; // ±1/√3 in Q14
        assert!((n.x.raw() - want).abs() <= 2, "{raw}: {n:?}");
    }
}

/// Exhaustive over every Q14 raw value for the unary operations.
#[test]
fn q14_unary_exhaustive() {
    for raw in -32768..=32767 {
        let x = Q14::<2>::from_raw(raw);
        let s = x.sqrt();
        assert!(s.raw() >= 0);
        assert!(x.to_unorm(16) <= 65535);
        assert_eq!(Q14::<2>::from_attr(x.to_attr()), x);
        let v = Vec3::new(x, Q14::from_raw(raw / 3), Q14::from_raw(-raw));
        let n = Q14::<2>::normalize_near_unit(v);
        assert_eq!(n, Q14::<2>::normalize(v), "{v:?}");
    }
}

proptest! {
    #![proptest_config(seeded::config("stability_overflow", 4000))]

    /// Random raw patterns for every pairwise and vector operation.
    #[test]
    fn random_raw_values(a in any::<u64>(), b in any::<u64>(), c in any::<u64>()) {
        fn tier<S: Extremes>(a: u64, b: u64, c: u64) {
            let (x, y, z) = (S::from_bits(a), S::from_bits(b), S::from_bits(c));
            check_unary(x);
            let v = Vec3::new(x, y, z);
            for n in [S::normalize(v), S::normalize_interpolated(v), S::normalize_precise(v)] {
                let ok = n.to_f32().iter().all(|c| c.abs() <= 1.0 + S::UNIT_TOL);
                assert!(ok, "{} {v:?}", S::NAME);
            }
            let u = Vec3::new(z, x, y);
            let _ = v.reflect(u).dot(v);
            let _ = (S::cos_normal(v, u), S::reflect_dot(v, u, Vec3::new(y, z, x)));
        }
        tier::<Q14<0>>(a, b, c);
        tier::<Q14<2>>(a, b, c);
        tier::<Q30<0>>(a, b, c);
        tier::<Q30<3>>(a, b, c);
        tier::<f32>(a, b, c);
        tier::<F32Fast<1>>(a, b, c);
        let _ = Geo16::from_bits(a as i32);
    }
}

/// `Q14::cos_normal` and `Q14::reflect_dot` against `f64`: the cosine of the
/// directions whatever the lengths within the correction's window. For lengths off
/// by up to 4·10⁻⁴ (a normalisation with one Newton step) only the rounding to Q14
/// remains (measured: 3.7·10⁻⁵, below one Q14 step); for 1.5 % off, the first-order correction leaves its residual
/// ((3/8)·ε² per length for a cosine, ε² for `1/|N|²`, ε = |v|² − 1 ≈ 0.03), against
/// an uncorrected error of about ε.
#[test]
fn length_corrected_cosines() {
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let q = |v: [f64; 3]| Vec3::<Q14<2>>::from_f32(v.map(|c| c as f32));
    let f = |v: Vec3<Q14<2>>| v.to_f32().map(|c| c as f64);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for (off, cos_bound, rv_bound) in [(4.0e-4, 5.0e-5, 5.0e-5), (0.015, 1.0e-3, 2.5e-3)] {
        let mut worst = [0.0f64; 2];
        for _ in 0..100_000 {
            let mut vector = || {
                let v = [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5];
                let len = (1.0 + off * (2.0 * rnd() - 1.0)) / dot(v, v).sqrt();
                q(v.map(|c| c * len))
            };
            let (n, l, v) = (vector(), vector(), vector());
            let (nf, lf, vf) = (f(n), f(l), f(v));
            let (nn, ll, vv) = (dot(nf, nf), dot(lf, lf), dot(vf, vf));
            let cos = dot(nf, lf) / (nn * ll).sqrt();
            let rv = (2.0 * dot(nf, lf) * dot(nf, vf) / nn - dot(lf, vf)) / (ll * vv).sqrt();
            let e0 = (Q14::<2>::cos_normal(n, l).to_f32() as f64 - cos).abs();
            let e1 = (Q14::<2>::reflect_dot(n, l, v).to_f32() as f64 - rv).abs();
            worst = [worst[0].max(e0), worst[1].max(e1)];
        }
        assert!(worst[0] < cos_bound, "{off}: cos_normal {worst:?}");
        assert!(worst[1] < rv_bound, "{off}: reflect_dot {worst:?}");
    }
}

/// `cargo test` runs with overflow checks on (the test profile is opt-level 2 but
/// keeps `dev`'s debug assertions and overflow checks), so every test of the suite
/// panics on a wrap-around instead of hiding it: proved here.
#[test]
fn overflow_checks_are_on_in_the_test_profile() {
    let wrapped =
        std::panic::catch_unwind(|| core::hint::black_box(i32::MAX) + core::hint::black_box(1));
    assert!(wrapped.is_err(), "overflow checks are off in this profile");
}
