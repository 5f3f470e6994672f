//! The frame image counted by `measure/frame.py`, and its host reference.
//!
//! * `thumbv6m-none-eabi`, `thumbv7em-none-eabihf`, `riscv32imc-unknown-none-elf`
//!   (`target_os = "none"`): a firmware image with one `extern "C"` entry per
//!   configuration (the `f32` ones on RISC-V only) and frame kind,
//!   `frame_<config>` (whole frame) and `frame_<config>_band8`, each
//!   rendering one complete frame of the standard scene into a
//!   `fixshade::framebuffer::Checksum<Rgb565>` and returning
//!   `status << 32 | checksum` (status 0: drawn, all 57 600 pixels sent).
//!   `init()` converts the camera (`FixedCamera::new(&standard::camera()?)`, `f32`) and
//!   builds every configuration's lighting once into statics; each frame builds
//!   its mesh transform from the camera in integers (`standard::fixed_transform`); frame.py calls it first and counts
//!   it separately. Buffers are statics (`.bss`), named for frame.py:
//!   `FRAME_COLOR`, `FRAME_DEPTH` (whole frame), `STRIP_COLOR`,
//!   `STRIP_DEPTH` (8-row bands), and per configuration `CACHE_<config>`,
//!   `BINS_FULL_<config>`, `BINS_BAND_<config>`, `CARRY_BAND_<config>`;
//!   `TYPES_<config>` holds the bytes of the lighting, the shader and the
//!   `MeshDraw` on the target.
//! * the host: `cargo run --release` prints, as JSON, every configuration's
//!   checksum, lit (non-black) pixels, and the bins and resume records the
//!   frame needs, from the same library functions.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;
    use core::mem::{zeroed, MaybeUninit};
    use core::ptr::{addr_of, addr_of_mut};

    #[cfg(target_arch = "arm")]
    use cortex_m_rt::entry;
    use embedded_graphics_core::geometry::Size;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use fixshade::camera::{FixedCamera, MeshTransform, Orthographic};
    use fixshade::framebuffer::Checksum;
    use fixshade::render::MeshDraw;
    use fixshade::render::{CachedVertex, Carry};
    use fixshade_frame::{
        Buffers, Fail, BANDS, BAND_ROWS, BINS_BAND, BINS_FULL, CARRY_BAND, NV, SPLIT, W,
    };
    #[cfg(target_arch = "riscv32")]
    use riscv_rt::entry;

    // All-zero is a valid value of every buffer element (integers, Rgb565 =
    // u16, CachedVertex and Carry = integers and integer arrays): `.bss`.
    const _: () = assert!(BANDS * BAND_ROWS >= W);
    static mut CAMERA: MaybeUninit<FixedCamera<Orthographic>> = MaybeUninit::uninit();
    #[no_mangle]
    static mut FRAME_COLOR: [Rgb565; W * W] = unsafe { zeroed() };
    #[no_mangle]
    static mut FRAME_DEPTH: [u16; W * W] = [0; W * W];
    #[no_mangle]
    static mut STRIP_COLOR: [Rgb565; W * BAND_ROWS] = unsafe { zeroed() };
    #[no_mangle]
    static mut STRIP_DEPTH: [u16; W * BAND_ROWS] = [0; W * BAND_ROWS];
    // the second core's strips in the `_2core` frames
    #[no_mangle]
    static mut STRIP2_COLOR: [Rgb565; W * BAND_ROWS] = unsafe { zeroed() };
    #[no_mangle]
    static mut STRIP2_DEPTH: [u16; W * BAND_ROWS] = [0; W * BAND_ROWS];
    /// The `_2core` frame's transform (built by core 0's vertex half) and
    /// display (written by both cores' bands, in order).
    static mut TRANSFORM2: MaybeUninit<MeshTransform<Orthographic>> = MaybeUninit::uninit();
    static mut DISPLAY2: MaybeUninit<Checksum<Rgb565>> = MaybeUninit::uninit();

    /// Converts the camera (once, in `f32`, before any frame). 0: done.
    #[no_mangle]
    pub unsafe extern "C" fn init() -> u32 {
        match fixshade::standard::camera().and_then(|c| FixedCamera::new(&c)) {
            Ok(c) => (*addr_of_mut!(CAMERA)).write(c),
            Err(_) => return 1,
        };
        init_lightings()
    }

    /// The frame's mesh transform, built in integers from the camera `init`
    /// converted (part of every counted frame, as in an animation).
    fn transform() -> Option<MeshTransform<Orthographic>> {
        // SAFETY: `init` wrote the camera before any frame runs.
        let c = unsafe { &*black_box(addr_of!(CAMERA)).cast::<FixedCamera<Orthographic>>() };
        fixshade::standard::fixed_transform(c).ok()
    }

    fn checksum() -> Checksum<Rgb565> {
        Checksum::new(Size::new(W as u32, W as u32))
    }

    /// `status << 32 | checksum`; status 4: not every pixel was sent.
    fn finish(r: Result<(), Fail>, d: &Checksum<Rgb565>) -> u64 {
        let status = match r {
            Ok(()) if d.pixels() == (W * W) as u32 => 0,
            Ok(()) => 4,
            Err(e) => e.code(),
        };
        (u64::from(status) << 32) | u64::from(d.value())
    }

    macro_rules! entries {
        ($($name:ident),*) => {
            $(
                mod $name {
                    use super::*;
                    #[export_name = concat!("CACHE_", stringify!($name))]
                    static mut CACHE: [CachedVertex<fixshade_frame::$name::Vertex>; NV] =
                        unsafe { zeroed() };
                    #[export_name = concat!("BINS_FULL_", stringify!($name))]
                    static mut BINS1: [u16; BINS_FULL] = [0; BINS_FULL];
                    #[export_name = concat!("BINS_BAND_", stringify!($name))]
                    static mut BINS8: [u16; BINS_BAND] = [0; BINS_BAND];
                    #[export_name = concat!("TYPES_", stringify!($name))]
                    #[used]
                    static TYPES: [u32; 3] = fixshade_frame::$name::TYPE_BYTES;
                    #[export_name = concat!("CARRY_BAND_", stringify!($name))]
                    static mut CARRY8: [Carry; CARRY_BAND] = unsafe { zeroed() };
                    // passed to every configuration, read by the `_refine` ones only
                    #[export_name = concat!("REFINE_", stringify!($name))]
                    static mut REFINE: fixshade_frame::RefineStore<fixshade_frame::$name::Vertex> =
                        unsafe { zeroed() };
                    static mut LIGHT: MaybeUninit<fixshade_frame::$name::Light> = MaybeUninit::uninit();

                    /// Builds the lighting (from `init`). 0: done.
                    pub unsafe fn init() -> u32 {
                        match fixshade_frame::$name::lighting() {
                            Ok(l) => {
                                (*addr_of_mut!(LIGHT)).write(l);
                                0
                            }
                            Err(_) => 2,
                        }
                    }

                    /// The lighting `init` built.
                    unsafe fn lighting<'a>() -> &'a fixshade_frame::$name::Light {
                        &*black_box(addr_of!(LIGHT)).cast::<fixshade_frame::$name::Light>()
                    }

                    /// One whole frame (FullFrame + flush).
                    #[export_name = concat!("frame_", stringify!($name))]
                    pub unsafe extern "C" fn full() -> u64 {
                        let mut d = checksum();
                        let b = Buffers {
                            cache: &mut *addr_of_mut!(CACHE),
                            bins: &mut *addr_of_mut!(BINS1),
                            carry: &mut [],
                            color: &mut *addr_of_mut!(FRAME_COLOR),
                            depth: &mut *addr_of_mut!(FRAME_DEPTH),
                            refine: Some(&mut *addr_of_mut!(REFINE)),
                        };
                        let r = match transform() {
                            Some(t) => fixshade_frame::$name::full(&t, lighting(), b, &mut d),
                            None => Err(Fail::Transform),
                        };
                        finish(r, &d)
                    }

                    #[export_name = concat!("CARRY2_", stringify!($name))]
                    static mut CARRY2: [Carry; CARRY_BAND] = unsafe { zeroed() };
                    static mut SHARED: MaybeUninit<MeshDraw<'static, fixshade_frame::$name::Kern>> =
                        MaybeUninit::uninit();

                    /// The `_2core` frame, core 0's half of the vertex stage (it
                    /// builds the frame's transform first). Status only.
                    #[export_name = concat!("frame_", stringify!($name), "_2core_v0")]
                    pub unsafe extern "C" fn v0() -> u64 {
                        let Some(t) = transform() else {
                            return u64::from(Fail::Transform.code()) << 32;
                        };
                        let t = (*addr_of_mut!(TRANSFORM2)).write(t);
                        let k = fixshade_frame::$name::kern(lighting());
                        fixshade_frame::light_half(&k, t, &mut *addr_of_mut!(CACHE), 0);
                        0
                    }

                    /// Core 1's half of the vertex stage.
                    #[export_name = concat!("frame_", stringify!($name), "_2core_v1")]
                    pub unsafe extern "C" fn v1() -> u64 {
                        let t = (*addr_of!(TRANSFORM2)).assume_init_ref();
                        let k = fixshade_frame::$name::kern(lighting());
                        fixshade_frame::light_half(&k, t, &mut *addr_of_mut!(CACHE), 1);
                        0
                    }

                    /// Core 0: the bins over the lit cache, the shared mesh.
                    #[export_name = concat!("frame_", stringify!($name), "_2core_bins")]
                    pub unsafe extern "C" fn bins() -> u64 {
                        let t = (*addr_of!(TRANSFORM2)).assume_init_ref();
                        let k = fixshade_frame::$name::kern(lighting());
                        match fixshade_frame::prepare_shared(
                            k,
                            t,
                            &mut *addr_of_mut!(CACHE),
                            &mut *addr_of_mut!(BINS8),
                        ) {
                            Ok(d) => {
                                (*addr_of_mut!(SHARED)).write(d);
                                0
                            }
                            Err(e) => u64::from(e.code()) << 32,
                        }
                    }

                    /// Core 0's bands (the upper half), into a new display.
                    #[export_name = concat!("frame_", stringify!($name), "_2core_c0")]
                    pub unsafe extern "C" fn c0() -> u64 {
                        let d = (*addr_of_mut!(DISPLAY2)).write(checksum());
                        let r = fixshade_frame::draw_core(
                            (*addr_of!(SHARED)).assume_init_ref(),
                            &mut *addr_of_mut!(CARRY8),
                            &mut *addr_of_mut!(STRIP_COLOR),
                            &mut *addr_of_mut!(STRIP_DEPTH),
                            d,
                            0..SPLIT,
                        );
                        match r {
                            Ok(()) => 0,
                            Err(e) => u64::from(e.code()) << 32,
                        }
                    }

                    /// Core 1's bands (the lower half), with its own records and
                    /// strips, into the same display: the frame's checksum.
                    #[export_name = concat!("frame_", stringify!($name), "_2core_c1")]
                    pub unsafe extern "C" fn c1() -> u64 {
                        let d = (*addr_of_mut!(DISPLAY2)).assume_init_mut();
                        let r = fixshade_frame::draw_core(
                            (*addr_of!(SHARED)).assume_init_ref(),
                            &mut *addr_of_mut!(CARRY2),
                            &mut *addr_of_mut!(STRIP2_COLOR),
                            &mut *addr_of_mut!(STRIP2_DEPTH),
                            d,
                            SPLIT..BANDS as u32,
                        );
                        finish(r, d)
                    }

                    /// One whole frame in 8-row bands.
                    #[export_name = concat!("frame_", stringify!($name), "_band8")]
                    pub unsafe extern "C" fn band8() -> u64 {
                        let mut d = checksum();
                        let b = Buffers {
                            cache: &mut *addr_of_mut!(CACHE),
                            bins: &mut *addr_of_mut!(BINS8),
                            carry: &mut *addr_of_mut!(CARRY8),
                            color: &mut *addr_of_mut!(STRIP_COLOR),
                            depth: &mut *addr_of_mut!(STRIP_DEPTH),
                            refine: Some(&mut *addr_of_mut!(REFINE)),
                        };
                        let r = match transform() {
                            Some(t) => fixshade_frame::$name::band8(&t, lighting(), b, &mut d),
                            None => Err(Fail::Transform),
                        };
                        finish(r, &d)
                    }
                }
            )*

            /// Builds every configuration's lighting.
            unsafe fn init_lightings() -> u32 {
                $(
                    let r = $name::init();
                    if r != 0 {
                        return r;
                    }
                )*
                0
            }

            /// Function pointers that keep every entry in the LTO image.
            pub struct Keep<T>(pub T);
            // SAFETY: read-only tables of code addresses.
            unsafe impl<T> Sync for Keep<T> {}
            #[used]
            pub static KEEP: Keep<[*const (); 1 + 7 * [$(stringify!($name)),*].len()]> = Keep([
                init as *const (),
                $($name::full as *const (), $name::band8 as *const (),
                  $name::v0 as *const (), $name::v1 as *const (), $name::bins as *const (),
                  $name::c0 as *const (), $name::c1 as *const (),)*
            ]);
        };
    }

    #[cfg(not(target_arch = "riscv32"))]
    entries!(
        lambert_gouraud,
        blinn_gouraud,
        blinn_phong,
        blinn_phong_inc,
        flat,
        lambert_gouraud_refine
    );
    // RISC-V (no FPU): also the `f32` tier's frames, to measure what fixed point buys
    #[cfg(target_arch = "riscv32")]
    entries!(
        lambert_gouraud,
        blinn_gouraud,
        blinn_phong,
        blinn_phong_inc,
        flat,
        lambert_gouraud_refine,
        lambert_gouraud_f32,
        blinn_gouraud_f32,
        blinn_phong_f32,
        flat_f32
    );

    #[entry]
    fn main() -> ! {
        // `#[used]` alone does not survive the linker's --gc-sections: reference it.
        black_box(&KEEP);
        loop {
            core::hint::spin_loop();
        }
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        loop {
            core::hint::spin_loop();
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
    use embedded_graphics_core::prelude::*;
    use fixshade::framebuffer::Checksum;
    use fixshade::render::Carry;
    use fixshade_frame::*;

    /// Checksums the stream like the firmware and counts the non-black pixels.
    struct Recorder(Checksum<Rgb565>, usize);
    impl OriginDimensions for Recorder {
        fn size(&self) -> Size {
            Size::new(W as u32, W as u32)
        }
    }
    impl DrawTarget for Recorder {
        type Color = Rgb565;
        type Error = core::convert::Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
            &mut self,
            _: I,
        ) -> Result<(), Self::Error> {
            unreachable!("frames are sent with fill_contiguous")
        }
        fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
            &mut self,
            area: &embedded_graphics_core::primitives::Rectangle,
            colors: I,
        ) -> Result<(), Self::Error> {
            let c: Vec<Rgb565> = colors.into_iter().collect();
            self.1 += c.iter().filter(|p| **p != Rgb565::BLACK).count();
            self.0.fill_contiguous(area, c)
        }
    }

    let camera = fixshade::standard::camera().expect("camera");
    let camera = fixshade::camera::FixedCamera::new(&camera).expect("fixed camera");
    let t = fixshade::standard::fixed_transform(&camera).expect("standard transform");
    let mut out = Vec::new();
    for name in CONFIGS {
        for band8 in [false, true] {
            let (bins_len, carry_len, px) = if band8 {
                (BINS_BAND, CARRY_BAND, W * BAND_ROWS)
            } else {
                (BINS_FULL, 0, W * W)
            };
            let go = |bins: usize,
                      carry: usize,
                      d: &mut dyn FnMut(
                &mut [u16],
                &mut [Carry],
                &mut [Rgb565],
                &mut [u16],
            ) -> Result<(), Fail>| {
                let mut b = vec![0u16; bins];
                let mut c = vec![Carry::default(); carry];
                let mut color = vec![Rgb565::BLACK; px];
                let mut depth = vec![0u16; px];
                d(&mut b, &mut c, &mut color, &mut depth)
            };
            // the checksum through exactly the firmware's display type
            let mut sum = Checksum::<Rgb565>::new(Size::new(W as u32, W as u32));
            go(bins_len, carry_len, &mut |b, c, col, dep| {
                run(name, band8, &t, b, c, col, dep, &mut sum).unwrap()
            })
            .expect("frame");
            let mut rec = Recorder(Checksum::new(Size::new(W as u32, W as u32)), 0);
            go(bins_len, carry_len, &mut |b, c, col, dep| {
                run(name, band8, &t, b, c, col, dep, &mut rec).unwrap()
            })
            .expect("frame");
            assert_eq!(
                rec.0.value(),
                sum.value(),
                "{name}: recorder and checksum disagree"
            );
            assert_eq!(sum.pixels() as usize, W * W, "{name}: pixels sent");
            // the exact needs, from the errors of too small buffers
            let need = |bins: usize, carry: usize| {
                let mut s = Checksum::<Rgb565>::new(Size::new(W as u32, W as u32));
                match go(bins, carry, &mut |b, c, col, dep| {
                    run(name, band8, &t, b, c, col, dep, &mut s).unwrap()
                }) {
                    Err(Fail::Buffer(n)) => n,
                    Ok(()) => 0,
                    Err(e) => panic!("{name}: {e:?}"),
                }
            };
            let bands = if band8 { BANDS } else { 1 };
            let bins_needed = need(2 * (bands + 1), carry_len);
            let carry_needed = need(bins_len, 0);
            // the `_2core` frame (vertex halves, bins, two cores' bands) is this one
            let two = if band8 && !name.ends_with("_refine") {
                let mut s2 = Checksum::<Rgb565>::new(Size::new(W as u32, W as u32));
                run_2core(name, &t, &mut s2).unwrap().expect("2core frame");
                assert_eq!(
                    (s2.value(), s2.pixels()),
                    (sum.value(), sum.pixels()),
                    "{name}: the two-core frame differs from the banded frame"
                );
                format!(", \"two_core\": \"{:#010x}\"", s2.value())
            } else {
                String::new()
            };
            let key = if band8 {
                format!("{name}_band8")
            } else {
                name.to_string()
            };
            out.push(format!(
                "  \"{key}\": {{\"checksum\": \"{:#010x}\", \"lit_px\": {}, \"pixels\": {}, \
                 \"bins_needed\": {bins_needed}, \"carry_needed\": {carry_needed}{two}}}",
                sum.value(),
                rec.1,
                sum.pixels()
            ));
        }
    }
    println!("{{\n{}\n}}", out.join(",\n"));
}
