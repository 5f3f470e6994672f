//! The reflection models: which terms a lighting evaluates (a type).

/// Which specular reflection model a [`Model`] evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Specular {
    /// No specular term.
    None,
    /// Phong: `(R·V)^n`, `R = 2(N·L)N − L`.
    Phong,
    /// Blinn-Phong: `(N·H)^n`, `H = (L + V)/|L + V|` (constant for a directional
    /// light and a viewer at infinity).
    BlinnPhong,
}

/// The material terms a lighting configuration evaluates, as compile-time constants.
pub trait Model: Copy + Default + core::fmt::Debug {
    /// The specular model.
    const SPECULAR: Specular;
    /// Diffuse `(N·L)^b` with the material's brilliance `b` instead of `N·L`.
    const BRILLIANCE: bool;
    /// The angle factor `f(β)` (Schlick's Fresnel) on the specular term.
    const FRESNEL: bool;
    /// The transmission term `kst·(T·V)^n''`.
    const TRANSMISSION: bool;
}

/// A model from four constants: `SPEC` is 0 (none), 1 (Phong) or 2 (Blinn-Phong).
#[derive(Clone, Copy, Debug, Default)]
pub struct Terms<
    const SPEC: u8,
    const BRILLIANCE: bool,
    const FRESNEL: bool,
    const TRANSMISSION: bool,
>;

impl<const SPEC: u8, const BRILLIANCE: bool, const FRESNEL: bool, const TRANSMISSION: bool> Model
    for Terms<SPEC, BRILLIANCE, FRESNEL, TRANSMISSION>
{
    const SPECULAR: Specular = match SPEC {
        0 => Specular::None,
        1 => Specular::Phong,
        _ => Specular::BlinnPhong,
    };
    const BRILLIANCE: bool = BRILLIANCE;
    const FRESNEL: bool = FRESNEL;
    const TRANSMISSION: bool = TRANSMISSION;
}

/// Ambient + Lambert diffuse only.
pub type Lambert = Terms<0, false, false, false>;
/// Ambient + diffuse + Phong specular `(R·V)^n`.
pub type Phong = Terms<1, false, false, false>;
/// Ambient + diffuse + Blinn-Phong specular `(N·H)^n` (OpenGL's model).
pub type BlinnPhong = Terms<2, false, false, false>;
/// Every term: brilliance, Blinn-Phong with the Fresnel angle factor, transmission.
pub type Full = Terms<2, true, true, true>;
