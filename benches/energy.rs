//! Cost of the shipped albedo tables against the quadrature they replace: lookups per second
//! of `energy::directional_albedo_table` (GGX, bilinear), `dielectric_albedo_table`
//! (residual over the closed-form corner, four regions, tricubic) and
//! `dielectric_average_albedo_table` on `f32` and `f32x8`, and one direct
//! `dielectric_albedo` quadrature (`f64`) for scale.
//!
//! Run: `cargo bench --bench energy -- --warm-up-time 1 --measurement-time 2`.
//! Inputs: 4096 points `(α, η, μ)` spread over the tables' domain (α ∈ [1e-4, 1] in `√α`,
//! η ∈ [1/3, 3] both sides of 1, μ ∈ [0, 1]).

use std::hint::black_box;

use brdf::energy::{
    Distribution, dielectric_albedo, dielectric_albedo_table, dielectric_average_albedo_table,
    directional_albedo_table,
};
use brdf::{Real, Scalar, f32x8};
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};

const N: usize = 4096;

/// Low-discrepancy points `(α, η, μ)` over the tables' domain.
fn inputs() -> [Vec<f64>; 3] {
    let g = |i: usize, a: f64| ((i as f64 + 0.5) * a).fract();
    let alpha = (0..N)
        .map(|i| g(i, 0.618_033_988_749_895).powi(2).max(1e-4))
        .collect();
    let eta = (0..N)
        .map(|i| 3f64.powf(2.0 * g(i, 0.754_877_666_246_693) - 1.0))
        .collect();
    let mu = (0..N).map(|i| g(i, 0.569_840_290_998_053)).collect();
    [alpha, eta, mu]
}

fn pack<R: Real>(s: &[f64]) -> Vec<R> {
    s.chunks(R::LANES)
        .map(|ch| R::from_fn(|l| <R::Scalar as Scalar>::of(ch[l])))
        .collect()
}

/// `f` over every point, results written to a buffer.
fn run<R: Real>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    id: &str,
    [a, e, m]: &[Vec<f64>; 3],
    f: impl Fn(R, R, R) -> R,
) {
    let (a, e, m) = (pack::<R>(a), pack::<R>(e), pack::<R>(m));
    let mut out = vec![R::zero(); a.len()];
    g.bench_function(id, |b| {
        b.iter(|| {
            for (i, o) in out.iter_mut().enumerate() {
                *o = f(black_box(a[i]), black_box(e[i]), black_box(m[i]));
            }
            black_box(&out);
        })
    });
}

fn tables(c: &mut Criterion) {
    let points = inputs();
    let mut g = c.benchmark_group("albedo_tables");
    g.throughput(Throughput::Elements(N as u64));
    run::<f32>(&mut g, "conductor_ggx/f32", &points, |a, _, m| {
        directional_albedo_table(Distribution::Ggx, a, m)
    });
    run::<f32x8>(&mut g, "conductor_ggx/f32x8", &points, |a, _, m| {
        directional_albedo_table(Distribution::Ggx, a, m)
    });
    run::<f32>(&mut g, "dielectric/f32", &points, dielectric_albedo_table);
    run::<f32x8>(&mut g, "dielectric/f32x8", &points, dielectric_albedo_table);
    run::<f32>(&mut g, "dielectric_average/f32", &points, |a, e, _| {
        dielectric_average_albedo_table(a, e)
    });
    run::<f32x8>(&mut g, "dielectric_average/f32x8", &points, |a, e, _| {
        dielectric_average_albedo_table(a, e)
    });
    g.finish();

    // The quadrature the dielectric table replaces, for scale (a few points per sample).
    let mut g = c.benchmark_group("albedo_quadrature");
    g.sample_size(10);
    g.throughput(Throughput::Elements(1));
    let mut i = 0;
    g.bench_function("dielectric_albedo/f64", |b| {
        b.iter(|| {
            i = (i + 1) % N;
            black_box(dielectric_albedo(points[0][i], points[1][i], points[2][i]))
        })
    });
    g.finish();
}

criterion_group!(benches, tables);
criterion_main!(benches);
