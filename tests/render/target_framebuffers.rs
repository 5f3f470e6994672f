//! Framebuffers: construction errors of `FullFrame`, `Bands` and `Layout`,
//! bands flushed to a display equal the whole frame (with depth), display
//! errors, band geometry, and a mesh refused by a frame of another layout.

use fixshade_testkit::support;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::{Gray8, GrayColor, Rgb565, RgbColor};
use embedded_graphics_core::Pixel;
use embedded_graphics_simulator::SimulatorDisplay;
use fixshade::error::{Error, RenderError};
use fixshade::framebuffer::{Bands, DrawBand, FullFrame, Layout};
use fixshade::prelude::*;
use fixshade::render::{bins_len, CachedVertex, Carry, MeshDraw, MeshMemory};
use fixshade_testkit::support::{corner, full, Solid, Tris, S};

/// The largest frame width and height the renderer accepts (documented on
/// `Layout::new`).
const MAX_SIZE: u32 = 1024;

fn tri(p: [(i32, i32, i32); 3]) -> [fixshade::render::Corner; 3] {
    p.map(|(x, y, z)| corner(x * S, y * S, z, 0))
}

#[test]
fn full_frame_and_bands_validate_their_buffers() {
    let mut buf = [Gray8::new(0); 100];
    let mut z = [0u16; 100];
    assert_eq!(
        FullFrame::new(0, 5, &mut buf, None).unwrap_err(),
        RenderError::Size
    );
    assert_eq!(
        FullFrame::new(MAX_SIZE + 1, 1, &mut buf, None).unwrap_err(),
        RenderError::Size
    );
    let err = FullFrame::new(10, 11, &mut buf, None).unwrap_err();
    assert_eq!(
        err,
        RenderError::BufferTooSmall {
            which: "frame",
            needed: 110,
            got: 100
        }
    );
    assert_eq!(
        err.to_string(),
        "frame too small: 110 elements needed, 100 given"
    );
    assert_eq!(
        FullFrame::new(10, 10, &mut buf, Some(&mut z[..99])).unwrap_err(),
        RenderError::BufferTooSmall {
            which: "depth buffer",
            needed: 100,
            got: 99
        }
    );
    // longer buffers are fine: the frame uses the first width·height
    let mut long = [Gray8::new(7); 120];
    let mut frame = FullFrame::new(10, 10, &mut long, Some(&mut z)).unwrap();
    frame.render(Gray8::new(1), &mut []).unwrap();
    assert_eq!(frame.pixels().len(), 120);
    assert!(long[..100].iter().all(|p| p.luma() == 1));
    assert!(
        long[100..].iter().all(|p| p.luma() == 7),
        "beyond the frame: untouched"
    );

    let layout = Layout::banded(40, 30, 8).unwrap();
    let mut strip = [Gray8::new(0); 40 * 8];
    let mut short = [0u16; 40 * 8 - 1];
    assert_eq!(
        Bands::new(layout, &mut strip[..40 * 8 - 1], None).unwrap_err(),
        RenderError::BufferTooSmall {
            which: "colour strip",
            needed: 320,
            got: 319
        }
    );
    assert_eq!(
        Bands::new(layout, &mut strip, Some(&mut short)).unwrap_err(),
        RenderError::BufferTooSmall {
            which: "depth strip",
            needed: 320,
            got: 319
        }
    );
    assert_eq!(Layout::banded(0, 30, 8), Err(RenderError::Size));
    assert_eq!(Layout::banded(40, 30, 0), Err(RenderError::Size));
    assert_eq!(Layout::full(40, MAX_SIZE + 1), Err(RenderError::Size));
    // every stage error converts into the crate's error
    let e: Error = RenderError::Size.into();
    assert_eq!(e, Error::Render(RenderError::Size));
}

