//! The standard scene (`fixshade::standard`) rendered as one whole frame, for
//! `measure/frame.py`: the same functions run on the host (reference
//! checksums, lit pixels) and in the firmware image (emulated Cortex-M0/M4F).
//!
//! One module per configuration (`lambert_gouraud`, `blinn_gouraud`,
//! `blinn_phong`, `blinn_phong_inc`, `flat`, and `lambert_gouraud_refine`:
//! `lambert_gouraud` with silhouette refinement; and the `f32` tier's
//! `lambert_gouraud_f32`, `blinn_gouraud_f32`, `blinn_phong_f32`, `flat_f32`:
//! the same scenes lit in `f32`, soft float on a core without an FPU; the
//! firmware image exports them on RISC-V only), each with
//!
//! * `full(t, buffers, display)`: a 240 × 240 [`FullFrame`] (colour + depth
//!   buffer) rendered and flushed to `display`;
//! * `band8(t, buffers, display)`: [`Bands`] of 8 rows over a 240 · 8 strip and
//!   depth strip, each band sent to `display`.
//!
//! Both build the lighting and the shader (the scene set-up, from `f32`
//! parameters), then call [`draw_full`] / [`draw_bands`] (never inlined: the
//! per-frame path, whose call graph `frame.py --check` inspects on its own):
//! vertex stage and binning (`MeshDraw::new`), clears, spans, flush. The
//! mesh transform is built by the caller (the firmware: in integers every frame,
//! [`standard::fixed_transform`]) and passed in.
#![no_std]

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::camera::{MeshTransform, Orthographic};
use fixshade::prelude::*;
use fixshade::render::{bins_len, CachedVertex, Carry, DrawOptions, MeshDraw, MeshMemory};
use fixshade::framebuffer::{Bands, DrawBand, FullFrame, Layout};
use fixshade::render::refine::{Refine, RefineBuffers};
use fixshade::error::RenderError;
use fixshade::shade::Kernel;
use fixshade::standard;

/// The sphere's mesh view, validated at compile time (`MeshData::mesh` called
/// at run time checks every index again, and has a panic path for data that
/// fails the check: measure/panics.py).
static SPHERE_MESH: Mesh<'static> = standard::SPHERE.mesh();

/// Frame width and height.
pub const W: usize = standard::SIZE as usize;
/// Mesh vertices and triangles.
pub const NV: usize = standard::COUNTS.0;
pub const NT: usize = standard::COUNTS.1;
/// Rows per band of the banded configurations.
pub const BAND_ROWS: usize = 8;
/// Bands of the banded configurations.
pub const BANDS: usize = W.div_ceil(BAND_ROWS);
/// Bins: the documented size `bins_len` (every triangle could be visible).
pub const BINS_FULL: usize = bins_len(NT, 1);
pub const BINS_BAND: usize = bins_len(NT, BANDS);
/// Resume records for 8-row bands: the standard scene needs
/// `MeshDraw::carry_needed()` = 48 (the host run prints it; a smaller
/// array makes every banded frame fail with status `Fail::Buffer`).
pub const CARRY_BAND: usize = 64;

/// Silhouette refinement's budget in the `_refine` configurations: new
/// vertices and replacing triangles (`4·REFINE_V` never runs out on a closed
/// mesh). The standard view needs 192 and 544 (`RefineStats`, printed by the
/// host run).
pub const REFINE_V: usize = 192;
pub const REFINE_T: usize = 4 * REFINE_V;
/// The refinement memory of one configuration.
pub type RefineStore<V> = RefineBuffers<V, NV, REFINE_V, REFINE_T>;

/// Why a frame was not drawn (the firmware returns it in the upper word).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fail {
    /// The lighting's `f32` parameters were rejected.
    Lighting,
    /// `RenderError::Size` or `TooManyVertices`.
    Render,
    /// A buffer too small: elements needed.
    Buffer(usize),
    /// The mesh transform could not be built.
    Transform,
}

