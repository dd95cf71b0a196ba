//! `Zmm`: sixteen `f32` lanes in one AVX-512 register, the number type of the batch path's
//! explicit AVX-512 loop ([`crate::batch`]) for models that ask for the hardware estimates
//! of [`crate::fast::HardwareEstimate`].
//!
//! Why a type of its own: the other batch kernels run a one-lane model ([`super::F32Fma`])
//! that LLVM vectorizes across loop iterations. LLVM does not vectorize the scalar estimate
//! intrinsics (`rsqrt14ss`, `rcp14ss`), so a formula that wants `vrsqrt14ps`/`vrcp14ps`
//! must run on registers of 16 lanes directly. Every other operation is the correctly
//! rounded instruction (`vaddps` … `vsqrtps`, `vfmadd`), and the transcendentals are the
//! `f32` ones lane by lane, so a formula without the estimates gives on `Zmm` the bits of
//! [`super::F32Fma`] in every lane (tested below).
//!
//! Crate-private and unsafe to construct: its operations are AVX-512F instructions, so a
//! `Zmm` may only exist inside a function compiled with `avx512f` that runs after the CPU
//! was checked ([`crate::batch::Isa::Avx512`]). The methods are `#[inline(always)]`, so the
//! intrinsics land inside the calling kernel.

use core::arch::x86_64::{
    __m512, __mmask16, _CMP_EQ_OQ, _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm512_abs_ps,
    _mm512_add_ps, _mm512_and_si512, _mm512_castps_si512, _mm512_castsi512_ps, _mm512_cmp_ps_mask,
    _mm512_div_ps, _mm512_fmadd_ps, _mm512_fnmadd_ps, _mm512_loadu_ps, _mm512_mask_blend_ps,
    _mm512_mask_storeu_ps, _mm512_maskz_loadu_ps, _mm512_max_ps, _mm512_min_ps, _mm512_mul_ps,
    _mm512_or_si512, _mm512_rcp14_ps, _mm512_roundscale_ps, _mm512_rsqrt14_ps, _mm512_set1_epi32,
    _mm512_set1_ps, _mm512_slli_epi32, _mm512_sqrt_ps, _mm512_srli_epi32, _mm512_storeu_ps,
    _mm512_sub_epi32, _mm512_sub_ps, _mm512_xor_si512,
};
use core::ops::{
    Add, AddAssign, BitAnd, BitOr, Div, DivAssign, Mul, MulAssign, Neg, Not, Sub, SubAssign,
};

use super::{Bits, Real, binary32};

/// Sixteen `f32` lanes in an AVX-512 register (see the module docs for when one may exist).
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct Zmm(pub(crate) __m512);

/// A lane mask of [`Zmm`]: one bit per lane in an AVX-512 mask register.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(transparent)]
pub struct ZmmMask(pub(crate) __mmask16);

impl BitAnd for ZmmMask {
    type Output = ZmmMask;
    #[inline(always)]
    fn bitand(self, o: ZmmMask) -> ZmmMask {
        ZmmMask(self.0 & o.0)
    }
}

impl BitOr for ZmmMask {
    type Output = ZmmMask;
    #[inline(always)]
    fn bitor(self, o: ZmmMask) -> ZmmMask {
        ZmmMask(self.0 | o.0)
    }
}

impl Not for ZmmMask {
    type Output = ZmmMask;
    #[inline(always)]
    fn not(self) -> ZmmMask {
        ZmmMask(!self.0)
    }
}

// SAFETY (every `unsafe` block of this file): the intrinsics need AVX-512F, and a `Zmm`
// exists only inside functions that run after the batch dispatcher checked that the CPU
// has it (module docs); they read no memory except `loadu`/`storeu` of 16-element arrays.

