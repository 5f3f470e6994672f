//! `fixshade-import`: a model file to fixshade's compact `static` mesh (and
//! texture) as Rust source, for flash.
//!
//! Reads Wavefront OBJ (with its MTL) and glTF 2.0 (`.gltf`, `.glb`);
//! quantises positions to `i16` with the most fraction bits that fit, normals
//! to Q14, texture coordinates to Q12; welds duplicate vertices; computes
//! vertex normals by face averaging where the file has none (by smoothing
//! group or crease angle) and tangents on request; converts a PNG texture to
//! `Rgb565`, `Gray8` or `Palette8`; and writes the `static`s a `no_std`
//! firmware `include!`s.
//!
//! One module per stage: [`read_obj`] and [`read_gltf`] read a file into a
//! [`SourceMesh`]; [`process`] makes a [`CompactMesh`] per part;
//! [`material`] converts the materials; [`texture`] converts the images;
//! [`emit`] writes the source; [`cli`] is the command-line tool. [`import`]
//! runs them all.
//!
//! From a build script (`build.rs`), with `fixshade-import` as a
//! build-dependency:
//!
//! ```no_run
//! use fixshade_import::{build, Options};
//! let mut options = Options::new("TEAPOT");
//! options.process.tangents = true;
//! // writes $OUT_DIR/teapot.rs and prints the cargo:rerun-if-changed lines
//! build::generate("models/teapot.obj", "teapot.rs", &options).unwrap();
//! ```
//!
//! and in the firmware: `include!(concat!(env!("OUT_DIR"), "/teapot.rs"));`
//! defines `TEAPOT: fixshade::mesh::Mesh<'static>`, `TEAPOT_FRAC`, the
//! arrays, `TEAPOT_MATERIAL` (a `fixshade::lighting::MaterialDesc`), the
//! counts `TEAPOT_VERTICES` and `TEAPOT_TRIANGLE_COUNT`, the buffers alias
//! `TEAPOT_BUFFERS` and the list `TEAPOT_PARTS`. A model of several materials
//! (or cut by [`ProcessOptions::split`]) gives one part each, `TEAPOT_PART0`,
//! `TEAPOT_PART1`, …, with the same items under its own prefix.
//!
//! A missing material library or texture is a warning and a default
//! (OpenGL's default material, no texture) unless [`Options::strict`]; the
//! materials are mapped by [`material`]; a closed mesh wound clockwise is a
//! warning ([`ProcessOptions::flip_winding`] reverses it).

#![forbid(unsafe_code)]
#![warn(missing_docs, missing_debug_implementations)]

pub mod cli;
pub mod emit;
mod error;
pub mod material;
pub mod process;
pub mod read_gltf;
pub mod read_obj;
mod source;
pub mod texture;

use std::path::{Path, PathBuf};

pub use error::{Error, FileKind};
pub use fixshade::mesh::Weighting;
pub use fixshade::texture::Wrap;
pub use material::PartMaterial;
pub use process::{
    CompactMesh, MeshReport, NormalSource, Orientation, ProcessOptions, ProcessedPart,
};
pub use source::{
    Corner, MaterialValues, MissingFile, Smoothing, SourceMaterial, SourceMesh, SourceTriangle,
    TextureSource,
};
pub use texture::{ConvertedTexture, TextureFormat};

use error::read_file;

/// Which texture to convert.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum TextureChoice {
    /// The diffuse texture of the model's materials (`map_Kd`, glTF base
    /// colour), if there is one.
    #[default]
    FromModel,
    /// This PNG instead.
    File(PathBuf),
    /// None.
    None,
}

/// Everything an import can be asked to do.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Prefix of the generated items: `NAME`, `NAME_POSITIONS`, …
    /// (`[A-Z_][A-Z0-9_]*`).
    pub name: String,
    /// Transform, quantisation, normals, tangents.
    pub process: ProcessOptions,
    /// Which texture.
    pub texture: TextureChoice,
    /// Its texel format.
    pub texture_format: TextureFormat,
    /// Its wrap mode.
    pub wrap: Wrap,
    /// Resample a texture whose sides are not powers of two (instead of an
    /// error).
    pub resize: bool,
    /// Missing material libraries and textures (named by the model) and
    /// material values outside OpenGL's ranges are errors (`--strict`);
    /// without, they are warnings with a default (OpenGL's default
    /// material, no texture, the value clamped).
    pub strict: bool,
}

