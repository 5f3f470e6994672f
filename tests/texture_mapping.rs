//! Texture mapping through the renderer (`TexturedGouraudShading`): texel
//! centres, the `GL_MODULATE` identity, separate specular, wrap and clamp,
//! mesh renderer against the per-triangle path, banded against full frame,
//! and robustness at the extremes. The perspective accuracy of the mesh
//! kernel's texture coordinates against the f64 method is a unit test of
//! `src/shade/textured.rs` (it needs the set-up's internals).

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::prelude::*;
use fixshade::camera::{MeshTransform, Orthographic, Perspective};
use fixshade::prelude::*;
use fixshade::raster::SUBPIXEL_BITS;
use fixshade::render::{bins_len, Bands, CachedVertex, Carry, Layout, MeshDraw, MeshMemory};
use fixshade::shade::{Kernel, TexturedGouraudShading, TexturedVertex};
use fixshade::texture::{Filter, TexCoord, Texels, Texture, Wrap};

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

/// A smooth texture: neighbouring texels differ by at most one step per channel.
fn smooth_texture(l: u8) -> Texture<'static> {
    let n = 1u16 << l;
    let d = leak(
        (0..n * n)
            .map(|i| {
                let (x, y) = (i % n, i / n);
                ((x & 31) << 11) | ((((x + y) & 31) + 16) << 5) | ((y & 15) + 8)
            })
            .collect(),
    );
    Texture::new(Texels::Rgb565(d), l, l, Wrap::Repeat).unwrap()
}

fn texture_of(words: Vec<u16>, lw: u8, lh: u8, wrap: Wrap) -> Texture<'static> {
    Texture::new(Texels::Rgb565(leak(words)), lw, lh, wrap).unwrap()
}

/// Fully lit, no specular: a white material lit head-on (primary = 1).
fn full_light() -> Lighting<Q14, DirectionalLight<Q14>, Lambert> {
    let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
    let m = MaterialDesc::classic([1.0; 3], AmbientSource::Object, 0.0, 1.0, 0.0, 1.0);
    Lighting::new(light, Material::new(&m).unwrap())
}

fn lambert() -> Lighting<Q14, DirectionalLight<Q14>, Lambert> {
    let light = DirectionalLight::<Q14>::white([-0.3, 0.5, 0.8]).unwrap();
    let m = MaterialDesc::classic([0.9, 0.6, 0.3], AmbientSource::Object, 0.15, 0.8, 0.0, 1.0);
    Lighting::new(light, Material::new(&m).unwrap())
}

fn blinn(kd: f32) -> Lighting<Q14, DirectionalLight<Q14>, BlinnPhong> {
    let light = DirectionalLight::<Q14>::white([-0.3, 0.5, 0.8]).unwrap();
    let ka = if kd == 0.0 { 0.0 } else { 0.1 };
    let m = MaterialDesc::classic([0.9, 0.6, 0.3], AmbientSource::Object, ka, kd, 0.7, 8.0);
    Lighting::new(light, Material::new(&m).unwrap())
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
        Viewport::new(0, 0, W as i32, W as i32).unwrap(),
    )
    .unwrap()
    .with_view(Mat4::translate([0.0, 0.0, -1.0]))
    .mesh_transform(&Mat4::IDENTITY, SUBPIXEL_BITS as u8)
    .unwrap()
}

