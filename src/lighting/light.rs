//! Light sources: directional, point (with distance attenuation) and spot lights,
//! and sets of them.
//!
//! Each light kind is its own type, so a scene whose lights are all directional
//! compiles to code without attenuation or spot-cone evaluation. [`AnyLight`] mixes
//! kinds at run time; arrays, `heapless::Vec`s and tuples of lights are light sets.

use crate::color::Rgb;
use crate::error::{direction, finite, finite_all, non_negative, non_negative3, ParamError};
use crate::lighting::{AnyLight, Material};
use crate::num::{point_from_f32, point_sub, Mat4, Point3, Vec3};
use crate::num::{Exponent, GeoScalar, Scalar};
use core::marker::PhantomData;

/// The colours a light emits into each term (OpenGL's `GL_AMBIENT`, `GL_DIFFUSE`,
/// `GL_SPECULAR` light parameters), linear RGB.
///
/// Kept as `f32`: only the product with the material's colour (and `1/a`),
/// formed when a [`Lighting`](crate::lighting::Lighting) is built, must fit the
/// tier (a `GL_DIFFUSE` of 2.5 on a material of 0.3 is exact in `Q14`).
/// [`LightColors::signed`] also takes negative colours (OpenGL's "negative light").
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightColors<S> {
    /// Added to the ambient term (`Ia`), scaled by the material's ambient colour.
    pub ambient: [f32; 3],
    /// Scaled by the material's diffuse colour and `N·L` (`Il` of the diffuse term).
    pub diffuse: [f32; 3],
    /// Scaled by the material's specular colour and the highlight (`Il` of the
    /// specular term; also drives the transmission term).
    pub specular: [f32; 3],
    tier: PhantomData<S>,
}

impl<S: Scalar> LightColors<S> {
    /// Validated colours: NaN, infinite or negative channels are rejected.
    pub fn new(
        ambient: [f32; 3],
        diffuse: [f32; 3],
        specular: [f32; 3],
    ) -> Result<Self, ParamError> {
        Ok(Self {
            ambient: non_negative3("light ambient", ambient)?,
            diffuse: non_negative3("light diffuse", diffuse)?,
            specular: non_negative3("light specular", specular)?,
            tier: PhantomData,
        })
    }

    /// Validated colours of any sign, as OpenGL takes them: a negative channel
    /// subtracts light (the output still clamps to [0, 1]). NaN and infinite
    /// channels are rejected.
    pub fn signed(
        ambient: [f32; 3],
        diffuse: [f32; 3],
        specular: [f32; 3],
    ) -> Result<Self, ParamError> {
        Ok(Self {
            ambient: finite_all("light ambient", ambient)?,
            diffuse: finite_all("light diffuse", diffuse)?,
            specular: finite_all("light specular", specular)?,
            tier: PhantomData,
        })
    }

    /// A light of colour `c` in the diffuse and specular terms, no ambient
    /// (the seeds' `Il`).
    pub fn rgb(c: [f32; 3]) -> Result<Self, ParamError> {
        Self::new([0.0; 3], c, c)
    }

    /// A white light of intensity 1 (no ambient), like OpenGL's `GL_LIGHT0`.
    pub fn white() -> Self {
        Self {
            ambient: [0.0; 3],
            diffuse: [1.0; 3],
            specular: [1.0; 3],
            tier: PhantomData,
        }
    }
}

/// A light's colours times the material's, with the attenuation's `1/a` folded
/// in, in `f32` (what [`Lighting::checked`](crate::lighting::Lighting::checked)
/// tests against the tier's range).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ColorTerms {
    /// `La ∘ ka / a`.
    pub ambient: [f32; 3],
    /// `Ld ∘ kd / a`.
    pub diffuse: [f32; 3],
    /// `Ls ∘ ks / a`.
    pub specular: [f32; 3],
    /// `Ls ∘ kst / a`.
    pub transmission: [f32; 3],
    /// Whether the terms are multiplied by a per-point factor in [0, 1] (the
    /// distance attenuation `1/(1 + b'·d + c'·d²)` or a spot cone); the ambient
    /// term then varies per point as well.
    pub varying: bool,
    /// Whether that factor is unbounded ([`Attenuation::is_unbounded`]).
    pub unbounded: bool,
}

