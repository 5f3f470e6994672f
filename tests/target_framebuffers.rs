//! Framebuffers: construction errors, DrawTarget adapter, band buffer with depth.

use core::convert::Infallible;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::{Gray8, GrayColor, Rgb565, RgbColor};
use embedded_graphics_core::Pixel;
use embedded_graphics_simulator::SimulatorDisplay;
use fixshade::raster::{draw_triangle, RasterOptions, RasterVertex, SpanShader, SUBPIXEL_BITS};
use fixshade::target::{
    BandBuffer, DepthBuffer, DrawTargetAdapter, Framebuffer, SliceFramebuffer, TargetError,
};

struct Solid<C>(C);
impl<C: Copy> SpanShader<0> for Solid<C> {
    type Color = C;
    fn shade_span(&mut self, _: i32, _: i32, _: &[i32; 0], _: &[i32; 0], out: &mut [C]) {
        out.fill(self.0);
    }
}

fn tri(p: [(i32, i32, u16); 3]) -> [RasterVertex<0>; 3] {
    p.map(|(x, y, z)| RasterVertex {
        x: x << SUBPIXEL_BITS,
        y: y << SUBPIXEL_BITS,
        z,
        inv_w: 1,
        attrs: [],
    })
}

#[test]
fn slice_framebuffer_validates_its_slice() {
    let mut buf = [Gray8::new(0); 100];
    assert_eq!(
        SliceFramebuffer::new(&mut buf, 0, 5).unwrap_err(),
        TargetError::ZeroSize
    );
    assert_eq!(
        SliceFramebuffer::with_stride(&mut buf, 10, 5, 9).unwrap_err(),
        TargetError::StrideTooSmall
    );
    let err = SliceFramebuffer::new(&mut buf, 10, 11).unwrap_err();
    assert_eq!(
        err,
        TargetError::BufferTooSmall {
            needed: 110,
            got: 100
        }
    );
    assert_eq!(
        err.to_string(),
        "framebuffer slice too small: needs 110 elements, got 100"
    );
    // Stride 12, 8 rows: 12·7 + 10 = 94 elements suffice.
    let mut fb = SliceFramebuffer::with_stride(&mut buf, 10, 8, 12).unwrap();
    fb.clear(Gray8::new(9));
    fb.fill_span(8, 7, 2, |_, p| p.fill(Gray8::new(1))).unwrap();
    fb.fill_span(9, 7, 2, |_, _| panic!("out of range span must be ignored"))
        .unwrap();
    fb.fill_span(0, -1, 1, |_, _| panic!("out of range span must be ignored"))
        .unwrap();
    assert_eq!(fb.get(9, 7), Some(Gray8::new(1)));
    assert_eq!(fb.as_slice()[10], Gray8::new(0), "padding untouched");
}

#[test]
fn adapter_draws_on_the_simulator_like_the_slice_framebuffer() {
    let t = tri([(3, 2, 0), (150, 40, 0), (20, 90, 0)]);
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(160, 100));
    let mut fb = DrawTargetAdapter::new(&mut display);
    assert_eq!((fb.width(), fb.rows()), (160, 0..100));
    let stats = draw_triangle(
        &mut fb,
        None,
        &t,
        &RasterOptions::default(),
        &mut Solid(Rgb565::GREEN),
    )
    .unwrap();

    let mut px = vec![Rgb565::BLACK; 160 * 100];
    let mut slice = SliceFramebuffer::new(&mut px, 160, 100).unwrap();
    let stats2 = draw_triangle(
        &mut slice,
        None,
        &t,
        &RasterOptions::default(),
        &mut Solid(Rgb565::GREEN),
    )
    .unwrap();
    assert_eq!(stats.pixels, stats2.pixels);
    for y in 0..100 {
        for x in 0..160 {
            assert_eq!(
                display.get_pixel(Point::new(x, y)),
                px[(y * 160 + x) as usize],
                "({x}, {y})"
            );
        }
    }
}

