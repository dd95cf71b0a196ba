//! Deterministic direction sets on the upper hemisphere, built by warping uniform samples.

use crate::math::f64m;
use crate::{Real, Vec3};
use core::f64::consts::PI;

/// Warps `(u1, u2) ∈ [0, 1]²` to the upper hemisphere, uniformly in solid angle.
///
/// ```text
/// cos θ = u1,  φ = 2π u2,  w = (sin θ cos φ, sin θ sin φ, cos θ),  pdf = 1/(2π)
/// ```
///
/// `u1 = 0` gives a horizon direction, `u1 = 1` the normal. Reference: M. Pharr, W. Jakob,
/// G. Humphreys, *Physically Based Rendering*, 4th ed., 2023, §A.5.2 (`SampleUniformHemisphere`).
///
/// # Examples
///
/// ```
/// use brdf::analysis::uniform_hemisphere;
/// let w = uniform_hemisphere(1e-4f64, 0.25);
/// assert!((w.z - 1e-4).abs() < 1e-18 && (w.length() - 1.0).abs() < 1e-15);
/// ```
#[inline]
#[must_use]
pub fn uniform_hemisphere<R: Real>(u1: R, u2: R) -> Vec3<R> {
    let z = u1;
    let r = ((R::one() - z) * (R::one() + z)).safe_sqrt();
    let phi = R::from_f64(2.0 * PI) * u2;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Fractional part of the golden ratio: successive multiples are maximally spread in `[0, 1)`.
const GOLDEN_FRACTION: f64 = 0.618_033_988_749_894_8;

/// A deterministic grid of directions on the upper hemisphere that includes the normal and
/// grazing directions: `rings` polar rings, uniform in `θ` from `0` to
/// `θmax = acos(min_cos_theta)` (the first ring is the single normal direction, the last one
/// has `cos θ = min_cos_theta` exactly), each with `per_ring` azimuths.
///
/// ```text
/// θₖ = θmax · k / (rings − 1),   φₖⱼ = 2π (j + frac(k · 0.618…)) / per_ring
/// ```
///
/// The golden-ratio offset between rings spreads the relative azimuths `φ − φ'` of pairs, so
/// [`DirectionGrid::pairs`] probes in-plane, out-of-plane and opposite configurations.
/// Number of directions: `1 + (rings − 1) · per_ring` (0 when `rings = 0`).
///
/// # Examples
///
/// ```
/// use brdf::analysis::DirectionGrid;
/// let grid = DirectionGrid::new(5, 6, 1e-4);
/// assert_eq!(grid.len(), 1 + 4 * 6);
/// let zs: Vec<f64> = grid.iter().map(|w| w.z).collect();
/// assert_eq!(zs[0], 1.0);
/// assert_eq!(*zs.last().unwrap(), 1e-4);
/// assert_eq!(grid.pairs().count(), 25 * 24 / 2);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionGrid {
    /// Number of polar rings, including the normal direction (ring 0).
    pub rings: usize,
    /// Azimuths per ring (ring 0 has one direction); treated as at least 1.
    pub per_ring: usize,
    /// `cos θ` of the last ring, clamped to `[0, 1]` (default `1e-4`).
    pub min_cos_theta: f64,
}

impl DirectionGrid {
    /// 8 rings × 8 azimuths down to `cos θ = 1e-4`: 57 directions, 1596 pairs.
    pub const DEFAULT: Self = Self {
        rings: 8,
        per_ring: 8,
        min_cos_theta: 1e-4,
    };

    /// A grid of `rings` rings × `per_ring` azimuths down to `cos θ = min_cos_theta`.
    #[must_use]
    pub const fn new(rings: usize, per_ring: usize, min_cos_theta: f64) -> Self {
        Self {
            rings,
            per_ring,
            min_cos_theta,
        }
    }

    fn per(&self) -> usize {
        self.per_ring.max(1)
    }

    /// Number of directions.
    #[must_use]
    pub fn len(&self) -> usize {
        if self.rings == 0 {
            0
        } else {
            1 + (self.rings - 1) * self.per()
        }
    }

