//! Shared by the pipeline-level tests (`raster_*`, `render_*`, `mesh_*`,
//! `framebuffer_pieces`, `target_framebuffers`, `one_pipeline`, …): kernels
//! of the tests' own (counting, solid, recording), triangle lists drawn
//! through the per-triangle front [`draw_triangle`], and frames rendered
//! whole ([`FullFrame`]) or in bands ([`Bands`]) into a `Vec`.

#![allow(dead_code)]

use std::cell::RefCell;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::{Gray8, GrayColor, PixelColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::camera::{Clip, ClipSpace, MeshTransform, Projection};
use fixshade::framebuffer::{BandView, Bands, DrawBand, FullFrame, Layout};
use fixshade::mesh::Mesh;
use fixshade::raster::Cull;
use fixshade::render::{
    bins_len, draw_triangle, CachedVertex, Carry, Corner, DrawOptions, MeshDraw, MeshMemory,
};
use fixshade::shade::{Kernel, VertexIn};

/// Sub-pixels per pixel.
pub const S: i32 = 1 << SUBPIXEL_BITS;

/// The sub-spans a run is cut into under a perspective projection: 8 pixels
/// (the `raster::interp` docs), so a kernel shades at most 8 pixels a call.
pub const PERSPECTIVE_SPAN: usize = 8;

/// A corner in screen space ([`ClipSpace::SCREEN`]): sub-pixel position,
/// depth `z`, and `value` (read by [`Record`] from `normal[0]`).
pub fn corner(x: i32, y: i32, z: i32, value: i32) -> Corner {
    Corner {
        clip: Clip { x, y, z, w: 1 },
        vertex: VertexIn::new([value, 0, 0], [0; 3]),
    }
}

/// A corner in clip coordinates (any [`ClipSpace`]), carrying `value`.
pub fn clip_corner(c: Clip, value: i32) -> Corner {
    Corner {
        clip: c,
        vertex: VertexIn::new([value, 0, 0], [0; 3]),
    }
}

/// Adds 1 to every pixel it shades (saturating): the frame counts writes.
#[derive(Clone, Copy, Debug, Default)]
pub struct Count;

impl Kernel for Count {
    type Color = Gray8;
    type Vertex = ();
    type Varyings = [i32; 0];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;

    fn vertex(&self, _: &VertexIn) {}

    fn triangle(&self, _: [&(); 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 0]; 3]) {
        ((), [[]; 3])
    }

    fn span(&self, _: &(), _: &[i32; 0], _: &[i32; 0], _: i32, _: i32, out: &mut [Gray8]) {
        for p in out {
            *p = Gray8::new(p.luma().saturating_add(1));
        }
    }
}

/// Paints one colour.
#[derive(Clone, Copy, Debug)]
pub struct Solid<C>(pub C);

impl<C: fixshade::color::OutputColor + core::fmt::Debug> Kernel for Solid<C> {
    type Color = C;
    type Vertex = ();
    type Varyings = [i32; 0];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;

    fn vertex(&self, _: &VertexIn) {}

    fn triangle(&self, _: [&(); 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 0]; 3]) {
        ((), [[]; 3])
    }

    fn span(&self, _: &(), _: &[i32; 0], _: &[i32; 0], _: i32, _: i32, out: &mut [C]) {
        out.fill(self.0);
    }
}

/// One shaded run as a kernel saw it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Run {
    pub x: i32,
    pub y: i32,
    pub len: usize,
    /// The values at the first pixel and the step (with `ATTR_FRAC` bits).
    pub start: i32,
    pub step: i32,
}

/// Interpolates one value (the corner's `normal[0]`, see [`corner`]) and
/// records every run it is handed; paints 1 (counting, like [`Count`]).
#[derive(Debug, Default)]
pub struct Record {
    pub runs: RefCell<Vec<Run>>,
}

impl Record {
    /// The value of every recorded pixel: `(x, y, start + k·step)` (64-bit,
    /// with `ATTR_FRAC` bits).
    pub fn pixels(&self) -> Vec<(i32, i32, i64)> {
        let mut out = Vec::new();
        for r in self.runs.borrow().iter() {
            for k in 0..r.len {
                let v = i64::from(r.start) + k as i64 * i64::from(r.step);
                out.push((r.x + k as i32, r.y, v));
            }
        }
        out
    }
}

