//! A `const fn` torus knot: a tube swept along a `(p, q)` torus-knot curve,
//! built at compile time into a [`MeshData`] (flash, no RAM, no floating
//! point at run time).

use super::compact::{round_i16, MeshData, NORMAL_ONE};
use crate::num::sin_cos;
use core::f64::consts::PI;

/// The shape of a torus knot: the curve winds `p` times around the `z` axis
/// and `q` times through the hole of a torus with radii `major` (centre
/// circle, in the `xy` plane) and `minor` (the circle the curve stays on),
/// and a tube of radius `tube` is swept along it.
///
/// The curve is `C(t) = ((R + r·cos qt)·cos pt, (R + r·cos qt)·sin pt, r·sin qt)`
/// for `t` in `[0, 2π)`, with `R = major` and `r = minor`. `p` and `q`
/// coprime give one knot (`(2, 3)`: the trefoil); otherwise the tube passes
/// through itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TorusKnot {
    /// Turns around the `z` axis.
    pub p: u32,
    /// Turns through the torus' hole.
    pub q: u32,
    /// Radius of the torus' centre circle.
    pub major: f64,
    /// Radius of the torus' tube on which the curve runs.
    pub minor: f64,
    /// Radius of the swept tube.
    pub tube: f64,
}

impl TorusKnot {
    /// `(vertices, triangles)` of [`MeshData::torus_knot`] with `tubular`
    /// segments along the curve and `radial` around the tube:
    /// `(tubular·radial, 2·tubular·radial)` (saturating). Sizes below
    /// `tubular = 3`, `radial = 3` give `(0, 0)`.
    ///
    /// ```
    /// use fixshade::mesh::TorusKnot;
    /// assert_eq!(TorusKnot::counts(64, 8), (512, 1024));
    /// ```
    pub const fn counts(tubular: usize, radial: usize) -> (usize, usize) {
        if tubular < 3 || radial < 3 {
            return (0, 0);
        }
        let v = tubular.saturating_mul(radial);
        (v, v.saturating_mul(2))
    }

    /// The trefoil knot `(2, 3)` with radii 0.6, 0.3 and tube 0.13: it fits
    /// the unit sphere (largest coordinate below 1.03) and positions with 14
    /// fraction bits.
    pub const TREFOIL: TorusKnot = TorusKnot {
        p: 2,
        q: 3,
        major: 0.6,
        minor: 0.3,
        tube: 0.13,
    };

    /// The largest absolute coordinate of any vertex: `major + minor + tube`
    /// bounds `x` and `y`, `minor + tube` bounds `z`.
    pub const fn extent(&self) -> f64 {
        self.major + self.minor + self.tube
    }

    /// The curve point `C(t)` and its derivative `C'(t)`.
    const fn curve(&self, t: f64) -> ([f64; 3], [f64; 3]) {
        let (p, q) = (self.p as f64, self.q as f64);
        let (sp, cp) = sin_cos(p * t);
        let (sq, cq) = sin_cos(q * t);
        let ring = self.major + self.minor * cq;
        let point = [ring * cp, ring * sp, self.minor * sq];
        let d_ring = -self.minor * q * sq;
        let tangent = [
            d_ring * cp - ring * p * sp,
            d_ring * sp + ring * p * cp,
            self.minor * q * cq,
        ];
        (point, tangent)
    }
}

