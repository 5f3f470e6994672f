//! Arbitrary `f32` input (NaN, infinities, huge, tiny) never panics, never
//! overflows (debug build), and outputs stay in their documented ranges:
//! mesh generators and normals, matrices, cameras and their fixed-point
//! transforms, and meshes drawn through any such transform (the vertex
//! stage, the one clip-space clipper and set-up).

use fixshade_testkit::seeded;
use fixshade_testkit::support;

use embedded_graphics_core::pixelcolor::Gray8;
use fixshade::camera::{Camera, Clip, ClipSpace, FixedCamera, MeshTransform, Projection, Viewport};
use fixshade::framebuffer::Layout;
use fixshade::mesh::*;
use fixshade::num::Mat4;
use fixshade::num::{Vec3, Q14};
use fixshade::raster::Cull;
use fixshade::render::{bins_len, CachedVertex, Carry, DrawOptions, MeshDraw, MeshMemory};
use fixshade_testkit::support::{clip_corner, full, lumas, Count, Tris};
use proptest::prelude::*;

/// Any f32, with the special values made likely.
fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -10.0f32..10.0,
        2 => proptest::num::f32::ANY,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(-f32::MAX),
        1 => Just(3.0e38f32),
        1 => Just(1.0e-40f32),
        1 => Just(0.0f32),
    ]
}

fn v3() -> impl Strategy<Value = [f32; 3]> {
    [any_f32(), any_f32(), any_f32()]
}

fn mat() -> impl Strategy<Value = Mat4> {
    prop_oneof![
        prop::array::uniform4(prop::array::uniform4(any_f32())).prop_map(|m| Mat4 { m }),
        prop::array::uniform4(prop::array::uniform4(-1.0e6f32..1.0e6)).prop_map(|m| Mat4 { m }),
        prop::array::uniform4(prop::array::uniform4(-2.0f32..2.0)).prop_map(|m| Mat4 { m }),
    ]
}

/// A view or model matrix that mostly makes sense (rotations, a
/// translation that may put the eye inside the mesh, a scale), or any.
fn placement() -> impl Strategy<Value = Mat4> {
    let sane = (
        prop::array::uniform3(-3.2f32..3.2),
        prop::array::uniform3(-6.0f32..6.0),
        -12.0f32..3.0,
        0.01f32..4.0,
    )
        .prop_map(|(r, t, z, k)| {
            Mat4::translate([t[0], t[1], z])
                .mul(&Mat4::rotate_x(r[0]))
                .mul(&Mat4::rotate_y(r[1]))
                .mul(&Mat4::rotate_z(r[2]))
                .mul(&Mat4::scale([k; 3]))
        });
    prop_oneof![3 => sane, 1 => mat()]
}

/// Draws `tris` over `pos` (normals `nrm`) through `t` with the counting
/// kernel and a depth buffer into a 32 × 24 frame, whole and in 5-row
/// bands: no panic, and the bands give the whole frame.
fn draw_mesh<P: Projection>(
    t: &MeshTransform<P>,
    pos: &[[i16; 3]],
    nrm: &[[i16; 3]],
    tris: &[[u16; 3]],
) -> Vec<u8> {
    let mesh = Mesh::new(pos, nrm, tris, 12).unwrap();
    let frame = |rows: u32| {
        let layout = Layout::banded(32, 24, rows).unwrap();
        let mut cache = vec![CachedVertex::<()>::default(); pos.len()];
        let mut bins = vec![0u16; bins_len(tris.len(), layout.bands() as usize)];
        let mut carry = vec![Carry::default(); 2 * tris.len()];
        let memory = MeshMemory {
            vertices: &mut cache,
            bins: &mut bins,
            carry: &mut carry,
        };
        let mut d = MeshDraw::new(
            layout,
            mesh,
            t,
            Count,
            memory,
            DrawOptions {
                cull: Cull::None,
                ..DrawOptions::default()
            },
        )
        .unwrap();
        if rows == 24 {
            lumas(&full(32, 24, Gray8::new(0), true, &mut [&mut d]))
        } else {
            lumas(&support::banded(
                32,
                24,
                rows,
                Gray8::new(0),
                true,
                &mut [&mut d],
            ))
        }
    };
    let whole = frame(24);
    assert_eq!(frame(5), whole, "5-row bands differ from the whole frame");
    whole
}

/// Projects `p` through `t`: the clip space's projection of `t.clip(p)`,
/// the eye position and normal: no panic, consistent.
fn probe<P: Projection>(t: &MeshTransform<P>, p: [i16; 3]) {
    let c = t.clip(p);
    assert_eq!(t.project(p), t.clip_space().project(c));
    if !P::PERSPECTIVE {
        assert_eq!(c.w, 1);
        assert!(t.project(p).is_some());
    }
    let _ = t.eye(p);
    let _ = t.normal(p);
}

