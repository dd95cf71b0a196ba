//! Masking-shadowing: erf accuracy, the weak white furnace for every Smith pair, bounds,
//! symmetry, grazing limits, the error table of the approximations, and SIMD lanes.
#![allow(clippy::too_many_arguments)]
mod common;

use approx::assert_abs_diff_eq;

use brdf::masking::{
    self, HammonApprox, Implicit, Kelemen, Masking, SchlickGgx, SmithHeightCorrelated,
    SmithSeparable, SmithSeparableWalter, VCavity,
};
use brdf::ndf::{self, Beckmann, Ggx, Ndf, SmithLambda};
use brdf::vec3::half_vector;
use brdf::{Real, Vec3};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

// ---------------------------------------------------------------------------------------------
// erf / erfc against an independent reference
// ---------------------------------------------------------------------------------------------

/// erf by the all-positive series `erf x = (2x/√π) e^{−x²} Σ (2x²)ⁿ / (1·3·…·(2n+1))`
/// (Abramowitz & Stegun 7.1.6), no cancellation; used for |x| ≤ 3.
fn erf_series(x: f64) -> f64 {
    let (mut term, mut sum) = (1.0, 1.0);
    for n in 1..400 {
        term *= 2.0 * x * x / (2 * n + 1) as f64;
        sum += term;
        if term < 1e-18 * sum {
            break;
        }
    }
    2.0 * x / PI.sqrt() * (-x * x).exp() * sum
}

/// erfc by Laplace's continued fraction evaluated backwards (A&S 7.1.14); used for x > 3.
fn erfc_cf(x: f64) -> f64 {
    let mut k = x;
    for n in (1..300).rev() {
        k = x + (n as f64 / 2.0) / k;
    }
    (-x * x).exp() / (PI.sqrt() * k)
}

fn erfc_ref(x: f64) -> f64 {
    if x < 0.0 {
        2.0 - erfc_ref(-x)
    } else if x <= 3.0 {
        1.0 - erf_series(x)
    } else {
        erfc_cf(x)
    }
}

fn erf_ref(x: f64) -> f64 {
    if x.abs() <= 3.0 {
        erf_series(x)
    } else {
        x.signum() * (1.0 - erfc_cf(x.abs()))
    }
}

#[test]
fn reference_erf_is_self_consistent() {
    // The two reference methods agree where both converge, and known values hold.
    for &x in &[2.0, 2.5, 3.0] {
        assert!(
            ((1.0 - erf_series(x)) / erfc_cf(x) - 1.0).abs() < 1e-10,
            "{x}"
        );
    }
    assert_abs_diff_eq!(erf_ref(1.0), 0.842_700_792_949_714_9, epsilon = 1e-15);
    assert_abs_diff_eq!(
        erfc_ref(5.0) / 1.537_459_794_428_034_8e-12,
        1.0,
        epsilon = 1e-13
    );
}

#[test]
fn erf_and_erfc_relative_error() {
    let (mut worst_erfc, mut worst_erf, mut worst_erfc_neg) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..=26_000 {
        let x = i as f64 * 1e-3;
        let e = ndf::erfc(x);
        worst_erfc = worst_erfc.max((e / erfc_ref(x) - 1.0).abs());
        worst_erfc_neg = worst_erfc_neg.max((ndf::erfc(-x) - erfc_ref(-x)).abs());
        if x > 0.0 {
            for s in [1.0, -1.0] {
                worst_erf = worst_erf.max((ndf::erf(s * x) / erf_ref(s * x) - 1.0).abs());
            }
        }
    }
    for &x in &[1e-300, 1e-20, 1e-8, 1e-4] {
        worst_erf = worst_erf.max((ndf::erf(x) / erf_ref(x) - 1.0).abs());
    }
    println!(
        "erfc rel. error on [0, 26]: {worst_erfc:.2e}; erf rel. error: {worst_erf:.2e}; erfc(x<0) abs: {worst_erfc_neg:.2e}"
    );
    assert!(worst_erfc < 1.2e-7, "{worst_erfc}");
    assert!(worst_erf < 1.2e-7, "{worst_erf}");
    assert!(worst_erfc_neg < 2.4e-7, "{worst_erfc_neg}");
    assert_eq!(ndf::erf(0.0f64), 0.0);
    assert_eq!(ndf::erfc(f64::INFINITY), 0.0);
    assert_eq!(ndf::erfc(f64::NEG_INFINITY), 2.0);
    assert_eq!(ndf::erf(f32::INFINITY), 1.0);
    // f32: same formula, the rounding of f32 on top.
    let mut worst32 = 0.0f64;
    for i in 0..=9_000 {
        let x = i as f64 * 1e-3;
        worst32 = worst32.max((ndf::erfc(x as f32) as f64 / erfc_ref(x as f32 as f64) - 1.0).abs());
    }
    println!("f32 erfc rel. error on [0, 9]: {worst32:.2e}");
    assert!(worst32 < 1e-5, "{worst32}");
}

