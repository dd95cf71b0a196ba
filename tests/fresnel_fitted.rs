//! Tests of `fresnel::FittedConductor`, the piecewise-polynomial conductor reflectance: its
//! error against the `f64` closed form between the points its constructor checks, beside the
//! error of the exact formula evaluated in `f32`; where it is accepted and refused; its
//! domain handling; and the batch path (explicit lanes) against the scalar body.
use brdf::batch::{self, Directions, Isa};
use brdf::fresnel::{
    Conductor, FIT_CHECK_BOUND, FIT_SEGMENTS, FIT_TOLERANCE, FittedConductor, FresnelTerm,
    conductor,
};
use brdf::ior::Preset;
use brdf::masking::SmithSeparable;
use brdf::models::CookTorrance;
use brdf::ndf::GgxIsotropic;
use brdf::real::{F32Fma, Splat};
use brdf::{Brdf, Error, Vec3};

/// Mitsuba 3's RGB gold (the peer benchmark's workload, `benches/peers`).
const MITSUBA_GOLD: ([f32; 3], [f32; 3]) = (
    [0.143_035_98, 0.375_307_08, 1.442_045_3],
    [3.982_997, 2.385_556_4, 1.603_359_2],
);

/// The RGB IORs of every metal preset and Mitsuba's gold.
fn metals() -> Vec<(String, [f32; 3], [f32; 3])> {
    let mut m: Vec<_> = Preset::METALS
        .iter()
        .map(|p| {
            let d = p.data();
            (
                p.name().to_string(),
                d.eta.map(|x| x as f32),
                d.k.map(|x| x as f32),
            )
        })
        .collect();
    m.push(("mitsuba gold".into(), MITSUBA_GOLD.0, MITSUBA_GOLD.1));
    m
}

/// Largest relative error of `f` against the `f64` closed form over the channels, at
/// `j/n` for `j = 0 … n` and at cosines below `1/n` down to `1e-30`.
fn max_rel_error<const N: usize>(
    f: impl Fn(f32) -> [f32; N],
    eta: [f32; N],
    k: [f32; N],
    n: u32,
) -> f64 {
    let tiny = (1..=30).map(|e| 10f32.powi(-e));
    let grid = (0..=n).map(|j| (f64::from(j) / f64::from(n)) as f32);
    let mut worst = 0.0f64;
    for c in grid.chain(tiny) {
        let v = f(c);
        for ch in 0..N {
            let exact = conductor(f64::from(c), f64::from(eta[ch]), f64::from(k[ch]));
            let rel = (f64::from(v[ch]) - exact).abs() / exact;
            assert!(rel.is_finite(), "c = {c}: {} against {exact}", v[ch]);
            worst = worst.max(rel);
        }
    }
    worst
}

#[test]
fn metals_stay_within_the_tolerance_between_the_checked_points() {
    // 2²⁰ cosines: 256 between every two the constructor checked.
    for (name, eta, k) in metals() {
        let exact = Conductor::<f32, 3>::new(eta, k).unwrap();
        let fitted = FittedConductor::from_conductor(&exact).unwrap();
        let fit_err = max_rel_error(|c| fitted.eval(c), eta, k, 1 << 20);
        let f32_err = max_rel_error(|c| exact.eval(c), eta, k, 1 << 20);
        // The batch kernels' fused form (FMA Horner steps) too.
        let fused = fitted.splat::<F32Fma>();
        let fused_err = max_rel_error(|c| fused.eval(F32Fma(c)).map(|x| x.0), eta, k, 1 << 20);
        assert!(fused_err <= FIT_TOLERANCE, "{name}, fused: {fused_err:e}");
        println!(
            "{name}: fit {fit_err:.3e} (fused {fused_err:.3e}, measured at construction {:.3e}), exact formula in f32 {f32_err:.3e}",
            fitted.max_error()
        );
        assert!(fitted.max_error() <= FIT_CHECK_BOUND);
        assert!(fit_err <= FIT_TOLERANCE, "{name}: {fit_err:e}");
        // More accurate than the exact formula evaluated in f32.
        assert!(fit_err < f32_err && fused_err < f32_err, "{name}");
    }
}

