//! Tests of the IOR presets: the seed talk's normal-incidence reflectance table, the
//! measured RGB metals against commonly quoted linear F0 values, preset sanity, names and
//! the preset constructors of `fresnel`.
mod common;

use approx::{assert_abs_diff_eq, assert_relative_eq};
use brdf::fresnel::{
    Conductor, Dielectric, F82Tint, FresnelTerm, Schlick, conductor, dielectric,
    f0_from_complex_ior, f0_from_preset,
};
use brdf::ior::{Preset, SEED_TABLE, SeedEntry};

fn seed(p: Preset) -> SeedEntry {
    p.seed().unwrap()
}

/// The seed's table "屈折率 / 垂直反射率": each printed value must equal F0 rounded to the
/// printed number of decimals (|F0 − printed| ≤ half a unit in the last printed digit).
#[test]
fn seed_normal_incidence_table() {
    let printed = [
        (seed(Preset::Iron), 0.164, 3u32),
        (seed(Preset::Gold), 0.887, 3),
        (seed(Preset::Quartz), 0.034, 3),
        (seed(Preset::Sapphire), 0.076, 3),
        (seed(Preset::Carbon), 0.2, 1),
    ];
    for (p, value, decimals) in printed {
        let f0 = f0_from_complex_ior(p.eta, p.k);
        let half_unit = 0.5 * 10f64.powi(-(decimals as i32));
        assert!(
            (f0 - value).abs() <= half_unit,
            "{}: F0 = {f0:.5}, seed prints {value}",
            p.preset
        );
        // Same through the exact Fresnel at normal incidence, and through the dielectric
        // presets (which take the seed's value).
        assert_abs_diff_eq!(conductor(1.0, p.eta, p.k), f0, epsilon = 1e-15);
        if p.k == 0.0 {
            assert_abs_diff_eq!(dielectric(1.0, p.eta), f0, epsilon = 1e-15);
        }
        if !p.preset.is_conductor() {
            assert_eq!(f0_from_preset(p.preset), [f0; 3]);
        }
    }
    // Carbon is exactly 0.2: ((2 − 1)² + 1²)/((2 + 1)² + 1²) = 2/10.
    assert_eq!(f0_from_complex_ior(2.0, 1.0), 0.2);
}

#[test]
fn seed_table_is_complete_and_conjugated() {
    let names: Vec<_> = SEED_TABLE.iter().map(|p| p.preset.name()).collect();
    assert_eq!(
        names,
        [
            "iron",
            "iron_oxide",
            "gold",
            "silver",
            "copper",
            "quartz",
            "sapphire",
            "water",
            "titanium_dioxide",
            "ivory",
            "carbon"
        ]
    );
    // The seed writes n − iκ; the presets store k = κ ≥ 0, and the sign does not change F0.
    for p in SEED_TABLE {
        assert!(p.eta > 0.0 && p.k >= 0.0, "{}", p.preset);
        assert_eq!(
            f0_from_complex_ior(p.eta, p.k),
            f0_from_complex_ior(p.eta, -p.k)
        );
        assert!(Conductor::new([p.eta], [p.k]).is_ok());
        assert_eq!(p.preset.seed(), Some(p));
    }
    let metals = SEED_TABLE.iter().filter(|p| p.k > 0.0).count();
    assert_eq!(metals, 4); // gold, silver, copper, carbon
}

/// The seed's iron (2.36, real) is a dielectric; measured iron is a conductor with a much
/// higher F0. The module docs say so; this test keeps the statement true.
#[test]
fn seed_iron_is_not_measured_iron() {
    let e = seed(Preset::Iron);
    let seed = f0_from_complex_ior(e.eta, e.k);
    let measured = f0_from_preset(Preset::Iron);
    assert!(seed < 0.17);
    assert!(measured.iter().all(|&f| f > 0.49), "{measured:?}");
}

/// Linear F0 values quoted for metals (Real-Time Rendering 4th ed., Table 9.2, after
/// N. Hoffman): the single-wavelength presets must land near them. The bound is the largest
/// measured difference (titanium blue, 0.0955) rounded up.
#[test]
fn metal_presets_match_quoted_f0() {
    let quoted: &[(&str, [f64; 3])] = &[
        ("gold", [1.000, 0.782, 0.344]),
        ("silver", [0.972, 0.960, 0.915]),
        ("copper", [0.955, 0.638, 0.538]),
        ("aluminium", [0.913, 0.922, 0.924]),
        ("iron", [0.562, 0.565, 0.578]),
        ("titanium", [0.542, 0.497, 0.449]),
        ("chromium", [0.549, 0.556, 0.554]),
    ];
    assert_eq!(quoted.len(), Preset::METALS.len());
    let mut worst = 0.0f64;
    for (p, (name, f0q)) in Preset::METALS.iter().zip(quoted) {
        assert_eq!(&p.name(), name);
        let f0 = f0_from_preset(*p);
        for i in 0..3 {
            worst = worst.max((f0[i] - f0q[i]).abs());
        }
        // Hue ordering of the coloured metals survives the sampling.
        if ["gold", "copper"].contains(name) {
            assert!(f0[0] > f0[1] && f0[1] > f0[2], "{name}: {f0:?}");
        }
    }
    println!("max |F0 − quoted| = {worst:.4}");
    assert!(worst < 0.10, "{worst}");
}

