//! Importance sampling of microfacet normals, and of the [`CookTorrance`] models built on
//! them.
//!
//! A [`NormalSampler`] is a *strategy* (a zero-sized type) that draws a microfacet normal
//! `wm` for a given `wo` from two uniform numbers and reports the density `pdf_wm` of `wm`
//! per unit solid angle of normals. A microfacet model reflects it,
//!
//! ```text
//! wi = 2 (wo·wm) wm − wo,        pdf(wi) = pdf_wm(wm) / (4 |wo·wm|)      (Walter et al. 2007, eq. 14)
//! ```
//!
//! | strategy | NDFs | `pdf_wm(wm)` |
//! |---|---|---|
//! | [`VisibleNormals`] (Heitz 2018) | [`Ggx`], [`GgxIsotropic`], [`Beckmann`] (Heitz & d'Eon 2014) | `G1(wo)·max(0, wo·wm)·D(wm) / cos θo` |
//! | [`SphericalCaps`] (Dupuy & Benyoub 2023) | [`Ggx`], [`GgxIsotropic`] | the same (same distribution, cheaper warp) |
//! | [`BoundedVisibleNormals`] (Eto & Tokuyoshi 2023) | [`Ggx`], [`GgxIsotropic`] | `2·max(0, wo·wm)·D(wm) / (t + k cos θo)` (see the type) |
//! | [`FullDistribution`] | every NDF of [`crate::ndf`] | `D(wm)·cos θm` |
//!
//! [`SampleNdf`] names each NDF's default strategy (the fastest correct one: spherical caps
//! for GGX, visible normals for Beckmann, `D cos θm` for Blinn-Phong and Ashikhmin-Shirley),
//! [`Auto`] is the strategy that forwards to it, and [`SampleBrdf`] for [`CookTorrance`] uses
//! it. To pick another strategy without paying for the others, wrap the model:
//! [`CookTorrance::sampled_with`] returns a [`Sampled`] whose [`SampleBrdf`] uses the chosen
//! strategy (and whose [`Brdf`] is the model's).
//!
//! **Weights.** For the visible-normal strategies the weight `f·cos θi/pdf` has a closed
//! form free of `D` and of the Jacobian: `F·G2/G1(wo)` (VNDF; Heitz 2018, §1) and
//! `F·G2·(t + k cos θo)/(2 cos θo)` (bounded VNDF), with `G2` the model's own masking term
//! and `G1` the NDF's Smith masking. Those are what [`Sample::weight`] holds; the other
//! strategies return `f·cos θi/pdf`.
//!
//! **Domain.** `wo.z > 0` (else the sample is invalid); `u ∈ [0, 1)²` (the end points `0` and
//! `1 − ε` give finite results); every parameter domain of [`crate::ndf`] (tested finite at
//! its ends). Everything is branch-free and generic over [`Real`].
//!
//! References:
//! * E. Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), 2018.
//! * J. Dupuy, A. Benyoub, "Sampling Visible GGX Normals with Spherical Caps", CGF 42(8)
//!   (HPG), 2023.
//! * K. Eto, Y. Tokuyoshi, "Bounded VNDF Sampling for Smith–GGX Reflections", SIGGRAPH Asia
//!   2023 Technical Communications.
//! * E. Heitz, E. d'Eon, "Importance Sampling Microfacet-Based BSDFs using the Distribution
//!   of Visible Normals", EGSR 2014; W. Jakob, "An Improved Visible Normal Sampling Routine
//!   for the Beckmann Distribution", tech. report, 2014.
//! * B. Walter, S. Marschner, H. Li, K. Torrance, "Microfacet Models for Refraction through
//!   Rough Surfaces", EGSR 2007.
//! * M. Ashikhmin, P. Shirley, "An Anisotropic Phong BRDF Model", JGT 5(2), 2000.
//! * M. Giles, "Approximating the erfinv function", GPU Computing Gems Jade Edition, 2011.

use core::marker::PhantomData;

use super::{Sample, SampleBrdf};
use crate::fast::SqrtFn;
use crate::fresnel::FresnelTerm;
use crate::masking::Masking;
use crate::models::{Brdf, CookTorrance, Kinks, Properties};
use crate::ndf::{
    AnyNdf, AshikhminShirleyLobe, Beckmann, BlinnPhong, Ggx, GgxIsotropic, Ndf, SmithLambda, erfc,
};
use crate::{Real, Vec3};

/// A floor for denominators, far below any valid value (keeps `x/0` out at the horizon).
#[inline(always)]
fn tiny<R: Real>() -> R {
    R::from_f64(1e-30)
}

/// A strategy for drawing microfacet normals of the NDF `D` given `wo` (see the
/// [module docs](self)).
///
/// Implementations are zero-sized types; the NDF is passed in.
pub trait NormalSampler<R: Real, D: Ndf<R>> {
    /// Draws a unit normal `wm` (upper hemisphere) given `wo` (unit, `wo.z > 0`) from
    /// `u ∈ [0, 1)²`. Finite for every `u ∈ [0, 1]²` and every `wo`.
    fn sample_wm(ndf: &D, wo: Vec3<R>, u: [R; 2]) -> Vec3<R>;

    /// The density of [`sample_wm`](NormalSampler::sample_wm) per unit solid angle of `wm`,
    /// `0` where `wo.z ≤ 0` or `wm` cannot be drawn.
    fn pdf_wm(ndf: &D, wo: Vec3<R>, wm: Vec3<R>) -> R;

    /// `Some(c)` if the strategy's weight has the closed form `f·cos θi/pdf = F·G2·c`, in
    /// which `D` cancels (`c = 1/G1(wo)` for visible normals, `(wo·wm)/(cos θo cos θm)` for
    /// `D cos θm`), given `wo` and the drawn normal `wm`; `None` if the weight is computed as
    /// `f·cos θi/pdf`. The choice is per type, not per lane.
    ///
    /// The closed form is also the accurate one: `f` evaluates `D` at the half vector
    /// rebuilt from `wi + wo`, `pdf` at the drawn `wm`; they differ by the rounding of `wm`
    /// times the conditioning of `D` (of order `tan θm/α²`), 1e-4 relative in `f32` at
    /// `α = 3e-4`, and the ratio carries it, where `F·G2·c` does not.
    #[inline(always)]
    fn weight_scale(ndf: &D, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
        let _ = (ndf, wo, wm);
        None
    }
}

