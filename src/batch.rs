//! Batch evaluation over many direction pairs, dispatched at run time to the widest SIMD
//! instruction set the CPU has.
//!
//! The formulas of this crate are branch-free generic bodies (see [`crate::real`]). Inside a
//! function compiled for AVX2+FMA or AVX-512, LLVM vectorizes the `f32` instantiation of such a
//! body across loop iterations: 8 or 16 direction pairs per instruction, with a scalar tail
//! for the remainder. This module compiles the batch loop three times — portable (the build's
//! baseline, SSE2 on the default x86-64 target), AVX2+FMA and AVX-512 — and picks one at run
//! time with `is_x86_feature_detected!`, so a crate built for the default target still uses
//! the hardware it runs on.
//!
//! Bodies that call a library transcendental (`powf`, `exp` from `std`/`libm`) do not
//! vectorize this way; the models offer polynomial alternatives (see [`crate::fast`]) for
//! their batch use.
//!
//! Inputs are structure-of-arrays slices ([`Directions`]) in the local shading frame; outputs
//! are one slice per colour channel. [`eval_glam`] converts from arrays of glam vectors.
//!
//! Without the `std` feature (or off x86-64) only [`Isa::Portable`] exists.

use crate::{Vec3, models::Brdf};

/// Unit directions in the local frame as structure of arrays: `(x[i], y[i], z[i])` is one
/// direction.
#[derive(Clone, Copy, Debug)]
pub struct Directions<'a> {
    /// Tangent components.
    pub x: &'a [f32],
    /// Bitangent components.
    pub y: &'a [f32],
    /// Normal components (`cos θ`).
    pub z: &'a [f32],
}

impl<'a> Directions<'a> {
    /// Groups three component slices.
    ///
    /// # Panics
    ///
    /// If the slices differ in length.
    #[inline]
    #[must_use]
    pub fn new(x: &'a [f32], y: &'a [f32], z: &'a [f32]) -> Self {
        assert!(
            x.len() == y.len() && y.len() == z.len(),
            "Directions: component slices differ in length"
        );
        Self { x, y, z }
    }

    /// Number of directions.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Whether there are no directions.
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
}

/// An instruction-set variant of the batch loop.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Isa {
    /// The build's baseline target features (SSE2 on default x86-64; any target).
    Portable,
    /// x86-64 with AVX2 and FMA (8 `f32` lanes).
    Avx2Fma,
    /// x86-64 with AVX-512 F/VL plus AVX2 and FMA (16 `f32` lanes).
    Avx512,
}

impl Isa {
    /// Every variant, narrowest first.
    pub const ALL: [Isa; 3] = [Isa::Portable, Isa::Avx2Fma, Isa::Avx512];

    /// Whether this CPU can run the variant (always `true` for [`Isa::Portable`]).
    #[inline]
    #[must_use]
    pub fn is_available(self) -> bool {
        match self {
            Isa::Portable => true,
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            Isa::Avx2Fma => {
                std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
            }
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            Isa::Avx512 => {
                Isa::Avx2Fma.is_available()
                    && std::is_x86_feature_detected!("avx512f")
                    && std::is_x86_feature_detected!("avx512vl")
            }
            #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
            _ => false,
        }
    }

    /// The widest available variant on this CPU.
    #[inline]
    #[must_use]
    pub fn detect() -> Isa {
        if Isa::Avx512.is_available() {
            Isa::Avx512
        } else if Isa::Avx2Fma.is_available() {
            Isa::Avx2Fma
        } else {
            Isa::Portable
        }
    }
}

/// The requested [`Isa`] is not available on this CPU or build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unavailable(pub Isa);

impl core::fmt::Display for Unavailable {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "instruction set {:?} is not available on this CPU",
            self.0
        )
    }
}

impl core::error::Error for Unavailable {}

/// The loop every variant compiles: one `f32` evaluation per iteration, vectorized by LLVM
/// across iterations when the enclosing function enables wider instruction sets.
#[inline(always)]
fn kernel<B: Brdf<f32, N>, const N: usize>(
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    let n = wi.len();
    assert!(wo.len() == n, "batch: wi and wo differ in length");
    assert!(
        out.iter().all(|c| c.len() == n),
        "batch: output and input differ in length"
    );
    // Re-slice to `n` so the optimizer drops the per-element bounds checks.
    let (ix, iy, iz) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
    let (ox, oy, oz) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
    let out = out.map(|c| &mut c[..n]);
    for i in 0..n {
        let f = brdf.eval(
            Vec3::new(ix[i], iy[i], iz[i]),
            Vec3::new(ox[i], oy[i], oz[i]),
        );
        for c in 0..N {
            out[c][i] = f[c];
        }
    }
}

#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2,fma")]
fn kernel_avx2<B: Brdf<f32, N>, const N: usize>(
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    kernel(brdf, wi, wo, out)
}

