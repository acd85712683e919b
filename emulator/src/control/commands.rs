//! `POST /commands`, `/inputs` and `/faults`: everything that changes the engine goes through
//! `axes::Command`, queued to the servo thread.

use axes::command::{
    AxisIndex, AxisInput, Command, EngineError, ForceAnalogInput, ForceDigitalInput, ForceInput,
    InjectFollowingError, Reply,
};
use axes::runtime::CallError;
use axum::extract::{Path, RawQuery, State};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use serde_json::Value;

use super::error::{from_value, parse_json, ApiError, JsonBody};
use super::ControlState;

/// Commands one request may carry: they run one after another, each waiting for its reply
/// (a tick on a paced clock), so the bound also bounds how long a request takes.
pub const MAX_COMMANDS_PER_REQUEST: usize = 1024;

/// One command, or an array applied in order.
#[derive(Debug, PartialEq)]
pub enum CommandBody {
    One(Command),
    Many(Vec<Command>),
}

impl CommandBody {
    pub fn parse(bytes: &[u8]) -> Result<CommandBody, ApiError> {
        let first = bytes.iter().find(|b| !b.is_ascii_whitespace());
        if first == Some(&b'[') {
            let commands: Vec<Command> = parse_json(bytes)?;
            if commands.len() > MAX_COMMANDS_PER_REQUEST {
                return Err(ApiError::InvalidRequest(format!(
                    "{} commands in one request; at most {MAX_COMMANDS_PER_REQUEST}",
                    commands.len()
                )));
            }
            Ok(CommandBody::Many(commands))
        } else {
            parse_json(bytes).map(CommandBody::One)
        }
    }
}

/// Apply `commands` in order, stopping at the first error (which says its index and carries
/// the replies of the commands before it).
pub async fn apply_all(
    state: &ControlState,
    commands: Vec<Command>,
) -> Result<Vec<Reply>, ApiError> {
    let mut replies = Vec::with_capacity(commands.len());
    for (index, command) in commands.into_iter().enumerate() {
        match state.handle.call_async(command).await {
            Ok(reply) => replies.push(reply),
            Err(e) => {
                return Err(match ApiError::from(e) {
                    ApiError::Engine { error, .. } => ApiError::Engine {
                        error,
                        index: Some(index),
                        replies,
                    },
                    other => other,
                })
            }
        }
    }
    Ok(replies)
}

/// The query of `POST /commands`: `?atomic=true` applies an array in one go (see
/// [`apply_atomically`]); `atomic=false` or no query, one after another.
pub fn atomic_query(query: Option<&str>) -> Result<bool, ApiError> {
    let mut atomic = false;
    for pair in query.unwrap_or("").split('&').filter(|p| !p.is_empty()) {
        match pair.split_once('=') {
            Some(("atomic", "true")) => atomic = true,
            Some(("atomic", "false")) => atomic = false,
            Some(("atomic", other)) => {
                return Err(ApiError::InvalidRequest(format!(
                    "atomic={other}: use atomic=true or atomic=false"
                )))
            }
            _ => {
                return Err(ApiError::InvalidRequest(format!(
                    "unknown query parameter `{pair}`: /commands takes only atomic=true|false"
                )))
            }
        }
    }
    Ok(atomic)
}

/// Apply `commands` between the same two ticks, in order, all or none (`?atomic=true`): the
/// servo thread applies them in one go ([`axes::Engine::apply_batch`]). A refusal undoes the
/// commands before it, so the error carries the refused command's `index` and no replies.
pub async fn apply_atomically(
    state: &ControlState,
    commands: Vec<Command>,
) -> Result<Vec<Reply>, ApiError> {
    state
        .handle
        .call_batch_async(commands)
        .await
        .map_err(|e| match e {
            CallError::Engine(EngineError::Item {
                list: "commands",
                index,
                error,
            }) => ApiError::Engine {
                error: *error,
                index: Some(index as usize),
                replies: Vec::new(),
            },
            other => ApiError::from(other),
        })
}

