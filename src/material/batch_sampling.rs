//! Batch sampling of the run-time mixtures, [`Material::Sum`] and [`Material::Layered`].
//!
//! Per sample, a mixture draws a sample from each part (with the third uniform number split
//! between them), keeps the chosen one, and weighs it by the mixture's density and the whole
//! material's value (`sampling::lobes::sample_pair`). Here each of those steps runs over a
//! block of samples: the parts' samples, densities and albedo estimates through the batch
//! kernels of the models they hold (recursively through nested mixtures), the material's
//! value through its batch evaluation, and the choice, the mixture density and the weight in
//! plain passes with the same functions as the per-sample sampler. So the samples are those
//! of [`SampleBrdf::sample`](crate::SampleBrdf::sample) on the form the batch loops run, bit
//! for bit (`tests/batch.rs`), except that a part with
//! [`HardwareEstimate`](crate::fast::HardwareEstimate) gets the estimates on AVX-512 (within
//! a few ULP, as in every batch loop).
//!
//! The passes' arithmetic (`first_probability`, `split_u2`, `choose_pair`, `pdf_pair_of`,
//! `finish`) is divisions, products, sums, comparisons and selections only, which round the
//! same on `f32` and on the FMA number types, so it runs on `f32`. The coat's transmission of
//! a layered material evaluates a Fresnel term, which does fuse, so it runs on the form of
//! the instruction set.

use alloc::vec;
use alloc::vec::Vec;

use super::Material;
use crate::Vec3;
use crate::batch::{self, BLOCK, Directions, Isa, SampleOut};
use crate::fresnel::AnyFresnel;
use crate::models::Layered;
use crate::models::layered::coat_transmission;
use crate::real::{F32Fma, F32FmaSharedDiv, Splat};
use crate::sampling::lobes::{choose_pair, finish, first_probability, pdf_pair_of, split_u2};

/// The mixtures as [`Layered`] holds them in a material.
type LayeredMaterial = Layered<Material<f32>, Material<f32>, AnyFresnel<f32>>;

/// Owned output arrays of `n` samples in one allocation: `wi.x`, `wi.y`, `wi.z`, the density
/// and three weights, each `n` long.
struct Samples {
    buf: Vec<f32>,
    n: usize,
}

impl Samples {
    fn new(n: usize) -> Self {
        Samples {
            buf: vec![0.0; 7 * n],
            n,
        }
    }

    /// The `k`-th array.
    fn at(&self, k: usize) -> &[f32] {
        &self.buf[k * self.n..(k + 1) * self.n]
    }

    fn out(&mut self) -> SampleOut<'_, 3> {
        let mut parts = self.buf.chunks_exact_mut(self.n.max(1));
        let mut next = || parts.next().unwrap_or_default();
        let (x, y, z, pdf) = (next(), next(), next(), next());
        SampleOut {
            x,
            y,
            z,
            pdf,
            weight: [next(), next(), next()],
        }
    }
}

/// Samples a `Sum` or `Layered` material over the whole batch, block by block of
/// [`BLOCK`] samples (`isa` available, every slice of one length: the caller checked).
pub(super) fn sample_mixture(
    m: &Material<f32>,
    isa: Isa,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, 3>,
) {
    let n = wo.len();
    let mut start = 0;
    while start < n {
        let r = start..(start + BLOCK).min(n);
        let [w0, w1, w2] = &mut out.weight;
        let mut block = SampleOut {
            x: &mut out.x[r.clone()],
            y: &mut out.y[r.clone()],
            z: &mut out.z[r.clone()],
            pdf: &mut out.pdf[r.clone()],
            weight: [&mut w0[r.clone()], &mut w1[r.clone()], &mut w2[r.clone()]],
        };
        let u = u.map(|s| &s[r.clone()]);
        sample(m, isa, wo.range(r.clone()), u, &mut block);
        start = r.end;
    }
}

/// Samples any material: a model through its batch sampler, a mixture by its parts.
fn sample(
    m: &Material<f32>,
    isa: Isa,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, 3>,
) {
    match m {
        Material::Sum(terms) => sum_sample(terms, isa, wo, u, out),
        Material::Layered(l) => layered_sample(l, isa, wo, u, out),
        leaf => {
            let _ = leaf.sample_batch_f32(isa, wo, u, out);
        }
    }
}

/// `Sum(Sum(t₀, t₁), t₂)…` as `sum_sample` in the parent module: an empty sum gives invalid
/// samples, one term its own samples, more the mixture of the sum of all but the last term
/// and the last.
fn sum_sample(
    terms: &[Material<f32>],
    isa: Isa,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, 3>,
) {
    match terms.split_last() {
        None => {
            out.x.fill(0.0);
            out.y.fill(0.0);
            out.z.fill(1.0);
            out.pdf.fill(0.0);
            out.weight.iter_mut().for_each(|c| c.fill(0.0));
        }
        Some((last, [])) => sample(last, isa, wo, u, out),
        Some((last, rest)) => {
            let p = probabilities(&sum_estimate(rest, isa, wo), &estimate(last, isa, wo));
            mix_samples(
                wo,
                u,
                &p,
                |wo, u, out| sum_sample(rest, isa, wo, u, out),
                |wo, u, out| sample(last, isa, wo, u, out),
                |wo, wi, out| sum_pdf(rest, isa, wo, wi, out),
                |wo, wi, out| pdf(last, isa, wo, wi, out),
                |wi, wo, out| super::sum_batch(terms, isa, wi, wo, out),
                out,
            );
        }
    }
}

