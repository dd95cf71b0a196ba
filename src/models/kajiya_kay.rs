//! Kajiya-Kay's fibre (hair, fur) reflection model (1989).

use super::{
    Brdf, Energy, Kinks, Properties, Reciprocity, masked, safe_dirs, splat_channels, unit_channels,
};
use crate::Scalar;
use crate::math::f64m;
use crate::real::{Splat, splat_array, splat_scalar};
use crate::sampling::SampleBrdf;
use crate::sampling::lobes::mean;
use crate::{Error, Real, Vec3};

/// `ln Γ(x)` for `x > 0` (Stirling series after shifting `x ≥ 10`; ~1e-15 relative).
fn ln_gamma(mut x: f64) -> f64 {
    let mut shift = 0.0;
    while x < 10.0 {
        shift -= <f64 as Real>::ln(x);
        x += 1.0;
    }
    let (x2, ln2pi) = (x * x, <f64 as Real>::ln(2.0 * core::f64::consts::PI));
    let series = 1.0 / (12.0 * x) - 1.0 / (360.0 * x * x2) + 1.0 / (1260.0 * x * x2 * x2)
        - 1.0 / (1680.0 * x * x2 * x2 * x2);
    shift + (x - 0.5) * <f64 as Real>::ln(x) - x + 0.5 * ln2pi + series
}

/// `W(p) = ∫_{−π/2}^{π/2} cosᵖ u du = √π Γ((p + 1)/2) / Γ(p/2 + 1)` (Wallis integral).
#[must_use]
pub(crate) fn wallis(p: f64) -> f64 {
    <f64 as Real>::exp(
        0.5 * <f64 as Real>::ln(core::f64::consts::PI) + ln_gamma((p + 1.0) / 2.0)
            - ln_gamma(p / 2.0 + 1.0),
    )
}

/// Kajiya and Kay's reflection from a thin fibre (hair, fur) with tangent `t`.
///
/// **Tangent convention.** `t` is the fibre direction given as a unit vector *in the local
/// shading frame* (whose z is the surface or hair-card normal). It is **not** that frame's z:
/// for strands combed along a card's tangent, `t = (1, 0, 0)`. With `cᵢ = t·wi`,
/// `cₒ = t·wo`, `sᵢ = √(1 − cᵢ²)` (the sine of the angle between the fibre and `wi`),
/// `sₒ = √(1 − cₒ²)`:
///
/// ```text
/// f(wi, wo) = kd/π · sᵢ  +  ks · c(p) · max(0, sᵢ sₒ − cᵢ cₒ)^p
/// ```
///
/// * Diffuse: Kajiya-Kay's `kd sin(t, l)` — a Lambertian cylinder's radiance is
///   proportional to the sine between the fibre and the light. It is read here as a BRDF
///   with Lambert's `1/π`, so that `kd` is a reflectance (albedo ≤ `kd`). It depends on `wi`
///   only: **not reciprocal**.
/// * Specular: `cos^p` of the angle between `wo` and the cone of mirror directions around
///   `t`. With both directions pointing away from the fibre that cone is `t·wo = −t·wi`, so
///   `cos φ = sᵢ sₒ − cᵢ cₒ = cos(π − θᵢ − θₒ)` (θ measured from `t`). The paper, whose light
///   vector points towards the fibre, writes `+cᵢcₒ`. Symmetric in `wi` and `wo`.
/// * Normalization `c(p)`: the published model has none (`c = 1`, [`KajiyaKay::new`]): the
///   reflected energy changes with `p` and exceeds `ks` (and 1) for broad lobes — **not
///   energy conserving**, proved by a test. [`KajiyaKay::normalized`] uses
///   `c(p) = 1/(2π W(p))` with `W(p) = ∫ cosᵖ u du = √π Γ((p+1)/2)/Γ(p/2+1)`: the specular
///   integral over the whole sphere of directions is then at most `ks` (integrate over the
///   angle from `t` with `sin ≤ 1`, and over the azimuth about `t`), so albedo ≤ `kd + ks`.
///
/// Domain: `kd, ks ∈ [0, 1]` per channel, `p ∈ (0, 1e6]`, `t` finite and non-zero
/// (normalized by the constructor).
///
/// Reference: J. T. Kajiya, T. L. Kay, "Rendering Fur with Three Dimensional Textures",
/// SIGGRAPH 1989, §4.2.
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, KajiyaKay}};
/// let hair = KajiyaKay::new([0.0_f32], [1.0], 50.0, [1.0, 0.0, 0.0])?;
/// // Peak on the cone t·wo = −t·wi: here the mirror direction about the card normal.
/// let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.6, 0.0, 0.8));
/// assert!((hair.eval(wi, wo)[0] - 1.0).abs() < 1e-6);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KajiyaKay<R, const N: usize> {
    t: Vec3<R>,
    kd_over_pi: [R; N],
    ks_c: [R; N],
    p: R,
    normalized: bool,
}

