//! Importance sampling: draw `wi` given `wo`, with the density a renderer can trust.
//!
//! # Conventions
//!
//! * `wo` is **given** (towards the viewer, or the previous path vertex), `wi` is **drawn**
//!   (towards the light to be gathered). Both in the local frame (z = normal), unit length,
//!   pointing away from the surface — the crate's conventions.
//! * `pdf` is a density **per unit solid angle** of `wi` (sr⁻¹), not per projected solid angle.
//! * [`Sample::f`] is `f(wi, wo)` without the cosine; [`Sample::weight`] is
//!   `f(wi, wo)·cos θi / pdf(wi)` — what a path tracer multiplies its throughput by. Models
//!   compute it in its simplified closed form where one exists (Lambert: the albedo; a Smith
//!   microfacet model sampled by visible normals: `F·G2/G1(wo)`), never as a ratio of two tiny
//!   numbers.
//! * An invalid sample (`wo` below the horizon, `wi` drawn below it, zero density) has
//!   [`Sample::valid`] unset, and `pdf = 0`, `f = 0`, `weight = 0`: never NaN.
//! * [`SampleBrdf::pdf`]`(wo, wi)` is exactly the density [`SampleBrdf::sample`] draws from,
//!   from the same formula body; it is `0` where `wi.z ≤ 0` or `wo.z ≤ 0`.
//! * `u = [u0, u1, u2] ∈ [0, 1)³` are uniform numbers. Single-lobe models use `u0, u1`;
//!   mixtures choose their lobe with `u2` (and leave `u0, u1` untouched, so stratification of
//!   the first two dimensions carries over to the chosen lobe).
//!
//! The microfacet conventions (to compare with pbrt-v4 and Mitsuba 3): the visible-normal
//! density is `D_wo(wm) = G1(wo)·max(0, wo·wm)·D(wm) / cos θo` (Heitz 2014, eq. 2), and a
//! reflection maps a normal density to a direction density with the Jacobian
//! `|∂wm/∂wi| = 1 / (4 |wo·wm|)` (Walter et al. 2007, eq. 14). The microfacet samplers
//! (visible normals, spherical caps, bounded VNDF, `D cos θm`) and [`SampleBrdf`] for
//! [`CookTorrance`](crate::models::CookTorrance) are in [`microfacet`].
//!
//! Everything is generic over [`Real`]: one sample on `f32`/`f64`, one per lane on SIMD types,
//! branch-free.
//!
//! References: E. Veach, *Robust Monte Carlo Methods for Light Transport Simulation*, doctoral
//! thesis, Stanford, 1997 (one-sample mixture densities, §9.2.4); M. Pharr, W. Jakob,
//! G. Humphreys, *Physically Based Rendering*, 4th ed., 2023, §9.

pub(crate) mod lobes;
pub mod microfacet;
pub use microfacet::{
    Auto, BoundedVisibleNormals, FullDistribution, NormalSampler, SampleNdf, Sampled,
    SphericalCaps, VisibleNormals, erf_inv,
};

use crate::models::{Brdf, masked};
use crate::{Real, Vec3};
use core::fmt;

/// One sampled direction and what a path tracer needs from it.
///
/// Invalid lanes (see [`valid`](Sample::valid)) have `pdf`, `f` and `weight` equal to `0`
/// and a finite `wi`.
#[derive(Clone, Copy)]
pub struct Sample<R: Real, const N: usize> {
    /// The drawn direction (unit, local frame, pointing away from the surface).
    pub wi: Vec3<R>,
    /// Density of `wi` per unit solid angle (sr⁻¹); `0` on invalid lanes.
    pub pdf: R,
    /// `f(wi, wo)` per channel (sr⁻¹, without the cosine).
    pub f: [R; N],
    /// `f(wi, wo)·cos θi / pdf` per channel (dimensionless).
    pub weight: [R; N],
    /// Lanes where the sample is valid: `wo` and `wi` above the horizon and `pdf > 0`.
    pub valid: R::Mask,
}

impl<R: Real, const N: usize> fmt::Debug for Sample<R, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Sample")
            .field("wi", &self.wi)
            .field("pdf", &self.pdf)
            .field("f", &self.f)
            .field("weight", &self.weight)
            .finish_non_exhaustive()
    }
}

