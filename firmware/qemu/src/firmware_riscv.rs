//! The firmware image on QEMU's RISC-V `virt` board (`riscv32imc-unknown-none-elf`,
//! `qemu-system-riscv32 -M virt -bios none`): one configuration (cargo feature),
//! the board's constants from `build.rs` (`board.rs`), riscv-rt's start-up.
//!
//! * **Output and exit**: the board's NS16550A UART at 0x1000_0000 (QEMU's
//!   `-nographic` puts it on stdout) and its SiFive test device at 0x10_0000
//!   (0x5555: QEMU exits with status 0; `code << 16 | 0x3333`: with `code`). No
//!   semihosting: a real RV32 board has a UART, not a debugger console.
//! * **Instructions**: the `minstret` CSR. Under `qemu -icount shift=0` QEMU's
//!   RISC-V target returns its instruction counter for `minstret` (in icount mode
//!   a CSR read of a counter ends the translation block, so the value is exact at
//!   that instruction), so the difference around a frame is its instruction count.
//!   The image checks it twice: a loop of 2·n known instructions (`c.addi`,
//!   `c.bnez`) must read exactly 2·n more than a loop of half the length, and the
//!   CLINT's `mtime` (10 MHz; one tick = 100 ns = 100 instructions at shift=0)
//!   must agree to ±100 instructions around every frame (run.py checks both).
//! * **Stack**: painted at the start of `main` (riscv-rt does not paint it), low-
//!   water mark as on the Cortex-M images. A locked PMP entry makes the 256 bytes
//!   below the stack inaccessible: an overflow traps (store access fault), the
//!   trap entry moves the SP back to the top and the image prints
//!   `FAIL ... stack overflow` and exits with status 1.

use core::arch::{asm, global_asm};
use core::fmt::Write;
use core::mem::MaybeUninit;
use core::ptr::{addr_of, addr_of_mut, read_volatile, write_volatile};

use embedded_graphics_core::geometry::Size;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::camera::{MeshTransform, Orthographic};
use fixshade::framebuffer::Checksum;
use fixshade::render::{CachedVertex, Carry};
use fixshade_qemu::{bins_for, Buffers, Fail, W};
use riscv_rt::entry;

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

// The frame's memory, in `.bss`, named for run.py (as on the Cortex-M images).
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
    /// The stack's lowest address (`memory.x`).
    static _stack_end: u32;
    /// The stack's top (riscv-rt's initial SP).
    static _stack_start: u32;
    /// 256 bytes below the stack, locked inaccessible by PMP.
    static _stack_guard: u32;
}

/// The virt board's NS16550A UART.
const UART: usize = 0x1000_0000;
/// The virt board's SiFive test device (QEMU exits when it is written).
const TEST: usize = 0x0010_0000;
/// The CLINT's `mtime` (10 MHz).
const MTIME: usize = 0x0200_BFF8;
/// Instructions per `mtime` tick under `-icount shift=0` (1 ns each, 100 ns a tick).
const PER_TICK: u64 = 100;
/// How far mtime may lag or lead `minstret / PER_TICK` over a frame (ticks).
const TICK_SLACK: u64 = 4;

/// The stack paint.
const PAINT: u32 = 0xcccc_cccc;

