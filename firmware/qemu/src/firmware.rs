//! The firmware image: one configuration (cargo feature), the board's
//! constants from `build.rs` (`board.rs`), semihosting output and exit.

use core::arch::{asm, global_asm};
use core::fmt::Write;
use core::mem::MaybeUninit;
use core::ptr::{addr_of, addr_of_mut};

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;
use cortex_m_rt::{entry, exception};
use cortex_m_semihosting::{debug, hio};
use embedded_graphics_core::geometry::Size;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::camera::{MeshTransform, Orthographic};
use fixshade::framebuffer::Checksum;
use fixshade::render::{CachedVertex, Carry};
use fixshade_qemu::{bins_for, Buffers, Fail, W};

mod board {
    include!(concat!(env!("OUT_DIR"), "/board.rs"));
}
use board::{BOARD, CORE, ROWS, STACK};

#[cfg(feature = "blinn_gouraud")]
use fixshade_qemu::blinn_gouraud as config;
#[cfg(feature = "blinn_phong")]
use fixshade_qemu::blinn_phong as config;
#[cfg(feature = "blinn_phong_inc")]
use fixshade_qemu::blinn_phong_inc as config;
#[cfg(feature = "flat")]
use fixshade_qemu::flat as config;
#[cfg(feature = "imported")]
use fixshade_qemu::imported as config;
#[cfg(feature = "imported_textured")]
use fixshade_qemu::imported_textured as config;
#[cfg(feature = "lambert_gouraud")]
use fixshade_qemu::lambert_gouraud as config;
#[cfg(not(any(
    feature = "lambert_gouraud",
    feature = "blinn_gouraud",
    feature = "blinn_phong",
    feature = "blinn_phong_inc",
    feature = "flat",
    feature = "imported",
    feature = "imported_textured"
)))]
compile_error!("choose one configuration: --features lambert_gouraud|blinn_gouraud|blinn_phong|blinn_phong_inc|flat|imported|imported_textured");

/// Frames rendered (all must give the same checksum and count).
const FRAMES: usize = 2;

// The frame's memory, in `.bss`, built at compile time by the crate's `const`
// zero values (no `unsafe` initialiser), named for run.py.
#[no_mangle]
static mut STRIP: [Rgb565; W * ROWS] = [Rgb565::BLACK; W * ROWS];
#[no_mangle]
static mut DEPTH: [u16; W * ROWS] = [0; W * ROWS];
#[no_mangle]
static mut CACHE: [CachedVertex<config::Vertex>; config::NV] = [CachedVertex::ZERO; config::NV];
#[no_mangle]
static mut BINS: [u16; bins_for(config::NT, ROWS)] = [0; bins_for(config::NT, ROWS)];
#[no_mangle]
static mut CARRY_RECORDS: [Carry; config::CARRY] = [Carry::ZERO; config::CARRY];

extern "C" {
    /// The stack's lowest address (`memory.x`: the bottom of RAM).
    static _stack_end: u32;
    /// The stack's top (its initial SP).
    static _stack_start: u32;
}

/// cortex-m-rt's `paint-stack` fills the stack with this before `main`.
const PAINT: u32 = 0xcccc_cccc;

/// `(peak bytes used below the top, bytes never touched above the bottom)`.
fn stack_use() -> (usize, usize) {
    let bottom = addr_of!(_stack_end) as usize;
    let top = addr_of!(_stack_start) as usize;
    let mut p = bottom;
    // SAFETY: [bottom, top) is the stack region; words below the current SP
    // are plain memory that nothing else uses.
    while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    (top - p, p - bottom)
}

/// The current stack pointer.
#[inline(always)]
fn sp() -> usize {
    let sp: usize;
    // SAFETY: reads a register.
    unsafe { asm!("mov {}, sp", out(reg) sp, options(nomem, nostack, preserves_flags)) };
    sp
}

/// Paints the stack again from its bottom up to just below this function's
/// own frame (no interrupt is enabled that could push below the SP).
#[inline(never)]
fn repaint() {
    let limit = sp() - 16;
    let mut p = addr_of!(_stack_end) as usize;
    while p < limit {
        // SAFETY: unused stack below the current SP.
        unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
        p += 4;
    }
}

