//! Normal distribution functions `D(wm)`, their Smith `Λ`, and parameter conversions.
//!
//! Every NDF here is normalized as a density of microfacet normals whose projected area is
//! the macro-surface's area:
//!
//! ```text
//! ∫_Ω D(wm) cos θm dωm = 1,        D(wm) = 0 for cos θm ≤ 0.
//! ```
//!
//! | type | `D(wm)` | parameters |
//! |---|---|---|
//! | [`BlinnPhong`] | `(s + 2)/(2π) cosˢ θm` | shininess `s ∈ [0, MAX_SHININESS]` |
//! | [`Beckmann`] | `exp(−(x²/αx² + y²/αy²)/z²) / (π αx αy z⁴)` | `alpha_x, alpha_y ∈ [MIN_ALPHA, MAX_ALPHA]` |
//! | [`Ggx`] (Trowbridge-Reitz) | `1 / (π αx αy (x²/αx² + y²/αy² + z²)²)` | `alpha_x, alpha_y ∈ [MIN_ALPHA, MAX_ALPHA]` |
//! | [`GgxIsotropic`] | the same with `αx = αy = α`, specialized | `alpha ∈ [MIN_ALPHA, MAX_ALPHA]` |
//! | [`AshikhminShirleyLobe`] | `√((nu + 2)(nv + 2))/(2π) cos^e θm`, `e = (nu x² + nv y²)/(x² + y²)` | `nu, nv ∈ [0, MAX_SHININESS]` |
//!
//! (`wm = (x, y, z)` in the local frame, `z = cos θm`.) Each type is generic over
//! [`Real`] and stores its per-material constants (`1/αx²`, `1/(π αx αy)`, the normalization
//! factor) already splatted to lanes, so [`Ndf::d`] is a handful of multiplies.
//!
//! # Minimum `alpha`
//!
//! Constructors accept `alpha ∈ [1e-4, 1]` ([`MIN_ALPHA`], [`MAX_ALPHA`]). The lower bound is
//! the one pbrt-v4 (`TrowbridgeReitzDistribution`) and Mitsuba 3 (`MicrofacetDistribution`)
//! clamp to: below it the lobe is narrower than the angular resolution of an `f32` half vector
//! near the normal (`cos θ` has a spacing of 6e-8, i.e. `θ` steps of ~3.5e-4), the peak
//! `1/(π α²)` passes 3·10⁷ and a renderer should switch to a delta (mirror) lobe. Everything
//! in this module and in [`crate::masking`] is tested finite for `alpha = 1e-4` on `f32`.
//! The upper bound 1 is the range over which the fast masking approximations and the
//! conversions ([`beckmann_alpha_to_shininess`]) are defined and tested; `alpha > 1` is not
//! a physically meaningful roughness for these models. Shininess is capped at
//! [`MAX_SHININESS`] `= 2/MIN_ALPHA² − 2`, the exponent whose lobe matches `MIN_ALPHA`.
//!
//! # Smith Λ
//!
//! [`Ggx`], [`GgxIsotropic`] and [`Beckmann`] implement [`SmithLambda`] (exact, anisotropic through the
//! projected roughness) and [`ProjectedAlpha`]. The Beckmann Λ needs the error function: [`erf`]
//! and [`erfc`] are lane-generic approximations whose error is stated on them.
//!
//! # Conversions
//!
//! [`beckmann_alpha_to_shininess`], [`shininess_to_beckmann_alpha`] (Walter et al. 2007),
//! [`roughness_to_alpha`], [`alpha_to_roughness`] (Burley 2012, Karis 2013) and
//! [`beckmann_alpha_to_ggx_alpha`] — with the measured distance between the matched lobes.
//!
//! # Reference-only: Blinn 1977
//!
//! [`mod@reference`] holds [`reference::blinn1977_d1`], [`reference::blinn1977_d2`] and
//! [`reference::blinn1977_d3`]: Blinn's three un-normalized distributions (peak value 1),
//! with the half-intensity constants of each. They are for comparison only and do not
//! implement [`Ndf`].
//!
//! # References
//!
//! * J. F. Blinn, "Models of light reflection for computer synthesized pictures", SIGGRAPH 1977.
//! * P. Beckmann, A. Spizzichino, *The Scattering of Electromagnetic Waves from Rough
//!   Surfaces*, Pergamon, 1963.
//! * T. S. Trowbridge, K. P. Reitz, "Average irregularity representation of a rough surface for
//!   ray reflection", JOSA 65(5), 1975.
//! * B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet models for refraction
//!   through rough surfaces", EGSR 2007.
//! * M. Ashikhmin, P. Shirley, "An anisotropic Phong BRDF model", Journal of Graphics Tools
//!   5(2), 2000.
//! * E. Heitz, "Understanding the masking-shadowing function in microfacet-based BRDFs",
//!   JCGT 3(2), 2014.

use crate::error::{self, Error};
use crate::real::{Splat, splat_scalar};
use crate::{Real, Scalar, Vec3};

/// Implements [`Splat`] for an NDF whose fields are all numbers.
macro_rules! splat_ndf {
    ($t:ident { $($f:ident),* $(,)? }) => {
        impl<S: Scalar> Splat for $t<S> {
            type On<L: Real> = $t<L>;
            #[inline]
            fn splat<L: Real>(&self) -> $t<L> {
                $t { $($f: splat_scalar(self.$f)),* }
            }
        }
    };
}

/// A microfacet normal distribution function.
///
/// `D(wm)` is the density of microfacet normals per unit solid angle, in sr⁻¹, normalized
/// so that `∫ D(wm) cos θm dωm = 1` over the hemisphere, and zero for `wm.z ≤ 0`.
pub trait Ndf<R: Real> {
    /// `D(wm)` for a unit `wm` in the local frame.
    fn d(&self, wm: Vec3<R>) -> R;

    /// `D(wm)` as a fraction `(numerator, denominator)`, given also the unnormalized half
    /// vector `h = wi + wo` (same direction as `wm`) and `len2 = h·h`.
    ///
    /// A Cook-Torrance body multiplies `D` by the visibility and divides once
    /// (`(dₙ vₙ)/(d_d v_d)`, see [`crate::masking::Masking::visibility_fraction`]), and an NDF
    /// that can be written on `h` directly spares the normalization of the half vector: after
    /// inlining, whatever an implementation does not use is never computed. The default is
    /// `(d(wm), 1)`; [`Ggx`] overrides it with `(norm·len2², (x²/αx² + y²/αy² + z²)²)` on `h`,
    /// which is `D(h/|h|)` exactly and needs neither a square root nor a division. The
    /// denominator is `≥ 0`, and may be `0` (at `h = 0`): a caller clamps the product of
    /// the denominators it divides by.
    #[inline(always)]
    fn d_fraction(&self, wm: Vec3<R>, h: Vec3<R>, len2: R) -> (R, R) {
        let _ = (h, len2);
        (self.d(wm), R::one())
    }
}

/// An NDF with a closed-form Smith auxiliary function Λ (Heitz 2014, eq. 72–86), from which
/// the Smith masking terms of [`crate::masking`] are built.
pub trait SmithLambda<R: Real>: Ndf<R> {
    /// `Λ(w)`: `G1(w) = 1 / (1 + Λ(w))`. Zero at normal incidence, `+∞`-free: at grazing
    /// incidence it returns a large finite value or the limit handled by the caller.
    fn lambda(&self, w: Vec3<R>) -> R;

    /// `cos θ · Λ(w)`, which stays finite (and has a finite nonzero limit) at grazing
    /// incidence where `Λ` itself diverges. The visibility terms of [`crate::masking`] are
    /// built on it: `V = 1 / (4 (cos θi cos θo + cos θo·cosΛ(wi) + cos θi·cosΛ(wo)))`.
    ///
    /// The default body is `max(|cos θ|, 1e-15) · Λ(w)`, which has the right grazing limit for
    /// an NDF whose `Λ` floors `cos θ` at 1e-15 as [`Ggx`] and [`Beckmann`] do (so a wrapper
    /// that forwards only [`SmithLambda::lambda`] still gets it); those two override it with
    /// forms that need no floor.
    #[inline(always)]
    fn cos_lambda(&self, w: Vec3<R>) -> R {
        w.z.abs().max(R::from_f64(COS_FLOOR)) * self.lambda(w)
    }

    /// The Smith masking function without the microfacet visibility indicator,
    /// `G1(w) = 1 / (1 + Λ(w))` (Heitz 2014, Smith masking function), in `[0, 1]`.
    #[inline(always)]
    fn g1(&self, w: Vec3<R>) -> R {
        (R::one() + self.lambda(w)).recip()
    }