/// An NDF with a default sampling strategy ([`Auto`] forwards to it): the methods are those
/// of [`NormalSampler`], on `self`.
///
/// | NDF | default |
/// |---|---|
/// | [`Ggx`], [`GgxIsotropic`] | [`SphericalCaps`] |
/// | [`Beckmann`] | [`VisibleNormals`] |
/// | [`BlinnPhong`], [`AshikhminShirleyLobe`] | [`FullDistribution`] (`D cos θm`) |
/// | [`AnyNdf`] | the wrapped distribution's |
pub trait SampleNdf<R: Real>: Ndf<R> {
    /// See [`NormalSampler::sample_wm`].
    fn sample_wm(&self, wo: Vec3<R>, u: [R; 2]) -> Vec3<R>;
    /// See [`NormalSampler::pdf_wm`].
    fn pdf_wm(&self, wo: Vec3<R>, wm: Vec3<R>) -> R;
    /// See [`NormalSampler::weight_scale`].
    fn weight_scale(&self, wo: Vec3<R>, wm: Vec3<R>) -> Option<R>;
}

/// The default strategy of each NDF ([`SampleNdf`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Auto;

/// Visible-normal sampling: `pdf_wm = G1(wo)·max(0, wo·wm)·D(wm)/cos θo`, the distribution
/// of normals seen from `wo` (Heitz & d'Eon 2014, eq. 2).
///
/// * GGX: Heitz 2018 — stretch `wo` to the configuration `α = 1`, sample the projected
///   hemisphere of the truncated sphere (a disk, its far half compressed by
///   `(1 + cos θ)/2`), lift to the hemisphere and unstretch.
/// * Beckmann: Heitz & d'Eon 2014 / Jakob 2014 — stretch to `α = 1`; the slope along the
///   projected `wo` has the CDF `C(x) = cos θ (√π/2)(1 + erf x) + sin θ e^(−x²)/2`
///   (`x ≤ cot θ`), inverted in `c = 1 + erf x` from Jakob's initial guess by three
///   bracketed Newton steps, the CDF's Taylor expansion at the rim (within 1e-7 of the CDF
///   in f64, 1e-6 in f32, tested); the orthogonal slope is Gaussian, `erf⁻¹(2u − 1)` by
///   Giles' approximation (relative 1.2e-7 in `erf`); both clamped to `[−6, 6]`.
///
/// Weight: `F·G2/G1(wo)`. No sample is rejected by the strategy, but reflected directions
/// fall below the horizon with a probability that grows with `α` and `θo` (about 50 % at
/// `α = 1`, normal incidence, for GGX): see [`BoundedVisibleNormals`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VisibleNormals;

/// Visible-normal sampling of GGX by spherical caps (Dupuy & Benyoub 2023): the same
/// distribution and density as [`VisibleNormals`], drawn by a cheaper warp.
///
/// In the stretched configuration (`α = 1`, `v` the stretched unit `wo`), the visible
/// normals are `normalize(c + v)` for `c` uniform on the spherical cap `z ∈ [−v.z, 1]`:
/// `φ = 2π u0`, `z = (1 − u1)(1 + v.z) − v.z`; unstretch and normalize. Weight
/// `F·G2/G1(wo)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SphericalCaps;

/// Bounded visible-normal sampling of GGX reflections (Eto & Tokuyoshi 2023): the spherical
/// cap of [`SphericalCaps`] shrunk to `z ∈ [−k·v.z, 1]`, which removes only normals whose
/// reflection lies below the horizon, so fewer samples are wasted (none at normal
/// incidence) and the estimator stays unbiased.
///
/// ```text
/// k = (1 − a²) s² / (s² + a² cos²θo),   s = 1 + sin θo,   a = min(αx, αy)
/// t = √(αx² wo.x² + αy² wo.y² + wo.z²)
/// ```
///
/// **Density (derived).** Samples are uniform on the smaller cap, of area `2π(1 + k v.z)`
/// instead of `2π(1 + v.z)`, so on the kept region the density is the VNDF's times
/// `(1 + v.z)/(1 + k v.z) = (t + cos θo)/(t + k cos θo)` (with `v.z = cos θo/t`). As the VNDF
/// reflected density is `D·G1(wo)/(4 cos θo) = D/(2(cos θo + t))` for GGX,
///
/// ```text
/// pdf(wi) = D(wm) / (2 (t + k cos θo)),      pdf_wm = 2 max(0, wo·wm) D(wm) / (t + k cos θo)
/// weight  = F·G2·(t + k cos θo) / (2 cos θo)
/// ```
///
/// `pdf_wm` is exact for every `wm` whose reflection is above the horizon (the others have
/// density 0 but are reported with the formula; the reflected [`SampleBrdf::pdf`] is 0 there).
/// For anisotropic GGX the bound uses the smaller `α`, which is conservative.
/// At `α = 1` and normal incidence `k = 0`: no sample is lost (plain VNDF: 50 %).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BoundedVisibleNormals;

/// Sampling the full distribution of normals, `pdf_wm = D(wm) cos θm` (independent of
/// `wo`), for comparison with the visible-normal strategies, and the default for the
/// Blinn-Phong and Ashikhmin-Shirley NDFs.
///
/// * GGX: slopes `√(u0/(1 − u0)) (αx cos φ, αy sin φ)`, `φ = 2π u1`, written as
///   `wm ∝ (αx √u0 cos φ, αy √u0 sin φ, √(1 − u0))` (Walter et al. 2007, eq. 35–36).
/// * Beckmann: slopes `√(−ln(1 − u0)) (αx cos φ, αy sin φ)` (Walter et al. 2007, eq. 28–29).
/// * Blinn-Phong: `cos θm = (1 − u0)^(1/(s + 2))`, `φ = 2π u1`.
/// * Ashikhmin-Shirley: the marginal of `φ` is `∝ 1/(e(φ) + 2)`, whose inverse CDF in each
///   quadrant is `φ = atan(√((nu + 2)/(nv + 2)) tan(π u'/2))` — evaluated without `atan` as
///   `(cos φ, sin φ) = normalize(√(nv + 2) cos(π u'/2), √(nu + 2) sin(π u'/2))`; then
///   `cos θm = (1 − u1)^(1/(e + 2))`, `e = nu cos²φ + nv sin²φ`. (Ashikhmin & Shirley 2000
///   sample their cosine-free half-vector density the same way with `+1` for `+2`.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FullDistribution;

