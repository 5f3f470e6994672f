//! Rasterizing and shading arbitrary triangles through the per-triangle front
//! of the pipeline (`render::draw_triangle`) into a small frame, whole
//! (`FullFrame`) and in bands (`Bands`): wild clip coordinates (screen space
//! or any perspective clip space), depths, values, Q14 normals and Q16.16
//! eye positions of any size, every tier and shading mode, any culling, with
//! or without a depth buffer. No panic, no wrap (overflow checks on), no run
//! outside the frame, the band or (when every corner is in front of the near
//! plane) the triangle's bounding box, values inside the range the kernel
//! declares safe (`Kernel::safe`), no pixel drawn twice by one triangle, and
//! the bands give the whole frame.
#![no_main]

use core::cell::{Cell, RefCell};
use core::convert::Infallible;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::camera::{Clip, ClipSpace};
use fixshade::color::Linear;
use fixshade::framebuffer::{BandView, Bands, DrawBand, FullFrame, Layout};
use fixshade::lighting::{AnyLight, BlinnPhong, Lighting, LinearFog, LocalViewer, Material};
use fixshade::num::ATTR_FRAC;
use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade::raster::interp::VARYING_LIMIT;
use fixshade::raster::Cull;
use fixshade::render::{draw_triangle, Corner};
use fixshade::shade::{FlatShading, GouraudShading, Kernel, PhongShading, Shader, VertexIn};
use fixshade_fuzz::Input;
use libfuzzer_sys::fuzz_target;

const MAX_W: u32 = 48;
const MAX_H: u32 = 40;

/// The frame: size, rows per band, depth buffer.
#[derive(Clone, Copy, Debug)]
struct Frame {
    width: u32,
    height: u32,
    band_rows: u32,
    depth: bool,
}

fn frame(inp: &mut Input) -> Frame {
    Frame {
        width: 1 + u32::from(inp.u8()) % MAX_W,
        height: 1 + u32::from(inp.u8()) % MAX_H,
        band_rows: 1 + u32::from(inp.u8()) % 9,
        depth: inp.u8() & 1 == 1,
    }
}

/// Where the kernel may be called: the frame, the band's rows, the
/// triangle's sub-pixel bounding box (with a sub-pixel of slack for the
/// rounding of clipped corners); which pixels it wrote.
struct Bounds {
    width: u32,
    rows: Cell<(i32, i32)>,
    bbox: Option<[i64; 4]>,
    hits: RefCell<Vec<u8>>,
}

impl Bounds {
    fn new(f: &Frame, space: &ClipSpace, c: &[Corner; 3]) -> Bounds {
        let p = c.map(|c| space.project(c.clip));
        let bbox = match p {
            [Some(a), Some(b), Some(c)] => {
                let xs = [a.x, b.x, c.x].map(i64::from);
                let ys = [a.y, b.y, c.y].map(i64::from);
                Some([
                    xs.iter().min().unwrap() - 1,
                    xs.iter().max().unwrap() + 1,
                    ys.iter().min().unwrap() - 1,
                    ys.iter().max().unwrap() + 1,
                ])
            }
            _ => None,
        };
        Bounds {
            width: f.width,
            rows: Cell::new((0, 0)),
            bbox,
            hits: RefCell::new(vec![0; (f.width * f.height) as usize]),
        }
    }

    fn check(&self, x: i32, y: i32, len: usize) {
        assert!(len > 0, "empty run");
        let rows = self.rows.get();
        assert!((rows.0..rows.1).contains(&y), "row {y} outside {rows:?}");
        assert!(
            x >= 0 && x as u32 + len as u32 <= self.width,
            "run {x}+{len} beyond width {}",
            self.width
        );
        if let Some([x0, x1, y0, y1]) = self.bbox {
            let c = |p: i64| (p << SUBPIXEL_BITS) + (1 << (SUBPIXEL_BITS - 1));
            let (first, last) = (c(i64::from(x)), c(i64::from(x) + len as i64 - 1));
            assert!(
                first >= x0 && last <= x1 && c(i64::from(y)) >= y0 && c(i64::from(y)) <= y1,
                "run ({x}..{}, {y}) outside the bounding box {:?}",
                x + len as i32,
                self.bbox
            );
        }
        let mut hits = self.hits.borrow_mut();
        for k in 0..len {
            let i = y as usize * self.width as usize + x as usize + k;
            hits[i] += 1;
            assert!(
                hits[i] <= 1,
                "pixel ({}, {y}) drawn twice by one triangle",
                x as usize + k
            );
        }
    }
}

/// A kernel with its runs checked against [`Bounds`].
struct Watch<'a, K> {
    inner: K,
    bounds: &'a Bounds,
}

