//! What the shading stage lights with: the [`Illuminate`] trait, implemented by
//! every [`Lighting`] configuration and by the [`BackFaces`] and
//! [`SeparateSpecular`] wrappers around one.

use super::{FogModel, LightSet, Lighting, LitColor, Model, Specular, Viewer};
use crate::color::Rgb;
use crate::num::{Exponent, Flag, Off, Point3, Scalar, Vec3};

/// What the shading stage lights with: anything that gives the colour of a surface
/// point. Implemented by every [`Lighting`] configuration (and by [`BackFaces`] and
/// [`SeparateSpecular`] around one); the shading modes take one type parameter for
/// it instead of the five of [`Lighting`].
pub trait Illuminate {
    /// The number tier.
    type Scalar: Scalar;
    /// Whether [`Illuminate::shade`] reads the position (see [`Lighting::NEEDS_POSITION`]).
    const NEEDS_POSITION: bool;
    /// [`On`](crate::num::On) for a lighting that the per-pixel fast path
    /// serves: `Q14`, one directional light, a viewer at infinity, no fog
    /// (the model is checked by [`Illuminate::directional`]).
    #[doc(hidden)]
    type Fast: Flag;
    /// What the per-pixel fast path needs, for a lighting whose `Fast` is on
    /// and whose model is Lambert or Blinn-Phong (no brilliance, Fresnel
    /// factor or transmission); `None` otherwise.
    #[doc(hidden)]
    fn directional(&self) -> Option<DirectionalTerms<Self::Scalar>> {
        None
    }
    /// Whether the lights are in eye coordinates, where the renderer hands
    /// points and normals (see [`Lighting::new`]); the default is `true`.
    fn lights_in_eye_space(&self) -> bool {
        true
    }
    /// The colour of surface point `p` with unit normal `n`, linear RGB.
    fn shade(&self, p: &Point3<Self::Scalar>, n: Vec3<Self::Scalar>) -> Rgb<Self::Scalar>;
    /// The colour in OpenGL's primary and secondary parts, with a vertex colour for
    /// `GL_COLOR_MATERIAL` (see [`Lighting::shade_parts`]). The default is
    /// [`Illuminate::shade`] as the primary colour, the vertex colour ignored.
    #[inline(always)]
    fn shade_parts(
        &self,
        p: &Point3<Self::Scalar>,
        n: Vec3<Self::Scalar>,
        color: Option<Rgb<Self::Scalar>>,
    ) -> LitColor<Self::Scalar> {
        let _ = color;
        LitColor {
            primary: self.shade(p, n),
            secondary: Rgb::BLACK,
        }
    }
}

impl<S: Scalar, L: LightSet<S>, M: Model, V: Viewer<S>, F: FogModel<S>> Illuminate
    for Lighting<S, L, M, V, F>
{
    type Scalar = S;
    const NEEDS_POSITION: bool = Self::NEEDS_POSITION;
    fn lights_in_eye_space(&self) -> bool {
        self.is_eye_space()
    }
    type Fast =
        <<<S::Fixed14 as Flag>::And<L::OneDirectional> as Flag>::And<V::AtInfinity> as Flag>::And<
            F::Clear,
        >;
    fn directional(&self) -> Option<DirectionalTerms<S>> {
        let plain = matches!(M::SPECULAR, Specular::None | Specular::BlinnPhong)
            && !M::BRILLIANCE
            && !M::FRESNEL
            && !M::TRANSMISSION;
        if !(Self::Fast::ON && plain) {
            return None;
        }
        let (dir, pre) = self.lights().directional()?;
        Some(DirectionalTerms {
            dir,
            half: pre.half.unwrap_or(dir),
            diffuse: pre.diffuse,
            specular: if M::SPECULAR == Specular::BlinnPhong {
                pre.specular
            } else {
                Rgb::BLACK
            },
            base: self.base(),
            shininess: self.material().shininess,
        })
    }
    #[inline(always)]
    fn shade(&self, p: &Point3<S>, n: Vec3<S>) -> Rgb<S> {
        Lighting::shade(self, p, n)
    }
    #[inline(always)]
    fn shade_parts(&self, p: &Point3<S>, n: Vec3<S>, color: Option<Rgb<S>>) -> LitColor<S> {
        Lighting::shade_parts(self, p, n, color)
    }
}

