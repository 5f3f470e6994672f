//! Texture mapping through the renderer (`GouraudShading.textured(…)`):
//! texel centres, the `GL_MODULATE` identity, separate specular, wrap and
//! clamp, the mesh renderer against the f64 method (orthographic and
//! perspective), the perspective-correct texture coordinates against the f64
//! method (squares receding in depth), banded against full frame, and
//! robustness at the extremes.

use core::cell::Cell;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::prelude::*;
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::camera::{Clip, ClipSpace, MeshTransform, Orthographic, Perspective, Projection};
use fixshade::framebuffer::{BandView, Bands, DrawBand, FullFrame, Layout};
use fixshade::lighting::{LightDesc, LightKind};
use fixshade::mesh::TEXCOORD_FRAC;
use fixshade::num::ATTR_FRAC;
use fixshade::prelude::*;
use fixshade::render::{
    bins_len, draw_triangle, CachedVertex, Carry, Corner, MeshDraw, MeshMemory,
};
use fixshade::shade::{Textured, VertexIn};
use fixshade::texture::{Filter, Texels, Texture, Wrap};
use fixshade_testkit::reference::{ModelDesc, Reference, ViewerDesc, V3};

/// The sub-spans a run is cut into under a perspective projection: 8 pixels
/// (the `raster::interp` docs), so a kernel shades at most 8 pixels a call.
const PERSPECTIVE_SPAN: usize = 8;

const W: u32 = 64;

fn leak<T>(v: Vec<T>) -> &'static [T] {
    Box::leak(v.into_boxed_slice())
}

fn lcg(seed: &mut u64) -> u32 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*seed >> 33) as u32
}

/// A random `2^lw × 2^lh` Rgb565 texture.
fn random_texture(lw: u8, lh: u8, wrap: Wrap, seed: u64) -> Texture<'static> {
    let mut s = seed;
    let d = leak(
        (0..1usize << (lw + lh))
            .map(|_| lcg(&mut s) as u16)
            .collect(),
    );
    Texture::new(Texels::Rgb565(d), lw, lh, wrap).unwrap()
}

/// A smooth texture: neighbouring texels differ by at most one step per
/// channel, across the repeat seam too (triangle waves of period 32 texels:
/// `l = 5` gives a seamless 32 × 32 texture).
fn smooth_texture(l: u8) -> Texture<'static> {
    let n = 1u16 << l;
    let tri = |k: u16| ((k + 16) % 32).abs_diff(16);
    let d = leak(
        (0..n * n)
            .map(|i| {
                let (x, y) = (i % n, i / n);
                (tri(x) << 11) | ((tri(x + y) + 16) << 5) | (tri(y) + 8)
            })
            .collect(),
    );
    Texture::new(Texels::Rgb565(d), l, l, Wrap::Repeat).unwrap()
}

fn texture_of(words: Vec<u16>, lw: u8, lh: u8, wrap: Wrap) -> Texture<'static> {
    Texture::new(Texels::Rgb565(leak(words)), lw, lh, wrap).unwrap()
}

/// Fully lit, no specular: a white material lit head-on (primary = 1).
fn full_light() -> Viewed<Lighting<Q14, DirectionalLight<Q14>, Lambert>> {
    let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
    let m = MaterialDesc::classic([1.0; 3], AmbientSource::Object, 0.0, 1.0, 0.0, 1.0);
    Lighting::new(light, Material::new(&m).unwrap()).eye_space()
}

const LAMBERT_DIR: [f32; 3] = [-0.3, 0.5, 0.8];

fn lambert_material() -> MaterialDesc {
    MaterialDesc::classic([0.9, 0.6, 0.3], AmbientSource::Object, 0.15, 0.8, 0.0, 1.0)
}

fn lambert() -> Viewed<Lighting<Q14, DirectionalLight<Q14>, Lambert>> {
    let light = DirectionalLight::<Q14>::white(LAMBERT_DIR).unwrap();
    Lighting::new(light, Material::new(&lambert_material()).unwrap()).eye_space()
}

fn blinn(kd: f32) -> Viewed<Lighting<Q14, DirectionalLight<Q14>, BlinnPhong>> {
    let light = DirectionalLight::<Q14>::white([-0.3, 0.5, 0.8]).unwrap();
    let ka = if kd == 0.0 { 0.0 } else { 0.1 };
    let m = MaterialDesc::classic([0.9, 0.6, 0.3], AmbientSource::Object, ka, kd, 0.7, 8.0);
    Lighting::new(light, Material::new(&m).unwrap()).eye_space()
}

/// One model unit per pixel, y up in the model (as the measure kernels).
fn ortho() -> MeshTransform<Orthographic> {
    let s = W as f32;
    Camera::orthographic(
        0.0,
        s,
        -s,
        0.0,
        0.5,
        10.0,
        Viewport::new(0, 0, W, W).unwrap(),
    )
    .unwrap()
    .with_view(Mat4::translate([0.0, 0.0, -1.0]))
    .mesh_transform(&Mat4::IDENTITY, SUBPIXEL_BITS as u8)
    .unwrap()
}

/// A perspective view of a plane tilted away (the far edge at about 3× the depth).
fn persp(tilt: f32) -> MeshTransform<Perspective> {
    Camera::perspective(1.2, 1.0, 0.5, 200.0, Viewport::new(0, 0, W, W).unwrap())
        .unwrap()
        .with_view(Mat4::translate([-32.0, 32.0, -40.0]))
        .mesh_transform(&Mat4::rotate_x(tilt), SUBPIXEL_BITS as u8)
        .unwrap()
}

/// A grid of `n × n` quads over `size` model units (z = 0, y down as
/// `-y`), uv from `uv0` to `uv1` (Q12); two triangles per quad.
struct Grid {
    pos: Vec<[i16; 3]>,
    nrm: Vec<[i16; 3]>,
    uv: Vec<[i16; 2]>,
    tris: Vec<[u16; 3]>,
}

fn grid(n: usize, size: f32, origin: [f32; 2], uv0: [i32; 2], uv1: [i32; 2], curved: bool) -> Grid {
    let mut g = Grid {
        pos: vec![],
        nrm: vec![],
        uv: vec![],
        tris: vec![],
    };
    let f = (1 << SUBPIXEL_BITS) as f32;
    for j in 0..=n {
        for i in 0..=n {
            let (a, b) = (i as f32 / n as f32, j as f32 / n as f32);
            g.pos.push([
                ((origin[0] + a * size) * f) as i16,
                (-(origin[1] + b * size) * f) as i16,
                0,
            ]);
            let nn = if curved {
                let (x, y) = (a - 0.5, 0.5 - b);
                let z = (1.0 - x * x - y * y).sqrt();
                [x, y, z]
            } else {
                [0.0, 0.0, 1.0]
            };
            g.nrm.push(nn.map(|c| (c * 16384.0) as i16));
            g.uv.push(
                [
                    uv0[0] + ((uv1[0] - uv0[0]) as f32 * a) as i32,
                    uv0[1] + ((uv1[1] - uv0[1]) as f32 * b) as i32,
                ]
                .map(|c| c.clamp(-32768, 32767) as i16),
            );
        }
    }
    let k = |i: usize, j: usize| (j * (n + 1) + i) as u16;
    for j in 0..n {
        for i in 0..n {
            g.tris.push([k(i, j), k(i, j + 1), k(i + 1, j)]);
            g.tris.push([k(i + 1, j), k(i, j + 1), k(i + 1, j + 1)]);
        }
    }
    g
}

