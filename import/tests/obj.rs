//! Wavefront OBJ import against the file: positions, normals (face averages,
//! smoothing groups, crease angle), winding, texture coordinates, welding,
//! triangulation, and every error case.

mod common;

use std::path::Path;

use common::{asset, cube_obj, scratch, write};
use fixshade_import::{
    import, Error, FileKind, NormalSource, Options, Orientation, TextureChoice, Weighting,
};

fn opts() -> Options {
    Options::new("M")
}

fn obj(dir: &Path, text: &str) -> std::path::PathBuf {
    write(dir, "m.obj", text)
}

/// `(x, y, z)` of every `v` line and `(u, v)` of every `vt` line, parsed
/// here (not through tobj).
fn file_lists(text: &str) -> (Vec<[f64; 3]>, Vec<[f64; 2]>) {
    let (mut v, mut vt) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        let num = |k: usize| w[k].parse::<f32>().unwrap() as f64;
        match w.first() {
            Some(&"v") => v.push([num(1), num(2), num(3)]),
            Some(&"vt") => vt.push([num(1), num(2)]),
            _ => {}
        }
    }
    (v, vt)
}

fn dequant(m: &fixshade_import::CompactMesh, i: usize) -> [f64; 3] {
    m.positions[i].map(|x| f64::from(x) * m.step())
}

fn signed_volume(m: &fixshade_import::CompactMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| dequant(m, usize::from(i)));
            let cross = [
                b[1] * c[2] - b[2] * c[1],
                b[2] * c[0] - b[0] * c[2],
                b[0] * c[1] - b[1] * c[0],
            ];
            (a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2]) / 6.0
        })
        .sum()
}

#[test]
fn positions_are_within_half_a_step_of_the_file() {
    let text = std::fs::read_to_string(asset("rocket.obj")).unwrap();
    let (file, _) = file_lists(&text);
    let model = import(&asset("rocket.obj"), &opts()).unwrap();
    let m = model.mesh();
    // the largest coordinate is 1.2: frac 14 (1.2 · 2^14 = 19661 fits, 2^15 does not)
    assert_eq!(m.frac, 14);
    assert_eq!(model.report.step, 1.0 / 16384.0);
    let half = 0.5 * m.step() + 1e-12;
    // every vertex is within half a step of a file position, and every file
    // position has a vertex within half a step
    let near = |p: [f64; 3], q: [f64; 3]| (0..3).all(|k| (p[k] - q[k]).abs() <= half);
    for i in 0..m.positions.len() {
        let p = dequant(m, i);
        assert!(file.iter().any(|&q| near(p, q)), "vertex {i} {p:?}");
    }
    for q in &file {
        assert!(
            (0..m.positions.len()).any(|i| near(dequant(m, i), *q)),
            "{q:?}"
        );
    }
    assert!(model.report.max_position_error <= 0.5 * m.step());
}

#[test]
fn frac_is_chosen_from_the_bounds() {
    let dir = scratch("frac");
    // largest |coordinate| 100: 100 · 2^8 = 25600 fits an i16, 2^9 does not
    let p = obj(&dir, "v 0 0 0\nv 100 0 0\nv 0 -37.3 0\nf 1 2 3\n");
    let model = import(&p, &opts()).unwrap();
    assert_eq!(model.mesh().frac, 8);
    assert!(model.mesh().positions.contains(&[25600, 0, 0]));
    assert!(model
        .mesh()
        .positions
        .contains(&[0, (-37.3f32 as f64 * 256.0).round() as i16, 0]));
    assert!(model.to_rust().contains("pub const M_FRAC: u8 = 8;"));
    // centred and scaled on request: [0, 100] × [−37.3, 0] → ±0.5 × ±0.1865
    let mut o = opts();
    o.process.center = true;
    o.process.scale = 0.01;
    let model = import(&p, &o).unwrap();
    assert_eq!(model.mesh().frac, 15);
    assert!((model.report.bounds[1][0] - 0.5).abs() < 1e-9);
    // a fixed frac: smaller is fine, larger than fits is an error
    let mut o = opts();
    o.process.frac = Some(4);
    assert_eq!(import(&p, &o).unwrap().mesh().frac, 4);
    o.process.frac = Some(9);
    let e = import(&p, &o).unwrap_err();
    assert!(
        matches!(
            e,
            Error::FracTooLarge {
                frac: 9,
                max_fitting: 8
            }
        ),
        "{e}"
    );
    // beyond an i16 even at frac 0
    let p = obj(&dir, "v 0 0 0\nv 40000 0 0\nv 0 1 0\nf 1 2 3\n");
    assert!(matches!(
        import(&p, &opts()),
        Err(Error::PositionRange { .. })
    ));
}

