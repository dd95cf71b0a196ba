//! The lane trait: one numeric vocabulary for `f32`, `f64` and SIMD lanes.
//!
//! Every formula in this crate is written once, generic over [`Real`], and runs unchanged on
//! a scalar (`f32`, `f64`: one lane, masks are `bool`) or on a SIMD register of lanes
//! ([`f32x4`], [`f32x8`], [`f32x16`], [`f64x4`] from the [`wide`] crate: masks are lane
//! vectors whose bits are all ones or all zeros). Control flow inside a formula is written
//! with [`Real::select`], never with `if` on a value, so a formula body is branch-free on
//! lanes (the style of Mitsuba 3's `dr::select` and wide's `select`).
//!
//! # Precision contract
//!
//! * `+ − × ÷ sqrt abs min max` are correctly rounded IEEE 754 operations on every
//!   implementation, so formulas built only from them agree bit for bit between a lane and
//!   the scalar of the same precision — except for [`Real::mul_add`], below.
//! * [`Real::mul_add`] fuses (one rounding) when the build enables hardware FMA
//!   (`target_feature = "fma"`) and is `a·b + c` (two roundings) otherwise, on scalars and
//!   lanes alike. The scalar never calls a software `fma`, which would be ~20× slower.
//! * Transcendentals (`exp`, `exp2`, `ln`, `log2`, `pow`, `sin`, `cos`) come from `std`/`libm`
//!   on scalars (≤ 1 ULP) and from `wide`'s polynomial kernels on lanes. They differ by a few
//!   ULP; `tests/simd_lanes.rs` states and checks the bound for every public formula.
//!
//! [`wide`]: https://docs.rs/wide

#![deny(unconditional_recursion)]

use core::fmt::Debug;
use core::ops::{
    Add, AddAssign, BitAnd, BitOr, Div, DivAssign, Mul, MulAssign, Neg, Not, Sub, SubAssign,
};

use crate::math::{f32m, f64m};
pub use wide::{f32x4, f32x8, f32x16, f64x4};

/// A number or a SIMD register of numbers on which every formula of the crate runs.
///
/// Implemented for `f32`, `f64`, [`f32x4`], [`f32x8`], [`f32x16`] and [`f64x4`]. The
/// arithmetic operators act lane-wise; comparisons return a [`Real::Mask`] that
/// [`Real::select`] consumes.
///
/// # Examples
///
/// One body, three types:
///
/// ```
/// use brdf::{Real, f32x8};
///
/// fn schlick_weight<R: Real>(cos_theta: R) -> R {
///     let m = (R::one() - cos_theta).max(R::zero());
///     let m2 = m * m;
///     m2 * m2 * m
/// }
///
/// assert_eq!(schlick_weight(0.5_f32), 0.03125);
/// assert_eq!(schlick_weight(0.5_f64), 0.03125);
/// assert_eq!(schlick_weight(f32x8::splat(0.5)), f32x8::splat(0.03125));
/// ```
pub trait Real:
    Copy
    + Debug
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
{
    /// The element type of one lane: `f32` or `f64`.
    type Scalar: Scalar;
    /// Result of a comparison: `bool` for scalars, an all-ones/all-zeros lane vector for SIMD.
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask> + Not<Output = Self::Mask>;
    /// Number of lanes (1 for scalars).
    const LANES: usize;

    /// Every lane set to `x`.
    fn splat(x: Self::Scalar) -> Self;
    /// Every lane set to the constant `x`, rounded to the lane precision. Formula bodies
    /// write their constants with it: `R::from_f64(0.5)`.
    fn from_f64(x: f64) -> Self;
    /// Lane `i` (panics if `i >= LANES`).
    fn lane(self, i: usize) -> Self::Scalar;
    /// Builds a value lane by lane.
    fn from_fn(f: impl FnMut(usize) -> Self::Scalar) -> Self;

    /// Square root (correctly rounded). Negative input gives NaN: use [`Real::safe_sqrt`]
    /// where rounding may push the argument below zero.
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// Lane-wise minimum.
    fn min(self, other: Self) -> Self;
    /// Lane-wise maximum.
    fn max(self, other: Self) -> Self;
    /// `self·a + b`, fused when the build has hardware FMA (see the module docs).
    fn mul_add(self, a: Self, b: Self) -> Self;
    /// `eˣ`.
    fn exp(self) -> Self;
    /// `2ˣ`.
    fn exp2(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// Base-2 logarithm.
    fn log2(self) -> Self;
    /// `selfʸ` for `self ≥ 0`; `0ʸ = 0` for `y > 0` and `x⁰ = 1`.
    fn pow(self, y: Self) -> Self;
    /// Sine (radians).
    fn sin(self) -> Self;
    /// Cosine (radians).
    fn cos(self) -> Self;
    /// Largest integer not greater than `self`.
    fn floor(self) -> Self;

    /// `self < other`, lane-wise.
    fn lt(self, other: Self) -> Self::Mask;
    /// `self ≤ other`, lane-wise.
    fn le(self, other: Self) -> Self::Mask;
    /// `self > other`, lane-wise.
    fn gt(self, other: Self) -> Self::Mask;
    /// `self ≥ other`, lane-wise.
    fn ge(self, other: Self) -> Self::Mask;
    /// `self == other`, lane-wise.
    fn eq(self, other: Self) -> Self::Mask;
    /// Lanes that are neither infinite nor NaN.
    fn is_finite(self) -> Self::Mask;
    /// Per lane: `if_true` where `mask` is set, `if_false` elsewhere. Both are evaluated.
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self;
    /// Whether any lane of `mask` is set.
    fn any(mask: Self::Mask) -> bool;
    /// Whether every lane of `mask` is set.
    fn all(mask: Self::Mask) -> bool;

    /// `0` in every lane.
    #[inline(always)]
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
    /// `1` in every lane.
    #[inline(always)]
    fn one() -> Self {
        Self::from_f64(1.0)
    }
    /// `self²`.
    #[inline(always)]
    fn sqr(self) -> Self {
        self * self
    }
    /// `1 / self`, correctly rounded (not an approximate reciprocal instruction).
    #[inline(always)]
    fn recip(self) -> Self {
        Self::one() / self
    }
    /// `√max(self, 0)`: the square root of a quantity that is mathematically ≥ 0 but may
    /// round to a tiny negative number.
    #[inline(always)]
    fn safe_sqrt(self) -> Self {
        self.max(Self::zero()).sqrt()
    }
    /// `min(max(self, lo), hi)`.
    #[inline(always)]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        self.max(lo).min(hi)
    }
    /// Clamps to `[0, 1]`: the domain of a cosine used as a weight.
    #[inline(always)]
    fn saturate(self) -> Self {
        self.clamp(Self::zero(), Self::one())
    }
    /// `π` in every lane.
    #[inline(always)]
    fn pi() -> Self {
        Self::from_f64(core::f64::consts::PI)
    }
    /// `1/π` in every lane.
    #[inline(always)]
    fn frac_1_pi() -> Self {
        Self::from_f64(core::f64::consts::FRAC_1_PI)
    }
}