/// Renders `g` with `kernel` in bands of `rows` rows (full frame for `rows = W`).
fn render<K: Kernel<Color = Rgb565>, P: Projection>(
    kernel: K,
    g: &Grid,
    t: &MeshTransform<P>,
    rows: u32,
) -> Vec<Rgb565> {
    let layout = Layout::banded(W, W, rows).unwrap();
    let mesh = Mesh::new(&g.pos, &g.nrm, &g.tris, SUBPIXEL_BITS as u8)
        .unwrap()
        .with_texcoords(&g.uv)
        .unwrap();
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); g.pos.len()];
    let mut bins = vec![0u16; bins_len(g.tris.len(), layout.bands() as usize)];
    let mut carry = vec![Carry::default(); 2 * g.tris.len() + 2];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut carry,
    };
    let opts = fixshade::render::DrawOptions {
        cull: Cull::None,
        ..DrawOptions::default()
    };
    let mut draw = MeshDraw::new(layout, mesh, t, kernel, memory, opts).unwrap();
    let mut strip = vec![Rgb565::BLACK; (W * rows) as usize];
    let mut depth = vec![0u16; (W * rows) as usize];
    let mut bands = Bands::new(layout, &mut strip, Some(&mut depth)).unwrap();
    let mut sink = Sink(vec![Rgb565::BLACK; (W * W) as usize]);
    bands
        .render(&mut sink, Rgb565::BLACK, &mut [&mut draw])
        .unwrap();
    sink.0
}

struct Sink(Vec<Rgb565>);
impl OriginDimensions for Sink {
    fn size(&self) -> Size {
        Size::new(W, W)
    }
}
impl DrawTarget for Sink {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in it {
            if let Some(s) = self.0.get_mut((p.y as u32 * W + p.x as u32) as usize) {
                *s = c;
            }
        }
        Ok(())
    }
}

fn tex_shader<'l, I: fixshade::lighting::Illuminate>(
    lit: &'l I,
    tex: Texture<'static>,
    filter: Filter,
) -> Shader<'l, Textured<'static, GouraudShading>, I, Linear, Rgb565> {
    Shader::new(GouraudShading.textured(tex, filter), lit, Linear)
}

/// Asserts two frames are equal, reporting the first difference (not the frames).
fn same(a: &[Rgb565], b: &[Rgb565], what: &str) {
    let diff = a.iter().zip(b).filter(|(p, q)| p != q).count();
    let first = a.iter().zip(b).position(|(p, q)| p != q);
    assert_eq!(
        diff,
        0,
        "{what}: {diff} pixels differ, first at {first:?}: {:?} vs {:?}",
        first.map(|i| a[i]),
        first.map(|i| b[i])
    );
}

fn max_delta(a: &[Rgb565], b: &[Rgb565]) -> u8 {
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            p.r()
                .abs_diff(q.r())
                .max(p.g().abs_diff(q.g()))
                .max(p.b().abs_diff(q.b()))
        })
        .max()
        .unwrap_or(0)
}

#[test]
fn texel_centres_return_the_texels_nearest_and_bilinear() {
    // an 8 × 8 texture over 8 × 8 pixels at the origin: pixel (i, j) samples
    // the centre of texel (i, j) (bilinear blends nothing in)
    let lit = full_light();
    for wrap in [Wrap::Repeat, Wrap::Clamp] {
        let tex = random_texture(3, 3, wrap, 11);
        let g = grid(1, 8.0, [0.0, 0.0], [0, 0], [4096, 4096], false);
        for filter in [Filter::Nearest, Filter::Bilinear] {
            let px = render(tex_shader(&lit, tex, filter), &g, &ortho(), W);
            for y in 0..8 {
                for x in 0..8 {
                    let t = tex.texel(x, y);
                    let want = Rgb565::new(t[0] >> 3, t[1] >> 2, t[2] >> 3);
                    let i = (y as u32 * W + x as u32) as usize;
                    assert_eq!(px[i], want, "mesh {wrap:?} {filter:?} ({x}, {y})");
                }
            }
        }
    }
}

/// Triangles of a program's own through the per-triangle front
/// (`render::draw_triangle` in `ClipSpace::SCREEN`, no culling).
struct Tris<K> {
    tris: Vec<[Corner; 3]>,
    kernel: K,
    space: ClipSpace,
}

impl<K: Kernel> DrawBand<K::Color> for Tris<K> {
    fn draw_band(&mut self, band: &mut BandView<'_, K::Color>) {
        for t in &self.tris {
            draw_triangle(band, &self.space, &self.kernel, t, Cull::None);
        }
    }
}

/// A corner at pixel `(x, y)` (screen space, depth 0) with texture
/// coordinates `(u, v)` (Q12) and a frontal normal.
fn screen_corner(x: i32, y: i32, u: i32, v: i32) -> Corner {
    let mut vertex = VertexIn::new([0, 0, 16384], [0; 3]);
    vertex.uv = [u, v];
    Corner {
        clip: Clip {
            x: x << SUBPIXEL_BITS,
            y: y << SUBPIXEL_BITS,
            z: 0,
            w: 1,
        },
        vertex,
    }
}

/// Draws `tris` (screen space) with `kernel` into a `W × W` frame.
fn render_tris<K: Kernel<Color = Rgb565>>(kernel: K, tris: Vec<[Corner; 3]>) -> Vec<Rgb565> {
    let mut px = vec![Rgb565::BLACK; (W * W) as usize];
    let mut item = Tris {
        tris,
        kernel,
        space: ClipSpace::SCREEN,
    };
    FullFrame::new(W, W, &mut px, None)
        .unwrap()
        .render(Rgb565::BLACK, &mut [&mut item])
        .unwrap();
    px
}

/// The texel-centre test through the per-triangle front: two triangles of a
/// program's own covering the texture, the same pixels as the mesh renderer.
#[test]
fn texel_centres_through_the_per_triangle_front() {
    let lit = full_light();
    for wrap in [Wrap::Repeat, Wrap::Clamp] {
        let tex = random_texture(3, 3, wrap, 11);
        for filter in [Filter::Nearest, Filter::Bilinear] {
            let v = screen_corner;
            let one = 1 << TEXCOORD_FRAC;
            let pt = render_tris(
                tex_shader(&lit, tex, filter),
                vec![
                    [v(0, 0, 0, 0), v(0, 8, 0, one), v(8, 0, one, 0)],
                    [v(8, 0, one, 0), v(0, 8, 0, one), v(8, 8, one, one)],
                ],
            );
            for y in 0..8 {
                for x in 0..8 {
                    let t = tex.texel(x, y);
                    let want = Rgb565::new(t[0] >> 3, t[1] >> 2, t[2] >> 3);
                    let i = (y as u32 * W + x as u32) as usize;
                    assert_eq!(pt[i], want, "per-triangle {wrap:?} {filter:?} ({x}, {y})");
                }
            }
        }
    }
}

