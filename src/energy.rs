//! Directional albedo of microfacet reflection with `F = 1`, and the building blocks of the
//! multiple-scattering compensations (Kulla & Conty 2017, Turquin 2019).
//!
//! # Definitions
//!
//! For a Cook-Torrance lobe `f = D F G2 / (4 cos θi cos θo)` with `F = 1` and the
//! height-correlated Smith term (the masking of the crate's default microfacet models,
//! [`SmithHeightCorrelated`](crate::masking::SmithHeightCorrelated)):
//!
//! ```text
//! E(μo, α)  = ∫_{H²} f(wi, wo) cos θi dωi,                  μo = cos θo ∈ (0, 1]
//! E_avg(α)  = 2 ∫_0^1 E(μ, α) μ dμ
//! F_avg     = 2 ∫_0^1 F(μ) μ dμ
//! ```
//!
//! # Method
//!
//! A fixed tensor Gauss-Legendre rule over the microfacet normal, in the variable `v` (the
//! NDF's own CDF in `tan²θm`) and `φm`, with the `v` range stopped exactly at the horizon of
//! `wi` (derived in [`directional_albedo`]). The heavy GGX tail, the peak of `D` at small `α`
//! and the grazing cut-off are then smooth for the rule at every `α` and `μ`.
//!
//! References: B. Walter, S. Marschner, H. Li, K. Torrance, "Microfacet Models for Refraction
//! through Rough Surfaces", EGSR 2007; E. Heitz, "Understanding the Masking-Shadowing Function
//! in Microfacet-Based BRDFs", JCGT 3(2), 2014; C. Kulla, A. Conty, "Revisiting Physically
//! Based Shading at Imageworks", SIGGRAPH 2017 course *Physically Based Shading in Theory and
//! Practice*; E. Turquin, "Practical multiple scattering compensation for microfacet models",
//! Industrial Light & Magic technical report, 2019.

use crate::fresnel::FresnelTerm;
use crate::ndf::{Beckmann, Ggx, SmithLambda};
use crate::{Error, Real, Vec3};

/// Gauss-Legendre nodes per panel of the albedo quadratures.
pub const ORDER: usize = 16;
/// Panels per axis of the albedo quadratures (equal widths on `[0, 1]`).
pub const PANELS: usize = 4;

/// Gauss-Legendre nodes and weights of order `N` on `[0, 1]`, by Newton's method on the
/// three-term recurrence of the Legendre polynomials (Abramowitz & Stegun 25.4.29).
///
/// Domain: `N ≥ 1`. Nodes ascending, weights summing to 1 (to rounding).
#[must_use]
pub fn gauss_legendre<const N: usize>() -> ([f64; N], [f64; N]) {
    let mut x = [0.0; N];
    let mut w = [0.0; N];
    let n = N as f64;
    for i in 0..N {
        // Initial guess: the Chebyshev-like estimate of the (i+1)-th root from the right.
        let mut z = Real::cos(core::f64::consts::PI * (i as f64 + 0.75) / (n + 0.5));
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=N {
                let k = k as f64;
                let p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            let p = if N == 1 { z } else { p1 };
            let pm1 = if N == 1 { 1.0 } else { p0 };
            dp = n * (z * p - pm1) / (z * z - 1.0);
            let dz = p / dp;
            z -= dz;
            if Real::abs(dz) < 1e-16 {
                break;
            }
        }
        // Map [-1, 1] → [0, 1]: node (1 − z)/2 ascending as z descends.
        x[i] = 0.5 * (1.0 - z);
        w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
    }
    (x, w)
}

/// Integrates `g` over `[0, 1]` with [`PANELS`] panels of [`ORDER`]-point Gauss-Legendre.
fn integrate_01(nodes: &([f64; ORDER], [f64; ORDER]), mut g: impl FnMut(f64) -> f64) -> f64 {
    let h = 1.0 / PANELS as f64;
    let mut sum = 0.0;
    for p in 0..PANELS {
        let a = p as f64 * h;
        for k in 0..ORDER {
            sum += nodes.1[k] * h * g(a + nodes.0[k] * h);
        }
    }
    sum
}

