//! The one place that calls fixshade's renderer (its API is being
//! refactored: keep this small): a mesh, optionally textured, lit by one
//! directional Blinn-Phong light in perspective, into a `side × side` frame,
//! as firmware draws it (a `MeshDraw`, one `DirectionalLight` in `Q14<2>`).

use fixshade::camera::{Camera, MeshTransform, Perspective, Viewport};
use fixshade::framebuffer::{DrawBand, FullFrame, Layout};
use fixshade::mesh::Mesh;
use fixshade::num::Mat4;
use fixshade::prelude::*;
use fixshade::render::{bins_len, CachedVertex, Carry, MeshDraw, MeshMemory};
use fixshade::shade::Kernel;
use fixshade::texture::{Filter, Texture};

/// The background colour.
pub const BG: Rgb888 = Rgb888::new(20, 22, 30);

/// A part as the generated `NAME_PARTS` lists it: mesh, material, texture.
pub type Part = (Mesh<'static>, MaterialDesc, Option<Texture<'static>>);

/// Renders `mesh` (positions with `frac` bits) seen from 4.5 units away,
/// turned by `model`, as RGB rows from the top: Gouraud shading, textured
/// (`GL_MODULATE`, bilinear) when a texture is given, a white material
/// (ka 0.15, kd 0.8, ks 0.4, n 40).
pub fn render(
    mesh: Mesh<'static>,
    texture: Option<Texture<'static>>,
    model: &Mat4,
    side: u32,
) -> Vec<Rgb888> {
    let white = MaterialDesc::classic([1.0, 1.0, 1.0], AmbientSource::Object, 0.15, 0.8, 0.4, 40.0);
    render_parts(&[(mesh, white, texture)], model, side)
}

/// Renders every part in one frame as [`render`] does one mesh, each with
/// its own material (one transform for all: the parts share `frac`).
pub fn render_parts(parts: &[Part], model: &Mat4, side: u32) -> Vec<Rgb888> {
    let camera = Camera::perspective(
        0.62,
        1.0,
        0.5,
        20.0,
        Viewport::new(0, 0, side, side).unwrap(),
    )
    .unwrap()
    .with_view(Mat4::translate([0.0, 0.0, -4.5]));
    let t = camera.mesh_transform(model, parts[0].0.frac()).unwrap();
    let light = DirectionalLight::<Q14<2>>::white([-0.4, 0.5, 0.8]).unwrap();
    let lightings: Vec<_> = parts
        .iter()
        .map(|p| {
            assert_eq!(p.0.frac(), parts[0].0.frac());
            Lighting::<Q14<2>, _, BlinnPhong>::new(light, Material::new(&p.1).unwrap()).eye_space()
        })
        .collect();
    let mut draws: Vec<Box<dyn DrawBand<Rgb888> + '_>> = parts
        .iter()
        .zip(&lightings)
        .map(|(&(mesh, _, texture), lighting)| match texture {
            Some(tex) => draw(
                mesh,
                &t,
                Shader::<_, _, _, Rgb888>::new(
                    GouraudShading.textured(tex, Filter::Bilinear),
                    lighting,
                    Linear,
                ),
                side,
            ),
            None => draw(
                mesh,
                &t,
                Shader::<_, _, _, Rgb888>::new(GouraudShading, lighting, Linear),
                side,
            ),
        })
        .collect();
    let mut items: Vec<&mut dyn DrawBand<Rgb888>> = draws
        .iter_mut()
        .map(|d| &mut **d as &mut dyn DrawBand<Rgb888>)
        .collect();
    let n = (side * side) as usize;
    let (mut color, mut depth) = (vec![BG; n], vec![0u16; n]);
    FullFrame::new(side, side, &mut color, Some(&mut depth))
        .unwrap()
        .render(BG, &mut items)
        .unwrap();
    drop(items);
    color
}

/// A `MeshDraw` of `mesh` over memory of its own (leaked: test code).
fn draw<'a, K: Kernel<Color = Rgb888> + 'a>(
    mesh: Mesh<'a>,
    t: &MeshTransform<Perspective>,
    kernel: K,
    side: u32,
) -> Box<dyn DrawBand<Rgb888> + 'a>
where
    K::Vertex: 'a,
{
    let memory = MeshMemory {
        vertices: vec![CachedVertex::<K::Vertex>::default(); mesh.vertex_count()].leak(),
        bins: vec![0u16; bins_len(mesh.triangle_count(), 1)].leak(),
        carry: vec![Carry::default(); 2 * mesh.triangle_count()].leak(),
    };
    Box::new(
        MeshDraw::new(
            Layout::full(side, side).unwrap(),
            mesh,
            t,
            kernel,
            memory,
            DrawOptions::default(),
        )
        .unwrap(),
    )
}

/// Writes RGB rows as a PNG.
pub fn write_png(path: &std::path::Path, side: u32, pixels: &[Rgb888]) {
    let file = std::fs::File::create(path).unwrap();
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), side, side);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().unwrap();
    let bytes: Vec<u8> = pixels.iter().flat_map(|p| [p.r(), p.g(), p.b()]).collect();
    w.write_image_data(&bytes).unwrap();
}
