//! Blinn-Phong as games write it, and the normalized Blinn-Phong of the seed talk
//! (Gotanda 2009) and of tri-Ace's 2010 model.
//!
//! # From the talk's "Out" to a BRDF
//!
//! The talk writes shading results as `Out`, the radiance leaving towards the eye for a
//! light of unit intensity: `Out = f · cos θi` in this crate's terms (`cos θi = N·L`). So
//! every `Out` formula is turned into a BRDF by dividing it by `N·L`:
//!
//! * a term written `X · (N·L)` (the diffuse terms) becomes `X`;
//! * a term written without `N·L` (the talk's specular terms, where "G is omitted so
//!   (N·L)/(N·E) is not considered") becomes `X / (N·L)`.
//!
//! The talk's normalization `∫ (N·H)^s dω = 4π(2 − 2^(−s/2))/(s + 2)` is an integral of
//! `Out` over the outgoing hemisphere **without** `cos θo`, for light at normal incidence.
//! As a BRDF the seed's specular is therefore `c(s) F (N·H)^s / (N·L)`: the division by `N·L`
//! alone makes it **not reciprocal**, and its light-side albedo `∫ f cos θo dωo` grows like
//! `1/cos θi` at grazing incidence for broad lobes. This module offers both that literal
//! form ([`CosThetaI`]) and tri-Ace's reciprocal 2010 form, which divides by
//! `max(N·L, N·V)` instead ([`MaxCos`]); the tests prove the declared properties of each.

use core::marker::PhantomData;

use super::{
    Brdf, DENOM_FLOOR, Energy, Properties, Reciprocity, half_and_cos_d, masked, safe_dirs,
    splat_channels, unit_channels, upper,
};
use crate::fast::{ExactPow, ExactSqrt, PowFn, SqrtFn};
use crate::ndf::MAX_SHININESS;
use crate::normalization::{Normalization, TRI_ACE_OFFSET};
use crate::real::{Splat, splat_array, splat_scalar};
use crate::{Error, Real, Scalar, Vec3};

/// Validates a Blinn-Phong exponent: `s ∈ [0, MAX_SHININESS]` ([`crate::ndf::MAX_SHININESS`]
/// `= 2e8 − 2`, compared in the precision of `S`).
///
/// The bound is the one of the Blinn-Phong NDF: the exponent whose lobe is as narrow as the
/// sharpest accepted microfacet roughness ([`crate::ndf::MIN_ALPHA`]), below the angular
/// resolution of an `f32` half vector near the normal. Sharper lobes are a mirror to `f32`
/// directions, and their normalization factors (`≈ s/(8π)`, divided by a floored cosine)
/// overflow `f32` (`s = 3e38` gave ∞, and NaN away from the mirror direction).
#[inline]
fn shininess_of<S: Scalar>(s: S) -> Result<f64, Error> {
    let s = crate::error::in_range("shininess", s, 0.0, MAX_SHININESS, "[0, 2e8 − 2]")?;
    Ok(s.into())
}

/// `F0 + (1 − F0)(1 − c)⁵` per channel ([`crate::fresnel::schlick`]).
#[inline(always)]
fn schlick_channels<R: Real, const N: usize>(f0: &[R; N], c: R) -> [R; N] {
    crate::real::channels(
        #[inline(always)]
        |i| crate::fresnel::schlick(f0[i], c),
    )
}

/// Blinn-Phong as games wrote it before physically based shading, expressed as a BRDF.
///
/// The engine formula (the seed talk's "Blinn-Phong", with Schlick's Fresnel on `E·H`):
///
/// ```text
/// Out = R_d (N·L) + R_s F(F0, E·H) (N·H)^s,     F(F0, c) = F0 + (1 − F0)(1 − c)⁵
/// ```
///
/// is the radiance for a light of unit intensity, `Out = f · cos θi`. Dividing the `N·L`
/// weighting out gives the BRDF this type evaluates:
///
/// ```text
/// f(wi, wo) = R_d + R_s F(F0, wo·wm) (wm.z)^s / cos θi,      wm = normalize(wi + wo)
/// ```
///
/// ([`ClassicBlinnPhong::out`] returns the engine's `Out` itself.) What this means:
///
/// * `R_d` is **not** an albedo: the diffuse albedo is `π R_d` (engines folded the `π` into
///   the light's units), so `R_d > 1/π` reflects more than it receives.
/// * The specular lobe is **not normalized**: its peak stays `R_s` whatever `s`, so the
///   reflected energy changes with `s` — the problem the seed talk sets out to fix.
/// * Dividing only by `cos θi` makes it **not reciprocal**, and the light-side albedo
///   `∫ f cos θo dωo` grows like `1/cos θi` at grazing incidence.
///
/// Domain: `R_d, R_s, F0 ∈ [0, 1]`, `s ∈ [0, MAX_SHININESS]` ([`crate::ndf::MAX_SHININESS`]).
/// `cos θi` below [`DENOM_FLOOR`] is floored.
///
/// `S:` [`SqrtFn`] (default [`ExactSqrt`]; choose with [`ClassicBlinnPhong::with_sqrt`])
/// normalizes the half vector, `wm = h/|h|`: engines use a fast reciprocal square root here.
/// Its relative error `ε` becomes `≈ s·ε` in `(wm.z)^s`, so sharp lobes need more Newton steps
/// (measured in `docs/tradeoffs.md`).
///
/// References: J. F. Blinn, "Models of Light Reflection for Computer Synthesized Pictures",
/// SIGGRAPH 1977; C. Schlick, "An Inexpensive BRDF Model for Physically-based Rendering",
/// Eurographics 1994; Y. Gotanda, "Basic of Reflectance", tri-Ace, 2009.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClassicBlinnPhong<R, const N: usize, S = ExactSqrt> {
    rd: [R; N],
    rs: R,
    f0: [R; N],
    shininess: R,
    _s: PhantomData<S>,
}