#[test]
fn walter_rational_g1_error_against_exact_beckmann() {
    let exact = |a: f64| {
        let lam = (erf_ref(a) - 1.0) / 2.0 + (-a * a).exp() / (2.0 * a * PI.sqrt());
        1.0 / (1.0 + lam)
    };
    let (mut worst, mut at) = (0.0f64, 0.0);
    for i in 1..=100_000 {
        let a = i as f64 * 1e-4;
        let e = (masking::walter_beckmann_g1(a) - exact(a)).abs();
        if e > worst {
            (worst, at) = (e, a);
        }
    }
    println!("Walter G1 max abs error {worst:.2e} at a = {at}");
    assert!(worst < 0.0032 && worst > 0.003, "{worst}");
    assert!((at - 1.34).abs() < 0.01, "{at}");
    assert_eq!(masking::walter_beckmann_g1(0.0f32), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Weak white furnace: ∫ G1(v, m) max(0, v·m) D(m) dωm = cos θv
// ---------------------------------------------------------------------------------------------

/// `∫ max(0, v·m) D(m) dωm` in stretched slope space (see tests/ndf.rs), with panel edges at
/// the terminator `v·m = 0` (a line in the slope plane).
fn projected_area(d: impl Fn(Vec3<f64>) -> f64, v: Vec3<f64>, ax: f64, ay: f64) -> f64 {
    let inner = |psi: f64| {
        let (sp, cp) = psi.sin_cos();
        // v·(p, q, 1) = r (vx ax cos ψ + vy ay sin ψ) + vz.
        let k = v.x * ax * cp + v.y * ay * sp;
        let g = |t: f64| {
            if t >= FRAC_PI_2 {
                return 0.0;
            }
            let r = t.tan();
            let (p, q) = (ax * r * cp, ay * r * sp);
            let n = (1.0 + p * p + q * q).sqrt();
            let m = Vec3::new(p / n, q / n, 1.0 / n);
            // dωm = n³ dp dq... here written as D(m) max(0, v·m) · cos⁴θm/cos θm dp dq.
            let vm = v.dot(m).max(0.0);
            d(m) * vm * m.z.powi(3) * ax * ay * r / (t.cos() * t.cos())
        };
        let mut breaks = vec![0.0, 0.3, 0.6, 0.9, 1.2, 1.4, 1.5, FRAC_PI_2];
        if k < 0.0 {
            let tstar = (-v.z / k).atan();
            breaks.push(tstar);
            breaks.sort_by(f64::total_cmp);
        }
        common::integrate_pieces(g, &breaks, 1, 16)
    };
    // ψ edges: the quadrants and where the terminator leaves the plane (k = 0).
    let psi0 = f64::atan2(v.y * ay, v.x * ax);
    let mut breaks = vec![0.0, FRAC_PI_2, PI, 1.5 * PI, 2.0 * PI];
    // Near grazing the terminator passes close to the lobe and t*(ψ) swings from ~0 to π/2
    // within a few vz/α radians of those angles: refine geometrically around them.
    for e in [psi0 + FRAC_PI_2, psi0 - FRAC_PI_2] {
        for delta in [0.0, 1e-3, 1e-2, 0.1, -1e-3, -1e-2, -0.1] {
            breaks.push((e + delta).rem_euclid(2.0 * PI));
        }
    }
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    common::integrate_pieces(inner, &breaks, 1, 16)
}

fn furnace_directions() -> Vec<Vec3<f64>> {
    let mut out = Vec::new();
    for &c in &[1.0, 0.5, 0.2, 0.05, 1e-2, 1e-3] {
        for &phi in &[0.3, 2.0] {
            let s = f64::sqrt(1.0 - c * c);
            out.push(Vec3::new(s * f64::cos(phi), s * f64::sin(phi), c));
        }
    }
    out
}

fn check_furnace<D: SmithLambda<f64>>(name: &str, d: &D, ax: f64, ay: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for v in furnace_directions() {
        let area = projected_area(|m| d.d(m), v, ax, ay);
        // G1 · ∫ = cos θv ⇔ ∫ = cos θv + cos θv Λ(v): compared in the finite form.
        let lhs = d.g1(v) * area;
        let rel = (area / (v.z + d.cos_lambda(v)) - 1.0).abs();
        assert!(
            rel < 1e-6,
            "{name} v={v:?}: ∫ = {area}, cos + cosΛ = {}",
            v.z + d.cos_lambda(v)
        );
        assert!(
            (lhs - v.z).abs() < 1e-6 * v.z.max(1e-3),
            "{name}: G1∫ = {lhs} vs {}",
            v.z
        );
        worst = worst.max(rel);
    }
    worst
}

#[test]
fn weak_white_furnace_ggx() {
    let mut worst: f64 = 0.0;
    for &(ax, ay) in &[
        (0.05, 0.05),
        (0.3, 0.3),
        (1.0, 1.0),
        (0.1, 0.5),
        (0.8, 0.02),
    ] {
        let g = Ggx::<f64>::anisotropic(ax, ay).unwrap();
        worst = worst.max(check_furnace("ggx", &g, ax, ay));
    }
    println!("weak white furnace GGX: worst relative error {worst:.1e}");
}

#[test]
fn weak_white_furnace_beckmann() {
    let mut worst: f64 = 0.0;
    for &(ax, ay) in &[
        (0.05, 0.05),
        (0.3, 0.3),
        (1.0, 1.0),
        (0.5, 0.1),
        (0.02, 0.7),
    ] {
        let b = Beckmann::<f64>::anisotropic(ax, ay).unwrap();
        worst = worst.max(check_furnace("beckmann", &b, ax, ay));
    }
    println!("weak white furnace Beckmann: worst relative error {worst:.1e}");
}

#[test]
fn v_cavity_g1_against_the_weak_white_furnace() {
    // The V-cavity G1(v, m) = min(1, 2 cos θm cos θv / (v·m)) is not the Smith G1, yet it
    // conserves the projected area too (Heitz 2014, V-cavity model): check it for a GGX lobe.
    let g = Ggx::<f64>::new(0.5).unwrap();
    let mut worst: f64 = 0.0;
    for v in furnace_directions() {
        let f = |m: Vec3<f64>| {
            let vm = v.dot(m);
            let g1 = if vm > 0.0 {
                (2.0 * m.z * v.z / vm).min(1.0)
            } else {
                0.0
            };
            g.d(m) * g1
        };
        let i = projected_area(f, v, 0.5, 0.5);
        worst = worst.max((i / v.z - 1.0).abs());
    }
    println!("V-cavity G1 with GGX α=0.5: worst |∫G1 max(0,v·m) D / cos θv − 1| = {worst:.1e}");
    assert!(worst < 1e-5, "V-cavity furnace: {worst}");
}

// ---------------------------------------------------------------------------------------------
// Properties
// ---------------------------------------------------------------------------------------------

fn terms_g2_v<R: Real, D>(
    ndf: &D,
    wi: Vec3<R>,
    wo: Vec3<R>,
    wm: Vec3<R>,
) -> Vec<(&'static str, R, R)>
where
    D: SmithLambda<R> + ndf::ProjectedAlpha<R>,
{
    vec![
        (
            "correlated",
            SmithHeightCorrelated.g2(ndf, wi, wo, wm),
            SmithHeightCorrelated.visibility(ndf, wi, wo, wm),
        ),
        (
            "separable",
            SmithSeparable.g2(ndf, wi, wo, wm),
            SmithSeparable.visibility(ndf, wi, wo, wm),
        ),
        (
            "v-cavity",
            VCavity.g2(ndf, wi, wo, wm),
            VCavity.visibility(ndf, wi, wo, wm),
        ),
        (
            "schlick",
            SchlickGgx.g2(ndf, wi, wo, wm),
            SchlickGgx.visibility(ndf, wi, wo, wm),
        ),
        (
            "hammon",
            HammonApprox.g2(ndf, wi, wo, wm),
            HammonApprox.visibility(ndf, wi, wo, wm),
        ),
        (
            "kelemen",
            Kelemen.g2(ndf, wi, wo, wm),
            Kelemen.visibility(ndf, wi, wo, wm),
        ),
        (
            "implicit",
            Implicit.g2(ndf, wi, wo, wm),
            Implicit.visibility(ndf, wi, wo, wm),
        ),
    ]
}

fn check_properties<R: brdf::Scalar>(
    wi: Vec3<R>,
    wo: Vec3<R>,
    ax: R,
    ay: R,
    tol: f64,
) -> Result<(), String> {
    let wm = half_vector(wi, wo);
    let g = Ggx::<R>::anisotropic(ax, ay).unwrap();
    let b = Beckmann::<R>::anisotropic(ax, ay).unwrap();
    let mut sets = vec![(
        "ggx",
        terms_g2_v(&g, wi, wo, wm),
        terms_g2_v(&g, wo, wi, wm),
    )];
    sets.push((
        "beckmann",
        terms_g2_v(&b, wi, wo, wm),
        terms_g2_v(&b, wo, wi, wm),
    ));
    let walter = SmithSeparableWalter;
    sets[1].1.push((
        "walter",
        walter.g2(&b, wi, wo, wm),
        walter.visibility(&b, wi, wo, wm),
    ));
    sets[1].2.push((
        "walter",
        walter.g2(&b, wo, wi, wm),
        walter.visibility(&b, wo, wi, wm),
    ));
    let (ci, co): (f64, f64) = (wi.z.into(), wo.z.into());
    for (nd, fwd, rev) in sets {
        for ((name, g2, v), (_, g2r, vr)) in fwd.into_iter().zip(rev) {
            let (g2, v, g2r, vr): (f64, f64, f64, f64) =
                (g2.into(), v.into(), g2r.into(), vr.into());
            let ctx = format!("{nd}/{name} wi={wi:?} wo={wo:?} a=({ax:?},{ay:?}): G2={g2} V={v}");
            if !(g2.is_finite() && v.is_finite() && v >= 0.0) {
                return Err(format!("non-finite {ctx}"));
            }
            if !(-0.0..=1.0 + tol).contains(&g2) {
                return Err(format!("G2 out of [0,1]: {ctx}"));
            }
            if (g2 - g2r).abs() > tol || (v - vr).abs() > tol * v.max(1.0) {
                return Err(format!("not symmetric ({g2r}, {vr}): {ctx}"));
            }
            // V = G2 / (4 cos θi cos θo) wherever that quotient is well conditioned.
            if ci > 1e-3 && co > 1e-3 {
                let q = g2 / (4.0 * ci * co);
                if (v - q).abs() > 50.0 * tol * q.max(1e-30) + 1e-30 {
                    return Err(format!("V ≠ G2/(4 ci co) = {q}: {ctx}"));
                }
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(common::config(256))]

    #[test]
    fn masking_terms_bounded_symmetric_finite(
        wi in common::direction(),
        wo in common::direction(),
        ai in 0usize..6,
        aj in 0usize..6,
    ) {
        let alphas = [1e-4, 1e-3, 0.05, 0.3, 0.7, 1.0];
        let (ax, ay) = (alphas[ai], alphas[aj]);
        check_properties::<f64>(wi, wo, ax, ay, 1e-12).map_err(TestCaseError::fail)?;
        check_properties::<f32>(common::to_f32(wi), common::to_f32(wo), ax as f32, ay as f32, 2e-6)
            .map_err(TestCaseError::fail)?;
    }
}

proptest! {
    #![proptest_config(common::config(256))]

    /// The terms that ignore the NDF evaluate without one, and their `Masking`
    /// implementation is that evaluation for every NDF, bit for bit (f64 and f32), for the
    /// half vector and for an arbitrary microfacet normal (either hemisphere); the values
    /// are those of the published formulas, computed here independently.
    #[test]
    fn ndf_free_terms_need_no_ndf(
        wi in common::direction(),
        wo in common::direction(),
        m in common::direction(),
        flip in any::<bool>(),
        a in 1e-4f64..=1.0,
    ) {
        let ggx = Ggx::<f64>::anisotropic(a, 0.5).unwrap();
        let beck = Beckmann::<f64>::new(a).unwrap();
        let other = if flip { Vec3::new(m.x, m.y, -m.z) } else { m };
        for wm in [half_vector(wi, wo), other] {
            let free = [
                VCavity::g2(wi, wo, wm),
                VCavity::visibility(wi, wo, wm),
                Kelemen::g2(wi, wo, wm),
                Kelemen::visibility(wi, wo, wm),
                Implicit::g2(wi, wo),
                Implicit::visibility(),
            ];
            let via_ggx = [
                VCavity.g2(&ggx, wi, wo, wm),
                VCavity.visibility(&ggx, wi, wo, wm),
                Kelemen.g2(&ggx, wi, wo, wm),
                Kelemen.visibility(&ggx, wi, wo, wm),
                Implicit.g2(&ggx, wi, wo, wm),
                Implicit.visibility(&ggx, wi, wo, wm),
            ];
            let via_beckmann = [
                VCavity.g2(&beck, wi, wo, wm),
                VCavity.visibility(&beck, wi, wo, wm),
                Kelemen.g2(&beck, wi, wo, wm),
                Kelemen.visibility(&beck, wi, wo, wm),
                Implicit.g2(&beck, wi, wo, wm),
                Implicit.visibility(&beck, wi, wo, wm),
            ];
            for i in 0..free.len() {
                prop_assert_eq!(free[i].to_bits(), via_ggx[i].to_bits(), "term {}", i);
                prop_assert_eq!(free[i].to_bits(), via_beckmann[i].to_bits(), "term {}", i);
            }
            // f32, against the trait on an f32 NDF.
            let (wi32, wo32, wm32) = (common::to_f32(wi), common::to_f32(wo), common::to_f32(wm));
            let g32 = Ggx::<f32>::new(a as f32).unwrap();
            prop_assert_eq!(
                VCavity::g2(wi32, wo32, wm32).to_bits(),
                VCavity.g2(&g32, wi32, wo32, wm32).to_bits()
            );
            prop_assert_eq!(
                Kelemen::visibility(wi32, wo32, wm32).to_bits(),
                Kelemen.visibility(&g32, wi32, wo32, wm32).to_bits()
            );
            // The formulas (Blinn 1977 / Heitz 2014; Kelemen & Szirmay-Kalos 2001).
            let (hi, ho) = (wi.dot(wm), wo.dot(wm));
            let front = hi > 0.0 && ho > 0.0;
            let nh = wm.z.max(0.0);
            let vc = (2.0 * nh * wo.z / ho).min(2.0 * nh * wi.z / hi).min(1.0);
            let ke = wi.z * wo.z / (hi * ho);
            if front && hi > 1e-12 && ho > 1e-12 {
                prop_assert!((free[0] - vc).abs() <= 1e-12 * vc.max(1.0), "{} vs {}", free[0], vc);
                prop_assert!((free[2] - ke).abs() <= 1e-12 * ke.max(1.0), "{} vs {}", free[2], ke);
            } else if !front {
                prop_assert_eq!(free[0], 0.0);
                prop_assert_eq!(free[2], 0.0);
            }
            prop_assert_eq!(free[4], wi.z * wo.z);
            prop_assert_eq!(free[5], 0.25);
        }
    }
}

#[test]
fn g1_is_one_at_normal_incidence_and_zero_at_grazing() {
    let n = Vec3::new(0.0, 0.0, 1.0);
    let graze = Vec3::new(0.0, 1.0, 0.0);
    for &a in &[1e-4, 0.1, 1.0] {
        let g = Ggx::<f64>::anisotropic(a, 0.5).unwrap();
        let b = Beckmann::<f64>::anisotropic(a, 0.5).unwrap();
        assert_eq!(g.g1(n), 1.0);
        assert_eq!(b.g1(n), 1.0);
        assert!(g.g1(graze) < 1e-10 && b.g1(graze) < 1e-10);
        assert_eq!(SmithHeightCorrelated.g2(&g, n, n, n), 1.0);
        assert_eq!(SmithSeparable.g2(&b, n, n, n), 1.0);
        assert_eq!(VCavity.g2(&g, n, n, n), 1.0);
        assert_eq!(SchlickGgx.g2(&g, n, n, n), 1.0);
        assert_eq!(HammonApprox.g2(&g, n, n, n), 1.0);
        assert_eq!(Kelemen.g2(&g, n, n, n), 1.0);
        assert_eq!(SmithSeparableWalter.g2(&b, n, n, n), 1.0);
    }
}

#[test]
fn grazing_visibility_has_its_finite_limit() {
    // One direction exactly grazing: V → 0.5/(cos θo α) for isotropic GGX (Filament's form).
    for &a in &[1e-4f64, 0.1, 1.0] {
        let g = Ggx::<f64>::new(a).unwrap();
        let wi = Vec3::new(1.0, 0.0, 0.0);
        let wo = Vec3::new(-0.6, 0.0, 0.8);
        let wm = half_vector(wi, wo);
        let v = SmithHeightCorrelated.visibility(&g, wi, wo, wm);
        assert!((v / (0.5 / (0.8 * a)) - 1.0).abs() < 1e-12, "a={a}: {v}");
        let vs = SmithSeparable.visibility(&g, wi, wo, wm);
        // Separable: G1(wi)/cos θi → 2/(α sin θi) = 2/α; V = (2/α) G1(wo)/(4 cos θo).
        let expect = 2.0 / a * g.g1(wo) / (4.0 * 0.8);
        assert!((vs / expect - 1.0).abs() < 1e-12, "a={a}: {vs} vs {expect}");
        assert!(SmithHeightCorrelated.g2(&g, wi, wo, wm) < 1e-10);
    }
    // Both grazing, the degenerate half vector, tiny alpha, f32: finite, non-negative.
    let g = Ggx::<f32>::new(1e-4).unwrap();
    let b = Beckmann::<f32>::new(1e-4).unwrap();
    let x = Vec3::new(1.0f32, 0.0, 0.0);
    let mx = Vec3::new(-1.0f32, 0.0, 0.0);
    let y = Vec3::new(0.0f32, 1.0, 1e-7);
    for (wi, wo) in [(x, x), (x, mx), (x, y), (y, y)] {
        let wm = half_vector(wi, wo);
        for (name, g2, v) in terms_g2_v(&g, wi, wo, wm)
            .into_iter()
            .chain(terms_g2_v(&b, wi, wo, wm))
        {
            assert!(
                g2.is_finite() && v.is_finite() && g2 >= 0.0 && v >= 0.0,
                "{name} {wi:?} {wo:?}: {g2} {v}"
            );
        }
        let w = SmithSeparableWalter.visibility(&b, wi, wo, wm);
        assert!(w.is_finite() && w >= 0.0);
    }
    // wm = 0 (wi = −wo) gives 0 for the terms that look at wm.
    let wm = half_vector(x, mx);
    assert_eq!(wm, Vec3::new(0.0, 0.0, 0.0));
    assert_eq!(SmithHeightCorrelated.g2(&g, x, mx, wm), 0.0);
    assert_eq!(VCavity.visibility(&g, x, mx, wm), 0.0);
    assert_eq!(Kelemen.visibility(&g, x, mx, wm), 0.0);
}

#[test]
fn correlated_ggx_visibility_matches_the_closed_form() {
    // V = 0.5 / (cos θo √(cos²θi (1 − α²) + α²) + cos θi √(cos²θo (1 − α²) + α²)).
    for &a in &[1e-3, 0.2, 0.9] {
        let g = Ggx::<f64>::new(a).unwrap();
        for &(ci, co) in &[(0.1, 0.9), (0.5, 0.5), (1e-6, 0.3), (1.0, 0.01)] {
            let wi = common::hemisphere(ci, 0.1);
            let wo = common::hemisphere(co, 0.6);
            let wm = half_vector(wi, wo);
            let a2 = a * a;
            let exact = 0.5
                / (co * (ci * ci * (1.0 - a2) + a2).sqrt()
                    + ci * (co * co * (1.0 - a2) + a2).sqrt());
            let v = SmithHeightCorrelated.visibility(&g, wi, wo, wm);
            assert!(
                (v / exact - 1.0).abs() < 1e-12,
                "a={a} ci={ci} co={co}: {v} vs {exact}"
            );
        }
    }
}

#[test]
fn walter_separable_is_close_to_exact_beckmann_separable() {
    let mut worst: f64 = 0.0;
    for &a in &[0.05, 0.3, 1.0] {
        let b = Beckmann::<f64>::anisotropic(a, 0.5 * a).unwrap();
        for i in 0..=40 {
            for j in 0..=40 {
                let wi = common::hemisphere(i as f64 / 40.0, 0.13);
                let wo = common::hemisphere(j as f64 / 40.0, 0.71);
                let wm = half_vector(wi, wo);
                let e = (SmithSeparableWalter.g2(&b, wi, wo, wm)
                    - SmithSeparable.g2(&b, wi, wo, wm))
                .abs();
                worst = worst.max(e);
            }
        }
    }
    println!("Walter separable vs exact separable Beckmann: max |ΔG2| = {worst:.4}");
    assert!(worst < 0.007, "{worst}");
}

// ---------------------------------------------------------------------------------------------
// Error table of the approximations vs exact height-correlated Smith GGX
// ---------------------------------------------------------------------------------------------

const TERMS: [&str; 6] = [
    "separable",
    "hammon",
    "schlick",
    "kelemen",
    "implicit",
    "v-cavity",
];
const TABLE_ALPHAS: [f64; 5] = [0.05, 0.25, 0.5, 0.75, 1.0];

/// Max |G2 − G2_exact| against the height-correlated Smith GGX over cos θi, cos θo on a
/// 41-point grid in [min_cos, 1] (plus 1e-7 when min_cos = 0), Δφ ∈ {0, π/2, π}.
fn error_table(min_cos: f64) -> [[f64; 5]; 6] {
    let mut cosines: Vec<f64> = (0..=40)
        .map(|i| min_cos + (1.0 - min_cos) * i as f64 / 40.0)
        .collect();
    if min_cos == 0.0 {
        cosines.push(1e-7);
    }
    let mut table = [[0.0f64; 5]; 6];
    for (ia, &a) in TABLE_ALPHAS.iter().enumerate() {
        let g = Ggx::<f64>::new(a).unwrap();
        for &ci in &cosines {
            for &co in &cosines {
                for &dphi in &[0.0, 0.25, 0.5] {
                    let wi = common::hemisphere(ci, 0.0);
                    let wo = common::hemisphere(co, dphi);
                    let wm = half_vector(wi, wo);
                    let exact = SmithHeightCorrelated.g2(&g, wi, wo, wm);
                    let approx = [
                        SmithSeparable.g2(&g, wi, wo, wm),
                        HammonApprox.g2(&g, wi, wo, wm),
                        SchlickGgx.g2(&g, wi, wo, wm),
                        Kelemen.g2(&g, wi, wo, wm),
                        Implicit.g2(&g, wi, wo, wm),
                        VCavity.g2(&g, wi, wo, wm),
                    ];
                    for (k, v) in approx.iter().enumerate() {
                        table[k][ia] = table[k][ia].max((v - exact).abs());
                    }
                }
            }
        }
    }
    table
}

fn check_table(title: &str, table: [[f64; 5]; 6], documented: [[f64; 5]; 6]) {
    println!("{title}");
    println!(
        "  {:<10} {:>7} {:>7} {:>7} {:>7} {:>7}",
        "α", 0.05, 0.25, 0.5, 0.75, 1.0
    );
    for (k, row) in table.iter().enumerate() {
        println!(
            "  {:<10} {:>7.3} {:>7.3} {:>7.3} {:>7.3} {:>7.3}",
            TERMS[k], row[0], row[1], row[2], row[3], row[4]
        );
    }
    for k in 0..6 {
        for ia in 0..5 {
            assert!(
                (table[k][ia] - documented[k][ia]).abs() <= 0.005,
                "{} α={}: measured {:.4}, documented {}",
                TERMS[k],
                TABLE_ALPHAS[ia],
                table[k][ia],
                documented[k][ia]
            );
        }
    }
}

#[test]
fn approximation_error_table() {
    // Both tables are in src/masking.rs (module docs); checked here to ±0.005.
    let full = [
        [0.065, 0.089, 0.090, 0.090, 0.090],
        [0.214, 0.151, 0.090, 0.040, 0.000],
        [0.249, 0.190, 0.134, 0.104, 0.090],
        [1.0, 1.0, 1.0, 1.0, 1.0],
        [0.932, 0.710, 0.508, 0.360, 0.250],
        [1.0, 1.0, 1.0, 1.0, 1.0],
    ];
    let typical = [
        [0.003, 0.078, 0.090, 0.090, 0.090],
        [0.206, 0.151, 0.090, 0.040, 0.000],
        [0.229, 0.190, 0.134, 0.104, 0.090],
        [0.932, 0.710, 0.803, 0.867, 0.900],
        [0.932, 0.710, 0.508, 0.360, 0.250],
        [0.909, 0.627, 0.803, 0.867, 0.900],
    ];
    check_table(
        "max |G2 − G2_exact| (correlated Smith GGX), cos θi, cos θo ∈ [0, 1]:",
        error_table(0.0),
        full,
    );
    check_table(
        "same, cos θi, cos θo ∈ [0.1, 1]:",
        error_table(0.1),
        typical,
    );
}

// ---------------------------------------------------------------------------------------------
// SIMD lanes
// ---------------------------------------------------------------------------------------------

fn pair_rows() -> Vec<[f64; 8]> {
    let cosines = [0.0, 1e-7, 1e-3, 0.1, 0.5, 0.9, 1.0];
    let alphas = [
        [1e-4, 1e-4],
        [0.05, 0.3],
        [0.5, 0.5],
        [1.0, 0.2],
        [1.0, 1.0],
    ];
    let mut rows = Vec::new();
    for (i, &ci) in cosines.iter().enumerate() {
        for (j, &co) in cosines.iter().enumerate() {
            for (k, a) in alphas.iter().enumerate() {
                let wi = common::hemisphere(ci, (i + k) as f64 / 7.0);
                let wo = common::hemisphere(co, 0.5 + (j * 3) as f64 / 11.0);
                rows.push([wi.x, wi.y, wi.z, wo.x, wo.y, wo.z, a[0], a[1]]);
            }
        }
    }
    // wi = −wo (degenerate half vector) and wi = wo.
    rows.push([1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.1, 0.1]);
    rows.push([0.6, 0.0, 0.8, 0.6, 0.0, 0.8, 0.1, 0.1]);
    rows
}

#[test]
fn simd_lanes_match_scalar() {
    let rows = pair_rows();
    let mut report: Vec<(&str, u64)> = Vec::new();
    macro_rules! lanes {
        ($name:expr, $ulp:expr, $abs:expr, $ndf:ident, $term:expr, $method:ident) => {
            report.push(($name, common::assert_lanes_match!($name, ulp = $ulp, abs = $abs, &rows,
                fn(ix, iy, iz, ox, oy, oz, ax, ay) {
                    let d = $ndf::<R>::from_lanes(ax, ay).unwrap();
                    let (wi, wo) = (Vec3::new(ix, iy, iz), Vec3::new(ox, oy, oz));
                    $term.$method(&d, wi, wo, half_vector(wi, wo))
                })));
        };
    }
    lanes!("correlated ggx g2", 0, 0.0, Ggx, SmithHeightCorrelated, g2);
    lanes!(
        "correlated ggx V",
        0,
        0.0,
        Ggx,
        SmithHeightCorrelated,
        visibility
    );
    lanes!("separable ggx g2", 0, 0.0, Ggx, SmithSeparable, g2);
    lanes!("separable ggx V", 0, 0.0, Ggx, SmithSeparable, visibility);
    lanes!(
        "correlated beckmann g2",
        4,
        0.0,
        Beckmann,
        SmithHeightCorrelated,
        g2
    );
    lanes!(
        "correlated beckmann V",
        4,
        0.0,
        Beckmann,
        SmithHeightCorrelated,
        visibility
    );
    lanes!(
        "separable beckmann g2",
        4,
        0.0,
        Beckmann,
        SmithSeparable,
        g2
    );
    lanes!(
        "separable beckmann V",
        4,
        0.0,
        Beckmann,
        SmithSeparable,
        visibility
    );
    lanes!("walter g2", 0, 0.0, Beckmann, SmithSeparableWalter, g2);
    lanes!(
        "walter V",
        0,
        0.0,
        Beckmann,
        SmithSeparableWalter,
        visibility
    );
    lanes!("v-cavity g2", 0, 0.0, Ggx, VCavity, g2);
    lanes!("v-cavity V", 0, 0.0, Ggx, VCavity, visibility);
    lanes!("schlick g2", 0, 0.0, Ggx, SchlickGgx, g2);
    lanes!("schlick V", 0, 0.0, Ggx, SchlickGgx, visibility);
    lanes!("hammon g2", 0, 0.0, Ggx, HammonApprox, g2);
    lanes!("hammon V", 0, 0.0, Ggx, HammonApprox, visibility);
    lanes!("kelemen g2", 0, 0.0, Ggx, Kelemen, g2);
    lanes!("kelemen V", 0, 0.0, Ggx, Kelemen, visibility);
    lanes!("implicit g2", 0, 0.0, Ggx, Implicit, g2);
    lanes!("implicit V", 0, 0.0, Ggx, Implicit, visibility);

    let xs: Vec<[f64; 1]> = [
        -30.0, -5.0, -1.0, -0.5, -0.49, -1e-7, 0.0, 1e-30, 1e-7, 0.3, 0.5, 1.0, 1.59, 1.6, 2.0,
        3.0, 5.0, 9.0, 10.0, 26.0, 30.0,
    ]
    .iter()
    .map(|&x| [x])
    .collect();
    report.push((
        "erf",
        common::assert_lanes_match!("erf", ulp = 4, abs = 0.0, &xs, fn(x) { ndf::erf(x) }),
    ));
    report.push((
        "erfc",
        common::assert_lanes_match!("erfc", ulp = 4, abs = 0.0, &xs, fn(x) { ndf::erfc(x) }),
    ));
    report.push((
        "walter g1",
        common::assert_lanes_match!("walter g1", ulp = 0, abs = 0.0, &xs,
        fn(x) { masking::walter_beckmann_g1(x.abs()) }),
    ));
    println!("worst lane-vs-scalar ULP (f32 lanes vs f32, f64x4 vs f64):");
    for (name, w) in report {
        println!("  {name:<24} {w}");
    }
}

/// The fraction forms used by Cook-Torrance (`Ndf::d_fraction`, `Masking::visibility_fraction`)
/// equal `d` and `visibility` for any scale of the half vector, anisotropic GGX included.
#[test]
fn fraction_forms_equal_the_direct_forms() {
    use brdf::masking::{Masking, SmithHeightCorrelated, SmithSeparable, VCavity};
    use brdf::ndf::{Beckmann, Ggx, Ndf};
    let ggx = Ggx::<f64>::anisotropic(0.05, 0.4).unwrap();
    let beck = Beckmann::<f64>::new(0.3).unwrap();
    let mut worst = 0.0f64;
    for i in 0..40 {
        for j in 0..40 {
            let wi = common::hemisphere(1e-6 + i as f64 / 40.0, 0.37 * i as f64);
            let wo = common::hemisphere(1e-6 + j as f64 / 40.0, 0.71 * j as f64);
            let h = wi + wo;
            let len2 = h.length_squared();
            let wm = h.scale(1.0 / len2.sqrt());
            let rel = |a: f64, (n, d): (f64, f64)| (n / d - a).abs() / a.abs().max(1e-300);
            worst = worst.max(rel(ggx.d(wm), ggx.d_fraction(wm, h, len2)));
            worst = worst.max(rel(beck.d(wm), beck.d_fraction(wm, h, len2)));
            for v in [
                rel(
                    SmithHeightCorrelated.visibility(&ggx, wi, wo, wm),
                    SmithHeightCorrelated.visibility_fraction(&ggx, wi, wo, wm),
                ),
                rel(
                    SmithSeparable.visibility(&ggx, wi, wo, wm),
                    SmithSeparable.visibility_fraction(&ggx, wi, wo, wm),
                ),
                rel(
                    VCavity.visibility(&beck, wi, wo, wm),
                    VCavity.visibility_fraction(&beck, wi, wo, wm),
                ),
            ] {
                worst = worst.max(v);
            }
        }
    }
    assert!(worst < 1e-13, "worst relative difference {worst:e}");
}
