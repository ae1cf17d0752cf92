use hdot_sim::elliptic::{agm, ellip_f, ellip_k, sncndn};
use proptest::prelude::*;

use crate::strategies::{argument, parameter};

const EPS: f64 = f64::EPSILON;

macro_rules! value_cases {
    ($($name:ident: $got:expr => $want:expr, $ulps:expr;)*) => {$(
        #[test]
        fn $name() {
            let (got, want): (f64, f64) = ($got, $want);
            assert!((got - want).abs() <= $ulps * EPS * want.abs().max(1.0),
                "{} = {got:e}, expected {want:e}", stringify!($got));
        }
    )*};
}

// Known values (A&S tables, DLMF 19.6, 22.5).
value_cases! {
    k_at_zero: ellip_k(0.0) => std::f64::consts::FRAC_PI_2, 2.0;
    k_at_half: ellip_k(0.5) => 1.854_074_677_301_372, 4.0;
    k_at_0_9: ellip_k(0.9) => 2.578_092_113_348_173, 4.0;
    agm_1_sqrt2: agm(1.0, std::f64::consts::SQRT_2) => 1.198_140_234_735_592_2, 4.0;
    sn_at_k: sncndn(ellip_k(0.7), 0.7).0 => 1.0, 8.0;
    dn_at_k: sncndn(ellip_k(0.7), 0.7).2 => (0.3f64).sqrt(), 8.0;
    sn_m0_is_sin: sncndn(1.3, 0.0).0 => 1.3f64.sin(), 2.0;
    sn_m1_is_tanh: sncndn(1.3, 1.0).0 => 1.3f64.tanh(), 2.0;
    cn_m1_is_sech: sncndn(1.3, 1.0).1 => 1.0 / 1.3f64.cosh(), 2.0;
    f_at_half_pi_is_k: ellip_f(std::f64::consts::FRAC_PI_2, 0.6) => ellip_k(0.6), 8.0;
    f_at_pi_is_2k: ellip_f(std::f64::consts::PI, 0.6) => 2.0 * ellip_k(0.6), 8.0;
}

/// `K(m) = π/2 Σ [(2n)! / (2^{2n} n!²)]² mⁿ`, summed to convergence.
fn k_series(m: f64) -> f64 {
    let mut term = 1.0;
    let mut sum = 1.0;
    for n in 1..2000 {
        let r = (2 * n - 1) as f64 / (2 * n) as f64;
        term *= r * r * m;
        sum += term;
        if term < 1e-18 * sum {
            break;
        }
    }
    std::f64::consts::FRAC_PI_2 * sum
}

#[test]
fn k_agrees_with_its_series() {
    for m in [1e-6, 0.01, 0.1, 0.3, 0.5, 0.7] {
        let (a, b) = (ellip_k(m), k_series(m));
        assert!((a - b).abs() <= 8.0 * EPS * b, "m = {m}: {a} vs {b}");
    }
}

#[test]
fn cn_vanishes_at_k() {
    for m in [0.1, 0.5, 0.9, 0.99] {
        let k = ellip_k(m);
        // cn(K) = 0; near K, cn ≈ −k' (u − K), so the error bound scales with K.
        assert!(sncndn(k, m).1.abs() <= 16.0 * EPS * k, "m = {m}");
    }
}

proptest! {
    #![proptest_config(hdot_tests::proptest_config(256))]

    #[test]
    fn pythagorean_identities(u in argument(), m in parameter()) {
        let (sn, cn, dn) = sncndn(u, m);
        // Round-off grows with |u| (the argument itself carries |u| ε).
        let tol = 16.0 * EPS * (1.0 + u.abs());
        prop_assert!((sn * sn + cn * cn - 1.0).abs() <= tol);
        prop_assert!((dn * dn + m * sn * sn - 1.0).abs() <= tol);
    }

    #[test]
    fn derivatives_match_the_jacobi_system(u in argument(), m in parameter()) {
        // d sn/du = cn dn, by a fourth-order central difference.
        let h = 1e-3;
        let sn = |x: f64| sncndn(x, m).0;
        let d = (sn(u - 2.0 * h) - 8.0 * sn(u - h) + 8.0 * sn(u + h) - sn(u + 2.0 * h)) / (12.0 * h);
        let (_, cn, dn) = sncndn(u, m);
        prop_assert!((d - cn * dn).abs() <= 1e-10 + 1e-12 * u.abs());
    }

    #[test]
    fn f_inverts_the_amplitude(phi in -6.0f64..6.0, m in parameter()) {
        let (sn, cn, _) = sncndn(ellip_f(phi, m), m);
        let tol = 32.0 * EPS * (1.0 + phi.abs() * ellip_k(m));
        prop_assert!((sn - phi.sin()).abs() <= tol);
        prop_assert!((cn - phi.cos()).abs() <= tol);
    }
}
