//! A path tracer's inner step, as a program to copy: build a material, draw `wi` with
//! `SampleBrdf::sample`, multiply the throughput by `weight`. Under a uniform white sky (the
//! white furnace) one bounce's expected radiance is the directional albedo, so the Monte-Carlo
//! mean of the weights is printed beside the crate's deterministic quadrature.
//!
//! `cargo run --release --example sample_furnace`
use brdf::analysis::{AlbedoConfig, directional_albedo};
use brdf::fresnel::{Conductor, Schlick};
use brdf::ior::Preset;
use brdf::masking::SmithHeightCorrelated;
use brdf::models::{GgxSmithConductor, GgxSmithSchlick, Lambert, Sum};
use brdf::ndf::GgxIsotropic;
use brdf::{Brdf, SampleBrdf, Vec3};

/// xorshift64*: any uniform generator in [0, 1) will do.
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Mean and standard error of the first channel's weight over `n` samples at `wo`.
fn furnace<M: SampleBrdf<f32, 3>>(m: &M, wo: Vec3<f32>, n: usize) -> (f64, f64) {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let s = m.sample(wo, [rng.uniform(), rng.uniform(), rng.uniform()]);
        // An invalid sample has weight 0: the path ends, the sum is unchanged.
        let w = f64::from(s.weight[0]);
        sum += w;
        sum2 += w * w;
    }
    let mean = sum / n as f64;
    (mean, ((sum2 / n as f64 - mean * mean) / n as f64).sqrt())
}

fn report<M: SampleBrdf<f32, 3> + Brdf<f32, 3>>(name: &str, m: &M) {
    for theta_deg in [0.0f64, 45.0, 80.0] {
        let t = theta_deg.to_radians();
        let wo64 = Vec3::new(t.sin(), 0.0, t.cos());
        let wo = Vec3::new(wo64.x as f32, 0.0, wo64.z as f32);
        let (mean, err) = furnace(m, wo, 1 << 16);
        let [exact, ..] = directional_albedo(m, wo64, &AlbedoConfig::default());
        println!(
            "{name:<12} θo = {theta_deg:>4.1}°  sampled {mean:.4} ± {err:.4}  quadrature {exact:.4}"
        );
    }
}

fn main() -> Result<(), brdf::Error> {
    let gold: GgxSmithConductor<f32> = GgxSmithConductor::new(
        GgxIsotropic::new(0.3)?,
        Conductor::from_preset(Preset::Gold)?,
        SmithHeightCorrelated,
    );
    let plastic = Sum::new(
        Lambert::new([0.5_f32, 0.1, 0.1])?,
        GgxSmithSchlick::new(
            GgxIsotropic::new(0.2)?,
            Schlick::new([0.04; 3])?,
            SmithHeightCorrelated,
        ),
    );
    report("gold (red)", &gold);
    report("plastic", &plastic);
    Ok(())
}
