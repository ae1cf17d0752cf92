//! A new user's multibody findings, each on a small file written for it
//! in `tests/sym/newcomer/` (their errors are in `tests/sym/broken/`,
//! 60–64): a body's mass centre is a point (`position`, `velocity`, a
//! `[[load]]` at it, a `[[point]]` of its name at its place); entries of an
//! array (`M.12`); an operating point at π; `position` across two fixed
//! points; a solution divided by the coefficients' own sums once, not by
//! their expanded power. Every step with an expectation must hold, and each
//! file must hold as many expectations as it was written with.

use hdot_sym::derivation::load;
use hdot_tests::repo_root;

/// The file `newcomer/NAME.toml`, loaded; every expectation holds, and
/// there are `checks` of them (a file that lost its expectations fails).
fn holds(name: &str, checks: usize) {
    let path = repo_root().join(format!("tests/sym/newcomer/{name}.toml"));
    let d = load(&path).unwrap_or_else(|e| panic!("{e}"));
    let failures: Vec<String> = d
        .failures()
        .iter()
        .map(|(step, c)| {
            format!(
                "{step}.{}: derived − expected = {}",
                c.component, c.difference
            )
        })
        .collect();
    assert!(failures.is_empty(), "{name}: {failures:#?}");
    assert_eq!(d.check_count(), checks, "{name}: expectations checked");
}

#[test]
fn a_body_s_centre_is_a_point_for_position_velocity_and_loads() {
    // Kane's equations with the load at the centre G2 equal Lagrange's
    // with its generalized forces, F · ∂v_G2/∂u_r.
    holds("centre-is-a-point", 3 + 3 + 3 + 2);
}

#[test]
fn a_point_named_as_a_body_s_centre_at_its_place_is_accepted() {
    holds("centre-also-a-point", 3 + 1);
}

#[test]
fn array_and_matrix_entries_are_read_by_row_and_column() {
    holds("array-entries", 4 + 4 + 4 + 1);
}

#[test]
fn an_operating_point_at_pi_linearizes_about_the_inverted_motion() {
    holds("inverted-pendulum", 4);
}

#[test]
fn position_runs_between_points_hung_from_two_fixed_points() {
    holds("two-fixed-points", 3 + 3 + 3);
}

#[test]
fn a_solution_holds_a_coefficient_s_sum_once_as_a_textbook_writes_it() {
    // Cramer's rule divides by (I + m r²)² J; each rate reads
    // (…)/(I + m r²), and the coupled pair, whose determinant holds no
    // entry's sum, is divided by it whole.
    holds("wheels-on-an-incline", 3);
    let path = repo_root().join("tests/sym/newcomer/wheels-on-an-incline.toml");
    let d = load(&path).unwrap_or_else(|e| panic!("{e}"));
    insta::assert_snapshot!(hdot_sym::render::render(
        &d,
        hdot_sym::render::Format::Unicode
    ));
}

/// After an operating point at a multiple of π/2 the printed angle is its
/// deviation from there: the step says so (its own or an earlier step's
/// point, for the angles its value still holds), after the file's doc.
#[test]
fn a_step_says_what_its_angles_stand_for_after_an_operating_point_at_pi() {
    let path = repo_root().join("tests/sym/newcomer/double-pendulum-upright.toml");
    let d = load(&path).unwrap_or_else(|e| panic!("{e}"));
    let doc = |name: &str| d.steps.iter().find(|s| s.name == name).unwrap().doc.clone();
    assert_eq!(
        doc("upright"),
        "both links above the pivot; q1 stands for q1 − π, its deviation from the operating point"
    );
    assert_eq!(
        doc("folded"),
        "q1 stands for q1 + π/2 and q2 for q2 − 3π/2, their deviations from the operating point"
    );
    // The stiffness holds cos q2 at q2 = 0 only through constants; the
    // mass matrix holds no angle: neither names one.
    assert_eq!(doc("stiffness"), "");
    assert_eq!(doc("mass"), "");
    let text = hdot_sym::render::render(&d, hdot_sym::render::Format::Latex);
    // The note opens the second step's sentence: q1 keeps its case.
    assert!(text.contains("\\quad q1 stands for q1 +"), "{text}");
}

/// sin and cos of sums of angles are written out by the addition
/// formulas, in values and expectations alike.
#[test]
fn sines_and_cosines_of_sums_of_angles_can_be_written() {
    holds("sums-of-angles", 3 + 1 + 1);
}

/// A matrix prints in the terminal as a grid in brackets, its columns
/// aligned (the trial's 4 × 4 matrix printed as 16 lines).
#[test]
fn a_matrix_prints_as_a_grid_in_the_terminal() {
    let path = repo_root().join("tests/sym/newcomer/double-pendulum-upright.toml");
    let d = load(&path).unwrap_or_else(|e| panic!("{e}"));
    let text = hdot_sym::render::render(&d, hdot_sym::render::Format::Unicode);
    let rows: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.contains("stiffness = ⎡"))
        .take(2)
        .collect();
    assert_eq!(rows.len(), 2, "{text}");
    assert!(rows[0].ends_with('⎤') && rows[1].ends_with('⎦'), "{rows:?}");
    // The second column starts at the same place on both rows.
    let col = |r: &str, w: &str| r.rfind(w).unwrap();
    assert_eq!(col(rows[0], "−m g l"), col(rows[1], "−m g l"), "{rows:?}");
    assert!(!text.contains("stiffness_11"), "{text}");
}
