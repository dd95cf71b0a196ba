//! Batch evaluation over many direction pairs, dispatched at run time to the widest SIMD
//! instruction set the CPU has.
//!
//! The formulas of this crate are branch-free generic bodies (see [`crate::real`]). Inside a
//! function compiled for AVX2+FMA or AVX-512, LLVM vectorizes a one-lane instantiation of such
//! a body across loop iterations: 8 or 16 direction pairs per instruction, with a scalar tail
//! for the remainder. This module compiles the batch loop three times — portable (the build's
//! baseline, SSE2 on the default x86-64 target), AVX2+FMA and AVX-512 — and picks one at run
//! time with `is_x86_feature_detected!`, so a crate built for the default target still uses
//! the hardware it runs on.
//!
//! The portable loop evaluates the model as it was built, on `f32`. The two FMA loops evaluate
//! it on [`F32Fma`] ([`BatchBrdf::fused`], through [`Splat`]), whose `mul_add` is one fused
//! instruction there: on a default-target build `f32`'s `mul_add` cannot fuse (its choice is
//! fixed when the crate is compiled), and fusing merges most multiplies into adds and
//! shortens the dependency chains of a BRDF body (measured on AVX-512: 1.4–2.3× faster, see
//! the README). So:
//!
//! * [`Isa::Portable`] results equal [`Brdf::eval`] on the `f32` model bit for bit;
//! * [`Isa::Avx2Fma`] and [`Isa::Avx512`] results equal `eval` on the [`F32Fma`] model
//!   (`brdf.splat::<F32Fma>()`) bit for bit — on Intel CPUs on the [`F32FmaSharedDiv`] model
//!   instead, which differs only where a material opted into shared divisions (see
//!   [`shares_divisions`]) — and differ from the `f32` model by the rounding of
//!   the products that `f32` leaves unfused: at most 8 ULP for every model in
//!   `tests/models.rs` but Kajiya-Kay (64: its `pow` with exponents up to 2·10⁴ amplifies
//!   them), and 4·10⁻⁷ relative on the batch tests' workloads.
//!
//! **Explicit lanes.** Two kinds of model run differently on the FMA instruction sets in
//! [`eval_with`], [`eval`], [`eval_glam`], [`sample_with`], [`sample`], [`pdf_with`] and
//! [`pdf`]
//! ([`Splat::EXPLICIT_LANES`]): on explicit
//! registers of lanes (16 on [`Isa::Avx512`], 8 on [`Isa::Avx2Fma`]), a register of pairs per
//! iteration and the remainder under a lane mask, every operation the one of [`F32Fma`], or
//! of [`F32FmaSharedDiv`] where [`shares_divisions`] (so `eval` on the form the one-lane
//! kernels would run still gives the bits), except that
//!
//! * a model that takes a square root or division through [`crate::fast::HardwareEstimate`]
//!   gets `vrsqrt14ps` / `vrcp14ps` with one refinement step on [`Isa::Avx512`] (each within
//!   1 ULP; LLVM does not vectorize the scalar estimate instructions): results within a few
//!   ULP of the exact policy (`tests/batch.rs`: 1e-6 relative, for samples too), not
//!   bit-identical to any `eval`. On the other instruction sets (and in the pipelined
//!   loops) the policy is the exact one, bit for bit;
//!
//! A wrapper model of your own forwards the flag in its `Splat` impl
//! (`const EXPLICIT_LANES: bool = B::EXPLICIT_LANES;`), or it runs on the one-lane loop.
//!
//! **Materials chosen at run time.** A model may evaluate a batch itself
//! ([`Brdf::eval_batch`], tried first). A [`crate::material::Material`] does: it matches on
//! its variant once per call and runs the concrete model through [`eval_with`], so it gets
//! that model's loop and bits on every instruction set (a `match` per pair would keep LLVM
//! from vectorizing). A `Sum` or `Layered` material runs its parts the same way over blocks
//! of [`BLOCK`] pairs and combines them in a vectorized pass, with the additions and the
//! fused multiply-add of its `eval` (so the bits of its static counterpart). A static
//! composition holding a `Material` (`Sum<Material<f32>, _>`) does not get this, and if
//! another part asks for explicit lanes the `Material` runs out of line there (the same
//! bits, slowly): compose run-time materials with `Material::Sum` and `Material::Layered`.
//! Sampling and densities have the same hooks ([`SampleBrdf::sample_batch`],
//! [`SampleBrdf::pdf_batch`]): a material of one model samples
//! a batch as that model; a `Sum` or `Layered` material runs its mixture over blocks: each
//! part's samples, densities and albedo estimates through that part's batch kernels, the
//! material's value through its batch evaluation, and the choice and weights in plain
//! passes with the per-sample sampler's functions (the same bits).
//!
//! Bodies that call a library transcendental (`powf`, `exp` from `std`/`libm`) do not
//! vectorize this way; the models offer polynomial alternatives (see [`crate::fast`]) for
//! their batch use.
//!
//! Inputs are structure-of-arrays slices ([`Directions`]) in the local shading frame; outputs
//! are one slice per colour channel. [`eval_glam`] converts from arrays of glam vectors.
//!
//! Without the `std` feature (or off x86-64) only [`Isa::Portable`] exists.

use core::marker::PhantomData;