impl<R: Real, D: SampleNdf<R>> NormalSampler<R, D> for Auto {
    #[inline(always)]
    fn sample_wm(ndf: &D, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
        ndf.sample_wm(wo, u)
    }
    #[inline(always)]
    fn pdf_wm(ndf: &D, wo: Vec3<R>, wm: Vec3<R>) -> R {
        ndf.pdf_wm(wo, wm)
    }
    #[inline(always)]
    fn weight_scale(ndf: &D, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
        ndf.weight_scale(wo, wm)
    }
}

// ---------------------------------------------------------------------------------------------
// Shared warps
// ---------------------------------------------------------------------------------------------

/// `normalize(ax w.x, ay w.y, w.z)`: `wo` in the stretched configuration `α = 1`.
#[inline(always)]
fn stretch<R: Real>(ax: R, ay: R, w: Vec3<R>) -> Vec3<R> {
    Vec3::new(ax * w.x, ay * w.y, w.z).normalize_or_zero()
}

/// A normal `h` of the stretched configuration back to the surface's:
/// `normalize(ax h.x, ay h.y, max(h.z, 0))`, the normal at the pole for `h = 0`.
#[inline(always)]
fn unstretch<R: Real>(ax: R, ay: R, h: Vec3<R>) -> Vec3<R> {
    let m = Vec3::new(ax * h.x, ay * h.y, h.z.max(R::zero()));
    let len2 = m.length_squared();
    let ok = len2.gt(tiny());
    let inv = len2.max(tiny()).sqrt().recip();
    Vec3::new(
        R::select(ok, m.x * inv, R::zero()),
        R::select(ok, m.y * inv, R::zero()),
        R::select(ok, m.z * inv, R::one()),
    )
}

/// `(cos 2πu, sin 2πu)` by [`crate::fast::sin_cos_2pi`] (polynomial, no library call, so the
/// samplers vectorize in the batch kernels).
#[inline(always)]
fn cis<R: Real>(u: R) -> (R, R) {
    let (s, c) = crate::fast::sin_cos_2pi(u);
    (c, s)
}

/// Heitz 2018: GGX visible normal for `α = (ax, ay)`.
#[inline(always)]
fn ggx_vndf_heitz<R: Real>(ax: R, ay: R, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
    let v = stretch(ax, ay, wo);
    // Orthonormal basis (t1, t2, v), t1 horizontal; (1, 0, 0) at normal incidence.
    let len2 = v.x * v.x + v.y * v.y;
    let ok = len2.gt(tiny());
    let inv = len2.max(tiny()).sqrt().recip();
    let t1 = Vec3::new(
        R::select(ok, -v.y * inv, R::one()),
        R::select(ok, v.x * inv, R::zero()),
        R::zero(),
    );
    let t2 = v.cross(t1);
    // Uniform point on the unit disk, its far half (p2 < 0 side seen from v) compressed.
    let r = u[0].sqrt();
    let (c, s) = cis(u[1]);
    let p1 = r * c;
    let half = R::from_f64(0.5) * (R::one() + v.z);
    let edge = (R::one() - p1 * p1).max(R::zero()).sqrt();
    let p2 = (R::one() - half) * edge + half * (r * s);
    let p3 = (R::one() - p1 * p1 - p2 * p2).max(R::zero()).sqrt();
    let h = t1.scale(p1) + t2.scale(p2) + v.scale(p3);
    unstretch(ax, ay, h)
}

/// Dupuy & Benyoub 2023: `normalize(c + v)` for `c` uniform on the cap `z ∈ [−b, 1]`
/// (`b = v.z`: all visible normals; `b = k v.z`: the bounded cap of Eto & Tokuyoshi).
#[inline(always)]
fn ggx_cap<R: Real>(ax: R, ay: R, v: Vec3<R>, b: R, u: [R; 2]) -> Vec3<R> {
    let (c, s) = cis(u[0]);
    let z = (R::one() - u[1]).mul_add(R::one() + b, -b);
    let sin = (R::one() - z * z).max(R::zero()).sqrt();
    let h = Vec3::new(sin * c + v.x, sin * s + v.y, z + v.z);
    unstretch(ax, ay, h)
}

/// Eto & Tokuyoshi's `k` (see [`BoundedVisibleNormals`]).
#[inline(always)]
fn bounded_k<R: Real>(ax: R, ay: R, wo: Vec3<R>) -> R {
    let a = ax.min(ay).min(R::one());
    let a2 = a * a;
    let s = R::one() + (wo.x * wo.x + wo.y * wo.y).sqrt();
    let s2 = s * s;
    (R::one() - a2) * s2 / a2.mul_add(wo.z * wo.z, s2)
}

/// `t = √(αx² wo.x² + αy² wo.y² + wo.z²)`.
#[inline(always)]
fn stretched_len<R: Real>(ax: R, ay: R, wo: Vec3<R>) -> R {
    let (x, y) = (ax * wo.x, ay * wo.y);
    (x * x + y * y + wo.z * wo.z).sqrt()
}

/// The visible-normal density `G1(wo)·max(0, wo·wm)·D(wm)/cos θo`, written with
/// `cos θo/G1(wo) = separable_den(wo)` so it stays finite at grazing `wo`.
#[inline(always)]
fn vndf_pdf<R: Real, D: SmithLambda<R>>(ndf: &D, wo: Vec3<R>, wm: Vec3<R>) -> R {
    let p = wo.dot(wm).max(R::zero()) * ndf.d(wm) / ndf.separable_den(wo).max(tiny());
    R::select(wo.z.gt(R::zero()), p, R::zero())
}

/// `1/G1(wo) = separable_den(wo)/cos θo`.
#[inline(always)]
fn inv_g1<R: Real, D: SmithLambda<R>>(ndf: &D, wo: Vec3<R>) -> R {
    ndf.separable_den(wo) / wo.z.max(tiny())
}

/// `D(wm) cos θm`.
#[inline(always)]
fn full_pdf<R: Real, D: Ndf<R>>(ndf: &D, wm: Vec3<R>) -> R {
    ndf.d(wm) * wm.z.max(R::zero())
}

/// The weight scale of `D cos θm` sampling: with `pdf = D cos θm/(4 wo·wm)` and
/// `f = D F G2/(4 cos θi cos θo)`, `f cos θi/pdf = F G2 (wo·wm)/(cos θo cos θm)`.
#[inline(always)]
fn full_weight_scale<R: Real>(wo: Vec3<R>, wm: Vec3<R>) -> R {
    wo.dot(wm).max(R::zero()) / (wo.z * wm.z).max(tiny())
}

