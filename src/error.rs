//! Typed errors for parameters rejected at construction.
//!
//! Hot-path functions never validate: they document their domain and stay branch-free.
//! Everything a user configures (IOR, shininess, roughness, albedo, …) is validated once, when
//! a model or material is built, and bad input is reported here instead of as a NaN later.

use core::fmt;

/// A parameter that was rejected when a model or material was constructed.
///
/// Non-exhaustive: later versions may reject parameters for new reasons.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
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
        /// The accepted domain in interval notation, e.g. `"(0, ∞)"` or `"[1e-4, 1]"`.
        domain: &'static str,
    },
    /// The parameter is finite and within the domain's formula, but its magnitude does not
    /// fit in `number_type`, a number type the model may be evaluated on: every model can be
    /// splatted to `f32` ([`crate::real::Splat`]), so a model built on `f64` takes only
    /// parameters an `f32` can hold (`|x| ≤ f32::MAX ≈ 3.4e38`).
    DoesNotFit {
        /// Name of the parameter, as in the constructor's signature (e.g. `"sigma"`).
        param: &'static str,
        /// The rejected value.
        value: f64,
        /// The number type it does not fit in, e.g. `"f32"`.
        number_type: &'static str,
    },
    /// A fitted approximation (such as [`crate::fresnel::FittedConductor`]) of valid
    /// parameters that misses its accuracy bound: the exact form should be used instead.
    FitInaccurate {
        /// The largest relative error the fit reached (`∞` for a NaN or a zero target).
        max_error: f64,
        /// The bound it had to meet.
        tolerance: f64,
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
            } => write!(
                f,
                "parameter `{param}` = {} is outside its domain {domain}",
                Short(*value)
            ),
            Error::DoesNotFit {
                param,
                value,
                number_type,
            } => write!(
                f,
                "parameter `{param}` = {} does not fit in {number_type}",
                Short(*value)
            ),
            Error::FitInaccurate {
                max_error,
                tolerance,
            } => write!(
                f,
                "the fit's relative error {} exceeds its bound {}: use the exact form",
                Short(*max_error),
                Short(*tolerance)
            ),
        }
    }
}

impl core::error::Error for Error {}

