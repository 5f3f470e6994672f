//! The surface-detail scenes of issue 13 (seed 003, last third), rendered by
//! the mesh renderer into side-by-side panels: silhouette refinement, a
//! normal map baked from a high-poly mesh, base / bump / displacement, and
//! texture mapping.
//!
//! Lit by one `DirectionalLight` in `Q14<2>` (as firmware writes it):
//! `IncrementalPhongShading` draws it per pixel,
//! `IncrementalPhongShading.normal_mapped` with the baked normal map and
//! `PhongShading.normal_mapped` (the general kernel) with the bump map.

#![allow(dead_code)]

use super::surface::{self as sf, HostMesh};
use embedded_graphics::pixelcolor::Rgb888;
use fixshade::camera::{Camera, MeshTransform, Perspective, Viewport};
use fixshade::framebuffer::{FullFrame, Layout};
use fixshade::mesh::{
    displace, textured_sphere_counts, to_compact, uv_sphere_counts, Mesh, MeshData,
    TexturedMeshData, TEXCOORD_FRAC,
};
use fixshade::num::Mat4;
use fixshade::prelude::*;
use fixshade::render::refine::RefineBuffers;
use fixshade::render::{bins_len, CachedVertex, Carry, MeshDraw, MeshMemory};
use fixshade::shade::{IncrementalPhongShading, Kernel, PhongShading};
use fixshade::texture::NormalMap;
use fixshade::texture::{Filter, Texels, Texture, Wrap};

/// Side of a panel in pixels.
pub const SIDE: u32 = 240;
const BG: Rgb888 = Rgb888::new(24, 26, 32);

pub struct Image {
    pub name: &'static str,
    pub title: &'static str,
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Rgb888>,
    pub notes: Vec<String>,
}

const COARSE: (usize, usize) = uv_sphere_counts(16, 24);
static COARSE_SPHERE: MeshData<{ COARSE.0 }, { COARSE.1 }> = MeshData::uv_sphere(16, 24, 14);
const LOW: (usize, usize) = textured_sphere_counts(16, 24);
static LOW_SPHERE: TexturedMeshData<{ LOW.0 }, { LOW.1 }> = TexturedMeshData::uv_sphere(16, 24, 14);

fn camera(side: u32, distance: f32) -> Camera<Perspective> {
    Camera::perspective(
        0.62,
        1.0,
        0.5,
        20.0,
        Viewport::new(0, 0, side, side).unwrap(),
    )
    .unwrap()
    .with_view(Mat4::translate([0.0, 0.0, -distance]))
}

fn model() -> Mat4 {
    Mat4::rotate_x(0.35).mul(&Mat4::rotate_y(-0.5))
}

fn material(color: [f32; 3], ks: f32, n: f32) -> MaterialDesc {
    MaterialDesc::classic(color, AmbientSource::Object, 0.12, 0.8, ks, n)
}

fn key_light() -> DirectionalLight<Q14<2>> {
    DirectionalLight::white([-0.5, 0.6, 0.65]).unwrap()
}

/// Renders one mesh into a `SIDE × SIDE` panel through the mesh renderer.
fn panel<K: Kernel<Color = Rgb888>>(
    mesh: Mesh<'_>,
    t: &MeshTransform<Perspective>,
    k: K,
) -> Vec<Rgb888> {
    let layout = Layout::full(SIDE, SIDE).unwrap();
    let mut verts = vec![CachedVertex::<K::Vertex>::default(); mesh.vertex_count()];
    let mut bins = vec![0u16; bins_len(mesh.triangle_count(), 1)];
    let mut carry = vec![Carry::default(); 2 * mesh.triangle_count()];
    let mut draw = MeshDraw::new(
        layout,
        mesh,
        t,
        k,
        MeshMemory {
            vertices: &mut verts,
            bins: &mut bins,
            carry: &mut carry,
        },
        DrawOptions::default(),
    )
    .unwrap();
    let n = (SIDE * SIDE) as usize;
    let (mut color, mut depth) = (vec![BG; n], vec![0u16; n]);
    FullFrame::new(SIDE, SIDE, &mut color, Some(&mut depth))
        .unwrap()
        .render(BG, &mut [&mut draw])
        .unwrap();
    color
}

fn frame_of(panels: Vec<Vec<Rgb888>>) -> (u32, u32, Vec<Rgb888>) {
    let p: Vec<(u32, u32, Vec<Rgb888>)> = panels.into_iter().map(|p| (SIDE, SIDE, p)).collect();
    sf::hcat(&p)
}