/// The microfacet distributions [`directional_albedo`] integrates: isotropic GGX and
/// Beckmann, each given by the inverse of its slope CDF.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distribution {
    /// GGX / Trowbridge-Reitz: `P(tan²θm ≤ T) = T/(α² + T)`, so `T(v) = α² v/(1 − v)`.
    Ggx,
    /// Beckmann: `P(tan²θm ≤ T) = 1 − e^(−T/α²)`, so `T(v) = −α² ln(1 − v)`.
    Beckmann,
}

/// Directional albedo `E(μo) = ∫ f cos θi dωi` of the isotropic lobe
/// `D·G2/(4 cos θi cos θo)` with `F = 1` and the height-correlated Smith term
/// `G2 = 1/(1 + Λ(wi) + Λ(wo))` (the masking of the crate's default microfacet models).
///
/// **Method (derived).** Over the microfacet normal (`dωi = 4 (wo·wm) dωm`, Walter et al.
/// 2007, eq. 14) and with `v` the NDF's CDF in `tan²θm` (`dv dφ/(2π) = D cos θm dωm`):
///
/// ```text
/// E(μo) = (1/π) ∫_0^π dφm ∫_0^{v_h(φm)} G2(wi, wo) (wo·wm) / (μo cos θm) dv
/// wi.z = 0  ⇔  μo t² − 2 sin θo cos φm t − μo = 0,  t = tan θm:
/// t_h = (sin θo cos φm + √(sin²θo cos²φm + μo²)) / μo
/// ```
///
/// `wi.z > 0` exactly for `tan θm < t_h`, and that implies `wo·wm > 0`; so the `v` integral
/// stops at the horizon instead of carrying a jump, the peak of `D` (width `α`) and its
/// heavy GGX tail are both spread evenly over `v`, and the integrand is smooth on `[0, v_h]`. Both
/// axes use [`PANELS`] × [`ORDER`] Gauss-Legendre nodes (4096 evaluations); the rule is
/// fixed, so results are deterministic.
///
/// Domain: `alpha ∈ [1e-4, 1]` (validated as by the NDF constructors), `cos_theta_o ∈
/// [0, 1]` (clamped to `[1e-6, 1]`). Result in `[0, 1]`; `E → 1` as
/// `α → 0`. Accuracy against the crate's adaptive reference: see `tests/energy.rs`.
///
/// References: Walter et al., EGSR 2007; E. Heitz, "Understanding the Masking-Shadowing
/// Function in Microfacet-Based BRDFs", JCGT 3(2), 2014.
///
/// ```
/// use brdf::analysis::{directional_albedo as adaptive, AlbedoConfig};
/// use brdf::energy::{directional_albedo, Distribution};
/// use brdf::{fresnel::NoFresnel, masking::SmithHeightCorrelated, models::CookTorrance};
/// use brdf::{ndf::Ggx, Vec3};
///
/// // GGX, α = 1, normal view: a large part of the energy is lost to single scattering.
/// let e = directional_albedo(Distribution::Ggx, 1.0, 1.0)?;
/// let ct = CookTorrance::new(Ggx::new(1.0)?, NoFresnel, SmithHeightCorrelated);
/// let [r] = adaptive::<_, f64, 1>(&ct, Vec3::new(0.0, 0.0, 1.0), &AlbedoConfig::DEFAULT);
/// assert!((e - r).abs() < 1e-4 && e < 0.9);
/// # Ok::<(), brdf::Error>(())
/// ```
///
/// # Errors
/// [`Error::NotFinite`] or [`Error::OutOfDomain`] for `alpha` outside `[1e-4, 1]` or
/// `cos_theta_o` outside `[0, 1]`.
pub fn directional_albedo(
    distribution: Distribution,
    alpha: f64,
    cos_theta_o: f64,
) -> Result<f64, Error> {
    crate::error::unit_interval("cos_theta_o", cos_theta_o)?;
    crate::error::check("alpha", alpha, "[1e-4, 1]", |a| (1e-4..=1.0).contains(&a))?;
    Ok(match distribution {
        Distribution::Ggx => match Ggx::new(alpha) {
            Ok(ndf) => albedo_with(
                &ndf,
                cos_theta_o,
                |w| alpha * alpha * (1.0 - w * w) / (w * w),
                |t2| alpha / Real::sqrt(alpha * alpha + t2),
            ),
            Err(e) => return Err(e),
        },
        Distribution::Beckmann => match Beckmann::new(alpha) {
            Ok(ndf) => albedo_with(
                &ndf,
                cos_theta_o,
                |w| -2.0 * alpha * alpha * Real::ln(w),
                |t2| Real::exp(-0.5 * t2 / (alpha * alpha)),
            ),
            Err(e) => return Err(e),
        },
    })
}

