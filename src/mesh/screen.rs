//! The per-triangle pipeline's fixed-point vertex stage: [`FixedMat4`],
//! [`ScreenTransform`] (projection to the rasterizer's [`ScreenVertex`]) and
//! [`EyeTransform`] (eye space for lighting); and the [`Viewport`] both
//! pipelines share.

use super::error::{finite, MeshError};
use super::normals::geo16;
use super::Mat4;
use crate::num::{Geo16, Scalar};
use crate::raster::{RasterVertex, SUBPIXEL_BITS};
use crate::vector::{Point3, Vec3};

/// Screen coordinates are saturated to ±`GUARD_BAND` pixels.
const GUARD_BAND: i32 = 1 << 15;

/// Bits an element of a [`FixedMat4`] may use besides the sign: the largest
/// element is scaled into `[2^28, 2^29]`.
const ELEMENT_BITS: i32 = 29;
/// Fractional bits of the positions the fixed-point stage reads ([`Geo16`]).
const POS_FRAC: i32 = 16;
/// Clip coordinates given in `f32` are clamped to ±(2^62 − 1) raw units, the
/// range [`FixedMat4::apply_raw`] produces, so that `w + z` and `2w` fit an `i64`.
const RAW_LIMIT: i64 = (1 << 62) - 1;

/// The exponent `e` with `max|x| = m·2^e`, `m ∈ [0.5, 1)`; 0 for all zeros.
fn max_exponent<'a>(xs: impl Iterator<Item = &'a f32>) -> i32 {
    let max = xs.fold(0.0f32, |m, &x| m.max(x.abs()));
    if max > 0.0 {
        libm::frexpf(max).1
    } else {
        0
    }
}

/// A 4×4 matrix in block floating point for the per-vertex stage: `i32`
/// elements `e_ij = round(m_ij·2^F)` sharing one exponent `F`, chosen so the
/// largest `|e_ij|` lies in `[2^28, 2^29]` (29 significant bits relative to the
/// largest element; `F` is clamped to −100..=100).
///
/// Applied to a [`Geo16`] position (Q16.16, ±32768) it accumulates in `i64`:
/// every product is below 2^60 and every sum of four below 2^62, so nothing
/// overflows for any input. The result is in units of `2^−(16+F)`.
///
/// ```
/// use fixshade::mesh::{FixedMat4, Mat4};
/// use fixshade::num::Geo16;
/// use fixshade::vector::Vec3;
/// let m = FixedMat4::new(&Mat4::translate([1.0, 0.0, 0.0]))?;
/// let p = Vec3::new(Geo16::from_num(2), Geo16::ZERO, Geo16::ZERO);
/// assert_eq!(m.apply_f32(p), [3.0, 0.0, 0.0, 1.0]);
/// # Ok::<(), fixshade::mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FixedMat4 {
    e: [[i32; 4]; 4],
    frac: i32,
}

impl FixedMat4 {
    /// Converts `m` (rounding to nearest).
    ///
    /// # Errors
    ///
    /// [`MeshError::NotFinite`] when an element is NaN or infinite.
    pub fn new(m: &Mat4) -> Result<Self, MeshError> {
        if !m.is_finite() {
            return Err(MeshError::NotFinite("matrix"));
        }
        let frac = (ELEMENT_BITS - max_exponent(m.m.iter().flatten())).clamp(-100, 100);
        let mut e = [[0i32; 4]; 4];
        for (er, mr) in e.iter_mut().zip(&m.m) {
            for (x, &v) in er.iter_mut().zip(mr) {
                // |v·2^F| ≤ 2^29: the cast is exact after rounding
                *x = libm::round(libm::ldexp(f64::from(v), frac)) as i32;
            }
        }
        Ok(Self { e, frac })
    }

    /// The elements `e_ij = round(m_ij·2^F)`.
    pub fn elements(&self) -> [[i32; 4]; 4] {
        self.e
    }

    /// The shared exponent `F`.
    pub fn frac_bits(&self) -> i32 {
        self.frac
    }

