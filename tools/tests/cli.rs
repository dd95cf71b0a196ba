//! The programs' command lines, run as a user runs them: usage and rejected arguments, an
//! unwritable output folder reported before any work, distinct images for material files
//! with the same name, `--only` together with `--material`, and header text wrapped to the
//! image width.
//!
//! Run with `cargo test --release -p brdf-tools --features serde` (release: the renderer is
//! slow in debug builds).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn run(exe: &str, args: &[&str]) -> Output {
    Command::new(exe)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {exe}: {e}"))
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// A fresh scratch folder under the target directory.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn tables_and_tradeoffs_take_help_and_reject_unknown_arguments() {
    for exe in [
        env!("CARGO_BIN_EXE_tables"),
        env!("CARGO_BIN_EXE_tradeoffs"),
    ] {
        let help = run(exe, &["--help"]);
        assert_eq!(help.status.code(), Some(0), "{exe} --help");
        assert!(
            text(&help.stdout).contains("USAGE:"),
            "{exe} --help prints usage"
        );
        for bad in ["--bogus", "-x", "extra"] {
            let out = run(exe, &[bad]);
            assert_eq!(out.status.code(), Some(2), "{exe} {bad}");
            let err = text(&out.stderr);
            assert!(
                err.contains(&format!("unexpected argument `{bad}`")),
                "{err}"
            );
            assert!(err.contains("USAGE:"), "{err}");
            assert!(out.stdout.is_empty(), "{exe} {bad} printed a report");
        }
    }
}

