//! Textured meshes built at compile time ([`TexturedMeshData`]): a UV sphere
//! with a texture seam and a plane grid.

use super::compact::{round_i16, Mesh, NORMAL_ONE, TEXCOORD_FRAC};
use super::uv::Uv;

/// `(vertices, triangles)` of [`TexturedMeshData::uv_sphere`] with `stacks`
/// bands of latitude and `slices` of longitude:
/// `(2·slices + (stacks − 1)·(slices + 1), 2·slices·(stacks − 1))`. Each pole
/// is `slices` vertices (one per slice, each with its own `u`), each ring
/// `slices + 1` (the seam column `u = 0` repeated at `u = 1`). Invalid sizes
/// (`stacks < 2`, `slices < 3`) or counts beyond `u16` indices give `(0, 0)`.
///
/// ```
/// use fixshade::mesh::textured_sphere_counts;
/// assert_eq!(textured_sphere_counts(16, 24), (423, 720));
/// assert_eq!(textured_sphere_counts(1, 24), (0, 0));
/// ```
pub const fn textured_sphere_counts(stacks: usize, slices: usize) -> (usize, usize) {
    if stacks < 2 || slices < 3 || stacks > 4096 || slices > 4096 {
        return (0, 0);
    }
    let v = 2 * slices + (stacks - 1) * (slices + 1);
    if v > 1 << 16 {
        return (0, 0);
    }
    (v, 2 * slices * (stacks - 1))
}

/// `(vertices, triangles)` of [`TexturedMeshData::plane`] with `nx × ny`
/// quads: `((nx + 1)·(ny + 1), 2·nx·ny)`; `(0, 0)` for an empty grid or
/// counts beyond `u16` indices.
///
/// ```
/// use fixshade::mesh::plane_counts;
/// assert_eq!(plane_counts(4, 2), (15, 16));
/// ```
pub const fn plane_counts(nx: usize, ny: usize) -> (usize, usize) {
    if nx == 0 || ny == 0 || nx > 4096 || ny > 4096 {
        return (0, 0);
    }
    let v = (nx + 1) * (ny + 1);
    if v > 1 << 16 {
        return (0, 0);
    }
    (v, 2 * nx * ny)
}

/// Textured mesh arrays owned by value: `V` vertices, `T` triangles; the
/// counterpart of [`MeshData`](super::MeshData) with texture coordinates
/// (Q12, [`TEXCOORD_FRAC`]: `u` across the texture, `v` down it) and analytic
/// tangents ([`Mesh::with_tangents`]' format: the unit direction of increasing
/// `u`, Q14). Both generators give increasing `v` along
/// `−(normal × tangent)`, handedness `−NORMAL_ONE` at every vertex, so a
/// normal map made for one suits the other.
///
/// ```
/// use fixshade::mesh::{textured_sphere_counts, Mesh, TexturedMeshData, NORMAL_ONE};
/// const N: (usize, usize) = textured_sphere_counts(16, 24);
/// static SPHERE: TexturedMeshData<{ N.0 }, { N.1 }> = TexturedMeshData::uv_sphere(16, 24, 14);
/// static MESH: Mesh<'static> = SPHERE.mesh();
/// assert_eq!(MESH.texcoords().len(), 423);
/// assert_eq!(MESH.tangents()[30][3], -NORMAL_ONE);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexturedMeshData<const V: usize, const T: usize> {
    /// Positions (`raw · 2^−frac`).
    pub positions: [[i16; 3]; V],
    /// Unit normals in Q14.
    pub normals: [[i16; 3]; V],
    /// Texture coordinates `(u, v)` in Q12.
    pub texcoords: [[i16; 2]; V],
    /// Unit tangents in Q14 (direction of increasing `u`), handedness in `[3]`.
    pub tangents: [[i16; 4]; V],
    /// Triangles, counter-clockwise seen from the side the normals point to.
    pub triangles: [[u16; 3]; T],
    /// Fraction bits of the positions.
    pub frac: u8,
}

/// `x` in Q12, rounded.
const fn q12(x: f64) -> i16 {
    round_i16(x * (1u32 << TEXCOORD_FRAC) as f64)
}

