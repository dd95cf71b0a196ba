//! Ashikhmin-Shirley's anisotropic Phong BRDF (2000).

use super::{
    Brdf, DENOM_FLOOR, Energy, Properties, Reciprocity, half_and_cos_d, masked, safe_dirs,
    splat_channels, unit_channels,
};
use crate::Scalar;
use crate::fresnel::schlick_complement;
use crate::real::{Splat, splat_array, splat_scalar};
use crate::sampling::lobes::{
    PhongHalf, first_probability, mean, pdf_diffuse_and_half, sample_diffuse_and_half,
};
use crate::sampling::{Sample, SampleBrdf};
use crate::{Error, Real, Vec3};

/// Ashikhmin and Shirley's anisotropic Phong model: a Schlick-Fresnel anisotropic lobe and
/// a diffuse term coupled to it.
///
/// ```text
/// f = f_s + f_d
/// f_s = √((nu + 1)(nv + 1)) / (8π) · (n·h)^((nu (h·x)² + nv (h·y)²) / (1 − (n·h)²))
///       / ((h·k) max(cos θi, cos θo)) · F(h·k),       F(c) = Rs + (1 − Rs)(1 − c)⁵
/// f_d = 28 Rd / (23π) · (1 − Rs) (1 − (1 − cos θi/2)⁵) (1 − (1 − cos θo/2)⁵)
/// ```
///
/// `h` is the unit half vector, `k` either direction (`h·wi = h·wo`), `x`, `y` the tangent
/// and bitangent, `nu`, `nv` the Phong exponents along them. The exponent is evaluated as
/// `(nu hx² + nv hy²)/(hx² + hy²)` (equal to the published form for a unit `h`, and free of
/// the `0/0` at `h = n`, where any exponent gives `1`).
///
/// The seed talk's slide of this model matches the paper (JGT 2000, eq. 4 and 5).
///
/// Properties: reciprocal. The specular lobe is normalized so that its albedo stays below
/// `max F ≤ 1` (the paper's §3), and the diffuse term is scaled by `1 − Rs` and by the
/// Schlick-like factors so that `f_s + f_d` conserves energy (the paper's §4). The tests
/// check albedo ≤ 1 numerically for `(Rd, Rs) ∈ {(0, 1), (1, 0), (1, 0.05)}`,
/// `nu, nv ∈ [0, 10⁴]` (isotropic and strongly anisotropic) and `θo` up to 89.99°.
///
/// Domain: `Rd, Rs ∈ [0, 1]` per channel, `nu, nv ∈ [0, 1e6]`.
///
/// References: M. Ashikhmin, P. Shirley, "An Anisotropic Phong BRDF Model", Journal of
/// Graphics Tools 5(2), 2000 (and UUCS-00-014, "An Anisotropic Phong Light Reflection
/// Model"); C. Schlick, Eurographics 1994.
///
/// # Examples
///
/// ```
/// use brdf::{Vec3, models::{Brdf, AshikhminShirley}};
/// let m = AshikhminShirley::new([0.0_f32], [1.0], 100.0, 10.0)?;
/// let n = Vec3::new(0.0, 0.0, 1.0);
/// // Peak at normal incidence: √(101·11)/(8π).
/// let peak = (101.0f32 * 11.0).sqrt() / (8.0 * core::f32::consts::PI);
/// assert!((m.eval(n, n)[0] - peak).abs() < 1e-5);
/// # Ok::<(), brdf::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AshikhminShirley<R, const N: usize> {
    rs: [R; N],
    diffuse_k: [R; N],
    spec_k: R,
    nu: R,
    nv: R,
}

