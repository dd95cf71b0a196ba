//! Normalization factors of Blinn-Phong and Phong lobes: the core result of the seed talk.
//!
//! A lobe `(N·H)^s` reflects more or less light depending on its shininess `s`; a
//! normalization factor `c(s)` scales it so that a chosen total is `1` (times the specular
//! colour) whatever `s` is, and highlights keep their energy as they sharpen. Which total is
//! made `1` differs between models, so the factors below are **not interchangeable**: each
//! documents the integral it normalizes and the model it belongs to.
//!
//! | function | `c(s)` | makes this equal to 1 |
//! |---|---|---|
//! | [`tri_ace_exact`] | `(s + 2)/(4π (2 − 2^(−s/2)))` | `∫ c (N·H)^s dω`, `L = N` (seed talk) |
//! | [`tri_ace_fit`] | `(s + n)/(8π)`, `n =` [`TRI_ACE_OFFSET`] `= 2.04` | (linear fit of the above) |
//! | [`tri_ace_2010_fit`] | `0.0397436 s + 0.0856832` | (published fit for `F (N·H)^s / max(N·L, N·V)`) |
//! | [`blinn_phong_ndf`] | `(s + 2)/(2π)` | `∫ D(wm) cos θm dωm` with `D = c (N·H)^s` |
//! | [`blinn_phong_cosine_exact`] | `(s + 2)(s + 4)/(8π (2^(−s/2) + s))` | `∫ c (N·H)^s (N·L) dωL`, `V = N` |
//! | [`blinn_phong_rtr_approx`] | `(s + 8)/(8π)` | (approximation of the above) |
//! | [`phong_lobe`] | `(s + 1)/(2π)` | `∫ c (R·V)^s dωV`, `L = N` |
//! | [`phong_cosine`] | `(s + 2)/(2π)` | `∫ c (R·V)^s (N·V) dωV`, `L = N` |
//!
//! # The seed's normalized Blinn-Phong
//!
//! ```text
//! rendered specular = R_s · c(s) · F · (N·H)^s          (the talk's term has no N·L)
//! c(s) = (s + 2) / (4π (2 − 2^(−s/2)))  ≈  (s + 2.04) / (8π)
//! ```
//!
//! [`tri_ace_integral`] derives the integral. The fit trades accuracy at low shininess for
//! one multiply-add. Its error, `fit/exact − 1 = (n − n₀(s))/(s + n₀(s))` with
//! [`tri_ace_exact_offset`] `n₀(s)` (recomputed from the functions by
//! `tests/normalization.rs`, which parses this table):
//!
//! <!-- fit-table:begin -->
//! | s | exact `c(s)` | fit `(s + 2.04)/(8π)` | relative error |
//! |---:|---:|---:|---:|
//! | 0 | 1.5915494e-01 | 8.1169021e-02 | -4.9000e-01 |
//! | 1 | 1.8464975e-01 | 1.2095776e-01 | -3.4493e-01 |
//! | 2 | 2.1220659e-01 | 1.6074649e-01 | -2.4250e-01 |
//! | 4 | 2.7283705e-01 | 2.4032396e-01 | -1.1917e-01 |
//! | 8 | 4.1072243e-01 | 3.9947891e-01 | -2.7375e-02 |
//! | 16 | 7.1759880e-01 | 7.1778879e-01 | +2.6476e-04 |
//! | 32 | 1.3528273e+00 | 1.3544086e+00 | +1.1688e-03 |
//! | 64 | 2.6260566e+00 | 2.6276481e+00 | +6.0606e-04 |
//! | 128 | 5.1725357e+00 | 5.1741272e+00 | +3.0769e-04 |
//! | 256 | 1.0265494e+01 | 1.0267085e+01 | +1.5504e-04 |
//! | 1024 | 4.0823243e+01 | 4.0824834e+01 | +3.8986e-05 |
//! | 10000 | 3.9796694e+02 | 3.9796853e+02 | +3.9992e-06 |
//! | 1000000 | 3.9788815e+04 | 3.9788817e+04 | +4.0000e-08 |
//! <!-- fit-table:end -->
//!
//! ## Where 2.04 comes from
//!
//! The talk says only that `n` depends on the shininess range and that the error is small.
//! Under the minimax relative error ([`fit::best_fit_offset`]), the optimum depends on the lower
//! end `s_min` alone once `s_max ≳ 23`: `n* = 3.528` for `[0, ·]`, `2.984` for `[2, ·]`,
//! `2.218` for `[8, ·]`, `2.022` for `[16, ·]`, and **`n* = 2.040` for `s_min ≈ 14`**, where
//! the fit's worst error is **0.143 %** (−0.142 % at `s = 14`, +0.143 % at `s ≈ 22.75`).
//! So 2.04 is the optimal offset for shininess `s ≥ 14`, the range where the talk's
//! "ほとんど誤差" (almost no error) holds; below `s = 14` the error grows to −2.7 % at
//! `s = 8` and −49 % at `s = 0`. (A least-squares fit of the offset alone, slope fixed at
//! `1/(8π)`, absolute error, over `[0, 221]` also gives 2.04: the mean of `n₀`; the slides
//! lost the plot that fixed the range.) Use [`fit::fit_error`] to measure any offset over your
//! own range.
//!
//! # Precomputation
//!
//! As the talk suggests, the factor depends on the shininess alone: compute it once per
//! material ([`BlinnPhongLobe`], [`Normalization`]) or once per shininess-map level
//! ([`NormalizationTable`], [`fill_table`]) instead of in every shader invocation.
//!
//! # References
//!
//! * Y. Gotanda, "本当のHDR表現へ — アーティストにも知ってほしいリフレクタンスの基礎" (Beyond a
//!   glare effect for HDR rendering — Basic of Reflectance), tri-Ace, Imagine Day 2009:
//!   the integral, its reciprocal and the fit `(s + 2.04)/(8π)`.
//! * Y. Gotanda, "Practical Implementation of Physically-Based Shading Models at tri-Ace",
//!   SIGGRAPH 2010 course *Physically-Based Shading Models in Film and Game Production*.
//! * F. Giesen, "The Blinn-Phong Normalization Zoo", blog post, 2009.
//! * T. Akenine-Möller, E. Haines, N. Hoffman, *Real-Time Rendering*, 3rd ed., 2008, §7.6.
//! * R. R. Lewis, "Making Shaders More Physically Plausible", Computer Graphics Forum 13(2),
//!   1994.

