//! Lafortune's generalized cosine lobes (1997).

use super::{
    Brdf, Energy, Kinks, Properties, Reciprocity, masked, safe_dirs, select_vec, splat_channels,
    unit_channels,
};
use crate::Scalar;
use crate::ndf::MAX_SHININESS;
use crate::real::{Splat, splat_array, splat_scalar};
use crate::sampling::lobes::{cos_power_pdf, finish, mean, sample_cos_power};
use crate::sampling::{Sample, SampleBrdf, cosine_hemisphere_pdf};
use crate::{Error, Real, Vec3};

/// Largest allowed `ρ · max(|Cx|, |Cy|, |Cz|)^n` of a lobe: keeps every value finite in
/// `f32`.
const LOBE_PEAK_MAX: f64 = 1e30;

/// One generalized cosine lobe `ρ · max(0, Cx wi.x wo.x + Cy wi.y wo.y + Cz wi.z wo.z)^n`.
///
/// Typical choices (Lafortune et al. 1997, §3):
///
/// * `Cx = Cy = −Cz`: a Phong lobe around the mirror direction (`−Cx = Cz = 1` gives
///   `(wi_mirror·wo)^n`);
/// * `|Cz| < |Cx|` (with `Cx = Cy < 0`): off-specular peak moving towards grazing angles;
/// * `Cx = Cy > 0`: retro-reflection (peak towards `wo = wi`);
/// * `Cx = Cy = 0`, `Cz > 0`: a lobe along the normal, `(Cz cos θi cos θo)^n`.
///
/// `n = 0` gives the constant `ρ` (`x⁰ = 1`, including `0⁰`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LafortuneLobe<S, const N: usize> {
    /// Weight of `wi.x wo.x` (tangent).
    pub cx: S,
    /// Weight of `wi.y wo.y` (bitangent).
    pub cy: S,
    /// Weight of `wi.z wo.z` (normal).
    pub cz: S,
    /// Exponent `n ≥ 0`.
    pub n: S,
    /// Scale `ρ ≥ 0` per channel.
    pub rho: [S; N],
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Lobe<R, const N: usize> {
    cx: R,
    cy: R,
    cz: R,
    n: R,
    rho: [R; N],
}

/// Lafortune's reflectance model: a Lambertian term plus `K` generalized cosine lobes.
///
/// ```text
/// f(wi, wo) = ρd/π + Σⱼ ρⱼ · max(0, Cxⱼ wi.x wo.x + Cyⱼ wi.y wo.y + Czⱼ wi.z wo.z)^nⱼ
/// ```
///
/// Each lobe is `ρ (v·wo)^n` with `v = (Cx wi.x, Cy wi.y, Cz wi.z)`: a cosine lobe about
/// `v̂` scaled by `|v|^n`. Symmetric in `wi` and `wo`, hence reciprocal.
///
/// **Energy bound.** With `Cmax = max(|Cx|, |Cy|, |Cz|)`, `|v| ≤ Cmax`, and the integral of
/// the product of two cosine lobes over the sphere is largest when their axes coincide
/// (rearrangement), so `∫ (v̂·wo)₊ⁿ cos θo dωo ≤ ∫ cos⁺ⁿ⁺¹ θ dω = 2π/(n + 2)`. Hence the
/// sufficient condition, per channel,
///
/// ```text
/// B = ρd + Σⱼ ρⱼ Cmaxⱼ^nⱼ · 2π/(nⱼ + 2) ≤ 1   ⇒   albedo ≤ 1 for every direction
/// ```
///
/// ([`Lafortune::energy_bound`] returns `B`; [`Brdf::properties`] declares
/// [`Energy::Conserving`] when `B ≤ 1` in every channel). A normalized Phong lobe
/// (`−Cx = −Cy = Cz = 1`) with `ρ = (n + 2)/(2π)` meets it with equality.
///
/// Domain: `ρd ∈ [0, 1]`; per lobe `Cx, Cy, Cz ∈ [−1e30, 1e30]`,
/// `n ∈ [0, MAX_SHININESS]` (the Phong exponents' bound, [`crate::ndf::MAX_SHININESS`]: a
/// sharper lobe is below `f32` direction resolution, and `wide`'s lane `powf` overflows for
/// exponents from `≈ 1.6e16` on),
/// `ρ ∈ [0, ∞)` with `Cmax^n ≤ 1e30` and `ρ Cmax^n ≤ 1e30` (`Cmax = max(|Cx|, |Cy|, |Cz|)`
/// bounds the lobe's base, so every value is finite in `f32`; scaling every `C` by `λ` is
/// scaling `ρ` by `λⁿ`, so the bounds cost no lobe shape).
///
/// Reference: E. P. F. Lafortune, S.-C. Foo, K. E. Torrance, D. P. Greenberg, "Non-Linear
/// Approximation of Reflectance Functions", SIGGRAPH 1997.
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, Lafortune, LafortuneLobe}};
/// // A normalized Phong lobe: (n + 2)/(2π) (mirror(wi)·wo)^n.
/// let n = 20.0;
/// let lobe = LafortuneLobe { cx: -1.0, cy: -1.0, cz: 1.0, n, rho: [(n + 2.0) / (2.0 * core::f64::consts::PI)] };
/// let m = Lafortune::new([0.0_f64], [lobe])?;
/// assert!(m.energy_bound()[0] <= 1.0 + 1e-12);
/// let wi = Vec3::new(0.6, 0.0, 0.8);
/// let mirror = Vec3::new(-0.6, 0.0, 0.8);
/// assert!((m.eval(wi, mirror)[0] - (n + 2.0) / (2.0 * core::f64::consts::PI)).abs() < 1e-12);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lafortune<R, const N: usize, const K: usize> {
    rho_d_over_pi: [R; N],
    lobes: [Lobe<R, N>; K],
    bound: [f64; N],
}

