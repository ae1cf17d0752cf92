//! The `means` language of verification as a registry (STYLE.md 14):
//! every combinator of measured quantities is one self-describing entry —
//! its name, how it is called, one line of documentation and its
//! evaluation on the particles with its scale — next to the quantities'
//! own registry ([`super::quantities::REGISTRY`]). The file is parsed by
//! `hdot-sym` (`derivation/physics.rs`, which holds the names and
//! argument kinds its parser needs); what a meaning *is* lives here, and
//! the two tables of `docs/derivation-format.md` (*Meanings*) are
//! generated from these lists ([`quantities_table`],
//! [`combinators_table`]; a test keeps them in step).

use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::{Meaning, Shape};
use nalgebra::{Matrix3, Vector3};

use super::quantities::{Measured, REGISTRY, measure};
use super::world::World;
use super::{TOLERANCE_ULPS, VerifyError, linear};
use crate::bind::Values;

/// One combinator of the `means` language.
pub struct Combinator {
    /// Its name in `means` (`+` for a sum, `*` for a scalar factor).
    pub name: &'static str,
    /// How it is called, for the docs: `rate(e', X)`.
    pub call: &'static str,
    /// What it means and how it is measured (Markdown), for the docs.
    pub doc: &'static str,
    /// Its value on the particles of a world, and the magnitudes its
    /// round-off is relative to.
    pub eval: fn(&World<'_>, &Meaning) -> Valued,
}

/// A measured meaning and the magnitudes its round-off is relative to.
pub type Valued = Result<(Val, f64), VerifyError>;

/// Every combinator, in the order of the docs table.
pub static COMBINATORS: &[Combinator] = &[
    Combinator {
        name: "+",
        call: "X + Y, X - Y",
        doc: "the sum of meanings of one shape, with number factors (`2*X`, `-X/3`)",
        eval: sum,
    },
    Combinator {
        name: "*",
        call: "e * X, X / e",
        doc: "a meaning times a scalar expression of the file's symbols, evaluated at the drawn values (`-X/Omega^2`)",
        eval: scaled,
    },
    Combinator {
        name: "list",
        call: "list(X1, X2, …)",
        doc: "a list of scalar meanings",
        eval: list,
    },
    Combinator {
        name: "along",
        call: "along(V, e)",
        doc: "the component of the vector meaning V along a vector expression e (`[0, 0, 1] in B`)",
        eval: along,
    },
    Combinator {
        name: "applied",
        call: "applied(e)",
        doc: "a scalar or a vector the file states rather than measures (an applied torque `M_a`, a given generalized force; a rotor's momentum `[0, 0, h] in B`, which is not a declared body, and its rate), evaluated at the drawn values",
        eval: applied,
    },
    Combinator {
        name: "solves",
        call: "solves(X)",
        doc: "of a step `solve(eq, [q1'', …])` (a list of accelerations): X (a vector or `list(…)` of quantities) evaluated with those accelerations must vanish (its components in N)",
        eval: inner,
    },
    Combinator {
        name: "mass_matrix",
        call: "mass_matrix(X, [q1'', …])",
        doc: "of a step `mass_matrix(eq, [q1'', …])`: column j is X at q̈ = e_j minus X at q̈ = 0 (X a scalar or a `list(…)`); for the rates of generalized speeds `[u1', …]`, the dependent speeds' rates and the coordinates' accelerations follow them through the constraint rows and `[kinematics]`",
        eval: inner,
    },
    Combinator {
        name: "forcing",
        call: "forcing(X, [q1'', …])",
        doc: "of a step `forcing(eq, [q1'', …])`: −X at q̈ = 0 (at u̇ = 0 for speeds, as above)",
        eval: inner,
    },
    Combinator {
        name: "linear",
        call: "linear(X)",
        doc: "of a step such as `linearize(M)`: X with the disturbance zero, plus X's first-order part in it: the disturbance scaled by h, `4/3 [X(½) − X(−½)] − 1/6 [X(1) − X(−1)]` (central differences, Richardson-extrapolated)",
        eval: linear_part,
    },
    Combinator {
        name: "rate",
        call: "rate(e', X), rate(e'', X), …",
        doc: "of a step such as `solve(L.3, epsilon_3')` (ε̈ after eliminating the other rates): the first-order part of X is `X₀ + P ε + Q ε̇` (P, Q measured column by column as for `linear`); X = 0 gives `ε̇ = −Q⁻¹ (X₀ + P ε)`, and, differentiating the linear system, `ε⁽ⁿ⁾ = J ε⁽ⁿ⁻¹⁾` with `J = −Q⁻¹ P`; at the drawn ε. X has one component per small symbol (a vector for three)",
        eval: rate,
    },
    Combinator {
        name: "coefficient",
        call: "coefficient(X, e)",
        doc: "of a step such as `coeff(eps2_acc, epsilon_2)`: the first-order part of the scalar X in e alone, at e = 0",
        eval: coefficient,
    },
    Combinator {
        name: "sign",
        call: "sign(X)",
        doc: "of a step `sign(…)`, a verdict ±1: the sign of the measured scalar X (0 within round-off)",
        eval: sign,
    },
];

/// The registry entry of a meaning that is not a quantity.
fn combinator(m: &Meaning) -> &'static Combinator {
    let name = match m {
        Meaning::Quantity(..) => unreachable!("a quantity is measured by its own entry"),
        Meaning::Sum(_) => "+",
        Meaning::Scaled(..) => "*",
        Meaning::List(_) => "list",
        Meaning::Along(..) => "along",
        Meaning::Applied(_) | Meaning::AppliedVector(..) => "applied",
        Meaning::Solves(_) => "solves",
        Meaning::MassMatrix(..) => "mass_matrix",
        Meaning::Forcing(..) => "forcing",
        Meaning::Linear(_) => "linear",
        Meaning::Rate(..) => "rate",
        Meaning::Coefficient(..) => "coefficient",
        Meaning::Sign(_) => "sign",
    };
    COMBINATORS
        .iter()
        .find(|c| c.name == name)
        .expect("every combinator is in the registry")
}

