//! χ² goodness-of-fit test of a direction sampler against its density, as pbrt-v4's and
//! Mitsuba 3's sampling tests run it: a (θ, φ) histogram of samples, expected counts from an
//! adaptive quadrature of the density over each cell, cells with expected count < 5 pooled,
//! and the p-value of Pearson's statistic compared with a Šidák-corrected significance level.
//! The test also fails if a sample lands in a cell whose integrated density is exactly zero,
//! or below the horizon.

use brdf::{SampleBrdf, Vec3};
use std::f64::consts::PI;

/// SplitMix64 (Steele, Lea, Flood 2014): a small, well-mixed generator for reproducible tests.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1), 53 bits.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    pub fn u3(&mut self) -> [f64; 3] {
        [self.uniform(), self.uniform(), self.uniform()]
    }
}

/// Histogram resolution and sample count.
#[derive(Clone, Copy, Debug)]
pub struct Chi2Config {
    pub theta_bins: usize,
    pub phi_bins: usize,
    pub samples: usize,
    pub seed: u64,
}

impl Chi2Config {
    /// 10⁶ samples over 16 × 32 cells of the upper hemisphere (uniform in θ and φ).
    pub const DEFAULT: Self = Self {
        theta_bins: 16,
        phi_bins: 32,
        samples: 1_000_000,
        seed: 7,
    };
}

/// What a run measured.
#[derive(Clone, Debug)]
pub struct Chi2Outcome {
    /// p-value of Pearson's statistic (probability of a statistic at least this large).
    pub p_value: f64,
    /// Degrees of freedom after pooling.
    pub dof: usize,
    /// ∫ pdf over the upper hemisphere (quadrature).
    pub integral: f64,
    /// Fraction of samples the sampler flagged invalid.
    pub invalid_fraction: f64,
}

fn cell_of(w: Vec3<f64>, cfg: &Chi2Config) -> (usize, usize) {
    let theta = w.z.clamp(-1.0, 1.0).acos();
    let mut phi = w.y.atan2(w.x);
    if phi < 0.0 {
        phi += 2.0 * PI;
    }
    let t = ((theta / (0.5 * PI)) * cfg.theta_bins as f64) as usize;
    let p = ((phi / (2.0 * PI)) * cfg.phi_bins as f64) as usize;
    (t.min(cfg.theta_bins - 1), p.min(cfg.phi_bins - 1))
}

const GL4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

fn gl_cell(f: &dyn Fn(f64, f64) -> f64, t0: f64, t1: f64, p0: f64, p1: f64) -> f64 {
    let (tc, th) = (0.5 * (t0 + t1), 0.5 * (t1 - t0));
    let (pc, ph) = (0.5 * (p0 + p1), 0.5 * (p1 - p0));
    let mut s = 0.0;
    for (xt, wt) in GL4 {
        for (xp, wp) in GL4 {
            s += wt * wp * f(tc + th * xt, pc + ph * xp);
        }
    }
    s * th * ph
}

/// Adaptive 4 × 4 Gauss-Legendre over the cell `[t0, t1] × [p0, p1]`: a cell is split in four
/// until the split changes the result (`whole`, the unsplit value) by less than `tol` (or
/// `depth` runs out).
fn adaptive(f: &dyn Fn(f64, f64) -> f64, cell: [f64; 4], whole: f64, tol: f64, depth: u32) -> f64 {
    let [t0, t1, p0, p1] = cell;
    let (tm, pm) = (0.5 * (t0 + t1), 0.5 * (p0 + p1));
    let quarters = [
        [t0, tm, p0, pm],
        [tm, t1, p0, pm],
        [t0, tm, pm, p1],
        [tm, t1, pm, p1],
    ];
    let parts = quarters.map(|[a, b, c, d]| gl_cell(f, a, b, c, d));
    let sum: f64 = parts.iter().sum();
    if depth == 0 || (sum - whole).abs() <= tol {
        return sum;
    }
    quarters
        .iter()
        .zip(parts)
        .map(|(q, part)| adaptive(f, *q, part, 0.25 * tol, depth - 1))
        .sum()
}

/// ∫ pdf over each (θ, φ) cell of the upper hemisphere, row-major in θ.
pub fn cell_integrals(pdf: &dyn Fn(Vec3<f64>) -> f64, cfg: &Chi2Config) -> Vec<f64> {
    let f = |theta: f64, phi: f64| {
        let (s, c) = theta.sin_cos();
        let w = Vec3::new(s * phi.cos(), s * phi.sin(), c);
        pdf(w) * s
    };
    let dt = 0.5 * PI / cfg.theta_bins as f64;
    let dp = 2.0 * PI / cfg.phi_bins as f64;
    let mut out = Vec::with_capacity(cfg.theta_bins * cfg.phi_bins);
    for i in 0..cfg.theta_bins {
        for j in 0..cfg.phi_bins {
            let (t0, p0) = (i as f64 * dt, j as f64 * dp);
            let whole = gl_cell(&f, t0, t0 + dt, p0, p0 + dp);
            out.push(adaptive(&f, [t0, t0 + dt, p0, p0 + dp], whole, 1e-10, 9));
        }
    }
    out
}

/// ln Γ(x) for x > 0 (Lanczos, g = 7, n = 9; |relative error| < 1e-14).
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Regularized upper incomplete gamma Q(a, x) = Γ(a, x)/Γ(a): the series of P for
/// x < a + 1, the continued fraction of Q (modified Lentz) otherwise.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let front = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut term, mut sum, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..100_000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        1.0 - sum * front
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..100_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        front * h
    }
}

/// Šidák-corrected significance for one of `tests` tests at family-wise level `alpha`.
pub fn sidak(alpha: f64, tests: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / tests as f64)
}

