//! Microfacet throughput: every NDF `D(wm)`, Smith `Λ`, and masking/visibility term on f32,
//! f64 and SIMD lanes, in elements (direction pairs) per second.
//!
//! Run: `cargo bench --bench microfacet -- --warm-up-time 1 --measurement-time 2`.
//! Every group evaluates the same 4096 `(wi, wo, wm)` triples (upper hemisphere, grazing and
//! normal incidence included); the element throughput makes lane widths directly comparable.

use std::hint::black_box;

use brdf::masking::{
    HammonApprox, Implicit, Kelemen, Masking, SchlickGgx, SmithHeightCorrelated, SmithSeparable,
    SmithSeparableWalter, VCavity,
};
use brdf::ndf::{AshikhminShirleyLobe, Beckmann, BlinnPhong, Ggx, Ndf, SmithLambda};
use brdf::real::Splat;
use brdf::vec3::half_vector;
use brdf::{Real, Scalar, Vec3, f32x4, f32x8, f32x16, f64x4};
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};

const N: usize = 4096;

/// A direction from two numbers in [0, 1]: `cos θ = u1` (uniform in solid angle), `φ = 2π u2`.
fn dir(u1: f64, u2: f64) -> [f64; 3] {
    let r = (1.0 - u1 * u1).max(0.0).sqrt();
    let phi = 2.0 * std::f64::consts::PI * u2;
    [r * phi.cos(), r * phi.sin(), u1]
}

/// 4096 `(wi, wo)` pairs from a fixed low-discrepancy sequence, with exact 0 and 1 cosines.
fn pairs() -> Vec<([f64; 3], [f64; 3])> {
    let g = [
        0.754_877_666_246_692_7,
        0.569_840_290_998_053_3,
        0.430_159_709_001_946_7,
    ];
    (0..N)
        .map(|i| {
            let f = |k: usize| ((i as f64 + 0.5) * g[k]).fract();
            let ci = match i % 64 {
                0 => 0.0,
                1 => 1.0,
                _ => f(0),
            };
            (
                dir(ci, f(1)),
                dir(f(2), (i as f64 * 0.618_033_988_749_895).fract()),
            )
        })
        .collect()
}

type Triple<R> = (Vec3<R>, Vec3<R>, Vec3<R>);

/// Packs the pairs into lanes of `R` and appends the half vector.
fn pack<R: Real>(p: &[([f64; 3], [f64; 3])]) -> Vec<Triple<R>> {
    p.chunks(R::LANES)
        .map(|ch| {
            let v = |k: usize, c: usize| {
                R::from_fn(|l| {
                    let (a, b) = ch[l];
                    <R::Scalar as Scalar>::of(if k == 0 { a[c] } else { b[c] })
                })
            };
            let wi = Vec3::new(v(0, 0), v(0, 1), v(0, 2));
            let wo = Vec3::new(v(1, 0), v(1, 1), v(1, 2));
            (wi, wo, half_vector(wi, wo))
        })
        .collect()
}

fn run<R: Real>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    id: &str,
    p: &[([f64; 3], [f64; 3])],
    f: impl Fn(Vec3<R>, Vec3<R>, Vec3<R>) -> R,
) {
    let input = pack::<R>(p);
    let mut out = vec![R::zero(); input.len()];
    group.bench_function(id, |b| {
        b.iter(|| {
            for (o, &(wi, wo, wm)) in out.iter_mut().zip(black_box(&input)) {
                *o = f(wi, wo, wm);
            }
            black_box(&out);
        })
    });
}