/// Converts a host mesh (f64) to the compact format: owned arrays.
pub struct Compact {
    pub pos: Vec<[i16; 3]>,
    pub nrm: Vec<[i16; 3]>,
    pub uv: Vec<[i16; 2]>,
    pub tris: Vec<[u16; 3]>,
}

impl Compact {
    pub fn from_host(m: &HostMesh) -> Compact {
        let f = |v: [f64; 3]| v.map(|c| c as f32);
        let pos32: Vec<[f32; 3]> = m.pos.iter().map(|&p| f(p)).collect();
        let nrm32: Vec<[f32; 3]> = m.nrm.iter().map(|&p| f(p)).collect();
        let mut pos = vec![[0i16; 3]; pos32.len()];
        let mut nrm = vec![[0i16; 3]; pos32.len()];
        to_compact(&pos32, &nrm32, 13, &mut pos, &mut nrm).unwrap();
        let q = |x: f64| (x * f64::from(1u32 << TEXCOORD_FRAC)).round() as i16;
        Compact {
            pos,
            nrm,
            uv: m.uv.iter().map(|u| [q(u[0]), q(u[1])]).collect(),
            tris: m.tris.clone(),
        }
    }

    pub fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.pos, &self.nrm, &self.tris, 13)
            .unwrap()
            .with_texcoords(&self.uv)
            .unwrap()
    }
}

/// The standard 24 × 16 sphere without and with silhouette refinement, drawn
/// by `cam`.
fn silhouette_pair(cam: &Camera<Perspective>) -> (Vec<Rgb888>, Vec<Rgb888>, String) {
    let mesh = COARSE_SPHERE.mesh();
    let t = cam.mesh_transform(&model(), COARSE_SPHERE.frac).unwrap();
    let lighting = Lighting::<Q14<2>, _, BlinnPhong>::new(
        [key_light()],
        Material::new(&material([0.85, 0.35, 0.25], 0.5, 40.0)).unwrap(),
    )
    .eye_space();
    let shader = || Shader::<_, _, _, Rgb888>::new(IncrementalPhongShading, &lighting, Linear);
    let plain = panel(mesh, &t, shader());
    let layout = Layout::full(SIDE, SIDE).unwrap();
    let extra = 1024;
    let mut verts = vec![CachedVertex::<[i16; 3]>::default(); mesh.vertex_count()];
    let mut bins = vec![0u16; bins_len(mesh.triangle_count() + extra, 1)];
    let mut carry = vec![Carry::default(); 2 * (mesh.triangle_count() + extra)];
    let mut refine: Box<RefineBuffers<[i16; 3], { COARSE.0 }, 512, 1024>> = Box::default();
    let mut draw = MeshDraw::new(
        layout,
        mesh,
        &t,
        shader(),
        MeshMemory {
            vertices: &mut verts,
            bins: &mut bins,
            carry: &mut carry,
        },
        DrawOptions::default().with_refine(refine.refine(0)),
    )
    .unwrap();
    let stats = draw.refine_stats();
    let n = (SIDE * SIDE) as usize;
    let (mut color, mut depth) = (vec![BG; n], vec![0u16; n]);
    FullFrame::new(SIDE, SIDE, &mut color, Some(&mut depth))
        .unwrap()
        .render(BG, &mut [&mut draw])
        .unwrap();
    (plain, color, format!("{stats:?}"))
}

/// Silhouette refinement: the standard 24 × 16 sphere without and with it,
/// whole and its upper-left outline magnified.
pub fn silhouette() -> Image {
    let (a, b, stats) = silhouette_pair(&camera(SIDE, 3.6));
    // a narrow field of view on the upper-left limb
    let zoom = Camera::perspective(
        0.22,
        1.0,
        0.5,
        20.0,
        Viewport::new(0, 0, SIDE, SIDE).unwrap(),
    )
    .unwrap()
    .with_view(Mat4::translate([0.62, -0.62, -3.6]));
    let (c, d, _) = silhouette_pair(&zoom);
    let (width, height, pixels) = frame_of(vec![a, b, c, d]);
    Image {
        name: "surface_silhouette",
        title: "the 24 × 16 sphere (720 triangles): plain, with silhouette refinement; the same outline magnified",
        width,
        height,
        pixels,
        notes: vec![format!("refinement (whole view): {stats}")],
    }
}

/// The height field as an 8-bit map, `2^wl × 2^hl` texels.
fn height_map(wl: u8, hl: u8) -> Vec<u8> {
    let (w, h) = (1usize << wl, 1usize << hl);
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let (u, v) = ((x as f64 + 0.5) / w as f64, (y as f64 + 0.5) / h as f64);
            out.push((sf::tiles(u, v) * 255.0).round() as u8);
        }
    }
    out
}

