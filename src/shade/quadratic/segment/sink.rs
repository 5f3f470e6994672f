//! The pixel loops of the segment walk ([`Sink`]): [`EncodeSink`] for any encoder
//! and colour, [`Fast565Sink`] for [`Linear`] 5-6-5 pixels (packed red/blue
//! interpolation, the diffuse table).
// the span loops index several per-light and per-channel arrays at once
#![allow(clippy::needless_range_loop)]

use super::lut::{run_lut_clamped, DiffuseTable};
use super::{Anchor, Probe, Quad, Segment, Sink, Walk, MAX_LOG};
use crate::color::OutputColor;
use crate::color::{Encoder, Linear};

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
fn exact_values<const K: usize>(w: &Walk<'_, K>, a: &Anchor<K>) -> [i32; 3] {
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
    fn segment<P: Probe<K>>(&mut self, probe: &P, seg: Segment<'_, K>, w: &Walk<'_, K>) {
        let Segment { x, jm, a, spec } = seg;
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
        crate::num::no_unroll();
    }
}

/// Whether the encoded values `v0, vm, v1` of a segment, plus up to `s` of
/// specular, stay in `[0, (max + 1)·2^(ATTR_FRAC + shift))` (the values a
/// 5-6-5 channel reads without clamping).
#[inline(always)]
fn in_565(v: [i32; 3], s: i32, max: u32) -> bool {
    let (lo, hi) = Quad::range(v[0], v[1], v[2]);
    let top =
        ((max + 1) << (crate::color::encode::vertex_shift(max) + crate::num::ATTR_FRAC)) as i32;
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

/// The fast sink for [`Linear`](crate::color::Linear) 5-6-5 pixels. Without a
/// specular term: one light reads the [`DiffuseTable`] at the interpolated
/// `N̂·L̂`; more interpolate red/blue (one word, as
/// [`fill565`](crate::shade::gouraud)) and green in two passes (each in the
/// Cortex-M0's registers). One light's specular term: one loop with the power
/// table. Clamping or several specular terms: the generic loop.
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
    fn segment<P: Probe<K>>(&mut self, probe: &P, seg: Segment<'_, K>, w: &Walk<'_, K>) {
        let Segment { x, jm, a, spec } = seg;
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
            let mut s = EncodeSink::<Linear, C, &G> {
                enc: Linear,
                x: self.x,
                y: self.y,
                out: self.out,
                general: &self.general,
            };
            return s.segment(probe, seg, w);
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
            *p = <Linear as Encoder<C>>::pixel(&Linear, clamp_safe::<Linear, C>(v), 0, 0);
        }
    }

    fn general(&mut self, x: usize) {
        let c = (self.general)(x);
        if let Some(p) = self.out.get_mut(x) {
            *p = c;
        }
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
        crate::num::no_unroll();
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
        crate::num::no_unroll();
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
        crate::num::no_unroll();
    }
}
