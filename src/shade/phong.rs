//! [`PhongShading`]: every pixel lit with the full lighting model, over the
//! per-pixel core (`perpixel.rs`).

use super::perpixel::{self, per_pixel_kernel, Features, PixelTriangle, Sources};
use super::{Encoder, Kernel, Mode, PhongShading, Shader, VertexIn};
use crate::color::OutputColor;
use crate::lighting::Illuminate;

impl<I, C> Mode<I, C> for PhongShading {
    const NAME: &'static str = "phong";
    type State = ();
    fn state(self, _: &I) {}
}

per_pixel_kernel!([] PhongShading, Features::PLAIN, [i16; 3], [i32; 6], |_s| Sources::NONE);
