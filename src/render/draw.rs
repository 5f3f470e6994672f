//! A mesh prepared for one frame and drawn band by band.

use super::bins::{self, Bins};
use super::hclip::{self, HPoint, HPolygon};
use super::refine::{self, Refine, RefineStats, Refined};
use super::vertex::{self, CachedVertex};
use super::{BandView, DrawBand, Layout, RenderError};
use crate::camera::{Clip, MeshTransform, Orthographic, Projection};
use crate::mesh::Mesh;
use crate::num::wide::lerp_i32;
use crate::raster::clip::{ClipPoint, Polygon};
use crate::raster::setup::at3;
use crate::raster::{Cull, Setup, Walker, ATTR_FRAC, SUBPIXEL_BITS};
use crate::shade::Kernel;

/// What a triangle that continues into the next band keeps: its index and
/// the bound columns of its two edges at the band's first row (6 bytes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Carry {
    tri: u16,
    long: i16,
    short: i16,
}

impl Carry {
    /// `long` of a triangle drawn through the clipping path: it is clipped and
    /// set up again in every band.
    const CLIPPED: i16 = i16::MIN;
}

/// Per-mesh drawing options.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DrawOptions {
    /// Face culling (back faces by default).
    pub cull: Cull,
}

impl Default for DrawOptions {
    /// Back faces culled.
    fn default() -> Self {
        DrawOptions { cull: Cull::Back }
    }
}

/// The caller-owned memory of one [`MeshDraw`]: the vertex cache, the bins and
/// the resume records, as slices (see [`MeshBuffers`] for arrays sized by
/// const generics).
#[derive(Debug)]
pub struct MeshMemory<'a, V> {
    /// One entry per mesh vertex.
    pub vertices: &'a mut [CachedVertex<V>],
    /// See [`bins_len`](super::bins_len).
    pub bins: &'a mut [u16],
    /// Twice the most triangles crossing one band boundary (none for a full
    /// frame).
    pub carry: &'a mut [Carry],
}

/// [`MeshMemory`] as arrays: `NV` vertices, `NB` bin entries, `NC` resume
/// records. The payload type `V` is inferred from the shader.
///
/// ```
/// use fixshade::render::{bins_len, MeshBuffers};
/// // the standard sphere (362 vertices, 720 triangles) in 30 bands
/// let buffers: MeshBuffers<[u16; 3], 362, { bins_len(720, 30) }, 64> = MeshBuffers::new();
/// assert_eq!(core::mem::size_of_val(&buffers), 362 * 12 + 782 * 2 + 64 * 6);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct MeshBuffers<V, const NV: usize, const NB: usize, const NC: usize> {
    vertices: [CachedVertex<V>; NV],
    bins: [u16; NB],
    carry: [Carry; NC],
}

impl<V: Copy + Default, const NV: usize, const NB: usize, const NC: usize>
    MeshBuffers<V, NV, NB, NC>
{
    /// Zeroed buffers.
    pub fn new() -> Self {
        MeshBuffers {
            vertices: [CachedVertex::default(); NV],
            bins: [0; NB],
            carry: [Carry::default(); NC],
        }
    }

    /// The buffers as slices.
    pub fn memory(&mut self) -> MeshMemory<'_, V> {
        MeshMemory {
            vertices: &mut self.vertices,
            bins: &mut self.bins,
            carry: &mut self.carry,
        }
    }
}

impl<V: Copy + Default, const NV: usize, const NB: usize, const NC: usize> Default
    for MeshBuffers<V, NV, NB, NC>
{
    fn default() -> Self {
        Self::new()
    }
}

