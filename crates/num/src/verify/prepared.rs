//! Polynomials evaluated again and again under [`Values`] — a constrained
//! file's constraint rows and kinematic equations with their time
//! derivatives, evaluated at every draw and at every state a
//! linearisation measures — prepared once: each distinct atom is read
//! from the values once per evaluation (no hash per factor, one sine or
//! cosine per angle), the coefficients are floats already, and each term
//! is formed by the operations of [`Values::eval`] in the same order, so
//! the value and the size are the same bits.

use std::ops::Range;

use hdot_sym::atom::Atom;
use hdot_sym::poly::Poly;

use crate::bind::{BindError, Values};

/// One term: its coefficient and the range of its factors.
#[derive(Clone, Debug)]
struct Term {
    coef: f64,
    factors: Range<u32>,
}

/// Several polynomials over one table of atoms.
#[derive(Clone, Debug, Default)]
pub(crate) struct Prepared {
    atoms: Vec<Atom>,
    /// Each polynomial's range of terms.
    polys: Vec<Range<u32>>,
    terms: Vec<Term>,
    /// `(atom slot, exponent)`, in the monomials' order.
    factors: Vec<(u32, i32)>,
}

/// The value and size of each atom of a [`Prepared`] under some values
/// (`None`: unbound), read once.
pub(crate) type Resolved = Vec<Option<(f64, f64)>>;

impl Prepared {
    /// Prepares `polys`; [`Prepared::eval`]`(k, …)` is `polys[k]`.
    pub(crate) fn new(polys: &[Poly]) -> Prepared {
        let mut p = Prepared::default();
        for poly in polys {
            let start = p.terms.len() as u32;
            for (m, c) in poly.terms() {
                let from = p.factors.len() as u32;
                for &(a, e) in m.factors() {
                    let slot = match p.atoms.iter().position(|&b| b == a) {
                        Some(s) => s,
                        None => {
                            p.atoms.push(a);
                            p.atoms.len() - 1
                        }
                    };
                    p.factors.push((slot as u32, e));
                }
                p.terms.push(Term {
                    coef: c.to_f64(),
                    factors: from..p.factors.len() as u32,
                });
            }
            p.polys.push(start..p.terms.len() as u32);
        }
        p
    }

    /// The number of polynomials.
    pub(crate) fn len(&self) -> usize {
        self.polys.len()
    }

    /// Each atom's value and size in `values`.
    pub(crate) fn resolve(&self, values: &Values) -> Resolved {
        self.atoms.iter().map(|&a| values.get(a)).collect()
    }

    /// The atoms the polynomials hold.
    pub(crate) fn atoms(&self) -> &[Atom] {
        &self.atoms
    }

    /// The slot of atom `a` in a [`Resolved`], if a polynomial holds it.
    pub(crate) fn slot(&self, a: Atom) -> Option<usize> {
        self.atoms.iter().position(|&b| b == a)
    }

    /// Polynomial `k`'s value and size under the resolved atoms: what
    /// [`Values::eval`] gives under the values they were read from, bit
    /// for bit.
    ///
    /// # Errors
    /// [`BindError::Unbound`] naming the first atom without a value, in
    /// the order [`Values::eval`] meets them.
    pub(crate) fn eval(
        &self,
        k: usize,
        at: &[Option<(f64, f64)>],
    ) -> Result<(f64, f64), BindError> {
        let (mut v, mut s) = (0.0, 0.0);
        let terms = &self.polys[k];
        for t in &self.terms[terms.start as usize..terms.end as usize] {
            let (mut tv, mut ts) = (t.coef, t.coef.abs());
            for &(slot, e) in &self.factors[t.factors.start as usize..t.factors.end as usize] {
                let (x, sx) = at[slot as usize]
                    .ok_or_else(|| BindError::Unbound(self.atoms[slot as usize].to_string()))?;
                if e == 1 {
                    // `powi(1)` is the number itself.
                    tv *= x;
                    ts *= sx;
                } else {
                    tv *= powi(x, e);
                    ts *= powi(if e < 0 { x.abs() } else { sx }, e);
                }
            }
            v += tv;
            s += ts;
        }
        Ok((v, s))
    }
}

/// `x.powi(e)` by the runtime's own steps (compiler-builtins' `__powidf2`:
/// square-and-multiply from the low bit, one reciprocal at the end for a
/// negative exponent), inlined: the same bits without a call per factor.
#[inline(always)]
fn powi(mut x: f64, e: i32) -> f64 {
    let mut n = e.unsigned_abs();
    let mut r = 1.0;
    loop {
        if n & 1 != 0 {
            r *= x;
        }
        n >>= 1;
        if n == 0 {
            break;
        }
        x *= x;
    }
    if e < 0 { 1.0 / r } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hdot_sym::atom::AtomKind;
    use hdot_sym::derivation::load_str;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The inlined power gives `powi`'s bits.
    #[test]
    fn powi_gives_the_bits_of_the_runtime() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for _ in 0..2000 {
            let x: f64 = rng.gen_range(-4.0..4.0);
            for e in -7..=7 {
                assert_eq!(powi(x, e).to_bits(), x.powi(e).to_bits(), "{x}^{e}");
            }
        }
    }

    /// The rolling disk's constraint rows and their rates give the bits
    /// `Values::eval` gives, at random values (negative, small and large
    /// sizes, an unbound atom reported as `Values::eval` reports it).
    #[test]
    fn prepared_rows_give_the_bits_of_values_eval() {
        let text = include_str!("../../../../derivations/disk-rolling-on-plane.toml");
        let d = load_str("disk-rolling-on-plane.toml", text).expect("the disk derives");
        let polys: Vec<Poly> = d
            .steps
            .iter()
            .flat_map(|s| s.values())
            .map(|p| d.unfold(p))
            .flat_map(|p| [p.dt(), p])
            .collect();
        let prepared = Prepared::new(&polys);
        assert_eq!(prepared.len(), polys.len());
        let mut atoms: Vec<Atom> = polys.iter().flat_map(Poly::atoms).collect();
        atoms.sort_by_key(|a| a.sort_key());
        atoms.dedup();
        let mut rng = ChaCha8Rng::seed_from_u64(25);
        for round in 0..20 {
            let mut v = Values::default();
            for &a in &atoms {
                let target = match a.kind() {
                    AtomKind::Sin(q) | AtomKind::Cos(q) => q,
                    AtomKind::Var { .. } => a,
                    _ => continue,
                };
                let x: f64 = rng.gen_range(-3.0..3.0);
                v.set(target, x, x * rng.gen_range(0.5..4.0));
            }
            if round % 5 == 4 {
                v.unset(atoms[round % atoms.len()]);
            }
            let at = prepared.resolve(&v);
            for (k, p) in polys.iter().enumerate() {
                match (v.eval(p), prepared.eval(k, &at)) {
                    (Ok(a), Ok(b)) => {
                        assert_eq!(a.0.to_bits(), b.0.to_bits(), "value of polynomial {k}");
                        assert_eq!(a.1.to_bits(), b.1.to_bits(), "size of polynomial {k}");
                    }
                    (a, b) => assert_eq!(a, b, "polynomial {k}"),
                }
            }
        }
    }
}
