//! Batch throughput on 64K direction pairs (structure of arrays, resident in L2), f32, one
//! core: the scalar loop, each wide lane width, and the run-time-dispatched batch path.
//!
//! Workloads (issue targets in parentheses):
//! * `ggx_schlick`: GGX Cook-Torrance, Schlick F, height-correlated Smith, one channel
//!   (≥ 1.0 G evaluations/s), plus a plain hand-written f32 version of the same formula to
//!   check that the generic scalar path (`scalar_f32`) costs nothing (ratio ≥ 0.95);
//! * `rough_conductor`: Mitsuba 3's `roughconductor` workload — isotropic GGX, separable
//!   Smith G1·G1, exact conductor Fresnel with a complex IOR per RGB channel, times cos θo
//!   (≥ 450 M evaluations/s); also with the conductor as `FittedConductor` (`batch_fitted*`);
//! * `normalized_blinn_phong`: the seed's normalized Blinn-Phong, diffuse + specular, one
//!   channel, with the exact `powf` and with `fast::pow_phong` (|relative error| ≤ 1e-5)
//!   (≥ 0.7 G evaluations/s);
//! * `multiscatter`: GGX + Schlick plain, with Kulla-Conty and with Turquin compensation;
//! * `material`: the run-time `Material` against the static model it holds (rough gold
//!   conductor, Lambert).
//!
//! Every workload runs as `scalar_f32` (one `eval` per pair in a plain loop), on each wide
//! lane width (`f32x4`, `f32x8`, `f32x16`: the model's `Splat`; on a default build these are
//! SSE2 registers), and through `batch::eval_with` / `eval_pipelined_with` on every
//! instruction set this CPU has (`batch/<Isa>`, `batch_pipelined/<Isa>`).
use std::hint::black_box;

use brdf::batch::{self, Directions, Isa, Pipelined};
use brdf::fast::{HardwareEstimate, NewtonSqrtRecip};
use brdf::fresnel::{Conductor, FittedConductor, Schlick};
use brdf::masking::{SmithHeightCorrelated, SmithSeparable};
use brdf::models::CookTorrance;
use brdf::ndf::{Ggx, GgxIsotropic};
use brdf::real::Splat;
use brdf::{Brdf, Real, Vec3, f32x4, f32x8, f32x16, ior};
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};

const N: usize = 1 << 16;

