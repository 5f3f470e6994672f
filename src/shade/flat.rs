//! Flat shading: one colour per triangle, lit at its centroid.

use super::{eye_point, unit_normal, Encoder, Fill, FlatShading, Kernel, Mode, Shader};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::ATTR_FRAC;

impl<I, C> Mode<I, C> for FlatShading {
    const NAME: &'static str = "flat";
    type State = ();
    fn state(self, _: &I) {}
}

/// A flat triangle in the mesh renderer: its encoded colour.
#[derive(Clone, Copy, Debug)]
pub struct FlatTriangle<C> {
    /// Encoder vertex values with [`ATTR_FRAC`] bits.
    a: [i32; 3],
    /// The pixel, for encoders that do not depend on the position.
    color: C,
}

/// `⌊x / 3⌋` rounded toward zero for `|x| < 2^31`.
#[inline]
fn third(x: i32) -> i32 {
    x / 3
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor + core::fmt::Debug> Kernel
    for Shader<'_, FlatShading, I, E, C>
{
    type Color = C;
    /// The eye-space unit normal in Q14.
    type Vertex = [i16; 3];
    type Triangle = FlatTriangle<C>;
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;
    const FILLS: bool = true;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> [i16; 3] {
        super::unit_q14(v.normal)
    }

    type Varyings = [i32; 0];

    fn triangle(&self, v: [&[i16; 3]; 3], p: &[[i32; 3]; 3]) -> (FlatTriangle<C>, [[i32; 0]; 3]) {
        // the normalised sum of the unit vertex normals (Q14, |sum| ≤ 3·2^14)
        let n =
            core::array::from_fn(|i| i32::from(v[0][i]) + i32::from(v[1][i]) + i32::from(v[2][i]));
        let pos = if I::NEEDS_POSITION {
            // centroid p0 + (d1 + d2)/3, the differences kept within ±2^30
            // and divided apart (their sum may not fit 32 bits)
            core::array::from_fn(|i| {
                let d = |k: usize| {
                    (i64::from(p[k][i]) - i64::from(p[0][i])).clamp(-(1 << 30), 1 << 30) as i32
                };
                let (d1, d2) = (d(1), d(2));
                let c = third(d1) + third(d2) + third(d1 % 3 + d2 % 3);
                p[0][i].saturating_add(c)
            })
        } else {
            [0; 3]
        };
        let c = self
            .lighting
            .shade(&eye_point::<I::Scalar>(pos), unit_normal::<I::Scalar>(n));
        let a = self.encoder.vertex(c).map(|v| v << ATTR_FRAC);
        let t = FlatTriangle {
            a,
            color: self.encoder.pixel(a, 0, 0),
        };
        // one colour: nothing is interpolated
        (t, [[]; 3])
    }

    /// One colour, unless the encoder depends on the position (dithering).
    #[inline(always)]
    fn fill(&self, t: &FlatTriangle<C>, _: &[i32; 0], _: &[i32; 0]) -> Fill<C> {
        if E::POSITIONAL {
            Fill::Shaded
        } else {
            Fill::Solid(t.color)
        }
    }

    #[inline(always)]
    fn span(
        &self,
        t: &FlatTriangle<C>,
        _: &[i32; 0],
        _: &[i32; 0],
        x: i32,
        y: i32,
        color: &mut [C],
    ) {
        if E::POSITIONAL {
            for (x, c) in (x..).zip(color.iter_mut()) {
                *c = self.encoder.pixel(t.a, x, y);
            }
        } else {
            color.fill(t.color);
        }
    }
}
