//! Fresnel reflectance: exact dielectric and conductor equations, Cook-Torrance's (g, c)
//! form, Schlick's approximation, and two models for metals (Hoffman's F82-tint and
//! Gulbrandsen's artist-friendly reflectivity / edge-tint mapping).
//!
//! Every formula is written once, generic over [`Real`], without branches on lane values, so
//! it evaluates on `f32`, `f64` and SIMD lanes alike. The [`FresnelTerm`] implementations
//! ([`Schlick`], [`Dielectric`], [`Conductor`], [`FittedConductor`], [`F82Tint`],
//! [`NoFresnel`]) are what the BRDF models consume: validated once at construction, with
//! per-material constants precomputed.
//!
//! # Conventions
//!
//! * `cos_theta_i = cos θi`, the cosine between the incident direction and the normal of the
//!   interface (for a microfacet model, `cos θd = wi·wm`). `eta = η_t / η_i`, the relative
//!   IOR of the far side over the near side; the dielectric functions flip it (`1/eta`)
//!   when `cos_theta_i < 0` (light arriving from inside). The [`FresnelTerm`]s of the BRDF
//!   models do not: they take `|cos θd|` (see [`Dielectric`]).
//! * A conductor's complex IOR is `eta + i·k` with `k ≥ 0` (time dependence `e^{−iωt}`, as
//!   pbrt). The seed talk (Gotanda 2009) writes `n − iκ`, the conjugate: reflectances are the
//!   same, phases of the complex amplitudes are conjugated.
//! * Amplitude signs follow the seed talk (and Fresnel's original, "Verdet" convention):
//!
//!   ```text
//!   r_s = (cos θi − η cos θt) / (cos θi + η cos θt)
//!   r_p = (cos θt − η cos θi) / (cos θt + η cos θi)      (r_p = r_s at normal incidence)
//!   t_s = 2 cos θi / (cos θi + η cos θt)
//!   t_p = 2 cos θi / (η cos θi + cos θt)
//!   ```
//!
//!   pbrt-v4's `FrDielectric` uses `r_perp = r_s` and `r_parl = (η cos θi − cos θt) /
//!   (η cos θi + cos θt) = −r_p` (Hecht's convention): the reflectance `(r_s² + r_p²)/2`
//!   is the same.
//! * Everything is computed from `g = η cos θt = √(η² − 1 + cos²θi)` (Cook & Torrance 1982),
//!   which is exact at `η = 1` and reaches total internal reflection (TIR) when `g² < 0`.
//!
//! # Parameter domains
//!
//! The constructors accept a relative IOR `eta ∈ [MIN_ETA, MAX_ETA] = [1e-4, 1e4]` and an
//! extinction coefficient `k ∈ [0, MAX_K] = [0, 1e4]` (and reflectances from which an IOR is
//! derived up to [`MAX_DIELECTRIC_F0`]), whatever number type they are built on. These are
//! *physical* bounds, chosen wider than any optical constant: relative IORs of dielectric
//! interfaces lie within about `[1/4, 4]`, the real parts of metals' IORs above `0.01`
//! (silver, sodium) and their `k` below `~10³` from the ultraviolet to the far infrared
//! (aluminium at 10 µm: `n ≈ 25`, `k ≈ 90`). Beyond them the formulas stop representing
//! anything in `f32`, the narrowest type a term may be splatted to: `η²`, `k²` and
//! `(η² + k²)²` overflow (`Dielectric::new(1e20)` and `conductor` at `k ≈ 1e12` gave NaN in
//! `f32`), and near normal incidence `η² − 1` rounds away the `η²` that `g²` reduces to. Inside
//! them every intermediate is finite and normal in `f32`, and `tests/domains.rs` evaluates
//! every constructor over its whole domain on `f32`, `f64` and lanes, with the `f64`-built
//! terms splatted to `f32` too — which is why an `f64` term has the same domain.
//!
//! The free functions ([`dielectric`], [`conductor`], …) do not validate; their documented
//! domain is the same, and they stay finite somewhat beyond it.
//!
//! # Accuracy of the approximations for metals
//!
//! Maximum absolute error over `cos θ ∈ [0, 1]` against the exact [`conductor`] Fresnel, per
//! channel (R, G, B at 650/550/450 nm), for the metal presets ([`crate::ior::Preset::METALS`])
//! (measured by `tests/fresnel.rs::metal_models_error_table`, which asserts these bounds):
//!
//! | metal     | F0 (R, G, B)        | Schlick (R, G, B)     | F82-tint (R, G, B)       |
//! |-----------|---------------------|-----------------------|--------------------------|
//! | gold      | 0.963, 0.787, 0.408 | 0.0153, 0.0096, 0.0176 | 0.0044, 0.0061, 0.0169 |
//! | silver    | 0.991, 0.983, 0.980 | 0.0061, 0.0066, 0.0023 | 0.0011, 0.0021, 0.0016 |
//! | copper    | 0.943, 0.619, 0.539 | 0.0235, 0.0390, 0.0399 | 0.0063, 0.0056, 0.0017 |
//! | aluminium | 0.905, 0.915, 0.923 | 0.1304, 0.1000, 0.0646 | 0.0223, 0.0090, 0.0060 |
//! | iron      | 0.532, 0.512, 0.496 | 0.1785, 0.1759, 0.1493 | 0.0181, 0.0187, 0.0123 |
//! | titanium  | 0.618, 0.582, 0.545 | 0.1865, 0.1658, 0.1385 | 0.0164, 0.0113, 0.0080 |
//! | chromium  | 0.557, 0.555, 0.555 | 0.1933, 0.1978, 0.1454 | 0.0218, 0.0236, 0.0087 |
//!
//! Schlick uses the exact `F0`; F82-tint is fitted to the exact reflectance at `cos θ = 1`
//! and `1/7` ([`F82Tint::from_ior`]). Schlick is good for the noble metals (error ≤ 0.04)
//! and poor for aluminium and the "grey" transition metals (0.06–0.20): their exact curve
//! dips well below Schlick's before grazing, a dip Schlick cannot produce. There F82-tint
//! cuts the error 6–17× (to ≤ 0.024) for one more multiply-add per channel; for the noble
//! metals the gain is smaller (gold blue barely improves, 0.0176 → 0.0169). For dielectrics
//! Schlick's error peaks at 0.036 for glass (`η = 1.5`, at ≈ 85°).
//!
//! Gulbrandsen's mapping is a re-parametrization of the exact equations: its error against
//! the exact Fresnel is rounding only (measured ≤ 3·10⁻¹⁵ for every preset), as long as the
//! material's edge tint `g` lies in `[0, 1]`; it does for all seven presets (`g` from 0.54
//! for iron to 1.000 for silver, see [`reference::gulbrandsen_from_nk`]).
//!
//! [`FittedConductor`] is not a model of metals but the exact reflectance of one, tabulated:
//! a piecewise quintic in `cos θ` fitted at construction and refused where it misses
//! [`FIT_CHECK_BOUND`] (2·10⁻⁷ relative) at its check points, tested within
//! [`FIT_TOLERANCE`] (2.5·10⁻⁷) everywhere. In `f32` it is closer to the `f64` closed form
//! than the closed form evaluated in `f32` (1.2·10⁻⁷ against 4.8·10⁻⁷ at worst on the
//! presets over 2²⁰ cosines),
//! and on the AVX-512 batch path it needs no square root or division.
//!
//! # References
//!
//! * A. Fresnel (1823); M. Born, E. Wolf, *Principles of Optics*, 7th ed., §1.5.
//! * R. L. Cook, K. E. Torrance, "A Reflectance Model for Computer Graphics", ACM Trans. Graph. 1(1), 1982.
//! * C. Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", CGF 13(3), 1994.
//! * N. Hoffman, "Fresnel Equations Considered Harmful", EGSR/MAM workshop 2019; A. Kutz et al.,
//!   "Novel aspects of the Adobe Standard Material", 2021; Open PBR Surface specification 1.0, 2024.
//! * O. Gulbrandsen, "Artist Friendly Metallic Fresnel", JCGT 3(4), 2014.
//! * M. Pharr, W. Jakob, G. Humphreys, *Physically Based Rendering*, 4th ed., §9.3.
//! * Y. Gotanda, "Basic of Reflectance", tri-Ace, 2009 (the seed talk).

use core::marker::PhantomData;

mod fitted;
pub use fitted::{FIT_CHECK_BOUND, FIT_DEGREE, FIT_SEGMENTS, FIT_TOLERANCE, FittedConductor};

use num_complex::Complex;

use crate::error::{self, Error};
use crate::fast::{ExactSqrt, SqrtFn};
use crate::ior::Preset;
use crate::real::{Splat, splat_array, splat_scalar};
use crate::{Real, Scalar};

/// A Fresnel term as a BRDF model uses it: reflectance per colour channel as a function of
/// `cos θd = wi·wm`, the cosine between the light and the microfacet normal.
pub trait FresnelTerm<R: Real, const N: usize> {
    /// Reflectance per channel, each in `[0, 1]`, for `cos_theta_d ∈ [0, 1]`.
    ///
    /// The microfacet models pass `cos θd = |wi + wo|/2`, which can exceed 1 by a rounding
    /// (by a few ULP with [`crate::fast::HardwareEstimate`]): the terms of this module clamp
    /// it, and an implementation whose formula needs `cos θd ≤ 1` should too.
    fn eval(&self, cos_theta_d: R) -> [R; N];

    /// [`FresnelTerm::eval`] for a caller that also has `cos²θd` (`cos2_theta_d`, equal to
    /// `cos_theta_d²` up to rounding, in `[0, 1]`).
    ///
    /// A microfacet model has `cos²θd = |wi + wo|²/4` one square root before `cos θd = |wi +
    /// wo|/2`. The exact dielectric and conductor terms start from `cos²θd` (`η² − sin²θ`), so
    /// given it they start before that square root has finished: a shorter dependency chain
    /// per evaluation (measured on the rough-conductor batch: see the README). The other terms
    /// ignore it (the default).
    #[inline(always)]
    fn eval_cos2(&self, cos_theta_d: R, cos2_theta_d: R) -> [R; N] {
        let _ = cos2_theta_d;
        self.eval(cos_theta_d)
    }
}

// ---------------------------------------------------------------------------------------
// Dielectric
// ---------------------------------------------------------------------------------------

/// The Fresnel amplitude coefficients of a dielectric interface, and the geometry they came
/// from. Returned by [`dielectric_amplitudes`].
///
/// Sign convention: the seed talk's (see the [module docs](self)); `r_p = r_s` at normal
/// incidence. pbrt's `r_parl` is `−r_p`, its `r_perp` is `r_s`.
///
/// Beyond the critical angle (TIR) the true amplitudes are complex of modulus 1; this real
/// struct then holds their values at the critical angle, `r_s = 1`, `r_p = −1`, and
/// `t_s = t_p = 0` (no power is transmitted; the evanescent field is not a transmission
/// coefficient). For the phases use [`conductor_amplitudes`] with `k = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Amplitudes<R> {
    /// s (perpendicular, TE) amplitude reflection coefficient, in `[−1, 1]`.
    pub r_s: R,
    /// p (parallel, TM) amplitude reflection coefficient, in `[−1, 1]`.
    pub r_p: R,
    /// s amplitude transmission coefficient, `2 cos θi / (cos θi + η cos θt)`.
    pub t_s: R,
    /// p amplitude transmission coefficient, `2 cos θi / (η cos θi + cos θt)`.
    pub t_p: R,
    /// `|cos θi|`, clamped to `[0, 1]`.
    pub cos_theta_i: R,
    /// `cos θt ≥ 0` of the refracted direction (its magnitude; `0` under TIR).
    pub cos_theta_t: R,
    /// The relative IOR actually used: `eta`, or `1/eta` for incidence from inside.
    pub eta: R,
}

impl<R: Real> Amplitudes<R> {
    /// Unpolarized reflectance `r = (r_s² + r_p²) / 2` (the seed's `r`, pbrt's
    /// `FrDielectric`). Equals `1` under total internal reflection.
    #[inline(always)]
    #[must_use]
    pub fn reflectance(&self) -> R {
        (self.r_s * self.r_s + self.r_p * self.r_p) * R::from_f64(0.5)
    }

