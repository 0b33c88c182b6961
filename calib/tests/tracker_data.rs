//! Real robots, position only (issue 5): the laser-tracker campaigns in
//! `calib/tests/data/kinematic/` through the tracker-session identification
//! (`instrument_to_base` + `flange_to_tool`, 3 rows per pose). Run with
//! `--nocapture` to print the before/after figures for BENCHMARKS.md.

use nalgebra::Vector3;
use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::identify::{
    fit_parameters, frame_indices, identify, validate, IdentifyMode, Measurement,
};
use robocal_calib::kinematics::initial::initial_world_to_base;
use robocal_calib::kinematics::tracker_csv::{jacobi2025_rows, landgraf2021_rows, TrackerRow};
use robocal_calib::kinematics::{presets, CalibratedModel, Instrument, ParamLayout, RobotModel};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/kinematic");
/// The UR5 data's nominal tool: its targets are the nominal flange plus
/// this offset (see presets::ur5).
const UR5_TOOL_GUESS_MM: [f64; 3] = [0.0, 0.0, 31.0];
/// T-Mac probe to flange, `Trafo_TM_F_init.txt` (about 109 mm along z).
const UR10_TOOL_GUESS_MM: [f64; 3] = [0.0, 0.0, 109.0];

fn read(path: &str) -> String {
    std::fs::read_to_string(format!("{DATA}/{path}")).unwrap()
}

/// A Jacobi 2025 UR5 file (`tracker_csv::jacobi2025_rows`).
fn load_ur5(file: &str) -> Vec<Measurement> {
    let rows = jacobi2025_rows(&read(&format!("ur5_wam_jacobi2025/{file}"))).unwrap();
    rows.iter().map(TrackerRow::measurement).collect()
}

/// The data's own `*_dif` columns: the controller's error (nominal model).
fn load_ur5_differences(file: &str) -> Vec<Vector3<f64>> {
    let rows = jacobi2025_rows(&read(&format!("ur5_wam_jacobi2025/{file}"))).unwrap();
    rows.iter().filter_map(|r| r.controller_error_mm).collect()
}

/// A Landgraf 2021 UR10 file (`tracker_csv::landgraf2021_rows`).
fn load_ur10(series: &str, file: &str) -> Vec<Measurement> {
    let rows = landgraf2021_rows(&read(&format!("ur10_landgraf2021/{series}/{file}"))).unwrap();
    rows.iter().map(TrackerRow::measurement).collect()
}

fn start(robot: RobotModel, tool_mm: [f64; 3], data: &[Measurement]) -> CalibratedModel {
    let mut m = CalibratedModel {
        robot,
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::translation(tool_mm[0], tool_mm[1], tool_mm[2]),
    };
    m.world_to_base = initial_world_to_base(&m, data).unwrap();
    m
}

#[test]
fn ur5_grid_calibration_matches_a_plain_geometric_fit() {
    let grid = load_ur5("3D_UR5_uncalibrated_grid_cleaned.csv");
    let test = load_ur5("3D_UR5_uncalibrated_random_cleaned.csv");
    assert_eq!((grid.len(), test.len()), (1000, 20));
    let reference = start(presets::ur5(), UR5_TOOL_GUESS_MM, &grid);
    let id = identify(
        &reference,
        Instrument::Tracker,
        &grid,
        IdentifyMode::Weighted.into(),
    )
    .unwrap();
    let paper = identify(
        &reference,
        Instrument::Tracker,
        &grid,
        IdentifyMode::Paper.into(),
    )
    .unwrap();
    let raw: Vec<Vector3<f64>> = load_ur5_differences("3D_UR5_uncalibrated_random_cleaned.csv");
    let raw = robocal_calib::stats::AccuracyStats::from_errors(&raw);
    let (before, _) = validate(&id.before, &test).unwrap();
    let (after, _) = validate(&id.model, &test).unwrap();
    let (after_paper, _) = validate(&paper.model, &test).unwrap();
    println!(
        "UR5 (Jacobi 2025), 1000 grid poses -> 20 random: controller as is {:.4} mm mean; nominal kinematics with base and tool fitted {:.4} mm mean (median {:.4}, max {:.4}); after {:.4} mm mean (median {:.4}, max {:.4}, rms {:.4}); paper mode {:.4}; fixed {:?}; cond {:.1}; {} iterations",
        raw.norm.mean_mm, before.norm.mean_mm, before.norm.median_mm, before.norm.max_mm,
        after.norm.mean_mm, after.norm.median_mm, after.norm.max_mm, after.norm.rms_mm,
        after_paper.norm.mean_mm, id.identifiability.fixed, id.identifiability.condition_number, id.iterations
    );
    assert!(
        raw.norm.mean_mm > 2.0,
        "the controller's UR5 is ~2.5 mm off"
    );
    assert!(before.norm.mean_mm > 3.0 * after.norm.mean_mm);
    assert_ne!(
        id.termination,
        robocal_calib::solver::Termination::MaxIterations,
        "the fit converges"
    );
    assert!(
        after.norm.mean_mm <= 0.105,
        "plain geometric fit reaches ~0.10 mm"
    );
}