impl ColorTerms {
    /// The terms of `colors` on `m`, each product times `k` (NaN from `0·∞` is 0;
    /// the conversion to a tier saturates what is beyond it).
    pub fn new<S: Scalar>(c: &LightColors<S>, m: &Material<S>, k: f32, varying: bool) -> Self {
        let p = |a: [f32; 3], b: [f32; 3]| core::array::from_fn(|i| a[i] * b[i] * k);
        Self {
            ambient: p(c.ambient, m.ambient),
            diffuse: p(c.diffuse, m.diffuse),
            specular: p(c.specular, m.specular),
            transmission: p(c.specular, m.transmission),
            varying,
            unbounded: false,
        }
    }
}

/// Light colours multiplied by a material's colours once, when a
/// [`Lighting`](crate::lighting::Lighting) is built, so the per-pixel work is one
/// product per channel and term.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Prepared<S> {
    /// `La ∘ ka`.
    pub ambient: Rgb<S>,
    /// `Ld ∘ kd`.
    pub diffuse: Rgb<S>,
    /// `Ls ∘ ks`.
    pub specular: Rgb<S>,
    /// `Ls ∘ kst` (transmission).
    pub transmission: Rgb<S>,
    /// The halfway vector `H = (L + V)/|L + V|` when both are constant
    /// (directional light, viewer at infinity), by
    /// [`Scalar::normalize_nearest_unit`]: the incremental kernels take it as unit.
    pub half: Option<Vec3<S>>,
}

impl<S: Scalar> Prepared<S> {
    /// The terms converted to the tier (rounded once; beyond the range they
    /// saturate, which [`Lighting::checked`](crate::lighting::Lighting::checked)
    /// reports), and the halfway vector of the constant `l` and `v`.
    fn new(t: &ColorTerms, l: Option<Vec3<S>>, v: Option<Vec3<S>>) -> Self {
        Self {
            ambient: Rgb::from_f32(t.ambient),
            diffuse: Rgb::from_f32(t.diffuse),
            specular: Rgb::from_f32(t.specular),
            transmission: Rgb::from_f32(t.transmission),
            half: l.zip(v).map(|(l, v)| S::normalize_nearest_unit(l.add(v))),
        }
    }
}

/// What one light contributes at one surface point.
#[derive(Clone, Copy, Debug)]
pub struct Incident<'a, S> {
    /// Unit vector from the surface point towards the light.
    pub l: Vec3<S>,
    /// `att · spot`, the factor on the whole contribution of this light; `None`
    /// means exactly 1 (no multiplication is done).
    pub scale: Option<S>,
    /// The factor is `scale · 2^scale_exp` ([`Scalar::geo_inv_quadratic_exp`]:
    /// `scale_exp` is 0 but near an unbounded attenuation); the terms are
    /// multiplied by `scale`, then by `2^scale_exp` with saturation.
    pub scale_exp: u32,
    /// Whether this light's ambient term is added per point. `false` for lights
    /// whose ambient is constant: it is folded into the scene's base colour.
    pub ambient_per_point: bool,
    /// The light's colours times the material's.
    pub colors: &'a Prepared<S>,
}

/// One light source.
pub trait LightSource<S: Scalar> {
    /// Whether the light needs the surface position (point and spot lights).
    const NEEDS_POSITION: bool;
    /// [`LightSet::prepare`] for this light.
    fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>);
    /// The ambient contribution that does not depend on the surface point, if any.
    fn constant_ambient(&self) -> Option<Rgb<S>>;
    /// The light arriving at surface point `p`.
    fn incident(&self, p: &Point3<S>) -> Incident<'_, S>;
    /// The colour terms [`LightSource::prepare`] converts for `material`, in `f32`
    /// (for the range check of [`Lighting::checked`](crate::lighting::Lighting::checked));
    /// `None` (the default) leaves the light out of the check.
    fn color_terms(&self, material: &Material<S>) -> Option<ColorTerms> {
        let _ = material;
        None
    }
    /// Moves the light by `m` (world to eye coordinates) as
    /// [`Lighting::viewed`](crate::lighting::Lighting::viewed) describes; call
    /// [`LightSource::prepare`] afterwards.
    ///
    /// # Errors
    ///
    /// [`ParamError::ZeroDirection`] when `m` maps a direction to zero,
    /// [`ParamError::NotFinite`] for a non-finite result (the light unchanged).
    fn transform(&mut self, m: &Mat4) -> Result<(), ParamError>;
}

