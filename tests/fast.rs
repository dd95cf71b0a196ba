//! Tests of `brdf::fast`: the Remez fits behind the coefficient tables are re-derived and
//! their error curves equioscillate; every approximation stays within its documented bound
//! on dense grids and under property tests over its whole domain (extremes included); the
//! rsqrt magic constant is re-found by search; SIMD lanes match scalars.
mod common;

use brdf::{Real, Scalar, f32x4, f32x8, f32x16, f64x4, fast};
use common::{horner, solve};
use proptest::prelude::*;
use std::f64::consts::{LN_2, SQRT_2};
use std::sync::OnceLock;

// ---------------------------------------------------------------------------------------
// The fit: weighted minimax by the Remez exchange algorithm (independent re-implementation
// of the procedure described in the module docs).
// ---------------------------------------------------------------------------------------

/// Sign-alternating local extrema of `r` on a uniform grid of `[a, b]`, merging runs of one
/// sign to their largest member.
fn alternation(r: &dyn Fn(f64) -> f64, a: f64, b: f64, grid: usize) -> Vec<(f64, f64)> {
    let xs: Vec<f64> = (0..=grid)
        .map(|i| a + (b - a) * i as f64 / grid as f64)
        .collect();
    let es: Vec<f64> = xs.iter().map(|&x| r(x)).collect();
    let mut alt: Vec<(f64, f64)> = vec![];
    for i in 0..=grid {
        let l = if i > 0 { es[i - 1].abs() } else { -1.0 };
        let rr = if i < grid { es[i + 1].abs() } else { -1.0 };
        if es[i] == 0.0 || es[i].abs() < l || es[i].abs() < rr {
            continue;
        }
        match alt.last_mut() {
            Some(last) if last.1.signum() == es[i].signum() => {
                if es[i].abs() > last.1.abs() {
                    *last = (xs[i], es[i]);
                }
            }
            _ => alt.push((xs[i], es[i])),
        }
    }
    alt
}

/// Minimises `max |w(x)·(q(x) − g(x))|` over polynomials `q` of degree `n` on `[a, b]`.
/// Returns the coefficients and the levelled error.
fn remez(
    g: &dyn Fn(f64) -> f64,
    w: &dyn Fn(f64) -> f64,
    a: f64,
    b: f64,
    n: usize,
) -> (Vec<f64>, f64) {
    let m = n + 2;
    let mut xs: Vec<f64> = (0..m)
        .map(|i| {
            a + (b - a) * (1.0 - (std::f64::consts::PI * (i as f64 + 0.5) / m as f64).cos()) / 2.0
        })
        .collect();
    let (mut coef, mut level) = (vec![], 0.0);
    for _ in 0..60 {
        let rows = xs
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let mut r: Vec<f64> = (0..=n).map(|k| w(x) * x.powi(k as i32)).collect();
                r.push(if i % 2 == 0 { 1.0 } else { -1.0 });
                r
            })
            .collect();
        let sol = solve(rows, xs.iter().map(|&x| w(x) * g(x)).collect());
        coef = sol[..=n].to_vec();
        level = sol[n + 1].abs();
        let c = coef.clone();
        let mut alt = alternation(&|x| w(x) * (horner(&c, x) - g(x)), a, b, 200_000);
        while alt.len() > m {
            if alt[0].1.abs() < alt[alt.len() - 1].1.abs() {
                alt.remove(0);
            } else {
                alt.pop();
            }
        }
        assert_eq!(alt.len(), m, "Remez lost the alternation at degree {n}");
        let max = alt.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        xs = alt.iter().map(|p| p.0).collect();
        if max / level - 1.0 < 1e-9 {
            break;
        }
    }
    (coef, level)
}

fn exp2_target(f: f64) -> f64 {
    if f == 0.0 {
        LN_2
    } else {
        (f * LN_2).exp_m1() / f
    }
}
fn exp2_weight(f: f64) -> f64 {
    f / f.exp2()
}
fn log2_target(u: f64) -> f64 {
    if u == 0.0 {
        1.0 / LN_2
    } else {
        u.ln_1p() / (u * LN_2)
    }
}
fn log2_weight(u: f64) -> f64 {
    1.0 / log2_target(u)
}
const LOG_A: f64 = SQRT_2 / 2.0 - 1.0;
const LOG_B: f64 = SQRT_2 - 1.0;

/// Max relative error, in exact (f64) arithmetic, of the tabulated exp2 polynomial of degree d
/// (10⁶-point grid, computed once).
fn exp2_minimax(d: usize) -> f64 {
    static CACHE: OnceLock<Vec<f64>> = OnceLock::new();
    CACHE.get_or_init(|| {
        (0..=8)
            .map(|d| {
                if d < 2 {
                    return f64::NAN;
                }
                let c = fast::EXP2_Q[d];
                (0..=1_000_000)
                    .map(|i| i as f64 / 1e6)
                    .map(|f| (exp2_weight(f) * (horner(c, f) - exp2_target(f))).abs())
                    .fold(0.0, f64::max)
            })
            .collect()
    })[d]
}
fn log2_minimax(d: usize) -> f64 {
    static CACHE: OnceLock<Vec<f64>> = OnceLock::new();
    CACHE.get_or_init(|| {
        (0..=12)
            .map(|d| {
                if d < 2 {
                    return f64::NAN;
                }
                let c = fast::LOG2_Q[d];
                (0..=1_000_000)
                    .map(|i| LOG_A + (LOG_B - LOG_A) * i as f64 / 1e6)
                    .map(|u| (log2_weight(u) * (horner(c, u) - log2_target(u))).abs())
                    .fold(0.0, f64::max)
            })
            .collect()
    })[d]
}

