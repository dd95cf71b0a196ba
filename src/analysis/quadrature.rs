//! Adaptive Gauss–Kronrod (7, 15) quadrature on fixed-size stack storage (no allocation).
//!
//! The 15-point Kronrod rule extends the 7-point Gauss–Legendre rule; `|K15 − G7|`, scaled by
//! QUADPACK's heuristic and never below itself (see `gk15`), is the error estimate of a
//! panel. The adaptive driver bisects the panel with the largest estimate until the summed
//! estimate meets the tolerance or the panel budget is spent (the "globally adaptive"
//! strategy of QUADPACK's `qag`).
//!
//! References: A. S. Kronrod, *Nodes and Weights of Quadrature Formulas*, Consultants Bureau,
//! 1965; R. Piessens, E. de Doncker-Kapenga, C. W. Überhuber, D. K. Kahaner, *QUADPACK: A
//! Subroutine Package for Automatic Integration*, Springer, 1983 (the node and weight values).

/// Abscissae of the 15-point Kronrod rule on `[−1, 1]` (non-negative half, descending).
/// Odd indices (1, 3, 5, 7) are the nodes of the 7-point Gauss–Legendre rule.
#[allow(clippy::excessive_precision)] // published digits, kept verbatim for checking
pub(crate) const XGK: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];

/// Weights of the 15-point Kronrod rule, matching [`XGK`].
#[allow(clippy::excessive_precision)]
pub(crate) const WGK: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];

/// Weights of the 7-point Gauss–Legendre rule at `XGK[1]`, `XGK[3]`, `XGK[5]`, `XGK[7]`.
#[allow(clippy::excessive_precision)]
pub(crate) const WG: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// Largest number of panels one adaptive integration keeps (stack storage).
pub(crate) const MAX_PANELS: usize = 128;

/// Result of a (possibly nested) integration: value per channel, error estimate (max over
/// channels, absolute) and the number of integrand evaluations at the innermost level.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Quad<const N: usize> {
    pub(crate) value: [f64; N],
    pub(crate) error: f64,
    pub(crate) evaluations: u64,
}

impl<const N: usize> Quad<N> {
    pub(crate) const ZERO: Self = Self {
        value: [0.0; N],
        error: 0.0,
        evaluations: 0,
    };
}

#[derive(Clone, Copy)]
struct Panel<const N: usize> {
    a: f64,
    b: f64,
    value: [f64; N],
    error: f64,
    splittable: bool,
}

/// One Gauss–Kronrod (7, 15) panel. The integrand returns its own value, the error of that
/// value (non-zero when it is itself an integral) and its evaluation count; the panel error is
/// `max_c E_c + Σ wₖ·errₖ` (the propagated inner error), with `E_c` QUADPACK's `qk15`
/// estimate of channel `c` (Piessens et al. 1983, §3.2).
fn gk15<const N: usize>(f: &mut impl FnMut(f64) -> Quad<N>, a: f64, b: f64) -> (Quad<N>, bool) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let mut k = [0.0; N];
    let mut g = [0.0; N];
    let mut inner_err = 0.0;
    let mut evaluations = 0;
    // Integrand values: fs[j] at c − h·XGK[j], fs[8 + j] at c + h·XGK[j] (fs[7] at c).
    let mut fs = [[0.0; N]; 15];
    let mut add = |x: f64, wk: f64, wg: f64| {
        let q = f(x);
        for ch in 0..N {
            k[ch] += wk * q.value[ch];
            g[ch] += wg * q.value[ch];
        }
        inner_err += wk * q.error;
        evaluations += q.evaluations;
        q.value
    };
    fs[7] = add(c, WGK[7], WG[3]);
    for j in 0..7 {
        let wg = if j % 2 == 1 { WG[j / 2] } else { 0.0 };
        fs[j] = add(c - h * XGK[j], WGK[j], wg);
        fs[8 + j] = add(c + h * XGK[j], WGK[j], wg);
    }
    // QUADPACK's qk15 error heuristic: with `resasc = ∫|f − mean|` over the panel, the raw
    // `|K15 − G7|` becomes `resasc · min(1, (200 |K15 − G7| / resasc)^1.5)` — larger than the
    // raw difference wherever that difference is not yet tiny against the integrand's
    // variation, which is where G7 and K15 can agree by accident on an unresolved peak.
    // QUADPACK lets it fall below the raw difference (by `2828 √(raw/resasc)` when
    // `raw < 1.25e-7 resasc`), which presumes K15 far more accurate than G7: true on smooth
    // panels, not on a panel with a kink inside, where both rules err by O(h²). Floored at
    // the raw difference, a small kink inside a panel is underestimated by at most ~75×
    // instead of a factor growing like 1/√amplitude (test `a_kink_needs_a_panel_edge`);
    // only an edge on the kink makes the estimate a bound, which is why the albedo
    // integrator puts edges on the kinks it knows. Measured cost of the floor: +0.002 %
    // evaluations over every model of the crate.
    let mut err = 0.0f64;
    let mut value = [0.0; N];
    for ch in 0..N {
        value[ch] = k[ch] * h;
        let mean = 0.5 * k[ch];
        let mut resasc = WGK[7] * (fs[7][ch] - mean).abs();
        for j in 0..7 {
            resasc += WGK[j] * ((fs[j][ch] - mean).abs() + (fs[8 + j][ch] - mean).abs());
        }
        let raw = ((k[ch] - g[ch]) * h).abs();
        let resasc = resasc * h.abs();
        let e = if resasc > 0.0 && raw > 0.0 {
            (resasc * crate::math::f64m::pow(200.0 * raw / resasc, 1.5).min(1.0)).max(raw)
        } else {
            raw
        };
        err = err.max(e);
    }
    // A panel narrower than a few ulps of its position cannot be refined further.
    let splittable = (c + 0.5 * h != c) && (c - 0.5 * h != c) && h > 0.0;
    let error = err + inner_err * h.abs();
    let error = if error.is_finite() {
        error
    } else {
        f64::INFINITY
    };
    (
        Quad {
            value,
            error,
            evaluations,
        },
        splittable,
    )
}

