//! Multiple-scattering compensation (issue 13, part 3): the fitted albedo series against
//! `energy::directional_albedo`, the white furnace of Kulla-Conty and Turquin, reciprocity
//! (and Turquin's documented violation), albedo ≤ 1 with a coloured conductor, f32 / f64 /
//! f32x8 agreement, the batch path, χ² of the samplers, the closed-form Fresnel averages, and
//! a stochastic reference: the random walk on the Smith microsurface of Heitz, Hanika,
//! d'Eon and Dachsbacher 2016.
mod common;

use brdf::analysis::{AlbedoConfig, directional_albedo as albedo_of};
use brdf::batch::{self, BatchBrdf, Directions, Isa};
use brdf::energy::{self, Distribution};
use brdf::fresnel::{Conductor, F82Tint, FresnelTerm, NoFresnel, Schlick};
use brdf::ior::Preset;
use brdf::masking::SmithHeightCorrelated;
use brdf::models::{
    AlbedoFit, CookTorrance, FIT_TABLE_LOW, FIT_TABLE_NODES, FIT_TERMS, FresnelAverage, KullaConty,
    Reciprocity, Turquin, albedo_fit_alpha, albedo_fit_node, albedo_fit_table,
};
use brdf::ndf::{Beckmann, Ggx, GgxIsotropic, SmithLambda};
use brdf::real::{F32Fma, F32FmaSharedDiv, Splat};
use brdf::sampling::{NormalSampler, VisibleNormals};
use brdf::{Brdf, Real, SampleBrdf, Vec3, f32x8};
use common::chi2::{Chi2Config, Rng};
use proptest::prelude::*;

type Ct<D, F> = CookTorrance<f64, D, F, SmithHeightCorrelated>;

fn wo_of(mu: f64) -> Vec3<f64> {
    Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu)
}

fn ggx<F>(alpha: f64, f: F) -> Ct<Ggx<f64>, F> {
    CookTorrance::new(Ggx::new(alpha).unwrap(), f, SmithHeightCorrelated)
}

fn beckmann<F>(alpha: f64, f: F) -> Ct<Beckmann<f64>, F> {
    CookTorrance::new(Beckmann::new(alpha).unwrap(), f, SmithHeightCorrelated)
}

fn gold() -> Conductor<f64, 3> {
    Conductor::from_preset(Preset::Gold).unwrap()
}

const ALPHAS: [f64; 10] = [1e-4, 1e-3, 0.01, 0.03, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0];

// ------------------------------------------------------------------------------------------
// The series
// ------------------------------------------------------------------------------------------

/// The series against a direct `directional_albedo`, on μ ∈ [0.05, 1] (the furnace domain)
/// and, reported separately, at grazing μ down to 1e-3.
#[test]
fn albedo_series_matches_the_direct_quadrature() {
    let mus: Vec<f64> = (0..20).map(|k| 0.05 + 0.95 * f64::from(k) / 19.0).collect();
    let grazing = [1e-3, 3e-3, 0.01, 0.02, 0.035];
    for dist in [Distribution::Ggx, Distribution::Beckmann] {
        let (mut worst, mut worst_g) = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0));
        for alpha in ALPHAS {
            let fit = AlbedoFit::<f64>::new(dist, alpha).unwrap();
            for &mu in mus.iter().chain(&grazing) {
                let e = energy::directional_albedo(dist, alpha, mu).unwrap();
                let err = (fit.eval(mu) - e).abs();
                let w = if mu < 0.05 { &mut worst_g } else { &mut worst };
                if err > w.0 {
                    *w = (err, alpha, mu);
                }
            }
        }
        eprintln!(
            "{dist:?}: |series − E| ≤ {:.2e} on μ ∈ [0.05, 1] (at α {}, μ {}); {:.2e} at \
             grazing μ ∈ [1e-3, 0.05) (at α {}, μ {})",
            worst.0, worst.1, worst.2, worst_g.0, worst_g.1, worst_g.2
        );
        assert!(worst.0 <= 1e-4, "{dist:?}: {worst:?}");
        assert!(worst_g.0 <= 1e-3, "{dist:?} grazing: {worst_g:?}");
    }
}

/// `E_avg` of the series against `energy::average_albedo`.
#[test]
fn series_average_matches_average_albedo() {
    for dist in [Distribution::Ggx, Distribution::Beckmann] {
        for alpha in [1e-3, 0.1, 0.5, 1.0] {
            let fit = AlbedoFit::<f64>::new(dist, alpha).unwrap();
            let e = energy::average_albedo(dist, alpha).unwrap();
            assert!(
                (fit.average() - e).abs() < 1e-4,
                "{dist:?} α {alpha}: {} vs {e}",
                fit.average()
            );
        }
    }
}

// ------------------------------------------------------------------------------------------
// The shipped coefficient table c_k(α_m) and its interpolation (AlbedoFit::new)
// ------------------------------------------------------------------------------------------

const DISTS: [Distribution; 2] = [Distribution::Ggx, Distribution::Beckmann];

/// Every shipped coefficient of the rows `rows` equals the generator's, bit for bit.
fn check_fit_rows(rows: impl Iterator<Item = usize> + Clone) {
    for dist in DISTS {
        let table = albedo_fit_table(dist);
        assert_eq!(table.len(), FIT_TABLE_NODES * FIT_TERMS, "{dist:?}");
        for m in rows.clone() {
            let now = albedo_fit_node(dist, m);
            for (k, c) in now.iter().enumerate() {
                let shipped = table[m * FIT_TERMS + k];
                assert_eq!(
                    shipped.to_bits(),
                    c.to_bits(),
                    "{dist:?} node {m} c_{k}: shipped {shipped}, regenerated {c}: run \
                     `cargo run --release -p brdf-tools --bin energy_tables -- --fit`"
                );
            }
        }
    }
}

/// A deterministic subset: both ends of both segments and one row between.
#[test]
fn fit_table_matches_the_generator_on_a_subset_of_nodes() {
    check_fit_rows([0, FIT_TABLE_LOW - 1, FIT_TABLE_LOW, 23, FIT_TABLE_NODES - 1].into_iter());
}

