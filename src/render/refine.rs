//! Silhouette refinement: the triangles along a mesh's outline subdivided
//! every frame with curved (PN triangle) positions and normals, so that a
//! coarse mesh shows a round outline.
//!
//! # What is split
//!
//! The decision is made per **edge**, from its two vertices only, so both
//! triangles sharing an edge split it identically and no crack opens:
//!
//! 1. every mesh vertex is classified for the current view by `N·V`, its
//!    eye-space normal against the direction to the viewer (`V = (0, 0, 1)`
//!    for an orthographic transform, towards the eye for a perspective one):
//!    *front* when `N·V > τ`, *back* when `N·V < −τ`, *near* otherwise
//!    (`τ` = [`Refine::threshold`], Q14; `τ = 0` is the plain sign test);
//! 2. an edge is a *silhouette edge* unless both its vertices are front or
//!    both are back (its normals straddle `N·V = 0`, or one of them lies
//!    within `τ` of it);
//! 3. a silhouette edge is split at its midpoint, in the order the triangles
//!    of the mesh meet it, while the budget lasts: the first triangle that
//!    meets it creates its vertex, the second finds it again (a short list per
//!    vertex), so an edge is either split for both its triangles or for
//!    neither. Once the budget of new vertices is spent, the remaining
//!    silhouette edges stay whole and their triangles are drawn flat, as
//!    without refinement: still crack-free, just less round.
//!
//! A triangle with 1, 2 or 3 split edges becomes 2, 3 or 4 triangles (one
//! level of subdivision); each is culled, binned and drawn like a mesh
//! triangle.
//!
//! # The new vertex
//!
//! The midpoint of the cubic Bézier edge of the PN triangle (Vlachos et al.,
//! 2001) over the edge `(P_i, N_i)`–`(P_j, N_j)`:
//! `M = (P_i + P_j)/2 − (w_ij·N_i + w_ji·N_j)/8`, `w_ij = (P_j − P_i)·N_i`;
//! its normal the midpoint of the quadratic normal edge,
//! `normalize(N_i + N_j + 2·n_ij)`, `n_ij = normalize(N_i + N_j − v_ij·(P_j − P_i))`,
//! `v_ij = 2·(P_j − P_i)·(N_i + N_j) / |P_j − P_i|²`. All in integers, in
//! model space on the mesh's raw `i16` positions and Q14 normals, and
//! symmetric in `i` and `j` (the same bits whichever triangle or seam copy
//! computes it). Texture coordinates are averaged, tangents averaged and
//! normalised. The new vertex then goes through the vertex stage like a mesh
//! vertex (transform, projection, [`Kernel::vertex`]) into the refinement's
//! own cache slots.
//!
//! On a unit sphere the new vertices land within `10⁻⁴` of the sphere for
//! the 15° edges of the 24 × 16 UV sphere (the chord midpoint is `0.0086`
//! inside): the outline's largest radial error drops about four-fold.

use super::vertex::{self, CachedVertex};
use crate::camera::{MeshTransform, Projection};
use crate::mesh::Mesh;
use crate::shade::Kernel;

/// No edge in a vertex's list (14 bits).
const NONE: u16 = 0x3FFF;
/// The class bits of a vertex word.
const CLASS_SHIFT: u32 = 14;
const FRONT: u16 = 1;
const BACK: u16 = 2;

/// The most new vertices one frame can add (14-bit edge lists).
pub const MAX_NEW_VERTICES: usize = NONE as usize;

