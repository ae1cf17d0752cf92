//! The value of an expression or step: a scalar, a vector in a frame, a
//! 3×3 matrix, a list (equations, or values labelled by the unknowns they
//! were solved for), or an n × n array (a mass matrix).

use crate::atom::Atom;
use crate::poly::Poly;
use crate::vector::{Mat3, Vec3};

/// The value of a step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Value {
    /// A scalar expression.
    Scalar(Poly),
    /// A vector and the frame its components are expressed in.
    Vector(Vec3, String),
    /// A 3×3 matrix (an inertia tensor, a rotation).
    Matrix(Mat3),
    /// A list of scalars: equations (`list(e1, e2)`), or the values of
    /// unknowns solved for, labelled by those unknowns (`labels` is empty
    /// for an unlabelled list, else as long as `items`).
    List {
        /// The components.
        items: Vec<Poly>,
        /// The unknown each component is the value of (θ̈ for θ̈ = …).
        labels: Vec<Atom>,
    },
    /// An n × m array by rows (a mass matrix).
    Array(Vec<Vec<Poly>>),
}

impl Value {
    /// An unlabelled list.
    pub fn list(items: Vec<Poly>) -> Value {
        Value::List {
            items,
            labels: Vec::new(),
        }
    }

    /// "a scalar", "a vector (in frame B)", … for messages.
    pub fn describe(&self) -> String {
        match self {
            Value::Scalar(_) => "a scalar".into(),
            Value::Vector(_, f) => format!("a vector (in frame {f})"),
            Value::Matrix(_) => "a matrix".into(),
            Value::List { items, .. } => format!("a list of {}", items.len()),
            Value::Array(rows) => format!(
                "a {}×{} array",
                rows.len(),
                rows.first().map_or(0, Vec::len)
            ),
        }
    }

    /// Applies `f` to every component.
    pub fn map(&self, f: &mut dyn FnMut(&Poly) -> Poly) -> Value {
        match self {
            Value::Scalar(p) => Value::Scalar(f(p)),
            Value::Vector(v, fr) => {
                Value::Vector(Vec3([f(&v.0[0]), f(&v.0[1]), f(&v.0[2])]), fr.clone())
            }
            Value::Matrix(m) => Value::Matrix(Mat3(std::array::from_fn(|i| {
                std::array::from_fn(|j| f(&m.0[i][j]))
            }))),
            Value::List { items, labels } => Value::List {
                items: items.iter().map(&mut *f).collect(),
                labels: labels.clone(),
            },
            Value::Array(rows) => Value::Array(
                rows.iter()
                    .map(|r| r.iter().map(&mut *f).collect())
                    .collect(),
            ),
        }
    }

    /// The components, flattened: a scalar; x, y, z; a matrix or an array
    /// by rows; a list in order.
    pub fn components(&self) -> Vec<&Poly> {
        match self {
            Value::Scalar(p) => vec![p],
            Value::Vector(v, _) => v.0.iter().collect(),
            Value::Matrix(m) => m.0.iter().flatten().collect(),
            Value::List { items, .. } => items.iter().collect(),
            Value::Array(rows) => rows.iter().flatten().collect(),
        }
    }

    /// The scalar equations a value stands for when it is set to zero: a
    /// scalar, the three components of a vector, or the items of a list.
    pub fn equations(&self) -> Option<Vec<Poly>> {
        match self {
            Value::Scalar(p) => Some(vec![p.clone()]),
            Value::Vector(v, _) => Some(v.0.to_vec()),
            Value::List { items, .. } => Some(items.clone()),
            Value::Matrix(_) | Value::Array(_) => None,
        }
    }
}
