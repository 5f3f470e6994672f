//! glTF 2.0 (`.gltf` with external or `data:` buffers, and `.glb`), read
//! through the `gltf` crate.
//!
//! The default scene (or the first; or, without scenes, every mesh
//! untransformed) is flattened: each node's mesh is transformed by the node's
//! world matrix, normals by its inverse transpose, and the winding of
//! mirrored nodes (negative determinant) is reversed so that triangles stay
//! counter-clockwise from outside. Triangle lists, strips and fans are read;
//! points and lines are skipped. glTF's texture coordinates already run down
//! the image, as fixshade's do. Each material's base colour factor,
//! metallic and roughness factors, emissive factor and alpha mode are kept
//! (mapped to Blinn-Phong by [`crate::material`]), its base colour texture is
//! its texture (PNG only; `KHR_texture_transform` is not applied).

use std::path::{Path, PathBuf};

use base64::Engine as _;
use gltf::mesh::Mode;

use crate::error::{read_file, Error, FileKind};
use crate::source::{
    Corner, MaterialValues, Smoothing, SourceMaterial, SourceMesh, SourceTriangle, TextureSource,
};

/// Reads the glTF or GLB at `path` and the buffers it names.
///
/// # Errors
///
/// [`Error::MissingFile`] for a missing file or external buffer;
/// [`Error::Parse`] for invalid JSON (with its line), an invalid document, a
/// short buffer or an index out of range.
pub fn read(path: &Path) -> Result<SourceMesh, Error> {
    let bytes = read_file(FileKind::Model, path)?;
    let parse = |line: Option<usize>, message: String| Error::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let gltf = gltf::Gltf::from_slice(&bytes).map_err(|e| {
        let line = match &e {
            gltf::Error::Deserialize(j) => Some(j.line()),
            _ => None,
        };
        parse(line, e.to_string())
    })?;
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let mut out = SourceMesh {
        files: vec![path.to_path_buf()],
        ..SourceMesh::default()
    };
    let mut buffers = Vec::new();
    for buffer in gltf.document.buffers() {
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => gltf
                .blob
                .clone()
                .ok_or_else(|| parse(None, "the GLB has no BIN chunk".into()))?,
            gltf::buffer::Source::Uri(uri) => {
                let (data, file) = load_uri(uri, &dir, FileKind::GltfBuffer)
                    .map_err(|e| e.unwrap_or_else(|m| parse(None, m)))?;
                out.files.extend(file);
                data
            }
        };
        if data.len() < buffer.length() {
            return Err(parse(
                None,
                format!(
                    "buffer {} holds {} bytes, {} declared",
                    buffer.index(),
                    data.len(),
                    buffer.length()
                ),
            ));
        }
        buffers.push(data);
    }
    let mut reader = Reader {
        buffers: &buffers,
        dir: &dir,
        out: &mut out,
        materials: Vec::new(),
    };
    let doc = &gltf.document;
    match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => {
            for node in scene.nodes() {
                reader
                    .node(&node, IDENTITY, 0)
                    .map_err(|m| parse(None, m))?;
            }
        }
        None => {
            for mesh in doc.meshes() {
                reader.mesh(&mesh, IDENTITY).map_err(|m| parse(None, m))?;
            }
        }
    }
    Ok(out)
}

type Mat4 = [[f64; 4]; 4];

/// Column-major: `m[column][row]`, as glTF stores matrices.
const IDENTITY: Mat4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

fn mul(a: &Mat4, b: &Mat4) -> Mat4 {
    core::array::from_fn(|c| core::array::from_fn(|r| (0..4).map(|k| a[k][r] * b[c][k]).sum()))
}

/// Nodes deeper than this are taken for a cycle (an invalid document).
const MAX_DEPTH: usize = 256;

struct Reader<'a> {
    buffers: &'a [Vec<u8>],
    dir: &'a Path,
    out: &'a mut SourceMesh,
    /// The document's material index of each of `out.materials`.
    materials: Vec<usize>,
}

