//! Three-component vectors, generic over the number tier.

use crate::num::Scalar;

/// A three-component vector: a direction or normal in a tier `S`, or a position in
/// the tier's geometry type `S::Geo`.
///
/// ```
/// use fixshade::num::Scalar;
/// use fixshade::num::Vec3;
/// let n = Vec3::<f32>::from_f32([0.0, 0.0, 2.0]).normalize();
/// assert_eq!(n, Vec3::new(0.0, 0.0, 1.0));
/// assert_eq!(n.dot(Vec3::new(0.0, 0.6, 0.8)), 0.8);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vec3<T> {
    /// x component.
    pub x: T,
    /// y component.
    pub y: T,
    /// z component.
    pub z: T,
}

impl<T> Vec3<T> {
    /// A vector from its components.
    #[inline(always)]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }
}

impl<S: Scalar> Vec3<S> {
    /// Converts from `f32` components (saturating; NaN becomes zero).
    #[inline]
    pub fn from_f32(v: [f32; 3]) -> Self {
        Self::new(S::from_f32(v[0]), S::from_f32(v[1]), S::from_f32(v[2]))
    }

    /// The components as `f32`.
    #[inline]
    pub fn to_f32(self) -> [f32; 3] {
        [self.x.to_f32(), self.y.to_f32(), self.z.to_f32()]
    }

    /// `a·b = ax·bx + ay·by + az·bz`, saturating ([`Scalar::dot3`]).
    #[inline(always)]
    pub fn dot(self, o: Self) -> S {
        S::dot3(self, o)
    }

    /// `a + b`, saturating per component.
    #[inline(always)]
    pub fn add(self, o: Self) -> Self {
        Self::new(self.x.add(o.x), self.y.add(o.y), self.z.add(o.z))
    }

    /// `a − b`, saturating per component.
    #[inline(always)]
    pub fn sub(self, o: Self) -> Self {
        Self::new(self.x.sub(o.x), self.y.sub(o.y), self.z.sub(o.z))
    }

    /// `k·a`, saturating per component.
    #[inline(always)]
    pub fn scale(self, k: S) -> Self {
        Self::new(self.x.mul(k), self.y.mul(k), self.z.mul(k))
    }

    /// `−a`.
    #[inline(always)]
    pub fn neg(self) -> Self {
        Self::new(
            S::ZERO.sub(self.x),
            S::ZERO.sub(self.y),
            S::ZERO.sub(self.z),
        )
    }

    /// `a / |a|` (see [`Scalar::normalize`] for tiny and zero vectors).
    #[inline(always)]
    pub fn normalize(self) -> Self {
        S::normalize(self)
    }

    /// The ideal reflection of `l` about the unit normal `self`: `R = 2(N·L)N − L`.
    ///
    /// Each component is `2(N·L)·N_i − L_i` rounded once (see
    /// [`Scalar::twice_mul_sub`]): at the mirror direction `2(N·L)` is 2, which the
    /// fixed tiers cannot hold, but the components of `R` can.
    #[inline(always)]
    pub fn reflect(self, l: Self) -> Self {
        let nl = self.dot(l);
        Self::new(
            nl.twice_mul_sub(self.x, l.x),
            nl.twice_mul_sub(self.y, l.y),
            nl.twice_mul_sub(self.z, l.z),
        )
    }
}

/// A position in the geometry type of tier `S`.
pub type Point3<S> = Vec3<<S as Scalar>::Geo>;

/// Converts an `f32` position to the geometry type of tier `S` (saturating, NaN → 0).
#[inline]
pub fn point_from_f32<S: Scalar>(p: [f32; 3]) -> Point3<S> {
    Vec3::new(
        S::geo_from_f32(p[0]),
        S::geo_from_f32(p[1]),
        S::geo_from_f32(p[2]),
    )
}

/// `a − b` for positions (saturating).
#[inline(always)]
pub(crate) fn point_sub<S: Scalar>(a: Point3<S>, b: Point3<S>) -> Point3<S> {
    Vec3::new(
        S::geo_sub(a.x, b.x),
        S::geo_sub(a.y, b.y),
        S::geo_sub(a.z, b.z),
    )
}
