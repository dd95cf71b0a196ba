//! # brdf — physically based reflectance math
//!
//! Fresnel equations (dielectric, conductor, Schlick, F82-tint), the normalized Blinn-Phong
//! of tri-Ace's 2009 talk "Basic of Reflectance" (Gotanda), microfacet distributions, masking
//! terms and BRDF models — each formula written once and evaluated on `f32`, `f64` or SIMD
//! lanes ([`f32x4`], [`f32x8`], [`f32x16`], [`f64x4`]) through the [`Real`] trait.
//!
//! ## Example
//!
//! A gold GGX microfacet material, evaluated at world-space directions of a y-up engine
//! through the shading [`Frame`] of the surface normal:
//!
//! ```
//! use brdf::{Brdf, Frame};
//! use brdf::fresnel::Conductor;
//! use brdf::ior::Preset;
//! use brdf::masking::SmithHeightCorrelated;
//! use brdf::models::GgxSmithConductor;
//! use brdf::ndf::GgxIsotropic;
//! use glam::Vec3;
//!
//! // Built once, validated once (bad parameters are an Err here, never a NaN later).
//! let gold = GgxSmithConductor::new(
//!     GgxIsotropic::new(0.3_f32)?,
//!     Conductor::from_preset(Preset::Gold)?,
//!     SmithHeightCorrelated,
//! );
//! let n = Vec3::Y; // the shading normal, world space
//! let wi = Vec3::new(-0.4, 0.8, 0.45).normalize(); // towards the light
//! let wo = Vec3::new(0.3, 0.9, 0.3).normalize(); // towards the viewer
//! let f = Frame::from_normal(n).eval(&gold, wi, wo); // RGB, sr⁻¹, without the cosine
//! let reflected = f.map(|c| c * wi.dot(n)); // × cos θi: radiance per unit irradiance
//! assert!((f[0] - 0.1625).abs() < 1e-3 && f[0] > f[1] && f[1] > f[2]); // gold
//! # let _ = reflected;
//! # Ok::<(), brdf::Error>(())
//! ```
//!
//! Models take directions in the local shading frame (next section); [`frame`] converts
//! from world space. Passing world vectors straight in (`gold.eval(wi.into(), wo.into())`)
//! compiles but reads world `z` as the normal: 0.055 instead of 0.163 above (see the
//! [`frame`] docs). [`batch`] evaluates many direction pairs with SIMD; [`real::Splat`]
//! puts a material on lanes; [`analysis`] integrates albedos and checks properties.
//!
//! ## Conventions
//!
//! These hold everywhere in the crate and are not repeated per function.
//!
//! * **Local shading frame.** +z is the shading normal `n`; x and y are the tangent and the
//!   bitangent (the anisotropy axes `alpha_x`, `alpha_y` lie along them). So `cos θ = w.z`.
//! * **Directions** are unit vectors pointing *away* from the surface: `wi` towards the light,
//!   `wo` towards the viewer, `wm` a microfacet normal or the half vector
//!   `normalize(wi + wo)`. Both `wi` and `wo` are in the upper hemisphere for reflection.
//! * **Angles** are in radians; functions take cosines (`cos_theta_i`) where they can.
//! * **Relative IOR** `eta = η_t / η_i`: the index of the side the light enters (inside, below
//!   the surface) over the index of the side it comes from (outside, above). `eta > 1` for
//!   air → glass. In the free dielectric functions, incidence from inside
//!   (`cos_theta_i < 0`) uses `1/eta`; the Fresnel terms of BRDF models take `|cos θd|`
//!   (light arrives from the outside; see [`fresnel::Dielectric`]).
//! * **Complex IOR** of a conductor is written `eta + i·k` with extinction `k ≥ 0` (the
//!   convention of pbrt and of most renderers, time dependence `e^{−iωt}`). The seed talk and
//!   optics texts with `e^{+iωt}` write `n − iκ`: the same material, the conjugate number.
//!   Reflectances do not depend on the choice; phases of the complex amplitudes are conjugated.
//! * **Units.** Reflectances and transmittances are dimensionless in `[0, 1]`. BRDF values
//!   `f(wi, wo)` are in sr⁻¹ and do **not** include the cosine `cos θi`. A normal distribution
//!   `D(wm)` is in sr⁻¹, normalized so that `∫ D(wm) cos θm dωm = 1`. Colours are linear
//!   (not gamma-encoded) values per channel.
//! * **Roughness.** `alpha` is the microfacet slope parameter; perceptual roughness `r`
//!   (what artists paint) is a different quantity, `alpha = r²`. Names never mix the two.
//!
//! ## Validation and hot paths
//!
//! Parameters are validated once, by constructors that return [`Error`]; hot-path functions
//! document their domain, do not branch per lane and never produce NaN or ∞ inside it.
//! Every model may be splatted to `f32` ([`real::Splat`]), so the domains are derived on
//! `f32` whatever type a model is built on: bounded where a formula stops representing
//! anything in `f32` (IORs in `[1e-4, 1e4]`, Phong exponents up to `2e8 − 2`), and a
//! finite value beyond `f32::MAX` is rejected as [`Error::DoesNotFit`] ("does not fit in
//! f32"). `tests/domains.rs` evaluates every constructor over its whole domain.
//!
//! ## Feature flags
//!
//! * `std` (default): math from the standard library.
//! * `libm`: math from [`libm`](https://docs.rs/libm); the crate is `#![no_std]` when `std`
//!   is off, and one of the two must be enabled.
//! * `alloc`: the compositions `Sum` and `Layered` of the runtime [`material::Material`]
//!   (they hold other materials); the crate stays `no_std`.
//! * `serde`: material descriptions that load from files (`material::MaterialDesc`,
//!   validated on load); enables `alloc`.
//! * `half`: `f16` split-sum tables (`split_sum::fill_dfg_f16`), in the IEEE binary16 type of
//!   the [`half`](https://docs.rs/half) crate that engines upload as `R16G16_FLOAT`; `no_std`.
//!
//! ## Re-exported dependencies: glam 0.34, num-complex 0.4
//!
//! [`glam`] (0.34) appears in the API (`Vec3<f32>: From<glam::Vec3>`, `Vec3<f64>:
//! From<glam::DVec3>`, [`batch::eval_glam`]) and [`num_complex`] (0.4) in the complex
//! Fresnel amplitudes; both are re-exported, as `brdf::glam` and `brdf::num_complex`.
//! An engine on another glam version has two different `glam::Vec3` types in its build:
//! `brdf::Vec3::from(engine_vec)` then fails to compile with "the trait `From<glam::Vec3>`
//! is not implemented for `brdf::Vec3<f32>`", and rustc adds that there are multiple
//! different versions of crate `glam` in the dependency graph. Either build your vectors
//! with `brdf::glam`, depend on glam 0.34 yourself, or convert through arrays, which do
//! not depend on glam's version: `brdf::Vec3::from(engine_vec.to_array())`.
//!
//! ## References
//!
//! * Y. Gotanda, "本当のHDR表現へ — アーティストにも知ってほしいリフレクタンスの基礎" (Beyond a
//!   glare effect for HDR rendering — Basic of Reflectance), tri-Ace, Imagine Day 2009.
//! * M. Pharr, W. Jakob, G. Humphreys, *Physically Based Rendering*, 4th ed., 2023.

