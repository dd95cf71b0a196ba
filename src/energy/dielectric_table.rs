//! The coordinates, node definition and lookup of the shipped dielectric albedo table
//! `E(μ, α, η)` (see [`super::dielectric_albedo_table`] for the derivation and the measured
//! accuracy). Every map is one generic body: the lookup runs it on the lanes, the generator
//! (`tools/` `energy_tables --dielectric`) on `f64`, and inverts it by bisection.
//!
//! Most users need only [`super::dielectric_albedo_table`]; this module serves the generator,
//! the accuracy tests and anyone checking or shipping a regenerated table ([`lookup_with`]).
//! Its parts: the regions ([`Region`]), the closed-form corner ([`corner`], [`corner_albedo`])
//! the table subtracts, the axis maps ([`roughness_axis`], [`view_axis`], [`ior_axis`],
//! [`normal_axes`]) and their inverses ([`alpha_node`], [`inverse`], [`node_point`]), and the
//! stored values ([`residual`], [`plane`], [`block`], [`quantize`]).

use super::{ALPHA_MIN, dielectric_albedo, dielectric_tables, gather};
use crate::{Real, fast};

/// The clamp of the quadrature: [`dielectric_albedo`] evaluates `cos θo` as `max(μ, 1e-6)`,
/// so `E` is constant below it; the table is a function of `μ' = max(μ, 1e-6)`.
pub(super) const MU_FLOOR: f64 = 1e-6;
/// `c` at `η' = 3`: `√(1 − 1/9) = √8/3`.
const C_MAX: f64 = 0.942_809_041_582_063_4;
/// `q = c/√(1 − c²) = √(η'² − 1)` at `η' = 3`: `√8`.
const Q_MAX: f64 = 2.828_427_124_746_190_3;

/// Roughness nodes of the dielectric table (axis [`roughness_axis`]).
///
/// (To change a size or a map: set it here and run `cargo run --release -p brdf-tools --bin
/// energy_tables -- --dielectric`, which rewrites `src/energy/dielectric_tables.rs`.)
pub const ALPHA_NODES: usize = 28;
/// `(view, IOR)` nodes of the region [`Region::Outside`].
pub const OUTSIDE_NODES: (usize, usize) = (40, 24);
/// `(view, IOR)` nodes of the region [`Region::InsideGrazing`].
pub const INSIDE_GRAZING_NODES: (usize, usize) = (36, 32);
/// `(view, IOR)` nodes of the region [`Region::InsideOblique`].
pub const INSIDE_OBLIQUE_NODES: (usize, usize) = (36, 48);
/// `(IOR, view)` nodes of the region [`Region::InsideNormal`] (its first axis is
/// the IOR, its second the view: see [`Region`]).
pub const INSIDE_NORMAL_NODES: (usize, usize) = (32, 24);

/// The grading of the roughness axis towards `α = 1e-4` ([`roughness_axis`]).
const KAPPA: f64 = 4.0;
/// Weight of `s` against `1 − √(1 − s²)` in the outside view axis.
const LAMBDA_OUTSIDE: f64 = 0.6;
/// Weight of `s` against `μ̃/(μ̃ + sin θo)` in the inside view axis.
const LAMBDA_INSIDE: f64 = 0.5;
/// `d = μ' + K_D α`: the facet cosine at which the Fresnel (and, inside, total internal
/// reflection) transition of the IOR axes sits.
const K_D: f64 = 0.5;
/// Width `K_E α` of the total-internal-reflection edge `c = μ` of the oblique IOR axis.
const K_E: f64 = 1.0;
/// `λ² = 2 K_C α μ'`: the scale of the index-matched corner in the oblique IOR axis.
const K_C: f64 = 1.0;
/// Offset of the IOR axis of the near-normal region (`√(c₀² + q²) − c₀`).
const C0_NORMAL: f64 = 0.2;
/// Weights of the view components of the near-normal inside region: `[sin θo, μ, edge]`.
const W_NORMAL: [f64; 3] = [1.0, 1.0, 1.0];
/// Weights of the IOR components outside: `[q, Fresnel]`.
const W_OUTSIDE: [f64; 2] = [1.0, 2.0];
/// Weights of the IOR components of the oblique inside region: `[corner, q, Fresnel, edge,
/// kink]`.
const W_OBLIQUE: [f64; 5] = [0.5, 1.0, 2.0, 1.0, 0.5];
/// Keeps a normalized component defined where its range vanishes (it then follows `q`).
const EPS_COMPONENT: f64 = 1e-6;

/// The stored residual `T = E − C` is quantized to `u16` over `[T_LO, T_HI]` (the ghost
/// nodes extrapolate a little beyond `[−0.5, 1]`).
pub(super) const T_LO: f64 = -1.0;
/// See [`T_LO`].
pub(super) const T_HI: f64 = 2.0;

/// `μ` where `sin θo = c_max` (`1/3`): below it every inside `c ≤ c_max` is below the kink.
const MU_THIRD: f64 = 1.0 / 3.0;

