//! What the shading stage lights with: the [`Illuminate`] trait, implemented by
//! every [`Lighting`] configuration and by the [`BackFaces`] and
//! [`SeparateSpecular`] wrappers around one.

use super::{
    DirectionalLight, FogModel, InfiniteViewer, LightSet, Lighting, LitColor, Model, NoFog,
};
use super::{Specular, Viewed, Viewer};
use crate::color::Rgb;
use crate::num::{Exponent, Point3, Scalar, Vec3};

/// What the shading stage lights with: the colour of a surface point in eye
/// coordinates. Implemented by every [`Viewed`] [`Lighting`] and by
/// [`BackFaces`] and [`SeparateSpecular`] around one (one type parameter for
/// the shading modes instead of five). A lighting of your own implements
/// `shade` (and `shade_parts` if it keeps a specular part apart).
///
/// Every mode refuses a [`Lighting`] whose lights were never seen from the eye
/// ([`Viewed`]): each of these fails to compile with "`Lighting<…>` does not
/// light a shader: it is not a lighting in eye coordinates" (with
/// `&world.eye_space()` each compiles).
///
/// ```compile_fail,E0277
/// # use fixshade::prelude::*;
/// # let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// # let world = Lighting::<Q14, _, BlinnPhong>::new([light], Material::new(&MaterialDesc::default()).unwrap());
/// Shader::<_, _, _, Rgb565>::new(FlatShading, &world, Linear);
/// ```
///
/// ```compile_fail,E0277
/// # use fixshade::prelude::*;
/// # let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// # let world = Lighting::<Q14, _, BlinnPhong>::new([light], Material::new(&MaterialDesc::default()).unwrap());
/// # use fixshade::texture::{Filter, Texels, Texture, Wrap};
/// # static TEX: [u16; 1] = [0xffff];
/// # let tex = Texture::new(Texels::Rgb565(&TEX), 0, 0, Wrap::Repeat).unwrap();
/// Shader::<_, _, _, Rgb565>::new(GouraudShading.textured(tex, Filter::Nearest), &world, Linear);
/// ```
///
/// ```compile_fail,E0277
/// # use fixshade::prelude::*;
/// # let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// # let world = Lighting::<Q14, _, BlinnPhong>::new([light], Material::new(&MaterialDesc::default()).unwrap());
/// Shader::<_, _, _, Rgb565>::new(PhongShading, &world, Linear);
/// ```
///
/// ```compile_fail,E0277
/// # use fixshade::prelude::*;
/// # let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// # let world = Lighting::<Q14, _, BlinnPhong>::new([light], Material::new(&MaterialDesc::default()).unwrap());
/// Shader::<_, _, _, Rgb565>::new(IncrementalPhongShading, &world, Linear);
/// ```
///
/// ```compile_fail,E0277
/// # use fixshade::prelude::*;
/// # let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// # let world = Lighting::<Q14, _, BlinnPhong>::new([light], Material::new(&MaterialDesc::default()).unwrap());
/// Shader::<_, _, _, Rgb565>::new(QuadraticPhongShading, &world, Linear);
/// ```
///
/// ```compile_fail,E0277
/// # use fixshade::prelude::*;
/// # let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// # let world = Lighting::<Q14, _, BlinnPhong>::new([light], Material::new(&MaterialDesc::default()).unwrap());
/// # use fixshade::texture::{NormalMap, Wrap};
/// # static MAP: [[i16; 3]; 1] = [NormalMap::FLAT];
/// # let map = NormalMap::new(&MAP, 0, 0, Wrap::Repeat).unwrap();
/// Shader::<_, _, _, Rgb565>::new(PhongShading.normal_mapped(map), &world, Linear);
/// ```
///
/// ```compile_fail,E0277
/// # use fixshade::prelude::*;
/// # let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// # let world = Lighting::<Q14, _, BlinnPhong>::new([light], Material::new(&MaterialDesc::default()).unwrap());
/// # use fixshade::texture::{NormalMap, Wrap};
/// # static MAP: [[i16; 3]; 1] = [NormalMap::FLAT];
/// # let map = NormalMap::new(&MAP, 0, 0, Wrap::Repeat).unwrap();
/// Shader::<_, _, _, Rgb565>::new(IncrementalPhongShading.normal_mapped(map), &world, Linear);
/// ```
#[diagnostic::on_unimplemented(
    message = "`{Self}` does not light a shader: it is not a lighting in eye coordinates",
    label = "not a lighting seen from the eye",
    note = "a `Lighting` has its lights in world coordinates: see them through the camera, `lighting.viewed(camera.view())?`, or say they are given in eye coordinates, `lighting.eye_space()`"
)]
pub trait Illuminate {
    /// The number tier.
    type Scalar: Scalar;
    /// Whether [`Illuminate::shade`] reads the position (see [`Lighting::NEEDS_POSITION`]).
    const NEEDS_POSITION: bool;
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
    for Viewed<Lighting<S, L, M, V, F>>
{
    type Scalar = S;
    const NEEDS_POSITION: bool = Lighting::<S, L, M, V, F>::NEEDS_POSITION;
    #[inline(always)]
    fn shade(&self, p: &Point3<S>, n: Vec3<S>) -> Rgb<S> {
        self.lighting().shade(p, n)
    }
    #[inline(always)]
    fn shade_parts(&self, p: &Point3<S>, n: Vec3<S>, color: Option<Rgb<S>>) -> LitColor<S> {
        self.lighting().shade_parts(p, n, color)
    }
}

/// The lightings of the per-pixel kernels for directional lights
/// ([`IncrementalPhongShading`](crate::shade::IncrementalPhongShading),
/// [`QuadraticPhongShading`](crate::shade::QuadraticPhongShading)): `K`
/// directional lights, a viewer at infinity, no fog.
pub(crate) type Directional<S, const K: usize, M> =
    Viewed<Lighting<S, [DirectionalLight<S>; K], M, InfiniteViewer<S>, NoFog>>;

impl<S: Scalar, const K: usize, M: Model> Directional<S, K, M> {
    /// Each light's terms of the lighting equation, prepared for the material
    /// and the viewer: what the kernels for directional lights evaluate per
    /// pixel from `N·L` and `N·H` (or `R·V`).
    pub(crate) fn directional_terms(&self) -> [DirectionalTerms<S>; K] {
        let l = self.lighting();
        core::array::from_fn(|j| {
            let light = &l.lights()[j];
            let pre = light.prepared();
            DirectionalTerms {
                dir: light.direction(),
                half: pre.half,
                diffuse: pre.diffuse,
                specular: if M::SPECULAR == Specular::None {
                    Rgb::BLACK
                } else {
                    pre.specular
                },
                base: l.base(),
                shininess: l.material().shininess,
            }
        })
    }
}

/// One directional light's prepared terms of the lighting equation, for a
/// viewer at infinity (see [`Directional::directional_terms`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct DirectionalTerms<S> {
    /// Towards the light.
    pub dir: Vec3<S>,
    /// The halfway vector (`None` without a specular term).
    pub half: Option<Vec3<S>>,
    /// Light diffuse times material diffuse.
    pub diffuse: Rgb<S>,
    /// Light specular times material specular (black without a specular term).
    pub specular: Rgb<S>,
    /// Emission and ambient.
    pub base: Rgb<S>,
    /// The specular exponent.
    pub shininess: Exponent,
}

/// Two-sided lighting (`GL_LIGHT_MODEL_TWO_SIDE`): lights back faces with the
/// normal negated. Wrap a lighting of the back material and draw the back
/// faces with it (`Cull::Front`), the front faces with the front lighting
/// (`Cull::Back`); a scene without two-sided lighting pays nothing.
///
/// ```
/// use fixshade::prelude::*;
/// use fixshade::lighting::BackFaces;
/// let light = DirectionalLight::<f32>::white([0.0, 0.0, 1.0]).unwrap();
/// let back = Material::new(&MaterialDesc { ambient: [0.0; 3], ..MaterialDesc::default() }).unwrap();
/// let lit = BackFaces(Lighting::<f32, _, Lambert>::new(light, back).eye_space());
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
/// [`LitColor::separate`]. Per-pixel shading then matches OpenGL; for Gouraud,
/// OpenGL interpolates the two clamped colours apart, as a
/// [`Textured`](crate::shade::Textured) Gouraud shader (white texture) does.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SeparateSpecular<I>(pub I);

wrapper_illuminate!(
    SeparateSpecular,
    |l, p, n| l.shade_parts(p, n, None).separate(),
    |l, p, n, color| l.shade_parts(p, n, color),
);
