//! The span engine of [`QuadraticPhongShading`](crate::shade::QuadraticPhongShading):
//! re-anchored quadratic interpolation of the lit colour along a span.
//!
//! A span is cut into segments of `h = 2^j` pixels; the tier's [`Probe`]
//! evaluates the lighting exactly at the two ends and the middle (the
//! *anchors*), and each encoded channel follows the quadratic through them by
//! second-order forward differences (Bishop & Weimer's idea, derivatives from
//! the anchors). The sharp specular `x^n` is not interpolated: its base (the
//! table coordinate `u` of `N̂·Ĥ` or `R̂·V̂`) is, and `x^n` read per pixel.
//!
//! # Why the interpolation error is bounded
//!
//! With `w = |dN|/|N|` (radians per pixel) a cosine `f = N̂·A` has
//! `|f''| ≤ 1.16·w²`, `|f'''| ≤ 3·w³` (for `R̂·V̂`: 8.64·w², 25.9·w³); the
//! quadratic through anchors `h/2` apart misses `f` by at most
//! `0.008·h³·max|f'''|`. [`Walk`] holds per lighting the largest `(h·w)²`
//! within each term's budget (the specular one per bucket of `u`), and
//! segments are halved until below it, or down to single exact pixels where
//! some `N·L` may change sign. Derivation: `docs/derivations.md`, "Quadratic
//! Phong".
//!
//! The pixel loops that follow the quadratics are the [`Sink`]s of `sink`; the
//! walk of one light's diffuse term through a table of pixels is [`walk_lut`].
// the span loops index several per-light and per-channel arrays at once
#![allow(clippy::needless_range_loop)]

mod lut;
mod sink;

pub(crate) use lut::{walk_lut, DAnchor, DiffuseTable};
pub(crate) use sink::{EncodeSink, Fast565Sink};

/// Fraction bits of the `N·L`-like quantities a probe returns (`d`, and `g`
/// before it becomes the table coordinate `u`).
pub(crate) const DFRAC: u32 = 15;
/// Table coordinate of `x = 1`.
pub(crate) const U_ONE: i32 = crate::num::pow::POW_END;
/// Probes clamp the table coordinate below at `U_FLOOR` (where `x^n` is 0).
pub(crate) const U_FLOOR: i32 = -(1 << 29);
/// The longest segment, `2^MAX_LOG` pixels.
pub(crate) const MAX_LOG: u32 = 5;

/// The specular power table of the quadratic kernel: Q15.
pub(crate) type PowTable = crate::num::pow::PowTable<15>;

/// What a probe computes at one pixel of a span.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Anchor<const K: usize> {
    /// Encoded channel values (the encoder's vertex scale with
    /// `ATTR_FRAC` bits) of the ambient and diffuse part, not clamped.
    pub v: [i32; 3],
    /// `N̂·L̂` of each light, Q15.
    pub d: [i32; K],
    /// The specular table coordinate of each light (below 0: `x < x0`).
    pub u: [i32; K],
    /// `1/|N|`, Q15.
    pub r: u32,
    /// Whether the interpolated normal is usable here (`|N|` in `[½, 2)`, values
    /// in range): if not, the pixel is shaded by the general path.
    pub ok: bool,
}

impl<const K: usize> Default for Anchor<K> {
    fn default() -> Self {
        Self {
            v: [0; 3],
            d: [0; K],
            u: [0; K],
            r: 0,
            ok: false,
        }
    }
}

/// Evaluates the lighting at pixels of the current span.
pub(crate) trait Probe<const K: usize> {
    /// The anchor at pixel offset `x` (`0 ≤ x ≤ n`: the end of the last
    /// segment may be the position after the span), into `a`. Encoded values
    /// must stay below 2^30 in magnitude, else `a.ok` is false.
    fn anchor(&self, x: i32, a: &mut Anchor<K>);
    /// `x^n` (Q15) of light `k`'s specular term at pixels `x0..x0 + out.len()`,
    /// evaluated at every pixel (where this light's `N·L` is positive).
    fn spec(&self, x0: i32, k: usize, out: &mut [u16]);
}

/// The constants of the segment walk (per lighting and encoder).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Walk<'p, const K: usize> {
    /// The power table (shared by the lights: one material).
    pub pow: &'p PowTable,
    /// Largest `(h·w)²` (Q30) for the ambient and diffuse part.
    pub y_q: u32,
    /// The deviation of `d` from the polyline through the anchors, per unit of
    /// `(h·w)²`: `dev = (Z >> 15)·dev_d >> 15` (Q15).
    pub dev_d: u32,
    /// The same for the specular base `x`.
    pub dev_x: u32,
    /// `u = (x − x0)·u_mul >> u_sh` (x in Q15): converts deviations.
    pub u_mul: i32,
    /// See `u_mul`.
    pub u_sh: u32,
    /// Specular colour of each light: encoded units per unit of `x^n` (Q15).
    pub ks: [[i32; 3]; K],
    /// Whether the model has a specular term.
    pub spec: bool,
}