#[test]
fn a_white_texture_is_the_untextured_gouraud_output() {
    let lit = lambert();
    let white = texture_of(vec![0xFFFF; 16], 2, 2, Wrap::Repeat);
    let g = grid(6, 56.0, [4.0, 4.0], [-5000, 300], [9000, 7000], true);
    for rows in [W, 7] {
        let gouraud = render(
            Shader::new(GouraudShading, &lit, Linear),
            &g,
            &ortho(),
            rows,
        );
        for filter in [Filter::Nearest, Filter::Bilinear] {
            let tex = render(tex_shader(&lit, white, filter), &g, &ortho(), rows);
            same(&tex, &gouraud, &format!("{filter:?}, {rows}-row bands"));
        }
        // perspective: the colours perspective-correct in both
        let gp = render(
            Shader::new(GouraudShading, &lit, Linear),
            &g,
            &persp(0.9),
            rows,
        );
        let tp = render(
            tex_shader(&lit, white, Filter::Nearest),
            &g,
            &persp(0.9),
            rows,
        );
        same(&tp, &gp, &format!("perspective, {rows}-row bands"));
        assert!(gp.iter().filter(|p| **p != Rgb565::BLACK).count() > 500);
    }
}

#[test]
fn separate_specular_adds_after_modulation() {
    // black texture: only the secondary colour is left, exactly the Gouraud
    // output of the specular term alone
    let spec_only = blinn(0.0);
    let full = blinn(0.8);
    let black = texture_of(vec![0; 16], 2, 2, Wrap::Repeat);
    let g = grid(6, 56.0, [4.0, 4.0], [0, 0], [8192, 8192], true);
    let want = render(
        Shader::new(GouraudShading, &spec_only, Linear),
        &g,
        &ortho(),
        W,
    );
    let got = render(tex_shader(&full, black, Filter::Nearest), &g, &ortho(), W);
    same(&got, &want, "black texture");
    assert!(want.iter().any(|p| p.r() > 20), "a highlight");
    // white texture with specular: within one step of the Gouraud sum (no
    // colour reaches 1 at a vertex, so that clamping the sum per vertex, as
    // Gouraud does, or per pixel, as OpenGL's separate specular does, agree)
    let light = DirectionalLight::<Q14>::white([-0.3, 0.5, 0.8]).unwrap();
    let m = MaterialDesc::classic([0.9, 0.6, 0.3], AmbientSource::Object, 0.1, 0.5, 0.4, 8.0);
    let soft: Viewed<Lighting<Q14, _, BlinnPhong>> =
        Lighting::new(light, Material::new(&m).unwrap()).eye_space();
    let white = texture_of(vec![0xFFFF; 16], 2, 2, Wrap::Repeat);
    let sum = render(Shader::new(GouraudShading, &soft, Linear), &g, &ortho(), W);
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let tex = render(tex_shader(&soft, white, filter), &g, &ortho(), W);
        assert!(
            max_delta(&sum, &tex) <= 1,
            "{filter:?}: {}",
            max_delta(&sum, &tex)
        );
    }
    // a mid-grey texture halves the primary colour but not the highlight
    let grey = texture_of(vec![0x8410; 16], 2, 2, Wrap::Repeat);
    let half = render(tex_shader(&full, grey, Filter::Nearest), &g, &ortho(), W);
    let brightest = |px: &[Rgb565]| px.iter().map(|p| p.r()).max().unwrap();
    assert!(
        brightest(&half) >= brightest(&want),
        "the highlight survives"
    );
}