impl<R: Real, const N: usize> Sample<R, N> {
    /// Assembles a sample, zeroing `pdf`, `f` and `weight` where `valid` is unset, and where
    /// `pdf ≤ 0` or `wi.z ≤ 0` (so callers need not repeat those tests). `wi` is replaced by
    /// the normal on invalid lanes (a finite direction).
    #[inline(always)]
    #[must_use]
    pub fn new(wi: Vec3<R>, pdf: R, f: [R; N], weight: [R; N], valid: R::Mask) -> Self {
        let valid = valid & pdf.gt(R::zero()) & wi.z.gt(R::zero());
        let n = Vec3::new(R::zero(), R::zero(), R::one());
        Self {
            wi: crate::models::select_vec(valid, wi, n),
            pdf: R::select(valid, pdf, R::zero()),
            f: masked(valid, f),
            weight: masked(valid, weight),
            valid,
        }
    }
}

/// A [`Brdf`] that can be importance sampled (see the [module docs](self) for the
/// conventions).
pub trait SampleBrdf<R: Real, const N: usize>: Brdf<R, N> {
    /// Draws `wi` given `wo` from the uniform numbers `u ∈ [0, 1)³`.
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N>;

    /// The density (per unit solid angle) with which [`sample`](SampleBrdf::sample) draws `wi`
    /// given `wo`; `0` if either is below the horizon.
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R;

    /// A cheap estimate of the directional albedo `ρ(wo) = ∫ f(wi, wo) cos θi dωi` (mean over
    /// the channels), with which the mixtures ([`Sum`](crate::models::Sum),
    /// [`Layered`](crate::models::Layered), the runtime `Sum` of
    /// [`Material`](crate::material::Material)) choose a part: part `a` is drawn with
    /// probability `ρ̂_a/(ρ̂_a + ρ̂_b)`. Only ratios matter, and any finite value `≥ 0` keeps the
    /// mixture unbiased as long as it is `> 0` wherever the model is not zero; a good estimate
    /// only lowers the variance.
    ///
    /// Default: `1`. The crate's models return their reflectance parameters (each model's
    /// sampling documentation says which; the diffuse models the channel mean of their albedo
    /// at normal incidence: `ρ` for `Lambert`, `ρA` for the Oren-Nayar models, `(1 − R0) ρd`
    /// for `ShirleyDiffuse`, `R_d (1 − R_s F0)` for `CoupledLambert`).
    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        let _ = wo;
        R::one()
    }

    /// The model's own batch sampling, which [`crate::batch::sample_with`] (and
    /// [`sample`](crate::batch::sample)) try first: it draws one sample per `wo[j]` from
    /// `(u[0][j], u[1][j], u[2][j])` with instruction set `isa`, writes it to `out` as
    /// `sample_with` does and returns `true`, or returns `false` without writing, and the
    /// entry point runs its own loops. The batch path calls it on the `f32` model, having
    /// checked that `isa` is available and that every slice has the same length; it is a safe
    /// method, so an implementation that runs `#[target_feature]` code must not rely on that
    /// (`Material`'s returns `false` for an unavailable `isa`).
    ///
    /// The default returns `false`. A wrapper that changes the samples (another sampler, a
    /// compensation lobe) must not forward it. The counterpart of
    /// [`Brdf::eval_batch`], with the same purpose: a material chosen
    /// at run time ([`crate::material::Material`]) matches on its variant **once per batch**
    /// and hands the concrete model to [`crate::batch::sample_with`], instead of matching on
    /// every sample out of line (README, Performance).
    #[inline]
    #[must_use]
    fn sample_batch(
        &self,
        isa: crate::batch::Isa,
        wo: crate::batch::Directions<'_>,
        u: [&[f32]; 3],
        out: &mut crate::batch::SampleOut<'_, N>,
    ) -> bool {
        let _ = (isa, wo, u, out);
        false
    }

    /// The model's own batch densities, which [`crate::batch::pdf_with`] (and
    /// [`pdf`](crate::batch::pdf)) try first: it writes `pdf(wo[j], wi[j])` to `out[j]` with
    /// instruction set `isa`, as `pdf_with` does, and returns `true`, or returns `false`
    /// without writing. Called on the `f32` model after the entry point checked `isa` and the
    /// lengths; a safe method, as [`SampleBrdf::sample_batch`] (whose rules it follows: a
    /// wrapper that changes the density must not forward it).
    ///
    /// The default returns `false`. [`crate::material::Material`] overrides it: a model
    /// through its batch kernels, a `Sum` or `Layered` material by its parts' batches. A hook
    /// for the entry points: to compute densities, call [`crate::batch::pdf_with`], which
    /// runs any model (this returns `false` for most, leaving `out` unwritten).
    #[inline]
    #[must_use]
    fn pdf_batch(
        &self,
        isa: crate::batch::Isa,
        wo: crate::batch::Directions<'_>,
        wi: crate::batch::Directions<'_>,
        out: &mut [f32],
    ) -> bool {
        let _ = (isa, wo, wi, out);
        false
    }
}

