//! The Cook-Torrance microfacet BRDF, composed at compile time from an NDF, a Fresnel term
//! and a masking-shadowing term.

use core::marker::PhantomData;

use super::{Brdf, Energy, Properties, Reciprocity, half_and_cos_d, upper};
use crate::fast::{ExactSqrt, SqrtFn};
use crate::fresnel::FresnelTerm;
use crate::masking::Masking;
use crate::ndf::Ndf;
use crate::real::Splat;
use crate::{Real, Vec3};

/// Microfacet reflection `f = D · F · G2 / (4 cos θi cos θo)`, generic over its parts.
///
/// ```text
/// f(wi, wo) = D(wm) · F(wi·wm) · V(wi, wo, wm),    wm = normalize(wi + wo)
/// V = G2 / (4 cos θi cos θo)                       (Masking::visibility)
/// ```
///
/// `D: Ndf<R>`, `F: FresnelTerm<R, N>` (conductor, dielectric, Schlick, …) and
/// `G: Masking<R, D>` are type parameters, so a scene that needs only GGX + Schlick + an
/// approximate visibility monomorphizes exactly that and pays for nothing else. The body
/// calls `G::visibility`, which approximate terms override with their cheaper direct forms.
///
/// `S:` [`SqrtFn`] (default [`ExactSqrt`]; choose with [`CookTorrance::with_sqrt`]) takes
/// the half vector's length `|wi + wo|` — hence `cos θd = |wi + wo|/2` — and its inverse,
/// which normalizes `wm` for the NDFs that need a unit half vector (Beckmann; GGX works on
/// the unnormalized one). The square roots inside the NDF, masking and Fresnel terms are
/// theirs and stay exact.
///
/// [`crate::batch::Pipelined`] is implemented on `f32` and [`crate::real::F32Fma`]: the
/// geometry (`cos θd`, `cos²θd`, `D·V`) and the Fresnel term run as separate passes over a
/// block, bit-identical to `eval`.
///
/// Below the horizon the result is replaced by 0 with a final select; the parts still run
/// on those lanes (branch-free) and may compute garbage there, which never reaches a
/// result because every operation is lane-wise.
///
/// Properties: reciprocal (D depends on `wm` only, `wi·wm = wo·wm`, and G2 is symmetric in
/// the masking terms of this crate). Albedo ≤ 1 when `F ≤ 1` and G2 is a proper masking
/// term, i.e. `G2(wi, wo, wm) ≤ G1(wo, wm)` for a `G1` satisfying the projected-area
/// identity `∫ G1(wo, wm) D(wm) ⟨wo·wm⟩ dωm = cos θo` (Smith separable and height
/// correlated) — checked numerically in the tests for GGX and Beckmann, `α ∈ [1e-3, 1]`,
/// up to `θo = 89.99°`. With the V-cavity term the measured albedo reaches `1 + 1.6e-4` at
/// `θo = 89.99°` (`α = 0.3`), at the accuracy limit of the quadratures; approximate terms
/// (Kelemen, Implicit, Schlick-GGX) carry no such guarantee.
///
/// References: R. L. Cook, K. E. Torrance, "A Reflectance Model for Computer Graphics",
/// ACM TOG 1(1), 1982; B. Walter et al., "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR 2007; E. Heitz, "Understanding the Masking-Shadowing Function in
/// Microfacet-Based BRDFs", JCGT 3(2), 2014.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CookTorrance<R, D, F, G, S = ExactSqrt> {
    /// The normal distribution `D(wm)`.
    pub ndf: D,
    /// The Fresnel term `F(wi·wm)`.
    pub fresnel: F,
    /// The masking-shadowing term `G2` (through its visibility form).
    pub masking: G,
    _r: PhantomData<(R, S)>,
}

impl<R: Real, D: Ndf<R>, F, G: Masking<R, D>> CookTorrance<R, D, F, G> {
    /// Composes a microfacet BRDF with the exact half-vector length; each part validated
    /// its own parameters when it was built.
    #[inline]
    #[must_use]
    pub const fn new(ndf: D, fresnel: F, masking: G) -> Self {
        Self {
            ndf,
            fresnel,
            masking,
            _r: PhantomData,
        }
    }
}

