//! Multiple-scattering compensation of microfacet reflection: the energy a single-scattering
//! Cook-Torrance lobe loses to inter-reflections between microfacets, given back by a
//! wrapper model.
//!
//! * [`KullaConty`] (Kulla & Conty 2017): adds the reciprocal lobe
//!   `F_ms (1 − E(μi))(1 − E(μo)) / (π (1 − E_avg))`, coloured by the average Fresnel.
//! * [`Turquin`] (Turquin 2019): scales the lobe by `1 + F0 (1 − E(μo))/E(μo)`; cheaper,
//!   not reciprocal.
//!
//! Both need the directional albedo `E(μ)` of the wrapped lobe with `F = 1` at every
//! evaluation. [`AlbedoFit`] represents it, for the model's `α`, by a short Chebyshev series
//! in a warped cosine, fitted to [`energy::directional_albedo`] and evaluated branch-free on
//! lanes (one division and a Clenshaw recurrence). Its coefficients ship as a table over `α`
//! (generated from the quadrature, `src/models/multiscatter/fit_tables.rs`), so a
//! construction is an interpolation of a few microseconds, not a quadrature.
//!
//! # Scope
//!
//! The wrapped model is a [`CookTorrance`] with the height-correlated Smith term
//! ([`SmithHeightCorrelated`], the one [`energy::directional_albedo`] integrates) and an
//! isotropic GGX or Beckmann distribution ([`AlbedoNdf`]; an anisotropic [`Ggx`] is
//! rejected with a typed error). The Fresnel term gives its average `F_avg` through
//! [`FresnelAverage`]: closed forms for [`Schlick`] and [`F82Tint`], exact quadrature for the
//! dielectric and the complex-IOR [`Conductor`] (per channel).
//!
//! References: C. Kulla, A. Conty, "Revisiting Physically Based Shading at Imageworks",
//! SIGGRAPH 2017 course *Physically Based Shading in Theory and Practice*; E. Turquin,
//! "Practical multiple scattering compensation for microfacet models", Industrial Light &
//! Magic technical report, 2019; E. Heitz, J. Hanika, E. d'Eon, C. Dachsbacher,
//! "Multiple-Scattering Microfacet BSDFs with the Smith Model", ACM TOG 35(4), 2016 (the
//! reference the tests compare with).

use super::{Brdf, Energy, Kinks, Properties, Reciprocity, masked, safe_dirs};
use crate::energy::{self, Distribution};
use crate::fresnel::{
    AnyFresnel, Conductor, Dielectric, F82Tint, FittedConductor, FresnelTerm, NoFresnel, Schlick,
};
use crate::masking::SmithHeightCorrelated;
use crate::models::CookTorrance;
use crate::ndf::{AnyNdf, Beckmann, Ggx, GgxIsotropic};
use crate::real::{Splat, splat_array, splat_scalar};
use crate::sampling::lobes::{first_probability, mean, pdf_pair, sample_pair};
use crate::sampling::{Sample, SampleBrdf, pdf_cosine};
use crate::{Error, Real, Scalar, Vec3};

/// Terms of the Chebyshev series of [`AlbedoFit`] (and nodes of its fit).
pub const FIT_TERMS: usize = 20;

// ---------------------------------------------------------------------------------------------
// The directional albedo E(μ) of one roughness, as a short series
// ---------------------------------------------------------------------------------------------

