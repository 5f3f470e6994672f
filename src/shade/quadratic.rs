//! Quadratic Phong shading: per-pixel lighting at close to Gouraud cost, by
//! re-anchored quadratic interpolation along each span (see [`segment`]).
// the span loops index several per-light and per-channel arrays at once
#![allow(clippy::needless_range_loop)]

mod probe;
mod segment;

use super::{Encoder, Kernel, Mode, QuadraticPhongShading, Shader};
use crate::color::{OutputColor, Rgb};
use crate::lighting::{BlinnPhong, Directional, Illuminate, Lambert, Model, Phong, Specular};
use crate::num::Vec3;
use crate::num::ATTR_FRAC;
use crate::num::{Exponent, Scalar, Q14};
use probe::{F32Probe, Q14Probe};
use segment::{DiffuseTable, EncodeSink, Fast565Sink, PowTable, Probe, Walk, DFRAC, U_ONE};

/// The reflection models [`QuadraticPhongShading`] evaluates: [`Lambert`],
/// [`BlinnPhong`] and [`Phong`] (`R·V`). Brilliance, the Fresnel factor and
/// transmission are not supported (use [`PhongShading`](super::PhongShading)).
pub trait QuadraticModel: Model {}
impl QuadraticModel for Lambert {}
impl QuadraticModel for BlinnPhong {}
impl QuadraticModel for Phong {}

/// The error budget of the interpolated ambient + diffuse colour, in 8-bit
/// steps of the output.
const TAU_Q: f32 = 0.4;

/// The precomputed constants of [`QuadraticPhongShading`] for `K` directional
/// lights and a viewer at infinity.
///
/// Anchors (ends and middle of each segment) get `1/|N|` from a 448-entry
/// seed and one Newton step; between them each encoded channel is quadratic
/// (two additions per channel and pixel), except the specular term, whose
/// table coordinate of `N̂·Ĥ` or `R̂·V̂` is interpolated and `x^n` read per pixel
/// from a 65-entry table over `[x0, 1]`, `x0 = 4096^(−1/n)`. Segments where
/// `N·L` may change sign are split down to single pixels, evaluated exactly.
/// A span falls back to [`PhongShading`](super::PhongShading)'s per-pixel
/// lighting pixel by pixel where the normal is shorter than ½ (normals over
/// 120° apart) or longer than √2, and as a whole where it turns by more than ¼
/// radian per pixel.
#[derive(Clone, Copy, Debug)]
pub struct QuadraticState<const K: usize> {
    pow: PowTable,
    y_q: u32,
    dev_x: u32,
    u_mul: i32,
    u_sh: u32,
    spec: bool,
    /// Whether the table coordinate can be computed in 32 bits (`n` < 2100).
    spec_ok: bool,
    /// Linear colour coefficients after the output colour's channel map, Q14.
    base_l: [i32; 3],
    kd_l: [[i32; 3]; K],
    ks_l: [[i32; 3]; K],
    /// The same in [`Linear`](super::Linear)'s encoded units.
    lin: Coeffs<K>,
    /// Direction to each light (Q14).
    l: [[i32; 3]; K],
    /// The second direction of each light: `H` (Blinn-Phong), `V` (Phong) or
    /// zero (Lambert), Q14.
    h: [[i32; 3]; K],
    /// `L·V` of each light (Phong), Q15.
    lv: [i32; K],
    /// The `f32` tiers' anchor constants.
    fl: FloatConsts<K>,
    /// The diffuse table of the 5-6-5 fast path (one light, `Linear`).
    lut: Option<DiffuseTable>,
}

/// The `f32` anchor constants: linear colour coefficients (after the channel
/// map), `L·V`, `x0` and the table coordinate scale.
#[derive(Clone, Copy, Debug)]
struct FloatConsts<const K: usize> {
    base: [f32; 3],
    kd: [[f32; 3]; K],
    lv: [f32; K],
    x0: f32,
    /// `U_ONE/(1 − x0)`.
    u_scale: f32,
}

