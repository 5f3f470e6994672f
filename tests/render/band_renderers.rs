//! Several band renderers draw one frame (issue 23): a prepared mesh
//! (`MeshDraw`) shared, read only, by renderers on their own threads, each
//! with its own strip, depth strip and resume records (`MeshDraw::share`),
//! each drawing its own bands (`Bands::render_bands`), gives the frame one
//! renderer draws alone, bit for bit — two and four renderers, the bands
//! split in runs (halves, quarters), interleaved (every other, every fourth)
//! and scattered, in every shading mode, with and without depth, two meshes
//! per frame, orthographic and perspective (through the near plane and
//! beyond the set-up window: the clipping path). The vertex stage run in two
//! halves on two threads (`MeshDraw::light_vertices`, `with_lit_vertices`)
//! gives the same frame, and so does a sink that keeps each strip until it
//! is asked for it (as DMA does) with a second strip.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use fixshade::camera::{Camera, MeshTransform, Perspective, Projection, Viewport};
use fixshade::color::Linear;
use fixshade::error::RenderError;
use fixshade::framebuffer::BandSink;
use fixshade::framebuffer::{Bands, DrawBand, Layout};
use fixshade::lighting::Viewed;
use fixshade::lighting::{BlinnPhong, Lighting, Material};
use fixshade::mesh::Mesh;
use fixshade::num::Mat4;
use fixshade::num::Q14;
use fixshade::raster::Cull;
use fixshade::render::{bins_len, CachedVertex, Carry, DrawOptions, MeshDraw, MeshMemory};
use fixshade::shade::{
    FlatShading, GouraudShading, IncrementalPhongShading, Kernel, PhongShading,
    QuadraticPhongShading, Shader,
};
use fixshade::standard::{self, SPHERE};
use fixshade_testkit::support::Collect;

const W: u32 = standard::SIZE;

/// Which renderer draws each of `n` bands: (name, renderers, owner of band b).
fn splits(n: u32) -> Vec<(&'static str, usize, Vec<usize>)> {
    let n = n as usize;
    vec![
        (
            "halves",
            2,
            (0..n).map(|b| usize::from(b >= n / 2)).collect(),
        ),
        ("every other band", 2, (0..n).map(|b| b % 2).collect()),
        ("quarters", 4, (0..n).map(|b| b * 4 / n).collect()),
        ("every fourth band", 4, (0..n).map(|b| b % 4).collect()),
        // runs of 1 to 5 bands, and renderers skipping up to 9
        (
            "scattered",
            4,
            (0..n).map(|b| (b * 7 + b / 3) % 11 % 4).collect(),
        ),
    ]
}

/// The two meshes of a frame: the standard sphere, and the same sphere
/// moved and turned, partly in front of it (so depth and mesh order both
/// decide pixels).
fn transforms<P: Projection>(
    t: &MeshTransform<P>,
    moved: &MeshTransform<P>,
) -> [MeshTransform<P>; 2] {
    [*t, *moved]
}

/// The bins, vertex caches and records of the meshes of one frame.
struct Memory<V> {
    cache: Vec<Vec<CachedVertex<V>>>,
    bins: Vec<Vec<u16>>,
}

impl<V: Copy + Default> Memory<V> {
    fn new(mesh: Mesh<'_>, layout: Layout, meshes: usize) -> Self {
        Memory {
            cache: vec![vec![CachedVertex::default(); mesh.vertex_count()]; meshes],
            bins: vec![vec![0; bins_len(mesh.triangle_count(), layout.bands() as usize)]; meshes],
        }
    }
}

