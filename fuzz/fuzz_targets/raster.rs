//! Rasterizing and shading arbitrary triangles into a small framebuffer that
//! hands spans out in odd pieces and accepts only some rows (like a band):
//! wild screen positions, depths, `1/w`, attributes, `f32` eye-space positions
//! and normals, every tier and shading mode, screen-linear and perspective.
//! No panic, no wrap (overflow checks on), no span outside the clip rectangle
//! or the triangle's bounding box, no pixel outside the piece it was handed,
//! attribute values inside the vertex range, no pixel drawn twice by one triangle.
#![no_main]

use core::ops::Range;
use embedded_graphics_core::pixelcolor::Rgb565;
use fixshade::lighting::{BlinnPhong, Lighting, LinearFog, LocalViewer};
use fixshade::material::Material;
use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade::raster::{
    draw_triangle, draw_triangle_perspective, Cull, RasterOptions, RasterVertex, SpanShader,
    SUBPIXEL_BITS,
};
use fixshade::shade::{
    FlatShading, GouraudShading, Linear, PhongShading, ShadeVertex, Shader, Shading,
};
use fixshade::target::{DepthBuffer, Framebuffer};
use fixshade_fuzz::Input;
use libfuzzer_sys::fuzz_target;

const MAX_W: u32 = 48;

/// A framebuffer of `width` × `height` accepting rows `rows`, handing spans out
/// in pieces whose lengths cycle through `sizes`; checks every span against the
/// clip rectangle and the bounding box of the triangle being drawn.
struct Checked {
    width: u32,
    rows: Range<i32>,
    sizes: [u32; 3],
    next: usize,
    /// Sub-pixel bounding box of the triangle: x0, x1, y0, y1.
    bbox: [i64; 4],
    hits: Vec<u8>,
}

impl Checked {
    fn check(&self, x: u32, y: i32, len: u32) {
        assert!(len > 0, "empty span");
        assert!(self.rows.contains(&y), "row {y} outside {:?}", self.rows);
        assert!(
            x.checked_add(len).is_some_and(|e| e <= self.width),
            "span {x}+{len} beyond width {}",
            self.width
        );
        let c = |p: i64| (p << SUBPIXEL_BITS) + (1 << (SUBPIXEL_BITS - 1));
        let [x0, x1, y0, y1] = self.bbox;
        let (first, last) = (c(i64::from(x)), c(i64::from(x) + i64::from(len) - 1));
        assert!(
            first >= x0 && last <= x1 && c(i64::from(y)) >= y0 && c(i64::from(y)) <= y1,
            "span ({x}..{}, {y}) outside the bounding box {:?}",
            x + len,
            self.bbox
        );
    }
}

impl Framebuffer for Checked {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn width(&self) -> u32 {
        self.width
    }
    fn rows(&self) -> Range<i32> {
        self.rows.clone()
    }
    fn fill_span<F: FnMut(u32, &mut [Rgb565])>(
        &mut self,
        x: u32,
        y: i32,
        len: u32,
        mut fill: F,
    ) -> Result<(), Self::Error> {
        self.check(x, y, len);
        let mut at = x;
        let mut piece = [Rgb565::new(0, 0, 0); MAX_W as usize];
        while at < x + len {
            let n = self.sizes[self.next % 3].clamp(1, MAX_W).min(x + len - at);
            self.next += 1;
            fill(at, &mut piece[..n as usize]);
            for k in at..at + n {
                let i = (y - self.rows.start) as usize * self.width as usize + k as usize;
                self.hits[i] += 1;
            }
            at += n;
        }
        Ok(())
    }
}

/// Checks the attribute values handed to the shader.
struct Attrs {
    lo: [i32; 2],
    hi: [i32; 2],
}

impl SpanShader<2> for Attrs {
    type Color = Rgb565;
    fn shade_span(
        &mut self,
        _x: i32,
        _y: i32,
        start: &[i32; 2],
        step: &[i32; 2],
        out: &mut [Rgb565],
    ) {
        for i in 0..2 {
            for k in 0..out.len() as i64 {
                let v = i64::from(start[i]) + k * i64::from(step[i]);
                assert!(
                    v >= i64::from(self.lo[i]) && v <= i64::from(self.hi[i]),
                    "attribute {i} = {v} at pixel {k} outside {}..={}",
                    self.lo[i],
                    self.hi[i]
                );
            }
        }
    }
}

fn framebuffer(inp: &mut Input) -> Checked {
    let width = 1 + u32::from(inp.u8()) % MAX_W;
    let height = 1 + i32::from(inp.u8()) % 40;
    let r0 = i32::from(inp.u8()) % height;
    let r1 = r0 + 1 + i32::from(inp.u8()) % (height - r0);
    Checked {
        width,
        rows: r0..r1,
        sizes: [1 + u32::from(inp.u8() % 9), 1 + u32::from(inp.u8() % 9), 64],
        next: 0,
        bbox: [0; 4],
        hits: vec![0; width as usize * (r1 - r0) as usize],
    }
}

