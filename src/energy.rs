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

/// The 16-point Gauss-Legendre rule on `[0, 1]` (nodes ascending, weights) as shipped:
/// [`gauss_legendre`]`::<16>()` computed by the generator (`tools/` `energy_tables`) and
/// stored in the table file, bit for bit (`tests/energy_tables.rs`), so that a construction
/// that integrates over `μ` (the series average of `models::AlbedoFit`, [`fresnel_average`])
/// does not spend about 5 µs on Newton's method for the Legendre roots.
#[must_use]
pub fn gauss_legendre_16() -> (&'static [f64; 16], &'static [f64; 16]) {
    (&tables::GL16_X, &tables::GL16_W)
}

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
    let [e] = lobe_moments(distribution, alpha, cos_theta_o, |_| [1.0])?;
    Ok(e)
}

/// `∫ D G2 w(wo·wm) / (4 cos θi cos θo) cos θi dωi` for `K` weights `w` of `wo·wm` at once, by
/// the rule of [`directional_albedo`] (which is the case `K = 1`, `w = 1`; the split-sum
/// table takes Schlick's two weights). Validates as [`directional_albedo`].
pub(crate) fn lobe_moments<const K: usize>(
    distribution: Distribution,
    alpha: f64,
    cos_theta_o: f64,
    weight: impl Fn(f64) -> [f64; K],
) -> Result<[f64; K], Error> {
    crate::error::unit_interval("cos_theta_o", cos_theta_o)?;
    crate::error::check("alpha", alpha, "[1e-4, 1]", |a| (1e-4..=1.0).contains(&a))?;
    Ok(match distribution {
        Distribution::Ggx => match Ggx::new(alpha) {
            Ok(ndf) => albedo_with(
                &ndf,
                cos_theta_o,
                |w| alpha * alpha * (1.0 - w * w) / (w * w),
                |t2| alpha / Real::sqrt(alpha * alpha + t2),
                weight,
            ),
            Err(e) => return Err(e),
        },
        Distribution::Beckmann => match Beckmann::new(alpha) {
            Ok(ndf) => albedo_with(
                &ndf,
                cos_theta_o,
                |w| -2.0 * alpha * alpha * Real::ln(w),
                |t2| Real::exp(-0.5 * t2 / (alpha * alpha)),
                weight,
            ),
            Err(e) => return Err(e),
        },
    })
}

fn albedo_with<D: SmithLambda<f64>, const K: usize>(
    ndf: &D,
    cos_theta_o: f64,
    tan2_of_w: impl Fn(f64) -> f64,
    w_of_tan2: impl Fn(f64) -> f64,
    weight: impl Fn(f64) -> [f64; K],
) -> [f64; K] {
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
        // Near the horizon end (x → 0) the weight behaves as wi.z/(wi.z + μo) (Λ(wi) ≈ α/2wi.z
        // against Λ(wo) ≈ α/2μo): a layer of width ≈ w_h/len in x that uniform panels miss by
        // a few 1e-6 at μo → 0 (then E > 1). Panels graded geometrically from that width up.
        let layer = (w_h / len).max(1e-9);
        let sum = integrate_01_graded(&nodes, layer, |x| {
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
                [0.0; K]
            } else {
                let e = 2.0 * w * d / (mu * c * (1.0 + lo + ndf.lambda(wi)));
                weight(d).map(|k| k * e)
            }
        });
        sum.map(|v| len * v)
    };
    // The horizon bound v_h(φ) turns from ≈ 1 to ≈ 0 where cos φm crosses a band of width
    // ~μo around 0: panels in φm graded geometrically in cos φm = ±μo·4^k resolve it.
    graded_phi_average(mu, &nodes, inner)
}

/// `(1/π) ∫_0^π g(φ) dφ` by [`integrate_01_k`] panels between the break points
/// `acos(±μ·4^k)` ([`graded_break`]): graded towards `φ = π/2`, where the horizon of a
/// view at `cos θo = μ` sweeps through a band of width `~μ`. One body for the albedo rules.
fn graded_phi_average<const K: usize>(
    mu: f64,
    nodes: &([f64; ORDER], [f64; ORDER]),
    mut g: impl FnMut(f64) -> [f64; K],
) -> [f64; K] {
    let mut total = [0.0; K];
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
            let panel = integrate_01_k(nodes, |y| g(prev + h * y));
            for (t, p) in total.iter_mut().zip(panel) {
                *t += h * p;
            }
        }
        if next >= core::f64::consts::PI {
            break;
        }
        prev = next;
        k += 1;
    }
    total.map(|t| t / core::f64::consts::PI)
}

/// [`integrate_01_k`] with the first panel `[0, 1/PANELS]` split at `layer·4^k` (nodes
/// graded towards 0, for an integrand with a boundary layer of width `layer` there).
fn integrate_01_graded<const K: usize>(
    nodes: &([f64; ORDER], [f64; ORDER]),
    layer: f64,
    mut g: impl FnMut(f64) -> [f64; K],
) -> [f64; K] {
    let h = 1.0 / PANELS as f64;
    let mut sum = [0.0; K];
    let mut panel = |a: f64, b: f64, sum: &mut [f64; K]| {
        for k in 0..ORDER {
            let v = g(a + nodes.0[k] * (b - a));
            for (s, v) in sum.iter_mut().zip(v) {
                *s += nodes.1[k] * (b - a) * v;
            }
        }
    };
    let (mut a, mut b) = (0.0, layer);
    while b < h {
        panel(a, b, &mut sum);
        a = b;
        b *= 4.0;
    }
    panel(a, h, &mut sum);
    for p in 1..PANELS {
        panel(p as f64 * h, (p + 1) as f64 * h, &mut sum);
    }
    sum
}

