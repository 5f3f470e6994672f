//! The demo asset: a low-poly textured rocket, written as OBJ + MTL + PNG.
//!
//! Made of convex pieces, each closed and wound counter-clockwise from
//! outside: a lathed body (a pointed nose blending into a cylinder, smoothing
//! group 1; a boat-tail taper, group 2, so the shoulder is a crease), a flat
//! bottom cap, a nozzle (group 3, flat cap) and four fins (`s off`: hard
//! edges). No normals in the file: the importer computes them from the
//! smoothing groups. The fins' faces are quads (the importer splits them).
//!
//! The texture is drawn here too (128 × 128): a red nose, a white body with a
//! blue stripe and two portholes, a black-and-white roll pattern, a grey tail.
//!
//! Everything is integer or fixed-decimal output of `f64` arithmetic, so the
//! files are the same bytes on every run (`tests/assets.rs` checks the
//! committed ones against a fresh generation; `cargo run --example
//! make_assets` rewrites them).

use std::f64::consts::PI;
use std::fmt::Write as _;

/// Slices around the axis.
const SLICES: usize = 32;
/// Body radius.
const R: f64 = 0.35;
/// Texture side.
pub const TEX: u32 = 128;

/// The file name and bytes of each asset: `rocket.obj`, `rocket.mtl`,
/// `rocket.png`.
pub fn files() -> Vec<(&'static str, Vec<u8>)> {
    vec![
        ("rocket.obj", obj().into_bytes()),
        ("rocket.mtl", mtl().into_bytes()),
        ("rocket.png", png_texture()),
    ]
}

fn mtl() -> String {
    "# fixshade-import demo asset (tests/common/rocket.rs)\n\
     newmtl rocket\n\
     Ka 0.1 0.1 0.1\n\
     Kd 1 1 1\n\
     Ks 0.4 0.4 0.4\n\
     Ns 40\n\
     map_Kd rocket.png\n"
        .to_string()
}

/// An OBJ under construction: 1-based `v` and `vt` counters.
struct Obj {
    text: String,
    v: usize,
    vt: usize,
    positions: Vec<[f64; 3]>,
}

impl Obj {
    fn v(&mut self, p: [f64; 3]) -> usize {
        let _ = writeln!(self.text, "v {:.5} {:.5} {:.5}", p[0], p[1], p[2]);
        self.positions.push(p);
        self.v += 1;
        self.v
    }

    fn vt(&mut self, u: f64, v: f64) -> usize {
        // OBJ's v runs up the image; the layout below is drawn top-down
        let _ = writeln!(self.text, "vt {:.5} {:.5}", u, 1.0 - v);
        self.vt += 1;
        self.vt
    }

    fn line(&mut self, s: &str) {
        self.text.push_str(s);
        self.text.push('\n');
    }

    /// A face of a convex piece around `centre`, wound so that it is
    /// counter-clockwise seen from outside (its Newell normal pointing away
    /// from the centre).
    fn face_outward(&mut self, corners: &[(usize, usize)], centre: [f64; 3]) {
        let p: Vec<[f64; 3]> = corners
            .iter()
            .map(|&(v, _)| self.positions[v - 1])
            .collect();
        let mut normal = [0.0; 3];
        let mut mid = [0.0; 3];
        for (i, a) in p.iter().enumerate() {
            let b = p[(i + 1) % p.len()];
            normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
            normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
            normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
            for k in 0..3 {
                mid[k] += a[k] / p.len() as f64;
            }
        }
        let out: f64 = (0..3).map(|k| normal[k] * (mid[k] - centre[k])).sum();
        if out < 0.0 {
            let reversed: Vec<(usize, usize)> = corners.iter().rev().copied().collect();
            self.face(&reversed);
        } else {
            self.face(corners);
        }
    }

    fn face(&mut self, corners: &[(usize, usize)]) {
        let c: Vec<String> = corners.iter().map(|(v, t)| format!("{v}/{t}")).collect();
        let _ = writeln!(self.text, "f {}", c.join(" "));
    }
}

/// A point at radius `r`, height `y`, angle `a` around the y axis.
fn around(r: f64, y: f64, a: f64) -> [f64; 3] {
    [r * a.sin(), y, r * a.cos()]
}

/// A ring of the lathe: radius, height, texture row `v` (top-down), and the
/// smoothing group of the band *below* it.
struct Ring {
    r: f64,
    y: f64,
    v: f64,
}

