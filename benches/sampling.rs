//! Batch sampling throughput (`batch::sample_with`; the densities of given pairs,
//! `batch::pdf_with`, in group `pdf_material`), 64K samples, f32, one core, on every
//! instruction set this CPU has: samples per second per sampler, so their ratio is measured
//! on the machine at hand (name the CPU beside any figure: `lscpu`).
use std::hint::black_box;

use brdf::SampleBrdf;
use brdf::batch::{self, Directions, Isa, SampleOut};
use brdf::fresnel::{Conductor, Schlick};
use brdf::ior::Preset;
use brdf::masking::{SmithHeightCorrelated, SmithSeparable};
use brdf::models::{CookTorrance, Lambert, OrenNayar};
use brdf::ndf::{Beckmann, GgxIsotropic};
use brdf::real::{F32Fma, F32FmaSharedDiv};
use brdf::sampling::{BoundedVisibleNormals, FullDistribution, SphericalCaps, VisibleNormals};
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};

const N: usize = 1 << 16;

/// Deterministic uniforms in [0, 1) (xorshift).
fn uniforms(seed: u32) -> Vec<f32> {
    let mut s = seed;
    (0..N)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            (s >> 8) as f32 / (1u32 << 24) as f32
        })
        .collect()
}

/// `wo` on the upper hemisphere, cos θo uniform in (0, 1].
fn view_directions() -> [Vec<f32>; 3] {
    let (a, b) = (uniforms(11), uniforms(12));
    let mut d: [Vec<f32>; 3] = Default::default();
    for (c, p) in a.iter().zip(&b) {
        let c = 1.0 - c;
        let r = (1.0 - c * c).max(0.0).sqrt();
        let phi = p * core::f32::consts::TAU;
        d[0].push(r * phi.cos());
        d[1].push(r * phi.sin());
        d[2].push(c);
    }
    d
}

/// Benchmarks `model` under `name` on every available instruction set.
pub fn bench_sampler<B, const C: usize>(c: &mut Criterion, group: &str, name: &str, model: &B)
where
    B: batch::BatchSample<C>,
    B::Fused: SampleBrdf<F32Fma, C>,
    B::SharedDiv: SampleBrdf<F32FmaSharedDiv, C>,
{
    let wo = view_directions();
    let u = [uniforms(1), uniforms(2), uniforms(3)];
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(N as u64));
    for isa in Isa::ALL.into_iter().filter(|i| i.is_available()) {
        let (mut x, mut y, mut z, mut pdf) =
            (vec![0.0; N], vec![0.0; N], vec![0.0; N], vec![0.0; N]);
        let mut w: [Vec<f32>; C] = core::array::from_fn(|_| vec![0.0; N]);
        g.bench_function(BenchmarkId::new(name, format!("{isa:?}")), |b| {
            b.iter(|| {
                let mut out = SampleOut {
                    x: &mut x,
                    y: &mut y,
                    z: &mut z,
                    pdf: &mut pdf,
                    weight: w.each_mut().map(|c| c.as_mut_slice()),
                };
                batch::sample_with(
                    isa,
                    black_box(model),
                    Directions::new(&wo[0], &wo[1], &wo[2]),
                    [&u[0], &u[1], &u[2]],
                    &mut out,
                )
                .unwrap();
                black_box(&pdf);
            })
        });
    }
    g.finish();
}

/// Benchmarks `batch::pdf_with` of `model` under `name` on every available instruction set:
/// the densities of given `(wo, wi)` pairs (as a renderer's multiple importance sampling asks
/// for them), `wi` cosine-distributed.
pub fn bench_pdf<B, const C: usize>(c: &mut Criterion, group: &str, name: &str, model: &B)
where
    B: batch::BatchSample<C>,
    B::Fused: SampleBrdf<F32Fma, C>,
    B::SharedDiv: SampleBrdf<F32FmaSharedDiv, C>,
{
    let wo = view_directions();
    let (a, b) = (uniforms(21), uniforms(22));
    let mut wi: [Vec<f32>; 3] = Default::default();
    for (u1, u2) in a.iter().zip(&b) {
        let w = brdf::sampling::cosine_hemisphere(*u1, *u2);
        wi[0].push(w.x);
        wi[1].push(w.y);
        wi[2].push(w.z);
    }
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(N as u64));
    for isa in Isa::ALL.into_iter().filter(|i| i.is_available()) {
        let mut out = vec![0.0f32; N];
        g.bench_function(BenchmarkId::new(name, format!("{isa:?}")), |b| {
            b.iter(|| {
                batch::pdf_with(
                    isa,
                    black_box(model),
                    Directions::new(&wo[0], &wo[1], &wo[2]),
                    Directions::new(&wi[0], &wi[1], &wi[2]),
                    &mut out,
                )
                .unwrap();
                black_box(&out);
            })
        });
    }
    g.finish();
}

fn diffuse(c: &mut Criterion) {
    bench_sampler(
        c,
        "sample_diffuse",
        "lambert",
        &Lambert::new([0.5_f32]).unwrap(),
    );
    bench_sampler(
        c,
        "sample_diffuse",
        "oren_nayar",
        &OrenNayar::new([0.5_f32], 0.5).unwrap(),
    );
}

