//! The crate half of the Mitsuba 3 peer benchmark (`benches/peers/run.sh` builds and runs
//! it): times [`brdf::batch::eval`] on Mitsuba's `roughconductor` workload — GGX, separable
//! Smith `G1·G1`, exact conductor Fresnel per RGB channel — over the direction pairs of a
//! pairs file, and writes the values and the timing.
//!
//! Mitsuba's `eval` returns `f · cos θ` of the direction it calls `wo` and samples, the one
//! towards the light — in this crate's naming `wi`. So the workload here is
//! `f(wi, wo) · wi.z` ([`TimesCosThetaI`]); the pairs file stores `wi` (light) and `wo`
//! (viewer) in this crate's naming (`benches/peers/peers.py` documents the format).
//!
//! `--mode sample` times [`brdf::batch::sample`] instead, on the viewer directions `wo` and
//! the uniforms `u0, u1` of the pairs file (Mitsuba's `sample2`; `uc` is passed as the third
//! uniform, which a single lobe ignores), with the visible-normal sampler (`--strategy vndf`,
//! default, as Mitsuba's `sample_visible`) or the crate's default spherical caps
//! (`--strategy caps`), and writes `wi` (3 arrays), the density and the weight
//! `f·cos θi / pdf` (3 arrays) as Mitsuba's `sample` half does.
//!
//! `--ndf isotropic` (default) runs `CookTorrance<GgxIsotropic, Conductor<3>, SmithSeparable>`,
//! `--ndf ggx` the same on the anisotropy-capable `Ggx` (with equal α, as Mitsuba's GGX).
//! Timing: `--warmup` untimed calls, then `--reps` calls each timed on its own (wall clock);
//! the timing file gives the median and the best.
//!
//! ```sh
//! cargo build --release -p brdf-tools --bin peer_roughconductor
//! bash benches/peers/run.sh   # generates the pairs and runs this program
//! ```
use std::hint::black_box;
use std::io::{Read, Write};
use std::time::Instant;
use std::{fs, process};

use brdf::batch::{self, BatchBrdf, BatchSample, Directions, Isa, SampleOut};
use brdf::fast::{ExactSqrt, HardwareEstimate, NewtonSqrtRecip};
use brdf::fresnel::{Conductor, FittedConductor};
use brdf::masking::SmithSeparable;
use brdf::models::{CookTorrance, Properties};
use brdf::ndf::{Ggx, GgxIsotropic};
use brdf::real::Splat;
use brdf::sampling::{SphericalCaps, VisibleNormals};
use brdf::{Brdf, Real, Vec3};

const PAIRS_MAGIC: &[u8; 8] = b"BRDFPR01";
const VALUES_MAGIC: &[u8; 8] = b"BRDFVL01";
/// Arrays of a pairs file: wi.xyz, wo.xyz, uc, u0, u1.
const PAIR_ARRAYS: usize = 9;

/// `f(wi, wo) · cos θi` per channel: the value Mitsuba's `eval` returns (its `wo` is `wi`
/// here).
#[derive(Clone, Copy, Debug)]
struct TimesCosThetaI<B>(B);

impl<R: Real, B: Brdf<R, 3>> Brdf<R, 3> for TimesCosThetaI<B> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; 3] {
        let f = self.0.eval(wi, wo);
        [f[0] * wi.z, f[1] * wi.z, f[2] * wi.z]
    }
    fn properties(&self) -> Properties {
        self.0.properties()
    }
}

impl<B: Splat> Splat for TimesCosThetaI<B> {
    type On<L: Real> = TimesCosThetaI<B::On<L>>;
    // A wrapper forwards its model's choice, or batch::eval would not see it.
    const EXPLICIT_LANES: bool = B::EXPLICIT_LANES;
    fn splat<L: Real>(&self) -> Self::On<L> {
        TimesCosThetaI(self.0.splat())
    }
}

const USAGE: &str = "usage: peer_roughconductor --pairs FILE --values OUT --timing OUT.json \\
    --alpha A --eta R,G,B --k R,G,B [--ndf isotropic|ggx] [--policy exact|shared|newton|estimate|estimate-shared|fit|estimate-fit]
    [--mode eval|sample] [--strategy vndf|caps] [--isa detect|portable|avx2|avx512]
    [--reps N] [--warmup N]