/// Lathes `rings` (top to bottom; a first ring of radius 0 is a tip) into
/// bands with the given smoothing groups (one per band), and closes the
/// bottom with a flat cap textured at rows `cap_v`.
fn lathe(o: &mut Obj, rings: &[Ring], groups: &[&str], cap_v: (f64, f64)) {
    let n = SLICES;
    let angle = |j: usize| 2.0 * PI * j as f64 / n as f64;
    // position indices per ring (one per slice; a tip is one vertex)
    let mut pos: Vec<Vec<usize>> = Vec::new();
    for ring in rings {
        if ring.r == 0.0 {
            let tip = o.v([0.0, ring.y, 0.0]);
            pos.push(vec![tip; n]);
        } else {
            pos.push(
                (0..n)
                    .map(|j| o.v(around(ring.r, ring.y, angle(j))))
                    .collect(),
            );
        }
    }
    // texture columns 0..=n per ring (the seam repeated at u = 1)
    let tex: Vec<Vec<usize>> = rings
        .iter()
        .map(|ring| (0..=n).map(|j| o.vt(j as f64 / n as f64, ring.v)).collect())
        .collect();
    for (i, group) in groups.iter().enumerate() {
        o.line(&format!("s {group}"));
        for j in 0..n {
            let a = (pos[i][j], tex[i][j]);
            let b = (pos[i][(j + 1) % n], tex[i][j + 1]);
            let c = (pos[i + 1][j], tex[i + 1][j]);
            let d = (pos[i + 1][(j + 1) % n], tex[i + 1][j + 1]);
            if rings[i].r == 0.0 {
                // the tip: its own texture coordinate per slice
                let t = o.vt((j as f64 + 0.5) / n as f64, rings[i].v);
                o.face(&[(a.0, t), c, d]);
            } else {
                // counter-clockwise seen from outside (as the library's spheres)
                o.face(&[a, c, d, b]);
            }
        }
    }
    // the bottom cap, facing −y: a fan around the centre
    let last = rings.len() - 1;
    let bottom = &rings[last];
    o.line("s off");
    let centre = o.v([0.0, bottom.y, 0.0]);
    let rim: Vec<usize> = (0..=n)
        .map(|j| o.vt(j as f64 / n as f64, cap_v.0))
        .collect();
    for j in 0..n {
        let t = o.vt((j as f64 + 0.5) / n as f64, cap_v.1);
        o.face(&[
            (centre, t),
            (pos[last][(j + 1) % n], rim[j + 1]),
            (pos[last][j], rim[j]),
        ]);
    }
}

/// A fin at angle `a`: a trapezoid in the plane of the axis (root at radius
/// 0.30, inside the body; tip at 0.75), 0.06 thick; six quads.
fn fin(o: &mut Obj, a: f64) {
    let profile = [(0.30, -0.35), (0.75, -0.75), (0.75, -1.05), (0.30, -0.95)];
    let half = 0.03;
    let (radial, side) = ([a.sin(), 0.0, a.cos()], [a.cos(), 0.0, -a.sin()]);
    let point = |(rho, y): (f64, f64), s: f64| {
        [
            rho * radial[0] + s * side[0],
            y,
            rho * radial[2] + s * side[2],
        ]
    };
    let front: Vec<usize> = profile.iter().map(|&p| o.v(point(p, half))).collect();
    let back: Vec<usize> = profile.iter().map(|&p| o.v(point(p, -half))).collect();
    // the fins take the red patch at the top left of the texture
    let patch = |rho: f64, y: f64| {
        (
            0.04 + 0.16 * (rho - 0.30) / 0.45,
            0.04 + 0.2 * (-0.35 - y) / 0.7,
        )
    };
    let tf: Vec<usize> = profile
        .iter()
        .map(|&(rho, y)| {
            let (u, v) = patch(rho, y);
            o.vt(u, v)
        })
        .collect();
    let tb: Vec<usize> = profile
        .iter()
        .map(|&(rho, y)| {
            let (u, v) = patch(rho, y);
            o.vt(0.24 - u, v)
        })
        .collect();
    let edge = [
        o.vt(0.04, 0.28),
        o.vt(0.2, 0.28),
        o.vt(0.2, 0.31),
        o.vt(0.04, 0.31),
    ];
    let centre = point((0.525, -0.775), 0.0);
    o.line("s off");
    let side = |v: &[usize], t: &[usize]| -> Vec<(usize, usize)> {
        v.iter().copied().zip(t.iter().copied()).collect()
    };
    o.face_outward(&side(&front, &tf), centre);
    o.face_outward(&side(&back, &tb), centre);
    // the four edge faces, each a quad around the rim
    for k in 0..4 {
        let l = (k + 1) % 4;
        o.face_outward(
            &[
                (front[k], edge[0]),
                (front[l], edge[1]),
                (back[l], edge[2]),
                (back[k], edge[3]),
            ],
            centre,
        );
    }
}

