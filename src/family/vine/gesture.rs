//! The camera of a vine turned round it: written as `camera = { turn,
//! tilt }` (a preset or a placed camera first becomes the orbit that sees
//! the same), the turn kept in −180–180 and the tilt in −89–89.

use serde_json::json;

use crate::error::{Error, Result};
use crate::family::gesture::{tenth, Change, Gesture, Gestures};
use crate::spec::VineSpec;

impl Gestures for VineSpec {
    fn offers(&self) -> Vec<(Gesture, serde_json::Value)> {
        // "below" and placed perspective cameras do not turn: the page
        // says so rather than jump.
        vec![(
            Gesture::Orbit,
            json!({ "orbits": self.camera.orbit().is_some() }),
        )]
    }

    fn turn(&self, field: &str, turn: f64, tilt: f64) -> Result<Vec<Change>> {
        let field = format!("{field}.camera");
        let Some(now) = self.camera.orbit() else {
            return Err(Error::invalid(
                &field,
                "this camera does not turn round the vine (\"below\" and perspective cameras              placed by hand): give camera = { turn = 0, tilt = 10 } to turn it",
            ));
        };
        let turn = tenth(180.0 - (180.0 - (now.turn + turn)).rem_euclid(360.0));
        let tilt = tenth((now.tilt + tilt).clamp(-89.0, 89.0));
        let mut camera = toml_edit::InlineTable::new();
        camera.insert("turn", turn.into());
        camera.insert("tilt", tilt.into());
        if let Some(fov) = now.perspective {
            camera.insert("perspective", fov.into());
        }
        Ok(vec![Change::Set(field, camera.into())])
    }
}
