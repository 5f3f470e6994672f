//! Texture conversion: known pixels to known Rgb565 / Gray8 / palette
//! values, palette quantisation, sizes, PNG decoding, and a texture through a
//! whole OBJ import.

mod common;

use std::path::Path;

use common::{scratch, write};
use fixshade_import::texture::{self, convert, decode_png, Image, TexelData};
use fixshade_import::{import, Error, Options, TextureFormat, Wrap};

fn image(w: u32, h: u32, pixels: Vec<[u8; 3]>) -> Image {
    Image {
        width: w,
        height: h,
        pixels,
        had_alpha: false,
    }
}

const KNOWN: [[u8; 3]; 8] = [
    [255, 0, 0],
    [0, 255, 0],
    [0, 0, 255],
    [255, 255, 255],
    [0, 0, 0],
    [128, 128, 128],
    [255, 128, 0],
    [8, 4, 12],
];

fn png_bytes(w: u32, h: u32, color: png::ColorType, data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(color);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header().unwrap().write_image_data(data).unwrap();
    out
}

#[test]
fn known_pixels_to_rgb565() {
    let c = convert(
        &image(4, 2, KNOWN.to_vec()),
        Path::new("k"),
        TextureFormat::Rgb565,
        Wrap::Repeat,
        false,
    )
    .unwrap();
    // 128 → 5-bit 16 (expands to 132) and 6-bit 32 (130); 255·128 → orange;
    // 8, 4, 12 → codes 1, 1, 1 (expand to 8, 4, 8)
    assert_eq!(
        c.texels,
        TexelData::Rgb565(vec![
            0xF800, 0x07E0, 0x001F, 0xFFFF, 0x0000, 0x8410, 0xFC00, 0x0821
        ])
    );
    assert_eq!((c.log2_width, c.log2_height), (2, 1));
    assert_eq!(c.report.max_error, 4); // 128 → 132
    assert_eq!(c.report.bytes, 16);
}

#[test]
fn known_pixels_to_gray8() {
    let c = convert(
        &image(4, 2, KNOWN.to_vec()),
        Path::new("k"),
        TextureFormat::Gray8,
        Wrap::Repeat,
        false,
    )
    .unwrap();
    // Rec. 601: 0.299 R + 0.587 G + 0.114 B
    assert_eq!(
        c.texels,
        TexelData::Gray8(vec![76, 150, 29, 255, 0, 128, 151, 6])
    );
    assert_eq!(c.report.max_error, 0);
}

#[test]
fn few_colours_make_an_exact_palette_in_order_of_use() {
    let px = vec![
        [255, 0, 0],
        [0, 255, 0],
        [255, 0, 0],
        [0, 0, 255],
        [0, 255, 0],
        [255, 0, 0],
        [255, 255, 255],
        [255, 0, 0],
    ];
    let c = convert(
        &image(4, 2, px),
        Path::new("p"),
        TextureFormat::Palette8,
        Wrap::Clamp,
        false,
    )
    .unwrap();
    assert_eq!(
        c.texels,
        TexelData::Palette8 {
            indices: vec![0, 1, 0, 2, 1, 0, 3, 0],
            palette: vec![0xF800, 0x07E0, 0x001F, 0xFFFF],
        }
    );
    assert!(!c.report.quantised);
    assert_eq!(c.report.max_error, 0);
    assert_eq!(c.texture().unwrap().wrap(), Wrap::Clamp);
}

/// A 64 × 64 image of 4096 colours: median cut to 256, error bounded.
#[test]
fn many_colours_are_quantised_to_256() {
    let px: Vec<[u8; 3]> = (0..64 * 64)
        .map(|i| {
            let (x, y) = (i % 64, i / 64);
            [(x * 4) as u8, (y * 4) as u8, ((x + y) * 2) as u8]
        })
        .collect();
    let img = image(64, 64, px);
    let c = convert(
        &img,
        Path::new("g"),
        TextureFormat::Palette8,
        Wrap::Repeat,
        false,
    )
    .unwrap();
    let TexelData::Palette8 { indices, palette } = &c.texels else {
        panic!()
    };
    assert_eq!(indices.len(), 4096);
    assert!(
        palette.len() <= 256 && palette.len() > 200,
        "{}",
        palette.len()
    );
    assert!(c.report.quantised);
    assert_eq!(c.report.source_colours, 4096);
    // 4096 colours on 256 entries: about a 4 × 4 block of the gradient each
    assert!(c.report.rms_error < 6.0, "rms {}", c.report.rms_error);
    assert!(c.report.max_error < 24, "max {}", c.report.max_error);
    // deterministic
    assert_eq!(
        convert(
            &img,
            Path::new("g"),
            TextureFormat::Palette8,
            Wrap::Repeat,
            false
        )
        .unwrap(),
        c
    );
}