impl<S: Scalar, const N: usize> KajiyaKay<S, N> {
    fn build(
        kd: [S; N],
        ks: [S; N],
        p: S,
        tangent: [S; 3],
        normalized: bool,
    ) -> Result<Self, Error> {
        let kd = unit_channels("kd", kd)?;
        let ks = unit_channels("ks", ks)?;
        let p: f64 = crate::error::check("p", p, "(0, 1e6]", |v| v > 0.0 && v <= 1e6)?.into();
        let mut t = [0.0f64; 3];
        for (o, v) in t.iter_mut().zip(tangent) {
            *o = crate::error::check("tangent", v, "finite", |_| true)?.into();
        }
        // Scaled by the largest component first: any nonzero tangent normalizes, the
        // subnormal ones included (their squares would underflow).
        let m = t.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if m == 0.0 {
            return Err(Error::OutOfDomain {
                param: "tangent",
                value: 0.0,
                domain: "length > 0",
            });
        }
        let t = t.map(|x| x / m);
        let len = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
        let c = if normalized {
            1.0 / (2.0 * core::f64::consts::PI * wallis(p))
        } else {
            1.0
        };
        Ok(Self {
            t: Vec3::new(
                S::from_f64(t[0] / len),
                S::from_f64(t[1] / len),
                S::from_f64(t[2] / len),
            ),
            kd_over_pi: splat_channels(kd.map(|k| k * core::f64::consts::FRAC_1_PI)),
            ks_c: splat_channels(ks.map(|k| k * c)),
            p: S::from_f64(p),
            normalized,
        })
    }

    /// The published model (no specular normalization) with diffuse `kd`, specular `ks`
    /// (per channel in `[0, 1]`), exponent `p ∈ (0, 1e6]` and fibre tangent `tangent` in
    /// the local frame (normalized here).
    ///
    /// # Errors
    /// Names `"kd"`, `"ks"`, `"p"` or `"tangent"` (non-finite or zero length).
    #[inline]
    pub fn new(kd: [S; N], ks: [S; N], p: S, tangent: [S; 3]) -> Result<Self, Error> {
        Self::build(kd, ks, p, tangent, false)
    }

    /// The energy-bounded variant: the specular is scaled by `c(p) = 1/(2π W(p))`.
    ///
    /// # Errors
    /// As [`KajiyaKay::new`].
    #[inline]
    pub fn normalized(kd: [S; N], ks: [S; N], p: S, tangent: [S; 3]) -> Result<Self, Error> {
        Self::build(kd, ks, p, tangent, true)
    }
}

impl<S: Scalar, const N: usize> Splat for KajiyaKay<S, N> {
    type On<L: Real> = KajiyaKay<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> KajiyaKay<L, N> {
        KajiyaKay {
            t: self.t.splat(),
            kd_over_pi: splat_array(&self.kd_over_pi),
            ks_c: splat_array(&self.ks_c),
            p: splat_scalar(self.p),
            normalized: self.normalized,
        }
    }
}

impl<R: Real, const N: usize> Brdf<R, N> for KajiyaKay<R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (m, wi, wo) = safe_dirs(wi, wo);
        let (ci, co) = (self.t.dot(wi), self.t.dot(wo));
        let si = (-ci).mul_add(ci, R::one()).safe_sqrt();
        let so = (-co).mul_add(co, R::one()).safe_sqrt();
        let cos_phi = si.mul_add(so, -(ci * co)).clamp(R::zero(), R::one());
        let lobe = cos_phi.pow(self.p);
        let r: [R; N] = crate::real::channels(
            #[inline(always)]
            |c| self.ks_c[c].mul_add(lobe, self.kd_over_pi[c] * si),
        );
        masked(m, r)
    }

    /// The clamp `max(0, sᵢsₒ − cᵢcₒ)`, i.e. `cos(θᵢ + θₒ) = 0` with `θ` measured from `t`:
    /// `sᵢsₒ = cᵢcₒ` needs `cᵢ` of the sign of `cₒ` and `(1 − cᵢ²) sₒ² = cᵢ² cₒ²`, so
    /// `cᵢ = sign(cₒ) sₒ` — the plane `t·wi = sign(t·wo) sₒ` (none when `cₒ = 0`, where the
    /// lobe `sᵢ` is never clamped). And `sᵢ = sin∠(wi, t)`, conical at the points `wi = ±t`.
    #[inline]
    fn kinks(&self, wo: Vec3<f64>) -> Kinks {
        let t: Vec3<f64> = Vec3::new(
            self.t.x.lane(0).into(),
            self.t.y.lane(0).into(),
            self.t.z.lane(0).into(),
        );
        let wo = wo.normalize_or_zero();
        let co = t.dot(wo);
        let so = f64m::sqrt(((1.0 - co) * (1.0 + co)).max(0.0));
        let k = Kinks::NONE.with_point(t).with_point(t.scale(-1.0));
        if co == 0.0 {
            k
        } else {
            k.with_plane(t, if co > 0.0 { so } else { -so })
        }
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::NotReciprocal {
                note: "the diffuse term kd sin(t, wi)/π depends on wi only",
            },
            energy: if self.normalized {
                Energy::ConservingWhen {
                    condition: "kd + ks ≤ 1 per channel",
                }
            } else {
                Energy::NotConserving {
                    note: "unnormalized specular: its albedo exceeds ks (and 1) for broad \
                           lobes, e.g. ks = 1, p ≤ 2",
                }
            },
        }
    }
}

