//! The machinery behind the registry in `family/mod.rs`: the
//! [`families!`] macro that turns one line per family into the layer's
//! fields, the [`Table`](crate::spec::Table) enum and the paint-order list
//! of a layer's tables.
//!
//! Each family keeps its own TOML table in a layer (`[[layers.trees]]`,
//! `[layers.background]`, …) so that serde reports exact field paths.

/// Declares the family modules and defines `LayerSpec` (its fixed fields
/// as written, then one field per table), `Table` (one variant per table),
/// `LayerSpec::items` and `tables` (every family's `description` items,
/// which `crate::spec` re-exports).
///
/// A family is a module (`family/<name>/`, with its tables in
/// `description.rs`) and its tables, each with the generator that draws
/// it (`by build`: a function of the module taking the table, the group
/// id and the context). A table is `one` (an optional single
/// table, `[layers.NAME]`, id and field `NAME`) or `many` (an array,
/// `[[layers.NAME]]`, ids `NAME-K` unless the table names its own `id`,
/// fields `NAME[K]`). Paint order: the `one` tables (behind), then the
/// `many` tables, each in registry order and then in the order written.
macro_rules! families {
    (
        $(#[$layer_meta:meta])*
        pub struct LayerSpec {
            $( $(#[$fixed_meta:meta])* pub $fixed:ident : $fixed_ty:ty, )*
        }
        registry {
            $(
                $module:ident {
                    $(
                        $(#[$meta:meta])*
                        $field:ident: $kind:ident $variant:ident($spec:ident)
                            by $($build:ident)::+,
                    )*
                }
            )*
        }
    ) => {
        $( pub(crate) mod $module; )*

        /// Every family's description tables, for `crate::spec`.
        pub(crate) mod tables {
            $( pub use super::$module::description::*; )*
        }

        $(#[$layer_meta])*
        pub struct LayerSpec {
            $( $(#[$fixed_meta])* pub $fixed: $fixed_ty, )*
            $( $(
                $(#[$meta])*
                pub $field: families!(@type $kind $module::description::$spec),
            )* )*
        }

        /// The table of one motif family in a layer.
        #[derive(Debug, Clone, Copy, PartialEq)]
        #[non_exhaustive]
        pub enum Table<'a> {
            $( $(
                #[doc = concat!("A `", stringify!($field), "` table of the layer.")]
                $variant(&'a $module::description::$spec),
            )* )*
        }

        impl<'a> Table<'a> {
            /// The table as the seam sees every family.
            pub(crate) fn family(self) -> &'a dyn $crate::family::Family {
                match self {
                    $( $( Table::$variant(t) => t, )* )*
                }
            }

            /// Draws the table into one group with id `group_id`
            /// (`<layer>.<item id>`), by its family's generator: ids
            /// below it, randomness from `cx.stream(id)`, paths taken
            /// from the budget before the work.
            ///
            /// # Errors
            /// What the generator reports: the path budget running out,
            /// an adjustment that does not fit what it addresses, a user
            /// motif missing from the library.
            pub(crate) fn draw(
                self,
                group_id: &str,
                cx: &mut $crate::motif::Context<'_>,
            ) -> $crate::error::Result<$crate::scene::Group> {
                match self {
                    $( $( Table::$variant(t) => $module::$($build)::+(t, group_id, cx), )* )*
                }
            }

            /// The name of the family's field in a layer (`trees`,
            /// `background`, …).
            pub fn name(self) -> &'static str {
                match self {
                    $( $( Table::$variant(_) => stringify!($field), )* )*
                }
            }
        }

        impl LayerSpec {
            /// An empty layer `name`, drawn with pen `pen`: the rest as a
            /// description that leaves it out gives it (no tables).
            pub fn new(name: impl Into<String>, pen: u32) -> LayerSpec {
                let mut layer = LayerSpec {
                    $( $fixed: Default::default(), )*
                    $( $( $field: Default::default(), )* )*
                };
                layer.name = name.into();
                layer.pen = pen;
                layer
            }

            /// The layer's tables in paint order: the single tables (the
            /// background) behind, then each family's tables in the order
            /// written.
            pub fn items(&self) -> Vec<LayerItem<'_>> {
                let mut items = Vec::new();
                $( $( families!(@one $kind self, items, $field, $variant); )* )*
                $( $( families!(@many $kind self, items, $field, $variant); )* )*
                items
            }
        }
    };
    (@type one $($spec:tt)*) => { Option<$($spec)*> };
    (@type many $($spec:tt)*) => { Vec<$($spec)*> };
    (@one one $layer:ident, $items:ident, $field:ident, $variant:ident) => {
        $items.extend($layer.$field.iter().map(|t| LayerItem {
            table: Table::$variant(t),
            id: stringify!($field).into(),
            field: stringify!($field).into(),
        }))
    };
    (@one many $($rest:tt)*) => {};
    (@many many $layer:ident, $items:ident, $field:ident, $variant:ident) => {
        $crate::family::registry::numbered(
            &mut $items,
            stringify!($field),
            &$layer.$field,
            |t| &t.id,
            Table::$variant,
        )
    };
    (@many one $($rest:tt)*) => {};
}
pub(crate) use families;

use crate::spec::{LayerItem, Table};

/// Appends the tables of a `[[layers.NAME]]` array: ids are their own or
/// `NAME-K`, fields `NAME[K]`.
pub(crate) fn numbered<'a, T>(
    items: &mut Vec<LayerItem<'a>>,
    name: &str,
    tables: &'a [T],
    id: impl Fn(&T) -> &Option<String>,
    table: impl Fn(&'a T) -> Table<'a>,
) {
    for (k, t) in tables.iter().enumerate() {
        items.push(LayerItem {
            table: table(t),
            id: id(t).clone().unwrap_or_else(|| format!("{name}-{k}")),
            field: format!("{name}[{k}]"),
        });
    }
}