    /// `2 cos θi cos θo (1 + Λ(wi) + Λ(wo))`, the denominator of the height-correlated
    /// visibility `V = 1/(2·sum)` (Filament's `λV + λL`), for `wi`, `wo` in the upper
    /// hemisphere; below it the value is unspecified (the callers mask by the horizon).
    ///
    /// ```text
    /// sum = 2 (cos θi cos θo + cos θo·cosΛ(wi) + cos θi·cosΛ(wo))
    /// ```
    ///
    /// The default body is that sum (cosines clamped at 0); [`Ggx`] overrides it with the
    /// algebraically equal `cos θo √(cos²θi + sᵢ) + cos θi √(cos²θo + sₒ)`,
    /// `s = x²αx² + y²αy²`, which needs no division (the `cos θ·cos θ` terms cancel exactly)
    /// — two square roots instead of two square roots and two divisions on the hottest path
    /// of a GGX Cook-Torrance. (It replaces `height_correlated_den`, half of this sum with
    /// the cosines clamped: the factor ½ and the clamps cost three operations per evaluation
    /// on that path.)
    #[inline(always)]
    fn height_correlated_sum(&self, wi: Vec3<R>, wo: Vec3<R>) -> R {
        let (ci, co) = (wi.z.max(R::zero()), wo.z.max(R::zero()));
        let den = ci * co + co * self.cos_lambda(wi) + ci * self.cos_lambda(wo);
        den + den
    }

    /// `cos θ (1 + Λ(w)) = cos θ / G1(w)` for `w` in the upper hemisphere (cosine clamped at
    /// 0): one factor of the separable visibility `V = 1/(4·den(wi)·den(wo))`.
    ///
    /// The default body is `cos θ + cosΛ(w)`; [`Ggx`] overrides it with the algebraically
    /// equal, division-free `(cos θ + √(cos²θ + s))/2`, `s = x²αx² + y²αy²`.
    #[inline(always)]
    fn separable_den(&self, w: Vec3<R>) -> R {
        w.z.max(R::zero()) + self.cos_lambda(w)
    }
}

/// An NDF that can report the isotropic slope parameter `alpha` seen from direction `w`
/// (the projected roughness for anisotropic NDFs), used by the approximate masking terms
/// (Schlick-GGX `k = alpha/2`, Hammon's and Filament's height-correlated fits).
pub trait ProjectedAlpha<R: Real>: Ndf<R> {
    /// `alpha` projected on the plane of `w`: `√(cos²φ αx² + sin²φ αy²)`.
    fn projected_alpha(&self, w: Vec3<R>) -> R;
}

/// Smallest `alpha` the constructors accept (see the module docs for why).
pub const MIN_ALPHA: f64 = 1e-4;
/// Largest `alpha` the constructors accept.
pub const MAX_ALPHA: f64 = 1.0;
/// Largest Blinn-Phong / Ashikhmin-Shirley exponent accepted: `2/MIN_ALPHA² − 2`, the
/// shininess whose lobe matches the narrowest Beckmann lobe ([`beckmann_alpha_to_shininess`]).
pub const MAX_SHININESS: f64 = 2.0 / (MIN_ALPHA * MIN_ALPHA) - 2.0;

/// Floor of `|cos θ|` inside `Λ` (so `Λ` is finite at grazing): `√(1e-30)`.
const COS_FLOOR: f64 = 1e-15;

/// A denominator floor far below anything a valid input produces, far above the `f32`
/// subnormal range: keeps `0/0` and `x/0` out of the formulas at exactly grazing angles
/// and for the degenerate half vector `wm = 0`.
#[inline(always)]
pub(crate) fn tiny<R: Real>() -> R {
    R::from_f64(1e-30)
}

fn check_lanes<R: Real>(
    param: &'static str,
    v: R,
    domain: &'static str,
    lo: f64,
    hi: f64,
) -> Result<(), Error> {
    // Compare in the lane precision so that `1e-4_f32` (which rounds below 1e-4) is accepted.
    let lo: f64 = <R::Scalar as Scalar>::of(lo).into();
    let hi: f64 = <R::Scalar as Scalar>::of(hi).into();
    for l in 0..R::LANES {
        error::check(param, v.lane(l), domain, |x| (lo..=hi).contains(&x))?;
    }
    Ok(())
}

const ALPHA_DOMAIN: &str = "[1e-4, 1]";
const SHININESS_DOMAIN: &str = "[0, 2e8 − 2]";

// ---------------------------------------------------------------------------------------------
// GGX / Trowbridge-Reitz
// ---------------------------------------------------------------------------------------------

/// The GGX (Trowbridge-Reitz) distribution, isotropic or anisotropic.
///
/// ```text
/// D(wm) = 1 / (π αx αy (x²/αx² + y²/αy² + z²)²),        wm = (x, y, z), z > 0
///       = 1 / (π α² cos⁴θm (1 + tan²θm/α²)²)            (isotropic, the usual form)
/// Λ(w)  = (−1 + √(1 + α(w)² tan²θ)) / 2,   α(w)² = (x² αx² + y² αy²)/(x² + y²)
/// ```
///
/// The first (stretched) form is the one evaluated: no `tan²` and no division by `cos⁴`, so
/// it is finite and accurate up to `cos θm = 0`. Normalization is exact:
/// `∫ D cos θm dωm = 1` for every `alpha_x, alpha_y > 0` (tested by quadrature for
/// `alpha` from 1e-3 to 1 and anisotropy ratios up to 10).
///
/// The formulas are the functions `ggx_d`, `ggx_lambda`, … below the type in `src/ndf.rs`,
/// written on two quadratic forms of a direction; [`GgxIsotropic`] calls the same functions
/// with its cheaper forms.
///
/// Domain: `alpha_x, alpha_y ∈ [1e-4, 1]` (see the [module docs](self)); `alpha_x` is the
/// roughness along the tangent (x), `alpha_y` along the bitangent (y).
///
/// References: T. S. Trowbridge, K. P. Reitz, JOSA 1975; B. Walter et al., "Microfacet models
/// for refraction through rough surfaces", EGSR 2007 (§5, "GGX"); E. Heitz, JCGT 2014
/// (anisotropic Λ through the projected roughness).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, ndf::{Ggx, Ndf, SmithLambda}};
///
/// let ggx = Ggx::new(0.5_f64).unwrap();
/// // Peak value 1/(π α²).
/// let peak = ggx.d(Vec3::new(0.0, 0.0, 1.0));
/// assert!((peak - 1.0 / (core::f64::consts::PI * 0.25)).abs() < 1e-12);
/// // No masking at normal incidence.
/// assert_eq!(ggx.g1(Vec3::new(0.0, 0.0, 1.0)), 1.0);
/// assert!(Ggx::new(0.0_f32).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx<R> {
    alphas: Alphas<R>,
}

/// The constructors and accessors shared by the two-slope NDFs (GGX, Beckmann): `new`,
/// `anisotropic`, `from_roughness` on scalars, `from_lanes`, `alpha_x`, `alpha_y` on any
/// [`Real`]. Their formulas stay in each type's own `impl` blocks.
macro_rules! alpha_ndf_constructors {
    ($t:ident) => {
        impl<S: Scalar> $t<S> {
            /// Isotropic distribution with slope parameter `alpha ∈ [1e-4, 1]`.
            ///
            /// # Errors
            /// [`Error::NotFinite`] or [`Error::OutOfDomain`] naming `alpha`, for `alpha` outside
            /// `[1e-4, 1]`.
            #[inline]
            pub fn new(alpha: S) -> Result<Self, Error> {
                Ok(Self {
                    alphas: Alphas::isotropic(alpha)?,
                })
            }

            /// Anisotropic distribution: `alpha_x` along the tangent, `alpha_y` along the
            /// bitangent, each in `[1e-4, 1]`.
            ///
            /// # Errors
            /// [`Error::NotFinite`] or [`Error::OutOfDomain`] naming the offending parameter.
            #[inline]
            pub fn anisotropic(alpha_x: S, alpha_y: S) -> Result<Self, Error> {
                Self::from_lanes(alpha_x, alpha_y)
            }

            /// Isotropic distribution from perceptual roughness `roughness ∈ [0.01, 1]`,
            /// `alpha = roughness²` ([`roughness_to_alpha`]).
            ///
            /// # Errors
            /// As [`Self::new`] for the resulting `alpha` (so `roughness < 0.01` is rejected
            /// and reported as `alpha`).
            #[inline]
            pub fn from_roughness(roughness: S) -> Result<Self, Error> {
                Self::new(roughness * roughness)
            }
        }

        impl<R: Real> $t<R> {
            /// One (possibly different) material per lane: every lane of `alpha_x` and
            /// `alpha_y` is validated as in [`Self::anisotropic`].
            ///
            /// # Errors
            /// The first offending lane's parameter.
            #[inline]
            pub fn from_lanes(alpha_x: R, alpha_y: R) -> Result<Self, Error> {
                Ok(Self {
                    alphas: Alphas::from_lanes(alpha_x, alpha_y)?,
                })
            }

            /// Slope parameter along the tangent (x).
            #[inline]
            #[must_use]
            pub fn alpha_x(&self) -> R {
                self.alphas.alpha_x
            }

            /// Slope parameter along the bitangent (y).
            #[inline]
            #[must_use]
            pub fn alpha_y(&self) -> R {
                self.alphas.alpha_y
            }
        }
    };
}