impl<S: Scalar, const N: usize> AshikhminShirley<S, N> {
    /// Diffuse `rd` and specular (normal-incidence Fresnel) `rs` per channel in `[0, 1]`,
    /// exponents `nu` (along x) and `nv` (along y) in `[0, 1e6]`.
    ///
    /// # Errors
    /// Names `"rd"`, `"rs"`, `"nu"` or `"nv"`.
    #[inline]
    pub fn new(rd: [S; N], rs: [S; N], nu: S, nv: S) -> Result<Self, Error> {
        let rd = unit_channels("rd", rd)?;
        let rs = unit_channels("rs", rs)?;
        let ok = |v: f64| (0.0..=1e6).contains(&v);
        let nu: f64 = crate::error::check("nu", nu, "[0, 1e6]", ok)?.into();
        let nv: f64 = crate::error::check("nv", nv, "[0, 1e6]", ok)?.into();
        let c = 28.0 / (23.0 * core::f64::consts::PI);
        let mut diffuse_k = [0.0; N];
        for i in 0..N {
            diffuse_k[i] = c * rd[i] * (1.0 - rs[i]);
        }
        Ok(Self {
            rs: splat_channels(rs),
            diffuse_k: splat_channels(diffuse_k),
            spec_k: S::from_f64(((nu + 1.0) * (nv + 1.0)).sqrt() / (8.0 * core::f64::consts::PI)),
            nu: S::from_f64(nu),
            nv: S::from_f64(nv),
        })
    }
}

impl<S: Scalar, const N: usize> Splat for AshikhminShirley<S, N> {
    type On<L: Real> = AshikhminShirley<L, N>;
    #[inline]
    fn splat<L: Real>(&self) -> AshikhminShirley<L, N> {
        AshikhminShirley {
            rs: splat_array(&self.rs),
            diffuse_k: splat_array(&self.diffuse_k),
            spec_k: splat_scalar(self.spec_k),
            nu: splat_scalar(self.nu),
            nv: splat_scalar(self.nv),
        }
    }
}

impl<R: Real, const N: usize> Brdf<R, N> for AshikhminShirley<R, N> {
    #[inline(always)]
    fn eval(&self, wi: Vec3<R>, wo: Vec3<R>) -> [R; N] {
        let (m, wi, wo) = safe_dirs(wi, wo);
        let (h, cos_d) = half_and_cos_d::<crate::fast::ExactSqrt, R>(wi, wo);
        let cos_d = cos_d.min(R::one());
        let e = crate::ndf::ashikhmin_shirley_exponent(self.nu, self.nv, h);
        let den = (cos_d * wi.z.max(wo.z)).max(R::from_f64(DENOM_FLOOR));
        let lobe = self.spec_k * h.z.saturate().pow(e) / den;
        let half = R::from_f64(0.5);
        let di = schlick_complement(wi.z * half);
        let dd = di * schlick_complement(wo.z * half);
        let r: [R; N] = crate::real::channels(
            #[inline(always)]
            |c| {
                let f = crate::fresnel::schlick(self.rs[c], cos_d);
                lobe.mul_add(f, self.diffuse_k[c] * dd)
            },
        );
        masked(m, r)
    }

    #[inline]
    fn properties(&self) -> Properties {
        Properties {
            reciprocity: Reciprocity::Reciprocal,
            energy: Energy::ConservingWhen {
                condition: "Rd, Rs ∈ [0, 1] (the constructor's domain); albedo ≤ 1 checked \
                            numerically for nu, nv ≤ 1e4 only, not over (1e4, 1e6]",
            },
        }
    }
}

impl<R: Real, const N: usize> AshikhminShirley<R, N> {
    /// `(ρ̂_d, ρ̂_s)`: `mean(Rd (1 − Rs))` and `mean(F(cos θo))`.
    #[inline(always)]
    fn estimates(&self, wo: Vec3<R>) -> (R, R) {
        let c = wo.z.saturate();
        (
            R::from_f64(23.0 * core::f64::consts::PI / 28.0) * mean(self.diffuse_k),
            mean(crate::real::channels::<R, N>(|i| {
                crate::fresnel::schlick(self.rs[i], c)
            })),
        )
    }

    #[inline(always)]
    fn half_lobe(&self) -> PhongHalf<R> {
        PhongHalf {
            nu: self.nu,
            nv: self.nv,
        }
    }
}