    /// Unpolarized power transmittance computed from the transmission amplitudes:
    ///
    /// ```text
    /// T_s = (η cos θt / cos θi) t_s²,   T_p = (η cos θt / cos θi) t_p²,   t = (T_s + T_p)/2
    /// ```
    ///
    /// The factor `η cos θt / cos θi` converts the ratio of field amplitudes into a ratio of
    /// power fluxes through the interface (the refracted beam has a different cross-section
    /// and travels in a medium of another impedance); the seed talk folds its square root
    /// into its `t_s`, `t_p`. Energy conservation gives `t = 1 − r`
    /// (`tests/fresnel.rs` checks it over the whole domain). At exactly grazing incidence
    /// (`cos θi = 0`) the limit is used: `0`, or `1` when `η = 1`.
    #[inline]
    #[must_use]
    pub fn transmittance(&self) -> R {
        let c = self.cos_theta_i;
        let g = self.eta * self.cos_theta_t;
        let factor = g / c;
        let t = factor * (self.t_s * self.t_s + self.t_p * self.t_p) * R::from_f64(0.5);
        // c = 0: no power crosses unless the interface is index-matched (g = 0, no TIR).
        let limit = R::select(
            g.gt(R::zero()) | self.t_s.eq(R::zero()),
            R::zero(),
            R::one(),
        );
        // Rounding can exceed 1 by an ulp near η = 1.
        R::select(c.gt(R::zero()), t.min(R::one()), limit)
    }
}

/// Fresnel amplitude coefficients `r_s, r_p, t_s, t_p` of a smooth dielectric interface.
///
/// ```text
/// η' = η if cos θi ≥ 0, 1/η otherwise;   c = min(|cos θi|, 1)
/// g² = η'² − 1 + c²  (= η'² cos² θt);    g = √g²          TIR when g² < 0
/// r_s = (c − g) / (c + g)                r_p = (g − η'² c) / (g + η'² c)
/// t_s = 2c / (c + g)                     t_p = 2η' c / (η'² c + g)
/// ```
///
/// (The seed's forms with `n₁ = 1, n₂ = η'`, multiplied through by `η'`; `g = η' cos θt`.)
///
/// Evaluated divided through by `η'` (see `DielectricConsts`), which avoids three losses of
/// the direct form: `η'²` overflowing (`f32` gave NaN from `η = 1e20`); `cos θt` near normal
/// incidence for small `η'`, where `η'² − 1 + c²` rounds away the `η'²` it reduces to (in
/// `f32` at `η' = 1e-6`, `cos θt` came out 244); and at `η' = 1` exactly `cos θt = c` (where
/// `√(c²)` loses `c` once `c²` underflows, below `c ≈ 1e-19` in `f32`, and
/// `r_s = (c − 0)/(c + 0)` gave `r = 1`). Both numerators are no larger than their
/// denominators, so `|r_s|, |r_p| ≤ 1` holds exactly after rounding.
///
/// * Domain: `eta ∈ [MIN_ETA, MAX_ETA]` (tested on every lane type); finite for every `eta`
///   from `≈ 1e-19` (`f32`; `1/eta²` must be finite) to the largest finite value. Any
///   `cos_theta_i` (values a rounding step outside `[−1, 1]` are clamped).
/// * Normal incidence: `r_s = r_p = (1 − η)/(1 + η)`. Grazing (`c = 0`, `η ≠ 1`):
///   `r_s = −1, r_p = 1`. Index-matched (`η = 1`): `r_s = r_p = 0`, `r = 0, t = 1`
///   everywhere, including `c = 0`. `cos θt ∈ [0, 1]` (clamped against rounding).
/// * Under TIR: see [`Amplitudes`] (`r_s = 1`, `r_p = −1`, `t_s = t_p = 0`).
///
/// Reference: Born & Wolf, *Principles of Optics*, §1.5.2; Cook & Torrance 1982 for the
/// `g` form; pbrt-v4 §9.3.
///
/// # Examples
///
/// ```
/// use brdf::fresnel::dielectric_amplitudes;
/// let a = dielectric_amplitudes(1.0_f64, 1.5);
/// assert!((a.r_s + 0.2).abs() < 1e-15 && (a.r_p + 0.2).abs() < 1e-15);
/// assert!((a.reflectance() + a.transmittance() - 1.0).abs() < 1e-15);
/// ```
#[inline]
#[must_use]
pub fn dielectric_amplitudes<R: Real>(cos_theta_i: R, eta: R) -> Amplitudes<R> {
    // 1/η' from η' itself (not η), so that dielectric(−c, η) = dielectric(c, 1/η) exactly.
    let eta = R::select(cos_theta_i.lt(R::zero()), eta.recip(), eta);
    let inv = eta.recip();
    let c = cos_theta_i.abs().min(R::one());
    oriented_amplitudes(c, c * c, DielectricConsts::of(eta, inv))
}

/// The per-IOR constants of the dielectric formulas, for the relative IOR `eta` seen from
/// the incident side. [`Dielectric`] stores them; the free functions compute them per call
/// with the same body, so both give the same bits.
///
/// Every formula is divided through by `η` (numerators and denominators alike), so that it
/// needs `cos θt = g/η` rather than `g` and no `η²`: finite for every `η` whose reciprocal
/// squared is finite (`η ≳ 1e-19` in `f32`), `1e20` and `f32::MAX` included. `cos²θt` is
/// `(c² − q)/η² + p`, in whichever of two forms rounds less for the IOR:
/// * `η ≥ 1/√2`: `p = ((η − 1)/η)((η + 1)/η)`, `q = 0`, i.e. `(η² − 1 + c²)/η²`. `η − 1` is
///   exact near `η = 1` (Sterbenz), so `p` keeps its relative accuracy where it is small
///   (`(1 − 1/η)(1 + 1/η)` would not: `1/η` is rounded, an error of `ε/(η − 1)` relative —
///   visible as `1e-11` in the reflectance at `η = 1 + 1e-8`, grazing). For `η ≥ 1` a sum of
///   two terms `≥ 0`; for `η ∈ [1/√2, 1)` the rounding of `|p| ≤ 1` and of `c²/η² ≤ 2` stays
///   a few `ε`.
/// * `η < 1/√2`: `p = 1`, `q = 1`, i.e. `1 − s²/η²` with `s² = 1 − c²`. Light is only
///   transmitted for `s < η`, i.e. `c² > 1/2`, where `c² − 1` is exact (Sterbenz), so near
///   normal incidence `cos θt → 1` keeps its digits, which `(η² − 1 + c²)/η²` cancels away
///   for small `η` (its rounding error `≈ ε/η²`: 244 instead of 1 in `f32` at `η = 1e-6`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct DielectricConsts<R> {
    eta: R,
    inv_eta: R,
    inv_eta2: R,
    p: R,
    q: R,
}

impl<R: Real> DielectricConsts<R> {
    /// The constants of `eta`, given `inv_eta = 1/eta`.
    #[inline(always)]
    fn of(eta: R, inv_eta: R) -> Self {
        let below = eta.lt(R::from_f64(core::f64::consts::FRAC_1_SQRT_2));
        let p = ((eta - R::one()) * inv_eta) * ((eta + R::one()) * inv_eta);
        Self {
            eta,
            inv_eta,
            inv_eta2: inv_eta * inv_eta,
            p: R::select(below, R::one(), p),
            q: R::select(below, R::one(), R::zero()),
        }
    }

    /// `cos θt = g/η` (`0` under TIR) and the TIR mask, for `c ∈ [0, 1]`, `c2 = c²`.
    #[inline(always)]
    fn cos_t(&self, c: R, c2: R) -> (R, R::Mask) {
        let t2 = (c2 - self.q).mul_add(self.inv_eta2, self.p);
        // η = 1: cos θt = c exactly (√(c²) loses c where c² underflows).
        let matched = self.eta.eq(R::one());
        (R::select(matched, c, t2.safe_sqrt()), t2.lt(R::zero()))
    }
}

/// The body of [`dielectric_amplitudes`] once the side is resolved: `c = |cos θi| ∈ [0, 1]`,
/// `c2 = c²` (up to rounding) and the constants of the relative IOR seen from the incident
/// side. [`Dielectric`] calls it directly (its cosines are never negative), so its `eval`
/// spends no division on `1/eta`.
///
/// With `t = cos θt = g/η`, `c/η` and `ηc`, the amplitudes of [`dielectric_amplitudes`]
/// divided through by `η`:
///
/// ```text
/// r_s = (c/η − t)/(c/η + t)     r_p = (t − ηc)/(t + ηc)
/// t_s = 2(c/η)/(c/η + t)        t_p = 2c/(t + ηc)
/// ```
#[inline(always)]
fn oriented_amplitudes<R: Real>(c: R, c2: R, k: DielectricConsts<R>) -> Amplitudes<R> {
    let (t, tir) = k.cos_t(c, c2);
    let c_eta = c * k.inv_eta;
    let eta_c = k.eta * c;
    let den_s = c_eta + t;
    let den_p = t + eta_c;
    // The denominators vanish together, only for c = 0 and t = 0: η = 1 at grazing
    // (index-matched) or the critical angle at grazing; the TIR select below handles the
    // latter.
    let ok = den_s.gt(R::zero());
    let r_s = R::select(ok, (c_eta - t) / den_s, R::zero());
    let r_p = R::select(ok, (t - eta_c) / den_p, R::zero());
    let t_s = R::select(ok, (c_eta + c_eta) / den_s, R::one());
    let t_p = R::select(ok, (c + c) / den_p, R::one());
    Amplitudes {
        r_s: R::select(tir, R::one(), r_s),
        r_p: R::select(tir, -R::one(), r_p),
        t_s: R::select(tir, R::zero(), t_s),
        t_p: R::select(tir, R::zero(), t_p),
        cos_theta_i: c,
        cos_theta_t: t.min(R::one()),
        eta: k.eta,
    }
}

/// `oriented_amplitudes(..).reflectance()`: what [`Dielectric`] evaluates (the transmission
/// coefficients are not computed once inlined).
#[inline(always)]
fn dielectric_reflectance<R: Real>(c: R, c2: R, k: DielectricConsts<R>) -> R {
    oriented_amplitudes(c, c2, k).reflectance()
}

/// Unpolarized Fresnel reflectance of a smooth dielectric interface.
///
/// ```text
/// r = (r_s² + r_p²) / 2      (amplitudes of dielectric_amplitudes)
///   = 1 under total internal reflection (g² = η'² − 1 + cos²θi < 0)
/// ```
///
/// * Domain: `eta ∈ [MIN_ETA, MAX_ETA]` (relative IOR `η_t/η_i`; finite beyond, see
///   [`dielectric_amplitudes`]), any `cos_theta_i`; negative cosines mean incidence from
///   inside and use `1/eta`. Result in `[0, 1]`.
/// * `r(1, η) = ((η − 1)/(η + 1))²`, `r(0, η ≠ 1) = 1`, `r(·, 1) = 0`.
///
/// Reference: Born & Wolf, *Principles of Optics*, §1.5.2; pbrt-v4 §9.3.1 (`FrDielectric`).
///
/// # Examples
///
/// ```
/// use brdf::fresnel::dielectric;
/// assert!((dielectric(1.0_f64, 1.5) - 0.04).abs() < 1e-15);
/// assert_eq!(dielectric(0.1_f32, 1.0 / 1.5), 1.0); // beyond the critical angle: TIR
/// assert_eq!(dielectric(-0.1_f32, 1.5), 1.0); // same interface, seen from inside
/// ```
#[doc(alias = "FrDielectric")]
#[inline]
#[must_use]
pub fn dielectric<R: Real>(cos_theta_i: R, eta: R) -> R {
    dielectric_amplitudes(cos_theta_i, eta).reflectance()
}

/// Unpolarized power transmittance of a smooth dielectric interface, `t = 1 − r`.
///
/// Energy conservation at a lossless interface; [`Amplitudes::transmittance`] computes the
/// same quantity from `t_s`, `t_p` and the `η cos θt / cos θi` factor (tests compare them).
/// Same domain as [`dielectric`]; `0` under TIR.
#[inline]
#[must_use]
pub fn dielectric_transmittance<R: Real>(cos_theta_i: R, eta: R) -> R {
    R::one() - dielectric(cos_theta_i, eta)
}