use crate::error::{self, Error};
use crate::{Real, Scalar};

/// The seed talk's fitted offset `n = 2.04` of the linear normalization `(s + n)/(8π)`.
///
/// Gotanda 2009 ("Basic of Reflectance", tri-Ace) replaces the exact factor
/// [`tri_ace_exact`] by `(s + 2.04)/(8π)`. Use it with [`tri_ace_fit`].
pub const TRI_ACE_OFFSET: f64 = 2.04;

/// The largest offset `n` of a linear fit `(s + n)/(8π)` that a material accepts
/// ([`Normalization::validate`]): `8`.
///
/// The exact factor's own offset [`tri_ace_exact_offset`] lies in `(2, 4]`, so every fit
/// worth using has `n` there (the seed's 2.04, the minimax optima of
/// [`fit::best_fit_offset`]);
/// `[0, 8]` also admits the plain `s/(8π)` (`n = 0`) and *Real-Time Rendering*'s `(s + 8)/(8π)`
/// ([`blinn_phong_rtr_approx`]). A larger offset brightens every lobe beyond its exact
/// normalization, and an unbounded one overflows the factor in `f32` (an offset of `1e300`
/// gave ∞). [`fit::fit_error`] measures any finite offset.
pub const MAX_FIT_OFFSET: f64 = 8.0;

/// [`crate::ndf::MAX_SHININESS`] (`2/MIN_ALPHA² − 2`), the bound of [`BlinnPhongLobe`]'s
/// exponent; written out here because `ndf` builds on this module.
const MAX_SHININESS: f64 = 2e8 - 2.0;

/// `8π`, the denominator of the linear fits.
const EIGHT_PI: f64 = 8.0 * core::f64::consts::PI;
/// `4π`.
const FOUR_PI: f64 = 4.0 * core::f64::consts::PI;

/// `2^(−s/2)` for `s ≥ 0`, written `exp(−s·ln2/2)`.
///
/// `exp` rather than `exp2`: wide's `f64x4::exp2` uses a short polynomial accurate to only
/// ~1e−13, while its `exp` is accurate to a few ULP. Rounding the argument `s·ln2/2` costs
/// a relative error `≈ (s·ln2/2)·ε` in the result, whose absolute effect on every formula
/// here is at most `max_x x·e^(−x)·ε = ε/e` (the result is added to or subtracted from
/// `O(1)` quantities, or multiplied by `s`). Large `s` underflows
/// to `0` (`+∞` gives `0`), which is the exact limit.
#[inline(always)]
fn exp2_neg_half<R: Real>(s: R) -> R {
    (s * R::from_f64(-0.5 * core::f64::consts::LN_2)).exp()
}

/// `max(2^(−s/2), ≈2^(−64))`: for formulas where `2^(−s/2)` is only added to or subtracted
/// from a number `≥ 1` that it cannot change below `2^(−54)` (`2 − q`, `s + q` for
/// `s ≥ 128`), so the results are identical to [`exp2_neg_half`]'s. Keeping the `exp`
/// argument above `−64·ln 2` avoids the underflow and subnormal paths of the SIMD `exp`
/// kernels, which otherwise cost a branch per register for large `s`. Not for `s·q`.
#[inline(always)]
fn exp2_neg_half_floored<R: Real>(s: R) -> R {
    let x = s * R::from_f64(-0.5 * core::f64::consts::LN_2);
    x.max(R::from_f64(-64.0 * core::f64::consts::LN_2)).exp()
}

/// The hemisphere integral of the seed talk, `∫_Ω (N·H)^s dω` with the light at normal
/// incidence, in closed form.
///
/// ```text
/// I(s) = ∫_Ω (N·H)^s dω = 4π (2 − 2^(−s/2)) / (s + 2)          s ∈ [0, ∞)
/// ```
///
/// # Derivation
///
/// Frame `N = (0, 0, 1)`; the integration variable is the view direction
/// `E = (sin θ cos φ, sin θ sin φ, cos θ)` over the upper hemisphere, and `L = N`. Then
/// `|N + E| = √(2 (1 + cos θ))`, so
///
/// ```text
/// N·H = N·(N + E)/|N + E| = √((1 + cos θ)/2) = cos(θ/2)
///
/// I(s) = ∫₀^{2π} ∫₀^{π/2} cos^s(θ/2) sin θ dθ dφ
///      = 2π ∫₀^{π/2} cos^s(θ/2) · 2 sin(θ/2) cos(θ/2) dθ        (sin θ = 2 sin(θ/2) cos(θ/2))
///      = 2π ∫_{1/√2}^{1} 4 u^{s+1} du                           (u = cos(θ/2), du = −½ sin(θ/2) dθ)
///      = 8π (1 − 2^{−(s+2)/2}) / (s + 2)
///      = 4π (2 − 2^{−s/2}) / (s + 2)
/// ```
///
/// (The OCR'd slides drop the minus sign of `2^(−s/2)` in two places; the appendix has it.)
///
/// What it measures: `N·H` is symmetric in `L` and `E`, so `I(s)` is also the integral over
/// light directions for a viewer at normal incidence, `∫ c (N·H)^s dω_L`; for the seed's
/// rendered specular term `c (N·H)^s` (a BRDF `c (N·H)^s / (N·L)` times `N·L`) that is the
/// hemispherical-directional reflectance seen head-on, so `c = 1/I(s)` makes a head-on view
/// of a white furnace return exactly `R_s`. The seed calls the light-at-normal-incidence
/// restriction an approximation ("厳密ではない近似"): other angles reflect less.
///
/// # Domain and accuracy
///
/// `s ∈ [0, ∞)`, including `+∞` (gives `0`). `I(0) = 2π` (the solid angle of the
/// hemisphere), `I(s) → 8π/s` for large `s`. `2 − 2^(−s/2) ∈ [1, 2)` is a subtraction of a
/// number at most half the minuend, so it cannot cancel: the rounding error of `2^(−s/2)` is
/// damped by `2^(−s/2)/(2 − 2^(−s/2)) ≤ 1`. Measured against a cancellation-free
/// `expm1` formulation over `s ∈ [0, 10¹²]`: within 2 ULP on `f32` and `f64` (this function
/// and [`tri_ace_exact`]); `2^(−s/2)` underflowing to `0` for huge `s` is harmless.
///
/// # Reference
///
/// Y. Gotanda, "Basic of Reflectance", tri-Ace, Imagine Day 2009, appendix 参考1.
///
/// # Examples
///
/// ```
/// use brdf::normalization::tri_ace_integral;
/// let two_pi = 2.0 * core::f64::consts::PI;
/// assert!((tri_ace_integral(0.0_f64) - two_pi).abs() < 1e-15);
/// // For large s the lobe narrows and the integral tends to 8π/s.
/// let s = 1e6_f64;
/// assert!((tri_ace_integral(s) * s / (8.0 * core::f64::consts::PI) - 1.0).abs() < 3e-6);
/// ```
#[inline]
#[must_use]
pub fn tri_ace_integral<R: Real>(s: R) -> R {
    let two = R::from_f64(2.0);
    R::from_f64(FOUR_PI) * (two - exp2_neg_half_floored(s)) / (s + two)
}

