//! The per-frame transform in integers, for cores without an FPU:
//! [`FixedCamera::mesh_transform`] combines a [`FixedCamera`] with a [`Pose`]
//! into the [`MeshTransform`] that [`Camera::mesh_transform`] builds from
//! `f32` (64-bit products from 16 × 16-bit ones, [`crate::num::wide`]).

use super::{Camera, ClipSpace, EyeRows, MeshTransform, NormalRows, Projection, Row};
use crate::error::ParamError;
use crate::num::at3;
use crate::num::wide::mul_i32;
use core::marker::PhantomData;

/// An angle as a fraction of a turn: `65536` is 360°, so every `u16` is an
/// angle and additions wrap correctly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Angle(pub u16);

impl Angle {
    /// From degrees (rounded to the nearest 1/65536 turn), for constants.
    pub const fn degrees(d: i32) -> Angle {
        Angle(((d.rem_euclid(360) as u32 * 65536 + 180) / 360) as u16)
    }

    /// `(sin, cos)` in Q30, within 2·10⁻⁵ of the exact values (a quarter-wave
    /// table of 129 entries, linearly interpolated).
    pub fn sin_cos(self) -> (i32, i32) {
        let a = self.0;
        // quadrant, then the position in it (14 bits)
        let quad = a >> 14;
        let r = a & 0x3FFF;
        let s = quarter_sin(r);
        let c = quarter_sin(0x4000 - r);
        match quad {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        }
    }
}

/// `sin(2π·r/65536)` in Q30 for `r` in `0..=16384` (a quarter turn).
fn quarter_sin(r: u16) -> i32 {
    let r = u32::from(r).min(0x4000);
    // 128 intervals of 128 steps each
    let i = (r >> 7) as usize;
    let f = (r & 0x7F) as i32;
    let a = SIN_Q30[i.min(128)];
    let b = SIN_Q30[(i + 1).min(128)];
    // |b − a| < 2^24, f < 2^7: the product fits
    a + (((b - a) * f + 64) >> 7)
}

/// `sin(k·π/256)` in Q30, `k = 0..=128`.
static SIN_Q30: [i32; 129] = {
    let mut t = [0i32; 129];
    let mut k = 0;
    while k <= 128 {
        let (s, _) = crate::num::sin_cos(k as f64 * core::f64::consts::PI / 256.0);
        let v = s * (1u64 << 30) as f64;
        t[k] = (if v >= 0.0 { v + 0.5 } else { v - 0.5 }) as i32;
        k += 1;
    }
    t
};

/// A model transform in fixed point: `p ↦ s·R·p + t` with `R` a rotation, `s`
/// a uniform scale (negative: mirrored) and `t` a translation. Rotation and
/// scale are held as one matrix in Q24 (elements up to ±128), the
/// translation in Q16.16 model units (±32 768).
///
/// ```
/// use fixshade::camera::{Angle, Pose};
/// // a quarter turn about y takes x to −z
/// let p = Pose::rotate_y(Angle::degrees(90));
/// assert_eq!(p.apply([1 << 16, 0, 0]), [0, 0, -(1 << 16)]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Pose {
    /// `s·R` in Q24.
    linear: [[i32; 3]; 3],
    /// `t` in Q16.16.
    translate: [i32; 3],
}

