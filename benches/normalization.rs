//! Normalization throughput: the seed's exact factor against its linear fit (and the
//! cosine-weighted exact factor, and a precomputed table lookup) on f32, f64 and SIMD
//! lanes, in elements (shininess values) per second.
//!
//! Run: `cargo bench --bench normalization -- --warm-up-time 1 --measurement-time 2`.
//! Every group evaluates the same 4096 shininess values (0 to 10⁶, log-spread, with exact
//! 0); the element throughput makes lane widths and formulas directly comparable.

use std::hint::black_box;

use brdf::normalization::{
    Normalization, NormalizationTable, TRI_ACE_OFFSET, blinn_phong_cosine_exact, tri_ace_exact,
    tri_ace_fit,
};
use brdf::{Real, Scalar, f32x4, f32x8, f32x16, f64x4};
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};

const N: usize = 4096;

/// 4096 shininess values: `10^u − 1` for `u` spread over `[0, 6]` by a golden-ratio
/// sequence (so 0 … 10⁶, dense at the low end where artists work), with exact zeros.
fn shininess() -> Vec<f64> {
    (0..N)
        .map(|i| {
            if i % 64 == 0 {
                0.0
            } else {
                10f64.powf(6.0 * ((i as f64) * 0.618_033_988_749_895).fract()) - 1.0
            }
        })
        .collect()
}

/// Packs the values into lanes of `R`.
fn pack<R: Real>(s: &[f64]) -> Vec<R> {
    s.chunks(R::LANES)
        .map(|ch| R::from_fn(|l| <R::Scalar as Scalar>::of(ch[l])))
        .collect()
}

/// One benchmark: `f` over all inputs, results written to a buffer.
fn run<R: Real>(group: &mut BenchmarkGroup<'_, WallTime>, id: &str, s: &[f64], f: impl Fn(R) -> R) {
    let input = pack::<R>(s);
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

/// Runs `$body` (an expression over `R`) for every lane type.
macro_rules! each_type {
    ($group:expr, $s:expr, |$x:ident: R| $body:expr) => {{
        each_type!(@one $group, $s, f32, "f32", $x, $body);
        each_type!(@one $group, $s, f64, "f64", $x, $body);
        each_type!(@one $group, $s, f32x4, "f32x4", $x, $body);
        each_type!(@one $group, $s, f32x8, "f32x8", $x, $body);
        each_type!(@one $group, $s, f32x16, "f32x16", $x, $body);
        each_type!(@one $group, $s, f64x4, "f64x4", $x, $body);
    }};
    (@one $group:expr, $s:expr, $t:ty, $id:expr, $x:ident, $body:expr) => {{
        type R = $t;
        run::<R>(&mut $group, $id, $s, |$x: R| $body);
    }};
}

fn normalization_benches(crit: &mut Criterion) {
    let s = shininess();
    let offset = black_box(TRI_ACE_OFFSET);

    let mut g = crit.benchmark_group("normalization_tri_ace_exact");
    g.throughput(Throughput::Elements(N as u64));
    each_type!(g, &s, |x: R| tri_ace_exact(x));
    g.finish();

    let mut g = crit.benchmark_group("normalization_tri_ace_fit");
    g.throughput(Throughput::Elements(N as u64));
    each_type!(g, &s, |x: R| tri_ace_fit(x, R::from_f64(offset)));
    g.finish();

    let mut g = crit.benchmark_group("normalization_blinn_phong_cosine_exact");
    g.throughput(Throughput::Elements(N as u64));
    each_type!(g, &s, |x: R| blinn_phong_cosine_exact(x));
    g.finish();

    // A shininess map's per-level table: 256 levels over [0, 255], scalar f32 lookups of
    // the same (clamped) values.
    let table = NormalizationTable::<256>::new(Normalization::TriAceExact, 0.0, 255.0)
        .expect("valid range");
    let s32: Vec<f32> = s.iter().map(|&x| (x as f32).min(255.0)).collect();
    let mut out = vec![0.0f32; N];
    let mut g = crit.benchmark_group("normalization_table_lookup");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("f32", |b| {
        b.iter(|| {
            for (o, &x) in out.iter_mut().zip(black_box(&s32)) {
                *o = table.lookup(x);
            }
            black_box(&out);
        })
    });
    g.finish();
}

criterion_group!(benches, normalization_benches);
criterion_main!(benches);
