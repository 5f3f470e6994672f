//! Face and vertex normals of an indexed triangle mesh (load-time work, `f32`
//! storage with `f64` intermediate products).

use crate::error::MeshError;
use crate::num::{cross3, dot3, sub3};

/// How [`vertex_normals`] weights the faces around a vertex.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Weighting {
    /// `N_v = normalize(Σ (b − a) × (c − a))`: each face's normal weighted by
    /// twice its area. Cheapest; large faces dominate, so a vertex whose faces are
    /// split unevenly (a cube corner) leans towards the side with more area.
    #[default]
    Area,
    /// `N_v = normalize(Σ α_f · n̂_f)`: each face's unit normal weighted by the
    /// face's interior angle `α_f` at the vertex. Independent of how the faces
    /// are triangulated (a cube corner gets exactly `(±1, ±1, ±1)/√3`).
    Angle,
}

/// Checks every index against `vertices` before anything is written.
pub(crate) fn check_indices(tris: &[[u16; 3]], vertices: usize) -> Result<(), MeshError> {
    for (triangle, t) in tris.iter().enumerate() {
        for &index in t {
            if usize::from(index) >= vertices {
                return Err(MeshError::IndexOutOfRange { triangle, index });
            }
        }
    }
    Ok(())
}

/// `(b − a) × (c − a)` in `f64`: exact enough, and finite for any finite `f32`
/// positions (|component| < 2·(6.8·10³⁸)² ≪ 10³⁰⁸). Non-finite for NaN or
/// infinite positions.
fn face_cross(p: &[[f32; 3]], t: [u16; 3]) -> [f64; 3] {
    let [a, b, c] = t.map(|i| p[usize::from(i)].map(f64::from));
    cross3(sub3(b, a), sub3(c, a))
}

/// `v / |v|` as `f32`, or zero when `|v|` is zero, denormal-small or not finite.
fn unit_or_zero(v: [f64; 3]) -> [f32; 3] {
    let len2 = dot3(v, v);
    if !(len2.is_finite() && len2 > 1.0e-300) {
        return [0.0; 3];
    }
    let inv = 1.0 / libm::sqrt(len2);
    v.map(|c| (c * inv) as f32)
}

/// The unit normal of every triangle, `n̂ = normalize((b − a) × (c − a))`, into
/// `out[..tris.len()]`; returns `tris.len()`.
///
/// The normal points to the side from which `a → b → c` is counter-clockwise
/// (right-handed space). Degenerate triangles (zero area) and triangles with
/// non-finite positions get the zero vector.
///
/// # Errors
///
/// [`MeshError::IndexOutOfRange`] for an index `≥ positions.len()`,
/// [`MeshError::BufferTooSmall`] when `out.len() < tris.len()`. Nothing is
/// written on error.
///
/// ```
/// use fixshade::mesh::face_normals;
/// let pos = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// let mut n = [[0.0f32; 3]; 2];
/// assert_eq!(face_normals(&pos, &[[0, 1, 2], [0, 2, 1]], &mut n), Ok(2));
/// assert_eq!(n, [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]);
/// ```
pub fn face_normals(
    positions: &[[f32; 3]],
    tris: &[[u16; 3]],
    out: &mut [[f32; 3]],
) -> Result<usize, MeshError> {
    MeshError::check_len("out", tris.len(), out.len())?;
    check_indices(tris, positions.len())?;
    for (o, &t) in out.iter_mut().zip(tris) {
        *o = unit_or_zero(face_cross(positions, t));
    }
    Ok(tris.len())
}

/// The normal of every vertex, the normalised weighted sum of the normals of the
/// faces around it (see [`Weighting`]), into `out[..positions.len()]`; returns
/// `positions.len()`.
///
/// Unused vertices and those whose sum vanishes (degenerate faces only, or
/// faces cancelling as on a two-sided sheet) get the **zero vector**; faces
/// with non-finite positions are skipped. [`Weighting::Area`] scales the
/// cross products by the largest before summing in `f32`: faces below about
/// 10⁻³⁰ of it count as degenerate. Triangles are expected counter-clockwise
/// seen from outside ([`face_normals`]); reversed ones pull normals inwards.
///
/// # Errors
///
/// [`MeshError::IndexOutOfRange`] for an index `≥ positions.len()`,
/// [`MeshError::BufferTooSmall`] when `out.len() < positions.len()`. Nothing
/// is written on error.
///
/// ```
/// use fixshade::mesh::{vertex_normals, Weighting};
/// // two triangles folded 90° along the edge 0–1
/// let pos = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let tris = [[0, 1, 2], [0, 3, 1]];
/// let mut n = [[0.0f32; 3]; 4];
/// vertex_normals(&pos, &tris, Weighting::Area, &mut n)?;
/// let h = core::f32::consts::FRAC_1_SQRT_2;
/// assert_eq!(n[0], [0.0, h, h]); // between +z and +y
/// assert_eq!(n[2], [0.0, 0.0, 1.0]); // only the first face
/// # Ok::<(), fixshade::error::MeshError>(())
/// ```
pub fn vertex_normals(
    positions: &[[f32; 3]],
    tris: &[[u16; 3]],
    weighting: Weighting,
    out: &mut [[f32; 3]],
) -> Result<usize, MeshError> {
    vertex_normals_mapped(positions, tris, weighting, usize::from, out)
}

