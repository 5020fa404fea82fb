//! [`ValidSpec`]: a scene description that passed validation, as a type.
//!
//! Everything downstream (`project`, the generators) takes a `ValidSpec`
//! and trusts it: ranges, finiteness, references and sizes were checked
//! once, here at the boundary. Its fields can be read (it dereferences to
//! [`SceneSpec`]) but not changed; [`ValidSpec::edit`] changes a copy and
//! validates it again.
//!
//! A description parsed from TOML keeps its text, so that errors found
//! later — an `[[adjust]]` id that matches nothing once the scene is built
//! — point at a line and column like every other field error
//! ([`ValidSpec::locate`]).

use std::ops::Deref;
use std::sync::Arc;

use super::{locate, Format, SceneSpec};
use crate::error::{Error, Result};

/// A validated scene description (see the module docs).
#[derive(Debug, Clone)]
pub struct ValidSpec {
    spec: SceneSpec,
    /// The TOML text it was parsed from, for error locations.
    toml: Option<Arc<str>>,
}

impl ValidSpec {
    /// Parses and validates a description.
    ///
    /// # Errors
    /// [`Error::Parse`] for text that is not a description, and
    /// [`Error::Invalid`] for a value out of range; both name the field and,
    /// where known, the line and column.
    pub fn parse(text: &str, format: Format) -> Result<ValidSpec> {
        let spec = super::parse_text(text, format)?;
        let toml = (format == Format::Toml).then(|| Arc::from(text));
        let valid = ValidSpec { spec, toml };
        super::validate::scene(&valid.spec).map_err(|e| valid.locate(e))?;
        Ok(valid)
    }

    /// Validates a description built in code.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the first field that is wrong.
    pub fn new(spec: SceneSpec) -> Result<ValidSpec> {
        super::validate::scene(&spec)?;
        Ok(ValidSpec { spec, toml: None })
    }

    /// Every numeric field of this description that validation checks
    /// against a range, with that range, in the order of the description.
    /// A field left out of the description is listed when it has a
    /// default that is checked; an optional one only when it is given.
    ///
    /// ```
    /// let spec = moyo::templates::get("tree-rules")?.spec()?;
    /// let ranges = spec.ranges();
    /// let precision = ranges.iter().find(|r| r.field == "output.precision").unwrap();
    /// assert_eq!((precision.lo, precision.hi, precision.integer), (0.0, 8.0, true));
    /// # Ok::<(), moyo::Error>(())
    /// ```
    pub fn ranges(&self) -> Vec<super::FieldRange> {
        super::validate::recording(|| super::validate::scene(&self.spec)).1
    }

    /// The description.
    pub fn spec(&self) -> &SceneSpec {
        &self.spec
    }

    /// The description, to change and validate again.
    pub fn into_inner(self) -> SceneSpec {
        self.spec
    }

    /// A changed copy, validated again. Errors in the change carry no
    /// line and column (it is not in the text); errors found later while
    /// rendering still point into the original text.
    ///
    /// ```
    /// let spec = moyo::templates::get("tree-rules")?.spec()?;
    /// let other = spec.edit(|s| s.seed = 42)?;
    /// assert_eq!((spec.seed, other.seed), (spec.seed, 42));
    /// // A change that breaks a rule is refused with the field's path.
    /// let err = spec.edit(|s| s.output.precision = 99).unwrap_err();
    /// assert!(err.to_string().starts_with("output.precision: "), "{err}");
    /// # Ok::<(), moyo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`ValidSpec::new`].
    pub fn edit(&self, change: impl FnOnce(&mut SceneSpec)) -> Result<ValidSpec> {
        let mut spec = self.spec.clone();
        change(&mut spec);
        let edited = ValidSpec {
            spec,
            toml: self.toml.clone(),
        };
        super::validate::scene(&edited.spec)?;
        Ok(edited)
    }

    /// Writes the description as TOML. Parsing the result gives back an
    /// equal value.
    pub fn to_toml(&self) -> String {
        // Validation keeps every value serialisable (the seed below 2^63,
        // counts far below i64::MAX), so this cannot fail for a ValidSpec;
        // the error is kept as text rather than a panic all the same.
        toml::to_string(&self.spec).unwrap_or_else(|e| format!("# not serialisable: {e}\n"))
    }

    /// Adds the line and column of the field an [`Error::Invalid`] names,
    /// when the description came from TOML text and the error has none.
    pub fn locate(&self, e: Error) -> Error {
        match (e, &self.toml) {
            (
                Error::Invalid {
                    at: None,
                    field,
                    message,
                },
                Some(text),
            ) => Error::Invalid {
                at: locate::toml_field(text, &field),
                field,
                message,
            },
            (e, _) => e,
        }
    }
}

impl Deref for ValidSpec {
    type Target = SceneSpec;

    fn deref(&self) -> &SceneSpec {
        &self.spec
    }
}

/// Equal when the descriptions are equal, wherever they came from.
impl PartialEq for ValidSpec {
    fn eq(&self, other: &ValidSpec) -> bool {
        self.spec == other.spec
    }
}

impl PartialEq<SceneSpec> for ValidSpec {
    fn eq(&self, other: &SceneSpec) -> bool {
        self.spec == *other
    }
}

impl TryFrom<SceneSpec> for ValidSpec {
    type Error = Error;

    fn try_from(spec: SceneSpec) -> Result<ValidSpec> {
        ValidSpec::new(spec)
    }
}
