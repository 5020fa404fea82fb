//! The motif families, one folder each, and the registry that is the one
//! seam between them and the rest of the crate.
//!
//! A family's folder holds everything it owns: its description table
//! (`description.rs`), its generator, its engine and the geometry only it
//! uses. `kimono` (tree sets and backgrounds on the eight tree rules),
//! `paths` (user paths placed and repeated), `voronoi` (cells, Delaunay
//! edges, stipples and tours in a region), `zentangle` (the filling
//! process), `lsystem` (the L-system engine and the stroke-guided sketch),
//! `vine` (the twining-vine simulation, seen through a camera), `wagara`
//! (traditional grounds) and `text` (titles and signatures in
//! single-stroke letters).
//!
//! Each table type implements [`Family`]; the registry below lists one
//! line per table, and the [`families!`](registry::families) macro makes
//! of it the layer's fields, the [`Table`] enum and
//! [`LayerSpec::items`], the list that validation, progress, user-file
//! loading and [`build`] all go through. Adding a family is a folder, a
//! registry line and a template (docs/ARCHITECTURE.md has the recipe).

#[cfg(feature = "studio")]
pub(crate) mod gesture;
pub(crate) mod registry;

use kurbo::Point;
use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::motif::Context;
use crate::scene::Group;
use crate::spec::{LimbSpec, MotifRef, VoronoiSpec};
use registry::families;

// The registry: each family's folder and its tables, in the order of the
// layer's fields. Paint order puts the single tables (the background)
// behind the rest.
families! {
    /// One depth layer.
    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct LayerSpec {
        /// Unique name; the layer's id in the SVG is made from it.
        pub name: String,
        /// Pen number.
        #[serde(default = "default_pen_number")]
        pub pen: u32,
        /// 0 is the front; larger is further back. Default: position in the list.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub depth: Option<i32>,
        /// How tree limbs are drawn.
        #[serde(default)]
        pub limbs: LimbSpec,
    }
    registry {
        kimono {
            /// Tree sets, each along its own centre line.
            #[serde(default)]
            trees: many Trees(TreeSetSpec) by tree_set,
            /// A background pattern composited into a mask (docs/SPEC.md §1.6).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            background: one Background(BackgroundSpec) by background::background,
        }
        paths {
            /// User paths and point lists, placed and repeated.
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            paths: many Paths(PathsSpec) by build,
        }
        voronoi {
            /// Voronoi and Delaunay patterns inside a region.
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            voronoi: many Voronoi(VoronoiSpec) by build,
        }
        zentangle {
            /// Zentangle fills inside a region.
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            zentangle: many Zentangle(ZentangleSpec) by build,
        }
        lsystem {
            /// L-systems: rules drawn by a turtle, or grown along a stroke.
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            lsystem: many LSystem(LSystemSpec) by build,
        }
        vine {
            /// Twining vines grown round their supports in 3D.
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            vine: many Vine(VineSpec) by build,
        }
        wagara {
            /// Traditional grounds (和柄) filling a region as one seamless repeat.
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            wagara: many Wagara(WagaraSpec) by build,
        }
        text {
            /// Titles and signatures in single-stroke letters.
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            text: many Text(TextSpec) by build,
        }
    }
}

fn default_pen_number() -> u32 {
    1
}

/// What the seam needs from every family's table.
pub(crate) trait Family {
    /// Checks the table; `field` is its path (`layers[0].trees[1]`).
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the field below `field`.
    fn check(&self, field: &str) -> Result<()>;

    /// Units of work the table makes, for progress reports (a tree, a
    /// cell, a plant …); the generator reports them as it goes.
    fn work(&self) -> usize {
        1
    }

    /// The motifs it names (user motifs among them are loaded by the
    /// caller, since generators never read files).
    fn motifs(&self) -> Vec<&MotifRef> {
        Vec::new()
    }

    /// The SVG files of paths it draws, relative to the description.
    fn path_files(&self) -> Vec<&str> {
        Vec::new()
    }

    /// The PNG or JPEG files it reads as density, relative to the
    /// description.
    fn image_files(&self) -> Vec<&str> {
        Vec::new()
    }

    /// The Wavefront OBJ files it reads as closed meshes, relative to the
    /// description.
    fn mesh_files(&self) -> Vec<&str> {
        Vec::new()
    }

    /// The layers whose regions it fills, by name, each with the field
    /// that names it below the table (`region.layer`). They must come
    /// before its own layer and offer regions.
    fn layers_read(&self) -> Vec<(&'static str, &str)> {
        Vec::new()
    }

    /// Whether the regions it draws (cells, a mask) can be filled by the
    /// tables of later layers.
    fn offers_regions(&self) -> bool {
        false
    }

    /// What it offers the studio's gestures, if anything.
    #[cfg(feature = "studio")]
    fn gestures(&self) -> Option<&dyn gesture::Gestures> {
        None
    }
}

/// One table of a layer with its id and field path.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerItem<'a> {
    /// The family's table.
    pub table: Table<'a>,
    /// Its id in the layer (its own `id`, or `trees-0`, `paths-2`,
    /// `background`): the middle part of the SVG ids it makes.
    pub id: String,
    /// Its field path in the layer (`trees[0]`, `background`).
    pub field: String,
}

/// Builds one table of the layer being built into a group with id
/// `<layer>.<item id>`, and counts its declared work as done.
///
/// # Errors
/// What the family's generator reports (see `Table::draw`).
pub(crate) fn build(item: &LayerItem<'_>, cx: &mut Context<'_>) -> Result<Group> {
    let id = format!("{}.{}", cx.layer_id(), item.id);
    let done = cx.done() + item.table.family().work();
    cx.enter_item(&item.field);
    let group = item.table.draw(&id, cx)?;
    cx.advance_to(done);
    Ok(group)
}

/// The sites the voronoi table `item` (`spec`) of the layer being built
/// starts from, before relaxation (see [`crate::project::voronoi_sites`]).
///
/// # Errors
/// As [`build`], up to the sites.
pub(crate) fn voronoi_sites(
    item: &LayerItem<'_>,
    spec: &VoronoiSpec,
    cx: &mut Context<'_>,
) -> Result<Vec<Point>> {
    let id = format!("{}.{}", cx.layer_id(), item.id);
    cx.enter_item(&item.field);
    voronoi::starting_sites(spec, &id, cx)
}
