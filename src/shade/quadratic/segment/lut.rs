//! The table walk of [`QuadraticPhongShading`](crate::shade::QuadraticPhongShading)
//! for one light without a specular term and 5-6-5 [`Linear`](crate::color::Linear)
//! pixels: the pixel is a function of `N̂·L̂` alone, read from a 256-entry table
//! ([`DiffuseTable`]) at the quadratically interpolated `N̂·L̂`.

use super::{hw2, log2_floor, Quad, MAX_LOG};
use crate::color::OutputColor;

/// The diffuse table of the 5-6-5 fast path: the pixel of one light's
/// ambient + diffuse colour at `N̂·L̂ = (i + ½)/255`, `i` in `0..256`.
pub(crate) type DiffuseTable = [u16; 256];

/// The table index of `N̂·L̂` in Q23 (clamped to the table).
#[inline(always)]
fn lut_index(d: i32) -> usize {
    // clamped before the product: (LUT_TOP − 1)·510 < 2^32 and indexes 255
    (((d.clamp(0, LUT_TOP - 1) as u32) * 510) >> 24) as usize
}

/// `N̂·L̂` (Q23) below which the table index needs no clamp: `256/255`.
const LUT_TOP: i32 = ((256u64 << 23) / 255) as i32;

/// One light's diffuse pixels from the [`DiffuseTable`]: `N̂·L̂` as `[value, first
/// difference − second, second difference]`, either in units of `1 = 255·2^24`
/// and in `[0, 256/255)` on the whole segment (the index is the top byte), or
/// (`CLAMP`) in Q23 and anywhere (the index clamped to the table).
#[inline(never)]
fn run_lut<C: OutputColor, const CLAMP: bool>(out: &mut [C], d: [u32; 3], lut: &DiffuseTable) {
    let [mut d, mut d1, d2] = d;
    for p in out.iter_mut() {
        d1 = d1.wrapping_add(d2);
        let i = if CLAMP {
            lut_index(d as i32)
        } else {
            (d >> 24) as usize
        };
        *p = C::from_rgb565_raw(lut[i]);
        d = d.wrapping_add(d1);
        crate::num::no_unroll();
    }
}

/// [`run_lut`] of Q23 values that may leave the table.
#[inline(always)]
pub(super) fn run_lut_clamped<C: OutputColor>(out: &mut [C], d: [i32; 3], lut: &DiffuseTable) {
    run_lut::<C, true>(out, d.map(|v| v as u32), lut);
}

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
/// (ambient + diffuse, one light, [`Linear`](crate::color::Linear) 5-6-5): `N̂·L̂` is
/// interpolated quadratically between anchors and the pixel read from the
/// [`DiffuseTable`] (which also clamps `N̂·L̂ ≤ 0`: no kinks to avoid). The
/// segment length follows the same bound as [`walk`](super::walk)'s ambient + diffuse part.
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
                        run_lut::<C, false>(seg, [u(q.v), u(q.d1 - q.d2), u(q.d2)], lut);
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

#[cfg(test)]
mod tests {
    use super::{lut_index, LUT_TOP};

    /// The clamped path's index for any `N̂·L̂` in Q23: an overshoot of the
    /// quadratic beyond 1 (up to `i32::MAX`) reads the last entry, without
    /// overflowing the product (it did above 1.004: a debug panic, a wrapped index
    /// in release).
    #[test]
    fn lut_index_clamps_any_value() {
        assert_eq!(lut_index(i32::MIN), 0);
        assert_eq!(lut_index(0), 0);
        assert_eq!(lut_index(1 << 23), 255);
        assert_eq!(lut_index(LUT_TOP - 1), 255);
        for d in [LUT_TOP, 1 << 24, 1 << 30, i32::MAX] {
            assert_eq!(lut_index(d), 255, "{d}");
        }
        for d in (0..LUT_TOP).step_by(4099) {
            assert_eq!(lut_index(d), (((d as u64) * 510) >> 24).min(255) as usize);
        }
    }
}
