//! The seed talk's tables, reproduced by the crate.
//!
//! ```sh
//! cargo run --release -p brdf-tools --bin tables
//! ```
//!
//! Prints, as Markdown tables: every preset's normal-incidence reflectance F0 (with the
//! talk's printed value where it gives one), the measured RGB metals, reflectance against
//! incidence angle (exact Fresnel and Schlick) for a few materials, and the Blinn-Phong
//! normalization factor exact and fitted, with the fit's error.

use brdf::{fresnel, ior, normalization};

const USAGE: &str = "\
Prints the tables of the seed talk (\"Basic of Reflectance\", tri-Ace 2009), recomputed by
the brdf crate, as Markdown on standard output: the materials' normal-incidence
reflectance, the measured RGB metals, reflectance against incidence angle (exact Fresnel
and Schlick) and the Blinn-Phong normalization factor, exact and fitted.

USAGE:
    cargo run --release -p brdf-tools --bin tables [-- OPTIONS]

OPTIONS:
    -h, --help        this text";

/// The normal-incidence reflectances printed in the talk's IOR table.
const SEED_F0: &[(&str, f64)] = &[
    ("iron", 0.164),
    ("gold", 0.887),
    ("quartz", 0.034),
    ("sapphire", 0.076),
    ("carbon", 0.2),
];

fn main() {
    // No options besides --help: anything else is an error (exit status 2).
    let _ = brdf_tools::Args::parse(&[], &[], USAGE);
    println!("# brdf: the tables of \"Basic of Reflectance\" (tri-Ace, 2009)\n");

    println!("## Normal-incidence reflectance of the talk's materials\n");
    println!("F0 = ((η − 1)² + κ²) / ((η + 1)² + κ²)\n");
    println!("| material | η | κ | F0 (brdf) | F0 (talk) |");
    println!("|---|---:|---:|---:|---:|");
    for p in ior::SEED_TABLE {
        let talk = SEED_F0
            .iter()
            .find(|(n, _)| *n == p.preset.label())
            .map_or("—".to_string(), |(_, v)| format!("{v:.3}"));
        println!(
            "| {} | {:.2} | {:.2} | {:.3} | {} |",
            p.preset.label(),
            p.eta,
            p.k,
            fresnel::f0_from_complex_ior(p.eta, p.k),
            talk
        );
    }

    println!("\n## Measured metals, one wavelength per channel\n");
    println!("| metal | λ (nm) | η (R, G, B) | κ (R, G, B) | F0 (R, G, B) | source |");
    println!("|---|---|---|---|---|---|");
    for p in ior::Preset::METALS {
        let (m, f0) = (p.data(), fresnel::f0_from_preset(p));
        let nm = m.wavelengths_nm.expect("metals are measured");
        println!(
            "| {} | {:.0}/{:.0}/{:.0} | {:.3}, {:.3}, {:.3} | {:.3}, {:.3}, {:.3} | {:.3}, {:.3}, {:.3} | {} |",
            p.label(),
            nm[0],
            nm[1],
            nm[2],
            m.eta[0],
            m.eta[1],
            m.eta[2],
            m.k[0],
            m.k[1],
            m.k[2],
            f0[0],
            f0[1],
            f0[2],
            m.source
        );
    }

    println!("\n## Reflectance against incidence angle (exact Fresnel / Schlick)\n");
    let angles = [0.0f64, 15.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 89.0];
    let materials = [
        ior::Preset::Quartz,
        ior::Preset::Water,
        ior::Preset::Sapphire,
        ior::Preset::TitaniumDioxide,
        ior::Preset::Gold,
        ior::Preset::Iron,
    ]
    .map(|p| p.seed().expect("in the seed table"));
    print!("| material |");
    for a in angles {
        print!(" {a:.0}° |");
    }
    println!("\n|---|{}", "---:|".repeat(angles.len()));
    for p in materials {
        print!("| {} |", p.preset.label());
        for a in angles {
            let c = a.to_radians().cos();
            let exact = fresnel::conductor(c, p.eta, p.k);
            let schlick = fresnel::schlick(fresnel::f0_from_complex_ior(p.eta, p.k), c);
            print!(" {exact:.3} / {schlick:.3} |");
        }
        println!();
    }

    println!("\n## Blinn-Phong normalization: exact against the (s + 2.04)/(8π) fit\n");
    println!(
        "exact = (s + 2) / (4π (2 − 2^(−s/2))), the reciprocal of ∫ (N·H)^s dω at normal incidence\n"
    );
    println!("| s | exact | fit (s + 2.04)/(8π) | relative error |");
    println!("|---:|---:|---:|---:|");
    for s in [
        0.0f64, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 1024.0, 1e4, 1e6,
    ] {
        let exact = normalization::tri_ace_exact(s);
        let fit = normalization::tri_ace_fit(s, normalization::TRI_ACE_OFFSET);
        println!(
            "| {s} | {exact:.6} | {fit:.6} | {:+.3}% |",
            100.0 * (fit / exact - 1.0)
        );
    }
    for (lo, hi) in [(1.0, 1e4), (8.0, 1e4), (16.0, 1e4), (0.0, 1e6)] {
        let e = normalization::fit::fit_error(normalization::TRI_ACE_OFFSET, lo, hi)
            .expect("valid shininess range");
        let best = normalization::fit::best_fit_offset(lo, hi).expect("valid shininess range");
        println!(
            "\ns ∈ [{lo}, {hi}]: offset 2.04 has max |relative error| {:.3}% (at s = {:.2}); \
             the minimax offset is {:.4} with {:.3}%.",
            100.0 * e.max_rel_error,
            e.at_shininess,
            best.offset,
            100.0 * best.max_rel_error
        );
    }
}