pub async fn post_commands(
    State(state): State<ControlState>,
    RawQuery(query): RawQuery,
    JsonBody(body): JsonBody,
) -> Response {
    let result = match atomic_query(query.as_deref())
        .and_then(|atomic| CommandBody::parse(&body).map(|body| (atomic, body)))
    {
        Err(e) => Err(e),
        // One command is applied in one go anyway: `atomic` changes nothing for it.
        Ok((_, CommandBody::One(command))) => state
            .handle
            .call_async(command)
            .await
            .map(|reply| Json(reply).into_response())
            .map_err(ApiError::from),
        Ok((false, CommandBody::Many(commands))) => apply_all(&state, commands)
            .await
            .map(|replies| Json(replies).into_response()),
        Ok((true, CommandBody::Many(commands))) => apply_atomically(&state, commands)
            .await
            .map(|replies| Json(replies).into_response()),
    };
    result.unwrap_or_else(IntoResponse::into_response)
}

// ---- inputs ---------------------------------------------------------------------------------

/// `POST /inputs` body: one of
/// `{"axis": A, "input": "limit_pos", "value": true}`, `{"di": N, "value": true}`,
/// `{"ai": N, "value": 3.3}`. `value` absent or null releases the input to the simulation.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputRequest {
    #[serde(default)]
    axis: Option<AxisIndex>,
    #[serde(default)]
    input: Option<AxisInput>,
    #[serde(default)]
    di: Option<u16>,
    #[serde(default)]
    ai: Option<u16>,
    #[serde(default)]
    value: Option<Value>,
}

impl InputRequest {
    /// The engine command this request means.
    pub fn command(self) -> Result<Command, ApiError> {
        let shape = "give one of {\"axis\": A, \"input\": NAME}, {\"di\": N} or {\"ai\": N}, with \
                     \"value\" (absent or null releases the input)";
        let value = self.value.filter(|v| !v.is_null());
        match (self.axis, self.input, self.di, self.ai) {
            (Some(axis), Some(input), None, None) => Ok(Command::from(ForceInput {
                axis,
                input,
                value: value.map(|v| boolean("value", v)).transpose()?,
            })),
            (None, None, Some(channel), None) => Ok(Command::from(ForceDigitalInput {
                channel,
                value: value.map(|v| boolean("value", v)).transpose()?,
            })),
            (None, None, None, Some(channel)) => Ok(Command::from(ForceAnalogInput {
                channel,
                value: value.map(|v| number("value", v)).transpose()?,
            })),
            (Some(_), None, None, None) => Err(ApiError::InvalidRequest(format!(
                "`input` is missing: limit_pos, limit_neg, home, index, drive_alarm or \
                 encoder_loss; {shape}"
            ))),
            (None, Some(_), None, None) => Err(ApiError::InvalidRequest(format!(
                "`axis` is missing; {shape}"
            ))),
            _ => Err(ApiError::InvalidRequest(format!(
                "one input per request: {shape}"
            ))),
        }
    }
}

fn boolean(field: &str, value: Value) -> Result<bool, ApiError> {
    value.as_bool().ok_or_else(|| ApiError::InvalidBody {
        detail: format!("`{field}` must be true, false or null for a digital input, not {value}"),
        field: Some(field.into()),
        line: 0,
        column: 0,
    })
}

fn number(field: &str, value: Value) -> Result<f64, ApiError> {
    value.as_f64().ok_or_else(|| ApiError::InvalidBody {
        detail: format!("`{field}` must be a number or null for an analog input, not {value}"),
        field: Some(field.into()),
        line: 0,
        column: 0,
    })
}

async fn call_one(state: &ControlState, command: Command) -> Response {
    match state.handle.call_async(command).await {
        Ok(reply) => Json(reply).into_response(),
        Err(e) => ApiError::from(e).into_response(),
    }
}

