//! Indices of refraction of common materials, as data: the named presets ([`Preset`], the
//! crate's single list of material names — for files, lookups by name and the preset
//! constructors of [`crate::fresnel`]), the seed talk's table and measured complex IORs of
//! metals at three visible wavelengths (an "RGB" sampling).
//!
//! This module holds numbers only and depends on no other module of the crate; the Fresnel
//! terms are built from it in [`crate::fresnel`] (`Conductor::from_preset`,
//! `Dielectric::from_preset`, `Schlick::from_preset`, `F82Tint::from_preset`), which also
//! computes a preset's normal-incidence reflectance ([`crate::fresnel::f0_from_preset`]).
//!
//! ```
//! use brdf::ior::Preset;
//! let gold = Preset::from_name("gold").unwrap();
//! assert_eq!(gold, Preset::Gold);
//! assert_eq!(gold.name(), "gold");
//! assert!(gold.is_conductor() && !Preset::Water.is_conductor());
//! assert_eq!(Preset::Gold.data().k[0], 3.697);         // measured, 659.5 nm
//! assert_eq!(Preset::Gold.seed().unwrap().eta, 0.34);  // the seed talk's single value
//! assert_eq!(Preset::ALL.len(), 14);
//! ```
//!
//! All values are relative to air (`η_air ≈ 1.0003`, taken as 1) and use the crate's sign
//! convention `η = eta + i·k`, `k ≥ 0`. The seed talk writes complex indices as `n − iκ`
//! (e.g. gold `0.34 − 3.2i`): the same materials, so `k = κ` with the sign dropped.
//!
//! # The seed table
//!
//! [`SEED_TABLE`] reproduces the talk's table of IORs "at some wavelength" (the talk does not
//! say which) and its normal-incidence reflectances, which `tests/ior.rs` recomputes with
//! [`crate::fresnel::f0_from_complex_ior`]. The dielectric presets ([`Preset::Quartz`],
//! [`Preset::Water`], …) take their value from it, the same in the three channels:
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
//! see [`Preset::Iron`]) — the seed's 0.164 is the reflectance of that dielectric, not of iron;
//! and **carbon** `2.0 − 1.0i` has the same `−` sign as the metals, so it is `2.0 + 1.0i` in
//! this crate's convention (an absorbing, graphite-like value).
//!
//! # Measured metals
//!
//! The metal presets ([`Preset::METALS`]: gold, silver, copper, aluminium, iron, titanium,
//! chromium) hold `(eta, k)` at three wavelengths near 650 / 550 / 450 nm (R, G, B),
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

/// A named material. The crate's one list of preset names: material files name them in
/// snake case (`"gold"`, `"titanium_dioxide"`: [`Preset::name`], [`Preset::from_name`]), and
/// [`crate::fresnel`] builds Fresnel terms from them.
///
/// The metals ([`Preset::METALS`]) carry measured RGB data (see the [module docs](self));
/// the other presets the seed talk's single value in all three channels. Metals that the
/// seed table also lists (gold, silver, copper, iron) use the measured data; the seed's value
/// is [`Preset::seed`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum Preset {
    /// Gold (Au), measured: Johnson & Christy 1972.
    Gold,
    /// Silver (Ag), measured: Johnson & Christy 1972.
    Silver,
    /// Copper (Cu), measured: Johnson & Christy 1972.
    Copper,
    /// Aluminium (Al), measured: Rakić 1995.
    Aluminium,
    /// Iron (Fe), measured: Johnson & Christy 1974 (the seed's 2.36 is [`Preset::seed`]).
    Iron,
    /// Titanium (Ti), measured: Johnson & Christy 1974.
    Titanium,
    /// Chromium (Cr), measured: Johnson & Christy 1974.
    Chromium,
    /// Quartz, seed table: `1.45`.
    Quartz,
    /// Water, seed table: `1.33`.
    Water,
    /// Sapphire, seed table: `1.76`.
    Sapphire,
    /// Titanium dioxide (`TiO₂`), seed table: `2.52`.
    TitaniumDioxide,
    /// Ivory, seed table: `1.54`.
    Ivory,
    /// Iron oxide (`Fe₂O₃`), seed table: `3.01`.
    IronOxide,
    /// Carbon, seed table: `2.0 + 1.0i` (seed: `2.0 − 1.0i`); absorbing.
    Carbon,
}

/// A complex IOR `eta + i·k` per colour channel (R, G, B) and where it comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RgbIor {
    /// Real part of the IOR per channel (relative to air).
    pub eta: [f64; 3],
    /// Extinction coefficient per channel, `k ≥ 0` (0 for dielectrics).
    pub k: [f64; 3],
    /// The wavelengths of the three samples in nm (R, G, B), or `None` for the seed
    /// table's single value "at some wavelength".
    pub wavelengths_nm: Option<[f64; 3]>,
    /// Short citation of the data.
    pub source: &'static str,
}

/// One row of the seed talk's IOR table: a single (possibly complex) IOR `eta + i·k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeedEntry {
    /// The material.
    pub preset: Preset,
    /// Real part of the IOR (relative to air).
    pub eta: f64,
    /// Extinction coefficient `k ≥ 0` (0 for dielectrics).
    pub k: f64,
}

const JC72: &str = "Johnson & Christy, Phys. Rev. B 6, 4370 (1972)";
const JC74: &str = "Johnson & Christy, Phys. Rev. B 9, 5056 (1974)";
const JC72_NM: Option<[f64; 3]> = Some([659.5, 548.6, 450.9]);
const JC74_NM: Option<[f64; 3]> = Some([659.0, 549.0, 451.0]);
const SEED: &str = "Gotanda, Basic of Reflectance, tri-Ace 2009 (seed table)";

