//! The `f32` constructors with any values: materials, lights, attenuation,
//! exponents, fog, viewers, colours, gamma tables, matrices, cameras, mesh
//! transforms and projections. Each returns a value or a typed error and never
//! panics or wraps (overflow checks on); what they accept lights finite
//! colours in every tier.
#![no_main]

use fixshade::camera::{Camera, Viewport};
use fixshade::color::{GammaTable, Rgb, Transfer};
use fixshade::lighting::{AnyLight, Attenuation, Material};
use fixshade::lighting::{Full, InfiniteViewer, Lighting, LinearFog, LocalViewer};
use fixshade::num::Mat4;
use fixshade::num::{point_from_f32, Vec3};
use fixshade::num::{Exponent, F32Fast, Scalar, Q14, Q30};
use fixshade_fuzz::{check_color, Input};
use libfuzzer_sys::fuzz_target;

fn tier<S: Scalar>(inp: &mut Input) {
    let m = Material::<S>::new(&inp.material());
    let l = AnyLight::<S>::new(&inp.light());
    let _ = Attenuation::new::<S>(inp.f32(), inp.f32(), inp.f32());
    let fog = LinearFog::<S>::new(inp.f32(), inp.f32(), inp.f3());
    let local = LocalViewer::<S>::new(inp.f3());
    let inf = InfiniteViewer::<S>::new(inp.f3());
    let c = Rgb::<S>::from_f32(inp.f3());
    check_color(c, "Rgb::from_f32");
    if let Ok(c) = Rgb::<S>::try_from_f32("c", inp.f3()) {
        check_color(c, "Rgb::try_from_f32");
    }
    let _ = Rgb::<S>::try_from_f32_signed("c", inp.f3());
    let (p, n) = (point_from_f32::<S>(inp.f3()), Vec3::<S>::from_f32(inp.f3()));
    if let (Ok(m), Ok(l)) = (m, l) {
        let lit = Lighting::<S, _, Full>::new([l], m).with_global_ambient_f32(inp.f3());
        check_color(lit.shade(&p, n), "shade");
        if let (Ok(v), Ok(f)) = (local, fog) {
            check_color(
                lit.with_viewer(v).with_fog(f).shade(&p, n),
                "local viewer + fog",
            );
        }
        if let Ok(v) = inf {
            check_color(
                lit.with_viewer(v).shade_normalizing(&p, n),
                "infinite viewer",
            );
        }
    }
}

fn geometry(inp: &mut Input) {
    let _ = Exponent::new("e", inp.f32());
    let _ = GammaTable::<256>::new(Transfer::Power(inp.f32()));
    let vp = Viewport::new(inp.i32(), inp.i32(), inp.u32(), inp.u32());
    let vp = vp.unwrap_or_else(|_| Viewport::new(0, 0, 64, 64).unwrap());
    let view = match inp.u8() % 5 {
        0 => Mat4::translate(inp.f3()),
        1 => Mat4::scale(inp.f3()),
        2 => Mat4::rotate_x(inp.f32()).mul(&Mat4::rotate_y(inp.f32())),
        3 => Mat4::look_at(inp.f3(), inp.f3(), inp.f3()).unwrap_or(Mat4::IDENTITY),
        _ => Mat4::rotate_z(inp.f32()),
    };
    let _ = view.normal_matrix();
    let _ = view.transform_point(inp.f3());
    let model = Mat4::translate(inp.f3()).mul(&Mat4::scale(inp.f3()));
    let frac = inp.u8() % 20;
    let raw = [inp.i32() as i16, inp.i32() as i16, inp.i32() as i16];
    if inp.u8() & 1 == 0 {
        let (a, b, c, d, e, f) = (
            inp.f32(),
            inp.f32(),
            inp.f32(),
            inp.f32(),
            inp.f32(),
            inp.f32(),
        );
        if let Ok(cam) = Camera::orthographic(a, b, c, d, e, f, vp) {
            if let Ok(t) = cam.with_view(view).mesh_transform(&model, frac) {
                let _ = t.project(raw);
            }
        }
    } else {
        let (a, b, c, d) = (inp.f32(), inp.f32(), inp.f32(), inp.f32());
        if let Ok(cam) = Camera::perspective(a, b, c, d, vp) {
            if let Ok(t) = cam.with_view(view).mesh_transform(&model, frac) {
                let _ = t.project(raw);
            }
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let mut inp = Input(data);
    match inp.u8() % 7 {
        0 => tier::<Q14<1>>(&mut inp),
        1 => tier::<Q14<2>>(&mut inp),
        2 => tier::<Q30<3>>(&mut inp),
        3 => tier::<f32>(&mut inp),
        4 => tier::<F32Fast<1>>(&mut inp),
        5 => tier::<F32Fast<2>>(&mut inp),
        _ => geometry(&mut inp),
    }
});
