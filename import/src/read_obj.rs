//! Wavefront OBJ and its MTL material libraries, read through `tobj`.
//!
//! `tobj` parses the geometry and the materials. What it does not keep is
//! recovered by a light pre-scan of the text:
//!
//! - **smoothing groups** (`s N`, `s off`): `tobj` ignores them; the pre-scan
//!   records the group of every face in file order, which is the order of
//!   `tobj`'s faces (its models are consecutive runs of the file's faces);
//! - **line numbers**: `tobj` stops at the first malformed line and reports
//!   only the kind of fault. The reader counts the lines `tobj` consumed, so
//!   the fault is on the last one; index faults, which `tobj` finds only when
//!   it closes an object, are located by checking every face's indices in the
//!   pre-scan.
//!
//! Polygons are split into fans `(0, i, i + 1)` (as `tobj`'s own `triangulate`
//! does; right for convex polygons). Points and lines are skipped (`l` lines
//! are blanked before `tobj` sees them: it would read a polyline of three
//! points as a face).

use std::cell::RefCell;
use std::collections::HashMap;
use std::io::{BufRead, Cursor, Read};
use std::path::{Path, PathBuf};

use crate::error::{io_error, read_file, Error, FileKind};
use crate::source::{
    Corner, MaterialValues, MissingFile, Smoothing, SourceMaterial, SourceMesh, SourceTriangle,
    TextureSource,
};

/// Reads the OBJ at `path` and the material libraries it names (relative to
/// its folder). A missing material library is not an error here: it is
/// listed in [`SourceMesh::missing`] and its materials are OpenGL's default
/// ([`crate::import`] makes it an error with `--strict`).
///
/// # Errors
///
/// [`Error::MissingFile`] for a missing OBJ; [`Error::Parse`] with the line
/// number for a malformed OBJ or MTL line or a face index out of range;
/// [`Error::Io`] for other read failures.
pub fn read(path: &Path) -> Result<SourceMesh, Error> {
    let bytes = read_file(FileKind::Model, path)?;
    read_bytes(path, &bytes)
}

