//! The mesh renderer with any small mesh (issue 21, item 7): vertices, normals
//! and triangles from the bytes (indices valid by construction, positions and
//! normals any `i16`, any fraction bits), an orthographic or perspective camera
//! in any pose, any frame size, band height, culling, with or without a depth
//! buffer, through several shading modes (flat, Gouraud, Phong, incremental
//! and quadratic Phong; Q14, Q30 and f32). No panic, no wrap (overflow checks
//! on), and the frame drawn in bands is the whole frame bit for bit.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| fixshade_fuzz::mesh::run(data));