/// A mesh prepared for one frame: its vertices transformed, projected and lit
/// into the vertex cache, its visible triangles binned. Drawn by
/// [`Bands::render`](super::Bands::render) or
/// [`FullFrame::render`](super::FullFrame::render) through [`DrawBand`].
///
/// Memory, all the caller's ([`MeshMemory`] or [`MeshBuffers`]):
/// - one [`CachedVertex`] per mesh vertex;
/// - the bins: see [`bins_len`](super::bins_len);
/// - the resume records: twice the largest number of triangles crossing one
///   band boundary (none for a full frame); [`MeshDraw::new`] reports the need.
///
/// The projection `P` comes from the transform's type:
/// - [`Orthographic`]: no division, no clip-space code linked; triangles
///   reaching beyond the set-up window are clipped to it exactly.
/// - [`Perspective`](crate::camera::Perspective): each vertex is divided by
///   its `w` once per frame. A triangle with a vertex behind the near plane or
///   beyond the window is clipped in clip space to the near plane and to a
///   guard band of ±2^26 sub-pixels ([`GUARD`](crate::camera::GUARD)), then
///   to the window; every cut point is computed from its edge's endpoints in
///   a canonical order, so meshes stay watertight across the near plane (the
///   property tests render random sheets through it and count every pixel).
///   Depth (`z/w`) is affine on the screen, so it is interpolated exactly;
///   the shading attributes (colours, normals, eye positions) are
///   interpolated affinely on the screen within each triangle, not
///   perspective-correctly: exact at the vertices, off inside a triangle by
///   the classic perspective distortion, which grows with the triangle's
///   depth range (negligible for the small triangles of a tessellated mesh,
///   visible on a large one spanning a wide depth range: subdivide it, or
///   use the per-triangle [`Shading::draw_perspective`](crate::shade::Shading::draw_perspective)).
///   No far-plane clipping: depth saturates at 65535 beyond it.
pub struct MeshDraw<'a, K: Kernel, P: Projection = Orthographic> {
    mesh: Mesh<'a>,
    transform: MeshTransform<P>,
    kernel: K,
    layout: Layout,
    cache: &'a [CachedVertex<K::Vertex>],
    bins: Bins<'a>,
    carry: &'a mut [Carry],
    /// Entries of the current half of `carry` and which half (0 or 1).
    carried: usize,
    half: usize,
    /// Silhouette refinement's vertices and triangles (empty without).
    refined: Refined<'a, K::Vertex>,
}

impl<K: Kernel, P: Projection> core::fmt::Debug for MeshDraw<'_, K, P> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MeshDraw")
            .field("vertices", &self.mesh.vertex_count())
            .field("triangles", &self.mesh.triangle_count())
            .field("crossing", &self.bins.crossing)
            .finish_non_exhaustive()
    }
}