/// One stream of a benchmark (a coordinate of the directions, or an output channel): `N`
/// floats at a chosen offset within a 4 KiB page.
///
/// Why placed: a load whose address equals, in its low 12 bits, that of a store still in
/// flight waits for it ("4K aliasing"). Where the allocator happens to put the streams
/// decides whether the output store of one iteration aliases the input loads of the next
/// few, and that moved `batch/ggx_schlick` by 12 % on an Intel Xeon (Sapphire Rapids class)
/// between runs of the same binary. So every input starts at [`INPUT_OFFSET`] and every
/// output half a page away (a store aliases a load only 32 iterations later, long retired).
/// `BRDF_BENCH_LAYOUT=aliased` puts the outputs 128 bytes behind the inputs instead (the store
/// of iteration `j` aliases the loads of iteration `j + 2`): the layout's worst case.
struct Stream(&'static mut [f32]);

impl core::ops::Deref for Stream {
    type Target = [f32];
    fn deref(&self) -> &[f32] {
        self.0
    }
}

impl core::ops::DerefMut for Stream {
    fn deref_mut(&mut self) -> &mut [f32] {
        self.0
    }
}

/// The page offset of every input stream (bytes).
const INPUT_OFFSET: usize = 2048;

/// The page offset of every output stream (bytes): see [`Stream`].
fn output_offset() -> usize {
    match std::env::var("BRDF_BENCH_LAYOUT").as_deref() {
        Ok("aliased") => INPUT_OFFSET - 128,
        _ => 0,
    }
}

/// `data` copied into a new stream starting at `offset` bytes into a page (leaked: a
/// benchmark allocates a few).
fn stream(offset: usize, data: &[f32]) -> Stream {
    let buf: &'static mut [f32] = Vec::leak(vec![0.0f32; data.len() + 1024]);
    let start = (offset + 4096 - buf.as_ptr() as usize % 4096) % 4096 / 4;
    let s = &mut buf[start..start + data.len()];
    s.copy_from_slice(data);
    Stream(s)
}

/// An output stream of `N` zeros.
fn output() -> Stream {
    stream(output_offset(), &[0.0; N])
}

/// Deterministic directions on the upper hemisphere (xorshift, warped uniformly).
fn directions(seed: u32) -> [Stream; 3] {
    let mut s = seed;
    let mut u = || {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        s as f32 / u32::MAX as f32
    };
    let (mut x, mut y, mut z) = (vec![0.0; N], vec![0.0; N], vec![0.0; N]);
    for i in 0..N {
        let (c, phi) = (u(), u() * core::f32::consts::TAU);
        let r = (1.0 - c * c).max(0.0).sqrt();
        (x[i], y[i], z[i]) = (r * phi.cos(), r * phi.sin(), c);
    }
    [x, y, z].map(|v| stream(INPUT_OFFSET, &v))
}

/// The GGX + Schlick + height-correlated Smith formula written by hand for `f32`, the way an
/// engine would: the reference for "generic costs nothing".
#[inline(always)]
fn ggx_by_hand(wi: [f32; 3], wo: [f32; 3], alpha: f32, f0: f32) -> f32 {
    let (ci, co) = (wi[2], wo[2]);
    if ci <= 0.0 || co <= 0.0 {
        return 0.0;
    }
    let h = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
    let len = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
    let cos_d = (0.5 * len).min(1.0);
    let ch = h[2] / len;
    let a2 = alpha * alpha;
    let t = ch * ch * (a2 - 1.0) + 1.0;
    let d = a2 / (core::f32::consts::PI * t * t);
    let li = co * (ci * ci * (1.0 - a2) + a2).sqrt();
    let lo = ci * (co * co * (1.0 - a2) + a2).sqrt();
    let v = 0.5 / (li + lo);
    let m = 1.0 - cos_d;
    let m2 = m * m;
    let f = f0 + (1.0 - f0) * m2 * m2 * m;
    d * v * f
}

/// The same formula with the horizon test moved to the end (a select instead of an early
/// return): what an engine writes when it wants the loop vectorized.
#[inline(always)]
fn ggx_by_hand_branchless(wi: [f32; 3], wo: [f32; 3], alpha: f32, f0: f32) -> f32 {
    let (ci, co) = (wi[2].max(0.0), wo[2].max(0.0));
    let h = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
    let len = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).max(1e-30).sqrt();
    let cos_d = (0.5 * len).min(1.0);
    let ch = h[2] / len;
    let a2 = alpha * alpha;
    let t = ch * ch * (a2 - 1.0) + 1.0;
    let d = a2 / (core::f32::consts::PI * t * t);
    let li = co * (ci * ci * (1.0 - a2) + a2).sqrt();
    let lo = ci * (co * co * (1.0 - a2) + a2).sqrt();
    let v = 0.5 / (li + lo).max(1e-30);
    let m = 1.0 - cos_d;
    let m2 = m * m;
    let f = f0 + (1.0 - f0) * m2 * m2 * m;
    let r = d * v * f;
    if wi[2] > 0.0 && wo[2] > 0.0 { r } else { 0.0 }
}

/// Evaluates a lane-typed model over the SoA arrays, `L::LANES` pairs at a time, writing
/// every channel.
fn lanes<L: Real<Scalar = f32>, B: Brdf<L, C>, const C: usize>(
    b: &B,
    wi: &[Stream; 3],
    wo: &[Stream; 3],
    out: &mut [Stream; C],
) {
    let w = L::LANES;
    for k in 0..N / w {
        let at = |v: &Stream| L::from_fn(|l| v[k * w + l]);
        let f = b.eval(
            Vec3::new(at(&wi[0]), at(&wi[1]), at(&wi[2])),
            Vec3::new(at(&wo[0]), at(&wo[1]), at(&wo[2])),
        );
        for c in 0..C {
            for l in 0..w {
                out[c][k * w + l] = f[c].lane(l);
            }
        }
    }
}

/// The scalar `f32` path: one `eval` per pair in a plain loop (what a renderer's shading loop
/// does), every channel written.
fn scalar<B: Brdf<f32, C>, const C: usize>(
    b: &B,
    wi: &[Stream; 3],
    wo: &[Stream; 3],
    out: &mut [Stream; C],
) {
    let (ix, iy, iz) = (&wi[0][..N], &wi[1][..N], &wi[2][..N]);
    let (ox, oy, oz) = (&wo[0][..N], &wo[1][..N], &wo[2][..N]);
    for i in 0..N {
        let f = b.eval(
            Vec3::new(ix[i], iy[i], iz[i]),
            Vec3::new(ox[i], oy[i], oz[i]),
        );
        for c in 0..C {
            out[c][i] = f[c];
        }
    }
}

