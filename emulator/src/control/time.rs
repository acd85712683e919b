//! `POST /time/advance`: run the virtual clock by ticks or seconds, optionally until an axis
//! condition holds.

use axes::runtime::{AdvanceError, ClockMode, EngineHandle};
use axes::status::{AxisFlags, AxisState, GroupState};
use axes::Snapshot;
use axum::extract::State;
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::{Deserialize, Serialize};

use super::error::{parse_json, ApiError, JsonBody};
use super::names::flag_by_name;
use super::ControlState;

/// Most ticks one request may run: one simulated hour at the default 1 ms period. The servo
/// thread runs an advance without a break (commands queue behind it), so this bounds how long
/// one request can hold it: a few seconds of wall time for a small machine.
pub const MAX_ADVANCE_TICKS: u64 = 3_600_000;

/// `{"ticks": N}` or `{"seconds": S}` (rounded to whole ticks), with an optional `until`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdvanceRequest {
    #[serde(default)]
    ticks: Option<u64>,
    #[serde(default)]
    seconds: Option<f64>,
    /// Stop early, after the first tick at which this holds; `ticks`/`seconds` is then the
    /// bound.
    #[serde(default)]
    until: Option<UntilCondition>,
}

/// A condition on one axis, checked on the snapshot after each tick: its `state` is the one
/// named, and/or its `flag` is set (or clear with `"value": false`). Both given: both hold.
/// Or a condition on an axis group: `{"group": 1, "group_state": "standby"}`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UntilCondition {
    #[serde(default)]
    axis: Option<u16>,
    #[serde(default)]
    group: Option<u16>,
    #[serde(default)]
    group_state: Option<GroupState>,
    #[serde(default)]
    state: Option<AxisState>,
    #[serde(default)]
    flag: Option<String>,
    #[serde(default = "yes")]
    value: bool,
}

fn yes() -> bool {
    true
}

/// A checked condition, cheap to evaluate on the servo thread.
#[derive(Clone, Copy, Debug)]
enum Check {
    Axis {
        axis: usize,
        state: Option<AxisState>,
        flag: Option<(AxisFlags, bool)>,
    },
    Group {
        group: u16,
        state: GroupState,
    },
}

impl Check {
    fn holds(&self, snapshot: &Snapshot) -> bool {
        match *self {
            Check::Axis { axis, state, flag } => snapshot.axes.get(axis).is_some_and(|a| {
                state.is_none_or(|s| a.state == s)
                    && flag.is_none_or(|(flag, value)| a.flags.contains(flag) == value)
            }),
            Check::Group { group, state } => snapshot
                .groups
                .iter()
                .any(|g| g.group == group && g.state == state),
        }
    }
}

#[derive(Debug, Serialize)]
pub struct AdvanceReply {
    /// Tick reached.
    pub tick: u64,
    /// Engine time reached, seconds.
    pub time: f64,
    /// Ticks this request ran.
    pub ticks_run: u64,
    /// With `until`: whether the condition held (false: the bound was reached first).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub met: Option<bool>,
}

impl AdvanceRequest {
    /// The tick count asked for, within [`MAX_ADVANCE_TICKS`].
    fn ticks(&self, period: f64) -> Result<u64, ApiError> {
        let ticks = match (self.ticks, self.seconds) {
            (Some(ticks), None) => ticks,
            (None, Some(seconds)) => {
                if !(seconds.is_finite() && seconds >= 0.0) {
                    return Err(ApiError::InvalidRequest(format!(
                        "`seconds` = {seconds}: must be zero or more"
                    )));
                }
                let ticks = (seconds / period).round();
                if ticks > MAX_ADVANCE_TICKS as f64 {
                    return Err(too_long(period));
                }
                ticks as u64
            }
            (Some(_), Some(_)) => {
                return Err(ApiError::InvalidRequest(
                    "give `ticks` or `seconds`, not both".into(),
                ))
            }
            (None, None) => {
                return Err(ApiError::InvalidRequest(
                    "give `ticks` (a whole number) or `seconds`, e.g. {\"seconds\": 1.5}".into(),
                ))
            }
        };
        if ticks > MAX_ADVANCE_TICKS {
            return Err(too_long(period));
        }
        Ok(ticks)
    }
}

fn too_long(period: f64) -> ApiError {
    ApiError::InvalidRequest(format!(
        "at most {MAX_ADVANCE_TICKS} ticks ({} s at this machine's period) per request; \
         advance in several requests",
        MAX_ADVANCE_TICKS as f64 * period
    ))
}

