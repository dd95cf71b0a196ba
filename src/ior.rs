//! Indices of refraction of common materials: the seed talk's table and measured complex
//! IORs of metals at three visible wavelengths (an "RGB" sampling).
//!
//! All values are relative to air (`η_air ≈ 1.0003`, taken as 1) and use the crate's sign
//! convention `η = eta + i·k`, `k ≥ 0`. The seed talk writes complex indices as `n − iκ`
//! (e.g. gold `0.34 − 3.2i`): the same materials, so `k = κ` with the sign dropped.
//!
//! # The seed table
//!
//! [`SEED_TABLE`] reproduces the talk's table of IORs "at some wavelength" (the talk does not
//! say which) and its normal-incidence reflectances, which `tests/ior.rs` recomputes with
//! [`crate::fresnel::f0_from_complex_ior`]:
//!
//! | material        | seed IOR    | F0 (computed) | seed's F0 |
//! |-----------------|-------------|---------------|-----------|
//! | iron            | 2.36        | 0.1638        | 0.164     |
//! | iron oxide      | 3.01        | 0.2524        | —         |
//! | gold            | 0.34 − 3.2i | 0.8870        | 0.887     |
//! | silver          | 0.17 − 3.4i | 0.9445        | —         |
//! | copper          | 0.6 − 3.6i  | 0.8750        | —         |
//! | quartz          | 1.45        | 0.0337        | 0.034     |
//! | sapphire        | 1.76        | 0.0758        | 0.076     |
//! | water           | 1.33        | 0.0201        | —         |
//! | titanium dioxide| 2.52        | 0.1863        | —         |
//! | ivory           | 1.54        | 0.0452        | —         |
//! | carbon          | 2.0 − 1.0i  | 0.2000        | 0.2       |
//!
//! Every printed value matches. Two entries are physically questionable and kept only to
//! reproduce the talk: **iron** is given a real index 2.36, i.e. as a dielectric, whereas
//! measured iron is a conductor (`2.95 + 2.93i` at 549 nm, Johnson & Christy 1974, F0 ≈ 0.51;
//! see [`IRON_RGB`]) — the seed's 0.164 is the reflectance of that dielectric, not of iron;
//! and **carbon** `2.0 − 1.0i` has the same `−` sign as the metals, so it is `2.0 + 1.0i` in
//! this crate's convention (an absorbing, graphite-like value).
//!
//! # Measured metals
//!
//! [`METALS_RGB`] holds `(eta, k)` at three wavelengths near 650 / 550 / 450 nm (R, G, B),
//! taken without interpolation from the tabulated points of:
//!
//! * Au, Ag, Cu: P. B. Johnson, R. W. Christy, "Optical Constants of the Noble Metals",
//!   Phys. Rev. B 6, 4370 (1972); points at 1.88 / 2.26 / 2.75 eV = 659.5 / 548.6 / 450.9 nm.
//! * Fe, Ti, Cr: P. B. Johnson, R. W. Christy, "Optical constants of transition metals: Ti,
//!   V, Cr, Mn, Fe, Co, Ni, and Pd", Phys. Rev. B 9, 5056 (1974); 659 / 549 / 451 nm.
//! * Al: A. D. Rakić, "Algorithm for the determination of intrinsic optical constants of
//!   metal films: application to aluminum", Appl. Opt. 34, 4755 (1995); 652.3 / 563.6 /
//!   442.8 nm (the tabulated points nearest to 650 / 550 / 450 nm).
//!
//! (Values as transcribed in the refractiveindex.info database, M. N. Polyanskiy, CC0.)
//! Their normal-incidence reflectances are close to the linear-sRGB F0 values commonly
//! quoted for these metals (Real-Time Rendering, 4th ed., Table 9.2, from N. Hoffman):
//!
//! | metal     | F0 from the preset (R, G, B) | RTR4 linear F0 (R, G, B) |
//! |-----------|------------------------------|--------------------------|
//! | gold      | 0.963, 0.787, 0.408          | 1.000, 0.782, 0.344      |
//! | silver    | 0.991, 0.983, 0.980          | 0.972, 0.960, 0.915      |
//! | copper    | 0.943, 0.619, 0.539          | 0.955, 0.638, 0.538      |
//! | aluminium | 0.905, 0.915, 0.923          | 0.913, 0.922, 0.924      |
//! | iron      | 0.532, 0.512, 0.496          | 0.562, 0.565, 0.578      |
//! | titanium  | 0.618, 0.582, 0.545          | 0.542, 0.497, 0.449      |
//! | chromium  | 0.557, 0.555, 0.555          | 0.549, 0.556, 0.554      |
//!
//! The differences (up to ≈ 0.1, largest for titanium, the blue of gold and silver) come
//! from sampling one wavelength per channel instead of integrating the spectrum against the
//! sRGB colour matching functions, and from different samples/films between the data sets;
//! `tests/ior.rs` bounds them. Use these presets for plausible metals, not for colorimetry.

