//! The standard scene (`fixshade::standard`) as firmware renders it: the mesh
//! renderer in bands of `rows` rows, straight to a `DrawTarget`. The same
//! functions run in the firmware images (`src/main.rs`, one configuration
//! per image) and on the host (`src/host.rs`: the reference checksums).
//!
//! Configurations (all `Q14`, `Linear`, back faces culled, depth test on):
//! `lambert_gouraud`, `blinn_gouraud`, `blinn_phong`, `blinn_phong_inc`
//! (`IncrementalPhongShading`), `flat` (Lambert). Each is a module with the
//! vertex payload `Vertex`, the lighting type `Light`, `lighting()` (built
//! once, from the scene's `f32` parameters) and `frame(...)` (one frame).
#![no_std]

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::camera::{MeshTransform, Orthographic};
use fixshade::prelude::*;
use fixshade::render::{
    Bands, CachedVertex, Carry, DrawBand, Layout, MeshDraw, MeshMemory, RenderError,
};
use fixshade::shade::{GeneralPhongShading, Kernel};
use fixshade::standard;

/// Frame width and height (240).
pub const W: usize = standard::SIZE as usize;
/// Mesh vertices (362) and triangles (720).
pub const NV: usize = standard::COUNTS.0;
/// Mesh triangles.
pub const NT: usize = standard::COUNTS.1;
/// Resume records: the standard scene needs 48 (`MeshDraw::carry_needed`,
/// printed by the host reference).
pub const CARRY: usize = 64;

/// Bands of `rows` rows.
pub const fn bands(rows: usize) -> usize {
    W.div_ceil(rows)
}

/// Bin entries for bands of `rows` rows (the documented `bins_len`: every
/// triangle could be visible).
pub const fn bins(rows: usize) -> usize {
    bins_len(NT, bands(rows))
}

/// Why a frame was not drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fail {
    /// The lighting's `f32` parameters were rejected.
    Lighting,
    /// The camera or transform was rejected.
    Transform,
    /// `RenderError::Size` or `TooManyVertices`, or the display failed.
    Render,
    /// A buffer too small: elements needed.
    Buffer(usize),
}

impl From<RenderError> for Fail {
    fn from(e: RenderError) -> Fail {
        match e {
            RenderError::BufferTooSmall { needed, .. } => Fail::Buffer(needed),
            _ => Fail::Render,
        }
    }
}

/// Caller-owned memory of one frame: the mesh's vertex cache, bins and
/// resume records, and one band strip with its depth strip (`W · rows`).
pub struct Buffers<'a, V> {
    /// One entry per vertex.
    pub cache: &'a mut [CachedVertex<V>],
    /// [`bins`]`(rows)` entries.
    pub bins: &'a mut [u16],
    /// [`CARRY`] records.
    pub carry: &'a mut [Carry],
    /// The colour strip.
    pub strip: &'a mut [Rgb565],
    /// The depth strip.
    pub depth: &'a mut [u16],
}

/// The mesh transform of the standard scene (once, before the frames).
pub fn transform() -> Result<MeshTransform<Orthographic>, Fail> {
    standard::transform().map_err(|_| Fail::Transform)
}

/// One frame in bands of `rows` rows: vertex stage and bins, then per band
/// clear, draw, send to `display`. Returns the resume records it needed.
#[inline(never)]
pub fn draw<K, D>(
    kernel: K,
    t: &MeshTransform<Orthographic>,
    rows: usize,
    b: Buffers<'_, K::Vertex>,
    display: &mut D,
) -> Result<usize, Fail>
where
    K: Kernel<Color = Rgb565>,
    D: DrawTarget<Color = Rgb565>,
{
    let layout = Layout::banded(W as u32, W as u32, rows as u32)?;
    let mut draw = MeshDraw::new(
        layout,
        standard::SPHERE.mesh(),
        t,
        kernel,
        MeshMemory {
            vertices: b.cache,
            bins: b.bins,
            carry: b.carry,
        },
    )?;
    let needed = draw.carry_needed();
    let mut bands = Bands::new(layout, b.strip, Some(b.depth))?;
    let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut draw];
    bands
        .render(display, Rgb565::BLACK, items)
        .map_err(|_| Fail::Render)?;
    Ok(needed)
}

