//! Per-vertex tangents for normal mapping, once at load time.

use super::normals::check_indices;
use crate::error::{finite_or, MeshError};
use crate::num::{cross3, dot3};

/// Per-vertex tangents from positions, unit normals, texture coordinates and
/// triangles, into `out` in the Q14 format of
/// [`Mesh::with_tangents`](super::Mesh::with_tangents): `[tx, ty, tz, w]`, one
/// per vertex, the unit tangent rounded to Q14 and the handedness `w = ±16384`.
///
/// Each triangle's `dP/du` and `dP/dv` (edges solved against the texture
/// edges, area-weighted) are summed at its vertices; per vertex `dP/du` is
/// made orthogonal to the normal (Gram–Schmidt) and normalised, and
/// `w = sign((N × T)·dP/dv)`, so that `B = w · N × T` (`w = −1` where the
/// texture is mirrored). Triangles of zero texture area are skipped; an
/// unreferenced vertex gets some unit tangent orthogonal to its normal, `w = 1`.
///
/// Errors (nothing is written): `normals`, `uvs` or `out` shorter than
/// `positions`; a triangle index beyond the positions
/// ([`MeshError::IndexOutOfRange`]); a non-finite input
/// ([`MeshError::NotFinite`]); a referenced vertex whose triangles all have
/// degenerate texture coordinates, or whose `dP/du` is parallel to its normal
/// or zero ([`MeshError::Degenerate`]`("texcoords")`); a zero normal
/// ([`MeshError::Degenerate`]`("normal")`).
///
/// ```
/// use fixshade::mesh::vertex_tangents;
/// // a unit square in the xy plane facing +z, u along +x, v along +y
/// let pos = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let nrm = [[0.0, 0.0, 1.0]; 4];
/// let uv = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let mut t = [[0i16; 4]; 4];
/// vertex_tangents(&pos, &nrm, &uv, &[[0, 1, 2], [0, 2, 3]], &mut t)?;
/// assert_eq!(t[0], [16384, 0, 0, 16384]);
/// // mirrored in v: the handedness flips
/// let uv = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
/// vertex_tangents(&pos, &nrm, &uv, &[[0, 1, 2], [0, 2, 3]], &mut t)?;
/// assert_eq!(t[0], [16384, 0, 0, -16384]);
/// # Ok::<(), fixshade::error::MeshError>(())
/// ```
pub fn vertex_tangents(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    uvs: &[[f32; 2]],
    triangles: &[[u16; 3]],
    out: &mut [[i16; 4]],
) -> Result<(), MeshError> {
    tangents_into(positions, normals, uvs, triangles, out)
}

/// A tangent as stored: `f32` (the computed value) or Q14.
pub(crate) trait Tangent {
    /// From a unit tangent and its handedness `±1`.
    fn from_f32(t: [f32; 4]) -> Self;
}

impl Tangent for [f32; 4] {
    fn from_f32(t: [f32; 4]) -> Self {
        t
    }
}

impl Tangent for [i16; 4] {
    fn from_f32(t: [f32; 4]) -> Self {
        let q = |c: f32| libm::roundf(c.clamp(-1.0, 1.0) * 16384.0) as i16;
        [
            q(t[0]),
            q(t[1]),
            q(t[2]),
            if t[3] < 0.0 { -16384 } else { 16384 },
        ]
    }
}

/// [`vertex_tangents`] into any [`Tangent`] format.
pub(crate) fn tangents_into<T: Tangent>(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    uvs: &[[f32; 2]],
    triangles: &[[u16; 3]],
    out: &mut [T],
) -> Result<(), MeshError> {
    let n = positions.len();
    MeshError::check_len("normals", n, normals.len())?;
    MeshError::check_len("uvs", n, uvs.len())?;
    MeshError::check_len("out", n, out.len())?;
    for &c in positions.iter().chain(normals).flatten() {
        finite_or("positions/normals", c, MeshError::NotFinite)?;
    }
    for &c in uvs.iter().flatten() {
        finite_or("texcoords", c, MeshError::NotFinite)?;
    }
    check_indices(triangles, n)?;
    // pass 1 (validation, no writes): every referenced vertex must get a tangent
    let mut result = Ok(());
    accumulate(positions, uvs, triangles, |v, t| {
        if result.is_ok() {
            result = t.and_then(|t| finish(normals, v, t)).map(|_| ());
        }
    });
    result?;
    // pass 2: write
    accumulate(positions, uvs, triangles, |v, t| {
        if let (Some(o), Ok(Ok(r))) = (out.get_mut(v), t.map(|t| finish(normals, v, t))) {
            *o = T::from_f32(r);
        }
    });
    Ok(())
}