/// The frame one renderer draws alone (`Bands::render`, each mesh with its
/// own records).
fn alone<K: Kernel<Color = Rgb565> + Copy, P: Projection>(
    layout: Layout,
    ts: &[MeshTransform<P>],
    k: K,
    cull: Cull,
    depth: bool,
) -> Vec<Rgb565> {
    let mesh = SPHERE.mesh();
    let mut m = Memory::<K::Vertex>::new(mesh, layout, ts.len());
    let mut carry = vec![vec![Carry::ZERO; 2 * mesh.triangle_count()]; ts.len()];
    let mut draws: Vec<MeshDraw<'_, K, P>> = m
        .cache
        .iter_mut()
        .zip(&mut m.bins)
        .zip(&mut carry)
        .zip(ts)
        .map(|(((vertices, bins), carry), t)| {
            let memory = MeshMemory {
                vertices,
                bins,
                carry,
            };
            MeshDraw::new(
                layout,
                mesh,
                t,
                k,
                memory,
                DrawOptions {
                    cull,
                    ..DrawOptions::default()
                },
            )
            .unwrap()
        })
        .collect();
    let mut items: Vec<&mut dyn DrawBand<Rgb565>> = draws
        .iter_mut()
        .map(|d| d as &mut dyn DrawBand<Rgb565>)
        .collect();
    let n = (W * layout.band_rows()) as usize;
    let (mut strip, mut z) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
    let mut bands = Bands::new(layout, &mut strip, depth.then_some(&mut z[..])).unwrap();
    let mut sink = Collect::new(W, W, Rgb565::CYAN);
    bands.render(&mut sink, Rgb565::BLACK, &mut items).unwrap();
    sink.px
}

