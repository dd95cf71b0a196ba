//! Code shared by the programs of `brdf-tools` (`src/bin/`): display encoding (tone
//! mapping, sRGB), SVG rasterization with an embedded font, PNG output, command-line
//! parsing, and the sphere renderer ([`render`]).
//!
//! The programs live in this workspace member rather than in `brdf`'s `examples/` so that
//! `brdf`'s test build does not compile their dependencies (plotters, resvg, the DejaVu
//! font). Run them from the repository root, for example
//! `cargo run --release -p brdf-tools --bin spheres`.

use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use resvg::{tiny_skia, usvg};

pub mod dds;
pub mod render;
pub mod sampling_stats;

// ---------------------------------------------------------------------------------------------
// Display encoding
// ---------------------------------------------------------------------------------------------

/// The ACES filmic curve as fitted by K. Narkowicz ("ACES Filmic Tone Mapping Curve", blog,
/// 2016), applied per channel to linear radiance already multiplied by the exposure:
///
/// ```text
/// t(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14),  clamped to [0, 1]
/// ```
///
/// `t(0) = 0`, `t` is monotonic on `[0, ∞)` and reaches 1 at `x ≈ 7.24`.
#[must_use]
pub fn aces_fitted(x: f32) -> f32 {
    let x = x.max(0.0);
    (x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// The exact piecewise sRGB opto-electronic transfer function (IEC 61966-2-1:1999):
///
/// ```text
/// V = 12.92 L                     L ≤ 0.003 130 8
/// V = 1.055 L^(1/2.4) − 0.055     otherwise
/// ```
#[must_use]
pub fn srgb_oetf(l: f32) -> f32 {
    let l = l.clamp(0.0, 1.0);
    if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// How linear radiance becomes an 8-bit sRGB pixel: `exposure`, then [`aces_fitted`] per
/// channel, then [`srgb_oetf`], then rounding to 8 bits.
#[derive(Clone, Copy, Debug)]
pub struct Display {
    /// Multiplier applied to linear radiance before the tone curve.
    pub exposure: f32,
}

impl Display {
    /// The 8-bit sRGB code of linear radiance `rgb`.
    #[must_use]
    pub fn encode(&self, rgb: [f32; 3]) -> [u8; 3] {
        rgb.map(|c| {
            let v = srgb_oetf(aces_fitted(c * self.exposure));
            (v * 255.0 + 0.5).clamp(0.0, 255.0) as u8
        })
    }

    /// The same, as a CSS colour for SVG labels.
    #[must_use]
    pub fn css(&self, rgb: [f32; 3]) -> String {
        let [r, g, b] = self.encode(rgb);
        format!("#{r:02x}{g:02x}{b:02x}")
    }
}

// ---------------------------------------------------------------------------------------------
// SVG rasterization with an embedded font
// ---------------------------------------------------------------------------------------------

/// A font database holding DejaVu Sans (regular and bold, embedded by the `dejavu` crate),
/// registered as the generic `sans-serif`, `serif` and `monospace` families: the programs
/// need no system fonts and no fontconfig.
pub fn fonts() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(dejavu::sans::regular().to_vec());
        db.load_font_data(dejavu::sans::bold().to_vec());
        db.load_font_data(dejavu::sans::oblique().to_vec());
        db.set_sans_serif_family("DejaVu Sans");
        db.set_serif_family("DejaVu Sans");
        db.set_monospace_family("DejaVu Sans");
        Arc::new(db)
    })
    .clone()
}

/// Parses an SVG document with the embedded fonts.
///
/// # Panics
/// If the SVG does not parse (a bug in the program that wrote it).
#[must_use]
pub fn parse_svg(svg: &str) -> usvg::Tree {
    let opt = usvg::Options {
        font_family: "DejaVu Sans".to_owned(),
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    usvg::Tree::from_str(svg, &opt).unwrap_or_else(|e| panic!("invalid SVG: {e}"))
}

/// Rasterizes an SVG document at `scale` (1 = its own pixel size) on a white background.
#[must_use]
pub fn rasterize(svg: &str, scale: f32) -> tiny_skia::Pixmap {
    let tree = parse_svg(svg);
    let size = tree.size();
    let w = (size.width() * scale).ceil() as u32;
    let h = (size.height() * scale).ceil() as u32;
    let mut pixmap = tiny_skia::Pixmap::new(w, h).expect("non-empty plot");
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    pixmap
}

/// Draws an SVG document (e.g. text labels on a transparent background) over `pixmap`.
pub fn overlay(pixmap: &mut tiny_skia::Pixmap, svg: &str) {
    let tree = parse_svg(svg);
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
}

/// Escapes text for an SVG `<text>` element.
#[must_use]
pub fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The width in pixels of `text` set in DejaVu Sans at `font_size` px (`bold` or regular),
/// measured by laying it out with the embedded font.
#[must_use]
pub fn text_width(text: &str, font_size: f32, bold: bool) -> f32 {
    if text.trim().is_empty() {
        return 0.0;
    }
    let weight = if bold { "bold" } else { "normal" };
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><text x="0" y="50" font-family="DejaVu Sans" font-size="{font_size}" font-weight="{weight}">{}</text></svg>"#,
        xml_escape(text)
    );
    parse_svg(&svg).root().bounding_box().width()
}