#[test]
fn modulation_is_within_one_step_of_the_f64_product() {
    // every texel value against every primary level, fast (nearest) and general
    // (bilinear) paths: out = round(t/max · p · max)
    let g = grid(1, 32.0, [0.0, 0.0], [0, 0], [4096, 4096], false);
    let mut words = Vec::new();
    for i in 0..32u16 {
        for j in 0..32u16 {
            words.push((i << 11) | ((2 * j + (i & 1)) << 5) | (31 - i));
        }
    }
    let tex = texture_of(words, 5, 5, Wrap::Repeat);
    for level in [0.0f32, 0.1, 0.33, 0.5, 0.77, 0.9, 1.0] {
        let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
        let m = MaterialDesc::classic([level; 3], AmbientSource::Object, 0.0, 1.0, 0.0, 1.0);
        let lit: Viewed<Lighting<Q14, _, Lambert>> =
            Lighting::new(light, Material::new(&m).unwrap()).eye_space();
        for filter in [Filter::Nearest, Filter::Bilinear] {
            let px = render(tex_shader(&lit, tex, filter), &g, &ortho(), W);
            for y in 0..32 {
                for x in 0..32 {
                    let t = tex.texel(x, y);
                    let p = px[(y as u32 * W + x as u32) as usize];
                    let want =
                        |t8: u8, max: f64| (f64::from(t8) / 255.0 * f64::from(level) * max).round();
                    for (got, w) in [
                        (p.r(), want(t[0], 31.0)),
                        (p.g(), want(t[1], 63.0)),
                        (p.b(), want(t[2], 31.0)),
                    ] {
                        assert!(
                            (f64::from(got) - w).abs() <= 1.0,
                            "{level} {filter:?} ({x},{y}): {got} vs {w}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn repeat_wraps_and_clamp_holds_the_edge() {
    // uv from −1 to 2 across 48 pixels: a 4 × 1 texture of four colours
    let words = vec![0xF800, 0x07E0, 0x001F, 0xFFFF];
    let lit = full_light();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        for wrap in [Wrap::Repeat, Wrap::Clamp] {
            let tex = texture_of(words.clone(), 2, 0, wrap);
            let g = grid(1, 48.0, [0.0, 0.0], [-4096, 0], [8192, 4095], false);
            let px = render(tex_shader(&lit, tex, filter), &g, &ortho(), W);
            for x in 0..48 {
                let u = (f64::from(x) + 0.5) / 48.0 * 3.0 - 1.0;
                // away from texel edges (nearest) and centres ± ¼ texel (bilinear)
                let s = u * 4.0;
                let col = if filter == Filter::Nearest {
                    if (s - s.round()).abs() < 0.1 {
                        continue;
                    }
                    s.floor() as i32
                } else {
                    let c = s - 0.5;
                    if (c - c.round()).abs() > 0.01 {
                        continue;
                    }
                    c.round() as i32
                };
                let i = match wrap {
                    Wrap::Repeat => col.rem_euclid(4),
                    Wrap::Clamp => col.clamp(0, 3),
                };
                let t = tex.texel(i, 0);
                let want = Rgb565::new(t[0] >> 3, t[1] >> 2, t[2] >> 3);
                assert_eq!(
                    px[(5 * W + x) as usize],
                    want,
                    "{filter:?} {wrap:?} x = {x} u = {u}"
                );
            }
        }
    }
}

/// The f64 method of textured Gouraud shading on the pixel centres of a mesh
/// drawn through `t`: per vertex the primary colour of the reference model
/// (clamped, from the transform's Q14 normal: the quantised input), the
/// texture coordinates (Q12) and the colour interpolated perspective-correctly
/// (screen-linearly for `w = 1`) from the vertices' sub-pixel positions and
/// clip `w`, the texture sampled in f64 (nearest: the texel containing the
/// point; bilinear: the four nearest texel centres), multiplied. Per pixel the
/// expected channel values (31, 63, 31 full scale), `None` outside the mesh.
fn f64_textured<P: Projection>(
    g: &Grid,
    t: &MeshTransform<P>,
    tex: &Texture<'_>,
    filter: Filter,
) -> Vec<Option<[f64; 3]>> {
    let lights = [LightDesc {
        kind: LightKind::Directional {
            towards_light: LAMBERT_DIR,
        },
        ambient: [0.0; 3],
        diffuse: [1.0; 3],
        specular: [1.0; 3],
    }];
    let r = Reference {
        lights: &lights,
        material: lambert_material(),
        global_ambient: [0.0; 3],
        viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
        fog: None,
        model: ModelDesc::of::<Lambert>(),
    };
    let o = fixshade_testkit::reference::VertexOptions::default();
    let sub = f64::from(1u32 << SUBPIXEL_BITS);
    let vert = |i: usize| {
        let p = t.project(g.pos[i]).expect("in front of the camera");
        let n = t.normal(g.nrm[i]).map(|c| f64::from(c) / 16384.0);
        let prim = r.shade_parts([0.0; 3], n, &o).0.map(|c| c.clamp(0.0, 1.0));
        let uv = g.uv[i].map(|c| f64::from(c) / f64::from(1u32 << TEXCOORD_FRAC));
        let w = if P::PERSPECTIVE {
            f64::from(t.clip(g.pos[i]).w)
        } else {
            1.0
        };
        ([f64::from(p.x) / sub, f64::from(p.y) / sub], w, prim, uv)
    };
    let (tw, th) = (f64::from(tex.width()), f64::from(tex.height()));
    let texel = |x: f64, y: f64| tex.texel(x.floor() as i32, y.floor() as i32).map(f64::from);
    let sample = |u: f64, v: f64| -> V3 {
        match filter {
            Filter::Nearest => texel(u * tw, v * th),
            Filter::Bilinear => {
                let (x, y) = (u * tw - 0.5, v * th - 0.5);
                let (fx, fy) = (x - x.floor(), y - y.floor());
                let (x0, y0) = (x.floor(), y.floor());
                let c = [
                    texel(x0, y0),
                    texel(x0 + 1.0, y0),
                    texel(x0, y0 + 1.0),
                    texel(x0 + 1.0, y0 + 1.0),
                ];
                core::array::from_fn(|k| {
                    (c[0][k] * (1.0 - fx) + c[1][k] * fx) * (1.0 - fy)
                        + (c[2][k] * (1.0 - fx) + c[3][k] * fx) * fy
                })
            }
        }
    };
    let mut out = vec![None; (W * W) as usize];
    for tri in &g.tris {
        let v = tri.map(|i| vert(usize::from(i)));
        let p = v.map(|v| v.0);
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        if area == 0.0 {
            continue;
        }
        for y in 0..W {
            for x in 0..W {
                let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                let e = |a: [f64; 2], b: [f64; 2]| {
                    ((b[0] - a[0]) * (cy - a[1]) - (cx - a[0]) * (b[1] - a[1])) / area
                };
                let l = [e(p[1], p[2]), e(p[2], p[0]), e(p[0], p[1])];
                if l.iter().any(|&b| b < -1e-9) {
                    continue;
                }
                let q: [f64; 3] = core::array::from_fn(|i| l[i] / v[i].1);
                let sum = q[0] + q[1] + q[2];
                let at = |f: &dyn Fn(usize) -> f64| (0..3).map(|i| q[i] * f(i)).sum::<f64>() / sum;
                let prim: V3 = core::array::from_fn(|k| at(&|i| v[i].2[k]));
                let (u, vv) = (at(&|i| v[i].3[0]), at(&|i| v[i].3[1]));
                let tx = sample(u, vv);
                let max = [31.0, 63.0, 31.0];
                out[(y * W + x) as usize] =
                    Some(core::array::from_fn(|k| tx[k] / 255.0 * prim[k] * max[k]));
            }
        }
    }
    out
}

#[test]
fn mesh_renderer_against_the_f64_method() {
    // a curved grid, orthographic and in perspective, against the f64 method
    // (exact interpolation): a smooth texture (neighbouring texels one step
    // apart) so that a coordinate a fraction of a texel off changes a channel
    // by at most one step: bound 2 (1 from the texel, 1 from the modulation's
    // rounding: the fast path's ⌊(t + 1)·A/32⌋ against t/31·p). (It compared
    // the mesh renderer with the per-triangle path's exact interpolation; both
    // are one pipeline now, and every value is perspective-correct in it.)
    let lit = lambert();
    let tex = smooth_texture(5);
    let g = grid(4, 56.0, [4.0, 4.0], [-3000, 500], [9000, 6000], true);
    let mut report = Vec::new();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let check = |px: &[Rgb565], want: &[Option<[f64; 3]>], what: &str| {
            let mut worst = 0.0f64;
            let mut n = 0;
            for (i, (p, w)) in px.iter().zip(want).enumerate() {
                if *p == Rgb565::BLACK {
                    continue;
                }
                let w = w.unwrap_or_else(|| panic!("{what}: pixel {i} drawn outside the mesh"));
                let got = [p.r(), p.g(), p.b()].map(f64::from);
                for k in 0..3 {
                    worst = worst.max((got[k] - w[k].round()).abs());
                }
                n += 1;
            }
            assert!(n > 1000, "{what}: {n} pixels");
            assert!(worst <= 2.0, "{what}: off by {worst} steps");
            format!("{what}: max {worst} steps over {n} px")
        };
        let t = ortho();
        let px = render(tex_shader(&lit, tex, filter), &g, &t, W);
        report.push(check(
            &px,
            &f64_textured(&g, &t, &tex, filter),
            &format!("orthographic {filter:?}"),
        ));
        for tilt in [0.4, 0.9] {
            let t = persp(tilt);
            let px = render(tex_shader(&lit, tex, filter), &g, &t, W);
            report.push(check(
                &px,
                &f64_textured(&g, &t, &tex, filter),
                &format!("perspective {tilt} {filter:?}"),
            ));
        }
    }
    println!("{}", report.join("\n"));
}

// ---- perspective-correct texture coordinates ---------------------------------------------

/// A triangle's f64 data for the coordinate test: sub-pixel positions (in
/// pixels), clip `w` and texture coordinates (textures).
#[derive(Clone, Copy, Debug, Default)]
struct CoordTri {
    s: [[f64; 2]; 3],
    w: [f64; 3],
    uv: [[f64; 2]; 3],
}

impl CoordTri {
    /// The perspective-correct coordinates at the centre of pixel `(x, y)`
    /// with the screen-space weights of vertices `order[1]` and `order[2]`
    /// clamped as the pipeline clamps them at a sub-span end beyond the
    /// triangle (`β₁ ∈ [0, 1]`, `β₂ ∈ [0, 1 − β₁]`; `None`: unclamped).
    fn at(&self, x: i32, y: i32, order: Option<[usize; 3]>) -> [f64; 2] {
        let p = self.s;
        let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        let e = |a: [f64; 2], b: [f64; 2]| {
            ((b[0] - a[0]) * (cy - a[1]) - (cx - a[0]) * (b[1] - a[1])) / area
        };
        let mut l = [e(p[1], p[2]), e(p[2], p[0]), e(p[0], p[1])];
        if let Some(o) = order {
            let b1 = l[o[1]].clamp(0.0, 1.0);
            let b2 = l[o[2]].clamp(0.0, 1.0 - b1);
            l[o[1]] = b1;
            l[o[2]] = b2;
            l[o[0]] = 1.0 - b1 - b2;
        }
        let q: [f64; 3] = core::array::from_fn(|i| l[i] / self.w[i]);
        let sum = q[0] + q[1] + q[2];
        core::array::from_fn(|k| (0..3).map(|i| q[i] * self.uv[i][k]).sum::<f64>() / sum)
    }

    fn inside(&self, x: i32, y: i32) -> bool {
        let p = self.s;
        let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        let e = |a: [f64; 2], b: [f64; 2]| {
            ((b[0] - a[0]) * (cy - a[1]) - (cx - a[0]) * (b[1] - a[1])) / area
        };
        [e(p[1], p[2]), e(p[2], p[0]), e(p[0], p[1])]
            .iter()
            .all(|&b| b >= -1e-9)
    }
}

/// The orders in which the pipeline may have oriented a triangle's vertices.
const ORDERS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [1, 2, 0],
    [2, 0, 1],
    [0, 2, 1],
    [2, 1, 0],
    [1, 0, 2],
];

/// What the coordinate test measures.
#[derive(Clone, Copy, Debug, Default)]
struct CoordStats {
    /// Largest `|u − u_f64|`, `|v − v_f64|` against the f64 method (exact at
    /// the sub-span ends, linear in between).
    method: [f64; 2],
    /// Largest error against the exact perspective-correct value per pixel.
    exact: f64,
    /// Largest distance outside the vertices' coordinate range.
    outside: f64,
    pixels: usize,
}

/// A kernel that records the texture coordinates the pipeline interpolates
/// (the values a textured kernel samples at) against the f64 method. Under a
/// perspective projection each call shades one sub-span of at most
/// `PERSPECTIVE_SPAN` pixels starting at `x` (runs are cut into sub-spans from
/// their first pixel), its values exact at `x` and `x + 8`, linear between.
struct CoordKernel<'a> {
    tri: CoordTri,
    stats: &'a Cell<CoordStats>,
    /// The coordinates interpolated per pixel of a `side`-wide frame.
    got: &'a core::cell::RefCell<Vec<Option<[f64; 2]>>>,
    side: u32,
}

impl Kernel for CoordKernel<'_> {
    type Color = Rgb565;
    type Vertex = [i32; 2];
    type Varyings = [i32; 2];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;
    const NEEDS_TEXCOORD: bool = true;

    fn vertex(&self, v: &VertexIn) -> [i32; 2] {
        v.uv
    }

    fn triangle(&self, v: [&[i32; 2]; 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 2]; 3]) {
        ((), v.map(|c| *c))
    }

    fn span(&self, _: &(), a: &[i32; 2], d: &[i32; 2], x: i32, y: i32, out: &mut [Rgb565]) {
        assert!(out.len() <= PERSPECTIVE_SPAN, "a sub-span");
        let one = f64::from(1u32 << (TEXCOORD_FRAC + ATTR_FRAC));
        let n = PERSPECTIVE_SPAN as i32;
        let len = out.len() as i32;
        let start = self.tri.at(x, y, Some([0, 1, 2]));
        // a whole sub-span ends at the next one's first pixel, a run's last
        // at its own last pixel: a sub-span of 8 may be either (the end 8
        // pixels on may lie beyond the triangle: clamped weights, in
        // whichever order the set-up oriented the vertices)
        let mut ends: Vec<([f64; 2], i32)> = Vec::new();
        if len == n {
            if self.tri.inside(x + n, y) {
                ends.push((self.tri.at(x + n, y, Some([0, 1, 2])), n));
            } else {
                ends.extend(ORDERS.iter().map(|o| (self.tri.at(x + n, y, Some(*o)), n)));
            }
        }
        if len > 1 {
            ends.push((self.tri.at(x + len - 1, y, Some([0, 1, 2])), len - 1));
        } else {
            ends.push((start, 1));
        }
        let range = |k: usize| {
            let v = self.tri.uv.map(|c| c[k]);
            (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]))
        };
        let mut st = self.stats.get();
        let mut rec = self.got.borrow_mut();
        for k in 0..out.len() {
            let got = [0, 1].map(|i| f64::from(a[i] + k as i32 * d[i]) / one);
            let e = ends
                .iter()
                .map(|(b, n)| {
                    let f = k as f64 / f64::from(*n);
                    let w = [0, 1].map(|i| start[i] + (b[i] - start[i]) * f);
                    [(got[0] - w[0]).abs(), (got[1] - w[1]).abs()]
                })
                .min_by(|p, q| p[0].max(p[1]).total_cmp(&q[0].max(q[1])))
                .unwrap();
            st.method[0] = st.method[0].max(e[0]);
            st.method[1] = st.method[1].max(e[1]);
            let exact = self.tri.at(x + k as i32, y, None);
            st.exact = st
                .exact
                .max((got[0] - exact[0]).abs().max((got[1] - exact[1]).abs()));
            for (i, g) in got.iter().enumerate() {
                let (lo, hi) = range(i);
                st.outside = st.outside.max(lo - g).max(g - hi);
            }
            st.pixels += 1;
            let px = x + k as i32;
            if (0..self.side as i32).contains(&px) {
                if let Some(s) = rec.get_mut((y as u32 * self.side + px as u32) as usize) {
                    *s = Some(got);
                }
            }
        }
        self.stats.set(st);
    }
}

