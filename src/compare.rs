//! [`approx`] comparisons (`AbsDiffEq`, `RelativeEq`, `UlpsEq`) for the crate's value types.
//!
//! Vector-like values compare component by component, and on SIMD lanes lane by lane: a
//! comparison holds when it holds for every component of every lane, with the tolerances
//! given in the lane's scalar type (`f32` for `Vec3<f32x8>`). So
//! `assert_relative_eq!(a, b, max_relative = 1e-6)` works alike for `Vec3<f32>` and
//! `Vec3<f32x8>`. [`F32Fma`] compares as the `f32` it wraps.
//!
//! ```
//! use approx::{assert_relative_eq, assert_ulps_eq};
//! use brdf::{Vec3, f32x8};
//! let a = Vec3::new(1.0_f32, 2.0, 3.0);
//! assert_relative_eq!(a, Vec3::new(1.0, 2.0, 3.0 + 1e-7), max_relative = 1e-6);
//! let lanes = Vec3::new(f32x8::splat(1.0), f32x8::splat(2.0), f32x8::from([3.0; 8]));
//! assert_ulps_eq!(lanes, lanes);
//! ```

use approx::{AbsDiffEq, RelativeEq, UlpsEq};

use crate::fresnel::Amplitudes;
use crate::real::F32Fma;
use crate::{Frame, Real, Vec3};

impl AbsDiffEq for F32Fma {
    type Epsilon = f32;
    fn default_epsilon() -> f32 {
        f32::default_epsilon()
    }
    fn abs_diff_eq(&self, other: &Self, epsilon: f32) -> bool {
        self.0.abs_diff_eq(&other.0, epsilon)
    }
}

impl RelativeEq for F32Fma {
    fn default_max_relative() -> f32 {
        f32::default_max_relative()
    }
    fn relative_eq(&self, other: &Self, epsilon: f32, max_relative: f32) -> bool {
        self.0.relative_eq(&other.0, epsilon, max_relative)
    }
}

impl UlpsEq for F32Fma {
    fn default_max_ulps() -> u32 {
        f32::default_max_ulps()
    }
    fn ulps_eq(&self, other: &Self, epsilon: f32, max_ulps: u32) -> bool {
        self.0.ulps_eq(&other.0, epsilon, max_ulps)
    }
}

/// Every lane of every listed component pair satisfies `$cmp`.
macro_rules! lanes_all {
    ($a:expr, $b:expr, [$($f:ident),+], |$x:ident, $y:ident| $cmp:expr) => {
        (0..R::LANES).all(|l| {
            true $(&& {
                let ($x, $y) = ($a.$f.lane(l), $b.$f.lane(l));
                $cmp
            })+
        })
    };
}

/// Implements the three approx traits for a struct of `R` fields, lane by lane.
macro_rules! approx_fields {
    ($t:ident, [$($f:ident),+]) => {
        impl<R: Real + PartialEq> AbsDiffEq for $t<R>
        where
            R::Scalar: AbsDiffEq<Epsilon = R::Scalar>,
        {
            type Epsilon = R::Scalar;
            fn default_epsilon() -> R::Scalar {
                R::Scalar::default_epsilon()
            }
            fn abs_diff_eq(&self, other: &Self, epsilon: R::Scalar) -> bool {
                lanes_all!(self, other, [$($f),+], |x, y| x.abs_diff_eq(&y, epsilon))
            }
        }

        impl<R: Real + PartialEq> RelativeEq for $t<R>
        where
            R::Scalar: RelativeEq<Epsilon = R::Scalar>,
        {
            fn default_max_relative() -> R::Scalar {
                R::Scalar::default_max_relative()
            }
            fn relative_eq(&self, other: &Self, epsilon: R::Scalar, max_relative: R::Scalar) -> bool {
                lanes_all!(self, other, [$($f),+], |x, y| x.relative_eq(&y, epsilon, max_relative))
            }
        }

        impl<R: Real + PartialEq> UlpsEq for $t<R>
        where
            R::Scalar: UlpsEq<Epsilon = R::Scalar>,
        {
            fn default_max_ulps() -> u32 {
                R::Scalar::default_max_ulps()
            }
            fn ulps_eq(&self, other: &Self, epsilon: R::Scalar, max_ulps: u32) -> bool {
                lanes_all!(self, other, [$($f),+], |x, y| x.ulps_eq(&y, epsilon, max_ulps))
            }
        }
    };
}

approx_fields!(Vec3, [x, y, z]);
approx_fields!(Amplitudes, [r_s, r_p, t_s, t_p, cos_theta_i, cos_theta_t]);

/// Frames compare by their three axes.
impl<R: Real + PartialEq> AbsDiffEq for Frame<R>
where
    R::Scalar: AbsDiffEq<Epsilon = R::Scalar>,
{
    type Epsilon = R::Scalar;
    fn default_epsilon() -> R::Scalar {
        R::Scalar::default_epsilon()
    }
    fn abs_diff_eq(&self, other: &Self, epsilon: R::Scalar) -> bool {
        self.axes()
            .iter()
            .zip(other.axes().iter())
            .all(|(a, b)| a.abs_diff_eq(b, epsilon))
    }
}

impl<R: Real + PartialEq> RelativeEq for Frame<R>
where
    R::Scalar: RelativeEq<Epsilon = R::Scalar>,
{
    fn default_max_relative() -> R::Scalar {
        R::Scalar::default_max_relative()
    }
    fn relative_eq(&self, other: &Self, epsilon: R::Scalar, max_relative: R::Scalar) -> bool {
        self.axes()
            .iter()
            .zip(other.axes().iter())
            .all(|(a, b)| a.relative_eq(b, epsilon, max_relative))
    }
}

impl<R: Real + PartialEq> UlpsEq for Frame<R>
where
    R::Scalar: UlpsEq<Epsilon = R::Scalar>,
{
    fn default_max_ulps() -> u32 {
        R::Scalar::default_max_ulps()
    }
    fn ulps_eq(&self, other: &Self, epsilon: R::Scalar, max_ulps: u32) -> bool {
        self.axes()
            .iter()
            .zip(other.axes().iter())
            .all(|(a, b)| a.ulps_eq(b, epsilon, max_ulps))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::f32x8;
    use approx::{abs_diff_eq, relative_eq, ulps_eq};

    #[test]
    fn vec3_compares_every_component_of_every_lane() {
        let a = Vec3::new(1.0_f32, 2.0, 3.0);
        let b = Vec3::new(1.0_f32, 2.0, f32::from_bits(3.0f32.to_bits() + 2)); // 2 ULP, 1.33 ε rel
        assert!(ulps_eq!(a, b, max_ulps = 2));
        assert!(!ulps_eq!(a, b, max_ulps = 1));
        assert!(relative_eq!(a, b, max_relative = 1.5 * f32::EPSILON));
        assert!(!relative_eq!(a, b, max_relative = f32::EPSILON));
        assert!(abs_diff_eq!(a, b, epsilon = 1e-6));
        // One lane of one component off: the whole comparison fails.
        let l = Vec3::new(f32x8::splat(1.0), f32x8::splat(2.0), f32x8::splat(3.0));
        let mut z = [3.0f32; 8];
        z[6] = 3.001;
        let m = Vec3::new(l.x, l.y, f32x8::from(z));
        assert!(ulps_eq!(l, l));
        assert!(!abs_diff_eq!(l, m, epsilon = 1e-4));
        assert!(abs_diff_eq!(l, m, epsilon = 2e-3));
        assert!(relative_eq!(F32Fma(1.0), F32Fma(1.0 + f32::EPSILON)));
    }
}
