//! A mesh prepared for one frame and drawn band by band.

use super::bins::{self, Bins};
use super::refine::{RefineStats, Refined};
use super::tri::{self, ClipCorner, Resume};
use super::vertex::{self, CachedVertex};
use super::{BandView, DrawBand, Layout, RenderError};
use crate::camera::SUBPIXEL_BITS;
use crate::camera::{MeshTransform, Orthographic, Projection};
use crate::mesh::Mesh;
use crate::num::Zeroed;
use crate::raster::Cull;
use crate::shade::Kernel;

/// What a triangle that continues into the next band keeps: its index, the
/// bound columns of its two edges at the band's first row and whether its
/// runs are clamped (the short edge's column doubled plus that flag: columns
/// of the set-up window fit 12 bits), 6 bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Carry {
    tri: u16,
    long: i16,
    short: i16,
}

impl Carry {
    /// An empty record (for arrays built by a `const fn`).
    pub const ZERO: Carry = Carry {
        tri: 0,
        long: 0,
        short: 0,
    };

    /// `long` of a triangle set up again in the band it continues into: one
    /// drawn through the clipping path (clipped and set up again in every
    /// band), or one a band renderer did not draw in the band before.
    const COLD: i16 = i16::MIN;

    /// The record of triangle `tri`, set up again where it continues.
    fn cold(tri: u16) -> Carry {
        Carry {
            tri,
            long: Carry::COLD,
            short: 0,
        }
    }

    /// The record of triangle `tri` continuing as `r` says.
    fn new(tri: u16, r: Resume) -> Carry {
        Carry {
            tri,
            long: r.cols.0 as i16,
            short: (r.cols.1 << 1 | i32::from(r.clamp)) as i16,
        }
    }

    /// Where the triangle continues (`None`: set up again).
    fn resume(self) -> Option<Resume> {
        (self.long != Carry::COLD).then_some(Resume {
            cols: (i32::from(self.long), i32::from(self.short) >> 1),
            clamp: self.short & 1 != 0,
        })
    }
}

/// One band renderer's way through a mesh's bands: its resume records, in
/// two halves (the band drawn writes one, the next band reads it), and the
/// band they continue into.
#[derive(Debug, Default)]
struct Progress<'c> {
    carry: &'c mut [Carry],
    /// Entries of the current half of `carry` and which half (0 or 1).
    carried: usize,
    half: usize,
    /// The band the current half's records continue into (0 before any).
    next: u32,
}

impl Progress<'_> {
    /// The current half (read) and the other (written).
    #[inline(always)]
    fn halves(&mut self) -> (&[Carry], &mut [Carry]) {
        let cap = self.carry.len() / 2;
        let (a, b) = self.carry.split_at_mut(cap);
        let (read, write) = if self.half == 0 { (a, b) } else { (b, a) };
        let n = self.carried.min(read.len());
        (&read[..n], write)
    }

    /// Makes the half written (`written` records) the current one.
    fn flip(&mut self, written: usize) {
        self.carried = written;
        self.half ^= 1;
    }
}

/// Per-mesh drawing options, the last argument of [`MeshDraw::new`].
/// [`DrawOptions::default()`] culls back faces and nothing else.
///
/// ```
/// use fixshade::raster::Cull;
/// use fixshade::render::DrawOptions;
/// // both faces, the vertex stage run by the caller (see MeshDraw::light_vertices)
/// let opts = DrawOptions { cull: Cull::None, lit: true, ..DrawOptions::default() };
/// # let _ = opts;
/// ```
#[derive(Debug)]
pub struct DrawOptions<R = ()> {
    /// Face culling (back faces by default).
    pub cull: Cull,
    /// Silhouette refinement: none (`()`, the default: no refinement code is
    /// linked) or a [`Refine`](super::refine::Refine) with its memory (see
    /// [`refine`](super::refine)).
    pub refine: R,
    /// Whether the vertex cache already holds this frame's lit vertices,
    /// every vertex of the mesh, for the same transform and shader (the
    /// vertex stage run in pieces by [`MeshDraw::light_vertices`], for
    /// example half on each core): then only the bins are built. A cache not
    /// filled so draws a wrong picture. `false` by default.
    pub lit: bool,
}

