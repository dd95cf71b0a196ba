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
//!   lanes alike. The scalar never calls a software `fma`, which would be ~20× slower. The
//!   exception is [`F32Fma`], an `f32` whose `mul_add` always fuses, for code compiled with
//!   FMA at run time (the [`crate::batch`] kernels).
//! * Transcendentals (`exp`, `exp2`, `ln`, `log2`, `pow`, `sin`, `cos`) come from `std`/`libm`
//!   on scalars (≤ 1 ULP) and from `wide`'s polynomial kernels on lanes. They differ by a few
//!   ULP. The lane-against-scalar tests state and check the bound per formula: the
//!   `lanes_*` / `simd_lanes_match_scalar` tests of `tests/core.rs`, `tests/fresnel.rs`,
//!   `tests/ndf.rs`, `tests/masking.rs`, `tests/normalization.rs`, `tests/fast.rs` and
//!   `tests/models.rs` (0–2 ULP for formulas of `+ − × ÷ √` and `mul_add` only; larger,
//!   stated bounds where a `pow` with a large exponent amplifies the kernels' difference).
//!
//! # Two traits
//!
//! * [`Real`] is the vocabulary of formula bodies: arithmetic, `sqrt`, `mul_add`, the
//!   transcendentals, comparisons to a [`Real::Mask`], [`Real::select`], constants
//!   (`from_f64`, `zero`, `one`, `pi`) and the lane plumbing (`splat`, `lane`, `from_fn`,
//!   `any`, `all`). Writing a formula needs nothing else.
//! * [`Bits`] holds the crate-internal bit tricks that only the polynomial kernels of
//!   [`crate::fast`] use: [`Bits::exponent_split`], [`Bits::ldexp`] and
//!   [`Bits::rsqrt_estimate`]. It is a supertrait of [`Real`] (so `fast`'s generic bodies can
//!   call it on any `R: Real`) and sealed: implemented for the seven lane types above, not
//!   implementable outside the crate — which seals [`Real`] too.
//!
//! [`Splat`] moves a material built on a scalar to any of these types.
//!
//! [`wide`]: https://docs.rs/wide

#![deny(unconditional_recursion)]

use core::fmt::Debug;
use core::ops::{
    Add, AddAssign, BitAnd, BitOr, Div, DivAssign, Mul, MulAssign, Neg, Not, Sub, SubAssign,
};

use crate::math::{f32m, f64m};
use wide::bytemuck::cast;
pub use wide::{f32x4, f32x8, f32x16, f64x4};
use wide::{u32x4, u32x8, u32x16, u64x4};

#[cfg(all(feature = "std", target_arch = "x86_64"))]
pub(crate) mod lanes;

