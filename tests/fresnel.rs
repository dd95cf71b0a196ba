//! Tests of the Fresnel module: exact dielectric and conductor equations against independent
//! formulations (angles, complex arithmetic, Stokes relations, energy conservation), the
//! Cook-Torrance (g, c) form, Schlick, F0 conversions, F82-tint and Gulbrandsen, the
//! `FresnelTerm` types and their validation, extremes on f32/f64, and SIMD lanes.
mod common;

use approx::assert_abs_diff_eq;

use brdf::fresnel::reference::{cook_torrance_gc, gulbrandsen_from_nk, gulbrandsen_to_nk};
use brdf::fresnel::{self, *};
use brdf::{Error, Real, ior};
use num_complex::Complex;
use proptest::prelude::*;

// ----------------------------------------------------------------------------------------
// Strategies and independent references
// ----------------------------------------------------------------------------------------

/// Relative IOR: log-uniform over [1e-3, 1e3], near 1 (both sides), exactly 1, and the
/// common glass range.
fn eta() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => (-3.0f64..=3.0).prop_map(|e| 10f64.powf(e)),
        1 => (-1.0f64..=1.0).prop_map(|t| 1.0 + 1e-6 * t),
        1 => Just(1.0),
        2 => 1.0f64..3.0,
        1 => 0.3f64..1.0,
    ]
}

/// Extinction coefficient: 0, log-uniform up to 100, and the metal range.
fn kappa() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        2 => (-4.0f64..=2.0).prop_map(|e| 10f64.powf(e)),
        2 => 0.0f64..8.0,
        1 => Just(100.0),
    ]
}

/// A signed cosine covering [−1, 1] with normal, grazing (0, ±1e-7) and a rounding step
/// outside the interval.
fn signed_cos() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => (common::cos_theta(), any::<bool>()).prop_map(|(c, s)| if s { -c } else { c }),
        1 => Just(1.0 + f64::EPSILON),
        1 => Just(-1.0 - f64::EPSILON),
    ]
}

/// Seed-convention amplitudes from angles (Born & Wolf §1.5.2), an independent formulation:
/// `r_s = −sin(θi − θt)/sin(θi + θt)`, `r_p = −tan(θi − θt)/tan(θi + θt)` (seed sign).
fn amplitudes_from_angles(cos_i: f64, eta: f64) -> (f64, f64) {
    let ti = cos_i.acos();
    let tt = (ti.sin() / eta).asin();
    (
        -(ti - tt).sin() / (ti + tt).sin(),
        -(ti - tt).tan() / (ti + tt).tan(),
    )
}

/// Complex amplitudes by straightforward complex arithmetic (num-complex's own sqrt), with
/// the branch `Im w ≥ 0`.
fn complex_reference(cos_i: f64, eta: Complex<f64>) -> (Complex<f64>, Complex<f64>) {
    let c = Complex::new(cos_i, 0.0);
    let e2 = eta * eta;
    // η² − sin²θ written as (η − 1)(η + 1) + cos²θ: no cancellation near grazing, and
    // η² − 1 keeps its digits for η ≈ 1 (`e2 − 1` lost up to 3.5e-8 of R at η = 1 − 1.2e-7,
    // c = 5e-4: a flaky failure of the 1e-9 comparison below).
    let mut w = ((eta - 1.0) * (eta + 1.0) + cos_i * cos_i).sqrt();
    if w.im < 0.0 {
        w = -w;
    }
    ((c - w) / (c + w), (w - e2 * c) / (w + e2 * c))
}

// ----------------------------------------------------------------------------------------
// Dielectric
// ----------------------------------------------------------------------------------------

#[test]
fn dielectric_reference_values() {
    // Air → glass at normal incidence: 4 %.
    assert_abs_diff_eq!(dielectric(1.0f64, 1.5), 0.04, epsilon = 1e-16);
    // Brewster's angle tan θB = η: r_p = 0, so r = r_s²/2.
    let cb = (1.0f64 / 1.5).atan().sin(); // cos θB = 1/√(1 + η²)
    let a = dielectric_amplitudes(cb, 1.5);
    assert!(a.r_p.abs() < 1e-15, "{}", a.r_p);
    // Hecht, Optics: at Brewster for n = 1.5, R_s = 0.1479 (θB = 56.31°).
    assert!(
        (a.r_s * a.r_s - 0.147_929).abs() < 1e-6,
        "{}",
        a.r_s * a.r_s
    );
    // Critical angle from inside: sin θc = 1/η; just beyond is TIR.
    let cos_c = (1.0f64 - 1.0 / 2.25).sqrt();
    assert_eq!(dielectric(-(cos_c * (1.0 - 1e-12)), 1.5), 1.0);
    assert!(dielectric(-(cos_c * (1.0 + 1e-9)), 1.5) < 1.0);
    // Grazing and index-matched.
    assert_eq!(dielectric(0.0, 1.5), 1.0);
    assert_eq!(dielectric(0.0, 1.0), 0.0);
    assert_eq!(dielectric(0.3, 1.0), 0.0);
    assert_eq!(dielectric_transmittance(0.0, 1.0), 1.0);
}

#[test]
fn amplitude_sign_convention_and_pbrt_mapping() {
    // Seed convention: r_p = r_s = (1 − η)/(1 + η) at normal incidence.
    let a = dielectric_amplitudes(1.0f64, 2.0);
    assert!((a.r_s + 1.0 / 3.0).abs() < 1e-16 && (a.r_p + 1.0 / 3.0).abs() < 1e-16);
    assert!((a.t_s - 2.0 / 3.0).abs() < 1e-16 && (a.t_p - 2.0 / 3.0).abs() < 1e-16);
    // pbrt-v4 FrDielectric: r_parl = (η cos θi − cos θt)/(η cos θi + cos θt) = −r_p,
    // r_perp = (cos θi − η cos θt)/(cos θi + η cos θt) = r_s.
    for &(c, eta) in &[(0.3f64, 1.5f64), (0.9, 1.33), (0.05, 2.4), (0.8, 0.7)] {
        let a = dielectric_amplitudes(c, eta);
        let ct = (1.0 - (1.0 - c * c) / (eta * eta)).sqrt();
        let r_parl = (eta * c - ct) / (eta * c + ct);
        let r_perp = (c - eta * ct) / (c + eta * ct);
        assert!((a.r_p + r_parl).abs() < 1e-15 && (a.r_s - r_perp).abs() < 1e-15);
        assert_abs_diff_eq!(a.cos_theta_t, ct, epsilon = 1e-15);
    }
    // Under TIR: critical-angle values, no transmission.
    let a = dielectric_amplitudes(0.2f64, 1.0 / 1.5);
    assert_eq!(
        (a.r_s, a.r_p, a.t_s, a.t_p, a.cos_theta_t),
        (1.0, -1.0, 0.0, 0.0, 0.0)
    );
}