/// A normal map of the low-poly sphere baked from the high-poly displaced one,
/// next to both.
pub fn normal_map() -> Image {
    const AMP: f64 = 0.035;
    let high = sf::displaced_sphere(160, 200, AMP, sf::tiles);
    let high_c = Compact::from_host(&high);
    let baked: Vec<[i16; 3]> = sf::bake_normal_map(&high, (512, 256))
        .into_iter()
        .map(|n| NormalMap::unit_texel(n.map(|c| c as f32)).unwrap())
        .collect();
    let map = NormalMap::new(&baked, 9, 8, Wrap::Repeat).unwrap();
    let cam = camera(SIDE, 3.6);
    let lighting = Lighting::<Q14<2>, _, BlinnPhong>::new(
        [key_light()],
        Material::new(&material([0.75, 0.72, 0.68], 0.45, 30.0)).unwrap(),
    )
    .eye_space();
    let low = LOW_SPHERE.mesh();
    let t_low = cam.mesh_transform(&model(), LOW_SPHERE.frac).unwrap();
    let t_high = cam.mesh_transform(&model(), 13).unwrap();
    let a = panel(
        low,
        &t_low,
        Shader::<_, _, _, Rgb888>::new(IncrementalPhongShading, &lighting, Linear),
    );
    let b = panel(
        low,
        &t_low,
        Shader::<_, _, _, Rgb888>::new(
            IncrementalPhongShading.normal_mapped(map),
            &lighting,
            Linear,
        ),
    );
    let c = panel(
        high_c.mesh(),
        &t_high,
        Shader::<_, _, _, Rgb888>::new(IncrementalPhongShading, &lighting, Linear),
    );
    let (width, height, pixels) = frame_of(vec![a, b, c]);
    Image {
        name: "surface_normal_map",
        title: "720 triangles; the same with a normal map baked from the high-poly mesh; the high-poly mesh (64 k triangles)",
        width,
        height,
        pixels,
        notes: vec![format!(
            "low-poly {} triangles, high-poly {} triangles, normal map 512 × 256 (Q14, IncrementalPhongShading.normal_mapped)",
            low.triangle_count(),
            high_c.tris.len()
        )],
    }
}

/// Base model, bump mapping, displacement mapping of the same sphere.
pub fn bump_displacement() -> Image {
    const WL: u8 = 9;
    const HL: u8 = 8;
    let heights = height_map(WL, HL);
    let mut bumps = vec![[0i16; 3]; heights.len()];
    NormalMap::from_bump(&heights, WL, HL, Wrap::Repeat, 0.016, &mut bumps).unwrap();
    let map = NormalMap::new(&bumps, WL, HL, Wrap::Repeat).unwrap();
    // a dense textured sphere for the displacement
    const D: (usize, usize) = textured_sphere_counts(96, 192);
    let dense: Box<TexturedMeshData<{ D.0 }, { D.1 }>> =
        Box::new(TexturedMeshData::uv_sphere(96, 192, 14));
    let dmesh = dense.mesh();
    let htex = Texture::new(Texels::Gray8(&heights), WL, HL, Wrap::Repeat).unwrap();
    let n = dmesh.vertex_count();
    let (mut weld, mut scratch) = (vec![0u16; n], vec![[0f32; 3]; n]);
    let (mut p32, mut n32) = (vec![[0f32; 3]; n], vec![[0f32; 3]; n]);
    displace(
        &dmesh,
        &htex,
        0.05,
        &mut weld,
        &mut scratch,
        &mut p32,
        &mut n32,
    )
    .unwrap();
    let (mut pos, mut nrm) = (vec![[0i16; 3]; n], vec![[0i16; 3]; n]);
    to_compact(&p32, &n32, 13, &mut pos, &mut nrm).unwrap();
    let displaced = Mesh::new(&pos, &nrm, dmesh.triangles(), 13).unwrap();
    let cam = camera(SIDE, 3.6);
    let lighting = Lighting::<Q14<2>, _, BlinnPhong>::new(
        [key_light()],
        Material::new(&material([0.35, 0.55, 0.8], 0.4, 30.0)).unwrap(),
    )
    .eye_space();
    let low = LOW_SPHERE.mesh();
    let t_low = cam.mesh_transform(&model(), LOW_SPHERE.frac).unwrap();
    let t_d = cam.mesh_transform(&model(), 13).unwrap();
    let a = panel(
        low,
        &t_low,
        Shader::<_, _, _, Rgb888>::new(IncrementalPhongShading, &lighting, Linear),
    );
    let b = panel(
        low,
        &t_low,
        Shader::<_, _, _, Rgb888>::new(PhongShading.normal_mapped(map), &lighting, Linear),
    );
    let c = panel(
        displaced,
        &t_d,
        Shader::<_, _, _, Rgb888>::new(IncrementalPhongShading, &lighting, Linear),
    );
    let (width, height, pixels) = frame_of(vec![a, b, c]);
    Image {
        name: "surface_bump_displacement",
        title: "base model; bump mapping (normals from the height map); displacement mapping (vertices moved by it)",
        width,
        height,
        pixels,
        notes: vec![format!(
            "base and bump: {} triangles; displaced: {} triangles",
            low.triangle_count(),
            dmesh.triangle_count()
        )],
    }
}