/// Draws `cfg.samples` directions with `sample` (None: an invalid sample) and compares their
/// histogram with `pdf`. Errors if a valid sample is below the horizon or not finite, or
/// lands in a cell of zero integrated density.
pub fn chi2(
    sample: &mut dyn FnMut([f64; 3]) -> Option<Vec3<f64>>,
    pdf: &dyn Fn(Vec3<f64>) -> f64,
    cfg: &Chi2Config,
) -> Result<Chi2Outcome, String> {
    let cells = cfg.theta_bins * cfg.phi_bins;
    let mut observed = vec![0u64; cells];
    let mut rng = Rng::new(cfg.seed);
    let mut invalid = 0usize;
    for _ in 0..cfg.samples {
        match sample(rng.u3()) {
            None => invalid += 1,
            Some(w) => {
                if !(w.z > 0.0 && w.x.is_finite() && w.y.is_finite()) {
                    return Err(format!(
                        "valid sample below the horizon or not finite: {w:?}"
                    ));
                }
                let (t, p) = cell_of(w, cfg);
                observed[t * cfg.phi_bins + p] += 1;
            }
        }
    }
    let integrals = cell_integrals(pdf, cfg);
    let integral: f64 = integrals.iter().sum();
    let n = cfg.samples as f64;
    let mut cells_sorted: Vec<(f64, u64)> = integrals
        .iter()
        .map(|q| q * n)
        .zip(observed.iter().copied())
        .collect();
    for &(e, o) in &cells_sorted {
        if e == 0.0 && o > 0 {
            return Err(format!("{o} samples in a cell of zero density"));
        }
    }
    cells_sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut stat, mut dof) = (0.0, 0usize);
    let (mut pool_e, mut pool_o) = (0.0, 0.0);
    for &(e, o) in &cells_sorted {
        if e < 5.0 {
            pool_e += e;
            pool_o += o as f64;
        } else {
            stat += (o as f64 - e).powi(2) / e;
            dof += 1;
        }
    }
    if pool_e > 0.0 {
        stat += (pool_o - pool_e).powi(2) / pool_e;
        dof += 1;
    }
    let dof = dof.saturating_sub(1).max(1);
    Ok(Chi2Outcome {
        p_value: gamma_q(dof as f64 / 2.0, stat / 2.0),
        dof,
        integral,
        invalid_fraction: invalid as f64 / n,
    })
}

/// χ² of `model`'s sampler at `wo` on `cfg`'s histogram (at the Šidák-corrected 1 % level
/// for `tests` tests), plus: ∫pdf ≤ 1 + 1e-4 and = 1 − invalid fraction (within 4σ of the
/// binomial estimate + 1e-4), `sample().pdf == pdf()` to 1e-6 relative, the sample's `f`
/// equal to `eval` within `f_rel` relative (0: bit for bit) and `weight == f cos θi / pdf`
/// to 1e-5 relative on every sample, invalid samples with zero pdf and weight. Returns the
/// invalid fraction.
pub fn check_sampler<const N: usize, M: SampleBrdf<f64, N>>(
    name: &str,
    model: &M,
    wo: Vec3<f64>,
    cfg: &Chi2Config,
    tests: usize,
    f_rel: f64,
) -> f64 {
    let mut worst_pdf: f64 = 0.0;
    let mut worst_weight: f64 = 0.0;
    let out = chi2(
        &mut |u| {
            let s = model.sample(wo, u);
            if !s.valid {
                assert_eq!(s.pdf, 0.0, "{name}: invalid sample with pdf");
                assert!(
                    s.weight.iter().all(|w| *w == 0.0),
                    "{name}: invalid sample with weight"
                );
                return None;
            }
            let p = model.pdf(wo, s.wi);
            worst_pdf = worst_pdf.max((s.pdf - p).abs() / p);
            let f = model.eval(s.wi, wo);
            for ((&sf, &ef), &sw) in s.f.iter().zip(&f).zip(&s.weight) {
                let rel_f = (sf - ef).abs() / ef.abs().max(1e-300);
                assert!(
                    rel_f <= f_rel,
                    "{name}: sample's f {sf:e} differs from eval {ef:e}"
                );
                let w = ef * s.wi.z / s.pdf;
                if w != 0.0 {
                    worst_weight = worst_weight.max((sw - w).abs() / w.abs());
                }
                assert!(sw.is_finite(), "{name}: weight {:?}", s.weight);
            }
            Some(s.wi)
        },
        &|wi| model.pdf(wo, wi),
        cfg,
    )
    .unwrap_or_else(|e| panic!("{name} at {wo:?}: {e}"));
    let level = sidak(0.01, tests);
    assert!(
        out.p_value > level,
        "{name} at {wo:?}: χ² rejected, p = {:e} < {level:e} ({out:?})",
        out.p_value
    );
    let valid = 1.0 - out.invalid_fraction;
    let sigma = (valid * (1.0 - valid) / cfg.samples as f64).sqrt();
    assert!(
        out.integral <= 1.0 + 1e-4,
        "{name}: ∫pdf = {}",
        out.integral
    );
    assert!(
        (out.integral - valid).abs() <= 4.0 * sigma + 1e-4,
        "{name} at {wo:?}: ∫pdf = {} but {valid} of the samples are valid",
        out.integral
    );
    assert!(
        worst_pdf <= 1e-6,
        "{name}: sample().pdf vs pdf(): {worst_pdf:e}"
    );
    assert!(
        worst_weight <= 1e-5,
        "{name}: weight vs f cos/pdf: {worst_weight:e}"
    );
    out.invalid_fraction
}
