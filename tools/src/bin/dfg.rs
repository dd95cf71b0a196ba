//! Writes the split-sum DFG lookup table (`brdf::split_sum`) as a DDS texture an engine
//! loads, and a PNG preview.
//!
//! ```sh
//! cargo run --release -p brdf-tools --bin dfg -- --size 128 --out dfg.dds --png dfg.png
//! ```
//!
//! The DDS holds `n × n` texels of `R16G16_FLOAT` (default) or `R32G32_FLOAT`, row-major, row
//! 0 (smallest roughness) first; column `i` is `n·v = (i + ½)/n`, row `j` the perceptual
//! roughness `(j + ½)/n` (header layout: `brdf_tools::dds`). The PNG shows the two channels
//! as red and green, linear values stored directly as 8-bit (no sRGB encoding), roughness
//! growing downwards, `n·v` to the right, each texel enlarged to at least 256 × 256 pixels.

use brdf::split_sum::{DfgLayout, fill_dfg_f32};
use brdf_tools::dds;
use resvg::tiny_skia;
use std::path::PathBuf;

const USAGE: &str = "\
Writes the split-sum environment-BRDF lookup table (GGX, Schlick Fresnel, height-correlated
Smith) of the brdf crate as a DDS texture and a PNG preview.

USAGE:
    cargo run --release -p brdf-tools --bin dfg [-- OPTIONS]

OPTIONS:
    --size N          texels per side, 16 to 512 (default 128; about 0.7 ms per texel)
    --format F        f16 (DXGI R16G16_FLOAT, default) or f32 (DXGI R32G32_FLOAT)
    --layout L        split-sum: (A, B), albedo F0*R + G (default);
                      multiscatter: (B, A + B), albedo mix(R, G, F0) (Filament's layout)
    --out FILE        the DDS file (default target/brdf-images/dfg.dds)
    --png FILE        the preview (default: the DDS path with .png)
    -h, --help        this text";

fn fail(msg: &str) -> ! {
    eprintln!("error: {msg}\n\n{USAGE}");
    std::process::exit(2);
}

fn main() {
    let args = brdf_tools::Args::parse(
        &["--size", "--format", "--layout", "--out", "--png"],
        &[],
        USAGE,
    );
    let n: usize = match args.value("--size").map(str::parse::<usize>) {
        None => 128,
        Some(Ok(n)) if (16..=512).contains(&n) => n,
        Some(_) => fail("--size takes a whole number from 16 to 512"),
    };
    let f16 = match args.value("--format") {
        None | Some("f16") => true,
        Some("f32") => false,
        Some(other) => fail(&format!("--format takes f16 or f32, not `{other}`")),
    };
    let layout = match args.value("--layout") {
        None | Some("split-sum") => DfgLayout::SplitSum,
        Some("multiscatter") => DfgLayout::Multiscatter,
        Some(other) => fail(&format!(
            "--layout takes split-sum or multiscatter, not `{other}`"
        )),
    };
    let out = args.value("--out").map_or_else(
        || brdf_tools::default_out_dir().join("dfg.dds"),
        PathBuf::from,
    );
    let png = args
        .value("--png")
        .map_or_else(|| out.with_extension("png"), PathBuf::from);
    // Fail on an unwritable destination before the (long) computation.
    for path in [&out, &png] {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
            && let Err(e) = brdf_tools::prepare_out_dir(dir)
        {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }

    let mut values = vec![0.0f32; 2 * n * n];
    fill_dfg_f32(n, layout, &mut values).unwrap_or_else(|e| fail(&e.to_string()));
    let (format, bytes): (u32, Vec<u8>) = if f16 {
        // What `fill_dfg_f16` computes (each f32 texel rounded to the nearest f16), without
        // integrating the table a second time.
        let h = values.iter().map(|&x| half::f16::from_f32(x));
        (
            dds::DXGI_R16G16_FLOAT,
            h.flat_map(half::f16::to_le_bytes).collect(),
        )
    } else {
        (
            dds::DXGI_R32G32_FLOAT,
            values.iter().flat_map(|x| x.to_le_bytes()).collect(),
        )
    };
    let mut file = dds::header(n as u32, n as u32, format);
    file.extend(bytes);
    if let Err(e) = std::fs::write(&out, &file) {
        eprintln!("error: cannot write {}: {e}", out.display());
        std::process::exit(1);
    }

    let scale = 256_usize.div_ceil(n).max(1);
    let side = (n * scale) as u32;
    let mut pixmap = tiny_skia::Pixmap::new(side, side).expect("non-empty preview");
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    for (p, px) in pixmap.pixels_mut().iter_mut().enumerate() {
        let (x, y) = (p % side as usize / scale, p / side as usize / scale);
        let k = 2 * (y * n + x);
        *px = tiny_skia::PremultipliedColorU8::from_rgba(
            byte(values[k]),
            byte(values[k + 1]),
            0,
            255,
        )
        .expect("opaque");
    }
    if let Err(e) = brdf_tools::save_png(&pixmap, &png) {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
    println!(
        "wrote {} ({n} × {n}, {}) and {}",
        out.display(),
        if f16 { "R16G16_FLOAT" } else { "R32G32_FLOAT" },
        png.display()
    );
}