/// `d` (a unit vector in the tier) through the upper-left 3×3 of `m`,
/// normalised again.
fn transform_direction<S: Scalar>(
    name: &'static str,
    d: Vec3<S>,
    m: &Mat4,
) -> Result<Vec3<S>, ParamError> {
    direction(name, m.transform_vector(d.to_f32())).map(Vec3::from_f32)
}

/// Position `p` through `m` (divided by the homogeneous `w`).
fn transform_position<S: Scalar>(p: Point3<S>, m: &Mat4) -> Result<Point3<S>, ParamError> {
    let [x, y, z, w] = m.transform_point([p.x, p.y, p.z].map(S::geo_to_f32));
    finite_all("position", [x / w, y / w, z / w]).map(point_from_f32::<S>)
}

/// What receives each light's [`Incident`] from [`LightSet::for_each`] (a trait
/// rather than a closure so that the per-light work is always inlined into the
/// per-pixel loop; closures are also visitors).
pub trait IncidentVisitor<S: Scalar> {
    /// Called once per light.
    fn visit(&mut self, inc: Incident<'_, S>);
}

impl<S: Scalar, F: FnMut(Incident<'_, S>)> IncidentVisitor<S> for F {
    #[inline(always)]
    fn visit(&mut self, inc: Incident<'_, S>) {
        self(inc)
    }
}

/// A set of lights, summed by the lighting equation.
///
/// Implemented for every light type, for arrays `[L; K]`, for `heapless::Vec<L, K>`
/// (a run-time count up to a compile-time capacity) and for tuples of up to four
/// light sets (mixed kinds without run-time dispatch).
pub trait LightSet<S: Scalar> {
    /// Whether any light needs the surface position.
    const NEEDS_POSITION: bool;
    /// Multiplies each light's colours with `material` and precomputes what is
    /// constant for a viewer direction `view` (`None` for a local viewer).
    fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>);
    /// The sum of the lights' point-independent ambient contributions.
    fn constant_ambient(&self) -> Rgb<S>;
    /// Hands the light arriving at `p` from each light to `visitor`.
    fn for_each<V: IncidentVisitor<S>>(&self, p: &Point3<S>, visitor: &mut V);
    /// Hands each light's colour terms for `material`, in `f32`, to `f`
    /// (construction time only).
    fn for_each_color_terms(&self, material: &Material<S>, f: &mut dyn FnMut(ColorTerms));
    /// Moves every light by `m` as
    /// [`Lighting::viewed`](crate::lighting::Lighting::viewed) describes; on an
    /// error, the lights before the failing one are moved.
    fn transform(&mut self, m: &Mat4) -> Result<(), ParamError>;
}

macro_rules! light_set_for_source {
    ($($ty:ident),*) => {$(
        impl<S: Scalar> LightSet<S> for $ty<S> {
            const NEEDS_POSITION: bool = <Self as LightSource<S>>::NEEDS_POSITION;
            #[inline]
            fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
                LightSource::prepare(self, material, view)
            }
            #[inline]
            fn constant_ambient(&self) -> Rgb<S> {
                LightSource::constant_ambient(self).unwrap_or(Rgb::BLACK)
            }
            #[inline(always)]
            fn for_each<V: IncidentVisitor<S>>(&self, p: &Point3<S>, visitor: &mut V) {
                visitor.visit(self.incident(p))
            }
            fn for_each_color_terms(&self, material: &Material<S>, f: &mut dyn FnMut(ColorTerms)) {
                if let Some(t) = LightSource::color_terms(self, material) {
                    f(t)
                }
            }
            fn transform(&mut self, m: &Mat4) -> Result<(), ParamError> {
                LightSource::transform(self, m)
            }
        }
    )*};
}
light_set_for_source!(DirectionalLight, PointLight, SpotLight, AnyLight);

