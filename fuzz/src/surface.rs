//! Surface detail with any parameters (issue 21, item 7), on small spheres
//! (texture-mapped: a seam of duplicated vertices; and seamless) in any
//! orientation, orthographic or perspective:
//!
//! - textures of any size (1 to 16 texels a side), wrap, filter, format
//!   (Rgb565, Gray8, a palette of any length with any indices) and texels,
//!   sampled at any coordinates and drawn with `GouraudShading.textured(..)`;
//! - normal maps of any `i16` texels: `NormalMap::new` accepts them or
//!   returns `NotUnit`, `normalize_texels` makes every non-zero map
//!   acceptable, and every accepted map is drawn by the fast and the general
//!   normal-mapping kernels;
//! - `displace` with any height texture and scale, then `to_compact`, drawn;
//! - silhouette refinement with any budget and threshold: on the closed
//!   spheres no pixel inside the outline is left uncovered (the frame with
//!   back faces culled covers what the frame without culling covers, away
//!   from the outline), whatever the budget.
//!
//! Every frame is drawn whole and in bands: the same pixels. No panic, no
//! wrap (overflow checks on).

use super::{frames, FrameSpec, Input};
use embedded_graphics_core::pixelcolor::Rgb565;
use fixshade::camera::Viewport;
use fixshade::camera::{Camera, MeshTransform, Projection};
use fixshade::color::Linear;
use fixshade::error::TextureError;
use fixshade::lighting::DirectionalLight;
use fixshade::lighting::Material;
use fixshade::lighting::{BlinnPhong, Lambert, Lighting, Viewed};
use fixshade::mesh::{
    displace, textured_sphere_counts, to_compact, uv_sphere_counts, Mesh, MeshData,
    TexturedMeshData,
};
use fixshade::num::Mat4;
use fixshade::num::Q14;
use fixshade::raster::Cull;
use fixshade::shade::{GouraudShading, IncrementalPhongShading, Kernel, PhongShading, Shader};
use fixshade::standard;
use fixshade::texture::NormalMap;
use fixshade::texture::{Filter, TexCoord, Texels, Texture, Wrap};
use std::collections::HashMap;
use std::sync::Mutex;

const TS: (usize, usize) = textured_sphere_counts(6, 8);
static SEAMED: TexturedMeshData<{ TS.0 }, { TS.1 }> = TexturedMeshData::uv_sphere(6, 8, 14);
const US: (usize, usize) = uv_sphere_counts(6, 8);
static SEAMLESS: MeshData<{ US.0 }, { US.1 }> = MeshData::uv_sphere(6, 8, 14);

/// Texel data for `'static` textures (the textured shader keeps its texture
/// for the program's life): each distinct content leaked once, so memory
/// grows with the distinct textures met, at most 512 bytes each.
static WORDS: Mutex<Option<HashMap<Vec<u16>, &'static [u16]>>> = Mutex::new(None);
static BYTES: Mutex<Option<HashMap<Vec<u8>, &'static [u8]>>> = Mutex::new(None);

fn interned<T: Clone + Eq + std::hash::Hash + 'static>(
    pool: &Mutex<Option<HashMap<Vec<T>, &'static [T]>>>,
    data: Vec<T>,
) -> &'static [T] {
    let mut g = pool.lock().unwrap_or_else(|e| e.into_inner());
    let map = g.get_or_insert_with(HashMap::new);
    if let Some(s) = map.get(&data) {
        return s;
    }
    let s: &'static [T] = Box::leak(data.clone().into_boxed_slice());
    map.insert(data, s);
    s
}

/// A frame spec and a camera: frame size, bands, depth, a pose.
struct View {
    spec: FrameSpec,
    model: Mat4,
    perspective: bool,
    size: u32,
}

fn view(inp: &mut Input) -> View {
    let size = 8 + u32::from(inp.u8() % 40);
    let model = Mat4::rotate_x(inp.f32())
        .mul(&Mat4::rotate_y(inp.f32()))
        .mul(&Mat4::rotate_z(inp.f32()));
    View {
        spec: FrameSpec {
            width: size,
            height: size,
            band_rows: 1 + u32::from(inp.u8()) % size,
            depth: inp.flag(),
            cull: Cull::Back,
            refine: None,
        },
        model,
        perspective: inp.flag(),
        size,
    }
}