/// The quantity table of `docs/derivation-format.md`, as Markdown rows.
pub fn quantities_table() -> String {
    let mut s =
        String::from("| quantity | shape | measured on the particles as |\n|---|---|---|\n");
    for m in REGISTRY {
        let shape = match m.quantity.sig().shape {
            Shape::Scalar => "scalar",
            Shape::Vector => "vector",
            Shape::Matrix => "matrix",
            Shape::List(_) => "list",
        };
        s.push_str(&format!("| `{}` | {shape} | {} |\n", m.call, m.doc));
    }
    s
}

/// The combinator table of `docs/derivation-format.md`, as Markdown rows.
pub fn combinators_table() -> String {
    let mut s = String::from("| meaning | measured as |\n|---|---|\n");
    for c in COMBINATORS {
        s.push_str(&format!("| `{}` | {} |\n", c.call, c.doc));
    }
    s
}

/// A measured meaning: a vector in N's axes, a scalar, a matrix in its
/// frame's axes or a list; and its scale.
#[derive(Clone, Debug, PartialEq)]
pub enum Val {
    /// A scalar.
    Scalar(f64),
    /// A vector, N's axes.
    Vector(Vector3<f64>),
    /// A matrix, in the axes of the frame its quantity names.
    Matrix(Matrix3<f64>),
    /// A list of scalars.
    List(Vec<f64>),
}

impl Val {
    pub(crate) fn vector(&self) -> Vector3<f64> {
        match self {
            Val::Vector(v) => *v,
            _ => unreachable!("shapes are validated"),
        }
    }

    pub(crate) fn scalar(&self) -> f64 {
        match self {
            Val::Scalar(v) => *v,
            _ => unreachable!("shapes are validated"),
        }
    }

    pub(crate) fn scaled(&self, c: f64) -> Val {
        match self {
            Val::Scalar(x) => Val::Scalar(c * x),
            Val::Vector(v) => Val::Vector(c * v),
            Val::Matrix(m) => Val::Matrix(c * m),
            Val::List(l) => Val::List(l.iter().map(|x| c * x).collect()),
        }
    }