/// Colour coefficients in an encoder's units.
#[derive(Clone, Copy, Debug)]
struct Coeffs<const K: usize> {
    /// The constant part (and the encoder's offset), encoded units.
    base: [i32; 3],
    /// Encoded units per unit of `N̂·L̂` (Q15).
    kd: [[i32; 3]; K],
    /// Encoded units per unit of `x^n` (Q15).
    ks: [[i32; 3]; K],
}

impl<const K: usize> QuadraticState<K> {
    /// The coefficients for an encoder whose vertex values are `off + v·fs`
    /// (`v` the clamped linear channel).
    fn coeffs(&self, fs: [i32; 3], off: [i32; 3]) -> Coeffs<K> {
        let scale = |l: &[i32; 3]| -> [i32; 3] { core::array::from_fn(|c| (l[c] * fs[c]) >> 15) };
        Coeffs {
            base: core::array::from_fn(|c| {
                (off[c] << ATTR_FRAC).saturating_add(self.base_l[c].saturating_mul(fs[c]))
            }),
            kd: core::array::from_fn(|k| scale(&self.kd_l[k])),
            ks: core::array::from_fn(|k| scale(&self.ks_l[k])),
        }
    }

    fn walk(&self, ks: [[i32; 3]; K]) -> Walk<'_, K> {
        Walk {
            pow: &self.pow,
            y_q: self.y_q,
            dev_d: DEV_D,
            dev_x: self.dev_x,
            u_mul: self.u_mul,
            u_sh: self.u_sh,
            ks,
            spec: self.spec,
        }
    }
}

/// `|f''| ≤ 1.16·w²` for `f = N̂·A`: the deviation from the anchors' polyline is
/// `1.16·(h·w)²/32`, in Q15 per unit of `(h·w)²` (Q15).
const DEV_D: u32 = 1188;
/// The same for `R̂·V̂` (`|f''| ≤ 8.64·w²`).
const DEV_RV: u32 = 8848;

/// The vertex scale and offset of encoder `E` per channel (`vertex(c) = off +
/// v·fs` for the clamped linear channel `v`).
fn encoder_map<E: Encoder<C>, C: OutputColor>(enc: &E) -> ([i32; 3], [i32; 3]) {
    if E::LINEAR {
        let fs = C::CHANNEL_MAX.map(|m| (m << crate::color::encode::vertex_shift(m)) as i32);
        let off =
            C::CHANNEL_MAX.map(|m| ((1u32 << crate::color::encode::vertex_shift(m)) >> 1) as i32);
        (fs, off)
    } else {
        let b = enc.vertex(Rgb::<Q14>::BLACK);
        let w = enc.vertex(Rgb::<Q14>::WHITE);
        (core::array::from_fn(|c| w[c] - b[c]), b)
    }
}

/// Everything [`QuadraticState`] needs from a lighting, in `f32`.
struct Desc<const K: usize> {
    base: [f32; 3],
    kd: [[f32; 3]; K],
    ks: [[f32; 3]; K],
    l: [[f32; 3]; K],
    h: [[f32; 3]; K],
    v: [f32; 3],
    /// The shininess.
    n: Exponent,
    specular: Specular,
}