pub async fn post_inputs(State(state): State<ControlState>, JsonBody(body): JsonBody) -> Response {
    match parse_json::<InputRequest>(&body).and_then(InputRequest::command) {
        Ok(command) => call_one(&state, command).await,
        Err(e) => e.into_response(),
    }
}

// ---- faults ---------------------------------------------------------------------------------

/// An axis fault, `{"axis": A, "fault": NAME, …}`. `active` defaults to true; false clears.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(tag = "fault", rename_all = "snake_case", deny_unknown_fields)]
pub enum AxisFault {
    /// The drive's alarm output (latches DRIVE_ALARM: ErrorStop until released and reset).
    DriveAlarm {
        axis: AxisIndex,
        #[serde(default = "yes")]
        active: bool,
    },
    /// Encoder feedback lost (latches ENCODER_LOSS).
    EncoderLoss {
        axis: AxisIndex,
        #[serde(default = "yes")]
        active: bool,
    },
    /// `amount` user units added between commanded and actual position.
    FollowingError {
        axis: AxisIndex,
        #[serde(default)]
        amount: Option<f64>,
        #[serde(default = "yes")]
        active: bool,
    },
}

fn yes() -> bool {
    true
}

impl AxisFault {
    pub fn command(self) -> Result<Command, ApiError> {
        let force = |axis, input, active: bool| {
            Command::from(ForceInput {
                axis,
                input,
                // Clearing releases the input to the simulation, which has no alarm of its own.
                value: active.then_some(true),
            })
        };
        match self {
            AxisFault::DriveAlarm { axis, active } => {
                Ok(force(axis, AxisInput::DriveAlarm, active))
            }
            AxisFault::EncoderLoss { axis, active } => {
                Ok(force(axis, AxisInput::EncoderLoss, active))
            }
            AxisFault::FollowingError {
                axis,
                amount,
                active,
            } => match (active, amount) {
                (true, Some(amount)) => Ok(Command::from(InjectFollowingError {
                    axis,
                    amount: Some(amount),
                })),
                (true, None) => Err(ApiError::InvalidRequest(
                    "following_error needs `amount` (user units) to inject, or \"active\": \
                     false to clear"
                        .into(),
                )),
                (false, _) => Ok(Command::from(InjectFollowingError { axis, amount: None })),
            },
        }
    }
}

/// A fault body: an axis fault, or `{"frontend": NAME, …}` for a protocol front-end's own
/// faults (frame delay/drop, Modbus exceptions …), which the front-end interprets.
#[derive(Debug, PartialEq)]
pub enum FaultRequest {
    Axis(AxisFault),
    Frontend {
        name: String,
        fault: serde_json::Map<String, Value>,
    },
}

impl FaultRequest {
    pub fn parse(bytes: &[u8]) -> Result<FaultRequest, ApiError> {
        let value: Value = parse_json(bytes)?;
        let Value::Object(mut map) = value else {
            return Err(ApiError::InvalidBody {
                detail: "a fault is a JSON object: {\"axis\": 0, \"fault\": \"drive_alarm\", \
                         \"active\": true} or {\"frontend\": NAME, …}"
                    .into(),
                field: None,
                line: 0,
                column: 0,
            });
        };
        match map.remove("frontend") {
            Some(Value::String(name)) => Ok(FaultRequest::Frontend { name, fault: map }),
            Some(other) => Err(ApiError::InvalidBody {
                detail: format!("`frontend` must be a front-end name, not {other}"),
                field: Some("frontend".into()),
                line: 0,
                column: 0,
            }),
            None => from_value(Value::Object(map)).map(FaultRequest::Axis),
        }
    }
}