    pub(crate) fn add(&self, o: &Val) -> Val {
        match (self, o) {
            (Val::Scalar(a), Val::Scalar(b)) => Val::Scalar(a + b),
            (Val::Vector(a), Val::Vector(b)) => Val::Vector(a + b),
            (Val::Matrix(a), Val::Matrix(b)) => Val::Matrix(a + b),
            (Val::List(a), Val::List(b)) => {
                Val::List(a.iter().zip(b).map(|(x, y)| x + y).collect())
            }
            _ => unreachable!("shapes are validated"),
        }
    }

    /// A value of this shape from its components (as [`Val::components`]
    /// gives them without a frame).
    pub(crate) fn like(&self, c: &[f64]) -> Val {
        match self {
            Val::Scalar(_) => Val::Scalar(c[0]),
            Val::Vector(_) => Val::Vector(Vector3::from_column_slice(c)),
            Val::Matrix(_) => Val::Matrix(Matrix3::from_row_slice(c)),
            Val::List(_) => Val::List(c.to_vec()),
        }
    }

    /// Components, a vector in the axes of `frame`.
    pub(crate) fn components(&self, w: &World<'_>, frame: Option<usize>) -> Vec<f64> {
        match self {
            Val::Scalar(x) => vec![*x],
            Val::Vector(v) => {
                let r = frame.map_or(Matrix3::identity(), |f| w.frames[f][0]);
                (r.transpose() * v).iter().copied().collect()
            }
            Val::Matrix(m) => m.transpose().iter().copied().collect(),
            Val::List(l) => l.clone(),
        }
    }
}

/// The value of a meaning on the particles of `w`, and its scale.
pub(crate) fn meaning_value(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::Quantity(q, args) = m else {
        return (combinator(m).eval)(w, m);
    };
    let (v, s) = (measure(*q).compute)(w, args)?;
    Ok((
        match v {
            Measured::Scalar(x) => Val::Scalar(x),
            Measured::Vector(v) => Val::Vector(v),
            Measured::Matrix(m) => Val::Matrix(m),
        },
        s,
    ))
}

fn sum(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::Sum(terms) = m else {
        unreachable!("the entry of a sum")
    };
    let mut acc: Option<Val> = None;
    let mut scale = 0.0;
    for (c, t) in terms {
        let c = c.to_f64();
        let (v, s) = meaning_value(w, t)?;
        let v = v.scaled(c);
        scale += c.abs() * s;
        acc = Some(match acc {
            None => v,
            Some(a) => a.add(&v),
        });
    }
    Ok((acc.expect("a sum has terms"), scale))
}

fn scaled(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::Scaled(p, x) = m else {
        unreachable!("the entry of a factor")
    };
    let (c, cs) = w.values.eval(p)?;
    let (v, s) = meaning_value(w, x)?;
    Ok((v.scaled(c), cs * s))
}

fn list(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::List(items) = m else {
        unreachable!("the entry of list")
    };
    let mut out = Vec::new();
    let mut scale: f64 = 0.0;
    for it in items {
        let (v, s) = meaning_value(w, it)?;
        out.push(v.scalar());
        scale = scale.max(s);
    }
    Ok((Val::List(out), scale))
}

fn along(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::Along(x, e, f) = m else {
        unreachable!("the entry of along")
    };
    let (v, s) = meaning_value(w, x)?;
    let fi = frame_index(w.d, f);
    let mut values_e = Vec::new();
    for c in &e.0 {
        values_e.push(w.values.eval(c)?.0);
    }
    let e = w.frames[fi][0] * Vector3::new(values_e[0], values_e[1], values_e[2]);
    Ok((Val::Scalar(v.vector().dot(&e)), s * e.norm()))
}

fn applied(w: &World<'_>, m: &Meaning) -> Valued {
    match m {
        Meaning::Applied(p) => {
            let (v, s) = w.values.eval(p)?;
            Ok((Val::Scalar(v), s))
        }
        Meaning::AppliedVector(e, f) => {
            let (mut c, mut s) = ([0.0; 3], 0.0);
            for (k, p) in e.0.iter().enumerate() {
                let (v, size) = w.values.eval(p)?;
                c[k] = v;
                s += size;
            }
            let r = w.frames[frame_index(w.d, f)][0];
            Ok((Val::Vector(r * Vector3::from(c)), s))
        }
        _ => unreachable!("the entry of applied"),
    }
}