#[test]
#[ignore = "full regeneration (80 fits, a few seconds at opt-level 2); CI runs it with --ignored"]
fn fit_table_matches_the_generator_everywhere() {
    check_fit_rows(0..FIT_TABLE_NODES);
}

/// At a node the interpolant is the node: `new`'s coefficients are the shipped row (no
/// quadrature here), and the node `α` lie in their segments, descending.
#[test]
fn tabulated_fit_reproduces_the_nodes() {
    for dist in DISTS {
        let table = albedo_fit_table(dist);
        for m in 0..FIT_TABLE_NODES {
            let alpha = albedo_fit_alpha(m);
            let fit = AlbedoFit::<f64>::new(dist, alpha).unwrap();
            assert_eq!(fit.alpha(), alpha);
            for (k, &c) in fit.coefficients().iter().enumerate() {
                let node = f64::from(table[m * FIT_TERMS + k]);
                assert!(
                    (c - node).abs() <= 1e-12,
                    "{dist:?} node {m} c_{k}: {c} vs {node}"
                );
            }
        }
    }
    let split = split_alpha();
    for m in 0..FIT_TABLE_NODES {
        let a = albedo_fit_alpha(m);
        if m < FIT_TABLE_LOW {
            assert!((1e-4..split).contains(&a), "node {m}: {a}");
        } else {
            assert!((split..=1.0).contains(&a), "node {m}: {a}");
        }
        if m + 1 != FIT_TABLE_LOW && m + 1 < FIT_TABLE_NODES {
            assert!(albedo_fit_alpha(m + 1) < a, "node {m}");
        }
    }
}

/// `α_s` of the docs, derived independently: the `α` at which the most grazing fit node
/// `μ(t_0) = α(1 + t_0)/(1 + 2α − t_0)` meets `directional_albedo`'s floor 1e-6, by
/// bisection.
fn split_alpha() -> f64 {
    let t0 = (std::f64::consts::PI * (FIT_TERMS as f64 - 0.5) / FIT_TERMS as f64).cos();
    let mu = |a: f64| a * (1.0 + t0) / (1.0 + 2.0 * a - t0);
    let (mut lo, mut hi) = (1e-5, 1e-2);
    for _ in 0..100 {
        let m = 0.5 * (lo + hi);
        if mu(m) < 1e-6 {
            lo = m;
        } else {
            hi = m;
        }
    }
    assert!((lo - 6.48e-4).abs() < 1e-6, "{lo}");
    lo
}

/// Test roughnesses between the nodes: the midpoint (in the segment's warp, `ln α` or `√α`)
/// of every pair of neighbouring nodes, and the segment ends (1e-4, `α_s` from either side, 1).
fn between_the_nodes() -> Vec<f64> {
    let split = split_alpha();
    let mut alphas = vec![1e-4, split * (1.0 - 1e-9), split, 1.0];
    for m in 0..FIT_TABLE_NODES - 1 {
        if m + 1 == FIT_TABLE_LOW {
            continue;
        }
        let (a, b) = (albedo_fit_alpha(m), albedo_fit_alpha(m + 1));
        alphas.push(if m < FIT_TABLE_LOW {
            (a * b).sqrt()
        } else {
            (0.5 * (a.sqrt() + b.sqrt())).powi(2)
        });
    }
    alphas
}

/// The worst `|new − integrate|` in `E(μ)` (201 cosines, uniform in the warped `t`) and in
/// `E_avg` over `alphas`, with where they are.
fn added_error(dist: Distribution, alphas: &[f64]) -> ((f64, f64, f64), (f64, f64)) {
    let (mut worst, mut worst_avg) = ((0.0, 0.0, 0.0), (0.0, 0.0));
    for &alpha in alphas {
        let table = AlbedoFit::<f64>::new(dist, alpha).unwrap();
        let direct = AlbedoFit::<f64>::integrate(dist, alpha).unwrap();
        for q in 0..=200 {
            let t = -1.0 + f64::from(q) / 100.0;
            let mu = (alpha * (1.0 + t) / (1.0 + 2.0 * alpha - t)).clamp(0.0, 1.0);
            let err = (table.eval(mu) - direct.eval(mu)).abs();
            if err > worst.0 {
                worst = (err, alpha, mu);
            }
        }
        let err = (table.average() - direct.average()).abs();
        if err > worst_avg.0 {
            worst_avg = (err, alpha);
        }
    }
    (worst, worst_avg)
}

/// The tabulated fit adds at most 1e-5 to the integrated one (issue 13 §3 target), in
/// `E(μ)` and `E_avg`: a lean subset of the roughnesses between the nodes (every fourth
/// interval, the segment ends, and the interval where the full sweep peaks).
#[test]
fn tabulated_fit_is_within_1e_5_of_the_integrated_fit_on_a_subset() {
    let all = between_the_nodes();
    let subset: Vec<f64> = all
        .iter()
        .copied()
        .step_by(4)
        .chain([all[1], all[2]])
        .collect();
    for dist in DISTS {
        let (e, avg) = added_error(dist, &subset);
        eprintln!(
            "{dist:?}: |new − integrate| ≤ {:.2e} in E (α {:.3e}, μ {:.3e}), {:.2e} in E_avg \
             (α {:.3e})",
            e.0, e.1, e.2, avg.0, avg.1
        );
        assert!(e.0 <= 1e-5, "{dist:?}: {e:?}");
        assert!(avg.0 <= 1e-5, "{dist:?}: {avg:?}");
    }
}