// ---------------------------------------------------------------------------------------
// Conductor
// ---------------------------------------------------------------------------------------

/// Unpolarized Fresnel reflectance of a conductor with complex IOR `eta + i·k`, in real
/// arithmetic (usable on lanes).
///
/// With `c = cos θi`, `s² = 1 − c²` and `a + i b = √(η̃² − s²)` (the principal root; it is
/// `η̃ cos θt`, the complex `g`), `|a + ib|² = √(t₀² + 4η²k²)`:
///
/// ```text
/// t₀ = η² − k² − s²          a² + b² = √(t₀² + 4η²k²)
/// a² = (a² + b² + t₀)/2      b² = (a² + b² − t₀)/2     (each taken in its cancellation-free form)
/// R_s = |(c − (a+ib)) / (c + (a+ib))|²  = ((a − c)² + b²) / ((a + c)² + b²)
/// R_p = R_s · |(c(a+ib) − s²) / (c(a+ib) + s²)|²
///     = R_s · ((ca − s²)² + c²b²) / ((ca + s²)² + c²b²)
/// R   = (R_s + R_p) / 2
/// ```
///
/// The `R_p/R_s` identity follows from `r_p/r_s = ∓cos(θi + θt)/cos(θi − θt)` and Snell's law
/// `η̃ sin θt = s`. This is the classic "a², b²" form (e.g. K. D. Möller, *Optics*, 1988;
/// used by Mitsuba 3's `fresnel_conductor`); here `a²`, `b²` are computed without
/// subtractive cancellation: the larger is `(a²+b² + |t₀|)/2` and the smaller `η²k²` over it
/// (`a²b² = η²k²`); that division is not carried out (both fractions are multiplied through
/// by the larger), and `R_s + R_p` share one division: two square roots and one division
/// per channel (Mitsuba's form takes two of each).
///
/// Two losses of the direct form are avoided: `t₀` is `(η² − k² − 1) + c²` or
/// `(η² − k²) − s²`, whichever has the smaller constant (see `ConductorConsts`), so a small
/// `t₀` near normal incidence keeps its digits; and at `η̃ = 1` exactly (`η = 1`, `k = 0`)
/// `R = 0` at every angle, selected (`√(c²)` loses `c` once `c²` underflows: in `f32` the
/// formula gave 0.029 at `c = 1e-20`). A dielectric (`k = 0`) exactly at its critical angle
/// (`a = b = 0`) gives 1.
///
/// * Domain: `eta ∈ [MIN_ETA, MAX_ETA]`, `k ∈ [0, MAX_K]` (tested on every lane type; finite
///   beyond as long as `(η² + k²)²` is finite in the lane precision); `cos_theta_i` taken by
///   magnitude and clamped to `[0, 1]` (a conductor is opaque: its sign does **not** flip
///   `eta`).
/// * Result in `[0, 1]` (exactly: `num_s ≤ den_s` and `num_p ≤ den_p` survive rounding);
///   equals [`dielectric`]`(|cos θi|, eta)` when `k = 0`, including TIR for `eta < 1` (then
///   `a = 0` and `R = 1`) and the index-matched `eta = 1` (`R = 0`). `k` and `−k` give the
///   same reflectance, so the seed's `n − iκ` values can be used as they are, with `k = κ`.
///
/// Reference: Born & Wolf §14.2 (metals); pbrt-v4 §9.3.6 (`FrComplex`).
///
/// # Examples
///
/// ```
/// use brdf::fresnel::{conductor, f0_from_complex_ior};
/// // Gold of the seed talk (0.34 − 3.2i there; 0.34 + 3.2i here): F0 ≈ 0.887.
/// let f0 = conductor(1.0_f64, 0.34, 3.2);
/// assert!((f0 - f0_from_complex_ior(0.34, 3.2)).abs() < 1e-15);
/// assert!((f0 - 0.887).abs() < 5e-4);
/// ```
#[doc(alias = "FrComplex")]
#[doc(alias = "FrConductor")]
#[inline]
#[must_use]
pub fn conductor<R: Real>(cos_theta_i: R, eta: R, k: R) -> R {
    let c = cos_theta_i.abs().min(R::one());
    ConductorConsts::of(eta, k).reflectance(c, c * c)
}

/// The per-channel constants of [`conductor`], which [`Conductor`] stores so that `eval`
/// does not recompute them (the free function computes them per call with the same body,
/// so both give the same bits).
///
/// `t₀ = η² − k² − s²` is evaluated as `(c² − q) + p` with
/// * `p = (η − 1)(η + 1) − k²`, `q = 0` when `η² − k² ≥ 1/2`: `t₀ = p + c²`, exact `0` for
///   `η = 1, k = 0`;
/// * `p = η² − k²`, `q = 1` otherwise: `t₀ = p − s²`, where `|η² − k²| < |η² − k² − 1|`, so
///   the rounding of the constant (`ε|p|`) is the smaller of the two. Where `t₀` is small in
///   this case, `s² < 1/2` and `c² − 1 = −s²` is exact (Sterbenz).
///
/// The first form alone loses `t₀ → η²` near normal incidence for small `η` (a rounding of
/// `≈ ε` against `η²`); the second alone loses `t₀ = c²` at grazing for `η = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ConductorConsts<R> {
    p: R,
    q: R,
    /// `|ηk|`.
    nk: R,
    /// `η²k²`.
    nk2: R,
}

impl<R: Real> ConductorConsts<R> {
    #[inline(always)]
    fn of(eta: R, k: R) -> Self {
        let k2 = k * k;
        let e1 = (eta - R::one()).mul_add(eta + R::one(), -k2);
        let e2 = eta.mul_add(eta, -k2);
        let second = e2.lt(R::from_f64(0.5));
        let nk = eta * k;
        Self {
            p: R::select(second, e2, e1),
            q: R::select(second, R::one(), R::zero()),
            nk: nk.abs(),
            nk2: nk * nk,
        }
    }

    /// `t₀ = η² − k² − s²` for `c2 = c²`.
    #[inline(always)]
    fn t0(&self, c2: R) -> R {
        (c2 - self.q) + self.p
    }

    /// `η̃ = 1` exactly (`η = 1`, `k = 0`).
    #[inline(always)]
    fn matched(&self) -> R::Mask {
        self.p.eq(R::zero()) & self.q.eq(R::zero()) & self.nk2.eq(R::zero())
    }

    /// The body of [`conductor`] for `c = |cos θi| ∈ [0, 1]` and `c2 = c²` (up to
    /// rounding).
    ///
    /// Steps (two square roots and one division per channel):
    /// * `a² + b² = h = √(t₀² + 4η²k²)`; the larger of `a²`, `b²` is `m = (h + |t₀|)/2` (no
    ///   cancellation), and the smaller is `η²k²/m` (`a²b² = η²k²`);
    /// * instead of dividing, every term of both fractions is multiplied by `m`. With
    ///   `g = √m`, `A = a·g` and `B = b²·m` are `A = m, B = η²k²` when `t₀ ≥ 0` (`a² = m`)
    ///   and `A = ηk, B = m²` when `t₀ < 0` (`b² = m`), and
    ///
    ///   ```text
    ///   R_s = ((A − c g)² + B) / ((A + c g)² + B)
    ///   R_p / R_s = ((c A − s² g)² + c² B) / ((c A + s² g)² + c² B)
    ///   R = (R_s + R_p)/2 = num_s (den_p + num_p) / (2 den_s den_p)
    ///   ```
    ///
    ///   — one division for both polarizations; every term is a sum of squares (no
    ///   cancellation). The product `den_s den_p` is at least `2 m⁴`-ish and at most
    ///   `≈ 8 (η² + k²)⁴`: finite in `f32` on the whole domain (`η, k ≤ 10⁴`).
    /// * `m < M` (`M = 10⁻⁹` in `f32`, `10⁻⁶⁰` in `f64`; only for `ηk < M` within `|t₀| < M`,
    ///   a dielectric at its critical angle) gives `R = 1`, the value at `a = b = 0`: the
    ///   products above would underflow there. The true value is within `≈ 4√M / c` of 1
    ///   (`1.3·10⁻⁴/c` in `f32`), less than the spread that rounding `c` alone causes at that
    ///   angle (`≈ 4√(ε)/c`, `10⁻³/c`).
    /// * `η̃ = 1` exactly gives `R = 0` at every angle.
    #[inline(always)]
    fn reflectance(&self, c: R, c2: R) -> R {
        self.reflectance_with::<ExactSqrt>(c, c2)
    }

    /// [`Self::reflectance`] with its square roots and division taken by `P` (the same
    /// bits for [`ExactSqrt`]).
    #[inline(always)]
    fn reflectance_with<P: SqrtFn>(&self, c: R, c2: R) -> R {
        let f = self.fraction_with::<P>(c, c2);
        let num = f.num_s * f.sum_p;
        let den = R::from_f64(2.0) * f.den_s * f.den_p;
        let critical =
            f.m.lt(R::from_f64(if core::mem::size_of::<R::Scalar>() == 4 {
                1e-9
            } else {
                1e-60
            }));
        let r = R::select(critical, R::one(), P::div(num, den));
        R::select(self.matched(), R::zero(), r)
    }

    /// The factors of [`Self::reflectance`]'s fraction `num_s (den_p + num_p) / (2 den_s
    /// den_p)`, with `P`'s two square roots.
    #[inline(always)]
    fn fraction_with<P: SqrtFn>(&self, c: R, c2: R) -> Fraction<R> {
        let nk2 = self.nk2;
        let s2 = R::one() - c2;
        let t0 = self.t0(c2);
        let (h, _) = P::sqrt_rsqrt(t0.mul_add(t0, R::from_f64(4.0) * nk2));
        // m = (h + |t₀|)/2 as h·½ + |t₀|·½: halving is exact, so the same bits with one
        // operation (an FMA) after the square root instead of two.
        let m = h.mul_add(R::from_f64(0.5), t0.abs() * R::from_f64(0.5));
        let (g, _) = P::sqrt_rsqrt(m);
        let t0_pos = t0.ge(R::zero());
        let a = R::select(t0_pos, m, self.nk);
        let b = R::select(t0_pos, nk2, m * m);
        let cg = c * g;
        let (sm, sp) = (a - cg, a + cg);
        let num_s = sm.mul_add(sm, b);
        let den_s = sp.mul_add(sp, b);
        let cb = c2 * b;
        let s2g = s2 * g;
        let (pm, pp) = (c.mul_add(a, -s2g), c.mul_add(a, s2g));
        let num_p = pm.mul_add(pm, cb);
        let den_p = pp.mul_add(pp, cb);
        Fraction {
            num_s,
            den_s,
            sum_p: den_p + num_p,
            den_p,
            m,
        }
    }
}

/// The factors of the conductor's fraction `R = num_s·sum_p / (2·den_s·den_p)` and `m` (the
/// larger of `a²`, `b²`; `< M` only at a dielectric's critical angle).
#[derive(Clone, Copy)]
struct Fraction<R> {
    num_s: R,
    den_s: R,
    /// `den_p + num_p`.
    sum_p: R,
    den_p: R,
    m: R,
}

/// Smallest `k` of every channel of a [`Conductor`] with [`SharedDivision`]. With
/// `k ≥ 0.1` (and `η² + k² ≤ `[`shared_division_max_norm`]) every denominator `2 den_s den_p`
/// of [`conductor`]'s fraction lies in `[2⁻¹⁹, 2.5 (η² + k² + 1)⁴]` (found by a dense f64
/// sweep of the domain, cosines 0 and 1 included, when this was written; `m ≥ ηk ≥ 10⁻⁵`, so
/// no critical angle and no index match), and the product of the channels' denominators
/// stays a normal `f32`; `tests/fresnel.rs` checks the results over the domain and at its
/// corners. Below `k = 0.1` the range reaches `2⁻⁸⁰` (at `k = 0`).
pub const SHARED_DIVISION_MIN_K: f64 = 0.1;

