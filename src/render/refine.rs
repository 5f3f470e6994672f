//! Silhouette refinement: the triangles along a mesh's outline subdivided
//! every frame with curved (PN triangle) positions and normals, so that a
//! coarse mesh shows a round outline.
//!
//! # What is split
//!
//! The decision is made per **edge**, from its two vertices only, so both
//! triangles sharing an edge split it identically and no crack opens:
//!
//! 1. every mesh vertex is classified by `N·V`, its eye-space normal against
//!    the direction to the viewer (`(0, 0, 1)` orthographic, towards the eye in
//!    perspective): *front* when `N·V > τ`, *back* when `N·V < −τ`, *near*
//!    otherwise (`τ` = [`Refine::threshold`], Q14; `τ = 0` is the sign test);
//! 2. a *silhouette edge* goes from front to back or from near to near; a
//!    near-to-front or near-to-back edge is not split (else a vertex exactly on
//!    the silhouette would split every edge around it);
//! 3. silhouette edges are split at their midpoint, in the order the triangles
//!    meet them, while the budget lasts, per **geometric edge**: an edge is
//!    keyed by its endpoint *positions*, so the copies of one edge (the two
//!    sides of a texture seam) decide together, each copy getting its own new
//!    vertex (texture coordinates, tangent) at the same position. When the
//!    budget runs out, a copy that finds no room marks its geometric edge dead
//!    and no copy of it is split. So every edge is split for all its triangles
//!    or none: crack-free within any budget; edges beyond it stay whole (drawn
//!    as without refinement).
//!
//! A triangle with 1, 2 or 3 split edges becomes 2, 3 or 4 triangles (one
//! level), each culled, binned and drawn like a mesh triangle.
//!
//! # The new vertex
//!
//! The midpoint of the cubic Bézier edge of the PN triangle (Vlachos et al.,
//! 2001) over the edge `(P_i, N_i)`–`(P_j, N_j)`:
//! `M = (P_i + P_j)/2 − (w_ij·N_i + w_ji·N_j)/8`, `w_ij = (P_j − P_i)·N_i`;
//! its normal the midpoint of the quadratic normal edge,
//! `normalize(N_i + N_j + 2·n_ij)`, `n_ij = normalize(N_i + N_j − v_ij·(P_j − P_i))`,
//! `v_ij = 2·(P_j − P_i)·(N_i + N_j) / |P_j − P_i|²`. In integers on the mesh's
//! raw `i16` positions and Q14 normals (model space), symmetric in `i` and `j`
//! (the same bits from either triangle or seam copy). Texture coordinates and
//! tangents are averaged (tangents normalised); the vertex then goes through the
//! vertex stage ([`Kernel::vertex`]) into the refinement's own cache slots.
//!
//! The new vertices land within `10⁻⁴` of a unit sphere for the 15° edges of
//! the 24 × 16 UV sphere (the chord midpoint is `0.0086` inside). On the
//! standard sphere at 960 px the outline's largest radial error drops from 2.50
//! to 1.19 px (1.00 to 0.75 px at 240 px); see `docs/tradeoff.md`.
//!
//! # Limits
//!
//! - One level: where the outline crosses the middle of a triangle it follows
//!   the straight cut between two new vertices.
//! - The budget is `min(E, T/4)` new vertices (`E` vertex slots, `T` triangle
//!   slots): room for every replacing triangle when each edge belongs to at most
//!   two triangles; otherwise a triangle whose pieces do not fit is drawn whole
//!   (a crack is then possible there).
//! - Replacing triangles are drawn after the mesh's own in each band (the
//!   order matters only without a depth buffer).
//! - Vertices sharing a position should share their normal: a crease whose
//!   copies fall in different classes can be split on one side only (a
//!   T-junction).

use super::vertex::{self, CachedVertex};
use super::RenderError;
use crate::camera::{MeshTransform, Projection};
use crate::mesh::Mesh;
use crate::num::{at3, Zeroed};
use crate::shade::Kernel;

/// No edge in a vertex's list (14 bits).
const NONE: u16 = 0x3FFF;
/// The class bits of a vertex word.
const CLASS_SHIFT: u32 = 14;
const FRONT: u16 = 1;
const BACK: u16 = 2;

/// The most new vertices one frame can add (14-bit edge lists).
pub(crate) const MAX_NEW_VERTICES: usize = NONE as usize;

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
    /// One word per mesh vertex: its class and the head of one list of split
    /// edges (the edges whose lower endpoint position hashes to this index).
    pub vertex_words: &'a mut [u16],
    /// The split edges `[i, j, next]` (`i` the endpoint with the lower
    /// position), one per new vertex.
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

