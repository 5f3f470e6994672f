//! The vertex stage: every vertex of a mesh transformed, projected and (for
//! flat and Gouraud shading) lit once per frame, into the caller's vertex cache.

use crate::camera::{Clip, ClipSpace, MeshTransform, Projection};
use crate::mesh::Mesh;
use crate::num::Zeroed;
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

impl<V: Zeroed> CachedVertex<V> {
    /// An empty cache entry (every vertex is written by the vertex stage
    /// before it is read).
    pub const ZERO: Self = CachedVertex {
        x: 0,
        y: 0,
        z: 0,
        v: V::ZERO,
    };
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

/// The window position and depth of clip coordinates `c`, or `None` behind
/// the near plane or outside the window (`PERSP`: a perspective clip space).
#[inline(always)]
pub(crate) fn window<const PERSP: bool>(space: &ClipSpace, c: Clip) -> Option<(i16, i16, u16)> {
    let s = space.project_as::<PERSP>(c)?;
    let inside = |v: i32| (WINDOW_MIN..=WINDOW_MAX).contains(&v);
    (inside(s.x) && inside(s.y)).then_some((s.x as i16, s.y as i16, s.z))
}

/// Runs the vertex stage of a mesh's vertices from `first` on: `cache[i]`
/// for vertex `first + i`, as many as `cache` holds (up to the last vertex).
/// A vertex behind the near plane or outside the set-up window is marked
/// [`CachedVertex::OUTSIDE`].
pub(crate) fn stage<K: Kernel, P: Projection>(
    mesh: &Mesh<'_>,
    t: &MeshTransform<P>,
    kernel: &K,
    first: usize,
    cache: &mut [CachedVertex<K::Vertex>],
) {
    let space = t.clip_space();
    let uvs = mesh.texcoords();
    let tangents = mesh.tangents();
    let positions = mesh.positions().get(first..).unwrap_or(&[]);
    let normals = mesh.normals().get(first..).unwrap_or(&[]);
    for (i, ((slot, p), n)) in cache
        .iter_mut()
        .zip(positions.iter())
        .zip(normals.iter())
        .enumerate()
    {
        let i = first + i;
        let c = t.clip(*p);
        let s = if P::PERSPECTIVE {
            window::<true>(&space, c)
        } else {
            window::<false>(&space, c)
        };
        let (x, y, z) = s.unwrap_or((CachedVertex::<K::Vertex>::OUTSIDE, 0, 0));
        let mut input = VertexIn::new(
            t.normal(*n),
            if K::NEEDS_POSITION { t.eye(*p) } else { [0; 3] },
        );
        if K::NEEDS_TEXCOORD {
            input.uv = uvs.get(i).map_or([0; 2], |c| c.map(i32::from));
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
