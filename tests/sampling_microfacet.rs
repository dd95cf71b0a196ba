//! Importance sampling of the microfacet models: χ² goodness of fit of every normal-sampling
//! strategy (GGX: visible normals, spherical caps, bounded visible normals, full
//! distribution; Beckmann: visible normals, full distribution; Blinn-Phong and
//! Ashikhmin-Shirley: `D cos θm`) reflected through a Cook-Torrance model, the pdf's
//! integral, the closed-form weights against `f·cos θi / pdf`, the inverse error function,
//! finite results at the extremes, lanes against scalars, and the rejection rates of plain
//! and bounded VNDF sampling.
mod common;

use brdf::fresnel::Schlick;
use brdf::masking::{SmithHeightCorrelated, VCavity};
use brdf::models::CookTorrance;
use brdf::ndf::{AnyNdf, AshikhminShirleyLobe, Beckmann, BlinnPhong, Ggx, GgxIsotropic, erf};
use brdf::real::Splat;
use brdf::sampling::{
    BoundedVisibleNormals, FullDistribution, NormalSampler, SampleNdf, SphericalCaps,
    VisibleNormals, erf_inv,
};
use brdf::{Real, SampleBrdf, Vec3};
use common::chi2::{Chi2Config, Rng};
use proptest::prelude::*;

/// Number of χ² configurations in this file (the Šidák correction divides the 1 % level
/// among them). Keep it ≥ the count of `check_chi2` calls.
const TESTS: usize = 64;