fn albedo_with<D: SmithLambda<f64>>(
    ndf: &D,
    cos_theta_o: f64,
    tan2_of_w: impl Fn(f64) -> f64,
    w_of_tan2: impl Fn(f64) -> f64,
) -> f64 {
    let mu = cos_theta_o.clamp(1e-6, 1.0);
    let s = Real::sqrt(1.0 - mu * mu);
    let wo = Vec3::new(s, 0.0, mu);
    let lo = ndf.lambda(wo);
    let nodes = gauss_legendre::<ORDER>();
    let inner = |phi: f64| {
        let (sp, cp) = (Real::sin(phi), Real::cos(phi));
        let th = (s * cp + Real::sqrt(s * s * cp * cp + mu * mu)) / mu;
        let t2h = th * th;
        // w = √(1 − v) from w_h (the horizon) to 1 (the normal); dv = 2w dw.
        let w_h = w_of_tan2(t2h);
        let len = 1.0 - w_h;
        len * integrate_01(&nodes, |x| {
            let w = w_h + len * x;
            let t2 = tan2_of_w(w).min(t2h);
            let c = 1.0 / Real::sqrt(1.0 + t2);
            let st = Real::sqrt(t2) * c;
            let wm = Vec3::new(st * cp, st * sp, c);
            let d = wo.dot(wm);
            let wi = Vec3::new(
                2.0 * d * wm.x - wo.x,
                2.0 * d * wm.y - wo.y,
                2.0 * d * wm.z - wo.z,
            );
            if wi.z <= 0.0 || d <= 0.0 {
                0.0
            } else {
                2.0 * w * d / (mu * c * (1.0 + lo + ndf.lambda(wi)))
            }
        })
    };
    // The horizon bound v_h(φ) turns from ≈ 1 to ≈ 0 where cos φm crosses a band of width
    // ~μo around 0: panels in φm graded geometrically in cos φm = ±μo·4^k resolve it.
    let mut total = 0.0;
    let mut prev = 0.0; // φ of the previous break point
    let mut k = 0;
    loop {
        // Break points in descending cos φ: 1 > … > μ·4^k > … > 0 > … > −μ·4^k > … > −1.
        let next = match graded_break(mu, k) {
            Some(c) => acos(c),
            None => core::f64::consts::PI,
        };
        let h = next - prev;
        if h > 0.0 {
            total += h * integrate_01(&nodes, |y| inner(prev + h * y));
        }
        if next >= core::f64::consts::PI {
            break;
        }
        prev = next;
        k += 1;
    }
    total / core::f64::consts::PI
}

/// The `k`-th break point in `cos φm` (descending) of the graded φ mesh, `None` past −1.
fn graded_break(mu: f64, k: usize) -> Option<f64> {
    // Levels μ·4^j below 1 (at most 11 for μ ≥ 1e-6), then 0, then the negatives.
    let mut levels = [0.0; 12];
    let mut n = 0;
    let mut c = mu;
    while c < 1.0 && n < levels.len() {
        levels[n] = c;
        n += 1;
        c *= 4.0;
    }
    // Sequence: levels[n-1], …, levels[0], 0, −levels[0], …, −levels[n-1].
    if k < n {
        Some(levels[n - 1 - k])
    } else if k == n {
        Some(0.0)
    } else if k <= 2 * n {
        Some(-levels[k - n - 1])
    } else {
        None
    }
}