/// A quadratic along a segment: the value and its first and second forward
/// differences.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Quad {
    pub v: i32,
    pub d1: i32,
    pub d2: i32,
}

impl Quad {
    /// The quadratic through `v0`, `vm`, `v1` at `0`, `m`, `2m` with `m = 2^jm`
    /// (`jm ≥ 1`, values below 2^30 in magnitude), as forward differences per
    /// pixel: `Δ² = (v0 − 2vm + v1)/m²`, `Δ¹ = (vm − v0)/m − Δ²·(m − 1)/2`
    /// (32-bit arithmetic on quarter values: the lowest two bits do not matter).
    #[inline]
    pub(crate) fn fit(v0: i32, vm: i32, v1: i32, jm: u32) -> Quad {
        let s4 = (v0 >> 2) - (vm >> 1) + (v1 >> 2);
        let d2 = if jm == 1 {
            s4
        } else {
            (s4 + (1 << (2 * jm - 3))) >> (2 * jm - 2)
        };
        let half = (vm >> 1) - (v0 >> 1);
        let d1 = (half >> (jm - 1)) - ((d2 * ((1 << jm) - 1)) >> 1);
        Quad { v: v0, d1, d2 }
    }

    /// `(lo, hi)` bounding the quadratic on the segment: the anchors' range
    /// widened by `|v0 − 2vm + v1|/8` (values below 2^30 in magnitude).
    #[inline]
    pub(crate) fn range(v0: i32, vm: i32, v1: i32) -> (i32, i32) {
        let s = ((v0 >> 2) - (vm >> 1) + (v1 >> 2)).abs() / 2 + 2;
        (v0.min(vm).min(v1) - s, v0.max(vm).max(v1) + s)
    }
}

/// A segment the walk accepted: pixels `x..x + 2^(jm+1)` with the anchors
/// `a` at `x`, `x + 2^jm` and `x + 2^(jm+1)`; `spec`: the lights whose
/// specular term it carries (per pixel).
#[derive(Clone, Copy)]
pub(crate) struct Segment<'a, const K: usize> {
    pub x: usize,
    pub jm: u32,
    pub a: [&'a Anchor<K>; 3],
    pub spec: [bool; K],
}

