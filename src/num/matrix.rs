//! 4×4 matrices in `f32`: model, view and projection, composed once per frame
//! (the fixed-point vertex stage takes them from here through
//! [`Camera`](crate::camera::Camera)).

use core::ops::{Add, Mul, Sub};

use crate::error::{finite, finite_all, ParamError};

/// A 4×4 matrix in `f32`, row-major (`m[row][col]`), applied to column vectors:
/// `p' = M·p`. [`Mat4::mul`] composes so that `a.mul(&b)` applies `b` first, as
/// in OpenGL: `mvp = projection.mul(&view).mul(&model)`.
///
/// Constructors that can fail return a [`ParamError`]; the others turn
/// non-finite input into a non-finite matrix, which
/// [`Camera::mesh_transform`](crate::camera::Camera::mesh_transform) rejects.
///
/// ```
/// use fixshade::num::Mat4;
/// let m = Mat4::translate([1.0, 2.0, 3.0]).mul(&Mat4::scale([2.0, 2.0, 2.0]));
/// assert_eq!(m.transform_point([1.0, 1.0, 1.0]), [3.0, 4.0, 5.0, 1.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat4 {
    /// The elements, `m[row][col]`; the translation is column 3.
    pub m: [[f32; 4]; 4],
}

impl Default for Mat4 {
    /// The identity.
    fn default() -> Self {
        Self::IDENTITY
    }
}

