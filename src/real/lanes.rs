//! Explicit SIMD lanes: `Lanes<Avx512>` (16 `f32` in a `__m512`, alias [`Zmm`]) and
//! `Lanes<Avx2>` (8 in a `__m256`, alias [`Ymm`]), the number types of the batch path's
//! explicit kernels ([`crate::batch`]) for models with [`super::Splat::EXPLICIT_LANES`].
//!
//! Why types of their own: the other batch kernels run a one-lane model ([`super::F32Fma`])
//! that LLVM vectorizes across loop iterations. That fails for two kinds of model: one that
//! wants the estimate instructions (`vrsqrt14ps`, `vrcp14ps`: LLVM does not vectorize their
//! scalar forms), and a run-time [`crate::material::Material`], whose per-pair `match`
//! keeps the loop scalar. On registers of lanes the first gets its instructions and the
//! second pays one branch per 8 or 16 pairs.
//!
//! Every operation is the correctly rounded instruction (`vaddps` … `vsqrtps`, `vfmadd`)
//! and the transcendentals are the `f32` ones lane by lane, so a formula gives on these
//! types the bits of [`super::F32Fma`] in every lane (tested below; on the sharing backends
//! [`ZmmShared`], [`YmmShared`], those of [`super::F32FmaSharedDiv`]) — except
//! [`super::Bits::sqrt_rsqrt_refined`] and [`super::Bits::div_refined`], which are the
//! hardware estimates with one refinement step on [`Zmm`] (exact on [`Ymm`]: AVX2's 12-bit
//! estimates would need two steps, no cheaper than its exact instructions).
//!
//! One body, two backends: [`Lanes`] implements [`Real`] and [`Bits`] once over a
//! [`Backend`], which names the instructions of its width.
//!
//! Crate-private and unsafe to construct: the operations are AVX-512F or AVX2+FMA
//! instructions, so a value may only exist inside a function compiled with them that runs
//! after the CPU was checked ([`crate::batch::Isa`]). The methods are `#[inline(always)]`, so
//! the intrinsics land inside the calling kernel.

use core::arch::x86_64::*;
use core::fmt::Debug;
use core::ops::{
    Add, AddAssign, BitAnd, BitOr, Div, DivAssign, Mul, MulAssign, Neg, Not, Sub, SubAssign,
};

use super::{Bits, Real, binary32};

/// The instructions of one register width. Every function is `unsafe`: it needs the
/// backend's CPU features (the module docs say when a value may exist).
pub trait Backend: Copy + Debug + Send + Sync + 'static {
    /// The register of `f32` lanes.
    type V: Copy + Debug + Send + Sync + 'static;
    /// A lane mask.
    type M: Copy + Debug + Send + Sync + 'static;
    /// Lanes per register.
    const LANES: usize;
    /// [`Bits::SHARE_DIVISIONS`] of [`Lanes`] on this backend: the explicit-lane form of
    /// [`super::F32FmaSharedDiv`] (`true`) or of [`super::F32Fma`] (`false`).
    const SHARE_DIVISIONS: bool;

    unsafe fn splat(x: f32) -> Self::V;
    /// Lanes `0 .. LANES` of `p`.
    unsafe fn load(p: *const f32) -> Self::V;
    unsafe fn store(p: *mut f32, v: Self::V);
    /// The first `n` lanes (`n ≥ LANES`: all).
    unsafe fn first(n: usize) -> Self::M;
    /// The masked lanes of `p`, zero elsewhere (the others are not read).
    unsafe fn load_masked(p: *const f32, m: Self::M) -> Self::V;
    /// Writes the masked lanes only.
    unsafe fn store_masked(p: *mut f32, m: Self::M, v: Self::V);
    unsafe fn add(a: Self::V, b: Self::V) -> Self::V;
    unsafe fn sub(a: Self::V, b: Self::V) -> Self::V;
    unsafe fn mul(a: Self::V, b: Self::V) -> Self::V;
    unsafe fn div(a: Self::V, b: Self::V) -> Self::V;
    /// `a·b + c`, one rounding.
    unsafe fn fmadd(a: Self::V, b: Self::V, c: Self::V) -> Self::V;
    /// `c − a·b`, one rounding.
    unsafe fn fnmadd(a: Self::V, b: Self::V, c: Self::V) -> Self::V;
    unsafe fn sqrt(a: Self::V) -> Self::V;
    /// `b` where either is NaN or both are zeros (x86 `minps` order), else the smaller.
    unsafe fn min(a: Self::V, b: Self::V) -> Self::V;
    /// As `min`, the larger.
    unsafe fn max(a: Self::V, b: Self::V) -> Self::V;
    /// The sign bit cleared.
    unsafe fn abs(a: Self::V) -> Self::V;
    /// The sign bit flipped.
    unsafe fn neg(a: Self::V) -> Self::V;
    /// Rounded towards −∞ (exact).
    unsafe fn floor(a: Self::V) -> Self::V;
    /// Ordered, quiet comparisons (`false` with a NaN): `<`, `≤`, `>`, `≥`, `=`.
    unsafe fn lt(a: Self::V, b: Self::V) -> Self::M;
    unsafe fn le(a: Self::V, b: Self::V) -> Self::M;
    unsafe fn gt(a: Self::V, b: Self::V) -> Self::M;
    unsafe fn ge(a: Self::V, b: Self::V) -> Self::M;
    unsafe fn eq(a: Self::V, b: Self::V) -> Self::M;
    /// `t` where `m`, else `f`.
    unsafe fn blend(m: Self::M, t: Self::V, f: Self::V) -> Self::V;
    unsafe fn and(a: Self::M, b: Self::M) -> Self::M;
    unsafe fn or(a: Self::M, b: Self::M) -> Self::M;
    unsafe fn not(a: Self::M) -> Self::M;
    unsafe fn any(a: Self::M) -> bool;
    unsafe fn all(a: Self::M) -> bool;
    /// The `u32` view of the lanes, as `f32` registers: `(bits >> s) & mask`, `bits | or`,
    /// `bits << s` and `magic − (bits >> 1)`, lane-wise on the integer view.
    unsafe fn shr_and(a: Self::V, s: u32, mask: u32) -> Self::V;
    unsafe fn or_bits(a: Self::V, or: u32) -> Self::V;
    unsafe fn and_bits(a: Self::V, and: u32) -> Self::V;
    unsafe fn shl(a: Self::V, s: u32) -> Self::V;
    unsafe fn magic_minus_half(a: Self::V, magic: u32) -> Self::V;
    /// `(√x, 1/√x)` for [`Bits::sqrt_rsqrt_refined`].
    unsafe fn sqrt_rsqrt_refined(x: Self::V) -> (Self::V, Self::V);
    /// `n/d` for [`Bits::div_refined`].
    unsafe fn div_refined(n: Self::V, d: Self::V) -> Self::V;
    /// `table[i]` per lane for [`Bits::lookup32`] (`i` integer-valued; the low five bits of
    /// the truncated index pick the entry). `table` points to 32 readable `f32`.
    unsafe fn lookup32(i: Self::V, table: *const f32) -> Self::V;
}

