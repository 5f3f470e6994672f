//! One triangle through clipping, set-up, interpolation and the kernel into a
//! band: the stages every triangle of a frame goes through, whether it comes
//! from a mesh ([`MeshDraw`](super::MeshDraw)) or from the per-triangle front
//! ([`draw_triangle`]).

use super::{BandView, DrawBand};
use crate::camera::SUBPIXEL_BITS;
use crate::camera::{Camera, Projection};
use crate::camera::{Clip, ClipSpace};
use crate::error::ParamError;
use crate::num::ATTR_FRAC;
use crate::raster::clip::{self, Screen};
use crate::raster::interp::{self, within, Affine, Persp, Varyings};
use crate::raster::setup::at3;
use crate::raster::{Cull, Setup, Walker};
use crate::raster::{WINDOW_MAX, WINDOW_MIN};
use crate::shade::{Kernel, VertexIn};
use crate::span;

/// A corner of a triangle in clip space, with the kernel's values.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ClipCorner<V> {
    pub c: Clip,
    pub v: V,
}

/// A corner on the screen, inside the set-up window, with the kernel's values.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ScreenCorner<V> {
    pub s: Screen,
    pub v: V,
}

/// Where a set-up triangle continues in the next band: its edges' bound
/// columns at that band's first row (long edge, short edge) and whether its
/// runs are clamped. The set-up is the same in every band, so the clamp
/// decision (an error bound per plane) is made once, in the first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Resume {
    pub cols: (i32, i32),
    pub clamp: bool,
}

/// Sets up the triangle of screen positions `xy` (inside the window), depths
/// `z`, clip `cw` and values `v` and draws its part in `band` with `kernel`
/// (constants `t`), from `resume` at the band's first row when given; returns
/// where it continues in the next band. `PERSP`: perspective-correct values
/// (from `cw`). Not inlined: the common and clipping paths share one copy.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn draw<K: Kernel, const PERSP: bool>(
    kernel: &K,
    t: &K::Triangle,
    xy: [(i32, i32); 3],
    z: [u16; 3],
    cw: [i32; 3],
    v: &[K::Varyings; 3],
    resume: Option<Resume>,
    band: &mut BandView<'_, K::Color>,
) -> Option<Resume> {
    let s = Setup::new(xy, Cull::None)?;
    let row0 = s.rows.0;
    // depth with ATTR_FRAC bits, + ½ so that the shift rounds; values must stay
    // in 0..65536
    let z = interp::oriented(&s, &z.map(i32::from));
    let zp = s.plane(z);
    let zbase = (at3(&z, s.tmb[0]) << ATTR_FRAC) + (1 << (ATTR_FRAC - 1));
    // whether values and depth are clamped: decided (with the planes' error
    // bounds) in the triangle's first band, kept for the others
    let known = resume.map(|r| r.clamp);
    let zclamp = known.unwrap_or_else(|| !within(&s, &zp, zbase, (0, (1 << (16 + ATTR_FRAC)) - 1)));
    let mut zp = zp.absolute(zbase);
    let rows = band.rows();
    let mut w = match resume {
        Some(r) => Walker::resume(&s, rows.start, r.cols),
        None => Walker::new(&s, rows.start),
    };
    let skip = w.y - row0;
    let last = w.last.min(rows.end - 1);
    if skip > 0 {
        zp.skip_rows(skip);
    }
    let clamp = if PERSP {
        let mut p = Persp::new(&s, v, cw);
        if skip > 0 {
            p.skip_rows(skip);
        }
        span::rows(kernel, t, &mut w, last, &mut zp, band, &mut p, zclamp);
        zclamp
    } else {
        let mut clamp = zclamp;
        let (safe, exact) = (|i| kernel.safe(i), |i| kernel.exact(i));
        let decide = known.is_none().then_some(&mut clamp);
        let mut l = Affine::new(&s, v, K::USED, safe, exact, decide);
        if skip > 0 {
            l.skip_rows(skip, K::USED);
        }
        span::rows(kernel, t, &mut w, last, &mut zp, band, &mut l, clamp);
        clamp
    };
    w.more().then(|| Resume {
        cols: w.snapshot(),
        clamp,
    })
}