impl Reader<'_> {
    fn node(&mut self, node: &gltf::Node<'_>, parent: Mat4, depth: usize) -> Result<(), String> {
        if depth > MAX_DEPTH {
            return Err("the node hierarchy is deeper than 256 (a cycle?)".into());
        }
        let local = node.transform().matrix().map(|c| c.map(f64::from));
        let world = mul(&parent, &local);
        if let Some(mesh) = node.mesh() {
            self.mesh(&mesh, world)?;
        }
        for child in node.children() {
            self.node(&child, world, depth + 1)?;
        }
        Ok(())
    }

    fn mesh(&mut self, mesh: &gltf::Mesh<'_>, m: Mat4) -> Result<(), String> {
        // the normal matrix: the inverse transpose of the linear part, i.e.
        // its cofactor matrix (the determinant's scale is removed by normalising)
        let a = |r: usize, c: usize| m[c][r];
        let cof = |r: usize, c: usize| {
            let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1)
        };
        let det: f64 = (0..3).map(|c| a(0, c) * cof(0, c)).sum();
        let mirrored = det < 0.0;
        let sign = if mirrored { -1.0 } else { 1.0 };
        let point = |p: [f32; 3]| -> [f64; 3] {
            core::array::from_fn(|r| {
                (0..3).map(|c| a(r, c) * f64::from(p[c])).sum::<f64>() + a(r, 3)
            })
        };
        let normal = |n: [f32; 3]| -> [f64; 3] {
            core::array::from_fn(|r| {
                sign * (0..3).map(|c| cof(r, c) * f64::from(n[c])).sum::<f64>()
            })
        };
        for (pi, prim) in mesh.primitives().enumerate() {
            let what = format!("mesh {} primitive {pi}", mesh.index());
            let mode = prim.mode();
            if !matches!(
                mode,
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
            ) {
                self.out
                    .warnings
                    .push(format!("{what}: {mode:?} skipped (not triangles)"));
                continue;
            }
            let material = prim.material();
            let texture = material.pbr_metallic_roughness().base_color_texture();
            let set = texture.as_ref().map_or(0, |t| t.tex_coord());
            let material = self.material(&material)?;
            let r = prim.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice));
            let Some(positions) = r.read_positions() else {
                self.out
                    .warnings
                    .push(format!("{what}: no POSITION, skipped"));
                continue;
            };
            let positions: Vec<[f32; 3]> = positions.collect();
            let normals: Option<Vec<[f32; 3]>> = r.read_normals().map(Iterator::collect);
            let uvs: Option<Vec<[f32; 2]>> = r.read_tex_coords(set).map(|t| t.into_f32().collect());
            let n = positions.len();
            let indices: Vec<u32> = match r.read_indices() {
                Some(i) => i.into_u32().collect(),
                None => (0..n as u32).collect(),
            };
            if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
                return Err(format!("{what}: index {bad} beyond its {n} vertices"));
            }
            if normals.as_ref().is_some_and(|v| v.len() != n)
                || uvs.as_ref().is_some_and(|v| v.len() != n)
            {
                return Err(format!("{what}: attribute counts differ"));
            }
            let corner = |i: u32| {
                let i = i as usize;
                Corner {
                    position: point(positions[i]),
                    normal: normals.as_ref().map(|v| normal(v[i])),
                    texcoord: uvs
                        .as_ref()
                        .map(|v| [f64::from(v[i][0]), f64::from(v[i][1])]),
                }
            };
            let k = indices.len();
            let tris: Vec<[u32; 3]> = match mode {
                Mode::Triangles => indices
                    .chunks_exact(3)
                    .map(|t| [t[0], t[1], t[2]])
                    .collect(),
                // triangle i of a strip: (i, i+1, i+2) for even i, (i, i+2, i+1) for odd
                Mode::TriangleStrip => (0..k.saturating_sub(2))
                    .map(|i| {
                        let (b, c) = if i % 2 == 0 {
                            (i + 1, i + 2)
                        } else {
                            (i + 2, i + 1)
                        };
                        [indices[i], indices[b], indices[c]]
                    })
                    .collect(),
                _ => (1..k.saturating_sub(1))
                    .map(|i| [indices[i], indices[i + 1], indices[0]])
                    .collect(),
            };
            for t in tris {
                let t = if mirrored { [t[0], t[2], t[1]] } else { t };
                self.out.triangles.push(SourceTriangle {
                    corners: t.map(corner),
                    smoothing: Smoothing::Unspecified,
                    material,
                });
            }
        }
        Ok(())
    }

    /// The index in `out.materials` of a primitive's material (added at its
    /// first use); `None` for the default material (no `material`).
    fn material(&mut self, material: &gltf::Material<'_>) -> Result<Option<usize>, String> {
        let Some(index) = material.index() else {
            return Ok(None);
        };
        if let Some(i) = self.materials.iter().position(|&m| m == index) {
            return Ok(Some(i));
        }
        let pbr = material.pbr_metallic_roughness();
        let texture = match pbr.base_color_texture() {
            Some(info) => Some(self.texture(&info.texture())?),
            None => None,
        };
        self.out.materials.push(SourceMaterial {
            name: material
                .name()
                .map_or_else(|| format!("material {index}"), str::to_string),
            values: MaterialValues::Gltf {
                base_colour: pbr.base_color_factor().map(f64::from),
                metallic: f64::from(pbr.metallic_factor()),
                roughness: f64::from(pbr.roughness_factor()),
                emissive: material.emissive_factor().map(f64::from),
                opaque: material.alpha_mode() == gltf::material::AlphaMode::Opaque,
            },
            texture,
        });
        self.materials.push(index);
        Ok(Some(self.out.materials.len() - 1))
    }

    fn texture(&mut self, texture: &gltf::Texture<'_>) -> Result<TextureSource, String> {
        let image = texture.source();
        let name = format!("image {}", image.index());
        match image.source() {
            gltf::image::Source::View { view, mime_type } => {
                let data = self
                    .buffers
                    .get(view.buffer().index())
                    .and_then(|b| b.get(view.offset()..view.offset() + view.length()))
                    .ok_or_else(|| format!("{name}: buffer view out of range"))?;
                Ok(TextureSource::Embedded {
                    name,
                    bytes: data.to_vec(),
                    mime_type: mime_type.to_string(),
                })
            }
            gltf::image::Source::Uri { uri, mime_type } => {
                if let Some((mime, bytes)) = decode_data_uri(uri) {
                    let bytes = bytes.map_err(|e| format!("{name}: {e}"))?;
                    Ok(TextureSource::Embedded {
                        name,
                        bytes,
                        mime_type: mime_type.unwrap_or(mime).to_string(),
                    })
                } else {
                    Ok(TextureSource::File(self.dir.join(percent_decode(uri))))
                }
            }
        }
    }
}