/// Every interval between the nodes, and against `energy::directional_albedo` as well: the
/// error each fit makes against the quadrature at 24 cosines (`μ ∈ [1e-3, 1]`), printed,
/// and the tabulated fit's excess over the integrated fit's bounded by 1e-5.
#[test]
#[ignore = "full sweep (about 160 fits and 2000 albedo quadratures, 23 s at opt-level 2); CI runs it with --ignored"]
fn tabulated_fit_is_within_1e_5_of_the_integrated_fit_everywhere() {
    let alphas = between_the_nodes();
    let mus: Vec<f64> = (0..24)
        .map(|k| 10f64.powf(-3.0 * f64::from(k) / 23.0))
        .collect();
    for dist in DISTS {
        let (e, avg) = added_error(dist, &alphas);
        let (mut table_err, mut direct_err, mut excess) = (0.0f64, 0.0f64, 0.0f64);
        for &alpha in &alphas {
            let table = AlbedoFit::<f64>::new(dist, alpha).unwrap();
            let direct = AlbedoFit::<f64>::integrate(dist, alpha).unwrap();
            for &mu in &mus {
                let truth = energy::directional_albedo(dist, alpha, mu).unwrap();
                let (a, b) = (
                    (table.eval(mu) - truth).abs(),
                    (direct.eval(mu) - truth).abs(),
                );
                table_err = table_err.max(a);
                direct_err = direct_err.max(b);
                excess = excess.max(a - b);
            }
        }
        eprintln!(
            "{dist:?}: |new − integrate| ≤ {:.2e} in E (α {:.3e}, μ {:.3e}), {:.2e} in E_avg \
             (α {:.3e}); against directional_albedo: new {table_err:.2e}, integrate \
             {direct_err:.2e}, excess {excess:.2e}",
            e.0, e.1, e.2, avg.0, avg.1
        );
        assert!(e.0 <= 1e-5 && avg.0 <= 1e-5, "{dist:?}: {e:?} {avg:?}");
        assert!(excess <= 1e-5, "{dist:?}: {excess}");
    }
}

/// `new` validates `α` as `directional_albedo` does (same parameter name and domain), at
/// both ends of `[1e-4, 1]` and outside.
#[test]
fn tabulated_fit_validates_alpha() {
    for dist in DISTS {
        for ok in [1e-4, 1.0] {
            let fit = AlbedoFit::<f32>::new(dist, ok).unwrap();
            assert!(fit.average() > 0.0 && fit.average() <= 1.0);
        }
        for bad in [0.0, 9.9e-5, 1.0 + 1e-12, -0.5] {
            let e = AlbedoFit::<f32>::new(dist, bad).unwrap_err();
            let d = energy::directional_albedo(dist, bad, 0.5).unwrap_err();
            assert_eq!(e, d, "{dist:?} α {bad}");
            assert!(matches!(e, brdf::Error::OutOfDomain { param: "alpha", .. }));
        }
        let e = AlbedoFit::<f64>::new(dist, f64::NAN).unwrap_err();
        assert!(
            matches!(e, brdf::Error::NotFinite { param: "alpha" }),
            "{e:?}"
        );
    }
}

#[test]
fn anisotropic_ndf_is_a_typed_error() {
    let ct = CookTorrance::new(
        Ggx::anisotropic(0.3, 0.5).unwrap(),
        NoFresnel,
        SmithHeightCorrelated,
    );
    let e = KullaConty::<_, f64, 1>::new(ct).unwrap_err();
    assert!(
        matches!(e, brdf::Error::OutOfDomain { param: "alpha_y", value, .. } if value == 0.5),
        "{e:?}"
    );
    assert!(Turquin::<_, f64, 1>::new(ct).is_err());
    assert!(AlbedoFit::<f32>::new(Distribution::Ggx, 0.0).is_err());
}

// ------------------------------------------------------------------------------------------
// Fresnel averages
// ------------------------------------------------------------------------------------------

#[test]
fn fresnel_average_closed_forms_match_quadrature() {
    let s = Schlick::<f64, 3>::with_f90([0.04, 0.5, 0.9], [1.0, 0.8, 0.95]).unwrap();
    let (a, q) = (s.average(), energy::fresnel_average(&s));
    for c in 0..3 {
        assert!(
            (a[c] - q[c]).abs() < 1e-12,
            "Schlick {c}: {} vs {}",
            a[c],
            q[c]
        );
    }
    for p in [
        Preset::Gold,
        Preset::Copper,
        Preset::Silver,
        Preset::Aluminium,
    ] {
        let f = F82Tint::<f64, 3>::from_preset(p).unwrap();
        let (a, q) = (f.average(), energy::fresnel_average(&f));
        for c in 0..3 {
            assert!(
                (a[c] - q[c]).abs() < 1e-10,
                "{p:?} F82 {c}: {} vs {}",
                a[c],
                q[c]
            );
        }
        // The exact conductor's average is its own quadrature (per channel).
        let exact = Conductor::<f64, 3>::from_preset(p).unwrap();
        assert_eq!(exact.average(), energy::fresnel_average(&exact));
        assert_eq!(exact.normal_reflectance(), exact.eval(1.0));
    }
    let f = F82Tint::<f64, 1>::new([0.8], [0.6]).unwrap();
    let (a, q) = (f.average(), energy::fresnel_average(&f));
    assert!((a[0] - q[0]).abs() < 1e-12);
    // And as Kulla & Conty tabulate it: F_avg of Schlick is (20 F0 + 1)/21.
    assert!((energy::f82_average(0.5, 0.0) - 11.0 / 21.0).abs() < 1e-15);
}

// ------------------------------------------------------------------------------------------
// White furnace
// ------------------------------------------------------------------------------------------

const FURNACE_MUS: [f64; 6] = [0.05, 0.1, 0.25, 0.5, 0.75, 1.0];

fn furnace<M: Brdf<f64, 1>>(name: &str, m: &M, alpha: f64, worst: &mut (f64, f64, f64)) {
    for mu in FURNACE_MUS {
        let [rho] = albedo_of::<_, f64, 1>(m, wo_of(mu), &AlbedoConfig::DEFAULT);
        let err = (rho - 1.0).abs();
        assert!(err <= 1e-3, "{name} α {alpha} μ {mu}: albedo {rho}");
        if err > worst.0 {
            *worst = (err, alpha, mu);
        }
    }
}

