//! The standard scene turning on a Raspberry Pi Pico (RP2040: two Cortex-M0+
//! cores at 125 MHz) with a 240 × 240 ST7789 SPI display. Every frame the
//! sphere's model matrix turns a little; both cores render it, each its own
//! half of the 30 8-row bands, and every band goes to the display by DMA
//! while its core draws the next one (no frame buffer).
//!
//! **Compiled in CI for `thumbv6m-none-eabi`, not tested on hardware.**
//!
//! What runs where, per frame (the handshake: one SIO FIFO word each way per
//! step, core 0 leading):
//! 1. Core 0 builds the transform and lends core 1 the upper half of the
//!    vertex cache (`LIGHT`); both cores run half of the vertex stage
//!    (`MeshDraw::light_vertices`); core 1 answers `LIT`.
//! 2. Core 0 bins the triangles (`MeshDraw::new` with `lit: true`); core 1
//!    waits.
//! 3. Core 0 lends core 1 the prepared mesh (`DRAW`); each core draws its run
//!    of bands (core 0 bands 0..15, core 1 bands 15..30) through its own
//!    `share` of it, into its own two colour strips; core 1 answers `DRAWN`
//!    once its last band is sent. Core 0 waits for that (its own last band
//!    is sent when `render_bands` returns) before the next frame rewrites
//!    the vertex cache, and toggles the LED.
//!
//! What core 0 lends lives on its stack: its address goes through a static
//! slot (`AtomicPtr`) that core 0 fills before its FIFO word and core 1
//! empties before its answer; core 0 leaves the lent value alone in between.
//!
//! The display: `mipidsi` resets and initialises the panel, then lets go of
//! the SPI bus and pins. From then on the SPI sends 16-bit frames (a pixel
//! as the `u16` it is in memory; a command as NOP and the command), and the
//! SPI, DC, CS and DMA channel 0 are one bus that both cores' band sinks
//! share in a `critical_section::Mutex` (rp2040-hal's implementation: the
//! SIO spinlock 31). One band is on the wire at a time: the sink of a core
//! whose band is ready waits until the bus is free, writes the band's window
//! (CASET, RASET, RAMWR) and starts the DMA transfer of its pixels; whoever
//! next finds that transfer ended raises CS and puts the strip aside for the
//! core it belongs to.
//!
//! RAM (statics, `.bss`): per core two colour strips (2 × 3.75 KiB), a depth
//! strip (3.75 KiB) and 64 resume records (384 B), 11.6 KiB; shared the
//! vertex cache (4.2 KiB) and the bins (1.5 KiB): 29 KiB in all. Stacks:
//! core 0 16 KiB at the bottom of RAM (`memory.x`), core 1 8 KiB (a static,
//! with the MPU guard rp2040-hal installs at its low end); a frame needs
//! about 2.5 KiB.
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

use core::cell::RefCell;
use core::convert::Infallible;
use core::ptr::{self, addr_of_mut, null_mut};
use core::sync::atomic::{fence, AtomicPtr, Ordering};

use critical_section::Mutex;
use embedded_dma::ReadBuffer;
use embedded_hal::digital::{OutputPin, StatefulOutputPin};
use embedded_hal::spi::{SpiBus, MODE_3};
use embedded_hal_bus::spi::ExclusiveDevice;
use fixshade::embedded_graphics_core::primitives::Rectangle;
use fixshade::framebuffer::BandSink;
use fixshade::prelude::*;
use fixshade::render::{CachedVertex, Carry, DrawOptions, MeshMemory};
use fixshade::standard;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use mipidsi::Builder;
use rp2040_hal as hal;
use rp2040_hal::clocks::Clock;
use rp2040_hal::dma::{single_buffer, DMAExt};
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::gpio::bank0::{Gpio10, Gpio11, Gpio8, Gpio9};
use rp2040_hal::gpio::{FunctionSioOutput, FunctionSpi, Pin, PullDown};
use rp2040_hal::multicore::{Multicore, Stack};
use rp2040_hal::pac;
use rp2040_hal::sio::SioFifo;

/// The second-stage boot loader for the Pico's W25Q080 flash.
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal.
const XTAL_HZ: u32 = 12_000_000;