alpha_ndf_constructors!(Ggx);

impl<R: Real> Ggx<R> {
    /// `cos²θ + x² αx² + y² αy²` of a unit `w`: the radicand of the visibility denominators.
    #[inline(always)]
    fn root2(&self, w: Vec3<R>) -> R {
        w.z * w.z + self.alphas.stretched_sin2(w)
    }
}

impl<R: Real> Ndf<R> for Ggx<R> {
    /// `ggx_d` on `x²/αx² + y²/αy²`.
    #[inline(always)]
    fn d(&self, wm: Vec3<R>) -> R {
        ggx_d(self.alphas.norm, self.alphas.slope2_cos2(wm), wm.z)
    }

    /// `x²/αx² + y²/αy² + z²` is homogeneous of degree 2, so on `h = |h|·wm` the
    /// stretched denominator is `len2` times that of `wm`:
    /// `D = norm·len2² / (stretched(h))²` (`ggx_d_fraction`).
    #[inline(always)]
    fn d_fraction(&self, _wm: Vec3<R>, h: Vec3<R>, len2: R) -> (R, R) {
        ggx_d_fraction(self.alphas.norm, self.alphas.slope2_cos2(h), h.z, len2)
    }
}

impl<R: Real> SmithLambda<R> for Ggx<R> {
    /// `Λ = (√(1 + t) − 1)/2 = t / (2 (1 + √(1 + t)))`, `t = α(w)² tan²θ`, written
    /// without cancellation; `cos θ` is floored at 1e-15 so that `Λ(grazing)` is large
    /// but finite (`ggx_lambda`).
    #[inline(always)]
    fn lambda(&self, w: Vec3<R>) -> R {
        ggx_lambda(self.alphas.stretched_sin2(w), w.z)
    }

    /// `cos θ Λ = (√(cos²θ + α(w)² sin²θ) − cos θ)/2 = s / (2 (√(cos²θ + s) + cos θ))`,
    /// `s = x² αx² + y² αy²`; `α(w) sin θ / 2` at grazing (`ggx_cos_lambda`).
    #[inline(always)]
    fn cos_lambda(&self, w: Vec3<R>) -> R {
        ggx_cos_lambda(self.alphas.stretched_sin2(w), w.z.abs())
    }

    /// `cos θo √(cos²θi + sᵢ) + cos θi √(cos²θo + sₒ)`: see
    /// [`SmithLambda::height_correlated_sum`] and `ggx_height_correlated_sum`. Unit `wi`,
    /// `wo`.
    #[inline(always)]
    fn height_correlated_sum(&self, wi: Vec3<R>, wo: Vec3<R>) -> R {
        ggx_height_correlated_sum(wi.z, wo.z, self.root2(wi), self.root2(wo))
    }

    /// `(cos θ + √(cos²θ + s))/2`: see [`SmithLambda::separable_den`] and
    /// `ggx_separable_den`. Unit `w`.
    #[inline(always)]
    fn separable_den(&self, w: Vec3<R>) -> R {
        ggx_separable_den(w.z, self.root2(w))
    }
}

impl<R: Real> ProjectedAlpha<R> for Ggx<R> {
    /// `α(w) = √((x² αx² + y² αy²)/(x² + y²))` (Heitz 2014, anisotropic Λ); at normal
    /// incidence, where it is undefined and irrelevant, `√((αx² + αy²)/2)`
    /// (`projected_alpha`).
    #[inline(always)]
    fn projected_alpha(&self, w: Vec3<R>) -> R {
        projected_alpha(self.alphas.alpha_x2, self.alphas.alpha_y2, w)
    }
}

impl<S: Scalar> Splat for Ggx<S> {
    type On<L: Real> = Ggx<L>;
    #[inline]
    fn splat<L: Real>(&self) -> Ggx<L> {
        Ggx {
            alphas: self.alphas.splat(),
        }
    }
}

/// GGX `D` from the stretched quadratic form `q = x²/αx² + y²/αy²` of `v = (x, y, z)`:
///
/// ```text
/// D = norm / (q + z²)²,    norm = 1/(π αx αy);    0 for z ≤ 0
/// ```
///
/// For a unit `v` this is [`Ggx`]'s `D(v)`; the denominator is floored at 1e-30 (the
/// degenerate `v = 0`). Walter et al. 2007 eq. 33, in the stretched form of Heitz 2014.
#[inline(always)]
fn ggx_d<R: Real>(norm: R, q: R, z: R) -> R {
    let den = q + z * z;
    let d = norm / (den * den).max(tiny());
    R::select(z.gt(R::zero()), d, R::zero())
}

/// GGX `D` on the unnormalized half vector `h = wi + wo` (`len2 = h·h`), as a fraction:
///
/// ```text
/// D(h/|h|) = (norm · len2²) / (q_h + h_z²)²,    q_h = h_x²/αx² + h_y²/αy²;   0 for h_z ≤ 0
/// ```
///
/// exact because the denominator is homogeneous of degree 2 in `h`: no square root, no
/// division ([`Ndf::d_fraction`]). The denominator is `0` only at `h = 0` (or when `den²`
/// underflows); the caller clamps the product of its denominators (Cook-Torrance: at 1e-30).
#[inline(always)]
fn ggx_d_fraction<R: Real>(norm: R, q_h: R, h_z: R, len2: R) -> (R, R) {
    let den = h_z.mul_add(h_z, q_h);
    let num = R::select(h_z.gt(R::zero()), norm * len2 * len2, R::zero());
    (num, den * den)
}

/// GGX Smith `Λ` from `s = x² αx² + y² αy² = (α(w) sin θ)²` and `z = cos θ`:
///
/// ```text
/// Λ = (√(1 + t) − 1)/2 = t / (2 (1 + √(1 + t))),    t = s / max(z², 1e-30) = α(w)² tan²θ
/// ```
///
/// the second form without cancellation for small `t`; large but finite at grazing. Heitz
/// 2014, eq. 86 (anisotropic through α(w), §5.2).
#[inline(always)]
fn ggx_lambda<R: Real>(s: R, z: R) -> R {
    let t = s / (z * z).max(tiny());
    t / (R::from_f64(2.0) * (R::one() + (R::one() + t).sqrt()))
}

/// GGX `cos θ · Λ` from `s = (α(w) sin θ)²` and `c = |cos θ|`:
///
/// ```text
/// cos θ Λ = (√(c² + s) − c)/2 = s / (2 (√(c² + s) + c))
/// ```
///
/// finite everywhere: `√s / 2 = α(w) sin θ / 2` at grazing, 0 at normal incidence.
#[inline(always)]
fn ggx_cos_lambda<R: Real>(s: R, c: R) -> R {
    s / (R::from_f64(2.0) * ((c * c + s).sqrt() + c)).max(tiny())
}

/// The height-correlated visibility sum of GGX, from the cosines and the radicands
/// `rᵢ = cos²θi + sᵢ`, `rₒ = cos²θo + sₒ` (`s = (α(w) sin θ)²`):
///
/// ```text
/// 2 cos θi cos θo (1 + Λ(wi) + Λ(wo)) = cos θo √rᵢ + cos θi √rₒ
/// ```
///
/// (the `cos θi cos θo` terms cancel exactly, so there is no division; the form of
/// Filament's docs for Heitz 2014's height-correlated G2). Upper hemisphere only: the
/// cosines are not clamped (the callers mask by the horizon).
#[inline(always)]
fn ggx_height_correlated_sum<R: Real>(cos_i: R, cos_o: R, root2_i: R, root2_o: R) -> R {
    let (root_i, root_o) = (root2_i.sqrt(), root2_o.sqrt());
    cos_o.mul_add(root_i, cos_i * root_o)
}

/// The separable visibility factor of GGX from `cos θ` and the radicand `r = cos²θ + s`:
///
/// ```text
/// cos θ (1 + Λ(w)) = (cos θ + √r) / 2
/// ```
///
/// Cosine clamped at 0.
#[inline(always)]
fn ggx_separable_den<R: Real>(cos: R, root2: R) -> R {
    let c = cos.max(R::zero());
    (c + root2.sqrt()) * R::from_f64(0.5)
}