const ONE_Q24: i32 = 1 << 24;

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    /// No transformation.
    pub const IDENTITY: Pose = Pose {
        linear: [[ONE_Q24, 0, 0], [0, ONE_Q24, 0], [0, 0, ONE_Q24]],
        translate: [0; 3],
    };

    fn rotation(axis: usize, a: Angle) -> Pose {
        let (s, c) = a.sin_cos();
        // Q30 → Q24
        let (s, c) = (
            round_shift(i64::from(s), 6) as i32,
            round_shift(i64::from(c), 6) as i32,
        );
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut l = [[0; 3]; 3];
        l[axis][axis] = ONE_Q24;
        l[i][i] = c;
        l[i][j] = -s;
        l[j][i] = s;
        l[j][j] = c;
        Pose {
            linear: l,
            translate: [0; 3],
        }
    }

    /// A rotation about the x axis (y towards z).
    pub fn rotate_x(a: Angle) -> Pose {
        Self::rotation(0, a)
    }

    /// A rotation about the y axis (z towards x).
    pub fn rotate_y(a: Angle) -> Pose {
        Self::rotation(1, a)
    }

    /// A rotation about the z axis (x towards y).
    pub fn rotate_z(a: Angle) -> Pose {
        Self::rotation(2, a)
    }

    /// A uniform scale by `s` in Q16.16 (negative mirrors).
    ///
    /// # Errors
    ///
    /// [`ParamError::OutOfRange`] for `|s| ≥ 128` or `s = 0`.
    pub fn scale(s: i32) -> Result<Pose, ParamError> {
        if s == 0 || s.unsigned_abs() >= 128 << 16 {
            return Err(ParamError::OutOfRange("scale"));
        }
        let v = s << 8;
        Ok(Pose {
            linear: [[v, 0, 0], [0, v, 0], [0, 0, v]],
            translate: [0; 3],
        })
    }

    /// A translation by `t` in Q16.16 model units.
    pub const fn translate(t: [i32; 3]) -> Pose {
        Pose {
            linear: Self::IDENTITY.linear,
            translate: t,
        }
    }

    /// `self` after `first` (as [`Mat4::mul`](crate::num::Mat4::mul):
    /// `a.mul(&b)` applies `b` first). Saturates where an element would leave its range.
    pub fn mul(&self, first: &Pose) -> Pose {
        let mut l = [[0i32; 3]; 3];
        let mut t = [0i32; 3];
        for i in 0..3 {
            for (j, e) in l[i].iter_mut().enumerate() {
                let s: i64 = (0..3)
                    .map(|k| mul_i32(self.linear[i][k], first.linear[k][j]))
                    .sum();
                *e = saturate(round_shift(s, 24));
            }
            let s: i64 = (0..3)
                .map(|k| mul_i32(self.linear[i][k], first.translate[k]))
                .sum();
            t[i] = saturate(round_shift(s, 24) + i64::from(self.translate[i]));
        }
        Pose {
            linear: l,
            translate: t,
        }
    }

    /// The transformed point of `p` (Q16.16), saturated.
    pub fn apply(&self, p: [i32; 3]) -> [i32; 3] {
        core::array::from_fn(|i| {
            let s: i64 = (0..3).map(|k| mul_i32(self.linear[i][k], p[k])).sum();
            saturate(round_shift(s, 24) + i64::from(self.translate[i]))
        })
    }
}

/// `round(v / 2^s)` for `s > 0`, `v·2^−s` for `s ≤ 0` (saturated to ±2^62).
#[inline]
fn round_shift(v: i64, s: i32) -> i64 {
    if s > 0 {
        if s >= 63 {
            0
        } else {
            (v + (1i64 << (s - 1))) >> s
        }
    } else {
        let l = (-s).min(62) as u32;
        let lim = (1i64 << 62) >> l;
        if v > lim {
            1i64 << 62
        } else if v < -lim {
            -(1i64 << 62)
        } else {
            v << l
        }
    }
}

#[inline]
fn saturate(v: i64) -> i32 {
    if v > i64::from(i32::MAX) {
        i32::MAX
    } else if v < i64::from(i32::MIN) {
        i32::MIN
    } else {
        v as i32
    }
}

/// Bits of `|v|` (0 for 0).
#[inline]
fn bits(v: i64) -> i32 {
    64 - v.unsigned_abs().leading_zeros() as i32
}

/// One row of a matrix as `i32` elements `c·2^−e` (the largest in
/// `[2^28, 2^29)`), the translation last.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct WideRow {
    c: [i32; 4],
    e: i32,
}

