//! Exact rational numbers: a machine-word fast path that widens to
//! arbitrary precision on overflow, so arithmetic is never silently wrong.
//!
//! Written by hand around `num-rational` because the coefficients of the
//! chapter's equations are tiny (±1, ±2, ½) and a `BigRational` for each
//! would allocate on every multiplication of the derivation's hot loop.

use std::cmp::Ordering;
use std::fmt;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// An exact rational number in lowest terms with a positive denominator.
///
/// Invariant: `Small` is used whenever numerator and denominator fit in
/// `i64`; `Big` only when they do not, so equal values have equal
/// representations and derived `PartialEq`/`Hash` are exact.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Rational {
    /// `num / den` with `den > 0` and `gcd(num, den) = 1`.
    Small(i64, i64),
    /// Values that do not fit in `i64`.
    Big(Box<BigRational>),
}

impl Rational {
    /// Zero.
    pub const ZERO: Rational = Rational::Small(0, 1);
    /// One.
    pub const ONE: Rational = Rational::Small(1, 1);

    /// The integer `n`.
    pub fn int(n: i64) -> Rational {
        Rational::Small(n, 1)
    }

    /// `num / den`, reduced. Returns `None` when `den == 0`.
    pub fn new(num: i64, den: i64) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        Some(Self::from_i128(num as i128, den as i128))
    }

    fn from_i128(num: i128, den: i128) -> Rational {
        debug_assert!(den != 0);
        let g = num.gcd(&den);
        let (mut n, mut d) = (num / g, den / g);
        if d < 0 {
            n = -n;
            d = -d;
        }
        match (i64::try_from(n), i64::try_from(d)) {
            (Ok(n), Ok(d)) => Rational::Small(n, d),
            _ => Self::from_big(BigRational::new(BigInt::from(n), BigInt::from(d))),
        }
    }

    fn from_big(r: BigRational) -> Rational {
        match (r.numer().to_i64(), r.denom().to_i64()) {
            (Some(n), Some(d)) => Rational::Small(n, d),
            _ => Rational::Big(Box::new(r)),
        }
    }

    /// The value as a big integer when it is an integer whose big form is
    /// at hand (or cheap to make), else `None`.
    fn big_integer(&self) -> Option<std::borrow::Cow<'_, BigInt>> {
        use std::borrow::Cow;
        match self {
            Rational::Small(n, 1) => Some(Cow::Owned(BigInt::from(*n))),
            Rational::Small(..) => None,
            Rational::Big(b) if b.is_integer() => Some(Cow::Borrowed(b.numer())),
            Rational::Big(_) => None,
        }
    }

    /// `self ∘ rhs` for two integers at least one of which is big, without
    /// the gcd reduction `num-rational` performs (its binary gcd against a
    /// denominator of one costs time quadratic in the digits: thousands of
    /// bits made the squaring chain of issue 13 take half a minute).
    fn big_integer_op(
        &self,
        rhs: &Rational,
        op: fn(&BigInt, &BigInt) -> BigInt,
    ) -> Option<Rational> {
        let (a, b) = (self.big_integer()?, rhs.big_integer()?);
        Some(Self::from_big(BigRational::from_integer(op(&a, &b))))
    }

    fn to_big(&self) -> BigRational {
        match self {
            Rational::Small(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Rational::Big(b) => (**b).clone(),
        }
    }

    /// Parses `"3"`, `"-3"`, `"3/4"` or an arbitrarily long integer.
    pub fn parse(text: &str) -> Option<Rational> {
        let (n, d) = match text.split_once('/') {
            Some((n, d)) => (n.trim(), d.trim()),
            None => (text.trim(), "1"),
        };
        let n: BigInt = n.parse().ok()?;
        let d: BigInt = d.parse().ok()?;
        if d.is_zero() {
            return None;
        }
        Some(Self::from_big(BigRational::new(n, d)))
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        matches!(self, Rational::Small(0, _))
    }

    /// True for one.
    pub fn is_one(&self) -> bool {
        matches!(self, Rational::Small(1, 1))
    }

    /// True for minus one.
    pub fn is_minus_one(&self) -> bool {
        matches!(self, Rational::Small(-1, 1))
    }

    /// True when the denominator is one.
    pub fn is_integer(&self) -> bool {
        match self {
            Rational::Small(_, d) => *d == 1,
            Rational::Big(b) => b.is_integer(),
        }
    }

    /// True for values below zero.
    pub fn is_negative(&self) -> bool {
        match self {
            Rational::Small(n, _) => *n < 0,
            Rational::Big(b) => b.is_negative(),
        }
    }

    /// The absolute value.
    pub fn abs(&self) -> Rational {
        if self.is_negative() {
            -self
        } else {
            self.clone()
        }
    }

    /// Numerator and denominator as decimal strings (denominator positive).
    pub fn parts(&self) -> (String, String) {
        match self {
            Rational::Small(n, d) => (n.to_string(), d.to_string()),
            Rational::Big(b) => (b.numer().to_string(), b.denom().to_string()),
        }
    }

    /// The nearest `f64`.
    pub fn to_f64(&self) -> f64 {
        match self {
            Rational::Small(n, d) => *n as f64 / *d as f64,
            Rational::Big(b) => b.to_f64().unwrap_or(f64::NAN),
        }
    }

    /// `self^n` for a non-negative exponent, by repeated squaring.
    pub fn pow(&self, mut n: u32) -> Rational {
        let mut base = self.clone();
        let mut acc = Rational::ONE;
        while n > 0 {
            if n & 1 == 1 {
                acc = &acc * &base;
            }
            n >>= 1;
            if n > 0 {
                base = &base * &base;
            }
        }
        acc
    }

    /// Bits of the larger of numerator and denominator (0 for zero).
    pub fn bits(&self) -> u64 {
        match self {
            Rational::Small(n, d) => u64::from(64 - n.unsigned_abs().leading_zeros())
                .max(u64::from(64 - d.unsigned_abs().leading_zeros())),
            Rational::Big(b) => b.numer().bits().max(b.denom().bits()),
        }
    }

    /// The multiplicative inverse, `None` for zero.
    pub fn recip(&self) -> Option<Rational> {
        match self {
            Rational::Small(0, _) => None,
            Rational::Small(n, d) => Some(Self::from_i128(*d as i128, *n as i128)),
            Rational::Big(b) => Some(Self::from_big(b.recip())),
        }
    }

    /// Greatest common divisor of two rationals: gcd of numerators over lcm
    /// of denominators (always non-negative).
    pub fn gcd(&self, other: &Rational) -> Rational {
        // Two integers (the coefficients of most results): in u64, no
        // i128 division; 2⁶³ does not fit an i64 and takes the path below.
        if let (Rational::Small(n1, 1), Rational::Small(n2, 1)) = (self, other) {
            let g = n1.unsigned_abs().gcd(&n2.unsigned_abs());
            if let Ok(g) = i64::try_from(g) {
                return Rational::Small(g, 1);
            }
        }
        if let (Rational::Small(n1, d1), Rational::Small(n2, d2)) = (self, other) {
            // gcd of numerators over lcm of denominators, in i128 (cannot
            // overflow: |n| ≤ 2⁶³ and lcm ≤ 2¹²⁶).
            let n = (*n1 as i128).gcd(&(*n2 as i128));
            if n == 0 {
                return Rational::ZERO;
            }
            let d = (*d1 as i128).lcm(&(*d2 as i128));
            return Self::from_i128(n, d);
        }
        let (a, b) = (self.to_big(), other.to_big());
        let n = a.numer().gcd(b.numer());
        let d = a.denom().lcm(b.denom());
        if n.is_zero() {
            return Rational::ZERO;
        }
        Self::from_big(BigRational::new(n, d))
    }
}

