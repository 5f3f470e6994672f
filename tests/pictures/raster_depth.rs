//! Depth test: nearer wins regardless of drawing order; runs of passing
//! pixels; a passing pixel writes its depth (the frame's depth buffer: a
//! pixel passes when `z < stored`, and then stores `z`).

use std::cell::Cell;

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use fixshade::framebuffer::DrawBand;
use fixshade::render::Corner;
use fixshade::shade::{Kernel, VertexIn};
use fixshade_testkit::support::{corner, full, Tris, S};

/// Paints a solid grey; counts the runs it is handed.
#[derive(Debug)]
struct Paint(u8, Cell<u32>);

impl Kernel for &Paint {
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
        self.1.set(self.1.get() + 1);
        out.fill(Gray8::new(self.0));
    }
}

/// A screen-space triangle with corners in whole pixels and depths `z`.
fn tri(x0: i32, y0: i32, x1: i32, y1: i32, x2: i32, y2: i32, z: [i32; 3]) -> [Corner; 3] {
    [
        corner(x0 * S, y0 * S, z[0], 0),
        corner(x1 * S, y1 * S, z[1], 0),
        corner(x2 * S, y2 * S, z[2], 0),
    ]
}

/// The triangles `(corners, grey)` drawn in order with a depth buffer.
fn render(w: u32, h: u32, tris: &[([Corner; 3], u8)]) -> (Vec<u8>, Vec<u32>) {
    let paints: Vec<Paint> = tris.iter().map(|t| Paint(t.1, Cell::new(0))).collect();
    let mut items: Vec<Tris<&Paint>> = tris
        .iter()
        .zip(&paints)
        .map(|(t, p)| Tris::screen(p, vec![t.0]))
        .collect();
    let mut refs: Vec<&mut dyn DrawBand<Gray8>> = items
        .iter_mut()
        .map(|i| i as &mut dyn DrawBand<Gray8>)
        .collect();
    let px = full(w, h, Gray8::new(0), true, &mut refs);
    (
        px.iter().map(|p| p.luma()).collect(),
        paints.iter().map(|p| p.1.get()).collect(),
    )
}

#[test]
fn nearer_wins_in_either_order() {
    // A: flat at z = 1000 (grey 10). B: slanted from z = 0 (left) to 2000 (right), grey 20.
    let a = (tri(0, 0, 32, 0, 0, 32, [1000; 3]), 10);
    let b = (tri(0, 4, 32, 4, 32, 28, [0, 2000, 2000]), 20);
    let (ab, _) = render(32, 32, &[a, b]);
    let (ba, _) = render(32, 32, &[b, a]);
    assert_eq!(ab, ba);
    assert!(ab.contains(&10) && ab.contains(&20));
    assert_eq!(ab[20 * 32 + 10], 10, "only A");
    assert_eq!(ab[2 * 32 + 31], 0, "neither");
    // Where both cover, B is nearer only left of x = 16 (z_B = 2000·x/32 < 1000).
    assert_eq!(ab[10 * 32 + 12], 20);
    assert_eq!(ab[10 * 32 + 18], 10);
}

#[test]
fn runs_split_around_failing_pixels_and_passing_pixels_write_depth() {
    // An occluder over columns 4..8 (z = 0, grey 9), then a quad over the
    // whole 16 × 4 frame at z = 100 (grey 7): every row of the quad is cut
    // into two runs around the occluder. Then a quad at z = 200 (grey 5):
    // hidden everywhere, since the passing pixels wrote their depth (the
    // old per-triangle depth_test/depth_write switches are gone: the frame's
    // depth buffer always does both).
    let occluder = [
        (tri(4, 0, 8, 0, 8, 4, [0; 3]), 9),
        (tri(4, 0, 8, 4, 4, 4, [0; 3]), 9),
    ];
    let quad = |z: i32, g: u8| {
        [
            (tri(0, 0, 16, 0, 16, 4, [z; 3]), g),
            (tri(0, 0, 16, 4, 0, 4, [z; 3]), g),
        ]
    };
    let scene: Vec<_> = occluder
        .iter()
        .chain(&quad(100, 7))
        .chain(&quad(200, 5))
        .copied()
        .collect();
    let (px, calls) = render(16, 4, &scene);
    assert!(px.chunks(16).all(|row| row[4..8].iter().all(|&p| p == 9)));
    assert_eq!(px.iter().filter(|&&p| p == 7).count(), 12 * 4);
    assert!(!px.contains(&5), "the far quad shows: depth not written");
    assert!(
        calls[2] + calls[3] >= 8,
        "each row is cut into runs around the occluder: {calls:?}"
    );
    assert_eq!(calls[4] + calls[5], 0, "{calls:?}");
}

/// A sliver on the outline of the standard sphere seen in perspective
/// (`tests/pictures/one_pipeline.rs`), in screen space: every depth it writes lies
/// within its corners' depths.
#[test]
fn sliver_depth_within_its_corners() {
    let tri = [
        (3097, 3660, 11073),
        (3164, 3626, 20685),
        (3435, 3480, 16405),
    ]
    .map(|(x, y, z)| corner(x, y, z, 0));
    let mut px = vec![Gray8::new(0); 240 * 240];
    let mut depth = vec![0u16; 240 * 240];
    let paint = Paint(255, Cell::new(0));
    let mut item = Tris::screen(&paint, vec![tri]);
    fixshade::framebuffer::FullFrame::new(240, 240, &mut px, Some(&mut depth))
        .unwrap()
        .render(Gray8::new(0), &mut [&mut item])
        .unwrap();
    let drawn: Vec<(usize, u16)> = (0..px.len())
        .filter(|&i| px[i].luma() == 255)
        .map(|i| (i, depth[i]))
        .collect();
    assert!(!drawn.is_empty());
    for (i, z) in drawn {
        assert!(
            (11073..=20685).contains(&z),
            "pixel ({}, {}): depth {z}",
            i % 240,
            i / 240
        );
    }
}