/// [`read`] on the file's bytes (`path` names it and anchors relative paths).
fn read_bytes(path: &Path, bytes: &[u8]) -> Result<SourceMesh, Error> {
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let Prescan {
        faces,
        text,
        polylines,
        usemtl,
    } = prescan(bytes);
    let loader = MaterialLoader::new(dir);
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = LineCounter::new(Cursor::new(&text[..]));
    let loaded = tobj::load_obj_buf(&mut reader, &options, |p| loader.load(p));
    let (models, materials) = match loaded {
        Ok(m) => m,
        Err(e) => {
            let line = match e {
                tobj::LoadError::FaceVertexOutOfBounds
                | tobj::LoadError::FaceTexCoordOutOfBounds
                | tobj::LoadError::FaceNormalOutOfBounds
                | tobj::LoadError::FaceColorOutOfBounds => find_index_fault(bytes),
                _ => Some(reader.line()),
            };
            return Err(parse_error(path, bytes, line, &e.to_string()));
        }
    };
    let MaterialLoader {
        error,
        material_dirs,
        files,
        missing,
        ..
    } = loader;
    if let Some(e) = error.into_inner() {
        return Err(e);
    }
    let materials = materials.unwrap_or_default();
    let material_dirs = material_dirs.into_inner();

    let mut out = SourceMesh {
        files: std::iter::once(path.to_path_buf())
            .chain(files.into_inner())
            .collect(),
        missing: missing.into_inner(),
        ..SourceMesh::default()
    };
    // `usemtl` names no library defines (tobj gives their faces no material)
    let mut unfound: Vec<&str> = usemtl
        .iter()
        .map(String::as_str)
        .filter(|n| !materials.iter().any(|m| m.name == *n))
        .collect();
    unfound.dedup();
    // (a missing library has its own warning)
    if !unfound.is_empty() && out.missing.is_empty() {
        out.warnings.push(format!(
            "no material library defines {}: OpenGL's default material used",
            unfound
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    // tobj's material index → ours (the materials used, in order of first use)
    let mut material_index: HashMap<usize, usize> = HashMap::new();
    let mut face_index = 0usize;
    let mut mismatch = false;
    let mut partial = [false; 2];
    for model in &models {
        let m = &model.mesh;
        let nv = m.positions.len() / 3;
        let has_normals = m.normals.len() == 3 * nv;
        let has_uv = m.texcoords.len() == 2 * nv;
        partial[0] |= !has_normals && !m.normals.is_empty();
        partial[1] |= !has_uv && !m.texcoords.is_empty();
        let corner = |i: u32| -> Corner {
            let i = i as usize;
            let p = |k: usize| f64::from(m.positions.get(3 * i + k).copied().unwrap_or(0.0));
            let n = |k: usize| f64::from(m.normals.get(3 * i + k).copied().unwrap_or(0.0));
            let t = |k: usize| f64::from(m.texcoords.get(2 * i + k).copied().unwrap_or(0.0));
            Corner {
                position: [p(0), p(1), p(2)],
                normal: has_normals.then(|| [n(0), n(1), n(2)]),
                // OBJ's v runs up the image, fixshade's down it
                texcoord: has_uv.then(|| [t(0), 1.0 - t(1)]),
            }
        };
        let material = match m.material_id.filter(|&id| id < materials.len()) {
            None => None,
            Some(id) => Some(match material_index.get(&id) {
                Some(&i) => i,
                None => {
                    let mat = &materials[id];
                    let texture = diffuse_texture(mat, &material_dirs, &mut out.warnings);
                    out.materials.push(SourceMaterial {
                        name: mat.name.clone(),
                        values: mtl_values(mat, &mut out.warnings),
                        texture,
                    });
                    material_index.insert(id, out.materials.len() - 1);
                    out.materials.len() - 1
                }
            }),
        };
        let arities: Vec<u32> = if m.face_arities.is_empty() {
            vec![3; m.indices.len() / 3]
        } else {
            m.face_arities.clone()
        };
        let mut start = 0usize;
        for &n in &arities {
            let n = n as usize;
            let smoothing = faces.get(face_index).copied().unwrap_or_else(|| {
                mismatch = true;
                Smoothing::Unspecified
            });
            face_index += 1;
            let idx = m.indices.get(start..start + n).unwrap_or(&[]);
            start += n;
            if idx.len() > 3 {
                out.polygons_split += 1;
            }
            for k in 1..idx.len().saturating_sub(1) {
                out.triangles.push(SourceTriangle {
                    corners: [corner(idx[0]), corner(idx[k]), corner(idx[k + 1])],
                    smoothing,
                    material,
                });
            }
        }
    }
    if mismatch || face_index != faces.len() {
        // never seen; keep the geometry, lose the groups
        out.warnings.push(format!(
            "smoothing groups ignored: tobj read {face_index} faces, the pre-scan {}",
            faces.len()
        ));
        for t in &mut out.triangles {
            t.smoothing = Smoothing::Unspecified;
        }
    }
    if polylines > 0 {
        out.warnings
            .push(format!("{polylines} polylines (`l` lines) skipped"));
    }
    if partial[0] {
        out.warnings.push(
            "an object has normals on some faces only: its normals are computed instead".into(),
        );
    }
    if partial[1] {
        out.warnings.push(
            "an object has texture coordinates on some faces only: its texture coordinates are dropped"
                .into(),
        );
    }
    Ok(out)
}

/// The values of an MTL material as written (`Tr` is not kept by `tobj`:
/// read from its unknown parameters).
fn mtl_values(mat: &tobj::Material, warnings: &mut Vec<String>) -> MaterialValues {
    let c = |v: Option<[f32; 3]>| v.map(|v| v.map(f64::from));
    let transparency = mat.unknown_param.get("Tr").and_then(|v| {
        let parsed = v.trim().parse::<f64>().ok();
        if parsed.is_none() {
            warnings.push(format!(
                "material `{}`: `Tr {v}` is not a number: ignored",
                mat.name
            ));
        }
        parsed
    });
    MaterialValues::Mtl {
        ambient: c(mat.ambient),
        diffuse: c(mat.diffuse),
        specular: c(mat.specular),
        emission: c(mat.emissive),
        shininess: mat.shininess.map(f64::from),
        dissolve: mat.dissolve.map(f64::from),
        transparency,
    }
}

/// The diffuse texture of `mat`, resolved against the folder of its MTL.
fn diffuse_texture(
    mat: &tobj::Material,
    dirs: &HashMap<String, PathBuf>,
    warnings: &mut Vec<String>,
) -> Option<TextureSource> {
    let spec = mat.diffuse_texture.as_deref()?.trim();
    // `map_Kd -o 0 0 0 -s 1 1 1 file.png`: options precede the file name
    let name = if spec.starts_with('-') {
        warnings.push(format!("map_Kd options ignored in {spec:?}"));
        spec.split_whitespace().last()?
    } else {
        spec
    };
    let dir = dirs.get(&mat.name).cloned().unwrap_or_default();
    Some(TextureSource::File(dir.join(name.replace('\\', "/"))))
}

/// What the pre-scan finds.
struct Prescan {
    /// The smoothing group of every face (`f` of three or more corners) in
    /// file order.
    faces: Vec<Smoothing>,
    /// The text for `tobj`, polylines (`l` lines, which it would read as
    /// faces) blanked to comments, line numbers kept.
    text: Vec<u8>,
    /// The number of those.
    polylines: usize,
    /// The material names of the `usemtl` lines, in order.
    usemtl: Vec<String>,
}

/// See [`Prescan`].
fn prescan(bytes: &[u8]) -> Prescan {
    let mut kept = Vec::with_capacity(bytes.len());
    let mut polylines = 0;
    for line in bytes.split_inclusive(|&b| b == b'\n') {
        let first = line
            .split(|b| b.is_ascii_whitespace())
            .find(|w| !w.is_empty());
        if first == Some(b"l") {
            polylines += 1;
            kept.push(b'#');
            kept.extend(line.iter().skip_while(|&&b| b != b'\n' && b != b'\r'));
        } else {
            kept.extend_from_slice(line);
        }
    }
    let text = String::from_utf8_lossy(bytes);
    let has_groups = text
        .lines()
        .any(|l| l.split_whitespace().next() == Some("s"));
    // OBJ's default before any `s` statement is "off"
    let mut smoothing = if has_groups {
        Smoothing::Off
    } else {
        Smoothing::Unspecified
    };
    let mut faces = Vec::new();
    let mut usemtl = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("usemtl") => {
                // as tobj reads it: the rest of the line, trimmed
                let name = line.trim().split_once(' ').unwrap_or_default().1.trim();
                if !name.is_empty() && !usemtl.iter().any(|n| n == name) {
                    usemtl.push(name.to_string());
                }
            }
            Some("s") => {
                smoothing = match words.next() {
                    Some("off") | Some("0") | None => Smoothing::Off,
                    Some(n) => n.parse().map_or(Smoothing::Off, Smoothing::Group),
                };
            }
            Some("f") if words.count() >= 3 => faces.push(smoothing),
            _ => {}
        }
    }
    Prescan {
        faces,
        text: kept,
        polylines,
        usemtl,
    }
}

/// The first line (1-based) of a face whose vertex, texture or normal index
/// is outside the file's lists, resolved as `tobj` does (negative indices
/// count back from the elements defined so far, 0 is invalid).
fn find_index_fault(bytes: &[u8]) -> Option<usize> {
    let text = String::from_utf8_lossy(bytes);
    let mut totals = [0usize; 3];
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => totals[0] += 1,
            Some("vt") => totals[1] += 1,
            Some("vn") => totals[2] += 1,
            _ => {}
        }
    }
    let mut seen = [0usize; 3];
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => seen[0] += 1,
            Some("vt") => seen[1] += 1,
            Some("vn") => seen[2] += 1,
            Some("f") => {
                for word in words {
                    for (k, part) in word.split('/').enumerate().take(3) {
                        let Ok(x) = part.parse::<i64>() else {
                            continue;
                        };
                        // tobj checks texture and normal indices only when the
                        // file has any
                        if k > 0 && totals[k] == 0 {
                            continue;
                        }
                        let ok = if x < 0 {
                            seen[k] as i64 + x >= 0
                        } else {
                            x >= 1 && (x as usize) <= totals[k]
                        };
                        if !ok {
                            return Some(number + 1);
                        }
                    }
                }
            }
            _ => {}
        }
    }
    None
}

