//! The batch path: every instruction-set variant this CPU can run, per-pair and pipelined,
//! equals the scalar `eval` bit for bit — on `f32` for the portable loop, on `F32Fma` (the
//! model's fused form) for the AVX2+FMA and AVX-512 loops — and the fused form stays within
//! a stated bound of the `f32` one.
mod common;

use brdf::batch::{self, BatchBrdf, Directions, Isa};
use brdf::fast::{FastPow, HardwareEstimate};
use brdf::fresnel::{Conductor, Schlick};
use brdf::masking::{SmithHeightCorrelated, SmithSeparable};
use brdf::models::{
    CookTorrance, Lambert, MaxCos, NormalizedBlinnPhong, NormalizedBlinnPhongSpecular, Sum,
};
use brdf::ndf::{Ggx, GgxIsotropic};
use brdf::normalization::Normalization;
use brdf::real::{F32Fma, F32FmaSharedDiv};
use brdf::{Brdf, Vec3, ior};

/// `n` direction pairs by warping a deterministic low-discrepancy sequence over the
/// hemisphere (cos θ uniform in [0, 1], grazing and normal incidence included).
fn pairs(n: usize) -> [Vec<f32>; 6] {
    let mut v: [Vec<f32>; 6] = Default::default();
    let g = 0.618_033_988_749_894_9_f64;
    for i in 0..n {
        let u = [
            (i as f64 * g).fract(),
            (i as f64 * g * g).fract(),
            (i as f64 * 0.754_877_666).fract(),
            (i as f64 * 0.569_840_290).fract(),
        ];
        let a = common::hemisphere(if i % 17 == 0 { 0.0 } else { u[0] }, u[1]);
        let b = common::hemisphere(if i % 19 == 0 { 1e-7 } else { u[2] }, u[3]);
        for (k, c) in [a.x, a.y, a.z, b.x, b.y, b.z].into_iter().enumerate() {
            v[k].push(c as f32);
        }
    }
    v
}

/// A batch entry point: `batch::eval_with` or `batch::eval_pipelined_with`.
type Entry<B, const N: usize> =
    fn(Isa, &B, Directions<'_>, Directions<'_>, [&mut [f32]; N]) -> Result<(), batch::Unavailable>;

/// Runs every available variant of `entry` on `n` pairs and requires, bit for bit, `eval` on
/// the `f32` model for [`Isa::Portable`] and `eval` on its `F32Fma` form for the FMA
/// variants (a correctly rounded `fma` is the same number in software and in hardware).
/// Also requires the `F32Fma` form within `rel` (relative, or absolute below 1e-6 of the
/// peak value) of the `f32` model, and reports the largest difference. Returns how many
/// variants ran.
fn check_entry<B: BatchBrdf<N>, const N: usize>(
    brdf: &B,
    n: usize,
    entry: Entry<B, N>,
    rel: f64,
) -> usize {
    let d = pairs(n);
    let wi = Directions::new(&d[0], &d[1], &d[2]);
    let wo = Directions::new(&d[3], &d[4], &d[5]);
    let fused = brdf.fused();
    let at = |i: usize| {
        (
            Vec3::new(d[0][i], d[1][i], d[2][i]),
            Vec3::new(d[3][i], d[4][i], d[5][i]),
        )
    };
    let fma = |w: Vec3<f32>| Vec3::new(F32Fma(w.x), F32Fma(w.y), F32Fma(w.z));
    let plain: Vec<[f32; N]> = (0..n).map(|i| brdf.eval(at(i).0, at(i).1)).collect();
    let fused_ref: Vec<[f32; N]> = (0..n)
        .map(|i| fused.eval(fma(at(i).0), fma(at(i).1)).map(|v| v.0))
        .collect();
    // The FMA kernels' own form: F32FmaSharedDiv where the batch path shares divisions.
    let shared = brdf.shared_div();
    let sdv = |w: Vec3<f32>| {
        Vec3::new(
            F32FmaSharedDiv(w.x),
            F32FmaSharedDiv(w.y),
            F32FmaSharedDiv(w.z),
        )
    };
    let shared_ref: Vec<[f32; N]> = (0..n)
        .map(|i| shared.eval(sdv(at(i).0), sdv(at(i).1)).map(|v| v.0))
        .collect();
    let kernel_ref = if batch::shares_divisions() {
        &shared_ref
    } else {
        &fused_ref
    };
    // The two FMA forms agree within the same bound as the fused and f32 forms.
    for (p, q) in shared_ref.iter().zip(&fused_ref) {
        for c in 0..N {
            let (a, b) = (f64::from(p[c]), f64::from(q[c]));
            let e = (a - b).abs() / b.abs().max(f64::MIN_POSITIVE);
            assert!(e <= rel.max(1e-6), "shared vs fused: {e:e}");
        }
    }
    // The fused form against the f32 one.
    let peak = plain
        .iter()
        .flatten()
        .fold(0.0f64, |m, &v| m.max(f64::from(v)));
    let mut worst = 0.0f64;
    for (p, q) in plain.iter().zip(&fused_ref) {
        for c in 0..N {
            let (a, b) = (f64::from(q[c]), f64::from(p[c]));
            let e = (a - b).abs() / b.abs().max(1e-6 * peak).max(f64::MIN_POSITIVE);
            worst = worst.max(e);
        }
    }
    eprintln!("fused vs f32: max relative difference {worst:.3e} (bound {rel:.1e})");
    assert!(worst <= rel, "fused vs f32: {worst:e} > {rel:e}");
    let mut ran = 0;
    for isa in Isa::ALL {
        let mut out = vec![vec![f32::NAN; n]; N];
        let slices: [&mut [f32]; N] = {
            let mut it = out.iter_mut();
            core::array::from_fn(|_| it.next().unwrap().as_mut_slice())
        };
        match entry(isa, brdf, wi, wo, slices) {
            Err(e) => {
                assert!(!isa.is_available(), "{e}");
                continue;
            }
            Ok(()) => ran += 1,
        }
        let reference = if isa == Isa::Portable {
            &plain
        } else {
            kernel_ref
        };
        for i in 0..n {
            for c in 0..N {
                let (a, b) = (out[c][i], reference[i][c]);
                assert!(a.is_finite(), "{isa:?} produced {a} at {i}");
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "{isa:?} channel {c} at {i}: batch {a} vs scalar {b}"
                );
            }
        }
    }
    assert!(ran >= 1 && Isa::detect().is_available());
    ran
}

