//! Any vertex values: no panic, no overflow, no write outside the target,
//! shader values always inside the vertex range.

#[path = "common/seeded.rs"]
mod seeded;

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use fixshade::raster::{
    draw_triangle, draw_triangle_perspective, Cull, RasterOptions, RasterVertex, SpanShader,
};
use fixshade::target::{BandBuffer, DepthBuffer, Framebuffer, SliceFramebuffer};
use proptest::prelude::*;

const W: u32 = 40;
const H: u32 = 30;

/// Checks every call against the frame and the vertex ranges, counts pixels.
struct Check {
    lo: [i64; 2],
    hi: [i64; 2],
    rows: core::ops::Range<i32>,
    pixels: u32,
}

impl SpanShader<2> for Check {
    type Color = Gray8;
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; 2], step: &[i32; 2], out: &mut [Gray8]) {
        assert!(!out.is_empty());
        assert!(
            x >= 0 && x as u32 + out.len() as u32 <= W,
            "x {x} len {}",
            out.len()
        );
        assert!(self.rows.contains(&y), "row {y}");
        for i in 0..2 {
            for k in [0, out.len() as i64 - 1] {
                let a = i64::from(start[i]) + k * i64::from(step[i]);
                assert!(
                    a >= self.lo[i] && a <= self.hi[i],
                    "attr {i} = {a} outside {}..={}",
                    self.lo[i],
                    self.hi[i]
                );
            }
        }
        self.pixels += out.len() as u32;
        for p in out.iter_mut() {
            *p = Gray8::new(p.luma().wrapping_add(1));
        }
    }
}

fn vertex() -> impl Strategy<Value = RasterVertex<2>> {
    let coord = prop_oneof![any::<i32>(), -2000i32..2000, Just(i32::MIN), Just(i32::MAX)];
    (
        coord.clone(),
        coord,
        any::<u16>(),
        any::<i32>(),
        any::<[i32; 2]>(),
    )
        .prop_map(|(x, y, z, inv_w, attrs)| RasterVertex {
            x,
            y,
            z,
            inv_w,
            attrs,
        })
}

fn options() -> impl Strategy<Value = (RasterOptions, bool)> {
    (0u8..3, any::<bool>(), any::<bool>(), any::<bool>()).prop_map(
        |(c, perspective, depth_test, depth_write)| {
            let cull = [Cull::None, Cull::Back, Cull::Front][c as usize];
            let opts = RasterOptions {
                cull,
                depth_test,
                depth_write,
            };
            (opts, perspective)
        },
    )
}

/// Draws with the screen-linear or the perspective-correct rasterizer.
fn draw<F: fixshade::target::Framebuffer<Color = Gray8, Error = core::convert::Infallible>>(
    fb: &mut F,
    depth: Option<&mut DepthBuffer<'_>>,
    v: &[RasterVertex<2>; 3],
    (opts, perspective): &(RasterOptions, bool),
    shader: &mut Check,
) -> fixshade::raster::DrawStats {
    let r = if *perspective {
        draw_triangle_perspective(fb, depth, v, opts, shader)
    } else {
        draw_triangle(fb, depth, v, opts, shader)
    };
    match r {
        Ok(s) => s,
        Err(e) => match e {},
    }
}

fn checker(v: &[RasterVertex<2>; 3], rows: core::ops::Range<i32>) -> Check {
    let r = |i: usize| {
        // attributes are clamped to ±ATTR_LIMIT before set-up
        let lim = i64::from(fixshade::raster::ATTR_LIMIT);
        let a = v.map(|v| i64::from(v.attrs[i]).clamp(-lim, lim));
        (a[0].min(a[1]).min(a[2]), a[0].max(a[1]).max(a[2]))
    };
    Check {
        lo: [r(0).0, r(1).0],
        hi: [r(0).1, r(1).1],
        rows,
        pixels: 0,
    }
}

proptest! {
    #![proptest_config(seeded::config("raster_robust", 3000))]

    #[test]
    fn any_triangle_is_safe(v in [vertex(), vertex(), vertex()], opts in options(), use_depth in any::<bool>()) {
        let mut px = vec![Gray8::new(0); (W * H) as usize];
        let mut fb = SliceFramebuffer::new(&mut px, W, H).unwrap();
        let mut z = vec![u16::MAX; (W * H) as usize];
        let mut depth = DepthBuffer::new(&mut z, W).unwrap();
        let mut shader = checker(&v, 0..H as i32);
        let stats = draw(&mut fb, use_depth.then_some(&mut depth), &v, &opts, &mut shader);
        prop_assert_eq!(stats.pixels, shader.pixels);
        prop_assert!(px.iter().all(|p| p.luma() <= 1), "pixel written twice by one triangle");
        prop_assert_eq!(px.iter().filter(|p| p.luma() == 1).count() as u32, stats.pixels);
    }

    #[test]
    fn any_triangle_in_bands_is_safe(v in [vertex(), vertex(), vertex()], opts in options(), band_rows in 1u32..9) {
        let mut strip = vec![Gray8::new(0); (W * band_rows) as usize];
        let mut band = BandBuffer::new(&mut strip, W, H).unwrap();
        let mut z = vec![0u16; (W * band_rows) as usize];
        let mut depth = DepthBuffer::new(&mut z, W).unwrap();
        for i in 0..band.bands() {
            band.set_band(i);
            band.clear(Gray8::new(0));
            depth.set_first_row(band.rows().start);
            depth.clear(u16::MAX);
            let mut shader = checker(&v, band.rows());
            draw(&mut band, Some(&mut depth), &v, &opts, &mut shader);
        }
    }
}