/// A layered material: the coat with probability `ρ̂_coat/(ρ̂_coat + T ρ̂_base)`, as
/// [`Layered`]'s sampler.
fn layered_sample(
    l: &LayeredMaterial,
    isa: Isa,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, 3>,
) {
    let (s, d) = layered_estimates(l, isa, wo);
    mix_samples(
        wo,
        u,
        &probabilities(&s, &d),
        |wo, u, out| sample(&l.coat, isa, wo, u, out),
        |wo, u, out| sample(&l.base, isa, wo, u, out),
        |wo, wi, out| pdf(&l.coat, isa, wo, wi, out),
        |wo, wi, out| pdf(&l.base, isa, wo, wi, out),
        |wi, wo, out| super::layered_batch(l, isa, wi, wo, out),
        out,
    );
}

/// `first_probability` per sample.
fn probabilities(ea: &[f32], eb: &[f32]) -> Vec<f32> {
    ea.iter()
        .zip(eb)
        .map(|(&a, &b)| first_probability(a, b))
        .collect()
}

/// The one-sample mixture of parts `a` (probability `p[j]`) and `b` over a block, step for
/// step `sample_pair`: both parts sampled with the split third number, the chosen sample
/// kept, its density `p·pa + (1 − p)·pb` and the material's value at it, then `finish`.
#[allow(clippy::too_many_arguments)]
fn mix_samples(
    wo: Directions<'_>,
    u: [&[f32]; 3],
    p: &[f32],
    sample_a: impl FnOnce(Directions<'_>, [&[f32]; 3], &mut SampleOut<'_, 3>),
    sample_b: impl FnOnce(Directions<'_>, [&[f32]; 3], &mut SampleOut<'_, 3>),
    pdf_a: impl FnOnce(Directions<'_>, Directions<'_>, &mut [f32]),
    pdf_b: impl FnOnce(Directions<'_>, Directions<'_>, &mut [f32]),
    eval: impl FnOnce(Directions<'_>, Directions<'_>, [&mut [f32]; 3]),
    out: &mut SampleOut<'_, 3>,
) {
    let n = wo.len();
    let (ua, ub): (Vec<f32>, Vec<f32>) =
        p.iter().zip(u[2]).map(|(&p, &u2)| split_u2(p, u2)).unzip();
    let (mut a, mut b) = (Samples::new(n), Samples::new(n));
    sample_a(wo, [u[0], u[1], &ua], &mut a.out());
    sample_b(wo, [u[0], u[1], &ub], &mut b.out());
    // The chosen direction (the normal on an invalid sample: `Sample::new`'s) and validity
    // (a sample is valid exactly where its density is > 0: `Sample::new`).
    let mut wi = [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]];
    let mut valid = vec![false; n];
    let (sa, sb): ([&[f32]; 4], [&[f32]; 4]) = (
        core::array::from_fn(|k| a.at(k)),
        core::array::from_fn(|k| b.at(k)),
    );
    for j in 0..n {
        let at = |s: &[&[f32]; 4]| (Vec3::new(s[0][j], s[1][j], s[2][j]), s[3][j] > 0.0);
        let (w, v) = choose_pair(p[j], u[2][j], at(&sa), at(&sb));
        [wi[0][j], wi[1][j], wi[2][j]] = [w.x, w.y, w.z];
        valid[j] = v;
    }
    let wi_dirs = Directions::new(&wi[0], &wi[1], &wi[2]);
    let (mut pa, mut pb) = (vec![0.0f32; n], vec![0.0f32; n]);
    pdf_a(wo, wi_dirs, &mut pa);
    pdf_b(wo, wi_dirs, &mut pb);
    let mut f = [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]];
    {
        let [f0, f1, f2] = &mut f;
        eval(wi_dirs, wo, [f0, f1, f2]);
    }
    for j in 0..n {
        let wo_j = Vec3::new(wo.x[j], wo.y[j], wo.z[j]);
        let wi_j = Vec3::new(wi[0][j], wi[1][j], wi[2][j]);
        let density = pdf_pair_of(p[j], wo_j, wi_j, pa[j], pb[j]);
        let s = finish(
            wi_j,
            density,
            [f[0][j], f[1][j], f[2][j]],
            valid[j] & (wo_j.z > 0.0),
        );
        (out.x[j], out.y[j], out.z[j], out.pdf[j]) = (s.wi.x, s.wi.y, s.wi.z, s.pdf);
        for c in 0..3 {
            out.weight[c][j] = s.weight[c];
        }
    }
}

