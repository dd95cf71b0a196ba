//! World space ↔ the local shading frame: [`Frame`], an orthonormal, right-handed basis
//! `(t, b, n)` built from a shading normal (and optionally a tangent), on any [`Real`].
//!
//! Every model of this crate works in the local frame, where the normal is +z (see the
//! [crate conventions](crate#conventions)). A renderer has world-space vectors; a frame
//! converts them:
//!
//! ```
//! use brdf::frame::Frame;
//! use brdf::{Brdf, Vec3};
//! use brdf::models::Lambert;
//!
//! let white = Lambert::<f32, 1>::new([1.0])?;
//! // A y-up world: the surface faces +y; light from above and a bit to the side.
//! let frame = Frame::from_normal(Vec3::new(0.0_f32, 1.0, 0.0));
//! let (wi, wo) = (Vec3::new(0.6, 0.8, 0.0), Vec3::new(0.0, 1.0, 0.0));
//! let f = frame.eval(&white, wi, wo);        // = white.eval(frame.to_local(wi), frame.to_local(wo))
//! assert!((f[0] - core::f32::consts::FRAC_1_PI).abs() < 1e-7);
//! assert!((frame.to_local(wi).z - 0.8).abs() < 1e-7); // cos θi = wi·n
//! # Ok::<(), brdf::Error>(())
//! ```
//!
//! # The y-up trap
//!
//! `Vec3<f32>: From<glam::Vec3>` copies components; it does not change frames. Passing
//! world vectors of a y-up engine straight through `.into()` compiles and evaluates the
//! model with the wrong axis as the normal: the model then reads `cos θ` from the world `z`
//! component, so the result is silently wrong — for the gold GGX material of the crate's
//! front-page example 0.055 instead of 0.163 sr⁻¹ (issue 12 met 0.044 instead of 0.177) —
//! or zero when a world `z` happens to be negative. Convert with a frame: `frame.to_local(w)` or
//! `frame.eval(&model, wi, wo)`.
//!
//! # From a normal alone: the branchless basis of Duff et al.
//!
//! [`Frame::from_normal`] builds the tangents from the unit normal `n = (nx, ny, nz)` alone.
//! For `nz > −1`, the rotation that takes `e_z` to `n` about the axis `e_z × n` (Rodrigues'
//! formula with `cos θ = nz`, `sin² θ = nx² + ny² = (1 − nz)(1 + nz)`) takes `e_x` and `e_y` to
//!
//! ```text
//! t = (1 − nx²/(1 + nz), −nx·ny/(1 + nz), −nx)
//! b = (−nx·ny/(1 + nz), 1 − ny²/(1 + nz), −ny)
//! ```
//!
//! which, being the images of an orthonormal right-handed pair under a rotation, are
//! orthonormal and satisfy `t × b = n` (Frisvad 2012). The division by `1 + nz` is
//! singular at `n = −e_z` and cancels near it. For `nz < 0` apply the same formula to
//! `m = (nx, −ny, −nz)`, the image of `n` under the half turn `P = diag(1, −1, −1)` about x,
//! whose `mz = −nz > 0`, and map the result back with `P` (a rotation, so it keeps the basis
//! right-handed). With `s = sign(nz) ∈ {+1, −1}`, `a = −1/(s + nz)` and `c = nx·ny·a`, both
//! cases are one branch-free formula:
//!
//! ```text
//! t = (1 + s·nx²·a,  s·c,  −s·nx)
//! b = (c,  s + ny²·a,  −ny)
//! ```
//!
//! Now `|s + nz| = 1 + |nz| ≥ 1`: no cancellation and no small divisor anywhere on the
//! sphere (Duff et al. 2017, who also measure its error). `s` is chosen with
//! [`Real::select`] (`+1` where `nz ≥ 0`, including `−0`), so the same body runs on SIMD
//! lanes; at `nz = ±0` either sign gives `|s + nz| = 1`. The basis jumps when `nz` changes
//! sign — unavoidable for any continuous choice of tangent (the hairy ball theorem) and
//! irrelevant for isotropic models. For anisotropic models give the tangent:
//!
//! # From a normal and a tangent: Gram-Schmidt
//!
//! [`Frame::from_normal_tangent`] keeps the tangent's direction in the tangent plane (the
//! `x` axis of the local frame, along which `alpha_x`, Ward's `alpha_x`, Ashikhmin-Shirley's
//! `nu` and Kajiya-Kay's fibre lie): `r = t − (t·n) n`, projected once more
//! (`r ← r − (r·n) n`: one classical Gram-Schmidt pass leaves a residual `r·n` of about
//! `ε/sin θ(n, t)`; a second pass brings it to rounding — "twice is enough", Giraud, Langou
//! & Rozložník 2005), then `t̂ = r/|r|` and `b = n × t̂`. The tangent need not be unit nor
//! orthogonal to `n`.
//!
//! A tangent **parallel to the normal** has no projection. Where `|r|² ≤ 10⁻⁶ |t|²`
//! (`sin θ(n, t) ≤ 10⁻³`, including a zero or non-finite tangent) the frame falls back to
//! [`Frame::from_normal`]'s basis, lane by lane, so evaluation stays finite; on scalars,
//! [`Frame::try_from_normal_tangent`] reports it as an [`Error`] instead.
//!
//! # Precision
//!
//! Both constructors use `+ − × ÷ √` and `select` only, so lanes equal the scalar result bit
//! for bit. For a unit normal the basis is orthonormal and right-handed to a few ULP
//! (`tests/frame.rs` checks `|t·b|`, `|t·n|`, `|b·n|`, `||t|² − 1|`, `|t × b − n|` against
//! `4 ε` at `n = ±e_x, ±e_y, ±e_z`, `nz = ±0`, components down to `10⁻³⁰` and over the
//! whole sphere). [`Frame::to_local`] and [`Frame::to_world`] are three dot products each.
//!
//! # References
//!
//! * T. Duff, J. Burgess, P. Christensen, C. Hery, A. Kensler, M. Liani, R. Villemin,
//!   "Building an Orthonormal Basis, Revisited", JCGT 6(1), 1–8, 2017.
//! * J. R. Frisvad, "Building an Orthonormal Basis from a 3D Unit Vector Without
//!   Normalization", Journal of Graphics Tools 16(3), 151–159, 2012.
//! * L. Giraud, J. Langou, M. Rozložník, "The loss of orthogonality in the Gram-Schmidt
//!   orthogonalization process", Computers & Mathematics with Applications 50, 2005.