impl<R> DrawOptions<R> {
    /// The same options with silhouette refinement `refine` (a
    /// [`Refine`](super::refine::Refine)).
    pub fn with_refine<R2>(self, refine: R2) -> DrawOptions<R2> {
        DrawOptions {
            cull: self.cull,
            refine,
            lit: self.lit,
        }
    }
}

impl Default for DrawOptions {
    /// Back faces culled, no refinement, the vertex stage run by
    /// [`MeshDraw::new`].
    fn default() -> Self {
        DrawOptions {
            cull: Cull::Back,
            refine: (),
            lit: false,
        }
    }
}

/// What [`DrawOptions::refine`] may hold: `()` (no refinement) or a
/// [`Refine`](super::refine::Refine). Sealed: the trait and the refinement's
/// results are not nameable outside the crate.
#[allow(private_interfaces)]
mod refinement {
    use super::super::refine::{self, Refine, Refined};
    use super::RenderError;
    use crate::camera::{MeshTransform, Projection};
    use crate::mesh::Mesh;
    use crate::shade::Kernel;

    /// Silhouette refinement or none.
    pub trait Refinement<'a, V> {
        /// The refined vertices and triangles for this frame.
        fn build<K: Kernel<Vertex = V>, P: Projection>(
            self,
            mesh: &Mesh<'a>,
            t: &MeshTransform<P>,
            kernel: &K,
        ) -> Result<Refined<'a, V>, RenderError>;
    }

    impl<'a, V: Copy + Default> Refinement<'a, V> for () {
        #[inline(always)]
        fn build<K: Kernel<Vertex = V>, P: Projection>(
            self,
            _: &Mesh<'a>,
            _: &MeshTransform<P>,
            _: &K,
        ) -> Result<Refined<'a, V>, RenderError> {
            Ok(Refined::default())
        }
    }

    impl<'a, V: Copy> Refinement<'a, V> for Refine<'a, V> {
        fn build<K: Kernel<Vertex = V>, P: Projection>(
            self,
            mesh: &Mesh<'a>,
            t: &MeshTransform<P>,
            kernel: &K,
        ) -> Result<Refined<'a, V>, RenderError> {
            refine::build(mesh, t, kernel, self)
        }
    }
}
use refinement::Refinement;

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
    /// frame; none for a mesh drawn only through
    /// [`MeshDraw::share`]s, each with its own records).
    pub carry: &'a mut [Carry],
}

/// [`MeshMemory`] as arrays: `NV` vertices, `NB` bin entries, `NC` resume
/// records. The payload type `V` is inferred from the shader. `new` is a
/// `const fn`: the buffers can live in a `static` in `.bss`, never on the stack
/// (unlike `cortex_m::singleton!` or `StaticCell::init`), e.g. through
/// `static_cell::ConstStaticCell`, which hands out the `&'static mut` once
/// without `unsafe`.
///
/// ```
/// use fixshade::render::{bins_len, MeshBuffers};
/// // the standard sphere (362 vertices, 720 triangles) in 30 bands
/// static BUFFERS: MeshBuffers<[u16; 3], 362, { bins_len(720, 30) }, 64> = MeshBuffers::new();
/// assert_eq!(core::mem::size_of_val(&BUFFERS), 362 * 12 + 782 * 2 + 64 * 6);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct MeshBuffers<V, const NV: usize, const NB: usize, const NC: usize> {
    vertices: [CachedVertex<V>; NV],
    bins: [u16; NB],
    carry: [Carry; NC],
}

impl<V: Zeroed, const NV: usize, const NB: usize, const NC: usize> MeshBuffers<V, NV, NB, NC> {
    /// Zeroed buffers (a `const fn`).
    pub const fn new() -> Self {
        MeshBuffers {
            vertices: [CachedVertex::ZERO; NV],
            bins: [0; NB],
            carry: [Carry::ZERO; NC],
        }
    }
}