impl Zmm {
    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn to_array(self) -> [f32; 16] {
        let mut a = [0.0f32; 16];
        unsafe { _mm512_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }

    /// A register from an array.
    #[inline(always)]
    pub(crate) fn from_array(a: [f32; 16]) -> Zmm {
        Zmm(unsafe { _mm512_loadu_ps(a.as_ptr()) })
    }

    /// `f` of `f32` on every lane (the transcendentals: bit for bit the `f32` ones).
    #[inline(always)]
    fn per_lane(self, f: impl Fn(f32) -> f32) -> Zmm {
        let mut a = self.to_array();
        for x in &mut a {
            *x = f(*x);
        }
        Zmm::from_array(a)
    }

    #[inline(always)]
    fn cmp<const P: i32>(self, o: Zmm) -> ZmmMask {
        ZmmMask(unsafe { _mm512_cmp_ps_mask::<P>(self.0, o.0) })
    }
}

macro_rules! zmm_ops {
    ($($tr:ident $m:ident $atr:ident $am:ident $f:ident),*) => {
        $(
            impl $tr for Zmm {
                type Output = Zmm;
                #[inline(always)]
                fn $m(self, o: Zmm) -> Zmm {
                    Zmm(unsafe { $f(self.0, o.0) })
                }
            }
            impl $atr for Zmm {
                #[inline(always)]
                fn $am(&mut self, o: Zmm) {
                    *self = $tr::$m(*self, o);
                }
            }
        )*
    };
}

zmm_ops!(
    Add add AddAssign add_assign _mm512_add_ps,
    Sub sub SubAssign sub_assign _mm512_sub_ps,
    Mul mul MulAssign mul_assign _mm512_mul_ps,
    Div div DivAssign div_assign _mm512_div_ps
);

impl Neg for Zmm {
    type Output = Zmm;
    /// Flips the sign bit (as `-x` on `f32`, zeros and NaN included).
    #[inline(always)]
    fn neg(self) -> Zmm {
        unsafe {
            let sign = _mm512_set1_epi32(i32::MIN);
            Zmm(_mm512_castsi512_ps(_mm512_xor_si512(
                _mm512_castps_si512(self.0),
                sign,
            )))
        }
    }
}

impl Real for Zmm {
    type Scalar = f32;
    type Mask = ZmmMask;
    const LANES: usize = 16;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Zmm(unsafe { _mm512_set1_ps(x) })
    }
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Zmm::splat(x as f32)
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f32 {
        self.to_array()[i]
    }
    #[inline(always)]
    fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        Zmm::from_array(core::array::from_fn(f))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Zmm(unsafe { _mm512_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Zmm(unsafe { _mm512_abs_ps(self.0) })
    }
    /// `vminps(self, other)`: `other` where either is NaN or both are zeros, as `f32`'s
    /// `if self < other { self } else { other }`.
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        Zmm(unsafe { _mm512_min_ps(self.0, other.0) })
    }
    /// `vmaxps(self, other)`, as `f32`'s `if self > other { self } else { other }`.
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        Zmm(unsafe { _mm512_max_ps(self.0, other.0) })
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        Zmm(unsafe { _mm512_fmadd_ps(self.0, a.0, b.0) })
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
        for (x, y) in a.iter_mut().zip(b) {
            *x = <f32 as Real>::pow(*x, y);
        }
        Zmm::from_array(a)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        self.per_lane(<f32 as Real>::sin)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        self.per_lane(<f32 as Real>::cos)
    }
    /// `vrndscaleps` rounding down (exact, as `floor`).
    #[inline(always)]
    fn floor(self) -> Self {
        Zmm(unsafe { _mm512_roundscale_ps::<0x09>(self.0) })
    }
    #[inline(always)]
    fn lt(self, other: Self) -> ZmmMask {
        self.cmp::<_CMP_LT_OQ>(other)
    }
    #[inline(always)]
    fn le(self, other: Self) -> ZmmMask {
        self.cmp::<_CMP_LE_OQ>(other)
    }
    #[inline(always)]
    fn gt(self, other: Self) -> ZmmMask {
        self.cmp::<_CMP_GT_OQ>(other)
    }
    #[inline(always)]
    fn ge(self, other: Self) -> ZmmMask {
        self.cmp::<_CMP_GE_OQ>(other)
    }
    #[inline(always)]
    fn eq(self, other: Self) -> ZmmMask {
        self.cmp::<_CMP_EQ_OQ>(other)
    }
    #[inline(always)]
    fn is_finite(self) -> ZmmMask {
        self.abs().lt(Zmm::splat(f32::INFINITY))
    }
    #[inline(always)]
    fn select(mask: ZmmMask, if_true: Self, if_false: Self) -> Self {
        Zmm(unsafe { _mm512_mask_blend_ps(mask.0, if_false.0, if_true.0) })
    }
    #[inline(always)]
    fn any(mask: ZmmMask) -> bool {
        mask.0 != 0
    }
    #[inline(always)]
    fn all(mask: ZmmMask) -> bool {
        mask.0 == u16::MAX
    }
}