/// A bumpy closed surface (a lathe with irregular radii), no normals in the
/// file; its vertex normals against an independent face-average computation.
#[test]
fn computed_normals_match_an_independent_face_average() {
    let dir = scratch("normals");
    let (rings, slices) = (7usize, 9usize);
    let mut text = String::new();
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
        (seed >> 40) as f64 / (1u64 << 24) as f64
    };
    text += "v 0 1.3 0\n";
    for i in 1..rings {
        for j in 0..slices {
            let a = 2.0 * std::f64::consts::PI * j as f64 / slices as f64;
            let r = 0.6 + 0.4 * rnd();
            let y = 1.3 - 2.6 * i as f64 / rings as f64 + 0.1 * rnd();
            text += &format!("v {:.6} {:.6} {:.6}\n", r * a.sin(), y, r * a.cos());
        }
    }
    text += "v 0 -1.3 0\n";
    let ring = |i: usize, j: usize| 2 + (i - 1) * slices + j % slices;
    let south = 2 + (rings - 1) * slices;
    let mut faces = Vec::new();
    for j in 0..slices {
        faces.push([1, ring(1, j), ring(1, j + 1)]);
        for i in 1..rings - 1 {
            faces.push([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)]);
            faces.push([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
        }
        faces.push([south, ring(rings - 1, j + 1), ring(rings - 1, j)]);
    }
    for f in &faces {
        text += &format!("f {} {} {}\n", f[0], f[1], f[2]);
    }
    let p = obj(&dir, &text);
    let (pos, _) = file_lists(&text);
    for weighting in [Weighting::Angle, Weighting::Area] {
        let mut o = opts();
        o.process.crease_angle = Some(180.0); // one normal per position
        o.process.weighting = weighting;
        let model = import(&p, &o).unwrap();
        let m = model.mesh();
        assert_eq!(m.positions.len(), pos.len());
        assert_eq!(model.report.normals, NormalSource::CreaseAngle(180.0));
        // the independent sums, in f64 on the file's positions
        let mut sum = vec![[0.0f64; 3]; pos.len()];
        for f in &faces {
            let v = f.map(|i| pos[i - 1]);
            let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            let cross = |a: [f64; 3], b: [f64; 3]| {
                [
                    a[1] * b[2] - a[2] * b[1],
                    a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0],
                ]
            };
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let c = cross(sub(v[1], v[0]), sub(v[2], v[0]));
            let len = dot(c, c).sqrt();
            for k in 0..3 {
                let w = match weighting {
                    Weighting::Area => 1.0,
                    _ => {
                        let (e1, e2) = (sub(v[(k + 1) % 3], v[k]), sub(v[(k + 2) % 3], v[k]));
                        let x = cross(e1, e2);
                        dot(x, x).sqrt().atan2(dot(e1, e2)) / len
                    }
                };
                for a in 0..3 {
                    sum[f[k] - 1][a] += w * c[a];
                }
            }
        }
        for (i, q) in pos.iter().enumerate() {
            let s = sum[i];
            let l = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            let want = s.map(|x| x / l);
            let v = (0..m.positions.len())
                .find(|&v| (0..3).all(|k| (dequant(m, v)[k] - q[k]).abs() <= m.step()))
                .unwrap();
            let got = m.normals[v].map(|x| f64::from(x) / 16384.0);
            for k in 0..3 {
                // Q14 rounding plus the positions' quantisation
                assert!(
                    (got[k] - want[k]).abs() < 1.5e-3,
                    "{weighting:?} {i}: {got:?} {want:?}"
                );
            }
        }
    }
}

fn cube(smoothing: &str, options: &Options) -> fixshade_import::Model {
    let dir = scratch(&format!("cube{}", smoothing.replace(' ', "_")));
    import(&obj(&dir, &cube_obj(smoothing)), options).unwrap()
}