/// The densities of a `Sum` or `Layered` material over the whole batch, block by block of
/// [`BLOCK`] pairs (`isa` available, the lengths equal: the caller checked).
pub(super) fn pdf_mixture(
    m: &Material<f32>,
    isa: Isa,
    wo: Directions<'_>,
    wi: Directions<'_>,
    out: &mut [f32],
) {
    for (k, out) in out.chunks_mut(BLOCK).enumerate() {
        let r = k * BLOCK..k * BLOCK + out.len();
        pdf(m, isa, wo.range(r.clone()), wi.range(r), out);
    }
}

/// The density of any material at `(wo[j], wi[j])` (`isa` available, the lengths equal).
fn pdf(m: &Material<f32>, isa: Isa, wo: Directions<'_>, wi: Directions<'_>, out: &mut [f32]) {
    match m {
        Material::Sum(terms) => sum_pdf(terms, isa, wo, wi, out),
        Material::Layered(l) => {
            let (s, d) = layered_estimates(l, isa, wo);
            pdf_mix(
                wo,
                wi,
                &probabilities(&s, &d),
                out,
                |out| pdf(&l.coat, isa, wo, wi, out),
                |out| pdf(&l.base, isa, wo, wi, out),
            );
        }
        leaf => {
            let _ = leaf.pdf_batch_f32(isa, wo, wi, out);
        }
    }
}

/// The density of `Sum(Sum(t₀, t₁), t₂)…` (`sum_pdf` in the parent module).
fn sum_pdf(
    terms: &[Material<f32>],
    isa: Isa,
    wo: Directions<'_>,
    wi: Directions<'_>,
    out: &mut [f32],
) {
    match terms.split_last() {
        None => out.fill(0.0),
        Some((last, [])) => pdf(last, isa, wo, wi, out),
        Some((last, rest)) => {
            let p = probabilities(&sum_estimate(rest, isa, wo), &estimate(last, isa, wo));
            pdf_mix(
                wo,
                wi,
                &p,
                out,
                |out| sum_pdf(rest, isa, wo, wi, out),
                |out| pdf(last, isa, wo, wi, out),
            );
        }
    }
}

/// `pdf_pair_of` per element from the parts' densities.
fn pdf_mix(
    wo: Directions<'_>,
    wi: Directions<'_>,
    p: &[f32],
    out: &mut [f32],
    pdf_a: impl FnOnce(&mut [f32]),
    pdf_b: impl FnOnce(&mut [f32]),
) {
    let n = out.len();
    let mut pb = vec![0.0f32; n];
    pdf_a(out);
    pdf_b(&mut pb);
    for j in 0..n {
        let wo_j = Vec3::new(wo.x[j], wo.y[j], wo.z[j]);
        let wi_j = Vec3::new(wi.x[j], wi.y[j], wi.z[j]);
        out[j] = pdf_pair_of(p[j], wo_j, wi_j, out[j], pb[j]);
    }
}

/// The albedo estimate of any material at each `wo[j]`.
fn estimate(m: &Material<f32>, isa: Isa, wo: Directions<'_>) -> Vec<f32> {
    match m {
        Material::Sum(terms) => sum_estimate(terms, isa, wo),
        Material::Layered(l) => {
            let (s, d) = layered_estimates(l, isa, wo);
            s.iter().zip(&d).map(|(s, d)| s + d).collect()
        }
        leaf => {
            let mut out = vec![0.0f32; wo.len()];
            let _ = leaf.estimate_batch_f32(isa, wo, &mut out);
            out
        }
    }
}

/// `((ρ̂₀ + ρ̂₁) + ρ̂₂) + …` (`sum_estimate` in the parent module); `0` if empty.
fn sum_estimate(terms: &[Material<f32>], isa: Isa, wo: Directions<'_>) -> Vec<f32> {
    let Some((first, rest)) = terms.split_first() else {
        return vec![0.0; wo.len()];
    };
    let mut acc = estimate(first, isa, wo);
    for t in rest {
        for (a, e) in acc.iter_mut().zip(estimate(t, isa, wo)) {
            *a += e;
        }
    }
    acc
}

/// `(ρ̂_coat, T ρ̂_base)` of a layered material, `T = coat_transmission` on the Fresnel form
/// of `isa`'s loops (it fuses).
fn layered_estimates(l: &LayeredMaterial, isa: Isa, wo: Directions<'_>) -> (Vec<f32>, Vec<f32>) {
    let s = estimate(&l.coat, isa, wo);
    let mut d = estimate(&l.base, isa, wo);
    macro_rules! weigh {
        ($k:ident) => {{
            let fresnel: AnyFresnel<$k> = l.fresnel.splat();
            for (j, d) in d.iter_mut().enumerate() {
                let w = Vec3::new($k(wo.x[j]), $k(wo.y[j]), $k(wo.z[j]));
                *d = (coat_transmission(&fresnel, w) * $k(*d)).0;
            }
        }};
    }
    if isa == Isa::Portable {
        for (j, d) in d.iter_mut().enumerate() {
            let w = Vec3::new(wo.x[j], wo.y[j], wo.z[j]);
            *d *= coat_transmission(&l.fresnel, w);
        }
    } else if batch::shares_divisions() {
        weigh!(F32FmaSharedDiv);
    } else {
        weigh!(F32Fma);
    }
    (s, d)
}
