//! Willson's published Tsai results (calib/tests/data/tsai/README.md).

use super::*;
use crate::camera::tsai::willson::fit::{calibrate_tsai_full, full_optimisation_cost};
use crate::camera::tsai::willson::test_data::{load, published, INITIAL_CENTRE};

fn close(name: &str, got: f64, published: f64, tol: f64) {
    println!("{name}: ours {got:.9} published {published:.9}");
    assert!(
        (got - published).abs() <= tol,
        "{name}: {got} vs published {published} (tol {tol})"
    );
}

/// Willson's `lmdif` stopped at a relative cost change of 1e-5 (`ftol`),
/// short of the minimum in the f–Tz–Cx valley: our converged solution has a
/// lower objective than the published one, and every parameter lies within
/// `SIGMAS` standard deviations of it; the error statistics agree to 2%.
const SIGMAS: f64 = 1.0;
const STATS_REL_TOL: f64 = 0.02;

fn compare(file: &str, cpcc: &str, tz_over_f_only: bool) {
    let sensor = TsaiSensor::photometrics_star_i();
    let points = load(file);
    let fit = calibrate_tsai_full(
        &points,
        &sensor,
        Point2::new(INITIAL_CENTRE.0, INITIAL_CENTRE.1),
    )
    .unwrap();
    let (m, sd, p) = (fit.model, fit.std_dev, published(cpcc));
    let published_cost = full_optimisation_cost(&p, &points, &sensor).unwrap();
    println!(
        "{file}: cost ours {:.9e} published {:.9e}",
        fit.cost_mm2, published_cost
    );
    assert!(
        fit.cost_mm2 <= published_cost,
        "we must reach at least the published minimum"
    );
    let mut rows = vec![
        ("kappa1", m.kappa1, p.kappa1, sd.kappa1),
        ("Cx", m.cx, p.cx, sd.cx),
        ("Cy", m.cy, p.cy, sd.cy),
        ("Tx", m.tx, p.tx, sd.tx),
        ("Ty", m.ty, p.ty, sd.ty),
        ("Rx", m.rx, p.rx, sd.rx),
        ("Ry", m.ry, p.ry, sd.ry),
        ("Rz", m.rz, p.rz, sd.rz),
        ("sx", m.sx, p.sx, sd.sx),
    ];
    if tz_over_f_only {
        let rel = (m.tz / m.f_mm) / (p.tz / p.f_mm) - 1.0;
        println!(
            "Tz/f ours {:.6} published {:.6} (rel {rel:.2e})",
            m.tz / m.f_mm,
            p.tz / p.f_mm
        );
        assert!(rel.abs() < 1e-3, "Tz/f within 0.1% (README)");
    } else {
        rows.push(("f", m.f_mm, p.f_mm, sd.f_mm));
        rows.push(("Tz", m.tz, p.tz, sd.tz));
    }
    for (name, ours, theirs, sigma) in rows {
        println!(
            "{name}: ours {ours:.9} published {theirs:.9} sd {sigma:.2e} ({:.2} sd)",
            (ours - theirs) / sigma.max(f64::MIN_POSITIVE)
        );
        assert!((ours - theirs).abs() <= SIGMAS * sigma + 1e-9, "{name}");
    }
    let (e, ep) = (
        m.distorted_error(&sensor, &points).unwrap(),
        p.distorted_error(&sensor, &points).unwrap(),
    );
    println!("errors ours {e:?}\n       published {ep:?}");
    for (a, b) in [
        (e.mean, ep.mean),
        (e.std_dev, ep.std_dev),
        (e.max, ep.max),
        (e.sse, ep.sse),
    ] {
        assert!((a / b - 1.0).abs() < STATS_REL_TOL, "{a} vs {b}");
    }
}

#[test]
fn noncoplanar_full_optimisation_matches_willson() {
    compare("ncc_cd.dat", "ncc_cpcc.dat", false);
}

#[test]
fn coplanar_full_optimisation_matches_willson() {
    compare("cc_cd.dat", "cc_cpcc.dat", true);
}

#[test]
fn published_models_reproject_to_the_published_error() {
    // Our projection (Cardan) on the published camera files gives the
    // published statistics to every printed digit (README tables).
    let sensor = TsaiSensor::photometrics_star_i();
    for (data, cpcc, mean, std, max, sse) in [
        (
            "ncc_cd.dat",
            "ncc_cpcc.dat",
            0.079657,
            0.040794,
            0.251662,
            2.401149,
        ),
        (
            "cc_cd.dat",
            "cc_cpcc.dat",
            0.096750,
            0.052966,
            0.280107,
            1.213781,
        ),
    ] {
        let e = published(cpcc)
            .distorted_error(&sensor, &load(data))
            .unwrap();
        close("mean", e.mean, mean, 5e-7);
        close("std", e.std_dev, std, 5e-7);
        close("max", e.max, max, 5e-7);
        close("sse", e.sse, sse, 5e-7);
    }
}

#[test]
fn degenerate_tsai_data_is_refused() {
    let sensor = TsaiSensor::photometrics_star_i();
    let few = &load("cc_cd.dat")[..5];
    assert!(matches!(
        calibrate_tsai_full(few, &sensor, Point2::new(258.0, 204.0)),
        Err(CameraError::TooFewPoints { .. })
    ));
    let line: Vec<TsaiPoint> = (0..20)
        .map(|i| TsaiPoint {
            world: Point3::new(i as f64, 2.0 * i as f64, 0.0),
            image: Point2::new(i as f64, i as f64),
        })
        .collect();
    assert!(matches!(
        calibrate_tsai_full(&line, &sensor, Point2::new(258.0, 204.0)),
        Err(CameraError::CollinearPoints { .. })
    ));
    assert!(parse_points("1 2 3 4").is_err());
}