/// The largest `η² + k²` of a channel of an `N`-channel [`Conductor`] with
/// [`SharedDivision`]: the `M = η² + k² + 1` for which `(2.5 M⁴)ᴺ = 2¹¹²`, so the product of
/// the `N` denominators (and every partial product) stays below `2¹¹²`, a factor `2¹⁶` from
/// the `f32` overflow. For `N = 3` it is 512 (`|η̃| ≤ 22.6`: every metal's visible-range
/// IOR); `N = 2`, 1.3·10⁴; `N = 4`, 101.
#[must_use]
pub fn shared_division_max_norm(n: usize) -> f64 {
    let n = n as f64;
    ((112.0 - n * 2.5f64.log2()) / (4.0 * n)).exp2() - 1.0
}

/// How a [`Conductor`] arranges its per-channel divisions: [`PerChannel`] (the default) or
/// [`SharedDivision`]. Sealed.
pub trait DivisionPlan:
    Copy + core::fmt::Debug + Default + Send + Sync + 'static + sealed::DivisionPlan
{
    /// Whether the channels share one division on a number type that asks for it
    /// ([`crate::real::Bits::SHARE_DIVISIONS`]).
    const SHARED: bool;
}

/// [`DivisionPlan`]: one division per channel on every number type.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PerChannel;

/// [`DivisionPlan`]: on [`crate::real::F32FmaSharedDiv`] — the batch kernels' number type on
/// cores whose divider bounds them ([`crate::batch::shares_divisions`]), and its
/// explicit-lane counterparts in those kernels — all channels share one division; on every
/// other type, one division per channel. Chosen with
/// [`Conductor::share_divisions`], which requires `k ≥ `[`SHARED_DIVISION_MIN_K`] in every
/// channel (the metals: gold, silver, copper, aluminium, iron … have `k > 1` in the visible).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SharedDivision;

impl DivisionPlan for PerChannel {
    const SHARED: bool = false;
}

impl DivisionPlan for SharedDivision {
    const SHARED: bool = true;
}

mod sealed {
    /// The two division plans of [`super::Conductor`].
    pub trait DivisionPlan {}
    impl DivisionPlan for super::PerChannel {}
    impl DivisionPlan for super::SharedDivision {}
}

/// Complex s and p amplitude reflection coefficients of a conductor (or, with `k = 0`, of a
/// dielectric including the phase under total internal reflection), `(r_s, r_p)`.
///
/// ```text
/// w   = √(η̃² − sin²θi)          principal root, η̃ = eta.re + i·eta.im  (w = η̃ cos θt)
/// r_s = (cos θi − w) / (cos θi + w)
/// r_p = (w − η̃² cos θi) / (w + η̃² cos θi)
/// ```
///
/// Sign convention: `eta.im = k ≥ 0` (`e^{−iωt}` time dependence, so `Im w ≥ 0` is the
/// field decaying into the metal); the seed talk's `n − iκ` is the conjugate, and its
/// amplitudes are the conjugates of these. Amplitude signs as in [`dielectric_amplitudes`]
/// (pbrt's `r_parl` is `−r_p`). `|r_s|² `, `|r_p|²` average to [`conductor`].
///
/// Under TIR of a dielectric (`k = 0`, `η < sin θi`) `w = i·√(sin²θi − η²)`, so
/// `|r_s| = |r_p| = 1` and `arg r_s = −2 atan(√(sin²θi − η²) / cos θi)` (the Goos–Hänchen /
/// Fresnel-rhomb phase).
///
/// * Domain: `eta.re ∈ [MIN_ETA, MAX_ETA]`, `eta.im ∈ [0, MAX_K]` (the constructors'
///   domains), `cos_theta_i` by magnitude, clamped to 1. Index-matched (`η̃ = 1`): `0` at
///   every angle, grazing included (the limit along `η̃ = 1`). `η̃² − s²` is formed as in
///   [`conductor`].
/// * Generic over [`Real`] (the complex values are plain `re`/`im` pairs of lanes), though
///   mostly useful on `f32`/`f64`.
///
/// Reference: Born & Wolf §1.5.4 (TIR phases), §14.2 (metals).
///
/// # Examples
///
/// ```
/// use brdf::fresnel::{conductor, conductor_amplitudes};
/// use num_complex::Complex;
/// let (r_s, r_p) = conductor_amplitudes(0.6_f64, Complex::new(0.2, 3.5));
/// let r = (r_s.norm_sqr() + r_p.norm_sqr()) / 2.0;
/// assert!((r - conductor(0.6, 0.2, 3.5)).abs() < 1e-14);
/// ```
#[inline]
#[must_use]
pub fn conductor_amplitudes<R: Real>(cos_theta_i: R, eta: Complex<R>) -> (Complex<R>, Complex<R>) {
    let c = cos_theta_i.abs().min(R::one());
    let (n, k) = (eta.re, eta.im);
    // η̃² = (n² − k²) + i 2nk;  η̃² − s² = t₀ + i 2nk, t₀ as in `conductor`.
    let e2 = (n * n - k * k, (n + n) * k);
    let consts = ConductorConsts::of(n, k);
    let z = (consts.t0(c * c), e2.1);
    // η̃ = 1: w = c exactly, so r_s = r_p = 0 at every angle.
    let w = csqrt(z);
    let matched = consts.matched();
    let w = (
        R::select(matched, c, w.0),
        R::select(matched, R::zero(), w.1),
    );
    let ec = (e2.0 * c, e2.1 * c);
    let r_s = cdiv((c - w.0, -w.1), (c + w.0, w.1));
    let r_p = cdiv((w.0 - ec.0, w.1 - ec.1), (w.0 + ec.0, w.1 + ec.1));
    (Complex::new(r_s.0, r_s.1), Complex::new(r_p.0, r_p.1))
}

/// Principal square root of `x + iy` (branch cut on the negative real axis; `Im ≥ 0` for
/// `y ≥ 0`, including `y = −0`), without cancellation.
#[inline]
fn csqrt<R: Real>((x, y): (R, R)) -> (R, R) {
    let half = R::from_f64(0.5);
    let m = x.mul_add(x, y * y).sqrt();
    let t = ((m + x.abs()) * half).sqrt();
    let other = R::select(t.gt(R::zero()), y.abs() / (t + t), R::zero());
    let pos = x.ge(R::zero());
    let re = R::select(pos, t, other);
    let im_mag = R::select(pos, other, t);
    (re, R::select(y.lt(R::zero()), -im_mag, im_mag))
}

/// `(a + ib) / (c + id)`; `0` when the divisor is `0` (only index-matched grazing incidence).
#[inline]
fn cdiv<R: Real>((a, b): (R, R), (c, d): (R, R)) -> (R, R) {
    let den = c.mul_add(c, d * d);
    let ok = den.gt(R::zero());
    let re = R::select(ok, a.mul_add(c, b * d) / den, R::zero());
    let im = R::select(ok, b.mul_add(c, -(a * d)) / den, R::zero());
    (re, im)
}

// ---------------------------------------------------------------------------------------
// Schlick and F0 conversions
// ---------------------------------------------------------------------------------------

/// The complement of Schlick's weight, `1 − (1 − cos θ)⁵`, without cancellation near
/// `cos θ = 0` (grazing), where the direct form loses every digit in `f32`.
///
/// ```text
/// 1 − (1 − c)⁵ = c (5 − 10c + 10c² − 5c³ + c⁴)      for c < 1/2   (Horner)
///              = 1 − (1 − c)⁵                          for c ≥ 1/2   ((1 − c)⁵ ≤ 1/32)
/// ```
///
/// Both forms are evaluated and one is selected, so the function is branch-free on lanes.
/// `cos θ` is clamped to `[0, 1]`. Used by the Fresnel-coupled diffuse terms (Shirley et al.
/// 1997, Ashikhmin-Shirley 2000).
///
/// # Examples
///
/// ```
/// use brdf::fresnel::schlick_complement;
/// let c = 1e-6_f32;
/// assert!((schlick_complement(c) / (5.0 * c) - 1.0).abs() < 1e-5);
/// assert_eq!(schlick_complement(1.0_f32), 1.0);
/// ```
#[inline(always)]
#[must_use]
pub fn schlick_complement<R: Real>(cos_theta: R) -> R {
    let c = cos_theta.saturate();
    let horner = c * c.mul_add(
        c.mul_add(
            c.mul_add(c - R::from_f64(5.0), R::from_f64(10.0)),
            R::from_f64(-10.0),
        ),
        R::from_f64(5.0),
    );
    R::select(c.lt(R::from_f64(0.5)), horner, R::one() - schlick_weight(c))
}

