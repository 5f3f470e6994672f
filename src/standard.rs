//! The standard scene of the frame measurements: one lit sphere filling 85 %
//! of a 240 × 240 frame (issue 8 of the project; `measure/frame.py`, the
//! firmware examples and the tests render exactly this).
//!
//! 240 × 240 `Rgb565`, black background; UV sphere of radius 1 with 24 slices
//! × 16 stacks (362 vertices, 720 triangles) at the origin; view = translation
//! by (0, 0, −5); orthographic projection ±1/0.85 on x and y, near 1, far 10;
//! one white directional light towards (1, 1, 1) with ambient, diffuse and
//! specular intensity 1; no global ambient light; viewer at infinity; material ambient
//! (0.08, 0.01, 0.01), diffuse (0.8, 0.1, 0.1), specular white, shininess 32;
//! depth test on; back faces culled.

use crate::camera::Viewport;
use crate::camera::{Camera, FixedCamera, MeshTransform, Orthographic, Pose};
use crate::color::Rgb;
use crate::error::ParamError;
use crate::lighting::{BlinnPhong, InfiniteViewer, Lambert, Lighting, Model, NoFog};
use crate::lighting::{DirectionalLight, LightColors, Viewed};
use crate::lighting::{Material, MaterialDesc};
use crate::mesh::{uv_sphere_counts, MeshData};
use crate::num::Mat4;
use crate::num::Scalar;

/// Frame width and height.
pub const SIZE: u32 = 240;

/// Vertices and triangles of the sphere.
pub const COUNTS: (usize, usize) = uv_sphere_counts(16, 24);

/// The sphere, built at compile time (in flash).
pub static SPHERE: MeshData<{ COUNTS.0 }, { COUNTS.1 }> = MeshData::uv_sphere(16, 24, 14);

/// The camera.
pub fn camera() -> Result<Camera<Orthographic>, ParamError> {
    let s = 1.0 / 0.85;
    Ok(
        Camera::orthographic(-s, s, -s, s, 1.0, 10.0, Viewport::new(0, 0, SIZE, SIZE)?)?
            .with_view(Mat4::translate([0.0, 0.0, -5.0])),
    )
}

/// The sphere's fixed-point transform (model matrix: identity).
pub fn transform() -> Result<MeshTransform<Orthographic>, ParamError> {
    camera()?.mesh_transform(&Mat4::IDENTITY, SPHERE.frac)
}

/// The sphere's transform built in integers from the camera converted once
/// (`FixedCamera::new(&camera()?)`): what a Cortex-M0 does every frame, no
/// soft float.
pub fn fixed_transform(
    c: &FixedCamera<Orthographic>,
) -> Result<MeshTransform<Orthographic>, ParamError> {
    c.mesh_transform(&Pose::IDENTITY, SPHERE.frac)
}

/// The material.
pub fn material() -> MaterialDesc {
    MaterialDesc {
        ambient: [0.08, 0.01, 0.01],
        diffuse: [0.8, 0.1, 0.1],
        specular: [1.0; 3],
        shininess: 32.0,
        ..MaterialDesc::default()
    }
}

/// The light.
pub fn light<S: Scalar>() -> Result<DirectionalLight<S>, ParamError> {
    DirectionalLight::new(
        [1.0, 1.0, 1.0],
        LightColors::new([1.0; 3], [1.0; 3], [1.0; 3])?,
    )
}

/// The lighting with Blinn-Phong specular (no global ambient light: the
/// scene's ambient comes from its light), in eye coordinates
/// ([`Lighting::eye_space`]): the view, a translation, leaves a directional
/// light's direction as it is.
pub fn blinn<S: Scalar>() -> Result<Viewed<Lighting<S, DirectionalLight<S>, BlinnPhong>>, ParamError>
{
    lighting()
}

/// The lighting without specular (ambient + Lambert diffuse; no global
/// ambient light; the light in eye coordinates, as [`blinn`]'s).
pub fn lambert<S: Scalar>() -> Result<Viewed<Lighting<S, DirectionalLight<S>, Lambert>>, ParamError>
{
    lighting()
}

/// The scene's light and material with model `M`, built once.
fn lighting<S: Scalar, M: Model>() -> Result<Viewed<Lighting<S, DirectionalLight<S>, M>>, ParamError>
{
    Ok(Lighting::with_parts(
        light()?,
        Material::new(&material())?,
        Rgb::BLACK,
        InfiniteViewer::default(),
        NoFog,
    )
    .eye_space())
}