#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
fn kernel_avx512<B: Brdf<f32, N>, const N: usize>(
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    kernel(brdf, wi, wo, out)
}

/// Evaluates `brdf` for every pair `(wi[i], wo[i])` with a chosen instruction set, writing
/// channel `c` of `f(wi[i], wo[i])` (sr⁻¹, without `cos θi`) to `out[c][i]`.
///
/// Returns [`Unavailable`] if the CPU lacks `isa`. The results equal those of
/// [`Brdf::eval`] on `f32` up to FMA contraction (the wide variants fuse `mul_add`).
///
/// # Panics
///
/// If `wi`, `wo` and the output slices differ in length.
#[inline]
pub fn eval_with<B: Brdf<f32, N>, const N: usize>(
    isa: Isa,
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) -> Result<(), Unavailable> {
    if !isa.is_available() {
        return Err(Unavailable(isa));
    }
    match isa {
        Isa::Portable => kernel(brdf, wi, wo, out),
        // SAFETY: `is_available` checked at run time that the CPU has these features.
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        Isa::Avx2Fma => unsafe { kernel_avx2(brdf, wi, wo, out) },
        // SAFETY: as above.
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        Isa::Avx512 => unsafe { kernel_avx512(brdf, wi, wo, out) },
        #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
        _ => unreachable!("only Portable is available here"),
    }
    Ok(())
}

/// Evaluates `brdf` for every pair `(wi[i], wo[i])` on the widest instruction set this CPU
/// has ([`Isa::detect`]); see [`eval_with`].
///
/// # Examples
///
/// ```
/// use brdf::batch::{Directions, eval};
/// use brdf::{Brdf, Vec3, models::{Properties, Reciprocity, Energy}};
///
/// struct White;
/// impl Brdf<f32, 1> for White {
///     fn eval(&self, wi: Vec3<f32>, wo: Vec3<f32>) -> [f32; 1] {
///         [if wi.z > 0.0 && wo.z > 0.0 { core::f32::consts::FRAC_1_PI } else { 0.0 }]
///     }
///     fn properties(&self) -> Properties {
///         Properties { reciprocity: Reciprocity::Reciprocal, energy: Energy::Conserving }
///     }
/// }
///
/// let z = [1.0f32; 100];
/// let zero = [0.0f32; 100];
/// let mut f = [0.0f32; 100];
/// eval(&White, Directions::new(&zero, &zero, &z), Directions::new(&zero, &zero, &z), [&mut f]);
/// assert!(f.iter().all(|&v| v == core::f32::consts::FRAC_1_PI));
/// ```
///
/// # Panics
///
/// If `wi`, `wo` and the output slices differ in length.
#[inline]
pub fn eval<B: Brdf<f32, N>, const N: usize>(
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    // The detected variant is available by construction.
    let _ = eval_with(Isa::detect(), brdf, wi, wo, out);
}

/// Convenience over glam: evaluates `brdf` for `(wi[i], wo[i])` given as arrays of
/// `glam::Vec3` (array of structures), writing `out[i]` per channel. Transposes in chunks on
/// the stack, then runs [`eval`].
///
/// # Panics
///
/// If `wi`, `wo` and `out` differ in length.
pub fn eval_glam<B: Brdf<f32, N>, const N: usize>(
    brdf: &B,
    wi: &[glam::Vec3],
    wo: &[glam::Vec3],
    out: &mut [[f32; N]],
) {
    const CHUNK: usize = 256;
    assert!(
        wi.len() == wo.len() && wo.len() == out.len(),
        "eval_glam: lengths differ"
    );
    let isa = Isa::detect();
    let mut soa = [[0.0f32; CHUNK]; 6];
    let mut res = [[0.0f32; CHUNK]; N];
    for ((wi, wo), out) in wi
        .chunks(CHUNK)
        .zip(wo.chunks(CHUNK))
        .zip(out.chunks_mut(CHUNK))
    {
        let n = wi.len();
        for (i, (a, b)) in wi.iter().zip(wo).enumerate() {
            soa[0][i] = a.x;
            soa[1][i] = a.y;
            soa[2][i] = a.z;
            soa[3][i] = b.x;
            soa[4][i] = b.y;
            soa[5][i] = b.z;
        }
        let [ix, iy, iz, ox, oy, oz] = &soa;
        let dirs_i = Directions::new(&ix[..n], &iy[..n], &iz[..n]);
        let dirs_o = Directions::new(&ox[..n], &oy[..n], &oz[..n]);
        let slices = res.each_mut().map(|c| &mut c[..n]);
        let _ = eval_with(isa, brdf, dirs_i, dirs_o, slices);
        for (i, o) in out.iter_mut().enumerate() {
            *o = core::array::from_fn(|c| res[c][i]);
        }
    }
}