/// `LANES` `f32` lanes in one register of backend `B` (see the module docs for when one may
/// exist).
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct Lanes<B: Backend>(pub(crate) B::V);

/// A lane mask of [`Lanes`].
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct LanesMask<B: Backend>(pub(crate) B::M);

/// Sixteen lanes in an AVX-512 register.
pub type Zmm = Lanes<Avx512>;

/// Eight lanes in an AVX2 register.
pub type Ymm = Lanes<Avx2>;

/// [`Zmm`] sharing divisions ([`Bits::SHARE_DIVISIONS`]): the explicit-lane form of
/// [`super::F32FmaSharedDiv`].
pub type ZmmShared = Lanes<Avx512<true>>;

/// [`Ymm`] sharing divisions, as [`ZmmShared`].
pub type YmmShared = Lanes<Avx2<true>>;

// SAFETY (every `unsafe` block of this file outside the backends' functions): the
// instructions need the backend's CPU features, and a value exists only inside functions
// that run after the batch dispatcher checked that the CPU has them (module docs).

impl<B: Backend> BitAnd for LanesMask<B> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        LanesMask(unsafe { B::and(self.0, o.0) })
    }
}

impl<B: Backend> BitOr for LanesMask<B> {
    type Output = Self;
    #[inline(always)]
    fn bitor(self, o: Self) -> Self {
        LanesMask(unsafe { B::or(self.0, o.0) })
    }
}

impl<B: Backend> Not for LanesMask<B> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        LanesMask(unsafe { B::not(self.0) })
    }
}

impl<B: Backend> Lanes<B> {
    /// The lanes as an array (`B::LANES` of the 16 are used).
    #[inline(always)]
    fn to_array(self) -> [f32; 16] {
        let mut a = [0.0f32; 16];
        unsafe { B::store(a.as_mut_ptr(), self.0) };
        a
    }

    /// A register from the first `B::LANES` of an array.
    #[inline(always)]
    fn from_array(a: [f32; 16]) -> Self {
        Lanes(unsafe { B::load(a.as_ptr()) })
    }

    /// `f` of `f32` on every lane (the transcendentals: bit for bit the `f32` ones).
    #[inline(always)]
    fn per_lane(self, f: impl Fn(f32) -> f32) -> Self {
        let mut a = self.to_array();
        for x in &mut a[..B::LANES] {
            *x = f(*x);
        }
        Self::from_array(a)
    }
}

macro_rules! lanes_ops {
    ($($tr:ident $m:ident $atr:ident $am:ident),*) => {
        $(
            impl<B: Backend> $tr for Lanes<B> {
                type Output = Self;
                #[inline(always)]
                fn $m(self, o: Self) -> Self {
                    Lanes(unsafe { B::$m(self.0, o.0) })
                }
            }
            impl<B: Backend> $atr for Lanes<B> {
                #[inline(always)]
                fn $am(&mut self, o: Self) {
                    *self = $tr::$m(*self, o);
                }
            }
        )*
    };
}

lanes_ops!(
    Add add AddAssign add_assign,
    Sub sub SubAssign sub_assign,
    Mul mul MulAssign mul_assign,
    Div div DivAssign div_assign
);

impl<B: Backend> Neg for Lanes<B> {
    type Output = Self;
    /// Flips the sign bit (as `-x` on `f32`, zeros and NaN included).
    #[inline(always)]
    fn neg(self) -> Self {
        Lanes(unsafe { B::neg(self.0) })
    }
}

/// `Real` methods that map to one backend function.
macro_rules! via_backend {
    ($($m:ident -> $out:ident),*) => {
        $(
            #[inline(always)]
            fn $m(self, other: Self) -> $out<B> {
                $out(unsafe { B::$m(self.0, other.0) })
            }
        )*
    };
}

