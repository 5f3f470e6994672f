//! The vertex stage: every vertex of a mesh transformed, projected and (for
//! flat and Gouraud shading) lit once per frame, into the caller's vertex cache.

use crate::camera::{MeshTransform, Projection};
use crate::mesh::Mesh;
use crate::raster::{WINDOW_MAX, WINDOW_MIN};
use crate::shade::{Kernel, VertexIn};

/// What the vertex stage keeps of one vertex: its screen position (sub-pixels,
/// within the set-up window, or [`CachedVertex::OUTSIDE`]), its depth and the
/// shading mode's payload `V` (the lit colour for Gouraud shading, the normal
/// for Phong shading).
///
/// Size: 6 bytes plus the payload: 12 bytes for Gouraud and Phong shading.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct CachedVertex<V> {
    pub(crate) x: i16,
    pub(crate) y: i16,
    pub(crate) z: u16,
    pub(crate) v: V,
}

impl<V> CachedVertex<V> {
    /// The `x` of a vertex outside the set-up window: its triangles take the
    /// clipping path, which recomputes the position in full precision.
    pub const OUTSIDE: i16 = i16::MIN;

    /// Whether the vertex lies inside the set-up window.
    #[inline(always)]
    pub(crate) fn inside(&self) -> bool {
        self.x != Self::OUTSIDE
    }

    /// Screen position in sub-pixels (meaningful when inside the window).
    pub fn screen(&self) -> (i32, i32) {
        (i32::from(self.x), i32::from(self.y))
    }

    /// Depth.
    pub fn depth(&self) -> u16 {
        self.z
    }

    /// The shading payload.
    pub fn payload(&self) -> &V {
        &self.v
    }
}

/// The window position as `i16`, or [`CachedVertex::OUTSIDE`].
#[inline(always)]
fn window(x: i32, y: i32) -> (i16, i16) {
    if (WINDOW_MIN..=WINDOW_MAX).contains(&x) && (WINDOW_MIN..=WINDOW_MAX).contains(&y) {
        (x as i16, y as i16)
    } else {
        (i16::MIN, 0)
    }
}

/// Runs the vertex stage of a mesh: `cache[i]` for every vertex `i` (the cache
/// holds at least `mesh.vertex_count()` entries). A vertex behind the near
/// plane or outside the set-up window is marked [`CachedVertex::OUTSIDE`].
pub(crate) fn stage<K: Kernel, P: Projection>(
    mesh: &Mesh<'_>,
    t: &MeshTransform<P>,
    kernel: &K,
    cache: &mut [CachedVertex<K::Vertex>],
) {
    let uvs = mesh.texcoords();
    let tangents = mesh.tangents();
    for (i, ((slot, p), n)) in cache
        .iter_mut()
        .zip(mesh.positions().iter())
        .zip(mesh.normals().iter())
        .enumerate()
    {
        let (x, y, z) = match t.screen(*p) {
            Some(s) => {
                let (x, y) = window(s.x, s.y);
                (x, y, s.z)
            }
            None => (CachedVertex::<K::Vertex>::OUTSIDE, 0, 0),
        };
        let mut input = VertexIn::new(
            t.normal(*n),
            if K::NEEDS_POSITION { t.eye(*p) } else { [0; 3] },
        );
        if K::NEEDS_TEXCOORD {
            input.uv = uvs.get(i).map_or([0; 2], |c| c.map(i32::from));
            input.w = if P::PERSPECTIVE {
                t.clip_coords(*p).w
            } else {
                1
            };
        }
        if K::NEEDS_TANGENT {
            if let Some(g) = tangents.get(i) {
                let d = t.normal([g[0], g[1], g[2]]);
                input.tangent = [d[0], d[1], d[2], i32::from(g[3])];
            }
        }
        *slot = CachedVertex {
            x,
            y,
            z,
            v: kernel.vertex(&input),
        };
    }
}