#[test]
fn smoothing_groups_and_creases_split_the_cube_as_expected() {
    // hard edges: 6 faces × 4 corners
    assert_eq!(cube("s off", &opts()).mesh().positions.len(), 24);
    // no groups: the default crease angle (60°) splits at the 90° edges
    let m = cube("", &opts());
    assert_eq!(m.mesh().positions.len(), 24);
    assert_eq!(m.report.normals, NormalSource::CreaseAngle(60.0));
    // one smoothing group: 8 vertices, normals along the diagonals
    let m = cube("s 1", &opts());
    assert_eq!(m.mesh().positions.len(), 8);
    assert_eq!(m.report.normals, NormalSource::SmoothingGroups);
    let d = (16384.0 / 3f64.sqrt()).round() as i16;
    for (p, n) in m.mesh().positions.iter().zip(&m.mesh().normals) {
        assert_eq!(*n, p.map(|c| d * c.signum()), "{p:?}");
    }
    // a crease angle above 90°: smooth too; given, it overrides the groups
    let mut o = opts();
    o.process.crease_angle = Some(100.0);
    assert_eq!(cube("", &o).mesh().positions.len(), 8);
    o.process.crease_angle = Some(30.0);
    assert_eq!(cube("s 1", &o).mesh().positions.len(), 24);
    // two groups: sides in one, top and bottom in another: 2 per corner
    let dir = scratch("cube_two_groups");
    let text = cube_obj("s 1")
        .replacen("s 1\nf 3 7 8 4", "s 2\nf 3 7 8 4", 1)
        .replacen("s 1\nf 1 2 6 5", "s 2\nf 1 2 6 5", 1);
    let m = import(&obj(&dir, &text), &opts()).unwrap();
    assert_eq!(m.mesh().positions.len(), 16);
}

#[test]
fn file_normals_are_kept() {
    let dir = scratch("file_normals");
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0.6 0 0.8\nf 1//1 2//2 3//1\n";
    let m = import(&obj(&dir, text), &opts()).unwrap();
    assert_eq!(m.report.normals, NormalSource::File);
    assert_eq!(
        m.mesh().normals,
        [[0, 0, 16384], [9830, 0, 13107], [0, 0, 16384]]
    );
    let mut o = opts();
    o.process.recompute_normals = true;
    let m = import(&obj(&dir, text), &o).unwrap();
    assert_eq!(m.mesh().normals, [[0, 0, 16384]; 3]);
}

#[test]
fn winding_is_kept_counter_clockwise_from_outside() {
    let model = import(&asset("rocket.obj"), &opts()).unwrap();
    let v = signed_volume(model.mesh());
    // the body alone is about π · 0.35² · 2 ≈ 0.77
    assert!(v > 0.5 && v < 1.2, "volume {v}");
    // on the hard-edged cube every face normal points outwards and agrees
    // with its vertices' normals
    let model = cube("s off", &opts());
    let m = model.mesh();
    assert!((signed_volume(m) - 8.0).abs() < 1e-9);
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| dequant(m, usize::from(i)));
        let n = [
            (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
            (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]),
        ];
        let centre = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
        assert!(n[0] * centre[0] + n[1] * centre[1] + n[2] * centre[2] > 0.0);
        let vn = m.normals[usize::from(t[0])].map(f64::from);
        assert!(n[0] * vn[0] + n[1] * vn[1] + n[2] * vn[2] > 0.0);
    }
    // a file wound inside out stays inside out (the importer does not "fix" it)
    let dir = scratch("inside_out");
    let reversed: String = cube_obj("s off")
        .lines()
        .map(|l| match l.strip_prefix("f ") {
            Some(f) => {
                let mut c: Vec<&str> = f.split_whitespace().collect();
                c.reverse();
                format!("f {}\n", c.join(" "))
            }
            None => format!("{l}\n"),
        })
        .collect();
    let m = import(&obj(&dir, &reversed), &opts()).unwrap();
    assert!((signed_volume(m.mesh()) + 8.0).abs() < 1e-9);
}

