//! The same scene gives the same pixels however the frame is split (issue
//! 11, item 9): a frame rendered whole (`FullFrame`) equals the frame
//! rendered in bands of 1, 3 and 7 rows (`Bands`, as the display receives
//! it), bit for bit, and the per-triangle front (`render::draw_triangle` with
//! the corners of the mesh's transform) equals `MeshDraw`, bit for bit, both
//! ways. A triangle continued in the next band must resume its edges and
//! values exactly (the old test handed spans out in pieces of 1, 3 and 7
//! pixels to the removed `Framebuffer` trait; bands of 1, 3 and 7 rows now
//! cut every triangle the same way).
//!
//! Scene: a lit sphere under four point lights (`f32`, Blinn-Phong, the
//! general kernels), Gouraud through a gamma table and Phong (linear),
//! orthographic and perspective (every value perspective-correct).

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::camera::Viewport;
use fixshade::camera::{Camera, MeshTransform, Orthographic, Perspective, Projection};
use fixshade::color::Linear;
use fixshade::color::{GammaTable, Transfer};
use fixshade::lighting::Viewed;
use fixshade::lighting::{
    AmbientSource, AnyLight, BlinnPhong, LightDesc, LightKind, Lighting, Material, MaterialDesc,
};
use fixshade::num::Mat4;
use fixshade::raster::Cull;
use fixshade::shade::{GouraudShading, Kernel, PhongShading, Shader};
use fixshade::standard::SPHERE;
use fixshade_testkit::support::mesh_frame;

const W: u32 = 240;

type Lights = heapless::Vec<AnyLight<f32>, 4>;

/// Red plastic under four point lights around the sphere (at (0, 0, −5)).
fn lighting() -> Viewed<Lighting<f32, Lights, BlinnPhong>> {
    let centre = [0.0f32, 0.0, -5.0];
    let point = |dx: f32, dy: f32, dz: f32, k: f32| LightDesc {
        kind: LightKind::Point {
            position: [centre[0] + dx, centre[1] + dy, centre[2] + dz],
            attenuation: [1.0, 0.05, 0.01],
        },
        ambient: [0.0; 3],
        diffuse: [k; 3],
        specular: [k; 3],
    };
    let lights: Lights = [
        point(-2.0, 2.0, 3.0, 0.5),
        point(2.5, 1.0, 2.0, 0.4),
        point(0.0, -2.5, 2.5, 0.3),
        point(-1.0, 0.0, 4.0, 0.3),
    ]
    .iter()
    .map(|d| AnyLight::new(d).unwrap())
    .collect();
    let red = MaterialDesc::classic([1.0, 0.1, 0.1], AmbientSource::Object, 0.1, 0.7, 0.5, 32.0);
    Lighting::new(lights, Material::new(&red).unwrap())
        .with_global_ambient_f32([0.1; 3])
        .eye_space()
}

fn ortho() -> MeshTransform<Orthographic> {
    fixshade::standard::transform().unwrap()
}

fn persp() -> MeshTransform<Perspective> {
    Camera::perspective(0.7, 1.0, 1.0, 20.0, Viewport::new(0, 0, W, W).unwrap())
        .unwrap()
        .with_view(Mat4::translate([0.3, -0.2, -3.2]))
        .mesh_transform(&Mat4::rotate_y(0.5).mul(&Mat4::rotate_x(0.4)), SPHERE.frac)
        .unwrap()
}

/// Every split of the frame, by both drawers, equals `MeshDraw`'s whole frame.
fn assert_same<K: Kernel<Color = Rgb565> + Copy, P: Projection>(
    what: &str,
    t: &MeshTransform<P>,
    k: K,
) {
    let frame = |rows: u32, front: bool| {
        mesh_frame(
            W,
            W,
            rows,
            SPHERE.mesh(),
            t,
            k,
            Cull::Back,
            front,
            Rgb565::BLACK,
        )
    };
    let base = frame(W, false);
    let lit = base.iter().filter(|p| **p != Rgb565::BLACK).count();
    assert!(
        lit > 20_000,
        "{what}: the sphere is drawn ({lit} lit pixels)"
    );
    for front in [false, true] {
        for rows in [W, 1, 3, 7] {
            if (rows, front) == (W, false) {
                continue;
            }
            let px = frame(rows, front);
            let diff: Vec<usize> = (0..base.len()).filter(|&i| px[i] != base[i]).collect();
            let how = if front { "draw_triangle" } else { "MeshDraw" };
            assert!(
                diff.is_empty(),
                "{what}: {how} in {rows}-row bands differs from MeshDraw whole on {} pixels, first at ({}, {}): {:?} vs {:?}",
                diff.len(),
                diff[0] % W as usize,
                diff[0] / W as usize,
                px[diff[0]],
                base[diff[0]]
            );
        }
    }
}

#[test]
fn gouraud_gamma_same_pixels_however_the_frame_is_split() {
    let l = lighting();
    let table = GammaTable::<1024>::new(Transfer::Srgb).unwrap();
    assert_same("gouraud", &ortho(), Shader::new(GouraudShading, &l, &table));
}

#[test]
fn phong_same_pixels_however_the_frame_is_split() {
    let l = lighting();
    assert_same("phong", &ortho(), Shader::new(PhongShading, &l, Linear));
}