#[test]
fn tables_are_the_remez_minimax_and_equioscillate() {
    let cases: Vec<(&str, usize, &[f64], f64, f64)> = (2..=8)
        .map(|d| ("exp2", d, fast::EXP2_Q[d], 0.0, 1.0))
        .chain((2..=12).map(|d| ("log2", d, fast::LOG2_Q[d], LOG_A, LOG_B)))
        .collect();
    for (name, d, table, a, b) in cases {
        let (g, w): (&dyn Fn(f64) -> f64, &dyn Fn(f64) -> f64) = if name == "exp2" {
            (&exp2_target, &exp2_weight)
        } else {
            (&log2_target, &log2_weight)
        };
        let (coef, level) = remez(g, w, a, b, d - 1);
        assert_eq!(coef.len(), table.len());
        for (k, (&c, &t)) in coef.iter().zip(table).enumerate() {
            // The highest degrees sit near the f64 resolution of the fit (errors ~1e-12),
            // where the coefficients are determined to ~1e-7 only; the error level checked
            // below is the sharp test.
            assert!(
                (c - t).abs() <= 1e-6 * t.abs(),
                "{name} degree {d} coefficient {k}: {c} vs {t}"
            );
        }
        // The table's error curve equioscillates: d + 1 alternating extrema of (nearly) equal
        // size, which characterises the minimax polynomial (Chebyshev's theorem).
        let r = |x: f64| w(x) * (horner(table, x) - g(x));
        let alt = alternation(&r, a, b, 400_000);
        let max = alt.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        let equal = alt.iter().filter(|p| p.1.abs() >= 0.999 * max).count();
        assert!(
            equal > d,
            "{name} degree {d}: only {equal} extrema at the level {max:e}"
        );
        assert!(
            (max / level - 1.0).abs() < 1e-5 + 1e-16 / level,
            "{name} {d}: {max:e} vs levelled {level:e}"
        );
        println!(
            "{name} degree {d:2}: minimax relative error {max:.3e}, {} alternations",
            alt.len()
        );
    }
}

// ---------------------------------------------------------------------------------------
// Documented bounds: minimax error (exact arithmetic) plus rounding, u = unit roundoff.
// ---------------------------------------------------------------------------------------

fn unit_roundoff<S: Scalar>() -> f64 {
    let e: f64 = S::EPSILON.into();
    e / 2.0
}
/// exp2 of degree d: ε_d + 2u.
fn exp2_bound<S: Scalar>(d: usize) -> f64 {
    exp2_minimax(d) * 1.000_01 + 2.0 * unit_roundoff::<S>()
}
/// log2 of degree d: ε_d + 4u.
fn log2_bound<S: Scalar>(d: usize) -> f64 {
    log2_minimax(d) * 1.000_01 + 4.0 * unit_roundoff::<S>()
}
/// pow(L, E) at t = y·log₂x: the exp2 bound plus ln2·|t| times the relative error of
/// t = y·log₂x, i.e. the log2 bound and one rounding of the product:
/// (ε_E + 2u) + ln2·|t|·(ε_L + 5u).
fn pow_bound<S: Scalar>(l: usize, e: usize, t: f64) -> f64 {
    exp2_bound::<S>(e) + LN_2 * t.abs() * (log2_bound::<S>(l) + unit_roundoff::<S>())
}

fn rel(a: f64, r: f64) -> f64 {
    if a == r { 0.0 } else { (a / r - 1.0).abs() }
}

macro_rules! for_degrees {
    ($mac:ident: $($d:literal)*) => { vec![$(($d, $mac!($d))),*] };
}

/// exp2 on 10⁶ points spanning every normal result, for each degree and both precisions.
#[test]
fn exp2_within_bound_on_dense_grid() {
    fn worst<S: Scalar, const D: usize>(lo: f64, hi: f64) -> f64 {
        let n = 1_000_000;
        let mut w = 0.0f64;
        for i in 0..=n {
            let x = S::of(lo + (hi - lo) * i as f64 / n as f64);
            let xd: f64 = x.into();
            let (a, r): (f64, f64) = (fast::exp2::<D, S>(x).into(), xd.exp2());
            // The last ε/ln2 below the overflow threshold may round up to ∞ (documented).
            if xd < hi - 1e-3 {
                assert!(a.is_finite(), "exp2<{D}>({xd}) = {a}");
                w = w.max(rel(a, r));
            }
        }
        w
    }
    macro_rules! m {
        ($d:literal) => {
            (
                worst::<f32, $d>(-126.0, 128.0),
                worst::<f64, $d>(-1022.0, 1024.0),
            )
        };
    }
    for (d, (w32, w64)) in for_degrees!(m: 2 3 4 5 6 7 8) {
        println!(
            "exp2<{d}>: f32 {w32:.3e} (bound {:.3e}), f64 {w64:.3e} (bound {:.3e})",
            exp2_bound::<f32>(d),
            exp2_bound::<f64>(d)
        );
        assert!(
            w32 <= exp2_bound::<f32>(d) && w64 <= exp2_bound::<f64>(d),
            "exp2<{d}>"
        );
    }
}