/// `cube_obj`'s cube (`s off`), each face reversed when `clockwise`, with a
/// normal per face (`vn`, outward times `normal_sign`) when `normal_sign` is
/// not 0.
fn cube_with(clockwise: bool, normal_sign: i32) -> String {
    let mut s = String::new();
    for i in 0..8 {
        let c = |bit: usize| if i & bit != 0 { 1 } else { -1 };
        s += &format!("v {} {} {}\n", c(1), c(2), c(4));
    }
    let faces = [
        ([1, 3, 4, 2], [0, 0, -1]),
        ([5, 6, 8, 7], [0, 0, 1]),
        ([1, 2, 6, 5], [0, -1, 0]),
        ([3, 7, 8, 4], [0, 1, 0]),
        ([1, 5, 7, 3], [-1, 0, 0]),
        ([2, 4, 8, 6], [1, 0, 0]),
    ];
    for (_, n) in faces {
        s += &format!(
            "vn {} {} {}\n",
            n[0] * normal_sign,
            n[1] * normal_sign,
            n[2] * normal_sign
        );
    }
    s += "s off\n";
    for (k, (mut f, _)) in faces.into_iter().enumerate() {
        if clockwise {
            f.reverse();
        }
        let corner = |v: usize| {
            if normal_sign == 0 {
                format!("{v}")
            } else {
                format!("{v}//{}", k + 1)
            }
        };
        s += &format!("f {}\n", f.map(corner).join(" "));
    }
    s
}

/// Every vertex normal agrees with its triangle's face normal, and both
/// point away from the centre.
fn normals_point_outward(m: &fixshade_import::CompactMesh) -> bool {
    m.triangles.iter().all(|t| {
        let [a, b, c] = t.map(|i| dequant(m, usize::from(i)));
        let n = [
            (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
            (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]),
        ];
        let centre = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
        let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        dot(n, centre) > 0.0
            && t.iter()
                .all(|&i| dot(n, m.normals[usize::from(i)].map(f64::from)) > 0.0)
    })
}

fn flip() -> Options {
    let mut o = opts();
    o.process.flip_winding = true;
    o
}

#[test]
fn a_clockwise_cube_warns_and_flip_winding_turns_it_outward() {
    let dir = scratch("clockwise");
    let p = obj(&dir, &cube_with(true, 0));
    let m = import(&p, &opts()).unwrap();
    assert!(
        matches!(m.report.orientation, Orientation::Closed { volume } if (volume + 8.0).abs() < 1e-9)
    );
    assert_eq!(
        m.warnings,
        [
            "wound clockwise from outside (signed volume -8.0000): renders inside-out; \
          pass --flip-winding"
        ]
    );
    assert!(m.summary().contains(
        "orientation: closed, signed volume -8.0000 (clockwise from outside: inside-out)"
    ));
    // --flip-winding: every triangle reversed, the volume positive, the
    // computed normals outward, no warning
    let m = import(&p, &flip()).unwrap();
    assert!(
        matches!(m.report.orientation, Orientation::Closed { volume } if (volume - 8.0).abs() < 1e-9)
    );
    assert!((signed_volume(m.mesh()) - 8.0).abs() < 1e-9);
    assert!(normals_point_outward(m.mesh()));
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    assert!(m.report.winding_flipped && !m.report.file_normals_negated);
    assert!(m.to_rust().contains("--flip-winding"));
    // --flip-winding on a cube that was right: the warning says so
    let m = import(&obj(&dir, &cube_with(false, 0)), &flip()).unwrap();
    assert!(
        m.warnings[0].contains("after --flip-winding"),
        "{:?}",
        m.warnings
    );
}

#[test]
fn flip_winding_turns_inward_file_normals_and_keeps_outward_ones() {
    let dir = scratch("clockwise_normals");
    // clockwise, its normals inward too (a mirrored export): both turned
    let m = import(&obj(&dir, &cube_with(true, -1)), &flip()).unwrap();
    assert_eq!(m.report.normals, NormalSource::File);
    assert!(m.report.file_normals_negated);
    assert!(normals_point_outward(m.mesh()));
    assert!((signed_volume(m.mesh()) - 8.0).abs() < 1e-9);
    assert!(m
        .summary()
        .contains("the file's normals negated with the winding"));
    // clockwise, its normals outward (only the winding wrong): normals kept
    let m = import(&obj(&dir, &cube_with(true, 1)), &flip()).unwrap();
    assert!(!m.report.file_normals_negated);
    assert!(normals_point_outward(m.mesh()));
    // without --flip-winding the file's normals are never touched
    let m = import(&obj(&dir, &cube_with(true, -1)), &opts()).unwrap();
    assert!(m.mesh().normals.contains(&[0, 0, 16384])); // the -z face's, inward
}