/// The seed talk's exact normalization factor, the reciprocal of [`tri_ace_integral`].
///
/// ```text
/// c(s) = 1 / ∫_Ω (N·H)^s dω = (s + 2) / (4π (2 − 2^(−s/2)))        s ∈ [0, ∞)
/// ```
///
/// `c(0) = 1/(2π)`, and `c(s) = (s + 2)/(8π) + O(s·2^(−s/2))` for large `s`: the slope is
/// exactly `1/(8π)`. Normalizes the seed's rendered specular term `c · F · (N·H)^s`, see
/// [`tri_ace_integral`] for the integral and its derivation. Finite for every finite
/// `s ≥ 0`; `+∞` maps to `+∞`.
///
/// # Reference
///
/// Y. Gotanda, "Basic of Reflectance", tri-Ace, Imagine Day 2009.
///
/// # Examples
///
/// ```
/// use brdf::normalization::{tri_ace_exact, tri_ace_fit, TRI_ACE_OFFSET};
/// use core::f64::consts::PI;
/// assert!((tri_ace_exact(0.0_f64) - 1.0 / (2.0 * PI)).abs() < 1e-16);
/// // The talk's linear fit is within 0.15 % of the exact factor from s = 16 on.
/// let (exact, fit) = (tri_ace_exact(16.0_f64), tri_ace_fit(16.0_f64, TRI_ACE_OFFSET));
/// assert!((fit / exact - 1.0).abs() < 1.5e-3);
/// ```
#[inline]
#[must_use]
pub fn tri_ace_exact<R: Real>(s: R) -> R {
    let two = R::from_f64(2.0);
    (s + two) / (R::from_f64(FOUR_PI) * (two - exp2_neg_half_floored(s)))
}

/// The seed talk's linear approximation of [`tri_ace_exact`]: `(s + offset)/(8π)`.
///
/// ```text
/// c_fit(s) = (s + n) / (8π),     n = offset (the talk uses n = TRI_ACE_OFFSET = 2.04)
/// ```
///
/// The exact factor is `(s + n₀(s))/(8π)` with `n₀(s) = (4 + s·2^(−s/2))/(2 − 2^(−s/2))`
/// decreasing from `4` at `s = 0` to `2` for large `s`, so no constant `n` is exact
/// everywhere: the relative error is `(n − n₀(s))/(s + n₀(s))`. With `n = 2.04` it is
/// −49 % at `s = 0`, −12 % at `s = 4`, −2.7 % at `s = 8`, crosses zero at `s ≈ 15.56`,
/// peaks at +0.143 % near `s ≈ 22.8` and then decays like `0.04/s`. The module
/// documentation tabulates it.
///
/// Domain: `s ∈ [0, ∞)`, `offset ≥ 0` (any finite values evaluate; the factor is positive
/// when `s + offset > 0`). Costs one add and one multiply, against an `exp2`, a division
/// and a few flops for [`tri_ace_exact`].
///
/// # Reference
///
/// Y. Gotanda, "Basic of Reflectance", tri-Ace, Imagine Day 2009.
///
/// # Examples
///
/// ```
/// use brdf::normalization::{tri_ace_fit, TRI_ACE_OFFSET};
/// let c = tri_ace_fit(100.0_f32, TRI_ACE_OFFSET as f32);
/// assert!((c - 102.04 / (8.0 * core::f32::consts::PI)).abs() < 1e-6);
/// ```
#[inline]
#[must_use]
pub fn tri_ace_fit<R: Real>(s: R, offset: R) -> R {
    (s + offset) * R::from_f64(1.0 / EIGHT_PI)
}

/// The offset `n₀(s)` that makes the linear fit exact at `s`: `tri_ace_exact(s) = (s + n₀(s))/(8π)`.
///
/// ```text
/// n₀(s) = 8π·c(s) − s = (4 + s·2^(−s/2)) / (2 − 2^(−s/2))        s ∈ [0, ∞)
/// n₀(s) − 2 = 2^(−s/2) (s + 2) / (2 − 2^(−s/2))  > 0
/// ```
///
/// Decreases from `n₀(0) = 4` to `2` (`n₀(s) − 2 ≈ (s + 2)·2^(−s/2−1)` for large `s`), so
/// `(s + 2)/(8π) < c(s) ≤ (s + 4)/(8π)`. The fit `(s + n)/(8π)` has relative error
/// `(n − n₀(s))/(s + n₀(s))`. Written without the cancellation of `8π·c(s) − s`:
/// accurate to a few ULP for every `s`.
///
/// # Reference
///
/// Derived here from Gotanda 2009 ("Basic of Reflectance", tri-Ace).
#[inline]
#[must_use]
pub fn tri_ace_exact_offset<R: Real>(s: R) -> R {
    let q = exp2_neg_half(s);
    (s.mul_add(q, R::from_f64(4.0))) / (R::from_f64(2.0) - q)
}

