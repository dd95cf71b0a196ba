//! The directional albedo of the rough dielectric interface (`brdf::energy::dielectric_albedo`,
//! Walter et al. 2007, energy form of `f_t`): the smooth limit, the single-scattering bound,
//! the reciprocity of the transmitted averages, an independent quadrature over `wi` (a second,
//! denser rule on another formulation: it checks the Jacobian of the half-vector rule too)
//! and a Monte-Carlo estimate with the crate's visible-normal sampler.

use brdf::Vec3;
use brdf::energy::{
    DIELECTRIC_AVERAGE_TABLE_ALPHA, DIELECTRIC_AVERAGE_TABLE_ETA, dielectric_albedo,
    dielectric_albedo_split, dielectric_albedo_table, dielectric_albedo_table_node,
    dielectric_albedo_tables, dielectric_average_albedo, dielectric_average_albedo_split,
    dielectric_average_albedo_table, dielectric_average_albedo_table_node, dielectric_table,
    gauss_legendre,
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

/// Stored `E` nodes `(region, s, p, r)` and `E_avg` nodes `(inside, j, r)` equal the
/// generator's, bit for bit.
fn check_nodes(
    e_nodes: &[(dielectric_table::Region, usize, usize, usize)],
    avg_nodes: &[(bool, usize, usize)],
) {
    let (e, avg) = dielectric_albedo_tables();
    assert_eq!(e.len(), dielectric_table::Region::table_len());
    assert_eq!(
        avg.len(),
        2 * DIELECTRIC_AVERAGE_TABLE_ALPHA * (DIELECTRIC_AVERAGE_TABLE_ETA + 2)
    );
    for &(region, s, p, r) in e_nodes {
        let (n, m) = region.stored();
        let shipped = e[region.offset() + (s * n + p) * m + r];
        let now = dielectric_albedo_table_node(region, s, p, r);
        assert_eq!(
            shipped, now,
            "E node ({region:?}, {s}, {p}, {r}): shipped {shipped}, regenerated {now}: \
             run `cargo run --release -p brdf-tools --bin energy_tables -- --dielectric`"
        );
    }
    let row = DIELECTRIC_AVERAGE_TABLE_ETA + 2;
    for &(inside, j, r) in avg_nodes {
        let side = usize::from(inside);
        let shipped = avg[(side * DIELECTRIC_AVERAGE_TABLE_ALPHA + j) * row + r];
        let now = dielectric_average_albedo_table_node(inside, j, r);
        assert_eq!(
            shipped.to_bits(),
            now.to_bits(),
            "E_avg node (inside {inside}, {j}, {r}): shipped {shipped}, regenerated {now}"
        );
    }
}

/// A deterministic subset: in every region, interior nodes, ghosts and a corner ghost of the
/// first, a middle and the last roughness planes; `E_avg` at both ends of both sides.
#[test]
fn shipped_dielectric_tables_match_the_generator_on_a_subset() {
    let mut e_nodes = Vec::new();
    let last = dielectric_table::ALPHA_NODES + 1;
    for region in dielectric_table::Region::ALL {
        let (n, m) = region.stored();
        for s in [1, 14, last - 1] {
            for (p, r) in [
                (1, 1),
                (n / 2, m / 3),
                (n - 2, m - 2),
                (3, m - 4),
                (0, 5),
                (n - 1, 2),
            ] {
                e_nodes.push((region, s, p, r));
            }
        }
        e_nodes.push((region, 0, 4, 0));
        e_nodes.push((region, last, n - 1, m - 1));
    }
    let last = DIELECTRIC_AVERAGE_TABLE_ETA + 1;
    let avg_nodes = [
        (false, 0, 1),
        (false, 31, last),
        (true, 12, 0),
        (true, 31, 9),
    ];
    check_nodes(&e_nodes, &avg_nodes);
}

#[test]
#[ignore = "full regeneration (about 22 min of CPU in release, as `energy_tables -- --dielectric --check`); run with --ignored"]
fn shipped_dielectric_tables_match_the_generator_everywhere() {
    let (e, _) = dielectric_albedo_tables();
    for region in dielectric_table::Region::ALL {
        let planes: Vec<Vec<f64>> = (0..dielectric_table::ALPHA_NODES)
            .map(|j| dielectric_table::plane(region, j))
            .collect();
        let block = dielectric_table::block(region, &planes);
        let off = region.offset();
        assert!(
            e[off..off + block.len()] == block[..],
            "E block of {region:?} differs: run `cargo run --release -p brdf-tools --bin \
             energy_tables -- --dielectric`"
        );
    }
    let avg_nodes: Vec<_> = [false, true]
        .into_iter()
        .flat_map(|inside| {
            (0..DIELECTRIC_AVERAGE_TABLE_ALPHA).flat_map(move |j| {
                (0..DIELECTRIC_AVERAGE_TABLE_ETA + 2).map(move |r| (inside, j, r))
            })
        })
        .collect();
    check_nodes(&[], &avg_nodes);
}

/// `α` at roughness coordinate `t ∈ [0, 1]` (the inverse of `dielectric_table::roughness_axis`).
fn alpha_at(t: f64) -> f64 {
    let (mut lo, mut hi) = (1e-4_f64, 1.0_f64);
    for _ in 0..80 {
        let m = 0.5 * (lo + hi);
        if dielectric_table::roughness_axis(m) < t {
            lo = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo + hi)
}

/// The worst `|table − direct|` over `points` `(α, η, μ)`, and where.
fn worst_over(points: impl IntoIterator<Item = (f64, f64, f64)>) -> (f64, f64, f64, f64, usize) {
    let mut worst = (0.0, 0.0, 0.0, 0.0, 0);
    for (alpha, eta, mu) in points {
        let d = (dielectric_albedo_table(alpha, eta, mu)
            - dielectric_albedo(alpha, eta, mu).unwrap())
        .abs();
        if d > worst.0 {
            worst = (d, alpha, eta, mu, worst.4);
        }
        worst.4 += 1;
    }
    worst
}

/// The point at the fractions `f = (ft, fa, fb)` of cell `(j, i, k)` of `region` (roughness
/// cell `j`, in-region cell `(i, k)`), through the table's own inverse maps.
fn cell_point(
    region: dielectric_table::Region,
    j: usize,
    i: usize,
    k: usize,
    f: [f64; 3],
) -> (f64, f64, f64) {
    let (n, m) = region.nodes();
    let alpha = alpha_at((j as f64 + f[0]) / (dielectric_table::ALPHA_NODES - 1) as f64);
    let (eta, mu) = dielectric_table::inverse(
        region,
        alpha,
        (i as f64 + f[1]) / (n - 1) as f64,
        (k as f64 + f[2]) / (m - 1) as f64,
    );
    (alpha, eta, mu)
}

/// The near-`η = 1` grazing corner (where the former table was 0.25 off) and a deterministic
/// sample of cells of every region (at the full sweep's points, [`sweep_point`]): within
/// 1e-3. The corner points: `η = 1`, `1 ± 1e-6 … 1e-2` and the former worst `η = 1.067`, `μ`
/// from 0 (below the quadrature's clamp) to 0.05, four roughnesses from `1e-4` to 1.
#[test]
fn dielectric_table_interpolates_within_1e3_on_a_subset() {
    let mut points = Vec::new();
    for alpha in [1e-4, 2e-3, 0.12, 1.0] {
        for eta in [
            1.0,
            1.000_001,
            0.999_999,
            1.0001,
            0.9999,
            1.001,
            0.999,
            1.01,
            0.99,
            1.067,
            1.0 / 1.067,
        ] {
            for mu in [0.0, 1e-7, 2.8e-5, 1e-3, 0.05] {
                points.push((alpha, eta, mu));
            }
        }
    }
    points.push((0.12, 1.067, 2.8e-5));
    let corner = worst_over(points);
    report("η ≈ 1 at grazing", corner);
    let mut cells = Vec::new();
    for region in dielectric_table::Region::ALL {
        let (n, m) = region.nodes();
        for j in [0, 12, 25, dielectric_table::ALPHA_NODES - 2] {
            for (i, k) in [
                (0, 0),
                (1, m / 2),
                (n / 3, 1),
                (n / 2, m / 2),
                (n - 2, m - 2),
                (n - 2, 0),
            ] {
                cells.push(sweep_point(region, j, i, k));
            }
        }
    }
    let sample = worst_over(cells);
    report("sampled cells", sample);
    assert_within_1e3(corner);
    assert_within_1e3(sample);
}

/// SplitMix64 of an integer: the fixed pseudo-random offsets of the full sweep.
fn hash01(x: u64) -> f64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// The point of cell `(j, i, k)` of `region` that the sweeps test: a fixed pseudo-random
/// position inside the cell (centres alone miss the peaks of the Catmull-Rom error).
fn sweep_point(region: dielectric_table::Region, j: usize, i: usize, k: usize) -> (f64, f64, f64) {
    let id = (((region as u64 * 64 + j as u64) * 128 + i as u64) * 64 + k as u64) * 3;
    cell_point(
        region,
        j,
        i,
        k,
        [hash01(id), hash01(id + 1), hash01(id + 2)],
    )
}

/// Prints the worst point `w` of [`worst_over`] under `label`.
fn report(label: &str, w: (f64, f64, f64, f64, usize)) {
    eprintln!(
        "dielectric table, {label}: worst {:.3e} at α {} η {} μ {} ({} points)",
        w.0, w.1, w.2, w.3, w.4
    );
}

/// Asserts the worst point `w` of [`worst_over`] is within 1e-3.
fn assert_within_1e3(w: (f64, f64, f64, f64, usize)) {
    assert!(
        w.0 < 1e-3,
        "worst {:e} at α {} η {} μ {}",
        w.0,
        w.1,
        w.2,
        w.3
    );
}

/// Every cell of every region and roughness, one point per cell ([`sweep_point`]), within 1e-3;
/// the worst per region is printed.
#[test]
#[ignore = "full sweep, one quadrature per cell (about 10 min in release); run with --ignored"]
fn dielectric_table_interpolates_within_1e3_everywhere() {
    let mut worst_all = (0.0, 0.0, 0.0, 0.0, 0);
    for region in dielectric_table::Region::ALL {
        let (n, m) = region.nodes();
        let mut points = Vec::new();
        for j in 0..dielectric_table::ALPHA_NODES - 1 {
            for i in 0..n - 1 {
                for k in 0..m - 1 {
                    points.push(sweep_point(region, j, i, k));
                }
            }
        }
        let w = worst_over(points);
        report(&format!("{region:?}"), w);
        if w.0 > worst_all.0 {
            worst_all = w;
        }
    }
    assert_within_1e3(worst_all);
}

/// `E_avg` from the table against the direct average within 1e-3: near `η = 1` (where the
/// former linear IOR axis was 1.5e-2 off) and at cell centres of both axes.
#[test]
fn dielectric_average_table_interpolates_within_1e3() {
    let mut worst: (f64, f64, f64) = (0.0, 0.0, 0.0);
    for alpha in [0.003, 0.12, 0.5, 1.0] {
        for e in [1.0005, 1.01, 1.03, 1.067, 1.6] {
            for eta in [e, 1.0 / e] {
                let d = (dielectric_average_albedo_table(alpha, eta)
                    - dielectric_average_albedo(alpha, eta).unwrap())
                .abs();
                if d > worst.0 {
                    worst = (d, alpha, eta);
                }
            }
        }
    }
    eprintln!(
        "E_avg table: worst {:.3e} at α {} η {}",
        worst.0, worst.1, worst.2
    );
    assert!(worst.0 < 1e-3, "{worst:?}");
}

/// The lookup on `f32x8` lanes (the three regions, `η = 1`, grazing and clamped inputs mixed
/// in one vector) equals the scalar lookup lane by lane, bit for bit.
#[test]
fn dielectric_table_lanes_match_scalars() {
    let rows: [([f32; 8], [f32; 8], [f32; 8]); 2] = [
        (
            [1e-4, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0],
            [1.0, 1.5, 1.0 / 1.5, 3.0, 1.0 / 3.0, 2.2, 0.9, 1.2],
            [0.0, 0.05, 0.3, 0.5, 0.7, 0.9, 1.0, 0.2],
        ),
        (
            [0.12, 2e-3, 1.0, 0.3, 5e-5, 2.0, 0.05, 0.6],
            [1.067, 0.999_999, 0.6, 1.0, 1.000_001, 0.5, 4.0, 0.8],
            [2.8e-5, 1e-7, 0.99, 1.0, 0.0, 0.8, 0.3, -0.1],
        ),
    ];
    for (a, e, m) in rows {
        let v = dielectric_albedo_table(f32x8::from(a), f32x8::from(e), f32x8::from(m));
        let avg = dielectric_average_albedo_table(f32x8::from(a), f32x8::from(e));
        for l in 0..8 {
            assert_eq!(
                v.to_array()[l].to_bits(),
                dielectric_albedo_table(a[l], e[l], m[l]).to_bits(),
                "lane {l}"
            );
            assert_eq!(
                avg.to_array()[l].to_bits(),
                dielectric_average_albedo_table(a[l], e[l]).to_bits(),
                "lane {l}"
            );
        }
    }
}

/// Points just below and just above `mu` at `eta` lie in regions `lower` and `upper`, and
/// the lookup at roughness `alpha` is continuous across the boundary (within 1e-3).
fn assert_regions_meet(
    alpha: f64,
    eta: f64,
    (below, above): (f64, f64),
    lower: dielectric_table::Region,
    upper: dielectric_table::Region,
) {
    assert_eq!(dielectric_table::region_of(eta, below), lower);
    assert_eq!(dielectric_table::region_of(eta, above), upper);
    let jump = (dielectric_albedo_table(alpha, eta, below)
        - dielectric_albedo_table(alpha, eta, above))
    .abs();
    assert!(
        jump < 1e-3,
        "α {alpha} η {eta}: jump {jump:e} between {lower:?} and {upper:?}"
    );
}

/// The regions meet on the kink `sin θo = c`: the lookup is continuous across it (within the
/// interpolation error) and the region of a point follows its definition.
#[test]
fn dielectric_table_regions_meet_on_the_kink() {
    use dielectric_table::Region::{InsideGrazing, InsideNormal, InsideOblique};
    for (alpha, c) in [(0.05, 0.3), (0.5, 0.6), (1.0, 0.9)] {
        let eta = (1.0_f64 - c * c).sqrt();
        let mu_k = eta; // sin θo = c  ⇔  μ = √(1 − c²) = η
        let edges = (mu_k * (1.0 - 1e-9), (mu_k * (1.0 + 1e-9)).min(1.0));
        assert_regions_meet(alpha, eta, edges, InsideOblique, InsideNormal);
    }
    // The part below the kink is split at μ = 1/3, where its IOR range stops being c_max.
    for (alpha, eta) in [(0.002, 0.99), (0.3, 0.5), (1.0, 0.9)] {
        let edges = (1.0 / 3.0 - 1e-9, 1.0 / 3.0 + 1e-9);
        assert_regions_meet(alpha, eta, edges, InsideGrazing, InsideOblique);
    }
    assert_eq!(
        dielectric_table::region_of(1.5, 0.2),
        dielectric_table::Region::Outside
    );
    assert_eq!(
        dielectric_table::region_of(1.0, 0.0),
        dielectric_table::Region::Outside
    );
    assert!(
        dielectric_table::alpha_node(0) == 1e-4
            && dielectric_table::alpha_node(dielectric_table::ALPHA_NODES - 1) == 1.0
    );
}

/// `Φ±(ρ)` of `dielectric_table::corner_albedo` (closed forms, derived in its doc) against
/// the defining integrals, with `x = tan θ` (`x (1 + x²)^{−3/2} dx = sin θ dθ`):
/// `Φ₊ = ∫_0^{π/2} sin θ (sin θ + ρ cos θ)/(2 sin θ + ρ cos θ) dθ` and
/// `Φ₋ = ∫_{atan ρ}^{π/2} sin θ (sin θ − ρ cos θ)/(2 sin θ − ρ cos θ) dθ`, by Simpson's rule
/// (an independent formulation: no logarithm, no closed form).
#[test]
fn corner_albedo_matches_its_defining_integral() {
    let simpson = |a: f64, b: f64, f: &dyn Fn(f64) -> f64| {
        let n = 20_000;
        let h = (b - a) / n as f64;
        let mut sum = f(a) + f(b);
        for i in 1..n {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(a + h * i as f64);
        }
        sum * h / 3.0
    };
    let half_pi = std::f64::consts::FRAC_PI_2;
    let mut worst: f64 = 0.0;
    for rho in [1e-4, 0.01, 0.1, 0.5, 1.0, 2.0, 5.0, 20.0, 100.0, 1e4] {
        let out = simpson(0.0, half_pi, &|t: f64| {
            let (s, c) = t.sin_cos();
            s * (s + rho * c) / (2.0 * s + rho * c)
        });
        let inn = simpson(rho.atan(), half_pi, &|t: f64| {
            let (s, c) = t.sin_cos();
            s * (s - rho * c) / (2.0 * s - rho * c)
        });
        let got_out = dielectric_table::corner_albedo(rho, false);
        let got_in = dielectric_table::corner_albedo(rho, true);
        for (got, want, side) in [(got_out, out, "outside"), (got_in, inn, "inside")] {
            assert!(
                (got - want).abs() < 1e-6,
                "ρ {rho} {side}: closed form {got}, integral {want}"
            );
            worst = worst.max((got - want).abs());
        }
    }
    eprintln!("corner albedo Φ± against its integral: worst {worst:.2e}");
}

/// The corner is the grazing limit of the quadrature: at `μ = 1e-6` (the quadrature's clamp)
/// and `η` with `ρ = c²/(2αμ)` fixed, `dielectric_albedo` equals `Φ(ρ)` up to its `O(μ/α)`
/// and `O(c²/α²) = O(ρ μ/α)` corrections, on both sides of `η = 1`: the difference is
/// bounded by `2 (μ/α)(1 + ρ) + 1e-5` for `α` from 0.01 to 1 and `ρ` up to 20.
#[test]
fn corner_albedo_is_the_grazing_limit_of_the_albedo() {
    let mu: f64 = 1e-6;
    let mut worst: (f64, f64, f64) = (0.0, 0.0, 0.0);
    for alpha in [0.01_f64, 0.1, 1.0] {
        for rho in [0.1_f64, 1.0, 5.0, 20.0] {
            let c2: f64 = 2.0 * alpha * mu * rho;
            for inside in [false, true] {
                let eta = if inside {
                    (1.0 - c2).sqrt()
                } else {
                    1.0 / (1.0 - c2).sqrt()
                };
                let e = dielectric_albedo(alpha, eta, mu).unwrap();
                let phi = dielectric_table::corner_albedo(rho, inside);
                let d = (e - phi).abs();
                if d > worst.0 {
                    worst = (d, alpha, rho);
                }
                // The corrections shrink linearly with μ/α (measured: 5e-5 … 2.3e-3 at
                // α = 0.01, ten times less per decade of α), above a floor of about 5e-6.
                let bound = 2.0 * mu * (1.0 + rho) / alpha + 1e-5;
                assert!(
                    d < bound,
                    "α {alpha} ρ {rho} inside {inside}: E {e}, Φ {phi}, bound {bound:e}"
                );
            }
        }
    }
    eprintln!(
        "E(μ = 1e-6) against Φ(ρ): worst {:.2e} at α {} ρ {}",
        worst.0, worst.1, worst.2
    );
}