/// The directional albedo `E(μ)` (`F = 1`) of an isotropic GGX or Beckmann lobe with
/// height-correlated Smith masking, for one `α`, as a Chebyshev series in a warped cosine:
///
/// ```text
/// t(μ) = ((1 + 2α) μ − α) / (μ + α)          maps μ ∈ [0, 1] onto t ∈ [−1, 1]
/// E(μ) ≈ clamp( Σ_{k<K} c_k(α) T_k(t(μ)), 0, 1 ),    K = FIT_TERMS
/// ```
///
/// **Why this warp.** For small `α` the albedo depends on `μ` mainly through `μ/α` (the
/// Smith `Λ` is a function of `cot θ / α`): it is 1 except in a grazing band of width `~α`.
/// `t` spreads that band over the whole interval (`μ = α` is `t ≈ 0`), so one short series
/// serves every `α` in `[1e-4, 1]`; for `α = 1` the warp is mild (`t = (3μ − 1)/(μ + 1)`).
///
/// **The series of one `α`** ([`AlbedoFit::integrate`]): `c_k(α)` interpolate
/// [`energy::directional_albedo`] at the `K` Chebyshev-Gauss nodes `t_j = cos(π (j + ½)/K)`
/// (discrete orthogonality: `c_k = (2/K) Σ_j E(μ(t_j)) T_k(t_j)`, `c_0` halved). Error
/// against a direct `directional_albedo` (measured in `tests/multiscatter.rs`, α ∈ {1e-4,
/// …, 1}, 20 cosines): on `μ ∈ [0.05, 1]` at most 4.4e-5 for GGX (peak at α = 1, μ = 0.05)
/// and 6.4e-5 for Beckmann (α = 0.03, μ = 0.15); at grazing `μ ∈ [1e-3, 0.05)` at most
/// 3.4e-4 for GGX (α = 1, μ = 0.003, where `E(μ)` is least smooth) and 6.9e-5 for
/// Beckmann. (`directional_albedo` itself is within 1.5e-5 of the adaptive reference,
/// `tests/energy.rs`.) With 12 terms the GGX error would be 2e-4, with 32 terms 4e-6.
///
/// **The coefficients as functions of `α`** ([`AlbedoFit::new`]): the crate ships
/// `c_k(α_m)` (rounded to `f32`, [`albedo_fit_table`]) at Chebyshev-Gauss nodes of a warped
/// roughness on two segments, and interpolates them (Chebyshev interpolation, in the
/// barycentric form of Berrut & Trefethen 2004, eq. 5.3 with first-kind weights
/// `(−1)^m sin(π (m + ½)/M)`):
///
/// ```text
/// α ∈ [1e-4, α_s]:  τ affine in ln α,  FIT_TABLE_LOW  = 8 nodes
/// α ∈ [α_s, 1]:     τ affine in √α,    FIT_TABLE_HIGH = 32 nodes
/// α_s = 1e-6 (1 − t_0)/(1 + t_0 − 2e-6) ≈ 6.48e-4,   t_0 = cos(π (K − ½)/K)
/// c_k(α) = Σ_m w_m c_k(α_m)/(τ − τ_m) / Σ_m w_m/(τ − τ_m)
/// ```
///
/// The split `α_s` is where the most grazing fit node `μ(t_0) ≈ 1.5e-3 α` reaches
/// `directional_albedo`'s cosine floor `1e-6`: below it that node's value is `E(1e-6)`, so
/// `c_k(α)` has a kink there (one series over `[1e-4, 1]` with 32 nodes errs by 1e-5 to 5e-5
/// next to it, in `ln α`, `α^(1/3)` or `√α` alike).
/// Warps chosen by measuring (a 20-term fit at 92 roughnesses between the nodes, the worst
/// `|Σ Δc_k T_k(t)|` over `t`): on `[α_s, 1]` with 32 nodes, `√α` gives 2.7e-11 (GGX) and
/// 1.8e-7 (Beckmann), `α^(1/3)` 2.5e-11 and 6.9e-7, `ln α` 1.0e-8 and 3.6e-5 (`ln α` puts half
/// its nodes below `α = 0.025`, where `c_k(α)` hardly changes); on `[1e-4, α_s]`, `ln α` with 8
/// nodes gives 8e-11. **Measured added error** of [`AlbedoFit::new`] against
/// [`AlbedoFit::integrate`] (the `f32` rounding of the table included; the midpoint in `τ`
/// of every pair of neighbouring nodes and the segment ends, 201 cosines uniform in `t`,
/// `tests/multiscatter.rs`): at most 4.6e-8 (GGX) and 2.0e-7 (Beckmann, at α = 0.17,
/// μ = 1) in `E(μ)`, 3.4e-8 and 3.3e-8 in `E_avg`, against the target 1e-5. Against
/// [`energy::directional_albedo`] (24 cosines in `[1e-3, 1]` at the same roughnesses) both
/// fits err by at most 3.57e-4 (GGX, grazing) and 7.47e-5 (Beckmann); the tabulated one
/// by at most 2.0e-7 more.
///
/// **Evaluation.** One division (the warp) and `K − 1` steps of Clenshaw's recurrence
/// `b_k = c_k + 2t b_{k+1} − b_{k+2}` (stable in `f32`), branch-free: the same body for
/// `f32`, `f64` and SIMD lanes. Domain: `μ ∈ [0, 1]` (clamped).
///
/// **Cost of construction.** [`AlbedoFit::new`]: one interpolation (8 or 32 nodes × `K`
/// coefficients, no allocation, no quadrature of `E`) and `E_avg` of the series (64
/// Clenshaw sums with the shipped Gauss-Legendre rule, [`energy::gauss_legendre_16`]): 1.7–2.2 µs
/// (`cargo bench --bench construction`, AMD EPYC (Zen 4), one core, release).
/// [`AlbedoFit::integrate`]: `K` calls of [`energy::directional_albedo`], 10.6–52.4 ms on the
/// same machine (GGX α = 0.5 fastest, GGX α = 3e-4 and Beckmann α = 1 slowest). 10 000
/// materials of distinct roughness cost tens of milliseconds to build, at scene-load speed;
/// sharing one fit between materials of the same roughness (`KullaConty::from_parts`,
/// `Turquin::from_parts`) is no longer needed for speed.
///
/// References: Kulla & Conty 2017 (the role of `E` and `E_avg`); L. N. Trefethen,
/// *Approximation Theory and Approximation Practice*, SIAM 2013 (Chebyshev interpolation,
/// Clenshaw's recurrence); J.-P. Berrut, L. N. Trefethen, "Barycentric Lagrange
/// Interpolation", SIAM Review 46(3), 2004.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlbedoFit<R> {
    /// `c_0 … c_{K−1}` (`c_0` already halved).
    coeffs: [R; FIT_TERMS],
    /// `1 + 2α`.
    p: R,
    /// `α`.
    q: R,
    /// `E_avg = 2 ∫ E(μ) μ dμ` of the series.
    average: f64,
    /// The distribution and `α` the series was fitted for.
    distribution: Distribution,
    alpha: f64,
}

