//! From a source triangle soup to fixshade's compact mesh: transform,
//! quantise, smooth, weld, tangents.
//!
//! 1. **Transform** (only if asked): `p' = (p − c) · s`, `c` the centre of the
//!    bounding box with `--center`, `s` from `--scale`.
//! 2. **`frac`**: the largest number of fraction bits `≤ 15` at which every
//!    coordinate rounds into an `i16` ([`frac_for_range`]); the quantisation
//!    step is `2^−frac`. Positions are rounded by the library's
//!    [`to_compact`].
//! 3. **Degenerate triangles** (two corners on the same quantised position)
//!    are dropped: they cover no pixel. With `--flip-winding` every triangle
//!    is reversed here.
//! 4. **Orientation**: a closed mesh (every edge, between quantised
//!    positions, shared by exactly two triangles, running opposite ways in
//!    them) has a signed volume `Σ a · (b × c) / 6`; a negative one means the
//!    triangles are clockwise from outside: a warning. Open meshes are not
//!    checked (they have no inside).
//! 5. **Normals** where the file has none: the library's [`vertex_normals`]
//!    (face averaging, angle-weighted by default) over *smoothing vertices*:
//!    the corners at one quantised position are split into groups that share
//!    a normal — by OBJ smoothing group (`s N` shares within group `N`, `s off`
//!    gives every face its own normal), or by crease angle (two triangles
//!    sharing an edge share the normals at its ends when their face normals
//!    differ by at most the angle; sharing is transitive around a vertex).
//!    Computed over the whole model, more than 65 536 smoothing vertices in
//!    overlapping chunks.
//! 6. **Parts and welding**: the triangles of each material form a part (in
//!    order of first use); within a part, corners with the same quantised
//!    position, Q14 normal and Q12 texture coordinate become one vertex
//!    (first use first). A part over [`MAX_VERTICES`] or [`MAX_TRIANGLES`] is
//!    an error, or with `--split` is cut, in file order, into parts that fit.
//! 7. **Tangents** (if asked): the library's [`vertex_tangents`] (Q14) on
//!    each welded part.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use fixshade::error::MeshError;
use fixshade::mesh::{
    to_compact, vertex_normals, vertex_tangents, Mesh, Weighting, NORMAL_ONE, TEXCOORD_FRAC,
};

use crate::error::Error;
use crate::source::{Smoothing, SourceMesh};

/// The default crease angle (degrees) when the file has neither normals nor
/// smoothing groups.
pub const DEFAULT_CREASE_ANGLE: f64 = 60.0;

/// The most vertices an imported mesh (a part) may have: `u16` indices, the
/// last value kept free.
pub const MAX_VERTICES: usize = 65_535;

/// The most triangles an imported mesh (a part) may have: the renderer bins
/// triangles by `u16` index and rejects more (`RenderError::TooManyVertices`
/// from `MeshDraw::new`).
pub const MAX_TRIANGLES: usize = 65_535;

/// How a mesh is processed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProcessOptions {
    /// Move the centre of the bounding box to the origin (before scaling).
    pub center: bool,
    /// Multiply every position by this (after centring); 1 keeps the file's
    /// units.
    pub scale: f64,
    /// Fraction bits of the positions; `None` chooses the largest that fits.
    pub frac: Option<u8>,
    /// Split vertex normals where adjacent faces differ by more than this many
    /// degrees. `None`: the file's smoothing groups if it has any, else
    /// [`DEFAULT_CREASE_ANGLE`]. Given, it overrides smoothing groups.
    pub crease_angle: Option<f64>,
    /// Ignore the file's normals and compute all of them.
    pub recompute_normals: bool,
    /// How faces are weighted in the face average.
    pub weighting: Weighting,
    /// Keep texture coordinates (when the file has them).
    pub texcoords: bool,
    /// Compute tangents (needs texture coordinates).
    pub tangents: bool,
    /// Reverse every triangle (`--flip-winding`): for a model wound
    /// clockwise from outside. The file's normals are negated too when most
    /// of them point against the reversed faces (inward).
    pub flip_winding: bool,
    /// Cut a part over [`MAX_VERTICES`] or [`MAX_TRIANGLES`] into parts that
    /// fit (`--split`) instead of an error.
    pub split: bool,
}

impl Default for ProcessOptions {
    fn default() -> Self {
        ProcessOptions {
            center: false,
            scale: 1.0,
            frac: None,
            crease_angle: None,
            recompute_normals: false,
            weighting: Weighting::Angle,
            texcoords: true,
            tangents: false,
            flip_winding: false,
            split: false,
        }
    }
}

/// Where the normals of a processed mesh come from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormalSource {
    /// The file's own normals, at every corner.
    File,
    /// Face averages within the file's smoothing groups (for the corners
    /// without a file normal).
    SmoothingGroups,
    /// Face averages split at creases sharper than the angle (degrees).
    CreaseAngle(f64),
}