pub async fn post_faults(State(state): State<ControlState>, JsonBody(body): JsonBody) -> Response {
    let request = match FaultRequest::parse(&body) {
        Ok(r) => r,
        Err(e) => return e.into_response(),
    };
    match request {
        FaultRequest::Axis(fault) => match fault.command() {
            Ok(command) => call_one(&state, command).await,
            Err(e) => e.into_response(),
        },
        FaultRequest::Frontend { name, fault } => {
            match state.frontends.iter().find(|f| f.name() == name) {
                Some(frontend) => match frontend.inject(fault) {
                    Ok(reply) => Json(reply).into_response(),
                    Err(e) => e.into_response(),
                },
                None => ApiError::NoSuchFrontend {
                    name,
                    running: running_names(&state),
                }
                .into_response(),
            }
        }
    }
}

/// `POST /api/v1/frontends/{name}/broadcast` with `{"message": "…"}`: the message, as given (no
/// terminator added), to every client of front-end `name` (User ASCII's `ASCII_ServerBroadcast`).
pub async fn post_broadcast(
    State(state): State<ControlState>,
    Path(name): Path<String>,
    JsonBody(body): JsonBody,
) -> Response {
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Broadcast {
        message: String,
    }
    let request: Broadcast = match parse_json(&body) {
        Ok(r) => r,
        Err(e) => return e.into_response(),
    };
    match state.frontends.iter().find(|f| f.name() == name) {
        Some(frontend) => match frontend.broadcast(&request.message) {
            Ok(reply) => Json(reply).into_response(),
            Err(e) => e.into_response(),
        },
        None => ApiError::NoSuchFrontend {
            name,
            running: running_names(&state),
        }
        .into_response(),
    }
}