/// Importance sampling of Kajiya-Kay: **cosine-weighted** (`pdf = cos θi/π`,
/// `weight = π f`), the documented choice. The specular term's mirror set is a cone about the
/// fibre tangent, not a lobe about one direction, so no simple lobe sampler matches it;
/// the cosine covers the whole hemisphere (unbiased for every `p`), is exact for the diffuse
/// term up to its `sin(t, wi)` factor, and costs one warp. For sharp highlights (large `p`)
/// the variance grows with `p`: combine with light sampling by MIS. `u[2]` is unused.
/// [`SampleBrdf::albedo_estimate`] is `mean(kd) + mean(ks c(p))`.
impl<R: Real, const N: usize> SampleBrdf<R, N> for KajiyaKay<R, N> {
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> crate::sampling::Sample<R, N> {
        crate::sampling::sample_cosine(self, wo, u)
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        crate::sampling::pdf_cosine(wo, wi)
    }

    #[inline(always)]
    fn albedo_estimate(&self, _wo: Vec3<R>) -> R {
        R::pi() * mean(self.kd_over_pi) + mean(self.ks_c)
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file description of [`KajiyaKay`]: `model = "kajiya_kay"`, re-exported from
/// [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use serde::{Deserialize, Serialize};

    use super::KajiyaKay;
    use crate::Scalar;
    use crate::material::{Material, MaterialError, ModelDesc, Rgb, invalid};

    crate::material::field_fns!(kd, ks, p, tangent, normalized);

    fn default_tangent() -> [f64; 3] {
        [1.0, 0.0, 0.0]
    }

    fn default_true() -> bool {
        true
    }

    /// [`KajiyaKay`] (Kajiya and Kay 1989): diffuse `kd`, specular `ks`, exponent
    /// `p ∈ (0, 1e6]`, the fibre direction `tangent` in the local frame (default the
    /// tangent `[1, 0, 0]`) and `normalized` (default `true`, the energy-bounded variant;
    /// `false` is the published model). Always anisotropic.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `kajiya_kay`")]
    pub struct KajiyaKayDesc {
        /// Diffuse coefficient.
        #[serde(deserialize_with = "field::kd")]
        pub kd: Rgb,
        /// Specular coefficient.
        #[serde(deserialize_with = "field::ks")]
        pub ks: Rgb,
        /// Exponent, `(0, 1e6]`.
        #[serde(deserialize_with = "field::p")]
        pub p: f64,
        /// Fibre direction in the local frame (default `[1, 0, 0]`, the tangent).
        #[serde(default = "default_tangent", deserialize_with = "field::tangent")]
        pub tangent: [f64; 3],
        /// Energy-bounded variant (default `true`); `false` is the published model.
        #[serde(default = "default_true", deserialize_with = "field::normalized")]
        pub normalized: bool,
    }

    impl ModelDesc for KajiyaKayDesc {
        const NAME: &'static str = "kajiya_kay";

        fn is_anisotropic(&self) -> bool {
            true
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let t = self.tangent.map(S::of);
            let (kd, ks, p) = (self.kd.scalars(), self.ks.scalars(), S::of(self.p));
            let m = if self.normalized {
                KajiyaKay::normalized(kd, ks, p, t)
            } else {
                KajiyaKay::new(kd, ks, p, t)
            };
            Ok(m.map_err(invalid(Self::NAME))?.into())
        }
    }
}