#![cfg_attr(not(feature = "std"), no_std)]
#![deny(missing_docs)]
#![warn(clippy::doc_markdown)]

// Unit tests use `std` (formatting, `Vec`) even when the library is built without it.
#[cfg(all(test, not(feature = "std")))]
extern crate std;

#[cfg(feature = "alloc")]
extern crate alloc;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!("brdf needs a math backend: enable the `std` (default) or the `libm` feature.");

mod compare;
mod math;

pub mod analysis;
pub mod batch;
pub mod energy;
pub mod error;
pub mod fast;
pub mod frame;
pub mod fresnel;
pub mod ior;
pub mod masking;
pub mod material;
pub mod models;
pub mod ndf;
pub mod normalization;
pub mod real;
pub mod sampling;
pub mod split_sum;
pub mod vec3;

pub use glam;
pub use num_complex;

pub use error::Error;
pub use frame::Frame;
pub use models::Brdf;
pub use real::{Real, Scalar, f32x4, f32x8, f32x16, f64x4};
pub use sampling::{Sample, SampleBrdf};
pub use vec3::Vec3;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The guide's examples and type signatures (`docs/guide.md`), compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/guide.md")]
pub struct GuideDoctests;

#[cfg(test)]
mod tests {
    /// The versions of the re-exported dependencies stated in the crate docs and the README
    /// are the ones in Cargo.toml.
    use std::vec::Vec;

    #[test]
    fn reexported_versions_are_documented() {
        let manifest = include_str!("../Cargo.toml");
        let docs = include_str!("lib.rs");
        let readme = include_str!("../README.md");
        for (krate, name) in [("glam", "glam"), ("num-complex", "num-complex")] {
            let line = manifest
                .lines()
                .find(|l| l.starts_with(&std::format!("{krate} = ")))
                .unwrap_or_else(|| panic!("{krate} in [dependencies]"));
            let v = line
                .split("version = \"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            // "0.34" or "0.4.6" → the compatible series, "0.34" / "0.4".
            let series: Vec<&str> = v.split('.').take(2).collect();
            let series = series.join(".");
            let stated = std::format!("{name} {series}");
            assert!(docs.contains(&stated), "crate docs do not state `{stated}`");
            assert!(readme.contains(&stated), "README does not state `{stated}`");
        }
    }
}