impl<const V: usize, const T: usize> MeshData<V, T> {
    /// The torus knot `shape` as a closed tube with `tubular` segments along
    /// the curve and `radial` around it, positions with `frac` fraction bits.
    ///
    /// Vertex `i·radial + j` is ring `i` (`t = 2πi/tubular`), angle
    /// `θ = 2πj/radial`: `C(t) + tube·(cos θ·N + sin θ·B)` with `T = C'/|C'|`,
    /// `B = T × C / |T × C|`, `N = B × T`; its normal is exactly
    /// `cos θ·N + sin θ·B`. The frame depends on `t` alone, so the mesh is
    /// closed; counter-clockwise seen from outside.
    ///
    /// `V` and `T` must equal [`TorusKnot::counts`] (at most 65 536
    /// vertices), `p` and `q` at least 1, the radii positive with
    /// `tube < minor < major`, and [`TorusKnot::extent`] below
    /// `2^(15 − frac)`: otherwise a compile-time error in a `static`.
    ///
    /// ```
    /// use fixshade::mesh::{MeshData, TorusKnot};
    /// const N: (usize, usize) = TorusKnot::counts(96, 8);
    /// static KNOT: MeshData<{ N.0 }, { N.1 }> = MeshData::torus_knot(&TorusKnot::TREFOIL, 96, 8, 14);
    /// let mesh = KNOT.mesh();
    /// assert_eq!((mesh.vertex_count(), mesh.triangle_count()), (768, 1536));
    /// ```
    pub const fn torus_knot(shape: &TorusKnot, tubular: usize, radial: usize, frac: u8) -> Self {
        let counts = TorusKnot::counts(tubular, radial);
        assert!(
            counts.0 == V && counts.1 == T && V > 0,
            "V, T must equal TorusKnot::counts"
        );
        assert!(V <= 1 << 16, "at most 65 536 vertices (u16 indices)");
        assert!(shape.p >= 1 && shape.q >= 1, "p and q must be at least 1");
        assert!(
            shape.tube > 0.0 && shape.tube < shape.minor && shape.minor < shape.major,
            "radii must satisfy 0 < tube < minor < major"
        );
        assert!(frac <= 15, "frac must be at most 15");
        let scale = (1u32 << frac) as f64;
        assert!(
            shape.extent() * scale < i16::MAX as f64,
            "the knot does not fit i16 positions with this frac"
        );
        let mut m = MeshData {
            positions: [[0; 3]; V],
            normals: [[0; 3]; V],
            triangles: [[0; 3]; T],
            frac,
        };
        let mut i = 0;
        while i < tubular {
            let t = 2.0 * PI * i as f64 / tubular as f64;
            let (c, d) = shape.curve(t);
            let tangent = normalize(d);
            let b = normalize(cross(tangent, c));
            let n = cross(b, tangent);
            let mut j = 0;
            while j < radial {
                let (s, co) = sin_cos(2.0 * PI * j as f64 / radial as f64);
                let k = i * radial + j;
                let mut a = 0;
                while a < 3 {
                    let normal = co * n[a] + s * b[a];
                    m.positions[k][a] = round_i16((c[a] + shape.tube * normal) * scale);
                    m.normals[k][a] = round_i16(normal * NORMAL_ONE as f64);
                    a += 1;
                }
                j += 1;
            }
            i += 1;
        }
        let mut k = 0;
        let mut i = 0;
        while i < tubular {
            let i1 = (i + 1) % tubular;
            let mut j = 0;
            while j < radial {
                let j1 = (j + 1) % radial;
                // (i, j) → (i, j + 1) → (i + 1, j + 1) runs counter-clockwise
                // seen from outside: ∂θ × ∂t points away from the curve.
                m.triangles[k] = [at(radial, i, j), at(radial, i, j1), at(radial, i1, j1)];
                m.triangles[k + 1] = [at(radial, i, j), at(radial, i1, j1), at(radial, i1, j)];
                k += 2;
                j += 1;
            }
            i += 1;
        }
        m
    }
}

/// Index of vertex `j` of ring `i`.
const fn at(radial: usize, i: usize, j: usize) -> u16 {
    (i * radial + j) as u16
}

const fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

const fn normalize(v: [f64; 3]) -> [f64; 3] {
    let len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    assert!(len > 0.0, "degenerate torus knot frame");
    [v[0] / len, v[1] / len, v[2] / len]
}

