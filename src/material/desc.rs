//! File descriptions of [`Material`]s (feature `serde`): the trait each model's description
//! implements beside its model ([`ModelDesc`]), and what [`MaterialDesc`] does with any of
//! them — read the `model` key, check the limits, validate, build, serialize. See the
//! [module docs](super).

use alloc::vec::Vec;
use core::fmt;

use serde::de::{self, Deserializer, Visitor};
use serde::ser::{Impossible, SerializeStruct, Serializer};
use serde::{Deserialize, Serialize};

use super::value::{Value, ValueDe, ValueVisitor};
use super::{Material, MaterialDesc, named};
use crate::{Error, Scalar};

// ---------------------------------------------------------------------------------------------
// What each model's description implements
// ---------------------------------------------------------------------------------------------

/// The file description of one model (feature `serde`), implemented beside the model in
/// `src/models/<model>.rs` and listed once in the dispatcher (`models!` in
/// `src/material/mod.rs`), which makes it a variant of [`MaterialDesc`].
///
/// The type itself is the model's parameters as plain `f64` numbers, with serde's derives
/// (`deny_unknown_fields`, one `deserialize_with = "field::…"` per field so that errors name
/// it); deserializing it does not validate (the constructors do, in [`ModelDesc::build`]).
pub(crate) trait ModelDesc: Sized {
    /// The model's name in files (`model = "…"`), snake case.
    const NAME: &'static str;

    /// Whether the parameters of this description itself (not of its [`parts`](Self::parts))
    /// make the material depend on the azimuth about the normal.
    fn is_anisotropic(&self) -> bool;

    /// The descriptions a composition holds (`sum`, `layered`), `None` for a leaf model.
    /// [`MaterialDesc`] walks them with an explicit stack, for the limits and anisotropy.
    #[inline]
    fn parts(&self) -> Option<Parts<'_>> {
        None
    }

    /// The model, built with the crate's validating constructors on `S`.
    ///
    /// A composition builds its parts with [`MaterialDesc::build_checked`]: the caller
    /// ([`MaterialDesc::build`]) has checked the limits, so that recursion is at most
    /// [`MAX_DEPTH`] deep.
    ///
    /// # Errors
    /// [`MaterialError::Invalid`] (see [`invalid`]) or [`MaterialError::Inconsistent`],
    /// naming [`Self::NAME`].
    fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError>;
}

/// The descriptions a composition holds, in order (see [`ModelDesc::parts`]): a slice
/// (`sum`'s terms) and up to two boxed ones (`layered`'s base and coat).
#[derive(Clone, Copy)]
pub(crate) struct Parts<'a> {
    slice: &'a [MaterialDesc],
    pair: [Option<&'a MaterialDesc>; 2],
}

impl<'a> Parts<'a> {
    /// The terms of a slice.
    pub(crate) fn slice(slice: &'a [MaterialDesc]) -> Self {
        Self {
            slice,
            pair: [None, None],
        }
    }

    /// Two parts.
    pub(crate) fn pair(a: &'a MaterialDesc, b: &'a MaterialDesc) -> Self {
        Self {
            slice: &[],
            pair: [Some(a), Some(b)],
        }
    }

    /// How many.
    fn len(self) -> usize {
        self.slice.len() + self.pair.iter().flatten().count()
    }

    /// In order.
    fn iter(self) -> impl DoubleEndedIterator<Item = &'a MaterialDesc> {
        self.slice.iter().chain(self.pair.into_iter().flatten())
    }
}

/// `map_err(invalid(Self::NAME))`: a constructor's error as [`MaterialError::Invalid`] of
/// `model`.
pub(crate) fn invalid(model: &'static str) -> impl Fn(Error) -> MaterialError {
    move |error| MaterialError::Invalid { model, error }
}

// ---------------------------------------------------------------------------------------------
// Limits and errors
// ---------------------------------------------------------------------------------------------

/// The most descriptions on one path from the root of a material to a leaf model
/// (`sum` and `layered` nest others): deeper descriptions are rejected by
/// [`MaterialDesc::validate`] and [`MaterialDesc::build`] with [`MaterialError::TooDeep`],
/// found without recursion.
pub const MAX_DEPTH: usize = 32;

/// The most leaf models (every description other than `sum` and `layered`) in one material:
/// a `sum` evaluates each term for every direction pair, so larger ones are rejected with
/// [`MaterialError::TooLarge`] instead of loading and then rendering for minutes.
pub const MAX_TERMS: usize = 1024;

