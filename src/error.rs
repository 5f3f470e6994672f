//! Every error of the crate, in one place.
//!
//! Each stage has its error type — [`ParamError`] (lights, materials,
//! colours, cameras), [`MeshError`] (meshes and their operations),
//! [`TextureError`] (textures and normal maps), [`RenderError`] (frames,
//! buffers, what a shader needs from a mesh) — and every one converts into
//! the crate's [`Error`] with `?`. All implement [`core::error::Error`] and
//! `Display`, all are `#[non_exhaustive]`, and a caller-owned buffer that is
//! too short is always `BufferTooSmall { which, needed, got }`: which buffer,
//! how many elements it needs and how many it has.
//!
//! ```
//! use fixshade::error::{Error, RenderError};
//! use fixshade::framebuffer::Layout;
//! fn frame() -> Result<(), Error> {
//!     let _layout = Layout::banded(0, 240, 8)?; // a RenderError, converted
//!     Ok(())
//! }
//! assert_eq!(frame(), Err(Error::Render(RenderError::Size)));
//! ```

use core::fmt;

/// Any error of the crate: the error of the stage that failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Error {
    /// A lighting, material, colour, gamma or camera parameter.
    Param(ParamError),
    /// A mesh or mesh operation.
    Mesh(MeshError),
    /// A texture or normal map.
    Texture(TextureError),
    /// A frame, its buffers, or what a shader needs from a mesh.
    Render(RenderError),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Param(e) => e.fmt(f),
            Error::Mesh(e) => e.fmt(f),
            Error::Texture(e) => e.fmt(f),
            Error::Render(e) => e.fmt(f),
        }
    }
}

impl core::error::Error for Error {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Error::Param(e) => Some(e),
            Error::Mesh(e) => Some(e),
            Error::Texture(e) => Some(e),
            Error::Render(e) => Some(e),
        }
    }
}

macro_rules! from_stage {
    ($($ty:ident => $var:ident),*) => {$(
        impl From<$ty> for Error {
            fn from(e: $ty) -> Self {
                Error::$var(e)
            }
        }
    )*};
}
from_stage!(ParamError => Param, MeshError => Mesh, TextureError => Texture, RenderError => Render);

/// Writes `which too small: needed N, got M`.
fn too_small(f: &mut fmt::Formatter<'_>, which: &str, needed: usize, got: usize) -> fmt::Result {
    write!(
        f,
        "{which} too small: {needed} elements needed, {got} given"
    )
}

