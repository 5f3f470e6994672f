//! The camera: projection (a type: orthographic scenes link no perspective
//! code), view and viewport, and the per-mesh fixed-point transform the vertex
//! stage applies once per vertex per frame.
//!
//! A [`Camera`] is built in `f32` (on a Cortex-M0 a few hundred soft-float
//! operations per matrix product, per frame). [`Camera::mesh_transform`]
//! converts `viewport · projection · view · model` to rows of `i32` with a
//! block exponent per row: an `i16` vertex position is transformed with two
//! 16 × 16-bit products per element (one `MULS` each), no 64-bit multiply, no
//! floating point.

mod fixed;

pub use fixed::{Angle, FixedCamera, Pose};

mod viewport;

use crate::num::Mat4;
pub use viewport::Viewport;

use crate::error::ParamError;
use core::marker::PhantomData;

/// Fractional bits of screen positions: 4, i.e. positions are in 1/16
/// pixel.
pub const SUBPIXEL_BITS: u32 = 4;

/// How eye space is projected: [`Orthographic`] or [`Perspective`]. A type, so
/// that a scene pays only for the projection it uses.
pub trait Projection: Copy + core::fmt::Debug + Default + 'static {
    /// Whether `w` varies (division per vertex, near-plane clipping,
    /// perspective-correct attributes).
    const PERSPECTIVE: bool;
}

/// Parallel projection (`glOrtho`): `w = 1`, screen position affine in the model
/// position, no division per vertex.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Orthographic;

/// Central projection (`gluPerspective`): division by `w` per vertex,
/// clipping at the near plane, perspective-correct attributes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Perspective;

impl Projection for Orthographic {
    const PERSPECTIVE: bool = false;
}

impl Projection for Perspective {
    const PERSPECTIVE: bool = true;
}

/// A camera: projection matrix, view matrix and viewport.
///
/// ```
/// use fixshade::camera::Camera;
/// use fixshade::num::Mat4;
/// use fixshade::camera::Viewport;
/// // the standard scene: ±1/0.85 orthographic, camera 5 units back
/// let s = 1.0 / 0.85;
/// let cam = Camera::orthographic(-s, s, -s, s, 1.0, 10.0, Viewport::new(0, 0, 240, 240)?)?
///     .with_view(Mat4::translate([0.0, 0.0, -5.0]));
/// let t = cam.mesh_transform(&Mat4::IDENTITY, 14)?;
/// // the model origin lands at the centre of the screen, depth (5 − 1)/9 of the range
/// let v = t.project([0, 0, 0]).expect("an orthographic transform has no near plane");
/// assert_eq!((v.x, v.y), (120 << 4, 120 << 4));
/// assert_eq!(v.z, (65535.0f32 * 4.0 / 9.0).round() as u16);
/// # Ok::<(), fixshade::error::ParamError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera<P: Projection> {
    projection: Mat4,
    view: Mat4,
    viewport: Viewport,
    near: f32,
    far: f32,
    kind: PhantomData<P>,
}

impl Camera<Orthographic> {
    /// An orthographic camera (`glOrtho`): the box `left..right`,
    /// `bottom..top`, `z = −near..−far` of eye space fills the viewport, depth
    /// 0 at `near` to 65535 at `far`.
    ///
    /// # Errors
    ///
    /// As [`Mat4::orthographic`].
    pub fn orthographic(
        left: f32,
        right: f32,
        bottom: f32,
        top: f32,
        near: f32,
        far: f32,
        viewport: Viewport,
    ) -> Result<Self, ParamError> {
        Ok(Camera {
            projection: Mat4::orthographic(left, right, bottom, top, near, far)?,
            view: Mat4::IDENTITY,
            viewport,
            near,
            far,
            kind: PhantomData,
        })
    }
}

impl Camera<Perspective> {
    /// A perspective camera (`gluPerspective`).
    ///
    /// # Errors
    ///
    /// As [`Mat4::perspective`].
    pub fn perspective(
        fovy_rad: f32,
        aspect: f32,
        near: f32,
        far: f32,
        viewport: Viewport,
    ) -> Result<Self, ParamError> {
        Ok(Camera {
            projection: Mat4::perspective(fovy_rad, aspect, near, far)?,
            view: Mat4::IDENTITY,
            viewport,
            near,
            far,
            kind: PhantomData,
        })
    }
}