impl<S: Scalar> AlbedoFit<S> {
    /// `E(μ)` of `distribution` with slope parameter `alpha ∈ [1e-4, 1]`, from the shipped
    /// coefficient table ([`albedo_fit_table`]) by Chebyshev interpolation in the warped
    /// roughness (see the type's docs): no quadrature, no allocation, 1.7–2.2 µs. Within
    /// 2.0e-7 of [`AlbedoFit::integrate`] (measured; the type's docs).
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfDomain`] (`param` `"alpha"`) for `alpha`
    /// outside `[1e-4, 1]`, as [`energy::directional_albedo`].
    pub fn new(distribution: Distribution, alpha: f64) -> Result<Self, Error> {
        crate::error::check("alpha", alpha, "[1e-4, 1]", |a| {
            (ALPHA_MIN..=1.0).contains(&a)
        })?;
        let table = albedo_fit_table(distribution);
        let (first, n, tau) = fit_segment(alpha);
        let mut num = [0.0; FIT_TERMS];
        let mut den = 0.0;
        for m in 0..n {
            let row = &table[(first + m) * FIT_TERMS..(first + m + 1) * FIT_TERMS];
            let angle = core::f64::consts::PI * (m as f64 + 0.5) / n as f64;
            let d = tau - Real::cos(angle);
            if d == 0.0 {
                // At a node the interpolant is the node.
                num = core::array::from_fn(|k| f64::from(row[k]));
                den = 1.0;
                break;
            }
            let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
            let w = sign * Real::sin(angle) / d;
            den += w;
            for (acc, &c) in num.iter_mut().zip(row) {
                *acc += w * f64::from(c);
            }
        }
        Ok(Self::from_coefficients(
            distribution,
            alpha,
            num.map(|c| c / den),
        ))
    }

    /// `E(μ)` of `distribution` with slope parameter `alpha ∈ [1e-4, 1]`, fitted now:
    /// [`FIT_TERMS`] quadratures [`energy::directional_albedo`] at the Chebyshev nodes of
    /// `t` (the type's docs). The definition the shipped table ([`albedo_fit_table`]) is
    /// generated from, for users who want the fit without the table's interpolation error
    /// (≤ 2.0e-7) and for the tests.
    ///
    /// Cost: 10.6–52.4 ms (`cargo bench --bench construction`, AMD EPYC (Zen 4)); use
    /// [`AlbedoFit::new`] at scene load.
    ///
    /// # Errors
    /// As [`energy::directional_albedo`] for `alpha`.
    pub fn integrate(distribution: Distribution, alpha: f64) -> Result<Self, Error> {
        let mut values = [0.0; FIT_TERMS];
        for (j, v) in values.iter_mut().enumerate() {
            *v = energy::directional_albedo(distribution, alpha, mu_of_t(alpha, node(j)))?;
        }
        let coeffs = crate::fast::chebyshev_coefficients(&values);
        Ok(Self::from_coefficients(distribution, alpha, coeffs))
    }

    /// The fit from its coefficients (`c_0` halved): the warp's constants and `E_avg`.
    fn from_coefficients(distribution: Distribution, alpha: f64, coeffs: [f64; FIT_TERMS]) -> Self {
        let average = series_average(&coeffs, alpha);
        Self {
            coeffs: coeffs.map(S::of),
            p: S::of(1.0 + 2.0 * alpha),
            q: S::of(alpha),
            average,
            distribution,
            alpha,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The shipped coefficient table c_k(α_m)
// ---------------------------------------------------------------------------------------------

mod fit_tables;

/// Nodes of the shipped coefficient table on the small-roughness segment `α ∈ [1e-4, α_s]`
/// (Chebyshev-Gauss in `ln α`; see [`AlbedoFit`]).
///
/// (To change a size: set it here and run `cargo run --release -p brdf-tools --bin
/// energy_tables -- --fit`, which rewrites `src/models/multiscatter/fit_tables.rs`; the table
/// is a slice, so the crate compiles before it is regenerated, and `tests/multiscatter.rs`
/// checks its length.)
pub const FIT_TABLE_LOW: usize = 8;
/// Nodes of the shipped coefficient table on `α ∈ [α_s, 1]` (Chebyshev-Gauss in `√α`).
pub const FIT_TABLE_HIGH: usize = 32;
/// Roughness nodes of the shipped coefficient table: [`FIT_TABLE_LOW`] then
/// [`FIT_TABLE_HIGH`].
pub const FIT_TABLE_NODES: usize = FIT_TABLE_LOW + FIT_TABLE_HIGH;

/// Smallest `α` of the fits (and of [`energy::directional_albedo`]'s domain).
const ALPHA_MIN: f64 = 1e-4;
/// The cosine floor of [`energy::directional_albedo`] (it clamps `μ` to `[1e-6, 1]`).
const MU_FLOOR: f64 = 1e-6;

/// `α_s`, where the most grazing fit node `μ(t_0) = α (1 + t_0)/(1 + 2α − t_0)` equals
/// [`MU_FLOOR`]: `α_s = 1e-6 (1 − t_0)/(1 + t_0 − 2e-6)` ≈ 6.48e-4.
fn split_alpha() -> f64 {
    let t0 = node(FIT_TERMS - 1);
    MU_FLOOR * (1.0 - t0) / (1.0 + t0 - 2.0 * MU_FLOOR)
}

/// The segment of `alpha`: (its first row in the table, its node count, `τ ∈ [−1, 1]`).
fn fit_segment(alpha: f64) -> (usize, usize, f64) {
    let s = split_alpha();
    if alpha < s {
        let (lo, hi) = (Real::ln(ALPHA_MIN), Real::ln(s));
        let tau = 2.0 * (Real::ln(alpha) - lo) / (hi - lo) - 1.0;
        (0, FIT_TABLE_LOW, tau.clamp(-1.0, 1.0))
    } else {
        let lo = Real::sqrt(s);
        let tau = 2.0 * (Real::sqrt(alpha) - lo) / (1.0 - lo) - 1.0;
        (FIT_TABLE_LOW, FIT_TABLE_HIGH, tau.clamp(-1.0, 1.0))
    }
}

/// `α` of roughness node `m` of the shipped coefficient table: on the low segment
/// (`m < FIT_TABLE_LOW`, local index `i = m`, `M = FIT_TABLE_LOW`)
/// `α = exp(ln 1e-4 + (τ_i + 1)/2 · (ln α_s − ln 1e-4))`, on the high one (`i = m −
/// FIT_TABLE_LOW`, `M = FIT_TABLE_HIGH`) `α = (√α_s + (τ_i + 1)/2 · (1 − √α_s))²`, with
/// `τ_i = cos(π (i + ½)/M)` (so `α` descends within each segment; `α_s` as in [`AlbedoFit`]).
///
/// Domain `m < FIT_TABLE_NODES` (panics outside).
#[must_use]
pub fn albedo_fit_alpha(m: usize) -> f64 {
    assert!(m < FIT_TABLE_NODES, "node {m}");
    let s = split_alpha();
    let (i, n) = if m < FIT_TABLE_LOW {
        (m, FIT_TABLE_LOW)
    } else {
        (m - FIT_TABLE_LOW, FIT_TABLE_HIGH)
    };
    let tau = Real::cos(core::f64::consts::PI * (i as f64 + 0.5) / n as f64);
    let x = 0.5 * (tau + 1.0);
    let alpha = if m < FIT_TABLE_LOW {
        let (lo, hi) = (Real::ln(ALPHA_MIN), Real::ln(s));
        Real::exp(lo + x * (hi - lo))
    } else {
        let lo = Real::sqrt(s);
        let r = lo + x * (1.0 - lo);
        r * r
    };
    alpha.clamp(ALPHA_MIN, 1.0)
}

/// Row `m` of the shipped coefficient table, computed now: the coefficients `c_0 … c_{K−1}`
/// (`c_0` halved) of [`AlbedoFit::integrate`] at `α` = [`albedo_fit_alpha`]`(m)`, rounded to
/// `f32`. The shipped row is this, bit for bit (`tests/multiscatter.rs` regenerates rows and
/// fails on any difference; `cargo run --release -p brdf-tools --bin energy_tables -- --fit`
/// writes `src/models/multiscatter/fit_tables.rs`).
///
/// Why `f32`: its rounding adds at most ~1e-7 to `E(μ)` (measured with the interpolation,
/// [`AlbedoFit`]), two orders below the 1e-5 target, and a bit-for-bit regeneration in
/// `f32` does not depend on the last bits of the platform's `exp`/`sin`/`cos` (as for the
/// albedo tables of [`energy`]); the table is 6.4 KB.
///
/// Domain `m < FIT_TABLE_NODES` (panics outside).
#[must_use]
pub fn albedo_fit_node(distribution: Distribution, m: usize) -> [f32; FIT_TERMS] {
    let alpha = albedo_fit_alpha(m);
    match AlbedoFit::<f64>::integrate(distribution, alpha) {
        Ok(fit) => fit.coeffs.map(|c| c as f32),
        Err(_) => [f32::NAN; FIT_TERMS],
    }
}

/// The shipped coefficient table of one distribution: [`FIT_TABLE_NODES`] rows (roughness
/// node `m`, `α` = [`albedo_fit_alpha`]`(m)`) of [`FIT_TERMS`] coefficients, row-major, `f32`.
#[must_use]
pub fn albedo_fit_table(distribution: Distribution) -> &'static [f32] {
    match distribution {
        Distribution::Ggx => fit_tables::GGX_FIT,
        Distribution::Beckmann => fit_tables::BECKMANN_FIT,
    }
}

