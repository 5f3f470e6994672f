//! Shared input decoding and checks of the fuzz targets (issues 11 and 21),
//! and the bodies of the targets `mesh` and `surface` ([`mesh::run`],
//! [`surface::run`]), through which fixshade's tests replay the kept inputs
//! exactly (`fuzz_regressions`: a dev-dependency on this library, without
//! libFuzzer). The one function that builds a frame of the mesh
//! renderer is `draw` (below; [`frames`] draws it whole and in bands): adapt it
//! when that API changes.
//!
//! Every target reads its parameters from the fuzzer's bytes with [`Input`]:
//! `f32`s are drawn so that the special values (±0, ±∞, NaN, ±MAX, subnormals,
//! the ±32 768 geometry edge, huge and tiny) are likely, and exhausted input
//! reads as zeros. Each target asserts its own properties; a panic (overflow
//! checks are on in the fuzz profile) is a crash the fuzzer reports.

#![allow(dead_code)]

pub mod mesh;
pub mod surface;

use fixshade::color::Rgb;
use fixshade::lighting::{AnyLight, LightDesc, LightKind, MaterialDesc};
use fixshade::num::Scalar;

/// The fuzzer's bytes as a stream of parameters.
pub struct Input<'a>(pub &'a [u8]);

impl Input<'_> {
    /// One byte (0 when exhausted).
    pub fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    /// Four bytes, little-endian.
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }

    /// Any `i32`, small ones and the edges likely.
    pub fn i32(&mut self) -> i32 {
        match self.u8() % 8 {
            0 => i32::MIN,
            1 => i32::MAX,
            2 | 3 => i32::from(self.u8() as i8),
            4 | 5 => i32::from(self.u32() as u16 as i16),
            _ => self.u32() as i32,
        }
    }

    /// Any `f32`, with the special values likely.
    pub fn f32(&mut self) -> f32 {
        let tag = self.u8();
        match tag % 16 {
            0 => f32::NAN,
            1 => f32::INFINITY,
            2 => f32::NEG_INFINITY,
            3 => f32::MAX,
            4 => -f32::MAX,
            5 => 0.0,
            6 => -0.0,
            7 => f32::MIN_POSITIVE / 4.0,
            8 => 32_768.0,
            9 => -32_768.0,
            10 => f32::from_bits(self.u32()),
            // small values: −4..4 in 1/64 steps, the common case
            _ => f32::from(self.u32() as u16 as i16) / 8192.0,
        }
    }

    /// Three `f32`s.
    pub fn f3(&mut self) -> [f32; 3] {
        [self.f32(), self.f32(), self.f32()]
    }

    /// A light description of any kind.
    pub fn light(&mut self) -> LightDesc {
        let kind = match self.u8() % 3 {
            0 => LightKind::Directional {
                towards_light: self.f3(),
            },
            1 => LightKind::Point {
                position: self.f3(),
                attenuation: self.f3(),
            },
            _ => LightKind::Spot {
                position: self.f3(),
                axis: self.f3(),
                exponent: self.f32(),
                cutoff_deg: self.f32(),
                attenuation: self.f3(),
            },
        };
        LightDesc {
            kind,
            ambient: self.f3(),
            diffuse: self.f3(),
            specular: self.f3(),
        }
    }

    /// A material description with any values.
    // the update keeps this compiling when the description gains a field
    #[allow(clippy::needless_update)]
    pub fn material(&mut self) -> MaterialDesc {
        MaterialDesc {
            emission: self.f3(),
            ambient: self.f3(),
            diffuse: self.f3(),
            specular: self.f3(),
            shininess: self.f32(),
            brilliance: self.u8(),
            fresnel_f0: self.f32(),
            transmission: self.f3(),
            transmission_exponent: self.f32(),
            refractive_index: self.f32(),
        }
    }

    /// Up to two lights the constructor accepts, for tier `S`.
    pub fn lights<S: Scalar>(&mut self) -> heapless::Vec<AnyLight<S>, 2> {
        let mut out = heapless::Vec::new();
        for _ in 0..1 + self.u8() % 2 {
            if let Ok(l) = AnyLight::<S>::new(&self.light()) {
                let _ = out.push(l);
            }
        }
        out
    }
}

