//! Device profiles: a plotter or cutter described once — its language
//! (G-code or HPGL) and every habit of it — and named, so a plot fits the
//! machine without a page of flags.
//!
//! A profile is a TOML table with a one-line `about` and exactly one of
//! `[gcode]` ([`GcodeOptions`]) or `[hpgl]` ([`HpglOptions`]); it may start
//! from a built-in one (`profile = "grbl-z"`) and change only what differs,
//! table by table:
//!
//! ```toml
//! profile = "grbl-z"
//! about = "my router, pen 1 mm lower"
//! [gcode]
//! pen_up = "G0 Z4"
//! height_range = [-1.5, -0.5]
//! ```
//!
//! The same table is the `[device]` of a scene description, which `moyo
//! render -o x.gcode` writes with and `moyo plot` finds again in an SVG
//! that `moyo render` wrote; `moyo plot --device NAME|FILE` names one on
//! the command line. The built-in profiles ([`BUILT_IN`]) are the TOML
//! files in `src/output/devices/`, each with comments saying what machine
//! it is for and why its numbers are what they are; `moyo devices NAME`
//! prints one to start from.
//!
//! Resolving a profile checks everything before anything is written:
//! unknown fields, an unknown profile, placeholders a template does not
//! allow, ranges — each refusal names the field (`device.gcode.pen_dwn`).

use serde::{Deserialize, Serialize};

use super::gcode::GcodeOptions;
use super::hpgl::HpglOptions;
use crate::error::{Error, Result};

/// A built-in device profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BuiltIn {
    /// Its name (`grbl-z`).
    pub name: &'static str,
    /// The profile's TOML, with comments.
    pub text: &'static str,
}

/// The built-in profiles, by name.
pub const BUILT_IN: &[BuiltIn] = &[
    BuiltIn {
        name: "grbl-servo",
        text: include_str!("devices/grbl-servo.toml"),
    },
    BuiltIn {
        name: "grbl-z",
        text: include_str!("devices/grbl-z.toml"),
    },
    BuiltIn {
        name: "marlin",
        text: include_str!("devices/marlin.toml"),
    },
    BuiltIn {
        name: "hp7475a",
        text: include_str!("devices/hp7475a.toml"),
    },
    BuiltIn {
        name: "roland-dxy",
        text: include_str!("devices/roland-dxy.toml"),
    },
    BuiltIn {
        name: "drag-knife",
        text: include_str!("devices/drag-knife.toml"),
    },
];

impl BuiltIn {
    /// The built-in profile called `name`.
    pub fn get(name: &str) -> Option<&'static BuiltIn> {
        BUILT_IN.iter().find(|b| b.name == name)
    }

    /// The built-in profiles' names, comma-separated, for messages.
    pub fn names() -> String {
        BUILT_IN
            .iter()
            .map(|b| b.name)
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Its `about` line.
    pub fn about(&self) -> String {
        DeviceSpec::parse(self.text)
            .ok()
            .and_then(|s| s.about)
            .unwrap_or_default()
    }
}

/// A device table as written: a profile file, or a scene's `[device]`
/// (see the module documentation). [`DeviceSpec::resolve`] turns it into
/// a [`Device`].
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DeviceSpec {
    /// The built-in profile these settings change ([`BUILT_IN`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<String>,
    /// One line saying what machine this is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub about: Option<String>,
    /// G-code settings ([`GcodeOptions`]'s fields; those not given keep
    /// the profile's, or the defaults).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gcode: Option<toml::Table>,
    /// HPGL settings ([`HpglOptions`]'s fields, likewise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hpgl: Option<toml::Table>,
}

/// A resolved device: the writer and its options.
// One per plot: the size of the larger variant costs nothing, a box would
// cost every caller a dereference.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Device {
    /// A G-code machine.
    Gcode(GcodeOptions),
    /// An HPGL plotter or cutter.
    Hpgl(HpglOptions),
}

impl DeviceSpec {
    /// Reads a profile file's text (TOML).
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the field for what TOML or the table's
    /// fields refuse.
    pub fn parse(text: &str) -> Result<DeviceSpec> {
        toml::from_str(text).map_err(|e| Error::invalid("device", e.message().to_string()))
    }