/// SysTick as a 24-bit down-counter of processor clock ticks.
struct Timer(SYST);

impl Timer {
    fn new(mut syst: SYST) -> Timer {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(0x00ff_ffff);
        syst.clear_current();
        syst.enable_counter();
        Timer(syst)
    }

    /// Ticks `f` takes (none of the runs here comes near the 2^24 wrap:
    /// checked).
    fn ticks<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
        let _ = self.0.has_wrapped(); // clears COUNTFLAG
        let a = SYST::get_current();
        let r = f();
        let b = SYST::get_current();
        if self.0.has_wrapped() {
            fail(format_args!("SysTick wrapped during one measurement"));
        }
        (r, a.wrapping_sub(b) & 0x00ff_ffff)
    }
}

/// Exactly `2 · n` instructions (`subs`, `bne` per iteration).
#[inline(never)]
fn spin(n: u32) {
    // SAFETY: register-only loop.
    unsafe {
        asm!("2:", "subs r0, #1", "bne 2b", inout("r0") n => _, options(nomem, nostack));
    }
}

/// A writer to the semihosting console.
fn out() -> hio::HostStream {
    hio::hstdout().unwrap_or_else(|_| exit(false))
}

fn exit(ok: bool) -> ! {
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    // not reached under QEMU; on a debugger-less board: stop here
    cortex_m::asm::udf()
}

/// Prints `FAIL <board> <config>: <why>` and exits with status 1.
#[cold]
#[inline(never)]
fn fail(why: core::fmt::Arguments<'_>) -> ! {
    let _ = writeln!(out(), "FAIL {BOARD} {}: {why}", config::NAME);
    exit(false)
}

/// What one image measured.
struct Report {
    checksum: u32,
    instructions: u64,
    ticks: u32,
    setup_instructions: u64,
    calib_ticks: u32,
    stack_peak: usize,
    stack_frame: usize,
    stack_setup: usize,
    carry_needed: usize,
}

/// Prints the `RESULT {json}` line (not inlined: its formatting state is on
/// the stack only while it prints, after the frames).
#[inline(never)]
fn report(r: &Report) {
    let _ = writeln!(
        out(),
        "RESULT {{\"board\": \"{BOARD}\", \"core\": \"{CORE}\", \"config\": \"{}\", \"rows\": {ROWS}, \
         \"checksum\": \"{:#010x}\", \"pixels\": {}, \"frames\": {FRAMES}, \
         \"instructions\": {}, \"ticks\": {}, \"setup_instructions\": {}, \
         \"calib_instructions\": {}, \"calib_ticks\": {}, \"stack_peak\": {}, \
         \"stack_frame\": {}, \"stack_setup\": {}, \"stack_size\": {STACK}, \"carry_needed\": {}}}",
        config::NAME,
        r.checksum,
        W * W,
        r.instructions,
        r.ticks,
        r.setup_instructions,
        2 * CALIB,
        r.calib_ticks,
        r.stack_peak,
        r.stack_frame,
        r.stack_setup,
        r.carry_needed,
    );
}

/// The transform and the lighting, built once (kept in a static: `main`'s
/// frame stays small, so the image's stack is mostly the renderer's).
static mut SCENE: MaybeUninit<(MeshTransform<Orthographic>, config::Light)> = MaybeUninit::uninit();

/// Builds [`SCENE`] (once).
#[inline(never)]
fn init_scene() -> Result<(&'static MeshTransform<Orthographic>, &'static config::Light), Fail> {
    let scene = config::setup()?;
    // SAFETY: called once, before anything reads SCENE.
    let (t, l) = unsafe { (*addr_of_mut!(SCENE)).write(scene) };
    Ok((t, l))
}

/// Instructions of the calibration loop: `2 · CALIB`.
const CALIB: u32 = 1 << 20;