/// Schlick's weight `(1 − cos θ)⁵`, with `1 − cos θ` clamped to `[0, 1]`.
///
/// Reference: C. Schlick, "An Inexpensive BRDF Model for Physically-based Rendering",
/// Computer Graphics Forum 13(3), 1994.
#[inline(always)]
#[must_use]
pub fn schlick_weight<R: Real>(cos_theta: R) -> R {
    let m = (R::one() - cos_theta).saturate();
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's approximation of the Fresnel reflectance.
///
/// ```text
/// F(θ) = F0 + (1 − F0)(1 − cos θ)⁵
/// ```
///
/// Argument order `(f0, cos_theta)` as in shading languages (Filament's `F_Schlick`).
/// * Domain: `f0 ∈ [0, 1]`; `cos_theta ∈ [0, 1]` (outside, `1 − cos θ` is clamped to
///   `[0, 1]`). Result in `[f0, 1]`. Exact at `cos θ = 1` and `cos θ = 0`; for dielectrics
///   it does not model total internal reflection, and for metals it misses the dip before
///   grazing (see [`f82_tint`]).
///
/// Reference: C. Schlick, Computer Graphics Forum 13(3), 1994, eq. 24; the seed talk.
///
/// # Examples
///
/// ```
/// use brdf::fresnel::schlick;
/// assert_eq!(schlick(0.04_f32, 1.0), 0.04);
/// assert_eq!(schlick(0.04_f32, 0.0), 1.0);
/// ```
#[inline]
#[must_use]
pub fn schlick<R: Real>(f0: R, cos_theta: R) -> R {
    (R::one() - f0).mul_add(schlick_weight(cos_theta), f0)
}

/// Schlick's approximation with an explicit grazing reflectance `f90`.
///
/// ```text
/// F(θ) = F0 + (F90 − F0)(1 − cos θ)⁵
/// ```
///
/// `f90 = 1` gives [`schlick`]; engines lower it to fade the grazing highlight of
/// materials whose `F0` is so small it must be occlusion (Filament: `f90 = saturate(50·F0)`).
/// Domain `f0, f90 ∈ [0, 1]`, `cos_theta` as in [`schlick`]; result between `f0` and `f90`.
///
/// Reference: Schlick 1994; R. Guy, M. Agopian, *Physically Based Rendering in Filament*,
/// Google, 2018, §4.4.3.
#[inline]
#[must_use]
pub fn schlick_f90<R: Real>(f0: R, f90: R, cos_theta: R) -> R {
    (f90 - f0).mul_add(schlick_weight(cos_theta), f0)
}

/// Normal-incidence reflectance of a dielectric, `F0 = ((η − 1)/(η + 1))²`.
///
/// Domain `eta ∈ (0, ∞)`; `eta` and `1/eta` give the same `F0`. Equals `dielectric(1, eta)`.
/// Reference: Born & Wolf §1.5.3; the seed talk writes `((1 − n)/(1 + n))²`.
#[inline]
#[must_use]
pub fn f0_from_ior<R: Real>(eta: R) -> R {
    let r = (eta - R::one()) / (eta + R::one());
    r * r
}

/// Normal-incidence reflectance of a conductor, `F0 = ((η − 1)² + k²) / ((η + 1)² + k²)`.
///
/// `|(η̃ − 1)/(η̃ + 1)|²` for `η̃ = η ± ik` (the sign of `k` does not matter). Domain
/// `eta ∈ (0, ∞)`, `k ∈ [0, ∞)`, `(η + 1)² + k²` finite. Equals `conductor(1, eta, k)`.
#[inline]
#[must_use]
pub fn f0_from_complex_ior<R: Real>(eta: R, k: R) -> R {
    let k2 = k * k;
    let m = eta - R::one();
    let p = eta + R::one();
    m.mul_add(m, k2) / p.mul_add(p, k2)
}

/// The real IOR `η ≥ 1` whose normal-incidence reflectance is `f0` (inverse of
/// [`f0_from_ior`]).
///
/// ```text
/// η = (1 + √F0) / (1 − √F0)
/// ```
///
/// * `F0 = ((η−1)/(η+1))²` has two roots, `η` and `1/η`; this returns the one `≥ 1`
///   (a denser medium seen from air, the usual meaning of an `F0` texture).
/// * Domain `f0 ∈ [0, 1)`. As `F0 → 1`, `η ≈ 4 / (1 − F0) → ∞` (`f0 = 1` gives `+∞`:
///   no real IOR reflects everything at normal incidence; that takes a conductor).
///   [`Dielectric::from_f0`] validates and rejects `f0 ∉ [0, 1)`.
///
/// Reference: inverse of Born & Wolf §1.5.3; used by Cook & Torrance 1982 to recover `η`
/// from a measured `F0`.
#[inline]
#[must_use]
pub fn ior_from_f0<R: Real>(f0: R) -> R {
    let s = f0.safe_sqrt();
    (R::one() + s) / (R::one() - s)
}

// ---------------------------------------------------------------------------------------
// Metals beyond Schlick
// ---------------------------------------------------------------------------------------

/// `μ̄ = 1/7`, the cosine (θ ≈ 81.8°, "82°") where `μ(1 − μ)⁶` peaks and where the F82-tint
/// model matches the desired edge reflectance.
pub const F82_COS_THETA: f64 = 1.0 / 7.0;

/// `μ̄ (1 − μ̄)⁶` at [`F82_COS_THETA`] = `6⁶ / 7⁷`.
const F82_W: f64 = 46656.0 / 823543.0;

/// The F82-tint correction coefficient `b` (per material; precompute it).
///
/// ```text
/// b = (F_Schlick(F0, μ̄) − tint · F_Schlick(F0, μ̄)) / (μ̄ (1 − μ̄)⁶),     μ̄ = 1/7
///   = F_Schlick(F0, μ̄) (1 − tint) · 7⁷/6⁶
/// ```
///
/// so that [`f82_tint_with_b`] passes through `tint · F_Schlick(F0, μ̄)` at `cos θ = μ̄`.
/// Domain `f0 ∈ [0, 1]`, `tint ∈ [0, 1]` (Open PBR's `specular_color`).
///
/// Reference: N. Hoffman, "Fresnel Equations Considered Harmful", 2019; A. Kutz et al.,
/// "Novel aspects of the Adobe Standard Material", 2021 (the `b` notation); Open PBR 1.0 §
/// "Metal".
#[inline]
#[must_use]
pub fn f82_b<R: Real>(f0: R, tint: R) -> R {
    schlick(f0, R::from_f64(F82_COS_THETA)) * (R::one() - tint) * R::from_f64(1.0 / F82_W)
}

/// Hoffman's F82-tint Fresnel for metals, with a precomputed `b` (see [`f82_b`]).
///
/// ```text
/// F(μ) = saturate( F0 + (1 − F0)(1 − μ)⁵ − b μ (1 − μ)⁶ ),     μ = cos θ
/// ```
///
/// The correction `μ(1 − μ)⁶` vanishes at `μ = 0` and `μ = 1` (so `F(1) = F0`, `F(0) = 1`)
/// and peaks at `μ̄ = 1/7`, reproducing the dip of real metals' reflectance before grazing
/// that Schlick misses. For strong corrections the published curve goes negative near
/// `μ ≈ 0.3–0.6` (Open PBR issue #256); the result is clamped to `[0, 1]`.
/// Domain `f0 ∈ [0, 1]`, `cos_theta ∈ [0, 1]` (clamped), `b` finite.
///
/// Reference: Hoffman 2019; Kutz et al. 2021; Open PBR Surface 1.0.
#[inline]
#[must_use]
pub fn f82_tint_with_b<R: Real>(f0: R, b: R, cos_theta: R) -> R {
    // F_Schlick(F0, μ) − b μ (1 − μ)⁶, with (1 − μ)⁶ = schlick_weight(μ)·(1 − μ).
    let m = (R::one() - cos_theta).saturate();
    let m5 = schlick_weight(cos_theta);
    let s = (R::one() - f0).mul_add(m5, f0);
    (s - b * (R::one() - m) * m5 * m).saturate()
}

/// Hoffman's F82-tint Fresnel for metals: Schlick with a correction so that the reflectance
/// at `cos θ = 1/7` (≈ 82°) is `tint × F_Schlick(F0, 1/7)`.
///
/// ```text
/// F(μ) = saturate( F_Schlick(F0, μ) − b μ (1 − μ)⁶ ),   b = F_Schlick(F0, 1/7)(1 − tint) / ((1/7)(6/7)⁶)
/// ```
///
/// Computes `b` on every call; [`F82Tint`] precomputes it. `tint = 1` is plain Schlick.
/// Domain `f0, tint ∈ [0, 1]`, `cos_theta ∈ [0, 1]`.
///
/// Reference: N. Hoffman, "Fresnel Equations Considered Harmful", EGSR 2019 workshop /
/// SIGGRAPH 2019 course; Open PBR Surface 1.0 (metal Fresnel), Kutz et al. 2021.
///
/// # Examples
///
/// ```
/// use brdf::fresnel::{f82_tint, schlick, F82_COS_THETA};
/// let (f0, tint) = (0.9_f64, 0.8);
/// let mu = F82_COS_THETA;
/// assert!((f82_tint(f0, tint, mu) - tint * schlick(f0, mu)).abs() < 1e-15);
/// assert_eq!(f82_tint(f0, tint, 1.0), f0);
/// ```
#[inline]
#[must_use]
pub fn f82_tint<R: Real>(f0: R, tint: R, cos_theta: R) -> R {
    f82_tint_with_b(f0, f82_b(f0, tint), cos_theta)
}

// ---------------------------------------------------------------------------------------
// Parameter domains
// ---------------------------------------------------------------------------------------

/// The smallest relative IOR (`eta`, real part) the constructors accept: `1e-4`.
///
/// See the [module docs](self#parameter-domains) for why the IOR domain is
/// `[MIN_ETA, MAX_ETA]` and `k ∈ [0, MAX_K]`.
pub const MIN_ETA: f64 = 1e-4;
/// The largest relative IOR (`eta`, real part) the constructors accept: `1e4`.
pub const MAX_ETA: f64 = 1e4;
/// The largest extinction coefficient `k` the constructors accept: `1e4`.
pub const MAX_K: f64 = 1e4;
/// The largest normal-incidence reflectance that [`Dielectric::from_f0`] and
/// [`Conductor::from_reflectivity_edge_tint`] accept: `0.9996`, just below
/// `F0(MAX_ETA) = ((1e4 − 1)/(1e4 + 1))² ≈ 0.99960008`, so the IOR they derive is at most
/// [`MAX_ETA`].
pub const MAX_DIELECTRIC_F0: f64 = 0.9996;

const ETA_DOMAIN: &str = "[1e-4, 1e4]";
const K_DOMAIN: &str = "[0, 1e4]";
const F0_IOR_DOMAIN: &str = "[0, 0.9996]";

/// The `k` domain of [`Conductor::share_divisions`], as error messages print it.
const SHARED_K_DOMAIN: &str = "[0.1, 1e4] (SharedDivision needs a metal)";
/// The `η² + k²` domain of [`Conductor::share_divisions`].
const SHARED_NORM_DOMAIN: &str = "[0, shared_division_max_norm(N)] (512 for 3 channels)";

/// `eta ∈ [MIN_ETA, MAX_ETA]`, compared in the precision of `S`.
#[inline]
pub(crate) fn check_eta<S: Scalar>(eta: S) -> Result<S, Error> {
    error::in_range("eta", eta, MIN_ETA, MAX_ETA, ETA_DOMAIN)
}

/// `k ∈ [0, MAX_K]`, compared in the precision of `S`.
#[inline]
pub(crate) fn check_k<S: Scalar>(k: S) -> Result<S, Error> {
    error::in_range("k", k, 0.0, MAX_K, K_DOMAIN)
}

// ---------------------------------------------------------------------------------------
// FresnelTerm implementations
// ---------------------------------------------------------------------------------------

/// Schlick's approximation per channel, with `f0` and `f90` per channel:
/// `F = F0 + (F90 − F0)(1 − cos θd)⁵` (see [`schlick_f90`]).
///
/// # Examples
///
/// ```
/// use brdf::fresnel::{FresnelTerm, Schlick};
/// let gold = Schlick::new([1.0_f32, 0.78, 0.34]).unwrap();
/// assert_eq!(gold.eval(1.0), [1.0, 0.78, 0.34]);
/// assert!(Schlick::new([1.5_f32]).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schlick<R, const N: usize> {
    f0: [R; N],
    f90: [R; N],
}

impl<S: Scalar, const N: usize> Schlick<S, N> {
    /// Schlick with `f90 = 1`. Each `f0 ∈ [0, 1]`, else [`Error`].
    pub fn new(f0: [S; N]) -> Result<Self, Error> {
        Self::with_f90(f0, [S::one(); N])
    }

    /// Schlick with an explicit grazing reflectance. Each `f0, f90 ∈ [0, 1]`, else [`Error`].
    pub fn with_f90(f0: [S; N], f90: [S; N]) -> Result<Self, Error> {
        for i in 0..N {
            error::unit_interval("f0", f0[i])?;
            error::unit_interval("f90", f90[i])?;
        }
        Ok(Self { f0, f90 })
    }

    /// Schlick with `f0 = ((η − 1)/(η + 1))²` from a real IOR per channel,
    /// `eta ∈ [MIN_ETA, MAX_ETA]` (the IOR domain of the module docs), else [`Error`].
    pub fn from_ior(eta: [S; N]) -> Result<Self, Error> {
        let mut f0 = eta;
        for i in 0..N {
            check_eta(eta[i])?;
            f0[i] = f0_from_ior(eta[i]);
        }
        Self::new(f0)
    }

    /// Schlick with `f0` from a complex IOR per channel, `((η−1)² + k²)/((η+1)² + k²)`
    /// (`eta ∈ [MIN_ETA, MAX_ETA]`, `k ∈ [0, MAX_K]`, else [`Error`]). Reproduces the exact
    /// [`Conductor`] at normal and grazing incidence only; see the module docs for its error
    /// in between.
    pub fn from_complex_ior(eta: [S; N], k: [S; N]) -> Result<Self, Error> {
        let mut f0 = eta;
        for i in 0..N {
            check_eta(eta[i])?;
            check_k(k[i])?;
            f0[i] = f0_from_complex_ior(eta[i], k[i]);
        }
        Self::new(f0)
    }
}

impl<R: Real, const N: usize> Schlick<R, N> {
    /// Normal-incidence reflectance per channel.
    pub fn f0(&self) -> [R; N] {
        self.f0
    }

    /// Grazing reflectance per channel.
    pub fn f90(&self) -> [R; N] {
        self.f90
    }
}

impl<S: Scalar, const N: usize> Splat for Schlick<S, N> {
    type On<L: Real> = Schlick<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> Schlick<L, N> {
        Schlick {
            f0: splat_array(&self.f0),
            f90: splat_array(&self.f90),
        }
    }
}

impl<R: Real, const N: usize> FresnelTerm<R, N> for Schlick<R, N> {
    #[inline(always)]
    fn eval(&self, cos_theta_d: R) -> [R; N] {
        let w = schlick_weight(cos_theta_d);
        crate::real::channels(
            #[inline(always)]
            |i| (self.f90[i] - self.f0[i]).mul_add(w, self.f0[i]),
        )
    }
}