/// The lighting of `blinn_phong_inc`: one directional light in an array, as
/// `IncrementalPhongShading` requires.
pub fn inc_lighting() -> Result<Lighting<Q14, [Dir; 1], BlinnPhong>, ParamError> {
    Ok(
        Lighting::<Q14, [DirectionalLight<Q14>; 1], BlinnPhong>::new(
            [standard::light()?],
            Material::new(&standard::material())?,
        )
        // the standard scene: no global ambient light, the light in eye
        // coordinates (as standard::blinn)
        .with_global_ambient_f32([0.0; 3])
        .eye_space(),
    )
}

macro_rules! configs {
    ($($name:ident: $v:ty, $l:ty = $lighting:expr, $mode:expr;)*) => {
        /// Configuration names, in order.
        pub const CONFIGS: &[&str] = &[$(stringify!($name)),*];
        $(
            #[doc = concat!("The `", stringify!($name), "` configuration.")]
            pub mod $name {
                use super::*;
                /// Its name.
                pub const NAME: &str = stringify!($name);
                /// The vertex cache payload of its shader.
                pub type Vertex = $v;
                /// The lighting.
                pub type Light = $l;
                /// The lighting (built once, like the transform, outside the frame).
                pub fn lighting() -> Result<Light, Fail> {
                    $lighting.map_err(|_| Fail::Lighting)
                }
                /// The transform and the lighting (once, before the frames;
                /// not inlined, so that its code counts as the scene's).
                #[inline(never)]
                pub fn setup() -> Result<(MeshTransform<Orthographic>, Light), Fail> {
                    Ok((transform()?, lighting()?))
                }
                /// One frame: the shader, then [`draw`] (not inlined: the
                /// firmware measures its stack from the call).
                #[inline(never)]
                pub fn frame<D: DrawTarget<Color = Rgb565>>(
                    t: &MeshTransform<Orthographic>,
                    lighting: &Light,
                    rows: usize,
                    b: Buffers<'_, Vertex>,
                    display: &mut D,
                ) -> Result<usize, Fail> {
                    draw(Shader::new($mode, lighting, Linear), t, rows, b, display)
                }
            }
        )*
        /// Runs configuration `name` in bands of `rows` rows on buffers of
        /// the given sizes (the host reference; the firmware calls the
        /// modules directly).
        #[allow(clippy::too_many_arguments)]
        pub fn run<D: DrawTarget<Color = Rgb565>>(
            name: &str,
            t: &MeshTransform<Orthographic>,
            rows: usize,
            bins: &mut [u16],
            carry: &mut [Carry],
            strip: &mut [Rgb565],
            depth: &mut [u16],
            display: &mut D,
        ) -> Option<Result<usize, Fail>> {
            $(
                if name == stringify!($name) {
                    let mut cache = [CachedVertex::<$v>::default(); NV];
                    let b = Buffers { cache: &mut cache, bins, carry, strip, depth };
                    return Some($name::lighting().and_then(|l| $name::frame(t, &l, rows, b, display)));
                }
            )*
            None
        }
    };
}

type Dir = DirectionalLight<Q14>;

configs! {
    lambert_gouraud: [u16; 3], Lighting<Q14, Dir, Lambert>
        = standard::lambert::<Q14>(), GouraudShading;
    blinn_gouraud: [u16; 3], Lighting<Q14, Dir, BlinnPhong>
        = standard::blinn::<Q14>(), GouraudShading;
    blinn_phong: [i16; 3], Lighting<Q14, Dir, BlinnPhong>
        = standard::blinn::<Q14>(), GeneralPhongShading;
    blinn_phong_inc: [i16; 3], Lighting<Q14, [Dir; 1], BlinnPhong>
        = inc_lighting(), IncrementalPhongShading;
    flat: [i16; 3], Lighting<Q14, Dir, Lambert>
        = standard::lambert::<Q14>(), FlatShading;
}