/// What the per-pixel fast path of the `Q14` tiers needs from a lighting of
/// one directional light (see [`Illuminate::directional`]).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct DirectionalTerms<S> {
    /// Towards the light.
    pub dir: Vec3<S>,
    /// The halfway vector (the light's direction without a specular term).
    pub half: Vec3<S>,
    /// Light diffuse times material diffuse.
    pub diffuse: Rgb<S>,
    /// Light specular times material specular (black for Lambert).
    pub specular: Rgb<S>,
    /// Emission and ambient.
    pub base: Rgb<S>,
    /// The specular exponent.
    pub shininess: Exponent,
}

/// Two-sided lighting (`GL_LIGHT_MODEL_TWO_SIDE`): lights back faces with the
/// normal negated. Wrap a lighting built with the back material (`GL_BACK`) and
/// draw the back faces with it (`Cull::Front`), the front faces with the front
/// lighting (`Cull::Back`): each face is lit as OpenGL lights it, and a scene
/// without two-sided lighting pays nothing.
///
/// ```
/// use fixshade::prelude::*;
/// use fixshade::lighting::BackFaces;
/// let light = DirectionalLight::<f32>::white([0.0, 0.0, 1.0]).unwrap();
/// let back = Material::new(&MaterialDesc { ambient: [0.0; 3], ..MaterialDesc::default() }).unwrap();
/// let lit = BackFaces(Lighting::<f32, _, Lambert>::new(light, back));
/// // a back face whose (front) normal points away from the viewer is lit from the front
/// use fixshade::lighting::Illuminate;
/// let c = lit.shade(&Lighting::<f32, DirectionalLight<f32>>::origin(), Vec3::from_f32([0.0, 0.0, -1.0]));
/// assert_eq!(c.to_rgb888().r(), 204); // 0.8·(N·L = 1)
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BackFaces<I>(pub I);

/// [`Illuminate`] for a wrapper around a lighting `l` (the tier and the need
/// of positions of `l`, no fast path): `shade` and `shade_parts` as given, in
/// terms of `l`, the point `p`, the normal `n` and the vertex colour `color`.
macro_rules! wrapper_illuminate {
    (
        $wrapper:ident,
        |$l:ident, $p:ident, $n:ident| $shade:expr,
        |$l2:ident, $p2:ident, $n2:ident, $color:ident| $parts:expr $(,)?
    ) => {
        impl<I: Illuminate> Illuminate for $wrapper<I> {
            type Scalar = I::Scalar;
            const NEEDS_POSITION: bool = I::NEEDS_POSITION;
            type Fast = Off;
            fn lights_in_eye_space(&self) -> bool {
                self.0.lights_in_eye_space()
            }
            #[inline(always)]
            fn shade(&self, $p: &Point3<I::Scalar>, $n: Vec3<I::Scalar>) -> Rgb<I::Scalar> {
                let $l = &self.0;
                $shade
            }
            #[inline(always)]
            fn shade_parts(
                &self,
                $p2: &Point3<I::Scalar>,
                $n2: Vec3<I::Scalar>,
                $color: Option<Rgb<I::Scalar>>,
            ) -> LitColor<I::Scalar> {
                let $l2 = &self.0;
                $parts
            }
        }
    };
}

wrapper_illuminate!(
    BackFaces,
    |l, p, n| l.shade(p, n.neg()),
    |l, p, n, color| l.shade_parts(p, n.neg(), color),
);

/// `GL_SEPARATE_SPECULAR_COLOR` per point: [`Illuminate::shade`] is
/// [`LitColor::separate`] (the primary and secondary colours clamped apart, then
/// added). Per-pixel shading ([`PhongShading`](crate::shade::PhongShading)) then
/// matches OpenGL; with Gouraud shading OpenGL interpolates the two clamped
/// colours separately, which a textured Gouraud shader does
/// ([`Textured`](crate::shade::Textured): with a white texture, exactly
/// that).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SeparateSpecular<I>(pub I);

wrapper_illuminate!(
    SeparateSpecular,
    |l, p, n| l.shade_parts(p, n, None).separate(),
    |l, p, n, color| l.shade_parts(p, n, color),
);