/// `F = 1`: the compensated albedo (the model integrated by the crate's adaptive
/// quadrature) is 1 within 1e-3 for α ∈ [1e-4, 1], μo ∈ [0.05, 1], GGX and Beckmann.
#[test]
fn kulla_conty_closes_the_white_furnace() {
    let mut worst = (0.0, 0.0, 0.0);
    for alpha in ALPHAS {
        furnace(
            "KC GGX",
            &KullaConty::<_, f64, 1>::new(ggx(alpha, NoFresnel)).unwrap(),
            alpha,
            &mut worst,
        );
        furnace(
            "KC Beckmann",
            &KullaConty::<_, f64, 1>::new(beckmann(alpha, NoFresnel)).unwrap(),
            alpha,
            &mut worst,
        );
    }
    eprintln!(
        "Kulla-Conty furnace: |ρ − 1| ≤ {:.2e} (at α {}, μ {})",
        worst.0, worst.1, worst.2
    );
}

#[test]
fn turquin_closes_the_white_furnace() {
    let mut worst = (0.0, 0.0, 0.0);
    for alpha in ALPHAS {
        furnace(
            "Turquin GGX",
            &Turquin::<_, f64, 1>::new(ggx(alpha, NoFresnel)).unwrap(),
            alpha,
            &mut worst,
        );
        let iso = CookTorrance::new(
            GgxIsotropic::new(alpha).unwrap(),
            NoFresnel,
            SmithHeightCorrelated,
        );
        furnace(
            "Turquin GGX iso",
            &Turquin::<_, f64, 1>::new(iso).unwrap(),
            alpha,
            &mut worst,
        );
        furnace(
            "Turquin Beckmann",
            &Turquin::<_, f64, 1>::new(beckmann(alpha, NoFresnel)).unwrap(),
            alpha,
            &mut worst,
        );
    }
    eprintln!(
        "Turquin furnace: |ρ − 1| ≤ {:.2e} (at α {}, μ {})",
        worst.0, worst.1, worst.2
    );
}

/// Without compensation the furnace is far from closed at α = 1 (what the wrappers fix).
#[test]
fn uncompensated_lobe_loses_energy() {
    let [rho] = albedo_of::<_, f64, 1>(&ggx(1.0, NoFresnel), wo_of(1.0), &AlbedoConfig::DEFAULT);
    assert!(rho < 0.9, "{rho}");
}

// ------------------------------------------------------------------------------------------
// Energy with a coloured conductor; reciprocity
// ------------------------------------------------------------------------------------------

/// Gold (exact complex IOR): the compensated albedo stays ≤ 1 per channel and gains over
/// the single-scattering lobe; the gain is `F_ms (1 − E(μo))` exactly (the added lobe's
/// closed-form integral).
#[test]
fn gold_albedo_is_at_most_one_and_gains() {
    for alpha in [0.3, 0.6, 1.0] {
        let ss = ggx(alpha, gold());
        let kc = KullaConty::<_, f64, 3>::new(ss).unwrap();
        let tq = Turquin::<_, f64, 3>::new(ss).unwrap();
        for mu in [0.05, 0.3, 0.7, 1.0] {
            let wo = wo_of(mu);
            let a = albedo_of::<_, f64, 3>(&ss, wo, &AlbedoConfig::DEFAULT);
            let b = albedo_of::<_, f64, 3>(&kc, wo, &AlbedoConfig::DEFAULT);
            let t = albedo_of::<_, f64, 3>(&tq, wo, &AlbedoConfig::DEFAULT);
            let e = kc.albedo().eval(mu);
            for c in 0..3 {
                assert!(
                    b[c] <= 1.0 + 1e-6 && t[c] <= 1.0 + 1e-6,
                    "α {alpha} μ {mu}: {b:?} {t:?}"
                );
                assert!(b[c] > a[c] && t[c] > a[c]);
                let gain = kc.f_ms()[c] * (1.0 - e);
                assert!(
                    (b[c] - a[c] - gain).abs() < 1e-6,
                    "gain {} vs {gain}",
                    b[c] - a[c]
                );
            }
        }
    }
}

/// Kulla-Conty over GGX and the exact gold conductor.
type GoldKc = KullaConty<Ct<Ggx<f64>, Conductor<f64, 3>>, f64, 3>;

fn reciprocity_models() -> Vec<GoldKc> {
    [0.05, 0.4, 1.0]
        .iter()
        .map(|&a| KullaConty::new(ggx(a, gold())).unwrap())
        .collect()
}

proptest! {
    #![proptest_config(common::config(256))]

    /// f(wi, wo) = f(wo, wi) within 1e-5 relative, grazing included.
    #[test]
    fn kulla_conty_is_reciprocal(k in 0usize..3, wi in common::direction(), wo in common::direction()) {
        thread_local!(static MODELS: Vec<GoldKc> = reciprocity_models());
        MODELS.with(|m| {
            let (a, b) = (m[k].eval(wi, wo), m[k].eval(wo, wi));
            for c in 0..3 {
                let scale = a[c].abs().max(b[c].abs()).max(1e-300);
                prop_assert!((a[c] - b[c]).abs() <= 1e-5 * scale, "{a:?} vs {b:?}");
                prop_assert!(a[c].is_finite() && a[c] >= 0.0);
            }
            Ok(())
        })?;
    }
}

/// Turquin's factor depends on `wo` only: a violating pair exists, and the declaration says
/// so (Kulla-Conty's says reciprocal).
#[test]
fn turquin_is_not_reciprocal() {
    let ss = ggx(0.8, gold());
    let tq = Turquin::<_, f64, 3>::new(ss).unwrap();
    assert!(matches!(
        tq.properties().reciprocity,
        Reciprocity::NotReciprocal { .. }
    ));
    let kc = KullaConty::<_, f64, 3>::new(ss).unwrap();
    assert_eq!(kc.properties().reciprocity, Reciprocity::Reciprocal);
    let (wi, wo) = (wo_of(0.1), Vec3::new(-0.3, 0.2, (1.0f64 - 0.13).sqrt()));
    let (a, b) = (tq.eval(wi, wo)[0], tq.eval(wo, wi)[0]);
    assert!(
        (a - b).abs() > 0.05 * a.max(b),
        "f(wi, wo) {a} vs f(wo, wi) {b}"
    );
    // And the factor is the energy module's formula.
    let e = tq.albedo().eval(wo.z);
    let f0 = gold().eval(1.0)[0];
    assert!((tq.factor(wo.z)[0] - energy::turquin_factor(f0, e)).abs() < 1e-12);
}