/// Side of the frame of the coordinate test; focal length `SIDE/2` pixels.
const SIDE: u32 = 400;

/// A square receding in depth seen by a perspective camera of focal length
/// 200 pixels (centre (200, 200)): its two triangles as meshes (positions
/// with 9 fraction bits, Q12 texture coordinates), or `None` when a corner is
/// behind the near plane or outside the set-up window (the clipping path's
/// pieces have vertices of their own).
#[allow(clippy::type_complexity)]
fn square(
    centre: [f64; 3],
    side: f64,
    rot: f64,
    tilt: f64,
    (off, scale): ([f64; 2], f64),
) -> Option<Vec<([[i16; 3]; 3], [[i16; 2]; 3])>> {
    let (c, s) = (rot.cos(), rot.sin());
    let e1 = [side * c, side * s, 0.0];
    let e2 = [
        -side * s * tilt.cos(),
        side * c * tilt.cos(),
        -side * tilt.sin(),
    ];
    let corner = |a: f64, b: f64| -> Option<([i16; 3], [i16; 2])> {
        let p = [0, 1, 2].map(|k| centre[k] + (a - 0.5) * e1[k] + (b - 0.5) * e2[k]);
        let w = -p[2];
        if w < 0.6 {
            return None;
        }
        let (x, y) = (200.0 + 200.0 * p[0] / w, 200.0 - 200.0 * p[1] / w);
        let (sx, sy) = ((x * 16.0).round(), (y * 16.0).round());
        if !(-8000.0..24000.0).contains(&sx) || !(-8000.0..24000.0).contains(&sy) {
            return None;
        }
        let q = p.map(|c| (c * 512.0).round());
        if q.iter().any(|c| c.abs() > 32767.0) {
            return None;
        }
        let t = [off[0] + a * scale, off[1] + b * scale]
            .map(|c| (c * 4096.0).round().clamp(-32768.0, 32767.0) as i16);
        Some((q.map(|c| c as i16), t))
    };
    let k = [
        corner(0.0, 0.0)?,
        corner(1.0, 0.0)?,
        corner(1.0, 1.0)?,
        corner(0.0, 1.0)?,
    ];
    let tri = |i: [usize; 3]| (i.map(|j| k[j].0), i.map(|j| k[j].1));
    Some(vec![tri([0, 1, 2]), tri([0, 2, 3])])
}