/// Where the walk puts pixels: the encoder and colour specific loops.
pub(crate) trait Sink<const K: usize> {
    /// The pixels of segment `seg` from its anchors.
    fn segment<P: Probe<K>>(&mut self, probe: &P, seg: Segment<'_, K>, walk: &Walk<'_, K>);
    /// Pixel `x` from its own anchor (exactly).
    fn exact(&mut self, x: usize, a: &Anchor<K>, walk: &Walk<'_, K>);
    /// Pixel `x` by the general path (the anchor was not usable).
    fn general(&mut self, x: usize);
}

/// `⌊log2 x⌋` for `x ≥ 1`, at most `MAX_LOG` (no library call).
#[inline]
fn log2_floor(x: usize) -> u32 {
    let mut j = 0;
    while j < MAX_LOG && (x >> (j + 1)) != 0 {
        j += 1;
    }
    j
}

/// `(h·w)²` (Q30) of a segment of `2^j` pixels with `w² = dd15·r²`, or `None`
/// if it reaches 1.
#[inline(always)]
fn hw2(dd15: u32, r: u32, j: u32) -> Option<u32> {
    // r < 2^16 (Q15): r² < 2^32; between anchors |N|² dips below the anchors'
    // minimum by at most |dN|²·(h/2)²/4, i.e. 1/|N| grows by < 1/14 while
    // (h·w)² ≤ 1: r² ·(1 + 1/8)
    let r2 = (r * r) >> 15;
    let r2 = r2 + (r2 >> 3) + 1;
    if dd15 >= 1 << 16 || r2 >= 1 << 17 {
        return None;
    }
    let w2 = dd15 * r2;
    if w2 >= 1 << (30 - 2 * j) {
        return None;
    }
    Some(w2 << (2 * j))
}

/// Walks a span of `n ≥ 1` pixels: segments where the error bounds allow,
/// single exact pixels where they do not. `dd` is an upper bound of `|dN|²`
/// per pixel² (Q30, the normal in the units of `N·N = 1`).
pub(crate) fn walk<const K: usize, P: Probe<K>, S: Sink<K>>(
    w: &Walk<'_, K>,
    probe: &P,
    n: usize,
    dd: u32,
    sink: &mut S,
) {
    let mut a = [Anchor::<K>::default(); 3];
    // anchors at the segment's start, middle and end: indices into `a`
    let (mut i0, mut im, mut i1) = (0usize, 1usize, 2usize);
    let mut pos = 0usize;
    probe.anchor(0, &mut a[i0]);
    let dd15 = (dd >> 15) + 1;
    // the first length to try: the longest the smooth part allows here
    let mut j = MAX_LOG;
    while j > 2 && hw2(dd15, a[i0].r, j).is_none_or(|z| z > w.y_q) {
        j -= 1;
    }
    while pos < n {
        let mut jj = j.min(log2_floor(n - pos));
        if jj < 2 || !a[i0].ok {
            // too short for a segment, or an unusable normal: one pixel
            one(sink, pos, &a[i0], w);
            pos += 1;
            if pos < n {
                probe.anchor(pos as i32, &mut a[i0]);
            }
            continue;
        }
        probe.anchor((pos + (1 << jj)) as i32, &mut a[i1]);
        probe.anchor((pos + (1 << (jj - 1))) as i32, &mut a[im]);
        loop {
            match check(w, [&a[i0], &a[im], &a[i1]], jj, dd15) {
                Some((spec, grow)) => {
                    let seg = Segment {
                        x: pos,
                        jm: jj - 1,
                        a: [&a[i0], &a[im], &a[i1]],
                        spec,
                    };
                    sink.segment(probe, seg, w);
                    pos += 1 << jj;
                    core::mem::swap(&mut i0, &mut i1);
                    j = if grow { (jj + 1).min(MAX_LOG) } else { jj };
                    break;
                }
                None if jj > 2 => {
                    jj -= 1;
                    core::mem::swap(&mut i1, &mut im);
                    probe.anchor((pos + (1 << (jj - 1))) as i32, &mut a[im]);
                }
                None => {
                    // the shortest segment (4 pixels) fails: two exact pixels
                    one(sink, pos, &a[i0], w);
                    probe.anchor((pos + 1) as i32, &mut a[i1]);
                    one(sink, pos + 1, &a[i1], w);
                    pos += 2;
                    core::mem::swap(&mut i0, &mut im);
                    j = 2;
                    break;
                }
            }
        }
    }
}

#[inline]
fn one<const K: usize, S: Sink<K>>(sink: &mut S, x: usize, a: &Anchor<K>, w: &Walk<'_, K>) {
    if a.ok {
        sink.exact(x, a, w)
    } else {
        sink.general(x)
    }
}

/// Whether the segment of `2^jj` pixels with anchors `a` meets the error
/// bounds: `Some((specular lights, whether twice the length would too))`.
#[inline]
fn check<const K: usize>(
    w: &Walk<'_, K>,
    a: [&Anchor<K>; 3],
    jj: u32,
    dd15: u32,
) -> Option<([bool; K], bool)> {
    if !(a[0].ok && a[1].ok && a[2].ok) {
        return None;
    }
    let z = hw2(dd15, a[0].r.max(a[1].r).max(a[2].r), jj)?;
    if z > w.y_q {
        return None;
    }
    let dev_d = (((z >> 15) * w.dev_d) >> 15) as i32 + 1;
    let mut spec = [false; K];
    for k in 0..K {
        let d = [a[0].d[k], a[1].d[k], a[2].d[k]];
        let lo = d[0].min(d[1]).min(d[2]) - dev_d;
        let hi = d[0].max(d[1]).max(d[2]) + dev_d;
        if lo <= 0 && hi > 0 {
            // N·L may change sign: a kink
            return None;
        }
        if w.spec && lo > 0 {
            let dev_x = ((z >> 15) * w.dev_x) >> 15;
            let dev_u = ((dev_x as i32 * w.u_mul) >> w.u_sh) + 1;
            let u = a[0].u[k]
                .max(a[1].u[k])
                .max(a[2].u[k])
                .saturating_add(dev_u);
            // below u = 0, x^n < 1/4096: dropped
            spec[k] = u >= 0;
        }
    }
    Some((spec, z <= w.y_q >> 2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_ends_at_the_end_anchor() {
        for jm in 1..5u32 {
            let (v0, vm, v1) = (100_000_000i32, 180_000_000, 190_000_000);
            let q = Quad::fit(v0, vm, v1, jm);
            let (mut v, mut d1) = (i64::from(q.v), i64::from(q.d1));
            for t in 0..(2i64 << jm) {
                if t == 1 << jm {
                    assert!(
                        (v - i64::from(vm)).abs() <= 1 << jm,
                        "mid jm {jm}: {v} {vm}"
                    );
                }
                v += d1;
                d1 += i64::from(q.d2);
            }
            assert!(
                (v - i64::from(v1)).abs() <= 2 << (2 * jm),
                "end jm {jm}: {v} {v1}"
            );
        }
    }

    #[test]
    fn quadratic_fit_is_exact_on_quadratics() {
        for jm in 1..5u32 {
            let m = 1i64 << jm;
            let p = |t: i64| 1000 + 37 * t - 5 * t * t;
            let q = Quad::fit(p(0) as i32, p(m) as i32, p(2 * m) as i32, jm);
            let (mut v, mut d1) = (i64::from(q.v), i64::from(q.d1));
            for t in 0..2 * m {
                assert_eq!(v, p(t), "jm {jm} t {t}");
                v += d1;
                d1 += i64::from(q.d2);
            }
        }
    }
}