#[test]
fn ur10_series_b_calibration_validated_on_c_and_d() {
    let b = load_ur10("Series_B", "measurements_joint_configurations.csv");
    let reference = start(presets::ur10(), UR10_TOOL_GUESS_MM, &b);
    let id = identify(
        &reference,
        Instrument::Tracker,
        &b,
        IdentifyMode::Weighted.into(),
    )
    .unwrap();
    let layout = ParamLayout::new(&reference.robot, Instrument::Tracker);
    let base_only = frame_indices(&layout, false);
    for (series, file) in [
        ("Series_C", "measurements_random_poses.csv"),
        ("Series_D", "measurements_iso_cubes.csv"),
    ] {
        let val = load_ur10(series, file);
        let refit = |m: &CalibratedModel| {
            let (m, _) = fit_parameters(
                m,
                Instrument::Tracker,
                &val,
                &base_only,
                IdentifyMode::Weighted.into(),
            )
            .unwrap();
            validate(&m, &val).unwrap().0
        };
        let (before, after) = (refit(&id.before), refit(&id.model));
        println!(
            "UR10 fixed {:?} (weak {:?})",
            id.identifiability.fixed, id.identifiability.weak
        );
        println!(
            "UR10 (Landgraf 2021) B -> {series} ({} poses), instrument_to_base refitted: before {:.4} mm mean (max {:.4}); after {:.4} mm mean (median {:.4}, max {:.4}, rms {:.4})",
            val.len(), before.norm.mean_mm, before.norm.max_mm,
            after.norm.mean_mm, after.norm.median_mm, after.norm.max_mm, after.norm.rms_mm
        );
        assert!(after.norm.mean_mm < 0.75 * before.norm.mean_mm);
        assert!(after.norm.mean_mm < 0.65);
    }
}

/// Issue 19: the same campaigns with non-geometric candidates (gravity
/// compliance of joints 2 and 3, first and second harmonics of every joint)
/// selected by identifiability, a Bonferroni Wald test and BIC.
mod with_terms {
    use super::*;
    use robocal_calib::kinematics::nongeometric::CandidateOptions;
    use robocal_calib::kinematics::term_selection::{identify_with_terms, Verdict};
    use robocal_calib::kinematics::term_validate::{refit_base_with_terms, validate_with_terms};

    /// "Never worse" up to the validation's rounding (mm): a set without
    /// kept terms must give the geometric figure itself.
    const NEVER_WORSE_SLACK_MM: f64 = 1e-6;

    fn print_report(id: &robocal_calib::kinematics::term_selection::TermIdentification) {
        for l in &id.report {
            if l.verdict == Verdict::Kept {
                println!(
                    "  kept {:26} {:+.3e} ± {:.1e} {}",
                    l.name, l.value, l.std_dev, l.unit
                );
            } else if l.verdict == Verdict::DoesNotGeneralise {
                println!(
                    "  does not generalise {:26} {:+.3e} ± {:.1e} {}: {}",
                    l.name, l.value, l.std_dev, l.unit, l.why
                );
            }
        }
        let count = |v: Verdict| id.report.iter().filter(|l| l.verdict == v).count();
        println!(
            "  {} kept, {} not identifiable, {} not significant, {} not generalising, {} without BIC gain (z threshold {:.2})",
            count(Verdict::Kept),
            count(Verdict::NotIdentifiable),
            count(Verdict::NotSignificant),
            count(Verdict::DoesNotGeneralise),
            count(Verdict::NoInformationGain),
            id.z_threshold
        );
    }