/// An [`Error::Parse`] quoting line `line` of `bytes`.
fn parse_error(path: &Path, bytes: &[u8], line: Option<usize>, message: &str) -> Error {
    let quoted = line.and_then(|n| {
        String::from_utf8_lossy(bytes)
            .lines()
            .nth(n.checked_sub(1)?)
            .map(|l| l.trim().chars().take(80).collect::<String>())
    });
    Error::Parse {
        path: path.to_path_buf(),
        line,
        message: match quoted {
            Some(q) if !q.is_empty() => format!("{message}: `{q}`"),
            _ => message.to_string(),
        },
    }
}

/// `tobj`'s material callback: opens an MTL relative to the OBJ's folder,
/// keeps the first error (a malformed line, a read failure), the missing
/// libraries (read as empty) and the folder of every material (its textures
/// are relative to it).
struct MaterialLoader {
    dir: PathBuf,
    error: RefCell<Option<Error>>,
    material_dirs: RefCell<HashMap<String, PathBuf>>,
    files: RefCell<Vec<PathBuf>>,
    missing: RefCell<Vec<MissingFile>>,
}

impl MaterialLoader {
    fn new(dir: PathBuf) -> Self {
        MaterialLoader {
            dir,
            error: RefCell::new(None),
            material_dirs: RefCell::new(HashMap::new()),
            files: RefCell::new(Vec::new()),
            missing: RefCell::new(Vec::new()),
        }
    }

