//! Fast approximations of `exp2`, `log2`, `pow` and `1/√x`, each with a measured error bound.
//!
//! Every function here is written once, generic over [`Real`], branch-free, and uses only
//! `+ − × ÷`, `mul_add`, `min`/`max`, [`Real::select`] and the bit primitives
//! [`Bits::exponent_split`], [`Bits::ldexp`] and [`Bits::rsqrt_estimate`] — no library call.
//! So the `f32` instantiation inside a loop over a slice auto-vectorizes (see
//! `benches/fast.rs`), and the SIMD lanes run the very same arithmetic: a lane and the scalar of
//! the same precision agree bit for bit except for [`rsqrt`] (the `f32` lanes start from the
//! hardware estimate, the `f32` scalar from a bit trick).
//!
//! Models take these as compile-time policies, so a material pays only for the accuracy it
//! asks for: [`PowFn`] ([`ExactPow`] or [`FastPow`]) for the Phong-family lobes, and
//! [`SqrtFn`] ([`ExactSqrt`] or [`NewtonSqrt`]) for the half-vector length and normalization.
//!
//! # Method
//!
//! * **Range reduction** (J.-M. Muller, *Elementary Functions: Algorithms and Implementation*,
//!   3rd ed., Birkhäuser 2016, ch. 11). `exp2`: `x = n + f` with `n = ⌊x⌋`, `f ∈ [0, 1)`, so
//!   `2ˣ = 2ⁿ · 2ᶠ` where `2ⁿ` is built in the exponent field ([`Bits::ldexp`]). `log2`:
//!   `x = m · 2ᵉ` ([`Bits::exponent_split`]), then `m ∈ [√2/2, √2)` by moving a factor 2
//!   between `m` and `e`, so `log₂ x = e + log₂(1 + u)` with `u = m − 1 ∈ [−0.293, 0.415)`
//!   (computed exactly, Sterbenz).
//! * **Polynomials.** `2ᶠ ≈ 1 + f·q(f)` and `log₂(1 + u) ≈ u·q(u)`, with `q` the weighted
//!   minimax approximation that minimises the maximum **relative** error of the whole
//!   expression, found by the Remez exchange algorithm (E. Ya. Remez, 1934; Muller ch. 3;
//!   L. N. Trefethen, *Approximation Theory and Approximation Practice*, SIAM 2013, ch. 10). The
//!   factored forms make `exp2(0) = 1`, `exp2(n) = 2ⁿ` for integer `n` and `log2(1) = 0`
//!   exactly, and therefore `pow(x, 0) = pow(1, y) = 1`. The fit runs in `f64` on a grid of
//!   2·10⁵ points until the levelled error equioscillates to 10⁻⁹; `tests/fast.rs` re-runs it
//!   and compares with [`EXP2_Q`] and [`LOG2_Q`]. No coefficient table was copied from
//!   elsewhere.
//! * **`pow(x, y) = exp2(y · log₂ x)`.** An absolute error `δ` of `log₂ x` becomes a relative
//!   error `ln 2 · |y| · δ` of the result, and `|δ| ≤ ε_log · |log₂ x|`, so
//!
//!   ```text
//!   |pow − xʸ| / xʸ  ≲  ε_exp + ln 2 · |t| · (ε_log + k·u),     t = y · log₂ x
//!   ```
//!
//!   where `u` is the unit roundoff (2⁻²⁴ for `f32`, 2⁻⁵³ for `f64`) and `k ≈ 2–3` counts the
//!   roundings of `log₂ x` and of the product `y · log₂ x`. The error grows linearly with
//!   `|t| = |log₂ result|`; for `f32` the rounding term alone is `≈ 10⁻⁵` at `|t| = 100`
//!   (results near 10⁻³⁰), a floor no polynomial order removes (`std`'s `powf` avoids it by
//!   working in double precision internally).
//! * **`1/√x`**: an estimate ([`Bits::rsqrt_estimate`]) refined by Newton–Raphson steps
//!   `y ← y·(3/2 − x·y²/2)`, each of which squares the relative error (`e ← −(3/2)e² − e³/2`).
//!
//! # Error bounds
//!
//! Maximum relative errors. "minimax" is the Remez level in exact arithmetic; the stated bounds
//! add rounding (`u` = 2⁻²⁴ for `f32`, 2⁻⁵³ for `f64`): `exp2`: `ε_D + 2u` over every normal
//! result (`x ∈ [−126, 128)` / `[−1022, 1024)`); `log2`: `ε_D + 4u` over all positive
//! normal numbers. Measured maxima on 10⁶-point grids (`tests/fast.rs`):
//!
//! ```text
//! exp2<D>   minimax    f32 measured   f64 measured      log2<D>  minimax    f32 measured   f64 measured
//!   2       2.05e-3    2.05e-3        2.05e-3             2      1.98e-2    1.98e-2        1.98e-2
//!   3       8.56e-5    8.57e-5        8.56e-5             3      2.55e-3    2.55e-3        2.55e-3
//!   4       2.90e-6    2.97e-6        2.90e-6             4      3.51e-4    3.51e-4        3.51e-4
//!   5       8.23e-8    1.66e-7        8.23e-8             5      5.02e-5    5.03e-5        5.02e-5
//!   6       2.01e-9    1.00e-7        2.01e-9             6      7.39e-6    7.51e-6        7.39e-6
//!   7       4.32e-11   9.06e-8        4.32e-11            7      1.11e-6    1.22e-6        1.11e-6
//!   8       8.26e-13   9.06e-8        8.26e-13            8      1.69e-7    3.38e-7        1.69e-7
//!                                                         9      2.61e-8    1.79e-7        2.61e-8
//!                                                        10      4.08e-9    1.51e-7        4.08e-9
//!                                                        11      6.42e-10   1.65e-7        6.42e-10
//!                                                        12      1.02e-10   1.52e-7        1.02e-10
//! ```
//!
//! `f32` stops improving at degree 6 for `exp2` and 9 for `log2` (rounding).
//!
//! [`pow`]`<L, E>` obeys `(ε_E + 2u) + ln 2·|t|·(ε_L + 5u)` with `t = y·log₂ x`; measured on
//! bases in `[10⁻³⁰, 1)` with exponents putting `|t|` at each value (results ≥ 10⁻³⁰):
//!
//! ```text
//!                 |t| =   1         10        30        66.4      99.6
//! pow<6,3>   f32        9.1e-5    1.4e-4    2.4e-4    3.8e-4    5.9e-4
//! pow<8,4>   f32        3.2e-6    5.2e-6    9.4e-6    1.7e-5    2.2e-5
//!            f64        3.0e-6    4.1e-6    6.4e-6    1.1e-5    1.3e-5
//! pow<9,4>   f32        3.0e-6    4.0e-6    5.9e-6    1.1e-5    1.3e-5
//!            f64        2.9e-6    3.1e-6    3.4e-6    4.1e-6    3.4e-6     ← pow_phong (f64)
//! pow<9,5>   f32        2.3e-7    1.2e-6    3.1e-6    7.9e-6    1.1e-5     ← pow_phong (f32)
//!            f64        1.0e-7    2.6e-7    6.3e-7    1.2e-6    1.9e-6
//! pow<12,8>  f32        1.5e-7    1.1e-6    3.0e-6    8.5e-6    1.0e-5
//!            f64        7.1e-11   7.1e-10   2.1e-9    4.7e-9    7.0e-9
//! ```
//!
//! The Blinn-Phong target (10⁻⁵ for `(n·h)ˢ` with results above 10⁻³⁰) is met most cheaply by
//! `pow<9, 4>` in `f64`; in `f32` by `pow<9, 5>` down to results of 10⁻²⁰ only — see
//! [`pow_phong`].
//!
//! [`rsqrt`]`<N>` (exhaustive over the `f32` values of `[1, 4)`, where the error repeats):
//!
//! ```text
//! Newton steps N               0          1          2          3
//! bit trick, f32               3.44e-2    1.75e-3    4.74e-6    1.5e-7  (≈ 2.5 ULP)
//! bit trick, f64 and f64x4     3.44e-2    1.75e-3    4.60e-6    3.2e-11
//! rsqrtps, f32x4/f32x8/f32x16  2.6e-4     2.2e-7     1.3e-7     1.0e-7  (spec: 3.7e-4 at N = 0)
//! ```
//!
//! # Cost
//!
//! Throughput over 4096 elements (`benches/fast.rs`, baseline x86-64 build, i.e. SSE2 without
//! FMA, on a shared 2-core machine: ±20 %), in millions of elements per second, and the ratio
//! to the exact path (`std` on scalars, `wide`'s kernels on lanes). The "f32" column is a loop
//! over a slice, which LLVM auto-vectorizes with SSE2 for the fast paths (not for `std`'s
//! library calls).
//!
//! ```text
//!                f32          f64          f32x4        f32x8        f32x16       f64x4
//! exp2 exact     120          200          203          241          250          123
//! exp2<3>        783 (6.5×)   377 (1.9×)   685 (3.4×)   548 (2.3×)   613 (2.5×)   212 (1.7×)
//! exp2<5>        492 (4.1×)   238 (1.2×)   287 (1.4×)   336 (1.4×)   458 (1.8×)   175 (1.4×)
//! exp2<7>        400 (3.3×)   198 (1.0×)   280 (1.4×)   245 (1.0×)   357 (1.4×)   137 (1.1×)
//! log2 exact     129           85          197          219          238           95
//! log2<4>        442 (3.4×)   207 (2.4×)   516 (2.6×)   363 (1.7×)   256 (1.1×)   190 (2.0×)
//! log2<6>        518 (4.0×)   204 (2.4×)   399 (2.0×)   409 (1.9×)   499 (2.1×)   206 (2.2×)
//! log2<9>        232 (1.8×)   111 (1.3×)   238 (1.2×)   184 (0.8×)   246 (1.0×)    87 (0.9×)
//! pow exact       54           29           70          117          107           33
//! pow<4,3>       208 (3.8×)   106 (3.7×)   129 (1.9×)   199 (1.7×)   281 (2.6×)   101 (3.1×)
//! pow_phong      149 (2.7×)    98 (3.4×)    98 (1.4×)   105 (0.9×)   147 (1.4×)    93 (2.8×)
//! pow<12,8>      152 (2.8×)    44 (1.5×)    57 (0.8×)    88 (0.7×)   261 (2.4×)    79 (2.4×)
//! 1/√x exact    1093          262          849          839          873          265
//! rsqrt<0>      7767 (7.1×)  3160 (12×)   4984 (5.9×)  5436 (6.5×)  2253 (2.6×)  1800 (6.8×)
//! rsqrt<1>      2757 (2.5×)  1168 (4.5×)  1444 (1.7×)  1813 (2.2×)  1343 (1.5×)   929 (3.5×)
//! rsqrt<2>      1582 (1.4×)   700 (2.7×)  1052 (1.2×)  1435 (1.7×)  1004 (1.1×)   305 (1.2×)
//! ```
//!
//! Inside `#[target_feature(enable = "avx2,fma")]` the `f32` slice loop of [`pow_phong`]
//! compiles to 8-wide `ymm` code with no calls (checked with `objdump`): 305 Melem/s against
//! 164 for the SSE2 loop and 61–72 for `std`'s `powf` (4.2–5×); `rsqrt<1>` reaches
//! 5.4 Gelem/s. On `f32`, [`Real::mul_add`] does not fuse there (its `cfg` is fixed when the
//! crate is compiled), so that loop uses separate multiplies and adds; on
//! [`F32Fma`](crate::real::F32Fma), as in the [`crate::batch`] kernels, it is one `vfmadd`.
//! Build with `-C target-feature=+fma` (or `target-cpu`) to fuse everywhere.
//!