/// Silhouette refinement for [`DrawOptions::with_refine`](super::DrawOptions::with_refine):
/// its memory and the threshold `τ` (Q14, `0..=16384`; see the [module](self)
/// docs): a larger `τ` also splits edges next to the silhouette (rounder for
/// coarse meshes, more triangles).
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
/// use fixshade::render::refine::RefineBuffers;
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

impl<V: Zeroed, const NV: usize, const E: usize, const T: usize> RefineBuffers<V, NV, E, T> {
    /// Zeroed buffers (a `const fn`: see [`MeshBuffers`](super::MeshBuffers)
    /// for buffers in a `static`).
    pub const fn new() -> Self {
        RefineBuffers {
            words: [0; NV],
            edges: [[0; 3]; E],
            positions: [[0; 3]; E],
            normals: [[0; 3]; E],
            texcoords: [[0; 2]; E],
            tangents: [[0; 4]; E],
            vertices: [CachedVertex::ZERO; E],
            triangles: [[0; 4]; T],
        }
    }
}

impl<V, const NV: usize, const E: usize, const T: usize> RefineBuffers<V, NV, E, T> {
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

impl<V: Zeroed, const NV: usize, const E: usize, const T: usize> Default
    for RefineBuffers<V, NV, E, T>
{
    fn default() -> Self {
        Self::new()
    }
}

/// What one frame's refinement produced.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct RefineStats {
    /// New vertices made: the split edge copies, and those of a geometric
    /// edge abandoned because another copy of it found the budget spent.
    pub vertices: usize,
    /// Mesh triangles replaced.
    pub refined: usize,
    /// Triangles replacing them.
    pub triangles: usize,
    /// Silhouette edges (counted per triangle side) left whole because the
    /// budget ran out.
    pub skipped: usize,
}

/// The refinement's results, borrowed by the `MeshDraw`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Refined<'a, V> {
    /// The mesh vertices' words (classes in the top bits).
    pub words: &'a [u16],
    pub vertices: &'a [CachedVertex<V>],
    pub positions: &'a [[i16; 3]],
    pub triangles: &'a [[u16; 4]],
    pub stats: RefineStats,
}

impl<V> Refined<'_, V> {
    /// Whether mesh triangle `tri` (with vertices `idx`) is replaced: only
    /// if it has a silhouette edge, then by a binary search over the parents
    /// (which increase).
    #[inline]
    pub(crate) fn replaced(&self, t: usize, idx: [u16; 3]) -> bool {
        if self.triangles.is_empty() {
            return false;
        }
        let c = idx.map(|i| {
            self.words
                .get(usize::from(i))
                .map_or(0, |w| w >> CLASS_SHIFT)
        });
        if !(silhouette(c[0], c[1]) || silhouette(c[1], c[2]) || silhouette(c[2], c[0])) {
            return false;
        }
        self.triangles
            .binary_search_by(|r| usize::from(r[3]).cmp(&t))
            .is_ok()
    }
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
/// edge: its normals cross the band `|N·V| ≤ τ` (front to back) or stay in
/// it (near to near).
#[inline]
fn silhouette(a: u16, b: u16) -> bool {
    a | b == FRONT | BACK || (a == 0 && b == 0)
}