#[test]
fn exp2_extremes() {
    fn check<S: Scalar, const D: usize>(lo: f64, hi: f64) {
        let e = |x: f64| -> f64 { fast::exp2::<D, S>(S::of(x)).into() };
        for k in [-1022, -126, -100, -1, 0, 1, 10, 127] {
            if (k as f64) >= lo && (k as f64) < hi {
                assert_eq!(e(k as f64), (k as f64).exp2(), "exp2<{D}>({k}) is exact");
            }
        }
        // flush below the normal range, never NaN or garbage for huge negative arguments
        for x in [
            lo - 0.5,
            lo - 1.0,
            lo - 1.0001,
            -1e4,
            -1e6,
            -3e38,
            f64::NEG_INFINITY,
        ] {
            assert_eq!(e(x), 0.0, "exp2<{D}>({x})");
        }
        for x in [hi, hi + 1.0, 1e6, f64::INFINITY] {
            assert_eq!(e(x), f64::INFINITY, "exp2<{D}>({x})");
        }
        assert!(e(hi - 0.01).is_finite());
        let first = e(lo);
        assert!(first > 0.0 && rel(first, lo.exp2()) <= exp2_bound::<S>(D));
    }
    check::<f32, 2>(-126.0, 128.0);
    check::<f32, 5>(-126.0, 128.0);
    check::<f32, 8>(-126.0, 128.0);
    check::<f64, 3>(-1022.0, 1024.0);
    check::<f64, 8>(-1022.0, 1024.0);
}

/// log2 on 10⁶ points log-spaced over all normal numbers plus 10⁶ points around 1.
#[test]
fn log2_within_bound_on_dense_grid() {
    fn worst<S: Scalar, const D: usize>(emin: f64, emax: f64) -> f64 {
        let n = 1_000_000;
        let mut w = 0.0f64;
        for i in 0..=n {
            for x in [
                S::of((emin + (emax - emin) * i as f64 / n as f64).exp2()),
                S::of(0.5 + 1.5 * i as f64 / n as f64),
            ] {
                let xd: f64 = x.into();
                let (a, r): (f64, f64) = (fast::log2::<D, S>(x).into(), xd.log2());
                assert!(a.is_finite());
                w = w.max(rel(a, r));
            }
        }
        w
    }
    macro_rules! m {
        ($d:literal) => {
            (
                worst::<f32, $d>(-126.0, 127.99),
                worst::<f64, $d>(-1022.0, 1023.99),
            )
        };
    }
    for (d, (w32, w64)) in for_degrees!(m: 2 3 4 5 6 7 8 9 10 11 12) {
        println!(
            "log2<{d}>: f32 {w32:.3e} (bound {:.3e}), f64 {w64:.3e} (bound {:.3e})",
            log2_bound::<f32>(d),
            log2_bound::<f64>(d)
        );
        assert!(
            w32 <= log2_bound::<f32>(d) && w64 <= log2_bound::<f64>(d),
            "log2<{d}>"
        );
    }
}

#[test]
fn log2_extremes() {
    fn check<S: Scalar, const D: usize>() {
        let l = |x: S| -> f64 { fast::log2::<D, S>(x).into() };
        assert_eq!(l(S::one()), 0.0);
        for k in [-126, -20, -1, 1, 2, 50, 127] {
            assert_eq!(l(S::of((k as f64).exp2())), k as f64);
        }
        let tiny: f64 = if size_of::<S>() == 4 {
            f32::MIN_POSITIVE as f64
        } else {
            f64::MIN_POSITIVE
        };
        let max: f64 = if size_of::<S>() == 4 {
            f32::MAX as f64
        } else {
            f64::MAX
        };
        assert!(rel(l(S::of(tiny)), tiny.log2()) <= log2_bound::<S>(D));
        assert!(rel(l(S::of(max)), max.log2()) <= log2_bound::<S>(D));
        for x in [0.0, -0.0, tiny / 2.0, tiny / 1e6, -1.0] {
            assert_eq!(l(S::of(x)), f64::NEG_INFINITY, "log2<{D}>({x})");
        }
    }
    check::<f32, 2>();
    check::<f32, 9>();
    check::<f64, 4>();
    check::<f64, 12>();
}

