//! The span engine of [`QuadraticPhongShading`](super::QuadraticPhongShading):
//! re-anchored quadratic interpolation of the lit colour along a span.
//!
//! A span of `n` pixels is cut into segments of `h = 2^j` pixels. At the two
//! ends and the middle of a segment (the *anchors*) the lighting is evaluated
//! by the tier's [`Probe`] (exactly, up to the tier's arithmetic); in between,
//! each encoded colour channel follows the quadratic through the three anchor
//! values, two additions per channel and pixel (second-order forward
//! differences, Bishop & Weimer's idea with the derivatives taken from the
//! anchors instead of a Taylor expansion). The specular term, whose power
//! `x^n` is sharp, is not interpolated: its smooth base (the table coordinate
//! `u` of `N̂·Ĥ` or `R̂·V̂`) is, and `x^n` is read from a table at every pixel.
//!
//! # Why the interpolation error is bounded
//!
//! Along a span the normal is `N(t) = N0 + t·dN`, so `N̂(t)` moves on a great
//! circle as the central projection of a line. With `w = |dN|/|N|` (the local
//! angular speed, radians per pixel) every component `f = N̂·A` of a fixed unit
//! vector `A` satisfies `|f'| ≤ w·√(1 − f²)`, `|f''| ≤ 1.16·w²` and
//! `|f'''| ≤ 3·w³` (from the derivatives of `atan`); for `R̂·V̂` (`R̂` the
//! reflection of `L̂`) the constants are 2, 8.64 and 25.9. A quadratic through
//! three points `h/2` apart misses a function by at most `0.008·h³·max|f'''|`,
//! and a function deviates from the polyline through the anchors by at most
//! `max|f''|·(h/2)²/8`. [`Walk`] holds, per lighting, the largest `(h·w)²`
//! that keeps each term's error under its budget (the specular one per bucket
//! of `u`, since the slope of `x^n` grows towards the highlight), and each
//! segment is halved until `(h·w)²` is below it. Segments where some light's
//! `N·L` may change sign (a kink: no diffuse and no specular behind the
//! surface) are halved too, down to single pixels evaluated exactly.
// the span loops index several per-light and per-channel arrays at once
#![allow(clippy::needless_range_loop)]

use super::Encoder;
use crate::color::OutputColor;

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

/// Where the walk puts pixels: the encoder and colour specific loops.
pub(crate) trait Sink<const K: usize> {
    /// Pixels `x..x + 2^(jm+1)` from the anchors at `x`, `x + 2^jm` and
    /// `x + 2^(jm+1)`; the specular terms of the lights in `spec` per pixel.
    fn segment<P: Probe<K>>(
        &mut self,
        probe: &P,
        x: usize,
        jm: u32,
        a: [&Anchor<K>; 3],
        spec: [bool; K],
        walk: &Walk<'_, K>,
    );
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
                    sink.segment(probe, pos, jj - 1, [&a[i0], &a[im], &a[i1]], spec, w);
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

// ---- sinks -----------------------------------------------------------------------

/// The specular value of light `k` at an anchor (Q15), 0 behind the surface.
#[inline(always)]
fn spec_at<const K: usize>(w: &Walk<'_, K>, a: &Anchor<K>, k: usize) -> i32 {
    if w.spec && a.d[k] > 0 {
        w.pow.at_clamped(a.u[k])
    } else {
        0
    }
}

/// The exact encoded channel values of an anchor (specular included), not clamped.
#[inline(always)]
pub(crate) fn exact_values<const K: usize>(w: &Walk<'_, K>, a: &Anchor<K>) -> [i32; 3] {
    let mut v = a.v;
    for k in 0..K {
        let p = spec_at(w, a, k);
        if p != 0 {
            for (c, v) in v.iter_mut().enumerate() {
                *v = v.saturating_add(p * w.ks[k][c]);
            }
        }
    }
    v
}

/// The generic sink: any encoder, any colour: channel values handed to
/// [`Encoder::pixel`], clamped to [`Encoder::safe`] where they may leave it.
pub(crate) struct EncodeSink<'o, E, C, G> {
    pub enc: E,
    pub x: i32,
    pub y: i32,
    pub out: &'o mut [C],
    /// Shades pixel `x` of the span by the general path.
    pub general: G,
}

/// The largest specular contribution of a segment to channel `c`.
#[inline(always)]
fn spec_max<const K: usize>(w: &Walk<'_, K>, spec: &[bool; K], c: usize) -> i32 {
    let mut s = 0i32;
    for k in 0..K {
        if spec[k] {
            s = s.saturating_add(w.ks[k][c].max(0).saturating_mul(32768));
        }
    }
    s
}