/// [`vertex_normals`] with the vertices welded: vertex `i`'s faces count for
/// vertex `weld[i]` (a representative with `weld[weld[i]] == weld[i]`), and every
/// vertex gets its representative's normal. Duplicates at a texture seam
/// (same position, different texture coordinates) thus share one normal.
///
/// # Errors
///
/// As [`vertex_normals`]; [`MeshError::BufferTooSmall`] when `weld` is shorter
/// than the positions, [`MeshError::IndexOutOfRange`] (triangle 0) for a
/// representative beyond the positions.
pub(crate) fn vertex_normals_welded(
    positions: &[[f32; 3]],
    tris: &[[u16; 3]],
    weighting: Weighting,
    weld: &[u16],
    out: &mut [[f32; 3]],
) -> Result<usize, MeshError> {
    let n = positions.len();
    MeshError::check_len("weld", n, weld.len())?;
    let weld = weld.get(..n).unwrap_or(&[]);
    if let Some(&index) = weld.iter().find(|&&w| usize::from(w) >= n) {
        return Err(MeshError::IndexOutOfRange { triangle: 0, index });
    }
    let map = |i: u16| weld.get(usize::from(i)).map_or(0, |&w| usize::from(w));
    vertex_normals_mapped(positions, tris, weighting, map, out)?;
    for (i, &r) in weld.iter().enumerate() {
        if let Some(&v) = out.get(usize::from(r)) {
            if let Some(o) = out.get_mut(i) {
                *o = v;
            }
        }
    }
    Ok(n)
}

/// The sums of [`vertex_normals`] gathered at `map(vertex)`; vertices that are
/// no vertex's image get zero.
fn vertex_normals_mapped(
    positions: &[[f32; 3]],
    tris: &[[u16; 3]],
    weighting: Weighting,
    map: impl Fn(u16) -> usize,
    out: &mut [[f32; 3]],
) -> Result<usize, MeshError> {
    let n = positions.len();
    MeshError::check_len("out", n, out.len())?;
    check_indices(tris, n)?;
    let out = &mut out[..n];
    out.fill([0.0; 3]);
    // Area: scale = 1 / max |(b − a) × (c − a)|, so every summand is ≤ 1.
    let max = match weighting {
        Weighting::Area => tris
            .iter()
            .map(|&t| face_cross(positions, t).map(f64::abs))
            .map(|c| c[0].max(c[1]).max(c[2]))
            .filter(|m| m.is_finite())
            .fold(0.0, f64::max),
        Weighting::Angle => 0.0,
    };
    let scale = if max > 0.0 { 1.0 / max } else { 1.0 };
    for &t in tris {
        let c = face_cross(positions, t);
        if !(c[0].is_finite() && c[1].is_finite() && c[2].is_finite()) {
            continue;
        }
        match weighting {
            Weighting::Area => {
                for &i in &t {
                    if let Some(o) = out.get_mut(map(i)) {
                        add(o, c.map(|x| x * scale));
                    }
                }
            }
            Weighting::Angle => {
                let len = libm::sqrt(dot3(c, c));
                if !(len > 0.0 && len.is_finite()) {
                    continue;
                }
                let unit = c.map(|x| x / len);
                let p = t.map(|i| positions[usize::from(i)].map(f64::from));
                for k in 0..3 {
                    // α = atan2(|e1 × e2|, e1 · e2), e1, e2 the edges leaving corner k.
                    let e1 = sub3(p[(k + 1) % 3], p[k]);
                    let e2 = sub3(p[(k + 2) % 3], p[k]);
                    let x = cross3(e1, e2);
                    let angle = libm::atan2(libm::sqrt(dot3(x, x)), dot3(e1, e2));
                    if angle.is_finite() {
                        if let Some(o) = out.get_mut(map(t[k])) {
                            add(o, unit.map(|u| u * angle));
                        }
                    }
                }
            }
        }
    }
    for o in out.iter_mut() {
        *o = unit_or_zero(o.map(f64::from));
    }
    Ok(n)
}