use crate::error::Error;
use crate::models::Brdf;
use crate::real::{Splat, splat_scalar};
use crate::{Real, Scalar, Vec3};

/// An orthonormal, right-handed shading frame: tangent `t`, bitangent `b = n × t` and
/// normal `n`, in world space. The local frame's x, y, z axes are `t`, `b`, `n`.
///
/// See the [module docs](self) for the constructions and their precision.
///
/// # Examples
///
/// ```
/// use brdf::frame::Frame;
/// use brdf::Vec3;
/// let n = glam::Vec3::new(0.0, 0.6, 0.8);
/// let frame = Frame::from_normal(n);                      // from glam (or brdf::Vec3)
/// let w = glam::Vec3::new(0.36, 0.48, 0.8);
/// let local = frame.to_local(w);
/// assert!((local.z - w.dot(n)).abs() < 1e-7);             // cos θ = w·n
/// let back: glam::Vec3 = frame.to_world(local).into();
/// assert!((back - w).length() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame<R> {
    t: Vec3<R>,
    b: Vec3<R>,
    n: Vec3<R>,
}

/// `|r|² ≤ PARALLEL · |t|²` marks a tangent parallel to the normal (`sin θ ≤ 10⁻³`).
const PARALLEL: f64 = 1e-6;

impl<R: Real> Frame<R> {
    /// The frame of the **unit** normal `n`, with the tangents of Duff et al. 2017 (see the
    /// [module docs](self)): branch-free, finite everywhere on the unit sphere, orthonormal
    /// to a few ULP. `n` is not normalized; for a normal of any length use
    /// [`Frame::try_from_normal`] (scalars) or normalize it first.
    ///
    /// ```
    /// use brdf::{frame::Frame, Vec3};
    /// let f = Frame::from_normal(Vec3::new(0.0_f64, 0.0, -1.0)); // the singular case of Frisvad 2012
    /// assert_eq!(f.tangent().cross(f.bitangent()), f.normal());
    /// ```
    #[inline(always)]
    #[must_use]
    pub fn from_normal(n: impl Into<Vec3<R>>) -> Self {
        let n = n.into();
        let s = R::select(n.z.ge(R::zero()), R::one(), -R::one());
        let a = -(s + n.z).recip();
        let c = n.x * n.y * a;
        Self {
            t: Vec3::new(R::one() + s * n.x * n.x * a, s * c, -s * n.x),
            b: Vec3::new(c, s + n.y * n.y * a, -n.y),
            n,
        }
    }

