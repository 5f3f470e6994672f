//! The row loop: a set-up triangle's rows in a band, each row's run of
//! pixels depth-tested and written ([`depth`](super::depth)), its values
//! screen-linear or perspective-correct.

use super::depth;
use crate::framebuffer::BandView;
use crate::raster::interp::{eighth, step_over, Affine, Persp, Varyings};
use crate::raster::{Plane, Walker, PERSPECTIVE_SPAN};
use crate::shade::Kernel;

/// How a triangle's values reach the kernel along its rows: screen-linear
/// planes or perspective-correct sub-spans.
pub(crate) trait Runs<K: Kernel> {
    /// Moves the values a row down.
    fn next_row(&mut self);
    /// Shades the `out.len()` pixels of row `y` from column `x`; `clamp`:
    /// the values are clamped to the vertex range per run.
    fn run(&self, kernel: &K, t: &K::Triangle, x: i32, y: i32, out: &mut [K::Color], clamp: bool);
    /// The screen-linear planes, if that is what these are (a kernel that
    /// fuses the depth test takes their runs whole).
    #[inline(always)]
    fn linear(&self) -> Option<&Affine<K::Varyings>> {
        None
    }
}

impl<K: Kernel> Runs<K> for Affine<K::Varyings> {
    #[inline(always)]
    fn next_row(&mut self) {
        Affine::next_row(self, K::USED)
    }

    #[inline(always)]
    fn run(&self, kernel: &K, t: &K::Triangle, x: i32, y: i32, out: &mut [K::Color], clamp: bool) {
        let (a, d) = Affine::run(self, x, out.len(), K::USED, clamp);
        kernel.span(t, &a, &d, x, y, out)
    }

    #[inline(always)]
    fn linear(&self) -> Option<&Affine<K::Varyings>> {
        Some(self)
    }
}

impl<K: Kernel> Runs<K> for Persp<K::Varyings> {
    #[inline(always)]
    fn next_row(&mut self) {
        Persp::next_row(self)
    }

    #[inline(always)]
    fn run(&self, kernel: &K, t: &K::Triangle, x: i32, y: i32, out: &mut [K::Color], _: bool) {
        perspective_run(kernel, t, self, x, y, out)
    }
}

/// Whether a triangle's runs are clamped ([`draw_rows`]): a constant, so that
/// each case gets its own copy of the row loop, or a flag read per row, so
/// that one copy serves both.
trait Clamp: Copy {
    fn on(self) -> bool;
}

impl Clamp for bool {
    #[inline(always)]
    fn on(self) -> bool {
        self
    }
}

/// [`Clamp`] as a constant (a loop copy per case; not built for size).
#[cfg(not(fixshade_opt_size))]
#[derive(Clone, Copy)]
struct Fixed<const ON: bool>;

#[cfg(not(fixshade_opt_size))]
impl<const ON: bool> Clamp for Fixed<ON> {
    #[inline(always)]
    fn on(self) -> bool {
        ON
    }
}

/// The rows `w.y..=last` of a set-up triangle ([`draw_rows`]), runs clamped
/// when `clamp` holds: a loop copy per case, or built for size
/// (`cfg(fixshade_opt_size)`, set by `build.rs`) one copy reading the flag
/// per row (about 0.4 KiB less code on the Cortex-M0).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn rows<K: Kernel, R: Runs<K>>(
    kernel: &K,
    t: &K::Triangle,
    w: &mut Walker,
    last: i32,
    zp: &mut Plane,
    band: &mut BandView<'_, K::Color>,
    values: &mut R,
    clamp: bool,
) {
    #[cfg(fixshade_opt_size)]
    draw_rows(kernel, t, w, last, zp, band, values, clamp);
    #[cfg(not(fixshade_opt_size))]
    if clamp {
        draw_rows(kernel, t, w, last, zp, band, values, Fixed::<true>);
    } else {
        draw_rows(kernel, t, w, last, zp, band, values, Fixed::<false>);
    }
}

/// The rows `w.y..=last` of a set-up triangle: the walker's columns, the
/// depth test of each run (the depth plane `zp`), and the kernel on the
/// passing pixels (all of them without a depth buffer: a branch per row, not
/// a second copy of the loop). `mode`: whether depth and values are clamped
/// per run ([`clamped_rows`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn draw_rows<K: Kernel, R: Runs<K>, M: Clamp>(
    kernel: &K,
    t: &K::Triangle,
    w: &mut Walker,
    last: i32,
    zp: &mut Plane,
    band: &mut BandView<'_, K::Color>,
    values: &mut R,
    mode: M,
) {
    let width = band.width as i32;
    let start = band.rows.start;
    let mut row = (w.y - start) as usize * band.width as usize;
    while w.y <= last {
        let y = w.y;
        let (lo, hi) = w.next();
        let (lo, hi) = (lo.max(0), hi.min(width - 1));
        if lo <= hi {
            let n = (hi - lo + 1) as usize;
            let at = row + lo as usize;
            if let Some(color) = band.color.get_mut(at..at + n) {
                if let Some(d) = band.depth.as_deref_mut() {
                    let (z0, dz) = if mode.on() {
                        zp.clamped(lo, n as i32)
                    } else {
                        (zp.at(lo), zp.dx)
                    };
                    if let Some(depth) = d.get_mut(at..at + n) {
                        match values.linear() {
                            // a kernel that fills takes the whole run (its
                            // values clamped over the whole run)
                            Some(l) if K::FILLS => {
                                let (a, d) = l.run(lo, n, K::USED, mode.on());
                                depth::write(kernel, t, (&a, &d), (lo, y), (z0, dz), color, depth);
                            }
                            // else the values of each passing run (clamped per run)
                            _ => depth::depth_runs(z0, dz, depth, |k0, k1| {
                                if let Some(c) = color.get_mut(k0..k1) {
                                    values.run(kernel, t, lo + k0 as i32, y, c, mode.on());
                                }
                            }),
                        }
                    }
                } else {
                    values.run(kernel, t, lo, y, color, mode.on());
                }
            }
        }
        values.next_row();
        zp.next_row();
        row += band.width as usize;
    }
}

/// A run of pixels from column `x` with perspective-correct values: exact at
/// every [`PERSPECTIVE_SPAN`]-th pixel from `x` and at the last, linear in
/// between.
#[inline(always)]
fn perspective_run<K: Kernel>(
    kernel: &K,
    t: &K::Triangle,
    p: &Persp<K::Varyings>,
    x: i32,
    y: i32,
    out: &mut [K::Color],
) {
    let mut x = x;
    let mut a = p.at(x);
    let mut rest = out;
    // whole sub-spans towards the next one's first pixel; the last towards
    // its own last pixel (a point beyond the run may lie outside the
    // triangle, where the weights are clamped)
    while rest.len() > PERSPECTIVE_SPAN {
        let (part, tail) = rest.split_at_mut(PERSPECTIVE_SPAN);
        let b = p.at(x + PERSPECTIVE_SPAN as i32);
        kernel.span(t, &a, &eighth(&a, &b), x, y, part);
        a = b;
        x += PERSPECTIVE_SPAN as i32;
        rest = tail;
    }
    let n = rest.len() as u32;
    let step = if n > 1 {
        step_over(&a, &p.at(x + n as i32 - 1), n - 1)
    } else {
        K::Varyings::from_fn(|_| 0)
    };
    kernel.span(t, &a, &step, x, y, rest);
}
