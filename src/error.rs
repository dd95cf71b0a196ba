//! Typed errors for parameters rejected at construction.
//!
//! Hot-path functions never validate: they document their domain and stay branch-free.
//! Everything a user configures (IOR, shininess, roughness, albedo, …) is validated once, when
//! a model or material is built, and bad input is reported here instead of as a NaN later.

use core::fmt;

/// A parameter that was rejected when a model or material was constructed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Error {
    /// The parameter is NaN or infinite.
    NotFinite {
        /// Name of the parameter, as in the constructor's signature (e.g. `"eta"`).
        param: &'static str,
    },
    /// The parameter is finite but outside the model's domain.
    OutOfDomain {
        /// Name of the parameter, as in the constructor's signature (e.g. `"shininess"`).
        param: &'static str,
        /// The rejected value (widened to `f64`).
        value: f64,
        /// The accepted domain in interval notation, e.g. `"(0, ∞)"`.
        domain: &'static str,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NotFinite { param } => write!(f, "parameter `{param}` must be finite"),
            Error::OutOfDomain {
                param,
                value,
                domain,
            } => {
                write!(
                    f,
                    "parameter `{param}` = {value} is outside its domain {domain}"
                )
            }
        }
    }
}

impl core::error::Error for Error {}

/// Checks that `value` is finite and satisfies `ok`; otherwise names `param` and `domain`.
///
/// The shared mechanism behind every constructor's validation.
#[inline]
pub(crate) fn check<T: Into<f64> + Copy>(
    param: &'static str,
    value: T,
    domain: &'static str,
    ok: impl FnOnce(f64) -> bool,
) -> Result<T, Error> {
    let v: f64 = value.into();
    if !v.is_finite() {
        Err(Error::NotFinite { param })
    } else if !ok(v) {
        Err(Error::OutOfDomain {
            param,
            value: v,
            domain,
        })
    } else {
        Ok(value)
    }
}

/// `value ∈ (0, ∞)`.
#[inline]
pub(crate) fn positive<T: Into<f64> + Copy>(param: &'static str, value: T) -> Result<T, Error> {
    check(param, value, "(0, ∞)", |v| v > 0.0)
}

/// `value ∈ [0, ∞)`.
#[inline]
pub(crate) fn non_negative<T: Into<f64> + Copy>(param: &'static str, value: T) -> Result<T, Error> {
    check(param, value, "[0, ∞)", |v| v >= 0.0)
}

/// `value ∈ [0, 1]`.
#[inline]
pub(crate) fn unit_interval<T: Into<f64> + Copy>(
    param: &'static str,
    value: T,
) -> Result<T, Error> {
    check(param, value, "[0, 1]", |v| (0.0..=1.0).contains(&v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::format;

    #[test]
    fn rejects_nan_infinite_and_out_of_domain() {
        assert_eq!(
            positive("eta", f64::NAN),
            Err(Error::NotFinite { param: "eta" })
        );
        assert_eq!(
            non_negative("k", f32::INFINITY),
            Err(Error::NotFinite { param: "k" })
        );
        assert_eq!(
            positive("shininess", 0.0f32),
            Err(Error::OutOfDomain {
                param: "shininess",
                value: 0.0,
                domain: "(0, ∞)"
            })
        );
        assert_eq!(unit_interval("f0", 1.0), Ok(1.0));
        assert!(unit_interval("f0", 1.0 + 1e-12).is_err());
        let msg = format!("{}", positive("alpha", -1.0).unwrap_err());
        assert_eq!(msg, "parameter `alpha` = -1 is outside its domain (0, ∞)");
    }
}