#[test]
fn f64_evaluation_keeps_the_f32_accuracy() {
    let (eta, k) = MITSUBA_GOLD;
    let fitted = FittedConductor::<f64, 3>::new(eta.map(f64::from), k.map(f64::from)).unwrap();
    let mut worst = 0.0f64;
    for j in 0..=100_000 {
        let c = f64::from(j) / 100_000.0;
        let v = fitted.eval(c);
        for ch in 0..3 {
            let exact = conductor(c, f64::from(eta[ch]), f64::from(k[ch]));
            worst = worst.max((v[ch] - exact).abs() / exact);
        }
    }
    assert!(worst <= FIT_TOLERANCE, "{worst:e}");
}

#[test]
fn accepted_for_the_visible_range_metals() {
    // The region the docs promise: η ∈ [0.03, 4.8] with k ∈ [0.5, 6.5], and k up to 9.5 for
    // η ≤ 2.3 (log-spaced grids, corners included).
    let log_grid = |lo: f64, hi: f64, n: u32| {
        (0..=n).map(move |i| lo * (hi / lo).powf(f64::from(i) / f64::from(n)))
    };
    let rect = |eta_hi: f64, k_lo: f64, k_hi: f64| {
        log_grid(0.03, eta_hi, 12)
            .flat_map(move |eta| log_grid(k_lo, k_hi, 8).map(move |k| (eta, k)))
    };
    for (eta, k) in rect(4.8, 0.5, 6.5).chain(rect(2.3, 6.5, 9.5)) {
        let fit = FittedConductor::<f64, 1>::new([eta], [k]);
        assert!(fit.is_ok(), "η = {eta}, k = {k}: {fit:?}");
    }
}

#[test]
fn refused_where_the_reflectance_bends_sharply() {
    // Near a dielectric's critical angle (η < 1, small k), a plain dielectric (TIR kink),
    // and a large |η̃| (the pseudo-Brewster dip narrower than a segment).
    // Each claim near its edge: k just below 0.3 at η < 1, η ≈ 7 with a small and a metal
    // k, and k ≈ 14 at η = 3.
    let refused = [
        (0.5, 0.05),
        (0.1, 0.15),
        (0.7, 0.0),
        (7.0, 0.25),
        (7.0, 3.0),
        (3.0, 14.0),
        (30.0, 30.0),
    ];
    for (eta, k) in refused {
        match FittedConductor::<f32, 1>::new([eta], [k]) {
            Err(Error::FitInaccurate {
                max_error,
                tolerance,
            }) => {
                assert!(max_error > tolerance, "η = {eta}, k = {k}");
                assert_eq!(tolerance, FIT_CHECK_BOUND);
                let msg = FittedConductor::<f32, 1>::new([eta], [k])
                    .unwrap_err()
                    .to_string();
                assert!(msg.contains("use the exact form"), "{msg}");
            }
            other => panic!("η = {eta}, k = {k}: {other:?}"),
        }
    }
    // Invalid IORs are reported as for the exact conductor.
    assert!(matches!(
        FittedConductor::<f32, 1>::new([f32::NAN], [1.0]),
        Err(Error::NotFinite { .. })
    ));
    assert!(matches!(
        FittedConductor::<f32, 1>::new([1.0], [-1.0]),
        Err(Error::OutOfDomain { .. })
    ));
}