#[test]
fn open_and_inconsistent_meshes() {
    let dir = scratch("open");
    // a cube without its last face: open, not checked, no warning
    let text = cube_with(true, 0);
    let open: String = text
        .lines()
        .take(text.lines().count() - 1)
        .map(|l| format!("{l}\n"))
        .collect();
    let m = import(&obj(&dir, &open), &opts()).unwrap();
    assert_eq!(m.report.orientation, Orientation::Open { edges: 4 });
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    assert!(m.summary().contains("winding not checked"));
    // one face turned against the others: closed, inconsistent
    let mut lines: Vec<String> = cube_with(false, 0).lines().map(String::from).collect();
    let last = lines.len() - 1;
    let mut f: Vec<&str> = lines[last].split_whitespace().skip(1).collect();
    f.reverse();
    lines[last] = format!("f {}", f.join(" "));
    let m = import(&obj(&dir, &(lines.join("\n") + "\n")), &opts()).unwrap();
    assert_eq!(m.report.orientation, Orientation::Inconsistent { edges: 4 });
    assert!(
        m.warnings[0].contains("4 edges run the same way"),
        "{:?}",
        m.warnings
    );
}

#[test]
fn texture_coordinates_are_within_half_a_q12_step() {
    let dir = scratch("texcoords");
    let text =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.1 0.2\nvt 0.3337 -2.5\nvt 7.99 0.123456\nf 1/1 2/2 3/3\n";
    let m = import(&obj(&dir, text), &opts()).unwrap();
    let uv = m.mesh().texcoords.as_ref().unwrap();
    let (_, vt) = file_lists(text);
    for (q, t) in uv.iter().zip(&vt) {
        // OBJ's v runs up, fixshade's down: 1 − v
        let want = [t[0], 1.0 - t[1]];
        for k in 0..2 {
            let got = f64::from(q[k]) / 4096.0;
            assert!(
                (got - want[k]).abs() <= 0.5 / 4096.0 + 1e-9,
                "{got} {}",
                want[k]
            );
        }
    }
    assert_eq!(uv[0], [410, 3277]); // round(0.1 · 4096), round(0.8 · 4096)
    assert!(m.report.max_texcoord_error.unwrap() <= 0.5 / 4096.0 + 1e-9);
    // on the asset: every emitted coordinate is near a file coordinate
    let text = std::fs::read_to_string(asset("rocket.obj")).unwrap();
    let (_, vt) = file_lists(&text);
    let model = import(&asset("rocket.obj"), &opts()).unwrap();
    for q in model.mesh().texcoords.as_ref().unwrap() {
        let got = q.map(|x| f64::from(x) / 4096.0);
        assert!(vt.iter().any(|t| {
            (got[0] - t[0]).abs() <= 0.5 / 4096.0 + 1e-7
                && (got[1] - (1.0 - t[1])).abs() <= 0.5 / 4096.0 + 1e-7
        }));
    }
    // beyond ±8 repeats
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 8.5 0\nvt 0 1\nf 1/1 2/2 3/3\n";
    let e = import(&obj(&dir, text), &opts()).unwrap_err();
    assert!(
        matches!(e, Error::TexcoordRange { value } if value == 8.5),
        "{e}"
    );
}

#[test]
fn duplicated_corners_are_welded() {
    let dir = scratch("weld");
    // a quad as two triangles, its shared corners written twice
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n";
    let m = import(&obj(&dir, text), &opts()).unwrap();
    assert_eq!(m.mesh().positions.len(), 4);
    assert_eq!(m.mesh().triangles, [[0, 1, 2], [0, 2, 3]]);
    // positions closer than half a step weld too (same quantised position)
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.00001 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n";
    assert_eq!(
        import(&obj(&dir, text), &opts())
            .unwrap()
            .mesh()
            .positions
            .len(),
        4
    );
    // the same corners with texture coordinates: equal ones weld, a seam does not
    let base = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n";
    let welded = format!("{base}f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    assert_eq!(
        import(&obj(&dir, &welded), &opts())
            .unwrap()
            .mesh()
            .positions
            .len(),
        4
    );
    let seam = format!("{base}f 1/1 2/2 3/3\nf 1/5 3/3 4/4\n");
    assert_eq!(
        import(&obj(&dir, &seam), &opts())
            .unwrap()
            .mesh()
            .positions
            .len(),
        5
    );
}