/// Whether a mesh is closed and which way it is wound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Orientation {
    /// Some edges are not shared by exactly two triangles (a boundary, or
    /// more than two faces on an edge): the mesh has no inside, not checked.
    Open {
        /// Those edges.
        edges: usize,
    },
    /// Closed, but some edges run the same way in both of their triangles:
    /// faces wound against their neighbours.
    Inconsistent {
        /// Those edges.
        edges: usize,
    },
    /// Closed and consistently wound.
    Closed {
        /// The signed volume `Σ a · (b × c) / 6` in model units³ (after
        /// `--center`, `--scale` and `--flip-winding`): positive when the
        /// triangles are counter-clockwise from outside, as fixshade draws
        /// front faces.
        volume: f64,
    },
}

/// One part of a processed model: the triangles of one material (or a piece
/// of them, with `split`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProcessedPart {
    /// The material, an index into `SourceMesh::materials` (`None`: none).
    pub material: Option<usize>,
    /// The part's mesh.
    pub mesh: CompactMesh,
}

/// The compact mesh as owned arrays, ready to emit or to view as a
/// [`Mesh`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CompactMesh {
    /// Positions, `raw · 2^−frac` model units.
    pub positions: Vec<[i16; 3]>,
    /// Unit normals, Q14.
    pub normals: Vec<[i16; 3]>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u16; 3]>,
    /// Texture coordinates, Q12 (`v` down the image), if kept.
    pub texcoords: Option<Vec<[i16; 2]>>,
    /// Tangents, Q14 with the handedness `±16384` in `[3]`, if asked for.
    pub tangents: Option<Vec<[i16; 4]>>,
    /// Fraction bits of the positions.
    pub frac: u8,
}

impl CompactMesh {
    /// The library's view of these arrays (texture coordinates and tangents
    /// attached when present).
    ///
    /// # Errors
    ///
    /// Those of [`Mesh::new`]; never for a mesh made by [`process`].
    pub fn mesh(&self) -> Result<Mesh<'_>, MeshError> {
        let mut m = Mesh::new(&self.positions, &self.normals, &self.triangles, self.frac)?;
        if let Some(t) = &self.texcoords {
            m = m.with_texcoords(t)?;
        }
        if let Some(t) = &self.tangents {
            m = m.with_tangents(t)?;
        }
        Ok(m)
    }

    /// The quantisation step of the positions, `2^−frac` model units.
    pub fn step(&self) -> f64 {
        step(self.frac)
    }
}

/// What processing found and decided, for the tool's output and the
/// generated comment.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshReport {
    /// Triangles read from the file.
    pub source_triangles: usize,
    /// Triangles dropped because two corners quantised to one position.
    pub degenerate_dropped: usize,
    /// Distinct quantised positions.
    pub positions: usize,
    /// Smoothing vertices (position × normal group) before welding.
    pub smoothing_vertices: usize,
    /// Vertices after welding (all parts).
    pub vertices: usize,
    /// Triangles emitted (all parts).
    pub triangles: usize,
    /// The chosen fraction bits.
    pub frac: u8,
    /// The quantisation step, `2^−frac`.
    pub step: f64,
    /// The subtracted centre (zero without `--center`).
    pub offset: [f64; 3],
    /// The scale applied.
    pub scale: f64,
    /// Bounds `[min, max]` of the positions after the transform.
    pub bounds: [[f64; 3]; 2],
    /// The largest |quantised − exact| position coordinate (≤ step / 2).
    pub max_position_error: f64,
    /// The largest |quantised − exact| texture coordinate (≤ 2^−13), if kept.
    pub max_texcoord_error: Option<f64>,
    /// Where the normals come from.
    pub normals: NormalSource,
    /// Corners whose normal was computed (the others are the file's).
    pub computed_normal_corners: usize,
    /// Closed or not, and the winding.
    pub orientation: Orientation,
    /// The triangles were reversed (`--flip-winding`).
    pub winding_flipped: bool,
    /// The file's normals were negated with them (they pointed inward).
    pub file_normals_negated: bool,
    /// Things to tell the user.
    pub warnings: Vec<String>,
}

/// `2^−frac`.
pub fn step(frac: u8) -> f64 {
    1.0 / f64::from(1u32 << frac.min(31))
}

/// The largest `frac ≤ 15` at which `round(x · 2^frac)` fits an `i16` for
/// every `x` in `[min, max]`; `None` when not even `frac = 0` does
/// (`max ≥ 32767.5` or `min < −32768.5`).
///
/// ```
/// use fixshade_import::process::frac_for_range;
/// assert_eq!(frac_for_range(-1.0, 1.0), Some(14)); // 16384 fits, 32768 does not
/// assert_eq!(frac_for_range(-1.0, 0.99), Some(15)); // -32768 fits
/// assert_eq!(frac_for_range(0.0, 40000.0), None);
/// ```
pub fn frac_for_range(min: f64, max: f64) -> Option<u8> {
    (0..=15u8).rev().find(|&f| fits(min, max, f))
}

