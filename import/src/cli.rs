//! The command-line tool: argument parsing (std only) and the run.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::{import, Error, Options, TextureChoice, TextureFormat, Weighting, Wrap};

/// The `--help` text.
pub const USAGE: &str = "\
fixshade-import: a model file to fixshade's compact static mesh (and texture) as Rust source

Usage: fixshade-import MODEL [options]

MODEL is a Wavefront .obj (its .mtl and map_Kd textures are read too), a .gltf
or a .glb. The source goes to --out (default: standard output); what was done
(counts, the chosen frac and quantisation step, materials, texture error,
warnings) to standard error. Each material becomes a part (its own mesh,
MaterialDesc and texture); NAME_PARTS lists them.

Options:
  -o, --out FILE             write the Rust source to FILE
  -n, --name NAME            prefix of the generated items, [A-Z_][A-Z0-9_]*
                             (default: the file name in upper case)
      --center               move the centre of the bounding box to the origin
      --scale S              multiply the positions by S (after --center)
      --frac N               fraction bits of the positions (default: the most
                             that fit every coordinate in an i16, at most 15)
      --crease-angle DEG     compute missing normals split at creases sharper
                             than DEG (default: the OBJ's smoothing groups if it
                             has any, else 60)
      --recompute-normals    ignore the file's normals
      --weighting angle|area face weights of the normal average (default: angle)
      --tangents             emit tangents (for normal maps; needs texture coordinates)
      --flip-winding         reverse every triangle (a model wound clockwise from
                             outside; the file's normals are negated too if they
                             point inward)
      --split                cut a part over 65535 vertices or triangles into
                             parts that fit (default: an error)
      --no-texcoords         drop texture coordinates
      --texture FILE         convert this PNG instead of the material's texture
      --no-texture           emit no texture
      --texture-format F     rgb565 (default), gray8 or palette8
      --clamp                the texture clamps at its edges (default: repeats)
      --resize               resample a texture whose sides are not powers of
                             two to the nearest ones (default: an error)
      --strict               a missing MTL or texture, or a material value outside
                             OpenGL's ranges, is an error (default: a warning, and
                             OpenGL's default material / no texture / the value
                             clamped)
  -q, --quiet                print nothing but errors
  -h, --help                 this text
  -V, --version              the version
";

/// What the command line asks for.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Print [`USAGE`].
    Help,
    /// Print the version.
    Version,
    /// Import a model.
    Import {
        /// The model file.
        input: PathBuf,
        /// Where the source goes (`None`: standard output).
        out: Option<PathBuf>,
        /// The options.
        options: Options,
        /// Print nothing but errors.
        quiet: bool,
    },
}

/// The default item prefix for a model file: its stem in upper case, other
/// characters than letters and digits as `_` (`teapot-2.obj` → `TEAPOT_2`).
pub fn default_name(path: &Path) -> String {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let mut n: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_uppercase()
            } else {
                '_'
            }
        })
        .collect();
    if !n.starts_with(|c: char| c.is_ascii_uppercase() || c == '_') || n == "_" {
        n.insert_str(0, "MODEL_");
    }
    n
}

/// Parses the arguments (without the program name).
///
/// # Errors
///
/// A message for an unknown flag, a missing or bad value, or no model.
pub fn parse(args: &[String]) -> Result<Command, String> {
    let mut it = args.iter();
    let mut input = None;
    let mut out = None;
    let mut name = None;
    let mut quiet = false;
    let mut o = Options::new("MODEL");
    while let Some(a) = it.next() {
        let mut value = |flag: &str| {
            it.next()
                .cloned()
                .ok_or_else(|| format!("{flag} needs a value"))
        };
        fn number<T: std::str::FromStr>(flag: &str, v: String) -> Result<T, String> {
            v.parse()
                .map_err(|_| format!("{flag}: not a number: {v:?}"))
        }
        match a.as_str() {
            "-h" | "--help" => return Ok(Command::Help),
            "-V" | "--version" => return Ok(Command::Version),
            "-o" | "--out" => out = Some(PathBuf::from(value(a)?)),
            "-n" | "--name" => name = Some(value(a)?),
            "-q" | "--quiet" => quiet = true,
            "--center" => o.process.center = true,
            "--scale" => o.process.scale = number(a, value(a)?)?,
            "--frac" => {
                let f: u8 = number(a, value(a)?)?;
                if f > 15 {
                    return Err("--frac: at most 15".into());
                }
                o.process.frac = Some(f);
            }
            "--crease-angle" => {
                let d: f64 = number(a, value(a)?)?;
                if !(0.0..=180.0).contains(&d) {
                    return Err("--crease-angle: degrees from 0 to 180".into());
                }
                o.process.crease_angle = Some(d);
            }
            "--recompute-normals" => o.process.recompute_normals = true,
            "--weighting" => {
                o.process.weighting = match value(a)?.as_str() {
                    "angle" => Weighting::Angle,
                    "area" => Weighting::Area,
                    v => return Err(format!("--weighting: angle or area, not {v:?}")),
                }
            }
            "--tangents" => o.process.tangents = true,
            "--flip-winding" => o.process.flip_winding = true,
            "--split" => o.process.split = true,
            "--strict" => o.strict = true,
            "--no-texcoords" => o.process.texcoords = false,
            "--texture" => o.texture = TextureChoice::File(PathBuf::from(value(a)?)),
            "--no-texture" => o.texture = TextureChoice::None,
            "--texture-format" => {
                o.texture_format = match value(a)?.as_str() {
                    "rgb565" => TextureFormat::Rgb565,
                    "gray8" => TextureFormat::Gray8,
                    "palette8" => TextureFormat::Palette8,
                    v => {
                        return Err(format!(
                            "--texture-format: rgb565, gray8 or palette8, not {v:?}"
                        ))
                    }
                }
            }
            "--clamp" => o.wrap = Wrap::Clamp,
            "--resize" => o.resize = true,
            flag if flag.starts_with('-') && flag.len() > 1 => {
                return Err(format!("unknown option {flag} (see --help)"))
            }
            file => {
                if input.replace(PathBuf::from(file)).is_some() {
                    return Err("one model file at a time".into());
                }
            }
        }
    }
    let input = input.ok_or("no model file given (see --help)")?;
    o.name = name.unwrap_or_else(|| default_name(&input));
    Ok(Command::Import {
        input,
        out,
        options: o,
        quiet,
    })
}

