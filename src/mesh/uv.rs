//! The UV sphere's layout, once: which unit point each vertex index is, which
//! vertices each triangle index joins, with or without a texture seam.
//! [`MeshData::uv_sphere`](super::MeshData::uv_sphere) and
//! [`TexturedMeshData::uv_sphere`](super::TexturedMeshData::uv_sphere)
//! store it in their formats.
//!
//! The layouts are documented on those two functions. Per slice, the
//! triangles run from the north fan through two per band to the south fan.

use crate::num::sin_cos;
use core::f64::consts::PI;

/// A UV sphere's sizes and seam.
#[derive(Clone, Copy)]
pub(crate) struct Uv {
    pub stacks: usize,
    pub slices: usize,
    pub seam: bool,
}

impl Uv {
    /// `stacks` × `slices`, with or without a seam of duplicated vertices.
    pub const fn new(stacks: usize, slices: usize, seam: bool) -> Self {
        Uv {
            stacks,
            slices,
            seam,
        }
    }

    /// Vertices in the first ring (the north pole's).
    const fn ring0(self) -> usize {
        if self.seam {
            self.slices
        } else {
            1
        }
    }

    /// Vertices per ring.
    const fn cols(self) -> usize {
        self.slices + self.seam as usize
    }

    /// Ring `i` (0: the north pole, `stacks`: the south pole) and column `j`
    /// of vertex `k` (of `v` vertices).
    const fn grid(self, k: usize, v: usize) -> (usize, usize) {
        let (r0, cols) = (self.ring0(), self.cols());
        if k < r0 {
            (0, k)
        } else if k >= v - r0 {
            (self.stacks, k - (v - r0))
        } else {
            (1 + (k - r0) / cols, (k - r0) % cols)
        }
    }

    /// The index of column `j` of ring `i` (`0 < i < stacks`).
    const fn index(self, i: usize, j: usize) -> u16 {
        let j = if self.seam { j } else { j % self.slices };
        (self.ring0() + (i - 1) * self.cols() + j) as u16
    }

    /// The unit point (and normal) of vertex `k` of `v`.
    pub const fn point(self, k: usize, v: usize) -> [f64; 3] {
        let (i, j) = self.grid(k, v);
        if i == 0 {
            return [0.0, 1.0, 0.0];
        }
        if i == self.stacks {
            return [0.0, -1.0, 0.0];
        }
        let (st, ct) = sin_cos(PI * i as f64 / self.stacks as f64);
        // the seam column repeats column 0 exactly
        let (sp, cp) = if j == self.slices {
            (0.0, 1.0)
        } else {
            sin_cos(2.0 * PI * j as f64 / self.slices as f64)
        };
        [st * sp, ct, st * cp]
    }

    /// The texture coordinates and unit tangent (the direction of increasing
    /// `u`) of vertex `k` of `v` of a sphere with a seam: a pole vertex at
    /// the middle of its slice.
    pub const fn texel(self, k: usize, v: usize) -> ([f64; 2], [f64; 3]) {
        let (i, j) = self.grid(k, v);
        let pole = i == 0 || i == self.stacks;
        let u = (j as f64 + if pole { 0.5 } else { 0.0 }) / self.slices as f64;
        let (sp, cp) = if j == self.slices {
            (0.0, 1.0)
        } else {
            sin_cos(2.0 * PI * u)
        };
        ([u, i as f64 / self.stacks as f64], [cp, 0.0, -sp])
    }

    /// The triangles of `v` vertices, as many as `out` holds.
    pub const fn triangles(self, out: &mut [[u16; 3]], v: usize) {
        let mut t = 0;
        while t < out.len() {
            out[t] = self.triangle(t, v);
            t += 1;
        }
    }

    /// The vertices of triangle `t` of `v` vertices.
    const fn triangle(self, t: usize, v: usize) -> [u16; 3] {
        let per = 2 * (self.stacks - 1);
        let (j, r) = (t / per, t % per);
        if r == 0 {
            // north fan: the pole, then the first ring left to right
            let pole = if self.seam { j as u16 } else { 0 };
            [pole, self.index(1, j), self.index(1, j + 1)]
        } else if r == per - 1 {
            let south = (v - self.ring0() + if self.seam { j } else { 0 }) as u16;
            [
                south,
                self.index(self.stacks - 1, j + 1),
                self.index(self.stacks - 1, j),
            ]
        } else {
            // the quad a b / c d of band i, a top-left: (a, c, d) and (a, d, b)
            let i = 1 + (r - 1) / 2;
            let (a, b) = (self.index(i, j), self.index(i, j + 1));
            let (c, d) = (self.index(i + 1, j), self.index(i + 1, j + 1));
            if (r - 1) % 2 == 0 {
                [a, c, d]
            } else {
                [a, d, b]
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Uv;
    use crate::mesh::{textured_sphere_counts, uv_sphere_counts};
    use crate::num::{cross3, dot3, sub3};
    use std::collections::HashMap;

    /// Every point unit length, every triangle non-degenerate and facing
    /// out, every vertex used; without a seam every edge shared by exactly
    /// two triangles in opposite directions (a closed mesh), with one every
    /// edge at most twice (the seam's columns are twins).
    #[test]
    fn every_layout_is_a_closed_outward_sphere() {
        for (stacks, slices) in [(2, 3), (2, 4), (3, 3), (5, 7), (16, 24), (40, 3), (3, 64)] {
            for seam in [false, true] {
                let uv = Uv::new(stacks, slices, seam);
                let (v, t) = if seam {
                    textured_sphere_counts(stacks, slices)
                } else {
                    uv_sphere_counts(stacks, slices)
                };
                let p: std::vec::Vec<[f64; 3]> = (0..v).map(|k| uv.point(k, v)).collect();
                for q in &p {
                    assert!((dot3(*q, *q).sqrt() - 1.0).abs() < 1e-12);
                }
                let mut edges = HashMap::new();
                let mut used = std::vec![false; v];
                for k in 0..t {
                    let tri = uv.triangle(k, v).map(usize::from);
                    let [a, b, c] = tri.map(|i| p[i]);
                    let n = cross3(sub3(b, a), sub3(c, a));
                    let centre = [0, 1, 2].map(|i| (a[i] + b[i] + c[i]) / 3.0);
                    assert!(
                        dot3(n, centre) > 0.0,
                        "{stacks}x{slices} {seam}: {k} faces in"
                    );
                    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                        *edges.entry((tri[i], tri[j])).or_insert(0) += 1;
                        used[tri[i]] = true;
                    }
                }
                assert!(
                    used.iter().all(|&u| u),
                    "{stacks}x{slices} {seam}: a vertex unused"
                );
                for (&(a, b), &n) in &edges {
                    assert_eq!(n, 1, "{stacks}x{slices}: edge {a}-{b} twice one way");
                    if !seam {
                        assert_eq!(edges.get(&(b, a)), Some(&1), "{stacks}x{slices}: open edge");
                    }
                }
            }
        }
    }
}