impl Options {
    /// The defaults, with items named `name`: the model's texture as
    /// `Rgb565`, repeating, no resizing; see [`ProcessOptions::default`].
    pub fn new(name: &str) -> Self {
        Options {
            name: name.to_string(),
            process: ProcessOptions::default(),
            texture: TextureChoice::FromModel,
            texture_format: TextureFormat::Rgb565,
            wrap: Wrap::Repeat,
            resize: false,
            strict: false,
        }
    }

    /// The options as command-line flags (for the generated header).
    fn flags(&self) -> String {
        let p = &self.process;
        let mut f = vec![format!("--name {}", self.name)];
        if p.center {
            f.push("--center".into());
        }
        if p.scale != 1.0 {
            f.push(format!("--scale {}", p.scale));
        }
        if let Some(frac) = p.frac {
            f.push(format!("--frac {frac}"));
        }
        if let Some(a) = p.crease_angle {
            f.push(format!("--crease-angle {a}"));
        }
        if p.recompute_normals {
            f.push("--recompute-normals".into());
        }
        if p.weighting == Weighting::Area {
            f.push("--weighting area".into());
        }
        if !p.texcoords {
            f.push("--no-texcoords".into());
        }
        if p.tangents {
            f.push("--tangents".into());
        }
        if p.flip_winding {
            f.push("--flip-winding".into());
        }
        if p.split {
            f.push("--split".into());
        }
        match &self.texture {
            TextureChoice::FromModel => {}
            TextureChoice::File(path) => f.push(format!(
                "--texture {}",
                path.file_name().unwrap_or_default().to_string_lossy()
            )),
            TextureChoice::None => f.push("--no-texture".into()),
        }
        if self.texture_format != TextureFormat::Rgb565 {
            f.push(format!("--texture-format {}", self.texture_format.name()));
        }
        if self.wrap == Wrap::Clamp {
            f.push("--clamp".into());
        }
        if self.resize {
            f.push("--resize".into());
        }
        if self.strict {
            f.push("--strict".into());
        }
        f.join(" ")
    }
}

/// A converted texture and the name it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelTexture {
    /// The file name (or the glTF image's name).
    pub name: String,
    /// The texels.
    pub converted: ConvertedTexture,
}

/// One mesh of a model: the triangles of one material (or a piece of them,
/// with `--split`).
#[derive(Clone, Debug, PartialEq)]
pub struct ModelPart {
    /// The prefix of its generated items: the model's name for a model of one
    /// part, `NAME_PART0`, `NAME_PART1`, … otherwise.
    pub name: String,
    /// The mesh.
    pub mesh: CompactMesh,
    /// Its material.
    pub material: PartMaterial,
    /// Its texture, an index into [`Model::textures`].
    pub texture: Option<usize>,
}

/// An imported model: its parts (one per material; one for most models),
/// their textures, and what was done.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// The prefix of the generated items.
    pub name: String,
    /// The model's file name (for the generated comment).
    pub source_name: String,
    /// The meshes, in order of the materials' first use; all share
    /// `report.frac`.
    pub parts: Vec<ModelPart>,
    /// The distinct textures the parts use.
    pub textures: Vec<ModelTexture>,
    /// What processing found (counts over all parts).
    pub report: MeshReport,
    /// Polygons split into triangles.
    pub polygons_split: usize,
    /// Every file read or looked for (for `cargo:rerun-if-changed`).
    pub files: Vec<PathBuf>,
    /// Everything skipped or assumed.
    pub warnings: Vec<String>,
    /// The options as flags, for the generated header.
    pub options_line: String,
}

impl Model {
    /// The first part's mesh: the model's, when it has one part.
    ///
    /// # Panics
    ///
    /// For a model without parts ([`import`] never makes one).
    pub fn mesh(&self) -> &CompactMesh {
        &self.parts[0].mesh
    }

    /// The first part's texture: the model's, when it has one part.
    ///
    /// # Panics
    ///
    /// For a model without parts ([`import`] never makes one).
    pub fn texture(&self) -> Option<&ModelTexture> {
        self.texture_of(&self.parts[0])
    }

    /// A part's texture.
    pub fn texture_of(&self, part: &ModelPart) -> Option<&ModelTexture> {
        part.texture.and_then(|t| self.textures.get(t))
    }

    /// The Rust source ([`emit::rust_source`]).
    pub fn to_rust(&self) -> String {
        emit::rust_source(self)
    }

    /// Writes the Rust source to `path`.
    ///
    /// # Errors
    ///
    /// [`Error::Io`] when the file cannot be written.
    pub fn write_rust(&self, path: &Path) -> Result<(), Error> {
        std::fs::write(path, self.to_rust()).map_err(|e| Error::Io {
            kind: FileKind::Output,
            path: path.to_path_buf(),
            source: e,
        })
    }