/// A textured, lit sphere and a textured floor in perspective.
pub fn textured() -> Image {
    // textures live in flash in firmware: leak the host copy (`'static`)
    let texels: &'static [u16] = Box::leak(
        sf::tile_texture(256, 128)
            .into_iter()
            .map(sf::rgb565)
            .collect::<Vec<u16>>()
            .into_boxed_slice(),
    );
    let tex = Texture::new(Texels::Rgb565(texels), 8, 7, Wrap::Repeat).unwrap();
    let cam = camera(SIDE, 3.6);
    let lighting = Lighting::<Q14<2>, _, BlinnPhong>::new(
        key_light(),
        Material::new(&material([1.0, 1.0, 1.0], 0.6, 40.0)).unwrap(),
    )
    .eye_space();
    let low = LOW_SPHERE.mesh();
    let t = cam.mesh_transform(&model(), LOW_SPHERE.frac).unwrap();
    let shader =
        |f| Shader::<_, _, _, Rgb888>::new(GouraudShading.textured(tex, f), &lighting, Linear);
    let a = panel(low, &t, shader(Filter::Nearest));
    let b = panel(low, &t, shader(Filter::Bilinear));
    // a floor receding in perspective, the texture repeated 2 × 4 times
    const G: usize = 8;
    let mut pos = Vec::new();
    let mut nrm = Vec::new();
    let mut uv = Vec::new();
    for i in 0..=G {
        for j in 0..=G {
            let (x, y) = (j as f64 / G as f64, i as f64 / G as f64);
            pos.push([
                ((2.0 * x - 1.0) * 8192.0) as i16,
                ((1.0 - 2.0 * y) * 8192.0) as i16,
                0,
            ]);
            nrm.push([0, 0, 1 << 14]);
            uv.push([(2.0 * x * 4096.0) as i16, (4.0 * y * 4096.0) as i16]);
        }
    }
    let mut tris = Vec::new();
    for i in 0..G {
        for j in 0..G {
            let (a, b) = ((i * (G + 1) + j) as u16, (i * (G + 1) + j + 1) as u16);
            let (c, d) = (a + (G + 1) as u16, b + (G + 1) as u16);
            tris.push([a, c, b]);
            tris.push([b, c, d]);
        }
    }
    let floor = Mesh::new(&pos, &nrm, &tris, 13)
        .unwrap()
        .with_texcoords(&uv)
        .unwrap();
    let floor_model = Mat4::translate([0.0, -0.7, 1.2])
        .mul(&Mat4::rotate_x(-1.3))
        .mul(&Mat4::scale([1.6, 3.5, 1.0]));
    let tf = cam.mesh_transform(&floor_model, 13).unwrap();
    let checks: &'static [u16] = Box::leak(
        sf::checker_texture(64, 64)
            .into_iter()
            .map(sf::rgb565)
            .collect::<Vec<u16>>()
            .into_boxed_slice(),
    );
    let floor_tex = Texture::new(Texels::Rgb565(checks), 6, 6, Wrap::Repeat).unwrap();
    let c = panel(
        floor,
        &tf,
        Shader::<_, _, _, Rgb888>::new(
            GouraudShading.textured(floor_tex, Filter::Bilinear),
            &lighting,
            Linear,
        ),
    );
    let (width, height, pixels) = frame_of(vec![a, b, c]);
    Image {
        name: "surface_textured",
        title: "texture mapping (GL_MODULATE, separate specular): nearest, bilinear; a floor in perspective (bilinear)",
        width,
        height,
        pixels,
        notes: vec![],
    }
}

pub fn all() -> Vec<Image> {
    vec![silhouette(), normal_map(), bump_displacement(), textured()]
}
