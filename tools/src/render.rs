//! A small sphere renderer on top of the crate's batch path.
//!
//! Each sphere is seen by an orthographic camera along −z (world space: x right, y up, z
//! towards the viewer). A pixel is the average of `SUPERSAMPLE²` stratified samples; each
//! sample that hits the sphere builds the local shading frame (tangent, bitangent, normal)
//! from a tangent field, expresses the light and view directions in it and evaluates the
//! BRDF through [`brdf::batch::eval`] (run-time dispatch to AVX2/AVX-512). Radiance is
//!
//! ```text
//! L(wo) = E · f(wi, wo) · cos θi  +  L_env · ρ(wo)
//! ```
//!
//! for one directional light of irradiance `E` (at normal incidence) and a constant
//! environment of radiance `L_env`, whose reflection is exactly `L_env · ρ(wo)` with
//! `ρ(wo) = ∫ f(wi, wo) cos θi dωi` the directional albedo. `ρ` comes from
//! [`brdf::analysis::directional_albedo`], tabulated per material over `θo` (and over
//! `φo` for anisotropic materials) and interpolated. Samples that miss the sphere see the
//! environment itself, so in a white-furnace scene (`E = 0`, white material) a sphere that
//! conserves energy is never brighter than its background.

use brdf::Vec3;
use brdf::analysis::{AlbedoConfig, directional_albedo};
use brdf::batch::{self, Directions};
use brdf::models::{Brdf, Properties};
use glam::Vec3 as V3;

/// Samples per pixel along each axis.
pub const SUPERSAMPLE: usize = 3;

/// The lighting of a scene.
#[derive(Clone, Copy, Debug)]
pub struct Lighting {
    /// Unit direction towards the light, world space.
    pub light_dir: V3,
    /// Irradiance of the light on a surface facing it (linear, per channel).
    pub irradiance: [f32; 3],
    /// Radiance of the constant environment (also the background).
    pub env: [f32; 3],
}

impl Lighting {
    /// The default studio: a light from the upper left, in front (`E = 3`), plus a dim
    /// environment (`L_env = 0.12`).
    pub fn studio() -> Lighting {
        Lighting {
            light_dir: V3::new(-0.5, 0.6, 0.62).normalize(),
            irradiance: [3.0; 3],
            env: [0.12; 3],
        }
    }

    /// White furnace: no light, a uniform environment of radiance 1.
    pub const FURNACE: Lighting = Lighting {
        light_dir: V3::new(0.0, 0.0, 1.0),
        irradiance: [0.0; 3],
        env: [1.0; 3],
    };
}

/// How the tangent (the local x axis, `alpha_x`, the hair fibre) runs over the sphere.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tangents {
    /// Along the meridians, from the bottom pole to the top pole (like combed hair).
    Meridians,
    /// Along the parallels, around the vertical axis (like a lathe-brushed ball).
    Parallels,
}

/// Directional albedo `ρ(θo, φo)` of one material, tabulated.
///
/// `θo` takes `THETA` nodes uniform in `[0, 89.5°]`; anisotropic materials also take
/// `PHI` nodes uniform in `φo ∈ [0, 90°]` and use the mirror symmetries `φ → −φ`,
/// `φ → π − φ` of the models (each is invariant when both directions are mirrored in the
/// x or the y axis). Bilinear interpolation in between.
pub struct AlbedoTable {
    phi_nodes: usize,
    values: Vec<[f32; 3]>,
}

const THETA: usize = 40;
const THETA_MAX: f64 = 89.5 * core::f64::consts::PI / 180.0;
const PHI: usize = 5;

/// Evaluates an `f32` BRDF from the `f64` integrator.
struct Widen<'a, B>(&'a B);

impl<B: Brdf<f32, 3>> Brdf<f64, 3> for Widen<'_, B> {
    fn eval(&self, wi: Vec3<f64>, wo: Vec3<f64>) -> [f64; 3] {
        let c = |w: Vec3<f64>| Vec3::new(w.x as f32, w.y as f32, w.z as f32);
        self.0.eval(c(wi), c(wo)).map(f64::from)
    }
    fn properties(&self) -> Properties {
        self.0.properties()
    }
}

impl AlbedoTable {
    /// Tabulates `ρ(wo)` of `brdf`; `anisotropic` adds the `φo` axis.
    pub fn new<B: Brdf<f32, 3>>(brdf: &B, anisotropic: bool) -> Self {
        let phi_nodes = if anisotropic { PHI } else { 1 };
        let cfg = AlbedoConfig::with_tolerance(1e-4);
        let mut values = Vec::with_capacity(THETA * phi_nodes);
        for t in 0..THETA {
            let theta = THETA_MAX * t as f64 / (THETA - 1) as f64;
            for p in 0..phi_nodes {
                let phi = if phi_nodes == 1 {
                    0.0
                } else {
                    core::f64::consts::FRAC_PI_2 * p as f64 / (phi_nodes - 1) as f64
                };
                let wo = Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                values.push(directional_albedo(&Widen(brdf), wo, &cfg).map(|v| v as f32));
            }
        }
        Self { phi_nodes, values }
    }