/// Draws a one-triangle mesh with `kernel` through the perspective transform
/// `t` into a `SIDE × SIDE` frame (no depth test, no culling).
fn draw_one<K: Kernel<Color = Rgb565>>(
    t: &MeshTransform<Perspective>,
    pos: &[[i16; 3]; 3],
    uv: &[[i16; 2]; 3],
    kernel: K,
    px: &mut [Rgb565],
) {
    let nrm = [[0i16, 0, 16384]; 3];
    let tris = [[0u16, 1, 2]];
    let mesh = Mesh::new(pos, &nrm, &tris, 9)
        .unwrap()
        .with_texcoords(uv)
        .unwrap();
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); 3];
    let mut bins = vec![0u16; bins_len(1, 1)];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut [],
    };
    let layout = Layout::full(SIDE, SIDE).unwrap();
    let opts = fixshade::render::DrawOptions {
        cull: Cull::None,
        ..DrawOptions::default()
    };
    let mut draw = MeshDraw::new(layout, mesh, t, kernel, memory, opts).unwrap();
    FullFrame::new(SIDE, SIDE, px, None)
        .unwrap()
        .render(Rgb565::BLACK, &mut [&mut draw])
        .unwrap();
}

/// What [`coordinate_run`] found.
#[derive(Debug, Default)]
struct CoordReport {
    /// Every triangle.
    all: CoordStats,
    /// Triangles at least one pixel wide (smallest altitude on the screen).
    wide: CoordStats,
    /// The worst triangle at least one pixel wide against the f64 method.
    worst_wide: String,
    /// Pixels drawn by the textured kernel, and those whose texel is not one
    /// the interpolated coordinates reach within 2^−9 of a texture.
    sampled: usize,
    sample_fails: Vec<String>,
}

/// Squares receding in depth (tilts up to 85°, rotations, sizes, distances:
/// depth ratios up to about 20 across a triangle; texture coordinates up to
/// ±8, as the old unit test of `src/shade/textured.rs` drew them), every
/// triangle drawn with [`CoordKernel`] (the coordinates the pipeline
/// interpolates, against the f64 method) and with the textured kernel on a
/// 256 × 256 texture whose texels encode their own position, fully lit (the
/// pixel is the texel).
fn coordinate_run(cases: usize) -> CoordReport {
    const REACH: f64 = 1.0 / 512.0;
    let cam = Camera::perspective(
        core::f32::consts::FRAC_PI_2,
        1.0,
        0.5,
        100.0,
        Viewport::new(0, 0, SIDE, SIDE).unwrap(),
    )
    .unwrap();
    let t = cam.mesh_transform(&Mat4::IDENTITY, 9).unwrap();
    // texel (x, y) of the 256 × 256 texture is the word (y << 8) | x
    let words: Vec<u16> = (0..=u16::MAX).collect();
    let tex = texture_of(words, 8, 8, Wrap::Repeat);
    let lit = full_light();
    let mut seed = 5;
    let mut r = CoordReport::default();
    let mut px = vec![Rgb565::BLACK; (SIDE * SIDE) as usize];
    let max = |a: &mut CoordStats, b: &CoordStats| {
        a.method[0] = a.method[0].max(b.method[0]);
        a.method[1] = a.method[1].max(b.method[1]);
        a.exact = a.exact.max(b.exact);
        a.outside = a.outside.max(b.outside);
        a.pixels += b.pixels;
    };
    for case in 0..cases {
        let f = |seed: &mut u64| f64::from(lcg(seed)) / f64::from(1u32 << 31);
        let tilt = [0.0, 0.5, 1.0, 1.3, 1.45, 1.48][case % 6] + 0.02 * f(&mut seed);
        let rot = 6.3 * f(&mut seed);
        let dist = 2.0 + 20.0 * f(&mut seed);
        let side = dist * (0.05 + 1.5 * f(&mut seed));
        let centre = [
            dist * (f(&mut seed) - 0.5),
            dist * (f(&mut seed) - 0.5),
            -dist,
        ];
        let scale: f64 = [1.0, 2.0, 4.0, 7.9][(case / 6) % 4];
        let off =
            [8.0 * f(&mut seed) - 4.0, 8.0 * f(&mut seed) - 4.0].map(|o: f64| o.min(7.99 - scale));
        let Some(tris) = square(centre, side, rot, tilt, (off, scale)) else {
            continue;
        };
        for (pos, uv) in tris {
            let sub = f64::from(1u32 << SUBPIXEL_BITS);
            let Some(sc) = pos
                .iter()
                .map(|p| t.project(*p))
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let tri = CoordTri {
                s: core::array::from_fn(|i| [f64::from(sc[i].x) / sub, f64::from(sc[i].y) / sub]),
                w: pos.map(|p| f64::from(t.clip(p).w)),
                uv: uv.map(|c| c.map(|v| f64::from(v) / f64::from(1u32 << TEXCOORD_FRAC))),
            };
            let stats = Cell::default();
            let got = core::cell::RefCell::new(vec![None; (SIDE * SIDE) as usize]);
            let k = CoordKernel {
                tri,
                stats: &stats,
                got: &got,
                side: SIDE,
            };
            draw_one(&t, &pos, &uv, k, &mut px);
            let st = stats.get();
            max(&mut r.all, &st);
            let p = tri.s;
            let area = ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]))
                .abs();
            let len = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]).hypot(b[1] - a[1]);
            let longest = len(p[0], p[1]).max(len(p[1], p[2])).max(len(p[2], p[0]));
            if area / longest >= 1.0 {
                if st.method[0].max(st.method[1]) > r.wide.method[0].max(r.wide.method[1]) {
                    let wr = tri.w.iter().copied().fold(0.0, f64::max)
                        / tri.w.iter().copied().fold(f64::MAX, f64::min);
                    r.worst_wide = format!(
                        "case {case}: {:.3e} textures; {:.0} px², {:.1} px wide, {longest:.0} px long, depth ratio {wr:.2}: {tri:?}",
                        st.method[0].max(st.method[1]),
                        area / 2.0,
                        area / longest
                    );
                }
                max(&mut r.wide, &st);
            }
            // the textured kernel samples at the interpolated coordinates
            draw_one(
                &t,
                &pos,
                &uv,
                tex_shader(&lit, tex, Filter::Nearest),
                &mut px,
            );
            for (i, (p, g)) in px.iter().zip(got.into_inner()).enumerate() {
                let Some(g) = g else { continue };
                let raw = p.into_storage();
                let (gx, gy) = (i32::from(raw & 255), i32::from(raw >> 8));
                let reach = |c: f64, texel: i32| {
                    let lo = ((c - REACH) * 256.0).floor() as i32;
                    let hi = ((c + REACH) * 256.0).floor() as i32;
                    (lo..=hi).any(|j| j.rem_euclid(256) == texel)
                };
                r.sampled += 1;
                if !(reach(g[0], gx) && reach(g[1], gy)) && r.sample_fails.len() < 10 {
                    r.sample_fails.push(format!(
                        "case {case} pixel {i}: texel ({gx}, {gy}), interpolated ({:.4}, {:.4}) texels",
                        g[0] * 256.0,
                        g[1] * 256.0
                    ));
                }
            }
        }
    }
    r
}