/// The exact Fresnel reflectance of a smooth dielectric, the same (real) relative IOR for
/// every channel: `Dielectric<R, N>` is a [`FresnelTerm<R, N>`] returning
/// `[dielectric(|cos θd|, eta); N]` (an uncoloured coat or glass; dispersion is not modelled).
///
/// The channel count is part of the type, so a model built on it knows its channel count:
/// the constructors make the one-channel term (`N = 1`, the default), and
/// [`Dielectric::channels`] widens it (`Dielectric::new(1.5)?.channels::<3>()` beside an RGB
/// diffuse). `CookTorrance::new(ggx, Dielectric::new(1.5)?, SmithSeparable).eval(wi, wo)`
/// is then a `[R; 1]` without annotations.
///
/// **Light arrives from the outside.** `eval` takes `|cos θd|` and keeps `eta`: unlike
/// [`dielectric`], a negative cosine does **not** mean incidence from inside (no `1/eta`
/// flip). In a BRDF both directions lie above the surface and `cos θd = wi·wm ≥ 0` for their
/// half vector, so a negative value is a rounding residue of a grazing configuration; the
/// flip would turn it into total internal reflection (`F = 1` instead of `≈ 1` from the other
/// side of zero, and `1` instead of `0.089` at `cos θd = −0.5`, `η = 1.5`): a discontinuity
/// made of rounding noise. For a surface lit from inside, build the term with `1/eta`.
///
/// # Examples
///
/// ```
/// use brdf::fresnel::{dielectric, Dielectric, FresnelTerm};
/// let glass = Dielectric::new(1.5_f64).unwrap();
/// let [f] = FresnelTerm::<f64, 1>::eval(&glass, 1.0);
/// assert!((f - 0.04).abs() < 1e-15);
/// // |cos θd|, no flip: the same as at +0.5 (dielectric(-0.5, 1.5) would be TIR, 1).
/// assert_eq!(FresnelTerm::<f64, 1>::eval(&glass, -0.5), [dielectric(0.5, 1.5)]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric<R, const N: usize = 1> {
    consts: DielectricConsts<R>,
}

impl<S: Scalar> Dielectric<S> {
    /// A dielectric interface with relative IOR `eta = η_t/η_i ∈ [MIN_ETA, MAX_ETA]` (the
    /// IOR domain of the module docs), else [`Error`].
    pub fn new(eta: S) -> Result<Self, Error> {
        check_eta(eta)?;
        Ok(Self {
            consts: DielectricConsts::of(eta, eta.recip()),
        })
    }

    /// The dielectric (`η ≥ 1`) whose normal-incidence reflectance is `f0` (see
    /// [`ior_from_f0`]). `f0 ∈ [0, MAX_DIELECTRIC_F0]`, else [`Error`]: `f0 = 1` has no real
    /// IOR, and above `MAX_DIELECTRIC_F0` the IOR exceeds [`MAX_ETA`].
    pub fn from_f0(f0: S) -> Result<Self, Error> {
        error::in_range("f0", f0, 0.0, MAX_DIELECTRIC_F0, F0_IOR_DOMAIN)?;
        // In f64: in f32, √f0 rounds to 1 for f0 within an ulp of 1.
        Self::new(S::of(ior_from_f0(f0.into())))
    }
}

impl<R: Real, const N: usize> Dielectric<R, N> {
    /// The relative IOR.
    pub fn eta(&self) -> R {
        self.consts.eta
    }

    /// The same interface as an `M`-channel term (every channel the same reflectance; the
    /// constants keep their bits).
    ///
    /// ```
    /// use brdf::fresnel::{Dielectric, FresnelTerm};
    /// let rgb = Dielectric::new(1.5_f32)?.channels::<3>();
    /// assert_eq!(rgb.eval(1.0), [Dielectric::new(1.5_f32)?.eval(1.0)[0]; 3]);
    /// # Ok::<(), brdf::Error>(())
    /// ```
    #[must_use]
    pub fn channels<const M: usize>(self) -> Dielectric<R, M> {
        Dielectric {
            consts: self.consts,
        }
    }
}

impl<S: Scalar, const N: usize> Splat for Dielectric<S, N> {
    type On<L: Real> = Dielectric<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> Dielectric<L, N> {
        let k = &self.consts;
        Dielectric {
            consts: DielectricConsts {
                eta: splat_scalar(k.eta),
                inv_eta: splat_scalar(k.inv_eta),
                inv_eta2: splat_scalar(k.inv_eta2),
                p: splat_scalar(k.p),
                q: splat_scalar(k.q),
            },
        }
    }
}

impl<R: Real, const N: usize> FresnelTerm<R, N> for Dielectric<R, N> {
    #[inline(always)]
    fn eval(&self, cos_theta_d: R) -> [R; N] {
        let c = cos_theta_d.abs().min(R::one());
        [dielectric_reflectance(c, c * c, self.consts); N]
    }

    #[inline(always)]
    fn eval_cos2(&self, cos_theta_d: R, cos2_theta_d: R) -> [R; N] {
        let c = cos_theta_d.abs().min(R::one());
        [dielectric_reflectance(c, cos2_theta_d, self.consts); N]
    }
}

/// The exact Fresnel reflectance of a conductor with a complex IOR `eta + i·k` per channel
/// (see [`conductor`]).
///
/// # Examples
///
/// ```
/// use brdf::fresnel::{Conductor, FresnelTerm};
/// use brdf::ior::Preset;
/// let gold = Conductor::<f32, 3>::from_preset(Preset::Gold)?;
/// let f = gold.eval(1.0);
/// assert!(f[0] > f[1] && f[1] > f[2]); // yellow
/// // The seed talk's single value for gold, 0.34 + 3.2i, on one channel:
/// let e = Preset::Gold.seed().unwrap();
/// let seed_gold = Conductor::new([e.eta], [e.k])?;
/// assert!((seed_gold.eval(1.0)[0] - 0.887).abs() < 5e-4);
/// # Ok::<(), brdf::Error>(())
/// ```
///
/// `P:` [`SqrtFn`] (default [`ExactSqrt`]; choose with [`Conductor::with_policy`]) takes the
/// two square roots and one division per channel; [`crate::fast::NewtonSqrtRecip`] replaces
/// them by estimates refined with Newton steps (error in `docs/tradeoffs.md`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor<R, const N: usize, P = ExactSqrt, D = PerChannel> {
    eta: [R; N],
    k: [R; N],
    /// Per channel the constants `p`, `q`, `|ηk|` and `η²k²` of `ConductorConsts`.
    p: [R; N],
    q: [R; N],
    nk: [R; N],
    nk2: [R; N],
    _p: PhantomData<(P, D)>,
}

impl<S: Scalar, const N: usize> Conductor<S, N> {
    /// A conductor with `eta ∈ [MIN_ETA, MAX_ETA]` and `k ∈ [0, MAX_K]` per channel (the
    /// IOR domain of the module docs), else [`Error`].
    pub fn new(eta: [S; N], k: [S; N]) -> Result<Self, Error> {
        for i in 0..N {
            check_eta(eta[i])?;
            check_k(k[i])?;
        }
        Ok(Self::from_valid(eta, k))
    }

    /// Builds the per-channel constants from already validated parameters.
    #[inline]
    fn from_valid(eta: [S; N], k: [S; N]) -> Self {
        let c: [ConductorConsts<S>; N] =
            core::array::from_fn(|i| ConductorConsts::of(eta[i], k[i]));
        Self {
            eta,
            k,
            p: c.map(|c| c.p),
            q: c.map(|c| c.q),
            nk: c.map(|c| c.nk),
            nk2: c.map(|c| c.nk2),
            _p: PhantomData,
        }
    }

    /// A conductor from Gulbrandsen's artist-friendly reflectivity
    /// `r ∈ [0, MAX_DIELECTRIC_F0]` and edge tint `g ∈ [0, 1]` per channel (see
    /// [`reference::gulbrandsen_to_nk`]), else [`Error`]. The bound on `r` keeps the IOR in
    /// the domain (`n ≤ n_max(r) ≤ MAX_ETA`, `k ≤ n_max/2`): as `r → 1`, `n_max` grows like
    /// `4/(1 − r)`.
    pub fn from_reflectivity_edge_tint(r: [S; N], g: [S; N]) -> Result<Self, Error> {
        let mut eta = r;
        let mut k = r;
        for i in 0..N {
            error::in_range("r", r[i], 0.0, MAX_DIELECTRIC_F0, F0_IOR_DOMAIN)?;
            error::unit_interval("g", g[i])?;
            let (n, kk) = reference::gulbrandsen_to_nk::<f64>(r[i].into(), g[i].into());
            (eta[i], k[i]) = (S::of(n), S::of(kk));
        }
        Self::new(eta, k)
    }
}

impl<R: Real, const N: usize, P: SqrtFn, D: DivisionPlan> Conductor<R, N, P, D> {
    /// The same conductor with its square roots and divisions taken by `P2` (for example
    /// [`crate::fast::NewtonSqrtRecip`]`<3, 3>`, relative error in `docs/tradeoffs.md`).
    ///
    /// With [`crate::fast::HardwareEstimate`] the estimates act only on the batch kernels of
    /// divider-bound cores (those where [`crate::batch::shares_divisions`] is `true`: Intel).
    /// On the other cores' explicit lanes (AMD) the conductor keeps the exact square roots
    /// and division, bit for bit: its two square roots and division form one dependency
    /// chain per channel, and the refinement steps lengthen it. Measured on an AMD EPYC
    /// (Zen 4, peer benchmark of the README): Cook-Torrance with estimates and this
    /// conductor exact 427 M/s, with the conductor's estimates too 365 M/s, all exact 407
    /// M/s. The Cook-Torrance half vector and final division keep their estimates on both
    /// families.
    ///
    /// ```
    /// use brdf::fast::NewtonSqrtRecip;
    /// use brdf::fresnel::{Conductor, FresnelTerm};
    /// use brdf::ior::Preset;
    /// let exact = Conductor::<f32, 3>::from_preset(Preset::Gold)?;
    /// let fast = exact.with_policy::<NewtonSqrtRecip<3, 3>>();
    /// let (a, b) = (exact.eval(0.3), fast.eval(0.3));
    /// assert!((0..3).all(|i| (a[i] - b[i]).abs() <= 1e-5 * a[i]));
    /// # Ok::<(), brdf::Error>(())
    /// ```
    #[inline]
    #[must_use]
    pub fn with_policy<P2: SqrtFn>(self) -> Conductor<R, N, P2, D> {
        self.retyped()
    }

    /// The same constants under other type parameters.
    #[inline]
    fn retyped<P2, D2>(self) -> Conductor<R, N, P2, D2> {
        Conductor {
            eta: self.eta,
            k: self.k,
            p: self.p,
            q: self.q,
            nk: self.nk,
            nk2: self.nk2,
            _p: PhantomData,
        }
    }

    /// The same conductor with [`SharedDivision`]: on the batch kernels' number types of
    /// divider-bound cores ([`crate::real::F32FmaSharedDiv`] and its explicit lanes) its
    /// channels share one division
    /// (within 8 ULP of the per-channel form; measured 1.12× faster on an Intel Xeon, see
    /// [`crate::batch::shares_divisions`]); elsewhere it is the per-channel conductor bit for
    /// bit.
    ///
    /// # Errors
    ///
    /// [`Error`] naming `k` if a channel has `k < `[`SHARED_DIVISION_MIN_K`] (a dielectric
    /// or nearly so), or `eta² + k²` if it exceeds [`shared_division_max_norm`]`(N)`: the
    /// product of the denominators could leave the `f32` range. More than 4 channels do not
    /// compile.
    ///
    /// ```
    /// use brdf::fresnel::{Conductor, FresnelTerm};
    /// use brdf::ior::Preset;
    /// let gold = Conductor::<f32, 3>::from_preset(Preset::Gold)?.share_divisions()?;
    /// assert!(gold.eval(1.0)[0] > 0.9);
    /// assert!(Conductor::<f32, 1>::new([1.5], [0.0])?.share_divisions().is_err());
    /// # Ok::<(), brdf::Error>(())
    /// ```
    pub fn share_divisions(self) -> Result<Conductor<R, N, P, SharedDivision>, Error>
    where
        R: crate::Scalar,
    {
        const { assert!(N <= 4, "SharedDivision: at most 4 channels") };
        let max_norm = shared_division_max_norm(N);
        for (eta, k) in self.eta.into_iter().zip(self.k) {
            error::in_range("k", k, SHARED_DIVISION_MIN_K, MAX_K, SHARED_K_DOMAIN)?;
            let norm = eta * eta + k * k;
            error::in_range("eta² + k²", norm, 0.0, max_norm, SHARED_NORM_DOMAIN)?;
        }
        Ok(self.retyped())
    }

