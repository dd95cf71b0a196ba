//! Shared test support: proptest configuration, direction warps, ULP comparison of SIMD
//! lanes against scalars, and an independent numeric quadrature.
//!
//! Every integration-test file starts with `mod common;` and uses what it needs.
#![allow(dead_code, unused_macros, unused_imports)]

use brdf::{Real, Scalar, Vec3};
use proptest::prelude::*;

/// proptest configuration: `PROPTEST_CASES` (env) or `default` cases. CI keeps the default.
pub fn config(default: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default);
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Uniform sample in [0, 1], with the end points and values a hair from them drawn often:
/// warped through a direction map they produce normal incidence and grazing angles.
pub fn unit() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => 0.0f64..=1.0,
        1 => Just(0.0),
        1 => Just(1.0),
        1 => (0.0f64..=1.0).prop_map(|t| 1e-7 * t),
        1 => (0.0f64..=1.0).prop_map(|t| 1.0 - 1e-7 * t),
    ]
}

/// Cosine of a polar angle covering `[0, 1]` uniformly in solid angle, with grazing
/// (down to 1e-7 and exactly 0) and normal incidence drawn often.
pub fn cos_theta() -> impl Strategy<Value = f64> {
    unit()
}

/// Warps `(u1, u2) ∈ [0,1]²` to a direction on the upper hemisphere, uniform in solid angle
/// (pbrt's `SampleUniformHemisphere`): `cos θ = u1`, `φ = 2π u2`.
pub fn hemisphere(u1: f64, u2: f64) -> Vec3<f64> {
    let z = u1;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * std::f64::consts::PI * u2;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Strategy: a unit direction on the upper hemisphere (map, never filter), including
/// `cos θ ∈ {0, 1e-7…, 1}`.
pub fn direction() -> impl Strategy<Value = Vec3<f64>> {
    (unit(), 0.0f64..1.0).prop_map(|(u1, u2)| hemisphere(u1, u2))
}

/// Converts a direction to `f32`.
pub fn to_f32(w: Vec3<f64>) -> Vec3<f32> {
    Vec3::new(w.x as f32, w.y as f32, w.z as f32)
}

/// Distance in units in the last place between two floats of the same type
/// (0 when equal, including +0/−0; `u64::MAX` when exactly one is NaN).
pub fn ulps<S: Scalar>(a: S, b: S) -> u64 {
    let (a, b): (f64, f64) = (a.into(), b.into());
    if a == b || (a.is_nan() && b.is_nan()) {
        return 0;
    }
    if a.is_nan() || b.is_nan() {
        return u64::MAX;
    }
    if size_of::<S>() == 4 {
        let key = |x: f32| {
            let i = x.to_bits() as i32;
            if i < 0 {
                i32::MIN.wrapping_sub(i) as i64
            } else {
                i as i64
            }
        };
        (key(a as f32) - key(b as f32)).unsigned_abs()
    } else {
        let key = |x: f64| {
            let i = x.to_bits() as i64;
            if i < 0 {
                (i64::MIN.wrapping_sub(i)) as i128
            } else {
                i as i128
            }
        };
        (key(a) - key(b)).unsigned_abs() as u64
    }
}

/// Packs up to `R::LANES` rows of arguments into one lane value per argument, repeating the
/// last row to fill the register.
pub fn pack<R: Real, const K: usize>(rows: &[[f64; K]]) -> [R; K] {
    core::array::from_fn(|j| {
        R::from_fn(|l| <R::Scalar as Scalar>::of(rows[l.min(rows.len() - 1)][j]))
    })
}

/// Asserts that a formula evaluated on every SIMD lane type equals the scalar result of the
/// same precision (f32x4/f32x8/f32x16 against f32, f64x4 against f64) within `ulp` units in
/// the last place, or within the absolute tolerance `abs` for results near zero.
///
/// ```ignore
/// assert_lanes_match!("fresnel_schlick", ulp = 2, abs = 1e-30, rows,
///     fn(f0, c) { brdf::fresnel::schlick(f0, c) });
/// ```
/// `rows` is a `&[[f64; K]]` with one column per argument.
macro_rules! assert_lanes_match {
    ($name:expr, ulp = $ulp:expr, abs = $abs:expr, $rows:expr, fn($($a:ident),+) $body:block) => {{
        #[allow(unused_variables)]
        fn formula<R: brdf::Real>($($a: R),+) -> R $body
        let rows = $rows;
        let mut worst: u64 = 0;
        $crate::common::assert_lanes_match!(@one brdf::f32x4, f32, formula, rows, $ulp, $abs, $name, worst, $($a),+);
        $crate::common::assert_lanes_match!(@one brdf::f32x8, f32, formula, rows, $ulp, $abs, $name, worst, $($a),+);
        $crate::common::assert_lanes_match!(@one brdf::f32x16, f32, formula, rows, $ulp, $abs, $name, worst, $($a),+);
        $crate::common::assert_lanes_match!(@one brdf::f64x4, f64, formula, rows, $ulp, $abs, $name, worst, $($a),+);
        worst
    }};
    (@one $v:ty, $s:ty, $f:ident, $rows:expr, $ulp:expr, $abs:expr, $name:expr, $worst:ident, $($a:ident),+) => {
        for chunk in $rows.chunks(<$v as brdf::Real>::LANES) {
            let [$($a),+] = $crate::common::pack::<$v, _>(chunk);
            let lanes = $f($($a),+);
            for (l, row) in chunk.iter().enumerate() {
                let [$($a),+] = row.map(|x| x as $s);
                let scalar = $f($($a),+);
                let lane = brdf::Real::lane(lanes, l);
                let d = $crate::common::ulps::<$s>(lane, scalar);
                let close = ((lane - scalar) as f64).abs() <= $abs;
                assert!(
                    d <= $ulp || close,
                    "{}: {} lane {} = {:e}, scalar = {:e} ({} ulp > {}) at {:?}",
                    $name, stringify!($v), l, lane, scalar, d, $ulp, row
                );
                assert!(lane.is_finite() == scalar.is_finite(), "{}: finiteness differs at {:?}", $name, row);
                if !close { $worst = $worst.max(d); }
            }
        }
    };
}
pub(crate) use assert_lanes_match;

/// Nodes and weights of the n-point Gauss-Legendre rule on [−1, 1] (Newton on Pₙ; accurate to
/// ~1e-15 for n ≤ 512). Independent of the crate's own `analysis` integrator.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// ∫ₐᵇ f by composite Gauss-Legendre: `panels` equal panels of `order` points each.
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize, order: usize) -> f64 {
    let rule = gauss_legendre(order);
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let (lo, hi) = (a + p as f64 * h, a + (p + 1) as f64 * h);
        let (mid, half) = ((lo + hi) / 2.0, (hi - lo) / 2.0);
        for &(x, w) in &rule {
            sum += w * half * f(mid + half * x);
        }
    }
    sum
}

