//! Tests of the lane trait itself and of the test support.
mod common;

#[test]
fn lane_primitives_match_scalar() {
    let rows: Vec<[f64; 2]> = (0..97)
        .map(|i| [i as f64 / 96.0, 1.0 + (i % 13) as f64 * 7.5])
        .collect();
    let w = common::assert_lanes_match!("sqrt-div-minmax", ulp = 0, abs = 0.0, &rows, fn(x, y) {
        (x.sqrt() / y).max(x * R::from_f64(0.01)).min(R::one()) + R::select(x.lt(R::from_f64(0.5)), x, y)
    });
    assert_eq!(w, 0);
    // Transcendentals: wide's polynomial kernels are within a few ULP of std.
    let w = common::assert_lanes_match!("exp-ln", ulp = 4, abs = 0.0, &rows, fn(x, y) {
        (x * R::from_f64(-3.0)).exp() + (y.ln() * R::from_f64(0.25))
    });
    println!("exp/ln worst ulp: {w}");
}