const W: usize = standard::SIZE as usize;
const ROWS: usize = 8;
const STRIP: usize = W * ROWS;
const LAYOUT: Layout = match Layout::banded(W as u32, W as u32, ROWS as u32) {
    Ok(layout) => layout,
    Err(_) => panic!("not a layout"),
};
const BANDS: u32 = LAYOUT.bands();
/// Core 0 draws bands `0..HALF`, core 1 `HALF..BANDS`.
const HALF: u32 = BANDS / 2;
const NV: usize = standard::COUNTS.0;
const NT: usize = standard::COUNTS.1;
/// Resume records per core: the standard scene needs 48 in any orientation
/// of the sphere (twice the triangles crossing one band boundary).
const CARRY: usize = 64;

type Light = Viewed<Lighting<Q14, DirectionalLight<Q14>, BlinnPhong>>;
type Sh = Shader<'static, GouraudShading, Light, Linear, Rgb565>;
type Vertex = CachedVertex<[u16; 3]>;
type Sphere<'f> = MeshDraw<'f, Sh>;

/// One core's band memory: two colour strips (one drawn while the DMA sends
/// the other), a depth strip and resume records.
struct CoreMemory {
    strips: [[Rgb565; STRIP]; 2],
    depth: [u16; STRIP],
    carry: [Carry; CARRY],
}

impl CoreMemory {
    const ZERO: CoreMemory = CoreMemory {
        strips: [[Rgb565::BLACK; STRIP]; 2],
        depth: [0; STRIP],
        carry: [Carry::ZERO; CARRY],
    };

    /// This core's band renderer and resume records.
    fn split(&'static mut self) -> (Bands<'static, Rgb565>, &'static mut [Carry]) {
        let [a, b] = &mut self.strips;
        let bands = Bands::new(LAYOUT, a, Some(&mut self.depth))
            .and_then(|bands| bands.with_second_strip(b))
            .unwrap();
        (bands, &mut self.carry)
    }
}

// The renderer's memory (`.bss`, from the crate's `const` zero values).
static mut CORES: [CoreMemory; 2] = [CoreMemory::ZERO, CoreMemory::ZERO];
static mut CACHE: [Vertex; NV] = [CachedVertex::ZERO; NV];
static mut BINS: [u16; bins_len(NT, BANDS as usize)] = [0; bins_len(NT, BANDS as usize)];
static CORE1_STACK: Stack<2048> = Stack::new();

// --- the frame handshake ----------------------------------------------------

/// FIFO words: core 0 lends (`LIGHT`, `DRAW`), core 1 gives back (`LIT`, `DRAWN`).
const LIGHT: u32 = 1;
const LIT: u32 = 2;
const DRAW: u32 = 3;
const DRAWN: u32 = 4;

/// Core 1's half of a frame's vertex stage (step 1).
struct VertexJob<'f> {
    transform: MeshTransform<Orthographic>,
    shader: Sh,
    /// Vertices `NV / 2..` of the vertex cache (core 0 lights the others).
    upper: &'f mut [Vertex],
}

/// What core 0 lends core 1: non-null from core 0's FIFO word to core 1's
/// answer, each on core 0's stack until then.
static VERTEX_JOB: AtomicPtr<VertexJob<'static>> = AtomicPtr::new(null_mut());
static PREPARED: AtomicPtr<Sphere<'static>> = AtomicPtr::new(null_mut());

// Lending crosses cores: core 1 gets `&mut VertexJob` (Send) and `&Sphere`
// (Sync, as `MeshDraw` is with a `Sync` shader); checked at compile time.
const _: () = {
    const fn send<T: Send>() {}
    const fn sync<T: Sync>() {}
    send::<VertexJob<'static>>();
    sync::<Sphere<'static>>();
};

/// Sends `word` to the other core. The fence (`dmb`) keeps every write
/// before it, the slot's included, ahead of the FIFO write, for the compiler
/// (the FIFO is a volatile register, not an atomic) and for the core.
fn signal(fifo: &mut SioFifo, word: u32) {
    fence(Ordering::SeqCst);
    fifo.write_blocking(word);
}

/// Waits (`wfe`) for `word` from the other core; reads after it stay after.
fn wait(fifo: &mut SioFifo, word: u32) {
    let got = fifo.read_blocking();
    fence(Ordering::SeqCst);
    assert_eq!(got, word, "frame handshake out of step");
}

/// Core 0: lends `value` to core 1 through `slot` (the `step` word).
fn lend<T>(fifo: &mut SioFifo, slot: &AtomicPtr<T>, value: *mut T, step: u32) {
    slot.store(value, Ordering::Release);
    signal(fifo, step);
}