const fn seed(preset: Preset, eta: f64, k: f64) -> SeedEntry {
    SeedEntry { preset, eta, k }
}

/// The seed talk's whole IOR table, in its order (iron as printed: real, i.e. a dielectric;
/// carbon conjugated to `2.0 + 1.0i`; see the [module docs](self)).
pub const SEED_TABLE: [SeedEntry; 11] = [
    seed(Preset::Iron, 2.36, 0.0),
    seed(Preset::IronOxide, 3.01, 0.0),
    seed(Preset::Gold, 0.34, 3.2),
    seed(Preset::Silver, 0.17, 3.4),
    seed(Preset::Copper, 0.6, 3.6),
    seed(Preset::Quartz, 1.45, 0.0),
    seed(Preset::Sapphire, 1.76, 0.0),
    seed(Preset::Water, 1.33, 0.0),
    seed(Preset::TitaniumDioxide, 2.52, 0.0),
    seed(Preset::Ivory, 1.54, 0.0),
    seed(Preset::Carbon, 2.0, 1.0),
];

impl Preset {
    /// Every preset: the metals, then the seed table's other materials.
    pub const ALL: [Preset; 14] = [
        Preset::Gold,
        Preset::Silver,
        Preset::Copper,
        Preset::Aluminium,
        Preset::Iron,
        Preset::Titanium,
        Preset::Chromium,
        Preset::Quartz,
        Preset::Water,
        Preset::Sapphire,
        Preset::TitaniumDioxide,
        Preset::Ivory,
        Preset::IronOxide,
        Preset::Carbon,
    ];

    /// The metals with measured RGB data.
    pub const METALS: [Preset; 7] = [
        Preset::Gold,
        Preset::Silver,
        Preset::Copper,
        Preset::Aluminium,
        Preset::Iron,
        Preset::Titanium,
        Preset::Chromium,
    ];

    /// The name in files and lookups: snake case (`"gold"`, `"titanium_dioxide"`).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Preset::Gold => "gold",
            Preset::Silver => "silver",
            Preset::Copper => "copper",
            Preset::Aluminium => "aluminium",
            Preset::Iron => "iron",
            Preset::Titanium => "titanium",
            Preset::Chromium => "chromium",
            Preset::Quartz => "quartz",
            Preset::Water => "water",
            Preset::Sapphire => "sapphire",
            Preset::TitaniumDioxide => "titanium_dioxide",
            Preset::Ivory => "ivory",
            Preset::IronOxide => "iron_oxide",
            Preset::Carbon => "carbon",
        }
    }

    /// The English name for tables and user interfaces (`"titanium dioxide"`).
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Preset::TitaniumDioxide => "titanium dioxide",
            Preset::IronOxide => "iron oxide",
            p => p.name(),
        }
    }

    /// The preset named `name` ([`Preset::name`], exactly), or `None`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The complex IOR per RGB channel and its source.
    #[must_use]
    pub const fn data(self) -> RgbIor {
        const fn m(
            eta: [f64; 3],
            k: [f64; 3],
            nm: Option<[f64; 3]>,
            source: &'static str,
        ) -> RgbIor {
            RgbIor {
                eta,
                k,
                wavelengths_nm: nm,
                source,
            }
        }
        match self {
            // Johnson & Christy 1972 at 659.5 / 548.6 / 450.9 nm.
            Preset::Gold => m([0.14, 0.43, 1.38], [3.697, 2.455, 1.914], JC72_NM, JC72),
            Preset::Silver => m([0.05, 0.06, 0.04], [4.483, 3.586, 2.657], JC72_NM, JC72),
            Preset::Copper => m([0.22, 1.02, 1.24], [3.747, 2.577, 2.397], JC72_NM, JC72),
            // Rakić 1995 at 652.3 / 563.6 / 442.8 nm.
            Preset::Aluminium => m(
                [1.5724, 1.0728, 0.6079],
                [7.7354, 6.7839, 5.3676],
                Some([652.25, 563.57, 442.80]),
                "Rakić, Appl. Opt. 34, 4755 (1995)",
            ),
            // Johnson & Christy 1974 at 659 / 549 / 451 nm.
            Preset::Iron => m([2.92, 2.95, 2.59], [3.10, 2.93, 2.77], JC74_NM, JC74),
            Preset::Titanium => m([2.76, 2.54, 2.27], [3.84, 3.43, 3.04], JC74_NM, JC74),
            // k = 3.14 at 451 nm is measured data, not π.
            #[allow(clippy::approx_constant)]
            Preset::Chromium => m([3.09, 3.18, 2.33], [3.34, 3.33, 3.14], JC74_NM, JC74),
            p => match p.seed() {
                Some(e) => m([e.eta; 3], [e.k; 3], None, SEED),
                None => unreachable!(),
            },
        }
    }

    /// The complex IOR `(eta, k)` per RGB channel ([`Preset::data`] without its source).
    #[must_use]
    pub const fn ior(self) -> ([f64; 3], [f64; 3]) {
        let d = self.data();
        (d.eta, d.k)
    }

    /// Whether the preset absorbs (`k > 0` in some channel): a conductor, not a dielectric.
    #[must_use]
    pub const fn is_conductor(self) -> bool {
        let k = self.data().k;
        k[0] > 0.0 || k[1] > 0.0 || k[2] > 0.0
    }

    /// The seed talk's single value for this material, if its table lists it.
    #[must_use]
    pub const fn seed(self) -> Option<SeedEntry> {
        let mut i = 0;
        while i < SEED_TABLE.len() {
            if SEED_TABLE[i].preset as u8 == self as u8 {
                return Some(SEED_TABLE[i]);
            }
            i += 1;
        }
        None
    }
}

impl core::fmt::Display for Preset {
    /// The snake-case name ([`Preset::name`]).
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}
