//! [`FittedConductor`]: the exact conductor reflectance of one material, tabulated at
//! construction as a piecewise polynomial in `cos θd` and evaluated without square roots or
//! divisions.

use core::marker::PhantomData;

use super::{Conductor, DivisionPlan, FresnelTerm, conductor};
use crate::error::{self, Error};
use crate::fast::{SqrtFn, chebyshev_coefficients, chebyshev_node};
use crate::real::{F32Fma, Splat};
use crate::{Real, Scalar};

/// Segments of `cos θd ∈ [0, 1]` in a [`FittedConductor`]: 32 of width 1/32.
pub const FIT_SEGMENTS: usize = 32;

/// Degree of a [`FittedConductor`]'s polynomial on each segment.
///
/// Chosen by measurement: on an AMD EPYC (Zen 4) the peer benchmark's rough conductor ran
/// at 650 M/s with degree 5 and 526 M/s with degree 7 (both accurate to `f32` rounding for
/// gold); degree 4 loses the metals with `η > 3`.
pub const FIT_DEGREE: usize = 5;

/// The bound on the relative error of an accepted [`FittedConductor`] against the exact
/// reflectance (the `f64` closed form of [`conductor`]) that the crate tests at every
/// cosine: `2.5·10⁻⁷`, about two units in the last place of an `f32` near 1 (the exact
/// formula evaluated in `f32` is off by up to 4.8·10⁻⁷: `tests/fresnel_fitted.rs` measures
/// both). The constructor checks [`FIT_CHECK_BOUND`] (80 % of it) on a grid; between the
/// grid's points the margin is empirical — a property test samples there over the whole IOR
/// domain — not a proof.
pub const FIT_TOLERANCE: f64 = 2.5e-7;

/// Points of `cos θd` at which [`FittedConductor::new`] measures the error: `j/16384`,
/// `j = 0 … 16384` (512 per segment, both ends of every segment included).
const CHECK_POINTS: usize = 16384;

/// The error [`FittedConductor::new`] accepts at its check points: `0.8 ·`
/// [`FIT_TOLERANCE`], leaving a margin for the cosines between them (a fit measured at
/// `2.50·10⁻⁷` on a coarser grid reached `2.504·10⁻⁷` between its points; the property test
/// of `tests/fresnel_fitted.rs` samples between them).
pub const FIT_CHECK_BOUND: f64 = 0.8 * FIT_TOLERANCE;

/// The coefficients of `uʲ` on the 32 segments, aligned to a cache line: a 16-lane load of
/// either half never straddles two lines (measured on Zen 4: unaligned tables, wherever the
/// stack put them, cost up to 15 % of the rough-conductor batch).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
struct Row([f32; FIT_SEGMENTS]);

/// Coefficient tables of one channel: `[j].0[s]` is the coefficient of `uʲ` on segment `s`.
type Tables = [Row; FIT_DEGREE + 1];

