//! The order of factors in a presented term: constant symbols first in
//! the file's or the conventional order (m g l, I′ θ̇), and two members of
//! one cyclic family (x → y → z, 1 → 2 → 3, A → B → C) in cyclic order;
//! and the order of the known terms of an equation after its unknowns
//! (lowest degree in the rates first: ½ m g L sin β + I′ φ̇² sin β cos β).

use smallvec::SmallVec;

use super::gather::is_trig;
use crate::atom::{Atom, AtomKind, AtomMemo};
use crate::expr::{Expr, Id, Node, PrintRanks, PrintTerm};
use crate::poly::Monomial;

/// The ranks of one result's atoms, found once per presentation and read
/// by atom id: their print order ([`PrintRanks`]) and the conventional
/// order of the constants among them ([`constant_class`]), so that the
/// factors of every term and bracket are ordered by integers, not names.
pub(super) struct Ranks {
    /// The print order of the atoms.
    pub(super) print: PrintRanks,
    /// The place of a leading constant in [`constant_class`] order, by
    /// atom id (`u32::MAX` for the other atoms).
    conv: Vec<u32>,
    /// The [`cyclic_place`] of each atom by id, its family numbered.
    place: Vec<Option<NumberedPlace>>,
    /// What each atom is, by id, read for every factor of every term
    /// (see [`Ranks::kind_bits`]): its derivative order, and whether it
    /// is a sine or a cosine (`u32::MAX` for atoms not in the result).
    kind: Vec<u32>,
}

/// The bit of [`Ranks`]' `kind` entry that marks a sine or a cosine.
const TRIG: u32 = 1 << 31;

impl Ranks {
    /// The ranks of the atoms of `monomials`, constants ordered by the
    /// file's `order` first.
    pub(super) fn of<'a>(monomials: impl Iterator<Item = &'a Monomial>, order: &[String]) -> Ranks {
        let print = PrintRanks::of(monomials);
        let mut constants: Vec<Atom> = print
            .atoms()
            .iter()
            .copied()
            .filter(|&a| leading_constant(a))
            .collect();
        // Names are distinct, so the classes are.
        constants.sort_by_cached_key(|&a| constant_class(a, order));
        let mut conv = Vec::new();
        for (k, a) in constants.iter().enumerate() {
            let i = a.id() as usize;
            if i >= conv.len() {
                conv.resize(i + 1, u32::MAX);
            }
            conv[i] = k as u32;
        }
        let mut place = Vec::new();
        let mut families: Vec<&'static str> = Vec::new();
        for &a in print.atoms() {
            if let Some((family, k, o)) = cyclic_place(a) {
                let f = families
                    .iter()
                    .position(|&x| x == family)
                    .unwrap_or_else(|| {
                        families.push(family);
                        families.len() - 1
                    });
                let i = a.id() as usize;
                if i >= place.len() {
                    place.resize(i + 1, None);
                }
                place[i] = Some((f as u32, k as u8, o));
            }
        }
        let mut kind = Vec::new();
        for &a in print.atoms() {
            let i = a.id() as usize;
            if i >= kind.len() {
                kind.resize(i + 1, u32::MAX);
            }
            kind[i] = Ranks::kind_bits(a);
        }
        Ranks {
            print,
            conv,
            place,
            kind,
        }
    }

    /// An atom's entry in the `kind` table: its derivative order (below
    /// bit 31; orders are far smaller), with the [`TRIG`] bit for a sine or
    /// a cosine.
    fn kind_bits(a: Atom) -> u32 {
        let trig = if is_trig(a) { TRIG } else { 0 };
        a.order().min(TRIG - 2) | trig
    }

    /// `a`'s entry in the `kind` table (found when `a` is not in it).
    fn kind_of(&self, a: Atom) -> u32 {
        match self.kind.get(a.id() as usize) {
            Some(&k) if k != u32::MAX => k,
            _ => Ranks::kind_bits(a),
        }
    }

    /// [`is_trig`] of `a`, read from the table.
    pub(super) fn is_trig(&self, a: Atom) -> bool {
        self.kind_of(a) & TRIG != 0
    }

    /// The highest derivative order among the factors of `m` (0 for 1),
    /// read from the table.
    pub(super) fn top(&self, m: &Monomial) -> u32 {
        m.factors()
            .iter()
            .map(|f| self.kind_of(f.0) & !TRIG)
            .max()
            .unwrap_or(0)
    }

    /// Whether every factor's atom is in the table.
    fn covers(&self, fs: &[(Atom, i32)]) -> bool {
        fs.iter().all(|f| self.print.rank(f.0).is_some())
    }

    /// [`cyclic_pair`] with each factor's place read from the table (one
    /// look at each factor; the general path when one is not in it).
    pub(super) fn cyclic_pair(&self, fs: &mut [(Atom, i32)]) {
        if fs.len() < 2 {
            return;
        }
        let mut placed: SmallVec<[(u32, NumberedPlace); 8]> = SmallVec::new();
        for (k, f) in fs.iter().enumerate() {
            if self.print.rank(f.0).is_none() {
                return cyclic_pair(fs);
            }
            if let Some(p) = self.place.get(f.0.id() as usize).copied().flatten() {
                placed.push((k as u32, p));
            }
        }
        pairs_in_order(fs, &placed);
    }

    /// The place of constant `a` in [`constant_class`] order.
    fn conv(&self, a: Atom) -> Option<u32> {
        self.conv
            .get(a.id() as usize)
            .copied()
            .filter(|&r| r != u32::MAX)
    }

    /// [`leading_constant`] of `a`, read from the table when `a` is
    /// among this result's atoms.
    pub(super) fn leads(&self, a: Atom) -> bool {
        if self.print.rank(a).is_some() {
            self.conv(a).is_some()
        } else {
            leading_constant(a)
        }
    }

    /// Whether `a` is a [`leading_constant`] among this result's atoms.
    pub(super) fn is_leading_constant(&self, a: Atom) -> bool {
        self.conv(a).is_some()
    }

    /// Leading constants sorted by [`constant_class`].
    pub(super) fn sort_constants(&self, fs: &mut [(Atom, i32)], order: &[String]) {
        if fs.iter().all(|f| self.conv(f.0).is_some()) {
            fs.sort_unstable_by_key(|f| self.conv(f.0));
        } else {
            fs.sort_by_key(|f| constant_class(f.0, order));
        }
    }
}