/// A one-lane [`Real`]: `f32` or `f64`. Adds what tests and validation need.
pub trait Scalar: Real<Scalar = Self, Mask = bool> + PartialOrd + Into<f64> + Default {
    /// Machine epsilon of the type.
    const EPSILON: Self;
    /// Converts from `f64`, rounding to nearest.
    fn of(x: f64) -> Self;
}

macro_rules! impl_scalar {
    ($t:ty, $m:ident) => {
        impl Real for $t {
            type Scalar = $t;
            type Mask = bool;
            const LANES: usize = 1;

            #[inline(always)]
            fn splat(x: $t) -> Self {
                x
            }
            #[inline(always)]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline(always)]
            fn lane(self, i: usize) -> $t {
                assert!(i == 0, "lane index out of range");
                self
            }
            #[inline(always)]
            fn from_fn(mut f: impl FnMut(usize) -> $t) -> Self {
                f(0)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                $m::sqrt(self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                <$t>::min(self, other)
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                <$t>::max(self, other)
            }
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                #[cfg(target_feature = "fma")]
                {
                    $m::fma(self, a, b)
                }
                #[cfg(not(target_feature = "fma"))]
                {
                    self * a + b
                }
            }
            #[inline(always)]
            fn exp(self) -> Self {
                $m::exp(self)
            }
            #[inline(always)]
            fn exp2(self) -> Self {
                $m::exp2(self)
            }
            #[inline(always)]
            fn ln(self) -> Self {
                $m::ln(self)
            }
            #[inline(always)]
            fn log2(self) -> Self {
                $m::log2(self)
            }
            #[inline(always)]
            fn pow(self, y: Self) -> Self {
                $m::pow(self, y)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                $m::sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                $m::cos(self)
            }
            #[inline(always)]
            fn floor(self) -> Self {
                $m::floor(self)
            }
            #[inline(always)]
            fn lt(self, other: Self) -> bool {
                self < other
            }
            #[inline(always)]
            fn le(self, other: Self) -> bool {
                self <= other
            }
            #[inline(always)]
            fn gt(self, other: Self) -> bool {
                self > other
            }
            #[inline(always)]
            fn ge(self, other: Self) -> bool {
                self >= other
            }
            #[inline(always)]
            fn eq(self, other: Self) -> bool {
                self == other
            }
            #[inline(always)]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            #[inline(always)]
            fn select(mask: bool, if_true: Self, if_false: Self) -> Self {
                if mask { if_true } else { if_false }
            }
            #[inline(always)]
            fn any(mask: bool) -> bool {
                mask
            }
            #[inline(always)]
            fn all(mask: bool) -> bool {
                mask
            }
        }

        impl Scalar for $t {
            const EPSILON: Self = <$t>::EPSILON;
            #[inline(always)]
            fn of(x: f64) -> Self {
                x as $t
            }
        }
    };
}

