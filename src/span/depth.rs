//! The depth test and the pixel write of a run: the fused loops for the
//! colours the span stage writes itself ([`Fill::Solid`],
//! [`Fill::Ramp565`]) and the split one (the depth test of the run, then the
//! kernel's own colours on each passing part). Everywhere pixel `k` has depth
//! `(z + k·dz) >> ATTR_FRAC` (wrapping `u32` steps) and passes when that is
//! less than `depth[k]`, which then takes it.

use crate::num::ATTR_FRAC;
use crate::raster::interp::{get, Varyings};
use crate::shade::{pixel565, Fill, Kernel};

/// Depth-tests pixels `x..x + color.len()` of row `y` and writes the passing
/// ones with `kernel`'s colours, its values starting at `start` and stepping
/// by `step` over the whole run.
#[inline(always)]
pub(crate) fn write<K: Kernel>(
    kernel: &K,
    t: &K::Triangle,
    (start, step): (&K::Varyings, &K::Varyings),
    (x, y): (i32, i32),
    z: (i32, i32),
    color: &mut [K::Color],
    depth: &mut [u16],
) {
    match kernel.fill(t, start, step) {
        Fill::Solid(c) => solid(c, z, color, depth),
        Fill::Ramp565 { rb, drb, g, dg } => ramp565((rb, drb, g, dg), z, color, depth),
        Fill::Shaded => depth_runs(z.0, z.1, depth, |k0, k1| {
            if let Some(c) = color.get_mut(k0..k1) {
                let a = K::Varyings::from_fn(|i| {
                    get(start, i).wrapping_add(get(step, i).wrapping_mul(k0 as i32))
                });
                kernel.span(t, &a, step, x + k0 as i32, y, c);
            }
        }),
    }
}

/// One colour with the depth test fused in ([`fused`]): a pass that tests,
/// writes the depth and the colour of a passing pixel.
#[inline(never)]
fn solid<C: Copy>(c: C, z: (i32, i32), color: &mut [C], depth: &mut [u16]) {
    fused(z, color, depth, (), |_| c, |_| {});
}

/// The rounded 5-6-5 ramp `(rb, drb, g, dg)` ([`Fill::Ramp565`]) with the
/// depth test fused in ([`fused`]): a function of its own, so that the
/// loop's values fit the Cortex-M0's registers.
#[inline(never)]
fn ramp565<C: crate::color::OutputColor>(
    (rb, drb, g, dg): (u32, u32, u32, u32),
    z: (i32, i32),
    color: &mut [C],
    depth: &mut [u16],
) {
    fused(
        z,
        color,
        depth,
        (rb, g),
        |&(rb, g)| C::from_rgb565_raw(pixel565(rb, g)),
        |(rb, g)| {
            *rb = rb.wrapping_add(drb);
            *g = g.wrapping_add(dg);
        },
    );
}

/// The fused loop: a passing pixel gets the colour `pixel(&s)`;
/// `step(&mut s)` moves the kernel's state a pixel on, passing or not. One
/// pass, few live values (the 5-6-5 Gouraud loop: two registers).
#[inline(always)]
fn fused<C, S>(
    z: (i32, i32),
    color: &mut [C],
    depth: &mut [u16],
    mut s: S,
    pixel: impl Fn(&S) -> C,
    step: impl Fn(&mut S),
) {
    let (mut z, dz) = (z.0 as u32, z.1 as u32);
    let n = color.len().min(depth.len());
    let (Some(color), Some(depth)) = (color.get_mut(..n), depth.get_mut(..n)) else {
        return;
    };
    for k in 0..n {
        // below 2^16: the run's depths are in range (clamped where they needed it)
        let zi = z >> ATTR_FRAC;
        if zi < u32::from(depth[k]) {
            depth[k] = zi as u16;
            color[k] = pixel(&s);
        }
        // the values after the last pixel are not used: wrapping is harmless
        z = z.wrapping_add(dz);
        step(&mut s);
        crate::num::no_unroll();
    }
}

/// The depth test of a run's leading pixels, up to the first that fails;
/// returns how many passed. A loop of its own (no register spills on a
/// Cortex-M0).
#[inline(never)]
fn depth_prefix(z: u32, dz: u32, depth: &mut [u16]) -> usize {
    let mut z = z;
    for (k, d) in depth.iter_mut().enumerate() {
        let zi = (z >> ATTR_FRAC) as u16;
        if zi >= *d {
            return k;
        }
        *d = zi;
        // the value after the last pixel is not used: wrapping is harmless
        z = z.wrapping_add(dz);
        crate::num::no_unroll();
    }
    depth.len()
}