/// Clips the triangle of clip-space corners `c` (in the clip space `space`)
/// and draws the pieces' rows in `band` with `kernel` (triangle constants
/// `t`). Returns whether a piece reaches below the band (the triangle is
/// clipped and drawn again in the next band). Never inlined: its polygons stay
/// off the common path's stack.
#[inline(never)]
#[cold]
pub(crate) fn draw_clipped<K: Kernel, const PERSP: bool>(
    kernel: &K,
    t: &K::Triangle,
    c: &[ClipCorner<K::Varyings>; 3],
    space: &ClipSpace,
    band: &mut BandView<'_, K::Color>,
) -> bool {
    let rows = band.rows();
    let mut more = false;
    pieces::<_, PERSP>(c, space, |p| {
        let bottom = p.iter().map(|c| c.s.y).max().unwrap_or(0);
        // the pieces' rows beyond this band are drawn in later bands
        if ((bottom - (1 << (SUBPIXEL_BITS - 1))) >> SUBPIXEL_BITS) >= rows.end {
            more = true;
        }
        let xy = p.map(|c| (c.s.x, c.s.y));
        let v = p.map(|c| c.v);
        let _ = draw::<K, PERSP>(
            kernel,
            t,
            xy,
            p.map(|c| c.s.z),
            p.map(|c| c.s.w),
            &v,
            None,
            band,
        );
    });
    more
}

/// Calls `f` with the screen triangles of the clip-space triangle `c` clipped
/// to the near plane (`PERSP`: a perspective clip space) and the set-up
/// window.
///
/// Rounding the cut corners to sub-pixels can bend a nearly straight corner
/// inwards, and a fan over that overlaps itself (pixels written twice). So the
/// rounded polygon is cut into triangles by ears ([`triangles`]), which keeps
/// its outline exactly: a cut of an edge shared with a neighbouring triangle
/// is the same point in both, so the two outlines meet along the same
/// segments and no pixel next to them is drawn by both.
#[inline]
pub(crate) fn pieces<V: Varyings, const PERSP: bool>(
    c: &[ClipCorner<V>; 3],
    space: &ClipSpace,
    mut f: impl FnMut(&[ScreenCorner<V>; 3]),
) {
    let tri = c.map(|k| k.c);
    let (poly, vs) = clip::clipped::<_, PERSP>(tri, &c.map(|k| k.v), interp::lerp, space);
    let Some((s, tris, n)) = outline::<PERSP>(tri, &poly, space) else {
        return;
    };
    // indices masked to the arrays (a power of two): no bounds checks
    let corner = |i: u8| {
        let i = usize::from(i) & (clip::MAX - 1);
        ScreenCorner { s: s[i], v: vs[i] }
    };
    for t in tris.iter().take(n) {
        f(&[corner(t[0]), corner(t[1]), corner(t[2])]);
    }
}

/// The screen positions of the clipped polygon `poly` of the triangle `tri`
/// and its triangles ([`triangles`]); `None` for a triangle of zero area. Not
/// generic over the values: one copy per projection.
#[inline(never)]
fn outline<const PERSP: bool>(
    tri: [Clip; 3],
    poly: &clip::Polygon,
    space: &ClipSpace,
) -> Option<([Screen; clip::MAX], [[u8; 3]; clip::MAX], usize)> {
    let front = clip::facing::<PERSP>(tri)?;
    let mut s = [Screen::default(); clip::MAX];
    let n = poly.vertices().len();
    for (q, c) in s.iter_mut().zip(poly.corners()).take(n) {
        *q = clip::screen::<PERSP>(space, *c);
    }
    let (tris, m) = triangles(&s, n, front);
    Some((s, tris, m))
}