impl<T: Scalar, const N: usize> ClassicBlinnPhong<T, N> {
    /// Engine Blinn-Phong with diffuse `rd`, specular coefficient `rs`, normal-incidence
    /// Fresnel reflectance `f0` (all in `[0, 1]`) and exponent
    /// `shininess ∈ [0, MAX_SHININESS]` ([`crate::ndf::MAX_SHININESS`] `= 2e8 − 2`).
    ///
    /// # Errors
    /// Names `"rd"`, `"rs"`, `"f0"` or `"shininess"`.
    #[inline]
    pub fn new(rd: [T; N], rs: T, f0: [T; N], shininess: T) -> Result<Self, Error> {
        let rd = unit_channels("rd", rd)?;
        let rs: f64 = crate::error::unit_interval("rs", rs)?.into();
        let f0 = unit_channels("f0", f0)?;
        let s = shininess_of(shininess)?;
        Ok(Self {
            rd: splat_channels(rd),
            rs: T::from_f64(rs),
            f0: splat_channels(f0),
            shininess: T::from_f64(s),
            _s: PhantomData,
        })
    }
}

impl<R: Real, const N: usize, S: SqrtFn> ClassicBlinnPhong<R, N, S> {
    /// The same model with the half vector normalized by `S2`, e.g.
    /// [`crate::fast::NewtonSqrt`].
    #[inline]
    #[must_use]
    pub fn with_sqrt<S2: SqrtFn>(self) -> ClassicBlinnPhong<R, N, S2> {
        ClassicBlinnPhong {
            rd: self.rd,
            rs: self.rs,
            f0: self.f0,
            shininess: self.shininess,
            _s: PhantomData,
        }
    }

    /// `R_s F(F0, wo·wm) (wm.z)^s`, the specular part of `Out`, on safe directions.
    #[inline(always)]
    fn specular_out(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (wm, cos_d) = half_and_cos_d::<S, R>(wi, wo);
        let lobe = self.rs * wm.z.saturate().pow(self.shininess);
        {
            let f = schlick_channels(&self.f0, cos_d);
            crate::real::channels(
                #[inline(always)]
                |c| f[c] * lobe,
            )
        }
    }

    /// The engine's shading result `Out = R_d (N·L) + R_s F(F0, E·H) (N·H)^s` for a light
    /// of unit intensity (`= f · cos θi`); `0` below the horizon.
    #[inline]
    #[must_use]
    pub fn out(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (m, wi, wo) = safe_dirs(wi, wo);
        let spec = self.specular_out(wi, wo);
        let r: [R; N] = crate::real::channels(
            #[inline(always)]
            |c| self.rd[c].mul_add(wi.z, spec[c]),
        );
        masked(m, r)
    }
}

impl<T: Scalar, const N: usize, S: SqrtFn> Splat for ClassicBlinnPhong<T, N, S> {
    const EXPLICIT_LANES: bool = S::HARDWARE_ESTIMATES;
    type On<L: Real> = ClassicBlinnPhong<L, N, S>;
    #[inline]
    fn splat<L: Real>(&self) -> ClassicBlinnPhong<L, N, S> {
        ClassicBlinnPhong {
            rd: splat_array(&self.rd),
            rs: splat_scalar(self.rs),
            f0: splat_array(&self.f0),
            shininess: splat_scalar(self.shininess),
            _s: PhantomData,
        }
    }
}

impl<R: Real, const N: usize, S: SqrtFn> Brdf<R, N> for ClassicBlinnPhong<R, N, S> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (m, wi, wo) = safe_dirs(wi, wo);
        let inv_cos_i = wi.z.max(R::from_f64(DENOM_FLOOR)).recip();
        let spec = self.specular_out(wi, wo);
        let r: [R; N] = crate::real::channels(
            #[inline(always)]
            |c| spec[c].mul_add(inv_cos_i, self.rd[c]),
        );
        masked(m, r)
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::NotReciprocal {
                note: "the specular term is divided by cos θi only",
            },
            energy: Energy::NotConserving {
                note: "unnormalized lobe: R_d is albedo/π and the specular albedo grows \
                       like 1/cos θi at grazing incidence",
            },
        }
    }
}

/// The denominator that turns the normalized Blinn-Phong specular `Out` into a BRDF:
/// [`CosThetaI`] (the seed talk, literal) or [`MaxCos`] (tri-Ace 2010, reciprocal).
pub trait SpecularDenominator: Copy + core::fmt::Debug + 'static {
    /// Whether `denom(cos θi, cos θo) = denom(cos θo, cos θi)`.
    const RECIPROCAL: bool;
    /// The denominator, floored at [`DENOM_FLOOR`]; arguments in `(0, 1]`.
    fn denom<R: Real>(cos_theta_i: R, cos_theta_o: R) -> R;
}

/// The seed talk's literal form: `Out / (N·L)`, i.e. divide by `cos θi`. Not reciprocal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CosThetaI;

impl SpecularDenominator for CosThetaI {
    const RECIPROCAL: bool = false;
    #[inline(always)]
    fn denom<R: Real>(cos_theta_i: R, _cos_theta_o: R) -> R {
        cos_theta_i.max(R::from_f64(DENOM_FLOOR))
    }
}

/// tri-Ace's 2010 reciprocal form: divide by `max(N·L, N·V)` (Gotanda, "Practical
/// Implementation of Physically-Based Shading Models at tri-Ace", SIGGRAPH 2010 course
/// "Physically-Based Shading Models in Film and Game Production").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MaxCos;

impl SpecularDenominator for MaxCos {
    const RECIPROCAL: bool = true;
    #[inline(always)]
    fn denom<R: Real>(cos_theta_i: R, cos_theta_o: R) -> R {
        cos_theta_i.max(cos_theta_o).max(R::from_f64(DENOM_FLOOR))
    }
}