/// The four regions of the dielectric table, each a tensor grid of its own.
///
/// With `c² = 1 − 1/η²` outside (`η ≥ 1`) and `c² = 1 − η²` inside (`c` is the cosine of the
/// critical angle, `η' = max(η, 1/η) = 1/√(1 − c²)`), `E` seen from inside has a kink on the
/// curve `sin θo = c`: a vertical microfacet facing the view sees it at the cosine `sin θo`
/// and, of the GGX tail of steep facets, refracts below the curve and totally reflects above
/// it (located at `μ = √(1 − c²)` for every measured `α`, e.g. `μ = 0.954` at `c = 0.3`,
/// a slope jump of 0.44 per unit `μ` at `α = 1`). The inside regions meet on that curve, so
/// that no cell straddles the kink. Below the kink the IOR range `[0, min(sin θo, c_max)]`
/// has a kink of its own in `μ` at `μ = 1/3` (`sin θo = c_max`), which an IOR axis scaled to
/// the range would carry into every row (1.3e-3 at `α = 0.54`, `η = 0.48`, `μ = 0.332`): the
/// part below the kink is split there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// `η ≥ 1`: axes `(v, u)` = (view [`view_axis`], IOR [`ior_axis`]).
    Outside,
    /// `η < 1`, `μ ≤ 1/3` (then `c ≤ c_max ≤ sin θo`): axes (view `v/v(1/3)`, IOR), the IOR
    /// axis spanning `c ∈ [0, c_max]`.
    InsideGrazing,
    /// `η < 1`, `μ > 1/3`, `c ≤ sin θo`: axes (view `(v − v(1/3))/(1 − v(1/3))`, IOR), the IOR
    /// axis spanning `c ∈ [0, sin θo]`.
    InsideOblique,
    /// `η < 1`, `c > sin θo`: axes (IOR `c`, view `sin θo ∈ (0, c]`).
    InsideNormal,
}

impl Region {
    /// The four regions in table order.
    pub const ALL: [Self; 4] = [
        Self::Outside,
        Self::InsideGrazing,
        Self::InsideOblique,
        Self::InsideNormal,
    ];

    /// Interior nodes `(first axis, second axis)`.
    #[must_use]
    pub const fn nodes(self) -> (usize, usize) {
        match self {
            Self::Outside => OUTSIDE_NODES,
            Self::InsideGrazing => INSIDE_GRAZING_NODES,
            Self::InsideOblique => INSIDE_OBLIQUE_NODES,
            Self::InsideNormal => INSIDE_NORMAL_NODES,
        }
    }

    /// Stored nodes per roughness: the interior nodes and one ghost row and column on each
    /// side (the Catmull-Rom stencil of a boundary cell reads them).
    #[must_use]
    pub const fn stored(self) -> (usize, usize) {
        let (n, m) = self.nodes();
        (n + 2, m + 2)
    }

    /// Offset of the region's block in the stored table.
    #[must_use]
    pub const fn offset(self) -> usize {
        match self {
            Self::Outside => 0,
            Self::InsideGrazing => Self::Outside.block(),
            Self::InsideOblique => Self::Outside.block() + Self::InsideGrazing.block(),
            Self::InsideNormal => {
                Self::Outside.block() + Self::InsideGrazing.block() + Self::InsideOblique.block()
            }
        }
    }

    /// Stored nodes of the region: `ALPHA_NODES + 2` roughness planes (with a
    /// ghost plane at each end) of [`Region::stored`] nodes.
    #[must_use]
    pub const fn block(self) -> usize {
        let (n, m) = self.stored();
        n * m * (ALPHA_NODES + 2)
    }

    /// Length of the whole stored table (all regions).
    #[must_use]
    pub const fn table_len() -> usize {
        Self::InsideNormal.offset() + Self::InsideNormal.block()
    }
}

/// `c²` of the interface: `1 − 1/η² = (η − 1)(η + 1)/η²` for `η ≥ 1`, `1 − η² = (1 − η)(1 + η)`
/// below (the factored forms keep `c` accurate at `η = 1 ± ulp`).
#[inline(always)]
#[must_use]
pub fn cos2_critical<R: Real>(eta: R) -> R {
    let one = R::one();
    let out = (eta - one) * (eta + one) / (eta * eta);
    let inside = (one - eta) * (one + eta);
    R::select(eta.ge(one), out, inside).max(R::zero())
}