impl WideRow {
    fn new(r: [f32; 4]) -> WideRow {
        let max = r.iter().fold(0.0f32, |m, v| m.max(v.abs()));
        let e = if max > 0.0 {
            29 - libm::frexpf(max).1
        } else {
            0
        }
        .clamp(-100, 100);
        WideRow {
            c: r.map(|v| libm::roundf(libm::ldexpf(v, e)) as i32),
            e,
        }
    }

    /// The row after pose `m`, per raw position unit of a mesh with `frac`
    /// fraction bits: the linear sums (scale `2^−(e + 24 + frac)`) and the
    /// translation (scale `2^−(e + 16)`), exact.
    fn times(&self, m: &Pose) -> ([i64; 3], i64) {
        let lin =
            core::array::from_fn(|j| (0..3).map(|k| mul_i32(self.c[k], m.linear[k][j])).sum());
        let t = (0..3)
            .map(|k| mul_i32(self.c[k], m.translate[k]))
            .sum::<i64>()
            + (i64::from(self.c[3]) << 16);
        (lin, t)
    }
}

/// The row's natural fraction bits (elements in `[2^28, 2^29)`, translation
/// below 2^30), as [`Row::new`] chooses them.
fn natural(lin: &[i64; 3], t: i64, e: i32, mfrac: i32) -> i32 {
    // element = lin·2^(frac + 16 − e − 24 − mfrac); translation = t·2^(frac − e − 16)
    let b = lin.iter().map(|&v| bits(v)).max().unwrap_or(0);
    let f_lin = if b > 0 {
        29 - b - 16 + e + 24 + mfrac
    } else {
        i32::MAX
    };
    let bt = bits(t);
    let f_t = if bt > 0 { 29 - bt + e + 16 } else { i32::MAX };
    let f = f_lin.min(f_t);
    if f == i32::MAX {
        0
    } else {
        f.clamp(-60, 60)
    }
}

fn row_at(lin: &[i64; 3], t: i64, e: i32, mfrac: i32, frac: i32) -> Row {
    let sh = e + 24 + mfrac - 16 - frac;
    Row {
        e: lin.map(|v| saturate(round_shift(v, sh))),
        t: saturate(round_shift(t, e + 16 - frac)),
        frac,
    }
}

/// A camera converted for integer per-frame transforms: built once from a
/// [`Camera`] in `f32`, then [`FixedCamera::mesh_transform`] every frame.
///
/// ```
/// use fixshade::camera::{Angle, Camera, FixedCamera, Pose};
/// use fixshade::num::Mat4;
/// use fixshade::camera::Viewport;
/// let s = 1.0 / 0.85;
/// let cam = Camera::orthographic(-s, s, -s, s, 1.0, 10.0, Viewport::new(0, 0, 240, 240)?)?
///     .with_view(Mat4::translate([0.0, 0.0, -5.0]));
/// let fixed = FixedCamera::new(&cam)?; // once, at start-up
/// // every frame: integers only
/// let t = fixed.mesh_transform(&Pose::rotate_y(Angle(1234)), 14)?;
/// let f = cam.mesh_transform(&Mat4::rotate_y(1234.0 / 65536.0 * core::f32::consts::TAU), 14)?;
/// let (a, b) = (t.project([16384, 0, 0]).unwrap(), f.project([16384, 0, 0]).unwrap());
/// assert!((a.x - b.x).abs() <= 1 && (a.y - b.y).abs() <= 1);
/// # Ok::<(), fixshade::error::ParamError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedCamera<P: Projection> {
    /// Output rows x, y, z, w of `viewport · projection · view` (per world unit).
    out: [WideRow; 4],
    /// The rows of `view` (eye space).
    eye: [WideRow; 3],
    /// The view's linear part with one exponent (for the normal matrix).
    view3: [[i32; 3]; 3],
    centre: [i32; 2],
    near: f32,
    near_w: [i32; 2],
    kind: PhantomData<P>,
}