#[test]
fn a_pentagon_is_triangulated() {
    let dir = scratch("pentagon");
    let mut text = String::new();
    for k in 0..5 {
        let a = 2.0 * std::f64::consts::PI * k as f64 / 5.0;
        text += &format!("v {:.6} {:.6} 0\n", a.cos(), a.sin());
    }
    text += "f 1 2 3 4 5\n";
    let m = import(&obj(&dir, &text), &opts()).unwrap();
    assert_eq!(m.polygons_split, 1);
    assert_eq!(m.mesh().triangles.len(), 3);
    assert_eq!(m.mesh().positions.len(), 5);
    assert!(m.mesh().normals.iter().all(|&n| n == [0, 0, 16384]));
    // the fan covers the pentagon once, counter-clockwise (+z)
    let area: f64 = m
        .mesh()
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| dequant(m.mesh(), usize::from(i)));
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        })
        .sum();
    let exact = 2.5 * (2.0 * std::f64::consts::PI / 5.0).sin();
    assert!((area - exact).abs() < 1e-3, "{area} {exact}");
}

/// `n` disjoint triangles (3n distinct positions).
fn disjoint_triangles(n: usize) -> String {
    let mut s = String::with_capacity(n * 80);
    for k in 0..n {
        let (x, y) = ((k % 256) as f64 * 0.01, (k / 256) as f64 * 0.01);
        s += &format!(
            "v {x:.3} {y:.3} 0\nv {:.3} {y:.3} 0\nv {x:.3} {:.3} 0\n",
            x + 0.005,
            y + 0.005
        );
    }
    for k in 0..n {
        s += &format!("f {} {} {}\n", 3 * k + 1, 3 * k + 2, 3 * k + 3);
    }
    s
}