#[cfg(all(feature = "std", target_arch = "x86_64"))]
use crate::real::lanes::{Avx2, Avx512, Lanes};
use crate::real::{F32Fma, F32FmaSharedDiv, Splat};
use crate::sampling::SampleBrdf;
use crate::{Real, Vec3, models::Brdf};

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

    /// The directions `r` (sub-slices).
    #[inline(always)]
    pub(crate) fn range(self, r: core::ops::Range<usize>) -> Directions<'a> {
        Directions {
            x: &self.x[r.clone()],
            y: &self.y[r.clone()],
            z: &self.z[r],
        }
    }

    /// Number of directions.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// [`Directions::len`], checking that the three slices have it (the fields are public, so
    /// a value need not come from [`Directions::new`]): the entry points call it before the
    /// explicit-lane kernels load `n` lanes of every component.
    #[inline]
    pub(crate) fn checked_len(&self) -> usize {
        let n = self.x.len();
        assert!(
            self.y.len() == n && self.z.len() == n,
            "Directions: component slices differ in length"
        );
        n
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

/// What the batch entry points need of a model: its `f32` form (for the portable loop) and
/// its [`F32Fma`] and [`F32FmaSharedDiv`] forms (for the FMA loops, see [`shares_divisions`]).
///
/// Implemented for every `B: Brdf<f32, N> + Splat` whose forms on the kernels' number types
/// ([`F32Fma`], [`F32FmaSharedDiv`] and the crate-private explicit-lane types of AVX-512 and
/// AVX2) are models on those types — every model of this crate, and a model
/// of your own once it is generic over [`Real`] and implements [`Splat`] (see its example).
///
/// In generic code, bound the composed model (`CookTorrance<f32, D, F, G>: BatchBrdf<3>`)
/// rather than each part's forms: the explicit-lane types cannot be named outside the crate.
pub trait BatchBrdf<const N: usize>: Brdf<f32, N> + wide_form::WideForm<N> {
    /// Whether the FMA kernels may run the model on explicit registers of lanes
    /// ([`Splat::EXPLICIT_LANES`]).
    const EXPLICIT_LANES: bool;
    /// The same model on [`F32Fma`].
    type Fused: Brdf<F32Fma, N>;
    /// The same model on [`F32FmaSharedDiv`].
    type SharedDiv: Brdf<F32FmaSharedDiv, N>;
    /// The same model on [`F32Fma`] (its constants keep their bits).
    fn fused(&self) -> Self::Fused;
    /// The same model on [`F32FmaSharedDiv`] (its constants keep their bits): what the FMA
    /// kernels run where [`shares_divisions`] is `true`.
    fn shared_div(&self) -> Self::SharedDiv;
}

impl<B, const N: usize> BatchBrdf<N> for B
where
    B: Brdf<f32, N> + Splat,
    B::On<F32Fma>: Brdf<F32Fma, N>,
    B::On<F32FmaSharedDiv>: Brdf<F32FmaSharedDiv, N>,
    B: wide_form::WideForm<N>,
{
    const EXPLICIT_LANES: bool = <B as Splat>::EXPLICIT_LANES;
    type Fused = B::On<F32Fma>;
    type SharedDiv = B::On<F32FmaSharedDiv>;
    #[inline]
    fn fused(&self) -> Self::Fused {
        self.splat()
    }
    #[inline]
    fn shared_div(&self) -> Self::SharedDiv {
        self.splat()
    }
}

/// The model on the explicit lanes of AVX-512 and AVX2 (crate-private: those number types may
/// exist only inside their kernels). Every `Splat` model whose form on any [`Real`] is a model
/// has it.
mod wide_form {
    use crate::real::Splat;
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    use crate::real::lanes::{Ymm, YmmShared, Zmm, ZmmShared};

    /// See the module docs.
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    pub trait WideForm<const N: usize> {
        /// The same model on [`Zmm`] (16 lanes, AVX-512).
        type Wide16: crate::Brdf<Zmm, N>;
        /// The same model on [`Ymm`] (8 lanes, AVX2).
        type Wide8: crate::Brdf<Ymm, N>;
        /// The same model on [`ZmmShared`] (16 lanes sharing divisions).
        type Wide16Shared: crate::Brdf<ZmmShared, N>;
        /// The same model on [`YmmShared`] (8 lanes sharing divisions).
        type Wide8Shared: crate::Brdf<YmmShared, N>;
        /// The 16-lane form, constants keeping their bits.
        fn wide16(&self) -> Self::Wide16;
        /// The 8-lane form, constants keeping their bits.
        fn wide8(&self) -> Self::Wide8;
        /// The 16-lane form sharing divisions, constants keeping their bits.
        fn wide16_shared(&self) -> Self::Wide16Shared;
        /// The 8-lane form sharing divisions, constants keeping their bits.
        fn wide8_shared(&self) -> Self::Wide8Shared;
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    impl<B: Splat, const N: usize> WideForm<N> for B
    where
        B::On<Zmm>: crate::Brdf<Zmm, N>,
        B::On<Ymm>: crate::Brdf<Ymm, N>,
        B::On<ZmmShared>: crate::Brdf<ZmmShared, N>,
        B::On<YmmShared>: crate::Brdf<YmmShared, N>,
    {
        type Wide16 = B::On<Zmm>;
        type Wide8 = B::On<Ymm>;
        type Wide16Shared = B::On<ZmmShared>;
        type Wide8Shared = B::On<YmmShared>;
        #[inline]
        fn wide16(&self) -> Self::Wide16 {
            self.splat()
        }
        #[inline]
        fn wide8(&self) -> Self::Wide8 {
            self.splat()
        }
        #[inline]
        fn wide16_shared(&self) -> Self::Wide16Shared {
            self.splat()
        }
        #[inline]
        fn wide8_shared(&self) -> Self::Wide8Shared {
            self.splat()
        }
    }

    /// See the module docs (no explicit lanes on this target).
    #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
    pub trait WideForm<const N: usize> {}

    #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
    impl<B: Splat, const N: usize> WideForm<N> for B {}

    /// The model's explicit-lane forms as samplers (the batch samplers' explicit lanes).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    pub trait WideSample<const N: usize> {
        /// The same model on [`Zmm`] (16 lanes, AVX-512).
        type Sampler16: crate::SampleBrdf<Zmm, N>;
        /// The same model on [`Ymm`] (8 lanes, AVX2).
        type Sampler8: crate::SampleBrdf<Ymm, N>;
        /// The same model on [`ZmmShared`] (16 lanes sharing divisions).
        type Sampler16Shared: crate::SampleBrdf<ZmmShared, N>;
        /// The same model on [`YmmShared`] (8 lanes sharing divisions).
        type Sampler8Shared: crate::SampleBrdf<YmmShared, N>;
        /// The 16-lane form, constants keeping their bits.
        fn sampler16(&self) -> Self::Sampler16;
        /// The 8-lane form, constants keeping their bits.
        fn sampler8(&self) -> Self::Sampler8;
        /// The 16-lane form sharing divisions, constants keeping their bits.
        fn sampler16_shared(&self) -> Self::Sampler16Shared;
        /// The 8-lane form sharing divisions, constants keeping their bits.
        fn sampler8_shared(&self) -> Self::Sampler8Shared;
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    impl<B: Splat, const N: usize> WideSample<N> for B
    where
        B::On<Zmm>: crate::SampleBrdf<Zmm, N>,
        B::On<Ymm>: crate::SampleBrdf<Ymm, N>,
        B::On<ZmmShared>: crate::SampleBrdf<ZmmShared, N>,
        B::On<YmmShared>: crate::SampleBrdf<YmmShared, N>,
    {
        type Sampler16 = B::On<Zmm>;
        type Sampler8 = B::On<Ymm>;
        type Sampler16Shared = B::On<ZmmShared>;
        type Sampler8Shared = B::On<YmmShared>;
        #[inline]
        fn sampler16(&self) -> Self::Sampler16 {
            self.splat()
        }
        #[inline]
        fn sampler8(&self) -> Self::Sampler8 {
            self.splat()
        }
        #[inline]
        fn sampler16_shared(&self) -> Self::Sampler16Shared {
            self.splat()
        }
        #[inline]
        fn sampler8_shared(&self) -> Self::Sampler8Shared {
            self.splat()
        }
    }

    /// See the module docs (no explicit lanes on this target).
    #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
    pub trait WideSample<const N: usize> {}

    #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
    impl<B: Splat, const N: usize> WideSample<N> for B {}
}

/// Whether the FMA kernels ([`Isa::Avx2Fma`], [`Isa::Avx512`]) of [`eval_with`], [`eval`],
/// [`eval_glam`], [`sample_with`] and [`sample`] run a model's [`F32FmaSharedDiv`] form ([`BatchBrdf::shared_div`]) rather
/// than its [`F32Fma`] form: `true` on Intel CPUs (the `cpuid` vendor string
/// `GenuineIntel`), `false` elsewhere and without `std` or off x86-64. Decided once per
/// process.
///
/// Why by vendor: the two forms differ where a formula divides once per channel (the exact
/// conductor), and which is faster depends on the core's divider. Measured on the rough gold
/// conductor workload (`benches/peers/run.sh`, AVX-512): the shared division is 1.12× faster
/// on an Intel Xeon (Sapphire Rapids class, divider-bound: three square roots and one
/// division cost more than the multiplications that replace two divisions) and 0.93–0.96×
/// on an AMD EPYC Zen 4, whose divider is not the bound. Results differ between the two
/// forms by a few ULP (`tests/fresnel.rs`); each kernel equals `eval` on its own form bit
/// for bit. The forms differ only where a material opted in
/// ([`crate::fresnel::Conductor::share_divisions`]): a model without such a term gives the
/// same bits on every CPU. The batch samplers ([`sample_with`], [`sample`]) and the explicit
/// lanes of a model with [`BatchBrdf::EXPLICIT_LANES`] (run-time parts and materials, with
/// [`crate::fresnel::AnyFresnel::ConductorShared`]) choose the same way; the pipelined
/// passes run the [`F32Fma`] form everywhere.
///
/// The same choice decides where a [`crate::fresnel::Conductor`] with
/// [`crate::fast::HardwareEstimate`] takes its estimates on the explicit AVX-512 lanes: where
/// this is `true` (divider-bound cores); elsewhere it keeps its exact operations (on an AMD
/// EPYC Zen 4 its refinement steps made the gold workload 1.17× slower).
///
/// The environment variable `BRDF_SHARE_DIVISIONS` overrides the vendor check when it is
/// `0` (never share) or `1` (share), read once: to measure both arrangements on one machine,
/// and so the test suite runs the other CPU family's kernels (`.ci/run` runs
/// `tests/batch.rs` both ways). Any other value is ignored.
#[must_use]
pub fn shares_divisions() -> bool {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    {
        use std::sync::OnceLock;
        static SHARE: OnceLock<bool> = OnceLock::new();
        *SHARE.get_or_init(|| match std::env::var("BRDF_SHARE_DIVISIONS").as_deref() {
            Ok("0") => false,
            Ok("1") => true,
            _ => {
                let id = core::arch::x86_64::__cpuid(0);
                let vendor = [id.ebx, id.edx, id.ecx].map(u32::to_le_bytes).concat();
                vendor == *b"GenuineIntel"
            }
        })
    }
    #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
    {
        false
    }
}

/// Panics unless `wi`, `wo` and every output slice have the same length; returns it.
#[inline(always)]
fn checked_len<const N: usize>(
    wi: &Directions<'_>,
    wo: &Directions<'_>,
    out: &[&mut [f32]; N],
) -> usize {
    let n = wi.checked_len();
    assert!(wo.checked_len() == n, "batch: wi and wo differ in length");
    assert!(
        out.iter().all(|c| c.len() == n),
        "batch: output and input differ in length"
    );
    n
}

/// A batch loop, compiled once per instruction set by [`dispatch`].
trait Loop<const N: usize> {
    fn run(&self, wi: Directions<'_>, wo: Directions<'_>, out: [&mut [f32]; N]);
}

/// One evaluation on the one-lane type `K` (`f32` or [`F32Fma`]) per iteration, vectorized
/// by LLVM across iterations when the enclosing function enables wider instruction sets.
struct PerPair<'a, K, B>(&'a B, PhantomData<K>);

impl<K, B, const N: usize> Loop<N> for PerPair<'_, K, B>
where
    K: Real<Scalar = f32, Mask = bool>,
    B: Brdf<K, N>,
{
    #[inline(always)]
    fn run(&self, wi: Directions<'_>, wo: Directions<'_>, out: [&mut [f32]; N]) {
        let n = checked_len(&wi, &wo, &out);
        // Re-slice to `n` so the optimizer drops the per-element bounds checks.
        let (ix, iy, iz) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
        let (ox, oy, oz) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
        let out = out.map(|c| &mut c[..n]);
        for i in 0..n {
            let f = self.0.eval(
                Vec3::new(K::splat(ix[i]), K::splat(iy[i]), K::splat(iz[i])),
                Vec3::new(K::splat(ox[i]), K::splat(oy[i]), K::splat(oz[i])),
            );
            for c in 0..N {
                out[c][i] = f[c].lane(0);
            }
        }
    }
}

/// [`crate::models::layered::layered_combine`] per pair on the one-lane type `K`: the base's
/// values from `base`, the coat's from `out`, overwritten with the layered value.
#[cfg(feature = "alloc")]
struct LayeredCombine<'a, K, F, const N: usize> {
    fresnel: &'a F,
    base: [&'a [f32]; N],
    _k: PhantomData<K>,
}

#[cfg(feature = "alloc")]
impl<K, F, const N: usize> Loop<N> for LayeredCombine<'_, K, F, N>
where
    K: Real<Scalar = f32, Mask = bool>,
    F: crate::fresnel::FresnelTerm<K, N>,
{
    #[inline(always)]
    fn run(&self, wi: Directions<'_>, wo: Directions<'_>, out: [&mut [f32]; N]) {
        let n = checked_len(&wi, &wo, &out);
        assert!(self.base.iter().all(|b| b.len() == n));
        let (ix, iy, iz) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
        let (ox, oy, oz) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
        let base = self.base.map(|b| &b[..n]);
        let out = out.map(|c| &mut c[..n]);
        for i in 0..n {
            let f = crate::models::layered::layered_combine(
                self.fresnel,
                Vec3::new(K::splat(ix[i]), K::splat(iy[i]), K::splat(iz[i])),
                Vec3::new(K::splat(ox[i]), K::splat(oy[i]), K::splat(oz[i])),
                core::array::from_fn(|c| K::splat(base[c][i])),
                core::array::from_fn(|c| K::splat(out[c][i])),
            );
            for c in 0..N {
                out[c][i] = f[c].lane(0);
            }
        }
    }
}

/// `out[c][i] += term[c][i]`: one more term of a sum, added in a vectorized loop.
#[cfg(feature = "alloc")]
struct AddInto<'a, const N: usize>([&'a [f32]; N]);

