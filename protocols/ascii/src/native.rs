//! [`Native`]: the sans-IO core of the Native ASCII server. A line in, a reply line (or engine
//! commands to apply first) out.
//!
//! Order of calls, per line: [`Native::line`] with the line, the engine's latest snapshot and
//! the shared [`Registers`]; on [`Step::Reply`] send the text; on [`Step::Engine`] apply the
//! commands as one batch, then [`Native::finish`] with the result (and, for
//! [`Then::AwaitHoming`], only once the axis has stopped homing) and send its text. Lines of
//! one client are handled one after the other, in order.

use std::collections::BTreeMap;
use std::sync::Arc;

use axes::command::EngineError;
use mcemu_dialects::himc::engine_error::{error_code, Subject};
use mcemu_dialects::himc::system::{
    HMPL_INTERNAL_ERROR, HMPL_INVALID_ARG, HMPL_INVALID_STR_FORMAT, HMPL_NOT_SUPPORTED,
    HMPL_STR_TOO_LONG,
};

use crate::counters::Counters;
use crate::functions;
use crate::line::Line;
use crate::parse::{parse_call, ParseError};
use crate::registers::Registers;
use crate::reply::Outcome;
use crate::table::{check_args, Addresses, Ctx, Function, Plan, Ret, Then, NO_ICON};

/// How the server reads names and ends replies (`[frontends.ascii_native]`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Options {
    /// `moveabs(0, 1)` calls `MoveAbs`.
    pub case_insensitive: bool,
    /// Only the 270 icon-marked functions (digest 004 §1.6).
    pub strict: bool,
    /// Appended to every reply.
    pub line_ending: String,
    /// `MoveHome` replies once homing has ended, as the manual's example expects.
    pub move_home_waits: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            case_insensitive: false,
            strict: false,
            line_ending: "\r\n".into(),
            move_home_waits: false,
        }
    }
}

/// A call waiting for the engine.
#[derive(Clone, Debug)]
pub struct Pending {
    function: &'static Function,
    subject: Subject,
    pub then: Then,
}

/// What to do with a line.
#[derive(Debug)]
pub enum Step {
    /// Send this (line ending included).
    Reply(String),
    /// Apply these commands as one batch, then [`Native::finish`].
    Engine(Vec<axes::Command>, Pending),
}

/// The Native ASCII server's functions and options.
pub struct Native {
    by_name: BTreeMap<String, &'static Function>,
    options: Options,
    counters: Arc<Counters>,
}

impl Native {
    pub fn new(options: Options, counters: Arc<Counters>) -> Native {
        let mut by_name = BTreeMap::new();
        for f in functions::all() {
            if options.strict && NO_ICON.contains(&f.name) {
                continue;
            }
            let key = if options.case_insensitive {
                f.name.to_ascii_lowercase()
            } else {
                f.name.to_string()
            };
            by_name.insert(key, f);
        }
        if options.move_home_waits {
            let f = &functions::homing::WAITING_MOVE_HOME;
            let key = if options.case_insensitive {
                f.name.to_ascii_lowercase()
            } else {
                f.name.to_string()
            };
            by_name.insert(key, f);
        }
        Native {
            by_name,
            options,
            counters,
        }
    }

    pub fn options(&self) -> &Options {
        &self.options
    }

    pub fn counters(&self) -> &Counters {
        &self.counters
    }