impl<E: Encoder<C>, C: OutputColor, G: Fn(usize) -> C, const K: usize> Sink<K>
    for EncodeSink<'_, E, C, G>
{
    fn segment<P: Probe<K>>(
        &mut self,
        probe: &P,
        x: usize,
        jm: u32,
        a: [&Anchor<K>; 3],
        spec: [bool; K],
        w: &Walk<'_, K>,
    ) {
        let h = 2usize << jm;
        let Some(out) = self.out.get_mut(x..(x + h).min(self.out.len())) else {
            return;
        };
        let n = out.len();
        let mut q = [Quad::default(); 3];
        let mut clamp = false;
        for (c, q) in q.iter_mut().enumerate() {
            *q = Quad::fit(a[0].v[c], a[1].v[c], a[2].v[c], jm);
            let (lo, hi) = Quad::range(a[0].v[c], a[1].v[c], a[2].v[c]);
            let (s0, s1) = E::safe(c);
            if lo < s0 || hi.saturating_add(spec_max(w, &spec, c)) > s1 {
                clamp = true;
            }
        }
        let mut sp = [[0u16; 1 << MAX_LOG]; K];
        for k in 0..K {
            if spec[k] {
                probe.spec(x as i32, k, &mut sp[k][..n]);
            }
        }
        let px = self.x + x as i32;
        if clamp {
            run_encode::<E, C, K, true>(self.enc, q, &sp, spec, w, px, self.y, out);
        } else {
            run_encode::<E, C, K, false>(self.enc, q, &sp, spec, w, px, self.y, out);
        }
    }

    fn exact(&mut self, x: usize, a: &Anchor<K>, w: &Walk<'_, K>) {
        let v = exact_values(w, a);
        if let Some(p) = self.out.get_mut(x) {
            *p = self
                .enc
                .pixel(clamp_safe::<E, C>(v), self.x + x as i32, self.y);
        }
    }

    fn general(&mut self, x: usize) {
        let c = (self.general)(x);
        if let Some(p) = self.out.get_mut(x) {
            *p = c;
        }
    }
}

/// Channel values clamped to the encoder's safe range.
#[inline(always)]
fn clamp_safe<E: Encoder<C>, C: OutputColor>(v: [i32; 3]) -> [i32; 3] {
    core::array::from_fn(|c| {
        let (lo, hi) = E::safe(c);
        v[c].clamp(lo, hi)
    })
}

#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn run_encode<E: Encoder<C>, C: OutputColor, const K: usize, const CLAMP: bool>(
    enc: E,
    mut q: [Quad; 3],
    sp: &[[u16; 1 << MAX_LOG]; K],
    spec: [bool; K],
    w: &Walk<'_, K>,
    x: i32,
    y: i32,
    out: &mut [C],
) {
    let mut x = x;
    for (i, p) in out.iter_mut().enumerate() {
        let mut v = [q[0].v, q[1].v, q[2].v];
        #[allow(clippy::needless_range_loop)]
        for k in 0..K {
            if spec[k] {
                let s = i32::from(sp[k][i & ((1 << MAX_LOG) - 1)]);
                for c in 0..3 {
                    v[c] = v[c].wrapping_add(s * w.ks[k][c]);
                }
            }
        }
        *p = enc.pixel(if CLAMP { clamp_safe::<E, C>(v) } else { v }, x, y);
        for q in q.iter_mut() {
            q.v = q.v.wrapping_add(q.d1);
            q.d1 = q.d1.wrapping_add(q.d2);
        }
        if E::POSITIONAL {
            x += 1;
        }
        super::no_unroll();
    }
}

/// Whether the encoded values `v0, vm, v1` of a segment, plus up to `s` of
/// specular, stay in `[0, (max + 1)·2^(ATTR_FRAC + shift))` (the values a
/// 5-6-5 channel reads without clamping).
#[inline(always)]
fn in_565(v: [i32; 3], s: i32, max: u32) -> bool {
    let (lo, hi) = Quad::range(v[0], v[1], v[2]);
    let top =
        ((max + 1) << (crate::color::encode::vertex_shift(max) + crate::raster::ATTR_FRAC)) as i32;
    lo >= 0 && hi.saturating_add(s) < top
}

