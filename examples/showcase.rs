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
//! (`<scene>_q14.png`, `<scene>_q30.png`); by the per-triangle front
//! (`render::draw_triangle` with the same corners, `<scene>_q14_triangles.png`:
//! the mesh renderer's pixels bit for bit); and by the f64 reference model
//! (`<scene>_reference.png`, from the renderer's quantised inputs on its
//! coverage). The error of each against the reference is printed beside the
//! file names.

use fixshade_testkit::render;
use fixshade_testkit::surface_scenes;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use fixshade::num::{Scalar, Q14, Q30};
use fixshade_testkit::reference::V3;
use fixshade_testkit::render::{
    compare, compare_mesh, reference_rgb888, render_mesh, render_reference, render_tier,
    render_triangles, scenes, Scene,
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

/// Renders through the per-triangle front (the whole frame in memory), saves
/// the PNG, and compares it (and an Rgb565 render) with the reference; and
/// counts the pixels that differ from the mesh renderer's frame `mesh`.
fn render_triangles_png<S: Scalar>(
    scene: &Scene,
    reference: &[Option<V3>],
    mesh: &[Rgb888],
    path: &Path,
) -> (render::Diff, usize) {
    let px = render_triangles::<S, Rgb888>(scene);
    save(scene, &px, path);
    let differ = px.iter().zip(mesh).filter(|(a, b)| a != b).count();
    (
        compare(&px, &render_triangles::<S, Rgb565>(scene), reference),
        differ,
    )
}

/// Renders with the mesh renderer straight into the simulator display, saves
/// the PNG and compares the display's pixels with the reference.
fn render_mesh_to_display<S: Scalar>(
    scene: &Scene,
    reference: &[Option<V3>],
    path: &Path,
) -> ((u32, f64, usize, usize), Vec<Rgb888>) {
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
    (compare_mesh(&shown, reference), shown)
}

/// The whole-frame renders (Rgb888 and Rgb565) against the reference.
fn diff_whole<S: Scalar>(scene: &Scene, reference: &[Option<V3>]) -> render::Diff {
    compare(
        &render_tier::<S, Rgb888>(scene),
        &render_tier::<S, Rgb565>(scene),
        reference,
    )
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
        let (q14, q14_px) = render_mesh_to_display::<Q14<2>>(
            &scene,
            &reference,
            &dir.join(format!("{}_q14.png", scene.name)),
        );
        let (q30, _) = render_mesh_to_display::<Q30<3>>(
            &scene,
            &reference,
            &dir.join(format!("{}_q30.png", scene.name)),
        );
        for (tier, (max, mean, n, only)) in [("q14", q14), ("q30", q30)] {
            println!(
                "  {}  mesh renderer: max {max} LSB, mean {mean:.3} on {n} pixels; {only} pixels covered by one of the two",
                dir.join(format!("{}_{tier}.png", scene.name)).display(),
            );
        }
        let d = diff_whole::<Q14<2>>(&scene, &reference);
        println!(
            "  (whole frame, Rgb888 and Rgb565: max {} LSB, mean {:.3}, PSNR {:.1} dB, Rgb565 identical {:.1} %)",
            d.max,
            d.mean,
            d.psnr,
            100.0 * d.identical_565
        );
        let path = dir.join(format!("{}_q14_triangles.png", scene.name));
        let (d, differ) = render_triangles_png::<Q14<2>>(&scene, &reference, &q14_px, &path);
        println!(
            "  {}  per-triangle front: max {} LSB, mean {:.3}, PSNR {:.1} dB on {} pixels; {}",
            path.display(),
            d.max,
            d.mean,
            d.psnr,
            d.pixels,
            if differ == 0 {
                "the mesh renderer's pixels bit for bit".to_string()
            } else {
                format!("{differ} pixels differ from the mesh renderer")
            }
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