/// `(b − a) × (c − a)` of screen corners: positive is clockwise on the screen
/// (y down). Corners are clamped to the window, whose sides are below 2^15
/// sub-pixels: each product is below 2^30 and their difference fits an `i32`
/// (no 64-bit multiply on the M0).
fn cross(a: Screen, b: Screen, c: Screen) -> i32 {
    const _: () = assert!(WINDOW_MAX - WINDOW_MIN < 1 << 15);
    (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
}

/// The rounded polygon `s[..n]` (the facing `front`) cut into triangles, as
/// indices into `s`, and their number (0: nothing to draw). Not generic: one
/// copy serves every kernel.
///
/// Ear clipping: a corner that turns as the polygon faces and whose triangle
/// with its neighbours holds no other corner is cut off as a triangle; a
/// corner in line with its neighbours is dropped (it adds no pixel). The
/// triangles tile the polygon exactly, its outline included. A rounded
/// polygon that crosses itself (two corners a sub-pixel apart, rounded past
/// each other) keeps the ears it has: the small loop that turns the wrong way
/// (less than a sub-pixel wide) is not drawn, rather than drawn over a
/// neighbour.
#[inline(never)]
fn triangles(s: &[Screen; clip::MAX], n: usize, front: bool) -> ([[u8; 3]; clip::MAX], usize) {
    // indices masked to the arrays (a power of two): no bounds checks
    const M: usize = clip::MAX - 1;
    const _: () = assert!(clip::MAX.is_power_of_two() && clip::MAX <= 256);
    let mut out = [[0u8; 3]; clip::MAX];
    let mut idx: [u8; clip::MAX] = core::array::from_fn(|i| i as u8);
    let pt = |i: u8| s[usize::from(i) & M];
    // `misses`: corners in a row that are not ears; n of them end the cut
    // (a last triangle turning the wrong way, or a polygon crossing itself)
    let (mut n, mut m, mut i, mut misses) = (n.min(clip::MAX), 0, 0, 0);
    while n >= 3 && misses < n {
        let prev = if i == 0 { n - 1 } else { i - 1 };
        let next = if i + 1 < n { i + 1 } else { 0 };
        let t = [idx[prev & M], idx[i & M], idx[next & M]];
        let (a, b, c) = (pt(t[0]), pt(t[1]), pt(t[2]));
        // negative: counter-clockwise on the screen, a front face
        let turn = cross(a, b, c);
        let ear = turn != 0
            && (turn < 0) == front
            && idx
                .iter()
                .take(n)
                .all(|&k| t.contains(&k) || !inside_or_on(a, b, c, pt(k)));
        if turn == 0 || ear {
            if ear {
                out[m & M] = t;
                m += 1;
            }
            for j in i..n - 1 {
                idx[j & M] = idx[(j + 1) & M];
            }
            n -= 1;
            misses = 0;
            i = if prev < n { prev } else { 0 };
        } else {
            misses += 1;
            i = next;
        }
    }
    (out, m)
}

/// Whether `p` is inside triangle `a b c` or on its outline (any winding).
fn inside_or_on(a: Screen, b: Screen, c: Screen, p: Screen) -> bool {
    let (d1, d2, d3) = (cross(a, b, p), cross(b, c, p), cross(c, a, p));
    let neg = d1 < 0 || d2 < 0 || d3 < 0;
    let pos = d1 > 0 || d2 > 0 || d3 > 0;
    !(neg && pos)
}

/// The rows `(first, last)` of a triangle whose corners are inside the window
/// or, for `None` corners, of the clip-space triangle `clip` after clipping
/// (`PERSP`: a perspective clip space), clamped to a frame of `width` ×
/// `height` pixels; `None` when it is culled, degenerate or outside the
/// frame.
#[inline(always)]
pub(crate) fn classify<const PERSP: bool>(
    screen: Option<[(i32, i32); 3]>,
    clip: impl FnOnce() -> Option<([Clip; 3], ClipSpace)>,
    cull: Cull,
    width: u32,
    height: u32,
) -> Option<(u32, u32)> {
    let ((xmin, xmax, ymin, ymax), front) = match screen {
        Some(p) => {
            // A > 0: clockwise on the screen (a back face); products < 2^30
            let area =
                (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[1].1 - p[0].1) * (p[2].0 - p[0].0);
            if area == 0 {
                return None;
            }
            let bbox = (
                p[0].0.min(p[1].0).min(p[2].0),
                p[0].0.max(p[1].0).max(p[2].0),
                p[0].1.min(p[1].1).min(p[2].1),
                p[0].1.max(p[1].1).max(p[2].1),
            );
            (bbox, area < 0)
        }
        None => clipped_bounds::<PERSP>(clip)?,
    };
    if cull.skips(front) {
        return None;
    }
    let half = 1 << (SUBPIXEL_BITS - 1);
    let one = (1 << SUBPIXEL_BITS) - 1;
    // rows whose centre lies in [ymin, ymax], columns likewise
    let r0 = (ymin.saturating_sub(half).saturating_add(one)) >> SUBPIXEL_BITS;
    let r1 = ymax.saturating_sub(half) >> SUBPIXEL_BITS;
    let c0 = (xmin.saturating_sub(half).saturating_add(one)) >> SUBPIXEL_BITS;
    let c1 = xmax.saturating_sub(half) >> SUBPIXEL_BITS;
    let clamp = |n: u32| n.min(i32::MAX as u32) as i32;
    let (h, w) = (clamp(height), clamp(width));
    if r1 < 0 || r0 >= h || r0 > r1 || c1 < 0 || c0 >= w || c0 > c1 {
        return None;
    }
    Some((r0.max(0) as u32, r1.min(h - 1) as u32))
}

/// The bounding box and facing of what remains of a clip-space triangle after
/// clipping (the rare path): exactly the pieces' box under a perspective
/// projection, the window's part of the triangle's box under an orthographic
/// one.
#[inline(never)]
#[cold]
fn clipped_bounds<const PERSP: bool>(
    clip: impl FnOnce() -> Option<([Clip; 3], ClipSpace)>,
) -> Option<((i32, i32, i32, i32), bool)> {
    let (c, space) = clip()?;
    let front = clip::facing::<PERSP>(c)?;
    if !PERSP {
        // orthographic: the clipped polygon lies in the triangle's box (its
        // cuts are on the edges) and in the window, so that box clamped to the
        // window holds it. A few bands more than the pieces cover at most (they
        // draw nothing), without clipping twice.
        let s = c.map(|c| clip::screen::<false>(&space, c));
        let (xs, ys) = (s.map(|p| p.x), s.map(|p| p.y));
        let bbox = (
            xs[0].min(xs[1]).min(xs[2]),
            xs[0].max(xs[1]).max(xs[2]),
            ys[0].min(ys[1]).min(ys[2]),
            ys[0].max(ys[1]).max(ys[2]),
        );
        return Some((bbox, front));
    }
    let (poly, _) = clip::clipped::<(), PERSP>(c, &[(); 3], |_, _, _, _| (), &space);
    // the corners of the triangles [`pieces`] draws
    let (s, tris, n) = outline::<PERSP>(c, &poly, &space)?;
    let mut bbox = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
    for &k in tris.iter().take(n).flatten() {
        let p = s[usize::from(k) & (clip::MAX - 1)];
        bbox = (
            bbox.0.min(p.x),
            bbox.1.max(p.x),
            bbox.2.min(p.y),
            bbox.3.max(p.y),
        );
    }
    (n >= 1).then_some((bbox, front))
}

/// One corner of a triangle a program brings itself: its clip coordinates
/// (in the [`ClipSpace`] it is drawn with) and what the vertex stage hands a
/// kernel (normal, eye position, texture coordinates, tangent).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Corner {
    /// Clip coordinates (see [`Clip`]).
    pub clip: Clip,
    /// The kernel's input for this corner.
    pub vertex: VertexIn,
}

