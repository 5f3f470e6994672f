//! The host side of the speed/accuracy table: for every tier × shading method ×
//! light set, the error of a 240×240 lit sphere against the f64 reference (same
//! method, same pixels) and the host time per shaded pixel (median of repeated
//! renders, with the ratio to `f32` Phong in the same run). Writes
//! `measure/out/host.json`, which `python3 measure/tradeoff.py` merges with the
//! Cortex-M instruction counts.
//!
//! ```sh
//! cargo bench --bench tradeoff
//! ```

#[path = "../tests/common/render.rs"]
mod render;

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use fixshade::light::{DirectionalLight, LightColors, LightKind};
use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade::target::{DepthBuffer, SliceFramebuffer};
use render::{
    compare, config_scene, draw_prepared, prepare, render_reference, LightSet, Mode, LIGHT_SETS,
    MODES,
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

fn measure<S: Scalar>(key: &'static str, rows: &mut Vec<Row>) {
    for lights in LIGHT_SETS {
        for mode in MODES {
            let scene = config_scene(lights, mode);
            let prepared = prepare(&scene);
            let n = (scene.width * scene.height) as usize;
            let reference = render_reference(&scene);
            let mut rgb888 = vec![Rgb888::default(); n];
            let mut rgb565 = vec![Rgb565::default(); n];
            draw_prepared::<S, Rgb888>(&scene, &prepared, &mut rgb888, &mut vec![u16::MAX; n]);
            let mut times = Vec::with_capacity(RUNS);
            let mut shaded = 0;
            for _ in 0..RUNS {
                let mut depth = vec![u16::MAX; n];
                let t = Instant::now();
                shaded = draw_prepared::<S, Rgb565>(&scene, &prepared, &mut rgb565, &mut depth);
                times.push(t.elapsed().as_secs_f64());
                std::hint::black_box(&rgb565);
            }
            times.sort_by(f64::total_cmp);
            rows.push(Row {
                tier: key,
                mode: mode.name(),
                lights,
                diff: compare(&rgb888, &rgb565, &reference),
                ns_per_pixel: times[RUNS / 2] * 1e9 / shaded.max(1) as f64,
            });
        }
    }
}

/// Draws one object of a directional-light scene with `IncrementalPhongShading`
/// in tier `S`; returns the shaded pixels.
fn draw_inc<
    S: fixshade::shade::IncrementalTier,
    M: fixshade::lighting::Model,
    C: fixshade::color::OutputColor + Default,
>(
    scene: &render::Scene,
    prepared: &[[render::Vert; 3]],
    pixels: &mut [C],
    depth: &mut [u16],
) -> u64
where
    for<'a> fixshade::shade::Shader<
        'a,
        fixshade::shade::IncrementalPhongShading,
        fixshade::lighting::Lighting<S, [DirectionalLight<S>; 1], M>,
        fixshade::shade::Linear,
        C,
    >: fixshade::shade::Shading<S, Color = C>,
    fixshade::shade::IncrementalPhongShading:
        fixshade::shade::ModeState<fixshade::lighting::Lighting<S, [DirectionalLight<S>; 1], M>, C>,
{
    use fixshade::shade::Shading;
    let d = &scene.lights[0];
    let LightKind::Directional { towards_light } = d.kind else {
        unreachable!("directional light sets only")
    };
    let light = DirectionalLight::<S>::new(
        towards_light,
        LightColors::new(d.ambient, d.diffuse, d.specular).unwrap(),
    )
    .unwrap();
    let obj = &scene.objects[0];
    let lighting = fixshade::lighting::Lighting::<S, _, M>::new(
        [light],
        fixshade::material::Material::new(&obj.material).unwrap(),
    )
    .with_global_ambient(fixshade::color::Rgb::from_f32(scene.global_ambient));
    let mut fb = SliceFramebuffer::new(pixels, scene.width, scene.height).unwrap();
    let mut db = DepthBuffer::new(depth, scene.width).unwrap();
    let mut s = fixshade::shade::Shader::new(
        fixshade::shade::IncrementalPhongShading,
        &lighting,
        fixshade::shade::Linear,
    );
    let o = fixshade::raster::RasterOptions {
        cull: fixshade::raster::Cull::Back,
        ..fixshade::raster::RasterOptions::default()
    };
    prepared
        .iter()
        .map(|t| {
            let sv = t.each_ref().map(|v| {
                fixshade::shade::ShadeVertex::<S>::new(
                    [v.screen.x, v.screen.y],
                    v.screen.z,
                    v.screen.inv_w,
                    v.pos,
                    v.normal,
                )
            });
            render::ok(s.draw(&mut fb, Some(&mut db), &sv, &o)).pixels as u64
        })
        .sum()
}

/// `IncrementalPhong` (directional light sets, every tier but Q30).
fn measure_inc<S: fixshade::shade::IncrementalTier>(key: &'static str, rows: &mut Vec<Row>) {
    use fixshade::lighting::{BlinnPhong, Lambert, Phong};
    for lights in [LightSet::DirDiffuse, LightSet::DirBlinn, LightSet::DirPhong] {
        let scene = config_scene(lights, Mode::Phong);
        let prepared = prepare(&scene);
        let n = (scene.width * scene.height) as usize;
        let reference = render_reference(&scene);
        fn draw<S: fixshade::shade::IncrementalTier, C: fixshade::color::OutputColor + Default>(
            lights: LightSet,
            scene: &render::Scene,
            prepared: &[[render::Vert; 3]],
            pixels: &mut [C],
            depth: &mut [u16],
        ) -> u64 {
            match lights {
                LightSet::DirDiffuse => draw_inc::<S, Lambert, C>(scene, prepared, pixels, depth),
                LightSet::DirBlinn => draw_inc::<S, BlinnPhong, C>(scene, prepared, pixels, depth),
                _ => draw_inc::<S, Phong, C>(scene, prepared, pixels, depth),
            }
        }
        let mut rgb888 = vec![Rgb888::default(); n];
        draw::<S, Rgb888>(
            lights,
            &scene,
            &prepared[0],
            &mut rgb888,
            &mut vec![u16::MAX; n],
        );
        let mut rgb565 = vec![Rgb565::default(); n];
        let mut times = Vec::with_capacity(RUNS);
        let mut shaded = 0;
        for _ in 0..RUNS {
            let mut depth = vec![u16::MAX; n];
            let t = Instant::now();
            shaded = draw::<S, Rgb565>(lights, &scene, &prepared[0], &mut rgb565, &mut depth);
            times.push(t.elapsed().as_secs_f64());
            std::hint::black_box(&rgb565);
        }
        times.sort_by(f64::total_cmp);
        rows.push(Row {
            tier: key,
            mode: "phong_inc",
            lights,
            diff: compare(&rgb888, &rgb565, &reference),
            ns_per_pixel: times[RUNS / 2] * 1e9 / shaded.max(1) as f64,
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
    measure_inc::<Q14<1>>("q14_1", &mut rows);
    measure_inc::<Q14<2>>("q14_2", &mut rows);
    measure_inc::<f32>("f32", &mut rows);
    measure_inc::<F32Fast<2>>("f32fast", &mut rows);
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