    /// The frame of the **unit** normal `n` whose tangent (local x axis) is the direction of
    /// `t` projected onto the tangent plane (two Gram-Schmidt passes, see the
    /// [module docs](self)); `t` need be neither unit nor orthogonal to `n`.
    ///
    /// Lanes where `t` is parallel to `n` (`sin θ(n, t) ≤ 10⁻³`), zero or not finite get the
    /// frame of [`Frame::from_normal`] instead (bit for bit), so the result is always
    /// finite for a finite unit `n`. On scalars, [`Frame::try_from_normal_tangent`] reports
    /// that case as an error.
    ///
    /// ```
    /// use brdf::{frame::Frame, Vec3};
    /// let n = Vec3::new(0.0_f32, 1.0, 0.0);
    /// let f = Frame::from_normal_tangent(n, Vec3::new(2.0, 0.5, 0.0)); // tilted, not unit
    /// assert_eq!(f.tangent(), Vec3::new(1.0, 0.0, 0.0));
    /// assert_eq!(f.bitangent(), Vec3::new(0.0, 0.0, -1.0));            // n × t
    /// ```
    #[inline(always)]
    #[must_use]
    pub fn from_normal_tangent(n: impl Into<Vec3<R>>, t: impl Into<Vec3<R>>) -> Self {
        let fallback = Self::from_normal(n);
        let (n, t) = (fallback.n, t.into());
        let r = t - n.scale(t.dot(n));
        let r = r - n.scale(r.dot(n));
        let r2 = r.length_squared();
        let ok = r2.gt(R::from_f64(PARALLEL) * t.length_squared());
        let t_hat = r.scale(r2.sqrt().recip());
        let b = n.cross(t_hat);
        let pick = |a: Vec3<R>, f: Vec3<R>| {
            Vec3::new(
                R::select(ok, a.x, f.x),
                R::select(ok, a.y, f.y),
                R::select(ok, a.z, f.z),
            )
        };
        Self {
            t: pick(t_hat, fallback.t),
            b: pick(b, fallback.b),
            n,
        }
    }

    /// The tangent `t` (local x axis), in world space.
    #[inline(always)]
    #[must_use]
    pub fn tangent(&self) -> Vec3<R> {
        self.t
    }

    /// The bitangent `b = n × t` (local y axis), in world space.
    #[inline(always)]
    #[must_use]
    pub fn bitangent(&self) -> Vec3<R> {
        self.b
    }

    /// The normal `n` (local z axis), in world space.
    #[inline(always)]
    #[must_use]
    pub fn normal(&self) -> Vec3<R> {
        self.n
    }

    /// `[t, b, n]`.
    #[inline(always)]
    pub(crate) fn axes(&self) -> [Vec3<R>; 3] {
        [self.t, self.b, self.n]
    }

    /// The world-space vector `w` in the local frame: `(w·t, w·b, w·n)`. Lengths are kept
    /// (to rounding), so a unit world direction gives a unit local one with `cos θ = w·n`.
    #[inline(always)]
    #[must_use]
    pub fn to_local(&self, w: impl Into<Vec3<R>>) -> Vec3<R> {
        let w = w.into();
        Vec3::new(w.dot(self.t), w.dot(self.b), w.dot(self.n))
    }