#[cfg(feature = "alloc")]
impl<const N: usize> Loop<N> for AddInto<'_, N> {
    #[inline(always)]
    fn run(&self, wi: Directions<'_>, wo: Directions<'_>, out: [&mut [f32]; N]) {
        let n = checked_len(&wi, &wo, &out);
        for (o, t) in out.into_iter().zip(self.0) {
            o[..n].iter_mut().zip(&t[..n]).for_each(|(o, t)| *o += t);
        }
    }
}

/// `out += term` channel by channel (`f32` additions, the same in every loop), compiled for
/// `isa` (available; the slices have the length of `wi`: the caller checked).
#[cfg(feature = "alloc")]
pub(crate) fn add_into_with<const N: usize>(
    isa: Isa,
    wi: Directions<'_>,
    wo: Directions<'_>,
    term: [&[f32]; N],
    out: [&mut [f32]; N],
) {
    let add = AddInto(term);
    let _ = dispatch(isa, &add, &add, wi, wo, out);
}

/// Overwrites `out` (the coat's values `S(wi, wo)`) with a [`crate::models::Layered`]
/// model's values, given its base's values `base`, computed with `isa` as [`eval_with`]
/// computes the static model (the fresnel term on the form [`shares_divisions`] selects).
/// `isa` is available and the slices have equal lengths (the caller checked).
#[cfg(feature = "alloc")]
pub(crate) fn layered_combine_with<F, const N: usize>(
    isa: Isa,
    fresnel: &F,
    wi: Directions<'_>,
    wo: Directions<'_>,
    base: [&[f32]; N],
    out: [&mut [f32]; N],
) where
    F: crate::fresnel::FresnelTerm<f32, N> + Splat,
    F::On<F32Fma>: crate::fresnel::FresnelTerm<F32Fma, N>,
    F::On<F32FmaSharedDiv>: crate::fresnel::FresnelTerm<F32FmaSharedDiv, N>,
{
    let portable = LayeredCombine::<f32, F, N> {
        fresnel,
        base,
        _k: PhantomData,
    };
    let _ = if shares_divisions() {
        let shared: F::On<F32FmaSharedDiv> = fresnel.splat();
        let fused = LayeredCombine::<F32FmaSharedDiv, _, N> {
            fresnel: &shared,
            base,
            _k: PhantomData,
        };
        dispatch(isa, &portable, &fused, wi, wo, out)
    } else {
        let plain: F::On<F32Fma> = fresnel.splat();
        let fused = LayeredCombine::<F32Fma, _, N> {
            fresnel: &plain,
            base,
            _k: PhantomData,
        };
        dispatch(isa, &portable, &fused, wi, wo, out)
    };
}

/// The passes of [`Pipelined::eval_passes`] on the one-lane type `K`.
struct Passes<'a, K, B>(&'a B, PhantomData<K>);

impl<K, B, const N: usize> Loop<N> for Passes<'_, K, B>
where
    K: Real<Scalar = f32, Mask = bool>,
    B: Pipelined<K, N>,
{
    #[inline(always)]
    fn run(&self, wi: Directions<'_>, wo: Directions<'_>, out: [&mut [f32]; N]) {
        checked_len(&wi, &wo, &out);
        self.0.eval_passes(wi, wo, out);
    }
}