impl Kernel for &Record {
    type Color = Gray8;
    type Vertex = i32;
    type Varyings = [i32; 1];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;

    fn vertex(&self, v: &VertexIn) -> i32 {
        v.normal[0]
    }

    fn triangle(&self, v: [&i32; 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 1]; 3]) {
        ((), [[*v[0]], [*v[1]], [*v[2]]])
    }

    fn span(&self, _: &(), s: &[i32; 1], d: &[i32; 1], x: i32, y: i32, out: &mut [Gray8]) {
        self.runs.borrow_mut().push(Run {
            x,
            y,
            len: out.len(),
            start: s[0],
            step: d[0],
        });
        for p in out {
            *p = Gray8::new(p.luma().saturating_add(1));
        }
    }
}

/// Triangles drawn through [`draw_triangle`] with one kernel, in one clip
/// space, in order, in every band.
pub struct Tris<K> {
    pub kernel: K,
    pub space: ClipSpace,
    pub cull: Cull,
    pub tris: Vec<[Corner; 3]>,
}

impl<K> Tris<K> {
    /// Screen-space triangles, no culling.
    pub fn screen(kernel: K, tris: Vec<[Corner; 3]>) -> Self {
        Tris {
            kernel,
            space: ClipSpace::SCREEN,
            cull: Cull::None,
            tris,
        }
    }
}

impl<K: Kernel> DrawBand<K::Color> for Tris<K> {
    fn draw_band(&mut self, band: &mut BandView<'_, K::Color>) {
        for t in &self.tris {
            draw_triangle(band, &self.space, &self.kernel, t, self.cull);
        }
    }
}

/// A whole frame: cleared to `clear` (depth to `u16::MAX` with `depth`),
/// then every item drawn.
pub fn full<C: PixelColor>(
    w: u32,
    h: u32,
    clear: C,
    depth: bool,
    items: &mut [&mut dyn DrawBand<C>],
) -> Vec<C> {
    let n = (w * h) as usize;
    let mut color = vec![clear; n];
    let mut z = vec![0u16; n];
    let mut frame = FullFrame::new(w, h, &mut color, depth.then_some(&mut z[..])).unwrap();
    frame.render(clear, items).unwrap();
    color
}

/// The same frame drawn in bands of `rows` rows through [`Bands`], as the
/// display receives it.
pub fn banded<C: PixelColor>(
    w: u32,
    h: u32,
    rows: u32,
    clear: C,
    depth: bool,
    items: &mut [&mut dyn DrawBand<C>],
) -> Vec<C> {
    let layout = Layout::banded(w, h, rows).unwrap();
    let n = (w * layout.band_rows()) as usize;
    let mut strip = vec![clear; n];
    let mut z = vec![0u16; n];
    let mut bands = Bands::new(layout, &mut strip, depth.then_some(&mut z[..])).unwrap();
    let mut sink = Collect::new(w, h, clear);
    bands.render(&mut sink, clear, items).unwrap();
    sink.px
}

/// A `DrawTarget` keeping a `w × h` frame in a `Vec`.
pub struct Collect<C> {
    pub w: u32,
    pub h: u32,
    pub px: Vec<C>,
}

impl<C: Copy> Collect<C> {
    pub fn new(w: u32, h: u32, clear: C) -> Self {
        Collect {
            w,
            h,
            px: vec![clear; (w * h) as usize],
        }
    }
}

impl<C> OriginDimensions for Collect<C> {
    fn size(&self) -> Size {
        Size::new(self.w, self.h)
    }
}