impl<R: Real> AlbedoFit<R> {
    /// `E(μ)` of the series, in `[0, 1]`, for `mu ∈ [0, 1]` (clamped). Branch-free.
    #[inline(always)]
    pub fn eval(&self, mu: R) -> R {
        let mu = mu.saturate();
        let t = self.p.mul_add(mu, -self.q) / (mu + self.q);
        let t2 = t + t;
        let (mut b1, mut b2) = (R::zero(), R::zero());
        for k in (1..FIT_TERMS).rev() {
            let b0 = t2.mul_add(b1, self.coeffs[k] - b2);
            b2 = b1;
            b1 = b0;
        }
        t.mul_add(b1, self.coeffs[0] - b2).saturate()
    }

    /// `E_avg = 2 ∫_0^1 E(μ) μ dμ` of the series (as `1 − 2∫(1 − E) μ dμ`, by 4 × 16-point
    /// Gauss-Legendre in `t`, where that integrand is smooth), in `[0, 1]`.
    #[must_use]
    pub fn average(&self) -> f64 {
        self.average
    }

    /// The coefficients `c_0 … c_{K−1}` of the series (`c_0` already halved: `E =
    /// Σ_k c_k T_k(t)` before the clamp).
    #[must_use]
    pub fn coefficients(&self) -> &[R; FIT_TERMS] {
        &self.coeffs
    }

    /// The distribution the series was fitted for.
    #[must_use]
    pub fn distribution(&self) -> Distribution {
        self.distribution
    }

    /// The slope parameter `α` the series was fitted for.
    #[must_use]
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
}

impl<S: Scalar> Splat for AlbedoFit<S> {
    type On<L: Real> = AlbedoFit<L>;
    #[inline]
    fn splat<L: Real>(&self) -> AlbedoFit<L> {
        AlbedoFit {
            coeffs: splat_array(&self.coeffs),
            p: splat_scalar(self.p),
            q: splat_scalar(self.q),
            average: self.average,
            distribution: self.distribution,
            alpha: self.alpha,
        }
    }
}

/// The `j`-th Chebyshev-Gauss node `cos(π (j + ½)/K)`.
fn node(j: usize) -> f64 {
    crate::fast::chebyshev_node(j, FIT_TERMS)
}

/// The inverse of the warp: `μ(t) = α (1 + t) / (1 + 2α − t)`.
fn mu_of_t(alpha: f64, t: f64) -> f64 {
    (alpha * (1.0 + t) / (1.0 + 2.0 * alpha - t)).clamp(0.0, 1.0)
}

/// `E_avg = 1 − 2 ∫_0^1 (1 − E(μ)) μ dμ` of the series, integrated in `t`
/// (`dμ/dt = 2α(1 + α)/(1 + 2α − t)²`). The loss `1 − E` is written out because the
/// Jacobian grows like `1/α` towards `t = 1` (normal view), where `1 − E` vanishes: the
/// product is smooth, `E μ dμ/dt` is not. The 16-point Gauss-Legendre rule on `[0, 1]` is
/// [`energy::gauss_legendre_16`], [`energy::gauss_legendre`]`::<16>()` as shipped (computing
/// it took 5.2 µs of a 7.4 µs construction).
fn series_average(coeffs: &[f64; FIT_TERMS], alpha: f64) -> f64 {
    let (x, w) = energy::gauss_legendre_16();
    let mut sum = 0.0;
    for panel in 0..4 {
        for (&xk, &wk) in x.iter().zip(w) {
            let t = -1.0 + 0.5 * (f64::from(panel) + xk);
            let mu = mu_of_t(alpha, t);
            let jac =
                2.0 * alpha * (1.0 + alpha) / ((1.0 + 2.0 * alpha - t) * (1.0 + 2.0 * alpha - t));
            sum += 0.5 * wk * (1.0 - chebyshev(coeffs, t).clamp(0.0, 1.0)) * mu * jac;
        }
    }
    (1.0 - 2.0 * sum).clamp(0.0, 1.0)
}

/// `Σ c_k T_k(t)` in `f64` (Clenshaw).
fn chebyshev(coeffs: &[f64; FIT_TERMS], t: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for k in (1..FIT_TERMS).rev() {
        let b0 = 2.0 * t * b1 + coeffs[k] - b2;
        b2 = b1;
        b1 = b0;
    }
    t * b1 + coeffs[0] - b2
}

// ---------------------------------------------------------------------------------------------
// What the wrapped model must tell: its distribution and α, its Fresnel averages
// ---------------------------------------------------------------------------------------------

/// An NDF whose albedo [`energy::directional_albedo`] tabulates: isotropic GGX or Beckmann,
/// with its `α`.
pub trait AlbedoNdf {
    /// `(distribution, α)`.
    ///
    /// # Errors
    /// [`Error::OutOfDomain`] (`param` `"alpha_y"`) for an anisotropic distribution: the
    /// albedo tables are isotropic.
    fn albedo_ndf(&self) -> Result<(Distribution, f64), Error>;
}

/// The domain message of an anisotropic NDF given to a compensation.
const ISOTROPIC: &str = "alpha_y = alpha_x (multiple-scattering compensation is isotropic)";

fn isotropic(distribution: Distribution, ax: f64, ay: f64) -> Result<(Distribution, f64), Error> {
    if ax == ay {
        Ok((distribution, ax))
    } else {
        Err(Error::OutOfDomain {
            param: "alpha_y",
            value: ay,
            domain: ISOTROPIC,
        })
    }
}

impl<S: Scalar> AlbedoNdf for Ggx<S> {
    /// GGX with `αx = αy`; anisotropic is an error.
    fn albedo_ndf(&self) -> Result<(Distribution, f64), Error> {
        isotropic(
            Distribution::Ggx,
            self.alpha_x().into(),
            self.alpha_y().into(),
        )
    }
}

impl<S: Scalar> AlbedoNdf for GgxIsotropic<S> {
    /// GGX with its `α`.
    fn albedo_ndf(&self) -> Result<(Distribution, f64), Error> {
        Ok((Distribution::Ggx, self.alpha().into()))
    }
}

impl<S: Scalar> AlbedoNdf for Beckmann<S> {
    /// Beckmann with `αx = αy`; anisotropic is an error.
    fn albedo_ndf(&self) -> Result<(Distribution, f64), Error> {
        isotropic(
            Distribution::Beckmann,
            self.alpha_x().into(),
            self.alpha_y().into(),
        )
    }
}

impl<S: Scalar> AlbedoNdf for AnyNdf<S> {
    /// The wrapped distribution's (so a runtime Cook-Torrance can be compensated).
    fn albedo_ndf(&self) -> Result<(Distribution, f64), Error> {
        crate::ndf::on_any_ndf!(self, n => n.albedo_ndf())
    }
}