impl Fail {
    /// Status word: 1 lighting, 2 render, 3 | needed << 8 buffer, 5 transform.
    pub fn code(self) -> u32 {
        match self {
            Fail::Lighting => 1,
            Fail::Render => 2,
            Fail::Buffer(n) => 3 | (n as u32) << 8,
            Fail::Transform => 5,
        }
    }
}

impl<E> From<RenderError<E>> for Fail {
    fn from(e: RenderError<E>) -> Fail {
        match e {
            RenderError::BufferTooSmall { needed, .. } => Fail::Buffer(needed),
            _ => Fail::Render,
        }
    }
}

/// Caller-owned memory of one frame: the whole frame (`color`, `depth`:
/// `W·W`) or one band strip (`W·BAND_ROWS`).
pub struct Buffers<'a, V> {
    pub cache: &'a mut [CachedVertex<V>],
    pub bins: &'a mut [u16],
    pub carry: &'a mut [Carry],
    pub color: &'a mut [Rgb565],
    pub depth: &'a mut [u16],
    /// Silhouette refinement's memory (the `_refine` configurations).
    pub refine: Option<&'a mut RefineStore<V>>,
}

/// The per-frame path of a whole frame: vertex stage and bins, clear, draw,
/// flush to `display`.
#[inline(never)]
pub fn draw_full<K, D>(
    kernel: K,
    t: &MeshTransform<Orthographic>,
    b: Buffers<'_, K::Vertex>,
    display: &mut D,
) -> Result<(), Fail>
where
    K: Kernel<Color = Rgb565>,
    D: DrawTarget<Color = Rgb565>,
{
    let layout = Layout::full(W as u32, W as u32)?;
    let mut draw = MeshDraw::new(layout, SPHERE_MESH, t, kernel, MeshMemory {
            vertices: b.cache,
            bins: b.bins,
            carry: b.carry,
        }, DrawOptions::default())?;
    let mut frame = FullFrame::new(W as u32, W as u32, b.color, Some(b.depth))?;
    frame.render(Rgb565::BLACK, &mut [&mut draw])?;
    frame.flush(display).map_err(|_| Fail::Render)
}

/// The per-frame path in 8-row bands: vertex stage and bins, then per band
/// clear, draw, send to `display`.
#[inline(never)]
pub fn draw_bands<K, D>(
    kernel: K,
    t: &MeshTransform<Orthographic>,
    b: Buffers<'_, K::Vertex>,
    display: &mut D,
) -> Result<(), Fail>
where
    K: Kernel<Color = Rgb565>,
    D: DrawTarget<Color = Rgb565>,
{
    let layout = Layout::banded(W as u32, W as u32, BAND_ROWS as u32)?;
    let mut draw = MeshDraw::new(layout, SPHERE_MESH, t, kernel, MeshMemory {
            vertices: b.cache,
            bins: b.bins,
            carry: b.carry,
        }, DrawOptions::default())?;
    let mut bands = Bands::new(layout, b.color, Some(b.depth))?;
    let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut draw];
    bands
        .render(display, Rgb565::BLACK, items)
        .map_err(Fail::from)
}

/// [`draw_full`] with silhouette refinement (`DrawOptions::with_refine`,
/// threshold 0: the edges whose vertex normals straddle `N·V = 0`).
#[inline(never)]
pub fn draw_full_refine<K, D>(
    kernel: K,
    t: &MeshTransform<Orthographic>,
    b: Buffers<'_, K::Vertex>,
    display: &mut D,
) -> Result<(), Fail>
where
    K: Kernel<Color = Rgb565>,
    D: DrawTarget<Color = Rgb565>,
{
    let layout = Layout::full(W as u32, W as u32)?;
    let refine = b.refine.ok_or(Fail::Render)?;
    let mut draw = MeshDraw::new(layout, SPHERE_MESH, t, kernel, MeshMemory {
            vertices: b.cache,
            bins: b.bins,
            carry: b.carry,
        }, DrawOptions::default().with_refine(Refine {
            memory: refine.memory(),
            threshold: 0,
        }))?;
    let mut frame = FullFrame::new(W as u32, W as u32, b.color, Some(b.depth))?;
    frame.render(Rgb565::BLACK, &mut [&mut draw])?;
    frame.flush(display).map_err(|_| Fail::Render)
}

