//! Normal distribution functions: normalization by quadrature, conversions and their measured
//! error, Blinn 1977's forms, extremes, and SIMD-lane equivalence.
mod common;

use approx::assert_abs_diff_eq;

use brdf::ndf::{
    self, AshikhminShirleyLobe, Beckmann, BlinnPhong, Ggx, GgxIsotropic, Ndf, ProjectedAlpha,
    SmithLambda,
};
use brdf::real::Splat;
use brdf::{Real, Vec3};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

// ---------------------------------------------------------------------------------------------
// Quadrature helpers
// ---------------------------------------------------------------------------------------------

/// Geometric breaks on [0, π/2] concentrated near 0 at the lobe width `w` (ratio 2).
fn theta_breaks(w: f64) -> Vec<f64> {
    let mut b = vec![0.0];
    let mut t = (w * 1e-2).min(0.1);
    while t < FRAC_PI_2 {
        b.push(t);
        t *= 2.0;
    }
    // Also towards the horizon, where cos^s θ with small s has an algebraic end point.
    for k in 1..=8 {
        let t = FRAC_PI_2 - 10f64.powi(-k);
        if t > *b.last().unwrap() {
            b.push(t);
        }
    }
    b.push(FRAC_PI_2);
    b
}

/// ∫ f(wm) cos θm dωm for an isotropic `f` in spherical coordinates: 2π ∫ f cos θ sin θ dθ,
/// with panel edges concentrated at the lobe width `w`.
fn iso_projected_integral(f: impl Fn(Vec3<f64>) -> f64, w: f64) -> f64 {
    let g = |t: f64| {
        let (s, c) = t.sin_cos();
        f(Vec3::new(s, 0.0, c)) * c * s
    };
    2.0 * PI * common::integrate_pieces(g, &theta_breaks(w), 2, 16)
}

/// ∫ f(wm) cos θm dωm in stretched slope space, an independent change of variables that
/// follows anisotropic lobes: slopes (p, q) = (ax r cos ψ, ay r sin ψ), r = tan t;
/// `cos θm dωm = cos⁴θm dp dq`, `dp dq = ax ay r dr dψ`, `dr = sec²t dt`.
fn slope_projected_integral(f: impl Fn(Vec3<f64>) -> f64, ax: f64, ay: f64) -> f64 {
    let inner = |psi: f64| {
        let (sp, cp) = psi.sin_cos();
        let g = |t: f64| {
            if t >= FRAC_PI_2 {
                return 0.0;
            }
            let r = t.tan();
            let (p, q) = (ax * r * cp, ay * r * sp);
            let n = (1.0 + p * p + q * q).sqrt();
            let c = 1.0 / n;
            let wm = Vec3::new(p / n, q / n, c);
            f(wm) * c.powi(4) * ax * ay * r / (t.cos() * t.cos())
        };
        common::integrate_pieces(g, &[0.0, 0.3, 0.6, 0.9, 1.2, 1.4, 1.5, FRAC_PI_2], 2, 16)
    };
    common::integrate_pieces(inner, &[0.0, FRAC_PI_2, PI, 1.5 * PI, 2.0 * PI], 3, 16)
}

const ALPHAS: [f64; 7] = [1e-3, 3e-3, 0.01, 0.05, 0.2, 0.5, 1.0];
const RATIOS: [f64; 4] = [1.0, 2.0, 4.0, 10.0];

// ---------------------------------------------------------------------------------------------
// Normalization
// ---------------------------------------------------------------------------------------------

#[test]
fn ggx_and_beckmann_isotropic_integrate_to_one() {
    let mut worst: f64 = 0.0;
    for &a in &ALPHAS {
        let g = Ggx::<f64>::new(a).unwrap();
        let b = Beckmann::<f64>::new(a).unwrap();
        for (name, i) in [
            ("ggx", iso_projected_integral(|m| g.d(m), a)),
            ("beckmann", iso_projected_integral(|m| b.d(m), a)),
        ] {
            assert!((i - 1.0).abs() < 1e-9, "{name} alpha={a}: ∫D cos = {i}");
            worst = worst.max((i - 1.0).abs());
        }
    }
    println!("isotropic GGX/Beckmann normalization: worst |∫D cos − 1| = {worst:.1e}");
}

#[test]
fn anisotropic_ndfs_integrate_to_one_in_slope_space() {
    let mut worst: f64 = 0.0;
    for &a in &ALPHAS {
        for &k in &RATIOS {
            let (ax, ay) = (a / k, a);
            if ax < ndf::MIN_ALPHA {
                continue;
            }
            let g = Ggx::<f64>::anisotropic(ax, ay).unwrap();
            let b = Beckmann::<f64>::anisotropic(ay, ax).unwrap();
            let ig = slope_projected_integral(|m| g.d(m), ax, ay);
            let ib = slope_projected_integral(|m| b.d(m), ay, ax);
            assert!((ig - 1.0).abs() < 1e-9, "ggx ({ax}, {ay}): {ig}");
            assert!((ib - 1.0).abs() < 1e-9, "beckmann ({ay}, {ax}): {ib}");
            worst = worst.max((ig - 1.0).abs()).max((ib - 1.0).abs());
        }
    }
    println!("anisotropic GGX/Beckmann normalization: worst |∫D cos − 1| = {worst:.1e}");
}

#[test]
fn f32_ndfs_integrate_to_one() {
    for &a in &[1e-3, 0.05, 1.0] {
        let g = Ggx::<f32>::anisotropic(a as f32 / 2.0, a as f32).unwrap();
        let b = Beckmann::<f32>::new(a as f32).unwrap();
        let ig = slope_projected_integral(|m| g.d(common::to_f32(m)) as f64, a / 2.0, a);
        let ib = iso_projected_integral(|m| b.d(common::to_f32(m)) as f64, a);
        assert!((ig - 1.0).abs() < 2e-5, "f32 ggx {a}: {ig}");
        assert!((ib - 1.0).abs() < 2e-5, "f32 beckmann {a}: {ib}");
    }
}

