//! Tests of `brdf::normalization`: every closed form against an independent quadrature,
//! domain properties on f32 and f64, the fit's error table and optimum, per-material and
//! per-level precomputation, and SIMD-lane equivalence.
mod common;

use approx::assert_abs_diff_eq;

use std::f64::consts::{FRAC_PI_2, PI};

use brdf::Error;
use brdf::ndf::MAX_SHININESS;
use brdf::normalization::fit::*;
use brdf::normalization::*;
use proptest::prelude::*;

// ---------------------------------------------------------------------------------------
// Independent quadrature over the hemisphere.
// ---------------------------------------------------------------------------------------

/// `2π ∫₀^{π/2} g(θ) sin θ dθ` for an azimuth-independent integrand, by composite
/// Gauss-Legendre with panel breaks at multiples of the lobe width `width` (the integrand
/// is a peak of that width at θ = 0 for large exponents).
fn hemisphere_integral(g: impl Fn(f64) -> f64, width: f64) -> f64 {
    let mut breaks = vec![0.0];
    if width < 0.5 {
        for k in [
            0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0, 24.0, 32.0, 48.0, 64.0,
        ] {
            let b = k * width;
            if b < FRAC_PI_2 {
                breaks.push(b);
            }
        }
    }
    // Geometric grading towards θ = π/2, where cos^s θ with s < 1 has an unbounded
    // derivative (Gauss-Legendre then needs small panels at the end point).
    for k in 1..=40 {
        let b = FRAC_PI_2 - 0.5f64.powi(k);
        if b > *breaks.last().unwrap() {
            breaks.push(b);
        }
    }
    breaks.push(FRAC_PI_2);
    2.0 * PI * common::integrate_pieces(|t| g(t) * t.sin(), &breaks, 2, 24)
}

/// Light at normal incidence `L = N = (0,0,1)`, viewer `V = (sin θ, 0, cos θ)`: `N·H` from
/// the normalized vector sum (not from the half-angle identity the derivation uses).
fn n_dot_h(theta: f64) -> f64 {
    let (x, z) = (theta.sin(), 1.0 + theta.cos());
    z / (x * x + z * z).sqrt()
}

/// Width of `(N·H)^s = cos^s(θ/2) ≈ exp(−sθ²/8)`.
fn half_angle_width(s: f64) -> f64 {
    2.0 / s.max(1e-300).sqrt()
}

/// Shininess values for the quadrature checks: 0 to 10⁶.
const QUAD_S: [f64; 23] = [
    0.0, 1e-7, 0.1, 0.5, 1.0, 2.0, 2.04, 3.0, 4.0, 7.5, 8.0, 16.0, 22.75, 32.0, 64.0, 100.0, 128.0,
    256.0, 1024.0, 1e4, 1e5, 3e5, 1e6,
];

/// Relative agreement demanded between closed forms and the quadrature.
const QUAD_TOL: f64 = 1e-9;

fn rel(a: f64, b: f64) -> f64 {
    if a == b { 0.0 } else { (a - b).abs() / b.abs() }
}

#[test]
fn tri_ace_integral_matches_quadrature() {
    let mut worst = 0.0f64;
    for s in QUAD_S {
        let q = hemisphere_integral(|t| n_dot_h(t).powf(s), half_angle_width(s));
        let (i, c, n0) = (
            tri_ace_integral(s),
            tri_ace_exact(s),
            tri_ace_exact_offset(s),
        );
        let e = rel(i, q)
            .max(rel(1.0 / c, q))
            .max(rel(s + n0, 8.0 * PI / q));
        assert!(
            e <= QUAD_TOL,
            "s = {s}: integral {i:e} exact⁻¹ {:e} quadrature {q:e}",
            1.0 / c
        );
        worst = worst.max(e);
    }
    println!("tri-Ace integral vs quadrature: worst relative {worst:.2e}");
}

#[test]
fn the_ocr_sign_drop_is_not_the_integral() {
    // The slides' 4π(2 − 2^(+s/2))/(s + 2) would be negative for s > 2: impossible for the
    // integral of a positive function. The minus sign of the appendix is right.
    let s = 4.0;
    let q = hemisphere_integral(|t| n_dot_h(t).powf(s), half_angle_width(s));
    let dropped = 4.0 * PI * (2.0 - 2f64.powf(s / 2.0)) / (s + 2.0);
    assert!(dropped < 0.0 && q > 0.0);
    assert!(rel(tri_ace_integral(s), q) < QUAD_TOL);
}

#[test]
fn blinn_phong_cosine_exact_matches_quadrature() {
    // ∫ (N·H)^s (N·L) dω_L with V = N: same geometry with the roles of L and V swapped.
    let mut worst = 0.0f64;
    for s in QUAD_S {
        let q = hemisphere_integral(|t| n_dot_h(t).powf(s) * t.cos(), half_angle_width(s));
        let e = rel(1.0 / blinn_phong_cosine_exact(s), q);
        assert!(e <= QUAD_TOL, "s = {s}: {e:e}");
        worst = worst.max(e);
    }
    println!("Giesen cosine-weighted vs quadrature: worst relative {worst:.2e}");
}

