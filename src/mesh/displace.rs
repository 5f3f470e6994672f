//! Displacement mapping at load time: every vertex moved along its normal by
//! a height read from a texture at the vertex's texture coordinates, normals
//! recomputed, the result converted back to the compact [`Mesh`] format.

use super::compact::{round_i16, Mesh, NORMAL_ONE, TEXCOORD_FRAC};
use super::normals::{vertex_normals_welded, Weighting};
use crate::error::MeshError;
use crate::texture::{Filter, TexCoord, Texture, TEX_FRAC};

/// For every vertex, the lowest index with the same raw position (its
/// *representative*), into `out[..positions.len()]`; returns the number of
/// vertices. Vertices duplicated at a texture seam share a representative.
/// Load-time work, `O(V²)` comparisons (130 000 for the 423 vertices of the
/// textured 24 × 16 sphere).
///
/// # Errors
///
/// [`MeshError::BufferTooSmall`] when `out` is shorter than the positions;
/// [`MeshError::TooManyVertices`] beyond 65536 positions.
pub(crate) fn weld_by_position(
    positions: &[[i16; 3]],
    out: &mut [u16],
) -> Result<usize, MeshError> {
    let n = positions.len();
    if n > 1 << 16 {
        return Err(MeshError::TooManyVertices { needed: n });
    }
    MeshError::check_len("out", n, out.len())?;
    for (i, p) in positions.iter().enumerate() {
        let r = positions.iter().position(|q| q == p).unwrap_or(i);
        if let Some(o) = out.get_mut(i) {
            // r ≤ i < 2^16
            *o = r as u16;
        }
    }
    Ok(n)
}

/// The height at texture coordinate `uv` (Q12): the first channel of the
/// bilinear sample (the grey level of a `Gray8` texture) over 255, in `[0, 1]`.
fn height(tex: &Texture<'_>, uv: [i16; 2]) -> f32 {
    let q = |c: i16| i32::from(c) << (TEX_FRAC - TEXCOORD_FRAC);
    let s = tex.sample(
        TexCoord {
            u: q(uv[0]),
            v: q(uv[1]),
        },
        Filter::Bilinear,
    );
    f32::from(s[0]) / 255.0
}

/// `v / |v|` in `f64`, or `v` unchanged when its length is zero or not finite.
fn normalize(v: [f32; 3]) -> [f32; 3] {
    let d = v.map(f64::from);
    let len = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if !(len > 0.0 && len.is_finite()) {
        return v;
    }
    d.map(|c| (c / len) as f32)
}