#[test]
fn an_unwritable_out_folder_is_an_error_before_rendering() {
    let dir = scratch("unwritable");
    // A folder inside a regular file cannot be created.
    let file = dir.join("a-file");
    std::fs::write(&file, b"").unwrap();
    let out_dir = file.join("images");
    for exe in [env!("CARGO_BIN_EXE_spheres"), env!("CARGO_BIN_EXE_plots")] {
        let out = run(exe, &["--out", out_dir.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(1), "{exe}: {}", text(&out.stderr));
        let err = text(&out.stderr);
        assert!(err.contains("error: cannot create"), "{err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(
            !err.contains("rendering spheres"),
            "{exe} rendered first: {err}"
        );
        assert!(out.stdout.is_empty());
    }
}

#[cfg(feature = "serde")]
#[test]
fn same_stem_materials_get_distinct_images_and_only_adds_grids() {
    let dir = scratch("same-stem");
    let material = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/materials/gold.toml");
    let (a, b) = (dir.join("a"), dir.join("b"));
    for d in [&a, &b] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::copy(material, d.join("gold.toml")).unwrap();
    }
    let out_dir = dir.join("out");
    let out = run(
        env!("CARGO_BIN_EXE_spheres"),
        &[
            "--out",
            out_dir.to_str().unwrap(),
            "--size",
            "16",
            "--only",
            "furnace",
            "--material",
            a.join("gold.toml").to_str().unwrap(),
            "--material",
            b.join("gold.toml").to_str().unwrap(),
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let mut written: Vec<String> = stdout
        .lines()
        .filter_map(|l| l.strip_prefix("wrote "))
        .map(|p| {
            Path::new(p)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    written.sort();
    assert_eq!(
        written,
        ["furnace.png", "material-gold-2.png", "material-gold.png"],
        "{stdout}"
    );
    for name in &written {
        assert!(out_dir.join(name).is_file(), "{name} reported but missing");
    }
}

#[test]
fn header_text_wraps_to_the_width() {
    let long = "Left: studio light + environment; right: the same material in a uniform \
                environment of radiance 1 (no light).\nLight: directional E = 3 from the \
                upper left + constant environment L = 0.12 (the background); exposure 1.";
    let width = 500.0;
    assert!(brdf_tools::text_width(long.lines().next().unwrap(), 11.5, false) > width);
    let lines = brdf_tools::wrap_text(long, 11.5, false, width);
    assert!(lines.len() >= 4, "{lines:?}");
    for l in &lines {
        assert!(brdf_tools::text_width(l, 11.5, false) <= width, "{l}");
    }
    // Every word is kept, in order, and the explicit line break is kept.
    let words = |s: &str| s.split_whitespace().map(str::to_owned).collect::<Vec<_>>();
    assert_eq!(words(&lines.join(" ")), words(long));
    assert!(lines.iter().any(|l| l.starts_with("Light:")));
    // Text that fits is left alone; a word wider than the width stays whole.
    assert_eq!(
        brdf_tools::wrap_text("short", 11.5, false, width),
        ["short"]
    );
    assert_eq!(
        brdf_tools::wrap_text("unbreakable", 11.5, false, 5.0),
        ["unbreakable"]
    );
}

#[test]
fn dfg_rejects_bad_sizes_formats_and_layouts() {
    let exe = env!("CARGO_BIN_EXE_dfg");
    let help = run(exe, &["--help"]);
    assert_eq!(help.status.code(), Some(0));
    assert!(text(&help.stdout).contains("USAGE:"));
    for bad in [
        &["--size", "8"][..],
        &["--size", "513"],
        &["--size", "x"],
        &["--format", "f64"],
        &["--layout", "both"],
        &["--bogus"],
    ] {
        let out = run(exe, bad);
        assert_eq!(out.status.code(), Some(2), "{bad:?}");
        assert!(text(&out.stderr).contains("USAGE:"), "{bad:?}");
    }
    // An output folder inside a regular file: an error before computing.
    let dir = scratch("dfg-unwritable");
    let file = dir.join("file");
    std::fs::write(&file, b"x").unwrap();
    let out = run(
        exe,
        &[
            "--size",
            "16",
            "--out",
            file.join("t.dds").to_str().unwrap(),
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).contains("cannot create"),
        "{}",
        text(&out.stderr)
    );
}

/// The DDS files parse back (every header field of `brdf_tools::dds`) to the texels the
/// library computes, for both formats and layouts; the PNG preview is a PNG.
#[test]
fn dfg_writes_dds_that_parse_back_to_the_library_table() {
    use brdf::split_sum::{DfgLayout, fill_dfg_f16, fill_dfg_f32};
    use brdf_tools::dds;
    let dir = scratch("dfg");
    let n = 16;
    for (format, layout, name) in [
        ("f16", DfgLayout::SplitSum, "split-sum"),
        ("f32", DfgLayout::SplitSum, "split-sum"),
        ("f32", DfgLayout::Multiscatter, "multiscatter"),
    ] {
        let dds_path = dir.join(format!("{format}-{name}.dds"));
        let png_path = dir.join(format!("{format}-{name}.png"));
        let out = run(
            env!("CARGO_BIN_EXE_dfg"),
            &[
                "--size",
                "16",
                "--format",
                format,
                "--layout",
                name,
                "--out",
                dds_path.to_str().unwrap(),
                "--png",
                png_path.to_str().unwrap(),
            ],
        );
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        let tex = dds::parse(&std::fs::read(&dds_path).unwrap()).unwrap();
        assert_eq!((tex.width, tex.height), (16, 16));
        let mut want32 = vec![0.0f32; 2 * n * n];
        fill_dfg_f32(n, layout, &mut want32).unwrap();
        if format == "f16" {
            assert_eq!(tex.dxgi_format, dds::DXGI_R16G16_FLOAT);
            let mut want = vec![half::f16::ZERO; 2 * n * n];
            fill_dfg_f16(n, layout, &mut want).unwrap();
            let got: Vec<half::f16> = tex
                .data
                .chunks(2)
                .map(|b| half::f16::from_le_bytes([b[0], b[1]]))
                .collect();
            assert_eq!(got, want);
        } else {
            assert_eq!(tex.dxgi_format, dds::DXGI_R32G32_FLOAT);
            let got: Vec<f32> = tex
                .data
                .chunks(4)
                .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                .collect();
            assert_eq!(got, want32);
        }
        let png = std::fs::read(&png_path).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    }
    // A damaged header is reported by field.
    let mut bytes = std::fs::read(dir.join("f32-split-sum.dds")).unwrap();
    bytes[84] = b'X';
    assert!(dds::parse(&bytes).unwrap_err().contains("dwFourCC"));
    assert!(dds::parse(&bytes[..100]).is_err());
}