/// The caller-owned memory of silhouette refinement, as slices (see
/// [`RefineBuffers`] for arrays sized by const generics):
///
/// | slice | length | bytes each |
/// |---|---|---|
/// | `vertex_words` | ≥ mesh vertices | 2 |
/// | `edges`, `positions`, `normals`, `vertices` | new-vertex budget `E` | 6, 6, 6, `size_of::<CachedVertex<V>>()` |
/// | `texcoords`, `tangents` | `E` when the mesh has them, else may be empty | 4, 8 |
/// | `triangles` | triangle budget (`4·E` never runs out on a closed mesh) | 8 |
#[derive(Debug)]
pub struct RefineMemory<'a, V> {
    /// One word per mesh vertex: its class and the head of its edge list.
    pub vertex_words: &'a mut [u16],
    /// The split edges `[i, j, next]` (`i < j`), one per new vertex.
    pub edges: &'a mut [[u16; 3]],
    /// New vertices: raw positions (the mesh's fraction bits).
    pub positions: &'a mut [[i16; 3]],
    /// New vertices: Q14 normals.
    pub normals: &'a mut [[i16; 3]],
    /// New vertices: Q12 texture coordinates.
    pub texcoords: &'a mut [[i16; 2]],
    /// New vertices: Q14 tangents and handedness.
    pub tangents: &'a mut [[i16; 4]],
    /// New vertices: the vertex cache slots.
    pub vertices: &'a mut [CachedVertex<V>],
    /// The triangles replacing refined ones: three vertex indices (mesh
    /// vertices first, then the new ones) and the mesh triangle replaced.
    pub triangles: &'a mut [[u16; 4]],
}

/// Silhouette refinement for [`MeshDraw::with_refinement`](super::MeshDraw::with_refinement):
/// its memory and the threshold `τ` (Q14, `0..=16384`; see the [module](self)
/// docs). `τ = 0` splits only the edges whose vertex normals straddle
/// `N·V = 0`; a larger `τ` also splits edges next to the silhouette (rounder
/// for coarse meshes, more triangles).
#[derive(Debug)]
pub struct Refine<'a, V> {
    /// The memory.
    pub memory: RefineMemory<'a, V>,
    /// `τ` in Q14 (values above 16384 act as 16384).
    pub threshold: u16,
}

/// [`RefineMemory`] as arrays: `NV` mesh vertices, a budget of `E` new
/// vertices and `T` new triangles (`T = 4·E` never runs out on a closed
/// mesh).
///
/// ```
/// use fixshade::render::RefineBuffers;
/// // the standard sphere (362 vertices), Gouraud payload, 192 new vertices
/// let b: RefineBuffers<[u16; 3], 362, 192, 768> = RefineBuffers::new();
/// assert_eq!(core::mem::size_of_val(&b), 362 * 2 + 192 * (6 + 6 + 6 + 4 + 8 + 12) + 768 * 8);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct RefineBuffers<V, const NV: usize, const E: usize, const T: usize> {
    words: [u16; NV],
    edges: [[u16; 3]; E],
    positions: [[i16; 3]; E],
    normals: [[i16; 3]; E],
    texcoords: [[i16; 2]; E],
    tangents: [[i16; 4]; E],
    vertices: [CachedVertex<V>; E],
    triangles: [[u16; 4]; T],
}

impl<V: Copy + Default, const NV: usize, const E: usize, const T: usize>
    RefineBuffers<V, NV, E, T>
{
    /// Zeroed buffers.
    pub fn new() -> Self {
        RefineBuffers {
            words: [0; NV],
            edges: [[0; 3]; E],
            positions: [[0; 3]; E],
            normals: [[0; 3]; E],
            texcoords: [[0; 2]; E],
            tangents: [[0; 4]; E],
            vertices: [CachedVertex::default(); E],
            triangles: [[0; 4]; T],
        }
    }

    /// The buffers as slices.
    pub fn memory(&mut self) -> RefineMemory<'_, V> {
        RefineMemory {
            vertex_words: &mut self.words,
            edges: &mut self.edges,
            positions: &mut self.positions,
            normals: &mut self.normals,
            texcoords: &mut self.texcoords,
            tangents: &mut self.tangents,
            vertices: &mut self.vertices,
            triangles: &mut self.triangles,
        }
    }

    /// The buffers with threshold `τ` (Q14).
    pub fn refine(&mut self, threshold: u16) -> Refine<'_, V> {
        Refine {
            memory: self.memory(),
            threshold,
        }
    }
}

