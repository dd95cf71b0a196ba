//! Importance sampling: χ² goodness of fit of every sampler against its own `pdf`, the pdf's
//! integral, the weight `f·cos θi / pdf`, the consistency of `sample` with `pdf`, and finite
//! results at the extremes of `u` and `wo`.
//!
//! The χ² runs draw 10⁶ samples per configuration; the full set runs in release-like test
//! builds (opt-level 2) in well under a minute per model family.
mod common;

use brdf::models::{CoupledLambert, Lambert, OrenNayar, OrenNayarFujii, ShirleyDiffuse};
use brdf::{SampleBrdf, Vec3};
use common::chi2::{Chi2Config, chi2, gamma_q};

/// Number of χ² configurations in this file (the Šidák correction divides the 1 % level
/// among them). Keep it ≥ the count of `check_chi2` calls.
const TESTS: usize = 64;

fn wo_at(theta_deg: f64) -> Vec3<f64> {
    let t = theta_deg.to_radians();
    Vec3::new(t.sin(), 0.0, t.cos())
}

/// [`common::chi2::check_sampler`] on the default histogram, `f` within 1e-6 of `eval`.
pub fn check_chi2<const N: usize, M: SampleBrdf<f64, N>>(name: &str, model: &M, wo: Vec3<f64>) {
    common::chi2::check_sampler(name, model, wo, &Chi2Config::DEFAULT, TESTS, 1e-6);
}

#[test]
fn the_chi2_p_value_matches_known_quantiles() {
    // χ² quantiles (Abramowitz & Stegun, table 26.8): P(χ²_k > x).
    for (k, x, p) in [
        (1.0, 6.634_896_601, 0.01),
        (10.0, 18.307_038_05, 0.05),
        (100.0, 135.806_7, 0.01),
        (2.0, 2.0 * 2.0_f64.ln(), 0.5),
    ] {
        let q = gamma_q(k / 2.0, x / 2.0);
        assert!(
            (q - p).abs() < 1e-6 * p.max(1e-3) + 1e-7,
            "k = {k}: {q} vs {p}"
        );
    }
}

#[test]
fn the_chi2_test_rejects_a_sampler_that_does_not_match_its_pdf() {
    // Uniform hemisphere samples against the cosine density: must fail.
    let out = chi2(
        &mut |u| Some(brdf::analysis::uniform_hemisphere(u[0], u[1])),
        &|w| brdf::sampling::cosine_hemisphere_pdf(w),
        &Chi2Config {
            samples: 200_000,
            ..Chi2Config::DEFAULT
        },
    )
    .unwrap();
    assert!(out.p_value < 1e-10, "{out:?}");
    // And a sample in a zero-density cell is caught.
    let e = chi2(
        &mut |_| Some(Vec3::new(0.0, 0.0, 1.0)),
        &|_| 0.0,
        &Chi2Config {
            samples: 10,
            ..Chi2Config::DEFAULT
        },
    );
    assert!(e.is_err());
}

#[test]
fn diffuse_models_sample_the_cosine_lobe() {
    let lambert = Lambert::new([0.8_f64, 0.5, 0.2]).unwrap();
    let on = OrenNayar::new([0.7_f64], 0.6).unwrap();
    let fon = OrenNayarFujii::new([0.7_f64], 0.9).unwrap();
    let shirley = ShirleyDiffuse::new([0.6_f64], [0.04]).unwrap();
    let coupled = CoupledLambert::new([0.6_f64], 0.5, [0.04]).unwrap();
    for theta in [0.0, 45.0, 89.0] {
        let wo = wo_at(theta);
        check_chi2("lambert", &lambert, wo);
        check_chi2("oren-nayar", &on, wo);
        check_chi2("fujii", &fon, wo);
        check_chi2("shirley", &shirley, wo);
        check_chi2("coupled lambert", &coupled, wo);
        // Lambert's weight is the albedo.
        let s = lambert.sample(wo, [0.3, 0.7, 0.0]);
        for (w, a) in s.weight.iter().zip([0.8, 0.5, 0.2]) {
            assert!((w - a).abs() < 1e-15);
        }
    }
}
