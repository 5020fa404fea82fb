//! The one number formatter of every text output (SVG, G-code, HPGL, path
//! dump), and whole numbers grouped by thousands for messages to people.
//!
//! Numbers are rounded to a fixed number of decimals and then made compact:
//! trailing zeros and a trailing `.` go, and a negative zero becomes `0`.
//! Going through this single function is what makes the outputs
//! byte-identical across runs and machines.
//!
//! The rounding is exact decimal rounding of the binary value, ties to even —
//! what Rust's `{:.p}` does. Rather than format and trim a string (400–550 ns
//! a number, a large share of a render's time), the value is split into its
//! integer significand and power of two, scaled by `10^p` in a `u128`
//! without any loss, and rounded with an exact remainder: a fixed-point
//! integer that is then written digit by digit. Values too large for that
//! (beyond 2^100) go through `{:.p}`, which is where the bytes are defined.

use std::fmt::Write as _;

/// The largest precision honoured; more is clamped to it. Eight decimals of a
/// millimetre (10 pm) is far below any plotter's resolution, and the cap keeps
/// `f64` noise out of the output.
pub(crate) const MAX_PRECISION: u8 = 8;

/// `10^p` for every precision up to [`MAX_PRECISION`].
const POWERS_OF_TEN: [u64; MAX_PRECISION as usize + 1] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
];

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
    let precision = precision.min(MAX_PRECISION);
    match fixed_point(v.abs(), precision) {
        Some(scaled) => write_fixed(out, v.is_sign_negative(), scaled, precision),
        None => write_formatted(out, v, precision),
    }
}

/// `a · 10^precision` rounded to the nearest integer, ties to even, computed
/// exactly; `None` when it does not fit the integer arithmetic (`a` above
/// 2^100, or a result above `u64::MAX`).
fn fixed_point(a: f64, precision: u8) -> Option<u64> {
    let bits = a.to_bits();
    let exponent_bits = i32::try_from((bits >> 52) & 0x7ff).expect("11 bits");
    let fraction = bits & ((1 << 52) - 1);
    // a = significand · 2^exponent, exactly (subnormals have no hidden bit).
    let (significand, exponent) = if exponent_bits == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), exponent_bits - 1075)
    };
    // Below 2^53 · 10^8 < 2^80: the product is exact in a u128.
    let scaled = u128::from(significand) * u128::from(POWERS_OF_TEN[usize::from(precision)]);
    let rounded = if exponent >= 0 {
        if exponent > 47 {
            return None;
        }
        scaled << exponent
    } else {
        let shift = exponent.unsigned_abs();
        if shift > 81 {
            // scaled < 2^80 ≤ half of 2^shift: rounds to zero.
            0
        } else {
            let whole = scaled >> shift;
            let rest = scaled & ((1 << shift) - 1);
            let half = 1 << (shift - 1);
            if rest > half || (rest == half && whole & 1 == 1) {
                whole + 1
            } else {
                whole
            }
        }
    };
    u64::try_from(rounded).ok()
}

/// Writes the fixed-point integer `scaled` (the value times `10^precision`)
/// with its decimal point, trailing fractional zeros trimmed; zero has no sign.
fn write_fixed(out: &mut String, negative: bool, scaled: u64, precision: u8) {
    if scaled == 0 {
        out.push('0');
        return;
    }
    let unit = POWERS_OF_TEN[usize::from(precision)];
    let (whole, mut fraction) = (scaled / unit, scaled % unit);
    let mut fraction_digits = usize::from(precision);
    while fraction_digits > 0 && fraction % 10 == 0 {
        fraction /= 10;
        fraction_digits -= 1;
    }
    // "-" + 20 digits + "." + 8 digits.
    let mut buffer = [0u8; 32];
    let mut start = buffer.len();
    if fraction_digits > 0 {
        for _ in 0..fraction_digits {
            start -= 1;
            buffer[start] = b'0' + (fraction % 10) as u8;
            fraction /= 10;
        }
        start -= 1;
        buffer[start] = b'.';
    }
    let mut rest = whole;
    loop {
        start -= 1;
        buffer[start] = b'0' + (rest % 10) as u8;
        rest /= 10;
        if rest == 0 {
            break;
        }
    }
    if negative {
        start -= 1;
        buffer[start] = b'-';
    }
    out.push_str(std::str::from_utf8(&buffer[start..]).expect("ASCII digits"));
}

/// The reference path, through `{:.p}` and trimming; kept for the values the
/// fixed-point path cannot hold.
fn write_formatted(out: &mut String, v: f64, precision: u8) {
    let start = out.len();
    let precision = usize::from(precision);
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

    /// The reference: the formatted-and-trimmed spelling of the same value.
    fn reference(v: f64, precision: u8) -> String {
        let mut s = String::new();
        write_formatted(&mut s, v, precision.min(MAX_PRECISION));
        s
    }

    #[test]
    fn ties_round_to_even_as_the_reference_does() {
        assert_eq!(num(0.5, 0), "0");
        assert_eq!(num(1.5, 0), "2");
        assert_eq!(num(2.5, 0), "2");
        assert_eq!(num(-2.5, 0), "-2");
        assert_eq!(num(-0.5, 0), "0");
        assert_eq!(num(0.125, 2), "0.12");
        assert_eq!(num(0.375, 2), "0.38");
        // 0.35 is a little below 0.35 in binary: not a tie.
        assert_eq!(num(0.35, 1), "0.3");
    }

    #[test]
    fn extremes_match_the_reference() {
        let edges = [
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            1e-9,
            4.999_999_999e-9,
            5e-9,
            0.5e-8,
            2f64.powi(52),
            2f64.powi(53) + 2.0,
            2f64.powi(63),
            1.844_674_407_370_955_2e19,
            1.844_674_407_370_955e11,
            2f64.powi(100),
            2f64.powi(100) * 1.5,
            1e22,
            -1e300,
            f64::MAX,
            -f64::MAX,
        ];
        for v in edges {
            for precision in 0..=MAX_PRECISION + 1 {
                assert_eq!(
                    num(v, precision),
                    reference(v, precision),
                    "{v:e} at {precision}"
                );
            }
        }
    }

    proptest::proptest! {
        #[test]
        fn any_float_is_written_as_the_reference(bits in proptest::num::u64::ANY, precision in 0u8..=8) {
            let v = f64::from_bits(bits);
            proptest::prop_assume!(v.is_finite());
            proptest::prop_assert_eq!(num(v, precision), reference(v, precision));
        }

        #[test]
        fn drawing_sized_floats_are_written_as_the_reference(v in -1e6f64..1e6, precision in 0u8..=8) {
            proptest::prop_assert_eq!(num(v, precision), reference(v, precision));
        }

        // k / 2^j is exact in binary and ends in 5 at its last decimal: the
        // half-way cases, where only exact rounding gets the last digit right.
        #[test]
        fn exact_halves_are_written_as_the_reference(k in -1_000_000_000i64..1_000_000_000, j in 0i32..=12, precision in 0u8..=8) {
            let v = k as f64 / 2f64.powi(j);
            proptest::prop_assert_eq!(num(v, precision), reference(v, precision));
        }
    }

    #[test]
    fn whole_numbers_are_grouped_by_thousands() {
        assert_eq!(grouped(10_000_000), "10,000,000");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(0), "0");
    }
}