/// [`check_entry`] with the per-pair loop.
fn check<B: BatchBrdf<N>, const N: usize>(brdf: &B, n: usize, rel: f64) -> usize {
    check_entry(brdf, n, batch::eval_with, rel)
}

/// [`check_entry`] with both loops, for a model with a pipelined evaluation, at lengths that
/// cover an empty batch, a single pair, a partial block and several blocks plus a tail.
fn check_pipelined<B, const N: usize>(brdf: &B, rel: f64)
where
    B: BatchBrdf<N> + batch::Pipelined<f32, N>,
    B::Fused: batch::Pipelined<F32Fma, N>,
{
    for n in [0, 1, 1031, 2 * batch::BLOCK + 517] {
        eprintln!("per-pair {n}");
        check(brdf, n, rel);
        eprintln!("pipelined {n}");
        check_entry(brdf, n, batch::eval_pipelined_with, rel);
    }
}

#[test]
fn every_available_variant_matches_scalar_ggx_schlick() {
    let ct = CookTorrance::new(
        Ggx::<f32>::new(0.3).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    // 1031: not a multiple of any lane width, so the scalar tail runs too.
    check(&ct, 1031, 1e-6);
}

#[test]
fn every_available_variant_matches_scalar_rough_conductor_rgb() {
    let ct = CookTorrance::new(
        Ggx::<f32>::new(0.2).unwrap(),
        Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap(),
        SmithSeparable,
    );
    let sum = Sum::new(ct, Lambert::<f32, 3>::new([0.1, 0.2, 0.3]).unwrap());
    check(&sum, 517, 1e-6);
}

/// Mitsuba's rough gold workload (GGX α = 0.3, separable Smith) with `share_divisions()`.
fn shared_division_gold() -> CookTorrance<
    f32,
    GgxIsotropic<f32>,
    Conductor<f32, 3, brdf::fast::ExactSqrt, brdf::fresnel::SharedDivision>,
    SmithSeparable,
> {
    CookTorrance::new(
        GgxIsotropic::<f32>::new(0.3).unwrap(),
        Conductor::<f32, 3>::from_preset(ior::Preset::Gold)
            .unwrap()
            .share_divisions()
            .unwrap(),
        SmithSeparable,
    )
}

/// The shared-division gold with run-time parts: the explicit lanes on the FMA instruction
/// sets.
fn shared_division_gold_parts() -> Parts {
    let ct = shared_division_gold();
    CookTorrance::new(
        brdf::ndf::AnyNdf::from(ct.ndf),
        brdf::fresnel::AnyFresnel::from(ct.fresnel),
        brdf::masking::AnyMasking::from(ct.masking),
    )
}

/// A conductor whose channels share one division on divider-bound cores: the FMA kernels
/// equal `eval` on the form they run (`F32FmaSharedDiv` on Intel), and both forms agree —
/// on the one-lane loop (the static model) and on the explicit lanes (run-time parts, and a
/// `Material` holding them).
#[test]
fn every_available_variant_matches_scalar_shared_division_conductor() {
    let ct = shared_division_gold();
    let parts = shared_division_gold_parts();
    fn explicit<B: BatchBrdf<3>>(_: &B) -> bool {
        B::EXPLICIT_LANES
    }
    assert!(explicit(&parts) && !explicit(&ct));
    let material = brdf::material::Material::from(parts);
    for n in [0, 1, 15, 16, 17, 1031] {
        check(&ct, n, 1e-6);
        check(&parts, n, 1e-6);
        check(&material, n, 1e-6);
    }
    // The two forms differ somewhere, so the checks above tell which one a kernel ran.
    let d = pairs(1031);
    let differ = (0..1031)
        .filter(|&i| {
            let w = |k: usize| [d[k][i], d[k + 1][i], d[k + 2][i]];
            let (wi, wo) = (w(0), w(3));
            let f = parts
                .fused()
                .eval(wi.map(F32Fma).into(), wo.map(F32Fma).into());
            let s = parts.shared_div().eval(
                wi.map(F32FmaSharedDiv).into(),
                wo.map(F32FmaSharedDiv).into(),
            );
            (0..3).any(|c| f[c].0 != s[c].0)
        })
        .count();
    assert!(
        differ > 100,
        "{differ} of 1031 pairs differ between the forms"
    );
}

/// A model with [`HardwareEstimate`] against the same model with the exact policy, on every
/// available variant at `n` pairs: bit for bit except on [`Isa::Avx512`], where the estimates
/// act (explicit 16-lane registers); there every value is finite, within `rel` relative (or
/// absolute below 1e-6 of the peak). Returns the worst relative difference seen on `Avx512`
/// and how many values differed there (the caller checks that the estimates ran).
fn check_estimate<B, E, const N: usize>(exact: &B, estimate: &E, n: usize, rel: f64) -> (f64, usize)
where
    B: BatchBrdf<N>,
    E: BatchBrdf<N>,
{
    assert!(E::EXPLICIT_LANES && !B::EXPLICIT_LANES);
    let d = pairs(n);
    let wi = Directions::new(&d[0], &d[1], &d[2]);
    let wo = Directions::new(&d[3], &d[4], &d[5]);
    let run = |isa: Isa, est: bool| -> Option<Vec<Vec<f32>>> {
        let mut out = vec![vec![f32::NAN; n]; N];
        let slices: [&mut [f32]; N] = {
            let mut it = out.iter_mut();
            core::array::from_fn(|_| it.next().unwrap().as_mut_slice())
        };
        let r = if est {
            batch::eval_with(isa, estimate, wi, wo, slices)
        } else {
            batch::eval_with(isa, exact, wi, wo, slices)
        };
        r.ok().map(|()| out)
    };
    let (mut worst, mut differ) = (0.0f64, 0);
    for isa in Isa::ALL {
        let (Some(a), Some(b)) = (run(isa, false), run(isa, true)) else {
            assert!(!isa.is_available());
            continue;
        };
        if isa != Isa::Avx512 {
            assert_eq!(a, b, "{isa:?}: the estimate policy is exact here");
            continue;
        }
        let peak = a.iter().flatten().fold(0.0f64, |m, &v| m.max(f64::from(v)));
        for c in 0..N {
            for i in 0..n {
                let (x, y) = (f64::from(a[c][i]), f64::from(b[c][i]));
                assert!(y.is_finite(), "Avx512 estimate produced {y} at {i}");
                let e = (x - y).abs() / x.abs().max(1e-6 * peak).max(f64::MIN_POSITIVE);
                worst = worst.max(e);
                differ += usize::from(x != y);
            }
        }
        eprintln!("Avx512 estimates at {n} pairs: {differ} values differ, worst {worst:.3e}");
        assert!(worst <= rel, "Avx512 estimates: {worst:e} > {rel:e}");
    }
    (worst, differ)
}

/// The workloads of the estimate tests: GGX + Schlick (α = 0.3), the rough gold conductor,
/// and that conductor with [`HardwareEstimate`] everywhere (the half vector, the final
/// division, the conductor's roots and divisions where the batch path shares divisions).
#[allow(clippy::type_complexity)]
fn estimate_workloads() -> (
    CookTorrance<f32, GgxIsotropic<f32>, Schlick<f32, 1>, SmithHeightCorrelated>,
    CookTorrance<f32, Ggx<f32>, Conductor<f32, 3>, SmithSeparable>,
    CookTorrance<
        f32,
        Ggx<f32>,
        Conductor<f32, 3, HardwareEstimate>,
        SmithSeparable,
        HardwareEstimate,
    >,
) {
    let ggx = CookTorrance::new(
        GgxIsotropic::<f32>::new(0.3).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    let gold = CookTorrance::new(
        Ggx::<f32>::new(0.2).unwrap(),
        Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap(),
        SmithSeparable,
    );
    let gold_estimate = CookTorrance::new(
        gold.ndf,
        gold.fresnel.with_policy::<HardwareEstimate>(),
        SmithSeparable,
    )
    .with_sqrt::<HardwareEstimate>();
    (ggx, gold, gold_estimate)
}

/// The conductor's estimates act on the AVX-512 lanes only where the batch path shares
/// divisions (divider-bound cores): elsewhere the gold conductor with [`HardwareEstimate`]
/// gives the exact conductor's bits, and with the estimates only in the Cook-Torrance half
/// vector and final division the two models agree bit for bit. Both branches run in CI
/// (`.ci/run` repeats this file with `BRDF_SHARE_DIVISIONS` flipped).
#[test]
fn conductor_estimates_follow_the_division_choice() {
    let (_, gold, gold_estimate) = estimate_workloads();
    let outer_only = gold.with_sqrt::<HardwareEstimate>();
    if !Isa::Avx512.is_available() {
        eprintln!("no AVX-512 here: the estimates do not run");
        return;
    }
    let d = pairs(1031);
    let wi = Directions::new(&d[0], &d[1], &d[2]);
    let wo = Directions::new(&d[3], &d[4], &d[5]);
    let run = |m: &dyn Fn([&mut [f32]; 3])| {
        let mut out = [vec![0.0f32; 1031], vec![0.0f32; 1031], vec![0.0f32; 1031]];
        let [a, b, c] = &mut out;
        m([a.as_mut_slice(), b.as_mut_slice(), c.as_mut_slice()]);
        out
    };
    let a = run(&|o| batch::eval_with(Isa::Avx512, &outer_only, wi, wo, o).unwrap());
    let b = run(&|o| batch::eval_with(Isa::Avx512, &gold_estimate, wi, wo, o).unwrap());
    let differ = (0..3)
        .map(|c| (0..1031).filter(|&i| a[c][i] != b[c][i]).count())
        .sum::<usize>();
    let shared = batch::shares_divisions();
    eprintln!("shares_divisions() = {shared}: {differ} values differ");
    if shared {
        assert!(differ > 0, "the conductor's estimates did not run");
    } else {
        assert_eq!(
            differ, 0,
            "the conductor took estimates on a fast-divider core"
        );
    }
}

/// GGX + Schlick and the rough gold conductor with [`HardwareEstimate`] (the half vector, the
/// final division and the conductor's roots and divisions): within 1e-6 relative of the
/// exact policy on AVX-512 (a few ULP: each estimate is within 1 ULP, `real::lanes`'s tests),
/// bit for bit elsewhere, at lengths around the 16-lane blocks and the masked tail.
#[test]
fn hardware_estimates_within_a_few_ulp_of_exact() {
    let (ggx, gold, gold_estimate) = estimate_workloads();
    let ggx_estimate = ggx.with_sqrt::<HardwareEstimate>();
    // Smaller roughness: the GGX peak is sharper, its relative error the same.
    let sharp = CookTorrance::new(
        GgxIsotropic::<f32>::new(1e-3).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    let sharp_estimate = sharp.with_sqrt::<HardwareEstimate>();
    // The conductor sharing its division (on the shared lanes where the batch path shares).
    let shared = CookTorrance::new(
        gold.ndf,
        gold.fresnel.share_divisions().unwrap(),
        SmithSeparable,
    );
    let shared_estimate = CookTorrance::new(
        gold.ndf,
        gold_estimate.fresnel.share_divisions().unwrap(),
        SmithSeparable,
    )
    .with_sqrt::<HardwareEstimate>();
    let (mut worst, mut differ) = ([0.0f64; 4], 0);
    for n in [0, 1, 15, 16, 17, 1031, 4099] {
        for (k, (w, d)) in [
            check_estimate(&ggx, &ggx_estimate, n, 1e-6),
            check_estimate(&gold, &gold_estimate, n, 1e-6),
            check_estimate(&sharp, &sharp_estimate, n, 1e-6),
            check_estimate(&shared, &shared_estimate, n, 1e-6),
        ]
        .into_iter()
        .enumerate()
        {
            worst[k] = worst[k].max(w);
            differ += d;
        }
    }
    let [g, c, s, d] = worst;
    eprintln!(
        "worst relative: GGX {g:.2e}, gold {c:.2e}, GGX α = 1e-3 {s:.2e}, gold shared {d:.2e}"
    );
    // Each estimate is within 1 ULP, so most values round alike; the conductor's twelve
    // estimated operations per evaluation make some differ (the estimates did run).
    if Isa::Avx512.is_available() {
        assert!(
            differ > 0,
            "Avx512: no value differs, the estimates did not run"
        );
    }
}

#[test]
fn pipelined_cook_torrance_matches_scalar() {
    check_pipelined(
        &CookTorrance::new(
            GgxIsotropic::<f32>::new(0.3).unwrap(),
            Schlick::<f32, 1>::new([0.04]).unwrap(),
            SmithHeightCorrelated,
        ),
        1e-6,
    );
    check_pipelined(
        &CookTorrance::new(
            Ggx::<f32>::anisotropic(0.05, 0.4).unwrap(),
            Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap(),
            SmithSeparable,
        ),
        1e-6,
    );
}

#[test]
fn pipelined_normalized_blinn_phong_matches_scalar() {
    let fit = Normalization::TRI_ACE_2009_FIT;
    check_pipelined(
        &NormalizedBlinnPhong::new([0.5_f32], 0.5, [0.04], 64.0, fit)
            .unwrap()
            .with_pow::<FastPow>(),
        1e-6,
    );
    check_pipelined(
        &NormalizedBlinnPhong::new(
            [0.2_f32, 0.5, 0.7],
            0.8,
            [0.04, 0.05, 0.9],
            1e4,
            Normalization::TriAceExact,
        )
        .unwrap()
        .with_denominator::<MaxCos>(),
        1e-6,
    );
    check_pipelined(
        &NormalizedBlinnPhongSpecular::new(1.0_f32, [0.04, 0.5, 1.0], 0.0, fit)
            .unwrap()
            .with_pow::<FastPow>(),
        1e-6,
    );
}

#[test]
fn glam_convenience_matches_scalar() {
    let ct = CookTorrance::new(
        Ggx::<f32>::new(0.5).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    let d = pairs(700);
    let wi: Vec<glam::Vec3> = (0..700)
        .map(|i| glam::Vec3::new(d[0][i], d[1][i], d[2][i]))
        .collect();
    let wo: Vec<glam::Vec3> = (0..700)
        .map(|i| glam::Vec3::new(d[3][i], d[4][i], d[5][i]))
        .collect();
    let mut out = vec![[0.0f32; 1]; 700];
    batch::eval_glam(&ct, &wi, &wo, &mut out);
    for i in 0..700 {
        let f = ct.eval(wi[i].into(), wo[i].into())[0];
        assert!(
            (out[i][0] - f).abs() <= 2e-5 * f.abs().max(1e-6),
            "{i}: {} vs {f}",
            out[i][0]
        );
    }
    // With the hardware estimates: the bits of `batch::eval` on the same pairs (whose
    // estimate path the test above bounds), through the same kernel.
    let estimate = ct.with_sqrt::<HardwareEstimate>();
    batch::eval_glam(&estimate, &wi, &wo, &mut out);
    let mut soa = vec![0.0f32; 700];
    batch::eval(
        &estimate,
        Directions::new(&d[0], &d[1], &d[2]),
        Directions::new(&d[3], &d[4], &d[5]),
        [&mut soa],
    );
    for i in 0..700 {
        assert_eq!(out[i][0].to_bits(), soa[i].to_bits(), "{i}");
    }
}

#[test]
#[should_panic(expected = "differ in length")]
fn mismatched_lengths_panic() {
    let ct = Lambert::<f32, 1>::new([0.5]).unwrap();
    let a = [0.0f32; 4];
    let mut out = [0.0f32; 3];
    batch::eval(
        &ct,
        Directions::new(&a, &a, &a),
        Directions::new(&a, &a, &a),
        [&mut out],
    );
}

/// `batch::sample_with` on every available variant equals `SampleBrdf::sample` bit for bit:
/// on the `f32` model for the portable loop, on the form the FMA loops run for the FMA loops
/// (`F32FmaSharedDiv` where `batch::shares_divisions()`, explicit lanes included, else
/// `F32Fma`).
fn check_sample<B, const N: usize>(name: &str, brdf: &B, n: usize) -> usize
where
    B: batch::BatchSample<N>,
    B::Fused: brdf::SampleBrdf<F32Fma, N>,
    B::SharedDiv: brdf::SampleBrdf<F32FmaSharedDiv, N>,
{
    use brdf::SampleBrdf;
    let d = pairs(n);
    let wo = Directions::new(&d[3], &d[4], &d[5]);
    // u from the other columns, mapped into [0, 1): wi.x, wi.y ∈ [−1, 1], wi.z ∈ [0, 1].
    let u: [Vec<f32>; 3] = [
        d[0].iter()
            .map(|x| (0.5 * (x + 1.0)).min(0.999_999_9))
            .collect(),
        d[1].iter()
            .map(|y| (0.5 * (y + 1.0)).min(0.999_999_9))
            .collect(),
        d[2].iter().map(|z| z.min(0.999_999_9)).collect(),
    ];
    let (fused, shared) = (brdf.fused(), brdf.shared_div());
    let mut ran = 0;
    for isa in Isa::ALL {
        let (mut x, mut y, mut z, mut pdf) =
            (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut w: [Vec<f32>; N] = core::array::from_fn(|_| vec![0.0; n]);
        let mut out = batch::SampleOut {
            x: &mut x,
            y: &mut y,
            z: &mut z,
            pdf: &mut pdf,
            weight: w.each_mut().map(|c| c.as_mut_slice()),
        };
        if batch::sample_with(isa, brdf, wo, [&u[0], &u[1], &u[2]], &mut out).is_err() {
            continue;
        }
        ran += 1;
        for i in 0..n {
            let wo_i = Vec3::new(d[3][i], d[4][i], d[5][i]);
            let ui = [u[0][i], u[1][i], u[2][i]];
            let (sx, sy, sz, sp, sw): (f32, f32, f32, f32, [f32; N]) = if isa == Isa::Portable {
                let s = brdf.sample(wo_i, ui);
                (s.wi.x, s.wi.y, s.wi.z, s.pdf, s.weight)
            } else if batch::shares_divisions() {
                let d = F32FmaSharedDiv;
                let s = shared.sample(Vec3::new(d(wo_i.x), d(wo_i.y), d(wo_i.z)), ui.map(d));
                (s.wi.x.0, s.wi.y.0, s.wi.z.0, s.pdf.0, s.weight.map(|v| v.0))
            } else {
                let wo_f = Vec3::new(F32Fma(wo_i.x), F32Fma(wo_i.y), F32Fma(wo_i.z));
                let s = fused.sample(wo_f, ui.map(F32Fma));
                (s.wi.x.0, s.wi.y.0, s.wi.z.0, s.pdf.0, s.weight.map(|v| v.0))
            };
            let got = (x[i], y[i], z[i], pdf[i]);
            assert_eq!(got, (sx, sy, sz, sp), "{name} {isa:?} sample {i}");
            for c in 0..N {
                assert_eq!(
                    w[c][i].to_bits(),
                    sw[c].to_bits(),
                    "{name} {isa:?} weight {i}"
                );
            }
        }
    }
    ran
}

#[test]
fn batch_sampling_equals_scalar_sampling_on_every_isa() {
    let lambert = Lambert::new([0.8_f32, 0.5, 0.2]).unwrap();
    let on = brdf::models::OrenNayar::new([0.6_f32], 0.5).unwrap();
    assert!(check_sample("lambert", &lambert, 1001) >= 1);
    assert!(check_sample("oren-nayar", &on, 1001) >= 1);
    // A conductor whose channels share one division where the batch path does (Intel).
    let gold = shared_division_gold();
    assert!(check_sample("gold, shared division", &gold, 1001) >= 1);
    // The same on explicit lanes: run-time parts and a material of them.
    let parts = shared_division_gold_parts();
    assert!(check_sample("gold parts, shared division", &parts, 1001) >= 1);
    let material = brdf::material::Material::from(parts);
    assert!(check_sample("gold material, shared division", &material, 1001) >= 1);
}

/// A Cook-Torrance with run-time parts (the explicit lanes on the FMA instruction sets).
type Parts = CookTorrance<
    f32,
    brdf::ndf::AnyNdf<f32>,
    brdf::fresnel::AnyFresnel<f32>,
    brdf::masking::AnyMasking,
>;

/// The mixtures of the batch sampling and density tests: a plastic (Lambert and a GGX
/// dielectric lobe) as the static `Sum` parts and as a `Sum` material, a `Layered` material,
/// and a nested sum of the two with an empty sum and a sum of one (`gold`).
struct Mixtures {
    lambert: Lambert<f32, 3>,
    coat: CookTorrance<f32, Ggx<f32>, brdf::fresnel::Dielectric<f32, 3>, SmithHeightCorrelated>,
    plastic: brdf::material::Material<f32>,
    layered: brdf::material::Material<f32>,
    nested: brdf::material::Material<f32>,
}

fn mixtures(gold: Parts) -> Mixtures {
    use brdf::fresnel::{AnyFresnel, Dielectric};
    use brdf::masking::AnyMasking;
    use brdf::material::Material;
    use brdf::ndf::AnyNdf;
    let lambert = Lambert::new([0.2_f32, 0.3, 0.4]).unwrap();
    let coat = CookTorrance::new(
        Ggx::<f32>::anisotropic(0.05, 0.4).unwrap(),
        Dielectric::new(1.5_f32).unwrap().channels::<3>(),
        SmithHeightCorrelated,
    );
    let coat_parts = CookTorrance::new(
        AnyNdf::from(coat.ndf),
        AnyFresnel::from(coat.fresnel),
        AnyMasking::from(coat.masking),
    );
    let plastic = Material::Sum(vec![Material::from(lambert), Material::from(coat_parts)]);
    let layered = Material::Layered(Box::new(brdf::models::Layered::new(
        Material::from(lambert),
        Material::from(coat_parts),
        AnyFresnel::from(Dielectric::new(1.5_f32).unwrap().channels::<3>()),
    )));
    let nested = Material::Sum(vec![
        plastic.clone(),
        Material::Sum(vec![]),
        Material::Sum(vec![Material::from(gold)]),
        layered.clone(),
    ]);
    Mixtures {
        lambert,
        coat,
        plastic,
        layered,
        nested,
    }
}

/// Sampling with run-time parts (explicit lanes on the FMA instruction sets), a `Material` of
/// one model (sampled as that model through its batch hook), `Sum` and `Layered` materials,
/// nested ones too (their mixtures over blocks of the parts' batches), and the static
/// plastic `Sum` whose mixture closures are inlined into the kernels: each equals its
/// `SampleBrdf::sample` bit for bit, at lengths around the 8- and 16-lane registers, the
/// masked tail and several blocks.
#[test]
fn batch_sampling_of_run_time_parts_and_materials() {
    use brdf::fresnel::AnyFresnel;
    use brdf::masking::AnyMasking;
    use brdf::material::Material;
    use brdf::ndf::AnyNdf;
    let gold = CookTorrance::new(
        GgxIsotropic::<f32>::new(0.2).unwrap(),
        Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap(),
        SmithSeparable,
    );
    let parts = CookTorrance::new(
        AnyNdf::from(gold.ndf),
        AnyFresnel::from(gold.fresnel),
        AnyMasking::from(gold.masking),
    );
    let Mixtures {
        lambert,
        coat,
        plastic,
        layered,
        nested,
    } = mixtures(parts);
    for n in [0, 1, 15, 17, 1031, 2 * batch::BLOCK + 5] {
        assert!(check_sample("run-time parts", &parts, n) >= 1);
        assert!(check_sample("gold material", &Material::from(parts), n) >= 1);
        assert!(check_sample("plastic material", &plastic, n) >= 1);
        assert!(check_sample("layered material", &layered, n) >= 1);
        assert!(check_sample("nested material", &nested, n) >= 1);
        assert!(check_sample("plastic", &Sum::new(lambert, coat), n) >= 1);
    }
}

/// `batch::pdf_with` on every available variant equals `SampleBrdf::pdf` per pair bit for bit,
/// on the form `batch::sample_with` runs (as `check_sample`), at `n` pairs whose `wi` is
/// below the horizon at every 23rd pair (density 0). Returns how many variants ran; also
/// checks that an unavailable one reports so and that some densities are positive.
fn check_pdf<B, const N: usize>(name: &str, brdf: &B, n: usize) -> usize
where
    B: batch::BatchSample<N>,
    B::Fused: brdf::SampleBrdf<F32Fma, N>,
    B::SharedDiv: brdf::SampleBrdf<F32FmaSharedDiv, N>,
{
    use brdf::SampleBrdf;
    let mut d = pairs(n);
    for i in (0..n).step_by(23) {
        d[2][i] = -d[2][i] - 0.01;
    }
    let wi = Directions::new(&d[0], &d[1], &d[2]);
    let wo = Directions::new(&d[3], &d[4], &d[5]);
    let (fused, shared) = (brdf.fused(), brdf.shared_div());
    let mut ran = 0;
    for isa in Isa::ALL {
        let mut out = vec![f32::NAN; n];
        match batch::pdf_with(isa, brdf, wo, wi, &mut out) {
            Err(e) => {
                assert!(!isa.is_available(), "{e}");
                continue;
            }
            Ok(()) => ran += 1,
        }
        let mut positive = 0;
        for i in 0..n {
            let (wi_i, wo_i) = (
                Vec3::new(d[0][i], d[1][i], d[2][i]),
                Vec3::new(d[3][i], d[4][i], d[5][i]),
            );
            let want = if isa == Isa::Portable {
                brdf.pdf(wo_i, wi_i)
            } else if batch::shares_divisions() {
                let v = |w: Vec3<f32>| {
                    Vec3::new(
                        F32FmaSharedDiv(w.x),
                        F32FmaSharedDiv(w.y),
                        F32FmaSharedDiv(w.z),
                    )
                };
                shared.pdf(v(wo_i), v(wi_i)).0
            } else {
                let v = |w: Vec3<f32>| Vec3::new(F32Fma(w.x), F32Fma(w.y), F32Fma(w.z));
                fused.pdf(v(wo_i), v(wi_i)).0
            };
            assert_eq!(
                out[i].to_bits(),
                want.to_bits(),
                "{name} {isa:?} pair {i}: {} vs {want}",
                out[i]
            );
            if i % 23 == 0 {
                assert_eq!(out[i], 0.0, "{name} {isa:?} pair {i}: wi below the horizon");
            }
            positive += usize::from(out[i] > 0.0);
        }
        assert!(
            n < 4 || positive > n / 2,
            "{name} {isa:?}: {positive} of {n} positive"
        );
    }
    ran
}

/// Batch densities (`batch::pdf_with`, `batch::pdf`) of static models, run-time parts,
/// materials of one model and mixture materials (`Sum`, `Layered`, nested), at lengths around
/// the registers, the masked tail and several blocks: `SampleBrdf::pdf` per pair bit for bit.
#[test]
fn batch_densities_equal_scalar_densities_on_every_isa() {
    use brdf::material::Material;
    let on = brdf::models::OrenNayar::new([0.6_f32], 0.5).unwrap();
    let gold = shared_division_gold();
    let parts = shared_division_gold_parts();
    let Mixtures {
        lambert,
        coat,
        plastic,
        layered,
        nested,
    } = mixtures(parts);
    for n in [0, 1, 15, 17, 1031, 2 * batch::BLOCK + 5] {
        assert!(check_pdf("lambert", &lambert, n) >= 1);
        assert!(check_pdf("oren-nayar", &on, n) >= 1);
        assert!(check_pdf("gold, shared division", &gold, n) >= 1);
        assert!(check_pdf("gold parts", &parts, n) >= 1);
        assert!(check_pdf("gold material", &Material::from(parts), n) >= 1);
        assert!(check_pdf("plastic material", &plastic, n) >= 1);
        assert!(check_pdf("layered material", &layered, n) >= 1);
        assert!(check_pdf("nested material", &nested, n) >= 1);
        assert!(check_pdf("plastic", &Sum::new(lambert, coat), n) >= 1);
    }
    // `pdf` runs the detected variant.
    let d = pairs(64);
    let (wi, wo) = (
        Directions::new(&d[0], &d[1], &d[2]),
        Directions::new(&d[3], &d[4], &d[5]),
    );
    let (mut a, mut b) = (vec![0.0f32; 64], vec![0.0f32; 64]);
    batch::pdf(&plastic, wo, wi, &mut a);
    batch::pdf_with(Isa::detect(), &plastic, wo, wi, &mut b).unwrap();
    assert_eq!(a, b);
    // The material's hook declines an unavailable instruction set (a safe method).
    for isa in Isa::ALL {
        use brdf::SampleBrdf;
        let got = plastic.pdf_batch(isa, wo, wi, &mut a);
        assert_eq!(got, isa.is_available(), "{isa:?}");
    }
}

#[test]
#[should_panic(expected = "differ in length")]
fn batch_densities_reject_unequal_lengths() {
    let lambert = Lambert::new([0.5_f32]).unwrap();
    let (x, short) = ([0.0f32; 8], [0.0f32; 7]);
    let mut out = [0.0f32; 8];
    batch::pdf(
        &lambert,
        Directions::new(&x, &x, &x),
        Directions {
            x: &x,
            y: &short,
            z: &x,
        },
        &mut out,
    );
}

/// Batch sampling with [`HardwareEstimate`] against the exact policy: bit for bit except on
/// [`Isa::Avx512`], where the model samples on explicit 16-lane registers with the estimates
/// (the half vector and the final division of `f`); there every direction is within 1e-6 of
/// the exact one per component, every density and weight within 1e-6 relative, and the
/// same samples are valid (density > 0). Returns the worst relative difference on `Avx512`.
fn check_sample_estimate<B, E, const N: usize>(exact: &B, estimate: &E, n: usize) -> f64
where
    B: batch::BatchSample<N>,
    B::Fused: brdf::SampleBrdf<F32Fma, N>,
    B::SharedDiv: brdf::SampleBrdf<F32FmaSharedDiv, N>,
    E: batch::BatchSample<N>,
    E::Fused: brdf::SampleBrdf<F32Fma, N>,
    E::SharedDiv: brdf::SampleBrdf<F32FmaSharedDiv, N>,
{
    assert!(E::EXPLICIT_LANES && !B::EXPLICIT_LANES);
    let d = pairs(n);
    let wo = Directions::new(&d[3], &d[4], &d[5]);
    let u: [Vec<f32>; 3] = core::array::from_fn(|k| {
        d[k].iter()
            .map(|x| (0.5 * (x + 1.0)).clamp(0.0, 0.999_999_9))
            .collect()
    });
    // x, y, z, pdf, then the weights.
    let run = |isa: Isa, est: bool| -> Option<Vec<Vec<f32>>> {
        let mut v = vec![vec![f32::NAN; n]; 4 + N];
        let (head, w) = v.split_at_mut(4);
        let [x, y, z, pdf] = head else { unreachable!() };
        let mut it = w.iter_mut();
        let mut out = batch::SampleOut {
            x,
            y,
            z,
            pdf,
            weight: core::array::from_fn(|_| it.next().unwrap().as_mut_slice()),
        };
        let u = [&u[0][..], &u[1][..], &u[2][..]];
        let r = if est {
            batch::sample_with(isa, estimate, wo, u, &mut out)
        } else {
            batch::sample_with(isa, exact, wo, u, &mut out)
        };
        r.ok().map(|()| v)
    };
    let mut worst = 0.0f64;
    for isa in Isa::ALL {
        let (Some(a), Some(b)) = (run(isa, false), run(isa, true)) else {
            assert!(!isa.is_available());
            continue;
        };
        if isa != Isa::Avx512 {
            let bits = |v: &Vec<Vec<f32>>| -> Vec<u32> {
                v.iter().flatten().map(|x| x.to_bits()).collect()
            };
            assert_eq!(
                bits(&a),
                bits(&b),
                "{isa:?}: the estimate policy is exact here"
            );
            continue;
        }
        for i in 0..n {
            assert_eq!(a[3][i] > 0.0, b[3][i] > 0.0, "validity differs at {i}");
            for k in 0..3 {
                let e = f64::from((a[k][i] - b[k][i]).abs());
                assert!(e <= 1e-6, "direction component {k} at {i}: {e:e}");
            }
            for k in 3..4 + N {
                let (x, y) = (f64::from(a[k][i]), f64::from(b[k][i]));
                assert!(y.is_finite());
                let e = (x - y).abs() / x.abs().max(f64::MIN_POSITIVE);
                worst = worst.max(if x == y { 0.0 } else { e });
            }
        }
        assert!(worst <= 1e-6, "Avx512 sampling estimates: {worst:e}");
    }
    worst
}

/// GGX + Schlick and the rough gold conductor with [`HardwareEstimate`], sampled in batches:
/// see `check_sample_estimate`.
#[test]
fn hardware_estimate_sampling_within_a_few_ulp_of_exact() {
    let (ggx, gold, gold_estimate) = estimate_workloads();
    let mut worst = [0.0f64; 2];
    for n in [0, 1, 15, 17, 1031] {
        worst[0] = worst[0].max(check_sample_estimate(
            &ggx,
            &ggx.with_sqrt::<HardwareEstimate>(),
            n,
        ));
        worst[1] = worst[1].max(check_sample_estimate(&gold, &gold_estimate, n));
    }
    eprintln!(
        "sampling with estimates, worst relative: GGX {:.2e}, gold {:.2e}",
        worst[0], worst[1]
    );
}

/// A `Directions` built by hand (its fields are public) whose `y` or `z` is shorter than `x`
/// is rejected by the entry points with a panic, before any kernel loads a lane.
#[test]
fn hand_built_directions_with_short_components_are_rejected() {
    use brdf::material::Material;
    let (long, short) = (vec![0.0f32; 33], vec![1.0f32; 17]);
    let up = Directions::new(&long, &long, &long);
    let bad = Directions {
        x: &long,
        y: &long,
        z: &short,
    };
    let gold = Material::from(CookTorrance::new(
        brdf::ndf::AnyNdf::from(GgxIsotropic::<f32>::new(0.2).unwrap()),
        brdf::fresnel::AnyFresnel::from(
            Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap(),
        ),
        brdf::masking::AnyMasking::from(SmithSeparable),
    ));
    for isa in Isa::ALL.into_iter().filter(|i| i.is_available()) {
        let eval = std::panic::catch_unwind(|| {
            let mut f = [vec![0.0f32; 33], vec![0.0f32; 33], vec![0.0f32; 33]];
            let [a, b, c] = &mut f;
            let _ = batch::eval_with(isa, &gold, bad, up, [a, b, c]);
        });
        assert!(eval.is_err(), "{isa:?}: eval_with accepted a short z");
        let sample = std::panic::catch_unwind(|| {
            let mut v = vec![vec![0.0f32; 33]; 7];
            let (head, w) = v.split_at_mut(4);
            let [x, y, z, pdf] = head else { unreachable!() };
            let [w0, w1, w2] = w else { unreachable!() };
            let mut out = batch::SampleOut {
                x,
                y,
                z,
                pdf,
                weight: [w0, w1, w2],
            };
            let u = [&long[..], &long[..], &long[..]];
            let _ = batch::sample_with(isa, &gold, bad, u, &mut out);
        });
        assert!(sample.is_err(), "{isa:?}: sample_with accepted a short z");
    }
}

/// `Material::sample_batch` is a safe method: called directly with an instruction set the CPU
/// lacks it declines (`false`) without running a kernel, and with one it has it samples.
#[test]
fn material_sample_batch_declines_unavailable_instruction_sets() {
    use brdf::SampleBrdf;
    use brdf::material::Material;
    let plastic = Material::Sum(vec![
        Material::from(Lambert::new([0.2_f32, 0.3, 0.4]).unwrap()),
        Material::from(Lambert::new([0.1_f32, 0.1, 0.1]).unwrap()),
    ]);
    let (x, z) = (vec![0.0f32; 20], vec![1.0f32; 20]);
    let u = vec![0.5f32; 20];
    for isa in Isa::ALL {
        let mut v = vec![vec![0.0f32; 20]; 7];
        let (head, w) = v.split_at_mut(4);
        let [ox, oy, oz, pdf] = head else {
            unreachable!()
        };
        let [w0, w1, w2] = w else { unreachable!() };
        let mut out = batch::SampleOut {
            x: ox,
            y: oy,
            z: oz,
            pdf,
            weight: [w0, w1, w2],
        };
        let ran = plastic.sample_batch(isa, Directions::new(&x, &x, &z), [&u, &u, &u], &mut out);
        assert_eq!(ran, isa.is_available(), "{isa:?}");
        if ran {
            assert!(
                v[3].iter().all(|&p| p > 0.0),
                "{isa:?}: the samples are valid"
            );
        }
    }
}

/// `BRDF_SHARE_DIVISIONS=0` or `1` decides `batch::shares_divisions()` (`.ci/run` runs this
/// file both ways); without it, the CPU vendor does (Intel: share).
#[test]
fn share_divisions_override() {
    match std::env::var("BRDF_SHARE_DIVISIONS").as_deref() {
        Ok("0") => assert!(!batch::shares_divisions()),
        Ok("1") => assert!(batch::shares_divisions()),
        _ => {
            #[cfg(target_arch = "x86_64")]
            {
                let id = core::arch::x86_64::__cpuid(0);
                let vendor = [id.ebx, id.edx, id.ecx].map(u32::to_le_bytes).concat();
                assert_eq!(batch::shares_divisions(), vendor == *b"GenuineIntel");
            }
        }
    }
}