impl<P: Projection> Camera<P> {
    /// The same camera with view matrix `view` (world → eye space).
    pub fn with_view(mut self, view: Mat4) -> Self {
        self.view = view;
        self
    }

    /// The viewport.
    pub fn viewport(&self) -> Viewport {
        self.viewport
    }

    /// The view matrix.
    pub fn view(&self) -> &Mat4 {
        &self.view
    }

    /// The projection matrix.
    pub fn projection(&self) -> &Mat4 {
        &self.projection
    }

    /// The near plane distance.
    pub fn near(&self) -> f32 {
        self.near
    }

    /// The clip space of [`Camera::clip`]: the viewport's centre and, under
    /// a perspective projection, the near plane in the unit of its `w`.
    pub fn clip_space(&self) -> ClipSpace {
        if P::PERSPECTIVE {
            let (_, c) = self.viewport.scale_centre();
            let near = libm::ldexpf(self.near, self.clip_frac());
            ClipSpace::perspective(
                c.map(|v| v as i32),
                libm::roundf(near).clamp(1.0, 1e9) as i32,
            )
        } else {
            ClipSpace::SCREEN
        }
    }

    /// Fraction bits of [`Camera::clip`]'s coordinates under a perspective
    /// projection: the most that keep `8·size·far` below 2^30.
    fn clip_frac(&self) -> i32 {
        let vp = &self.viewport;
        let reach = 8.0 * vp.width().max(vp.height()) as f32 * self.far.abs().max(self.near.abs());
        let mut frac = 20;
        while frac > 0 && libm::ldexpf(reach, frac) >= (1u32 << 30) as f32 {
            frac -= 1;
        }
        frac
    }

    /// The clip coordinates of world point `position` in [`Camera::clip_space`]:
    /// what [`draw_triangle`](crate::render::draw_triangle) takes. Orthographic:
    /// sub-pixel screen position and depth; perspective: `(8W·x_c, −8H·y_c, z_c,
    /// w_c)` times a power of two fixed per camera (as is the near plane).
    ///
    /// # Errors
    ///
    /// [`ParamError::NotFinite`] for a non-finite position;
    /// [`ParamError::OutOfRange`] for coordinates leaving `i32` (beyond about
    /// 2^30 sub-pixels, or in perspective behind the far plane by more than the
    /// camera's depth range).
    pub fn clip(&self, position: [f32; 3]) -> Result<Clip, ParamError> {
        for c in position {
            crate::error::finite("position", c)?;
        }
        let e = self.view.transform_point(position);
        let c = self.projection.transform_point([e[0], e[1], e[2]]);
        let ([w8, h8], [cx, cy]) = self.viewport.scale_centre();
        let fit = |v: f32| {
            if v.is_finite() && libm::fabsf(v) < 2.0e9 {
                Ok(libm::roundf(v) as i32)
            } else {
                Err(ParamError::OutOfRange("clip coordinates"))
            }
        };
        if P::PERSPECTIVE {
            let k = libm::ldexpf(1.0, self.clip_frac());
            Ok(Clip {
                x: fit(c[0] * w8 * k)?,
                y: fit(-c[1] * h8 * k)?,
                z: fit(c[2] * k)?,
                w: fit(c[3] * k)?,
            })
        } else {
            Ok(Clip {
                x: fit(cx + c[0] * w8)?,
                y: fit(cy - c[1] * h8)?,
                z: fit(((c[2] + 1.0) * 0.5 * 65535.0).clamp(0.0, 65535.0))?,
                w: 1,
            })
        }
    }

    /// The eye-space position (Q16.16, saturated at ±32768) and normal (Q14,
    /// through the normal matrix, normalised) of world point `position` with
    /// normal `normal`: what a kernel's vertex stage reads
    /// ([`VertexIn`](crate::shade::VertexIn)).
    ///
    /// # Errors
    ///
    /// [`ParamError::NotFinite`] for a non-finite position or normal.
    pub fn eye(
        &self,
        position: [f32; 3],
        normal: [f32; 3],
    ) -> Result<([i32; 3], [i32; 3]), ParamError> {
        for c in position.iter().chain(&normal) {
            crate::error::finite("position or normal", *c)?;
        }
        let e = self.view.transform_point(position);
        let m = self.view.normal_matrix();
        let n: [f32; 3] = core::array::from_fn(|i| {
            m[i][0] * normal[0] + m[i][1] * normal[1] + m[i][2] * normal[2]
        });
        let len = libm::sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        let q16 = |v: f32| libm::roundf(v * 65536.0).clamp(-2.147e9, 2.147e9) as i32;
        let q14 = |v: f32| {
            if len > 0.0 {
                libm::roundf(v / len * 16384.0) as i32
            } else {
                0
            }
        };
        Ok(([e[0], e[1], e[2]].map(q16), n.map(q14)))
    }