impl<P: Projection> FixedCamera<P> {
    /// Converts `camera` (in `f32`, once).
    ///
    /// # Errors
    ///
    /// [`ParamError::NotFinite`] for a non-finite matrix;
    /// [`ParamError::OutOfRange`]`("view")` when the view matrix is not a
    /// rotation with a uniform scale and a translation (the integer normal
    /// matrix relies on it).
    pub fn new(camera: &Camera<P>) -> Result<Self, ParamError> {
        // the f32 path's rows for the identity model, per world unit
        let view = camera.view();
        let pv = camera.projection().mul(view);
        if !pv.is_finite() {
            return Err(ParamError::NotFinite("matrix"));
        }
        let ([w8, h8], [cx, cy]) = camera.viewport().scale_centre();
        let m = &pv.m;
        let k = |r: [f32; 4], s: f32, c: f32| {
            WideRow::new([r[0] * s, r[1] * s, r[2] * s, r[3] * s + c])
        };
        let out = if P::PERSPECTIVE {
            [
                k(m[0], w8, 0.0),
                k(m[1], -h8, 0.0),
                k(m[2], 1.0, 0.0),
                k(m[3], 1.0, 0.0),
            ]
        } else {
            [
                k(m[0], w8, cx),
                k(m[1], -h8, cy),
                k(m[2], 65535.0 * 0.5, 65535.0 * 0.5),
                WideRow::default(),
            ]
        };
        // the view must be a similarity: rows orthogonal, of equal length
        let v = &view.m;
        let dot = |a: usize, b: usize| (0..3).map(|j| v[a][j] * v[b][j]).sum::<f32>();
        let len = dot(0, 0);
        let tol = 1e-4 * len;
        if !(len > 0.0)
            || (dot(1, 1) - len).abs() > tol
            || (dot(2, 2) - len).abs() > tol
            || dot(0, 1).abs() > tol
            || dot(0, 2).abs() > tol
            || dot(1, 2).abs() > tol
        {
            return Err(ParamError::OutOfRange("view"));
        }
        let max = v
            .iter()
            .flat_map(|r| r[..3].iter())
            .fold(0.0f32, |a, x| a.max(x.abs()));
        let e = 29 - libm::frexpf(max).1;
        let view3 = core::array::from_fn(|i| {
            core::array::from_fn(|j| libm::roundf(libm::ldexpf(v[i][j], e)) as i32)
        });
        Ok(FixedCamera {
            out,
            eye: [0, 1, 2].map(|i| WideRow::new(v[i])),
            view3,
            centre: [cx as i32, cy as i32],
            near: camera.near(),
            near_w: [
                // near in w units is near·2^frac: kept as mantissa and exponent
                libm::roundf(libm::ldexpf(camera.near(), 24)) as i32,
                24,
            ],
            kind: PhantomData,
        })
    }