/// Benchmarks `$body` for every lane type; `$setup` (over `R`) builds the material once.
macro_rules! all_types {
    ($c:expr, $name:expr, $p:expr, $n:ident = $setup:expr, |$wi:ident, $wo:ident, $wm:ident| $body:expr) => {{
        let mut group = $c.benchmark_group($name);
        group.throughput(Throughput::Elements(N as u64));
        all_types!(@one group, $p, f32, "f32", $n, $setup, $wi, $wo, $wm, $body);
        all_types!(@one group, $p, f64, "f64", $n, $setup, $wi, $wo, $wm, $body);
        all_types!(@one group, $p, f32x4, "f32x4", $n, $setup, $wi, $wo, $wm, $body);
        all_types!(@one group, $p, f32x8, "f32x8", $n, $setup, $wi, $wo, $wm, $body);
        all_types!(@one group, $p, f32x16, "f32x16", $n, $setup, $wi, $wo, $wm, $body);
        all_types!(@one group, $p, f64x4, "f64x4", $n, $setup, $wi, $wo, $wm, $body);
        group.finish();
    }};
    (@one $group:expr, $p:expr, $t:ty, $id:expr, $n:ident, $setup:expr, $wi:ident, $wo:ident, $wm:ident, $body:expr) => {{
        #[allow(dead_code)]
        type R = $t;
        #[allow(dead_code)]
        type S = <$t as Real>::Scalar;
        #[allow(unused_variables)]
        let $n = $setup;
        #[allow(unused_variables)]
        run::<$t>(&mut $group, $id, $p, |$wi, $wo, $wm| $body);
    }};
}

fn ndfs(c: &mut Criterion) {
    let p = pairs();
    all_types!(
        c,
        "d/ggx",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| n.d(wm)
    );
    all_types!(
        c,
        "d/ggx_aniso",
        &p,
        n = Ggx::<S>::anisotropic(0.1, 0.5).unwrap().splat::<R>(),
        |wi, wo, wm| n.d(wm)
    );
    all_types!(
        c,
        "d/beckmann",
        &p,
        n = Beckmann::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| n.d(wm)
    );
    all_types!(
        c,
        "d/blinn_phong",
        &p,
        n = BlinnPhong::<S>::new(64.0).unwrap().splat::<R>(),
        |wi, wo, wm| n.d(wm)
    );
    all_types!(
        c,
        "d/ashikhmin_shirley",
        &p,
        n = AshikhminShirleyLobe::<S>::new(10.0, 500.0)
            .unwrap()
            .splat::<R>(),
        |wi, wo, wm| n.d(wm)
    );
    all_types!(
        c,
        "lambda/ggx",
        &p,
        n = Ggx::<S>::anisotropic(0.1, 0.5).unwrap().splat::<R>(),
        |wi, wo, wm| n.lambda(wi)
    );
    all_types!(
        c,
        "lambda/beckmann",
        &p,
        n = Beckmann::<S>::anisotropic(0.1, 0.5).unwrap().splat::<R>(),
        |wi, wo, wm| n.lambda(wi)
    );
    all_types!(c, "erf", &p, n = (), |wi, wo, wm| brdf::ndf::erf(
        wi.z * R::from_f64(4.0) - R::from_f64(2.0)
    ));
}

fn masking(c: &mut Criterion) {
    let p = pairs();
    all_types!(
        c,
        "v/correlated_ggx",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| SmithHeightCorrelated.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "v/separable_ggx",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| SmithSeparable.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "v/correlated_beckmann",
        &p,
        n = Beckmann::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| SmithHeightCorrelated.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "v/separable_walter_beckmann",
        &p,
        n = Beckmann::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| SmithSeparableWalter.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "v/v_cavity",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| VCavity.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "v/schlick_ggx",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| SchlickGgx.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "v/hammon",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| HammonApprox.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "v/kelemen",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| Kelemen.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "v/implicit",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| Implicit.visibility(&n, wi, wo, wm)
    );
    all_types!(
        c,
        "g2/correlated_ggx",
        &p,
        n = Ggx::<S>::new(0.3).unwrap().splat::<R>(),
        |wi, wo, wm| SmithHeightCorrelated.g2(&n, wi, wo, wm)
    );
}

criterion_group!(benches, ndfs, masking);
criterion_main!(benches);