/// A channel of the packed red/blue word: the quadratic of `v >> sh` (`24 −
/// sh` fraction bits of a 5-bit channel) with its first difference chosen so
/// that the value after the segment is the end anchor's (the rounding of the
/// differences then moves a value by at most `h²/16 + ½` units inside it).
#[inline(always)]
fn quad16(v: [i32; 3], jm: u32, sh: u32) -> Quad {
    let q = Quad::fit(v[0], v[1], v[2], jm);
    let (a, b) = (v[0] >> sh, v[2] >> sh);
    let d2 = (q.d2 + (1 << (sh - 1))) >> sh;
    let j = jm + 1;
    let h = 1i32 << j;
    // b = a + h·d1 + h(h−1)/2·d2
    let rest = b - a - d2 * ((h * (h - 1)) >> 1);
    let d1 = (rest + (1 << (j - 1))) >> j;
    Quad { v: a, d1, d2 }
}

/// The diffuse table of the 5-6-5 fast path: the pixel of one light's
/// ambient + diffuse colour at `N̂·L̂ = (i + ½)/255`, `i` in `0..256`.
pub(crate) type DiffuseTable = [u16; 256];

/// The table index of `N̂·L̂` in Q23 (clamped to the table).
#[inline(always)]
fn lut_index(d: i32) -> usize {
    ((((d.max(0) as u32) * 510) >> 24) as usize).min(255)
}

/// `N̂·L̂` (Q23) below which the table index needs no clamp: `256/255`.
const LUT_TOP: i32 = ((256u64 << 23) / 255) as i32;

/// The fast sink for [`Linear`](super::Linear) 5-6-5 pixels. Segments without a
/// specular term: with one light, the pixel comes from the [`DiffuseTable`]
/// indexed by the interpolated `N̂·L̂` (one quadratic, one load per pixel);
/// otherwise red/blue (one word, as [`fill565`](super::gouraud)) and green
/// are interpolated in two passes (each keeps its values in the Cortex-M0's
/// registers). Segments with one light's specular term: one loop with the
/// power table per pixel. Segments that need clamping, or with several
/// specular terms: the generic loop.
pub(crate) struct Fast565Sink<'o, C, G> {
    pub x: i32,
    pub y: i32,
    pub out: &'o mut [C],
    /// Shades pixel `x` of the span by the general path.
    pub general: G,
    /// The diffuse table (one light).
    pub lut: Option<&'o DiffuseTable>,
}

impl<C: OutputColor, G: Fn(usize) -> C, const K: usize> Sink<K> for Fast565Sink<'_, C, G> {
    fn segment<P: Probe<K>>(
        &mut self,
        probe: &P,
        x: usize,
        jm: u32,
        a: [&Anchor<K>; 3],
        spec: [bool; K],
        w: &Walk<'_, K>,
    ) {
        let h = 2usize << jm;
        let len = self.out.len();
        let Some(out) = self.out.get_mut(x..(x + h).min(len)) else {
            return;
        };
        let nspec = spec.iter().filter(|s| **s).count();
        if nspec == 0 && K == 1 {
            if let Some(lut) = self.lut {
                let q = |i: usize| a[i].d[0] << 8;
                let d = Quad::fit(q(0), q(1), q(2), jm);
                run_lut_clamped(out, [d.v, d.d1 - d.d2, d.d2], lut);
                return;
            }
        }
        let k = spec.iter().position(|s| *s).unwrap_or(0);
        let ch = |c: usize| [a[0].v[c], a[1].v[c], a[2].v[c]];
        let max = C::CHANNEL_MAX;
        let fast = match nspec {
            0 => in_565(ch(0), 0, max[0]) && in_565(ch(1), 0, max[1]) && in_565(ch(2), 0, max[2]),
            // the specular loop clamps: the values need only stay in their fields
            1 => (0..3).all(|c| {
                let (lo, hi) = Quad::range(ch(c)[0], ch(c)[1], ch(c)[2]);
                lo >= 0 && hi.saturating_add(spec_max(w, &spec, c)) < 1 << 30
            }),
            _ => false,
        };
        if !fast {
            let mut s = EncodeSink::<super::Linear, C, &G> {
                enc: super::Linear,
                x: self.x,
                y: self.y,
                out: self.out,
                general: &self.general,
            };
            return s.segment(probe, x, jm, a, spec, w);
        }
        let g = Quad::fit(a[0].v[1], a[1].v[1], a[2].v[1], jm);
        let pack = |r: Quad, b: Quad| {
            let p = |r: i32, b: i32| ((r as u32) << 16).wrapping_add(b as u32);
            // first differences less one second difference: the loops add the
            // second difference first (each update in place)
            [p(r.v, b.v), p(r.d1 - r.d2, b.d1 - b.d2), p(r.d2, b.d2)]
        };
        let gg = [g.v as u32, (g.d1 - g.d2) as u32, g.d2 as u32];
        if nspec == 0 {
            let rb = pack(quad16(ch(0), jm, 13), quad16(ch(2), jm, 13));
            let mut green = [0u16; 1 << MAX_LOG];
            let green = &mut green[..out.len().min(1 << MAX_LOG)];
            run565_g(green, gg);
            run565_rb(out, green, rb);
        } else {
            // one more integer bit per field: room to clamp
            let rb = pack(quad16(ch(0), jm, 14), quad16(ch(2), jm, 14));
            let mut sp = [0u16; 1 << MAX_LOG];
            let sp = &mut sp[..out.len().min(1 << MAX_LOG)];
            probe.spec(x as i32, k, sp);
            run565_spec(out, sp, rb, gg, w.ks[k]);
        }
    }

    fn exact(&mut self, x: usize, a: &Anchor<K>, w: &Walk<'_, K>) {
        let v = exact_values(w, a);
        if let Some(p) = self.out.get_mut(x) {
            *p = <super::Linear as Encoder<C>>::pixel(
                &super::Linear,
                clamp_safe::<super::Linear, C>(v),
                0,
                0,
            );
        }
    }

    fn general(&mut self, x: usize) {
        let c = (self.general)(x);
        if let Some(p) = self.out.get_mut(x) {
            *p = c;
        }
    }
}