impl<'a, K: Kernel, P: Projection> MeshDraw<'a, K, P>
where
    K::Vertex: Lerp,
{
    /// Runs the vertex stage and bins the triangles of `mesh` seen through
    /// `transform`, for a frame of `layout`, drawn with `shader` (back faces
    /// culled; see [`MeshDraw::with_options`]).
    ///
    /// # Errors
    ///
    /// [`RenderError::TooManyVertices`] when the mesh has more vertices than
    /// the cache holds; [`RenderError::BufferTooSmall`] for too few bins or
    /// resume records. Nothing is drawn then.
    pub fn new(
        layout: Layout,
        mesh: Mesh<'a>,
        transform: &MeshTransform<P>,
        shader: K,
        memory: MeshMemory<'a, K::Vertex>,
    ) -> Result<Self, RenderError> {
        Self::with_options(
            layout,
            mesh,
            transform,
            shader,
            DrawOptions::default(),
            memory,
        )
    }

    /// [`MeshDraw::new`] with options (culling).
    ///
    /// # Errors
    ///
    /// As [`MeshDraw::new`].
    pub fn with_options(
        layout: Layout,
        mesh: Mesh<'a>,
        transform: &MeshTransform<P>,
        kernel: K,
        opts: DrawOptions,
        memory: MeshMemory<'a, K::Vertex>,
    ) -> Result<Self, RenderError> {
        let MeshMemory {
            vertices: cache,
            bins,
            carry,
        } = memory;
        if cache.len() < mesh.vertex_count() {
            return Err(RenderError::TooManyVertices);
        }
        vertex::stage(&mesh, transform, &kernel, cache);
        let cache: &'a [CachedVertex<K::Vertex>] = cache;
        let classify = |t: usize| classify(&mesh, transform, cache, &layout, opts.cull, t);
        let bins = bins::sort(&layout, mesh.triangle_count(), classify, bins)?;
        if carry.len() < 2 * bins.crossing {
            return Err(RenderError::BufferTooSmall {
                buffer: "carry",
                needed: 2 * bins.crossing,
                got: carry.len(),
            });
        }
        Ok(MeshDraw {
            mesh,
            transform: *transform,
            kernel,
            layout,
            cache,
            bins,
            carry,
            carried: 0,
            half: 0,
            refined: Refined::default(),
        })
    }

    /// [`MeshDraw::with_options`] with silhouette refinement: after the vertex
    /// stage, the triangles along the outline of the mesh for this view are
    /// subdivided into curved (PN triangle) pieces within the budget of
    /// `refine` (see [`refine`](super::refine) for the rule, the geometry and
    /// what happens when the budget runs out). The new triangles are culled,
    /// binned and drawn like mesh triangles, after them within each band
    /// (so a banded frame is still the whole frame bit for bit).
    ///
    /// The bins must hold the replacing triangles too:
    /// [`bins_len`](super::bins_len)`(triangles + refine triangle budget, bands)`
    /// always suffices.
    ///
    /// ```
    /// use fixshade::camera::Camera;
    /// use fixshade::mesh::{uv_sphere_counts, Mat4, MeshData, Viewport};
    /// use fixshade::prelude::*;
    /// use fixshade::render::{bins_len, FullFrame, Layout, MeshBuffers, MeshDraw, RefineBuffers};
    /// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
    /// const N: (usize, usize) = uv_sphere_counts(8, 12);
    /// static SPHERE: MeshData<{ N.0 }, { N.1 }> = MeshData::uv_sphere(8, 12, 14);
    /// let cam = Camera::orthographic(-1.2, 1.2, -1.2, 1.2, 1.0, 10.0, Viewport::new(0, 0, 64, 64)?)?
    ///     .with_view(Mat4::translate([0.0, 0.0, -5.0]));
    /// let t = cam.mesh_transform(&Mat4::rotate_x(0.3), SPHERE.frac)?;
    /// let lighting = fixshade::standard::lambert::<Q14>().unwrap();
    /// let shader = Shader::new(GouraudShading, &lighting, Linear);
    /// let mut mem: MeshBuffers<[u16; 3], { N.0 }, { bins_len(N.1 + 256, 1) }, 0> = MeshBuffers::new();
    /// let mut refine: RefineBuffers<[u16; 3], { N.0 }, 64, 256> = RefineBuffers::new();
    /// let layout = Layout::full(64, 64).unwrap();
    /// let mut draw = MeshDraw::with_refinement(
    ///     layout, SPHERE.mesh(), &t, shader, Default::default(), mem.memory(), refine.refine(0),
    /// ).unwrap();
    /// assert!(draw.refine_stats().vertices > 0);
    /// let (mut color, mut depth) = ([Rgb565::BLACK; 64 * 64], [0u16; 64 * 64]);
    /// let mut frame = FullFrame::new(64, 64, &mut color, Some(&mut depth)).unwrap();
    /// frame.render(Rgb565::BLACK, &mut [&mut draw]);
    /// # Ok::<(), fixshade::mesh::MeshError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`MeshDraw::new`]; [`RenderError::BufferTooSmall`] for refinement
    /// memory shorter than the mesh's vertices (`vertex_words`), and
    /// [`RenderError::TooManyVertices`] when the mesh and its replacing
    /// triangles exceed `u16` indices.
    pub fn with_refinement(
        layout: Layout,
        mesh: Mesh<'a>,
        transform: &MeshTransform<P>,
        kernel: K,
        opts: DrawOptions,
        memory: MeshMemory<'a, K::Vertex>,
        refine: Refine<'a, K::Vertex>,
    ) -> Result<Self, RenderError> {
        let MeshMemory {
            vertices: cache,
            bins,
            carry,
        } = memory;
        if cache.len() < mesh.vertex_count() {
            return Err(RenderError::TooManyVertices);
        }
        vertex::stage(&mesh, transform, &kernel, cache);
        let refined = refine::build(&mesh, transform, &kernel, refine).map_err(|e| {
            RenderError::BufferTooSmall {
                buffer: e.buffer,
                needed: e.needed,
                got: e.got,
            }
        })?;
        let cache: &'a [CachedVertex<K::Vertex>] = cache;
        let nt = mesh.triangle_count();
        let nv = mesh.vertex_count();
        let vert = |i: usize| {
            if i < nv {
                cache.get(i)
            } else {
                refined.vertices.get(i - nv)
            }
        };
        let pos = |i: usize| {
            if i < nv {
                mesh.positions().get(i).copied()
            } else {
                refined.positions.get(i - nv).copied()
            }
        };
        let classify = |t: usize| {
            if t < nt {
                if refined.replaced(t) {
                    return None;
                }
                classify(&mesh, transform, cache, &layout, opts.cull, t)
            } else {
                let r = refined.triangles.get(t - nt)?;
                let idx = [r[0], r[1], r[2]].map(usize::from);
                classify_idx(idx, vert, pos, transform, &layout, opts.cull)
            }
        };
        let total = nt.saturating_add(refined.triangles.len());
        let bins = bins::sort(&layout, total, classify, bins)?;
        if carry.len() < 2 * bins.crossing {
            return Err(RenderError::BufferTooSmall {
                buffer: "carry",
                needed: 2 * bins.crossing,
                got: carry.len(),
            });
        }
        Ok(MeshDraw {
            mesh,
            transform: *transform,
            kernel,
            layout,
            cache,
            bins,
            carry,
            carried: 0,
            half: 0,
            refined,
        })
    }

    /// What this frame's silhouette refinement produced (zeros without).
    pub fn refine_stats(&self) -> RefineStats {
        self.refined.stats
    }

    /// Vertex `i` of the mesh and the refinement's new vertices after it.
    #[inline]
    fn vertex(&self, i: usize) -> Option<&CachedVertex<K::Vertex>> {
        let nv = self.mesh.vertex_count();
        if i < nv {
            self.cache.get(i)
        } else {
            self.refined.vertices.get(i - nv)
        }
    }

    /// The raw position of vertex `i` (mesh, then new vertices).
    #[inline]
    fn position(&self, i: usize) -> Option<[i16; 3]> {
        let nv = self.mesh.vertex_count();
        if i < nv {
            self.mesh.positions().get(i).copied()
        } else {
            self.refined.positions.get(i - nv).copied()
        }
    }

    /// A triangle replacing a refined one (`tri` beyond the mesh's
    /// triangles), drawn like [`MeshDraw::triangle`].
    #[inline(never)]
    fn refined_triangle(
        &self,
        tri: u16,
        resume: Option<(i32, i32)>,
        band: &mut BandView<'_, K::Color>,
    ) -> Option<Carry> {
        let r = self
            .refined
            .triangles
            .get(usize::from(tri).checked_sub(self.mesh.triangle_count())?)?;
        let idx = [r[0], r[1], r[2]].map(usize::from);
        let v = [
            self.vertex(idx[0])?,
            self.vertex(idx[1])?,
            self.vertex(idx[2])?,
        ];
        if !(v[0].inside() && v[1].inside() && v[2].inside()) {
            return self.clipped(tri, idx, band);
        }
        let xy = v.map(|c| (i32::from(c.x), i32::from(c.y)));
        let eye = if K::NEEDS_POSITION {
            idx.map(|i| self.position(i).map_or([0; 3], |p| self.transform.eye(p)))
        } else {
            [[0; 3]; 3]
        };
        let next = self.draw_setup(
            xy,
            [v[0].z, v[1].z, v[2].z],
            [&v[0].v, &v[1].v, &v[2].v],
            eye,
            resume,
            band,
        )?;
        Some(Carry {
            tri,
            long: next.0 as i16,
            short: next.1 as i16,
        })
    }

    /// Resume records this frame needs (twice the largest number of
    /// triangles crossing one band boundary).
    pub fn carry_needed(&self) -> usize {
        2 * self.bins.crossing
    }

    /// Draws triangle `tri` into `band`, starting at the band's first row when
    /// `resume` holds its edge columns there; the edge columns at the next
    /// band's first row when it continues.
    fn triangle(
        &self,
        tri: u16,
        resume: Option<(i32, i32)>,
        band: &mut BandView<'_, K::Color>,
    ) -> Option<Carry> {
        let Some(idx) = self.mesh.triangles().get(tri as usize) else {
            return self.refined_triangle(tri, resume, band);
        };
        let idx = idx.map(usize::from);
        let v = [
            self.cache.get(idx[0])?,
            self.cache.get(idx[1])?,
            self.cache.get(idx[2])?,
        ];
        if !(v[0].inside() && v[1].inside() && v[2].inside()) {
            return self.clipped(tri, idx, band);
        }
        let xy = v.map(|c| (i32::from(c.x), i32::from(c.y)));
        let eye = if K::NEEDS_POSITION {
            idx.map(|i| {
                self.mesh
                    .positions()
                    .get(i)
                    .map_or([0; 3], |p| self.transform.eye(*p))
            })
        } else {
            [[0; 3]; 3]
        };
        let next = self.draw_setup(
            xy,
            [v[0].z, v[1].z, v[2].z],
            [&v[0].v, &v[1].v, &v[2].v],
            eye,
            resume,
            band,
        )?;
        Some(Carry {
            tri,
            long: next.0 as i16,
            short: next.1 as i16,
        })
    }

    /// Sets up and draws one triangle inside the window; the edge columns at
    /// the next band's first row when it continues.
    fn draw_setup(
        &self,
        xy: [(i32, i32); 3],
        z: [u16; 3],
        pay: [&K::Vertex; 3],
        eye: [[i32; 3]; 3],
        resume: Option<(i32, i32)>,
        band: &mut BandView<'_, K::Color>,
    ) -> Option<(i32, i32)> {
        let mut s = Setup::new(xy, Cull::None)?;
        s.prepare_planes();
        let o = s.order;
        let row0 = s.rows.0;
        let mut zp = s.plane(o.map(|i| i32::from(at3(&z, i))));
        // depth with ATTR_FRAC bits, + ½ so that the shift rounds
        let zbase = (i32::from(at3(&z, at3(&o, s.tmb[0]))) << ATTR_FRAC) + (1 << (ATTR_FRAC - 1));
        let (mut t, kclamp) =
            self.kernel
                .triangle(&s, o.map(|i| at3(&pay, i)), o.map(|i| at3(&eye, i)));
        // depth values must stay in 0..65536 (with ATTR_FRAC bits)
        let clamp =
            kclamp || !crate::shade::within(&s, &zp, zbase, (0, (1 << (16 + ATTR_FRAC)) - 1));
        let rows = band.rows();
        let mut w = match resume {
            Some(cols) => Walker::resume(&s, rows.start, cols),
            None => s.walker(rows.start),
        };
        let skip = w.y - row0;
        if skip > 0 {
            K::skip_rows(&mut t, skip);
            zp.skip_rows(skip);
        }
        let last = w.last.min(rows.end - 1);
        zp.row = zp.row.wrapping_add(zbase);
        if clamp {
            self.rows::<true>(&mut w, last, &mut t, &mut zp, band);
        } else {
            self.rows::<false>(&mut w, last, &mut t, &mut zp, band);
        }
        w.more().then(|| w.snapshot())
    }

    /// The rows `w.y..=last` of a set-up triangle: the walker's columns, the
    /// depth test of each run (the depth plane `zp` holds absolute values), the
    /// kernel on the passing pixels (all of them without a depth buffer: a
    /// branch per row, not a second copy of the loop). `CLAMP`: values clamped
    /// per run.
    #[inline(always)]
    fn rows<const CLAMP: bool>(
        &self,
        w: &mut Walker,
        last: i32,
        t: &mut K::Triangle,
        zp: &mut crate::raster::Plane,
        band: &mut BandView<'_, K::Color>,
    ) {
        let width = band.width as i32;
        let start = band.rows.start;
        let mut row = (w.y - start) as usize * band.width as usize;
        while w.y <= last {
            let y = w.y;
            let (lo, hi) = w.next();
            let (lo, hi) = (lo.max(0), hi.min(width - 1));
            if lo <= hi {
                let n = (hi - lo + 1) as usize;
                let at = row + lo as usize;
                if let Some(color) = band.color.get_mut(at..at + n) {
                    if let Some(d) = band.depth.as_deref_mut() {
                        let (z0, dz) = crate::shade::start::<CLAMP>(zp, lo, n);
                        if let Some(depth) = d.get_mut(at..at + n) {
                            crate::shade::depth_runs(z0, dz, depth, |k0, k1| {
                                if let Some(c) = color.get_mut(k0..k1) {
                                    self.kernel.shade::<CLAMP>(t, lo + k0 as i32, y, c);
                                }
                            });
                        }
                    } else {
                        self.kernel.shade::<CLAMP>(t, lo, y, color);
                    }
                }
            }
            K::next_row(t);
            zp.next_row();
            row += band.width as usize;
        }
    }

    /// A triangle with a vertex outside the set-up window (or, in perspective,
    /// behind the near plane): clipped in full precision (in clip space to the
    /// near plane and the guard band, then to the window), the pieces drawn for
    /// this band; clipped and set up again in every band it continues into.
    /// Never inlined: its polygons stay off the common path's stack.
    #[inline(never)]
    #[cold]
    fn clipped(
        &self,
        tri: u16,
        idx: [usize; 3],
        band: &mut BandView<'_, K::Color>,
    ) -> Option<Carry> {
        let rows = band.rows();
        let mut more = false;
        pieces(
            |i| self.position(i),
            &self.transform,
            |i| self.vertex(i).map(|c| c.v),
            K::NEEDS_POSITION,
            idx,
            |pts| {
                let mut poly = Polygon::new(pts);
                poly.clip_to_window();
                let mut t = *pts;
                let mut k = 0;
                while poly.fan(k, &mut t) {
                    k += 1;
                    // the pieces' rows beyond this band are drawn in later bands
                    let bottom = t.iter().map(|p| p.y).max().unwrap_or(0);
                    if ((bottom - (1 << (SUBPIXEL_BITS - 1))) >> SUBPIXEL_BITS) >= rows.end {
                        more = true;
                    }
                    let xy = t.map(|p| (p.x, p.y));
                    let z = t.map(|p| p.z.clamp(0, 65535) as u16);
                    let eye = t.map(|p| p.eye);
                    let _ = self.draw_setup(xy, z, [&t[0].v, &t[1].v, &t[2].v], eye, None, band);
                }
            },
        )?;
        more.then_some(Carry {
            tri,
            long: Carry::CLIPPED,
            short: 0,
        })
    }
}

