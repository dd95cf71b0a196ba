//! The split-sum environment BRDF ("DFG" lookup table) of image-based lighting, for
//! isotropic GGX with Schlick's Fresnel and the height-correlated Smith term.
//!
//! # Definition
//!
//! Karis 2013 splits the image-based-lighting integral into a prefiltered radiance and the
//! directional albedo of the specular lobe. With Schlick's `F = F0 + (1 − F0)(1 − wo·wm)⁵`
//! the albedo is linear in `F0`:
//!
//! ```text
//! ∫ f(wi, wo) cos θi dωi = F0·A(μ, α) + B(μ, α),        μ = cos θo = n·wo
//! A = ∫ D G2 (1 − Fc) / (4 cos θo) dωi,   B = ∫ D G2 Fc / (4 cos θo) dωi,   Fc = (1 − wo·wm)⁵
//! ```
//!
//! `D` is GGX, `G2 = 1/(1 + Λ(wi) + Λ(wo))` the height-correlated Smith term (Heitz 2014), so
//! `A + B` is [`energy::directional_albedo`](crate::energy::directional_albedo) with `F = 1`.
//!
//! # Method
//!
//! [`dfg`] integrates both moments with the fixed horizon-cut Gauss-Legendre rule of
//! [`energy`](crate::energy) (the microfacet normal's CDF variable, stopped exactly at the
//! horizon of `wi`; φ panels graded towards grazing), weighting each node by `1 − Fc` and
//! `Fc`. The rule is deterministic, `A, B ≥ 0` node by node, `A + B` is the same quadrature
//! as `E` (within 5.2e-6 of the adaptive reference down to `μ = 1e-6`), and `A + B ≤ 1` holds
//! down to `μ = 0` (tested; a Hammersley estimate with the same integrand gave 1.008 at
//! `μ = 1e-6`, `α = 0.5`).
//!
//! # Multiple scattering
//!
//! The single-scattering lobe loses `1 − E`, `E = A + B`. Two compensations read the same
//! table: Fdez-Agüera 2019 ([`fdez_aguera`]: a geometric series of bounces with
//! `F_avg = F0 + (1 − F0)/21`), and the energy scaling `1 + F0 (1/E − 1)` of Filament
//! (Turquin 2019, [`turquin_factor`](crate::energy::turquin_factor)), for which Filament
//! stores `(B, A + B)` instead of `(A, B)`: [`DfgLayout::Multiscatter`].
//!
//! # Tables
//!
//! [`fill_dfg_f32`] (and `fill_dfg_f16`, feature `half`) fill a caller's slice, `no_std`;
//! `dfg_table_f32` / `dfg_table_f16` (feature `alloc`) return a `Vec`. The layout is what an
//! engine uploads as a two-channel texture (RG): `n × n` texels, row-major, two values per
//! texel; column `i` is `μ = n·v = (i + ½)/n`, row `j` is the perceptual roughness
//! `r = (j + ½)/n` (`α = r²`, floored at `1e-4`), both at texel centres, so a bilinear sampler
//! at `uv = (n·v, r)` returns the table. Row 0 (smallest roughness) comes first in memory, as
//! both Direct3D (`v = 0` at the first row) and OpenGL (`t = 0` at the first row uploaded)
//! expect.
//!
//! # Approximations
//!
//! [`env_brdf_approx`] (Karis 2014) and [`lazarov_env_brdf`] (Lazarov 2013) are the analytic
//! fits engines use instead of the table; their errors against it are in `docs/tradeoffs.md`.
//!
//! References: B. Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 course *Physically
//! Based Shading in Theory and Practice*; C. Fdez-Agüera, "A Multiple-Scattering Microfacet
//! Model for Real-Time Image-based Lighting", JCGT 8(1), 2019; R. Guy, M. Agopian, "Physically
//! Based Rendering in Filament" (Google, 2018–); E. Heitz, "Understanding the Masking-Shadowing
//! Function in Microfacet-Based BRDFs", JCGT 3(2), 2014; B. Karis, "Physically Based Shading
//! on Mobile", Unreal Engine blog, 2014; D. Lazarov, "Getting More Physical in Call of Duty:
//! Black Ops II", SIGGRAPH 2013 course *Physically Based Shading in Theory and Practice*.

use crate::energy::{Distribution, lobe_moments};
use crate::{Error, Real};

/// The two terms of the split-sum specular albedo at one `(μ, α)`: `F0·a + b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dfg {
    /// `A = ∫ D G2 (1 − (1 − wo·wm)⁵) / (4 cos θo) dωi`: the scale of `F0`.
    pub a: f64,
    /// `B = ∫ D G2 (1 − wo·wm)⁵ / (4 cos θo) dωi`: the bias (the response at `F0 = 0`).
    pub b: f64,
}