#[test]
fn blinn_phong_integrates_to_one_for_shininess_0_to_1e4() {
    let mut worst: f64 = 0.0;
    for &s in &[0.0, 0.5, 1.0, 2.0, 10.0, 100.0, 1e3, 1e4] {
        let bp = BlinnPhong::<f64>::new(s).unwrap();
        let width = (2.0 / (s + 2.0)).sqrt();
        let i = iso_projected_integral(|m| bp.d(m), width);
        assert!((i - 1.0).abs() < 1e-9, "s={s}: {i}");
        worst = worst.max((i - 1.0).abs());
    }
    println!("Blinn-Phong normalization: worst |∫D cos − 1| = {worst:.1e}");
}

#[test]
fn ashikhmin_shirley_is_exactly_normalized_and_the_paper_factor_is_not() {
    let mut worst: f64 = 0.0;
    println!("Ashikhmin-Shirley: ∫ D_paper cos θm dωm with the paper's √((nu+1)(nv+1))/(2π):");
    for &(nu, nv) in &[
        (0.0, 0.0),
        (1.0, 1.0),
        (10.0, 10.0),
        (10.0, 100.0),
        (100.0, 100.0),
        (1.0, 1e3),
        (1e3, 1e3),
        (1e2, 1e4),
    ] {
        let a = AshikhminShirleyLobe::<f64>::new(nu, nv).unwrap();
        let (ax, ay) = ((2.0 / (nu + 2.0)).sqrt(), (2.0 / (nv + 2.0)).sqrt());
        let i = slope_projected_integral(|m| a.d(m), ax, ay);
        assert!((i - 1.0).abs() < 1e-8, "AS ({nu}, {nv}): ∫D cos = {i}");
        worst = worst.max((i - 1.0).abs());
        // The paper's factor: integral of D_paper·cos = ∫ p(wm) cos θm dωm.
        let paper = slope_projected_integral(|m| a.half_vector_pdf(m), ax, ay);
        let expect = ((nu + 1.0) * (nv + 1.0) / ((nu + 2.0) * (nv + 2.0))).sqrt();
        assert!(
            (paper - expect).abs() < 1e-8,
            "paper factor ({nu}, {nv}): {paper} vs {expect}"
        );
        // ... while it normalizes the half-vector density without the cosine.
        let pdf = slope_projected_integral(|m| a.half_vector_pdf(m) / m.z, ax, ay);
        assert!((pdf - 1.0).abs() < 1e-8, "∫ p dω ({nu}, {nv}) = {pdf}");
        println!("  nu={nu:>6} nv={nv:>6}: {paper:.6}  (∫ p dω = {pdf:.9})");
    }
    println!("Ashikhmin-Shirley (NDF-normalized): worst |∫D cos − 1| = {worst:.1e}");
}

#[test]
fn normalization_does_not_depend_on_the_slope_space_formulation() {
    // Cross-check the two quadratures on the same isotropic lobe.
    let g = Ggx::<f64>::new(0.3).unwrap();
    let a = slope_projected_integral(|m| g.d(m), 0.3, 0.3);
    let b = iso_projected_integral(|m| g.d(m), 0.3);
    assert!((a - b).abs() < 1e-12, "{a} vs {b}");
    // And on an unnormalized function with a known integral: ∫ cos θ dω = π.
    let c = slope_projected_integral(|_| 1.0, 0.7, 0.2);
    assert!((c - PI).abs() < 1e-10, "{c}");
}

// ---------------------------------------------------------------------------------------------
// Closed forms
// ---------------------------------------------------------------------------------------------

#[test]
fn peaks_and_textbook_forms() {
    for &a in &[1e-4, 0.01, 0.3, 1.0] {
        let n = Vec3::new(0.0, 0.0, 1.0);
        let peak = 1.0 / (PI * a * a);
        let g = Ggx::<f64>::new(a).unwrap();
        let b = Beckmann::<f64>::new(a).unwrap();
        assert_abs_diff_eq!(g.d(n) / peak, 1.0, epsilon = 1e-14);
        assert_abs_diff_eq!(b.d(n) / peak, 1.0, epsilon = 1e-14);
        // Textbook tan/cos forms away from the extremes.
        for &t in &[0.1, 0.5, 1.0, 1.4] {
            let th: f64 = t * a.sqrt().max(0.05);
            let (s, c) = th.sin_cos();
            let m = Vec3::new(s * 0.6, s * 0.8, c);
            let t2 = (s / c).powi(2);
            let ggx = a * a / (PI * c.powi(4) * (a * a + t2).powi(2));
            let beck = (-t2 / (a * a)).exp() / (PI * a * a * c.powi(4));
            assert!((g.d(m) / ggx - 1.0).abs() < 1e-12, "ggx a={a} θ={th}");
            if beck > 1e-300 {
                assert!((b.d(m) / beck - 1.0).abs() < 1e-11, "beckmann a={a} θ={th}");
            }
        }
    }
    let bp = BlinnPhong::<f64>::new(37.0).unwrap();
    let m = Vec3::new(0.6, 0.0, 0.8);
    assert_abs_diff_eq!(
        bp.d(m),
        39.0 / (2.0 * PI) * 0.8f64.powf(37.0),
        epsilon = 1e-15
    );
}

