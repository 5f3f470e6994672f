//! Flat shading: one colour per triangle, lit at its centroid.

use super::{eye_point, unit_normal, Encoder, FlatShading, Kernel, ModeState, Shader};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::raster::ATTR_FRAC;

impl<I: Illuminate, C> ModeState<I, C> for FlatShading {
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
    const FUSED_DEPTH: bool = true;

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

    #[inline(always)]
    fn span_depth(
        &self,
        t: &FlatTriangle<C>,
        _: (&[i32; 0], &[i32; 0]),
        (x, y): (i32, i32),
        z: (i32, i32),
        color: &mut [C],
        depth: &mut [u16],
    ) {
        if E::POSITIONAL {
            let (enc, a) = (self.encoder, t.a);
            super::fused_depth(z, color, depth, x, |x| enc.pixel(a, *x, y), |x| *x += 1);
        } else {
            fill_depth(t.color, z, color, depth);
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

/// One colour with the depth test fused in
/// ([`fused_depth`](super::fused_depth)): a pass that tests, writes the depth
/// and the colour of a passing pixel.
#[inline(never)]
fn fill_depth<C: Copy>(c: C, z: (i32, i32), color: &mut [C], depth: &mut [u16]) {
    super::fused_depth(z, color, depth, (), |_| c, |_| {});
}

#[cfg(test)]
mod tests {
    use super::fill_depth;
    use crate::raster::ATTR_FRAC;

    /// The fused loop writes the colour and the depth exactly where the
    /// depth test passes: strictly nearer pixels, ties and farther ones in
    /// stretches, rising and falling depths.
    #[test]
    fn fused_fill_writes_where_the_test_passes() {
        for (case, dz) in [-70_000, -1, 0, 1, 3 << ATTR_FRAC, 123_457]
            .into_iter()
            .enumerate()
        {
            let z0: i32 = 30_000 << ATTR_FRAC;
            let at = |k: usize| {
                ((z0 as u32).wrapping_add((dz as u32).wrapping_mul(k as u32)) >> ATTR_FRAC) as i32
            };
            let mut depth: std::vec::Vec<u16> = (0..100)
                .map(|k| (at(k) + ((k / 7 + case) % 3) as i32 - 1) as u16)
                .collect();
            let before = depth.clone();
            let mut color = [0u8; 100];
            fill_depth(9u8, (z0, dz), &mut color, &mut depth);
            for k in 0..100 {
                let pass = at(k) < i32::from(before[k]);
                assert_eq!(color[k] == 9, pass, "case {case} pixel {k}");
                assert_eq!(
                    i32::from(depth[k]),
                    if pass { at(k) } else { i32::from(before[k]) }
                );
            }
            assert!(color.contains(&9) && color.contains(&0));
        }
    }
}