Times brdf::batch::eval on Mitsuba's roughconductor workload over the pairs of FILE (written
by benches/peers/peers.py gen), writes the values (3 channels) to OUT and the timing to
OUT.json. --policy newton takes the half vector, the final division and the conductor's
square roots and divisions by brdf::fast::NewtonSqrtRecip<3, 3>, --policy estimate by
brdf::fast::HardwareEstimate (vrsqrt14ps/vrcp14ps + one step on Isa::Avx512, exact
elsewhere); --policy fit replaces the exact conductor by brdf::fresnel::FittedConductor
(estimate-fit: with HardwareEstimate); --policy shared gives the
conductor SharedDivision (one division for the three channels where
brdf::batch::shares_divisions(), e.g. on Intel); --policy estimate-shared, both (explicit
lanes sharing the division); default: exact.
--mode sample times brdf::batch::sample on the viewer directions and uniforms of FILE
(--strategy vndf: visible normals, as Mitsuba; caps: the crate's default spherical caps;
--policy exact, shared, estimate, estimate-shared or fit) and writes wi (3 arrays), pdf and the weight (3 arrays). --isa picks the batch kernel
(default: brdf::batch::Isa::detect()). Run by benches/peers/run.sh.";

/// The command line.
struct Args {
    pairs: String,
    values: String,
    timing: String,
    alpha: f32,
    eta: [f32; 3],
    k: [f32; 3],
    ndf: String,
    policy: String,
    mode: String,
    strategy: String,
    isa: Isa,
    reps: usize,
    warmup: usize,
}

fn fail(msg: impl std::fmt::Display) -> ! {
    eprintln!("peer_roughconductor: {msg}");
    process::exit(2)
}

/// A number, or exit with the offending text.
fn number<T: std::str::FromStr<Err: std::fmt::Display>>(s: &str) -> T {
    s.trim()
        .parse()
        .unwrap_or_else(|e| fail(format!("{s:?}: {e}")))
}

/// Three comma-separated numbers.
fn rgb(s: &str) -> [f32; 3] {
    let v: Vec<f32> = s.split(',').map(number).collect();
    v.try_into()
        .unwrap_or_else(|_| fail(format!("{s:?}: expected three comma-separated numbers")))
}

fn args() -> Args {
    let a = brdf_tools::Args::parse(
        &[
            "--pairs",
            "--values",
            "--timing",
            "--alpha",
            "--eta",
            "--k",
            "--ndf",
            "--policy",
            "--mode",
            "--strategy",
            "--isa",
            "--reps",
            "--warmup",
        ],
        &[],
        USAGE,
    );
    let required = |name: &str| {
        a.value(name)
            .unwrap_or_else(|| fail(format!("{name} is required\n\n{USAGE}")))
    };
    let args = Args {
        pairs: required("--pairs").into(),
        values: required("--values").into(),
        timing: required("--timing").into(),
        alpha: number(required("--alpha")),
        eta: rgb(required("--eta")),
        k: rgb(required("--k")),
        ndf: a.value("--ndf").unwrap_or("isotropic").into(),
        policy: a.value("--policy").unwrap_or("exact").into(),
        mode: a.value("--mode").unwrap_or("eval").into(),
        strategy: a.value("--strategy").unwrap_or("vndf").into(),
        isa: match a.value("--isa").unwrap_or("detect") {
            "detect" => Isa::detect(),
            "portable" => Isa::Portable,
            "avx2" => Isa::Avx2Fma,
            "avx512" => Isa::Avx512,
            other => fail(format!(
                "--isa {other:?}: expected detect, portable, avx2 or avx512"
            )),
        },
        reps: a.value("--reps").map_or(1000, number),
        warmup: a.value("--warmup").map_or(20, number),
    };
    if args.reps == 0 {
        fail("--reps must be positive");
    }
    if !args.isa.is_available() {
        fail(format!("--isa {:?} is not available on this CPU", args.isa));
    }
    args
}

/// The arrays of a pairs file.
fn read_pairs(path: &str) -> Vec<Vec<f32>> {
    let mut bytes = Vec::new();
    fs::File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .unwrap_or_else(|e| fail(format!("{path}: {e}")));
    if bytes.len() < 16 || &bytes[..8] != PAIRS_MAGIC {
        fail(format!("{path}: not a pairs file"));
    }
    let n = u64::from_le_bytes(bytes[8..16].try_into().unwrap()) as usize;
    let body = &bytes[16..];
    if body.len() != n * PAIR_ARRAYS * 4 {
        fail(format!("{path}: expected {} floats", n * PAIR_ARRAYS));
    }
    body.chunks_exact(n * 4)
        .map(|a| {
            a.chunks_exact(4)
                .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
                .collect()
        })
        .collect()
}

