//! What a reader hands to the processing stage: a triangle soup in the file's
//! own units, with whatever per-corner attributes the file has.

use std::path::PathBuf;

use crate::error::FileKind;

/// One corner of a [`SourceTriangle`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// Position in the file's units (after the node transforms of a glTF scene).
    pub position: [f64; 3],
    /// The file's normal, if it gives one (not necessarily unit length).
    pub normal: Option<[f64; 3]>,
    /// The texture coordinate in fixshade's convention: `u` across, `v`
    /// **down** the image (an OBJ's `v` is flipped: `1 − v`; glTF's is
    /// already down).
    pub texcoord: Option<[f64; 2]>,
}

/// How the faces of a file ask to be smoothed where the file gives no normals.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Smoothing {
    /// The file says nothing: a crease angle decides.
    Unspecified,
    /// OBJ `s off` / `s 0`: the face is flat.
    Off,
    /// OBJ `s N`: the face shares its vertex normals with the faces of group
    /// `N` that touch it.
    Group(u32),
}

/// A triangle of the source, counter-clockwise seen from the side it faces
/// (as the file gives it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SourceTriangle {
    /// The three corners.
    pub corners: [Corner; 3],
    /// The smoothing of the face the triangle came from.
    pub smoothing: Smoothing,
    /// Its material: an index into [`SourceMesh::materials`]; `None` for
    /// none (OBJ faces before any `usemtl` or naming a material no library
    /// defines, glTF primitives without one): OpenGL's default material.
    pub material: Option<usize>,
}

/// Where a texture's PNG bytes are.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TextureSource {
    /// A file (resolved against the file that named it).
    File(PathBuf),
    /// Bytes embedded in the model (a `.glb` buffer view or a `data:` URI),
    /// with a name for messages.
    Embedded {
        /// A name for messages and the generated comment.
        name: String,
        /// The encoded image.
        bytes: Vec<u8>,
        /// Its MIME type as the file states it.
        mime_type: String,
    },
}

/// A material's values as the file states them (validated and converted to
/// a `fixshade::lighting::MaterialDesc` by [`crate::material`]).
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialValues {
    /// A Wavefront MTL material: the statements present (`None` for absent).
    Mtl {
        /// `Ka`.
        ambient: Option<[f64; 3]>,
        /// `Kd`.
        diffuse: Option<[f64; 3]>,
        /// `Ks`.
        specular: Option<[f64; 3]>,
        /// `Ke`.
        emission: Option<[f64; 3]>,
        /// `Ns`.
        shininess: Option<f64>,
        /// `d` (opacity, "dissolve").
        dissolve: Option<f64>,
        /// `Tr` (transparency, `1 − d`), used when there is no `d`.
        transparency: Option<f64>,
    },
    /// A glTF 2.0 metallic-roughness material (the specification's defaults
    /// for absent values).
    Gltf {
        /// `pbrMetallicRoughness.baseColorFactor` (linear RGBA).
        base_colour: [f64; 4],
        /// `metallicFactor`.
        metallic: f64,
        /// `roughnessFactor`.
        roughness: f64,
        /// `emissiveFactor`.
        emissive: [f64; 3],
        /// `alphaMode` is `OPAQUE` (the base colour's alpha is ignored).
        opaque: bool,
    },
}

/// A material the faces of a [`SourceMesh`] use.
#[derive(Clone, Debug, PartialEq)]
pub struct SourceMaterial {
    /// Its name (`newmtl`, the glTF material's name or `material N`).
    pub name: String,
    /// Its values.
    pub values: MaterialValues,
    /// Its diffuse texture (`map_Kd`, the base colour texture), if any.
    pub texture: Option<TextureSource>,
}

/// A file the model refers to that does not exist: a warning and a default
/// (or an error with `--strict`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MissingFile {
    /// What it is.
    pub kind: FileKind,
    /// The path tried (resolved against the referring file).
    pub path: PathBuf,
    /// What is used instead (for the warning).
    pub instead: String,
}

/// A model as read from a file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SourceMesh {
    /// The triangles (polygons already split into fans).
    pub triangles: Vec<SourceTriangle>,
    /// The materials the triangles name (`SourceTriangle::material`).
    pub materials: Vec<SourceMaterial>,
    /// Polygons (faces of more than three corners) split into triangles.
    pub polygons_split: usize,
    /// Files read (the model, its material libraries, buffers), for a build
    /// script's `rerun-if-changed`.
    pub files: Vec<PathBuf>,
    /// Referenced files that do not exist (a material library); the reader
    /// went on without them.
    pub missing: Vec<MissingFile>,
    /// Things the reader skipped or assumed, for the user.
    pub warnings: Vec<String>,
}