    /// `Σ_j e_ij·p_j + e_i3·2^16` for a Q16.16 position: the homogeneous image
    /// `M·(p, 1)` in units of `2^−(16+F)` (each component below 2^62).
    pub fn apply_raw(&self, p: Vec3<Geo16>) -> [i64; 4] {
        let p = [
            i64::from(p.x.to_bits()),
            i64::from(p.y.to_bits()),
            i64::from(p.z.to_bits()),
        ];
        let mut out = [0i64; 4];
        for (o, r) in out.iter_mut().zip(&self.e) {
            *o = i64::from(r[0]) * p[0]
                + i64::from(r[1]) * p[1]
                + i64::from(r[2]) * p[2]
                + (i64::from(r[3]) << POS_FRAC);
        }
        out
    }

    /// [`FixedMat4::apply_raw`] converted to `f32`: each component rounded to
    /// 24 significant bits, then scaled by `2^−(16+F)` (exact unless the value
    /// exceeds the `f32` range, which needs elements near 10³⁸).
    pub fn apply_f32(&self, p: Vec3<Geo16>) -> [f32; 4] {
        let unit = self.unit();
        self.apply_raw(p).map(|r| r as f32 * unit)
    }

    /// The value of one raw unit, `2^−(16+F)` (a normal `f32`: `16 + F` is in
    /// −83..=116).
    fn unit(&self) -> f32 {
        libm::ldexpf(1.0, -(POS_FRAC + self.frac))
    }
}

/// `round(a·b/c)` for `b ≥ 0`, `c > 0`, without overflow: when `|a·b|` would
/// need more than 62 bits, `a` and `c` drop the excess low bits first (the
/// quotient keeps the precision of what is left of `c`). A `c` that vanishes
/// that way means the quotient is beyond ±2^62: it saturates to ±(2^62 − 1).
fn mul_div(a: i64, b: i64, c: i64) -> i64 {
    let bits = |v: i64| 64 - v.unsigned_abs().leading_zeros() as i32;
    let excess = (bits(a) + bits(b) - 62).min(63);
    let (a, c) = if excess > 0 {
        (a >> excess, c >> excess)
    } else {
        (a, c)
    };
    if c <= 0 {
        return if a < 0 { -RAW_LIMIT } else { RAW_LIMIT };
    }
    let p = a * b; // |p| < 2^62
    let half = c / 2; // < 2^62
    if p >= 0 {
        (p + half) / c
    } else {
        (p - half) / c
    }
}

/// The screen rectangle clip space maps to: `x0..x0 + width` left to right,
/// `y0..y0 + height` top to bottom (y down), depth `−1..1` to `0..=65535`.
///
/// ```
/// use fixshade::mesh::Viewport;
/// let vp = Viewport::new(0, 0, 240, 135)?;
/// assert_eq!((vp.width(), vp.height()), (240, 135));
/// assert!(Viewport::new(0, 0, 0, 10).is_err());
/// # Ok::<(), fixshade::mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Viewport {
    x0: i32,
    y0: i32,
    width: i32,
    height: i32,
}

impl Viewport {
    /// A viewport with its top-left corner at pixel `(x0, y0)`.
    ///
    /// # Errors
    ///
    /// [`MeshError::OutOfRange`] unless `1 ≤ width, height ≤ GUARD_BAND` and
    /// `|x0|, |y0| ≤ GUARD_BAND` (`GUARD_BAND` = 32768).
    pub fn new(x0: i32, y0: i32, width: i32, height: i32) -> Result<Self, MeshError> {
        let g = GUARD_BAND;
        if !(1..=g).contains(&width) {
            return Err(MeshError::OutOfRange("width"));
        }
        if !(1..=g).contains(&height) {
            return Err(MeshError::OutOfRange("height"));
        }
        if !(-g..=g).contains(&x0) {
            return Err(MeshError::OutOfRange("x0"));
        }
        if !(-g..=g).contains(&y0) {
            return Err(MeshError::OutOfRange("y0"));
        }
        Ok(Self {
            x0,
            y0,
            width,
            height,
        })
    }