impl<V, const NV: usize, const NB: usize, const NC: usize> MeshBuffers<V, NV, NB, NC> {
    /// The buffers as slices.
    pub fn memory(&mut self) -> MeshMemory<'_, V> {
        MeshMemory {
            vertices: &mut self.vertices,
            bins: &mut self.bins,
            carry: &mut self.carry,
        }
    }
}

impl<V: Zeroed, const NV: usize, const NB: usize, const NC: usize> Default
    for MeshBuffers<V, NV, NB, NC>
{
    fn default() -> Self {
        Self::new()
    }
}

/// A mesh prepared for one frame: its vertices transformed, projected and lit
/// into the vertex cache, its visible triangles binned. Drawn by
/// [`Bands::render`](crate::framebuffer::Bands::render) or
/// [`FullFrame::render`](crate::framebuffer::FullFrame::render) through [`DrawBand`].
///
/// Memory, all the caller's: [`MeshMemory`] (or [`MeshBuffers`]) lists it;
/// [`MeshDraw::new`] reports the resume records a frame needs.
///
/// The projection `P` comes from the transform's type:
/// - [`Orthographic`]: values interpolated screen-linearly (exact for an
///   orthographic projection), no division, no perspective code linked;
///   triangles reaching beyond the set-up window are clipped to it.
/// - [`Perspective`](crate::camera::Perspective): each vertex divided by its
///   `w` once per frame; every interpolated value is perspective-correct as in
///   OpenGL (exact at every 8th pixel of a run and its last, linear between:
///   [`interp`](crate::raster::interp)); depth (`z/w`) is exact. A triangle
///   behind the near plane or beyond the window is clipped in clip space, each
///   cut point computed from its edge's endpoints in canonical order, so meshes
///   stay watertight (the property tests render random sheets through the near
///   plane and count every pixel). No far-plane clipping: depth saturates at
///   65535 beyond it.
pub struct MeshDraw<'a, K: Kernel, P: Projection = Orthographic> {
    prep: Binned<'a, K, P>,
    /// This renderer's resume records and where it is in the frame.
    progress: Progress<'a>,
}

/// What every band renderer of a [`MeshDraw`] reads: the mesh, its frame's
/// transform, shader, vertex cache and bins.
#[derive(Clone)]
struct Binned<'a, K: Kernel, P: Projection> {
    mesh: Mesh<'a>,
    transform: MeshTransform<P>,
    kernel: K,
    layout: Layout,
    cache: &'a [CachedVertex<K::Vertex>],
    bins: Bins<'a>,
    /// Silhouette refinement's vertices and triangles (empty without).
    refined: Refined<'a, K::Vertex>,
    cull: Cull,
}

impl<K: Kernel, P: Projection> core::fmt::Debug for MeshDraw<'_, K, P> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MeshDraw")
            .field("vertices", &self.prep.mesh.vertex_count())
            .field("triangles", &self.prep.mesh.triangle_count())
            .field("crossing", &self.prep.bins.crossing)
            .finish_non_exhaustive()
    }
}