impl<K: Kernel, P: Projection> DrawBand<K::Color> for MeshDraw<'_, K, P>
where
    K::Vertex: Lerp,
{
    fn draw_band(&mut self, band: &mut BandView<'_, K::Color>) {
        let rows = band.rows();
        let b = self.layout.band_of(rows.start.max(0) as u32);
        let new = self.bins.band(b);
        // a new band without a carried list (the first band, or a full frame)
        if b == 0 {
            self.carried = 0;
        }
        // the carry slice is taken out of `self` while triangles are drawn
        let carry = core::mem::take(&mut self.carry);
        let cap = carry.len() / 2;
        let (read, write) = carry.split_at_mut(cap);
        let (old, out) = if self.half == 0 {
            (read, write)
        } else {
            (write, read)
        };
        let old = &old[..self.carried.min(old.len())];
        let mut written = 0;
        let (mut i, mut j) = (0, 0);
        // merge by triangle index: within the band, mesh order
        loop {
            let (c, t, take_old) = match (old.get(i), new.get(j)) {
                (Some(&o), Some(&n)) => (o, n, o.tri < n),
                (Some(&o), None) => (o, 0, true),
                (None, Some(&n)) => (Carry::default(), n, false),
                (None, None) => break,
            };
            let next = if take_old {
                i += 1;
                let resume =
                    (c.long != Carry::CLIPPED).then_some((i32::from(c.long), i32::from(c.short)));
                self.triangle(c.tri, resume, band)
            } else {
                j += 1;
                self.triangle(t, None, band)
            };
            if let Some(c) = next {
                if let Some(slot) = out.get_mut(written) {
                    *slot = c;
                    written += 1;
                }
            }
        }
        self.carried = written;
        self.half ^= 1;
        self.carry = carry;
    }
}