/// Runs a parsed command, the source to `stdout` (without `--out`), the
/// summary to `stderr`.
///
/// # Errors
///
/// The import's [`Error`]; writing to `stdout` failing is an [`Error::Io`].
pub fn run(command: &Command, stdout: &mut dyn Write, stderr: &mut dyn Write) -> Result<(), Error> {
    let io = |e: std::io::Error| Error::Io {
        kind: crate::FileKind::Output,
        path: PathBuf::from("<stdout>"),
        source: e,
    };
    match command {
        Command::Help => stdout.write_all(USAGE.as_bytes()).map_err(io),
        Command::Version => {
            writeln!(stdout, "fixshade-import {}", env!("CARGO_PKG_VERSION")).map_err(io)
        }
        Command::Import {
            input,
            out,
            options,
            quiet,
        } => {
            let model = import(input, options)?;
            match out {
                Some(path) => model.write_rust(path)?,
                None => stdout.write_all(model.to_rust().as_bytes()).map_err(io)?,
            }
            if !quiet {
                let _ = writeln!(stderr, "{}", model.summary());
                if let Some(path) = out {
                    let _ = writeln!(stderr, "wrote {}", path.display());
                }
            }
            Ok(())
        }
    }
}

/// The tool: parses `args`, runs, prints errors; returns the exit code (0,
/// 1 for a failed import, 2 for a bad command line).
pub fn main(args: &[String]) -> i32 {
    let (mut stdout, mut stderr) = (std::io::stdout().lock(), std::io::stderr().lock());
    match parse(args) {
        Err(e) => {
            let _ = writeln!(stderr, "fixshade-import: {e}");
            2
        }
        Ok(cmd) => match run(&cmd, &mut stdout, &mut stderr) {
            Ok(()) => 0,
            Err(e) => {
                let _ = writeln!(stderr, "fixshade-import: error: {e}");
                1
            }
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn parses_the_documented_flags() {
        let c = parse(&args(
            "model.obj --out mesh.rs --name TEAPOT --tangents --texture-format palette8 --crease-angle 30 --center --scale 0.5",
        ))
        .unwrap();
        let Command::Import {
            input,
            out,
            options,
            quiet,
        } = c
        else {
            panic!()
        };
        assert_eq!(input, PathBuf::from("model.obj"));
        assert_eq!(out, Some(PathBuf::from("mesh.rs")));
        assert!(!quiet);
        assert_eq!(options.name, "TEAPOT");
        assert!(options.process.tangents && options.process.center);
        assert_eq!(options.process.scale, 0.5);
        assert_eq!(options.process.crease_angle, Some(30.0));
        assert_eq!(options.texture_format, TextureFormat::Palette8);
        assert!(!options.strict && !options.process.flip_winding && !options.process.split);
        let Ok(Command::Import { options, .. }) =
            parse(&args("m.obj --strict --flip-winding --split"))
        else {
            panic!()
        };
        assert!(options.strict && options.process.flip_winding && options.process.split);
    }

    #[test]
    fn rejects_bad_command_lines() {
        assert!(parse(&args("")).is_err());
        assert!(parse(&args("a.obj b.obj")).is_err());
        assert!(parse(&args("a.obj --frac 16")).is_err());
        assert!(parse(&args("a.obj --bogus")).is_err());
        assert!(parse(&args("a.obj --scale")).is_err());
        assert!(parse(&args("a.obj --texture-format rgb888")).is_err());
        assert_eq!(parse(&args("--help")), Ok(Command::Help));
    }

    #[test]
    fn default_names() {
        assert_eq!(default_name(Path::new("dir/teapot-2.obj")), "TEAPOT_2");
        assert_eq!(default_name(Path::new("3d.glb")), "MODEL_3D");
    }
}