/// `eᵗ − 1` without cancellation for small `t` (Kahan's trick: `(eᵗ − 1)·t / ln eᵗ`, exact
/// to a few ulps because the rounding errors of `eᵗ` cancel in the ratio; `t` where `eᵗ`
/// rounds to 1).
#[inline(always)]
fn expm1<R: Real>(t: R) -> R {
    let e = t.exp();
    let l = e.ln();
    let r = (e - R::one()) * t / R::select(l.eq(R::zero()), R::one(), l);
    R::select(e.eq(R::one()), t, r)
}

/// A normal with `cos θ = (1 − u)^(1/n)` and azimuth `(c, s)`: `cos θ = exp(ln(1 − u)/n)`,
/// `sin²θ = −expm1(2 ln(1 − u)/n)` (no cancellation in `1 − cos²θ` for sharp lobes).
#[inline(always)]
fn power_lobe<R: Real>(u: R, n: R, c: R, s: R) -> Vec3<R> {
    let t = (R::one() - u).max(tiny()).ln() / n;
    let z = t.exp();
    let sin = (-expm1(t + t)).max(R::zero()).sqrt();
    Vec3::new(sin * c, sin * s, z)
}

/// Full-distribution GGX normal.
#[inline(always)]
fn ggx_full<R: Real>(ax: R, ay: R, u: [R; 2]) -> Vec3<R> {
    let r = u[0].sqrt();
    let (c, s) = cis(u[1]);
    let z = (R::one() - u[0]).max(R::zero()).sqrt();
    unstretch(R::one(), R::one(), Vec3::new(ax * r * c, ay * r * s, z))
}

/// Full-distribution Beckmann normal.
#[inline(always)]
fn beckmann_full<R: Real>(ax: R, ay: R, u: [R; 2]) -> Vec3<R> {
    let r = (-(R::one() - u[0]).max(tiny()).ln()).max(R::zero()).sqrt();
    let (c, s) = cis(u[1]);
    unstretch(
        R::one(),
        R::one(),
        Vec3::new(ax * r * c, ay * r * s, R::one()),
    )
}

// ---------------------------------------------------------------------------------------------
// Inverse error function and the Beckmann visible slopes
// ---------------------------------------------------------------------------------------------

/// Inverse error function `erf⁻¹(y)`, `y ∈ [−1, 1]`, on lanes.
///
/// ```text
/// w = −ln((1 − y)(1 + y))
/// x₀ = y·P₁(w − 2.5)        (w < 5)       x₀ = y·P₂(√w − 3)      (w ≥ 5)
/// ```
///
/// `P₁, P₂` are Giles' single-precision polynomials (degree 8), fitted for
/// `1 − |y| ≥ 10⁻⁷`; beyond (`L = −ln(1 − |y|) ≥ 16`, reachable in f64) the start is the
/// asymptote of `erfc`, `x₀ = √(L − ln(π L)/2)`. Then three Newton steps on `|x|` against the
/// crate's [`erf`](crate::ndf::erf) (`|y| < 1/2`) or on `ln erfc(|x|) = ln(1 − |y|)` (the
/// tails, where `erf(x) − y` would cancel and `erfc` is too convex for Newton), so
/// `erf(erf_inv(y)) = y` to the accuracy of those functions (relative 1.2e-7; tested down to
/// `1 − |y| = 10⁻²⁵`, `tests/sampling_microfacet.rs`). `1 − |y|` is floored at 1e-30, so
/// `erf_inv(±1) ≈ ±8.1` (`erfc⁻¹(10⁻³⁰)`) is finite instead of `±∞`.
///
/// Reference: M. Giles, "Approximating the erfinv function", GPU Computing Gems Jade
/// Edition, 2011.
#[inline]
#[must_use]
pub fn erf_inv<R: Real>(y: R) -> R {
    let one = R::one();
    let parts = ErfInvArg {
        y,
        one_plus: one + y,
        one_minus: one - y,
    };
    erf_inv_refined(parts, erf_inv_giles(parts))
}

/// The argument of an inverse error function as `y`, `1 + y` and `1 − y`, each rounded
/// once: a caller that knows `1 + y` exactly (the Beckmann sampler's `c = erfc(−x)`) keeps
/// its relative precision near `y = −1`, which `1 + y` formed from `y` would lose.
#[derive(Clone, Copy)]
struct ErfInvArg<R> {
    y: R,
    one_plus: R,
    one_minus: R,
}

/// Giles' single-precision approximation of `erf⁻¹` (see [`erf_inv`]): `erf` of it is within
/// 1.2e-7 of `y` relative while `(1 − y)(1 + y) ≥ 6e-8` (`|x| ≤ 3.83`, measured against
/// f64 `erf`), the range the polynomials were fitted on; beyond it the tail polynomial
/// diverges.
#[inline(always)]
fn erf_inv_giles<R: Real>(a: ErfInvArg<R>) -> R {
    let w = -(a.one_minus * a.one_plus).max(tiny()).ln();
    // A function, not a closure: a closure may stay out of line, outside the features of
    // the batch kernel that inlines this body (every lane operation a call).
    #[inline(always)]
    fn horner<R: Real>(c: &[f64], t: R) -> R {
        let mut p = R::from_f64(c[0]);
        for &k in &c[1..] {
            p = p.mul_add(t, R::from_f64(k));
        }
        p
    }
    const P1: [f64; 9] = [
        2.810_226_36e-08,
        3.432_739_39e-07,
        -3.523_387_7e-06,
        -4.391_506_54e-06,
        0.000_218_580_87,
        -0.001_253_725_03,
        -0.004_177_681_64,
        0.246_640_727,
        1.501_409_41,
    ];
    const P2: [f64; 9] = [
        -0.000_200_214_257,
        0.000_100_950_558,
        0.001_349_343_22,
        -0.003_673_428_44,
        0.005_739_507_73,
        -0.007_622_461_3,
        0.009_438_870_47,
        1.001_674_06,
        2.832_976_82,
    ];
    let small = w.lt(R::from_f64(5.0));
    let p1 = horner(&P1, w - R::from_f64(2.5));
    let p2 = horner(&P2, w.max(R::zero()).sqrt() - R::from_f64(3.0));
    R::select(small, p1, p2) * a.y
}