/// A Fresnel term's cosine-weighted hemispherical average and normal-incidence reflectance,
/// per channel, in `f64`:
///
/// ```text
/// F_avg = 2 ∫_0^1 F(μ) μ dμ,        F0 = F(1)
/// ```
///
/// Closed forms where they exist ([`Schlick`]: `F0 + (F90 − F0)/21`; [`F82Tint`]:
/// [`energy::f82_average`]); the others by [`energy::fresnel_average`] on the term splatted
/// to `f64` (exact to ~1e-12 for conductors).
///
/// Reference: Kulla & Conty 2017 (`F_avg`).
pub trait FresnelAverage<const N: usize> {
    /// `F_avg` per channel.
    fn average(&self) -> [f64; N];
    /// `F(1)` per channel.
    fn normal_reflectance(&self) -> [f64; N];
}

/// `F_avg` by quadrature, on the term splatted to `f64`.
fn by_quadrature<F, const N: usize>(f: &F) -> [f64; N]
where
    F: Splat,
    F::On<f64>: FresnelTerm<f64, N>,
{
    energy::fresnel_average(&f.splat::<f64>())
}

impl<S: Scalar, const N: usize> FresnelAverage<N> for Schlick<S, N> {
    /// `F_avg = F0 + (F90 − F0) · 2 B(2, 6) = F0 + (F90 − F0)/21` (with `F90 = 1`:
    /// [`energy::schlick_average`]).
    fn average(&self) -> [f64; N] {
        let (f0, f90) = (self.f0(), self.f90());
        core::array::from_fn(|c| {
            let (a, b): (f64, f64) = (f0[c].into(), f90[c].into());
            a + (b - a) / 21.0
        })
    }
    fn normal_reflectance(&self) -> [f64; N] {
        self.f0().map(Into::into)
    }
}

impl<S: Scalar, const N: usize> FresnelAverage<N> for F82Tint<S, N> {
    /// [`energy::f82_average`] per channel (exact while the F82 curve needs no clamping,
    /// see there).
    fn average(&self) -> [f64; N] {
        let (f0, b) = (self.f0(), self.b());
        core::array::from_fn(|c| energy::f82_average(f0[c].into(), b[c].into()))
    }
    fn normal_reflectance(&self) -> [f64; N] {
        self.f0().map(Into::into)
    }
}

impl<S: Scalar, const N: usize, P: crate::fast::SqrtFn, D: crate::fresnel::DivisionPlan>
    FresnelAverage<N> for Conductor<S, N, P, D>
{
    /// [`energy::fresnel_average`] of the exact complex-IOR reflectance, per channel.
    fn average(&self) -> [f64; N] {
        by_quadrature(self)
    }
    fn normal_reflectance(&self) -> [f64; N] {
        self.splat::<f64>().eval(1.0)
    }
}

impl<S: Scalar, const N: usize> FresnelAverage<N> for FittedConductor<S, N> {
    /// [`energy::fresnel_average`] of the fitted reflectance (within the fit's tolerance of
    /// the exact conductor's), per channel.
    fn average(&self) -> [f64; N] {
        by_quadrature(self)
    }
    fn normal_reflectance(&self) -> [f64; N] {
        self.splat::<f64>().eval(1.0)
    }
}

impl<S: Scalar, const N: usize> FresnelAverage<N> for Dielectric<S, N> {
    /// [`energy::fresnel_average`] of the exact dielectric reflectance.
    fn average(&self) -> [f64; N] {
        by_quadrature(self)
    }
    fn normal_reflectance(&self) -> [f64; N] {
        self.splat::<f64>().eval(1.0)
    }
}

impl<S: Scalar> FresnelAverage<3> for AnyFresnel<S> {
    /// The wrapped term's (its closed form where it has one), so that a runtime
    /// compensation is the static one bit for bit.
    fn average(&self) -> [f64; 3] {
        crate::fresnel::on_any_fresnel!(self, f => f.average())
    }
    fn normal_reflectance(&self) -> [f64; 3] {
        crate::fresnel::on_any_fresnel!(self, f => f.normal_reflectance())
    }
}

impl<const N: usize> FresnelAverage<N> for NoFresnel {
    /// `1`.
    fn average(&self) -> [f64; N] {
        [1.0; N]
    }
    fn normal_reflectance(&self) -> [f64; N] {
        [1.0; N]
    }
}

// ---------------------------------------------------------------------------------------------
// Kulla & Conty 2017
// ---------------------------------------------------------------------------------------------