/// The specular lobe of the normalized Blinn-Phong.
///
/// ```text
/// f(wi, wo) = R_s c(s) F(F0, wo·wm) (wm.z)^s / V(cos θi, cos θo)
/// c(s) = (s + 2)/(4π(2 − 2^(−s/2)))  (Normalization::TriAceExact, the seed's derivation)
///      = (s + 2.04)/(8π)               (Normalization::TRI_ACE_2009_FIT, the seed's fit)
///      = 0.0397436 s + 0.0856832       (Normalization::TriAce2010Fit), or any other
///                                       crate::normalization::Normalization
/// V = cos θi (CosThetaI, the seed)   or   max(cos θi, cos θo) (MaxCos, tri-Ace 2010)
/// F(F0, c) = F0 + (1 − F0)(1 − c)⁵
/// ```
///
/// With [`CosThetaI`] the lobe is the seed talk's specular `Out` divided by `N·L`; its
/// view-side albedo `∫ f cos θi dωi = R_s c(s) ∫ F (wm.z)^s dωi` is exactly `R_s` at
/// `wo = n` for `F ≡ 1` and the exact `c(s)` (that is how `c(s)` was derived), but the
/// lobe is not reciprocal and its light-side albedo `∫ f cos θo dωo` exceeds 1 at grazing
/// incidence. With [`MaxCos`] it is reciprocal and
/// its albedo stays ≤ `R_s` for the tri-Ace factors (proved numerically in the tests for
/// `s ∈ [0, 10⁴]`).
///
/// `P` chooses how `(wm.z)^s` is computed: [`ExactPow`] (default, the library `powf`) or
/// [`crate::fast::FastPow`] (polynomial, relative error ≤ 1e-5 on the lobe's domain, and it
/// vectorizes in the [`crate::batch`] kernels). The lobe is evaluated as
/// `(cos²θm)^(s/2)`, `cos²θm = h.z²/|h|²` with `h = wi + wo`: no square root before the
/// `pow`, and one division for both `1/|h|²` and `1/V`.
///
/// For batches, [`crate::batch::eval_pipelined`] evaluates it in passes (geometry and
/// Fresnel, `y·log₂ x`, `exp2`), bit-identical to `eval` and faster on long-chain cores
/// ([`crate::batch::Pipelined`]).
///
/// Domain: `R_s, F0 ∈ [0, 1]`, `s ∈ [0, MAX_SHININESS]` ([`crate::ndf::MAX_SHININESS`]),
/// a [`Normalization::TriAceFit`] offset in `[0, 8]`.
///
/// References: Y. Gotanda, "Basic of Reflectance", tri-Ace, Imagine Day 2009 (the seed);
/// Y. Gotanda, SIGGRAPH 2010 course (the `max(N·L, N·V)` form); C. Schlick 1994.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalizedBlinnPhongSpecular<R, const N: usize, V = CosThetaI, P = ExactPow> {
    rs_c: R,
    f0: [R; N],
    /// `s/2`: the lobe is evaluated as `(cos²θm)^(s/2)`.
    half_shininess: R,
    normalization: Normalization,
    _v: PhantomData<(V, P)>,
}

impl<S: Scalar, const N: usize> NormalizedBlinnPhongSpecular<S, N> {
    /// Lobe with specular intensity `rs ∈ [0, 1]`, Fresnel `f0 ∈ [0, 1]` per channel and
    /// exponent `shininess ∈ [0, MAX_SHININESS]` ([`crate::ndf::MAX_SHININESS`]); `c(s)` is
    /// computed once, in `f64`. The seed's
    /// [`CosThetaI`] denominator and [`ExactPow`]; choose others with
    /// [`Self::with_denominator`] and [`Self::with_pow`].
    ///
    /// # Errors
    /// Names `"rs"`, `"f0"`, `"shininess"` or `"offset"` (of [`Normalization::TriAceFit`]).
    #[inline]
    pub fn new(
        rs: S,
        f0: [S; N],
        shininess: S,
        normalization: Normalization,
    ) -> Result<Self, Error> {
        let rs: f64 = crate::error::unit_interval("rs", rs)?.into();
        let f0 = unit_channels("f0", f0)?;
        let s = shininess_of(shininess)?;
        let normalization = normalization.validate()?;
        Ok(Self {
            rs_c: S::from_f64(rs * normalization.factor(s)),
            f0: splat_channels(f0),
            half_shininess: S::from_f64(0.5 * s),
            normalization,
            _v: PhantomData,
        })
    }
}

impl<R, const N: usize, V, P> NormalizedBlinnPhongSpecular<R, N, V, P> {
    /// The same lobe divided by another [`SpecularDenominator`] (e.g. [`MaxCos`], tri-Ace's
    /// reciprocal 2010 form). The stored constants do not depend on it: this costs nothing.
    #[inline]
    #[must_use]
    pub fn with_denominator<V2: SpecularDenominator>(
        self,
    ) -> NormalizedBlinnPhongSpecular<R, N, V2, P> {
        NormalizedBlinnPhongSpecular {
            rs_c: self.rs_c,
            f0: self.f0,
            half_shininess: self.half_shininess,
            normalization: self.normalization,
            _v: PhantomData,
        }
    }

    /// The same lobe with its power computed by another [`PowFn`] (e.g.
    /// [`crate::fast::FastPow`] for batches). Costs nothing.
    #[inline]
    #[must_use]
    pub fn with_pow<P2: PowFn>(self) -> NormalizedBlinnPhongSpecular<R, N, V, P2> {
        NormalizedBlinnPhongSpecular {
            rs_c: self.rs_c,
            f0: self.f0,
            half_shininess: self.half_shininess,
            normalization: self.normalization,
            _v: PhantomData,
        }
    }
}

impl<R: Real, const N: usize, V: SpecularDenominator, P: PowFn>
    NormalizedBlinnPhongSpecular<R, N, V, P>
{
    /// The normalization this lobe was built with.
    #[inline]
    #[must_use]
    pub fn normalization(&self) -> Normalization {
        self.normalization
    }

    /// The lobe without its power: `(cos²θm, k)` with `f_c = (cos²θm)^(s/2) · k_c`,
    /// `k_c = R_s c(s) F_c / V`, and `k = 0` below the horizon. Shared by `eval` and the
    /// pipelined batch passes (one body).
    #[inline(always)]
    fn lobe_parts(&self, wi: Vec3<R>, wo: Vec3<R>) -> (R, [R; N]) {
        // Lanes below the horizon compute garbage that the final select replaces by 0.
        let m = upper(wi, wo);
        // h = wi + wo; cos θd = |h|/2 (as in `half_and_cos_d`) feeds only the Fresnel term.
        let h = wi + wo;
        let len2 = h.length_squared();
        let cos_d = (len2.sqrt() * R::from_f64(0.5)).min(R::one());
        // The lobe takes no square root: (cos θm)^s = (cos²θm)^(s/2), cos²θm = h.z²/|h|².
        // One division serves both 1/|h|² and 1/V: inv = 1/(|h|² V), so cos²θm = h.z²·V·inv
        // and 1/V = |h|²·inv (|h| > 0 above the horizon, V ≥ DENOM_FLOOR).
        let v = V::denom(wi.z, wo.z);
        let inv = (len2 * v).max(R::from_f64(1e-30)).recip();
        let cos2_m = (h.z * h.z * v * inv).saturate();
        let scale = self.rs_c * (len2 * inv);
        let f = schlick_channels(&self.f0, cos_d);
        (
            cos2_m,
            masked(
                m,
                crate::real::channels(
                    #[inline(always)]
                    |c| f[c] * scale,
                ),
            ),
        )
    }
}