/// A lit colour: every channel finite and within the 8-bit range once quantised.
pub fn check_color<S: Scalar>(c: Rgb<S>, what: &str) {
    for x in c.to_f32() {
        assert!(
            x.is_finite(),
            "{}: non-finite channel {c:?} ({what})",
            S::NAME
        );
    }
    for u in c.to_unorm(8) {
        assert!(u <= 255, "{}: channel {u} > 255 ({what})", S::NAME);
    }
}

impl Input<'_> {
    /// Any `i16`, small values and the edges likely.
    pub fn i16(&mut self) -> i16 {
        match self.u8() % 8 {
            0 => i16::MIN,
            1 => i16::MAX,
            2..=4 => i16::from(self.u8() as i8),
            _ => u16::from_le_bytes([self.u8(), self.u8()]) as i16,
        }
    }

    /// One bit.
    pub fn flag(&mut self) -> bool {
        self.u8() & 1 == 1
    }
}

// ---- the mesh renderer ------------------------------------------------------------

use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::prelude::{DrawTarget, OriginDimensions, Pixel, RgbColor, Size};
use fixshade::camera::{MeshTransform, Projection};
use fixshade::framebuffer::{Bands, DrawBand, FullFrame, Layout};
use fixshade::mesh::Mesh;
use fixshade::raster::Cull;
use fixshade::render::refine::{Refine, RefineMemory, RefineStats};
use fixshade::render::{bins_len, CachedVertex, Carry, DrawOptions, MeshDraw, MeshMemory};
use fixshade::shade::Kernel;

/// How a frame is drawn: size, band height, depth buffer, culling and
/// silhouette refinement (`(new vertices, threshold)`).
#[derive(Clone, Copy, Debug)]
pub struct FrameSpec {
    pub width: u32,
    pub height: u32,
    pub band_rows: u32,
    pub depth: bool,
    pub cull: Cull,
    pub refine: Option<(usize, u16)>,
}

/// What [`frames`] drew: the whole frame, the same frame in bands (as sent to
/// a display), and the refinement's statistics (`None`: the renderer refused
/// the set-up with a typed error).
pub struct Frames {
    pub full: Vec<Rgb565>,
    pub banded: Vec<Rgb565>,
    pub stats: RefineStats,
}

/// A display receiving the bands through `fill_contiguous`.
struct Sink(Vec<Rgb565>, Size);
impl OriginDimensions for Sink {
    fn size(&self) -> Size {
        self.1
    }
}
impl DrawTarget for Sink {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Self::Error> {
        // not used by the band renderer (kept correct anyway)
        for Pixel(p, c) in it {
            let (w, h) = (self.1.width as i32, self.1.height as i32);
            if p.x >= 0 && p.y >= 0 && p.x < w && p.y < h {
                self.0[(p.y * w + p.x) as usize] = c;
            }
        }
        Ok(())
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &embedded_graphics_core::primitives::Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        let w = self.1.width as usize;
        let y0 = area.top_left.y.max(0) as usize;
        for (i, c) in colors.into_iter().enumerate() {
            if let Some(p) = self.0.get_mut(y0 * w + i) {
                *p = c;
            }
        }
        Ok(())
    }
}

/// One `MeshDraw` of `mesh` through `t` with `kernel` into `layout` (owned
/// memory), or `None` for a typed error. The one place that builds a draw: the
/// mesh renderer's API is all here.
fn draw<'a, K: Kernel<Color = Rgb565> + Copy, P: Projection>(
    layout: Layout,
    mesh: Mesh<'a>,
    t: &MeshTransform<P>,
    kernel: K,
    spec: &FrameSpec,
    mem: &'a mut Memory<K::Vertex>,
) -> Option<MeshDraw<'a, K, P>> {
    let opts = DrawOptions {
        cull: spec.cull,
        ..DrawOptions::default()
    };
    let memory = MeshMemory {
        vertices: &mut mem.cache,
        bins: &mut mem.bins,
        carry: &mut mem.carry,
    };
    match spec.refine {
        None => MeshDraw::new(layout, mesh, t, kernel, memory, opts).ok(),
        Some((_, tau)) => {
            let r = &mut mem.refine;
            let refine = Refine {
                memory: RefineMemory {
                    vertex_words: &mut r.words,
                    edges: &mut r.edges,
                    positions: &mut r.pos,
                    normals: &mut r.nrm,
                    texcoords: &mut r.uv,
                    tangents: &mut r.tg,
                    vertices: &mut r.cache,
                    triangles: &mut r.tris,
                },
                threshold: tau,
            };
            MeshDraw::new(layout, mesh, t, kernel, memory, opts.with_refine(refine)).ok()
        }
    }
}