proptest! {
    #![proptest_config(common::config(256))]

    /// Energy conservation r + t = 1, with t computed independently here from the
    /// transmission amplitudes and the (η cos θt / cos θi) factor, over the whole domain.
    #[test]
    fn dielectric_energy_conservation(c in signed_cos(), eta in eta()) {
        let a = dielectric_amplitudes(c, eta);
        let r = dielectric(c, eta);
        prop_assert!((0.0..=1.0).contains(&r));
        prop_assert_eq!(r, a.reflectance());
        let ci = a.cos_theta_i;
        if ci > 0.0 {
            let factor = a.eta * a.cos_theta_t / ci;
            let t = factor * (a.t_s * a.t_s + a.t_p * a.t_p) / 2.0;
            prop_assert!((r + t - 1.0).abs() < 1e-12, "r {r} t {t} at {c} {eta}");
        }
        prop_assert!((r + a.transmittance() - 1.0).abs() < 1e-12);
        prop_assert!((dielectric_transmittance(c, eta) - a.transmittance()).abs() < 1e-12);
    }

    /// The g-form equals the angle form of Born & Wolf over the non-TIR domain, without
    /// filtering: `u` is warped into `c ∈ [c_min(η), 1]`, η drawn over [1e-3, 1e3]
    /// log-uniform, near and at 1. At `c = 1` exactly the angle form is 0/0 and its limit
    /// `(1 − η)/(1 + η)` (both amplitudes) is the reference.
    ///
    /// `c_min` comes from a lower bound on `t = cos θt` (`c² = 1 − η² (1 − t²)`, clamped at
    /// 0). Always `t ≥ 1e-3` (`sin²θt ≤ 1 − 1e-6`): beyond it the reference's `asin` is
    /// ill-conditioned; this only removes grazing `c < 1e-3` for η ∈ [1, 1 + 5e-7] (the whole
    /// `[0, 1]` is drawn for larger η). For η < 1, near the critical angle
    /// `g² = (η² − 1) + c²` cancels, so a one-ulp change of `c` moves `r_p` by
    /// `s(t) = c³ ε / (η t (t + η c)²)` (ε = 2⁻⁵²; `r_s` is less sensitive); observed 5.5e-8 at
    /// η = 0.0128, t = 1e-3: the amplitude's own conditioning in `c`, not an error of either
    /// form. The margin keeps `s ≤ 5e-10` (half the tolerance) with the smallest of three
    /// sufficient bounds (`c ≤ 1`, `c ≥ c_crit`, and `c³/(t + ηc)² ≤ c/η² ≤ (c_crit + ηt)/η²`),
    /// with `c_crit² = 1 − η²`.
    #[test]
    fn dielectric_matches_angle_form(u in common::unit(), eta in eta()) {
        let (eps, s_max) = (f64::EPSILON, 5e-10);
        let t_min = if eta >= 1.0 {
            1e-3
        } else {
            let k = eps / s_max;
            let c_crit = (1.0 - eta * eta).sqrt();
            let e3 = eta.powi(3);
            let t1 = k / (e3 * c_crit * c_crit);
            let t2 = (k / eta).cbrt();
            let room = s_max - eps / (eta * eta);
            let t3 = if room > 0.0 { c_crit * eps / (e3 * room) } else { f64::INFINITY };
            t1.min(t2).min(t3).max(1e-3)
        };
        let c_min = (1.0 - eta * eta * (1.0 - t_min * t_min)).max(0.0).sqrt();
        let c = (c_min + (1.0 - c_min) * u).min(1.0);
        let (rs, rp) = if c == 1.0 {
            let r = (1.0 - eta) / (1.0 + eta);
            (r, r)
        } else {
            amplitudes_from_angles(c, eta)
        };
        let a = dielectric_amplitudes(c, eta);
        prop_assert!((a.r_s - rs).abs() < 1e-9 && (a.r_p - rp).abs() < 1e-9,
            "c {c} eta {eta}: {:?} vs ({rs}, {rp})", a);
    }

    /// Incidence from inside uses 1/η; reflectance is reciprocal, r(θi, η) = r(θt, 1/η),
    /// and the Stokes relation t_s·t'_s = 1 − r_s² holds.
    #[test]
    fn dielectric_inside_outside_and_stokes(c in common::cos_theta(), eta in eta()) {
        prop_assert_eq!(dielectric(-c, eta), dielectric(c, 1.0 / eta));
        let a = dielectric_amplitudes(c, eta);
        // Near grazing θi ↦ θt is ill-conditioned (dθt/dθi → ∞ at the critical angle).
        if a.r_s < 1.0 && a.cos_theta_i > 1e-4 {
            let b = dielectric_amplitudes(-a.cos_theta_t, eta); // the refracted ray, reversed
            // Rounding of cos θt is amplified by ~max(η, 1/η)²/cos θi on the way back.
            let m = eta.max(1.0 / eta);
            let tol = 1e-12 * (1.0 + m * m / a.cos_theta_i);
            prop_assert!((a.reflectance() - b.reflectance()).abs() < tol,
                "{} vs {}", a.reflectance(), b.reflectance());
            prop_assert!((a.t_s * b.t_s - (1.0 - a.r_s * a.r_s)).abs() < tol);
            prop_assert!((a.t_p * b.t_p - (1.0 - a.r_p * a.r_p)).abs() < tol);
        }
    }
}

// ----------------------------------------------------------------------------------------
// Conductor
// ----------------------------------------------------------------------------------------

#[test]
fn conductor_reference_values() {
    // F0 of the seed's gold.
    assert_abs_diff_eq!(conductor(1.0f64, 0.34, 3.2), 0.887, epsilon = 5e-4);
    // Grazing: 1 for every conductor.
    assert_eq!(conductor(0.0, 0.2, 3.5), 1.0);
    // Index-matched grazing: the limit 0 along η = 1.
    assert_eq!(conductor(0.0, 1.0, 0.0), 0.0);
    // The sign of cos θ is ignored (an opaque conductor).
    assert_eq!(conductor(-0.4, 0.2, 3.5), conductor(0.4, 0.2, 3.5));
}

/// `conductor` with `k = 0` across the critical angle of a dense medium seen from inside,
/// in `f32`, against the f64 dielectric at the same (f32) cosine: exactly 1 under TIR, and
/// within the conditioning of the problem above it — near the critical cosine `c*`,
/// `R ≈ 1 − 4√t₀/c` with `t₀ = η² − s²`, so rounding `c²` alone (`ε`) moves `R` by up to
/// `4√ε/c`; the one-division form's critical-angle floor (`m < 10⁻⁹` gives 1) stays within
/// the same `4√M/c`.
#[test]
fn conductor_without_k_across_the_critical_angle() {
    let mut worst = 0.0f64;
    for eta in [0.2f64, 0.5, 1.0 / 1.5, 0.9, 0.999] {
        let c_star = (1.0 - eta * eta).sqrt();
        for i in -1000..=1000 {
            let c = (c_star * (1.0 + f64::from(i) * 1e-6)).min(1.0) as f32;
            let cf = f64::from(c);
            let got = f64::from(conductor(c, eta as f32, 0.0));
            let want = dielectric(cf, eta as f32 as f64);
            let t0 = (eta as f32 as f64).powi(2) - (1.0 - cf * cf);
            if t0 < -1e-6 {
                assert_eq!(got, 1.0, "η {eta} c {c}: TIR");
            }
            let bound = 4.0 * (f64::from(f32::EPSILON)).sqrt() / cf + 1e-6;
            assert!(
                (got - want).abs() <= bound,
                "η {eta} c {c}: {got} vs {want} (bound {bound})"
            );
            // Away from the steep vicinity, float32 accuracy up to the same conditioning:
            // `|∂R/∂t₀| ≈ 2/(c√t₀)` times the rounding of `t₀` (a few `ε`).
            if t0 > 1e-4 {
                let e = 8.0 * f64::from(f32::EPSILON) / (cf * t0.sqrt()) + 1e-6;
                assert!(
                    (got - want).abs() < e,
                    "η {eta} c {c}: {got} vs {want} ({e})"
                );
            }
            worst = worst.max((got - want).abs());
        }
    }
    eprintln!("worst |Δ| across the critical angles: {worst:.2e}");
}

#[test]
fn conductor_tir_phase() {
    // Dielectric under TIR through the complex amplitudes: modulus 1 and the classic phase.
    let (c, eta) = (0.3f64, 1.0 / 1.5);
    let (r_s, r_p) = conductor_amplitudes(c, Complex::new(eta, 0.0));
    assert!((r_s.norm() - 1.0).abs() < 1e-15 && (r_p.norm() - 1.0).abs() < 1e-15);
    let q = (1.0 - c * c - eta * eta).sqrt();
    assert!(
        (r_s.arg() + 2.0 * (q / c).atan()).abs() < 1e-14,
        "{}",
        r_s.arg()
    );
    // Seed (n − iκ) convention: conjugate IOR, conjugate amplitudes, same reflectance.
    let (a_s, a_p) = conductor_amplitudes(0.5f64, Complex::new(0.34, 3.2));
    let (b_s, b_p) = conductor_amplitudes(0.5f64, Complex::new(0.34, -3.2));
    assert!((a_s.conj() - b_s).norm() < 1e-15 && (a_p.conj() - b_p).norm() < 1e-15);
}

