//! Arbitrary `f32` input (NaN, infinities, huge, tiny) never panics, never
//! overflows (debug build), and outputs stay in their documented ranges.

#[path = "common/seeded.rs"]
mod seeded;

use fixshade::mesh::*;
use fixshade::num::{Geo16, Q14};
use fixshade::raster::SUBPIXEL_BITS;

/// `ScreenTransform` saturates screen coordinates to ±2^15 pixels.
const GUARD_BAND: i32 = 1 << 15;
use fixshade::vector::Vec3;
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

fn check_screen(s: Option<ScreenVertex>) {
    if let Some(s) = s {
        let g = GUARD_BAND << SUBPIXEL_BITS;
        assert!((-g..=g).contains(&s.x) && (-g..=g).contains(&s.y), "{s:?}");
        assert!(
            s.inv_w >= 1 && s.inv_w <= INV_W_ONE / 255 * 256 + 256,
            "{s:?}"
        );
    }
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
        let mut q = vec![Vec3::<Q14>::default(); out_len];
        let _ = normals_to_tier(&pos, &mut q);
    }

    #[test]
    fn generators_never_panic(stacks in 0usize..12, slices in 0usize..12, level in 0u32..7,
                              c in v3(), r in any_f32()) {
        let (mut p, mut n, mut t) = ([[0.0f32; 3]; 200], [[0.0f32; 3]; 200], [[0u16; 3]; 400]);
        if let Ok((nv, nt)) = uv_sphere(stacks, slices, c, r, &mut p, &mut n, &mut t) {
            prop_assert_eq!((nv, nt), uv_sphere_counts(stacks, slices));
            prop_assert!(t[..nt].iter().flatten().all(|&i| usize::from(i) < nv));
        }
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
        for m in ms.into_iter().flatten() {
            let _ = m.transform_point(z);
            let _ = m.normal_matrix();
            if let Ok(st) = ScreenTransform::new(&m, Viewport::new(0, 0, 320, 240).unwrap(), 0.1) {
                check_screen(st.project_f32(z));
            }
            let _ = EyeTransform::new(&m);
        }
    }

    #[test]
    fn projection_never_panics(m in mat(), p in v3(), c in [any_f32(), any_f32(), any_f32(), any_f32()],
                               near in any_f32(), vp in (-40000i32..40000, -40000i32..40000, -10i32..40000, -10i32..40000)) {
        let Ok(vp) = Viewport::new(vp.0, vp.1, vp.2, vp.3) else { return Ok(()); };
        if let Ok(st) = ScreenTransform::new(&m, vp, near) {
            check_screen(st.project_f32(p));
            check_screen(st.project_clip(c));
            let g = Vec3::new(Geo16::MAX, Geo16::MIN, Geo16::MAX);
            check_screen(st.project(g));
            let clip = st.clip(g);
            let a = st.project_clip(clip);
            if clip.iter().all(|v| v.is_finite()) {
                prop_assert_eq!(a, st.project(g));
            }
        }
        if let Ok(et) = EyeTransform::new(&m) {
            let _ = et.point_f32::<Q14>(p);
            let _ = et.point_f32::<f32>(p);
            let n = et.normal(Vec3::<Q14>::from_f32(c[..3].try_into().unwrap()));
            let l = n.to_f32().iter().map(|v| v * v).sum::<f32>();
            prop_assert!(l == 0.0 || (l - 1.0).abs() < 0.01, "{:?}", n);
            let _ = et.normal(Vec3::<f32>::from_f32(p));
        }
    }

    #[test]
    fn clipping_never_panics(w in [any_f32(), any_f32(), any_f32()], x in v3(), near in any_f32()) {
        let tri = [0, 1, 2].map(|i| ClipVertex { clip: [x[i], 0.0, 0.0, w[i]], attrs: [x[i], w[i]] });
        let mut out = [[ClipVertex::default(); 3]; 2];
        let n = clip_near(&tri, near, &mut out);
        prop_assert!(n <= 2);
        let inside = w.iter().filter(|&&w| w >= near).count();
        prop_assert_eq!(n, match inside { 0 => 0, 3 => 1, k => k });
    }
}