    /// The transform of a mesh with pose `model` whose positions carry `frac`
    /// fraction bits, in integers: 32-bit multiplications only (exact 64-bit
    /// products from 16-bit ones), no soft float, no division.
    ///
    /// # Errors
    ///
    /// [`ParamError::OutOfRange`] for `frac > 15`.
    pub fn mesh_transform(&self, model: &Pose, frac: u8) -> Result<MeshTransform<P>, ParamError> {
        if frac > 15 {
            return Err(ParamError::OutOfRange("frac"));
        }
        let mf = i32::from(frac);
        let wide = self.out.map(|r| (r.times(model), r.e));
        let rows: [Row; 4];
        let common;
        if P::PERSPECTIVE {
            let f = wide
                .iter()
                .map(|((l, t), e)| natural(l, *t, *e, mf))
                .min()
                .unwrap_or(0);
            rows = wide.map(|((l, t), e)| row_at(&l, t, e, mf, f));
            common = f;
        } else {
            rows = wide.map(|((l, t), e)| row_at(&l, t, e, mf, natural(&l, t, e, mf)));
            common = 0;
        }
        let [x, y, z, w] = rows;
        let w = if P::PERSPECTIVE { w } else { Row::default() };
        let near_w = if P::PERSPECTIVE {
            // near·2^common
            let v = round_shift(i64::from(self.near_w[0]), self.near_w[1] - common);
            saturate(v).max(1)
        } else {
            1
        };
        let eye = self.eye.map(|r| {
            let (l, t) = r.times(model);
            row_at(&l, t, r.e, mf, natural(&l, t, r.e, mf))
        });
        // view·model = σ·Q (σ > 0, Q orthogonal: both are similarities), whose
        // normal matrix (cofactors, sign-corrected as in `Mat4::normal_matrix`)
        // is σ²·Q: view·model itself, up to a positive factor
        let mut n = [[0i64; 3]; 3];
        for (row, v3) in n.iter_mut().zip(&self.view3) {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (v3.iter().zip(&model.linear))
                    .map(|(&a, m)| mul_i32(a, at3(m, j)))
                    .sum();
            }
        }
        let b = n.iter().flatten().map(|&v| bits(v)).max().unwrap_or(0);
        let normal = NormalRows {
            // the largest element in (2^13, 2^14]
            e: n.map(|r| {
                r.map(|v| {
                    if b > 0 {
                        round_shift(v, b - 14).clamp(-16384, 16384) as i16
                    } else {
                        0
                    }
                })
            }),
        };
        Ok(MeshTransform {
            x,
            y,
            z,
            w,
            space: if P::PERSPECTIVE {
                ClipSpace::perspective(self.centre, near_w)
            } else {
                ClipSpace::SCREEN
            },
            near: self.near,
            normal,
            eye: EyeRows { r: eye },
            kind: PhantomData,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Viewport;
    use crate::camera::{Orthographic, Perspective};
    use crate::num::Mat4;
    use crate::test_rng::Rng;

    fn poses(r: &mut Rng) -> (Pose, Mat4) {
        let a = [r.next() as u16, r.next() as u16, r.next() as u16];
        let rad = |a: u16| f32::from(a) / 65536.0 * core::f32::consts::TAU;
        let sc = (r.next() % (3 << 16)) as i32 + (1 << 14);
        let sc = if r.next() % 5 == 0 { -sc } else { sc };
        let t = [0, 1, 2].map(|_| (r.next() % (2 << 16)) as i32 - (1 << 16));
        let p = Pose::translate(t)
            .mul(&Pose::rotate_z(Angle(a[2])))
            .mul(&Pose::rotate_x(Angle(a[0])))
            .mul(&Pose::rotate_y(Angle(a[1])))
            .mul(&Pose::scale(sc).unwrap());
        let f = |v: i32| v as f32 / 65536.0;
        let m = Mat4::translate([f(t[0]), f(t[1]), f(t[2])])
            .mul(&Mat4::rotate_z(rad(a[2])))
            .mul(&Mat4::rotate_x(rad(a[0])))
            .mul(&Mat4::rotate_y(rad(a[1])))
            .mul(&Mat4::scale([f(sc); 3]));
        (p, m)
    }

    fn unit(v: [i32; 3]) -> [f64; 3] {
        let l = v
            .iter()
            .map(|&c| f64::from(c).powi(2))
            .sum::<f64>()
            .sqrt()
            .max(1e-9);
        v.map(|c| f64::from(c) / l)
    }

    #[test]
    fn sin_cos_within_2e_5() {
        for a in (0..=65535u16).step_by(7) {
            let (s, c) = Angle(a).sin_cos();
            let x = f64::from(a) / 65536.0 * core::f64::consts::TAU;
            assert!((f64::from(s) / 2f64.powi(30) - x.sin()).abs() < 2e-5, "{a}");
            assert!((f64::from(c) / 2f64.powi(30) - x.cos()).abs() < 2e-5, "{a}");
        }
        assert_eq!(Angle::degrees(90), Angle(16384));
        assert_eq!(Angle::degrees(-90), Angle(49152));
    }

    /// The integer transform equals the f32 one to a sub-pixel: 500 random
    /// poses (rotations about three axes, scales 0.25–3.25 and mirrored,
    /// translations) through an orthographic and a perspective camera.
    #[test]
    fn matches_the_f32_transform() {
        let mut r = Rng(0x1234_5678_9ABC_DEF1);
        let vp = Viewport::new(0, 0, 240, 240).unwrap();
        let view = Mat4::translate([0.1, -0.2, -6.0]).mul(&Mat4::rotate_x(0.3));
        let ortho = Camera::orthographic(-2.0, 2.0, -2.0, 2.0, 1.0, 12.0, vp)
            .unwrap()
            .with_view(view);
        let persp = Camera::perspective(1.0, 1.0, 1.0, 30.0, vp)
            .unwrap()
            .with_view(view);
        let fo = FixedCamera::<Orthographic>::new(&ortho).unwrap();
        let fp = FixedCamera::<Perspective>::new(&persp).unwrap();
        let pts = [
            [0i16, 0, 0],
            [16384, 0, 0],
            [0, -16384, 8000],
            [-12000, 9000, -5000],
            [3000, 3000, 3000],
        ];
        let nrm = [
            [16384i16, 0, 0],
            [0, 16384, 0],
            [9459, 9459, 9459],
            [0, -11585, 11585],
        ];
        for _ in 0..500 {
            let (p, m) = poses(&mut r);
            let (a, b) = (
                fo.mesh_transform(&p, 14).unwrap(),
                ortho.mesh_transform(&m, 14).unwrap(),
            );
            for q in pts {
                let (Some(x), Some(y)) = (a.project(q), b.project(q)) else {
                    panic!("an orthographic transform has no near plane");
                };
                assert!(
                    (x.x - y.x).abs() <= 1 && (x.y - y.y).abs() <= 1,
                    "{p:?} {q:?} {x:?} {y:?}"
                );
                assert!((i32::from(x.z) - i32::from(y.z)).abs() <= 2, "{x:?} {y:?}");
                let (e, f) = (a.eye(q), b.eye(q));
                for k in 0..3 {
                    // both paths round the rotation near 2·10⁻⁵ (the table, f32)
                    assert!(
                        (e[k] - f[k]).abs() <= 8 + f[k].abs() / 8192,
                        "eye {e:?} {f:?}"
                    );
                }
            }
            for n in nrm {
                let (u, v) = (unit(a.normal(n)), unit(b.normal(n)));
                let d: f64 = (0..3).map(|k| (u[k] - v[k]).abs()).sum();
                assert!(d < 4e-4, "normal {u:?} {v:?}");
            }
            let (a, b) = (
                fp.mesh_transform(&p, 14).unwrap(),
                persp.mesh_transform(&m, 14).unwrap(),
            );
            let (an, bn) = (a.clip_space().near(), b.clip_space().near());
            assert!((an - bn).abs() <= 1, "{an} {bn}");
            for q in pts {
                match (a.project(q), b.project(q)) {
                    (Some(x), Some(y)) => {
                        assert!(
                            (x.x - y.x).abs() <= 1 && (x.y - y.y).abs() <= 1,
                            "{x:?} {y:?}"
                        );
                        // z/w amplifies the rotation's rounding (2·10⁻⁵) in both paths
                        assert!((i32::from(x.z) - i32::from(y.z)).abs() <= 4, "{x:?} {y:?}");
                    }
                    (None, None) => {}
                    // a point on the near plane may fall either side
                    (x, y) => {
                        let c = a.clip(q);
                        assert!((c.w - an).abs() <= 2, "{x:?} {y:?} {c:?}");
                    }
                }
            }
        }
    }
}