/// A description that the model's constructor rejected, an inconsistent one, or one past
/// the limits [`MAX_DEPTH`] and [`MAX_TERMS`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum MaterialError {
    /// A constructor rejected a parameter.
    Invalid {
        /// The model (`model = "…"`).
        model: &'static str,
        /// The constructor's error, naming the parameter.
        error: Error,
    },
    /// Fields that do not go together.
    Inconsistent {
        /// The model.
        model: &'static str,
        /// The field at fault.
        field: &'static str,
        /// Why.
        reason: &'static str,
    },
    /// Descriptions nested deeper than [`MAX_DEPTH`].
    TooDeep {
        /// The limit, [`MAX_DEPTH`].
        limit: usize,
    },
    /// More leaf models than [`MAX_TERMS`].
    TooLarge {
        /// The model whose field went past the limit (`"sum"` or `"layered"`).
        model: &'static str,
        /// How many terms that `sum` has, or how many leaf models were counted when the
        /// limit was passed.
        count: usize,
        /// The limit, [`MAX_TERMS`].
        limit: usize,
    },
}

impl fmt::Display for MaterialError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MaterialError::Invalid { model, error } => write!(f, "`{model}`: {error}"),
            MaterialError::Inconsistent {
                model,
                field,
                reason,
            } => {
                write!(f, "`{model}`: field `{field}`: {reason}")
            }
            MaterialError::TooDeep { limit } => write!(
                f,
                "materials nested more than {limit} levels deep (`sum` and `layered` inside each other)"
            ),
            MaterialError::TooLarge {
                model,
                count,
                limit,
            } => write!(
                f,
                "`{model}`: {count} terms, more than the {limit} models one material may hold"
            ),
        }
    }
}

impl core::error::Error for MaterialError {}

// ---------------------------------------------------------------------------------------------
// What a description does, whatever its model
// ---------------------------------------------------------------------------------------------

impl MaterialDesc {
    /// Whether the material depends on the azimuth about the normal (so a renderer needs
    /// a tangent frame, and an albedo table needs `φ`).
    /// Walks the tree with an explicit stack, so any depth is safe.
    #[must_use]
    pub fn is_anisotropic(&self) -> bool {
        let mut stack = alloc::vec![self];
        while let Some(d) = stack.pop() {
            if d.own_anisotropy() {
                return true;
            }
            if let Some(parts) = d.parts() {
                stack.extend(parts.iter());
            }
        }
        false
    }

    /// Checks the limits ([`Self::check_limits`]) and that the material builds in `f32` and
    /// in `f64` (what deserialization runs).
    ///
    /// # Errors
    /// The first limit passed or rejected parameter.
    pub fn validate(&self) -> Result<(), MaterialError> {
        self.check_limits()?;
        self.build_checked::<f64>()?;
        self.build_checked::<f32>()?;
        Ok(())
    }

    /// Checks [`MAX_DEPTH`] and [`MAX_TERMS`] with an explicit stack (no recursion, and at
    /// most about `MAX_TERMS + MAX_DEPTH` descriptions visited whatever the size of `self`).
    ///
    /// # Errors
    /// [`MaterialError::TooDeep`] or [`MaterialError::TooLarge`].
    pub fn check_limits(&self) -> Result<(), MaterialError> {
        let mut stack: Vec<(&MaterialDesc, usize)> = Vec::new();
        stack.push((self, 1));
        let mut leaves = 0usize;
        while let Some((d, depth)) = stack.pop() {
            if depth > MAX_DEPTH {
                return Err(MaterialError::TooDeep { limit: MAX_DEPTH });
            }
            if let Some(parts) = d.parts() {
                if parts.len() > MAX_TERMS {
                    return Err(MaterialError::TooLarge {
                        model: d.model_name(),
                        count: parts.len(),
                        limit: MAX_TERMS,
                    });
                }
                // Pushed last to first, so the first part (`layered`'s base) is visited
                // first: depth is found before size.
                stack.extend(parts.iter().rev().map(|t| (t, depth + 1)));
            } else {
                leaves += 1;
                if leaves > MAX_TERMS {
                    return Err(MaterialError::TooLarge {
                        model: self.model_name(),
                        count: leaves,
                        limit: MAX_TERMS,
                    });
                }
            }
        }
        Ok(())
    }