// ------------------------------------------------------------------------------------------
// Number types and the batch path
// ------------------------------------------------------------------------------------------

/// A direction pair `(wi, wo)`.
type Pair = (Vec3<f64>, Vec3<f64>);

fn pairs(n: usize) -> Vec<Pair> {
    let g = 0.618_033_988_749_894_9_f64;
    (0..n)
        .map(|i| {
            let i = i as f64;
            (
                common::hemisphere((i * g).fract(), (i * g * g).fract()),
                common::hemisphere((i * 0.754_877_666).fract(), (i * 0.569_840_290).fract()),
            )
        })
        .collect()
}

/// f32 against f64 (relative 2e-4, or absolute 1e-6 of the peak), and each f32x8 lane
/// against the f32 scalar bit for bit (no transcendental in the series), for both wrappers.
#[test]
fn f32_f64_and_f32x8_agree() {
    let kc = KullaConty::<_, f64, 3>::new(ggx(0.5, gold())).unwrap();
    let tq = Turquin::<_, f64, 3>::new(ggx(0.5, gold())).unwrap();
    check_types("Kulla-Conty", &kc);
    check_types("Turquin", &tq);
}

fn check_types<M>(name: &str, m: &M)
where
    M: Brdf<f64, 3> + Splat,
    M::On<f32>: Brdf<f32, 3>,
    M::On<f32x8>: Brdf<f32x8, 3>,
{
    let (m32, m8) = (m.splat::<f32>(), m.splat::<f32x8>());
    let ps = pairs(256);
    let peak = ps
        .iter()
        .map(|(a, b)| m.eval(*a, *b)[0])
        .fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    for chunk in ps.chunks(8) {
        let lane =
            |f: &dyn Fn(&Pair) -> f64| f32x8::from_fn(|l| f(&chunk[l.min(chunk.len() - 1)]) as f32);
        let wi8 = Vec3::new(lane(&|p| p.0.x), lane(&|p| p.0.y), lane(&|p| p.0.z));
        let wo8 = Vec3::new(lane(&|p| p.1.x), lane(&|p| p.1.y), lane(&|p| p.1.z));
        let wide = m8.eval(wi8, wo8);
        for (l, (wi, wo)) in chunk.iter().enumerate() {
            let (a, b) = (common::to_f32(*wi), common::to_f32(*wo));
            let single = m32.eval(a, b);
            let double = m.eval(*wi, *wo);
            for c in 0..3 {
                assert_eq!(
                    wide[c].lane(l).to_bits(),
                    single[c].to_bits(),
                    "{name}: lane {l}"
                );
                let e = (f64::from(single[c]) - double[c]).abs() / double[c].abs().max(1e-6 * peak);
                worst = worst.max(e);
            }
        }
    }
    eprintln!("{name}: f32 vs f64 ≤ {worst:.2e} relative");
    assert!(worst < 2e-4, "{name}: {worst:e}");
}

/// The batch path equals `eval` bit for bit: on `f32` for the portable loop, on `F32Fma`
/// for the FMA loops.
#[test]
fn batch_path_equals_eval() {
    let kc = KullaConty::<_, f64, 3>::new(ggx(0.5, gold()))
        .unwrap()
        .splat::<f32>();
    let tq = Turquin::<_, f64, 3>::new(ggx(0.5, gold()))
        .unwrap()
        .splat::<f32>();
    assert!(batch_check(&kc) >= 1);
    assert!(batch_check(&tq) >= 1);
}

fn batch_check<B: BatchBrdf<3>>(m: &B) -> usize {
    let ps = pairs(1000);
    let col = |f: fn(&Pair) -> f64| -> Vec<f32> { ps.iter().map(|p| f(p) as f32).collect() };
    let d = [
        col(|p| p.0.x),
        col(|p| p.0.y),
        col(|p| p.0.z),
        col(|p| p.1.x),
        col(|p| p.1.y),
        col(|p| p.1.z),
    ];
    let (fused, shared) = (m.fused(), m.shared_div());
    let mut ran = 0;
    for isa in [Isa::Portable, Isa::Avx2Fma, Isa::Avx512] {
        let mut out = [
            vec![0.0f32; ps.len()],
            vec![0.0f32; ps.len()],
            vec![0.0f32; ps.len()],
        ];
        let [o0, o1, o2] = &mut out;
        let r = batch::eval_with(
            isa,
            m,
            Directions::new(&d[0], &d[1], &d[2]),
            Directions::new(&d[3], &d[4], &d[5]),
            [o0.as_mut_slice(), o1.as_mut_slice(), o2.as_mut_slice()],
        );
        if r.is_err() {
            continue;
        }
        ran += 1;
        for i in 0..ps.len() {
            let wi = Vec3::new(d[0][i], d[1][i], d[2][i]);
            let wo = Vec3::new(d[3][i], d[4][i], d[5][i]);
            let want: [f32; 3] = if isa == Isa::Portable {
                m.eval(wi, wo)
            } else if batch::shares_divisions() {
                let f = |w: Vec3<f32>| {
                    Vec3::new(
                        F32FmaSharedDiv(w.x),
                        F32FmaSharedDiv(w.y),
                        F32FmaSharedDiv(w.z),
                    )
                };
                shared.eval(f(wi), f(wo)).map(|v| v.0)
            } else {
                let f = |w: Vec3<f32>| Vec3::new(F32Fma(w.x), F32Fma(w.y), F32Fma(w.z));
                fused.eval(f(wi), f(wo)).map(|v| v.0)
            };
            for c in 0..3 {
                assert_eq!(out[c][i].to_bits(), want[c].to_bits(), "{isa:?} pair {i}");
            }
        }
    }
    ran
}

// ------------------------------------------------------------------------------------------
// Sampling
// ------------------------------------------------------------------------------------------