    /// `ρ(wo)` for a unit `wo` in the local frame (`wo.z > 0`).
    pub fn lookup(&self, wo: [f32; 3]) -> [f32; 3] {
        let theta = wo[2].clamp(-1.0, 1.0).acos() as f64;
        let ft = (theta / THETA_MAX * (THETA - 1) as f64).clamp(0.0, (THETA - 1) as f64);
        let t0 = (ft.floor() as usize).min(THETA - 2);
        let wt = (ft - t0 as f64) as f32;
        let (p0, wp) = if self.phi_nodes == 1 {
            (0, 0.0)
        } else {
            let phi = (wo[1].abs() as f64).atan2(wo[0].abs() as f64);
            let fp = phi / core::f64::consts::FRAC_PI_2 * (self.phi_nodes - 1) as f64;
            let p0 = (fp.floor() as usize).min(self.phi_nodes - 2);
            (p0, (fp - p0 as f64) as f32)
        };
        let at = |t: usize, p: usize| self.values[t * self.phi_nodes + p.min(self.phi_nodes - 1)];
        let p1 = if self.phi_nodes == 1 { 0 } else { p0 + 1 };
        let (a, b, c, d) = (at(t0, p0), at(t0, p1), at(t0 + 1, p0), at(t0 + 1, p1));
        core::array::from_fn(|i| {
            let lo = a[i] + (b[i] - a[i]) * wp;
            let hi = c[i] + (d[i] - c[i]) * wp;
            lo + (hi - lo) * wt
        })
    }
}

/// A rendered sphere: linear radiance per pixel, row-major, top row first.
pub struct Image {
    /// Width and height in pixels.
    pub size: usize,
    /// Linear radiance.
    pub pixels: Vec<[f32; 3]>,
}

/// The local frame `(t, b, n)` at the sphere point with normal `n`.
fn frame(n: V3, tangents: Tangents) -> (V3, V3) {
    let up = V3::Y;
    let t = match tangents {
        Tangents::Meridians => up - n * n.dot(up),
        Tangents::Parallels => up.cross(n),
    };
    // At the poles (only reached on the silhouette) any tangent will do.
    let t = if t.length_squared() > 1e-12 {
        t.normalize()
    } else {
        V3::X
    };
    (t, n.cross(t))
}

/// Renders `brdf` on a sphere of `size` pixels under `lighting`.
pub fn sphere<B: batch::BatchBrdf<3>>(
    brdf: &B,
    albedo: &AlbedoTable,
    lighting: &Lighting,
    tangents: Tangents,
    size: usize,
) -> Image {
    let ss = SUPERSAMPLE;
    // Slightly inside the pixel grid so that the silhouette is anti-aliased on all sides.
    let radius = 0.5 * size as f32 - 1.0;
    let centre = 0.5 * size as f32;
    let view = V3::Z;
    let mut owner = Vec::new();
    let (mut ix, mut iy, mut iz) = (Vec::new(), Vec::new(), Vec::new());
    let (mut ox, mut oy, mut oz) = (Vec::new(), Vec::new(), Vec::new());
    for py in 0..size {
        for px in 0..size {
            for sy in 0..ss {
                for sx in 0..ss {
                    let x = (px as f32 + (sx as f32 + 0.5) / ss as f32 - centre) / radius;
                    let y = (centre - (py as f32 + (sy as f32 + 0.5) / ss as f32)) / radius;
                    let r2 = x * x + y * y;
                    if r2 >= 1.0 {
                        continue;
                    }
                    let n = V3::new(x, y, (1.0 - r2).sqrt());
                    let (t, b) = frame(n, tangents);
                    let l = lighting.light_dir;
                    ix.push(l.dot(t));
                    iy.push(l.dot(b));
                    iz.push(l.dot(n));
                    ox.push(view.dot(t));
                    oy.push(view.dot(b));
                    oz.push(view.dot(n));
                    owner.push(py * size + px);
                }
            }
        }
    }
    let m = owner.len();
    let (mut r, mut g, mut b) = (vec![0.0f32; m], vec![0.0f32; m], vec![0.0f32; m]);
    batch::eval(
        brdf,
        Directions::new(&ix, &iy, &iz),
        Directions::new(&ox, &oy, &oz),
        [&mut r, &mut g, &mut b],
    );
    let per_pixel = (ss * ss) as f32;
    // Start every pixel as all-background, then swap in the samples that hit the sphere.
    let mut pixels = vec![lighting.env; size * size];
    for k in 0..m {
        let cos_i = iz[k].max(0.0);
        let rho = albedo.lookup([ox[k], oy[k], oz[k]]);
        let f = [r[k], g[k], b[k]];
        let p = &mut pixels[owner[k]];
        for c in 0..3 {
            let radiance = lighting.irradiance[c] * f[c] * cos_i + lighting.env[c] * rho[c];
            p[c] += (radiance - lighting.env[c]) / per_pixel;
        }
    }
    Image { size, pixels }
}