/// `solves`, `mass_matrix` and `forcing` measure X; the step's comparison
/// (`declared::compare_step`) varies the accelerations.
fn inner(w: &World<'_>, m: &Meaning) -> Valued {
    let (Meaning::Solves(x) | Meaning::MassMatrix(x, _) | Meaning::Forcing(x, _)) = m else {
        unreachable!("the entry of solves, mass_matrix or forcing")
    };
    meaning_value(w, x)
}

fn linear_part(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::Linear(x) = m else {
        unreachable!("the entry of linear")
    };
    let shape = meaning_value(w, x)?.0;
    let (v, s) = linear::linear(&at(w, x), &w.values, &w.d.physics.small)?;
    Ok((shape.like(&v), s))
}

fn rate(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::Rate(e, x) = m else {
        unreachable!("the entry of rate")
    };
    let (v, s) = linear::rate(&at(w, x), &w.values, &w.d.physics.small, *e, &w.d.name)?;
    Ok((Val::Scalar(v), s))
}

fn coefficient(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::Coefficient(x, e) = m else {
        unreachable!("the entry of coefficient")
    };
    let (v, s) = linear::coefficient(&at(w, x), &w.values, *e)?;
    Ok((Val::Scalar(v), s))
}

fn sign(w: &World<'_>, m: &Meaning) -> Valued {
    let Meaning::Sign(x) = m else {
        unreachable!("the entry of sign")
    };
    let (v, s) = meaning_value(w, x)?;
    let v = v.scalar();
    let sign = if v.abs() <= TOLERANCE_ULPS * f64::EPSILON * s {
        0.0
    } else {
        v.signum()
    };
    Ok((Val::Scalar(sign), 1.0))
}

/// `x` measured at other values of the symbols (the same draw): its
/// components (N's axes for a vector) and scale.
fn at<'a>(
    w: &'a World<'_>,
    x: &'a Meaning,
) -> impl Fn(&Values) -> Result<(Vec<f64>, f64), VerifyError> + 'a {
    move |values: &Values| {
        w.measured_at(values, x, |w2| {
            let (v, s) = meaning_value(w2, x)?;
            Ok((v.components(w2, None), s))
        })
    }
}

/// What a meaning is measured as, for reports.
pub(crate) fn against_of(m: &Meaning) -> String {
    match m {
        Meaning::Linear(x) => format!(
            "X(0) + central differences in the small symbols, X = {}",
            against_of(x)
        ),
        Meaning::Rate(e, x) => format!(
            "{e} from −Q⁻¹(X₀ + P ε) (and J = −Q⁻¹P), P, Q the first-order part of X = {}",
            against_of(x)
        ),
        Meaning::Coefficient(x, e) => {
            format!("central differences in {e} of {}", against_of(x))
        }
        Meaning::Sign(x) => format!("the sign of {}", against_of(x)),
        Meaning::Applied(_) | Meaning::AppliedVector(..) => "the value the file states".into(),
        Meaning::Scaled(_, x) => against_of(x),
        Meaning::Sum(terms) => terms
            .iter()
            .map(|(_, x)| against_of(x))
            .fold(Vec::new(), |mut v, s| {
                if !v.contains(&s) {
                    v.push(s);
                }
                v
            })
            .join(", "),
        _ => m
            .quantities()
            .iter()
            .map(|(q, _)| measure(*q).measured_as)
            .fold(Vec::new(), |mut v, s| {
                if !v.contains(&s) {
                    v.push(s);
                }
                v
            })
            .join(", "),
    }
}

/// The index of the frame named `f` (validated by `hdot-sym`).
pub(crate) fn frame_index(d: &Derivation, f: &str) -> usize {
    d.frames
        .iter()
        .position(|x| x.name == f)
        .expect("frame exists")
}
