//! `?controller_serial=` (issue 34): the serial of the controller a caller
//! is about to apply an answer on, for the calls that apply a set
//! (`compensate`, `filter`, `export`, the re-check). A mismatch is a 409
//! naming `controller`; `expect_controller` in a body names more fields.

use serde::Deserialize;
use utoipa::IntoParams;

#[derive(Debug, Default, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
pub struct ControllerQuery {
    /// The controller's serial the caller expects the set (for a re-check:
    /// the approved set) to be made on: 409 naming `controller`, with both
    /// identities, when it records another.
    pub controller_serial: Option<String>,
}