impl<S: Scalar, const N: usize, const K: usize> Lafortune<S, N, K> {
    /// Lambertian `rho_d ∈ [0, 1]` per channel plus `K` lobes.
    ///
    /// # Errors
    /// Names `"rho_d"`, `"cx"`, `"cy"`, `"cz"`, `"n"` or `"rho"` (a lobe whose `Cmax^n` or
    /// peak `ρ Cmax^n` exceeds `1e30` is rejected naming `"n"`).
    pub fn new(rho_d: [S; N], lobes: [LafortuneLobe<S, N>; K]) -> Result<Self, Error> {
        let rho_d = unit_channels("rho_d", rho_d)?;
        let mut bound = rho_d;
        let mut out = [Lobe {
            cx: S::zero(),
            cy: S::zero(),
            cz: S::zero(),
            n: S::zero(),
            rho: [S::zero(); N],
        }; K];
        for (o, l) in out.iter_mut().zip(lobes) {
            let fin = |p, v: S| {
                crate::error::in_range(p, v, -LOBE_PEAK_MAX, LOBE_PEAK_MAX, "[−1e30, 1e30]")
                    .map(Into::<f64>::into)
            };
            let (cx, cy, cz) = (fin("cx", l.cx)?, fin("cy", l.cy)?, fin("cz", l.cz)?);
            let n: f64 =
                crate::error::in_range("n", l.n, 0.0, MAX_SHININESS, "[0, 2e8 − 2]")?.into();
            let mut rho = [0.0; N];
            for (r, &v) in rho.iter_mut().zip(&l.rho) {
                *r = crate::error::non_negative("rho", v)?.into();
            }
            let cmax = cx.abs().max(cy.abs()).max(cz.abs());
            let cmax_n = <f64 as Real>::pow(cmax, n);
            let rho_max = rho.iter().copied().fold(0.0, f64::max);
            // max|C|^n bounds the lobe's base to the power n (|wi·diag(C)·wo| ≤ max|C| for
            // unit directions): finite in f32 even when ρ = 0 (0·∞ would be NaN).
            // The bound in the precision of S, as the C bound (1e30_f32 > 1e30).
            let peak_max: f64 = S::of(LOBE_PEAK_MAX).into();
            if cmax_n > peak_max || rho_max * cmax_n > peak_max || cmax_n.is_nan() {
                return Err(Error::OutOfDomain {
                    param: "n",
                    value: n,
                    domain: "max|C|^n ≤ 1e30 and ρ·max|C|^n ≤ 1e30",
                });
            }
            for (b, r) in bound.iter_mut().zip(rho) {
                *b += r * cmax_n * 2.0 * core::f64::consts::PI / (n + 2.0);
            }
            *o = Lobe {
                cx: S::from_f64(cx),
                cy: S::from_f64(cy),
                cz: S::from_f64(cz),
                n: S::from_f64(n),
                rho: splat_channels(rho),
            };
        }
        Ok(Self {
            rho_d_over_pi: splat_channels(rho_d.map(|r| r * core::f64::consts::FRAC_1_PI)),
            lobes: out,
            bound,
        })
    }
}

