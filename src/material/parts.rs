//! The parts every file description shares (feature `serde`): field-named errors, colours
//! ([`Rgb`]), reflectances ([`Reflectance`], [`Preset`]), the Fresnel and NDF parts of the
//! microfacet models ([`FresnelDesc`], [`NdfDesc`]) and the roughness fields (`alpha`, or
//! `alpha_x` and `alpha_y`).
//!
//! A model's own description lives beside the model (`src/models/<model>.rs`, module
//! `desc`); what several models use lives here.

use core::fmt;

use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::ser::{SerializeMap, Serializer};
use serde::{Deserialize, Serialize};

use super::MaterialError;
use crate::fresnel::{AnyFresnel, Conductor, Dielectric, NoFresnel, Schlick};
use crate::ndf::{AnyNdf, Beckmann, Ggx, GgxIsotropic};
use crate::{Error, Scalar};

// ---------------------------------------------------------------------------------------------
// Field-named deserialization errors
// ---------------------------------------------------------------------------------------------

/// Deserializes `T`, prefixing any error with the field name.
pub(crate) fn named<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    field: &'static str,
    d: D,
) -> Result<T, D::Error> {
    T::deserialize(d).map_err(|e| de::Error::custom(format_args!("`{field}`: {e}")))
}

/// `field_fns!(alpha, rho)`: a private module `field` with one `deserialize_with` function
/// per field name (`#[serde(deserialize_with = "field::alpha")]`), so that type errors name
/// the field. Each description module declares the fields it uses.
macro_rules! field_fns {
    ($($f:ident),* $(,)?) => {
        /// One `deserialize_with` function per field name, so that type errors name the field.
        mod field {
            $(
                pub(super) fn $f<'de, D, T>(d: D) -> Result<T, D::Error>
                where
                    D: serde::Deserializer<'de>,
                    T: serde::Deserialize<'de>,
                {
                    $crate::material::named(stringify!($f), d)
                }
            )*
        }
    };
}
pub(crate) use field_fns;

field_fns!(eta, k, f0);

// ---------------------------------------------------------------------------------------------
// Colours, presets, reflectances
// ---------------------------------------------------------------------------------------------

/// A linear RGB triple. Deserializes from a number (grey) or an array of three numbers;
/// serializes as an array.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rgb(pub [f64; 3]);

impl Rgb {
    /// The channels on the scalar type `S` (rounded once from `f64`).
    pub(crate) fn scalars<S: Scalar>(self) -> [S; 3] {
        self.0.map(S::of)
    }
}

impl Serialize for Rgb {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

struct RgbVisitor;

impl<'de> Visitor<'de> for RgbVisitor {
    type Value = Rgb;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number or an array of 3 numbers")
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Rgb, E> {
        Ok(Rgb([v; 3]))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Rgb, E> {
        Ok(Rgb([v as f64; 3]))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Rgb, E> {
        Ok(Rgb([v as f64; 3]))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Rgb, A::Error> {
        let mut v = [0.0; 3];
        for (i, x) in v.iter_mut().enumerate() {
            *x = seq
                .next_element()?
                .ok_or_else(|| de::Error::invalid_length(i, &self))?;
        }
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(4, &self));
        }
        Ok(Rgb(v))
    }
}

impl<'de> Deserialize<'de> for Rgb {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(RgbVisitor)
    }
}

/// A named optical constant: the crate's one list of preset names, [`crate::ior::Preset`]
/// (re-exported here for material files). Names in files are snake case: `"gold"`,
/// `"titanium_dioxide"`, …
pub(crate) use crate::ior::Preset;

/// A normal-incidence reflectance per channel (`f0`, a specular colour): given directly,
/// or from a preset, or from a complex IOR.
///
/// Deserializes from a number or an array of 3 (the values), `{ preset = "gold" }`, or
/// `{ eta = …, k = … }` (`k` optional, each a number or 3 numbers).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Reflectance {
    /// The reflectance itself, per channel in `[0, 1]`.
    Value(Rgb),
    /// `f0` of a preset's complex IOR.
    Preset(Preset),
    /// `f0 = ((η − 1)² + k²)/((η + 1)² + k²)` of a complex IOR (`eta ∈ [1e-4, 1e4]`,
    /// `k ∈ [0, 1e4]`: the domains of [`crate::fresnel::Conductor::new`]).
    Ior {
        /// Real part of the relative IOR.
        eta: Rgb,
        /// Extinction coefficient.
        k: Rgb,
    },
}

impl Reflectance {
    /// The reflectance per channel, validating a given IOR (the domains of
    /// [`crate::fresnel::Conductor::new`]) and reporting a bad one as `param`.
    pub(crate) fn value(self) -> Result<[f64; 3], Error> {
        let (eta, k) = match self {
            Reflectance::Value(v) => return Ok(v.0),
            Reflectance::Preset(p) => p.ior(),
            Reflectance::Ior { eta, k } => (eta.0, k.0),
        };
        let mut f0 = [0.0; 3];
        for c in 0..3 {
            let e = crate::fresnel::check_eta(eta[c])?;
            let k = crate::fresnel::check_k(k[c])?;
            f0[c] = crate::fresnel::f0_from_complex_ior(e, k);
        }
        Ok(f0)
    }
}