impl Dfg {
    /// The single-scattering specular albedo `F0·A + B` with Schlick's Fresnel.
    /// Domain `F0 ∈ [0, 1]`; result in `[0, 1]`. Reference: Karis 2013.
    #[must_use]
    pub fn single_scatter(self, f0: f64) -> f64 {
        f0 * self.a + self.b
    }

    /// The albedo with `F = 1`, `E = A + B` (= [`energy::directional_albedo`] of GGX to
    /// rounding). Reference: Karis 2013.
    ///
    /// [`energy::directional_albedo`]: crate::energy::directional_albedo
    #[must_use]
    pub fn albedo(self) -> f64 {
        self.a + self.b
    }
}

/// `(A, B)` of the split-sum approximation for isotropic GGX, Schlick's Fresnel and the
/// height-correlated Smith term (Karis 2013):
///
/// ```text
/// ∫ f cos θi dωi = F0·A + B,   A = ∫ f₁ (1 − Fc) cos θi dωi,   B = ∫ f₁ Fc cos θi dωi
/// f₁ = D G2 / (4 cos θi cos θo),   Fc = (1 − wo·wm)⁵
/// ```
///
/// Computed by the deterministic horizon-cut Gauss-Legendre rule of
/// [`energy::directional_albedo`](crate::energy::directional_albedo) with the node weights
/// `1 − Fc` and `Fc` (see the [module docs](self)), within 2e-4 of an adaptive integral of
/// the crate's Cook-Torrance (tested). `A, B ≥ 0`; `A + B ≤ 1` (the rule's own `A + B`
/// exceeds 1 by at most 3e-6, at `μ < 1e-5` where the true value is within 3e-6 of 1: both
/// terms are then scaled by `1/(A + B)`); `A + B → 1` and `B → (1 − μ)⁵` as `α → 0`.
///
/// Domain `cos_theta_o ∈ [0, 1]` (clamped to `[1e-6, 1]` inside, as `directional_albedo`),
/// `alpha ∈ [1e-4, 1]`. Cost: one quadrature of 8k–150k integrand evaluations (about 0.7 ms
/// on average over a table, in release).
///
/// ```
/// use brdf::split_sum::dfg;
/// let t = dfg(0.5, 0.25)?;
/// assert!(t.a > 0.0 && t.b > 0.0 && t.albedo() <= 1.0);
/// # Ok::<(), brdf::Error>(())
/// ```
///
/// # Errors
/// [`Error::NotFinite`] or [`Error::OutOfDomain`] naming `cos_theta_o` or `alpha`.
pub fn dfg(cos_theta_o: f64, alpha: f64) -> Result<Dfg, Error> {
    let [a, b] = lobe_moments(Distribution::Ggx, alpha, cos_theta_o, |o_m| {
        let c = (1.0 - o_m).max(0.0);
        let c2 = c * c;
        let fc = c2 * c2 * c;
        [1.0 - fc, fc]
    })?;
    // The rule overestimates E by up to 5.2e-6 at grazing (against the adaptive reference);
    // where that crosses the bound E ≤ 1 (μ < 1e-5, E within 3e-6 of 1), scaling both terms
    // onto it moves them towards the true values.
    let e = a + b;
    let k = if e > 1.0 { 1.0 / e } else { 1.0 };
    Ok(Dfg { a: a * k, b: b * k })
}

/// Fdez-Agüera's multiple-scattering specular albedo from a split-sum texel:
///
/// ```text
/// E_ss = A + B,   F_ss E_ss = F0·A + B,   E_ms = 1 − E_ss,   F_avg = F0 + (1 − F0)/21
/// F_ms = F_ss E_ss · F_avg / (1 − E_ms F_avg)
/// albedo = F_ss E_ss + F_ms E_ms
/// ```
///
/// (`F_avg` of Schlick's term is [`energy::schlick_average`](crate::energy::schlick_average).)
/// With `F0 = 1` the albedo is exactly `E_ss + E_ms = 1` (white furnace). Domain `F0, A, B ≥ 0`
/// with `A + B ∈ (0, 1]`; the denominator is at least `E_ss` and is floored at `1e-30`.
///
/// Reference: C. Fdez-Agüera, "A Multiple-Scattering Microfacet Model for Real-Time
/// Image-based Lighting", JCGT 8(1), 2019 (the single-scattering Fresnel `F_ss` of its
/// eq. 9 is Schlick's here).
#[inline(always)]
#[must_use]
pub fn fdez_aguera<R: Real>(f0: R, a: R, b: R) -> R {
    let e_ss = a + b;
    let fss_ess = f0 * a + b;
    let e_ms = R::one() - e_ss;
    let f_avg = crate::energy::schlick_average(f0);
    let f_ms = fss_ess * f_avg / (R::one() - e_ms * f_avg).max(R::from_f64(1e-30));
    fss_ess + f_ms * e_ms
}