/// `(peak bytes used below the top, bytes never touched above the bottom)`.
fn stack_use() -> (usize, usize) {
    let bottom = addr_of!(_stack_end) as usize;
    let top = addr_of!(_stack_start) as usize;
    let mut p = bottom;
    // SAFETY: [bottom, top) is the stack region; words below the SP are unused.
    while p < top && unsafe { read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    (top - p, p - bottom)
}

/// The current stack pointer.
#[inline(always)]
fn sp() -> usize {
    let sp: usize;
    // SAFETY: reads a register.
    unsafe { asm!("mv {}, sp", out(reg) sp, options(nomem, nostack, preserves_flags)) };
    sp
}

/// Paints the stack from its bottom up to just below this function's frame.
#[inline(never)]
fn repaint() {
    let limit = sp() - 16;
    let mut p = addr_of!(_stack_end) as usize;
    while p < limit {
        // SAFETY: unused stack below the current SP.
        unsafe { write_volatile(p as *mut u32, PAINT) };
        p += 4;
    }
}

/// Locks PMP entry 0 over the guard below the stack: no read, write or execute,
/// in M-mode too (L bit). NAPOT, 256 bytes (the guard is 256-byte aligned).
fn lock_guard() {
    let base = addr_of!(_stack_guard) as usize;
    let addr = (base >> 2) | ((256 >> 3) - 1);
    // SAFETY: PMP entry 0 is unused; the guard holds nothing.
    unsafe {
        asm!("csrw pmpaddr0, {0}", "csrw pmpcfg0, {1}", in(reg) addr, in(reg) 0x98usize,
             options(nomem, nostack));
    }
}

/// Instructions retired (`minstret`, exact under `-icount`).
#[inline(always)]
fn instret() -> u64 {
    loop {
        let (hi, lo, hi2): (u32, u32, u32);
        // SAFETY: reads counters.
        unsafe {
            asm!("csrr {0}, minstreth", "csrr {1}, minstret", "csrr {2}, minstreth",
                 out(reg) hi, out(reg) lo, out(reg) hi2, options(nomem, nostack));
        }
        if hi == hi2 {
            return (u64::from(hi) << 32) | u64::from(lo);
        }
    }
}

/// The CLINT's `mtime`.
#[inline(always)]
fn mtime() -> u64 {
    // SAFETY: the virt board's CLINT; 64-bit counter read as two words.
    unsafe {
        loop {
            let hi = read_volatile((MTIME + 4) as *const u32);
            let lo = read_volatile(MTIME as *const u32);
            if read_volatile((MTIME + 4) as *const u32) == hi {
                return (u64::from(hi) << 32) | u64::from(lo);
            }
        }
    }
}

/// `(result, minstret delta, mtime delta)` of `f`.
#[inline(always)]
fn measure<R>(f: impl FnOnce() -> R) -> (R, u64, u64) {
    let t = mtime();
    let a = instret();
    let r = f();
    let b = instret();
    let u = mtime();
    (r, b - a, u - t)
}

/// Exactly `2 · n` instructions (`c.addi`, `c.bnez` per iteration), `n` ≥ 1.
#[inline(never)]
fn spin(n: u32) {
    // SAFETY: register-only loop.
    unsafe {
        asm!("2:", "addi {0}, {0}, -1", "bnez {0}, 2b", inout(reg) n => _, options(nomem, nostack));
    }
}

/// Writes to the UART.
struct Uart;

impl Write for Uart {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        for b in s.bytes() {
            // SAFETY: the virt board's UART registers: THR (+0), LSR (+5, bit 5: THR empty).
            unsafe {
                while read_volatile((UART + 5) as *const u8) & 0x20 == 0 {}
                write_volatile(UART as *mut u8, b);
            }
        }
        Ok(())
    }
}

fn exit(ok: bool) -> ! {
    // SAFETY: the virt board's test device.
    unsafe {
        write_volatile(
            TEST as *mut u32,
            if ok { 0x5555 } else { (1 << 16) | 0x3333 },
        )
    };
    loop {
        core::hint::spin_loop();
    }
}

/// Prints `FAIL <board> <config>: <why>` and exits with status 1.
#[cold]
#[inline(never)]
fn fail(why: core::fmt::Arguments<'_>) -> ! {
    let _ = writeln!(Uart, "FAIL {BOARD} {}: {why}", config::NAME);
    exit(false)
}

/// What one image measured.
struct Report {
    checksum: u32,
    instructions: u64,
    ticks: u64,
    setup_instructions: u64,
    calib: [u64; 3],
    stack_peak: usize,
    stack_frame: usize,
    stack_setup: usize,
    carry_needed: usize,
}

/// Prints the `RESULT {json}` line.
#[inline(never)]
fn report(r: &Report) {
    let _ = writeln!(
        Uart,
        "RESULT {{\"board\": \"{BOARD}\", \"core\": \"{CORE}\", \"config\": \"{}\", \"rows\": {ROWS}, \
         \"checksum\": \"{:#010x}\", \"pixels\": {}, \"frames\": {FRAMES}, \
         \"instructions\": {}, \"ticks\": {}, \"setup_instructions\": {}, \
         \"calib_n\": {CALIB}, \"calib_empty\": {}, \"calib_instructions\": {}, \"calib_instructions_2n\": {}, \
         \"stack_peak\": {}, \"stack_frame\": {}, \"stack_setup\": {}, \"stack_size\": {STACK}, \
         \"carry_needed\": {}}}",
        config::NAME,
        r.checksum,
        W * W,
        r.instructions,
        r.ticks,
        r.setup_instructions,
        r.calib[0],
        r.calib[1],
        r.calib[2],
        r.stack_peak,
        r.stack_frame,
        r.stack_setup,
        r.carry_needed,
    );
}