/// `dP/du`, `dP/dv` summed over the triangles of every vertex, reported to
/// `visit(vertex, sums)` once per vertex (`Err` for a referenced vertex without
/// a triangle of non-degenerate texture coordinates; unreferenced vertices
/// report zero sums). `O(V·T)` time without scratch memory would be too slow:
/// vertices are processed in blocks of 64 with one pass over the triangles
/// per block.
fn accumulate(
    positions: &[[f32; 3]],
    uvs: &[[f32; 2]],
    triangles: &[[u16; 3]],
    mut visit: impl FnMut(usize, Result<[[f64; 3]; 2], MeshError>),
) {
    const BLOCK: usize = 64;
    let n = positions.len();
    let mut base = 0;
    while base < n {
        let end = (base + BLOCK).min(n);
        let mut sums = [[[0.0f64; 3]; 2]; BLOCK];
        let mut used = [false; BLOCK];
        let mut valid = [false; BLOCK];
        for tri in triangles {
            let idx = tri.map(usize::from);
            if !idx.iter().any(|&i| i >= base && i < end) {
                continue;
            }
            // a triangle of zero uv area marks its vertices used, not valid
            let d = triangle_derivatives(positions, uvs, idx);
            for &i in &idx {
                if i >= base && i < end {
                    let k = i - base;
                    if let Some(u) = used.get_mut(k) {
                        *u = true;
                    }
                    if let (Some(d), Some(s), Some(v)) = (d, sums.get_mut(k), valid.get_mut(k)) {
                        for a in 0..2 {
                            for c in 0..3 {
                                s[a][c] += d[a][c];
                            }
                        }
                        *v = true;
                    }
                }
            }
        }
        for v in base..end {
            let k = v - base;
            let (u, ok) = (
                used.get(k).copied().unwrap_or(false),
                valid.get(k).copied().unwrap_or(false),
            );
            if u && !ok {
                visit(v, Err(MeshError::Degenerate("texcoords")));
            } else {
                visit(v, Ok(sums.get(k).copied().unwrap_or_default()));
            }
        }
        base = end;
    }
}

/// `(dP/du, dP/dv)` of a triangle scaled by its doubled uv area (so that the
/// sum over triangles weights by area), or `None` for zero uv area.
fn triangle_derivatives(
    positions: &[[f32; 3]],
    uvs: &[[f32; 2]],
    idx: [usize; 3],
) -> Option<[[f64; 3]; 2]> {
    let p = idx.map(|i| positions.get(i).copied().unwrap_or_default().map(f64::from));
    let t = idx.map(|i| uvs.get(i).copied().unwrap_or_default().map(f64::from));
    let e1 = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
    let e2 = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
    let (du1, dv1) = (t[1][0] - t[0][0], t[1][1] - t[0][1]);
    let (du2, dv2) = (t[2][0] - t[0][0], t[2][1] - t[0][1]);
    let det = du1 * dv2 - du2 * dv1;
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    // [e1; e2] = [du1 dv1; du2 dv2]·[dP/du; dP/dv], solved by Cramer and scaled by
    // |det| (the sign kept, so that mirrored triangles accumulate consistently)
    let s = det.signum();
    let dpdu = core::array::from_fn(|c| s * (dv2 * e1[c] - dv1 * e2[c]));
    let dpdv = core::array::from_fn(|c| s * (du1 * e2[c] - du2 * e1[c]));
    Some([dpdu, dpdv])
}

