//! The icosphere generator into caller-owned arrays, and the UV sphere's
//! counts (its layout: `uv.rs`).

use crate::error::{finite_or, MeshError};

/// The highest subdivision level [`icosphere`] accepts: 4 (2562 vertices, 5120
/// triangles).
pub(crate) const MAX_ICOSPHERE_LEVEL: u32 = 4;

/// `(vertices, triangles)` of [`MeshData::uv_sphere`](super::MeshData::uv_sphere) with `stacks` bands of latitude and
/// `slices` of longitude: `(2 + (stacks − 1)·slices, 2·slices·(stacks − 1))`
/// (saturating). Invalid sizes (`stacks < 2` or `slices < 3`) give `(0, 0)`.
///
/// ```
/// use fixshade::mesh::uv_sphere_counts;
/// const N: (usize, usize) = uv_sphere_counts(8, 16);
/// let positions = [[0.0f32; 3]; N.0]; // sized at compile time
/// assert_eq!(N, (114, 224));
/// # let _ = positions;
/// ```
pub const fn uv_sphere_counts(stacks: usize, slices: usize) -> (usize, usize) {
    if stacks < 2 || slices < 3 {
        return (0, 0);
    }
    let rings = (stacks - 1).saturating_mul(slices);
    (rings.saturating_add(2), rings.saturating_mul(2))
}

/// `(vertices, triangles)` of [`icosphere`] at subdivision `level`:
/// `(10·4^level + 2, 20·4^level)`. Levels above 4 give
/// `(0, 0)`.
///
/// ```
/// use fixshade::mesh::icosphere_counts;
/// assert_eq!(icosphere_counts(0), (12, 20));
/// assert_eq!(icosphere_counts(4), (2562, 5120));
/// ```
pub const fn icosphere_counts(level: u32) -> (usize, usize) {
    if level > MAX_ICOSPHERE_LEVEL {
        return (0, 0);
    }
    let k = 1usize << (2 * level);
    (10 * k + 2, 20 * k)
}

/// Validates centre and radius, and the three output lengths.
fn check_common(
    centre: [f32; 3],
    radius: f32,
    counts: (usize, usize),
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    tris: &[[u16; 3]],
) -> Result<(), MeshError> {
    for c in centre {
        finite_or("centre", c, MeshError::NotFinite)?;
    }
    if !(finite_or("radius", radius, MeshError::NotFinite)? > 0.0) {
        return Err(MeshError::OutOfRange("radius"));
    }
    if counts.0 > 1 << 16 {
        return Err(MeshError::TooManyVertices { needed: counts.0 });
    }
    MeshError::check_len("positions", counts.0, positions.len())?;
    MeshError::check_len("normals", counts.0, normals.len())?;
    MeshError::check_len("triangles", counts.1, tris.len())
}

/// `p = centre + radius·n` in `f32` (`n` unit).
fn place(centre: [f32; 3], radius: f32, n: [f32; 3]) -> [f32; 3] {
    core::array::from_fn(|c| centre[c] + radius * n[c])
}

/// `v / |v|` in `f64`, rounded to `f32`.
fn unit(v: [f64; 3]) -> [f32; 3] {
    let len = libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v.map(|c| (c / len) as f32)
}

/// The golden ratio, for the icosahedron's vertices `(0, ±1, ±φ)` and cyclic
/// permutations.
const PHI: f64 = 1.618_033_988_749_895;

/// The 12 vertices of the icosahedron (before normalisation).
const ICO_VERTICES: [[f64; 3]; 12] = [
    [-1.0, PHI, 0.0],
    [1.0, PHI, 0.0],
    [-1.0, -PHI, 0.0],
    [1.0, -PHI, 0.0],
    [0.0, -1.0, PHI],
    [0.0, 1.0, PHI],
    [0.0, -1.0, -PHI],
    [0.0, 1.0, -PHI],
    [PHI, 0.0, -1.0],
    [PHI, 0.0, 1.0],
    [-PHI, 0.0, -1.0],
    [-PHI, 0.0, 1.0],
];

/// The 20 faces of the icosahedron, counter-clockwise seen from outside.
const ICO_FACES: [[u16; 3]; 20] = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
];