impl UntilCondition {
    fn check(self, axes: usize) -> Result<Check, ApiError> {
        let axis = match (self.axis, self.group, self.group_state) {
            (None, Some(group), Some(state)) => {
                if self.state.is_some() || self.flag.is_some() {
                    return Err(ApiError::InvalidRequest(
                        "until: a group condition takes `group_state` only".into(),
                    ));
                }
                return Ok(Check::Group { group, state });
            }
            (Some(axis), None, None) => axis,
            _ => {
                return Err(ApiError::InvalidRequest(
                    "until needs an `axis` with `state` or `flag`, or a `group` with \
                     `group_state`, e.g. {\"axis\": 0, \"state\": \"standstill\"}"
                        .into(),
                ))
            }
        };
        if usize::from(axis) >= axes {
            return Err(ApiError::InvalidRequest(format!(
                "until.axis: axis {axis} does not exist (the machine has {axes} axes)"
            )));
        }
        let flag = match self.flag {
            None => None,
            Some(name) => Some((
                flag_by_name(&name).ok_or_else(|| {
                    ApiError::InvalidRequest(format!(
                        "until.flag: no flag `{name}` (in_position, moving, enabled, homed, \
                         hw_limit_pos … as /state lists them)"
                    ))
                })?,
                self.value,
            )),
        };
        if self.state.is_none() && flag.is_none() {
            return Err(ApiError::InvalidRequest(
                "until needs `state` or `flag`, e.g. {\"axis\": 0, \"state\": \"standstill\"}"
                    .into(),
            ));
        }
        Ok(Check::Axis {
            axis: usize::from(axis),
            state: self.state,
            flag,
        })
    }
}

async fn advance(handle: &EngineHandle, request: AdvanceRequest) -> Result<AdvanceReply, ApiError> {
    let before = handle.snapshot();
    let ticks = request.ticks(before.period)?;
    let check = request
        .until
        .map(|u| u.check(before.axes.len()))
        .transpose()?;
    let (tick, met) = match check {
        None => (handle.advance_async(ticks).await?, None),
        Some(check) => {
            let until = handle
                .advance_until_async(move |s: &Snapshot| check.holds(s), ticks)
                .await?;
            (until.tick, Some(until.met))
        }
    };
    Ok(AdvanceReply {
        tick,
        time: tick as f64 * before.period,
        // Nothing else advances a virtual clock, so the difference is this request's ticks.
        ticks_run: tick.saturating_sub(before.tick),
        met,
    })
}

pub async fn post_advance(State(state): State<ControlState>, JsonBody(body): JsonBody) -> Response {
    // No body can help on a paced clock: say so first.
    let clock = state.handle.clock();
    if clock != ClockMode::Virtual {
        return ApiError::from(AdvanceError::NotVirtual(clock)).into_response();
    }
    let result = match parse_json::<AdvanceRequest>(&body) {
        Ok(request) => advance(&state.handle, request).await,
        Err(e) => Err(e),
    };
    match result {
        Ok(reply) => Json(reply).into_response(),
        Err(e) => e.into_response(),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    fn request(json: &str) -> AdvanceRequest {
        parse_json(json.as_bytes()).unwrap()
    }

    #[test]
    fn ticks_and_seconds_are_bounded() {
        assert_eq!(request(r#"{"ticks":10}"#).ticks(1e-3).unwrap(), 10);
        assert_eq!(request(r#"{"seconds":1.5}"#).ticks(1e-3).unwrap(), 1500);
        assert_eq!(request(r#"{"seconds":0.0004}"#).ticks(1e-3).unwrap(), 0);
        assert_eq!(
            request(r#"{"seconds":3600}"#).ticks(1e-3).unwrap(),
            3_600_000
        );
        for bad in [
            r#"{"seconds":3600.01}"#,
            r#"{"ticks":3600001}"#,
            r#"{"seconds":-1}"#,
            r#"{"seconds":1e300}"#,
            r#"{"ticks":1,"seconds":1}"#,
            r#"{}"#,
        ] {
            assert!(request(bad).ticks(1e-3).is_err(), "{bad}");
        }
        assert!(parse_json::<AdvanceRequest>(br#"{"ticks":-1}"#).is_err());
        assert!(parse_json::<AdvanceRequest>(br#"{"ticks":1.5}"#).is_err());
        assert!(parse_json::<AdvanceRequest>(br#"{"tick":1}"#).is_err());
    }

    #[test]
    fn until_conditions_check_state_and_flags() {
        let until = |json: &str| -> Result<Check, ApiError> {
            parse_json::<UntilCondition>(json.as_bytes())?.check(2)
        };
        let mut snapshot = Snapshot::default();
        snapshot.axes.resize(2, Default::default());
        snapshot.axes[1].state = AxisState::Standstill;
        snapshot.axes[1].flags = AxisFlags::IN_POSITION;
        let holds = |json: &str| until(json).unwrap().holds(&snapshot);
        assert!(holds(r#"{"axis":1,"state":"standstill"}"#));
        assert!(!holds(r#"{"axis":0,"state":"standstill"}"#));
        assert!(holds(r#"{"axis":1,"flag":"in_position"}"#));
        assert!(holds(r#"{"axis":1,"flag":"moving","value":false}"#));
        assert!(!holds(r#"{"axis":1,"state":"standstill","flag":"moving"}"#));
        assert!(until(r#"{"axis":2,"state":"standstill"}"#).is_err());
        assert!(until(r#"{"axis":0,"flag":"IN_POSITION"}"#).is_err());
        assert!(until(r#"{"axis":0}"#).is_err());
        assert!(until(r#"{"axis":0,"state":"parked"}"#).is_err());
    }
}