/// `LightSet` for a container of light sets that iterates by reference.
macro_rules! light_set_for_container {
    ($($ty:ty),*) => {$(
        impl<S: Scalar, L: LightSet<S>, const K: usize> LightSet<S> for $ty {
            const NEEDS_POSITION: bool = L::NEEDS_POSITION;
            fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
                self.iter_mut().for_each(|l| l.prepare(material, view));
            }
            fn constant_ambient(&self) -> Rgb<S> {
                self.iter().fold(Rgb::BLACK, |a, l| a.add(l.constant_ambient()))
            }
            #[inline(always)]
            fn for_each<V: IncidentVisitor<S>>(&self, p: &Point3<S>, visitor: &mut V) {
                for l in self.iter() {
                    l.for_each(p, visitor);
                }
            }
            fn for_each_color_terms(&self, material: &Material<S>, f: &mut dyn FnMut(ColorTerms)) {
                self.iter().for_each(|l| l.for_each_color_terms(material, f));
            }
            fn transform(&mut self, m: &Mat4) -> Result<(), ParamError> {
                self.iter_mut().try_for_each(|l| l.transform(m))
            }
        }
    )*};
}
light_set_for_container!([L; K], heapless::Vec<L, K>);

macro_rules! light_set_tuple {
    ($($name:ident $idx:tt),*) => {
        impl<S: Scalar, $($name: LightSet<S>),*> LightSet<S> for ($($name,)*) {
            const NEEDS_POSITION: bool = false $(|| $name::NEEDS_POSITION)*;
            fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
                $(self.$idx.prepare(material, view);)*
            }
            fn constant_ambient(&self) -> Rgb<S> {
                Rgb::BLACK $(.add(self.$idx.constant_ambient()))*
            }
            #[inline(always)]
            fn for_each<V: IncidentVisitor<S>>(&self, p: &Point3<S>, visitor: &mut V) {
                $(self.$idx.for_each(p, visitor);)*
            }
            fn for_each_color_terms(&self, material: &Material<S>, f: &mut dyn FnMut(ColorTerms)) {
                $(self.$idx.for_each_color_terms(material, f);)*
            }
            fn transform(&mut self, m: &Mat4) -> Result<(), ParamError> {
                $(self.$idx.transform(m)?;)*
                Ok(())
            }
        }
    };
}
light_set_tuple!(A 0, B 1);
light_set_tuple!(A 0, B 1, C 2);
light_set_tuple!(A 0, B 1, C 2, D 3);

/// A light at infinity: parallel rays, constant direction, no attenuation
/// (homogeneous `w = 0`).
///
/// ```
/// use fixshade::lighting::{DirectionalLight, LightColors};
/// use fixshade::num::Q14;
/// let sun = DirectionalLight::<Q14>::new([1.0, 1.0, 1.0], LightColors::white()).unwrap();
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight<S> {
    dir: Vec3<S>,
    colors: LightColors<S>,
    pre: Prepared<S>,
}

impl<S: Scalar> DirectionalLight<S> {
    /// A light shining from `towards_light` (the direction from the surface to the
    /// light; normalised here). Errors: non-finite or zero-length direction.
    pub fn new(towards_light: [f32; 3], colors: LightColors<S>) -> Result<Self, ParamError> {
        let d = direction("direction", towards_light)?;
        Ok(Self {
            dir: Vec3::from_f32(d),
            colors,
            pre: Prepared::default(),
        })
    }

    /// A white light of intensity 1 from `towards_light`.
    pub fn white(towards_light: [f32; 3]) -> Result<Self, ParamError> {
        Self::new(towards_light, LightColors::white())
    }

    /// The unit direction towards the light.
    pub fn direction(&self) -> Vec3<S> {
        self.dir
    }

    /// The light's colours times the material's, and the halfway vector, as set by
    /// the last `prepare`.
    pub fn prepared(&self) -> &Prepared<S> {
        &self.pre
    }
}

impl<S: Scalar> LightSource<S> for DirectionalLight<S> {
    const NEEDS_POSITION: bool = false;
    fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
        let t = ColorTerms::new(&self.colors, material, 1.0, false);
        self.pre = Prepared::new(&t, Some(self.dir), view);
    }
    fn constant_ambient(&self) -> Option<Rgb<S>> {
        Some(self.pre.ambient)
    }
    fn color_terms(&self, material: &Material<S>) -> Option<ColorTerms> {
        Some(ColorTerms::new(&self.colors, material, 1.0, false))
    }
    fn transform(&mut self, m: &Mat4) -> Result<(), ParamError> {
        self.dir = transform_direction("direction", self.dir, m)?;
        Ok(())
    }
    #[inline(always)]
    fn incident(&self, _p: &Point3<S>) -> Incident<'_, S> {
        Incident {
            l: self.dir,
            scale: None,
            scale_exp: 0,
            ambient_per_point: false,
            colors: &self.pre,
        }
    }
}