fn state<const K: usize, C: OutputColor>(d: &Desc<K>) -> QuadraticState<K> {
    // the output colour's channel map (luminance for grey), linear: from the basis
    let basis: [[f32; 3]; 3] = core::array::from_fn(|k| {
        let mut e = [0.0f32; 3];
        e[k] = 1.0;
        C::linear_channels(Rgb::<f32>::new(e[0], e[1], e[2]))
    });
    let map = |c: [f32; 3]| -> [f32; 3] {
        core::array::from_fn(|ch| (0..3).map(|k| basis[k][ch] * c[k]).sum())
    };
    let q14 = |c: [f32; 3]| -> [i32; 3] {
        map(c).map(|v| libm::roundf(v * 16384.0).clamp(-65536.0, 65536.0) as i32)
    };
    // `L` and `H` made unit (Q14 rounding: 5·10⁻⁵, 4 % of x^840), in f32
    // (6·10⁻⁸ relative; no f64 linked into a firmware)
    let unit = |v: [f32; 3]| -> [f32; 3] {
        let len = libm::sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if len > 0.0 {
            v.map(|c| c / len)
        } else {
            v
        }
    };
    let q14v = |v: [f32; 3]| -> [i32; 3] { unit(v).map(|c| libm::roundf(c * 16384.0) as i32) };
    let spec = d.specular != Specular::None;
    let phong = d.specular == Specular::Phong;
    let pow = PowTable::new(d.n);
    let x0 = pow.x0() as f32 / 32768.0;
    // u = (x − x0)·U_ONE/(1 − x0) = (x_q15 − x0q)·u_mul >> u_sh, u_mul < 2^15
    // (U_ONE = 2^22: u_mul/2^u_sh = 2^7/(1 − x0)); possible for 1 − x0 > 2^−8,
    // i.e. n up to about 2100 (above: the general path)
    let width = 1.0 - x0;
    let mut u_sh = 8;
    while u_sh > 0 && libm::ldexpf(1.0, u_sh as i32 + 7) / width >= 32768.0 {
        u_sh -= 1;
    }
    let u_mul = libm::roundf(libm::ldexpf(1.0, u_sh as i32 + 7) / width);
    let spec_ok = !spec || u_mul < 32768.0;
    let u_mul = u_mul.min(32767.0) as i32;
    let y = |tau: f32, f: f32| -> u32 {
        // (h·w)³·0.008·f ≤ tau  ⇔  (h·w)² ≤ (tau/(0.008·f))^(2/3)
        let r = if f > 0.0 {
            libm::powf(tau / (0.008 * f), 2.0 / 3.0)
        } else {
            1.0
        };
        (r.min(0.999) * 1_073_741_824.0) as u32
    };
    let f_q: f32 = 3.0
        * 255.0
        * (0..3)
            .map(|c| (0..K).map(|k| libm::fabsf(map(d.kd[k])[c])).sum::<f32>())
            .fold(0.0, f32::max);
    let lv = core::array::from_fn(|k| {
        let l = unit(d.l[k]);
        libm::roundf((0..3).map(|i| l[i] * d.v[i]).sum::<f32>() * 32768.0) as i32
    });
    let mut st = QuadraticState {
        pow,
        y_q: y(TAU_Q, f_q),
        dev_x: if phong { DEV_RV } else { DEV_D },
        u_mul,
        u_sh,
        spec,
        spec_ok,
        base_l: q14(d.base),
        kd_l: core::array::from_fn(|k| q14(d.kd[k])),
        ks_l: core::array::from_fn(|k| if spec { q14(d.ks[k]) } else { [0; 3] }),
        lin: Coeffs {
            base: [0; 3],
            kd: [[0; 3]; K],
            ks: [[0; 3]; K],
        },
        l: core::array::from_fn(|k| q14v(d.l[k])),
        h: core::array::from_fn(|k| if spec { q14v(d.h[k]) } else { [0; 3] }),
        lv,
        fl: FloatConsts {
            base: map(d.base),
            kd: core::array::from_fn(|k| map(d.kd[k])),
            lv: core::array::from_fn(|k| {
                let l = unit(d.l[k]);
                (0..3).map(|i| l[i] * d.v[i]).sum::<f32>()
            }),
            x0,
            u_scale: U_ONE as f32 / width,
        },
        lut: None,
    };
    let (fs, off) = encoder_map::<super::Linear, C>(&super::Linear);
    st.lin = st.coeffs(fs, off);
    if K == 1 && C::IS_RGB565 {
        // the pixel at N̂·L̂ = (i + ½)/255, rounded as Linear does
        let lin = st.lin;
        st.lut = Some(core::array::from_fn(|i| {
            let d = ((2 * i as i32 + 1) * 32768 + 255) / 510;
            let ch = |c: usize| {
                let v = lin.base[c].saturating_add(d * lin.kd[0][c]);
                let m = C::CHANNEL_MAX[c];
                let sh = crate::color::encode::vertex_shift(m) + ATTR_FRAC;
                ((v.max(0) as u32) >> sh).min(m)
            };
            ((ch(0) << 11) | (ch(1) << 5) | ch(2)) as u16
        }));
    }
    st
}