/// tri-Ace's published linear normalization of 2010: `c(s) = 0.0397436·s + 0.0856832`.
///
/// ```text
/// f(wi, wo) = c(s) · F(f0, wi·wm) · (N·H)^s / max(N·L, N·V)
/// c(s) = 0.0397436 s + 0.0856832  =  (0.998866 s + 2.15345) / (8π)
/// ```
///
/// Gotanda's SIGGRAPH 2010 course notes give these constants for that model (the
/// `max(N·L, N·V)` denominator is the geometric term of Neumann, Neumann and
/// Szirmay-Kalos, "Compact Metallic Reflectance Models", Eurographics 1999); the notes do
/// not state the fitted range, and the crate does not re-derive them. Relative to the
/// seed's exact [`tri_ace_exact`] it is −46 % at `s = 0`, −10 % at `s = 4`, +0.57 % at its
/// peak near `s ≈ 17.5`, −0.05 % at `s = 256`, −0.10 % at `s = 1024`, and tends to
/// −0.113 % (its slope `0.0397436` is 0.113 % below the exact `1/(8π)`). At normal viewing
/// (`V = N`, so `max(N·L, N·V) = 1`) the model's directional albedo with `F = 1` is
/// `c(s)/`[`blinn_phong_cosine_exact`]`(s)`: 0.27 at `s = 0`, 0.81 at `s = 16`, 0.98 at
/// `s = 256` — always below 1.
///
/// Domain: `s ∈ [0, ∞)`.
///
/// # Reference
///
/// Y. Gotanda, "Practical Implementation of Physically-Based Shading Models at tri-Ace",
/// SIGGRAPH 2010 course *Physically-Based Shading Models in Film and Game Production*.
#[inline]
#[must_use]
pub fn tri_ace_2010_fit<R: Real>(s: R) -> R {
    s.mul_add(R::from_f64(0.0397436), R::from_f64(0.0856832))
}

/// Normalization of the Blinn-Phong normal distribution function: `(s + 2)/(2π)`.
///
/// ```text
/// D(wm) = (s + 2)/(2π) · (N·wm)^s          ∫_Ω D(wm) cos θm dωm = 1
/// ∫_Ω cos^s θ cos θ dω = 2π ∫₀^{π/2} cos^{s+1} θ sin θ dθ = 2π/(s + 2)
/// ```
///
/// The microfacet convention of this crate (projected area of the microsurface = 1). It
/// normalizes the distribution of normals, not the reflected energy of a BRDF: a
/// microfacet BRDF still divides by `4 (N·L)(N·V)` and multiplies by `F·G`. Domain
/// `s ∈ [0, ∞)`; `s = 0` gives `1/π` (the cosine-weighted hemisphere).
///
/// # Reference
///
/// J. F. Blinn, "Models of Light Reflection for Computer Synthesized Pictures", SIGGRAPH
/// 1977 (the `cos^s` distribution); normalization as in B. Walter et al., "Microfacet
/// Models for Refraction through Rough Surfaces", EGSR 2007.
#[inline]
#[must_use]
pub fn blinn_phong_ndf<R: Real>(s: R) -> R {
    (s + R::from_f64(2.0)) * R::from_f64(0.5 * core::f64::consts::FRAC_1_PI)
}

/// Exact cosine-weighted normalization of a Blinn-Phong lobe at normal incidence:
/// `(s + 2)(s + 4) / (8π (2^(−s/2) + s))`.
///
/// ```text
/// f(wi, wo) = c(s) · (N·H)^s,   ∫_Ω f (N·L) dωL = 1  for V = N
/// c(s) = (s + 2)(s + 4) / (8π (2^(−s/2) + s))
/// ```
///
/// # Derivation
///
/// With `V = N` and `L` at polar angle `θ`, `N·H = cos(θ/2)` and `N·L = cos θ = 2u² − 1`
/// for `u = cos(θ/2)`; as in [`tri_ace_integral`], `sin θ dθ = −4u du`:
///
/// ```text
/// ∫_Ω (N·H)^s (N·L) dω = 2π ∫_{1/√2}^{1} 4 u^{s+1} (2u² − 1) du
///                      = 8π [2u^{s+4}/(s+4) − u^{s+2}/(s+2)]_{1/√2}^{1}
///                      = 8π [s/((s+2)(s+4)) + 2^{−s/2}/((s+2)(s+4))]
///                      = 8π (s + 2^{−s/2}) / ((s + 2)(s + 4))
/// ```
///
/// `c(0) = 1/π` (Lambert); `c(s) ≈ (s + 6)/(8π)` for large `s`. Evaluated as
/// `(s + 2)·((s + 4)/(s + 2^(−s/2)))/(8π)`, so nothing overflows for any finite `s ≥ 0`.
/// Domain `s ∈ [0, ∞)`. Also the normal-viewing albedo normalization of the tri-Ace
/// 2010 model, see [`tri_ace_2010_fit`].
///
/// # Reference
///
/// F. Giesen, "The Blinn-Phong Normalization Zoo", blog post, 2009.
#[inline]
#[must_use]
pub fn blinn_phong_cosine_exact<R: Real>(s: R) -> R {
    let q = exp2_neg_half_floored(s);
    let ratio = (s + R::from_f64(4.0)) / (s + q);
    (s + R::from_f64(2.0)) * ratio * R::from_f64(1.0 / EIGHT_PI)
}

/// The *Real-Time Rendering* approximation `(s + 8)/(8π)` of
/// [`blinn_phong_cosine_exact`].
///
/// ```text
/// f(wi, wo) = (s + 8)/(8π) · (N·H)^s
/// ```
///
/// Equal to the exact cosine-weighted factor at `s = 0` (`1/π`) and above it for `s > 0`:
/// `(s + 8)(s + 2^(−s/2)) − (s + 2)(s + 4) = 2s + (s + 8)·2^(−s/2) − 8 ≥ 0`. The excess is
/// +2.4 % at `s = 1`, +6.3 % at `s = 4`, +7.5 % at its peak near `s ≈ 8.8`, +2.7 % at
/// `s = 64`, and tends to `2/(s + 6)`: a normal-incidence albedo slightly above 1. Domain
/// `s ∈ [0, ∞)`.
///
/// # Reference
///
/// T. Akenine-Möller, E. Haines, N. Hoffman, *Real-Time Rendering*, 3rd ed., 2008, §7.6.
#[inline]
#[must_use]
pub fn blinn_phong_rtr_approx<R: Real>(s: R) -> R {
    (s + R::from_f64(8.0)) * R::from_f64(1.0 / EIGHT_PI)
}

