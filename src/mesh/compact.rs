//! The compact mesh format the renderer reads from flash ([`Mesh`]), and
//! `const` generators that build meshes at compile time ([`MeshData`]).

use super::uv::Uv;
use crate::error::MeshError;

/// Unit normal components are stored in Q14: `16384` is 1.
pub const NORMAL_ONE: i16 = 1 << 14;

/// Fraction bits of per-vertex texture coordinates: `4096` is 1, so an `i16`
/// coordinate spans `[−8, 8)` (textures repeat up to eight times across a
/// mesh in each direction).
pub const TEXCOORD_FRAC: u32 = 12;

/// A triangle mesh in the renderer's compact format, three borrowed slices:
/// `i16` positions with `frac` fraction bits, Q14 unit normals (`16384` is 1),
/// `u16` triangles (counter-clockwise seen from the side the surface faces).
/// 6 + 6 bytes per vertex and 6 per triangle: the 24 × 16 UV sphere (362
/// vertices, 720 triangles) takes 8 664 bytes. The constructor checks that the
/// slices agree and every index is in range, so the renderer can rely on it.
///
/// ```
/// use fixshade::mesh::{Mesh, NORMAL_ONE};
/// // one triangle in the z = 0 plane facing +z, positions with 8 fraction bits
/// static POS: [[i16; 3]; 3] = [[0, 0, 0], [256, 0, 0], [0, 256, 0]];
/// static NRM: [[i16; 3]; 3] = [[0, 0, NORMAL_ONE]; 3];
/// static TRI: [[u16; 3]; 1] = [[0, 1, 2]];
/// static MESH: Mesh<'static> = Mesh::checked(&POS, &NRM, &TRI, 8);
/// assert_eq!(MESH.position(1), Some([1.0, 0.0, 0.0]));
/// assert!(Mesh::new(&POS, &NRM, &[[0, 1, 3]], 8).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mesh<'a> {
    positions: &'a [[i16; 3]],
    normals: &'a [[i16; 3]],
    triangles: &'a [[u16; 3]],
    texcoords: &'a [[i16; 2]],
    tangents: &'a [[i16; 4]],
    frac: u8,
}

impl<'a> Mesh<'a> {
    /// A mesh over the given slices; a position is `raw · 2^−frac` model units.
    ///
    /// # Errors
    ///
    /// [`MeshError::BufferTooSmall`] when there are fewer normals than
    /// positions; [`MeshError::IndexOutOfRange`] for an index beyond the
    /// positions; [`MeshError::OutOfRange`] for `frac > 15`.
    pub const fn new(
        positions: &'a [[i16; 3]],
        normals: &'a [[i16; 3]],
        triangles: &'a [[u16; 3]],
        frac: u8,
    ) -> Result<Self, MeshError> {
        if frac > 15 {
            return Err(MeshError::OutOfRange("frac"));
        }
        if let Err(e) = MeshError::check_len("normals", positions.len(), normals.len()) {
            return Err(e);
        }
        let mut t = 0;
        while t < triangles.len() {
            let mut k = 0;
            while k < 3 {
                let index = triangles[t][k];
                if index as usize >= positions.len() {
                    return Err(MeshError::IndexOutOfRange { triangle: t, index });
                }
                k += 1;
            }
            t += 1;
        }
        Ok(Mesh {
            positions,
            normals,
            triangles,
            texcoords: &[],
            tangents: &[],
            frac,
        })
    }

    /// The mesh with per-vertex texture coordinates `(u, v)` with
    /// [`TEXCOORD_FRAC`] fraction bits (`u` across the texture, `v` down it),
    /// one per vertex.
    ///
    /// # Errors
    ///
    /// [`MeshError::BufferTooSmall`] when there are fewer coordinates than
    /// positions.
    pub const fn with_texcoords(mut self, texcoords: &'a [[i16; 2]]) -> Result<Self, MeshError> {
        if let Err(e) = MeshError::check_len("texcoords", self.positions.len(), texcoords.len()) {
            return Err(e);
        }
        self.texcoords = texcoords;
        Ok(self)
    }

    /// The mesh with per-vertex tangents: a Q14 unit vector along increasing
    /// `u` in the surface, and in `[3]` the handedness (`±NORMAL_ONE`: the
    /// bitangent is `handedness · (normal × tangent)`), one per vertex.
    ///
    /// # Errors
    ///
    /// [`MeshError::BufferTooSmall`] when there are fewer tangents than
    /// positions.
    pub const fn with_tangents(mut self, tangents: &'a [[i16; 4]]) -> Result<Self, MeshError> {
        if let Err(e) = MeshError::check_len("tangents", self.positions.len(), tangents.len()) {
            return Err(e);
        }
        self.tangents = tangents;
        Ok(self)
    }