/// `Φ(ρ)`, the albedo of the index-matched corner (`μ ≪ α`, `η → 1`, `ρ = c²/(2αμ)` fixed),
/// outside (`Φ₊`, from 1/2 up to 1) or inside (`Φ₋`, from 1/2 down to 0).
///
/// At grazing view `Λ(wo) ≈ α/(2μ)` and a visible facet at slope `p = α x` (density
/// `x (1 + x²)^{−3/2}`, the GGX slope marginal weighted by visibility) refracts `wo` to an
/// elevation `e = μ ± c² /(2 p)` (outside `+`, inside `−`: light bent above the horizon is
/// lost); `G2/G1 = e/(μ + e)`. Hence
///
/// ```text
/// Φ₊(ρ) = ∫₀^∞ x (1 + x²)^{−3/2} (x + ρ)/(2x + ρ) dx
///       = 1/2 + ρ/(2(4 + ρ²)) · [2 + ρ − (2ρ/A) ln((A + ρ)(A + 2)/(2ρ))]
/// Φ₋(ρ) = ∫_ρ^∞ x (1 + x²)^{−3/2} (x − ρ)/(2x − ρ) dx
///       = 1/(2B) − (ρ/2) [2 − 3ρ/B + (2ρ/A) ln(4(AB + 2 + ρ²)/(2ρ (A + ρ)))]/(4 + ρ²)
/// A = √(4 + ρ²),  B = √(1 + ρ²)
/// ```
///
/// (substituting `x = tan θ`, `sin θ cos θ = ((a s + b c)(b s + a c) − ab)/(a² + b²)`).
/// `Φ₊ = 1/2 + ρ/4 + O(ρ²)`, `1 − Φ₊ ≈ ln ρ/ρ` and `Φ₋ = 1/2 − ρ/4 + …`. Tested
/// (`tests/energy_dielectric.rs`) against the defining integrals (Simpson, within 2.3e-7) and
/// against the quadrature at `μ = 1e-6`: the difference shrinks linearly with `μ/α` (the
/// corrections are `O(μ/α)` and `O(c²/α²) = O(ρ μ/α)`; within `2 (μ/α)(1 + ρ) + 1e-5`
/// for `α ∈ [0.01, 1]`, `ρ ≤ 20`, e.g. 2.3e-3 at `α = 0.01`, `ρ = 20` inside, 5e-6 at
/// `α = 1` outside). The table stores `E − C`, so these corrections are part of the
/// smooth residual, not an error of the lookup. The logarithm is [`fast::log2`] of degree 6: generator and
/// lookup evaluate the same function, so its own error does not matter.
#[inline(always)]
#[must_use]
pub fn corner_albedo<R: Real>(rho: R, inside: R::Mask) -> R {
    let r = rho.max(R::from_f64(1e-30));
    let (one, two, four) = (R::one(), R::from_f64(2.0), R::from_f64(4.0));
    let r2 = r * r;
    let a = (four + r2).sqrt();
    let b = (one + r2).sqrt();
    let arg_out = (a + r) * (a + two) / (two * r);
    // A − ρ = 4/(A + ρ) without cancellation at large ρ.
    let arg_in = four * (a * b + two + r2) / (two * r * (a + r));
    let ln = fast::log2::<6, R>(R::select(inside, arg_in, arg_out))
        * R::from_f64(core::f64::consts::LN_2);
    let out = R::from_f64(0.5) + r / (two * (four + r2)) * (two + r - two * r / a * ln);
    let k = (two - R::from_f64(3.0) * r / b + two * r / a * ln) / (four + r2);
    let inn = R::from_f64(0.5) / b - R::from_f64(0.5) * r * k;
    R::select(inside, inn.max(R::zero()), out)
}

/// The part of `E` the table does not store, `C = W Φ(ρ)` ([`corner_albedo`]), with
/// `ρ = c²/(2αμ')`, `μ' = max(μ, 1e-6)` and the window
///
/// ```text
/// W(x) = 1/(1 + x + x²/2 + x³/6 + x⁴/24),   x = μ'/α
/// ```
///
/// (the reciprocal of the quartic Taylor polynomial of `eˣ`), which keeps `C` to grazing
/// views (`W = 1 − x + O(x²)`, `W < 0.05` for `x > 3.6`). `W` is smooth (no point where it
/// closes) and changes over a factor of about 30 in `μ/α`, so the residual `E − C` stays
/// smooth along the roughness axis, whose nodes are a factor of about 1.7 apart near
/// `α = 0.03`. (A window closing at `μ = 2α`, `(1 − min(μ/(2α), 1))³`, left a jump in the
/// third derivative that the tricubic lookup missed by up to 1.1e-3 at `μ ≈ 2α`, `η → 1`.)
#[inline(always)]
#[must_use]
pub fn corner<R: Real>(alpha: R, eta: R, cos_theta_o: R) -> R {
    let mu = cos_theta_o.max(R::from_f64(MU_FLOOR));
    let c2 = cos2_critical(eta);
    let rho = c2 / (R::from_f64(2.0) * alpha * mu);
    let x = mu / alpha;
    // 1 + x (1 + x/2 (1 + x/3 (1 + x/4))), Horner.
    let q = R::one() + x * R::from_f64(0.25);
    let q = R::one() + x * R::from_f64(1.0 / 3.0) * q;
    let q = R::one() + x * R::from_f64(0.5) * q;
    let q = R::one() + x * q;
    corner_albedo(rho, eta.lt(R::one())) / q
}

/// The roughness coordinate `t = (g(α) − g(1e-4))/(g(1) − g(1e-4))`,
/// `g(α) = √α − κ √(10⁻⁶/α)`, `κ = 6`.
///
/// `√α` (the albedo tables' axis) spaces the nodes for the smooth dependence on `α`. The
/// second term grades them towards `α = 1e-4` for the quadrature's clamp `μ ≥ 1e-6`: at the
/// clamp the albedo depends on `x = 10⁻⁶/α` through a grazing term `∝ x ln(1/x)` (as
/// `1 − E ∝ μ (c − ln μ)` at grazing). Its second derivative in `α`, `∝ ln(α/10⁻⁶)·10⁻⁶/α³`,
/// asks for a node density `∝ α^{−3/2}` (equidistributed linear-interpolation error), that
/// is a coordinate `∝ −α^{−1/2}`. Measured in the prototype (40 nodes): a term
/// `10 x ln(1/x)` is interpolated within 5.1e-4 on this axis and 2.3e-3 on
/// `√α − 30·10⁻⁶/α` (whose worst table cell, `α ≈ 1.7e-3`, `μ` at the clamp, was 1.2e-3
/// off), while a smooth `0.1 sin 3√α` stays within 1.8e-4.
#[inline(always)]
#[must_use]
pub fn roughness_axis<R: Real>(alpha: R) -> R {
    let g = |a: f64| a.sqrt() - KAPPA * (MU_FLOOR / a).sqrt();
    let (g0, g1) = (g(ALPHA_MIN), g(1.0));
    let ga = alpha.sqrt() - R::from_f64(KAPPA * MU_FLOOR.sqrt()) / alpha.sqrt();
    (ga - R::from_f64(g0)) / R::from_f64(g1 - g0)
}