/// The degree of a presented term in the rates: time-dependent symbols
/// and constant rates named by Greek letters count, numbers, sin, cos and
/// the constants that lead a product ([`leading_constant`]) do not; a
/// bracket counts as its highest-degree term (`(I_3 − I_2) u_2 u_3` is of
/// degree 2, `½ m g L sin β` of degree 0).
pub(super) fn rate_degree(e: &Expr, id: Id) -> i32 {
    match e.node(id) {
        Node::Num(_) => 0,
        Node::Atom(a) => {
            i32::from(matches!(a.kind(), AtomKind::Var { .. }) && !leading_constant(*a))
        }
        Node::Add(ts) => ts.iter().map(|&t| rate_degree(e, t)).max().unwrap_or(0),
        Node::Mul(ts) => ts.iter().map(|&t| rate_degree(e, t)).sum(),
        Node::Neg(x) => rate_degree(e, *x),
        Node::Pow(x, k) => rate_degree(e, *x).saturating_mul(*k),
    }
}

/// The known terms of a sum that holds an unknown, in the order a
/// textbook lists them after the unknowns: lowest degree in the rates
/// first ([`rate_degree`]: the loads — a weight, an applied moment —
/// before the terms in the rates), each degree in the order it had
/// (`a (A_x − B_x) + ½ m g L sin β + I′ φ̇² sin β cos β = 0`).
pub(super) fn knowns_by_degree(e: &Expr, knowns: &mut [Id]) {
    if knowns.len() > 1 {
        knowns.sort_by_cached_key(|&id| rate_degree(e, id));
    }
}

/// A constant symbol that leads a product (`m g l`), as opposed to a rate,
/// sin or cos, or a constant named by a Greek letter (a constant rate Ω),
/// which follow the bracket.
pub(super) fn leading_constant(a: Atom) -> bool {
    // Asked for every factor of every term: each atom's answer (a name
    // looked up in the Greek table) is found once.
    thread_local! {
        static KNOWN: AtomMemo<bool> = const { AtomMemo::new() };
    }
    KNOWN.with(|k| {
        k.get(a, |a| {
            !a.is_time_dependent()
                && matches!(a.kind(), AtomKind::Var { .. })
                && crate::symbols::greek(a.name().split('_').next().unwrap_or("")).is_none()
        })
    })
}

/// The place of a constant factor: the names of the file's own order
/// (`[symbols] order`) first, in that order; then the conventional one —
/// mass first, then inertia, then gravity, then the others (lengths),
/// `m g l`, `I′ θ̇` — each class by name.
pub(super) fn constant_class(a: Atom, order: &[String]) -> (usize, u8, &'static str) {
    let name = a.name();
    let own = order.iter().position(|n| n == name).unwrap_or(order.len());
    let base = name.split('_').next().unwrap_or(name);
    let class = match base {
        "m" | "M" | "mass" => 0,
        "I" | "Ip" | "J" | "Jp" => 1,
        "g" => 2,
        _ => 3,
    };
    (own, class, name)
}