/// The perspective path's texture coordinates are convex combinations of the
/// vertices' (within their range, slivers included), and the textured kernel
/// samples the texel they reach (within 2^−9 of a texture: its 16-bit
/// packing and re-anchored steps).
#[test]
fn perspective_coordinates_stay_in_range_and_are_sampled() {
    let r = coordinate_run(1500);
    println!(
        "{} pixels; outside the vertex range by {:.2e} textures; {} sampled",
        r.all.pixels, r.all.outside, r.sampled
    );
    assert!(r.all.pixels > 500_000, "{}", r.all.pixels);
    assert!(r.all.outside <= 1e-6, "{:?}", r.all);
    assert!(r.sample_fails.is_empty(), "{:#?}", r.sample_fails);
}

/// The texture-coordinate precision of the perspective path (the intent of
/// the old `perspective_coordinates_match_the_f64_method` unit test of
/// `src/shade/textured.rs`, which held every triangle whose coordinate planes
/// needed no clamping to 2^−9, largest found 1.65·10^−3): on squares
/// receding in depth, every pixel of every sub-span of every triangle at
/// least one pixel wide against the f64 method (the perspective-correct
/// value at the sub-span ends, linear in between), within 2^−9 of a
/// texture; largest found 8.7·10^−4, slivers included (`cargo test --release
/// --test surface perspective_coordinates_match -- --nocapture`).
#[test]
fn perspective_coordinates_match_the_f64_method() {
    const BOUND: f64 = 1.0 / 512.0;
    let r = coordinate_run(4000);
    println!(
        "{} pixels ({} on triangles ≥ 1 px wide); largest error against the f64 method: u {:.3e}, v {:.3e} textures (all: {:.3e}, {:.3e}); against the exact per-pixel value {:.3e}\nworst: {}",
        r.all.pixels, r.wide.pixels, r.wide.method[0], r.wide.method[1], r.all.method[0], r.all.method[1], r.all.exact, r.worst_wide
    );
    assert!(r.wide.pixels > 1_000_000, "{}", r.wide.pixels);
    assert!(
        r.wide.method[0].max(r.wide.method[1]) <= BOUND,
        "off by {:?} textures: {}",
        r.wide.method,
        r.worst_wide
    );
}

#[test]
fn bands_equal_full_frame_bit_for_bit() {
    let lit = blinn(0.7);
    let lam = lambert();
    let tex = random_texture(6, 6, Wrap::Repeat, 3);
    let odd = random_texture(3, 5, Wrap::Clamp, 4);
    let g = grid(8, 60.0, [2.0, 2.0], [-20000, -9000], [20000, 25000], true);
    for tilt in [0.0, 0.8, 1.3] {
        let t = persp(tilt);
        for filter in [Filter::Nearest, Filter::Bilinear] {
            let full = render(tex_shader(&lam, tex, filter), &g, &t, W);
            assert!(full.iter().filter(|p| **p != Rgb565::BLACK).count() > 300);
            for rows in [1, 5, 16] {
                same(
                    &render(tex_shader(&lam, tex, filter), &g, &t, rows),
                    &full,
                    "lambert",
                );
            }
            let full = render(tex_shader(&lit, odd, filter), &g, &t, W);
            for rows in [3, 8] {
                same(
                    &render(tex_shader(&lit, odd, filter), &g, &t, rows),
                    &full,
                    "blinn",
                );
            }
        }
    }
}

#[test]
fn extremes_never_panic() {
    let lit = blinn(0.7);
    let tex = random_texture(4, 4, Wrap::Repeat, 9);
    let big = random_texture(15, 0, Wrap::Clamp, 10);
    let tiny = texture_of(vec![0x1234], 0, 0, Wrap::Repeat);
    // uv at the i16 extremes (±8), a plane through the near plane and far
    // beyond the window, tiny and huge grids
    for (uv0, uv1) in [
        ([-32768, -32768], [32767, 32767]),
        ([32767, -32768], [-32768, 32767]),
        ([0, 0], [0, 0]),
    ] {
        for (n, size, origin) in [
            (1, 0.2, [10.0, 10.0]),
            (3, 60.0, [2.0, 2.0]),
            (2, 3000.0, [-1500.0, -1500.0]),
            (5, 1.0, [30.0, 30.0]),
        ] {
            let g = grid(n, size, origin, uv0, uv1, true);
            for t in [
                texture_of(vec![0xFFFF; 4], 1, 1, Wrap::Clamp),
                tex,
                big,
                tiny,
            ] {
                for filter in [Filter::Nearest, Filter::Bilinear] {
                    render(tex_shader(&lit, t, filter), &g, &ortho(), 7);
                    for tilt in [0.0, 1.2, core::f32::consts::FRAC_PI_2] {
                        render(tex_shader(&lit, t, filter), &g, &persp(tilt), 9);
                    }
                    // a camera inside the plane's depth range: the near plane cuts it
                    let cam = Camera::perspective(
                        1.2,
                        1.0,
                        0.5,
                        200.0,
                        Viewport::new(0, 0, W, W).unwrap(),
                    )
                    .unwrap()
                    .with_view(Mat4::translate([-32.0, 32.0, -2.0]));
                    let tn = cam
                        .mesh_transform(&Mat4::rotate_x(1.2), SUBPIXEL_BITS as u8)
                        .unwrap();
                    render(tex_shader(&lit, t, filter), &g, &tn, W);
                }
            }
        }
    }
    // per-triangle: extreme coordinates, degenerate w (zero, negative, the
    // largest), screen space and a perspective clip space
    for (w, uv) in [
        ([1, 1, 1], i32::MAX),
        ([0, -5, i32::MAX], i32::MIN),
        ([i32::MAX, 1, 1], 1 << 20),
    ] {
        let v = |k: usize, x: i32, y: i32| {
            let mut c = screen_corner(x, y, uv, uv.wrapping_neg());
            c.vertex.normal = [0, 9830, 13107];
            c.clip.w = w[k];
            c
        };
        let tri = [v(0, -3000, 5), v(1, 40, 9000), v(2, 60, 0)];
        for space in [ClipSpace::SCREEN, ClipSpace::perspective([512, 512], 4)] {
            let mut px = vec![Rgb565::BLACK; (W * W) as usize];
            let mut item = Tris {
                tris: vec![tri],
                kernel: tex_shader(&lit, tex, Filter::Bilinear),
                space,
            };
            FullFrame::new(W, W, &mut px, None)
                .unwrap()
                .render(Rgb565::BLACK, &mut [&mut item])
                .unwrap();
        }
    }
}

