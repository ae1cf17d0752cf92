//! A function of time written as an expression (`"0.2*sin(3*t)"`,
//! `"M_0*(1 - exp(-t/tau))"` with the scene's constants), for the applied
//! inputs of a derived model.
//!
//! Parsed with `hdot-sym`'s expression parser (so the syntax, its limits
//! and its error positions are the derivation files'), then evaluated in
//! `f64`. Unlike a derivation, any function below may take any argument,
//! and decimal numbers (`0.02`, `1.5e-3`) are allowed: this is numerics,
//! not the canonical form (each is read as the exact fraction it denotes).

use std::collections::BTreeMap;
use std::fmt;

use hdot_sym::parse::{Ast, AstKind, parse};

/// The functions an input may use.
pub const FUNCTIONS: &[&str] = &["sin", "cos", "tan", "exp", "ln", "sqrt", "abs"];

/// A parsed expression of `t`.
#[derive(Clone, PartialEq)]
pub struct TimeFunction {
    text: String,
    ast: Ast,
    constants: BTreeMap<String, f64>,
}

impl fmt::Debug for TimeFunction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "TimeFunction({:?})", self.text)
    }
}

impl TimeFunction {
    /// Parses `text`; names other than `t`, `pi` and the keys of
    /// `constants` are errors (with the byte offset in `text`).
    pub fn parse(text: &str, constants: &BTreeMap<String, f64>) -> Result<TimeFunction, String> {
        let exact = decimals_as_fractions(text);
        let ast = parse(&exact).map_err(|e| {
            if exact == text {
                format!("{} (at byte {})", e.message, e.span.start)
            } else {
                format!("{} (in `{exact}`, at byte {})", e.message, e.span.start)
            }
        })?;
        check(&ast, constants)?;
        Ok(TimeFunction {
            text: text.to_owned(),
            ast,
            constants: constants.clone(),
        })
    }

    /// The expression as written.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The value at `t`.
    pub fn eval(&self, t: f64) -> f64 {
        eval(&self.ast, t, &self.constants)
    }
}

/// `text` with every decimal literal (`0.25`, `3e-2`, `1.5E+3`) replaced by
/// the exact fraction it denotes, in parentheses (`(25/100)`).
fn decimals_as_fractions(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        let starts_number = b[i].is_ascii_digit()
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'));
        if !starts_number {
            let ch = text[i..].chars().next().expect("in bounds");
            out.push(ch);
            i += ch.len_utf8();
            continue;
        }
        let digits = |mut j: usize| {
            while j < b.len() && b[j].is_ascii_digit() {
                j += 1;
            }
            j
        };
        let int_end = digits(i);
        let mut j = int_end;
        let mut frac = "";
        if j + 1 < b.len() && b[j] == b'.' && b[j + 1].is_ascii_digit() {
            let end = digits(j + 1);
            frac = &text[j + 1..end];
            j = end;
        }
        let mut exp: i64 = 0;
        let mut has_exp = false;
        if j < b.len() && (b[j] == b'e' || b[j] == b'E') {
            let mut k = j + 1;
            if k < b.len() && (b[k] == b'+' || b[k] == b'-') {
                k += 1;
            }
            if k < b.len() && b[k].is_ascii_digit() {
                let end = digits(k);
                // Saturate absurd exponents: the parser's literal limit refuses them.
                exp = text[j + 1..end].parse().unwrap_or(i64::MAX / 2);
                has_exp = true;
                j = end;
            }
        }
        if frac.is_empty() && !has_exp {
            out.push_str(&text[i..j]);
        } else {
            let digits = format!("{}{frac}", &text[i..int_end]);
            let mantissa = match digits.trim_start_matches('0') {
                "" => "0",
                m => m,
            };
            let scale = exp - frac.len() as i64;
            let zeros = |n: i64| "0".repeat(n.clamp(0, 4096) as usize);
            if scale >= 0 {
                out.push_str(&format!("({mantissa}{})", zeros(scale)));
            } else {
                out.push_str(&format!("({mantissa}/1{})", zeros(-scale)));
            }
        }
        i = j;
    }
    out
}

