//! The HTTP + JSON control API (ARCHITECTURE §6): the back door tests and users need.

use std::sync::Arc;

use axes::runtime::EngineHandle;
use axum::extract::State;
use axum::routing::get;
use axum::{Json, Router};

/// What every handler needs.
#[derive(Clone)]
pub struct ControlState {
    pub handle: EngineHandle,
    pub machine: Arc<String>,
}

/// The API's routes, versioned under `/api/v1`.
pub fn router(state: ControlState) -> Router {
    Router::new()
        .route("/api/v1/state", get(get_state))
        .with_state(state)
}

async fn get_state(State(state): State<ControlState>) -> Json<serde_json::Value> {
    let snapshot = state.handle.snapshot();
    Json(serde_json::json!({
        "machine": state.machine.as_str(),
        "tick": snapshot.tick,
        "time": snapshot.time(),
        "axes": snapshot.axes,
    }))
}