/// Kulla & Conty's multiple-scattering compensation of a Cook-Torrance lobe `M`: the single-
/// scattering lobe plus a reciprocal lobe carrying the energy it loses.
///
/// ```text
/// f(wi, wo) = f_ss(wi, wo) + F_ms · (1 − E(μi)) (1 − E(μo)) / (π (1 − E_avg))
/// F_ms      = F_avg² E_avg / (1 − F_avg (1 − E_avg))          (per channel)
/// ```
///
/// `E` is the lobe's directional albedo with `F = 1` ([`AlbedoFit`], fitted at
/// construction), `E_avg = 2∫E(μ)μ dμ` its average (of the same series, so the added lobe
/// integrates to exactly `F_ms (1 − E(μo))`), `F_avg` the Fresnel term's average
/// ([`FresnelAverage`]). With `F = 1` the albedo is `E(μo) + (1 − E(μo)) = 1`: the white
/// furnace closes (up to the error of the series: measured `|ρ − 1| ≤ 5.5e-5` for GGX and
/// Beckmann, `α ∈ [1e-4, 1]`, `μo ∈ [0.05, 1]`; the test's bound is 1e-3). `F_ms` sums the
/// bounces `k ≥ 2` of a walk that leaves with probability `E_avg` and is weighted by
/// `F_avg` per bounce: an approximation. Against the random walk on the Smith microsurface
/// (Heitz et al. 2016) with gold's exact Fresnel, the compensated albedo is within 1e-2 for
/// `α ≤ 0.5` and `μo ≥ 0.5`, and low by up to 1.4e-2 at `α = 0.5, μo = 0.2` and 4.5e-2 at
/// `α = 1, μo = 0.3` (green channel: later bounces meet facets at grazing local angles,
/// where gold reflects more than `F_avg`); the single-scattering part is exact.
///
/// Conventions: `wi`, `wo` in the local frame, away from the surface; `0` below the
/// horizon; `eval` excludes `cos θi`. Domain: the wrapped model's; isotropic `α` only
/// ([`AlbedoNdf`]).
///
/// Properties: reciprocal when `M` is (the added lobe is symmetric). Albedo
/// `ρ(wo) ≤ E_F(μo) + F_ms (1 − E(μo)) ≤ 1` when `F ≤ 1` (`E_F ≤ E` the lobe's albedo with
/// its Fresnel term, `F_ms ≤ F_avg ≤ 1`), up to the series' error.
///
/// Sampling ([`SampleBrdf`]): a one-sample mixture (Veach 1997, §9.2.4) of the wrapped
/// model's sampler and the cosine-weighted hemisphere for the added lobe, the latter chosen
/// with probability
///
/// ```text
/// P_ms = ρ̂_ms / (ρ̂_ss + ρ̂_ms),   ρ̂_ms = mean(F_ms) (1 − E(μo)),   ρ̂_ss = ρ̂_M(wo) E(μo)
/// pdf  = (1 − P_ms) pdf_M(wi) + P_ms cos θi/π
/// ```
///
/// (`ρ̂_M` the wrapped model's [`SampleBrdf::albedo_estimate`]); the estimate is
/// `ρ̂_ss + ρ̂_ms`.
///
/// Reference: C. Kulla, A. Conty, "Revisiting Physically Based Shading at Imageworks",
/// SIGGRAPH 2017 course *Physically Based Shading in Theory and Practice* (after
/// C. Kelemen, L. Szirmay-Kalos, "A Microfacet Based Coupled Specular-Matte BRDF Model with
/// Importance Sampling", Eurographics 2001 short papers, for the `(1 − E)(1 − E)` form).
///
/// # Examples
///
/// ```
/// use brdf::{Brdf, Vec3, fresnel::NoFresnel, masking::SmithHeightCorrelated};
/// use brdf::{models::{CookTorrance, KullaConty}, ndf::Ggx};
/// let ct = CookTorrance::new(Ggx::new(1.0_f32)?, NoFresnel, SmithHeightCorrelated);
/// let ms = KullaConty::<_, f32, 1>::new(ct)?;
/// let n = Vec3::new(0.0, 0.0, 1.0);
/// // The added lobe is positive: the compensated model reflects more.
/// assert!(ms.eval(n, n)[0] > Brdf::<f32, 1>::eval(&ct, n, n)[0]);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KullaConty<M, R, const N: usize> {
    /// The single-scattering model.
    pub model: M,
    albedo: AlbedoFit<R>,
    /// `F_ms / (π (1 − E_avg))` per channel.
    k: [R; N],
    /// `mean(F_ms)`, for the sampler's choice.
    ms_mean: R,
    f_avg: [f64; N],
    f_ms: [f64; N],
}

impl<S, D, F, Q, const N: usize> KullaConty<CookTorrance<S, D, F, SmithHeightCorrelated, Q>, S, N>
where
    S: Scalar,
    D: AlbedoNdf,
    F: FresnelAverage<N>,
{
    /// Wraps a Cook-Torrance lobe with height-correlated Smith masking: `E(μ)` for its NDF
    /// and `α` from the shipped table ([`AlbedoFit::new`], 1.7–2.2 µs), `F_avg` from its
    /// Fresnel term ([`FresnelAverage`]: closed forms for Schlick and F82-tint, a 64-point
    /// quadrature for the exact conductor and dielectric). Measured (`cargo bench --bench
    /// construction`, AMD EPYC (Zen 4), load 2.8): 4.7 µs for GGX α = 0.5 with gold's exact
    /// complex-IOR Fresnel (9.9 µs in the same run while [`energy::fresnel_average`]
    /// recomputed its Gauss-Legendre nodes on every call), against 10.7 ms when the fit was
    /// integrated at construction.
    ///
    /// # Errors
    /// [`Error::OutOfDomain`] for an anisotropic NDF ([`AlbedoNdf`]).
    pub fn new(model: CookTorrance<S, D, F, SmithHeightCorrelated, Q>) -> Result<Self, Error> {
        let (distribution, alpha) = model.ndf.albedo_ndf()?;
        let albedo = AlbedoFit::new(distribution, alpha)?;
        let f_avg = model.fresnel.average();
        Ok(Self::from_parts(model, albedo, f_avg))
    }
}

impl<M, S: Scalar, const N: usize> KullaConty<M, S, N> {
    /// The compensation of `model` from an already fitted albedo and the Fresnel averages
    /// (each `F_avg ∈ [0, 1]`, clamped): for a lobe the constructor does not know, or to share
    /// one [`AlbedoFit`] between models of the same roughness. The caller vouches that
    /// `albedo` is the albedo (with `F = 1`) of `model`.
    pub fn from_parts(model: M, albedo: AlbedoFit<S>, f_avg: [f64; N]) -> Self {
        let e_avg = albedo.average();
        let f_avg = f_avg.map(|f| f.clamp(0.0, 1.0));
        let f_ms = f_avg.map(|f| energy::kulla_conty_fresnel(f, e_avg));
        let lobe = energy::kulla_conty_lobe(0.0, 0.0, e_avg);
        Self {
            model,
            albedo,
            k: f_ms.map(|f| S::of(f * lobe)),
            ms_mean: S::of(f_ms.iter().sum::<f64>() / N.max(1) as f64),
            f_avg,
            f_ms,
        }
    }
}

impl<M, R: Real, const N: usize> KullaConty<M, R, N> {
    /// The fitted albedo `E(μ)` (with `E_avg`).
    pub fn albedo(&self) -> &AlbedoFit<R> {
        &self.albedo
    }

    /// `F_avg` per channel.
    pub fn f_avg(&self) -> [f64; N] {
        self.f_avg
    }

    /// `F_ms = F_avg² E_avg / (1 − F_avg (1 − E_avg))` per channel.
    pub fn f_ms(&self) -> [f64; N] {
        self.f_ms
    }

    /// The added lobe alone, `F_ms (1 − E(μi))(1 − E(μo)) / (π (1 − E_avg))`, on safe
    /// directions.
    #[inline(always)]
    fn lobe(&self, cos_i: R, cos_o: R) -> R {
        (R::one() - self.albedo.eval(cos_i)) * (R::one() - self.albedo.eval(cos_o))
    }

    /// `(ρ̂_ss, ρ̂_ms)` of the sampler (see the type's docs).
    #[inline(always)]
    fn estimates(&self, wo: Vec3<R>) -> (R, R)
    where
        M: SampleBrdf<R, N>,
    {
        let e = self.albedo.eval(wo.z);
        (
            self.model.albedo_estimate(wo) * e,
            self.ms_mean * (R::one() - e),
        )
    }
}

impl<M: Splat, S: Scalar, const N: usize> Splat for KullaConty<M, S, N> {
    const EXPLICIT_LANES: bool = M::EXPLICIT_LANES;
    type On<L: Real> = KullaConty<M::On<L>, L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> Self::On<L> {
        KullaConty {
            model: self.model.splat(),
            albedo: self.albedo.splat(),
            k: splat_array(&self.k),
            ms_mean: splat_scalar(self.ms_mean),
            f_avg: self.f_avg,
            f_ms: self.f_ms,
        }
    }
}