/// The caller-owned memory of one draw.
struct Memory<V> {
    cache: Vec<CachedVertex<V>>,
    bins: Vec<u16>,
    carry: Vec<Carry>,
    refine: RefineMem<V>,
}

struct RefineMem<V> {
    words: Vec<u16>,
    edges: Vec<[u16; 3]>,
    pos: Vec<[i16; 3]>,
    nrm: Vec<[i16; 3]>,
    uv: Vec<[i16; 2]>,
    tg: Vec<[i16; 4]>,
    cache: Vec<CachedVertex<V>>,
    tris: Vec<[u16; 4]>,
}

impl<V: Copy + Default> Memory<V> {
    fn new(mesh: &Mesh<'_>, bands: u32, e: usize) -> Self {
        let (nv, nt) = (mesh.vertex_count(), mesh.triangle_count() + 4 * e);
        Memory {
            cache: vec![CachedVertex::default(); nv],
            bins: vec![0; bins_len(nt, bands as usize)],
            carry: vec![Carry::default(); 2 * nt + 2],
            refine: RefineMem {
                words: vec![0; nv],
                edges: vec![[0; 3]; e],
                pos: vec![[0; 3]; e],
                nrm: vec![[0; 3]; e],
                uv: vec![[0; 2]; e],
                tg: vec![[0; 4]; e],
                cache: vec![CachedVertex::default(); e],
                tris: vec![[0; 4]; 4 * e],
            },
        }
    }
}

/// Draws `mesh` through `t` with `kernel` as a whole frame and in bands
/// (`spec`): no panic (overflow checks on), and the caller compares the two.
/// `None` when the renderer refuses the set-up with a typed error (the same
/// for both).
pub fn frames<K: Kernel<Color = Rgb565> + Copy, P: Projection>(
    mesh: Mesh<'_>,
    t: &MeshTransform<P>,
    kernel: K,
    spec: &FrameSpec,
) -> Option<Frames> {
    let (w, h) = (spec.width, spec.height);
    let e = spec.refine.map_or(0, |r| r.0);
    let full_layout = Layout::full(w, h).ok()?;
    let band_layout = Layout::banded(w, h, spec.band_rows).ok()?;
    let n = (w * h) as usize;
    let bg = Rgb565::new(31, 0, 31);
    // the whole frame
    let mut mem = Memory::<K::Vertex>::new(&mesh, 1, e);
    let full_draw = draw(full_layout, mesh, t, kernel, spec, &mut mem);
    let mut mem_b = Memory::<K::Vertex>::new(&mesh, band_layout.bands(), e);
    let band_draw = draw(band_layout, mesh, t, kernel, spec, &mut mem_b);
    let (mut full_draw, mut band_draw) = match (full_draw, band_draw) {
        (Some(a), Some(b)) => (a, b),
        (None, None) => return None,
        _ => panic!("whole frame and bands disagree about the set-up"),
    };
    let stats = full_draw.refine_stats();
    assert_eq!(
        stats,
        band_draw.refine_stats(),
        "refinement differs in bands"
    );
    let mut full = vec![bg; n];
    let mut zfull = vec![0u16; n];
    {
        let mut frame =
            FullFrame::new(w, h, &mut full, spec.depth.then_some(&mut zfull[..])).ok()?;
        frame.render(bg, &mut [&mut full_draw]).ok()?;
    }
    let rows = (w * spec.band_rows.min(h)) as usize;
    let mut strip = vec![bg; rows];
    let mut zstrip = vec![0u16; rows];
    let mut sink = Sink(vec![Rgb565::BLACK; n], Size::new(w, h));
    {
        let mut bands = Bands::new(
            band_layout,
            &mut strip,
            spec.depth.then_some(&mut zstrip[..]),
        )
        .ok()?;
        let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut band_draw];
        let _ = bands.render(&mut sink, bg, items);
    }
    Some(Frames {
        full,
        banded: sink.0,
        stats,
    })
}