/// Three Newton steps from `x0` towards `erf⁻¹(y)` (see [`erf_inv`]).
#[inline(always)]
fn erf_inv_refined<R: Real>(a: ErfInvArg<R>, x0: R) -> R {
    // Newton on |x|: on erf(a) = |y| in the middle, on ln erfc(a) = ln(1 − |y|) in the tails
    // (nearly linear there, where erfc itself is too convex for two steps).
    let two_over_sqrt_pi = R::from_f64(core::f64::consts::FRAC_2_SQRT_PI);
    let ay = a.y.abs();
    let mid = ay.lt(R::from_f64(0.5));
    let ln_t = a.one_plus.min(a.one_minus).max(tiny()).ln();
    // Beyond Giles' fitted range, erfc's asymptote e^(−x²)/(x√π) = 1 − |y| as the start.
    let l = -ln_t;
    let asymptote = (l - R::from_f64(0.5) * (R::from_f64(core::f64::consts::PI) * l).ln())
        .max(R::zero())
        .sqrt();
    let mut x = R::select(l.ge(R::from_f64(16.0)), asymptote, x0.abs());
    for _ in 0..3 {
        let e2 = (two_over_sqrt_pi * (-x * x).exp()).max(tiny());
        let ec = erfc(x).max(tiny());
        let step_mid = (crate::ndf::erf(x) - ay) / e2;
        let step_tail = (ln_t - ec.ln()) * ec / e2;
        let xn = x - R::select(mid, step_mid, step_tail);
        x = R::select(xn.is_finite(), xn.max(R::zero()), x);
    }
    R::select(a.y.lt(R::zero()), -x, x)
}

/// `erf⁻¹(c − 1)` for `c ∈ [0, 2]` given as `c`, for sampling: Giles' approximation, and
/// [`erf_inv`]'s refinement in lanes beyond its fitted range (`c (2 − c) < 10⁻⁷`: `u` within
/// 10⁻⁷ of an end, so a branch taken about once per 10⁷ samples, on a mask of lanes).
#[inline(always)]
fn erf_inv_of_c<R: Real>(c: R) -> R {
    let a = ErfInvArg {
        y: c - R::one(),
        one_plus: c,
        one_minus: R::from_f64(2.0) - c,
    };
    let x = erf_inv_giles(a);
    let far = (a.one_plus * a.one_minus).lt(R::from_f64(1e-7));
    if R::any(far) {
        R::select(far, erf_inv_refined(a, x), x)
    } else {
        x
    }
}

/// `√π`.
const SQRT_PI: f64 = 1.772_453_850_905_516;

/// The slope `x` (configuration `α = 1`, `wo = (sin θ, 0, cos θ)`, `θ ∈ [0, π/2]`) with
/// `C(x) = u·C(x_max)`, where `C` is the visible slopes' CDF (Heitz & d'Eon 2014):
///
/// ```text
/// C(x) ∝ G(c) = cos θ · c + sin θ · e^(−x²)/√π,    c = erfc(−x) = 1 + erf(x) ∈ [0, c_max]
/// G'(c) = cos θ − x sin θ,                        x_max = min(cot θ, 6), c_max = 2 − erfc(x_max)
/// ```
///
/// Solved in `c` (Jakob 2014: `G` is nearly linear there, unlike `C(x)` in its tails): from
/// Jakob's fitted initial guess `c₀ = c_max (1 − (1 − u)^p(θ))`,
/// `p(θ) = 1 + θ(−0.876 + θ(0.4265 − 0.0594 θ))` (θ by Abramowitz & Stegun 4.4.45, within
/// 7e-5: a guess), three Newton steps on `G(c) = u G(c_max)`, each kept inside the bracket
/// of the signs seen so far (else bisection), `x(c)` by Giles' approximation
/// ([`erf_inv_of_c`]). At the rim, where `x → x_max = cot θ` and the root is nearly double,
/// the CDF's Taylor expansion instead (see the body). The result, clamped to `[−6, x_max]`:
/// `C(x)` within 1e-7 of `u C(x_max)` relative to `C(x_max)` in f64 and 1e-6 in f32 over
/// θ ∈ [0, π/2) and every `u` from 0 to 1 − 2⁻⁵³, and within 1e-4 relative in the lower tail
/// (`tests/sampling_microfacet.rs`, against an independent `erfc`; measured 3.4e-8 and
/// 2.4e-7), about the accuracy of `erf` itself. Eleven transcendental calls (the bracketed
/// Newton in `x` this replaced took 20 steps, about 40).
#[inline(always)]
fn beckmann_visible_slope<R: Real>(cos: R, sin: R, u: R) -> R {
    let one = R::one();
    let inv_sqrt_pi = R::from_f64(1.0 / SQRT_PI);
    let x_max = (cos / sin.max(tiny())).min(R::from_f64(6.0));
    let c_max = R::from_f64(2.0) - erfc(x_max);
    let e_max = (-x_max * x_max).exp();
    let g_max = cos.mul_add(c_max, sin * e_max * inv_sqrt_pi);
    let target = u * g_max;
    // Jakob's initial guess; 1 − (1 − u)^p by its series where u is small (no cancellation).
    let theta = (one - cos).max(R::zero()).sqrt()
        * cos.mul_add(
            cos.mul_add(
                cos.mul_add(R::from_f64(-0.018_729_3), R::from_f64(0.074_261_0)),
                R::from_f64(-0.212_114_4),
            ),
            R::from_f64(1.570_728_8),
        );
    let p = theta.mul_add(
        theta.mul_add(
            theta.mul_add(R::from_f64(-0.0594), R::from_f64(0.4265)),
            R::from_f64(-0.876),
        ),
        one,
    );
    let series = p * u * (R::from_f64(0.5) * (one - p)).mul_add(u, one);
    let power = one - (p * (one - u).max(tiny()).log2()).exp2();
    let mut c = c_max * R::select(u.lt(R::from_f64(1e-3)), series, power);
    let (mut lo, mut hi) = (R::zero(), c_max);
    for _ in 0..3 {
        let x = erf_inv_of_c(c);
        let g = cos.mul_add(c, sin * (-x * x).exp() * inv_sqrt_pi) - target;
        let below = g.lt(R::zero());
        lo = R::select(below, c, lo);
        hi = R::select(below, hi, c);
        let cn = c - g / (-x).mul_add(sin, cos);
        // Non-strict: at the root the step is 0 and `c` sits on a bracket end.
        let inside = cn.ge(lo) & cn.le(hi);
        c = R::select(inside, cn, R::from_f64(0.5) * (lo + hi));
    }
    // At the rim (x → x_max = cot θ < 6) G'(c_max) = 0: the root is nearly double and the
    // approximate inverse's error steers Newton astray. There the CDF's Taylor expansion,
    // C(x_max − δ) = C_max − ½ sin θ e^(−x_max²) δ² − ⅔ x_max sin θ e^(−x_max²) δ³ + …,
    // gives δ = √(√π (1 − u) G_max / (sin θ e^(−x_max²))) to a relative 4 x_max δ/3 of 1 − u:
    // used where δ < 10⁻³ (NaN and ∞ at sin θ = 0 or u = 1 fail the test).
    let delta = (R::from_f64(SQRT_PI) * (one - u) * g_max / (sin * e_max)).sqrt();
    let rim = delta.lt(R::from_f64(1e-3)) & x_max.lt(R::from_f64(6.0));
    let x = R::select(rim, x_max - delta, erf_inv_of_c(c));
    // Inside `[−6, x_max]`, the bracket in `x` (at `c = 0` or `c_max` rounded to 2 the
    // inverse is far outside it).
    x.max(R::from_f64(-6.0)).min(x_max)
}