/// A material with one (possibly complex) IOR `eta + i·k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    /// Material name, English.
    pub name: &'static str,
    /// Real part of the IOR (relative to air).
    pub eta: f64,
    /// Extinction coefficient `k ≥ 0` (0 for dielectrics).
    pub k: f64,
}

/// A material with a complex IOR per colour channel (R, G, B).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RgbPreset {
    /// Material name, English.
    pub name: &'static str,
    /// Real part of the IOR per channel.
    pub eta: [f64; 3],
    /// Extinction coefficient per channel, `k ≥ 0`.
    pub k: [f64; 3],
    /// The wavelengths of the three samples, in nm (R, G, B).
    pub wavelengths_nm: [f64; 3],
    /// Short citation of the measured data.
    pub source: &'static str,
}

impl Preset {
    /// Normal-incidence reflectance `((η − 1)² + k²)/((η + 1)² + k²)`.
    #[must_use]
    pub fn f0(&self) -> f64 {
        crate::fresnel::f0_from_complex_ior(self.eta, self.k)
    }
}

impl RgbPreset {
    /// Normal-incidence reflectance per channel.
    #[must_use]
    pub fn f0(&self) -> [f64; 3] {
        core::array::from_fn(|i| crate::fresnel::f0_from_complex_ior(self.eta[i], self.k[i]))
    }
}

const fn seed(name: &'static str, eta: f64, k: f64) -> Preset {
    Preset { name, eta, k }
}

/// Seed table: iron, `2.36` (as printed: real, i.e. a dielectric; see the module docs).
pub const IRON: Preset = seed("iron", 2.36, 0.0);
/// Seed table: iron oxide (`Fe₂O₃`), `3.01`.
pub const IRON_OXIDE: Preset = seed("iron oxide", 3.01, 0.0);
/// Seed table: gold, `0.34 + 3.2i` (seed: `0.34 − 3.2i`).
pub const GOLD: Preset = seed("gold", 0.34, 3.2);
/// Seed table: silver, `0.17 + 3.4i` (seed: `0.17 − 3.4i`).
pub const SILVER: Preset = seed("silver", 0.17, 3.4);
/// Seed table: copper, `0.6 + 3.6i` (seed: `0.6 − 3.6i`).
pub const COPPER: Preset = seed("copper", 0.6, 3.6);
/// Seed table: quartz, `1.45`.
pub const QUARTZ: Preset = seed("quartz", 1.45, 0.0);
/// Seed table: sapphire, `1.76`.
pub const SAPPHIRE: Preset = seed("sapphire", 1.76, 0.0);
/// Seed table: water, `1.33`.
pub const WATER: Preset = seed("water", 1.33, 0.0);
/// Seed table: titanium dioxide, `2.52`.
pub const TITANIUM_DIOXIDE: Preset = seed("titanium dioxide", 2.52, 0.0);
/// Seed table: ivory, `1.54`.
pub const IVORY: Preset = seed("ivory", 1.54, 0.0);
/// Seed table: carbon, `2.0 + 1.0i` (seed: `2.0 − 1.0i`, same sign convention as its metals).
pub const CARBON: Preset = seed("carbon", 2.0, 1.0);