fn running_names(state: &ControlState) -> String {
    if state.frontends.is_empty() {
        "none that takes faults".into()
    } else {
        state
            .frontends
            .iter()
            .map(|f| f.name())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use axes::command::{
        Enable, ForceAnalogInput, ForceDigitalInput, ForceInput, InjectFollowingError, Reset,
    };

    use super::*;

    fn input(json: &str) -> Result<Command, ApiError> {
        parse_json::<InputRequest>(json.as_bytes()).and_then(InputRequest::command)
    }

    fn fault(json: &str) -> Result<Command, ApiError> {
        match FaultRequest::parse(json.as_bytes())? {
            FaultRequest::Axis(f) => f.command(),
            FaultRequest::Frontend { name, .. } => panic!("front-end {name}"),
        }
    }

    #[test]
    fn command_bodies_are_one_command_or_an_array() {
        let one = CommandBody::parse(br#" {"type":"enable","axis":1}"#).unwrap();
        assert_eq!(one, CommandBody::One(Command::from(Enable { axis: 1 })));
        let many = CommandBody::parse(
            b"\n[{\"type\":\"enable\",\"axis\":1},{\"type\":\"reset\",\"axis\":0}]",
        )
        .unwrap();
        assert_eq!(
            many,
            CommandBody::Many(vec![
                Command::from(Enable { axis: 1 }),
                Command::from(Reset { axis: 0 })
            ])
        );
        assert_eq!(
            CommandBody::parse(b"[]").unwrap(),
            CommandBody::Many(vec![])
        );
        let big = format!(
            "[{}]",
            vec![r#"{"type":"enable","axis":0}"#; MAX_COMMANDS_PER_REQUEST + 1].join(",")
        );
        assert!(matches!(
            CommandBody::parse(big.as_bytes()),
            Err(ApiError::InvalidRequest(_))
        ));
    }

    #[test]
    fn the_commands_query_takes_only_atomic() {
        assert!(!atomic_query(None).unwrap());
        assert!(!atomic_query(Some("")).unwrap());
        assert!(atomic_query(Some("atomic=true")).unwrap());
        assert!(!atomic_query(Some("atomic=true&atomic=false")).unwrap());
        for bad in ["atomic=yes", "atomic", "atomically=true", "atomic=true&x=1"] {
            let e = atomic_query(Some(bad)).unwrap_err();
            assert_eq!(e.status(), axum::http::StatusCode::BAD_REQUEST, "{bad}");
        }
    }

    #[test]
    fn inputs_map_to_force_commands() {
        assert_eq!(
            input(r#"{"axis":0,"input":"limit_pos","value":true}"#).unwrap(),
            Command::from(ForceInput {
                axis: 0,
                input: AxisInput::LimitPos,
                value: Some(true)
            })
        );
        assert_eq!(
            input(r#"{"axis":2,"input":"home"}"#).unwrap(),
            Command::from(ForceInput {
                axis: 2,
                input: AxisInput::Home,
                value: None
            })
        );
        assert_eq!(
            input(r#"{"di":5,"value":false}"#).unwrap(),
            Command::from(ForceDigitalInput {
                channel: 5,
                value: Some(false)
            })
        );
        assert_eq!(
            input(r#"{"ai":2,"value":3.3}"#).unwrap(),
            Command::from(ForceAnalogInput {
                channel: 2,
                value: Some(3.3)
            })
        );
        assert_eq!(
            input(r#"{"ai":2,"value":null}"#).unwrap(),
            Command::from(ForceAnalogInput {
                channel: 2,
                value: None
            })
        );
        for bad in [
            r#"{"di":5,"value":1}"#,
            r#"{"ai":5,"value":"high"}"#,
            r#"{"axis":0,"value":true}"#,
            r#"{"input":"home","value":true}"#,
            r#"{"di":1,"ai":1}"#,
            r#"{}"#,
        ] {
            let e = input(bad).unwrap_err();
            assert_eq!(e.status(), axum::http::StatusCode::BAD_REQUEST, "{bad}");
        }
        let e = input(r#"{"axis":0,"input":"limit_up"}"#).unwrap_err();
        assert!(e.to_string().contains("unknown variant"), "{e}");
        let e = input(r#"{"di":0,"levle":true}"#).unwrap_err();
        assert_eq!(e.body()["field"], "levle");
    }

    #[test]
    fn faults_map_to_commands_and_front_ends_are_routed_by_name() {
        assert_eq!(
            fault(r#"{"axis":1,"fault":"drive_alarm"}"#).unwrap(),
            Command::from(ForceInput {
                axis: 1,
                input: AxisInput::DriveAlarm,
                value: Some(true)
            })
        );
        assert_eq!(
            fault(r#"{"axis":1,"fault":"encoder_loss","active":false}"#).unwrap(),
            Command::from(ForceInput {
                axis: 1,
                input: AxisInput::EncoderLoss,
                value: None
            })
        );
        assert_eq!(
            fault(r#"{"axis":0,"fault":"following_error","amount":2.5}"#).unwrap(),
            Command::from(InjectFollowingError {
                axis: 0,
                amount: Some(2.5)
            })
        );
        assert_eq!(
            fault(r#"{"axis":0,"fault":"following_error","active":false}"#).unwrap(),
            Command::from(InjectFollowingError {
                axis: 0,
                amount: None
            })
        );
        assert!(fault(r#"{"axis":0,"fault":"following_error"}"#).is_err());
        let e = fault(r#"{"axis":0,"fault":"meltdown"}"#).unwrap_err();
        assert!(e.to_string().contains("unknown variant"), "{e}");
        let e = fault(r#"{"axis":0,"fault":"drive_alarm","severity":3}"#).unwrap_err();
        assert_eq!(e.body()["field"], "severity");
        assert!(fault("[1]").is_err());
        assert_eq!(
            FaultRequest::parse(br#"{"frontend":"modbus_tcp","fault":"exception","code":4}"#)
                .unwrap(),
            FaultRequest::Frontend {
                name: "modbus_tcp".into(),
                fault: serde_json::from_str(r#"{"fault":"exception","code":4}"#).unwrap(),
            }
        );
        assert!(FaultRequest::parse(br#"{"frontend":3}"#).is_err());
    }
}