impl Serialize for Reflectance {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Reflectance::Value(v) => v.serialize(s),
            Reflectance::Preset(p) => {
                let mut m = s.serialize_map(Some(1))?;
                m.serialize_entry("preset", p)?;
                m.end()
            }
            Reflectance::Ior { eta, k } => {
                let mut m = s.serialize_map(Some(2))?;
                m.serialize_entry("eta", eta)?;
                m.serialize_entry("k", k)?;
                m.end()
            }
        }
    }
}

#[derive(Deserialize)]
#[serde(field_identifier, rename_all = "snake_case")]
enum ReflectanceKey {
    Preset,
    Eta,
    K,
}

struct ReflectanceVisitor;

impl<'de> Visitor<'de> for ReflectanceVisitor {
    type Value = Reflectance;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number, an array of 3 numbers, { preset = \"…\" } or { eta = …, k = … }")
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Reflectance, E> {
        RgbVisitor.visit_f64(v).map(Reflectance::Value)
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Reflectance, E> {
        RgbVisitor.visit_i64(v).map(Reflectance::Value)
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Reflectance, E> {
        RgbVisitor.visit_u64(v).map(Reflectance::Value)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Reflectance, A::Error> {
        RgbVisitor.visit_seq(seq).map(Reflectance::Value)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Reflectance, A::Error> {
        let (mut preset, mut eta, mut k) = (None, None, None);
        while let Some(key) = map.next_key()? {
            match key {
                ReflectanceKey::Preset if preset.is_none() => {
                    preset = Some(map.next_value_seed(Named::<Preset>::new("preset"))?);
                }
                ReflectanceKey::Eta if eta.is_none() => {
                    eta = Some(map.next_value_seed(Named::<Rgb>::new("eta"))?);
                }
                ReflectanceKey::K if k.is_none() => {
                    k = Some(map.next_value_seed(Named::<Rgb>::new("k"))?);
                }
                ReflectanceKey::Preset => return Err(de::Error::duplicate_field("preset")),
                ReflectanceKey::Eta => return Err(de::Error::duplicate_field("eta")),
                ReflectanceKey::K => return Err(de::Error::duplicate_field("k")),
            }
        }
        match (preset, eta, k) {
            (Some(p), None, None) => Ok(Reflectance::Preset(p)),
            (None, Some(eta), k) => Ok(Reflectance::Ior {
                eta,
                k: k.unwrap_or(Rgb([0.0; 3])),
            }),
            (Some(_), _, _) => Err(de::Error::custom(
                "`preset` cannot be combined with `eta` or `k`",
            )),
            (None, None, _) => Err(de::Error::missing_field("eta")),
        }
    }
}

/// A `DeserializeSeed` that names the field in errors (for hand-written map visitors).
pub(crate) struct Named<T> {
    field: &'static str,
    _t: core::marker::PhantomData<T>,
}

impl<T> Named<T> {
    /// The seed for the value of `field`.
    pub(crate) fn new(field: &'static str) -> Self {
        Self {
            field,
            _t: core::marker::PhantomData,
        }
    }
}

impl<'de, T: Deserialize<'de>> de::DeserializeSeed<'de> for Named<T> {
    type Value = T;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<T, D::Error> {
        named(self.field, d)
    }
}

impl<'de> Deserialize<'de> for Reflectance {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ReflectanceVisitor)
    }
}

// ---------------------------------------------------------------------------------------------
// The parts of the microfacet models
// ---------------------------------------------------------------------------------------------

/// The microfacet distribution of a Cook-Torrance description (`ndf = "ggx"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[serde(expecting = "an NDF name (`ggx` or `beckmann`)")]
#[non_exhaustive]
pub enum NdfDesc {
    /// [`Ggx`] (Trowbridge-Reitz).
    Ggx,
    /// [`Beckmann`].
    Beckmann,
}

impl NdfDesc {
    /// The runtime distribution of slope parameters `(alpha_x, alpha_y)`, each validated by
    /// the distribution's constructor (`[1e-4, 1]`); `isotropic` (the file gave one `alpha`)
    /// picks the specialized isotropic GGX, [`GgxIsotropic`].
    pub(crate) fn build<S: Scalar>(
        self,
        (alpha_x, alpha_y): (f64, f64),
        isotropic: bool,
    ) -> Result<AnyNdf<S>, Error> {
        let s = S::of;
        Ok(match (self, isotropic) {
            (NdfDesc::Ggx, true) => GgxIsotropic::new(s(alpha_x))?.into(),
            (NdfDesc::Ggx, false) => Ggx::anisotropic(s(alpha_x), s(alpha_y))?.into(),
            (NdfDesc::Beckmann, _) => Beckmann::anisotropic(s(alpha_x), s(alpha_y))?.into(),
        })
    }
}

/// The Fresnel term of a Cook-Torrance or layered description (`fresnel = …`).
///
/// In TOML: `fresnel = { preset = "gold" }` (exact: conductor if the preset absorbs,
/// else dielectric), `{ dielectric = { eta = 1.5 } }`, `{ conductor = { eta = […], k = […] } }`,
/// `{ schlick = { f0 = 0.04 } }` or `"one"` (`F = 1`, for white-furnace tests).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
#[serde(
    expecting = "a Fresnel term: `{ preset = … }`, `{ dielectric = … }`, `{ conductor = … }`, `{ schlick = … }` or `\"one\"`"
)]
#[non_exhaustive]
pub enum FresnelDesc {
    /// The exact Fresnel term of a preset.
    Preset(Preset),
    /// Exact dielectric Fresnel, relative IOR `eta ∈ [1e-4, 1e4]`.
    Dielectric {
        /// Relative IOR.
        #[serde(deserialize_with = "field::eta")]
        eta: f64,
    },
    /// Exact conductor Fresnel, complex IOR `eta + i k` per channel.
    Conductor {
        /// Real part, in `[1e-4, 1e4]`.
        #[serde(deserialize_with = "field::eta")]
        eta: Rgb,
        /// Extinction, in `[0, 1e4]`.
        #[serde(deserialize_with = "field::k")]
        k: Rgb,
        /// Whether the channels share one division on the batch kernels of divider-bound
        /// cores ([`crate::fresnel::Conductor::share_divisions`]: within 8 ULP of the
        /// per-channel term; requires `k ≥ 0.1` and `η² + k² ≤ 512` in every channel).
        /// Optional, default `false`.
        #[serde(default, skip_serializing_if = "core::ops::Not::not")]
        share_divisions: bool,
    },
    /// Schlick's approximation with `f0`.
    Schlick {
        /// Normal-incidence reflectance.
        #[serde(deserialize_with = "field::f0")]
        f0: Reflectance,
    },
    /// `F = 1`.
    One,
}