/// The frame drawn by `renderers` threads, band `b` by `owner[b]` (the odd
/// renderers' bands in decreasing order), each with
/// its own strip, depth strip, records and display; the displays' bands put
/// together.
fn together<K: Kernel<Color = Rgb565> + Copy + Sync, P: Projection + Sync>(
    layout: Layout,
    draws: &[MeshDraw<'_, K, P>],
    renderers: usize,
    owner: &[usize],
    depth: bool,
) -> Vec<Rgb565>
where
    K::Vertex: Sync,
{
    let n = (W * layout.band_rows()) as usize;
    let need = draws.iter().map(MeshDraw::carry_needed).max().unwrap_or(0);
    let shown: Vec<Vec<Rgb565>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..renderers)
            .map(|r| {
                s.spawn(move || {
                    let mut carry = vec![vec![Carry::ZERO; need]; draws.len()];
                    let mut mine: Vec<MeshDraw<'_, K, P>> = draws
                        .iter()
                        .zip(&mut carry)
                        .map(|(d, c)| d.share(c))
                        .collect();
                    let mut items: Vec<&mut dyn DrawBand<Rgb565>> = mine
                        .iter_mut()
                        .map(|d| d as &mut dyn DrawBand<Rgb565>)
                        .collect();
                    let (mut strip, mut z) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
                    let mut bands =
                        Bands::new(layout, &mut strip, depth.then_some(&mut z[..])).unwrap();
                    let mut sink = Collect::new(W, W, Rgb565::CYAN);
                    // odd renderers draw their bands bottom up: any order works
                    let mut which: Vec<u32> = (0..layout.bands())
                        .filter(|&b| owner[b as usize] == r)
                        .collect();
                    if r % 2 == 1 {
                        which.reverse();
                    }
                    bands
                        .render_bands(&mut sink, Rgb565::BLACK, &mut items, which)
                        .unwrap();
                    sink.px
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let mut frame = vec![Rgb565::CYAN; (W * W) as usize];
    for b in 0..layout.bands() {
        let rows = layout.rows(b);
        let px = (rows.start as usize * W as usize)..(rows.end as usize * W as usize);
        frame[px.clone()].copy_from_slice(&shown[owner[b as usize]][px]);
    }
    frame
}

/// Every split, with and without depth, in 8-row and 3-row bands, equals the
/// frame one renderer draws alone.
fn assert_split<K: Kernel<Color = Rgb565> + Copy + Sync, P: Projection + Sync>(
    what: &str,
    ts: &[MeshTransform<P>],
    k: K,
) where
    K::Vertex: Sync,
{
    let mesh = SPHERE.mesh();
    for rows in [8, 3] {
        let layout = Layout::banded(W, W, rows).unwrap();
        for depth in [true, false] {
            let cull = if depth { Cull::Back } else { Cull::None };
            let want = alone(layout, ts, k, cull, depth);
            let lit = want.iter().filter(|&&p| p != Rgb565::BLACK).count();
            assert!(lit > 20_000, "{what}: {lit} lit pixels");
            let mut m = Memory::<K::Vertex>::new(mesh, layout, ts.len());
            let draws: Vec<MeshDraw<'_, K, P>> = m
                .cache
                .iter_mut()
                .zip(&mut m.bins)
                .zip(ts)
                .map(|((vertices, bins), t)| {
                    let memory = MeshMemory {
                        vertices,
                        bins,
                        carry: &mut [],
                    };
                    MeshDraw::new(
                        layout,
                        mesh,
                        t,
                        k,
                        memory,
                        DrawOptions {
                            cull,
                            ..DrawOptions::default()
                        },
                    )
                    .unwrap()
                })
                .collect();
            for (name, renderers, owner) in splits(layout.bands()) {
                let got = together(layout, &draws, renderers, &owner, depth);
                let bad: Vec<usize> = (0..got.len()).filter(|&i| got[i] != want[i]).collect();
                assert!(
                    bad.is_empty(),
                    "{what}, {rows}-row bands, depth {depth}, {name}: {} pixels differ, first at {:?}",
                    bad.len(),
                    bad.first().map(|i| (i % W as usize, i / W as usize))
                );
            }
        }
    }
}

fn moved() -> MeshTransform<fixshade::camera::Orthographic> {
    let c = standard::camera().unwrap();
    c.mesh_transform(
        &Mat4::translate([0.35, 0.25, 0.5]).mul(&Mat4::rotate_y(0.7)),
        SPHERE.frac,
    )
    .unwrap()
}

#[test]
fn two_and_four_renderers_draw_the_frame_of_one_in_every_mode() {
    let t = standard::transform().unwrap();
    let ts = transforms(&t, &moved());
    let blinn = standard::blinn::<Q14>().unwrap();
    let lambert = standard::lambert::<Q14>().unwrap();
    let array: Viewed<Lighting<Q14, [_; 1], BlinnPhong>> = Lighting::new(
        [standard::light::<Q14>().unwrap()],
        Material::new(&standard::material()).unwrap(),
    )
    .eye_space();
    assert_split("flat", &ts, Shader::new(FlatShading, &lambert, Linear));
    assert_split("gouraud", &ts, Shader::new(GouraudShading, &blinn, Linear));
    assert_split("phong", &ts, Shader::new(PhongShading, &blinn, Linear));
    assert_split(
        "general phong",
        &ts,
        Shader::new(PhongShading, &blinn, Linear),
    );
    assert_split(
        "incremental phong",
        &ts,
        Shader::new(IncrementalPhongShading, &array, Linear),
    );
    assert_split(
        "quadratic phong",
        &ts,
        Shader::new(QuadraticPhongShading, &array, Linear),
    );
}

/// Perspective, the sphere close enough to cross the near plane and the
/// set-up window: the clipping path's triangles, set up again in every band,
/// and the records of triangles reaching into a band after a gap.
#[test]
fn two_and_four_renderers_draw_the_frame_of_one_through_the_clipping_path() {
    let persp = |z: f32| -> MeshTransform<Perspective> {
        Camera::perspective(0.9, 1.0, 0.5, 20.0, Viewport::new(0, 0, W, W).unwrap())
            .unwrap()
            .with_view(Mat4::translate([0.3, -0.2, z]))
            .mesh_transform(&Mat4::rotate_y(0.5).mul(&Mat4::rotate_x(0.4)), SPHERE.frac)
            .unwrap()
    };
    let ts = [persp(-1.3), persp(-3.0)];
    let blinn = standard::blinn::<Q14>().unwrap();
    assert_split(
        "perspective gouraud",
        &ts,
        Shader::new(GouraudShading, &blinn, Linear),
    );
    assert_split(
        "perspective phong",
        &ts,
        Shader::new(PhongShading, &blinn, Linear),
    );
}

/// The vertex stage in two halves on two threads, then the bins: the frame
/// of `MeshDraw::new`.
#[test]
fn vertex_stage_in_halves_on_two_threads_gives_the_same_frame() {
    let t = standard::transform().unwrap();
    let blinn = standard::blinn::<Q14>().unwrap();
    let k = Shader::new(GouraudShading, &blinn, Linear);
    let layout = Layout::banded(W, W, 8).unwrap();
    let want = alone(layout, &[t], k, Cull::Back, true);
    let mesh = SPHERE.mesh();
    let mut m = Memory::<[u16; 3]>::new(mesh, layout, 1);
    let cache = &mut m.cache[0];
    let half = cache.len() / 2;
    let (a, b) = cache.split_at_mut(half);
    std::thread::scope(|s| {
        s.spawn(|| MeshDraw::light_vertices(&mesh, &t, &k, half, b));
        MeshDraw::light_vertices(&mesh, &t, &k, 0, a);
    });
    let mut carry = vec![Carry::ZERO; 64];
    let memory = MeshMemory {
        vertices: cache,
        bins: &mut m.bins[0],
        carry: &mut carry,
    };
    let mut draw = MeshDraw::new(
        layout,
        mesh,
        &t,
        k,
        memory,
        DrawOptions {
            lit: true,
            ..DrawOptions::default()
        },
    )
    .unwrap();
    let n = (W * 8) as usize;
    let (mut strip, mut z) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
    let mut bands = Bands::new(layout, &mut strip, Some(&mut z)).unwrap();
    let mut sink = Collect::new(W, W, Rgb565::CYAN);
    bands
        .render(&mut sink, Rgb565::BLACK, &mut [&mut draw])
        .unwrap();
    assert!(sink.px == want, "the frame differs");
}

/// A sink that keeps each strip until `finish` (as a DMA transfer does) and
/// only then copies its pixels out: a band drawn into a strip still being
/// sent would show.
struct Later<'a> {
    held: Option<(Rectangle, &'a mut [Rgb565])>,
    shown: Collect<Rgb565>,
    /// Transfers started and strips given back short (by this many).
    started: usize,
    short: usize,
}

impl<'a> BandSink<'a, Rgb565> for Later<'a> {
    type Error = &'static str;

    fn start(
        &mut self,
        area: &Rectangle,
        strip: &'a mut [Rgb565],
    ) -> Result<Option<&'a mut [Rgb565]>, &'static str> {
        if self.held.is_some() {
            return Err("two transfers at once");
        }
        self.started += 1;
        self.held = Some((*area, strip));
        Ok(None)
    }

    fn finish(&mut self) -> Result<&'a mut [Rgb565], &'static str> {
        use embedded_graphics_core::draw_target::DrawTarget;
        let (area, strip) = self.held.take().ok_or("nothing to finish")?;
        let n = (area.size.width * area.size.height) as usize;
        self.shown
            .fill_contiguous(&area, strip[..n].iter().copied())
            .unwrap();
        let keep = strip.len() - self.short;
        Ok(&mut strip[..keep])
    }
}

#[test]
fn a_second_strip_is_drawn_while_a_deferred_sink_holds_the_first() {
    let t = standard::transform().unwrap();
    let blinn = standard::blinn::<Q14>().unwrap();
    let k = Shader::new(PhongShading, &blinn, Linear);
    let layout = Layout::banded(W, W, 8).unwrap();
    let want = alone(layout, &[t], k, Cull::Back, true);
    let mesh = SPHERE.mesh();
    let n = (W * 8) as usize;
    for second in [false, true] {
        let mut m = Memory::<[i16; 3]>::new(mesh, layout, 1);
        let mut carry = vec![Carry::ZERO; 64];
        let memory = MeshMemory {
            vertices: &mut m.cache[0],
            bins: &mut m.bins[0],
            carry: &mut carry,
        };
        let mut draw = MeshDraw::new(layout, mesh, &t, k, memory, DrawOptions::default()).unwrap();
        let (mut a, mut b, mut z) = (vec![Rgb565::BLACK; n], vec![Rgb565::BLACK; n], vec![0; n]);
        let mut bands = Bands::new(layout, &mut a, Some(&mut z)).unwrap();
        if second {
            bands = bands.with_second_strip(&mut b).unwrap();
        }
        let mut sink = Later {
            held: None,
            shown: Collect::new(W, W, Rgb565::CYAN),
            started: 0,
            short: 0,
        };
        // twice: the strips come back for the next frame
        for _ in 0..2 {
            bands
                .render(&mut sink, Rgb565::BLACK, &mut [&mut draw])
                .unwrap();
            assert!(sink.held.is_none(), "the last transfer has ended");
            assert!(
                sink.shown.px == want,
                "second strip {second}: the frame differs"
            );
            sink.shown = Collect::new(W, W, Rgb565::CYAN);
        }
        assert_eq!(sink.started, 60);
        // a strip given back short is an error, not a wrong picture
        sink.short = 1;
        let e = bands.render(&mut sink, Rgb565::BLACK, &mut [&mut draw]);
        assert!(
            matches!(
                e,
                Err(RenderError::BufferTooSmall {
                    which: "colour strip",
                    ..
                })
            ),
            "{e:?}"
        );
    }
}

#[test]
fn short_records_and_strips_are_errors() {
    let t = standard::transform().unwrap();
    let blinn = standard::blinn::<Q14>().unwrap();
    let k = Shader::new(GouraudShading, &blinn, Linear);
    let layout = Layout::banded(W, W, 8).unwrap();
    let mesh = SPHERE.mesh();
    let mut m = Memory::<[u16; 3]>::new(mesh, layout, 1);
    let memory = MeshMemory {
        vertices: &mut m.cache[0],
        bins: &mut m.bins[0],
        carry: &mut [],
    };
    // a mesh prepared without records of its own is drawn through shares;
    // drawn itself, it is an error before anything is drawn
    let mut draw = MeshDraw::new(layout, mesh, &t, k, memory, DrawOptions::default()).unwrap();
    let mut strip = vec![Rgb565::BLACK; (W * 8) as usize];
    let mut sink = Collect::new(W, W, Rgb565::CYAN);
    let e = Bands::new(layout, &mut strip, None).unwrap().render(
        &mut sink,
        Rgb565::BLACK,
        &mut [&mut draw],
    );
    assert!(
        matches!(
            e,
            Err(RenderError::BufferTooSmall {
                which: "carry",
                got: 0,
                ..
            })
        ),
        "{e:?}"
    );
    assert!(
        sink.px.iter().all(|&p| p == Rgb565::CYAN),
        "nothing is drawn"
    );
    let need = draw.carry_needed();
    let mut few = vec![Carry::ZERO; need - 1];
    let mut short_share = draw.share(&mut few);
    let mut strip = vec![Rgb565::BLACK; (W * 8) as usize];
    assert!(matches!(
        Bands::new(layout, &mut strip, None).unwrap().render(
            &mut sink,
            Rgb565::BLACK,
            &mut [&mut short_share]
        ),
        Err(RenderError::BufferTooSmall { which: "carry", .. })
    ));
    let mut strip = vec![Rgb565::BLACK; (W * 8) as usize];
    let mut short = vec![Rgb565::BLACK; (W * 8) as usize - 1];
    let bands = Bands::new(layout, &mut strip, None).unwrap();
    assert!(matches!(
        bands.with_second_strip(&mut short),
        Err(RenderError::BufferTooSmall {
            which: "second colour strip",
            ..
        })
    ));
}
