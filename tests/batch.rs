//! The batch path: every instruction-set variant this CPU can run equals the scalar `eval`.
mod common;

use brdf::batch::{self, Directions, Isa};
use brdf::fresnel::{Conductor, Schlick};
use brdf::masking::{SmithHeightCorrelated, SmithSeparable};
use brdf::models::{CookTorrance, Lambert, Sum};
use brdf::ndf::Ggx;
use brdf::{Brdf, Vec3, ior};

/// `n` direction pairs by warping a deterministic low-discrepancy sequence over the
/// hemisphere (cos θ uniform in [0, 1], grazing and normal incidence included).
fn pairs(n: usize) -> [Vec<f32>; 6] {
    let mut v: [Vec<f32>; 6] = Default::default();
    let g = 0.618_033_988_749_894_9_f64;
    for i in 0..n {
        let u = [
            (i as f64 * g).fract(),
            (i as f64 * g * g).fract(),
            (i as f64 * 0.754_877_666).fract(),
            (i as f64 * 0.569_840_290).fract(),
        ];
        let a = common::hemisphere(if i % 17 == 0 { 0.0 } else { u[0] }, u[1]);
        let b = common::hemisphere(if i % 19 == 0 { 1e-7 } else { u[2] }, u[3]);
        for (k, c) in [a.x, a.y, a.z, b.x, b.y, b.z].into_iter().enumerate() {
            v[k].push(c as f32);
        }
    }
    v
}

/// Runs every available variant and compares with `eval` on `f32`, returning the worst
/// relative difference (FMA contraction in the wide variants may change the last bits).
fn check<B: Brdf<f32, N>, const N: usize>(brdf: &B, n: usize) -> f32 {
    let d = pairs(n);
    let wi = Directions::new(&d[0], &d[1], &d[2]);
    let wo = Directions::new(&d[3], &d[4], &d[5]);
    let mut worst = 0.0f32;
    let mut ran = 0;
    for isa in Isa::ALL {
        let mut out = vec![vec![f32::NAN; n]; N];
        let slices: [&mut [f32]; N] = {
            let mut it = out.iter_mut();
            core::array::from_fn(|_| it.next().unwrap().as_mut_slice())
        };
        match batch::eval_with(isa, brdf, wi, wo, slices) {
            Err(e) => {
                assert!(!isa.is_available(), "{e}");
                continue;
            }
            Ok(()) => ran += 1,
        }
        for i in 0..n {
            let f = brdf.eval(
                Vec3::new(d[0][i], d[1][i], d[2][i]),
                Vec3::new(d[3][i], d[4][i], d[5][i]),
            );
            for c in 0..N {
                let (a, b) = (out[c][i], f[c]);
                assert!(a.is_finite(), "{isa:?} produced {a} at {i}");
                let rel = (a - b).abs() / b.abs().max(1e-6);
                assert!(
                    rel <= 2e-5,
                    "{isa:?} channel {c} at {i}: batch {a} vs scalar {b}"
                );
                worst = worst.max(rel);
            }
        }
    }
    assert!(ran >= 1 && Isa::detect().is_available());
    worst
}

#[test]
fn every_available_variant_matches_scalar_ggx_schlick() {
    let ct = CookTorrance::new(
        Ggx::<f32>::new(0.3).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    // 1031: not a multiple of any lane width, so the scalar tail runs too.
    let w = check(&ct, 1031);
    println!("GGX/Schlick worst relative difference: {w:e}");
}

#[test]
fn every_available_variant_matches_scalar_rough_conductor_rgb() {
    let ct = CookTorrance::new(
        Ggx::<f32>::new(0.2).unwrap(),
        Conductor::<f32, 3>::from_rgb_preset(&ior::GOLD_RGB),
        SmithSeparable,
    );
    let sum = Sum::new(ct, Lambert::<f32, 3>::new([0.1, 0.2, 0.3]).unwrap());
    let w = check(&sum, 517);
    println!("rough conductor + Lambert worst relative difference: {w:e}");
}

#[test]
fn glam_convenience_matches_scalar() {
    let ct = CookTorrance::new(
        Ggx::<f32>::new(0.5).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    let d = pairs(700);
    let wi: Vec<glam::Vec3> = (0..700)
        .map(|i| glam::Vec3::new(d[0][i], d[1][i], d[2][i]))
        .collect();
    let wo: Vec<glam::Vec3> = (0..700)
        .map(|i| glam::Vec3::new(d[3][i], d[4][i], d[5][i]))
        .collect();
    let mut out = vec![[0.0f32; 1]; 700];
    batch::eval_glam(&ct, &wi, &wo, &mut out);
    for i in 0..700 {
        let f = ct.eval(wi[i].into(), wo[i].into())[0];
        assert!(
            (out[i][0] - f).abs() <= 2e-5 * f.abs().max(1e-6),
            "{i}: {} vs {f}",
            out[i][0]
        );
    }
}

#[test]
#[should_panic(expected = "differ in length")]
fn mismatched_lengths_panic() {
    let ct = Lambert::<f32, 1>::new([0.5]).unwrap();
    let a = [0.0f32; 4];
    let mut out = [0.0f32; 3];
    batch::eval(
        &ct,
        Directions::new(&a, &a, &a),
        Directions::new(&a, &a, &a),
        [&mut out],
    );
}