impl<S: Scalar, const K: usize, M: QuadraticModel, C: OutputColor> Mode<Directional<S, K, M>, C>
    for QuadraticPhongShading
{
    const NAME: &'static str = "phong_quad";
    type State = QuadraticState<K>;

    fn state(self, lighting: &Directional<S, K, M>) -> QuadraticState<K> {
        let v = [0.0, 0.0, 1.0];
        let terms = lighting.directional_terms();
        let desc = Desc {
            base: lighting.lighting().base().to_f32(),
            kd: terms.map(|t| t.diffuse.to_f32()),
            ks: terms.map(|t| t.specular.to_f32()),
            l: terms.map(|t| t.dir.to_f32()),
            h: terms.map(|t| match M::SPECULAR {
                Specular::Phong => v,
                _ => t.half.map(|h| h.to_f32()).unwrap_or([0.0; 3]),
            }),
            v,
            n: lighting.lighting().material().shininess,
            specular: M::SPECULAR,
        };
        state::<K, C>(&desc)
    }
}

// ---- the shader ------------------------------------------------------------------

/// A quadratic Phong shader for `K` directional lights in tier `S`.
type Quad<'l, S, const K: usize, M, E, C> =
    Shader<'l, QuadraticPhongShading, Directional<S, K, M>, E, C>;

