//! Perspective meshes through the renderer: coverage counted per pixel against
//! the exact projection, for sheets crossing the near plane and reaching far
//! beyond the screen.

/// Fixed proptest seeds (shared with the integration tests: `fixshade-testkit`,
/// which passes no `fixshade` type, so the other instance of the crate it links
/// does not matter here).
use fixshade_testkit::seeded;

use super::*;
use crate::camera::{Camera, Perspective, Viewport};
use crate::framebuffer::{Bands, FullFrame};
use crate::mesh::Mesh;
use crate::num::Mat4;
use crate::raster::Cull;
use crate::shade::{Kernel, VertexIn};
use crate::test_rng::Rng;
use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use proptest::prelude::*;
use std::format;
use std::string::String;
use std::vec;
use std::vec::Vec;

/// Counts the writes of every pixel.
#[derive(Clone, Copy, Debug)]
struct Count;

impl Kernel for Count {
    type Color = Gray8;
    type Vertex = ();
    type Varyings = [i32; 0];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;

    fn vertex(&self, _: &VertexIn) {}

    fn triangle(&self, _: [&(); 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 0]; 3]) {
        ((), [[]; 3])
    }

    fn span(&self, _: &(), _: &[i32; 0], _: &[i32; 0], _: i32, _: i32, out: &mut [Gray8]) {
        for c in out {
            *c = Gray8::new(c.luma().saturating_add(1));
        }
    }
}

const W: u32 = 96;
const FRAC: u8 = 8;

fn camera() -> Camera<Perspective> {
    Camera::perspective(1.0, 1.0, 1.0, 100.0, Viewport::new(0, 0, W, W).unwrap()).unwrap()
}

/// A sheet: an `n × n` grid of quads on the plane through `o` spanned by `u`,
/// `v` (eye space = model space), each quad split along a chosen diagonal.
struct Sheet {
    pos: Vec<[i16; 3]>,
    tris: Vec<[u16; 3]>,
    corners: [[f64; 3]; 4],
}

fn sheet(o: [f64; 3], u: [f64; 3], v: [f64; 3], n: usize, diag: u64) -> Sheet {
    let q = |x: f64| (x * f64::from(1 << FRAC)).round().clamp(-32767.0, 32767.0) as i16;
    let at = |i: usize, j: usize| {
        let (a, b) = (i as f64 / n as f64 - 0.5, j as f64 / n as f64 - 0.5);
        [0, 1, 2].map(|k| q(o[k] + a * u[k] + b * v[k]))
    };
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            pos.push(at(i, j));
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u16;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (diag >> ((i + j * n) % 64)) & 1 == 0 {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            } else {
                tris.push([a, b, d]);
                tris.push([b, c, d]);
            }
        }
    }
    let f = |p: [i16; 3]| p.map(|c| f64::from(c) / f64::from(1 << FRAC));
    let corners = [f(at(0, 0)), f(at(n, 0)), f(at(n, n)), f(at(0, n))];
    Sheet { pos, tris, corners }
}

/// Renders `s` with the counting kernel, no culling, no depth, in `band`-row
/// bands (0: a full frame).
fn counts(s: &Sheet, band: u32) -> Vec<u8> {
    let normals = vec![[0i16; 3]; s.pos.len()];
    let mesh = Mesh::new(&s.pos, &normals, &s.tris, FRAC).unwrap();
    let t = camera().mesh_transform(&Mat4::IDENTITY, FRAC).unwrap();
    let layout = if band == 0 {
        Layout::full(W, W).unwrap()
    } else {
        Layout::banded(W, W, band).unwrap()
    };
    let mut cache = vec![CachedVertex::<()>::default(); s.pos.len()];
    let mut bins = vec![0u16; bins_len(s.tris.len(), layout.bands() as usize)];
    let mut carry = vec![Carry::default(); 2 * s.tris.len()];
    let mut draw = MeshDraw::new(
        layout,
        mesh,
        &t,
        Count,
        MeshMemory {
            vertices: &mut cache,
            bins: &mut bins,
            carry: &mut carry,
        },
        DrawOptions {
            cull: Cull::None,
            ..DrawOptions::default()
        },
    )
    .unwrap();
    let mut px = vec![Gray8::new(0); (W * W) as usize];
    if band == 0 {
        FullFrame::new(W, W, &mut px, None)
            .unwrap()
            .render(Gray8::new(0), &mut [&mut draw])
            .unwrap();
    } else {
        let mut strip = vec![Gray8::new(0); (W * band) as usize];
        let mut out = Collect(&mut px);
        Bands::new(layout, &mut strip, None)
            .unwrap()
            .render(&mut out, Gray8::new(0), &mut [&mut draw])
            .unwrap();
    }
    px.iter().map(|c| c.luma()).collect()
}