impl Bits for Zmm {
    /// As `f32`'s, lane by lane in integer registers.
    #[inline(always)]
    fn exponent_split(self) -> (Self, Self) {
        unsafe {
            let b = _mm512_castps_si512(self.0);
            let biased = _mm512_and_si512(
                _mm512_srli_epi32::<{ binary32::MANTISSA_BITS }>(b),
                _mm512_set1_epi32(binary32::EXPONENT_MASK as i32),
            );
            let two_pow_plus_biased = _mm512_castsi512_ps(_mm512_or_si512(
                biased,
                _mm512_set1_epi32(binary32::TWO_POW_MANTISSA_BITS as i32),
            ));
            let e = _mm512_sub_ps(
                two_pow_plus_biased,
                _mm512_set1_ps(binary32::EXPONENT_OFFSET),
            );
            let fraction = _mm512_and_si512(b, _mm512_set1_epi32(binary32::FRACTION_MASK as i32));
            let m = _mm512_or_si512(fraction, _mm512_set1_epi32(binary32::ONE_BITS as i32));
            (Zmm(_mm512_castsi512_ps(m)), Zmm(e))
        }
    }
    #[inline(always)]
    fn ldexp(self, e: Self) -> Self {
        unsafe {
            let biased = _mm512_castps_si512(_mm512_add_ps(
                e.0,
                _mm512_set1_ps(binary32::EXPONENT_OFFSET),
            ));
            let p = _mm512_slli_epi32::<{ binary32::MANTISSA_BITS }>(biased);
            Zmm(_mm512_mul_ps(self.0, _mm512_castsi512_ps(p)))
        }
    }
    /// The bit trick of `f32` (not `vrsqrt14ps`), so that [`crate::fast::rsqrt`] and the
    /// [`crate::fast::NewtonSqrt`] policies give the bits of [`super::F32Fma`].
    #[inline(always)]
    fn rsqrt_estimate(self) -> Self {
        unsafe {
            let b = _mm512_castps_si512(self.0);
            let y = _mm512_sub_epi32(
                _mm512_set1_epi32(binary32::RSQRT_MAGIC as i32),
                _mm512_srli_epi32::<1>(b),
            );
            Zmm(_mm512_castsi512_ps(y))
        }
    }
    /// `vrsqrt14ps` and one Newton step (see [`Bits::sqrt_rsqrt_refined`]).
    #[inline(always)]
    fn sqrt_rsqrt_refined(self) -> (Self, Self) {
        unsafe {
            // Inputs below the smallest normal are raised to it for the estimate: √0 = 0·y
            // = 0, and 1/√0 is a large finite value (as `fast::rsqrt`), without a select.
            let x = self.0;
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
            (Zmm(sqrt), Zmm(_mm512_fmadd_ps(h, e, y)))
        }
    }
    /// `vrcp14ps` and one correction step (see [`Bits::div_refined`]).
    #[inline(always)]
    fn div_refined(self, d: Self) -> Self {
        unsafe {
            let r = _mm512_rcp14_ps(d.0);
            // q = n·r ≈ n/d (1 + ε); the remainder n − q·d is exact to one rounding by the
            // FMA, and q + remainder·r removes the first-order error (Markstein's step).
            let q = _mm512_mul_ps(self.0, r);
            let rem = _mm512_fnmadd_ps(q, d.0, self.0);
            Zmm(_mm512_fmadd_ps(rem, r, q))
        }
    }
}

