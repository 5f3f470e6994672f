//! Phong shading: normals interpolated per pixel, renormalised, lit per pixel.

use super::incremental::{shade_run, IncrementalState};
use super::{eye_point, Encoder, GeneralPhongShading, Kernel, ModeState, PhongShading, Shader};
use crate::num::{Flag, Off, On};
use crate::raster::interp::Varyings;
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::interp::VARYING_LIMIT;
use crate::raster::ATTR_FRAC;
use crate::num::Vec3;

impl<I: Illuminate, C> ModeState<I, C> for GeneralPhongShading {
    type State = ();
    fn state(self, _: &I) {}
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

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel
    for Shader<'_, GeneralPhongShading, I, E, C>
{
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

/// How [`PhongShading`] lights the pixels of a lighting `I`: the general
/// kernel ([`Off`]) or the incremental one ([`On`]: see
/// [`Illuminate::directional`](crate::lighting::Illuminate::directional)).
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "`PhongShading` cannot choose a kernel for the lighting `{I}`",
    note = "every `Lighting` of this crate is served; a lighting of your own implements `Illuminate` with `type Fast = fixshade::num::Off`"
)]
pub trait PhongPath<I: Illuminate, C: OutputColor>: Flag {
    /// The values interpolated.
    type Varyings: Varyings;
    /// What the shader precomputes.
    type State: Copy + core::fmt::Debug;
    /// How many values are used.
    const USED: usize;
    /// Precomputes it.
    fn state(lighting: &I) -> Self::State;
    /// The values of a vertex with unit normal `n` (and, for the general
    /// kernel, the position varyings `p`).
    fn varyings(state: &Self::State, n: &[i16; 3], p: [i32; 3]) -> Self::Varyings;
    /// The range of value `i`.
    fn safe(i: usize) -> (i32, i32);
    /// Shades a span.
    #[allow(clippy::too_many_arguments)]
    fn span<E: Encoder<C>>(
        state: &Self::State,
        lighting: &I,
        encoder: &E,
        t: &PhongTriangle,
        a: &Self::Varyings,
        d: &Self::Varyings,
        x: i32,
        y: i32,
        out: &mut [C],
    );
}

/// The value `i` of `v` (0 beyond it).
#[inline(always)]
fn at<V: Varyings>(v: &V, i: usize) -> i32 {
    v.values().get(i).copied().unwrap_or(0)
}

impl<I: Illuminate, C: OutputColor> PhongPath<I, C> for Off {
    type Varyings = [i32; 6];
    type State = ();
    const USED: usize = if I::NEEDS_POSITION { 6 } else { 3 };
    fn state(_: &I) {}
    #[inline(always)]
    fn varyings(_: &(), n: &[i16; 3], p: [i32; 3]) -> [i32; 6] {
        [
            i32::from(n[0]),
            i32::from(n[1]),
            i32::from(n[2]),
            p[0],
            p[1],
            p[2],
        ]
    }
    #[inline(always)]
    fn safe(i: usize) -> (i32, i32) {
        // normals within [−1, 1] in Q14 (Q28 with ATTR_FRAC bits), positions
        // anywhere (the tier saturates them)
        let one = 1 << (14 + ATTR_FRAC);
        if i < 3 {
            (-one, one)
        } else {
            (-(1 << 30), 1 << 30)
        }
    }
    #[inline(always)]
    fn span<E: Encoder<C>>(
        _: &(),
        lighting: &I,
        encoder: &E,
        t: &PhongTriangle,
        a: &[i32; 6],
        d: &[i32; 6],
        x: i32,
        y: i32,
        out: &mut [C],
    ) {
        let three = |v: &[i32; 6], k: usize| [v[k], v[k + 1], v[k + 2]];
        lit_span(
            lighting,
            encoder,
            t,
            three(a, 0),
            three(d, 0),
            three(a, 3),
            three(d, 3),
            x,
            y,
            out,
        )
    }
}

