//! Renders every reference scene of the source documents in the host simulator
//! (embedded-graphics-simulator, no SDL) and writes PNGs to `target/renders/`:
//!
//! ```sh
//! cargo run --release --example showcase
//! ```
//!
//! Each scene is rendered by the mesh renderer (`fixshade::render`: one
//! `MeshDraw` per object with its own model matrix and material, drawn in 8-row
//! bands straight into the simulator's `DrawTarget`, as firmware drives a
//! display) with the fast tier `Q14<2>` and the accurate tier `Q30<3>`
//! (`<scene>_q14.png`, `<scene>_q30.png`); by the per-triangle API
//! (`<scene>_q14_triangles.png`); and by the f64 reference model
//! (`<scene>_reference.png`). The error of each against the reference is
//! printed beside the file names.

#[path = "../tests/common/render.rs"]
mod render;
#[path = "../tests/common/surface.rs"]
mod surface;
#[path = "../tests/common/surface_scenes.rs"]
mod surface_scenes;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use fixshade::num::{Scalar, Q14, Q30};
use fixshade::reference::V3;
use fixshade::target::DrawTargetAdapter;
use render::{
    compare, compare_mesh, draw_into, prepare, reference_rgb888, render_mesh, render_reference,
    render_tier, scenes, Scene,
};
use std::path::{Path, PathBuf};

fn save(scene: &Scene, pixels: &[Rgb888], path: &Path) {
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(scene.width, scene.height));
    let points = (0..scene.height)
        .flat_map(|y| (0..scene.width).map(move |x| Point::new(x as i32, y as i32)));
    display
        .draw_iter(points.zip(pixels.iter().copied()).map(|(p, c)| Pixel(p, c)))
        .expect("the simulator display accepts every pixel");
    let settings = OutputSettingsBuilder::new().build();
    display
        .to_rgb_output_image(&settings)
        .save_png(path)
        .expect("write PNG");
}

/// Renders straight into the simulator display through `DrawTargetAdapter`, as
/// firmware drives a real display, saves the PNG, and compares the display's pixels
/// (and an Rgb565 render) with the reference.
fn render_to_display<S: Scalar>(scene: &Scene, path: &Path) -> render::Diff {
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(scene.width, scene.height));
    let mut depth = vec![u16::MAX; (scene.width * scene.height) as usize];
    {
        let mut fb = DrawTargetAdapter::new(&mut display);
        // the simulator display accepts every pixel: a display error panics
        draw_into::<S, Rgb888, _>(scene, &prepare(scene), &mut fb, &mut depth);
    }
    let settings = OutputSettingsBuilder::new().build();
    display
        .to_rgb_output_image(&settings)
        .save_png(path)
        .expect("write PNG");
    let shown: Vec<Rgb888> = (0..scene.height)
        .flat_map(|y| (0..scene.width).map(move |x| Point::new(x as i32, y as i32)))
        .map(|p| display.get_pixel(p))
        .collect();
    compare(
        &shown,
        &render_tier::<S, Rgb565>(scene),
        &render_reference(scene),
    )
}

/// Renders with the mesh renderer straight into the simulator display, saves
/// the PNG and compares the display's pixels with the reference.
fn render_mesh_to_display<S: Scalar>(
    scene: &Scene,
    reference: &[Option<V3>],
    path: &Path,
) -> (u32, f64, usize, usize) {
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(scene.width, scene.height));
    render_mesh::<S, _>(scene, &mut display).expect("the simulator display accepts every pixel");
    display
        .to_rgb_output_image(&OutputSettingsBuilder::new().build())
        .save_png(path)
        .expect("write PNG");
    let shown: Vec<Rgb888> = (0..scene.height)
        .flat_map(|y| (0..scene.width).map(move |x| Point::new(x as i32, y as i32)))
        .map(|p| display.get_pixel(p))
        .collect();
    compare_mesh(&shown, reference)
}

fn main() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join("renders");
    std::fs::create_dir_all(&dir).expect("create target/renders");
    println!("Rendering the reference scenes into {}", dir.display());
    for scene in scenes() {
        let reference = render_reference(&scene);
        let ref_path = dir.join(format!("{}_reference.png", scene.name));
        save(&scene, &reference_rgb888(&reference), &ref_path);
        println!("\n{} — {}", scene.name, scene.title);
        println!("  {}", ref_path.display());
        for (tier, (max, mean, n, only)) in [
            (
                "q14",
                render_mesh_to_display::<Q14<2>>(
                    &scene,
                    &reference,
                    &dir.join(format!("{}_q14.png", scene.name)),
                ),
            ),
            (
                "q30",
                render_mesh_to_display::<Q30<3>>(
                    &scene,
                    &reference,
                    &dir.join(format!("{}_q30.png", scene.name)),
                ),
            ),
        ] {
            println!(
                "  {}  mesh renderer: max {max} LSB, mean {mean:.3} on {n} pixels; {only} silhouette pixels covered by one of the two",
                dir.join(format!("{}_{tier}.png", scene.name)).display(),
            );
        }
        let path = dir.join(format!("{}_q14_triangles.png", scene.name));
        let d = render_to_display::<Q14<2>>(&scene, &path);
        println!(
            "  {}  per-triangle API: max {} LSB, mean {:.3}, PSNR {:.1} dB, Rgb565 identical {:.1} %",
            path.display(),
            d.max,
            d.mean,
            d.psnr,
            100.0 * d.identical_565
        );
    }
    println!("\nSurface detail (textures, normal and bump mapping, displacement, silhouette refinement):");
    for img in surface_scenes::all() {
        let path = dir.join(format!("{}.png", img.name));
        let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(img.width, img.height));
        let points = (0..img.height)
            .flat_map(|y| (0..img.width).map(move |x| Point::new(x as i32, y as i32)));
        display
            .draw_iter(
                points
                    .zip(img.pixels.iter().copied())
                    .map(|(p, c)| Pixel(p, c)),
            )
            .expect("the simulator display accepts every pixel");
        display
            .to_rgb_output_image(&OutputSettingsBuilder::new().build())
            .save_png(&path)
            .expect("write PNG");
        println!("  {} — {}", path.display(), img.title);
        for n in &img.notes {
            println!("    {n}");
        }
    }
}