impl Corner {
    /// The corner at world point `position` with normal `normal` (`f32`) seen
    /// through `camera`: clip coordinates ([`Camera::clip`]), eye position and
    /// normal ([`Camera::eye`]) and `w`; add texture coordinates or a tangent
    /// with [`VertexIn::with_uv`], [`VertexIn::with_tangent`].
    ///
    /// # Errors
    ///
    /// As [`Camera::clip`] and [`Camera::eye`].
    pub fn world<P: Projection>(
        camera: &Camera<P>,
        position: [f32; 3],
        normal: [f32; 3],
    ) -> Result<Corner, ParamError> {
        let clip = camera.clip(position)?;
        let (eye, normal) = camera.eye(position, normal)?;
        Ok(Corner {
            clip,
            vertex: VertexIn::new(normal, eye).with_w(clip.w),
        })
    }

    /// The corner at pixel position `(x, y)` (pixel centres at `.5`) and
    /// depth `depth` (0 near to 1 far, clamped) with the kernel's input
    /// `vertex`, in [`ClipSpace::SCREEN`].
    ///
    /// # Errors
    ///
    /// [`ParamError::NotFinite`] for a non-finite coordinate,
    /// [`ParamError::OutOfRange`] beyond ±2^26 pixels.
    pub fn screen(x: f32, y: f32, depth: f32, vertex: VertexIn) -> Result<Corner, ParamError> {
        let sub = (1 << SUBPIXEL_BITS) as f32;
        let fit = |name, v: f32| {
            crate::error::finite(name, v)?;
            if libm::fabsf(v) < (1 << 26) as f32 {
                Ok(libm::roundf(v * sub) as i32)
            } else {
                Err(ParamError::OutOfRange(name))
            }
        };
        crate::error::finite("depth", depth)?;
        Ok(Corner {
            clip: Clip {
                x: fit("x", x)?,
                y: fit("y", y)?,
                z: libm::roundf(depth.clamp(0.0, 1.0) * 65535.0) as i32,
                w: 1,
            },
            vertex,
        })
    }
}

