//! Attribute interpolation over a set-up triangle: what a shading kernel gets
//! for a run of pixels, screen-linear under an orthographic projection,
//! perspective-correct under a perspective one.
//!
//! A kernel's *varyings* are `[i32; N]` values at the three vertices, each
//! within ±[`VARYING_LIMIT`] (2^15 − 1; larger values are clamped). For a run of
//! pixels the kernel receives the values at its first pixel and their change
//! per pixel, both with [`ATTR_FRAC`] fraction bits.
//!
//! - **Screen-linear**: one 32-bit plane per varying (14-bit barycentric
//!   coefficients), evaluated once per run; where a plane's error bound could
//!   carry values out of [`Kernel::safe`](crate::shade::Kernel::safe), runs
//!   are clamped to the vertex range. The pieces of a clipped triangle stay
//!   within the whole triangle's bound (`tests/raster_precision.rs` searches
//!   both cases for their worst error).
//! - **Perspective-correct**, as OpenGL: with screen barycentric weights
//!   `βᵢ` and clip `wᵢ`, a pixel gets `Σ βᵢ·aᵢ/wᵢ / Σ βᵢ/wᵢ`, evaluated at the
//!   ends of sub-spans of 8 pixels (the last ending at the run's last pixel)
//!   and linearly between; a kernel gets one sub-span at a time. Every value
//!   is a convex combination of the vertex values (weights clamped to
//!   `[0, 1]`): no clamping needed. `1/wᵢ` is the product of the other two `w`
//!   (16-bit mantissas, no division), the weights Q15 from one
//!   table-and-Newton reciprocal per sub-span end: a value is off by about
//!   `2^−14·max|aⱼ − a₀|` plus the weights' error, their planes' own
//!   (dominant on large triangles) and the reciprocal's, about
//!   `2^−16·w_max/w_min` relative.
//!
//! Depth (`z/w`) is screen-linear under both projections.

use super::setup::{at3, bit_length, next3, ClampTo, Plane, Setup};
use super::ATTR_FRAC;
use super::SUBPIXEL_BITS;
use crate::num::recip::{normalise, recip16};

/// Varyings at the vertices are clamped to ±(2^15 − 1), so that the
/// differences of two fit the set-up's 17-bit plane inputs.
pub const VARYING_LIMIT: i32 = (1 << 15) - 1;

mod sealed {
    use super::Plane;

    /// The set-up's side of [`Varyings`](super::Varyings): one plane per
    /// value (implemented for `[i32; N]` only).
    pub trait Planes {
        /// One plane per value.
        type Planes: Copy + core::fmt::Debug + AsRef<[Plane]> + AsMut<[Plane]>;
        /// The planes `f(0), f(1), …`.
        fn planes_from_fn(f: impl FnMut(usize) -> Plane) -> Self::Planes;
    }

    impl<const N: usize> Planes for [i32; N] {
        type Planes = [Plane; N];
        #[inline(always)]
        fn planes_from_fn(f: impl FnMut(usize) -> Plane) -> [Plane; N] {
            core::array::from_fn(f)
        }
    }
}

/// The values a shading kernel interpolates across a triangle: `[i32; N]`
/// (sealed; see the [module docs](self) for units and precision).
pub trait Varyings: Copy + core::fmt::Debug + sealed::Planes + 'static {
    /// How many values.
    const LEN: usize;
    /// The values `f(0), f(1), …`.
    fn from_fn(f: impl FnMut(usize) -> i32) -> Self;
    /// The values as a slice.
    fn values(&self) -> &[i32];
    /// The values as a mutable slice.
    fn values_mut(&mut self) -> &mut [i32];
}

impl<const N: usize> Varyings for [i32; N] {
    const LEN: usize = N;
    #[inline(always)]
    fn from_fn(f: impl FnMut(usize) -> i32) -> Self {
        core::array::from_fn(f)
    }
    #[inline(always)]
    fn values(&self) -> &[i32] {
        self
    }
    #[inline(always)]
    fn values_mut(&mut self) -> &mut [i32] {
        self
    }
}

/// Value `i` of `v` (0 past the end: no panic path).
#[inline(always)]
pub(crate) fn get<V: Varyings>(v: &V, i: usize) -> i32 {
    v.values().get(i).copied().unwrap_or(0)
}