/// One light's diffuse pixels from the [`DiffuseTable`]: `N̂·L̂` in units of
/// `1 = 255·2^24` (the index is the top byte) as `[value, first difference −
/// second, second difference]`, in `[0, 256/255)` on the whole segment.
#[inline(never)]
fn run_lut<C: OutputColor>(out: &mut [C], d: [u32; 3], lut: &DiffuseTable) {
    let [mut d, mut d1, d2] = d;
    for p in out.iter_mut() {
        d1 = d1.wrapping_add(d2);
        *p = C::from_rgb565_raw(lut[(d >> 24) as usize]);
        d = d.wrapping_add(d1);
        super::no_unroll();
    }
}

/// Green of 5-6-5 pixels into `out` (the pixel's green bits): `g` with 23
/// fraction bits, as `[value, first difference − second, second difference]`.
#[inline(never)]
fn run565_g(out: &mut [u16], g: [u32; 3]) {
    let [mut g, mut dg, ddg] = g;
    for p in out.iter_mut() {
        dg = dg.wrapping_add(ddg);
        *p = ((g >> 23) << 5) as u16;
        g = g.wrapping_add(dg);
        super::no_unroll();
    }
}

/// Red and blue of 5-6-5 pixels, with the green bits `green` from
/// [`run565_g`]: `rb` = red (bits 27..32) and blue (bits 11..16) with 11
/// fraction bits each, as in [`run565_g`].
#[inline(never)]
fn run565_rb<C: OutputColor>(out: &mut [C], green: &[u16], rb: [u32; 3]) {
    let [mut rb, mut drb, ddrb] = rb;
    for (p, g) in out.iter_mut().zip(green) {
        drb = drb.wrapping_add(ddrb);
        let raw = (((rb >> 27) << 11) | ((rb << 16) >> 27)) as u16 | *g;
        *p = C::from_rgb565_raw(raw);
        rb = rb.wrapping_add(drb);
        super::no_unroll();
    }
}

/// Red/blue and green as [`run565_rb`] and [`run565_g`] (but red and blue with
/// 10 fraction bits: an integer bit to spare) plus one light's specular term
/// `x^n` (Q15) per pixel from `sp`, `ks` encoded units per unit of `x^n`; each
/// channel clamped to its maximum.
#[inline(never)]
fn run565_spec<C: OutputColor>(out: &mut [C], sp: &[u16], rb: [u32; 3], g: [u32; 3], ks: [i32; 3]) {
    let [mut rb, mut drb, ddrb] = rb;
    let [mut g, mut dg, ddg] = g;
    for (p, s) in out.iter_mut().zip(sp) {
        drb = drb.wrapping_add(ddrb);
        dg = dg.wrapping_add(ddg);
        let s = i32::from(*s);
        let srb = (((s * ks[0]) >> 14) << 16).wrapping_add((s * ks[2]) >> 14) as u32;
        let v = rb.wrapping_add(srb);
        let gv = g.wrapping_add((s * ks[1]) as u32);
        let r = (v >> 26).min(31);
        let b = ((v << 16) >> 26).min(31);
        let gg = (gv >> 23).min(63);
        *p = C::from_rgb565_raw(((r << 11) | (gg << 5) | b) as u16);
        rb = rb.wrapping_add(drb);
        g = g.wrapping_add(dg);
        super::no_unroll();
    }
}