impl Default for Rational {
    fn default() -> Self {
        Rational::ZERO
    }
}

impl From<i64> for Rational {
    fn from(n: i64) -> Self {
        Rational::int(n)
    }
}

impl std::ops::Add for &Rational {
    type Output = Rational;
    fn add(self, rhs: &Rational) -> Rational {
        if let (Rational::Small(a, b), Rational::Small(c, d)) = (self, rhs) {
            if *b == 1
                && *d == 1
                && let Some(n) = a.checked_add(*c)
            {
                return Rational::Small(n, 1);
            }
            let (a, b, c, d) = (*a as i128, *b as i128, *c as i128, *d as i128);
            if let (Some(x), Some(y)) = (a.checked_mul(d), c.checked_mul(b))
                && let (Some(n), Some(den)) = (x.checked_add(y), b.checked_mul(d))
            {
                return Rational::from_i128(n, den);
            }
        }
        if let Some(r) = self.big_integer_op(rhs, |a, b| a + b) {
            return r;
        }
        Rational::from_big(self.to_big() + rhs.to_big())
    }
}

impl std::ops::Sub for &Rational {
    type Output = Rational;
    fn sub(self, rhs: &Rational) -> Rational {
        self + &(-rhs)
    }
}

impl std::ops::Mul for &Rational {
    type Output = Rational;
    fn mul(self, rhs: &Rational) -> Rational {
        if let (Rational::Small(a, b), Rational::Small(c, d)) = (self, rhs) {
            // Integers (the common case): no gcd to take.
            if *b == 1
                && *d == 1
                && let Some(n) = a.checked_mul(*c)
            {
                return Rational::Small(n, 1);
            }
            // Products of two i64 always fit in i128.
            return Rational::from_i128(*a as i128 * *c as i128, *b as i128 * *d as i128);
        }
        if let Some(r) = self.big_integer_op(rhs, |a, b| a * b) {
            return r;
        }
        Rational::from_big(self.to_big() * rhs.to_big())
    }
}

