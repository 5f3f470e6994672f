//! Sphere generators and vertex normals: geometry, topology, winding, accuracy.

use fixshade::error::MeshError;
use fixshade::mesh::*;
use fixshade::num::Scalar;
use std::collections::HashMap;

type Mesh = (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<[u16; 3]>);

/// The UV sphere of `stacks × slices` (the one generator, `MeshData::uv_sphere`,
/// Q14 positions and normals) at centre `c` with radius `r`, in `f32`.
macro_rules! uv {
    ($stacks:literal, $slices:literal, $c:expr, $r:expr) => {{
        const N: (usize, usize) = uv_sphere_counts($stacks, $slices);
        static S: MeshData<{ N.0 }, { N.1 }> = MeshData::uv_sphere($stacks, $slices, 14);
        let (m, c, r): (_, [f32; 3], f32) = (S.mesh(), $c, $r);
        let p = (0..N.0)
            .map(|i| m.position(i).unwrap().map(|v| v * r))
            .map(|q| [q[0] + c[0], q[1] + c[1], q[2] + c[2]])
            .collect();
        let n = (0..N.0).map(|i| m.normal(i).unwrap()).collect();
        (p, n, S.triangles.to_vec()) as Mesh
    }};
}

/// The largest distance from the sphere, relative to the radius, of a Q14
/// vertex (a unit vector rounded per component to 2^-15, and `f32`).
const Q14_POSITION: f32 = 1.1e-4;

fn ico(level: u32, c: [f32; 3], r: f32) -> Mesh {
    let (nv, nt) = icosphere_counts(level);
    let (mut p, mut n, mut t) = (vec![[0.0; 3]; nv], vec![[0.0; 3]; nv], vec![[0; 3]; nt]);
    assert_eq!(icosphere(level, c, r, &mut p, &mut n, &mut t), Ok((nv, nt)));
    (p, n, t)
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| f64::from(a[i]) - f64::from(b[i]))
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Every vertex at distance r with the exact normal, every triangle outward and
/// non-degenerate, every edge shared by exactly two triangles in opposite
/// directions, every vertex used.
/// Vertices within `tol`·max(r, 1) of the sphere, normals within `tol` of
/// unit length and of the exact normal (`1e-5`: `f32` generators; Q14 ones
/// [`Q14_POSITION`]).
fn check_sphere((p, n, t): &Mesh, c: [f32; 3], r: f32, tol: f32) {
    let tol = f64::from(tol);
    for (pi, ni) in p.iter().zip(n) {
        let d = sub(*pi, c);
        let len = dot(d, d).sqrt();
        assert!(
            (len - f64::from(r)).abs() < tol * f64::from(r.max(1.0)) * 4.0,
            "{pi:?} {len}"
        );
        let nl = dot(ni.map(f64::from), ni.map(f64::from)).sqrt();
        assert!((nl - 1.0).abs() < tol.max(1e-6));
        for k in 0..3 {
            assert!(
                (d[k] / len - f64::from(ni[k])).abs() < tol * 2.0,
                "{pi:?} {ni:?}"
            );
        }
    }
    let mut edges: HashMap<(u16, u16), usize> = HashMap::new();
    let mut used = vec![false; p.len()];
    for tri in t {
        let g = cross(
            sub(p[tri[1] as usize], p[tri[0] as usize]),
            sub(p[tri[2] as usize], p[tri[0] as usize]),
        );
        let centroid = [0, 1, 2].map(|k| {
            (0..3)
                .map(|i| f64::from(p[tri[i] as usize][k]))
                .sum::<f64>()
                / 3.0
        });
        let out = sub(centroid.map(|v| v as f32), c);
        assert!(dot(g, out) > 0.0, "inward triangle {tri:?}");
        for k in 0..3 {
            used[tri[k] as usize] = true;
            *edges.entry((tri[k], tri[(k + 1) % 3])).or_default() += 1;
        }
    }
    assert!(used.iter().all(|&u| u), "unused vertex");
    for (&(a, b), &count) in &edges {
        assert_eq!(count, 1, "directed edge {a}->{b} used {count} times");
        assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}-{b} is open");
    }
    // Euler characteristic of a sphere: V − E + F = 2
    assert_eq!(
        p.len() as i64 - (edges.len() / 2) as i64 + t.len() as i64,
        2
    );
}

#[test]
fn uv_spheres_are_closed_outward_and_exact() {
    for (c, r) in [
        ([0.0; 3], 1.0),
        ([3.0, -2.0, 10.0], 0.25),
        ([-100.0, 0.0, 5.0], 40.0),
    ] {
        for m in [
            uv!(2, 3, c, r),
            uv!(3, 4, c, r),
            uv!(8, 16, c, r),
            uv!(17, 5, c, r),
            uv!(40, 80, c, r),
        ] {
            check_sphere(&m, c, r, Q14_POSITION);
        }
    }
}