/// Distance attenuation `1/(a + b·d + c·d²)` (OpenGL's constant, linear and
/// quadratic attenuation). `a = 1, b = c = 0` is no attenuation; pure `1/d²` is
/// the physical case.
///
/// # Representation
///
/// The coefficients keep their `f32` relative precision: `f32` in the float
/// tiers; in the fixed tiers the exact 24-bit mantissa and exponent of each (a
/// 16-bit mantissa for `Q14`), multiplied with the normalised distance in 32-bit
/// (`Q14`) or 64-bit (`Q30`) integers. So `c = 10⁻⁶` at `d = 300` counts, for
/// every legal coefficient and distance (error: [`Scalar::geo_inv_quadratic`],
/// far below 1 LSB of 8-bit output).
///
/// # Folding `1/a`
///
/// A light folds the constant `1/a` into its colours once (in `f32`, when a
/// [`Lighting`](crate::lighting::Lighting) is built) and evaluates the factor
/// `1/(1 + (b/a)·d + (c/a)·d²)` in [0, 1]. So `GL_CONSTANT_ATTENUATION` 0.25 is
/// exact in the fixed tiers wherever the brightened colour terms fit
/// ([`Lighting::checked`](crate::lighting::Lighting::checked)).
///
/// # Extremes
///
/// - `a = 0` (pure `1/d²`) cannot be folded: the factor grows without bound near
///   the light ([`Attenuation::is_unbounded`]). The fixed tiers carry it as
///   `m·2^e` ([`Scalar::geo_inv_quadratic_exp`]) and saturate the contribution
///   only once formed (colours × cosines × `m`, then `× 2^e`): right wherever
///   it fits the range, else clamped to 1 as the reference's (so
///   `GL_LINEAR_ATTENUATION` 10⁻³⁰ with `a = 0` gives 255).
///   [`Lighting::checked`](crate::lighting::Lighting::checked) refuses what
///   could pull it back below 1. The float tiers cap the factor at 10⁹.
///   [`Attenuation::factor`] saturates at the tier's maximum (below 2 for the
///   fixed tiers, for any `a < ½`).
/// - Very far lights give factors that round to 0; lengths beyond the geometry range
///   (32768 units for the fixed tiers) saturate there.
/// - Negative distances (only reachable through [`Attenuation::factor`]) count as 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attenuation<G: GeoScalar> {
    /// `a, b, c` as given (for [`Attenuation::factor`]).
    k: G::InvQuadratic,
    /// `1, b/a, c/a`, or `a, b, c` when `a = 0` (or `b/a`, `c/a` overflow).
    kn: G::InvQuadratic,
    /// `1/a` when `kn` is normalised, else 1: folded into the colours.
    inv_a: f32,
    /// `b = c = 0`: the factor is the constant `1/a`, folded into the colours.
    constant: bool,
    /// `1/a` not folded and `b` or `c` non-zero: the factor is unbounded.
    unbounded: bool,
}

impl<G: GeoScalar> Attenuation<G> {
    /// Validated coefficients: finite, non-negative, not all zero.
    pub fn new<S: Scalar<Geo = G>>(a: f32, b: f32, c: f32) -> Result<Self, ParamError> {
        let a = non_negative("attenuation constant", a)?;
        let b = non_negative("attenuation linear", b)?;
        let c = non_negative("attenuation quadratic", c)?;
        if a == 0.0 && b == 0.0 && c == 0.0 {
            return Err(ParamError::AttenuationAllZero);
        }
        let (inv_a, bn, cn) = (1.0 / a, b / a, c / a);
        let constant = b == 0.0 && c == 0.0;
        // a constant 1/a is folded even where it overflows f32 (a < 2^-128):
        // the infinite colour terms `Lighting::checked` reports and the tier
        // conversion saturates
        let folded =
            a > 0.0 && (constant || (inv_a.is_finite() && bn.is_finite() && cn.is_finite()));
        let (kn, inv_a) = if folded {
            (G::inv_quadratic(1.0, bn, cn), inv_a)
        } else {
            (G::inv_quadratic(a, b, c), 1.0)
        };
        Ok(Self {
            k: G::inv_quadratic(a, b, c),
            kn,
            inv_a,
            constant,
            unbounded: !folded && !constant,
        })
    }

