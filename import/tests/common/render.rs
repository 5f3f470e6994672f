//! The one place that calls fixshade's renderer (its API is being
//! refactored: keep this small): a mesh, optionally textured, lit by one
//! directional Blinn-Phong light in perspective, into a `side × side` frame,
//! as firmware draws it (a `MeshDraw`, one `DirectionalLight` in `Q14<2>`).

use fixshade::camera::{Camera, Mat4, MeshTransform, Perspective, Viewport};
use fixshade::mesh::Mesh;
use fixshade::prelude::*;
use fixshade::render::{bins_len, CachedVertex, Carry, FullFrame, Layout, MeshDraw, MeshMemory};
use fixshade::shade::Kernel;
use fixshade::texture::{Filter, Texture};

/// The background colour.
pub const BG: Rgb888 = Rgb888::new(20, 22, 30);

/// Renders `mesh` (positions with `frac` bits) seen from 4.5 units away,
/// turned by `model`, as RGB rows from the top: Gouraud shading, textured
/// (`GL_MODULATE`, bilinear) when a texture is given.
pub fn render(
    mesh: Mesh<'static>,
    texture: Option<Texture<'static>>,
    model: &Mat4,
    side: u32,
) -> Vec<Rgb888> {
    let camera = Camera::perspective(
        0.62,
        1.0,
        0.5,
        20.0,
        Viewport::new(0, 0, side as i32, side as i32).unwrap(),
    )
    .unwrap()
    .with_view(Mat4::translate([0.0, 0.0, -4.5]));
    let t = camera.mesh_transform(model, mesh.frac()).unwrap();
    let light = DirectionalLight::<Q14<2>>::white([-0.4, 0.5, 0.8]).unwrap();
    let white = MaterialDesc::classic([1.0, 1.0, 1.0], AmbientSource::Object, 0.15, 0.8, 0.4, 40.0);
    let lighting =
        Lighting::<Q14<2>, _, BlinnPhong>::new(light, Material::new(&white).unwrap()).eye_space();
    match texture {
        Some(tex) => frame(
            mesh,
            &t,
            Shader::<_, _, _, Rgb888>::new(
                GouraudShading.textured(tex, Filter::Bilinear),
                &lighting,
                Linear,
            ),
            side,
        ),
        None => frame(
            mesh,
            &t,
            Shader::<_, _, _, Rgb888>::new(GouraudShading, &lighting, Linear),
            side,
        ),
    }
}

fn frame<K: Kernel<Color = Rgb888>>(
    mesh: Mesh<'_>,
    t: &MeshTransform<Perspective>,
    kernel: K,
    side: u32,
) -> Vec<Rgb888> {
    let mut verts = vec![CachedVertex::<K::Vertex>::default(); mesh.vertex_count()];
    let mut bins = vec![0u16; bins_len(mesh.triangle_count(), 1)];
    let mut carry = vec![Carry::default(); 2 * mesh.triangle_count()];
    let memory = MeshMemory {
        vertices: &mut verts,
        bins: &mut bins,
        carry: &mut carry,
    };
    let mut draw =
        MeshDraw::new(Layout::full(side, side).unwrap(), mesh, t, kernel, memory).unwrap();
    let n = (side * side) as usize;
    let (mut color, mut depth) = (vec![BG; n], vec![0u16; n]);
    FullFrame::new(side, side, &mut color, Some(&mut depth))
        .unwrap()
        .render(BG, &mut [&mut draw])
        .unwrap();
    color
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
