//! Phong shading: normals interpolated per pixel, renormalised, lit per pixel.

use super::{eye_point, Encoder, Kernel, ModeState, PhongShading, Shader};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::interp::VARYING_LIMIT;
use crate::raster::ATTR_FRAC;
use crate::num::Vec3;

impl<I: Illuminate, C> ModeState<I, C> for PhongShading {
    type State = ();
    fn state(_: &I) {}
}

/// A Phong triangle: where its interpolated eye-space positions are measured
/// from (vertex 0, Q16.16) and their shift (the varyings hold
/// `(eye − origin) >> shift`).
#[derive(Clone, Copy, Debug, Default)]
pub struct PhongTriangle {
    origin: [i32; 3],
    shift: u32,
}

impl PhongTriangle {
    /// The triangle of eye positions `eye` and the position varyings of its
    /// corners (within ±2^15 − 1).
    #[inline]
    pub(crate) fn new(eye: &[[i32; 3]; 3]) -> (PhongTriangle, [[i32; 3]; 3]) {
        let o = eye[0];
        let rel = eye.map(|e| core::array::from_fn(|i| i64::from(e[i]) - i64::from(o[i])));
        let big = rel
            .iter()
            .flatten()
            .fold(0u64, |m: u64, v: &i64| m.max(v.unsigned_abs()));
        let mut shift = 0;
        while big >> shift > (VARYING_LIMIT as u64) {
            shift += 1;
        }
        let v = rel.map(|r: [i64; 3]| r.map(|c| (c >> shift) as i32));
        (PhongTriangle { origin: o, shift }, v)
    }

    /// The eye position (Q16.16) of interpolated position varyings `a` (with
    /// [`ATTR_FRAC`] bits).
    #[inline(always)]
    pub(crate) fn position(&self, a: [i32; 3]) -> [i32; 3] {
        let sh = ATTR_FRAC as i32 - self.shift as i32;
        core::array::from_fn(|i| {
            let r = if sh > 0 {
                ((a[i] >> (sh - 1)) + 1) >> 1
            } else {
                a[i].wrapping_shl((-sh) as u32)
            };
            self.origin[i].wrapping_add(r)
        })
    }
}

/// The per-pixel Phong loop: the normal (Q14 with [`ATTR_FRAC`] bits) from
/// `n` stepping by `dn`, renormalised with the tier's
/// [`Scalar::normalize_interpolated`]; the position from `p` stepping by `dp`
/// (`t`'s position varyings) when the lighting reads it; every pixel lit with
/// the full model.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn lit_span<I: Illuminate, E: Encoder<C>, C: OutputColor>(
    lighting: &I,
    encoder: &E,
    t: &PhongTriangle,
    n: [i32; 3],
    dn: [i32; 3],
    p: [i32; 3],
    dp: [i32; 3],
    x: i32,
    y: i32,
    out: &mut [C],
) {
    let (mut n, mut p) = (n, p);
    for (x, c) in (x..).zip(out.iter_mut()) {
        // Q14 normal with ATTR_FRAC bits → the tier's attribute (Q26)
        let nn = I::Scalar::normalize_interpolated(Vec3::new(
            I::Scalar::from_attr(n[0] >> 2),
            I::Scalar::from_attr(n[1] >> 2),
            I::Scalar::from_attr(n[2] >> 2),
        ));
        let pos = if I::NEEDS_POSITION {
            eye_point::<I::Scalar>(t.position(p))
        } else {
            eye_point::<I::Scalar>([0; 3])
        };
        *c = encoder.encode(lighting.shade(&pos, nn), x, y);
        for i in 0..3 {
            // the values after the last pixel are not used: wrapping is harmless
            n[i] = n[i].wrapping_add(dn[i]);
            if I::NEEDS_POSITION {
                p[i] = p[i].wrapping_add(dp[i]);
            }
        }
    }
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel for Shader<'_, PhongShading, I, E, C> {
    type Color = C;
    /// The eye-space unit normal in Q14.
    type Vertex = [i16; 3];
    /// The normal (Q14), then the position (see [`PhongTriangle`]) when the
    /// lighting reads it.
    type Varyings = [i32; 6];
    type Triangle = PhongTriangle;
    const USED: usize = if I::NEEDS_POSITION { 6 } else { 3 };
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> [i16; 3] {
        super::unit_q14(v.normal)
    }

    #[inline(always)]
    fn triangle(&self, v: [&[i16; 3]; 3], eye: &[[i32; 3]; 3]) -> (PhongTriangle, [[i32; 6]; 3]) {
        let (t, p) = if I::NEEDS_POSITION {
            PhongTriangle::new(eye)
        } else {
            (PhongTriangle::default(), [[0; 3]; 3])
        };
        let var = core::array::from_fn(|k| {
            let n = v[k];
            let p = p[k];
            [
                i32::from(n[0]),
                i32::from(n[1]),
                i32::from(n[2]),
                p[0],
                p[1],
                p[2],
            ]
        });
        (t, var)
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        // normals must stay within [−1, 1] in Q14 (Q28 with ATTR_FRAC bits),
        // positions anywhere (the tier saturates them)
        let one = 1 << (14 + ATTR_FRAC);
        if i < 3 {
            (-one, one)
        } else {
            (-(1 << 30), 1 << 30)
        }
    }

    #[inline(always)]
    fn span(&self, t: &PhongTriangle, a: &[i32; 6], d: &[i32; 6], x: i32, y: i32, out: &mut [C]) {
        lit_span(
            self.lighting,
            &self.encoder,
            t,
            [a[0], a[1], a[2]],
            [d[0], d[1], d[2]],
            [a[3], a[4], a[5]],
            [d[3], d[4], d[5]],
            x,
            y,
            out,
        )
    }
}