/// Whether `[min, max]` rounds into `i16` at `frac` bits (the test of the
/// library's `to_compact`).
fn fits(min: f64, max: f64, frac: u8) -> bool {
    let s = f64::from(1u32 << frac);
    let ok = |x: f64| (-32768.5..32767.5).contains(&(x * s));
    ok(min) && ok(max)
}

/// What makes a vertex: quantised position, Q14 normal, Q12 texture
/// coordinate (zero without).
type VertexKey = ([i16; 3], [i16; 3], [i16; 2]);

/// A triangle's use of an edge: (triangle, its corner at the edge's lower
/// position id, its corner at the higher).
type EdgeUse = (usize, usize, usize);

fn mesh_error(step: &'static str) -> impl Fn(MeshError) -> Error {
    move |source| Error::Mesh { step, source }
}

/// Processes `src` (read from `path`, named in errors) into compact meshes,
/// one per material (or more with [`ProcessOptions::split`]), sharing one
/// `frac` (see the module documentation).
///
/// # Errors
///
/// [`Error::NotFinite`], [`Error::PositionRange`], [`Error::FracTooLarge`],
/// [`Error::TexcoordRange`], [`Error::TooManyVertices`] and
/// [`Error::TooManyTriangles`] (without `split`), [`Error::NoTexcoords`]
/// (tangents without texture coordinates), [`Error::Mesh`] (tangents on
/// degenerate texture coordinates), and [`Error::Empty`] when no triangle is
/// left.
pub fn process(
    src: &SourceMesh,
    options: &ProcessOptions,
    path: &Path,
) -> Result<(Vec<ProcessedPart>, MeshReport), Error> {
    let empty = || Error::Empty {
        path: path.to_path_buf(),
    };
    let corners: Vec<_> = src.triangles.iter().flat_map(|t| t.corners).collect();
    let mut warnings = Vec::new();
    for c in &corners {
        if !c.position.iter().all(|x| x.is_finite()) {
            return Err(Error::NotFinite { what: "position" });
        }
        if c.normal.is_some_and(|n| !n.iter().all(|x| x.is_finite())) {
            return Err(Error::NotFinite { what: "normal" });
        }
        if c.texcoord.is_some_and(|t| !t.iter().all(|x| x.is_finite())) {
            return Err(Error::NotFinite {
                what: "texture coordinate",
            });
        }
    }
    if !(options.scale.is_finite() && options.scale != 0.0) {
        return Err(Error::NotFinite { what: "scale" });
    }
    if corners.is_empty() {
        return Err(empty());
    }

    // 1. transform
    let raw_bounds = bounds(corners.iter().map(|c| c.position));
    let offset = if options.center {
        core::array::from_fn(|k| 0.5 * (raw_bounds[0][k] + raw_bounds[1][k]))
    } else {
        [0.0; 3]
    };
    let placed: Vec<[f64; 3]> = corners
        .iter()
        .map(|c| core::array::from_fn(|k| (c.position[k] - offset[k]) * options.scale))
        .collect();
    let b = bounds(placed.iter().copied());

    // 2. frac, and the positions rounded by the library
    let (lo, hi) = (
        b[0].iter().copied().fold(f64::INFINITY, f64::min),
        b[1].iter().copied().fold(f64::NEG_INFINITY, f64::max),
    );
    let best = frac_for_range(lo, hi).ok_or(Error::PositionRange {
        max_abs: lo.abs().max(hi.abs()),
    })?;
    let frac = match options.frac {
        Some(f) if f > best => {
            return Err(Error::FracTooLarge {
                frac: f,
                max_fitting: best,
            })
        }
        Some(f) => f,
        None => best,
    };
    let placed32: Vec<[f32; 3]> = placed.iter().map(|p| p.map(|x| x as f32)).collect();
    let mut qpos = vec![[0i16; 3]; placed.len()];
    let mut unused = vec![[0i16; 3]; placed.len()];
    let zero = vec![[0.0f32; 3]; placed.len()];
    to_compact(&placed32, &zero, frac, &mut qpos, &mut unused)
        .map_err(mesh_error("quantising positions"))?;
    let dequant = |q: [i16; 3]| q.map(|x| f64::from(x) * step(frac));
    let max_position_error = placed
        .iter()
        .zip(&qpos)
        .flat_map(|(p, q)| {
            let d = dequant(*q);
            (0..3).map(move |k| (d[k] - p[k]).abs())
        })
        .fold(0.0, f64::max);

    // 3. position ids; degenerate triangles dropped
    let mut position_id: HashMap<[i16; 3], u32> = HashMap::new();
    let pid: Vec<u32> = qpos
        .iter()
        .map(|q| {
            let n = position_id.len() as u32;
            *position_id.entry(*q).or_insert(n)
        })
        .collect();
    let kept: Vec<usize> = (0..src.triangles.len())
        .filter(|&t| {
            let p = &pid[3 * t..3 * t + 3];
            p[0] != p[1] && p[1] != p[2] && p[2] != p[0]
        })
        .collect();
    let degenerate_dropped = src.triangles.len() - kept.len();
    if kept.is_empty() {
        return Err(empty());
    }
    // too many triangles for one mesh: known before the normals
    if !options.split {
        let mut per_material: HashMap<Option<usize>, (usize, HashSet<u32>)> = HashMap::new();
        for &t in &kept {
            let e = per_material.entry(src.triangles[t].material).or_default();
            e.0 += 1;
            e.1.extend(&pid[3 * t..3 * t + 3]);
        }
        // the first material (in order of use) over the limit
        if let Some(&t) = kept.iter().find(|&&t| {
            per_material
                .get(&src.triangles[t].material)
                .is_some_and(|e| e.0 > MAX_TRIANGLES)
        }) {
            let m = src.triangles[t].material;
            let (count, positions) = per_material.get(&m).map_or((0, 0), |e| (e.0, e.1.len()));
            return Err(Error::TooManyTriangles {
                path: path.to_path_buf(),
                material: (per_material.len() > 1).then(|| material_label(src, m)),
                count,
                positions,
            });
        }
    }
    // corner `3k + j` of the kept triangles is source corner `3 kept[k] + j`,
    // or `3 kept[k] + (0, 2, 1)[j]` with the winding flipped
    let order: [usize; 3] = if options.flip_winding {
        [0, 2, 1]
    } else {
        [0, 1, 2]
    };
    let src_corner = |c: usize| 3 * kept[c / 3] + order[c % 3];
    let n_corners = 3 * kept.len();
    let corner_pid = |c: usize| pid[src_corner(c)];
    let corner_pos = |c: usize| dequant(qpos[src_corner(c)]);
    let face_normal: Vec<Option<[f64; 3]>> = (0..kept.len())
        .map(|k| {
            let [a, b, c] = [0, 1, 2].map(|j| corner_pos(3 * k + j));
            unit(cross(sub(b, a), sub(c, a)))
        })
        .collect();

    // 4. orientation of a closed mesh
    let orientation = orientation(kept.len(), &corner_pid, &corner_pos);
    match orientation {
        Orientation::Closed { volume } if volume < 0.0 => warnings.push(if options.flip_winding {
            format!(
                "wound clockwise from outside after --flip-winding (signed volume {volume:.4}): \
                 the file was counter-clockwise; drop --flip-winding"
            )
        } else {
            format!(
                "wound clockwise from outside (signed volume {volume:.4}): renders inside-out; \
                 pass --flip-winding"
            )
        }),
        Orientation::Inconsistent { edges } => warnings.push(format!(
            "closed, but {edges} edges run the same way in both of their triangles: some faces \
             are wound against their neighbours and render inside-out (--flip-winding flips \
             every face, not those)"
        )),
        _ => {}
    }

    // 5. normals: the file's (turned outward with the winding when they
    // pointed inward with it), or computed
    let raw_file_normal = |c: usize| -> Option<[f64; 3]> {
        if options.recompute_normals {
            return None;
        }
        corners[src_corner(c)].normal.and_then(unit)
    };
    let file_normals_negated = options.flip_winding && {
        // the file's normals against the (flipped) faces, corner by corner
        let (mut inward, mut outward) = (0usize, 0usize);
        for c in 0..n_corners {
            if let (Some(n), Some(f)) = (raw_file_normal(c), face_normal[c / 3]) {
                let d = dot(n, f);
                if d < 0.0 {
                    inward += 1;
                } else if d > 0.0 {
                    outward += 1;
                }
            }
        }
        inward > outward
    };
    let file_normal = |c: usize| {
        raw_file_normal(c).map(|n| {
            if file_normals_negated {
                n.map(|x| -x)
            } else {
                n
            }
        })
    };
    let all_file = (0..n_corners).all(|c| file_normal(c).is_some());
    let has_groups = kept
        .iter()
        .any(|&t| src.triangles[t].smoothing != Smoothing::Unspecified);
    let policy = match (all_file, options.crease_angle, has_groups) {
        (true, _, _) => NormalSource::File,
        (false, Some(a), _) => NormalSource::CreaseAngle(a),
        (false, None, true) => NormalSource::SmoothingGroups,
        (false, None, false) => NormalSource::CreaseAngle(DEFAULT_CREASE_ANGLE),
    };
    let (normals, smoothing_vertices, computed) = if policy == NormalSource::File {
        let n: Vec<[f64; 3]> = (0..n_corners)
            .map(|c| file_normal(c).unwrap_or([0.0, 0.0, 1.0]))
            .collect();
        (n, 0, 0)
    } else {
        let groups = match policy {
            NormalSource::CreaseAngle(angle) => {
                crease_groups(kept.len(), &corner_pid, &face_normal, angle)
            }
            _ => smoothing_groups(kept.len(), &corner_pid, |k| {
                src.triangles[kept[k]].smoothing
            }),
        };
        let count = groups.iter().copied().max().map_or(0, |m| m as usize + 1);
        let mut spos = vec![[0.0f32; 3]; count];
        for (c, &g) in groups.iter().enumerate() {
            spos[g as usize] = corner_pos(c).map(|x| x as f32);
        }
        let stris: Vec<[u32; 3]> = groups.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        let snrm = smooth_normals(&spos, &stris, options.weighting, NORMAL_CHUNK)?;
        let mut zero_normals = 0;
        let mut computed = 0;
        let n: Vec<[f64; 3]> = (0..n_corners)
            .map(|c| {
                file_normal(c).unwrap_or_else(|| {
                    computed += 1;
                    let v = snrm[groups[c] as usize].map(f64::from);
                    unit(v).or(face_normal[c / 3]).unwrap_or_else(|| {
                        zero_normals += 1;
                        [0.0; 3]
                    })
                })
            })
            .collect();
        if zero_normals > 0 {
            warnings.push(format!(
                "{zero_normals} corners got no normal (their faces have no area): left zero"
            ));
        }
        (n, count, computed)
    };

    // normals to Q14 by the library (positions again, unchanged)
    let corner_pos32: Vec<[f32; 3]> = (0..n_corners)
        .map(|c| corner_pos(c).map(|x| x as f32))
        .collect();
    let normals32: Vec<[f32; 3]> = normals.iter().map(|n| n.map(|x| x as f32)).collect();
    let mut cpos = vec![[0i16; 3]; n_corners];
    let mut cnrm = vec![[0i16; 3]; n_corners];
    to_compact(&corner_pos32, &normals32, frac, &mut cpos, &mut cnrm)
        .map_err(mesh_error("quantising normals"))?;

    // texture coordinates, Q12
    let with_uv = (0..n_corners)
        .filter(|&c| corners[src_corner(c)].texcoord.is_some())
        .count();
    let keep_uv = options.texcoords && with_uv > 0;
    if options.tangents && !keep_uv {
        return Err(Error::NoTexcoords);
    }
    if keep_uv && with_uv < n_corners {
        warnings.push(format!(
            "{} of {n_corners} corners have no texture coordinates: (0, 0) used",
            n_corners - with_uv
        ));
    }
    let q12 = f64::from(1u32 << TEXCOORD_FRAC);
    let mut max_uv_error = 0.0f64;
    let mut cuv = vec![[0i16; 2]; n_corners];
    if keep_uv {
        for (c, out) in cuv.iter_mut().enumerate() {
            let t = corners[src_corner(c)].texcoord.unwrap_or([0.0; 2]);
            for k in 0..2 {
                let r = (t[k] * q12).round();
                if !(f64::from(i16::MIN)..=f64::from(i16::MAX)).contains(&r) {
                    return Err(Error::TexcoordRange { value: t[k] });
                }
                out[k] = r as i16;
                max_uv_error = max_uv_error.max((r / q12 - t[k]).abs());
            }
        }
    }

    // 6. parts: the triangles of each material (in order of first use),
    // each welded on its own; cut where a part would go over the limits
    let mut groups: Vec<(Option<usize>, Vec<usize>)> = Vec::new();
    for (k, &t) in kept.iter().enumerate() {
        let m = src.triangles[t].material;
        match groups.iter_mut().find(|g| g.0 == m) {
            Some(g) => g.1.push(k),
            None => groups.push((m, vec![k])),
        }
    }
    let several = groups.len() > 1;
    let key = |c: usize| -> VertexKey { (cpos[c], cnrm[c], cuv[c]) };
    let mut parts = Vec::new();
    for (material, tris) in &groups {
        let mut rest = &tris[..];
        while !rest.is_empty() {
            let (mut mesh, used) = weld(rest, &key, options.split);
            rest = &rest[used..];
            let (v, t) = (mesh.positions.len(), mesh.triangles.len());
            if v > MAX_VERTICES {
                return Err(Error::TooManyVertices {
                    path: path.to_path_buf(),
                    material: several.then(|| material_label(src, *material)),
                    count: v,
                    triangles: t,
                });
            }
            mesh.frac = frac;
            if !keep_uv {
                mesh.texcoords = None;
            }
            // 7. tangents
            if options.tangents {
                mesh.tangents = Some(tangents(&mesh, &dequant)?);
            }
            parts.push(ProcessedPart {
                material: *material,
                mesh,
            });
        }
    }

    let report = MeshReport {
        source_triangles: src.triangles.len(),
        degenerate_dropped,
        positions: position_id.len(),
        smoothing_vertices,
        vertices: parts.iter().map(|p| p.mesh.positions.len()).sum(),
        triangles: parts.iter().map(|p| p.mesh.triangles.len()).sum(),
        frac,
        step: step(frac),
        offset,
        scale: options.scale,
        bounds: b,
        max_position_error,
        max_texcoord_error: keep_uv.then_some(max_uv_error),
        normals: policy,
        computed_normal_corners: computed,
        orientation,
        winding_flipped: options.flip_winding,
        file_normals_negated,
        warnings,
    };
    Ok((parts, report))
}

