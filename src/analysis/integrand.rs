//! What the analysis functions evaluate: a model of the crate, your own [`Brdf`], or a
//! closure.

use crate::models::{Brdf, Kinks};
use crate::{Scalar, Vec3};

/// A BRDF as the analysis functions see it: `f(wi, wo)` per channel on `S = f32` or `f64`.
///
/// Implemented for every [`Brdf<S, N>`] (so the crate's models, `Brdf<f32, N>` models
/// included, and trait objects `dyn Brdf<S, N>` are accepted as they are) and for closures
/// wrapped in [`FnBrdf`]. The analysis functions integrate and compare in `f64`: directions
/// are rounded to `S` before the call and values widened after it.
///
/// Implement [`Brdf`] rather than this trait for a model of your own: `Integrand` is only the
/// input of `analysis`.
pub trait Integrand<S: Scalar, const N: usize> {
    /// `f(wi, wo)` per channel in sr⁻¹, without the cosine; `wi`, `wo` unit vectors in the
    /// local frame (z = normal), both in the upper hemisphere when the integrators call it.
    fn value(&self, wi: Vec3<S>, wo: Vec3<S>) -> [S; N];

    /// Where `f(·, wo)` is not smooth (see [`Brdf::kinks`]); the albedo integrator puts panel
    /// edges there. Models forward [`Brdf::kinks`]; closures ([`FnBrdf`]) declare none.
    #[inline]
    fn kinks(&self, _wo: Vec3<f64>) -> Kinks {
        Kinks::NONE
    }
}

impl<S: Scalar, const N: usize, B: Brdf<S, N> + ?Sized> Integrand<S, N> for B {
    #[inline]
    fn value(&self, wi: Vec3<S>, wo: Vec3<S>) -> [S; N] {
        self.eval(wi, wo)
    }

    #[inline]
    fn kinks(&self, wo: Vec3<f64>) -> Kinks {
        Brdf::kinks(self, wo)
    }
}

/// A closure `|wi, wo| -> [S; N]` (`S = f64` or `f32`) as the BRDF of the analysis functions,
/// without the [`Brdf::properties`] a model declares.
///
/// Build it with [`FnBrdf::new`] (`f64`) or [`FnBrdf::new_f32`] (`f32`): their bounds give the
/// closure's parameter types, so none need spelling. The closure returns `f(wi, wo)` per
/// channel in sr⁻¹, without the cosine, and should return 0 below the horizon like a
/// [`Brdf`] (the integrators never call it there; [`reciprocity_check`](super::reciprocity_check)
/// calls it on the pairs you pass).
///
/// # Examples
///
/// ```
/// use brdf::analysis::{AlbedoConfig, FnBrdf, directional_albedo};
/// use brdf::Vec3;
/// use core::f64::consts::PI;
///
/// // A normalized Phong lobe about the normal: (n + 2)/(2π) cosⁿθi, albedo 1 for every wo.
/// let n = 50.0;
/// let lobe = FnBrdf::new(|wi, _wo| [(n + 2.0) / (2.0 * PI) * wi.z.max(0.0).powf(n)]);
/// let wo = Vec3::new(0.6, 0.0, 0.8);
/// let [rho] = directional_albedo(&lobe, wo, &AlbedoConfig::DEFAULT);
/// assert!((rho - 1.0).abs() < 1e-6);
///
/// // An f32 closure: directions are rounded to f32, values widened.
/// let lambert = FnBrdf::new_f32(|_wi, _wo| [0.5 * core::f32::consts::FRAC_1_PI; 3]);
/// let rgb = directional_albedo(&lambert, wo, &AlbedoConfig::DEFAULT);
/// assert!(rgb.iter().all(|&r| (r - 0.5).abs() < 1e-6));
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct FnBrdf<F>(pub F);

impl<F> FnBrdf<F> {
    /// Wraps an `f64` closure `f(wi, wo) -> [f64; N]`.
    #[inline]
    #[must_use]
    pub fn new<const N: usize>(f: F) -> Self
    where
        F: Fn(Vec3<f64>, Vec3<f64>) -> [f64; N],
    {
        Self(f)
    }

    /// Wraps an `f32` closure `f(wi, wo) -> [f32; N]`.
    #[inline]
    #[must_use]
    pub fn new_f32<const N: usize>(f: F) -> Self
    where
        F: Fn(Vec3<f32>, Vec3<f32>) -> [f32; N],
    {
        Self(f)
    }
}

impl<F: Fn(Vec3<f64>, Vec3<f64>) -> [f64; N], const N: usize> Integrand<f64, N> for FnBrdf<F> {
    #[inline]
    fn value(&self, wi: Vec3<f64>, wo: Vec3<f64>) -> [f64; N] {
        (self.0)(wi, wo)
    }
}

impl<F: Fn(Vec3<f32>, Vec3<f32>) -> [f32; N], const N: usize> Integrand<f32, N> for FnBrdf<F> {
    #[inline]
    fn value(&self, wi: Vec3<f32>, wo: Vec3<f32>) -> [f32; N] {
        (self.0)(wi, wo)
    }
}

/// `f(wi, wo)` in `f64` for `f64` directions: rounded to `S`, evaluated, widened.
#[inline]
pub(crate) fn eval_f64<S: Scalar, const N: usize, B: Integrand<S, N> + ?Sized>(
    b: &B,
    wi: Vec3<f64>,
    wo: Vec3<f64>,
) -> [f64; N] {
    let c = |w: Vec3<f64>| Vec3::new(S::of(w.x), S::of(w.y), S::of(w.z));
    b.value(c(wi), c(wo)).map(Into::into)
}
