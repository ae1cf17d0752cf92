//! The multibody derivations bundled for issue 24 (item 7): every step
//! with a particle meaning compared on the particles — the angular
//! velocity in the speeds, the contact's material point at rest, the
//! dependent speeds against the contact point's measured velocity, Kane's
//! equations of the torque-free body, the energy and the power balance
//! (`energy_rate`), the gyrostat's momentum with the rotor's h stated
//! (`applied` of a vector) and its rates solved for u̇. The two new
//! meanings are also tried on files written for these tests
//! (`derivations/pendulum-power.toml`, `derivations/rotor-turntable.toml`).
//! A wrong step fails by name.

use hdot_num::verify::Options;

use super::verified;

const DISK: &str = include_str!("../../derivations/disk-rolling-on-plane.toml");
const GYROSTAT: &str = include_str!("../../derivations/gyrostat.toml");
const QUATERNION: &str = include_str!("../../derivations/torque-free-quaternion.toml");
const PENDULUM: &str = include_str!("derivations/pendulum-power.toml");
const TURNTABLE: &str = include_str!("derivations/rotor-turntable.toml");

fn options() -> Options {
    Options { draws: 12, seed: 7 }
}

/// `text` with `from` replaced by `to`, which occurs exactly once.
fn mutate(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "{from}");
    text.replace(from, to)
}

/// `text`'s compared steps include `wanted`, and none fails.
fn passes_with(text: &str, wanted: &[&str]) {
    let (compared, failed) = verified(text, &options());
    assert!(failed.is_empty(), "failed: {failed:?}");
    for w in wanted {
        assert!(compared.iter().any(|c| c == w), "{w} not in {compared:?}");
    }
}

/// The steps of `text` that fail.
fn failing(text: &str) -> Vec<String> {
    verified(text, &options()).1
}

#[test]
fn the_rolling_disks_steps_agree_with_the_particles() {
    passes_with(
        DISK,
        &[
            "omega",
            "contact",
            "contact_z",
            "no_slip",
            "dependent",
            "v_G",
            "E",
            "dE",
        ],
    );
}

#[test]
fn dependent_speeds_swapped_are_rejected() {
    // u₄ and u₅ solved in the wrong order: C's velocity along x is not u₅
    // (the centre's velocity, the energy and its rate, written with them,
    // fail too; E both as measured and as conserved).
    let wrong = mutate(
        DISK,
        "solve(no_slip, [u_4, u_5])",
        "list(solve(no_slip, [u_4, u_5]).2, solve(no_slip, [u_4, u_5]).1)",
    );
    assert_eq!(failing(&wrong), ["dependent", "v_G", "E", "dE", "E"]);
}

#[test]
fn a_wrong_potential_energy_is_rejected() {
    // G's height taken as r, not r cos θ.
    let wrong = mutate(DISK, "+ m*g*r*cos(theta)\"", "+ m*g*r\"");
    let failed = failing(&wrong);
    assert!(failed.iter().any(|f| f == "E"), "{failed:?}");
}

#[test]
fn the_gyrostats_angular_velocity_in_the_speeds_agrees_with_the_particles() {
    passes_with(GYROSTAT, &["omega", "H", "euler", "rates"]);
    // ω written by hand with two body rates exchanged.
    let wrong = mutate(
        GYROSTAT,
        "value = \"in_speeds(omega_q)\"",
        "value = \"[u_2, u_1, u_3] in B\"",
    );
    let failed = failing(&wrong);
    assert!(failed.iter().any(|f| f == "omega"), "{failed:?}");
}

#[test]
fn kanes_equations_of_the_quaternion_body_agree_with_the_particles() {
    passes_with(QUATERNION, &["omega", "K", "same", "M", "f"]);
    // The third equation with its sign flipped: Kane's equations from the
    // wrong inertia forces fail, and so does their agreement with Euler's.
    let wrong = mutate(
        QUATERNION,
        "value = \"kane([u_1, u_2, u_3])\"",
        "value = \"list(kane([u_1, u_2, u_3]).1, kane([u_1, u_2, u_3]).2, -kane([u_1, u_2, u_3]).3)\"",
    );
    let failed = failing(&wrong);
    for s in ["K", "same", "M", "f"] {
        assert!(failed.iter().any(|f| f == s), "{s} not in {failed:?}");
    }
}

#[test]
fn the_gyrostats_rates_with_the_rotors_momentum_wrong_are_rejected() {
    // h with its sign slipped: the momentum, its rate and the body rates'
    // rates solved from it all fail (the rates measured as the moment the
    // particles need, less the rotor's ω × h, vanishing at the solved u̇).
    let wrong = mutate(
        GYROSTAT,
        "value = \"principal(I1, I2, I3)*omega + [0, 0, h] in B\"",
        "value = \"principal(I1, I2, I3)*omega - [0, 0, h] in B\"",
    );
    let failed = failing(&wrong);
    for s in ["H", "euler", "rates"] {
        assert!(failed.iter().any(|f| f == s), "{s} not in {failed:?}");
    }
}

#[test]
fn the_energys_rate_and_the_power_balance_agree_with_the_particles() {
    passes_with(PENDULUM, &["K", "E", "dE", "power"]);
    // The weight's potential with its sign slipped, and the rotation's
    // energy with the wrong moment: the energy, its rate and the balance
    // fail; Kane's equation, not built on E, passes.
    for (from, to) in [
        ("- m*g*l*cos(theta)\"", "+ m*g*l*cos(theta)\""),
        ("+ I_z*u^2/2", "+ I_x*u^2/2"),
    ] {
        assert_eq!(failing(&mutate(PENDULUM, from, to)), ["E", "dE", "power"]);
    }
}

#[test]
fn a_stated_vector_enters_the_momentum_and_its_rate() {
    passes_with(TURNTABLE, &["H", "M"]);
    // The rotor's axis taken as y: both fail.
    let wrong = mutate(TURNTABLE, "[h, 0, 0] in B\"", "[0, h, 0] in B\"");
    assert_eq!(failing(&wrong), ["H", "M"]);
    // The rate without the transport term: the gyroscopic h ψ̇ y is lost.
    let wrong = mutate(TURNTABLE, "value = \"dt(H)\"", "value = \"dt_rel(H)\"");
    assert_eq!(failing(&wrong), ["M"]);
}

#[test]
fn the_bicycles_power_balance_with_a_wrong_energy_is_rejected() {
    // The front wheel's translational kinetic energy a third too small:
    // dE/dt − Σ u_r K_r is no longer zero on the particles.
    let wrong = mutate(
        include_str!("../../derivations/bicycle-nonlinear.toml"),
        "m_F*dot(velocity(W_F), velocity(W_F))/2",
        "m_F*dot(velocity(W_F), velocity(W_F))/3",
    );
    let (_, failed) = verified(&wrong, &Options { draws: 2, seed: 7 });
    assert!(failed.iter().any(|f| f == "power"), "{failed:?}");
}