/// `a` interpolated `num/den` of the way to `b` (clipping), each value exact
/// to rounding. Not inlined: the rare path.
#[inline(never)]
pub(crate) fn lerp<V: Varyings>(a: &V, b: &V, num: u32, den: u32) -> V {
    V::from_fn(|i| crate::num::wide::lerp_i32(get(a, i), get(b, i), num, den))
}

/// The first `n` elements of `s` (all of them if it is shorter): a slice
/// loop, which opt-level "z" inlines (`iter().take(n)` it does not).
#[inline(always)]
fn first_mut<T>(s: &mut [T], n: usize) -> &mut [T] {
    let n = n.min(s.len());
    s.get_mut(..n).unwrap_or_default()
}

/// [`first_mut`] of a shared slice.
#[inline(always)]
fn first<T>(s: &[T], n: usize) -> &[T] {
    s.get(..n.min(s.len())).unwrap_or_default()
}

/// The values of the oriented vertices (`s.order`).
#[inline(always)]
pub(crate) fn oriented<T: Copy>(s: &Setup, v: &[T; 3]) -> [T; 3] {
    s.order.map(|i| super::setup::at3(v, i))
}

/// Value `i` of the oriented vertex `k` of `v` (the vertices as given, `s`
/// orients them), clamped to ±[`VARYING_LIMIT`].
#[inline(always)]
fn corner<V: Varyings>(s: &Setup, v: &[V; 3], k: usize, i: usize) -> i32 {
    let c = super::setup::at3(&s.order, k);
    get(&v[c.min(2)], i).clamp_to(-VARYING_LIMIT, VARYING_LIMIT)
}

/// Screen-linear interpolation: one absolute plane per varying.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Affine<V: Varyings> {
    planes: V::Planes,
}

impl<V: Varyings> Affine<V> {
    /// The planes of the first `used` of the vertices' values `v` (order of
    /// [`Setup::new`], clamped to ±[`VARYING_LIMIT`]) at the triangle's first
    /// row, exact to rounding where `exact(i)` (`Setup::plane_exact`). `clamp`
    /// is set when runs must be clamped to keep every value in `safe(i)`
    /// given the error bounds (`None`: decided in an earlier band).
    #[inline(always)]
    pub(crate) fn new(
        s: &Setup,
        v: &[V; 3],
        used: usize,
        safe: impl Fn(usize) -> (i32, i32),
        exact: impl Fn(usize) -> bool,
        mut clamp: Option<&mut bool>,
    ) -> Self {
        let mut recip = None;
        // built in place (no zeroed array copied over: a memclr and a memcpy of
        // the planes per triangle)
        let planes = V::planes_from_fn(|i| {
            if i >= used {
                return Plane::default();
            }
            let a = [corner(s, v, 0, i), corner(s, v, 1, i), corner(s, v, 2, i)];
            let plane = if exact(i) {
                s.plane_exact(a, *recip.get_or_insert_with(|| s.exact_recip()))
            } else {
                s.plane(a)
            };
            let base = super::setup::at3(&a, s.tmb[0]) << ATTR_FRAC;
            if let Some(c) = clamp.as_deref_mut() {
                *c |= !within(s, &plane, base, safe(i));
            }
            plane.absolute(base)
        });
        Affine { planes }
    }

    /// The next row.
    #[inline(always)]
    pub(crate) fn next_row(&mut self, used: usize) {
        for p in first_mut(self.planes.as_mut(), used) {
            p.next_row();
        }
    }

    /// `n` rows down.
    #[inline(always)]
    pub(crate) fn skip_rows(&mut self, n: i32, used: usize) {
        for p in first_mut(self.planes.as_mut(), used) {
            p.skip_rows(n);
        }
    }

    /// `(start, step)` of a run of `n ≥ 1` pixels from column `x` (the first
    /// `used` values; the others zero), clamped to the vertex range when
    /// `clamp` holds.
    #[inline(always)]
    pub(crate) fn run(&self, x: i32, n: usize, used: usize, clamp: bool) -> (V, V) {
        let mut start = V::from_fn(|_| 0);
        let mut step = start;
        let (starts, steps) = (start.values_mut(), step.values_mut());
        for (i, p) in first(self.planes.as_ref(), used).iter().enumerate() {
            if let (Some(s), Some(d)) = (starts.get_mut(i), steps.get_mut(i)) {
                (*s, *d) = if clamp {
                    p.clamped(x, n as i32)
                } else {
                    (p.at(x), p.dx)
                };
            }
        }
        (start, step)
    }
}

