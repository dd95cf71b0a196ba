//! World-space frames: orthonormality at degenerate normals and over the sphere, Gram-Schmidt
//! tangents and their fallback, world-space evaluation against local evaluation under random
//! rotations (scalars and lanes), anisotropic models following the tangent, and the SoA batch
//! conversion.

mod common;

use approx::{assert_relative_eq, assert_ulps_eq, relative_eq};
use brdf::batch::{self, Directions, Isa};
use brdf::fresnel::{Conductor, Schlick};
use brdf::masking::SmithHeightCorrelated;
use brdf::models::{AshikhminShirley, CookTorrance, KajiyaKay, Lambert, Ward};
use brdf::ndf::{Beckmann, Ggx};
use brdf::{Brdf, Frame, Real, Scalar, Vec3, f32x8, f64x4, ior};
use glam::{DQuat, DVec3};
use proptest::prelude::*;

use common::{config, direction, unit};

/// A uniformly distributed rotation from three uniforms (Shoemake, "Uniform random
/// rotations", Graphics Gems III, 1992): a warp, no rejection.
fn rotation(u1: f64, u2: f64, u3: f64) -> DQuat {
    let tau = 2.0 * std::f64::consts::PI;
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    DQuat::from_xyzw(
        a * (tau * u2).sin(),
        a * (tau * u2).cos(),
        b * (tau * u3).sin(),
        b * (tau * u3).cos(),
    )
    .normalize()
}

fn rotations() -> impl Strategy<Value = DQuat> {
    (unit(), unit(), unit()).prop_map(|(a, b, c)| rotation(a, b, c))
}

