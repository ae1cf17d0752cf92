//! 10⁶-step energy study (feature `slow-tests`; run it in release:
//! `cargo test --release -p hdot-sim --features slow-tests --test long_run -- --nocapture`).
//! RK4's energy error drifts secularly, the Strang splitting's stays bounded.
#![cfg(feature = "slow-tests")]

use hdot_sim::nalgebra::{UnitQuaternion, Vector3};
use hdot_sim::systems::FreeBody;
use hdot_sim::systems::free::pack;
use hdot_sim::{Limits, Method, Step, integrate};

/// Largest relative energy error in each tenth of a 10⁶-step run.
fn tenths(method: Method, h: f64) -> Vec<f64> {
    let body = FreeBody {
        moments: [0.6, 0.8, 1.0],
        gravity: None,
    };
    let y0 = pack(&UnitQuaternion::identity(), &Vector3::new(3.0, 0.5, -0.9));
    let e0 = body.energy(&y0);
    let n = 1_000_000u64;
    let mut out = vec![0.0f64; 10];
    let mut k = 0u64;
    integrate(
        &body,
        method,
        Step::Fixed(h),
        0.0,
        y0,
        h * n as f64,
        Limits::default(),
        |_, y| {
            let slot = ((k * 10) / (n + 1)) as usize;
            out[slot] = out[slot].max(((body.energy(y) - e0) / e0).abs());
            k += 1;
            Ok(())
        },
    )
    .unwrap();
    out
}

#[test]
fn rk4_drifts_and_the_splitting_does_not_over_a_million_steps() {
    let h = 0.05;
    let rk4 = tenths(Method::Rk4, h);
    let split = tenths(Method::Split2, h);
    println!("h = {h}, 10^6 steps; max |ΔE|/E per tenth of the run");
    println!(
        "rk4:    {:?}",
        rk4.iter().map(|e| format!("{e:.2e}")).collect::<Vec<_>>()
    );
    println!(
        "split2: {:?}",
        split.iter().map(|e| format!("{e:.2e}")).collect::<Vec<_>>()
    );
    // Secular: the last tenth is about ten times the first (≥ 7).
    assert!(rk4[9] >= 7.0 * rk4[0], "{rk4:?}");
    // Bounded: no tenth exceeds the first by more than 10 %.
    assert!(split.iter().all(|e| *e <= 1.1 * split[0]), "{split:?}");
}