/// Beckmann visible normal for `α = (ax, ay)` (Heitz & d'Eon 2014 in the stretched
/// configuration).
#[inline(always)]
fn beckmann_vndf<R: Real>(ax: R, ay: R, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
    let v = stretch(ax, ay, wo);
    let sin = (v.x * v.x + v.y * v.y).sqrt();
    let ok = sin.gt(tiny());
    let inv = sin.max(tiny()).recip();
    let (c, s) = (
        R::select(ok, v.x * inv, R::one()),
        R::select(ok, v.y * inv, R::zero()),
    );
    let x = beckmann_visible_slope(v.z.max(R::zero()), sin, u[0]);
    let six = R::from_f64(6.0);
    let y = erf_inv_of_c(R::from_f64(2.0) * u[1]).clamp(-six, six);
    // Rotate the slopes to wo's azimuth, unstretch; wm ∝ (−slope, 1).
    let (sx, sy) = (c * x - s * y, s * x + c * y);
    unstretch(R::one(), R::one(), Vec3::new(-ax * sx, -ay * sy, R::one()))
}

// ---------------------------------------------------------------------------------------------
// Strategy × NDF
// ---------------------------------------------------------------------------------------------

/// The GGX strategies for a type with `(αx, αy)` given by `$alpha`.
macro_rules! ggx_strategies {
    ($t:ident, $n:ident => $alpha:expr) => {
        impl<R: Real> NormalSampler<R, $t<R>> for VisibleNormals {
            #[inline(always)]
            fn sample_wm($n: &$t<R>, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
                let (ax, ay) = $alpha;
                ggx_vndf_heitz(ax, ay, wo, u)
            }
            #[inline(always)]
            fn pdf_wm($n: &$t<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
                vndf_pdf($n, wo, wm)
            }
            #[inline(always)]
            fn weight_scale($n: &$t<R>, wo: Vec3<R>, _wm: Vec3<R>) -> Option<R> {
                Some(inv_g1($n, wo))
            }
        }

        impl<R: Real> NormalSampler<R, $t<R>> for SphericalCaps {
            #[inline(always)]
            fn sample_wm($n: &$t<R>, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
                let (ax, ay) = $alpha;
                let v = stretch(ax, ay, wo);
                ggx_cap(ax, ay, v, v.z, u)
            }
            #[inline(always)]
            fn pdf_wm($n: &$t<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
                vndf_pdf($n, wo, wm)
            }
            #[inline(always)]
            fn weight_scale($n: &$t<R>, wo: Vec3<R>, _wm: Vec3<R>) -> Option<R> {
                Some(inv_g1($n, wo))
            }
        }

        impl<R: Real> NormalSampler<R, $t<R>> for BoundedVisibleNormals {
            #[inline(always)]
            fn sample_wm($n: &$t<R>, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
                let (ax, ay) = $alpha;
                let v = stretch(ax, ay, wo);
                let k = bounded_k(ax, ay, wo);
                ggx_cap(ax, ay, v, k * v.z, u)
            }
            #[inline(always)]
            fn pdf_wm($n: &$t<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
                let (ax, ay) = $alpha;
                let den = bounded_k(ax, ay, wo).mul_add(wo.z, stretched_len(ax, ay, wo));
                let p = R::from_f64(2.0) * wo.dot(wm).max(R::zero()) * $n.d(wm) / den.max(tiny());
                R::select(wo.z.gt(R::zero()), p, R::zero())
            }
            #[inline(always)]
            fn weight_scale($n: &$t<R>, wo: Vec3<R>, _wm: Vec3<R>) -> Option<R> {
                let (ax, ay) = $alpha;
                let den = bounded_k(ax, ay, wo).mul_add(wo.z, stretched_len(ax, ay, wo));
                Some(den / (R::from_f64(2.0) * wo.z.max(tiny())))
            }
        }

        impl<R: Real> NormalSampler<R, $t<R>> for FullDistribution {
            #[inline(always)]
            fn sample_wm($n: &$t<R>, _wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
                let (ax, ay) = $alpha;
                ggx_full(ax, ay, u)
            }
            #[inline(always)]
            fn pdf_wm($n: &$t<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
                R::select(wo.z.gt(R::zero()), full_pdf($n, wm), R::zero())
            }
            #[inline(always)]
            fn weight_scale(_: &$t<R>, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
                Some(full_weight_scale(wo, wm))
            }
        }

        impl<R: Real> SampleNdf<R> for $t<R> {
            #[inline(always)]
            fn sample_wm(&self, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
                <SphericalCaps as NormalSampler<R, Self>>::sample_wm(self, wo, u)
            }
            #[inline(always)]
            fn pdf_wm(&self, wo: Vec3<R>, wm: Vec3<R>) -> R {
                <SphericalCaps as NormalSampler<R, Self>>::pdf_wm(self, wo, wm)
            }
            #[inline(always)]
            fn weight_scale(&self, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
                <SphericalCaps as NormalSampler<R, Self>>::weight_scale(self, wo, wm)
            }
        }
    };
}

ggx_strategies!(Ggx, n => (n.alpha_x(), n.alpha_y()));
ggx_strategies!(GgxIsotropic, n => (n.alpha(), n.alpha()));

impl<R: Real> NormalSampler<R, Beckmann<R>> for VisibleNormals {
    #[inline(always)]
    fn sample_wm(ndf: &Beckmann<R>, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
        beckmann_vndf(ndf.alpha_x(), ndf.alpha_y(), wo, u)
    }
    #[inline(always)]
    fn pdf_wm(ndf: &Beckmann<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        vndf_pdf(ndf, wo, wm)
    }
    #[inline(always)]
    fn weight_scale(ndf: &Beckmann<R>, wo: Vec3<R>, _wm: Vec3<R>) -> Option<R> {
        Some(inv_g1(ndf, wo))
    }
}

