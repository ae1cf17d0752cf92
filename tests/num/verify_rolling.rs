//! Rolling constraints and Kane's forces of rolling systems measured on
//! the particles (issue 24, item 7). The file written for these tests
//! (`derivations/disk-on-its-rim.toml`): a disk whose centre's height is
//! a dependent coordinate of a configuration constraint (the rim touches
//! the plane), so verification draws the height by Newton's method and
//! the dependent speeds from the constraints, and the contact's material
//! point must then be at rest. The bundled bicycles: the contacts'
//! velocities, the constraint satisfaction along the drawn motion and the
//! nonlinear Kane equations in all eight speeds (their 8×8 mass matrix
//! and forcing) measured on the four bodies' particles. A wrong force, a
//! wrong constraint row or a perturbed term must fail.

use hdot_num::verify::{Options, check};

use super::{load, verified};

const DISK: &str = include_str!("derivations/disk-on-its-rim.toml");
const BICYCLE: &str = include_str!("../../derivations/bicycle.toml");
const NONLINEAR: &str = include_str!("../../derivations/bicycle-nonlinear.toml");

/// The `[motion] vanishes` entry of a report.
const VANISHES: &str = "[motion] vanishes";

fn options(draws: usize) -> Options {
    Options { draws, seed: 24 }
}

/// `text` with `from` replaced by `to`, which occurs exactly once.
fn mutate(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "{from}");
    text.replace(from, to)
}

/// The steps of `text` compared and passing, or the test fails naming
/// those that failed.
fn passing(text: &str, draws: usize) -> Vec<String> {
    let (compared, failed) = verified(text, &options(draws));
    assert!(failed.is_empty(), "failed: {failed:?}");
    compared
}

fn has(names: &[String], wanted: &[&str]) {
    for w in wanted {
        assert!(names.iter().any(|n| n == w), "{w} not in {names:?}");
    }
}

#[test]
fn the_disk_on_its_rim_agrees_with_the_particles() {
    let compared = passing(DISK, 8);
    has(&compared, &["contact", "ground", "K", "F_1", VANISHES]);
}

#[test]
fn a_wrong_force_on_the_disk_is_rejected() {
    let text = mutate(
        DISK,
        "value = \"m*g*r*sin(theta)\"",
        "value = \"-m*g*r*sin(theta)\"",
    );
    let (_, failed) = verified(&text, &options(8));
    assert_eq!(failed, ["F_1"]);
    // The weight's lever arm from the wrong point (G's height, not r).
    let text = mutate(
        DISK,
        "value = \"m*g*r*sin(theta)\"",
        "value = \"m*g*h*sin(theta)\"",
    );
    let (_, failed) = verified(&text, &options(8));
    assert_eq!(failed, ["F_1"]);
}

#[test]
fn a_configuration_constraint_not_met_by_the_contact_is_rejected() {
    // h = r cos θ / 2: the dependent height is solved from the wrong
    // constraint, and C, still r below G, moves through the plane.
    let text = mutate(
        DISK,
        "value = \"h - r*cos(theta)\"",
        "value = \"h - r*cos(theta)/2\"",
    );
    let (_, failed) = verified(&text, &options(8));
    assert!(failed.iter().any(|f| f == VANISHES), "{failed:?}");
}

#[test]
fn a_configuration_constraint_without_a_root_is_a_located_error() {
    let text = mutate(
        DISK,
        "value = \"h - r*cos(theta)\"",
        "value = \"sin(h) + 2\"",
    );
    let e = check(&load(&text), &options(2)).expect_err("sin h + 2 has no root");
    let msg = e.to_string();
    assert!(
        msg.contains("step `K`") && msg.contains("no solution") && msg.contains('h'),
        "{msg}"
    );
}

#[test]
fn the_bicycle_s_contacts_are_at_rest_along_the_drawn_motion() {
    let compared = passing(BICYCLE, 4);
    has(&compared, &["rear", "rear_z", "front", "z_F", VANISHES]);
}

#[test]
fn the_bicycle_s_eight_kane_equations_agree_with_the_particles() {
    let compared = passing(NONLINEAR, 2);
    has(
        &compared,
        &[
            "rear",
            "rear_z",
            "rear_height",
            "front",
            "K_all",
            "M_all",
            "f_all",
            "E",
            "power",
        ],
    );
}

#[test]
fn a_perturbed_term_of_the_bicycle_s_equations_is_rejected() {
    // The front wheel's translational kinetic energy a third too small.
    let text = mutate(
        NONLINEAR,
        "m_F*dot(velocity(W_F), velocity(W_F))/2",
        "m_F*dot(velocity(W_F), velocity(W_F))/3",
    );
    let (_, failed) = verified(&text, &options(2));
    assert!(failed.iter().any(|f| f == "E"), "{failed:?}");
    // One of Kane's eight equations given a small extra inertia term.
    let kane = "value = \"kane([u_1, u_2, u_3, u_4, u_5, u_6, u_7, u_8])\"";
    let rows: Vec<String> = (1..=8)
        .map(|r| match r {
            5 => "K_raw.5 + m_F*r_F^2*u_5'/1000".to_string(),
            _ => format!("K_raw.{r}"),
        })
        .collect();
    let text = mutate(
        NONLINEAR,
        kane,
        &format!("value = \"list({})\"", rows.join(", ")),
    );
    let text = mutate(
        &text,
        "[[step]]\nname = \"K_all\"",
        &format!("[[step]]\nname = \"K_raw\"\n{kane}\nshow = false\n\n[[step]]\nname = \"K_all\""),
    );
    let (_, failed) = verified(&text, &options(2));
    has(&failed, &["K_all", "M_all"]);
}
