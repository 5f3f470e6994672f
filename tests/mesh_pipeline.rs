//! Transform → projection → near clipping → rasterizer, end to end.

use core::f32::consts::FRAC_PI_2;
use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use fixshade::mesh::*;
use fixshade::num::Geo16;
use fixshade::raster::{draw_triangle, Cull, RasterOptions, SpanShader, SUBPIXEL_BITS};
use fixshade::target::SliceFramebuffer;
use fixshade::vector::Vec3;

const W: i32 = 64;
const H: i32 = 48;

struct White;
impl SpanShader<0> for White {
    type Color = Gray8;
    fn shade_span(&mut self, _: i32, _: i32, _: &[i32; 0], _: &[i32; 0], out: &mut [Gray8]) {
        out.fill(Gray8::WHITE);
    }
}

/// Draws every triangle (clipping those that cross the near plane); returns
/// (covered pixels, pixel writes, triangles that needed clipping).
fn draw(
    st: &ScreenTransform,
    pos: &[[f32; 3]],
    tris: &[[u16; 3]],
    cull: Cull,
) -> (usize, u32, usize) {
    let mut geo = vec![Vec3::new(Geo16::ZERO, Geo16::ZERO, Geo16::ZERO); pos.len()];
    positions_to_geo16(pos, &mut geo).unwrap();
    let mut pixels = vec![Gray8::BLACK; (W * H) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, W as u32, H as u32).unwrap();
    let opts = RasterOptions {
        cull,
        ..RasterOptions::default()
    };
    let (mut writes, mut clipped) = (0, 0);
    for t in tris {
        let p = t.map(|i| geo[usize::from(i)]);
        let screen = p.map(|p| st.project(p));
        if let [Some(a), Some(b), Some(c)] = screen {
            let v = [a, b, c].map(|s| s.to_raster([]));
            writes += draw_triangle(&mut fb, None, &v, &opts, &mut White)
                .unwrap()
                .pixels;
            continue;
        }
        clipped += 1;
        let cv = p.map(|p| ClipVertex {
            clip: st.clip(p),
            attrs: [],
        });
        let mut out = [[ClipVertex::default(); 3]; 2];
        let n = clip_near(&cv, st.near_w(), &mut out);
        for tri in &out[..n] {
            let s = tri.map(|v| st.project_clip(v.clip));
            let [Some(a), Some(b), Some(c)] = s else {
                panic!("a clipped vertex was rejected: {tri:?}");
            };
            let v = [a, b, c].map(|s| s.to_raster([]));
            writes += draw_triangle(&mut fb, None, &v, &opts, &mut White)
                .unwrap()
                .pixels;
        }
    }
    let covered = pixels.iter().filter(|&&p| p == Gray8::WHITE).count();
    (covered, writes, clipped)
}

fn sphere(level: u32, c: [f32; 3], r: f32) -> (Vec<[f32; 3]>, Vec<[u16; 3]>) {
    let (nv, nt) = icosphere_counts(level);
    let (mut p, mut n, mut t) = (vec![[0.0; 3]; nv], vec![[0.0; 3]; nv], vec![[0; 3]; nt]);
    icosphere(level, c, r, &mut p, &mut n, &mut t).unwrap();
    (p, t)
}

fn camera(near: f32) -> ScreenTransform {
    let proj = Mat4::perspective(FRAC_PI_2, W as f32 / H as f32, near, 50.0).unwrap();
    let view = Mat4::look_at([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]).unwrap();
    ScreenTransform::new(&proj.mul(&view), Viewport::new(0, 0, W, H).unwrap(), near).unwrap()
}