/// Normalization of a Phong (reflection-vector) lobe alone: `(s + 1)/(2π)`.
///
/// ```text
/// ∫_Ω (R·V)^s dωV = 2π ∫₀^{π/2} cos^s θ sin θ dθ = 2π/(s + 1)      for L = N (R = N)
/// ```
///
/// The lobe `(R·V)^s` around the mirror direction `R = reflect(L)`, without the cosine of
/// the outgoing direction, fully inside the hemisphere (normal incidence); at oblique
/// incidence the horizon clips it and the integral is smaller. The Phong analogue of
/// [`tri_ace_exact`]. Domain `s ∈ [0, ∞)`.
///
/// # Reference
///
/// B. T. Phong, "Illumination for Computer Generated Pictures", CACM 18(6), 1975 (the
/// lobe); R. R. Lewis, "Making Shaders More Physically Plausible", CGF 13(2), 1994.
#[inline]
#[must_use]
pub fn phong_lobe<R: Real>(s: R) -> R {
    (s + R::one()) * R::from_f64(0.5 * core::f64::consts::FRAC_1_PI)
}

/// Cosine-weighted normalization of a Phong lobe at normal incidence: `(s + 2)/(2π)`.
///
/// ```text
/// f(wi, wo) = (s + 2)/(2π) · (R·V)^s,   ∫_Ω f (N·V) dωV = 2π ∫₀^{π/2} cos^{s+1} θ sin θ dθ · c = 1
/// ```
///
/// For `L = N` the mirror direction is `R = N`, so `R·V = N·V`. The energy-conserving
/// Phong BRDF of Lewis (1994); the same number as [`blinn_phong_ndf`], for a different
/// integral. Domain `s ∈ [0, ∞)`.
///
/// # Reference
///
/// R. R. Lewis, "Making Shaders More Physically Plausible", Computer Graphics Forum 13(2),
/// 1994.
#[inline]
#[must_use]
pub fn phong_cosine<R: Real>(s: R) -> R {
    // The same number as the Blinn-Phong NDF's factor, for a different integral.
    blinn_phong_ndf(s)
}

/// A choice of normalization factor, stored per material.
///
/// Each variant names one of the functions of this module; [`Normalization::factor`]
/// evaluates it. The variants normalize **different integrals** (see the module table):
/// pick the one that belongs to the BRDF you evaluate. Non-exhaustive: more normalizations
/// may be added.
///
/// # Examples
///
/// ```
/// use brdf::normalization::{Normalization, tri_ace_exact};
/// let n = Normalization::TriAceExact;
/// assert_eq!(n.factor(64.0_f64), tri_ace_exact(64.0_f64));
/// let fit = Normalization::TRI_ACE_2009_FIT; // (s + 2.04)/(8π)
/// assert!((fit.factor(64.0_f32) / n.factor(64.0_f32) - 1.0).abs() < 1e-3);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Normalization {
    /// No normalization: `c(s) = 1` (the classic, unnormalized Blinn-Phong).
    Unnormalized,
    /// [`tri_ace_exact`]: `(s + 2)/(4π (2 − 2^(−s/2)))`.
    TriAceExact,
    /// [`tri_ace_fit`]: `(s + offset)/(8π)`; the talk uses `offset = 2.04`.
    TriAceFit {
        /// The offset `n` of `(s + n)/(8π)`, in `[0, 8]` ([`MAX_FIT_OFFSET`]; see
        /// [`fit::best_fit_offset`]).
        offset: f64,
    },
    /// [`tri_ace_2010_fit`]: `0.0397436 s + 0.0856832`.
    TriAce2010Fit,
    /// [`blinn_phong_ndf`]: `(s + 2)/(2π)`.
    BlinnPhongNdf,
    /// [`blinn_phong_cosine_exact`]: `(s + 2)(s + 4)/(8π (2^(−s/2) + s))`.
    BlinnPhongCosineExact,
    /// [`blinn_phong_rtr_approx`]: `(s + 8)/(8π)`.
    BlinnPhongRtrApprox,
    /// [`phong_lobe`]: `(s + 1)/(2π)`.
    PhongLobe,
    /// [`phong_cosine`]: `(s + 2)/(2π)`.
    PhongCosine,
}

impl Normalization {
    /// The seed talk's fit `(s + 2.04)/(8π)`: [`Normalization::TriAceFit`] with
    /// [`TRI_ACE_OFFSET`].
    pub const TRI_ACE_2009_FIT: Self = Normalization::TriAceFit {
        offset: TRI_ACE_OFFSET,
    };

    /// The factor `c(s)` of this normalization (see each variant's function).
    ///
    /// Domain `s ∈ [0, ∞)`. The variant is matched once per call, not per lane, so a SIMD
    /// `s` runs the same branch-free body as the function it names. `offset` is not
    /// validated here: [`BlinnPhongLobe::new`] and [`NormalizationTable::new`] do it.
    #[inline]
    #[must_use]
    pub fn factor<R: Real>(self, s: R) -> R {
        match self {
            Normalization::Unnormalized => R::one(),
            Normalization::TriAceExact => tri_ace_exact(s),
            Normalization::TriAceFit { offset } => tri_ace_fit(s, R::from_f64(offset)),
            Normalization::TriAce2010Fit => tri_ace_2010_fit(s),
            Normalization::BlinnPhongNdf => blinn_phong_ndf(s),
            Normalization::BlinnPhongCosineExact => blinn_phong_cosine_exact(s),
            Normalization::BlinnPhongRtrApprox => blinn_phong_rtr_approx(s),
            Normalization::PhongLobe => phong_lobe(s),
            Normalization::PhongCosine => phong_cosine(s),
        }
    }

    /// Checks the variant's own parameter: `offset` of [`Normalization::TriAceFit`] must lie
    /// in `[0, 8]` ([`MAX_FIT_OFFSET`]).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfDomain`] naming `"offset"`.
    pub fn validate(self) -> Result<Self, Error> {
        if let Normalization::TriAceFit { offset } = self {
            error::check("offset", offset, "[0, 8]", |v| {
                (0.0..=MAX_FIT_OFFSET).contains(&v)
            })?;
        }
        Ok(self)
    }
}

/// A Blinn-Phong lobe `c(s)·(N·H)^s` whose factor is computed once, when the material is
/// built.
///
/// The seed talk's advice: the factor depends on the shininess only, so a material with a
/// constant shininess evaluates it once on the CPU, not per pixel.
///
/// ```text
/// lobe(cos_theta_h) = factor · max(cos_theta_h, 0)^shininess,   factor = c(shininess)
/// ```
///
/// # Examples
///
/// ```
/// use brdf::normalization::{BlinnPhongLobe, Normalization, tri_ace_exact};
/// let lobe = BlinnPhongLobe::new(32.0_f32, Normalization::TriAceExact)?;
/// assert_eq!(lobe.factor(), tri_ace_exact(32.0_f32));
/// assert_eq!(lobe.eval(1.0_f32), lobe.factor());
/// assert!(BlinnPhongLobe::new(f32::NAN, Normalization::TriAceExact).is_err());
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlinnPhongLobe<S: Scalar> {
    shininess: S,
    factor: S,
    normalization: Normalization,
}