#[test]
fn ggx_lambda_matches_the_textbook_form_and_anisotropy_uses_the_projected_alpha() {
    let g = Ggx::<f64>::anisotropic(0.2, 0.6).unwrap();
    for &(th, ph) in &[(0.3, 0.0), (1.0, 0.7), (1.5, 2.0), (1.57, 4.0)] {
        let (s, c) = f64::sin_cos(th);
        let (sp, cp) = f64::sin_cos(ph);
        let w = Vec3::new(s * cp, s * sp, c);
        let a2 = cp * cp * 0.04 + sp * sp * 0.36;
        assert_abs_diff_eq!(g.projected_alpha(w), a2.sqrt(), epsilon = 1e-14);
        let lam = ((1.0 + a2 * (s / c).powi(2)).sqrt() - 1.0) / 2.0;
        assert!(
            (g.lambda(w) / lam - 1.0).abs() < 1e-10,
            "θ={th}: {} vs {lam}",
            g.lambda(w)
        );
        assert_abs_diff_eq!(g.cos_lambda(w) / (c * lam), 1.0, epsilon = 1e-10);
        assert_abs_diff_eq!(g.g1(w), 1.0 / (1.0 + lam), epsilon = 1e-14);
        // Isotropic GGX at the projected alpha gives the same Λ.
        let iso = Ggx::<f64>::new(a2.sqrt()).unwrap();
        assert_abs_diff_eq!(iso.lambda(w) / lam, 1.0, epsilon = 1e-10);
    }
    // Grazing: cosΛ → α sin θ / 2 = α/2, finite; Λ large but finite.
    let w = Vec3::new(1.0, 0.0, 0.0);
    assert_abs_diff_eq!(g.cos_lambda(w), 0.1, epsilon = 1e-15);
    assert!(g.lambda(w).is_finite() && g.lambda(w) > 1e10);
    assert_eq!(g.lambda(Vec3::new(0.0, 0.0, 1.0)), 0.0);
}

/// Reference Beckmann Λ by direct quadrature of its definition (Heitz 2014, eq. 72):
/// `Λ(μ) = (1/μ) ∫_μ^∞ (q − μ) P2(q) dq` with the 1D slope density
/// `P2(q) = exp(−q²/α²)/(α√π)`, `μ = cot θ`.
fn beckmann_lambda_quadrature(alpha: f64, cos_theta: f64) -> f64 {
    let mu = cos_theta / (1.0 - cos_theta * cos_theta).sqrt();
    let f = |q: f64| (q - mu) * (-(q * q) / (alpha * alpha)).exp() / (alpha * PI.sqrt());
    let hi = mu + 40.0 * alpha;
    let breaks: Vec<f64> = (0..=40).map(|i| mu + (hi - mu) * i as f64 / 40.0).collect();
    common::integrate_pieces(f, &breaks, 1, 16) / mu
}

#[test]
fn beckmann_lambda_matches_its_defining_integral() {
    let mut worst: f64 = 0.0;
    for &a in &[0.01, 0.1, 0.4, 1.0] {
        let b = Beckmann::<f64>::new(a).unwrap();
        for &c in &[1e-3, 0.01, 0.05, 0.1, 0.3, 0.6, 0.9] {
            let s = (1.0 - c * c).sqrt();
            let w = Vec3::new(s * 0.8, -s * 0.6, c);
            let exact = beckmann_lambda_quadrature(a, c);
            // Error in G1 = 1/(1 + Λ) is what a BRDF sees.
            let err = (b.g1(w) - 1.0 / (1.0 + exact)).abs();
            assert!(
                err < 1e-7,
                "alpha={a} cos={c}: Λ={} vs {exact}",
                b.lambda(w)
            );
            worst = worst.max(err);
        }
    }
    println!("Beckmann G1 (erfc approx) vs quadrature of Λ's definition: max |ΔG1| = {worst:.1e}");
}

