//! The two-material demo asset: a wooden crate with metal lids, written as
//! OBJ + MTL + two PNGs.
//!
//! A 1 × 1 × 1 cube around the origin, each face a quad with its own texture
//! coordinates (0..1), counter-clockwise from outside, `s off`. The four
//! sides use material `wood` (texture `crate_wood.png`: planks), the top and
//! the bottom `metal` (`crate_metal.png`: a plate with rivets); the faces
//! alternate between the two so that the importer has to gather each
//! material's faces. A closed mesh: its signed volume is 1.
//!
//! Integer and fixed-decimal output only: the same bytes on every run
//! (`tests/assets.rs` checks the committed files; `cargo run --example
//! make_assets` rewrites them).

use std::fmt::Write as _;

/// Texture side.
pub const TEX: u32 = 32;

/// The file name and bytes of each asset.
pub fn files() -> Vec<(&'static str, Vec<u8>)> {
    vec![
        ("crate.obj", obj().into_bytes()),
        ("crate.mtl", mtl().into_bytes()),
        ("crate_wood.png", png(&wood_pixels())),
        ("crate_metal.png", png(&metal_pixels())),
    ]
}

fn mtl() -> String {
    "# fixshade-import two-material demo asset (tests/common/crate_model.rs)\n\
     newmtl wood\n\
     Ka 0.2 0.2 0.2\n\
     Kd 0.9 0.8 0.7\n\
     Ks 0.1 0.1 0.1\n\
     Ns 10\n\
     map_Kd crate_wood.png\n\
     \n\
     newmtl metal\n\
     Ka 0.2 0.2 0.2\n\
     Kd 0.7 0.7 0.8\n\
     Ks 0.9 0.9 0.9\n\
     Ns 80\n\
     d 1\n\
     map_Kd crate_metal.png\n"
        .to_string()
}

fn obj() -> String {
    let mut s = String::from(
        "# fixshade-import two-material demo asset (tests/common/crate_model.rs)\n\
         mtllib crate.mtl\n\
         o crate\n",
    );
    // corners: bit 0 = +x, bit 1 = +y, bit 2 = +z
    for i in 0..8 {
        let c = |bit: usize| if i & bit != 0 { 0.5 } else { -0.5 };
        let _ = writeln!(s, "v {:.1} {:.1} {:.1}", c(1), c(2), c(4));
    }
    for (u, v) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
        let _ = writeln!(s, "vt {u} {v}");
    }
    s += "s off\n";
    // counter-clockwise from outside (as `cube_obj`), sides wood, top and
    // bottom metal, the two alternating
    let faces: [(&str, [usize; 4]); 6] = [
        ("wood", [1, 3, 4, 2]),  // -z
        ("metal", [3, 7, 8, 4]), // +y
        ("wood", [2, 4, 8, 6]),  // +x
        ("metal", [1, 2, 6, 5]), // -y
        ("wood", [5, 6, 8, 7]),  // +z
        ("wood", [1, 5, 7, 3]),  // -x
    ];
    for (material, f) in faces {
        let _ = writeln!(
            s,
            "usemtl {material}\nf {}/1 {}/2 {}/3 {}/4",
            f[0], f[1], f[2], f[3]
        );
    }
    s
}

/// Planks: four brown boards with dark gaps and a grain of lighter streaks.
pub fn wood_pixels() -> Vec<[u8; 3]> {
    let mut px = Vec::with_capacity((TEX * TEX) as usize);
    for y in 0..TEX {
        for x in 0..TEX {
            let board = y / 8;
            let gap = y % 8 == 7;
            let grain = (x * 5 + board * 11 + (y % 8) * 3) % 13 < 3;
            let shade: i32 = if gap {
                -70
            } else if grain {
                20
            } else {
                (board as i32 % 2) * 12
            };
            let c = |v: i32| (v + shade).clamp(0, 255) as u8;
            px.push([c(150), c(95), c(45)]);
        }
    }
    px
}

/// A blue-grey steel plate, brighter at its rivets (every 8 texels) and
/// along a diagonal stripe.
pub fn metal_pixels() -> Vec<[u8; 3]> {
    let mut px = Vec::with_capacity((TEX * TEX) as usize);
    for y in 0..TEX {
        for x in 0..TEX {
            let rivet = x % 8 == 3 && y % 8 == 3;
            let stripe = (x + TEX - y) % 16 < 2;
            let shade: i32 = if rivet {
                70
            } else if stripe {
                25
            } else {
                0
            };
            let c = |v: i32| (v + shade).clamp(0, 255) as u8;
            px.push([c(110), c(125), c(160)]);
        }
    }
    px
}

fn png(pixels: &[[u8; 3]]) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, TEX, TEX);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::High);
        let mut w = enc.write_header().expect("in-memory PNG header");
        let bytes: Vec<u8> = pixels.iter().flatten().copied().collect();
        w.write_image_data(&bytes).expect("in-memory PNG data");
    }
    out
}