/// χ² configurations in this file (Šidák correction).
const CHI2_TESTS: usize = 12;

#[test]
fn samplers_pass_chi2() {
    let kc_gold = KullaConty::<_, f64, 3>::new(ggx(0.6, gold())).unwrap();
    let kc_white = KullaConty::<_, f64, 1>::new(beckmann(1.0, NoFresnel)).unwrap();
    let tq = Turquin::<_, f64, 3>::new(ggx(0.6, gold())).unwrap();
    let cfg = Chi2Config::DEFAULT;
    for theta in [0.0f64, 45.0, 80.0, 89.0] {
        let wo = Vec3::new(theta.to_radians().sin(), 0.0, theta.to_radians().cos());
        common::chi2::check_sampler(
            &format!("KC gold θo {theta}"),
            &kc_gold,
            wo,
            &cfg,
            CHI2_TESTS,
            1e-6,
        );
        common::chi2::check_sampler(
            &format!("KC white θo {theta}"),
            &kc_white,
            wo,
            &cfg,
            CHI2_TESTS,
            1e-6,
        );
        common::chi2::check_sampler(
            &format!("Turquin θo {theta}"),
            &tq,
            wo,
            &cfg,
            CHI2_TESTS,
            1e-6,
        );
    }
}

/// The sampler's weight averages to the albedo (an unbiased estimate; 4σ), and the
/// mixture picks the added lobe with the documented probability (more at large α).
#[test]
fn sample_weights_estimate_the_albedo() {
    let kc = KullaConty::<_, f64, 1>::new(ggx(1.0, NoFresnel)).unwrap();
    let mut rng = Rng::new(7);
    for mu in [0.2, 1.0] {
        let wo = wo_of(mu);
        let n = 100_000;
        let (mut s, mut s2) = (0.0, 0.0);
        for _ in 0..n {
            let w = kc.sample(wo, rng.u3()).weight[0];
            s += w;
            s2 += w * w;
        }
        let mean = s / f64::from(n);
        let sigma = ((s2 / f64::from(n) - mean * mean) / f64::from(n)).sqrt();
        assert!(
            (mean - 1.0).abs() < 4.0 * sigma + 1e-3,
            "μ {mu}: {mean} ± {sigma}"
        );
    }
}

// ------------------------------------------------------------------------------------------
// The stochastic reference: a random walk on the Smith microsurface (Heitz et al. 2016)
// ------------------------------------------------------------------------------------------

/// Smith's Λ for any direction: `Λ(w)` above the horizon, `−1 − Λ(−w)` below (the walk's
/// downward rays), Heitz et al. 2016 §3.
fn lambda_signed<D: SmithLambda<f64>>(ndf: &D, w: Vec3<f64>) -> f64 {
    if w.z >= 0.0 {
        ndf.lambda(w)
    } else {
        -1.0 - ndf.lambda(w.scale(-1.0))
    }
}

/// The uniform height distribution on [−1, 1]: `C1(h) = (h + 1)/2` clamped; the walk's
/// result does not depend on the choice (Heitz et al. 2016, §3.2).
fn c1(h: f64) -> f64 {
    ((h + 1.0) * 0.5).clamp(0.0, 1.0)
}

/// The outcome of one walk: the energy carried out per channel (0 if truncated), the
/// number of scattering events, and the exit direction.
struct Walk<const N: usize> {
    energy: [f64; N],
    order: u32,
    exit: Vec3<f64>,
    escaped: bool,
}

/// A random walk on the conductor microsurface, entering along `−wo` (reciprocity: the
/// exit distribution is the BRDF times `cos θi`, for light from `wo`):
///
/// ```text
/// height:  upward ray w:   escapes with G1(w, h) = C1(h)^Λ(w), else
///                          h' = C1⁻¹(C1(h) / (1 − U)^(1/Λ(w)))
///          downward ray:   h' = C1⁻¹(C1(h) · U^(1/(1 + Λ(−w))))
/// facet:   wm drawn from the visible normals seen from −w (Heitz 2014)
/// bounce:  w ← reflect(−w, wm), energy ×= F(−w·wm)
/// ```
fn walk<D, F, const N: usize>(
    ndf: &D,
    fresnel: &F,
    wo: Vec3<f64>,
    rng: &mut Rng,
    max: u32,
) -> Walk<N>
where
    D: SmithLambda<f64>,
    VisibleNormals: NormalSampler<f64, D>,
    F: FresnelTerm<f64, N>,
{
    let mut w = wo.scale(-1.0);
    let mut h = f64::INFINITY;
    let mut energy = [1.0; N];
    let mut order = 0;
    loop {
        let u = 1.0 - rng.uniform(); // (0, 1]
        let c = if h.is_finite() { c1(h) } else { 1.0 };
        if w.z > 0.0 {
            let l = lambda_signed(ndf, w);
            if u > 1.0 - c.powf(l) {
                return Walk {
                    energy,
                    order,
                    exit: w,
                    escaped: true,
                };
            }
            h = 2.0 * (c / (1.0 - u).powf(1.0 / l)) - 1.0;
        } else {
            let l = lambda_signed(ndf, w.scale(-1.0));
            h = 2.0 * (c * u.powf(1.0 / (1.0 + l))) - 1.0;
        }
        order += 1;
        if order > max {
            return Walk {
                energy: [0.0; N],
                order,
                exit: w,
                escaped: false,
            };
        }
        let v = w.scale(-1.0);
        let wm = visible_normal(ndf, v, rng);
        let d = v.dot(wm);
        let f = fresnel.eval(d.clamp(0.0, 1.0));
        for k in 0..N {
            energy[k] *= f[k];
        }
        w = wm.scale(2.0 * d) + w;
    }
}

