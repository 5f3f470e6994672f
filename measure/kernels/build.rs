//! Puts this crate's memory.x on the linker path and links with cortex-m-rt's
//! link.x, so the build works from any directory (no .cargo/config needed).
//! RISC-V: riscv-rt's link.x with `memory-riscv.x` (the same map plus its
//! region aliases), linked with `--emit-relocs` (counts.py reads the calls
//! from the relocations).
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap());
    let riscv = env::var("CARGO_CFG_TARGET_ARCH").as_deref() == Ok("riscv32");
    let memory = if riscv { "memory-riscv.x" } else { "memory.x" };
    fs::copy(memory, out.join(memory)).unwrap();
    println!("cargo:rustc-link-search={}", out.display());
    if riscv {
        // riscv-rt's link.x does not include a memory map itself (named apart:
        // the linker looks in the package directory first, where memory.x is Arm's)
        println!("cargo:rustc-link-arg-bins=-Tmemory-riscv.x");
        println!("cargo:rustc-link-arg-bins=--emit-relocs");
    }
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=memory-riscv.x");
    println!("cargo:rerun-if-changed=build.rs");
}
