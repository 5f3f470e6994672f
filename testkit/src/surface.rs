//! Data for the surface-detail scenes (issue 13), all made by this code: a
//! height field of raised tiles, a dense sphere displaced by it (the
//! "high-poly original"), the tangent-space normal map baked from that mesh
//! onto a coarse sphere, and a procedural texture.
//!
//! Conventions shared with the library: texture coordinate `u` runs around the
//! sphere (longitude, increasing eastwards seen from +y), `v` from the north
//! pole (`v = 0`) to the south pole (`v = 1`); the tangent `T` points along
//! increasing `u`, the bitangent `B` along increasing `v`, and a tangent-space
//! normal `(x, y, z)` means `x·T + y·B + z·N`.

#![allow(dead_code)]

use std::f64::consts::PI;

pub type V3 = [f64; 3];

pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    if l > 0.0 {
        scale(a, 1.0 / l)
    } else {
        a
    }
}

/// The unit direction of texture coordinates `(u, v)` on the sphere: `v = 0`
/// the north pole `(0, 1, 0)`, `u = 0` towards `+z`, `u` increasing towards
/// `+x` (counter-clockwise seen from the north).
pub fn direction(u: f64, v: f64) -> V3 {
    let (theta, phi) = (v * PI, u * 2.0 * PI);
    [
        theta.sin() * phi.sin(),
        theta.cos(),
        theta.sin() * phi.cos(),
    ]
}

/// The sphere's tangent frame at `(u, v)`: `T` along increasing `u`, `B`
/// along increasing `v`, `N` outwards (away from the poles, where `T` is
/// taken from the nearest non-degenerate longitude).
pub fn frame(u: f64, v: f64) -> (V3, V3, V3) {
    let phi = u * 2.0 * PI;
    let t = [phi.cos(), 0.0, -phi.sin()];
    let n = direction(u, v);
    let theta = v * PI;
    let b = [
        theta.cos() * phi.sin(),
        -theta.sin(),
        theta.cos() * phi.cos(),
    ];
    (t, b, n)
}