proptest! {
    #![proptest_config(common::config(256))]

    /// The closed real form equals |r_s|², |r_p|² from complex arithmetic (both the crate's
    /// generic complex amplitudes and num-complex's), and lies in [0, 1].
    #[test]
    fn conductor_matches_complex_form(c in signed_cos(), n in eta(), k in kappa()) {
        let r = conductor(c, n, k);
        prop_assert!((0.0..=1.0).contains(&r), "{r}");
        let ci = c.abs().min(1.0);
        let (s, p) = complex_reference(ci, Complex::new(n, k));
        let reference = (s.norm_sqr() + p.norm_sqr()) / 2.0;
        let (s2, p2) = conductor_amplitudes(c, Complex::new(n, k));
        let mine = (s2.norm_sqr() + p2.norm_sqr()) / 2.0;
        if reference.is_finite() {
            prop_assert!((r - reference).abs() < 1e-9, "{r} vs {reference}");
            prop_assert!((s2 - s).norm() < 1e-9 && (p2 - p).norm() < 1e-9);
        }
        prop_assert!((r - mine).abs() < 1e-9, "{r} vs {mine}");
    }

    /// `eval_cos2(c, c²)` is `eval(c)` bit for bit for the terms that use `cos²θd`
    /// (conductor, dielectric), and with `cos²θd` rounded on its own — as a microfacet model
    /// computes it, `|wi + wo|²/4` — within f32 rounding of it; the other terms ignore it.
    #[test]
    fn eval_cos2_is_eval(c in common::cos_theta(), n in eta(), k in kappa()) {
        let cond = Conductor::<f32, 1>::new([n as f32], [k as f32]).unwrap();
        let diel = Dielectric::<f32>::new(n as f32).unwrap();
        let schlick = Schlick::<f32, 1>::new([(k / 100.0) as f32]).unwrap();
        let c32 = c as f32;
        prop_assert_eq!(cond.eval_cos2(c32, c32 * c32), cond.eval(c32));
        prop_assert_eq!(
            FresnelTerm::<f32, 1>::eval_cos2(&diel, c32, c32 * c32),
            FresnelTerm::<f32, 1>::eval(&diel, c32)
        );
        let c2 = (c * c) as f32;
        prop_assert_eq!(schlick.eval_cos2(c32, 0.0), schlick.eval(c32));
        let g2 = n * n - 1.0 + c * c;
        if g2.abs() > 1e-2 || k > 0.1 {
            let (a, b) = (cond.eval_cos2(c32, c2)[0], conductor(c, n, k));
            prop_assert!((f64::from(a) - b).abs() < 2e-5, "conductor {a} vs {b}");
        }
        if g2.abs() > 1e-2 {
            let a = FresnelTerm::<f32, 1>::eval_cos2(&diel, c32, c2)[0];
            let b = dielectric(c, n);
            prop_assert!((f64::from(a) - b).abs() < 2e-5, "dielectric {a} vs {b}");
        }
    }

    /// With k = 0 the conductor is the dielectric seen from outside, for η > 1 and η < 1
    /// (TIR included: both give exactly 1).
    #[test]
    fn conductor_with_zero_k_is_dielectric(c in common::cos_theta(), n in eta()) {
        let a = conductor(c, n, 0.0);
        let b = dielectric(c, n);
        prop_assert!((a - b).abs() < 1e-12, "{a} vs {b} at c={c} eta={n}");
        if b == 1.0 && c > 0.0 && n < 1.0 {
            prop_assert_eq!(a, 1.0);
        }
    }
}

// ----------------------------------------------------------------------------------------
// Cook-Torrance (g, c)
// ----------------------------------------------------------------------------------------

proptest! {
    #![proptest_config(common::config(256))]

    #[test]
    fn cook_torrance_gc_equals_sp_form(c in common::cos_theta(), eta in eta()) {
        let a = cook_torrance_gc(c, eta);
        let b = dielectric(c, eta);
        prop_assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        prop_assert!((0.0..=1.0).contains(&a));
    }
}

#[test]
fn cook_torrance_seed_transcription_is_wrong() {
    // The seed prints g = √(n² + c²) − 1 and omits the factor ½. Taken literally, at normal
    // incidence it gives 2·F0 for glass: the corrected form gives F0.
    let seed = |c: f64, n: f64| {
        let g = (n * n + c * c).sqrt() - 1.0;
        (g - c).powi(2) / (g + c).powi(2)
            * (1.0 + (c * (g + c) - 1.0).powi(2) / (c * (g - c) + 1.0).powi(2))
    };
    let (f0, literal) = (cook_torrance_gc(1.0f64, 1.5), seed(1.0, 1.5));
    assert_abs_diff_eq!(f0, 0.04, epsilon = 1e-16);
    assert!((literal - 0.04).abs() > 0.01, "{literal}");
    // TIR: g² < 0 → 1.
    assert_eq!(cook_torrance_gc(0.2, 1.0 / 1.5), 1.0);
}

// ----------------------------------------------------------------------------------------
// Schlick and F0 conversions
// ----------------------------------------------------------------------------------------

#[test]
fn schlick_end_points_and_f90() {
    for f0 in [0.0, 0.02, 0.04, 0.5, 0.9, 1.0] {
        assert_eq!(schlick(f0, 1.0), f0);
        assert_eq!(schlick(f0, 0.0), 1.0);
        assert_eq!(schlick(f0, 1.0 + 1e-16), f0); // clamped
        assert_eq!(schlick_f90(f0, 0.5, 0.0), 0.5);
        assert_eq!(schlick_f90(f0, 1.0, 0.37), schlick(f0, 0.37));
    }
    assert_eq!(schlick_weight(0.5), 0.03125);
    // Monotone decreasing in cos θ.
    let mut prev = 2.0;
    for i in 0..=100 {
        let f = schlick(0.04, i as f64 / 100.0);
        assert!(f <= prev);
        prev = f;
    }
    // Schlick vs exact glass (η = 1.5): measured max error 0.0357 at cos θ ≈ 0.088 (85°),
    // where the exact curve dips below Schlick's before rising to 1.
    let mut worst = 0.0f64;
    for i in 0..=10000 {
        let c = i as f64 / 10000.0;
        worst = worst.max((schlick(f0_from_ior(1.5), c) - dielectric(c, 1.5)).abs());
    }
    assert!(worst < 0.036 && worst > 0.035, "{worst}");
}

#[test]
fn f0_conversions() {
    for eta in [1.0f64, 1.33, 1.5, 2.4, 0.5, 1e-3, 1e3] {
        assert_abs_diff_eq!(f0_from_ior(eta), dielectric(1.0, eta), epsilon = 1e-15);
        assert_abs_diff_eq!(f0_from_ior(eta), f0_from_ior(1.0 / eta), epsilon = 1e-15);
        assert_abs_diff_eq!(
            f0_from_complex_ior(eta, 0.0),
            f0_from_ior(eta),
            epsilon = 1e-15
        );
        if (1.0..1e3).contains(&eta) {
            assert!(
                (ior_from_f0(f0_from_ior(eta)) - eta).abs() < 1e-12 * eta,
                "{eta}"
            );
        }
    }
    for (n, k) in [(0.34f64, 3.2f64), (0.2, 3.5), (2.0, 1.0), (1e-3, 100.0)] {
        assert_abs_diff_eq!(
            f0_from_complex_ior(n, k),
            conductor(1.0, n, k),
            epsilon = 1e-15
        );
    }
    assert_eq!(ior_from_f0(0.0), 1.0);
    assert_abs_diff_eq!(ior_from_f0(0.04f64), 1.5, epsilon = 1e-15);
    // As F0 → 1, η ≈ 4/(1 − F0).
    let f0 = 1.0f64 - 1e-6;
    assert_abs_diff_eq!(ior_from_f0(f0) * (1.0 - f0), 4.0, epsilon = 1e-5);
    assert_eq!(ior_from_f0(1.0), f64::INFINITY);
    // The validated constructor.
    assert!(Dielectric::<f64>::from_f0(0.04).is_ok());
    assert_abs_diff_eq!(
        Dielectric::<f32>::from_f0(0.04).unwrap().eta(),
        1.5,
        epsilon = 1e-6
    );
    // The domain ends at MAX_DIELECTRIC_F0 (the IOR would exceed MAX_ETA), in the lane
    // precision.
    let top = Dielectric::<f32>::from_f0(MAX_DIELECTRIC_F0 as f32).unwrap();
    assert!(top.eta() <= MAX_ETA as f32 && top.eta() > 0.99 * MAX_ETA as f32);
    assert!(Dielectric::<f32>::from_f0((MAX_DIELECTRIC_F0 as f32).next_up()).is_err());
    assert!(Dielectric::<f64>::from_f0(MAX_DIELECTRIC_F0.next_up()).is_err());
    assert_eq!(
        Dielectric::<f64>::from_f0(1.0),
        Err(Error::OutOfDomain {
            param: "f0",
            value: 1.0,
            domain: "[0, 0.9996]"
        })
    );
    assert!(Dielectric::<f64>::from_f0(-0.01).is_err());
    assert_eq!(
        Dielectric::<f32>::from_f0(f32::NAN),
        Err(Error::NotFinite { param: "f0" })
    );
}