fn check(a: &Ast, constants: &BTreeMap<String, f64>) -> Result<(), String> {
    let at = |m: String| Err(format!("{m} (at byte {})", a.span.start));
    match &a.kind {
        AstKind::Num(_) => Ok(()),
        AstKind::Name { name, primes: 0 }
            if name == "t" || name == "pi" || constants.contains_key(name) =>
        {
            Ok(())
        }
        AstKind::Name { name, .. } => at(format!(
            "unknown name `{name}`: an input is a function of `t`, `pi` and the scene's constants"
        )),
        AstKind::Add(items) | AstKind::Mul(items) => {
            items.iter().try_for_each(|i| check(i, constants))
        }
        AstKind::Neg(x) | AstKind::Recip(x) | AstKind::Pow(x, _) => check(x, constants),
        AstKind::Call { func, args } if FUNCTIONS.contains(&func.as_str()) && args.len() == 1 => {
            check(&args[0], constants)
        }
        AstKind::Call { func, .. } => at(format!(
            "`{func}` is not a function of one argument an input may use ({})",
            FUNCTIONS.join(", ")
        )),
        _ => at("an input is a scalar expression of t".into()),
    }
}

fn eval(a: &Ast, t: f64, c: &BTreeMap<String, f64>) -> f64 {
    match &a.kind {
        AstKind::Num(r) => r.to_f64(),
        AstKind::Name { name, .. } => match name.as_str() {
            "t" => t,
            "pi" => std::f64::consts::PI,
            n => c[n],
        },
        AstKind::Add(items) => items.iter().map(|i| eval(i, t, c)).sum(),
        AstKind::Mul(items) => items.iter().map(|i| eval(i, t, c)).product(),
        AstKind::Neg(x) => -eval(x, t, c),
        AstKind::Recip(x) => 1.0 / eval(x, t, c),
        AstKind::Pow(x, n) => eval(x, t, c).powi(*n as i32),
        AstKind::Call { func, args } => {
            let x = eval(&args[0], t, c);
            match func.as_str() {
                "sin" => x.sin(),
                "cos" => x.cos(),
                "tan" => x.tan(),
                "exp" => x.exp(),
                "ln" => x.ln(),
                "sqrt" => x.sqrt(),
                _ => x.abs(),
            }
        }
        _ => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn evaluates_and_refuses_unknown_names() {
        let mut c = BTreeMap::new();
        c.insert("M_0".to_string(), 2.0);
        let f = TimeFunction::parse("M_0*(1 - exp(-t/2)) + sin(pi*t)^2", &c).unwrap();
        let t = 0.7f64;
        let want = 2.0 * (1.0 - (-t / 2.0).exp()) + (std::f64::consts::PI * t).sin().powi(2);
        assert!((f.eval(t) - want).abs() <= 4.0 * f64::EPSILON * want.abs());
        assert!(
            TimeFunction::parse("omega*t", &c)
                .unwrap_err()
                .contains("unknown name `omega`")
        );
        assert!(
            TimeFunction::parse("atan(t)", &c)
                .unwrap_err()
                .contains("`atan`")
        );
    }

    #[test]
    fn decimal_numbers_are_read_exactly() {
        let c = BTreeMap::new();
        for (text, want) in [
            ("0.02*t", 0.02 * 1.5),
            ("1.5e-3 + t", 1.5e-3 + 1.5),
            ("2E+2*t", 300.0),
            ("12.5", 12.5),
        ] {
            let f = TimeFunction::parse(text, &c).unwrap();
            assert!(
                (f.eval(1.5) - want).abs() <= 4.0 * f64::EPSILON * want.abs(),
                "{text}: {} ≠ {want}",
                f.eval(1.5)
            );
        }
        assert_eq!(decimals_as_fractions("M_2*0.5"), "M_2*(5/10)");
    }
}
