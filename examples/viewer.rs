//! An interactive window on the renderer (the embedded-graphics simulator
//! with SDL2): the standard scene's sphere or the trefoil knot, turning,
//! under flat, Gouraud or Phong shading (`PhongShading`, the per-pixel
//! kernel of every lighting). Needs SDL2 (`apt-get install
//! libsdl2-dev`), so it is behind the `sdl` feature and not built by CI:
//!
//! ```sh
//! cargo run --release --example viewer --features sdl
//! ```
//!
//! Keys: `1` flat, `2` Gouraud, `3` Phong; `m` sphere / knot; arrows turn
//! the model; space pauses the turning; drag with the mouse to turn it;
//! Escape quits.

use std::time::Instant;

use embedded_graphics::prelude::Point;
use embedded_graphics_simulator::sdl2::Keycode;
use embedded_graphics_simulator::{
    OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
};
use fixshade::camera::{MeshTransform, Orthographic};
use fixshade::framebuffer::DrawBand;
use fixshade::mesh::TorusKnot;
use fixshade::prelude::*;
use fixshade::render::{CachedVertex, MeshMemory};
use fixshade::shade::Kernel;
use fixshade::standard;

const W: u32 = standard::SIZE;
const N: (usize, usize) = TorusKnot::counts(96, 8);
static KNOT: MeshData<{ N.0 }, { N.1 }> = MeshData::torus_knot(&TorusKnot::TREFOIL, 96, 8, 14);

/// One whole frame of `mesh` under `kernel` into `display`.
fn render<K>(
    kernel: K,
    mesh: Mesh<'_>,
    t: &MeshTransform<Orthographic>,
    display: &mut SimulatorDisplay<Rgb565>,
) -> Result<(), Box<dyn std::error::Error>>
where
    K: Kernel<Color = Rgb565>,
{
    let layout = Layout::full(W, W)?;
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); mesh.vertex_count()];
    let mut bins = vec![0u16; bins_len(mesh.triangle_count(), 1)];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut [],
    };
    let mut draw = MeshDraw::new(layout, mesh, t, kernel, memory, DrawOptions::default())?;
    let mut color = vec![Rgb565::BLACK; (W * W) as usize];
    let mut depth = vec![0u16; (W * W) as usize];
    let mut frame = FullFrame::new(W, W, &mut color, Some(&mut depth))?;
    let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut draw];
    frame.render(Rgb565::BLACK, items)?;
    frame.flush(display)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let camera = standard::camera()?;
    let lighting = standard::blinn::<Q14>()?;
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(W, W));
    let mut window = Window::new(
        "fixshade: 1 flat, 2 Gouraud, 3 Phong, m mesh, arrows/drag turn, space pause",
        &OutputSettingsBuilder::new().scale(2).build(),
    );
    let (mut yaw, mut pitch) = (0.0f32, 0.4f32);
    let (mut mode, mut knot, mut paused) = (3, true, false);
    let mut drag: Option<Point> = None;
    let mut last = Instant::now();
    'frames: loop {
        let dt = last.elapsed().as_secs_f32();
        last = Instant::now();
        if !paused {
            yaw += 0.8 * dt;
        }
        let model = Mat4::rotate_x(pitch).mul(&Mat4::rotate_y(yaw));
        let mesh = if knot {
            KNOT.mesh()
        } else {
            standard::SPHERE.mesh()
        };
        let t = camera.mesh_transform(&model, mesh.frac())?;
        match mode {
            1 => render(
                Shader::new(FlatShading, &lighting, Linear),
                mesh,
                &t,
                &mut display,
            )?,
            2 => render(
                Shader::new(GouraudShading, &lighting, Linear),
                mesh,
                &t,
                &mut display,
            )?,
            _ => render(
                Shader::new(PhongShading, &lighting, Linear),
                mesh,
                &t,
                &mut display,
            )?,
        }
        window.update(&display);
        for event in window.events() {
            match event {
                SimulatorEvent::Quit => break 'frames,
                SimulatorEvent::KeyDown { keycode, .. } => match keycode {
                    Keycode::Num1 => mode = 1,
                    Keycode::Num2 => mode = 2,
                    Keycode::Num3 => mode = 3,
                    Keycode::M => knot = !knot,
                    Keycode::Space => paused = !paused,
                    Keycode::Left => yaw -= 0.1,
                    Keycode::Right => yaw += 0.1,
                    Keycode::Up => pitch -= 0.1,
                    Keycode::Down => pitch += 0.1,
                    _ => {}
                },
                SimulatorEvent::MouseButtonDown { point, .. } => drag = Some(point),
                SimulatorEvent::MouseButtonUp { .. } => drag = None,
                SimulatorEvent::MouseMove { point } => {
                    if let Some(p) = drag {
                        yaw += 0.01 * (point.x - p.x) as f32;
                        pitch += 0.01 * (point.y - p.y) as f32;
                        drag = Some(point);
                    }
                }
                _ => {}
            }
        }
    }
    Ok(())
}