/// Core 0: waits until core 1 gives back what it lent through `slot`.
fn take_back<T>(fifo: &mut SioFifo, slot: &AtomicPtr<T>, step: u32) {
    wait(fifo, step);
    // core 1 emptied the slot before answering: what it wrote is visible
    assert!(slot.load(Ordering::Acquire).is_null());
}

/// Core 1: waits for the `step` word and takes what core 0 lent in `slot`.
fn borrow<T>(fifo: &mut SioFifo, slot: &AtomicPtr<T>, step: u32) -> *mut T {
    wait(fifo, step);
    slot.load(Ordering::Acquire)
}

/// Core 1: gives back what `slot` lent (the `step` word); unused from here.
fn give_back<T>(fifo: &mut SioFifo, slot: &AtomicPtr<T>, step: u32) {
    slot.store(null_mut(), Ordering::Release);
    signal(fifo, step);
}

// --- the display bus, shared by both cores ---------------------------------

type Mosi = Pin<Gpio11, FunctionSpi, PullDown>;
type Sck = Pin<Gpio10, FunctionSpi, PullDown>;
type Spi16 = hal::Spi<hal::spi::Enabled, pac::SPI1, (Mosi, Sck), 16>;
type Dma = hal::dma::Channel<hal::dma::CH0>;

/// ST7789 (MIPI DCS) commands: column and row address set, memory write.
const CASET: u8 = 0x2A;
const RASET: u8 = 0x2B;
const RAMWR: u8 = 0x2C;

/// A band on its way: the first `len` colours of a core's strip, owned by
/// the DMA transfer that sends them.
struct Band {
    strip: &'static mut [Rgb565],
    len: usize,
    core: usize,
}

// embedded-graphics-core 0.4.1 declares `pub struct Rgb565(u16)` (the packed
// RRRRRGGGGGGBBBBB value) without `#[repr(transparent)]`; of size 2, its one
// `u16` field is all of it, at offset 0.
const _: () = assert!(core::mem::size_of::<Rgb565>() == 2 && core::mem::align_of::<Rgb565>() == 2);

// SAFETY: the pointer and length cover the first `len <= strip.len()`
// colours of a `'static` strip that the band owns (`&'static mut`: nothing
// else reads or writes it until the transfer gives the band back), which
// never moves or is freed: the same answer on every call. Each `Rgb565` is
// exactly its `u16` (the assertion above), so the DMA reads the colours.
unsafe impl ReadBuffer for Band {
    type Word = u16;

    unsafe fn read_buffer(&self) -> (*const u16, usize) {
        (self.strip.as_ptr().cast(), self.len.min(self.strip.len()))
    }
}

/// The SPI, DC, CS and DMA channel: one band on the wire at a time.
struct Bus {
    /// The channel and the SPI while no band is sent ...
    idle: Option<(Dma, Spi16)>,
    /// ... or the transfer that holds them.
    sending: Option<single_buffer::Transfer<Dma, Band, Spi16>>,
    dc: Pin<Gpio8, FunctionSioOutput, PullDown>,
    cs: Pin<Gpio9, FunctionSioOutput, PullDown>,
    /// Strips whose transfer has ended, until their core takes them back.
    sent: [Option<&'static mut [Rgb565]>; 2],
}

static BUS: Mutex<RefCell<Option<Bus>>> = Mutex::new(RefCell::new(None));

/// Runs `f` on the bus in a critical section (both cores, interrupts off).
fn with_bus<R>(f: impl FnOnce(&mut Bus) -> R) -> R {
    critical_section::with(|cs| f(BUS.borrow_ref_mut(cs).as_mut().expect("bus set up")))
}

impl Bus {
    /// Ends the running transfer if the DMA is done with it: once the SPI has
    /// shifted out its last words, CS goes high and the strip waits in `sent`.
    fn poll(&mut self) -> Result<(), Infallible> {
        if let Some(transfer) = self.sending.take_if(|t| t.is_done()) {
            let (ch, band, mut spi) = transfer.wait();
            SpiBus::flush(&mut spi)?;
            // The transfer only wrote: the receive FIFO holds stale words,
            // which would let the next blocking write return early.
            while embedded_hal_nb::spi::FullDuplex::<u16>::read(&mut spi).is_ok() {}
            self.cs.set_high()?;
            self.sent[band.core] = Some(band.strip);
            self.idle = Some((ch, spi));
        }
        Ok(())
    }