    fn load(&self, name: &Path) -> tobj::MTLLoadResult {
        let path = self.dir.join(name);
        let fail = |e: Error| {
            self.error.borrow_mut().get_or_insert(e);
            Err(tobj::LoadError::OpenFileFailed)
        };
        let bytes = match std::fs::read(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                let mut missing = self.missing.borrow_mut();
                if !missing.iter().any(|m| m.path == path) {
                    missing.push(MissingFile {
                        kind: FileKind::MaterialLibrary,
                        path,
                        instead: "its materials are OpenGL's default material, untextured".into(),
                    });
                }
                return Ok((Vec::new(), HashMap::new()));
            }
            Err(e) => return fail(io_error(FileKind::MaterialLibrary, &path, e)),
        };
        self.files.borrow_mut().push(path.clone());
        let mut reader = LineCounter::new(Cursor::new(&bytes[..]));
        match tobj::load_mtl_buf(&mut reader) {
            Ok((materials, map)) => {
                let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
                let mut dirs = self.material_dirs.borrow_mut();
                for m in &materials {
                    dirs.entry(m.name.clone()).or_insert_with(|| dir.clone());
                }
                Ok((materials, map))
            }
            Err(e) => fail(parse_error(
                &path,
                &bytes,
                Some(reader.line()),
                &e.to_string(),
            )),
        }
    }
}

/// A `BufRead` that counts the lines consumed through it, so that the line a
/// line-by-line parser stopped at is known.
struct LineCounter<R> {
    inner: R,
    newlines: usize,
    ends_with_newline: bool,
}

impl<R> LineCounter<R> {
    fn new(inner: R) -> Self {
        LineCounter {
            inner,
            newlines: 0,
            ends_with_newline: true,
        }
    }

    /// The 1-based number of the last line consumed (partly or wholly).
    fn line(&self) -> usize {
        if self.ends_with_newline {
            self.newlines.max(1)
        } else {
            self.newlines + 1
        }
    }
}

impl<R: BufRead> Read for LineCounter<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.count(buf.get(..n).unwrap_or(&[]));
        Ok(n)
    }
}

impl<R: BufRead> BufRead for LineCounter<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amt: usize) {
        let (newlines, last) = match self.inner.fill_buf() {
            Ok(buf) => {
                let b = buf.get(..amt).unwrap_or(buf);
                (b.iter().filter(|&&c| c == b'\n').count(), b.last().copied())
            }
            Err(_) => (0, None),
        };
        self.add(newlines, last);
        self.inner.consume(amt);
    }
}

impl<R> LineCounter<R> {
    fn count(&mut self, bytes: &[u8]) {
        let newlines = bytes.iter().filter(|&&c| c == b'\n').count();
        self.add(newlines, bytes.last().copied());
    }

    fn add(&mut self, newlines: usize, last: Option<u8>) {
        if let Some(last) = last {
            self.newlines += newlines;
            self.ends_with_newline = last == b'\n';
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<SourceMesh, Error> {
        read_bytes(Path::new("mem.obj"), text.as_bytes())
    }

    #[test]
    fn line_of_a_malformed_vertex() {
        let e = parse("# a\nv 0 0 0\nv 1 0 0\nv 0 zero 0\nf 1 2 3\n").unwrap_err();
        match e {
            Error::Parse { line, message, .. } => {
                assert_eq!(line, Some(4));
                assert!(message.contains("v 0 zero 0"), "{message}");
            }
            e => panic!("{e}"),
        }
        // the last line without a newline
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 q").unwrap_err();
        assert!(matches!(e, Error::Parse { line: Some(4), .. }), "{e}");
    }

    #[test]
    fn index_faults_are_located_by_the_prescan() {
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\nv 1 1 1\n").unwrap_err();
        assert!(matches!(e, Error::Parse { line: Some(5), .. }), "{e}");
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n").unwrap_err();
        assert!(matches!(e, Error::Parse { line: Some(4), .. }), "{e}");
    }

    #[test]
    fn smoothing_groups_follow_the_faces() {
        let m = parse(
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\ns 2\nf 1 3 4\no b\ns off\nf 1 2 4\n",
        )
        .unwrap();
        let s: Vec<_> = m.triangles.iter().map(|t| t.smoothing).collect();
        assert_eq!(s, [Smoothing::Off, Smoothing::Group(2), Smoothing::Off]);
        let m = parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(m.triangles[0].smoothing, Smoothing::Unspecified);
    }

    #[test]
    fn texcoords_flip_v_and_polylines_are_skipped() {
        let m =
            parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0.25\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\nl 1 2 3\n")
                .unwrap();
        assert_eq!(m.triangles.len(), 1);
        assert_eq!(m.triangles[0].corners[0].texcoord, Some([0.0, 0.75]));
        assert_eq!(m.triangles[0].corners[2].texcoord, Some([1.0, 0.0]));
        assert_eq!(m.warnings.len(), 1, "{:?}", m.warnings);
    }
}
