//! Building blocks of the lobe samplers of the non-microfacet models: cosine-power lobes
//! about an axis, Phong-type half-vector lobes (Ashikhmin & Shirley 2000), Ward's Gaussian
//! half-vector lobe (Walter 2005), and one-sample mixtures (Veach 1997, §9.2.4).
//!
//! Everything is branch-free: a mixture draws every candidate direction and selects one per
//! lane, so lanes that choose different lobes stay in one instruction stream.

use super::{Sample, cosine_hemisphere_pdf};
use crate::fast::{ExactSqrt, sin_cos_2pi};
use crate::models::{half_and_cos_d, select_vec};
use crate::{Real, Vec3};

/// The largest `f32` below 1 (`1 − 2⁻²⁴`, exact in `f64` too): remapped uniform numbers are
/// clamped to it so that they stay in `[0, 1)` after rounding.
const ONE_BELOW: f64 = 1.0 - 1.0 / 16_777_216.0;

/// Floor of the densities' denominators (`4 wo·wm`, `cos³θm`): finite results where a cosine
/// underflows.
const PDF_FLOOR: f64 = 1e-30;

/// `1 − eˣ` for `x ≤ 0`, accurate near `0` (a degree-5 Taylor polynomial for `x > −0.01`,
/// relative error < 2e-13; `1 − eˣ` below). `x = −∞` gives `1`.
#[inline(always)]
pub(crate) fn one_minus_exp<R: Real>(x: R) -> R {
    let c = |v: f64| R::from_f64(v);
    let poly = x.mul_add(
        x.mul_add(
            x.mul_add(x.mul_add(c(1.0 / 120.0), c(1.0 / 24.0)), c(1.0 / 6.0)),
            c(0.5),
        ),
        R::one(),
    );
    R::select(x.gt(c(-0.01)), -x * poly, R::one() - x.exp())
}

/// `(cos θ, sin θ)` with `cos θ = (1 − u)^(1/(e + 1))`: the polar angle of a direction drawn
/// with density `(e + 1)/(2π) cos^e θ` per solid angle, for `u ∈ [0, 1)`, `e ≥ 0`.
///
/// `sin²θ = 1 − (1 − u)^(2/(e+1))` is computed as `1 − exp(2 ln(1 − u)/(e + 1))` by
/// [`one_minus_exp`], so it keeps its digits for huge exponents (`e = 1e4` in `f32`).
#[inline(always)]
pub(crate) fn cos_power_angle<R: Real>(e: R, u: R) -> (R, R) {
    let l = (R::one() - u).ln() / (e + R::one());
    let cos = l.exp();
    let sin = one_minus_exp(l + l).saturate().sqrt();
    (cos, sin)
}

/// The density `(e + 1)/(2π) max(0, c)^e` of [`cos_power_angle`] at `c = cos θ` (per solid
/// angle; `0` where `c ≤ 0`, also for `e = 0`).
#[inline(always)]
pub(crate) fn cos_power_pdf<R: Real>(e: R, c: R) -> R {
    let p = (e + R::one()) * R::from_f64(0.5 / core::f64::consts::PI) * c.max(R::zero()).pow(e);
    R::select(c.gt(R::zero()), p, R::zero())
}

/// An orthonormal basis `(t, b)` completing the unit vector `a` (Duff et al., "Building an
/// Orthonormal Basis, Revisited", JCGT 6(1), 2017): branch-free, continuous except across
/// `a.z = 0`, exact for `a = ±z`.
#[inline(always)]
pub(crate) fn basis<R: Real>(a: Vec3<R>) -> (Vec3<R>, Vec3<R>) {
    let sign = R::select(a.z.ge(R::zero()), R::one(), -R::one());
    let k = -(sign + a.z).recip();
    let b = a.x * a.y * k;
    (
        Vec3::new(
            (sign * a.x * a.x).mul_add(k, R::one()),
            sign * b,
            -sign * a.x,
        ),
        Vec3::new(b, (a.y * a.y).mul_add(k, sign), -a.y),
    )
}

/// A direction drawn about the unit `axis` with density `(e + 1)/(2π) max(0, axis·w)^e`
/// ([`cos_power_angle`] for the polar angle, `φ = 2π u1`).
#[inline(always)]
pub(crate) fn sample_cos_power<R: Real>(axis: Vec3<R>, e: R, u0: R, u1: R) -> Vec3<R> {
    let (cos, sin) = cos_power_angle(e, u0);
    let (sin_phi, cos_phi) = sin_cos_2pi(u1);
    let (t, b) = basis(axis);
    t.scale(sin * cos_phi) + b.scale(sin * sin_phi) + axis.scale(cos)
}