    /// The function a name calls, if served.
    pub fn function(&self, name: &str) -> Option<&'static Function> {
        if self.options.case_insensitive {
            self.by_name.get(&name.to_ascii_lowercase()).copied()
        } else {
            self.by_name.get(name).copied()
        }
    }

    fn text(&self, outcome: Outcome) -> String {
        let mut s = String::new();
        outcome.write(&mut s);
        s.push_str(&self.options.line_ending);
        s
    }

    /// A line that cannot be called: its system code, latched (issue 14 item 1).
    fn refuse(&self, code: u32, registers: &mut Registers) -> Step {
        registers.latch(code);
        Step::Reply(self.text(Outcome::code(code)))
    }

    /// A function that failed with `code`: latched, and its return type's failure value.
    fn fail(&self, f: &Function, code: u32, registers: &mut Registers) -> String {
        registers.latch(code);
        self.counters.calls_failed.inc();
        self.text(failure(f.ret, code))
    }

    /// Handle one line.
    pub fn line(&self, line: &Line, snapshot: &axes::Snapshot, registers: &mut Registers) -> Step {
        self.counters.lines.inc();
        let text = match line {
            Line::TooLong => {
                self.counters.too_long.inc();
                return self.refuse(HMPL_STR_TOO_LONG, registers);
            }
            Line::Text(t) => t,
        };
        let call = match parse_call(text) {
            Ok(c) => c,
            Err(ParseError::Syntax { .. }) => {
                self.counters.syntax_errors.inc();
                return self.refuse(HMPL_INVALID_STR_FORMAT, registers);
            }
            Err(ParseError::Argument(_)) => {
                self.counters.invalid_args.inc();
                return self.refuse(HMPL_INVALID_ARG, registers);
            }
        };
        let Some(f) = self.function(&call.name) else {
            self.counters.unsupported.inc();
            return self.refuse(HMPL_NOT_SUPPORTED, registers);
        };
        let args = match check_args(f.params, call.args) {
            Ok(a) => a,
            Err(_) => {
                self.counters.invalid_args.inc();
                return self.refuse(HMPL_INVALID_ARG, registers);
            }
        };
        let id = u16::try_from(args.int(0)).unwrap_or(u16::MAX);
        let subject = match f.addresses {
            Addresses::Controller => Subject::System,
            Addresses::Axis => Subject::Axis(id),
            Addresses::Group => Subject::Group(id),
        };
        let mut cx = Ctx {
            snapshot,
            registers,
        };
        match (f.handler)(&mut cx, &args) {
            Plan::Done(outcome) => {
                self.counters.calls_ok.inc();
                Step::Reply(self.text(outcome))
            }
            Plan::Fail(code) => Step::Reply(self.fail(f, code, registers)),
            Plan::Engine(commands, then) => Step::Engine(
                commands,
                Pending {
                    function: f,
                    subject,
                    then,
                },
            ),
        }
    }

    /// The reply to a call whose commands the engine applied (`Ok`) or refused; `None` for an
    /// engine that did not answer (stopped).
    pub fn finish(
        &self,
        pending: &Pending,
        result: Result<(), Option<EngineError>>,
        registers: &mut Registers,
    ) -> String {
        match result {
            Ok(()) => {
                self.counters.calls_ok.inc();
                self.text(success(pending.function.ret))
            }
            Err(e) => {
                self.counters.engine_refusals.inc();
                if let (true, Subject::Axis(a)) =
                    (pending.function.name == "EnableComp", pending.subject)
                {
                    // Recorded before the engine answered: a refused EnableComp (no table, or
                    // over the compensation limit, TV 63) leaves the compensation off.
                    registers.compensating.remove(&a);
                }
                let code = e.map_or(HMPL_INTERNAL_ERROR, |e| error_code(&e, pending.subject));
                self.fail(pending.function, code, registers)
            }
        }
    }

    /// The reply to a call whose batch ended in an object read ([`Then::Object`]): its value
    /// as the function returns it; a read that did not give an integer is the HMPL internal
    /// error.
    pub fn finish_object(
        &self,
        pending: &Pending,
        replies: &[axes::Reply],
        registers: &mut Registers,
    ) -> String {
        let outcome = match (pending.then, replies.last()) {
            (Then::Object(how), Some(axes::Reply::Object { value })) => how.outcome(value),
            _ => None,
        };
        match outcome {
            Some(o) => {
                self.counters.calls_ok.inc();
                self.text(o)
            }
            None => self.fail(pending.function, HMPL_INTERNAL_ERROR, registers),
        }
    }

    /// The reply to `MoveHome` awaited until homing ended: 0 if the axis is homed, else the
    /// engine's homing failure (`eERR_AXIS_DRIVE_HOME_FAILED`), latched.
    pub fn finish_homing(
        &self,
        pending: &Pending,
        homed: bool,
        registers: &mut Registers,
    ) -> String {
        if homed {
            self.counters.calls_ok.inc();
            return self.text(success(pending.function.ret));
        }
        let code = match pending.subject {
            Subject::Axis(a) => {
                mcemu_dialects::himc::AxisError::by_name("eERR_AXIS_DRIVE_HOME_FAILED")
                    .map_or(HMPL_INTERNAL_ERROR, |e| {
                        e.code(u8::try_from(a).unwrap_or(u8::MAX))
                    })
            }
            _ => HMPL_INTERNAL_ERROR,
        };
        self.fail(pending.function, code, registers)
    }
}