fn smooth(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Raised tiles: 16 around × 8 down in staggered rows (bricks), each a plateau of
/// height 1 with bevelled edges, mortar grooves at 0; fades to 0 towards
/// the poles (where the tiles would be squeezed).
pub fn tiles(u: f64, v: f64) -> f64 {
    let (cols, rows) = (16.0, 8.0);
    let y = v * rows;
    let row = y.floor();
    let x = u * cols + if row as i64 % 2 == 0 { 0.0 } else { 0.5 };
    let (fx, fy) = (x - x.floor(), y - row);
    // distance to the nearest tile edge, in tile sides (a tile is about as
    // tall as it is wide at the equator: 2π/16 across, π/8 down)
    let d = fx.min(1.0 - fx).min(fy.min(1.0 - fy));
    let bevel = smooth(0.04, 0.16, d);
    let pole = smooth(0.06, 0.16, v.min(1.0 - v));
    bevel * pole
}

/// A mesh on the host in `f64`, with texture coordinates.
pub struct HostMesh {
    pub pos: Vec<V3>,
    pub nrm: Vec<V3>,
    pub uv: Vec<[f64; 2]>,
    pub tris: Vec<[u16; 3]>,
    /// Grid size: `stacks` × `slices` quads, `(stacks + 1)·(slices + 1)` vertices.
    pub stacks: usize,
    pub slices: usize,
}

/// A sphere of radius 1 displaced along its normal by `amp · h(u, v)`, as a
/// `(stacks + 1) × (slices + 1)` grid of vertices (the seam column and the
/// pole rows duplicated, so every vertex has its own texture coordinates),
/// counter-clockwise seen from outside. Normals are the displaced surface's
/// exact normals (central differences of the position function).
pub fn displaced_sphere(
    stacks: usize,
    slices: usize,
    amp: f64,
    h: impl Fn(f64, f64) -> f64,
) -> HostMesh {
    let p = |u: f64, v: f64| scale(direction(u, v), 1.0 + amp * h(u, v));
    let mut m = HostMesh {
        pos: vec![],
        nrm: vec![],
        uv: vec![],
        tris: vec![],
        stacks,
        slices,
    };
    let e = 1e-5;
    for i in 0..=stacks {
        for j in 0..=slices {
            let (u, v) = (j as f64 / slices as f64, i as f64 / stacks as f64);
            m.pos.push(p(u, v));
            m.uv.push([u, v]);
            let n = if !(1e-9..=1.0 - 1e-9).contains(&v) {
                direction(u, v)
            } else {
                let du = sub(p(u + e, v), p(u - e, v));
                let dv = sub(p(u, v + e), p(u, v - e));
                // u eastwards × v southwards points outwards
                norm(cross(dv, du))
            };
            m.nrm.push(n);
        }
    }
    let w = slices + 1;
    for i in 0..stacks {
        for j in 0..slices {
            let a = (i * w + j) as u16;
            let b = (i * w + j + 1) as u16;
            let c = ((i + 1) * w + j) as u16;
            let d = ((i + 1) * w + j + 1) as u16;
            if i > 0 {
                m.tris.push([a, c, b]);
            }
            if i + 1 < stacks {
                m.tris.push([b, c, d]);
            }
        }
    }
    m
}

impl HostMesh {
    /// The mesh's own (interpolated) normal at texture coordinates `(u, v)`:
    /// the grid cell holding `(u, v)`, the triangle of it, barycentric
    /// interpolation of its vertex normals (what the mesh shows there under
    /// Phong shading).
    pub fn normal_at(&self, u: f64, v: f64) -> V3 {
        let (s, t) = (u * self.slices as f64, v * self.stacks as f64);
        let j = (s.floor() as usize).min(self.slices - 1);
        let i = (t.floor() as usize).min(self.stacks - 1);
        let (fx, fy) = (s - j as f64, t - i as f64);
        let w = self.slices + 1;
        let n = |ii: usize, jj: usize| self.nrm[ii * w + jj];
        // the cell's triangles are (a, c, b) and (b, c, d): split along b–c
        let r = if fx + fy <= 1.0 {
            add(
                add(scale(n(i, j), 1.0 - fx - fy), scale(n(i, j + 1), fx)),
                scale(n(i + 1, j), fy),
            )
        } else {
            add(
                add(
                    scale(n(i + 1, j + 1), fx + fy - 1.0),
                    scale(n(i, j + 1), 1.0 - fy),
                ),
                scale(n(i + 1, j), 1.0 - fx),
            )
        };
        norm(r)
    }
}

/// Bakes the tangent-space normal map of `high` onto the unit sphere: texel
/// `(x, y)` of a `size.0 × size.1` map holds the high-poly mesh's normal at the
/// texel centre's texture coordinates, in the sphere's tangent frame there.
pub fn bake_normal_map(high: &HostMesh, size: (usize, usize)) -> Vec<V3> {
    let mut out = Vec::with_capacity(size.0 * size.1);
    for y in 0..size.1 {
        for x in 0..size.0 {
            let (u, v) = (
                (x as f64 + 0.5) / size.0 as f64,
                (y as f64 + 0.5) / size.1 as f64,
            );
            let n = high.normal_at(u, v);
            let (t, b, nn) = frame(u, v);
            out.push(norm([dot(n, t), dot(n, b), dot(n, nn)]));
        }
    }
    out
}

/// A procedural texture, `w × h` texels of 8-bit RGB: terracotta tiles of the
/// same layout as [`tiles`] with pale mortar, a few tiles tinted.
pub fn tile_texture(w: usize, h: usize) -> Vec<[u8; 3]> {
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let (u, v) = ((x as f64 + 0.5) / w as f64, (y as f64 + 0.5) / h as f64);
            let t = tiles(u, v);
            let row = (v * 8.0).floor() as i64;
            let col = (u * 16.0 + if row % 2 == 0 { 0.0 } else { 0.5 }).floor() as i64;
            let tile: [f64; 3] = match (row * 7 + col * 3).rem_euclid(5) {
                0 => [0.55, 0.62, 0.75],
                1 => [0.80, 0.42, 0.25],
                2 => [0.72, 0.36, 0.22],
                3 => [0.85, 0.70, 0.40],
                _ => [0.66, 0.30, 0.20],
            };
            let mortar = [0.92, 0.90, 0.85];
            let c = [0, 1, 2].map(|k| (mortar[k] + (tile[k] - mortar[k]) * t) * 255.0);
            out.push(c.map(|c| c.round().clamp(0.0, 255.0) as u8));
        }
    }
    out
}

/// Packs 8-bit RGB into Rgb565 (rounded).
pub fn rgb565(c: [u8; 3]) -> u16 {
    let r = (u16::from(c[0]) * 31 + 127) / 255;
    let g = (u16::from(c[1]) * 63 + 127) / 255;
    let b = (u16::from(c[2]) * 31 + 127) / 255;
    (r << 11) | (g << 5) | b
}

/// Side-by-side panels of equal height into one image (`width`, pixels).
pub fn hcat<P: Copy>(panels: &[(u32, u32, Vec<P>)]) -> (u32, u32, Vec<P>) {
    let h = panels.iter().map(|p| p.1).max().unwrap_or(0);
    let w: u32 = panels.iter().map(|p| p.0).sum();
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for (pw, ph, px) in panels {
            assert_eq!(*ph, h, "panels of equal height");
            out.extend_from_slice(&px[(y * pw) as usize..((y + 1) * pw) as usize]);
        }
    }
    (w, h, out)
}

/// A procedural floor texture, `w × h` texels: 8 × 8 checks of two stone
/// colours with a thin dark grout line.
pub fn checker_texture(w: usize, h: usize) -> Vec<[u8; 3]> {
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let (cx, cy) = (x * 8 / w, y * 8 / h);
            let (fx, fy) = ((x * 8) % w, (y * 8) % h);
            let grout = fx == 0 || fy == 0;
            let c: [u8; 3] = if grout {
                [40, 38, 36]
            } else if (cx + cy) % 2 == 0 {
                [214, 206, 190]
            } else {
                [120, 70, 50]
            };
            out.push(c);
        }
    }
    out
}
