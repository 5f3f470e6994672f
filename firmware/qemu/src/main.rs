//! The showcase firmware, and its host reference.
//!
//! * `thumbv6m-none-eabi` (QEMU `microbit`, Cortex-M0, 16 KiB RAM) and
//!   `thumbv7em-none-eabihf` (QEMU `mps2-an386`, Cortex-M4F): one
//!   configuration per image (a cargo feature). It renders the standard
//!   scene twice through a band strip into a `fixshade::framebuffer::Checksum`,
//!   times every stage with SysTick (under `qemu -icount shift=0` one
//!   instruction is one nanosecond of virtual time, so the count is exact
//!   and deterministic), reads the painted stack's low-water mark, prints one
//!   `RESULT {json}` line through semihosting and exits with status 0, or
//!   prints `FAIL ...` and exits with 1: on a failed frame, a panic, and
//!   any fault (a stack overflow faults: the stack is below the statics).
//! * `riscv32imc-unknown-none-elf` (QEMU `virt`, RV32IMC): the same frames,
//!   counted with `minstret` (exact under `-icount`), output through the UART,
//!   exit through the test device (`src/firmware_riscv.rs`).
//! * the host: `cargo run -p fixshade-qemu --profile host` prints, as JSON,
//!   every configuration's checksum, from the same library functions, in
//!   bands of 4 and 8 rows and as one 240-row band (all must agree).
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_arch = "arm"))]
mod firmware;
#[cfg(all(target_os = "none", target_arch = "riscv32"))]
#[path = "firmware_riscv.rs"]
mod firmware;

#[cfg(not(target_os = "none"))]
fn main() {
    use embedded_graphics_core::geometry::Size;
    use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
    use fixshade::framebuffer::Checksum;
    use fixshade::render::Carry;
    use fixshade_qemu::*;

    let t = transform().expect("standard transform");
    let mut out = Vec::new();
    for name in CONFIGS {
        let mut sums = Vec::new();
        let mut needed = 0;
        for rows in [4, 8, W] {
            let mut bins = vec![0u16; bins(rows)];
            let mut carry = vec![Carry::default(); CARRY];
            let mut strip = vec![Rgb565::BLACK; W * rows];
            let mut depth = vec![0u16; W * rows];
            let mut sum = Checksum::<Rgb565>::new(Size::new(W as u32, W as u32));
            let n = run(
                name, &t, rows, &mut bins, &mut carry, &mut strip, &mut depth, &mut sum,
            )
            .expect("a configuration")
            .unwrap_or_else(|e| panic!("{name}, {rows} rows: {e:?}"));
            assert_eq!(sum.pixels() as usize, W * W, "{name}: pixels sent");
            needed = needed.max(n);
            sums.push(sum.value());
        }
        assert!(
            sums.iter().all(|s| *s == sums[0]),
            "{name}: bands of 4, 8 and 240 rows disagree: {sums:x?}"
        );
        out.push(format!(
            "  \"{name}\": {{\"checksum\": \"{:#010x}\", \"carry_needed\": {needed}}}",
            sums[0]
        ));
    }
    println!("{{\n{}\n}}", out.join(",\n"));
}