/// A number or a SIMD register of numbers on which every formula of the crate runs.
///
/// Implemented for `f32`, `f64`, [`F32Fma`], [`F32FmaSharedDiv`], [`f32x4`], [`f32x8`],
/// [`f32x16`] and [`f64x4`], and sealed through its supertrait [`Bits`] (the bit tricks of
/// [`crate::fast`], kept out of this list). The arithmetic operators act lane-wise; comparisons return a [`Real::Mask`]
/// that [`Real::select`] consumes.
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
    + Bits
{
    /// The element type of one lane: `f32` or `f64`.
    type Scalar: Scalar;
    /// Result of a comparison: `bool` for scalars, an all-ones/all-zeros lane vector for SIMD.
    type Mask: Copy
        + BitAnd<Output = Self::Mask>
        + BitOr<Output = Self::Mask>
        + Not<Output = Self::Mask>;
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
    /// Lane-wise minimum: `if self < other { self } else { other }` — one `minss`/`minps`
    /// instruction on x86. If either operand is NaN the result is `other` (so
    /// `x.min(c)` with a constant `c` maps a NaN `x` to `c`), unlike `f32::min`.
    fn min(self, other: Self) -> Self;
    /// Lane-wise maximum: `if self > other { self } else { other }` — one `maxss`/`maxps`
    /// instruction on x86. If either operand is NaN the result is `other` (so
    /// `x.max(0)` maps a NaN `x` to 0), unlike `f32::max`.
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

/// The bit-level building blocks of [`crate::fast`]: reading and writing the exponent field
/// and the integer-view estimate of `1/√x`.
///
/// These are implementation tricks, not formula vocabulary, so they live apart from
/// [`Real`] (which has them as a supertrait, so `fast`'s generic bodies can call them on any
/// `R: Real`). The trait is sealed: it is implemented for every lane type of the crate
/// (`f32`, `f64`, [`F32Fma`], [`F32FmaSharedDiv`], [`f32x4`], [`f32x8`], [`f32x16`],
/// [`f64x4`]) and cannot be implemented elsewhere, which also seals [`Real`]. Each body reads the IEEE 754 fields of
/// its precision, named once in the private `binary32` / `binary64` layouts of this module.
pub trait Bits: Sized + sealed::Sealed {
    /// Splits a finite nonzero number into mantissa and exponent: `|self| = m·2ᵉ` with
    /// `m ∈ [1, 2)` and `e` an integer-valued float, read from the bits (no library call,
    /// branch-free). The sign is ignored.
    ///
    /// ```text
    /// exponent_split(x) = (m, e),   |x| = m · 2ᵉ,   1 ≤ m < 2,   e = ⌊log₂|x|⌋
    /// ```
    ///
    /// Exact for normal numbers (`e ∈ [−126, 127]` for `f32`, `[−1022, 1023]` for `f64`).
    /// Outside that domain it returns the raw fields: `0` and subnormals give
    /// `e = −127` / `−1023` (and `m` built from the subnormal fraction bits), `∞` and NaN give
    /// `e = 128` / `1024`. The building block of range reduction for logarithms (J.-M. Muller,
    /// *Elementary Functions: Algorithms and Implementation*, 3rd ed., Birkhäuser 2016, §11).
    fn exponent_split(self) -> (Self, Self);
    /// `self · 2ᵉ` for an integer-valued `e`, by building `2ᵉ` in the exponent field (the
    /// inverse of [`Bits::exponent_split`]; no library call, branch-free).
    ///
    /// ```text
    /// ldexp(x, e) = x · 2ᵉ      (one correctly rounded multiplication)
    /// ```
    ///
    /// Domain: `e` integer-valued in `[−127, 128]` (`f32`) or `[−1023, 1024]` (`f64`). Inside
    /// the normal range `2ᵉ` is exact; the end points encode `2ᵉ` as `0` (so the result is
    /// `x·0 = 0`: flush to zero) and `+∞` (the result overflows to `±∞`; NaN if `x = 0`).
    /// Other `e` (non-integer or outside the range) give unspecified finite or infinite values.
    fn ldexp(self, e: Self) -> Self;
    /// A cheap estimate `y ≈ 1/√self` for positive normal `self`, to be refined by Newton
    /// steps (see `brdf::fast::rsqrt`).
    ///
    /// * `f32`, `f64`, [`f64x4`]: the bit trick `y = bits⁻¹(R − bits(x)/2)` (the integer
    ///   view of a float is a scaled, shifted `log₂ x`), with the magic constant
    ///   `R = 0x5F37_5A80` (`f32`) / `0x5FE6_EB50_0000_0000` (`f64`, the same constant for the
    ///   wider fields) found by a search minimising the error after one Newton step
    ///   (`tests/fast.rs` repeats it). Relative error ≤ 3.43·10⁻² (C. Lomont, "Fast inverse
    ///   square root", tech. report, Purdue 2003, derived 0x5F375A86 the same way).
    ///   Bit-identical between `f64` and `f64x4` lanes.
    /// * [`f32x4`], [`f32x8`], [`f32x16`]: `wide`'s `recip_sqrt`, i.e. the hardware estimate
    ///   `rsqrtps` on x86 with SSE/AVX (relative error ≤ 1.5·2⁻¹² ≈ 3.7·10⁻⁴ by Intel's
    ///   specification; the exact bits differ between CPU vendors), and the exact `1/√x` where
    ///   `wide` has no estimate instruction (`f32x16` under AVX-512, NEON, WASM, portable
    ///   fallback). Either way the error is ≤ 3.7·10⁻⁴, so lanes and the `f32` scalar differ.
    ///
    /// `wide`'s `f64x4::recip_sqrt` is an exact division `1/√x` (there is no double-precision
    /// estimate instruction before AVX-512's `rsqrt14`), which is why [`f64x4`] uses the bit
    /// trick here. Outside the domain (`0`, subnormals, negatives, `∞`, NaN) the value is
    /// unspecified.
    fn rsqrt_estimate(self) -> Self;

    /// `(√x, 1/√x)` for positive normal `x`, the square root of
    /// [`crate::fast::HardwareEstimate`]: on the batch path's explicit AVX-512 lanes the
    /// hardware estimate `vrsqrt14ps` (relative error ≤ 2⁻¹⁴) refined by one Newton step,
    ///
    /// ```text
    /// y = rsqrt14(max(x, MIN_POSITIVE)),  s = x·y,  r = x − s² (one FMA),
    /// √x ≈ s + r·y/2,  1/√x ≈ y + (y/2)(1 − s·y)
    /// ```
    ///
    /// (error `O(2⁻²⁸)` before the last roundings: a few ULP, bounded in `tests/batch.rs`).
    /// `x = 0` gives `√x = 0` and a large finite `1/√x`, as [`crate::fast::rsqrt`];
    /// subnormal `x`, `∞` and NaN are outside the domain (inaccurate, NaN and NaN). On every other type, which has no
    /// vectorizable estimate instruction, the correctly rounded `(√x, 1/√x)`.
    fn sqrt_rsqrt_refined(self) -> (Self, Self);

    /// `self / d`, the division of [`crate::fast::HardwareEstimate`]: on the batch path's
    /// explicit AVX-512 lanes the hardware estimate `r = rcp14(d)` (relative error ≤ 2⁻¹⁴)
    /// and one correction (P. Markstein, "IA-64 and Elementary Functions", Prentice Hall
    /// 2000, §8),
    ///
    /// ```text
    /// q = n·r,   n/d ≈ q + (n − q·d)·r      (the remainder by one FMA)
    /// ```
    ///
    /// for normal finite nonzero `d` and a normal quotient (`d = 0` or `∞` give NaN there);
    /// within a few ULP of `n/d`, bounded in `tests/batch.rs`. On every other type, the
    /// correctly rounded `n / d`.
    fn div_refined(self, d: Self) -> Self;

    /// `table[i]` lane by lane, for an integer-valued `self = i ∈ [0, 31]`: the coefficient
    /// lookup of piecewise polynomials ([`crate::fresnel::FittedConductor`]), one table entry
    /// per segment. On the batch path's explicit lanes it is a register permute (AVX-512
    /// `vpermt2ps` over the two halves of the table; AVX2 four `vpermps` and three blends);
    /// elsewhere an indexed load per lane, widened to the lane precision.
    ///
    /// Outside the domain (non-integer, negative, `≥ 32`, NaN) the result is some entry of
    /// the table, never out of bounds: on the batch path's explicit lanes the low five bits
    /// of the truncated index pick it (NaN gives entry 0, −1 entry 31); on scalars and the
    /// `wide` lane types the index saturates to `[0, 31]` (NaN gives entry 0).
    fn lookup32(self, table: &[f32; 32]) -> Self;

    /// Whether formulas that divide once per channel should share one division (computing
    /// the reciprocal of the product of the denominators, and each quotient from it with a
    /// few multiplications). `true` only for [`F32FmaSharedDiv`], the batch kernels' number
    /// type on cores whose divider is their bottleneck, and for its explicit-lane
    /// counterparts (crate-private); a formula reads it at compile time.
    const SHARE_DIVISIONS: bool = false;
}

mod sealed {
    /// The lane types of the crate: [`super::Bits`] (hence [`super::Real`]) is implemented
    /// for these only.
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
    impl Sealed for super::F32Fma {}
    impl Sealed for super::F32FmaSharedDiv {}
    impl Sealed for super::f32x4 {}
    impl Sealed for super::f32x8 {}
    impl Sealed for super::f32x16 {}
    impl Sealed for super::f64x4 {}
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    impl<B: super::lanes::Backend> Sealed for super::lanes::Lanes<B> {}
}

/// The IEEE 754 binary32 fields the [`Bits`] of `f32` and its lanes read and write.
mod binary32 {
    /// Stored fraction bits (the exponent field starts above them).
    pub(super) const MANTISSA_BITS: u32 = 23;
    /// The exponent field, shifted down.
    pub(super) const EXPONENT_MASK: u32 = 0xFF;
    /// The fraction field.
    pub(super) const FRACTION_MASK: u32 = 0x007F_FFFF;
    /// The bits of `1.0`: OR-ed onto a fraction, they give a mantissa in `[1, 2)`.
    pub(super) const ONE_BITS: u32 = 0x3F80_0000;
    /// The bits of `2²³`: OR-ed onto a small integer `n`, they give the float `2²³ + n`.
    pub(super) const TWO_POW_MANTISSA_BITS: u32 = 0x4B00_0000;
    /// `2²³ + 127` (the exponent bias): `(2²³ + biased) − this` is the unbiased exponent,
    /// and `e + this` puts the biased exponent of `e` in the low fraction bits.
    pub(super) const EXPONENT_OFFSET: f32 = 8_388_735.0;
    /// The magic constant of the `1/√x` estimate (see [`super::Bits::rsqrt_estimate`]).
    pub(super) const RSQRT_MAGIC: u32 = 0x5F37_5A80;
}

/// The IEEE 754 binary64 fields the [`Bits`] of `f64` and its lanes read and write (as in
/// `binary32`).
mod binary64 {
    /// Stored fraction bits (the exponent field starts above them).
    pub(super) const MANTISSA_BITS: u32 = 52;
    /// The exponent field, shifted down.
    pub(super) const EXPONENT_MASK: u64 = 0x7FF;
    /// The fraction field.
    pub(super) const FRACTION_MASK: u64 = 0x000F_FFFF_FFFF_FFFF;
    /// The bits of `1.0`.
    pub(super) const ONE_BITS: u64 = 0x3FF0_0000_0000_0000;
    /// The bits of `2⁵²`.
    pub(super) const TWO_POW_MANTISSA_BITS: u64 = 0x4330_0000_0000_0000;
    /// `2⁵² + 1023` (the exponent bias).
    pub(super) const EXPONENT_OFFSET: f64 = 4_503_599_627_371_519.0;
    /// The magic constant of the `1/√x` estimate (see [`super::Bits::rsqrt_estimate`]).
    pub(super) const RSQRT_MAGIC: u64 = 0x5FE6_EB50_0000_0000;
}

/// `[f(0), f(1), …, f(N−1)]` for per-channel values in hot paths.
///
/// Same result as `core::array::from_fn`, written as a plain loop so that it is always
/// inlined: inside the `#[target_feature]` batch kernels LLVM declines to inline `from_fn` and
/// `array::map`, which blocks vectorization of a whole BRDF (measured: 10× slower).
#[inline(always)]
pub(crate) fn channels<R: Real, const N: usize>(mut f: impl FnMut(usize) -> R) -> [R; N] {
    let mut out = [R::zero(); N];
    for (c, o) in out.iter_mut().enumerate() {
        *o = f(c);
    }
    out
}

/// A one-lane [`Real`]: `f32` or `f64`. Adds what tests and validation need.
pub trait Scalar: Real<Scalar = Self, Mask = bool> + PartialOrd + Into<f64> + Default {
    /// Machine epsilon of the type.
    const EPSILON: Self;
    /// Converts from `f64`, rounding to nearest.
    fn of(x: f64) -> Self;
}

/// `select`, `any` and `all` of a one-lane `Real` whose mask is `bool`.
macro_rules! bool_mask {
    () => {
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
    };
}

/// `Real`, `Bits` and `Scalar` of a primitive float: `impl_scalar!(f32 { math: f32m, layout:
/// binary32 })`, with `math` the private std/libm dispatch and `layout` the IEEE 754 fields.
macro_rules! impl_scalar {
    ($t:ty { math: $m:ident, layout: $l:ident $(,)? }) => {
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
                if self < other { self } else { other }
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                if self > other { self } else { other }
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
            bool_mask!();
        }

        impl Bits for $t {
            #[inline(always)]
            fn exponent_split(self) -> (Self, Self) {
                let b = self.to_bits();
                let biased = (b >> $l::MANTISSA_BITS) & $l::EXPONENT_MASK;
                let e = <$t>::from_bits($l::TWO_POW_MANTISSA_BITS | biased) - $l::EXPONENT_OFFSET;
                let m = <$t>::from_bits((b & $l::FRACTION_MASK) | $l::ONE_BITS);
                (m, e)
            }
            #[inline(always)]
            fn ldexp(self, e: Self) -> Self {
                self * <$t>::from_bits((e + $l::EXPONENT_OFFSET).to_bits() << $l::MANTISSA_BITS)
            }
            #[inline(always)]
            fn rsqrt_estimate(self) -> Self {
                <$t>::from_bits($l::RSQRT_MAGIC - (self.to_bits() >> 1))
            }
            #[inline(always)]
            fn sqrt_rsqrt_refined(self) -> (Self, Self) {
                let s = Real::sqrt(self);
                (s, 1.0 / s)
            }
            #[inline(always)]
            fn div_refined(self, d: Self) -> Self {
                self / d
            }
            #[inline(always)]
            fn lookup32(self, table: &[f32; 32]) -> Self {
                // `as` saturates (NaN gives 0): in bounds for every input.
                table[(self as usize).min(31)] as $t
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

impl_scalar!(f32 {
    math: f32m,
    layout: binary32,
});
impl_scalar!(f64 {
    math: f64m,
    layout: binary64,
});

/// `Real` and `Bits` of a `wide` lane type: `impl_lanes!(f32x8 { scalar: f32, lanes: 8, bits:
/// u32x8, layout: binary32, rsqrt_estimate: |x| … })`, with `bits` the unsigned lane type of the
/// same width (for the bit casts), `layout` the IEEE 754 fields of `scalar`, and
/// `rsqrt_estimate` the body of [`Bits::rsqrt_estimate`].
macro_rules! impl_lanes {
    ($v:ty {
        scalar: $t:ty,
        lanes: $n:expr,
        bits: $u:ty,
        layout: $l:ident,
        rsqrt_estimate: $rsqrt:expr $(,)?
    }) => {
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
                <$v>::fast_min(self, other)
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                <$v>::fast_max(self, other)
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
                <$v>::powf_simd(self, y)
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

        impl Bits for $v {
            #[inline(always)]
            fn exponent_split(self) -> (Self, Self) {
                let b: $u = cast(self);
                let biased =
                    b.unbounded_shr_scalar($l::MANTISSA_BITS) & <$u>::splat($l::EXPONENT_MASK);
                let two_pow_plus_biased =
                    cast::<$u, $v>(biased | <$u>::splat($l::TWO_POW_MANTISSA_BITS));
                let e = two_pow_plus_biased - <$v>::splat($l::EXPONENT_OFFSET);
                let fraction = b & <$u>::splat($l::FRACTION_MASK);
                let m = cast::<$u, $v>(fraction | <$u>::splat($l::ONE_BITS));
                (m, e)
            }
            #[inline(always)]
            fn ldexp(self, e: Self) -> Self {
                let b: $u = cast(e + <$v>::splat($l::EXPONENT_OFFSET));
                self * cast::<$u, $v>(b.unbounded_shl_scalar($l::MANTISSA_BITS))
            }
            #[inline(always)]
            fn rsqrt_estimate(self) -> Self {
                let f: fn($v) -> $v = $rsqrt;
                f(self)
            }
            #[inline(always)]
            fn sqrt_rsqrt_refined(self) -> (Self, Self) {
                let s = <$v>::sqrt(self);
                (s, <$v>::splat(1.0) / s)
            }
            #[inline(always)]
            fn div_refined(self, d: Self) -> Self {
                self / d
            }
            #[inline(always)]
            fn lookup32(self, table: &[f32; 32]) -> Self {
                let i = self.to_array();
                <$v>::from(core::array::from_fn::<$t, $n, _>(|j| {
                    table[(i[j] as usize).min(31)] as $t
                }))
            }
        }
    };
}

impl_lanes!(f32x4 {
    scalar: f32,
    lanes: 4,
    bits: u32x4,
    layout: binary32,
    rsqrt_estimate: |x| x.recip_sqrt(),
});
impl_lanes!(f32x8 {
    scalar: f32,
    lanes: 8,
    bits: u32x8,
    layout: binary32,
    rsqrt_estimate: |x| x.recip_sqrt(),
});
impl_lanes!(f32x16 {
    scalar: f32,
    lanes: 16,
    bits: u32x16,
    layout: binary32,
    rsqrt_estimate: |x| x.recip_sqrt(),
});
impl_lanes!(f64x4 {
    scalar: f64,
    lanes: 4,
    bits: u64x4,
    layout: binary64,
    // The f64 bit trick, lane-wise (wide's f64x4::recip_sqrt is an exact division).
    rsqrt_estimate: |x| {
        let b: u64x4 = cast(x);
        cast(u64x4::splat(binary64::RSQRT_MAGIC) - b.unbounded_shr_scalar(1))
    },
});

// ---------------------------------------------------------------------------------------------
// F32Fma: f32 with a multiply-add that always fuses
// ---------------------------------------------------------------------------------------------

/// An `f32` whose [`Real::mul_add`] always fuses (one rounding), whatever the build's target
/// features: the number type of the batch kernels compiled for AVX2+FMA and AVX-512
/// ([`crate::batch`]).
///
/// Every other operation is the `f32` one, bit for bit (`F32Fma` is `#[repr(transparent)]`
/// and its [`Real::Scalar`] is `f32`). What differs is `mul_add`: on `f32` it fuses only when
/// the crate is compiled with `target_feature = "fma"` (otherwise `a·b + c`, two roundings,
/// because a software `fma` would be ~20× slower), while on `F32Fma` it is always the
/// correctly rounded `fma(a, b, c)`. Inside a function compiled with FMA enabled — the
/// run-time dispatched batch kernels — that is one `vfmadd` instruction, and LLVM vectorizes
/// it with the rest of the body; elsewhere it is a call to the math library's `fmaf`:
/// correct, but slow, so do not use `F32Fma` for scalar work outside such kernels.
///
/// A model built on `f32` becomes a model on `F32Fma` with [`Splat::splat`] (exact: the
/// constants keep their bits). Since a correctly rounded `fma` is the same number in
/// software and in hardware, `eval` on the `F32Fma` model equals the FMA batch kernels bit
/// for bit on any machine (the batch tests rely on it), and differs from `eval` on `f32` by
/// the rounding of the unfused products only.
///
/// # Examples
///
/// ```
/// use brdf::Real;
/// use brdf::real::F32Fma;
/// // 1 + 2⁻²³ squared is 1 + 2⁻²² + 2⁻⁴⁶: fused, the 2⁻⁴⁶ survives the subtraction.
/// let x = 1.0 + f32::EPSILON;
/// let fused = F32Fma(x).mul_add(F32Fma(x), F32Fma(-(1.0 + 2.0 * f32::EPSILON)));
/// assert_eq!(fused.0, 2.0f32.powi(-46));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
#[repr(transparent)]
pub struct F32Fma(pub f32);

/// `Real` and `Bits` of a one-lane `f32` wrapper whose `mul_add` always fuses:
/// `fused_f32!(F32Fma, share_divisions: false)`. [`F32Fma`] and [`F32FmaSharedDiv`] are the
/// same number (every operation the `f32` one, `mul_add` the correctly rounded `fma`); they
/// differ only in [`Bits::SHARE_DIVISIONS`], which selects a formula's arrangement.
macro_rules! fused_f32 {
    ($t:ident, share_divisions: $share:expr) => {
        fused_f32!(@ops $t;
            Add add AddAssign add_assign +,
            Sub sub SubAssign sub_assign -,
            Mul mul MulAssign mul_assign *,
            Div div DivAssign div_assign /
        );

        impl Neg for $t {
            type Output = $t;
            #[inline(always)]
            fn neg(self) -> $t {
                $t(-self.0)
            }
        }

        impl Real for $t {
            type Scalar = f32;
            type Mask = bool;
            const LANES: usize = 1;

            #[inline(always)]
            fn splat(x: f32) -> Self {
                $t(x)
            }
            #[inline(always)]
            fn from_f64(x: f64) -> Self {
                $t(x as f32)
            }
            #[inline(always)]
            fn lane(self, i: usize) -> f32 {
                assert!(i == 0, "lane index out of range");
                self.0
            }
            #[inline(always)]
            fn from_fn(mut f: impl FnMut(usize) -> f32) -> Self {
                $t(f(0))
            }
            fused_f32!(@via_f32 $t; sqrt, abs, exp, exp2, ln, log2, sin, cos, floor);
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                $t(<f32 as Real>::min(self.0, other.0))
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                $t(<f32 as Real>::max(self.0, other.0))
            }
            /// `fma(self, a, b)`, one rounding, on every build (see [`F32Fma`]).
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                $t(f32m::fma(self.0, a.0, b.0))
            }
            #[inline(always)]
            fn pow(self, y: Self) -> Self {
                $t(<f32 as Real>::pow(self.0, y.0))
            }
            fused_f32!(@cmp_via_f32; lt, le, gt, ge, eq);
            #[inline(always)]
            fn is_finite(self) -> bool {
                self.0.is_finite()
            }
            bool_mask!();
        }

        impl Bits for $t {
            const SHARE_DIVISIONS: bool = $share;
            #[inline(always)]
            fn exponent_split(self) -> (Self, Self) {
                let (m, e) = <f32 as Bits>::exponent_split(self.0);
                ($t(m), $t(e))
            }
            #[inline(always)]
            fn ldexp(self, e: Self) -> Self {
                $t(<f32 as Bits>::ldexp(self.0, e.0))
            }
            #[inline(always)]
            fn rsqrt_estimate(self) -> Self {
                $t(<f32 as Bits>::rsqrt_estimate(self.0))
            }
            #[inline(always)]
            fn sqrt_rsqrt_refined(self) -> (Self, Self) {
                let (s, y) = <f32 as Bits>::sqrt_rsqrt_refined(self.0);
                ($t(s), $t(y))
            }
            #[inline(always)]
            fn div_refined(self, d: Self) -> Self {
                $t(self.0 / d.0)
            }
            #[inline(always)]
            fn lookup32(self, table: &[f32; 32]) -> Self {
                $t(<f32 as Bits>::lookup32(self.0, table))
            }
        }
    };
    (@ops $t:ident; $($tr:ident $m:ident $atr:ident $am:ident $op:tt),*) => {
        $(
            impl $tr for $t {
                type Output = $t;
                #[inline(always)]
                fn $m(self, o: $t) -> $t {
                    $t(self.0 $op o.0)
                }
            }
            impl $atr for $t {
                #[inline(always)]
                fn $am(&mut self, o: $t) {
                    self.0 = self.0 $op o.0;
                }
            }
        )*
    };
    (@via_f32 $t:ident; $($m:ident),*) => {
        $(
            #[inline(always)]
            fn $m(self) -> Self {
                $t(<f32 as Real>::$m(self.0))
            }
        )*
    };
    (@cmp_via_f32; $($m:ident),*) => {
        $(
            #[inline(always)]
            fn $m(self, other: Self) -> bool {
                <f32 as Real>::$m(self.0, other.0)
            }
        )*
    };
}

fused_f32!(F32Fma, share_divisions: false);

/// [`F32Fma`] for cores whose divider bounds the batch kernels: the same number, bit for bit
/// in every operation, but formulas that divide once per channel share one division instead
/// ([`Bits::SHARE_DIVISIONS`]; today the exact conductor Fresnel term,
/// [`crate::fresnel::Conductor`], for metals with `k ≥ 0.1` in every channel).
///
/// The [`crate::batch`] FMA kernels run a model on this type instead of [`F32Fma`] where
/// [`crate::batch::shares_divisions`] says so (Intel CPUs): `eval` on
/// `model.splat::<F32FmaSharedDiv>()` reproduces them bit for bit there, as `eval` on the
/// [`F32Fma`] form does elsewhere. The two forms differ by a few ULP (bounded in
/// `tests/fresnel.rs`).
///
/// Why a type: the choice is made where the batch path dispatches, at run time, without
/// changing the model's type; the formula reads the flag of its number type at compile
/// time, so each kernel has one arrangement and no branch.
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
#[repr(transparent)]
pub struct F32FmaSharedDiv(pub f32);

fused_f32!(F32FmaSharedDiv, share_divisions: true);

// ---------------------------------------------------------------------------------------------
// Splat: a material on another number type
// ---------------------------------------------------------------------------------------------

/// A material (model, NDF, Fresnel or masking term) built on a scalar, re-expressed on
/// another [`Real`]: the same parameters, with every per-material constant converted to the
/// new type.
///
/// Constructors validate their parameters once, on scalars; `splat` then gives the same
/// material on SIMD lanes (`f32` → [`f32x8`]: each constant broadcast to every lane) or on
/// [`F32Fma`] (what the batch kernels use), without validating or deriving anything again.
/// Constants go through `f64` and are rounded to the target precision, so `f32` → `f32x8`,
/// `f32` → `F32Fma` and `f64` → [`f64x4`] keep every bit, and `f64` → `f32` rounds once.
///
/// Every model and term of this crate implements it; [`crate::batch`] needs it. A model of
/// your own that is generic over `R: Real` implements it by converting its fields:
///
/// ```
/// use brdf::{Brdf, Real, Scalar, Vec3, real::Splat, models::{Properties, Reciprocity, Energy}};
///
/// /// A constant BRDF `ρ/π`.
/// struct Flat<R> { rho_over_pi: R }
///
/// impl<R: Real> Brdf<R, 1> for Flat<R> {
///     fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; 1] {
///         let up = wi.z.gt(R::zero()) & wo.z.gt(R::zero());
///         [R::select(up, self.rho_over_pi, R::zero())]
///     }
///     fn properties(&self) -> Properties {
///         Properties { reciprocity: Reciprocity::Reciprocal, energy: Energy::Conserving }
///     }
/// }
///
/// impl<S: Scalar> Splat for Flat<S> {
///     type On<L: Real> = Flat<L>;
///     fn splat<L: Real>(&self) -> Flat<L> {
///         Flat { rho_over_pi: L::from_f64(self.rho_over_pi.into()) }
///     }
/// }
///
/// let wide = Flat { rho_over_pi: 0.25f32 }.splat::<brdf::f32x8>();
/// let up = Vec3::new(brdf::f32x8::splat(0.0), brdf::f32x8::splat(0.0), brdf::f32x8::splat(1.0));
/// assert_eq!(wide.eval(up, up)[0], brdf::f32x8::splat(0.25));
/// ```
pub trait Splat {
    /// The same type with its number type replaced by `L`.
    type On<L: Real>;
    /// The same material on `L`.
    fn splat<L: Real>(&self) -> Self::On<L>;

    /// Whether [`crate::batch`] may run the material on explicit registers of lanes (16 on
    /// [`crate::batch::Isa::Avx512`], 8 on [`crate::batch::Isa::Avx2Fma`]) instead of the
    /// one-lane [`F32Fma`] loop that LLVM vectorizes: `true` for a model that takes a square
    /// root or division through [`crate::fast::HardwareEstimate`] (the estimate instructions
    /// are used on AVX-512), and for the run-time parts [`crate::ndf::AnyNdf`],
    /// [`crate::fresnel::AnyFresnel`] and [`crate::masking::AnyMasking`] (a `match` per pair
    /// keeps LLVM from vectorizing the one-lane loop; on lanes it is one branch per
    /// register). `false` by default; a composed model reports its parts'
    /// (`a || b`), and a wrapper of your own forwards its model's
    /// (`const EXPLICIT_LANES: bool = B::EXPLICIT_LANES;`), or the batch path runs it on the
    /// one-lane loop (exact operations instead of the estimates).
    const EXPLICIT_LANES: bool = false;
}

/// `x` on `L` (through `f64`: exact for `f32` and `f64` sources on a type of at least the
/// source's precision).
#[inline]
pub(crate) fn splat_scalar<S: Scalar, L: Real>(x: S) -> L {
    L::from_f64(x.into())
}

/// Every element of `x` on `L`.
#[inline]
pub(crate) fn splat_array<S: Scalar, L: Real, const N: usize>(x: &[S; N]) -> [L; N] {
    core::array::from_fn(|i| splat_scalar(x[i]))
}

/// Implements [`Splat`] for unit structs (masking terms, policy types) that hold no number:
/// they are their own image on every type.
macro_rules! splat_as_itself {
    ($($t:ty),* $(,)?) => {
        $(
            impl $crate::real::Splat for $t {
                type On<L: $crate::Real> = $t;
                #[inline]
                fn splat<L: $crate::Real>(&self) -> $t {
                    *self
                }
            }
        )*
    };
}
pub(crate) use splat_as_itself;

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
    fn min_max_return_other_on_nan_on_every_type() {
        assert_eq!(Real::max(f32::NAN, 0.0f32), 0.0);
        assert_eq!(Real::max(f64::NAN, 1.0f64), 1.0);
        assert_eq!(Real::min(f32::NAN, 1.0f32), 1.0);
        assert_eq!(
            Real::max(f32x8::splat(f32::NAN), f32x8::splat(0.0)).lane(3),
            0.0
        );
        assert_eq!(
            Real::min(f64x4::splat(f64::NAN), f64x4::splat(2.0)).lane(1),
            2.0
        );
        assert_eq!(
            Real::max(f32x16::splat(-1.0), f32x16::splat(3.0)).lane(9),
            3.0
        );
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