#[cfg(doc)]
use crate::real::Bits;
use crate::real::Real;

/// Coefficients of `q` in `2ᶠ ≈ 1 + f·q(f)`, `f ∈ [0, 1]`, by polynomial degree `D` of
/// `1 + f·q(f)` (index `D`, `2 ≤ D ≤ 8`; `q` has degree `D − 1`, coefficients by increasing
/// power). Weighted Remez fit minimising `max |(1 + f·q(f)) / 2ᶠ − 1|` (see the module docs);
/// the comment on each row is that minimax error in exact arithmetic.
pub const EXP2_Q: [&[f64]; 9] = [
    &[],
    &[],
    // degree 2: minimax relative error 2.053e-3 (in exact arithmetic)
    &[0.6659609408960432, 0.3299324044232817],
    // degree 3: minimax relative error 8.559e-5 (in exact arithmetic)
    &[0.6951167864112018, 0.22764499121162354, 0.07706704198819887],
    // degree 4: minimax relative error 2.896e-6 (in exact arithmetic)
    &[
        0.6930448449030171,
        0.24128020475132397,
        0.05224247422380382,
        0.013426684271564621,
    ],
    // degree 5: minimax relative error 8.227e-8 (in exact arithmetic)
    &[
        0.6931513118046011,
        0.24016445015508717,
        0.05579991310375669,
        0.009017030322410755,
        0.0018671300698925829,
    ],
    // degree 6: minimax relative error 2.012e-9 (in exact arithmetic)
    &[
        0.6931470444433242,
        0.2402293055522308,
        0.05548528061866247,
        0.009675451566861773,
        0.0012467846446805688,
        0.00021612914951617642,
    ],
    // degree 7: minimax relative error 4.319e-11 (in exact arithmetic)
    &[
        0.6931471843442177,
        0.2402264051163994,
        0.055505023019146775,
        0.00961428317569642,
        0.001341901566820316,
        0.00014377207601800658,
        2.1430615316655263e-5,
    ],
    // degree 8: minimax relative error 8.257e-13 (in exact arithmetic)
    &[
        0.6931471804690079,
        0.24022651005787518,
        0.055504072974575235,
        0.009618326019716754,
        0.00133276021813776,
        0.00015507427998055447,
        1.421731903982779e-5,
        1.858660015387992e-6,
    ],
];