impl<B: Backend> Real for Lanes<B> {
    type Scalar = f32;
    type Mask = LanesMask<B>;
    const LANES: usize = B::LANES;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Lanes(unsafe { B::splat(x) })
    }
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Self::splat(x as f32)
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f32 {
        assert!(i < B::LANES, "lane index out of range");
        self.to_array()[i]
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f32) -> Self {
        let mut a = [0.0f32; 16];
        for (i, x) in a[..B::LANES].iter_mut().enumerate() {
            *x = f(i);
        }
        Self::from_array(a)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Lanes(unsafe { B::sqrt(self.0) })
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Lanes(unsafe { B::abs(self.0) })
    }
    via_backend!(min -> Lanes, max -> Lanes);
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        Lanes(unsafe { B::fmadd(self.0, a.0, b.0) })
    }
    #[inline(always)]
    fn exp(self) -> Self {
        self.per_lane(<f32 as Real>::exp)
    }
    #[inline(always)]
    fn exp2(self) -> Self {
        self.per_lane(<f32 as Real>::exp2)
    }
    #[inline(always)]
    fn ln(self) -> Self {
        self.per_lane(<f32 as Real>::ln)
    }
    #[inline(always)]
    fn log2(self) -> Self {
        self.per_lane(<f32 as Real>::log2)
    }
    #[inline(always)]
    fn pow(self, y: Self) -> Self {
        let (mut a, b) = (self.to_array(), y.to_array());
        for (x, y) in a[..B::LANES].iter_mut().zip(b) {
            *x = <f32 as Real>::pow(*x, y);
        }
        Self::from_array(a)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        self.per_lane(<f32 as Real>::sin)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        self.per_lane(<f32 as Real>::cos)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        Lanes(unsafe { B::floor(self.0) })
    }
    via_backend!(lt -> LanesMask, le -> LanesMask, gt -> LanesMask, ge -> LanesMask, eq -> LanesMask);
    #[inline(always)]
    fn is_finite(self) -> LanesMask<B> {
        self.abs().lt(Self::splat(f32::INFINITY))
    }
    #[inline(always)]
    fn select(mask: LanesMask<B>, if_true: Self, if_false: Self) -> Self {
        Lanes(unsafe { B::blend(mask.0, if_true.0, if_false.0) })
    }
    #[inline(always)]
    fn any(mask: LanesMask<B>) -> bool {
        unsafe { B::any(mask.0) }
    }
    #[inline(always)]
    fn all(mask: LanesMask<B>) -> bool {
        unsafe { B::all(mask.0) }
    }
}

impl<B: Backend> Bits for Lanes<B> {
    /// As `f32`'s, lane by lane on the integer view.
    #[inline(always)]
    fn exponent_split(self) -> (Self, Self) {
        unsafe {
            let biased = B::shr_and(self.0, binary32::MANTISSA_BITS, binary32::EXPONENT_MASK);
            let two_pow_plus_biased = B::or_bits(biased, binary32::TWO_POW_MANTISSA_BITS);
            let e = B::sub(two_pow_plus_biased, B::splat(binary32::EXPONENT_OFFSET));
            let fraction = B::and_bits(self.0, binary32::FRACTION_MASK);
            (Lanes(B::or_bits(fraction, binary32::ONE_BITS)), Lanes(e))
        }
    }
    #[inline(always)]
    fn ldexp(self, e: Self) -> Self {
        unsafe {
            let biased = B::add(e.0, B::splat(binary32::EXPONENT_OFFSET));
            Lanes(B::mul(self.0, B::shl(biased, binary32::MANTISSA_BITS)))
        }
    }
    /// The bit trick of `f32` (not a hardware estimate), so that [`crate::fast::rsqrt`] and
    /// the [`crate::fast::NewtonSqrt`] policies give the bits of [`super::F32Fma`].
    #[inline(always)]
    fn rsqrt_estimate(self) -> Self {
        Lanes(unsafe { B::magic_minus_half(self.0, binary32::RSQRT_MAGIC) })
    }
    #[inline(always)]
    fn sqrt_rsqrt_refined(self) -> (Self, Self) {
        let (s, y) = unsafe { B::sqrt_rsqrt_refined(self.0) };
        (Lanes(s), Lanes(y))
    }
    #[inline(always)]
    fn div_refined(self, d: Self) -> Self {
        Lanes(unsafe { B::div_refined(self.0, d.0) })
    }
    #[inline(always)]
    fn lookup32(self, table: &[f32; 32]) -> Self {
        Lanes(unsafe { B::lookup32(self.0, table.as_ptr()) })
    }
    const SHARE_DIVISIONS: bool = B::SHARE_DIVISIONS;
}

/// Lanes `i .. i + LANES` of `x` where `mask` is set, zero elsewhere.
///
/// # Safety
///
/// The CPU has the backend's features, and every masked lane `i + j` is within `x`.
#[inline(always)]
pub(crate) unsafe fn load<B: Backend>(x: &[f32], i: usize, mask: LanesMask<B>) -> Lanes<B> {
    unsafe { Lanes(B::load_masked(x.as_ptr().add(i), mask.0)) }
}

/// Writes the masked lanes of `v` to `x[i ..]`.
///
/// # Safety
///
/// As [`load`].
#[inline(always)]
pub(crate) unsafe fn store<B: Backend>(x: &mut [f32], i: usize, mask: LanesMask<B>, v: Lanes<B>) {
    unsafe { B::store_masked(x.as_mut_ptr().add(i), mask.0, v.0) }
}

/// The mask of the first `min(n, LANES)` lanes.
///
/// # Safety
///
/// The CPU has the backend's features.
#[inline(always)]
pub(crate) unsafe fn first_lanes<B: Backend>(n: usize) -> LanesMask<B> {
    LanesMask(unsafe { B::first(n) })
}

// ---------------------------------------------------------------------------------------------
// AVX-512F: 16 lanes, k-register masks
// ---------------------------------------------------------------------------------------------

/// The AVX-512F backend (16 lanes, masks in k registers); `SHARED` is its
/// [`Backend::SHARE_DIVISIONS`].
#[derive(Clone, Copy, Debug)]
pub struct Avx512<const SHARED: bool = false>;

