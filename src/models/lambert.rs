//! Lambertian diffuse reflection.

use super::{Brdf, Energy, Properties, Reciprocity, masked, splat_channels, unit_channels, upper};
use crate::Scalar;
use crate::real::{Splat, splat_array};
use crate::{Error, Real, Vec3};

/// Lambertian (ideal diffuse) reflection.
///
/// ```text
/// f(wi, wo) = albedo / π        (wi.z > 0 and wo.z > 0; 0 otherwise)
/// ```
///
/// Directional albedo `∫ f cos θi dωi = albedo` for every `wo`. Reciprocal; albedo ≤ 1 for
/// `albedo ∈ [0, 1]`, the constructor's domain.
///
/// Reference: J. H. Lambert, *Photometria*, 1760; as a BRDF: F. E. Nicodemus et al.,
/// "Geometrical Considerations and Nomenclature for Reflectance", NBS Monograph 160, 1977.
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, Lambert}};
/// let m = Lambert::new([0.5_f32, 0.25, 1.0])?;
/// let up = Vec3::new(0.0, 0.0, 1.0);
/// let f = m.eval(up, Vec3::new(0.6, 0.0, 0.8));
/// assert!((f[0] - 0.5 / core::f32::consts::PI).abs() < 1e-7);
/// assert_eq!(m.eval(Vec3::new(0.0, 0.6, -0.8), up), [0.0; 3]); // below the horizon
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambert<R, const N: usize> {
    albedo_over_pi: [R; N],
}

impl<S: Scalar, const N: usize> Lambert<S, N> {
    /// Lambertian reflection of `albedo ∈ [0, 1]` per channel.
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfDomain`] naming `"albedo"`.
    #[inline]
    pub fn new(albedo: [S; N]) -> Result<Self, Error> {
        let a = unit_channels("albedo", albedo)?;
        Ok(Self {
            albedo_over_pi: splat_channels(a.map(|a| a * core::f64::consts::FRAC_1_PI)),
        })
    }
}

impl<S: Scalar, const N: usize> Splat for Lambert<S, N> {
    type On<L: Real> = Lambert<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> Lambert<L, N> {
        Lambert {
            albedo_over_pi: splat_array(&self.albedo_over_pi),
        }
    }
}

impl<R: Real, const N: usize> Brdf<R, N> for Lambert<R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        masked(upper(wi, wo), self.albedo_over_pi)
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::Reciprocal,
            energy: Energy::Conserving,
        }
    }
}

impl<R: Real, const N: usize> Lambert<R, N> {
    /// The albedo's channel mean (its sampling's albedo estimate).
    #[inline(always)]
    pub(crate) fn estimate(&self) -> R {
        R::pi() * crate::sampling::lobes::mean(self.albedo_over_pi)
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file description of [`Lambert`]: `model = "lambert"`, re-exported from
/// [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use serde::{Deserialize, Serialize};

    use super::Lambert;
    use crate::Scalar;
    use crate::material::{Material, MaterialError, ModelDesc, Rgb, invalid};

    crate::material::field_fns!(albedo);

    /// [`Lambert`], `f = albedo/π`: `albedo ∈ [0, 1]` per channel. In TOML:
    /// `model = "lambert"`, `albedo = [0.8, 0.5, 0.2]`.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `lambert`")]
    pub struct LambertDesc {
        /// Diffuse albedo.
        #[serde(deserialize_with = "field::albedo")]
        pub albedo: Rgb,
    }

    impl ModelDesc for LambertDesc {
        const NAME: &'static str = "lambert";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let m = Lambert::new(self.albedo.scalars()).map_err(invalid(Self::NAME))?;
            Ok(m.into())
        }
    }
}
