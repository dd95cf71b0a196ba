//! Composition of models: sums and a Fresnel-weighted coat over a base.

use super::{Brdf, Energy, Properties, Reciprocity, masked, safe_dirs};
use crate::fresnel::FresnelTerm;
use crate::real::Splat;
use crate::sampling::lobes::{first_probability, mean, pdf_pair, sample_pair};
use crate::sampling::{Sample, SampleBrdf};
use crate::{Real, Vec3};

/// The sum of two models, `f = A + B` (e.g. a diffuse and a specular lobe), composed at
/// compile time.
///
/// ```text
/// f(wi, wo) = A(wi, wo) + B(wi, wo)
/// ```
///
/// Reciprocal when both parts are. Energy: the albedos add, so the sum conserves energy
/// only when `ρ_A(w) + ρ_B(w) ≤ 1`; the declaration says so (and reports a non-conserving
/// part).
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, Lambert, Sum, OrenNayar}};
/// let m = Sum::new(Lambert::new([0.25_f32])?, OrenNayar::new([0.25_f32], 0.0)?);
/// let n = Vec3::new(0.0, 0.0, 1.0);
/// assert!((m.eval(n, n)[0] - 0.5 / core::f32::consts::PI).abs() < 1e-7);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sum<A, B> {
    /// The first summand.
    pub a: A,
    /// The second summand.
    pub b: B,
}

impl<A, B> Sum<A, B> {
    /// `a + b`.
    #[inline]
    #[must_use]
    pub const fn new(a: A, b: B) -> Self {
        Self { a, b }
    }
}

/// The energy condition of a sum (see [`Sum`]).
pub(crate) const SUM_CONDITION: &str = "the parts' albedos add up to ≤ 1 for every direction";

/// The energy condition of a coat over a base (see [`Layered`]).
pub(crate) const LAYERED_CONDITION: &str = "the coat's albedo ρ_S(w) ≤ F(cos θ) and ρ_base ≤ 1";

impl Properties {
    /// The properties of a composition of two parts (a [`Sum`], a [`Layered`] coat, a
    /// composition of your own):
    ///
    /// * reciprocal iff both parts are (otherwise the first non-reciprocal part's note);
    /// * energy: not conserving if a part is not (that part's note, the first one's if
    ///   both), otherwise conserving under `condition` — what the composition needs of its
    ///   parts beyond their own bounds (e.g. "the parts' albedos add up to ≤ 1").
    ///
    /// ```
    /// use brdf::models::{Energy, Properties, Reciprocity};
    /// let lambert = Properties { reciprocity: Reciprocity::Reciprocal, energy: Energy::Conserving };
    /// let seed = Properties {
    ///     reciprocity: Reciprocity::NotReciprocal { note: "divides by cos θi" },
    ///     energy: Energy::Conserving,
    /// };
    /// let c = lambert.combine(seed, "albedos add up to ≤ 1");
    /// assert_eq!(c.reciprocity, seed.reciprocity);
    /// assert_eq!(c.energy, Energy::ConservingWhen { condition: "albedos add up to ≤ 1" });
    /// ```
    #[must_use]
    pub fn combine(self, other: Properties, condition: &'static str) -> Properties {
        let reciprocity = match (self.reciprocity, other.reciprocity) {
            (Reciprocity::Reciprocal, Reciprocity::Reciprocal) => Reciprocity::Reciprocal,
            (Reciprocity::NotReciprocal { note }, _) | (_, Reciprocity::NotReciprocal { note }) => {
                Reciprocity::NotReciprocal { note }
            }
        };
        let energy = match (self.energy, other.energy) {
            (Energy::NotConserving { note }, _) | (_, Energy::NotConserving { note }) => {
                Energy::NotConserving { note }
            }
            _ => Energy::ConservingWhen { condition },
        };
        Properties {
            reciprocity,
            energy,
        }
    }
}

impl<A: Splat, B: Splat> Splat for Sum<A, B> {
    const EXPLICIT_LANES: bool = A::EXPLICIT_LANES || B::EXPLICIT_LANES;
    type On<L: Real> = Sum<A::On<L>, B::On<L>>;
    #[inline]
    fn splat<L: Real>(&self) -> Self::On<L> {
        Sum {
            a: self.a.splat(),
            b: self.b.splat(),
        }
    }
}

