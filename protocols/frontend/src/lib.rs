//! The front-end kit: what every protocol front-end of mcemu shares, so that a new front-end
//! writes only its codec and its service (ARCHITECTURE §5).

pub mod artefact;
pub mod axis_ref;

pub use artefact::{Artefact, ArtefactError, Artefacts, Located};
pub use axis_ref::{AxisRef, AxisRefError};