/// The unpolarized reflectance of a conductor ([`conductor`]: complex IOR `η + i k` per
/// channel) as a piecewise polynomial in `c = cos θd`, fitted once at construction: no
/// square root and no division per evaluation, where the exact form ([`Conductor`]) takes
/// two square roots and a division per channel.
///
/// ```text
/// s = min(⌊32 c⌋, 31),   u = 2(32 c − s) − 1 ∈ [−1, 1]
/// R(c) ≈ Σ_{j=0}^{5} a_{s,j} uʲ            (Horner: one FMA per degree)
/// ```
///
/// On each segment the polynomial interpolates the `f64` reflectance at the 6 Chebyshev
/// points of the segment (near-minimax; L. N. Trefethen, *Approximation Theory and
/// Approximation Practice*, SIAM 2013, ch. 8 and 16), and is stored in the monomial basis of
/// `u` in `f32`. The conductor reflectance is analytic in `c` on `[0, 1]` when `k > 0` — the
/// square roots of its closed form take arguments bounded away from 0 — so on segments of
/// width 1/32 a quintic reaches `f32` rounding for the metals of the visible range.
///
/// * Accuracy: [`FittedConductor::new`] evaluates the fit in `f32` at 16385 cosines
///   (`j/16384`) against the `f64` closed form and returns [`Error::FitInaccurate`] if the
///   largest relative error (of the `f32` body and of the fused form the batch kernels run)
///   exceeds [`FIT_CHECK_BOUND`] (`2·10⁻⁷`), leaving a margin for the cosines between the
///   checked ones, which a property test holds to [`FIT_TOLERANCE`] (`2.5·10⁻⁷`); the value
///   it measured is [`FittedConductor::max_error`]. On the crate's metal presets and
///   Mitsuba's RGB gold the worst error over 2²⁰ cosines is `6.0·10⁻⁸ … 1.2·10⁻⁷` (up to
///   `1.4·10⁻⁷` on the `tradeoffs` grid), where the exact formula evaluated in `f32`
///   ([`Conductor`]) is off by `3.0·10⁻⁷ … 4.8·10⁻⁷` (`2.6·10⁻⁷ … 3.8·10⁻⁷` there): the fit is
///   the more accurate of the two in `f32`.
/// * Where it is accepted (tested): `η ∈ [0.03, 4.8]` with `k ∈ [0.5, 6.5]`, and `k` up to
///   9.5 for `η ≤ 2.3` — the metals of the visible range. It is refused near a dielectric's
///   critical angle (`η < 1` with `k ≲ 0.3`, where the reflectance bends sharply), for a
///   dielectric with TIR (`k = 0`, `η < 1`), and for large IORs (`η ≳ 6` or `k ≳ 10`: the
///   pseudo-Brewster dip near grazing becomes narrower than a segment): use [`Conductor`]
///   there.
/// * The accuracy is that of `f32` on every number type: on `f64` the coefficients are still
///   `f32` (use [`Conductor`] for `f64` accuracy).
/// * Domain: `cos_theta_d` by magnitude, clamped to `[0, 1]` (NaN gives some value in
///   `[0, 1]`); the result is clamped to at most 1. Branch-free; the coefficient lookup is
///   [`crate::real::Bits::lookup32`] (one register permute per coefficient on the batch
///   path's AVX-512 lanes).
/// * Speed: on the batch path it runs on explicit lanes ([`Splat::EXPLICIT_LANES`]); the
///   measured speed-up over the exact conductor is in the README and `docs/tradeoffs.md`.
/// * Size: `32 × 6` `f32` per channel (768 bytes).
///
/// # Examples
///
/// ```
/// use brdf::fresnel::{Conductor, FittedConductor, FresnelTerm};
/// use brdf::ior::Preset;
/// let exact = Conductor::<f32, 3>::from_preset(Preset::Gold)?;
/// let fitted = FittedConductor::from_conductor(&exact)?;
/// assert!(fitted.max_error() <= 2e-7); // FIT_CHECK_BOUND
/// let (a, b) = (exact.eval(0.3), fitted.eval(0.3));
/// assert!((0..3).all(|i| (a[i] - b[i]).abs() <= 1e-6 * a[i]));
/// // Near a dielectric's critical angle the fit is refused, with the error it reached.
/// assert!(FittedConductor::<f32, 1>::new([0.5], [0.05]).is_err());
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FittedConductor<R, const N: usize> {
    tables: [Tables; N],
    eta: [f64; N],
    k: [f64; N],
    max_error: f64,
    _r: PhantomData<R>,
}

impl<S: Scalar, const N: usize> FittedConductor<S, N> {
    /// Fits the conductor with `eta ∈ [MIN_ETA, MAX_ETA]`, `k ∈ [0, MAX_K]` per channel (the
    /// domain of [`Conductor::new`]).
    ///
    /// # Errors
    ///
    /// [`Error`] for an IOR outside the domain, and [`Error::FitInaccurate`] if the fit of
    /// a channel misses [`FIT_CHECK_BOUND`] at the check points (see the type's docs for
    /// where).
    pub fn new(eta: [S; N], k: [S; N]) -> Result<Self, Error> {
        Conductor::new(eta, k)?;
        let eta: [f64; N] = eta.map(Into::into);
        let k: [f64; N] = k.map(Into::into);
        let tables = core::array::from_fn(|ch| fit_channel(eta[ch], k[ch]));
        let fitted = Self {
            tables,
            eta,
            k,
            max_error: 0.0,
            _r: PhantomData,
        };
        let max_error = fitted.measure_error();
        if max_error > FIT_CHECK_BOUND {
            return Err(error::fit_inaccurate(max_error, FIT_CHECK_BOUND));
        }
        Ok(Self {
            max_error,
            ..fitted
        })
    }

    /// The fit of `conductor`'s IOR (its square-root policy and division plan do not
    /// matter: the fit is of the exact reflectance).
    ///
    /// # Errors
    ///
    /// As [`FittedConductor::new`].
    pub fn from_conductor<P: SqrtFn, D: DivisionPlan>(
        conductor: &Conductor<S, N, P, D>,
    ) -> Result<Self, Error> {
        Self::new(conductor.eta(), conductor.k())
    }

    /// The largest relative error against the `f64` closed form over every channel,
    /// measured in `f32` at the construction's check points (`≤ `[`FIT_CHECK_BOUND`]).
    pub fn max_error(&self) -> f64 {
        self.max_error
    }

    /// The real part of the IOR per channel, as given.
    pub fn eta(&self) -> [f64; N] {
        self.eta
    }