/// `acc += w` (in `f32`; every summand is bounded, so the sum stays finite for
/// fewer than 10³⁷ faces per vertex).
fn add(acc: &mut [f32; 3], w: [f64; 3]) {
    for (a, w) in acc.iter_mut().zip(w) {
        *a += w as f32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube, corners shared, two triangles per face, CCW from outside.
    pub(crate) fn cube() -> ([[f32; 3]; 8], [[u16; 3]; 12]) {
        let mut p = [[0.0f32; 3]; 8];
        for (i, v) in p.iter_mut().enumerate() {
            *v = [
                if i & 1 != 0 { 1.0 } else { -1.0 },
                if i & 2 != 0 { 1.0 } else { -1.0 },
                if i & 4 != 0 { 1.0 } else { -1.0 },
            ];
        }
        let t = [
            [0, 2, 3],
            [0, 3, 1], // −z
            [4, 5, 7],
            [4, 7, 6], // +z
            [0, 1, 5],
            [0, 5, 4], // −y
            [2, 6, 7],
            [2, 7, 3], // +y
            [0, 4, 6],
            [0, 6, 2], // −x
            [1, 3, 7],
            [1, 7, 5], // +x
        ];
        (p, t)
    }

    #[test]
    fn cube_faces_point_outwards() {
        let (p, t) = cube();
        let mut n = [[0.0f32; 3]; 12];
        face_normals(&p, &t, &mut n).unwrap();
        for (f, tri) in n.iter().zip(&t) {
            let c = p[tri[0] as usize];
            let d = f[0] * c[0] + f[1] * c[1] + f[2] * c[2];
            assert_eq!(d, 1.0, "{f:?}");
        }
    }

    #[test]
    fn cube_vertex_normals() {
        let (p, t) = cube();
        let mut n = [[0.0f32; 3]; 8];
        vertex_normals(&p, &t, Weighting::Angle, &mut n).unwrap();
        let k = 1.0 / libm::sqrtf(3.0);
        for (v, nv) in p.iter().zip(&n) {
            for a in 0..3 {
                assert!((nv[a] - v[a] * k).abs() < 1.0e-6, "{v:?} {nv:?}");
            }
        }
        vertex_normals(&p, &t, Weighting::Area, &mut n).unwrap();
        for (v, nv) in p.iter().zip(&n) {
            let len = libm::sqrtf(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
            assert!((len - 1.0).abs() < 1.0e-6);
            // same octant, within 20° of the diagonal
            let cos = (nv[0] * v[0] + nv[1] * v[1] + nv[2] * v[2]) * k;
            assert!(cos > 0.94, "{v:?} {nv:?}");
        }
    }

    #[test]
    fn errors_and_isolated_vertices() {
        let (p, t) = cube();
        let mut n = [[9.0f32; 3]; 8];
        assert_eq!(
            vertex_normals(&p, &t, Weighting::Area, &mut n[..7]),
            Err(MeshError::BufferTooSmall {
                which: "out",
                needed: 8,
                got: 7
            })
        );
        assert_eq!(
            vertex_normals(&p[..7], &t, Weighting::Area, &mut n),
            Err(MeshError::IndexOutOfRange {
                triangle: 2,
                index: 7
            })
        );
        assert_eq!(n, [[9.0; 3]; 8], "nothing written on error");
        // a vertex without faces, a degenerate face
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [5.0, 5.0, 5.0],
        ];
        vertex_normals(&p, &[[0, 1, 2]], Weighting::Angle, &mut n).unwrap();
        assert_eq!(&n[..4], &[[0.0; 3]; 4]);
        vertex_normals(&p, &[[0, 1, 2]], Weighting::Area, &mut n).unwrap();
        assert_eq!(&n[..4], &[[0.0; 3]; 4]);
        // two-sided sheet cancels
        let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        vertex_normals(&p, &[[0, 1, 2], [0, 2, 1]], Weighting::Area, &mut n).unwrap();
        assert_eq!(&n[..3], &[[0.0; 3]; 3]);
    }

    #[test]
    fn non_finite_faces_are_skipped() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [f32::NAN, 0.0, f32::INFINITY],
        ];
        let mut n = [[0.0f32; 3]; 4];
        for w in [Weighting::Area, Weighting::Angle] {
            vertex_normals(&p, &[[0, 1, 2], [0, 3, 1]], w, &mut n).unwrap();
            assert_eq!(n[0], [0.0, 0.0, 1.0]);
            assert_eq!(n[3], [0.0; 3]);
        }
        // huge but finite positions still work
        let p = [[0.0, 0.0, 0.0], [3.0e38, 0.0, 0.0], [0.0, 3.0e38, 0.0]];
        vertex_normals(&p, &[[0, 1, 2]], Weighting::Area, &mut n).unwrap();
        assert_eq!(n[0], [0.0, 0.0, 1.0]);
    }
}