// ---- targeted worst-case search (issue 21, item 6) -------------------------------------

use fixshade_testkit::worst_case;

/// The modulation bound (one Rgb565 step of `round(t/max · p · max)`) at
/// targeted worst cases: primary levels hill-climbed towards the rounding
/// boundaries of every texel value (the exhaustive test above takes seven
/// levels; here the level is continuous, with the light tilted so that `N·L`
/// varies too), both filters. Prints the worst.
#[test]
fn targeted_modulation_search() {
    let g = grid(1, 32.0, [0.0, 0.0], [0, 0], [4096, 4096], false);
    let mut words = Vec::new();
    for i in 0..32u16 {
        for j in 0..32u16 {
            words.push((i << 11) | ((2 * j + (i & 1)) << 5) | (31 - i));
        }
    }
    let tex = texture_of(words, 5, 5, Wrap::Repeat);
    // a search point: the material level and the light's tilt
    let starts: Vec<(f64, f64)> = (0..12)
        .map(|k| (f64::from(k) / 11.0, if k % 2 == 0 { 0.0 } else { 0.7 }))
        .collect();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let score = |&(level, tilt): &(f64, f64)| {
            let light =
                DirectionalLight::<Q14>::white([tilt.sin() as f32, 0.0, tilt.cos() as f32]).ok()?;
            let m =
                MaterialDesc::classic([level as f32; 3], AmbientSource::Object, 0.0, 1.0, 0.0, 1.0);
            let lit: Viewed<Lighting<Q14, _, Lambert>> =
                Lighting::new(light, Material::new(&m).ok()?).eye_space();
            let px = render(tex_shader(&lit, tex, filter), &g, &ortho(), W);
            // the primary level the lighting gives (exactly: N = (0, 0, 1))
            let p = f64::from(level as f32) * tilt.cos();
            let (mut lin, mut q) = (0.0f64, 0u32);
            for y in 0..32 {
                for x in 0..32 {
                    let t = tex.texel(x, y);
                    let c = px[(y as u32 * W + x as u32) as usize];
                    for (got, t8, max) in [
                        (c.r(), t[0], 31.0),
                        (c.g(), t[1], 63.0),
                        (c.b(), t[2], 31.0),
                    ] {
                        let w = f64::from(t8) / 255.0 * p * max;
                        lin = lin.max((f64::from(got) - w).abs());
                        q = q.max((f64::from(got) - w.round()).abs() as u32);
                    }
                }
            }
            Some((lin, q))
        };
        let w = worst_case::climb(
            &starts,
            40,
            31,
            |&(level, tilt), amount, rng| {
                (
                    (level + amount * rng.range(-1.0, 1.0)).clamp(0.0, 1.0),
                    (tilt + amount * rng.range(-1.0, 1.0)).clamp(0.0, 1.4),
                )
            },
            score,
        );
        println!(
            "modulation {filter:?}: worst {} step (bound 1, {} frames) at {:?}",
            w.error, w.evaluations, w.at
        );
        assert!(w.error <= 1, "{filter:?}: {} at {:?}", w.error, w.at);
    }
}

/// A texture smooth everywhere, across its wrap too (`smooth_texture` jumps
/// from 31 to 0 there, and in blue at row 16): triangle waves, neighbouring
/// texels at most one step apart in every channel.
fn wrap_smooth_texture(l: u8) -> Texture<'static> {
    let n = 1u16 << l;
    let tri = |s: u16| (s % n).min(n - s % n);
    let d = leak(
        (0..n * n)
            .map(|i| {
                let (x, y) = (i % n, i / n);
                (tri(x) << 11) | ((tri(x + y) + 16) << 5) | (tri(y) + 8)
            })
            .collect(),
    );
    Texture::new(Texels::Rgb565(d), l, l, Wrap::Repeat).unwrap()
}

/// The mesh renderer against the f64 method (bound 2, see
/// `mesh_renderer_against_the_f64_method`) at targeted worst cases: curved
/// grids with texture coordinates hill-climbed over their range (up to ±8
/// textures) and offsets (texel edges under pixel centres). The bound assumes
/// neighbouring texels one step apart: a coordinate a fraction of a texel off
/// may pick the neighbour (on `smooth_texture`, whose channels jump at its
/// seams, the search finds 15 steps where a pixel centre lies within that
/// fraction of a seam). (Before the one pipeline it compared the mesh
/// renderer with the per-triangle path; they give the same pixels now.)
#[test]
fn targeted_mesh_versus_f64_search() {
    let lit = lambert();
    let tex = wrap_smooth_texture(5);
    let t = ortho();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let score = |p: &[i32; 4]| {
            let g = grid(4, 56.0, [4.0, 4.0], [p[0], p[1]], [p[2], p[3]], true);
            let mesh = render(tex_shader(&lit, tex, filter), &g, &t, W);
            let want = f64_textured(&g, &t, &tex, filter);
            let mut d = 0.0f64;
            for (px, w) in mesh.iter().zip(&want) {
                if let (false, Some(w)) = (*px == Rgb565::BLACK, w) {
                    let got = [px.r(), px.g(), px.b()].map(f64::from);
                    for k in 0..3 {
                        d = d.max((got[k] - w[k].round()).abs());
                    }
                }
            }
            Some((d, d as u32))
        };
        let starts = [
            [-3000, 500, 9000, 6000],
            [0, 0, 4096, 4096],
            [-32000, -32000, 32000, 32000],
            [100, -7000, 20000, 3],
            [-1, 1, 1, -1],
        ];
        let w = worst_case::climb(
            &starts,
            40,
            57,
            |p, amount, rng| {
                p.map(|c| {
                    (f64::from(c) + amount * 20000.0 * rng.range(-1.0, 1.0))
                        .clamp(-32000.0, 32000.0) as i32
                })
            },
            score,
        );
        println!(
            "mesh vs f64 method {filter:?}: worst {} (bound 2, {} grids) at {:?}",
            w.error, w.evaluations, w.at
        );
        assert!(w.error <= 2, "{filter:?}: {} at {:?}", w.error, w.at);
    }
}