#[test]
fn perspective_same_pixels_however_the_frame_is_split() {
    let l = lighting();
    let table = GammaTable::<1024>::new(Transfer::Srgb).unwrap();
    assert_same(
        "perspective gouraud",
        &persp(),
        Shader::new(GouraudShading, &l, &table),
    );
    assert_same(
        "perspective phong",
        &persp(),
        Shader::new(PhongShading, &l, Linear),
    );
}

/// The Q14 fast per-pixel kernels (issue 21, item 4: `IncrementalPhongShading`
/// gave other pixels when a span was handed out in pieces): the incremental
/// and quadratic kernels, and `PhongShading` choosing the incremental one,
/// give the same pixels in every band height and through `draw_triangle`,
/// orthographic and perspective.
#[test]
fn fast_per_pixel_kernels_same_pixels_however_the_frame_is_split() {
    use fixshade::num::Q14;
    use fixshade::shade::{IncrementalPhongShading, QuadraticPhongShading};
    let blinn = fixshade::standard::blinn::<Q14>().unwrap();
    let array: Viewed<Lighting<Q14, [_; 1], BlinnPhong>> = Lighting::new(
        [fixshade::standard::light::<Q14>().unwrap()],
        Material::new(&fixshade::standard::material()).unwrap(),
    )
    .eye_space();
    assert_same(
        "picked incremental",
        &ortho(),
        Shader::new(PhongShading, &blinn, Linear),
    );
    assert_same(
        "incremental",
        &ortho(),
        Shader::new(IncrementalPhongShading, &array, Linear),
    );
    assert_same(
        "incremental, perspective",
        &persp(),
        Shader::new(IncrementalPhongShading, &array, Linear),
    );
    assert_same(
        "quadratic",
        &ortho(),
        Shader::new(QuadraticPhongShading, &array, Linear),
    );
}

/// 2D over 3D (issue 35, item 2): a background rectangle before the sphere,
/// a label, a frame and a disc after it, in bands of 1, 3, 7 and 8 rows and
/// whole, give the sphere's frame with the same drawables drawn over it by
/// embedded-graphics into a plain display, bit for bit (the label crossing
/// band boundaries, shapes partly off screen).
#[test]
fn drawables_over_and_under_the_meshes_in_any_bands() {
    use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::{Circle, PrimitiveStyle, Rectangle};
    use embedded_graphics::text::Text;
    use fixshade::framebuffer::DrawBand;
    use fixshade_testkit::support::{banded, full, Collect};

    let lighting = lighting();
    let k = Shader::new(GouraudShading, &lighting, Linear);
    let t = ortho();
    let background = Rectangle::new(Point::new(-10, 100), Size::new(60, 50))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::BLUE));
    let label = Text::new(
        "fixshade 2D over 3D",
        Point::new(4, 118),
        MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE),
    );
    let border = Rectangle::new(Point::new(1, 1), Size::new(W - 2, W - 2))
        .into_styled(PrimitiveStyle::with_stroke(Rgb565::YELLOW, 3));
    let disc =
        Circle::new(Point::new(200, 225), 30).into_styled(PrimitiveStyle::with_fill(Rgb565::GREEN));

    // the expected frame: the sphere whole, the background under it (where
    // the sphere leaves it), the others drawn over it
    let bare = fixshade_testkit::support::mesh_frame(
        W,
        W,
        W,
        SPHERE.mesh(),
        &t,
        k,
        Cull::Back,
        false,
        Rgb565::BLACK,
    );
    let mut under = Collect::new(W, W, Rgb565::BLACK);
    background.draw(&mut under).unwrap();
    let mut want = Collect::new(W, W, Rgb565::BLACK);
    want.px = bare
        .iter()
        .zip(&under.px)
        .map(|(s, u)| if *s == Rgb565::BLACK { *u } else { *s })
        .collect();
    label.draw(&mut want).unwrap();
    border.draw(&mut want).unwrap();
    disc.draw(&mut want).unwrap();
    let lit = want.px.iter().filter(|p| **p == Rgb565::WHITE).count();
    assert!(lit > 100, "the label is drawn ({lit} white pixels)");

    for rows in [W, 1, 3, 7, 8] {
        let layout = fixshade::framebuffer::Layout::banded(W, W, rows).unwrap();
        let mesh = SPHERE.mesh();
        let mut cache = vec![fixshade::render::CachedVertex::default(); mesh.vertex_count()];
        let mut bins =
            vec![0u16; fixshade::render::bins_len(mesh.triangle_count(), layout.bands() as usize)];
        let mut carry = vec![fixshade::render::Carry::default(); 2 * mesh.triangle_count()];
        let mut draw = fixshade::render::MeshDraw::new(
            layout,
            mesh,
            &t,
            k,
            fixshade::render::MeshMemory {
                vertices: &mut cache,
                bins: &mut bins,
                carry: &mut carry,
            },
            fixshade::render::DrawOptions::default(),
        )
        .unwrap();
        let (mut bg, mut label, mut border, mut disc) = (background, label, border, disc);
        let mut items: [&mut dyn DrawBand<Rgb565>; 5] =
            [&mut bg, &mut draw, &mut label, &mut border, &mut disc];
        let got = if rows == W {
            full(W, W, Rgb565::BLACK, true, &mut items)
        } else {
            banded(W, W, rows, Rgb565::BLACK, true, &mut items)
        };
        let diff = (0..got.len()).filter(|&i| got[i] != want.px[i]).count();
        assert_eq!(diff, 0, "{rows}-row bands: {diff} pixels differ from the sphere with the drawables drawn over it");
    }
}