/// Karis's analytic fit of the split-sum `(A, B)` for mobile (`EnvBRDFApprox`), in the
/// perceptual roughness `r` (`α = r²`):
///
/// ```text
/// c = r (−1, −0.0275, −0.572, 0.022) + (1, 0.0425, 1.04, −0.04)
/// a004 = min(c.x², 2^(−9.28 μ)) c.x + c.y
/// (A, B) = (−1.04 a004 + c.z, 1.04 a004 + c.w)
/// ```
///
/// Domain `r, μ ∈ [0, 1]`. A fit of Unreal's GGX table (Schlick–Smith visibility, not the
/// height-correlated term): its error against [`dfg`] is in `docs/tradeoffs.md`.
/// Reference: B. Karis, "Physically Based Shading on Mobile", Unreal Engine blog, 2014
/// (after Lazarov 2013).
#[inline(always)]
#[must_use]
pub fn env_brdf_approx<R: Real>(roughness: R, cos_theta_o: R) -> (R, R) {
    let c = |k0: f64, k1: f64| roughness * R::from_f64(k0) + R::from_f64(k1);
    let (cx, cy, cz, cw) = (
        c(-1.0, 1.0),
        c(-0.0275, 0.0425),
        c(-0.572, 1.04),
        c(0.022, -0.04),
    );
    let a004 = (cx * cx).min((R::from_f64(-9.28) * cos_theta_o).exp2()) * cx + cy;
    let k = R::from_f64(1.04);
    (cz - k * a004, k * a004 + cw)
}

/// Lazarov's analytic environment BRDF (Call of Duty: Black Ops II), as `(A, B)` of
/// `F0·A + B`, in the gloss `g` (this crate compares it at `g = 1 − r`, `r` the perceptual
/// roughness, the mapping engines use):
///
/// ```text
/// t = g (1/0.96, 0.475, (0.0275 − 0.25·0.04)/0.96, 0.25) + (0, 0, (0.015 − 0.75·0.04)/0.96, 0.75)
/// a0 = t.x min(t.y, 2^(−9.28 μ)) + t.z,   a1 = t.w
/// F0·A + B = saturate(a0 + F0 (a1 − a0)):   (A, B) = (a1 − a0, a0)
/// ```
///
/// (the `saturate` of the combined value is left to the caller). Domain `g, μ ∈ [0, 1]`. A fit
/// for the normalized Blinn-Phong lobe of Black Ops II, not GGX: its error against [`dfg`] is
/// in `docs/tradeoffs.md`. Reference: D. Lazarov, "Getting More Physical in Call of Duty:
/// Black Ops II", SIGGRAPH 2013 course *Physically Based Shading in Theory and Practice*.
#[inline(always)]
#[must_use]
pub fn lazarov_env_brdf<R: Real>(gloss: R, cos_theta_o: R) -> (R, R) {
    let tx = gloss * R::from_f64(1.0 / 0.96);
    let ty = gloss * R::from_f64(0.475);
    let tz = gloss * R::from_f64((0.0275 - 0.25 * 0.04) / 0.96)
        + R::from_f64((0.015 - 0.75 * 0.04) / 0.96);
    let tw = gloss * R::from_f64(0.25) + R::from_f64(0.75);
    let a0 = tx * ty.min((R::from_f64(-9.28) * cos_theta_o).exp2()) + tz;
    (tw - a0, a0)
}

/// What the two channels of a DFG texel hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DfgLayout {
    /// `(A, B)`: the specular albedo is `F0·R + G` (Karis 2013).
    SplitSum,
    /// `(B, A + B)`: the specular albedo is `mix(R, G, F0) = (1 − F0) R + F0 G`, and the
    /// multiple-scattering compensation `1 + F0 (1/G − 1)` reads `E = G` directly
    /// (Filament's layout; Turquin 2019, Fdez-Agüera 2019).
    Multiscatter,
}

/// Smallest table size the generators accept.
pub const DFG_MIN_SIZE: usize = 16;
/// Largest table size the generators accept.
pub const DFG_MAX_SIZE: usize = 512;

