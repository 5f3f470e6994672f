//! One pipeline: a mesh drawn by `MeshDraw` and the same mesh drawn triangle
//! by triangle through the per-triangle front (`render::draw_triangle`, with
//! the corners of the same transform: `t.clip(p)`, `VertexIn::new(t.normal(n),
//! t.eye(p))`) give the same pixels bit for bit — on the standard scene in
//! every shading mode, and on random meshes reaching beyond the set-up window
//! and, in perspective, through the near plane — whole and in bands. And the
//! depth-plane regression: a back face never wins over the front surface.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::camera::{Camera, MeshTransform, Projection, Viewport};
use fixshade::color::Linear;
use fixshade::mesh::Mesh;
use fixshade::num::Mat4;
use fixshade::num::Q14;
use fixshade::raster::Cull;
use fixshade::shade::{FlatShading, GouraudShading, Kernel, PhongShading, Shader};
use fixshade::standard::{self, SPHERE};
use fixshade_testkit::support::mesh_frame;

const W: u32 = standard::SIZE;

/// The pixels on which two frames differ: (count, first index).
fn diff(a: &[Rgb565], b: &[Rgb565]) -> (usize, Option<usize>) {
    let d: Vec<usize> = (0..a.len()).filter(|&i| a[i] != b[i]).collect();
    (d.len(), d.first().copied())
}

/// `MeshDraw` and the per-triangle front, whole and in `rows`-row bands:
/// all four frames equal bit for bit. Returns the frame.
#[allow(clippy::too_many_arguments)]
fn same<K: Kernel<Color = Rgb565> + Copy, P: Projection>(
    what: &str,
    w: u32,
    rows: u32,
    mesh: Mesh<'_>,
    t: &MeshTransform<P>,
    k: K,
    cull: Cull,
) -> Vec<Rgb565> {
    let base = mesh_frame(w, w, w, mesh, t, k, cull, false, Rgb565::BLACK);
    for (r, front) in [(w, true), (rows, false), (rows, true)] {
        let px = mesh_frame(w, w, r, mesh, t, k, cull, front, Rgb565::BLACK);
        let (n, first) = diff(&px, &base);
        let how = if front { "draw_triangle" } else { "MeshDraw" };
        assert!(
            n == 0,
            "{what}: {how} in {r}-row bands differs from MeshDraw whole on {n} pixels, first at {:?}",
            first.map(|i| (i % w as usize, i / w as usize))
        );
    }
    base
}

#[test]
fn standard_scene_meshdraw_equals_draw_triangle_in_every_mode() {
    let t = standard::transform().unwrap();
    let blinn = standard::blinn::<Q14>().unwrap();
    let lambert = standard::lambert::<Q14>().unwrap();
    for cull in [Cull::Back, Cull::None] {
        let f = same(
            "flat",
            W,
            8,
            SPHERE.mesh(),
            &t,
            Shader::new(FlatShading, &lambert, Linear),
            cull,
        );
        let lit = f.iter().filter(|&&p| p != Rgb565::BLACK).count();
        // the sphere covers 85 % of the width: π·102² ≈ 32 700 pixels
        assert!((32_000..33_500).contains(&lit), "{lit} lit pixels");
        same(
            "flat blinn",
            W,
            8,
            SPHERE.mesh(),
            &t,
            Shader::new(FlatShading, &blinn, Linear),
            cull,
        );
        same(
            "gouraud",
            W,
            8,
            SPHERE.mesh(),
            &t,
            Shader::new(GouraudShading, &blinn, Linear),
            cull,
        );
        same(
            "gouraud lambert",
            W,
            8,
            SPHERE.mesh(),
            &t,
            Shader::new(GouraudShading, &lambert, Linear),
            cull,
        );
        same(
            "phong",
            W,
            8,
            SPHERE.mesh(),
            &t,
            Shader::new(PhongShading, &blinn, Linear),
            cull,
        );
        same(
            "phong lambert",
            W,
            8,
            SPHERE.mesh(),
            &t,
            Shader::new(PhongShading, &lambert, Linear),
            cull,
        );
        same(
            "general phong",
            W,
            8,
            SPHERE.mesh(),
            &t,
            Shader::new(PhongShading, &blinn, Linear),
            cull,
        );
    }
}

/// A deterministic LCG (Knuth's MMIX constants).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) as u32
    }
    /// Uniform in `lo..=hi`.
    fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % (hi - lo + 1) as u32) as i32
    }
}

/// A random mesh: `nv` positions (8 fraction bits: ±128 units, most within
/// `spread` units of `centre`), random unit-ish normals, `nt` random
/// triangles.
struct Random {
    pos: Vec<[i16; 3]>,
    nrm: Vec<[i16; 3]>,
    tris: Vec<[u16; 3]>,
}