impl<S: Scalar, const N: usize, V: SpecularDenominator, P: PowFn> Splat
    for NormalizedBlinnPhongSpecular<S, N, V, P>
{
    type On<L: Real> = NormalizedBlinnPhongSpecular<L, N, V, P>;
    #[inline]
    fn splat<L: Real>(&self) -> Self::On<L> {
        NormalizedBlinnPhongSpecular {
            rs_c: splat_scalar(self.rs_c),
            f0: splat_array(&self.f0),
            half_shininess: splat_scalar(self.half_shininess),
            normalization: self.normalization,
            _v: PhantomData,
        }
    }
}

impl<R: Real, const N: usize, V: SpecularDenominator, P: PowFn> Brdf<R, N>
    for NormalizedBlinnPhongSpecular<R, N, V, P>
{
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (cos2_m, k) = self.lobe_parts(wi, wo);
        let p = P::pow(cos2_m, self.half_shininess);
        crate::real::channels(
            #[inline(always)]
            |c| p * k[c],
        )
    }

    #[inline]
    fn properties(&self) -> Properties {
        if V::RECIPROCAL {
            let tested = match self.normalization {
                Normalization::TriAceExact | Normalization::TriAce2010Fit => true,
                Normalization::TriAceFit { offset } => offset <= TRI_ACE_OFFSET,
                _ => false,
            };
            Properties {
                reciprocity: Reciprocity::Reciprocal,
                energy: if tested {
                    Energy::Conserving
                } else {
                    Energy::ConservingWhen {
                        condition: "c(s) ≤ the tri-Ace factors (TriAceExact, TriAceFit with \
                                    offset ≤ 2.04, TriAce2010Fit: albedo ≤ R_s, tested); larger \
                                    factors (e.g. BlinnPhongNdf) exceed 1",
                    }
                },
            }
        } else {
            Properties {
                reciprocity: Reciprocity::NotReciprocal {
                    note: "seed form: the specular Out is divided by cos θi only",
                },
                energy: Energy::NotConserving {
                    note: "seed form: the light-side albedo ∫ f cos θo dωo grows like \
                           1/cos θi at grazing incidence (view-side albedo ≤ 1 with the \
                           exact normalization)",
                },
            }
        }
    }
}

/// The seed talk's energy-conserving diffuse: Lambert weighted by what the specular does
/// not reflect.
///
/// ```text
/// f(wi, wo) = (R_d/π) (1 − R_s F(F0, cos θi)),     F(F0, c) = F0 + (1 − F0)(1 − c)⁵
/// ```
///
/// The talk's `Out = R_d/π (1 − R_s F_diffuse(F0)) (N·L)` divided by `N·L`. It depends on
/// `wi` only, so it is **not reciprocal** (the talk says so); its albedo is
/// `R_d (1 − R_s F(F0, cos θi)) ≤ R_d ≤ 1`. Domain: `R_d, R_s, F0 ∈ [0, 1]`.
///
/// Evaluated without cancellation as a sum of two non-negative terms,
///
/// ```text
/// 1 − R_s F(F0, c) = (1 − R_s) + R_s (1 − F0) (1 − (1 − c)⁵)
/// ```
///
/// with both coefficients per material and the last factor by
/// [`crate::fresnel::schlick_complement`]: at grazing light `1 − F → 0`, and `1 − R_s F`
/// computed directly loses every digit in `f32` (10 % at `cos θi = 10⁻⁷`).
///
/// Reference: Y. Gotanda, "Basic of Reflectance", tri-Ace, Imagine Day 2009.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoupledLambert<R, const N: usize> {
    /// `R_d (1 − R_s)/π` per channel.
    base: [R; N],
    /// `R_d R_s (1 − F0)/π` per channel.
    weight: [R; N],
}

impl<S: Scalar, const N: usize> CoupledLambert<S, N> {
    /// Diffuse `rd`, specular intensity `rs` and Fresnel `f0`, all in `[0, 1]`.
    ///
    /// # Errors
    /// Names `"rd"`, `"rs"` or `"f0"`.
    #[inline]
    pub fn new(rd: [S; N], rs: S, f0: [S; N]) -> Result<Self, Error> {
        let rd = unit_channels("rd", rd)?;
        let rs: f64 = crate::error::unit_interval("rs", rs)?.into();
        let f0 = unit_channels("f0", f0)?;
        let rd_over_pi = rd.map(|r| r * core::f64::consts::FRAC_1_PI);
        Ok(Self {
            base: splat_channels(rd_over_pi.map(|r| r * (1.0 - rs))),
            weight: splat_channels(core::array::from_fn(|c| rd_over_pi[c] * rs * (1.0 - f0[c]))),
        })
    }
}

impl<S: Scalar, const N: usize> Splat for CoupledLambert<S, N> {
    type On<L: Real> = CoupledLambert<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> CoupledLambert<L, N> {
        CoupledLambert {
            base: splat_array(&self.base),
            weight: splat_array(&self.weight),
        }
    }
}

impl<R: Real, const N: usize> Brdf<R, N> for CoupledLambert<R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let m = upper(wi, wo);
        let t = crate::fresnel::schlick_complement(wi.z);
        let r: [R; N] = crate::real::channels(
            #[inline(always)]
            |c| self.weight[c].mul_add(t, self.base[c]),
        );
        masked(m, r)
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::NotReciprocal {
                note: "the Fresnel weight depends on cos θi only",
            },
            energy: Energy::Conserving,
        }
    }
}

