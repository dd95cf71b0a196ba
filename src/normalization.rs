//! Normalization factors of Blinn-Phong and Phong lobes: the core result of the seed talk.
//!
//! A lobe `(N·H)^s` reflects more or less light depending on its shininess `s`; a
//! normalization factor `c(s)` scales it so that the reflected total is `1` (times the
//! specular colour) whatever `s` is. Which total is made `1` differs between models, and the
//! factors below are **not interchangeable**: each documents the integral it normalizes.
//!
//! | function | integral set to 1 | large-`s` behaviour |
//! |---|---|---|
//! | [`tri_ace_exact`] | `∫ (N·H)^s dω`, `L = N` (seed talk, Gotanda 2009) | `(s + 2)/(8π)` |
//! | [`tri_ace_fit`] | linear fit of the above, `(s + n)/(8π)`, `n =` [`TRI_ACE_OFFSET`] | `(s + 2.04)/(8π)` |
//!
//! The seed's normalized Blinn-Phong is
//!
//! ```text
//! f_spec(wi, wo) · cos θi = R_s · c(s) · F · (N·H)^s      (no cos θi in the rendered term)
//! c(s) = (s + 2) / (4π (2 − 2^(−s/2)))  ≈  (s + 2.04) / (8π)
//! ```
//!
//! # References
//!
//! * Y. Gotanda, "本当のHDR表現へ — アーティストにも知ってほしいリフレクタンスの基礎" (Beyond a
//!   glare effect for HDR rendering — Basic of Reflectance), tri-Ace, Imagine Day 2009:
//!   the integral, its reciprocal and the fit `(s + 2.04)/(8π)`.

use crate::Real;

/// The seed talk's fitted offset `n = 2.04` of the linear normalization `(s + n)/(8π)`.
///
/// Gotanda 2009 ("Basic of Reflectance", tri-Ace) replaces the exact factor
/// [`tri_ace_exact`] by `(s + 2.04)/(8π)`. Use it with [`tri_ace_fit`].
pub const TRI_ACE_OFFSET: f64 = 2.04;

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
/// damped by `2^(−s/2)/(2 − 2^(−s/2)) ≤ 1`. The result is within a few ULP of the true value
/// for every `s` (see `tests/normalization.rs`); `2^(−s/2)` underflowing to `0` for huge
/// `s` is harmless.
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
    R::from_f64(FOUR_PI) * (two - exp2_neg_half(s)) / (s + two)
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
    (s + two) / (R::from_f64(FOUR_PI) * (two - exp2_neg_half(s)))
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
