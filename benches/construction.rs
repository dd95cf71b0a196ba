//! Construction cost of the multiple-scattering compensations (issue 13 §3): one
//! `AlbedoFit` (the directional albedo `E(μ)` series of one roughness) from the shipped
//! coefficient table (`AlbedoFit::new`) and by quadrature (`AlbedoFit::integrate`, the
//! construction before the table), and the whole `KullaConty::new` / `Turquin::new` of a
//! gold GGX Cook-Torrance (`f32`, RGB, exact complex-IOR Fresnel: its `F_avg` by quadrature
//! is part of the cost), against the same model assembled from an integrated fit.
//!
//! Run: `cargo bench --bench construction`. The quadrature cases take 10–50 ms per
//! iteration, so their groups take 10 samples.

use std::hint::black_box;

use brdf::energy::Distribution;
use brdf::fresnel::Conductor;
use brdf::ior::Preset;
use brdf::masking::SmithHeightCorrelated;
use brdf::models::{AlbedoFit, CookTorrance, FresnelAverage, KullaConty, Turquin};
use brdf::ndf::Ggx;
use criterion::{Criterion, criterion_group, criterion_main};

/// `(name, distribution, α)`: both segments of the table (α = 3e-4 is below the split
/// α_s ≈ 6.48e-4) and the slowest and fastest quadratures measured before the table.
const CASES: [(&str, Distribution, f64); 4] = [
    ("ggx_3e-4", Distribution::Ggx, 3e-4),
    ("ggx_0.05", Distribution::Ggx, 0.05),
    ("ggx_0.5", Distribution::Ggx, 0.5),
    ("beckmann_1", Distribution::Beckmann, 1.0),
];

fn gold(alpha: f32) -> CookTorrance<f32, Ggx<f32>, Conductor<f32, 3>, SmithHeightCorrelated> {
    CookTorrance::new(
        Ggx::new(alpha).unwrap(),
        Conductor::from_preset(Preset::Gold).unwrap(),
        SmithHeightCorrelated,
    )
}

fn bench_construction(c: &mut Criterion) {
    let mut g = c.benchmark_group("construction");
    for (name, dist, alpha) in CASES {
        g.bench_function(format!("albedo_fit_new/{name}"), |b| {
            b.iter(|| AlbedoFit::<f32>::new(dist, black_box(alpha)).unwrap());
        });
    }
    let ct = gold(0.5);
    g.bench_function("kulla_conty_new/gold_ggx_0.5", |b| {
        b.iter(|| KullaConty::<_, f32, 3>::new(black_box(ct)).unwrap());
    });
    g.bench_function("turquin_new/gold_ggx_0.5", |b| {
        b.iter(|| Turquin::<_, f32, 3>::new(black_box(ct)).unwrap());
    });
    g.finish();

    let mut g = c.benchmark_group("construction_integrated");
    g.sample_size(10);
    for (name, dist, alpha) in CASES {
        g.bench_function(format!("albedo_fit_integrate/{name}"), |b| {
            b.iter(|| AlbedoFit::<f32>::integrate(dist, black_box(alpha)).unwrap());
        });
    }
    g.bench_function("kulla_conty_from_integrated_fit/gold_ggx_0.5", |b| {
        b.iter(|| {
            let ct = black_box(ct);
            let fit = AlbedoFit::integrate(Distribution::Ggx, 0.5).unwrap();
            KullaConty::<_, f32, 3>::from_parts(ct, fit, ct.fresnel.average())
        });
    });
    g.finish();
}

criterion_group!(benches, bench_construction);
criterion_main!(benches);
