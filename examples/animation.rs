//! A trefoil torus knot (`MeshData::torus_knot`, built at compile time)
//! turning under per-pixel Phong shading, rendered the way firmware renders
//! it (8-row bands through a `DrawTarget`, here the host simulator) and
//! written as a looping GIF:
//!
//! ```sh
//! cargo run --release --example animation            # docs/img/torus_knot.gif
//! cargo run --release --example animation -- out.gif # elsewhere
//! ```
//!
//! Every frame is also checked: all 200 × 200 pixels sent, and the knot
//! covers a plausible part of the frame.

use std::f32::consts::PI;
use std::fs::File;
use std::io::BufWriter;

use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use fixshade::mesh::TorusKnot;
use fixshade::prelude::*;
use image::codecs::gif::{GifEncoder, Repeat};
use image::{Delay, Frame, RgbaImage};

/// Frame size, frames per turn, milliseconds per frame.
const SIZE: u32 = 200;
const FRAMES: usize = 48;
const DELAY_MS: u32 = 50;
const ROWS: u32 = 8;

const N: (usize, usize) = TorusKnot::counts(96, 8);
/// The trefoil in flash: 768 vertices, 1536 triangles, 18 KiB.
static KNOT: MeshData<{ N.0 }, { N.1 }> = MeshData::torus_knot(&TorusKnot::TREFOIL, 96, 8, 14);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "docs/img/torus_knot.gif".into());
    let camera = Camera::orthographic(
        -1.1,
        1.1,
        -1.1,
        1.1,
        1.0,
        10.0,
        Viewport::new(0, 0, SIZE, SIZE)?,
    )?
    .with_view(Mat4::translate([0.0, 0.0, -5.0]));
    let light = DirectionalLight::<Q14>::white([-0.6, 1.0, 1.0])?;
    let gold = MaterialDesc::classic(
        [1.0, 0.62, 0.15],
        AmbientSource::Object,
        0.12,
        0.75,
        0.7,
        40.0,
    );
    let lighting = Lighting::<Q14, _, BlinnPhong>::new([light], Material::new(&gold)?).eye_space();

    let layout = Layout::banded(SIZE, SIZE, ROWS)?;
    let mut strip = [Rgb565::BLACK; (SIZE * ROWS) as usize];
    let mut depth = [0u16; (SIZE * ROWS) as usize];
    const BANDS: usize = SIZE.div_ceil(ROWS) as usize;
    let mut buffers: Box<MeshBuffers<_, { N.0 }, { bins_len(N.1, BANDS) }, 256>> =
        Box::new(MeshBuffers::new());

    let file = BufWriter::new(File::create(&path)?);
    let mut gif = GifEncoder::new_with_speed(file, 10);
    gif.set_repeat(Repeat::Infinite)?;
    let settings = OutputSettingsBuilder::new().build();
    for f in 0..FRAMES {
        let a = 2.0 * PI * f as f32 / FRAMES as f32;
        // one turn about y, a slow wobble about x
        let model = Mat4::rotate_x(0.5 + 0.25 * a.sin()).mul(&Mat4::rotate_y(a));
        let transform = camera.mesh_transform(&model, KNOT.frac)?;
        let shader = Shader::new(IncrementalPhongShading, &lighting, Linear);
        let mut knot = MeshDraw::new(
            layout,
            KNOT.mesh(),
            &transform,
            shader,
            buffers.memory(),
            DrawOptions::default(),
        )?;
        let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(SIZE, SIZE));
        Bands::new(layout, &mut strip, Some(&mut depth))?.render(
            &mut display,
            Rgb565::BLACK,
            &mut [&mut knot],
        )?;
        let out = display.to_rgb_output_image(&settings);
        let rgb = out.as_image_buffer();
        let lit = rgb.pixels().filter(|p| p.0 != [0, 0, 0]).count();
        let share = lit as f64 / (SIZE * SIZE) as f64;
        assert!(
            (0.15..0.7).contains(&share),
            "frame {f}: {lit} lit pixels, the knot is missing or fills the frame"
        );
        let rgba = RgbaImage::from_fn(SIZE, SIZE, |x, y| {
            let p = rgb.get_pixel(x, y).0;
            image::Rgba([p[0], p[1], p[2], 255])
        });
        gif.encode_frame(Frame::from_parts(
            rgba,
            0,
            0,
            Delay::from_numer_denom_ms(DELAY_MS, 1),
        ))?;
    }
    drop(gif);
    println!(
        "{path}: {FRAMES} frames of {SIZE}x{SIZE}, {} bytes",
        std::fs::metadata(&path)?.len()
    );
    Ok(())
}
