//! Mesh → camera transform → vertex stage → the one clip-space clipper →
//! set-up → kernel, end to end: `MeshDraw` with a perspective camera and a
//! counting kernel, and one triangle through the near plane via the
//! per-triangle front.

use core::f32::consts::FRAC_PI_2;
use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::camera::{Camera, MeshTransform, Perspective, Viewport};
use fixshade::framebuffer::Layout;
use fixshade::mesh::{icosphere, icosphere_counts, Mesh};
use fixshade::num::Mat4;
use fixshade::raster::Cull;
use fixshade::render::{bins_len, CachedVertex, DrawOptions, MeshDraw, MeshMemory};
use fixshade_testkit::support::{clip_corner, full, lumas, Count, Record, Tris};

const W: u32 = 64;
const H: u32 = 48;
/// Fraction bits of the test meshes' positions.
const FRAC: u8 = 12;

/// A mesh in the compact format, owned.
struct Owned {
    pos: Vec<[i16; 3]>,
    nrm: Vec<[i16; 3]>,
    tris: Vec<[u16; 3]>,
}

impl Owned {
    fn new(pos: &[[f32; 3]], tris: &[[u16; 3]]) -> Owned {
        let q = |v: f32| (v * f32::from(1u16 << FRAC)).round() as i16;
        Owned {
            pos: pos.iter().map(|p| p.map(q)).collect(),
            nrm: vec![[0, 0, 1 << 14]; pos.len()],
            tris: tris.to_vec(),
        }
    }

    fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.pos, &self.nrm, &self.tris, FRAC).unwrap()
    }
}

fn camera(near: f32) -> Camera<Perspective> {
    Camera::perspective(
        FRAC_PI_2,
        W as f32 / H as f32,
        near,
        50.0,
        Viewport::new(0, 0, W, H).unwrap(),
    )
    .unwrap()
    .with_view(Mat4::look_at([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]).unwrap())
}

fn transform(near: f32) -> MeshTransform<Perspective> {
    camera(near).mesh_transform(&Mat4::IDENTITY, FRAC).unwrap()
}

/// Draws the mesh with the counting kernel (whole frame, no depth); returns
/// (covered pixels, pixel writes, vertices behind the near plane).
fn draw(t: &MeshTransform<Perspective>, m: &Owned, cull: Cull) -> (usize, u32, usize) {
    let layout = Layout::full(W, H).unwrap();
    let mut cache = vec![CachedVertex::<()>::default(); m.pos.len()];
    let mut bins = vec![0u16; bins_len(m.tris.len(), 1)];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut [],
    };
    let mut d = MeshDraw::new(
        layout,
        m.mesh(),
        t,
        Count,
        memory,
        DrawOptions {
            cull,
            ..DrawOptions::default()
        },
    )
    .unwrap();
    let px = lumas(&full(W, H, Gray8::BLACK, false, &mut [&mut d]));
    let covered = px.iter().filter(|&&n| n > 0).count();
    let writes = px.iter().map(|&n| u32::from(n)).sum();
    let behind = m.pos.iter().filter(|&&p| t.project(p).is_none()).count();
    (covered, writes, behind)
}

fn sphere(level: u32, c: [f32; 3], r: f32) -> Owned {
    let (nv, nt) = icosphere_counts(level);
    let (mut p, mut n, mut t) = (vec![[0.0; 3]; nv], vec![[0.0; 3]; nv], vec![[0; 3]; nt]);
    icosphere(level, c, r, &mut p, &mut n, &mut t).unwrap();
    Owned::new(&p, &t)
}