impl<S: Scalar> BlinnPhongLobe<S> {
    /// Builds the lobe and computes its factor `normalization.factor(shininess)`.
    ///
    /// # Errors
    ///
    /// `shininess` NaN, infinite or outside `[0, 2e8 − 2]` ([`Error::NotFinite`] /
    /// [`Error::OutOfDomain`] naming `"shininess"`; the bound is
    /// [`crate::ndf::MAX_SHININESS`], the sharpest lobe an `f32` direction resolves, and
    /// `wide`'s lane `powf` overflows from `s ≈ 1.6e16` on); a [`Normalization::TriAceFit`]
    /// offset outside `[0, 8]` (`"offset"`).
    #[inline]
    pub fn new(shininess: S, normalization: Normalization) -> Result<Self, Error> {
        let shininess =
            error::in_range("shininess", shininess, 0.0, MAX_SHININESS, "[0, 2e8 − 2]")?;
        let normalization = normalization.validate()?;
        let factor = normalization.factor(shininess);
        Ok(Self {
            shininess,
            factor,
            normalization,
        })
    }

    /// The exponent `s`.
    #[inline]
    #[must_use]
    pub fn shininess(&self) -> S {
        self.shininess
    }

    /// The precomputed factor `c(s)`.
    #[inline]
    #[must_use]
    pub fn factor(&self) -> S {
        self.factor
    }

    /// The normalization the factor was computed with.
    #[inline]
    #[must_use]
    pub fn normalization(&self) -> Normalization {
        self.normalization
    }

    /// `factor · max(cos_theta_h, 0)^shininess` on a scalar or on SIMD lanes.
    ///
    /// `cos_theta_h = N·H` (`wm.z` in the local frame). Negative cosines give `0`; for
    /// `shininess = 0` the lobe is the constant `factor` (`x⁰ = 1`, including `0⁰`).
    /// Finite for every `cos_theta_h ∈ [−1, 1]`.
    #[inline]
    #[must_use]
    pub fn eval<R: Real<Scalar = S>>(&self, cos_theta_h: R) -> R {
        R::splat(self.factor) * cos_theta_h.saturate().pow(R::splat(self.shininess))
    }
}

/// Validates a shininess range `0 ≤ s_min ≤ s_max < ∞` (strictly below when `strict`);
/// with `f32`, both must fit in `f32` (the tables hold `f32`).
fn check_range(s_min: f64, s_max: f64, strict: bool, f32: bool) -> Result<(), Error> {
    let check = |param, v: f64, domain, ok: &dyn Fn(f64) -> bool| {
        if f32 {
            error::check(param, v, domain, ok)
        } else {
            error::check_f64(param, v, domain, ok)
        }
    };
    check("s_min", s_min, "[0, ∞)", &|v| v >= 0.0)?;
    if strict {
        check("s_max", s_max, "(s_min, ∞)", &|v| v > s_min)?;
    } else {
        check("s_max", s_max, "[s_min, ∞)", &|v| v >= s_min)?;
    }
    Ok(())
}

/// Fills `out` with `normalization.factor(s)` at `out.len()` shininess values evenly
/// spaced over `[s_min, s_max]` (`out[0]` at `s_min`, the last at `s_max`).
///
/// For a shininess map whose texel values `0 … len − 1` encode shininess linearly: the
/// seed talk's suggestion of storing the factor alongside each shininess. Factors are
/// computed in `f64` and rounded once to `f32`. An empty `out` is left alone; one entry
/// holds the factor at `s_min`. [`NormalizationTable`] wraps a fixed-size table with
/// interpolation.
///
/// # Errors
///
/// `s_min` not finite or negative, `s_max` not finite or below `s_min`, or an invalid
/// [`Normalization::TriAceFit`] offset.
///
/// # Examples
///
/// ```
/// use brdf::normalization::{fill_table, Normalization};
/// let mut levels = [0.0_f32; 256];
/// fill_table(Normalization::TriAceExact, 0.0, 255.0, &mut levels)?;
/// assert!((levels[0] - 1.0 / (2.0 * core::f32::consts::PI)).abs() < 1e-7);
/// # Ok::<(), brdf::Error>(())
/// ```
pub fn fill_table(
    normalization: Normalization,
    s_min: f64,
    s_max: f64,
    out: &mut [f32],
) -> Result<(), Error> {
    check_range(s_min, s_max, false, true)?;
    let normalization = normalization.validate()?;
    let last = out.len().saturating_sub(1).max(1) as f64;
    for (i, v) in out.iter_mut().enumerate() {
        let s = grid_point(s_min, s_max, i as f64 / last);
        *v = normalization.factor(s) as f32;
    }
    Ok(())
}

/// `s_min + t (s_max − s_min)`, exact at both ends.
#[inline]
fn grid_point(s_min: f64, s_max: f64, t: f64) -> f64 {
    if t >= 1.0 {
        s_max
    } else {
        s_min + t * (s_max - s_min)
    }
}

/// A table of `N` normalization factors over a shininess range, built once, with linear
/// interpolation: per-level factors for a shininess map without `alloc`.
///
/// ```text
/// s_i = s_min + i·h,   h = (s_max − s_min)/(N − 1),   values[i] = c(s_i)  (f32)
/// lookup(s) = linear interpolation of values at clamp(s, s_min, s_max)
/// ```
///
/// Linear interpolation of the exact factor [`tri_ace_exact`] is very accurate because
/// `c(s) = (s + n₀(s))/(8π)` is linear in `s` up to the slowly varying
/// [`tri_ace_exact_offset`] `n₀`: the error is `h²/8 · |n₀''|/(s + n₀)` at most, with
/// `|n₀''| ≤ 0.056`. With `N = 256` over `[0, 255]` (`h = 1`) it stays below `1.6e−3`
/// relative, near `s = 0` only, and below the `f32` rounding from `s ≈ 60` on (measured in
/// `tests/normalization.rs`) — far better than the fit `(s + 2.04)/(8π)` at low `s`.
///
/// # Examples
///
/// ```
/// use brdf::normalization::{NormalizationTable, Normalization, tri_ace_exact};
/// let table = NormalizationTable::<256>::new(Normalization::TriAceExact, 0.0, 255.0)?;
/// assert_eq!(table.get(32), tri_ace_exact(32.0_f64) as f32);
/// let c = table.lookup(100.5);
/// assert!((c / tri_ace_exact(100.5_f32) - 1.0).abs() < 1e-5);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct NormalizationTable<const N: usize> {
    s_min: f32,
    s_max: f32,
    inv_step: f32,
    normalization: Normalization,
    values: [f32; N],
}