/// Benchmarks `model` (built on `f32`) as the scalar loop and on each wide lane width (its
/// `Splat` to `f32x4`, `f32x8`, `f32x16`), as `scalar_f32`, `f32x4`, ….
fn bench_scalar_and_lanes<B, const C: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    model: &B,
    wi: &[Stream; 3],
    wo: &[Stream; 3],
    out: &mut [Stream; C],
) where
    B: Brdf<f32, C> + Splat,
    B::On<f32x4>: Brdf<f32x4, C>,
    B::On<f32x8>: Brdf<f32x8, C>,
    B::On<f32x16>: Brdf<f32x16, C>,
{
    g.bench_function("scalar_f32", |b| {
        b.iter(|| scalar(black_box(model), wi, wo, out))
    });
    let (m4, m8, m16) = (
        model.splat::<f32x4>(),
        model.splat::<f32x8>(),
        model.splat::<f32x16>(),
    );
    g.bench_function("f32x4", |b| b.iter(|| lanes(black_box(&m4), wi, wo, out)));
    g.bench_function("f32x8", |b| b.iter(|| lanes(black_box(&m8), wi, wo, out)));
    g.bench_function("f32x16", |b| b.iter(|| lanes(black_box(&m16), wi, wo, out)));
}

/// One batch entry point: `batch::eval_with` or `batch::eval_pipelined_with`.
type Entry<B, const C: usize> =
    fn(Isa, &B, Directions<'_>, Directions<'_>, [&mut [f32]; C]) -> Result<(), batch::Unavailable>;

/// Benchmarks `entry` on every instruction set this CPU has, as `name/<Isa>`.
fn bench_isas<B, const C: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    entry: Entry<B, C>,
    brdf: &B,
    wi: &[Stream; 3],
    wo: &[Stream; 3],
    out: &mut [Stream; C],
) {
    for isa in Isa::ALL.into_iter().filter(|i| i.is_available()) {
        g.bench_with_input(
            BenchmarkId::new(name, format!("{isa:?}")),
            &isa,
            |b, &isa| {
                b.iter(|| {
                    let slices = out.each_mut().map(|c| &mut **c);
                    entry(
                        isa,
                        black_box(brdf),
                        Directions::new(&wi[0], &wi[1], &wi[2]),
                        Directions::new(&wo[0], &wo[1], &wo[2]),
                        slices,
                    )
                    .unwrap()
                })
            },
        );
    }
}

/// The hand-written loop: `body` over the re-sliced SoA inputs (no bounds checks).
fn bench_by_hand(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    wi: &[Stream; 3],
    wo: &[Stream; 3],
    out: &mut [f32],
    body: impl Fn([f32; 3], [f32; 3], f32, f32) -> f32,
) {
    g.bench_function(name, |b| {
        b.iter(|| {
            let (alpha, f0) = (black_box(0.3f32), black_box(0.04f32));
            let o = &mut out[..N];
            let (ix, iy, iz) = (&wi[0][..N], &wi[1][..N], &wi[2][..N]);
            let (ox, oy, oz) = (&wo[0][..N], &wo[1][..N], &wo[2][..N]);
            for i in 0..N {
                o[i] = body([ix[i], iy[i], iz[i]], [ox[i], oy[i], oz[i]], alpha, f0);
            }
            black_box(&*o);
        })
    });
}