/// The isotropic GGX distribution: [`Ggx`] with `αx = αy = α`, specialized.
///
/// ```text
/// D(wm) = 1 / (π α² ((x² + y²)/α² + z²)²)
/// Λ(w)  = (−1 + √(1 + α² tan²θ)) / 2
/// √(cos²θ + α² sin²θ) = √(α² + (1 − α²) cos²θ)        (the visibility radicand, unit w)
/// ```
///
/// The same formula functions as [`Ggx`], called with cheaper forms: the visibility
/// radicand is one multiply-add of `cos²θ`, the projected roughness of [`ProjectedAlpha`]
/// is the constant `α` (no square root, no division), and fewer constants are live in
/// registers. A scene whose materials are all isotropic — most are — should use it; the
/// values agree with `Ggx::new(alpha)` to a few ULP (tested).
///
/// Domain: `alpha ∈ [1e-4, 1]` (see the [module docs](self)); directions are unit vectors.
///
/// References: T. S. Trowbridge, K. P. Reitz, JOSA 1975; B. Walter et al., EGSR 2007 (§5).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, ndf::{Ggx, GgxIsotropic, Ndf, SmithLambda}};
///
/// let iso = GgxIsotropic::new(0.3_f64).unwrap();
/// let ggx = Ggx::new(0.3_f64).unwrap();
/// let w = Vec3::new(0.6, 0.0, 0.8);
/// assert!((iso.d(w) - ggx.d(w)).abs() < 1e-12 * ggx.d(w));
/// assert!((iso.g1(w) - ggx.g1(w)).abs() < 1e-15);
/// assert_eq!(Ggx::from(iso), ggx);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GgxIsotropic<R> {
    alpha: R,
    alpha2: R,
    one_minus_alpha2: R,
    inv_alpha2: R,
    /// `1/(π α²)`.
    norm: R,
}

impl<S: Scalar> GgxIsotropic<S> {
    /// The distribution with slope parameter `alpha ∈ [1e-4, 1]`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfDomain`] for `alpha` outside `[1e-4, 1]`.
    #[inline]
    pub fn new(alpha: S) -> Result<Self, Error> {
        Self::from_lanes(alpha)
    }

    /// From perceptual roughness `roughness ∈ [0.01, 1]`, `alpha = roughness²`.
    ///
    /// # Errors
    /// As [`Self::new`] for the resulting `alpha`.
    #[inline]
    pub fn from_roughness(roughness: S) -> Result<Self, Error> {
        Self::new(roughness * roughness)
    }
}

impl<R: Real> GgxIsotropic<R> {
    /// One (possibly different) material per lane, each validated as in [`Self::new`].
    ///
    /// # Errors
    /// The first offending lane's `alpha`.
    #[inline]
    pub fn from_lanes(alpha: R) -> Result<Self, Error> {
        check_lanes("alpha", alpha, ALPHA_DOMAIN, MIN_ALPHA, MAX_ALPHA)?;
        let alpha2 = alpha * alpha;
        Ok(Self {
            alpha,
            alpha2,
            one_minus_alpha2: R::one() - alpha2,
            inv_alpha2: alpha2.recip(),
            norm: R::frac_1_pi() / alpha2,
        })
    }

    /// The slope parameter `α`.
    #[inline]
    #[must_use]
    pub fn alpha(&self) -> R {
        self.alpha
    }

    /// `(x² + y²)/α²` of a (possibly unnormalized) `v`.
    #[inline(always)]
    fn slope2_cos2(&self, v: Vec3<R>) -> R {
        // x² + y² as `Vec3::length_squared` forms it, so the two share the work.
        (v.x * v.x + v.y * v.y) * self.inv_alpha2
    }

    /// `(x² + y²) α²` = `(α sin θ)²` of a unit `w`.
    #[inline(always)]
    fn stretched_sin2(&self, w: Vec3<R>) -> R {
        (w.x * w.x + w.y * w.y) * self.alpha2
    }

    /// `cos²θ + α² sin²θ = α² + (1 − α²) cos²θ` for a unit `w`.
    #[inline(always)]
    fn root2(&self, w: Vec3<R>) -> R {
        (w.z * w.z).mul_add(self.one_minus_alpha2, self.alpha2)
    }
}

impl<R: Real> Ndf<R> for GgxIsotropic<R> {
    /// `ggx_d` on `(x² + y²)/α²`.
    #[inline(always)]
    fn d(&self, wm: Vec3<R>) -> R {
        ggx_d(self.norm, self.slope2_cos2(wm), wm.z)
    }

    /// `ggx_d_fraction` on `(h_x² + h_y²)/α²`.
    #[inline(always)]
    fn d_fraction(&self, _wm: Vec3<R>, h: Vec3<R>, len2: R) -> (R, R) {
        ggx_d_fraction(self.norm, self.slope2_cos2(h), h.z, len2)
    }
}

impl<R: Real> SmithLambda<R> for GgxIsotropic<R> {
    /// `ggx_lambda` on `s = (x² + y²) α²`.
    #[inline(always)]
    fn lambda(&self, w: Vec3<R>) -> R {
        ggx_lambda(self.stretched_sin2(w), w.z)
    }

    /// `ggx_cos_lambda` on `s = (x² + y²) α²`.
    #[inline(always)]
    fn cos_lambda(&self, w: Vec3<R>) -> R {
        ggx_cos_lambda(self.stretched_sin2(w), w.z.abs())
    }

    /// `ggx_height_correlated_sum` on the radicands `α² + (1 − α²) cos²θ`.
    #[inline(always)]
    fn height_correlated_sum(&self, wi: Vec3<R>, wo: Vec3<R>) -> R {
        ggx_height_correlated_sum(wi.z, wo.z, self.root2(wi), self.root2(wo))
    }

    /// `ggx_separable_den` on the radicand `α² + (1 − α²) cos²θ`.
    #[inline(always)]
    fn separable_den(&self, w: Vec3<R>) -> R {
        ggx_separable_den(w.z, self.root2(w))
    }
}

impl<R: Real> ProjectedAlpha<R> for GgxIsotropic<R> {
    /// `α`, whatever `w`.
    #[inline(always)]
    fn projected_alpha(&self, _w: Vec3<R>) -> R {
        self.alpha
    }
}

splat_ndf!(GgxIsotropic {
    alpha,
    alpha2,
    one_minus_alpha2,
    inv_alpha2,
    norm
});

