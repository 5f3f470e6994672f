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
//!   The imported configurations (features `imported`, `imported_textured`)
//!   also run in 2-row bands; every configuration's entry has `lit` (pixels
//!   not of the clear colour), and `clear` is the checksum of a clear frame.
//!   `run.py` builds it with `--features imported,imported_textured`.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_arch = "arm"))]
mod firmware;
#[cfg(all(target_os = "none", target_arch = "riscv32"))]
#[path = "firmware_riscv.rs"]
mod firmware;

/// A display that passes every pixel to a `Checksum` and counts those not of
/// the clear colour (the host reference: the frame is more than a clear one).
#[cfg(not(target_os = "none"))]
struct Counting {
    sum: fixshade::framebuffer::Checksum<embedded_graphics_core::pixelcolor::Rgb565>,
    lit: usize,
}

#[cfg(not(target_os = "none"))]
impl embedded_graphics_core::geometry::OriginDimensions for Counting {
    fn size(&self) -> embedded_graphics_core::geometry::Size {
        self.sum.size()
    }
}

#[cfg(not(target_os = "none"))]
impl embedded_graphics_core::draw_target::DrawTarget for Counting {
    type Color = embedded_graphics_core::pixelcolor::Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = embedded_graphics_core::Pixel<Self::Color>>,
    {
        let area = embedded_graphics_core::primitives::Rectangle::zero();
        self.fill_contiguous(&area, pixels.into_iter().map(|p| p.1))
    }

    fn fill_contiguous<I>(
        &mut self,
        area: &embedded_graphics_core::primitives::Rectangle,
        colors: I,
    ) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        use embedded_graphics_core::pixelcolor::RgbColor;
        let colors: Vec<_> = colors.into_iter().collect();
        self.lit += colors.iter().filter(|c| **c != Self::Color::BLACK).count();
        self.sum.fill_contiguous(area, colors)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    use embedded_graphics_core::draw_target::DrawTarget;
    use embedded_graphics_core::geometry::{Dimensions, Size};
    use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
    use fixshade::framebuffer::Checksum;
    use fixshade::render::Carry;
    use fixshade_qemu::*;

    let size = Size::new(W as u32, W as u32);
    let mut clear = Checksum::<Rgb565>::new(size);
    // (not fill_solid: Checksum's fill_contiguous takes every colour given,
    // and the trait's fill_solid gives an endless iterator)
    let area = clear.bounding_box();
    clear
        .fill_contiguous(&area, core::iter::repeat_n(Rgb565::BLACK, W * W))
        .unwrap();
    let t = transform().expect("standard transform");
    let mut out = vec![format!("  \"clear\": \"{:#010x}\"", clear.value())];
    for name in CONFIGS.iter().chain(IMPORTED) {
        let imported = IMPORTED.contains(name);
        let (mut sums, mut lit) = (Vec::new(), Vec::new());
        let mut needed = 0;
        let rows: &[usize] = if imported { &[2, 4, 8, W] } else { &[4, 8, W] };
        for &rows in rows {
            // bins for the larger mesh (the renderer uses what it needs)
            let mut bins = vec![0u16; bins_for(NT.max(784), rows)];
            let mut carry = vec![Carry::default(); if imported { rocket::CARRY } else { CARRY }];
            let mut strip = vec![Rgb565::BLACK; W * rows];
            let mut depth = vec![0u16; W * rows];
            let mut d = Counting {
                sum: Checksum::<Rgb565>::new(size),
                lit: 0,
            };
            let r = if imported {
                run_imported(
                    name, rows, &mut bins, &mut carry, &mut strip, &mut depth, &mut d,
                )
            } else {
                run(
                    name, &t, rows, &mut bins, &mut carry, &mut strip, &mut depth, &mut d,
                )
            };
            let Some(r) = r else {
                break; // an imported configuration whose feature is off
            };
            let n = r.unwrap_or_else(|e| panic!("{name}, {rows} rows: {e:?}"));
            assert_eq!(d.sum.pixels() as usize, W * W, "{name}: pixels sent");
            needed = needed.max(n);
            sums.push(d.sum.value());
            lit.push(d.lit);
        }
        if sums.is_empty() {
            continue;
        }
        assert!(
            sums.iter().all(|s| *s == sums[0]) && lit.iter().all(|l| *l == lit[0]),
            "{name}: bands of {rows:?} rows disagree: {sums:x?}, lit {lit:?}"
        );
        // a rendered model, not a clear frame: at least 5 % of the pixels lit
        assert!(
            sums[0] != clear.value() && lit[0] * 20 >= W * W,
            "{name}: {} of {} pixels lit, checksum {:#010x} (clear {:#010x})",
            lit[0],
            W * W,
            sums[0],
            clear.value()
        );
        out.push(format!(
            "  \"{name}\": {{\"checksum\": \"{:#010x}\", \"carry_needed\": {needed}, \"lit\": {}}}",
            sums[0], lit[0]
        ));
    }
    println!("{{\n{}\n}}", out.join(",\n"));
}
