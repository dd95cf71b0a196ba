//! Directions in the local shading frame, on any [`Real`].
//!
//! The local frame has the shading normal along +z, so `cos θ = w.z`. A [`Vec3<R>`] holds one
//! direction per lane (structure of arrays): `Vec3<f32x8>` is eight directions. The free
//! functions below are the spherical-coordinate helpers of pbrt-v4's `vecmath.h`, written for
//! lanes.
//!
//! glam types and arrays convert in at the API edge: `Vec3<f32>: From<glam::Vec3>`,
//! `Vec3<f64>: From<glam::DVec3>`, `Vec3<f32x8>: From<[glam::Vec3; 8]>` and
//! `Vec3<R>: From<[R; 3]>`. These conversions copy components; they do not change frames:
//! a world-space vector goes through [`crate::frame::Frame::to_local`] (see the y-up trap
//! in the [`frame`](crate::frame) docs).

use crate::Scalar;
use crate::real::{Real, Splat, f32x4, f32x8, f32x16, splat_scalar};

/// A 3-vector whose components are [`Real`]s (one direction per lane).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vec3<R> {
    /// Component along the first tangent.
    pub x: R,
    /// Component along the second tangent (bitangent).
    pub y: R,
    /// Component along the normal.
    pub z: R,
}

impl<R: Real> Vec3<R> {
    /// `(x, y, z)`.
    #[inline(always)]
    #[must_use]
    pub const fn new(x: R, y: R, z: R) -> Self {
        Self { x, y, z }
    }

    /// Dot product.
    #[inline(always)]
    #[must_use]
    pub fn dot(self, o: Self) -> R {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Squared length.
    #[inline(always)]
    #[must_use]
    pub fn length_squared(self) -> R {
        self.dot(self)
    }

    /// Euclidean length.
    #[inline(always)]
    #[must_use]
    pub fn length(self) -> R {
        self.length_squared().sqrt()
    }

    /// `self · s`.
    #[inline(always)]
    #[must_use]
    pub fn scale(self, s: R) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }

    /// Unit vector along `self`; lanes of zero length give the zero vector (never NaN).
    #[inline(always)]
    #[must_use]
    pub fn normalize_or_zero(self) -> Self {
        let len2 = self.length_squared();
        let ok = len2.gt(R::zero());
        let inv = R::select(ok, len2.max(R::from_f64(1e-300)).sqrt().recip(), R::zero());
        self.scale(inv)
    }

    /// Cross product `self × o` (right-handed: `x × y = z`).
    #[inline(always)]
    #[must_use]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Mirror direction of `self` about `n`: `2 (self·n) n − self`.
    #[inline(always)]
    #[must_use]
    pub fn reflect(self, n: Self) -> Self {
        n.scale(R::from_f64(2.0) * self.dot(n)) + self.scale(-R::one())
    }
}

/// The same vector on another number type (every lane the same direction on lanes).
impl<S: Scalar> Splat for Vec3<S> {
    type On<L: Real> = Vec3<L>;
    #[inline]
    fn splat<L: Real>(&self) -> Vec3<L> {
        Vec3::new(
            splat_scalar(self.x),
            splat_scalar(self.y),
            splat_scalar(self.z),
        )
    }
}

/// Component-wise sum, `a + b` (the one spelling of vector addition).
impl<R: Real> core::ops::Add for Vec3<R> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<R: Real> core::ops::Sub for Vec3<R> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<R: Real> core::ops::Neg for Vec3<R> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

/// `cos θ = w.z`.
#[inline(always)]
#[must_use]
pub fn cos_theta<R: Real>(w: Vec3<R>) -> R {
    w.z
}

/// `cos² θ`.
#[inline(always)]
#[must_use]
pub fn cos2_theta<R: Real>(w: Vec3<R>) -> R {
    w.z * w.z
}

/// `sin² θ = x² + y²` (computed from the tangent components, which keeps precision near the
/// pole where `1 − cos² θ` cancels).
#[inline(always)]
#[must_use]
pub fn sin2_theta<R: Real>(w: Vec3<R>) -> R {
    w.x * w.x + w.y * w.y
}

/// `tan² θ = sin² θ / cos² θ`; `+∞` at `cos θ = 0`.
#[inline(always)]
#[must_use]
pub fn tan2_theta<R: Real>(w: Vec3<R>) -> R {
    sin2_theta(w) / cos2_theta(w)
}

/// Half vector `wm = normalize(wi + wo)`; zero (never NaN) when `wi = −wo`.
///
/// For directions in the upper hemisphere `wm.z ≥ 0`.
#[inline(always)]
#[must_use]
pub fn half_vector<R: Real>(wi: Vec3<R>, wo: Vec3<R>) -> Vec3<R> {
    (wi + wo).normalize_or_zero()
}

/// `[x, y, z]` → `Vec3 { x, y, z }`.
impl<R> From<[R; 3]> for Vec3<R> {
    #[inline]
    fn from([x, y, z]: [R; 3]) -> Self {
        Self { x, y, z }
    }
}

/// `Vec3 { x, y, z }` → `[x, y, z]`.
impl<R> From<Vec3<R>> for [R; 3] {
    #[inline]
    fn from(v: Vec3<R>) -> Self {
        [v.x, v.y, v.z]
    }
}

impl From<glam::Vec3> for Vec3<f32> {
    #[inline]
    fn from(v: glam::Vec3) -> Self {
        Self::new(v.x, v.y, v.z)
    }
}

impl From<Vec3<f32>> for glam::Vec3 {
    #[inline]
    fn from(v: Vec3<f32>) -> Self {
        glam::Vec3::new(v.x, v.y, v.z)
    }
}

impl From<glam::DVec3> for Vec3<f64> {
    #[inline]
    fn from(v: glam::DVec3) -> Self {
        Self::new(v.x, v.y, v.z)
    }
}

impl From<Vec3<f64>> for glam::DVec3 {
    #[inline]
    fn from(v: Vec3<f64>) -> Self {
        glam::DVec3::new(v.x, v.y, v.z)
    }
}

macro_rules! from_glam_array {
    ($v:ty, $n:expr) => {
        impl From<[glam::Vec3; $n]> for Vec3<$v> {
            /// Transposes `N` glam vectors (array of structures) into one lane vector.
            #[inline]
            fn from(a: [glam::Vec3; $n]) -> Self {
                Self::new(
                    <$v>::new(core::array::from_fn(|i| a[i].x)),
                    <$v>::new(core::array::from_fn(|i| a[i].y)),
                    <$v>::new(core::array::from_fn(|i| a[i].z)),
                )
            }
        }
    };
}
from_glam_array!(f32x4, 4);
from_glam_array!(f32x8, 8);
from_glam_array!(f32x16, 16);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_vector_of_opposite_directions_is_zero_not_nan() {
        let w = Vec3::new(0.6f32, 0.0, 0.8);
        let h = half_vector(w, w.scale(-1.0));
        assert_eq!(h, Vec3::new(0.0, 0.0, 0.0));
        let h = half_vector(w, Vec3::new(-0.6, 0.0, 0.8));
        assert!((h.z - 1.0).abs() < 1e-6);
    }

    #[test]
    fn glam_lanes_transpose() {
        let a: [glam::Vec3; 8] = core::array::from_fn(|i| glam::Vec3::new(i as f32, 1.0, 2.0));
        let v = Vec3::<f32x8>::from(a);
        assert_eq!(v.x.lane(5), 5.0);
        assert_eq!(v.z.lane(7), 2.0);
    }
}