/// How many leading pixels of a run fail the depth test (changing nothing).
#[inline(never)]
fn depth_fails(z: u32, dz: u32, depth: &[u16]) -> usize {
    let mut z = z;
    for (k, d) in depth.iter().enumerate() {
        if ((z >> ATTR_FRAC) as u16) < *d {
            return k;
        }
        z = z.wrapping_add(dz);
        crate::num::no_unroll();
    }
    depth.len()
}

/// The depth test of a run, split from the shading: `shade(k0, k1)` is called
/// for every maximal run `k0..k1` of passing pixels, in order (see
/// [`depth_prefix`]). In the common case (every pixel passes) that is one
/// depth loop and one call.
#[inline(always)]
pub(super) fn depth_runs(z: i32, dz: i32, depth: &mut [u16], mut shade: impl FnMut(usize, usize)) {
    let n = depth.len();
    let dz = dz as u32;
    let mut z = z as u32;
    let mut k = 0;
    while k < n {
        let Some(rest) = depth.get_mut(k..) else {
            return;
        };
        let m = depth_prefix(z, dz, rest);
        if m > 0 {
            shade(k, k + m);
        }
        k += m;
        z = z.wrapping_add(dz.wrapping_mul(m as u32));
        let Some(rest) = depth.get(k..) else {
            return;
        };
        let f = depth_fails(z, dz, rest);
        k += f;
        z = z.wrapping_add(dz.wrapping_mul(f as u32));
    }
}

#[cfg(test)]
mod tests {
    use super::{ramp565, solid};
    use crate::color::OutputColor;
    use crate::num::ATTR_FRAC;
    use crate::shade::pixel565;
    use crate::test_rng::Rng;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use embedded_graphics_core::prelude::RgbColor;

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
            solid(9u8, (z0, dz), &mut color, &mut depth);
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

    /// The fused loop equals the two passes it replaces: the depth test of
    /// every pixel, then the colour of the whole run kept where it passed.
    /// Runs of 1 to 240 pixels, rising and falling depths, strips whose
    /// pixels pass, fail and tie in stretches.
    #[test]
    fn fused_span_equals_test_then_colour() {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        let (mut passed, mut failed) = (0, 0);
        // every run length from 1 to 240, eight times over
        for (case, n) in (0..1920).map(|c| (c, 1 + c % 240)) {
            let ch = |rng: &mut Rng, bits: u32| (rng.next() % (1 << bits)) as i32;
            // packed accumulators and steps (any values: the loop wraps)
            let c = [0; 4].map(|_| rng.next() as u32);
            let z0 = (ch(&mut rng, 15) + 16384) << ATTR_FRAC;
            let dz = ch(&mut rng, 16) - (1 << 15);
            let z = (z0, dz);
            let mut depth: std::vec::Vec<u16> = (0..n)
                .map(|k| {
                    let at = ((z0 as u32).wrapping_add((dz as u32).wrapping_mul(k as u32))
                        >> ATTR_FRAC) as i32;
                    // ties, passes and fails in stretches of 8
                    (at + (((k / 8 + case) % 3) as i32 - 1) * 5).clamp(0, 65535) as u16
                })
                .collect();
            let mut want_depth = depth.clone();
            // pixel k of the ramp, computed on its own
            let all: std::vec::Vec<Rgb565> = (0..n as u32)
                .map(|k| {
                    let rb = c[0].wrapping_add(c[1].wrapping_mul(k));
                    let g = c[2].wrapping_add(c[3].wrapping_mul(k));
                    Rgb565::from_rgb565_raw(pixel565(rb, g))
                })
                .collect();
            let mut want = std::vec![Rgb565::WHITE; n];
            for k in 0..n {
                let zk = (z0 as u32).wrapping_add((dz as u32).wrapping_mul(k as u32)) >> ATTR_FRAC;
                if zk < u32::from(want_depth[k]) {
                    want_depth[k] = zk as u16;
                    want[k] = all[k];
                }
            }
            let mut got = std::vec![Rgb565::WHITE; n];
            ramp565((c[0], c[1], c[2], c[3]), z, &mut got, &mut depth);
            assert_eq!(got, want, "case {case}");
            assert_eq!(depth, want_depth, "case {case}");
            passed += want.iter().filter(|p| **p != Rgb565::WHITE).count();
            failed += want.iter().filter(|p| **p == Rgb565::WHITE).count();
        }
        // the sweep tests both branches many times
        assert!(passed > 50_000 && failed > 50_000, "{passed} {failed}");
    }
}