#[test]
fn known_points_land_on_known_pixels() {
    // camera at (3, 0, 0) looking at the origin: the origin is the viewport centre
    let vp = Viewport::new(8, 4, 160, 120).unwrap();
    let cam = Camera::perspective(FRAC_PI_2, 4.0 / 3.0, 0.5, 10.0, vp)
        .unwrap()
        .with_view(Mat4::look_at([3.0, 0.0, 0.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap());
    let t = cam.mesh_transform(&Mat4::IDENTITY, FRAC).unwrap();
    let q = |p: [f32; 3]| p.map(|v| (v * f32::from(1u16 << FRAC)).round() as i16);
    let px = |p: [f32; 3]| {
        let s = t.project(q(p)).expect("in front of the near plane");
        (s.x, s.y)
    };
    let sub = |x: i32, y: i32| (x << SUBPIXEL_BITS, y << SUBPIXEL_BITS);
    assert_eq!(px([0.0; 3]), sub(88, 64));
    // fovy = 90°: at distance 3 the top edge is y = 3, the right edge z = −4
    // (the camera looks along −x, so +z is to its left)
    assert_eq!(px([0.0, 3.0, 0.0]), sub(88, 4));
    assert_eq!(px([0.0, 0.0, -4.0]), sub(168, 64));
    assert_eq!(px([0.0, -3.0, 4.0]), sub(8, 124));
    // clip w is the distance in front of the eye (in the clip space's unit,
    // where the near plane is `near()`): nearer points have smaller w and z
    let (c, n) = (t.clip(q([0.0; 3])), t.clip(q([2.0, 0.0, 0.0])));
    let unit = f64::from(t.clip_space().near()) / 0.5;
    assert!((f64::from(c.w) / unit - 3.0).abs() < 1e-3, "{c:?}");
    assert!((f64::from(n.w) / unit - 1.0).abs() < 1e-3, "{n:?}");
    assert!(t.project(q([2.0, 0.0, 0.0])).unwrap().z < t.project(q([0.0; 3])).unwrap().z);
    // behind the near plane and behind the eye
    assert_eq!(t.project(q([2.8, 0.0, 0.0])), None);
    assert_eq!(t.project(q([5.0, 0.0, 0.0])), None);
}

#[test]
fn front_faces_survive_back_culling() {
    let t = transform(0.5);
    // counter-clockwise seen from the eye (which looks down −z)
    let pos = [[-1.0, -1.0, -3.0], [1.0, -1.0, -3.0], [0.0, 1.0, -3.0]];
    let (covered, ..) = draw(&t, &Owned::new(&pos, &[[0, 1, 2]]), Cull::Back);
    assert!(covered > 100, "{covered}");
    let (covered, ..) = draw(&t, &Owned::new(&pos, &[[0, 2, 1]]), Cull::Back);
    assert_eq!(covered, 0);
}

#[test]
fn sphere_from_outside_covers_its_disc_once() {
    let t = transform(0.5);
    let (covered, writes, behind) = draw(&t, &sphere(3, [0.0, 0.0, -5.0], 1.0), Cull::Back);
    assert_eq!(behind, 0);
    assert_eq!(writes as usize, covered, "a pixel was drawn twice");
    // silhouette: a circle of angular radius asin(1/5); on screen (focal length
    // H/2 pixels) a disc of radius H/2·tan(asin(0.2))
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
    let t = transform(0.1);
    for level in [1, 2, 3] {
        let (covered, writes, behind) = draw(&t, &sphere(level, [0.0, 0.0, 0.5], 1.0), Cull::Front);
        assert!(behind > 0);
        assert_eq!(covered, (W * H) as usize, "level {level}: holes");
        assert_eq!(writes as usize, covered, "level {level}: overdraw");
    }
}

#[test]
fn a_triangle_cut_by_the_near_plane_covers_its_visible_part() {
    // (was: `clip_near` puts the cut vertices on the near plane.) The eye-space
    // triangle from z = −0.25 (behind the near plane at 0.5) to z = −2,
    // through the per-triangle front in the camera's clip space: it covers
    // the exact projection of its part in front of the near plane (to within
    // a pixel of the boundary), and its perspective-correct eye depth is at
    // least `near` everywhere and reaches it at the cut.
    let t = transform(0.5);
    let p = [[0.0, 0.0, -0.25], [2.0, 0.0, -2.0], [0.0, 2.0, -2.0]];
    let q = |p: [f32; 3]| p.map(|v| (v * f32::from(1u16 << FRAC)).round() as i16);
    // the value: the distance in front of the eye in 1/1000 units (affine in
    // eye space, so its perspective-correct interpolation is exact)
    let tri = p.map(|v| clip_corner(t.clip(q(v)), (-v[2] * 1000.0).round() as i32));
    assert!(t.project(q(p[0])).is_none() && t.project(q(p[1])).is_some());
    let rec = Record::default();
    let mut item = Tris {
        space: t.clip_space(),
        ..Tris::screen(&rec, vec![tri])
    };
    full(W, H, Gray8::BLACK, false, &mut [&mut item]);
    let px = rec.pixels();
    let depth: Vec<f64> = px.iter().map(|p| p.2 as f64 / 16384.0).collect();
    let nearest = depth.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(
        nearest >= 500.0 - 2.0,
        "a pixel {nearest}/1000 in front of the eye"
    );
    assert!(
        nearest <= 500.0 + 60.0,
        "nearest pixel {nearest}/1000: the cut is not drawn"
    );
    // the exact polygon: (cut on 0→1, v1, v2, cut on 2→0), in pixels
    let (f, cx, cy) = (f64::from(H) / 2.0, f64::from(W) / 2.0, f64::from(H) / 2.0);
    let proj = |x: f64, y: f64, z: f64| (cx + f * x / -z, cy - f * y / -z);
    let s = 2.0 * (0.5 - 0.25) / 1.75;
    let poly = [
        proj(s, 0.0, -0.5),
        proj(2.0, 0.0, -2.0),
        proj(0.0, 2.0, -2.0),
        proj(0.0, s, -0.5),
    ];
    let mut drawn = vec![false; (W * H) as usize];
    for p in &px {
        assert!(!drawn[(p.1 * W as i32 + p.0) as usize], "pixel {p:?} twice");
        drawn[(p.1 * W as i32 + p.0) as usize] = true;
    }
    let area: f64 = (0..4)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % 4]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    let mut inside = 0;
    for y in 0..H {
        for x in 0..W {
            let c = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            // signed distance from the polygon's boundary (positive inside)
            let d = (0..4)
                .map(|i| {
                    let (a, b) = (poly[i], poly[(i + 1) % 4]);
                    let (ex, ey) = (b.0 - a.0, b.1 - a.1);
                    area.signum() * (ex * (c.1 - a.1) - ey * (c.0 - a.0))
                        / (ex * ex + ey * ey).sqrt()
                })
                .fold(f64::INFINITY, f64::min);
            let got = drawn[(y * W + x) as usize];
            if d > 1.0 {
                inside += 1;
                assert!(got, "hole at ({x}, {y}), {d:.2} px inside");
            } else if d < -1.0 {
                assert!(!got, "({x}, {y}) drawn {:.2} px outside", -d);
            }
        }
    }
    assert!(inside > 100, "{inside}");
}