impl_scalar!(f32, f32m);
impl_scalar!(f64, f64m);

macro_rules! impl_lanes {
    ($v:ty, $t:ty, $n:expr, $pow:ident) => {
        impl Real for $v {
            type Scalar = $t;
            type Mask = $v;
            const LANES: usize = $n;

            #[inline(always)]
            fn splat(x: $t) -> Self {
                <$v>::splat(x)
            }
            #[inline(always)]
            fn from_f64(x: f64) -> Self {
                <$v>::splat(x as $t)
            }
            #[inline(always)]
            fn lane(self, i: usize) -> $t {
                self.to_array()[i]
            }
            #[inline(always)]
            fn from_fn(f: impl FnMut(usize) -> $t) -> Self {
                <$v>::new(core::array::from_fn(f))
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$v>::sqrt(self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$v>::abs(self)
            }
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                <$v>::min(self, other)
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                <$v>::max(self, other)
            }
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                <$v>::mul_add(self, a, b)
            }
            #[inline(always)]
            fn exp(self) -> Self {
                <$v>::exp(self)
            }
            #[inline(always)]
            fn exp2(self) -> Self {
                <$v>::exp2(self)
            }
            #[inline(always)]
            fn ln(self) -> Self {
                <$v>::ln(self)
            }
            #[inline(always)]
            fn log2(self) -> Self {
                <$v>::log2(self)
            }
            #[inline(always)]
            fn pow(self, y: Self) -> Self {
                <$v>::$pow(self, y)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                <$v>::sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                <$v>::cos(self)
            }
            #[inline(always)]
            fn floor(self) -> Self {
                <$v>::floor(self)
            }
            #[inline(always)]
            fn lt(self, other: Self) -> Self {
                self.simd_lt(other)
            }
            #[inline(always)]
            fn le(self, other: Self) -> Self {
                self.simd_le(other)
            }
            #[inline(always)]
            fn gt(self, other: Self) -> Self {
                self.simd_gt(other)
            }
            #[inline(always)]
            fn ge(self, other: Self) -> Self {
                self.simd_ge(other)
            }
            #[inline(always)]
            fn eq(self, other: Self) -> Self {
                self.simd_eq(other)
            }
            #[inline(always)]
            fn is_finite(self) -> Self {
                <$v>::is_finite(self)
            }
            #[inline(always)]
            fn select(mask: Self, if_true: Self, if_false: Self) -> Self {
                wide::Select::select(mask, if_true, if_false)
            }
            #[inline(always)]
            fn any(mask: Self) -> bool {
                mask.any()
            }
            #[inline(always)]
            fn all(mask: Self) -> bool {
                mask.all()
            }
        }
    };
}

impl_lanes!(f32x4, f32, 4, powf_simd);
impl_lanes!(f32x8, f32, 8, powf_simd);
impl_lanes!(f32x16, f32, 16, powf_simd);
impl_lanes!(f64x4, f64, 4, powf_simd);

#[cfg(test)]
mod tests {
    use super::*;

    fn body<R: Real>(x: R) -> R {
        let m = x.lt(R::zero());
        R::select(m, -x, x.sqrt().mul_add(R::from_f64(2.0), R::one()))
    }

    #[test]
    fn scalar_and_lanes_agree_on_a_select_body() {
        let xs = [-4.0f32, 0.0, 1.0, 4.0, 9.0, -0.5, 16.0, 2.25];
        let v = body(f32x8::new(xs));
        for (i, &x) in xs.iter().enumerate() {
            assert_eq!(v.lane(i), body(x), "lane {i}");
        }
        assert_eq!(body(-3.0f64), 3.0);
    }

    #[test]
    fn pow_of_zero_base_is_zero_and_zero_exponent_is_one() {
        for p in [0.5f32, 1.0, 100.0, 1e4] {
            assert_eq!(0.0f32.pow(p), 0.0);
            assert_eq!(f32x8::splat(0.0).pow(f32x8::splat(p)).lane(3), 0.0);
            assert_eq!(f64x4::splat(0.0).pow(f64x4::splat(p as f64)).lane(1), 0.0);
        }
        assert_eq!(f32x4::splat(0.0).pow(f32x4::splat(0.0)).lane(0), 1.0);
    }
}