/// `LANES` evaluations per iteration of `model` on explicit registers ([`Zmm`], [`Ymm`]), the
/// last `n mod LANES` under a lane mask: the loop of models with [`Splat::EXPLICIT_LANES`].
/// The model comes by value, so its constants are locals that the optimizer keeps in
/// registers across the loop. Inlined into the `#[target_feature]` kernels below.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[inline(always)]
fn lanes_loop<Bk, B, const N: usize>(
    model: B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) where
    Bk: crate::real::lanes::Backend,
    B: Brdf<crate::real::lanes::Lanes<Bk>, N>,
{
    use crate::real::lanes::{Lanes, LanesMask, first_lanes, load, store};
    let n = checked_len(&wi, &wo, &out);
    #[inline(always)]
    fn block<Bk, B, const N: usize>(
        model: &B,
        wi: &Directions<'_>,
        wo: &Directions<'_>,
        out: &mut [&mut [f32]; N],
        i: usize,
        m: LanesMask<Bk>,
    ) where
        Bk: crate::real::lanes::Backend,
        B: Brdf<Lanes<Bk>, N>,
    {
        // SAFETY: called only from the kernels below (their features checked by the
        // dispatcher), and the mask keeps lanes `i + j < n`, within every slice.
        unsafe {
            let f = model.eval(
                Vec3::new(load(wi.x, i, m), load(wi.y, i, m), load(wi.z, i, m)),
                Vec3::new(load(wo.x, i, m), load(wo.y, i, m), load(wo.z, i, m)),
            );
            for c in 0..N {
                store(out[c], i, m, f[c]);
            }
        }
    }
    let mut out = out;
    let lanes = Bk::LANES;
    let full = n - n % lanes;
    // SAFETY: as above.
    let all = unsafe { first_lanes::<Bk>(lanes) };
    let mut i = 0;
    while i < full {
        block(&model, &wi, &wo, &mut out, i, all);
        i += lanes;
    }
    if full < n {
        let tail = unsafe { first_lanes::<Bk>(n - full) };
        block(&model, &wi, &wo, &mut out, full, tail);
    }
}

/// [`lanes_loop`] on 16 AVX-512 lanes.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
fn kernel_avx512_lanes16<const S: bool, B: Brdf<Lanes<Avx512<S>>, N>, const N: usize>(
    model: B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    lanes_loop::<Avx512<S>, B, N>(model, wi, wo, out)
}

/// [`lanes_loop`] on 8 AVX2 lanes.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2,fma")]
fn kernel_avx2_lanes8<const S: bool, B: Brdf<Lanes<Avx2<S>>, N>, const N: usize>(
    model: B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    lanes_loop::<Avx2<S>, B, N>(model, wi, wo, out)
}

#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2,fma")]
fn kernel_avx2<L: Loop<N>, const N: usize>(
    l: &L,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    l.run(wi, wo, out)
}

#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
fn kernel_avx512<L: Loop<N>, const N: usize>(
    l: &L,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    l.run(wi, wo, out)
}

/// Runs `portable` compiled for the build's baseline, or `fused` compiled for `isa`'s FMA
/// instruction sets.
#[inline]
fn dispatch<P: Loop<N>, F: Loop<N>, const N: usize>(
    isa: Isa,
    portable: &P,
    fused: &F,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) -> Result<(), Unavailable> {
    if !isa.is_available() {
        return Err(Unavailable(isa));
    }
    match isa {
        Isa::Portable => portable.run(wi, wo, out),
        // SAFETY: `is_available` checked at run time that the CPU has these features.
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        Isa::Avx2Fma => unsafe { kernel_avx2(fused, wi, wo, out) },
        // SAFETY: as above.
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        Isa::Avx512 => unsafe { kernel_avx512(fused, wi, wo, out) },
        #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
        _ => {
            let _ = fused;
            unreachable!("only Portable is available here")
        }
    }
    Ok(())
}

/// Evaluates `brdf` for every pair `(wi[i], wo[i])` with a chosen instruction set, writing
/// channel `c` of `f(wi[i], wo[i])` (sr⁻¹, without `cos θi`) to `out[c][i]`.
///
/// Returns [`Unavailable`] if the CPU lacks `isa`. [`Isa::Portable`] results equal
/// [`Brdf::eval`] on `brdf` bit for bit; the FMA variants equal `eval` on
/// [`BatchBrdf::fused`] bit for bit, or on [`BatchBrdf::shared_div`] where
/// [`shares_divisions`] (see the [module docs](self)). A model with a batch evaluation of
/// its own ([`Brdf::eval_batch`], tried first: a run-time
/// [`Material`](crate::material::Material)) gives the results of the model it runs.
///
/// # Panics
///
/// If `wi`, `wo` and the output slices differ in length.
#[inline]
pub fn eval_with<B: BatchBrdf<N>, const N: usize>(
    isa: Isa,
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) -> Result<(), Unavailable> {
    if !isa.is_available() {
        return Err(Unavailable(isa));
    }
    checked_len(&wi, &wo, &out);
    let mut out = out;
    if brdf.eval_batch(isa, wi, wo, &mut out) {
        return Ok(());
    }
    // Only the form the FMA kernels run is built.
    let portable = PerPair::<f32, B>(brdf, PhantomData);
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    if B::EXPLICIT_LANES && isa != Isa::Portable {
        // SAFETY: `is_available` checked at run time that the CPU has these features.
        match (isa, shares_divisions()) {
            (Isa::Avx512, false) => unsafe { kernel_avx512_lanes16(brdf.wide16(), wi, wo, out) },
            (Isa::Avx512, true) => unsafe {
                kernel_avx512_lanes16(brdf.wide16_shared(), wi, wo, out)
            },
            (_, false) => unsafe { kernel_avx2_lanes8(brdf.wide8(), wi, wo, out) },
            (_, true) => unsafe { kernel_avx2_lanes8(brdf.wide8_shared(), wi, wo, out) },
        }
        return Ok(());
    }
    if shares_divisions() {
        let shared = brdf.shared_div();
        let shared = PerPair::<F32FmaSharedDiv, B::SharedDiv>(&shared, PhantomData);
        dispatch(isa, &portable, &shared, wi, wo, out)
    } else {
        let fused = brdf.fused();
        let fused = PerPair::<F32Fma, B::Fused>(&fused, PhantomData);
        dispatch(isa, &portable, &fused, wi, wo, out)
    }
}

/// Evaluates `brdf` for every pair `(wi[i], wo[i])` on the widest instruction set this CPU
/// has ([`Isa::detect`]); see [`eval_with`].
///
/// # Examples
///
/// ```
/// use brdf::batch::{Directions, eval};
/// use brdf::models::Lambert;
///
/// let white = Lambert::new([1.0_f32]).unwrap();
/// let z = [1.0f32; 100];
/// let zero = [0.0f32; 100];
/// let mut f = [0.0f32; 100];
/// eval(&white, Directions::new(&zero, &zero, &z), Directions::new(&zero, &zero, &z), [&mut f]);
/// assert!(f.iter().all(|&v| v == core::f32::consts::FRAC_1_PI));
/// ```
///
/// # Panics
///
/// If `wi`, `wo` and the output slices differ in length.
#[inline]
pub fn eval<B: BatchBrdf<N>, const N: usize>(
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) {
    // The detected variant is available by construction.
    let _ = eval_with(Isa::detect(), brdf, wi, wo, out);
}

/// Pairs per block of a [`Pipelined`] evaluation: 1024 (measured best of 128…4096 on the
/// normalized Blinn-Phong; its scratch arrays, `(1 + 2N)·4` KiB, stay in L1/L2).
pub const BLOCK: usize = 1024;

/// A model with a software-pipelined batch evaluation on the one-lane type `K` (`f32` or
/// [`F32Fma`]).
///
/// A BRDF body is one long dependency chain (a square root, a division, then a polynomial
/// `pow`), and a vector iteration of the [`eval`] loop carries all of it: the out-of-order
/// window holds only a few iterations, so the core waits on latency instead of filling its
/// pipes. [`Pipelined::eval_passes`] splits the body into passes over blocks of [`BLOCK`]
/// pairs — each pass a short chain that vectorizes on its own, with the intermediates in
/// scratch arrays on the stack — using the same formula bodies as [`Brdf::eval`], so its
/// results equal `eval`'s bit for bit (tested). [`eval_pipelined`] runs it with run-time
/// dispatch, like [`eval`], on `f32` in the portable loop and on [`F32Fma`] in the FMA loops.
///
/// Implemented by [`crate::models::NormalizedBlinnPhong`] and
/// [`crate::models::NormalizedBlinnPhongSpecular`] (passes: geometry, Fresnel and diffuse;
/// `y·log₂ x`; `exp2` and the sum), the seed's model, whose chain the `pow` dominates; and by
/// [`crate::models::CookTorrance`] (passes: `cos θd`, `cos²θd` and `D·V`; the Fresnel term and the
/// product). Whether it pays depends on the model: see the measured ratios in the README.
/// Scratch space on the stack: `(1 + 2N)·4` KiB for the normalized Blinn-Phong, 12 KiB for
/// Cook-Torrance.
pub trait Pipelined<K: Real<Scalar = f32, Mask = bool>, const N: usize>: Brdf<K, N> {
    /// Writes `f(wi[i], wo[i])` to `out[c][i]`, in passes over blocks of [`BLOCK`] pairs
    /// ([`for_each_block`]). The slices have equal lengths (the caller checks).
    fn eval_passes(&self, wi: Directions<'_>, wo: Directions<'_>, out: [&mut [f32]; N]);
}