/// Runs `f` with the transform of `v` for `mesh` (orthographic or
/// perspective); nothing for a typed error.
macro_rules! with_transform {
    ($v:expr, $mesh:expr, |$t:ident| $body:expr) => {{
        let vp = Viewport::new(0, 0, $v.size as u32, $v.size as u32).unwrap();
        if $v.perspective {
            let cam = Camera::perspective(0.8, 1.0, 0.5, 20.0, vp)
                .unwrap()
                .with_view(Mat4::translate([0.0, 0.0, -3.5]));
            if let Ok($t) = cam.mesh_transform(&$v.model, $mesh.frac()) {
                $body;
            }
        } else {
            let cam = Camera::orthographic(-1.2, 1.2, -1.2, 1.2, 1.0, 10.0, vp)
                .unwrap()
                .with_view(Mat4::translate([0.0, 0.0, -5.0]));
            if let Ok($t) = cam.mesh_transform(&$v.model, $mesh.frac()) {
                $body;
            }
        }
    }};
}

/// Whole frame = bands; returns the whole frame.
fn same<K: Kernel<Color = Rgb565> + Copy, P: Projection>(
    mesh: Mesh<'_>,
    t: &MeshTransform<P>,
    kernel: K,
    spec: &FrameSpec,
) -> Option<Vec<Rgb565>> {
    let f = frames(mesh, t, kernel, spec)?;
    assert!(f.full == f.banded, "bands differ from the whole frame");
    Some(f.full)
}

fn lighting() -> Viewed<Lighting<Q14, [DirectionalLight<Q14>; 1], BlinnPhong>> {
    Lighting::new(
        [standard::light::<Q14>().unwrap()],
        Material::new(&standard::material()).unwrap(),
    )
    .eye_space()
}

fn texture(inp: &mut Input) {
    let (lw, lh) = (inp.u8() % 5, inp.u8() % 5);
    let n = 1usize << (lw + lh);
    let wrap = if inp.flag() {
        Wrap::Repeat
    } else {
        Wrap::Clamp
    };
    let filter = if inp.flag() {
        Filter::Nearest
    } else {
        Filter::Bilinear
    };
    // the formats' data: Rgb565 words, Gray8 bytes or palette indices, palette
    let words: Vec<u16> = (0..n).map(|_| inp.i16() as u16).collect();
    let palette: Vec<u16> = (0..usize::from(inp.u8() % 17))
        .map(|_| inp.i16() as u16)
        .collect();
    let format = inp.u8() % 3;
    // the low bytes of the words: grey levels or palette indices
    let bytes = interned(&BYTES, words.iter().map(|&w| w as u8).collect());
    let words = interned(&WORDS, words);
    let palette = interned(&WORDS, palette);
    let texels = match format {
        0 => Texels::Rgb565(words),
        1 => Texels::Gray8(bytes),
        _ => Texels::Palette8 {
            indices: bytes,
            palette,
        },
    };
    let Ok(tex) = Texture::new(texels, lw, lh, wrap) else {
        return;
    };
    for _ in 0..4 {
        let c = TexCoord {
            u: inp.i32(),
            v: inp.i32(),
        };
        let _ = tex.sample(c, filter);
        let _ = tex.texel(inp.i32(), inp.i32());
    }
    let v = view(inp);
    let lit = lighting();
    let mesh = SEAMED.mesh();
    let kernel = Shader::<_, _, _, Rgb565>::new(GouraudShading.textured(tex, filter), &lit, Linear);
    with_transform!(v, mesh, |t| same(mesh, &t, kernel, &v.spec));
}

fn normal_map(inp: &mut Input) {
    let (lw, lh) = (inp.u8() % 4, inp.u8() % 4);
    let n = 1usize << (lw + lh);
    let wrap = if inp.flag() {
        Wrap::Repeat
    } else {
        Wrap::Clamp
    };
    let mut texels: Vec<[i16; 3]> = (0..n).map(|_| [inp.i16(), inp.i16(), inp.i16()]).collect();
    match NormalMap::new(&texels, lw, lh, wrap) {
        Ok(_) => {}
        Err(TextureError::NotUnit { .. }) => {
            if NormalMap::normalize_texels(&mut texels).is_err() {
                assert!(
                    texels.contains(&[0; 3]),
                    "normalize_texels refused a non-zero map"
                );
                return;
            }
        }
        Err(e) => panic!("{e}"),
    }
    let map = NormalMap::new(&texels, lw, lh, wrap).expect("normalised texels are unit normals");
    let v = view(inp);
    let mesh = SEAMED.mesh();
    // one directional light: `IncrementalPhongShading.normal_mapped` (the
    // fast kernel) for Blinn-Phong and Lambert, `PhongShading.normal_mapped`
    // (the general one) for Q14 and f32
    let l1 = Lighting::<Q14<1>, _, BlinnPhong>::new(
        [standard::light::<Q14<1>>().unwrap()],
        Material::new(&standard::material()).unwrap(),
    )
    .eye_space();
    let lam = Lighting::<Q14<1>, _, Lambert>::new(
        [standard::light::<Q14<1>>().unwrap()],
        Material::new(&standard::material()).unwrap(),
    )
    .eye_space();
    let lit = lighting();
    let lf = Lighting::<f32, _, BlinnPhong>::new(
        [standard::light::<f32>().unwrap()],
        Material::new(&standard::material()).unwrap(),
    )
    .eye_space();
    match inp.u8() % 4 {
        0 => with_transform!(v, mesh, |t| same(
            mesh,
            &t,
            Shader::<_, _, _, Rgb565>::new(IncrementalPhongShading.normal_mapped(map), &l1, Linear),
            &v.spec
        )),
        1 => with_transform!(v, mesh, |t| same(
            mesh,
            &t,
            Shader::<_, _, _, Rgb565>::new(
                IncrementalPhongShading.normal_mapped(map),
                &lam,
                Linear
            ),
            &v.spec
        )),
        2 => with_transform!(v, mesh, |t| same(
            mesh,
            &t,
            Shader::<_, _, _, Rgb565>::new(PhongShading.normal_mapped(map), &lit, Linear),
            &v.spec
        )),
        _ => with_transform!(v, mesh, |t| same(
            mesh,
            &t,
            Shader::<_, _, _, Rgb565>::new(PhongShading.normal_mapped(map), &lf, Linear),
            &v.spec
        )),
    }
}

