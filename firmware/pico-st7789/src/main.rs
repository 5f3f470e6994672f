//! The standard scene turning on a Raspberry Pi Pico (RP2040, Cortex-M0+ at
//! 125 MHz) with a 240 × 240 ST7789 SPI display, through the `mipidsi`
//! driver: every frame the sphere's model matrix turns a little, the mesh
//! renderer draws it in 8-row bands, and each band goes straight to the
//! display (no frame buffer: 7.5 KiB of strips and 6 KiB of mesh buffers).
//!
//! **Compiled in CI for `thumbv6m-none-eabi`, not tested on hardware.**
//!
//! Wiring (the Waveshare Pico-LCD-1.3 layout; change the pins below for
//! another board): SPI1 SCK = GP10, MOSI = GP11, CS = GP9, DC = GP8,
//! RST = GP12, backlight = GP13. The on-board LED (GP25) toggles every frame.
//!
//! ```sh
//! cd firmware && cargo build -p fixshade-pico-st7789 --release --target thumbv6m-none-eabi
//! # then flash target/thumbv6m-none-eabi/release/pico-st7789 with probe-rs or elf2uf2-rs
//! ```
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use embedded_hal::digital::{OutputPin, StatefulOutputPin};
use embedded_hal::spi::MODE_3;
use embedded_hal_bus::spi::ExclusiveDevice;
use fixshade::prelude::*;
use fixshade::render::{CachedVertex, Carry, MeshMemory};
use fixshade::standard;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use mipidsi::Builder;
use rp2040_hal as hal;
use rp2040_hal::clocks::Clock;
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::gpio::FunctionSpi;
use rp2040_hal::pac;

/// The second-stage boot loader for the Pico's W25Q080 flash.
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal.
const XTAL_HZ: u32 = 12_000_000;

const W: usize = standard::SIZE as usize;
const ROWS: usize = 8;
const BANDS: usize = W.div_ceil(ROWS);
const NV: usize = standard::COUNTS.0;
const NT: usize = standard::COUNTS.1;
/// Resume records: the standard scene needs 48 in any orientation of the
/// sphere (twice the triangles crossing one band boundary).
const CARRY: usize = 64;

// The renderer's memory (`.bss`, from the crate's `const` zero values).
static mut STRIP: [Rgb565; W * ROWS] = [Rgb565::BLACK; W * ROWS];
static mut DEPTH: [u16; W * ROWS] = [0; W * ROWS];
static mut CACHE: [CachedVertex<[u16; 3]>; NV] = [CachedVertex::ZERO; NV];
static mut BINS: [u16; bins_len(NT, BANDS)] = [0; bins_len(NT, BANDS)];
static mut CARRY_RECORDS: [Carry; CARRY] = [Carry::ZERO; CARRY];
/// The SPI interface's staging buffer.
static mut SPI_BUFFER: [u8; 512] = [0; 512];

#[hal::entry]
fn main() -> ! {
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let clocks = hal::clocks::init_clocks_and_plls(
        XTAL_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .unwrap();
    let sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    // the display: SPI1 at 62.5 MHz, mode 3
    let sck = pins.gpio10.into_function::<FunctionSpi>();
    let mosi = pins.gpio11.into_function::<FunctionSpi>();
    let spi = hal::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        MODE_3,
    );
    let cs = pins.gpio9.into_push_pull_output();
    let dc = pins.gpio8.into_push_pull_output();
    let rst = pins.gpio12.into_push_pull_output();
    let mut backlight = pins.gpio13.into_push_pull_output();
    let mut led = pins.gpio25.into_push_pull_output();
    let spi = ExclusiveDevice::new_no_delay(spi, cs).unwrap();
    // SAFETY: main runs once; these statics are borrowed here only.
    let (buffer, strip, depth, cache, bins, carry) = unsafe {
        (
            &mut *addr_of_mut!(SPI_BUFFER),
            &mut *addr_of_mut!(STRIP),
            &mut *addr_of_mut!(DEPTH),
            &mut *addr_of_mut!(CACHE),
            &mut *addr_of_mut!(BINS),
            &mut *addr_of_mut!(CARRY_RECORDS),
        )
    };
    let mut display = Builder::new(ST7789, SpiInterface::new(spi, dc, buffer))
        .display_size(240, 240)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut timer)
        .unwrap();
    backlight.set_high().unwrap();

    // once: camera and lighting of the standard scene (f32 parameters)
    let camera = standard::camera().unwrap();
    let lighting = standard::blinn::<Q14>().unwrap();
    let layout = Layout::banded(W as u32, W as u32, ROWS as u32).unwrap();
    let mut bands = Bands::new(layout, strip, Some(depth)).unwrap();

    let mut angle = 0.0f32;
    loop {
        // the model matrix turns 2° a frame about a tilted axis
        let model = Mat4::rotate_x(0.4).mul(&Mat4::rotate_y(angle));
        angle = (angle + 0.035) % core::f32::consts::TAU;
        let transform = camera
            .mesh_transform(&model, standard::SPHERE.frac)
            .unwrap();
        let shader = Shader::new(GouraudShading, &lighting, Linear);
        let memory = MeshMemory {
            vertices: &mut cache[..],
            bins: &mut bins[..],
            carry: &mut carry[..],
        };
        let mut sphere =
            MeshDraw::new(layout, standard::SPHERE.mesh(), &transform, shader, memory).unwrap();
        // each band is sent to the display as soon as it is drawn
        bands
            .render(&mut display, Rgb565::BLACK, &mut [&mut sphere])
            .unwrap();
        led.toggle().unwrap();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // stop: the LED stops blinking
    loop {
        cortex_m::asm::wfi();
    }
}