impl<const N: usize> NormalizationTable<N> {
    /// Builds the table of `N ≥ 2` entries (checked at compile time) over
    /// `[s_min, s_max]`.
    ///
    /// # Errors
    ///
    /// `s_min` not finite or negative, `s_max` not finite or `≤ s_min`, or an invalid
    /// [`Normalization::TriAceFit`] offset.
    pub fn new(normalization: Normalization, s_min: f64, s_max: f64) -> Result<Self, Error> {
        const { assert!(N >= 2, "a NormalizationTable needs at least two entries") };
        check_range(s_min, s_max, true, true)?;
        // The table lives in f32: tabulate at the f32-rounded range so that entries, their
        // shininess and the lookup agree exactly.
        let (s_min, s_max) = (s_min as f32, s_max as f32);
        check_range(s_min.into(), s_max.into(), true, true)?;
        let mut values = [0.0f32; N];
        fill_table(normalization, s_min.into(), s_max.into(), &mut values)?;
        Ok(Self {
            s_min,
            s_max,
            inv_step: ((N - 1) as f64 / (s_max as f64 - s_min as f64)) as f32,
            normalization,
            values,
        })
    }

    /// The tabulated factors, `values[i] = c(s_min + i·h)`.
    #[inline]
    #[must_use]
    pub fn values(&self) -> &[f32; N] {
        &self.values
    }

    /// The factor of entry `i` (panics if `i ≥ N`): an exact lookup for a shininess map
    /// whose level `i` means shininess [`NormalizationTable::shininess_at`]`(i)`.
    #[inline]
    #[must_use]
    pub fn get(&self, i: usize) -> f32 {
        self.values[i]
    }

    /// The shininess of entry `i`: `s_min + i·(s_max − s_min)/(N − 1)`.
    #[inline]
    #[must_use]
    pub fn shininess_at(&self, i: usize) -> f32 {
        grid_point(
            self.s_min as f64,
            self.s_max as f64,
            i as f64 / (N - 1) as f64,
        ) as f32
    }

    /// The shininess range `(s_min, s_max)`.
    #[inline]
    #[must_use]
    pub fn range(&self) -> (f32, f32) {
        (self.s_min, self.s_max)
    }

    /// The normalization the table holds.
    #[inline]
    #[must_use]
    pub fn normalization(&self) -> Normalization {
        self.normalization
    }

    /// Linearly interpolated factor at shininess `s`, clamped to `[s_min, s_max]`.
    ///
    /// NaN maps to `s_min`. Outside the range the end values are returned (the caller
    /// chooses a range that covers its shininess map).
    #[inline]
    #[must_use]
    pub fn lookup(&self, s: f32) -> f32 {
        let x = ((s - self.s_min) * self.inv_step).clamp(0.0, (N - 1) as f32);
        let x = if x.is_nan() { 0.0 } else { x };
        let i = (x as usize).min(N - 2);
        let t = x - i as f32;
        let (a, b) = (self.values[i], self.values[i + 1]);
        Real::mul_add(t, b - a, a)
    }
}

/// Tools that measure the linear fit `(s + n)/(8π)` of the seed's normalization against the
/// exact factor [`tri_ace_exact`] over a shininess
/// range: the error of a given offset ([`fit_error`](fit::fit_error))
/// and the minimax offset ([`best_fit_offset`](fit::best_fit_offset)).
/// For choosing an offset offline and for the report programs; rendering uses
/// [`Normalization`].
///
/// Reference: Y. Gotanda, "Basic of Reflectance", tri-Ace, 2009 (the fit and its offset
/// 2.04); the minimax search is this crate's.
pub mod fit {
    use super::{check_range, tri_ace_exact_offset};
    use crate::Real;
    use crate::error::{self, Error};

