//! The Fresnel-coupled diffuse term of Shirley et al. (1997).

use super::{
    Brdf, Energy, Properties, Reciprocity, masked, safe_dirs, splat_channels, unit_channels,
};
use crate::Scalar;
use crate::fresnel::schlick_complement;
use crate::real::{Splat, splat_array};
use crate::{Error, Real, Vec3};

/// Diffuse reflection under a smooth dielectric coat, with Schlick's Fresnel transmission
/// on both sides (Shirley, Hu, Smits, Lafortune 1997, §5.1).
///
/// ```text
/// f(wi, wo) = 21/(20π) · (1 − R0) · ρd · (1 − (1 − cos θi)⁵) (1 − (1 − cos θo)⁵)
/// ```
///
/// Derivation: Schlick's `1 − F(c) = (1 − R0)(1 − (1 − c)⁵)` is the fraction transmitted
/// through the coat; weighting a diffuse term by `(1 − (1 − cos θi)⁵)(1 − (1 − cos θo)⁵)`
/// and normalizing with `∫ (1 − (1 − c)⁵) c dc = 1/2 − 1/42 = 10/21` gives the `21/(20π)`
/// factor, so that the albedo is
///
/// ```text
/// ρ(wo) = (1 − R0) ρd (1 − (1 − cos θo)⁵) ≤ ρd ≤ 1.
/// ```
///
/// **The seed talk's appendix writes `R_d · 21/(20π(1 − F0)) · (…)(…)`**, with `(1 − F0)`
/// in the denominator. Taken literally that *raises* the diffuse as the coat gets more
/// reflective, and its albedo `ρd (1 − (1 − cos θo)⁵)/(1 − F0)` exceeds 1 (e.g. `ρd = 1`,
/// `F0 = 0.5`, `θo = 0`: 2). It matches the paper only if the two brackets are read as the
/// full Schlick transmissions `1 − F(cos θ)` (which carry `(1 − F0)²`); with the brackets
/// as written, the factor belongs in the numerator — which is what this type implements
/// (the tests check the albedo above and show the literal reading exceeds 1).
///
/// Properties: reciprocal; albedo ≤ 1. Domain: `ρd, R0 ∈ [0, 1]` per channel.
///
/// Reference: P. Shirley, H. Hu, B. Smits, E. Lafortune, "A Practitioners' Assessment of
/// Light Reflection Models", Pacific Graphics 1997, §5.1.
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, ShirleyDiffuse}};
/// let m = ShirleyDiffuse::new([1.0_f64], [0.04])?;
/// let n = Vec3::new(0.0, 0.0, 1.0);
/// let f = m.eval(n, n)[0];
/// assert!((f - 21.0 / (20.0 * core::f64::consts::PI) * 0.96).abs() < 1e-15);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShirleyDiffuse<R, const N: usize> {
    k: [R; N],
}

impl<S: Scalar, const N: usize> ShirleyDiffuse<S, N> {
    /// Diffuse albedo `rho_d` and the coat's normal-incidence reflectance `r0`, per
    /// channel in `[0, 1]`.
    ///
    /// # Errors
    /// Names `"rho_d"` or `"r0"`.
    #[inline]
    pub fn new(rho_d: [S; N], r0: [S; N]) -> Result<Self, Error> {
        let rho_d = unit_channels("rho_d", rho_d)?;
        let r0 = unit_channels("r0", r0)?;
        let c = 21.0 / (20.0 * core::f64::consts::PI);
        let mut k = [0.0; N];
        for i in 0..N {
            k[i] = c * (1.0 - r0[i]) * rho_d[i];
        }
        Ok(Self {
            k: splat_channels(k),
        })
    }
}

impl<S: Scalar, const N: usize> Splat for ShirleyDiffuse<S, N> {
    type On<L: Real> = ShirleyDiffuse<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> ShirleyDiffuse<L, N> {
        ShirleyDiffuse {
            k: splat_array(&self.k),
        }
    }
}

impl<R: Real, const N: usize> Brdf<R, N> for ShirleyDiffuse<R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (m, wi, wo) = safe_dirs(wi, wo);
        let t = schlick_complement(wi.z) * schlick_complement(wo.z);
        masked(
            m,
            crate::real::channels(
                #[inline(always)]
                |c| self.k[c] * t,
            ),
        )
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::Reciprocal,
            energy: Energy::Conserving,
        }
    }
}

impl<R: Real, const N: usize> ShirleyDiffuse<R, N> {
    /// `(1 − R0) ρd`, the channel mean (its sampling's albedo estimate).
    #[inline(always)]
    pub(crate) fn estimate(&self) -> R {
        R::from_f64(20.0 * core::f64::consts::PI / 21.0) * crate::sampling::lobes::mean(self.k)
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file description of [`ShirleyDiffuse`]: `model = "shirley_diffuse"`, re-exported
/// from [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use serde::{Deserialize, Serialize};

    use super::ShirleyDiffuse;
    use crate::Scalar;
    use crate::material::{Material, MaterialError, ModelDesc, Reflectance, Rgb, invalid};

    crate::material::field_fns!(rho_d, r0);

    /// [`ShirleyDiffuse`], the Fresnel-coupled diffuse of Shirley et al. 1997: the
    /// substrate's `rho_d ∈ [0, 1]` and the coat's normal-incidence reflectance `r0` (a
    /// colour, a preset or a complex IOR).
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `shirley_diffuse`")]
    pub struct ShirleyDiffuseDesc {
        /// Diffuse reflectance of the substrate.
        #[serde(deserialize_with = "field::rho_d")]
        pub rho_d: Rgb,
        /// Normal-incidence reflectance of the coat.
        #[serde(deserialize_with = "field::r0")]
        pub r0: Reflectance,
    }

    impl ModelDesc for ShirleyDiffuseDesc {
        const NAME: &'static str = "shirley_diffuse";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let inv = invalid(Self::NAME);
            let r0 = Rgb(self.r0.value().map_err(&inv)?).scalars();
            Ok(ShirleyDiffuse::new(self.rho_d.scalars(), r0)
                .map_err(inv)?
                .into())
        }
    }
}