#[test]
fn ndf_and_phong_factors_match_quadrature() {
    let mut worst = 0.0f64;
    for s in QUAD_S {
        let w = 1.0 / s.max(1e-300).sqrt();
        // Blinn-Phong NDF: ∫ cos^s θm cos θm dωm.
        let ndf = hemisphere_integral(|t| t.cos().powf(s) * t.cos(), w);
        // Phong lobe around R = N (L = N): ∫ (R·V)^s dωV and ∫ (R·V)^s (N·V) dωV, with R
        // computed as the reflection of L = (0,0,1) about N: R = 2(N·L)N − L = (0,0,1).
        let r_dot_v = |t: f64| {
            let (lx, lz) = (0.0, 1.0);
            let (rx, rz) = (2.0 * lz * 0.0 - lx, 2.0 * lz * 1.0 - lz);
            rx * t.sin() + rz * t.cos()
        };
        let lobe = hemisphere_integral(|t| r_dot_v(t).powf(s), w);
        let cosine = hemisphere_integral(|t| r_dot_v(t).powf(s) * t.cos(), w);
        for (name, closed, q) in [
            ("blinn_phong_ndf", blinn_phong_ndf(s), ndf),
            ("phong_lobe", phong_lobe(s), lobe),
            ("phong_cosine", phong_cosine(s), cosine),
        ] {
            let e = rel(1.0 / closed, q);
            assert!(e <= QUAD_TOL, "{name} s = {s}: {e:e}");
            worst = worst.max(e);
        }
    }
    println!("NDF / Phong factors vs quadrature: worst relative {worst:.2e}");
}

#[test]
fn precomputed_lobes_are_normalized_by_quadrature() {
    // The per-material lobe, integrated as the seed does (L = N, over V): exactly 1.
    for s in [0.0, 1.0, 7.0, 64.0, 1e4] {
        let lobe = BlinnPhongLobe::new(s, Normalization::TriAceExact).unwrap();
        let total = hemisphere_integral(|t| lobe.eval(n_dot_h(t)), half_angle_width(s));
        assert!((total - 1.0).abs() < 1e-9, "tri-Ace s = {s}: {total}");
        let lobe = BlinnPhongLobe::new(s, Normalization::BlinnPhongCosineExact).unwrap();
        let total = hemisphere_integral(|t| lobe.eval(n_dot_h(t)) * t.cos(), half_angle_width(s));
        assert!((total - 1.0).abs() < 1e-9, "cosine-exact s = {s}: {total}");
    }
}

// ---------------------------------------------------------------------------------------
// Domain properties on f32 and f64.
// ---------------------------------------------------------------------------------------

/// Shininess over [0, 10⁹] and beyond (log-uniform), with 0 and 1e-7 drawn often.
fn shininess() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        1 => Just(1e-7),
        1 => Just(1e9),
        3 => 0.0f64..4.0,
        6 => (-7.0f64..9.0).prop_map(|e| 10f64.powf(e)),
        2 => (9.0f64..30.0).prop_map(|e| 10f64.powf(e)),
    ]
}