// ---- one light, diffuse only, 5-6-5: the table walk -------------------------------

/// `N̂·L̂` of one light at a pixel, for [`walk_lut`].
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct DAnchor {
    /// `N̂·L̂` in Q23.
    pub d: i32,
    /// `1/|N|`, Q15.
    pub r: u32,
    /// Whether the normal is usable (else the general path shades the pixel).
    pub ok: bool,
}

/// The walk of a span whose pixels are a function of one light's `N̂·L̂`
/// (ambient + diffuse, one light, [`Linear`](super::Linear) 5-6-5): `N̂·L̂` is
/// interpolated quadratically between anchors and the pixel read from the
/// [`DiffuseTable`] (which also clamps `N̂·L̂ ≤ 0`: no kinks to avoid). The
/// segment length follows the same bound as [`walk`]'s ambient + diffuse part.
pub(crate) fn walk_lut<C: OutputColor, F: Fn(i32) -> DAnchor, G: Fn(usize) -> C>(
    y_q: u32,
    dd: u32,
    lut: &DiffuseTable,
    at: F,
    general: G,
    out: &mut [C],
) {
    let n = out.len();
    let dd15 = (dd >> 15) + 1;
    let mut pos = 0usize;
    let mut a0 = at(0);
    let mut j = MAX_LOG;
    while j > 2 && hw2(dd15, a0.r, j).is_none_or(|z| z > y_q) {
        j -= 1;
    }
    let one = |x: usize, a: &DAnchor, out: &mut [C]| {
        let c = if a.ok {
            C::from_rgb565_raw(lut[lut_index(a.d)])
        } else {
            general(x)
        };
        if let Some(p) = out.get_mut(x) {
            *p = c;
        }
    };
    while pos < n {
        let mut jj = j.min(log2_floor(n - pos));
        if jj < 2 || !a0.ok {
            one(pos, &a0, out);
            pos += 1;
            if pos < n {
                a0 = at(pos as i32);
            }
            continue;
        }
        let mut a1 = at((pos + (1 << jj)) as i32);
        let mut am = at((pos + (1 << (jj - 1))) as i32);
        loop {
            let ok =
                a1.ok && am.ok && hw2(dd15, a0.r.max(am.r).max(a1.r), jj).is_some_and(|z| z <= y_q);
            if ok {
                let q = Quad::fit(a0.d, am.d, a1.d, jj - 1);
                let (lo, hi) = Quad::range(a0.d, am.d, a1.d);
                let end = (pos + (1 << jj)).min(n);
                if let Some(seg) = out.get_mut(pos..end) {
                    if lo >= 0 && hi < LUT_TOP {
                        // Q23 → 1 = 255·2^24 (below 2^32): the index is the top byte
                        let u = |v: i32| (v as u32).wrapping_mul(510);
                        run_lut(seg, [u(q.v), u(q.d1 - q.d2), u(q.d2)], lut);
                    } else {
                        run_lut_clamped(seg, [q.v, q.d1 - q.d2, q.d2], lut);
                    }
                }
                pos += 1 << jj;
                a0 = a1;
                if hw2(dd15, a0.r, jj + 1).is_some_and(|z| z <= y_q) {
                    j = (jj + 1).min(MAX_LOG);
                } else {
                    j = jj;
                }
                break;
            } else if jj > 2 {
                jj -= 1;
                a1 = am;
                am = at((pos + (1 << (jj - 1))) as i32);
            } else {
                one(pos, &a0, out);
                let b = at((pos + 1) as i32);
                one(pos + 1, &b, out);
                pos += 2;
                a0 = am;
                j = 2;
                break;
            }
        }
    }
}

/// [`run_lut`] for values that may leave the table (`N̂·L̂` in Q23): clamped.
#[inline(never)]
fn run_lut_clamped<C: OutputColor>(out: &mut [C], d: [i32; 3], lut: &DiffuseTable) {
    let [mut d, mut d1, d2] = d;
    for p in out.iter_mut() {
        d1 = d1.wrapping_add(d2);
        *p = C::from_rgb565_raw(lut[lut_index(d)]);
        d = d.wrapping_add(d1);
        super::no_unroll();
    }
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