/// A `DrawTarget` over a `W × W` slice.
struct Collect<'a>(&'a mut [Gray8]);

impl embedded_graphics_core::geometry::OriginDimensions for Collect<'_> {
    fn size(&self) -> embedded_graphics_core::geometry::Size {
        embedded_graphics_core::geometry::Size::new(W, W)
    }
}

impl embedded_graphics_core::draw_target::DrawTarget for Collect<'_> {
    type Color = Gray8;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = embedded_graphics_core::Pixel<Gray8>>,
    {
        for embedded_graphics_core::Pixel(p, c) in pixels {
            if (0..W as i32).contains(&p.x) && (0..W as i32).contains(&p.y) {
                self.0[(p.y as u32 * W + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

/// The exact coverage of a sheet's quad: per pixel, the signed distance (in
/// pixels) of its centre from the boundary of the projected, near-clipped
/// quad (positive inside).
fn exact(s: &Sheet) -> Vec<f64> {
    let cam = camera();
    let m = cam.projection();
    let clip = |p: [f64; 3]| -> [f64; 4] {
        core::array::from_fn(|r| {
            (0..3).map(|c| f64::from(m.m[r][c]) * p[c]).sum::<f64>() + f64::from(m.m[r][3])
        })
    };
    let near = f64::from(cam.near());
    // clip to w ≥ near
    let cs: Vec<[f64; 4]> = s.corners.iter().map(|&p| clip(p)).collect();
    let mut poly = Vec::new();
    for i in 0..4 {
        let (a, b) = (cs[i], cs[(i + 1) % 4]);
        let (da, db) = (a[3] - near, b[3] - near);
        if da >= 0.0 {
            poly.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            poly.push(core::array::from_fn(|k| a[k] + t * (b[k] - a[k])));
        }
    }
    let w = f64::from(W);
    let pts: Vec<(f64, f64)> = poly
        .iter()
        .map(|c| {
            (
                w / 2.0 + w / 2.0 * c[0] / c[3],
                w / 2.0 - w / 2.0 * c[1] / c[3],
            )
        })
        .collect();
    let mut out = vec![-1e9; (W * W) as usize];
    if pts.len() < 3 {
        return out;
    }
    // orientation
    let area: f64 = (0..pts.len())
        .map(|i| {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    let sgn = area.signum();
    for r in 0..W as usize {
        for c in 0..W as usize {
            let p = (c as f64 + 0.5, r as f64 + 0.5);
            let mut d = f64::INFINITY;
            for i in 0..pts.len() {
                let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
                let (ex, ey) = (b.0 - a.0, b.1 - a.1);
                let len = (ex * ex + ey * ey).sqrt();
                if len < 1e-12 {
                    continue;
                }
                let cross = ex * (p.1 - a.1) - ey * (p.0 - a.0);
                d = d.min(sgn * cross / len);
            }
            out[r * W as usize + c] = d;
        }
    }
    out
}

fn check(s: &Sheet) -> Result<(), String> {
    let full = counts(s, 0);
    if let Some(i) = full.iter().position(|&n| n > 1) {
        return Err(format!("pixel {i} drawn {} times", full[i]));
    }
    let ex = exact(s);
    for (i, (&n, &d)) in full.iter().zip(&ex).enumerate() {
        if d > 1.0 && n != 1 {
            return Err(format!(
                "hole at pixel ({}, {}), {d:.2} px inside",
                i % W as usize,
                i / W as usize
            ));
        }
        if d < -1.0 && n != 0 {
            return Err(format!(
                "pixel ({}, {}) drawn {:.2} px outside",
                i % W as usize,
                i / W as usize,
                -d
            ));
        }
    }
    for band in [1, 7, 16] {
        if counts(s, band) != full {
            return Err(format!("{band}-row bands differ from the full frame"));
        }
    }
    Ok(())
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-9);
    v.map(|c| c / l)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[test]
fn floor_through_the_near_plane_is_watertight() {
    // a floor from behind the eye to far ahead, much wider than the view
    let s = sheet(
        [0.0, -1.5, -40.0],
        [120.0, 0.0, 0.0],
        [0.0, 0.0, 90.0],
        9,
        0x5A5A_1234,
    );
    check(&s).unwrap();
    assert!(counts(&s, 0).iter().filter(|&&n| n == 1).count() > 2000);
}

proptest! {
    #![proptest_config(seeded::config("render::tests", 200))]

    /// Random sheets crossing the near plane, many reaching far beyond the
    /// screen (up to ~120 units to the side at the near plane): no pixel twice,
    /// none missing or extra away from the exact boundary, bands = full frame.
    #[test]
    fn sheets_crossing_the_near_plane(
        o in prop::array::uniform3(-20.0f64..20.0),
        oz in -40.0f64..0.0,
        a in prop::array::uniform3(-1.0f64..1.0),
        b in prop::array::uniform3(-1.0f64..1.0),
        size in 4.0f64..120.0,
        n in 1usize..8,
        diag in any::<u64>(),
    ) {
        let u = unit(a);
        let v = unit(cross(u, unit(b)));
        // a plane passing near the eye is seen edge-on: the quantised
        // positions (1/256) then fold it over itself in projection
        let nrm = unit(cross(u, v));
        let dist = nrm[0] * o[0] + nrm[1] * o[1] + nrm[2] * oz;
        prop_assume!(dist.abs() >= 1.0);
        let s = sheet([o[0], o[1], oz], u.map(|c| c * size), v.map(|c| c * size), n, diag);
        prop_assert!(check(&s).is_ok(), "{:?}", check(&s));
    }
}

/// 1 000 random sheets (seeded): every one watertight and within a pixel of
/// the exact projection; most of them cross the near plane, many reach
/// beyond the ±32 768-pixel range the old screen transform clamped to.
#[test]
fn sheet_sweep() {
    let mut r = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut tested, mut crossing, mut beyond) = (0, 0, 0);
    let t = camera().mesh_transform(&Mat4::IDENTITY, FRAC).unwrap();
    while tested < 1000 {
        let o = [r.f(-20.0, 20.0), r.f(-20.0, 20.0), r.f(-40.0, 0.0)];
        let u = unit([r.f(-1.0, 1.0), r.f(-1.0, 1.0), r.f(-1.0, 1.0)]);
        let v = unit(cross(
            u,
            unit([r.f(-1.0, 1.0), r.f(-1.0, 1.0), r.f(-1.0, 1.0)]),
        ));
        let nrm = unit(cross(u, v));
        if (nrm[0] * o[0] + nrm[1] * o[1] + nrm[2] * o[2]).abs() < 1.0 {
            continue;
        }
        let size = r.f(4.0, 120.0);
        let n = 1 + (r.next() % 7) as usize;
        let s = sheet(o, u.map(|c| c * size), v.map(|c| c * size), n, r.next());
        let c: Vec<_> = s.pos.iter().map(|p| t.clip(*p)).collect();
        let near = t.clip_space().near();
        if c.iter().any(|c| c.w < near) && c.iter().any(|c| c.w >= near) {
            crossing += 1;
        }
        if c.iter()
            .any(|c| c.w > 0 && (i64::from(c.x).abs() > (32768 * 16) * i64::from(c.w)))
        {
            beyond += 1;
        }
        if let Err(e) = check(&s) {
            panic!("sheet {tested}: {e}");
        }
        tested += 1;
    }
    assert!(
        crossing > 300 && beyond > 10,
        "{crossing} crossing, {beyond} beyond"
    );
}
