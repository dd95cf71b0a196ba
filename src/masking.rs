//! Masking-shadowing terms `G2(wi, wo, wm)` and visibility terms `V = G2 / (4 cos θi cos θo)`.
//!
//! Each term is a zero-sized type implementing [`Masking`], so a model picks one at compile
//! time (`CookTorrance<R, D, F, G>`):
//!
//! | type | `G2` | needs |
//! |---|---|---|
//! | [`SmithHeightCorrelated`] | `χ⁺ / (1 + Λ(wi) + Λ(wo))` (exact for Smith microsurfaces) | [`SmithLambda`] |
//! | [`SmithSeparable`] | `χ⁺ G1(wi) G1(wo)`, `G1 = 1/(1 + Λ)` | [`SmithLambda`] |
//! | [`SmithSeparableWalter`] | separable, Walter's rational Beckmann `G1` | [`Beckmann`] |
//! | [`VCavity`] | `min(1, 2 cos θm cos θo/(wo·wm), 2 cos θm cos θi/(wi·wm))` | nothing (any [`Ndf`]) |
//! | [`SchlickGgx`] | `G1 = cos θ/(cos θ (1 − k) + k)`, `k = α/2`, separable | [`ProjectedAlpha`] |
//! | [`HammonApprox`] | `V = 0.5 / lerp(2 cos θi cos θo, cos θi + cos θo, α)` | [`ProjectedAlpha`] |
//! | [`Kelemen`] | `V = 1 / (4 (wi·wm)(wo·wm))` | nothing (any [`Ndf`]) |
//! | [`Implicit`] | `G2 = cos θi cos θo`, `V = 1/4` | nothing (any [`Ndf`]) |
//!
//! The terms that ignore the NDF ([`VCavity`], [`Kelemen`], [`Implicit`]) also evaluate
//! without one: `VCavity::g2(wi, wo, wm)` and `VCavity::visibility(wi, wo, wm)` are
//! associated functions, and their [`Masking`] implementation, for every NDF, forwards to
//! them (bit for bit, tested). The method call `VCavity.g2(&ndf, wi, wo, wm)` is the trait's.
//!
//! `χ⁺` is 1 when `wi·wm > 0` and `wo·wm > 0`, else 0 (Heitz 2014, the microfacet visibility indicator): with `wm` the
//! half vector of two upper-hemisphere directions it is 1 except for the degenerate
//! `wm = 0` (`wi = −wo`), where every term here returns 0 instead of NaN. The approximations
//! ([`SchlickGgx`], [`HammonApprox`], [`Implicit`]) do not look at `wm`.
//!
//! # Grazing angles
//!
//! Every [`Masking::visibility`] is overridden with a form that has no `0/0` or `0·∞` at
//! `cos θ = 0`: the Smith terms divide by `cos θ + cosΛ(w)` ([`SmithLambda::cos_lambda`])
//! instead of multiplying `G1` by `1/cos θ`, so `V` has its finite grazing limit when one
//! direction grazes. When *both* cosines are exactly 0 the true `V` is `+∞` (e.g. GGX:
//! `1/(4 α cos θ)` as both go to 0); there the denominators are floored at 1e-30 and `V` is
//! large but finite. `G2` is finite and in `[0, 1]` everywhere.
//!
//! # Accuracy of the approximations
//!
//! Max absolute error of `G2` (dimensionless, so the error is bounded in `[0, 1]`) against
//! the exact height-correlated Smith GGX `G2` ([`SmithHeightCorrelated`] with
//! [`Ggx`](crate::ndf::Ggx)), isotropic, half vectors, over `cos θi, cos θo` on a 41-point grid
//! (plus 1e-7) and relative azimuths `Δφ ∈ {0, π/2, π}`, measured in `tests/masking.rs`
//! (which prints and checks both tables):
//!
//! | `cos θ ∈ [0, 1]` | α = 0.05 | α = 0.25 | α = 0.5 | α = 0.75 | α = 1 |
//! |---|---|---|---|---|---|
//! | [`SmithSeparable`] (exact `G1·G1`) | 0.065 | 0.089 | 0.090 | 0.090 | 0.090 |
//! | [`HammonApprox`] | 0.214 | 0.151 | 0.090 | 0.040 | 0 (exact) |
//! | [`SchlickGgx`] (`k = α/2`) | 0.249 | 0.190 | 0.134 | 0.104 | 0.090 |
//! | [`Kelemen`] | 1 | 1 | 1 | 1 | 1 |
//! | [`Implicit`] | 0.932 | 0.710 | 0.508 | 0.360 | 0.250 |
//! | [`VCavity`] | 1 | 1 | 1 | 1 | 1 |
//!
//! | `cos θ ∈ [0.1, 1]` | α = 0.05 | α = 0.25 | α = 0.5 | α = 0.75 | α = 1 |
//! |---|---|---|---|---|---|
//! | [`SmithSeparable`] | 0.003 | 0.078 | 0.090 | 0.090 | 0.090 |
//! | [`HammonApprox`] | 0.206 | 0.151 | 0.090 | 0.040 | 0 (exact) |
//! | [`SchlickGgx`] | 0.229 | 0.190 | 0.134 | 0.104 | 0.090 |
//! | [`Kelemen`] | 0.932 | 0.710 | 0.803 | 0.867 | 0.900 |
//! | [`Implicit`] | 0.932 | 0.710 | 0.508 | 0.360 | 0.250 |
//! | [`VCavity`] | 0.909 | 0.627 | 0.803 | 0.867 | 0.900 |
//!
//! Reading the tables: the separable product is at most ~0.09 below the correlated form
//! (0.0902 where `Λi = Λo ≈ 1.62`: `1/(1 + 2Λ)` against `1/(1 + Λ)²`); Hammon's fit is exact at `α = 1` and worst for smooth surfaces at
//! grazing (`cos θ ≈ α`); Kelemen and the V-cavity return `G2 ≈ 1` for two grazing directions
//! on opposite sides (half vector ≈ n), where Smith gives ≈ 0; the implicit term is the
//! worst for smooth surfaces at moderate angles. (On the grid the `α = 0.05` column misses
//! part of the steep `cos θ ≈ α` region, so its Smith entries are lower bounds.)
//!
//! (The [`SmithSeparableWalter`] rational `G1` is within 0.0031 of the exact Beckmann `G1`.)
//!
//! # References
//!
//! * E. Heitz, "Understanding the masking-shadowing function in microfacet-based BRDFs",
//!   JCGT 3(2), 2014.
//! * B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet models for refraction
//!   through rough surfaces", EGSR 2007.
//! * J. F. Blinn, "Models of light reflection for computer synthesized pictures", SIGGRAPH 1977.
//! * R. L. Cook, K. E. Torrance, "A reflectance model for computer graphics", ACM TOG 1(1), 1982.
//! * C. Schlick, "An inexpensive BRDF model for physically-based rendering", CGF 13(3), 1994.
//! * B. Karis, "Real shading in Unreal Engine 4", SIGGRAPH 2013 course.
//! * C. Kelemen, L. Szirmay-Kalos, "A microfacet based coupled specular-matte BRDF model with
//!   importance sampling", Eurographics 2001 short papers.
//! * E. Hammon Jr., "PBR diffuse lighting for GGX+Smith microsurfaces", GDC 2017.
//! * R. Guy, M. Agopian, *Physically Based Rendering in Filament* (documentation), 2018.