    /// Left column.
    pub fn x0(&self) -> i32 {
        self.x0
    }
    /// Top row.
    pub fn y0(&self) -> i32 {
        self.y0
    }
    /// Width in pixels.
    pub fn width(&self) -> i32 {
        self.width
    }
    /// Height in pixels.
    pub fn height(&self) -> i32 {
        self.height
    }
}

/// The [`ScreenVertex::inv_w`] of a vertex on the near plane: 2^24.
pub const INV_W_ONE: i32 = 1 << 24;

/// A projected vertex in the rasterizer's format (see
/// [`RasterVertex`](crate::raster::RasterVertex)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ScreenVertex {
    /// Column with [`SUBPIXEL_BITS`] fractional bits, within ±`GUARD_BAND` pixels.
    pub x: i32,
    /// Row (down is positive) with [`SUBPIXEL_BITS`] fractional bits, within
    /// ±`GUARD_BAND` pixels.
    pub y: i32,
    /// Depth: `round((z_c/w_c + 1)/2·65535)`, saturated; smaller is nearer.
    pub z: u16,
    /// `round(2^24·near_w/w_c)` in `1..=2^24·256/255`: [`INV_W_ONE`] on the near
    /// plane, halving each time the distance doubles.
    pub inv_w: i32,
}

impl ScreenVertex {
    /// The rasterizer vertex with these coordinates and `attrs`.
    pub fn to_raster<const N: usize>(self, attrs: [i32; N]) -> RasterVertex<N> {
        RasterVertex {
            x: self.x,
            y: self.y,
            z: self.z,
            inv_w: self.inv_w,
            attrs,
        }
    }
}

/// The fixed-point projection of positions to the screen: the model-view-
/// projection matrix as a [`FixedMat4`], a [`Viewport`] and the near plane
/// `w_c = near_w`.
///
/// For a position `p` ([`Geo16`]), with `(x_c, y_c, z_c, w_c) = MVP·(p, 1)` in
/// `i64` (see [`FixedMat4`]), [`ScreenTransform::project`] computes
///
/// - `None` when `w_c ≤ near_w·(1 − 2⁻⁸)`: the vertex is behind (or too close
///   to) the near plane; clip the triangle with [`clip_near`](super::clip_near)
///   and project the clipped vertices with [`ScreenTransform::project_clip`].
///   The 2⁻⁸ tolerance accepts clipped vertices, which lie on `w_c = near_w` up
///   to rounding;
/// - `x = 16·(x0 + width/2) + 8·width·x_c/w_c` (sub-pixels; `x_c/w_c = −1` is
///   the left edge of the viewport, `+1` the right edge),
/// - `y = 16·(y0 + height/2) − 8·height·y_c/w_c` (y down: `+1` is the top edge),
///
///   both saturated to ±`GUARD_BAND` pixels (geometry farther out is
///   distorted, as in the rasterizer);
/// - `z = (z_c/w_c + 1)/2·65535`, saturated to `0..=65535`;
/// - `inv_w = 2^24·near_w/w_c` (see [`ScreenVertex::inv_w`]).
///
/// The clip coordinates carry 24 significant bits (see
/// [`ScreenTransform::project`]), so positions are placed to about 2⁻²⁴ of
/// `|x_c|/w_c` of the viewport (far below a sub-pixel on screen); the divisions
/// are `i64`, rounded to nearest.
///
/// ```
/// use fixshade::mesh::{Mat4, ScreenTransform, Viewport, INV_W_ONE};
/// let proj = Mat4::perspective(core::f32::consts::FRAC_PI_2, 1.0, 1.0, 100.0)?;
/// let st = ScreenTransform::new(&proj, Viewport::new(0, 0, 100, 100)?, 1.0)?;
/// // on the axis: the centre of the viewport, 50 px = 800 sub-pixels
/// let v = st.project_f32([0.0, 0.0, -2.0]).unwrap();
/// assert_eq!((v.x, v.y, v.inv_w), (800, 800, INV_W_ONE / 2));
/// // 45° up and right (fovy = 90°): the top-right corner
/// let v = st.project_f32([2.0, 2.0, -2.0]).unwrap();
/// assert_eq!((v.x, v.y), (1600, 0));
/// assert_eq!(st.project_f32([0.0, 0.0, 1.0]), None); // behind the eye
/// # Ok::<(), fixshade::mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenTransform {
    mvp: FixedMat4,
    viewport: Viewport,
    near_w: f32,
    /// One clip-space unit in raw units, `2^(16+F)`.
    scale: f32,
    /// `near_w` in raw units (≥ 1).
    near_raw: i64,
    /// Vertices with raw `w_c ≤ reject_raw` are rejected.
    reject_raw: i64,
}

