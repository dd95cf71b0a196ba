//! Reciprocity and white-furnace checks over sets of directions.

use super::albedo::{AlbedoConfig, directional_albedo_estimate};
use super::integrand::{Integrand, eval_f64};
use crate::{Scalar, Vec3};

/// The largest violation of one kind found by a check, and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Worst {
    /// Size of the violation (`+∞` when a value was NaN or infinite).
    pub value: f64,
    /// `wi` of the pair where it occurs.
    pub wi: Vec3<f64>,
    /// `wo` of the pair where it occurs.
    pub wo: Vec3<f64>,
    /// Colour channel where it occurs.
    pub channel: usize,
}

impl Worst {
    const NONE: Self = Self {
        value: 0.0,
        wi: Vec3::new(0.0, 0.0, 0.0),
        wo: Vec3::new(0.0, 0.0, 0.0),
        channel: 0,
    };
}

/// Result of [`reciprocity_check`]: the worst absolute and relative asymmetry found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Violation {
    /// Largest `|f(wi, wo) − f(wo, wi)|` (sr⁻¹).
    pub abs: Worst,
    /// Largest `|f(wi, wo) − f(wo, wi)| / max(|f(wi, wo)|, |f(wo, wi)|)` (0 where both are 0;
    /// in `[0, 2]` for finite values).
    pub rel: Worst,
    /// Number of pairs compared.
    pub checked: usize,
}

/// Helmholtz reciprocity check: evaluates `f(wi, wo)` and `f(wo, wi)` on every pair and
/// returns the worst absolute and relative differences with the pair and channel where they
/// occur.
///
/// ```text
/// abs = maxₚ,c |f_c(wi, wo) − f_c(wo, wi)|,   rel = maxₚ,c abs_c / max(|f_c(wi, wo)|, |f_c(wo, wi)|)
/// ```
///
/// A reciprocal BRDF gives 0 up to rounding (exactly 0 when its formula is symmetric in
/// floating point, e.g. through `wi + wo`). A non-finite value counts as an infinite
/// violation. Cost: `2 · pairs` evaluations. Use [`DirectionGrid::pairs`](super::DirectionGrid::pairs)
/// for a deterministic set with grazing directions.
///
/// Reference: H. von Helmholtz (1856), as stated for BRDFs by F. E. Nicodemus et al.,
/// "Geometrical Considerations and Nomenclature for Reflectance", NBS Monograph 160, 1977.
///
/// # Examples
///
/// ```
/// use brdf::analysis::{DirectionGrid, FnBrdf, reciprocity_check};
///
/// // Not reciprocal: depends on cos θo only.
/// let view_dependent = FnBrdf::new(|wi, wo| {
///     [if wi.z > 0.0 && wo.z > 0.0 { (1.0 + wo.z) / (2.0 * core::f64::consts::PI) } else { 0.0 }]
/// });
/// let v = reciprocity_check(&view_dependent, DirectionGrid::DEFAULT.pairs());
/// // The worst pair is one at normal incidence against one at grazing incidence.
/// assert!(v.rel.value > 0.49);
/// assert!(v.rel.wi.z.max(v.rel.wo.z) == 1.0 && v.rel.wi.z.min(v.rel.wo.z) <= 1e-4);
/// ```
#[must_use]
pub fn reciprocity_check<B, S, const N: usize>(
    brdf: &B,
    pairs: impl IntoIterator<Item = (Vec3<f64>, Vec3<f64>)>,
) -> Violation
where
    B: Integrand<S, N> + ?Sized,
    S: Scalar,
{
    let mut out = Violation {
        abs: Worst::NONE,
        rel: Worst::NONE,
        checked: 0,
    };
    for (wi, wo) in pairs {
        let a = eval_f64(brdf, wi, wo);
        let b = eval_f64(brdf, wo, wi);
        for ch in 0..N {
            let (x, y) = (a[ch], b[ch]);
            let (abs, rel) = if !(x.is_finite() && y.is_finite()) {
                (f64::INFINITY, f64::INFINITY)
            } else {
                let d = (x - y).abs();
                let m = x.abs().max(y.abs());
                (d, if m > 0.0 { d / m } else { 0.0 })
            };
            let first = out.checked == 0 && ch == 0;
            if first || abs > out.abs.value {
                out.abs = Worst {
                    value: abs,
                    wi,
                    wo,
                    channel: ch,
                };
            }
            if first || rel > out.rel.value {
                out.rel = Worst {
                    value: rel,
                    wi,
                    wo,
                    channel: ch,
                };
            }
        }
        out.checked += 1;
    }
    out
}