    /// The extinction coefficient per channel, as given.
    pub fn k(&self) -> [f64; N] {
        self.k
    }

    /// Largest relative error at `j/16384` over the channels and over both `f32` forms — the
    /// `f32` body (whose `mul_add` fuses only on builds with the `fma` target feature) and
    /// the always-fused [`F32Fma`] the batch kernels run — (`∞` where the exact reflectance is
    /// 0 and the fit is not).
    fn measure_error(&self) -> f64 {
        let (on_f32, fused) = (self.splat::<f32>(), self.splat::<F32Fma>());
        let mut worst = 0.0f64;
        for j in 0..=CHECK_POINTS {
            let c = j as f32 / CHECK_POINTS as f32;
            let (plain, fma) = (on_f32.eval(c), fused.eval(F32Fma(c)));
            let fits = plain.iter().zip(&fma).map(|(&p, f)| [p, f.0]);
            for ((pair, &eta), &k) in fits.zip(&self.eta).zip(&self.k) {
                for f in pair {
                    let exact = conductor(f64::from(c), eta, k);
                    let err = (f64::from(f) - exact).abs();
                    // 0/0 where both vanish; err/0 = ∞ where only the fit does not.
                    let rel = if err == 0.0 { 0.0 } else { err / exact };
                    // A NaN counts as infinitely wrong.
                    worst = if rel.is_nan() {
                        f64::INFINITY
                    } else {
                        worst.max(rel)
                    };
                }
            }
        }
        worst
    }
}

/// The coefficient tables of one channel: per segment, the Chebyshev interpolant at
/// `FIT_DEGREE + 1` points converted to the monomial basis of `u ∈ [−1, 1]`, rounded to `f32`.
fn fit_channel(eta: f64, k: f64) -> Tables {
    const M: usize = FIT_DEGREE + 1;
    // Monomial coefficients of T_0 … T_{M−1}: T_{j+1} = 2u T_j − T_{j−1} (small integers, exact).
    let mut cheb = [[0.0f64; M]; M];
    cheb[0][0] = 1.0;
    cheb[1][1] = 1.0;
    for j in 1..M - 1 {
        for p in 0..M {
            let up = if p > 0 { 2.0 * cheb[j][p - 1] } else { 0.0 };
            cheb[j + 1][p] = up - cheb[j - 1][p];
        }
    }
    let mut tables = [Row([0.0f32; FIT_SEGMENTS]); M];
    for s in 0..FIT_SEGMENTS {
        // The reflectance at the segment's Chebyshev points, u_m ↦ c = (s + (u_m + 1)/2)/32.
        let f: [f64; M] = core::array::from_fn(|m| {
            let u = chebyshev_node(m, M);
            let c = (s as f64 + (u + 1.0) * 0.5) / FIT_SEGMENTS as f64;
            conductor(c, eta, k)
        });
        let b = chebyshev_coefficients(&f);
        for (p, row) in tables.iter_mut().enumerate() {
            let a: f64 = (0..M).map(|j| b[j] * cheb[j][p]).sum();
            row.0[s] = a as f32;
        }
    }
    tables
}

impl<S: Scalar, const N: usize> Splat for FittedConductor<S, N> {
    /// The coefficient lookup wants register permutes (the one-lane loop would load per
    /// lane).
    const EXPLICIT_LANES: bool = true;
    type On<L: Real> = FittedConductor<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> FittedConductor<L, N> {
        FittedConductor {
            tables: self.tables,
            eta: self.eta,
            k: self.k,
            max_error: self.max_error,
            _r: PhantomData,
        }
    }
}

impl<R: Real, const N: usize> FresnelTerm<R, N> for FittedConductor<R, N> {
    /// The segment's polynomial by Horner's rule (five FMAs and six lookups per channel, the
    /// segment index and `u` shared by the channels).
    #[inline(always)]
    fn eval(&self, cos_theta_d: R) -> [R; N] {
        let c = cos_theta_d.abs().min(R::one());
        // 32c is exact, so is 32c − s (Sterbenz); u = 2(32c − s) − 1 rounds once.
        let x = c * R::from_f64(FIT_SEGMENTS as f64);
        let s = x.floor().min(R::from_f64((FIT_SEGMENTS - 1) as f64));
        let u = (x - s).mul_add(R::from_f64(2.0), -R::one());
        let mut out = [R::zero(); N];
        for (o, t) in out.iter_mut().zip(&self.tables) {
            let mut r = s.lookup32(&t[FIT_DEGREE].0);
            for row in t[..FIT_DEGREE].iter().rev() {
                r = r.mul_add(u, s.lookup32(&row.0));
            }
            *o = r.min(R::one());
        }
        out
    }
}