/// A material's name for messages.
fn material_label(src: &SourceMesh, m: Option<usize>) -> String {
    match m {
        Some(m) => src
            .materials
            .get(m)
            .map_or_else(|| format!("material {m}"), |m| m.name.clone()),
        None => "(none)".to_string(),
    }
}

/// Welds the corners of the triangles `tris` (kept-triangle numbers; corner
/// `3k + j`) by `key`, first use first. With `split`, stops before the
/// triangle that would take the mesh over [`MAX_VERTICES`] or
/// [`MAX_TRIANGLES`]; returns the mesh (`frac` 0, texture coordinates always
/// set) and the triangles used.
fn weld(tris: &[usize], key: &impl Fn(usize) -> VertexKey, split: bool) -> (CompactMesh, usize) {
    let mut vertex_id: HashMap<VertexKey, u32> = HashMap::new();
    let mut mesh = CompactMesh::default();
    let mut uvs = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    for (used, &k) in tris.iter().enumerate() {
        let keys = [0, 1, 2].map(|j| key(3 * k + j));
        if split {
            let mut new = 0;
            for (j, kj) in keys.iter().enumerate() {
                if !vertex_id.contains_key(kj) && !keys[..j].contains(kj) {
                    new += 1;
                }
            }
            if triangles.len() + 1 > MAX_TRIANGLES || vertex_id.len() + new > MAX_VERTICES {
                return (finish(mesh, uvs, &triangles), used);
            }
        }
        let t = keys.map(|kj| {
            let next = vertex_id.len() as u32;
            *vertex_id.entry(kj).or_insert_with(|| {
                mesh.positions.push(kj.0);
                mesh.normals.push(kj.1);
                uvs.push(kj.2);
                next
            })
        });
        triangles.push(t);
    }
    (finish(mesh, uvs, &triangles), tris.len())
}

