//! Normal maps with hostile texels (issue 21, item 1): `NormalMap::new` took
//! any `[i16; 3]`, and a texel far from unit length (a 1 × 1 map of
//! `[i16::MAX; 3]`) overflowed the fast path's 32-bit dot products inside
//! `FullFrame::render` ("attempt to add with overflow" with overflow checks
//! on; a wrapped colour in release). Every map the constructor accepts is now
//! rendered on the standard sphere by every normal-mapping kernel, whole frame
//! and in bands, with overflow checks on (the test profile keeps them): no
//! panic, banded = whole frame; every map it rejects is rejected with
//! `TextureError::NotUnit`, and `normalize_texels` makes it acceptable.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::prelude::*;
use fixshade::error::TextureError;
use fixshade::framebuffer::{Bands, DrawBand, FullFrame, Layout};
use fixshade::lighting::{Illuminate, Model};
use fixshade::prelude::*;
use fixshade::render::{bins_len, CachedVertex, Carry, MeshDraw, MeshMemory};
use fixshade::shade::{IncrementalModel, IncrementalPhongShading, Kernel, PhongShading};
use fixshade::texture::{NormalMap, Wrap};

/// The tolerance `NormalMap::new` documents: `|x² + y² + z² − 2^28| ≤ 2^15`.
const UNIT_TOLERANCE: u32 = 1 << 15;

/// Whether `t` is a unit normal as `NormalMap::new` accepts it (its
/// documented tolerance, restated).
fn is_unit_texel(t: [i16; 3]) -> bool {
    let d = t.iter().map(|&c| i64::from(c) * i64::from(c)).sum::<i64>() - (1 << 28);
    d.unsigned_abs() <= u64::from(UNIT_TOLERANCE)
}
use fixshade::standard;

const W: u32 = standard::SIZE;
const NV: usize = standard::COUNTS.0;
const NT: usize = standard::COUNTS.1;

/// Spherical texture coordinates (Q12, two repeats around) and tangents along
/// the parallels (Q14) of the standard sphere.
fn uv_tangents() -> (Vec<[i16; 2]>, Vec<[i16; 4]>) {
    let mut uv = Vec::new();
    let mut tg = Vec::new();
    for n in standard::SPHERE.normals.iter() {
        let n = n.map(|c| f64::from(c) / 16384.0);
        let phi = n[0].atan2(n[2]);
        let theta = n[1].clamp(-1.0, 1.0).acos();
        uv.push([
            (phi / core::f64::consts::TAU * 2.0 * 4096.0).round() as i16,
            (theta / core::f64::consts::PI * 4096.0).round() as i16,
        ]);
        tg.push([
            (phi.cos() * 16384.0).round() as i16,
            0,
            (-phi.sin() * 16384.0).round() as i16,
            16384,
        ]);
    }
    (uv, tg)
}

struct Sink(Vec<Rgb565>);
impl OriginDimensions for Sink {
    fn size(&self) -> Size {
        Size::new(W, W)
    }
}
impl DrawTarget for Sink {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        unreachable!("bands flush through fill_contiguous")
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        _: &embedded_graphics_core::primitives::Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.0.extend(colors);
        Ok(())
    }
}

/// The standard sphere through `kernel`, as a whole frame (`band_rows` =
/// `None`) or in bands, depth-tested.
fn frame<K: Kernel<Color = Rgb565>>(kernel: K, band_rows: Option<u32>) -> Vec<Rgb565>
where
{
    let (uv, tg) = uv_tangents();
    let layout = match band_rows {
        Some(r) => Layout::banded(W, W, r).unwrap(),
        None => Layout::full(W, W).unwrap(),
    };
    let mesh = standard::SPHERE
        .mesh()
        .with_texcoords(&uv)
        .unwrap()
        .with_tangents(&tg)
        .unwrap();
    let t = standard::transform().unwrap();
    let mut cache = vec![CachedVertex::<K::Vertex>::default(); NV];
    let mut bins = vec![0u16; bins_len(NT, layout.bands() as usize)];
    let mut carry = vec![Carry::default(); 4096];
    let memory = MeshMemory {
        vertices: &mut cache,
        bins: &mut bins,
        carry: &mut carry,
    };
    let mut draw = MeshDraw::new(layout, mesh, &t, kernel, memory, DrawOptions::default()).unwrap();
    match band_rows {
        None => {
            let mut color = vec![Rgb565::BLACK; (W * W) as usize];
            let mut depth = vec![0u16; (W * W) as usize];
            let mut f = FullFrame::new(W, W, &mut color, Some(&mut depth)).unwrap();
            f.render(Rgb565::BLACK, &mut [&mut draw]).unwrap();
            color
        }
        Some(r) => {
            let mut strip = vec![Rgb565::BLACK; (W * r) as usize];
            let mut depth = vec![0u16; (W * r) as usize];
            let mut bands = Bands::new(layout, &mut strip, Some(&mut depth)).unwrap();
            let mut sink = Sink(Vec::new());
            let items: &mut [&mut dyn DrawBand<Rgb565>] = &mut [&mut draw];
            bands.render(&mut sink, Rgb565::BLACK, items).unwrap();
            sink.0
        }
    }
}