/// Coefficients of `q` in `log₂(1 + u) ≈ u·q(u)`, `u ∈ [√2/2 − 1, √2 − 1]`, by polynomial
/// degree `D` of `u·q(u)` (index `D`, `2 ≤ D ≤ 12`; coefficients by increasing power).
/// Weighted Remez fit minimising `max |u·q(u) / log₂(1 + u) − 1|`; the comment on each row is
/// that minimax error in exact arithmetic.
pub const LOG2_Q: [&[f64]; 13] = [
    &[],
    &[],
    // degree 2: minimax relative error 1.980e-2 (in exact arithmetic)
    &[1.4703038623683047, -0.6931078876569339],
    // degree 3: minimax relative error 2.552e-3 (in exact arithmetic)
    &[1.4441770472400959, -0.7511347303749022, 0.44960968895099784],
    // degree 4: minimax relative error 3.507e-4 (in exact arithmetic)
    &[
        1.4422704322258468,
        -0.7242969531948958,
        0.5112727403022367,
        -0.32777077071611316,
    ],
    // degree 5: minimax relative error 5.019e-5 (in exact arithmetic)
    &[
        1.4426462509044038,
        -0.7205549723264425,
        0.48530651469062963,
        -0.3908924424364722,
        0.2547518727228882,
    ],
    // degree 6: minimax relative error 7.386e-6 (in exact arithmetic)
    &[
        1.44270161787801,
        -0.7212063897837675,
        0.47981185535632315,
        -0.36649170488412064,
        0.3181999099389237,
        -0.20619105455014242,
    ],
    // degree 7: minimax relative error 1.109e-6 (in exact arithmetic)
    &[
        1.442696447258849,
        -0.7213635760042781,
        0.48062676828454887,
        -0.35937164358059964,
        0.2956995207290535,
        -0.26932021674185963,
        0.17162456175094798,
    ],
    // degree 8: minimax relative error 1.693e-7 (in exact arithmetic)
    &[
        1.4426949619871985,
        -0.7213527880630637,
        0.4809232423061726,
        -0.36023963972067924,
        0.2870986995231553,
        -0.24887686470383888,
        0.2340423705821049,
        -0.1458116886943594,
    ],
    // degree 9: minimax relative error 2.614e-8 (in exact arithmetic)
    &[
        1.4426950036524329,
        -0.721347346801593,
        0.480910642941089,
        -0.36070368294248906,
        0.28791624833378104,
        -0.2389448187578229,
        0.21571560121113428,
        -0.2072697618148837,
        0.1258370512135327,
    ],
    // degree 10: minimax relative error 4.079e-9 (in exact arithmetic)
    &[
        1.4426950408299362,
        -0.7213473515005779,
        0.4808982410576547,
        -0.3606966494118864,
        0.28856740838751715,
        -0.23961740351215607,
        0.2046006196197015,
        -0.19106275495792877,
        0.18617496208071357,
        -0.10994955118048076,
    ],
    // degree 11: minimax relative error 6.416e-10 (in exact arithmetic)
    &[
        1.4426950417996438,
        -0.7213475156601212,
        0.48089788920890064,
        -0.36067414930719627,
        0.2885761734235317,
        -0.24046720907281385,
        0.20504348947416956,
        -0.17890870262948108,
        0.17205684558789172,
        -0.1690633936904644,
        0.09703389304742974,
    ],
    // degree 12: minimax relative error 1.016e-10 (in exact arithmetic)
    &[
        1.4426950409393455,
        -0.7213475252132125,
        0.4808983207294964,
        -0.36067280054701384,
        0.2885406435492669,
        -0.2405041741031484,
        0.2060962566472518,
        -0.17904695291721762,
        0.15900149204046538,
        -0.15698225363697477,
        0.15485755252771002,
        -0.0863460332985843,
    ],
];

/// `true` for `f32` lanes, `false` for `f64` lanes (a property of the type, not of a value).
#[inline(always)]
fn single<R: Real>() -> bool {
    core::mem::size_of::<R::Scalar>() == 4
}

/// Smallest positive normal number of the lane precision.
#[inline(always)]
fn min_positive<R: Real>() -> R {
    R::from_f64(if single::<R>() {
        f32::MIN_POSITIVE as f64
    } else {
        f64::MIN_POSITIVE
    })
}

/// The `j`-th of `K` Chebyshev–Gauss nodes, `x_j = cos(π (j + ½)/K)` (`j = 0 … K − 1`,
/// descending from near 1): where the fitted tables of the crate
/// ([`crate::fresnel::FittedConductor`], `models::AlbedoFit`) sample their function.
pub(crate) fn chebyshev_node(j: usize, k: usize) -> f64 {
    Real::cos(core::f64::consts::PI * (j as f64 + 0.5) / k as f64)
}

/// The coefficients `c_i` of the degree-`K − 1` polynomial `Σ c_i T_i(x)` that interpolates
/// `values[j]` at the nodes [`chebyshev_node`]`(j, K)`, by the discrete orthogonality of the
/// `T_i` there (J. C. Mason, D. C. Handscomb, *Chebyshev Polynomials*, 2003, §6.3):
///
/// ```text
/// c_i = (2/K) Σ_j values[j] · cos(π i (j + ½)/K),   c_0 halved
/// ```
pub(crate) fn chebyshev_coefficients<const K: usize>(values: &[f64; K]) -> [f64; K] {
    let k = K as f64;
    let mut coeffs: [f64; K] = core::array::from_fn(|i| {
        let mut s = 0.0;
        for (j, v) in values.iter().enumerate() {
            let angle = core::f64::consts::PI * i as f64 * (j as f64 + 0.5) / k;
            s += v * Real::cos(angle);
        }
        2.0 * s / k
    });
    coeffs[0] *= 0.5;
    coeffs
}