impl<R: Real, const N: usize, A: Brdf<R, N>, B: Brdf<R, N>> Brdf<R, N> for Sum<A, B> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (a, b) = (self.a.eval(wi, wo), self.b.eval(wi, wo));
        crate::real::channels(
            #[inline(always)]
            |c| a[c] + b[c],
        )
    }

    /// The union of both parts' kinks.
    #[inline]
    fn kinks(&self, wo: Vec3<f64>) -> super::Kinks {
        self.a.kinks(wo).union(self.b.kinks(wo))
    }

    #[inline]
    fn properties(&self) -> Properties {
        self.a
            .properties()
            .combine(self.b.properties(), SUM_CONDITION)
    }
}

/// A coat over a base: the coat reflects `S`, and the base `D` is seen through the coat's
/// Fresnel transmission on the way in and out.
///
/// ```text
/// f(wi, wo) = S(wi, wo) + (1 − F(cos θi)) (1 − F(cos θo)) · D(wi, wo)
/// ```
///
/// A first-order layering (no refraction of the directions, no absorption, no
/// interreflection between the layers), in the spirit of Weidlich and Wilkie's layered
/// model and of the Fresnel-coupled diffuse of Shirley et al. 1997. `F: FresnelTerm<R, N>`
/// is the coat's Fresnel term (e.g. dielectric, or Schlick with the coat's `F0`).
///
/// Reciprocal when `S` and `D` are (the weight is symmetric). Energy: the albedo is at most
/// `ρ_S(wo) + (1 − F(cos θo)) ρ_D`, so it is ≤ 1 when the coat's albedo is at most its
/// Fresnel reflectance `F(cos θo)` and `ρ_D ≤ 1`.
///
/// Reference: A. Weidlich, A. Wilkie, "Arbitrarily Layered Micro-Facet Surfaces", GRAPHITE
/// 2007; P. Shirley et al., "A Practitioners' Assessment of Light Reflection Models",
/// Pacific Graphics 1997.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layered<D, S, F> {
    /// The base (seen through the coat), e.g. a diffuse model.
    pub base: D,
    /// The coat's own reflection, e.g. a Cook-Torrance lobe.
    pub coat: S,
    /// The coat's Fresnel reflectance, applied as `1 − F` on each side.
    pub fresnel: F,
}

impl<D, S, F> Layered<D, S, F> {
    /// `coat + (1 − F(cos θi))(1 − F(cos θo)) · base`.
    #[inline]
    #[must_use]
    pub const fn new(base: D, coat: S, fresnel: F) -> Self {
        Self {
            base,
            coat,
            fresnel,
        }
    }
}

impl<D: Splat, S: Splat, F: Splat> Splat for Layered<D, S, F> {
    const EXPLICIT_LANES: bool = D::EXPLICIT_LANES || S::EXPLICIT_LANES || F::EXPLICIT_LANES;
    type On<L: Real> = Layered<D::On<L>, S::On<L>, F::On<L>>;
    #[inline]
    fn splat<L: Real>(&self) -> Self::On<L> {
        Layered {
            base: self.base.splat(),
            coat: self.coat.splat(),
            fresnel: self.fresnel.splat(),
        }
    }
}

impl<R, const N: usize, D, S, F> Brdf<R, N> for Layered<D, S, F>
where
    R: Real,
    D: Brdf<R, N>,
    S: Brdf<R, N>,
    F: FresnelTerm<R, N>,
{
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (d, s) = (self.base.eval(wi, wo), self.coat.eval(wi, wo));
        layered_combine(&self.fresnel, wi, wo, d, s)
    }

    /// The union of the base's and the coat's kinks (both are evaluated at `(wi, wo)`; the
    /// Fresnel weights are smooth).
    #[inline]
    fn kinks(&self, wo: Vec3<f64>) -> super::Kinks {
        self.base.kinks(wo).union(self.coat.kinks(wo))
    }

    #[inline]
    fn properties(&self) -> Properties {
        self.base
            .properties()
            .combine(self.coat.properties(), LAYERED_CONDITION)
    }
}