/// Hemispherical average `E_avg = 2 ∫_0^1 E(μ) μ dμ` of [`directional_albedo`], by
/// [`PANELS`] × [`ORDER`] Gauss-Legendre nodes in `μ`. Result in `[0, 1]`; 1 in the limit
/// `α → 0`.
///
/// Reference: Kulla & Conty 2017 (`E_avg`).
///
/// # Errors
/// As [`directional_albedo`] for `alpha`.
pub fn average_albedo(distribution: Distribution, alpha: f64) -> Result<f64, Error> {
    directional_albedo(distribution, alpha, 1.0)?;
    let nodes = gauss_legendre::<ORDER>();
    Ok(2.0
        * integrate_01(&nodes, |mu| {
            directional_albedo(distribution, alpha, mu).unwrap_or(0.0) * mu
        }))
}

/// Cosine-weighted hemispherical average of a Fresnel term, `F_avg = 2 ∫_0^1 F(μ) μ dμ`,
/// per channel, by [`PANELS`] × [`ORDER`] Gauss-Legendre nodes (exact to ~1e-12 for the
/// smooth dielectric and conductor terms; a dielectric's total-internal-reflection kink is
/// not split, see the tests for the achieved accuracy).
///
/// Reference: Kulla & Conty 2017 (`F_avg`).
#[must_use]
pub fn fresnel_average<F: FresnelTerm<f64, N>, const N: usize>(fresnel: &F) -> [f64; N] {
    let nodes = gauss_legendre::<ORDER>();
    core::array::from_fn(|c| 2.0 * integrate_01(&nodes, |mu| fresnel.eval(mu)[c] * mu))
}

/// `F_avg` of Schlick's approximation `F = F0 + (1 − F0)(1 − μ)⁵`, in closed form:
///
/// ```text
/// F_avg = F0 + (1 − F0) · 2 ∫ (1 − μ)⁵ μ dμ = F0 + (1 − F0) · 2 B(2, 6) = (20 F0 + 1) / 21
/// ```
///
/// Domain `F0 ∈ [0, 1]`. Reference: C. Schlick, "An Inexpensive BRDF Model for
/// Physically-based Rendering", Computer Graphics Forum 13(3), 1994; Kulla & Conty 2017.
#[inline(always)]
#[must_use]
pub fn schlick_average<R: Real>(f0: R) -> R {
    (R::from_f64(20.0) * f0 + R::one()) / R::from_f64(21.0)
}

/// The Fresnel factor of Kulla & Conty's multiple-scattering lobe: the sum over bounces
/// `k ≥ 1` of `F_avg^(k+1) E_avg (1 − E_avg)^(k−1)` renormalized to the energy `1 − E_avg`
/// the single-scattering lobe loses:
///
/// ```text
/// F_ms = F_avg² E_avg / (1 − F_avg (1 − E_avg))
/// ```
///
/// Domain `F_avg, E_avg ∈ [0, 1]` (finite: the denominator is ≥ `E_avg`, and `F_ms = 1` at
/// `F_avg = 1`). Reference: Kulla & Conty 2017.
#[inline(always)]
#[must_use]
pub fn kulla_conty_fresnel<R: Real>(f_avg: R, e_avg: R) -> R {
    f_avg * f_avg * e_avg / (R::one() - f_avg * (R::one() - e_avg)).max(R::from_f64(1e-30))
}

/// Kulla & Conty's multiple-scattering lobe with `F = 1` (multiply by [`kulla_conty_fresnel`]):
///
/// ```text
/// f_ms(wi, wo) = (1 − E(μi)) (1 − E(μo)) / (π (1 − E_avg))
/// ```
///
/// Symmetric in `μi, μo` (reciprocal); with `F = 1` its albedo is
/// `(1 − E(μo)) · 2∫(1 − E(μ))μ dμ / (1 − E_avg) = 1 − E(μo)`, so `E + ∫ f_ms cos = 1`.
/// Domain: `E(μi), E(μo), E_avg ∈ [0, 1]`; the denominator is floored at `1e-30` (it is 0
/// only at `α = 0`, where the numerator is 0 too). Reference: Kulla & Conty 2017.
#[inline(always)]
#[must_use]
pub fn kulla_conty_lobe<R: Real>(e_i: R, e_o: R, e_avg: R) -> R {
    (R::one() - e_i) * (R::one() - e_o) / (R::pi() * (R::one() - e_avg)).max(R::from_f64(1e-30))
}