impl<S: Scalar, const K: usize, M: QuadraticModel, E: Encoder<C>, C: OutputColor>
    Quad<'_, S, K, M, E, C>
{
    /// The general path's colour of pixel `k` of a span (the normal interpolated
    /// and normalised in the tier, the full lighting).
    #[inline(never)]
    fn general(&self, x: i32, y: i32, start: &[i32], step: &[i32], k: usize) -> C {
        let a = |i: usize| S::from_attr(start[i].wrapping_add((k as i32).wrapping_mul(step[i])));
        let n = S::normalize_interpolated(Vec3::new(a(0), a(1), a(2)));
        let p = crate::num::point_from_f32::<S>([0.0; 3]);
        self.encoder
            .encode(self.lighting.shade(&p, n), x + k as i32, y)
    }

    /// Shades one span; `start`/`step` are `[Nx, Ny, Nz, N·L₁, N·H₁, …]` (Q26).
    fn shade_run(&self, x: i32, y: i32, start: &[i32], step: &[i32], out: &mut [C]) {
        let n = out.len();
        if n == 0 {
            return;
        }
        let dn = [step[0], step[1], step[2]];
        let general = |k: usize| self.general(x, y, start, step, k);
        if dn.iter().any(|d| d.unsigned_abs() >= 1 << 24) || !self.state.spec_ok {
            // the normal turns by more than ¼ radian per pixel, or a shininess
            // above about 2100: the general path
            for (k, p) in out.iter_mut().enumerate() {
                *p = general(k);
            }
            return;
        }
        let dd = probe::turn2(&dn);
        let st = &self.state;
        let c = if E::LINEAR {
            st.lin
        } else {
            let (fs, off) = encoder_map::<E, C>(&self.encoder);
            st.coeffs(fs, off)
        };
        if let (Some(lut), 1, Specular::None) = (st.lut.as_ref(), K, M::SPECULAR) {
            if E::LINEAR && C::IS_RGB565 {
                // one light, diffuse only: the pixel is a function of N̂·L̂ (Q23)
                let (n0, nl0, dnl) = ([start[0], start[1], start[2]], start[3], step[3]);
                let d_at = move |x: i32| -> segment::DAnchor {
                    let Some(r) = probe::inv_len_at(&n0, &dn, x) else {
                        return segment::DAnchor::default();
                    };
                    let nl = nl0.wrapping_add(x.wrapping_mul(dnl)) >> 11;
                    segment::DAnchor {
                        d: (nl * r as i32) >> (DFRAC - 8),
                        r,
                        ok: true,
                    }
                };
                return segment::walk_lut(st.y_q, dd, lut, d_at, general, out);
            }
        }
        if S::FLOAT {
            let f = &st.fl;
            let (fs, off) = if E::LINEAR {
                encoder_map::<super::Linear, C>(&super::Linear)
            } else {
                encoder_map::<E, C>(&self.encoder)
            };
            // encoded units per unit of linear colour
            let unit: [f32; 3] = core::array::from_fn(|ch| (fs[ch] << ATTR_FRAC) as f32);
            let probe = F32Probe::<K, M>::new(
                st,
                core::array::from_fn(|ch| (off[ch] << ATTR_FRAC) as f32 + f.base[ch] * unit[ch]),
                core::array::from_fn(|k| core::array::from_fn(|ch| f.kd[k][ch] * unit[ch])),
                start,
                step,
            );
            self.walk_with(&probe, c.ks, n, dd, x, y, out, general);
        } else {
            let probe = Q14Probe::<K, M>::new(st, c, start, step);
            self.walk_with(&probe, c.ks, n, dd, x, y, out, general);
        }
    }

    /// The segment walk of a span with `probe`, into the fast 5-6-5 sink or the
    /// generic one.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn walk_with<P: Probe<K>, G: Fn(usize) -> C>(
        &self,
        probe: &P,
        ks: [[i32; 3]; K],
        n: usize,
        dd: u32,
        x: i32,
        y: i32,
        out: &mut [C],
        general: G,
    ) {
        let st = &self.state;
        let walk = st.walk(ks);
        if C::IS_RGB565 && E::LINEAR {
            let mut sink = Fast565Sink {
                x,
                y,
                out,
                general,
                lut: st.lut.as_ref(),
            };
            segment::walk(&walk, probe, n, dd, &mut sink);
        } else {
            let mut sink = EncodeSink {
                enc: self.encoder,
                x,
                y,
                out,
                general,
            };
            segment::walk(&walk, probe, n, dd, &mut sink);
        }
    }
}

/// The `Kernel` for `K` lights, with `N = 3 + 2K` values.
macro_rules! quadratic_lights {
    ($($k:literal => $n:literal),*) => {$(
        impl<S: Scalar, M: QuadraticModel, E: Encoder<C>, C: OutputColor> Kernel
            for Quad<'_, S, $k, M, E, C>
        {
            super::normal_kernel_items!($n);
            /// The normal, then `N·L` and `N·H` (or `N·V`) per light (Q14).
            type Varyings = [i32; $n];

            #[inline(always)]
            fn triangle(&self, v: [&[i16; 3]; 3], _eye: &[[i32; 3]; 3]) -> ((), [[i32; $n]; 3]) {
                // the normal and N·L, N·H (or N·V) per light (Q14)
                let var = v.map(|n| {
                    let n = n.map(i32::from);
                    let mut a = [0i32; $n];
                    a[..3].copy_from_slice(&n);
                    for j in 0..$k {
                        let dot = |d: &[i32; 3]| (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) >> 14;
                        a[3 + 2 * j] = dot(&self.state.l[j]);
                        a[4 + 2 * j] = dot(&self.state.h[j]);
                    }
                    a
                });
                ((), var)
            }

            #[inline(always)]
            fn span(&self, _t: &(), a: &[i32; $n], d: &[i32; $n], x: i32, y: i32, out: &mut [C]) {
                // Q14 with ATTR_FRAC bits (Q28) → Q26
                self.shade_run(x, y, &a.map(|v| v >> 2), &d.map(|v| v >> 2), out)
            }
        }
    )*};
}
quadratic_lights!(1 => 5, 2 => 7, 3 => 9, 4 => 11);
