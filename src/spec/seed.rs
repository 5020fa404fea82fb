//! The seed as a description writes it: any number a person or a form may
//! type is read, and one outside 0 ..= 2^63−1 (negative, fractional, too
//! large) is refused with the range — the words `moyo render --seed` and
//! the studio use — rather than the parser's "expected u64".

use std::fmt;

use serde::de::{self, Deserializer, Visitor};

/// The largest seed: every seed fits a signed 64-bit integer, so TOML,
/// JSON and JavaScript-free tools all carry it.
pub const MAX_SEED: u64 = i64::MAX as u64;

/// Reads a seed, refusing what is not one with its range.
pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<u64, D::Error> {
    d.deserialize_any(SeedVisitor)
}

struct SeedVisitor;

/// Why `got` is no seed.
fn refused<E: de::Error>(got: impl fmt::Display) -> E {
    E::custom(format!(
        "must be a whole number between 0 and {MAX_SEED}, got {got}"
    ))
}

impl Visitor<'_> for SeedVisitor {
    type Value = u64;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a whole number between 0 and {MAX_SEED}")
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<u64, E> {
        // The range itself is checked by validation, with the field's
        // place; here only what cannot be a u64 at all.
        Ok(v)
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<u64, E> {
        u64::try_from(v).map_err(|_| refused(v))
    }

    fn visit_u128<E: de::Error>(self, v: u128) -> Result<u64, E> {
        u64::try_from(v).map_err(|_| refused(v))
    }

    fn visit_i128<E: de::Error>(self, v: i128) -> Result<u64, E> {
        u64::try_from(v).map_err(|_| refused(v))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<u64, E> {
        // A whole number written with a point (`7.0`) is still that seed.
        if v.fract() == 0.0 && (0.0..2f64.powi(63)).contains(&v) {
            Ok(v as u64)
        } else {
            Err(refused(v))
        }
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<u64, E> {
        Err(refused(format!("{v:?}")))
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<u64, E> {
        Err(refused(v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize)]
    struct Holder {
        #[serde(deserialize_with = "deserialize")]
        seed: u64,
    }

    fn read(toml_value: &str) -> Result<u64, String> {
        toml::from_str::<Holder>(&format!("seed = {toml_value}"))
            .map(|h| h.seed)
            .map_err(|e| e.message().to_string())
    }

    #[test]
    fn whole_numbers_are_seeds_and_anything_else_is_refused_with_the_range() {
        assert_eq!(read("0"), Ok(0));
        assert_eq!(read("42"), Ok(42));
        assert_eq!(read("7.0"), Ok(7));
        assert_eq!(read(&MAX_SEED.to_string()), Ok(MAX_SEED));
        for (bad, got) in [
            ("-1", "got -1"),
            ("1.5", "got 1.5"),
            ("\"7\"", "got \"7\""),
            ("true", "got true"),
        ] {
            let e = read(bad).unwrap_err();
            assert!(
                e.starts_with(&format!("must be a whole number between 0 and {MAX_SEED}"))
                    && e.ends_with(got),
                "{bad}: {e}"
            );
        }
    }
}