/// A microfacet normal drawn with density `∝ max(0, v·wm) D(wm)`, `wm.z > 0`, for any unit
/// `v`. Above the horizon: the crate's visible-normal sampler. Below it (an upward ray that
/// meets the microsurface): rejection from the visible normals of `g = (v.x, v.y, ε)`,
/// whose density `∝ max(0, g·wm) D` bounds the target because `g·wm ≥ v·wm` for
/// `wm.z > 0`; accepted with probability `max(0, v·wm)/max(0, g·wm) ≤ 1` (exact).
fn visible_normal<D>(ndf: &D, v: Vec3<f64>, rng: &mut Rng) -> Vec3<f64>
where
    D: SmithLambda<f64>,
    VisibleNormals: NormalSampler<f64, D>,
{
    let draw = |w: Vec3<f64>, rng: &mut Rng| {
        <VisibleNormals as NormalSampler<f64, D>>::sample_wm(ndf, w, [rng.uniform(), rng.uniform()])
    };
    if v.z > 0.0 {
        return draw(v, rng);
    }
    let g = Vec3::new(v.x, v.y, 1e-3);
    let gn = g.scale(1.0 / g.length());
    loop {
        let wm = draw(gn, rng);
        let (a, b) = (v.dot(wm), g.dot(wm));
        if a > 0.0 && rng.uniform() * b < a {
            return wm;
        }
    }
}

/// The rejection sampler of [`visible_normal`] below the horizon against quadrature: the
/// means of `wm.x` and `wm.z` under `∝ max(0, v·wm) D(wm)` within 4σ (200 000 draws).
#[test]
fn visible_normals_below_the_horizon_have_the_visible_density() {
    use brdf::ndf::Ndf;
    let ndf = Ggx::new(0.5).unwrap();
    let mut rng = Rng::new(99);
    for theta in [95.0f64, 120.0, 170.0] {
        let t = theta.to_radians();
        let v = Vec3::new(t.sin(), 0.0, t.cos());
        // ∫ g(wm) max(0, v·wm) D(wm) dωm over the upper hemisphere, in (θm, φm).
        let moment = |g: &dyn Fn(Vec3<f64>) -> f64| {
            common::integrate(
                |tm| {
                    let (st, ct) = tm.sin_cos();
                    st * common::integrate(
                        |pm| {
                            let wm = Vec3::new(st * pm.cos(), st * pm.sin(), ct);
                            g(wm) * v.dot(wm).max(0.0) * ndf.d(wm)
                        },
                        -std::f64::consts::PI,
                        std::f64::consts::PI,
                        32,
                        8,
                    )
                },
                0.0,
                std::f64::consts::FRAC_PI_2,
                32,
                8,
            )
        };
        let norm = moment(&|_| 1.0);
        let n = 200_000;
        let (mut sx, mut sz, mut sx2, mut sz2) = (0.0, 0.0, 0.0, 0.0);
        for _ in 0..n {
            let wm = visible_normal(&ndf, v, &mut rng);
            assert!(wm.z > 0.0 && v.dot(wm) > 0.0);
            sx += wm.x;
            sz += wm.z;
            sx2 += wm.x * wm.x;
            sz2 += wm.z * wm.z;
        }
        let nf = f64::from(n);
        for (name, s, s2, exact) in [
            ("x", sx, sx2, moment(&|w| w.x) / norm),
            ("z", sz, sz2, moment(&|w| w.z) / norm),
        ] {
            let mean = s / nf;
            let sigma = ((s2 / nf - mean * mean) / nf).sqrt();
            assert!(
                (mean - exact).abs() < 4.0 * sigma,
                "θ {theta} {name}: {mean} ± {sigma} vs {exact}"
            );
        }
    }
}

/// `F = 1`: every walk leaves the surface (none is truncated at 64 events), so its albedo
/// is exactly 1; and the walks that leave after one event carry the single-scattering
/// albedo `E(μo)` of `energy::directional_albedo` (within 4σ) — the walk and the crate's
/// lobe are the same microsurface.
#[test]
fn random_walk_conserves_energy_and_its_first_bounce_is_the_single_scattering_lobe() {
    let mut rng = Rng::new(0x5eed);
    for (alpha, mu) in [(0.3, 0.5), (1.0, 1.0), (1.0, 0.2), (0.6, 0.8)] {
        let ndf = Ggx::new(alpha).unwrap();
        let n = 100_000;
        let (mut total, mut single, mut truncated) = (0.0, 0.0, 0);
        for _ in 0..n {
            let r: Walk<1> = walk(&ndf, &NoFresnel, wo_of(mu), &mut rng, 64);
            assert!(!r.escaped || r.exit.z > 0.0);
            truncated += u32::from(!r.escaped);
            total += r.energy[0];
            if r.order == 1 {
                single += 1.0;
            }
        }
        let nf = f64::from(n);
        assert_eq!(truncated, 0, "α {alpha} μ {mu}");
        assert_eq!(total, nf);
        let p = single / nf;
        let sigma = (p * (1.0 - p) / nf).sqrt();
        let e = energy::directional_albedo(Distribution::Ggx, alpha, mu).unwrap();
        assert!(
            (p - e).abs() < 4.0 * sigma,
            "α {alpha} μ {mu}: walk {p} ± {sigma}, E {e}"
        );
    }
}