    /// Starts sending `band` to the window `area` if the bus is free (else
    /// gives the band back): the window commands blocking, the pixels by DMA.
    fn send(&mut self, area: &Rectangle, band: Band) -> Result<Option<Band>, Infallible> {
        let Some((ch, mut spi)) = self.idle.take() else {
            return Ok(Some(band));
        };
        let (x, y) = (area.top_left.x as u16, area.top_left.y as u16);
        let (w, h) = (area.size.width as u16, area.size.height as u16);
        self.cs.set_low()?;
        self.command(&mut spi, CASET, &[x, x + w - 1])?;
        self.command(&mut spi, RASET, &[y, y + h - 1])?;
        // DC stays high: the pixels that follow are RAMWR's data
        self.command(&mut spi, RAMWR, &[])?;
        self.sending = Some(single_buffer::Config::new(ch, band, spi).start());
        Ok(None)
    }

    /// Sends `command` with DC low, then `params` with DC high, in 16-bit
    /// frames, MSB first. The ST7789 reads the serial stream in bytes and
    /// takes each as command or data by the DC pin (Sitronix's 4-line serial
    /// interface), so the frame `command` (high byte 0) arrives as NOP (00h,
    /// the empty command) then the command, and a parameter as two bytes,
    /// high first: CASET and RASET take their start and end so (as mipidsi
    /// sends them). Each blocking write returns once its word is out (it
    /// waits for the word received meanwhile).
    fn command(&mut self, spi: &mut Spi16, command: u8, params: &[u16]) -> Result<(), Infallible> {
        self.dc.set_low()?;
        spi.write(&[u16::from(command)])?;
        self.dc.set_high()?;
        spi.write(params)
    }
}

/// One core's band sink: its bands go out over the shared bus.
struct DmaDisplay {
    core: usize,
}

impl BandSink<'static, Rgb565> for DmaDisplay {
    type Error = Infallible;

    fn start(
        &mut self,
        area: &Rectangle,
        strip: &'static mut [Rgb565],
    ) -> Result<Option<&'static mut [Rgb565]>, Infallible> {
        let len = area.size.width as usize * area.size.height as usize;
        let core = self.core;
        let mut band = Band { strip, len, core };
        // the other core's band may be on the wire: try until the bus is free
        loop {
            match with_bus(|bus| bus.poll().and_then(|()| bus.send(area, band)))? {
                None => return Ok(None),
                Some(back) => band = back,
            }
        }
    }

    fn finish(&mut self) -> Result<&'static mut [Rgb565], Infallible> {
        loop {
            let sent = with_bus(|bus| bus.poll().map(|()| bus.sent[self.core].take()))?;
            if let Some(strip) = sent {
                return Ok(strip);
            }
        }
    }
}