    /// The local vector `l` in world space: `l.x·t + l.y·b + l.z·n` (the inverse of
    /// [`Frame::to_local`]: the basis is orthonormal, so its inverse is its transpose).
    #[inline(always)]
    #[must_use]
    pub fn to_world(&self, l: Vec3<R>) -> Vec3<R> {
        Vec3::new(
            l.x * self.t.x + l.y * self.b.x + l.z * self.n.x,
            l.x * self.t.y + l.y * self.b.y + l.z * self.n.y,
            l.x * self.t.z + l.y * self.b.z + l.z * self.n.z,
        )
    }

    /// `brdf` at the world-space unit directions `wi` (towards the light) and `wo`
    /// (towards the viewer): `brdf.eval(self.to_local(wi), self.to_local(wo))`, in sr⁻¹
    /// per channel, without the cosine (`cos θi = wi·n`). Zero where either direction is
    /// below the surface (`w·n ≤ 0`).
    #[inline(always)]
    #[must_use]
    pub fn eval<B: Brdf<R, N> + ?Sized, const N: usize>(
        &self,
        brdf: &B,
        wi: impl Into<Vec3<R>>,
        wo: impl Into<Vec3<R>>,
    ) -> [R; N] {
        brdf.eval(self.to_local(wi), self.to_local(wo))
    }
}

/// `v / |v|` for a finite nonzero scalar vector, scaled first by its largest component so
/// that neither tiny nor huge components underflow or overflow; `param` names it in errors.
fn unit_or_error<S: Scalar>(param: &'static str, v: Vec3<S>) -> Result<Vec3<S>, Error> {
    let finite = |x: S| -> bool { Into::<f64>::into(x).is_finite() };
    if !(finite(v.x) && finite(v.y) && finite(v.z)) {
        return Err(Error::NotFinite { param });
    }
    let m = v.x.abs().max(v.y.abs()).max(v.z.abs());
    if m == S::zero() {
        return Err(Error::OutOfDomain {
            param,
            value: 0.0,
            domain: "length > 0",
        });
    }
    // Division, not a multiplication by 1/m: 1/m overflows for subnormal m.
    let v = Vec3::new(v.x / m, v.y / m, v.z / m);
    let len = v.length();
    Ok(Vec3::new(v.x / len, v.y / len, v.z / len))
}

impl<S: Scalar> Frame<S> {
    /// [`Frame::from_normal`] of `n / |n|`, for a normal of any finite nonzero length, else
    /// [`Error`] (`param` `"normal"`).
    ///
    /// ```
    /// use brdf::{frame::Frame, Vec3};
    /// let f = Frame::try_from_normal(Vec3::new(0.0_f32, 3.0, 4.0))?;
    /// assert_eq!(f.normal(), Vec3::new(0.0, 0.6, 0.8));
    /// assert!(Frame::try_from_normal(Vec3::new(0.0_f32, 0.0, 0.0)).is_err());
    /// # Ok::<(), brdf::Error>(())
    /// ```
    pub fn try_from_normal(n: impl Into<Vec3<S>>) -> Result<Self, Error> {
        Ok(Self::from_normal(unit_or_error("normal", n.into())?))
    }

    /// [`Frame::from_normal_tangent`] of `n / |n|` and `t`, else [`Error`]: `param`
    /// `"normal"` for a zero or non-finite normal, `"tangent"` for a zero or non-finite
    /// tangent or one parallel to the normal (`sin θ(n, t) ≤ 10⁻³`; the error's `value` is
    /// that sine).
    ///
    /// ```
    /// use brdf::{frame::Frame, Vec3};
    /// let n = Vec3::new(0.0_f64, 0.0, 2.0);
    /// assert!(Frame::try_from_normal_tangent(n, Vec3::new(1.0, 0.0, 5.0)).is_ok());
    /// assert!(Frame::try_from_normal_tangent(n, Vec3::new(0.0, 0.0, -1.0)).is_err());
    /// ```
    pub fn try_from_normal_tangent(
        n: impl Into<Vec3<S>>,
        t: impl Into<Vec3<S>>,
    ) -> Result<Self, Error> {
        let n = unit_or_error("normal", n.into())?;
        let t = unit_or_error("tangent", t.into())?;
        let sin2 = n.cross(t).length_squared();
        if sin2 <= S::of(PARALLEL) {
            return Err(Error::OutOfDomain {
                param: "tangent",
                value: Into::<f64>::into(sin2).sqrt(),
                domain: "sin θ(normal, tangent) > 1e-3 (not parallel to the normal)",
            });
        }
        Ok(Self::from_normal_tangent(n, t))
    }