impl<R: Real, const N: usize, const K: usize> Lafortune<R, N, K> {
    /// The sufficient energy bound `B = ρd + Σⱼ ρⱼ Cmaxⱼ^nⱼ 2π/(nⱼ + 2)` per channel
    /// (albedo ≤ `B` for every direction).
    #[inline]
    #[must_use]
    pub fn energy_bound(&self) -> [f64; N] {
        self.bound
    }
}

impl<S: Scalar, const N: usize, const K: usize> Splat for Lafortune<S, N, K> {
    type On<L: Real> = Lafortune<L, N, K>;
    #[inline]
    fn splat<L: Real>(&self) -> Lafortune<L, N, K> {
        Lafortune {
            rho_d_over_pi: splat_array(&self.rho_d_over_pi),
            lobes: core::array::from_fn(|j| {
                let l = &self.lobes[j];
                Lobe {
                    cx: splat_scalar(l.cx),
                    cy: splat_scalar(l.cy),
                    cz: splat_scalar(l.cz),
                    n: splat_scalar(l.n),
                    rho: splat_array(&l.rho),
                }
            }),
            bound: self.bound,
        }
    }
}

impl<R: Real, const N: usize, const K: usize> Brdf<R, N> for Lafortune<R, N, K> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (m, wi, wo) = safe_dirs(wi, wo);
        let (px, py, pz) = (wi.x * wo.x, wi.y * wo.y, wi.z * wo.z);
        let mut r = self.rho_d_over_pi;
        for l in &self.lobes {
            let base = l.cx.mul_add(px, l.cy.mul_add(py, l.cz * pz)).max(R::zero());
            let v = base.pow(l.n);
            for (rc, rho) in r.iter_mut().zip(&l.rho) {
                *rc = rho.mul_add(v, *rc);
            }
        }
        masked(m, r)
    }

    /// Each lobe's clamp `max(0, ·)`: the plane `(Cx wo.x, Cy wo.y, Cz wo.z)·wi = 0` (the first
    /// [`Kinks::MAX_PLANES`] lobes).
    #[inline]
    fn kinks(&self, wo: Vec3<f64>) -> Kinks {
        self.lobes.iter().fold(Kinks::NONE, |k, l| {
            let c = |v: R| -> f64 { v.lane(0).into() };
            k.with_plane(
                Vec3::new(c(l.cx) * wo.x, c(l.cy) * wo.y, c(l.cz) * wo.z),
                0.0,
            )
        })
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::Reciprocal,
            energy: if self.bound.iter().all(|&b| b <= 1.0) {
                Energy::Conserving
            } else {
                Energy::ConservingWhen {
                    condition: "sufficient: ρd + Σ ρⱼ max(|Cx|,|Cy|,|Cz|)^nⱼ 2π/(nⱼ + 2) ≤ 1 \
                                (Lafortune::energy_bound); this instance does not meet it",
                }
            },
        }
    }
}

/// A lobe as the sampler sees it at a given `wo`: axis, exponent, probability weight.
#[derive(Clone, Copy)]
struct SampledLobe<R: Real> {
    axis: Vec3<R>,
    e: R,
    estimate: R,
}

