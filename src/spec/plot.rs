//! `[plot]` of a description: the plot stages a render runs. The option
//! types are the stages' own ([`crate::plot`]), so the file and the
//! library cannot drift apart.
//!
//! The pen stage — `dedupe`, `merge`, `blots`, `debris`, `sort` — runs unless a
//! step is turned off (`dedupe = false`); a table tunes a step
//! (`[plot.dedupe]` with `tolerance = 0.05`). The other stages run only
//! when their table is there (`[plot.occlude]`).

use std::fmt;
use std::marker::PhantomData;

use serde::de::{MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::error::Result;
use crate::plot::{
    BlotOptions, DebrisOptions, DedupeOptions, HatchOptions, MergeOptions, MultipassOptions,
    OccludeOptions, PlotOptions, SimplifyOptions, SortOptions, TransformOptions,
};

/// The `[plot]` table.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlotSpec {
    /// Rotate, scale, fit to the page, centre.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transform: Option<TransformOptions>,
    /// Remove strokes hidden behind closed shapes in front.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub occlude: Option<OccludeOptions>,
    /// Turn fills into hatch lines.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hatch: Option<HatchOptions>,
    /// Pen stage: take out line work that lies on line work of the same
    /// pen. On by default.
    #[serde(default, skip_serializing_if = "Step::is_on")]
    pub dedupe: Step<DedupeOptions>,
    /// Pen stage: join paths whose ends meet. On by default.
    #[serde(default, skip_serializing_if = "Step::is_on")]
    pub merge: Step<MergeOptions>,
    /// Pen stage: trim line ends where a square millimetre would hold
    /// more ink than `limit` times solid (default 2). On by default.
    #[serde(default, skip_serializing_if = "Step::is_on")]
    pub blots: Step<BlotOptions>,
    /// Pen stage: take out strokes shorter than the pen is wide that touch
    /// others. On by default.
    #[serde(default, skip_serializing_if = "Step::is_on")]
    pub debris: Step<DebrisOptions>,
    /// Drop points within a tolerance.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simplify: Option<SimplifyOptions>,
    /// Pen stage: order paths to shorten pen-up travel. On by default.
    #[serde(default, skip_serializing_if = "Step::is_on")]
    pub sort: Step<SortOptions>,
    /// Draw every path several times.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multipass: Option<MultipassOptions>,
}

impl PlotSpec {
    /// Whether it says nothing a file need say.
    pub fn is_default(&self) -> bool {
        *self == PlotSpec::default()
    }

    /// No stage at all, the pen stage turned off too: the drawing as its
    /// generators made it, with the description's layers and groups.
    pub fn none() -> PlotSpec {
        PlotSpec {
            dedupe: Step::Off,
            merge: Step::Off,
            blots: Step::Off,
            debris: Step::Off,
            sort: Step::Off,
            ..PlotSpec::default()
        }
    }

    /// The stages to run.
    pub fn options(&self) -> PlotOptions {
        PlotOptions {
            transform: self.transform,
            occlude: self.occlude.clone(),
            hatch: self.hatch,
            dedupe: self.dedupe.options(),
            merge: self.merge.options(),
            blots: self.blots.options(),
            debris: self.debris.options(),
            simplify: self.simplify,
            sort: self.sort.options(),
            multipass: self.multipass,
            inside_first: false,
        }
    }

    /// Checks every option's range; `field` prefixes the error paths.
    pub fn validate(&self, field: &str) -> Result<()> {
        self.options().validate(field)
    }
}

/// A step of the pen stage: on with its defaults (written as nothing, or
/// `true`), off (`false`), or tuned (a table of its options).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Step<T> {
    /// With its defaults.
    #[default]
    On,
    /// Not run.
    Off,
    /// With these options.
    With(T),
}

impl<T: Default + Clone> Step<T> {
    fn is_on(&self) -> bool {
        matches!(self, Step::On)
    }

    /// The options it runs with, `None` when off.
    pub fn options(&self) -> Option<T> {
        match self {
            Step::On => Some(T::default()),
            Step::Off => None,
            Step::With(t) => Some(t.clone()),
        }
    }
}

impl<T: Serialize> Serialize for Step<T> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Step::On => s.serialize_bool(true),
            Step::Off => s.serialize_bool(false),
            Step::With(t) => t.serialize(s),
        }
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Step<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct StepVisitor<T>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>> Visitor<'de> for StepVisitor<T> {
            type Value = Step<T>;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("true, false or a table of options")
            }

            fn visit_bool<E>(self, on: bool) -> std::result::Result<Step<T>, E> {
                Ok(if on { Step::On } else { Step::Off })
            }

            fn visit_map<A: MapAccess<'de>>(
                self,
                map: A,
            ) -> std::result::Result<Step<T>, A::Error> {
                T::deserialize(serde::de::value::MapAccessDeserializer::new(map)).map(Step::With)
            }
        }
        d.deserialize_any(StepVisitor(PhantomData))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> std::result::Result<PlotSpec, toml::de::Error> {
        toml::from_str(text)
    }

    #[test]
    fn the_pen_stage_is_on_unless_a_step_is_turned_off() {
        let options = parse("").unwrap().options();
        assert_eq!(options, PlotOptions::pen_ready());
        let off = parse("dedupe = false\nsort = false\n").unwrap().options();
        assert!(off.dedupe.is_none() && off.sort.is_none());
        assert!(off.merge.is_some() && off.debris.is_some());
        let tuned = parse("[dedupe]\ntolerance = 0.05\n").unwrap().options();
        assert_eq!(tuned.dedupe.unwrap().tolerance, Some(0.05));
        assert_eq!(parse("dedupe = true\n").unwrap(), PlotSpec::default());
        assert!(PlotSpec::none().options().is_empty());
    }

    #[test]
    fn it_is_written_as_it_was_read() {
        for text in ["", "dedupe = false\n", "[debris]\nlength = 0.5\n"] {
            let spec = parse(text).unwrap();
            let written = toml::to_string(&spec).unwrap();
            assert_eq!(parse(&written).unwrap(), spec, "{written}");
        }
    }

    #[test]
    fn a_wrong_step_says_what_it_takes() {
        let e = parse("dedupe = 3\n").unwrap_err().to_string();
        assert!(e.contains("true, false or a table of options"), "{e}");
        let e = parse("[dedupe]\ntolerence = 1\n").unwrap_err().to_string();
        assert!(e.contains("tolerence"), "{e}");
        let e = PlotSpec {
            dedupe: Step::With(DedupeOptions::DEFAULT.with_tolerance(Some(-1.0))),
            ..PlotSpec::default()
        }
        .validate("plot")
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("plot.dedupe.tolerance"), "{e}");
        assert!(e.contains("between 0 and 10"), "{e}");
    }
}