/// [`integrate_01`] for `K` integrands at once (the same nodes, sums and rounding per
/// component as `K` separate calls).
fn integrate_01_k<const K: usize>(
    nodes: &([f64; ORDER], [f64; ORDER]),
    mut g: impl FnMut(f64) -> [f64; K],
) -> [f64; K] {
    let h = 1.0 / PANELS as f64;
    let mut sum = [0.0; K];
    for p in 0..PANELS {
        let a = p as f64 * h;
        for k in 0..ORDER {
            let v = g(a + nodes.0[k] * h);
            for (s, v) in sum.iter_mut().zip(v) {
                *s += nodes.1[k] * h * v;
            }
        }
    }
    sum
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
    // The shipped 16-point rule: `gauss_legendre::<ORDER>()` bit for bit, without its
    // Newton iterations (most of the cost of a call).
    const { assert!(ORDER == 16) };
    let (x, w) = gauss_legendre_16();
    let nodes = (*x, *w);
    // One evaluation per node for all channels (the same sums, bit for bit, as one
    // integral per channel: `integrate_01_k`).
    integrate_01_k(&nodes, |mu| fresnel.eval(mu).map(|f| f * mu)).map(|v| 2.0 * v)
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

// ---------------------------------------------------------------------------------------
// Shipped tables of E(μ, α) and E_avg(α)
// ---------------------------------------------------------------------------------------

mod tables;

/// Nodes of the shipped albedo tables along the view axis `s` ([`albedo_table_s`]).
///
/// (To change a table size: set it here, run `cargo run --release -p brdf-tools --bin
/// energy_tables`, which rewrites `src/energy/tables.rs`; the tables are slices, so the crate
/// compiles before they are regenerated, and `tests/energy_tables.rs` checks their lengths.)
pub const ALBEDO_TABLE_MU: usize = 128;
/// Nodes of the shipped albedo tables along the roughness axis `t` ([`albedo_table_t`]).
pub const ALBEDO_TABLE_ALPHA: usize = 64;

/// Smallest `α` of the tables (and of [`directional_albedo`]'s domain).
const ALPHA_MIN: f64 = 1e-4;

/// The view coordinate of the albedo tables, `s = √(μ (1 + α) / (μ + α))` ∈ `[0, 1]`.
///
/// Two features of `E(μ, α)` set it. As `α → 0`, `E` becomes a function of `μ/α` alone (the
/// lobe and the masking `Λ(a)`, `a = cot θo / α`, both scale with `α` in slope space), with a
/// dip at `μ ~ α` that a grid in `μ` cannot follow; at fixed `x = μ (1 + α)/(μ + α)`,
/// `μ/α = x / (1 + α − x)` tends to `x/(1 − x)`, so `E` has a limit as `α → 0` and the grid
/// resolves the dip at every roughness. And at grazing, `E → 1` (`Λ(wo) → ∞` makes
/// `G2/G1(wo) → 1`, and every visible facet reflects a horizontal `wo` upwards) with
/// `1 − E ∝ μ (c − ln μ)`, an infinite slope at `μ = 0` (a bilinear table on `x` was 1.8e-3
/// off at `α = 0.78`, `μ = 0.0035`); the square root makes it `∝ s² (c − 2 ln s)`, whose
/// slope vanishes there. `s` maps `μ = 0 → 0` and `μ = 1 → 1`; inverse
/// `μ = s² α / (1 + α − s²)`.
///
/// Domain `μ ∈ [0, 1]`, `α ∈ [1e-4, 1]`.
#[inline(always)]
#[must_use]
pub fn albedo_table_s<R: Real>(cos_theta_o: R, alpha: R) -> R {
    (cos_theta_o * (R::one() + alpha) / (cos_theta_o + alpha)).sqrt()
}

/// The roughness coordinate of the albedo tables, `t = (√α − 0.01) / 0.99` ∈ `[0, 1]`: the
/// perceptual roughness `√α` rescaled so that `α = 1e-4 → 0` and `α = 1 → 1`.
///
/// Domain `α ∈ [1e-4, 1]`.
#[inline(always)]
#[must_use]
pub fn albedo_table_t<R: Real>(alpha: R) -> R {
    (alpha.sqrt() - R::from_f64(0.01)) / R::from_f64(0.99)
}

/// `α` at roughness node `j` of the tables: the inverse of [`albedo_table_t`] at
/// `t = j / (ALBEDO_TABLE_ALPHA − 1)`, `α = (0.01 + 0.99 t)²`, clamped to `[1e-4, 1]`.
fn table_alpha(j: usize) -> f64 {
    let t = j as f64 / (ALBEDO_TABLE_ALPHA - 1) as f64;
    let r = 0.01 + 0.99 * t;
    (r * r).clamp(ALPHA_MIN, 1.0)
}

/// `μ` at view node `i` for roughness `α`: the inverse of [`albedo_table_s`] at
/// `s = i / (ALBEDO_TABLE_MU − 1)`, `μ = s² α / (1 + α − s²)`, clamped to `[0, 1]`.
fn table_mu(i: usize, alpha: f64) -> f64 {
    let s = i as f64 / (ALBEDO_TABLE_MU - 1) as f64;
    let x = s * s;
    (x * alpha / (1.0 + alpha - x)).clamp(0.0, 1.0)
}

/// Node `(i, j)` of the shipped `E(μ, α)` table, computed now: [`directional_albedo`] at
/// `α` of roughness node `j` and `μ` of view node `i` (see [`albedo_table_s`],
/// [`albedo_table_t`]), rounded to `f32`. The shipped value is this number, bit for bit
/// (`tests/energy_tables.rs` regenerates the tables and fails on any difference; the program
/// `cargo run --release -p brdf-tools --bin energy_tables` writes `src/energy/tables.rs`).
///
/// Domain `i < ALBEDO_TABLE_MU`, `j < ALBEDO_TABLE_ALPHA` (panics outside).
#[must_use]
pub fn albedo_table_node(distribution: Distribution, i: usize, j: usize) -> f32 {
    assert!(
        i < ALBEDO_TABLE_MU && j < ALBEDO_TABLE_ALPHA,
        "node ({i}, {j})"
    );
    let alpha = table_alpha(j);
    let e = directional_albedo(distribution, alpha, table_mu(i, alpha));
    e.unwrap_or(f64::NAN) as f32
}

/// Node `j` of the shipped `E_avg(α)` table, computed now: [`average_albedo`] at `α` of
/// roughness node `j`, rounded to `f32` (regenerated bit for bit by the same test and program
/// as [`albedo_table_node`]).
///
/// Domain `j < ALBEDO_TABLE_ALPHA` (panics outside).
#[must_use]
pub fn average_albedo_table_node(distribution: Distribution, j: usize) -> f32 {
    assert!(j < ALBEDO_TABLE_ALPHA, "node {j}");
    average_albedo(distribution, table_alpha(j)).unwrap_or(f64::NAN) as f32
}

/// The shipped tables of one distribution: `E` row-major (`ALBEDO_TABLE_ALPHA` rows of
/// `ALBEDO_TABLE_MU`), and `E_avg` (`ALBEDO_TABLE_ALPHA` values), in `f32`.
#[must_use]
pub fn albedo_tables(distribution: Distribution) -> (&'static [f32], &'static [f32]) {
    match distribution {
        Distribution::Ggx => (tables::GGX_E, tables::GGX_E_AVG),
        Distribution::Beckmann => (tables::BECKMANN_E, tables::BECKMANN_E_AVG),
    }
}

/// `table[k]` for each lane's index `k` (a gather; one load per lane), for the `f32` tables
/// and the `u16` residuals of the dielectric table alike.
#[inline(always)]
fn gather<T: Copy + Into<f64>, R: Real>(table: &[T], k: R) -> R {
    R::from_fn(|l| {
        let k: f64 = k.lane(l).into();
        <R::Scalar as crate::Scalar>::of(table[k as usize].into())
    })
}

/// Directional albedo `E(μo, α)` of [`directional_albedo`] (isotropic, `F = 1`,
/// height-correlated Smith) looked up in the shipped table: bilinear interpolation on the
/// axes `s` = [`albedo_table_s`] and `t` = [`albedo_table_t`] over
/// [`ALBEDO_TABLE_MU`] × [`ALBEDO_TABLE_ALPHA`] nodes.
///
/// ```text
/// E(μ, α) ≈ (1 − u)(1 − v) E[j][i] + u (1 − v) E[j][i+1] + (1 − u) v E[j+1][i] + u v E[j+1][i+1]
/// s (N_μ − 1) = i + u,   t (N_α − 1) = j + v
/// ```
///
/// Branch-free on every lane type (one gather of four nodes per lane). Domain `α ∈ [1e-4,
/// 1]`, `μ ∈ [0, 1]`; inputs outside are clamped to them (NaN to the lower bound), so the
/// result is always in `[0, 1]`. Accuracy: within 1e-3 of [`directional_albedo`] over the
/// whole domain (measured worst and where it peaks: `tests/energy_tables.rs` and the guide).
///
/// References: as [`directional_albedo`]; the tables serve Kulla & Conty 2017 and
/// Turquin 2019.
///
/// ```
/// use brdf::energy::{directional_albedo, directional_albedo_table, Distribution};
/// let e = directional_albedo_table(Distribution::Ggx, 0.5_f32, 0.3);
/// assert!((f64::from(e) - directional_albedo(Distribution::Ggx, 0.5, 0.3)?).abs() < 1e-3);
/// # Ok::<(), brdf::Error>(())
/// ```
#[inline(always)]
#[must_use]
pub fn directional_albedo_table<R: Real>(
    distribution: Distribution,
    alpha: R,
    cos_theta_o: R,
) -> R {
    let (e, _) = albedo_tables(distribution);
    let alpha = alpha.clamp(R::from_f64(ALPHA_MIN), R::one());
    let mu = cos_theta_o.saturate();
    let s = albedo_table_s(mu, alpha).saturate();
    let t = albedo_table_t(alpha).saturate();
    let (nx, ny) = (ALBEDO_TABLE_MU, ALBEDO_TABLE_ALPHA);
    let fx = s * R::from_f64((nx - 1) as f64);
    let fy = t * R::from_f64((ny - 1) as f64);
    let ix = fx.floor().min(R::from_f64((nx - 2) as f64));
    let iy = fy.floor().min(R::from_f64((ny - 2) as f64));
    let (u, v) = (fx - ix, fy - iy);
    let k = iy * R::from_f64(nx as f64) + ix;
    let e00 = gather(e, k);
    let e01 = gather(e, k + R::one());
    let e10 = gather(e, k + R::from_f64(nx as f64));
    let e11 = gather(e, k + R::from_f64((nx + 1) as f64));
    let e0 = e00 + u * (e01 - e00);
    let e1 = e10 + u * (e11 - e10);
    e0 + v * (e1 - e0)
}

/// Hemispherical average `E_avg(α)` of [`average_albedo`] looked up in the shipped table:
/// linear interpolation in `t` = [`albedo_table_t`] over [`ALBEDO_TABLE_ALPHA`] nodes.
///
/// Branch-free on every lane type. Domain `α ∈ [1e-4, 1]` (clamped, NaN to `1e-4`); result in
/// `[0, 1]`. Accuracy: within 1e-3 of [`average_albedo`] (`tests/energy_tables.rs`).
/// Reference: Kulla & Conty 2017 (`E_avg`).
#[inline(always)]
#[must_use]
pub fn average_albedo_table<R: Real>(distribution: Distribution, alpha: R) -> R {
    let (_, avg) = albedo_tables(distribution);
    let alpha = alpha.clamp(R::from_f64(ALPHA_MIN), R::one());
    let fy = albedo_table_t(alpha).saturate() * R::from_f64((ALBEDO_TABLE_ALPHA - 1) as f64);
    let iy = fy.floor().min(R::from_f64((ALBEDO_TABLE_ALPHA - 2) as f64));
    let v = fy - iy;
    let a0 = gather(avg, iy);
    let a1 = gather(avg, iy + R::one());
    a0 + v * (a1 - a0)
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

// ---------------------------------------------------------------------------------------
// Rough dielectric interface (Walter et al. 2007): reflection + transmission
// ---------------------------------------------------------------------------------------

/// Domain of the relative IOR of the dielectric albedo functions: `eta ∈ [1/4, 4]`.
pub const DIELECTRIC_ETA_RANGE: (f64, f64) = (0.25, 4.0);

/// Directional albedo `E(μo, α, η) = R + T` of the single-scattering rough dielectric BSDF
/// of Walter et al. 2007 (isotropic GGX, height-correlated Smith, exact dielectric Fresnel):
/// the sum of [`dielectric_albedo_split`]'s two parts. See there for the definitions, the
/// conventions (`eta`, the energy form of `f_t`) and the method.
///
/// Domain: `alpha ∈ [1e-4, 1]`, `eta ∈ [1/4, 4]`, `cos_theta_o ∈ [0, 1]` (clamped to
/// `[1e-6, 1]`). Result in `[0, 1]`; `→ 1` as `α → 0` (smooth interface: `R + T = 1`).
/// It falls with `α` for `cos_theta_o ≥ 0.15` (measured for `η ∈ [1/3, 3]`, tested at
/// `η = 1.33, 1.5, 2.4` and their inverses). At grazing view it is not monotone: it dips
/// near `α ≈ cos_theta_o`, then recovers (the masking of a near-mirror lobe, as for the
/// conductor; e.g. `E(0.1) = 0.9224 < E(0.2) = 0.9285` at `μo = 0.1`, `η = 2.4`; tested in
/// `tests/energy_dielectric.rs`).
///
/// Reference: B. Walter, S. Marschner, H. Li, K. Torrance, "Microfacet Models for Refraction
/// through Rough Surfaces", EGSR 2007.
///
/// ```
/// use brdf::energy::dielectric_albedo;
/// // Glass seen from outside, nearly smooth: almost no energy is lost.
/// assert!((dielectric_albedo(1e-3, 1.5, 0.7)? - 1.0).abs() < 1e-3);
/// // Rough glass: single scattering loses energy.
/// assert!(dielectric_albedo(1.0, 1.5, 0.7)? < 0.95);
/// # Ok::<(), brdf::Error>(())
/// ```
///
/// # Errors
/// As [`dielectric_albedo_split`].
pub fn dielectric_albedo(alpha: f64, eta: f64, cos_theta_o: f64) -> Result<f64, Error> {
    let [r, t] = dielectric_albedo_split(alpha, eta, cos_theta_o)?;
    Ok(r + t)
}

/// The reflected and transmitted parts `[R(μo), T(μo)]` of the directional albedo of the
/// single-scattering rough dielectric BSDF of Walter et al. 2007, isotropic GGX with the
/// height-correlated Smith term `G2 = 1/(1 + Λ(wo) + Λ(wi))` (the masking of the crate's
/// `CookTorrance` default, used for both lobes as in pbrt-v4; Heitz 2014 §6 gives a
/// Beta-function form for the exact height-correlated transmission, not used here).
///
/// **Conventions.** Local frame `z` = the normal on the viewer's side, `wo.z = μo > 0`;
/// `eta = η_beyond / η_viewer` is the relative IOR of the medium below the interface over
/// the medium `wo` is in: `eta > 1` sees glass **from outside**, `eta < 1` (its reciprocal)
/// the same glass **from inside** (total internal reflection possible).
///
/// ```text
/// R(μo) = ∫_{wi.z>0} f_r(wi, wo) cos θi dωi,   f_r = D F(wo·wm) G2 / (4 cos θi cos θo),  wm ∝ wi + wo
/// T(μo) = ∫_{wi.z<0} f_t(wi, wo) |cos θi| dωi, wm = −(η wi + wo)/|η wi + wo|   (wm.z > 0)
/// f_t   = |wi·wm| |wo·wm| / (|cos θi| cos θo) · η² (1 − F(wo·wm)) D G2 / (wo·wm + η wi·wm)²
/// ```
///
/// with `wo·wm > 0 > wi·wm` (else `f_t = 0`) and `F = fresnel::dielectric(wo·wm, η)`.
///
/// **Energy form, loudly.** This `f_t` is the *importance* (energy) form: it carries `η²`
/// where Walter's radiance BSDF carries `1` (relative to the same denominator), i.e. it
/// omits the radiance factor `1/η²`: `f_t,radiance = f_t / η²`. So the smooth limit is
/// `R + T = 1` (`T → 1 − F(μo)`), and the radiance-form albedo is `R + T/η²`.
///
/// **Derivation of the Jacobian.** Refraction through `wm` maps `dωi` to
/// `dωm = η² |wi·wm| / (wo·wm + η wi·wm)² dωi` (Walter et al. 2007, eq. 17, with `wo` the
/// incident side), so `f_t |cos θi| dωi = (1 − F) G2 D (wo·wm)/cos θo dωm`; likewise
/// `dωi = 4 (wo·wm) dωm` for reflection. Both parts are then integrals over the visible
/// normals:
///
/// ```text
/// R = ∫ D (wo·wm)⁺/μo · F G2(wo, wr) [wr.z > 0] dωm,        wr = 2 (wo·wm) wm − wo
/// T = ∫ D (wo·wm)⁺/μo · (1 − F) G2(wo, wt) [wt.z < 0] dωm,   wt = −wo/η + ((wo·wm)/η − cos θt) wm
/// ```
///
/// (`cos θt = √(1 − (1 − (wo·wm)²)/η²)`, `1 − F = 0` under total internal reflection.)
///
/// **Method.** `R` is [`directional_albedo`]'s horizon-cut rule with the weight `F(wo·wm)`.
/// `T` uses the same variables (`w = √(1 − v)`, `v` the GGX CDF in `tan²θm`; the graded
/// `φm` mesh), `w` running from the horizon of `wo` (`wo·wm = 0`) to the normal; for
/// `eta < 1` the support of the `T` integrand (not TIR and `wt.z < 0`) is located along each
/// `φm` line by a scan of 64 cells and bisection, and each piece gets [`PANELS`] ×
/// [`ORDER`] Gauss-Legendre nodes. For `eta ≥ 1` the integrand is supported on the whole
/// line. Deterministic. Accuracy (against a dense, independent quadrature over `wi` and a
/// Monte-Carlo estimate with the crate's visible-normal sampler): `tests/energy_dielectric.rs`.
///
/// Reference: Walter et al., EGSR 2007; E. Heitz, "Understanding the Masking-Shadowing
/// Function in Microfacet-Based BRDFs", JCGT 3(2), 2014.
///
/// # Errors
/// [`Error::NotFinite`] or [`Error::OutOfDomain`] for `alpha` outside `[1e-4, 1]`, `eta`
/// outside `[1/4, 4]` or `cos_theta_o` outside `[0, 1]`.
pub fn dielectric_albedo_split(alpha: f64, eta: f64, cos_theta_o: f64) -> Result<[f64; 2], Error> {
    let (lo, hi) = DIELECTRIC_ETA_RANGE;
    crate::error::check("eta", eta, "[1/4, 4]", |e| (lo..=hi).contains(&e))?;
    let [r] = lobe_moments(Distribution::Ggx, alpha, cos_theta_o, |d| {
        [crate::fresnel::dielectric(d, eta)]
    })?;
    let ndf = Ggx::new(alpha)?;
    let r = if eta < 1.0 {
        interface_part(&ndf, alpha, eta, cos_theta_o, Lobe::Reflection)
    } else {
        r
    };
    Ok([
        r,
        interface_part(&ndf, alpha, eta, cos_theta_o, Lobe::Transmission),
    ])
}

/// The refracted direction of `wo` through `wm` (`c = wo·wm > 0`) for relative IOR `eta`
/// (beyond over viewer), `None` under total internal reflection.
fn refract_through(wo: Vec3<f64>, wm: Vec3<f64>, c: f64, eta: f64) -> Option<Vec3<f64>> {
    let sin2_t = (1.0 - c * c) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = Real::sqrt(1.0 - sin2_t);
    let k = c / eta - cos_t;
    Some(Vec3::new(
        -wo.x / eta + k * wm.x,
        -wo.y / eta + k * wm.y,
        -wo.z / eta + k * wm.z,
    ))
}

/// Which lobe [`interface_part`] integrates.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Lobe {
    Reflection,
    Transmission,
}

/// `R(μo)` or `T(μo)` of [`dielectric_albedo_split`] by the scan rule (validated inputs).
///
/// Along each `φm` line, `w` ∈ `[0, 1]` is cut where the integrand's region changes (zero /
/// beyond / below the critical angle, i.e. the horizons and the total-internal-reflection
/// kink of `F`), found by a scan of 64 cells and 60 bisections; each piece gets
/// [`integrate_01_graded`] (geometric panels towards its lower, horizon-side end).
fn interface_part(ndf: &Ggx<f64>, alpha: f64, eta: f64, cos_theta_o: f64, lobe: Lobe) -> f64 {
    let mu = cos_theta_o.clamp(1e-6, 1.0);
    let s = Real::sqrt(1.0 - mu * mu);
    let wo = Vec3::new(s, 0.0, mu);
    let lo = ndf.lambda(wo);
    let nodes = gauss_legendre::<ORDER>();
    let a2 = alpha * alpha;
    // cos² of the critical angle on the facet (no TIR for eta ≥ 1).
    let crit2 = if eta < 1.0 { 1.0 - eta * eta } else { -1.0 };
    let inner = |phi: f64| {
        let (sp, cp) = (Real::sin(phi), Real::cos(phi));
        // The integrand at w (w = α/√(α² + tan²θm)) and its region label (0: zero).
        let eval = |w: f64| -> (f64, u8) {
            let t2 = a2 * (1.0 - w * w) / (w * w);
            let c = 1.0 / Real::sqrt(1.0 + t2);
            let st = Real::sqrt(t2) * c;
            let wm = Vec3::new(st * cp, st * sp, c);
            let d = wo.dot(wm);
            if d.is_nan() || d <= 0.0 {
                return (0.0, 0);
            }
            let label = if d * d > crit2 { 1 } else { 2 };
            let f = crate::fresnel::dielectric(d, eta);
            match lobe {
                Lobe::Reflection => {
                    let wr = wo.reflect(wm);
                    if wr.z > 0.0 {
                        let li = ndf.lambda(wr);
                        (2.0 * w * d * f / (mu * c * (1.0 + lo + li)), label)
                    } else {
                        (0.0, 0)
                    }
                }
                Lobe::Transmission => match refract_through(wo, wm, d, eta) {
                    Some(wt) if wt.z < 0.0 => {
                        let li = ndf.lambda(Vec3::new(wt.x, wt.y, -wt.z));
                        (2.0 * w * d * (1.0 - f) / (mu * c * (1.0 + lo + li)), label)
                    }
                    _ => (0.0, 0),
                },
            }
        };
        let piece = |a: f64, b: f64| {
            let len = b - a;
            let layer = (a / len).clamp(1e-9, 1.0);
            let [v] = integrate_01_graded(&nodes, layer, |x| [eval(a + len * x).0]);
            len * v
        };
        const CELLS: usize = 64;
        let label = |x: f64| eval(x.max(1e-12)).1;
        let mut total = 0.0;
        let mut start = 0.0;
        let mut prev = label(0.0);
        for cell in 1..=CELLS {
            let x1 = cell as f64 / CELLS as f64;
            let now = label(x1);
            if now != prev {
                let (mut a, mut b) = ((cell - 1) as f64 / CELLS as f64, x1);
                for _ in 0..60 {
                    let m = 0.5 * (a + b);
                    if label(m) == prev {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                let edge = 0.5 * (a + b);
                if prev != 0 {
                    total += piece(start, edge);
                }
                start = edge;
                prev = now;
            }
        }
        if prev != 0 {
            total += piece(start, 1.0);
        }
        total
    };
    let [average] = graded_phi_average(mu, &nodes, |phi| [inner(phi)]);
    average
}

/// Hemispherical averages `[R_avg, T_avg]`, `X_avg = 2 ∫_0^1 X(μ) μ dμ`, of the two parts of
/// [`dielectric_albedo_split`], by [`PANELS`] × [`ORDER`] Gauss-Legendre nodes in `μ`.
///
/// Reciprocity (derived from Walter et al. 2007's `f_t(wi, wo)/η_o² = f_t(wo, wi)/η_i²` for
/// the radiance form): the energy form of [`dielectric_albedo_split`] obeys
/// `f_t(wi, wo; η) = η² f_t(wo, wi; 1/η)`, hence `T_avg(1/η) = T_avg(η) / η²` (the rough
/// generalisation of `1 − F_avg(1/η) = (1 − F_avg(η))/η²`).
///
/// Domain and errors as [`dielectric_albedo_split`] for `alpha` and `eta`.
/// Reference: Walter et al., EGSR 2007; Kulla & Conty 2017 (`E_avg`).
///
/// # Errors
/// As [`dielectric_albedo_split`].
pub fn dielectric_average_albedo_split(alpha: f64, eta: f64) -> Result<[f64; 2], Error> {
    dielectric_albedo_split(alpha, eta, 1.0)?;
    let nodes = gauss_legendre::<ORDER>();
    let [r, t] = integrate_01_k(&nodes, |mu| {
        dielectric_albedo_split(alpha, eta, mu)
            .unwrap_or([0.0; 2])
            .map(|x| x * mu)
    });
    Ok([2.0 * r, 2.0 * t])
}

/// Hemispherical average `E_avg(α, η) = R_avg + T_avg` of [`dielectric_albedo`] (see
/// [`dielectric_average_albedo_split`]). Result in `[0, 1]`.
///
/// Reference: Walter et al., EGSR 2007; Kulla & Conty 2017 (`E_avg`).
///
/// # Errors
/// As [`dielectric_albedo_split`].
pub fn dielectric_average_albedo(alpha: f64, eta: f64) -> Result<f64, Error> {
    let [r, t] = dielectric_average_albedo_split(alpha, eta)?;
    Ok(r + t)
}

// ---------------------------------------------------------------------------------------
// Shipped tables of the dielectric E(μ, α, η) and E_avg(α, η)
// ---------------------------------------------------------------------------------------

pub mod dielectric_table;
mod dielectric_tables;

/// Largest IOR of the dielectric tables: outside `η ∈ [1, 3]`, inside `η ∈ [1/3, 1]`.
pub const DIELECTRIC_TABLE_ETA_MAX: f64 = 3.0;
/// Roughness nodes of the shipped `E_avg(α, η)` table (axis [`albedo_table_t`]).
pub const DIELECTRIC_AVERAGE_TABLE_ALPHA: usize = 32;
/// IOR nodes of the shipped `E_avg(α, η)` table ([`dielectric_average_table_u`]), per side
/// (stored with one ghost node at each end).
pub const DIELECTRIC_AVERAGE_TABLE_ETA: usize = 24;
/// The IOR coordinate of the `E_avg` table, `u = (q/q_max + F(c)/F(c_max))/2` ∈ `[0, 1]`:
///
/// ```text
/// q = √(η'² − 1),  c = q/√(1 + q²) = √(1 − 1/η'²),  η' = max(η, 1/η),  q_max = √8
/// F(c) = 1 − 1/√(1 + c/α)
/// ```
///
/// the same `u` for an interface seen from outside (`η`) and from inside (`1/η`). `E_avg`
/// changes on the scale `c ~ α` (the averaged grazing layer and total-internal-reflection
/// transition, whose tail goes as `1/c`: `F` spaces nodes evenly over it) and, linearly in
/// `η'`, up to `η' = 3` (`q`). Measured on a fine rule at `α = 0.03…1` with 24 nodes:
/// within 6.5e-5 in `u` (1.9e-3 with `√(c₀² + q²)`, `c₀ = 1/4`; the former axis, linear in
/// `η'` with 16 nodes and bilinear, was 1.5e-2 off at `α = 0.5`, `η = 1/1.067`).
/// Domain `α ∈ [1e-4, 1]`, `η ∈ [1/3, 3]`.
#[inline(always)]
#[must_use]
pub fn dielectric_average_table_u<R: Real>(alpha: R, eta: R) -> R {
    let one = R::one();
    let c2 = dielectric_table::cos2_critical(eta).min(R::from_f64(8.0 / 9.0));
    let q = (c2 / (one - c2)).sqrt();
    let f = |c: R| one - one / (one + c / alpha).sqrt();
    let c_max = R::from_f64((8.0_f64 / 9.0).sqrt());
    let r = f(c2.sqrt()) / f(c_max);
    R::from_f64(0.5) * (q / R::from_f64(8.0_f64.sqrt()) + r)
}

/// `(α, η)` of roughness node `j`, interior IOR node `k`, side `inside` of the `E_avg` table.
fn dielectric_average_alpha_eta(j: usize, k: usize, inside: bool) -> (f64, f64) {
    let t = j as f64 / (DIELECTRIC_AVERAGE_TABLE_ALPHA - 1) as f64;
    let r = 0.01 + 0.99 * t;
    let alpha = (r * r).clamp(ALPHA_MIN, 1.0);
    let u = k as f64 / (DIELECTRIC_AVERAGE_TABLE_ETA - 1) as f64;
    let eta_of_q = |q: f64| (1.0 + q * q).sqrt().min(DIELECTRIC_TABLE_ETA_MAX);
    let q = if k == 0 {
        0.0
    } else if k + 1 == DIELECTRIC_AVERAGE_TABLE_ETA {
        8.0_f64.sqrt()
    } else {
        let (mut lo, mut hi) = (0.0, 8.0_f64.sqrt());
        for _ in 0..100 {
            let m = 0.5 * (lo + hi);
            if dielectric_average_table_u(alpha, eta_of_q(m)) < u {
                lo = m;
            } else {
                hi = m;
            }
        }
        0.5 * (lo + hi)
    };
    let eta = eta_of_q(q);
    (alpha, if inside { 1.0 / eta } else { eta })
}

/// Stored node `(s, p, r)` of `region` of the shipped dielectric `E(μ, α, η)` table, computed
/// now: the residual [`dielectric_table::stored_residual`] (`E` of [`dielectric_albedo`] at
/// [`dielectric_table::node_point`] minus [`dielectric_table::corner`]; a ghost node is the
/// quadratic extrapolation of three interior ones) quantized by
/// [`dielectric_table::quantize`]. The shipped value is this number bit for bit
/// (`tests/energy_dielectric.rs`; the program `cargo run --release -p brdf-tools --bin
/// energy_tables -- --dielectric` writes `src/energy/dielectric_tables.rs`).
///
/// Domain (padded indices: `x − 1` is the interior node, `0` and the last the ghosts):
/// roughness `s < dielectric_table::ALPHA_NODES + 2`, `p < n + 2`, `r < m + 2` with `(n, m)` =
/// [`dielectric_table::Region::nodes`] (panics outside).
#[must_use]
pub fn dielectric_albedo_table_node(
    region: dielectric_table::Region,
    s: usize,
    p: usize,
    r: usize,
) -> u16 {
    let (n, m) = region.stored();
    assert!(
        s < dielectric_table::ALPHA_NODES + 2 && p < n && r < m,
        "node ({s}, {p}, {r}) of {region:?}"
    );
    dielectric_table::quantize(dielectric_table::stored_residual(region, s, p, r))
}

/// Stored node `(j, r)` of the shipped dielectric `E_avg(α, η)` table of one side, computed
/// now: [`dielectric_average_albedo`] at `α = (0.01 + 0.99 t_j)²` (`t_j = j/31`, the axis
/// [`albedo_table_t`]) and the IOR of interior node `k = r − 1` (`u_k = k/23` of
/// [`dielectric_average_table_u`] at that `α`, inverted by bisection; `η = η'` outside,
/// `1/η'` inside), rounded to `f32`; `r = 0`
/// and `r = 25` are ghosts, `3 E₀ − 3 E₁ + E₂` of the nearest interior nodes (regenerated bit
/// for bit by the same test and program as [`dielectric_albedo_table_node`]).
///
/// Domain `j < DIELECTRIC_AVERAGE_TABLE_ALPHA`, `r < DIELECTRIC_AVERAGE_TABLE_ETA + 2`
/// (panics outside).
#[must_use]
pub fn dielectric_average_albedo_table_node(inside: bool, j: usize, r: usize) -> f32 {
    let n = DIELECTRIC_AVERAGE_TABLE_ETA;
    assert!(
        j < DIELECTRIC_AVERAGE_TABLE_ALPHA && r < n + 2,
        "node ({j}, {r})"
    );
    let node = |k: usize| {
        let (alpha, eta) = dielectric_average_alpha_eta(j, k, inside);
        dielectric_average_albedo(alpha, eta).unwrap_or(f64::NAN)
    };
    let v = if r == 0 {
        3.0 * node(0) - 3.0 * node(1) + node(2)
    } else if r == n + 1 {
        3.0 * node(n - 1) - 3.0 * node(n - 2) + node(n - 3)
    } else {
        node(r - 1)
    };
    v as f32
}

/// The shipped dielectric tables: `E` as quantized residuals (the regions of
/// [`dielectric_table::Region::ALL`] one after the other; per region `dielectric_table::ALPHA_NODES + 2`
/// planes of `n + 2` rows of `m + 2`, [`dielectric_table::Region::block`]) and `E_avg` in `f32` (outside
/// then inside; per side `DIELECTRIC_AVERAGE_TABLE_ALPHA` rows of
/// `DIELECTRIC_AVERAGE_TABLE_ETA + 2`).
#[must_use]
pub fn dielectric_albedo_tables() -> (&'static [u16], &'static [f32]) {
    (
        dielectric_tables::DIELECTRIC_E,
        dielectric_tables::DIELECTRIC_E_AVG,
    )
}

/// Directional albedo `E(μo, α, η)` of [`dielectric_albedo`] (GGX, height-correlated Smith,
/// energy form of `f_t`; `E = R + T`) looked up in the shipped table. Branch-free on every
/// lane type; one body for scalars and lanes.
///
/// ```text
/// E ≈ C(μ, α, η) + Σ_{s,a,b ∈ −1..2} cr_s(z) cr_a(x) cr_b(y) T[region][j + s][i + a][k + b]
/// ```
///
/// **What is stored.** The residual `T = E − C` of the closed-form index-matched corner
/// `C = W Φ(ρ)` ([`dielectric_table::corner`], [`dielectric_table::corner_albedo`]), `ρ = c²/(2αμ')`.
/// At grazing view (`μ ≪ α`) and `η → 1`, `E` depends on `ρ` alone: from the index-matched
/// `1/2` (`ρ → 0`: the refracted ray is as grazing as `wo`, `G2/G1 = 1/2`) to `1` outside and
/// `0` inside (`ρ → ∞`: refraction lifts the exit above the view, or bends it back above the
/// horizon). That transition is singular at `(μ, η) = (0, 1)` — no grid on `μ` and `η`
/// follows it (the former table, linear in `η'` with 16 nodes, was 0.25 off at `η = 1.067`,
/// `μ = 2.8e-5`) — and its tail `1 − Φ₊ ≈ ln ρ/ρ` is long; `C` carries it exactly, and `T`
/// is `O(μ/α) + O(c²/α²)` there.
///
/// **Regions and axes.** [`dielectric_table::Region`]: outside; inside with `sin θo ≥ c` (split at
/// `μ = 1/3`, where the IOR range `[0, min(sin θo, c_max)]` turns); inside with `sin θo < c`
/// (`c` the cosine of the critical angle), split on the kink of the inside albedo at
/// `sin θo = c` so that no cell straddles it. Each region is a grid of its own:
/// view [`dielectric_table::view_axis`] × IOR [`dielectric_table::ior_axis`] (the IOR axis follows the
/// Fresnel / total-internal-reflection transition of facets at cosine `~ μ + α/2`, the edge
/// `c = μ`, the corner and the kink), or for the near-normal inside region
/// [`dielectric_table::normal_axes`]; roughness [`dielectric_table::roughness_axis`] (graded towards `α = 1e-4`
/// for the quadrature's clamp `μ ≥ 1e-6`). Nodes: 28 roughnesses × `(40, 24)`, `(36, 32)`,
/// `(36, 48)`, `(32, 24)`, plus a ghost plane, row and column at each end of every axis.
///
/// **Interpolation.** Catmull-Rom on all three axes (weights `cr`, 4 × 4 × 4 nodes: 64
/// gathers, one [`fast::log2`](crate::fast::log2) and about twenty square roots); the ghosts
/// are quadratic extrapolations, so quadratics are reproduced up to the boundaries. Measured
/// while designing: linear interpolation in roughness on 40 nodes was up to 8e-4 off at
/// near-normal views (`α ≈ 0.2–0.3`), Catmull-Rom on the same nodes within 4.4e-5; bilinear
/// interpolation in the two in-region axes needed about 2.5 times the nodes per axis of
/// Catmull-Rom for the same error.
///
/// **Storage.** `u16` residuals on `[−1, 2]`: a step of 4.6e-5, so at most 4.5e-5 after
/// the 64 weights (`Σ|cr| ≤ 1.25` per axis); 155 040 values, 303 KiB (the former `f32` table
/// was 128 KiB).
///
/// Domain `α ∈ [1e-4, 1]`, `η ∈ [1/3, 3]`, `μ ∈ [0, 1]`; inputs outside are clamped to them;
/// result in `[0, 1]`. Accuracy against [`dielectric_albedo`] (`tests/energy_dielectric.rs`;
/// measured on an Intel Xeon, the same on any CPU): one pseudo-random point in every cell
/// (117 180 points, `#[ignore]`d sweep) within 8.8e-4, per region 1.8e-4 outside, 8.8e-4
/// inside grazing (at `α = 2.8e-4`, `η = 1 − 7.6e-8`, `μ = 7.7e-4`), 7.0e-4 inside oblique,
/// 8.1e-4 inside near normal; the largest difference found by line searches across the
/// worst cells is 9.5e-4 (inside, `c = 2e-4`, `α = 1.9e-4`, `μ = 3.8e-4`, where the
/// transmitted ray turns grazing). Near `η = 1` at grazing views: within 3.1e-4.
///
/// Cost (`cargo bench --bench energy`, Intel Xeon, Sapphire Rapids class): 4.5 M lookups/s
/// on `f32`, 7.1 M points/s on `f32x8` (the gathers are per lane) — about 1/8 of the
/// bilinear conductor table's 37 / 88 M/s, and 18 000 times faster than one quadrature
/// (3.9 ms). Fine for per-material or per-pixel set-up; a per-sample hot path that needs
/// only `η > 1` at moderate roughness can precompute its own smaller table with
/// [`dielectric_albedo`].
///
/// References: Walter et al. 2007; E. Catmull, R. Rom, "A class of local interpolating
/// splines", 1974; the table serves Kulla & Conty 2017's dielectric compensation and
/// Turquin 2019's energy scaling for glass.
///
/// ```
/// use brdf::energy::{dielectric_albedo, dielectric_albedo_table};
/// for (alpha, eta, mu) in [(0.5, 1.5, 0.3), (0.12, 1.067, 2.8e-5), (0.3, 1.0 / 1.33, 0.9)] {
///     let e = dielectric_albedo_table(alpha as f32, eta as f32, mu as f32);
///     assert!((f64::from(e) - dielectric_albedo(alpha, eta, mu)?).abs() < 1e-3);
/// }
/// # Ok::<(), brdf::Error>(())
/// ```
#[inline(always)]
#[must_use]
pub fn dielectric_albedo_table<R: Real>(alpha: R, eta: R, cos_theta_o: R) -> R {
    dielectric_table::lookup(alpha, eta, cos_theta_o)
}

/// Hemispherical average `E_avg(α, η)` of [`dielectric_average_albedo`] looked up in the
/// shipped table: linear in `t` = [`albedo_table_t`] (32 nodes), Catmull-Rom in `u` =
/// [`dielectric_average_table_u`] (24 nodes and a ghost at each end), the side chosen per
/// lane without a branch (8 gathers).
///
/// ```text
/// E_avg ≈ Σ_{j'∈{j,j+1}} w_{j'}(t) Σ_{b ∈ −1..2} cr_b(y) E_avg[side][j'][k + b]
/// ```
///
/// Domain `α ∈ [1e-4, 1]`, `η ∈ [1/3, 3]` (clamped). Accuracy against
/// [`dielectric_average_albedo`]: `tests/energy_dielectric.rs`.
/// Reference: Kulla & Conty 2017 (`E_avg`); Walter et al. 2007.
#[inline(always)]
#[must_use]
pub fn dielectric_average_albedo_table<R: Real>(alpha: R, eta: R) -> R {
    let (_, avg) = dielectric_albedo_tables();
    let (ny, nz) = (DIELECTRIC_AVERAGE_TABLE_ALPHA, DIELECTRIC_AVERAGE_TABLE_ETA);
    let row = R::from_f64((nz + 2) as f64);
    let alpha = alpha.clamp(R::from_f64(ALPHA_MIN), R::one());
    let eta = eta.clamp(
        R::from_f64(1.0 / DIELECTRIC_TABLE_ETA_MAX),
        R::from_f64(DIELECTRIC_TABLE_ETA_MAX),
    );
    let side = R::select(
        eta.lt(R::one()),
        R::from_f64((ny * (nz + 2)) as f64),
        R::zero(),
    );
    let (iy, v) = dielectric_table::cell(albedo_table_t(alpha), ny);
    let (iz, w) = dielectric_table::cell(dielectric_average_table_u(alpha, eta), nz);
    let weights = dielectric_table::catmull_rom(w);
    let k = side + iy * row + iz;
    // One loop over both rows, not a closure (see `erf_inv_giles` in `sampling::microfacet`);
    // the indices are small integers, so `(k + b) + row` is exact.
    let (mut e0, mut e1) = (R::zero(), R::zero());
    for (b, &wb) in weights.iter().enumerate() {
        let kb = k + R::from_f64(b as f64);
        e0 += wb * gather(avg, kb);
        e1 += wb * gather(avg, kb + row);
    }
    e0 + v * (e1 - e0)
}