/// [`Layered`]'s value from its base's `d = D(wi, wo)` and its coat's `s = S(wi, wo)`:
/// `s + (1 − F(cos θi))(1 − F(cos θo)) · d` (one fused multiply-add per channel), 0 unless
/// both directions are above the surface. The body of [`Layered`]'s `eval`, shared with the
/// batch evaluation of a layered material, which evaluates `d` and `s` in passes.
#[inline(always)]
pub(crate) fn layered_combine<R: Real, F: FresnelTerm<R, N>, const N: usize>(
    fresnel: &F,
    wi: Vec3<R>,
    wo: Vec3<R>,
    d: [R; N],
    s: [R; N],
) -> [R; N] {
    let (m, swi, swo) = safe_dirs(wi, wo);
    let (fi, fo) = (fresnel.eval(swi.z), fresnel.eval(swo.z));
    let r = crate::real::channels(
        #[inline(always)]
        |c| ((R::one() - fi[c]) * (R::one() - fo[c])).mul_add(d[c], s[c]),
    );
    masked(m, r)
}

/// Importance sampling of a sum: a one-sample mixture of the parts' own samplers (Veach
/// 1997, §9.2.4). Part `a` is chosen with probability `P = ρ̂_a/(ρ̂_a + ρ̂_b)` (their
/// [`SampleBrdf::albedo_estimate`]s at `wo`; `1/2` if both are 0) when `u[2] < P`, and gets
/// `u[2]/P` as its own third number (`b` gets `(u[2] − P)/(1 − P)`), so nested sums and
/// mixtures inside a part still receive a uniform number:
///
/// ```text
/// pdf(wi)   = P pdf_a(wi) + (1 − P) pdf_b(wi)
/// weight    = (f_a + f_b)(wi) cos θi / pdf(wi)        (the whole f, not the part's weight)
/// ρ̂         = ρ̂_a + ρ̂_b
/// ```
impl<R, const N: usize, A, B> SampleBrdf<R, N> for Sum<A, B>
where
    R: Real,
    A: SampleBrdf<R, N>,
    B: SampleBrdf<R, N>,
{
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let p = first_probability(self.a.albedo_estimate(wo), self.b.albedo_estimate(wo));
        sample_pair(
            p,
            wo,
            u,
            #[inline(always)]
            |u| self.a.sample(wo, u),
            #[inline(always)]
            |u| self.b.sample(wo, u),
            #[inline(always)]
            |wi| self.a.pdf(wo, wi),
            #[inline(always)]
            |wi| self.b.pdf(wo, wi),
            #[inline(always)]
            |wi| self.eval(wi, wo),
        )
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        let p = first_probability(self.a.albedo_estimate(wo), self.b.albedo_estimate(wo));
        pdf_pair(
            p,
            wo,
            wi,
            #[inline(always)]
            |wi| self.a.pdf(wo, wi),
            #[inline(always)]
            |wi| self.b.pdf(wo, wi),
        )
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        self.a.albedo_estimate(wo) + self.b.albedo_estimate(wo)
    }
}

impl<D, S, F> Layered<D, S, F> {
    /// `(ρ̂_coat, (1 − mean F(cos θo)) ρ̂_base)`.
    #[inline(always)]
    fn estimates<R: Real, const N: usize>(&self, wo: Vec3<R>) -> (R, R)
    where
        D: SampleBrdf<R, N>,
        S: SampleBrdf<R, N>,
        F: FresnelTerm<R, N>,
    {
        (
            self.coat.albedo_estimate(wo),
            coat_transmission(&self.fresnel, wo) * self.base.albedo_estimate(wo),
        )
    }
}

/// `max(0, 1 − mean F(cos θo))`: the weight of the base's estimate under a coat.
#[inline(always)]
pub(crate) fn coat_transmission<R: Real, const N: usize, F: FresnelTerm<R, N>>(
    fresnel: &F,
    wo: Vec3<R>,
) -> R {
    let fo = mean(fresnel.eval(wo.z.saturate()));
    (R::one() - fo).max(R::zero())
}