impl<C: PixelColor> DrawTarget for Collect<C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if (0..self.w as i32).contains(&p.x) && (0..self.h as i32).contains(&p.y) {
                self.px[(p.y as u32 * self.w + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        let (x0, y0) = (area.top_left.x, area.top_left.y);
        let w = area.size.width as i32;
        // the area's pixels only: `fill_solid` passes an endless iterator
        let n = area.size.width as usize * area.size.height as usize;
        for (i, c) in colors.into_iter().take(n).enumerate() {
            let (x, y) = (x0 + i as i32 % w.max(1), y0 + i as i32 / w.max(1));
            if (0..self.w as i32).contains(&x) && (0..self.h as i32).contains(&y) {
                self.px[(y as u32 * self.w + x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

/// Gray8 frame as write counts.
pub fn lumas(px: &[Gray8]) -> Vec<u8> {
    px.iter().map(|p| p.luma()).collect()
}

/// Counts of the screen-space triangles `tris` (no culling, no depth) in a
/// `w × h` frame.
pub fn counts(w: u32, h: u32, tris: &[[Corner; 3]]) -> Vec<u8> {
    let mut t = Tris::screen(Count, tris.to_vec());
    lumas(&full(w, h, Gray8::new(0), false, &mut [&mut t]))
}

/// Deterministic generator (xorshift64*).
pub struct Rng(pub u64);

impl Rng {
    /// The next value (an endless stream, not an `Iterator`).
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in `lo..=hi`.
    pub fn range(&mut self, lo: i32, hi: i32) -> i32 {
        (i64::from(lo) + (self.next() % (i64::from(hi) - i64::from(lo) + 1) as u64) as i64) as i32
    }
    /// Uniform in `[lo, hi)`.
    pub fn f(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The exact value, with `ATTR_FRAC` fraction bits, at the centre of pixel
/// `(x, y)` of the plane through the sub-pixel corners `xy` with values `a`.
pub fn exact_plane(xy: [(i32, i32); 3], a: [i32; 3], x: i32, y: i32) -> f64 {
    let s = f64::from(S);
    let (px, py) = ((f64::from(x) + 0.5) * s, (f64::from(y) + 0.5) * s);
    let f = |i: usize| (f64::from(xy[i].0), f64::from(xy[i].1), f64::from(a[i]));
    let ((x0, y0, a0), (x1, y1, a1), (x2, y2, a2)) = (f(0), f(1), f(2));
    let det = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
    let b1 = ((px - x0) * (y2 - y0) - (py - y0) * (x2 - x0)) / det;
    let b2 = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)) / det;
    (a0 + b1 * (a1 - a0) + b2 * (a2 - a0)) * f64::from(1u32 << fixshade::num::ATTR_FRAC)
}

/// The error bound of a screen-linear value of the triangle with sub-pixel
/// corners `xy` (inside the set-up window) and values `a` (within
/// ±`VARYING_LIMIT`), in units of 2^−`ATTR_FRAC`: `Setup::err` (crate
/// private) restated from the geometry.
///
/// `Setup::err`: every barycentric coefficient `C` (|C| < 2^14, one unit
/// worth `2^s` per pixel) is within 1.5 of its exact value, so the
/// per-pixel steps of a plane are off by at most `ε = ½ + 1.5·2^s·spread`
/// (`spread = |a₁ − a_top| + |a₂ − a_top|`, the values' differences from
/// the top vertex); values are reached from the reference pixel (the top
/// vertex's column, the first row) by at most `w` column and `h` row steps
/// (`w` = the bounding box's width in whole pixels + 2, `h` = its rows + 3),
/// and the reference value is off by less than 24: `|error| ≤ ε·(w + h) +
/// 24`, computed with `ε` rounded up to `⌈1.5·2^s·spread⌉ + 1`.
///
/// `2^s` from the geometry: set-up scales the coefficients so that the
/// largest `|C|` is at least 2^13 (its 14 bits are used), so with `g` the
/// largest exact per-pixel barycentric gradient, `g·2^14 ≥ (2^13 − 1.5)·2^s`,
/// i.e. `2^s ≤ 2g / (1 − 1.5·2^−13)`. Taking `g` over all three vertices
/// (set-up uses two of them) and the top vertex as the worst of the corners
/// sharing the smallest `y` only makes the bound larger; nothing else is
/// added.
pub fn plane_bound(xy: [(i32, i32); 3], a: [i32; 3]) -> f64 {
    let f = |i: usize| (f64::from(xy[i].0), f64::from(xy[i].1));
    let ((x0, y0), (x1, y1), (x2, y2)) = (f(0), f(1), f(2));
    let area = ((x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0)).abs();
    let s = f64::from(S);
    // per-pixel gradients of the three barycentric weights
    let g = [
        (y1 - y2).abs(),
        (x1 - x2).abs(),
        (y2 - y0).abs(),
        (x2 - x0).abs(),
        (y0 - y1).abs(),
        (x0 - x1).abs(),
    ]
    .iter()
    .fold(0.0f64, |m, &d| m.max(d * s / area));
    let two_s = 2.0 * g / (1.0 - 1.5 / 8192.0);
    let ymin = xy.iter().map(|p| p.1).min().unwrap();
    let spread = (0..3)
        .filter(|&t| xy[t].1 == ymin)
        .map(|t| {
            (0..3)
                .map(|i| (i64::from(a[i]) - i64::from(a[t])).abs())
                .sum::<i64>()
        })
        .max()
        .unwrap() as f64;
    let eps = (1.5 * two_s * spread).ceil() + 1.0;
    let xmin = xy.iter().map(|p| p.0).min().unwrap();
    let xmax = xy.iter().map(|p| p.0).max().unwrap();
    let ymax = xy.iter().map(|p| p.1).max().unwrap();
    let half = S / 2;
    let first = (ymin - half + S - 1) >> SUBPIXEL_BITS;
    let last = (ymax - half) >> SUBPIXEL_BITS;
    let w = f64::from(((xmax - xmin) >> SUBPIXEL_BITS) + 2);
    let h = f64::from((last - first).max(0) + 3);
    eps * (w + h) + 24.0
}

/// A mesh drawn triangle by triangle through the per-triangle front, with
/// the corners of its transform: `t.clip(p)`, `VertexIn::new(t.normal(n),
/// t.eye(p))` (what `MeshDraw` must equal bit for bit).
pub struct Front<'a, K, P: Projection> {
    pub mesh: Mesh<'a>,
    pub t: MeshTransform<P>,
    pub kernel: K,
    pub cull: Cull,
}

impl<K: Kernel, P: Projection> DrawBand<K::Color> for Front<'_, K, P> {
    fn draw_band(&mut self, band: &mut BandView<'_, K::Color>) {
        let (pos, nrm) = (self.mesh.positions(), self.mesh.normals());
        let space = self.t.clip_space();
        for tri in self.mesh.triangles() {
            let c = tri.map(|i| {
                let (p, n) = (pos[usize::from(i)], nrm[usize::from(i)]);
                Corner {
                    clip: self.t.clip(p),
                    vertex: VertexIn::new(self.t.normal(n), self.t.eye(p)),
                }
            });
            draw_triangle(band, &space, &self.kernel, &c, self.cull);
        }
    }
}

/// A `w × h` frame of `mesh` seen through `t`, drawn with `kernel`, back
/// faces culled per `cull`, with a depth buffer, in bands of `rows` rows
/// (`rows ≥ h`: one `FullFrame`), by `MeshDraw` (`front` false) or by the
/// per-triangle front ([`Front`]).
#[allow(clippy::too_many_arguments)]
pub fn mesh_frame<K: Kernel + Copy, P: Projection>(
    w: u32,
    h: u32,
    rows: u32,
    mesh: Mesh<'_>,
    t: &MeshTransform<P>,
    kernel: K,
    cull: Cull,
    front: bool,
    clear: K::Color,
) -> Vec<K::Color>
where
    K::Color: PixelColor,
{
    let draw = |item: &mut dyn DrawBand<K::Color>| {
        if rows >= h {
            full(w, h, clear, true, &mut [item])
        } else {
            banded(w, h, rows, clear, true, &mut [item])
        }
    };
    if front {
        let mut item = Front {
            mesh,
            t: *t,
            kernel,
            cull,
        };
        return draw(&mut item);
    }
    let layout = Layout::banded(w, h, rows).unwrap();
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); mesh.vertex_count()];
    let mut bins = vec![0u16; bins_len(mesh.triangle_count(), layout.bands() as usize)];
    let mut carry = vec![Carry::default(); 2 * mesh.triangle_count()];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut carry,
    };
    let mut item = MeshDraw::new(
        layout,
        mesh,
        t,
        kernel,
        memory,
        DrawOptions {
            cull,
            ..DrawOptions::default()
        },
    )
    .unwrap();
    draw(&mut item)
}