impl<R: Real> From<GgxIsotropic<R>> for Ggx<R> {
    /// The same distribution as an (anisotropic-capable) [`Ggx`] with `αx = αy = α`.
    #[inline]
    fn from(iso: GgxIsotropic<R>) -> Self {
        Ggx {
            alphas: Alphas::from_valid(iso.alpha, iso.alpha),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Beckmann
// ---------------------------------------------------------------------------------------------

/// The Beckmann distribution, isotropic or anisotropic.
///
/// ```text
/// D(wm) = exp(−(x²/αx² + y²/αy²)/z²) / (π αx αy z⁴),     wm = (x, y, z), z > 0
///       = exp(−tan²θm/α²) / (π α² cos⁴θm)                  (isotropic)
/// Λ(w)  = (erf(a) − 1)/2 + exp(−a²)/(2 a √π),   a = 1/(α(w) tan θ)
/// ```
///
/// `alpha` is the RMS slope (√2 times the standard deviation of each slope component).
/// Normalization is exact. At `z < 1e-3`, `exp(−tan²θm/α²) < e^(−10⁶)` underflows to 0 for
/// every accepted `alpha ≤ 1`, so `z` is floored there to keep `0/0` out of the result.
///
/// Λ uses [`erfc`] (relative error < 1.2e-7), so `G1 = 1/(1 + Λ)` is within 1e-7 of exact.
/// The formulas are the functions `beckmann_d`, `beckmann_cos_lambda` below the type in
/// `src/ndf.rs`.
///
/// Domain: `alpha_x, alpha_y ∈ [1e-4, 1]` (see the [module docs](self)).
///
/// References: P. Beckmann, A. Spizzichino 1963; B. Walter et al., EGSR 2007 (§5, Beckmann);
/// E. Heitz, JCGT 2014 (Beckmann Λ; anisotropic via the projected roughness).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, ndf::{Beckmann, Ndf, SmithLambda}};
///
/// let b = Beckmann::anisotropic(0.2_f64, 0.4).unwrap();
/// let peak = b.d(Vec3::new(0.0, 0.0, 1.0));
/// assert!((peak - 1.0 / (core::f64::consts::PI * 0.08)).abs() < 1e-9);
/// let grazing = Vec3::new(1.0, 0.0, 0.0);
/// assert!(b.d(grazing) == 0.0 && b.g1(grazing) < 1e-10);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beckmann<R> {
    alphas: Alphas<R>,
}

alpha_ndf_constructors!(Beckmann);

impl<R: Real> Ndf<R> for Beckmann<R> {
    /// `beckmann_d` on `x²/αx² + y²/αy²`.
    #[inline(always)]
    fn d(&self, wm: Vec3<R>) -> R {
        beckmann_d(self.alphas.norm, self.alphas.slope2_cos2(wm), wm.z)
    }
}

impl<R: Real> SmithLambda<R> for Beckmann<R> {
    /// `Λ = cosΛ / cos θ` ([`SmithLambda::cos_lambda`]) with `cos θ` floored at 1e-15:
    /// large but finite at grazing.
    #[inline(always)]
    fn lambda(&self, w: Vec3<R>) -> R {
        self.cos_lambda(w) / w.z.abs().max(R::from_f64(COS_FLOOR))
    }

    /// `cos θ Λ = (α(w) sin θ e^(−a²)/√π − cos θ erfc(a)) / 2`, `a = cos θ/(α(w) sin θ)`;
    /// `α(w) sin θ/(2√π)` at grazing, 0 at normal incidence (`beckmann_cos_lambda`).
    #[inline(always)]
    fn cos_lambda(&self, w: Vec3<R>) -> R {
        beckmann_cos_lambda(w.z.abs(), self.alphas.stretched_sin2(w).sqrt())
    }
}

impl<R: Real> ProjectedAlpha<R> for Beckmann<R> {
    /// `α(w) = √((x² αx² + y² αy²)/(x² + y²))` (Heitz 2014, anisotropic Λ); at normal
    /// incidence, where it is undefined and irrelevant, `√((αx² + αy²)/2)`
    /// (`projected_alpha`).
    #[inline(always)]
    fn projected_alpha(&self, w: Vec3<R>) -> R {
        projected_alpha(self.alphas.alpha_x2, self.alphas.alpha_y2, w)
    }
}

impl<S: Scalar> Splat for Beckmann<S> {
    type On<L: Real> = Beckmann<L>;
    #[inline]
    fn splat<L: Real>(&self) -> Beckmann<L> {
        Beckmann {
            alphas: self.alphas.splat(),
        }
    }
}

/// Beckmann `D` from the stretched quadratic form `q = x²/αx² + y²/αy²` and `z = cos θm`:
///
/// ```text
/// D = norm · exp(−q/z²) / z⁴,    norm = 1/(π αx αy);    0 for z ≤ 0
/// ```
///
/// with `z` floored at 1e-3 (where the exponential has underflowed to 0 for every accepted
/// `alpha`; see [`Beckmann`]). Walter et al. 2007 eq. 25, in stretched form.
#[inline(always)]
fn beckmann_d<R: Real>(norm: R, q: R, z: R) -> R {
    let zf = z.max(R::from_f64(1e-3));
    let inv_z2 = (zf * zf).recip();
    let e = (-(q * inv_z2)).exp();
    let d = norm * e * inv_z2 * inv_z2;
    R::select(z.gt(R::zero()), d, R::zero())
}

/// `cos θ · Λ_Beckmann` from `c = |cos θ|` and `σ = α(w) sin θ`:
///
/// ```text
/// cos θ Λ = (σ e^(−a²)/√π − c erfc(a)) / 2,    a = c/σ
/// ```
///
/// clamped at 0 against rounding (Heitz 2014, eq. 80, multiplied by `cos θ` so that it stays
/// finite at grazing: `σ/(2√π)` there).
#[inline(always)]
fn beckmann_cos_lambda<R: Real>(c: R, sigma: R) -> R {
    let a = c / sigma.max(tiny());
    let e = (-(a * a)).exp();
    let v = (sigma * e * R::from_f64(FRAC_1_SQRT_PI) - c * erfc_nonneg(a)) * R::from_f64(0.5);
    v.max(R::zero())
}

const FRAC_1_SQRT_PI: f64 = core::f64::consts::FRAC_2_SQRT_PI * 0.5;

// ---------------------------------------------------------------------------------------------
// The slope parameters of GGX and Beckmann
// ---------------------------------------------------------------------------------------------

/// The per-material constants of a distribution with slope parameters `αx`, `αy` ([`Ggx`],
/// [`Beckmann`]) and the two quadratic forms of a direction `v = (x, y, z)` their formulas
/// are written on:
///
/// ```text
/// slope2_cos2(v)    = x²/αx² + y²/αy²      (= cos²θ tan²θ / α(v)² for a unit v)
/// stretched_sin2(w) = x² αx² + y² αy²      (= (α(w) sin θ)², Heitz 2014 §5.2)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
struct Alphas<R> {
    alpha_x: R,
    alpha_y: R,
    alpha_x2: R,
    alpha_y2: R,
    inv_alpha_x2: R,
    inv_alpha_y2: R,
    /// `1/(π αx αy)`.
    norm: R,
}

splat_ndf!(Alphas {
    alpha_x,
    alpha_y,
    alpha_x2,
    alpha_y2,
    inv_alpha_x2,
    inv_alpha_y2,
    norm
});

impl<R: Real> Alphas<R> {
    /// `alpha_x`, `alpha_y ∈ [1e-4, 1]` in every lane, each named in the error.
    #[inline]
    fn from_lanes(alpha_x: R, alpha_y: R) -> Result<Self, Error> {
        check_lanes("alpha_x", alpha_x, ALPHA_DOMAIN, MIN_ALPHA, MAX_ALPHA)?;
        check_lanes("alpha_y", alpha_y, ALPHA_DOMAIN, MIN_ALPHA, MAX_ALPHA)?;
        Ok(Self::from_valid(alpha_x, alpha_y))
    }

    /// One `alpha ∈ [1e-4, 1]` for both axes, named `alpha` in the error.
    #[inline]
    fn isotropic(alpha: R) -> Result<Self, Error> {
        check_lanes("alpha", alpha, ALPHA_DOMAIN, MIN_ALPHA, MAX_ALPHA)?;
        Ok(Self::from_valid(alpha, alpha))
    }

    /// The constants of already validated slope parameters.
    #[inline]
    fn from_valid(alpha_x: R, alpha_y: R) -> Self {
        let (alpha_x2, alpha_y2) = (alpha_x * alpha_x, alpha_y * alpha_y);
        Self {
            alpha_x,
            alpha_y,
            alpha_x2,
            alpha_y2,
            inv_alpha_x2: alpha_x2.recip(),
            inv_alpha_y2: alpha_y2.recip(),
            norm: R::frac_1_pi() / (alpha_x * alpha_y),
        }
    }

    /// `x²/αx² + y²/αy²` of a (possibly unnormalized) `v`.
    #[inline(always)]
    fn slope2_cos2(&self, v: Vec3<R>) -> R {
        (v.x * v.x).mul_add(self.inv_alpha_x2, v.y * v.y * self.inv_alpha_y2)
    }

    /// `x² αx² + y² αy²` = `(α(w) sin θ)²` of a unit `w`.
    #[inline(always)]
    fn stretched_sin2(&self, w: Vec3<R>) -> R {
        (w.x * w.x).mul_add(self.alpha_x2, w.y * w.y * self.alpha_y2)
    }
}

/// The projected roughness `α(w)` of slope parameters `αx`, `αy` (given squared):
///
/// ```text
/// α(w) = √((x² αx² + y² αy²)/(x² + y²));    √((αx² + αy²)/2) where x² + y² ≤ 1e-30
/// ```
///
/// (at normal incidence it is undefined and irrelevant). Heitz 2014, §5.2.
#[inline(always)]
fn projected_alpha<R: Real>(alpha_x2: R, alpha_y2: R, w: Vec3<R>) -> R {
    let sin2 = w.x * w.x + w.y * w.y;
    let normal = sin2.le(tiny());
    let stretched = w.x * w.x * alpha_x2 + w.y * w.y * alpha_y2;
    let a2 = R::select(
        normal,
        (alpha_x2 + alpha_y2) * R::from_f64(0.5),
        stretched / sin2.max(tiny()),
    );
    a2.sqrt()
}

// ---------------------------------------------------------------------------------------------
// Error function
// ---------------------------------------------------------------------------------------------

/// `erfc(x)` for `x ≥ 0` (Numerical Recipes `erfcc`, relative error < 1.2e-7).
#[inline(always)]
fn erfc_nonneg<R: Real>(x: R) -> R {
    // t = 1/(1 + x/2); erfc(x) ≈ t exp(−x² + P(t)), P a degree-9 Chebyshev-fitted polynomial.
    const P: [f64; 10] = [
        -1.265_512_23,
        1.000_023_68,
        0.374_091_96,
        0.096_784_18,
        -0.186_288_06,
        0.278_868_07,
        -1.135_203_98,
        1.488_515_87,
        -0.822_152_23,
        0.170_872_77,
    ];
    let t = (R::one() + R::from_f64(0.5) * x).recip();
    let mut p = R::from_f64(P[9]);
    for &c in P[..9].iter().rev() {
        p = p.mul_add(t, R::from_f64(c));
    }
    t * (p - x * x).exp()
}

/// Complementary error function `erfc(x) = 1 − erf(x) = (2/√π) ∫ₓ^∞ e^(−t²) dt`, on lanes.
///
/// ```text
/// erfc(x) ≈ t · exp(−x² + P(t)),   t = 1/(1 + x/2),   x ≥ 0     (P: degree 9)
/// erfc(x) = 2 − erfc(−x),                             x < 0
/// ```
///
/// Relative error < 1.2e-7 for every `x ≥ 0` (the bound stated by Numerical Recipes for this
/// Chebyshev fit; measured in `tests/masking.rs` against an independent series/continued
/// fraction: worst 1.07e-7 relative on `[0, 26]` in `f64`). The relative accuracy holds in the
/// tail, so `erfc(10) ≈ 2.1e-45` is resolved (on `f64`; it underflows `f32`). On `f32` the
/// rounding of `x²` inside `exp` adds about `x²·2⁻²⁴` relative (7.3e-6 measured on `[0, 9]`).
/// For `x < 0` the absolute error is < 2.4e-7 (8.3e-8 measured). Finite for every finite `x`;
/// `erfc(+∞) = 0`, `erfc(−∞) = 2`.
///
/// Reference: W. H. Press, S. A. Teukolsky, W. T. Vetterling, B. P. Flannery, *Numerical
/// Recipes in C*, 2nd ed., 1992, §6.2 (`erfcc`).
///
/// # Examples
///
/// ```
/// use brdf::ndf::erfc;
/// assert!((erfc(1.0_f64) - 0.157_299_207_050_285_1).abs() < 2e-8);
/// ```
#[inline]
#[must_use]
pub fn erfc<R: Real>(x: R) -> R {
    let y = erfc_nonneg(x.abs());
    R::select(x.ge(R::zero()), y, R::from_f64(2.0) - y)
}

/// Error function `erf(x) = (2/√π) ∫₀ˣ e^(−t²) dt`, on lanes.
///
/// ```text
/// |x| < 1/2:  erf(x) = (2/√π) Σₙ₌₀⁷ (−1)ⁿ x²ⁿ⁺¹ / (n! (2n + 1))     (Taylor, truncation < 3e-11 rel.)
/// |x| ≥ 1/2:  erf(x) = sign(x) (1 − erfc(|x|))                     (see [`erfc`])
/// ```
///
/// Relative error < 1.2e-7 everywhere in `f64` (5.8e-8 measured; the Taylor branch keeps it
/// relative near 0, where `1 − erfc` would lose it). Odd, finite, `erf(±∞) = ±1`.
///
/// Reference: M. Abramowitz, I. Stegun, *Handbook of Mathematical Functions*, 1964, eq. 7.1.5
/// (series); [`erfc`] for the rest.
///
/// # Examples
///
/// ```
/// use brdf::{f32x4, ndf::erf};
/// assert!((erf(0.25_f64) - 0.276_326_390_168_236_9).abs() < 1e-12);
/// assert!((erf(0.5_f64) - 0.520_499_877_813_046_5).abs() < 1e-7);
/// assert!((erf(f32x4::splat(-2.0)).to_array()[0] + 0.995_322_3).abs() < 1e-6);
/// ```
#[inline]
#[must_use]
pub fn erf<R: Real>(x: R) -> R {
    // Taylor coefficients (2/√π)(−1)ⁿ/(n!(2n+1)), n = 0..7.
    const T: [f64; 8] = [
        core::f64::consts::FRAC_2_SQRT_PI,
        -0.376_126_389_031_837_5,
        0.112_837_916_709_551_26,
        -0.026_866_170_645_131_25,
        0.005_223_977_625_442_187,
        -8.548_327_023_450_852e-4,
        1.205_533_298_178_967e-4,
        -1.492_565_035_840_625e-5,
    ];
    let ax = x.abs();
    let x2 = x * x;
    let mut s = R::from_f64(T[7]);
    for &c in T[..7].iter().rev() {
        s = s.mul_add(x2, R::from_f64(c));
    }
    let small = s * x;
    let big = R::one() - erfc_nonneg(ax);
    let big = R::select(x.lt(R::zero()), -big, big);
    R::select(ax.lt(R::from_f64(0.5)), small, big)
}

// ---------------------------------------------------------------------------------------------
// Blinn-Phong
// ---------------------------------------------------------------------------------------------

/// The normalized Blinn-Phong distribution.
///
/// ```text
/// D(wm) = (s + 2)/(2π) · cosˢ θm,     cos θm > 0
/// ```
///
/// Normalization is exact: `∫ cosˢ θ cos θ dω = 2π/(s + 2)`. (The seed's `(s + 2)/(8π)` is the
/// *BRDF* normalization of the Blinn-Phong model, which adds the `1/(4 cos θd)`-like factors;
/// see [`crate::normalization`].) Domain: shininess `s ∈ [0, 2·10⁸]`
/// ([`MAX_SHININESS`]); `s = 0` is the cosine distribution `1/π`.
///
/// Blinn-Phong has no closed-form Smith Λ; Walter et al. 2007 pair it with the Beckmann Λ at
/// `alpha = √(2/(s + 2))` ([`shininess_to_beckmann_alpha`]), which a caller can do with
/// [`Beckmann`].
///
/// References: J. F. Blinn, SIGGRAPH 1977 (`D1 = cosᶜ`); B. Walter et al., EGSR 2007 (§5, Phong).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, ndf::{BlinnPhong, Ndf}};
/// let bp = BlinnPhong::new(100.0_f32).unwrap();
/// let peak = bp.d(Vec3::new(0.0, 0.0, 1.0));
/// assert!((peak - 102.0 / (2.0 * core::f32::consts::PI)).abs() < 1e-4);
/// assert!(BlinnPhong::new(-1.0_f32).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlinnPhong<R> {
    shininess: R,
    /// `(s + 2)/(2π)`.
    norm: R,
}

impl<S: Scalar> BlinnPhong<S> {
    /// Distribution with exponent `shininess ∈ [0, 2·10⁸]`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] / [`Error::OutOfDomain`] for `shininess` outside the domain.
    #[inline]
    pub fn new(shininess: S) -> Result<Self, Error> {
        Self::from_lanes(shininess)
    }
}

impl<R: Real> BlinnPhong<R> {
    /// One (possibly different) exponent per lane, each validated as in [`Self::new`].
    ///
    /// # Errors
    /// As [`Self::new`], for the first offending lane.
    #[inline]
    pub fn from_lanes(shininess: R) -> Result<Self, Error> {
        check_lanes("shininess", shininess, SHININESS_DOMAIN, 0.0, MAX_SHININESS)?;
        let norm = crate::normalization::blinn_phong_ndf(shininess);
        Ok(Self { shininess, norm })
    }