    /// The device this table describes: its profile's settings with this
    /// table's over them, checked. Field names in errors start with
    /// `device.`.
    ///
    /// # Errors
    /// [`Error::Invalid`] for an unknown profile, a table for the other
    /// language than the profile's, no language at all or both, fields
    /// the options do not have or refuse.
    pub fn resolve(&self) -> Result<Device> {
        let base = match &self.profile {
            Some(name) => {
                let built_in = BuiltIn::get(name).ok_or_else(|| {
                    Error::invalid(
                        "device.profile",
                        format!("unknown profile '{name}'; built in: {}", BuiltIn::names()),
                    )
                })?;
                let base = DeviceSpec::parse(built_in.text)?;
                if base.profile.is_some() {
                    return Err(Error::invalid(
                        "device.profile",
                        "a built-in profile starts from no other",
                    ));
                }
                Some((name.as_str(), base))
            }
            None => None,
        };
        let mut gcode = base.as_ref().and_then(|(_, b)| b.gcode.clone());
        let mut hpgl = base.as_ref().and_then(|(_, b)| b.hpgl.clone());
        if let Some((name, _)) = &base {
            let (mine, theirs, language) = match (&self.gcode, &self.hpgl) {
                (Some(_), _) if gcode.is_none() => ("gcode", "hpgl", "an HPGL"),
                (_, Some(_)) if hpgl.is_none() => ("hpgl", "gcode", "a G-code"),
                _ => ("", "", ""),
            };
            if !mine.is_empty() {
                return Err(Error::invalid(
                    format!("device.{mine}"),
                    format!("profile '{name}' is {language} device: change its [{theirs}] table"),
                ));
            }
        }
        merge(&mut gcode, &self.gcode);
        merge(&mut hpgl, &self.hpgl);
        match (gcode, hpgl) {
            (Some(table), None) => {
                let options: GcodeOptions = table.try_into().map_err(|e: toml::de::Error| {
                    Error::invalid("device.gcode", e.message().to_string())
                })?;
                options.validate().map_err(prefixed)?;
                Ok(Device::Gcode(options))
            }
            (None, Some(table)) => {
                let options: HpglOptions = table.try_into().map_err(|e: toml::de::Error| {
                    Error::invalid("device.hpgl", e.message().to_string())
                })?;
                options.validate().map_err(prefixed)?;
                Ok(Device::Hpgl(options))
            }
            (None, None) => Err(Error::invalid(
                "device",
                "needs a profile, or a [gcode] or [hpgl] table",
            )),
            (Some(_), Some(_)) => Err(Error::invalid(
                "device",
                "is either a G-code or an HPGL device: one of [gcode] and [hpgl]",
            )),
        }
    }
}

/// `over`'s keys written into `base`, tables merged key by key.
fn merge(base: &mut Option<toml::Table>, over: &Option<toml::Table>) {
    let Some(over) = over else { return };
    let base = base.get_or_insert_with(toml::Table::new);
    for (key, value) in over {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => {
                let mut inner = Some(std::mem::take(b));
                merge(&mut inner, &Some(o.clone()));
                *b = inner.unwrap_or_default();
            }
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

/// An options error with `device.` before its field.
fn prefixed(e: Error) -> Error {
    match e {
        Error::Invalid { field, message, at } => Error::Invalid {
            field: format!("device.{field}"),
            message,
            at,
        },
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_built_in_profile_resolves_and_says_what_it_is() {
        for b in BUILT_IN {
            let spec = DeviceSpec::parse(b.text).unwrap();
            assert!(spec.resolve().is_ok(), "{}", b.name);
            assert!(!b.about().is_empty(), "{}", b.name);
            // And as the base of a profile that changes nothing.
            let on_top = DeviceSpec {
                profile: Some(b.name.into()),
                ..DeviceSpec::default()
            };
            assert_eq!(
                on_top.resolve().unwrap(),
                spec.resolve().unwrap(),
                "{}",
                b.name
            );
        }
    }

    #[test]
    fn a_profile_changes_only_what_it_says() {
        let spec =
            DeviceSpec::parse("profile = \"grbl-z\"\n[gcode]\npen_up = \"G0 Z4\"\n").unwrap();
        let Device::Gcode(o) = spec.resolve().unwrap() else {
            panic!("grbl-z is G-code")
        };
        assert_eq!(o.pen_up, "G0 Z4");
        assert_eq!(o.pen_down, "G1 Z{height} F600");
        assert_eq!(o.feed_up_mm_min, None, "G0 travel kept");

        // Nested tables merge key by key.
        let spec =
            DeviceSpec::parse("profile = \"drag-knife\"\n[hpgl.cutter]\novercut_mm = 2\n").unwrap();
        let Device::Hpgl(o) = spec.resolve().unwrap() else {
            panic!("drag-knife is HPGL")
        };
        let cutter = o.cutter.unwrap();
        assert_eq!((cutter.overcut_mm, cutter.knife_offset_mm), (2.0, 0.25));
    }

    #[test]
    fn bad_profiles_name_the_field_and_what_is_allowed() {
        let cases = [
            (
                "profile = \"grbl\"",
                "device.profile: unknown profile 'grbl'; built in: grbl-servo",
            ),
            (
                "profile = \"hp7475a\"\n[gcode]\npen_up = \"M5\"",
                "device.gcode: profile 'hp7475a' is an HPGL device",
            ),
            (
                "[gcode]\npen_dwn = \"M3\"",
                "device.gcode: unknown field `pen_dwn`",
            ),
            (
                "[gcode]\ntool_change = \"M0 {pne}\"",
                "device.gcode.tool_change: unknown placeholder {pne}",
            ),
            ("[hpgl]\nunits_per_mm = -1", "device.hpgl.units_per_mm"),
            ("about = \"nothing\"", "device: needs a profile"),
            ("[gcode]\n[hpgl]", "device: is either"),
            ("speed = 3", "device: unknown field `speed`"),
        ];
        for (text, want) in cases {
            let e = DeviceSpec::parse(text)
                .and_then(|s| s.resolve())
                .unwrap_err()
                .to_string();
            assert!(e.starts_with(want), "{text}: {e}");
        }
    }
}
