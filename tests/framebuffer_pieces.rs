//! The same scene gives the same pixels through every framebuffer (issue 11,
//! item 9): `SliceFramebuffer`, `BandBuffer` (8-row bands), `DrawTargetAdapter`
//! (64-pixel pieces) and a test framebuffer that hands every span out in
//! pieces of 1, 3 or 7 pixels. The rasterizer must continue `start + k·step`
//! (and, in perspective, the sub-span of `PERSPECTIVE_SPAN` pixels) across
//! pieces instead of restarting the attribute plane at each one.
//!
//! Scenes: the lit sphere of the golden tests under four point lights
//! (Blinn-Phong), Gouraud through a gamma table and Phong (linear), drawn with
//! `draw` and with `draw_perspective` (varying `1/w`).

mod common;

use common::render::{config_scene, prepare, LightSet, Mode, Scene, Vert};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::prelude::*;
use embedded_graphics_simulator::SimulatorDisplay;
use fixshade::color::{GammaTable, Rgb, Transfer};
use fixshade::light::AnyLight;
use fixshade::lighting::{BlinnPhong, Lighting};
use fixshade::material::Material;
use fixshade::raster::RasterOptions;
use fixshade::shade::{Gamma, GouraudShading, Linear, PhongShading, ShadeVertex, Shader, Shading};
use fixshade::target::{BandBuffer, DepthBuffer, DrawTargetAdapter, Framebuffer, SliceFramebuffer};
use std::ops::Range;

const W: u32 = 240;

/// A full frame in memory that hands every span out in pieces whose lengths
/// cycle through `sizes` (all legal: consecutive, left to right, covering the span).
struct Pieces {
    px: Vec<Rgb565>,
    sizes: &'static [u32],
    next: usize,
}

impl Framebuffer for Pieces {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn width(&self) -> u32 {
        W
    }
    fn rows(&self) -> Range<i32> {
        0..W as i32
    }
    fn fill_span<F: FnMut(u32, &mut [Rgb565])>(
        &mut self,
        x: u32,
        y: i32,
        len: u32,
        mut fill: F,
    ) -> Result<(), Self::Error> {
        assert!(
            y >= 0 && y < W as i32 && x + len <= W,
            "span outside the frame"
        );
        let row = y as usize * W as usize;
        let mut at = x;
        while at < x + len {
            let n = self.sizes[self.next % self.sizes.len()].min(x + len - at);
            self.next += 1;
            let a = row + at as usize;
            fill(at, &mut self.px[a..a + n as usize]);
            at += n;
        }
        Ok(())
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Draw {
    GouraudGamma,
    Phong,
}

fn draw_scene<F: Framebuffer<Color = Rgb565, Error: core::fmt::Debug>>(
    scene: &Scene,
    tris: &[[Vert; 3]],
    how: Draw,
    perspective: bool,
    fb: &mut F,
    depth: &mut DepthBuffer<'_>,
) {
    let lights: heapless::Vec<AnyLight<f32>, 4> = scene
        .lights
        .iter()
        .map(|d| AnyLight::new(d).unwrap())
        .collect();
    let obj = &scene.objects[0];
    let lighting =
        Lighting::<f32, _, BlinnPhong>::new(lights, Material::new(&obj.material).unwrap())
            .with_global_ambient(Rgb::from_f32(scene.global_ambient));
    let table = GammaTable::<1024>::new(Transfer::Srgb).unwrap();
    // a w that varies over the sphere (perspective draws): 1/w grows 3.8-fold left to right
    let sv = |v: &Vert| {
        let inv_w = if perspective {
            (1 << 14) + 12 * v.screen.x.clamp(0, (W << 4) as i32)
        } else {
            v.screen.inv_w
        };
        ShadeVertex::<f32>::new([v.screen.x, v.screen.y], v.screen.z, inv_w, v.pos, v.normal)
    };
    fn run<
        S: Shading<f32, Color = Rgb565>,
        F: Framebuffer<Color = Rgb565, Error: core::fmt::Debug>,
    >(
        s: &mut S,
        tris: &[[ShadeVertex<f32>; 3]],
        perspective: bool,
        fb: &mut F,
        depth: &mut DepthBuffer<'_>,
    ) {
        let o = RasterOptions::default();
        for t in tris {
            if perspective {
                s.draw_perspective(fb, Some(depth), t, &o).unwrap();
            } else {
                s.draw(fb, Some(depth), t, &o).unwrap();
            }
        }
    }
    let tris: Vec<[ShadeVertex<f32>; 3]> = tris.iter().map(|t| t.each_ref().map(sv)).collect();
    match how {
        Draw::GouraudGamma => {
            let mut s = Shader::new(GouraudShading, &lighting, Gamma(&table));
            run(&mut s, &tris, perspective, fb, depth);
        }
        Draw::Phong => {
            let mut s = Shader::new(PhongShading, &lighting, Linear);
            run(&mut s, &tris, perspective, fb, depth);
        }
    }
}

/// The frame through each framebuffer; the first is the `SliceFramebuffer`'s.
fn frames(how: Draw, perspective: bool) -> Vec<(&'static str, Vec<Rgb565>)> {
    let mode = if how == Draw::Phong {
        Mode::Phong
    } else {
        Mode::Gouraud
    };
    let scene = config_scene(LightSet::Point4Blinn, mode);
    let tris = prepare(&scene).remove(0);
    let n = (W * W) as usize;
    let mut out = Vec::new();

    let mut px = vec![Rgb565::BLACK; n];
    let mut z = vec![u16::MAX; n];
    {
        let mut fb = SliceFramebuffer::new(&mut px, W, W).unwrap();
        let mut db = DepthBuffer::new(&mut z, W).unwrap();
        draw_scene(&scene, &tris, how, perspective, &mut fb, &mut db);
    }
    out.push(("SliceFramebuffer", px));

    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(W, W));
    let mut z = vec![u16::MAX; n];
    {
        let mut fb = DrawTargetAdapter::new(&mut display);
        let mut db = DepthBuffer::new(&mut z, W).unwrap();
        draw_scene(&scene, &tris, how, perspective, &mut fb, &mut db);
    }
    let px = (0..n)
        .map(|i| display.get_pixel(Point::new((i as u32 % W) as i32, (i as u32 / W) as i32)))
        .collect();
    out.push(("DrawTargetAdapter", px));

    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(W, W));
    let mut strip = vec![Rgb565::BLACK; W as usize * 8];
    let mut z = vec![u16::MAX; n];
    {
        let mut band = BandBuffer::new(&mut strip, W, W).unwrap();
        let mut db = DepthBuffer::new(&mut z, W).unwrap();
        band.render(&mut display, Rgb565::BLACK, |fb| {
            draw_scene(&scene, &tris, how, perspective, fb, &mut db);
        })
        .unwrap();
    }
    let px = (0..n)
        .map(|i| display.get_pixel(Point::new((i as u32 % W) as i32, (i as u32 / W) as i32)))
        .collect();
    out.push(("BandBuffer", px));