impl ScreenTransform {
    /// Converts `mvp` to fixed point for `viewport`; `near_w` is the near plane in
    /// clip space (the `near` of [`Mat4::perspective`]).
    ///
    /// # Errors
    ///
    /// [`MeshError::NotFinite`] for a non-finite matrix or `near_w`;
    /// [`MeshError::OutOfRange`] for `near_w ≤ 0`.
    pub fn new(mvp: &Mat4, viewport: Viewport, near_w: f32) -> Result<Self, MeshError> {
        if finite("near_w", near_w)? <= 0.0 {
            return Err(MeshError::OutOfRange("near_w"));
        }
        let mvp = FixedMat4::new(mvp)?;
        // near_w·2^(16+F), saturating (`as` saturates), at least 1
        let scale = libm::ldexpf(1.0, POS_FRAC + mvp.frac);
        let near_raw = ((near_w * scale) as i64).clamp(1, RAW_LIMIT);
        Ok(Self {
            mvp,
            viewport,
            near_w,
            scale,
            near_raw,
            reject_raw: near_raw - (near_raw >> 8),
        })
    }

    /// The model-view-projection matrix in fixed point.
    pub fn matrix(&self) -> &FixedMat4 {
        &self.mvp
    }

    /// The viewport.
    pub fn viewport(&self) -> Viewport {
        self.viewport
    }

    /// The near plane `w_c = near_w`.
    pub fn near_w(&self) -> f32 {
        self.near_w
    }

    /// The clip coordinates `MVP·(p, 1)` in `f32`, for [`clip_near`](super::clip_near).
    pub fn clip(&self, p: Vec3<Geo16>) -> [f32; 4] {
        self.mvp.apply_f32(p)
    }

    /// Projects a Q16.16 position (see the [type docs](Self)); `None` behind the
    /// near plane.
    ///
    /// The clip coordinates are rounded to 24 significant bits (as `f32` holds
    /// them) before the division, so that `project(p)` equals
    /// `project_clip(clip(p))` bit for bit: a triangle that was clipped shares
    /// exact screen vertices with its unclipped neighbours (no cracks).
    pub fn project(&self, p: Vec3<Geo16>) -> Option<ScreenVertex> {
        // |r| < 2^62: the round trip through f32 cannot saturate
        self.finish(self.mvp.apply_raw(p).map(|r| r as f32 as i64))
    }

    /// [`ScreenTransform::project`] of an `f32` position, converted to Q16.16
    /// first (saturating at ±32768, NaN → 0).
    pub fn project_f32(&self, p: [f32; 3]) -> Option<ScreenVertex> {
        self.project(geo16(p))
    }

    /// Projects clip coordinates (as produced by [`ScreenTransform::clip`] and
    /// [`clip_near`](super::clip_near)); NaN counts as 0, values beyond the raw
    /// range saturate.
    pub fn project_clip(&self, c: [f32; 4]) -> Option<ScreenVertex> {
        // `as` saturates and maps NaN to 0; the scaling by 2^(16+F) is exact
        self.finish(c.map(|v| ((v * self.scale) as i64).clamp(-RAW_LIMIT, RAW_LIMIT)))
    }