/// A display that fails every other call.
struct Flaky(u32);
impl OriginDimensions for Flaky {
    fn size(&self) -> Size {
        Size::new(200, 10)
    }
}
impl DrawTarget for Flaky {
    type Color = Gray8;
    type Error = u32;
    fn draw_iter<I: IntoIterator<Item = Pixel<Gray8>>>(&mut self, _: I) -> Result<(), u32> {
        self.0 += 1;
        if self.0 % 2 == 0 {
            Err(self.0)
        } else {
            Ok(())
        }
    }
}

#[test]
fn adapter_returns_the_display_error() {
    let mut display = Flaky(0);
    let mut fb = DrawTargetAdapter::new(&mut display);
    // 200 pixels = 4 chunks of at most 64: call 1 succeeds, call 2 fails and
    // stops the span
    let mut pieces = Vec::new();
    let r = fb.fill_span(0, 3, 200, |x, p| {
        pieces.push((x, p.len()));
        p.fill(Gray8::new(1));
    });
    assert_eq!(r, Err(2));
    assert_eq!(pieces, [(0, 64), (64, 64)]);
    // a triangle drawn through the adapter reports the error too
    let t = tri([(0, 0, 0), (150, 2, 0), (10, 9, 0)]);
    let r = draw_triangle(
        &mut fb,
        None,
        &t,
        &RasterOptions::default(),
        &mut Solid(Gray8::new(3)),
    );
    assert_eq!(r.map(|_| ()), Err(4));
}

#[test]
fn band_rendering_with_depth_matches_full_frame() {
    let far = tri([(2, 2, 3000), (60, 10, 3000), (10, 60, 3000)]);
    let near = tri([(5, 30, 100), (60, 20, 5000), (40, 62, 100)]);
    let scene = [(far, Gray8::new(50)), (near, Gray8::new(200))];

    let mut full = vec![Gray8::new(0); 64 * 64];
    let mut fb = SliceFramebuffer::new(&mut full, 64, 64).unwrap();
    let mut z = vec![u16::MAX; 64 * 64];
    let mut depth = DepthBuffer::new(&mut z, 64).unwrap();
    for (t, c) in &scene {
        draw_triangle(
            &mut fb,
            Some(&mut depth),
            t,
            &RasterOptions::default(),
            &mut Solid(*c),
        )
        .unwrap();
    }

    for rows in [1u32, 3, 8, 64] {
        let mut strip = vec![Gray8::new(0); (64 * rows) as usize];
        let mut band = BandBuffer::new(&mut strip, 64, 64).unwrap();
        let mut zb = vec![0u16; (64 * rows) as usize];
        let mut depth = DepthBuffer::new(&mut zb, 64).unwrap();
        let mut display = SimulatorDisplay::<Gray8>::new(Size::new(64, 64));
        let result: Result<(), Infallible> = band.render_with_depth(
            &mut display,
            Gray8::new(0),
            &mut depth,
            u16::MAX,
            |fb, depth| {
                for (t, c) in &scene {
                    draw_triangle(
                        fb,
                        Some(&mut *depth),
                        t,
                        &RasterOptions::default(),
                        &mut Solid(*c),
                    )
                    .unwrap();
                }
            },
        );
        result.unwrap();
        for y in 0..64 {
            for x in 0..64 {
                assert_eq!(
                    display.get_pixel(Point::new(x, y)),
                    full[(y * 64 + x) as usize],
                    "band rows {rows} ({x}, {y})"
                );
            }
        }
    }
    assert!(full.iter().any(|p| p.luma() == 50) && full.iter().any(|p| p.luma() == 200));
}

#[test]
fn band_buffer_geometry() {
    let mut strip = [Rgb565::BLACK; 240 * 8];
    let mut band = BandBuffer::new(&mut strip, 240, 250).unwrap();
    assert_eq!((band.band_rows(), band.bands()), (8, 32));
    assert!(band.set_band(31));
    assert_eq!(band.rows(), 248..250);
    assert!(!band.set_band(32));
    assert_eq!(band.band(), 31);
    let mut tiny = [Rgb565::BLACK; 10];
    assert!(matches!(
        BandBuffer::new(&mut tiny, 240, 10),
        Err(TargetError::BufferTooSmall { .. })
    ));
}