/// Writes an icosphere: the icosahedron with every triangle split into four
/// `level` times (0..=4), new vertices pushed out to the sphere. Returns
/// `(vertices, triangles)`, equal to [`icosphere_counts`]. A closed mesh
/// (every vertex shared, no seam), counter-clockwise seen from outside, with
/// the exact normals `(p − centre)/radius`. Triangle `t` of level `k − 1`
/// becomes triangle `t` (the centre) and `F + 3t .. F + 3t + 3` (the corners)
/// of level `k`. No extra memory: during subdivision `normals` tags each new
/// vertex with the edge it splits, found again by a linear search (about
/// 4·10⁶ integer comparisons at level 4).
///
/// # Errors
///
/// [`MeshError::OutOfRange`] for `level > 4` or `radius ≤ 0`;
/// [`MeshError::NotFinite`] for a NaN or infinite centre or radius;
/// [`MeshError::BufferTooSmall`] when an output is shorter than the counts.
/// Nothing is written on error.
///
/// ```
/// use fixshade::mesh::{icosphere, icosphere_counts};
/// const N: (usize, usize) = icosphere_counts(2);
/// let (mut p, mut n, mut t) = ([[0.0f32; 3]; N.0], [[0.0f32; 3]; N.0], [[0u16; 3]; N.1]);
/// assert_eq!(icosphere(2, [1.0, 0.0, 0.0], 3.0, &mut p, &mut n, &mut t), Ok((162, 320)));
/// let d = [p[100][0] - 1.0, p[100][1], p[100][2]];
/// assert!(((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() - 3.0).abs() < 1e-5);
/// ```
pub fn icosphere(
    level: u32,
    centre: [f32; 3],
    radius: f32,
    positions: &mut [[f32; 3]],
    normals: &mut [[f32; 3]],
    tris: &mut [[u16; 3]],
) -> Result<(usize, usize), MeshError> {
    if level > MAX_ICOSPHERE_LEVEL {
        return Err(MeshError::OutOfRange("level"));
    }
    let counts = icosphere_counts(level);
    check_common(centre, radius, counts, positions, normals, tris)?;
    // Unit vectors in `positions` while subdividing.
    for (p, v) in positions.iter_mut().zip(ICO_VERTICES) {
        *p = unit(v);
    }
    tris[..20].copy_from_slice(&ICO_FACES);
    let (mut nv, mut nf) = (12usize, 20usize);
    for _ in 0..level {
        let first_new = nv;
        // midpoint of edge (a, b): found among this level's new vertices, or made
        let mut midpoint = |a: u16, b: u16, nv: &mut usize| -> u16 {
            let key = [u32::from(a.min(b)), u32::from(a.max(b))];
            for v in (first_new..*nv).rev() {
                if normals[v][0].to_bits() == key[0] && normals[v][1].to_bits() == key[1] {
                    return v as u16;
                }
            }
            let (pa, pb) = (positions[usize::from(a)], positions[usize::from(b)]);
            // m = (pa + pb)/|pa + pb|, projected onto the unit sphere
            positions[*nv] = unit(core::array::from_fn(|c| {
                f64::from(pa[c]) + f64::from(pb[c])
            }));
            normals[*nv] = [f32::from_bits(key[0]), f32::from_bits(key[1]), 0.0];
            *nv += 1;
            (*nv - 1) as u16
        };
        for t in 0..nf {
            let [a, b, c] = tris[t];
            let ab = midpoint(a, b, &mut nv);
            let bc = midpoint(b, c, &mut nv);
            let ca = midpoint(c, a, &mut nv);
            tris[t] = [ab, bc, ca];
            tris[nf + 3 * t] = [a, ab, ca];
            tris[nf + 3 * t + 1] = [ab, b, bc];
            tris[nf + 3 * t + 2] = [ca, bc, c];
        }
        nf *= 4;
    }
    debug_assert_eq!((nv, nf), counts);
    for (p, n) in positions.iter_mut().zip(normals.iter_mut()).take(nv) {
        *n = *p;
        *p = place(centre, radius, *n);
    }
    Ok(counts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_errors() {
        assert_eq!(uv_sphere_counts(2, 3), (5, 6));
        assert_eq!(uv_sphere_counts(1, 8), (0, 0));
        assert_eq!(uv_sphere_counts(4, 2), (0, 0));
        assert_eq!(icosphere_counts(1), (42, 80));
        assert_eq!(icosphere_counts(5), (0, 0));
        let mut p = [[0.0f32; 3]; 64];
        let mut n = [[0.0f32; 3]; 64];
        let mut t = [[0u16; 3]; 128];
        let e = |r| Err::<(usize, usize), _>(r);
        assert_eq!(
            icosphere(5, [0.0; 3], 1.0, &mut p, &mut n, &mut t),
            e(MeshError::OutOfRange("level"))
        );
        assert_eq!(
            icosphere(2, [0.0; 3], 1.0, &mut p, &mut n, &mut t),
            e(MeshError::BufferTooSmall {
                which: "positions",
                needed: 162,
                got: 64
            })
        );
        assert_eq!(
            icosphere(1, [0.0; 3], 1.0, &mut p, &mut n, &mut t[..79]),
            e(MeshError::BufferTooSmall {
                which: "triangles",
                needed: 80,
                got: 79
            })
        );
        assert_eq!(p, [[0.0; 3]; 64], "nothing written on error");
        assert_eq!(
            icosphere(1, [0.0; 3], 1.0, &mut p, &mut n, &mut t),
            Ok((42, 80))
        );
    }

    #[test]
    fn icosahedron_faces_point_outwards() {
        for f in ICO_FACES {
            let [a, b, c] = f.map(|i| ICO_VERTICES[usize::from(i)]);
            let e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                e1[1] * e2[2] - e1[2] * e2[1],
                e1[2] * e2[0] - e1[0] * e2[2],
                e1[0] * e2[1] - e1[1] * e2[0],
            ];
            assert!(n[0] * a[0] + n[1] * a[1] + n[2] * a[2] > 0.0, "{f:?}");
        }
    }
}