/// What a function of return type `ret` returns on success with nothing to report.
fn success(ret: Ret) -> Outcome {
    match ret {
        Ret::Void => Outcome::Void,
        Ret::Double => Outcome::Double(0.0),
        Ret::Int64 => Outcome::Int64(0),
        Ret::Int | Ret::Status | Ret::Array6 => Outcome::Int(0),
        Ret::DoubleWithStatus | Ret::IntWithValue => Outcome::WithStatus(0, 0.0),
    }
}

/// What a function of return type `ret` returns when it fails with `code` (digest 004 §7.3:
/// a `double` getter has no error channel: 0; `int64` SDO reads: −1).
fn failure(ret: Ret, code: u32) -> Outcome {
    match ret {
        Ret::Int => Outcome::code(code),
        Ret::Status => Outcome::Int(-1),
        Ret::Double => Outcome::Double(0.0),
        Ret::Int64 => Outcome::Int64(-1),
        Ret::Array6 => Outcome::Array(code as i32, [0.0; 6]),
        Ret::DoubleWithStatus => Outcome::WithStatus(-1, 0.0),
        Ret::IntWithValue => Outcome::WithStatus(code as i32, 0.0),
        Ret::Void => Outcome::Void,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::ICON;

    fn reply(native: &Native, registers: &mut Registers, line: &str) -> String {
        let snapshot = axes::Snapshot::default();
        match native.line(&Line::Text(line.into()), &snapshot, registers) {
            Step::Reply(t) => t,
            Step::Engine(..) => format!("engine: {line}"),
        }
    }

    fn native(options: Options) -> Native {
        Native::new(options, Arc::new(Counters::default()))
    }

    #[test]
    fn every_served_function_is_in_the_manual_once() {
        let mut names: Vec<&str> = functions::all().map(|f| f.name).collect();
        let n = names.len();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), n, "a name is served twice");
        for f in functions::all() {
            let known = ICON
                .iter()
                .any(|(name, s)| *name == f.name && *s == f.section)
                || NO_ICON.contains(&f.name)
                || f.name == "ldexp";
            assert!(
                known,
                "{} (§{}) is not in digest 004's lists",
                f.name, f.section
            );
        }
    }

    #[test]
    fn tv85_strings() {
        let n = native(Options::default());
        let r = &mut Registers::default();
        for (call, want) in [
            (r#"StringLen("hello world")"#, "11"),
            (r#"StrFindStr("hello world", "wor")"#, "6"),
            (r#"StrFindStr("hello world", "wol")"#, "-1"),
            (r#"StrFindCharEx("hello world", "lo ", 0)"#, "2"),
            (r#"StrFindCharEx("hello world", "leh", 1)"#, "4"),
            (r#"IsStringEqual("hello world", "hello worldd")"#, "0"),
            (r#"StringToDouble("1.234")"#, "1.234"),
        ] {
            assert_eq!(reply(&n, r, call), format!("{want}\r\n"), "{call}");
        }
    }

    #[test]
    fn tv88_math() {
        let n = native(Options::default());
        let r = &mut Registers::default();
        for (call, want) in [
            ("atan2(10, -10)", "2.35619449019234"),
            ("pow(7.0, 3.0)", "343"),
            ("pow(4.73, 12.0)", "125410439.217423"),
            ("hypot(3, 4)", "5"),
            ("cbrt(27)", "3"),
            ("log(5.5)", "1.70474809223843"),
            ("exp(5.0)", "148.413159102577"),
            ("ceil(-2.3)", "-2"),
            ("floor(-2.3)", "-3"),
            ("abs(-3591)", "3591"),
            ("ldexp(0.95, 4)", "15.2"),
            ("Idexp(0.95, 4)", "15.2"),
            ("exp(1000)", "1.79769313486232e+308"),
        ] {
            assert_eq!(reply(&n, r, call), format!("{want}\r\n"), "{call}");
        }
    }

    #[test]
    fn lines_that_cannot_be_called_reply_and_latch_their_system_code() {
        let n = native(Options::default());
        let r = &mut Registers::default();
        for (line, code) in [
            ("NoSuchFunction(1)", "5201"),
            ("movabs(0, 1)", "5201"),
            ("MoveAbs(0)", "5000"),
            ("MoveAbs(0, \"x\")", "5000"),
            ("MoveAbs(0, NOT_A_CONSTANT)", "5000"),
            ("MoveAbs(0, 1", "5006"),
            ("\u{fffd}\u{fffd}", "5006"),
        ] {
            assert_eq!(reply(&n, r, line), format!("{code}\r\n"), "{line}");
            assert_eq!(r.system_error.to_string(), code, "{line}");
        }
        let snapshot = axes::Snapshot::default();
        let Step::Reply(t) = n.line(&Line::TooLong, &snapshot, r) else {
            panic!("too long is answered at once");
        };
        assert_eq!(t, "5005\r\n");
        assert_eq!(reply(&n, r, "GetSystemLastErr()"), "5005\r\n");
    }

    #[test]
    fn a_missing_axis_fails_with_the_return_types_failure() {
        let n = native(Options::default());
        let r = &mut Registers::default();
        // No axes in an empty snapshot: an int function returns the code, a double getter 0.
        assert_eq!(reply(&n, r, "MoveAbs(3, 1)"), "5007\r\n");
        assert_eq!(reply(&n, r, "GetPosFb(3)"), "0\r\n");
        assert_eq!(reply(&n, r, "GetSystemLastErr()"), "5007\r\n");
    }

    /// Two axes: axis 0 with the status the last getters read.
    fn measured_snapshot() -> axes::Snapshot {
        let axis = axes::AxisStatus {
            state: axes::AxisState::Standstill,
            flags: axes::AxisFlags::ENABLED,
            move_time: 1.1,
            settling_time: 0.015,
            position_offset: -50.0,
            rollover_turns: -3,
            torque: 0.5,
            ..axes::AxisStatus::default()
        };
        axes::Snapshot {
            axes: vec![axis, axes::AxisStatus::default()],
            params: Arc::new(vec![axes::param::ParamSet::default(); 2]),
            ..axes::Snapshot::default()
        }
    }

    fn reply_on(native: &Native, r: &mut Registers, s: &axes::Snapshot, line: &str) -> String {
        match native.line(&Line::Text(line.into()), s, r) {
            Step::Reply(t) => t,
            Step::Engine(commands, _) => format!("engine: {}", serde_json::json!(commands)),
        }
    }

    #[test]
    fn the_measured_getters_read_the_snapshot_in_hmpl_units() {
        let n = native(Options::default());
        let r = &mut Registers::default();
        let s = measured_snapshot();
        for (call, want) in [
            ("GetMoveTime(0)", "1100"),
            ("GetSettlingTime(0)", "15"),
            ("GetPosOffset(0)", "-50"),
            ("GetRolloverTurns(0)", "-3"),
            // Half the rated torque × the default rated current, 2.6 A.
            ("GetCurrFb(0)", "1.3"),
            ("GetCurrFb(1)", "0"),
            ("GetMoveTime(5)", "0"),
        ] {
            assert_eq!(reply_on(&n, r, &s, call), format!("{want}\r\n"), "{call}");
        }
    }

    #[test]
    fn move_trq_needs_torque_mode_and_clamps_to_the_rated_torque() {
        let n = native(Options::default());
        let r = &mut Registers::default();
        let s = measured_snapshot();
        // 0x830000FA eERR_AXIS_CMD_INVALID_OP_MODE, as a signed int.
        let invalid_op_mode = (0x8300_00fa_u32 as i32).to_string();
        assert_eq!(
            reply_on(&n, r, &s, "MoveTrq(0, 1)"),
            format!("{invalid_op_mode}\r\n")
        );
        assert_eq!(reply_on(&n, r, &s, "SetOpMode(0, 10)"), "0\r\n");
        let sent = reply_on(&n, r, &s, "MoveTrq(0, 0.635)");
        assert!(sent.contains(r#""mode":"torque","torque":0.5"#), "{sent}");
        let clamped = reply_on(&n, r, &s, "MoveTrq(0, -100)");
        assert!(clamped.contains(r#""torque":-1.0"#), "{clamped}");
    }

    #[test]
    fn task_functions_are_not_supported_but_check_their_arguments() {
        let n = native(Options::default());
        let r = &mut Registers::default();
        for (call, want) in [
            ("StartTask(0)", "5201"),
            ("StartTaskFunc(63, \"main\")", "5201"),
            ("StopTask(1)", "5201"),
            ("IsTaskStop(0)", "5201"),
            ("StopAllTask()", "5201"),
            ("GetSystemLastErr()", "5201"),
            ("StartTask(\"x\")", "5000"),
        ] {
            assert_eq!(reply(&n, r, call), format!("{want}\r\n"), "{call}");
        }
    }

    #[test]
    fn every_icon_marked_function_is_served() {
        let n = native(Options {
            strict: true,
            ..Options::default()
        });
        let missing: Vec<&str> = ICON
            .iter()
            .map(|(name, _)| *name)
            .filter(|name| n.function(name).is_none())
            .collect();
        assert!(missing.is_empty(), "not served: {missing:?}");
    }

    #[test]
    fn set_comp_alg_type_1_makes_the_table_a_cubic_spline() {
        let n = native(Options::default());
        let r = &mut Registers::default();
        let s = measured_snapshot();
        assert_eq!(reply_on(&n, r, &s, "SetCompAlgType(1, 1)"), "0\r\n");
        let table = reply_on(&n, r, &s, "SetupComp(1, 0, 0, 10, 4, 1)");
        assert!(table.contains(r#""interpolation":"cubic""#), "{table}");
        // Back to linear: the table set up is sent again.
        let again = reply_on(&n, r, &s, "SetCompAlgType(1, 0)");
        assert!(
            again.contains("compensation_table") && !again.contains("cubic"),
            "{again}"
        );
        assert!(reply_on(&n, r, &s, "SetCompAlgType(1, 2)").starts_with('-'));
    }

    #[test]
    fn options_change_names_endings_and_the_set() {
        let lax = native(Options {
            case_insensitive: true,
            line_ending: "\n".into(),
            ..Options::default()
        });
        let r = &mut Registers::default();
        assert_eq!(reply(&lax, r, "isSYSTEMoper()"), "1\n");
        assert_eq!(reply(&lax, r, "GetAllGPI()"), "0\n");
        let strict = native(Options {
            strict: true,
            ..Options::default()
        });
        assert_eq!(reply(&strict, r, "GetAllGPI()"), "5201\r\n");
        assert_eq!(reply(&strict, r, "IsSystemOper();"), "1\r\n");
    }
}