    for sizes in [&[1u32][..], &[3], &[7], &[1, 3, 7, 2, 5]] {
        let mut fb = Pieces {
            px: vec![Rgb565::BLACK; n],
            sizes,
            next: 0,
        };
        let mut z = vec![u16::MAX; n];
        let mut db = DepthBuffer::new(&mut z, W).unwrap();
        draw_scene(&scene, &tris, how, perspective, &mut fb, &mut db);
        let name: &'static str = match sizes.len() {
            1 if sizes[0] == 1 => "1-pixel pieces",
            1 if sizes[0] == 3 => "3-pixel pieces",
            1 => "7-pixel pieces",
            _ => "1,3,7,2,5-pixel pieces",
        };
        out.push((name, fb.px));
    }
    out
}

fn assert_same(how: Draw, perspective: bool) {
    let f = frames(how, perspective);
    let (_, base) = &f[0];
    let lit = base.iter().filter(|p| **p != Rgb565::BLACK).count();
    assert!(
        lit > 20_000,
        "{how:?}: the sphere is drawn ({lit} lit pixels)"
    );
    for (name, px) in &f[1..] {
        let diff: Vec<usize> = (0..base.len()).filter(|&i| px[i] != base[i]).collect();
        assert!(
            diff.is_empty(),
            "{how:?} perspective={perspective}: {name} differs from SliceFramebuffer on {} pixels, first at ({}, {}): {:?} vs {:?}",
            diff.len(),
            diff[0] % W as usize,
            diff[0] / W as usize,
            px[diff[0]],
            base[diff[0]]
        );
    }
}

#[test]
fn gouraud_gamma_same_pixels_through_every_framebuffer() {
    assert_same(Draw::GouraudGamma, false);
}

#[test]
fn phong_same_pixels_through_every_framebuffer() {
    assert_same(Draw::Phong, false);
}

#[test]
fn perspective_same_pixels_through_every_framebuffer() {
    assert_same(Draw::GouraudGamma, true);
    assert_same(Draw::Phong, true);
}