    /// What the import did, one fact a line (the tool prints it).
    pub fn summary(&self) -> String {
        let r = &self.report;
        let mut s = vec![
            format!(
                "{}: {} triangles read ({} polygons split, {} degenerate dropped) -> {} vertices, {} triangles{}",
                self.source_name,
                r.source_triangles,
                self.polygons_split,
                r.degenerate_dropped,
                r.vertices,
                r.triangles,
                if self.parts.len() > 1 {
                    format!(" in {} parts", self.parts.len())
                } else {
                    String::new()
                }
            ),
            format!(
                "positions: frac = {}, step 2^-{} = {} model units, largest error {:.3e}; bounds [{:.4}, {:.4}, {:.4}] to [{:.4}, {:.4}, {:.4}]",
                r.frac, r.frac, r.step, r.max_position_error,
                r.bounds[0][0], r.bounds[0][1], r.bounds[0][2],
                r.bounds[1][0], r.bounds[1][1], r.bounds[1][2]
            ),
            format!(
                "normals: {}{}",
                match r.normals {
                    NormalSource::File => "the file's".to_string(),
                    NormalSource::SmoothingGroups => format!(
                        "smoothing groups ({} smoothing vertices at {} positions)",
                        r.smoothing_vertices, r.positions
                    ),
                    NormalSource::CreaseAngle(a) => format!(
                        "crease angle {a}° ({} smoothing vertices at {} positions)",
                        r.smoothing_vertices, r.positions
                    ),
                },
                if r.file_normals_negated {
                    "; the file's normals negated with the winding (they pointed inward)"
                } else {
                    ""
                }
            ),
            format!(
                "orientation: {}{}",
                match r.orientation {
                    Orientation::Open { edges } => format!(
                        "not closed ({edges} edges not shared by exactly two triangles): winding not checked"
                    ),
                    Orientation::Inconsistent { edges } => format!(
                        "closed, {edges} edges wound the same way in both triangles: inconsistent"
                    ),
                    Orientation::Closed { volume } => format!(
                        "closed, signed volume {volume:.4} ({})",
                        if volume < 0.0 {
                            "clockwise from outside: inside-out"
                        } else {
                            "counter-clockwise from outside"
                        }
                    ),
                },
                if r.winding_flipped {
                    "; every triangle reversed (--flip-winding)"
                } else {
                    ""
                }
            ),
        ];
        if let Some(e) = r.max_texcoord_error {
            s.push(format!("texture coordinates: Q12, largest error {e:.3e}"));
        }
        let mut described = vec![false; self.textures.len()];
        for part in &self.parts {
            if self.parts.len() > 1 {
                s.push(format!(
                    "part {}: {} vertices, {} triangles",
                    part.name,
                    part.mesh.positions.len(),
                    part.mesh.triangles.len()
                ));
            }
            let m = &part.material;
            let d = &m.desc;
            s.push(format!(
                "{}material {}: ambient {:?}, diffuse {:?}, specular {:?}, emission {:?}, shininess {:?}, opacity {:?}",
                if self.parts.len() > 1 { "  " } else { "" },
                m.name
                    .as_ref()
                    .map_or_else(|| "(none): OpenGL's default".to_string(), |n| format!("`{n}`")),
                d.ambient,
                d.diffuse,
                d.specular,
                d.emission,
                d.shininess,
                m.opacity
            ));
            let Some(ti) = part.texture else { continue };
            let Some(t) = self.textures.get(ti) else {
                continue;
            };
            let indent = if self.parts.len() > 1 { "  " } else { "" };
            if described[ti] {
                s.push(format!("{indent}texture {}: as above", t.name));
                continue;
            }
            described[ti] = true;
            let c = &t.converted;
            let q = &c.report;
            s.push(format!(
                "{indent}texture {}: {} x {}{} as {} ({} bytes), {} colours{}, error max {} rms {:.2} (8-bit LSBs)",
                t.name,
                1u32 << c.log2_width,
                1u32 << c.log2_height,
                if q.resized {
                    format!(" (resized from {} x {})", q.source_size.0, q.source_size.1)
                } else {
                    String::new()
                },
                q.format.name(),
                q.bytes,
                q.source_colours,
                if q.quantised { " quantised to 256" } else { "" },
                q.max_error,
                q.rms_error
            ));
        }
        let bytes: usize = self
            .parts
            .iter()
            .map(|p| {
                let m = &p.mesh;
                12 * m.positions.len()
                    + 6 * m.triangles.len()
                    + m.texcoords.as_ref().map_or(0, |t| 4 * t.len())
                    + m.tangents.as_ref().map_or(0, |t| 8 * t.len())
            })
            .sum();
        s.push(format!("mesh arrays: {bytes} bytes of flash"));
        for w in &self.warnings {
            s.push(format!("warning: {w}"));
        }
        s.join("\n")
    }
}