// ----------------------------------------------------------------------------------------
// F82-tint and Gulbrandsen
// ----------------------------------------------------------------------------------------

#[test]
fn f82_tint_properties() {
    let mu = F82_COS_THETA;
    // μ(1 − μ)⁶ peaks at μ̄ = 1/7.
    let w = |m: f64| m * (1.0 - m).powi(6);
    assert!(w(mu) > w(mu - 1e-4) && w(mu) > w(mu + 1e-4));
    for f0 in [0.0, 0.04, 0.5, 0.9, 1.0] {
        for tint in [0.0, 0.3, 0.8, 1.0] {
            let at = f82_tint(f0, tint, mu);
            assert!((at - tint * schlick(f0, mu)).abs() < 1e-15, "{f0} {tint}");
            assert_eq!(f82_tint(f0, tint, 1.0), f0);
            assert_eq!(f82_tint(f0, tint, 0.0), 1.0);
            let b = f82_b(f0, tint);
            for c in [0.0, 0.1, 0.5, 0.9, 1.0] {
                assert_eq!(f82_tint(f0, tint, c), f82_tint_with_b(f0, b, c));
            }
        }
        // tint = 1 is Schlick.
        assert_eq!(f82_tint(f0, 1.0, 0.33), schlick(f0, 0.33));
    }
    // The published curve goes negative for a strong correction (f0 = 0, tint = 0); the
    // clamped one stays in [0, 1].
    let raw = |c: f64| schlick(0.0, c) - f82_b(0.0, 0.0) * w(c);
    assert!(raw(0.5) < 0.0);
    assert_eq!(f82_tint(0.0, 0.0, 0.5), 0.0);
}

#[test]
fn f82_fitted_to_ior_is_exact_at_three_points() {
    for p in ior::Preset::METALS {
        let m = F82Tint::<f64, 3>::from_preset(p).unwrap();
        let exact = Conductor::<f64, 3>::from_preset(p).unwrap();
        for c in [0.0, F82_COS_THETA, 1.0] {
            let (a, b) = (m.eval(c), exact.eval(c));
            for i in 0..3 {
                assert!(
                    (a[i] - b[i]).abs() < 1e-14,
                    "{} {c} {i}: {} vs {}",
                    p,
                    a[i],
                    b[i]
                );
            }
        }
    }
}

proptest! {
    #![proptest_config(common::config(256))]

    /// Gulbrandsen's mapping: F0(n, k) = r, the inverse recovers (r, g), and k² ≥ 0 over
    /// the whole domain (no clamping needed).
    #[test]
    fn gulbrandsen_round_trip(r in prop_oneof![0.0f64..0.99, Just(0.0), Just(0.999)],
                              g in prop_oneof![0.0f64..=1.0, Just(0.0), Just(1.0)]) {
        let (n, k) = gulbrandsen_to_nk(r, g);
        prop_assert!(n > 0.0 && k.is_finite());
        prop_assert!((f0_from_complex_ior(n, k) - r).abs() < 1e-9, "{} vs {r}",
            f0_from_complex_ior(n, k));
        let (r2, g2) = gulbrandsen_from_nk(n, k);
        prop_assert!((r2 - r).abs() < 1e-9);
        if r > 1e-6 {
            prop_assert!((g2 - g).abs() < 1e-6, "{g2} vs {g}");
        }
        if g == 0.0 {
            prop_assert!(k < 1e-5 * n.max(1.0), "k {k}");
        }
        // Raw k², before the safe square root.
        let (n_min, n_max) = ((1.0 - r) / (1.0 + r), (1.0 + r.sqrt()) / (1.0 - r.sqrt()));
        prop_assert!(n >= n_min * (1.0 - 1e-12) && n <= n_max * (1.0 + 1e-12));
    }
}

/// Maximum error over cos θ ∈ [0, 1] (10⁴ + 1 uniform points) of an approximation against
/// the exact conductor Fresnel of one channel.
fn max_error(approx: impl Fn(f64) -> f64, n: f64, k: f64) -> f64 {
    (0..=10_000)
        .map(|i| i as f64 / 10_000.0)
        .map(|c| (approx(c) - conductor(c, n, k)).abs())
        .fold(0.0, f64::max)
}

/// The accuracy table of the module docs: max |F − F_exact| per metal and channel for
/// Schlick (with the exact F0) and F82-tint (fitted at μ = 1 and 1/7), and Gulbrandsen's
/// round trip. Bounds are the measured maxima rounded up to two significant digits; the
/// test also fails if a bound is more than ~10 % loose.
#[test]
fn metal_models_error_table() {
    // (name, Schlick bounds R G B, F82 bounds R G B)
    const BOUNDS: &[(&str, [f64; 3], [f64; 3])] = &[
        ("gold", [0.016, 0.0096, 0.018], [0.0044, 0.0061, 0.017]),
        ("silver", [0.0062, 0.0066, 0.0023], [0.0011, 0.0022, 0.0016]),
        ("copper", [0.024, 0.039, 0.040], [0.0063, 0.0056, 0.0017]),
        ("aluminium", [0.14, 0.11, 0.065], [0.023, 0.0091, 0.0061]),
        ("iron", [0.18, 0.18, 0.15], [0.019, 0.019, 0.013]),
        ("titanium", [0.19, 0.17, 0.14], [0.017, 0.012, 0.0080]),
        ("chromium", [0.20, 0.20, 0.15], [0.022, 0.024, 0.0087]),
    ];
    assert_eq!(BOUNDS.len(), ior::Preset::METALS.len());
    let tight = |err: f64, bound: f64, what: &str| {
        let sig2 = {
            let e = 10f64.powf(err.log10().floor() - 1.0);
            (err / e).ceil() * e
        };
        println!("{what}: {err:.6} (suggested bound {sig2:.2e})");
        assert!(err <= bound, "{what}: {err:.5} > bound {bound}");
        assert!(
            err > 0.9 * bound,
            "{what}: bound {bound} is loose for {err:.5}"
        );
    };
    for (p, (name, schlick_b, f82_b_)) in ior::Preset::METALS.iter().zip(BOUNDS) {
        assert_eq!(&p.name(), name);
        let f82 = F82Tint::<f64, 3>::from_preset(*p).unwrap();
        let mut line = format!("{:10}", p.name());
        let (eta, kk) = p.ior();
        for i in 0..3 {
            let (n, k) = (eta[i], kk[i]);
            let f0 = f0_from_complex_ior(n, k);
            let e_s = max_error(|c| schlick(f0, c), n, k);
            let e_f = max_error(|c| f82.eval(c)[i], n, k);
            let (r, g) = gulbrandsen_from_nk(n, k);
            assert!(
                (0.0..=1.0 + 1e-9).contains(&g),
                "{}: edge tint {g} outside [0, 1]",
                p.name()
            );
            let (n2, k2) = gulbrandsen_to_nk(r, g.min(1.0));
            let e_g = max_error(|c| conductor(c, n2, k2), n, k);
            tight(e_s, schlick_b[i], &format!("{} schlick ch{i}", p.name()));
            tight(e_f, f82_b_[i], &format!("{} f82 ch{i}", p.name()));
            assert!(e_f < e_s, "{}: F82 must beat Schlick", p.name());
            assert!(e_g < 1e-12, "{}: Gulbrandsen round trip {e_g}", p.name());
            line += &format!("  S {e_s:.4} F82 {e_f:.4} G {e_g:.0e} (g {g:.3})");
        }
        println!("{line}");
    }
}

// ----------------------------------------------------------------------------------------
// FresnelTerm types and validation
// ----------------------------------------------------------------------------------------