/// The `(μ, α)` at the centre of texel `(i, j)` of an `n × n` table: `μ = (i + ½)/n`,
/// perceptual roughness `r = (j + ½)/n`, `α = max(r², 1e-4)` (the floor of [`dfg`]'s domain;
/// it changes only texels with `r < 0.01`, where the lobe is a mirror either way).
///
/// Domain `i, j < n` (not checked; any `n ≥ 1`).
#[must_use]
pub fn dfg_texel_centre(n: usize, i: usize, j: usize) -> (f64, f64) {
    let n = n as f64;
    let mu = (i as f64 + 0.5) / n;
    let r = (j as f64 + 0.5) / n;
    (mu, (r * r).max(1e-4))
}

/// The two channels of texel `(i, j)` of an `n × n` table in `layout`: [`dfg`] at
/// [`dfg_texel_centre`].
fn texel(n: usize, layout: DfgLayout, i: usize, j: usize) -> Result<[f64; 2], Error> {
    let (mu, alpha) = dfg_texel_centre(n, i, j);
    let t = dfg(mu, alpha)?;
    Ok(match layout {
        DfgLayout::SplitSum => [t.a, t.b],
        DfgLayout::Multiscatter => [t.b, t.a + t.b],
    })
}

fn check_n(n: usize) -> Result<(), Error> {
    crate::error::check_f64("n", n as f64, "[16, 512]", |v| {
        (DFG_MIN_SIZE as f64..=DFG_MAX_SIZE as f64).contains(&v)
    })
    .map(|_| ())
}

fn check_size(n: usize, len: usize) -> Result<(), Error> {
    check_n(n)?;
    let want = 2 * n * n;
    if len == want {
        Ok(())
    } else {
        Err(Error::OutOfDomain {
            param: "out.len()",
            value: len as f64,
            domain: "2 n² (two channels per texel)",
        })
    }
}

/// Fills `out` with the `n × n` DFG table in `layout`, as `f32`: texel `(i, j)` at
/// `out[2 (j n + i)]` and `out[2 (j n + i) + 1]` ([`dfg`] at [`dfg_texel_centre`], rounded
/// to nearest; axes in the [module docs](self)). `no_std`, no allocation.
///
/// Domain `n ∈ [16, 512]`, `out.len() = 2 n²`. Cost `n²` quadratures: about 0.7 ms per texel
/// in release on one core of an AMD EPYC (Zen 4) (11 s at `n = 128`, about 3 minutes at 512).
///
/// # Errors
/// [`Error::OutOfDomain`] naming `n` or `out.len()` (nothing is written then).
pub fn fill_dfg_f32(n: usize, layout: DfgLayout, out: &mut [f32]) -> Result<(), Error> {
    check_size(n, out.len())?;
    for j in 0..n {
        for i in 0..n {
            let [r, g] = texel(n, layout, i, j)?;
            let k = 2 * (j * n + i);
            out[k] = r as f32;
            out[k + 1] = g as f32;
        }
    }
    Ok(())
}

/// [`fill_dfg_f32`] with `f16` texels (DXGI `R16G16_FLOAT`): each value is the `f32` texel
/// rounded to the nearest `f16` (ties to even). Feature `half`: the `half` crate provides the
/// IEEE binary16 type engines upload, so the table is bit-compatible with their textures.
///
/// # Errors
/// As [`fill_dfg_f32`].
#[cfg(feature = "half")]
pub fn fill_dfg_f16(n: usize, layout: DfgLayout, out: &mut [half::f16]) -> Result<(), Error> {
    check_size(n, out.len())?;
    for j in 0..n {
        for i in 0..n {
            let [r, g] = texel(n, layout, i, j)?;
            let k = 2 * (j * n + i);
            out[k] = half::f16::from_f32(r as f32);
            out[k + 1] = half::f16::from_f32(g as f32);
        }
    }
    Ok(())
}

/// [`fill_dfg_f32`] into a new `Vec` of `2 n²` values (feature `alloc`).
///
/// # Errors
/// [`Error::OutOfDomain`] naming `n` outside `[16, 512]`.
#[cfg(feature = "alloc")]
pub fn dfg_table_f32(n: usize, layout: DfgLayout) -> Result<alloc::vec::Vec<f32>, Error> {
    check_n(n)?;
    let mut v = alloc::vec![0.0; 2 * n * n];
    fill_dfg_f32(n, layout, &mut v)?;
    Ok(v)
}

/// [`fill_dfg_f16`] into a new `Vec` of `2 n²` values (features `alloc` and `half`).
///
/// # Errors
/// [`Error::OutOfDomain`] naming `n` outside `[16, 512]`.
#[cfg(all(feature = "alloc", feature = "half"))]
pub fn dfg_table_f16(n: usize, layout: DfgLayout) -> Result<alloc::vec::Vec<half::f16>, Error> {
    check_n(n)?;
    let mut v = alloc::vec![half::f16::ZERO; 2 * n * n];
    fill_dfg_f16(n, layout, &mut v)?;
    Ok(v)
}