/// A vertex of the clipping path.
#[derive(Clone, Copy, Debug, Default)]
struct Point<V> {
    x: i32,
    y: i32,
    z: i32,
    v: V,
    eye: [i32; 3],
}

/// A vertex payload the clipping path can interpolate.
pub trait Lerp: Copy {
    /// The payload `num/den` of the way from `self` to `other`.
    fn lerp(&self, other: &Self, num: u32, den: u32) -> Self;
}

impl Lerp for [u16; 3] {
    fn lerp(&self, o: &Self, num: u32, den: u32) -> Self {
        core::array::from_fn(|i| lerp_i32(i32::from(self[i]), i32::from(o[i]), num, den) as u16)
    }
}

impl Lerp for [i16; 3] {
    fn lerp(&self, o: &Self, num: u32, den: u32) -> Self {
        core::array::from_fn(|i| lerp_i32(i32::from(self[i]), i32::from(o[i]), num, den) as i16)
    }
}

impl<V: Lerp + Default> ClipPoint for Point<V> {
    #[inline]
    fn xy(&self) -> (i32, i32) {
        (self.x, self.y)
    }

    fn cut(&self, o: &Self, num: u32, den: u32, xy: (i32, i32)) -> Self {
        let l = |a: i32, b: i32| lerp_i32(a, b, num, den);
        Point {
            x: xy.0,
            y: xy.1,
            z: l(self.z, o.z),
            v: self.v.lerp(&o.v, num, den),
            eye: core::array::from_fn(|i| l(self.eye[i], o.eye[i])),
        }
    }
}