proptest! {
    #![proptest_config(seeded::config("mesh_robust", 512))]

    #[test]
    fn normals_never_panic(pos in prop::collection::vec(v3(), 0..12),
                           tris in prop::collection::vec(prop::array::uniform3(0u16..14), 0..16),
                           out_len in 0usize..14) {
        let mut out = vec![[0.0f32; 3]; out_len];
        for w in [Weighting::Area, Weighting::Angle] {
            if vertex_normals(&pos, &tris, w, &mut out).is_ok() {
                for n in &out[..pos.len()] {
                    let l = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
                    prop_assert!(l == 0.0 || (l - 1.0).abs() < 1e-5, "{n:?}");
                }
            }
        }
        let mut f = vec![[0.0f32; 3]; out_len];
        let _ = face_normals(&pos, &tris, &mut f);
        let _: Vec<Vec3<Q14>> = pos.iter().map(|&n| Vec3::from_f32(n)).collect();
    }

    #[test]
    fn generators_never_panic(level in 0u32..7, c in v3(), r in any_f32()) {
        let (mut p, mut n, mut t) = ([[0.0f32; 3]; 200], [[0.0f32; 3]; 200], [[0u16; 3]; 400]);
        if let Ok((nv, nt)) = icosphere(level, c, r, &mut p, &mut n, &mut t) {
            prop_assert_eq!((nv, nt), icosphere_counts(level));
            prop_assert!(t[..nt].iter().flatten().all(|&i| usize::from(i) < nv));
        }
    }

    #[test]
    fn matrices_never_panic(a in any_f32(), b in any_f32(), c in any_f32(), d in any_f32(),
                            e in any_f32(), f in any_f32(), x in v3(), y in v3(), z in v3()) {
        let ms = [
            Mat4::perspective(a, b, c, d).ok(),
            Mat4::orthographic(a, b, c, d, e, f).ok(),
            Mat4::look_at(x, y, z).ok(),
            Some(Mat4::rotate_x(a).mul(&Mat4::rotate_y(b)).mul(&Mat4::rotate_z(c))),
            Some(Mat4::translate(x).mul(&Mat4::scale(y))),
        ];
        let vp = Viewport::new(0, 0, 320, 240).unwrap();
        for m in ms.into_iter().flatten() {
            let _ = m.transform_point(z);
            let _ = m.normal_matrix();
            // as a view and as a model matrix of both camera kinds
            if let Ok(cam) = Camera::perspective(1.0, 1.3, 0.1, 100.0, vp) {
                if let Ok(t) = cam.with_view(m).mesh_transform(&m, 12) {
                    probe(&t, [1000, -2000, 300]);
                }
            }
            if let Ok(cam) = Camera::orthographic(-1.0, 1.0, -1.0, 1.0, 0.1, 100.0, vp) {
                if let Ok(t) = cam.with_view(m).mesh_transform(&m, 12) {
                    probe(&t, [1000, -2000, 300]);
                }
            }
        }
    }

    #[test]
    fn projection_never_panics(m in mat(), model in mat(), p in prop::array::uniform3(any::<i16>()),
                               cam in (any_f32(), any_f32(), any_f32(), any_f32()), frac in 0u8..17,
                               vp in (-40000i32..40000, -40000i32..40000, 0u32..40000, 0u32..40000)) {
        let Ok(vp) = Viewport::new(vp.0, vp.1, vp.2, vp.3) else { return Ok(()); };
        if let Ok(c) = Camera::perspective(cam.0, cam.1, cam.2, cam.3, vp) {
            let c = c.with_view(m);
            if let Ok(t) = c.mesh_transform(&model, frac) {
                probe(&t, p);
                probe(&t, [i16::MAX, i16::MIN, i16::MAX]);
            }
            if let Ok(fc) = FixedCamera::new(&c) {
                if let Ok(t) = fc.mesh_transform(&fixshade::camera::Pose::IDENTITY, frac) {
                    probe(&t, p);
                }
            }
        }
        if let Ok(c) = Camera::orthographic(cam.0, cam.1, cam.2, cam.3, cam.1, cam.0, vp) {
            if let Ok(t) = c.with_view(m).mesh_transform(&model, frac) {
                probe(&t, p);
                probe(&t, [i16::MAX, i16::MIN, i16::MAX]);
            }
        }
    }

    #[test]
    fn meshes_through_any_transform_never_panic(
        m in placement(), model in placement(),
        pos in prop::collection::vec(prop::array::uniform3(any::<i16>()), 3..9),
        nrm in prop::collection::vec(prop::array::uniform3(any::<i16>()), 9),
        tris in prop::collection::vec(prop::array::uniform3(0u16..9), 1..12),
        fovy in prop_oneof![3 => 0.1f32..3.1, 1 => any_f32()], near in prop_oneof![3 => 0.01f32..5.0, 1 => any_f32()],
        persp in any::<bool>(),
    ) {
        let tris: Vec<[u16; 3]> = tris.iter().map(|t| t.map(|i| i % pos.len() as u16)).collect();
        let vp = Viewport::new(0, 0, 32, 24).unwrap();
        if persp {
            if let Ok(t) = Camera::perspective(fovy, 1.3, near, near * 100.0, vp)
                .map(|c| c.with_view(m))
                .and_then(|c| c.mesh_transform(&model, 12))
            {
                draw_mesh(&t, &pos, &nrm, &tris);
            }
        } else if let Ok(t) = Camera::orthographic(-fovy, fovy, -near, near, 0.1, 50.0, vp)
            .map(|c| c.with_view(m))
            .and_then(|c| c.mesh_transform(&model, 12))
        {
            draw_mesh(&t, &pos, &nrm, &tris);
        }
    }

    #[test]
    fn clipping_never_panics(w in [any_f32(), any_f32(), any_f32()], x in v3(), y in v3(), near in any_f32(),
                             centre in prop::array::uniform2(any::<i32>())) {
        // any clip coordinates (saturated from f32) in any perspective clip
        // space: a triangle wholly behind the near plane draws nothing
        let space = ClipSpace::perspective(centre, near as i32);
        let tri = [0, 1, 2].map(|i| clip_corner(Clip { x: x[i] as i32, y: y[i] as i32, z: 0, w: w[i] as i32 }, 0));
        let mut item = Tris { space, ..Tris::screen(Count, vec![tri]) };
        let px = lumas(&full(32, 24, Gray8::new(0), false, &mut [&mut item]));
        prop_assert!(px.iter().all(|&n| n <= 1));
        if tri.iter().all(|c| c.clip.w < space.near()) {
            prop_assert!(px.iter().all(|&n| n == 0));
        }
    }
}