/// The seed talk's whole IOR table, in its order.
pub const SEED_TABLE: &[Preset] = &[
    IRON,
    IRON_OXIDE,
    GOLD,
    SILVER,
    COPPER,
    QUARTZ,
    SAPPHIRE,
    WATER,
    TITANIUM_DIOXIDE,
    IVORY,
    CARBON,
];

const JC72: &str = "Johnson & Christy, Phys. Rev. B 6, 4370 (1972)";
const JC74: &str = "Johnson & Christy, Phys. Rev. B 9, 5056 (1974)";
const JC72_NM: [f64; 3] = [659.5, 548.6, 450.9];
const JC74_NM: [f64; 3] = [659.0, 549.0, 451.0];

/// Gold (Au), Johnson & Christy 1972 at 659.5 / 548.6 / 450.9 nm.
pub const GOLD_RGB: RgbPreset = RgbPreset {
    name: "gold",
    eta: [0.14, 0.43, 1.38],
    k: [3.697, 2.455, 1.914],
    wavelengths_nm: JC72_NM,
    source: JC72,
};
/// Silver (Ag), Johnson & Christy 1972 at 659.5 / 548.6 / 450.9 nm.
pub const SILVER_RGB: RgbPreset = RgbPreset {
    name: "silver",
    eta: [0.05, 0.06, 0.04],
    k: [4.483, 3.586, 2.657],
    wavelengths_nm: JC72_NM,
    source: JC72,
};
/// Copper (Cu), Johnson & Christy 1972 at 659.5 / 548.6 / 450.9 nm.
pub const COPPER_RGB: RgbPreset = RgbPreset {
    name: "copper",
    eta: [0.22, 1.02, 1.24],
    k: [3.747, 2.577, 2.397],
    wavelengths_nm: JC72_NM,
    source: JC72,
};
/// Aluminium (Al), Rakić 1995 at 652.3 / 563.6 / 442.8 nm.
pub const ALUMINIUM_RGB: RgbPreset = RgbPreset {
    name: "aluminium",
    eta: [1.5724, 1.0728, 0.6079],
    k: [7.7354, 6.7839, 5.3676],
    wavelengths_nm: [652.25, 563.57, 442.80],
    source: "Rakić, Appl. Opt. 34, 4755 (1995)",
};
/// Iron (Fe), Johnson & Christy 1974 at 659 / 549 / 451 nm.
pub const IRON_RGB: RgbPreset = RgbPreset {
    name: "iron",
    eta: [2.92, 2.95, 2.59],
    k: [3.10, 2.93, 2.77],
    wavelengths_nm: JC74_NM,
    source: JC74,
};
/// Titanium (Ti), Johnson & Christy 1974 at 659 / 549 / 451 nm.
pub const TITANIUM_RGB: RgbPreset = RgbPreset {
    name: "titanium",
    eta: [2.76, 2.54, 2.27],
    k: [3.84, 3.43, 3.04],
    wavelengths_nm: JC74_NM,
    source: JC74,
};
/// Chromium (Cr), Johnson & Christy 1974 at 659 / 549 / 451 nm.
#[allow(clippy::approx_constant)] // k = 3.14 at 451 nm is measured data, not π
pub const CHROMIUM_RGB: RgbPreset = RgbPreset {
    name: "chromium",
    eta: [3.09, 3.18, 2.33],
    k: [3.34, 3.33, 3.14],
    wavelengths_nm: JC74_NM,
    source: JC74,
};

/// All measured RGB metal presets.
pub const METALS_RGB: &[RgbPreset] = &[
    GOLD_RGB,
    SILVER_RGB,
    COPPER_RGB,
    ALUMINIUM_RGB,
    IRON_RGB,
    TITANIUM_RGB,
    CHROMIUM_RGB,
];