/// [`draw_bands`] with silhouette refinement.
#[inline(never)]
pub fn draw_bands_refine<K, D>(
    kernel: K,
    t: &MeshTransform<Orthographic>,
    b: Buffers<'_, K::Vertex>,
    display: &mut D,
) -> Result<(), Fail>
where
    K: Kernel<Color = Rgb565>,
    D: DrawTarget<Color = Rgb565>,
{
    let layout = Layout::banded(W as u32, W as u32, BAND_ROWS as u32)?;
    let refine = b.refine.ok_or(Fail::Render)?;
    let mut draw = MeshDraw::new(layout, SPHERE_MESH, t, kernel, MeshMemory {
            vertices: b.cache,
            bins: b.bins,
            carry: b.carry,
        }, DrawOptions::default().with_refine(Refine {
            memory: refine.memory(),
            threshold: 0,
        }))?;
    let mut bands = Bands::new(layout, b.color, Some(b.depth))?;
    let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut draw];
    bands
        .render(display, Rgb565::BLACK, items)
        .map_err(Fail::from)
}

/// Bands core 0 draws in the `_2core` frames (from the top); core 1 the rest.
pub const SPLIT: u32 = (BANDS / 2) as u32;

/// One core's half of the vertex stage in the `_2core` frames (`core` 0:
/// the first `NV / 2` vertices, 1: the others), into its half of `cache`.
#[inline(never)]
pub fn light_half<K: Kernel>(
    kernel: &K,
    t: &MeshTransform<Orthographic>,
    cache: &mut [CachedVertex<K::Vertex>],
    core: usize,
) {
    let half = (NV / 2).min(cache.len());
    let (a, b) = cache.split_at_mut(half);
    let (first, part) = if core == 0 { (0, a) } else { (half, b) };
    MeshDraw::<K>::light_vertices(&SPHERE_MESH, t, kernel, first, part);
}

/// The bins over the vertex cache both cores lit (core 0, `_2core`): the
/// prepared mesh both cores share, without resume records of its own.
#[inline(never)]
pub fn prepare_shared<'a, K: Kernel>(
    kernel: K,
    t: &MeshTransform<Orthographic>,
    cache: &'a mut [CachedVertex<K::Vertex>],
    bins: &'a mut [u16],
) -> Result<MeshDraw<'a, K>, Fail> {
    let memory = MeshMemory {
        vertices: cache,
        bins,
        carry: &mut [],
    };
    Ok(MeshDraw::new(BANDED, SPHERE_MESH, t, kernel, memory, DrawOptions { lit: true, ..DrawOptions::default() })?)
}

/// One core's bands of the shared mesh (`_2core`): its own records and
/// strips, bands `bands` cleared, drawn and sent to `display`.
#[inline(never)]
pub fn draw_core<K, D>(
    draw: &MeshDraw<'_, K>,
    carry: &mut [Carry],
    color: &mut [Rgb565],
    depth: &mut [u16],
    display: &mut D,
    bands: core::ops::Range<u32>,
) -> Result<(), Fail>
where
    K: Kernel<Color = Rgb565> + Clone,
    D: DrawTarget<Color = Rgb565>,
{
    let mut mine = draw.share(carry);
    let mut b = Bands::new(BANDED, color, Some(depth))?;
    b.render_bands(display, Rgb565::BLACK, &mut [&mut mine], bands)
        .map_err(Fail::from)
}