#[test]
fn fresnel_terms_match_free_functions() {
    let s = Schlick::<f64, 3>::with_f90([0.04, 0.5, 0.9], [1.0, 0.8, 0.5]).unwrap();
    let c = Conductor::<f64, 3>::new([0.2, 0.5, 1.4], [3.5, 2.5, 1.9]).unwrap();
    let f = F82Tint::<f64, 3>::new([0.9, 0.6, 0.3], [0.8, 0.9, 1.0]).unwrap();
    let d = Dielectric::<f64>::new(1.5).unwrap().channels::<3>();
    for cos in [0.0, 1e-7, 0.3, 0.7, 1.0] {
        let (es, ec, ef) = (s.eval(cos), c.eval(cos), f.eval(cos));
        let ed: [f64; 3] = d.eval(cos);
        for i in 0..3 {
            assert_eq!(es[i], schlick_f90(s.f0()[i], s.f90()[i], cos));
            assert_eq!(ec[i], conductor(cos, c.eta()[i], c.k()[i]));
            assert_eq!(ef[i], f82_tint(f.f0()[i], [0.8, 0.9, 1.0][i], cos));
            assert_eq!(ed[i], dielectric(cos, 1.5));
        }
        assert_eq!(FresnelTerm::<f64, 2>::eval(&NoFresnel, cos), [1.0; 2]);
    }
    // Precomputed coefficient.
    assert_eq!(f.b()[0], f82_b(0.9, 0.8));
    // Constructors from presets and from the artist parametrization.
    let e = ior::Preset::Gold.seed().unwrap();
    let g = Conductor::new([e.eta as f32], [e.k as f32]).unwrap();
    assert_abs_diff_eq!(g.eval(1.0)[0], 0.887, epsilon = 5e-4);
    let a =
        Conductor::<f64, 3>::from_reflectivity_edge_tint([0.9, 0.7, 0.4], [0.2, 0.5, 0.9]).unwrap();
    let f0 = a.eval(1.0);
    assert!((f0[0] - 0.9).abs() < 1e-12 && (f0[2] - 0.4).abs() < 1e-12);
    let sc = Schlick::<f64, 2>::from_complex_ior([0.34, 1.5], [3.2, 0.0]).unwrap();
    assert_abs_diff_eq!(sc.f0()[0], conductor(1.0, 0.34, 3.2), epsilon = 1e-15);
    assert_abs_diff_eq!(
        Schlick::<f32, 1>::from_ior([1.5]).unwrap().f0()[0],
        0.04,
        epsilon = 1e-8
    );
}

#[test]
fn constructors_reject_bad_parameters() {
    fn nf<T>(param: &'static str) -> Result<T, Error> {
        Err(Error::NotFinite { param })
    }
    assert_eq!(Schlick::<f32, 1>::new([f32::NAN]), nf("f0"));
    assert!(matches!(
        Schlick::<f32, 2>::new([0.5, 1.5]),
        Err(Error::OutOfDomain { param: "f0", .. })
    ));
    assert!(matches!(
        Schlick::<f64, 1>::with_f90([0.5], [-0.1]),
        Err(Error::OutOfDomain { param: "f90", .. })
    ));
    assert!(Schlick::<f64, 1>::from_ior([0.0]).is_err());
    assert!(Schlick::<f64, 1>::from_complex_ior([1.0], [-1.0]).is_err());
    assert_eq!(Dielectric::<f64>::new(f64::INFINITY), nf("eta"));
    assert!(matches!(
        Dielectric::<f64>::new(-1.5),
        Err(Error::OutOfDomain { param: "eta", .. })
    ));
    assert!(matches!(
        Conductor::<f64, 1>::new([0.0], [1.0]),
        Err(Error::OutOfDomain { param: "eta", .. })
    ));
    assert!(matches!(
        Conductor::<f64, 1>::new([0.2], [-3.0]),
        Err(Error::OutOfDomain { param: "k", .. })
    ));
    assert_eq!(Conductor::<f32, 1>::new([0.2], [f32::NAN]), nf("k"));
    assert!(matches!(
        Conductor::<f64, 1>::from_reflectivity_edge_tint([1.0], [0.5]),
        Err(Error::OutOfDomain { param: "r", .. })
    ));
    assert!(Conductor::<f64, 1>::from_reflectivity_edge_tint([0.5], [1.5]).is_err());
    assert!(matches!(
        F82Tint::<f64, 1>::new([0.5], [1.2]),
        Err(Error::OutOfDomain { param: "tint", .. })
    ));
    assert!(F82Tint::<f64, 1>::new([-0.5], [0.2]).is_err());
    assert!(F82Tint::<f64, 1>::from_ior([f64::NAN], [0.2]).is_err());
}

// ----------------------------------------------------------------------------------------
// Extremes: no NaN or ∞ on f32 and f64
// ----------------------------------------------------------------------------------------

fn all_finite_in_unit<S: brdf::Scalar>(c: f64, n: f64, k: f64) -> Result<(), TestCaseError> {
    let (c, n, k) = (S::of(c), S::of(n), S::of(k));
    let unit = |x: S, what: &str| -> Result<(), TestCaseError> {
        let v: f64 = x.into();
        prop_assert!(v.is_finite() && (0.0..=1.0).contains(&v), "{what} = {v}");
        Ok(())
    };
    unit(dielectric(c, n), "dielectric")?;
    unit(dielectric_transmittance(c, n), "dielectric_transmittance")?;
    let a = dielectric_amplitudes(c, n);
    unit(a.transmittance(), "amplitudes transmittance")?;
    for x in [a.r_s, a.r_p, a.t_s, a.t_p, a.cos_theta_t] {
        prop_assert!(x.is_finite());
    }
    unit(conductor(c, n, k), "conductor")?;
    let (s, p) = conductor_amplitudes(c, Complex::new(n, k));
    prop_assert!(s.re.is_finite() && s.im.is_finite() && p.re.is_finite() && p.im.is_finite());
    unit(cook_torrance_gc(c, n), "cook_torrance_gc")?;
    let f0 = f0_from_complex_ior(n, k);
    unit(f0, "f0_from_complex_ior")?;
    unit(f0_from_ior(n), "f0_from_ior")?;
    unit(schlick(f0, c), "schlick")?;
    unit(schlick_f90(f0, S::of(0.5), c), "schlick_f90")?;
    unit(f82_tint(f0, S::of(0.7), c), "f82_tint")?;
    let r = f0.min(S::of(0.99));
    prop_assert!(ior_from_f0(r).is_finite());
    let (gn, gk) = gulbrandsen_to_nk(r, S::of(0.5));
    prop_assert!(gn.is_finite() && gk.is_finite());
    Ok(())
}

proptest! {
    #![proptest_config(common::config(256))]

    #[test]
    fn no_nan_at_extremes(c in signed_cos(), n in eta(), k in kappa()) {
        all_finite_in_unit::<f64>(c, n, k)?;
        all_finite_in_unit::<f32>(c, n, k)?;
        // A rounding step outside [−1, 1] in f32, too.
        all_finite_in_unit::<f32>(f64::from(1.0f32 + f32::EPSILON), n, k)?;
        all_finite_in_unit::<f32>(f64::from(-1.0f32 - f32::EPSILON), n, k)?;
    }

    /// f32 agrees with f64 away from the steep vicinity of the critical angle.
    #[test]
    fn f32_agrees_with_f64(c in common::cos_theta(), n in eta(), k in kappa()) {
        let g2 = n * n - 1.0 + c * c;
        if g2.abs() > 1e-2 {
            let d = dielectric(c as f32, n as f32) as f64 - dielectric(c, n);
            prop_assert!(d.abs() < 2e-5, "dielectric {d}");
        }
        let d = conductor(c as f32, n as f32, k as f32) as f64 - conductor(c, n, k);
        if g2.abs() > 1e-2 || k > 0.1 {
            prop_assert!(d.abs() < 2e-5, "conductor {d}");
        }
    }
}

// ----------------------------------------------------------------------------------------
// SIMD lanes
// ----------------------------------------------------------------------------------------

/// Rows (cos, eta, k) including every extreme.
fn lane_rows() -> Vec<[f64; 3]> {
    let cosines = [
        0.0,
        1e-7,
        -1e-7,
        0.01,
        0.3,
        0.5,
        std::f64::consts::FRAC_1_SQRT_2,
        0.99,
        1.0,
        -1.0,
        -0.4,
        1.0 + 1e-7,
        -1.0 - 1e-7,
    ];
    let etas = [
        1e-3,
        0.2,
        0.6667,
        1.0 - 1e-6,
        1.0,
        1.0 + 1e-6,
        1.33,
        1.5,
        2.4,
        10.0,
        1e3,
    ];
    let ks = [0.0, 1e-3, 0.5, 3.2, 100.0];
    let mut rows = Vec::new();
    for (i, &c) in cosines.iter().enumerate() {
        for (j, &e) in etas.iter().enumerate() {
            rows.push([c, e, ks[(i + j) % ks.len()]]);
        }
    }
    rows
}

