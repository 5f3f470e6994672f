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
//! file names. `labelled_q14.png`: the first scene with its title and a frame
//! drawn over it by embedded-graphics in the same 8-row bands (2D over 3D).

use fixshade_testkit::render;
use fixshade_testkit::surface_scenes;

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use embedded_graphics::text::Text;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use fixshade::framebuffer::{Bands, DrawBand, Layout};
use fixshade::num::{Scalar, Q14, Q30};
use fixshade_testkit::reference::V3;
use fixshade_testkit::render::{
    compare, compare_mesh, reference_rgb888, render_mesh, render_reference, render_tier,
    render_triangles, scenes, with_draws, Scene,
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

/// The scene's meshes in 8-row bands with a title bar, its text and a frame
/// drawn over them (every embedded-graphics `Drawable` is an item of the
/// frame), straight into the simulator display.
fn render_labelled(scene: &Scene, path: &Path) {
    const ROWS: u32 = 8;
    let (w, h) = (scene.width, scene.height);
    let layout = Layout::banded(w, h, ROWS).expect("the scene's size is a layout");
    let mut strip = vec![Rgb888::BLACK; (w * ROWS) as usize];
    let mut depth = vec![0u16; (w * ROWS) as usize];
    let mut bar = Rectangle::new(Point::new(0, h as i32 - 16), Size::new(w, 16))
        .into_styled(PrimitiveStyle::with_fill(Rgb888::new(24, 32, 48)));
    let mut title = Text::new(
        scene.name,
        Point::new(6, h as i32 - 5),
        MonoTextStyle::new(&FONT_6X10, Rgb888::WHITE),
    );
    let mut frame = Rectangle::new(Point::zero(), Size::new(w, h))
        .into_styled(PrimitiveStyle::with_stroke(Rgb888::new(200, 200, 210), 2));
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(w, h));
    with_draws::<Q14<2>, Rgb888, _>(scene, layout, |meshes| {
        let mut items: Vec<&mut dyn DrawBand<Rgb888>> = meshes
            .iter_mut()
            .map(|m| &mut **m as &mut dyn DrawBand<Rgb888>)
            .collect();
        items.extend([
            &mut bar as &mut dyn DrawBand<Rgb888>,
            &mut title,
            &mut frame,
        ]);
        Bands::new(layout, &mut strip, Some(&mut depth))
            .and_then(|mut bands| bands.render(&mut display, Rgb888::BLACK, &mut items))
            .expect("the simulator display accepts every pixel");
    });
    display
        .to_rgb_output_image(&OutputSettingsBuilder::new().build())
        .save_png(path)
        .expect("write PNG");
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
    if let Some(scene) = scenes().first() {
        let path = dir.join("labelled_q14.png");
        render_labelled(scene, &path);
        println!(
            "\n{}  2D over 3D: the scene's title and a frame drawn over it in the same bands",
            path.display()
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