impl<V: Copy + Default, const NV: usize, const E: usize, const T: usize> Default
    for RefineBuffers<V, NV, E, T>
{
    fn default() -> Self {
        Self::new()
    }
}

/// What one frame's refinement produced.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct RefineStats {
    /// Edges split (new vertices).
    pub vertices: usize,
    /// Mesh triangles replaced.
    pub refined: usize,
    /// Triangles replacing them.
    pub triangles: usize,
    /// Silhouette edges left whole because the budget ran out.
    pub skipped: usize,
}

/// The refinement's results, borrowed by the `MeshDraw`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Refined<'a, V> {
    pub vertices: &'a [CachedVertex<V>],
    pub positions: &'a [[i16; 3]],
    pub triangles: &'a [[u16; 4]],
    pub stats: RefineStats,
}

impl<V> Refined<'_, V> {
    /// Whether mesh triangle `t` is replaced (binary search over the parents,
    /// which increase).
    #[inline]
    pub(crate) fn replaced(&self, t: usize) -> bool {
        if self.triangles.is_empty() {
            return false;
        }
        self.triangles
            .binary_search_by(|r| usize::from(r[3]).cmp(&t))
            .is_ok()
    }
}

/// Why the refinement's memory does not fit the mesh.
pub(crate) struct Short {
    pub buffer: &'static str,
    pub needed: usize,
    pub got: usize,
}

/// The class of a vertex with eye-space normal `n` and eye-space position
/// `e` (perspective) for threshold `tau` (Q14).
#[inline]
fn class<P: Projection>(n: [i32; 3], e: [i32; 3], tau: u32) -> u16 {
    if P::PERSPECTIVE {
        // N·V·|e| = −n·e; compare with τ·|n|·|e| (exact in i128/u128)
        let d: i128 = -(0..3)
            .map(|c| i128::from(n[c]) * i128::from(e[c]))
            .sum::<i128>();
        if tau == 0 {
            return sign_class(d.signum() as i32);
        }
        let n2: u128 = (0..3)
            .map(|c| (i128::from(n[c]) * i128::from(n[c])) as u128)
            .sum();
        let e2: u128 = (0..3)
            .map(|c| (i128::from(e[c]) * i128::from(e[c])) as u128)
            .sum();
        let d2 = d.unsigned_abs().saturating_mul(d.unsigned_abs());
        // d² · 2^28 > τ² · n² · e² (each factor < 2^96 / 2^64: saturating)
        let lhs = d2.saturating_mul(1 << 28);
        let rhs = u128::from(tau * tau).saturating_mul(n2.saturating_mul(e2));
        if lhs > rhs {
            sign_class(d.signum() as i32)
        } else {
            0
        }
    } else {
        let a = n[2];
        if tau == 0 {
            return sign_class(a.signum());
        }
        let n2: u64 = n.iter().map(|&c| u64::from(c.unsigned_abs()).pow(2)).sum();
        let a2 = u64::from(a.unsigned_abs()).pow(2);
        // a² · 2^28 > τ² · |n|²: a² < 2^32, |n|² < 2^34, τ² ≤ 2^28
        if a2 << 28 > u64::from(tau * tau).saturating_mul(n2) {
            sign_class(a.signum())
        } else {
            0
        }
    }
}

#[inline]
fn sign_class(s: i32) -> u16 {
    match s {
        1 => FRONT,
        -1 => BACK,
        _ => 0,
    }
}

/// Whether an edge between vertices of classes `a` and `b` is a silhouette
/// edge.
#[inline]
fn silhouette(a: u16, b: u16) -> bool {
    !(a == b && a != 0)
}