    #[test]
    fn ur5_grid_with_selected_terms() {
        let grid = load_ur5("3D_UR5_uncalibrated_grid_cleaned.csv");
        let test = load_ur5("3D_UR5_uncalibrated_random_cleaned.csv");
        let reference = start(presets::ur5(), UR5_TOOL_GUESS_MM, &grid);
        let id = identify_with_terms(
            &reference,
            Instrument::Tracker,
            &grid,
            IdentifyMode::Weighted.into(),
            &CandidateOptions::for_robot(&reference.robot),
        )
        .unwrap();
        let (geo, _) = validate(&id.geometric.model, &test).unwrap();
        let (with, _) = validate_with_terms(&id.model, &id.terms, &test).unwrap();
        println!(
            "UR5 1000 grid -> 20 random: geometric {:.4} mm mean (max {:.4}); with terms {:.4} mm mean (max {:.4})",
            geo.norm.mean_mm, geo.norm.max_mm, with.norm.mean_mm, with.norm.max_mm
        );
        print_report(&id);
        assert!(
            with.norm.mean_mm <= geo.norm.mean_mm + NEVER_WORSE_SLACK_MM,
            "terms do not make validation worse: {} vs geometric {}",
            with.norm.mean_mm,
            geo.norm.mean_mm
        );
    }

    #[test]
    fn ur10_series_b_with_selected_terms_validated_on_c_and_d() {
        let b = load_ur10("Series_B", "measurements_joint_configurations.csv");
        let reference = start(presets::ur10(), UR10_TOOL_GUESS_MM, &b);
        let id = identify_with_terms(
            &reference,
            Instrument::Tracker,
            &b,
            IdentifyMode::Weighted.into(),
            &CandidateOptions::for_robot(&reference.robot),
        )
        .unwrap();
        print_report(&id);
        let layout = ParamLayout::new(&reference.robot, Instrument::Tracker);
        let base_only = frame_indices(&layout, false);
        for (series, file) in [
            ("Series_C", "measurements_random_poses.csv"),
            ("Series_D", "measurements_iso_cubes.csv"),
        ] {
            let val = load_ur10(series, file);
            let (geo_model, _) = fit_parameters(
                &id.geometric.model,
                Instrument::Tracker,
                &val,
                &base_only,
                IdentifyMode::Weighted.into(),
            )
            .unwrap();
            let geo = validate(&geo_model, &val).unwrap().0;
            let refit = refit_base_with_terms(
                &id.model,
                &id.terms,
                Instrument::Tracker,
                &val,
                IdentifyMode::Weighted.into(),
            )
            .unwrap();
            let with = validate_with_terms(&refit, &id.terms, &val).unwrap().0;
            println!(
                "UR10 B -> {series} ({} poses), base refitted: geometric {:.4} mm mean (max {:.4}); with terms {:.4} mm mean (max {:.4})",
                val.len(), geo.norm.mean_mm, geo.norm.max_mm, with.norm.mean_mm, with.norm.max_mm
            );
            // Issue 19: the selected set is never worse than geometry on a
            // held-out series. Before the region cross-validation (session
            // 8) 17 terms passed every check inside Series B and made C / D
            // 2.3 / 3.4 mm against 0.54 mm: C and D lie outside B's
            // joint-1 and joint-5 ranges.
            assert!(geo.norm.mean_mm < 0.65);
            assert!(
                with.norm.mean_mm <= geo.norm.mean_mm + NEVER_WORSE_SLACK_MM,
                "with terms {} vs geometric {}",
                with.norm.mean_mm,
                geo.norm.mean_mm
            );
        }
    }
}