#[test]
fn bands_on_the_simulator_equal_the_full_frame() {
    let t = tri([(3, 2, 0), (150, 40, 0), (20, 90, 0)]);
    let mut item = Tris::screen(Solid(Rgb565::GREEN), vec![t]);
    let px = full(160, 100, Rgb565::BLACK, false, &mut [&mut item]);
    assert!(px.iter().filter(|&&p| p == Rgb565::GREEN).count() > 3000);
    for rows in [1, 7, 8, 100] {
        let layout = Layout::banded(160, 100, rows).unwrap();
        let mut strip = vec![Rgb565::BLACK; 160 * rows as usize];
        let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(160, 100));
        Bands::new(layout, &mut strip, None)
            .unwrap()
            .render(&mut display, Rgb565::BLACK, &mut [&mut item])
            .unwrap();
        for y in 0..100 {
            for x in 0..160 {
                assert_eq!(
                    display.get_pixel(Point::new(x, y)),
                    px[(y * 160 + x) as usize],
                    "{rows}-row bands: ({x}, {y})"
                );
            }
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
fn bands_return_the_display_error_and_stop() {
    // 10 rows in 2-row bands: band 0 is sent, band 1 fails and drawing stops
    let layout = Layout::banded(200, 10, 2).unwrap();
    let mut strip = [Gray8::new(0); 400];
    let mut display = Flaky(0);
    let t = tri([(0, 0, 0), (150, 2, 0), (10, 9, 0)]);
    let mut item = Tris::screen(Solid(Gray8::new(3)), vec![t]);
    let r = Bands::new(layout, &mut strip, None).unwrap().render(
        &mut display,
        Gray8::new(0),
        &mut [&mut item],
    );
    assert_eq!(r, Err(RenderError::Display(2)));
    assert_eq!(display.0, 2, "no band sent after the error");
}

#[test]
fn band_rendering_with_depth_matches_full_frame() {
    let far = tri([(2, 2, 3000), (60, 10, 3000), (10, 60, 3000)]);
    let near = tri([(5, 30, 100), (60, 20, 5000), (40, 62, 100)]);
    let mut a = Tris::screen(Solid(Gray8::new(50)), vec![far]);
    let mut b = Tris::screen(Solid(Gray8::new(200)), vec![near]);
    let whole = full(64, 64, Gray8::new(0), true, &mut [&mut a, &mut b]);
    for rows in [1u32, 3, 8, 64] {
        let banded = support::banded(64, 64, rows, Gray8::new(0), true, &mut [&mut a, &mut b]);
        assert_eq!(banded, whole, "{rows}-row bands");
    }
    assert!(whole.iter().any(|p| p.luma() == 50) && whole.iter().any(|p| p.luma() == 200));
    // the near triangle is partly behind the far one (z rises to 5000)
    let far_only = full(64, 64, Gray8::new(0), true, &mut [&mut a]);
    assert!(whole
        .iter()
        .zip(&far_only)
        .any(|(w, f)| w.luma() == 50 && f.luma() == 50));
}

#[test]
fn band_geometry() {
    let layout = Layout::banded(240, 250, 8).unwrap();
    assert_eq!((layout.band_rows(), layout.bands()), (8, 32));
    assert_eq!(layout.rows(31), 248..250);
    assert_eq!(layout.rows(0), 0..8);
    // more rows per band than the frame has: one band
    let one = Layout::banded(240, 5, 8).unwrap();
    assert_eq!((one.band_rows(), one.bands(), one.rows(0)), (5, 1, 0..5));
    let mut tiny = [Rgb565::BLACK; 10];
    assert!(matches!(
        Bands::new(layout, &mut tiny, None),
        Err(RenderError::BufferTooSmall { .. })
    ));
}

#[test]
fn a_mesh_prepared_for_another_layout_is_refused() {
    let lighting = fixshade::standard::lambert::<Q14>().unwrap();
    let t = fixshade::standard::transform().unwrap();
    let (nv, nt) = fixshade::standard::COUNTS;
    let mut cache = vec![CachedVertex::default(); nv];
    let mut bins = vec![0u16; bins_len(nt, 30)];
    let mut carry = vec![Carry::default(); 128];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut carry,
    };
    let banded = Layout::banded(240, 240, 8).unwrap();
    let shader = Shader::new(GouraudShading, &lighting, Linear);
    let mut draw = MeshDraw::new(
        banded,
        fixshade::standard::SPHERE.mesh(),
        &t,
        shader,
        memory,
        DrawOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut color = vec![Rgb565::RED; 240 * 240];
    let mut frame = FullFrame::new(240, 240, &mut color, None).unwrap();
    let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut draw];
    assert_eq!(
        frame.render(Rgb565::BLACK, items),
        Err(RenderError::LayoutMismatch)
    );
    assert!(
        frame.pixels().iter().all(|&p| p == Rgb565::RED),
        "nothing drawn, not even cleared"
    );
}

/// A textured shader on a mesh without texture coordinates, and a vertex
/// cache shorter than the mesh: typed errors from `MeshDraw::new`, not a
/// picture painted with one texel or a bare "too many vertices".
#[test]
fn missing_texture_coordinates_and_a_short_cache_are_refused() {
    use fixshade::texture::{Filter, Texels, Texture, Wrap};
    static WHITE: [u16; 16] = [0xFFFF; 16];
    let texture = Texture::new(Texels::Rgb565(&WHITE), 2, 2, Wrap::Repeat).unwrap();
    let lighting = fixshade::standard::lambert::<Q14>().unwrap();
    let t = fixshade::standard::transform().unwrap();
    let (nv, nt) = fixshade::standard::COUNTS;
    let layout = Layout::full(240, 240).unwrap();
    let shader: Shader<'_, _, _, _, Rgb565> = Shader::new(
        GouraudShading.textured(texture, Filter::Nearest),
        &lighting,
        Linear,
    );
    let mut cache = vec![CachedVertex::ZERO; nv];
    let mut bins = vec![0u16; bins_len(nt, 1)];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut [],
    };
    let mesh = fixshade::standard::SPHERE.mesh();
    assert!(mesh.texcoords().is_empty());
    assert!(matches!(
        MeshDraw::new(layout, mesh, &t, shader, memory, DrawOptions::default()),
        Err(RenderError::MissingAttribute(_))
    ));
    let shader: Shader<'_, _, _, _, Rgb565> = Shader::new(GouraudShading, &lighting, Linear);
    let mut cache = vec![CachedVertex::ZERO; nv - 1];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut [],
    };
    match MeshDraw::new(layout, mesh, &t, shader, memory, DrawOptions::default()) {
        Err(RenderError::BufferTooSmall { which, needed, got }) => {
            assert_eq!((which, needed, got), ("vertex cache", nv, nv - 1));
        }
        other => panic!("{:?}", other.err()),
    }
}