fn wo_at(theta_deg: f64, phi_deg: f64) -> Vec3<f64> {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// [`common::chi2::check_sampler`] on `cfg`; the microfacet samplers return `eval` itself,
/// so `f` must equal it bit for bit. Returns the invalid fraction.
fn check_chi2_cfg<const N: usize, M: SampleBrdf<f64, N>>(
    name: &str,
    model: &M,
    wo: Vec3<f64>,
    cfg: &Chi2Config,
) -> f64 {
    common::chi2::check_sampler(name, model, wo, cfg, TESTS, 0.0)
}

/// The histogram for a lobe of width `alpha`: 16 × 32 cells, or 64 θ bins for narrow lobes
/// (so the peak spreads over several rows).
fn cfg_for(alpha: f64) -> Chi2Config {
    Chi2Config {
        theta_bins: if alpha < 0.1 { 64 } else { 16 },
        ..Chi2Config::DEFAULT
    }
}

fn check_chi2<const N: usize, M: SampleBrdf<f64, N>>(
    name: &str,
    model: &M,
    wo: Vec3<f64>,
    alpha: f64,
) -> f64 {
    check_chi2_cfg(name, model, wo, &cfg_for(alpha))
}

fn schlick() -> Schlick<f64, 1> {
    Schlick::new([0.04]).unwrap()
}

type Ct<D, G> = CookTorrance<f64, D, Schlick<f64, 1>, G>;

fn ggx_iso(alpha: f64) -> Ct<GgxIsotropic<f64>, SmithHeightCorrelated> {
    CookTorrance::new(
        GgxIsotropic::new(alpha).unwrap(),
        schlick(),
        SmithHeightCorrelated,
    )
}

fn ggx(ax: f64, ay: f64) -> Ct<Ggx<f64>, SmithHeightCorrelated> {
    CookTorrance::new(
        Ggx::anisotropic(ax, ay).unwrap(),
        schlick(),
        SmithHeightCorrelated,
    )
}

fn beckmann(alpha: f64) -> Ct<Beckmann<f64>, SmithHeightCorrelated> {
    CookTorrance::new(
        Beckmann::new(alpha).unwrap(),
        schlick(),
        SmithHeightCorrelated,
    )
}

// --- χ²: 10⁶ samples per configuration --------------------------------------------------------

#[test]
fn ggx_default_spherical_caps_chi2() {
    // α ∈ {0.05, 0.2, 0.5, 1} × θo ∈ {0°, 45°, 80°, 89°}, split so tests run in parallel.
    for (alpha, theta) in [
        (0.05, 0.0),
        (0.05, 45.0),
        (0.2, 80.0),
        (0.5, 89.0),
        (1.0, 0.0),
    ] {
        check_chi2("ggx caps", &ggx_iso(alpha), wo_at(theta, 0.0), alpha);
    }
}

#[test]
fn ggx_default_spherical_caps_chi2_grazing() {
    for (alpha, theta) in [
        (0.05, 89.0),
        (0.2, 0.0),
        (0.5, 45.0),
        (1.0, 80.0),
        (1.0, 89.0),
    ] {
        check_chi2("ggx caps", &ggx_iso(alpha), wo_at(theta, 0.0), alpha);
    }
}

#[test]
fn ggx_heitz_vndf_chi2() {
    for (alpha, theta) in [(0.05, 80.0), (0.2, 45.0), (0.5, 0.0), (1.0, 89.0)] {
        let m = ggx_iso(alpha).sampled_with::<VisibleNormals>();
        check_chi2("ggx vndf", &m, wo_at(theta, 0.0), alpha);
    }
}

#[test]
fn ggx_bounded_vndf_chi2() {
    for (alpha, theta) in [
        (0.05, 45.0),
        (0.2, 89.0),
        (0.5, 80.0),
        (1.0, 0.0),
        (1.0, 45.0),
    ] {
        let m = ggx_iso(alpha).sampled_with::<BoundedVisibleNormals>();
        check_chi2("ggx bounded", &m, wo_at(theta, 0.0), alpha);
    }
}

#[test]
fn ggx_full_distribution_chi2() {
    for (alpha, theta) in [(0.05, 0.0), (0.2, 80.0), (1.0, 45.0)] {
        let m = ggx_iso(alpha).sampled_with::<FullDistribution>();
        check_chi2("ggx full", &m, wo_at(theta, 0.0), alpha);
    }
}

#[test]
fn anisotropic_ggx_every_strategy_chi2() {
    let m = ggx(0.1, 0.5);
    let wo = wo_at(60.0, 30.0);
    check_chi2("aniso ggx caps", &m, wo, 0.1);
    check_chi2(
        "aniso ggx vndf",
        &m.sampled_with::<VisibleNormals>(),
        wo,
        0.1,
    );
    check_chi2(
        "aniso ggx bounded",
        &m.sampled_with::<BoundedVisibleNormals>(),
        wo_at(80.0, 120.0),
        0.1,
    );
    check_chi2(
        "aniso ggx full",
        &m.sampled_with::<FullDistribution>(),
        wo,
        0.1,
    );
}

#[test]
fn beckmann_vndf_chi2() {
    for (alpha, theta) in [(0.05, 45.0), (0.2, 0.0), (0.5, 89.0), (1.0, 80.0)] {
        check_chi2("beckmann vndf", &beckmann(alpha), wo_at(theta, 0.0), alpha);
    }
}

#[test]
fn beckmann_vndf_chi2_more() {
    for (alpha, theta) in [(0.05, 89.0), (0.2, 80.0), (0.5, 0.0), (1.0, 45.0)] {
        check_chi2("beckmann vndf", &beckmann(alpha), wo_at(theta, 0.0), alpha);
    }
    let aniso = CookTorrance::new(
        Beckmann::anisotropic(0.1, 0.5).unwrap(),
        schlick(),
        SmithHeightCorrelated,
    );
    check_chi2("aniso beckmann vndf", &aniso, wo_at(70.0, 45.0), 0.1);
}

#[test]
fn beckmann_full_distribution_chi2() {
    for (alpha, theta) in [(0.05, 0.0), (0.5, 80.0)] {
        let m = beckmann(alpha).sampled_with::<FullDistribution>();
        check_chi2("beckmann full", &m, wo_at(theta, 0.0), alpha);
    }
}

#[test]
fn blinn_phong_and_ashikhmin_shirley_ndfs_chi2() {
    for (s, theta) in [(10.0, 0.0), (100.0, 60.0), (1.0, 85.0)] {
        let m = CookTorrance::new(BlinnPhong::new(s).unwrap(), schlick(), VCavity);
        check_chi2("blinn-phong", &m, wo_at(theta, 0.0), 1.0);
    }
    for (nu, nv, theta, phi) in [
        (10.0, 1000.0, 30.0, 20.0),
        (100.0, 10.0, 75.0, 200.0),
        (0.0, 5.0, 0.0, 0.0),
    ] {
        let m = CookTorrance::new(
            AshikhminShirleyLobe::new(nu, nv).unwrap(),
            schlick(),
            VCavity,
        );
        check_chi2(
            "ashikhmin-shirley",
            &m,
            wo_at(theta, phi),
            if nu.max(nv) > 500.0 { 0.05 } else { 1.0 },
        );
    }
}

#[test]
fn any_ndf_samples_like_the_wrapped_distribution() {
    let wo = wo_at(50.0, 10.0);
    let any = CookTorrance::new(
        AnyNdf::from(Beckmann::new(0.3).unwrap()),
        schlick(),
        SmithHeightCorrelated,
    );
    check_chi2("any beckmann", &any, wo, 0.3);
    let ggx_any = AnyNdf::from(GgxIsotropic::new(0.3).unwrap());
    let ggx_direct = GgxIsotropic::new(0.3).unwrap();
    let mut rng = Rng::new(3);
    for _ in 0..1000 {
        let u = [rng.uniform(), rng.uniform()];
        let (a, b) = (ggx_any.sample_wm(wo, u), ggx_direct.sample_wm(wo, u));
        assert_eq!([a.x, a.y, a.z], [b.x, b.y, b.z]);
        assert_eq!(ggx_any.pdf_wm(wo, a), ggx_direct.pdf_wm(wo, b));
    }
}

// --- The weights ---------------------------------------------------------------------------

#[test]
fn vndf_weight_is_fresnel_times_g2_over_g1() {
    // F = 1 isolates G2/G1(wo); at normal incidence and α → small it tends to 1.
    use brdf::masking::Masking;
    use brdf::ndf::SmithLambda;
    let ndf = GgxIsotropic::new(0.4).unwrap();
    let m = CookTorrance::new(ndf, Schlick::new([1.0]).unwrap(), SmithHeightCorrelated);
    let mut rng = Rng::new(11);
    for _ in 0..1000 {
        let wo = common::hemisphere(rng.uniform().max(1e-3), rng.uniform());
        let s = m.sample(wo, rng.u3());
        if !s.valid {
            continue;
        }
        let wm = (s.wi + wo).normalize_or_zero();
        let g = SmithHeightCorrelated.g2(&ndf, s.wi, wo, wm) / ndf.g1(wo);
        assert!(
            (s.weight[0] - g).abs() <= 1e-12 * g.max(1e-300),
            "{} vs {g}",
            s.weight[0]
        );
        assert!(s.weight[0] <= 1.0 + 1e-12);
    }
}

// --- Inverse error function ----------------------------------------------------------------

#[test]
fn erf_inv_inverts_erf() {
    // Reference values (Abramowitz & Stegun 26.2 / high-precision tables).
    for (y, x) in [
        (0.5, 0.476_936_276_204_469_9),
        (0.9, 1.163_087_153_676_674_3),
        (0.999, 2.326_753_765_513_524_6),
        (-0.25, -0.225_312_055_012_178_1),
    ] {
        let got = erf_inv(y);
        assert!(
            (got - x).abs() <= 2e-7 * x.abs(),
            "erf_inv({y}) = {got}, want {x}"
        );
    }
    // Round trip on a grid, in the tails relative to 1 − |y|.
    let mut worst: f64 = 0.0;
    for i in 1..20_000 {
        let y = -1.0 + 2.0 * i as f64 / 20_000.0;
        let r = erf(erf_inv(y));
        let scale = (1.0 - y.abs()).min(y.abs()).max(1e-300);
        worst = worst.max((r - y).abs() / scale);
    }
    for t in [1e-3, 1e-6, 1e-9, 1e-12] {
        let y = 1.0 - t;
        let t = 1.0 - y; // exactly the represented tail
        let x = erf_inv(y);
        let back = brdf::ndf::erfc(x);
        worst = worst.max((back - t).abs() / t);
        assert_eq!(erf_inv(-y), -x);
    }
    assert!(worst < 1e-6, "worst relative round-trip error {worst:e}");
    // f32 agrees with f64 to f32 accuracy where the f32 argument is exact.
    for y in [0.0_f32, 0.125, 0.5, 0.75, 0.96875] {
        let (a, b) = (erf_inv(y) as f64, erf_inv(y as f64));
        assert!((a - b).abs() <= 4e-7 * b.abs().max(1e-3), "{y}: {a} vs {b}");
    }
    assert!(erf_inv(1.0_f64).is_finite() && erf_inv(-1.0_f32).is_finite());
}

/// `erfc(x)` to about 1e-15 relative in f64, independently of the crate's: Taylor series of
/// `erf` for `|x| < 2.5`, Laplace's continued fraction (evaluated backwards, 200 terms)
/// above, and `2 − erfc(−x)` below.
fn erfc_reference(x: f64) -> f64 {
    if x < -2.5 {
        return 2.0 - erfc_reference(-x);
    }
    if x < 2.5 {
        // erf(x) = (2/√π) Σ (−1)ⁿ x^(2n+1) / (n! (2n+1))
        let (mut term, mut sum, mut n) = (x, x, 0.0);
        while term.abs() > 1e-18 * sum.abs().max(1e-300) {
            n += 1.0;
            term *= -x * x / n;
            sum += term / (2.0 * n + 1.0);
        }
        return 1.0 - core::f64::consts::FRAC_2_SQRT_PI * sum;
    }
    // erfc(x) = e^(−x²)/√π · 1/(x + (1/2)/(x + 1/(x + (3/2)/(x + …))))
    let mut k = x;
    for n in (1..=200).rev() {
        k = x + (n as f64 / 2.0) / k;
    }
    (-x * x).exp() / core::f64::consts::PI.sqrt() / k
}

/// The slope `x` that Beckmann's visible-normal sampler draws for `α = 1`,
/// `wo = (sin θ, 0, cos θ)` and `u = (u0, 1/2)` (`wm ∝ (−x, 0, 1)`), on `R`.
fn beckmann_slope<R: Real>(theta: f64, u0: f64) -> f64
where
    R::Scalar: Into<f64>,
{
    let (sin, cos) = theta.sin_cos();
    let wo = Vec3::new(R::from_f64(sin), R::from_f64(0.0), R::from_f64(cos));
    let ndf = Beckmann::<R>::from_lanes(R::one(), R::one()).unwrap();
    let u = [R::from_f64(u0), R::from_f64(0.5)];
    let wm = <VisibleNormals as NormalSampler<R, Beckmann<R>>>::sample_wm(&ndf, wo, u);
    let (x, y, z): (f64, f64, f64) = (
        wm.x.lane(0).into(),
        wm.y.lane(0).into(),
        wm.z.lane(0).into(),
    );
    assert!(
        y.abs() < 1e-12 && z > 0.0,
        "θ = {theta}, u0 = {u0}: wm = ({x}, {y}, {z})"
    );
    -x / z
}

/// Beckmann's visible-normal inversion hits its CDF: for `α = 1` and `wo = (sin θ, 0, cos θ)`
/// the drawn slope `x` (from `VisibleNormals::sample_wm`, every `u0`, the rim's included)
/// has `C(x)` equal to `u₀ C(x_max)`, where
/// `C(x) = cos θ (√π/2) erfc(−x) + sin θ e^(−x²)/2` (Heitz & d'Eon 2014) and `erfc` is an
/// independent reference: within `tol` of `C(x_max)`, and within 1e-4 of `u₀ C(x_max)`
/// relative in the lower tail (`u₀ ≤ 1e-3`, the refined inverse's branch below 1e-7), over
/// θ ∈ [0°, 90°) and `u₀` from 0 to 1 − 2⁻⁵³ (the sampler solves for `c = erfc(−x)` by three
/// bracketed Newton steps from Jakob's initial guess). `x` stays in `[−6, x_max]`. Returns
/// the worst absolute error.
fn check_beckmann_slope<R: Real>(tol: f64) -> f64
where
    R::Scalar: Into<f64>,
{
    let sqrt_pi = core::f64::consts::PI.sqrt();
    let mut worst = (0.0f64, 0.0, 0.0);
    let mut thetas: Vec<f64> = (0..90).map(|i| (i as f64).to_radians()).collect();
    thetas.extend([89.9_f64.to_radians(), core::f64::consts::FRAC_PI_2 - 1e-6]);
    let mut us: Vec<f64> = (0..200).map(|j| (j as f64 + 0.5) / 200.0).collect();
    us.extend([0.0, 1e-16, 1e-12, 1e-9, 6e-8, 1e-6, 1e-4, 1e-3]);
    us.extend([1e-3, 1e-6, 1e-9, 1e-12, 2f64.powi(-24), 2f64.powi(-53)].map(|t| 1.0 - t));
    for &theta in &thetas {
        // The angle and u as `R` holds them, so the reference solves the same problem.
        let theta_r: f64 = R::from_f64(theta).lane(0).into();
        let (sin, cos) = theta_r.sin_cos();
        let x_max = (cos / sin.max(1e-300)).min(6.0);
        let cdf = |x: f64| cos * sqrt_pi / 2.0 * erfc_reference(-x) + sin * (-x * x).exp() / 2.0;
        let total = cdf(x_max);
        for &u0 in &us {
            let u0: f64 = R::from_f64(u0).lane(0).into();
            let x = beckmann_slope::<R>(theta_r, u0);
            // (1e-6: the slope read back from the f32 normal.)
            let range = -6.0 * (1.0 + 1e-6)..=x_max * (1.0 + 1e-6) + 1e-6;
            assert!(range.contains(&x), "θ = {theta}, u0 = {u0}: x = {x}");
            let e = (cdf(x) - u0 * total).abs() / total;
            if e > worst.0 {
                worst = (e, theta.to_degrees(), u0);
            }
            // (Below x = −6 the sampler clamps: a mass under 1e-17.)
            if u0 > 0.0 && u0 <= 1e-3 && x > -5.999 {
                let rel = (cdf(x) - u0 * total).abs() / (u0 * total);
                assert!(
                    rel < 1e-4,
                    "θ = {theta}, u0 = {u0}: x = {x}, relative {rel:e}"
                );
            }
        }
    }
    eprintln!(
        "{}: worst |C(x) − u C(x_max)| / C(x_max) = {:.2e} at θ = {:.2}°, u0 = {}",
        core::any::type_name::<R>(),
        worst.0,
        worst.1,
        worst.2
    );
    assert!(worst.0 < tol, "{worst:?}");
    worst.0
}

#[test]
fn beckmann_visible_slope_inverts_its_cdf() {
    check_beckmann_slope::<f64>(1e-7);
    check_beckmann_slope::<f32>(1e-6);
}

/// `erf_inv` beyond Giles' fitted range (`1 − |y| < 1e-7`, reachable in f64) and at `±1`:
/// `erfc(erf_inv(y)) = 1 − y` within 1e-6 relative down to `1 + y = 2⁻⁵³`, and `erf_inv(±1)`
/// is `±erfc⁻¹(1e-30)` (the floor).
#[test]
fn erf_inv_deep_tails() {
    // 1 + y down to 2⁻⁵³, the smallest an f64 `y` represents (the sampler reaches smaller
    // ones through `erfc(−x)` itself, `beckmann_visible_slope_inverts_its_cdf`).
    for t in [1e-8, 1e-10, 1e-13, 1e-15, 2f64.powi(-53)] {
        let y = -1.0 + t;
        let t = 1.0 + y; // exactly the represented tail
        let x = erf_inv(y);
        let back = erfc_reference(-x);
        assert!(
            (back - t).abs() <= 1e-6 * t,
            "1 + y = {t:e}: erf_inv = {x}, erfc(−x) = {back:e}"
        );
    }
    // f32 at its last representable tails (Giles' range ends there: the asymptote starts).
    for t in [1e-6_f32, 1e-7, f32::EPSILON / 2.0] {
        for y in [1.0 - t, -1.0 + t] {
            let t = f64::from(1.0 - y.abs());
            let x = f64::from(erf_inv(y));
            let back = erfc_reference(x.abs());
            assert!(
                (back - t).abs() <= 2e-5 * t,
                "f32 {y}: erf_inv = {x}, erfc = {back:e}"
            );
        }
    }
    for y in [1.0_f64, -1.0] {
        let x = erf_inv(y);
        let back = erfc_reference(x.abs());
        assert!(
            (back - 1e-30).abs() <= 1e-6 * 1e-30,
            "erf_inv({y}) = {x}: erfc = {back:e}"
        );
        assert_eq!(x.signum(), y);
    }
}

// --- Rejection rates -----------------------------------------------------------------------

fn invalid_fraction<M: SampleBrdf<f64, 1>>(m: &M, wo: Vec3<f64>, n: usize) -> f64 {
    let mut rng = Rng::new(5);
    (0..n).filter(|_| !m.sample(wo, rng.u3()).valid).count() as f64 / n as f64
}

#[test]
fn bounded_vndf_rejects_fewer_samples() {
    let n = 200_000;
    let sigma = |p: f64| (p * (1.0 - p) / n as f64).sqrt();
    // α = 1, normal incidence: the plain VNDF reflects below the horizon exactly when
    // θm > 45°, i.e. for the lower half of the stretched sphere: probability 1/2.
    // The bounded cap is the upper half: no sample is lost.
    let wo = wo_at(0.0, 0.0);
    let m = ggx_iso(1.0);
    let plain = invalid_fraction(&m.sampled_with::<VisibleNormals>(), wo, n);
    let caps = invalid_fraction(&m, wo, n);
    let bounded = invalid_fraction(&m.sampled_with::<BoundedVisibleNormals>(), wo, n);
    println!("α = 1, θo = 0: plain {plain}, caps {caps}, bounded {bounded}");
    assert!((plain - 0.5).abs() < 5.0 * sigma(0.5), "plain {plain}");
    assert!((caps - 0.5).abs() < 5.0 * sigma(0.5), "caps {caps}");
    assert!(bounded < 1e-4, "bounded {bounded}");
    // Elsewhere bounded never rejects more than plain (the same cap, cut).
    for (alpha, theta) in [
        (0.2, 80.0),
        (0.5, 45.0),
        (0.5, 80.0),
        (1.0, 60.0),
        (1.0, 89.0),
    ] {
        let m = ggx_iso(alpha);
        let wo = wo_at(theta, 0.0);
        let plain = invalid_fraction(&m.sampled_with::<VisibleNormals>(), wo, n);
        let bounded = invalid_fraction(&m.sampled_with::<BoundedVisibleNormals>(), wo, n);
        println!("α = {alpha}, θo = {theta}: plain {plain}, bounded {bounded}");
        assert!(
            bounded < plain,
            "α = {alpha}, θo = {theta}: {bounded} ≥ {plain}"
        );
    }
}

// --- Extremes ------------------------------------------------------------------------------

fn assert_finite_sample<R: Real, const N: usize, M: SampleBrdf<R, N>>(
    name: &str,
    m: &M,
    wo: Vec3<R>,
    u: [R; 3],
) {
    let s = m.sample(wo, u);
    let fin = |x: R| R::all(x.is_finite());
    assert!(
        fin(s.wi.x)
            && fin(s.wi.y)
            && fin(s.wi.z)
            && fin(s.pdf)
            && s.weight.iter().all(|w| fin(*w))
            && s.f.iter().all(|w| fin(*w)),
        "{name}: {s:?} at wo = {wo:?}, u = {u:?}"
    );
    let p = m.pdf(wo, s.wi);
    assert!(fin(p) && R::all(p.ge(R::zero())), "{name}: pdf {p:?}");
}

fn extremes_on<R: brdf::Scalar>() {
    let one_minus =
        R::one() - R::from_f64(f64::EPSILON).max(R::from_f64(f32::EPSILON as f64 / 2.0));
    let us = [R::zero(), R::from_f64(0.5), one_minus];
    let c = R::from_f64(1e-7);
    let s = (R::one() - c * c).sqrt();
    let wos = [
        Vec3::new(R::zero(), R::zero(), R::one()),
        Vec3::new(s, R::zero(), c),
        Vec3::new(s * R::from_f64(0.6), s * R::from_f64(0.8), c),
        Vec3::new(R::from_f64(0.6), R::zero(), R::from_f64(0.8)),
    ];
    let fr = Schlick::new([R::from_f64(0.04)]).unwrap();
    for alpha in [brdf::ndf::MIN_ALPHA, 0.01, 1.0] {
        let a = R::from_f64(alpha);
        let gi = CookTorrance::new(GgxIsotropic::new(a).unwrap(), fr, SmithHeightCorrelated);
        let ga = CookTorrance::new(
            Ggx::anisotropic(a, R::one()).unwrap(),
            fr,
            SmithHeightCorrelated,
        );
        let b = CookTorrance::new(Beckmann::new(a).unwrap(), fr, SmithHeightCorrelated);
        let ba = CookTorrance::new(
            Beckmann::anisotropic(R::one(), a).unwrap(),
            fr,
            SmithHeightCorrelated,
        );
        for wo in wos {
            for u0 in us {
                for u1 in us {
                    let u = [u0, u1, R::zero()];
                    assert_finite_sample("ggx caps", &gi, wo, u);
                    assert_finite_sample("ggx vndf", &gi.sampled_with::<VisibleNormals>(), wo, u);
                    assert_finite_sample(
                        "ggx bounded",
                        &gi.sampled_with::<BoundedVisibleNormals>(),
                        wo,
                        u,
                    );
                    assert_finite_sample("ggx full", &gi.sampled_with::<FullDistribution>(), wo, u);
                    assert_finite_sample("aniso ggx caps", &ga, wo, u);
                    assert_finite_sample(
                        "aniso ggx bounded",
                        &ga.sampled_with::<BoundedVisibleNormals>(),
                        wo,
                        u,
                    );
                    assert_finite_sample(
                        "aniso ggx vndf",
                        &ga.sampled_with::<VisibleNormals>(),
                        wo,
                        u,
                    );
                    assert_finite_sample("beckmann vndf", &b, wo, u);
                    assert_finite_sample("aniso beckmann vndf", &ba, wo, u);
                    assert_finite_sample(
                        "beckmann full",
                        &b.sampled_with::<FullDistribution>(),
                        wo,
                        u,
                    );
                }
            }
        }
    }
    for sh in [0.0, 1.0, brdf::ndf::MAX_SHININESS] {
        let sh = R::from_f64(sh);
        let bp = CookTorrance::new(BlinnPhong::new(sh).unwrap(), fr, VCavity);
        let as1 = CookTorrance::new(
            AshikhminShirleyLobe::new(sh, R::zero()).unwrap(),
            fr,
            VCavity,
        );
        let as2 = CookTorrance::new(
            AshikhminShirleyLobe::new(R::from_f64(3.0), sh).unwrap(),
            fr,
            VCavity,
        );
        for wo in wos {
            for u0 in us {
                for u1 in us {
                    let u = [u0, u1, R::zero()];
                    assert_finite_sample("blinn-phong", &bp, wo, u);
                    assert_finite_sample("ashikhmin-shirley", &as1, wo, u);
                    assert_finite_sample("ashikhmin-shirley", &as2, wo, u);
                }
            }
        }
    }
}

#[test]
fn samples_are_finite_at_the_extremes() {
    extremes_on::<f32>();
    extremes_on::<f64>();
}

// --- Lanes against scalars -----------------------------------------------------------------

/// One output of a strategy on lanes: `which` 0..3 = wm.x, wm.y, wm.z, 3 = pdf_wm.
fn strategy_out<R: Real, D: brdf::ndf::Ndf<R>, St: NormalSampler<R, D>>(
    ndf: &D,
    wo: Vec3<R>,
    u: [R; 2],
    which: usize,
) -> R {
    let wm = St::sample_wm(ndf, wo, u);
    [wm.x, wm.y, wm.z, St::pdf_wm(ndf, wo, wm)][which]
}

/// `which` selects the output, `kind` the NDF × strategy.
fn lane_body<R: Real>(ox: R, oz: R, u0: R, u1: R, a: R, kind: usize, which: usize) -> R {
    let wo = Vec3::new(ox, ox * R::from_f64(0.5), oz).normalize_or_zero();
    let u = [u0, u1];
    let b = R::from_f64(0.5) + a;
    match kind {
        0 => strategy_out::<R, _, SphericalCaps>(
            &Ggx::from_lanes(a, b.min(R::one())).unwrap(),
            wo,
            u,
            which,
        ),
        1 => strategy_out::<R, _, VisibleNormals>(
            &Ggx::from_lanes(a, b.min(R::one())).unwrap(),
            wo,
            u,
            which,
        ),
        2 => strategy_out::<R, _, BoundedVisibleNormals>(
            &Ggx::from_lanes(a, b.min(R::one())).unwrap(),
            wo,
            u,
            which,
        ),
        3 => strategy_out::<R, _, FullDistribution>(
            &Ggx::from_lanes(a, b.min(R::one())).unwrap(),
            wo,
            u,
            which,
        ),
        4 => {
            strategy_out::<R, _, VisibleNormals>(&Beckmann::from_lanes(a, a).unwrap(), wo, u, which)
        }
        5 => strategy_out::<R, _, FullDistribution>(
            &Beckmann::from_lanes(a, a).unwrap(),
            wo,
            u,
            which,
        ),
        6 => strategy_out::<R, _, FullDistribution>(
            &BlinnPhong::from_lanes(R::from_f64(2.0) / (a * a)).unwrap(),
            wo,
            u,
            which,
        ),
        _ => strategy_out::<R, _, FullDistribution>(
            &AshikhminShirleyLobe::from_lanes(R::from_f64(1.0) / a, R::from_f64(10.0)).unwrap(),
            wo,
            u,
            which,
        ),
    }
}

#[test]
fn lanes_agree_with_the_scalar() {
    let mut rng = Rng::new(42);
    let rows: Vec<[f64; 5]> = (0..64)
        .map(|_| {
            let t = rng.uniform() * 1.5;
            [
                t.sin(),
                t.cos(),
                rng.uniform(),
                rng.uniform(),
                0.05 + 0.9 * rng.uniform(),
            ]
        })
        .collect();
    let mut report = Vec::new();
    for kind in 0..8 {
        for which in 0..4 {
            let rows: Vec<[f64; 7]> = rows
                .iter()
                .map(|r| [r[0], r[1], r[2], r[3], r[4], kind as f64, which as f64])
                .collect();
            let worst = common::assert_lanes_match!("strategy", ulp = 32, abs = 1e-7, &rows,
            fn(ox, oz, u0, u1, a, kind, which) {
                lane_body(ox, oz, u0, u1, a, kind.lane(0).into() as usize, which.lane(0).into() as usize)
            });
            report.push((kind, which, worst));
        }
    }
    println!("worst ULP distance per (strategy, output): {report:?}");
}

// ------------------------------------------------------------------------------------------
// Property test: whole-model samples on every lane type agree with the scalar
// ------------------------------------------------------------------------------------------

/// A whole model's sample at `(wo, u)`, and its `pdf(wo, probe)`, for the model `kind`:
/// 0 GGX isotropic (default, spherical caps), 1 anisotropic GGX by bounded visible normals,
/// 2 Beckmann (visible normals), 3 GGX by `D cos θm`, 4 the mixture Lambert + GGX.
fn model_run<R: Real>(
    kind: usize,
    a: R,
    wo: Vec3<R>,
    u: [R; 3],
    probe: Vec3<R>,
) -> (brdf::Sample<R, 1>, R) {
    // `probe` exercises `pdf` on lanes (its value is not compared: see
    // `lanes_sample_as_scalar`).
    let schlick = Schlick::<f64, 1>::new([0.04]).unwrap().splat::<R>();
    let iso = CookTorrance::new(
        GgxIsotropic::from_lanes(a).unwrap(),
        schlick,
        SmithHeightCorrelated,
    );
    macro_rules! run {
        ($m:expr) => {{
            let m = $m;
            (m.sample(wo, u), m.pdf(wo, probe))
        }};
    }
    match kind {
        0 => run!(iso),
        1 => run!(
            CookTorrance::new(
                Ggx::from_lanes(a, (a * R::from_f64(3.0)).min(R::one())).unwrap(),
                schlick,
                SmithHeightCorrelated,
            )
            .sampled_with::<BoundedVisibleNormals>()
        ),
        2 => run!(CookTorrance::new(
            Beckmann::from_lanes(a, a).unwrap(),
            schlick,
            SmithHeightCorrelated,
        )),
        3 => run!(iso.sampled_with::<FullDistribution>()),
        _ => run!(brdf::models::Sum::new(
            brdf::models::Lambert::<f64, 1>::new([0.5])
                .unwrap()
                .splat::<R>(),
            iso
        )),
    }
}

/// Rows `[wo.x, wo.y, wo.z, u0, u1, u2, α]` sampled on the lane type `V` against its scalar,
/// lane by lane: the same validity, `wi` within 4e-6, the weight within 1e-4 relative (`D cos θm`
/// at α = 1e-4 and cos θo = 3e-8, a weight of 228: 2e-5 seen), the density
/// within 256 ULP or 1e-6 of the lobe's peak density `~1/(4π α²)` (it passes through `D`, whose exponent multiplies the few-ULP differences
/// of `wm` far in a sharp lobe's tail: 0.2 % seen for Beckmann at α = 1e-4, `u0 = 1 − 2⁻²⁴`,
/// at a density 10⁻⁷ of the peak).
/// Samples within 1e-5 of the horizon are skipped: whether `wi.z` rounds to the valid side
/// there may differ by one ULP between lane types.
fn lanes_sample_as_scalar<V: Real>(rows: &[[f64; 7]], kind: usize)
where
    V::Scalar: Real<Scalar = V::Scalar>,
{
    for chunk in rows.chunks(V::LANES) {
        let [ox, oy, oz, u0, u1, u2, a] = common::pack::<V, 7>(chunk);
        let wo = Vec3::new(ox, oy, oz);
        let (s, _) = model_run::<V>(kind, a, wo, [u0, u1, u2], wo);
        for (l, row) in chunk.iter().enumerate() {
            let [ox, oy, oz, u0, u1, u2, a] = row.map(<V::Scalar as brdf::Scalar>::of);
            let wo1 = Vec3::new(ox, oy, oz);
            let wi = Vec3::new(s.wi.x.lane(l), s.wi.y.lane(l), s.wi.z.lane(l));
            let (r, _) = model_run::<V::Scalar>(kind, a, wo1, [u0, u1, u2], wi);
            let valid = V::select(s.valid, V::one(), V::zero()).lane(l) == V::Scalar::one();
            let near = |z: V::Scalar| Into::<f64>::into(z) < 1e-5;
            let what = format!("{}, kind {kind}, row {row:?}", core::any::type_name::<V>());
            assert!(
                s.pdf.lane(l).is_finite() && s.weight[0].lane(l).is_finite(),
                "{what}: not finite"
            );
            if near(wi.z) || near(r.wi.z) {
                // A valid sample far above the horizon on one side only is a real mismatch.
                let far = |v: bool, z: V::Scalar| v && Into::<f64>::into(z) > 1e-3;
                assert!(
                    !far(valid, wi.z) && !far(r.valid, r.wi.z),
                    "{what}: validity"
                );
                continue;
            }
            assert_eq!(valid, r.valid, "{what}: validity");
            // The lobe's peak density is of order 1/(4π α²).
            let peak = 1.0 + 1.0 / (4.0 * core::f64::consts::PI * row[6] * row[6]);
            // Samples of negligible density (below 1e-6 of the peak) are ill-conditioned in
            // f32 and carry no weight in an estimate: at the rim of the visible cap, the
            // stretched normal `h = c + v` nearly vanishes (`c ≈ −v`), and its rounding,
            // stretched by 1/α, moves `wi` by 1e-3 (seen at α = 1e-4, cos θo = 2.4e-3, where
            // f32 and f64 also differ so); Beckmann's erfc⁻¹ tail as u0 → 1 likewise.
            if !valid || Into::<f64>::into(r.pdf) < 1e-6 * peak {
                continue;
            }
            // Components of a unit vector: 4e-6 absolute (32 ULP of 1; a grazing `wo` at
            // cos θo = 1e-7 reflects with 1.2e-6 seen), plus what the precision of the lane's
            // scalar makes unavoidable: 64 ε times the sampler's sensitivity to `u`,
            // `|∂wi/∂u0| + |∂wi/∂u1|` (central differences in f64). It matters only where
            // the warp is steep: Beckmann's visible normals as u0 → 1 (∂wi/∂u0 ≈ 2e3 at
            // u0 = 1 − 1e-4, α = 0.063, where the lanes differ by 9.3e-6 in f32).
            let eps: f64 = <V::Scalar as brdf::Scalar>::EPSILON.into();
            let (d_wi, d_weight, d_pdf) = sensitivity(kind, row);
            let tol = 4e-6 + 64.0 * eps * d_wi;
            for (x, y) in [(wi.x, r.wi.x), (wi.y, r.wi.y), (wi.z, r.wi.z)] {
                let d = (Into::<f64>::into(x) - Into::<f64>::into(y)).abs();
                assert!(
                    d <= tol,
                    "{what}: wi {wi:?} vs {:?} (tolerance {tol:e})",
                    r.wi
                );
            }
            let (p, q) = (s.pdf.lane(l), r.pdf);
            // The lobe's peak density is of order 1/(4π α²): 1e-6 of it (and at least 1e-6).
            let mut peak_tol = 1e-6 * (1.0 + 1.0 / (4.0 * core::f64::consts::PI * row[6] * row[6]));
            if kind == 2 {
                // Beckmann in f32 (see the proptest): 1e-3 relative, measured 4e-4 at
                // α = 1.2e-4, u0 = 1 − 1e-4.
                peak_tol = peak_tol.max(1e-3 * Into::<f64>::into(q));
            }
            // Plus 64 ε |∂pdf/∂u|, as for `wi`: the lanes' `wi` differs from the scalar's by
            // ULPs of the warp, and a sharp lobe's density changes by `pdf/α` per unit of
            // `wi` (seen: the mixture at α = 0.027, cos θo = 0.063, a cosine-drawn `wi` on
            // the GGX lobe's flank, 94.3376 vs 94.3403, 351 ULP).
            peak_tol += 64.0 * eps * d_pdf;
            // Plus 8 ε |∇pdf(wi)|₁: the density of a sharp lobe is ill-conditioned in the
            // direction itself (relative condition ~1/α on a lobe's flank), so the rounding
            // of `wi` and of the half vector rebuilt from it moves it whatever the lane type
            // (seen: the mixture's GGX lobe at α = 1e-4, 1.4 % of its peak, f64 116563.1,
            // f32 116596.1, f32x4 116544.9, with `wi` equal to 1 ULP).
            let wi64 = Vec3::new(r.wi.x.into(), r.wi.y.into(), r.wi.z.into());
            peak_tol += 8.0 * eps * pdf_gradient(kind, row, wi64);
            assert!(
                common::ulps(p, q) <= 256
                    || (Into::<f64>::into(p) - Into::<f64>::into(q)).abs() <= peak_tol,
                "{what}: pdf {p:?} vs {q:?} ({} ULP)",
                common::ulps(p, q)
            );
            let (w, v) = (
                Into::<f64>::into(s.weight[0].lane(l)),
                Into::<f64>::into(r.weight[0]),
            );
            // 1e-4 relative, plus 64 ε |∂weight/∂u| as for `wi`.
            let w_tol = 1e-4 * v.abs().max(1e-2) + 64.0 * eps * d_weight;
            assert!(
                (w - v).abs() <= w_tol,
                "{what}: weight {w:?} vs {v:?} (tolerance {w_tol:e})"
            );
        }
    }
}

/// `|∂wi/∂u0| + |∂wi/∂u1|` (largest component), `|∂weight/∂u0| + |∂weight/∂u1|` and
/// `|∂pdf/∂u0| + |∂pdf/∂u1|` of the `f64` sampler at `row`, by central differences of step
/// 1e-7 (one-sided at the ends of `[0, 1)`).
fn sensitivity(kind: usize, row: &[f64; 7]) -> (f64, f64, f64) {
    let wo = Vec3::new(row[0], row[1], row[2]);
    let at = |u: [f64; 3]| model_run::<f64>(kind, row[6], wo, u, wo).0;
    let (mut total, mut weight, mut pdf) = (0.0, 0.0, 0.0);
    for axis in 0..2 {
        let h = 1e-7;
        let (lo, hi) = (
            (row[3 + axis] - h).max(0.0),
            (row[3 + axis] + h).min(1.0 - 1e-12),
        );
        let mut u = [row[3], row[4], row[5]];
        u[axis] = lo;
        let a = at(u);
        u[axis] = hi;
        let b = at(u);
        let d = [b.wi.x - a.wi.x, b.wi.y - a.wi.y, b.wi.z - a.wi.z]
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        total += d / (hi - lo);
        weight += (b.weight[0] - a.weight[0]).abs() / (hi - lo);
        pdf += (b.pdf - a.pdf).abs() / (hi - lo);
    }
    (total, weight, pdf)
}

/// `|∂pdf/∂wi_x| + |∂pdf/∂wi_y| + |∂pdf/∂wi_z|` of the `f64` model at `row` and `wi`, by
/// central differences of step 1e-9 on the unit sphere (each perturbed `wi` renormalized).
fn pdf_gradient(kind: usize, row: &[f64; 7], wi: Vec3<f64>) -> f64 {
    let wo = Vec3::new(row[0], row[1], row[2]);
    let u = [row[3], row[4], row[5]];
    let pdf = |w: Vec3<f64>| model_run::<f64>(kind, row[6], wo, u, w.normalize_or_zero()).1;
    let h = 1e-9;
    [
        Vec3::new(h, 0.0, 0.0),
        Vec3::new(0.0, h, 0.0),
        Vec3::new(0.0, 0.0, h),
    ]
    .iter()
    .map(|&d| (pdf(wi + d) - pdf(wi - d)).abs() / (2.0 * h))
    .sum()
}

/// `α` log-uniform over the whole domain `[1e-4, 1]`, end points included.
fn alpha() -> impl Strategy<Value = f64> {
    common::unit().prop_map(|t| 1e-4f64.powf(1.0 - t))
}

/// `u ∈ [0, 1)`: the common unit strategy (which draws 0 and values a hair below 1 often),
/// with 1 itself mapped to the largest f32 below 1.
fn uniform() -> impl Strategy<Value = f64> {
    common::unit().prop_map(|t| t.min(1.0 - f64::from(f32::EPSILON) / 2.0))
}

proptest! {
    #![proptest_config(common::config(256))]

    /// Every lane type (f32x4, f32x8, f32x16, f64x4) samples as its scalar does, lane by lane
    /// (see `lanes_sample_as_scalar`), for GGX (caps, bounded VNDF, D cos θm), Beckmann
    /// and a mixture, per-lane α over [1e-4, 1], `wo` from normal to
    /// cos θo = 1e-7 and 0, `u` at 0 and 1 − ε.
    #[test]
    fn model_samples_on_lanes_match_the_scalar(
        rows in proptest::collection::vec(
            (common::direction(), uniform(), uniform(), uniform(), alpha()), 16),
        kind in 0usize..5,
    ) {
        // Beckmann (kind 2) keeps u0 ≤ 1 − 1e-4, a known limit: its visible-normal inversion
        // (a bracketed Newton solve in erfc(−x)) is ill-conditioned in f32 as u0 → 1, where the lanes'
        // and the scalar's math functions differ by ULPs: the drawn directions differ by
        // 7e-6 at u0 = 1 − 2⁻²⁴ (α = 0.045), up to 1e-3 further in the tail.
        let rows: Vec<[f64; 7]> = rows
            .iter()
            .map(|&(w, u0, u1, u2, a)| {
                let u0 = if kind == 2 { u0.min(1.0 - 1e-4) } else { u0 };
                [w.x, w.y, w.z, u0, u1, u2, a]
            })
            .collect();
        lanes_sample_as_scalar::<brdf::f32x4>(&rows, kind);
        lanes_sample_as_scalar::<brdf::f32x8>(&rows, kind);
        lanes_sample_as_scalar::<brdf::f32x16>(&rows, kind);
        lanes_sample_as_scalar::<brdf::f64x4>(&rows, kind);
    }
}

/// `D cos θm` sampling's weight in `f32` agrees with `f64` to 64 ε relative for sharp lobes
/// (`α ∈ [1.01e-4, 1e-2]`, `cos θo ∈ [0.05, 1]`, a 64 × 64 stratified grid of `u` per case):
/// the weight is the closed form `F G2 (wo·wm)/(cos θo cos θm)`, in which `D` cancels. The
/// ratio `f cos θi/pdf` instead carried `D` at two normals (the half vector rebuilt from
/// `wi + wo` and the drawn one), whose `f32` rounding `D` amplifies by `tan θm/α²`: 1.75e-4
/// relative was seen at `α = 3e-4`.
#[test]
fn full_distribution_weights_are_accurate_in_f32() {
    let mut worst = 0.0f64;
    for (k, &alpha) in [1.01e-4, 3e-4, 1e-3, 1e-2].iter().enumerate() {
        for &cos_o in &[0.05, 0.3, 0.44, 0.9, 1.0] {
            let phi_o = 0.7 + k as f64;
            let s = (1.0f64 - cos_o * cos_o).sqrt();
            let wo = Vec3::new(s * phi_o.cos(), s * phi_o.sin(), cos_o);
            let wo32 = Vec3::new(wo.x as f32, wo.y as f32, wo.z as f32);
            let wo = Vec3::new(f64::from(wo32.x), f64::from(wo32.y), f64::from(wo32.z));
            for i in 0..64 {
                for j in 0..64 {
                    let u = [(i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0, 0.5];
                    let (a, _) = model_run::<f32>(3, alpha as f32, wo32, u, wo32);
                    let (b, _) =
                        model_run::<f64>(3, f64::from(alpha as f32), wo, u.map(f64::from), wo);
                    if !b.valid || b.wi.z < 0.05 {
                        continue; // G1(wi) is steep near the horizon: conditioning, not this.
                    }
                    let rel = (f64::from(a.weight[0]) - b.weight[0]).abs() / b.weight[0];
                    worst = worst.max(rel);
                }
            }
        }
    }
    println!("worst relative weight error, f32 vs f64: {worst:e}");
    assert!(worst <= 64.0 * f64::from(f32::EPSILON), "{worst:e}");
}