impl Random {
    fn new(r: &mut Lcg, nv: usize, nt: usize, centre: [i32; 3], spread: i32) -> Random {
        let pos = (0..nv)
            .map(|_| {
                if r.next() % 8 == 0 {
                    // anywhere: far beyond the window
                    [0; 3].map(|_| r.range(-32767, 32767) as i16)
                } else {
                    [0, 1, 2]
                        .map(|k| (centre[k] + r.range(-spread, spread)).clamp(-32767, 32767) as i16)
                }
            })
            .collect();
        let nrm = (0..nv)
            .map(|_| [0; 3].map(|_| r.range(-16384, 16384) as i16))
            .collect();
        let tris = (0..nt)
            .map(|_| [0; 3].map(|_| (r.next() as usize % nv) as u16))
            .collect();
        Random { pos, nrm, tris }
    }

    fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.pos, &self.nrm, &self.tris, 8).unwrap()
    }
}

#[test]
fn random_meshes_meshdraw_equals_draw_triangle_both_projections() {
    const S: u32 = 96;
    let vp = Viewport::new(0, 0, S, S).unwrap();
    let ortho = Camera::orthographic(-3.0, 3.0, -3.0, 3.0, 1.0, 100.0, vp)
        .unwrap()
        .with_view(Mat4::translate([0.0, 0.0, -40.0]));
    let persp = Camera::perspective(1.2, 1.0, 1.0, 100.0, vp).unwrap();
    let blinn = standard::blinn::<Q14>().unwrap();
    let blinn_f32 = standard::blinn::<f32>().unwrap();
    let mut r = Lcg(0x0123_4567_89AB_CDEF);
    let (mut lit, mut crossing, mut beyond) = (0usize, 0usize, 0usize);
    for m in 0..24 {
        let model = Mat4::rotate_y(0.37 * m as f32).mul(&Mat4::rotate_x(0.21 * m as f32));
        let cull = [Cull::None, Cull::Back][m % 2];
        // orthographic: ±3 units in 96 pixels, positions mostly within ±4
        // units, some anywhere in ±128 units (up to 2 000 pixels off: beyond
        // the set-up window, −512..1536 pixels)
        let mesh = Random::new(&mut r, 24, 40, [0; 3], 4 << 8);
        let t = ortho.mesh_transform(&model, 8).unwrap();
        beyond += mesh
            .pos
            .iter()
            .filter(|&&p| {
                let s = t.project(p).unwrap();
                !(-512 * 16..1536 * 16).contains(&s.x) || !(-512 * 16..1536 * 16).contains(&s.y)
            })
            .count();
        let f = same(
            "ortho gouraud",
            S,
            8,
            mesh.mesh(),
            &t,
            Shader::new(GouraudShading, &blinn, Linear),
            cull,
        );
        lit += f.iter().filter(|&&p| p != Rgb565::BLACK).count();
        same(
            "ortho flat",
            S,
            8,
            mesh.mesh(),
            &t,
            Shader::new(FlatShading, &blinn, Linear),
            cull,
        );
        same(
            "ortho phong",
            S,
            8,
            mesh.mesh(),
            &t,
            Shader::new(PhongShading, &blinn, Linear),
            cull,
        );
        same(
            "ortho general phong",
            S,
            8,
            mesh.mesh(),
            &t,
            Shader::new(PhongShading, &blinn_f32, Linear),
            cull,
        );
        // perspective: the eye at the origin looking down −z, near plane at
        // 1: positions around z = −6 within ±8 units cross it
        let mesh = Random::new(&mut r, 24, 40, [0, 0, -6 << 8], 8 << 8);
        let t = persp.mesh_transform(&model, 8).unwrap();
        crossing += mesh
            .tris
            .iter()
            .filter(|tri| {
                let behind = tri
                    .iter()
                    .filter(|&&i| t.project(mesh.pos[usize::from(i)]).is_none())
                    .count();
                behind == 1 || behind == 2
            })
            .count();
        let f = same(
            "persp gouraud",
            S,
            8,
            mesh.mesh(),
            &t,
            Shader::new(GouraudShading, &blinn, Linear),
            cull,
        );
        lit += f.iter().filter(|&&p| p != Rgb565::BLACK).count();
        same(
            "persp flat",
            S,
            8,
            mesh.mesh(),
            &t,
            Shader::new(FlatShading, &blinn, Linear),
            cull,
        );
        same(
            "persp phong",
            S,
            8,
            mesh.mesh(),
            &t,
            Shader::new(PhongShading, &blinn, Linear),
            cull,
        );
        same(
            "persp general phong",
            S,
            8,
            mesh.mesh(),
            &t,
            Shader::new(PhongShading, &blinn_f32, Linear),
            cull,
        );
    }
    println!("{lit} lit pixels, {crossing} triangles through the near plane, {beyond} vertices beyond the window");
    assert!(lit > 24 * 2000, "{lit}");
    assert!(crossing > 100, "{crossing}");
    assert!(beyond > 20, "{beyond}");
}