/// A unit vector uniform on the whole sphere (`z = 2u − 1`), poles and equator drawn often.
fn sphere() -> impl Strategy<Value = DVec3> {
    (unit(), 0.0f64..1.0).prop_map(|(u, v)| {
        let z = 2.0 * u - 1.0;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * std::f64::consts::PI * v;
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

fn dv(v: Vec3<f64>) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

fn of<S: Scalar>(v: DVec3) -> Vec3<S> {
    Vec3::new(S::of(v.x), S::of(v.y), S::of(v.z))
}

fn wide<S: Scalar>(v: Vec3<S>) -> DVec3 {
    DVec3::new(v.x.into(), v.y.into(), v.z.into())
}

/// The largest orthonormality defect of a frame, in units of the scalar's epsilon:
/// `|t·b|, |t·n|, |b·n|` (the cosines of the angles between axes, i.e. their deviation from
/// 90° in radians), `||t| − 1|, ||b| − 1|` and the components of `t × b − n`, all computed in
/// f64 from the frame's (exactly widened) components.
fn defect<S: Scalar>(f: &Frame<S>) -> f64 {
    let (t, b, n) = (wide(f.tangent()), wide(f.bitangent()), wide(f.normal()));
    let eps: f64 = S::EPSILON.into();
    let r = t.cross(b) - n;
    [
        t.dot(b).abs(),
        t.dot(n).abs(),
        b.dot(n).abs(),
        (t.length() - 1.0).abs(),
        (b.length() - 1.0).abs(),
        r.abs().max_element(),
    ]
    .into_iter()
    .fold(0.0, f64::max)
        / eps
}

/// Unit normals at and next to the singular and branch points of the basis.
fn degenerate_normals() -> Vec<DVec3> {
    let mut v = vec![
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
        DVec3::new(1.0, 0.0, -0.0),
        DVec3::new(-0.0, 1.0, -0.0),
        DVec3::new(-0.0, -0.0, -1.0),
        DVec3::new(0.6, 0.0, -0.8),
        DVec3::new(0.0, -0.6, -0.8),
        DVec3::new(-0.48, 0.6, 0.64),
    ];
    for tiny in [1e-7, 1e-20, 1e-30, 1e-38, 1e-45] {
        for s in [1.0, -1.0] {
            let (c2, c1) = ((1.0 - 2.0 * tiny * tiny).sqrt(), (1.0 - tiny * tiny).sqrt());
            v.push(DVec3::new(tiny, tiny, s * c2));
            v.push(DVec3::new(-tiny, 0.0, s * c1));
            v.push(DVec3::new(0.0, tiny, s * c1));
            v.push(DVec3::new(0.0, 0.0, s) + DVec3::new(tiny, -tiny, 0.0) * 1e-10);
            v.push(DVec3::new((1.0 - tiny * tiny).sqrt(), 0.0, s * tiny));
            v.push(DVec3::new(0.0, -(1.0 - tiny * tiny).sqrt(), s * tiny));
        }
    }
    // One ULP of f32 and of f64 away from the poles.
    for z in [1.0 - f32::EPSILON as f64 / 2.0, 1.0 - f64::EPSILON / 2.0] {
        for s in [1.0, -1.0] {
            let r = (1.0 - z * z).sqrt();
            v.push(DVec3::new(r * 0.6, r * 0.8, s * z));
        }
    }
    v
}

#[test]
fn degenerate_normals_give_orthonormal_right_handed_frames() {
    let (mut worst32, mut worst64) = (0.0f64, 0.0f64);
    for n in degenerate_normals() {
        let f32f = Frame::from_normal(of::<f32>(n));
        let f64f = Frame::from_normal(of::<f64>(n));
        let (d32, d64) = (defect(&f32f), defect(&f64f));
        assert!(d32 <= 4.0, "f32 frame of {n:?}: defect {d32} ε");
        assert!(d64 <= 4.0, "f64 frame of {n:?}: defect {d64} ε");
        assert!(f32f.tangent().x.is_finite() && f64f.bitangent().y.is_finite());
        (worst32, worst64) = (worst32.max(d32), worst64.max(d64));
    }
    println!("worst defect: f32 {worst32} ε, f64 {worst64} ε");
}

#[test]
fn lanes_build_the_scalar_frame_bit_for_bit() {
    let normals = degenerate_normals();
    for chunk in normals.chunks(8) {
        let get = |i: usize| of::<f32>(chunk[i.min(chunk.len() - 1)]);
        let n8 = Vec3::new(
            f32x8::from_fn(|l| get(l).x),
            f32x8::from_fn(|l| get(l).y),
            f32x8::from_fn(|l| get(l).z),
        );
        let t8 = Vec3::new(f32x8::splat(0.3), f32x8::splat(-0.2), f32x8::splat(0.9));
        let (f8, g8) = (Frame::from_normal(n8), Frame::from_normal_tangent(n8, t8));
        for l in 0..8 {
            let lane = |v: Vec3<f32x8>| Vec3::new(v.x.lane(l), v.y.lane(l), v.z.lane(l));
            let f = Frame::from_normal(get(l));
            let g = Frame::from_normal_tangent(get(l), Vec3::new(0.3, -0.2, 0.9));
            assert_eq!(lane(f8.tangent()), f.tangent());
            assert_eq!(lane(f8.bitangent()), f.bitangent());
            assert_eq!(lane(g8.tangent()), g.tangent());
            assert_eq!(lane(g8.bitangent()), g.bitangent());
        }
    }
    // f64x4 too.
    let n = Vec3::new(
        f64x4::from([0.0, 0.6, 0.0, -0.0]),
        f64x4::from([0.0, 0.0, -0.6, 1.0]),
        f64x4::from([-1.0, -0.8, 0.8, 0.0]),
    );
    let f = Frame::from_normal(n);
    for l in 0..4 {
        let s = Frame::from_normal(Vec3::new(n.x.lane(l), n.y.lane(l), n.z.lane(l)));
        assert_eq!(f.tangent().y.lane(l), s.tangent().y);
        assert_eq!(f.bitangent().x.lane(l), s.bitangent().x);
    }
}

proptest! {
    #![proptest_config(config(512))]

    #[test]
    fn from_normal_is_orthonormal_over_the_sphere(n in sphere()) {
        let d32 = defect(&Frame::from_normal(of::<f32>(n)));
        let d64 = defect(&Frame::from_normal(of::<f64>(n)));
        prop_assert!(d32 <= 4.0 && d64 <= 4.0, "{n:?}: {d32} ε (f32), {d64} ε (f64)");
    }

    #[test]
    fn from_normal_tangent_keeps_the_tangent_direction(
        q in rotations(),
        tilt in -10.0f64..10.0,
        len in prop_oneof![Just(1.0), 1e-3f64..1e3],
    ) {
        // The rotated frame (q e_x, q e_y, q e_z); the tangent handed in is q e_x scaled and
        // tilted towards the normal by any amount.
        let (n, t) = (q * DVec3::Z, q * DVec3::X);
        let given = (t + n * tilt) * len;
        let f = Frame::from_normal_tangent(of::<f64>(n), of::<f64>(given));
        prop_assert!(defect(&f) <= 4.0, "{}", defect(&f));
        prop_assert!((wide(f.tangent()) - t).length() <= 1e-14 * (1.0 + tilt.abs()));
        prop_assert!((wide(f.bitangent()) - q * DVec3::Y).length() <= 1e-14 * (1.0 + tilt.abs()));
        let g = Frame::from_normal_tangent(of::<f32>(n), of::<f32>(given));
        prop_assert!(defect(&g) <= 4.0, "{}", defect(&g));
        prop_assert!((wide(g.tangent()) - t).length() <= 1e-6 * (1.0 + tilt.abs()));
    }

    #[test]
    fn to_world_inverts_to_local(q in rotations(), w in sphere()) {
        let f = Frame::from_normal(of::<f64>(q * DVec3::Z));
        let l = f.to_local(of::<f64>(w));
        // Two three-term dot products (≤ 3 ε each for unit vectors) and the basis defect
        // (≤ 4 ε): 10 ε.
        assert_relative_eq!(f.to_world(l), of::<f64>(w), epsilon = 10.0 * f64::EPSILON);
        assert_relative_eq!(l.length(), 1.0, epsilon = 10.0 * f64::EPSILON);
        assert_relative_eq!(l.z, w.dot(q * DVec3::Z), epsilon = 4.0 * f64::EPSILON);
    }

    /// A model evaluated through a frame at rotated world directions equals the model at the
    /// local directions: isotropic models with the frame of the normal alone (any rotation
    /// about the normal leaves them unchanged), anisotropic ones with the rotated tangent.
    #[test]
    fn world_space_eval_equals_local_eval_under_random_rotations(
        q in rotations(),
        wi in direction(),
        wo in direction(),
    ) {
        // The round trip moves a cosine by ~1e-16: keep directions off the exact horizon,
        // where the value is discontinuous (0 below, finite above).
        let lift = |w: Vec3<f64>| {
            let z = w.z.max(1e-6);
            let r = ((1.0 - z * z) / (w.x * w.x + w.y * w.y)).sqrt();
            if r.is_finite() { Vec3::new(w.x * r, w.y * r, z) } else { Vec3::new(0.0, 0.0, 1.0) }
        };
        let (wi, wo) = (lift(wi), lift(wo));
        let (wi_w, wo_w) = (q * dv(wi), q * dv(wo));
        let (n, t) = (q * DVec3::Z, q * DVec3::X);
        let iso = Frame::from_normal(n);
        let aniso = Frame::from_normal_tangent(n, t);

        let gold = CookTorrance::new(
            Ggx::<f64>::new(0.2).unwrap(),
            Conductor::<f64, 3>::new([0.14, 0.43, 1.38], [3.697, 2.455, 1.914]).unwrap(),
            SmithHeightCorrelated,
        );
        let brushed = CookTorrance::new(
            Ggx::<f64>::anisotropic(0.05, 0.4).unwrap(),
            Schlick::<f64, 1>::new([0.9]).unwrap(),
            SmithHeightCorrelated,
        );
        let ward = Ward::<f64, 1>::new([0.2], [0.5], 0.1, 0.3).unwrap();
        let ash = AshikhminShirley::<f64, 1>::new([0.3], [0.5], 100.0, 10.0).unwrap();
        let hair = KajiyaKay::<f64, 1>::new([0.2], [0.6], 50.0, [1.0, 0.0, 0.0]).unwrap();
        let beck = CookTorrance::new(
            Beckmann::<f64>::anisotropic(0.3, 0.1).unwrap(),
            Schlick::<f64, 1>::new([0.04]).unwrap(),
            SmithHeightCorrelated,
        );

        // Relative 1e-9, or 1e-10 absolute (values are O(0.01–1000)): Kajiya-Kay's
        // sin(t, w) = √(1 − (t·w)²) is ill-conditioned along the fibre, where a 1e-16 change
        // of t·w moves a 6e-8 value by 3e-11 — the model's conditioning, not the frame's.
        let check = |name: &str, world: &[f64], local: &[f64]| {
            for (a, b) in world.iter().zip(local) {
                assert!(
                    relative_eq!(a, b, epsilon = 1e-10, max_relative = 1e-9),
                    "{name}: world {a:e} vs local {b:e} (wi {wi:?}, wo {wo:?}, q {q:?})"
                );
            }
        };
        check("gold (from_normal)", &iso.eval(&gold, wi_w, wo_w), &gold.eval(wi, wo));
        check("brushed GGX", &aniso.eval(&brushed, wi_w, wo_w), &brushed.eval(wi, wo));
        check("Beckmann aniso", &aniso.eval(&beck, wi_w, wo_w), &beck.eval(wi, wo));
        check("Ward", &aniso.eval(&ward, wi_w, wo_w), &ward.eval(wi, wo));
        check("Ashikhmin-Shirley", &aniso.eval(&ash, wi_w, wo_w), &ash.eval(wi, wo));
        check("Kajiya-Kay", &aniso.eval(&hair, wi_w, wo_w), &hair.eval(wi, wo));
    }

    /// Eight frames and direction pairs on f32x8 equal eight scalar f32 evaluations (the
    /// frame uses + − × ÷ √ only), which agree with the f64 local evaluation to f32 accuracy.
    #[test]
    fn world_space_eval_on_lanes_equals_scalar(
        cases in proptest::collection::vec((rotations(), direction(), direction()), 8),
    ) {
        let ct = CookTorrance::new(
            Ggx::<f32>::anisotropic(0.15, 0.4).unwrap(),
            Schlick::<f32, 1>::new([0.9]).unwrap(),
            SmithHeightCorrelated,
        );
        let ct64 = CookTorrance::new(
            Ggx::<f64>::anisotropic(0.15, 0.4).unwrap(),
            Schlick::<f64, 1>::new([0.9]).unwrap(),
            SmithHeightCorrelated,
        );
        let ct8 = brdf::real::Splat::splat::<f32x8>(&ct);
        let lanes = |f: &dyn Fn(usize) -> DVec3| {
            Vec3::new(
                f32x8::from_fn(|l| f(l).x as f32),
                f32x8::from_fn(|l| f(l).y as f32),
                f32x8::from_fn(|l| f(l).z as f32),
            )
        };
        let n8 = lanes(&|l| cases[l].0 * DVec3::Z);
        let t8 = lanes(&|l| cases[l].0 * DVec3::X);
        let wi8 = lanes(&|l| cases[l].0 * dv(cases[l].1));
        let wo8 = lanes(&|l| cases[l].0 * dv(cases[l].2));
        let f8 = Frame::from_normal_tangent(n8, t8).eval(&ct8, wi8, wo8)[0];
        for (l, (q, wi, wo)) in cases.iter().enumerate() {
            let frame = Frame::from_normal_tangent(of::<f32>(*q * DVec3::Z), of::<f32>(*q * DVec3::X));
            let scalar = frame.eval(&ct, of::<f32>(*q * dv(*wi)), of::<f32>(*q * dv(*wo)))[0];
            prop_assert_eq!(f8.lane(l).to_bits(), scalar.to_bits(), "lane {}", l);
            // Against f64 in the local frame, away from the horizon (an f32 rotation moves a
            // cosine by ~1e-7) and for values that f32 resolves.
            if wi.z > 0.05 && wo.z > 0.05 {
                let exact = ct64.eval(*wi, *wo)[0];
                prop_assert!(
                    relative_eq!(scalar as f64, exact, epsilon = 1e-6, max_relative = 1e-3),
                    "lane {}: {} vs {}", l, scalar, exact
                );
            }
        }
    }
}

/// Swapping the roughnesses of an anisotropic model equals turning its tangent by 90° about
/// the normal: the anisotropy lies along the frame's tangent, not along a world axis.
#[test]
fn anisotropic_models_follow_the_tangent() {
    let n = DVec3::new(0.0, 1.0, 0.0); // y-up
    let t = DVec3::new(0.6, 0.0, 0.8);
    let turned = n.cross(t); // t turned by +90° about n
    let along = Frame::from_normal_tangent(n, t);
    let across = Frame::from_normal_tangent(n, turned);
    assert_ulps_eq!(across.tangent(), along.bitangent(), max_ulps = 2);

    let ct = |ax, ay| {
        CookTorrance::new(
            Ggx::<f64>::anisotropic(ax, ay).unwrap(),
            Schlick::<f64, 1>::new([0.5]).unwrap(),
            SmithHeightCorrelated,
        )
    };
    let (xy, yx) = (ct(0.05, 0.5), ct(0.5, 0.05));
    let (wx, wy) = (
        Ward::<f64, 1>::new([0.0], [1.0], 0.05, 0.5).unwrap(),
        Ward::<f64, 1>::new([0.0], [1.0], 0.5, 0.05).unwrap(),
    );
    let mut differs = 0;
    for k in 0..64 {
        let a = k as f64 * 0.37;
        let wi = (n * 0.7 + t * (0.5 * a.cos()) + turned * (0.5 * a.sin())).normalize();
        let wo = (n * 0.8 + t * (-0.3 * (a * 1.3).sin()) + turned * (0.4 * a.cos())).normalize();
        let (p, q) = (along.eval(&xy, wi, wo)[0], across.eval(&yx, wi, wo)[0]);
        assert_relative_eq!(p, q, max_relative = 1e-12);
        assert_relative_eq!(
            along.eval(&wx, wi, wo)[0],
            across.eval(&wy, wi, wo)[0],
            max_relative = 1e-12
        );
        // ...and it matters: the same model under the turned frame gives another value.
        if !relative_eq!(p, across.eval(&xy, wi, wo)[0], max_relative = 1e-3) {
            differs += 1;
        }
    }
    assert!(differs > 48, "{differs}");

    // A highlight stretched along the tangent: off-specular along t is brighter than the same
    // offset across it (α along t is the larger one here).
    let stretched = ct(0.5, 0.05);
    let wi = (n + t).normalize();
    let mirror = (n - t).normalize();
    let off_t = (mirror + t * 0.2).normalize();
    let off_b = (mirror + turned * 0.2).normalize();
    assert!(along.eval(&stretched, wi, off_t)[0] > 5.0 * along.eval(&stretched, wi, off_b)[0]);
}

#[test]
fn parallel_tangents_fall_back_and_scalars_report_them() {
    let n = Vec3::new(0.0_f64, 0.6, 0.8);
    let duff = Frame::from_normal(n);
    for t in [
        n,
        n.scale(-3.0),
        n + Vec3::new(1e-4, 0.0, 0.0), // sin θ ≈ 1e-4 < 1e-3
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(f64::NAN, 0.0, 1.0),
        Vec3::new(f64::INFINITY, 0.0, 1.0),
    ] {
        let f = Frame::from_normal_tangent(n, t);
        assert_eq!(f, duff, "tangent {t:?}");
        assert!(
            Frame::try_from_normal_tangent(n, t).is_err(),
            "tangent {t:?}"
        );
    }
    // Just above the threshold the projection is used.
    let t = n + Vec3::new(2e-3, 0.0, 0.0);
    let f = Frame::try_from_normal_tangent(n, t).unwrap();
    // The projection of a tangent at angle θ from the normal is ill-conditioned: its
    // direction carries an error of about ε / sin θ = 5.6e-14 here.
    assert_relative_eq!(f.tangent(), Vec3::new(1.0, 0.0, 0.0), epsilon = 1e-12);
    let e = Frame::try_from_normal_tangent(n, n.scale(2.0)).unwrap_err();
    assert!(
        matches!(e, brdf::Error::OutOfDomain { param: "tangent", value, .. } if value == 0.0),
        "{e:?}"
    );
    let e = Frame::<f32>::try_from_normal(Vec3::new(0.0, f32::NAN, 1.0)).unwrap_err();
    assert_eq!(e, brdf::Error::NotFinite { param: "normal" });
    let e =
        Frame::<f32>::try_from_normal_tangent(Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0))
            .unwrap_err();
    assert!(
        matches!(
            e,
            brdf::Error::OutOfDomain {
                param: "normal",
                ..
            }
        ),
        "{e:?}"
    );
    // try_ normalizes normals of any length, tiny and huge.
    for s in [1e-40_f32, 1e-20, 1e20, 3e38] {
        let f = Frame::try_from_normal(Vec3::new(0.0, s, 0.0)).unwrap();
        assert_eq!(f.normal(), Vec3::new(0.0, 1.0, 0.0));
        let g =
            Frame::try_from_normal_tangent(Vec3::new(s, 0.0, s), Vec3::new(0.0, s, 0.0)).unwrap();
        assert!(defect(&g) <= 4.0);
        assert_eq!(g.tangent(), Vec3::new(0.0, 1.0, 0.0));
    }
    // On lanes the fallback is per lane.
    let n8 = Vec3::new(f32x8::splat(0.0), f32x8::splat(0.6), f32x8::splat(0.8));
    let t8 = Vec3::new(
        f32x8::from([1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0]),
        f32x8::from([0.0, 0.6, 0.0, 0.6, 0.0, 0.6, 0.0, 0.0]),
        f32x8::from([0.0, 0.8, 0.0, 0.8, 0.0, 0.8, 0.0, 0.0]),
    );
    let f8 = Frame::from_normal_tangent(n8, t8);
    let duff32 = Frame::from_normal(Vec3::new(0.0_f32, 0.6, 0.8));
    for l in 0..8 {
        let want = if l % 2 == 0 { 1.0 } else { duff32.tangent().x };
        assert_eq!(f8.tangent().x.lane(l), want, "lane {l}");
    }
}

#[test]
fn glam_types_convert_in() {
    let n = glam::Vec3::new(0.0, 0.6, 0.8);
    let a = Frame::from_normal(n);
    let b = Frame::from_normal(Vec3::new(0.0_f32, 0.6, 0.8));
    assert_eq!(a, b);
    let d = Frame::from_normal(DVec3::new(0.0, 0.6, 0.8));
    assert_eq!(d, Frame::from_normal(Vec3::new(0.0_f64, 0.6, 0.8)));
    let w = glam::Vec3::new(0.36, 0.48, 0.8);
    assert_relative_eq!(a.to_local(w).z, w.dot(n), max_relative = 1e-6);
    let back: glam::Vec3 = a.to_world(a.to_local(w)).into();
    assert!((back - w).length() < 1e-6);
    // Lanes from eight glam vectors.
    let n8 = Vec3::<f32x8>::from([n; 8]);
    assert_eq!(Frame::from_normal(n8).tangent().y.lane(3), a.tangent().y);
    // [R; 3] in and out.
    let arr: [f32; 3] = a.normal().into();
    assert_eq!(Frame::from_normal(arr), a);
}

/// The y-up trap of the docs, as numbers: world vectors passed through `.into()` are read as
/// z-up and give another (wrong) value; through the frame they give the local one.
#[test]
fn y_up_vectors_need_a_frame() {
    let gold = CookTorrance::new(
        Ggx::<f32>::new(0.3).unwrap(),
        Conductor::from_preset(ior::Preset::Gold).unwrap(),
        SmithHeightCorrelated,
    );
    // Local (z-up) directions and the same directions in a y-up world (x, z, y) → (x, y, z)
    // is a reflection; the rotation taking z-up to y-up maps (x, y, z) → (x, z, −y).
    let (wi, wo) = (
        Vec3::new(0.5_f32, -0.1, 0.86).normalize_or_zero(),
        Vec3::new(-0.3, -0.2, 0.93).normalize_or_zero(),
    );
    let up = |w: Vec3<f32>| glam::Vec3::new(w.x, w.z, -w.y);
    let local = gold.eval(wi, wo);
    let naive = gold.eval(up(wi).into(), up(wo).into());
    let frame = Frame::from_normal(glam::Vec3::Y);
    let through = frame.eval(&gold, up(wi), up(wo));
    assert!(
        (naive[1] - local[1]).abs() > 0.5 * local[1],
        "{naive:?} {local:?}"
    );
    // The frame about y differs from the original x, y axes by a rotation about the normal,
    // to which the isotropic model is blind.
    assert_relative_eq!(through[1], local[1], max_relative = 1e-5);
}

#[test]
fn to_local_soa_matches_to_local_and_feeds_batch_eval() {
    let rots: Vec<DQuat> = (0..37)
        .map(|i| {
            rotation(
                (i as f64 * 0.61) % 1.0,
                (i as f64 * 0.37) % 1.0,
                (i as f64 * 0.113) % 1.0,
            )
        })
        .collect();
    let frames: Vec<Frame<f32>> = rots
        .iter()
        .map(|q| Frame::from_normal(of::<f32>(*q * DVec3::Z)))
        .collect();
    let wi: Vec<glam::Vec3> = rots
        .iter()
        .map(|q| (*q * DVec3::new(0.3, 0.2, 0.93).normalize()).as_vec3())
        .collect();
    let wo: Vec<glam::Vec3> = rots
        .iter()
        .map(|q| (*q * DVec3::new(-0.5, 0.1, 0.86).normalize()).as_vec3())
        .collect();
    let soa = |dirs: &[glam::Vec3]| {
        let mut c = vec![vec![0.0f32; dirs.len()]; 3];
        let [x, y, z] = &mut c[..] else {
            unreachable!()
        };
        brdf::frame::to_local_soa(&frames, dirs, [x, y, z]);
        c
    };
    let (i, o) = (soa(&wi), soa(&wo));
    for k in 0..frames.len() {
        let l = frames[k].to_local(wi[k]);
        assert_eq!([i[0][k], i[1][k], i[2][k]], <[f32; 3]>::from(l));
    }
    let ct = CookTorrance::new(
        Ggx::<f32>::new(0.3).unwrap(),
        Schlick::<f32, 1>::new([0.04]).unwrap(),
        SmithHeightCorrelated,
    );
    let mut out = vec![0.0f32; frames.len()];
    batch::eval_with(
        Isa::Portable,
        &ct,
        Directions::new(&i[0], &i[1], &i[2]),
        Directions::new(&o[0], &o[1], &o[2]),
        [&mut out],
    )
    .unwrap();
    for k in 0..frames.len() {
        assert_eq!(out[k], frames[k].eval(&ct, wi[k], wo[k])[0], "pair {k}");
    }
    // One shared frame.
    let f = frames[5];
    let mut c = [[0.0f32; 37]; 3];
    let [x, y, z] = &mut c;
    f.to_local_soa(&wi, [x, y, z]);
    assert_eq!(Vec3::new(c[0][9], c[1][9], c[2][9]), f.to_local(wi[9]));
    let white = Lambert::<f32, 1>::new([1.0]).unwrap();
    assert!(f.eval(&white, wi[5], wo[5])[0] > 0.0);
}
