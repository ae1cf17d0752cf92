//! A bracket's parts grouped by their time-dependent part (rates, sin and
//! cos, constant rates named by Greek letters: what follows a bracket of
//! constants, ((I_2 − A_3) ω_3 − h) ω_2/I_1), without building that part
//! as a monomial for every part: each part's time-dependent factors are
//! hashed in one pass, the parts sorted by hash, and a run of equal hashes
//! split by comparing the factors (a collision costs time, never
//! correctness). Only a part shared by two parts or more is built, once.

use std::borrow::Cow;

use crate::atom::Atom;
use crate::poly::Monomial;
use crate::rational::Rational;

/// The class of a part without a time-dependent part (a term of
/// constants only).
pub(super) const NONE: u32 = u32::MAX;

/// The parts of a bracket by their time-dependent part.
pub(super) struct Classes {
    /// Each part's class (`NONE`: its time-dependent part is 1).
    pub(super) of: Vec<u32>,
    /// Each class's number of parts.
    pub(super) size: Vec<u32>,
}

impl Classes {
    /// No classes: a bracket whose parts are not grouped.
    pub(super) fn none() -> Classes {
        Classes {
            of: Vec::new(),
            size: Vec::new(),
        }
    }

    /// The classes of `parts`, `lead` telling a leading constant (what is
    /// not part of the time-dependent part) from the other atoms.
    pub(super) fn of(
        parts: &[(Cow<'_, Monomial>, Rational)],
        lead: &impl Fn(Atom) -> bool,
    ) -> Classes {
        let mut keyed: Vec<(u64, u32)> = Vec::with_capacity(parts.len());
        for (k, (m, _)) in parts.iter().enumerate() {
            let mut h: u64 = 0x243F_6A88_85A3_08D3;
            let mut any = false;
            for &(a, x) in m.factors() {
                if !lead(a) {
                    let w = (u64::from(a.id()) << 32) | u64::from(x as u32);
                    h = (h ^ w).wrapping_mul(0x9E37_79B9_7F4A_7C15);
                    h ^= h >> 29;
                    any = true;
                }
            }
            if any {
                keyed.push((h, k as u32));
            }
        }
        keyed.sort_unstable();
        let mut of = vec![NONE; parts.len()];
        let mut size: Vec<u32> = Vec::new();
        let timed = |k: u32| parts[k as usize].0.factors().iter().filter(|f| !lead(f.0));
        let mut start = 0;
        while start < keyed.len() {
            let h = keyed[start].0;
            let end = start + keyed[start..].iter().take_while(|x| x.0 == h).count();
            // The classes of this run: (class, a part of it).
            let mut run: smallvec::SmallVec<[(u32, u32); 2]> = smallvec::SmallVec::new();
            for &(_, k) in &keyed[start..end] {
                let class = match run.iter().find(|r| timed(r.1).eq(timed(k))) {
                    Some(r) => r.0,
                    None => {
                        size.push(0);
                        let c = (size.len() - 1) as u32;
                        run.push((c, k));
                        c
                    }
                };
                of[k as usize] = class;
                size[class as usize] += 1;
            }
            start = end;
        }
        Classes { of, size }
    }

    /// Whether part `k` shares its time-dependent part with another part.
    pub(super) fn shared(&self, k: usize) -> bool {
        let c = self.of[k];
        c != NONE && self.size[c as usize] > 1
    }
}

/// The time-dependent part of `m`, and what is left (its constants).
pub(super) fn split(m: &Monomial, lead: &impl Fn(Atom) -> bool) -> (Monomial, Monomial) {
    m.split(|a| !lead(a))
}