/// pow error as a function of |t| = |y·log₂x| on bases spread over [1e-30, 1) and exponents
/// chosen so that |t| sits at the band edge (the worst case of each band): the bound
/// (ε_E + 2u) + ln2·|t|·(ε_L + 3u) holds, and the table printed is the one in the docs.
#[test]
fn pow_error_grows_linearly_with_t() {
    fn worst<S: Scalar, const L: usize, const E: usize>(t: f64) -> f64 {
        let n = 200_000;
        let mut w = 0.0f64;
        for i in 1..n {
            let s = i as f64 / n as f64;
            let x = if s < 0.5 {
                0.5 * 10f64.powf(-30.0 * (1.0 - 2.0 * s))
            } else {
                1.0 - 0.5 * 10f64.powf(-7.0 * (2.0 * s - 1.0))
            };
            let (x, y) = (S::of(x), S::of(t / -x.log2()));
            let (xd, yd): (f64, f64) = (x.into(), y.into());
            let r = xd.powf(yd);
            if r >= 1e-30 {
                let a: f64 = fast::pow::<L, E, S>(x, y).into();
                let e = rel(a, r);
                assert!(
                    e <= pow_bound::<S>(L, E, t),
                    "pow<{L},{E}>({xd}, {yd}) = {a} vs {r}"
                );
                w = w.max(e);
            }
        }
        w
    }
    macro_rules! m {
        ($l:literal, $e:literal) => {{
            let ts = [1.0, 10.0, 30.0, 66.4, 99.6];
            let f32s = ts.map(|t| worst::<f32, $l, $e>(t));
            let f64s = ts.map(|t| worst::<f64, $l, $e>(t));
            println!(
                "pow<{},{}> |t| = {ts:?}\n   f32 {:?}\n   f64 {:?}",
                $l,
                $e,
                f32s.map(|v| format!("{v:.2e}")),
                f64s.map(|v| format!("{v:.2e}"))
            );
            (f32s, f64s)
        }};
    }
    m!(6, 3);
    m!(8, 4);
    let (_, f64s) = m!(9, 4);
    // The Blinn-Phong target: the cheapest pair within 1e-5 for results ≥ 1e-30 in f64 ...
    assert!(f64s.iter().all(|&e| e <= 1e-5));
    let (f32s, _) = m!(9, 5);
    // ... and in f32 up to |t| = 66.4 (results ≥ 1e-20); at 1e-30 the f32 rounding floor
    // (≈ 1.2e-7·|t|) exceeds 1e-5 for every degree.
    assert!(
        f32s[..4].iter().all(|&e| e <= 1e-5) && f32s[4] <= 1.3e-5,
        "{f32s:?}"
    );
    let f32_9_5 = f32s[4];
    let (f32s, _) = m!(12, 8);
    // Higher degrees do not lower the f32 error at |t| = 99.6: it is rounding.
    assert!(f32s[4] > 0.8 * f32_9_5, "{f32s:?}");
    // Cheaper pairs miss the target: (8, 5) and (9, 3) in f64 (and so in f32).
    assert!(worst::<f64, 8, 5>(99.6) > 1e-5 && worst::<f64, 9, 3>(1.0) > 1e-5);
    assert!(worst::<f64, 7, 6>(99.6) > 1e-5 && worst::<f64, 10, 2>(1.0) > 1e-5);
}

#[test]
fn pow_phong_meets_its_documented_target() {
    fn check<S: Scalar>(t_max: f64, target: f64) {
        let n = 400_000;
        let mut s = 0x2545_F491_4F6C_DD1D_u64;
        let mut rnd = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..n {
            let x = S::of(10f64.powf(-30.0 * rnd().powi(3)));
            let y = S::of(1e4 * rnd().powi(4));
            let (xd, yd): (f64, f64) = (x.into(), y.into());
            let r = xd.powf(yd);
            if r >= 2f64.powf(-t_max) {
                let a: f64 = fast::pow_phong(x, y).into();
                assert!(rel(a, r) <= target, "pow_phong({xd}, {yd}) = {a} vs {r}");
            }
        }
    }
    check::<f64>(99.66, 1e-5);
    check::<f32>(66.4, 1e-5);
    check::<f32>(99.66, 1.3e-5);
}

#[test]
fn pow_special_values() {
    fn check<S: Scalar, const L: usize, const E: usize>() {
        let p = |x: f64, y: f64| -> f64 { fast::pow::<L, E, S>(S::of(x), S::of(y)).into() };
        for y in [1e-6, 0.5, 1.0, 100.0, 1e4, 1e6, 1e30] {
            assert_eq!(p(0.0, y), 0.0, "0^{y}");
            assert_eq!(p(1.0, y), 1.0, "1^{y}");
            assert_eq!(p(0.5, 1e4 + y), 0.0, "underflow flushes");
            let subnormal = if size_of::<S>() == 4 { 1e-40 } else { 1e-310 };
            assert_eq!(p(subnormal, y), 0.0, "subnormal base counts as 0");
        }
        for x in [0.0, 1e-30, 0.5, 1.0, 3.0] {
            assert_eq!(p(x, 0.0), 1.0, "{x}^0 = 1 (0^0 = 1)");
        }
        assert_eq!(p(0.0, -1.0), f64::INFINITY);
        assert_eq!(p(2.0, 1e6), f64::INFINITY);
        assert_eq!(p(0.5, 3.0), 0.125);
    }
    check::<f32, 3, 2>();
    check::<f32, 9, 5>();
    check::<f64, 9, 4>();
    check::<f64, 12, 8>();
}

fn base() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => (-30.0f64..0.0).prop_map(|e| 10f64.powf(e)),
        2 => common::unit(),
        1 => (0.0f64..1.0).prop_map(|t| 1.0 - 1e-7 * t),
        1 => Just(0.0),
        1 => (0.0f64..1.0).prop_map(|t| 1e-45 * t),
        1 => 1.0f64..1e3,
    ]
}
fn exponent() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => (0.0f64..4.0).prop_map(|e| 10f64.powf(e)),
        1 => (4.0f64..6.0).prop_map(|e| 10f64.powf(e)),
        1 => Just(0.0),
        1 => 0.0f64..1.0,
        1 => -100.0f64..0.0,
    ]
}