/// A vertex of the perspective clipping path, in clip space.
#[derive(Clone, Copy, Debug, Default)]
struct HVertex<V> {
    c: Clip,
    v: V,
    eye: [i32; 3],
}

impl<V: Lerp + Default> HPoint for HVertex<V> {
    #[inline]
    fn clip(&self) -> Clip {
        self.c
    }

    fn hcut(&self, o: &Self, num: u32, den: u32, c: Clip) -> Self {
        HVertex {
            c,
            v: self.v.lerp(&o.v, num, den),
            eye: core::array::from_fn(|i| lerp_i32(self.eye[i], o.eye[i], num, den)),
        }
    }
}

impl Lerp for () {
    fn lerp(&self, _: &Self, _: u32, _: u32) -> Self {}
}

/// Calls `f` with the screen triangles of mesh triangle `idx`, before window
/// clipping: the triangle itself (orthographic), or the fan of its polygon
/// clipped to the near plane and the guard band (perspective). `payload(i)`
/// gives vertex `i`'s payload; eye positions are computed when `eye`.
/// `None` when an index or payload lookup fails.
fn pieces<V: Lerp + Default, P: Projection>(
    pos: impl Fn(usize) -> Option<[i16; 3]>,
    transform: &MeshTransform<P>,
    payload: impl Fn(usize) -> Option<V>,
    eye: bool,
    idx: [usize; 3],
    mut f: impl FnMut(&[Point<V>; 3]),
) -> Option<()> {
    let pos = [pos(idx[0])?, pos(idx[1])?, pos(idx[2])?];
    let pay = [payload(idx[0])?, payload(idx[1])?, payload(idx[2])?];
    let eyes = pos.map(|p| if eye { transform.eye(p) } else { [0; 3] });
    if P::PERSPECTIVE {
        let hv = [0, 1, 2].map(|k| HVertex {
            c: transform.clip_coords(pos[k]),
            v: pay[k],
            eye: eyes[k],
        });
        let poly = HPolygon::clipped(&hv, transform.near_units());
        let centre = transform.centre_sub();
        let screen = |h: &HVertex<V>| {
            let s = crate::camera::divide(centre, h.c);
            Point {
                x: s.x,
                y: s.y,
                z: i32::from(s.z),
                v: h.v,
                eye: h.eye,
            }
        };
        let vs = poly.vertices();
        for k in 1..vs.len().saturating_sub(1) {
            f(&[screen(&vs[0]), screen(&vs[k]), screen(&vs[k + 1])]);
        }
    } else {
        let mut pts = [Point::<V>::default(); 3];
        for k in 0..3 {
            let s = transform.screen(pos[k])?;
            pts[k] = Point {
                x: s.x,
                y: s.y,
                z: i32::from(s.z),
                v: pay[k],
                eye: eyes[k],
            };
        }
        f(&pts);
    }
    Some(())
}

