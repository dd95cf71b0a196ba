//! # brdf — physically based reflectance math
//!
//! Fresnel equations (dielectric, conductor, Schlick, F82-tint), the normalized Blinn-Phong
//! of tri-Ace's 2009 talk "Basic of Reflectance" (Gotanda), microfacet distributions, masking
//! terms and BRDF models — each formula written once and evaluated on `f32`, `f64` or SIMD
//! lanes ([`f32x4`], [`f32x8`], [`f32x16`], [`f64x4`]) through the [`Real`] trait.
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
//!   air → glass. Incidence from inside (`cos_theta_i < 0`) uses `1/eta`.
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
pub mod vec3;

pub use error::Error;
pub use frame::Frame;
pub use models::Brdf;
pub use real::{Real, Scalar, f32x4, f32x8, f32x16, f64x4};
pub use vec3::Vec3;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
