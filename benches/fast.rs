//! Throughput of the fast approximations against the exact paths (`std` on scalars, `wide`'s
//! polynomial kernels on lanes) on f32, f64 and SIMD lanes, in elements per second; plus
//! slice loops over `&[f32]` compiled for the baseline target and inside
//! `#[target_feature(enable = "avx2,fma")]`, to show whether the generic scalar body
//! auto-vectorizes.
//!
//! Run: `cargo bench --bench fast -- --warm-up-time 1 --measurement-time 2`.
//! Inputs: 4096 Blinn-Phong-like pairs (x = n·h ∈ [10⁻³, 1], y = s ∈ [1, 10⁴], log-spread).

use std::hint::black_box;

use brdf::{Real, Scalar, f32x4, f32x8, f32x16, f64x4, fast};
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};

const N: usize = 4096;

fn inputs() -> (Vec<f64>, Vec<f64>) {
    let g = |i: usize, a: f64| ((i as f64) * a).fract();
    let x = (0..N)
        .map(|i| 10f64.powf(-3.0 * g(i, 0.618_033_988_749_895)))
        .collect();
    let y = (0..N)
        .map(|i| 10f64.powf(4.0 * g(i, 0.754_877_666_246_693)))
        .collect();
    (x, y)
}

fn pack<R: Real>(s: &[f64]) -> Vec<R> {
    s.chunks(R::LANES)
        .map(|ch| R::from_fn(|l| <R::Scalar as Scalar>::of(ch[l])))
        .collect()
}

/// `f` over all input pairs, results written to a buffer.
fn run<R: Real>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    id: &str,
    x: &[f64],
    y: &[f64],
    f: impl Fn(R, R) -> R,
) {
    let (xs, ys) = (pack::<R>(x), pack::<R>(y));
    let mut out = vec![R::zero(); xs.len()];
    g.bench_function(id, |b| {
        b.iter(|| {
            for ((o, &a), &b) in out.iter_mut().zip(black_box(&xs)).zip(black_box(&ys)) {
                *o = f(a, b);
            }
            black_box(&out);
        })
    });
}

macro_rules! per_type {
    ($g:expr, $x:expr, $y:expr, $name:literal, |$a:ident, $b:ident| $body:expr) => {{
        fn f<R: Real>($a: R, $b: R) -> R {
            $body
        }
        run::<f32>($g, concat!($name, "/f32"), $x, $y, f::<f32>);
        run::<f64>($g, concat!($name, "/f64"), $x, $y, f::<f64>);
        run::<f32x4>($g, concat!($name, "/f32x4"), $x, $y, f::<f32x4>);
        run::<f32x8>($g, concat!($name, "/f32x8"), $x, $y, f::<f32x8>);
        run::<f32x16>($g, concat!($name, "/f32x16"), $x, $y, f::<f32x16>);
        run::<f64x4>($g, concat!($name, "/f64x4"), $x, $y, f::<f64x4>);
    }};
}

fn exp2(c: &mut Criterion) {
    let (x, y) = inputs();
    // arguments t = −y·(1 − x)/8 ∈ [−1250, 0]: underflowing ones included, like a lobe.
    let mut g = c.benchmark_group("exp2");
    g.throughput(Throughput::Elements(N as u64));
    per_type!(&mut g, &x, &y, "exact", |a, b| (b
        * (a - R::one())
        * R::from_f64(0.125))
    .exp2());
    per_type!(&mut g, &x, &y, "deg3", |a, b| fast::exp2::<3, R>(
        b * (a - R::one()) * R::from_f64(0.125)
    ));
    per_type!(&mut g, &x, &y, "deg5", |a, b| fast::exp2::<5, R>(
        b * (a - R::one()) * R::from_f64(0.125)
    ));
    per_type!(&mut g, &x, &y, "deg7", |a, b| fast::exp2::<7, R>(
        b * (a - R::one()) * R::from_f64(0.125)
    ));
    g.finish();
}

fn log2(c: &mut Criterion) {
    let (x, y) = inputs();
    let mut g = c.benchmark_group("log2");
    g.throughput(Throughput::Elements(N as u64));
    per_type!(&mut g, &x, &y, "exact", |a, _b| a.log2());
    per_type!(&mut g, &x, &y, "deg4", |a, _b| fast::log2::<4, R>(a));
    per_type!(&mut g, &x, &y, "deg6", |a, _b| fast::log2::<6, R>(a));
    per_type!(&mut g, &x, &y, "deg9", |a, _b| fast::log2::<9, R>(a));
    g.finish();
}