#[test]
fn lanes_match_scalar() {
    let rows = lane_rows();
    // f0/tint-style rows in [0, 1].
    let unit_rows: Vec<[f64; 3]> = rows
        .iter()
        .map(|r| {
            [
                r[0],
                fresnel::f0_from_complex_ior(r[1], r[2]),
                (r[2] / 100.0).min(1.0),
            ]
        })
        .collect();
    // Only + − × ÷ √ and fused multiply-add (identical on lanes): bit-exact, 0 ULP.
    let mut report = Vec::new();
    macro_rules! check {
        ($name:expr, $rows:expr, fn($($a:ident),+) $body:block) => {{
            let w = common::assert_lanes_match!($name, ulp = 0, abs = 0.0, $rows, fn($($a),+) $body);
            report.push(($name, w));
        }};
    }
    check!("dielectric", &rows, fn(c, e, k) { fresnel::dielectric(c, e) });
    check!("dielectric_transmittance", &rows, fn(c, e, k) { fresnel::dielectric_transmittance(c, e) });
    check!("amplitudes.r_s", &rows, fn(c, e, k) { fresnel::dielectric_amplitudes(c, e).r_s });
    check!("amplitudes.r_p", &rows, fn(c, e, k) { fresnel::dielectric_amplitudes(c, e).r_p });
    check!("amplitudes.t_s", &rows, fn(c, e, k) { fresnel::dielectric_amplitudes(c, e).t_s });
    check!("amplitudes.t_p", &rows, fn(c, e, k) { fresnel::dielectric_amplitudes(c, e).t_p });
    check!("amplitudes.transmittance", &rows, fn(c, e, k) {
        fresnel::dielectric_amplitudes(c, e).transmittance()
    });
    check!("conductor", &rows, fn(c, e, k) { fresnel::conductor(c, e, k) });
    check!("conductor_amplitudes.re", &rows, fn(c, e, k) {
        let (s, p) = fresnel::conductor_amplitudes(c, num_complex::Complex::new(e, k));
        s.re + p.re * R::from_f64(3.0)
    });
    check!("conductor_amplitudes.im", &rows, fn(c, e, k) {
        let (s, p) = fresnel::conductor_amplitudes(c, num_complex::Complex::new(e, k));
        s.im + p.im * R::from_f64(3.0)
    });
    check!("cook_torrance_gc", &rows, fn(c, e, k) { fresnel::reference::cook_torrance_gc(c, e) });
    check!("f0_from_ior", &rows, fn(c, e, k) { fresnel::f0_from_ior(e) });
    check!("f0_from_complex_ior", &rows, fn(c, e, k) { fresnel::f0_from_complex_ior(e, k) });
    check!("ior_from_f0", &unit_rows, fn(c, f0, t) { fresnel::ior_from_f0(f0.min(R::from_f64(0.999))) });
    check!("schlick", &unit_rows, fn(c, f0, t) { fresnel::schlick(f0, c) });
    check!("schlick_f90", &unit_rows, fn(c, f0, t) { fresnel::schlick_f90(f0, t, c) });
    check!("f82_tint", &unit_rows, fn(c, f0, t) { fresnel::f82_tint(f0, t, c) });
    check!("gulbrandsen_to_nk", &unit_rows, fn(c, f0, t) {
        let (n, k) = fresnel::reference::gulbrandsen_to_nk(f0.min(R::from_f64(0.99)), t);
        n + k
    });
    check!("gulbrandsen_from_nk", &rows, fn(c, e, k) {
        let (r, g) = fresnel::reference::gulbrandsen_from_nk(e, k);
        r + g
    });
    println!("worst ULP per formula: {report:?}");
}

/// `schlick_complement` = 1 − (1 − c)⁵ in f32 within 4 ulp-level relative error of the f64
/// reference over [0, 1], grazing included (the direct f32 form loses every digit there),
/// and the lanes match the scalar.
#[test]
fn schlick_complement_is_accurate_at_grazing() {
    use brdf::fresnel::schlick_complement;
    let mut worst = 0.0f64;
    for i in 0..=20_000 {
        // Dense near 0 (down to 1e-9) and uniform over [0, 1].
        let c = if i <= 10_000 {
            1e-9 * 1e9f64.powf(i as f64 / 10_000.0)
        } else {
            (i - 10_000) as f64 / 10_000.0
        };
        let c32 = c as f32;
        let exact = 1.0 - (1.0 - c32 as f64).powi(5);
        let got = schlick_complement(c32) as f64;
        let rel = (got - exact).abs() / exact.max(f64::MIN_POSITIVE);
        worst = worst.max(rel);
        let direct = 1.0 - (1.0 - c32).powi(5);
        if c < 1e-8 {
            // The naive form is 0 there: the test would catch a regression to it.
            assert_eq!(direct, 0.0);
        }
    }
    assert!(worst < 5e-7, "worst relative error {worst:e}");
    assert_eq!(schlick_complement(0.0f32), 0.0);
    assert_eq!(schlick_complement(-0.5f64), 0.0);
    assert_eq!(schlick_complement(1.5f64), 1.0);
    let rows: Vec<[f64; 1]> = (0..=64)
        .map(|i| [if i == 0 { 1e-7 } else { i as f64 / 64.0 }])
        .collect();
    common::assert_lanes_match!("schlick_complement", ulp = 0, abs = 0.0, &rows, fn(c) {
        brdf::fresnel::schlick_complement(c)
    });
}

// ----------------------------------------------------------------------------------------
// Edge cases (issue 12 §4)
// ----------------------------------------------------------------------------------------

/// Cosines down to the smallest subnormals of both types, where `c²` underflows (below
/// `≈ 1e-23` in `f32`, `≈ 1e-162` in `f64`) or loses digits (below `≈ 1e-19`, `1e-154`).
const TINY_COSINES: [f64; 16] = [
    0.0, 5e-324, 1e-320, 1e-300, 1e-162, 1e-155, 1e-45, 1e-40, 3e-23, 1e-23, 1e-20, 1e-19, 1e-10,
    1e-7, 0.5, 1.0,
];

/// At `η = 1` exactly (an index-matched interface) nothing is reflected, at every angle and
/// on every number type: the dielectric, its amplitudes, the Cook-Torrance (g, c) form, the
/// conductor with `k = 0`, its complex amplitudes and the Fresnel terms are all exactly 0
/// (they returned 1, or 0.029 for the conductor, where `c²` underflows).
#[test]
fn index_matched_reflects_nothing_at_any_angle() {
    fn on<R: Real>(ty: &str) {
        let one = R::one();
        for &c64 in &TINY_COSINES {
            let c = R::from_f64(c64);
            let zero = |v: R, what: &str| {
                for l in 0..R::LANES {
                    let x: f64 = v.lane(l).into();
                    assert!(x == 0.0, "{ty}: {what} = {x:e} at |c| = {c64:e}");
                }
            };
            for c in [c, -c] {
                zero(dielectric(c, one), "dielectric");
                let a = dielectric_amplitudes(c, one);
                zero(a.r_s, "r_s");
                zero(a.r_p, "r_p");
                zero(a.transmittance() - one, "1 − transmittance");
                zero(cook_torrance_gc(c, one), "cook_torrance_gc");
                zero(conductor(c, one, R::zero()), "conductor(c, 1, 0)");
                let (rs, rp) = conductor_amplitudes(c, Complex::new(one, R::zero()));
                for (name, z) in [("conductor r_s", rs), ("conductor r_p", rp)] {
                    zero(z.re, name);
                    zero(z.im, name);
                }
            }
        }
    }
    on::<f32>("f32");
    on::<f64>("f64");
    on::<brdf::f32x8>("f32x8");
    on::<brdf::f64x4>("f64x4");
    on::<brdf::real::F32Fma>("F32Fma");
    // The terms, through eval and through eval_cos2 (c² = |h|²/4 in a microfacet model).
    let (d32, d64) = (
        Dielectric::new(1.0_f32).unwrap(),
        Dielectric::new(1.0_f64).unwrap(),
    );
    let (k32, k64) = (
        Conductor::new([1.0_f32], [0.0]).unwrap(),
        Conductor::new([1.0_f64], [0.0]).unwrap(),
    );
    for &c in &TINY_COSINES {
        let c32 = c as f32;
        assert_eq!(
            FresnelTerm::<f32, 1>::eval(&d32, c32),
            [0.0],
            "Dielectric f32 at {c:e}"
        );
        assert_eq!(
            FresnelTerm::<f64, 1>::eval(&d64, c),
            [0.0],
            "Dielectric f64 at {c:e}"
        );
        assert_eq!(k32.eval(c32), [0.0], "Conductor f32 at {c:e}");
        assert_eq!(k64.eval(c), [0.0], "Conductor f64 at {c:e}");
        // cos²θd a few ulp off c², as |h|²/4 is.
        for c2 in [c32 * c32, (c32 * c32).next_up(), (c32 * c32 * 1.000001)] {
            assert_eq!(
                FresnelTerm::<f32, 1>::eval_cos2(&d32, c32, c2),
                [0.0],
                "at {c:e}"
            );
            assert_eq!(k32.eval_cos2(c32, c2), [0.0], "at {c:e}");
        }
    }
}

