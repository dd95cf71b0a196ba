//! Oren-Nayar rough diffuse reflection (qualitative model, 1994).

use super::{
    Brdf, Energy, Properties, Reciprocity, masked, safe_dirs, splat_channels, unit_channels,
};
use crate::Scalar;
use crate::real::{Splat, splat_array};
use crate::{Error, Real, Vec3};

/// The qualitative Oren-Nayar model of rough (V-cavity, Gaussian slope) diffuse surfaces.
///
/// ```text
/// f(wi, wo) = ρ/π · (A + B · max(0, cos(φi − φo)) · sin α · tan β)
/// A = 1 − 0.5 σ²/(σ² + 0.33),   B = 0.45 σ²/(σ² + 0.09)
/// α = max(θi, θo),  β = min(θi, θo)
/// ```
///
/// Evaluated without trigonometry: since `sin` is increasing and `cos` decreasing on
/// `[0, π/2]`, `sin α tan β = sin θi sin θo / max(cos θi, cos θo)`, and
/// `cos(φi − φo) sin θi sin θo = wi.x wo.x + wi.y wo.y`, so
///
/// ```text
/// f = ρ/π · (A + B · max(0, wi.x wo.x + wi.y wo.y) / max(cos θi, cos θo))
/// ```
///
/// (no division by `sin θ`, no `atan`). `σ = 0` gives `A = 1`, `B = 0` exactly: Lambert.
///
/// Properties: reciprocal. **Not energy conserving**: the qualitative model gains a little
/// energy at grazing view for small roughness (ρ = 1, σ = 0.2 rad: albedo ≈ 1.014 at
/// θo = 89°; the tests locate the violation); it also lacks the interreflection term of the
/// full model. Domain: `ρ ∈ [0, 1]` per channel, `σ ∈ [0, ∞)` radians (the RMS slope
/// angle; physically meaningful up to about `π/2`).
///
/// Reference: M. Oren, S. K. Nayar, "Generalization of Lambert's Reflectance Model",
/// SIGGRAPH 1994 (eq. 30, the qualitative model).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, OrenNayar, Lambert}};
/// let smooth = OrenNayar::new([0.7_f32], 0.0)?;
/// let lambert = Lambert::new([0.7_f32])?;
/// let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.28, 0.96, 0.0001));
/// assert_eq!(smooth.eval(wi, wo), lambert.eval(wi, wo));
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrenNayar<R, const N: usize> {
    a: [R; N],
    b: [R; N],
}

impl<S: Scalar, const N: usize> OrenNayar<S, N> {
    /// Albedo `rho ∈ [0, 1]` per channel and roughness `sigma ∈ [0, ∞)` (radians).
    ///
    /// # Errors
    /// Names `"rho"` or `"sigma"`.
    #[inline]
    pub fn new(rho: [S; N], sigma: S) -> Result<Self, Error> {
        let rho = unit_channels("rho", rho)?;
        let s: f64 = crate::error::non_negative("sigma", sigma)?.into();
        let s2 = s * s;
        let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
        let b = 0.45 * s2 / (s2 + 0.09);
        let k = rho.map(|r| r * core::f64::consts::FRAC_1_PI);
        Ok(Self {
            a: splat_channels(k.map(|k| k * a)),
            b: splat_channels(k.map(|k| k * b)),
        })
    }
}

impl<S: Scalar, const N: usize> Splat for OrenNayar<S, N> {
    type On<L: Real> = OrenNayar<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> OrenNayar<L, N> {
        OrenNayar {
            a: splat_array(&self.a),
            b: splat_array(&self.b),
        }
    }
}

impl<R: Real, const N: usize> Brdf<R, N> for OrenNayar<R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (m, wi, wo) = safe_dirs(wi, wo);
        let proj = wi.x.mul_add(wo.x, wi.y * wo.y).max(R::zero());
        // Floored: keeps t ≤ 1e20 when both directions graze (B·t stays finite, and
        // 0·t = 0 for σ = 0).
        let t = proj / wi.z.max(wo.z).max(R::from_f64(super::DENOM_FLOOR));
        let r: [R; N] = crate::real::channels(
            #[inline(always)]
            |c| self.b[c].mul_add(t, self.a[c]),
        );
        masked(m, r)
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::Reciprocal,
            energy: Energy::NotConserving {
                note: "the qualitative model's albedo exceeds ρ slightly at grazing view for \
                       small σ (ρ = 1, σ = 0.2 rad: ≈ 1.014 at θo = 89°)",
            },
        }
    }
}

/// Fujii's improved Oren-Nayar model ("FON"), the single-scattering base of the
/// energy-preserving Oren-Nayar (EON) of `OpenPBR`.
///
/// ```text
/// f(wi, wo) = ρ/π · A · (1 + σ s/t),       A = 1 / (1 + (1/2 − 2/(3π)) σ)
/// s = wi·wo − cos θi cos θo,   t = max(cos θi, cos θo) if s > 0, else 1
/// ```
///
/// Compared with [`OrenNayar`]: the backscatter term is not clipped at `s < 0` (it darkens
/// forward scattering), `σ ∈ [0, 1]` is a dimensionless roughness, not an angle, and the
/// factor `A` keeps the albedo below `ρ` (at normal view `s = 0`, so the albedo is `ρA`).
/// `s = (wi.x wo.x + wi.y wo.y)` is computed from the tangent components (no cancellation).
/// `σ = 0` gives Lambert exactly.
///
/// Properties: reciprocal. Energy: the albedo stays ≤ `ρ` (it *loses* energy at grazing
/// angles and high roughness — the loss EON's multiple-scattering lobe restores); checked
/// numerically in the tests over `σ ∈ [0, 1]`.
///
/// Domain: `ρ ∈ [0, 1]` per channel, `σ ∈ [0, 1]`.
///
/// References: Y. Fujii, "A tiny improvement of Oren-Nayar reflectance model", 2013
/// (<https://mimosa-pudica.net/improved-oren-nayar.html>); J. Portsmouth et al., "EON: A
/// practical energy-preserving rough diffuse BRDF", JCGT 14(1), 2025; `OpenPBR` Surface 1.1.
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, OrenNayarFujii}};
/// let m = OrenNayarFujii::new([1.0_f64], 1.0)?;
/// let n = Vec3::new(0.0, 0.0, 1.0);
/// let a = 1.0 / (1.0 + (0.5 - 2.0 / (3.0 * core::f64::consts::PI)));
/// // Normal view: s = 0 for every wi, so f = ρ A / π.
/// assert!((m.eval(Vec3::new(0.6, 0.0, 0.8), n)[0] - a / core::f64::consts::PI).abs() < 1e-15);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrenNayarFujii<R, const N: usize> {
    a: [R; N],
    b: [R; N],
}