/// Importance sampling of a coat over a base: a one-sample mixture (Veach 1997, §9.2.4) of
/// the coat's and the base's own samplers, chosen and remapped with `u[2]` as in [`Sum`]'s,
/// with the coat's probability
///
/// ```text
/// P = ρ̂_S / (ρ̂_S + (1 − mean F(cos θo)) ρ̂_D)
/// pdf(wi) = P pdf_S(wi) + (1 − P) pdf_D(wi)
/// weight  = f(wi) cos θi / pdf(wi)    with f = S + (1 − F(cos θi))(1 − F(cos θo)) D
/// ```
///
/// (`ρ̂` the parts' [`SampleBrdf::albedo_estimate`]s; the base's is weighted by the coat's
/// transmission towards `wo`). [`SampleBrdf::albedo_estimate`] is
/// `ρ̂_S + (1 − mean F(cos θo)) ρ̂_D`.
impl<R, const N: usize, D, S, F> SampleBrdf<R, N> for Layered<D, S, F>
where
    R: Real,
    D: SampleBrdf<R, N>,
    S: SampleBrdf<R, N>,
    F: FresnelTerm<R, N>,
{
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let (s, d) = self.estimates(wo);
        sample_pair(
            first_probability(s, d),
            wo,
            u,
            #[inline(always)]
            |u| self.coat.sample(wo, u),
            #[inline(always)]
            |u| self.base.sample(wo, u),
            #[inline(always)]
            |wi| self.coat.pdf(wo, wi),
            #[inline(always)]
            |wi| self.base.pdf(wo, wi),
            #[inline(always)]
            |wi| self.eval(wi, wo),
        )
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        let (s, d) = self.estimates(wo);
        pdf_pair(
            first_probability(s, d),
            wo,
            wi,
            #[inline(always)]
            |wi| self.coat.pdf(wo, wi),
            #[inline(always)]
            |wi| self.base.pdf(wo, wi),
        )
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        let (s, d) = self.estimates(wo);
        s + d
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file descriptions of the compositions: [`Sum`] of any number of terms
/// (`model = "sum"`) and [`Layered`] (`model = "layered"`), re-exported from
/// [`crate::material`]. They hold other descriptions, as their runtime variants
/// (`Material::Sum`, `Material::Layered`) hold other materials.
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use alloc::boxed::Box;
    use alloc::vec::Vec;

    use serde::{Deserialize, Serialize};

    use super::Layered;
    use crate::Scalar;
    use crate::material::{
        FresnelDesc, Material, MaterialDesc, MaterialError, ModelDesc, Parts, build_fresnel,
        invalid,
    };

    crate::material::field_fns!(terms, base, coat, fresnel);

    /// [`crate::models::Sum`] of any number of terms (at least one).
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `sum`")]
    pub struct SumDesc {
        /// The summands.
        #[serde(deserialize_with = "field::terms")]
        pub terms: Vec<MaterialDesc>,
    }

    /// [`Layered`]: `coat + (1 − F(cos θi))(1 − F(cos θo)) · base`.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `layered`")]
    pub struct LayeredDesc {
        /// The base, seen through the coat.
        #[serde(deserialize_with = "field::base")]
        pub base: Box<MaterialDesc>,
        /// The coat's own reflection.
        #[serde(deserialize_with = "field::coat")]
        pub coat: Box<MaterialDesc>,
        /// The coat's Fresnel term.
        #[serde(deserialize_with = "field::fresnel")]
        pub fresnel: FresnelDesc,
    }

    impl ModelDesc for SumDesc {
        const NAME: &'static str = "sum";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn parts(&self) -> Option<Parts<'_>> {
            Some(Parts::slice(&self.terms))
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            if self.terms.is_empty() {
                return Err(MaterialError::Inconsistent {
                    model: Self::NAME,
                    field: "terms",
                    reason: "give at least one term",
                });
            }
            let terms = self.terms.iter().map(MaterialDesc::build_checked);
            Ok(Material::Sum(terms.collect::<Result<_, _>>()?))
        }
    }

    impl ModelDesc for LayeredDesc {
        const NAME: &'static str = "layered";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn parts(&self) -> Option<Parts<'_>> {
            Some(Parts::pair(&self.base, &self.coat))
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let base = self.base.build_checked()?;
            let coat = self.coat.build_checked()?;
            let fresnel = build_fresnel(&self.fresnel).map_err(invalid(Self::NAME))?;
            Ok(Material::Layered(Box::new(Layered::new(
                base, coat, fresnel,
            ))))
        }
    }
}
