//! The one number formatter of every text output (SVG, path dump), and
//! whole numbers grouped by thousands for messages to people.
//!
//! Numbers are rounded to a fixed number of decimals and then made compact:
//! trailing zeros and a trailing `.` go, and a negative zero becomes `0`.
//! Going through this single function is what makes the outputs
//! byte-identical across runs and machines: Rust's fixed-precision
//! formatting is exact decimal rounding, with no dependence on the platform.

use std::fmt::Write as _;

/// The largest precision honoured; more is clamped to it. Eight decimals of a
/// millimetre (10 pm) is far below any plotter's resolution, and the cap keeps
/// `f64` noise out of the output.
pub(crate) const MAX_PRECISION: u8 = 8;

/// Appends `v` rounded to `precision` decimals (at most 8) to `out`, with
/// trailing zeros and a trailing `.` removed and `-0` written as `0`.
///
/// `1.5` at precision 3 is `1.5`, `2.0` is `2`, `-0.0001` is `0`.
/// Non-finite values are a bug upstream (scenes are validated at the
/// boundary): debug builds panic, release builds write `0` so that the
/// output at least stays well-formed.
pub fn write_number(out: &mut String, v: f64, precision: u8) {
    debug_assert!(v.is_finite(), "non-finite number {v} reached an output");
    if !v.is_finite() {
        out.push('0');
        return;
    }
    let start = out.len();
    let precision = usize::from(precision.min(MAX_PRECISION));
    write!(out, "{v:.precision$}").expect("writing to a String cannot fail");
    // Only trim inside a fraction: "100" must stay "100".
    if out[start..].contains('.') {
        let kept = out[start..]
            .trim_end_matches('0')
            .trim_end_matches('.')
            .len();
        out.truncate(start + kept);
    }
    // Values that round to zero from below print as "-0"; one spelling of
    // zero keeps equal geometry byte-equal.
    if &out[start..] == "-0" {
        out.truncate(start);
        out.push('0');
    }
}

/// `n` with its thousands separated by commas, for messages and reports:
/// `10000000` is `10,000,000`.
pub fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn num(v: f64, precision: u8) -> String {
        let mut s = String::new();
        write_number(&mut s, v, precision);
        s
    }

    #[test]
    fn rounds_and_trims() {
        assert_eq!(num(1.5, 3), "1.5");
        assert_eq!(num(2.0, 3), "2");
        assert_eq!(num(100.0, 3), "100");
        assert_eq!(num(100.0, 0), "100");
        assert_eq!(num(0.1 + 0.2, 3), "0.3");
        assert_eq!(num(1.23456, 2), "1.23");
        assert_eq!(num(1.235_000_1, 2), "1.24");
        assert_eq!(num(-12.345_678, 4), "-12.3457");
        assert_eq!(num(0.000_5, 3), "0.001");
        assert_eq!(num(1e-9, 8), "0");
        assert_eq!(num(123_456_789.0, 3), "123456789");
    }

    #[test]
    fn negative_zero_is_zero() {
        assert_eq!(num(-0.0, 3), "0");
        assert_eq!(num(-0.0001, 3), "0");
        assert_eq!(num(-0.4, 0), "0");
        assert_eq!(num(-0.6, 0), "-1");
    }

    #[test]
    fn precision_is_capped() {
        assert_eq!(num(1.0 / 3.0, 200), "0.33333333");
    }

    #[test]
    fn appends_without_touching_what_is_there() {
        let mut s = String::from("x=1.500 ");
        write_number(&mut s, -0.0, 2);
        write_number(&mut s, 2.50, 2);
        assert_eq!(s, "x=1.500 02.5");
    }

    // Debug builds stop at the bug; release builds still write valid text.
    #[test]
    #[cfg_attr(debug_assertions, should_panic(expected = "non-finite"))]
    fn non_finite_writes_zero() {
        assert_eq!(num(f64::NAN, 3), "0");
        assert_eq!(num(f64::INFINITY, 3), "0");
    }

    #[test]
    fn whole_numbers_are_grouped_by_thousands() {
        assert_eq!(grouped(10_000_000), "10,000,000");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(0), "0");
    }
}