/// The complete normalized Blinn-Phong of the seed talk: [`CoupledLambert`] plus
/// [`NormalizedBlinnPhongSpecular`].
///
/// ```text
/// Out = R_d/π (1 − R_s F(F0, N·L)) (N·L) + R_s c(s) F(F0, E·H) (N·H)^s
/// f   = R_d/π (1 − R_s F(F0, cos θi))     + R_s c(s) F(F0, wo·wm) (wm.z)^s / V
/// ```
///
/// With `V = CosThetaI` this is the talk's final model ("最終的に導出された正規化
/// Blinn-Phong", with [`Normalization::TriAceExact`], or the slide "改良されたBlinn-Phongの式" with
/// [`Normalization::TRI_ACE_2009_FIT`]). Neither form is reciprocal (the diffuse depends on `wi`
/// only). The diffuse coupling uses `F(F0, N·L)` as a stand-in for the specular's true
/// albedo, so the sum can exceed albedo 1 (proved in the tests, e.g. `R_d = R_s = 1`,
/// `F0 = 0`, grazing `wo`).
///
/// For batches use [`crate::batch::eval_pipelined`] with [`crate::fast::FastPow`] (see
/// [`crate::batch::Pipelined`]).
///
/// Reference: Y. Gotanda, "Basic of Reflectance", tri-Ace, Imagine Day 2009.
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, Normalization, NormalizedBlinnPhong, CosThetaI}};
/// let m = NormalizedBlinnPhong::<f32, 3>::new(
///     [0.8, 0.5, 0.3], 0.5, [0.04; 3], 64.0, Normalization::TriAceExact)?;
/// let n = Vec3::new(0.0, 0.0, 1.0);
/// let f = m.eval(n, n);
/// // Diffuse (0.8/π)(1 − 0.5·0.04) plus the lobe peak 0.5·c(64)·0.04.
/// let c = brdf::normalization::tri_ace_exact(64.0_f32);
/// let expect = 0.8 / core::f32::consts::PI * (1.0 - 0.5 * 0.04) + 0.5 * c * 0.04;
/// assert!((f[0] - expect).abs() < 1e-5);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalizedBlinnPhong<R, const N: usize, V = CosThetaI, P = ExactPow> {
    /// The energy-conserving diffuse term.
    pub diffuse: CoupledLambert<R, N>,
    /// The normalized specular lobe.
    pub specular: NormalizedBlinnPhongSpecular<R, N, V, P>,
}

impl<S: Scalar, const N: usize> NormalizedBlinnPhong<S, N> {
    /// The seed's model with diffuse `rd`, specular intensity `rs`, Fresnel `f0` (all in
    /// `[0, 1]`) and exponent `shininess ∈ [0, MAX_SHININESS]` ([`crate::ndf::MAX_SHININESS`]),
    /// with the seed's [`CosThetaI`]
    /// denominator and [`ExactPow`]; choose others with [`Self::with_denominator`] and
    /// [`Self::with_pow`].
    ///
    /// # Errors
    /// Names `"rd"`, `"rs"`, `"f0"` or `"shininess"`.
    #[inline]
    pub fn new(
        rd: [S; N],
        rs: S,
        f0: [S; N],
        shininess: S,
        normalization: Normalization,
    ) -> Result<Self, Error> {
        Ok(Self {
            diffuse: CoupledLambert::new(rd, rs, f0)?,
            specular: NormalizedBlinnPhongSpecular::new(rs, f0, shininess, normalization)?,
        })
    }
}

impl<R, const N: usize, V, P> NormalizedBlinnPhong<R, N, V, P> {
    /// The same model with the specular divided by another [`SpecularDenominator`] (e.g.
    /// [`MaxCos`]). Costs nothing.
    #[inline]
    #[must_use]
    pub fn with_denominator<V2: SpecularDenominator>(self) -> NormalizedBlinnPhong<R, N, V2, P> {
        NormalizedBlinnPhong {
            diffuse: self.diffuse,
            specular: self.specular.with_denominator(),
        }
    }

    /// The same model with the specular power computed by another [`PowFn`] (e.g.
    /// [`crate::fast::FastPow`]). Costs nothing.
    #[inline]
    #[must_use]
    pub fn with_pow<P2: PowFn>(self) -> NormalizedBlinnPhong<R, N, V, P2> {
        NormalizedBlinnPhong {
            diffuse: self.diffuse,
            specular: self.specular.with_pow(),
        }
    }
}

impl<S: Scalar, const N: usize, V: SpecularDenominator, P: PowFn> Splat
    for NormalizedBlinnPhong<S, N, V, P>
{
    type On<L: Real> = NormalizedBlinnPhong<L, N, V, P>;
    #[inline]
    fn splat<L: Real>(&self) -> Self::On<L> {
        NormalizedBlinnPhong {
            diffuse: self.diffuse.splat(),
            specular: self.specular.splat(),
        }
    }
}