/// Turquin's energy-compensation factor, which scales the single-scattering lobe:
///
/// ```text
/// f = (1 + F0 (1 − E(μo)) / E(μo)) · f_ss
/// ```
///
/// With `F = F0 = 1` the compensated albedo is exactly `E(μo)/E(μo) = 1`. It depends on `μo`
/// only, so the compensated BRDF is **not reciprocal**. Domain `F0 ∈ [0, 1]`, `E ∈ (0, 1]`
/// (floored at `1e-30`). Reference: Turquin 2019.
#[inline(always)]
#[must_use]
pub fn turquin_factor<R: Real>(f0: R, e_o: R) -> R {
    R::one() + f0 * (R::one() - e_o) / e_o.max(R::from_f64(1e-30))
}

/// `acos` on `[-1, 1]` for the quadrature mesh, by `atan2`-free bisection-free identity
/// `acos c = 2 atan(√((1 − c)/(1 + c)))` evaluated with [`atan`].
fn acos(c: f64) -> f64 {
    2.0 * atan(Real::sqrt((1.0 - c) / (1.0 + c)))
}

/// `atan x` for `x ≥ 0`: argument reduction to `[0, tan(π/12)]` and a Taylor series
/// (error below 1e-16 there), so the crate needs no libm `atan`.
fn atan(x: f64) -> f64 {
    use core::f64::consts::FRAC_PI_2;
    let (x, flip) = if x > 1.0 { (1.0 / x, true) } else { (x, false) };
    // atan x = π/6 + atan((x√3 − 1)/(x + √3)) for x > tan(π/12).
    let t15 = 2.0 - Real::sqrt(3.0);
    let (y, off) = if x > t15 {
        let r3 = Real::sqrt(3.0);
        ((x * r3 - 1.0) / (x + r3), core::f64::consts::FRAC_PI_6)
    } else {
        (x, 0.0)
    };
    let y2 = y * y;
    let mut term = y;
    let mut sum = 0.0;
    for k in 0..20 {
        sum += term / f64::from(2 * k + 1);
        term *= -y2;
    }
    let a = off + sum;
    if flip { FRAC_PI_2 - a } else { a }
}

/// `F_avg` of Hoffman's F82-tint Fresnel ([`crate::fresnel::f82_tint_with_b`]) in closed
/// form, from its `F0` and correction coefficient `b`:
///
/// ```text
/// F(μ)  = F0 + (1 − F0)(1 − μ)⁵ − b μ (1 − μ)⁶
/// F_avg = 2 ∫_0^1 F(μ) μ dμ = (20 F0 + 1)/21 − 2 b B(3, 7) = (20 F0 + 1)/21 − b/126
/// ```
///
/// (`B(3, 7) = 2! 6!/9! = 1/252`.) Exact for the curve as written; the crate's term clamps
/// it to `[0, 1]`, which changes nothing unless the correction is strong enough to push the
/// curve outside (large `b`, Open PBR issue #256) — then the quadrature
/// [`fresnel_average`] of the clamped term is the exact one. Domain `F0 ∈ [0, 1]`, `b`
/// finite.
///
/// References: N. Hoffman, "Fresnel Equations Considered Harmful", 2019; A. Kutz et al.,
/// "Novel aspects of the Adobe Standard Material", 2021; Kulla & Conty 2017 (`F_avg`).
#[inline(always)]
#[must_use]
pub fn f82_average<R: Real>(f0: R, b: R) -> R {
    schlick_average(f0) - b * R::from_f64(1.0 / 126.0)
}