    /// The exponent `s`.
    #[inline]
    #[must_use]
    pub fn shininess(&self) -> R {
        self.shininess
    }
}

impl<R: Real> Ndf<R> for BlinnPhong<R> {
    #[inline(always)]
    fn d(&self, wm: Vec3<R>) -> R {
        let d = self.norm * wm.z.max(R::zero()).pow(self.shininess);
        R::select(wm.z.gt(R::zero()), d, R::zero())
    }
}

splat_ndf!(BlinnPhong { shininess, norm });

// ---------------------------------------------------------------------------------------------
// Ashikhmin-Shirley
// ---------------------------------------------------------------------------------------------

/// The Ashikhmin-Shirley exponent `e = (nu x² + nv y²)/(x² + y²)` of a unit half vector
/// `wm = (x, y, z)`; `(nu + nv)/2` where `x² + y² ≤ 1e-30` (at the pole any `e` gives
/// `cos^e θ = 1`). Shared by [`AshikhminShirleyLobe`] and the model [`crate::models::AshikhminShirley`].
#[inline(always)]
pub(crate) fn ashikhmin_shirley_exponent<R: Real>(nu: R, nv: R, wm: Vec3<R>) -> R {
    let (x2, y2) = (wm.x * wm.x, wm.y * wm.y);
    let sin2 = x2 + y2;
    R::select(
        sin2.gt(tiny()),
        nu.mul_add(x2, nv * y2) / sin2.max(tiny()),
        (nu + nv) * R::from_f64(0.5),
    )
}

/// The anisotropic Phong lobe of Ashikhmin and Shirley, normalized as an NDF.
///
/// ```text
/// D(wm) = √((nu + 2)(nv + 2))/(2π) · cos^e θm,    e = (nu x² + nv y²)/(x² + y²)
///                                                    = nu cos²φm + nv sin²φm
/// ```
///
/// **Normalization (exact).** `∫ cos^e θ cos θ dω = ∫₀^{2π} dφ/(e(φ) + 2)
/// = ∫₀^{2π} dφ/((nu + 2) cos²φ + (nv + 2) sin²φ) = 2π/√((nu + 2)(nv + 2))`, so the factor
/// above makes `∫ D cos θm dωm = 1` exactly for every `nu, nv` (tested by quadrature).
///
/// **The paper's factor.** Ashikhmin and Shirley use `√((nu + 1)(nv + 1))/(2π)`, which by the
/// same integral normalizes the *half-vector density* `p(wm)` (`∫ p dωm = 1`, exact; see
/// [`AshikhminShirleyLobe::half_vector_pdf`]), not the NDF: with it
/// `∫ D cos θm dωm = √((nu + 1)(nv + 1)/((nu + 2)(nv + 2)))` — 0.5 at `nu = nv = 0`,
/// 0.990 at 100, 0.9990 at 1000. (The approximate normalization in their paper is that of
/// the whole BRDF, whose `1/((h·k) max(cos θi, cos θo))` factor is not exactly integrable.)
///
/// Domain: `nu, nv ∈ [0, 2·10⁸]`; `nu` is the exponent along the tangent (x), `nv` along the
/// bitangent (y). At normal incidence `e` is undefined and irrelevant (`1ᵉ = 1`).
///
/// Reference: M. Ashikhmin, P. Shirley, "An anisotropic Phong BRDF model", Journal of
/// Graphics Tools 5(2), 2000 (the specular term and its half-vector density).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, ndf::{AshikhminShirleyLobe, Ndf}};
/// let a = AshikhminShirleyLobe::new(10.0_f64, 1000.0).unwrap();
/// let peak = a.d(Vec3::new(0.0, 0.0, 1.0));
/// assert!((peak - (12.0f64 * 1002.0).sqrt() / (2.0 * core::f64::consts::PI)).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AshikhminShirleyLobe<R> {
    nu: R,
    nv: R,
    /// `√((nu + 2)(nv + 2))/(2π)`.
    norm: R,
    /// `√((nu + 1)(nv + 1))/(2π)`.
    pdf_norm: R,
}