/// `c[0] + c[1]·x + … + c[k]·x^k` by Horner's rule (the coefficient slice is a constant, so
/// the loop unrolls).
#[inline(always)]
fn horner<R: Real>(c: &[f64], x: R) -> R {
    let mut acc = R::from_f64(c[c.len() - 1]);
    for &k in c[..c.len() - 1].iter().rev() {
        acc = acc.mul_add(x, R::from_f64(k));
    }
    acc
}

/// `c[0] + c[1]·x + … + c[k]·x^k` by second-order Horner: the pairs `c[2j] + c[2j+1]·x`
/// (independent of each other) combined by Horner's rule in `x²`. One more multiply than
/// Horner, and a dependency chain about half as long (`⌈(k+1)/2⌉` multiply-adds instead of
/// `k`) — what bounds a batch kernel, whose out-of-order window holds too few iterations of a
/// long chain. Used by [`exp2`]; [`log2`] keeps [`horner`], whose smaller rounding `pow`
/// needs (for `f32` results near 1e-20, `pow_phong` is at the rounding floor: with the
/// second-order `log2` it measured 9.9e-6 against 7.9e-6). The coefficient slice is a
/// constant, so the loop unrolls.
#[inline(always)]
fn horner2<R: Real>(c: &[f64], x: R) -> R {
    let n = c.len();
    let x2 = x * x;
    let pair = |j: usize| {
        let lo = R::from_f64(c[2 * j]);
        if 2 * j + 1 < n {
            R::from_f64(c[2 * j + 1]).mul_add(x, lo)
        } else {
            lo
        }
    };
    let m = n.div_ceil(2);
    let mut acc = pair(m - 1);
    for j in (0..m - 1).rev() {
        acc = acc.mul_add(x2, pair(j));
    }
    acc
}

/// `⌊x⌋` for `|x| ≤ 2²²` (`f32`) / `2⁵¹` (`f64`) without a library call: adding and removing
/// `1.5·2ᵖ` (`p` = fraction bits) rounds to the nearest integer in the current rounding mode,
/// then one `select` turns round-to-nearest into floor.
#[inline(always)]
fn floor_small<R: Real>(x: R) -> R {
    let magic = R::from_f64(if single::<R>() {
        12_582_912.0
    } else {
        6_755_399_441_055_744.0
    });
    let r = (x + magic) - magic;
    R::select(r.gt(x), r - R::one(), r)
}

/// `2ˣ` by a degree-`D` minimax polynomial, `2 ≤ D ≤ 8`.
///
/// ```text
/// n = ⌊x⌋,  f = x − n ∈ [0, 1),   exp2(x) = (1 + f·q_D(f)) · 2ⁿ      (q_D: EXP2_Q[D])
/// ```
///
/// Domain and special values: relative error bound (table in the module docs) for
/// `x ∈ [−126, 128)` (`f32`) / `[−1022, 1024)` (`f64`), i.e. every normal result. Below,
/// results flush to `+0` (the exact value is subnormal or underflows, `< 2⁻¹²⁶` / `2⁻¹⁰²²`);
/// `x = −∞` gives `0`. At and above `128` / `1024`, and `+∞`, the result is `+∞`; the exact
/// `2ˣ` is finite up to `x < 128`, so within `ε_D/ln 2` below the threshold the approximation
/// may already overflow. Integers `x` give `2ˣ` exactly (`exp2(0) = 1`). NaN gives an
/// unspecified value. Never NaN for non-NaN input.
///
/// Cost: `D` multiply-adds plus ~12 cheap operations (see the module docs for throughput).
///
/// # Examples
///
/// ```
/// use brdf::fast;
/// let y = fast::exp2::<5, f32>(-3.3);
/// assert!((y / (-3.3f32).exp2() - 1.0).abs() < 2e-7);
/// assert_eq!(fast::exp2::<3, f32>(-1000.0), 0.0); // flushes, never garbage
/// assert_eq!(fast::exp2::<3, f64>(10.0), 1024.0); // exact at integers
/// ```
#[inline]
#[must_use]
pub fn exp2<const D: usize, R: Real>(x: R) -> R {
    let c: &'static [f64] = const {
        assert!(D >= 2 && D <= 8, "fast::exp2 has degrees 2..=8");
        EXP2_Q[D]
    };
    // Clamping keeps n inside [−127, 128]: ldexp encodes 2⁻¹²⁷ as 0 (flush) and 2¹²⁸ as ∞.
    let (lo, hi) = if single::<R>() {
        (-127.0, 128.0)
    } else {
        (-1023.0, 1024.0)
    };
    let xc = x.max(R::from_f64(lo)).min(R::from_f64(hi));
    let n = floor_small(xc);
    let f = xc - n;
    horner2(c, f).mul_add(f, R::one()).ldexp(n)
}

/// `log₂ x` by a degree-`D` minimax polynomial, `2 ≤ D ≤ 12`.
///
/// ```text
/// x = m·2ᵉ, m ∈ [√2/2, √2),  u = m − 1,   log2(x) = e + u·q_D(u)      (q_D: LOG2_Q[D])
/// ```
///
/// Domain: positive normal `x` (`f32`: `[1.18·10⁻³⁸, 3.4·10³⁸]`), where the relative error
/// is bounded by the table in the module docs (“Error bounds”) and the absolute error by half
/// of it plus the rounding of the result (since
/// `|u·q| ≤ 1/2`). `log2(1) = 0` and `log2(2ᵏ) = k` exactly. Inputs below the smallest normal
/// — `0`, subnormals (treated as zero, like a GPU's denormals-are-zero) and negative numbers —
/// give `−∞`; `+∞` gives `128` / `1024` and NaN an unspecified value.
///
/// Cost: `D − 1` multiply-adds, one multiply-add for `e + u·q`, ~8 cheap operations.
///
/// # Examples
///
/// ```
/// use brdf::fast;
/// let l = fast::log2::<9, f64>(0.3);
/// assert!((l / 0.3f64.log2() - 1.0).abs() < 3e-8);
/// assert_eq!(fast::log2::<3, f32>(8.0), 3.0);
/// assert_eq!(fast::log2::<3, f32>(0.0), f32::NEG_INFINITY);
/// ```
#[inline]
#[must_use]
pub fn log2<const D: usize, R: Real>(x: R) -> R {
    let c: &'static [f64] = const {
        assert!(D >= 2 && D <= 12, "fast::log2 has degrees 2..=12");
        LOG2_Q[D]
    };
    let (m, e) = x.exponent_split();
    let big = m.gt(R::from_f64(core::f64::consts::SQRT_2));
    let m = R::select(big, m * R::from_f64(0.5), m);
    let e = R::select(big, e + R::one(), e);
    let u = m - R::one();
    let l = u.mul_add(horner(c, u), e);
    R::select(x.ge(min_positive::<R>()), l, R::from_f64(f64::NEG_INFINITY))
}