/// Whether a plane's values, with its error bound, stay in `safe` when added
/// to `base` (so that they need no clamping).
#[inline]
pub(crate) fn within(s: &Setup, p: &Plane, base: i32, safe: (i32, i32)) -> bool {
    let err = s.err(p);
    if err >= 1 << 29 {
        return false;
    }
    let err = err as i32;
    // |base|, |lo|, |hi| < 2^30 and err < 2^29: saturating, no overflow
    let lo = base.saturating_add(p.lo).saturating_sub(err);
    let hi = base.saturating_add(p.hi).saturating_add(err);
    lo >= safe.0 && hi <= safe.1
}

/// Perspective-correct interpolation (see the [module docs](self)).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Persp<V: Varyings> {
    /// The edge functions `Eᵢ` of the oriented vertices (the doubled area of
    /// the triangle a pixel centre makes with the other two vertices, in
    /// sub-pixels², exact) at column 0 of the current row, and their change
    /// per column and per row. Inside the triangle `Eᵢ ≥ 0` and `ΣEᵢ = A`.
    e_row: [i32; 3],
    e_dx: [i32; 3],
    e_dy: [i32; 3],
    /// `bit_length(A) − 8`: `Eᵢ·qᵢ / 2^k < 2^24`.
    k: i32,
    /// `1/wᵢ` up to a common factor, at most 2^16.
    q: [u32; 3],
    /// Vertex 0's values with [`ATTR_FRAC`] bits, and the differences
    /// `a₁ − a₀`, `a₂ − a₀`.
    a0: V,
    d1: V,
    d2: V,
}

