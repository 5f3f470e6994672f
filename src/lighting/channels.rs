//! The lighting equation of directional lights and a viewer at infinity
//! (Lambert, Blinn-Phong) in output channel units, evaluated from cosines by
//! [`IncrementalPhongShading`](crate::shade::IncrementalPhongShading) and its
//! normal-mapped form; its terms are the lighting's
//! ([`Directional::directional_terms`](super::Directional)), converted once.

use super::DirectionalTerms;
use crate::color::{OutputColor, Rgb};
use crate::num::pow::PowTable;
use crate::num::{Exponent, Scalar, Vec3};

/// `I = base + Σ_j kd_j·max(0, N·L_j) + ks_j·(N·H_j)^n` (the specular part
/// only where `N·L_j > 0`) for `K` directional lights, each term per channel
/// in output channel units · 2^8.
#[derive(Clone, Copy, Debug)]
pub struct ChannelTerms<const K: usize> {
    /// Each light's directions and colours.
    pub(crate) lights: [LightChannels; K],
    /// Constant part per channel, in channel units · 2^8, plus ½ for rounding
    /// (negative for a negative global ambient: pixels clamp at 0).
    base: [i32; 3],
    /// `x^n` over `[0, 1]` in Q14.
    pow: PowTable<14>,
}

/// One light's terms in the units of [`ChannelTerms`].
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct LightChannels {
    /// Direction to the light, Q14.
    pub l: [i32; 3],
    /// Halfway vector, Q14.
    pub h: [i32; 3],
    /// `Ld∘Kd` per channel in channel units · 2^8.
    pub kd: [i32; 3],
    /// `Ls∘Ks` per channel in channel units · 2^8.
    pub ks: [i32; 3],
}

/// A colour's channels (`C::linear_channels`) in channel units · 2^8 (from
/// their Q14 values: exact for the `Q14` tiers).
fn channel_units<C: OutputColor, S: Scalar>(c: Rgb<S>) -> [i32; 3] {
    let l = C::linear_channels(c);
    // the attribute scale is Q26: Q14 = (a + 2^11) >> 12
    let q14 = |v: S| (v.to_attr() + (1 << 11)) >> 12;
    // value (Q14, < 2) · max · 2^8 ≤ 2·255·256 < 2^17
    core::array::from_fn(|i| (q14(l[i]) * C::CHANNEL_MAX[i] as i32 * 256 + 8192) >> 14)
}

/// A Q14 vector from a tier's unit vector.
fn q14v<S: Scalar>(v: Vec3<S>) -> [i32; 3] {
    let q = |c: S| (c.to_attr() + (1 << 11)) >> 12;
    [q(v.x), q(v.y), q(v.z)]
}

impl<const K: usize> ChannelTerms<K> {
    /// The terms of the lights `terms` for output colour `C` (once per
    /// shader, out of line: its table stays off the frame's stack).
    pub(crate) fn new<C: OutputColor, S: Scalar>(terms: [DirectionalTerms<S>; K]) -> Self {
        let first = terms.first();
        ChannelTerms {
            lights: terms.map(|t| LightChannels {
                l: q14v(t.dir),
                h: q14v(t.half.unwrap_or(t.dir)),
                kd: channel_units::<C, S>(t.diffuse),
                ks: channel_units::<C, S>(t.specular),
            }),
            base: first.map_or([128; 3], |t| channel_units::<C, S>(t.base).map(|v| v + 128)),
            pow: PowTable::new(first.map_or(Exponent::ZERO, |t| t.shininess)),
        }
    }

    /// Whether any light has a specular colour.
    pub(crate) fn specular(&self) -> bool {
        self.lights.iter().any(|l| l.ks != [0; 3])
    }

    /// The constant part (emission, ambient and ½), the start of a pixel's
    /// sum.
    #[inline(always)]
    pub(crate) fn base(&self) -> [i32; 3] {
        self.base
    }

    /// Adds light `lt`'s terms at a point where `N·L = d > 0` and `N·H = h`
    /// (Q14) to `acc`: `kd·min(d, 1)` and (`SPEC`) `ks·h^n` (the caller
    /// skips a light with `d ≤ 0`: no diffuse and no specular term there).
    #[inline(always)]
    pub(crate) fn add<const SPEC: bool>(
        &self,
        acc: &mut [i32; 3],
        lt: &LightChannels,
        d: i32,
        h: i32,
    ) {
        add_term(acc, d.min(16384), &lt.kd);
        if SPEC {
            add_term(acc, self.pow.get(h), &lt.ks);
        }
    }

    /// The colour of the channel sums `acc`, each clamped to the colour's
    /// range (rounded to nearest by the ½ in the base).
    #[inline(always)]
    pub(crate) fn color<C: OutputColor>(acc: [i32; 3]) -> C {
        // (no `array::map`: at opt-level "z" it stays a call per pixel)
        let m = C::CHANNEL_MAX;
        C::from_channels([
            (acc[0] >> 8).max(0).min(m[0] as i32) as u32,
            (acc[1] >> 8).max(0).min(m[1] as i32) as u32,
            (acc[2] >> 8).max(0).min(m[2] as i32) as u32,
        ])
    }
}

/// `acc += (k·w) ≫ 14` per channel: a light term `k` (Q14) times the
/// channel weights `w`.
#[inline(always)]
fn add_term(acc: &mut [i32; 3], k: i32, w: &[i32; 3]) {
    acc[0] += (k * w[0]) >> 14;
    acc[1] += (k * w[1]) >> 14;
    acc[2] += (k * w[2]) >> 14;
}