impl<const V: usize, const T: usize> TexturedMeshData<V, T> {
    const EMPTY: Self = TexturedMeshData {
        positions: [[0; 3]; V],
        normals: [[0; 3]; V],
        texcoords: [[0; 2]; V],
        tangents: [[0; 4]; V],
        triangles: [[0; 3]; T],
        frac: 0,
    };

    /// The mesh view with texture coordinates and tangents, checked like
    /// [`MeshData::mesh`](super::MeshData::mesh): at compile time in a
    /// `static`, with a panic path when called at run time on arrays made
    /// invalid through the public fields.
    pub const fn mesh(&self) -> Mesh<'_> {
        let m = Mesh::checked(&self.positions, &self.normals, &self.triangles, self.frac);
        let m = match m.with_texcoords(&self.texcoords) {
            Ok(m) => m,
            Err(_) => panic!("texcoords shorter than positions"),
        };
        match m.with_tangents(&self.tangents) {
            Ok(m) => m,
            Err(_) => panic!("tangents shorter than positions"),
        }
    }

    /// The start of a generator: the empty mesh with `frac` and the position
    /// scale `2^frac`, after checking that its `counts` are `(V, T)` and that
    /// `frac ≤ 14` (else panicking with `msg[0]` or `msg[1]`).
    const fn start(counts: (usize, usize), frac: u8, msg: [&str; 2]) -> (Self, f64) {
        assert!(counts.0 == V && counts.1 == T && V > 0, "{}", msg[0]);
        assert!(frac <= 14, "{}", msg[1]);
        let mut m = Self::EMPTY;
        m.frac = frac;
        (m, (1u32 << frac) as f64)
    }

    /// Stores vertex `k`: unit normal `n` (position `n`, radius 1), texture
    /// coordinate `uv`, tangent `t`.
    const fn put(&mut self, k: usize, n: [f64; 3], uv: [f64; 2], t: [f64; 3], scale: f64) {
        let mut c = 0;
        while c < 3 {
            self.positions[k][c] = round_i16(n[c] * scale);
            self.normals[k][c] = round_i16(n[c] * NORMAL_ONE as f64);
            self.tangents[k][c] = round_i16(t[c] * NORMAL_ONE as f64);
            c += 1;
        }
        self.tangents[k][3] = -NORMAL_ONE;
        self.texcoords[k] = [q12(uv[0]), q12(uv[1])];
    }

    /// The UV sphere of radius 1 around the origin with a texture seam:
    /// `stacks` bands of latitude (≥ 2), `slices` of longitude (≥ 3),
    /// positions with `frac` (≤ 14) fraction bits.
    ///
    /// Layout: vertices `0..slices` are the north pole `(0, 1, 0)`, one per
    /// slice `j` with `u = (j + ½)/slices`, `v = 0`; then `stacks − 1` rings of
    /// `slices + 1` vertices, ring `i` (1-based) at polar angle `θ = π·i/stacks`,
    /// column `j` (0..=slices) at azimuth `φ = 2π·j/slices` with
    /// `u = j/slices`, `v = i/stacks` (columns 0 and `slices` share a position
    /// and normal: the seam); the south pole last, like the north one with
    /// `v = 1`. Position = normal `(sin θ sin φ, cos θ, sin θ cos φ)`; tangent
    /// `∂p/∂φ / |∂p/∂φ| = (cos φ, 0, −sin φ)` (at a pole vertex: at its `u`).
    /// Counter-clockwise seen from outside.
    ///
    /// `V` and `T` must equal [`textured_sphere_counts`] (a compile-time error
    /// in a `static`).
    pub const fn uv_sphere(stacks: usize, slices: usize, frac: u8) -> Self {
        let (mut m, scale) = Self::start(
            textured_sphere_counts(stacks, slices),
            frac,
            [
                "V, T must equal textured_sphere_counts",
                "positions of a unit sphere need frac <= 14",
            ],
        );
        let uv = Uv::new(stacks, slices, true);
        let mut k = 0;
        while k < V {
            let (c, t) = uv.texel(k, V);
            m.put(k, uv.point(k, V), c, t, scale);
            k += 1;
        }
        uv.triangles(&mut m.triangles, V);
        m
    }

    /// A flat grid of `nx × ny` quads (two triangles each) covering
    /// `[−1, 1]²` in the `z = 0` plane, facing `+z`, positions with `frac`
    /// (≤ 14) fraction bits. Vertex `(i, j)` (row `i` from the top, column
    /// `j` from the left) is index `i·(nx + 1) + j` at
    /// `(−1 + 2j/nx, 1 − 2i/ny, 0)` with `u = j/nx`, `v = i/ny`; normal
    /// `(0, 0, 1)`, tangent `(1, 0, 0)`.
    ///
    /// `V` and `T` must equal [`plane_counts`].
    ///
    /// ```
    /// use fixshade::mesh::{plane_counts, TexturedMeshData};
    /// const N: (usize, usize) = plane_counts(2, 2);
    /// static PLANE: TexturedMeshData<{ N.0 }, { N.1 }> = TexturedMeshData::plane(2, 2, 14);
    /// assert_eq!(PLANE.texcoords[8], [4096, 4096]); // bottom right: u = v = 1
    /// assert_eq!(PLANE.mesh().position(8), Some([1.0, -1.0, 0.0]));
    /// ```
    pub const fn plane(nx: usize, ny: usize, frac: u8) -> Self {
        let (mut m, scale) = Self::start(
            plane_counts(nx, ny),
            frac,
            [
                "V, T must equal plane_counts",
                "positions in [-1, 1] need frac <= 14",
            ],
        );
        let mut i = 0;
        while i <= ny {
            let mut j = 0;
            while j <= nx {
                let (u, v) = (j as f64 / nx as f64, i as f64 / ny as f64);
                let k = i * (nx + 1) + j;
                m.positions[k] = [
                    round_i16((2.0 * u - 1.0) * scale),
                    round_i16((1.0 - 2.0 * v) * scale),
                    0,
                ];
                m.normals[k] = [0, 0, NORMAL_ONE];
                m.tangents[k] = [NORMAL_ONE, 0, 0, -NORMAL_ONE];
                m.texcoords[k] = [q12(u), q12(v)];
                j += 1;
            }
            i += 1;
        }
        let mut k = 0;
        let mut i = 0;
        while i < ny {
            let mut j = 0;
            while j < nx {
                let (a, b) = (at(nx, i, j), at(nx, i, j + 1));
                let (c, d) = (at(nx, i + 1, j), at(nx, i + 1, j + 1));
                m.triangles[k] = [a, c, d];
                m.triangles[k + 1] = [a, d, b];
                k += 2;
                j += 1;
            }
            i += 1;
        }
        m
    }
}

