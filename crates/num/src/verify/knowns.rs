//! The symbols of `[[known]]` bound from the quantities they name,
//! measured on the drawn particles (with their time derivatives, for point
//! and frame kinematics): what the declared check and the claims' checks
//! both start from.

use hdot_sym::atom::Atom;
use hdot_sym::derivation::physics::Meaning;
use hdot_sym::derivation::{Derivation, Value};
use nalgebra::Vector3;

use super::VerifyError;
use super::draw::Draw;
use super::means::{frame_index, meaning_value};
use super::world::{ORDERS, World, mat_t_vec, vee};
use crate::bind::{Values, bind_all, nth};

/// The model at `values` once the symbols of `[[known]]` are bound into
/// `values` from the model before them ([`bind_knowns`]); one model when
/// the file declares none.
pub(crate) fn world_with_knowns<'d>(
    d: &'d Derivation,
    draw: &'d Draw,
    values: &mut Values,
    coordinates: &[Atom],
) -> Result<World<'d>, VerifyError> {
    if !d.physics.knowns.is_empty() {
        let w = World::build(d, draw, values, coordinates)?;
        bind_knowns(d, &w, values)?;
    }
    World::build(d, draw, values, coordinates)
}

/// Binds the symbols of `[[known]]` from the measured quantities (and
/// their time derivatives, for point and frame kinematics).
pub(crate) fn bind_knowns(
    d: &Derivation,
    w: &World<'_>,
    values: &mut Values,
) -> Result<(), VerifyError> {
    for k in &d.physics.knowns {
        let jets: Vec<[f64; 3]> = match (&k.value, &k.meaning) {
            (Value::Vector(_, f), m) => {
                let fi = frame_index(d, f);
                let x = kinematic_jet(w, m);
                match x {
                    Some(x) => {
                        let rf = &w.frames[fi];
                        let c = mat_t_vec(rf, &x);
                        (0..3).map(|i| [c[0][i], c[1][i], c[2][i]]).collect()
                    }
                    None => {
                        let (v, _) = meaning_value(w, m)?;
                        let v = w.frames[fi][0].transpose() * v.vector();
                        (0..3).map(|i| [v[i], f64::NAN, f64::NAN]).collect()
                    }
                }
            }
            // A scalar, or a matrix entry by entry (row by row).
            (_, m) => meaning_value(w, m)?
                .0
                .components(w, None)
                .into_iter()
                .map(|x| [x, f64::NAN, f64::NAN])
                .collect(),
        };
        let (_, size) = meaning_value(w, &k.meaning)?;
        for (p, jet) in k.value.components().into_iter().zip(jets) {
            let atoms: Vec<Atom> = p
                .atoms()
                .into_iter()
                .filter(|a| !values.bound(*a))
                .collect();
            bind_all(
                d,
                values,
                vec![(p.clone(), jet[0], size, format!("the known {}", k.text))],
            )?;
            // Derivatives: p = c s + r with c and r constant.
            if let [s] = atoms.as_slice()
                && p.atoms().iter().all(|a| *a == *s || !a.is_time_dependent())
                && s.is_time_dependent()
            {
                let (c, _) = values.eval(&p.partial(*s))?;
                for (n, x) in jet.iter().enumerate().skip(1) {
                    if x.is_finite() {
                        values.set(nth(*s, n as u32), x / c, size / c.abs());
                    }
                }
            }
        }
    }
    Ok(())
}

/// The jet (N's axes, orders 0..2) of a point-kinematics or angular-velocity
/// meaning.
fn kinematic_jet(w: &World<'_>, m: &Meaning) -> Option<[Vector3<f64>; ORDERS]> {
    use hdot_sym::derivation::physics::{Arg, Quantity};
    let Meaning::Quantity(q, args) = m else {
        return None;
    };
    let pt = |a: &Arg| match a {
        Arg::Point(p) => w.points[p].r,
        _ => unreachable!("validated"),
    };
    let z = Vector3::zeros();
    Some(match q {
        Quantity::Position => {
            let (p, o) = (pt(&args[0]), pt(&args[1]));
            std::array::from_fn(|n| p[n] - o[n])
        }
        Quantity::Velocity => {
            let p = pt(&args[0]);
            [p[1], p[2], p[3], z]
        }
        Quantity::AngularVelocity => {
            let Arg::Frame(f) = args[0] else {
                unreachable!("validated")
            };
            let r = &w.frames[f];
            [
                vee(&(r[1] * r[0].transpose())),
                vee(&(r[2] * r[0].transpose() + r[1] * r[1].transpose())),
                vee(&(r[3] * r[0].transpose()
                    + 2.0 * r[2] * r[1].transpose()
                    + r[1] * r[2].transpose())),
                z,
            ]
        }
        _ => return None,
    })
}
