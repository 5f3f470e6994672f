//! Lighting evaluation with arbitrary parameters in every tier: lights and
//! materials from any `f32` the constructors accept, any viewer and fog, any
//! point and normal (also the raw values the saturating conversions never
//! make). No panic, no wrap (overflow checks on), no NaN or infinite channel.
#![no_main]

use fixshade::color::Rgb;
use fixshade::lighting::Material;
use fixshade::lighting::{
    BlinnPhong, FogModel, Full, InfiniteViewer, Lambert, Lighting, LinearFog, LocalViewer, Model,
    NoFog, Phong, Viewer,
};
use fixshade::num::{point_from_f32, Point3, Vec3};
use fixshade::num::{F32Fast, Geo16, Scalar, Q14, Q30};
use fixshade_fuzz::{check_color, Input};
use libfuzzer_sys::fuzz_target;

fn shade<S: Scalar, M: Model, V: Viewer<S>, F: FogModel<S>>(
    inp: &mut Input,
    m: Material<S>,
    viewer: V,
    fog: F,
    p: &Point3<S>,
    n: Vec3<S>,
) {
    let lights = inp.lights::<S>();
    let amb = Rgb::splat(S::from_f32(inp.f32()));
    let lit = Lighting::<S, _, M>::new(lights, m)
        .with_global_ambient(amb)
        .with_viewer(viewer)
        .with_fog(fog);
    check_color(lit.shade(p, n), "shade");
    check_color(lit.shade_normalizing(p, n), "shade_normalizing");
}

fn tier<S: Scalar>(inp: &mut Input, raw: impl Fn(&mut Input) -> (Point3<S>, Vec3<S>)) {
    let Ok(m) = Material::<S>::new(&inp.material()) else {
        return;
    };
    let (p, n) = if inp.u8() & 1 == 0 {
        (point_from_f32::<S>(inp.f3()), Vec3::from_f32(inp.f3()))
    } else {
        raw(inp)
    };
    let fog = LinearFog::<S>::new(inp.f32(), inp.f32(), inp.f3());
    let eye = inp.f3();
    let model = inp.u8() % 4;
    macro_rules! all_models {
        ($v:expr, $f:expr) => {
            match model {
                0 => shade::<S, Full, _, _>(inp, m, $v, $f, &p, n),
                1 => shade::<S, Phong, _, _>(inp, m, $v, $f, &p, n),
                2 => shade::<S, BlinnPhong, _, _>(inp, m, $v, $f, &p, n),
                _ => shade::<S, Lambert, _, _>(inp, m, $v, $f, &p, n),
            }
        };
    }
    let infinite = InfiniteViewer::<S>::new(eye).unwrap_or_default();
    match (inp.u8() % 4, fog) {
        (0, _) => all_models!(infinite, NoFog),
        (1, Ok(f)) => all_models!(infinite, f),
        (2, _) => {
            if let Ok(v) = LocalViewer::<S>::new(eye) {
                all_models!(v, NoFog)
            }
        }
        (_, f) => {
            if let (Ok(v), Ok(f)) = (LocalViewer::<S>::new(eye), f) {
                all_models!(v, f)
            }
        }
    }
}

fn q14<const N: u8>(inp: &mut Input) -> (Point3<Q14<N>>, Vec3<Q14<N>>) {
    let g = |i: &mut Input| Geo16::from_bits(i.u32() as i32);
    let q = |i: &mut Input| Q14::<N>::from_raw(i.u32() as u16 as i16 as i32);
    (
        Vec3::new(g(inp), g(inp), g(inp)),
        Vec3::new(q(inp), q(inp), q(inp)),
    )
}

fn q30<const N: u8>(inp: &mut Input) -> (Point3<Q30<N>>, Vec3<Q30<N>>) {
    let g = |i: &mut Input| Geo16::from_bits(i.u32() as i32);
    let q = |i: &mut Input| Q30::<N>::from_raw(i.u32() as i32);
    (
        Vec3::new(g(inp), g(inp), g(inp)),
        Vec3::new(q(inp), q(inp), q(inp)),
    )
}

fn fast<const N: u8>(inp: &mut Input) -> (Point3<F32Fast<N>>, Vec3<F32Fast<N>>) {
    let f = |i: &mut Input| F32Fast::<N>(i.f32());
    (
        Vec3::new(inp.f32(), inp.f32(), inp.f32()),
        Vec3::new(f(inp), f(inp), f(inp)),
    )
}

fuzz_target!(|data: &[u8]| {
    let mut inp = Input(data);
    match inp.u8() % 6 {
        0 => tier::<Q14<1>>(&mut inp, q14::<1>),
        1 => tier::<Q14<2>>(&mut inp, q14::<2>),
        2 => tier::<Q30<3>>(&mut inp, q30::<3>),
        3 => tier::<f32>(&mut inp, |i| {
            (
                Vec3::new(i.f32(), i.f32(), i.f32()),
                Vec3::new(i.f32(), i.f32(), i.f32()),
            )
        }),
        4 => tier::<F32Fast<1>>(&mut inp, fast::<1>),
        _ => tier::<F32Fast<2>>(&mut inp, fast::<2>),
    }
});