/// `xʸ = exp2(y · log₂ x)` from [`log2`] of degree `L` and [`exp2`] of degree `E`.
///
/// ```text
/// pow(x, y) = exp2_E(y · log2_L(x)),    pow(x, 0) = 1 (also 0⁰ = 1),   pow(0, y > 0) = 0
/// ```
///
/// Domain: `x ≥ 0` finite, `y` finite. The relative error grows with `|t| = |y·log₂ x|`
/// (`= |log₂ xʸ|`): see the bound and the measured table in the module docs. Results that
/// underflow (below the smallest normal) flush to `0`, results that overflow give `+∞`; `x = 0`
/// gives `0` for `y > 0` and `+∞` for `y < 0`; subnormal `x` counts as `0`. Exponents of any
/// size (10⁴, 10⁶, …) are fine: the product `y·log₂ x` saturates in [`exp2`]'s clamp, so the
/// result never becomes NaN or garbage. `x < 0` is outside the domain (treated as `0`).
///
/// For Blinn-Phong lobes `(n·h)ˢ`, [`pow_phong`] picks the cheapest degrees meeting a relative
/// error of 10⁻⁵ (see its docs).
///
/// # Examples
///
/// ```
/// use brdf::fast;
/// let v = fast::pow::<9, 4, f64>(0.99, 1000.0);
/// assert!((v / 0.99f64.powf(1000.0) - 1.0).abs() < 1e-5);
/// assert_eq!(fast::pow::<6, 3, f32>(0.0, 1e6), 0.0);
/// assert_eq!(fast::pow::<6, 3, f32>(0.0, 0.0), 1.0);
/// assert_eq!(fast::pow::<6, 3, f32>(0.5, 1e6), 0.0); // underflow flushes to zero
/// ```
#[inline]
#[must_use]
pub fn pow<const L: usize, const E: usize, R: Real>(x: R, y: R) -> R {
    pow_finish::<E, R>(pow_start::<L, R>(x, y), y)
}

/// The first stage of [`pow`]: `t = y · log2_L(x)`. `pow::<L, E>(x, y)` is exactly
/// `pow_finish::<E>(pow_start::<L>(x, y), y)`; the split lets a batch kernel run the two
/// halves of the dependency chain as separate passes (see [`crate::batch::Pipelined`]).
#[inline(always)]
#[must_use]
pub fn pow_start<const L: usize, R: Real>(x: R, y: R) -> R {
    y * log2::<L, R>(x)
}

/// The second stage of [`pow`]: `exp2_E(t)`, and `1` for `y = 0` (so `0⁰ = 1`).
#[inline(always)]
#[must_use]
pub fn pow_finish<const E: usize, R: Real>(t: R, y: R) -> R {
    R::select(y.eq(R::zero()), R::one(), exp2::<E, R>(t))
}

/// `1/√x` from [`Bits::rsqrt_estimate`] refined by `N` Newton–Raphson steps, `0 ≤ N ≤ 3`.
///
/// ```text
/// y₀ = rsqrt_estimate(x),   y_{k+1} = y_k · (3/2 − (x/2) · y_k²)
/// ```
///
/// Domain: positive normal finite `x`; inputs below the smallest normal (`0`, subnormals) are
/// raised to it, giving a large finite value (≈ 1.1·10¹⁹ for `f32`) instead of `∞`, so that
/// `v · rsqrt(v·v)` of a zero vector is `0`. Relative error bounds (table in the module docs)
/// depend on the start: the bit trick on `f32`/`f64`/[`f64x4`](crate::f64x4) scalars and lanes,
/// the hardware estimate on `f32` lanes; the two meet at ~1 ULP after two steps.
///
/// # Examples
///
/// ```
/// use brdf::fast;
/// let y = fast::rsqrt::<2, f32>(2.0);
/// assert!((y * 2.0f32.sqrt() - 1.0).abs() < 1e-6);
/// assert!(fast::rsqrt::<1, f32>(0.0).is_finite());
/// ```
#[inline(always)]
#[must_use]
pub fn rsqrt<const N: usize, R: Real>(x: R) -> R {
    const { assert!(N <= 3, "fast::rsqrt takes 0..=3 Newton steps") };
    let x = x.max(min_positive::<R>());
    let half_x = x * R::from_f64(0.5);
    let three_halves = R::from_f64(1.5);
    let mut y = x.rsqrt_estimate();
    for _ in 0..N {
        y = y * (-(half_x * y)).mul_add(y, three_halves);
    }
    y
}

/// The cheapest [`pow`] for Blinn-Phong lobes `(n·h)ˢ` with a relative error of 10⁻⁵:
/// base `x ∈ [10⁻³⁰, 1]`, exponent `y ∈ [0, 10⁴]`, results above 10⁻³⁰ (`|t| ≤ 99.7`).
///
/// ```text
/// f64: pow_phong(x, y) = pow::<9, 4>(x, y) = exp2₄(y · log2₉(x))
/// f32: pow_phong(x, y) = pow::<9, 5>(x, y) = exp2₅(y · log2₉(x))
/// ```
///
/// * `f64`: ≤ 10⁻⁵ (measured 4.6·10⁻⁶) for every result above 10⁻³⁰; no pair with fewer
///   than 13 coefficients does it ((8, 5) reaches 1.3·10⁻⁵, (9, 3) 8.6·10⁻⁵).
/// * `f32`: ≤ 10⁻⁵ for results above 10⁻²⁰ (`|t| ≤ 66.4`, measured 7.9·10⁻⁶) and ≤ 1.3·10⁻⁵
///   down to 10⁻³⁰. The target at 10⁻³⁰ is out of reach in single precision for every
///   degree: rounding `log₂ x` and `y·log₂ x` to `f32` alone costs ≈ 1.2·10⁻⁷·|t|
///   (degrees (12, 8) still measure 1.16·10⁻⁵ at `|t| = 99.6`).
///
/// The choice between the two is made on the lane type at compile time. Same domain and
/// special values as [`pow`].
///
/// # Examples
///
/// ```
/// use brdf::fast;
/// let (x, s) = (0.97_f64, 2000.0);
/// assert!((fast::pow_phong(x, s) / x.powf(s) - 1.0).abs() < 1e-5);
/// ```
#[inline(always)]
#[must_use]
pub fn pow_phong<R: Real>(x: R, y: R) -> R {
    FastPow::finish(FastPow::start(x, y), y)
}