/// The rows of triangle `t` clamped to the frame, or `None` when it is culled,
/// degenerate or outside the frame.
#[inline(always)]
fn classify<V, P: Projection>(
    mesh: &Mesh<'_>,
    transform: &MeshTransform<P>,
    cache: &[CachedVertex<V>],
    layout: &Layout,
    cull: Cull,
    t: usize,
) -> Option<(u32, u32)> {
    let idx = mesh.triangles().get(t)?.map(usize::from);
    classify_idx(
        idx,
        |i| cache.get(i),
        |i| mesh.positions().get(i).copied(),
        transform,
        layout,
        cull,
    )
}

/// [`classify`] for the triangle of vertices `idx`, looked up with `vert`
/// (cache entries) and `pos` (raw positions).
#[inline(always)]
fn classify_idx<'c, V: 'c, P: Projection>(
    idx: [usize; 3],
    vert: impl Fn(usize) -> Option<&'c CachedVertex<V>>,
    pos: impl Fn(usize) -> Option<[i16; 3]>,
    transform: &MeshTransform<P>,
    layout: &Layout,
    cull: Cull,
) -> Option<(u32, u32)> {
    let v = [vert(idx[0])?, vert(idx[1])?, vert(idx[2])?];
    let ((xmin, xmax, ymin, ymax), front) = if v[0].inside() && v[1].inside() && v[2].inside() {
        let p = v.map(|c| (i32::from(c.x), i32::from(c.y)));
        // A > 0: clockwise on the screen (a back face); products < 2^30
        let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[1].1 - p[0].1) * (p[2].0 - p[0].0);
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
    } else {
        let front = if P::PERSPECTIVE {
            hclip::facing([
                transform.clip_coords(pos(idx[0])?),
                transform.clip_coords(pos(idx[1])?),
                transform.clip_coords(pos(idx[2])?),
            ])?
        } else {
            let p = idx.map(|i| {
                pos(i)
                    .and_then(|p| transform.screen(p))
                    .map_or((0, 0), |s| (s.x, s.y))
            });
            let d1 = (
                i64::from(p[1].0) - i64::from(p[0].0),
                i64::from(p[1].1) - i64::from(p[0].1),
            );
            let d2 = (
                i64::from(p[2].0) - i64::from(p[0].0),
                i64::from(p[2].1) - i64::from(p[0].1),
            );
            match crate::raster::clip::cmp_products(d1.0, d2.1, d1.1, d2.0) {
                core::cmp::Ordering::Equal => return None,
                o => o == core::cmp::Ordering::Less,
            }
        };
        // the bounding box of what remains after clipping in clip space
        let mut bbox = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
        pieces(
            &pos,
            transform,
            |_| Some(()),
            false,
            idx,
            |t| {
                for p in t {
                    bbox = (
                        bbox.0.min(p.x),
                        bbox.1.max(p.x),
                        bbox.2.min(p.y),
                        bbox.3.max(p.y),
                    );
                }
            },
        )?;
        if bbox.0 > bbox.1 {
            return None;
        }
        (bbox, front)
    };
    let culled = match cull {
        Cull::None => false,
        Cull::Back => !front,
        Cull::Front => front,
    };
    if culled {
        return None;
    }
    let half = 1 << (SUBPIXEL_BITS - 1);
    // rows whose centre lies in [ymin, ymax], columns likewise
    let r0 = (ymin
        .saturating_sub(half)
        .saturating_add((1 << SUBPIXEL_BITS) - 1))
        >> SUBPIXEL_BITS;
    let r1 = ymax.saturating_sub(half) >> SUBPIXEL_BITS;
    let c0 = (xmin
        .saturating_sub(half)
        .saturating_add((1 << SUBPIXEL_BITS) - 1))
        >> SUBPIXEL_BITS;
    let c1 = xmax.saturating_sub(half) >> SUBPIXEL_BITS;
    let (h, w) = (layout.height() as i32, layout.width() as i32);
    if r1 < 0 || r0 >= h || r0 > r1 || c1 < 0 || c0 >= w || c0 > c1 {
        return None;
    }
    Some((r0.max(0) as u32, r1.min(h - 1) as u32))
}
