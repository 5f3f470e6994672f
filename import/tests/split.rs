//! Models over the renderer's limits: the message names the file, its counts,
//! the limit and `--split`; `--split` cuts them into parts that each fit and
//! together hold every triangle, with the normals of one surface.

mod common;

use std::collections::{BTreeSet, HashMap};

use fixshade_import::process::{MAX_TRIANGLES, MAX_VERTICES};
use fixshade_import::{import, Error, Options};

/// Vertices a side of the grid: 300 × 300 = 90 000 vertices, 299 × 299 quads,
/// 178 802 triangles (the size of the example).
const N: usize = 300;

/// A gently waving square grid as OBJ text, quads counter-clockwise from +z,
/// no normals (the importer computes them: 90 000 smoothing vertices, more
/// than one call of the library's `vertex_normals` takes).
fn grid() -> String {
    let mut s = String::with_capacity(6_000_000);
    for j in 0..N {
        for i in 0..N {
            let (x, y) = (
                i as f64 / (N - 1) as f64 * 2.0 - 1.0,
                j as f64 / (N - 1) as f64 * 2.0 - 1.0,
            );
            let z = 0.05 * (3.0 * x).sin() * (3.0 * y).cos();
            s += &format!("v {x:.5} {y:.5} {z:.5}\n");
        }
    }
    for j in 0..N - 1 {
        for i in 0..N - 1 {
            let v = |i: usize, j: usize| j * N + i + 1;
            s += &format!(
                "f {} {} {} {}\n",
                v(i, j),
                v(i + 1, j),
                v(i + 1, j + 1),
                v(i, j + 1)
            );
        }
    }
    s
}

#[test]
fn over_the_limit_the_message_names_the_file_the_counts_and_split() {
    let dir = common::scratch("split_limit");
    let p = common::write(&dir, "grid.obj", grid());
    let e = import(&p, &Options::new("GRID")).unwrap_err();
    assert!(
        matches!(
            e,
            Error::TooManyTriangles {
                count: 178_802,
                positions: 90_000,
                material: None,
                ..
            }
        ),
        "{e}"
    );
    assert_eq!(
        e.to_string(),
        format!(
            "{}: 178802 triangles (90000 positions): more than the 65535 triangles the \
             renderer's u16 bins address; pass --split to cut the model into parts of at most \
             65535 vertices and 65535 triangles each",
            p.display()
        )
    );
}

#[test]
fn split_parts_fit_and_hold_every_triangle_with_one_surface_of_normals() {
    let dir = common::scratch("split");
    let p = common::write(&dir, "grid.obj", grid());
    let mut o = Options::new("GRID");
    o.process.split = true;
    let m = import(&p, &o).unwrap();
    let sizes: Vec<(usize, usize)> = m
        .parts
        .iter()
        .map(|p| (p.mesh.positions.len(), p.mesh.triangles.len()))
        .collect();
    eprintln!("{sizes:?}");
    assert_eq!(m.parts.len(), 3);
    for &(v, t) in &sizes {
        assert!(
            v <= MAX_VERTICES && t <= MAX_TRIANGLES,
            "{v} vertices, {t} triangles"
        );
    }
    assert_eq!(sizes.iter().map(|s| s.1).sum::<usize>(), 178_802);
    assert_eq!(m.report.triangles, 178_802);
    assert_eq!(m.report.smoothing_vertices, 90_000);
    // every triangle of the file, once: as (lowest position, next, next)
    // counter-clockwise, in model-unit-free quantised positions
    let mut got = BTreeSet::new();
    for part in &m.parts {
        let q = &part.mesh.positions;
        for t in &part.mesh.triangles {
            let c = t.map(|i| q[usize::from(i)]);
            let k = (0..3).min_by_key(|&k| c[k]).unwrap();
            assert!(got.insert([c[k], c[(k + 1) % 3], c[(k + 2) % 3]]), "twice");
        }
    }
    assert_eq!(got.len(), 178_802);
    // the quads' two triangles, from the file's own positions, rounded
    let step = m.report.step;
    let positions: Vec<[i16; 3]> = grid()
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            [0, 1, 2].map(|k| (v[k] / step).round() as i16)
        })
        .collect();
    let mut expected = BTreeSet::new();
    for j in 0..N - 1 {
        for i in 0..N - 1 {
            let v = |i: usize, j: usize| positions[j * N + i];
            let quad = [v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)];
            for c in [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]] {
                let k = (0..3).min_by_key(|&k| c[k]).unwrap();
                expected.insert([c[k], c[(k + 1) % 3], c[(k + 2) % 3]]);
            }
        }
    }
    assert_eq!(got, expected);
    // one surface: a position cut between parts has the same normal in each
    // (normals are computed on the whole model before the cut)
    let mut normal_at: HashMap<[i16; 3], [i16; 3]> = HashMap::new();
    let mut shared = 0;
    for part in &m.parts {
        for (p, n) in part.mesh.positions.iter().zip(&part.mesh.normals) {
            if let Some(old) = normal_at.insert(*p, *n) {
                assert_eq!(old, *n, "at {p:?}");
                shared += 1;
            }
            assert!(n[2] > 15_000, "{n:?}");
        }
    }
    assert!(shared >= 2 * (N - 1), "{shared} positions on the cuts");
    // emitted like the parts of several materials
    let src = m.to_rust();
    assert!(src.contains("pub const GRID_PART_COUNT: usize = 3;"));
    assert!(src.contains(&format!(
        "pub const GRID_MAX_TRIANGLES: usize = {};",
        sizes.iter().map(|s| s.1).max().unwrap()
    )));
    assert!(src.contains("pub static GRID_PART2: ::fixshade::mesh::Mesh<'static>"));
    assert!(m.summary().contains("in 3 parts"));
}
