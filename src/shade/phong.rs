//! Per-pixel Phong shading: [`PhongShading`] lets the lighting choose the
//! kernel, [`GeneralPhongShading`] names the general one.

use super::incremental::{shade_run, IncrementalState};
use super::perpixel::{self, GeneralSurface, HasSources, PixelTriangle, Plain};
use super::{Encoder, GeneralPhongShading, Kernel, ModeState, PhongShading, Shader};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::{Flag, Off, On};
use crate::raster::interp::Varyings;

impl GeneralSurface for GeneralPhongShading {
    type Features = Plain;
    type Sources = ();
    fn sources(self) {}
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
    /// The triangle of unit normals `n` (Q14) and eye positions `eye`, and
    /// the values at its corners.
    fn triangle(
        state: &Self::State,
        n: [&[i16; 3]; 3],
        eye: &[[i32; 3]; 3],
    ) -> (PixelTriangle, [Self::Varyings; 3]);
    /// The range of value `i`.
    fn safe(i: usize) -> (i32, i32);
    /// Shades a span.
    #[allow(clippy::too_many_arguments)]
    fn span<E: Encoder<C>>(
        state: &Self::State,
        lighting: &I,
        encoder: &E,
        t: &PixelTriangle,
        a: &Self::Varyings,
        d: &Self::Varyings,
        x: i32,
        y: i32,
        out: &mut [C],
    );
}

impl<I: Illuminate, C: OutputColor> PhongPath<I, C> for Off {
    type Varyings = [i32; 6];
    type State = ();
    const USED: usize = perpixel::used::<Plain, I>();
    fn state(_: &I) {}
    #[inline(always)]
    fn triangle(_: &(), n: [&[i16; 3]; 3], eye: &[[i32; 3]; 3]) -> (PixelTriangle, [[i32; 6]; 3]) {
        if I::NEEDS_POSITION {
            perpixel::triangle::<Plain, true>(n, eye)
        } else {
            perpixel::triangle::<Plain, false>(n, eye)
        }
    }
    #[inline(always)]
    fn safe(i: usize) -> (i32, i32) {
        perpixel::safe::<Plain>(i)
    }
    #[inline(always)]
    fn span<E: Encoder<C>>(
        _: &(),
        lighting: &I,
        encoder: &E,
        t: &PixelTriangle,
        a: &[i32; 6],
        d: &[i32; 6],
        x: i32,
        y: i32,
        out: &mut [C],
    ) {
        let src = ().get();
        if I::NEEDS_POSITION {
            perpixel::span::<Plain, I, E, C, true>(lighting, encoder, &src, t, a, d, x, y, out)
        } else {
            perpixel::span::<Plain, I, E, C, false>(lighting, encoder, &src, t, a, d, x, y, out)
        }
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
    fn triangle(
        state: &Self::State,
        n: [&[i16; 3]; 3],
        _: &[[i32; 3]; 3],
    ) -> (PixelTriangle, [[i32; 5]; 3]) {
        let var = n.map(|n| match state {
            Some(st) => st.varyings(n),
            None => [i32::from(n[0]), i32::from(n[1]), i32::from(n[2]), 0, 0],
        });
        (PixelTriangle::default(), var)
    }
    #[inline(always)]
    fn safe(_: usize) -> (i32, i32) {
        super::normal_range()
    }
    #[inline(always)]
    fn span<E: Encoder<C>>(
        state: &Self::State,
        lighting: &I,
        encoder: &E,
        t: &PixelTriangle,
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
                // the normal alone (a directional lighting reads no position)
                let six = |v: &[i32; 5]| [v[0], v[1], v[2], 0, 0, 0];
                let src = ().get();
                perpixel::span::<Plain, I, E, C, false>(
                    lighting,
                    encoder,
                    &src,
                    t,
                    &six(a),
                    &six(d),
                    x,
                    y,
                    out,
                )
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
    type Triangle = PixelTriangle;
    fn check(&self) -> Result<(), crate::error::RenderError> {
        self.check_lights()
    }
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
    ) -> (PixelTriangle, [Self::Varyings; 3]) {
        <I::Fast as PhongPath<I, C>>::triangle(&self.state, v, eye)
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        <I::Fast as PhongPath<I, C>>::safe(i)
    }

    #[inline(always)]
    fn span(
        &self,
        t: &PixelTriangle,
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