impl<'a, K: Kernel, P: Projection> MeshDraw<'a, K, P> {
    /// Runs the vertex stage and bins the triangles of `mesh` seen through
    /// `transform`, for a frame of `layout`, drawn with `shader`, in the
    /// caller's `memory`; `options`: culling, silhouette refinement, a vertex
    /// stage already run ([`DrawOptions`]).
    ///
    /// With refinement ([`refine`](super::refine)), the triangles along the
    /// outline are then subdivided into curved pieces, drawn after the mesh's
    /// own in each band (a banded frame is still the full frame bit for bit).
    /// The bins must hold them too: [`bins_len`](super::bins_len)`(triangles +
    /// refine triangle budget, bands)` always suffices.
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// use fixshade::render::{refine::RefineBuffers, DrawOptions};
    /// use fixshade::standard::{lambert, transform, SPHERE};
    /// let (t, lighting) = (transform()?, lambert::<Q14>()?);
    /// let shader = Shader::new(GouraudShading, &lighting, Linear);
    /// let mut mem: MeshBuffers<[u16; 3], 362, { bins_len(720 + 256, 1) }, 0> = MeshBuffers::new();
    /// let mut refine: RefineBuffers<[u16; 3], 362, 64, 256> = RefineBuffers::new();
    /// let options = DrawOptions::default().with_refine(refine.refine(0));
    /// let mut draw = MeshDraw::new(Layout::full(240, 240)?, SPHERE.mesh(), &t, shader, mem.memory(), options)?;
    /// assert!(draw.refine_stats().vertices > 0);
    /// let (mut color, mut depth) = (vec![Rgb565::BLACK; 240 * 240], vec![0u16; 240 * 240]);
    /// FullFrame::new(240, 240, &mut color, Some(&mut depth))?.render(Rgb565::BLACK, &mut [&mut draw])?;
    /// # Ok::<(), fixshade::error::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// Nothing is drawn on an error. [`RenderError::BufferTooSmall`] for a
    /// vertex cache or refinement `vertex_words` shorter than the mesh's
    /// vertices, too few bins, or too few resume records (none given: checked
    /// before drawing, unless drawn only through [`MeshDraw::share`]s);
    /// [`RenderError::MissingAttribute`] when the shader reads texture
    /// coordinates or tangents the mesh lacks; [`RenderError::TooManyVertices`]
    /// when the mesh and its replacing triangles exceed `u16` indices.
    pub fn new<R: Refinement<'a, K::Vertex>>(
        layout: Layout,
        mesh: Mesh<'a>,
        transform: &MeshTransform<P>,
        shader: K,
        memory: MeshMemory<'a, K::Vertex>,
        options: DrawOptions<R>,
    ) -> Result<Self, RenderError> {
        let MeshMemory {
            vertices: cache,
            bins,
            carry,
        } = memory;
        let kernel = shader;
        if K::NEEDS_TEXCOORD && mesh.texcoords().is_empty() {
            return Err(RenderError::MissingAttribute("texture coordinates"));
        }
        if K::NEEDS_TANGENT && mesh.tangents().is_empty() {
            return Err(RenderError::MissingAttribute("tangents"));
        }
        RenderError::check_len("vertex cache", mesh.vertex_count(), cache.len())?;
        if !options.lit {
            vertex::stage(&mesh, transform, &kernel, 0, cache);
        }
        let refined = options.refine.build(&mesh, transform, &kernel)?;
        let mut prep = Binned {
            mesh,
            transform: *transform,
            kernel,
            layout,
            cache,
            bins: Bins::default(),
            refined,
            cull: options.cull,
        };
        let total = mesh
            .triangle_count()
            .saturating_add(prep.refined.triangles.len());
        let classify = |t: usize| prep.classify(t);
        let sorted = bins::sort(&layout, total, classify, bins)?;
        prep.bins = sorted;
        // none: drawn only through shares (checked again before drawing)
        if !carry.is_empty() {
            prep.check_carry(carry.len())?;
        }
        Ok(MeshDraw {
            prep,
            progress: Progress {
                carry,
                ..Progress::default()
            },
        })
    }

    /// The vertex stage of [`MeshDraw::new`] for vertices `first .. first +
    /// part.len()` of `mesh` (fewer at its end) into `part`, those entries of
    /// the cache: e.g. half the cache on each core (`split_at_mut`), then
    /// [`MeshDraw::new`] with [`DrawOptions::lit`].
    pub fn light_vertices(
        mesh: &Mesh<'_>,
        transform: &MeshTransform<P>,
        kernel: &K,
        first: usize,
        part: &mut [CachedVertex<K::Vertex>],
    ) {
        vertex::stage(mesh, transform, kernel, first, part);
    }

    /// This prepared mesh for another band renderer with its own resume
    /// records `carry` (as many as [`MeshDraw::carry_needed`]; too few are
    /// refused by [`DrawBand::check`] before anything is drawn), sharing the
    /// cache, bins and shader read-only. Renderers with their own strips draw
    /// disjoint bands of one frame, e.g. one per core
    /// ([`Bands::render_bands`](crate::framebuffer::Bands::render_bands)), bit
    /// for bit the single-renderer frame. Each goes top down; give each one run
    /// of bands (e.g. the upper and lower half): after a gap every triangle
    /// reaching into the band from above is set up again.
    ///
    /// ```
    /// # use fixshade::prelude::*;
    /// # use fixshade::render::{bins_len, Carry, MeshBuffers, MeshDraw};
    /// # use fixshade::framebuffer::{Bands, Layout};
    /// # use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
    /// # let lighting = fixshade::standard::lambert::<Q14>().unwrap();
    /// # let t = fixshade::standard::transform().unwrap();
    /// let layout = Layout::banded(240, 240, 8)?;
    /// let mut mem: MeshBuffers<[u16; 3], 362, { bins_len(720, 30) }, 0> = MeshBuffers::new();
    /// let shader = Shader::new(GouraudShading, &lighting, Linear);
    /// let draw = MeshDraw::new(layout, fixshade::standard::SPHERE.mesh(), &t, shader, mem.memory(), DrawOptions::default())?;
    /// let mut carry = [[Carry::ZERO; 64]; 2];
    /// let mut strips = [[Rgb565::BLACK; 240 * 8]; 2];
    /// let mut depths = [[0u16; 240 * 8]; 2];
    /// std::thread::scope(|s| {
    ///     for (((half, carry), strip), depth) in
    ///         [0..15, 15..30].into_iter().zip(&mut carry).zip(&mut strips).zip(&mut depths)
    ///     {
    ///         let draw = &draw;
    ///         s.spawn(move || -> Result<(), fixshade::error::Error> {
    ///             let mut mine = draw.share(carry);
    ///             let mut bands = Bands::new(layout, strip, Some(depth))?;
    ///             let mut display = fixshade::framebuffer::Checksum::new((240, 240).into());
    ///             bands.render_bands(&mut display, Rgb565::BLACK, &mut [&mut mine], half)?;
    ///             Ok(())
    ///         });
    ///     }
    /// });
    /// # Ok::<(), fixshade::error::Error>(())
    /// ```
    #[inline(always)]
    pub fn share<'b>(&'b self, carry: &'b mut [Carry]) -> MeshDraw<'b, K, P>
    where
        K: Clone,
    {
        MeshDraw {
            prep: self.prep.clone(),
            progress: Progress {
                carry,
                ..Progress::default()
            },
        }
    }

    /// What this frame's silhouette refinement produced (zeros without).
    pub fn refine_stats(&self) -> RefineStats {
        self.prep.refined.stats
    }

    /// Resume records this frame needs (twice the largest number of
    /// triangles crossing one band boundary).
    pub fn carry_needed(&self) -> usize {
        self.prep.carry_needed()
    }
}