#[entry]
fn main() -> ! {
    let cp = cortex_m::Peripherals::take().unwrap_or_else(|| fail(format_args!("peripherals")));
    let mut timer = Timer::new(cp.SYST);
    // instructions per tick, from a loop of known length
    let ((), calib_ticks) = timer.ticks(|| spin(CALIB));
    let instr = |ticks: u32| {
        (u64::from(ticks) * u64::from(2 * CALIB)).div_ceil(u64::from(calib_ticks.max(1)))
    };

    // once: the mesh transform and the lighting (f32 parameters)
    let (scene, setup_ticks) = timer.ticks(init_scene);
    let (transform, lighting) = scene.unwrap_or_else(|e| fail(format_args!("scene set-up: {e:?}")));

    // the stack used so far (start-up, set-up), then the frames' own
    let (setup_peak, _) = stack_use();
    repaint();
    let mut frame_sp = 0;
    let mut sums = [0u32; FRAMES];
    let mut ticks = [0u32; FRAMES];
    let mut carry_needed = 0;
    for k in 0..FRAMES {
        let mut display = Checksum::<Rgb565>::new(Size::new(W as u32, W as u32));
        // SAFETY: the statics are used by this loop only, one frame at a time.
        let b = unsafe {
            Buffers {
                cache: &mut *addr_of_mut!(CACHE),
                bins: &mut *addr_of_mut!(BINS),
                carry: &mut *addr_of_mut!(CARRY_RECORDS),
                strip: &mut *addr_of_mut!(STRIP),
                depth: &mut *addr_of_mut!(DEPTH),
            }
        };
        let (r, t) = timer.ticks(|| {
            frame_sp = sp();
            config::frame(transform, lighting, ROWS, b, &mut display)
        });
        match r {
            Ok(n) => carry_needed = n,
            Err(e) => fail(format_args!("frame {k}: {e:?}")),
        }
        if display.pixels() as usize != W * W {
            fail(format_args!(
                "frame {k}: {} pixels sent, not {}",
                display.pixels(),
                W * W
            ));
        }
        sums[k] = display.value();
        ticks[k] = t;
    }
    // the peak of everything so far (start-up, set-up, frames), and the
    // frame's own: below the SP at the call of `config::frame`
    let (frames_peak, headroom) = stack_use();
    let stack_peak = setup_peak.max(frames_peak);
    let stack_frame = frames_peak - (addr_of!(_stack_start) as usize - frame_sp);
    if headroom == 0 {
        fail(format_args!("the stack reached its bottom ({STACK} bytes)"));
    }
    if sums.iter().any(|s| *s != sums[0]) || ticks.iter().any(|t| t.abs_diff(ticks[0]) > 1) {
        fail(format_args!(
            "frames differ: checksums {sums:x?}, ticks {ticks:?}"
        ));
    }
    report(&Report {
        checksum: sums[0],
        instructions: instr(ticks[0]),
        ticks: ticks[0],
        setup_instructions: instr(setup_ticks),
        calib_ticks,
        stack_peak,
        stack_frame,
        stack_setup: setup_peak,
        carry_needed,
    });
    // printing may go deeper than the frame: check again before success
    if stack_use().1 == 0 {
        fail(format_args!("the stack reached its bottom while printing"));
    }
    exit(true)
}

// HardFault: entered with the SP wherever the fault left it, possibly below
// the stack (the overflow this layout turns into a fault). Move the SP back to
// the top of the stack first, then report and exit.
global_asm!(
    ".section .text.HardFault, \"ax\"",
    ".global HardFault",
    ".type HardFault,%function",
    ".thumb_func",
    "HardFault:",
    "mrs r0, MSP",
    "ldr r1, =_stack_start",
    "mov sp, r1",
    "bl fixshade_hard_fault",
    ".size HardFault, . - HardFault",
);

/// Reports a HardFault (`sp`: the SP it was taken with) and exits with 1.
#[no_mangle]
extern "C" fn fixshade_hard_fault(sp: u32) -> ! {
    let bottom = addr_of!(_stack_end) as u32;
    if sp < bottom + 32 {
        fail(format_args!(
            "HardFault: stack overflow (SP {sp:#010x}, the stack's bottom is {bottom:#010x}; \
             {STACK} bytes reserved)"
        ));
    }
    fail(format_args!("HardFault (SP {sp:#010x})"))
}

#[exception]
unsafe fn DefaultHandler(irqn: i16) {
    fail(format_args!("unexpected exception {irqn}"))
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    fail(format_args!("panic: {info}"))
}