fn pow_prop<S: Scalar, const L: usize, const E: usize>(
    x: f64,
    y: f64,
) -> Result<(), TestCaseError> {
    let (xs, ys) = (S::of(x), S::of(y));
    let (x, y): (f64, f64) = (xs.into(), ys.into());
    let a: f64 = fast::pow::<L, E, S>(xs, ys).into();
    let min: f64 = if size_of::<S>() == 4 {
        f32::MIN_POSITIVE as f64
    } else {
        f64::MIN_POSITIVE
    };
    let max: f64 = if size_of::<S>() == 4 {
        f32::MAX as f64
    } else {
        f64::MAX
    };
    let r = if x < min {
        if y == 0.0 {
            1.0
        } else if y > 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    } else {
        x.powf(y)
    };
    prop_assert!(!a.is_nan(), "pow<{L},{E}>({x}, {y}) is NaN");
    if r >= 2.0 * min && r <= max / 2.0 {
        let t = if x < min { 0.0 } else { y * x.log2() };
        prop_assert!(
            rel(a, r) <= pow_bound::<S>(L, E, t),
            "pow<{L},{E}>({x}, {y}) = {a} vs {r}"
        );
    } else if r < 2.0 * min {
        prop_assert!(
            a >= 0.0 && a <= 2.0 * min * 1.01,
            "pow<{L},{E}>({x}, {y}) = {a} vs {r}"
        );
    } else {
        prop_assert!(a >= max / 2.0 * 0.99, "pow<{L},{E}>({x}, {y}) = {a} vs {r}");
    }
    Ok(())
}

proptest! {
    #![proptest_config(common::config(512))]

    /// pow over the whole domain (x ∈ {0, subnormal, [1e-30, 1], > 1}, y ∈ {0, < 0, up to
    /// 10⁶}): within the |t|-dependent bound for normal results, flushed to [0, 2·MIN] below,
    /// ≈ ∞ above, never NaN.
    #[test]
    fn pow_within_bound_everywhere(x in base(), y in exponent()) {
        pow_prop::<f32, 9, 5>(x, y)?;
        pow_prop::<f32, 4, 3>(x, y)?;
        pow_prop::<f64, 9, 4>(x, y)?;
        pow_prop::<f64, 12, 8>(x, y)?;
    }

    /// exp2 over [−2000, 2000] in both precisions.
    #[test]
    fn exp2_within_bound_everywhere(x in -2000.0f64..2000.0) {
        let a = fast::exp2::<5, f32>(x as f32) as f64;
        let r = ((x as f32) as f64).exp2();
        if (f32::MIN_POSITIVE as f64..f32::MAX as f64 / 2.0).contains(&r) {
            prop_assert!(rel(a, r) <= exp2_bound::<f32>(5));
        } else if r < f32::MIN_POSITIVE as f64 {
            prop_assert_eq!(a, 0.0);
        } else {
            prop_assert!(a > f32::MAX as f64 / 2.0);
        }
        let a = fast::exp2::<7, f64>(x);
        let r = x.exp2();
        if (f64::MIN_POSITIVE..f64::MAX / 2.0).contains(&r) {
            prop_assert!(rel(a, r) <= exp2_bound::<f64>(7));
        } else if r < f64::MIN_POSITIVE {
            prop_assert_eq!(a, 0.0);
        }
    }

    /// log2 of arbitrary positive normal bit patterns.
    #[test]
    fn log2_within_bound_everywhere(b32 in 0x0080_0000u32..0x7F80_0000, b64 in 0x0010_0000_0000_0000u64..0x7FF0_0000_0000_0000) {
        let x = f32::from_bits(b32);
        prop_assert!(rel(fast::log2::<6, f32>(x) as f64, (x as f64).log2()) <= log2_bound::<f32>(6));
        let x = f64::from_bits(b64);
        prop_assert!(rel(fast::log2::<10, f64>(x), x.log2()) <= log2_bound::<f64>(10));
    }
}

// ---------------------------------------------------------------------------------------
// rsqrt
// ---------------------------------------------------------------------------------------

fn bit_trick_error(magic: u32, steps: usize, samples: u32) -> f64 {
    let mut w = 0.0f64;
    for i in 0..samples {
        // [1, 4) covers every case: the error is periodic under x → 4x.
        let x = f32::from_bits(
            0x3F80_0000 + ((i as u64 * (0x4080_0000 - 0x3F80_0000)) / samples as u64) as u32,
        );
        let mut y = f32::from_bits(magic - (x.to_bits() >> 1)) as f64;
        for _ in 0..steps {
            y *= 1.5 - 0.5 * x as f64 * y * y;
        }
        w = w.max((y * (x as f64).sqrt() - 1.0).abs());
    }
    w
}

/// The magic constant 0x5F37_5A80 is (within the sampling) the one that minimises the error
/// after one Newton step; the scan covers 2¹⁶ candidates around the classic constants.
#[test]
fn rsqrt_magic_constant_is_the_searched_optimum() {
    let ours = 0x5F37_5A80u32;
    let (mut best, mut at) = (f64::MAX, 0);
    for m in (0x5F37_0000u32..0x5F38_0000).step_by(16) {
        let e = bit_trick_error(m, 1, 1 << 12);
        if e < best {
            (best, at) = (e, m);
        }
    }
    for m in at - 16..at + 16 {
        let e = bit_trick_error(m, 1, 1 << 16);
        if e < best {
            (best, at) = (e, m);
        }
    }
    let e = bit_trick_error(ours, 1, 1 << 16);
    println!("searched optimum {at:#x}: {best:.5e}; ours {ours:#x}: {e:.5e}");
    // The max-error curve is flat near the optimum (±0.03 % over ±64 steps) and the sampled
    // maximum is noisy at that level: ours must be within 0.1 % of the best found.
    assert!(e <= best * 1.001, "{e} vs {best} at {at:#x}");
}