fn obj() -> String {
    let mut o = Obj {
        text: String::new(),
        v: 0,
        vt: 0,
        positions: Vec::new(),
    };
    o.line("# fixshade-import demo asset: a rocket (tests/common/rocket.rs)");
    o.line("mtllib rocket.mtl");
    o.line("o body");
    o.line("usemtl rocket");
    // nose: r = R·s·(2 − s) for s from 0 (tip) to 1 (meets the cylinder
    // tangentially), then the cylinder, then the boat tail
    let v_of = |y: f64| (1.2 - y) / 2.1;
    let mut rings = Vec::new();
    for k in 0..=6 {
        let s = k as f64 / 6.0;
        let y = 0.45 + (1.0 - s) * 0.75;
        rings.push(Ring {
            r: R * s * (2.0 - s),
            y,
            v: v_of(y),
        });
    }
    for y in [0.05, -0.35, -0.75] {
        rings.push(Ring {
            r: R,
            y,
            v: v_of(y),
        });
    }
    rings.push(Ring {
        r: 0.27,
        y: -0.9,
        v: 0.99,
    });
    let mut groups = vec!["1"; 9];
    groups.push("2");
    lathe(&mut o, &rings, &groups, (0.995, 0.999));
    o.line("o nozzle");
    let nozzle = [
        Ring {
            r: 0.14,
            y: -0.88,
            v: 0.955,
        },
        Ring {
            r: 0.22,
            y: -1.12,
            v: 0.985,
        },
    ];
    lathe(&mut o, &nozzle, &["3"], (0.995, 0.999));
    for k in 0..4 {
        o.line(&format!("o fin{k}"));
        fin(&mut o, PI / 4.0 + k as f64 * PI / 2.0);
    }
    o.text
}

/// The texture, 8-bit RGB rows from the top.
pub fn texture_pixels() -> Vec<[u8; 3]> {
    let n = TEX as usize;
    let mut px = Vec::with_capacity(n * n);
    let red = [200, 40, 36];
    let white = [236, 234, 226];
    let blue = [40, 70, 160];
    let black = [24, 24, 28];
    let grey = [118, 118, 124];
    for y in 0..n {
        for x in 0..n {
            let (u, v) = ((x as f64 + 0.5) / n as f64, (y as f64 + 0.5) / n as f64);
            let mut c = match v {
                v if v < 0.357 => red,
                v if (0.40..0.44).contains(&v) => blue,
                v if (0.78..0.86).contains(&v) => {
                    // the roll pattern: quarters of the circumference
                    if ((u * 4.0) as usize + usize::from(v > 0.82)) & 1 == 0 {
                        black
                    } else {
                        white
                    }
                }
                v if v > 0.93 => grey,
                // a rainbow band: a hue sweep around the body, darker upwards
                v if (0.62..0.72).contains(&v) => {
                    let k = 0.6 + 4.0 * (v - 0.62);
                    hue(u).map(|ch| (f64::from(ch) * k).round() as u8)
                }
                _ => white,
            };
            // soft shading bands (darker towards the nose tip, and around
            // the circumference, and down the body): a few thousand colours, work
            // for a palette
            let mut k = (0.9 + 0.1 * (2.0 * PI * (u - 0.3)).cos()) * (0.94 + 0.06 * v);
            if v < 0.357 {
                k *= 0.75 + 0.25 * (v / 0.357);
            }
            c = c.map(|ch| (f64::from(ch) * k).round() as u8);
            // two portholes with a rim
            for cu in [0.25, 0.75] {
                let (dx, dy) = ((u - cu) * n as f64, (v - 0.56) * n as f64);
                let d = (dx * dx + dy * dy).sqrt();
                if d < 5.0 {
                    c = [30, 45, 90];
                } else if d < 7.0 {
                    c = [170, 185, 210];
                }
            }
            // the fins' patch (top left): a white diagonal stripe
            if x < 32 && y < 42 {
                let t = x as i32 - y as i32 / 2;
                if (6..10).contains(&t) {
                    c = white;
                }
            }
            px.push(c);
        }
    }
    px
}

/// A saturated colour of hue `h` (0 … 1, red → yellow → green → blue → red).
fn hue(h: f64) -> [u8; 3] {
    let x = (h * 6.0).rem_euclid(6.0);
    let f = |d: f64| {
        let t = (x - d).rem_euclid(6.0);
        let c = if t < 1.0 {
            t
        } else if t < 3.0 {
            1.0
        } else if t < 4.0 {
            4.0 - t
        } else {
            0.0
        };
        (40.0 + 190.0 * c).round() as u8
    };
    [f(4.0), f(2.0), f(0.0)]
}

fn png_texture() -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, TEX, TEX);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::High);
        let mut w = enc.write_header().expect("in-memory PNG header");
        let bytes: Vec<u8> = texture_pixels().into_iter().flatten().collect();
        w.write_image_data(&bytes).expect("in-memory PNG data");
    }
    out
}
