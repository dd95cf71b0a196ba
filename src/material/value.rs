//! A self-describing buffer for file descriptions (feature `serde`): a description's table
//! is read whole into a [`Value`] (so that `model` may come anywhere in it, with a cap on
//! nesting and on echoed strings), then replayed into the named model's description.

use alloc::vec::Vec;
use core::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};

use super::MAX_DEPTH;

/// A parsed value of any serde format.
#[derive(Clone, Debug)]
pub(crate) enum Value {
    Unit,
    Bool(bool),
    I64(i64),
    U64(u64),
    F64(f64),
    Str(alloc::string::String),
    Seq(Vec<Value>),
    Map(Vec<(alloc::string::String, Value)>),
}

/// How deeply the tables and arrays of one file may nest: room for [`MAX_DEPTH`] nested
/// descriptions (a `sum` level takes a table and an array) and the few levels inside a leaf
/// model (Lafortune's lobes, an `f0` table). Checked while reading, so hostile input cannot
/// overflow the stack whatever the format's own limit.
const MAX_VALUE_DEPTH: usize = 2 * MAX_DEPTH + 6;

/// The longest input string echoed in a message, in characters; longer ones are cut with
/// `…` (no name the crate knows is this long, so a cut string never matches one).
const MAX_ECHO: usize = 48;

/// `s`, cut to [`MAX_ECHO`] characters with a trailing `…` if longer.
pub(crate) fn truncated(s: &str) -> alloc::string::String {
    match s.char_indices().nth(MAX_ECHO) {
        None => s.into(),
        Some((at, _)) => {
            let mut t = alloc::string::String::from(&s[..at]);
            t.push('…');
            t
        }
    }
}

/// Reads any value nested at most [`MAX_VALUE_DEPTH`] deep (`.0` is the current depth);
/// errors while reading a map's value name its key.
#[derive(Clone, Copy)]
pub(crate) struct ValueVisitor(pub(crate) usize);

impl<'de> de::DeserializeSeed<'de> for ValueVisitor {
    type Value = Value;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl ValueVisitor {
    /// The visitor one table or array deeper, or the error past the limit.
    fn deeper<E: de::Error>(self) -> Result<Self, E> {
        if self.0 >= MAX_VALUE_DEPTH {
            Err(E::custom(format_args!(
                "tables and arrays nested more than {MAX_VALUE_DEPTH} levels deep"
            )))
        } else {
            Ok(ValueVisitor(self.0 + 1))
        }
    }
}

/// [`ValueVisitor`] for the value of key `key`.
struct KeyedValue<'a> {
    key: &'a str,
    inner: ValueVisitor,
}

impl<'de> de::DeserializeSeed<'de> for KeyedValue<'_> {
    type Value = Value;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        let key = self.key;
        d.deserialize_any(self.inner)
            .map_err(|e| de::Error::custom(format_args!("`{key}`: {e}")))
    }
}

impl<'de> Visitor<'de> for ValueVisitor {
    type Value = Value;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any value")
    }
    fn visit_unit<E: de::Error>(self) -> Result<Value, E> {
        Ok(Value::Unit)
    }
    fn visit_none<E: de::Error>(self) -> Result<Value, E> {
        Ok(Value::Unit)
    }
    fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        d.deserialize_any(self.deeper()?)
    }
    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Value, E> {
        Ok(Value::I64(v))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Value, E> {
        Ok(Value::U64(v))
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Value, E> {
        Ok(Value::F64(v))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Value, E> {
        // Every string of a description is a name; a longer one is wrong anyway, and
        // cutting it here keeps every message that echoes it short.
        Ok(Value::Str(truncated(v)))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let inner = self.deeper()?;
        let mut v = Vec::new();
        while let Some(x) = seq.next_element_seed(inner)? {
            v.push(x);
        }
        Ok(Value::Seq(v))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let inner = self.deeper()?;
        let mut v = Vec::new();
        while let Some(k) = map.next_key::<alloc::string::String>()? {
            let k = truncated(&k);
            let x = map.next_value_seed(KeyedValue { key: &k, inner })?;
            v.push((k, x));
        }
        Ok(Value::Map(v))
    }
}

/// Replays a [`Value`] into any `Deserialize` type, with the caller's error type.
pub(crate) struct ValueDe<E> {
    value: Value,
    _e: core::marker::PhantomData<E>,
}

impl<E> ValueDe<E> {
    /// Replays `value`.
    pub(crate) fn new(value: Value) -> Self {
        Self {
            value,
            _e: core::marker::PhantomData,
        }
    }
}

impl<'de, E: de::Error> de::IntoDeserializer<'de, E> for Value {
    type Deserializer = ValueDe<E>;
    fn into_deserializer(self) -> ValueDe<E> {
        ValueDe::new(self)
    }
}

impl<'de, E: de::Error> Deserializer<'de> for ValueDe<E> {
    type Error = E;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, E> {
        match self.value {
            Value::Unit => visitor.visit_unit(),
            Value::Bool(b) => visitor.visit_bool(b),
            Value::I64(i) => visitor.visit_i64(i),
            Value::U64(u) => visitor.visit_u64(u),
            Value::F64(f) => visitor.visit_f64(f),
            Value::Str(s) => visitor.visit_string(s),
            Value::Seq(v) => {
                let mut seq = de::value::SeqDeserializer::new(v.into_iter());
                let out = visitor.visit_seq(&mut seq)?;
                seq.end()?;
                Ok(out)
            }
            Value::Map(v) => {
                let mut map = de::value::MapDeserializer::new(v.into_iter());
                let out = visitor.visit_map(&mut map)?;
                map.end()?;
                Ok(out)
            }
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, E> {
        match self.value {
            Value::Unit => visitor.visit_none(),
            _ => visitor.visit_some(self),
        }
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, E> {
        match self.value {
            Value::Str(s) => visitor.visit_enum(de::IntoDeserializer::<E>::into_deserializer(s)),
            Value::Map(mut v) if v.len() == 1 => {
                let (variant, value) = v.pop().expect("one entry");
                visitor.visit_enum(EnumDe::<E> {
                    variant,
                    value: ValueDe::new(value),
                })
            }
            other => ValueDe::<E>::new(other).deserialize_any(visitor),
        }
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        unit unit_struct newtype_struct seq tuple tuple_struct map struct identifier ignored_any
    }
}

/// An externally tagged enum value `{ variant = value }`.
struct EnumDe<E> {
    variant: alloc::string::String,
    value: ValueDe<E>,
}

impl<'de, E: de::Error> de::EnumAccess<'de> for EnumDe<E> {
    type Error = E;
    type Variant = ValueDe<E>;
    fn variant_seed<V: de::DeserializeSeed<'de>>(
        self,
        seed: V,
    ) -> Result<(V::Value, ValueDe<E>), E> {
        let v = seed.deserialize(de::IntoDeserializer::<E>::into_deserializer(self.variant))?;
        Ok((v, self.value))
    }
}

impl<'de, E: de::Error> de::VariantAccess<'de> for ValueDe<E> {
    type Error = E;
    fn unit_variant(self) -> Result<(), E> {
        Deserialize::deserialize(self)
    }
    fn newtype_variant_seed<T: de::DeserializeSeed<'de>>(self, seed: T) -> Result<T::Value, E> {
        seed.deserialize(self)
    }
    fn tuple_variant<V: Visitor<'de>>(self, _len: usize, visitor: V) -> Result<V::Value, E> {
        self.deserialize_any(visitor)
    }
    fn struct_variant<V: Visitor<'de>>(
        self,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, E> {
        self.deserialize_any(visitor)
    }
}