    /// The screen mapping of raw clip coordinates (formulas in the type docs).
    fn finish(&self, c: [i64; 4]) -> Option<ScreenVertex> {
        let [xc, yc, zc, wc] = c;
        if wc <= self.reject_raw {
            return None;
        }
        let vp = &self.viewport;
        let (w8, h8) = (i64::from(vp.width) << 3, i64::from(vp.height) << 3);
        let guard = i64::from(GUARD_BAND) << SUBPIXEL_BITS;
        let cx = (i64::from(vp.x0) << SUBPIXEL_BITS) + w8;
        let cy = (i64::from(vp.y0) << SUBPIXEL_BITS) + h8;
        // |mul_div| ≤ 2^62 and |cx| < 2^21: no overflow
        let x = (cx + mul_div(xc, w8, wc)).clamp(-guard, guard);
        let y = (cy - mul_div(yc, h8, wc)).clamp(-guard, guard);
        // z = (w + z)/(2w)·65535; |w + z| < 2^63, 2w < 2^63 (saturation is a
        // safety net only)
        let z = mul_div(wc.saturating_add(zc), 65535, wc.saturating_mul(2)).clamp(0, 65535);
        let inv_w = mul_div(self.near_raw, i64::from(INV_W_ONE), wc).clamp(1, i64::from(i32::MAX));
        Some(ScreenVertex {
            x: x as i32,
            y: y as i32,
            z: z as u16,
            inv_w: inv_w as i32,
        })
    }
}

/// The fixed-point transformation of positions and normals to eye space, for
/// lighting: the model-view matrix as a [`FixedMat4`] and its
/// [normal matrix](Mat4::normal_matrix) (the inverse-transpose of the 3×3, up
/// to a positive factor, so non-uniform scales keep normals perpendicular to
/// the surface).
///
/// Positions: `p_e = MV·(p, 1)` with `i64` accumulation, converted to the
/// tier's geometry type through `f32` (24 significant bits). Normals:
/// `n_e = normalize(N·n)`, `N` in `i32` with 29 significant bits, `n` read
/// through `f32`, the product rounded to 16 significant bits before
/// [`Scalar::normalize`] in the tier.
///
/// ```
/// use fixshade::mesh::{EyeTransform, Mat4};
/// use fixshade::num::Q14;
/// use fixshade::vector::Vec3;
/// // squash y by 2: the normal of the plane x + y = 1 turns towards y
/// let et = EyeTransform::new(&Mat4::scale([1.0, 0.5, 1.0]))?;
/// let n = et.normal(Vec3::<f32>::from_f32([0.7071068, 0.7071068, 0.0]));
/// assert!((n.x - 0.4472136).abs() < 1e-4 && (n.y - 0.8944272).abs() < 1e-4);
/// let p = et.point_f32::<Q14>([1.0, 4.0, -2.0]);
/// assert_eq!(p.y.to_num::<f32>(), 2.0);
/// # Ok::<(), fixshade::mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EyeTransform {
    mv: FixedMat4,
    normal: [[i32; 3]; 3],
}

impl EyeTransform {
    /// Converts the model-view matrix `mv`.
    ///
    /// # Errors
    ///
    /// [`MeshError::NotFinite`] for a non-finite matrix (or normal matrix).
    pub fn new(mv: &Mat4) -> Result<Self, MeshError> {
        let fixed = FixedMat4::new(mv)?;
        let nm = mv.normal_matrix();
        if !nm.iter().flatten().all(|v| v.is_finite()) {
            return Err(MeshError::NotFinite("normal matrix"));
        }
        // any positive scale will do: the result is normalised
        let frac = (ELEMENT_BITS - max_exponent(nm.iter().flatten())).clamp(-100, 100);
        let mut normal = [[0i32; 3]; 3];
        for (er, mr) in normal.iter_mut().zip(&nm) {
            for (e, &v) in er.iter_mut().zip(mr) {
                *e = libm::round(libm::ldexp(f64::from(v), frac)) as i32;
            }
        }
        Ok(Self { mv: fixed, normal })
    }