/// GGX Cook-Torrance (`GgxIsotropic`, α = 0.3, Schlick F0 = 0.04, height-correlated Smith)
/// with each normal-sampling strategy, and Beckmann's visible normals (three bracketed
/// Newton steps in `erfc(−x)`) for comparison: the ratio between strategies is the figure to
/// read.
fn microfacet(c: &mut Criterion) {
    let ggx = CookTorrance::new(
        GgxIsotropic::new(0.3_f32).unwrap(),
        Schlick::new([0.04_f32]).unwrap(),
        SmithHeightCorrelated,
    );
    let group = "sample_ggx";
    bench_sampler(
        c,
        group,
        "visible_normals",
        &ggx.sampled_with::<VisibleNormals>(),
    );
    bench_sampler(
        c,
        group,
        "spherical_caps",
        &ggx.sampled_with::<SphericalCaps>(),
    );
    bench_sampler(
        c,
        group,
        "bounded_visible_normals",
        &ggx.sampled_with::<BoundedVisibleNormals>(),
    );
    bench_sampler(
        c,
        group,
        "full_distribution",
        &ggx.sampled_with::<FullDistribution>(),
    );
    let beckmann = CookTorrance::new(
        Beckmann::new(0.3_f32).unwrap(),
        Schlick::new([0.04_f32]).unwrap(),
        SmithHeightCorrelated,
    );
    bench_sampler(c, "sample_beckmann", "visible_normals", &beckmann);
}

/// Mitsuba's `roughconductor` workload (as `benches/peers/run.sh --sample`): GGX α = 0.3
/// (`GgxIsotropic`), the exact RGB conductor Fresnel of gold, separable Smith `G1·G1`, drawn
/// by visible normals (Heitz 2018, Mitsuba's `sample_visible`) and by the default spherical
/// caps; portable against the dispatched kernels (the `Isa` of each row).
fn roughconductor(c: &mut Criterion) {
    let gold = Conductor::<f32, 3>::from_preset(Preset::Gold).unwrap();
    let ct = CookTorrance::new(GgxIsotropic::new(0.3_f32).unwrap(), gold, SmithSeparable);
    let group = "batch_sample_roughconductor";
    bench_sampler(
        c,
        group,
        "visible_normals",
        &ct.sampled_with::<VisibleNormals>(),
    );
    bench_sampler(
        c,
        group,
        "spherical_caps",
        &ct.sampled_with::<SphericalCaps>(),
    );
    // The conductor's channels sharing one division where batch::shares_divisions() (Intel).
    let shared = CookTorrance::new(ct.ndf, gold.share_divisions().unwrap(), SmithSeparable);
    bench_sampler(
        c,
        group,
        "visible_normals_shared_division",
        &shared.sampled_with::<VisibleNormals>(),
    );
    bench_sampler(
        c,
        group,
        "spherical_caps_shared_division",
        &shared.sampled_with::<SphericalCaps>(),
    );
}

/// The run-time `Material` against the static models it holds, sampled: the rough gold
/// conductor (GGX α = 0.2, separable Smith, spherical caps: every model's default sampler)
/// with run-time parts, and a plastic (Lambert + a GGX lobe with a dielectric's Fresnel) as
/// a `Sum` material, whose one-sample mixture picks a term per sample. The material matches
/// on its variant per sample (`SampleBrdf` has no batch hook).
fn material(c: &mut Criterion) {
    use brdf::fresnel::{AnyFresnel, Dielectric};
    use brdf::masking::AnyMasking;
    use brdf::material::Material;
    use brdf::models::Sum;
    use brdf::ndf::AnyNdf;
    let group = "sample_material";
    let gold = CookTorrance::new(
        GgxIsotropic::new(0.2_f32).unwrap(),
        Conductor::<f32, 3>::from_preset(Preset::Gold).unwrap(),
        SmithSeparable,
    );
    let runtime_parts = CookTorrance::new(
        AnyNdf::from(gold.ndf),
        AnyFresnel::from(gold.fresnel),
        AnyMasking::from(gold.masking),
    );
    bench_sampler(c, group, "gold_static", &gold);
    bench_sampler(c, group, "gold_runtime_parts", &runtime_parts);
    bench_sampler(c, group, "gold_material", &Material::from(runtime_parts));
    // The channels sharing one division where `batch::shares_divisions()`.
    let shared = CookTorrance::new(
        gold.ndf,
        gold.fresnel.share_divisions().unwrap(),
        gold.masking,
    );
    let shared_parts = CookTorrance::new(
        AnyNdf::from(shared.ndf),
        AnyFresnel::from(shared.fresnel),
        AnyMasking::from(shared.masking),
    );
    bench_sampler(c, group, "gold_shared_static", &shared);
    bench_sampler(
        c,
        group,
        "gold_shared_material",
        &Material::from(shared_parts),
    );
    let lambert = Lambert::<f32, 3>::new([0.2, 0.3, 0.4]).unwrap();
    let coat = CookTorrance::new(
        GgxIsotropic::new(0.2_f32).unwrap(),
        Dielectric::new(1.5_f32).unwrap().channels::<3>(),
        SmithHeightCorrelated,
    );
    let coat_parts = CookTorrance::new(
        AnyNdf::from(coat.ndf),
        AnyFresnel::from(coat.fresnel),
        AnyMasking::from(coat.masking),
    );
    bench_sampler(c, group, "plastic_static", &Sum::new(lambert, coat));
    let plastic = Material::Sum(vec![Material::from(lambert), Material::from(coat_parts)]);
    bench_sampler(c, group, "plastic_material", &plastic);
    // The densities of given pairs (`batch::pdf_with`), static models against materials.
    let group = "pdf_material";
    bench_pdf(c, group, "gold_static", &gold);
    bench_pdf(c, group, "gold_material", &Material::from(runtime_parts));
    bench_pdf(c, group, "plastic_static", &Sum::new(lambert, coat));
    bench_pdf(c, group, "plastic_material", &plastic);
}

criterion_group!(benches, diffuse, microfacet, roughconductor, material);
criterion_main!(benches);