/// `(media type, decoded bytes)` of a `data:` URI; `None` for other URIs.
fn decode_data_uri(uri: &str) -> Option<(&str, Result<Vec<u8>, String>)> {
    let rest = uri.strip_prefix("data:")?;
    let (head, data) = rest.split_once(',').unwrap_or((rest, ""));
    let Some(mime) = head.strip_suffix(";base64") else {
        return Some((head, Err("only base64 data URIs are supported".into())));
    };
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(data)
        .map_err(|e| format!("base64: {e}"));
    Some((mime, bytes))
}

/// `%XX` escapes of a relative URI decoded (invalid escapes kept as written).
fn percent_decode(uri: &str) -> String {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        match (
            b[i],
            b.get(i + 1).copied().and_then(hex),
            b.get(i + 2).copied().and_then(hex),
        ) {
            (b'%', Some(h), Some(l)) => {
                out.push((h * 16 + l) as u8);
                i += 3;
            }
            (c, _, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The bytes of a buffer URI and the file read (none for a `data:` URI).
/// `Err(Ok(e))` is an I/O error, `Err(Err(m))` a malformed URI.
#[allow(clippy::type_complexity)]
fn load_uri(
    uri: &str,
    dir: &Path,
    kind: FileKind,
) -> Result<(Vec<u8>, Option<PathBuf>), Result<Error, String>> {
    if let Some((_, bytes)) = decode_data_uri(uri) {
        return bytes.map(|b| (b, None)).map_err(Err);
    }
    let path = dir.join(percent_decode(uri));
    let bytes = read_file(kind, &path).map_err(Ok)?;
    Ok((bytes, Some(path)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris() {
        assert_eq!(percent_decode("a%20b.bin"), "a b.bin");
        assert_eq!(percent_decode("100%.bin"), "100%.bin");
        let (mime, bytes) = decode_data_uri("data:application/octet-stream;base64,AAEC").unwrap();
        assert_eq!(
            (mime, bytes.unwrap()),
            ("application/octet-stream", vec![0, 1, 2])
        );
        assert!(decode_data_uri("mesh.bin").is_none());
    }

    #[test]
    fn matrices_compose_column_major() {
        let t: Mat4 = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [5.0, 6.0, 7.0, 1.0],
        ];
        let s: Mat4 = core::array::from_fn(|c| {
            core::array::from_fn(|r| match (r == c, r) {
                (true, 3) => 1.0,
                (true, _) => 2.0,
                _ => 0.0,
            })
        });
        let m = mul(&t, &s); // scale, then translate
        assert_eq!(m[3], [5.0, 6.0, 7.0, 1.0]);
        assert_eq!(m[0][0], 2.0);
    }
}
