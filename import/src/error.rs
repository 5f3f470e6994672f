//! The importer's one error type.

use std::fmt;
use std::path::PathBuf;

use fixshade::error::MeshError;

/// Which kind of file an [`Error::MissingFile`] or [`Error::Io`] names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FileKind {
    /// The model itself (`.obj`, `.gltf`, `.glb`).
    Model,
    /// A Wavefront material library (`mtllib`).
    MaterialLibrary,
    /// A texture image (`map_Kd`, a glTF image, `--texture`).
    Texture,
    /// An external glTF buffer (`.bin`).
    GltfBuffer,
    /// The generated Rust source being written.
    Output,
}

impl fmt::Display for FileKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FileKind::Model => "model",
            FileKind::MaterialLibrary => "material library",
            FileKind::Texture => "texture",
            FileKind::GltfBuffer => "glTF buffer",
            FileKind::Output => "output",
        })
    }
}

/// Why an import failed. Every variant names what the user has to fix: the
/// file and line, the count over the limit, the value out of range.
#[derive(Debug)]
#[non_exhaustive]
pub enum Error {
    /// A file the model refers to (or the model itself) does not exist.
    MissingFile {
        /// What the file is.
        kind: FileKind,
        /// The path tried (relative names resolved against the referring file).
        path: PathBuf,
    },
    /// Reading or writing a file failed for another reason than its absence.
    Io {
        /// What the file is.
        kind: FileKind,
        /// The path.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The model (or its material library) is malformed.
    Parse {
        /// The file.
        path: PathBuf,
        /// The 1-based line of the fault, when the format has lines and it
        /// could be found.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },
    /// The file's extension is none of `.obj`, `.gltf`, `.glb`, or a texture
    /// is not a PNG.
    Unsupported {
        /// The file.
        path: PathBuf,
        /// What is not supported.
        what: String,
    },
    /// The model has no triangles (after dropping points, lines and
    /// zero-area triangles).
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// A coordinate, normal or texture coordinate is NaN or infinite.
    NotFinite {
        /// Which attribute.
        what: &'static str,
    },
    /// More vertices after welding than `u16` indices address with the
    /// last index kept free (the limit is 65 535): pass `--split`.
    TooManyVertices {
        /// The model file.
        path: PathBuf,
        /// The material whose faces are too many, when the model has several.
        material: Option<String>,
        /// The vertices the mesh needs.
        count: usize,
        /// Its triangles.
        triangles: usize,
    },
    /// More triangles than the renderer's `u16` bins address (65 535): pass
    /// `--split`.
    TooManyTriangles {
        /// The model file.
        path: PathBuf,
        /// The material whose faces are too many, when the model has several.
        material: Option<String>,
        /// The triangles the mesh has.
        count: usize,
        /// Its distinct (quantised) positions.
        positions: usize,
    },
    /// A coordinate does not fit `i16` even with `frac = 0` (|x| ≥ 32 767.5):
    /// use `--scale`.
    PositionRange {
        /// The largest coordinate magnitude.
        max_abs: f64,
    },
    /// The `frac` asked for (`--frac`) does not fit every coordinate.
    FracTooLarge {
        /// The fraction bits asked for.
        frac: u8,
        /// The largest that fits.
        max_fitting: u8,
    },
    /// A texture coordinate outside `[−8, 8)` (Q12 in an `i16`).
    TexcoordRange {
        /// The coordinate (in the file's convention).
        value: f64,
    },
    /// A texture was asked for (or tangents) but the mesh has no texture
    /// coordinates.
    NoTexcoords,
    /// A material value outside what OpenGL accepts (with `--strict`;
    /// without, it is clamped and a warning given).
    Material {
        /// The material's name.
        material: String,
        /// The value and its range.
        message: String,
    },
    /// A texture image could not be decoded.
    Texture {
        /// The image.
        path: PathBuf,
        /// The decoder's message.
        message: String,
    },
    /// A texture side is not a power of two (or above 2^15): fixshade samples
    /// with masks. Resample it, or pass `--resize`.
    TextureSize {
        /// The image.
        path: PathBuf,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
    },
    /// The `NAME` of the generated statics is not an upper-case Rust
    /// identifier (`[A-Z_][A-Z0-9_]*`).
    InvalidName(String),
    /// A fixshade mesh function rejected the data (tangents on degenerate
    /// texture coordinates, for example).
    Mesh {
        /// What was being computed.
        step: &'static str,
        /// The library's error.
        source: MeshError,
    },
    /// The `OUT_DIR` environment variable is not set (the build-script helper
    /// was called outside a build script).
    NoOutDir,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::MissingFile { kind, path } => {
                write!(f, "{kind} file not found: {}", path.display())
            }
            Error::Io { kind, path, source } => {
                write!(f, "{kind} file {}: {source}", path.display())
            }
            Error::Parse {
                path,
                line: Some(line),
                message,
            } => write!(f, "{}:{line}: {message}", path.display()),
            Error::Parse {
                path,
                line: None,
                message,
            } => write!(f, "{}: {message}", path.display()),
            Error::Unsupported { path, what } => {
                write!(f, "{}: unsupported: {what}", path.display())
            }
            Error::Empty { path } => write!(f, "{}: no triangles", path.display()),
            Error::NotFinite { what } => write!(f, "a {what} is NaN or infinite"),
            Error::TooManyVertices {
                path,
                material,
                count,
                triangles,
            } => write!(
                f,
                "{}: {count} vertices after welding ({triangles} triangles){}: more than the \
                 65535 vertices a fixshade mesh's u16 indices address; pass --split to cut the \
                 model into parts of at most 65535 vertices and 65535 triangles each",
                path.display(),
                of_material(material)
            ),
            Error::TooManyTriangles {
                path,
                material,
                count,
                positions,
            } => write!(
                f,
                "{}: {count} triangles ({positions} positions){}: more than the 65535 triangles \
                 the renderer's u16 bins address; pass --split to cut the model into parts of \
                 at most 65535 vertices and 65535 triangles each",
                path.display(),
                of_material(material)
            ),
            Error::PositionRange { max_abs } => write!(
                f,
                "a coordinate of magnitude {max_abs} does not fit an i16 even with frac = 0: \
                 scale the model down (--scale)"
            ),
            Error::FracTooLarge { frac, max_fitting } => write!(
                f,
                "frac = {frac} does not fit every coordinate in an i16; at most {max_fitting} does"
            ),
            Error::TexcoordRange { value } => write!(
                f,
                "texture coordinate {value} outside [-8, 8): Q12 in an i16 repeats a texture \
                 at most 8 times each way"
            ),
            Error::NoTexcoords => f.write_str(
                "a texture or tangents were asked for but the mesh has no texture coordinates",
            ),
            Error::Material { material, message } => write!(
                f,
                "material `{material}`: {message} (--strict: OpenGL's ranges are enforced)"
            ),
            Error::Texture { path, message } => write!(f, "texture {}: {message}", path.display()),
            Error::TextureSize {
                path,
                width,
                height,
            } => write!(
                f,
                "texture {} is {width} × {height}: sides must be powers of two up to 32768 \
                 (resample it, or pass --resize)",
                path.display()
            ),
            Error::InvalidName(n) => write!(
                f,
                "name {n:?} is not an upper-case Rust identifier ([A-Z_][A-Z0-9_]*)"
            ),
            Error::Mesh { step, source } => write!(f, "{step}: {source}"),
            Error::NoOutDir => f.write_str("OUT_DIR is not set: call this from a build script"),
        }
    }
}

/// `" in material `m`"`, or nothing.
fn of_material(material: &Option<String>) -> String {
    material
        .as_ref()
        .map_or_else(String::new, |m| format!(" in material `{m}`"))
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source),
            Error::Mesh { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Reads a whole file, a missing one reported as [`Error::MissingFile`].
pub(crate) fn read_file(kind: FileKind, path: &std::path::Path) -> Result<Vec<u8>, Error> {
    std::fs::read(path).map_err(|e| io_error(kind, path, e))
}

/// The error of an I/O failure on `path`.
pub(crate) fn io_error(kind: FileKind, path: &std::path::Path, e: std::io::Error) -> Error {
    if e.kind() == std::io::ErrorKind::NotFound {
        Error::MissingFile {
            kind,
            path: path.to_path_buf(),
        }
    } else {
        Error::Io {
            kind,
            path: path.to_path_buf(),
            source: e,
        }
    }
}