    /// The fixed-point transform of a mesh with model matrix `model` whose
    /// positions carry `frac` fraction bits (see [`Mesh`](crate::mesh::Mesh)).
    ///
    /// # Errors
    ///
    /// [`ParamError::NotFinite`] for a non-finite matrix;
    /// [`ParamError::OutOfRange`] for `frac > 15`.
    pub fn mesh_transform(&self, model: &Mat4, frac: u8) -> Result<MeshTransform<P>, ParamError> {
        if frac > 15 {
            return Err(ParamError::OutOfRange("frac"));
        }
        let mv = self.view.mul(model);
        let mvp = self.projection.mul(&mv);
        if !mvp.is_finite() || !mv.is_finite() {
            return Err(ParamError::NotFinite("matrix"));
        }
        let ([w8, h8], [cx, cy]) = self.viewport.scale_centre();
        let m = &mvp.m;
        let inv = 1.0 / (1u32 << frac) as f32;
        let ([x, y, z, w], space) = if P::PERSPECTIVE {
            // clip rows in one unit (so that they compare and divide):
            // x' = 8W·x_c, y' = −8H·y_c (x_sub = cx + x'/w'), z' = z_c, w' = w_c
            let rows = [
                scaled(m[0], w8, inv),
                scaled(m[1], -h8, inv),
                scaled(m[2], 1.0, inv),
                scaled(m[3], 1.0, inv),
            ];
            let frac = rows.iter().map(Row::natural_frac).min().unwrap_or(0);
            // the near plane at w_c = near (gluPerspective: w_c = −z_eye)
            let near_w = libm::roundf(libm::ldexpf(self.near, frac)).clamp(1.0, 1e9) as i32;
            let space = ClipSpace::perspective([cx as i32, cy as i32], near_w);
            (rows.map(|r| Row::with_frac(r, frac)), space)
        } else {
            // w = 1: x_sub = cx + 8W·x_c, y_sub = cy − 8H·y_c, z = (z_c + 1)/2·65535
            let row = |r: [f32; 4], k: f32, c: f32| {
                let mut e = scaled(r, k, inv);
                e[3] += c;
                Row::new(e)
            };
            let z = row(m[2], 65535.0 * 0.5, 65535.0 * 0.5);
            let rows = [row(m[0], w8, cx), row(m[1], -h8, cy), z, Row::default()];
            (rows, ClipSpace::SCREEN)
        };
        Ok(MeshTransform {
            x,
            y,
            z,
            w,
            space,
            near: self.near,
            normal: NormalRows::new(&mv.normal_matrix()),
            eye: EyeRows::new(&mv, inv),
            kind: PhantomData,
        })
    }
}

/// Row `r` of a matrix times `k`, the 3 linear elements per raw position unit.
fn scaled(r: [f32; 4], k: f32, inv: f32) -> [f32; 4] {
    [r[0] * k * inv, r[1] * k * inv, r[2] * k * inv, r[3] * k]
}

/// One output of the vertex transform: `out = Σ e_c·p_c·2^−16 + t`, in units of
/// `2^−frac`, for an `i16` position `p`. The elements share a block exponent:
/// the largest `|e_c|` lies in `[2^28, 2^29)`, so every product term is below
/// 2^28 and the sum with `|t| < 2^30` cannot overflow.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Row {
    e: [i32; 3],
    t: i32,
    frac: i32,
}

impl Row {
    /// From `f32` elements (per raw position unit) and translation.
    fn new(r: [f32; 4]) -> Row {
        Self::with_frac(r, Self::natural_frac(&r))
    }

    /// The fraction bits [`Row::new`] gives `r`: the most that keep the
    /// elements below 2^29 and the translation below 2^30.
    fn natural_frac(r: &[f32; 4]) -> i32 {
        let max = r[0].abs().max(r[1].abs()).max(r[2].abs());
        // frac with max·2^(frac + 16) in [2^28, 2^29): frac = 12 − exponent
        let frac = if max > 0.0 {
            12 - libm::frexpf(max).1 + 1
        } else {
            0
        };
        // keep the translation below 2^30 in output units
        let tmax = r[3].abs();
        if tmax > 0.0 {
            frac.min(29 - libm::frexpf(tmax).1)
        } else {
            frac
        }
        .clamp(-60, 60)
    }