impl<I: Illuminate, C: OutputColor> PhongPath<I, C> for On {
    /// The normal, `N·L` and `N·H`.
    type Varyings = [i32; 5];
    /// `None` for a model the fast path does not evaluate (the general
    /// kernel then lights every pixel; no position is needed).
    type State = Option<IncrementalState<1>>;
    const USED: usize = 5;
    fn state(lighting: &I) -> Self::State {
        lighting
            .directional()
            .map(|t| IncrementalState::new::<C, I::Scalar>([t]))
    }
    #[inline(always)]
    fn varyings(state: &Self::State, n: &[i16; 3], _p: [i32; 3]) -> [i32; 5] {
        match state {
            Some(st) => st.varyings(n),
            None => [i32::from(n[0]), i32::from(n[1]), i32::from(n[2]), 0, 0],
        }
    }
    #[inline(always)]
    fn safe(_: usize) -> (i32, i32) {
        // the span code checks |N|² itself; the values must only stay inside
        // ±2 (Q14, with ATTR_FRAC bits) so that nothing wraps
        let two = 1 << (15 + ATTR_FRAC);
        (-two, two - 1)
    }
    #[inline(always)]
    fn span<E: Encoder<C>>(
        state: &Self::State,
        lighting: &I,
        encoder: &E,
        t: &PhongTriangle,
        a: &[i32; 5],
        d: &[i32; 5],
        x: i32,
        y: i32,
        out: &mut [C],
    ) {
        match state {
            Some(st) if st.spec => shade_run::<_, C, 1, true>(st, lighting, x, y, a, d, out),
            Some(st) => shade_run::<_, C, 1, false>(st, lighting, x, y, a, d, out),
            None => {
                let n = |v: &[i32; 5]| [at(v, 0), at(v, 1), at(v, 2)];
                lit_span(lighting, encoder, t, n(a), n(d), [0; 3], [0; 3], x, y, out)
            }
        }
    }
}

impl<I: Illuminate, C: OutputColor> ModeState<I, C> for PhongShading
where
    I::Fast: PhongPath<I, C>,
{
    type State = <I::Fast as PhongPath<I, C>>::State;
    fn state(self, lighting: &I) -> Self::State {
        <I::Fast as PhongPath<I, C>>::state(lighting)
    }
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel for Shader<'_, PhongShading, I, E, C>
where
    I::Fast: PhongPath<I, C>,
{
    type Color = C;
    /// The eye-space unit normal in Q14.
    type Vertex = [i16; 3];
    type Varyings = <I::Fast as PhongPath<I, C>>::Varyings;
    type Triangle = PhongTriangle;
    const USED: usize = <I::Fast as PhongPath<I, C>>::USED;
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> [i16; 3] {
        super::unit_q14(v.normal)
    }

    #[inline(always)]
    fn triangle(
        &self,
        v: [&[i16; 3]; 3],
        eye: &[[i32; 3]; 3],
    ) -> (PhongTriangle, [Self::Varyings; 3]) {
        let (t, p) = if I::NEEDS_POSITION {
            PhongTriangle::new(eye)
        } else {
            (PhongTriangle::default(), [[0; 3]; 3])
        };
        let var = [0, 1, 2].map(|k| <I::Fast as PhongPath<I, C>>::varyings(&self.state, v[k], p[k]));
        (t, var)
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        <I::Fast as PhongPath<I, C>>::safe(i)
    }

    #[inline(always)]
    fn span(
        &self,
        t: &PhongTriangle,
        a: &Self::Varyings,
        d: &Self::Varyings,
        x: i32,
        y: i32,
        out: &mut [C],
    ) {
        <I::Fast as PhongPath<I, C>>::span(
            &self.state,
            self.lighting,
            &self.encoder,
            t,
            a,
            d,
            x,
            y,
            out,
        )
    }
}