impl<R: Real, D: Ndf<R>, F, G: Masking<R, D>, S: SqrtFn> CookTorrance<R, D, F, G, S> {
    /// The same model with the half-vector length and normalization taken by `S2`, e.g.
    /// [`crate::fast::NewtonSqrt`].
    ///
    /// ```
    /// use brdf::{Brdf, Vec3, fast::NewtonSqrt, fresnel::Schlick, masking::SmithHeightCorrelated};
    /// use brdf::{models::CookTorrance, ndf::GgxIsotropic};
    /// let exact = CookTorrance::new(
    ///     GgxIsotropic::new(0.3_f32).unwrap(),
    ///     Schlick::new([0.04_f32]).unwrap(),
    ///     SmithHeightCorrelated,
    /// );
    /// let fast = exact.with_sqrt::<NewtonSqrt<2>>();
    /// let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.28, 0.0, 0.96));
    /// let (a, b) = (exact.eval(wi, wo)[0], fast.eval(wi, wo)[0]);
    /// assert!((a - b).abs() <= 1e-5 * a);
    /// ```
    #[inline]
    #[must_use]
    pub fn with_sqrt<S2: SqrtFn>(self) -> CookTorrance<R, D, F, G, S2> {
        CookTorrance {
            ndf: self.ndf,
            fresnel: self.fresnel,
            masking: self.masking,
            _r: PhantomData,
        }
    }

    /// `(cos θd, cos²θd, D·V)` with `D·V = 0` below the horizon: everything but the Fresnel
    /// term. Shared by `eval` and the pipelined batch passes (one body).
    #[inline(always)]
    fn geometry(&self, wi: Vec3<R>, wo: Vec3<R>) -> (R, R, R) {
        // Lanes with a direction below the horizon compute garbage (possibly NaN) that the
        // select replaces by 0: every operation is lane-wise, so nothing leaks.
        let m = upper(wi, wo);
        // cos θd = wi·wm = wo·wm, computed symmetrically as |wi + wo|/2.
        let (wm, cos_d) = half_and_cos_d::<S, R>(wi, wo);
        let h = wi + wo;
        let len2 = h.length_squared();
        // cos²θd = |wi + wo|²/4, without waiting for the square root of cos θd (the exact
        // Fresnel terms start from it: FresnelTerm::eval_cos2).
        let cos2_d = (len2 * R::from_f64(0.25)).min(R::one());
        // D·V with a single division; NDFs written on the unnormalized half vector (GGX) never
        // use `wm`, and then its normalization is not computed at all.
        let (dn, dd) = self.ndf.d_fraction(wm, h, len2);
        let (vn, vd) = self.masking.visibility_fraction(&self.ndf, wi, wo, wm);
        let dv = S::div(dn * vn, (dd * vd).max(R::from_f64(1e-30)));
        (cos_d, cos2_d, R::select(m, dv, R::zero()))
    }
}

impl<K, const N: usize, D, F, G, S> crate::batch::Pipelined<K, N> for CookTorrance<K, D, F, G, S>
where
    K: Real<Scalar = f32, Mask = bool>,
    D: Ndf<K>,
    F: FresnelTerm<K, N>,
    G: Masking<K, D>,
    S: SqrtFn,
{
    /// Two passes per block: the microfacet geometry (`cos θd`, `D·V`: the half vector's
    /// square root, the masking roots, one division), then the Fresnel term and the product.
    #[inline(always)]
    fn eval_passes(
        &self,
        wi: crate::batch::Directions<'_>,
        wo: crate::batch::Directions<'_>,
        out: [&mut [f32]; N],
    ) {
        use crate::batch::BLOCK;
        let mut cos_d = [K::zero(); BLOCK];
        let mut cos2_d = [K::zero(); BLOCK];
        let mut dv = [K::zero(); BLOCK];
        crate::batch::for_each_block(
            wi,
            wo,
            out,
            #[inline(always)]
            |wi, wo, block| {
                let n = wi.len();
                let (ix, iy, iz) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
                let (ox, oy, oz) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
                let (cos_d, cos2_d, dv) = (&mut cos_d[..n], &mut cos2_d[..n], &mut dv[..n]);
                for i in 0..n {
                    (cos_d[i], cos2_d[i], dv[i]) = self.geometry(
                        Vec3::new(K::splat(ix[i]), K::splat(iy[i]), K::splat(iz[i])),
                        Vec3::new(K::splat(ox[i]), K::splat(oy[i]), K::splat(oz[i])),
                    );
                }
                let block = block.map(|o| &mut o[..n]);
                for i in 0..n {
                    let f = self.fresnel.eval_cos2(cos_d[i], cos2_d[i]);
                    for c in 0..N {
                        block[c][i] = (f[c] * dv[i]).lane(0);
                    }
                }
            },
        );
    }
}

impl<R, D: Splat, F: Splat, G: Splat, S: SqrtFn> Splat for CookTorrance<R, D, F, G, S> {
    const EXPLICIT_LANES: bool =
        S::HARDWARE_ESTIMATES || D::EXPLICIT_LANES || F::EXPLICIT_LANES || G::EXPLICIT_LANES;
    type On<L: Real> = CookTorrance<L, D::On<L>, F::On<L>, G::On<L>, S>;
    #[inline]
    fn splat<L: Real>(&self) -> Self::On<L> {
        CookTorrance {
            ndf: self.ndf.splat(),
            fresnel: self.fresnel.splat(),
            masking: self.masking.splat(),
            _r: PhantomData,
        }
    }
}