/// A half-vector distribution: draws the microfacet normal `wm` (upper hemisphere) and gives
/// its density per solid angle of `wm`.
pub(crate) trait HalfLobe<R: Real> {
    /// `wm` from `u0, u1 ∈ [0, 1)`.
    fn draw(&self, u0: R, u1: R) -> Vec3<R>;
    /// The density of [`draw`](HalfLobe::draw) at the unit `wm`.
    fn density(&self, wm: Vec3<R>) -> R;
}

/// Ashikhmin and Shirley's anisotropic Phong half-vector lobe (JGT 5(2), 2000, §5):
///
/// ```text
/// p_h(wm) = √((nu + 1)(nv + 1))/(2π) · cos^e θm,    e = nu cos²φm + nv sin²φm
/// φm:  tan φm = √((nu + 1)/(nv + 1)) tan(2π u1)    (same quadrant as 2π u1)
/// cos θm = (1 − u0)^(1/(e + 1))
/// ```
///
/// `φm` without `atan`: `(cos φm, sin φm)` is the direction of `(√(nv + 1) cos ψ,
/// √(nu + 1) sin ψ)`, `ψ = 2π u1` (same tangent, same quadrant), so the paper's quadrant
/// bookkeeping of `πu/2` is not needed. With `nu = nv = s` it is the Blinn-Phong lobe
/// `(s + 1)/(2π) cos^s θm`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PhongHalf<R> {
    pub nu: R,
    pub nv: R,
}

impl<R: Real> HalfLobe<R> for PhongHalf<R> {
    #[inline(always)]
    fn draw(&self, u0: R, u1: R) -> Vec3<R> {
        let (sin_psi, cos_psi) = sin_cos_2pi(u1);
        let (x, y) = (
            (self.nv + R::one()).sqrt() * cos_psi,
            (self.nu + R::one()).sqrt() * sin_psi,
        );
        // |(x, y)| ≥ 1: both square roots are ≥ 1.
        let inv = x.mul_add(x, y * y).sqrt().recip();
        let (c, s) = (x * inv, y * inv);
        let e = self.nu.mul_add(c * c, self.nv * s * s);
        let (cos, sin) = cos_power_angle(e, u0);
        Vec3::new(sin * c, sin * s, cos)
    }

    #[inline(always)]
    fn density(&self, wm: Vec3<R>) -> R {
        let e = crate::ndf::ashikhmin_shirley_exponent(self.nu, self.nv, wm);
        let norm = ((self.nu + R::one()) * (self.nv + R::one())).sqrt();
        let p = norm * R::from_f64(0.5 / core::f64::consts::PI) * wm.z.saturate().pow(e);
        R::select(wm.z.gt(R::zero()), p, R::zero())
    }
}

/// Ward's elliptical Gaussian half-vector lobe as Walter samples it ("Notes on the Ward BRDF",
/// Cornell PCG-05-06, 2005, §3):
///
/// ```text
/// p_h(wm) = exp(−tan²θm (cos²φm/αx² + sin²φm/αy²)) / (π αx αy cos³θm)
/// φm:  tan φm = (αy/αx) tan(2π u1)                 (same quadrant)
/// tan²θm = −ln(1 − u0) / (cos²φm/αx² + sin²φm/αy²)
/// ```
///
/// `φm` without `atan`: `(cos φm, sin φm)` is the direction of `(αx cos ψ, αy sin ψ)`,
/// `ψ = 2π u1`. Stored as `1/αx²`, `1/αy²` (the model's constants), each floored at
/// `1e-30` (α capped at `1e15`, in the sampler and its density alike: a lobe that broad is
/// uniform in `tan θm` to every precision) so that `f32` lanes stay finite.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WardHalf<R> {
    pub inv_ax2: R,
    pub inv_ay2: R,
}

impl<R: Real> WardHalf<R> {
    /// `1/αx²`, `1/αy²` floored at `1e-30`.
    #[inline(always)]
    fn inv2(&self) -> (R, R) {
        let floor = R::from_f64(1e-30);
        (self.inv_ax2.max(floor), self.inv_ay2.max(floor))
    }
}

impl<R: Real> HalfLobe<R> for WardHalf<R> {
    #[inline(always)]
    fn draw(&self, u0: R, u1: R) -> Vec3<R> {
        let (ix2, iy2) = self.inv2();
        let (sin_psi, cos_psi) = sin_cos_2pi(u1);
        // (αx cos ψ, αy sin ψ) ∝ (cos ψ/αy, sin ψ/αx); rescaled by the larger factor first so
        // that the squares neither overflow nor underflow.
        let (fx, fy) = (iy2.sqrt(), ix2.sqrt());
        let big = fx.max(fy);
        let (x, y) = ((fx / big) * cos_psi, (fy / big) * sin_psi);
        let inv = x.mul_add(x, y * y).sqrt().recip();
        let (c, s) = (x * inv, y * inv);
        let a = (c * c).mul_add(ix2, s * s * iy2);
        let q = -(R::one() - u0).ln() / a;
        // cos²θ = 1/(1 + q), sin²θ = q/(1 + q) (the second form loses nothing for small q and
        // is 1 for q = ∞).
        let cos2 = (R::one() + q).recip();
        let sin2 = R::select(q.lt(R::one()), q * cos2, R::one() - cos2);
        let sin = sin2.saturate().sqrt();
        Vec3::new(sin * c, sin * s, cos2.sqrt())
    }