/// Bounds of rsqrt::<N>: bit trick (f32, f64, f64x4) and hardware estimate (f32 lanes).
const RSQRT_BITS_F32: [f64; 4] = [3.44e-2, 1.76e-3, 4.8e-6, 1.8e-7];
const RSQRT_BITS_F64: [f64; 4] = [3.44e-2, 1.76e-3, 4.7e-6, 3.4e-11];
const RSQRT_HW_F32: [f64; 4] = [3.67e-4, 3.3e-7, 1.8e-7, 1.8e-7];

fn rsqrt_worst<R: Real>(n: usize, mut each: impl FnMut(R) -> R) -> f64
where
    R::Scalar: Scalar,
{
    // Every f32 bit pattern in [1, 4) (exhaustive for f32: the error is periodic under x → 4x),
    // then the extremes of the normal range.
    let mut w = 0.0f64;
    let mut xs: Vec<f64> = (0x3F80_0000u32..0x4080_0000)
        .step_by(n)
        .map(|b| f32::from_bits(b) as f64)
        .collect();
    xs.extend([
        f32::MIN_POSITIVE as f64,
        1e-30,
        1e30,
        f32::MAX as f64,
        0.3,
        7.0,
    ]);
    for chunk in xs.chunks(R::LANES) {
        let x = R::from_fn(|i| <R::Scalar as Scalar>::of(chunk[i.min(chunk.len() - 1)]));
        let y = each(x);
        for (i, &xd) in chunk.iter().enumerate() {
            let yd: f64 = y.lane(i).into();
            w = w.max((yd * xd.sqrt() - 1.0).abs());
        }
    }
    w
}

#[test]
fn rsqrt_within_bounds() {
    macro_rules! row {
        ($t:ty, $stride:expr, $bounds:expr) => {{
            let w = [
                rsqrt_worst::<$t>($stride, fast::rsqrt::<0, $t>),
                rsqrt_worst::<$t>($stride, fast::rsqrt::<1, $t>),
                rsqrt_worst::<$t>($stride, fast::rsqrt::<2, $t>),
                rsqrt_worst::<$t>($stride, fast::rsqrt::<3, $t>),
            ];
            println!(
                "rsqrt {:>6}: N=0..3 {:?}",
                stringify!($t),
                w.map(|v| format!("{v:.3e}"))
            );
            for n in 0..4 {
                assert!(w[n] <= $bounds[n], "{} N={n}: {:e}", stringify!($t), w[n]);
            }
        }};
    }
    row!(f32, 1, RSQRT_BITS_F32);
    row!(f64, 7, RSQRT_BITS_F64);
    row!(f64x4, 7, RSQRT_BITS_F64);
    row!(f32x4, 1, RSQRT_HW_F32);
    row!(f32x8, 3, RSQRT_HW_F32);
    row!(f32x16, 3, RSQRT_HW_F32);
    // Below the normal range the input is raised to it: finite, never ∞ or NaN.
    for x in [0.0f32, 1e-40, -0.0] {
        assert_eq!(
            fast::rsqrt::<2, f32>(x),
            fast::rsqrt::<2, f32>(f32::MIN_POSITIVE)
        );
        assert!(fast::rsqrt::<3, f32x8>(f32x8::splat(x)).lane(5).is_finite());
        assert!(fast::rsqrt::<1, f64>(x as f64).is_finite());
    }
}

/// The `SqrtFn` policies: `ExactSqrt` is `(√x, 1/√x)` correctly rounded; `NewtonSqrt<N>` is
/// `(x·rsqrt::<N>(x), rsqrt::<N>(x))`, both within the `rsqrt` bound of `N` steps (plus one
/// rounding for the product) over `f32` values from 10⁻³⁰ to 10³⁰, and `(0, finite)` at 0.
#[test]
fn sqrt_policies() {
    use brdf::fast::{ExactSqrt, NewtonSqrt, SqrtFn};
    fn worst<Q: SqrtFn>() -> (f64, f64) {
        let (mut ws, mut wr) = (0.0f64, 0.0f64);
        for i in 0..=60_000 {
            let x = 10f64.powf(-30.0 + 60.0 * f64::from(i) / 60_000.0) as f32;
            let (s, r) = Q::sqrt_rsqrt(x);
            let t = f64::from(x).sqrt();
            ws = ws.max((f64::from(s) / t - 1.0).abs());
            wr = wr.max((f64::from(r) * t - 1.0).abs());
        }
        let (s0, r0) = Q::sqrt_rsqrt(0.0f32);
        assert!(s0 == 0.0 && (r0.is_finite() || r0 == f32::INFINITY));
        (ws, wr)
    }
    for x in [1e-30f32, 0.3, 2.0, 7.5e12] {
        assert_eq!(ExactSqrt::sqrt_rsqrt(x), (x.sqrt(), 1.0 / x.sqrt()));
        assert_eq!(NewtonSqrt::<2>::sqrt_rsqrt(x).1, fast::rsqrt::<2, f32>(x));
    }
    let u = f64::from(f32::EPSILON) / 2.0;
    let (s, r) = worst::<ExactSqrt>();
    assert!(s <= u && r <= 2.0 * u, "exact: {s:e} {r:e}");
    for (n, (s, r)) in [
        worst::<NewtonSqrt<0>>(),
        worst::<NewtonSqrt<1>>(),
        worst::<NewtonSqrt<2>>(),
        worst::<NewtonSqrt<3>>(),
    ]
    .into_iter()
    .enumerate()
    {
        println!("NewtonSqrt<{n}>: sqrt {s:.3e}, rsqrt {r:.3e}");
        assert!(r <= RSQRT_BITS_F32[n], "rsqrt N={n}: {r:e}");
        assert!(s <= RSQRT_BITS_F32[n] + 2.0 * u, "sqrt N={n}: {s:e}");
        assert!(NewtonSqrt::<3>::sqrt_rsqrt(0.0f32).1.is_finite());
    }
}