use crate::ndf::{Beckmann, Ndf, ProjectedAlpha, SmithLambda, tiny};
use crate::{Real, Vec3};

crate::real::splat_as_itself!(
    SmithHeightCorrelated,
    SmithSeparable,
    SmithSeparableWalter,
    VCavity,
    SchlickGgx,
    HammonApprox,
    Kelemen,
    Implicit,
);

/// A masking-shadowing term `G2(wi, wo, wm)` usable with the NDF `D`.
///
/// Implementations that need the NDF (the Smith family) read it through `ndf`; others
/// (V-cavity, Kelemen) ignore it. Both `wi` and `wo` are in the upper hemisphere.
pub trait Masking<R: Real, D: Ndf<R>> {
    /// `G2(wi, wo, wm)`, dimensionless in `[0, 1]`.
    fn g2(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R;

    /// The visibility term `V = G2 / (4 cos θi cos θo)` (dimensionless) — what a Cook-Torrance
    /// body multiplies by `D·F`. Terms with a cheaper direct form of `V` override this.
    /// Domain: `wi.z ≥ 0`, `wo.z ≥ 0`; the default body floors the denominator at `1e-30`, so
    /// it is finite (if large) at exactly grazing angles.
    #[inline(always)]
    fn visibility(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        self.g2(ndf, wi, wo, wm) / (R::from_f64(4.0) * wi.z * wo.z).max(R::from_f64(1e-30))
    }

    /// The visibility as a fraction `(numerator, denominator)`, so that a Cook-Torrance body
    /// divides once for `D·V` (see [`crate::ndf::Ndf::d_fraction`]). The default is
    /// `(visibility(..), 1)`; the Smith terms override it with `(1, den)` and never read
    /// `wm` (so a body that passes them an unnormalized half vector loses nothing). The
    /// denominator is `≥ 0` and may be `0` (both directions exactly grazing): the caller
    /// floors the product of the denominators it divides by (Cook-Torrance: at `1e-30`).
    ///
    /// Domain: unit `wi`, `wo` with `wi.z > 0`, `wo.z > 0` and `wm ∥ wi + wo` — the
    /// reflection configuration. There `wi·wm = wo·wm = |wi + wo|/2 > 0` (the directions
    /// cannot be opposite), so the microfacet visibility `χ⁺(wi·wm) χ⁺(wo·wm)` is 1 and the
    /// Smith terms omit it; [`Masking::g2`] and [`Masking::visibility`] keep it for any `wm`.
    #[inline(always)]
    fn visibility_fraction(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> (R, R) {
        (self.visibility(ndf, wi, wo, wm), R::one())
    }
}

/// `χ⁺(wi·wm) χ⁺(wo·wm)`: both directions see the front of the microfacet.
#[inline(always)]
fn front<R: Real>(wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R::Mask {
    wi.dot(wm).gt(R::zero()) & wo.dot(wm).gt(R::zero())
}

#[inline(always)]
fn cos_clamped<R: Real>(w: Vec3<R>) -> R {
    w.z.max(R::zero())
}

// ---------------------------------------------------------------------------------------------
// Smith
// ---------------------------------------------------------------------------------------------

/// Smith height-correlated masking-shadowing (the exact `G2` of a Smith microsurface for
/// reflection).
///
/// ```text
/// G2 = χ⁺(wi·wm) χ⁺(wo·wm) / (1 + Λ(wi) + Λ(wo))
/// V  = χ⁺ / (4 (cos θi cos θo + cos θo·cosΛ(wi) + cos θi·cosΛ(wo))),   cosΛ(w) = cos θ Λ(w)
/// ```
///
/// The `V` form is algebraically `G2/(4 cos θi cos θo)` and finite when one cosine is 0
/// (GGX isotropic: `V = 0.5/(cos θo √(cos²θi(1 − α²) + α²) + cos θi √(cos²θo(1 − α²) + α²))`,
/// the form in Filament's docs). Works with any [`SmithLambda`] NDF, anisotropic included.
///
/// Reference: E. Heitz, JCGT 2014 (height-correlated masking and shadowing).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, vec3::half_vector, ndf::Ggx, masking::{Masking, SmithHeightCorrelated}};
///
/// let ggx = Ggx::<f64>::new(0.3).unwrap();
/// let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.28, 0.0, 0.96));
/// let wm = half_vector(wi, wo);
/// let g = SmithHeightCorrelated.g2(&ggx, wi, wo, wm);
/// let v = SmithHeightCorrelated.visibility(&ggx, wi, wo, wm);
/// assert!(g > 0.9 && g < 1.0);
/// assert!((v - g / (4.0 * 0.8 * 0.96)).abs() < 1e-14);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SmithHeightCorrelated;

impl<R: Real, D: SmithLambda<R>> Masking<R, D> for SmithHeightCorrelated {
    #[inline(always)]
    fn g2(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let g = (R::one() + ndf.lambda(wi) + ndf.lambda(wo)).recip();
        R::select(front(wi, wo, wm), g, R::zero())
    }

    /// `1/(2·sum)` ([`SmithLambda::height_correlated_sum`]), the sum floored at `1e-30`
    /// (finite at exactly grazing angles), and 0 below the horizon or behind the microfacet.
    #[inline(always)]
    fn visibility(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let (_, den) = self.visibility_fraction(ndf, wi, wo, wm);
        let m = front(wi, wo, wm) & wi.z.ge(R::zero()) & wo.z.ge(R::zero());
        R::select(m, den.max(tiny()).recip(), R::zero())
    }

    /// `(1, 2·sum)`: the denominator is not floored (0 when both directions are exactly
    /// grazing); the Cook-Torrance body floors the product of its denominators.
    #[inline(always)]
    fn visibility_fraction(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, _wm: Vec3<R>) -> (R, R) {
        let sum = ndf.height_correlated_sum(wi, wo);
        (R::one(), sum + sum)
    }
}

/// Smith separable (uncorrelated) masking-shadowing: the product of the two `G1`.
///
/// ```text
/// G2 = χ⁺(wi·wm) χ⁺(wo·wm) G1(wi) G1(wo),     G1(w) = 1/(1 + Λ(w))
/// V  = χ⁺ / (4 (cos θi + cosΛ(wi)) (cos θo + cosΛ(wo)))
/// ```
///
/// Ignores the correlation of masking and shadowing by height, so `G2` is lower than
/// [`SmithHeightCorrelated`] (by up to 0.0902 absolute, where `Λ(wi) = Λ(wo) ≈ 1.62`:
/// `1/(1 + Λ)²` against `1/(1 + 2Λ)`; see the [module](self) table); it is what Walter et al. 2007 and Mitsuba use.
///
/// Reference: B. Smith, "Geometrical shadowing of a random rough surface", IEEE TAP 1967;
/// B. Walter et al., EGSR 2007, §5; E. Heitz, JCGT 2014 (separable masking and shadowing).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, ndf::Beckmann, masking::{Masking, SmithSeparable, SmithHeightCorrelated}};
/// let b = Beckmann::<f32>::new(0.5).unwrap();
/// let (wi, wo) = (Vec3::new(0.8, 0.0, 0.6), Vec3::new(-0.8, 0.0, 0.6));
/// let wm = Vec3::new(0.0, 0.0, 1.0);
/// assert!(SmithSeparable.g2(&b, wi, wo, wm) < SmithHeightCorrelated.g2(&b, wi, wo, wm));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SmithSeparable;

impl<R: Real, D: SmithLambda<R>> Masking<R, D> for SmithSeparable {
    #[inline(always)]
    fn g2(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let g = ndf.g1(wi) * ndf.g1(wo);
        R::select(front(wi, wo, wm), g, R::zero())
    }

    #[inline(always)]
    fn visibility(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let (_, den) = self.visibility_fraction(ndf, wi, wo, wm);
        R::select(front(wi, wo, wm), den.recip(), R::zero())
    }

    #[inline(always)]
    fn visibility_fraction(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, _wm: Vec3<R>) -> (R, R) {
        let (gi, go) = (ndf.separable_den(wi), ndf.separable_den(wo));
        (R::one(), (R::from_f64(4.0) * gi * go).max(tiny()))
    }
}

/// Walter's rational approximation of the Beckmann Smith `G1`.
///
/// ```text
/// G1(a) ≈ (3.535 a + 2.181 a²) / (1 + 2.276 a + 2.577 a²),   a < 1.6
///       = 1,                                                 a ≥ 1.6
/// a = 1/(α tan θ)
/// ```
///
/// The rational part slightly exceeds 1 just below the switch (1.00002 at `a = 1.6`), so it
/// is clamped at 1 to keep `G2 ≤ 1`.
///
/// Max absolute error against the exact `1/(1 + Λ(a))`: 0.0031 at `a ≈ 1.34` (measured over
/// `a ∈ [0, 10]` in `tests/masking.rs`; Walter et al. state < 0.35 %). Domain: `a ≥ 0`.
///
/// Reference: B. Walter et al., EGSR 2007, eq. 27.
#[inline]
#[must_use]
pub fn walter_beckmann_g1<R: Real>(a: R) -> R {
    let (num, den) = walter_g1_parts(a);
    R::select(
        a.lt(R::from_f64(1.6)),
        (a * num / den).min(R::one()),
        R::one(),
    )
}

/// Walter's rational fit `G1 ≈ a·p(a)/q(a)` below `a = 1.6`: returns `(p(a), q(a))` with
/// `p = 3.535 + 2.181a`, `q = 1 + 2.276a + 2.577a²` (EGSR 2007, eq. 27). The one place the
/// coefficients live.
#[inline(always)]
fn walter_g1_parts<R: Real>(a: R) -> (R, R) {
    let p = R::from_f64(2.181).mul_add(a, R::from_f64(3.535));
    let q = a.mul_add(R::from_f64(2.577).mul_add(a, R::from_f64(2.276)), R::one());
    (p, q)
}

/// `G1(w)/cos θ` of Walter's approximation, finite at grazing (`3.535/(α(w) sin θ)` there).
#[inline(always)]
fn walter_g1_over_cos<R: Real>(ndf: &Beckmann<R>, w: Vec3<R>) -> R {
    let c = cos_clamped(w);
    let sigma = ndf.projected_alpha(w) * (w.x * w.x + w.y * w.y).sqrt();
    let sigma = sigma.max(tiny());
    let a = c / sigma;
    // G1/cos θ = (a p/q)/cos θ = p/(σ q), since a = cos θ/σ.
    let (p, q) = walter_g1_parts(a);
    let g = p / (sigma * q);
    let inv_c = c.max(tiny()).recip();
    R::select(a.lt(R::from_f64(1.6)), g.min(inv_c), inv_c)
}

/// Separable Smith masking for [`Beckmann`] with Walter's rational `G1`
/// ([`walter_beckmann_g1`]) instead of the `erf` form.
///
/// ```text
/// G2 = χ⁺ G1w(a(wi)) G1w(a(wo)),    a(w) = cos θ / (α(w) sin θ)
/// ```
///
/// `G2` within 0.0062 of [`SmithSeparable`] with the exact Beckmann Λ (measured).
/// Anisotropic through the projected roughness `α(w)`.
///
/// Reference: B. Walter et al., EGSR 2007, eq. 27.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SmithSeparableWalter;

impl<R: Real> Masking<R, Beckmann<R>> for SmithSeparableWalter {
    #[inline(always)]
    fn g2(&self, ndf: &Beckmann<R>, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        // A function, not a closure (see `erf_inv_giles` in `sampling::microfacet`).
        #[inline(always)]
        fn g1<R: Real>(ndf: &Beckmann<R>, w: Vec3<R>) -> R {
            let sigma = ndf.projected_alpha(w) * (w.x * w.x + w.y * w.y).sqrt();
            walter_beckmann_g1(cos_clamped(w) / sigma.max(tiny()))
        }
        R::select(front(wi, wo, wm), g1(ndf, wi) * g1(ndf, wo), R::zero())
    }

    #[inline(always)]
    fn visibility(&self, ndf: &Beckmann<R>, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let v = walter_g1_over_cos(ndf, wi) * walter_g1_over_cos(ndf, wo) * R::from_f64(0.25);
        R::select(front(wi, wo, wm), v, R::zero())
    }
}

// ---------------------------------------------------------------------------------------------
// V-cavity
// ---------------------------------------------------------------------------------------------

/// The V-cavity masking-shadowing of Torrance-Sparrow, Blinn 1977 and Cook-Torrance 1982.
///
/// ```text
/// G2 = min(1, 2 (n·wm)(n·wo)/(wo·wm), 2 (n·wm)(n·wi)/(wi·wm))
/// V  = min(1/(4 cos θi cos θo), (n·wm)/(2 cos θi (wo·wm)), (n·wm)/(2 cos θo (wi·wm)))
/// ```
///
/// Blinn 1977 and Cook & Torrance 1982 (and the seed slide) write both fractions over
/// `E·H` (`wo·wm`): for the half vector `wi·wm = wo·wm`, so the two agree; with a general
/// `wm` the per-direction form above (Heitz 2014, V-cavity masking function) is the one that is symmetric in
/// `wi ↔ wo`. The seed's `G = min(1, 2(N·H)(N·E)/(E·H), 2(N·H)(N·L)/(E·H))` is correct.
/// The term ignores the NDF. Its `G1(v, m) = min(1, 2 cos θm cos θv/(v·m))` conserves the
/// projected area like a Smith `G1` (`∫ G1 max(0, v·m) D dωm = cos θv`, checked by quadrature
/// for GGX to 5e-6 in `tests/masking.rs`, as Heitz 2014 notes for the V-cavity model).
///
/// References: J. F. Blinn, SIGGRAPH 1977 (`Ge`, `Gs`); R. L. Cook, K. E. Torrance, ACM TOG
/// 1982 (geometrical attenuation factor); E. Heitz, JCGT 2014 (the V-cavity model).
///
/// # Examples
///
/// Without an NDF, and as the masking term of a microfacet model (any NDF):
///
/// ```
/// use brdf::{Vec3, ndf::Ggx, masking::{Masking, VCavity}, vec3::half_vector};
/// let n = Vec3::new(0.0, 0.0, 1.0);
/// assert_eq!(VCavity::g2(n, n, n), 1.0);
/// let (wi, wo) = (Vec3::new(0.8, 0.0, 0.6), Vec3::new(-0.6, 0.0, 0.8));
/// let wm = half_vector(wi, wo);
/// let ggx = Ggx::new(0.5_f64).unwrap();
/// assert_eq!(VCavity.g2(&ggx, wi, wo, wm), VCavity::g2(wi, wo, wm));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VCavity;

impl VCavity {
    /// `G2(wi, wo, wm)` of the formula above, in `[0, 1]`; 0 unless `wi·wm > 0` and
    /// `wo·wm > 0`. Needs no NDF (the [`Masking`] implementation forwards here).
    #[inline(always)]
    pub fn g2<R: Real>(wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let two_nh = R::from_f64(2.0) * wm.z.max(R::zero());
        let (hi, ho) = (wi.dot(wm), wo.dot(wm));
        let go = two_nh * cos_clamped(wo) / ho.max(tiny());
        let gi = two_nh * cos_clamped(wi) / hi.max(tiny());
        let g = R::one().min(go).min(gi);
        R::select(front(wi, wo, wm), g, R::zero())
    }

    /// The visibility `V = G2/(4 cos θi cos θo)` of the formula above, without the `0/0` at
    /// grazing angles (denominators floored at 1e-30). Needs no NDF.
    #[inline(always)]
    pub fn visibility<R: Real>(wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let nh = wm.z.max(R::zero());
        let (ci, co) = (cos_clamped(wi), cos_clamped(wo));
        let (hi, ho) = (wi.dot(wm), wo.dot(wm));
        let two = R::from_f64(2.0);
        let a = (R::from_f64(4.0) * ci * co).max(tiny()).recip();
        let b = nh / (two * ci * ho).max(tiny());
        let c = nh / (two * co * hi).max(tiny());
        R::select(front(wi, wo, wm), a.min(b).min(c), R::zero())
    }
}

impl<R: Real, D: Ndf<R>> Masking<R, D> for VCavity {
    #[inline(always)]
    fn g2(&self, _ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        Self::g2(wi, wo, wm)
    }

    #[inline(always)]
    fn visibility(&self, _ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        Self::visibility(wi, wo, wm)
    }
}

// ---------------------------------------------------------------------------------------------
// Fast approximations
// ---------------------------------------------------------------------------------------------

/// Schlick's approximation of the separable Smith GGX `G1`, with Karis's `k = α/2`.
///
/// ```text
/// G1(w) = cos θ / (cos θ (1 − k) + k),    k = α(w)/2
/// G2    = G1(wi) G1(wo)
/// V     = 1 / (4 (cos θi (1 − ki) + ki)(cos θo (1 − ko) + ko))
/// ```
///
/// Schlick 1994 fitted `k` to the Beckmann `G1` (`k = α√(2/π)`); Karis 2013 chose `k = α/2`
/// to fit the Smith GGX `G1`. (UE4 additionally remaps `α` for analytic lights,
/// `α' = ((roughness + 1)/2)²`, Burley's "hotness" fix: pass that `α` to the NDF if wanted.)
/// Anisotropic NDFs use the projected `α(w)` ([`ProjectedAlpha`]). Ignores `wm`. Error
/// against the exact correlated Smith GGX: see the [module](self) table (0.09 at `α = 1`,
/// 0.25 at `α = 0.05`).
///
/// References: C. Schlick, CGF 1994; B. Karis, "Real shading in Unreal Engine 4", SIGGRAPH
/// 2013 course, "Specular G".
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SchlickGgx;

impl SchlickGgx {
    /// `cos θ (1 − k) + k` with `k = α(w)/2`: the `G1` denominator, ≥ `min(1, k) > 0`.
    #[inline(always)]
    fn den<R: Real, D: ProjectedAlpha<R>>(ndf: &D, w: Vec3<R>) -> R {
        let k = ndf.projected_alpha(w) * R::from_f64(0.5);
        cos_clamped(w).mul_add(R::one() - k, k)
    }
}

impl<R: Real, D: ProjectedAlpha<R>> Masking<R, D> for SchlickGgx {
    #[inline(always)]
    fn g2(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, _wm: Vec3<R>) -> R {
        cos_clamped(wi) * cos_clamped(wo) / (Self::den(ndf, wi) * Self::den(ndf, wo))
    }

    #[inline(always)]
    fn visibility(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, _wm: Vec3<R>) -> R {
        (R::from_f64(4.0) * Self::den(ndf, wi) * Self::den(ndf, wo)).recip()
    }
}

/// Hammon's fit of the height-correlated Smith GGX visibility (also Filament's
/// `V_SmithGGXCorrelated_Fast` and UE4's `Vis_SmithJointApprox`: the same formula).
///
/// ```text
/// V  = 0.5 / lerp(2 cos θi cos θo, cos θi + cos θo, α)
///    = 0.5 / (cos θo (cos θi (1 − αi) + αi) + cos θi (cos θo (1 − αo) + αo))
/// G2 = 4 cos θi cos θo V
/// ```
///
/// It replaces each `√(cos²θ (1 − α²) + α²)` of the exact correlated GGX `V` (see
/// [`SmithHeightCorrelated`]) by its linear interpolation `cos θ (1 − α) + α`, exact at
/// `cos θ ∈ {0, 1}`. Hammon writes it with one `α`; the second form (Filament's notation,
/// algebraically identical for isotropic `α`) generalizes to anisotropic NDFs with the
/// projected `αi = α(wi)`, `αo = α(wo)`. Ignores `wm`. Exact at `α = 1`; max error of `G2`
/// 0.09 at `α = 0.5`, 0.21 at `α = 0.05` near grazing (module table). Domain: `alpha ≤ 1`.
///
/// References: E. Hammon Jr., GDC 2017; Filament documentation, §4.4.2 "Geometric shadowing".
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, vec3::half_vector, ndf::Ggx};
/// use brdf::masking::{HammonApprox, Masking, SmithHeightCorrelated};
///
/// let (wi, wo) = (Vec3::new(0.8, 0.0, 0.6), Vec3::new(0.0, -0.28, 0.96));
/// let wm = half_vector(wi, wo);
/// // Exact at α = 1, approximate below.
/// let rough = Ggx::<f64>::new(1.0).unwrap();
/// let exact = SmithHeightCorrelated.visibility(&rough, wi, wo, wm);
/// assert!((HammonApprox.visibility(&rough, wi, wo, wm) - exact).abs() < 1e-15);
/// let smooth = Ggx::<f64>::new(0.2).unwrap();
/// let exact = SmithHeightCorrelated.visibility(&smooth, wi, wo, wm);
/// assert!((HammonApprox.visibility(&smooth, wi, wo, wm) / exact - 1.0).abs() < 0.05);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HammonApprox;

impl HammonApprox {
    #[inline(always)]
    fn den<R: Real, D: ProjectedAlpha<R>>(ndf: &D, wi: Vec3<R>, wo: Vec3<R>) -> R {
        let (ci, co) = (cos_clamped(wi), cos_clamped(wo));
        let (ai, ao) = (ndf.projected_alpha(wi), ndf.projected_alpha(wo));
        co * ci.mul_add(R::one() - ai, ai) + ci * co.mul_add(R::one() - ao, ao)
    }
}

impl<R: Real, D: ProjectedAlpha<R>> Masking<R, D> for HammonApprox {
    #[inline(always)]
    fn g2(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, _wm: Vec3<R>) -> R {
        let num = R::from_f64(2.0) * cos_clamped(wi) * cos_clamped(wo);
        (num / Self::den(ndf, wi, wo).max(tiny())).min(R::one())
    }

    #[inline(always)]
    fn visibility(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, _wm: Vec3<R>) -> R {
        R::from_f64(0.5) / Self::den(ndf, wi, wo).max(tiny())
    }
}

/// Kelemen and Szirmay-Kalos's approximation of the Cook-Torrance `G/(cos θi cos θo)`.
///
/// ```text
/// G2 / (cos θi cos θo) ≈ 2/(1 + wi·wo) = 1/(wi·wm)²     (wm the half vector)
/// V = 1 / (4 (wi·wm)(wo·wm)),     G2 = cos θi cos θo / ((wi·wm)(wo·wm))
/// ```
///
/// Written with `(wi·wm)(wo·wm)` (equal to `(wi·wm)²` for the half vector) so that it is
/// symmetric for any `wm`. For the half vector `G2 ≤ 1`, since
/// `cos θi + cos θo = 2 (wi·wm) cos θm ≤ 2 (wi·wm)` and `cos θi cos θo ≤ ((cos θi + cos θo)/2)²`.
/// Cheap (no NDF, no square root) but far from Smith at grazing (module table).
/// Filament uses it for the clear-coat layer (`V_Kelemen`).
///
/// Reference: C. Kelemen, L. Szirmay-Kalos, Eurographics 2001 short papers.
///
/// ```
/// use brdf::{Vec3, masking::Kelemen, vec3::half_vector};
/// let (wi, wo) = (Vec3::new(0.8_f64, 0.0, 0.6), Vec3::new(-0.6, 0.0, 0.8));
/// let wm = half_vector(wi, wo);
/// // No NDF needed: V = 1/(4 (wi·wm)²) for the half vector.
/// assert!((Kelemen::visibility(wi, wo, wm) - 0.25 / wi.dot(wm).powi(2)).abs() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Kelemen;

impl Kelemen {
    /// `G2 = cos θi cos θo / ((wi·wm)(wo·wm))`, 0 unless `wi·wm > 0` and `wo·wm > 0`. Needs
    /// no NDF (the [`Masking`] implementation forwards here).
    #[inline(always)]
    pub fn g2<R: Real>(wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let den = (wi.dot(wm) * wo.dot(wm)).max(tiny());
        let g = cos_clamped(wi) * cos_clamped(wo) / den;
        R::select(front(wi, wo, wm), g, R::zero())
    }

    /// `V = 1 / (4 (wi·wm)(wo·wm))`, 0 unless `wi·wm > 0` and `wo·wm > 0`. Needs no NDF.
    #[inline(always)]
    pub fn visibility<R: Real>(wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        let den = (R::from_f64(4.0) * wi.dot(wm) * wo.dot(wm)).max(tiny());
        R::select(front(wi, wo, wm), den.recip(), R::zero())
    }
}

impl<R: Real, D: Ndf<R>> Masking<R, D> for Kelemen {
    #[inline(always)]
    fn g2(&self, _ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        Self::g2(wi, wo, wm)
    }

    #[inline(always)]
    fn visibility(&self, _ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        Self::visibility(wi, wo, wm)
    }
}

/// The implicit masking-shadowing term: `G2 = cos θi cos θo`, so `V = 1/4`.
///
/// ```text
/// G2 = cos θi cos θo,     V = 1/4
/// ```
///
/// What a microfacet BRDF "without G" amounts to; it costs nothing. Ignores `wm` and the
/// NDF. Error: see the [module](self) table.
///
/// Reference: B. Karis, "Specular BRDF reference" (blog), 2013, `G_Implicit`; N. Hoffman,
/// "Background: physics and math of shading", SIGGRAPH 2013 course.
///
/// ```
/// use brdf::{Vec3, masking::Implicit};
/// let (wi, wo) = (Vec3::new(0.8, 0.0, 0.6), Vec3::new(-0.6, 0.0, 0.8));
/// assert_eq!(Implicit::g2(wi, wo), 0.6 * 0.8); // no NDF, no half vector
/// assert_eq!(Implicit::visibility::<f64>(), 0.25);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Implicit;

impl Implicit {
    /// `G2 = max(0, cos θi) max(0, cos θo)`. Needs neither an NDF nor `wm` (the [`Masking`]
    /// implementation forwards here).
    #[inline(always)]
    pub fn g2<R: Real>(wi: Vec3<R>, wo: Vec3<R>) -> R {
        cos_clamped(wi) * cos_clamped(wo)
    }

    /// `V = 1/4`.
    #[inline(always)]
    #[must_use]
    pub fn visibility<R: Real>() -> R {
        R::from_f64(0.25)
    }
}

impl<R: Real, D: Ndf<R>> Masking<R, D> for Implicit {
    #[inline(always)]
    fn g2(&self, _ndf: &D, wi: Vec3<R>, wo: Vec3<R>, _wm: Vec3<R>) -> R {
        Self::g2(wi, wo)
    }

    #[inline(always)]
    fn visibility(&self, _ndf: &D, _wi: Vec3<R>, _wo: Vec3<R>, _wm: Vec3<R>) -> R {
        Self::visibility()
    }
}

// ---------------------------------------------------------------------------------------------
// A masking term chosen at run time
// ---------------------------------------------------------------------------------------------

/// A masking-shadowing term chosen at run time, for a model whose parts come from a file or
/// a renderer's material table ([`crate::material::Material`]).
///
/// It implements [`Masking<R, D>`] for every NDF with a Smith `Λ` and a projected `α` (what
/// the approximations need), [`crate::ndf::AnyNdf`] included, by forwarding **every**
/// method ([`Masking::visibility`] and [`Masking::visibility_fraction`] included) to the
/// term it names, so a model built on `AnyMasking` evaluates exactly the operations, hence
/// the bits, of the same model built on that term (tested in `tests/material.rs`). The
/// price is one branch per call on the variant, a per-material constant.
/// ([`SmithSeparableWalter`] is missing: it works with [`Beckmann`] only.)
///
/// It holds no number, so it is also its own file description (feature `serde`: the snake
/// case of the variant, `"smith_height_correlated"` (the default), …, `"hammon"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case", expecting = "a masking term name")
)]
#[non_exhaustive]
pub enum AnyMasking {
    /// [`SmithHeightCorrelated`] (the default).
    #[default]
    SmithHeightCorrelated,
    /// [`SmithSeparable`].
    SmithSeparable,
    /// [`VCavity`].
    VCavity,
    /// [`SchlickGgx`].
    SchlickGgx,
    /// [`HammonApprox`] (`"hammon"` in files).
    #[cfg_attr(feature = "serde", serde(rename = "hammon"))]
    HammonApprox,
    /// [`Kelemen`].
    Kelemen,
    /// [`Implicit`].
    Implicit,
}