/// Displaces `mesh` by the height map `heights`: vertex `i` moves to
/// `p_i + scale · h(uv_i) · n_i` (model units; `n_i` its Q14 normal as `f32`,
/// `h` the first channel of the bilinear sample at its texture coordinates,
/// over 255, so in `[0, 1]`), into `positions`; the new vertex normals into
/// `normals`. Returns the number of vertices.
///
/// **Seams.** Vertices with the same raw position (a texture seam, a pole
/// fan) are welded (into `weld`, each vertex's representative: the lowest
/// index with its position): they take the representative's height, normal
/// and displacement, so no crack opens, and their normals are computed over
/// the faces of all of them together.
///
/// **Normals.** `n'_i = normalize(n_i + avg(displaced)_i − avg(base)_i)`, the
/// averages area-weighted and welded ([`vertex_normals`](super::vertex_normals);
/// `scratch` holds the base's): a normal changes as much as its face average,
/// and a zero displacement gives back the mesh's (analytic) normals.
///
/// # Errors
///
/// [`MeshError::MissingAttribute`] for a mesh without texture coordinates;
/// [`MeshError::NotFinite`] for a NaN or infinite `scale`;
/// [`MeshError::BufferTooSmall`] when `weld`, `scratch`, `positions` or
/// `normals` is shorter than the mesh's vertices. The outputs are not written
/// then.
///
/// ```
/// use fixshade::mesh::*;
/// use fixshade::texture::{Texels, Texture, Wrap};
/// const N: (usize, usize) = textured_sphere_counts(8, 12);
/// static SPHERE: TexturedMeshData<{ N.0 }, { N.1 }> = TexturedMeshData::uv_sphere(8, 12, 13);
/// // a height map: a bump along the equator (v = ½)
/// let mut h = [0u8; 16 * 16];
/// for (i, t) in h.iter_mut().enumerate() {
///     *t = if (6..10).contains(&(i / 16)) { 255 } else { 0 };
/// }
/// let tex = Texture::new(Texels::Gray8(&h), 4, 4, Wrap::Repeat).unwrap();
/// let (mut weld, mut scratch) = ([0u16; N.0], [[0.0f32; 3]; N.0]);
/// let (mut p, mut n) = ([[0.0f32; 3]; N.0], [[0.0f32; 3]; N.0]);
/// displace(&SPHERE.mesh(), &tex, 0.1, &mut weld, &mut scratch, &mut p, &mut n)?;
/// // back to the compact format, for the renderer
/// let (mut pc, mut nc) = ([[0i16; 3]; N.0], [[0i16; 3]; N.0]);
/// to_compact(&p, &n, 13, &mut pc, &mut nc)?;
/// let bumpy = Mesh::new(&pc, &nc, &SPHERE.triangles, 13)?.with_texcoords(&SPHERE.texcoords)?;
/// assert_eq!(bumpy.triangle_count(), N.1);
/// # Ok::<(), fixshade::error::MeshError>(())
/// ```
pub fn displace(
    mesh: &Mesh<'_>,
    heights: &Texture<'_>,
    scale: f32,
    weld: &mut [u16],
    scratch: &mut [[f32; 3]],
    positions: &mut [[f32; 3]],
    normals: &mut [[f32; 3]],
) -> Result<usize, MeshError> {
    let n = mesh.vertex_count();
    let uv = mesh.texcoords();
    if uv.len() < n {
        return Err(MeshError::MissingAttribute("texture coordinates"));
    }
    if !scale.is_finite() {
        return Err(MeshError::NotFinite("scale"));
    }
    for (which, got) in [
        ("weld", weld.len()),
        ("scratch", scratch.len()),
        ("positions", positions.len()),
        ("normals", normals.len()),
    ] {
        MeshError::check_len(which, n, got)?;
    }
    weld_by_position(mesh.positions(), weld)?;
    let weld = weld.get(..n).unwrap_or(&[]);
    let positions = positions.get_mut(..n).unwrap_or(&mut []);
    let normals = normals.get_mut(..n).unwrap_or(&mut []);
    let base = |i: usize| mesh.position(i).unwrap_or([0.0; 3]);
    let nrm = |i: usize| mesh.normal(i).unwrap_or([0.0; 3]);
    // the base positions first: their welded face averages into `scratch`
    for (i, p) in positions.iter_mut().enumerate() {
        *p = base(i);
    }
    vertex_normals_welded(positions, mesh.triangles(), Weighting::Area, weld, scratch)?;
    for (i, p) in positions.iter_mut().enumerate() {
        let r = weld.get(i).map_or(i, |&r| usize::from(r));
        let d = scale * height(heights, uv.get(r).copied().unwrap_or([0; 2]));
        let (b, m) = (base(r), nrm(r));
        *p = [b[0] + d * m[0], b[1] + d * m[1], b[2] + d * m[2]];
    }
    vertex_normals_welded(positions, mesh.triangles(), Weighting::Area, weld, normals)?;
    for (i, o) in normals.iter_mut().enumerate() {
        let r = weld.get(i).map_or(i, |&r| usize::from(r));
        let (m, s) = (nrm(r), scratch.get(i).copied().unwrap_or([0.0; 3]));
        *o = normalize([m[0] + o[0] - s[0], m[1] + o[1] - s[1], m[2] + o[2] - s[2]]);
    }
    Ok(n)
}