/// The layout of the banded frames (checked at compile time).
const BANDED: Layout = match Layout::banded(W as u32, W as u32, BAND_ROWS as u32) {
    Ok(l) => l,
    Err(_) => panic!("not a layout"),
};

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
    ($($(#[$attr:meta])* $name:ident: $v:ty, $l:ty, $m:ty = $lighting:expr, $mode:expr => $full:ident, $bands:ident;)*) => {
        /// Configuration names, in order.
        pub const CONFIGS: &[&str] = &[$($(#[$attr])* stringify!($name)),*];
        $(
            #[doc = concat!("The `", stringify!($name), "` configuration.")]
            $(#[$attr])*
            pub mod $name {
                use super::*;
                /// The vertex cache payload of this shader.
                pub type Vertex = $v;
                /// The lighting.
                pub type Light = $l;
                /// The shader (the `Kernel`).
                pub type Kern = Shader<'static, $m, Light, Linear, Rgb565>;
                /// Bytes of the lighting, the shader and the `MeshDraw` on this target
                /// (the firmware exports them for frame.py: they explain the stack).
                pub const TYPE_BYTES: [u32; 3] = [
                    core::mem::size_of::<Light>() as u32,
                    core::mem::size_of::<Kern>() as u32,
                    core::mem::size_of::<MeshDraw<'static, Kern>>() as u32,
                ];
                const _: () = assert!(core::mem::size_of::<<Kern as Kernel>::Vertex>() == core::mem::size_of::<Vertex>());
                /// The lighting (built once, like the transform, outside the frame).
                pub fn lighting() -> Result<Light, Fail> {
                    $lighting.map_err(|_| Fail::Lighting)
                }
                /// The shader over `lighting`.
                pub fn kern(lighting: &Light) -> Shader<'_, $m, Light, Linear, Rgb565> {
                    Shader::new($mode, lighting, Linear)
                }
                /// The shader, then [`draw_full`].
                pub fn full<D: DrawTarget<Color = Rgb565>>(
                    t: &MeshTransform<Orthographic>,
                    lighting: &Light,
                    b: Buffers<'_, Vertex>,
                    display: &mut D,
                ) -> Result<(), Fail> {
                    $full(Shader::new($mode, lighting, Linear), t, b, display)
                }
                /// The shader, then [`draw_bands`].
                pub fn band8<D: DrawTarget<Color = Rgb565>>(
                    t: &MeshTransform<Orthographic>,
                    lighting: &Light,
                    b: Buffers<'_, Vertex>,
                    display: &mut D,
                ) -> Result<(), Fail> {
                    $bands(Shader::new($mode, lighting, Linear), t, b, display)
                }
            }
        )*
        /// Runs configuration `name` (`band8`: in bands) on the given buffers
        /// (the host reference; the firmware calls the modules directly).
        pub fn run<D: DrawTarget<Color = Rgb565>>(
            name: &str,
            band8: bool,
            t: &MeshTransform<Orthographic>,
            bins: &mut [u16],
            carry: &mut [Carry],
            color: &mut [Rgb565],
            depth: &mut [u16],
            display: &mut D,
        ) -> Option<Result<(), Fail>> {
            $(
                $(#[$attr])*
                if name == stringify!($name) {
                    let mut c = [CachedVertex::<$v>::default(); NV];
                    let mut r = RefineStore::<$v>::new();
                    let b = Buffers { cache: &mut c, bins, carry, color, depth, refine: Some(&mut r) };
                    let l = match $name::lighting() {
                        Ok(l) => l,
                        Err(e) => return Some(Err(e)),
                    };
                    return Some(if band8 {
                        $name::band8(t, &l, b, display)
                    } else {
                        $name::full(t, &l, b, display)
                    });
                }
            )*
            None
        }

        /// Runs configuration `name` as the `_2core` frame does, one part
        /// after the other (the host reference: the frame must be the
        /// banded frame's).
        pub fn run_2core<D: DrawTarget<Color = Rgb565>>(
            name: &str,
            t: &MeshTransform<Orthographic>,
            display: &mut D,
        ) -> Option<Result<(), Fail>> {
            $(
                $(#[$attr])*
                if name == stringify!($name) {
                    let mut c = [CachedVertex::<$v>::default(); NV];
                    let mut bins = [0u16; BINS_BAND];
                    let mut carry = [[Carry::ZERO; CARRY_BAND]; 2];
                    let mut color = [[Rgb565::BLACK; W * BAND_ROWS]; 2];
                    let mut depth = [[0u16; W * BAND_ROWS]; 2];
                    let l = match $name::lighting() {
                        Ok(l) => l,
                        Err(e) => return Some(Err(e)),
                    };
                    let k = $name::kern(&l);
                    light_half(&k, t, &mut c, 0);
                    light_half(&k, t, &mut c, 1);
                    let draw = match prepare_shared(k, t, &mut c, &mut bins) {
                        Ok(d) => d,
                        Err(e) => return Some(Err(e)),
                    };
                    let [c0, c1] = &mut carry;
                    let [s0, s1] = &mut color;
                    let [d0, d1] = &mut depth;
                    return Some(
                        draw_core(&draw, c0, s0, d0, display, 0..SPLIT)
                            .and_then(|()| draw_core(&draw, c1, s1, d1, display, SPLIT..BANDS as u32)),
                    );
                }
            )*
            None
        }
    };
}

type Dir = DirectionalLight<Q14>;
#[cfg(any(target_arch = "riscv32", not(target_os = "none")))]
type DirF = DirectionalLight<f32>;

configs! {
    lambert_gouraud: [u16; 3], Viewed<Lighting<Q14, Dir, Lambert>>, GouraudShading
        = standard::lambert::<Q14>(), GouraudShading => draw_full, draw_bands;
    blinn_gouraud: [u16; 3], Viewed<Lighting<Q14, Dir, BlinnPhong>>, GouraudShading
        = standard::blinn::<Q14>(), GouraudShading => draw_full, draw_bands;
    blinn_phong: [i16; 3], Viewed<Lighting<Q14, Dir, BlinnPhong>>, PhongShading
        = standard::blinn::<Q14>(), PhongShading => draw_full, draw_bands;
    blinn_phong_inc: [i16; 3], Viewed<Lighting<Q14, [Dir; 1], BlinnPhong>>, IncrementalPhongShading
        = inc_lighting(), IncrementalPhongShading => draw_full, draw_bands;
    flat: [i16; 3], Viewed<Lighting<Q14, Dir, Lambert>>, FlatShading
        = standard::lambert::<Q14>(), FlatShading => draw_full, draw_bands;
    lambert_gouraud_refine: [u16; 3], Viewed<Lighting<Q14, Dir, Lambert>>, GouraudShading
        = standard::lambert::<Q14>(), GouraudShading => draw_full_refine, draw_bands_refine;
    // the f32 tier: the RISC-V image and the host reference only (the Arm images stay as they were)
    #[cfg(any(target_arch = "riscv32", not(target_os = "none")))]
    lambert_gouraud_f32: [u16; 3], Viewed<Lighting<f32, DirF, Lambert>>, GouraudShading
        = standard::lambert::<f32>(), GouraudShading => draw_full, draw_bands;
    #[cfg(any(target_arch = "riscv32", not(target_os = "none")))]
    blinn_gouraud_f32: [u16; 3], Viewed<Lighting<f32, DirF, BlinnPhong>>, GouraudShading
        = standard::blinn::<f32>(), GouraudShading => draw_full, draw_bands;
    #[cfg(any(target_arch = "riscv32", not(target_os = "none")))]
    blinn_phong_f32: [i16; 3], Viewed<Lighting<f32, DirF, BlinnPhong>>, PhongShading
        = standard::blinn::<f32>(), PhongShading => draw_full, draw_bands;
    #[cfg(any(target_arch = "riscv32", not(target_os = "none")))]
    flat_f32: [i16; 3], Viewed<Lighting<f32, DirF, Lambert>>, FlatShading
        = standard::lambert::<f32>(), FlatShading => draw_full, draw_bands;
}