/// Why a lighting, material, colour or gamma parameter was rejected.
///
/// Constructors that take `f32` validate their input and return this error instead
/// of panicking. Each variant names the offending parameter.
///
/// ```
/// use fixshade::lighting::DirectionalLight;
/// use fixshade::error::ParamError;
/// let err = DirectionalLight::<f32>::white([0.0, 0.0, 0.0]).unwrap_err();
/// assert_eq!(err, ParamError::ZeroDirection("direction"));
/// assert_eq!(err.to_string(), "direction: zero-length direction");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ParamError {
    /// The named parameter is NaN or infinite.
    NotFinite(&'static str),
    /// The named coefficient or intensity is negative.
    Negative(&'static str),
    /// The named direction has zero (or denormal) length.
    ZeroDirection(&'static str),
    /// The spot cutoff is outside [0°, 90°] (or exactly 180° for "no cone").
    CutoffOutOfRange,
    /// All three attenuation coefficients are zero.
    AttenuationAllZero,
    /// The named exponent is outside its documented range.
    ExponentOutOfRange(&'static str),
    /// The named parameter (a camera plane, a viewport side, a number of
    /// fraction bits) is outside its documented range.
    OutOfRange(&'static str),
    /// The relative index of refraction is not positive.
    RefractiveIndex,
    /// The gamma exponent is outside [1, 4].
    GammaOutOfRange,
    /// The fog end distance is not beyond its start.
    FogRange,
    /// A term beyond the tier's range ([`Lighting::checked`](crate::lighting::Lighting::checked)):
    /// the named product or sum must stay below `limit` in magnitude in tier
    /// `tier` ([`Scalar::NAME`](crate::num::Scalar::NAME)); use a wider tier
    /// (`f32`) for such scenes.
    TierRange {
        /// The term.
        param: &'static str,
        /// The tier's name.
        tier: &'static str,
        /// The largest magnitude the tier holds, rounded up (2 for the fixed tiers).
        limit: u32,
    },
    /// An OpenGL light of another kind than the light type asked for (e.g. a
    /// positional `GL_POSITION` for a [`DirectionalLight`](crate::lighting::DirectionalLight)).
    LightKind(&'static str),
    /// More lights than the light set holds.
    LightCount {
        /// Lights given.
        lights: usize,
        /// Lights the set holds (its exact length for arrays).
        capacity: usize,
    },
    /// The viewer type does not match `GL_LIGHT_MODEL_LOCAL_VIEWER`.
    Viewer(&'static str),
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite(p) => write!(f, "{p}: NaN or infinite"),
            Self::Negative(p) => write!(f, "{p}: negative"),
            Self::ZeroDirection(p) => write!(f, "{p}: zero-length direction"),
            Self::CutoffOutOfRange => f.write_str(
                "spot cutoff: outside 0..=90 degrees (180, no cone, is a point light: PointLight)",
            ),
            Self::AttenuationAllZero => f.write_str("attenuation: all coefficients are zero"),
            Self::ExponentOutOfRange(p) => write!(f, "{p}: exponent out of range"),
            Self::OutOfRange(p) => write!(f, "{p}: out of range"),
            Self::RefractiveIndex => f.write_str("relative refractive index: not positive"),
            Self::GammaOutOfRange => f.write_str("gamma: outside 1..=4"),
            Self::FogRange => f.write_str("fog: end is not beyond start"),
            Self::TierRange { param, tier, limit } => {
                write!(
                    f,
                    "{param}: beyond the range of tier {tier} (magnitude below {limit})"
                )
            }
            Self::LightKind(p) => write!(f, "light kind: {p}"),
            Self::LightCount { lights, capacity } => {
                write!(f, "{lights} lights for a light set of {capacity}")
            }
            Self::Viewer(p) => write!(f, "viewer: {p}"),
        }
    }
}

impl core::error::Error for ParamError {}

/// `v` when it is finite, else `err(name)` (an error type's `NotFinite`).
pub(crate) fn finite_or<E>(
    name: &'static str,
    v: f32,
    err: fn(&'static str) -> E,
) -> Result<f32, E> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(err(name))
    }
}

/// Checks that `v` is finite.
pub(crate) fn finite(name: &'static str, v: f32) -> Result<f32, ParamError> {
    finite_or(name, v, ParamError::NotFinite)
}

/// Checks every component with [`finite`].
pub(crate) fn finite_all<const N: usize>(
    name: &'static str,
    v: [f32; N],
) -> Result<[f32; N], ParamError> {
    for c in v {
        finite(name, c)?;
    }
    Ok(v)
}

/// `check_len(which, needed, got)`: `Ok` when `got ≥ needed`, else the
/// error's `BufferTooSmall` naming `which` (a `const fn`:
/// [`Mesh`](crate::mesh::Mesh)'s constructors use it).
macro_rules! check_len {
    ($($err:ident $(<$g:ident>)?),*) => {$(
        impl$(<$g>)? $err$(<$g>)? {
            pub(crate) const fn check_len(
                which: &'static str,
                needed: usize,
                got: usize,
            ) -> Result<(), Self> {
                if got < needed {
                    Err(Self::BufferTooSmall { which, needed, got })
                } else {
                    Ok(())
                }
            }
        }
    )*};
}
check_len!(MeshError, TextureError, RenderError<E>);

/// Checks that `v` is finite and not negative.
pub(crate) fn non_negative(name: &'static str, v: f32) -> Result<f32, ParamError> {
    let v = finite(name, v)?;
    if v < 0.0 {
        Err(ParamError::Negative(name))
    } else {
        Ok(v)
    }
}

/// Checks every component with [`non_negative`].
pub(crate) fn non_negative3(name: &'static str, v: [f32; 3]) -> Result<[f32; 3], ParamError> {
    for c in v {
        non_negative(name, c)?;
    }
    Ok(v)
}

/// Checks that a direction is finite and has a usable length; returns it
/// normalised in `f32`, not `f64` (no soft double arithmetic linked): relative
/// error ≈ 10⁻⁷, under 1 LSB of 8-bit output even in Q30.
pub(crate) fn direction(name: &'static str, v: [f32; 3]) -> Result<[f32; 3], ParamError> {
    finite_all(name, v)?;
    // scale by the largest component first so that squaring neither overflows nor
    // underflows for any finite input
    let m = v[0].abs().max(v[1].abs()).max(v[2].abs());
    if !(m > 1.0e-30) {
        return Err(ParamError::ZeroDirection(name));
    }
    let [x, y, z] = v.map(|c| c / m);
    let len = libm::sqrtf(x * x + y * y + z * z);
    Ok([x / len, y / len, z / len])
}

/// Why a mesh operation was rejected. Nothing is written to the outputs when an
/// error is returned, except where a function documents otherwise.
///
/// ```
/// use fixshade::mesh::face_normals;
/// use fixshade::error::MeshError;
/// let pos = [[0.0f32; 3]; 3];
/// let mut out = [[0.0f32; 3]; 1];
/// let err = face_normals(&pos, &[[0, 1, 3]], &mut out).unwrap_err();
/// assert_eq!(err, MeshError::IndexOutOfRange { triangle: 0, index: 3 });
/// assert_eq!(err.to_string(), "triangle 0: vertex index 3 out of range");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum MeshError {
    /// An output (or scratch) slice holds fewer elements than needed.
    BufferTooSmall {
        /// Which buffer.
        which: &'static str,
        /// Elements required.
        needed: usize,
        /// Elements provided.
        got: usize,
    },
    /// A triangle refers to a vertex beyond the end of the positions.
    IndexOutOfRange {
        /// Index of the offending triangle.
        triangle: usize,
        /// The vertex index it holds.
        index: u16,
    },
    /// The mesh would need more vertices than a `u16` index can address (65536).
    TooManyVertices {
        /// Vertices the mesh would need.
        needed: usize,
    },
    /// The named parameter is NaN or infinite.
    NotFinite(&'static str),
    /// The named parameter is outside its documented range.
    OutOfRange(&'static str),
    /// A vertex coordinate does not fit an `i16` at the chosen number of
    /// fraction bits ([`to_compact`](crate::mesh::to_compact)).
    PositionOutOfRange {
        /// Index of the vertex.
        vertex: usize,
        /// The coordinate: 0 for x, 1 for y, 2 for z.
        axis: u8,
        /// The fraction bits asked for.
        frac: u8,
        /// The most fraction bits at which this coordinate fits (`None`: it
        /// does not fit even at 0, `|p| ≥ 32767.5`).
        fits: Option<u8>,
    },
    /// The named parameters describe a degenerate configuration (zero-length
    /// direction, parallel vectors, empty volume).
    Degenerate(&'static str),
    /// The mesh lacks the named per-vertex attribute (texture coordinates,
    /// tangents) the operation reads.
    MissingAttribute(&'static str),
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BufferTooSmall { which, needed, got } => too_small(f, which, *needed, *got),
            Self::IndexOutOfRange { triangle, index } => {
                write!(f, "triangle {triangle}: vertex index {index} out of range")
            }
            Self::TooManyVertices { needed } => {
                write!(f, "{needed} vertices exceed the u16 index range")
            }
            Self::NotFinite(p) => write!(f, "{p}: NaN or infinite"),
            Self::OutOfRange(p) => write!(f, "{p}: out of range"),
            Self::PositionOutOfRange {
                vertex,
                axis,
                frac,
                fits,
            } => {
                let c = ["x", "y", "z"].get(usize::from(*axis)).unwrap_or(&"?");
                write!(f, "vertex {vertex}: {c} does not fit an i16 at frac {frac}")?;
                match fits {
                    Some(k) => write!(f, " (it fits at frac {k} or less)"),
                    None => f.write_str(" (nor at frac 0: |value| ≥ 32767.5)"),
                }
            }
            Self::Degenerate(p) => write!(f, "{p}: degenerate"),
            Self::MissingAttribute(p) => write!(f, "the mesh has no {p}"),
        }
    }
}

impl core::error::Error for MeshError {}

/// Why a texture or normal map was rejected.
///
/// ```
/// use fixshade::error::TextureError;
/// use fixshade::texture::{Texels, Texture, Wrap};
/// static TEXELS: [u16; 3] = [0; 3];
/// let err = Texture::new(Texels::Rgb565(&TEXELS), 1, 1, Wrap::Repeat).unwrap_err();
/// assert_eq!(err, TextureError::BufferTooSmall { which: "texels", needed: 4, got: 3 });
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TextureError {
    /// A side's `log2` exceeds [`Texture::MAX_LOG2_SIZE`](crate::texture::Texture::MAX_LOG2_SIZE)
    /// (a texture) or [`NormalMap::MAX_LOG2_SIZE`](crate::texture::NormalMap::MAX_LOG2_SIZE).
    TooLarge {
        /// The `log2` given.
        log2: u8,
    },
    /// A texel, height or output slice holds fewer elements than the size
    /// needs.
    BufferTooSmall {
        /// Which slice.
        which: &'static str,
        /// Elements required.
        needed: usize,
        /// Elements provided.
        got: usize,
    },
    /// A palette of more than 256 colours.
    PaletteTooLong,
    /// The named parameter is NaN or infinite.
    NotFinite(&'static str),
    /// The named vector has zero length.
    Degenerate(&'static str),
    /// A normal map's texel is not a unit normal (`x² + y² + z²` outside
    /// `2^28 ± 2^15`; see [`NormalMap::new`](crate::texture::NormalMap::new)).
    NotUnit {
        /// The texel's index (row by row).
        index: usize,
        /// The texel.
        texel: [i16; 3],
    },
}

impl fmt::Display for TextureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooLarge { log2 } => write!(f, "texture side 2^{log2} too large"),
            Self::BufferTooSmall { which, needed, got } => too_small(f, which, *needed, *got),
            Self::PaletteTooLong => f.write_str("palette longer than 256 colours"),
            Self::NotFinite(p) => write!(f, "{p}: NaN or infinite"),
            Self::Degenerate(p) => write!(f, "{p}: zero length"),
            Self::NotUnit { index, texel } => write!(
                f,
                "texel {index} {texel:?} is not a unit normal (x² + y² + z² must be 2^28 ± 2^15)"
            ),
        }
    }
}

impl core::error::Error for TextureError {}

/// Why a frame could not be prepared or drawn.
///
/// ```
/// use fixshade::error::RenderError;
/// use fixshade::framebuffer::{Bands, Layout};
/// use embedded_graphics_core::pixelcolor::Rgb565;
/// let layout = Layout::banded(240, 240, 8)?;
/// let mut strip = [Rgb565::new(0, 0, 0); 240 * 4];
/// let err = Bands::new(layout, &mut strip, None).unwrap_err();
/// assert_eq!(err, RenderError::BufferTooSmall { which: "colour strip", needed: 1920, got: 960 });
/// assert_eq!(err.to_string(), "colour strip too small: 1920 elements needed, 960 given");
/// # Ok::<(), RenderError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RenderError<E = core::convert::Infallible> {
    /// The frame is empty or larger than 1024 pixels a side, or a band has no
    /// rows.
    Size,
    /// A caller-owned buffer is too small.
    BufferTooSmall {
        /// Which buffer.
        which: &'static str,
        /// Elements needed.
        needed: usize,
        /// Elements given.
        got: usize,
    },
    /// A mesh with its refinement's new vertices needs more vertices than
    /// `u16` indices address.
    TooManyVertices {
        /// Vertices needed.
        needed: usize,
    },
    /// A prepared mesh is drawn through a frame of another layout than the
    /// one it was binned for.
    LayoutMismatch,
    /// The shader reads a per-vertex attribute the mesh does not have
    /// (`"texture coordinates"`, `"tangents"`).
    MissingAttribute(&'static str),
    /// The display returned an error while a band was sent.
    Display(E),
}

impl<E> RenderError<E> {
    /// The same error for a display whose error type is `E` (an error that
    /// carries no display error).
    pub fn widen(e: RenderError) -> Self {
        match e {
            RenderError::Size => RenderError::Size,
            RenderError::BufferTooSmall { which, needed, got } => {
                RenderError::BufferTooSmall { which, needed, got }
            }
            RenderError::TooManyVertices { needed } => RenderError::TooManyVertices { needed },
            RenderError::LayoutMismatch => RenderError::LayoutMismatch,
            RenderError::MissingAttribute(a) => RenderError::MissingAttribute(a),
            RenderError::Display(e) => match e {},
        }
    }
}

impl<E: fmt::Debug> fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Size => f.write_str(
                "frame size out of range (sides 1 to 1024 pixels, bands of at least one row)",
            ),
            Self::BufferTooSmall { which, needed, got } => too_small(f, which, *needed, *got),
            Self::TooManyVertices { needed } => {
                write!(f, "{needed} vertices exceed the u16 index range")
            }
            Self::LayoutMismatch => f.write_str("the mesh was prepared for another frame layout"),
            Self::MissingAttribute(a) => write!(f, "the shader needs {a}, the mesh has none"),
            Self::Display(e) => write!(f, "display error: {e:?}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for RenderError<E> {}