#[test]
fn rsqrt_f64_lanes_equal_scalar_and_f32_lanes_meet_scalar_after_newton() {
    let xs: Vec<f64> = (0..4000)
        .map(|i| 10f64.powf(-37.0 + 74.0 * i as f64 / 4000.0))
        .collect();
    for chunk in xs.chunks(4) {
        let v = f64x4::from_fn(|i| chunk[i]);
        for (i, &x) in chunk.iter().enumerate() {
            assert_eq!(fast::rsqrt::<0, f64x4>(v).lane(i), fast::rsqrt::<0, f64>(x));
            assert_eq!(fast::rsqrt::<2, f64x4>(v).lane(i), fast::rsqrt::<2, f64>(x));
        }
    }
    let rows: Vec<[f64; 1]> = xs.iter().map(|&x| [x]).collect();
    let w = common::assert_lanes_match!("rsqrt<3>", ulp = 3, abs = 0.0, &rows, fn(x) {
        fast::rsqrt::<3, R>(x)
    });
    println!("rsqrt<3> lanes vs scalar: worst {w} ulp");
}

// ---------------------------------------------------------------------------------------
// SIMD lanes: pure arithmetic, so lanes equal scalars bit for bit where both sides fuse
// multiply-adds the same way (x86-64: always). Elsewhere allow a few ULP (amplified by |t|
// in pow).
// ---------------------------------------------------------------------------------------

const EXACT: bool = cfg!(any(target_arch = "x86_64", target_arch = "x86"));

#[test]
fn lanes_match_scalars() {
    let mut rows: Vec<[f64; 2]> = vec![];
    for i in 0..600 {
        let s = i as f64 / 600.0;
        rows.push([10f64.powf(-35.0 * s), 10f64.powf(-2.0 + 8.0 * s)]);
        rows.push([1.0 - 1e-7 * s, 1e4 * s]);
    }
    rows.extend([
        [0.0, 0.0],
        [0.0, 1.0],
        [1.0, 1e6],
        [1e-40, 0.5],
        [0.5, 1e6],
        [3.0, 100.0],
        [1.0, 0.0],
    ]);
    let (u1, u2) = if EXACT { (0, 0) } else { (4, 400) };
    let w = common::assert_lanes_match!("exp2<5>", ulp = u1, abs = 0.0, &rows, fn(x, y) {
        fast::exp2::<5, R>(-y * x - x)
    });
    println!("exp2<5> worst {w} ulp");
    let w = common::assert_lanes_match!("exp2<8>", ulp = u1, abs = 0.0, &rows, fn(x, y) {
        fast::exp2::<8, R>(y * R::from_f64(0.01) - x * R::from_f64(2000.0))
    });
    println!("exp2<8> worst {w} ulp");
    let w = common::assert_lanes_match!("log2<3,9,12>", ulp = u1, abs = 0.0, &rows, fn(x, y) {
        fast::log2::<3, R>(x) + fast::log2::<9, R>(y) * R::from_f64(0.5) - fast::log2::<12, R>(x + y)
    });
    println!("log2 worst {w} ulp");
    let w = common::assert_lanes_match!("pow<9,5>", ulp = u2, abs = 0.0, &rows, fn(x, y) {
        fast::pow::<9, 5, R>(x, y)
    });
    println!("pow<9,5> worst {w} ulp");
    let w = common::assert_lanes_match!("pow_phong", ulp = u2, abs = 0.0, &rows, fn(x, y) {
        fast::pow_phong(x, y) + fast::pow::<4, 2, R>(x, y)
    });
    println!("pow_phong worst {w} ulp");
}

// ---------------------------------------------------------------------------------------
// recip
// ---------------------------------------------------------------------------------------

/// Bounds of recip::<N> from the error recurrence `δ₀ = 2e + e²` (`e` the rsqrt estimate's
/// bound above), `δ_{k+1} = δ_k²`, plus three roundings of `f32` (`3·2⁻²⁴ ≈ 1.8e-7`) once
/// the recurrence is below that.
const RECIP_BITS_F32: [f64; 4] = [7.0e-2, 4.9e-3, 2.4e-5, 1.8e-7];
const RECIP_HW_F32: [f64; 4] = [7.34e-4, 5.4e-7, 1.8e-7, 1.8e-7];

fn recip_worst<R: Real>(n: usize, mut each: impl FnMut(R) -> R) -> f64
where
    R::Scalar: Scalar,
{
    // Every f32 bit pattern in [1, 4) (the rsqrt start is periodic under x → 4x, its square
    // under x → 4x as well), then the extremes of the models' denominators.
    let mut xs: Vec<f64> = (0x3F80_0000u32..0x4080_0000)
        .step_by(n)
        .map(|b| f32::from_bits(b) as f64)
        .collect();
    xs.extend([f32::MIN_POSITIVE as f64, 1e-30, 1e30, 1e36, 0.3, 7.0]);
    let mut w = 0.0f64;
    for chunk in xs.chunks(R::LANES) {
        let x = R::from_fn(|i| <R::Scalar as Scalar>::of(chunk[i.min(chunk.len() - 1)]));
        let y = each(x);
        for (i, &xd) in chunk.iter().enumerate() {
            let yd: f64 = y.lane(i).into();
            w = w.max((yd * xd - 1.0).abs());
        }
    }
    w
}

