//! The albedo quadratures of `brdf::energy` against the crate's adaptive reference
//! (`analysis::directional_albedo`) and a Monte-Carlo estimate with the crate's sampler, and
//! the compensation formulas (Kulla & Conty 2017, Turquin 2019) against their defining
//! identities.

use brdf::analysis::{AlbedoConfig, directional_albedo as reference_albedo};
use brdf::energy::{
    Distribution, average_albedo, directional_albedo, fresnel_average, gauss_legendre,
    kulla_conty_fresnel, kulla_conty_lobe, schlick_average, turquin_factor,
};
use brdf::fresnel::{Conductor, NoFresnel, Schlick};
use brdf::masking::SmithHeightCorrelated;
use brdf::models::CookTorrance;
use brdf::ndf::{Beckmann, Ggx};

use brdf::{SampleBrdf, Vec3};

fn wo_of(mu: f64) -> Vec3<f64> {
    Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu)
}

#[test]
fn gauss_legendre_integrates_polynomials_of_degree_2n_minus_1_exactly() {
    let (x, w) = gauss_legendre::<16>();
    for k in 0..32 {
        let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(k)).sum();
        let exact = 1.0 / f64::from(k + 1);
        assert!((q - exact).abs() < 1e-14, "x^{k}: {q} vs {exact}");
    }
}

const ALPHAS: [f64; 7] = [1e-3, 0.01, 0.05, 0.1, 0.3, 0.6, 1.0];
const MUS: [f64; 7] = [1e-3, 0.01, 0.05, 0.2, 0.5, 0.8, 1.0];

#[test]
fn ggx_albedo_matches_the_adaptive_reference() {
    const DIST: Distribution = Distribution::Ggx;
    let mut worst = (0.0, 0.0, 0.0);
    for alpha in ALPHAS {
        let ndf = Ggx::new(alpha).unwrap();
        let ct = CookTorrance::new(ndf, NoFresnel, SmithHeightCorrelated);
        for mu in MUS {
            let e = directional_albedo(DIST, alpha, mu).unwrap();
            let [r] = reference_albedo::<_, f64, 1>(&ct, wo_of(mu), &AlbedoConfig::DEFAULT);
            let err = (e - r).abs();
            if err > worst.0 {
                worst = (err, alpha, mu);
            }
        }
    }
    eprintln!(
        "GGX worst |E − ref| = {:.3e} at α = {}, μ = {}",
        worst.0, worst.1, worst.2
    );
    assert!(worst.0 < 1.5e-5, "{worst:?}");
}

#[test]
fn beckmann_albedo_matches_the_adaptive_reference() {
    const DIST: Distribution = Distribution::Beckmann;
    let mut worst = (0.0, 0.0, 0.0);
    for alpha in ALPHAS {
        let ndf = Beckmann::new(alpha).unwrap();
        let ct = CookTorrance::new(ndf, NoFresnel, SmithHeightCorrelated);
        for mu in MUS {
            let e = directional_albedo(DIST, alpha, mu).unwrap();
            let [r] = reference_albedo::<_, f64, 1>(&ct, wo_of(mu), &AlbedoConfig::DEFAULT);
            let err = (e - r).abs();
            if err > worst.0 {
                worst = (err, alpha, mu);
            }
        }
    }
    eprintln!(
        "Beckmann worst |E − ref| = {:.3e} at α = {}, μ = {}",
        worst.0, worst.1, worst.2
    );
    assert!(worst.0 < 1.5e-5, "{worst:?}");
}

/// The mean of the visible-normal sampler's weight `G2/G1(wo)` (`F = 1`) estimates `E`.
#[test]
fn ggx_albedo_agrees_with_a_monte_carlo_estimate_within_4_sigma() {
    let mut state = 0x9E37_79B9_7F4A_7C15_u64;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for (alpha, mu) in [(0.3, 0.5), (1.0, 1.0), (0.7, 0.1)] {
        let ct = CookTorrance::new(Ggx::new(alpha).unwrap(), NoFresnel, SmithHeightCorrelated);
        let n = 200_000;
        let (mut s, mut s2) = (0.0, 0.0);
        for _ in 0..n {
            let smp =
                SampleBrdf::<f64, 1>::sample(&ct, wo_of(mu), [uniform(), uniform(), uniform()]);
            let w = smp.weight[0];
            s += w;
            s2 += w * w;
        }
        let mean = s / f64::from(n);
        let sigma = ((s2 / f64::from(n) - mean * mean) / f64::from(n)).sqrt();
        let e = directional_albedo(Distribution::Ggx, alpha, mu).unwrap();
        assert!(
            (mean - e).abs() < 4.0 * sigma,
            "α {alpha} μ {mu}: MC {mean} ± {sigma}, E {e}"
        );
        assert!(sigma < 2e-3);
    }
}