    /// The constants of channel `i`.
    #[inline(always)]
    fn consts(&self, i: usize) -> ConductorConsts<R> {
        ConductorConsts {
            p: self.p[i],
            q: self.q[i],
            nk: self.nk[i],
            nk2: self.nk2[i],
        }
    }

    /// Real part of the IOR per channel.
    pub fn eta(&self) -> [R; N] {
        self.eta
    }

    /// Extinction coefficient per channel.
    pub fn k(&self) -> [R; N] {
        self.k
    }
}

impl<S: Scalar, const N: usize, P: SqrtFn, D: DivisionPlan> Splat for Conductor<S, N, P, D> {
    const EXPLICIT_LANES: bool = P::HARDWARE_ESTIMATES;
    type On<L: Real> = Conductor<L, N, P, D>;
    #[inline]
    fn splat<L: Real>(&self) -> Conductor<L, N, P, D> {
        Conductor {
            eta: splat_array(&self.eta),
            k: splat_array(&self.k),
            p: splat_array(&self.p),
            q: splat_array(&self.q),
            nk: splat_array(&self.nk),
            nk2: splat_array(&self.nk2),
            _p: PhantomData,
        }
    }
}

impl<R: Real, const N: usize, P: SqrtFn, D: DivisionPlan> FresnelTerm<R, N>
    for Conductor<R, N, P, D>
{
    #[inline(always)]
    fn eval(&self, cos_theta_d: R) -> [R; N] {
        let c = cos_theta_d.abs().min(R::one());
        self.eval_cos2(c, c * c)
    }

    /// Per channel [`conductor`]'s two square roots and one division; with [`SharedDivision`]
    /// on a number type with [`crate::real::Bits::SHARE_DIVISIONS`], one division for all
    /// channels instead (`n_i = num_s sum_p`, `d_i = 2 den_s den_p` of channel `i`):
    ///
    /// ```text
    /// R_i = n_i / d_i = n_i · Π_{j≠i} d_j · (Π_j d_j)⁻¹
    /// ```
    ///
    /// (`N − 1` prefix products, one division, `2N` multiplications and a clamp to 1; a few
    /// more roundings: within 8 ULP of the per-channel form, `tests/fresnel.rs`).
    #[inline(always)]
    fn eval_cos2(&self, cos_theta_d: R, cos2_theta_d: R) -> [R; N] {
        let c = cos_theta_d.abs().min(R::one());
        if R::SHARE_DIVISIONS && D::SHARED && N >= 2 {
            // Numerators and denominators, then prefix products of the denominators.
            let mut num = [R::zero(); N];
            let mut den = [R::zero(); N];
            for i in 0..N {
                let f = self.consts(i).fraction_with::<P>(c, cos2_theta_d);
                num[i] = f.num_s * f.sum_p;
                den[i] = R::from_f64(2.0) * f.den_s * f.den_p;
            }
            let mut before = [R::one(); N];
            for i in 1..N {
                before[i] = before[i - 1] * den[i - 1];
            }
            let r = P::div(R::one(), before[N - 1] * den[N - 1]);
            // R_i = n_i · (Π_{j<i} d_j · Π_{j>i} d_j) · r, the suffix product built backwards.
            let mut out = [R::zero(); N];
            let mut after = R::one();
            for i in (0..N).rev() {
                // (`min`: at grazing n_i = d_i, and the rounding of the products could
                // give 1 + 1 ULP.)
                out[i] = (num[i] * (before[i] * after) * r).min(R::one());
                after *= den[i];
            }
            return out;
        }
        if P::HARDWARE_ESTIMATES && !R::SHARE_DIVISIONS {
            // Explicit lanes of a core with a fast divider (not divider-bound: AMD): the
            // estimates' refinement steps would lengthen this term's chain of two square
            // roots and a division, which bounds the kernel there (see `with_policy`).
            return crate::real::channels(
                #[inline(always)]
                |i| {
                    self.consts(i)
                        .reflectance_with::<ExactSqrt>(c, cos2_theta_d)
                },
            );
        }
        crate::real::channels(
            #[inline(always)]
            |i| self.consts(i).reflectance_with::<P>(c, cos2_theta_d),
        )
    }
}

/// Hoffman's F82-tint metal Fresnel per channel, with the correction coefficient `b`
/// precomputed at construction (see [`f82_tint_with_b`]).
///
/// # Examples
///
/// ```
/// use brdf::fresnel::{Conductor, F82Tint, FresnelTerm};
/// use brdf::ior::Preset;
/// let gold = F82Tint::<f32, 3>::from_preset(Preset::Gold)?;
/// let exact = Conductor::<f32, 3>::from_preset(Preset::Gold)?;
/// let (a, b) = (gold.eval(0.5), exact.eval(0.5));
/// assert!((0..3).all(|i| (a[i] - b[i]).abs() < 0.02));
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct F82Tint<R, const N: usize> {
    f0: [R; N],
    b: [R; N],
}

impl<S: Scalar, const N: usize> F82Tint<S, N> {
    /// From `f0 ∈ [0, 1]` and `tint ∈ [0, 1]` (Open PBR's `base_color` and `specular_color`
    /// of a metal) per channel, else [`Error`].
    pub fn new(f0: [S; N], tint: [S; N]) -> Result<Self, Error> {
        let mut b = f0;
        for i in 0..N {
            error::unit_interval("f0", f0[i])?;
            error::unit_interval("tint", tint[i])?;
            b[i] = f82_b(f0[i], tint[i]);
        }
        Ok(Self { f0, b })
    }

    /// Fitted to a complex IOR per channel (`eta ∈ [MIN_ETA, MAX_ETA]`, `k ∈ [0, MAX_K]`,
    /// else [`Error`]): `F0` and
    /// the reflectance at `cos θ = 1/7` are taken from the exact [`conductor`] Fresnel, so
    /// the model is exact at `μ = 1`, `1/7` and `0`. (The implied tint may exceed 1 for
    /// some metals; `b` is then negative, which the model handles.)
    pub fn from_ior(eta: [S; N], k: [S; N]) -> Result<Self, Error> {
        let mut f0 = eta;
        let mut b = eta;
        for i in 0..N {
            check_eta(eta[i])?;
            check_k(k[i])?;
            let (n, kk): (f64, f64) = (eta[i].into(), k[i].into());
            let f0_i = conductor(1.0, n, kk);
            let f82 = conductor(F82_COS_THETA, n, kk);
            f0[i] = S::of(f0_i);
            b[i] = S::of((schlick(f0_i, F82_COS_THETA) - f82) / F82_W);
        }
        Ok(Self { f0, b })
    }
}

impl<R: Real, const N: usize> F82Tint<R, N> {
    /// Normal-incidence reflectance per channel.
    pub fn f0(&self) -> [R; N] {
        self.f0
    }

    /// The precomputed correction coefficient `b` per channel.
    pub fn b(&self) -> [R; N] {
        self.b
    }
}

impl<S: Scalar, const N: usize> Splat for F82Tint<S, N> {
    type On<L: Real> = F82Tint<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> F82Tint<L, N> {
        F82Tint {
            f0: splat_array(&self.f0),
            b: splat_array(&self.b),
        }
    }
}

impl<R: Real, const N: usize> FresnelTerm<R, N> for F82Tint<R, N> {
    #[inline(always)]
    fn eval(&self, cos_theta_d: R) -> [R; N] {
        crate::real::channels(
            #[inline(always)]
            |i| f82_tint_with_b(self.f0[i], self.b[i], cos_theta_d),
        )
    }
}

/// No Fresnel factor: reflectance `1` on every channel, so a model can be evaluated (and
/// pay) for no Fresnel at all, e.g. when the caller applies its own, or to isolate `D·G`.
///
/// ```
/// use brdf::fresnel::{FresnelTerm, NoFresnel};
/// assert_eq!(FresnelTerm::<f32, 3>::eval(&NoFresnel, 0.3), [1.0; 3]);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoFresnel;

crate::real::splat_as_itself!(NoFresnel);

impl<R: Real, const N: usize> FresnelTerm<R, N> for NoFresnel {
    #[inline(always)]
    fn eval(&self, _cos_theta_d: R) -> [R; N] {
        [R::one(); N]
    }
}

// ---------------------------------------------------------------------------------------
// A Fresnel term chosen at run time
// ---------------------------------------------------------------------------------------

/// An RGB Fresnel term chosen at run time, for a model whose parts come from a file or a
/// renderer's material table ([`crate::material::Material`]).
///
/// It implements [`FresnelTerm<R, 3>`] by forwarding **every** method
/// ([`FresnelTerm::eval_cos2`] included) to the wrapped term, so a model built on
/// `AnyFresnel` evaluates exactly the operations, hence the bits, of the same model built on
/// the wrapped type (tested in `tests/material.rs`). The price is one branch per call on
/// the variant, a per-material constant.
///
/// Build one with `From`: `AnyFresnel::from(Dielectric::<f32>::new(1.5)?)`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum AnyFresnel<R> {
    /// The exact [`Dielectric`] (the same IOR for every channel).
    Dielectric(Dielectric<R, 3>),
    /// The exact [`Conductor`], a complex IOR per channel.
    Conductor(Conductor<R, 3>),
    /// The exact [`Conductor`] whose channels share one division on the batch kernels of
    /// divider-bound cores ([`Conductor::share_divisions`], [`SharedDivision`]).
    ConductorShared(Conductor<R, 3, ExactSqrt, SharedDivision>),
    /// [`Schlick`]'s approximation with `f0` (and `f90`) per channel.
    Schlick(Schlick<R, 3>),
    /// Hoffman's [`F82Tint`] per channel.
    F82Tint(F82Tint<R, 3>),
    /// [`NoFresnel`]: `F = 1`.
    NoFresnel(NoFresnel),
}

/// `on_any_fresnel!(self, f => f.eval(c))`: the expression on the term an [`AnyFresnel`]
/// holds.
macro_rules! on_any_fresnel {
    ($any:expr, $f:ident => $e:expr) => {
        match $any {
            AnyFresnel::Dielectric($f) => $e,
            AnyFresnel::Conductor($f) => $e,
            AnyFresnel::ConductorShared($f) => $e,
            AnyFresnel::Schlick($f) => $e,
            AnyFresnel::F82Tint($f) => $e,
            AnyFresnel::NoFresnel($f) => $e,
        }
    };
}
pub(crate) use on_any_fresnel;

/// `From` each wrapped term.
macro_rules! any_fresnel_from {
    ($($v:ident($t:ty)),*) => {
        $(impl<R> From<$t> for AnyFresnel<R> {
            #[inline]
            fn from(f: $t) -> Self {
                AnyFresnel::$v(f)
            }
        })*
    };
}
any_fresnel_from!(
    Dielectric(Dielectric<R, 3>),
    Conductor(Conductor<R, 3>),
    ConductorShared(Conductor<R, 3, ExactSqrt, SharedDivision>),
    Schlick(Schlick<R, 3>),
    F82Tint(F82Tint<R, 3>),
    NoFresnel(NoFresnel)
);

impl<R> From<Dielectric<R>> for AnyFresnel<R> {
    /// The one-channel term as the three-channel one ([`Dielectric::channels`]).
    #[inline]
    fn from(f: Dielectric<R>) -> Self {
        AnyFresnel::Dielectric(Dielectric { consts: f.consts })
    }
}

impl<S: Scalar> Splat for AnyFresnel<S> {
    /// `true`: a `match` on the variant per pair keeps LLVM from vectorizing the batch
    /// path's one-lane loop; on explicit lanes it is one branch per register of 8 or 16
    /// pairs (the same operations, so the bits of [`crate::real::F32Fma`], or of
    /// [`crate::real::F32FmaSharedDiv`] where the batch path shares divisions).
    const EXPLICIT_LANES: bool = true;
    type On<L: Real> = AnyFresnel<L>;
    #[inline]
    fn splat<L: Real>(&self) -> AnyFresnel<L> {
        on_any_fresnel!(self, f => AnyFresnel::from(f.splat::<L>()))
    }
}