// --- the two cores ------------------------------------------------------------

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
    let mut sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    // the display: SPI1 at 62.5 MHz, mode 3; mipidsi initialises it over
    // borrowed bus and pins, then the display value is dropped (RST stays high)
    let sck = pins.gpio10.into_function::<FunctionSpi>();
    let mosi = pins.gpio11.into_function::<FunctionSpi>();
    let mut spi = hal::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        MODE_3,
    );
    let mut cs = pins.gpio9.into_push_pull_output();
    let mut dc = pins.gpio8.into_push_pull_output();
    let rst = pins.gpio12.into_push_pull_output();
    let mut backlight = pins.gpio13.into_push_pull_output();
    let mut led = pins.gpio25.into_push_pull_output();
    let mut buffer = [0u8; 64];
    let device = ExclusiveDevice::new_no_delay(&mut spi, &mut cs).unwrap();
    Builder::new(ST7789, SpiInterface::new(device, &mut dc, &mut buffer))
        .display_size(240, 240)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut timer)
        .unwrap();
    backlight.set_high().unwrap();

    // from here 16-bit SPI frames: a pixel goes out as the u16 it is in
    // memory, MSB first, the byte order the ST7789 reads (as mipidsi sends)
    let (spi1, spi_pins) = spi.disable().free();
    let spi = hal::Spi::<_, _, _, 16>::new(spi1, spi_pins).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        MODE_3,
    );
    let dma = pac.DMA.split(&mut pac.RESETS);
    let bus = Bus {
        idle: Some((dma.ch0, spi)),
        sending: None,
        dc,
        cs,
        sent: [None, None],
    };
    critical_section::with(|cs| BUS.borrow(cs).replace(Some(bus)));

    // SAFETY: main runs once, before core 1 starts; each static is borrowed
    // here only (core 1's memory moves into its closure).
    let (cache, bins, [mem0, mem1]) = unsafe {
        (
            &mut *addr_of_mut!(CACHE),
            &mut *addr_of_mut!(BINS),
            &mut *addr_of_mut!(CORES),
        )
    };

    // once: camera and lighting of the standard scene (f32 parameters)
    let camera = standard::camera().unwrap();
    let lighting: &'static Light =
        cortex_m::singleton!(: Light = standard::blinn::<Q14>().unwrap()).unwrap();

    let mut mc = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
    let core1 = &mut mc.cores()[1];
    core1
        .spawn(CORE1_STACK.take().unwrap(), move || core1_main(mem1))
        .unwrap();
    let fifo = &mut sio.fifo;

    let (mut bands, carry) = mem0.split();
    let mesh = standard::SPHERE.mesh();
    let mut angle = 0.0f32;
    loop {
        // the model matrix turns 2° a frame about a tilted axis
        let model = Mat4::rotate_x(0.4).mul(&Mat4::rotate_y(angle));
        angle = (angle + 0.035) % core::f32::consts::TAU;
        let transform = camera
            .mesh_transform(&model, standard::SPHERE.frac)
            .unwrap();
        let shader = Shader::new(GouraudShading, lighting, Linear);

        // 1. the vertex stage: vertices NV/2.. on core 1, the others here
        {
            let (lower, upper) = cache.split_at_mut(NV / 2);
            let mut job = VertexJob {
                transform,
                shader,
                upper,
            };
            lend(fifo, &VERTEX_JOB, ptr::from_mut(&mut job).cast(), LIGHT);
            Sphere::light_vertices(&mesh, &transform, &shader, 0, lower);
            take_back(fifo, &VERTEX_JOB, LIT);
        }

        // 2. the bins, here alone
        let memory = MeshMemory {
            vertices: &mut cache[..],
            bins: &mut bins[..],
            carry: &mut [],
        };
        let sphere = Sphere::new(
            LAYOUT,
            mesh,
            &transform,
            shader,
            memory,
            DrawOptions {
                lit: true,
                ..DrawOptions::default()
            },
        )
        .unwrap();

        // 3. the bands: 0..HALF here, HALF.. on core 1, at the same time
        let lent = ptr::from_ref(&sphere).cast_mut().cast();
        lend(fifo, &PREPARED, lent, DRAW);
        let mut mine = sphere.share(carry);
        let mut display = DmaDisplay { core: 0 };
        bands
            .render_bands(&mut display, Rgb565::BLACK, &mut [&mut mine], 0..HALF)
            .unwrap();
        take_back(fifo, &PREPARED, DRAWN);
        led.toggle().unwrap();
    }
}

/// Core 1: its half of every frame's vertex stage and of its bands.
fn core1_main(mem: &'static mut CoreMemory) -> ! {
    // SAFETY: core 1 needs its own handle on the SIO FIFO (what rp2040-hal's
    // multicore does too); each core sees its own end of the FIFO at the same
    // registers, and core 1 uses nothing else of the SIO.
    let mut fifo = hal::Sio::new(unsafe { pac::Peripherals::steal() }.SIO).fifo;
    let (mut bands, carry) = mem.split();
    let mesh = standard::SPHERE.mesh();
    let mut display = DmaDisplay { core: 1 };
    loop {
        let job = borrow(&mut fifo, &VERTEX_JOB, LIGHT);
        {
            // SAFETY: core 0 stored the address of this frame's job (on its
            // stack) before its word, and neither moves nor touches the job
            // (it lights the cache's other half) until our answer; the
            // reference is not used after this block.
            let job = unsafe { job.as_mut() }.expect("a vertex job");
            Sphere::light_vertices(&mesh, &job.transform, &job.shader, NV / 2, job.upper);
        }
        give_back(&mut fifo, &VERTEX_JOB, LIT);

        let sphere = borrow(&mut fifo, &PREPARED, DRAW);
        {
            // SAFETY: core 0 stored the address of this frame's prepared
            // mesh (on its stack) before its word, and only reads it (its
            // own share) until our answer; `Sphere` is `Sync`. The
            // reference is not used after this block.
            let sphere = unsafe { sphere.as_ref() }.expect("a prepared mesh");
            let mut mine = sphere.share(carry);
            bands
                .render_bands(&mut display, Rgb565::BLACK, &mut [&mut mine], HALF..BANDS)
                .unwrap();
        }
        give_back(&mut fifo, &PREPARED, DRAWN);
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // stop: the LED stops blinking (the other core then waits for ever)
    loop {
        cortex_m::asm::wfi();
    }
}
