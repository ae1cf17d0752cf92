//! Convergence: observed orders and the cheapest discretisation.

use hdot_num::Primitive;
use hdot_num::convergence::{
    METHODS, cell_ladder, cheapest_meeting, error_of, observed_orders, sweep,
};
use hdot_num::{Discretization, Method};

#[test]
fn midpoint_order_is_two_on_the_disk_and_cone() {
    for shape in [
        Primitive::Disk { radius: 0.7 },
        Primitive::Cone {
            radius: 0.5,
            height: 1.2,
        },
    ] {
        let pts = sweep(&shape, Method::Midpoint, 40_000);
        let orders: Vec<f64> = observed_orders(&pts).into_iter().flatten().collect();
        let last = *orders.last().unwrap();
        assert!((last - 2.0).abs() < 0.1, "{shape:?}: orders {orders:?}");
    }
}

#[test]
fn gauss_legendre_beats_midpoint_at_equal_cost() {
    let shape = Primitive::Cylinder {
        radius: 0.4,
        length: 1.5,
    };
    // same particle count: 16 midpoint cells vs 8 cells × 2 points
    let m = error_of(&shape, &Discretization::midpoint(16));
    let g = error_of(&shape, &Discretization::gauss(8, 2));
    assert_eq!(m.particles, g.particles);
    assert!(g.error < m.error / 10.0, "{} vs {}", g.error, m.error);
}

#[test]
fn cheapest_discretisation_meets_the_tolerance_and_nothing_cheaper_does() {
    let shape = Primitive::Sphere { radius: 0.6 };
    let tol = 1e-6;
    let best = cheapest_meeting(&shape, tol, &METHODS, 1_000_000).unwrap();
    assert!(best.error <= tol);
    // every cheaper rung of the cell ladder, in every method, misses it
    for &method in &METHODS {
        for cells in cell_ladder().take_while(|&c| c <= 64) {
            let d = Discretization { method, cells };
            if hdot_num::discretize::particle_count(&shape, &d) >= best.particles {
                continue;
            }
            let p = error_of(&shape, &d);
            {
                assert!(p.error > tol, "{d:?} is cheaper and meets tol: {}", p.error);
            }
        }
    }
}