    /// The eye-space position `MV·(p, 1)` of a Q16.16 position, in tier `S`'s
    /// geometry type (saturating at its range).
    pub fn point<S: Scalar>(&self, p: Vec3<Geo16>) -> Point3<S> {
        let e = self.mv.apply_f32(p);
        Vec3::new(
            S::geo_from_f32(e[0]),
            S::geo_from_f32(e[1]),
            S::geo_from_f32(e[2]),
        )
    }

    /// [`EyeTransform::point`] of an `f32` position (converted to Q16.16 first,
    /// saturating at ±32768, NaN → 0).
    pub fn point_f32<S: Scalar>(&self, p: [f32; 3]) -> Point3<S> {
        self.point::<S>(geo16(p))
    }

    /// The eye-space unit normal `normalize(N·n)`; the zero vector for a zero
    /// `n` or a normal matrix that annihilates it.
    pub fn normal<S: Scalar>(&self, n: Vec3<S>) -> Vec3<S> {
        // n in Q16 (|n| ≤ 2^31 even for the float tiers' saturated values)
        let q = n.to_f32().map(|v| (v * 65536.0) as i32 as i64);
        let mut r = [0i64; 3];
        for (o, row) in r.iter_mut().zip(&self.normal) {
            // each product < 2^60, sum < 2^62
            *o = i64::from(row[0]) * q[0] + i64::from(row[1]) * q[1] + i64::from(row[2]) * q[2];
        }
        // keep 16 significant bits: the largest component in [2^14, 2^15)
        let max = r.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0);
        if max == 0 {
            return Vec3::new(S::ZERO, S::ZERO, S::ZERO);
        }
        let shift = (64 - max.leading_zeros() as i32) - 15;
        let v = r.map(|c| {
            let c = if shift > 0 { c >> shift } else { c << -shift };
            S::from_f32(c as f32 * (1.0 / 32768.0))
        });
        S::normalize(Vec3::new(v[0], v[1], v[2]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::FRAC_PI_2;

    fn close(a: &[f32], b: &[f32], tol: f32) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn mul_div_saturates() {
        assert_eq!(mul_div(7, 3, 2), 11); // 10.5 → 11
        assert_eq!(mul_div(-7, 3, 2), -11);
        assert_eq!(mul_div(1 << 61, 1 << 20, 1 << 61), 1 << 20);
        assert_eq!(mul_div(1 << 61, 1 << 20, 3), RAW_LIMIT);
        assert_eq!(mul_div(-(1 << 61), 1 << 20, 3), -RAW_LIMIT);
        assert_eq!(mul_div(i64::MIN, i64::MAX, 1), -RAW_LIMIT);
    }

    #[test]
    fn fixed_matches_float() {
        let mvp = Mat4::perspective(1.0, 1.5, 0.1, 100.0)
            .unwrap()
            .mul(&Mat4::translate([0.5, -1.0, -10.0]))
            .mul(&Mat4::rotate_x(0.4));
        let f = FixedMat4::new(&mvp).unwrap();
        for p in [[0.0f32, 0.0, 0.0], [1.5, -2.25, 3.0], [-100.0, 40.0, 7.0]] {
            let want = mvp.transform_point(p);
            let got = f.apply_f32(super::geo16(p));
            for (g, w) in got.iter().zip(want) {
                assert!(
                    (g - w).abs() <= 1e-4 * (1.0 + w.abs()),
                    "{p:?} {got:?} {want:?}"
                );
            }
        }
        assert_eq!(
            FixedMat4::new(&Mat4::translate([f32::NAN, 0.0, 0.0])),
            Err(MeshError::NotFinite("matrix"))
        );
        // all-zero and huge matrices convert
        let z = FixedMat4::new(&Mat4 { m: [[0.0; 4]; 4] }).unwrap();
        assert_eq!(z.apply_raw(super::geo16([1.0; 3])), [0; 4]);
        let h = FixedMat4::new(&Mat4::scale([3.0e38, 1.0, 1.0])).unwrap();
        assert!(((1 << 28)..=(1 << 29)).contains(&h.elements()[0][0]));
        assert_eq!(h.elements()[1][1], 0);
        assert_eq!(h.frac_bits(), 29 - 128);
    }

    #[test]
    fn viewport_mapping_and_depth() {
        let proj = Mat4::perspective(FRAC_PI_2, 2.0, 1.0, 9.0).unwrap();
        let st =
            ScreenTransform::new(&proj, Viewport::new(10, 20, 200, 100).unwrap(), 1.0).unwrap();
        let px = |x: i32, y: i32| (x << SUBPIXEL_BITS, y << SUBPIXEL_BITS);
        // centre of the viewport
        let v = st.project_f32([0.0, 0.0, -3.0]).unwrap();
        assert_eq!((v.x, v.y), px(110, 70));
        // x_c/w_c = x/(2·3) with aspect 2: x = 6 → right edge; y = 3 → top edge
        let v = st.project_f32([6.0, 3.0, -3.0]).unwrap();
        assert_eq!((v.x, v.y), px(210, 20));
        let v = st.project_f32([-6.0, -3.0, -3.0]).unwrap();
        assert_eq!((v.x, v.y), px(10, 120));
        // depth: near → 0, far → 65535
        assert_eq!(st.project_f32([0.0, 0.0, -1.0]).unwrap().z, 0);
        assert_eq!(st.project_f32([0.0, 0.0, -9.0]).unwrap().z, 65535);
        assert_eq!(st.project_f32([0.0, 0.0, -20.0]).unwrap().z, 65535);
        // inv_w = 2^24·near/w
        assert_eq!(st.project_f32([0.0, 0.0, -1.0]).unwrap().inv_w, INV_W_ONE);
        assert_eq!(
            st.project_f32([0.0, 0.0, -4.0]).unwrap().inv_w,
            INV_W_ONE / 4
        );
        // just inside the tolerance, and just beyond it
        assert!(st.project_f32([0.0, 0.0, -0.999]).is_some());
        assert!(st.project_f32([0.0, 0.0, -0.99]).is_none());
        // far outside: saturated to the guard band
        let v = st.project_f32([30000.0, -30000.0, -1.0]).unwrap();
        let g = GUARD_BAND << SUBPIXEL_BITS;
        assert_eq!((v.x, v.y), (g, g));
        // project_clip agrees with project
        for p in [
            [1.0f32, 2.0, -3.0],
            [-0.5, 0.25, -8.0],
            [123.4, -0.001, -1.75],
        ] {
            let a = st.project_f32(p).unwrap();
            let b = st.project_clip(st.clip(super::geo16(p))).unwrap();
            assert_eq!(a, b);
        }
        assert_eq!(st.project_clip([f32::NAN; 4]), None);
        assert!(st
            .project_clip([f32::INFINITY, f32::NEG_INFINITY, 1.0, 2.0])
            .is_some());
        assert_eq!(
            ScreenTransform::new(&proj, st.viewport(), 0.0),
            Err(MeshError::OutOfRange("near_w"))
        );
    }

    #[test]
    fn eye_space() {
        let mv = Mat4::translate([0.0, 0.0, -5.0]).mul(&Mat4::rotate_y(FRAC_PI_2));
        let et = EyeTransform::new(&mv).unwrap();
        let p = et.point_f32::<f32>([1.0, 2.0, 0.0]);
        assert!(close(&[p.x, p.y, p.z], &[0.0, 2.0, -6.0], 1e-4), "{p:?}");
        let n = et
            .normal(Vec3::<crate::num::Q14>::from_f32([1.0, 0.0, 0.0]))
            .to_f32();
        assert!(close(&n, &[0.0, 0.0, -1.0], 2e-3), "{n:?}");
        let z = et.normal(Vec3::<f32>::new(0.0, 0.0, 0.0));
        assert_eq!(z, Vec3::new(0.0, 0.0, 0.0));
        let nan = et.normal(Vec3::<f32>::new(f32::NAN, 1.0, 0.0)).to_f32();
        assert!(nan.iter().all(|v| v.is_finite()));
    }
}