/// Breaks `text` at spaces into lines no wider than `max_width` px ([`text_width`]); a
/// single word wider than that stays on its own line. Existing line breaks are kept.
#[must_use]
pub fn wrap_text(text: &str, font_size: f32, bold: bool, max_width: f32) -> Vec<String> {
    let mut lines = Vec::new();
    for paragraph in text.split('\n') {
        let mut line = String::new();
        for word in paragraph.split(' ').filter(|w| !w.is_empty()) {
            let candidate = if line.is_empty() {
                word.to_owned()
            } else {
                format!("{line} {word}")
            };
            if line.is_empty() || text_width(&candidate, font_size, bold) <= max_width {
                line = candidate;
            } else {
                lines.push(std::mem::replace(&mut line, word.to_owned()));
            }
        }
        lines.push(line);
    }
    lines
}

/// Writes `pixmap` as PNG to `path`, creating the parent folder, and returns the path; the
/// error names the path and the reason.
///
/// # Errors
/// If the folder cannot be created or the file cannot be written.
pub fn save_png(pixmap: &tiny_skia::Pixmap, path: &Path) -> Result<PathBuf, String> {
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent)
            .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
    }
    pixmap
        .save_png(path)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(path.to_path_buf())
}

/// Creates the output folder `dir` (and its parents) and checks that a file can be written
/// in it, so that a program fails before its work rather than after.
///
/// # Errors
/// If the folder cannot be created or is not writable (the message names it).
pub fn prepare_out_dir(dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let probe = dir.join(format!(".brdf-tools-write-test-{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(|e| format!("cannot write in {}: {e}", dir.display()))?;
    // Removing the probe can only fail if someone else removed it first.
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Command line
// ---------------------------------------------------------------------------------------------

/// The default output folder: `target/brdf-images/` of the workspace (the repository root,
/// one level above this package; `CARGO_TARGET_DIR` is honoured).
#[must_use]
pub fn default_out_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            // This package is tools/ inside the workspace, whose target/ is at the root.
            let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent();
            root.unwrap_or(Path::new(".")).join("target")
        });
    target.join("brdf-images")
}

/// Parsed `--flag value` pairs and bare flags.
#[derive(Debug, Default)]
pub struct Args {
    /// `--name value` pairs in order.
    pub values: Vec<(String, String)>,
    /// Bare `--name` flags.
    pub flags: Vec<String>,
}

impl Args {
    /// Parses the process arguments. `value_flags` take a value; `bool_flags` do not.
    /// Unknown arguments print `usage` and exit with status 2.
    pub fn parse(value_flags: &[&str], bool_flags: &[&str], usage: &str) -> Self {
        let mut args = Args::default();
        let mut it = std::env::args().skip(1);
        while let Some(a) = it.next() {
            if a == "-h" || a == "--help" {
                println!("{usage}");
                std::process::exit(0);
            } else if value_flags.contains(&a.as_str()) {
                match it.next() {
                    Some(v) => args.values.push((a, v)),
                    None => {
                        eprintln!("error: {a} needs a value\n\n{usage}");
                        std::process::exit(2);
                    }
                }
            } else if bool_flags.contains(&a.as_str()) {
                args.flags.push(a);
            } else {
                eprintln!("error: unexpected argument `{a}`\n\n{usage}");
                std::process::exit(2);
            }
        }
        args
    }

    /// The last value of `--name`.
    #[must_use]
    pub fn value(&self, name: &str) -> Option<&str> {
        self.values
            .iter()
            .rev()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// Every value of `--name`, in order.
    #[must_use]
    pub fn all(&self, name: &str) -> Vec<&str> {
        self.values
            .iter()
            .filter(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
            .collect()
    }

    /// Whether `--name` was given.
    #[must_use]
    pub fn flag(&self, name: &str) -> bool {
        self.flags.iter().any(|f| f == name)
    }
}
