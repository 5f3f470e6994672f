//! Kernels whose instructions `measure/cortex.py` counts in Unicorn.
//!
//! Pattern for every kernel:
//! * `#[no_mangle] pub extern "C" fn name(ptr/count args in r0..r3) -> u32`;
//! * inputs read through `core::hint::black_box`, so nothing is constant-folded;
//! * listed in `KEEP` (a `#[used]` static that `main` also references), so LTO and
//!   the linker's section GC keep the symbol.
//!
//! `count(n) - count(0)` over `n` items is the per-item cost the emulator reports.
//! The kernels below are self-contained placeholders that validate the instrument;
//! kernels calling fixshade's API follow the same pattern.
#![no_std]
#![no_main]

use core::hint::black_box;
use core::slice;

#[cfg(target_arch = "arm")]
use cortex_m_rt::entry;
#[cfg(target_arch = "riscv32")]
use riscv_rt::entry;

mod shading;

/// Borrow `n` items at `p`, both laundered through `black_box`.
///
/// # Safety
/// `p` must point to `n` readable, aligned items (the emulator writes them).
unsafe fn input<'a, T>(p: *const T, n: u32) -> &'a [T] {
    let n = black_box(n) as usize;
    if n == 0 {
        return &[];
    }
    slice::from_raw_parts(black_box(p), n)
}

/// Σ a[i]·b[i] (wrapping i32): the plain 32-bit multiply-accumulate loop.
#[no_mangle]
pub unsafe extern "C" fn dot_i32(a: *const i32, b: *const i32, n: u32) -> u32 {
    let (a, b) = (input(a, n), input(b, n));
    let mut acc = 0i32;
    for (x, y) in a.iter().zip(b) {
        acc = acc.wrapping_add(x.wrapping_mul(*y));
    }
    acc as u32
}

/// Σ (a[i]·b[i]) >> 16 with a 64-bit product (I16F16 × I16F16):
/// `__aeabi_lmul` on the M0, `smull` on the M4.
#[no_mangle]
pub unsafe extern "C" fn dot_q16_i64(a: *const i32, b: *const i32, n: u32) -> u32 {
    let (a, b) = (input(a, n), input(b, n));
    let mut acc = 0i32;
    for (x, y) in a.iter().zip(b) {
        acc = acc.wrapping_add(((*x as i64 * *y as i64) >> 16) as i32);
    }
    acc as u32
}

/// Σ a[i] / b[i] (b[i] ≠ 0): `__aeabi_idiv` on the M0, `sdiv` on the M4.
#[no_mangle]
pub unsafe extern "C" fn div_i32(a: *const i32, b: *const i32, n: u32) -> u32 {
    let (a, b) = (input(a, n), input(b, n));
    let mut acc = 0i32;
    for (x, y) in a.iter().zip(b) {
        acc = acc.wrapping_add(x.wrapping_div(*y));
    }
    acc as u32
}

/// Σ a[i]·k in f32, returned as bits: soft-float calls on the M0, VFP on the M4F.
#[no_mangle]
pub unsafe extern "C" fn scale_f32(a: *const f32, n: u32, k_bits: u32) -> u32 {
    let a = input(a, n);
    let k = f32::from_bits(black_box(k_bits));
    let mut acc = 0.0f32;
    for x in a {
        acc += *x * k;
    }
    acc.to_bits()
}

/// Σ clamp(a[i], lo, hi) with a data-dependent select: IT blocks on the M4.
#[no_mangle]
pub unsafe extern "C" fn clamp_sum(a: *const i32, n: u32, lo: i32, hi: i32) -> u32 {
    let a = input(a, n);
    let (lo, hi) = (black_box(lo), black_box(hi));
    let mut acc = 0i32;
    for x in a {
        let c = if *x < lo {
            lo
        } else if *x > hi {
            hi
        } else {
            *x
        };
        acc = acc.wrapping_add(c);
    }
    acc as u32
}

/// Function pointers that keep every kernel in the LTO image.
pub struct Keep<T>(pub T);
// SAFETY: read-only tables of code addresses.
unsafe impl<T> Sync for Keep<T> {}

#[used]
pub static KEEP: Keep<[*const (); 5]> = Keep([
    dot_i32 as *const (),
    dot_q16_i64 as *const (),
    div_i32 as *const (),
    scale_f32 as *const (),
    clamp_sum as *const (),
]);

#[entry]
fn main() -> ! {
    // `#[used]` alone does not survive the linker's --gc-sections: reference it.
    black_box(&KEEP);
    black_box(&shading::KEEP);
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