/// Whole frame and 8-row bands: the same pixels; returns the lit pixels.
fn both<K: Kernel<Color = Rgb565> + Copy>(kernel: K, what: &str) -> usize
where
{
    let full = frame(kernel, None);
    let banded = frame(kernel, Some(8));
    assert!(full == banded, "{what}: bands differ from the whole frame");
    full.iter().filter(|p| **p != Rgb565::BLACK).count()
}

fn fast<const NW: u8, M: IncrementalModel>(map: NormalMap<'_>, what: &str) -> usize {
    let light = DirectionalLight::<Q14<NW>>::white([-0.3, 0.5, 0.8]).unwrap();
    // one directional light: the incremental kernel
    let lit =
        Lighting::<Q14<NW>, _, M>::new([light], Material::new(&standard::material()).unwrap())
            .eye_space();
    both(
        Shader::<_, _, _, Rgb565>::new(IncrementalPhongShading.normal_mapped(map), &lit, Linear),
        what,
    )
}

fn general<S: Scalar, M: Model>(map: NormalMap<'_>, what: &str) -> usize
where
    Viewed<Lighting<S, [DirectionalLight<S>; 1], M>>: Illuminate<Scalar = S>,
{
    let light = DirectionalLight::<S>::white([-0.3, 0.5, 0.8]).unwrap();
    let lit = Lighting::<S, _, M>::new([light], Material::new(&standard::material()).unwrap())
        .eye_space();
    both(
        Shader::new(PhongShading.normal_mapped(map), &lit, Linear),
        what,
    )
}

/// Every normal-mapping kernel on the standard sphere with `map`: no panic
/// (overflow checks on), banded = whole frame. Returns the fewest lit pixels.
fn render_everywhere(map: NormalMap<'_>, what: &str) -> usize {
    [
        fast::<1, Lambert>(map, what),
        fast::<1, BlinnPhong>(map, what),
        fast::<2, BlinnPhong>(map, what),
        general::<Q14, BlinnPhong>(map, what),
        general::<Q30, Phong>(map, what),
        general::<f32, BlinnPhong>(map, what),
    ]
    .into_iter()
    .min()
    .unwrap_or(0)
}

/// A deterministic generator.
fn lcg(s: &mut u64) -> u64 {
    *s = s
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    *s >> 16
}

/// Maps no unit normal makes: every extreme of `i16`, zero, slightly too long
/// or too short, and random `i16` texels.
fn hostile_maps() -> Vec<(String, Vec<[i16; 3]>, u8)> {
    let mut maps: Vec<(String, Vec<[i16; 3]>, u8)> = [
        [i16::MAX; 3],
        [i16::MIN; 3],
        [i16::MAX, i16::MIN, i16::MAX],
        [i16::MIN, 0, 0],
        [0, 0, i16::MAX],
        [0, 0, i16::MIN],
        [0; 3],
        [16385, 0, 0],
        [16384, 182, 0],
        [16382, 0, 0],
        [1, 1, 1],
        [23170, 23170, 0],
    ]
    .iter()
    .map(|t| (format!("1 × 1 of {t:?}"), vec![*t], 0))
    .collect();
    let mut s = 21u64;
    for k in 0..8 {
        let texels: Vec<[i16; 3]> = (0..16)
            .map(|i| {
                // mostly unit texels with hostile ones among them
                let r = [0, 1, 2].map(|_| lcg(&mut s) as i16);
                if (i + k) % 5 == 0 {
                    r
                } else {
                    NormalMap::unit_texel(r.map(|c| f32::from(c) + 0.5)).unwrap()
                }
            })
            .collect();
        maps.push((format!("4 × 4 random, seed {k}"), texels, 2));
    }
    maps
}

#[test]
fn hostile_texels_are_typed_errors_never_a_panic() {
    for (what, texels, log2) in hostile_maps() {
        match NormalMap::new(&texels, log2, log2, Wrap::Repeat) {
            // before the fix: accepted, and the fast path panicked here
            Ok(map) => {
                render_everywhere(map, &what);
                panic!("{what}: accepted");
            }
            Err(TextureError::NotUnit { index, texel }) => {
                assert!(!is_unit_texel(texel), "{what}");
                assert_eq!(texels[index], texel, "{what}");
                assert!(texels[..index].iter().all(|&t| is_unit_texel(t)), "{what}");
            }
            Err(e) => panic!("{what}: {e}"),
        }
    }
}

#[test]
fn normalized_hostile_maps_render() {
    for (what, mut texels, log2) in hostile_maps() {
        if texels.contains(&[0; 3]) {
            assert_eq!(
                NormalMap::normalize_texels(&mut texels),
                Err(TextureError::Degenerate("texel"))
            );
            continue;
        }
        NormalMap::normalize_texels(&mut texels).unwrap();
        let map = NormalMap::new(&texels, log2, log2, Wrap::Repeat).unwrap();
        render_everywhere(map, &what);
    }
}

/// The accepted extremes: the longest and shortest texels within the
/// tolerance, in every octant, and unit texels pointing into the surface,
/// along the tangent plane and straight out: rendered everywhere.
#[test]
fn accepted_extremes_render() {
    let mut edge = Vec::new();
    // the longest and shortest [x, y, z] of each direction the tolerance accepts
    for k in 0..64u32 {
        let (a, b) = (k as f64 * 0.41, (k % 8) as f64 * 0.45 - 1.6);
        let d = [a.cos() * b.cos(), a.sin() * b.cos(), b.sin()];
        let t = NormalMap::unit_texel(d.map(|c| c as f32)).unwrap();
        let len2 = |t: [i16; 3]| t.iter().map(|&c| i64::from(c) * i64::from(c)).sum::<i64>();
        // push each component away from zero (then towards it, not across)
        // while the texel is still accepted
        for outward in [true, false] {
            let mut u = t;
            for c in 0..3 {
                let step = match (t[c].signum(), outward) {
                    (0, false) => continue,
                    (0, true) => 1,
                    (s, true) => s,
                    (s, false) => -s,
                };
                loop {
                    let mut v = u;
                    v[c] = v[c].saturating_add(step);
                    if !is_unit_texel(v) || v == u || v[c].signum() * t[c].signum() < 0 {
                        break;
                    }
                    u = v;
                }
            }
            assert!(is_unit_texel(u));
            assert!((len2(u) - (1 << 28)).unsigned_abs() > u64::from(UNIT_TOLERANCE) / 2);
            edge.push(u);
        }
    }
    edge.truncate(64);
    let map = NormalMap::new(&edge, 3, 3, Wrap::Repeat).unwrap();
    assert!(render_everywhere(map, "tolerance edges") > 10_000);
    let special = [
        [0, 0, -16384],
        [16384, 0, 0],
        [-16384, 0, 0],
        [0, 16384, 0],
        [0, -16384, 0],
        [9459, 9459, 9459],
        [-9459, -9459, -9459],
        [0, 0, 16384],
    ];
    for log2 in [0u8, 1] {
        let t = &special[..1 << (2 * log2)];
        let map = NormalMap::new(t, log2, log2, Wrap::Clamp).unwrap();
        render_everywhere(map, "special directions");
    }
    let map = NormalMap::new(&special, 3, 0, Wrap::Clamp).unwrap();
    render_everywhere(map, "special directions, 8 × 1");
}