impl<S: Scalar> AshikhminShirleyLobe<S> {
    /// Lobe with exponents `nu` (tangent) and `nv` (bitangent), each in `[0, 2·10⁸]`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] / [`Error::OutOfDomain`] naming `nu` or `nv`.
    #[inline]
    pub fn new(nu: S, nv: S) -> Result<Self, Error> {
        Self::from_lanes(nu, nv)
    }
}

impl<R: Real> AshikhminShirleyLobe<R> {
    /// One (possibly different) pair of exponents per lane, validated as in [`Self::new`].
    ///
    /// # Errors
    /// As [`Self::new`], for the first offending lane.
    #[inline]
    pub fn from_lanes(nu: R, nv: R) -> Result<Self, Error> {
        check_lanes("nu", nu, SHININESS_DOMAIN, 0.0, MAX_SHININESS)?;
        check_lanes("nv", nv, SHININESS_DOMAIN, 0.0, MAX_SHININESS)?;
        let c = R::from_f64(0.5) * R::frac_1_pi();
        let norm = ((nu + R::from_f64(2.0)) * (nv + R::from_f64(2.0))).sqrt() * c;
        let pdf_norm = ((nu + R::one()) * (nv + R::one())).sqrt() * c;
        Ok(Self {
            nu,
            nv,
            norm,
            pdf_norm,
        })
    }

    /// Exponent along the tangent (x).
    #[inline]
    #[must_use]
    pub fn nu(&self) -> R {
        self.nu
    }

    /// Exponent along the bitangent (y).
    #[inline]
    #[must_use]
    pub fn nv(&self) -> R {
        self.nv
    }

    /// `cos^e θm` with `e = (nu x² + nv y²)/(x² + y²)`; zero below the horizon.
    #[inline(always)]
    fn lobe(&self, wm: Vec3<R>) -> R {
        let e = ashikhmin_shirley_exponent(self.nu, self.nv, wm);
        let v = wm.z.max(R::zero()).pow(e);
        R::select(wm.z.gt(R::zero()), v, R::zero())
    }

    /// The paper's half-vector density `p(wm) = √((nu + 1)(nv + 1))/(2π) · cos^e θm`
    /// (Ashikhmin & Shirley 2000, §3), normalized as `∫ p(wm) dωm = 1` (no cosine) — exact.
    /// Equals `D(wm)` up to the constant factor `√((nu + 1)(nv + 1)/((nu + 2)(nv + 2)))`.
    #[inline]
    #[must_use]
    pub fn half_vector_pdf(&self, wm: Vec3<R>) -> R {
        self.pdf_norm * self.lobe(wm)
    }
}

impl<R: Real> Ndf<R> for AshikhminShirleyLobe<R> {
    #[inline(always)]
    fn d(&self, wm: Vec3<R>) -> R {
        self.norm * self.lobe(wm)
    }
}

splat_ndf!(AshikhminShirleyLobe {
    nu,
    nv,
    norm,
    pdf_norm
});

// ---------------------------------------------------------------------------------------------
// Conversions
// ---------------------------------------------------------------------------------------------

/// Blinn-Phong shininess matching a Beckmann (or GGX) `alpha`: `s = 2/α² − 2`.
///
/// ```text
/// s = 2/α² − 2       ⇔       α = √(2/(s + 2))
/// ```
///
/// The `2/α²` matches the Gaussian fall-off near the peak (`cosˢθ ≈ e^(−sθ²/2)` vs
/// `e^(−θ²/α²)`) and the `−2` makes the peaks equal exactly: `(s + 2)/(2π) = 1/(π α²)`.
/// Measured distance between the matched lobes, in the L1 norm of the projected densities
/// `‖D_BP cos θm − D_B cos θm‖₁ = ∫ |D_BP − D_B| cos θm dωm` (0 = identical, 2 = disjoint; it
/// is twice the total-variation distance of the two microfacet-normal distributions),
/// computed by quadrature in `tests/ndf.rs`:
///
/// | α | 0.001 | 0.01 | 0.05 | 0.1 | 0.2 | 0.3 | 0.5 | 0.7 | 1 |
/// |---|---|---|---|---|---|---|---|---|---|
/// | s | 2·10⁶ | 19998 | 798 | 198 | 48 | 20.2 | 6 | 2.1 | 0 |
/// | L1 | < 1e-4 | 1e-4 | 0.0014 | 0.0054 | 0.021 | 0.047 | 0.125 | 0.228 | 0.407 |
///
/// So the pairing is close for glossy lobes (`s ≳ 50`) and poor for rough ones.
/// Domain: `alpha ∈ (0, 1]`.
///
/// Reference: B. Walter et al., EGSR 2007, §5 (the Phong distribution and its α conversion);
/// B. Karis, "Specular BRDF reference" (blog), 2013.
#[inline]
#[must_use]
pub fn beckmann_alpha_to_shininess<R: Real>(alpha: R) -> R {
    R::from_f64(2.0) / (alpha * alpha) - R::from_f64(2.0)
}

/// Beckmann `alpha` matching a Blinn-Phong shininess: `α = √(2/(s + 2))`, the inverse of
/// [`beckmann_alpha_to_shininess`] (same error table). Domain: `s ≥ 0`.
///
/// Reference: B. Walter et al., EGSR 2007, §5.
#[inline]
#[must_use]
pub fn shininess_to_beckmann_alpha<R: Real>(shininess: R) -> R {
    (R::from_f64(2.0) / (shininess + R::from_f64(2.0))).sqrt()
}

/// Slope parameter from perceptual roughness: `alpha = roughness²`.
///
/// A definition, not an approximation (exact up to one rounding): the remapping of Burley
/// (Disney 2012) adopted by UE4 (Karis 2013), Filament and glTF, which makes a linear
/// roughness slider look perceptually linear. Domain: `roughness ∈ [0, 1]`.
///
/// References: B. Burley, "Physically-based shading at Disney", SIGGRAPH 2012 course;
/// B. Karis, "Real shading in Unreal Engine 4", SIGGRAPH 2013 course.
#[inline]
#[must_use]
pub fn roughness_to_alpha<R: Real>(roughness: R) -> R {
    roughness * roughness
}

/// Perceptual roughness from the slope parameter: `roughness = √alpha`, the inverse of
/// [`roughness_to_alpha`] (exact up to rounding). Domain: `alpha ∈ [0, 1]`.
///
/// Reference: B. Burley, SIGGRAPH 2012 course.
#[inline]
#[must_use]
pub fn alpha_to_roughness<R: Real>(alpha: R) -> R {
    alpha.sqrt()
}

/// GGX `alpha` matching a Beckmann `alpha`: the identity, `α_GGX = α_Beckmann`.
///
/// With equal `alpha` the two distributions have the same peak `D(n) = 1/(π α²)` (so the
/// same highlight intensity at the mirror direction); this is the pairing of Walter et
/// al. 2007 (Fig. 6) and of most engines. GGX has a much longer tail (`D ∝ θ⁻⁴`) and a
/// narrower core. Both projected densities are functions of `slope/α` only, so their
/// distance does not depend on `α`: measured L1 distance of the projected densities (the
/// norm of [`beckmann_alpha_to_shininess`]) 0.407 for every `α`, while the best constant
/// scale `α_GGX = k α_B`, `k ≈ 0.87`, only brings it to 0.360 (`tests/ndf.rs`). No `α`
/// makes the two shapes match; the identity is kept for its exact peak.
///
/// Reference: B. Walter et al., EGSR 2007, §5.
#[inline]
#[must_use]
pub fn beckmann_alpha_to_ggx_alpha<R: Real>(alpha: R) -> R {
    alpha
}

// ---------------------------------------------------------------------------------------------
// A distribution chosen at run time
// ---------------------------------------------------------------------------------------------