/// Globally adaptive GK15 integration of `f` over the sorted `breaks` (initial panel edges).
///
/// Every initial interval is integrated (the whole domain is always covered); refinement then
/// stops when the summed error estimate is `≤ tol`, when `max_panels` (≤ [`MAX_PANELS`])
/// panels exist, or when no panel can be split further. Zero-width intervals are skipped.
pub(crate) fn adaptive<const N: usize>(
    mut f: impl FnMut(f64) -> Quad<N>,
    breaks: &[f64],
    tol: f64,
    max_panels: usize,
) -> Quad<N> {
    let initial = breaks.windows(2).filter(|w| w[1] > w[0]).count();
    debug_assert!(initial <= MAX_PANELS);
    let cap = max_panels.clamp(initial.max(1), MAX_PANELS);
    let mut panels = [Panel {
        a: 0.0,
        b: 0.0,
        value: [0.0; N],
        error: 0.0,
        splittable: false,
    }; MAX_PANELS];
    let mut n = 0;
    let mut evaluations = 0;
    for w in breaks.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b <= a || n == MAX_PANELS {
            continue;
        }
        let (q, splittable) = gk15(&mut f, a, b);
        evaluations += q.evaluations;
        panels[n] = Panel {
            a,
            b,
            value: q.value,
            error: q.error,
            splittable,
        };
        n += 1;
    }
    loop {
        let total: f64 = panels[..n].iter().map(|p| p.error).sum();
        if total <= tol || n >= cap {
            break;
        }
        // Worst splittable panel.
        let mut worst = usize::MAX;
        let mut worst_err = -1.0;
        for (i, p) in panels[..n].iter().enumerate() {
            if p.splittable && p.error > worst_err {
                worst = i;
                worst_err = p.error;
            }
        }
        if worst == usize::MAX {
            break;
        }
        let Panel { a, b, .. } = panels[worst];
        let m = 0.5 * (a + b);
        let (ql, sl) = gk15(&mut f, a, m);
        let (qr, sr) = gk15(&mut f, m, b);
        evaluations += ql.evaluations + qr.evaluations;
        panels[worst] = Panel {
            a,
            b: m,
            value: ql.value,
            error: ql.error,
            splittable: sl,
        };
        panels[n] = Panel {
            a: m,
            b,
            value: qr.value,
            error: qr.error,
            splittable: sr,
        };
        n += 1;
    }
    let mut value = [0.0; N];
    let mut error = 0.0;
    for p in &panels[..n] {
        for (v, pv) in value.iter_mut().zip(p.value) {
            *v += pv;
        }
        error += p.error;
    }
    Quad {
        value,
        error,
        evaluations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::{println, vec::Vec};

    fn leaf(v: f64) -> Quad<1> {
        Quad {
            value: [v],
            error: 0.0,
            evaluations: 1,
        }
    }

    /// K15 is exact for polynomials of degree ≤ 23 (3n + 2, n = 7 odd), G7 for degree ≤ 13:
    /// checks the tables digit for digit (a wrong digit breaks exactness).
    #[test]
    fn rules_are_exact_for_their_polynomial_degrees() {
        for deg in 0..=24u32 {
            let exact = if deg % 2 == 1 {
                0.0
            } else {
                2.0 / f64::from(deg + 1)
            };
            let mut k = WGK[7] * if deg == 0 { 1.0 } else { 0.0 };
            let mut g = WG[3] * if deg == 0 { 1.0 } else { 0.0 };
            for j in 0..7 {
                let p = XGK[j].powi(deg as i32) * (1.0 + if deg % 2 == 0 { 1.0 } else { -1.0 });
                k += WGK[j] * p;
                if j % 2 == 1 {
                    g += WG[j / 2] * p;
                }
            }
            if deg <= 23 {
                assert!(
                    (k - exact).abs() < 2e-15,
                    "K15 degree {deg}: {k} vs {exact}"
                );
            } else {
                assert!(
                    (k - exact).abs() > 1e-12,
                    "K15 should not be exact at degree 24"
                );
            }
            if deg <= 13 {
                assert!((g - exact).abs() < 2e-15, "G7 degree {deg}: {g} vs {exact}");
            } else if deg == 14 {
                assert!(
                    (g - exact).abs() > 1e-6,
                    "G7 should not be exact at degree 14"
                );
            }
        }
    }

    /// QUADPACK's `qk15` estimate of `∫ₐᵇ f` from the same nodes, without the floor.
    fn quadpack_estimate(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        let fs: Vec<f64> = (0..15)
            .map(|j| match j {
                7 => f(c),
                j if j < 7 => f(c - h * XGK[j]),
                j => f(c + h * XGK[j - 8]),
            })
            .collect();
        let (mut k, mut g) = (WGK[7] * fs[7], WG[3] * fs[7]);
        for j in 0..7 {
            k += WGK[j] * (fs[j] + fs[8 + j]);
            if j % 2 == 1 {
                g += WG[j / 2] * (fs[j] + fs[8 + j]);
            }
        }
        let mean = 0.5 * k;
        let mut resasc = WGK[7] * (fs[7] - mean).abs();
        for j in 0..7 {
            resasc += WGK[j] * ((fs[j] - mean).abs() + (fs[8 + j] - mean).abs());
        }
        let (raw, resasc) = (((k - g) * h).abs(), resasc * h);
        resasc * (200.0 * raw / resasc).powf(1.5).min(1.0)
    }

    /// Why the albedo integrator puts panel edges on the kinks it knows: a kink `a|x − c|`
    /// inside a panel, on the smooth `x²`, defeats every estimate made from the panel's nodes
    /// (K15 and G7 both err by O(h²) there). QUADPACK's estimate then falls short of the
    /// error by a factor growing like `1/√a` (1.7·10⁵× at `a = 1e-9`, measured); floored at
    /// `|K15 − G7|` by at most ~75× at any amplitude; with an edge at `c` the estimate bounds
    /// the error.
    #[test]
    fn a_kink_needs_a_panel_edge() {
        for amp in [1e-9, 1e-7, 1e-5, 1e-3, 1e-1] {
            let (mut floored, mut quadpack) = (0.0f64, 0.0f64);
            for k in 0..2000 {
                // Interior positions (between the outermost nodes and the ends every rule on
                // these nodes is blind to the kink).
                let c = 0.005 + 0.99 * (f64::from(k) + 0.5) / 2000.0;
                let f = |x: f64| x * x + amp * (x - c).abs();
                let exact = 1.0 / 3.0 + amp * (c * c + (1.0 - c) * (1.0 - c)) / 2.0;
                let (q, _) = gk15(&mut |x| leaf(f(x)), 0.0, 1.0);
                let err = (q.value[0] - exact).abs();
                floored = floored.max(err / q.error);
                quadpack = quadpack.max(err / quadpack_estimate(f, 0.0, 1.0));
                let q = adaptive(|x| leaf(f(x)), &[0.0, c, 1.0], 1e-12, 128);
                let err = (q.value[0] - exact).abs();
                assert!(
                    err <= q.error.max(4e-16),
                    "edge at {c}: {err:e} > {:e}",
                    q.error
                );
            }
            println!("amp {amp:e}: floored {floored:.1} quadpack {quadpack:.1}");
            assert!(floored > 1.0 && floored < 100.0, "amp {amp}: {floored}");
            if amp < 1e-3 {
                assert!(quadpack > 500.0, "amp {amp}: {quadpack}");
            }
        }
    }

    #[test]
    fn adaptive_resolves_a_sharp_peak_and_a_kink() {
        // ∫₀¹ 1/(ε² + x²) dx = atan(1/ε)/ε, peak of width ε at the left edge.
        let eps = 1e-4;
        let q = adaptive(|x| leaf(1.0 / (eps * eps + x * x)), &[0.0, 1.0], 1e-8, 128);
        let exact = (1.0 / eps).atan() / eps;
        assert!(
            (q.value[0] - exact).abs() < 1e-6 * exact,
            "{} vs {exact}",
            q.value[0]
        );
        // |x − 1/3| on [0, 1]: a kink inside a panel.
        let q = adaptive(|x| leaf((x - 1.0 / 3.0).abs()), &[0.0, 1.0], 1e-12, 128);
        let exact = (1.0 / 9.0 + 4.0 / 9.0) / 2.0;
        assert!((q.value[0] - exact).abs() < 1e-11, "{}", q.value[0]);
        assert!(q.error <= 1e-12);
    }
}