/// Gram–Schmidt and handedness for vertex `v`.
fn finish(normals: &[[f32; 3]], v: usize, s: [[f64; 3]; 2]) -> Result<[f32; 4], MeshError> {
    let n = normals.get(v).copied().unwrap_or_default().map(f64::from);
    let nl = libm::sqrt(dot3(n, n));
    if !(nl > 0.0) {
        return Err(MeshError::Degenerate("normal"));
    }
    let n = n.map(|c| c / nl);
    let [du, dv] = s;
    if du == [0.0; 3] && dv == [0.0; 3] {
        // unreferenced: any unit vector orthogonal to n
        let a = if n[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let t = orthonormal(n, a).unwrap_or([0.0, 0.0, 1.0]);
        return Ok([t[0] as f32, t[1] as f32, t[2] as f32, 1.0]);
    }
    let t = orthonormal(n, du).ok_or(MeshError::Degenerate("texcoords"))?;
    let w = if dot3(cross3(n, t), dv) < 0.0 {
        -1.0
    } else {
        1.0
    };
    Ok([t[0] as f32, t[1] as f32, t[2] as f32, w])
}

/// `a − (a·n)n`, normalised; `None` when (nearly) parallel to `n` or zero.
fn orthonormal(n: [f64; 3], a: [f64; 3]) -> Option<[f64; 3]> {
    let k = dot3(a, n);
    let t = [a[0] - k * n[0], a[1] - k * n[1], a[2] - k * n[2]];
    let l = libm::sqrt(dot3(t, t));
    let al = libm::sqrt(dot3(a, a));
    if !(l > 1e-6 * al) || !l.is_finite() {
        return None;
    }
    Some(t.map(|c| c / l))
}

#[cfg(test)]
mod tests {
    use super::*;

    type Square = ([[f32; 3]; 4], [[f32; 3]; 4], [[u16; 3]; 2]);

    fn sq() -> Square {
        let pos = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        (pos, [[0.0, 0.0, 1.0]; 4], [[0, 1, 2], [0, 2, 3]])
    }

    #[test]
    fn errors() {
        let (pos, nrm, tris) = sq();
        let uv = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut out = [[9.0f32; 4]; 4];
        assert_eq!(
            tangents_into(&pos, &nrm, &uv, &[[0, 1, 4]], &mut out),
            Err(MeshError::IndexOutOfRange {
                triangle: 0,
                index: 4
            })
        );
        assert_eq!(
            tangents_into(&pos, &nrm, &uv[..3], &tris, &mut out),
            Err(MeshError::BufferTooSmall {
                which: "uvs",
                needed: 4,
                got: 3
            })
        );
        assert_eq!(
            tangents_into(&pos, &nrm, &uv, &tris, &mut out[..2]),
            Err(MeshError::BufferTooSmall {
                which: "out",
                needed: 4,
                got: 2
            })
        );
        // all texture coordinates equal: degenerate, nothing written
        let flat = [[0.5, 0.5]; 4];
        assert_eq!(
            tangents_into(&pos, &nrm, &flat, &tris, &mut out),
            Err(MeshError::Degenerate("texcoords"))
        );
        // collinear texture coordinates
        let line = [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]];
        assert_eq!(
            tangents_into(&pos, &nrm, &line, &tris, &mut out),
            Err(MeshError::Degenerate("texcoords"))
        );
        assert!(out.iter().all(|t| *t == [9.0; 4]));
        // dP/du along the normal
        let tilted = [[0.0, 0.0, 1.0]; 4];
        let pos_z = [
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
            [0.0, 1.0, 0.0],
        ];
        assert_eq!(
            tangents_into(&pos_z, &tilted, &uv, &tris, &mut out),
            Err(MeshError::Degenerate("texcoords"))
        );
        let mut bad = uv;
        bad[2][0] = f32::NAN;
        assert_eq!(
            tangents_into(&pos, &nrm, &bad, &tris, &mut out),
            Err(MeshError::NotFinite("texcoords"))
        );
        assert_eq!(
            tangents_into(&pos, &[[0.0; 3]; 4], &uv, &tris, &mut out),
            Err(MeshError::Degenerate("normal"))
        );
    }

    #[test]
    fn unit_orthogonal_and_handed() {
        // a curved patch: a cylinder strip, normals radial, u around, v along the axis
        const N: usize = 9;
        let mut pos = [[0.0f32; 3]; 2 * N];
        let mut nrm = [[0.0f32; 3]; 2 * N];
        let mut uv = [[0.0f32; 2]; 2 * N];
        for i in 0..N {
            let a = i as f32 * 0.3;
            for j in 0..2 {
                let k = 2 * i + j;
                pos[k] = [libm::sinf(a), j as f32, libm::cosf(a)];
                nrm[k] = [libm::sinf(a), 0.0, libm::cosf(a)];
                uv[k] = [a, j as f32];
            }
        }
        let mut tris = [[0u16; 3]; 2 * (N - 1)];
        for i in 0..N - 1 {
            let (a, b, c, d) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
            tris[2 * i] = [a as u16, c as u16, d as u16];
            tris[2 * i + 1] = [a as u16, d as u16, b as u16];
        }
        for mirror in [false, true] {
            let uv = if mirror {
                uv.map(|t| [-t[0], t[1]])
            } else {
                uv
            };
            let mut out = [[0.0f32; 4]; 2 * N];
            tangents_into(&pos, &nrm, &uv, &tris, &mut out).unwrap();
            for (k, t) in out.iter().enumerate() {
                let tv = [t[0] as f64, t[1] as f64, t[2] as f64];
                let n = nrm[k].map(f64::from);
                assert!((dot3(tv, tv) - 1.0).abs() < 1e-6, "unit {t:?}");
                assert!(dot3(tv, n).abs() < 1e-6, "orthogonal {t:?}");
                // the exact tangent ∂P/∂u = (cos a, 0, −sin a), reversed when mirrored
                let a = (k / 2) as f64 * 0.3;
                let s = if mirror { -1.0 } else { 1.0 };
                let exact = [s * libm::cos(a), 0.0, -s * libm::sin(a)];
                assert!(dot3(tv, exact) > 0.995, "{k}: {t:?}");
                // B = w·N×T must point along +v (the axis, +y)
                let b = cross3(n, tv).map(|c| c * f64::from(t[3]));
                assert!(b[1] > 0.99, "{k} mirror {mirror}: {t:?}");
                assert_eq!(t[3], if mirror { -1.0 } else { 1.0 });
            }
        }
    }

    #[test]
    fn unreferenced_vertices_get_some_tangent() {
        let (pos, nrm, _) = sq();
        let uv = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut out = [[0.0f32; 4]; 4];
        tangents_into(&pos, &nrm, &uv, &[[0, 1, 2]], &mut out).unwrap();
        assert_eq!(out[3][2], 0.0);
        assert!((out[3][0].hypot(out[3][1]) - 1.0).abs() < 1e-6);
    }
}