/// The mask of the first `min(n, 16)` lanes.
#[inline(always)]
pub(crate) fn first_lanes(n: usize) -> ZmmMask {
    ZmmMask(if n >= 16 { u16::MAX } else { (1u16 << n) - 1 })
}

/// Lanes `i .. i + 16` of `x` where `mask` is set, zero elsewhere.
///
/// # Safety
///
/// The CPU has AVX-512F, and every masked lane `i + j` is within `x`.
#[inline(always)]
pub(crate) unsafe fn load(x: &[f32], i: usize, mask: ZmmMask) -> Zmm {
    unsafe { Zmm(_mm512_maskz_loadu_ps(mask.0, x.as_ptr().add(i))) }
}

/// Writes the masked lanes of `v` to `x[i ..]`.
///
/// # Safety
///
/// As [`load`].
#[inline(always)]
pub(crate) unsafe fn store(x: &mut [f32], i: usize, mask: ZmmMask, v: Zmm) {
    unsafe { _mm512_mask_storeu_ps(x.as_mut_ptr().add(i), mask.0, v.0) }
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
            let (s, r) = Zmm::from_array(c.try_into().unwrap()).sqrt_rsqrt_refined();
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
            let q = Zmm::from_array(cn.try_into().unwrap())
                .div_refined(Zmm::from_array(cd.try_into().unwrap()));
            for j in 0..16 {
                e = e.max(ulps(q.lane(j), f64::from(cn[j]) / f64::from(cd[j])));
            }
        }
        e
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
        let zero = unsafe { sqrt_errors_at_zero() };
        assert_eq!(zero.0, 0.0);
        assert!(zero.1.is_finite() && zero.1 > 1e18);
    }

    #[target_feature(enable = "avx512f,avx512vl")]
    fn sqrt_errors_at_zero() -> (f32, f32) {
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
        // denominator mantissa of [1, 2) against a fixed numerator.
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

    /// `model` on `Zmm` and on `F32Fma` at `n` pairs: every lane bit for bit.
    #[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
    fn same_bits<B, const N: usize>(model: &B, n: usize) -> usize
    where
        B: Splat,
        B::On<Zmm>: Brdf<Zmm, N>,
        B::On<F32Fma>: Brdf<F32Fma, N>,
    {
        let (wide, fused) = (model.splat::<Zmm>(), model.splat::<F32Fma>());
        let dir = |u: f64, v: f64| {
            let (c, phi) = (u, v * core::f64::consts::TAU);
            let s = (1.0 - c * c).sqrt();
            [(s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32]
        };
        let mut compared = 0;
        for k in 0..n {
            let g = 0.618_033_988_749_894_9_f64;
            let ds: [[[f32; 3]; 2]; 16] = core::array::from_fn(|j| {
                let i = (16 * k + j) as f64;
                let grazing = if (16 * k + j) % 13 == 0 { 0.0 } else { 1.0 };
                [
                    dir(grazing * (i * g).fract(), (i * g * g).fract()),
                    dir((i * 0.754_877_666).fract(), (i * 0.569_840_290).fract()),
                ]
            });
            let lanes = |w: usize, a: usize| Zmm::from_fn(|j| ds[j][w][a]);
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

    /// Without the estimates, `Zmm` is `F32Fma` lane by lane: `+ − × ÷ √`, `mul_add`,
    /// `min`/`max`, selects (GGX, the exact conductor, Oren-Nayar) and the per-lane `pow`
    /// (the classic Blinn-Phong, at a grazing-heavy set of pairs).
    #[test]
    fn zmm_models_equal_f32fma_bit_for_bit() {
        if !avx512() {
            eprintln!("no AVX-512 on this CPU: skipped");
            return;
        }
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
        // SAFETY: AVX-512F/VL checked above (FMA and AVX2 come with them).
        let n = unsafe {
            same_bits(&ggx, 256)
                + same_bits(&gold, 256)
                + same_bits(&oren_nayar, 256)
                + same_bits(&phong, 256)
        };
        assert_eq!(n, 256 * 16 * 8);
    }
}