proptest! {
    #![proptest_config(common::config(256))]

    /// `conductor(c, η, 0)` is `dielectric(c, η)` on both types, down to the smallest
    /// cosines (where `√(t₀² + 4η²k²)` and `c²` underflow) and over the whole IOR domain.
    #[test]
    fn conductor_without_k_is_dielectric_down_to_subnormal_cosines(
        i in 0usize..TINY_COSINES.len(), u in 0.0f64..=1.0, e in -4.0f64..=4.0, exact_one in any::<bool>()
    ) {
        let n = if exact_one { 1.0 } else { 10f64.powf(e) };
        for c in [TINY_COSINES[i], 10f64.powf(-300.0 * u), u] {
            let (a, b) = (conductor(c, n, 0.0), dielectric(c, n));
            prop_assert!((a - b).abs() <= 1e-12, "f64 at c = {c:e}, η = {n}: {a:e} vs {b:e}");
            let (c32, n32) = (c as f32, n as f32);
            let (a, b) = (conductor(c32, n32, 0.0), dielectric(c32, n32));
            prop_assert!((a - b).abs() <= 4e-6, "f32 at c = {c:e}, η = {n}: {a:e} vs {b:e}");
        }
    }

    /// `cos θt ∈ [0, 1]` for every relative IOR, small ones included (244 in f32 and
    /// 1.00004 in f64 at η = 1e-6 before), and accurate against `√(1 − (1 − c)(1 + c)/η²)`
    /// in f64 for the f32 result.
    #[test]
    fn cos_theta_t_stays_in_unit_interval(e in -8.0f64..=8.0, u in common::unit(), below in any::<bool>()) {
        let eta = 10f64.powf(e);
        // Cosines at and a few ulp below 1, where the small-η interface is not totally
        // reflecting, and uniform ones.
        let c = if below { 1.0 - 1e-16 * (u * 8.0).floor() } else { u };
        let a = dielectric_amplitudes(c, eta);
        prop_assert!((0.0..=1.0).contains(&a.cos_theta_t), "f64: cos θt = {:e} at c = {c}, η = {eta:e}", a.cos_theta_t);
        let (c32, eta32) = (c as f32, eta as f32);
        let a = dielectric_amplitudes(c32, eta32);
        prop_assert!((0.0..=1.0).contains(&a.cos_theta_t), "f32: cos θt = {:e} at c = {c32}, η = {eta32:e}", a.cos_theta_t);
        let (cc, ee) = (f64::from(c32), f64::from(eta32));
        let t2 = 1.0 - (1.0 - cc) * (1.0 + cc) / (ee * ee);
        if t2 >= 0.0 {
            let t = t2.sqrt();
            prop_assert!((f64::from(a.cos_theta_t) - t).abs() <= 1e-6 + 1e-6 * t,
                "f32: cos θt = {:e}, reference {t:e} at c = {c32}, η = {eta32:e}", a.cos_theta_t);
        } else {
            prop_assert_eq!(a.cos_theta_t, 0.0);
        }
    }
}

/// The `Dielectric` term takes `|cos θd|` and keeps `eta` (light arrives from the outside in
/// a BRDF), as its docs say; the free function flips to `1/eta` for a negative cosine.
#[test]
fn dielectric_term_takes_the_magnitude_and_does_not_flip() {
    let glass = Dielectric::new(1.5_f64).unwrap();
    let f = |c: f64| FresnelTerm::<f64, 1>::eval(&glass, c)[0];
    assert_eq!(f(-0.5), f(0.5));
    assert_eq!(f(-0.5), dielectric(0.5, 1.5));
    assert!((f(-0.5) - 0.0891).abs() < 1e-4, "{}", f(-0.5));
    assert_eq!(
        FresnelTerm::<f64, 1>::eval_cos2(&glass, -0.5, 0.25)[0],
        f(0.5)
    );
    // The free function sees the same interface from inside: total internal reflection.
    assert_eq!(dielectric(-0.5, 1.5), 1.0);
    // Continuous through 0: a rounding residue below zero does not switch to TIR.
    assert_eq!(f(-1e-9), f(1e-9));
}

/// Huge IORs: the free dielectric function is finite (≈ 1) where `η²` overflows, on both
/// types (it was NaN at `η = 1e20` in f32 and `1e300` in f64); the constructors reject them.
#[test]
fn huge_ior_dielectric_is_finite_and_rejected_by_constructors() {
    for c in [0.0f32, 1e-30, 1e-20, 0.5, 0.9, 1.0] {
        for eta in [1e20_f32, 3e38, f32::MAX] {
            let r = dielectric(c, eta);
            assert!(
                (0.0..=1.0).contains(&r) && r > 0.4,
                "f32 dielectric({c}, {eta:e}) = {r}"
            );
        }
    }
    for c in [0.0f64, 1e-300, 0.5, 0.9, 1.0] {
        let r = dielectric(c, 1e300);
        assert!(
            (0.0..=1.0).contains(&r) && r > 0.4,
            "f64 dielectric({c}, 1e300) = {r}"
        );
    }
    assert!((dielectric(0.9_f32, 1e20) - 1.0).abs() < 1e-6);
    assert!(matches!(
        Dielectric::new(1e20_f32),
        Err(Error::OutOfDomain {
            param: "eta",
            domain: "[1e-4, 1e4]",
            ..
        })
    ));
    assert!(matches!(
        Dielectric::new(1e300_f64),
        Err(Error::OutOfDomain { param: "eta", .. })
    ));
    assert_eq!(
        format!("{}", Dielectric::new(1e300_f64).unwrap_err()),
        "parameter `eta` = 1e300 is outside its domain [1e-4, 1e4]"
    );
}

/// The channel count of a Cook-Torrance model on a dielectric follows from the term: no
/// annotation is needed to evaluate it (this was E0284 when `Dielectric` implemented
/// `FresnelTerm` for every `N`), and widening keeps every bit.
#[test]
fn a_dielectric_model_infers_its_channel_count() {
    use brdf::masking::SmithSeparable;
    use brdf::models::{Brdf, CookTorrance};
    use brdf::ndf::Ggx;
    let w = brdf::Vec3::new(0.0, 0.6, 0.8);
    let ggx = Ggx::new(0.3).unwrap();
    let one = CookTorrance::new(ggx, Dielectric::new(1.5).unwrap(), SmithSeparable).eval(w, w);
    let rgb = CookTorrance::new(
        ggx,
        Dielectric::new(1.5).unwrap().channels::<3>(),
        SmithSeparable,
    )
    .eval(w, w);
    assert!(one[0] > 0.0 && one[0].is_finite());
    assert_eq!(rgb, [one[0]; 3]);
}

// ----------------------------------------------------------------------------------------
// SharedDivision: one division for all channels on F32FmaSharedDiv
// ----------------------------------------------------------------------------------------

/// A metal's channel in the `SharedDivision` domain: `k ∈ [0.1, 22]` log-uniform (the bound
/// included), `η ∈ [1e-4, 22]` log-uniform; the pair is kept inside
/// `η² + k² ≤ shared_division_max_norm(3)` by scaling it down onto the boundary.
fn shared_channel() -> impl Strategy<Value = (f64, f64)> {
    let k = prop_oneof![
        4 => (-1.0f64..=1.35).prop_map(|e| 10f64.powf(e)),
        1 => Just(SHARED_DIVISION_MIN_K),
    ];
    let eta = prop_oneof![
        4 => (-4.0f64..=1.35).prop_map(|e| 10f64.powf(e)),
        1 => Just(MIN_ETA),
    ];
    (eta, k).prop_map(|(eta, k)| {
        let max = shared_division_max_norm(3) * (1.0 - 1e-4);
        let norm = eta * eta + k * k;
        if norm <= max {
            (eta, k)
        } else {
            let s = (max / norm).sqrt();
            ((eta * s).max(MIN_ETA), (k * s).max(SHARED_DIVISION_MIN_K))
        }
    })
}