impl<R: Real> NormalSampler<R, Beckmann<R>> for FullDistribution {
    #[inline(always)]
    fn sample_wm(ndf: &Beckmann<R>, _wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
        beckmann_full(ndf.alpha_x(), ndf.alpha_y(), u)
    }
    #[inline(always)]
    fn pdf_wm(ndf: &Beckmann<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        R::select(wo.z.gt(R::zero()), full_pdf(ndf, wm), R::zero())
    }
    #[inline(always)]
    fn weight_scale(_ndf: &Beckmann<R>, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
        Some(full_weight_scale(wo, wm))
    }
}

impl<R: Real> NormalSampler<R, BlinnPhong<R>> for FullDistribution {
    #[inline(always)]
    fn sample_wm(ndf: &BlinnPhong<R>, _wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
        let (c, s) = cis(u[1]);
        power_lobe(u[0], ndf.shininess() + R::from_f64(2.0), c, s)
    }
    #[inline(always)]
    fn pdf_wm(ndf: &BlinnPhong<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        R::select(wo.z.gt(R::zero()), full_pdf(ndf, wm), R::zero())
    }
    #[inline(always)]
    fn weight_scale(_ndf: &BlinnPhong<R>, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
        Some(full_weight_scale(wo, wm))
    }
}

impl<R: Real> NormalSampler<R, AshikhminShirleyLobe<R>> for FullDistribution {
    #[inline(always)]
    fn sample_wm(ndf: &AshikhminShirleyLobe<R>, _wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
        let two = R::from_f64(2.0);
        let (nu, nv) = (ndf.nu(), ndf.nv());
        // Quadrant q ∈ {0, 1, 2, 3} and the position u' ∈ [0, 1) inside it.
        let u4 = u[0] * R::from_f64(4.0);
        let q = u4.floor().min(R::from_f64(3.0));
        let up = (u4 - q).clamp(R::zero(), R::one());
        // a = π up/2 = 2π (up/4) (the quarter is exact): (cos a, sin a) without a library call.
        let (sin_a, cos_a) = crate::fast::sin_cos_2pi(up * R::from_f64(0.25));
        // tan φ = √((nu + 2)/(nv + 2)) tan a, in the first quadrant.
        let (cx, sy) = ((nv + two).sqrt() * cos_a, (nu + two).sqrt() * sin_a);
        let inv = (cx * cx + sy * sy).max(tiny()).sqrt().recip();
        let (c, s) = (cx * inv, sy * inv);
        // φ → π − φ, π + φ, 2π − φ in the other quadrants.
        let half = R::from_f64(0.5);
        let flip_x = q.gt(half) & q.lt(R::from_f64(2.5));
        let flip_y = q.gt(R::from_f64(1.5));
        let c = R::select(flip_x, -c, c);
        let s = R::select(flip_y, -s, s);
        let e = nu.mul_add(c * c, nv * (s * s));
        power_lobe(u[1], e + two, c, s)
    }
    #[inline(always)]
    fn pdf_wm(ndf: &AshikhminShirleyLobe<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        R::select(wo.z.gt(R::zero()), full_pdf(ndf, wm), R::zero())
    }
    #[inline(always)]
    fn weight_scale(_ndf: &AshikhminShirleyLobe<R>, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
        Some(full_weight_scale(wo, wm))
    }
}

/// `SampleNdf` forwarding to one strategy.
macro_rules! default_strategy {
    ($t:ident => $st:ident) => {
        impl<R: Real> SampleNdf<R> for $t<R> {
            #[inline(always)]
            fn sample_wm(&self, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
                <$st as NormalSampler<R, Self>>::sample_wm(self, wo, u)
            }
            #[inline(always)]
            fn pdf_wm(&self, wo: Vec3<R>, wm: Vec3<R>) -> R {
                <$st as NormalSampler<R, Self>>::pdf_wm(self, wo, wm)
            }
            #[inline(always)]
            fn weight_scale(&self, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
                <$st as NormalSampler<R, Self>>::weight_scale(self, wo, wm)
            }
        }
    };
}

default_strategy!(Beckmann => VisibleNormals);
default_strategy!(BlinnPhong => FullDistribution);
default_strategy!(AshikhminShirleyLobe => FullDistribution);

/// Forwards to the wrapped distribution's default strategy (one branch per call on the
/// variant, as for evaluation).
#[deny(clippy::missing_trait_methods)] // forward every hook, defaulted ones too
impl<R: Real> SampleNdf<R> for AnyNdf<R> {
    #[inline(always)]
    fn sample_wm(&self, wo: Vec3<R>, u: [R; 2]) -> Vec3<R> {
        crate::ndf::on_any_ndf!(self, n => n.sample_wm(wo, u))
    }
    #[inline(always)]
    fn pdf_wm(&self, wo: Vec3<R>, wm: Vec3<R>) -> R {
        crate::ndf::on_any_ndf!(self, n => n.pdf_wm(wo, wm))
    }
    #[inline(always)]
    fn weight_scale(&self, wo: Vec3<R>, wm: Vec3<R>) -> Option<R> {
        crate::ndf::on_any_ndf!(self, n => n.weight_scale(wo, wm))
    }
}

// ---------------------------------------------------------------------------------------------
// Cook-Torrance
// ---------------------------------------------------------------------------------------------

/// Samples a Cook-Torrance model by reflecting a normal of the strategy `St`.
#[inline(always)]
fn sample_ct<R, D, F, G, S, St, const N: usize>(
    m: &CookTorrance<R, D, F, G, S>,
    wo: Vec3<R>,
    u: [R; 3],
) -> Sample<R, N>
where
    R: Real,
    D: Ndf<R>,
    F: FresnelTerm<R, N>,
    G: Masking<R, D>,
    S: SqrtFn,
    St: NormalSampler<R, D>,
{
    let wm = St::sample_wm(&m.ndf, wo, [u[0], u[1]]);
    let cos_d = wo.dot(wm);
    let wi = wm.scale(R::from_f64(2.0) * cos_d) - wo;
    let pdf = St::pdf_wm(&m.ndf, wo, wm) / (R::from_f64(4.0) * cos_d).max(tiny());
    let f = m.eval(wi, wo);
    let weight = match St::weight_scale(&m.ndf, wo, wm) {
        Some(c) => {
            let fr = m.fresnel.eval(cos_d.clamp(R::zero(), R::one()));
            let g = m.masking.g2(&m.ndf, wi, wo, wm) * c;
            crate::real::channels(
                #[inline(always)]
                |k| fr[k] * g,
            )
        }
        None => {
            let r = wi.z / pdf.max(tiny());
            crate::real::channels(
                #[inline(always)]
                |k| f[k] * r,
            )
        }
    };
    let valid = wo.z.gt(R::zero()) & cos_d.gt(R::zero());
    Sample::new(wi, pdf, f, weight, valid)
}