/// ∫ over the points `breaks` (sorted): composite Gauss-Legendre on each sub-interval, so a
/// caller puts panel edges where the integrand is sharp (e.g. near a narrow lobe's peak).
pub fn integrate_pieces(
    f: impl Fn(f64) -> f64,
    breaks: &[f64],
    panels: usize,
    order: usize,
) -> f64 {
    breaks
        .windows(2)
        .map(|w| integrate(&f, w[0], w[1], panels, order))
        .sum()
}

#[test]
fn gauss_legendre_integrates_polynomials_and_cosines() {
    let i = integrate(|x| x.powi(9) + 3.0 * x * x, 0.0, 2.0, 1, 6);
    assert!((i - (1024.0 / 10.0 + 8.0)).abs() < 1e-12, "{i}");
    let i = integrate(|x| x.cos(), 0.0, std::f64::consts::FRAC_PI_2, 4, 16);
    assert!((i - 1.0).abs() < 1e-14, "{i}");
}

#[test]
fn ulps_counts_across_zero_and_precision() {
    assert_eq!(ulps(1.0f32, f32::from_bits(1.0f32.to_bits() + 3)), 3);
    assert_eq!(ulps(-0.0f32, 0.0), 0);
    assert_eq!(ulps(f32::from_bits(1), -f32::from_bits(1)), 2);
    assert_eq!(ulps(1.0f64, 1.0 + f64::EPSILON), 1);
}
pub mod chi2;

/// Solves `A x = b` by Gaussian elimination with partial pivoting.
#[allow(clippy::needless_range_loop)]
/// (The polynomial fits of `tests/fast.rs` and `tests/sin_cos_2pi.rs`.)
pub fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap();
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..n {
            let f = a[r][c] / a[c][c];
            for k in c..n {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    x
}

/// `c₀ + c₁x + c₂x² + …` by Horner's rule.
pub fn horner(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * x + k)
}
