//! Named proptest strategies for the simulation tests.

use proptest::prelude::*;

/// Principal moments of a physical body: positive, triangle inequality,
/// pairwise distinct by at least 5 % (so the elliptic form applies).
pub fn asymmetric_moments() -> impl Strategy<Value = [f64; 3]> {
    (0.5f64..2.0, 0.05f64..0.45, 0.05f64..0.45).prop_filter_map("triangle", |(a, d1, d2)| {
        let b = a * (1.0 + d1);
        let c = b * (1.0 + d2);
        (a + b >= c).then_some([a, b, c])
    })
}

/// A body angular velocity of moderate size, away from zero.
pub fn angular_velocity() -> impl Strategy<Value = [f64; 3]> {
    prop::array::uniform3(-3.0f64..3.0)
        .prop_filter("not tiny", |w| w.iter().map(|x| x * x).sum::<f64>() > 0.1)
}

/// An elliptic parameter m in [0, 1).
pub fn parameter() -> impl Strategy<Value = f64> {
    0.0f64..0.999
}

/// An argument of moderate size.
pub fn argument() -> impl Strategy<Value = f64> {
    -20.0f64..20.0
}