/// The mesh with its texture coordinates and its triangles (as `u16`: the
/// caller checks the count first).
fn finish(mut mesh: CompactMesh, uvs: Vec<[i16; 2]>, triangles: &[[u32; 3]]) -> CompactMesh {
    mesh.texcoords = Some(uvs);
    mesh.triangles = triangles
        .iter()
        .map(|t| t.map(|i| u16::try_from(i).unwrap_or(u16::MAX)))
        .collect();
    mesh
}

/// The library's [`vertex_tangents`] (Q14) of a welded part.
fn tangents(
    mesh: &CompactMesh,
    dequant: &impl Fn([i16; 3]) -> [f64; 3],
) -> Result<Vec<[i16; 4]>, Error> {
    let q12 = f64::from(1u32 << TEXCOORD_FRAC);
    let uv = mesh.texcoords.as_deref().unwrap_or(&[]);
    let p: Vec<[f32; 3]> = mesh
        .positions
        .iter()
        .map(|q| dequant(*q).map(|x| x as f32))
        .collect();
    let inv_one = 1.0 / f32::from(NORMAL_ONE);
    let n: Vec<[f32; 3]> = mesh
        .normals
        .iter()
        .map(|q| q.map(|x| f32::from(x) * inv_one))
        .collect();
    let t: Vec<[f32; 2]> = uv
        .iter()
        .map(|q| q.map(|x| f32::from(x) / q12 as f32))
        .collect();
    let mut q = vec![[0i16; 4]; p.len()];
    vertex_tangents(&p, &n, &t, &mesh.triangles, &mut q).map_err(mesh_error("tangents"))?;
    Ok(q)
}

