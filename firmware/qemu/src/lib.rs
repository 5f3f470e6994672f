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
//!
//! With the features `imported` / `imported_textured`: the demo rocket that
//! `build.rs` imports from `import/assets/rocket.obj` (fixshade-import) into
//! `$OUT_DIR/model.rs`, drawn by the modules [`imported`] (Gouraud) and
//! [`imported_textured`] (textured Gouraud), with the same interface plus the
//! mesh's counts `NV`, `NT`.
#![no_std]

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::camera::{MeshTransform, Orthographic};
use fixshade::error::RenderError;
use fixshade::framebuffer::{Bands, DrawBand, Layout};
use fixshade::prelude::*;
use fixshade::render::{CachedVertex, Carry, MeshDraw, MeshMemory};
use fixshade::shade::Kernel;
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

/// Bin entries for a mesh of `triangles` triangles in bands of `rows` rows.
pub const fn bins_for(triangles: usize, rows: usize) -> usize {
    bins_len(triangles, bands(rows))
}

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
        DrawOptions::default(),
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
pub fn inc_lighting() -> Result<Viewed<Lighting<Q14, [Dir; 1], BlinnPhong>>, ParamError> {
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
                /// The mesh's vertices (the standard sphere).
                pub const NV: usize = super::NV;
                /// The mesh's triangles.
                pub const NT: usize = super::NT;
                /// Resume records.
                pub const CARRY: usize = super::CARRY;
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
    lambert_gouraud: [u16; 3], Viewed<Lighting<Q14, Dir, Lambert>>
        = standard::lambert::<Q14>(), GouraudShading;
    blinn_gouraud: [u16; 3], Viewed<Lighting<Q14, Dir, BlinnPhong>>
        = standard::blinn::<Q14>(), GouraudShading;
    blinn_phong: [i16; 3], Viewed<Lighting<Q14, Dir, BlinnPhong>>
        = standard::blinn::<Q14>(), PhongShading;
    blinn_phong_inc: [i16; 3], Viewed<Lighting<Q14, [Dir; 1], BlinnPhong>>
        = inc_lighting(), IncrementalPhongShading;
    flat: [i16; 3], Viewed<Lighting<Q14, Dir, Lambert>>
        = standard::lambert::<Q14>(), FlatShading;
}

/// The rocket, as `build.rs` imported it (`ROCKET`, `ROCKET_FRAC`,
/// `ROCKET_TEXTURE` and their arrays).
#[cfg(any(feature = "imported", feature = "imported_textured"))]
#[allow(missing_docs)]
pub mod model {
    include!(concat!(env!("OUT_DIR"), "/model.rs"));
}

/// The rocket's scene: camera, model matrix, lighting (shared by
/// [`imported`] and [`imported_textured`]).
#[cfg(any(feature = "imported", feature = "imported_textured"))]
pub mod rocket {
    use super::*;
    use fixshade::camera::{Camera, Viewport};
    use fixshade::mesh::Mesh;
    use fixshade::num::Mat4;

    /// Its vertices (687).
    pub const NV: usize = super::model::ROCKET_POSITIONS.len();
    /// Its triangles (784).
    pub const NT: usize = super::model::ROCKET_TRIANGLES.len();
    /// Resume records: the rocket needs 134 in 2-row bands (printed by the
    /// host reference).
    pub const CARRY: usize = 136;

    /// The mesh (in flash).
    pub fn mesh() -> Mesh<'static> {
        super::model::ROCKET
    }

    /// The rocket's transform: the bounds are about ±0.55 across and −1.12 to
    /// 1.20 along y; tilted towards the camera and turned so that the
    /// portholes (u = 1/4, the +x side) face it, in a ±1.35 orthographic view.
    pub fn transform() -> Result<MeshTransform<Orthographic>, Fail> {
        let model = Mat4::rotate_x(0.25).mul(&Mat4::rotate_y(-1.2));
        camera()?
            .mesh_transform(&model, super::model::ROCKET_FRAC)
            .map_err(|_| Fail::Transform)
    }

    /// The camera: five units up +z, looking down −z.
    fn camera() -> Result<Camera<Orthographic>, Fail> {
        let s = 1.35;
        Ok(Camera::orthographic(
            -s,
            s,
            -s,
            s,
            1.0,
            10.0,
            Viewport::new(0, 0, standard::SIZE, standard::SIZE).map_err(|_| Fail::Transform)?,
        )
        .map_err(|_| Fail::Transform)?
        .with_view(Mat4::translate([0.0, 0.0, -5.0])))
    }

    /// One directional light, ambient + Lambert diffuse on a white material
    /// (the texture, where there is one, gives the colour), OpenGL's global
    /// ambient light.
    pub fn lighting() -> Result<Viewed<Lighting<Q14, DirectionalLight<Q14>, Lambert>>, Fail> {
        let light = DirectionalLight::new(
            [1.0, 0.8, 1.0],
            LightColors::new([1.0; 3], [1.0; 3], [1.0; 3]).map_err(|_| Fail::Lighting)?,
        )
        .map_err(|_| Fail::Lighting)?;
        let material = Material::new(&MaterialDesc {
            ambient: [0.2; 3],
            diffuse: [0.85; 3],
            specular: [0.0; 3],
            ..MaterialDesc::default()
        })
        .map_err(|_| Fail::Lighting)?;
        // the camera's view is a translation, which leaves a directional
        // light's direction as it is: the light is given in eye coordinates
        // (`viewed(camera.view())` gives the same lighting but needs 1.2 KiB
        // more stack at start-up, which the micro:bit's 2.75 KiB do not have)
        Ok(Lighting::new(light, material).eye_space())
    }

    /// One frame of `kernel` on the rocket in bands of `rows` rows (as
    /// [`draw`], on the imported mesh).
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
            mesh(),
            t,
            kernel,
            MeshMemory {
                vertices: b.cache,
                bins: b.bins,
                carry: b.carry,
            },
            DrawOptions::default(),
        )?;
        let needed = draw.carry_needed();
        let mut bands = Bands::new(layout, b.strip, Some(b.depth))?;
        let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut draw];
        bands
            .render(display, Rgb565::BLACK, items)
            .map_err(|_| Fail::Render)?;
        Ok(needed)
    }
}

