//! A depth layer and the seam between the file format and the motif
//! families: the one list of the tables a layer can hold.
//!
//! Each family has its own table in a layer (`[[layers.trees]]`,
//! `[layers.background]`, `[[layers.paths]]`, …), so that serde keeps exact
//! field paths for errors. [`LayerSpec::items`] lists them, in paint order,
//! as [`LayerItem`]s; validation, progress, the user files to load and the
//! generators' dispatch (`motif::build`) all go through that list, so a new
//! family is one more field, one line there and one line in the dispatch
//! (docs/ARCHITECTURE.md has the recipe).

use serde::{Deserialize, Serialize};

use super::{
    BackgroundSpec, LSystemSpec, LimbSpec, MotifRef, PathsSpec, TreeSetSpec, VineSpec, VoronoiSpec,
    ZentangleSpec,
};
use crate::error::Result;

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
    /// Tree sets, each along its own centre line.
    #[serde(default)]
    pub trees: Vec<TreeSetSpec>,
    /// A background pattern composited into a mask (SPEC §1.6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub background: Option<BackgroundSpec>,
    /// User paths and point lists, placed and repeated.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub paths: Vec<PathsSpec>,
    /// Voronoi and Delaunay patterns inside a region.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub voronoi: Vec<VoronoiSpec>,
    /// Zentangle fills inside a region.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub zentangle: Vec<ZentangleSpec>,
    /// L-systems: rules drawn by a turtle, or grown along a stroke.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lsystem: Vec<LSystemSpec>,
    /// Twining vines grown round their supports in 3D.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub vine: Vec<VineSpec>,
}

fn default_pen_number() -> u32 {
    1
}

/// The table of one motif family in a layer.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Table<'a> {
    /// `[layers.background]`: a mask from hidden trees and a pattern.
    Background(&'a BackgroundSpec),
    /// `[[layers.trees]]`: a set of trees along a centre line.
    Trees(&'a TreeSetSpec),
    /// `[[layers.paths]]`: user paths placed and repeated.
    Paths(&'a PathsSpec),
    /// `[[layers.voronoi]]`: Voronoi and Delaunay patterns in a region.
    Voronoi(&'a VoronoiSpec),
    /// `[[layers.zentangle]]`: zentangle fills in a region.
    Zentangle(&'a ZentangleSpec),
    /// `[[layers.lsystem]]`: an L-system or a sketch along a stroke.
    LSystem(&'a LSystemSpec),
    /// `[[layers.vine]]`: a twining vine round its supports.
    Vine(&'a VineSpec),
}

/// What the seam needs from every family's table.
pub trait Family {
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
}

impl<'a> Table<'a> {
    /// The table as the seam sees every family.
    pub fn family(self) -> &'a dyn Family {
        match self {
            Table::Background(t) => t,
            Table::Trees(t) => t,
            Table::Paths(t) => t,
            Table::Voronoi(t) => t,
            Table::Zentangle(t) => t,
            Table::LSystem(t) => t,
            Table::Vine(t) => t,
        }
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

impl LayerSpec {
    /// The layer's tables in paint order: the background behind, then
    /// each family's tables in the order written.
    pub fn items(&self) -> Vec<LayerItem<'_>> {
        let mut items = Vec::new();
        items.extend(self.background.iter().map(|b| LayerItem {
            table: Table::Background(b),
            id: "background".into(),
            field: "background".into(),
        }));
        numbered(&mut items, "trees", &self.trees, |t| &t.id, Table::Trees);
        numbered(&mut items, "paths", &self.paths, |t| &t.id, Table::Paths);
        numbered(
            &mut items,
            "voronoi",
            &self.voronoi,
            |t| &t.id,
            Table::Voronoi,
        );
        numbered(
            &mut items,
            "zentangle",
            &self.zentangle,
            |t| &t.id,
            Table::Zentangle,
        );
        numbered(
            &mut items,
            "lsystem",
            &self.lsystem,
            |t| &t.id,
            Table::LSystem,
        );
        numbered(&mut items, "vine", &self.vine, |t| &t.id, Table::Vine);
        items
    }
}

/// Appends the tables of a `[[layers.NAME]]` array: ids are their own or
/// `NAME-K`, fields `NAME[K]`.
fn numbered<'a, T>(
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