impl<R: Real, const N: usize, V: SpecularDenominator, P: PowFn> Brdf<R, N>
    for NormalizedBlinnPhong<R, N, V, P>
{
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let d = self.diffuse.eval(wi, wo);
        let (cos2_m, k) = self.specular.lobe_parts(wi, wo);
        let p = P::pow(cos2_m, self.specular.half_shininess);
        crate::real::channels(
            #[inline(always)]
            |c| p.mul_add(k[c], d[c]),
        )
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::NotReciprocal {
                note: "the diffuse Fresnel weight depends on cos θi only (and the seed \
                       form's specular is divided by cos θi)",
            },
            energy: Energy::NotConserving {
                note: "the diffuse coupling 1 − R_s F(F0, N·L) underestimates the specular \
                       albedo at grazing view (R_s = 1, F0 = 0)",
            },
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Pipelined batch evaluation
// ---------------------------------------------------------------------------------------------

/// The passes of [`crate::batch::Pipelined`] for the normalized Blinn-Phong: (1) geometry,
/// Fresnel and the diffuse term per pair, (2) `P::start` (`y·log₂ x`), (3) `P::finish`
/// (`exp2`) and `pow·k + d`, block by block — the same bodies as `eval`, so the same bits. For the specular
/// lobe alone `diffuse` returns 0 (and `p·k + 0 = p·k`, as `p·k ≥ 0`).
#[inline(always)]
fn nbp_passes<K, const N: usize, V: SpecularDenominator, P: PowFn>(
    specular: &NormalizedBlinnPhongSpecular<K, N, V, P>,
    diffuse: impl Fn(Vec3<K>, Vec3<K>) -> [K; N],
    wi: crate::batch::Directions<'_>,
    wo: crate::batch::Directions<'_>,
    out: [&mut [f32]; N],
) where
    K: Real<Scalar = f32, Mask = bool>,
{
    use crate::batch::BLOCK;
    let mut x = [K::zero(); BLOCK];
    let mut k = [[K::zero(); BLOCK]; N];
    let mut d = [[K::zero(); BLOCK]; N];
    let y = specular.half_shininess;
    crate::batch::for_each_block(
        wi,
        wo,
        out,
        #[inline(always)]
        |wi, wo, block| {
            let n = wi.len();
            let (ix, iy, iz) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
            let (ox, oy, oz) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
            let x = &mut x[..n];
            // Pass 1: geometry, Fresnel, diffuse.
            for i in 0..n {
                let (wi, wo) = (
                    Vec3::new(K::splat(ix[i]), K::splat(iy[i]), K::splat(iz[i])),
                    Vec3::new(K::splat(ox[i]), K::splat(oy[i]), K::splat(oz[i])),
                );
                let (cos2_m, kk) = specular.lobe_parts(wi, wo);
                let dd = diffuse(wi, wo);
                x[i] = cos2_m;
                for c in 0..N {
                    k[c][i] = kk[c];
                    d[c][i] = dd[c];
                }
            }
            // Pass 2: the first half of pow (y·log₂ x).
            for v in x.iter_mut() {
                *v = P::start(*v, y);
            }
            // Pass 3: the second half (exp2) and the sum.
            let block = block.map(|o| &mut o[..n]);
            for i in 0..n {
                let p = P::finish(x[i], y);
                for c in 0..N {
                    block[c][i] = p.mul_add(k[c][i], d[c][i]).lane(0);
                }
            }
        },
    );
}

impl<K, const N: usize, V: SpecularDenominator, P: PowFn> crate::batch::Pipelined<K, N>
    for NormalizedBlinnPhong<K, N, V, P>
where
    K: Real<Scalar = f32, Mask = bool>,
{
    #[inline(always)]
    fn eval_passes(
        &self,
        wi: crate::batch::Directions<'_>,
        wo: crate::batch::Directions<'_>,
        out: [&mut [f32]; N],
    ) {
        nbp_passes(
            &self.specular,
            |wi, wo| self.diffuse.eval(wi, wo),
            wi,
            wo,
            out,
        );
    }
}

impl<K, const N: usize, V: SpecularDenominator, P: PowFn> crate::batch::Pipelined<K, N>
    for NormalizedBlinnPhongSpecular<K, N, V, P>
where
    K: Real<Scalar = f32, Mask = bool>,
{
    #[inline(always)]
    fn eval_passes(
        &self,
        wi: crate::batch::Directions<'_>,
        wo: crate::batch::Directions<'_>,
        out: [&mut [f32]; N],
    ) {
        nbp_passes(self, |_, _| [K::zero(); N], wi, wo, out);
    }
}

// ---------------------------------------------------------------------------------------------
// Importance sampling
// ---------------------------------------------------------------------------------------------

use crate::sampling::lobes::{
    HalfLobe, PhongHalf, first_probability, mean, pdf_diffuse_and_half, reflect, reflected_pdf,
    sample_diffuse_and_half,
};
use crate::sampling::{Sample, SampleBrdf};

/// The estimate `8π R_s c F̄/(s + 2)` of a Blinn-Phong lobe's albedo `∫ R_s c F (wm.z)^s dωi`
/// at normal incidence (`dωi = 4 (wo·wm) dωm`, `∫ cos^(s+1) θm dωm = 2π/(s + 2)`), with the
/// channel mean of `F(F0, cos θo)` standing in for `F(F0, wo·wm)`.
#[inline(always)]
fn lobe_estimate<R: Real, const N: usize>(rs_c: R, f0: &[R; N], s: R, wo: Vec3<R>) -> R {
    let f = mean(schlick_channels(f0, wo.z.saturate()));
    R::from_f64(8.0 * core::f64::consts::PI) * rs_c * f / (s + R::from_f64(2.0))
}

/// Importance sampling of the engine Blinn-Phong: a one-sample mixture (Veach 1997, §9.2.4)
/// of cosine sampling for `R_d` and the half-vector lobe `p(wm) = (s + 1)/(2π) (wm.z)^s`
/// reflected about `wm` (Ashikhmin & Shirley 2000, §5, with `nu = nv = s`), so
///
/// ```text
/// pdf(wi) = P_d cos θi/π + (1 − P_d) (s + 1)/(2π) (wm.z)^s / (4 wo·wm)
/// P_d = ρ̂_d/(ρ̂_d + ρ̂_s),   ρ̂_d = π mean(R_d),   ρ̂_s = 8π R_s mean(F(F0, cos θo))/(s + 2)
/// ```
///
/// `u[2] < P_d` chooses the diffuse lobe. `weight = f cos θi / pdf` with the whole `f`.
/// [`SampleBrdf::albedo_estimate`] is `ρ̂_d + ρ̂_s`.
impl<R: Real, const N: usize, S: SqrtFn> SampleBrdf<R, N> for ClassicBlinnPhong<R, N, S> {
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let (pd, lobe) = self.mixture(wo);
        sample_diffuse_and_half(
            &lobe,
            pd,
            wo,
            u,
            #[inline(always)]
            |wi| self.eval(wi, wo),
        )
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        let (pd, lobe) = self.mixture(wo);
        pdf_diffuse_and_half(&lobe, pd, wo, wi)
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        let (d, s) = self.estimates(wo);
        d + s
    }
}

impl<R: Real, const N: usize, S: SqrtFn> ClassicBlinnPhong<R, N, S> {
    /// `(ρ̂_d, ρ̂_s)` (see the [`SampleBrdf`] impl).
    #[inline(always)]
    fn estimates(&self, wo: Vec3<R>) -> (R, R) {
        (
            R::pi() * mean(self.rd),
            lobe_estimate(self.rs, &self.f0, self.shininess, wo),
        )
    }