impl<K: Kernel, P: Projection> Binned<'_, K, P> {
    /// Resume records a band renderer needs.
    fn carry_needed(&self) -> usize {
        2 * self.bins.crossing
    }

    /// [`RenderError::BufferTooSmall`] for fewer than the resume records this
    /// frame needs.
    fn check_carry(&self, got: usize) -> Result<(), RenderError> {
        RenderError::check_len("carry", self.carry_needed(), got)
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

    /// The vertices of triangle `t`: a mesh triangle (`None` when the
    /// refinement replaces it), then the refinement's.
    #[inline]
    fn indices(&self, t: usize) -> Option<[usize; 3]> {
        let nt = self.mesh.triangle_count();
        if t < nt {
            let idx = *self.mesh.triangles().get(t)?;
            Some(idx.map(usize::from))
        } else {
            let r = self.refined.triangles.get(t - nt)?;
            Some([r[0], r[1], r[2]].map(usize::from))
        }
    }

    /// The rows of triangle `t` in the frame, or `None` when it is culled,
    /// replaced, degenerate or outside the frame.
    #[inline(never)]
    fn classify(&self, t: usize) -> Option<(u32, u32)> {
        let nt = self.mesh.triangle_count();
        if t < nt {
            let idx = *self.mesh.triangles().get(t)?;
            if self.refined.replaced(t, idx) {
                return None;
            }
        }
        let idx = self.indices(t)?;
        let v = [
            self.vertex(idx[0])?,
            self.vertex(idx[1])?,
            self.vertex(idx[2])?,
        ];
        let inside = v[0].inside() && v[1].inside() && v[2].inside();
        let clip = || {
            let c = [
                self.transform.clip(self.position(idx[0])?),
                self.transform.clip(self.position(idx[1])?),
                self.transform.clip(self.position(idx[2])?),
            ];
            Some((c, self.transform.clip_space()))
        };
        let screen = inside.then(|| v.map(|c| c.screen()));
        let (w, h) = (self.layout.width(), self.layout.height());
        if P::PERSPECTIVE {
            tri::classify::<true>(screen, clip, self.cull, w, h)
        } else {
            tri::classify::<false>(screen, clip, self.cull, w, h)
        }
    }

    /// Draws triangle `tri` into `band`, starting at the band's first row when
    /// `resume` holds its edge columns there; what the next band needs when
    /// it continues.
    #[inline(always)]
    fn triangle(
        &self,
        tri: u16,
        resume: Option<Resume>,
        band: &mut BandView<'_, K::Color>,
    ) -> Option<Carry> {
        let idx = self.indices(usize::from(tri))?;
        let v = [
            self.vertex(idx[0])?,
            self.vertex(idx[1])?,
            self.vertex(idx[2])?,
        ];
        let eye = if K::NEEDS_POSITION {
            idx.map(|i| self.position(i).map_or([0; 3], |p| self.transform.eye(p)))
        } else {
            [[0; 3]; 3]
        };
        let (t, var) = self.kernel.triangle([&v[0].v, &v[1].v, &v[2].v], &eye);
        if !(v[0].inside() && v[1].inside() && v[2].inside()) {
            return self.clipped(tri, idx, &t, &var, band);
        }
        let w = if P::PERSPECTIVE {
            idx.map(|i| self.position(i).map_or(1, |p| self.transform.clip(p).w))
        } else {
            [1; 3]
        };
        let xy = v.map(|c| (i32::from(c.x), i32::from(c.y)));
        let z = v.map(|c| c.z);
        let next = if P::PERSPECTIVE {
            tri::draw::<K, true>(&self.kernel, &t, xy, z, w, &var, resume, band)
        } else {
            tri::draw::<K, false>(&self.kernel, &t, xy, z, w, &var, resume, band)
        }?;
        Some(Carry::new(tri, next))
    }

    /// A triangle with a vertex outside the set-up window (or, in perspective,
    /// behind the near plane): clipped in clip space, the pieces drawn for
    /// this band; clipped and set up again in every band it continues into.
    #[inline(never)]
    #[cold]
    fn clipped(
        &self,
        tri: u16,
        idx: [usize; 3],
        t: &K::Triangle,
        var: &[K::Varyings; 3],
        band: &mut BandView<'_, K::Color>,
    ) -> Option<Carry> {
        let c: [ClipCorner<K::Varyings>; 3] = [
            ClipCorner {
                c: self.transform.clip(self.position(idx[0])?),
                v: var[0],
            },
            ClipCorner {
                c: self.transform.clip(self.position(idx[1])?),
                v: var[1],
            },
            ClipCorner {
                c: self.transform.clip(self.position(idx[2])?),
                v: var[2],
            },
        ];
        let space = self.transform.clip_space();
        let more = if P::PERSPECTIVE {
            tri::draw_clipped::<K, true>(&self.kernel, t, &c, &space, band)
        } else {
            tri::draw_clipped::<K, false>(&self.kernel, t, &c, &space, band)
        };
        more.then_some(Carry::cold(tri))
    }

    /// Bands this renderer does not draw, from `p.next` to `b`: the records
    /// become those of every triangle starting above `b` and reaching its
    /// first row, in mesh order, each to be set up again (at most the
    /// triangles crossing one boundary, which the records hold).
    #[inline(never)]
    #[cold]
    fn catch_up(&self, p: &mut Progress<'_>, b: u32) {
        let from = p.next;
        p.next = b;
        for s in from..b {
            self.merge(p, Err(s));
        }
    }

    /// One band's triangles: the records' merged in mesh order with those
    /// starting in the band. Each is drawn into `Ok(band)`, its record kept when
    /// it continues (a band at or above the last one drawn starts a new frame;
    /// after a gap, [`Binned::catch_up`] first); for `Err(b)` not drawn, kept
    /// when it reaches band `p.next`'s first row. (Three arguments: a tail call
    /// from `draw_band`, no stack frame between.)
    fn merge(&self, p: &mut Progress<'_>, mut to: Result<&mut BandView<'_, K::Color>, u32>) {
        let b = match &to {
            Ok(band) => {
                let b = self.layout.band_of(band.rows().start.max(0) as u32);
                if b < p.next {
                    p.carried = 0;
                    p.next = 0;
                }
                if b > p.next {
                    self.catch_up(p, b);
                }
                p.next = b + 1;
                b
            }
            Err(b) => *b,
        };
        let new = self.bins.band(b);
        let row = self.layout.rows(p.next).start;
        let (old, out) = p.halves();
        let mut written = 0;
        let (mut i, mut j) = (0, 0);
        loop {
            let (c, t, take_old) = match (old.get(i), new.get(j)) {
                (Some(&o), Some(&n)) => (o, n, o.tri < n),
                (Some(&o), None) => (o, 0, true),
                (None, Some(&n)) => (Carry::default(), n, false),
                (None, None) => break,
            };
            let (tri, resume) = if take_old {
                i += 1;
                (c.tri, c.resume())
            } else {
                j += 1;
                (t, None)
            };
            let next = match &mut to {
                Ok(band) => self.triangle(tri, resume, band),
                Err(_) => (self.last_row(usize::from(tri)) >= row).then_some(Carry::cold(tri)),
            };
            if let Some(c) = next {
                if let Some(slot) = out.get_mut(written) {
                    *slot = c;
                    written += 1;
                }
            }
        }
        p.flip(written);
    }

    /// The last frame row of triangle `t` (−1 when it is not drawn): from
    /// the cached screen positions, as [`Binned::classify`] computes it.
    fn last_row(&self, t: usize) -> i32 {
        let y = |i: usize| self.vertex(i).filter(|v| v.inside()).map(|v| v.y);
        let inside = self
            .indices(t)
            .and_then(|idx| Some(y(idx[0])?.max(y(idx[1])?).max(y(idx[2])?)));
        match inside {
            Some(ymax) => (i32::from(ymax) - (1 << (SUBPIXEL_BITS - 1))) >> SUBPIXEL_BITS,
            None => self.classify(t).map_or(-1, |(_, r1)| r1 as i32),
        }
    }
}

impl<K: Kernel, P: Projection> DrawBand<K::Color> for MeshDraw<'_, K, P> {
    fn check(&self, layout: Layout) -> Result<(), RenderError> {
        let l = self.prep.layout;
        if (layout.width(), layout.height(), layout.band_rows())
            != (l.width(), l.height(), l.band_rows())
        {
            return Err(RenderError::LayoutMismatch);
        }
        self.prep.check_carry(self.progress.carry.len())
    }

    fn draw_band(&mut self, band: &mut BandView<'_, K::Color>) {
        self.prep.merge(&mut self.progress, Ok(band));
    }
}