    /// Converts world-space directions to the local frame as structure of arrays, ready
    /// for [`crate::batch::Directions::new`]: `out[0][i], out[1][i], out[2][i]` are the local
    /// `x, y, z` of `world[i]`. `world` holds anything that converts into a [`Vec3`]
    /// (`glam::Vec3`, `[f32; 3]`, `Vec3<f32>`).
    ///
    /// # Panics
    ///
    /// If `world` and the output slices differ in length.
    pub fn to_local_soa<W: Copy + Into<Vec3<S>>>(&self, world: &[W], out: [&mut [S]; 3]) {
        let [x, y, z] = out;
        assert!(
            world.len() == x.len() && x.len() == y.len() && y.len() == z.len(),
            "Frame::to_local_soa: lengths differ"
        );
        for (i, &w) in world.iter().enumerate() {
            let l = self.to_local(w);
            (x[i], y[i], z[i]) = (l.x, l.y, l.z);
        }
    }
}

/// Converts `world[i]` to the local frame of `frames[i]`, as structure of arrays ready for
/// [`crate::batch::Directions::new`] (one frame per direction, e.g. a G-buffer's normals);
/// see [`Frame::to_local_soa`] for one frame shared by every direction.
///
/// ```
/// use brdf::batch::{self, Directions};
/// use brdf::frame::{self, Frame};
/// use brdf::models::Lambert;
///
/// let normals = [glam::Vec3::Y, glam::Vec3::X, glam::Vec3::new(0.0, 0.6, 0.8)];
/// let frames = normals.map(Frame::from_normal);
/// let (wi, wo) = (normals, normals.map(|n| (n + glam::Vec3::Z).normalize()));
/// let (mut i, mut o) = ([[0.0f32; 3]; 3], [[0.0f32; 3]; 3]);
/// frame::to_local_soa(&frames, &wi, i.each_mut().map(|c| &mut c[..]));
/// frame::to_local_soa(&frames, &wo, o.each_mut().map(|c| &mut c[..]));
/// let mut f = [0.0f32; 3];
/// let white = Lambert::<f32, 1>::new([1.0])?;
/// batch::eval(&white, Directions::new(&i[0], &i[1], &i[2]), Directions::new(&o[0], &o[1], &o[2]), [&mut f]);
/// assert!(f.iter().all(|&v| v == core::f32::consts::FRAC_1_PI));
/// # Ok::<(), brdf::Error>(())
/// ```
///
/// # Panics
///
/// If `frames`, `world` and the output slices differ in length.
pub fn to_local_soa<S: Scalar, W: Copy + Into<Vec3<S>>>(
    frames: &[Frame<S>],
    world: &[W],
    out: [&mut [S]; 3],
) {
    let [x, y, z] = out;
    assert!(
        frames.len() == world.len()
            && world.len() == x.len()
            && x.len() == y.len()
            && y.len() == z.len(),
        "frame::to_local_soa: lengths differ"
    );
    for (i, (f, &w)) in frames.iter().zip(world).enumerate() {
        let l = f.to_local(w);
        (x[i], y[i], z[i]) = (l.x, l.y, l.z);
    }
}

/// The same frame on another number type (every lane the same frame on lanes).
impl<S: Scalar> Splat for Frame<S> {
    type On<L: Real> = Frame<L>;
    #[inline]
    fn splat<L: Real>(&self) -> Frame<L> {
        let v = |w: Vec3<S>| Vec3::new(splat_scalar(w.x), splat_scalar(w.y), splat_scalar(w.z));
        Frame {
            t: v(self.t),
            b: v(self.b),
            n: v(self.n),
        }
    }
}