#[test]
fn segments_join_continuously_and_the_result_stays_in_range() {
    let (eta, k) = MITSUBA_GOLD;
    let fitted = FittedConductor::<f32, 3>::new(eta, k).unwrap();
    // At a segment boundary the two neighbouring polynomials agree to the tolerance: the
    // left one at u = 1 (the largest f32 below the boundary) and the right one at u = −1.
    for s in 1..FIT_SEGMENTS {
        let c = s as f32 / FIT_SEGMENTS as f32;
        let (left, right) = (fitted.eval(c.next_down()), fitted.eval(c));
        for ch in 0..3 {
            let rel = f64::from((left[ch] - right[ch]).abs()) / f64::from(right[ch]);
            assert!(
                rel <= 2.0 * FIT_TOLERANCE,
                "segment {s}, channel {ch}: {rel:e}"
            );
        }
    }
    // The sign of the cosine is ignored; beyond 1 it is clamped; every result in [0, 1].
    for c in [0.0f32, 1e-30, 0.3, 0.77, 1.0] {
        assert_eq!(fitted.eval(-c), fitted.eval(c), "c = {c}");
    }
    for c in [1.5, f32::INFINITY, -7.0] {
        assert_eq!(fitted.eval(c), fitted.eval(1.0), "c = {c}");
    }
    for c in [0.0, 1e-30, 0.5, 1.0, f32::NAN] {
        let v = fitted.eval(c);
        assert!(v.iter().all(|x| (0.0..=1.0).contains(x)), "c = {c}: {v:?}");
    }
    // At normal incidence the fit meets the closed form's F0 within the tolerance.
    let f0 = fitted.eval(1.0);
    for ch in 0..3 {
        let exact = conductor(1.0, f64::from(eta[ch]), f64::from(k[ch]));
        assert!((f64::from(f0[ch]) - exact).abs() <= FIT_TOLERANCE * exact);
    }
}

#[test]
fn batch_equals_the_scalar_body_on_every_instruction_set() {
    // Cook-Torrance with the fitted conductor, on pairs that cover the hemisphere
    // (a warped grid, grazing rows included).
    let (eta, k) = MITSUBA_GOLD;
    let model = CookTorrance::new(
        GgxIsotropic::<f32>::new(0.3).unwrap(),
        FittedConductor::new(eta, k).unwrap(),
        SmithSeparable,
    );
    let n = 16 * 37 + 5;
    let dir = |i: usize, salt: f32| {
        let u = ((i as f32 + 0.5) / n as f32 + salt).fract();
        let v = ((i as f32 * 0.618_034) + salt).fract();
        let z = 1.0 - u;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = std::f32::consts::TAU * v;
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    };
    let wi: Vec<Vec3<f32>> = (0..n).map(|i| dir(i, 0.0)).collect();
    let wo: Vec<Vec3<f32>> = (0..n).map(|i| dir(i, 0.37)).collect();
    let split = |w: &[Vec3<f32>]| -> [Vec<f32>; 3] {
        [
            w.iter().map(|d| d.x).collect(),
            w.iter().map(|d| d.y).collect(),
            w.iter().map(|d| d.z).collect(),
        ]
    };
    let (i3, o3) = (split(&wi), split(&wo));
    let fused = model.splat::<F32Fma>();
    for isa in Isa::ALL {
        if !isa.is_available() {
            continue;
        }
        let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        let [r, g, b] = &mut out;
        batch::eval_with(
            isa,
            &model,
            Directions::new(&i3[0], &i3[1], &i3[2]),
            Directions::new(&o3[0], &o3[1], &o3[2]),
            [r, g, b],
        )
        .unwrap();
        for j in 0..n {
            // The portable loop runs the f32 model, the others its fused form.
            let want: [f32; 3] = if isa == Isa::Portable {
                model.eval(wi[j], wo[j])
            } else {
                let w = fused.eval(
                    Vec3::new(F32Fma(wi[j].x), F32Fma(wi[j].y), F32Fma(wi[j].z)),
                    Vec3::new(F32Fma(wo[j].x), F32Fma(wo[j].y), F32Fma(wo[j].z)),
                );
                w.map(|x| x.0)
            };
            for ch in 0..3 {
                assert_eq!(
                    out[ch][j].to_bits(),
                    want[ch].to_bits(),
                    "{isa:?}, pair {j}, channel {ch}"
                );
            }
        }
    }
}