#[test]
fn sides_must_be_powers_of_two_unless_resized() {
    let img = image(3, 5, vec![[10, 200, 30]; 15]);
    let e = convert(
        &img,
        Path::new("odd.png"),
        TextureFormat::Rgb565,
        Wrap::Repeat,
        false,
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            Error::TextureSize {
                width: 3,
                height: 5,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("odd.png"));
    let c = convert(
        &img,
        Path::new("odd.png"),
        TextureFormat::Rgb565,
        Wrap::Repeat,
        true,
    )
    .unwrap();
    assert_eq!((c.log2_width, c.log2_height), (2, 2));
    assert!(c.report.resized);
    assert_eq!(c.report.source_size, (3, 5));
    // a flat colour stays flat
    assert_eq!(
        c.texels,
        TexelData::Rgb565(vec![texture::rgb565([10, 200, 30]); 16])
    );
}

#[test]
fn png_colour_types_decode_to_rgb() {
    let rgb: Vec<u8> = KNOWN.iter().flatten().copied().collect();
    let img = decode_png(&png_bytes(4, 2, png::ColorType::Rgb, &rgb), Path::new("a")).unwrap();
    assert_eq!(img.pixels, KNOWN);
    assert!(!img.had_alpha);
    let grey = decode_png(
        &png_bytes(2, 1, png::ColorType::Grayscale, &[7, 250]),
        Path::new("g"),
    )
    .unwrap();
    assert_eq!(grey.pixels, [[7, 7, 7], [250, 250, 250]]);
    let rgba = decode_png(
        &png_bytes(2, 1, png::ColorType::Rgba, &[1, 2, 3, 255, 4, 5, 6, 128]),
        Path::new("r"),
    )
    .unwrap();
    assert_eq!(rgba.pixels, [[1, 2, 3], [4, 5, 6]]);
    assert!(rgba.had_alpha);
    let e = decode_png(b"\x89PNG\r\n\x1a\ntruncated", Path::new("bad.png")).unwrap_err();
    assert!(matches!(e, Error::Texture { .. }), "{e}");
}

/// A textured quad: the MTL's `map_Kd` read, converted, emitted.
#[test]
fn a_texture_through_an_obj_import() {
    let dir = scratch("textured_quad");
    let rgb: Vec<u8> = KNOWN.iter().flatten().copied().collect();
    write(&dir, "t.png", png_bytes(4, 2, png::ColorType::Rgb, &rgb));
    write(&dir, "q.mtl", "newmtl t\nKd 1 1 1\nmap_Kd t.png\n");
    let p = write(
        &dir,
        "q.obj",
        "mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl t\nf 1/1 2/2 3/3 4/4\n",
    );
    for (format, name) in [
        (TextureFormat::Rgb565, "Rgb565(&Q_TEXELS)"),
        (TextureFormat::Gray8, "Gray8(&Q_TEXELS)"),
        (TextureFormat::Palette8, "indices: &Q_INDICES"),
    ] {
        let mut o = Options::new("Q");
        o.texture_format = format;
        let m = import(&p, &o).unwrap();
        let t = m.texture().unwrap();
        assert_eq!(t.name, "t.png");
        assert_eq!(t.converted.report.format, format);
        assert!(m.files.iter().any(|f| f.ends_with("t.png")));
        let src = m.to_rust();
        assert!(src.contains(name), "{src}");
        assert!(src.contains("pub static Q_TEXTURE: ::fixshade::texture::Texture<'static>"));
    }
    let m = import(&p, &Options::new("Q")).unwrap();
    assert_eq!(
        m.texture().unwrap().converted.texels.clone(),
        TexelData::Rgb565(vec![
            0xF800, 0x07E0, 0x001F, 0xFFFF, 0x0000, 0x8410, 0xFC00, 0x0821
        ])
    );
}