    /// The relative error of a linear fit `(s + offset)/(8π)` against [`tri_ace_exact`](super::tri_ace_exact) over a
    /// shininess range: where it is largest, and by how much.
    ///
    /// Relative error `e(s) = fit(s)/exact(s) − 1 = (offset − n₀(s))/(s + n₀(s))`, with
    /// `n₀` = [`tri_ace_exact_offset`]; negative where the fit is too dark.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct FitError {
        /// The offset `n` of the fit `(s + n)/(8π)`.
        pub offset: f64,
        /// `max |e(s)|` over the range: the minimax norm.
        pub max_rel_error: f64,
        /// A shininess where `|e|` reaches `max_rel_error`.
        pub at_shininess: f64,
        /// `max e(s)`: the largest overestimate (negative if the fit is too dark everywhere).
        pub highest: f64,
        /// Where `highest` is reached.
        pub highest_at: f64,
        /// `min e(s)`: the largest underestimate (positive if the fit is too bright everywhere).
        pub lowest: f64,
        /// Where `lowest` is reached.
        pub lowest_at: f64,
    }

    /// Relative error of the fit with `offset` at `s`, without cancellation.
    #[inline]
    fn fit_rel_error(s: f64, offset: f64) -> f64 {
        let n0 = tri_ace_exact_offset(s);
        (offset - n0) / (s + n0)
    }

    /// Maximum of `f` over `[a, b]`: a grid of `GRID` cells uniform in `ln(1 + s)` (dense at
    /// low shininess, where the error varies fastest), then golden-section search on the two
    /// cells around the best node. Returns `(max, argmax)`.
    fn maximize(f: impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
        const GRID: usize = 256;
        let (ua, ub) = (Real::ln(1.0 + a), Real::ln(1.0 + b));
        let node = |k: usize| -> f64 {
            match k {
                0 => a,
                GRID => b,
                _ => (Real::exp(ua + (ub - ua) * k as f64 / GRID as f64) - 1.0).clamp(a, b),
            }
        };
        let (mut best, mut arg, mut k_best) = (f(a), a, 0);
        for k in 1..=GRID {
            let s = node(k);
            let v = f(s);
            if v > best {
                (best, arg, k_best) = (v, s, k);
            }
        }
        // Golden-section search on [node(k−1), node(k+1)] (a unimodal bracket when the grid
        // resolves the extremum).
        let (mut lo, mut hi) = (node(k_best.saturating_sub(1)), node((k_best + 1).min(GRID)));
        const INV_PHI: f64 = 0.618_033_988_749_894_9;
        let mut x1 = hi - INV_PHI * (hi - lo);
        let mut x2 = lo + INV_PHI * (hi - lo);
        let (mut f1, mut f2) = (f(x1), f(x2));
        for _ in 0..120 {
            if hi - lo <= f64::EPSILON * hi.abs().max(1e-300) {
                break;
            }
            if f1 < f2 {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + INV_PHI * (hi - lo);
                f2 = f(x2);
            } else {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - INV_PHI * (hi - lo);
                f1 = f(x1);
            }
        }
        for (v, s) in [(f1, x1), (f2, x2)] {
            if v > best {
                (best, arg) = (v, s);
            }
        }
        (best, arg)
    }

    /// `(max e, argmax, min e, argmin)` of the fit's relative error over `[a, b]`.
    fn error_extremes(offset: f64, a: f64, b: f64) -> (f64, f64, f64, f64) {
        let (hi, hi_at) = maximize(|s| fit_rel_error(s, offset), a, b);
        let (neg_lo, lo_at) = maximize(|s| -fit_rel_error(s, offset), a, b);
        (hi, hi_at, -neg_lo, lo_at)
    }

    /// Measures the linear fit `(s + offset)/(8π)` against the exact factor [`tri_ace_exact`](super::tri_ace_exact)
    /// over `[s_min, s_max]`: the maximum relative error and where it peaks.
    ///
    /// ```text
    /// e(s) = (s + offset)/(8π) / c(s) − 1 = (offset − n₀(s)) / (s + n₀(s))
    /// max_rel_error = max_{s ∈ [s_min, s_max]} |e(s)|
    /// ```
    ///
    /// Use it to see what the cheap fit costs on your own content's shininess range.
    ///
    /// # Method
    ///
    /// `e` is evaluated on 257 points uniform in `ln(1 + s)` plus the ends, and the best point
    /// is refined by golden-section search to full precision. For `offset ≤ 2`, `e` increases
    /// monotonically; for `2 < offset ≤ 4` it rises to one interior maximum and then decays
    /// (`e′(s) ∝ (s + n)(s + 2)·(ln 2/2)·2^(−s/2) − (n − 2)(2 − 2^(−s/2))`); both shapes are
    /// resolved by the grid (checked against a dense scan in the tests).
    ///
    /// # Errors
    ///
    /// `offset` not finite; `s_min` not finite or negative; `s_max` not finite or below
    /// `s_min`.
    ///
    /// # Examples
    ///
    /// ```
    /// use brdf::normalization::{TRI_ACE_OFFSET, fit::fit_error};
    /// let e = fit_error(TRI_ACE_OFFSET, 0.0, 1e4)?;
    /// assert!((e.max_rel_error - 0.49).abs() < 1e-12 && e.at_shininess == 0.0);
    /// let e = fit_error(TRI_ACE_OFFSET, 16.0, 1e4)?;
    /// assert!(e.max_rel_error < 1.5e-3 && (e.at_shininess - 22.75).abs() < 0.1);
    /// # Ok::<(), brdf::Error>(())
    /// ```
    pub fn fit_error(offset: f64, s_min: f64, s_max: f64) -> Result<FitError, Error> {
        error::check_f64("offset", offset, "(−∞, ∞)", |_| true)?;
        check_range(s_min, s_max, false, false)?;
        Ok(fit_error_unchecked(offset, s_min, s_max))
    }

    fn fit_error_unchecked(offset: f64, s_min: f64, s_max: f64) -> FitError {
        let (highest, highest_at, lowest, lowest_at) = error_extremes(offset, s_min, s_max);
        let (max_rel_error, at_shininess) = if highest >= -lowest {
            (highest.abs(), highest_at)
        } else {
            (lowest.abs(), lowest_at)
        };
        FitError {
            offset,
            max_rel_error,
            at_shininess,
            highest,
            highest_at,
            lowest,
            lowest_at,
        }
    }

    /// The offset `n` minimizing the maximum relative error of `(s + n)/(8π)` against
    /// [`tri_ace_exact`](super::tri_ace_exact) over `[s_min, s_max]`, with that error.
    ///
    /// ```text
    /// n* = argmin_n max_{s ∈ [s_min, s_max]} |(n − n₀(s)) / (s + n₀(s))|      (minimax relative error)
    /// ```
    ///
    /// # Method
    ///
    /// `e(s, n)` increases strictly with `n` at every `s`, so `U(n) = max_s e` and
    /// `L(n) = min_s e` are increasing, and the minimax optimum is the root of `U(n) + L(n)`,
    /// where over- and underestimate balance (`U = −L`). It lies in `[2, 4]` because
    /// `2 < n₀(s) ≤ 4` (all errors are `≤ 0` at `n = 2` and `≥ 0` at `n = 4`); bisection finds
    /// it to machine precision. Each `U`, `L` comes from the search of [`fit_error`].
    ///
    /// For `[s_min, ∞)`-like ranges (`s_max ≳ 23`) the optimum depends on `s_min` only:
    /// `s_min = 0 → n* = 3.528` (error 11.8 %), `8 → 2.218` (1.0 %), `14 → 2.040` (0.143 %:
    /// the seed talk's value), `16 → 2.022` (0.073 %).
    ///
    /// # Errors
    ///
    /// `s_min` not finite or negative; `s_max` not finite or below `s_min`.
    ///
    /// # Examples
    ///
    /// ```
    /// use brdf::normalization::fit::best_fit_offset;
    /// let best = best_fit_offset(14.0, 1e4)?;
    /// assert!((best.offset - 2.04).abs() < 1e-3);
    /// assert!(best.max_rel_error < 1.5e-3);
    /// # Ok::<(), brdf::Error>(())
    /// ```
    pub fn best_fit_offset(s_min: f64, s_max: f64) -> Result<FitError, Error> {
        check_range(s_min, s_max, false, false)?;
        let (mut lo, mut hi) = (2.0f64, 4.0f64);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let (u, _, l, _) = error_extremes(mid, s_min, s_max);
            if u + l > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Ok(fit_error_unchecked(0.5 * (lo + hi), s_min, s_max))
    }
}