/// `1 − √(1 − x)` for `x ∈ [0, 1]`, without cancellation: `x/(1 + √(1 − x))`.
#[inline(always)]
fn one_minus_sqrt_one_minus<R: Real>(x: R) -> R {
    x / (R::one() + (R::one() - x).safe_sqrt())
}

/// `q(c) = c/√(1 − c²) = √(η'² − 1)`.
#[inline(always)]
fn q_of<R: Real>(c: R, c2: R) -> R {
    c / (R::one() - c2).sqrt()
}

/// The view coordinate `v ∈ [0, 1]` outside and below the kink inside (the regions
/// `InsideGrazing` and `InsideOblique` rescale its parts `μ ≤ 1/3` and `μ ≥ 1/3`):
///
/// ```text
/// μ̃ = max(μ, 1e-6) − 1e-6,   s² = μ̃ (1 + α)/(μ̃ + α)
/// outside:  v = 0.6 s + 0.4 (1 − √(1 − s²))
/// inside:   v = 0.5 s + 0.5 μ̃/(μ̃ + sin θo)
/// ```
///
/// `s` is the albedo tables' view axis ([`super::albedo_table_s`]: the dip at `μ ~ α` and the
/// grazing slope), started at the quadrature's clamp so that `v = 0` is `μ' = 1e-6` at every
/// `α`. Near normal view `E` has a term linear in `sin θo` (a cusp in `θo`; outside at `α = 1`
/// `E'' ∝ (1 − μ)^{−3/2}`), which `s` (`1 − s ∝ sin²θo`) turns into a square root; the
/// second terms are linear in `sin θo` there. Inside, the features (the kink and the
/// total-internal-reflection edge `c = μ`) sit at `α`-independent angles: `μ/(μ + sin θo)`
/// (`tan ψ/(1 + tan ψ)` of the elevation `ψ`) is linear in `μ` at grazing and in `sin θo` at
/// normal view. With `1 − sin θo` instead, views `μ ∈ [0.03, 1/3]` got two nodes at
/// `α = 1.3e-3` (8e-4 off where a row of the IOR axis leaves the edge).
#[inline(always)]
#[must_use]
pub fn view_axis<R: Real>(alpha: R, cos_theta_o: R, inside: R::Mask) -> R {
    let mu = cos_theta_o.max(R::from_f64(MU_FLOOR));
    let mt = mu - R::from_f64(MU_FLOOR);
    let s2 = (mt * (R::one() + alpha) / (mt + alpha)).min(R::one());
    let s = s2.sqrt();
    let out = R::from_f64(LAMBDA_OUTSIDE) * s
        + R::from_f64(1.0 - LAMBDA_OUTSIDE) * one_minus_sqrt_one_minus(s2);
    let sin = ((R::one() - mu) * (R::one() + mu)).safe_sqrt();
    let inn = R::from_f64(LAMBDA_INSIDE) * s + R::from_f64(1.0 - LAMBDA_INSIDE) * (mt / (mt + sin));
    R::select(inside, inn, out)
}

/// `(f(x) − f(0) + ε x̂)/(f(hi) − f(0) + ε)`: a component normalized on its range, `x̂` the
/// `q`-linear coordinate (the fallback where the component's range vanishes).
#[inline(always)]
fn normalized<R: Real>(f_c: R, f_0: R, f_hi: R, lin: R) -> R {
    let eps = R::from_f64(EPS_COMPONENT);
    (f_c - f_0 + eps * lin) / (f_hi - f_0 + eps)
}

/// `½(1 + x/√(1 + x²))`: the CDF of the GGX slope marginal, a smooth step of width 1.
#[inline(always)]
fn step<R: Real>(x: R) -> R {
    R::from_f64(0.5) * (R::one() + x / (R::one() + x * x).sqrt())
}

