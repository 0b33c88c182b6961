//! Willson's normal-equation least squares (`willson_linear`).

use super::*;

#[test]
fn gauss_jordan_inverts_with_pivoting() {
    // Needs both row and column interchanges.
    let a0 = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 5.0];
    let mut a = a0;
    let det = invert_gauss_jordan(&mut a, 3);
    assert!((det - (-13.0)).abs() < 1e-12, "det {det}");
    for i in 0..3 {
        for j in 0..3 {
            let p: f64 = (0..3).map(|k| a0[i * 3 + k] * a[k * 3 + j]).sum();
            assert!((p - f64::from(u8::from(i == j))).abs() < 1e-12);
        }
    }
    assert_eq!(invert_gauss_jordan(&mut [0.0; 4], 2), 0.0);
}

#[test]
fn normal_equations_fit_a_line_and_refuse_rank_deficiency() {
    let m = [1.0, 0.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0];
    let a = solve_system(&m, 2, &[1.0, 3.0, 5.0, 7.0]).unwrap();
    assert!((a[0] - 1.0).abs() < 1e-12 && (a[1] - 2.0).abs() < 1e-12);
    assert!(solve_system(&[1.0, 2.0, 2.0, 4.0], 2, &[1.0, 2.0]).is_none());
}