/// Index of grid vertex `(i, j)` of a plane of `nx` columns of quads.
const fn at(nx: usize, i: usize, j: usize) -> u16 {
    (i * (nx + 1) + j) as u16
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{cross3, dot3};

    const N: (usize, usize) = textured_sphere_counts(16, 24);
    static SPHERE: TexturedMeshData<{ N.0 }, { N.1 }> = TexturedMeshData::uv_sphere(16, 24, 14);
    const P: (usize, usize) = plane_counts(5, 3);
    static PLANE: TexturedMeshData<{ P.0 }, { P.1 }> = TexturedMeshData::plane(5, 3, 12);

    fn f(v: [i16; 3]) -> [f64; 3] {
        v.map(|c| f64::from(c) / 16384.0)
    }

    /// Texcoords in [0, 1], tangents unit and orthogonal to the normals, the
    /// handedness matching the direction of increasing v across every
    /// triangle, every triangle facing its normals.
    fn check<const V: usize, const T: usize>(m: &TexturedMeshData<V, T>) {
        let mesh = m.mesh();
        assert_eq!(mesh.vertex_count(), V);
        for k in 0..V {
            for c in m.texcoords[k] {
                assert!((0..=4096).contains(&c), "{k}: {c}");
            }
            let (n, t) = (
                f(m.normals[k]),
                f([m.tangents[k][0], m.tangents[k][1], m.tangents[k][2]]),
            );
            assert!(
                (dot3(t, t).sqrt() - 1.0).abs() < 1e-4,
                "{k}: tangent length"
            );
            assert!((dot3(n, n).sqrt() - 1.0).abs() < 1e-4, "{k}: normal length");
            assert!(dot3(n, t).abs() < 1e-4, "{k}: tangent ⟂ normal");
            assert_eq!(m.tangents[k][3], -NORMAL_ONE);
        }
        let s = 1.0 / f64::from(1u32 << m.frac);
        for tri in &m.triangles {
            let p = tri.map(|i| m.positions[usize::from(i)].map(|c| f64::from(c) * s));
            let uv = tri.map(|i| m.texcoords[usize::from(i)].map(|c| f64::from(c) / 4096.0));
            let e1 = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
            let e2 = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
            let (du1, dv1) = (uv[1][0] - uv[0][0], uv[1][1] - uv[0][1]);
            let (du2, dv2) = (uv[2][0] - uv[0][0], uv[2][1] - uv[0][1]);
            let g = cross3(e1, e2);
            let nsum = tri
                .iter()
                .map(|&i| f(m.normals[usize::from(i)]))
                .fold([0.0; 3], |a, b| [a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
            assert!(dot3(g, nsum) > 0.0, "{tri:?} winds against its normals");
            // dp/du and dp/dv of the triangle's linear map
            let det = du1 * dv2 - du2 * dv1;
            assert!(det.abs() > 1e-9, "{tri:?}: degenerate uv");
            let dpdu: [f64; 3] = core::array::from_fn(|c| (e1[c] * dv2 - e2[c] * dv1) / det);
            let dpdv: [f64; 3] = core::array::from_fn(|c| (e2[c] * du1 - e1[c] * du2) / det);
            for &i in tri {
                let i = usize::from(i);
                let (n, t) = (
                    f(m.normals[i]),
                    f([m.tangents[i][0], m.tangents[i][1], m.tangents[i][2]]),
                );
                assert!(dot3(t, dpdu) > 0.0, "{tri:?}: tangent against du");
                let b = cross3(n, t).map(|c| c * f64::from(m.tangents[i][3]) / 16384.0);
                assert!(dot3(b, dpdv) > 0.0, "{tri:?}: handedness against dv");
            }
        }
    }

    #[test]
    fn textured_sphere_texcoords_tangents_handedness_and_validity() {
        check(&SPHERE);
        // positions on the unit sphere, equal to the normals
        for k in 0..N.0 {
            let p = f(SPHERE.positions[k]);
            assert!((dot3(p, p).sqrt() - 1.0).abs() < 1e-4);
        }
        // the seam: columns 0 and `slices` share position and normal, not u
        for i in 1..16 {
            let (a, b) = (24 + (i - 1) * 25, 24 + (i - 1) * 25 + 24);
            assert_eq!(SPHERE.positions[a], SPHERE.positions[b]);
            assert_eq!(SPHERE.normals[a], SPHERE.normals[b]);
            assert_eq!((SPHERE.texcoords[a][0], SPHERE.texcoords[b][0]), (0, 4096));
        }
    }

    #[test]
    fn textured_sphere_matches_the_untextured_one() {
        const M: (usize, usize) = crate::mesh::uv_sphere_counts(16, 24);
        static S: crate::mesh::MeshData<{ M.0 }, { M.1 }> =
            crate::mesh::MeshData::uv_sphere(16, 24, 14);
        // every ring vertex of the plain sphere appears with the same position
        for p in &S.positions {
            assert!(SPHERE.positions.contains(p));
        }
        assert_eq!(SPHERE.triangles.len(), S.triangles.len());
    }

    #[test]
    fn plane_texcoords_tangents_handedness_and_validity() {
        check(&PLANE);
        assert_eq!(PLANE.mesh().position(0), Some([-1.0, 1.0, 0.0]));
        assert_eq!(PLANE.texcoords[P.0 - 1], [4096, 4096]);
    }

    #[test]
    fn counts_reject_bad_sizes() {
        assert_eq!(textured_sphere_counts(2, 2), (0, 0));
        assert_eq!(textured_sphere_counts(2, 3), (10, 6));
        assert_eq!(plane_counts(0, 3), (0, 0));
        assert_eq!(plane_counts(300, 300), (0, 0));
    }
}
