//! The `zentangle` family (SPEC §2, issue 10): the filling process of the
//! zentangle paper in exact vector form.
//!
//! This folder will own the family: its elements, placement templates,
//! region patterns, the twenty procedures with their seed groups and the
//! filling loop. For now it holds the library layer the family stands on:
//! - `element`: the 26 elements (basic and compound shapes) as marks in
//!   painter's order, their placement and hand-drawn deformation;
//! - `compose`: what a list of marks does to a white region: the visible
//!   lines, the white pieces left (with the mark each lies in) and the
//!   black area;
//! - `placement`: the placement templates MR, MT, MS, MA, MC and ML, where
//!   the elements of a symmetric pattern go.
// Wired by the zentangle family (issue 10, next step).
#![allow(dead_code)]

mod compose;
mod element;
mod placement;