impl<K: Kernel> Kernel for Watch<'_, K> {
    type Color = K::Color;
    type Vertex = K::Vertex;
    type Varyings = K::Varyings;
    type Triangle = K::Triangle;
    const USED: usize = K::USED;
    const NEEDS_POSITION: bool = K::NEEDS_POSITION;
    const NEEDS_TEXCOORD: bool = K::NEEDS_TEXCOORD;
    const NEEDS_TANGENT: bool = K::NEEDS_TANGENT;

    fn vertex(&self, v: &VertexIn) -> K::Vertex {
        self.inner.vertex(v)
    }

    fn triangle(&self, v: [&K::Vertex; 3], eye: &[[i32; 3]; 3]) -> (K::Triangle, [K::Varyings; 3]) {
        self.inner.triangle(v, eye)
    }

    fn safe(&self, i: usize) -> (i32, i32) {
        self.inner.safe(i)
    }

    fn span(
        &self,
        t: &K::Triangle,
        start: &K::Varyings,
        step: &K::Varyings,
        x: i32,
        y: i32,
        out: &mut [K::Color],
    ) {
        self.bounds.check(x, y, out.len());
        self.inner.span(t, start, step, x, y, out)
    }
}

/// Two raw values per corner; checks that every value handed to `span` stays
/// in the corners' range, which it declares as its safe range.
struct Values {
    lo: [i64; 2],
    hi: [i64; 2],
}

impl Kernel for Values {
    type Color = Rgb565;
    type Vertex = [i32; 2];
    type Varyings = [i32; 2];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;

    fn vertex(&self, v: &VertexIn) -> [i32; 2] {
        [v.normal[0], v.normal[1]]
    }

    fn triangle(&self, v: [&[i32; 2]; 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 2]; 3]) {
        ((), [*v[0], *v[1], *v[2]])
    }

    fn safe(&self, i: usize) -> (i32, i32) {
        (self.lo[i] as i32, self.hi[i] as i32)
    }

    fn span(&self, _: &(), start: &[i32; 2], step: &[i32; 2], _: i32, _: i32, out: &mut [Rgb565]) {
        for i in 0..2 {
            for k in 0..out.len() as i64 {
                let v = i64::from(start[i]) + k * i64::from(step[i]);
                assert!(
                    v >= self.lo[i] && v <= self.hi[i],
                    "value {i} = {v} at pixel {k} outside {}..={}",
                    self.lo[i],
                    self.hi[i]
                );
            }
        }
        out.fill(Rgb565::WHITE);
    }
}

/// One triangle drawn in every band, the bounds told each band's rows.
struct One<'a, K> {
    kernel: Watch<'a, K>,
    space: ClipSpace,
    tri: [Corner; 3],
    cull: Cull,
}

impl<K: Kernel<Color = Rgb565>> DrawBand<Rgb565> for One<'_, K> {
    fn draw_band(&mut self, band: &mut BandView<'_, Rgb565>) {
        let r = band.rows();
        self.kernel.bounds.rows.set((r.start, r.end));
        self.kernel.bounds.hits.borrow_mut().fill(0);
        draw_triangle(band, &self.space, &self.kernel, &self.tri, self.cull);
    }
}

/// A display keeping the frame.
struct Sink(u32, Vec<Rgb565>);

impl OriginDimensions for Sink {
    fn size(&self) -> Size {
        Size::new(self.0, self.1.len() as u32 / self.0)
    }
}

impl DrawTarget for Sink {
    type Color = Rgb565;
    type Error = Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), Infallible> {
        unreachable!("bands are sent whole")
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        let at = (area.top_left.y as u32 * self.0) as usize;
        for (p, c) in self.1[at..].iter_mut().zip(colors) {
            *p = c;
        }
        Ok(())
    }
}

/// Draws `tri` with `kernel` whole and in bands; the frames must agree.
fn draw<K: Kernel<Color = Rgb565>>(
    f: &Frame,
    space: ClipSpace,
    tri: [Corner; 3],
    cull: Cull,
    kernel: K,
) {
    let bounds = Bounds::new(f, &space, &tri);
    let mut one = One {
        kernel: Watch {
            inner: kernel,
            bounds: &bounds,
        },
        space,
        tri,
        cull,
    };
    let n = (f.width * f.height) as usize;
    let mut whole = vec![Rgb565::BLACK; n];
    let mut z = vec![0u16; n];
    FullFrame::new(f.width, f.height, &mut whole, f.depth.then_some(&mut z[..]))
        .unwrap()
        .render(Rgb565::BLACK, &mut [&mut one])
        .unwrap();
    let layout = Layout::banded(f.width, f.height, f.band_rows).unwrap();
    let m = (f.width * layout.band_rows()) as usize;
    let (mut strip, mut zs) = (vec![Rgb565::BLACK; m], vec![0u16; m]);
    let mut sink = Sink(f.width, vec![Rgb565::BLACK; n]);
    Bands::new(layout, &mut strip, f.depth.then_some(&mut zs[..]))
        .unwrap()
        .render(&mut sink, Rgb565::BLACK, &mut [&mut one])
        .unwrap();
    assert!(sink.1 == whole, "the bands differ from the whole frame");
}