type Formula<S> = (&'static str, fn(S) -> S);

fn formulas<S: brdf::Scalar>() -> [Formula<S>; 9] {
    [
        ("tri_ace_exact", tri_ace_exact::<S>),
        ("tri_ace_fit", |s| tri_ace_fit(s, S::of(TRI_ACE_OFFSET))),
        ("tri_ace_exact_offset", tri_ace_exact_offset::<S>),
        ("tri_ace_2010_fit", tri_ace_2010_fit::<S>),
        ("blinn_phong_ndf", blinn_phong_ndf::<S>),
        ("blinn_phong_cosine_exact", blinn_phong_cosine_exact::<S>),
        ("blinn_phong_rtr_approx", blinn_phong_rtr_approx::<S>),
        ("phong_lobe", phong_lobe::<S>),
        ("phong_cosine", phong_cosine::<S>),
    ]
}

/// Finite, positive, and (except the offset n₀, which decreases) non-decreasing in `s`;
/// the integral is finite, positive and non-increasing.
fn check_domain<S: brdf::Scalar>(s1: f64, s2: f64) -> Result<(), TestCaseError> {
    let (a, b) = (S::of(s1.min(s2)), S::of(s1.max(s2)));
    let slack = 8.0 * Into::<f64>::into(S::EPSILON);
    for (name, f) in formulas::<S>() {
        let (fa, fb): (f64, f64) = (f(a).into(), f(b).into());
        prop_assert!(fa.is_finite() && fa > 0.0, "{name}({a:?}) = {fa}");
        prop_assert!(fb.is_finite() && fb > 0.0, "{name}({b:?}) = {fb}");
        if name == "tri_ace_exact_offset" {
            prop_assert!(fb <= fa * (1.0 + slack), "{name} increases: {fa} → {fb}");
            prop_assert!(
                fa >= 2.0 * (1.0 - slack) && fa <= 4.0 * (1.0 + slack),
                "{name}({a:?}) = {fa} ∉ [2, 4]"
            );
        } else {
            prop_assert!(fb >= fa * (1.0 - slack), "{name} decreases: {fa} → {fb}");
        }
    }
    let (ia, ib): (f64, f64) = (tri_ace_integral(a).into(), tri_ace_integral(b).into());
    prop_assert!(ia.is_finite() && ia >= 0.0 && ib.is_finite() && ib >= 0.0);
    prop_assert!(ib <= ia * (1.0 + slack), "integral increases: {ia} → {ib}");
    // Sandwiches from the derivations: (s+2)/(8π) < c(s) ≤ (s+4)/(8π); the cosine-exact
    // factor lies between (s+2)/(8π) and the RTR approximation (s+8)/(8π).
    let s: f64 = a.into();
    let c: f64 = tri_ace_exact(a).into();
    let g: f64 = blinn_phong_cosine_exact(a).into();
    let rtr: f64 = blinn_phong_rtr_approx(a).into();
    let lo = (s + 2.0) / (8.0 * PI);
    prop_assert!(c >= lo * (1.0 - slack) && c <= (s + 4.0) / (8.0 * PI) * (1.0 + slack));
    prop_assert!(
        g >= lo * (1.0 - slack) && g <= rtr * (1.0 + slack),
        "{g} vs {rtr}"
    );
    Ok(())
}

proptest! {
    #![proptest_config(common::config(256))]

    #[test]
    fn factors_are_finite_positive_and_monotone_f64(s1 in shininess(), s2 in shininess()) {
        check_domain::<f64>(s1, s2)?;
    }

    #[test]
    fn factors_are_finite_positive_and_monotone_f32(s1 in shininess(), s2 in shininess()) {
        check_domain::<f32>(s1.min(1e37), s2.min(1e37))?;
    }

    #[test]
    fn lobe_is_finite_and_bounded_by_its_factor(s in shininess(), c in common::cos_theta()) {
        // The lobe's domain ends at MAX_SHININESS (the factor functions above take any s).
        let s = s.min(MAX_SHININESS);
        for n in [Normalization::TriAceExact, Normalization::TRI_ACE_2009_FIT] {
            let lobe = BlinnPhongLobe::new(s, n).unwrap();
            let v = lobe.eval(c);
            prop_assert!(v.is_finite() && v >= 0.0 && v <= lobe.factor());
            let lobe32 = BlinnPhongLobe::new(s as f32, n).unwrap();
            let v32 = lobe32.eval(c as f32);
            prop_assert!(v32.is_finite() && v32 >= 0.0 && v32 <= lobe32.factor());
            prop_assert_eq!(lobe.eval(-c), if s == 0.0 { lobe.factor() } else { 0.0 });
        }
    }

    #[test]
    fn fit_error_equals_the_direct_ratio(s in shininess(), n in 0.0f64..5.0) {
        // The cancellation-free (n − n₀)/(s + n₀) against fit/exact − 1 computed naively:
        // the naive ratio carries ~8 roundings of relative size ε/2 on a quantity 1 + e.
        let s = s.min(1e12);
        let e = fit_error(n, s, s).unwrap();
        let direct = tri_ace_fit(s, n) / tri_ace_exact(s) - 1.0;
        prop_assert!((e.highest - direct).abs() <= 8.0 * f64::EPSILON * (1.0 + direct.abs()),
            "s = {s}, n = {n}: {} vs {direct}", e.highest);
        prop_assert_eq!(e.highest, e.lowest);
    }
}

#[test]
fn limits_at_zero_and_infinity() {
    // Values at s = 0 from the closed forms: 1/(2π), 1/π, ...
    assert!(rel(tri_ace_exact(0.0), 1.0 / (2.0 * PI)) < 1e-16);
    assert!(rel(tri_ace_integral(0.0), 2.0 * PI) < 1e-16);
    assert_eq!(tri_ace_exact_offset(0.0), 4.0);
    assert!(rel(blinn_phong_cosine_exact(0.0), 1.0 / PI) < 1e-16);
    assert!(rel(blinn_phong_rtr_approx(0.0), 1.0 / PI) < 1e-16);
    assert!(rel(tri_ace_exact(1e-7_f32) as f64, 1.0 / (2.0 * PI)) < 1e-6);
    // Large s: the slope is exactly 1/(8π) and n₀ → 2.
    assert_eq!(tri_ace_exact_offset(1e9_f64), 2.0);
    assert!(rel(tri_ace_exact(1e9), (1e9 + 2.0) / (8.0 * PI)) < 1e-15);
    assert!(rel(blinn_phong_cosine_exact(1e9), (1e9 + 6.0) / (8.0 * PI)) < 1e-15);
    assert_eq!(tri_ace_integral(f64::INFINITY), 0.0);
    assert_eq!(tri_ace_exact(f32::INFINITY), f32::INFINITY);
    for s in [f32::MAX, 3e38] {
        for (name, f) in formulas::<f32>() {
            assert!(f(s).is_finite(), "{name}({s})");
        }
    }
}

// ---------------------------------------------------------------------------------------
// The fit: documented table, error search, optimum.
// ---------------------------------------------------------------------------------------

/// Parses `| s | exact | fit | error |` rows between the fit-table markers of the module
/// documentation, so the published table cannot drift from the functions.
#[test]
fn documented_fit_table_matches_the_functions() {
    let src = include_str!("../src/normalization.rs");
    let begin = src.find("<!-- fit-table:begin -->").expect("table start");
    let end = src.find("<!-- fit-table:end -->").expect("table end");
    let mut rows = 0;
    for line in src[begin..end].lines().skip(3) {
        let cells: Vec<f64> = line
            .trim_start_matches("//!")
            .split('|')
            .map(str::trim)
            .filter(|c| !c.is_empty())
            .map(|c| {
                c.parse()
                    .unwrap_or_else(|_| panic!("cell {c:?} in {line:?}"))
            })
            .collect();
        if cells.is_empty() {
            continue;
        }
        let [s, exact, fit, err] = cells[..] else {
            panic!("row {line:?}")
        };
        let (c, f) = (tri_ace_exact(s), tri_ace_fit(s, TRI_ACE_OFFSET));
        let e = fit_error(TRI_ACE_OFFSET, s, s).unwrap().highest;
        // Printed with 8 significant digits (5 for the error): half a unit in the last place.
        assert!(rel(exact, c) <= 5e-8, "exact at s = {s}: {exact} vs {c}");
        assert!(rel(fit, f) <= 5e-8, "fit at s = {s}: {fit} vs {f}");
        assert!(rel(err, e) <= 5e-5, "error at s = {s}: {err} vs {e}");
        assert!(rel(err, f / c - 1.0) <= 1e-4, "error at s = {s}");
        rows += 1;
    }
    assert_eq!(rows, 13, "the table lists s = 0, 1, 2, 4, …, 10⁶");
}

/// Brute-force extremes of the fit error on a dense log + linear scan.
fn scan(offset: f64, a: f64, b: f64) -> (f64, f64) {
    let n = 20_000;
    let (la, lb) = ((1.0 + a).ln(), (1.0 + b).ln());
    let mut hi = f64::NEG_INFINITY;
    let mut lo = f64::INFINITY;
    for i in 0..=n {
        let t = i as f64 / n as f64;
        for s in [
            ((la + (lb - la) * t).exp() - 1.0).clamp(a, b),
            a + (b - a) * t,
        ] {
            let e = tri_ace_fit(s, offset) / tri_ace_exact(s) - 1.0;
            hi = hi.max(e);
            lo = lo.min(e);
        }
    }
    (hi, lo)
}

#[test]
fn fit_error_finds_the_global_extremes() {
    let ranges = [
        (0.0, 1e4),
        (14.0, 1e4),
        (5.0, 30.0),
        (0.0, 3.0),
        (100.0, 1e6),
        (20.0, 25.0),
    ];
    for (a, b) in ranges {
        for n in [0.0, 1.5, 2.0, 2.04, 2.5, 3.0, 3.5, 4.0, 5.0] {
            let e = fit_error(n, a, b).unwrap();
            let (hi, lo) = scan(n, a, b);
            let tol = 1e-12 + 1e-9 * hi.abs().max(lo.abs());
            // The search is at least as good as the scan, and not better than the truth:
            // the scan's extremes are within O(h²) of the true ones.
            assert!(
                e.highest >= hi - tol && e.highest <= hi + 1e-6 * hi.abs() + 1e-12,
                "n = {n} [{a}, {b}]: highest {} vs scan {hi}",
                e.highest
            );
            assert!(
                e.lowest <= lo + tol && e.lowest >= lo - 1e-6 * lo.abs() - 1e-12,
                "n = {n} [{a}, {b}]: lowest {} vs scan {lo}",
                e.lowest
            );
            assert_eq!(e.max_rel_error, e.highest.abs().max(e.lowest.abs()));
            for (v, at) in [(e.highest, e.highest_at), (e.lowest, e.lowest_at)] {
                assert!((a..=b).contains(&at));
                assert!((tri_ace_fit(at, n) / tri_ace_exact(at) - 1.0 - v).abs() < 1e-14);
            }
        }
    }
}

#[test]
fn error_shape_is_rising_then_falling_for_offsets_in_2_to_4() {
    // The search relies on e(s) having at most one interior maximum for 2 < n ≤ 4 and
    // being increasing for n ≤ 2. Count sign changes of a dense finite-difference slope.
    for n in [1.0, 2.0, 2.01, 2.04, 2.5, 3.0, 3.5, 4.0] {
        let mut changes = 0;
        let mut prev: Option<bool> = None;
        let mut s = 0.0;
        while s < 400.0 {
            let e = |s: f64| {
                let n0 = tri_ace_exact_offset(s);
                (n - n0) / (s + n0)
            };
            let d = e(s + 0.01) - e(s);
            let sign = d > 0.0;
            if d.abs() > 1e-15 {
                if let Some(p) = prev
                    && p != sign
                {
                    changes += 1;
                    assert!(p, "n = {n}: the error has an interior minimum near s = {s}");
                }
                prev = Some(sign);
            }
            s += 0.01;
        }
        assert!(changes <= 1, "n = {n}: {changes} slope sign changes");
        assert_eq!(changes == 1, n > 2.0, "n = {n}");
    }
}

#[test]
fn best_offset_is_minimax_optimal() {
    for (a, b) in [
        (0.0, 1e4),
        (2.0, 1e4),
        (8.0, 1e4),
        (14.0, 1e4),
        (16.0, 1e6),
        (5.0, 30.0),
        (7.0, 7.0),
    ] {
        let best = best_fit_offset(a, b).unwrap();
        // Equioscillation: over- and underestimate balance (unless the range is a point).
        assert!(
            (best.highest + best.lowest).abs() <= 1e-12,
            "[{a}, {b}]: {} vs {}",
            best.highest,
            best.lowest
        );
        // Any other offset is worse.
        for d in [1e-6, 1e-3, 0.1] {
            for n in [best.offset - d, best.offset + d] {
                let e = fit_error(n, a, b).unwrap().max_rel_error;
                assert!(
                    e > best.max_rel_error,
                    "[{a}, {b}] n = {n}: {e} ≤ {}",
                    best.max_rel_error
                );
            }
        }
        assert!((2.0..=4.0).contains(&best.offset));
    }
    // A single point: the exact offset, zero error.
    let p = best_fit_offset(7.0, 7.0).unwrap();
    assert!((p.offset - tri_ace_exact_offset(7.0)).abs() < 1e-13 && p.max_rel_error < 1e-14);
}

#[test]
fn the_talks_offset_is_optimal_for_shininess_from_14() {
    // Independent check: the brute-force scan of the error of n = 2.04 over [14, 10⁴] is
    // nearly balanced (over- and underestimate within 1 % of each other), so 2.04 is
    // (almost) the minimax offset there; exactly so for s_min ≈ 13.99.
    let (hi, lo) = scan(TRI_ACE_OFFSET, 14.0, 1e4);
    assert!((hi + lo).abs() < 0.01 * hi, "scan: +{hi} / {lo}");
    let (hi2, lo2) = scan(TRI_ACE_OFFSET, 13.99, 1e4);
    assert!((hi2 + lo2).abs() < 1e-3 * hi2, "scan: +{hi2} / {lo2}");
    assert!((hi - 1.428e-3).abs() < 1e-6, "{hi}");
    let best = best_fit_offset(14.0, 1e4).unwrap();
    assert!((best.offset - TRI_ACE_OFFSET).abs() < 2e-4, "{best:?}");
    assert!((best.max_rel_error - 1.423e-3).abs() < 1e-6, "{best:?}");
    // The talk's fit over [14, ∞): worst +0.143 % near s = 22.75.
    let talk = fit_error(TRI_ACE_OFFSET, 14.0, 1e9).unwrap();
    assert!((talk.max_rel_error - 1.4276e-3).abs() < 1e-7, "{talk:?}");
    assert!((talk.at_shininess - 22.75).abs() < 0.05, "{talk:?}");
    // Documented optima by lower end (s_max large); the upper end does not matter.
    for (a, n, err) in [
        (0.0, 3.528, 0.118),
        (2.0, 2.984, 0.0655),
        (8.0, 2.218, 0.0101),
        (16.0, 2.022, 7.3e-4),
    ] {
        for b in [64.0, 1e4, 1e9] {
            let best = best_fit_offset(a, b).unwrap();
            assert!((best.offset - n).abs() < 5e-4, "[{a}, {b}]: {best:?}");
            assert!(rel(best.max_rel_error, err) < 0.02, "[{a}, {b}]: {best:?}");
        }
    }
    // Over the whole range the talk's fit is off by 49 % (at s = 0).
    let all = fit_error(TRI_ACE_OFFSET, 0.0, 1e6).unwrap();
    assert!((all.max_rel_error - 0.49).abs() < 1e-12 && all.at_shininess == 0.0);
}

#[test]
fn fit_analysis_rejects_bad_ranges() {
    assert_eq!(
        fit_error(f64::NAN, 0.0, 1.0),
        Err(Error::NotFinite { param: "offset" })
    );
    assert_eq!(
        best_fit_offset(f64::NAN, 1.0),
        Err(Error::NotFinite { param: "s_min" })
    );
    assert!(matches!(
        best_fit_offset(-1.0, 1.0),
        Err(Error::OutOfDomain { param: "s_min", .. })
    ));
    assert!(matches!(
        best_fit_offset(2.0, 1.0),
        Err(Error::OutOfDomain { param: "s_max", .. })
    ));
    assert_eq!(
        best_fit_offset(0.0, f64::INFINITY),
        Err(Error::NotFinite { param: "s_max" })
    );
}

// ---------------------------------------------------------------------------------------
// Per-material and per-level precomputation.
// ---------------------------------------------------------------------------------------

#[test]
fn lobe_constructor_validates_once() {
    let bad = [
        f32::NAN,
        f32::INFINITY,
        -1.0,
        -1e-30,
        (MAX_SHININESS as f32).next_up(),
        1e9,
    ];
    for s in bad {
        let e = BlinnPhongLobe::new(s, Normalization::TriAceExact).unwrap_err();
        assert!(
            matches!(
                e,
                Error::NotFinite { param: "shininess" }
                    | Error::OutOfDomain {
                        param: "shininess",
                        ..
                    }
            ),
            "{s}: {e:?}"
        );
    }
    for offset in [f64::NAN, -0.5] {
        let e = BlinnPhongLobe::new(8.0f64, Normalization::TriAceFit { offset }).unwrap_err();
        assert!(matches!(
            e,
            Error::NotFinite { param: "offset" }
                | Error::OutOfDomain {
                    param: "offset",
                    ..
                }
        ));
    }
    let lobe = BlinnPhongLobe::new(0.0f64, Normalization::TRI_ACE_2009_FIT).unwrap();
    assert_eq!(lobe.shininess(), 0.0);
    assert_eq!(lobe.factor(), TRI_ACE_OFFSET / (8.0 * PI));
    assert_eq!(lobe.normalization(), Normalization::TRI_ACE_2009_FIT);
    assert_eq!(
        lobe.eval(0.0),
        lobe.factor(),
        "0⁰ = 1: the s = 0 lobe is constant"
    );
    // The sharpest accepted lobe: a mirror to f32 directions.
    let lobe = BlinnPhongLobe::new(MAX_SHININESS as f32, Normalization::Unnormalized).unwrap();
    assert_eq!(
        (lobe.factor(), lobe.eval(1.0f32), lobe.eval(0.999_999f32)),
        (1.0, 1.0, 0.0)
    );
}

#[test]
fn normalization_variants_name_their_functions() {
    for s in [0.0, 1e-7, 2.04, 100.0, 1e6] {
        let cases: [(Normalization, f64); 9] = [
            (Normalization::Unnormalized, 1.0),
            (Normalization::TriAceExact, tri_ace_exact(s)),
            (
                Normalization::TriAceFit { offset: 3.0 },
                tri_ace_fit(s, 3.0),
            ),
            (Normalization::TriAce2010Fit, tri_ace_2010_fit(s)),
            (Normalization::BlinnPhongNdf, blinn_phong_ndf(s)),
            (
                Normalization::BlinnPhongCosineExact,
                blinn_phong_cosine_exact(s),
            ),
            (
                Normalization::BlinnPhongRtrApprox,
                blinn_phong_rtr_approx(s),
            ),
            (Normalization::PhongLobe, phong_lobe(s)),
            (Normalization::PhongCosine, phong_cosine(s)),
        ];
        for (n, v) in cases {
            assert_eq!(n.factor(s), v, "{n:?}");
        }
    }
    // The 2010 fit in the (k s + n)/(8π) form.
    let k = 0.0397436 * 8.0 * PI;
    assert!((k - 0.998866).abs() < 1e-6 && (0.0856832 * 8.0 * PI - 2.15345).abs() < 1e-5);
}

#[test]
fn table_entries_are_the_factors_at_their_levels() {
    let t = NormalizationTable::<256>::new(Normalization::TriAceExact, 0.0, 255.0).unwrap();
    assert_eq!(t.range(), (0.0, 255.0));
    assert_eq!(t.normalization(), Normalization::TriAceExact);
    for i in 0..256 {
        assert_eq!(t.shininess_at(i), i as f32);
        assert_eq!(t.get(i), tri_ace_exact(i as f64) as f32);
        assert_eq!(
            t.lookup(i as f32),
            t.get(i),
            "a lookup at a node returns the node"
        );
    }
    assert_eq!(t.values().len(), 256);
    assert_eq!(t.lookup(-5.0), t.get(0));
    assert_eq!(t.lookup(1e9), t.get(255));
    assert_eq!(t.lookup(f32::NAN), t.get(0));
    let mut buf = [0.0f32; 5];
    fill_table(Normalization::BlinnPhongNdf, 2.0, 6.0, &mut buf).unwrap();
    assert_eq!(
        buf,
        [2.0, 3.0, 4.0, 5.0, 6.0].map(|s: f64| blinn_phong_ndf(s) as f32)
    );
    let mut one = [0.0f32; 1];
    fill_table(Normalization::TriAceExact, 3.0, 3.0, &mut one).unwrap();
    assert_eq!(one[0], tri_ace_exact(3.0f64) as f32);
    fill_table(Normalization::TriAceExact, 0.0, 1.0, &mut []).unwrap();
    let bad = NormalizationTable::<4>::new(Normalization::TriAceExact, 5.0, 5.0);
    assert!(matches!(
        bad,
        Err(Error::OutOfDomain { param: "s_max", .. })
    ));
    let bad = NormalizationTable::<4>::new(Normalization::TriAceFit { offset: -1.0 }, 0.0, 5.0);
    assert!(matches!(
        bad,
        Err(Error::OutOfDomain {
            param: "offset",
            ..
        })
    ));
    assert!(fill_table(Normalization::TriAceExact, f64::NAN, 1.0, &mut buf).is_err());
}

/// `n₀''` by central differences (n₀ is smooth; h = 1e-3 gives ~1e-7 absolute accuracy).
fn n0_second_derivative(s: f64) -> f64 {
    let h = 1e-3;
    let s = s.max(h);
    (tri_ace_exact_offset(s + h) - 2.0 * tri_ace_exact_offset(s) + tri_ace_exact_offset(s - h))
        / (h * h)
}

#[test]
fn table_interpolation_error_is_within_its_bound() {
    // Linear interpolation error of c(s) = (s + n₀(s))/(8π) on a cell of width h:
    // |c − interp| ≤ h²/8 · max_cell |n₀''| / (8π), relative to c(s) = (s + n₀(s))/(8π).
    let mut worst = 0.0f64;
    let mut worst_above_60 = 0.0f64;
    let mut max_n0pp = 0.0f64;
    let t = NormalizationTable::<256>::new(Normalization::TriAceExact, 0.0, 255.0).unwrap();
    for cell in 0..255 {
        let (a, h) = (cell as f64, 1.0);
        let m = (0..=8)
            .map(|k| n0_second_derivative(a + h * k as f64 / 8.0).abs())
            .fold(0.0, f64::max)
            * 1.1
            + 1e-6;
        max_n0pp = max_n0pp.max(m);
        for k in 1..40 {
            let s = a + h * k as f64 / 40.0;
            let exact = tri_ace_exact(s);
            let e = rel(t.lookup(s as f32) as f64, exact);
            let bound = h * h / 8.0 * m / (s + tri_ace_exact_offset(s)) + 3.0 * f32::EPSILON as f64;
            assert!(e <= bound, "s = {s}: {e:e} > {bound:e}");
            worst = worst.max(e);
            if s >= 60.0 {
                worst_above_60 = worst_above_60.max(e);
            }
        }
    }
    println!(
        "table<256> over [0,255]: worst relative {worst:.2e}, from s = 60: {worst_above_60:.2e}, max |n0''| ≈ {max_n0pp:.3}"
    );
    assert!(worst < 1.6e-3, "documented bound: {worst:e}");
    assert!(
        max_n0pp < 0.056 * 1.1 + 1e-6,
        "documented |n0''| ≤ 0.056: {max_n0pp}"
    );
    assert!(
        worst_above_60 <= 2.0 * f32::EPSILON as f64,
        "f32 rounding from s = 60: {worst_above_60:e}"
    );
}

// ---------------------------------------------------------------------------------------
// SIMD lanes against scalars.
// ---------------------------------------------------------------------------------------

/// Shininess rows for the lane tests, extremes included.
const LANE_S: [f64; 18] = [
    0.0, 1e-7, 1e-3, 0.5, 1.0, 2.0, 2.04, 3.0, 7.0, 22.75, 100.0, 255.0, 1e3, 1e4, 1e6, 1e9, 1e20,
    3e38,
];

#[test]
fn lanes_match_scalars() {
    let rows: Vec<[f64; 1]> = LANE_S.iter().map(|&s| [s]).collect();
    let rows2: Vec<[f64; 2]> = LANE_S
        .iter()
        .flat_map(|&s| [0.0, 2.0, 2.04, 3.5].map(|n| [s, n]))
        .collect();
    use common::assert_lanes_match as lanes;
    let mut report = Vec::new();
    // exp-based: wide's exp vs std differs by ≤ 1 ULP; the formulas damp it (measured 0–1).
    report.push((
        "tri_ace_integral",
        lanes!("tri_ace_integral", ulp = 2, abs = 0.0, &rows, fn(s) { tri_ace_integral(s) }),
    ));
    report.push((
        "tri_ace_exact",
        lanes!("tri_ace_exact", ulp = 2, abs = 0.0, &rows, fn(s) { tri_ace_exact(s) }),
    ));
    report.push(("tri_ace_exact_offset", lanes!("tri_ace_exact_offset", ulp = 2, abs = 0.0, &rows, fn(s) { tri_ace_exact_offset(s) })));
    report.push(("blinn_phong_cosine_exact", lanes!("blinn_phong_cosine_exact", ulp = 2, abs = 0.0, &rows, fn(s) { blinn_phong_cosine_exact(s) })));
    // + − × only: bit-identical (mul_add fuses on lanes and scalars alike).
    report.push((
        "tri_ace_fit",
        lanes!("tri_ace_fit", ulp = 0, abs = 0.0, &rows2, fn(s, n) { tri_ace_fit(s, n) }),
    ));
    report.push((
        "tri_ace_2010_fit",
        lanes!("tri_ace_2010_fit", ulp = 0, abs = 0.0, &rows, fn(s) { tri_ace_2010_fit(s) }),
    ));
    report.push((
        "blinn_phong_ndf",
        lanes!("blinn_phong_ndf", ulp = 0, abs = 0.0, &rows, fn(s) { blinn_phong_ndf(s) }),
    ));
    report.push(("blinn_phong_rtr_approx", lanes!("blinn_phong_rtr_approx", ulp = 0, abs = 0.0, &rows, fn(s) { blinn_phong_rtr_approx(s) })));
    report.push((
        "phong_lobe",
        lanes!("phong_lobe", ulp = 0, abs = 0.0, &rows, fn(s) { phong_lobe(s) }),
    ));
    report.push((
        "phong_cosine",
        lanes!("phong_cosine", ulp = 0, abs = 0.0, &rows, fn(s) { phong_cosine(s) }),
    ));
    report.push((
        "Normalization::factor (all)",
        lanes!("Normalization::factor", ulp = 2, abs = 0.0, &rows, fn(s) {
            let all = [
                Normalization::Unnormalized,
                Normalization::TriAceExact,
                Normalization::TRI_ACE_2009_FIT,
                Normalization::TriAce2010Fit,
                Normalization::BlinnPhongNdf,
                Normalization::BlinnPhongCosineExact,
                Normalization::BlinnPhongRtrApprox,
                Normalization::PhongLobe,
                Normalization::PhongCosine,
            ];
            // Sum of ratios to each variant's own value keeps every variant in the result.
            let mut acc = R::zero();
            for n in all {
                acc += n.factor(s) / (s + R::one());
            }
            acc
        }),
    ));
    for (name, w) in &report {
        println!("lanes {name}: worst {w} ulp");
    }
}

#[test]
fn lobe_eval_lanes_match_scalars() {
    // pow on lanes is wide's exp2(s·log2 x) kernel: the relative error grows with s·|log x|,
    // so results are compared in ULP where they are not tiny and absolutely below 1e-30.
    let cos: Vec<f64> = (0..=64)
        .map(|i| i as f64 / 64.0)
        .chain([1e-7, 0.999_999_9, 1.0])
        .collect();
    let mut worst = 0;
    for s in [0.0, 1e-7, 1.0, 2.04, 64.0, 1e4, 1e6, MAX_SHININESS] {
        let rows: Vec<[f64; 2]> = cos.iter().map(|&c| [c, s]).collect();
        let w = common::assert_lanes_match!("BlinnPhongLobe::eval", ulp = 64, abs = 1e-30, &rows, fn(c, s) {
            let lobe = BlinnPhongLobe::<R::Scalar>::new(s.lane(0), Normalization::TriAceExact).unwrap();
            lobe.eval(c)
        });
        worst = worst.max(w);
    }
    println!("lanes BlinnPhongLobe::eval: worst {worst} ulp");
}

// ---------------------------------------------------------------------------------------
// Floating-point accuracy of the exact factor.
// ---------------------------------------------------------------------------------------

#[test]
fn exact_factor_is_accurate_to_a_few_ulp() {
    // Independent formulation: 2 − 2^(−s/2) = 1 − expm1(−s·ln2/2), evaluated with std's
    // exp_m1 (no subtraction of nearly equal numbers at any s).
    let mut worst64 = 0;
    let mut worst32 = 0;
    let mut s = 1e-300f64;
    let mut grid = vec![0.0];
    while s < 1e12 {
        grid.push(s);
        s *= 1.07;
    }
    grid.extend((0..=4000).map(|i| i as f64 * 0.05));
    for s in grid {
        let d = 1.0 - (-s * std::f64::consts::LN_2 / 2.0).exp_m1();
        let reference = (s + 2.0) / (4.0 * PI * d);
        worst64 = worst64.max(common::ulps(tri_ace_exact(s), reference));
        let reference_integral = 4.0 * PI * d / (s + 2.0);
        worst64 = worst64.max(common::ulps(tri_ace_integral(s), reference_integral));
        // n₀ = 2 + 2^(−s/2)(s + 2)/(2 − 2^(−s/2)): a different arrangement of the same value.
        let q = (-s * std::f64::consts::LN_2 / 2.0).exp();
        let reference_n0 = 2.0 + q * (s + 2.0) / d;
        worst64 = worst64.max(common::ulps(tri_ace_exact_offset(s), reference_n0));
        // f32 against the f64 reference rounded to f32 (s itself rounded first).
        let s32 = s as f32;
        if s32.is_finite() {
            let d = 1.0 - (-(s32 as f64) * std::f64::consts::LN_2 / 2.0).exp_m1();
            let r32 = ((s32 as f64 + 2.0) / (4.0 * PI * d)) as f32;
            worst32 = worst32.max(common::ulps(tri_ace_exact(s32), r32));
        }
    }
    println!("tri_ace_exact/integral/offset: worst {worst64} ulp (f64), exact {worst32} ulp (f32)");
    assert!(worst64 <= 4, "f64: {worst64} ulp");
    assert!(worst32 <= 4, "f32: {worst32} ulp");
}

#[test]
fn least_squares_offset_over_0_to_221_is_also_2_04() {
    // Minimizing ∫₀^S (fit − exact)² ds over the offset alone (slope 1/(8π)) gives the
    // mean of n₀ over [0, S]; for S = 221 that mean is 2.04 (documented alternative origin).
    let s_max = 221.0;
    let breaks: Vec<f64> = (0..=17)
        .map(|k| if k == 17 { s_max } else { k as f64 * 13.0 })
        .collect();
    let mean = common::integrate_pieces(tri_ace_exact_offset, &breaks, 4, 16) / s_max;
    assert!((mean - TRI_ACE_OFFSET).abs() < 1e-3, "{mean}");
}

#[test]
fn tri_ace_2010_fit_against_the_exact_factor() {
    // Documented comparison (values from an independent evaluation of the closed forms).
    let r = |s: f64| tri_ace_2010_fit(s) / tri_ace_exact(s) - 1.0;
    assert!((r(0.0) + 0.4616).abs() < 1e-4, "{}", r(0.0));
    assert!((r(4.0) + 0.1033).abs() < 1e-4, "{}", r(4.0));
    assert!((r(256.0) + 5.308e-4).abs() < 1e-6, "{}", r(256.0));
    assert_abs_diff_eq!(r(1e9), (0.0397436 * 8.0 * PI - 1.0), epsilon = 1e-8);
    let peak = (1..4000)
        .map(|i| i as f64 * 0.01)
        .map(|s| (r(s), s))
        .fold((-1.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
    assert!(
        (peak.0 - 5.68e-3).abs() < 1e-5 && (peak.1 - 17.46).abs() < 0.05,
        "{peak:?}"
    );
    // Normal-viewing albedo of F (N·H)^s / max(N·L, N·V) with this factor stays below 1.
    let mut s = 0.0;
    while s < 1e9 {
        let albedo = tri_ace_2010_fit(s) / blinn_phong_cosine_exact(s);
        assert!(albedo < 1.0 && albedo > 0.26, "s = {s}: {albedo}");
        s = s * 1.1 + 0.01;
    }
    assert_abs_diff_eq!(
        tri_ace_2010_fit(16.0f64) / blinn_phong_cosine_exact(16.0),
        0.8062,
        epsilon = 1e-4
    );
}
