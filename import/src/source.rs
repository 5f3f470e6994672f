//! What a reader hands to the processing stage: a triangle soup in the file's
//! own units, with whatever per-corner attributes the file has.

use std::path::PathBuf;

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

/// A model as read from a file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SourceMesh {
    /// The triangles (polygons already split into fans).
    pub triangles: Vec<SourceTriangle>,
    /// The distinct diffuse textures the faces' materials name, in order of
    /// first use.
    pub textures: Vec<TextureSource>,
    /// Polygons (faces of more than three corners) split into triangles.
    pub polygons_split: usize,
    /// Files read (the model, its material libraries, buffers), for a build
    /// script's `rerun-if-changed`.
    pub files: Vec<PathBuf>,
    /// Things the reader skipped or assumed, for the user.
    pub warnings: Vec<String>,
}