fn write_values(path: &str, channels: &[Vec<f32>]) {
    let mut out = Vec::with_capacity(24 + channels.len() * channels[0].len() * 4);
    out.extend_from_slice(VALUES_MAGIC);
    out.extend_from_slice(&(channels[0].len() as u64).to_le_bytes());
    out.extend_from_slice(&(channels.len() as u64).to_le_bytes());
    for c in channels {
        for v in c {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    fs::File::create(path)
        .and_then(|mut f| f.write_all(&out))
        .unwrap_or_else(|e| fail(format!("{path}: {e}")));
}

/// Per-repetition wall times (s) of `batch::eval` over all pairs, after `warmup` untimed
/// calls; leaves the last values in `out`.
fn time_eval<B: BatchBrdf<3>>(
    m: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: &mut [Vec<f32>; 3],
    a: &Args,
) -> Vec<f64> {
    let run = |out: &mut [Vec<f32>; 3]| {
        let [r, g, b] = out;
        // Available: checked when the arguments were read.
        let _ = batch::eval_with(a.isa, black_box(m), black_box(wi), black_box(wo), [r, g, b]);
        black_box(&*out);
    };
    for _ in 0..a.warmup {
        run(out);
    }
    (0..a.reps)
        .map(|_| {
            let t = Instant::now();
            run(out);
            t.elapsed().as_secs_f64()
        })
        .collect()
}

/// Per-repetition wall times (s) of `batch::sample` over all pairs (viewer directions `wo`,
/// uniforms `u`), after `warmup` untimed calls; leaves the last samples in `out`
/// (`wi.x, wi.y, wi.z, pdf, weight r, g, b`).
fn time_sample<B: BatchSample<3>>(
    m: &B,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut [Vec<f32>; 7],
    a: &Args,
) -> Vec<f64>
where
    B::Fused: brdf::SampleBrdf<brdf::real::F32Fma, 3>,
    B::SharedDiv: brdf::SampleBrdf<brdf::real::F32FmaSharedDiv, 3>,
{
    let run = |out: &mut [Vec<f32>; 7]| {
        let [x, y, z, pdf, r, g, b] = out;
        let mut s = SampleOut {
            x,
            y,
            z,
            pdf,
            weight: [r, g, b],
        };
        // Available: checked when the arguments were read.
        let _ = batch::sample_with(a.isa, black_box(m), black_box(wo), black_box(u), &mut s);
        black_box(&*out);
    };
    for _ in 0..a.warmup {
        run(out);
    }
    (0..a.reps)
        .map(|_| {
            let t = Instant::now();
            run(out);
            t.elapsed().as_secs_f64()
        })
        .collect()
}

/// `--mode sample`: the Cook-Torrance of the workload sampled with `--strategy`.
fn sample_mode(a: &Args, p: &[Vec<f32>], gold: Conductor<f32, 3>) -> (Vec<f64>, Vec<Vec<f32>>) {
    let n = p[0].len();
    let wo = Directions::new(&p[3], &p[4], &p[5]);
    // Mitsuba's sample2 is (u0, u1); the crate's microfacet samplers use u[0], u[1] for the
    // normal (u[2] picks a lobe in mixtures).
    let u = [&p[7][..], &p[8][..], &p[6][..]];
    let mut out: [Vec<f32>; 7] = std::array::from_fn(|_| vec![0.0f32; n]);
    macro_rules! run {
        ($d:expr, $fresnel:expr, $sqrt:ty) => {{
            let d = $d.unwrap_or_else(|e| fail(e));
            let ct = CookTorrance::new(d, $fresnel, SmithSeparable).with_sqrt::<$sqrt>();
            match a.strategy.as_str() {
                "vndf" => time_sample(&ct.sampled_with::<VisibleNormals>(), wo, u, &mut out, a),
                "caps" => time_sample(&ct.sampled_with::<SphericalCaps>(), wo, u, &mut out, a),
                other => fail(format!("--strategy {other:?}: expected vndf or caps")),
            }
        }};
        ($fresnel:expr, $sqrt:ty) => {
            match a.ndf.as_str() {
                "isotropic" => run!(GgxIsotropic::<f32>::new(a.alpha), $fresnel, $sqrt),
                "ggx" => run!(Ggx::<f32>::anisotropic(a.alpha, a.alpha), $fresnel, $sqrt),
                other => fail(format!("--ndf {other:?}: expected isotropic or ggx")),
            }
        };
    }
    let times = match a.policy.as_str() {
        "exact" => run!(gold, ExactSqrt),
        "shared" => run!(
            gold.share_divisions().unwrap_or_else(|e| fail(e)),
            ExactSqrt
        ),
        // Explicit 16-lane registers with vrsqrt14ps/vrcp14ps on Isa::Avx512.
        "estimate" => run!(gold.with_policy::<HardwareEstimate>(), HardwareEstimate),
        "estimate-shared" => run!(
            gold.with_policy::<HardwareEstimate>()
                .share_divisions()
                .unwrap_or_else(|e| fail(e)),
            HardwareEstimate
        ),
        "fit" => run!(fitted(&gold), ExactSqrt),
        other => fail(format!(
            "--mode sample takes --policy exact, shared, estimate, estimate-shared or fit, not {other:?}"
        )),
    };
    (times, out.into())
}

fn main() {
    let a = args();
    let p = read_pairs(&a.pairs);
    let n = p[0].len();
    let wi = Directions::new(&p[0], &p[1], &p[2]);
    let wo = Directions::new(&p[3], &p[4], &p[5]);
    let mut out = [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]];
    let gold = Conductor::<f32, 3>::new(a.eta, a.k).unwrap_or_else(|e| fail(e));
    let (mut times, values) = match a.mode.as_str() {
        "eval" => (eval_mode(&a, wi, wo, gold, &mut out), out.to_vec()),
        "sample" => sample_mode(&a, &p, gold),
        other => fail(format!("--mode {other:?}: expected eval or sample")),
    };
    write_values(&a.values, &values);
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let json = format!(
        "{{\n \"n\": {n},\n \"isa\": \"{:?}\",\n \"shares_divisions\": {},\n \"ndf\": \"{}\",\n \"policy\": \"{}\",\n \"mode\": \"{}\",\n \
         \"strategy\": \"{}\",\n \"reps\": {},\n \"median_s\": {median:e},\n \"best_s\": {:e}\n}}\n",
        a.isa,
        batch::shares_divisions(),
        a.ndf,
        a.policy,
        a.mode,
        a.strategy,
        a.reps,
        times[0],
    );
    fs::write(&a.timing, json).unwrap_or_else(|e| fail(format!("{}: {e}", a.timing)));
}

/// `--mode eval`: `batch::eval` of the workload times `cos θi`, values left in `out`.
fn eval_mode(
    a: &Args,
    wi: Directions<'_>,
    wo: Directions<'_>,
    gold: Conductor<f32, 3>,
    out: &mut [Vec<f32>; 3],
) -> Vec<f64> {
    type Fast = NewtonSqrtRecip<3, 3>;
    // One arm per (policy, NDF): the model types differ.
    macro_rules! run {
        ($d:expr, $fresnel:expr, $sqrt:ty) => {{
            let d = $d.unwrap_or_else(|e| fail(e));
            let m =
                TimesCosThetaI(CookTorrance::new(d, $fresnel, SmithSeparable).with_sqrt::<$sqrt>());
            time_eval(&m, wi, wo, out, a)
        }};
        ($fresnel:expr, $sqrt:ty) => {
            match a.ndf.as_str() {
                "isotropic" => run!(GgxIsotropic::<f32>::new(a.alpha), $fresnel, $sqrt),
                "ggx" => run!(Ggx::<f32>::anisotropic(a.alpha, a.alpha), $fresnel, $sqrt),
                other => fail(format!("--ndf {other:?}: expected isotropic or ggx")),
            }
        };
    }
    match a.policy.as_str() {
        "exact" => run!(gold, ExactSqrt),
        "shared" => run!(
            gold.share_divisions().unwrap_or_else(|e| fail(e)),
            ExactSqrt
        ),
        "newton" => run!(gold.with_policy::<Fast>(), Fast),
        "estimate" => run!(gold.with_policy::<HardwareEstimate>(), HardwareEstimate),
        "estimate-shared" => run!(
            gold.with_policy::<HardwareEstimate>()
                .share_divisions()
                .unwrap_or_else(|e| fail(e)),
            HardwareEstimate
        ),
        "fit" => run!(fitted(&gold), ExactSqrt),
        "estimate-fit" => run!(fitted(&gold), HardwareEstimate),
        other => fail(format!(
            "--policy {other:?}: expected exact, shared, newton, estimate, estimate-shared, fit or estimate-fit"
        )),
    }
}

/// The workload's conductor fitted as a piecewise polynomial ([`FittedConductor`]).
fn fitted(gold: &Conductor<f32, 3>) -> FittedConductor<f32, 3> {
    FittedConductor::from_conductor(gold).unwrap_or_else(|e| fail(e))
}