/// A perspective view of a plane tilted away (the far edge at about 3× the depth).
fn persp(tilt: f32) -> MeshTransform<Perspective> {
    Camera::perspective(
        1.2,
        1.0,
        0.5,
        200.0,
        Viewport::new(0, 0, W as i32, W as i32).unwrap(),
    )
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
fn render<K: Kernel<Color = Rgb565>, P: fixshade::camera::Projection>(
    kernel: K,
    g: &Grid,
    t: &MeshTransform<P>,
    rows: u32,
) -> Vec<Rgb565>
where
    K::Vertex: fixshade::render::Lerp,
{
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
    let opts = fixshade::render::DrawOptions { cull: Cull::None };
    let mut draw = MeshDraw::with_options(layout, mesh, t, kernel, opts, memory).unwrap();
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
) -> Shader<'l, TexturedGouraudShading, I, Linear, Rgb565> {
    Shader::new(TexturedGouraudShading, lit, Linear).with_texture(tex, filter)
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
    // an 8 × 8 texture over 32 × 32 pixels at the origin: pixel (i, j) samples
    // ((i + ½)/32, (j + ½)/32), texel (i/4, j/4); pixels 4k + 1, 4k + 2 are the
    // two nearest a texel centre (off by 1/8 texel: bilinear blends 1/8 in)
    let lit = full_light();
    for wrap in [Wrap::Repeat, Wrap::Clamp] {
        let tex = random_texture(3, 3, wrap, 11);
        // 8 × 8 pixels exactly on the texels: pixel (i, j) at texel centre (i, j)
        let g = grid(1, 8.0, [0.0, 0.0], [0, 0], [4096, 4096], false);
        for filter in [Filter::Nearest, Filter::Bilinear] {
            let px = render(tex_shader(&lit, tex, filter), &g, &ortho(), W);
            let mut pt = vec![Rgb565::BLACK; (W * W) as usize];
            let mut fb = SliceFramebuffer::new(&mut pt, W, W).unwrap();
            let v = |x: i32, y: i32, u: i32, w: i32| {
                TexturedVertex::new(
                    ShadeVertex::<Q14>::new([x << 4, y << 4], 0, 1, [0.0; 3], [0.0, 0.0, 1.0]),
                    TexCoord { u, v: w },
                )
            };
            let one = 1 << 16;
            let mut sh = tex_shader(&lit, tex, filter);
            for tri in [
                [v(0, 0, 0, 0), v(0, 8, 0, one), v(8, 0, one, 0)],
                [v(8, 0, one, 0), v(0, 8, 0, one), v(8, 8, one, one)],
            ] {
                sh.draw_textured(&mut fb, None, &tri, &RasterOptions::default(), false)
                    .unwrap();
            }
            for y in 0..8 {
                for x in 0..8 {
                    let t = tex.texel(x, y);
                    let want = Rgb565::new(t[0] >> 3, t[1] >> 2, t[2] >> 3);
                    let i = (y as u32 * W + x as u32) as usize;
                    assert_eq!(px[i], want, "mesh {wrap:?} {filter:?} ({x}, {y})");
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
        // perspective: the colours are screen-linear in both
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
    let soft: Lighting<Q14, _, BlinnPhong> = Lighting::new(light, Material::new(&m).unwrap());
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
        let lit: Lighting<Q14, _, Lambert> = Lighting::new(light, Material::new(&m).unwrap());
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

#[test]
fn mesh_renderer_matches_the_per_triangle_path() {
    // a curved grid, orthographic: the mesh kernel's 32-bit planes against the
    // per-triangle path's exact interpolation; a smooth texture (neighbouring
    // texels one step apart) so that a coordinate a fraction of a texel off
    // changes a channel by at most one step: bound 2 (1 from the texel, 1 from
    // the modulation's rounding: the fast path's ⌊(t + 1)·A/32⌋ against the
    // general path's weight)
    let lit = lambert();
    let tex = smooth_texture(5);
    let g = grid(4, 56.0, [4.0, 4.0], [-3000, 500], [9000, 6000], true);
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let mesh = render(tex_shader(&lit, tex, filter), &g, &ortho(), W);
        let mut pt = vec![Rgb565::BLACK; (W * W) as usize];
        let mut fb = SliceFramebuffer::new(&mut pt, W, W).unwrap();
        let mut depth_mem = vec![u16::MAX; (W * W) as usize];
        let mut depth = DepthBuffer::new(&mut depth_mem, W).unwrap();
        let t = ortho();
        let mut sh = tex_shader(&lit, tex, filter);
        for tri in &g.tris {
            let v = tri.map(|i| {
                let i = i as usize;
                let s = t.project(g.pos[i]);
                let n = g.nrm[i].map(|c| f32::from(c) / 16384.0);
                TexturedVertex::new(
                    ShadeVertex::<Q14>::new([s.x, s.y], s.z, 1, [0.0; 3], n),
                    TexCoord {
                        u: i32::from(g.uv[i][0]) << 4,
                        v: i32::from(g.uv[i][1]) << 4,
                    },
                )
            });
            sh.draw_textured(
                &mut fb,
                Some(&mut depth),
                &v,
                &RasterOptions::default(),
                false,
            )
            .unwrap();
        }
        let covered = |p: &[Rgb565]| p.iter().filter(|c| **c != Rgb565::BLACK).count();
        assert_eq!(covered(&mesh), covered(&pt));
        let d = max_delta(&mesh, &pt);
        assert!(d <= 2, "{filter:?}: {d}");
    }
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
                        Viewport::new(0, 0, W as i32, W as i32).unwrap(),
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
    // per-triangle: extreme coordinates, degenerate 1/w
    let mut px = vec![Rgb565::BLACK; (W * W) as usize];
    let mut fb = SliceFramebuffer::new(&mut px, W, W).unwrap();
    let mut sh = tex_shader(&lit, tex, Filter::Bilinear);
    for (inv_w, uv) in [
        ([1, 1, 1], i32::MAX),
        ([0, -5, i32::MAX], i32::MIN),
        ([i32::MAX, 1, 1], 1 << 20),
    ] {
        let v = |k: usize, x: i32, y: i32| {
            TexturedVertex::new(
                ShadeVertex::<Q14>::new([x << 4, y << 4], 0, inv_w[k], [0.0; 3], [0.0, 0.6, 0.8]),
                TexCoord {
                    u: uv,
                    v: uv.wrapping_neg(),
                },
            )
        };
        let tri = [v(0, -3000, 5), v(1, 40, 9000), v(2, 60, 0)];
        for persp in [false, true] {
            sh.draw_textured(&mut fb, None, &tri, &RasterOptions::default(), persp)
                .unwrap();
        }
    }
}

// ---- targeted worst-case search (issue 21, item 6) -------------------------------------

#[path = "common/worst_case.rs"]
mod worst_case;

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
            let lit: Lighting<Q14, _, Lambert> = Lighting::new(light, Material::new(&m).ok()?);
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

/// The mesh renderer against the per-triangle path (bound 2) at targeted
/// worst cases: curved grids with texture coordinates hill-climbed over their
/// range (up to ±8 textures) and offsets (texel edges under pixel centres).
/// The bound assumes neighbouring texels one step apart: a coordinate a
/// fraction of a texel off may pick the neighbour (on `smooth_texture`, whose
/// channels jump at its seams, the search finds 15 steps where a pixel centre
/// lies within that fraction of a seam).
#[test]
fn targeted_mesh_versus_triangle_search() {
    let lit = lambert();
    let tex = wrap_smooth_texture(5);
    let t = ortho();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let score = |p: &[i32; 4]| {
            let g = grid(4, 56.0, [4.0, 4.0], [p[0], p[1]], [p[2], p[3]], true);
            let mesh = render(tex_shader(&lit, tex, filter), &g, &t, W);
            let mut pt = vec![Rgb565::BLACK; (W * W) as usize];
            let mut fb = SliceFramebuffer::new(&mut pt, W, W).unwrap();
            let mut depth_mem = vec![u16::MAX; (W * W) as usize];
            let mut depth = DepthBuffer::new(&mut depth_mem, W).unwrap();
            let mut sh = tex_shader(&lit, tex, filter);
            for tri in &g.tris {
                let v = tri.map(|i| {
                    let i = i as usize;
                    let s = t.project(g.pos[i]);
                    let n = g.nrm[i].map(|c| f32::from(c) / 16384.0);
                    TexturedVertex::new(
                        ShadeVertex::<Q14>::new([s.x, s.y], s.z, 1, [0.0; 3], n),
                        TexCoord {
                            u: i32::from(g.uv[i][0]) << 4,
                            v: i32::from(g.uv[i][1]) << 4,
                        },
                    )
                });
                sh.draw_textured(
                    &mut fb,
                    Some(&mut depth),
                    &v,
                    &RasterOptions::default(),
                    false,
                )
                .unwrap();
            }
            let d = u32::from(max_delta(&mesh, &pt));
            Some((f64::from(d), d))
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
            "mesh vs per-triangle {filter:?}: worst {} (bound 2, {} grids) at {:?}",
            w.error, w.evaluations, w.at
        );
        assert!(w.error <= 2, "{filter:?}: {} at {:?}", w.error, w.at);
    }
}