/// The memory ceiling of a batch: read the six direction components of every pair and write
/// `C` outputs (their sum), in a loop LLVM vectorizes with the build's baseline — the traffic
/// of a batch evaluation with no arithmetic. 64K pairs are 1.5 MiB of input, more than one
/// core's L2 on some machines (1 MiB on Zen 4/5), so this can be an L3 bound.
fn bench_memory_ceiling(c: &mut Criterion) {
    let (wi, wo) = (directions(1), directions(7));
    let mut g = c.benchmark_group("batch/memory_ceiling");
    g.throughput(Throughput::Elements(N as u64));
    fn run<const C: usize>(wi: &[Stream; 3], wo: &[Stream; 3], out: &mut [Stream; C]) {
        let (ix, iy, iz) = (&wi[0][..N], &wi[1][..N], &wi[2][..N]);
        let (ox, oy, oz) = (&wo[0][..N], &wo[1][..N], &wo[2][..N]);
        let mut out = out.each_mut().map(|o| &mut o[..N]);
        for i in 0..N {
            let s = ix[i] + iy[i] + iz[i] + ox[i] + oy[i] + oz[i];
            for (c, o) in out.iter_mut().enumerate() {
                o[i] = s + c as f32;
            }
        }
    }
    let mut out1 = [output()];
    g.bench_function("read6_write1", |b| {
        b.iter(|| run(black_box(&wi), &wo, &mut out1))
    });
    let mut out3 = [output(), output(), output()];
    g.bench_function("read6_write3", |b| {
        b.iter(|| run(black_box(&wi), &wo, &mut out3))
    });
    g.finish();
}

fn bench_ggx_schlick(c: &mut Criterion) {
    let (wi, wo) = (directions(1), directions(7));
    let mut out = output();
    let mut g = c.benchmark_group("batch/ggx_schlick");
    g.throughput(Throughput::Elements(N as u64));
    // The same loop shape for the hand-written bodies and the crate's generic one
    // (`scalar_f32` below; re-sliced, so no bounds checks): the only difference is the body.
    // LLVM treats both alike (here: SSE2-vectorized on the default target), so the ratio is
    // the cost of genericity.
    let ct = CookTorrance::new(
        GgxIsotropic::<f32>::new(0.3).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    // Each function item is its own type, so the loop is monomorphized and inlined for it.
    bench_by_hand(&mut g, "hand_written_f32", &wi, &wo, &mut out, ggx_by_hand);
    bench_by_hand(
        &mut g,
        "hand_written_branchless_f32",
        &wi,
        &wo,
        &mut out,
        ggx_by_hand_branchless,
    );
    let mut out1 = [out];
    bench_scalar_and_lanes(&mut g, &ct, &wi, &wo, &mut out1);
    bench_isas(&mut g, "batch", batch::eval_with, &ct, &wi, &wo, &mut out1);
    let piped = batch::eval_pipelined_with;
    bench_isas(&mut g, "batch_pipelined", piped, &ct, &wi, &wo, &mut out1);
    // The half vector and the final division by refined estimates (issue 14).
    let newton = ct.with_sqrt::<NewtonSqrtRecip<3, 3>>();
    bench_isas(
        &mut g,
        "batch_newton_sqrt_recip_3_3",
        batch::eval_with,
        &newton,
        &wi,
        &wo,
        &mut out1,
    );
    // The half vector and the final division by the hardware estimates + one refinement
    // step: explicit 16-lane registers on Avx512, the exact path elsewhere (issue 14).
    let estimate = ct.with_sqrt::<HardwareEstimate>();
    bench_isas(
        &mut g,
        "batch_hardware_estimate",
        batch::eval_with,
        &estimate,
        &wi,
        &wo,
        &mut out1,
    );
    // The anisotropy-capable `Ggx` type with αx = αy: the price of not specializing.
    let aniso = CookTorrance::new(
        Ggx::<f32>::new(0.3).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    bench_isas(
        &mut g,
        "batch_anisotropic_type",
        batch::eval_with,
        &aniso,
        &wi,
        &wo,
        &mut out1,
    );
    g.finish();
}

/// Mitsuba's roughconductor: `f · cos θo` per RGB channel.
struct TimesCos<B>(B);
impl<R: Real, B: Brdf<R, 3>> Brdf<R, 3> for TimesCos<B> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; 3] {
        let f = self.0.eval(wi, wo);
        [f[0] * wo.z, f[1] * wo.z, f[2] * wo.z]
    }
    fn properties(&self) -> brdf::models::Properties {
        self.0.properties()
    }
}
impl<B: Splat> Splat for TimesCos<B> {
    type On<L: Real> = TimesCos<B::On<L>>;
    const EXPLICIT_LANES: bool = B::EXPLICIT_LANES;
    fn splat<L: Real>(&self) -> Self::On<L> {
        TimesCos(self.0.splat())
    }
}
impl<K: Real<Scalar = f32, Mask = bool>, B: Pipelined<K, 3>> Pipelined<K, 3> for TimesCos<B> {
    #[inline(always)]
    fn eval_passes(&self, wi: Directions<'_>, wo: Directions<'_>, mut out: [&mut [f32]; 3]) {
        self.0.eval_passes(wi, wo, out.each_mut().map(|o| &mut **o));
        for o in out {
            for (o, z) in o.iter_mut().zip(wo.z) {
                *o *= z;
            }
        }
    }
}