    /// `(P_d, half-vector lobe)`.
    #[inline(always)]
    fn mixture(&self, wo: Vec3<R>) -> (R, PhongHalf<R>) {
        let (d, s) = self.estimates(wo);
        let lobe = PhongHalf {
            nu: self.shininess,
            nv: self.shininess,
        };
        (first_probability(d, s), lobe)
    }
}

impl<R: Real, const N: usize, V: SpecularDenominator, P: PowFn>
    NormalizedBlinnPhongSpecular<R, N, V, P>
{
    /// The half-vector lobe `(s + 1)/(2π) (wm.z)^s`.
    #[inline(always)]
    fn half_lobe(&self) -> PhongHalf<R> {
        let s = self.half_shininess + self.half_shininess;
        PhongHalf { nu: s, nv: s }
    }

    /// `ρ̂_s = 8π R_s c(s) mean(F(F0, cos θo))/(s + 2)` (≈ `R_s F̄` for the tri-Ace factors).
    #[inline(always)]
    fn estimate(&self, wo: Vec3<R>) -> R {
        let s = self.half_shininess + self.half_shininess;
        lobe_estimate(self.rs_c, &self.f0, s, wo)
    }
}

/// Importance sampling of the normalized Blinn-Phong lobe: the half vector from
/// `p(wm) = (s + 1)/(2π) (wm.z)^s` (Ashikhmin & Shirley 2000, §5, `nu = nv = s`), `wo`
/// reflected about it:
///
/// ```text
/// pdf(wi) = (s + 1)/(2π) (wm.z)^s / (4 wo·wm),     wm = (wi + wo)/|wi + wo|
/// weight  = R_s c(s) F(F0, wo·wm) · (cos θi / V) · 8π (wo·wm)/(s + 1)
/// ```
///
/// The weight is that closed form (the powers cancel), not a quotient of two tiny numbers.
/// A drawn `wm` with `wo·wm ≤ 0`, or a reflection below the horizon, is an invalid sample.
/// `u[2]` is unused. [`SampleBrdf::albedo_estimate`] is `8π R_s c(s) mean(F(F0, cos θo))/(s + 2)`.
impl<R: Real, const N: usize, V: SpecularDenominator, P: PowFn> SampleBrdf<R, N>
    for NormalizedBlinnPhongSpecular<R, N, V, P>
{
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let lobe = self.half_lobe();
        let (wi, ok) = reflect(wo, lobe.draw(u[0], u[1]));
        let pdf = reflected_pdf(&lobe, wo, wi);
        let f = self.eval(wi, wo);
        let (_, k) = self.lobe_parts(wi, wo);
        let (_, cos_d) = half_and_cos_d::<ExactSqrt, R>(wi, wo);
        let cos_d = cos_d.min(R::one());
        let s = self.half_shininess + self.half_shininess;
        let g = R::from_f64(8.0 * core::f64::consts::PI) * cos_d * wi.z / (s + R::one());
        let weight = crate::real::channels(
            #[inline(always)]
            |c| k[c] * g,
        );
        Sample::new(wi, pdf, f, weight, ok & wo.z.gt(R::zero()))
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        reflected_pdf(&self.half_lobe(), wo, wi)
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        self.estimate(wo)
    }
}

/// Importance sampling of the seed's normalized Blinn-Phong: a one-sample mixture (Veach
/// 1997, §9.2.4) of cosine sampling for the [`CoupledLambert`] diffuse and the specular's
/// half-vector lobe ([`NormalizedBlinnPhongSpecular`]'s sampler):
///
/// ```text
/// pdf(wi) = P_d cos θi/π + (1 − P_d) (s + 1)/(2π) (wm.z)^s / (4 wo·wm)
/// P_d = ρ̂_d/(ρ̂_d + ρ̂_s),   ρ̂_d = R_d (1 − R_s mean(F0)),   ρ̂_s = 8π R_s c(s) mean(F(F0, cos θo))/(s + 2)
/// ```
///
/// `u[2] < P_d` chooses the diffuse lobe; `weight = f cos θi / pdf` with the whole `f`.
/// [`SampleBrdf::albedo_estimate`] is `ρ̂_d + ρ̂_s`.
impl<R: Real, const N: usize, V: SpecularDenominator, P: PowFn> SampleBrdf<R, N>
    for NormalizedBlinnPhong<R, N, V, P>
{
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let pd = self.diffuse_probability(wo);
        sample_diffuse_and_half(&self.specular.half_lobe(), pd, wo, u, |wi| {
            self.eval(wi, wo)
        })
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        let pd = self.diffuse_probability(wo);
        pdf_diffuse_and_half(&self.specular.half_lobe(), pd, wo, wi)
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        self.diffuse.estimate() + self.specular.estimate(wo)
    }
}

impl<R: Real, const N: usize, V: SpecularDenominator, P: PowFn> NormalizedBlinnPhong<R, N, V, P> {
    /// `P_d = ρ̂_d/(ρ̂_d + ρ̂_s)`.
    #[inline(always)]
    fn diffuse_probability(&self, wo: Vec3<R>) -> R {
        first_probability(self.diffuse.estimate(), self.specular.estimate(wo))
    }
}

impl<R: Real, const N: usize> CoupledLambert<R, N> {
    /// `R_d (1 − R_s F0)` averaged over the channels: the albedo at normal incidence (and an
    /// upper bound at every angle).
    #[inline(always)]
    pub(crate) fn estimate(&self) -> R {
        R::pi()
            * mean(crate::real::channels::<R, N>(|c| {
                self.base[c] + self.weight[c]
            }))
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file descriptions of [`ClassicBlinnPhong`] (`model = "classic_blinn_phong"`) and
/// [`NormalizedBlinnPhong`] (`model = "normalized_blinn_phong"`), re-exported from
/// [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use serde::{Deserialize, Serialize};

    use super::{ClassicBlinnPhong, NormalizedBlinnPhong};
    use crate::Scalar;
    use crate::material::{Material, MaterialError, ModelDesc, Reflectance, Rgb, invalid};
    use crate::normalization::Normalization;

    crate::material::field_fns!(rd, rs, f0, shininess, normalization, denominator, offset);

    /// [`ClassicBlinnPhong`], the engine form `Out = R_d (N·L) + R_s F (N·H)^s`.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `classic_blinn_phong`")]
    pub struct ClassicBlinnPhongDesc {
        /// Diffuse coefficient (the albedo is `π rd`).
        #[serde(deserialize_with = "field::rd")]
        pub rd: Rgb,
        /// Specular coefficient `R_s ∈ [0, 1]`.
        #[serde(deserialize_with = "field::rs")]
        pub rs: f64,
        /// Schlick's normal-incidence reflectance.
        #[serde(deserialize_with = "field::f0")]
        pub f0: Reflectance,
        /// Exponent `s ≥ 0`.
        #[serde(deserialize_with = "field::shininess")]
        pub shininess: f64,
    }

    impl ModelDesc for ClassicBlinnPhongDesc {
        const NAME: &'static str = "classic_blinn_phong";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let inv = invalid(Self::NAME);
            let f0 = Rgb(self.f0.value().map_err(&inv)?).scalars();
            let (rs, shininess) = (S::of(self.rs), S::of(self.shininess));
            Ok(ClassicBlinnPhong::new(self.rd.scalars(), rs, f0, shininess)
                .map_err(inv)?
                .into())
        }
    }

