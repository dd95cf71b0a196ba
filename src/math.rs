//! Private scalar math backend: `std` when it is enabled, `libm` otherwise.
//!
//! Without `std`, `f32::sqrt` and friends are not inherent methods of `core`, so every
//! scalar transcendental in the crate goes through these functions (glam's pattern).

#[cfg(feature = "std")]
macro_rules! std_backend {
    ($m:ident, $t:ty) => {
        pub(crate) mod $m {
            #[inline(always)]
            pub(crate) fn sqrt(x: $t) -> $t {
                x.sqrt()
            }
            #[inline(always)]
            pub(crate) fn exp(x: $t) -> $t {
                x.exp()
            }
            #[inline(always)]
            pub(crate) fn exp2(x: $t) -> $t {
                x.exp2()
            }
            #[inline(always)]
            pub(crate) fn ln(x: $t) -> $t {
                x.ln()
            }
            #[inline(always)]
            pub(crate) fn log2(x: $t) -> $t {
                x.log2()
            }
            #[inline(always)]
            pub(crate) fn pow(x: $t, y: $t) -> $t {
                x.powf(y)
            }
            #[inline(always)]
            pub(crate) fn sin(x: $t) -> $t {
                x.sin()
            }
            #[inline(always)]
            pub(crate) fn cos(x: $t) -> $t {
                x.cos()
            }
            #[inline(always)]
            pub(crate) fn floor(x: $t) -> $t {
                x.floor()
            }
            #[allow(dead_code)]
            #[inline(always)]
            pub(crate) fn fma(a: $t, b: $t, c: $t) -> $t {
                a.mul_add(b, c)
            }
        }
    };
}

#[cfg(not(feature = "std"))]
macro_rules! libm_backend {
    ($m:ident, $t:ty, $sqrt:ident, $exp:ident, $exp2:ident, $ln:ident, $log2:ident, $pow:ident,
     $sin:ident, $cos:ident, $floor:ident, $fma:ident) => {
        pub(crate) mod $m {
            #[inline(always)]
            pub(crate) fn sqrt(x: $t) -> $t {
                libm::$sqrt(x)
            }
            #[inline(always)]
            pub(crate) fn exp(x: $t) -> $t {
                libm::$exp(x)
            }
            #[inline(always)]
            pub(crate) fn exp2(x: $t) -> $t {
                libm::$exp2(x)
            }
            #[inline(always)]
            pub(crate) fn ln(x: $t) -> $t {
                libm::$ln(x)
            }
            #[inline(always)]
            pub(crate) fn log2(x: $t) -> $t {
                libm::$log2(x)
            }
            #[inline(always)]
            pub(crate) fn pow(x: $t, y: $t) -> $t {
                libm::$pow(x, y)
            }
            #[inline(always)]
            pub(crate) fn sin(x: $t) -> $t {
                libm::$sin(x)
            }
            #[inline(always)]
            pub(crate) fn cos(x: $t) -> $t {
                libm::$cos(x)
            }
            #[inline(always)]
            pub(crate) fn floor(x: $t) -> $t {
                libm::$floor(x)
            }
            #[allow(dead_code)]
            #[inline(always)]
            pub(crate) fn fma(a: $t, b: $t, c: $t) -> $t {
                libm::$fma(a, b, c)
            }
        }
    };
}

#[cfg(feature = "std")]
std_backend!(f32m, f32);
#[cfg(feature = "std")]
std_backend!(f64m, f64);
#[cfg(not(feature = "std"))]
libm_backend!(
    f32m, f32, sqrtf, expf, exp2f, logf, log2f, powf, sinf, cosf, floorf, fmaf
);
#[cfg(not(feature = "std"))]
libm_backend!(
    f64m, f64, sqrt, exp, exp2, log, log2, pow, sin, cos, floor, fma
);