    /// No attenuation (`a = 1, b = c = 0`).
    pub fn none<S: Scalar<Geo = G>>() -> Self {
        let k = G::inv_quadratic(1.0, 0.0, 0.0);
        Self {
            k,
            kn: k,
            inv_a: 1.0,
            constant: true,
            unbounded: false,
        }
    }

    /// The attenuation factor `1/(a + b·d + c·d²)` at distance `d`
    /// ([`Scalar::geo_inv_quadratic`]; saturates at the tier's maximum).
    #[inline(always)]
    pub fn factor<S: Scalar<Geo = G>>(&self, d: G) -> S {
        S::geo_inv_quadratic(&self.k, d)
    }

    /// Whether the factor is the constant `1/a` (`b = c = 0`).
    pub fn is_constant(&self) -> bool {
        self.constant
    }

    /// The constant a light folds into its colours: `1/a` (1 when `a = 0`).
    pub fn folded(&self) -> f32 {
        self.inv_a
    }

    /// Whether the per-point factor is unbounded: no constant term to fold
    /// (`a = 0`, or `b/a`, `c/a` beyond `f32`) and `b` or `c` non-zero (see
    /// the type's docs, *Extremes*).
    pub fn is_unbounded(&self) -> bool {
        self.unbounded
    }

    /// The per-point factor after folding, `1/(1 + (b/a)·d + (c/a)·d²)` (or
    /// `1/(b·d + c·d²)` when `a = 0`), as `(m, e)`: `m·2^e`
    /// ([`Scalar::geo_inv_quadratic_exp`]).
    #[inline(always)]
    fn varying<S: Scalar<Geo = G>>(&self, d: G) -> (S, u32) {
        S::geo_inv_quadratic_exp(&self.kn, d)
    }

    /// The colour terms of `colors` on `m` with `1/a` folded in.
    fn terms<S: Scalar<Geo = G>>(
        &self,
        colors: &LightColors<S>,
        m: &Material<S>,
        spot: bool,
    ) -> ColorTerms {
        ColorTerms {
            unbounded: self.unbounded,
            ..ColorTerms::new(colors, m, self.inv_a, spot || !self.constant)
        }
    }
}

/// A point light at a position, with distance attenuation.
///
/// ```
/// use fixshade::lighting::{Attenuation, LightColors, PointLight};
/// use fixshade::num::Q14;
/// let att = Attenuation::new::<Q14>(1.0, 0.0, 0.05).unwrap();
/// let bulb = PointLight::<Q14>::new([0.0, 4.0, 3.0], att, LightColors::white()).unwrap();
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight<S: Scalar> {
    pos: Point3<S>,
    att: Attenuation<S::Geo>,
    colors: LightColors<S>,
    pre: Prepared<S>,
}

impl<S: Scalar> PointLight<S> {
    /// A point light at `position` (scene units; saturates beyond the geometry range).
    /// Errors: a non-finite position.
    pub fn new(
        position: [f32; 3],
        attenuation: Attenuation<S::Geo>,
        colors: LightColors<S>,
    ) -> Result<Self, ParamError> {
        Ok(Self {
            pos: point_from_f32::<S>(finite_all("position", position)?),
            att: attenuation,
            colors,
            pre: Prepared::default(),
        })
    }

    /// The colour terms on `material`; `cone`: a spot cone makes them vary per
    /// point whatever the attenuation.
    fn terms(&self, material: &Material<S>, cone: bool) -> ColorTerms {
        self.att.terms(&self.colors, material, cone)
    }

    /// Prepares [`PointLight::terms`] for the tier.
    fn prepare_terms(&mut self, material: &Material<S>, cone: bool) {
        self.pre = Prepared::new(&self.terms(material, cone), None, None);
    }

    /// `L = (P_light − P)/d` at `p`, and the attenuation factor `(k, e)` (`k·2^e`)
    /// there, `None` when it is constant.
    #[inline(always)]
    fn towards(&self, p: &Point3<S>) -> (Vec3<S>, Option<(S, u32)>) {
        let (l, d) = S::geo_direction(point_sub::<S>(self.pos, *p));
        (l, (!self.att.constant).then(|| self.att.varying::<S>(d)))
    }
}