/// Calls `block(wi, wo, out)` on consecutive blocks of at most [`BLOCK`] pairs (the last one
/// shorter) of equal-length slices: the loop of a [`Pipelined::eval_passes`], whose scratch
/// arrays of [`BLOCK`] entries live outside it (allocated once per call).
///
/// Mark the closure `#[inline(always)]`: otherwise LLVM may keep it out of line, outside the
/// instruction set of the kernel that called it (measured: 7× slower).
#[inline(always)]
pub fn for_each_block<const N: usize>(
    wi: Directions<'_>,
    wo: Directions<'_>,
    mut out: [&mut [f32]; N],
    mut block: impl FnMut(Directions<'_>, Directions<'_>, [&mut [f32]; N]),
) {
    let total = wi.len();
    let mut start = 0;
    while start < total {
        let end = (start + BLOCK).min(total);
        let r = start..end;
        let out = out.each_mut().map(|o| &mut o[r.clone()]);
        block(wi.range(r.clone()), wo.range(r), out);
        start = end;
    }
}

/// [`eval_with`] for a [`Pipelined`] model: the passes of [`Pipelined::eval_passes`], compiled
/// for `isa`. Same results as [`eval_with`].
///
/// # Errors
///
/// [`Unavailable`] if the CPU lacks `isa`.
///
/// # Panics
///
/// If `wi`, `wo` and the output slices differ in length.
#[inline]
pub fn eval_pipelined_with<B, const N: usize>(
    isa: Isa,
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) -> Result<(), Unavailable>
where
    B: BatchBrdf<N> + Pipelined<f32, N>,
    B::Fused: Pipelined<F32Fma, N>,
{
    let fused = brdf.fused();
    dispatch(
        isa,
        &Passes::<f32, B>(brdf, PhantomData),
        &Passes::<F32Fma, B::Fused>(&fused, PhantomData),
        wi,
        wo,
        out,
    )
}

/// [`eval`] for a [`Pipelined`] model, on the widest instruction set this CPU has.
///
/// # Examples
///
/// ```
/// use brdf::batch::{Directions, eval, eval_pipelined};
/// use brdf::fast::FastPow;
/// use brdf::models::{CosThetaI, NormalizedBlinnPhong};
/// use brdf::normalization::Normalization;
///
/// let nbp = NormalizedBlinnPhong::<f32, 1>::new(
///     [0.5], 0.5, [0.04], 64.0, Normalization::TRI_ACE_2009_FIT,
/// ).unwrap().with_pow::<FastPow>();
/// let n = 1000;
/// let x: Vec<f32> = (0..n).map(|i| 0.5 * (i as f32 / n as f32)).collect();
/// let z: Vec<f32> = x.iter().map(|x| (1.0 - x * x).sqrt()).collect();
/// let zero = vec![0.0f32; n];
/// let (wi, wo) = (Directions::new(&x, &zero, &z), Directions::new(&zero, &zero, &[1.0; 1000]));
/// let (mut a, mut b) = (vec![0.0f32; n], vec![0.0f32; n]);
/// eval_pipelined(&nbp, wi, wo, [&mut a]);
/// eval(&nbp, wi, wo, [&mut b]);
/// assert_eq!(a, b);
/// ```
///
/// # Panics
///
/// If `wi`, `wo` and the output slices differ in length.
#[inline]
pub fn eval_pipelined<B, const N: usize>(
    brdf: &B,
    wi: Directions<'_>,
    wo: Directions<'_>,
    out: [&mut [f32]; N],
) where
    B: BatchBrdf<N> + Pipelined<f32, N>,
    B::Fused: Pipelined<F32Fma, N>,
{
    // The detected variant is available by construction.
    let _ = eval_pipelined_with(Isa::detect(), brdf, wi, wo, out);
}

/// Convenience over glam: evaluates `brdf` for `(wi[i], wo[i])` given as arrays of
/// `glam::Vec3` (array of structures), writing `out[i]` per channel. Transposes in chunks on
/// the stack, then runs [`eval`].
///
/// # Panics
///
/// If `wi`, `wo` and `out` differ in length.
pub fn eval_glam<B: BatchBrdf<N>, const N: usize>(
    brdf: &B,
    wi: &[glam::Vec3],
    wo: &[glam::Vec3],
    out: &mut [[f32; N]],
) {
    assert!(
        wi.len() == wo.len() && wo.len() == out.len(),
        "eval_glam: lengths differ"
    );
    let isa = Isa::detect();
    // `eval_with` per chunk: the model's forms are copies of its constants (a material
    // is not copied at all: its `eval_batch` hands the variant on), cheap beside 256 pairs.
    // The detected variant is available by construction.
    glam_chunks(wi, wo, out, |i, o, s| {
        let _ = eval_with(isa, brdf, i, o, s);
    });
}