/// More than 32 767 triangles crossing one band boundary (the bins count
/// crossings in `u16`; summed as `i16` they wrapped, `carry_needed` said 0 and
/// the bands below the first lost the triangles): 40 000 copies of one
/// triangle over a 32 × 32 orthographic view in 8-row bands draw the whole
/// frame's pixels, and the records needed are counted exactly.
#[test]
fn forty_thousand_triangles_across_one_boundary_are_all_carried() {
    const N: usize = 40_000;
    let pos = [[-900i16, 900, 0], [900, 900, 0], [-900, -900, 0]];
    let nrm = [[0i16, 0, NORMAL_ONE]; 3];
    let tris = vec![[0u16, 1, 2]; N];
    let mesh = Mesh::new(&pos, &nrm, &tris, 10).unwrap();
    let vp = Viewport::new(0, 0, 32, 32).unwrap();
    let t = Camera::orthographic(-1.0, 1.0, -1.0, 1.0, 0.1, 100.0, vp)
        .unwrap()
        .with_view(Mat4::translate([0.0, 0.0, -2.0]))
        .mesh_transform(&Mat4::IDENTITY, 10)
        .unwrap();
    let frame = |rows: u32| {
        let layout = Layout::banded(32, 32, rows).unwrap();
        let mut cache = vec![CachedVertex::<()>::default(); pos.len()];
        let mut bins = vec![0u16; bins_len(N, layout.bands() as usize)];
        let mut carry = vec![Carry::default(); 2 * N];
        let memory = MeshMemory {
            vertices: &mut cache,
            bins: &mut bins,
            carry: &mut carry,
        };
        let options = DrawOptions {
            cull: Cull::None,
            ..DrawOptions::default()
        };
        let mut d = MeshDraw::new(
            layout,
            mesh,
            &t,
            support::Solid(Gray8::new(200)),
            memory,
            options,
        )
        .unwrap();
        let need = d.carry_needed();
        let px = if rows == 32 {
            full(32, 32, Gray8::new(0), false, &mut [&mut d])
        } else {
            support::banded(32, 32, rows, Gray8::new(0), false, &mut [&mut d])
        };
        (need, lumas(&px))
    };
    let (_, whole) = frame(32);
    let lit = whole.iter().filter(|&&l| l == 200).count();
    assert!(
        lit > 300,
        "the triangle covers most of half the view: {lit} pixels"
    );
    let (need, banded) = frame(8);
    // every copy crosses the first boundaries: two records per crossing triangle
    assert_eq!(need, 2 * N, "resume records needed");
    assert_eq!(banded, whole, "8-row bands differ from the whole frame");
}
