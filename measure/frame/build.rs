//! Firmware targets (`target_os = "none"`): puts this crate's memory.x on the
//! linker path and links with cortex-m-rt's link.x (Arm) or riscv-rt's link.x
//! with `memory-riscv.x` (RISC-V: the same map plus riscv-rt's region
//! aliases). Host builds: nothing.
use std::{env, fs, path::PathBuf};

fn main() {
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=memory-riscv.x");
    println!("cargo:rerun-if-changed=build.rs");
    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("none") {
        return;
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap());
    let riscv = env::var("CARGO_CFG_TARGET_ARCH").as_deref() == Ok("riscv32");
    let memory = if riscv { "memory-riscv.x" } else { "memory.x" };
    fs::copy(memory, out.join(memory)).unwrap();
    println!("cargo:rustc-link-search={}", out.display());
    if riscv {
        // riscv-rt's link.x does not include a memory map itself (named apart:
        // the linker looks in the package directory first, where memory.x is Arm's)
        println!("cargo:rustc-link-arg-bins=-Tmemory-riscv.x");
    }
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    // keep the relocations: frame.py reads which words are code pointers
    println!("cargo:rustc-link-arg-bins=--emit-relocs");
}