    /// Whether the grid has no direction (`rings = 0`).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.rings == 0
    }

    /// Direction number `index` (`< len()`), ring by ring from the normal outwards.
    ///
    /// # Panics
    ///
    /// If `index ≥ len()`.
    #[must_use]
    pub fn direction(&self, index: usize) -> Vec3<f64> {
        assert!(
            index < self.len(),
            "direction index {index} out of range {}",
            self.len()
        );
        if index == 0 {
            return Vec3::new(0.0, 0.0, 1.0);
        }
        let k = 1 + (index - 1) / self.per();
        let j = (index - 1) % self.per();
        let c_min = self.min_cos_theta.clamp(0.0, 1.0);
        let z = if k == self.rings - 1 {
            c_min
        } else {
            let theta_max = super::angle(f64m::sqrt((1.0 - c_min) * (1.0 + c_min)), c_min);
            f64m::cos(theta_max * k as f64 / (self.rings - 1) as f64)
        };
        let offset = (k as f64 * GOLDEN_FRACTION) % 1.0;
        let phi = 2.0 * PI * (j as f64 + offset) / self.per() as f64;
        let r = f64m::sqrt((1.0 - z) * (1.0 + z));
        Vec3::new(r * f64m::cos(phi), r * f64m::sin(phi), z)
    }

    /// All directions, in index order.
    #[must_use]
    pub fn iter(&self) -> GridDirections {
        GridDirections {
            grid: *self,
            next: 0,
        }
    }

    /// All unordered pairs `(wi, wo)` of distinct grid directions (`len·(len − 1)/2` pairs),
    /// e.g. for [`reciprocity_check`](super::reciprocity_check).
    #[must_use]
    pub fn pairs(&self) -> GridPairs {
        GridPairs {
            grid: *self,
            i: 0,
            j: 1,
        }
    }
}

impl Default for DirectionGrid {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl IntoIterator for DirectionGrid {
    type Item = Vec3<f64>;
    type IntoIter = GridDirections;
    fn into_iter(self) -> GridDirections {
        self.iter()
    }
}

/// Iterator over the directions of a [`DirectionGrid`].
#[derive(Clone, Debug)]
pub struct GridDirections {
    grid: DirectionGrid,
    next: usize,
}

impl Iterator for GridDirections {
    type Item = Vec3<f64>;
    fn next(&mut self) -> Option<Vec3<f64>> {
        (self.next < self.grid.len()).then(|| {
            self.next += 1;
            self.grid.direction(self.next - 1)
        })
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.grid.len().saturating_sub(self.next);
        (n, Some(n))
    }
}

impl ExactSizeIterator for GridDirections {}

/// Iterator over the unordered pairs of distinct directions of a [`DirectionGrid`].
#[derive(Clone, Debug)]
pub struct GridPairs {
    grid: DirectionGrid,
    i: usize,
    j: usize,
}

impl Iterator for GridPairs {
    type Item = (Vec3<f64>, Vec3<f64>);
    fn next(&mut self) -> Option<Self::Item> {
        let n = self.grid.len();
        if self.j >= n {
            return None;
        }
        let out = (self.grid.direction(self.i), self.grid.direction(self.j));
        self.j += 1;
        if self.j >= n {
            self.i += 1;
            self.j = self.i + 1;
        }
        Some(out)
    }
}

/// `n` directions of a spherical Fibonacci lattice on the upper hemisphere: equal-area
/// (uniform in solid angle) and low-discrepancy.
///
/// ```text
/// cos θᵢ = 1 − (i + ½)/n,   φᵢ = 2π frac(i · 0.618…),   i = 0 … n − 1
/// ```
///
/// Reference: R. Marques, C. Bouville, M. Ribeiro, L. P. Santos, K. Bouatouch, "Spherical
/// Fibonacci Point Sets for Illumination Integrals", Computer Graphics Forum 32(8), 2013.
///
/// # Examples
///
/// ```
/// use brdf::analysis::fibonacci_hemisphere;
/// let mean_z = fibonacci_hemisphere(1000).map(|w| w.z).sum::<f64>() / 1000.0;
/// assert!((mean_z - 0.5).abs() < 1e-9); // E[cos θ] = 1/2 under the uniform measure
/// ```
#[must_use]
pub fn fibonacci_hemisphere(n: usize) -> FibonacciHemisphere {
    FibonacciHemisphere { n, next: 0 }
}

/// Iterator returned by [`fibonacci_hemisphere`].
#[derive(Clone, Debug)]
pub struct FibonacciHemisphere {
    n: usize,
    next: usize,
}

impl Iterator for FibonacciHemisphere {
    type Item = Vec3<f64>;
    fn next(&mut self) -> Option<Vec3<f64>> {
        if self.next >= self.n {
            return None;
        }
        let i = self.next as f64;
        self.next += 1;
        let u1 = 1.0 - (i + 0.5) / self.n as f64;
        let u2 = (i * GOLDEN_FRACTION) % 1.0;
        Some(uniform_hemisphere(u1, u2))
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.n - self.next;
        (n, Some(n))
    }
}

impl ExactSizeIterator for FibonacciHemisphere {}