/// One labelled sphere of a grid.
pub struct Cell {
    /// Caption under the sphere.
    pub label: String,
    /// The rendered sphere.
    pub image: Image,
}

/// A row of spheres with a caption on the left.
pub struct Row {
    /// Caption (lines separated by `\n`).
    pub label: String,
    /// The spheres.
    pub cells: Vec<Cell>,
}

/// A titled grid of spheres.
pub struct Grid {
    /// First line of the header.
    pub title: String,
    /// Further header lines, separated by `\n` (parameters, lighting).
    pub subtitle: String,
    /// The rows, top first.
    pub rows: Vec<Row>,
}

const GAP: usize = 10;
const CAPTION: usize = 20;

/// Lays the grid out on a background of radiance `background`, encodes it for display and
/// draws the captions.
pub fn compose(
    grid: &Grid,
    display: &super::Display,
    background: [f32; 3],
) -> resvg::tiny_skia::Pixmap {
    let size = grid
        .rows
        .iter()
        .flat_map(|r| &r.cells)
        .map(|c| c.image.size)
        .max()
        .unwrap_or(64);
    let cols = grid.rows.iter().map(|r| r.cells.len()).max().unwrap_or(1);
    let has_row_labels = grid.rows.iter().any(|r| !r.label.is_empty());
    let left = if has_row_labels { 170 } else { GAP };
    let cell_w = size + GAP;
    let cell_h = size + CAPTION + GAP;
    let width = (left + cols * cell_w).max(520);
    // The header is wrapped to the image width (long material paths and captions would
    // otherwise run off the right edge).
    let text_w = (width - 2 * GAP) as f32;
    let title_lines = super::wrap_text(&grid.title, 16.0, true, text_w);
    let sub_lines = super::wrap_text(&grid.subtitle, 11.5, false, text_w);
    let title_h = 20 * title_lines.len();
    let header = 14 + title_h + 15 * sub_lines.len();
    let height = header + grid.rows.len() * cell_h;
    let mut pixmap = resvg::tiny_skia::Pixmap::new(width as u32, height as u32).expect("size");
    let bg = display.encode(background);
    let put = |data: &mut [u8], x: usize, y: usize, c: [u8; 3]| {
        let o = 4 * (y * width + x);
        data[o..o + 4].copy_from_slice(&[c[0], c[1], c[2], 255]);
    };
    {
        let data = pixmap.data_mut();
        for y in 0..height {
            for x in 0..width {
                put(data, x, y, bg);
            }
        }
        for (ri, row) in grid.rows.iter().enumerate() {
            for (ci, cell) in row.cells.iter().enumerate() {
                let (x0, y0) = (left + ci * cell_w, header + ri * cell_h);
                let s = cell.image.size;
                for y in 0..s {
                    for x in 0..s {
                        put(
                            data,
                            x0 + x,
                            y0 + y,
                            display.encode(cell.image.pixels[y * s + x]),
                        );
                    }
                }
            }
        }
    }
    // Captions: light text on dark backgrounds, dark text on light ones.
    let luma = 0.2126 * f32::from(bg[0]) + 0.7152 * f32::from(bg[1]) + 0.0722 * f32::from(bg[2]);
    let (ink, faint) = if luma < 128.0 {
        ("#f0f0f0", "#b8b8b8")
    } else {
        ("#101010", "#404040")
    };
    let esc = super::xml_escape;
    let mut svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="DejaVu Sans">"#
    );
    for (i, line) in title_lines.iter().enumerate() {
        svg += &format!(
            r#"<text x="{GAP}" y="{}" font-size="16" font-weight="bold" fill="{ink}">{}</text>"#,
            21 + 20 * i,
            esc(line)
        );
    }
    for (i, line) in sub_lines.iter().enumerate() {
        svg += &format!(
            r#"<text x="{GAP}" y="{}" font-size="11.5" fill="{faint}">{}</text>"#,
            20 + title_h + 15 * i,
            esc(line)
        );
    }
    for (ri, row) in grid.rows.iter().enumerate() {
        let y0 = header + ri * cell_h;
        let lines: Vec<&str> = row.label.split('\n').collect();
        let first = y0 + size / 2 + 5 - (lines.len() - 1) * 8;
        for (li, line) in lines.iter().enumerate() {
            let (w, s, c) = if li == 0 {
                ("bold", 12.5, ink)
            } else {
                ("normal", 11.0, faint)
            };
            svg += &format!(
                r#"<text x="{GAP}" y="{}" font-size="{s}" font-weight="{w}" fill="{c}">{}</text>"#,
                first + li * 16,
                esc(line)
            );
        }
        for (ci, cell) in row.cells.iter().enumerate() {
            let x = left + ci * cell_w + size / 2;
            svg += &format!(
                r#"<text x="{x}" y="{}" font-size="12" text-anchor="middle" fill="{ink}">{}</text>"#,
                y0 + size + 15,
                esc(&cell.label)
            );
        }
    }
    svg += "</svg>";
    super::overlay(&mut pixmap, &svg);
    pixmap
}