/// The density of [`sample_ct`]: `pdf_wm(normalize(wi + wo)) / (4 wo·wm)`.
#[inline(always)]
fn pdf_ct<R: Real, D: Ndf<R>, St: NormalSampler<R, D>>(ndf: &D, wo: Vec3<R>, wi: Vec3<R>) -> R {
    let wm = (wi + wo).normalize_or_zero();
    let cos_d = wo.dot(wm);
    let p = St::pdf_wm(ndf, wo, wm) / (R::from_f64(4.0) * cos_d).max(tiny());
    let ok = wo.z.gt(R::zero()) & wi.z.gt(R::zero()) & cos_d.gt(R::zero());
    R::select(ok, p, R::zero())
}

/// A Cook-Torrance lobe's albedo estimate: the channel mean of its Fresnel term at the view
/// angle, `mean(F(cos θo))` (one body for [`CookTorrance`] and [`Sampled`]).
#[inline(always)]
fn fresnel_estimate<R: Real, F: FresnelTerm<R, N>, const N: usize>(fresnel: &F, wo: Vec3<R>) -> R {
    crate::sampling::lobes::mean(fresnel.eval(wo.z.saturate()))
}

/// Samples the NDF's default strategy ([`SampleNdf`]) and reflects:
/// `wi = 2 (wo·wm) wm − wo`, `pdf = pdf_wm / (4 wo·wm)`; the weight in closed form
/// (`F·G2/G1(wo)` for visible normals) where the strategy has one. Any `F`, `G`, `S`.
impl<R, D, F, G, S, const N: usize> SampleBrdf<R, N> for CookTorrance<R, D, F, G, S>
where
    R: Real,
    D: SampleNdf<R>,
    F: FresnelTerm<R, N>,
    G: Masking<R, D>,
    S: SqrtFn,
{
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        sample_ct::<R, D, F, G, S, Auto, N>(self, wo, u)
    }
    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        pdf_ct::<R, D, Auto>(&self.ndf, wo, wi)
    }
    /// The channel mean of the Fresnel term at the view angle, `mean(F(cos θo))`: the
    /// directional albedo with `F = 1` is at most 1 (0.3 to 1 for GGX), so this bounds the
    /// lobe's albedo from above up to the Fresnel term's variation over the lobe; a mixture
    /// ([`Sum`](crate::models::Sum), [`Layered`](crate::models::Layered)) uses it to pick
    /// the lobe, and any positive estimate keeps the mixture unbiased.
    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        fresnel_estimate(&self.fresnel, wo)
    }
}

/// A model sampled by the strategy `St` instead of its default: [`Brdf`] is the model's,
/// [`SampleBrdf`] reflects normals drawn by `St`. Build with [`CookTorrance::sampled_with`].
///
/// ```
/// use brdf::{SampleBrdf, Vec3, fresnel::Schlick, masking::SmithHeightCorrelated};
/// use brdf::{models::CookTorrance, ndf::Ggx, sampling::BoundedVisibleNormals};
/// let ct = CookTorrance::new(Ggx::new(0.5_f64).unwrap(), Schlick::new([0.04]).unwrap(), SmithHeightCorrelated);
/// let bounded = ct.sampled_with::<BoundedVisibleNormals>();
/// let s = bounded.sample(Vec3::new(0.0, 0.0, 1.0), [0.3, 0.9, 0.0]);
/// assert!(s.wi.z > 0.0 && (s.pdf - bounded.pdf(Vec3::new(0.0, 0.0, 1.0), s.wi)).abs() < 1e-9 * s.pdf);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampled<M, St> {
    /// The model.
    pub model: M,
    _st: PhantomData<St>,
}

impl<R: Real, D: Ndf<R>, F, G: Masking<R, D>, S: SqrtFn> CookTorrance<R, D, F, G, S> {
    /// This model with [`SampleBrdf`] by the normal-sampling strategy `St`
    /// ([`VisibleNormals`], [`SphericalCaps`], [`BoundedVisibleNormals`],
    /// [`FullDistribution`], [`Auto`]).
    #[inline]
    #[must_use]
    pub fn sampled_with<St: NormalSampler<R, D>>(self) -> Sampled<Self, St> {
        Sampled {
            model: self,
            _st: PhantomData,
        }
    }
}

impl<R: Real, const N: usize, M: Brdf<R, N>, St> Brdf<R, N> for Sampled<M, St> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        self.model.eval(wi, wo)
    }
    #[inline]
    fn properties(&self) -> Properties {
        self.model.properties()
    }
    #[inline]
    fn kinks(&self, wo: Vec3<f64>) -> Kinks {
        self.model.kinks(wo)
    }
}

impl<R, D, F, G, S, St, const N: usize> SampleBrdf<R, N>
    for Sampled<CookTorrance<R, D, F, G, S>, St>
where
    R: Real,
    D: Ndf<R>,
    F: FresnelTerm<R, N>,
    G: Masking<R, D>,
    S: SqrtFn,
    St: NormalSampler<R, D>,
{
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        sample_ct::<R, D, F, G, S, St, N>(&self.model, wo, u)
    }
    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        pdf_ct::<R, D, St>(&self.model.ndf, wo, wi)
    }
    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        fresnel_estimate(&self.model.fresnel, wo)
    }
}

/// The model splatted, the strategy kept: a [`Sampled`] model goes through the batch path
/// ([`batch::sample`](crate::batch::sample)) like the model it wraps.
impl<M: crate::real::Splat, St> crate::real::Splat for Sampled<M, St> {
    const EXPLICIT_LANES: bool = M::EXPLICIT_LANES;
    type On<L: Real> = Sampled<M::On<L>, St>;
    #[inline]
    fn splat<L: Real>(&self) -> Self::On<L> {
        Sampled {
            model: self.model.splat(),
            _st: PhantomData,
        }
    }
}