/// How a model raises a cosine to its exponent, chosen at compile time (a type parameter of
/// the Phong-family models), so a scene pays for the accuracy it asks for.
///
/// * [`ExactPow`]: [`Real::pow`] — `std`/`libm` `powf` on scalars (≤ 1 ULP, a library call that
///   blocks auto-vectorization in the [`crate::batch`] kernels), wide's `powf` on lanes.
/// * [`FastPow`]: [`pow_phong`] — relative error ≤ 1e-5 for results ≥ 1e-20 (f32) and
///   everywhere in f64 (see the module docs), branch-free, no library call: it vectorizes.
pub trait PowFn: Copy + core::fmt::Debug + Default + Send + Sync + 'static {
    /// `xʸ` for `x ∈ [0, 1]`, `y ≥ 0` (`0⁰ = 1`): `finish(start(x, y), y)`.
    #[inline(always)]
    fn pow<R: Real>(x: R, y: R) -> R {
        Self::finish(Self::start(x, y), y)
    }

    /// The first half of `pow`'s dependency chain (for [`FastPow`]: `y · log₂ x`).
    fn start<R: Real>(x: R, y: R) -> R;

    /// The second half: `pow(x, y) = finish(start(x, y), y)`.
    fn finish<R: Real>(t: R, y: R) -> R;
}

/// [`PowFn`] through [`Real::pow`] (the library `powf`); its stages are the identity and
/// `powf` itself.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExactPow;

impl PowFn for ExactPow {
    #[inline(always)]
    fn start<R: Real>(x: R, _y: R) -> R {
        x
    }
    #[inline(always)]
    fn finish<R: Real>(t: R, y: R) -> R {
        t.pow(y)
    }
}

/// [`PowFn`] through [`pow_phong`] (polynomial, relative error ≤ 1e-5 on the Phong domain);
/// its stages are [`pow_start`] and [`pow_finish`] with `pow_phong`'s degrees.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FastPow;

impl PowFn for FastPow {
    #[inline(always)]
    fn start<R: Real>(x: R, y: R) -> R {
        pow_start::<9, R>(x, y)
    }
    #[inline(always)]
    fn finish<R: Real>(t: R, y: R) -> R {
        if single::<R>() {
            pow_finish::<5, R>(t, y)
        } else {
            pow_finish::<4, R>(t, y)
        }
    }
}

/// Coefficients of `q` in `sin(π r/2) ≈ r·q(r²)`, `r ∈ [−1/2, 1/2]`, for `f32` lanes (by
/// increasing power of `w = r²`; degree 7 in `r`): the interpolant at the 4 Chebyshev nodes
/// of `w ∈ [0, 1/4]`, relative error 3.4e-9 in exact arithmetic (`tests/sin_cos_2pi.rs`
/// re-runs the fit). See [`sin_cos_2pi`].
pub const SIN_2PI_Q32: [f64; 4] = [
    1.5707963219532366,
    -0.6459634776648107,
    0.07968021764774692,
    -0.004602149212783359,
];

/// Coefficients of `p` in `cos(π r/2) ≈ 1 + r²·p(r²)`, `r ∈ [−1/2, 1/2]`, for `f32` lanes
/// (degree 8 in `r`): the interpolant of `(cos(π√w/2) − 1)/w` at the 4 Chebyshev nodes of
/// `w ∈ [0, 1/4]`, relative error 2.7e-10 in exact arithmetic. See [`sin_cos_2pi`].
pub const COS_2PI_P32: [f64; 4] = [
    -1.2337005493742195,
    0.2536694103571154,
    -0.0208615283423014,
    0.0009067398987360607,
];

/// As [`SIN_2PI_Q32`] for `f64` lanes: 7 Chebyshev nodes, degree 13 in `r`, relative error
/// 4.6e-16 (at the `f64` resolution of the fit).
// The fit's leading coefficient rounds to π/2 itself (kept as fitted).
#[allow(clippy::approx_constant)]
pub const SIN_2PI_Q64: [f64; 7] = [
    1.5707963267948966,
    -0.6459640975062338,
    0.07969262624547682,
    -0.004681754122866753,
    0.0001604410829634379,
    -3.5984213064187592e-06,
    5.6063953992604314e-08,
];

/// As [`COS_2PI_P32`] for `f64` lanes: 7 Chebyshev nodes, degree 14 in `r`, relative error
/// 2.3e-16.
pub const COS_2PI_P64: [f64; 7] = [
    -1.23370055013617,
    0.25366950790107234,
    -0.02086348076438492,
    0.0009192602899097904,
    -2.5202142679288747e-05,
    4.713981320871853e-07,
    -6.732465753648521e-09,
];

