//! Per-pixel modes composed with a colour texture and a normal map
//! (issue 18 item 4): `PhongShading.textured(…)`,
//! `PhongShading.textured(…)`, `….normal_mapped(map).textured(…)`,
//! through the mesh renderer. Neutral maps give the plain pixels; a texture
//! modulates the primary colour and leaves the specular alone.

use fixshade::mesh::{textured_sphere_counts, TexturedMeshData};
use fixshade::prelude::*;
use fixshade::render::{CachedVertex, MeshMemory};
use fixshade::shade::Kernel;
use fixshade::shade::PhongShading;
use fixshade::texture::{Filter, NormalMap, Texels, Texture, Wrap};

const N: (usize, usize) = textured_sphere_counts(12, 16);
static SPHERE: TexturedMeshData<{ N.0 }, { N.1 }> = TexturedMeshData::uv_sphere(12, 16, 14);
const W: u32 = 64;

/// The standard sphere (textured) drawn with `kernel` on a 64 × 64 frame.
fn draw<K: Kernel<Color = Rgb565>>(kernel: K) -> Vec<Rgb565> {
    let camera = Camera::orthographic(
        -1.2,
        1.2,
        -1.2,
        1.2,
        1.0,
        10.0,
        Viewport::new(0, 0, W, W).unwrap(),
    )
    .unwrap()
    .with_view(Mat4::translate([0.0, 0.0, -5.0]));
    let transform = camera
        .mesh_transform(&Mat4::rotate_y(0.4), SPHERE.frac)
        .unwrap();
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); N.0];
    let mut bins = vec![0u16; bins_len(N.1, 8)];
    let layout = Layout::full(W, W).unwrap();
    let mut draw = MeshDraw::new(
        layout,
        SPHERE.mesh(),
        &transform,
        kernel,
        MeshMemory {
            vertices: &mut cache,
            bins: &mut bins,
            carry: &mut [],
        },
        DrawOptions::default(),
    )
    .unwrap();
    let mut color = vec![Rgb565::BLACK; (W * W) as usize];
    let mut depth = vec![0u16; (W * W) as usize];
    let mut frame = FullFrame::new(W, W, &mut color, Some(&mut depth)).unwrap();
    frame.render(Rgb565::BLACK, &mut [&mut draw]).unwrap();
    color
}

static WHITE: [u16; 16] = [0xFFFF; 16];
static FLAT: [[i16; 3]; 4] = [NormalMap::FLAT; 4];

/// Asserts that `a` equals `b`, saying where and by how much not.
fn same(a: &[Rgb565], b: &[Rgb565], what: &str) {
    let diff: Vec<_> = a
        .iter()
        .zip(b)
        .enumerate()
        .filter(|(_, (x, y))| x != y)
        .collect();
    assert!(
        diff.is_empty(),
        "{what}: {} pixels differ, first {:?}",
        diff.len(),
        diff.first()
    );
}

/// Asserts that `a` is within one step of `b` in every channel.
fn near(a: &[Rgb565], b: &[Rgb565], what: &str) {
    for (x, y) in a.iter().zip(b) {
        let d = [
            x.r().abs_diff(y.r()),
            x.g().abs_diff(y.g()),
            x.b().abs_diff(y.b()),
        ];
        assert!(d.iter().all(|&d| d <= 1), "{what}: {x:?} vs {y:?}");
    }
}

fn white() -> Texture<'static> {
    Texture::new(Texels::Rgb565(&WHITE), 2, 2, Wrap::Repeat).unwrap()
}

fn flat() -> NormalMap<'static> {
    NormalMap::new(&FLAT, 1, 1, Wrap::Repeat).unwrap()
}

/// A flat normal map gives the plain per-pixel pixels exactly; a white
/// texture on a surface without specular light gives them within one
/// step (the lighting's primary part is encoded on its own: its sum
/// rounds apart from the plain colour's), and exactly the same pixels
/// with a flat map; `PhongShading` textured takes the general kernel.
#[test]
fn neutral_maps_give_the_plain_pixels() {
    let lighting = fixshade::standard::lambert::<Q14>().unwrap();
    let plain = draw(Shader::new(PhongShading, &lighting, Linear));
    assert!(plain.iter().filter(|&&c| c != Rgb565::BLACK).count() > 1500);
    let tex = draw(Shader::new(
        PhongShading.textured(white(), Filter::Nearest),
        &lighting,
        Linear,
    ));
    near(&tex, &plain, "textured");
    let white_tex = tex;
    let tex = draw(Shader::new(
        PhongShading.textured(white(), Filter::Bilinear),
        &lighting,
        Linear,
    ));
    same(&tex, &white_tex, "textured bilinear");
    let mapped = draw(Shader::new(
        PhongShading.normal_mapped(flat()),
        &lighting,
        Linear,
    ));
    same(&mapped, &plain, "mapped");
    let both = draw(Shader::new(
        PhongShading
            .normal_mapped(flat())
            .textured(white(), Filter::Nearest),
        &lighting,
        Linear,
    ));
    same(&both, &white_tex, "both");
}

/// A black texture leaves the specular light alone: textured Blinn-Phong
/// on black is the highlight, zero outside it, and never brighter than
/// the plain pixels.
#[test]
fn black_texture_keeps_the_specular() {
    static BLACK: [u16; 16] = [0; 16];
    let black = Texture::new(Texels::Rgb565(&BLACK), 2, 2, Wrap::Repeat).unwrap();
    let lighting = fixshade::standard::blinn::<Q14>().unwrap();
    let plain = draw(Shader::new(PhongShading, &lighting, Linear));
    let spec = draw(Shader::new(
        PhongShading.textured(black, Filter::Nearest),
        &lighting,
        Linear,
    ));
    let lit = spec.iter().filter(|&&c| c != Rgb565::BLACK).count();
    assert!(lit > 20 && lit < 1000, "{lit} pixels with a highlight");
    for (s, p) in spec.iter().zip(&plain) {
        assert!(s.r() <= p.r() && s.g() <= p.g() && s.b() <= p.b());
    }
}