    #[inline(always)]
    fn density(&self, wm: Vec3<R>) -> R {
        let (ix2, iy2) = self.inv2();
        let z2 = (wm.z * wm.z).max(R::from_f64(PDF_FLOOR));
        let e = (wm.x * wm.x).mul_add(ix2, wm.y * wm.y * iy2) / z2;
        let k = ix2.sqrt() * iy2.sqrt() * R::frac_1_pi();
        let cos3 = (z2 * wm.z).max(R::from_f64(PDF_FLOOR));
        R::select(wm.z.gt(R::zero()), k * (-e).exp() / cos3, R::zero())
    }
}

/// `wi = 2 (wo·wm) wm − wo`, the mirror of `wo` about `wm`, and whether `wo·wm > 0` (the
/// reflection of a back-facing normal is not a sample of the lobe).
#[inline(always)]
pub(crate) fn reflect<R: Real>(wo: Vec3<R>, wm: Vec3<R>) -> (Vec3<R>, R::Mask) {
    let d = wo.dot(wm);
    (wm.scale(d + d) + wo.scale(-R::one()), d.gt(R::zero()))
}

/// The density of `wi` when `wm` is drawn from `lobe` and `wo` reflected about it:
/// `p_h(wm) / (4 wo·wm)`, `wm = (wi + wo)/|wi + wo|` (Walter et al. 2007, eq. 14). `0` where
/// either direction is below the horizon.
#[inline(always)]
pub(crate) fn reflected_pdf<R: Real, H: HalfLobe<R>>(lobe: &H, wo: Vec3<R>, wi: Vec3<R>) -> R {
    let ok = wi.z.gt(R::zero()) & wo.z.gt(R::zero());
    let (wm, cos_d) = half_and_cos_d::<ExactSqrt, R>(wi, wo);
    let p = lobe.density(wm) / (R::from_f64(4.0) * cos_d.min(R::one())).max(R::from_f64(PDF_FLOOR));
    R::select(ok, p, R::zero())
}

/// Mean of the channels.
#[inline(always)]
pub(crate) fn mean<R: Real, const N: usize>(v: [R; N]) -> R {
    let s = v.iter().fold(R::zero(), |a, &b| a + b);
    s * R::from_f64(1.0 / N.max(1) as f64)
}

/// Probability `ea/(ea + eb)` of the first of two lobes with (non-negative) estimates `ea`,
/// `eb`; `1/2` if both are `0`.
#[inline(always)]
pub(crate) fn first_probability<R: Real>(ea: R, eb: R) -> R {
    let t = ea + eb;
    R::select(
        t.gt(R::zero()),
        (ea / t.max(R::from_f64(1e-30))).saturate(),
        R::from_f64(0.5),
    )
}

/// The one-sample mixture density `p·pa + (1 − p)·pb` (Veach 1997, §9.2.4).
#[inline(always)]
pub(crate) fn mix<R: Real>(p: R, pa: R, pb: R) -> R {
    p * pa + (R::one() - p) * pb
}

/// Completes a sample drawn at `wi` by any strategy: the density `pdf` (of the whole
/// strategy, e.g. a mixture), `f = eval(wi)`, `weight = f cos θi / pdf`.
#[inline(always)]
pub(crate) fn finish<R: Real, const N: usize>(
    wi: Vec3<R>,
    pdf: R,
    f: [R; N],
    valid: R::Mask,
) -> Sample<R, N> {
    // Where pdf = 0 the lane is invalid and `Sample::new` replaces the quotient by 0.
    let inv = wi.z.max(R::zero()) / pdf;
    let weight = crate::real::channels(
        #[inline(always)]
        |c| f[c] * inv,
    );
    Sample::new(wi, pdf, f, weight, valid)
}