/// Reads a model by its extension (`.obj`, `.gltf`, `.glb`, any case).
///
/// # Errors
///
/// [`Error::Unsupported`] for another extension; the readers' errors.
pub fn read_source(path: &Path) -> Result<SourceMesh, Error> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "obj" => read_obj::read(path),
        "gltf" | "glb" => read_gltf::read(path),
        _ => Err(Error::Unsupported {
            path: path.to_path_buf(),
            what: format!("extension {ext:?} (expected .obj, .gltf or .glb)"),
        }),
    }
}

/// Whether `name` is an upper-case identifier the generated items can use.
fn valid_name(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some('A'..='Z' | '_'))
        && chars.all(|c| matches!(c, 'A'..='Z' | '0'..='9' | '_'))
        && name != "_"
}

/// Imports the model at `path`: reads it, processes the meshes (one part per
/// material), converts the materials and the textures.
///
/// A missing material library or texture that the model names, or a
/// material value outside OpenGL's ranges, is a warning (in
/// [`Model::warnings`]) and a default, or with [`Options::strict`] an error.
///
/// # Errors
///
/// Every [`Error`] variant but [`Error::NoOutDir`].
pub fn import(path: &Path, options: &Options) -> Result<Model, Error> {
    if !valid_name(&options.name) {
        return Err(Error::InvalidName(options.name.clone()));
    }
    let source = read_source(path)?;
    let mut files = source.files.clone();
    let mut warnings = source.warnings.clone();
    for m in &source.missing {
        if options.strict {
            return Err(Error::MissingFile {
                kind: m.kind,
                path: m.path.clone(),
            });
        }
        warnings.push(format!(
            "{} file not found: {}: {}",
            m.kind,
            m.path.display(),
            m.instead
        ));
        // rerun a build script when it appears
        files.push(m.path.clone());
    }
    let (processed, report) = process::process(&source, &options.process, path)?;
    warnings.extend(report.warnings.iter().cloned());

    // the materials the parts use, each converted once
    let mut materials: Vec<Option<PartMaterial>> = vec![None; source.materials.len()];
    for p in &processed {
        if let Some(m) = p.material {
            if materials[m].is_none() {
                materials[m] = Some(material::convert(
                    &source.materials[m],
                    options.strict,
                    &mut warnings,
                )?);
            }
        }
    }

    // the textures, each read and converted once
    let mut textures: Vec<ModelTexture> = Vec::new();
    let mut loaded: Vec<(TextureSource, Option<usize>)> = Vec::new();
    let several = processed.len() > 1;
    let mut parts = Vec::with_capacity(processed.len());
    for (i, p) in processed.into_iter().enumerate() {
        let material_name = p.material.map(|m| source.materials[m].name.as_str());
        let chosen = match &options.texture {
            TextureChoice::None => None,
            TextureChoice::File(f) => Some(TextureSource::File(f.clone())),
            TextureChoice::FromModel => {
                p.material.and_then(|m| source.materials[m].texture.clone())
            }
        };
        let texture = match chosen {
            None => None,
            Some(src) => match loaded.iter().find(|(s, _)| *s == src) {
                Some((_, t)) => *t,
                None => {
                    let explicit = matches!(options.texture, TextureChoice::File(_));
                    let t = load_texture(
                        &src,
                        &p.mesh,
                        options,
                        explicit,
                        material_name,
                        &mut files,
                        &mut warnings,
                    )?;
                    let index = t.map(|t| {
                        textures.push(t);
                        textures.len() - 1
                    });
                    loaded.push((src, index));
                    index
                }
            },
        };
        parts.push(ModelPart {
            name: if several {
                format!("{}_PART{i}", options.name)
            } else {
                options.name.clone()
            },
            mesh: p.mesh,
            material: p
                .material
                .and_then(|m| materials[m].clone())
                .unwrap_or_default(),
            texture,
        });
    }
    Ok(Model {
        name: options.name.clone(),
        source_name: path
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned(),
        parts,
        textures,
        report,
        polygons_split: source.polygons_split,
        files,
        warnings,
        options_line: format!(
            "fixshade-import {} {}",
            path.file_name().unwrap_or_default().to_string_lossy(),
            options.flags()
        ),
    })
}