/// `round(√(x² + y² + z²))`-normalised `v` in Q14 (`v` with components below
/// 2^17), or `None` when it vanishes.
fn unit_q14(v: [i32; 3]) -> Option<[i16; 3]> {
    // shift so that every component is below 2^14: squares sum below 2^30
    let m = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
    if m == 0 {
        return None;
    }
    let s = (32 - m.leading_zeros()).saturating_sub(14);
    let w = v.map(|c| c >> s);
    let len2: u32 = w.iter().map(|&c| c.unsigned_abs() * c.unsigned_abs()).sum();
    let len = len2.isqrt();
    if len == 0 {
        return None;
    }
    let len = len as i32;
    // |c| ≤ len, so c · 2^14 / len ≤ 2^14 (< 2^31 before the division)
    Some(w.map(|c| ((c << 14) / len).clamp(-16384, 16384) as i16))
}

/// The data of the new vertex on the edge between mesh vertices `i` and `j`:
/// position, normal, texture coordinates, tangent (see the module docs).
/// Symmetric in `i` and `j`.
#[allow(clippy::type_complexity)]
fn midpoint(
    mesh: &Mesh<'_>,
    i: usize,
    j: usize,
) -> Option<([i16; 3], [i16; 3], [i16; 2], [i16; 4])> {
    let (pi, pj) = (*mesh.positions().get(i)?, *mesh.positions().get(j)?);
    let (ni, nj) = (*mesh.normals().get(i)?, *mesh.normals().get(j)?);
    let pi64 = pi.map(i64::from);
    let pj64 = pj.map(i64::from);
    let ni64 = ni.map(i64::from);
    let nj64 = nj.map(i64::from);
    let d: [i64; 3] = core::array::from_fn(|c| pj64[c] - pi64[c]);
    let dot = |a: [i64; 3], b: [i64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // w_ij = d·N_i, w_ji = −d·N_j (raw · 2^14); products < 2^46
    let (wij, wji) = (dot(d, ni64), -dot(d, nj64));
    let pos: [i16; 3] = core::array::from_fn(|c| {
        // (P_i + P_j)/2 − (w_ij N_i + w_ji N_j)/8, in raw · 2^31, rounded
        let num = ((pi64[c] + pj64[c]) << 30) - (wij * ni64[c] + wji * nj64[c]);
        ((num + (1 << 30)) >> 31).clamp(-32768, 32767) as i16
    });
    // quadratic normal: n_ij = N_i + N_j − v·d, v = 2 d·(N_i + N_j) / |d|²
    let s: [i64; 3] = core::array::from_fn(|c| ni64[c] + nj64[c]);
    let dd = dot(d, d);
    let mut h = s;
    if dd > 0 {
        // f = 2 (d·s) / |d|² in Q14, bounded so that f·d stays small
        let f = ((2 * dot(d, s)) << 14) / dd;
        let f = f.clamp(-(1 << 30), 1 << 30);
        for c in 0..3 {
            h[c] -= (f * d[c]) >> 14;
        }
    }
    let h = h.map(|c| c.clamp(-(1 << 16), 1 << 16) as i32);
    let nij = unit_q14(h).unwrap_or([0; 3]);
    let sum: [i32; 3] =
        core::array::from_fn(|c| i32::from(ni[c]) + i32::from(nj[c]) + 2 * i32::from(nij[c]));
    let normal = unit_q14(sum).unwrap_or(ni);
    let uv = match (mesh.texcoords().get(i), mesh.texcoords().get(j)) {
        (Some(a), Some(b)) => {
            core::array::from_fn(|c| ((i32::from(a[c]) + i32::from(b[c]) + 1) >> 1) as i16)
        }
        _ => [0; 2],
    };
    let tangent = match (mesh.tangents().get(i), mesh.tangents().get(j)) {
        (Some(a), Some(b)) => {
            let t = unit_q14(core::array::from_fn(|c| i32::from(a[c]) + i32::from(b[c])))
                .unwrap_or([a[0], a[1], a[2]]);
            // the handedness of the copy with the larger value (symmetric)
            [t[0], t[1], t[2], a[3].max(b[3])]
        }
        _ => [0; 4],
    };
    Some((pos, normal, uv, tangent))
}

/// Runs the refinement of one frame: classifies the vertices, splits the
/// silhouette edges within the budget, runs the vertex stage on the new
/// vertices and writes the replacing triangles.
pub(crate) fn build<'a, K: Kernel, P: Projection>(
    mesh: &Mesh<'_>,
    t: &MeshTransform<P>,
    kernel: &K,
    refine: Refine<'a, K::Vertex>,
) -> Result<Refined<'a, K::Vertex>, Short> {
    let tau = u32::from(refine.threshold.min(16384));
    let m = refine.memory;
    let nv = mesh.vertex_count();
    if m.vertex_words.len() < nv {
        return Err(Short {
            buffer: "refine vertex words",
            needed: nv,
            got: m.vertex_words.len(),
        });
    }
    // the budget: every per-new-vertex slice, 4 triangles per new vertex,
    // and indices within u16
    let mut budget = m
        .edges
        .len()
        .min(m.positions.len())
        .min(m.normals.len())
        .min(m.vertices.len())
        .min(m.triangles.len() / 4)
        .min(MAX_NEW_VERTICES - 1)
        .min(usize::from(u16::MAX).saturating_sub(nv));
    if !mesh.texcoords().is_empty() {
        budget = budget.min(m.texcoords.len());
    }
    if !mesh.tangents().is_empty() {
        budget = budget.min(m.tangents.len());
    }
    let words = m.vertex_words.get_mut(..nv).unwrap_or(&mut []);
    for (i, w) in words.iter_mut().enumerate() {
        let (p, n) = (
            mesh.positions().get(i).copied().unwrap_or([0; 3]),
            mesh.normals().get(i).copied().unwrap_or([0; 3]),
        );
        let e = if P::PERSPECTIVE { t.eye(p) } else { [0; 3] };
        *w = (class::<P>(t.normal(n), e, tau) << CLASS_SHIFT) | NONE;
    }
    let mut stats = RefineStats::default();
    let mut nt = 0usize;
    for (ti, tri) in mesh.triangles().iter().enumerate() {
        let idx = tri.map(usize::from);
        let cls = idx.map(|i| words.get(i).map_or(0, |w| w >> CLASS_SHIFT));
        if cls[0] == cls[1] && cls[1] == cls[2] && cls[0] != 0 {
            continue;
        }
        // the new vertex of each edge k = (idx[k], idx[k+1]), if split
        let mut mid: [Option<u16>; 3] = [None; 3];
        for k in 0..3 {
            let (a, b) = (idx[k], idx[(k + 1) % 3]);
            if !silhouette(cls[k], cls[(k + 1) % 3]) || a == b {
                continue;
            }
            let (lo, hi) = (a.min(b), a.max(b));
            // look the edge up in lo's list
            let mut e = words.get(lo).map_or(NONE, |w| w & NONE);
            while e != NONE {
                match m.edges.get(usize::from(e)) {
                    Some(r) if usize::from(r[1]) == hi => break,
                    Some(r) => e = r[2],
                    None => e = NONE,
                }
            }
            if e == NONE {
                if stats.vertices >= budget {
                    stats.skipped += 1;
                    continue;
                }
                let Some((p, n, uv, tg)) = midpoint(mesh, lo, hi) else {
                    continue;
                };
                let k_new = stats.vertices;
                let (Some(w), Some(r)) = (words.get_mut(lo), m.edges.get_mut(k_new)) else {
                    continue;
                };
                // lo, hi < nv ≤ 65535; k_new < budget < NONE
                *r = [lo as u16, hi as u16, *w & NONE];
                *w = (*w & !NONE) | k_new as u16;
                if let Some(s) = m.positions.get_mut(k_new) {
                    *s = p;
                }
                if let Some(s) = m.normals.get_mut(k_new) {
                    *s = n;
                }
                if let Some(s) = m.texcoords.get_mut(k_new) {
                    *s = uv;
                }
                if let Some(s) = m.tangents.get_mut(k_new) {
                    *s = tg;
                }
                e = k_new as u16;
                stats.vertices += 1;
            }
            mid[k] = Some((nv + usize::from(e)) as u16);
        }
        let splits = mid.iter().filter(|m| m.is_some()).count();
        if splits == 0 {
            continue;
        }
        let v = *tri;
        let mut out = [[0u16; 3]; 4];
        let n = match splits {
            3 => {
                let (m0, m1, m2) = (
                    mid[0].unwrap_or(0),
                    mid[1].unwrap_or(0),
                    mid[2].unwrap_or(0),
                );
                out = [[v[0], m0, m2], [m0, v[1], m1], [m2, m1, v[2]], [m0, m1, m2]];
                4
            }
            1 => {
                let r = mid.iter().position(|m| m.is_some()).unwrap_or(0);
                let m0 = mid[r].unwrap_or(0);
                let (a, b, c) = (v[r], v[(r + 1) % 3], v[(r + 2) % 3]);
                out[0] = [a, m0, c];
                out[1] = [m0, b, c];
                2
            }
            _ => {
                // the whole edge j; rotate it to (v2, v0)
                let j = mid.iter().position(|m| m.is_none()).unwrap_or(0);
                let r = (j + 1) % 3;
                let (a, b, c) = (v[r], v[(r + 1) % 3], v[(r + 2) % 3]);
                let (m0, m1) = (mid[r].unwrap_or(0), mid[(r + 1) % 3].unwrap_or(0));
                out[0] = [m0, b, m1];
                out[1] = [a, m0, m1];
                out[2] = [a, m1, c];
                3
            }
        };
        // room is guaranteed on a closed mesh (4 triangles per new vertex);
        // otherwise the triangle stays whole (only possible on a mesh with
        // an edge in more than two triangles)
        let Some(dst) = m.triangles.get_mut(nt..nt + n) else {
            continue;
        };
        for (d, s) in dst.iter_mut().zip(&out) {
            // ti < triangle count ≤ 65535 (bins reject more)
            *d = [s[0], s[1], s[2], ti as u16];
        }
        nt += n;
        stats.refined += 1;
    }
    stats.triangles = nt;
    let nnew = stats.vertices;
    let positions: &'a [[i16; 3]] = m.positions;
    let normals: &'a [[i16; 3]] = m.normals;
    let texcoords: &'a [[i16; 2]] = m.texcoords;
    let tangents: &'a [[i16; 4]] = m.tangents;
    let positions = positions.get(..nnew).unwrap_or(&[]);
    let vertices = m.vertices.get_mut(..nnew).unwrap_or(&mut []);
    if let Ok(mut sub) = Mesh::new(
        positions,
        normals.get(..nnew).unwrap_or(&[]),
        &[],
        mesh.frac(),
    ) {
        if !mesh.texcoords().is_empty() {
            if let Ok(s) = sub.with_texcoords(texcoords.get(..nnew).unwrap_or(&[])) {
                sub = s;
            }
        }
        if !mesh.tangents().is_empty() {
            if let Ok(s) = sub.with_tangents(tangents.get(..nnew).unwrap_or(&[])) {
                sub = s;
            }
        }
        vertex::stage(&sub, t, kernel, vertices);
    }
    let vertices: &'a [CachedVertex<K::Vertex>] = vertices;
    let triangles: &'a [[u16; 4]] = m.triangles;
    let triangles = triangles.get(..nt).unwrap_or(&[]);
    Ok(Refined {
        vertices,
        positions,
        triangles,
        stats,
    })
}