/// Warps `(u1, u2) ∈ [0, 1]²` to the upper hemisphere with density `cos θ / π`.
///
/// ```text
/// sin θ = √u1,  cos θ = √(1 − u1),  φ = 2π u2,  pdf = cos θ / π
/// ```
///
/// `(cos φ, sin φ)` by [`crate::fast::sin_cos_2pi`] (polynomial, ≤ ≤ 1.72 ULP in `f32`, no library
/// call: the warp vectorizes in the batch kernels).
/// (Malley's method in its polar form: a uniform disk sample lifted to the hemisphere.)
/// `u1 = 1` gives a horizon direction, `u1 = 0` the normal. Reference: M. Pharr, W. Jakob,
/// G. Humphreys, *Physically Based Rendering*, 4th ed., 2023, §A.5.3.
#[inline]
#[must_use]
pub fn cosine_hemisphere<R: Real>(u1: R, u2: R) -> Vec3<R> {
    let r = u1.safe_sqrt();
    let z = (R::one() - u1).safe_sqrt();
    let (sin_phi, cos_phi) = crate::fast::sin_cos_2pi(u2);
    Vec3::new(r * cos_phi, r * sin_phi, z)
}

/// Cosine-weighted hemisphere density `max(0, cos θ) / π` of the warp
/// [`cosine_hemisphere`].
#[inline(always)]
#[must_use]
pub fn cosine_hemisphere_pdf<R: Real>(w: Vec3<R>) -> R {
    w.z.max(R::zero()) * R::frac_1_pi()
}

/// Samples a model by the cosine-weighted hemisphere (`pdf = cos θi / π`, so
/// `weight = π f`): the exact strategy for [`Lambert`](crate::models::Lambert), and the
/// one the other diffuse models use.
#[inline(always)]
#[must_use]
pub fn sample_cosine<R: Real, const N: usize, B: Brdf<R, N> + ?Sized>(
    model: &B,
    wo: Vec3<R>,
    u: [R; 3],
) -> Sample<R, N> {
    let wi = cosine_hemisphere(u[0], u[1]);
    let pdf = cosine_hemisphere_pdf(wi);
    let f = model.eval(wi, wo);
    let weight = crate::real::channels(
        #[inline(always)]
        |c| f[c] * R::pi(),
    );
    Sample::new(wi, pdf, f, weight, wo.z.gt(R::zero()))
}

/// The density of [`sample_cosine`]: `cos θi / π` where `wo.z > 0`, else `0`.
#[inline(always)]
#[must_use]
pub fn pdf_cosine<R: Real>(wo: Vec3<R>, wi: Vec3<R>) -> R {
    R::select(wo.z.gt(R::zero()), cosine_hemisphere_pdf(wi), R::zero())
}

/// Implements [`SampleBrdf`] by cosine-weighted sampling for diffuse models.
/// [`SampleBrdf::albedo_estimate`] is each model's `pub(crate) fn estimate` (the mean of its
/// albedo parameter, see there).
macro_rules! cosine_sampled {
    ($($model:ident),*) => {$(
        impl<R: Real, const N: usize> SampleBrdf<R, N> for crate::models::$model<R, N> {
            #[inline(always)]
            fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
                sample_cosine(self, wo, u)
            }
            #[inline(always)]
            fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
                pdf_cosine(wo, wi)
            }
            #[inline(always)]
            fn albedo_estimate(&self, _wo: Vec3<R>) -> R {
                self.estimate()
            }
        }
    )*};
}

cosine_sampled!(
    Lambert,
    OrenNayar,
    OrenNayarFujii,
    ShirleyDiffuse,
    CoupledLambert
);