/// `fast::recip::<N>` within the bound of its recurrence on every `f32` in [1, 4) and at the
/// extremes, on the bit-trick start (`f32`, `F32Fma`: what the batch kernels run) and the
/// hardware start (`f32` lanes); finite below the normal range.
#[test]
fn recip_within_bounds() {
    use brdf::real::F32Fma;
    macro_rules! row {
        ($t:ty, $stride:expr, $bounds:expr) => {{
            let w = [
                recip_worst::<$t>($stride, fast::recip::<0, $t>),
                recip_worst::<$t>($stride, fast::recip::<1, $t>),
                recip_worst::<$t>($stride, fast::recip::<2, $t>),
                recip_worst::<$t>($stride, fast::recip::<3, $t>),
            ];
            println!(
                "recip {:>6}: N=0..3 {:?}",
                stringify!($t),
                w.map(|v| format!("{v:.3e}"))
            );
            for n in 0..4 {
                assert!(w[n] <= $bounds[n], "{} N={n}: {:e}", stringify!($t), w[n]);
            }
        }};
    }
    row!(f32, 1, RECIP_BITS_F32);
    row!(F32Fma, 1, RECIP_BITS_F32);
    row!(f32x8, 3, RECIP_HW_F32);
    row!(f32x16, 3, RECIP_HW_F32);
    for x in [0.0f32, 1e-40] {
        assert!(fast::recip::<3, f32>(x).is_finite());
        assert!(fast::recip::<3, f32x8>(f32x8::splat(x)).lane(2).is_finite());
    }
}

/// `NewtonSqrtRecip<3, 3>` on Cook-Torrance GGX and on the exact conductor, against the exact
/// policy, on `f32` and `F32Fma` (the batch kernels' form): within 16 ULP (`2⁻²⁴·16`
/// relative, i.e. ~1e-6) over a grid of directions, and 0 below the horizon.
#[test]
fn newton_sqrt_recip_models_within_16_ulp() {
    use brdf::fast::NewtonSqrtRecip;
    use brdf::fresnel::{Conductor, Schlick};
    use brdf::ior::Preset;
    use brdf::masking::{SmithHeightCorrelated, SmithSeparable};
    use brdf::models::CookTorrance;
    use brdf::ndf::GgxIsotropic;
    use brdf::real::{F32Fma, Splat};
    use brdf::{Brdf, Vec3};
    type Fast = NewtonSqrtRecip<3, 3>;
    let bound = 16.0 * f64::from(f32::EPSILON) / 2.0;
    let dir = |t: f32, p: f32| Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
    fn worst<const N: usize, R: Real<Scalar = f32, Mask = bool>>(
        a: &impl Brdf<R, N>,
        b: &impl Brdf<R, N>,
        pairs: &[(Vec3<f32>, Vec3<f32>)],
    ) -> f64 {
        let mut w = 0.0f64;
        for &(i, o) in pairs {
            let v = |d: Vec3<f32>| Vec3::new(R::splat(d.x), R::splat(d.y), R::splat(d.z));
            let (x, y) = (a.eval(v(i), v(o)), b.eval(v(i), v(o)));
            for c in 0..N {
                let (x, y) = (f64::from(x[c].lane(0)), f64::from(y[c].lane(0)));
                assert!(y.is_finite());
                if x == 0.0 {
                    assert_eq!(y, 0.0);
                } else {
                    w = w.max((y / x - 1.0).abs());
                }
            }
        }
        w
    }
    let mut pairs = Vec::new();
    for a in 0..24 {
        for b in 0..24 {
            for p in 0..8 {
                let ti = -0.05 + 1.62 * a as f32 / 23.0;
                let to = -0.05 + 1.62 * b as f32 / 23.0;
                pairs.push((dir(ti, 0.0), dir(to, 0.8 * p as f32)));
            }
        }
    }
    for alpha in [0.01f32, 0.3, 1.0] {
        let ggx = CookTorrance::new(
            GgxIsotropic::<f32>::new(alpha).unwrap(),
            Schlick::<f32, 1>::new([0.04]).unwrap(),
            SmithHeightCorrelated,
        );
        let fast = ggx.with_sqrt::<Fast>();
        let gold = Conductor::<f32, 3>::from_preset(Preset::Gold).unwrap();
        let rough = CookTorrance::new(
            GgxIsotropic::<f32>::new(alpha).unwrap(),
            gold,
            SmithSeparable,
        );
        let rough_fast = CookTorrance::new(
            GgxIsotropic::<f32>::new(alpha).unwrap(),
            gold.with_policy::<Fast>(),
            SmithSeparable,
        )
        .with_sqrt::<Fast>();
        let w = [
            worst::<1, f32>(&ggx, &fast, &pairs),
            worst::<1, F32Fma>(&ggx.splat::<F32Fma>(), &fast.splat::<F32Fma>(), &pairs),
            worst::<3, f32>(&rough, &rough_fast, &pairs),
            worst::<3, F32Fma>(
                &rough.splat::<F32Fma>(),
                &rough_fast.splat::<F32Fma>(),
                &pairs,
            ),
        ];
        println!(
            "alpha {alpha}: GGX f32, F32Fma; conductor f32, F32Fma: {:?}",
            w.map(|v| format!("{v:.3e}"))
        );
        for v in w {
            assert!(v <= bound, "alpha {alpha}: {v:e} > {bound:e}");
        }
    }
}