fn displaced(inp: &mut Input) {
    let (lw, lh) = (inp.u8() % 5, inp.u8() % 5);
    let heights: Vec<u8> = (0..1usize << (lw + lh)).map(|_| inp.u8()).collect();
    let Ok(tex) = Texture::new(Texels::Gray8(&heights), lw, lh, Wrap::Repeat) else {
        return;
    };
    let scale = inp.f32();
    let mesh = SEAMED.mesh();
    let n = mesh.vertex_count();
    let (mut weld, mut scratch) = (vec![0u16; n], vec![[0.0f32; 3]; n]);
    let (mut pos, mut nrm) = (vec![[0.0f32; 3]; n], vec![[0.0f32; 3]; n]);
    if displace(
        &mesh,
        &tex,
        scale,
        &mut weld,
        &mut scratch,
        &mut pos,
        &mut nrm,
    )
    .is_err()
    {
        return;
    }
    let frac = inp.u8() % 16;
    let (mut p16, mut n16) = (vec![[0i16; 3]; n], vec![[0i16; 3]; n]);
    if to_compact(&pos, &nrm, frac, &mut p16, &mut n16).is_err() {
        return;
    }
    let Ok(m) = Mesh::new(&p16, &n16, mesh.triangles(), frac) else {
        return;
    };
    let v = view(inp);
    let lit = lighting();
    let kernel = Shader::<_, _, _, Rgb565>::new(GouraudShading, &lit, Linear);
    with_transform!(v, m, |t| same(m, &t, kernel, &v.spec));
}

/// Refinement: whole = bands, and no crack on the closed spheres.
fn refined(inp: &mut Input) {
    let budget = usize::from(inp.u8() % 64);
    let tau = u16::from_le_bytes([inp.u8(), inp.u8()]);
    let mut v = view(inp);
    v.spec.refine = Some((budget, tau));
    let mesh = if inp.flag() {
        SEAMED.mesh()
    } else {
        SEAMLESS.mesh()
    };
    let lit = lighting();
    let kernel = Shader::<_, _, _, Rgb565>::new(GouraudShading, &lit, Linear);
    with_transform!(v, mesh, |t| {
        let back = same(mesh, &t, kernel, &v.spec);
        let none = same(
            mesh,
            &t,
            kernel,
            &FrameSpec {
                cull: Cull::None,
                ..v.spec
            },
        );
        if let (Some(back), Some(none)) = (back, none) {
            let s = v.size as i64;
            let bg = Rgb565::new(31, 0, 31);
            let at = |px: &[Rgb565], x: i64, y: i64| {
                x >= 0 && y >= 0 && x < s && y < s && px[(y * s + x) as usize] != bg
            };
            for y in 0..s {
                for x in 0..s {
                    let inside = (-1..=1).all(|dy| (-1..=1).all(|dx| at(&none, x + dx, y + dy)));
                    assert!(
                        !inside || at(&back, x, y),
                        "crack at ({x}, {y}), budget {budget}, τ {tau}"
                    );
                }
            }
        }
    });
}

/// One input of the fuzz target.
pub fn run(data: &[u8]) {
    let mut inp = Input(data);
    match inp.u8() % 4 {
        0 => texture(&mut inp),
        1 => normal_map(&mut inp),
        2 => displaced(&mut inp),
        _ => refined(&mut inp),
    }
}