impl AnyMasking {
    /// Every variant.
    pub const ALL: [AnyMasking; 7] = [
        AnyMasking::SmithHeightCorrelated,
        AnyMasking::SmithSeparable,
        AnyMasking::VCavity,
        AnyMasking::SchlickGgx,
        AnyMasking::HammonApprox,
        AnyMasking::Kelemen,
        AnyMasking::Implicit,
    ];
}

impl crate::real::Splat for AnyMasking {
    /// `true`: a `match` on the variant per pair keeps LLVM from vectorizing the batch
    /// path's one-lane loop; on explicit lanes it is one branch per register of 8 or 16
    /// pairs (the same operations, so the bits of [`crate::real::F32Fma`]).
    const EXPLICIT_LANES: bool = true;
    type On<L: Real> = AnyMasking;
    #[inline]
    fn splat<L: Real>(&self) -> AnyMasking {
        *self
    }
}

/// `on_any_masking!(self, g => g.g2(..))`: the expression on the term an [`AnyMasking`]
/// names.
macro_rules! on_any_masking {
    ($any:expr, $g:ident => $e:expr) => {
        match $any {
            AnyMasking::SmithHeightCorrelated => {
                let $g = SmithHeightCorrelated;
                $e
            }
            AnyMasking::SmithSeparable => {
                let $g = SmithSeparable;
                $e
            }
            AnyMasking::VCavity => {
                let $g = VCavity;
                $e
            }
            AnyMasking::SchlickGgx => {
                let $g = SchlickGgx;
                $e
            }
            AnyMasking::HammonApprox => {
                let $g = HammonApprox;
                $e
            }
            AnyMasking::Kelemen => {
                let $g = Kelemen;
                $e
            }
            AnyMasking::Implicit => {
                let $g = Implicit;
                $e
            }
        }
    };
}

/// `From` each term.
macro_rules! any_masking_from {
    ($($v:ident),*) => {
        $(impl From<$v> for AnyMasking {
            #[inline]
            fn from(_: $v) -> Self {
                AnyMasking::$v
            }
        })*
    };
}
any_masking_from!(
    SmithHeightCorrelated,
    SmithSeparable,
    VCavity,
    SchlickGgx,
    HammonApprox,
    Kelemen,
    Implicit
);

#[deny(clippy::missing_trait_methods)] // forward every hook, defaulted ones too
impl<R: Real, D: SmithLambda<R> + ProjectedAlpha<R>> Masking<R, D> for AnyMasking {
    #[inline(always)]
    fn g2(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        on_any_masking!(self, g => g.g2(ndf, wi, wo, wm))
    }

    #[inline(always)]
    fn visibility(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        on_any_masking!(self, g => g.visibility(ndf, wi, wo, wm))
    }

    #[inline(always)]
    fn visibility_fraction(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> (R, R) {
        on_any_masking!(self, g => g.visibility_fraction(ndf, wi, wo, wm))
    }
}