    /// The texture coordinates (empty when the mesh has none).
    pub const fn texcoords(&self) -> &'a [[i16; 2]] {
        self.texcoords
    }

    /// The tangents (empty when the mesh has none).
    pub const fn tangents(&self) -> &'a [[i16; 4]] {
        self.tangents
    }

    /// [`Mesh::new`] for `static`s and `const`s: an invalid mesh is a
    /// compile-time error there (and a panic if called at run time, so prefer
    /// [`Mesh::new`] for data read at run time).
    pub const fn checked(
        positions: &'a [[i16; 3]],
        normals: &'a [[i16; 3]],
        triangles: &'a [[u16; 3]],
        frac: u8,
    ) -> Self {
        match Self::new(positions, normals, triangles, frac) {
            Ok(m) => m,
            Err(_) => panic!("invalid mesh: index out of range, normals missing or frac > 15"),
        }
    }

    /// The raw positions.
    pub const fn positions(&self) -> &'a [[i16; 3]] {
        self.positions
    }

    /// The raw normals (Q14).
    pub const fn normals(&self) -> &'a [[i16; 3]] {
        self.normals
    }

    /// The triangles.
    pub const fn triangles(&self) -> &'a [[u16; 3]] {
        self.triangles
    }

    /// Fraction bits of the positions.
    pub const fn frac(&self) -> u8 {
        self.frac
    }

    /// Number of vertices.
    pub const fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub const fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Vertex `i`'s position in model units, as `f32` (for tests and tools).
    pub fn position(&self, i: usize) -> Option<[f32; 3]> {
        let s = 1.0 / (1u32 << self.frac) as f32;
        self.positions.get(i).map(|p| p.map(|c| c as f32 * s))
    }

    /// Vertex `i`'s normal as `f32`.
    pub fn normal(&self, i: usize) -> Option<[f32; 3]> {
        let s = 1.0 / NORMAL_ONE as f32;
        self.normals.get(i).map(|n| n.map(|c| c as f32 * s))
    }
}

/// Mesh arrays owned by value, sized by const generics: `V` vertices and `T`
/// triangles. A `static` filled by a `const fn` generator lives in flash: no
/// RAM, no floating point at run time.
///
/// ```
/// use fixshade::mesh::{uv_sphere_counts, MeshData};
/// // the standard scene's sphere, built at compile time
/// const N: (usize, usize) = uv_sphere_counts(16, 24);
/// static SPHERE: MeshData<{ N.0 }, { N.1 }> = MeshData::uv_sphere(16, 24, 14);
/// let mesh = SPHERE.mesh();
/// assert_eq!((mesh.vertex_count(), mesh.triangle_count()), (362, 720));
/// assert_eq!(mesh.position(0), Some([0.0, 1.0, 0.0])); // the north pole
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshData<const V: usize, const T: usize> {
    /// Positions (`raw · 2^−frac`).
    pub positions: [[i16; 3]; V],
    /// Unit normals in Q14.
    pub normals: [[i16; 3]; V],
    /// Triangles.
    pub triangles: [[u16; 3]; T],
    /// Fraction bits of the positions.
    pub frac: u8,
}

impl<const V: usize, const T: usize> MeshData<V, T> {
    /// The mesh view of these arrays, checked by [`Mesh::checked`]: in a
    /// `static` or `const` (`static M: Mesh = DATA.mesh();`) at compile time,
    /// leaving no code; at run time it checks every index again and panics if
    /// the public fields were made invalid, so panic-free firmware keeps the
    /// view in a `static` (as `measure/frame` does) or uses [`Mesh::new`].
    pub const fn mesh(&self) -> Mesh<'_> {
        Mesh::checked(&self.positions, &self.normals, &self.triangles, self.frac)
    }

    /// The UV sphere of radius 1 around the origin with `stacks` bands of
    /// latitude and `slices` of longitude, positions with `frac` fraction bits
    /// (14 for a unit sphere: coordinates up to ±2): vertex 0 the north pole
    /// `(0, 1, 0)`, then `stacks − 1` rings of `slices` vertices from the north
    /// (ring `i` at `θ = π·i/stacks`, column `j` at `φ = 2π·j/slices`: the
    /// point `(sin θ sin φ, cos θ, sin θ cos φ)`), the south pole last;
    /// counter-clockwise seen from outside.
    ///
    /// `V` and `T` must equal [`uv_sphere_counts`](super::uv_sphere_counts)
    /// (a compile-time error in a `static`), and `frac` at most 14.
    pub const fn uv_sphere(stacks: usize, slices: usize, frac: u8) -> Self {
        let counts = super::uv_sphere_counts(stacks, slices);
        assert!(
            counts.0 == V && counts.1 == T,
            "V, T must equal uv_sphere_counts"
        );
        assert!(frac <= 14, "positions of a unit sphere need frac <= 14");
        let mut m = MeshData {
            positions: [[0; 3]; V],
            normals: [[0; 3]; V],
            triangles: [[0; 3]; T],
            frac,
        };
        let scale = (1u32 << frac) as f64;
        let uv = Uv::new(stacks, slices, false);
        let mut k = 0;
        while k < V {
            m.put(k, uv.point(k, V), scale);
            k += 1;
        }
        uv.triangles(&mut m.triangles, V);
        m
    }

    /// Stores vertex `k` with unit normal `n` at position `n` (radius 1).
    const fn put(&mut self, k: usize, n: [f64; 3], scale: f64) {
        let mut c = 0;
        while c < 3 {
            self.positions[k][c] = round_i16(n[c] * scale);
            self.normals[k][c] = round_i16(n[c] * NORMAL_ONE as f64);
            c += 1;
        }
    }
}

/// `round(x)` saturated to `i16` (ties away from zero), usable in `const fn`.
pub(crate) const fn round_i16(x: f64) -> i16 {
    let r = if x >= 0.0 { x + 0.5 } else { x - 0.5 };
    let r = r as i64; // truncation after the half offset rounds; `as` saturates
    if r > i16::MAX as i64 {
        i16::MAX
    } else if r < i16::MIN as i64 {
        i16::MIN
    } else {
        r as i16
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_saturates() {
        assert_eq!(round_i16(2.5), 3);
        assert_eq!(round_i16(-2.5), -3);
        assert_eq!(round_i16(1e9), i16::MAX);
        assert_eq!(round_i16(-1e9), i16::MIN);
        assert_eq!(round_i16(f64::NAN), 0);
    }
}
