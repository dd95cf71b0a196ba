//! Normal distribution functions D(wm).
//!
//! (Filled in by the NDF work; the traits below are the contract the models build on.)

use crate::{Real, Vec3};

/// A microfacet normal distribution function.
///
/// `D(wm)` is the density of microfacet normals per unit solid angle, in sr⁻¹, normalized
/// so that `∫ D(wm) cos θm dωm = 1` over the hemisphere, and zero for `wm.z ≤ 0`.
pub trait Ndf<R: Real> {
    /// `D(wm)` for a unit `wm` in the local frame.
    fn d(&self, wm: Vec3<R>) -> R;
}

/// An NDF with a closed-form Smith auxiliary function Λ (Heitz 2014, eq. 72–86), from which
/// the Smith masking terms of [`crate::masking`] are built.
pub trait SmithLambda<R: Real>: Ndf<R> {
    /// `Λ(w)`: `G1(w) = 1 / (1 + Λ(w))`. Zero at normal incidence, `+∞`-free: at grazing
    /// incidence it returns a large finite value or the limit handled by the caller.
    fn lambda(&self, w: Vec3<R>) -> R;
}

/// An NDF that can report the isotropic slope parameter `alpha` seen from direction `w`
/// (the projected roughness for anisotropic NDFs), used by the approximate masking terms
/// (Schlick-GGX `k = alpha/2`, Hammon's and Filament's height-correlated fits).
pub trait ProjectedAlpha<R: Real>: Ndf<R> {
    /// `alpha` projected on the plane of `w`: `√(cos²φ αx² + sin²φ αy²)`.
    fn projected_alpha(&self, w: Vec3<R>) -> R;
}