#[test]
fn vertex_limit_is_65535() {
    let dir = scratch("limit");
    let m = import(&obj(&dir, &disjoint_triangles(21845)), &opts()).unwrap();
    assert_eq!(m.mesh().positions.len(), 65535);
    let e = import(&obj(&dir, &disjoint_triangles(21846)), &opts()).unwrap_err();
    assert!(
        matches!(
            e,
            Error::TooManyVertices {
                count: 65538,
                triangles: 21846,
                material: None,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("65538 vertices"), "{e}");
    // triangles: the renderer's bins address 65535
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    text += &"f 1 2 3\n".repeat(65536);
    let e = import(&obj(&dir, &text), &opts()).unwrap_err();
    assert!(
        matches!(
            e,
            Error::TooManyTriangles {
                count: 65536,
                positions: 3,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn malformed_lines_are_reported_with_their_number() {
    let dir = scratch("malformed");
    let cases = [
        ("v 0 0 0\nv 1 0 0\n# comment\nv 0 one 0\nf 1 2 3\n", 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nf 1 2 3\n", 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 3/x\n", 5),
        // an index beyond the vertices is found when the object closes: the
        // pre-scan locates it
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\no next\n", 5),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", 4),
    ];
    for (text, line) in cases {
        let p = obj(&dir, text);
        match import(&p, &opts()) {
            Err(Error::Parse { path, line: l, .. }) => {
                assert_eq!(l, Some(line), "{text:?}");
                assert_eq!(path, p);
            }
            other => panic!("{text:?}: {other:?}"),
        }
    }
    let e = import(
        &obj(&dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 1 0\n\nf 1 2 q\n"),
        &opts(),
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("m.obj:6: face parse error: `f 1 2 q`"),
        "{e}"
    );
    // a malformed MTL line: the MTL's path and line
    write(&dir, "bad.mtl", "newmtl a\nKd 1 1 1\nNs many\n");
    let p = obj(
        &dir,
        "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n",
    );
    match import(&p, &opts()) {
        Err(Error::Parse { path, line, .. }) => {
            assert!(path.ends_with("bad.mtl"));
            assert_eq!(line, Some(3));
        }
        other => panic!("{other:?}"),
    }
    // NaN coordinates parse as numbers: caught after reading
    let e = import(
        &obj(&dir, "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        &opts(),
    )
    .unwrap_err();
    assert!(matches!(e, Error::NotFinite { what: "position" }), "{e}");
}

#[test]
fn missing_files_are_typed_errors_naming_the_path_with_strict() {
    let dir = scratch("missing");
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n";
    let opts = || Options {
        strict: true,
        ..opts()
    };
    // the model
    match import(&dir.join("none.obj"), &opts()) {
        Err(Error::MissingFile {
            kind: FileKind::Model,
            path,
        }) => assert!(path.ends_with("none.obj")),
        other => panic!("{other:?}"),
    }
    // the material library
    let p = obj(&dir, &format!("mtllib gone.mtl\n{tri}"));
    match import(&p, &opts()) {
        Err(
            e @ Error::MissingFile {
                kind: FileKind::MaterialLibrary,
                ..
            },
        ) => {
            assert!(e.to_string().contains("gone.mtl"), "{e}")
        }
        other => panic!("{other:?}"),
    }
    // the texture it names
    write(
        &dir,
        "m.mtl",
        "newmtl a\nKd 1 1 1\nmap_Kd textures/missing.png\n",
    );
    let p = obj(&dir, &format!("mtllib m.mtl\n{tri}"));
    match import(&p, &opts()) {
        Err(Error::MissingFile {
            kind: FileKind::Texture,
            path,
        }) => {
            assert_eq!(path, dir.join("textures/missing.png"))
        }
        other => panic!("{other:?}"),
    }
    // without the texture it imports
    let mut o = opts();
    o.texture = TextureChoice::None;
    assert!(import(&p, &o).unwrap().texture().is_none());
    // --texture FILE missing: an error even without --strict (it was asked for)
    o.texture = TextureChoice::File(dir.join("nope.png"));
    o.strict = false;
    assert!(matches!(
        import(&p, &o),
        Err(Error::MissingFile {
            kind: FileKind::Texture,
            ..
        })
    ));
}

#[test]
fn other_errors() {
    let dir = scratch("errors");
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let p = obj(&dir, tri);
    // a name that is no upper-case identifier
    assert!(matches!(
        import(&p, &Options::new("teapot")),
        Err(Error::InvalidName(_))
    ));
    // unsupported extension
    let q = write(&dir, "m.stl", "solid");
    assert!(matches!(
        import(&q, &opts()),
        Err(Error::Unsupported { .. })
    ));
    // no triangles (points and lines only, or zero-area triangles)
    let e = write(&dir, "lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\np 1\n");
    assert!(matches!(import(&e, &opts()), Err(Error::Empty { .. })));
    let e = write(&dir, "flat.obj", "v 0 0 0\nv 1 0 0\nf 1 2 2\n");
    assert!(matches!(import(&e, &opts()), Err(Error::Empty { .. })));
    // tangents need texture coordinates
    let mut o = opts();
    o.process.tangents = true;
    assert!(matches!(import(&p, &o), Err(Error::NoTexcoords)));
    // (several textures make several parts: tests/materials.rs)
    write(
        &dir,
        "two.mtl",
        "newmtl a\nmap_Kd a.png\nnewmtl b\nmap_Kd b.png\n",
    );
    let two = write(
        &dir,
        "two.obj",
        "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 2/2\n",
    );
    // a texture that is not a PNG
    write(&dir, "a.png", b"\xFF\xD8\xFF\xE0 not a png");
    let mut o = opts();
    o.texture = TextureChoice::File(dir.join("a.png"));
    assert!(matches!(import(&two, &o), Err(Error::Unsupported { .. })));
}

#[test]
fn tangents_follow_u() {
    let model = {
        let mut o = opts();
        o.process.tangents = true;
        import(&asset("rocket.obj"), &o).unwrap()
    };
    let m = model.mesh();
    let (t, n) = (m.tangents.as_ref().unwrap(), &m.normals);
    for (t, n) in t.iter().zip(n) {
        let tv = [t[0], t[1], t[2]].map(f64::from);
        let nv = n.map(f64::from);
        let len = (tv[0] * tv[0] + tv[1] * tv[1] + tv[2] * tv[2]).sqrt();
        assert!((len - 16384.0).abs() < 3.0, "{t:?}");
        // orthogonal to the normal
        assert!((tv[0] * nv[0] + tv[1] * nv[1] + tv[2] * nv[2]).abs() / 16384.0 / 16384.0 < 2e-3);
        assert_eq!(t[3].abs(), 16384);
    }
}