/// The transform and the lighting, built once.
static mut SCENE: MaybeUninit<(MeshTransform<Orthographic>, config::Light)> = MaybeUninit::uninit();

/// Builds [`SCENE`] (once).
#[inline(never)]
fn init_scene() -> Result<(&'static MeshTransform<Orthographic>, &'static config::Light), Fail> {
    let scene = config::setup()?;
    // SAFETY: called once, before anything reads SCENE.
    let (t, l) = unsafe { (*addr_of_mut!(SCENE)).write(scene) };
    Ok((t, l))
}

/// Iterations of the calibration loop.
const CALIB: u32 = 1 << 20;

#[entry]
fn main() -> ! {
    repaint();
    lock_guard();
    // the counter: an empty measurement, and loops of 2n and 4n instructions
    let ((), empty, _) = measure(|| ());
    let ((), c1, _) = measure(|| spin(CALIB));
    let ((), c2, _) = measure(|| spin(2 * CALIB));
    let instr = |delta: u64| delta - empty;

    // once: the mesh transform and the lighting (f32 parameters)
    let (scene, setup, _) = measure(init_scene);
    let (transform, lighting) = scene.unwrap_or_else(|e| fail(format_args!("scene set-up: {e:?}")));

    let (setup_peak, _) = stack_use();
    repaint();
    let mut frame_sp = 0;
    let mut sums = [0u32; FRAMES];
    let mut counts = [0u64; FRAMES];
    let mut ticks = [0u64; FRAMES];
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
        let (r, n, t) = measure(|| {
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
        counts[k] = instr(n);
        ticks[k] = t;
    }
    let (frames_peak, headroom) = stack_use();
    let stack_peak = setup_peak.max(frames_peak);
    let stack_frame = frames_peak - (addr_of!(_stack_start) as usize - frame_sp);
    if headroom == 0 {
        fail(format_args!("the stack reached its bottom ({STACK} bytes)"));
    }
    if sums.iter().any(|s| *s != sums[0]) || counts.iter().any(|c| *c != counts[0]) {
        fail(format_args!(
            "frames differ: checksums {sums:x?}, instructions {counts:?}"
        ));
    }
    // mtime is read at a translation block's edge under -icount (each of
    // the two reads up to a block late: one CI run saw 38 816 ticks for
    // 3 881 490 instructions, the run before 38 815); without -icount the
    // ratio is off by far more than these few ticks
    if ticks[0].abs_diff(counts[0] / PER_TICK) > TICK_SLACK {
        fail(format_args!(
            "minstret counted {} instructions, mtime {} ticks: is -icount shift=0 in effect?",
            counts[0], ticks[0]
        ));
    }
    report(&Report {
        checksum: sums[0],
        instructions: counts[0],
        ticks: ticks[0],
        setup_instructions: instr(setup),
        calib: [empty, instr(c1), instr(c2)],
        stack_peak,
        stack_frame,
        stack_setup: setup_peak,
        carry_needed,
    });
    if stack_use().1 == 0 {
        fail(format_args!("the stack reached its bottom while printing"));
    }
    exit(true)
}

// Every trap (no interrupt is enabled: an exception) lands here, with the SP
// wherever the fault left it, possibly in the guard below the stack. Move the
// SP back to the top of the stack first, then report and exit.
global_asm!(
    ".section .trap.start, \"ax\"",
    ".global _start_trap",
    ".align 2",
    "_start_trap:",
    "mv a3, sp",
    "la sp, _stack_start",
    "csrr a0, mcause",
    "csrr a1, mepc",
    "csrr a2, mtval",
    "j fixshade_trap",
);

/// Reports a trap and exits with 1 (`sp`: the SP it was taken with).
#[no_mangle]
extern "C" fn fixshade_trap(mcause: usize, mepc: usize, mtval: usize, sp: usize) -> ! {
    let guard = addr_of!(_stack_guard) as usize;
    let bottom = addr_of!(_stack_end) as usize;
    if (guard..bottom).contains(&mtval) || sp < bottom + 16 {
        fail(format_args!(
            "trap {mcause}: stack overflow (SP {sp:#010x}, address {mtval:#010x}; the stack's bottom is \
             {bottom:#010x}, {STACK} bytes reserved)"
        ));
    }
    fail(format_args!(
        "trap {mcause} at {mepc:#010x} (mtval {mtval:#010x}, SP {sp:#010x})"
    ))
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    fail(format_args!("panic: {info}"))
}
