//! Fresnel reflectance.
//!
//! (Filled in by the Fresnel work; the trait below is the contract the models build on.)

use crate::Real;

/// A Fresnel term as a BRDF model uses it: reflectance per colour channel as a function of
/// `cos θd = wi·wm`, the cosine between the light and the microfacet normal.
pub trait FresnelTerm<R: Real, const N: usize> {
    /// Reflectance per channel, each in `[0, 1]`, for `cos_theta_d ∈ [0, 1]`.
    fn eval(&self, cos_theta_d: R) -> [R; N];
}