impl<R, D, F, G, S, const N: usize> Brdf<R, N> for CookTorrance<R, D, F, G, S>
where
    R: Real,
    D: Ndf<R>,
    F: FresnelTerm<R, N>,
    G: Masking<R, D>,
    S: SqrtFn,
{
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (cos_d, cos2_d, dv) = self.geometry(wi, wo);
        let f = self.fresnel.eval_cos2(cos_d, cos2_d);
        crate::real::channels(
            #[inline(always)]
            |c| f[c] * dv,
        )
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::Reciprocal,
            energy: Energy::ConservingWhen {
                condition: "F ≤ 1 and G2(wi, wo, wm) ≤ G1(wo, wm) of a masking function with \
                            ∫ G1 D ⟨wo·wm⟩ dωm = cos θo (the Smith terms)",
            },
        }
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file description of [`CookTorrance`]: `model = "cook_torrance"`, re-exported from
/// [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use serde::{Deserialize, Serialize};

    use super::CookTorrance;
    use crate::Scalar;
    use crate::masking::AnyMasking;
    use crate::material::{
        FresnelDesc, Material, MaterialError, ModelDesc, NdfDesc, alphas, build_fresnel, invalid,
        iso_alpha,
    };

    crate::material::field_fns!(ndf, alpha, alpha_x, alpha_y, fresnel, masking, sqrt);

    /// How a Cook-Torrance material takes the half vector's length and its final division
    /// (a [`crate::fast::SqrtFn`] policy). In TOML: `sqrt = "hardware_estimate"`.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
    #[serde(rename_all = "snake_case")]
    #[serde(expecting = "a square-root policy name")]
    pub enum SqrtDesc {
        /// [`ExactSqrt`](crate::fast::ExactSqrt): correctly rounded (default).
        #[default]
        Exact,
        /// [`HardwareEstimate`](crate::fast::HardwareEstimate): the AVX-512 estimates with one
        /// refinement step in the batch path on `Isa::Avx512` (within a few ULP), exact
        /// everywhere else.
        HardwareEstimate,
    }

    impl SqrtDesc {
        /// Whether this is the default, [`SqrtDesc::Exact`] (not written out).
        #[must_use]
        pub fn is_exact(&self) -> bool {
            *self == SqrtDesc::Exact
        }
    }

    /// [`CookTorrance`] with a choice of NDF, Fresnel and masking term.
    ///
    /// Roughness: either `alpha` (isotropic) or both `alpha_x` and `alpha_y`, each in
    /// `[1e-4, 1]`.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `cook_torrance`")]
    pub struct CookTorranceDesc {
        /// The distribution.
        #[serde(deserialize_with = "field::ndf")]
        pub ndf: NdfDesc,
        /// Isotropic slope parameter.
        #[serde(
            default,
            skip_serializing_if = "Option::is_none",
            deserialize_with = "field::alpha"
        )]
        pub alpha: Option<f64>,
        /// Slope parameter along the tangent.
        #[serde(
            default,
            skip_serializing_if = "Option::is_none",
            deserialize_with = "field::alpha_x"
        )]
        pub alpha_x: Option<f64>,
        /// Slope parameter along the bitangent.
        #[serde(
            default,
            skip_serializing_if = "Option::is_none",
            deserialize_with = "field::alpha_y"
        )]
        pub alpha_y: Option<f64>,
        /// The Fresnel term.
        #[serde(deserialize_with = "field::fresnel")]
        pub fresnel: FresnelDesc,
        /// The masking term (default `smith_height_correlated`).
        #[serde(default, deserialize_with = "field::masking")]
        pub masking: AnyMasking,
        /// The square-root policy (default `exact`).
        #[serde(
            default,
            skip_serializing_if = "SqrtDesc::is_exact",
            deserialize_with = "field::sqrt"
        )]
        pub sqrt: SqrtDesc,
    }

    impl ModelDesc for CookTorranceDesc {
        const NAME: &'static str = "cook_torrance";

        fn is_anisotropic(&self) -> bool {
            self.alpha.is_none() && self.alpha_x.is_some() && self.alpha_x != self.alpha_y
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let alpha = alphas(Self::NAME, self.alpha, self.alpha_x, self.alpha_y)?;
            let isotropic = self.alpha.is_some();
            let inv = |e| invalid(Self::NAME)(iso_alpha(isotropic, e));
            let ndf = self.ndf.build(alpha, isotropic).map_err(inv)?;
            let fresnel = build_fresnel(&self.fresnel).map_err(inv)?;
            let ct = CookTorrance::new(ndf, fresnel, self.masking);
            Ok(match self.sqrt {
                SqrtDesc::Exact => ct.into(),
                SqrtDesc::HardwareEstimate => {
                    ct.with_sqrt::<crate::fast::HardwareEstimate>().into()
                }
            })
        }
    }
}
