//! Fresnel throughput: each variant (exact dielectric, exact conductor, Schlick, F82-tint,
//! Cook-Torrance g-c) on f32, f64 and SIMD lanes, in elements (cosines) per second.
//!
//! Run: `cargo bench --bench fresnel -- --warm-up-time 1 --measurement-time 2`.
//! Every group evaluates the same 4096 cosines (0..1, with grazing and normal values); the
//! element throughput makes lane widths directly comparable.

use std::hint::black_box;

use brdf::fresnel;
use brdf::{Real, Scalar, f32x4, f32x8, f32x16, f64x4};
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};

const N: usize = 4096;

/// 4096 cosines in [0, 1] (a fixed low-discrepancy sequence plus exact 0 and 1).
fn cosines() -> Vec<f64> {
    (0..N)
        .map(|i| match i % 64 {
            0 => 0.0,
            1 => 1.0,
            _ => ((i as f64) * 0.618_033_988_749_895).fract(),
        })
        .collect()
}

/// Packs the cosines into lanes of `R`.
fn pack<R: Real>(c: &[f64]) -> Vec<R> {
    c.chunks(R::LANES)
        .map(|ch| R::from_fn(|l| <R::Scalar as Scalar>::of(ch[l])))
        .collect()
}

/// One benchmark: `f` over all inputs, results written to a buffer.
fn run<R: Real>(group: &mut BenchmarkGroup<'_, WallTime>, id: &str, c: &[f64], f: impl Fn(R) -> R) {
    let input = pack::<R>(c);
    let mut out = vec![R::zero(); input.len()];
    group.bench_function(id, |b| {
        b.iter(|| {
            for (o, &x) in out.iter_mut().zip(black_box(&input)) {
                *o = f(x);
            }
            black_box(&out);
        })
    });
}

/// Runs `$body` (a closure-like expression over `R`) for every lane type.
macro_rules! all_types {
    ($group:expr, $c:expr, |$x:ident: R| $body:expr) => {{
        all_types!(@one $group, $c, f32, "f32", $x, $body);
        all_types!(@one $group, $c, f64, "f64", $x, $body);
        all_types!(@one $group, $c, f32x4, "f32x4", $x, $body);
        all_types!(@one $group, $c, f32x8, "f32x8", $x, $body);
        all_types!(@one $group, $c, f32x16, "f32x16", $x, $body);
        all_types!(@one $group, $c, f64x4, "f64x4", $x, $body);
    }};
    (@one $group:expr, $c:expr, $t:ty, $id:expr, $x:ident, $body:expr) => {{
        type R = $t;
        run::<R>(&mut $group, $id, $c, |$x: R| $body);
    }};
}

fn fresnel_benches(crit: &mut Criterion) {
    let c = cosines();
    // Material parameters, opaque to the optimizer: glass, gold (one channel), F82 coefficients.
    let (eta, n, k) = (black_box(1.5), black_box(0.43), black_box(2.455));
    let f0 = black_box(fresnel::f0_from_complex_ior(0.43, 2.455));
    let b = black_box(fresnel::f82_b(f0, 0.9));

    let mut g = crit.benchmark_group("fresnel_dielectric");
    g.throughput(Throughput::Elements(N as u64));
    all_types!(g, &c, |x: R| fresnel::dielectric(x, R::from_f64(eta)));
    g.finish();

    let mut g = crit.benchmark_group("fresnel_conductor");
    g.throughput(Throughput::Elements(N as u64));
    all_types!(g, &c, |x: R| fresnel::conductor(
        x,
        R::from_f64(n),
        R::from_f64(k)
    ));
    g.finish();

    let mut g = crit.benchmark_group("fresnel_schlick");
    g.throughput(Throughput::Elements(N as u64));
    all_types!(g, &c, |x: R| fresnel::schlick(R::from_f64(f0), x));
    g.finish();

    let mut g = crit.benchmark_group("fresnel_f82_tint");
    g.throughput(Throughput::Elements(N as u64));
    all_types!(g, &c, |x: R| fresnel::f82_tint_with_b(
        R::from_f64(f0),
        R::from_f64(b),
        x
    ));
    g.finish();

    let mut g = crit.benchmark_group("fresnel_cook_torrance_gc");
    g.throughput(Throughput::Elements(N as u64));
    all_types!(g, &c, |x: R| fresnel::reference::cook_torrance_gc(
        x,
        R::from_f64(eta)
    ));
    g.finish();
}

criterion_group!(benches, fresnel_benches);
criterion_main!(benches);