/// Vertices the library's [`vertex_normals`] takes at once (`u16` indices).
const NORMAL_CHUNK: usize = 65_536;

/// The library's [`vertex_normals`] over any number of vertices: at most
/// `chunk` at once. Beyond, the vertices are taken in ranges, each with every
/// triangle touching it (in the original order) and those triangles'
/// vertices: a vertex's normal depends only on its own triangles, so
/// angle-weighted normals are the same as in one call (area weighting scales
/// each range by its largest face: the same up to rounding).
fn smooth_normals(
    positions: &[[f32; 3]],
    tris: &[[u32; 3]],
    weighting: Weighting,
    chunk: usize,
) -> Result<Vec<[f32; 3]>, Error> {
    let n = positions.len();
    let mut out = vec![[0.0f32; 3]; n];
    let short = |t: &[u32; 3]| t.map(|i| u16::try_from(i).unwrap_or(u16::MAX));
    if n <= chunk {
        let t16: Vec<[u16; 3]> = tris.iter().map(short).collect();
        vertex_normals(positions, &t16, weighting, &mut out)
            .map_err(mesh_error("vertex normals"))?;
        return Ok(out);
    }
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (t, tri) in tris.iter().enumerate() {
        for &v in tri {
            let list = &mut incident[v as usize];
            if list.last() != Some(&(t as u32)) {
                list.push(t as u32);
            }
        }
    }
    let mut ranges: Vec<(usize, usize)> = (0..n)
        .step_by(chunk / 4)
        .map(|a| (a, (a + chunk / 4).min(n)))
        .rev()
        .collect();
    while let Some((a, b)) = ranges.pop() {
        let mut ts: Vec<u32> = incident[a..b].iter().flatten().copied().collect();
        ts.sort_unstable();
        ts.dedup();
        let mut local: HashMap<u32, u32> = HashMap::new();
        let mut lpos = Vec::new();
        let ltris: Vec<[u32; 3]> = ts
            .iter()
            .map(|&t| {
                tris[t as usize].map(|v| {
                    let next = local.len() as u32;
                    *local.entry(v).or_insert_with(|| {
                        lpos.push(positions[v as usize]);
                        next
                    })
                })
            })
            .collect();
        if lpos.len() > chunk {
            if b - a == 1 {
                return Err(Error::Mesh {
                    step: "vertex normals",
                    source: MeshError::TooManyVertices { needed: lpos.len() },
                });
            }
            let mid = a + (b - a) / 2;
            ranges.push((mid, b));
            ranges.push((a, mid));
            continue;
        }
        let t16: Vec<[u16; 3]> = ltris.iter().map(short).collect();
        let mut lout = vec![[0.0f32; 3]; lpos.len()];
        vertex_normals(&lpos, &t16, weighting, &mut lout).map_err(mesh_error("vertex normals"))?;
        for (v, o) in out.iter_mut().enumerate().take(b).skip(a) {
            if let Some(&l) = local.get(&(v as u32)) {
                *o = lout[l as usize];
            }
        }
    }
    Ok(out)
}