#[test]
fn metal_presets_are_valid_and_documented() {
    for p in Preset::METALS {
        let d = p.data();
        for i in 0..3 {
            assert!(d.eta[i] > 0.0 && d.k[i] > 1.0, "{p} channel {i}");
        }
        // R, G, B wavelengths near 650 / 550 / 450 nm, in that order.
        let [r, g, b] = d.wavelengths_nm.unwrap();
        assert!((r - 650.0).abs() < 15.0 && (g - 550.0).abs() < 15.0 && (b - 450.0).abs() < 10.0);
        assert!(!d.source.is_empty());
        assert!(p.is_conductor());
        let c = Conductor::<f32, 3>::from_preset(p).unwrap();
        let f = c.eval(0.5);
        assert!(f.iter().all(|x| (0.0..=1.0).contains(x)));
        for (got, want) in c.eval(1.0).into_iter().zip(f0_from_preset(p)) {
            assert_abs_diff_eq!(f64::from(got), want, epsilon = 1e-6);
        }
    }
}

/// Names: every preset round-trips through its name, names are distinct snake case, and
/// unknown or differently spelt names are rejected.
#[test]
fn presets_are_found_by_name() {
    let mut names: Vec<_> = Preset::ALL.iter().map(|p| p.name()).collect();
    for p in Preset::ALL {
        assert_eq!(Preset::from_name(p.name()), Some(p));
        assert_eq!(format!("{p}"), p.name());
        assert!(
            p.name()
                .bytes()
                .all(|b| b.is_ascii_lowercase() || b == b'_'),
            "{p}"
        );
    }
    names.sort();
    names.dedup();
    assert_eq!(names.len(), Preset::ALL.len());
    for bad in ["Gold", "titanium dioxide", "unobtainium", ""] {
        assert_eq!(Preset::from_name(bad), None, "{bad}");
    }
    // METALS are exactly the presets with measured wavelengths.
    for p in Preset::ALL {
        assert_eq!(
            Preset::METALS.contains(&p),
            p.data().wavelengths_nm.is_some(),
            "{p}"
        );
    }
}

/// The preset constructors of `fresnel` build the same terms as the general constructors
/// from the preset's numbers, and only `Dielectric` refuses (absorbing presets).
#[test]
fn fresnel_terms_from_presets() {
    for p in Preset::ALL {
        let (eta, k) = p.ior();
        let (e32, k32) = (eta.map(|v| v as f32), k.map(|v| v as f32));
        assert_eq!(
            Conductor::<f32, 3>::from_preset(p).unwrap(),
            Conductor::new(e32, k32).unwrap()
        );
        assert_eq!(
            F82Tint::<f64, 3>::from_preset(p).unwrap(),
            F82Tint::from_ior(eta, k).unwrap()
        );
        let schlick = Schlick::<f64, 3>::from_preset(p).unwrap();
        assert_eq!(schlick.f0(), f0_from_preset(p));
        // Schlick and the exact conductor agree at normal incidence.
        let exact = Conductor::<f64, 3>::from_preset(p).unwrap().eval(1.0);
        for (s, e) in schlick.eval(1.0).into_iter().zip(exact) {
            assert_relative_eq!(s, e, max_relative = 1e-14);
        }
        match Dielectric::<f64>::from_preset(p) {
            Ok(d) => {
                assert!(!p.is_conductor(), "{p}");
                assert_eq!(d.eta(), eta[1]);
                assert_eq!(eta, [eta[1]; 3]);
                let [f] = FresnelTerm::<f64, 1>::eval(&d, 0.3);
                assert_relative_eq!(
                    f,
                    Conductor::<f64, 3>::from_preset(p).unwrap().eval(0.3)[0],
                    max_relative = 1e-12
                );
            }
            Err(e) => {
                assert!(p.is_conductor(), "{p}");
                assert!(
                    matches!(e, brdf::Error::OutOfDomain { param: "preset", value, .. } if value > 0.0)
                );
            }
        }
    }
}