/// The IOR coordinate `u ∈ [0, 1]` of the regions `Outside` and `InsideOblique`, a weighted
/// mean of normalized components of `c` on the region's range `[0, c_hi]` (`c_hi = c_max`
/// outside, `min(sin θo, c_max)` inside):
///
/// ```text
/// q̂ = q(c)/q(c_hi)                               q = c/√(1 − c²) = √(η'² − 1): linear in η' at large η'
/// F̂ ∝ 1 − 1/√(1 + c/d),   d = μ' + α/2            the Fresnel (inside also total reflection)
///                                                 transition of facets at cosine ~ d, and its
///                                                 1/c tail (F ≈ 1 − 4d/c), evenly
/// inside only:
/// Ĉ ∝ c²/(c² + 2αμ')                              the index-matched corner, ρ ~ 1 (E is even in c)
/// Ê ∝ step((c − μ')/α)                            the total-internal-reflection edge c = μ
/// K̂ = 1 − √(1 − c/c_hi)                           the kink at c_hi = sin θo: E − E(kink) ~ (c_hi − c)^{3/2}
/// u = (1 q̂ + 2 F̂)/3 outside,  (½ Ĉ + 1 q̂ + 2 F̂ + 1 Ê + ½ K̂)/5 inside
/// ```
///
/// Every component is monotone in `c` and `0` at `c = 0`, `1` at `c_hi`, so `u` is; the
/// generator inverts it by bisection.
#[inline(always)]
#[must_use]
pub fn ior_axis<R: Real>(alpha: R, eta: R, cos_theta_o: R) -> R {
    let mu = cos_theta_o.max(R::from_f64(MU_FLOOR));
    let inside = eta.lt(R::one());
    let c2 = cos2_critical(eta);
    let c = c2.sqrt();
    let one = R::one();
    let sin = ((one - mu) * (one + mu)).safe_sqrt();
    let hi = R::select(inside, sin.min(R::from_f64(C_MAX)), R::from_f64(C_MAX));
    let hi = hi.max(R::from_f64(1e-30));
    let c = c.min(hi);
    let c2 = c * c;
    let hi2 = hi * hi;
    let lin = q_of(c, c2) / q_of(hi, hi2);
    let d = mu + R::from_f64(K_D) * alpha;
    let fres = |c: R| one - one / (one + c / d).sqrt();
    let f = normalized(fres(c), R::zero(), fres(hi), lin);
    let l2 = R::from_f64(2.0 * K_C) * alpha * mu;
    let corner = normalized(c2 / (c2 + l2), R::zero(), hi2 / (hi2 + l2), lin);
    let we = R::from_f64(K_E) * alpha;
    let e0 = step(-mu / we);
    let edge = normalized(step((c - mu) / we), e0, step((hi - mu) / we), lin);
    let kink = one_minus_sqrt_one_minus(c / hi);
    let out = (R::from_f64(W_OUTSIDE[0]) * lin + R::from_f64(W_OUTSIDE[1]) * f)
        / R::from_f64(W_OUTSIDE[0] + W_OUTSIDE[1]);
    let w = W_OBLIQUE;
    let inn = (R::from_f64(w[0]) * corner
        + R::from_f64(w[1]) * lin
        + R::from_f64(w[2]) * f
        + R::from_f64(w[3]) * edge
        + R::from_f64(w[4]) * kink)
        / R::from_f64(w[0] + w[1] + w[2] + w[3] + w[4]);
    R::select(inside, inn, out)
}

/// The coordinates `(a, b) ∈ [0, 1]²` of the region `InsideNormal` (`c > sin θo`):
///
/// ```text
/// a = h(q)/h(q_max),   h(q) = √(c₀² + q²) − c₀,  c₀ = 0.2,  q = √(η'² − 1)
/// b = (Ŝ + M̂ + Ê)/3,   Ŝ = 1 − sin θo/c,   M̂ = (μ' − μ_k)/(1 − μ_k),   μ_k = √(1 − c²) = η
/// Ê ∝ step((μ' − c)/α)   (normalized on [μ_k, 1])
/// ```
///
/// (`b = 0` on the kink `sin θo = c`, `b = 1` at normal view). `a` is quadratic in `c` near
/// `c = 0` (where `E(μ → 1, c) ≈ 1 − k c²`) and linear in `q` (so in `η'`) beyond `c₀`.
/// Near normal view `E` has a term linear in `sin θo` (a cusp in `θo`), which an axis linear
/// in `μ` turns into a square root (9.9e-4 off at `α = 0.21`, `η = 0.338`, `μ = 0.983` with
/// 20 nodes linear in `μ`); an axis linear in `sin θo` alone crowds out `μ` near the kink at
/// `c → c_max` (2.4e-3 at `α = 0.96`, `η = 0.340`, `μ = 0.405`). `Ê` follows the
/// total-internal-reflection edge `μ = c`, which lies in this region for `c > 1/√2`
/// (without it, 7.3e-4 at `α = 0.21`, `η = 0.336`, `μ = 0.982`, from the roughness
/// interpolation across the edge's `α`-wide dip).
#[inline(always)]
#[must_use]
pub fn normal_axes<R: Real>(alpha: R, eta: R, cos_theta_o: R) -> (R, R) {
    let mu = cos_theta_o.max(R::from_f64(MU_FLOOR));
    let c2 = cos2_critical(eta).min(R::from_f64(C_MAX * C_MAX));
    let one = R::one();
    let q = c2.sqrt() / (one - c2).sqrt();
    let c0 = R::from_f64(C0_NORMAL);
    let h = (c0 * c0 + q * q).sqrt() - c0;
    let h_max = (C0_NORMAL * C0_NORMAL + Q_MAX * Q_MAX).sqrt() - C0_NORMAL;
    let a = h / R::from_f64(h_max);
    let sin = ((one - mu) * (one + mu)).safe_sqrt();
    let tiny = R::from_f64(1e-30);
    let c = c2.sqrt();
    let by_sin = one - sin / c.max(tiny);
    let mk = (one - c2).sqrt();
    let by_mu = (mu - mk) / (one - mk).max(tiny);
    let we = R::from_f64(K_E) * alpha;
    let edge = normalized(
        step((mu - c) / we),
        step((mk - c) / we),
        step((one - c) / we),
        by_mu,
    );
    let w = W_NORMAL;
    let b = (R::from_f64(w[0]) * by_sin + R::from_f64(w[1]) * by_mu + R::from_f64(w[2]) * edge)
        / R::from_f64(w[0] + w[1] + w[2]);
    (a, b)
}