/// Whether the mesh is closed (every edge, between quantised positions,
/// shared by exactly two triangles), consistently wound, and its signed
/// volume `Σ a · (b × c) / 6`.
fn orientation(
    triangles: usize,
    position: &impl Fn(usize) -> u32,
    point: &impl Fn(usize) -> [f64; 3],
) -> Orientation {
    // edge (low, high position) → (uses, uses low → high minus high → low)
    let mut edges: HashMap<(u32, u32), (u32, i32)> = HashMap::new();
    for t in 0..triangles {
        for j in 0..3 {
            let (a, b) = (position(3 * t + j), position(3 * t + (j + 1) % 3));
            let (k, dir) = if a < b { ((a, b), 1) } else { ((b, a), -1) };
            let e = edges.entry(k).or_insert((0, 0));
            e.0 += 1;
            e.1 += dir;
        }
    }
    let open = edges.values().filter(|e| e.0 != 2).count();
    if open > 0 {
        return Orientation::Open { edges: open };
    }
    let inconsistent = edges.values().filter(|e| e.1 != 0).count();
    if inconsistent > 0 {
        return Orientation::Inconsistent {
            edges: inconsistent,
        };
    }
    let volume = (0..triangles)
        .map(|t| {
            let [a, b, c] = [0, 1, 2].map(|j| point(3 * t + j));
            dot(a, cross(b, c))
        })
        .sum::<f64>()
        / 6.0;
    Orientation::Closed { volume }
}

/// Smoothing vertex of every corner by OBJ smoothing group: corners at one
/// position share one when their faces are in the same group `N ≠ 0`; a
/// face with smoothing off gets its own.
fn smoothing_groups(
    triangles: usize,
    position: &impl Fn(usize) -> u32,
    group: impl Fn(usize) -> Smoothing,
) -> Vec<u32> {
    let mut ids: HashMap<(u32, u32), u32> = HashMap::new();
    let mut next = 0u32;
    let mut out = Vec::with_capacity(3 * triangles);
    for c in 0..3 * triangles {
        let id = match group(c / 3) {
            Smoothing::Group(g) if g != 0 => *ids.entry((position(c), g)).or_insert_with(|| {
                next += 1;
                next - 1
            }),
            _ => {
                next += 1;
                next - 1
            }
        };
        out.push(id);
    }
    out
}