impl<V: Varyings> Persp<V> {
    /// The interpolation of the vertices' values `v` and clip `w`
    /// (positive), in the order given to [`Setup::new`], positioned at the
    /// triangle's first row.
    pub(crate) fn new(s: &Setup, v: &[V; 3], w: [i32; 3]) -> Self {
        let w = oriented(s, &w);
        let p = s.xy;
        let one = 1i32 << SUBPIXEL_BITS;
        let half = one >> 1;
        // the centre of pixel (0, first row), sub-pixels
        let (px, py) = (half, (s.rows.0 << SUBPIXEL_BITS) + half);
        let edge = |i: usize| {
            let (j, k) = (next3(i), next3(next3(i)));
            let (pj, pk) = (at3(&p, j), at3(&p, k));
            // every coordinate difference below 2^15 (the window): products
            // below 2^30
            let e = (pj.0 - px) * (pk.1 - py) - (pj.1 - py) * (pk.0 - px);
            (e, (pj.1 - pk.1) * one, (pk.0 - pj.0) * one)
        };
        let e = [edge(0), edge(1), edge(2)];
        let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[1].1 - p[0].1) * (p[2].0 - p[0].0);
        Persp {
            e_row: e.map(|e| e.0),
            e_dx: e.map(|e| e.1),
            e_dy: e.map(|e| e.2),
            k: bit_length(area.max(0) as u32) as i32 - 8,
            q: inverse_w(w),
            a0: V::from_fn(|i| corner(s, v, 0, i) << ATTR_FRAC),
            d1: V::from_fn(|i| corner(s, v, 1, i) - corner(s, v, 0, i)),
            d2: V::from_fn(|i| corner(s, v, 2, i) - corner(s, v, 0, i)),
        }
    }

    /// The next row.
    #[inline(always)]
    pub(crate) fn next_row(&mut self) {
        for i in 0..3 {
            self.e_row[i] = self.e_row[i].wrapping_add(self.e_dy[i]);
        }
    }

    /// `n` rows down.
    #[inline(always)]
    pub(crate) fn skip_rows(&mut self, n: i32) {
        for i in 0..3 {
            self.e_row[i] = self.e_row[i].wrapping_add(n.wrapping_mul(self.e_dy[i]));
        }
    }

    /// The values at column `x` of the current row (a pixel the triangle
    /// covers), with [`ATTR_FRAC`] bits.
    #[inline]
    pub(crate) fn at(&self, x: i32) -> V {
        // Eᵢ at the pixel: exact in [0, A] inside the triangle (so the
        // wrapping sum is exact)
        let e = [0, 1, 2].map(|i| {
            let e = self.e_row[i].wrapping_add(x.wrapping_mul(self.e_dx[i]));
            e.max(0) as u32
        });
        // tᵢ = Eᵢ·qᵢ / 2^k < 2^24 (and Σtᵢ ≤ A·max qᵢ / 2^k < 2^24), from the 16-bit
        // halves of Eᵢ (32-bit products): Eᵢ is not rounded before it is
        // weighed (near a far vertex a small Eᵢ meets a large qᵢ)
        let k = self.k;
        let t = [0, 1, 2].map(|i| {
            let (hi, lo) = ((e[i] >> 16) * self.q[i], (e[i] & 0xFFFF) * self.q[i]);
            let hi = if k >= 16 {
                hi >> (k - 16)
            } else {
                hi << (16 - k)
            };
            hi + if k >= 0 { lo >> k } else { lo << -k }
        });
        let sum = t[0] + t[1] + t[2];
        let (sn, m) = normalise(sum, 15);
        if sn == 0 {
            return self.a0;
        }
        let r = recip16(sn);
        // tᵢ·2^m ≤ sn < 2^16 and r ≤ 2^16: the product (≈ 2^31·tᵢ/Σt) and
        // its rounding half fit 32 bits; the weights in Q15, rounded
        let weight = |ti: u32| {
            let tn = if m >= 0 { ti << m } else { ti >> -m };
            ((tn * r + (1 << 15)) >> 16).min(1 << 15) as i32
        };
        let w1 = weight(t[1]);
        let w2 = weight(t[2]).min((1 << 15) - w1);
        // a₀ + w₁·(a₁ − a₀) + w₂·(a₂ − a₀) with ATTR_FRAC (14) bits: a convex
        // combination, rounded once (two terms rounded apart could both round
        // up and pass the largest corner by a unit: found by fuzzing);
        // |wⱼ·dⱼ| ≤ 2^15·(2^16 − 2) and, as w₁ + w₂ ≤ 2^15, so is their sum:
        // below 2^31 (the wrapping sum is exact)
        V::from_fn(|i| {
            let s = (w1 * get(&self.d1, i)).wrapping_add(w2 * get(&self.d2, i));
            get(&self.a0, i).wrapping_add((s + 1) >> 1)
        })
    }
}

/// `qᵢ ∝ 1/wᵢ`, the largest at most 2^16: `qᵢ = ∏_{j≠i} wⱼ` from 16-bit
/// mantissas of the `w` (no division).
fn inverse_w(w: [i32; 3]) -> [u32; 3] {
    let w = w.map(|v| v.max(1) as u32);
    let big = w[0].max(w[1]).max(w[2]);
    let sh = super::setup::bit_length(big).saturating_sub(16);
    // mantissas below 2^16 (at least 1): products below 2^32
    let m = w.map(|v| (v >> sh).max(1));
    let q = [m[1] * m[2], m[0] * m[2], m[0] * m[1]];
    let qmax = q[0].max(q[1]).max(q[2]);
    let s = super::setup::bit_length(qmax).saturating_sub(16);
    q.map(|v| (v >> s).max(1))
}

/// The change per pixel between two ends `n` pixels apart (`1 ≤ n ≤ 8`;
/// rounded toward zero, so that every pixel's value lies between the ends;
/// within `2^−15` of the exact step's magnitude besides).
#[inline(always)]
pub(crate) fn step_over<V: Varyings>(a: &V, b: &V, n: u32) -> V {
    V::from_fn(|i| crate::num::div_small(get(b, i).wrapping_sub(get(a, i)), n))
}

/// The change per pixel between two sub-span ends 8 pixels apart (rounded
/// toward zero, so that every pixel's value lies between the ends).
#[inline(always)]
pub(crate) fn eighth<V: Varyings>(a: &V, b: &V) -> V {
    V::from_fn(|i| {
        let d = get(b, i).wrapping_sub(get(a, i));
        (d + ((d >> 31) & 7)) >> 3
    })
}