/// Reads and converts one texture; `None` (and a warning) when a file the
/// model names is missing and the options are not strict.
fn load_texture(
    src: &TextureSource,
    mesh: &CompactMesh,
    options: &Options,
    explicit: bool,
    material: Option<&str>,
    files: &mut Vec<PathBuf>,
    warnings: &mut Vec<String>,
) -> Result<Option<ModelTexture>, Error> {
    let (name, path, bytes) = match src {
        TextureSource::File(p) => {
            let bytes = match read_file(FileKind::Texture, p) {
                Ok(b) => b,
                Err(Error::MissingFile { kind, path }) if !(options.strict || explicit) => {
                    warnings.push(format!(
                        "{kind} file not found: {}{}: drawn untextured",
                        path.display(),
                        material.map_or_else(String::new, |m| format!(" (material `{m}`)"))
                    ));
                    files.push(path);
                    return Ok(None);
                }
                Err(e) => return Err(e),
            };
            files.push(p.clone());
            let name = p
                .file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned();
            (name, p.clone(), bytes)
        }
        TextureSource::Embedded { name, bytes, .. } => {
            (name.clone(), PathBuf::from(name), bytes.clone())
        }
    };
    if mesh.texcoords.is_none() {
        return Err(Error::NoTexcoords);
    }
    if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        return Err(Error::Unsupported {
            path,
            what: "texture format: only PNG textures are read".into(),
        });
    }
    let image = texture::decode_png(&bytes, &path)?;
    let converted = texture::convert(
        &image,
        &path,
        options.texture_format,
        options.wrap,
        options.resize,
    )?;
    warnings.extend(converted.report.warnings.iter().cloned());
    Ok(Some(ModelTexture { name, converted }))
}

/// The build-script route: import a model into `$OUT_DIR`.
pub mod build {
    use std::io::Write;
    use std::path::{Path, PathBuf};

    use crate::{import, Error, FileKind, Options};

    /// Imports `input` (relative to the package being built) with `options`,
    /// writes the source to `$OUT_DIR/file_name`, prints
    /// `cargo:rerun-if-changed` for every file read (and for the folder of
    /// every missing file the model names: the script reruns when the file
    /// appears), and returns the path written. Warnings (a missing MTL or texture, a clamped material
    /// value, a model wound clockwise, …) are printed as `cargo:warning=`
    /// lines; [`Options::strict`] makes the missing files and bad values
    /// errors.
    ///
    /// # Errors
    ///
    /// [`Error::NoOutDir`] outside a build script; the errors of
    /// [`import`] and of writing the file.
    pub fn generate(
        input: impl AsRef<Path>,
        file_name: &str,
        options: &Options,
    ) -> Result<PathBuf, Error> {
        let out_dir = std::env::var_os("OUT_DIR").ok_or(Error::NoOutDir)?;
        generate_in(
            input,
            Path::new(&out_dir),
            file_name,
            options,
            &mut std::io::stdout().lock(),
        )
    }

    /// [`generate`] without the environment: writes `out_dir/file_name` and
    /// the `cargo:` lines to `cargo` (a build script's standard output).
    ///
    /// # Errors
    ///
    /// As [`generate`] (but for [`Error::NoOutDir`]); writing to `cargo`
    /// failing is an [`Error::Io`].
    pub fn generate_in(
        input: impl AsRef<Path>,
        out_dir: &Path,
        file_name: &str,
        options: &Options,
        cargo: &mut dyn Write,
    ) -> Result<PathBuf, Error> {
        let io = |e: std::io::Error| Error::Io {
            kind: FileKind::Output,
            path: PathBuf::from("<build script output>"),
            source: e,
        };
        let out = out_dir.join(file_name);
        let result = import(input.as_ref(), options);
        // rerun when the model changes, even after an error
        writeln!(cargo, "cargo:rerun-if-changed={}", input.as_ref().display()).map_err(io)?;
        let model = result?;
        for f in &model.files {
            // a missing file: its folder (or the nearest one that exists),
            // which changes when the file appears; cargo would rerun the
            // script on every build for a path that does not exist
            let watched = f
                .ancestors()
                .find(|a| a.exists())
                .filter(|a| !a.as_os_str().is_empty())
                .unwrap_or(Path::new("."));
            writeln!(cargo, "cargo:rerun-if-changed={}", watched.display()).map_err(io)?;
        }
        for w in &model.warnings {
            writeln!(cargo, "cargo:warning={}: {w}", model.source_name).map_err(io)?;
        }
        model.write_rust(&out)?;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn names() {
        for ok in ["TEAPOT", "_X", "A1_B"] {
            assert!(super::valid_name(ok), "{ok}");
        }
        for bad in ["", "_", "teapot", "1A", "A-B", "Ä"] {
            assert!(!super::valid_name(bad), "{bad}");
        }
    }
}