/// `v / |v|` in Q14, rounded, or `None` when `v` vanishes.
fn unit_q14(v: [i32; 3]) -> Option<[i16; 3]> {
    // scale so that the largest component has 15 bits: squares sum below
    // 3·2^30, and |v| ≥ 2^14 keeps the square root precise
    let m = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
    if m == 0 {
        return None;
    }
    let bits = 32 - m.leading_zeros();
    let w = if bits > 15 {
        v.map(|c| c >> (bits - 15))
    } else {
        // |c| < 2^bits: the shifted value stays below 2^15
        v.map(|c| c << (15 - bits))
    };
    let len2: u32 = w.iter().map(|&c| c.unsigned_abs() * c.unsigned_abs()).sum();
    let len = len2.isqrt();
    if len == 0 {
        return None;
    }
    let len = len as i32;
    // |c| ≤ len < 2^16: c · 2^14 < 2^30, the rounded quotient ≤ 2^14
    Some(w.map(|c| {
        let q = ((c << 14) + if c < 0 { -(len >> 1) } else { len >> 1 }) / len;
        q.clamp(-16384, 16384) as i16
    }))
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
    // h = s − v·d with 8 more fraction bits (its direction matters, and it is
    // short where the normals nearly oppose each other)
    let mut h = s.map(|c| c << 8);
    if dd > 0 {
        // f = 2 (d·s) / |d|² with 28 more fraction bits: |2 d·s| < 2^34, so
        // the shift stays below 2^62; |f·d_c| ≤ 2^29·|s|·|d_c|/|d| < 2^46
        let f = ((2 * dot(d, s)) << 28) / dd;
        for c in 0..3 {
            h[c] -= (f * d[c]) >> 20;
        }
    }
    // |h| ≤ 3|s| < 2^17, with 8 more bits below 2^25
    let h = h.map(|c| c.clamp(-(1 << 28), 1 << 28) as i32);
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

/// The flag of a split-edge record (in its `next` word) whose geometric edge
/// is not split after all: another copy of it found the budget spent.
const DEAD: u16 = 0x4000;

/// The bucket (`0..n`) of the edges whose lower endpoint is at position `p`:
/// a multiplicative hash, scaled without a division (`n < 2^16`).
#[inline]
fn bucket(p: [i16; 3], n: usize) -> usize {
    let c = p.map(|v| u32::from(v as u16));
    let h = c[0]
        .wrapping_mul(0x9E37_79B1)
        .wrapping_add(c[1].wrapping_mul(0x85EB_CA77))
        .wrapping_add(c[2].wrapping_mul(0xC2B2_AE3D));
    let h = h ^ (h >> 15);
    // (h ≫ 16) < 2^16 and n < 2^16: the product fits
    (((h >> 16) * (n.min(0xFFFF) as u32)) >> 16) as usize
}

/// A mesh edge as the refinement keys it: its endpoints ordered by position
/// (so every copy of a geometric edge, e.g. the two sides of a texture seam,
/// orders them alike), with the lower position. `None` for an edge whose
/// endpoints share a position (nothing to split).
#[inline]
fn edge_key(mesh: &Mesh<'_>, a: usize, b: usize) -> Option<(usize, usize, [i16; 3], [i16; 3])> {
    let (pa, pb) = (*mesh.positions().get(a)?, *mesh.positions().get(b)?);
    match pa.cmp(&pb) {
        core::cmp::Ordering::Less => Some((a, b, pa, pb)),
        core::cmp::Ordering::Greater => Some((b, a, pb, pa)),
        core::cmp::Ordering::Equal => None,
    }
}

/// What the bucket list holds of edge `lo`–`hi` (positions `plo`, `phi`):
/// the record of this copy, and a record of another copy of the same
/// geometric edge (same endpoint positions).
fn find(
    mesh: &Mesh<'_>,
    head: u16,
    edges: &[[u16; 3]],
    (lo, hi, plo, phi): (usize, usize, [i16; 3], [i16; 3]),
) -> (Option<usize>, Option<usize>) {
    let (mut copy, mut twin) = (None, None);
    let mut e = head & NONE;
    while e != NONE {
        let Some(r) = edges.get(usize::from(e)) else {
            break;
        };
        let (i, j) = (usize::from(r[0]), usize::from(r[1]));
        if i == lo && j == hi {
            copy = Some(usize::from(e));
        } else if twin.is_none()
            && mesh.positions().get(i) == Some(&plo)
            && mesh.positions().get(j) == Some(&phi)
        {
            twin = Some(usize::from(e));
        }
        e = r[2] & NONE;
    }
    (copy, twin)
}

/// Runs one frame's refinement (see the module docs): classifies the vertices,
/// splits silhouette edges within the budget, runs the vertex stage on the new
/// vertices and writes the replacing triangles.
pub(crate) fn build<'a, K: Kernel, P: Projection>(
    mesh: &Mesh<'_>,
    t: &MeshTransform<P>,
    kernel: &K,
    refine: Refine<'a, K::Vertex>,
) -> Result<Refined<'a, K::Vertex>, RenderError> {
    let tau = u32::from(refine.threshold.min(16384));
    let m = refine.memory;
    let nv = mesh.vertex_count();
    RenderError::check_len("refine vertex words", nv, m.vertex_words.len())?;
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
    // one word per mesh vertex: its class (top bits) and the head of bucket
    // i's list of split edges (low bits)
    let words = m.vertex_words.get_mut(..nv).unwrap_or(&mut []);
    for (i, w) in words.iter_mut().enumerate() {
        let (p, n) = (
            mesh.positions().get(i).copied().unwrap_or([0; 3]),
            mesh.normals().get(i).copied().unwrap_or([0; 3]),
        );
        let e = if P::PERSPECTIVE { t.eye(p) } else { [0; 3] };
        *w = (class::<P>(t.normal(n), e, tau) << CLASS_SHIFT) | NONE;
    }
    let class_of = |words: &[u16], i: usize| words.get(i).map_or(0, |w| w >> CLASS_SHIFT);
    let mut stats = RefineStats::default();
    // pass 1: which edges are split (see the module docs, step 3)
    let mut used = 0usize;
    for tri in mesh.triangles() {
        let idx = tri.map(usize::from);
        let cls = idx.map(|i| class_of(words, i));
        for k in 0..3 {
            if !silhouette(at3(&cls, k), at3(&cls, (k + 1) % 3)) {
                continue;
            }
            let Some(key) = edge_key(mesh, at3(&idx, k), at3(&idx, (k + 1) % 3)) else {
                continue;
            };
            let b = bucket(key.2, nv);
            let head = words.get(b).map_or(NONE, |w| w & NONE);
            let (copy, twin) = find(mesh, head, m.edges.get(..used).unwrap_or(&[]), key);
            if copy.is_some() {
                continue;
            }
            let twin_dead = twin
                .and_then(|e| m.edges.get(e))
                .is_some_and(|r| r[2] & DEAD != 0);
            if twin_dead {
                continue;
            }
            if used >= budget {
                // no room for this copy: its geometric edge stays whole
                let mut e = head;
                while e & NONE != NONE {
                    let Some(r) = m.edges.get_mut(usize::from(e & NONE)) else {
                        break;
                    };
                    let (i, j) = (usize::from(r[0]), usize::from(r[1]));
                    if mesh.positions().get(i) == Some(&key.2)
                        && mesh.positions().get(j) == Some(&key.3)
                    {
                        r[2] |= DEAD;
                    }
                    e = r[2];
                }
                continue;
            }
            let (lo, hi) = (key.0, key.1);
            let Some((mut p, n, uv, tg)) = midpoint(mesh, lo, hi) else {
                continue;
            };
            if let Some(tp) = twin.and_then(|e| m.positions.get(e)) {
                p = *tp;
            }
            let (Some(w), Some(r)) = (words.get_mut(b), m.edges.get_mut(used)) else {
                continue;
            };
            // lo, hi < nv ≤ 65535; used < budget < NONE
            *r = [lo as u16, hi as u16, *w & NONE];
            *w = (*w & !NONE) | used as u16;
            if let Some(s) = m.positions.get_mut(used) {
                *s = p;
            }
            if let Some(s) = m.normals.get_mut(used) {
                *s = n;
            }
            if let Some(s) = m.texcoords.get_mut(used) {
                *s = uv;
            }
            if let Some(s) = m.tangents.get_mut(used) {
                *s = tg;
            }
            used += 1;
        }
    }
    stats.vertices = used;
    // pass 2: the replacing triangles, from the live split edges
    let mut nt = 0usize;
    for (ti, tri) in mesh.triangles().iter().enumerate() {
        let idx = tri.map(usize::from);
        let cls = idx.map(|i| class_of(words, i));
        // the new vertex of each edge k = (idx[k], idx[k+1]), if split
        let mut mid: [Option<u16>; 3] = [None; 3];
        for k in 0..3 {
            if !silhouette(at3(&cls, k), at3(&cls, (k + 1) % 3)) {
                continue;
            }
            let Some(key) = edge_key(mesh, at3(&idx, k), at3(&idx, (k + 1) % 3)) else {
                continue;
            };
            let head = words.get(bucket(key.2, nv)).map_or(NONE, |w| w & NONE);
            match find(mesh, head, m.edges.get(..used).unwrap_or(&[]), key).0 {
                Some(e) if m.edges.get(e).is_some_and(|r| r[2] & DEAD == 0) => {
                    // e < used < NONE, nv + e ≤ 65535
                    if let Some(m) = mid.get_mut(k) {
                        *m = Some((nv + e) as u16);
                    }
                }
                _ => stats.skipped += 1,
            }
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
                let m0 = at3(&mid, r).unwrap_or(0);
                let (a, b, c) = (at3(&v, r), at3(&v, (r + 1) % 3), at3(&v, (r + 2) % 3));
                out[0] = [a, m0, c];
                out[1] = [m0, b, c];
                2
            }
            _ => {
                // the whole edge j; rotate it to (v2, v0)
                let j = mid.iter().position(|m| m.is_none()).unwrap_or(0);
                let r = (j + 1) % 3;
                let (a, b, c) = (at3(&v, r), at3(&v, (r + 1) % 3), at3(&v, (r + 2) % 3));
                let (m0, m1) = (
                    at3(&mid, r).unwrap_or(0),
                    at3(&mid, (r + 1) % 3).unwrap_or(0),
                );
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
    let nnew = used;
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
        vertex::stage(&sub, t, kernel, 0, vertices);
    }
    let vertices: &'a [CachedVertex<K::Vertex>] = vertices;
    let words: &'a [u16] = words;
    let triangles: &'a [[u16; 4]] = m.triangles;
    let triangles = triangles.get(..nt).unwrap_or(&[]);
    Ok(Refined {
        words,
        vertices,
        positions,
        triangles,
        stats,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn lcg(s: &mut u64) -> f64 {
        *s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*s >> 11) as f64 / (1u64 << 53) as f64
    }

    fn unit(v: [f64; 3]) -> [f64; 3] {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    }

    /// The PN midpoint and quadratic midpoint normal in f64 from the
    /// quantised inputs (positions in raw units, normals as Q14 / 16384).
    fn reference(p: [[f64; 3]; 2], n: [[f64; 3]; 2]) -> ([f64; 3], [f64; 3]) {
        let d: [f64; 3] = core::array::from_fn(|c| p[1][c] - p[0][c]);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let (wij, wji) = (dot(d, n[0]), -dot(d, n[1]));
        let m = core::array::from_fn(|c| {
            (p[0][c] + p[1][c]) / 2.0 - (wij * n[0][c] + wji * n[1][c]) / 8.0
        });
        let s: [f64; 3] = core::array::from_fn(|c| n[0][c] + n[1][c]);
        let v = 2.0 * dot(d, s) / dot(d, d);
        let h = unit(core::array::from_fn(|c| s[c] - v * d[c]));
        let nm = unit(core::array::from_fn(|c| n[0][c] + n[1][c] + 2.0 * h[c]));
        (m, nm)
    }

    fn two(p: [[i16; 3]; 2], n: [[i16; 3]; 2]) -> ([[i16; 3]; 2], [[i16; 3]; 2]) {
        (p, n)
    }

    #[test]
    fn midpoint_matches_the_f64_pn_formula_and_is_symmetric() {
        let mut s = 99u64;
        let mut worst = (0.0f64, 0.0f64);
        for k in 0..20000 {
            // edges from tiny to a quarter of the i16 range; normals from
            // aligned to grazing (nearly along the edge) and opposed
            let len = [8.0, 300.0, 4000.0, 8000.0][k % 4];
            let a: [f64; 3] = core::array::from_fn(|_| (lcg(&mut s) - 0.5) * 16000.0);
            let dir = unit(core::array::from_fn(|_| lcg(&mut s) - 0.5));
            let b: [f64; 3] = core::array::from_fn(|c| a[c] + dir[c] * len);
            let perp = unit([dir[1] - dir[2], dir[2] - dir[0], dir[0] - dir[1]]);
            let tilt = [0.0, 0.3, 0.9, 1.4, 1.55][k % 5];
            let ni = unit(core::array::from_fn(|c| {
                perp[c] * libm::cos(tilt) - dir[c] * libm::sin(tilt)
            }));
            let nj = unit(core::array::from_fn(|c| {
                perp[c] * libm::cos(tilt) + dir[c] * libm::sin(tilt) + (lcg(&mut s) - 0.5) * 0.4
            }));
            let q = |v: [f64; 3], k: f64| v.map(|c| libm::round(c * k) as i16);
            let (p, n) = two([q(a, 1.0), q(b, 1.0)], [q(ni, 16384.0), q(nj, 16384.0)]);
            let uv = [[0i16; 2]; 2];
            let tris: [[u16; 3]; 0] = [];
            let mesh = Mesh::new(&p, &n, &tris, 0)
                .unwrap()
                .with_texcoords(&uv)
                .unwrap();
            let (mp, mn, _, _) = midpoint(&mesh, 0, 1).unwrap();
            assert_eq!(
                midpoint(&mesh, 1, 0).unwrap(),
                midpoint(&mesh, 0, 1).unwrap(),
                "not symmetric"
            );
            let (rp, rn) = reference(
                [p[0].map(f64::from), p[1].map(f64::from)],
                [
                    n[0].map(|c| f64::from(c) / 16384.0),
                    n[1].map(|c| f64::from(c) / 16384.0),
                ],
            );
            for c in 0..3 {
                let e = (f64::from(mp[c]) - rp[c]).abs();
                worst.0 = worst.0.max(e);
                assert!(e <= 0.5 + 1e-6, "{k}: position {mp:?} vs {rp:?}");
                let e = (f64::from(mn[c]) / 16384.0 - rn[c]).abs();
                worst.1 = worst.1.max(e);
                assert!(e < 2.5e-4, "{k}: normal {mn:?} vs {rn:?} p {p:?} n {n:?}");
            }
        }
        std::println!("worst: position {:.3} raw, normal {:.2e}", worst.0, worst.1);
    }

    #[test]
    fn sphere_midpoints_land_on_the_sphere() {
        for deg in [5.0f64, 11.25, 15.0, 30.0, 60.0] {
            let t = deg.to_radians();
            let pi = [0.0, 0.0, 1.0];
            let pj = [libm::sin(t), 0.0, libm::cos(t)];
            let q = |v: [f64; 3]| v.map(|c| libm::round(c * 16384.0) as i16);
            let (p, n) = two([q(pi), q(pj)], [q(pi), q(pj)]);
            let tris: [[u16; 3]; 0] = [];
            let mesh = Mesh::new(&p, &n, &tris, 14).unwrap();
            let (mp, mn, _, _) = midpoint(&mesh, 0, 1).unwrap();
            let r = mp.map(|c| f64::from(c) / 16384.0);
            let r = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
            let want = libm::cos(t / 2.0) * (1.0 + (1.0 - libm::cos(t)) / 4.0);
            assert!((r - want).abs() < 1e-4, "{deg}: {r} vs {want}");
            assert!(
                (1.0 - r) < 0.2 * (1.0 - libm::cos(t / 2.0)),
                "{deg}: not rounder than the chord"
            );
            // the normal is the sphere's at the new point
            let dir = mp.map(f64::from).map(|c| c / (r * 16384.0));
            for c in 0..3 {
                // the quadratic term amplifies the Q14 rounding of the
                // positions by about |N_i + N_j| / |P_j − P_i| (23 at 5°)
                assert!(
                    (f64::from(mn[c]) / 16384.0 - dir[c]).abs() < 1e-3,
                    "{deg}: {mn:?} {dir:?} {mp:?}"
                );
            }
        }
    }

    #[test]
    fn classes_and_the_edge_rule() {
        use crate::camera::{Orthographic, Perspective};
        // orthographic: the sign of n.z, with τ a band around 0
        assert_eq!(class::<Orthographic>([0, 0, 5], [0; 3], 0), FRONT);
        assert_eq!(class::<Orthographic>([0, 0, -5], [0; 3], 0), BACK);
        assert_eq!(class::<Orthographic>([16384, 0, 0], [0; 3], 0), 0);
        // n·V = 0.2 against τ = 0.25 and 0.15 (unnormalised n: length 2)
        let n = [
            0,
            (2.0 * 16384.0 * 0.979_795_9f64) as i32,
            (2.0 * 16384.0 * 0.2f64) as i32,
        ];
        assert_eq!(class::<Orthographic>(n, [0; 3], 4096), 0);
        assert_eq!(class::<Orthographic>(n, [0; 3], 2458), FRONT);
        // perspective: towards the eye at the origin from e
        let e = [0, 0, -5 << 16];
        assert_eq!(class::<Perspective>([0, 0, 16384], e, 0), FRONT);
        assert_eq!(class::<Perspective>([0, 0, -16384], e, 4000), BACK);
        assert_eq!(
            class::<Perspective>([16384, 0, 0], [1 << 16, 0, -5 << 16], 0),
            BACK
        );
        assert_eq!(
            class::<Perspective>([16384, 0, 0], [1 << 16, 0, -5 << 16], 8192),
            0
        );
        let rule: Vec<bool> = [
            (FRONT, FRONT),
            (BACK, BACK),
            (FRONT, BACK),
            (BACK, FRONT),
            (0, FRONT),
            (BACK, 0),
            (0, 0),
        ]
        .iter()
        .map(|&(a, b)| silhouette(a, b))
        .collect();
        assert_eq!(rule, [false, false, true, true, false, false, true]);
    }
}