impl<S: Scalar> LightSource<S> for PointLight<S> {
    const NEEDS_POSITION: bool = true;
    fn prepare(&mut self, material: &Material<S>, _view: Option<Vec3<S>>) {
        self.prepare_terms(material, false);
    }
    fn constant_ambient(&self) -> Option<Rgb<S>> {
        self.att.constant.then_some(self.pre.ambient)
    }
    fn color_terms(&self, material: &Material<S>) -> Option<ColorTerms> {
        Some(self.terms(material, false))
    }
    fn transform(&mut self, m: &Mat4) -> Result<(), ParamError> {
        self.pos = transform_position::<S>(self.pos, m)?;
        Ok(())
    }
    #[inline(always)]
    fn incident(&self, p: &Point3<S>) -> Incident<'_, S> {
        let (l, att) = self.towards(p);
        let (scale, scale_exp) = match att {
            Some((k, e)) => (Some(k), e),
            None => (None, 0),
        };
        Incident {
            l,
            scale,
            scale_exp,
            ambient_per_point: att.is_some(),
            colors: &self.pre,
        }
    }
}

/// A spot light: a point light whose intensity is `cos^e φ` inside a cone around
/// its axis and zero outside (φ is the angle between the axis and the ray from
/// the light; `cos φ = s·(−L)`).
///
/// At extremes: a cutoff of 90° is a hemisphere; exponent 0 is a sharp-edged cone
/// of uniform intensity; the point exactly at the light has `L = 0`, so only the
/// ambient term survives there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight<S: Scalar> {
    /// The light without its cone.
    point: PointLight<S>,
    axis: Vec3<S>,
    cos_cutoff: S,
    exponent: Exponent,
}

impl<S: Scalar> SpotLight<S> {
    /// A spot light at `position` pointing along `axis`, with a real `exponent`
    /// in 0..=65535 (`GL_SPOT_EXPONENT`) and `cutoff_deg` in 0..=90
    /// (`GL_SPOT_CUTOFF`; for 180, no cone, use a [`PointLight`]).
    ///
    /// Errors: non-finite position, zero or non-finite axis, exponent negative or
    /// above 65535, cutoff outside 0..=90.
    pub fn new(
        position: [f32; 3],
        axis: [f32; 3],
        exponent: f32,
        cutoff_deg: f32,
        attenuation: Attenuation<S::Geo>,
        colors: LightColors<S>,
    ) -> Result<Self, ParamError> {
        let point = PointLight::new(position, attenuation, colors)?;
        let axis = direction("spot axis", axis)?;
        let exponent = Exponent::new("spot exponent", exponent)?;
        let cutoff = finite("spot cutoff", cutoff_deg).map_err(|_| ParamError::CutoffOutOfRange)?;
        if !(0.0..=90.0).contains(&cutoff) {
            return Err(ParamError::CutoffOutOfRange);
        }
        Ok(Self {
            point,
            axis: Vec3::from_f32(axis),
            cos_cutoff: S::from_f32(libm::cosf(cutoff.to_radians())),
            exponent,
        })
    }
}

impl<S: Scalar> LightSource<S> for SpotLight<S> {
    const NEEDS_POSITION: bool = true;
    fn prepare(&mut self, material: &Material<S>, _view: Option<Vec3<S>>) {
        self.point.prepare_terms(material, true);
    }
    fn constant_ambient(&self) -> Option<Rgb<S>> {
        None
    }
    fn color_terms(&self, material: &Material<S>) -> Option<ColorTerms> {
        Some(self.point.terms(material, true))
    }
    fn transform(&mut self, m: &Mat4) -> Result<(), ParamError> {
        let axis = transform_direction("spot axis", self.axis, m)?;
        LightSource::transform(&mut self.point, m)?;
        self.axis = axis;
        Ok(())
    }
    #[inline(always)]
    fn incident(&self, p: &Point3<S>) -> Incident<'_, S> {
        let (l, att) = self.point.towards(p);
        // cos φ = s·(−L); spot = cos^e φ inside the cone, 0 outside (a cosine that
        // corrects the lengths of s and L, which cos^e φ amplifies)
        let cos_phi = S::ZERO.sub(S::cos_normal(self.axis, l));
        let spot = if cos_phi >= self.cos_cutoff && cos_phi > S::ZERO {
            cos_phi.min1().pow(self.exponent)
        } else {
            S::ZERO
        };
        let (scale, scale_exp) = match att {
            Some((k, e)) => (spot.mul(k), e),
            None => (spot, 0),
        };
        Incident {
            l,
            scale: Some(scale),
            scale_exp,
            ambient_per_point: true,
            colors: &self.point.pre,
        }
    }
}