    /// From `f32` elements with `frac` fraction bits (at most the natural ones).
    fn with_frac(r: [f32; 4], frac: i32) -> Row {
        let conv = |v: f32, s: i32| {
            let x = libm::roundf(libm::ldexpf(v, s));
            // `as` saturates (and maps NaN to 0)
            x as i32
        };
        Row {
            e: [r[0], r[1], r[2]].map(|v| conv(v, frac + 16)),
            t: conv(r[3], frac),
            frac,
        }
    }

    /// The output for position `p`, in `2^−frac` units (see the type docs).
    #[inline(always)]
    pub fn apply(&self, p: [i16; 3]) -> i32 {
        self.t
            .wrapping_add(mul_q16(self.e[0], p[0]))
            .wrapping_add(mul_q16(self.e[1], p[1]))
            .wrapping_add(mul_q16(self.e[2], p[2]))
    }

    /// [`Row::apply`] rounded to whole output units (sub-pixels, depth units),
    /// saturated to `i32`.
    #[inline(always)]
    pub fn apply_round(&self, p: [i16; 3]) -> i32 {
        // frac ≤ 0: a matrix scaling one raw unit beyond 2^13 sub-pixels
        shift_round(self.apply(p), self.frac)
    }
}

/// `v / 2^s` rounded half up for `s > 0` (`s` capped at 31), else `v·2^−s`
/// saturated to ±`i32::MAX` (`−s` capped at 30), without a 64-bit multiply.
#[inline(always)]
fn shift_round(v: i32, s: i32) -> i32 {
    if s > 0 {
        let f = s.min(31) as u32;
        // round half up: floor(v / 2^f) + bit f − 1 (`((v >> (f − 1)) + 1) >> 1`
        // without its overflow at v = i32::MAX)
        (v >> f) + ((v >> (f - 1)) & 1)
    } else {
        let s = (-s).min(30) as u32;
        let lim = i32::MAX >> s;
        if v > lim {
            i32::MAX
        } else if v < -lim {
            -i32::MAX
        } else {
            v << s
        }
    }
}

/// `⌊e·p / 2^16⌋` exactly, from two 16 × 16-bit products: `e = eh·2^16 + el`
/// with `0 ≤ el < 2^16`, so `e·p/2^16 = eh·p + el·p/2^16` and `|el·p| < 2^31`.
#[inline(always)]
pub(crate) fn mul_q16(e: i32, p: i16) -> i32 {
    let p = i32::from(p);
    (e >> 16) * p + (((e & 0xFFFF) * p) >> 16)
}

/// The normal matrix (inverse-transpose of the model-view 3×3, up to a positive
/// factor) in Q14 with a common scale: normals come out unnormalised.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct NormalRows {
    e: [[i16; 3]; 3],
}

impl NormalRows {
    fn new(nm: &[[f32; 3]; 3]) -> Self {
        let max = nm.iter().flatten().fold(0.0f32, |m, v| m.max(v.abs()));
        // largest element at 16384 (Q14 of 1): a rotation keeps unit length.
        // Each element is divided by the largest first (|v / max| ≤ 1 even
        // when max is subnormal, where 16384 / max would be infinite)
        let ok = max > 0.0 && max.is_finite();
        let q = |v: f32| libm::roundf((v / max).clamp(-1.0, 1.0) * 16384.0) as i16;
        NormalRows {
            e: nm.map(|r| r.map(|v| if ok { q(v) } else { 0 })),
        }
    }

    /// `N·n` for a Q14 normal: components in Q14 (up to √3·2 in magnitude).
    #[inline(always)]
    pub fn apply(&self, n: [i16; 3]) -> [i32; 3] {
        let n = n.map(i32::from);
        self.e.map(|r| {
            // each product ≤ 2^28, the sum < 2^30
            (i32::from(r[0]) * n[0] + i32::from(r[1]) * n[1] + i32::from(r[2]) * n[2] + (1 << 13))
                >> 14
        })
    }
}

/// The model-view matrix for eye-space positions, as rows with Q16.16 output.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct EyeRows {
    r: [Row; 3],
}

impl EyeRows {
    fn new(mv: &Mat4, inv: f32) -> Self {
        EyeRows {
            r: [0, 1, 2].map(|i| Row::new(scaled(mv.m[i], 1.0, inv))),
        }
    }

