//! Tree rule parameters (docs/SPEC.md §1.2, table 3.1 of the source), defined once.
//!
//! One macro invocation lists every parameter with its default and its
//! allowed range; from it come the optional-field file struct
//! ([`TreeParams`], used both for a tree set and for per-tree overrides),
//! the resolved struct ([`ResolvedTreeParams`]), the merge and the
//! validation. Adding a parameter is one line.

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::spec::validate::{base_curve, range};

macro_rules! tree_params {
    ($( $(#[$doc:meta])* $name:ident : $ty:ty = $default:expr, check $check:expr; )*) => {
        /// Tree rule parameters as written in a file; absent fields take the
        /// value of the enclosing set, or the default.
        #[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct TreeParams {
            $(
                $(#[$doc])*
                #[serde(default, skip_serializing_if = "Option::is_none")]
                pub $name: Option<$ty>,
            )*
        }

        /// Tree rule parameters with every value decided.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct ResolvedTreeParams {
            $( $(#[$doc])* pub $name: $ty, )*
        }

        impl TreeParams {
            /// True when no parameter is set.
            pub fn is_empty(&self) -> bool {
                true $( && self.$name.is_none() )*
            }

            /// These parameters where set, `base`'s elsewhere.
            pub fn over(&self, base: &TreeParams) -> TreeParams {
                TreeParams { $( $name: self.$name.or(base.$name), )* }
            }

            /// Every parameter decided, defaults where unset.
            pub fn resolve(&self) -> ResolvedTreeParams {
                ResolvedTreeParams { $( $name: self.$name.unwrap_or($default), )* }
            }

            /// Checks the set parameters; `field` is the path of this table.
            pub(crate) fn check(&self, field: &str) -> Result<()> {
                $(
                    if let Some(v) = self.$name {
                        let check: fn(&str, $ty) -> Result<()> = $check;
                        check(&format!("{field}.{}", stringify!($name)), v)?;
                    }
                )*
                Ok(())
            }
        }
    };
}

tree_params! {
    /// Generations (世代): trunk steps, 0–64 (the original allowed 0–20).
    generations: u32 = 6, check |f, v| range(f, v, 0, 64);
    /// Length of the first trunk step in mm (0.1–2000).
    trunk: f64 = 28.0, check |f, v| range(f, v, 0.1, 2000.0);
    /// Ang1: trunk bend per step in degrees (−180–180).
    ang1: f64 = 8.0, check |f, v| range(f, v, -180.0, 180.0);
    /// Ang2: angle between trunk and branch in degrees (−180–180).
    ang2: f64 = 50.0, check |f, v| range(f, v, -180.0, 180.0);
    /// Ang3: fork angle of Tree4 prongs and Tree6 root branches (−180–180).
    ang3: f64 = 35.0, check |f, v| range(f, v, -180.0, 180.0);
    /// Ratio1: trunk length ratio per step (0.05–1.5).
    ratio1: f64 = 0.85, check |f, v| range(f, v, 0.05, 1.5);
    /// Ratio2: branch length as a fraction of the trunk step (0.01–2).
    ratio2: f64 = 0.55, check |f, v| range(f, v, 0.01, 2.0);
    /// Ratio3: Tree6 root-branch length as a fraction of the first step
    /// (0.01–2).
    ratio3: f64 = 0.5, check |f, v| range(f, v, 0.01, 2.0);
    /// Depth of complex branches (TreeSub) of Tree1 and Tree3, 0–16 (the
    /// source fixes it at 3).
    sub_generations: u32 = 3, check |f, v| range(f, v, 0, 16);
    /// Random bend added to every angle, ± degrees (0–45).
    jitter_angle: f64 = 3.0, check |f, v| range(f, v, 0.0, 45.0);
    /// Random change of every length, ± fraction (0–0.5).
    jitter_length: f64 = 0.06, check |f, v| range(f, v, 0.0, 0.5);
    /// Tree8 base curve: 4 control points in the tree's own frame, in units
    /// of `trunk`: x to the right of the growth direction, y along it.
    base: [[f64; 2]; 4] = [[0.0, 0.0], [0.35, 1.3], [-0.3, 2.6], [0.15, 3.9]],
        check |f, v| base_curve(f, &v);
}