/// The conductor on `F32FmaSharedDiv` (one division) and on `F32Fma` (per channel), and
/// `fresnel::conductor` in f64, at one cosine.
fn shared_and_per_channel(channels: [(f64, f64); 3], c: f64) -> ([f32; 3], [f32; 3], [f64; 3]) {
    use brdf::real::{F32Fma, F32FmaSharedDiv, Splat};
    let eta = channels.map(|(e, _)| e as f32);
    let k = channels.map(|(_, k)| k as f32);
    let per_channel = Conductor::<f32, 3>::new(eta, k).unwrap();
    let shared = per_channel.share_divisions().unwrap();
    let c32 = c as f32;
    let a = shared
        .splat::<F32FmaSharedDiv>()
        .eval(F32FmaSharedDiv(c32))
        .map(|v| v.0);
    let b = per_channel.splat::<F32Fma>().eval(F32Fma(c32)).map(|v| v.0);
    let exact = core::array::from_fn(|i| {
        fresnel::conductor(f64::from(c32), f64::from(eta[i]), f64::from(k[i]))
    });
    (a, b, exact)
}

proptest! {
    #![proptest_config(common::config(4000))]

    /// On `F32FmaSharedDiv` the channels share one division: finite over the whole domain
    /// (grazing and normal incidence, the smallest `k` and `η`, the largest `η² + k²`),
    /// within 8 ULP of the per-channel form and within 2e-6 relative of f64.
    #[test]
    fn shared_division_matches_per_channel(
        ch in [shared_channel(), shared_channel(), shared_channel()],
        c in prop_oneof![4 => common::cos_theta(), 1 => Just(0.0), 1 => Just(1.0)],
    ) {
        let (shared, per_channel, exact) = shared_and_per_channel(ch, c);
        for i in 0..3 {
            prop_assert!(shared[i].is_finite() && (0.0..=1.0).contains(&shared[i]),
                "channel {i}: {} at {ch:?}, c {c}", shared[i]);
            let ulps = common::ulps(shared[i], per_channel[i]);
            prop_assert!(ulps <= 8, "channel {i}: {} vs {} ({ulps} ULP) at {ch:?}, c {c}",
                shared[i], per_channel[i]);
            let rel = (f64::from(shared[i]) - exact[i]).abs() / exact[i];
            prop_assert!(rel <= 2e-6, "channel {i}: {rel:e} from f64 at {ch:?}, c {c}");
        }
    }
}

/// The corners of the domain (smallest and largest `η` and `k` that `share_divisions`
/// accepts, mixed across channels so the denominators are as unequal as they get) at the
/// end points and a dense sweep of the cosine.
#[test]
fn shared_division_at_the_corners_of_its_domain() {
    let max = shared_division_max_norm(3) * (1.0 - 1e-4);
    let corners = [
        (MIN_ETA, SHARED_DIVISION_MIN_K),
        (MIN_ETA, max.sqrt()),
        (max.sqrt(), SHARED_DIVISION_MIN_K),
        ((max / 2.0).sqrt(), (max / 2.0).sqrt()),
        (1.0, SHARED_DIVISION_MIN_K),
        (0.143, 3.983),
    ];
    let mut worst = (0u64, 0.0f64);
    for a in corners {
        for b in corners {
            for d in corners {
                for j in 0..=200 {
                    let c = (f64::from(j) / 200.0).powi(3);
                    let (shared, per_channel, exact) = shared_and_per_channel([a, b, d], c);
                    for i in 0..3 {
                        assert!(shared[i].is_finite(), "{a:?} {b:?} {d:?} c {c}");
                        let rel = (f64::from(shared[i]) - exact[i]).abs() / exact[i];
                        worst.0 = worst.0.max(common::ulps(shared[i], per_channel[i]));
                        worst.1 = worst.1.max(rel);
                    }
                }
            }
        }
    }
    eprintln!(
        "shared division at the corners: {} ULP from per-channel, {:.2e} from f64",
        worst.0, worst.1
    );
    assert!(worst.0 <= 8 && worst.1 <= 2e-6, "{worst:?}");
}

/// Off `F32FmaSharedDiv` a `SharedDivision` conductor is the per-channel one, bit for bit.
#[test]
fn shared_division_is_per_channel_on_other_types() {
    use brdf::real::{F32Fma, Splat};
    let gold = Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap();
    let shared = gold.share_divisions().unwrap();
    for j in 0..=100 {
        let c = f64::from(j) / 100.0;
        let c32 = c as f32;
        assert_eq!(shared.eval(c32), gold.eval(c32));
        assert_eq!(
            shared.splat::<F32Fma>().eval(F32Fma(c32)),
            gold.splat::<F32Fma>().eval(F32Fma(c32))
        );
        assert_eq!(shared.splat::<f64>().eval(c), gold.splat::<f64>().eval(c));
        let l = brdf::f32x8::splat(c32);
        assert_eq!(
            shared.splat::<brdf::f32x8>().eval(l),
            gold.splat::<brdf::f32x8>().eval(l)
        );
    }
}

/// `share_divisions` rejects a dielectric-like channel and an IOR too large for the shared
/// product, naming the parameter; it accepts the metals of `ior`.
#[test]
fn share_divisions_validates_its_domain() {
    let err = Conductor::<f32, 3>::new([1.5, 0.2, 0.2], [0.0, 3.0, 3.0])
        .unwrap()
        .share_divisions()
        .unwrap_err();
    assert!(err.to_string().contains("k"), "{err}");
    let err = Conductor::<f32, 3>::new([0.2, 0.2, 0.2], [3.0, 3.0, 0.099])
        .unwrap()
        .share_divisions()
        .unwrap_err();
    assert!(err.to_string().contains("k"), "{err}");
    let err = Conductor::<f64, 3>::new([0.2, 0.2, 0.2], [3.0, 30.0, 3.0])
        .unwrap()
        .share_divisions()
        .unwrap_err();
    assert!(err.to_string().contains("eta² + k²"), "{err}");
    // Two channels allow larger IORs, four smaller ones.
    assert!(
        Conductor::<f64, 2>::new([0.2, 0.2], [3.0, 30.0])
            .unwrap()
            .share_divisions()
            .is_ok()
    );
    assert!(
        Conductor::<f64, 4>::new([0.2; 4], [3.0, 3.0, 3.0, 10.5])
            .unwrap()
            .share_divisions()
            .is_err()
    );
    for name in [
        "gold",
        "silver",
        "copper",
        "aluminium",
        "iron",
        "titanium",
        "chromium",
    ] {
        let preset = ior::Preset::from_name(name).unwrap();
        assert!(
            Conductor::<f32, 3>::from_preset(preset)
                .unwrap()
                .share_divisions()
                .is_ok(),
            "{name}"
        );
    }
}

/// `SharedDivision` composes with the Newton policy: the one shared reciprocal is
/// `fast::recip::<3>` of the product, and the result stays within the Newton policy's own
/// bound (`NewtonSqrtRecip<3, 3>`: 9.5e-7 relative of the exact path) plus the sharing's.
#[test]
fn shared_division_with_the_newton_policy() {
    use brdf::fast::NewtonSqrtRecip;
    use brdf::real::{F32FmaSharedDiv, Splat};
    for preset in ior::Preset::METALS {
        let exact = Conductor::<f64, 3>::from_preset(preset).unwrap();
        let fast = Conductor::<f32, 3>::from_preset(preset)
            .unwrap()
            .with_policy::<NewtonSqrtRecip<3, 3>>()
            .share_divisions()
            .unwrap()
            .splat::<F32FmaSharedDiv>();
        for j in 0..=400 {
            let c = (f64::from(j) / 400.0).powi(2);
            let (a, b) = (
                fast.eval(F32FmaSharedDiv(c as f32)),
                exact.eval(f64::from(c as f32)),
            );
            for i in 0..3 {
                let rel = (f64::from(a[i].0) - b[i]).abs() / b[i];
                assert!(rel <= 2e-6, "{preset:?} channel {i} at c {c}: {rel:e}");
            }
        }
    }
}