fn bench_rough_conductor(c: &mut Criterion) {
    let (wi, wo) = (directions(3), directions(11));
    let mut out = [output(), output(), output()];
    let m = TimesCos(CookTorrance::new(
        GgxIsotropic::<f32>::new(0.2).unwrap(),
        Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap(),
        SmithSeparable,
    ));
    let mut g = c.benchmark_group("batch/rough_conductor");
    g.throughput(Throughput::Elements(N as u64));
    bench_scalar_and_lanes(&mut g, &m, &wi, &wo, &mut out);
    bench_isas(&mut g, "batch", batch::eval_with, &m, &wi, &wo, &mut out);
    let piped = batch::eval_pipelined_with;
    bench_isas(&mut g, "batch_pipelined", piped, &m, &wi, &wo, &mut out);
    // The conductor's channels sharing one division where batch::shares_divisions() (Intel).
    let shared = TimesCos(CookTorrance::new(
        m.0.ndf,
        m.0.fresnel.share_divisions().unwrap(),
        SmithSeparable,
    ));
    bench_isas(
        &mut g,
        "batch_shared_division",
        batch::eval_with,
        &shared,
        &wi,
        &wo,
        &mut out,
    );
    // Every square root and division of the geometry and the conductor by refined estimates.
    type Fast = NewtonSqrtRecip<3, 3>;
    let fast = TimesCos(
        CookTorrance::new(m.0.ndf, m.0.fresnel.with_policy::<Fast>(), SmithSeparable)
            .with_sqrt::<Fast>(),
    );
    bench_isas(
        &mut g,
        "batch_newton_sqrt_recip_3_3",
        batch::eval_with,
        &fast,
        &wi,
        &wo,
        &mut out,
    );
    // The same by the hardware estimates (explicit 16-lane registers on Avx512).
    let estimate = TimesCos(
        CookTorrance::new(
            m.0.ndf,
            m.0.fresnel.with_policy::<HardwareEstimate>(),
            SmithSeparable,
        )
        .with_sqrt::<HardwareEstimate>(),
    );
    bench_isas(
        &mut g,
        "batch_hardware_estimate",
        batch::eval_with,
        &estimate,
        &wi,
        &wo,
        &mut out,
    );
    // The conductor fitted as a piecewise quintic (no square root or division in the
    // Fresnel term), with the exact and the estimated geometry.
    let fitted = FittedConductor::from_conductor(&m.0.fresnel).unwrap();
    let fit = TimesCos(CookTorrance::new(m.0.ndf, fitted, SmithSeparable));
    bench_isas(
        &mut g,
        "batch_fitted",
        batch::eval_with,
        &fit,
        &wi,
        &wo,
        &mut out,
    );
    let fit_estimate = TimesCos(fit.0.with_sqrt::<HardwareEstimate>());
    let name = "batch_fitted_hardware_estimate";
    bench_isas(
        &mut g,
        name,
        batch::eval_with,
        &fit_estimate,
        &wi,
        &wo,
        &mut out,
    );
    g.finish();
}

fn bench_normalized_blinn_phong(c: &mut Criterion) {
    use brdf::fast::FastPow;
    use brdf::models::NormalizedBlinnPhong;
    use brdf::normalization::Normalization;
    let (wi, wo) = (directions(5), directions(13));
    let out = output();
    let exact = NormalizedBlinnPhong::new(
        [0.5_f32],
        0.5,
        [0.04],
        64.0,
        Normalization::TRI_ACE_2009_FIT,
    )
    .unwrap();
    let fast = exact.with_pow::<FastPow>();
    let mut g = c.benchmark_group("batch/normalized_blinn_phong");
    g.throughput(Throughput::Elements(N as u64));
    let mut out = [out];
    bench_scalar_and_lanes(&mut g, &fast, &wi, &wo, &mut out);
    bench_isas(
        &mut g,
        "exact_pow",
        batch::eval_with,
        &exact,
        &wi,
        &wo,
        &mut out,
    );
    bench_isas(
        &mut g,
        "fast_pow",
        batch::eval_with,
        &fast,
        &wi,
        &wo,
        &mut out,
    );
    let piped = batch::eval_pipelined_with;
    bench_isas(
        &mut g,
        "fast_pow_pipelined",
        piped,
        &fast,
        &wi,
        &wo,
        &mut out,
    );
    g.finish();
}