/// The energy condition of [`KullaConty`].
const KC_CONDITION: &str =
    "F ≤ 1 (ρ ≤ E_F(μo) + F_ms (1 − E(μo)) ≤ 1, up to the error of the E(μ) series)";

impl<M: Brdf<R, N>, R: Real, const N: usize> Brdf<R, N> for KullaConty<M, R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let f = self.model.eval(wi, wo);
        let (m, swi, swo) = safe_dirs(wi, wo);
        let lobe = self.lobe(swi.z, swo.z);
        masked(
            m,
            crate::real::channels(
                #[inline(always)]
                |c| lobe.mul_add(self.k[c], f[c]),
            ),
        )
    }

    #[inline]
    fn properties(&self) -> Properties {
        let own = Properties {
            reciprocity: Reciprocity::Reciprocal,
            energy: Energy::ConservingWhen {
                condition: KC_CONDITION,
            },
        };
        self.model.properties().combine(own, KC_CONDITION)
    }

    /// The wrapped model's (the added lobe is smooth).
    #[inline]
    fn kinks(&self, wo: Vec3<f64>) -> Kinks {
        self.model.kinks(wo)
    }
}

/// A cosine-weighted direction with its density (no value: the mixture evaluates the whole
/// model once, at the chosen direction).
#[inline(always)]
fn cosine_direction<R: Real, const N: usize>(wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
    let wi = crate::sampling::cosine_hemisphere(u[0], u[1]);
    let pdf = pdf_cosine(wo, wi);
    Sample::new(wi, pdf, [R::zero(); N], [R::zero(); N], wo.z.gt(R::zero()))
}

impl<M: SampleBrdf<R, N>, R: Real, const N: usize> SampleBrdf<R, N> for KullaConty<M, R, N> {
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let (ss, ms) = self.estimates(wo);
        sample_pair(
            first_probability(ss, ms),
            wo,
            u,
            #[inline(always)]
            |u| self.model.sample(wo, u),
            #[inline(always)]
            |u| cosine_direction(wo, u),
            #[inline(always)]
            |wi| self.model.pdf(wo, wi),
            #[inline(always)]
            |wi| pdf_cosine(wo, wi),
            #[inline(always)]
            |wi| self.eval(wi, wo),
        )
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        let (ss, ms) = self.estimates(wo);
        pdf_pair(
            first_probability(ss, ms),
            wo,
            wi,
            #[inline(always)]
            |wi| self.model.pdf(wo, wi),
            #[inline(always)]
            |wi| pdf_cosine(wo, wi),
        )
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        let (ss, ms) = self.estimates(wo);
        ss + ms
    }
}

// ---------------------------------------------------------------------------------------------
// Turquin 2019
// ---------------------------------------------------------------------------------------------

/// Turquin's multiple-scattering compensation of a Cook-Torrance lobe `M`: the lobe scaled by
/// a factor of the view direction alone.
///
/// ```text
/// f(wi, wo) = (1 + F0 (1 − E(μo)) / E(μo)) · f_ss(wi, wo)        (per channel)
/// ```
///
/// `E` as in [`KullaConty`] ([`AlbedoFit`]); `F0 = F(1)` of the wrapped Fresnel term
/// ([`FresnelAverage::normal_reflectance`]), Turquin's stand-in for the average Fresnel
/// ([`crate::energy::turquin_factor`]). With `F = 1`: albedo `E(μo)/E(μo) = 1` (up to the
/// series' error: measured `|ρ − 1| ≤ 5.7e-5` on the domain of [`KullaConty`]'s test).
/// Against the random walk with gold: within 1e-2 for `α ≤ 0.5`, over by up to 6.1e-2 at
/// `α = 1, μo = 1`. The lobe keeps its shape (it is the single-scattering one, brighter), so
/// sampling is the wrapped model's, with the weight scaled.
///
/// Conventions and domain as [`KullaConty`].
///
/// Properties: **not reciprocal** (the factor depends on `μo` only; a test finds the
/// violating pairs). View-side albedo `ρ(wo) = factor · E_F(μo) ≤ E(μo) + F0 (1 − E(μo)) ≤ 1`
/// when `F ≤ 1` (`E_F ≤ E`), but the light-side integral `∫ f cos θo dωo` is not bounded:
/// it reaches 1.94 at `cos θi = 0.05` (GGX α = 1, `F = 1`; measured in the tests), so
/// [`Brdf::properties`] declares it not energy conserving, as for the seed's normalized
/// Blinn-Phong. Real-time use (view-side shading) is what it is made for.
///
/// Reference: E. Turquin, "Practical multiple scattering compensation for microfacet
/// models", Industrial Light & Magic technical report, 2019.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Turquin<M, R, const N: usize> {
    /// The single-scattering model.
    pub model: M,
    albedo: AlbedoFit<R>,
    f0: [R; N],
}

impl<S, D, F, Q, const N: usize> Turquin<CookTorrance<S, D, F, SmithHeightCorrelated, Q>, S, N>
where
    S: Scalar,
    D: AlbedoNdf,
    F: FresnelAverage<N>,
{
    /// Wraps a Cook-Torrance lobe with height-correlated Smith masking (cost: one
    /// [`AlbedoFit::new`] and `F(1)`: 2.2 µs for GGX α = 0.5 with gold's exact Fresnel,
    /// `cargo bench --bench construction`, AMD EPYC (Zen 4)); `F0` from its Fresnel term.
    ///
    /// # Errors
    /// [`Error::OutOfDomain`] for an anisotropic NDF ([`AlbedoNdf`]).
    pub fn new(model: CookTorrance<S, D, F, SmithHeightCorrelated, Q>) -> Result<Self, Error> {
        let (distribution, alpha) = model.ndf.albedo_ndf()?;
        let albedo = AlbedoFit::new(distribution, alpha)?;
        let f0 = model.fresnel.normal_reflectance();
        Ok(Self::from_parts(model, albedo, f0))
    }
}

impl<M, S: Scalar, const N: usize> Turquin<M, S, N> {
    /// The compensation of `model` from an already fitted albedo and `F0` per channel
    /// (clamped to `[0, 1]`); the caller vouches that `albedo` is `model`'s (with `F = 1`).
    pub fn from_parts(model: M, albedo: AlbedoFit<S>, f0: [f64; N]) -> Self {
        Self {
            model,
            albedo,
            f0: f0.map(|f| S::of(f.clamp(0.0, 1.0))),
        }
    }
}