/// Gold: the compensated directional albedo against the walk's (Monte-Carlo noise σ ≈
/// 1.5e-3 included), per channel: within 1e-2 for α ≤ 0.5 at μo ≥ 0.5. Elsewhere the
/// compensations' own approximation shows (measured, the walk taken as the truth; the
/// walk's extra energy is in the green and blue channels, where gold's reflectance rises
/// most towards grazing): Kulla-Conty gives the second and later bounces the cosine-weighted
/// `F_avg`, but they meet the facets at more grazing local angles, so it is low by up to
/// 1.4e-2 at α = 0.5, μo = 0.2, 3.1e-2 at α = 1, μo = 1 and 4.5e-2 at α = 1, μo = 0.3
/// (bounds 2e-2, 5e-2); Turquin scales by `F0` and its direction-only factor overshoots by
/// up to 6.1e-2 at α = 1, μo = 1 (bound 7e-2; 1.4e-2 at μo = 0.3). Prints all four albedos.
#[test]
fn compensated_gold_albedo_matches_the_random_walk() {
    let mut rng = Rng::new(0xa11ce);
    for (alpha, mu, tol_kc, tol_tq) in [
        (0.3, 0.5, 1e-2, 1e-2),
        (0.5, 0.7, 1e-2, 1e-2),
        (0.5, 0.2, 2e-2, 1e-2),
        (1.0, 1.0, 5e-2, 7e-2),
        (1.0, 0.3, 5e-2, 7e-2),
    ] {
        let ss = ggx(alpha, gold());
        let kc = KullaConty::<_, f64, 3>::new(ss).unwrap();
        let tq = Turquin::<_, f64, 3>::new(ss).unwrap();
        let n = 100_000;
        let mut sum = [0.0; 3];
        for _ in 0..n {
            let r: Walk<3> = walk(&ss.ndf, &ss.fresnel, wo_of(mu), &mut rng, 64);
            for (s, e) in sum.iter_mut().zip(r.energy) {
                *s += e;
            }
        }
        let walk_albedo = sum.map(|s| s / f64::from(n));
        let a_kc = albedo_of::<_, f64, 3>(&kc, wo_of(mu), &AlbedoConfig::DEFAULT);
        let a_tq = albedo_of::<_, f64, 3>(&tq, wo_of(mu), &AlbedoConfig::DEFAULT);
        let a_ss = albedo_of::<_, f64, 3>(&ss, wo_of(mu), &AlbedoConfig::DEFAULT);
        eprintln!(
            "gold α {alpha} μ {mu}: walk {walk_albedo:.4?}, Kulla-Conty {a_kc:.4?}, Turquin \
             {a_tq:.4?}, single {a_ss:.4?}"
        );
        for c in 0..3 {
            assert!(
                (a_kc[c] - walk_albedo[c]).abs() < tol_kc,
                "KC α {alpha} μ {mu} channel {c}"
            );
            assert!(
                (a_tq[c] - walk_albedo[c]).abs() < tol_tq,
                "Turquin α {alpha} μ {mu} channel {c}"
            );
        }
    }
}

/// Lobe shapes: the walk's multiply scattered exit directions (events ≥ 2, `F = 1`)
/// binned by `cos θi` and by the half-space (`φ` towards `wo`: back, away: forward),
/// against the Kulla-Conty added lobe integrated over the same bins. Prints the slices (the
/// report quotes them); asserts only the totals (the added lobe carries `1 − E(μo)`, as
/// the walk's events ≥ 2 do).
#[test]
fn lobe_shape_slices_against_the_random_walk() {
    let alpha = 1.0;
    let ct = ggx(alpha, NoFresnel);
    let kc = KullaConty::<_, f64, 1>::new(ct).unwrap();
    let mut rng = Rng::new(42);
    const BINS: usize = 5;
    for mu in [1.0, 0.5, 0.2] {
        let wo = wo_of(mu);
        let n = 100_000;
        let mut hist = [[0.0; 2]; BINS];
        for _ in 0..n {
            let r: Walk<1> = walk(&ct.ndf, &NoFresnel, wo, &mut rng, 64);
            if r.order >= 2 && r.escaped {
                let b = ((r.exit.z * BINS as f64) as usize).min(BINS - 1);
                // Normal view has no back or forward: split by the sign of x.
                let back = if wo.x == 0.0 {
                    usize::from(r.exit.x >= 0.0)
                } else {
                    usize::from(r.exit.x * wo.x > 0.0)
                };
                hist[b][back] += 1.0 / f64::from(n);
            }
        }
        // The KC lobe's ∫ f_ms cos θi over each bin: the lobe does not depend on φ, so each
        // half-space gets half of (1 − E(μo)) F_ms/(π(1 − E_avg)) · 2π ∫ (1 − E(μ)) μ dμ.
        let e_o = kc.albedo().eval(mu);
        let k = kc.f_ms()[0] * (1.0 - e_o) / (1.0 - kc.albedo().average());
        let mut line = String::new();
        let (mut walk_total, mut kc_total) = (0.0, 0.0);
        for (b, h) in hist.iter().enumerate() {
            let (lo, hi) = (b as f64 / BINS as f64, (b + 1) as f64 / BINS as f64);
            let bin =
                common::integrate(|m| 2.0 * (1.0 - kc.albedo().eval(m)) * m, lo, hi, 2, 8) * k;
            line += &format!(
                " μi∈[{lo:.1},{hi:.1}]: walk back {:.4} fwd {:.4} | KC {:.4} each;",
                h[1],
                h[0],
                bin / 2.0
            );
            walk_total += h[0] + h[1];
            kc_total += bin;
        }
        eprintln!("α {alpha} μo {mu}:{line}");
        let sigma = (walk_total / f64::from(n)).sqrt();
        assert!(
            (walk_total - kc_total).abs() < 4.0 * sigma + 1e-3,
            "μo {mu}: walk {walk_total} vs KC {kc_total}"
        );
    }
}

/// Turquin's declaration is for the view side; the light side `∫ f(wi, wo) cos θo dωo`
/// (the transposed model's albedo) is not bounded by it: with `F = 1` it exceeds 1 — a
/// located violation, printed and asserted.
#[test]
fn turquin_light_side_albedo_exceeds_one() {
    use brdf::analysis::FnBrdf;
    let tq = Turquin::<_, f64, 1>::new(ggx(1.0, NoFresnel)).unwrap();
    let transposed = FnBrdf::new(|wi: Vec3<f64>, wo: Vec3<f64>| tq.eval(wo, wi));
    let mut worst = (0.0, 0.0);
    for mu in [0.05, 0.2, 0.5, 1.0] {
        let [rho] = albedo_of(&transposed, wo_of(mu), &AlbedoConfig::DEFAULT);
        if rho > worst.0 {
            worst = (rho, mu);
        }
    }
    eprintln!(
        "Turquin, GGX α = 1, F = 1: light-side albedo up to {:.4} (cos θi = {})",
        worst.0, worst.1
    );
    assert!(worst.0 > 1.01, "{worst:?}");
    assert!(matches!(
        tq.properties().energy,
        brdf::models::Energy::NotConserving { .. }
    ));
}