/// Multiple-scattering compensation (issue 13): the GGX + Schlick + height-correlated Smith
/// lobe of `ggx_schlick` (α = 0.5, one channel) plain, with Kulla-Conty's added lobe (two
/// 20-term Chebyshev series: two divisions, 38 fused steps) and with Turquin's factor (one
/// series, one more division), as the scalar loop and through `batch::eval_with`.
fn bench_multiscatter(c: &mut Criterion) {
    use brdf::models::{KullaConty, Turquin};
    let (wi, wo) = (directions(1), directions(7));
    let mut out = [output()];
    let mut g = c.benchmark_group("batch/multiscatter");
    g.throughput(Throughput::Elements(N as u64));
    let ct = CookTorrance::new(
        GgxIsotropic::<f32>::new(0.5).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    let kc = KullaConty::<_, f32, 1>::new(ct).unwrap();
    let tq = Turquin::<_, f32, 1>::new(ct).unwrap();
    g.bench_function("plain/scalar_f32", |b| {
        b.iter(|| scalar(black_box(&ct), &wi, &wo, &mut out))
    });
    g.bench_function("kulla_conty/scalar_f32", |b| {
        b.iter(|| scalar(black_box(&kc), &wi, &wo, &mut out))
    });
    g.bench_function("turquin/scalar_f32", |b| {
        b.iter(|| scalar(black_box(&tq), &wi, &wo, &mut out))
    });
    bench_isas(&mut g, "plain", batch::eval_with, &ct, &wi, &wo, &mut out);
    bench_isas(
        &mut g,
        "kulla_conty",
        batch::eval_with,
        &kc,
        &wi,
        &wo,
        &mut out,
    );
    bench_isas(&mut g, "turquin", batch::eval_with, &tq, &wi, &wo, &mut out);
    g.finish();
}

/// The run-time `Material` against the static model it holds (the rough gold conductor of
/// `rough_conductor`, without the cosine; Lambert; a plastic as a sum and as a layered
/// model), through `batch::eval_with`: the material matches on its variant once per call
/// and runs the model it holds (a Cook-Torrance with run-time parts on explicit lanes).
fn bench_material(c: &mut Criterion) {
    use brdf::fresnel::AnyFresnel;
    use brdf::masking::AnyMasking;
    use brdf::material::Material;
    use brdf::models::Lambert;
    use brdf::ndf::AnyNdf;
    let (wi, wo) = (directions(3), directions(11));
    let mut out = [output(), output(), output()];
    let mut g = c.benchmark_group("batch/material");
    g.throughput(Throughput::Elements(N as u64));
    let gold = CookTorrance::new(
        GgxIsotropic::<f32>::new(0.2).unwrap(),
        Conductor::<f32, 3>::from_preset(ior::Preset::Gold).unwrap(),
        SmithSeparable,
    );
    let runtime = Material::from(CookTorrance::new(
        AnyNdf::from(gold.ndf),
        AnyFresnel::from(gold.fresnel),
        AnyMasking::from(gold.masking),
    ));
    bench_isas(
        &mut g,
        "gold_static",
        batch::eval_with,
        &gold,
        &wi,
        &wo,
        &mut out,
    );
    bench_isas(
        &mut g,
        "gold_material",
        batch::eval_with,
        &runtime,
        &wi,
        &wo,
        &mut out,
    );
    // The same with the channels sharing one division (where `batch::shares_divisions()`):
    // the static model on the one-lane loop, the material on explicit lanes.
    let shared = CookTorrance::new(
        gold.ndf,
        gold.fresnel.share_divisions().unwrap(),
        gold.masking,
    );
    let runtime_shared = Material::from(CookTorrance::new(
        AnyNdf::from(shared.ndf),
        AnyFresnel::from(shared.fresnel),
        AnyMasking::from(shared.masking),
    ));
    bench_isas(
        &mut g,
        "gold_shared_static",
        batch::eval_with,
        &shared,
        &wi,
        &wo,
        &mut out,
    );
    bench_isas(
        &mut g,
        "gold_shared_material",
        batch::eval_with,
        &runtime_shared,
        &wi,
        &wo,
        &mut out,
    );
    let lambert = Lambert::<f32, 3>::new([0.2, 0.3, 0.4]).unwrap();
    let runtime_lambert = Material::from(lambert);
    bench_isas(
        &mut g,
        "lambert_static",
        batch::eval_with,
        &lambert,
        &wi,
        &wo,
        &mut out,
    );
    bench_isas(
        &mut g,
        "lambert_material",
        batch::eval_with,
        &runtime_lambert,
        &wi,
        &wo,
        &mut out,
    );
    // A plastic: Lambert + a GGX lobe with a dielectric's Fresnel, as the static `Sum` and
    // as a `Sum` material of two leaf materials (each term over blocks, then added).
    let coat = CookTorrance::new(
        GgxIsotropic::<f32>::new(0.2).unwrap(),
        brdf::fresnel::Dielectric::<f32>::new(1.5)
            .unwrap()
            .channels::<3>(),
        SmithHeightCorrelated,
    );
    let coat_material = Material::from(CookTorrance::new(
        AnyNdf::from(coat.ndf),
        AnyFresnel::from(coat.fresnel),
        AnyMasking::from(coat.masking),
    ));
    bench_isas(
        &mut g,
        "coat_static",
        batch::eval_with,
        &coat,
        &wi,
        &wo,
        &mut out,
    );
    bench_isas(
        &mut g,
        "coat_material",
        batch::eval_with,
        &coat_material,
        &wi,
        &wo,
        &mut out,
    );
    // The same coat with the hardware-estimate policy (`sqrt = "hardware_estimate"` in a
    // material file), static and as a material.
    let coat_estimate = coat.with_sqrt::<HardwareEstimate>();
    bench_isas(
        &mut g,
        "coat_estimate_static",
        batch::eval_with,
        &coat_estimate,
        &wi,
        &wo,
        &mut out,
    );
    let coat_estimate_material = Material::from(
        CookTorrance::new(
            AnyNdf::from(coat.ndf),
            AnyFresnel::from(coat.fresnel),
            AnyMasking::from(coat.masking),
        )
        .with_sqrt::<HardwareEstimate>(),
    );
    bench_isas(
        &mut g,
        "coat_estimate_material",
        batch::eval_with,
        &coat_estimate_material,
        &wi,
        &wo,
        &mut out,
    );
    let plastic = brdf::models::Sum::new(lambert, coat);
    let runtime = Material::Sum(vec![
        runtime_lambert.clone(),
        Material::from(CookTorrance::new(
            AnyNdf::from(coat.ndf),
            AnyFresnel::from(coat.fresnel),
            AnyMasking::from(coat.masking),
        )),
    ]);
    bench_isas(
        &mut g,
        "plastic_static",
        batch::eval_with,
        &plastic,
        &wi,
        &wo,
        &mut out,
    );
    bench_isas(
        &mut g,
        "plastic_material",
        batch::eval_with,
        &runtime,
        &wi,
        &wo,
        &mut out,
    );
    // The same parts layered: the coat over the Lambert base, seen through the coat's
    // dielectric Fresnel, static and as a `Layered` material (parts in passes over blocks).
    let dielectric = brdf::fresnel::Dielectric::<f32>::new(1.5)
        .unwrap()
        .channels::<3>();
    let layered = brdf::models::Layered::new(lambert, coat, dielectric);
    let runtime = Material::Layered(Box::new(brdf::models::Layered::new(
        runtime_lambert,
        Material::from(CookTorrance::new(
            AnyNdf::from(coat.ndf),
            AnyFresnel::from(coat.fresnel),
            AnyMasking::from(coat.masking),
        )),
        AnyFresnel::from(dielectric),
    )));
    bench_isas(
        &mut g,
        "layered_static",
        batch::eval_with,
        &layered,
        &wi,
        &wo,
        &mut out,
    );
    bench_isas(
        &mut g,
        "layered_material",
        batch::eval_with,
        &runtime,
        &wi,
        &wo,
        &mut out,
    );
    g.finish();
}

criterion_group!(
    benches,
    bench_memory_ceiling,
    bench_ggx_schlick,
    bench_rough_conductor,
    bench_normalized_blinn_phong,
    bench_multiscatter,
    bench_material
);
criterion_main!(benches);
