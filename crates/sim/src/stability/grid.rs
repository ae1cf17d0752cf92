//! The values of a stability sweep: `count` values evenly spaced from
//! `from` to `to`, each the double nearest to the decimal the user means.
//!
//! A value computed in binary, `from + (to − from)·k/n`, can miss the
//! decimal it stands for by an ulp (0 to 10 in 101 values gives
//! `0.8999999999999999` for 0.9), and the CSV, which writes the shortest
//! form that reads back exactly, shows the miss. Here `from` and `to` are
//! taken as the decimals they print as (their shortest round-trip form),
//! the k-th value `(from·(n − k) + to·k) / n` is formed exactly in integers
//! and only its final quotient is rounded, once, to the nearest double: 0.9
//! is written `0.9`. Where the integers would overflow (decimals of very
//! different exponents), the binary formula is the fallback.

/// The values, `count ≥ 2`, the first exactly `from` and the last exactly
/// `to`.
pub(super) fn values(from: f64, to: f64, count: usize) -> Vec<f64> {
    let n = count.saturating_sub(1).max(1);
    (0..=n)
        .map(|k| match k {
            0 => from,
            k if k == n => to,
            k => decimal_point(from, to, k, n)
                .unwrap_or_else(|| from + (to - from) * (k as f64 / n as f64)),
        })
        .collect()
}

/// A finite double as the decimal it prints as: `(digits, exponent)` with
/// value `digits · 10^exponent`.
fn decimal(x: f64) -> Option<(i128, i32)> {
    let text = format!("{x:e}");
    let (mantissa, exponent) = text.split_once('e')?;
    let mut exponent: i32 = exponent.parse().ok()?;
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    exponent -= frac.len() as i32;
    let digits: i128 = format!("{int}{frac}").parse().ok()?;
    Some((digits, exponent))
}

/// `(from·(n − k) + to·k) / n`, the quotient of exact integers rounded once.
fn decimal_point(from: f64, to: f64, k: usize, n: usize) -> Option<f64> {
    let (a, ea) = decimal(from)?;
    let (b, eb) = decimal(to)?;
    let e = ea.min(eb);
    let scale = |d: i128, ed: i32| d.checked_mul(10_i128.checked_pow((ed - e) as u32)?);
    let (a, b) = (scale(a, ea)?, scale(b, eb)?);
    let (k, n) = (k as i128, n as i128);
    let num = a.checked_mul(n - k)?.checked_add(b.checked_mul(k)?)?;
    Some(quotient(num, n, e))
}

/// `num / den · 10^e` (den > 0) as the nearest double: the quotient's
/// decimal digits by long division, past the precision of a double, with
/// a last digit 1 when the division has not ended so that a tie is broken
/// the right way; then parsed (correctly rounded).
fn quotient(num: i128, den: i128, e: i32) -> f64 {
    let sign = if num < 0 { "-" } else { "" };
    let num = num.unsigned_abs();
    let den = den.unsigned_abs();
    let mut digits = (num / den).to_string();
    let mut significant = if digits == "0" { 0 } else { digits.len() };
    let mut rest = num % den;
    let mut places = 0_i32;
    while rest != 0 && significant < 25 {
        rest *= 10;
        let d = rest / den;
        rest %= den;
        digits.push(char::from(b'0' + d as u8));
        places += 1;
        if significant > 0 || d != 0 {
            significant += 1;
        }
    }
    if rest != 0 {
        digits.push('1');
        places += 1;
    }
    format!("{sign}{digits}e{}", e - places)
        .parse()
        .expect("a decimal number parses")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each value is the double nearest to the decimal meant, so the
    /// shortest form that reads back exactly is that decimal.
    #[test]
    fn values_are_the_decimals_meant() {
        let v = values(0.0, 10.0, 101);
        assert_eq!(format!("{:?}", v[9]), "0.9");
        for (k, x) in v.iter().enumerate() {
            let want: f64 = format!("{k}e-1").parse().unwrap();
            assert_eq!(*x, want, "value {k}");
        }
        let v = values(-0.3, 0.7, 11);
        assert_eq!(format!("{:?}", v[1]), "-0.2");
        assert_eq!(format!("{:?}", v[3]), "0.0");
        assert_eq!(values(0.1, 0.2, 3)[1], 0.15);
        // A third is not a decimal: the nearest double to it.
        assert_eq!(values(0.0, 1.0, 4)[1], 1.0 / 3.0);
    }

    /// Ends exact, values increasing, and the fallback where the
    /// decimals' exponents are too far apart.
    #[test]
    fn ends_are_exact_and_values_increase() {
        for (from, to, count) in [(1e-300, 1e300, 7), (0.0, 1.0, 2), (-5.5, 12.25, 1000)] {
            let v = values(from, to, count);
            assert_eq!(v.len(), count);
            assert_eq!((v[0], v[count - 1]), (from, to));
            assert!(v.windows(2).all(|w| w[0] < w[1]), "{v:?}");
        }
    }
}