/// The mixture of cosine sampling (probability `pd`) and reflection about a half vector drawn
/// from `lobe` (probability `1 − pd`), chosen by `u2 < pd`. `eval` is the whole model.
#[inline(always)]
pub(crate) fn sample_diffuse_and_half<R: Real, const N: usize, H: HalfLobe<R>>(
    lobe: &H,
    pd: R,
    wo: Vec3<R>,
    u: [R; 3],
    eval: impl Fn(Vec3<R>) -> [R; N],
) -> Sample<R, N> {
    let wd = super::cosine_hemisphere(u[0], u[1]);
    let (ws, ok_s) = reflect(wo, lobe.draw(u[0], u[1]));
    let choose_d = u[2].lt(pd);
    let wi = select_vec(choose_d, wd, ws);
    let pdf = pdf_diffuse_and_half(lobe, pd, wo, wi);
    finish(wi, pdf, eval(wi), wo.z.gt(R::zero()) & (choose_d | ok_s))
}

/// The density of [`sample_diffuse_and_half`]: `pd cos θi/π + (1 − pd) p_h(wm)/(4 wo·wm)`.
#[inline(always)]
pub(crate) fn pdf_diffuse_and_half<R: Real, H: HalfLobe<R>>(
    lobe: &H,
    pd: R,
    wo: Vec3<R>,
    wi: Vec3<R>,
) -> R {
    let ok = wi.z.gt(R::zero()) & wo.z.gt(R::zero());
    let p = mix(pd, cosine_hemisphere_pdf(wi), reflected_pdf(lobe, wo, wi));
    R::select(ok, p, R::zero())
}

/// The one-sample mixture of two samplers `a` (probability `p`) and `b`: `u2 < p` chooses
/// `a`, which gets `u2/p` as its own third number (`b` gets `(u2 − p)/(1 − p)`), so nested
/// mixtures still receive a uniform number. The density is `p·pa + (1 − p)·pb` and the weight
/// `f cos θi / pdf` with `f = eval(wi)` the whole model (not the chosen part's own weight).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn sample_pair<R: Real, const N: usize>(
    p: R,
    wo: Vec3<R>,
    u: [R; 3],
    sample_a: impl FnOnce([R; 3]) -> Sample<R, N>,
    sample_b: impl FnOnce([R; 3]) -> Sample<R, N>,
    pdf_a: impl Fn(Vec3<R>) -> R,
    pdf_b: impl Fn(Vec3<R>) -> R,
    eval: impl Fn(Vec3<R>) -> [R; N],
) -> Sample<R, N> {
    let (ua, ub) = split_u2(p, u[2]);
    let sa = sample_a([u[0], u[1], ua]);
    let sb = sample_b([u[0], u[1], ub]);
    let (wi, valid) = choose_pair(p, u[2], (sa.wi, sa.valid), (sb.wi, sb.valid));
    let pdf = pdf_pair(p, wo, wi, pdf_a, pdf_b);
    finish(wi, pdf, eval(wi), valid & wo.z.gt(R::zero()))
}

/// The third uniform numbers of [`sample_pair`]'s parts: `u2/p` for `a` and
/// `(u2 − p)/(1 − p)` for `b`, each kept below 1.
#[inline(always)]
pub(crate) fn split_u2<R: Real>(p: R, u2: R) -> (R, R) {
    let tiny = R::from_f64(1e-30);
    let top = R::from_f64(ONE_BELOW);
    let ua = (u2 / p.max(tiny)).min(top);
    let ub = ((u2 - p) / (R::one() - p).max(tiny)).clamp(R::zero(), top);
    (ua, ub)
}

/// [`sample_pair`]'s choice: part `a`'s direction and validity where `u2 < p`, else `b`'s.
#[inline(always)]
pub(crate) fn choose_pair<R: Real>(
    p: R,
    u2: R,
    a: (Vec3<R>, R::Mask),
    b: (Vec3<R>, R::Mask),
) -> (Vec3<R>, R::Mask) {
    let choose_a = u2.lt(p);
    let wi = select_vec(choose_a, a.0, b.0);
    (wi, (choose_a & a.1) | (!choose_a & b.1))
}

/// The density of [`sample_pair`]: `p·pa(wi) + (1 − p)·pb(wi)`, `0` below the horizon.
#[inline(always)]
pub(crate) fn pdf_pair<R: Real>(
    p: R,
    wo: Vec3<R>,
    wi: Vec3<R>,
    pdf_a: impl Fn(Vec3<R>) -> R,
    pdf_b: impl Fn(Vec3<R>) -> R,
) -> R {
    pdf_pair_of(p, wo, wi, pdf_a(wi), pdf_b(wi))
}

/// [`pdf_pair`] from the parts' densities at `wi`.
#[inline(always)]
pub(crate) fn pdf_pair_of<R: Real>(p: R, wo: Vec3<R>, wi: Vec3<R>, pa: R, pb: R) -> R {
    let ok = wi.z.gt(R::zero()) & wo.z.gt(R::zero());
    R::select(ok, mix(p, pa, pb), R::zero())
}