/// A microfacet distribution chosen at run time: one of the NDFs with a Smith `Λ`, for a
/// model whose parts come from a file or a renderer's material table
/// ([`crate::material::Material`]).
///
/// It implements [`Ndf`], [`SmithLambda`] and [`ProjectedAlpha`] by forwarding **every**
/// method — the optimised forms ([`Ndf::d_fraction`], [`SmithLambda::height_correlated_sum`],
/// …) included — to the wrapped distribution, so a model built on `AnyNdf` evaluates exactly
/// the operations, hence the bits, of the same model built on the wrapped type
/// (`tests/material.rs` checks every method and every model). The price is one branch per
/// call on the variant, a per-material constant (the same for every lane).
///
/// Build one with `From`: `AnyNdf::from(Ggx::<f32>::new(0.3)?)`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum AnyNdf<R> {
    /// [`Ggx`] (isotropic or anisotropic).
    Ggx(Ggx<R>),
    /// [`GgxIsotropic`], the specialized isotropic GGX.
    GgxIsotropic(GgxIsotropic<R>),
    /// [`Beckmann`] (isotropic or anisotropic).
    Beckmann(Beckmann<R>),
}

/// `on_any_ndf!(self, n => n.d(wm))`: the expression on the distribution an [`AnyNdf`] holds.
macro_rules! on_any_ndf {
    ($any:expr, $n:ident => $e:expr) => {
        match $any {
            AnyNdf::Ggx($n) => $e,
            AnyNdf::GgxIsotropic($n) => $e,
            AnyNdf::Beckmann($n) => $e,
        }
    };
}
pub(crate) use on_any_ndf;

/// `From` each wrapped distribution.
macro_rules! any_ndf_from {
    ($($v:ident),*) => {
        $(impl<R> From<$v<R>> for AnyNdf<R> {
            #[inline]
            fn from(n: $v<R>) -> Self {
                AnyNdf::$v(n)
            }
        })*
    };
}
any_ndf_from!(Ggx, GgxIsotropic, Beckmann);

impl<S: Scalar> Splat for AnyNdf<S> {
    /// `true`: a `match` on the variant per pair keeps LLVM from vectorizing the batch
    /// path's one-lane loop; on explicit lanes it is one branch per register of 8 or 16
    /// pairs (the same operations, so the bits of [`crate::real::F32Fma`]).
    const EXPLICIT_LANES: bool = true;
    type On<L: Real> = AnyNdf<L>;
    #[inline]
    fn splat<L: Real>(&self) -> AnyNdf<L> {
        on_any_ndf!(self, n => AnyNdf::from(n.splat::<L>()))
    }
}

#[deny(clippy::missing_trait_methods)] // forward every hook, defaulted ones too
impl<R: Real> Ndf<R> for AnyNdf<R> {
    #[inline(always)]
    fn d(&self, wm: Vec3<R>) -> R {
        on_any_ndf!(self, n => n.d(wm))
    }

    #[inline(always)]
    fn d_fraction(&self, wm: Vec3<R>, h: Vec3<R>, len2: R) -> (R, R) {
        on_any_ndf!(self, n => n.d_fraction(wm, h, len2))
    }
}

#[deny(clippy::missing_trait_methods)] // forward every hook, defaulted ones too
impl<R: Real> SmithLambda<R> for AnyNdf<R> {
    #[inline(always)]
    fn lambda(&self, w: Vec3<R>) -> R {
        on_any_ndf!(self, n => n.lambda(w))
    }

    #[inline(always)]
    fn cos_lambda(&self, w: Vec3<R>) -> R {
        on_any_ndf!(self, n => n.cos_lambda(w))
    }

    #[inline(always)]
    fn g1(&self, w: Vec3<R>) -> R {
        on_any_ndf!(self, n => n.g1(w))
    }

    #[inline(always)]
    fn height_correlated_sum(&self, wi: Vec3<R>, wo: Vec3<R>) -> R {
        on_any_ndf!(self, n => n.height_correlated_sum(wi, wo))
    }

    #[inline(always)]
    fn separable_den(&self, w: Vec3<R>) -> R {
        on_any_ndf!(self, n => n.separable_den(w))
    }
}

#[deny(clippy::missing_trait_methods)] // forward every hook, defaulted ones too
impl<R: Real> ProjectedAlpha<R> for AnyNdf<R> {
    #[inline(always)]
    fn projected_alpha(&self, w: Vec3<R>) -> R {
        on_any_ndf!(self, n => n.projected_alpha(w))
    }
}

// ---------------------------------------------------------------------------------------------
// Reference-only distributions
// ---------------------------------------------------------------------------------------------

/// Distributions from the literature kept for comparison, not for rendering: Blinn's three
/// un-normalized distributions of 1977 (peak value 1) and the constants that give each a
/// half-intensity angle. They do not implement [`Ndf`]; their normalized
/// counterparts do (`D1` ↔ [`BlinnPhong`], `D3` ↔
/// [`Ggx`], `D2` ≈ [`Beckmann`] for small angles,
/// each relation tested in `tests/ndf.rs`).
///
/// Reference: J. F. Blinn, "Models of light reflection for computer synthesized pictures",
/// SIGGRAPH 1977.
pub mod reference {
    use super::tiny;
    use crate::Real;

    /// Blinn's first distribution (the "Phong" one), un-normalized: `D1 = cos^c1 θm`, peak 1.
    ///
    /// `theta_m` is the angle between `H` and `N` (Blinn writes α; here `alpha` is reserved for
    /// the slope parameter). Compare with [`BlinnPhong`](super::BlinnPhong), its normalized form:
    /// `D_BP = (c1 + 2)/(2π) · D1`. Domain: `cos_theta_m ∈ [0, 1]`, `c1 ≥ 0`.
    ///
    /// Reference: J. F. Blinn, "Models of light reflection for computer synthesized pictures",
    /// SIGGRAPH 1977, §"Specular reflection", D1.
    #[inline]
    #[must_use]
    pub fn blinn1977_d1<R: Real>(cos_theta_m: R, c1: R) -> R {
        cos_theta_m.max(R::zero()).pow(c1)
    }

    /// Blinn's Gaussian distribution, un-normalized: `D2 = exp(−(c2 θm)²)`, peak 1.
    ///
    /// ```text
    /// D2 = e^(−(c2 θm)²),     θm = angle between H and N (radians)
    /// ```
    ///
    /// The seed slide prints `e^(−(α c²)²)`: an OCR/slide garble of `e^(−(α c₂)²)` (the
    /// subscript became a square). Note the argument is the *angle* θm, not `tan θm` as in
    /// Beckmann: for small angles `D2 ≈ π α² D_Beckmann` with `c2 = 1/α`, and they differ at
    /// large angles. Domain: `theta_m ∈ [0, π/2]`, `c2 > 0`.
    ///
    /// Reference: J. F. Blinn, SIGGRAPH 1977, D2 (after Torrance & Sparrow 1967).
    #[inline]
    #[must_use]
    pub fn blinn1977_d2<R: Real>(theta_m: R, c2: R) -> R {
        (-(c2 * theta_m).sqr()).exp()
    }

    /// Blinn's Trowbridge-Reitz distribution, un-normalized: peak 1.
    ///
    /// ```text
    /// D3 = (c3² / (cos²θm (c3² − 1) + 1))²
    /// ```
    ///
    /// `c3` is the eccentricity of the microfacet ellipsoids (0 shiny, 1 dull). It is GGX up to
    /// a constant: `D3 = π c3² · D_GGX` with `alpha = c3` (tested). Domain: `cos_theta_m ∈ [0, 1]`,
    /// `c3 ∈ (0, 1]`.
    ///
    /// Reference: J. F. Blinn, SIGGRAPH 1977, D3; T. S. Trowbridge, K. P. Reitz, JOSA 1975.
    #[inline]
    #[must_use]
    pub fn blinn1977_d3<R: Real>(cos_theta_m: R, c3: R) -> R {
        // cos²θ (c3² − 1) + 1 = c3² cos²θ + (1 − cos θ)(1 + cos θ), without the cancellation
        // that loses the peak value for small c3.
        let c32 = c3 * c3;
        let c = cos_theta_m;
        let den = c32 * c * c + (R::one() - c) * (R::one() + c);
        (c32 / den.max(tiny())).sqr()
    }

    /// Blinn's constants from the half-intensity angle `beta` (where each of D1, D2, D3 falls to
    /// 1/2): `(c1, c2, c3)`.
    ///
    /// ```text
    /// c1 = −ln 2 / ln cos β,     c2 = √(ln 2) / β,     c3 = √((1 − cos²β) / (√2 − cos²β))
    /// ```
    ///
    /// (Solving `Dk(β) = 1/2`; Blinn quotes this parameterization in the text.) Domain:
    /// `beta ∈ (0, π/2)`.
    ///
    /// Reference: J. F. Blinn, SIGGRAPH 1977.
    #[inline]
    #[must_use]
    pub fn blinn1977_constants_from_half_angle<R: Real>(beta: R) -> (R, R, R) {
        let ln2 = R::from_f64(core::f64::consts::LN_2);
        let c = beta.cos();
        let c1 = -ln2 / c.ln();
        let c2 = ln2.sqrt() / beta;
        let c2c = c * c;
        let c3 = ((R::one() - c2c) / (R::from_f64(core::f64::consts::SQRT_2) - c2c)).sqrt();
        (c1, c2, c3)
    }
}
