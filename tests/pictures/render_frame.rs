//! The mesh renderer on the standard scene: banded equals full frame bit for
//! bit, every shading mode, orthographic and through the near plane (the
//! per-triangle front equals `MeshDraw` bit for bit: `tests/pictures/one_pipeline.rs`).

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::prelude::*;
use fixshade::framebuffer::Checksum;
use fixshade::framebuffer::{Bands, DrawBand, FullFrame, Layout};
use fixshade::prelude::*;
use fixshade::render::{bins_len, CachedVertex, Carry, MeshDraw, MeshMemory};
use fixshade::shade::{Kernel, PhongShading};
use fixshade::standard;

const W: u32 = standard::SIZE;
const NV: usize = standard::COUNTS.0;
const NT: usize = standard::COUNTS.1;

/// Renders the standard scene with `kernel` in bands of `band_rows` rows;
/// returns the pixels and the checksum of the stream sent to the display.
fn render<K: Kernel<Color = Rgb565>>(kernel: K, band_rows: u32) -> (Vec<Rgb565>, u32) {
    let layout = Layout::banded(W, W, band_rows).unwrap();
    let mesh = standard::SPHERE.mesh();
    let t = standard::transform().unwrap();
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); NV];
    let mut bins = vec![0u16; bins_len(NT, layout.bands() as usize)];
    let mut carry = vec![Carry::default(); 128];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut carry,
    };
    let mut draw = MeshDraw::new(layout, mesh, &t, kernel, memory, DrawOptions::default()).unwrap();
    let mut strip = vec![Rgb565::BLACK; (W * band_rows) as usize];
    let mut depth = vec![0u16; (W * band_rows) as usize];
    let mut bands = Bands::new(layout, &mut strip, Some(&mut depth)).unwrap();
    let mut sink = Recorder(Vec::new(), Checksum::new(Size::new(W, W)));
    let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut draw];
    bands.render(&mut sink, Rgb565::BLACK, items).unwrap();
    (sink.0, sink.1.value())
}

/// Records the pixel stream and checksums it.
struct Recorder(Vec<Rgb565>, Checksum<Rgb565>);
impl OriginDimensions for Recorder {
    fn size(&self) -> Size {
        Size::new(W, W)
    }
}
impl DrawTarget for Recorder {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        unreachable!("the band renderer sends whole bands")
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &embedded_graphics_core::primitives::Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        let c: Vec<Rgb565> = colors.into_iter().collect();
        self.0.extend_from_slice(&c);
        self.1.fill_contiguous(area, c)
    }
}

#[test]
fn bands_equal_full_frame_bit_for_bit() {
    let lit = standard::blinn::<Q14>().unwrap();
    let lam = standard::lambert::<Q14>().unwrap();
    for rows in [240, 8, 1, 5, 17] {
        let g = render(Shader::new(GouraudShading, &lit, Linear), rows);
        let g_full = render(Shader::new(GouraudShading, &lit, Linear), 240);
        assert_eq!(g.0, g_full.0, "gouraud, {rows}-row bands");
        assert_eq!(g.1, g_full.1);
        let f = render(Shader::new(FlatShading, &lam, Linear), rows);
        let f_full = render(Shader::new(FlatShading, &lam, Linear), 240);
        assert_eq!(f.0, f_full.0, "flat, {rows}-row bands");
        let p = render(Shader::new(PhongShading, &lit, Linear), rows);
        let p_full = render(Shader::new(PhongShading, &lit, Linear), 240);
        assert_eq!(p.0, p_full.0, "phong, {rows}-row bands");
        let q = render(Shader::new(PhongShading, &lit, Linear), rows);
        let q_full = render(Shader::new(PhongShading, &lit, Linear), 240);
        assert_eq!(q.0, q_full.0, "general phong, {rows}-row bands");
    }
    let (px, _) = render(Shader::new(GouraudShading, &lit, Linear), 8);
    let lit_px = px.iter().filter(|p| **p != Rgb565::BLACK).count();
    // the sphere covers 85 % of the width: π·102² ≈ 32 700 pixels
    assert!((32_000..33_500).contains(&lit_px), "{lit_px} lit pixels");
}