impl std::ops::Neg for &Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        match self {
            Rational::Small(n, d) => match n.checked_neg() {
                Some(n) => Rational::Small(n, *d),
                None => Rational::from_big(-self.to_big()),
            },
            Rational::Big(b) => Rational::from_big(-(**b).clone()),
        }
    }
}

impl std::ops::Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        -&self
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Rational {
    fn cmp(&self, other: &Self) -> Ordering {
        match (self, other) {
            (Rational::Small(a, b), Rational::Small(c, d)) => {
                (*a as i128 * *d as i128).cmp(&(*c as i128 * *b as i128))
            }
            _ => self.to_big().cmp(&other.to_big()),
        }
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (n, d) = self.parts();
        if d == "1" {
            write!(f, "{n}")
        } else {
            write!(f, "{n}/{d}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overflow_widens_instead_of_wrapping() {
        let big = Rational::int(i64::MAX);
        let sq = &big * &big;
        assert!(matches!(sq, Rational::Big(_)));
        let back = &sq * &big.recip().unwrap();
        assert_eq!(back, big);
        assert_eq!(
            -Rational::int(i64::MIN),
            Rational::parse("9223372036854775808").unwrap()
        );
    }

    #[test]
    fn big_integers_stay_exact() {
        let two_200 = Rational::int(2).pow(200);
        let one = Rational::ONE;
        let p = &(&two_200 + &one) * &(&two_200 - &one);
        assert_eq!(p, &Rational::int(2).pow(400) - &one);
        assert!(p.is_integer());
        // Back to the machine-word form when small again.
        let q = &(&two_200 + &Rational::int(5)) - &two_200;
        assert_eq!(q, Rational::Small(5, 1));
        let half = Rational::new(1, 2).unwrap();
        assert_eq!(&(&two_200 * &half) * &Rational::int(2), two_200);
    }

    #[test]
    fn reduces_and_normalises_sign() {
        assert_eq!(Rational::new(2, -4).unwrap(), Rational::Small(-1, 2));
        assert_eq!(Rational::parse("6/4").unwrap().to_string(), "3/2");
        assert_eq!(Rational::new(1, 0), None);
        assert_eq!(
            Rational::parse("4/6").unwrap().gcd(&Rational::int(2)),
            Rational::new(2, 3).unwrap()
        );
    }
}