#[test]
fn albedo_tends_to_one_for_a_smooth_surface_and_drops_with_roughness() {
    assert!((directional_albedo(Distribution::Ggx, 1e-3, 0.5).unwrap() - 1.0).abs() < 1e-4);
    assert!((average_albedo(Distribution::Beckmann, 1e-3).unwrap() - 1.0).abs() < 1e-3);
    let mut last = 1.0;
    for alpha in [0.1, 0.3, 0.6, 1.0] {
        let e = average_albedo(Distribution::Ggx, alpha).unwrap();
        assert!(e < last, "E_avg not decreasing at α = {alpha}");
        last = e;
    }
}

#[test]
fn schlick_average_closed_form_matches_quadrature() {
    for f0 in [0.0, 0.04, 0.5, 0.9, 1.0] {
        let [q] = fresnel_average(&Schlick::<f64, 1>::new([f0]).unwrap());
        assert!((q - schlick_average(f0)).abs() < 1e-12, "F0 {f0}: {q}");
    }
}

#[test]
fn conductor_average_matches_a_fine_midpoint_rule() {
    // Gold-like complex IOR (RGB); the reference is an independent 200 000-point midpoint rule.
    let au = Conductor::<f64, 3>::new([0.143, 0.374, 1.442], [3.983, 2.385, 1.603]).unwrap();
    let favg = fresnel_average(&au);
    let n = 200_000;
    for (c, &fc) in favg.iter().enumerate() {
        let mid: f64 = (0..n)
            .map(|k| {
                let mu = (f64::from(k) + 0.5) / f64::from(n);
                2.0 * brdf::fresnel::FresnelTerm::<f64, 3>::eval(&au, mu)[c] * mu
            })
            .sum::<f64>()
            / f64::from(n);
        assert!((fc - mid).abs() < 1e-9, "channel {c}: {fc} vs {mid}");
    }
}

/// White furnace of the Kulla-Conty compensation with `F = 1`: `E(μo) + ∫ f_ms cos θi dωi = 1`,
/// the inner integral by an independent 48-point rule in `μi` (φ integrates to 2π).
#[test]
fn kulla_conty_lobe_fills_the_missing_energy_with_f_equal_one() {
    for alpha in [0.3, 1.0] {
        let e_avg = average_albedo(Distribution::Ggx, alpha).unwrap();
        assert!((kulla_conty_fresnel(1.0, e_avg) - 1.0).abs() < 1e-15);
        let (x, w) = gauss_legendre::<48>();
        for mu_o in [0.05, 0.5, 1.0] {
            let e_o = directional_albedo(Distribution::Ggx, alpha, mu_o).unwrap();
            let ms: f64 = x
                .iter()
                .zip(&w)
                .map(|(&mi, wt)| {
                    wt * 2.0
                        * core::f64::consts::PI
                        * kulla_conty_lobe(
                            directional_albedo(Distribution::Ggx, alpha, mi).unwrap(),
                            e_o,
                            e_avg,
                        )
                        * mi
                })
                .sum();
            assert!(
                (e_o + ms - 1.0).abs() < 2e-4,
                "α {alpha} μo {mu_o}: {}",
                e_o + ms
            );
        }
    }
}

/// Turquin with `F0 = 1` restores the albedo to 1; with `F0 < 1` the factor depends on `μo`
/// only, so swapping `wi` and `wo` changes the value: a violating pair exists.
#[test]
fn turquin_factor_is_a_furnace_fix_and_not_reciprocal() {
    for mu in [0.05, 0.5, 1.0] {
        let e = directional_albedo(Distribution::Ggx, 0.8, mu).unwrap();
        assert!((turquin_factor(1.0, e) * e - 1.0).abs() < 1e-12);
    }
    let (e_i, e_o) = (
        directional_albedo(Distribution::Ggx, 0.8, 0.1).unwrap(),
        directional_albedo(Distribution::Ggx, 0.8, 0.9).unwrap(),
    );
    let (a, b) = (turquin_factor(0.5, e_o), turquin_factor(0.5, e_i));
    assert!((a - b).abs() / a > 1e-2, "f(wi, wo)/f(wo, wi) = {}", a / b);
}

/// Bad input is a typed error, never a NaN.
#[test]
fn bad_input_is_an_error() {
    use brdf::Error;
    for alpha in [0.0, 1e-5, 1.5, f64::NAN] {
        let e = directional_albedo(Distribution::Ggx, alpha, 0.5).unwrap_err();
        assert!(
            matches!(
                e,
                Error::OutOfDomain { param: "alpha", .. } | Error::NotFinite { param: "alpha" }
            ),
            "{e:?}"
        );
        assert!(average_albedo(Distribution::Beckmann, alpha).is_err());
    }
    for mu in [-0.1, 1.1, f64::INFINITY] {
        assert!(
            directional_albedo(Distribution::Beckmann, 0.3, mu).is_err(),
            "{mu}"
        );
    }
    assert!(
        directional_albedo(Distribution::Ggx, 0.3, 0.0)
            .unwrap()
            .is_finite()
    );
}