/// `(sin 2πu, cos 2πu)` for `u ∈ [0, 1]` — the azimuth `φ = 2πu` of every sampler — with
/// no library call: branch-free, generic over [`Real`], so it vectorizes inside the
/// [`crate::batch`] kernels (`std`'s `sinf`/`cosf` are calls that keep a loop scalar).
///
/// ```text
/// k = round(4u) ∈ {0, 1, 2, 3, 4},   r = 4u − k ∈ [−1/2, 1/2]     (both exact)
/// 2πu = k·π/2 + x,   x = π r/2 ∈ [−π/4, π/4]
/// sin x ≈ r·q(r²),   cos x ≈ 1 + r²·p(r²)
/// (sin 2πu, cos 2πu) = (sin x, cos x), (cos x, −sin x), (−sin x, −cos x), (−cos x, sin x)
///                      for k mod 4 = 0, 1, 2, 3
/// ```
///
/// **Range reduction is exact** (J.-M. Muller, *Elementary Functions: Algorithms and
/// Implementation*, 3rd ed., Birkhäuser 2016, ch. 11): `4u` is a scaling by a power of two,
/// `k` is found by adding and removing `1.5·2ᵖ` (`p` = fraction bits), and `4u − k` is
/// exact (Sterbenz). A library `sin(2π·u)` instead rounds the product `2π·u` first (an
/// absolute error up to `ulp(2π)/2`, i.e. `2.4e-7` in `f32`), so this form is the more accurate
/// one near the zeros of `sin` and `cos` (relative accuracy is kept there: the result near
/// `u = 1/4` is `−sin(π r/2)` of a tiny exact `r`).
///
/// **Polynomials**: `q` and `p` interpolate at Chebyshev nodes of `w = r² ∈ [0, 1/4]`
/// ([`SIN_2PI_Q32`]/[`COS_2PI_P32`]: degrees 7 and 8 in `r` for `f32` lanes;
/// [`SIN_2PI_Q64`]/[`COS_2PI_P64`]: 13 and 14 for `f64` lanes, chosen on the lane type at
/// compile time), fitted in `f64` by `tests/sin_cos_2pi.rs`, which re-runs the fit and
/// compares. No coefficient table was copied.
///
/// **Measured error** (`tests/sin_cos_2pi.rs`, against an `f64` reference from the same
/// exact reduction): `f32`: ≤ 1.72 ULP of the correctly rounded value, absolute ≤ 8.8e-8, on
/// every 16th `f32` in `[0, 1]` and on every `f32` of `[0.24, 0.26]` (baseline build, unfused
/// `mul_add`); `f64`: absolute ≤ 2.2e-16 on 2·10⁷ points. `sin² + cos²` is within `2.1e-7`
/// (`f32`) / `4.4e-16` (`f64`) of 1.
/// Exact at `u = 0, 1/4, 1/2, 3/4, 1` (the zeros may be `−0`). Accurate (same bounds) on
/// `[−1/8, 9/8)`, where `k` stays in `{0, …, 4}`; outside, the quadrant is wrong.
///
/// # Examples
///
/// ```
/// use brdf::fast::sin_cos_2pi;
/// let (s, c) = sin_cos_2pi(0.1_f32);
/// assert!((s - 0.587_785_25).abs() < 9e-8 && (c - 0.809_017).abs() < 9e-8);
/// assert_eq!(sin_cos_2pi(0.25_f64), (1.0, 0.0));
/// ```
#[inline(always)]
#[must_use]
pub fn sin_cos_2pi<R: Real>(u: R) -> (R, R) {
    let magic = R::from_f64(if single::<R>() {
        12_582_912.0
    } else {
        6_755_399_441_055_744.0
    });
    let t = u * R::from_f64(4.0);
    let k = (t + magic) - magic;
    let r = t - k;
    let w = r * r;
    let (sin, cos) = if single::<R>() {
        (
            r * horner(&SIN_2PI_Q32, w),
            horner(&COS_2PI_P32, w).mul_add(w, R::one()),
        )
    } else {
        (
            r * horner(&SIN_2PI_Q64, w),
            horner(&COS_2PI_P64, w).mul_add(w, R::one()),
        )
    };
    // k ∈ {0, …, 4}: odd k swaps sin and cos; cos is negated for k ∈ {1, 2}, sin for {2, 3}.
    let swap = (k - R::from_f64(2.0)).abs().eq(R::one());
    let neg_cos = (k - R::from_f64(1.5)).abs().lt(R::one());
    let neg_sin = (k - R::from_f64(2.5)).abs().lt(R::one());
    let (s, c) = (R::select(swap, cos, sin), R::select(swap, sin, cos));
    (R::select(neg_sin, -s, s), R::select(neg_cos, -c, c))
}

/// How a model takes the length of its half vector `h = wi + wo` and normalizes it —
/// `|h| = √(h·h)` and `1/|h|` — chosen at compile time (a type parameter of
/// [`crate::models::CookTorrance`] and [`crate::models::ClassicBlinnPhong`]), so a scene pays
/// for the accuracy it asks for.
///
/// * [`ExactSqrt`]: the correctly rounded `√x` and `1/√x` (a square root and a division).
/// * [`NewtonSqrt`]`<STEPS>`: [`rsqrt`]`::<STEPS>(x)`, the estimate of
///   [`Bits::rsqrt_estimate`] refined by `STEPS` Newton steps, and `√x = x · rsqrt(x)`:
///   multiplies and adds only, no square root or division (relative error in the module docs;
///   both results carry it).
/// * [`NewtonSqrtRecip`]`<SQRT, RECIP>`: as [`NewtonSqrt`], and the model's final division
///   by [`recip`].
/// * [`HardwareEstimate`]: the exact operations, except in the [`crate::batch`] AVX-512
///   kernel, where the hardware estimates `vrsqrt14ps`/`vrcp14ps` with one refinement step
///   take them (a few ULP).
///
/// The trade measured on this crate's models (error and speed against [`ExactSqrt`]) is in
/// `docs/tradeoffs.md`: on an x86 core with a fast square-root unit (Zen 5 here) the exact
/// path is the faster one, by 1.0–1.4× in scalar loops and in the batch kernels; the Newton
/// path is for hardware whose square root and division are slow — measure there.
pub trait SqrtFn: Copy + core::fmt::Debug + Default + Send + Sync + 'static {
    /// `(√x, 1/√x)` for positive normal `x`. At `x = 0` the first is `0` and the second is
    /// `+∞` ([`ExactSqrt`]) or a large finite value ([`NewtonSqrt`]): callers select it away.
    fn sqrt_rsqrt<R: Real>(x: R) -> (R, R);

    /// `n / d` for the model's final denominator (positive normal `d`): the correctly rounded
    /// division unless the policy says otherwise ([`NewtonSqrtRecip`] uses [`recip`]).
    #[inline(always)]
    fn div<R: Real>(n: R, d: R) -> R {
        n / d
    }

    /// Whether the policy wants the hardware estimates of the batch path's explicit
    /// AVX-512 lanes ([`HardwareEstimate`]); a model reports it through
    /// [`crate::real::Splat::EXPLICIT_LANES`].
    const HARDWARE_ESTIMATES: bool = false;
}

/// [`SqrtFn`] through the correctly rounded [`Real::sqrt`] and a division.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExactSqrt;

impl SqrtFn for ExactSqrt {
    #[inline(always)]
    fn sqrt_rsqrt<R: Real>(x: R) -> (R, R) {
        let s = x.sqrt();
        (s, s.recip())
    }
}

/// [`SqrtFn`] through [`rsqrt`]`::<STEPS>` (`0 ≤ STEPS ≤ 3` Newton steps): `1/√x ≈ y`,
/// `√x ≈ x·y`, with no square root or division.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NewtonSqrt<const STEPS: usize>;

impl<const STEPS: usize> SqrtFn for NewtonSqrt<STEPS> {
    #[inline(always)]
    fn sqrt_rsqrt<R: Real>(x: R) -> (R, R) {
        let y = rsqrt::<STEPS, R>(x);
        (x * y, y)
    }
}

