//! Monte-Carlo statistics of the crate's samplers, shared by `tradeoffs` (variance and lost
//! fractions) and `plots` (error against sample count): the white-furnace estimate of a GGX
//! Cook-Torrance's directional albedo (`F = 1`, height-correlated Smith), whose exact value
//! the crate's quadrature gives.
use brdf::analysis::{AlbedoConfig, directional_albedo};
use brdf::fresnel::Schlick;
use brdf::masking::SmithHeightCorrelated;
use brdf::models::{Brdf, CookTorrance, Kinks, Properties};
use brdf::ndf::GgxIsotropic;
use brdf::sampling::{
    self, BoundedVisibleNormals, FullDistribution, SphericalCaps, VisibleNormals,
};
use brdf::{Sample, SampleBrdf, Vec3};

/// The furnace model: GGX (`GgxIsotropic`), `F = 1` (Schlick with `F0 = 1`), height-correlated
/// Smith, on `f64`.
pub type FurnaceGgx = CookTorrance<f64, GgxIsotropic<f64>, Schlick<f64, 1>, SmithHeightCorrelated>;

/// The furnace model at roughness `alpha ∈ [1e-4, 1]`.
///
/// # Panics
/// If `alpha` is outside the NDF's domain.
#[must_use]
pub fn furnace_ggx(alpha: f64) -> FurnaceGgx {
    CookTorrance::new(
        GgxIsotropic::new(alpha).expect("alpha in [1e-4, 1]"),
        Schlick::new([1.0]).expect("F0 = 1"),
        SmithHeightCorrelated,
    )
}

/// A model sampled by the cosine-weighted hemisphere (`pdf = cos θi / π`), whatever its own
/// sampler: the baseline of the comparison.
#[derive(Clone, Copy, Debug)]
pub struct CosineSampled<M>(pub M);

impl<M: Brdf<f64, 1>> Brdf<f64, 1> for CosineSampled<M> {
    fn eval(&self, wi: Vec3<f64>, wo: Vec3<f64>) -> [f64; 1] {
        self.0.eval(wi, wo)
    }
    fn properties(&self) -> Properties {
        self.0.properties()
    }
    fn kinks(&self, wo: Vec3<f64>) -> Kinks {
        self.0.kinks(wo)
    }
}

impl<M: Brdf<f64, 1>> SampleBrdf<f64, 1> for CosineSampled<M> {
    fn sample(&self, wo: Vec3<f64>, u: [f64; 3]) -> Sample<f64, 1> {
        sampling::sample_cosine(&self.0, wo, u)
    }
    fn pdf(&self, wo: Vec3<f64>, wi: Vec3<f64>) -> f64 {
        sampling::pdf_cosine(wo, wi)
    }
}

/// The GGX furnace model at `alpha` under each strategy compared: visible normals (Heitz
/// 2018), spherical caps (Dupuy & Benyoub 2023: the same density), bounded visible normals
/// (Eto & Tokuyoshi 2023), `D cos θm`, and the cosine hemisphere.
#[must_use]
pub fn strategies(alpha: f64) -> Vec<(&'static str, Box<dyn SampleBrdf<f64, 1>>)> {
    let m = furnace_ggx(alpha);
    vec![
        (
            "visible normals",
            Box::new(m.sampled_with::<VisibleNormals>()),
        ),
        (
            "spherical caps",
            Box::new(m.sampled_with::<SphericalCaps>()),
        ),
        (
            "bounded VNDF",
            Box::new(m.sampled_with::<BoundedVisibleNormals>()),
        ),
        ("D cos θm", Box::new(m.sampled_with::<FullDistribution>())),
        ("cosine", Box::new(CosineSampled(m))),
    ]
}

/// `wo` at `theta_deg` from the normal, in the xz plane.
#[must_use]
pub fn wo_at(theta_deg: f64) -> Vec3<f64> {
    let t = theta_deg.to_radians();
    Vec3::new(t.sin(), 0.0, t.cos())
}

/// The exact furnace albedo of [`furnace_ggx`]`(alpha)` at `wo` (the crate's adaptive
/// quadrature, within 1e-6).
#[must_use]
pub fn exact_albedo(alpha: f64, wo: Vec3<f64>) -> f64 {
    directional_albedo(&furnace_ggx(alpha), wo, &AlbedoConfig::default())[0]
}

/// A deterministic uniform generator in `[0, 1)` (SplitMix64), one stream per seed.
#[derive(Clone, Debug)]
pub struct Uniform(u64);

impl Uniform {
    /// The stream of `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ 0x2545_f491_4f6c_dd1d)
    }
    /// The next number, 53 random bits.
    pub fn draw(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) as f64 / 2f64.powi(64)
    }
}

/// Statistics of `n` one-sample estimates `weight` of the albedo at `wo`.
#[derive(Clone, Copy, Debug)]
pub struct Stats {
    /// Mean weight: the estimate of the directional albedo.
    pub mean: f64,
    /// Variance of one sample's weight (the estimator's variance is this over `n`).
    pub variance: f64,
    /// Fraction of invalid samples (reflected below the horizon, or zero density).
    pub lost: f64,
}

/// [`Stats`] of `sampler` at `wo` over `n` samples of the stream `seed`.
#[must_use]
pub fn furnace_stats(
    sampler: &dyn SampleBrdf<f64, 1>,
    wo: Vec3<f64>,
    n: usize,
    seed: u64,
) -> Stats {
    let mut rng = Uniform::new(seed);
    let (mut sum, mut sum2, mut lost) = (0.0, 0.0, 0usize);
    for _ in 0..n {
        let s = sampler.sample(wo, [rng.draw(), rng.draw(), rng.draw()]);
        lost += usize::from(!s.valid);
        sum += s.weight[0];
        sum2 += s.weight[0] * s.weight[0];
    }
    let mean = sum / n as f64;
    Stats {
        mean,
        variance: (sum2 / n as f64 - mean * mean).max(0.0),
        lost: lost as f64 / n as f64,
    }
}