/// `a − b` for plain `f32` or `f64` 3-vectors.
pub(crate) fn sub3<T: Copy + Sub<Output = T>>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a × b` for plain `f32` or `f64` 3-vectors.
pub(crate) fn cross3<T: Copy + Sub<Output = T> + Mul<Output = T>>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a·b` for plain `f32` or `f64` 3-vectors.
pub(crate) fn dot3<T: Copy + Add<Output = T> + Mul<Output = T>>(a: [T; 3], b: [T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The cofactors of a 3×3 matrix, `cof_ij = (−1)^(i+j)·minor_ij` (written with
/// cyclic indices), for plain `f32` or `f64` elements: `det = a₀·cof₀` and
/// `a⁻¹ = cofᵀ/det`.
pub(crate) fn cof3<T: Copy + Sub<Output = T> + Mul<Output = T>>(a: [[T; 3]; 3]) -> [[T; 3]; 3] {
    core::array::from_fn(|i| {
        core::array::from_fn(|j| {
            let (i1, i2, j1, j2) = ((i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3);
            a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]
        })
    })
}

/// `v/|v|`, or `None` when `|v|` is zero, tiny or not finite.
fn unit3(v: [f32; 3]) -> Option<[f32; 3]> {
    let len = libm::sqrtf(dot3(v, v));
    if len.is_finite() && len > 1.0e-18 {
        Some([v[0] / len, v[1] / len, v[2] / len])
    } else {
        None
    }
}

impl Mat4 {
    /// The identity matrix.
    pub const IDENTITY: Mat4 = Mat4 {
        m: [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ],
    };

    /// The identity matrix.
    pub const fn identity() -> Self {
        Self::IDENTITY
    }

    /// `p' = p + t`.
    pub const fn translate(t: [f32; 3]) -> Self {
        Self::identity_with(t, [3, 3, 3])
    }

    /// `p' = (sx·x, sy·y, sz·z)`.
    pub const fn scale(s: [f32; 3]) -> Self {
        Self::identity_with(s, [0, 1, 2])
    }

    /// The identity with `m[i][col[i]] = v[i]` in rows 0 to 2.
    const fn identity_with(v: [f32; 3], col: [usize; 3]) -> Self {
        let mut m = Self::IDENTITY.m;
        m[0][col[0]] = v[0];
        m[1][col[1]] = v[1];
        m[2][col[2]] = v[2];
        Self { m }
    }

    /// Rotation by `rad` about +x, counter-clockwise looking from +x towards
    /// the origin: `y' = c·y − s·z`, `z' = s·y + c·z`.
    pub fn rotate_x(rad: f32) -> Self {
        Self::rotation(rad, 1, 2)
    }

    /// Rotation by `rad` about +y: `z' = c·z − s·x`, `x' = s·z + c·x`.
    pub fn rotate_y(rad: f32) -> Self {
        Self::rotation(rad, 2, 0)
    }

    /// Rotation by `rad` about +z: `x' = c·x − s·y`, `y' = s·x + c·y`.
    pub fn rotate_z(rad: f32) -> Self {
        Self::rotation(rad, 0, 1)
    }

    /// Rotation by `rad` in the plane of axes `i` and `j`, from `i` towards `j`:
    /// `i' = c·i − s·j`, `j' = s·i + c·j`.
    fn rotation(rad: f32, i: usize, j: usize) -> Self {
        let (s, c) = (libm::sinf(rad), libm::cosf(rad));
        let mut m = Self::IDENTITY.m;
        m[i][i] = c;
        m[i][j] = -s;
        m[j][i] = s;
        m[j][j] = c;
        Self { m }
    }

    /// The view matrix of a camera at `eye` looking at `target` (`gluLookAt`):
    /// with `f = normalize(target − eye)`, `s = normalize(f × up)`, `u = s × f`,
    /// the rows are `(s, −s·eye)`, `(u, −u·eye)`, `(−f, f·eye)`, `(0, 0, 0, 1)`.
    /// The eye ends at the origin looking down −z with `up` projected to +y.
    ///
    /// # Errors
    ///
    /// [`ParamError::NotFinite`] for NaN or infinite input;
    /// [`ParamError::ZeroDirection`] when `eye = target` or `up` is zero or parallel
    /// to the view direction.
    ///
    /// ```
    /// use fixshade::num::Mat4;
    /// let v = Mat4::look_at([0.0, 0.0, 5.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0])?;
    /// assert_eq!(v, Mat4::translate([0.0, 0.0, -5.0]));
    /// # Ok::<(), fixshade::error::ParamError>(())
    /// ```
    pub fn look_at(eye: [f32; 3], target: [f32; 3], up: [f32; 3]) -> Result<Self, ParamError> {
        finite_all("eye", eye)?;
        finite_all("target", target)?;
        finite_all("up", up)?;
        let f = unit3(sub3(target, eye)).ok_or(ParamError::ZeroDirection("eye/target"))?;
        let s = unit3(cross3(f, up)).ok_or(ParamError::ZeroDirection("up"))?;
        let u = cross3(s, f);
        let m = Self {
            m: [
                [s[0], s[1], s[2], -dot3(s, eye)],
                [u[0], u[1], u[2], -dot3(u, eye)],
                [-f[0], -f[1], -f[2], dot3(f, eye)],
                [0.0, 0.0, 0.0, 1.0],
            ],
        };
        m.checked("eye")
    }

    /// A perspective projection (`gluPerspective`): with `f = 1/tan(fovy/2)`,
    /// `x_c = f/aspect·x`, `y_c = f·y`,
    /// `z_c = (far + near)/(near − far)·z + 2·far·near/(near − far)`, `w_c = −z`.
    /// Eye-space points at `z = −near` get `z_c/w_c = −1`, at `z = −far` `+1`;
    /// `w_c` is the distance in front of the eye, so the near plane is
    /// `w_c = near` (where [`Camera::perspective`](crate::camera::Camera::perspective)
    /// clips).
    ///
    /// # Errors
    ///
    /// [`ParamError::NotFinite`] for NaN or infinite input;
    /// [`ParamError::OutOfRange`] unless `0 < fovy_rad < π`, `aspect > 0`,
    /// `near > 0` and `far > near`.
    ///
    /// ```
    /// use fixshade::num::Mat4;
    /// let p = Mat4::perspective(core::f32::consts::FRAC_PI_2, 2.0, 1.0, 3.0)?;
    /// assert_eq!(p.transform_point([2.0, 1.0, -1.0]), [1.0, 1.0, -1.0, 1.0]);
    /// assert!(Mat4::perspective(1.0, 1.0, 0.0, 10.0).is_err());
    /// # Ok::<(), fixshade::error::ParamError>(())
    /// ```
    pub fn perspective(
        fovy_rad: f32,
        aspect: f32,
        near: f32,
        far: f32,
    ) -> Result<Self, ParamError> {
        let fovy = finite("fovy", fovy_rad)?;
        let aspect = finite("aspect", aspect)?;
        let near = finite("near", near)?;
        let far = finite("far", far)?;
        if !(fovy > 0.0 && fovy < core::f32::consts::PI) {
            return Err(ParamError::OutOfRange("fovy"));
        }
        if aspect <= 0.0 {
            return Err(ParamError::OutOfRange("aspect"));
        }
        if near <= 0.0 {
            return Err(ParamError::OutOfRange("near"));
        }
        if far <= near {
            return Err(ParamError::OutOfRange("far"));
        }
        let f = 1.0 / libm::tanf(fovy * 0.5);
        let d = near - far;
        Self {
            m: [
                [f / aspect, 0.0, 0.0, 0.0],
                [0.0, f, 0.0, 0.0],
                [0.0, 0.0, (far + near) / d, 2.0 * far * near / d],
                [0.0, 0.0, -1.0, 0.0],
            ],
        }
        .checked("perspective")
    }

    /// An orthographic projection (`glOrtho`): the box `left..right`,
    /// `bottom..top`, `z = −near..−far` maps to `−1..1` on each axis; `w_c = 1`,
    /// so nothing is clipped at the near plane: depths outside `near..far`
    /// saturate to 0 or 65535.
    ///
    /// # Errors
    ///
    /// [`ParamError::NotFinite`] for NaN or infinite input;
    /// [`ParamError::ZeroDirection`] when `left = right`, `bottom = top` or
    /// `near = far`.
    ///
    /// ```
    /// use fixshade::num::Mat4;
    /// let o = Mat4::orthographic(0.0, 4.0, 0.0, 2.0, 1.0, 3.0)?;
    /// assert_eq!(o.transform_point([4.0, 1.0, -2.0]), [1.0, 0.0, 0.0, 1.0]);
    /// # Ok::<(), fixshade::error::ParamError>(())
    /// ```
    pub fn orthographic(
        left: f32,
        right: f32,
        bottom: f32,
        top: f32,
        near: f32,
        far: f32,
    ) -> Result<Self, ParamError> {
        let (l, r) = (finite("left", left)?, finite("right", right)?);
        let (b, t) = (finite("bottom", bottom)?, finite("top", top)?);
        let (n, f) = (finite("near", near)?, finite("far", far)?);
        if l == r {
            return Err(ParamError::ZeroDirection("left/right"));
        }
        if b == t {
            return Err(ParamError::ZeroDirection("bottom/top"));
        }
        if n == f {
            return Err(ParamError::ZeroDirection("near/far"));
        }
        Self {
            m: [
                [2.0 / (r - l), 0.0, 0.0, -(r + l) / (r - l)],
                [0.0, 2.0 / (t - b), 0.0, -(t + b) / (t - b)],
                [0.0, 0.0, -2.0 / (f - n), -(f + n) / (f - n)],
                [0.0, 0.0, 0.0, 1.0],
            ],
        }
        .checked("orthographic")
    }

    /// `Ok(self)` when every element is finite.
    fn checked(self, name: &'static str) -> Result<Self, ParamError> {
        self.is_finite()
            .then_some(self)
            .ok_or(ParamError::NotFinite(name))
    }

    /// Whether every element is finite.
    pub fn is_finite(&self) -> bool {
        self.m.iter().flatten().all(|v| v.is_finite())
    }

    /// The product `self·rhs`: `(self·rhs)_ij = Σ_k self_ik·rhs_kj` (applies
    /// `rhs` first, then `self`).
    pub fn mul(&self, rhs: &Mat4) -> Mat4 {
        let mut m = [[0.0f32; 4]; 4];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                *e = (0..4).map(|k| self.m[i][k] * rhs.m[k][j]).sum();
            }
        }
        Mat4 { m }
    }

    /// `M·(x, y, z, 1)`: the homogeneous image of a point.
    pub fn transform_point(&self, p: [f32; 3]) -> [f32; 4] {
        let mut out = [0.0f32; 4];
        for (o, r) in out.iter_mut().zip(&self.m) {
            *o = r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3];
        }
        out
    }

    /// `M₃·v` with the upper-left 3×3 (a direction: no translation).
    pub fn transform_vector(&self, v: [f32; 3]) -> [f32; 3] {
        let r = &self.m;
        [
            r[0][0] * v[0] + r[0][1] * v[1] + r[0][2] * v[2],
            r[1][0] * v[0] + r[1][1] * v[1] + r[1][2] * v[2],
            r[2][0] * v[0] + r[2][1] * v[1] + r[2][2] * v[2],
        ]
    }

    /// The matrix that transforms normals: `sign(det M₃)·cof(M₃) = |det M₃|·M₃⁻ᵀ`,
    /// the inverse-transpose of the upper-left 3×3 up to a positive factor (which
    /// normalisation removes). Correct for non-uniform scales and mirrors, equal
    /// to `M₃` itself for rotations; needs no division, so a singular `M₃` gives
    /// a finite (possibly zero) matrix.
    pub fn normal_matrix(&self) -> [[f32; 3]; 3] {
        let a: [[f32; 3]; 3] = core::array::from_fn(|i| [self.m[i][0], self.m[i][1], self.m[i][2]]);
        let c = cof3(a);
        if dot3(a[0], c[0]) < 0.0 {
            c.map(|row| row.map(|e| -e))
        } else {
            c
        }
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
    fn rotations_are_right_handed() {
        let r = Mat4::rotate_z(FRAC_PI_2).transform_vector([1.0, 0.0, 0.0]);
        assert!(close(&r, &[0.0, 1.0, 0.0], 1e-6), "{r:?}");
        let r = Mat4::rotate_x(FRAC_PI_2).transform_vector([0.0, 1.0, 0.0]);
        assert!(close(&r, &[0.0, 0.0, 1.0], 1e-6), "{r:?}");
        let r = Mat4::rotate_y(FRAC_PI_2).transform_vector([0.0, 0.0, 1.0]);
        assert!(close(&r, &[1.0, 0.0, 0.0], 1e-6), "{r:?}");
    }

    #[test]
    fn look_at_hand_computed() {
        // eye at (1, 2, 3) looking along +x: s = f × up = (0, 0, 1), u = (0, 1, 0)
        let v = Mat4::look_at([1.0, 2.0, 3.0], [5.0, 2.0, 3.0], [0.0, 1.0, 0.0]).unwrap();
        let want = Mat4 {
            m: [
                [0.0, 0.0, 1.0, -3.0],
                [0.0, 1.0, 0.0, -2.0],
                [-1.0, 0.0, 0.0, 1.0],
                [0.0, 0.0, 0.0, 1.0],
            ],
        };
        assert_eq!(v, want);
        // the target ends on −z at its distance
        assert_eq!(v.transform_point([5.0, 2.0, 3.0]), [0.0, 0.0, -4.0, 1.0]);
        let d = |r| Err::<Mat4, _>(ParamError::ZeroDirection(r));
        assert_eq!(
            Mat4::look_at([1.0; 3], [1.0; 3], [0.0, 1.0, 0.0]),
            d("eye/target")
        );
        assert_eq!(
            Mat4::look_at([0.0; 3], [0.0, 3.0, 0.0], [0.0, 1.0, 0.0]),
            d("up")
        );
        assert!(Mat4::look_at([f32::NAN; 3], [0.0; 3], [0.0, 1.0, 0.0]).is_err());
    }

    #[test]
    fn projection_parameters_are_validated() {
        let o = |r| Err::<Mat4, _>(ParamError::OutOfRange(r));
        assert_eq!(Mat4::perspective(0.0, 1.0, 1.0, 2.0), o("fovy"));
        assert_eq!(Mat4::perspective(3.2, 1.0, 1.0, 2.0), o("fovy"));
        assert_eq!(Mat4::perspective(1.0, -1.0, 1.0, 2.0), o("aspect"));
        assert_eq!(Mat4::perspective(1.0, 1.0, -1.0, 2.0), o("near"));
        assert_eq!(Mat4::perspective(1.0, 1.0, 2.0, 2.0), o("far"));
        assert_eq!(
            Mat4::perspective(1.0, f32::NAN, 1.0, 2.0),
            Err(ParamError::NotFinite("aspect"))
        );
        assert_eq!(
            Mat4::perspective(1.0, 1.0, 1.0, f32::INFINITY),
            Err(ParamError::NotFinite("far"))
        );
        assert_eq!(
            Mat4::perspective(1.0, 1.0e-40, 1.0, 2.0),
            Err(ParamError::NotFinite("perspective"))
        );
        assert!(Mat4::orthographic(1.0, 1.0, 0.0, 1.0, 0.0, 1.0).is_err());
        assert!(Mat4::orthographic(0.0, 1.0, 0.0, 1.0, 1.0, 1.0).is_err());
        // near = 1, far = 3: z = −1 → −1, z = −3 → +1, w = −z
        let p = Mat4::perspective(FRAC_PI_2, 1.0, 1.0, 3.0).unwrap();
        let c = p.transform_point([0.0, 0.0, -3.0]);
        assert!(close(&c, &[0.0, 0.0, 3.0, 3.0], 1e-6), "{c:?}");
        let c = p.transform_point([0.0, 0.0, -1.0]);
        assert!(close(&c, &[0.0, 0.0, -1.0, 1.0], 1e-6), "{c:?}");
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // matrix indices read best as i, j, k
    fn normal_matrix_is_inverse_transpose() {
        let m = Mat4::rotate_y(0.3).mul(&Mat4::scale([2.0, 3.0, 4.0]));
        let n = m.normal_matrix();
        // (M⁻ᵀ)ᵀ·M = I  ⇒  nᵀ·M = |det|·I with |det| = 24
        for i in 0..3 {
            for j in 0..3 {
                let s: f32 = (0..3).map(|k| n[k][i] * m.m[k][j]).sum();
                let want = if i == j { 24.0 } else { 0.0 };
                assert!((s - want).abs() < 1e-4, "{i} {j} {s}");
            }
        }
        // a mirror keeps normals pointing out of the mirrored surface
        let n = Mat4::scale([-1.0, 1.0, 1.0]).normal_matrix();
        assert_eq!(n[0][0], -1.0);
        assert_eq!(n[1][1], 1.0);
    }
}