/// A place in a cyclic order: (family, position, which order).
pub(super) type Place = (&'static str, usize, u8);

/// A [`Place`] with its family numbered (in one result's [`Ranks`]), its
/// position (0, 1 or 2) as a byte.
type NumberedPlace = (u32, u8, u8);

/// A [`Place`] with its position as a byte.
type BytePlace = (&'static str, u8, u8);

/// The position of a subscript or letter in a cyclic order (x → y → z,
/// 1 → 2 → 3, A → B → C, also with a common subscript: A_p → B_p → C_p),
/// the family (the name without the subscript, or the letters' common
/// subscript), and which of the three orders it is in.
pub(super) fn cyclic_place(a: Atom) -> Option<Place> {
    // Each atom's place is found once (names compared as strings).
    thread_local! {
        static KNOWN: AtomMemo<Option<Place>> = const { AtomMemo::new() };
    }
    KNOWN.with(|k| k.get(a, place_of))
}

pub(super) fn place_of(a: Atom) -> Option<Place> {
    let name = a.name();
    if let Some((base, sub)) = name.rsplit_once('_') {
        if let Some(k) = ["x", "y", "z"].iter().position(|c| *c == sub) {
            return Some((base, k, 0));
        }
        if let Some(k) = ["1", "2", "3"].iter().position(|c| *c == sub) {
            return Some((base, k, 1));
        }
        // The letters A, B, C with one other subscript (a platform's A_p,
        // B_p, C_p): the family is the subscript.
        let k = ["A", "B", "C"].iter().position(|c| *c == base)?;
        return Some((sub, k, 2));
    }
    ["A", "B", "C"]
        .iter()
        .position(|c| *c == name)
        .map(|k| ("", k, 2))
}

/// Whether two constants are of one cyclic family as moments of inertia
/// about the three axes are: the same name with subscripts in one order,
/// or different names with subscripts in one order (a gyrostat's I_1, I_2
/// and A_3), or the letters A, B, C.
pub(super) fn constants_of_one_family(a: Atom, b: Atom) -> bool {
    match (cyclic_place(a), cyclic_place(b)) {
        (Some((fa, _, oa)), Some((fb, _, ob))) => oa == ob && (fa == fb || oa != 2),
        _ => false,
    }
}

/// Whether constant `b` follows constant `a` in the cyclic order of their
/// subscripts ([`constants_of_one_family`]).
pub(super) fn constant_next(a: Atom, b: Atom) -> bool {
    match (cyclic_place(a), cyclic_place(b)) {
        (Some((_, ka, _)), Some((_, kb, _))) => constants_of_one_family(a, b) && (ka + 1) % 3 == kb,
        _ => false,
    }
}

/// Two terms, each a single constant of one cyclic family (I_x and I_z,
/// A and C), times a common factor.
pub(super) fn cyclic_pair_of_constants(terms: &[PrintTerm<'_>]) -> bool {
    let [t0, t1] = terms else { return false };
    // Each term over the two's gcd: the atoms it has to a higher power
    // than the other term.
    let over_gcd = |m: &Monomial, n: &Monomial| single_quotient(m, n, |x| x.max(0));
    matches!((over_gcd(t0.1, t1.1), over_gcd(t1.1, t0.1)), (Some(a), Some(b)) if constants_of_one_family(a, b))
}

/// A bracket of two terms `a − b` (single constants of one cyclic family,
/// coefficients +1 and −1 after the common factor) in which `a` follows
/// `b` in cyclic order, so that it reads better as `−(b − a)`:
/// (I_x − I_z) → −(I_z − I_x), (A − C) → −(C − A).
pub(super) fn cyclic_difference(
    terms: &[PrintTerm<'_>],
    common: &Monomial,
) -> Option<(Atom, Atom)> {
    let [t0, t1] = terms else { return None };
    let single = |m: &Monomial| single_quotient(m, common, |x| x);
    let (a, b) = (single(t0.1)?, single(t1.1)?);
    if t0.2.is_negative() || !(t0.2 + t1.2).is_zero() {
        return None;
    }
    // a − b: reads cyclically when b follows a.
    (constant_next(b, a) && !constant_next(a, b)).then_some((a, b))
}

/// The atom of a quotient of `m` by `d` that is a single constant to the
/// first power, `None` when it is anything else; the quotient's exponent
/// of each atom is `quotient` of its exponent in `m` less that in `d`
/// (the difference itself for `m / d`, its positive part for `m` over
/// the gcd of `m` and `d`). One walk over the two sorted factor lists,
/// nothing built.
fn single_quotient(m: &Monomial, d: &Monomial, quotient: impl Fn(i32) -> i32) -> Option<Atom> {
    let (a, b) = (m.factors(), d.factors());
    let (mut i, mut j) = (0, 0);
    let mut found = None;
    loop {
        let (atom, x, y) = match (a.get(i), b.get(j)) {
            (Some(p), Some(q)) if p.0 == q.0 => {
                i += 1;
                j += 1;
                (p.0, p.1, q.1)
            }
            (Some(p), Some(q)) if p.0 < q.0 => {
                i += 1;
                (p.0, p.1, 0)
            }
            (Some(p), None) => {
                i += 1;
                (p.0, p.1, 0)
            }
            (_, Some(q)) => {
                j += 1;
                (q.0, 0, q.1)
            }
            (None, None) => break,
        };
        match quotient(x.checked_sub(y)?) {
            0 => {}
            1 if found.is_none() => found = Some(atom),
            _ => return None,
        }
    }
    found.filter(|a| !a.is_time_dependent())
}

/// The factors of a term inside a bracket in conventional order: constants
/// first as [`constant_class`] orders them (`2 m g l cos θ`), the rest as
/// they were, two rates of one cyclic family in cyclic order.
pub(super) fn conventional(fs: &mut [(Atom, i32)], order: &[String], ranks: &Ranks) {
    // Atoms in the table are read from it: a leading constant is one with
    // a conventional place.
    let covered = ranks.covers(fs);
    let constant = |a: Atom| {
        if covered {
            ranks.conv(a).is_some()
        } else {
            leading_constant(a)
        }
    };
    // One look at each factor: the first constant and whether there is a
    // second.
    let mut constants = fs.iter().enumerate().filter(|(_, f)| constant(f.0));
    let first = constants.next().map(|(k, _)| k);
    if constants.next().is_none() {
        // The sort below would only move the one constant to the front.
        if let Some(k) = first {
            fs[..=k].rotate_right(1);
        }
        ranks.cyclic_pair(fs);
        return;
    }
    // Constants have distinct places; the others keep their order (a
    // stable sort).
    if covered {
        fs.sort_by_key(|&(a, _)| {
            if constant(a) {
                (0, ranks.conv(a).unwrap_or(0))
            } else {
                (1, 0)
            }
        });
    } else {
        fs.sort_by_cached_key(|&(a, _)| {
            if constant(a) {
                (0, constant_class(a, order))
            } else {
                (1, (0, 0, ""))
            }
        });
    }
    ranks.cyclic_pair(fs);
}

/// Two rates of one cyclic family in cyclic order: ω_x ω_z → ω_z ω_x
/// (the order Euler's equations write them in).
pub(super) fn cyclic_pair(fs: &mut [(Atom, i32)]) {
    // Each factor's place is looked up once (names are compared as
    // strings), and only the factors that have one are visited. A family
    // of exactly two factors is looked at once, from its first member; a
    // swap exchanges those two, so no other family's members move.
    let placed: SmallVec<[(u32, BytePlace); 8]> = fs
        .iter()
        .enumerate()
        .filter_map(|(k, f)| cyclic_place(f.0).map(|p| (k as u32, (p.0, p.1 as u8, p.2))))
        .collect();
    pairs_in_order(fs, &placed);
}

/// The swaps of [`cyclic_pair`], given the factors that have a place (the
/// factor's index, its place with the family as a name or a number and
/// the position as a byte).
fn pairs_in_order<F: Copy + Eq>(fs: &mut [(Atom, i32)], placed: &[(u32, (F, u8, u8))]) {
    if placed.len() < 2 {
        return;
    }
    let next = |a: (F, u8, u8), b: (F, u8, u8)| a.0 == b.0 && a.2 == b.2 && (a.1 + 1) % 3 == b.1;
    for (j, &(p, pp)) in placed.iter().enumerate() {
        let family = pp.0;
        if placed[..j].iter().any(|e| e.1.0 == family) {
            continue;
        }
        let mut rest = placed[j + 1..].iter().filter(|e| e.1.0 == family);
        let (Some(&(q, pq)), None) = (rest.next(), rest.next()) else {
            continue;
        };
        let (p, q) = (p as usize, q as usize);
        if fs[p].1 == 1 && fs[q].1 == 1 && next(pq, pp) && !next(pp, pq) {
            fs.swap(p, q);
        }
    }
}