/// Converts `f32` positions and unit normals to the compact [`Mesh`] format:
/// positions `round(p · 2^frac)` as `i16`, normals in Q14; returns the number
/// of vertices.
///
/// Choose the largest `frac` with `max|p| · 2^frac < 32767.5` (a step of
/// `2^−frac` model units): 14 for a model within ±2, 12 within ±8, as the
/// importer (`import/`) does.
///
/// # Errors
///
/// [`MeshError::OutOfRange`] (`"frac"`) for `frac > 15`;
/// [`MeshError::PositionOutOfRange`] for a coordinate that does not fit an
/// `i16` at `frac` bits (naming the vertex, the axis and the most fraction
/// bits at which it fits);
/// [`MeshError::NotFinite`] for a NaN or infinite position or normal;
/// [`MeshError::BufferTooSmall`] for short inputs or outputs. The outputs may
/// be partly written on error.
///
/// ```
/// use fixshade::mesh::to_compact;
/// use fixshade::error::MeshError;
/// let (mut p, mut n) = ([[0i16; 3]; 1], [[0i16; 3]; 1]);
/// to_compact(&[[0.5, -1.0, 0.0]], &[[0.0, 1.0, 0.0]], 14, &mut p, &mut n)?;
/// assert_eq!((p[0], n[0]), ([8192, -16384, 0], [0, 16384, 0]));
/// let err = to_compact(&[[2.5, 0.0, 0.0]], &[[0.0; 3]], 14, &mut p, &mut n);
/// assert_eq!(
///     err,
///     Err(MeshError::PositionOutOfRange { vertex: 0, axis: 0, frac: 14, fits: Some(13) })
/// );
/// assert_eq!(
///     err.unwrap_err().to_string(),
///     "vertex 0: x does not fit an i16 at frac 14 (it fits at frac 13 or less)"
/// );
/// # Ok::<(), MeshError>(())
/// ```
pub fn to_compact(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    frac: u8,
    out_positions: &mut [[i16; 3]],
    out_normals: &mut [[i16; 3]],
) -> Result<usize, MeshError> {
    if frac > 15 {
        return Err(MeshError::OutOfRange("frac"));
    }
    let n = positions.len();
    MeshError::check_len("normals", n, normals.len())?;
    MeshError::check_len("out_positions", n, out_positions.len())?;
    MeshError::check_len("out_normals", n, out_normals.len())?;
    let scale = f64::from(1u32 << frac);
    let fit = |x: f64| (-32768.5..32767.5).contains(&x);
    for (vertex, ((p, m), (op, on))) in positions
        .iter()
        .zip(normals)
        .zip(out_positions.iter_mut().zip(out_normals.iter_mut()))
        .enumerate()
    {
        for c in 0..3 {
            let (pc, mc) = (f64::from(p[c]), f64::from(m[c]));
            if !(pc.is_finite() && mc.is_finite()) {
                return Err(MeshError::NotFinite("position or normal"));
            }
            if !fit(pc * scale) {
                return Err(MeshError::PositionOutOfRange {
                    vertex,
                    axis: c as u8,
                    frac,
                    fits: (0..frac).rev().find(|&k| fit(pc * f64::from(1u32 << k))),
                });
            }
            op[c] = round_i16(pc * scale);
            on[c] = round_i16(mc * f64::from(NORMAL_ONE));
        }
    }
    Ok(n)
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::mesh::{textured_sphere_counts, TexturedMeshData};
    use crate::texture::{Texels, Wrap};

    const N: (usize, usize) = textured_sphere_counts(16, 24);
    static SPHERE: TexturedMeshData<{ N.0 }, { N.1 }> = TexturedMeshData::uv_sphere(16, 24, 13);

    #[test]
    fn weld_names_the_lowest_index_of_a_position() {
        let mut w = [0u16; 3];
        assert_eq!(
            weld_by_position(&[[1, 2, 3], [4, 5, 6], [1, 2, 3]], &mut w),
            Ok(3)
        );
        assert_eq!(w, [0, 1, 0]);
    }

    struct Out {
        weld: [u16; N.0],
        scratch: [[f32; 3]; N.0],
        p: [[f32; 3]; N.0],
        n: [[f32; 3]; N.0],
    }

    fn run(tex: &Texture<'_>, scale: f32) -> Out {
        let mut o = Out {
            weld: [0; N.0],
            scratch: [[0.0; 3]; N.0],
            p: [[0.0; 3]; N.0],
            n: [[0.0; 3]; N.0],
        };
        displace(
            &SPHERE.mesh(),
            tex,
            scale,
            &mut o.weld,
            &mut o.scratch,
            &mut o.p,
            &mut o.n,
        )
        .unwrap();
        o
    }

    /// A deterministic noisy height map, 32 × 16.
    fn noise() -> [u8; 512] {
        let mut s = 12345u32;
        core::array::from_fn(|_| {
            s = s.wrapping_mul(1_103_515_245).wrapping_add(12345);
            (s >> 16) as u8
        })
    }

    #[test]
    fn zero_displacement_gives_back_the_base_mesh() {
        let h = noise();
        let tex = Texture::new(Texels::Gray8(&h), 5, 4, Wrap::Repeat).unwrap();
        for scale in [0.0f32, -0.0] {
            let o = run(&tex, scale);
            let mesh = SPHERE.mesh();
            let (mut pc, mut nc) = ([[0i16; 3]; N.0], [[0i16; 3]; N.0]);
            to_compact(&o.p, &o.n, 13, &mut pc, &mut nc).unwrap();
            assert_eq!(pc, SPHERE.positions);
            assert_eq!(nc, SPHERE.normals);
            for i in 0..N.0 {
                assert_eq!(Some(o.p[i]), mesh.position(i));
                let b = mesh.normal(i).unwrap();
                for c in 0..3 {
                    assert!((o.n[i][c] - b[c]).abs() < 1e-4, "{i}");
                }
            }
        }
    }

    #[test]
    fn constant_height_scales_the_unit_sphere() {
        for (level, scale) in [(255u8, 0.25f32), (255, -0.5), (51, 1.0), (0, 3.0)] {
            let h = [level; 64];
            let tex = Texture::new(Texels::Gray8(&h), 3, 3, Wrap::Repeat).unwrap();
            let o = run(&tex, scale);
            let want = 1.0 + f64::from(level) / 255.0 * f64::from(scale);
            for i in 0..N.0 {
                let p = o.p[i].map(f64::from);
                let r = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                // the Q13 base positions are within 1e-4 of the unit sphere
                assert!(
                    (r - want).abs() < 2e-4 * want.abs().max(1.0),
                    "{i}: {r} vs {want}"
                );
                // normals stay radial
                let b = SPHERE.mesh().normal(i).unwrap();
                for c in 0..3 {
                    assert!((o.n[i][c] - b[c]).abs() < 2e-3, "{i}");
                }
            }
        }
    }

    #[test]
    fn seams_move_identically_and_share_normals() {
        // a height map whose u = 0 and u = 1 columns differ under Clamp: the
        // weld must still keep the seam closed
        let h = noise();
        for wrap in [Wrap::Repeat, Wrap::Clamp] {
            let tex = Texture::new(Texels::Gray8(&h), 5, 4, wrap).unwrap();
            let o = run(&tex, 0.3);
            let mut pairs = 0;
            for i in 0..N.0 {
                for j in i + 1..N.0 {
                    if SPHERE.positions[i] == SPHERE.positions[j] {
                        assert_eq!(o.p[i], o.p[j], "{i} {j}: crack");
                        assert_eq!(o.n[i], o.n[j], "{i} {j}: normals differ");
                        pairs += 1;
                    }
                }
            }
            // 15 seam pairs, 2 × C(24, 2) pole pairs
            assert_eq!(pairs, 15 + 2 * 24 * 23 / 2);
            // every edge of the displaced mesh is shared by exactly two
            // triangles once welded: no crack anywhere
            let mut count = std::collections::HashMap::new();
            for t in &SPHERE.triangles {
                for k in 0..3 {
                    let (a, b) = (
                        o.weld[usize::from(t[k])],
                        o.weld[usize::from(t[(k + 1) % 3])],
                    );
                    if a != b {
                        *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                    }
                }
            }
            assert!(count.values().all(|&c| c == 2));
        }
    }

    #[test]
    fn errors() {
        static POS: [[i16; 3]; 3] = [[0, 0, 0], [256, 0, 0], [0, 256, 0]];
        static NRM: [[i16; 3]; 3] = [[0, 0, NORMAL_ONE]; 3];
        let m = Mesh::new(&POS, &NRM, &[[0, 1, 2]], 8).unwrap();
        let h = [0u8; 1];
        let tex = Texture::new(Texels::Gray8(&h), 0, 0, Wrap::Repeat).unwrap();
        let (mut w, mut s, mut p, mut n) = (
            [0u16; 3],
            [[0.0f32; 3]; 3],
            [[0.0f32; 3]; 3],
            [[0.0f32; 3]; 3],
        );
        assert_eq!(
            displace(&m, &tex, 1.0, &mut w, &mut s, &mut p, &mut n),
            Err(MeshError::MissingAttribute("texture coordinates"))
        );
        let uv = [[0i16; 2]; 3];
        let m = m.with_texcoords(&uv).unwrap();
        assert_eq!(
            displace(&m, &tex, f32::NAN, &mut w, &mut s, &mut p, &mut n),
            Err(MeshError::NotFinite("scale"))
        );
        assert_eq!(
            displace(&m, &tex, 1.0, &mut w[..2], &mut s, &mut p, &mut n),
            Err(MeshError::BufferTooSmall {
                which: "weld",
                needed: 3,
                got: 2
            })
        );
        assert!(displace(&m, &tex, 1.0, &mut w, &mut s, &mut p, &mut n).is_ok());
        let (mut pc, mut nc) = ([[0i16; 3]; 1], [[0i16; 3]; 1]);
        assert_eq!(
            to_compact(&[[f32::NAN; 3]], &[[0.0; 3]], 8, &mut pc, &mut nc),
            Err(MeshError::NotFinite("position or normal"))
        );
        assert_eq!(
            to_compact(&[[0.0; 3]], &[[0.0; 3]], 16, &mut pc, &mut nc),
            Err(MeshError::OutOfRange("frac"))
        );
    }

    #[test]
    fn a_coordinate_out_of_range_names_its_vertex_axis_and_fitting_frac() {
        let (mut p, mut n) = ([[0i16; 3]; 3], [[0i16; 3]; 3]);
        let pos = [[0.0; 3], [1.0, -1.0, 1.0], [0.5, 0.25, -9.0]];
        // -9 fits at frac 11 (−18432), not 12 (−36864)
        assert_eq!(
            to_compact(&pos, &[[0.0; 3]; 3], 14, &mut p, &mut n),
            Err(MeshError::PositionOutOfRange {
                vertex: 2,
                axis: 2,
                frac: 14,
                fits: Some(11)
            })
        );
        assert_eq!(to_compact(&pos, &[[0.0; 3]; 3], 11, &mut p, &mut n), Ok(3));
        assert_eq!(p[2][2], -18432);
        let far = [[0.0, 40000.0, 0.0]];
        let err = to_compact(&far, &[[0.0; 3]], 0, &mut p[..1], &mut n[..1]).unwrap_err();
        assert_eq!(
            err,
            MeshError::PositionOutOfRange {
                vertex: 0,
                axis: 1,
                frac: 0,
                fits: None
            }
        );
        assert!(std::format!("{err}").contains("nor at frac 0"), "{err}");
    }
}