/// The runtime Fresnel term of a description.
pub(crate) fn build_fresnel<S: Scalar>(d: &FresnelDesc) -> Result<AnyFresnel<S>, Error> {
    let rgb = |v: Rgb| v.0.map(S::of);
    Ok(match *d {
        FresnelDesc::Preset(p) => {
            let (eta, k) = p.ior();
            if p.is_conductor() {
                Conductor::new(eta.map(S::of), k.map(S::of))?.into()
            } else {
                Dielectric::new(S::of(eta[1]))?.into()
            }
        }
        FresnelDesc::Dielectric { eta } => Dielectric::new(S::of(eta))?.into(),
        FresnelDesc::Conductor {
            eta,
            k,
            share_divisions: false,
        } => Conductor::new(rgb(eta), rgb(k))?.into(),
        FresnelDesc::Conductor {
            eta,
            k,
            share_divisions: true,
        } => Conductor::new(rgb(eta), rgb(k))?.share_divisions()?.into(),
        FresnelDesc::Schlick { f0 } => Schlick::new(rgb(Rgb(f0.value()?)))?.into(),
        FresnelDesc::One => NoFresnel.into(),
    })
}

// ---------------------------------------------------------------------------------------------
// Roughness fields
// ---------------------------------------------------------------------------------------------

/// Either `alpha` or both `alpha_x` and `alpha_y`.
pub(crate) fn alphas(
    model: &'static str,
    alpha: Option<f64>,
    alpha_x: Option<f64>,
    alpha_y: Option<f64>,
) -> Result<(f64, f64), MaterialError> {
    let bad = |field, reason| {
        Err(MaterialError::Inconsistent {
            model,
            field,
            reason,
        })
    };
    match (alpha, alpha_x, alpha_y) {
        (Some(a), None, None) => Ok((a, a)),
        (None, Some(x), Some(y)) => Ok((x, y)),
        (Some(_), _, _) => bad(
            "alpha",
            "give either `alpha` or both `alpha_x` and `alpha_y`",
        ),
        (None, None, None) => bad(
            "alpha",
            "missing: give `alpha` or both `alpha_x` and `alpha_y`",
        ),
        (None, None, Some(_)) => bad("alpha_x", "missing: `alpha_y` needs `alpha_x`"),
        (None, Some(_), None) => bad("alpha_y", "missing: `alpha_x` needs `alpha_y`"),
    }
}

/// When the file gave an isotropic `alpha`, reports the constructor's `alpha_x`/`alpha_y`
/// as `alpha`, the field the user wrote.
pub(crate) fn iso_alpha(isotropic: bool, e: Error) -> Error {
    let rename = |p: &'static str| {
        if isotropic && p.starts_with("alpha_") {
            "alpha"
        } else {
            p
        }
    };
    match e {
        Error::NotFinite { param } => Error::NotFinite {
            param: rename(param),
        },
        Error::OutOfDomain {
            param,
            value,
            domain,
        } => Error::OutOfDomain {
            param: rename(param),
            value,
            domain,
        },
        Error::DoesNotFit {
            param,
            value,
            number_type,
        } => Error::DoesNotFit {
            param: rename(param),
            value,
            number_type,
        },
        // Names no parameter.
        e @ Error::FitInaccurate { .. } => e,
    }
}