fn coord(inp: &mut Input) -> i32 {
    // mostly near the frame (sub-pixels), sometimes anywhere
    match inp.u8() % 4 {
        0 => inp.i32(),
        _ => i32::from(inp.u32() as u16 as i16) / 32,
    }
}

/// Screen space, or a perspective clip space with its centre near the frame
/// or anywhere and any near plane.
fn space(inp: &mut Input) -> ClipSpace {
    match inp.u8() % 3 {
        0 => ClipSpace::SCREEN,
        1 => ClipSpace::perspective([coord(inp), coord(inp)], inp.i32()),
        _ => ClipSpace::perspective(
            [i32::from(inp.u8()) << 2, i32::from(inp.u8()) << 2],
            1 + i32::from(inp.u8()),
        ),
    }
}

fn clip(inp: &mut Input) -> Clip {
    let w = match inp.u8() % 4 {
        0 => inp.i32(),
        1 => 1,
        _ => 1 + i32::from(inp.u8()),
    };
    Clip {
        x: coord(inp),
        y: coord(inp),
        z: inp.i32(),
        w,
    }
}

fn cull(inp: &mut Input) -> Cull {
    [Cull::None, Cull::Back, Cull::Front][usize::from(inp.u8() % 3)]
}

fn raw(inp: &mut Input) {
    let f = frame(inp);
    let space = space(inp);
    let tri: [Corner; 3] = core::array::from_fn(|_| Corner {
        clip: clip(inp),
        vertex: VertexIn::new([inp.i32(), inp.i32(), 0], [0; 3]),
    });
    let lim = i64::from(VARYING_LIMIT);
    let a = |i: usize| tri.map(|c| i64::from(c.vertex.normal[i]).clamp(-lim, lim) << ATTR_FRAC);
    let lo = [0, 1].map(|i| *a(i).iter().min().unwrap());
    let hi = [0, 1].map(|i| *a(i).iter().max().unwrap());
    let cull = cull(inp);
    draw(&f, space, tri, cull, Values { lo, hi });
}

fn shaded<S: Scalar>(inp: &mut Input) {
    let f = frame(inp);
    let light = inp.light();
    let lights = heapless::Vec::<_, 1>::from_iter(AnyLight::<S>::new(&light));
    let Ok(m) = Material::<S>::new(&inp.material()) else {
        return;
    };
    let mut lit = Lighting::<S, _, BlinnPhong>::new(lights, m);
    if let Ok(v) = LocalViewer::<S>::new(inp.f3()) {
        if let Ok(fog) = LinearFog::<S>::new(inp.f32(), inp.f32(), inp.f3()) {
            return draw_modes(inp, &f, &lit.with_viewer(v).with_fog(fog).eye_space());
        }
        return draw_modes(inp, &f, &lit.with_viewer(v).eye_space());
    }
    lit = lit.with_global_ambient_f32(inp.f3());
    draw_modes(inp, &f, &lit.eye_space());
}

fn draw_modes<S: Scalar, I: fixshade::lighting::Illuminate<Scalar = S>>(
    inp: &mut Input,
    f: &Frame,
    lit: &I,
) {
    let space = space(inp);
    // any Q14 normals and Q16.16 eye positions
    let tri: [Corner; 3] = core::array::from_fn(|_| Corner {
        clip: clip(inp),
        vertex: VertexIn::new(
            [inp.i32(), inp.i32(), inp.i32()],
            [inp.i32(), inp.i32(), inp.i32()],
        ),
    });
    let cull = cull(inp);
    draw(f, space, tri, cull, Shader::new(FlatShading, lit, Linear));
    draw(
        f,
        space,
        tri,
        cull,
        Shader::new(GouraudShading, lit, Linear),
    );
    draw(f, space, tri, cull, Shader::new(PhongShading, lit, Linear));
}

fuzz_target!(|data: &[u8]| {
    let mut inp = Input(data);
    match inp.u8() % 7 {
        0 | 1 => raw(&mut inp),
        2 => shaded::<Q14<1>>(&mut inp),
        3 => shaded::<Q14<2>>(&mut inp),
        4 => shaded::<Q30<3>>(&mut inp),
        5 => shaded::<f32>(&mut inp),
        _ => shaded::<F32Fast<2>>(&mut inp),
    }
});