impl<R: Real, const N: usize> Lobe<R, N> {
    /// As a function of `wi` the lobe is `ρ |u|ⁿ max(0, û·wi)ⁿ` with
    /// `u = (Cx wo.x, Cy wo.y, Cz wo.z)`: sampled about `û` with exponent `n`, estimate
    /// `mean(ρ) |u|ⁿ 2π/(n + 2) (max(0, û.z) + 0.01)`. Where `n = 0` (the lobe is the constant
    /// `ρ` on the whole hemisphere, `0⁰ = 1`) or `|u|` underflows, the axis is the normal and
    /// the exponent 0 (uniform hemisphere).
    #[inline(always)]
    fn at(&self, wo: Vec3<R>) -> SampledLobe<R> {
        let u = Vec3::new(self.cx * wo.x, self.cy * wo.y, self.cz * wo.z);
        // Scaled by the largest component: |C| up to 1e30 squares beyond f32.
        let m = u.x.abs().max(u.y.abs()).max(u.z.abs());
        let ok = m.gt(R::from_f64(1e-30)) & self.n.gt(R::zero());
        let v = u.scale(m.max(R::from_f64(1e-30)).recip());
        let l = v.length();
        let n = Vec3::new(R::zero(), R::zero(), R::one());
        let axis = select_vec(ok, v.scale(l.recip()), n);
        let e = R::select(ok, self.n, R::zero());
        let peak = R::select(ok, (m * l).pow(self.n), R::one());
        let two_pi = R::from_f64(2.0 * core::f64::consts::PI);
        let estimate = mean(self.rho) * peak * two_pi / (self.n + R::from_f64(2.0))
            * (axis.z.max(R::zero()) + R::from_f64(0.01));
        SampledLobe { axis, e, estimate }
    }
}

impl<R: Real, const N: usize, const K: usize> Lafortune<R, N, K> {
    /// The lobes at `wo` and the mixture probabilities: `(lobes, P_d, [P_j])`.
    #[inline(always)]
    fn mixture(&self, wo: Vec3<R>) -> ([SampledLobe<R>; K], R, [R; K]) {
        let lobes: [SampledLobe<R>; K] = core::array::from_fn(|j| self.lobes[j].at(wo));
        let d = R::pi() * mean(self.rho_d_over_pi);
        let total = lobes.iter().fold(d, |t, l| t + l.estimate);
        let ok = total.gt(R::zero());
        let inv = total.max(R::from_f64(1e-30)).recip();
        let pd = R::select(ok, (d * inv).saturate(), R::one());
        let pj = core::array::from_fn(|j| {
            R::select(ok, (lobes[j].estimate * inv).saturate(), R::zero())
        });
        (lobes, pd, pj)
    }

    /// The mixture density at `wi` given the mixture.
    #[inline(always)]
    fn mixture_pdf(lobes: &[SampledLobe<R>; K], pd: R, pj: &[R; K], wo: Vec3<R>, wi: Vec3<R>) -> R {
        let ok = wi.z.gt(R::zero()) & wo.z.gt(R::zero());
        let p = lobes
            .iter()
            .zip(pj)
            .fold(pd * cosine_hemisphere_pdf(wi), |acc, (l, &p)| {
                p.mul_add(cos_power_pdf(l.e, l.axis.dot(wi)), acc)
            });
        R::select(ok, p, R::zero())
    }
}

/// Importance sampling of Lafortune's model: each lobe `ρ max(0, Cx wi.x wo.x + Cy wi.y wo.y +
/// Cz wi.z wo.z)ⁿ` is, as a function of `wi`, the cosine-power lobe `ρ |u|ⁿ max(0, û·wi)ⁿ`
/// about `û`, `u = (Cx wo.x, Cy wo.y, Cz wo.z)` (the mirror direction for the Phong choice
/// `−Cx = −Cy = Cz`), and is sampled exactly in that form (Lafortune & Willems,
/// "Using the Modified Phong Reflectance Model for Physically Based Rendering", 1994; the
/// lobes of Lafortune et al. 1997). With the diffuse term sampled by the cosine, a one-sample
/// mixture over the `K + 1` parts (Veach 1997, §9.2.4):
///
/// ```text
/// pdf(wi) = P_d cos θi/π + Σⱼ Pⱼ (nⱼ + 1)/(2π) max(0, ûⱼ·wi)^nⱼ
/// ρ̂_d = mean(ρd),   ρ̂ⱼ = mean(ρⱼ) |uⱼ|^nⱼ 2π/(nⱼ + 2) (max(0, ûⱼ.z) + 0.01),   P = ρ̂/Σρ̂
/// ```
///
/// (`ρ̂ⱼ` is the lobe's albedo for an axis at the normal, scaled by how much of it is above the
/// horizon; the `0.01` keeps a lobe whose axis points below the horizon, but which still
/// reaches above it, in the mixture.) `u[2]` chooses the part by its cumulative
/// probabilities; `weight = f cos θi / pdf` with the whole `f`. A lobe with `n = 0` is
/// constant on the hemisphere and is sampled uniformly. Draws below the horizon are invalid
/// samples. [`SampleBrdf::albedo_estimate`] is `ρ̂_d + Σ ρ̂ⱼ`.
impl<R: Real, const N: usize, const K: usize> SampleBrdf<R, N> for Lafortune<R, N, K> {
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let (lobes, pd, pj) = self.mixture(wo);
        let mut wi = crate::sampling::cosine_hemisphere(u[0], u[1]);
        let mut acc = pd;
        for (l, &p) in lobes.iter().zip(&pj) {
            let w = sample_cos_power(l.axis, l.e, u[0], u[1]);
            wi = select_vec(u[2].ge(acc) & p.gt(R::zero()), w, wi);
            acc += p;
        }
        let pdf = Self::mixture_pdf(&lobes, pd, &pj, wo, wi);
        finish(wi, pdf, self.eval(wi, wo), wo.z.gt(R::zero()))
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        let (lobes, pd, pj) = self.mixture(wo);
        Self::mixture_pdf(&lobes, pd, &pj, wo, wi)
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        let (lobes, _, _) = self.mixture(wo);
        lobes
            .iter()
            .fold(R::pi() * mean(self.rho_d_over_pi), |t, l| t + l.estimate)
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file description of [`Lafortune`]: `model = "lafortune"`, re-exported from
/// [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use alloc::vec::Vec;