    /// Builds the model with the constructors of the crate, after [`Self::check_limits`].
    ///
    /// # Errors
    /// [`MaterialError`] naming the model and the parameter, or the limit passed.
    pub fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
        self.check_limits()?;
        self.build_checked()
    }
}

impl<'de> Deserialize<'de> for MaterialDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        // Buffer the table first (naming each key in parse errors), then read `model`
        // wherever it is, then the parameters into that model's description.
        let Value::Map(mut entries) = d.deserialize_any(ValueVisitor(0))? else {
            return Err(de::Error::custom(
                "expected a material: a table with a `model` key",
            ));
        };
        let Some(at) = entries.iter().position(|(k, _)| k == "model") else {
            return Err(de::Error::missing_field("model"));
        };
        let (_, tag) = entries.remove(at);
        let ModelName(name) = named("model", ValueDe::<D::Error>::new(tag))?;
        let desc = MaterialDesc::read(name, ValueDe::<D::Error>::new(Value::Map(entries)))?;
        desc.validate().map_err(de::Error::custom)?;
        Ok(desc)
    }
}

/// The value of `model`: one of [`MaterialDesc::NAMES`].
struct ModelName(&'static str);

impl<'de> Deserialize<'de> for ModelName {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_str(ModelNameVisitor)
    }
}

struct ModelNameVisitor;

impl Visitor<'_> for ModelNameVisitor {
    type Value = ModelName;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a model name")
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<ModelName, E> {
        MaterialDesc::NAMES
            .iter()
            .find(|&&n| n == v)
            .map(|&n| ModelName(n))
            .ok_or_else(|| E::unknown_variant(v, MaterialDesc::NAMES))
    }
}

impl Serialize for MaterialDesc {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.write(Tagged {
            inner: s,
            name: self.model_name(),
        })
    }
}

/// Serializes a model's description (a struct) with `model = "<name>"` as its first field.
pub(crate) struct Tagged<S> {
    inner: S,
    name: &'static str,
}

/// The error of anything but a struct given to [`Tagged`] (a description is a table).
fn not_a_table<E: serde::ser::Error>() -> E {
    E::custom("a model description serializes as a table")
}

/// Serializer methods of [`Tagged`] that refuse their value.
macro_rules! refuse {
    ($($f:ident($($t:ty),*)),* $(,)?) => {
        $(fn $f(self, $(_: $t),*) -> Result<S::Ok, S::Error> {
            Err(not_a_table())
        })*
    };
}

impl<S: Serializer> Serializer for Tagged<S> {
    type Ok = S::Ok;
    type Error = S::Error;
    type SerializeSeq = Impossible<S::Ok, S::Error>;
    type SerializeTuple = Impossible<S::Ok, S::Error>;
    type SerializeTupleStruct = Impossible<S::Ok, S::Error>;
    type SerializeTupleVariant = Impossible<S::Ok, S::Error>;
    type SerializeMap = Impossible<S::Ok, S::Error>;
    type SerializeStruct = S::SerializeStruct;
    type SerializeStructVariant = Impossible<S::Ok, S::Error>;

    fn serialize_struct(
        self,
        name: &'static str,
        len: usize,
    ) -> Result<S::SerializeStruct, S::Error> {
        let mut st = self.inner.serialize_struct(name, len + 1)?;
        st.serialize_field("model", self.name)?;
        Ok(st)
    }

    refuse!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_f32(f32),
        serialize_f64(f64),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_none(),
        serialize_unit(),
        serialize_unit_struct(&'static str),
        serialize_unit_variant(&'static str, u32, &'static str),
    );

    fn serialize_some<T: ?Sized + Serialize>(self, _: &T) -> Result<S::Ok, S::Error> {
        Err(not_a_table())
    }
    fn serialize_newtype_struct<T: ?Sized + Serialize>(
        self,
        _: &'static str,
        _: &T,
    ) -> Result<S::Ok, S::Error> {
        Err(not_a_table())
    }
    fn serialize_newtype_variant<T: ?Sized + Serialize>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<S::Ok, S::Error> {
        Err(not_a_table())
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, S::Error> {
        Err(not_a_table())
    }
    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, S::Error> {
        Err(not_a_table())
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, S::Error> {
        Err(not_a_table())
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, S::Error> {
        Err(not_a_table())
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, S::Error> {
        Err(not_a_table())
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, S::Error> {
        Err(not_a_table())
    }
}