/// One triangle a program brings itself, as an item of a frame
/// ([`DrawBand`]): [`draw_triangle`] in every band.
///
/// ```
/// use fixshade::prelude::*;
/// use fixshade::render::{Corner, Triangle};
/// // a perspective camera 4 units back and one lit triangle in world coordinates
/// let camera = Camera::perspective(0.8, 1.0, 1.0, 20.0, Viewport::new(0, 0, 64, 64)?)?
///     .with_view(Mat4::translate([0.0, 0.0, -4.0]));
/// let lighting = fixshade::standard::blinn::<Q14>()?; // lights in eye coordinates
/// let shader = Shader::new(PhongShading, &lighting, Linear);
/// let up = [0.0, 0.0, 1.0];
/// let corners = [
///     Corner::world(&camera, [-1.0, -1.0, 0.0], up)?,
///     Corner::world(&camera, [1.0, -1.0, 0.0], up)?,
///     Corner::world(&camera, [0.0, 1.0, 0.0], up)?,
/// ];
/// let mut tri = Triangle::new(&shader, camera.clip_space(), corners);
/// let (mut strip, mut depth) = ([Rgb565::BLACK; 64 * 8], [0u16; 64 * 8]);
/// let mut display = Checksum::new(Size::new(64, 64)); // any DrawTarget
/// Bands::new(Layout::banded(64, 64, 8)?, &mut strip, Some(&mut depth))?
///     .render(&mut display, Rgb565::BLACK, &mut [&mut tri])?;
/// assert!(display.pixels() == 64 * 64);
/// # Ok::<(), fixshade::error::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Triangle<'k, K> {
    kernel: &'k K,
    space: ClipSpace,
    corners: [Corner; 3],
    cull: Cull,
}

impl<'k, K: Kernel> Triangle<'k, K> {
    /// The triangle of `corners` in clip space `space` drawn with `kernel`,
    /// back faces culled.
    pub fn new(kernel: &'k K, space: ClipSpace, corners: [Corner; 3]) -> Self {
        Triangle {
            kernel,
            space,
            corners,
            cull: Cull::Back,
        }
    }

    /// The same triangle with culling `cull`.
    pub fn with_cull(mut self, cull: Cull) -> Self {
        self.cull = cull;
        self
    }
}

impl<K: Kernel> DrawBand<K::Color> for Triangle<'_, K> {
    fn draw_band(&mut self, band: &mut BandView<'_, K::Color>) {
        draw_triangle(band, &self.space, self.kernel, &self.corners, self.cull);
    }
}