/// Which region each lane is in: `(inside, grazing, normal)` masks (`grazing` and `normal`
/// imply `inside` and exclude each other).
#[inline(always)]
fn regions<R: Real>(eta: R, cos_theta_o: R) -> (R::Mask, R::Mask, R::Mask) {
    let mu = cos_theta_o.max(R::from_f64(MU_FLOOR));
    let inside = eta.lt(R::one());
    let c2 = cos2_critical(eta);
    let sin2 = (R::one() - mu) * (R::one() + mu);
    let normal = inside & c2.gt(sin2);
    let grazing = inside & mu.le(R::from_f64(MU_THIRD)) & !normal;
    (inside, grazing, normal)
}

/// The region of a scalar `(η, μ)` (clamped like the lookup).
#[must_use]
pub fn region_of(eta: f64, cos_theta_o: f64) -> Region {
    let eta = eta.clamp(1.0 / 3.0, 3.0);
    let mu = cos_theta_o.clamp(0.0, 1.0);
    match regions(eta, mu) {
        (false, _, _) => Region::Outside,
        (true, true, _) => Region::InsideGrazing,
        (true, false, false) => Region::InsideOblique,
        (true, false, true) => Region::InsideNormal,
    }
}

/// The view coordinate of a view-major region: [`view_axis`] outside, and inside
/// rescaled to the region's part of it, `v/v(1/3)` (`InsideGrazing`) or
/// `(v − v(1/3))/(1 − v(1/3))` (`InsideOblique`).
#[inline(always)]
fn region_view<R: Real>(alpha: R, cos_theta_o: R, inside: R::Mask, grazing: R::Mask) -> R {
    let v = view_axis(alpha, cos_theta_o, inside);
    let third = view_axis(alpha, R::from_f64(MU_THIRD), inside);
    let low = v / third;
    let high = (v - third) / (R::one() - third);
    R::select(inside, R::select(grazing, low, high), v)
}

/// The table coordinates of a scalar point: region and `(t, first, second)` in `[0, 1]`
/// (inputs clamped like the lookup).
#[must_use]
pub fn coordinates(alpha: f64, eta: f64, cos_theta_o: f64) -> (Region, [f64; 3]) {
    let alpha = alpha.clamp(ALPHA_MIN, 1.0);
    let eta = eta.clamp(1.0 / 3.0, 3.0);
    let mu = cos_theta_o.clamp(0.0, 1.0);
    let region = region_of(eta, mu);
    let t = roughness_axis(alpha);
    let ab = match region {
        Region::InsideNormal => normal_axes(alpha, eta, mu),
        r => (
            region_view(alpha, mu, r != Region::Outside, r == Region::InsideGrazing),
            ior_axis(alpha, eta, mu),
        ),
    };
    (region, [t, ab.0.clamp(0.0, 1.0), ab.1.clamp(0.0, 1.0)])
}