/// Importance sampling as the paper does it (Ashikhmin & Shirley 2000, §5): the specular
/// lobe by its half-vector density, the diffuse term by the cosine, in a one-sample mixture
/// (Veach 1997, §9.2.4):
///
/// ```text
/// φm: tan φm = √((nu + 1)/(nv + 1)) tan(2π u1)   (same quadrant; the direction of
///     (√(nv + 1) cos 2πu1, √(nu + 1) sin 2πu1): no atan, no quadrant cases)
/// cos θm = (1 − u0)^(1/(nu cos²φm + nv sin²φm + 1))
/// p_h(wm) = √((nu + 1)(nv + 1))/(2π) · cos^(nu cos²φm + nv sin²φm) θm,   p(wi) = p_h/(4 wo·wm)
/// pdf(wi) = P_d cos θi/π + (1 − P_d) p(wi),   P_d = ρ̂_d/(ρ̂_d + ρ̂_s)
/// ρ̂_d = mean(Rd (1 − Rs)),   ρ̂_s = mean(F(cos θo))
/// ```
///
/// The paper samples the diffuse term by the cosine as well (its `f_d` is nearly
/// Lambertian). `u[2] < P_d` chooses it; `weight = f cos θi / pdf` with the whole `f`.
/// [`SampleBrdf::albedo_estimate`] is `ρ̂_d + ρ̂_s`.
impl<R: Real, const N: usize> SampleBrdf<R, N> for AshikhminShirley<R, N> {
    #[inline(always)]
    fn sample(&self, wo: Vec3<R>, u: [R; 3]) -> Sample<R, N> {
        let (d, s) = self.estimates(wo);
        sample_diffuse_and_half(&self.half_lobe(), first_probability(d, s), wo, u, |wi| {
            self.eval(wi, wo)
        })
    }

    #[inline(always)]
    fn pdf(&self, wo: Vec3<R>, wi: Vec3<R>) -> R {
        let (d, s) = self.estimates(wo);
        pdf_diffuse_and_half(&self.half_lobe(), first_probability(d, s), wo, wi)
    }

    #[inline(always)]
    fn albedo_estimate(&self, wo: Vec3<R>) -> R {
        let (d, s) = self.estimates(wo);
        d + s
    }
}

// ---------------------------------------------------------------------------------------------
// File description (feature `serde`)
// ---------------------------------------------------------------------------------------------

/// The file description of [`AshikhminShirley`]: `model = "ashikhmin_shirley"`,
/// re-exported from [`crate::material`].
#[cfg(feature = "serde")]
pub(crate) mod desc {
    use serde::{Deserialize, Serialize};

    use super::AshikhminShirley;
    use crate::Scalar;
    use crate::material::{Material, MaterialError, ModelDesc, Reflectance, Rgb, invalid};

    crate::material::field_fns!(rd, rs, nu, nv);

    /// [`AshikhminShirley`] (Ashikhmin and Shirley 2000): diffuse `rd`, specular
    /// normal-incidence reflectance `rs` (a colour, a preset or a complex IOR), exponents
    /// `nu`, `nv ∈ [0, 1e6]` along the tangent and the bitangent (anisotropic when they
    /// differ).
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[serde(expecting = "the parameters of `ashikhmin_shirley`")]
    pub struct AshikhminShirleyDesc {
        /// Diffuse reflectance.
        #[serde(deserialize_with = "field::rd")]
        pub rd: Rgb,
        /// Specular normal-incidence reflectance.
        #[serde(deserialize_with = "field::rs")]
        pub rs: Reflectance,
        /// Exponent along the tangent, `[0, 1e6]`.
        #[serde(deserialize_with = "field::nu")]
        pub nu: f64,
        /// Exponent along the bitangent, `[0, 1e6]`.
        #[serde(deserialize_with = "field::nv")]
        pub nv: f64,
    }

    impl ModelDesc for AshikhminShirleyDesc {
        const NAME: &'static str = "ashikhmin_shirley";

        fn is_anisotropic(&self) -> bool {
            self.nu != self.nv
        }

        fn build<S: Scalar>(&self) -> Result<Material<S>, MaterialError> {
            let inv = invalid(Self::NAME);
            let rs = Rgb(self.rs.value().map_err(&inv)?).scalars();
            let (nu, nv) = (S::of(self.nu), S::of(self.nv));
            Ok(AshikhminShirley::new(self.rd.scalars(), rs, nu, nv)
                .map_err(inv)?
                .into())
        }
    }
}