#[test]
fn average_and_normal_reflectance_follow_the_exact_conductor() {
    use brdf::models::FresnelAverage;
    let exact = Conductor::<f32, 3>::new(MITSUBA_GOLD.0, MITSUBA_GOLD.1).unwrap();
    let fitted = FittedConductor::from_conductor(&exact).unwrap();
    let (a, b) = (exact.average(), fitted.average());
    let (f0, g0) = (exact.normal_reflectance(), fitted.normal_reflectance());
    for ch in 0..3 {
        assert!(
            (a[ch] - b[ch]).abs() <= FIT_TOLERANCE * a[ch],
            "{a:?} {b:?}"
        );
        assert!(
            (f0[ch] - g0[ch]).abs() <= FIT_TOLERANCE * f0[ch],
            "{f0:?} {g0:?}"
        );
    }
}

/// The fit's worst relative error at `3 × 4096` warped cosines (uniform `u`, `u²` and
/// `1 − u²`: dense at grazing and at normal incidence), on the `f32` body and on the fused
/// form the batch kernels run.
fn worst_between_checks(fitted: &FittedConductor<f32, 1>, eta: f32, k: f32, shift: f64) -> f64 {
    let fused = fitted.splat::<F32Fma>();
    let mut worst = 0.0f64;
    for j in 0..4096 {
        let u = ((f64::from(j) + shift) / 4096.0) as f32;
        for c in [u, u * u, 1.0 - u * u] {
            let exact = conductor(f64::from(c), f64::from(eta), f64::from(k));
            for v in [fitted.eval(c)[0], fused.eval(F32Fma(c))[0].0] {
                worst = worst.max((f64::from(v) - exact).abs() / exact);
            }
        }
    }
    worst
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(32))]

    /// Inside the documented region every IOR is accepted and holds the bound between the
    /// checked cosines.
    #[test]
    fn the_documented_region_is_accepted_and_holds_its_bound(
        log_eta in (0.03f64).log10()..(4.8f64).log10(),
        log_k in (0.5f64).log10()..(6.5f64).log10(),
        shift in 0.0f64..1.0,
    ) {
        let (eta, k) = (10f64.powf(log_eta) as f32, 10f64.powf(log_k) as f32);
        let fitted = FittedConductor::<f32, 1>::new([eta], [k]);
        proptest::prop_assert!(fitted.is_ok(), "η = {}, k = {}: {:?}", eta, k, fitted);
        let worst = worst_between_checks(&fitted.unwrap(), eta, k, shift);
        proptest::prop_assert!(worst <= FIT_TOLERANCE, "η = {}, k = {}: {:e}", eta, k, worst);
    }

    /// Whenever the constructor accepts an IOR, the fit holds its bound between the checked
    /// cosines. IORs from the domain's smallest `η` (1e-4) and `k = 0` (dielectrics, with
    /// and without TIR) up to 10^1.5, beyond which every IOR is refused (`η ≳ 6` or
    /// `k ≳ 10`; the refusal tests).
    #[test]
    fn an_accepted_fit_holds_its_bound_between_the_checked_points(
        log_eta in -4.0f64..1.5,
        log_k in proptest::prop_oneof![4 => -4.0f64..1.5, 1 => proptest::strategy::Just(f64::NEG_INFINITY)],
        shift in 0.0f64..1.0,
    ) {
        let (eta, k) = (10f64.powf(log_eta) as f32, 10f64.powf(log_k) as f32);
        if let Ok(fitted) = FittedConductor::<f32, 1>::new([eta], [k]) {
            let worst = worst_between_checks(&fitted, eta, k, shift);
            proptest::prop_assert!(worst <= FIT_TOLERANCE, "η = {}, k = {}: {:e}", eta, k, worst);
        }
    }
}