    /// Which normalization factor a normalized Blinn-Phong uses (see
    /// [`Normalization`] for the formulas). In TOML: `normalization = "tri_ace_exact"`, or
    /// `{ tri_ace_fit = { offset = 2.0 } }`.
    #[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
    #[serde(rename_all = "snake_case")]
    #[serde(expecting = "a normalization name")]
    pub enum NormalizationDesc {
        /// [`Normalization::Unnormalized`].
        Unnormalized,
        /// [`Normalization::TriAceExact`].
        TriAceExact,
        /// [`Normalization::TriAceFit`] with another offset.
        TriAceFit {
            /// The offset `n` of `(s + n)/(8π)`.
            #[serde(deserialize_with = "field::offset")]
            offset: f64,
        },
        /// [`Normalization::TRI_ACE_2009_FIT`], the seed's `(s + 2.04)/(8π)` (default). In files
        /// `"tri_ace_2009_fit"` (also accepted: `"tri_ace2009_fit"`, serde's own snake case of the
        /// variant name, which earlier versions required).
        #[default]
        #[serde(rename = "tri_ace_2009_fit", alias = "tri_ace2009_fit")]
        TriAce2009Fit,
        /// [`Normalization::TriAce2010Fit`]. In files `"tri_ace_2010_fit"` (also accepted:
        /// `"tri_ace2010_fit"`).
        #[serde(rename = "tri_ace_2010_fit", alias = "tri_ace2010_fit")]
        TriAce2010Fit,
        /// [`Normalization::BlinnPhongNdf`].
        BlinnPhongNdf,
        /// [`Normalization::BlinnPhongCosineExact`].
        BlinnPhongCosineExact,
        /// [`Normalization::BlinnPhongRtrApprox`].
        BlinnPhongRtrApprox,
        /// [`Normalization::PhongLobe`].
        PhongLobe,
        /// [`Normalization::PhongCosine`].
        PhongCosine,
    }

    impl NormalizationDesc {
        /// The crate's [`Normalization`].
        #[must_use]
        pub fn normalization(self) -> Normalization {
            match self {
                NormalizationDesc::Unnormalized => Normalization::Unnormalized,
                NormalizationDesc::TriAceExact => Normalization::TriAceExact,
                NormalizationDesc::TriAceFit { offset } => Normalization::TriAceFit { offset },
                NormalizationDesc::TriAce2009Fit => Normalization::TRI_ACE_2009_FIT,
                NormalizationDesc::TriAce2010Fit => Normalization::TriAce2010Fit,
                NormalizationDesc::BlinnPhongNdf => Normalization::BlinnPhongNdf,
                NormalizationDesc::BlinnPhongCosineExact => Normalization::BlinnPhongCosineExact,
                NormalizationDesc::BlinnPhongRtrApprox => Normalization::BlinnPhongRtrApprox,
                NormalizationDesc::PhongLobe => Normalization::PhongLobe,
                NormalizationDesc::PhongCosine => Normalization::PhongCosine,
            }
        }
    }

    /// The specular denominator of a normalized Blinn-Phong.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
    #[serde(rename_all = "snake_case")]
    #[serde(expecting = "a denominator name")]
    pub enum DenominatorDesc {
        /// [`CosThetaI`](crate::models::CosThetaI): the seed talk's form (default).
        #[default]
        CosThetaI,
        /// [`MaxCos`](crate::models::MaxCos): tri-Ace 2010's reciprocal form.
        MaxCos,
    }

    /// [`NormalizedBlinnPhong`], the seed talk's model.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `normalized_blinn_phong`")]
    pub struct NormalizedBlinnPhongDesc {
        /// Diffuse albedo.
        #[serde(deserialize_with = "field::rd")]
        pub rd: Rgb,
        /// Specular intensity `R_s ∈ [0, 1]`.
        #[serde(deserialize_with = "field::rs")]
        pub rs: f64,
        /// Schlick's normal-incidence reflectance.
        #[serde(deserialize_with = "field::f0")]
        pub f0: Reflectance,
        /// Exponent `s ≥ 0`.
        #[serde(deserialize_with = "field::shininess")]
        pub shininess: f64,
        /// Normalization factor (default `tri_ace_2009_fit`).
        #[serde(default, deserialize_with = "field::normalization")]
        pub normalization: NormalizationDesc,
        /// Specular denominator (default `cos_theta_i`).
        #[serde(default, deserialize_with = "field::denominator")]
        pub denominator: DenominatorDesc,
    }

    impl ModelDesc for NormalizedBlinnPhongDesc {
        const NAME: &'static str = "normalized_blinn_phong";

        fn is_anisotropic(&self) -> bool {
            false
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let inv = invalid(Self::NAME);
            let f0 = Rgb(self.f0.value().map_err(&inv)?).scalars();
            let norm = self.normalization.normalization();
            let (rd, rs, sh) = (self.rd.scalars(), S::of(self.rs), S::of(self.shininess));
            let m = NormalizedBlinnPhong::new(rd, rs, f0, sh, norm).map_err(inv)?;
            Ok(match self.denominator {
                DenominatorDesc::CosThetaI => m.into(),
                DenominatorDesc::MaxCos => m.with_denominator::<super::MaxCos>().into(),
            })
        }
    }
}
