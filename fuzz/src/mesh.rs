//! The mesh renderer with any small mesh (issue 21, item 7): vertices, normals
//! and triangles from the bytes (indices valid by construction, positions and
//! normals any `i16`, any fraction bits), an orthographic or perspective camera
//! in any pose, any frame size, band height, culling, with or without a depth
//! buffer, through several shading modes (flat, Gouraud, Phong, incremental
//! and quadratic Phong; Q14, Q30 and f32). No panic, no wrap (overflow checks
//! on), and the frame drawn in bands is the whole frame bit for bit.

use super::{frames, FrameSpec, Input};
use embedded_graphics_core::pixelcolor::Rgb565;
use fixshade::camera::Viewport;
use fixshade::camera::{Camera, MeshTransform, Projection};
use fixshade::color::Linear;
use fixshade::lighting::DirectionalLight;
use fixshade::lighting::Material;
use fixshade::lighting::{BlinnPhong, Lambert, Lighting, Phong};
use fixshade::mesh::Mesh;
use fixshade::num::Mat4;
use fixshade::num::{Q14, Q30};
use fixshade::raster::Cull;
use fixshade::shade::{
    FlatShading, GouraudShading, IncrementalPhongShading, Kernel, PhongShading,
    QuadraticPhongShading, Shader,
};
use fixshade::standard;

/// A position coordinate: small (a few units at the mesh's fraction bits)
/// most of the time, any `i16` else.
fn coord(inp: &mut Input) -> i16 {
    match inp.u8() % 4 {
        0 => inp.i16(),
        _ => i16::from(inp.u8() as i8) * 64,
    }
}

/// A pose: rotations, a translation, a scale.
fn matrix(inp: &mut Input) -> Mat4 {
    let r = Mat4::rotate_x(inp.f32())
        .mul(&Mat4::rotate_y(inp.f32()))
        .mul(&Mat4::rotate_z(inp.f32()));
    let s = match inp.u8() % 4 {
        0 => inp.f3(),
        _ => [1.0; 3],
    };
    Mat4::translate(inp.f3()).mul(&r).mul(&Mat4::scale(s))
}

/// Draws with every kernel of the run and compares whole frame and bands.
fn check<K: Kernel<Color = Rgb565> + Copy, P: Projection>(
    mesh: Mesh<'_>,
    t: &MeshTransform<P>,
    kernel: K,
    spec: &FrameSpec,
) {
    if let Some(f) = frames(mesh, t, kernel, spec) {
        assert!(f.full == f.banded, "bands differ from the whole frame");
    }
}

fn shade_all<P: Projection>(
    inp: &mut Input,
    mesh: Mesh<'_>,
    t: &MeshTransform<P>,
    spec: &FrameSpec,
) {
    let mat = Material::new(&standard::material()).unwrap();
    let dir = [inp.f32(), inp.f32(), 1.0];
    let l14 = DirectionalLight::<Q14>::white(dir).unwrap_or(standard::light::<Q14>().unwrap());
    let l30 = DirectionalLight::<Q30>::white(dir).unwrap_or(standard::light::<Q30>().unwrap());
    let lf = DirectionalLight::<f32>::white(dir).unwrap_or(standard::light::<f32>().unwrap());
    let blinn14 = Lighting::<Q14, _, BlinnPhong>::new([l14], mat).eye_space();
    let lambert14 = Lighting::<Q14, _, Lambert>::new([l14], mat).eye_space();
    let phong30 =
        Lighting::<Q30, _, Phong>::new([l30], Material::new(&standard::material()).unwrap())
            .eye_space();
    let blinnf =
        Lighting::<f32, _, BlinnPhong>::new([lf], Material::new(&standard::material()).unwrap())
            .eye_space();
    match inp.u8() % 6 {
        0 => check(
            mesh,
            t,
            Shader::<_, _, _, Rgb565>::new(FlatShading, &lambert14, Linear),
            spec,
        ),
        1 => check(
            mesh,
            t,
            Shader::<_, _, _, Rgb565>::new(GouraudShading, &blinn14, Linear),
            spec,
        ),
        2 => check(
            mesh,
            t,
            Shader::<_, _, _, Rgb565>::new(PhongShading, &phong30, Linear),
            spec,
        ),
        3 => check(
            mesh,
            t,
            Shader::<_, _, _, Rgb565>::new(IncrementalPhongShading, &blinn14, Linear),
            spec,
        ),
        4 => check(
            mesh,
            t,
            Shader::<_, _, _, Rgb565>::new(QuadraticPhongShading, &blinnf, Linear),
            spec,
        ),
        _ => check(
            mesh,
            t,
            Shader::<_, _, _, Rgb565>::new(QuadraticPhongShading, &blinn14, Linear),
            spec,
        ),
    }
}

/// One input of the fuzz target.
pub fn run(data: &[u8]) {
    let mut inp = Input(data);
    let nv = 3 + usize::from(inp.u8() % 14);
    let positions: Vec<[i16; 3]> = (0..nv)
        .map(|_| [coord(&mut inp), coord(&mut inp), coord(&mut inp)])
        .collect();
    let normals: Vec<[i16; 3]> = (0..nv).map(|_| [inp.i16(), inp.i16(), inp.i16()]).collect();
    let nt = 1 + usize::from(inp.u8() % 24);
    let tris: Vec<[u16; 3]> = (0..nt)
        .map(|_| [0; 3].map(|_: u16| (usize::from(inp.u8()) % nv) as u16))
        .collect();
    let frac = inp.u8() % 16;
    let Ok(mesh) = Mesh::new(&positions, &normals, &tris, frac) else {
        return;
    };
    let size = 4 + u32::from(inp.u8() % 44);
    let height = 1 + u32::from(inp.u8() % 40);
    let spec = FrameSpec {
        width: size,
        height,
        band_rows: 1 + u32::from(inp.u8()) % height,
        depth: inp.flag(),
        cull: [Cull::None, Cull::Back, Cull::Front][usize::from(inp.u8() % 3)],
        refine: None,
    };
    let Ok(vp) = Viewport::new(0, 0, size, height) else {
        return;
    };
    let model = matrix(&mut inp);
    let view = matrix(&mut inp);
    if inp.flag() {
        let e = inp.f32();
        let Ok(cam) = Camera::orthographic(-e, e, -e, e, inp.f32(), inp.f32(), vp) else {
            return;
        };
        if let Ok(t) = cam.with_view(view).mesh_transform(&model, frac) {
            shade_all(&mut inp, mesh, &t, &spec);
        }
    } else {
        let Ok(cam) = Camera::perspective(inp.f32(), inp.f32(), inp.f32(), inp.f32(), vp) else {
            return;
        };
        if let Ok(t) = cam.with_view(view).mesh_transform(&model, frac) {
            shade_all(&mut inp, mesh, &t, &spec);
        }
    }
}