/// Draws the rows `band` holds of one triangle with `kernel`: the pipeline's
/// per-triangle entry ([`Triangle`] makes one an item of a frame; a
/// [`DrawBand`] of your own calls this per band). The corners
/// ([`Corner::world`], [`Corner::screen`]) go through the kernel's vertex
/// stage, then the culling (`cull`), clipping, set-up, interpolation and span
/// stage of a mesh triangle: corners from a mesh's transform
/// ([`MeshTransform::clip`](crate::camera::MeshTransform::clip)) give
/// [`MeshDraw`](super::MeshDraw)'s pixels bit for bit. Never panics.
///
/// ```
/// use fixshade::camera::ClipSpace;
/// use fixshade::framebuffer::{BandView, DrawBand};
/// use fixshade::prelude::*;
/// use fixshade::render::{draw_triangle, Corner};
/// use fixshade::shade::VertexIn;
///
/// /// Two triangles in screen space, lit from the front.
/// struct Quad<K>(K, [Corner; 4]);
/// impl<K: Kernel<Color = Rgb565>> DrawBand<Rgb565> for Quad<K> {
///     fn draw_band(&mut self, band: &mut BandView<'_, Rgb565>) {
///         let [a, b, c, d] = self.1;
///         draw_triangle(band, &ClipSpace::SCREEN, &self.0, &[a, b, c], Cull::Back);
///         draw_triangle(band, &ClipSpace::SCREEN, &self.0, &[a, c, d], Cull::Back);
///     }
/// }
/// let lighting = fixshade::standard::blinn::<Q14>()?; // lights in eye coordinates
/// let front = VertexIn::new([0, 0, 16384], [0; 3]);
/// let at = |x, y| Corner::screen(x, y, 0.5, front);
/// let mut item = Quad(
///     Shader::new(GouraudShading, &lighting, Linear),
///     [at(2.0, 2.0)?, at(2.0, 30.0)?, at(30.0, 30.0)?, at(30.0, 2.0)?],
/// );
/// let (mut color, mut depth) = ([Rgb565::BLACK; 32 * 32], [0u16; 32 * 32]);
/// let mut frame = FullFrame::new(32, 32, &mut color, Some(&mut depth))?;
/// frame.render(Rgb565::BLACK, &mut [&mut item])?;
/// assert_eq!(frame.pixels().iter().filter(|&&p| p != Rgb565::BLACK).count(), 28 * 28);
/// # Ok::<(), fixshade::error::Error>(())
/// ```
pub fn draw_triangle<K: Kernel>(
    band: &mut BandView<'_, K::Color>,
    space: &ClipSpace,
    kernel: &K,
    corners: &[Corner; 3],
    cull: Cull,
) {
    if space.is_perspective() {
        front::<K, true>(band, space, kernel, corners, cull)
    } else {
        front::<K, false>(band, space, kernel, corners, cull)
    }
}

/// [`draw_triangle`] in a clip space known to be perspective (`PERSP`) or
/// not.
fn front<K: Kernel, const PERSP: bool>(
    band: &mut BandView<'_, K::Color>,
    space: &ClipSpace,
    kernel: &K,
    corners: &[Corner; 3],
    cull: Cull,
) {
    let v = corners.map(|c| kernel.vertex(&c.vertex));
    let eye = if K::NEEDS_POSITION {
        corners.map(|c| c.vertex.eye)
    } else {
        [[0; 3]; 3]
    };
    let clip = corners.map(|c| c.clip);
    let screen = clip.map(|c| super::vertex::window::<PERSP>(space, c));
    let inside = screen.iter().all(Option::is_some);
    let xy = screen.map(|s| s.map_or((0, 0), |s| (i32::from(s.0), i32::from(s.1))));
    let rows = classify::<PERSP>(
        inside.then_some(xy),
        || Some((clip, *space)),
        cull,
        band.width,
        u32::MAX,
    );
    if rows.is_none() {
        return;
    }
    let (t, var) = kernel.triangle([&v[0], &v[1], &v[2]], &eye);
    if inside {
        let z = screen.map(|s| s.map_or(0, |s| s.2));
        let w = clip.map(|c| if PERSP { c.w } else { 1 });
        let _ = draw::<K, PERSP>(kernel, &t, xy, z, w, &var, None, band);
    } else {
        let c: [ClipCorner<K::Varyings>; 3] = core::array::from_fn(|k| ClipCorner {
            c: clip[k],
            v: var[k],
        });
        draw_clipped::<K, PERSP>(kernel, &t, &c, space, band);
    }
}