#[test]
fn icospheres_are_closed_outward_and_exact() {
    // 4: the highest level `icosphere` accepts
    for level in 0..=4 {
        for (c, r) in [([0.0; 3], 1.0), ([3.0, -2.0, 10.0], 0.25)] {
            check_sphere(&ico(level, c, r), c, r, 1e-5);
        }
    }
}

/// Largest angle in degrees between computed vertex normals and the exact ones.
fn max_angle_error((p, exact, t): &Mesh, w: Weighting) -> f64 {
    let mut n = vec![[9.0f32; 3]; p.len()];
    assert_eq!(vertex_normals(p, t, w, &mut n), Ok(p.len()));
    n.iter()
        .zip(exact)
        .map(|(a, b)| {
            let c = dot(a.map(f64::from), b.map(f64::from)).clamp(-1.0, 1.0);
            c.acos().to_degrees()
        })
        .fold(0.0, f64::max)
}

#[test]
fn sphere_vertex_normals_converge_to_exact() {
    for w in [Weighting::Area, Weighting::Angle] {
        // icospheres: level 1 is symmetric about every vertex (nearly exact); from
        // level 2 on the error halves with each level (first order in edge length)
        let e: Vec<f64> = (1..=4)
            .map(|l| max_angle_error(&ico(l, [1.0, 2.0, 3.0], 2.0), w))
            .collect();
        assert!(e[0] < 0.1 && e[1] < 1.5, "{w:?} {e:?}");
        assert!(
            e[2] < 0.6 * e[1] && e[3] < 0.6 * e[2] && e[3] < 0.4,
            "{w:?} {e:?}"
        );
        // UV spheres (stacks = k, slices = 2k): the error halves as k doubles
        // (up to k = 16: beyond, the Q14 positions of the one generator, 6·10⁻⁵
        // apart, are a visible part of the polar triangles' 0.01-long edges)
        let c = [0.0; 3];
        let e: Vec<f64> = [uv!(4, 8, c, 1.0), uv!(8, 16, c, 1.0), uv!(16, 32, c, 1.0)]
            .iter()
            .map(|m| max_angle_error(m, w))
            .collect();
        assert!(e.windows(2).all(|p| p[1] < 0.6 * p[0]), "{w:?} {e:?}");
        // (the old bound at k = 32 was 1°: 2° at k = 16 at the halving rate)
        assert!(e[0] < 10.0 && e[2] < 2.0, "{w:?} {e:?}");
    }
}

#[test]
fn face_normals_of_a_sphere_point_outwards() {
    let (p, _, t) = ico(2, [0.0, 0.0, -4.0], 1.0);
    let mut f = vec![[0.0f32; 3]; t.len()];
    assert_eq!(face_normals(&p, &t, &mut f), Ok(t.len()));
    for (fi, tri) in f.iter().zip(&t) {
        let out = sub(p[tri[0] as usize], [0.0, 0.0, -4.0]);
        assert!(dot(fi.map(f64::from), out) > 0.9, "{fi:?}");
    }
    assert_eq!(
        face_normals(&p, &t, &mut f[..10]),
        Err(MeshError::BufferTooSmall {
            which: "out",
            needed: t.len(),
            got: 10
        })
    );
}

#[test]
fn cube_vertex_normals_by_angle_are_diagonals() {
    // 8 shared corners, two triangles per face, counter-clockwise from outside
    let p: Vec<[f32; 3]> = (0..8)
        .map(|i| [i & 1, i & 2, i & 4].map(|b| if b != 0 { 1.0 } else { -1.0 }))
        .collect();
    let t: [[u16; 3]; 12] = [
        [0, 2, 3],
        [0, 3, 1],
        [4, 5, 7],
        [4, 7, 6],
        [0, 1, 5],
        [0, 5, 4],
        [2, 6, 7],
        [2, 7, 3],
        [0, 4, 6],
        [0, 6, 2],
        [1, 3, 7],
        [1, 7, 5],
    ];
    let mut n = [[0.0f32; 3]; 8];
    vertex_normals(&p, &t, Weighting::Angle, &mut n).unwrap();
    let k = 3.0f32.sqrt().recip();
    for (v, nv) in p.iter().zip(&n) {
        assert!(
            (0..3).all(|a| (nv[a] - v[a] * k).abs() < 1e-6),
            "{v:?} {nv:?}"
        );
    }
    // to a tier
    let q = fixshade::num::Vec3::<fixshade::num::Q14>::from_f32(n[7]);
    assert!((q.x.to_f32() - k).abs() < 1e-4);
}