/// A number in short form for messages: the shortest digits that round-trip, in plain
/// notation for magnitudes in `[1e-3, 1e6)` (and 0) and in exponent notation otherwise
/// (`1e-300`, `3.4028235e38`, `1.5e-7`, not their hundreds of digits). A value that is exactly
/// an `f32` is written with the `f32`'s shortest digits (`1e-4`, not `9.999999747378752e-5`):
/// parameters given as `f32` are widened to `f64` in [`Error`].
pub(crate) struct Short(pub(crate) f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let a = v.abs();
        let plain = a == 0.0 || !v.is_finite() || (1e-3..1e6).contains(&a);
        // Exactly an f32 (and in its normal range): its own shortest digits are shorter.
        let narrow = v as f32;
        if f64::from(narrow) == v && (a == 0.0 || a >= f64::from(f32::MIN_POSITIVE)) {
            if plain {
                write!(f, "{narrow}")
            } else {
                write!(f, "{narrow:e}")
            }
        } else if plain {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

/// The largest magnitude a parameter may have: `f32::MAX` (see [`Error::DoesNotFit`]).
const F32_MAX: f64 = f32::MAX as f64;

/// Checks that `value` is finite, satisfies `ok` and fits in `f32`; otherwise names `param`
/// (and `domain`).
///
/// The shared mechanism behind every constructor's validation. The domain is checked before
/// the fit, so a value beyond a bounded domain is reported against that domain.
#[inline]
pub(crate) fn check<T: Into<f64> + Copy>(
    param: &'static str,
    value: T,
    domain: &'static str,
    ok: impl FnOnce(f64) -> bool,
) -> Result<T, Error> {
    let v = check_f64(param, value, domain, ok)?.into();
    if v.abs() > F32_MAX {
        Err(Error::DoesNotFit {
            param,
            value: v,
            number_type: "f32",
        })
    } else {
        Ok(value)
    }
}

/// [`check`] without the `f32` fit: for parameters of `f64`-only computations (the fit
/// analysis of [`crate::normalization::fit::fit_error`]).
#[inline]
pub(crate) fn check_f64<T: Into<f64> + Copy>(
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

/// `value ∈ [lo, hi]`, the bounds compared in the precision of `S` (rounded to nearest), so
/// that `1e-4_f32` (which is below `1e-4`) is accepted for a bound `1e-4`.
#[inline]
pub(crate) fn in_range<S: crate::Scalar>(
    param: &'static str,
    value: S,
    lo: f64,
    hi: f64,
    domain: &'static str,
) -> Result<S, Error> {
    let (lo, hi): (f64, f64) = (S::of(lo).into(), S::of(hi).into());
    check(param, value, domain, |v| (lo..=hi).contains(&v))
}

/// [`Error::FitInaccurate`].
#[inline]
pub(crate) fn fit_inaccurate(max_error: f64, tolerance: f64) -> Error {
    Error::FitInaccurate {
        max_error,
        tolerance,
    }
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

    fn positive<T: Into<f64> + Copy>(param: &'static str, value: T) -> Result<T, Error> {
        check(param, value, "(0, ∞)", |v| v > 0.0)
    }

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

    #[test]
    fn finite_values_beyond_f32_do_not_fit() {
        assert_eq!(
            non_negative("sigma", 1e300),
            Err(Error::DoesNotFit {
                param: "sigma",
                value: 1e300,
                number_type: "f32"
            })
        );
        let msg = format!("{}", non_negative("sigma", 1e300).unwrap_err());
        assert_eq!(msg, "parameter `sigma` = 1e300 does not fit in f32");
        // The largest f32 fits; the next f64 above it does not.
        let max = f64::from(f32::MAX);
        assert_eq!(non_negative("x", max), Ok(max));
        assert!(matches!(
            non_negative("x", max.next_up()),
            Err(Error::DoesNotFit { .. })
        ));
        // A bounded domain is reported as such, even beyond f32.
        assert!(matches!(
            unit_interval("f0", 1e300),
            Err(Error::OutOfDomain { .. })
        ));
        // f64-only checks have no f32 bound.
        assert_eq!(check_f64("offset", 1e300, "(−∞, ∞)", |_| true), Ok(1e300));
    }

    #[test]
    fn in_range_compares_in_the_lane_precision() {
        // 1e-4_f32 = 9.99999974e-5 < 1e-4: accepted for the bound 1e-4 on f32.
        assert_eq!(
            in_range("alpha", 1e-4_f32, 1e-4, 1.0, "[1e-4, 1]"),
            Ok(1e-4_f32)
        );
        let below = 1e-4_f32.next_down();
        assert!(in_range("alpha", below, 1e-4, 1.0, "[1e-4, 1]").is_err());
        assert!(in_range("alpha", 1.0_f64.next_up(), 1e-4, 1.0, "[1e-4, 1]").is_err());
    }

    #[test]
    fn values_print_in_short_form() {
        let s = |v: f64| format!("{}", Short(v));
        assert_eq!(s(1e-300), "1e-300");
        assert_eq!(s(1e300), "1e300");
        assert_eq!(s(-2.5e-7), "-2.5e-7");
        assert_eq!(s(0.0), "0");
        assert_eq!(s(0.5), "0.5");
        assert_eq!(s(123456.0), "123456");
        assert_eq!(s(1e6), "1e6");
        assert_eq!(s(f64::from(1e-4_f32)), "1e-4");
        assert_eq!(s(1e-4), "1e-4");
        assert_eq!(s(0.001), "0.001");
        assert_eq!(s(f64::from(1e-5_f32)), "1e-5");
        assert_eq!(s(f64::from(f32::MAX)), "3.4028235e38");
        assert_eq!(s(0.1), "0.1");
        assert_eq!(s(f64::from(0.1_f32)), "0.1");
        assert_eq!(s(1.0 + 1e-12), "1.000000000001");
    }
}
