//! One socketcand connection's state machine, sans-IO: commands in, replies and frames to
//! transmit out; frames from the bus in, messages for the client out (raw mode only).
//!
//! Modes as in socketcand: NO_BUS after `< hi >` until `< open BUS >`, then BCM; `rawmode`,
//! `bcmmode` and `controlmode` switch. mcemu's BCM mode sends (`send`, `sendrtr`) but has no
//! reception filters (refused with the reason), so it delivers nothing; raw mode delivers every
//! frame. Unlike socketcand, a bad command, including an `open` of a bus not served here,
//! never closes the connection: the client gets `< error … >` and may go on.

use crate::clock::Timestamp;
use crate::frame::WireFrame;
use crate::socketcand::codec::{encode_error_reply, encode_frame, Command, CommandError, ECHO, OK};

/// The protocol mode of a connection.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    NoBus,
    Bcm,
    Raw,
    Control,
}

/// What the transport must do after a command.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SessionAction {
    /// Write this message to the client.
    Reply(String),
    /// Attach to the bus of this name (it is served: the session checked).
    Attach(String),
    /// Put this frame on the bus.
    Transmit(WireFrame),
    /// The client just entered raw mode: frames follow from now on.
    EnteredRawMode,
}

/// One connection's protocol state.
#[derive(Debug)]
pub struct Session {
    mode: Mode,
    bus: Option<String>,
}

impl Default for Session {
    fn default() -> Self {
        Self::new()
    }
}

impl Session {
    pub fn new() -> Self {
        Self {
            mode: Mode::NoBus,
            bus: None,
        }
    }

    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The bus this connection opened.
    pub fn bus(&self) -> Option<&str> {
        self.bus.as_deref()
    }

    /// Handle one decoded element. `served` lists the buses that can be opened.
    pub fn on_command(
        &mut self,
        command: Result<Command, CommandError>,
        served: &[String],
        actions: &mut Vec<SessionAction>,
    ) {
        let command = match command {
            Ok(command) => command,
            Err(error) => return actions.push(error_reply(&error.to_string())),
        };
        match (self.mode, command) {
            (Mode::NoBus, Command::Open(bus)) => {
                if served.contains(&bus) {
                    self.mode = Mode::Bcm;
                    self.bus = Some(bus.clone());
                    actions.push(SessionAction::Attach(bus));
                    actions.push(SessionAction::Reply(OK.to_string()));
                } else {
                    actions.push(error_reply(&format!(
                        "could not open bus {bus}: not served here (served: {})",
                        served.join(", ")
                    )));
                }
            }
            (_, Command::Open(_)) => {
                actions.push(error_reply("a bus is already open on this connection"));
            }
            (_, Command::Unsupported { command, reason }) => {
                actions.push(error_reply(&format!("{command} not supported: {reason}")));
            }
            (Mode::NoBus, Command::Echo) => actions.push(SessionAction::Reply(ECHO.to_string())),
            (Mode::NoBus, _) => actions.push(error_reply("open a bus first: < open vcan0 >")),
            (_, Command::Echo) => actions.push(SessionAction::Reply(ECHO.to_string())),
            (_, Command::RawMode) => {
                let entering = self.mode != Mode::Raw;
                self.mode = Mode::Raw;
                actions.push(SessionAction::Reply(OK.to_string()));
                if entering {
                    actions.push(SessionAction::EnteredRawMode);
                }
            }
            (_, Command::BcmMode) => {
                self.mode = Mode::Bcm;
                actions.push(SessionAction::Reply(OK.to_string()));
            }
            (_, Command::ControlMode) => {
                self.mode = Mode::Control;
                actions.push(SessionAction::Reply(OK.to_string()));
            }
            (_, Command::IsoTpMode) => {
                actions.push(error_reply(
                    "isotpmode not supported: ISO-TP is not implemented by mcemu",
                ));
            }
            (Mode::Control, Command::Send(_)) => {
                actions.push(error_reply(
                    "send is not available in control mode: < rawmode > first",
                ));
            }
            (Mode::Bcm | Mode::Raw, Command::Send(frame)) => {
                actions.push(SessionAction::Transmit(frame))
            }
        }
    }

    /// A frame from the bus: the message for the client, in raw mode.
    pub fn on_frame(&self, stamp: Timestamp, frame: &WireFrame, out: &mut String) -> bool {
        if self.mode != Mode::Raw {
            return false;
        }
        encode_frame(out, stamp, frame);
        true
    }
}

fn error_reply(text: &str) -> SessionAction {
    let mut out = String::new();
    encode_error_reply(&mut out, text);
    SessionAction::Reply(out)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    fn run(session: &mut Session, command: Result<Command, CommandError>) -> Vec<SessionAction> {
        let mut actions = vec![];
        session.on_command(command, &["vcan0".to_string()], &mut actions);
        actions
    }

    fn reply(text: &str) -> SessionAction {
        SessionAction::Reply(text.to_string())
    }

    #[test]
    fn python_can_handshake() {
        let mut s = Session::new();
        assert_eq!(
            run(&mut s, Ok(Command::Open("vcan0".into()))),
            [SessionAction::Attach("vcan0".into()), reply("< ok >")]
        );
        assert_eq!(s.mode(), Mode::Bcm);
        assert_eq!(
            run(&mut s, Ok(Command::RawMode)),
            [reply("< ok >"), SessionAction::EnteredRawMode]
        );
        let frame = WireFrame::standard(1, &[2]).unwrap();
        assert_eq!(
            run(&mut s, Ok(Command::Send(frame))),
            [SessionAction::Transmit(frame)]
        );
        let mut out = String::new();
        assert!(s.on_frame(Timestamp { secs: 1, micros: 2 }, &frame, &mut out));
        assert_eq!(out, "< frame 001 1.000002 02 >");
    }

    #[test]
    fn refusals_keep_the_connection() {
        let mut s = Session::new();
        let is_error = |actions: Vec<SessionAction>| matches!(actions.as_slice(), [SessionAction::Reply(r)] if r.starts_with("< error ") && r.ends_with(" >"));
        assert!(is_error(run(&mut s, Ok(Command::RawMode))));
        assert!(is_error(run(&mut s, Ok(Command::Open("vcan9".into())))));
        assert_eq!(s.mode(), Mode::NoBus);
        assert!(is_error(run(
            &mut s,
            Err(CommandError::Unknown("x".into()))
        )));
        run(&mut s, Ok(Command::Open("vcan0".into())));
        assert!(is_error(run(&mut s, Ok(Command::Open("vcan0".into())))));
        assert!(is_error(run(&mut s, Ok(Command::IsoTpMode))));
        assert!(is_error(run(
            &mut s,
            Ok(Command::Unsupported {
                command: "add",
                reason: "r"
            })
        )));
        // BCM mode delivers nothing; control mode sends nothing.
        let mut out = String::new();
        assert!(!s.on_frame(
            Timestamp { secs: 0, micros: 0 },
            &WireFrame::standard(1, &[]).unwrap(),
            &mut out
        ));
        run(&mut s, Ok(Command::ControlMode));
        assert!(is_error(run(
            &mut s,
            Ok(Command::Send(WireFrame::standard(1, &[]).unwrap()))
        )));
        assert_eq!(run(&mut s, Ok(Command::Echo)), [reply("< echo >")]);
    }
}