fn pow(c: &mut Criterion) {
    let (x, y) = inputs();
    let mut g = c.benchmark_group("pow");
    g.throughput(Throughput::Elements(N as u64));
    per_type!(&mut g, &x, &y, "exact", |a, b| a.pow(b));
    per_type!(&mut g, &x, &y, "l4e3", |a, b| fast::pow::<4, 3, R>(a, b));
    per_type!(&mut g, &x, &y, "phong", |a, b| fast::pow_phong(a, b));
    per_type!(&mut g, &x, &y, "l12e8", |a, b| fast::pow::<12, 8, R>(a, b));
    g.finish();
}

fn rsqrt(c: &mut Criterion) {
    let (x, y) = inputs();
    let mut g = c.benchmark_group("rsqrt");
    g.throughput(Throughput::Elements(N as u64));
    per_type!(&mut g, &x, &y, "exact", |_a, b| b.sqrt().recip());
    per_type!(&mut g, &x, &y, "newton0", |_a, b| fast::rsqrt::<0, R>(b));
    per_type!(&mut g, &x, &y, "newton1", |_a, b| fast::rsqrt::<1, R>(b));
    per_type!(&mut g, &x, &y, "newton2", |_a, b| fast::rsqrt::<2, R>(b));
    g.finish();
}

// Slice loops: the generic scalar body over `&[f32]`, compiled for the baseline target and
// for AVX2+FMA. `R::mul_add` does not fuse inside the AVX2 function (its `cfg` is decided
// when the crate is compiled), so the vectorized code uses separate multiplies and adds.

fn slice_pow_exact(x: &[f32], y: &[f32], out: &mut [f32]) {
    for ((o, &a), &b) in out.iter_mut().zip(x).zip(y) {
        *o = a.pow(b);
    }
}
fn slice_pow_phong(x: &[f32], y: &[f32], out: &mut [f32]) {
    for ((o, &a), &b) in out.iter_mut().zip(x).zip(y) {
        *o = fast::pow_phong(a, b);
    }
}
fn slice_rsqrt1(_x: &[f32], y: &[f32], out: &mut [f32]) {
    for (o, &b) in out.iter_mut().zip(y) {
        *o = fast::rsqrt::<1, f32>(b);
    }
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn slice_pow_phong_avx2(x: &[f32], y: &[f32], out: &mut [f32]) {
    for ((o, &a), &b) in out.iter_mut().zip(x).zip(y) {
        *o = fast::pow_phong(a, b);
    }
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn slice_pow_exact_avx2(x: &[f32], y: &[f32], out: &mut [f32]) {
    for ((o, &a), &b) in out.iter_mut().zip(x).zip(y) {
        *o = a.pow(b);
    }
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn slice_rsqrt1_avx2(_x: &[f32], y: &[f32], out: &mut [f32]) {
    for (o, &b) in out.iter_mut().zip(y) {
        *o = fast::rsqrt::<1, f32>(b);
    }
}

fn slices(c: &mut Criterion) {
    let (x, y) = inputs();
    let x: Vec<f32> = x.iter().map(|&v| v as f32).collect();
    let y: Vec<f32> = y.iter().map(|&v| v as f32).collect();
    let mut out = vec![0.0f32; N];
    let mut g = c.benchmark_group("slice_f32");
    g.throughput(Throughput::Elements(N as u64));
    type Kernel = fn(&[f32], &[f32], &mut [f32]);
    let mut kernels: Vec<(&str, Kernel)> = vec![
        ("pow_exact/baseline", slice_pow_exact),
        ("pow_phong/baseline", slice_pow_phong),
        ("rsqrt1/baseline", slice_rsqrt1),
    ];
    #[cfg(target_arch = "x86_64")]
    if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
        // SAFETY: the CPU supports AVX2 and FMA (checked just above).
        kernels.push(("pow_exact/avx2", |x, y, o| unsafe {
            slice_pow_exact_avx2(x, y, o)
        }));
        kernels.push(("pow_phong/avx2", |x, y, o| unsafe {
            slice_pow_phong_avx2(x, y, o)
        }));
        kernels.push(("rsqrt1/avx2", |x, y, o| unsafe {
            slice_rsqrt1_avx2(x, y, o)
        }));
    }
    for (id, k) in kernels {
        g.bench_function(id, |b| {
            b.iter(|| {
                k(black_box(&x), black_box(&y), &mut out);
                black_box(&out);
            })
        });
    }
    g.finish();
}

criterion_group!(benches, exp2, log2, pow, rsqrt, slices);
criterion_main!(benches);