/// Result of [`white_furnace`]: extreme directional albedos over the tested `wo`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FurnaceReport {
    /// Largest albedo over directions and channels (`+∞` if one was NaN or infinite).
    pub max_albedo: f64,
    /// `wo` where the largest albedo occurs.
    pub max_at: Vec3<f64>,
    /// Channel of the largest albedo.
    pub max_channel: usize,
    /// Smallest albedo over directions and channels.
    pub min_albedo: f64,
    /// `wo` where the smallest albedo occurs.
    pub min_at: Vec3<f64>,
    /// Channel of the smallest albedo.
    pub min_channel: usize,
    /// Largest integration error estimate among the albedos.
    pub max_error: f64,
    /// Number of directions tested.
    pub checked: usize,
    /// Total BRDF evaluations.
    pub evaluations: u64,
}

impl FurnaceReport {
    /// `max_albedo ≤ 1 + max_error + slack`: no tested direction reflects more energy than it
    /// receives, allowing for the integration error and a caller's `slack`.
    #[must_use]
    pub fn conserves_energy(&self, slack: f64) -> bool {
        self.max_albedo <= 1.0 + self.max_error + slack
    }
}

/// White-furnace test: the directional albedo `ρ(wo)` (the radiance reflected towards `wo`
/// under a uniform unit environment) at every `wo`, reporting the extremes.
///
/// ```text
/// ρ(wo) = ∫_{H²} f(wi, wo) cos θi dωi  ≤ 1   for an energy-conserving BRDF
/// ```
///
/// Each albedo is computed by [`directional_albedo_estimate`] with `cfg`, so the reported
/// values carry its accuracy (default ≈ 1e-7 or better) and cost (10³–10⁵ evaluations per
/// direction). Use [`DirectionGrid`](super::DirectionGrid) for a deterministic set including
/// grazing directions.
///
/// Reference: the furnace test as used in production renderers, e.g. M. Pharr, W. Jakob,
/// G. Humphreys, *Physically Based Rendering*, 4th ed., 2023 (energy-conservation tests of
/// its BSDFs).
///
/// # Examples
///
/// ```
/// use brdf::analysis::{AlbedoConfig, DirectionGrid, FnBrdf, white_furnace};
///
/// // Over-bright Lambert, f = 1.2/π.
/// let bright = FnBrdf::new(|_wi, _wo| [1.2 / core::f64::consts::PI]);
/// let r = white_furnace(&bright, DirectionGrid::new(3, 2, 1e-3), &AlbedoConfig::FAST);
/// assert!(!r.conserves_energy(0.0));
/// assert!((r.max_albedo - 1.2).abs() < 1e-4);
/// ```
#[must_use]
pub fn white_furnace<B, S, const N: usize>(
    brdf: &B,
    wos: impl IntoIterator<Item = Vec3<f64>>,
    cfg: &AlbedoConfig,
) -> FurnaceReport
where
    B: Integrand<S, N> + ?Sized,
    S: Scalar,
{
    let zero = Vec3::new(0.0, 0.0, 0.0);
    let mut r = FurnaceReport {
        max_albedo: f64::NEG_INFINITY,
        max_at: zero,
        max_channel: 0,
        min_albedo: f64::INFINITY,
        min_at: zero,
        min_channel: 0,
        max_error: 0.0,
        checked: 0,
        evaluations: 0,
    };
    for wo in wos {
        let e = directional_albedo_estimate(brdf, wo, cfg);
        for (ch, &v) in e.value.iter().enumerate() {
            let v = if v.is_nan() { f64::INFINITY } else { v };
            if v > r.max_albedo {
                (r.max_albedo, r.max_at, r.max_channel) = (v, wo, ch);
            }
            if v < r.min_albedo {
                (r.min_albedo, r.min_at, r.min_channel) = (v, wo, ch);
            }
        }
        r.max_error = r.max_error.max(e.error);
        r.evaluations += e.evaluations;
        r.checked += 1;
    }
    if r.checked == 0 {
        r.max_albedo = 0.0;
        r.min_albedo = 0.0;
    }
    r
}