/// The smallest `x ∈ [lo, hi]` with `f(x) ≥ y` for increasing `f`, by 100 bisections
/// (the generator's inverse of the axis maps; deterministic).
fn bisect(lo: f64, hi: f64, y: f64, f: impl Fn(f64) -> f64) -> f64 {
    let (mut a, mut b) = (lo, hi);
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        if f(m) < y {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// `η` from `c` on a side: `1/√(1 − c²)` outside, `√(1 − c²)` inside.
fn eta_of_c(c: f64, inside: bool) -> f64 {
    let r = (1.0 - c * c).sqrt();
    if inside { r } else { 1.0 / r }
}

/// `α` of roughness node `j` (the inverse of [`roughness_axis`] at `j/(N − 1)`).
#[must_use]
pub fn alpha_node(j: usize) -> f64 {
    assert!(j < ALPHA_NODES, "roughness node {j}");
    if j == 0 {
        return ALPHA_MIN;
    }
    if j + 1 == ALPHA_NODES {
        return 1.0;
    }
    let t = j as f64 / (ALPHA_NODES - 1) as f64;
    bisect(ALPHA_MIN, 1.0, t, roughness_axis::<f64>)
}

/// The point `(η, μ)` at the in-region coordinates `(a, b) ∈ [0, 1]²` of `region` at
/// roughness `alpha`: the inverse of the region's axes ([`view_axis`] ×
/// [`ior_axis`], or [`normal_axes`]), by bisection where it has no
/// closed form. `a = 0` is `μ = 1e-6` (the quadrature's clamp) in the regions `Outside` and
/// `InsideGrazing`.
#[must_use]
pub fn inverse(region: Region, alpha: f64, a: f64, b: f64) -> (f64, f64) {
    let (a, b) = (a.clamp(0.0, 1.0), b.clamp(0.0, 1.0));
    if region == Region::InsideNormal {
        // a = h(q)/h_max → q → c; b → μ between the kink and 1.
        let h_max = (C0_NORMAL * C0_NORMAL + Q_MAX * Q_MAX).sqrt() - C0_NORMAL;
        let h = a * h_max + C0_NORMAL;
        let q = (h * h - C0_NORMAL * C0_NORMAL).max(0.0).sqrt();
        let c = (q / (1.0 + q * q).sqrt()).min(C_MAX);
        let eta = eta_of_c(c, true);
        let mu = if b == 0.0 {
            eta
        } else if b == 1.0 {
            1.0
        } else {
            bisect(eta, 1.0, b, |mu| normal_axes(alpha, eta, mu).1)
        };
        return (eta, mu);
    }
    let inside = region != Region::Outside;
    let grazing = region == Region::InsideGrazing;
    let (lo, hi) = match region {
        Region::InsideGrazing => (MU_FLOOR, MU_THIRD),
        Region::InsideOblique => (MU_THIRD, 1.0),
        _ => (MU_FLOOR, 1.0),
    };
    let mu = if a == 0.0 {
        lo
    } else if a == 1.0 {
        hi
    } else {
        bisect(lo, hi, a, |mu| region_view(alpha, mu, inside, grazing))
    };
    let hi = if inside {
        (1.0 - mu * mu).sqrt().min(C_MAX)
    } else {
        C_MAX
    };
    let c = if b == 0.0 {
        0.0
    } else if b == 1.0 {
        hi
    } else {
        bisect(0.0, hi, b, |c| ior_axis(alpha, eta_of_c(c, inside), mu))
    };
    (eta_of_c(c, inside), mu)
}

/// The point `(α, η, μ)` of interior node `(i, k)` (first, second axis) of roughness `j` in
/// `region`: [`inverse`] at `(i/(n − 1), k/(m − 1))` and
/// `α` = [`alpha_node`]`(j)`.
///
/// Domain `i < n`, `k < m` ([`Region::nodes`]), `j < ALPHA_NODES`
/// (panics outside).
#[must_use]
pub fn node_point(region: Region, i: usize, j: usize, k: usize) -> (f64, f64, f64) {
    let (n, m) = region.nodes();
    assert!(i < n && k < m, "node ({i}, {j}, {k}) of {region:?}");
    let alpha = alpha_node(j);
    let (eta, mu) = inverse(
        region,
        alpha,
        i as f64 / (n - 1) as f64,
        k as f64 / (m - 1) as f64,
    );
    (alpha, eta, mu)
}

/// The residual `T = E − C` ([`corner`]) at interior node `(i, j, k)`, in
/// `f64` (before quantization): [`dielectric_albedo`] at [`node_point`].
///
/// # Panics
/// Outside the node ranges.
#[must_use]
pub fn residual(region: Region, i: usize, j: usize, k: usize) -> f64 {
    let (alpha, eta, mu) = node_point(region, i, j, k);
    let e = dielectric_albedo(alpha, eta.clamp(1.0 / 3.0, 3.0), mu).unwrap_or(f64::NAN);
    e - corner(alpha, eta, mu)
}

/// `T` at a stored (padded) index `p ∈ [0, n + 2)` along one axis from the interior values
/// `f(0 … n − 1)`: the interior node `p − 1`, or a ghost extrapolated quadratically
/// (`3 f₀ − 3 f₁ + f₂`, exact for a parabola, so Catmull-Rom reproduces quadratics up to the
/// boundary; a linear ghost was 2e-3 off in the last cell where `E` curves most).
fn padded(p: usize, n: usize, f: &mut impl FnMut(usize) -> f64) -> f64 {
    if p == 0 {
        3.0 * f(0) - 3.0 * f(1) + f(2)
    } else if p == n + 1 {
        3.0 * f(n - 1) - 3.0 * f(n - 2) + f(n - 3)
    } else {
        f(p - 1)
    }
}

/// `T` at the stored node `(s, p, r)` (padded indices: roughness
/// `s < ALPHA_NODES + 2`, first axis `p < n + 2`, second `r < m + 2`) in `f64`.
#[must_use]
pub fn stored_residual(region: Region, s: usize, p: usize, r: usize) -> f64 {
    let (n, m) = region.nodes();
    padded(s, ALPHA_NODES, &mut |j| {
        padded(p, n, &mut |i| {
            padded(r, m, &mut |k| residual(region, i, j, k))
        })
    })
}

/// Quantizes a residual to the stored `u16` (round to nearest on `[T_LO, T_HI]`).
#[must_use]
pub fn quantize(t: f64) -> u16 {
    let y = (t - T_LO) / (T_HI - T_LO) * 65535.0;
    // Round half away from zero (`f64::round`, which needs `std`): `y − ⌊y⌋` is exact.
    let f = Real::floor(y);
    let x = if y - f >= 0.5 { f + 1.0 } else { f };
    assert!(
        (0.0..=65535.0).contains(&x),
        "residual {t} outside [{T_LO}, {T_HI}]"
    );
    x as u16
}

/// The residuals `T` of the interior nodes of roughness plane `j` of `region` (first axis
/// major, `n × m` values), computed now: [`residual`] at every node. (Needs the `std`
/// feature: it allocates.)
#[cfg(feature = "std")]
#[must_use]
pub fn plane(region: Region, j: usize) -> Vec<f64> {
    let (n, m) = region.nodes();
    (0..n)
        .flat_map(|i| (0..m).map(move |k| (i, k)))
        .map(|(i, k)| residual(region, i, j, k))
        .collect()
}

/// The stored block of `region` from its interior planes `planes[j]` (of
/// [`plane`]): ghost planes, rows and columns extrapolated, every value
/// quantized by [`quantize`]; roughness major, then the first axis.
///
/// # Panics
/// If `planes` is not `ALPHA_NODES` planes of `n × m` values. (Needs the `std` feature: it
/// allocates.)
#[cfg(feature = "std")]
#[must_use]
pub fn block(region: Region, planes: &[Vec<f64>]) -> Vec<u16> {
    let (n, m) = region.nodes();
    let nt = ALPHA_NODES;
    assert!(planes.len() == nt && planes.iter().all(|p| p.len() == n * m));
    let mut out = Vec::with_capacity(region.block());
    for s in 0..nt + 2 {
        for p in 0..n + 2 {
            for r in 0..m + 2 {
                let t = padded(s, nt, &mut |j| {
                    padded(p, n, &mut |i| padded(r, m, &mut |k| planes[j][i * m + k]))
                });
                out.push(quantize(t));
            }
        }
    }
    out
}

/// Catmull-Rom weights of the offsets `−1, 0, 1, 2` at `x ∈ [0, 1]`.
#[inline(always)]
pub(super) fn catmull_rom<R: Real>(x: R) -> [R; 4] {
    let h = R::from_f64(0.5);
    let x2 = x * x;
    let x3 = x2 * x;
    [
        h * (x2 + x2 - x - x3),
        h * (R::from_f64(2.0) - R::from_f64(5.0) * x2 + R::from_f64(3.0) * x3),
        h * (x + R::from_f64(4.0) * x2 - R::from_f64(3.0) * x3),
        h * (x3 - x2),
    ]
}

/// Cell index and fraction of a coordinate `x ∈ [0, 1]` on `n` nodes.
#[inline(always)]
pub(super) fn cell<R: Real>(x: R, n: usize) -> (R, R) {
    let f = x.saturate() * R::from_f64((n - 1) as f64);
    let i = f.floor().min(R::from_f64((n - 2) as f64));
    (i, f - i)
}

/// The lookup of [`super::dielectric_albedo_table`] on the shipped table.
#[inline(always)]
pub(super) fn lookup<R: Real>(alpha: R, eta: R, cos_theta_o: R) -> R {
    lookup_with(dielectric_tables::DIELECTRIC_E, alpha, eta, cos_theta_o)
}

/// [`super::dielectric_albedo_table`] on a table of the shipped layout
/// ([`Region::table_len`] values, the blocks of [`block`] in
/// [`Region::ALL`] order): for checking a regenerated or partial table before
/// shipping it.
///
/// # Panics
/// If `table` is shorter than [`Region::table_len`].
#[inline(always)]
#[must_use]
pub fn lookup_with<R: Real>(table: &[u16], alpha: R, eta: R, cos_theta_o: R) -> R {
    assert!(
        table.len() >= Region::table_len(),
        "a dielectric table is {} values",
        Region::table_len()
    );
    let alpha = alpha.clamp(R::from_f64(ALPHA_MIN), R::one());
    let eta = eta.clamp(R::from_f64(1.0 / 3.0), R::from_f64(3.0));
    let mu = cos_theta_o.saturate();
    let (inside, grazing, normal) = regions(eta, mu);
    let (na, nb) = normal_axes(alpha, eta, mu);
    let va = region_view(alpha, mu, inside, grazing);
    let vb = ior_axis(alpha, eta, mu);
    // A per-region constant, per lane (region order of `Region::ALL`).
    let pick = |f: &dyn Fn(Region) -> usize| {
        let [o, g, b, n] = Region::ALL.map(|r| R::from_f64(f(r) as f64));
        R::select(normal, n, R::select(grazing, g, R::select(inside, b, o)))
    };
    let a = R::select(normal, na, va);
    let b = R::select(normal, nb, vb);
    // Cells: per lane, the region's node counts.
    let cells = |x: R, nn: R| {
        let f = x.saturate() * (nn - R::one());
        let i = f.floor().min(nn - R::from_f64(2.0));
        (i, f - i)
    };
    let (ia, fa) = cells(a, pick(&|r| r.nodes().0));
    let (ib, fb) = cells(b, pick(&|r| r.nodes().1));
    let (jt, ft) = cell(roughness_axis(alpha), ALPHA_NODES);
    let wt = catmull_rom(ft);
    let row = pick(&|r| r.stored().1);
    let plane = pick(&|r| r.stored().0 * r.stored().1);
    let base = pick(&|r| r.offset());
    // Stored (padded) index of the stencil's first node: plane jt − 1 + 1, row ia − 1 + 1,
    // column ib − 1 + 1.
    let k0 = base + jt * plane + ia * row + ib;
    let (wa, wb) = (catmull_rom(fa), catmull_rom(fb));
    let layer = |k: R| {
        let mut sum = R::zero();
        for (p, &w_a) in wa.iter().enumerate() {
            let mut inner = R::zero();
            for (r, &w_b) in wb.iter().enumerate() {
                let idx = k + R::from_f64(p as f64) * row + R::from_f64(r as f64);
                inner += w_b * gather(table, idx);
            }
            sum += w_a * inner;
        }
        sum
    };
    let mut q = R::zero();
    for (s, &w_t) in wt.iter().enumerate() {
        q += w_t * layer(k0 + R::from_f64(s as f64) * plane);
    }
    let t = R::from_f64(T_LO) + q * R::from_f64((T_HI - T_LO) / 65535.0);
    (t + corner(alpha, eta, mu)).saturate()
}
