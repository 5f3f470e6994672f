//! The host side of the speed/accuracy table: for every tier × shading method ×
//! light set, the error of a 240×240 lit sphere against the f64 reference (same
//! method, same pixels) and the host time per shaded pixel (median of repeated
//! renders of a `MeshDraw` prepared once: set-up, rasterization and shading;
//! the vertex stage and the bins are the per-frame geometry work, outside the
//! timing; with the ratio to `f32` Phong in the same run). Writes
//! `measure/out/host.json`, which `python3 measure/tradeoff.py` merges with the
//! Cortex-M instruction counts.
//!
//! ```sh
//! cargo bench --bench tradeoff
//! ```

use fixshade_testkit::render;

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use fixshade::framebuffer::{DrawBand, FullFrame, Layout};
use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade_testkit::render::{
    compare, config_scene, render_reference, render_tier, with_draws, with_incremental_draws,
    LightSet, Mode, Scene, LIGHT_SETS, MODES,
};
use std::fmt::Write;
use std::time::Instant;

const RUNS: usize = 15;

struct Row {
    tier: &'static str,
    mode: &'static str,
    lights: LightSet,
    diff: render::Diff,
    ns_per_pixel: f64,
}

/// Renders the prepared items `RUNS` times into an Rgb565 frame: the frame
/// and the median time.
fn time(scene: &Scene, items: &mut [&mut dyn DrawBand<Rgb565>]) -> (Vec<Rgb565>, f64) {
    let (w, h) = (scene.width, scene.height);
    let n = (w * h) as usize;
    let mut rgb565 = vec![Rgb565::BLACK; n];
    let mut depth = vec![0u16; n];
    let mut times = Vec::with_capacity(RUNS);
    for _ in 0..RUNS {
        let t = Instant::now();
        FullFrame::new(w, h, &mut rgb565, Some(&mut depth))
            .unwrap()
            .render(Rgb565::BLACK, items)
            .unwrap();
        times.push(t.elapsed().as_secs_f64());
        std::hint::black_box(&rgb565);
    }
    times.sort_by(f64::total_cmp);
    (rgb565, times[RUNS / 2])
}

fn measure<S: Scalar>(key: &'static str, rows: &mut Vec<Row>) {
    for lights in LIGHT_SETS {
        for mode in MODES {
            let scene = config_scene(lights, mode);
            let layout = Layout::full(scene.width, scene.height).unwrap();
            let reference = render_reference(&scene);
            let shaded = reference.iter().filter(|r| r.is_some()).count();
            let rgb888 = render_tier::<S, Rgb888>(&scene);
            let (rgb565, t) =
                with_draws::<S, Rgb565, _>(&scene, layout, |items| time(&scene, items));
            rows.push(Row {
                tier: key,
                mode: mode.name(),
                lights,
                diff: compare(&rgb888, &rgb565, &reference),
                ns_per_pixel: t * 1e9 / shaded.max(1) as f64,
            });
        }
    }
}

/// `IncrementalPhongShading` (Q14, directional light sets only).
fn measure_inc<const NW: u8>(key: &'static str, rows: &mut Vec<Row>) {
    for lights in [LightSet::DirDiffuse, LightSet::DirBlinn] {
        let scene = config_scene(lights, Mode::Phong);
        let layout = Layout::full(scene.width, scene.height).unwrap();
        let reference = render_reference(&scene);
        let shaded = reference.iter().filter(|r| r.is_some()).count();
        let rgb888 = render::render_incremental::<NW, Rgb888>(&scene).expect("a supported scene");
        let (rgb565, t) =
            with_incremental_draws::<NW, Rgb565, _>(&scene, layout, |items| time(&scene, items))
                .expect("a supported scene");
        rows.push(Row {
            tier: key,
            mode: "phong_inc",
            lights,
            diff: compare(&rgb888, &rgb565, &reference),
            ns_per_pixel: t * 1e9 / shaded.max(1) as f64,
        });
    }
}

fn main() {
    let mut rows = Vec::new();
    measure::<Q14<1>>("q14_1", &mut rows);
    measure::<Q14<2>>("q14_2", &mut rows);
    measure::<Q30<3>>("q30", &mut rows);
    measure::<f32>("f32", &mut rows);
    measure::<F32Fast<2>>("f32fast", &mut rows);
    measure_inc::<1>("q14_1", &mut rows);
    measure_inc::<2>("q14_2", &mut rows);
    let base = rows
        .iter()
        .find(|r| r.tier == "f32" && r.mode == "phong" && r.lights == LightSet::DirBlinn)
        .map(|r| r.ns_per_pixel)
        .unwrap_or(1.0);
    let mut json = String::from("[\n");
    println!(
        "{:<8} {:<8} {:<13} {:>4} {:>7} {:>7} {:>7} {:>8} {:>7}",
        "tier", "shading", "lights", "max", "mean", "PSNR", "565 %", "ns/px", "ratio"
    );
    for (i, r) in rows.iter().enumerate() {
        let d = &r.diff;
        println!(
            "{:<8} {:<8} {:<13} {:>4} {:>7.3} {:>7.1} {:>7.1} {:>8.2} {:>7.2}",
            r.tier,
            r.mode,
            r.lights.name(),
            d.max,
            d.mean,
            d.psnr,
            100.0 * d.identical_565,
            r.ns_per_pixel,
            r.ns_per_pixel / base
        );
        let psnr = if d.psnr.is_finite() {
            format!("{:.2}", d.psnr)
        } else {
            "null".into()
        };
        writeln!(
            json,
            "  {{\"tier\": \"{}\", \"shading\": \"{}\", \"lights\": \"{}\", \"max_lsb\": {}, \"mean_lsb\": {:.4}, \"psnr_db\": {}, \"identical_565\": {:.4}, \"pixels\": {}, \"host_ns_per_pixel\": {:.3}, \"host_ratio_to_f32_phong_dir_blinn\": {:.3}}}{}",
            r.tier,
            r.mode,
            r.lights.name(),
            d.max,
            d.mean,
            psnr,
            d.identical_565,
            d.pixels,
            r.ns_per_pixel,
            r.ns_per_pixel / base,
            if i + 1 < rows.len() { "," } else { "" }
        )
        .unwrap();
    }
    json.push_str("]\n");
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("measure/out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("host.json"), json).unwrap();
    println!("wrote {}", out.join("host.json").display());
}