/// Smoothing vertex of every corner by crease angle: the corners at the two
/// ends of an edge shared by two triangles are joined when the triangles'
/// face normals differ by at most `angle` degrees (or one of them has no
/// area); joined corners (transitively) share a vertex. Numbered in order of
/// first corner.
fn crease_groups(
    triangles: usize,
    position: &impl Fn(usize) -> u32,
    face_normal: &[Option<[f64; 3]>],
    angle: f64,
) -> Vec<u32> {
    let cos = angle.to_radians().cos() - 1e-9;
    let mut parent: Vec<u32> = (0..3 * triangles as u32).collect();
    // edge (low, high position) → [(triangle, corner at low, corner at high)]
    let mut edges: HashMap<(u32, u32), Vec<EdgeUse>> = HashMap::new();
    for t in 0..triangles {
        for j in 0..3 {
            let (a, b) = (3 * t + j, 3 * t + (j + 1) % 3);
            let (pa, pb) = (position(a), position(b));
            let entry = if pa < pb {
                ((pa, pb), (t, a, b))
            } else {
                ((pb, pa), (t, b, a))
            };
            edges.entry(entry.0).or_default().push(entry.1);
        }
    }
    let smooth = |s: usize, t: usize| match (face_normal[s], face_normal[t]) {
        (Some(m), Some(n)) => dot(m, n) >= cos,
        _ => true,
    };
    for list in edges.values() {
        for (i, &(s, s_lo, s_hi)) in list.iter().enumerate() {
            for &(t, t_lo, t_hi) in &list[i + 1..] {
                if smooth(s, t) {
                    union(&mut parent, s_lo, t_lo);
                    union(&mut parent, s_hi, t_hi);
                }
            }
        }
    }
    let mut ids: HashMap<u32, u32> = HashMap::new();
    (0..3 * triangles)
        .map(|c| {
            let r = find(&mut parent, c);
            let n = ids.len() as u32;
            *ids.entry(r).or_insert(n)
        })
        .collect()
}

fn find(parent: &mut [u32], mut x: usize) -> u32 {
    while parent[x] as usize != x {
        let p = parent[x] as usize;
        parent[x] = parent[p];
        x = p;
    }
    x as u32
}

fn union(parent: &mut [u32], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        // the lower root wins: the result does not depend on the visiting order
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        parent[hi as usize] = lo;
    }
}

fn bounds(points: impl Iterator<Item = [f64; 3]>) -> [[f64; 3]; 2] {
    let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for p in points {
        for k in 0..3 {
            b[0][k] = b[0][k].min(p[k]);
            b[1][k] = b[1][k].max(p[k]);
        }
    }
    b
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `v / |v|`, or `None` for a zero (or non-finite) vector.
fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let l = dot(v, v).sqrt();
    (l > 1e-300 && l.is_finite()).then(|| v.map(|x| x / l))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frac_boundaries() {
        assert_eq!(frac_for_range(0.0, 0.0), Some(15));
        assert_eq!(frac_for_range(-1.0, 0.999), Some(15));
        assert_eq!(frac_for_range(-1.0, 1.0), Some(14));
        assert_eq!(frac_for_range(-1.00002, 0.0), Some(14));
        assert_eq!(frac_for_range(0.0, 32767.4), Some(0));
        assert_eq!(frac_for_range(0.0, 32767.5), None);
        assert_eq!(frac_for_range(-32768.4, 0.0), Some(0));
    }

    #[test]
    fn normals_in_chunks_equal_one_call() {
        // a waving 12 × 12 grid, vertices numbered in an order that scatters
        // neighbours across the chunks
        let n = 12usize;
        let id = |i: usize, j: usize| ((j * n + i) * 37 % (n * n)) as u32;
        let mut positions = vec![[0.0f32; 3]; n * n];
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (i as f32 / 3.0, j as f32 / 3.0);
                positions[id(i, j) as usize] = [x, y, (x * 1.3).sin() * (y * 0.7).cos()];
            }
        }
        let mut tris = Vec::new();
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let whole = smooth_normals(&positions, &tris, Weighting::Angle, NORMAL_CHUNK).unwrap();
        for chunk in [64, 40, 24] {
            let parts = smooth_normals(&positions, &tris, Weighting::Angle, chunk).unwrap();
            assert_eq!(parts, whole, "chunk {chunk}");
        }
        // area weighting scales each chunk by its largest face: the same up to rounding
        let whole = smooth_normals(&positions, &tris, Weighting::Area, NORMAL_CHUNK).unwrap();
        let parts = smooth_normals(&positions, &tris, Weighting::Area, 24).unwrap();
        for (a, b) in whole.iter().zip(&parts) {
            for k in 0..3 {
                assert!((a[k] - b[k]).abs() < 1e-6, "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn union_find_joins_transitively() {
        let mut p: Vec<u32> = (0..6).collect();
        union(&mut p, 4, 5);
        union(&mut p, 1, 5);
        union(&mut p, 2, 3);
        let roots: Vec<u32> = (0..6).map(|i| find(&mut p, i)).collect();
        assert_eq!(roots, [0, 1, 2, 2, 1, 1]);
    }
}