#[deny(clippy::missing_trait_methods)] // forward every hook, defaulted ones too
impl<R: Real> FresnelTerm<R, 3> for AnyFresnel<R> {
    #[inline(always)]
    fn eval(&self, cos_theta_d: R) -> [R; 3] {
        on_any_fresnel!(self, f => f.eval(cos_theta_d))
    }

    #[inline(always)]
    fn eval_cos2(&self, cos_theta_d: R, cos2_theta_d: R) -> [R; 3] {
        on_any_fresnel!(self, f => f.eval_cos2(cos_theta_d, cos2_theta_d))
    }
}

// ---------------------------------------------------------------------------------------------
// Terms from the named presets of `crate::ior`
// ---------------------------------------------------------------------------------------------

/// Normal-incidence reflectance per RGB channel of a preset's complex IOR,
/// `((η − 1)² + k²)/((η + 1)² + k²)` ([`f0_from_complex_ior`]).
///
/// ```
/// use brdf::{fresnel::f0_from_preset, ior::Preset};
/// assert!((f0_from_preset(Preset::Quartz)[1] - 0.0337).abs() < 1e-4);
/// ```
#[must_use]
pub fn f0_from_preset(p: Preset) -> [f64; 3] {
    let (eta, k) = p.ior();
    core::array::from_fn(|i| f0_from_complex_ior(eta[i], k[i]))
}

/// Every preset constructor has one shape: `from_preset(p: ior::Preset) -> Result<_, Error>`
/// with three (RGB) channels where the term has channels. They fail only where the term
/// cannot represent the preset ([`Dielectric::from_preset`] of an absorbing one).
impl<S: Scalar> Conductor<S, 3> {
    /// The exact RGB conductor of a preset's complex IOR (dielectric presets, `k = 0`,
    /// give the [`Dielectric`] seen from outside).
    ///
    /// ```
    /// use brdf::fresnel::{Conductor, FresnelTerm};
    /// use brdf::ior::Preset;
    /// let copper: Conductor<f32, 3> = Conductor::from_preset(Preset::from_name("copper").unwrap())?;
    /// assert!(copper.eval(1.0)[0] > 0.9);
    /// # Ok::<(), brdf::Error>(())
    /// ```
    pub fn from_preset(p: Preset) -> Result<Self, Error> {
        let (eta, k) = p.ior();
        Self::new(eta.map(S::of), k.map(S::of))
    }
}

impl<S: Scalar> Schlick<S, 3> {
    /// Schlick with the exact `F0` of a preset's complex IOR per channel
    /// ([`f0_from_preset`]) and `f90 = 1`. See the module docs for its error on metals.
    ///
    /// ```
    /// use brdf::fresnel::{FresnelTerm, Schlick};
    /// use brdf::ior::Preset;
    /// let water = Schlick::<f32, 3>::from_preset(Preset::Water)?;
    /// assert!((water.eval(1.0)[0] - 0.0201).abs() < 1e-4);
    /// # Ok::<(), brdf::Error>(())
    /// ```
    pub fn from_preset(p: Preset) -> Result<Self, Error> {
        Self::new(f0_from_preset(p).map(S::of))
    }
}

impl<S: Scalar> F82Tint<S, 3> {
    /// F82-tint fitted to a preset's complex IOR per channel (see [`F82Tint::from_ior`]).
    pub fn from_preset(p: Preset) -> Result<Self, Error> {
        let (eta, k) = p.ior();
        Self::from_ior(eta.map(S::of), k.map(S::of))
    }
}

impl<S: Scalar> Dielectric<S> {
    /// The exact dielectric of a non-absorbing preset ([`Preset::is_conductor`] false: quartz,
    /// water, sapphire, titanium dioxide, ivory, iron oxide); its IOR is the same in every
    /// channel. An absorbing preset is an [`Error`] (`param` `"preset"`, `value` its largest
    /// `k`): use [`Conductor::from_preset`].
    ///
    /// ```
    /// use brdf::fresnel::Dielectric;
    /// use brdf::ior::Preset;
    /// assert_eq!(Dielectric::<f64>::from_preset(Preset::Sapphire)?.eta(), 1.76);
    /// assert!(Dielectric::<f64>::from_preset(Preset::Gold).is_err());
    /// # Ok::<(), brdf::Error>(())
    /// ```
    pub fn from_preset(p: Preset) -> Result<Self, Error> {
        let (eta, k) = p.ior();
        if p.is_conductor() {
            return Err(Error::OutOfDomain {
                param: "preset",
                value: k[0].max(k[1]).max(k[2]),
                domain: "non-absorbing presets (k = 0); use Conductor::from_preset",
            });
        }
        Self::new(S::of(eta[1]))
    }
}

// ---------------------------------------------------------------------------------------
// Reference-only formulas
// ---------------------------------------------------------------------------------------

/// Formulas from the literature kept for comparison and conversion rather than as Fresnel
/// terms: Cook & Torrance's `(g, c)` form of the dielectric reflectance (algebraically
/// [`dielectric`], tested equal) and Gulbrandsen's
/// artist-friendly reflectivity/edge-tint mapping to a complex IOR (the model-facing entry
/// point is [`Conductor::from_reflectivity_edge_tint`]).
///
/// References: R. L. Cook, K. E. Torrance, ACM Trans. Graph. 1(1), 1982; O. Gulbrandsen,
/// "Artist Friendly Metallic Fresnel", JCGT 3(4), 2014.
pub mod reference {
    use super::{DielectricConsts, ior_from_f0};
    use crate::Real;
    use crate::fresnel::f0_from_complex_ior;

    /// Cook & Torrance's closed form of the unpolarized dielectric Fresnel reflectance, as the
    /// seed talk quotes it for Blinn's model, with its two OCR/slide errors corrected:
    ///
    /// ```text
    /// c = cos θ,   g² = η² + c² − 1     (seed: "g = √(n² + c²) − 1": the −1 belongs under the root)
    /// F = ½ (g − c)²/(g + c)² · (1 + (c(g + c) − 1)² / (c(g − c) + 1)²)      (seed omits the ½)
    /// F = 1 when g² < 0 (total internal reflection)
    /// ```
    ///
    /// It is algebraically the same as [`dielectric`](super::dielectric): `(g − c)/(g + c) = −r_s` and the second
    /// factor is `1 + r_p²/r_s²` (tests check the equality over the whole domain). Without the
    /// `½` the value at normal incidence would be `2 F0`.
    ///
    /// * Domain: `eta ∈ [MIN_ETA, MAX_ETA]`, `cos_theta` by magnitude, clamped to 1 (no `1/η`
    ///   flip: pass the relative IOR seen from the incident side). Result in `[0, 1]`;
    ///   index-matched (`η = 1`) gives `0` at every angle. `g` is formed as in [`dielectric`](super::dielectric).
    ///
    /// Reference: R. L. Cook, K. E. Torrance, "A Reflectance Model for Computer Graphics",
    /// ACM Trans. Graph. 1(1), 1982, eq. in §3 (after Sparrow & Cess); J. F. Blinn, "Models of Light
    /// Reflection for Computer Synthesized Pictures", SIGGRAPH 1977.
    ///
    /// # Examples
    ///
    /// ```
    /// use brdf::fresnel::{dielectric, reference::cook_torrance_gc};
    /// let (c, eta) = (0.3_f64, 1.5);
    /// assert!((cook_torrance_gc(c, eta) - dielectric(c, eta)).abs() < 1e-15);
    /// ```
    #[inline]
    #[must_use]
    pub fn cook_torrance_gc<R: Real>(cos_theta: R, eta: R) -> R {
        let c = cos_theta.abs().min(R::one());
        // g = η cos θt, cos θt formed as in `dielectric` (g = c at η = 1).
        let (t, tir) = DielectricConsts::of(eta, eta.recip()).cos_t(c, c * c);
        let g = eta * t;
        let gpc = g + c;
        let gmc = g - c;
        let a = R::select(gpc.gt(R::zero()), gmc / gpc, R::zero());
        let b = c.mul_add(gpc, -R::one()) / c.mul_add(gmc, R::one());
        let f = (a * a * b.mul_add(b, R::one()) * R::from_f64(0.5)).min(R::one());
        R::select(tir, R::one(), f)
    }

    /// Gulbrandsen's artist-friendly parameters → complex IOR: from reflectivity `r` (the
    /// normal-incidence reflectance) and edge tint `g`, the `(n, k)` with `F0 = r`.
    ///
    /// ```text
    /// n_min = (1 − r)/(1 + r),   n_max = (1 + √r)/(1 − √r)
    /// n = g·n_min + (1 − g)·n_max
    /// k = √( (r (n + 1)² − (n − 1)²) / (1 − r) )
    /// ```
    ///
    /// `k` solves `F0(n, k) = r` for `k` (see [`f0_from_complex_ior`]); real `k` needs
    /// `n ∈ [(1−√r)/(1+√r), n_max]`, which `n ∈ [n_min, n_max]` satisfies. `g = 0` gives the
    /// dielectric `n = n_max, k = 0`; `g = 1` the smallest `n` (`n_min`). Along the family `k`
    /// is not monotonic: it peaks at `n = (1 + r)/(1 − r)`, inside `[n_min, n_max]`. The result is exact Fresnel: [`conductor`](super::conductor)`(1, n, k) = r`.
    ///
    /// * Domain `r ∈ [0, 1)`, `g ∈ [0, 1]`. As `r → 1`, `n_max` and `k` grow like `1/(1 − √r)`;
    ///   shader implementations clamp `r ≤ 0.99`.
    ///
    /// Reference: O. Gulbrandsen, "Artist Friendly Metallic Fresnel", JCGT 3(4), 2014, §3.
    ///
    /// # Examples
    ///
    /// ```
    /// use brdf::fresnel::f0_from_complex_ior;
    /// use brdf::fresnel::reference::{gulbrandsen_from_nk, gulbrandsen_to_nk};
    /// let (n, k) = gulbrandsen_to_nk(0.9_f64, 0.5);
    /// assert!((f0_from_complex_ior(n, k) - 0.9).abs() < 1e-12);
    /// let (r, g) = gulbrandsen_from_nk(n, k);
    /// assert!((r - 0.9).abs() < 1e-12 && (g - 0.5).abs() < 1e-12);
    /// ```
    #[inline]
    #[must_use]
    pub fn gulbrandsen_to_nk<R: Real>(r: R, g: R) -> (R, R) {
        let (n_min, n_max) = gulbrandsen_n_range(r);
        // (1 − g)·n_max + g·n_min: exact at both ends (n_max ≫ n_min as r → 1).
        let n = g.mul_add(n_min, (R::one() - g) * n_max);
        let np = n + R::one();
        let nm = n - R::one();
        let k2 = (r * np).mul_add(np, -(nm * nm)) / (R::one() - r);
        (n, k2.safe_sqrt())
    }

    /// Complex IOR → Gulbrandsen's artist-friendly `(r, g)`: reflectivity and edge tint.
    ///
    /// ```text
    /// r = ((n − 1)² + k²) / ((n + 1)² + k²)
    /// g = (n_max(r) − n) / (n_max(r) − n_min(r))
    /// ```
    ///
    /// The exact inverse of [`gulbrandsen_to_nk`]. A measured metal may give `g` outside
    /// `[0, 1]` (its `n` below `n_min(r)`); the mapping still round-trips, but artist UIs that
    /// clamp `g` to `[0, 1]` then change the material. Domain `n ∈ (0, ∞)`, `k ∈ [0, ∞)` with
    /// `r < 1` and `n_max ≠ n_min` (i.e. `r > 0`); `r = 0` (`n = 1, k = 0`) returns `g = 0`.
    ///
    /// Reference: Gulbrandsen 2014, §3.
    #[inline]
    #[must_use]
    pub fn gulbrandsen_from_nk<R: Real>(n: R, k: R) -> (R, R) {
        let r = f0_from_complex_ior(n, k);
        let (n_min, n_max) = gulbrandsen_n_range(r);
        let span = n_max - n_min;
        let g = R::select(span.gt(R::zero()), (n_max - n) / span, R::zero());
        (r, g)
    }

    #[inline]
    fn gulbrandsen_n_range<R: Real>(r: R) -> (R, R) {
        // n_max is the dielectric with F0 = r.
        ((R::one() - r) / (R::one() + r), ior_from_f0(r))
    }
}