    /// The eye-space position in Q16.16 (saturated at ±32768).
    #[inline]
    pub fn apply(&self, p: [i16; 3]) -> [i32; 3] {
        self.r.map(|row| {
            let v = row.apply(p);
            match row.frac - 16 {
                0 => v,
                s => shift_round(v, s),
            }
        })
    }
}

/// A vertex projected to the screen: sub-pixel position and depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Projected {
    /// Column in sub-pixels (may lie far outside the screen).
    pub x: i32,
    /// Row in sub-pixels (down is positive).
    pub y: i32,
    /// Depth, 0 at the near plane to 65535 at the far plane (saturated).
    pub z: u16,
}

/// The fixed-point transform of one mesh for one frame (see the [module](self)
/// docs): screen rows, the normal matrix and the eye-space rows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshTransform<P: Projection> {
    x: Row,
    y: Row,
    z: Row,
    w: Row,
    space: ClipSpace,
    near: f32,
    normal: NormalRows,
    eye: EyeRows,
    kind: PhantomData<P>,
}

/// Clip coordinates of a vertex in one fixed-point unit: the screen position
/// is `centre + (x/w, y/w)` sub-pixels (see [`ClipSpace`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Clip {
    /// `8W·x_c` (perspective) or the column in sub-pixels (orthographic).
    pub x: i32,
    /// `−8H·y_c` (perspective) or the row in sub-pixels (orthographic).
    pub y: i32,
    /// `z_c` (perspective) or the depth, 0 to 65535 (orthographic).
    pub z: i32,
    /// `w_c`, the distance in front of the eye (perspective), or 1.
    pub w: i32,
}

/// Where clip coordinates land on the screen: the screen centre, the near
/// plane and whether `w` varies.
///
/// Perspective: a point `(x, y, z, w)` with `w` at least the near plane is
/// drawn at `centre + (x/w, y/w)` sub-pixels with depth
/// `round((z/w + 1)/2·65535)` (saturated: no far-plane clipping), the same for
/// any common positive factor. Orthographic ([`ClipSpace::SCREEN`], for a
/// program computing screen positions itself): `x`, `y` the sub-pixel position,
/// `z` the depth, `w = 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ClipSpace {
    centre: [i32; 2],
    near: i32,
    perspective: bool,
}

impl ClipSpace {
    /// Screen space: `x`, `y` in sub-pixels, `z` the depth (0 to 65535),
    /// `w = 1`.
    pub const SCREEN: ClipSpace = ClipSpace {
        centre: [0, 0],
        near: 1,
        perspective: false,
    };

    /// A perspective clip space: the screen centre in sub-pixels and the near
    /// plane in `w` units (at least 1).
    pub const fn perspective(centre: [i32; 2], near: i32) -> ClipSpace {
        ClipSpace {
            centre,
            near: if near < 1 { 1 } else { near },
            perspective: true,
        }
    }

    /// The screen position of `x = y = 0`, in sub-pixels.
    pub const fn centre(&self) -> [i32; 2] {
        self.centre
    }

    /// The near plane in `w` units (1 in screen space).
    pub const fn near(&self) -> i32 {
        self.near
    }

    /// Whether `w` varies.
    pub const fn is_perspective(&self) -> bool {
        self.perspective
    }

    /// The screen position and depth of `c`, or `None` behind the near
    /// plane. The position saturates to `i32`.
    #[inline]
    pub fn project(&self, c: Clip) -> Option<Projected> {
        if self.perspective {
            self.project_as::<true>(c)
        } else {
            self.project_as::<false>(c)
        }
    }

    /// [`ClipSpace::project`] for a space known to be perspective
    /// (`PERSP`) or not: the other case's code is not linked.
    #[inline(always)]
    pub(crate) fn project_as<const PERSP: bool>(&self, c: Clip) -> Option<Projected> {
        if PERSP && c.w < self.near {
            return None;
        }
        Some(self.screen::<PERSP>(c))
    }

