//! Masking-shadowing terms G.
//!
//! (Filled in by the masking work; the trait below is the contract the models build on.)

use crate::{Real, Vec3, ndf::Ndf};

/// A masking-shadowing term `G2(wi, wo, wm)` usable with the NDF `D`.
///
/// Implementations that need the NDF (the Smith family) read it through `ndf`; others
/// (V-cavity, Kelemen) ignore it. Both `wi` and `wo` are in the upper hemisphere.
pub trait Masking<R: Real, D: Ndf<R>> {
    /// `G2(wi, wo, wm)`, dimensionless in `[0, 1]`.
    fn g2(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R;

    /// The visibility term `V = G2 / (4 cos θi cos θo)` in sr⁻¹·(sr) — what a Cook-Torrance
    /// body multiplies by `D·F`. Terms with a cheaper direct form of `V` override this.
    /// Domain: `wi.z > 0`, `wo.z > 0`.
    #[inline(always)]
    fn visibility(&self, ndf: &D, wi: Vec3<R>, wo: Vec3<R>, wm: Vec3<R>) -> R {
        self.g2(ndf, wi, wo, wm) / (R::from_f64(4.0) * wi.z * wo.z)
    }
}
