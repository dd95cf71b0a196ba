//! BRDF models behind one trait, [`Brdf`].
//!
//! (The models themselves are filled in by the models work; the trait is the contract that
//! the models, the [`crate::analysis`] tools and the tests share.)

use crate::{Real, Vec3};

/// Whether a model satisfies Helmholtz reciprocity `f(wi, wo) = f(wo, wi)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reciprocity {
    /// Reciprocal for every valid parameter and direction.
    Reciprocal,
    /// Not reciprocal; `note` says where and why (proved by a test that finds the violation).
    NotReciprocal {
        /// Where the violation comes from, e.g. `"divides by N·L only"`.
        note: &'static str,
    },
}

/// Whether a model conserves energy: directional albedo `ρ(wo) = ∫ f(wi, wo) cos θi dωi ≤ 1`
/// for every `wo` (and, for reciprocal models, every `wi`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Energy {
    /// Albedo ≤ 1 over the model's whole parameter domain.
    Conserving,
    /// Albedo ≤ 1 only under `condition` (e.g. `"albedo ≤ 1 and F0 ≤ 1"`).
    ConservingWhen {
        /// The parameter condition under which the bound holds.
        condition: &'static str,
    },
    /// The published model exceeds albedo 1 somewhere; `note` says where (proved by a test).
    NotConserving {
        /// Where the bound fails, e.g. `"grazing wo, α ≥ 0.3"`.
        note: &'static str,
    },
}

/// The physical properties a model declares, so that tests and users can rely on them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Properties {
    /// Helmholtz reciprocity.
    pub reciprocity: Reciprocity,
    /// Energy conservation.
    pub energy: Energy,
}

/// A bidirectional reflectance distribution function with `N` colour channels.
///
/// [`Brdf::eval`] returns `f(wi, wo)` in sr⁻¹ per channel — the BRDF value **without** the
/// cosine `cos θi` of the rendering equation. Directions are unit vectors in the local frame
/// (z = normal) pointing away from the surface; `f` is zero when either is below the horizon.
/// `R` is any [`Real`]: one evaluation on `f32`/`f64`, or one per lane on SIMD types.
pub trait Brdf<R: Real, const N: usize> {
    /// `f(wi, wo)` per channel, in sr⁻¹, without `cos θi`; `0` if `wi.z ≤ 0` or `wo.z ≤ 0`.
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N];

    /// The properties this model declares for its current parameters.
    fn properties(&self) -> Properties;
}
