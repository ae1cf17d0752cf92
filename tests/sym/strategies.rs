//! Named proptest strategies for the symbolic core.

use hdot_sym::{Atom, Expr, Node, Rational, Symbols};
use proptest::prelude::*;

/// The symbols random expressions draw from.
pub fn symbols() -> Symbols {
    Symbols::parse_decl(&["a", "b", "I_x", "m"], &["theta", "phi", "omega"])
}

/// A random atom: a constant, a time symbol with derivative order 0–2, or sin/cos of an angle.
pub fn atom() -> impl Strategy<Value = Atom> {
    prop_oneof![
        prop::sample::select(vec!["a", "b", "I_x", "m"]).prop_map(Atom::constant),
        (prop::sample::select(vec!["theta", "phi", "omega"]), 0u32..3)
            .prop_map(|(n, k)| Atom::time(n, k)),
        (prop::sample::select(vec!["theta", "phi"]), any::<bool>()).prop_map(|(n, s)| {
            let q = Atom::time(n, 0);
            if s {
                Atom::sin(q).unwrap()
            } else {
                Atom::cos(q).unwrap()
            }
        }),
    ]
}

/// A tree shape, turned into an [`Expr`] by [`build`].
#[derive(Clone, Debug)]
pub enum Tree {
    Num(i64, i64),
    Atom(Atom),
    Add(Vec<Tree>),
    Mul(Vec<Tree>),
    Neg(Box<Tree>),
    Pow(Box<Tree>, u32),
}

/// A random expression tree of bounded depth and width.
pub fn tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        (0i64..7, 1i64..4).prop_map(|(n, d)| Tree::Num(n, d)),
        atom().prop_map(Tree::Atom),
        atom().prop_map(Tree::Atom),
    ];
    leaf.prop_recursive(4, 24, 3, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 2..4).prop_map(Tree::Add),
            prop::collection::vec(inner.clone(), 2..4).prop_map(Tree::Mul),
            inner.clone().prop_map(|t| Tree::Neg(Box::new(t))),
            (inner, 2u32..4).prop_map(|(t, e)| Tree::Pow(Box::new(t), e)),
        ]
    })
}

/// Builds the tree into a flat expression store.
pub fn build(t: &Tree) -> Expr {
    fn go(t: &Tree, e: &mut Expr) -> hdot_sym::expr::Id {
        match t {
            Tree::Num(n, d) => e.push(Node::Num(Rational::new(*n, *d).unwrap())),
            Tree::Atom(a) => e.push(Node::Atom(*a)),
            Tree::Add(v) => {
                let ids = v.iter().map(|c| go(c, e)).collect();
                e.push(Node::Add(ids))
            }
            Tree::Mul(v) => {
                let ids = v.iter().map(|c| go(c, e)).collect();
                e.push(Node::Mul(ids))
            }
            Tree::Neg(c) => {
                let id = go(c, e);
                e.push(Node::Neg(id))
            }
            Tree::Pow(c, k) => {
                let id = go(c, e);
                e.push(Node::Pow(id, *k as i32))
            }
        }
    }
    let mut e = Expr::new();
    go(t, &mut e);
    e
}

/// A random expression tree as an [`Expr`].
pub fn expr() -> impl Strategy<Value = Expr> {
    tree().prop_map(|t| build(&t))
}

/// Values for the atoms at a random point: angles in (−π, π), rates and
/// constants in (−2, 2); sin/cos consistent with their angle.
pub fn point() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-2.0f64..2.0, 16)
}

/// Evaluates an atom at a point drawn by [`point`].
pub fn value_at(p: &[f64], a: Atom) -> f64 {
    use hdot_sym::AtomKind;
    let idx = |name: &str, order: u32| {
        let base = ["a", "b", "I_x", "m", "theta", "phi", "omega"]
            .iter()
            .position(|n| *n == name)
            .unwrap();
        (base * 2 + order as usize) % p.len()
    };
    match a.kind() {
        AtomKind::Var { name, order, .. } => p[idx(name, order)],
        AtomKind::Sin(q) => (p[idx(q.name(), 0)] * 1.5).sin(),
        AtomKind::Cos(q) => (p[idx(q.name(), 0)] * 1.5).cos(),
        AtomKind::Sum { .. } => unreachable!("the strategies draw no sum atoms"),
    }
}