/// `1/x` for positive `x` from [`Bits::rsqrt_estimate`] squared, refined by `N`
/// Newton–Raphson steps, `0 ≤ N ≤ 3`: multiplies and adds only, no division.
///
/// ```text
/// y₀ = rsqrt_estimate(x)²,   e_k = 1 − x·y_k,   y_{k+1} = y_k + y_k·e_k
/// ```
///
/// Each step squares the relative error (`1 − x·y_{k+1} = e_k²`); the start carries
/// `δ₀ = 2e + e²` for an estimate of relative error `e`. Domain: positive normal finite `x`
/// (the models' denominators, which are sums of squares clamped away from 0); inputs below
/// the smallest normal are raised to it (a large finite result instead of `∞`). Relative error
/// bounds against `1/x` (`f32`, checked exhaustively on `[1, 4)` in `tests/fast.rs`):
///
/// ```text
/// start                                         N = 0     1        2        3
/// bit trick (f32, F32Fma scalars: the kernels)  7.0e-2    4.9e-3   2.4e-5   1.8e-7
/// hardware rsqrtps (f32 lanes)                  7.3e-4    5.4e-7   1.8e-7   1.8e-7
/// ```
///
/// so `N = 3` is within 3 roundings (≈ 1.5 ULP) on every type.
///
/// Why not `vrcp14ps`/`vrcpps` directly: the [`crate::batch`] kernels run a one-lane model
/// (`f32`/[`F32Fma`](crate::real::F32Fma)) that LLVM vectorizes across iterations, and LLVM
/// does not vectorize the scalar `rcp14ss`/`rcpss` intrinsics; the integer bit trick
/// vectorizes into 16-lane integer subtracts and shifts, so this form runs on the
/// vector units without a division (see the README's Performance section for what it buys).
///
/// # Examples
///
/// ```
/// use brdf::fast;
/// let y = fast::recip::<3, f32>(3.0);
/// assert!((y * 3.0 - 1.0).abs() < 2e-7);
/// ```
#[inline(always)]
#[must_use]
pub fn recip<const N: usize, R: Real>(x: R) -> R {
    const { assert!(N <= 3, "fast::recip takes 0..=3 Newton steps") };
    let x = x.max(min_positive::<R>());
    let r = x.rsqrt_estimate();
    let mut y = r * r;
    for _ in 0..N {
        let e = (-x).mul_add(y, R::one());
        y = y.mul_add(e, y);
    }
    y
}

/// [`SqrtFn`] with the half vector taken by [`rsqrt`]`::<SQRT>` (as [`NewtonSqrt`]) and the
/// model's final division `n / d` as `n · `[`recip`]`::<RECIP>(d)`: a Cook-Torrance
/// `with_sqrt::<NewtonSqrtRecip<3, 3>>()` evaluates GGX without a square root or division
/// outside its masking terms, and a [`crate::fresnel::Conductor::with_policy`] conductor
/// without any. `<3, 3>` stays within `16·2⁻²⁴ ≈ 9.5·10⁻⁷` relative of the exact policy on
/// these models (tested on f32 and `F32Fma`: measured ≤ 7.1·10⁻⁷).
///
/// Speed: on an Intel Xeon with AVX-512 (Sapphire Rapids class) it is slower than
/// [`ExactSqrt`] in the [`crate::batch`] kernels (README, Performance): three Newton steps
/// from the bit-trick start cost more than that core's 16-lane square root and division.
/// Measure before choosing it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NewtonSqrtRecip<const SQRT: usize, const RECIP: usize>;

impl<const SQRT: usize, const RECIP: usize> SqrtFn for NewtonSqrtRecip<SQRT, RECIP> {
    #[inline(always)]
    fn sqrt_rsqrt<R: Real>(x: R) -> (R, R) {
        NewtonSqrt::<SQRT>::sqrt_rsqrt(x)
    }
    #[inline(always)]
    fn div<R: Real>(n: R, d: R) -> R {
        n * recip::<RECIP, R>(d)
    }
}

/// [`SqrtFn`] through the hardware estimates with one refinement step where the batch path
/// can use them, and exact elsewhere: [`Bits::sqrt_rsqrt_refined`] and
/// [`Bits::div_refined`].
///
/// * [`crate::batch`] on [`crate::batch::Isa::Avx512`]: a model with this policy runs on
///   explicit 16-lane AVX-512 registers, where `√x` is `vrsqrt14ps` + one Newton step and
///   `n / d` is `vrcp14ps` + one Markstein correction: multiplies and adds on the FMA ports
///   instead of the square-root/division unit, which bounds GGX on Intel cores (README,
///   Performance). Results within a few ULP of [`ExactSqrt`] (`tests/batch.rs` states the
///   bound), and not bit-identical to `eval`. One exception, chosen at run time with the
///   kernel: a [`crate::fresnel::Conductor`] with this policy keeps its exact operations on
///   cores that are not divider-bound ([`crate::batch::shares_divisions`] `false`: AMD),
///   where its chained refinement steps cost more than the divider (see
///   [`crate::fresnel::Conductor::with_policy`]).
/// * Everywhere else (`eval` on any type, the portable and AVX2 kernels): exactly
///   [`ExactSqrt`], bit for bit — those have no vectorizable estimate instruction, and three
///   Newton steps from a bit trick ([`NewtonSqrtRecip`]) cost more than the exact
///   operations.
///
/// Domain as [`SqrtFn`]: positive normal `x` (and `√0 = 0`) and a positive normal final
/// denominator `d` (the models clamp it to `≥ 10⁻³⁰`).
///
/// ```
/// use brdf::{Brdf, Vec3, fast::HardwareEstimate, fresnel::Schlick};
/// use brdf::{masking::SmithHeightCorrelated, models::CookTorrance, ndf::GgxIsotropic};
/// let exact = CookTorrance::new(
///     GgxIsotropic::new(0.3_f32).unwrap(),
///     Schlick::new([0.04_f32]).unwrap(),
///     SmithHeightCorrelated,
/// );
/// let fast = exact.with_sqrt::<HardwareEstimate>();
/// let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.28, 0.0, 0.96));
/// // Scalar `eval` is the exact policy bit for bit; the estimates act in batch::eval.
/// assert_eq!(exact.eval(wi, wo), fast.eval(wi, wo));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HardwareEstimate;

impl SqrtFn for HardwareEstimate {
    #[inline(always)]
    fn sqrt_rsqrt<R: Real>(x: R) -> (R, R) {
        x.sqrt_rsqrt_refined()
    }
    #[inline(always)]
    fn div<R: Real>(n: R, d: R) -> R {
        n.div_refined(d)
    }
    const HARDWARE_ESTIMATES: bool = true;
}