    use serde::{Deserialize, Serialize};

    use super::{Lafortune, LafortuneLobe};
    use crate::Scalar;
    use crate::material::{Material, MaterialError, ModelDesc, Rgb, invalid};

    crate::material::field_fns!(cx, cy, cz, n, rho, rho_d, lobes);

    /// One lobe of a [`LafortuneDesc`]: `ρ (Cx x_i x_o + Cy y_i y_o + Cz z_i z_o)^n`.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "a lobe: a table with `cx`, `cy`, `cz`, `n` and `rho`")]
    pub struct LobeDesc {
        /// Weight of `x_i x_o`.
        #[serde(deserialize_with = "field::cx")]
        pub cx: f64,
        /// Weight of `y_i y_o`.
        #[serde(deserialize_with = "field::cy")]
        pub cy: f64,
        /// Weight of `z_i z_o`.
        #[serde(deserialize_with = "field::cz")]
        pub cz: f64,
        /// Exponent, `≥ 0`.
        #[serde(deserialize_with = "field::n")]
        pub n: f64,
        /// Lobe scale per channel, `≥ 0`.
        #[serde(deserialize_with = "field::rho")]
        pub rho: Rgb,
    }

    /// [`Lafortune`] with one to three lobes.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `lafortune`")]
    pub struct LafortuneDesc {
        /// Lambertian part.
        #[serde(deserialize_with = "field::rho_d")]
        pub rho_d: Rgb,
        /// The lobes (1 to 3).
        #[serde(deserialize_with = "field::lobes")]
        pub lobes: Vec<LobeDesc>,
    }

    impl ModelDesc for LafortuneDesc {
        const NAME: &'static str = "lafortune";

        fn is_anisotropic(&self) -> bool {
            self.lobes.iter().any(|l| l.cx != l.cy)
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let inv = invalid(Self::NAME);
            let s = S::of;
            let lobe = |l: &LobeDesc| LafortuneLobe {
                cx: s(l.cx),
                cy: s(l.cy),
                cz: s(l.cz),
                n: s(l.n),
                rho: l.rho.scalars(),
            };
            let rd = self.rho_d.scalars();
            Ok(match self.lobes.as_slice() {
                [a] => Lafortune::new(rd, [lobe(a)]).map_err(inv)?.into(),
                [a, b] => Lafortune::new(rd, [lobe(a), lobe(b)]).map_err(inv)?.into(),
                [a, b, c] => Lafortune::new(rd, [lobe(a), lobe(b), lobe(c)])
                    .map_err(inv)?
                    .into(),
                _ => {
                    return Err(MaterialError::Inconsistent {
                        model: Self::NAME,
                        field: "lobes",
                        reason: "give 1 to 3 lobes",
                    });
                }
            })
        }
    }
}