#[test]
fn ggx_lambda_matches_its_defining_integral() {
    // GGX 1D slope density P2(q) = 1/(2α (1 + q²/α²)^{3/2}) (Heitz 2014, eq. 85 marginal).
    for &a in &[0.05, 0.5, 1.0] {
        let g = Ggx::<f64>::new(a).unwrap();
        for &c in &[0.02, 0.3, 0.8] {
            let mu = c / (1.0 - c * c).sqrt();
            let f = |t: f64| {
                // q = mu + tan t maps [0, π/2) to [mu, ∞).
                if t >= FRAC_PI_2 {
                    return 0.0;
                }
                let dq = t.tan();
                let q = mu + dq;
                dq / (2.0 * a * (1.0 + q * q / (a * a)).powf(1.5)) / (t.cos() * t.cos())
            };
            let lam = common::integrate(f, 0.0, FRAC_PI_2, 32, 16) / mu;
            let s = (1.0 - c * c).sqrt();
            let got = g.lambda(Vec3::new(0.0, s, c));
            assert!(
                (got / lam - 1.0).abs() < 1e-8,
                "a={a} c={c}: {got} vs {lam}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Conversions: measured distances
// ---------------------------------------------------------------------------------------------

/// L1 distance of the projected densities, ∫ |D1 − D2| cos θm dωm ∈ [0, 2].
fn l1(d1: impl Fn(Vec3<f64>) -> f64, d2: impl Fn(Vec3<f64>) -> f64, width: f64) -> f64 {
    iso_projected_integral(|m| (d1(m) - d2(m)).abs(), width)
}

#[test]
fn shininess_and_beckmann_alpha_conversion_error() {
    println!("Blinn-Phong(s) vs Beckmann(α = √(2/(s+2))): L1 distance of D cos θm");
    let mut prev = 0.0;
    for &a in &[1e-3, 0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0] {
        let s = ndf::beckmann_alpha_to_shininess(a);
        assert_abs_diff_eq!(
            ndf::shininess_to_beckmann_alpha(s),
            a,
            epsilon = 1e-14 * a.max(1e-2)
        );
        let bp = BlinnPhong::<f64>::new(s).unwrap();
        let b = Beckmann::<f64>::new(a).unwrap();
        // Same peak by construction.
        let n = Vec3::new(0.0, 0.0, 1.0);
        assert_abs_diff_eq!(bp.d(n) / b.d(n), 1.0, epsilon = 1e-12);
        let d = l1(|m| bp.d(m), |m| b.d(m), a);
        println!("  α = {a:<6} s = {s:<12.1} L1 = {d:.4}");
        // The documented table (ndf::beckmann_alpha_to_shininess), to 2 %.
        let doc = [
            (1e-3, 0.0),
            (0.01, 1e-4),
            (0.05, 0.0014),
            (0.1, 0.0054),
            (0.2, 0.0214),
            (0.3, 0.0473),
            (0.5, 0.125),
            (0.7, 0.228),
            (1.0, 0.407),
        ];
        let want = doc.iter().find(|r| r.0 == a).unwrap().1;
        assert!(
            (d - want).abs() <= 0.02 * want + 5e-5,
            "α={a}: L1 {d} vs documented {want}"
        );
        // The distance shrinks as the lobes sharpen (the Gaussian limit).
        assert!(d >= prev * 0.9999, "not monotone in α at {a}");
        prev = d;
    }
}

#[test]
fn ggx_and_beckmann_with_the_same_alpha() {
    println!("GGX(α) vs Beckmann(α): L1 distance of D cos θm; best scale k for α_GGX = k α_B");
    for &a in &[1e-3, 0.01, 0.1, 0.3, 0.5, 1.0] {
        let b = Beckmann::<f64>::new(a).unwrap();
        let g = Ggx::<f64>::new(ndf::beckmann_alpha_to_ggx_alpha(a)).unwrap();
        let d_same = l1(|m| g.d(m), |m| b.d(m), a);
        // Golden-section search for the best constant scale (only where k α ≤ 1).
        let f = |k: f64| {
            let g = Ggx::<f64>::new((k * a).min(1.0)).unwrap();
            l1(|m| g.d(m), |m| b.d(m), a)
        };
        let (mut lo, mut hi) = (0.5, 1.8_f64.min(1.0 / a));
        for _ in 0..30 {
            let m1 = hi - 0.618 * (hi - lo);
            let m2 = lo + 0.618 * (hi - lo);
            if f(m1) < f(m2) { hi = m2 } else { lo = m1 }
        }
        let k = 0.5 * (lo + hi);
        // Both are functions of slope/α only, so the distance does not depend on α.
        assert!((d_same - 0.407).abs() < 1e-3, "α={a}: {d_same}");
        assert!(
            (k - 0.87).abs() < 0.01 && (f(k) - 0.360).abs() < 1e-3,
            "k={k}"
        );
        println!(
            "  α = {a:<6} L1(same α) = {d_same:.4}   best k = {k:.3}, L1 = {:.4}",
            f(k)
        );
    }
}

#[test]
fn roughness_alpha_round_trip() {
    for i in 0..=100 {
        let r = i as f64 / 100.0;
        let a = ndf::roughness_to_alpha(r);
        assert_eq!(a, r * r);
        assert_abs_diff_eq!(ndf::alpha_to_roughness(a), r, epsilon = 1e-15);
    }
    let g = Ggx::<f32>::from_roughness(0.5).unwrap();
    assert_eq!(g.alpha_x(), 0.25);
    assert!(Ggx::<f32>::from_roughness(0.005).is_err());
}

// ---------------------------------------------------------------------------------------------
// Blinn 1977
// ---------------------------------------------------------------------------------------------

#[test]
fn blinn_1977_distributions() {
    for &beta in &[0.05, 0.2, 0.5, 1.0] {
        let (c1, c2, c3) = ndf::reference::blinn1977_constants_from_half_angle(beta);
        let cb = f64::cos(beta);
        assert_abs_diff_eq!(ndf::reference::blinn1977_d1(cb, c1), 0.5, epsilon = 1e-14);
        assert_abs_diff_eq!(ndf::reference::blinn1977_d2(beta, c2), 0.5, epsilon = 1e-14);
        assert_abs_diff_eq!(ndf::reference::blinn1977_d3(cb, c3), 0.5, epsilon = 1e-14);
        for d in [
            ndf::reference::blinn1977_d1(1.0, c1),
            ndf::reference::blinn1977_d2(0.0, c2),
            ndf::reference::blinn1977_d3(1.0, c3),
        ] {
            assert!((d - 1.0).abs() < 1e-15, "peak {d}");
        }
    }
    // D3 is GGX up to the constant π c3²; D1 is Blinn-Phong up to (c1 + 2)/(2π).
    for &c3 in &[0.01, 0.3, 1.0] {
        let g = Ggx::<f64>::new(c3).unwrap();
        for &th in &[0.0, 0.01, 0.3, 1.0, 1.5] {
            let (s, c) = f64::sin_cos(th);
            let m = Vec3::new(s, 0.0, c);
            let d3 = ndf::reference::blinn1977_d3(c, c3);
            assert!(
                (d3 / (PI * c3 * c3 * g.d(m)) - 1.0).abs() < 1e-12,
                "c3={c3} θ={th}"
            );
        }
    }
    let bp = BlinnPhong::<f64>::new(20.0).unwrap();
    let m = Vec3::new(0.6, 0.0, 0.8);
    assert_abs_diff_eq!(
        bp.d(m),
        22.0 / (2.0 * PI) * ndf::reference::blinn1977_d1(0.8, 20.0),
        epsilon = 1e-15
    );
    // D2 (Gaussian in the angle) ≈ π α² D_Beckmann (Gaussian in tan θ) near the peak only.
    let a = 0.05;
    let b = Beckmann::<f64>::new(a).unwrap();
    for &(th, tol) in &[(0.01, 1e-3), (0.05, 5e-3), (0.1, 2e-2)] {
        let (s, c) = f64::sin_cos(th);
        let r =
            ndf::reference::blinn1977_d2(th, 1.0 / a) / (PI * a * a * b.d(Vec3::new(s, 0.0, c)));
        assert!((r - 1.0).abs() < tol, "θ={th}: ratio {r}");
    }
}

// ---------------------------------------------------------------------------------------------
// Constructors and extremes
// ---------------------------------------------------------------------------------------------

#[test]
fn constructors_validate() {
    use brdf::Error;
    assert!(
        Ggx::<f32>::new(1e-4).is_ok(),
        "f32 1e-4 rounds below 1e-4 but must be accepted"
    );
    assert!(Beckmann::<f64>::new(1e-4).is_ok() && Beckmann::<f64>::new(1.0).is_ok());
    assert!(matches!(
        Ggx::<f64>::new(f64::NAN),
        Err(Error::NotFinite { param: "alpha" })
    ));
    assert!(matches!(
        Beckmann::<f64>::anisotropic(0.5, 0.0),
        Err(Error::OutOfDomain {
            param: "alpha_y",
            ..
        })
    ));
    for bad in [0.0, -0.1, 9e-5, 1.0001, f64::INFINITY] {
        assert!(Ggx::<f64>::new(bad).is_err(), "{bad}");
        assert!(Beckmann::<f64>::new(bad).is_err(), "{bad}");
    }
    assert!(
        BlinnPhong::<f32>::new(0.0).is_ok() && BlinnPhong::<f64>::new(ndf::MAX_SHININESS).is_ok()
    );
    assert!(BlinnPhong::<f64>::new(-1e-9).is_err() && BlinnPhong::<f64>::new(3e8).is_err());
    assert!(matches!(
        AshikhminShirleyLobe::<f32>::new(1.0, f32::NAN),
        Err(Error::NotFinite { param: "nv" })
    ));
    let lanes = brdf::f32x4::new([0.1, 0.2, 0.0, 0.4]);
    assert!(Ggx::<brdf::f32x4>::from_lanes(lanes, lanes).is_err());
    let lanes = brdf::f32x4::new([0.1, 0.2, 0.3, 0.4]);
    let g = Ggx::<brdf::f32x4>::from_lanes(lanes, lanes).unwrap();
    assert_eq!(g.alpha_y().lane(2), 0.3);
}

/// The isotropic constructors name their parameter `alpha`, as their signature and docs do
/// (they reported `alpha_x` before); the anisotropic ones name the offending axis. A
/// rejected roughness is reported as the `alpha` it maps to.
#[test]
fn isotropic_constructors_name_alpha() {
    use brdf::Error;
    let out = |param: &'static str, value: f64| Error::OutOfDomain {
        param,
        value,
        domain: "[1e-4, 1]",
    };
    assert_eq!(Ggx::<f64>::new(0.0).unwrap_err(), out("alpha", 0.0));
    assert_eq!(Beckmann::<f64>::new(0.0).unwrap_err(), out("alpha", 0.0));
    assert_eq!(
        GgxIsotropic::<f64>::new(0.0).unwrap_err(),
        out("alpha", 0.0)
    );
    assert_eq!(Ggx::<f32>::new(2.0).unwrap_err(), out("alpha", 2.0));
    assert_eq!(
        Beckmann::<f64>::from_roughness(0.005).unwrap_err(),
        out("alpha", 0.005 * 0.005)
    );
    assert_eq!(
        Ggx::<f64>::from_roughness(f64::NAN).unwrap_err(),
        Error::NotFinite { param: "alpha" }
    );
    assert_eq!(
        Ggx::<f64>::anisotropic(0.0, 0.5).unwrap_err(),
        out("alpha_x", 0.0)
    );
    assert_eq!(
        Beckmann::<f64>::anisotropic(0.5, 1.5).unwrap_err(),
        out("alpha_y", 1.5)
    );
    assert_eq!(
        format!("{}", Ggx::new(1e-5_f32).unwrap_err()),
        "parameter `alpha` = 1e-5 is outside its domain [1e-4, 1]"
    );
    // The isotropic constructor builds the same constants as the anisotropic one.
    for a in [1e-4, 0.3, 1.0] {
        assert_eq!(Ggx::<f64>::new(a), Ggx::anisotropic(a, a));
        assert_eq!(
            Beckmann::<f32>::new(a as f32),
            Beckmann::anisotropic(a as f32, a as f32)
        );
        assert_eq!(
            Ok(Ggx::from(GgxIsotropic::<f64>::new(a).unwrap())),
            Ggx::new(a)
        );
    }
}

fn all_ndfs_finite<R: Real>(w: Vec3<R>, alpha: R::Scalar, s: R::Scalar) -> Result<(), String>
where
    R::Scalar: std::fmt::Debug,
{
    let checks: Vec<(&str, R, bool)> = {
        let of = <R::Scalar as brdf::Scalar>::of;
        let g = Ggx::new(alpha).unwrap().splat::<R>();
        let gi = GgxIsotropic::new(alpha).unwrap().splat::<R>();
        let ga = Ggx::anisotropic(alpha, alpha.max(of(0.1)))
            .unwrap()
            .splat::<R>();
        let b = Beckmann::new(alpha).unwrap().splat::<R>();
        let ba = Beckmann::anisotropic(of(1.0), alpha).unwrap().splat::<R>();
        let bp = BlinnPhong::new(s).unwrap().splat::<R>();
        let asx = AshikhminShirleyLobe::new(s, of(10.0)).unwrap().splat::<R>();
        vec![
            ("ggx d", g.d(w), true),
            ("ggx aniso d", ga.d(w), true),
            ("beckmann d", b.d(w), true),
            ("beckmann aniso d", ba.d(w), true),
            ("blinn-phong d", bp.d(w), true),
            ("ashikhmin-shirley d", asx.d(w), true),
            ("as pdf", asx.half_vector_pdf(w), true),
            ("ggx Λ", ga.lambda(w), true),
            ("beckmann Λ", ba.lambda(w), true),
            ("ggx cosΛ", ga.cos_lambda(w), true),
            ("beckmann cosΛ", ba.cos_lambda(w), true),
            ("ggx g1", ga.g1(w), false),
            ("beckmann g1", ba.g1(w), false),
            ("projected alpha", ba.projected_alpha(w), true),
            ("ggx isotropic d", gi.d(w), true),
            ("ggx isotropic cosΛ", gi.cos_lambda(w), true),
            ("ggx isotropic g1", gi.g1(w), false),
            ("ggx isotropic separable den", gi.separable_den(w), true),
        ]
    };
    for (name, v, unbounded) in checks {
        for l in 0..R::LANES {
            let x: f64 = v.lane(l).into();
            if !x.is_finite() || x < 0.0 || (!unbounded && x > 1.0) {
                return Err(format!(
                    "{name} = {x} at lane {l}, alpha {alpha:?}, s {s:?}"
                ));
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(common::config(256))]

    #[test]
    fn ndfs_finite_nonnegative_on_the_whole_domain(
        w in common::direction(),
        ai in 0usize..5,
        s in prop_oneof![Just(0.0), 0.0f64..10.0, 10.0f64..1e4, Just(ndf::MAX_SHININESS)],
    ) {
        let alpha = [1e-4, 1e-3, 0.05, 0.5, 1.0][ai];
        all_ndfs_finite::<f64>(w, alpha, s).map_err(TestCaseError::fail)?;
        all_ndfs_finite::<f32>(common::to_f32(w), alpha as f32, s as f32).map_err(TestCaseError::fail)?;
        let w8 = Vec3::new(brdf::f32x8::splat(w.x as f32), brdf::f32x8::splat(w.y as f32),
            brdf::f32x8::splat(w.z as f32));
        all_ndfs_finite::<brdf::f32x8>(w8, alpha as f32, s as f32).map_err(TestCaseError::fail)?;
    }
}

#[test]
fn degenerate_and_lower_hemisphere_directions_give_zero_not_nan() {
    let zero = Vec3::new(0.0f32, 0.0, 0.0);
    let below = Vec3::new(0.6f32, 0.0, -0.8);
    let horizon = Vec3::new(0.0f32, 1.0, 0.0);
    for w in [zero, below, horizon] {
        assert_eq!(Ggx::<f32>::new(1e-4).unwrap().d(w), 0.0);
        assert_eq!(Beckmann::<f32>::new(1e-4).unwrap().d(w), 0.0);
        assert_eq!(BlinnPhong::<f32>::new(0.0).unwrap().d(w), 0.0);
        assert_eq!(
            AshikhminShirleyLobe::<f32>::new(0.0, 5.0).unwrap().d(w),
            0.0
        );
    }
    all_ndfs_finite::<f32>(zero, 1e-4, 0.0).unwrap();
    all_ndfs_finite::<f64>(Vec3::new(0.0, 0.0, 0.0), 1e-4, 1e4).unwrap();
}

#[test]
fn tiny_alpha_peak_and_shoulder_are_finite_in_f32() {
    for &a in &[1e-4f32, 1e-3] {
        let g = Ggx::<f32>::new(a).unwrap();
        let b = Beckmann::<f32>::new(a).unwrap();
        for &t in &[0.0f32, 1e-5, 1e-4, 1e-3, 1e-2, 0.5, 1.57] {
            let m = Vec3::new(t.sin(), 0.0, t.cos());
            for v in [g.d(m), b.d(m), g.lambda(m), b.lambda(m), g.g1(m), b.g1(m)] {
                assert!(v.is_finite() && v >= 0.0, "alpha={a} θ={t}: {v}");
            }
        }
        let peak = g.d(Vec3::new(0.0, 0.0, 1.0));
        assert_abs_diff_eq!(peak as f64 * PI * (a as f64).powi(2), 1.0, epsilon = 1e-6);
    }
}

// ---------------------------------------------------------------------------------------------
// SIMD lanes
// ---------------------------------------------------------------------------------------------

/// Directions including the extremes: normal, grazing (cos 0, 1e-7), near-normal, and the
/// degenerate zero vector.
fn direction_rows() -> Vec<[f64; 3]> {
    let mut rows = vec![
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.6, 0.0, -0.8],
    ];
    let cosines = [0.0, 1e-7, 1e-4, 0.01, 0.2, 0.5, 0.8, 0.99, 0.999_999, 1.0];
    for (i, &c) in cosines.iter().enumerate() {
        for j in 0..5 {
            let w = common::hemisphere(c, (i * 5 + j) as f64 / 37.0);
            rows.push([w.x, w.y, w.z]);
        }
    }
    rows
}

fn with_params(params: &[[f64; 2]]) -> Vec<[f64; 5]> {
    let mut out = Vec::new();
    for d in direction_rows() {
        for p in params {
            out.push([d[0], d[1], d[2], p[0], p[1]]);
        }
    }
    out
}

#[test]
fn simd_lanes_match_scalar() {
    let alphas = with_params(&[
        [1e-4, 1e-4],
        [1e-3, 0.05],
        [0.1, 0.1],
        [0.5, 0.2],
        [1.0, 1.0],
        [1e-4, 1.0],
    ]);
    let shin = with_params(&[
        [0.0, 0.0],
        [1.0, 100.0],
        [50.0, 50.0],
        [1e4, 10.0],
        [ndf::MAX_SHININESS, 1e3],
    ]);
    let mut report = Vec::new();
    report.push((
        "ggx d",
        common::assert_lanes_match!("ggx d", ulp = 0, abs = 0.0, &alphas,
        fn(x, y, z, ax, ay) { Ggx::<R>::from_lanes(ax, ay).unwrap().d(Vec3::new(x, y, z)) }),
    ));
    report.push((
        "ggx Λ",
        common::assert_lanes_match!("ggx Λ", ulp = 0, abs = 0.0, &alphas,
        fn(x, y, z, ax, ay) { Ggx::<R>::from_lanes(ax, ay).unwrap().lambda(Vec3::new(x, y, z)) }),
    ));
    report.push(("ggx cosΛ", common::assert_lanes_match!("ggx cosΛ", ulp = 0, abs = 0.0, &alphas,
        fn(x, y, z, ax, ay) { Ggx::<R>::from_lanes(ax, ay).unwrap().cos_lambda(Vec3::new(x, y, z)) })));
    report.push((
        "ggx g1",
        common::assert_lanes_match!("ggx g1", ulp = 0, abs = 0.0, &alphas,
        fn(x, y, z, ax, ay) { Ggx::<R>::from_lanes(ax, ay).unwrap().g1(Vec3::new(x, y, z)) }),
    ));
    report.push(("projected alpha", common::assert_lanes_match!("projected alpha", ulp = 0, abs = 0.0, &alphas,
        fn(x, y, z, ax, ay) { Ggx::<R>::from_lanes(ax, ay).unwrap().projected_alpha(Vec3::new(x, y, z)) })));
    report.push((
        "beckmann d",
        common::assert_lanes_match!("beckmann d", ulp = 4, abs = 1e-300, &alphas,
        fn(x, y, z, ax, ay) { Beckmann::<R>::from_lanes(ax, ay).unwrap().d(Vec3::new(x, y, z)) }),
    ));
    // Λ = (σe^{−a²}/√π − c·erfc(a))/(2c) cancels for large a, where Λ ≪ 1: the lane/scalar
    // difference is then bounded in absolute terms (what G1 = 1/(1 + Λ) sees).
    report.push(("beckmann Λ", common::assert_lanes_match!("beckmann Λ", ulp = 8, abs = 1e-9, &alphas,
        fn(x, y, z, ax, ay) { Beckmann::<R>::from_lanes(ax, ay).unwrap().lambda(Vec3::new(x, y, z)) })));
    report.push(("beckmann cosΛ", common::assert_lanes_match!("beckmann cosΛ", ulp = 8, abs = 1e-9, &alphas,
        fn(x, y, z, ax, ay) { Beckmann::<R>::from_lanes(ax, ay).unwrap().cos_lambda(Vec3::new(x, y, z)) })));
    report.push((
        "beckmann g1",
        common::assert_lanes_match!("beckmann g1", ulp = 4, abs = 0.0, &alphas,
        fn(x, y, z, ax, ay) { Beckmann::<R>::from_lanes(ax, ay).unwrap().g1(Vec3::new(x, y, z)) }),
    ));
    report.push((
        "blinn-phong d",
        common::assert_lanes_match!("blinn-phong d", ulp = 32, abs = 1e-30, &shin,
        fn(x, y, z, s, t) { BlinnPhong::<R>::from_lanes(s).unwrap().d(Vec3::new(x, y, z)) }),
    ));
    report.push(("ashikhmin-shirley d", common::assert_lanes_match!("ashikhmin-shirley d", ulp = 32, abs = 1e-30, &shin,
        fn(x, y, z, nu, nv) { AshikhminShirleyLobe::<R>::from_lanes(nu, nv).unwrap().d(Vec3::new(x, y, z)) })));
    report.push(("ashikhmin-shirley pdf", common::assert_lanes_match!("ashikhmin-shirley pdf", ulp = 32, abs = 1e-30, &shin,
        fn(x, y, z, nu, nv) { AshikhminShirleyLobe::<R>::from_lanes(nu, nv).unwrap().half_vector_pdf(Vec3::new(x, y, z)) })));

    // Conversions and Blinn 1977 forms.
    let scalars: Vec<[f64; 2]> = [
        0.0, 1e-7, 1e-4, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999_999, 1.0,
    ]
    .iter()
    .flat_map(|&c| [1e-4, 0.01, 0.2, 1.0, 30.0, 1e4].map(|p| [c, p]))
    .collect();
    report.push(("conversions", common::assert_lanes_match!("conversions", ulp = 0, abs = 0.0, &scalars,
        fn(a, s) {
            let a = a.max(R::from_f64(1e-4));
            ndf::beckmann_alpha_to_shininess(a) + ndf::shininess_to_beckmann_alpha(s)
                + ndf::roughness_to_alpha(a) + ndf::alpha_to_roughness(a) + ndf::beckmann_alpha_to_ggx_alpha(a)
        })));
    report.push((
        "blinn1977 d1",
        common::assert_lanes_match!("blinn1977 d1", ulp = 32, abs = 1e-30, &scalars,
        fn(c, p) { ndf::reference::blinn1977_d1(c, p) }),
    ));
    report.push((
        "blinn1977 d2",
        common::assert_lanes_match!("blinn1977 d2", ulp = 8, abs = 1e-30, &scalars,
        fn(t, p) { ndf::reference::blinn1977_d2(t * R::from_f64(1.57), p) }),
    ));
    report.push((
        "blinn1977 d3",
        common::assert_lanes_match!("blinn1977 d3", ulp = 0, abs = 0.0, &scalars,
        fn(c, p) { ndf::reference::blinn1977_d3(c, p.min(R::one())) }),
    ));
    report.push((
        "blinn1977 constants",
        common::assert_lanes_match!("blinn1977 constants", ulp = 16, abs = 0.0, &scalars,
        fn(c, p) {
            let beta = c.max(R::from_f64(0.01)).min(R::from_f64(1.5));
            let (c1, c2, c3) = ndf::reference::blinn1977_constants_from_half_angle(beta);
            c1 * R::from_f64(1e-3) + c2 + c3
        }),
    ));
    println!("worst lane-vs-scalar ULP (f32 lanes vs f32, f64x4 vs f64):");
    for (name, w) in report {
        println!("  {name:<24} {w}");
    }
}

/// A wrapper that forwards only `d` and `lambda` (like a run-time NDF enum would).
struct OnlyLambda<N>(N);
impl<N: Ndf<f64>> Ndf<f64> for OnlyLambda<N> {
    fn d(&self, wm: Vec3<f64>) -> f64 {
        self.0.d(wm)
    }
}
impl<N: SmithLambda<f64>> SmithLambda<f64> for OnlyLambda<N> {
    fn lambda(&self, w: Vec3<f64>) -> f64 {
        self.0.lambda(w)
    }
}

#[test]
fn default_cos_lambda_keeps_the_grazing_limit() {
    let g = Ggx::<f64>::anisotropic(0.3, 1e-4).unwrap();
    let b = Beckmann::<f64>::anisotropic(1.0, 0.02).unwrap();
    for &c in &[0.0, 1e-16, 1e-9, 1e-3, 0.5, 1.0] {
        let w = common::hemisphere(c, 0.1);
        for (full, wrapped) in [
            (g.cos_lambda(w), OnlyLambda(g).cos_lambda(w)),
            (b.cos_lambda(w), OnlyLambda(b).cos_lambda(w)),
        ] {
            assert!(
                (wrapped - full).abs() <= 1e-12 * full.max(1e-300),
                "c={c}: {wrapped} vs {full}"
            );
        }
        assert_abs_diff_eq!(OnlyLambda(g).g1(w), g.g1(w), epsilon = 1e-15);
    }
}

// ---------------------------------------------------------------------------------------------
// Isotropic GGX
// ---------------------------------------------------------------------------------------------

/// `|a − b| ≤ tol·max(|a|, |b|)`, or both below `floor`.
fn close(a: f64, b: f64, tol: f64, floor: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()) || a.abs().max(b.abs()) < floor
}

/// Every value of the isotropic GGX against the anisotropy-capable `Ggx` with `αx = αy`, in
/// one precision: relative tolerance `tol`.
fn iso_matches_ggx<R: brdf::Scalar>(
    wi: Vec3<R>,
    wo: Vec3<R>,
    alpha: R,
    tol: f64,
) -> Result<(), TestCaseError> {
    let (iso, ggx) = (
        GgxIsotropic::<R>::new(alpha).unwrap(),
        Ggx::<R>::new(alpha).unwrap(),
    );
    let h = wi + wo;
    let len2 = h.length_squared();
    let wm = h.scale(len2.sqrt().recip());
    let frac = |(n, d): (R, R)| -> f64 { n.into() / d.into() };
    let pairs: [(&str, R, R); 9] = [
        ("d", iso.d(wm), ggx.d(wm)),
        ("lambda", iso.lambda(wi), ggx.lambda(wi)),
        ("cos_lambda", iso.cos_lambda(wo), ggx.cos_lambda(wo)),
        ("g1", iso.g1(wi), ggx.g1(wi)),
        (
            "height_correlated_sum",
            iso.height_correlated_sum(wi, wo),
            ggx.height_correlated_sum(wi, wo),
        ),
        (
            "separable_den",
            iso.separable_den(wo),
            ggx.separable_den(wo),
        ),
        (
            "projected_alpha",
            iso.projected_alpha(wi),
            ggx.projected_alpha(wi),
        ),
        (
            "d_fraction",
            R::of(frac(iso.d_fraction(wm, h, len2))),
            R::of(frac(ggx.d_fraction(wm, h, len2))),
        ),
        ("alpha", iso.alpha(), ggx.alpha_x()),
    ];
    for (name, a, b) in pairs {
        let (a, b): (f64, f64) = (a.into(), b.into());
        prop_assert!(a.is_finite() && b.is_finite(), "{name}: {a} vs {b}");
        prop_assert!(
            close(a, b, tol, 1e-30),
            "{name}: {a} vs {b} (alpha {alpha:?})"
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(common::config(512))]

    /// `GgxIsotropic` is `Ggx` with `αx = αy`: every NDF and Smith value agrees to a few
    /// ULP (f64: 1e-13 relative; f32: 2e-6), over α ∈ [1e-4, 1] log-uniform and directions
    /// from normal incidence to exactly grazing.
    #[test]
    fn isotropic_ggx_equals_ggx(
        wi in common::direction(),
        wo in common::direction(),
        log_alpha in -4.0f64..=0.0,
    ) {
        let alpha = 10f64.powf(log_alpha);
        iso_matches_ggx::<f64>(wi, wo, alpha, 1e-13)?;
        iso_matches_ggx::<f32>(common::to_f32(wi), common::to_f32(wo), alpha as f32, 2e-6)?;
    }
}

#[test]
fn isotropic_ggx_constructors_and_conversion() {
    assert!(GgxIsotropic::<f32>::new(0.0).is_err());
    assert!(GgxIsotropic::<f64>::new(1.5).is_err());
    assert!(GgxIsotropic::<f64>::new(f64::NAN).is_err());
    assert!(GgxIsotropic::<f32>::new(1e-4).is_ok());
    let r = GgxIsotropic::<f64>::from_roughness(0.5).unwrap();
    assert_eq!(r.alpha(), 0.25);
    assert_eq!(Ggx::from(r), Ggx::<f64>::new(0.25).unwrap());
    let lanes = brdf::f32x4::new([0.1, 0.2, 0.0, 0.4]);
    assert!(GgxIsotropic::<brdf::f32x4>::from_lanes(lanes).is_err());
    // Normalized: ∫ D cos θm dω = 1 (the same quadrature as for Ggx).
    for alpha in [1e-3, 0.05, 0.3, 1.0] {
        let iso = GgxIsotropic::<f64>::new(alpha).unwrap();
        let i = iso_projected_integral(|w| iso.d(w), alpha);
        assert!((i - 1.0).abs() < 1e-9, "alpha {alpha}: {i}");
    }
}