#[test]
fn known_points_land_on_known_pixels() {
    // camera at (3, 0, 0) looking at the origin: the origin is the viewport centre
    let proj = Mat4::perspective(FRAC_PI_2, 4.0 / 3.0, 0.5, 10.0).unwrap();
    let view = Mat4::look_at([3.0, 0.0, 0.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    let vp = Viewport::new(8, 4, 160, 120).unwrap();
    let st = ScreenTransform::new(&proj.mul(&view), vp, 0.5).unwrap();
    let sub = |x: i32, y: i32| (x << SUBPIXEL_BITS, y << SUBPIXEL_BITS);
    let c = st.project_f32([0.0; 3]).unwrap();
    assert_eq!((c.x, c.y), sub(88, 64));
    // fovy = 90°: at distance 3 the top edge is y = 3, the right edge z = −4
    // (the camera looks along −x, so +z is to its left)
    let t = st.project_f32([0.0, 3.0, 0.0]).unwrap();
    assert_eq!((t.x, t.y), sub(88, 4));
    let r = st.project_f32([0.0, 0.0, -4.0]).unwrap();
    assert_eq!((r.x, r.y), sub(168, 64));
    let bl = st.project_f32([0.0, -3.0, 4.0]).unwrap();
    assert_eq!((bl.x, bl.y), sub(8, 124));
    // nearer points have larger inv_w (and smaller z); inv_w = 2^24·near/w
    let near = st.project_f32([2.0, 0.0, 0.0]).unwrap();
    assert_eq!(near.inv_w, INV_W_ONE / 2);
    assert_eq!(c.inv_w, (INV_W_ONE + 3) / 6); // rounded
    assert!(near.z < c.z);
    // behind the near plane and behind the eye
    assert_eq!(st.project_f32([2.8, 0.0, 0.0]), None);
    assert_eq!(st.project_f32([5.0, 0.0, 0.0]), None);
}

#[test]
fn front_faces_survive_back_culling() {
    let st = camera(0.5);
    // counter-clockwise seen from the eye (which looks down −z)
    let pos = [[-1.0, -1.0, -3.0], [1.0, -1.0, -3.0], [0.0, 1.0, -3.0]];
    let (covered, ..) = draw(&st, &pos, &[[0, 1, 2]], Cull::Back);
    assert!(covered > 100, "{covered}");
    let (covered, ..) = draw(&st, &pos, &[[0, 2, 1]], Cull::Back);
    assert_eq!(covered, 0);
}

#[test]
fn sphere_from_outside_covers_its_disc_once() {
    let st = camera(0.5);
    let (pos, tris) = sphere(3, [0.0, 0.0, -5.0], 1.0);
    let (covered, writes, clipped) = draw(&st, &pos, &tris, Cull::Back);
    assert_eq!(clipped, 0);
    assert_eq!(writes as usize, covered, "a pixel was drawn twice");
    // silhouette: a circle of angular radius asin(1/5); on screen (focal length
    // H/2 pixels) an ellipse-free disc of radius H/2·tan(asin(0.2))
    let r = H as f64 / 2.0 * (0.2f64).asin().tan();
    let area = std::f64::consts::PI * r * r;
    assert!(
        (covered as f64 - area).abs() < 0.05 * area + 2.0 * std::f64::consts::PI * r,
        "{covered} vs {area}"
    );
}

#[test]
fn sphere_through_the_near_plane_still_covers_the_screen() {
    // The eye sits inside a sphere whose surface passes through the near plane:
    // seen from inside, the faces wind clockwise (cull front faces), and every
    // view ray meets the surface beyond the near plane, so the whole viewport
    // must be covered exactly once — which needs the clipped triangles.
    let st = camera(0.1);
    for level in [1, 2, 3] {
        let (pos, tris) = sphere(level, [0.0, 0.0, 0.5], 1.0);
        let (covered, writes, clipped) = draw(&st, &pos, &tris, Cull::Front);
        assert!(clipped > 0);
        assert_eq!(covered, (W * H) as usize, "level {level}: holes");
        assert_eq!(writes as usize, covered, "level {level}: overdraw");
    }
}

#[test]
fn clipped_vertices_land_on_the_near_plane() {
    let st = camera(0.5);
    // eye-space triangle from z = −0.25 (behind) to z = −2 (in front)
    let p = [[0.0, 0.0, -0.25], [1.0, 0.0, -2.0], [0.0, 1.0, -2.0]].map(|p| {
        let mut g = [Geo16::ZERO; 3];
        for (g, v) in g.iter_mut().zip(p) {
            *g = Geo16::from_num(v);
        }
        Vec3::new(g[0], g[1], g[2])
    });
    let cv = p.map(|p| ClipVertex {
        clip: st.clip(p),
        attrs: [st.clip(p)[3]],
    });
    let mut out = [[ClipVertex::default(); 3]; 2];
    assert_eq!(clip_near(&cv, 0.5, &mut out), 2);
    // the polygon is (cut on 0→1, v1, v2, cut on 2→0)
    assert_eq!(out[0][1], cv[1]);
    assert_eq!(out[0][2], cv[2]);
    for v in [out[0][0], out[1][2]] {
        assert_eq!(v.clip[3], 0.5);
        assert!((v.attrs[0] - 0.5).abs() < 1e-6);
        let s = st.project_clip(v.clip).unwrap();
        assert_eq!(s.inv_w, INV_W_ONE);
        assert_eq!(s.z, 0);
    }
    // cut on 0→1 at eye z = −0.5: t = (0.5 − 0.25)/1.75, x = t
    let x = st.project_clip(out[0][0].clip).unwrap().x;
    let want = (W as f32 / 2.0 + (1.0 / 7.0) / 0.5 * H as f32 / 2.0) * 16.0;
    assert!((x as f32 - want).abs() <= 1.0, "{x} {want}");
}