/// `√x` for `x > 0` in `const fn`: a guess from the exponent bits, then
/// Newton steps (exact to the last bit or one below).
const fn sqrt(x: f64) -> f64 {
    // halving the biased exponent gives a guess within a factor of √2
    let mut r = f64::from_bits((x.to_bits() >> 1) + (1023u64 << 51));
    let mut n = 0;
    while n < 8 {
        r = 0.5 * (r + x / r);
        n += 1;
    }
    r
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::collections::HashMap;
    use std::vec::Vec;

    const N: (usize, usize) = TorusKnot::counts(96, 8);
    static KNOT: MeshData<{ N.0 }, { N.1 }> = MeshData::torus_knot(&TorusKnot::TREFOIL, 96, 8, 14);

    #[test]
    fn const_sqrt_matches_std() {
        for x in [1e-9, 0.001, 0.5, 1.0, 2.0, 3.0, 10.0, 12345.678, 1e12] {
            let (a, b) = (sqrt(x), libm::sqrt(x));
            assert!((a - b).abs() <= b * 4e-16, "{x}: {a} {b}");
        }
    }

    #[test]
    fn closed_with_consistent_winding() {
        // every directed edge exactly once, and its reverse exactly once:
        // a closed two-manifold whose neighbouring triangles agree on the winding
        let mut edges: HashMap<(u16, u16), usize> = HashMap::new();
        for t in KNOT.triangles {
            assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "{t:?}");
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1, "edge {a}-{b} used {n} times in one direction");
            assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}-{b} has no twin");
        }
        // a torus: V − E + F = 0
        let (v, e, f) = (N.0 as i64, edges.len() as i64 / 2, N.1 as i64);
        assert_eq!(v - e + f, 0);
        // every vertex used
        let mut used = [false; N.0];
        for t in KNOT.triangles {
            for i in t {
                used[i as usize] = true;
            }
        }
        assert!(used.iter().all(|u| *u));
    }

    #[test]
    fn unit_normals_facing_out() {
        let mesh = KNOT.mesh();
        for (i, n) in KNOT.normals.iter().enumerate() {
            let len =
                ((n[0] as f64).powi(2) + (n[1] as f64).powi(2) + (n[2] as f64).powi(2)).sqrt();
            assert!((len - NORMAL_ONE as f64).abs() < 1.0, "{i}: |n| = {len}");
        }
        // the geometric normal of every triangle agrees with its vertex normals
        for t in KNOT.triangles {
            let p: Vec<[f32; 3]> = t
                .iter()
                .map(|&i| mesh.position(i as usize).unwrap())
                .collect();
            let (u, v) = (sub(p[1], p[0]), sub(p[2], p[0]));
            let g = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let gl = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
            assert!(gl > 0.0, "degenerate triangle {t:?}");
            for &i in &t {
                let n = mesh.normal(i as usize).unwrap();
                let cos = (g[0] * n[0] + g[1] * n[1] + g[2] * n[2]) / gl;
                assert!(cos > 0.7, "triangle {t:?}, vertex {i}: cos = {cos}");
            }
        }
    }

    #[test]
    fn on_the_tube_around_the_curve() {
        let shape = TorusKnot::TREFOIL;
        let mesh = KNOT.mesh();
        let lsb = 1.0 / 16384.0;
        for i in 0..96 {
            let t = 2.0 * PI * i as f64 / 96.0;
            // the curve, evaluated with the standard library
            let ring = shape.major + shape.minor * (3.0 * t).cos();
            let c = [
                ring * (2.0 * t).cos(),
                ring * (2.0 * t).sin(),
                shape.minor * (3.0 * t).sin(),
            ];
            for j in 0..8 {
                let k = i * 8 + j;
                let (p, n) = (mesh.position(k).unwrap(), mesh.normal(k).unwrap());
                for a in 0..3 {
                    // position = curve + tube · normal (to rounding)
                    let want = c[a] + shape.tube * n[a] as f64;
                    assert!((p[a] as f64 - want).abs() < 2.0 * lsb, "{k} axis {a}");
                    assert!(p[a].abs() as f64 <= shape.extent() + lsb);
                }
            }
        }
        // the normal is perpendicular to the curve's tangent
        for i in 0..96 {
            let (_, d) = shape.curve(2.0 * PI * i as f64 / 96.0);
            let tl = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            for j in 0..8 {
                let n = mesh.normal(i * 8 + j).unwrap();
                let dot = (n[0] as f64 * d[0] + n[1] as f64 * d[1] + n[2] as f64 * d[2]) / tl;
                assert!(dot.abs() < 1e-3, "{i},{j}: n·T = {dot}");
            }
        }
    }

    #[test]
    fn counts() {
        assert_eq!(TorusKnot::counts(2, 8), (0, 0));
        assert_eq!(TorusKnot::counts(8, 2), (0, 0));
        assert_eq!(TorusKnot::counts(3, 3), (9, 18));
        assert_eq!(TorusKnot::counts(usize::MAX, 3), (usize::MAX, usize::MAX));
    }

    fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
}
