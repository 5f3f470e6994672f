//! The `fixshade-import` command: see `fixshade-import --help`.

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    std::process::exit(fixshade_import::cli::main(&args));
}