/// The chunked transposition of [`eval_glam`] around `run` (a batch loop on one chunk).
fn glam_chunks<const N: usize>(
    wi: &[glam::Vec3],
    wo: &[glam::Vec3],
    out: &mut [[f32; N]],
    mut run: impl FnMut(Directions<'_>, Directions<'_>, [&mut [f32]; N]),
) {
    const CHUNK: usize = 256;
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
        run(dirs_i, dirs_o, slices);
        for (i, o) in out.iter_mut().enumerate() {
            *o = core::array::from_fn(|c| res[c][i]);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Batch sampling
// ---------------------------------------------------------------------------------------------

/// What [`sample`] needs of a model: [`BatchBrdf`] whose `f32` and [`F32Fma`] forms both
/// sample ([`SampleBrdf`]). Implemented for every model of this crate that samples.
pub trait BatchSample<const N: usize>:
    BatchBrdf<N> + SampleBrdf<f32, N> + wide_form::WideSample<N>
where
    Self::Fused: SampleBrdf<F32Fma, N>,
    Self::SharedDiv: SampleBrdf<F32FmaSharedDiv, N>,
{
}

impl<B, const N: usize> BatchSample<N> for B
where
    B: BatchBrdf<N> + SampleBrdf<f32, N> + wide_form::WideSample<N>,
    B::Fused: SampleBrdf<F32Fma, N>,
    B::SharedDiv: SampleBrdf<F32FmaSharedDiv, N>,
{
}

/// Output slices of a batch [`sample`]: the drawn directions (structure of arrays), their densities and the
/// weights per channel. Every slice has the length of the input.
#[derive(Debug)]
pub struct SampleOut<'a, const N: usize> {
    /// `wi.x` of each sample.
    pub x: &'a mut [f32],
    /// `wi.y` of each sample.
    pub y: &'a mut [f32],
    /// `wi.z` of each sample (`cos θi`).
    pub z: &'a mut [f32],
    /// The density per unit solid angle (`0`: invalid sample).
    pub pdf: &'a mut [f32],
    /// `f·cos θi / pdf` per channel (`0` on invalid samples).
    pub weight: [&'a mut [f32]; N],
}

/// A batch sampling loop, compiled once per instruction set.
trait SampleLoop<const N: usize> {
    fn run(&self, wo: Directions<'_>, u: [&[f32]; 3], out: &mut SampleOut<'_, N>);
}

/// One [`SampleBrdf::sample`] on the one-lane type `K` per iteration.
struct PerSample<'a, K, B>(&'a B, PhantomData<K>);

impl<K, B, const N: usize> SampleLoop<N> for PerSample<'_, K, B>
where
    K: Real<Scalar = f32, Mask = bool>,
    B: SampleBrdf<K, N>,
{
    #[inline(always)]
    fn run(&self, wo: Directions<'_>, u: [&[f32]; 3], out: &mut SampleOut<'_, N>) {
        let n = wo.len();
        let (ox, oy, oz) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
        let (u0, u1, u2) = (&u[0][..n], &u[1][..n], &u[2][..n]);
        let (x, y, z, pdf) = (
            &mut out.x[..n],
            &mut out.y[..n],
            &mut out.z[..n],
            &mut out.pdf[..n],
        );
        let mut weight = out.weight.each_mut().map(|c| &mut c[..n]);
        for i in 0..n {
            let s = self.0.sample(
                Vec3::new(K::splat(ox[i]), K::splat(oy[i]), K::splat(oz[i])),
                [K::splat(u0[i]), K::splat(u1[i]), K::splat(u2[i])],
            );
            x[i] = s.wi.x.lane(0);
            y[i] = s.wi.y.lane(0);
            z[i] = s.wi.z.lane(0);
            pdf[i] = s.pdf.lane(0);
            for (o, w) in weight.iter_mut().zip(&s.weight) {
                o[i] = w.lane(0);
            }
        }
    }
}

#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2,fma")]
fn sample_kernel_avx2<L: SampleLoop<N>, const N: usize>(
    l: &L,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, N>,
) {
    l.run(wo, u, out)
}

#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
fn sample_kernel_avx512<L: SampleLoop<N>, const N: usize>(
    l: &L,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, N>,
) {
    l.run(wo, u, out)
}

/// Batch densities ([`pdf_with`], [`pdf`]) and the crate-private albedo estimates (the
/// batch sampler of `Material::Sum` and `Material::Layered`): per-element map loops.
mod maps {
    use super::*;

    /// A per-element loop of the batch densities and albedo estimates, compiled once per
    /// instruction set: `I` input streams, one output.
    trait MapLoop<const I: usize> {
        fn run(&self, inputs: [&[f32]; I], out: &mut [f32]);
    }

    /// [`SampleBrdf::pdf`] on the one-lane type `K` per element: inputs `wo` then `wi`.
    struct PerPdf<'a, K, B, const N: usize>(&'a B, PhantomData<K>);

    impl<K, B, const N: usize> MapLoop<6> for PerPdf<'_, K, B, N>
    where
        K: Real<Scalar = f32, Mask = bool>,
        B: SampleBrdf<K, N>,
    {
        #[inline(always)]
        fn run(&self, inputs: [&[f32]; 6], out: &mut [f32]) {
            let n = out.len();
            let [ox, oy, oz, ix, iy, iz] = inputs.map(|s| &s[..n]);
            for j in 0..n {
                let wo = Vec3::new(K::splat(ox[j]), K::splat(oy[j]), K::splat(oz[j]));
                let wi = Vec3::new(K::splat(ix[j]), K::splat(iy[j]), K::splat(iz[j]));
                out[j] = self.0.pdf(wo, wi).lane(0);
            }
        }
    }

    /// [`SampleBrdf::albedo_estimate`] on the one-lane type `K` per element: input `wo`.
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    struct PerEstimate<'a, K, B, const N: usize>(&'a B, PhantomData<K>);

    impl<K, B, const N: usize> MapLoop<3> for PerEstimate<'_, K, B, N>
    where
        K: Real<Scalar = f32, Mask = bool>,
        B: SampleBrdf<K, N>,
    {
        #[inline(always)]
        fn run(&self, inputs: [&[f32]; 3], out: &mut [f32]) {
            let n = out.len();
            let [ox, oy, oz] = inputs.map(|s| &s[..n]);
            for j in 0..n {
                let wo = Vec3::new(K::splat(ox[j]), K::splat(oy[j]), K::splat(oz[j]));
                out[j] = self.0.albedo_estimate(wo).lane(0);
            }
        }
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx2,fma")]
    fn map_kernel_avx2<L: MapLoop<I>, const I: usize>(l: &L, inputs: [&[f32]; I], out: &mut [f32]) {
        l.run(inputs, out)
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
    fn map_kernel_avx512<L: MapLoop<I>, const I: usize>(
        l: &L,
        inputs: [&[f32]; I],
        out: &mut [f32],
    ) {
        l.run(inputs, out)
    }

    /// Runs a [`MapLoop`] built by `make` on the form `isa`'s loop runs: the `f32` model on
    /// [`Isa::Portable`], else its [`F32FmaSharedDiv`] form where [`shares_divisions`] and its
    /// [`F32Fma`] form elsewhere, compiled for `isa` (available: the caller checked).
    macro_rules! map_with {
        ($isa:expr, $brdf:expr, $loop:ident, $op:expr, $inputs:expr, $out:expr) => {{
            let (isa, brdf, inputs, out) = ($isa, $brdf, $inputs, $out);
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            if B::EXPLICIT_LANES && isa != Isa::Portable {
                // SAFETY: the caller checked with `is_available` that the CPU has these
                // features.
                match (isa, shares_divisions()) {
                    (Isa::Avx512, false) => unsafe {
                        map_kernel_avx512_lanes16(brdf.sampler16(), $op, &inputs, out)
                    },
                    (Isa::Avx512, true) => unsafe {
                        map_kernel_avx512_lanes16(brdf.sampler16_shared(), $op, &inputs, out)
                    },
                    (_, false) => unsafe {
                        map_kernel_avx2_lanes8(brdf.sampler8(), $op, &inputs, out)
                    },
                    (_, true) => unsafe {
                        map_kernel_avx2_lanes8(brdf.sampler8_shared(), $op, &inputs, out)
                    },
                }
                return;
            }
            if isa == Isa::Portable {
                $loop::<f32, _, N>(brdf, PhantomData).run(inputs, out);
            } else if shares_divisions() {
                let form = brdf.shared_div();
                map_fma(
                    isa,
                    &$loop::<F32FmaSharedDiv, _, N>(&form, PhantomData),
                    inputs,
                    out,
                );
            } else {
                let form = brdf.fused();
                map_fma(isa, &$loop::<F32Fma, _, N>(&form, PhantomData), inputs, out);
            }
        }};
    }

    /// What a map loop computes per element (the explicit-lane loops' switch).
    #[derive(Clone, Copy)]
    #[cfg_attr(not(all(feature = "std", target_arch = "x86_64")), allow(dead_code))]
    enum MapOp {
        /// [`SampleBrdf::pdf`]: inputs `wo` then `wi`.
        Pdf,
        /// [`SampleBrdf::albedo_estimate`]: input `wo`.
        #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
        Estimate,
    }

    /// `LANES` densities or estimates per iteration of `model` on explicit registers, the
    /// last `n mod LANES` under a lane mask: the map loop of models with
    /// [`Splat::EXPLICIT_LANES`] (as [`lanes_sample_loop`] is their sampling loop).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[inline(always)]
    fn lanes_map_loop<Bk, B, const N: usize>(
        model: B,
        op: MapOp,
        inputs: &[&[f32]],
        out: &mut [f32],
    ) where
        Bk: crate::real::lanes::Backend,
        B: SampleBrdf<crate::real::lanes::Lanes<Bk>, N>,
    {
        use crate::real::lanes::{LanesMask, first_lanes, load, store};
        let n = out.len();
        assert!(inputs.iter().all(|s| s.len() == n));
        #[inline(always)]
        fn block<Bk, B, const N: usize>(
            model: &B,
            op: MapOp,
            inputs: &[&[f32]],
            out: &mut [f32],
            i: usize,
            m: LanesMask<Bk>,
        ) where
            Bk: crate::real::lanes::Backend,
            B: SampleBrdf<crate::real::lanes::Lanes<Bk>, N>,
        {
            // SAFETY: called only from the kernels below (their features checked by the
            // dispatcher), and the mask keeps lanes `i + j < n`, within every slice.
            unsafe {
                // A function marked for inlining, not a closure: LLVM kept a closure out of
                // line, without the kernel's features (seen on AVX2: every load a call,
                // 10× slower).
                #[inline(always)]
                unsafe fn at<Bk: crate::real::lanes::Backend>(
                    s: &[&[f32]],
                    i: usize,
                    m: LanesMask<Bk>,
                ) -> Vec3<crate::real::lanes::Lanes<Bk>> {
                    unsafe { Vec3::new(load(s[0], i, m), load(s[1], i, m), load(s[2], i, m)) }
                }
                let v = match op {
                    MapOp::Pdf => model.pdf(at(inputs, i, m), at(&inputs[3..], i, m)),
                    MapOp::Estimate => model.albedo_estimate(at(inputs, i, m)),
                };
                store(out, i, m, v);
            }
        }
        let lanes = Bk::LANES;
        let full = n - n % lanes;
        // SAFETY: as above.
        let all = unsafe { first_lanes::<Bk>(lanes) };
        let mut i = 0;
        while i < full {
            block(&model, op, inputs, out, i, all);
            i += lanes;
        }
        if full < n {
            let tail = unsafe { first_lanes::<Bk>(n - full) };
            block(&model, op, inputs, out, full, tail);
        }
    }

    /// [`lanes_map_loop`] on 16 AVX-512 lanes.
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
    fn map_kernel_avx512_lanes16<
        const S: bool,
        B: SampleBrdf<Lanes<Avx512<S>>, N>,
        const N: usize,
    >(
        model: B,
        op: MapOp,
        inputs: &[&[f32]],
        out: &mut [f32],
    ) {
        lanes_map_loop::<Avx512<S>, B, N>(model, op, inputs, out)
    }

    /// [`lanes_map_loop`] on 8 AVX2 lanes.
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx2,fma")]
    fn map_kernel_avx2_lanes8<const S: bool, B: SampleBrdf<Lanes<Avx2<S>>, N>, const N: usize>(
        model: B,
        op: MapOp,
        inputs: &[&[f32]],
        out: &mut [f32],
    ) {
        lanes_map_loop::<Avx2<S>, B, N>(model, op, inputs, out)
    }

    /// Runs `l` compiled for `isa`'s FMA instruction sets (available: the caller checked).
    #[inline]
    fn map_fma<L: MapLoop<I>, const I: usize>(
        isa: Isa,
        l: &L,
        inputs: [&[f32]; I],
        out: &mut [f32],
    ) {
        match isa {
            // SAFETY: the caller checked with `is_available` that the CPU has these features.
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            Isa::Avx2Fma => unsafe { map_kernel_avx2(l, inputs, out) },
            // SAFETY: as above.
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            Isa::Avx512 => unsafe { map_kernel_avx512(l, inputs, out) },
            _ => {
                let _ = (l, inputs, out);
                unreachable!("only Portable is available here")
            }
        }
    }

    /// Evaluates the density [`SampleBrdf::pdf`] for every pair, `out[j] = pdf(wo[j], wi[j])`
    /// (sr⁻¹: the density of drawing `wi[j]` from `wo[j]` with the model's sampler, per unit
    /// solid angle; `0` where that sampler cannot draw it, below the horizon included) with a
    /// chosen instruction set: the densities a renderer needs for multiple importance
    /// sampling of directions it drew otherwise (light sampling).
    ///
    /// Returns [`Unavailable`] if the CPU lacks `isa`. The results are [`SampleBrdf::pdf`]
    /// on the form [`sample_with`] runs, bit for bit: on the `f32` model for
    /// [`Isa::Portable`], on [`BatchBrdf::fused`] (or [`BatchBrdf::shared_div`] where
    /// [`shares_divisions`]) for the FMA variants, on explicit lanes for a model with
    /// [`BatchBrdf::EXPLICIT_LANES`] (hardware estimates aside, as for [`eval_with`]). A model
    /// with batch densities of its own ([`SampleBrdf::pdf_batch`], tried first: a run-time
    /// [`Material`](crate::material::Material)) gives those of the model it runs; a `Sum` or
    /// `Layered` material combines its parts' batches with the per-pair mixture's formula
    /// (the same bits as its `pdf` per pair).
    ///
    /// Note the argument order: `wo` (the given direction) first, as in
    /// [`SampleBrdf::pdf`], unlike [`eval_with`]'s `(wi, wo)`.
    ///
    /// # Panics
    ///
    /// If `wo`, `wi` and `out` differ in length.
    pub fn pdf_with<B, const N: usize>(
        isa: Isa,
        brdf: &B,
        wo: Directions<'_>,
        wi: Directions<'_>,
        out: &mut [f32],
    ) -> Result<(), Unavailable>
    where
        B: BatchSample<N>,
        B::Fused: SampleBrdf<F32Fma, N>,
        B::SharedDiv: SampleBrdf<F32FmaSharedDiv, N>,
    {
        assert!(
            wo.checked_len() == out.len() && wi.checked_len() == out.len(),
            "batch: output and input differ in length"
        );
        if !isa.is_available() {
            return Err(Unavailable(isa));
        }
        if !brdf.pdf_batch(isa, wo, wi, out) {
            pdf_kernels(isa, brdf, wo, wi, out);
        }
        Ok(())
    }

    /// The loops of [`pdf_with`] (`isa` available, the lengths equal: the caller checked).
    fn pdf_kernels<B, const N: usize>(
        isa: Isa,
        brdf: &B,
        wo: Directions<'_>,
        wi: Directions<'_>,
        out: &mut [f32],
    ) where
        B: BatchSample<N>,
        B::Fused: SampleBrdf<F32Fma, N>,
        B::SharedDiv: SampleBrdf<F32FmaSharedDiv, N>,
    {
        map_with!(
            isa,
            brdf,
            PerPdf,
            MapOp::Pdf,
            [wo.x, wo.y, wo.z, wi.x, wi.y, wi.z],
            out
        )
    }

    /// [`pdf_with`] on the widest instruction set this CPU has ([`Isa::detect`]).
    ///
    /// ```
    /// use brdf::batch::{Directions, pdf};
    /// use brdf::models::Lambert;
    ///
    /// let white = Lambert::new([1.0_f32]).unwrap();
    /// let (zero, one) = ([0.0f32; 64], [1.0f32; 64]);
    /// let mut p = [0.0f32; 64];
    /// // wo = wi = the normal: the cosine density 1/π.
    /// let n = Directions::new(&zero, &zero, &one);
    /// pdf(&white, n, n, &mut p);
    /// assert!(p.iter().all(|&v| (v - core::f32::consts::FRAC_1_PI).abs() < 1e-7));
    /// ```
    ///
    /// # Panics
    ///
    /// If `wo`, `wi` and `out` differ in length.
    #[inline]
    pub fn pdf<B, const N: usize>(brdf: &B, wo: Directions<'_>, wi: Directions<'_>, out: &mut [f32])
    where
        B: BatchSample<N>,
        B::Fused: SampleBrdf<F32Fma, N>,
        B::SharedDiv: SampleBrdf<F32FmaSharedDiv, N>,
    {
        // The detected variant is available by construction.
        let _ = pdf_with(Isa::detect(), brdf, wo, wi, out);
    }

    /// `out[j] = albedo_estimate(wo[j])` ([`SampleBrdf::albedo_estimate`]) on the form
    /// [`pdf_with`] runs, with `isa` (panics if it is not available; the lengths equal).
    #[cfg(feature = "alloc")]
    pub(crate) fn albedo_estimate_with<B, const N: usize>(
        isa: Isa,
        brdf: &B,
        wo: Directions<'_>,
        out: &mut [f32],
    ) where
        B: BatchSample<N>,
        B::Fused: SampleBrdf<F32Fma, N>,
        B::SharedDiv: SampleBrdf<F32FmaSharedDiv, N>,
    {
        assert!(
            isa.is_available(),
            "batch: {isa:?} is not available on this CPU"
        );
        assert!(wo.checked_len() == out.len());
        map_with!(
            isa,
            brdf,
            PerEstimate,
            MapOp::Estimate,
            [wo.x, wo.y, wo.z],
            out
        )
    }
}

#[cfg(feature = "alloc")]
pub(crate) use maps::albedo_estimate_with;
pub use maps::{pdf, pdf_with};

/// `LANES` samples per iteration of `model` on explicit registers ([`Zmm`], [`Ymm`]), the last
/// `n mod LANES` under a lane mask: the sampling loop of models with
/// [`Splat::EXPLICIT_LANES`], as [`lanes_loop`] is their evaluation loop.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[inline(always)]
fn lanes_sample_loop<Bk, B, const N: usize>(
    model: B,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, N>,
) where
    Bk: crate::real::lanes::Backend,
    B: SampleBrdf<crate::real::lanes::Lanes<Bk>, N>,
{
    use crate::real::lanes::{first_lanes, load, store};
    let n = wo.len();
    #[inline(always)]
    fn block<Bk, B, const N: usize>(
        model: &B,
        wo: &Directions<'_>,
        u: &[&[f32]; 3],
        out: &mut SampleOut<'_, N>,
        i: usize,
        m: crate::real::lanes::LanesMask<Bk>,
    ) where
        Bk: crate::real::lanes::Backend,
        B: SampleBrdf<crate::real::lanes::Lanes<Bk>, N>,
    {
        // SAFETY: called only from the kernels below (their features checked by the
        // dispatcher), and the mask keeps lanes `i + j < n`, within every slice (the caller
        // checked that all have length `n`).
        unsafe {
            let s = model.sample(
                Vec3::new(load(wo.x, i, m), load(wo.y, i, m), load(wo.z, i, m)),
                [load(u[0], i, m), load(u[1], i, m), load(u[2], i, m)],
            );
            store(out.x, i, m, s.wi.x);
            store(out.y, i, m, s.wi.y);
            store(out.z, i, m, s.wi.z);
            store(out.pdf, i, m, s.pdf);
            for (o, w) in out.weight.iter_mut().zip(s.weight) {
                store(o, i, m, w);
            }
        }
    }
    let lanes = Bk::LANES;
    let full = n - n % lanes;
    // SAFETY: as above.
    let all = unsafe { first_lanes::<Bk>(lanes) };
    let mut i = 0;
    while i < full {
        block(&model, &wo, &u, out, i, all);
        i += lanes;
    }
    if full < n {
        let tail = unsafe { first_lanes::<Bk>(n - full) };
        block(&model, &wo, &u, out, full, tail);
    }
}

/// [`lanes_sample_loop`] on 16 AVX-512 lanes.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
fn sample_kernel_avx512_lanes16<
    const S: bool,
    B: SampleBrdf<Lanes<Avx512<S>>, N>,
    const N: usize,
>(
    model: B,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, N>,
) {
    lanes_sample_loop::<Avx512<S>, B, N>(model, wo, u, out)
}

/// [`lanes_sample_loop`] on 8 AVX2 lanes.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2,fma")]
fn sample_kernel_avx2_lanes8<const S: bool, B: SampleBrdf<Lanes<Avx2<S>>, N>, const N: usize>(
    model: B,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, N>,
) {
    lanes_sample_loop::<Avx2<S>, B, N>(model, wo, u, out)
}

/// Draws one `wi` per `wo[i]` from the uniform numbers `(u[0][i], u[1][i], u[2][i])` with a
/// chosen instruction set ([`SampleBrdf::sample`] per element; see the
/// [sampling conventions](crate::sampling)), writing the direction, its density and its
/// weight to `out`.
///
/// [`Isa::Portable`] results equal [`SampleBrdf::sample`] on `brdf` bit for bit; the FMA
/// variants equal `sample` on [`BatchBrdf::fused`] (or [`BatchBrdf::shared_div`] where
/// [`shares_divisions`]) bit for bit, as for [`eval_with`] (hardware estimates
/// aside: see the [module docs](self)). A model with a batch sampler of its own
/// ([`SampleBrdf::sample_batch`], tried first: a run-time
/// [`Material`](crate::material::Material) of one model) gives the samples of the model it
/// runs.
///
/// # Errors
///
/// [`Unavailable`] if the CPU lacks `isa`.
///
/// # Panics
///
/// If `wo`, the three `u` slices and the output slices differ in length.
#[inline]
pub fn sample_with<B, const N: usize>(
    isa: Isa,
    brdf: &B,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, N>,
) -> Result<(), Unavailable>
where
    B: BatchSample<N>,
    B::Fused: SampleBrdf<F32Fma, N>,
    B::SharedDiv: SampleBrdf<F32FmaSharedDiv, N>,
{
    let n = wo.checked_len();
    assert!(
        u.iter().all(|s| s.len() == n),
        "batch: u and wo differ in length"
    );
    assert!(
        out.x.len() == n
            && out.y.len() == n
            && out.z.len() == n
            && out.pdf.len() == n
            && out.weight.iter().all(|c| c.len() == n),
        "batch: output and input differ in length"
    );
    if !isa.is_available() {
        return Err(Unavailable(isa));
    }
    if brdf.sample_batch(isa, wo, u, out) {
        return Ok(());
    }
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    if B::EXPLICIT_LANES && isa != Isa::Portable {
        // SAFETY: `is_available` checked at run time that the CPU has these features.
        match (isa, shares_divisions()) {
            (Isa::Avx512, false) => unsafe {
                sample_kernel_avx512_lanes16(brdf.sampler16(), wo, u, out)
            },
            (Isa::Avx512, true) => unsafe {
                sample_kernel_avx512_lanes16(brdf.sampler16_shared(), wo, u, out)
            },
            (_, false) => unsafe { sample_kernel_avx2_lanes8(brdf.sampler8(), wo, u, out) },
            (_, true) => unsafe { sample_kernel_avx2_lanes8(brdf.sampler8_shared(), wo, u, out) },
        }
        return Ok(());
    }
    if isa == Isa::Portable {
        PerSample::<f32, B>(brdf, PhantomData).run(wo, u, out);
    } else if shares_divisions() {
        let shared = brdf.shared_div();
        sample_fma(
            isa,
            &PerSample::<F32FmaSharedDiv, B::SharedDiv>(&shared, PhantomData),
            wo,
            u,
            out,
        );
    } else {
        let fused = brdf.fused();
        sample_fma(
            isa,
            &PerSample::<F32Fma, B::Fused>(&fused, PhantomData),
            wo,
            u,
            out,
        );
    }
    Ok(())
}

/// Runs `l` compiled for `isa`'s FMA instruction sets (available: the caller checked).
#[inline]
fn sample_fma<L: SampleLoop<N>, const N: usize>(
    isa: Isa,
    l: &L,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, N>,
) {
    match isa {
        // SAFETY: the caller checked with `is_available` that the CPU has these features.
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        Isa::Avx2Fma => unsafe { sample_kernel_avx2(l, wo, u, out) },
        // SAFETY: as above.
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        Isa::Avx512 => unsafe { sample_kernel_avx512(l, wo, u, out) },
        _ => {
            let _ = (l, wo, u, out);
            unreachable!("only Portable is available here")
        }
    }
}

/// [`sample_with`] on the widest instruction set this CPU has ([`Isa::detect`]).
///
/// # Examples
///
/// ```
/// use brdf::batch::{Directions, SampleOut, sample};
/// use brdf::models::Lambert;
///
/// let m = Lambert::new([0.5_f32]).unwrap();
/// let (zero, one) = ([0.0f32; 64], [1.0f32; 64]);
/// let u: Vec<f32> = (0..64).map(|i| i as f32 / 64.0).collect();
/// let (mut x, mut y, mut z, mut pdf, mut w) = ([0.0; 64], [0.0; 64], [0.0; 64], [0.0; 64], [0.0; 64]);
/// let mut out = SampleOut { x: &mut x, y: &mut y, z: &mut z, pdf: &mut pdf, weight: [&mut w] };
/// sample(&m, Directions::new(&zero, &zero, &one), [&u, &u, &u], &mut out);
/// // Cosine sampling of Lambert: the weight is the albedo (`u0 = 0` draws the normal).
/// assert!(w.iter().all(|&w| (w - 0.5).abs() < 1e-6));
/// ```
///
/// # Panics
///
/// As [`sample_with`].
#[inline]
pub fn sample<B, const N: usize>(
    brdf: &B,
    wo: Directions<'_>,
    u: [&[f32]; 3],
    out: &mut SampleOut<'_, N>,
) where
    B: BatchSample<N>,
    B::Fused: SampleBrdf<F32Fma, N>,
    B::SharedDiv: SampleBrdf<F32FmaSharedDiv, N>,
{
    // The detected variant is available by construction.
    let _ = sample_with(Isa::detect(), brdf, wo, u, out);
}