/// The standard sphere through a perspective camera so close that the near
/// plane cuts its front (the clip-space path), in bands of `band_rows` rows.
fn render_near<K: Kernel<Color = Rgb565>>(kernel: K, band_rows: u32) -> Vec<Rgb565> {
    let layout = Layout::banded(W, W, band_rows).unwrap();
    let cam = Camera::perspective(1.2, 1.0, 1.0, 20.0, Viewport::new(0, 0, W, W).unwrap())
        .unwrap()
        .with_view(Mat4::translate([0.2, -0.1, -1.9]));
    let t = cam
        .mesh_transform(
            &Mat4::rotate_y(0.4).mul(&Mat4::rotate_x(0.3)),
            standard::SPHERE.frac,
        )
        .unwrap();
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); NV];
    let mut bins = vec![0u16; bins_len(NT, layout.bands() as usize)];
    let mut carry = vec![Carry::default(); 256];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut carry,
    };
    let mut draw = MeshDraw::new(
        layout,
        standard::SPHERE.mesh(),
        &t,
        kernel,
        memory,
        DrawOptions::default(),
    )
    .unwrap();
    let mut strip = vec![Rgb565::BLACK; (W * band_rows) as usize];
    let mut depth = vec![0u16; (W * band_rows) as usize];
    let mut bands = Bands::new(layout, &mut strip, Some(&mut depth)).unwrap();
    let mut sink = Recorder(Vec::new(), Checksum::new(Size::new(W, W)));
    bands
        .render(&mut sink, Rgb565::BLACK, &mut [&mut draw])
        .unwrap();
    sink.0
}

#[test]
fn perspective_through_the_near_plane_bands_equal_full_frame() {
    let lit = standard::blinn::<Q14>().unwrap();
    let g_full = render_near(Shader::new(GouraudShading, &lit, Linear), 240);
    let p_full = render_near(Shader::new(PhongShading, &lit, Linear), 240);
    for rows in [8, 1, 13] {
        assert_eq!(
            render_near(Shader::new(GouraudShading, &lit, Linear), rows),
            g_full,
            "{rows}"
        );
        assert_eq!(
            render_near(Shader::new(PhongShading, &lit, Linear), rows),
            p_full,
            "{rows}"
        );
    }
    // the near plane opens the sphere: its front is cut away, the back faces
    // behind it are culled, so the middle of the frame shows the background
    let lit_px = g_full.iter().filter(|p| **p != Rgb565::BLACK).count();
    assert!(lit_px > 10_000, "{lit_px}");
    let centre = (W / 2 * W + W / 2) as usize;
    assert_eq!(g_full[centre], Rgb565::BLACK);
}

#[test]
fn full_frame_target_matches_bands() {
    let lit = standard::blinn::<Q14>().unwrap();
    let (banded, _) = render(Shader::new(GouraudShading, &lit, Linear), 8);
    let layout = Layout::full(W, W).unwrap();
    let mesh = standard::SPHERE.mesh();
    let t = standard::transform().unwrap();
    let mut cache = vec![CachedVertex::default(); NV];
    let mut bins = vec![0u16; bins_len(NT, 1)];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut [],
    };
    let shader = Shader::new(GouraudShading, &lit, Linear);
    let mut draw = MeshDraw::new(layout, mesh, &t, shader, memory, DrawOptions::default()).unwrap();
    let mut color = vec![Rgb565::BLACK; (W * W) as usize];
    let mut depth = vec![0u16; (W * W) as usize];
    let mut frame = FullFrame::new(W, W, &mut color, Some(&mut depth)).unwrap();
    frame.render(Rgb565::BLACK, &mut [&mut draw]).unwrap();
    assert_eq!(frame.pixels(), &banded[..]);
}

#[test]
#[ignore]
fn write_pngs() {
    use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
    let lit = standard::blinn::<Q14>().unwrap();
    let lam = standard::lambert::<Q14>().unwrap();
    let imgs = [
        ("flat", render(Shader::new(FlatShading, &lam, Linear), 8).0),
        (
            "near_phong",
            render_near(Shader::new(PhongShading, &lit, Linear), 8),
        ),
        (
            "gouraud",
            render(Shader::new(GouraudShading, &lit, Linear), 8).0,
        ),
        (
            "phong",
            render(Shader::new(PhongShading, &lit, Linear), 8).0,
        ),
    ];
    for (name, px) in imgs {
        let mut d = SimulatorDisplay::<Rgb565>::new(Size::new(W, W));
        d.fill_contiguous(
            &embedded_graphics_core::primitives::Rectangle::new(Point::zero(), Size::new(W, W)),
            px,
        )
        .unwrap();
        d.to_rgb_output_image(&OutputSettingsBuilder::new().build())
            .save_png(format!("/tmp/std_{name}.png"))
            .unwrap();
    }
}