/// On every pixel where the front surface is visible (drawn with back faces
/// culled), the frame drawn without culling shows the same colour: no back
/// face wins the depth test there. Returns the mismatching pixels and the
/// pixels compared.
fn back_faces_hidden<K: Kernel<Color = Rgb565> + Copy, P: Projection>(
    w: u32,
    t: &MeshTransform<P>,
    k: K,
) -> (usize, usize) {
    let back = mesh_frame(
        w,
        w,
        w,
        SPHERE.mesh(),
        t,
        k,
        Cull::Back,
        false,
        Rgb565::BLACK,
    );
    let none = mesh_frame(
        w,
        w,
        w,
        SPHERE.mesh(),
        t,
        k,
        Cull::None,
        false,
        Rgb565::BLACK,
    );
    let front: Vec<usize> = (0..back.len())
        .filter(|&i| back[i] != Rgb565::BLACK)
        .collect();
    let bad = front.iter().filter(|&&i| none[i] != back[i]).count();
    (bad, front.len())
}

/// The depth-plane regression. The old bug: a triangle whose depth plane's
/// error bound could leave 0..65535 (`zclamp`: the edge-on slivers along the
/// silhouette) had its depth clamped per run to the plane's vertex range —
/// kept relative to the top vertex (around 0) while the depth values were
/// absolute, so its depths were squeezed towards 0 (the near plane) and won
/// every depth test: with `Cull::None` the back triangles along the outline
/// showed through the front ones. Fixed by making the clamp range absolute
/// together with the values (`Plane::absolute` in `src/raster/setup.rs`).
/// The test compares, on every pixel where the front surface is visible,
/// the frame without culling to the frame with back faces culled; on the old
/// code the squeezed back triangles differ there. (Checked: with the depth
/// plane's `lo`/`hi` left relative while its values are made absolute — the
/// old `draw` — 809 of the 32 480 front pixels of the general Phong frame
/// show a back face and this test fails.)
#[test]
fn no_back_face_wins_over_the_front_surface() {
    let t = standard::transform().unwrap();
    let blinn = standard::blinn::<Q14>().unwrap();
    let blinn_f32 = standard::blinn::<f32>().unwrap();
    let (bad, n) = back_faces_hidden(W, &t, Shader::new(PhongShading, &blinn, Linear));
    assert!(n > 32_000, "{n}");
    assert_eq!(
        bad, 0,
        "general phong (Q14): {bad} of {n} front pixels show a back face"
    );
    let (bad, n) = back_faces_hidden(W, &t, Shader::new(PhongShading, &blinn_f32, Linear));
    assert_eq!(
        bad, 0,
        "general phong (f32): {bad} of {n} front pixels show a back face"
    );
    let (bad, n) = back_faces_hidden(W, &t, Shader::new(GouraudShading, &blinn, Linear));
    assert_eq!(
        bad, 0,
        "gouraud: {bad} of {n} front pixels show a back face"
    );
}

/// The same on a perspective camera so close that the near plane cuts the
/// sphere's front open: through the hole the inside (back faces) is
/// visible, but wherever a front face remains it is nearer than any back
/// face.
#[test]
fn no_back_face_wins_over_the_front_surface_in_perspective() {
    let blinn = standard::blinn::<Q14>().unwrap();
    let cam = Camera::perspective(1.2, 1.0, 1.0, 20.0, Viewport::new(0, 0, W, W).unwrap())
        .unwrap()
        .with_view(Mat4::translate([0.2, -0.1, -1.9]));
    let t = cam
        .mesh_transform(&Mat4::rotate_y(0.4).mul(&Mat4::rotate_x(0.3)), SPHERE.frac)
        .unwrap();
    assert!(
        SPHERE
            .mesh()
            .positions()
            .iter()
            .any(|&p| t.project(p).is_none()),
        "the near plane cuts the sphere"
    );
    let (bad, n) = back_faces_hidden(W, &t, Shader::new(GouraudShading, &blinn, Linear));
    assert!(n > 10_000, "{n}");
    assert_eq!(
        bad, 0,
        "perspective gouraud: {bad} of {n} front pixels show a back face"
    );
    let (bad, n) = back_faces_hidden(W, &t, Shader::new(PhongShading, &blinn, Linear));
    assert_eq!(
        bad, 0,
        "perspective phong: {bad} of {n} front pixels show a back face"
    );
    let (bad, n) = back_faces_hidden(W, &t, Shader::new(PhongShading, &blinn, Linear));
    assert_eq!(
        bad, 0,
        "perspective general phong: {bad} of {n} front pixels show a back face"
    );
}