fn set_bbox(fb: &mut Checked, xy: [[i32; 2]; 3]) {
    let xs = xy.map(|p| i64::from(p[0]));
    let ys = xy.map(|p| i64::from(p[1]));
    fb.bbox = [
        *xs.iter().min().unwrap(),
        *xs.iter().max().unwrap(),
        *ys.iter().min().unwrap(),
        *ys.iter().max().unwrap(),
    ];
    fb.hits.fill(0);
}

fn no_double(fb: &Checked) {
    assert!(
        fb.hits.iter().all(|&h| h <= 1),
        "a pixel was handed out twice for one triangle"
    );
}

fn coord(inp: &mut Input) -> i32 {
    // mostly near the frame (sub-pixels), sometimes anywhere
    match inp.u8() % 4 {
        0 => inp.i32(),
        _ => i32::from(inp.u32() as u16 as i16) / 32,
    }
}

fn options(inp: &mut Input) -> RasterOptions {
    let b = inp.u8();
    RasterOptions {
        cull: [Cull::None, Cull::Back, Cull::Front][usize::from(b % 3)],
        depth_test: b & 4 != 0,
        depth_write: b & 8 != 0,
    }
}

fn raw(inp: &mut Input) {
    let mut fb = framebuffer(inp);
    let v: [RasterVertex<2>; 3] = core::array::from_fn(|_| RasterVertex {
        x: coord(inp),
        y: coord(inp),
        z: inp.u32() as u16,
        inv_w: inp.i32(),
        attrs: [inp.i32(), inp.i32()],
    });
    set_bbox(&mut fb, v.map(|p| [p.x, p.y]));
    let limit = fixshade::raster::ATTR_LIMIT;
    let a = |i: usize| v.map(|p| p.attrs[i].clamp(-limit, limit));
    let lo = [0, 1].map(|i| *a(i).iter().min().unwrap());
    let hi = [0, 1].map(|i| *a(i).iter().max().unwrap());
    let opts = options(inp);
    let mut shader = Attrs { lo, hi };
    let mut z = vec![u16::MAX; (fb.width * fb.rows.end as u32) as usize];
    let use_depth = inp.u8() & 1 == 1;
    let mut db = DepthBuffer::new(&mut z, fb.width).unwrap();
    let depth = if use_depth { Some(&mut db) } else { None };
    let _ = if inp.u8() & 1 == 0 {
        draw_triangle(&mut fb, depth, &v, &opts, &mut shader)
    } else {
        draw_triangle_perspective(&mut fb, depth, &v, &opts, &mut shader)
    };
    no_double(&fb);
}

fn shaded<S: Scalar>(inp: &mut Input) {
    let mut fb = framebuffer(inp);
    let light = inp.light();
    let lights = heapless::Vec::<_, 1>::from_iter(fixshade::light::AnyLight::<S>::new(&light));
    let Ok(m) = Material::<S>::new(&inp.material()) else {
        return;
    };
    let mut lit = Lighting::<S, _, BlinnPhong>::new(lights, m);
    if let Ok(v) = LocalViewer::<S>::new(inp.f3()) {
        if let Ok(f) = LinearFog::<S>::new(inp.f32(), inp.f32(), inp.f3()) {
            return draw_modes(inp, &mut fb, &lit.with_viewer(v).with_fog(f));
        }
        return draw_modes(inp, &mut fb, &lit.with_viewer(v));
    }
    lit = lit.with_global_ambient_f32(inp.f3());
    draw_modes(inp, &mut fb, &lit);
}

fn draw_modes<S: Scalar, I: fixshade::lighting::Illuminate<Scalar = S>>(
    inp: &mut Input,
    fb: &mut Checked,
    lit: &I,
) {
    let xy: [[i32; 2]; 3] = core::array::from_fn(|_| [coord(inp), coord(inp)]);
    let tri: [ShadeVertex<S>; 3] = core::array::from_fn(|i| {
        ShadeVertex::new(xy[i], inp.u32() as u16, inp.i32(), inp.f3(), inp.f3())
    });
    let opts = options(inp);
    let persp = inp.u8() & 1 == 1;
    let mut z = vec![u16::MAX; (fb.width * fb.rows.end as u32) as usize];
    let mut db = DepthBuffer::new(&mut z, fb.width).unwrap();
    macro_rules! run {
        ($mode:expr) => {{
            set_bbox(fb, xy);
            let mut s = Shader::new($mode, lit, Linear);
            let _ = if persp {
                s.draw_perspective(fb, Some(&mut db), &tri, &opts)
            } else {
                s.draw(fb, Some(&mut db), &tri, &opts)
            };
            no_double(fb);
        }};
    }
    run!(FlatShading);
    run!(GouraudShading);
    run!(PhongShading);
}

fuzz_target!(|data: &[u8]| {
    let mut inp = Input(data);
    match inp.u8() % 7 {
        0 | 1 => raw(&mut inp),
        2 => shaded::<Q14<1>>(&mut inp),
        3 => shaded::<Q14<2>>(&mut inp),
        4 => shaded::<Q30<3>>(&mut inp),
        5 => shaded::<f32>(&mut inp),
        _ => shaded::<F32Fast<2>>(&mut inp),
    }
});