impl<S: Scalar, const N: usize> OrenNayarFujii<S, N> {
    /// Albedo `rho ∈ [0, 1]` per channel and roughness `sigma ∈ [0, 1]`.
    ///
    /// # Errors
    /// Names `"rho"` or `"sigma"`.
    #[inline]
    pub fn new(rho: [S; N], sigma: S) -> Result<Self, Error> {
        let rho = unit_channels("rho", rho)?;
        let s: f64 = crate::error::unit_interval("sigma", sigma)?.into();
        let a = 1.0 / (1.0 + (0.5 - 2.0 / (3.0 * core::f64::consts::PI)) * s);
        let k = rho.map(|r| r * core::f64::consts::FRAC_1_PI * a);
        Ok(Self {
            a: splat_channels(k),
            b: splat_channels(k.map(|k| k * s)),
        })
    }
}

impl<S: Scalar, const N: usize> Splat for OrenNayarFujii<S, N> {
    type On<L: Real> = OrenNayarFujii<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> OrenNayarFujii<L, N> {
        OrenNayarFujii {
            a: splat_array(&self.a),
            b: splat_array(&self.b),
        }
    }
}

impl<R: Real, const N: usize> Brdf<R, N> for OrenNayarFujii<R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (m, wi, wo) = safe_dirs(wi, wo);
        let s = wi.x.mul_add(wo.x, wi.y * wo.y);
        let t = R::select(s.gt(R::zero()), wi.z.max(wo.z), R::one());
        let st = s / t.max(R::from_f64(super::DENOM_FLOOR));
        let r: [R; N] = crate::real::channels(
            #[inline(always)]
            |c| self.b[c].mul_add(st, self.a[c]),
        );
        masked(m, r)
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::Reciprocal,
            energy: Energy::Conserving,
        }
    }
}

impl<R: Real, const N: usize> OrenNayar<R, N> {
    /// `ρA`, the channel mean (its sampling's albedo estimate; the `B` term adds little).
    #[inline(always)]
    pub(crate) fn estimate(&self) -> R {
        R::pi() * crate::sampling::lobes::mean(self.a)
    }
}

impl<R: Real, const N: usize> OrenNayarFujii<R, N> {
    /// `ρA`, the channel mean (its sampling's albedo estimate).
    #[inline(always)]
    pub(crate) fn estimate(&self) -> R {
        R::pi() * crate::sampling::lobes::mean(self.a)
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file descriptions of [`OrenNayar`] (`model = "oren_nayar"`) and [`OrenNayarFujii`]
/// (`model = "oren_nayar_fujii"`), re-exported from [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use serde::{Deserialize, Serialize};

    use super::{OrenNayar, OrenNayarFujii};
    use crate::Scalar;
    use crate::material::{Material, MaterialError, ModelDesc, Rgb, invalid};

    crate::material::field_fns!(rho, sigma);

    /// [`OrenNayar`] (qualitative model, Oren and Nayar 1994): albedo `rho ∈ [0, 1]` per
    /// channel and the RMS slope angle `sigma ≥ 0` in radians.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `oren_nayar`")]
    pub struct OrenNayarDesc {
        /// Albedo.
        #[serde(deserialize_with = "field::rho")]
        pub rho: Rgb,
        /// RMS slope angle in radians, `≥ 0`.
        #[serde(deserialize_with = "field::sigma")]
        pub sigma: f64,
    }

    impl ModelDesc for OrenNayarDesc {
        const NAME: &'static str = "oren_nayar";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let m = OrenNayar::new(self.rho.scalars(), S::of(self.sigma))
                .map_err(invalid(Self::NAME))?;
            Ok(m.into())
        }
    }

    /// [`OrenNayarFujii`] (Fujii 2013, the improved Oren-Nayar of `OpenPBR`): albedo
    /// `rho ∈ [0, 1]` per channel and roughness `sigma ∈ [0, 1]`. In TOML:
    /// `model = "oren_nayar_fujii"`, `rho = 0.8`, `sigma = 0.5`.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `oren_nayar_fujii`")]
    pub struct OrenNayarFujiiDesc {
        /// Albedo.
        #[serde(deserialize_with = "field::rho")]
        pub rho: Rgb,
        /// Roughness, `[0, 1]`.
        #[serde(deserialize_with = "field::sigma")]
        pub sigma: f64,
    }

    impl ModelDesc for OrenNayarFujiiDesc {
        const NAME: &'static str = "oren_nayar_fujii";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let m = OrenNayarFujii::new(self.rho.scalars(), S::of(self.sigma))
                .map_err(invalid(Self::NAME))?;
            Ok(m.into())
        }
    }
}