macro_rules! imported {
    ($($(#[$doc:meta])* $feature:literal $name:ident: $v:ty = $mode:expr;)*) => {
        /// The imported configurations (each present with its feature).
        pub const IMPORTED: &[&str] = &[$(stringify!($name)),*];
        $(
            $(#[$doc])*
            #[cfg(feature = $feature)]
            pub mod $name {
                use super::*;
                /// Its name.
                pub const NAME: &str = stringify!($name);
                /// The vertex cache payload of its shader.
                pub type Vertex = $v;
                /// The lighting.
                pub type Light = Viewed<Lighting<Q14, Dir, Lambert>>;
                /// The mesh's vertices.
                pub const NV: usize = rocket::NV;
                /// The mesh's triangles.
                pub const NT: usize = rocket::NT;
                /// Resume records.
                pub const CARRY: usize = rocket::CARRY;
                /// The transform and the lighting (once, before the frames).
                #[inline(never)]
                pub fn setup() -> Result<(MeshTransform<Orthographic>, Light), Fail> {
                    Ok((rocket::transform()?, rocket::lighting()?))
                }
                /// One frame (not inlined: the firmware measures its stack
                /// from the call).
                #[inline(never)]
                pub fn frame<D: DrawTarget<Color = Rgb565>>(
                    t: &MeshTransform<Orthographic>,
                    lighting: &Light,
                    rows: usize,
                    b: Buffers<'_, Vertex>,
                    display: &mut D,
                ) -> Result<usize, Fail> {
                    rocket::draw(Shader::new($mode, lighting, Linear), t, rows, b, display)
                }
            }
        )*
        /// Runs imported configuration `name` (set-up included) in bands of
        /// `rows` rows (the host reference); `None` for a name that is not
        /// an imported configuration built in (its feature off).
        #[allow(clippy::too_many_arguments)]
        pub fn run_imported<D: DrawTarget<Color = Rgb565>>(
            name: &str,
            rows: usize,
            bins: &mut [u16],
            carry: &mut [Carry],
            strip: &mut [Rgb565],
            depth: &mut [u16],
            display: &mut D,
        ) -> Option<Result<usize, Fail>> {
            $(
                #[cfg(feature = $feature)]
                if name == stringify!($name) {
                    let mut cache = [CachedVertex::<$v>::default(); rocket::NV];
                    let b = Buffers { cache: &mut cache, bins, carry, strip, depth };
                    return Some($name::setup().and_then(|(t, l)| $name::frame(&t, &l, rows, b, display)));
                }
            )*
            let _ = (name, rows, bins, carry, strip, depth, display);
            None
        }
    };
}

imported! {
    /// The `imported` configuration: the rocket, Gouraud (Lambert), untextured
    /// (12-byte cache entries: fits the micro:bit in 2-row bands).
    "imported" imported: [u16; 3] = GouraudShading;
    /// The `imported_textured` configuration: the rocket, textured Gouraud
    /// (Lambert, `ROCKET_TEXTURE`, nearest texel: the 5-6-5 fast path).
    "imported_textured" imported_textured: TexVertex = GouraudShading.textured(model::ROCKET_TEXTURE, Filter::Nearest);
}

/// The textured Gouraud shader's vertex cache payload (16 bytes: 22 per
/// cache entry).
#[cfg(feature = "imported_textured")]
pub type TexVertex = fixshade::shade::Payload<fixshade::shade::Textured<'static, GouraudShading>>;
#[cfg(feature = "imported_textured")]
use fixshade::texture::Filter;
