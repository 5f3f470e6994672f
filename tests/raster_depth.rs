//! Depth test: nearer wins regardless of drawing order; runs of passing pixels.

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use fixshade::raster::{draw_triangle, RasterOptions, RasterVertex, SpanShader, SUBPIXEL_BITS};
use fixshade::target::{DepthBuffer, SliceFramebuffer};

const S: i32 = 1 << SUBPIXEL_BITS;

/// Paints a solid grey; counts shader calls.
struct Solid(u8, u32);
impl SpanShader<0> for Solid {
    type Color = Gray8;
    fn shade_span(&mut self, _: i32, _: i32, _: &[i32; 0], _: &[i32; 0], out: &mut [Gray8]) {
        self.1 += 1;
        out.fill(Gray8::new(self.0));
    }
}

fn tri(x0: i32, y0: i32, x1: i32, y1: i32, x2: i32, y2: i32, z: [u16; 3]) -> [RasterVertex<0>; 3] {
    let v = |x: i32, y: i32, z: u16| RasterVertex {
        x: x * S,
        y: y * S,
        z,
        inv_w: 1,
        attrs: [],
    };
    [v(x0, y0, z[0]), v(x1, y1, z[1]), v(x2, y2, z[2])]
}

fn render(order: [usize; 2]) -> Vec<u8> {
    // A: flat at z = 1000 (grey 10). B: slanted from z = 0 (left) to 2000 (right), grey 20.
    let tris = [
        (tri(0, 0, 32, 0, 0, 32, [1000; 3]), 10),
        (tri(0, 4, 32, 4, 32, 28, [0, 2000, 2000]), 20),
    ];
    let mut px = vec![Gray8::new(0); 32 * 32];
    let mut fb = SliceFramebuffer::new(&mut px, 32, 32).unwrap();
    let mut z = vec![0u16; 32 * 32];
    let mut depth = DepthBuffer::new(&mut z, 32).unwrap();
    depth.clear(u16::MAX);
    for i in order {
        let (t, grey) = tris[i];
        draw_triangle(
            &mut fb,
            Some(&mut depth),
            &t,
            &RasterOptions::default(),
            &mut Solid(grey, 0),
        )
        .unwrap();
    }
    px.iter().map(|p| p.luma()).collect()
}

#[test]
fn nearer_wins_in_either_order() {
    let a = render([0, 1]);
    let b = render([1, 0]);
    assert_eq!(a, b);
    assert!(a.contains(&10) && a.contains(&20));
    assert_eq!(a[20 * 32 + 10], 10, "only A");
    assert_eq!(a[2 * 32 + 31], 0, "neither");
    // Where both cover, B is nearer only left of x = 16 (z_B = 2000·x/32 < 1000).
    assert_eq!(a[10 * 32 + 12], 20);
    assert_eq!(a[10 * 32 + 18], 10);
}

#[test]
fn runs_split_around_failing_pixels_and_write_only_when_asked() {
    let mut px = vec![Gray8::new(0); 16 * 4];
    let mut fb = SliceFramebuffer::new(&mut px, 16, 4).unwrap();
    let mut z = vec![500u16; 16 * 4];
    // Columns 4..8 of every row are nearer than anything drawn.
    for row in z.chunks_mut(16) {
        row[4..8].fill(0);
    }
    let mut depth = DepthBuffer::new(&mut z, 16).unwrap();
    let quad = [
        tri(0, 0, 16, 0, 16, 4, [100; 3]),
        tri(0, 0, 16, 4, 0, 4, [100; 3]),
    ];
    let opts = RasterOptions {
        depth_write: false,
        ..RasterOptions::default()
    };
    let mut shader = Solid(7, 0);
    for t in &quad {
        draw_triangle(&mut fb, Some(&mut depth), t, &opts, &mut shader).unwrap();
    }
    assert!(px
        .chunks(16)
        .all(|row| row[4..8].iter().all(|p| p.luma() == 0)));
    assert_eq!(px.iter().filter(|p| p.luma() == 7).count(), 12 * 4);
    assert_eq!(depth.get(0, 0), Some(500), "no depth write");
    assert!(
        shader.1 >= 8,
        "each row is cut into runs around the occluder"
    );
}