impl<M, R: Real, const N: usize> Turquin<M, R, N> {
    /// The fitted albedo `E(μ)`.
    pub fn albedo(&self) -> &AlbedoFit<R> {
        &self.albedo
    }

    /// The factor `1 + F0 (1 − E(μo))/E(μo)` per channel (`E` floored at `1e-30`).
    #[inline(always)]
    pub fn factor(&self, cos_theta_o: R) -> [R; N] {
        let e = self.albedo.eval(cos_theta_o);
        let s = (R::one() - e) / e.max(R::from_f64(1e-30));
        crate::real::channels(
            #[inline(always)]
            |c| self.f0[c].mul_add(s, R::one()),
        )
    }
}

impl<M: Splat, S: Scalar, const N: usize> Splat for Turquin<M, S, N> {
    const EXPLICIT_LANES: bool = M::EXPLICIT_LANES;
    type On<L: Real> = Turquin<M::On<L>, L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> Self::On<L> {
        Turquin {
            model: self.model.splat(),
            albedo: self.albedo.splat(),
            f0: splat_array(&self.f0),
        }
    }
}

/// The reciprocity note of [`Turquin`].
const TURQUIN_NOTE: &str = "the compensation factor depends on cos θo only";
/// The energy note of [`Turquin`].
const TURQUIN_NOTE_ENERGY: &str = "light side: ∫ f cos θo dωo reaches 1.94 at cos θi = 0.05 \
     (GGX α = 1, F = 1); view-side albedo ≤ E(μo) + F0 (1 − E(μo)) ≤ 1 when F ≤ 1";
/// The composition condition of [`Turquin`] (the wrapped model's own bound).
const TURQUIN_CONDITION: &str = "F ≤ 1 (view side)";

impl<M: Brdf<R, N>, R: Real, const N: usize> Brdf<R, N> for Turquin<M, R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let f = self.model.eval(wi, wo);
        let g = self.factor(wo.z);
        crate::real::channels(
            #[inline(always)]
            |c| f[c] * g[c],
        )
    }

    #[inline]
    fn properties(&self) -> Properties {
        let own = Properties {
            reciprocity: Reciprocity::NotReciprocal { note: TURQUIN_NOTE },
            energy: Energy::NotConserving {
                note: TURQUIN_NOTE_ENERGY,
            },
        };
        own.combine(self.model.properties(), TURQUIN_CONDITION)
    }

    /// The wrapped model's (the factor is smooth).
    #[inline]
    fn kinks(&self, wo: Vec3<f64>) -> Kinks {
        self.model.kinks(wo)
    }
}

/// The wrapped model's sampler: same directions and density, `f` and the weight scaled by
/// the factor at `wo`; the albedo estimate is the wrapped one times the factor's channel
/// mean.
impl<M: SampleBrdf<R, N>, R: Real, const N: usize> SampleBrdf<R, N> for Turquin<M, R, N> {
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let s = self.model.sample(wo, u);
        let g = self.factor(wo.z);
        Sample::new(
            s.wi,
            s.pdf,
            crate::real::channels(
                #[inline(always)]
                |c| s.f[c] * g[c],
            ),
            crate::real::channels(
                #[inline(always)]
                |c| s.weight[c] * g[c],
            ),
            s.valid,
        )
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        self.model.pdf(wo, wi)
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        self.model.albedo_estimate(wo) * mean(self.factor(wo.z))
    }
}

// ---------------------------------------------------------------------------------------------

/// The file descriptions of [`KullaConty`] and [`Turquin`] over a runtime Cook-Torrance
/// (`model = "kulla_conty"` / `"turquin"`), re-exported from [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use serde::{Deserialize, Serialize};

    use super::{KullaConty, Turquin};
    use crate::Scalar;
    use crate::masking::SmithHeightCorrelated;
    use crate::material::{
        FresnelDesc, Material, MaterialError, ModelDesc, NdfDesc, build_fresnel, invalid,
    };
    use crate::models::CookTorrance;

    crate::material::field_fns!(ndf, alpha, fresnel);

    /// [`KullaConty`] over a Cook-Torrance lobe with height-correlated Smith masking (the
    /// masking the albedo fit assumes): `ndf` (`ggx` or `beckmann`), an isotropic
    /// `alpha ∈ [1e-4, 1]` and a `fresnel`. Building interpolates `E(μ)` for `alpha` from the
    /// shipped table ([`AlbedoFit::new`](crate::models::AlbedoFit::new), microseconds).
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `kulla_conty`")]
    pub struct KullaContyDesc {
        /// The distribution.
        #[serde(deserialize_with = "field::ndf")]
        pub ndf: NdfDesc,
        /// Isotropic slope parameter.
        #[serde(deserialize_with = "field::alpha")]
        pub alpha: f64,
        /// The Fresnel term.
        #[serde(deserialize_with = "field::fresnel")]
        pub fresnel: FresnelDesc,
    }

    /// [`Turquin`] over a Cook-Torrance lobe with height-correlated Smith masking, with the
    /// fields of [`KullaContyDesc`] (`model = "turquin"`).
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `turquin`")]
    pub struct TurquinDesc {
        /// The distribution.
        #[serde(deserialize_with = "field::ndf")]
        pub ndf: NdfDesc,
        /// Isotropic slope parameter.
        #[serde(deserialize_with = "field::alpha")]
        pub alpha: f64,
        /// The Fresnel term.
        #[serde(deserialize_with = "field::fresnel")]
        pub fresnel: FresnelDesc,
    }

    /// The wrapped lobe of either description.
    type Lobe<S> = CookTorrance<
        S,
        crate::ndf::AnyNdf<S>,
        crate::fresnel::AnyFresnel<S>,
        SmithHeightCorrelated,
    >;

    fn lobe<S: Scalar>(
        name: &'static str,
        ndf: NdfDesc,
        alpha: f64,
        fresnel: &FresnelDesc,
    ) -> Result<Lobe<S>, MaterialError> {
        let ndf = ndf.build((alpha, alpha), true).map_err(invalid(name))?;
        let fresnel = build_fresnel(fresnel).map_err(invalid(name))?;
        Ok(CookTorrance::new(ndf, fresnel, SmithHeightCorrelated))
    }

    impl ModelDesc for KullaContyDesc {
        const NAME: &'static str = "kulla_conty";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let ct = lobe::<S>(Self::NAME, self.ndf, self.alpha, &self.fresnel)?;
            Ok(KullaConty::new(ct).map_err(invalid(Self::NAME))?.into())
        }
    }

    impl ModelDesc for TurquinDesc {
        const NAME: &'static str = "turquin";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let ct = lobe::<S>(Self::NAME, self.ndf, self.alpha, &self.fresnel)?;
            Ok(Turquin::new(ct).map_err(invalid(Self::NAME))?.into())
        }
    }
}