    /// [`ClipSpace::project_as`] without the near-plane test (`w` below 1
    /// counts as 1).
    #[inline(always)]
    pub(crate) fn screen<const PERSP: bool>(&self, c: Clip) -> Projected {
        let sat = |v: i64| v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        if PERSP {
            let w = i64::from(c.w.max(1));
            let z = div_round((i64::from(c.z) + w) * 65535, 2 * w);
            Projected {
                x: sat(i64::from(self.centre[0]) + div_round(i64::from(c.x), w)),
                y: sat(i64::from(self.centre[1]) + div_round(i64::from(c.y), w)),
                z: z.clamp(0, 65535) as u16,
            }
        } else {
            Projected {
                x: c.x,
                y: c.y,
                z: c.z.clamp(0, 65535) as u16,
            }
        }
    }
}

/// `round(n / d)` (halves away from zero) for `d > 0`.
#[inline]
fn div_round(n: i64, d: i64) -> i64 {
    let q = (2 * n.unsigned_abs() + d as u64) / (2 * d as u64);
    if n < 0 {
        -(q as i64)
    } else {
        q as i64
    }
}

impl<P: Projection> MeshTransform<P> {
    /// The clip coordinates of a raw position ([`Clip`], in
    /// [`MeshTransform::clip_space`]).
    #[inline]
    pub fn clip(&self, p: [i16; 3]) -> Clip {
        if P::PERSPECTIVE {
            Clip {
                x: self.x.apply(p),
                y: self.y.apply(p),
                z: self.z.apply(p),
                w: self.w.apply(p),
            }
        } else {
            Clip {
                x: self.x.apply_round(p),
                y: self.y.apply_round(p),
                z: self.z.apply_round(p),
                w: 1,
            }
        }
    }

    /// Where this transform's clip coordinates land on the screen.
    #[inline]
    pub fn clip_space(&self) -> ClipSpace {
        self.space
    }

    /// The screen position and depth of a raw position, or `None` behind the
    /// near plane (perspective).
    #[inline]
    pub fn project(&self, p: [i16; 3]) -> Option<Projected> {
        self.space.project(self.clip(p))
    }

    /// The eye-space normal (unnormalised, Q14) of a Q14 normal.
    #[inline(always)]
    pub fn normal(&self, n: [i16; 3]) -> [i32; 3] {
        self.normal.apply(n)
    }

    /// The eye-space position (Q16.16) of a raw position.
    #[inline]
    pub fn eye(&self, p: [i16; 3]) -> [i32; 3] {
        self.eye.apply(p)
    }

    /// The near plane distance.
    pub fn near(&self) -> f32 {
        self.near
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mul_q16_is_exact() {
        for e in [
            0i32,
            1,
            -1,
            65535,
            65536,
            -65537,
            (1 << 29) - 1,
            -(1 << 29),
            123_456_789,
        ] {
            for p in [0i16, 1, -1, 16384, -16384, i16::MAX, i16::MIN, 12345] {
                let want = ((i64::from(e) * i64::from(p)) >> 16) as i32;
                assert_eq!(mul_q16(e, p), want, "{e} {p}");
            }
        }
    }

    #[test]
    fn orthographic_transform_matches_float() {
        let s = 1.0 / 0.85;
        let cam = Camera::orthographic(
            -s,
            s,
            -s,
            s,
            1.0,
            10.0,
            Viewport::new(0, 0, 240, 240).unwrap(),
        )
        .unwrap()
        .with_view(Mat4::translate([0.0, 0.0, -5.0]));
        let model = Mat4::rotate_y(0.3).mul(&Mat4::rotate_x(-0.2));
        let t = cam.mesh_transform(&model, 14).unwrap();
        let mvp = cam.projection().mul(cam.view()).mul(&model);
        for p in [
            [0i16, 0, 0],
            [16384, 0, 0],
            [0, -16384, 8000],
            [-12000, 9000, -5000],
            [i16::MAX; 3],
        ] {
            let f = p.map(|c| c as f32 / 16384.0);
            let c = mvp.transform_point(f);
            let want_x = 16.0 * 120.0 + 8.0 * 240.0 * c[0];
            let want_y = 16.0 * 120.0 - 8.0 * 240.0 * c[1];
            let want_z = (c[2] + 1.0) * 0.5 * 65535.0;
            let v = t.project(p).expect("in front of the camera");
            assert!(
                (v.x as f32 - want_x).abs() <= 0.51,
                "{p:?} {} {want_x}",
                v.x
            );
            assert!(
                (v.y as f32 - want_y).abs() <= 0.51,
                "{p:?} {} {want_y}",
                v.y
            );
            assert!(
                (v.z as f32 - want_z.clamp(0.0, 65535.0)).abs() <= 1.01,
                "{p:?}"
            );
        }
    }
}