impl<const SHARED: bool> Backend for Avx512<SHARED> {
    type V = __m512;
    type M = __mmask16;
    const LANES: usize = 16;
    const SHARE_DIVISIONS: bool = SHARED;

    #[inline(always)]
    unsafe fn splat(x: f32) -> __m512 {
        unsafe { _mm512_set1_ps(x) }
    }
    #[inline(always)]
    unsafe fn load(p: *const f32) -> __m512 {
        unsafe { _mm512_loadu_ps(p) }
    }
    #[inline(always)]
    unsafe fn store(p: *mut f32, v: __m512) {
        unsafe { _mm512_storeu_ps(p, v) }
    }
    #[inline(always)]
    unsafe fn first(n: usize) -> __mmask16 {
        if n >= 16 { u16::MAX } else { (1u16 << n) - 1 }
    }
    #[inline(always)]
    unsafe fn load_masked(p: *const f32, m: __mmask16) -> __m512 {
        unsafe { _mm512_maskz_loadu_ps(m, p) }
    }
    #[inline(always)]
    unsafe fn store_masked(p: *mut f32, m: __mmask16, v: __m512) {
        unsafe { _mm512_mask_storeu_ps(p, m, v) }
    }
    #[inline(always)]
    unsafe fn add(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_add_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn sub(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_sub_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn mul(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_mul_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn div(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_div_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn fmadd(a: __m512, b: __m512, c: __m512) -> __m512 {
        unsafe { _mm512_fmadd_ps(a, b, c) }
    }
    #[inline(always)]
    unsafe fn fnmadd(a: __m512, b: __m512, c: __m512) -> __m512 {
        unsafe { _mm512_fnmadd_ps(a, b, c) }
    }
    #[inline(always)]
    unsafe fn sqrt(a: __m512) -> __m512 {
        unsafe { _mm512_sqrt_ps(a) }
    }
    #[inline(always)]
    unsafe fn min(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_min_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn max(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_max_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn abs(a: __m512) -> __m512 {
        unsafe { _mm512_abs_ps(a) }
    }
    #[inline(always)]
    unsafe fn neg(a: __m512) -> __m512 {
        unsafe {
            let sign = _mm512_set1_epi32(i32::MIN);
            _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a), sign))
        }
    }
    #[inline(always)]
    unsafe fn floor(a: __m512) -> __m512 {
        unsafe { _mm512_roundscale_ps::<0x09>(a) }
    }
    #[inline(always)]
    unsafe fn lt(a: __m512, b: __m512) -> __mmask16 {
        unsafe { _mm512_cmp_ps_mask::<_CMP_LT_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn le(a: __m512, b: __m512) -> __mmask16 {
        unsafe { _mm512_cmp_ps_mask::<_CMP_LE_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn gt(a: __m512, b: __m512) -> __mmask16 {
        unsafe { _mm512_cmp_ps_mask::<_CMP_GT_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn ge(a: __m512, b: __m512) -> __mmask16 {
        unsafe { _mm512_cmp_ps_mask::<_CMP_GE_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn eq(a: __m512, b: __m512) -> __mmask16 {
        unsafe { _mm512_cmp_ps_mask::<_CMP_EQ_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn blend(m: __mmask16, t: __m512, f: __m512) -> __m512 {
        unsafe { _mm512_mask_blend_ps(m, f, t) }
    }
    #[inline(always)]
    unsafe fn and(a: __mmask16, b: __mmask16) -> __mmask16 {
        a & b
    }
    #[inline(always)]
    unsafe fn or(a: __mmask16, b: __mmask16) -> __mmask16 {
        a | b
    }
    #[inline(always)]
    unsafe fn not(a: __mmask16) -> __mmask16 {
        !a
    }
    #[inline(always)]
    unsafe fn any(a: __mmask16) -> bool {
        a != 0
    }
    #[inline(always)]
    unsafe fn all(a: __mmask16) -> bool {
        a == u16::MAX
    }
    #[inline(always)]
    unsafe fn shr_and(a: __m512, s: u32, mask: u32) -> __m512 {
        unsafe {
            let b = _mm512_srlv_epi32(_mm512_castps_si512(a), _mm512_set1_epi32(s as i32));
            _mm512_castsi512_ps(_mm512_and_si512(b, _mm512_set1_epi32(mask as i32)))
        }
    }
    #[inline(always)]
    unsafe fn or_bits(a: __m512, or: u32) -> __m512 {
        unsafe {
            let b = _mm512_or_si512(_mm512_castps_si512(a), _mm512_set1_epi32(or as i32));
            _mm512_castsi512_ps(b)
        }
    }
    #[inline(always)]
    unsafe fn and_bits(a: __m512, and: u32) -> __m512 {
        unsafe {
            let b = _mm512_and_si512(_mm512_castps_si512(a), _mm512_set1_epi32(and as i32));
            _mm512_castsi512_ps(b)
        }
    }
    #[inline(always)]
    unsafe fn shl(a: __m512, s: u32) -> __m512 {
        unsafe {
            let b = _mm512_sllv_epi32(_mm512_castps_si512(a), _mm512_set1_epi32(s as i32));
            _mm512_castsi512_ps(b)
        }
    }
    #[inline(always)]
    unsafe fn magic_minus_half(a: __m512, magic: u32) -> __m512 {
        unsafe {
            let half = _mm512_srli_epi32::<1>(_mm512_castps_si512(a));
            _mm512_castsi512_ps(_mm512_sub_epi32(_mm512_set1_epi32(magic as i32), half))
        }
    }
    /// `vrsqrt14ps` (relative error ≤ 2⁻¹⁴) and one Newton step.
    #[inline(always)]
    unsafe fn sqrt_rsqrt_refined(x: __m512) -> (__m512, __m512) {
        unsafe {
            // Inputs below the smallest normal are raised to it for the estimate: √0 = 0·y
            // = 0, and 1/√0 is a large finite value (as `fast::rsqrt`), without a select.
            let y = _mm512_rsqrt14_ps(_mm512_max_ps(x, _mm512_set1_ps(f32::MIN_POSITIVE)));
            // s ≈ √x and h ≈ 1/(2√x) with the estimate's error ε; the residual
            // r = x − s² = x(1 − (1 + ε)²) ≈ −2εx, exact to one rounding by the FMA.
            let s = _mm512_mul_ps(x, y);
            let h = _mm512_mul_ps(y, _mm512_set1_ps(0.5));
            let r = _mm512_fnmadd_ps(s, s, x);
            // √x = s + r/(2√x) + O(ε²): one step, error O(ε²) = O(2⁻²⁸) before rounding.
            let sqrt = _mm512_fmadd_ps(r, h, s);
            // 1/√x = y(1 + (1 − x y²)/2 + O(ε²)), with x·y = s: y + h·(1 − s·y).
            let e = _mm512_fnmadd_ps(s, y, _mm512_set1_ps(1.0));
            (sqrt, _mm512_fmadd_ps(h, e, y))
        }
    }
    /// `vrcp14ps` (relative error ≤ 2⁻¹⁴) and one correction step.
    #[inline(always)]
    unsafe fn div_refined(n: __m512, d: __m512) -> __m512 {
        unsafe {
            let r = _mm512_rcp14_ps(d);
            // q = n·r ≈ n/d (1 + ε); the remainder n − q·d is exact to one rounding by the
            // FMA, and q + remainder·r removes the first-order error (Markstein's step).
            let q = _mm512_mul_ps(n, r);
            let rem = _mm512_fnmadd_ps(q, d, n);
            _mm512_fmadd_ps(rem, r, q)
        }
    }
    /// `vpermt2ps`: one permute over the table's two 16-entry halves (the index's bit 4
    /// picks the half).
    #[inline(always)]
    unsafe fn lookup32(i: __m512, table: *const f32) -> __m512 {
        unsafe {
            let lo = _mm512_loadu_ps(table);
            let hi = _mm512_loadu_ps(table.add(16));
            _mm512_permutex2var_ps(lo, _mm512_cvttps_epi32(i), hi)
        }
    }
}

// ---------------------------------------------------------------------------------------------
// AVX2 + FMA: 8 lanes, vector masks
// ---------------------------------------------------------------------------------------------

/// The AVX2+FMA backend (8 lanes, masks as all-ones/all-zeros lanes); `SHARED` is its
/// [`Backend::SHARE_DIVISIONS`].
#[derive(Clone, Copy, Debug)]
pub struct Avx2<const SHARED: bool = false>;

impl<const SHARED: bool> Avx2<SHARED> {
    /// Every bit set.
    #[inline(always)]
    unsafe fn ones() -> __m256 {
        unsafe { _mm256_castsi256_ps(_mm256_set1_epi32(-1)) }
    }
}

impl<const SHARED: bool> Backend for Avx2<SHARED> {
    type V = __m256;
    type M = __m256;
    const LANES: usize = 8;
    const SHARE_DIVISIONS: bool = SHARED;

    #[inline(always)]
    unsafe fn splat(x: f32) -> __m256 {
        unsafe { _mm256_set1_ps(x) }
    }
    #[inline(always)]
    unsafe fn load(p: *const f32) -> __m256 {
        unsafe { _mm256_loadu_ps(p) }
    }
    #[inline(always)]
    unsafe fn store(p: *mut f32, v: __m256) {
        unsafe { _mm256_storeu_ps(p, v) }
    }
    #[inline(always)]
    unsafe fn first(n: usize) -> __m256 {
        unsafe {
            let lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
            let n = _mm256_set1_epi32(n.min(8) as i32);
            _mm256_castsi256_ps(_mm256_cmpgt_epi32(n, lane))
        }
    }
    #[inline(always)]
    unsafe fn load_masked(p: *const f32, m: __m256) -> __m256 {
        unsafe { _mm256_maskload_ps(p, _mm256_castps_si256(m)) }
    }
    #[inline(always)]
    unsafe fn store_masked(p: *mut f32, m: __m256, v: __m256) {
        unsafe { _mm256_maskstore_ps(p, _mm256_castps_si256(m), v) }
    }
    #[inline(always)]
    unsafe fn add(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_add_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn sub(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_sub_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn mul(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_mul_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn div(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_div_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn fmadd(a: __m256, b: __m256, c: __m256) -> __m256 {
        unsafe { _mm256_fmadd_ps(a, b, c) }
    }
    #[inline(always)]
    unsafe fn fnmadd(a: __m256, b: __m256, c: __m256) -> __m256 {
        unsafe { _mm256_fnmadd_ps(a, b, c) }
    }
    #[inline(always)]
    unsafe fn sqrt(a: __m256) -> __m256 {
        unsafe { _mm256_sqrt_ps(a) }
    }
    #[inline(always)]
    unsafe fn min(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_min_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn max(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_max_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn abs(a: __m256) -> __m256 {
        unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), a) }
    }
    #[inline(always)]
    unsafe fn neg(a: __m256) -> __m256 {
        unsafe { _mm256_xor_ps(a, _mm256_set1_ps(-0.0)) }
    }
    #[inline(always)]
    unsafe fn floor(a: __m256) -> __m256 {
        unsafe { _mm256_round_ps::<0x09>(a) }
    }
    #[inline(always)]
    unsafe fn lt(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn le(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_cmp_ps::<_CMP_LE_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn gt(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_cmp_ps::<_CMP_GT_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn ge(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_cmp_ps::<_CMP_GE_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn eq(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_cmp_ps::<_CMP_EQ_OQ>(a, b) }
    }
    #[inline(always)]
    unsafe fn blend(m: __m256, t: __m256, f: __m256) -> __m256 {
        unsafe { _mm256_blendv_ps(f, t, m) }
    }
    #[inline(always)]
    unsafe fn and(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_and_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn or(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_or_ps(a, b) }
    }
    #[inline(always)]
    unsafe fn not(a: __m256) -> __m256 {
        unsafe { _mm256_xor_ps(a, Self::ones()) }
    }
    #[inline(always)]
    unsafe fn any(a: __m256) -> bool {
        unsafe { _mm256_movemask_ps(a) != 0 }
    }
    #[inline(always)]
    unsafe fn all(a: __m256) -> bool {
        unsafe { _mm256_movemask_ps(a) == 0xFF }
    }
    #[inline(always)]
    unsafe fn shr_and(a: __m256, s: u32, mask: u32) -> __m256 {
        unsafe {
            let b = _mm256_srlv_epi32(_mm256_castps_si256(a), _mm256_set1_epi32(s as i32));
            _mm256_castsi256_ps(_mm256_and_si256(b, _mm256_set1_epi32(mask as i32)))
        }
    }
    #[inline(always)]
    unsafe fn or_bits(a: __m256, or: u32) -> __m256 {
        unsafe {
            let b = _mm256_or_si256(_mm256_castps_si256(a), _mm256_set1_epi32(or as i32));
            _mm256_castsi256_ps(b)
        }
    }
    #[inline(always)]
    unsafe fn and_bits(a: __m256, and: u32) -> __m256 {
        unsafe {
            let b = _mm256_and_si256(_mm256_castps_si256(a), _mm256_set1_epi32(and as i32));
            _mm256_castsi256_ps(b)
        }
    }
    #[inline(always)]
    unsafe fn shl(a: __m256, s: u32) -> __m256 {
        unsafe {
            let b = _mm256_sllv_epi32(_mm256_castps_si256(a), _mm256_set1_epi32(s as i32));
            _mm256_castsi256_ps(b)
        }
    }
    #[inline(always)]
    unsafe fn magic_minus_half(a: __m256, magic: u32) -> __m256 {
        unsafe {
            let half = _mm256_srli_epi32::<1>(_mm256_castps_si256(a));
            _mm256_castsi256_ps(_mm256_sub_epi32(_mm256_set1_epi32(magic as i32), half))
        }
    }
    /// Exact: AVX2's `vrsqrtps` carries 1.5·2⁻¹² and would need two steps.
    #[inline(always)]
    unsafe fn sqrt_rsqrt_refined(x: __m256) -> (__m256, __m256) {
        unsafe {
            let s = _mm256_sqrt_ps(x);
            (s, _mm256_div_ps(_mm256_set1_ps(1.0), s))
        }
    }
    /// Exact (see `sqrt_rsqrt_refined`).
    #[inline(always)]
    unsafe fn div_refined(n: __m256, d: __m256) -> __m256 {
        unsafe { _mm256_div_ps(n, d) }
    }
    /// Four `vpermps` (one per quarter of the table, by the index's low three bits) and
    /// three blends (by its bits 3 and 4, shifted into the sign bits `vblendvps` reads).
    #[inline(always)]
    unsafe fn lookup32(i: __m256, table: *const f32) -> __m256 {
        unsafe {
            let i = _mm256_cvttps_epi32(i);
            // No closure: it could stay out of line, outside the kernel's features.
            let q0 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table), i);
            let q1 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table.add(8)), i);
            let q2 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table.add(16)), i);
            let q3 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table.add(24)), i);
            let bit3 = _mm256_castsi256_ps(_mm256_slli_epi32::<28>(i));
            let bit4 = _mm256_castsi256_ps(_mm256_slli_epi32::<27>(i));
            let low = _mm256_blendv_ps(q0, q1, bit3);
            let high = _mm256_blendv_ps(q2, q3, bit3);
            _mm256_blendv_ps(low, high, bit4)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fresnel::{Conductor, Schlick};
    use crate::masking::{SmithHeightCorrelated, SmithSeparable};
    use crate::models::{Brdf, ClassicBlinnPhong, CookTorrance, OrenNayar};
    use crate::ndf::{Ggx, GgxIsotropic};
    use crate::real::{F32Fma, Splat};
    use crate::{Vec3, ior};

    fn avx512() -> bool {
        std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512vl")
    }

    fn avx2() -> bool {
        std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
    }

    /// Distance in units in the last place of `a` from the exact `x` (f64).
    fn ulps(a: f32, x: f64) -> f64 {
        let r = x as f32;
        let ulp = f64::from(f32::from_bits(r.to_bits() + 1) - r);
        (f64::from(a) - x).abs() / ulp
    }

    /// Worst ULP errors of `(√x, 1/√x)` over `xs`, 16 at a time.
    #[target_feature(enable = "avx512f,avx512vl")]
    fn sqrt_errors(xs: &[f32]) -> (f64, f64) {
        let (mut es, mut er) = (0.0f64, 0.0f64);
        for c in xs.chunks_exact(16) {
            let (s, r) = Zmm::from_fn(|j| c[j]).sqrt_rsqrt_refined();
            for (j, &x) in c.iter().enumerate() {
                let exact = f64::from(x).sqrt();
                es = es.max(ulps(s.lane(j), exact));
                er = er.max(ulps(r.lane(j), 1.0 / exact));
            }
        }
        (es, er)
    }

    /// Worst ULP error of `n / d` over the pairs.
    #[target_feature(enable = "avx512f,avx512vl")]
    fn div_error(ns: &[f32], ds: &[f32]) -> f64 {
        let mut e = 0.0f64;
        for (cn, cd) in ns.chunks_exact(16).zip(ds.chunks_exact(16)) {
            let q = Zmm::from_fn(|j| cn[j]).div_refined(Zmm::from_fn(|j| cd[j]));
            for j in 0..16 {
                e = e.max(ulps(q.lane(j), f64::from(cn[j]) / f64::from(cd[j])));
            }
        }
        e
    }

    /// `lookup32` of every index 0 … 31 in every lane position, and out-of-domain indices
    /// (the low five bits of the truncated value pick the entry), on `LANES`-wide lanes.
    #[inline(always)]
    fn lookup_errors<B: Backend>() -> usize {
        let table: [f32; 32] = core::array::from_fn(|i| 100.0 + i as f32);
        let mut wrong = 0;
        for shift in 0..32usize {
            let idx = Lanes::<B>::from_fn(|j| ((j + shift) % 32) as f32);
            let v = idx.lookup32(&table);
            for j in 0..B::LANES {
                wrong += usize::from(v.lane(j) != table[(j + shift) % 32]);
            }
        }
        // Outside the domain the low five bits of the truncated index pick the entry: 33.7
        // truncates to 33 (entry 1), −1 to 0xFFFF_FFFF (31), NaN to 0x8000_0000 (0).
        let odd = [(33.7, 1), (-1.0, 31), (f32::NAN, 0)];
        for (x, want) in odd {
            let v = Lanes::<B>::splat(x).lookup32(&table);
            wrong += (0..B::LANES).filter(|&j| v.lane(j) != table[want]).count();
        }
        wrong
    }

    #[target_feature(enable = "avx512f,avx512vl")]
    fn lookup_errors_avx512() -> usize {
        lookup_errors::<Avx512>()
    }

    #[target_feature(enable = "avx2,fma")]
    fn lookup_errors_avx2() -> usize {
        lookup_errors::<Avx2>()
    }

    #[test]
    fn lookup32_reads_every_entry() {
        // SAFETY: each call runs only where its features were detected.
        if avx512() {
            assert_eq!(unsafe { lookup_errors_avx512() }, 0);
        }
        if avx2() {
            assert_eq!(unsafe { lookup_errors_avx2() }, 0);
        }
    }

    /// Every float of `[1, 4)` (two binades: both parities of the exponent, which the
    /// square root treats differently), and a spread of exponents on top.
    fn sqrt_inputs() -> Vec<f32> {
        let (lo, hi) = (1.0f32.to_bits(), 4.0f32.to_bits());
        let mut xs: Vec<f32> = (lo..hi).map(f32::from_bits).collect();
        let mut s = 0x9E37_79B9u32;
        for _ in 0..(1 << 16) {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            // Positive normal floats, exponents −126 … 127.
            xs.push(f32::from_bits(
                (s % (0x7F80_0000 - 0x0080_0000)) + 0x0080_0000,
            ));
        }
        xs.truncate(xs.len() / 16 * 16);
        xs
    }

    #[test]
    fn refined_square_root_within_one_ulp() {
        if !avx512() {
            eprintln!("no AVX-512 on this CPU: skipped");
            return;
        }
        let xs = sqrt_inputs();
        // SAFETY: AVX-512F/VL checked above.
        let (es, er) = unsafe { sqrt_errors(&xs) };
        eprintln!("√: {es:.3} ULP, 1/√: {er:.3} ULP over {} inputs", xs.len());
        // Measured on an Intel Xeon (Sapphire Rapids class): 0.68 and 1.04 ULP.
        assert!(es <= 1.0 && er <= 1.5, "√ {es} ULP, 1/√ {er} ULP");
        // √0 = 0 with a finite 1/√.
        let zero = unsafe { sqrt_at_zero() };
        assert_eq!(zero.0, 0.0);
        assert!(zero.1.is_finite() && zero.1 > 1e18);
    }

    #[target_feature(enable = "avx512f,avx512vl")]
    fn sqrt_at_zero() -> (f32, f32) {
        let (s, r) = Zmm::splat(0.0).sqrt_rsqrt_refined();
        (s.lane(3), r.lane(3))
    }

    #[test]
    fn refined_division_within_one_ulp() {
        if !avx512() {
            eprintln!("no AVX-512 on this CPU: skipped");
            return;
        }
        // Numerators and denominators over exponents ±60 (quotients normal), plus every
        // seventh denominator mantissa of [1, 2) against a fixed numerator.
        let mut s = 0x2545_F491u32;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s
        };
        let mut ns = Vec::new();
        let mut ds = Vec::new();
        for _ in 0..(1 << 18) {
            let (a, b) = (next(), next());
            let exp = |r: u32| ((r >> 23) % 121 + 127 - 60) << 23;
            ns.push(f32::from_bits(exp(a) | (a & 0x007F_FFFF)));
            ds.push(f32::from_bits(exp(b) | (b & 0x007F_FFFF)));
        }
        for m in (0..(1u32 << 23)).step_by(7) {
            ns.push(1.7);
            ds.push(f32::from_bits(1.0f32.to_bits() | m));
        }
        let len = ns.len() / 16 * 16;
        // SAFETY: AVX-512F/VL checked above.
        let e = unsafe { div_error(&ns[..len], &ds[..len]) };
        eprintln!("÷: {e:.3} ULP over {len} pairs");
        // Measured on an Intel Xeon (Sapphire Rapids class): 0.54 ULP.
        assert!(e <= 1.0, "÷ {e} ULP");
    }

    /// `model` on `Lanes<B>` and on `F32Fma` at `n` registers of pairs: every lane bit for
    /// bit. Call it from a function compiled with `B`'s features.
    #[inline(always)]
    fn same_bits<Bk, M, const N: usize>(model: &M, n: usize) -> usize
    where
        Bk: Backend,
        M: Splat,
        M::On<Lanes<Bk>>: Brdf<Lanes<Bk>, N>,
        M::On<F32Fma>: Brdf<F32Fma, N>,
    {
        let (wide, fused) = (model.splat::<Lanes<Bk>>(), model.splat::<F32Fma>());
        let dir = |u: f64, v: f64| {
            let (c, phi) = (u, v * core::f64::consts::TAU);
            let s = (1.0 - c * c).sqrt();
            [(s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32]
        };
        let w = Bk::LANES;
        let mut compared = 0;
        for k in 0..n {
            let g = 0.618_033_988_749_894_9_f64;
            let ds: Vec<[[f32; 3]; 2]> = (0..w)
                .map(|j| {
                    let i = (w * k + j) as f64;
                    let grazing = if (w * k + j) % 13 == 0 { 0.0 } else { 1.0 };
                    [
                        dir(grazing * (i * g).fract(), (i * g * g).fract()),
                        dir((i * 0.754_877_666).fract(), (i * 0.569_840_290).fract()),
                    ]
                })
                .collect();
            let lanes = |d: usize, a: usize| Lanes::<Bk>::from_fn(|j| ds[j][d][a]);
            let f = wide.eval(
                Vec3::new(lanes(0, 0), lanes(0, 1), lanes(0, 2)),
                Vec3::new(lanes(1, 0), lanes(1, 1), lanes(1, 2)),
            );
            for (j, d) in ds.iter().enumerate() {
                let v = |w: [f32; 3]| Vec3::new(F32Fma(w[0]), F32Fma(w[1]), F32Fma(w[2]));
                let g = fused.eval(v(d[0]), v(d[1]));
                for c in 0..N {
                    assert_eq!(
                        f[c].lane(j).to_bits(),
                        g[c].0.to_bits(),
                        "lane {j}, channel {c}"
                    );
                    compared += 1;
                }
            }
        }
        compared
    }

    /// GGX, the exact conductor, Oren-Nayar and the classic Blinn-Phong (its per-lane `pow`)
    /// on `Lanes<B>`, compared with `F32Fma`; returns how many values.
    #[inline(always)]
    fn models_same_bits<Bk: Backend>() -> usize {
        let ggx = CookTorrance::new(
            GgxIsotropic::<f32>::new(0.3).unwrap(),
            Schlick::<f32, 1>::new([0.04]).unwrap(),
            SmithHeightCorrelated,
        );
        let gold = CookTorrance::new(
            Ggx::<f32>::new(0.2).unwrap(),
            Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap(),
            SmithSeparable,
        );
        let oren_nayar = OrenNayar::<f32, 3>::new([0.5, 0.4, 0.3], 0.7).unwrap();
        let phong = ClassicBlinnPhong::<f32, 1>::new([0.3], 0.5, [0.04], 57.0).unwrap();
        same_bits::<Bk, _, 1>(&ggx, 256)
            + same_bits::<Bk, _, 3>(&gold, 256)
            + same_bits::<Bk, _, 3>(&oren_nayar, 256)
            + same_bits::<Bk, _, 1>(&phong, 256)
    }

    #[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
    fn models_same_bits_avx512() -> usize {
        models_same_bits::<Avx512>()
    }

    #[target_feature(enable = "avx2,fma")]
    fn models_same_bits_avx2() -> usize {
        models_same_bits::<Avx2>()
    }

    /// Without the estimates, `Lanes` is `F32Fma` lane by lane: `+ − × ÷ √`, `mul_add`,
    /// `min`/`max`, selects (GGX, the exact conductor, Oren-Nayar) and the per-lane `pow`
    /// (the classic Blinn-Phong), at a grazing-heavy set of pairs; on `Ymm` the refined
    /// operations are exact too.
    #[test]
    fn explicit_lanes_equal_f32fma_bit_for_bit() {
        let mut ran = 0;
        if avx512() {
            // SAFETY: AVX-512F/VL checked (FMA and AVX2 come with them).
            assert_eq!(unsafe { models_same_bits_avx512() }, 256 * 16 * 8);
            ran += 1;
        }
        if avx2() {
            // SAFETY: AVX2 and FMA checked.
            assert_eq!(unsafe { models_same_bits_avx2() }, 256 * 8 * 8);
            ran += 1;
        }
        eprintln!("{ran} backends compared");
    }

    /// The AVX2 masks: the first `n` lanes, any/all, and a masked load/store that leaves the
    /// other lanes alone.
    #[target_feature(enable = "avx2,fma")]
    fn avx2_masks() {
        let x = [1.0f32, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0];
        for n in 0..=9 {
            let m = unsafe { first_lanes::<Avx2>(n) };
            assert_eq!(Ymm::any(m), n > 0);
            assert_eq!(Ymm::all(m), n >= 8);
            let v = unsafe { load(&x, 1, m) };
            for j in 0..8 {
                assert_eq!(v.lane(j), if j < n { x[1 + j] } else { 0.0 });
            }
            let mut out = [-1.0f32; 9];
            unsafe { store(&mut out, 1, m, v + Ymm::splat(10.0)) };
            for (j, &o) in out.iter().enumerate() {
                let expect = if j >= 1 && j - 1 < n.min(8) {
                    x[j] + 10.0
                } else {
                    -1.0
                };
                assert_eq!(o, expect, "n = {n}, lane {j}");
            }
            assert!(Ymm::all(!m | m));
            assert!(!Ymm::any(!m & m));
        }
    }

    #[test]
    fn avx2_lane_masks() {
        if avx2() {
            // SAFETY: AVX2 and FMA checked.
            unsafe { avx2_masks() };
        }
    }
}
