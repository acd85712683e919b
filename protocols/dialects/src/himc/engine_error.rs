//! Every [`EngineError`] as the 0xCCNNVVVV code an HMPL function returns (digest 004 §5): an
//! axis code (0x83, the axis the error names, else the one the call addressed), a group code
//! (0x82) or a system code (0x00). One `match` over all variants, so a new engine error does
//! not compile until it has its code.

use axes::command::EngineError;
use axes::status::GroupState;
use axes::types::Direction;
use axes::AxisState;

use super::group_errors::GroupErrorRow;
use super::system::{
    HCV_ID_NOT_FOUND, HCV_IS_READ_ONLY, HMPL_ARG_OUT_OF_RANGE, HMPL_NOT_SUPPORTED,
};
use super::{code_for, compose, AxisError, AXIS_CLASS, GROUP_CLASS};

/// What an HMPL call addressed: its first argument's axis or group, or the controller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Subject {
    System,
    Axis(u16),
    Group(u16),
}

/// `eERR_DATA_EXCEEDED`.
const DATA_EXCEEDED: u32 = 0x0000_0002;

fn id_byte(id: u16) -> u8 {
    u8::try_from(id).unwrap_or(u8::MAX)
}

fn axis(axis: u16, name: &str) -> u32 {
    AxisError::by_name(name).map_or(HMPL_ARG_OUT_OF_RANGE, |e| e.code(id_byte(axis)))
}

fn group(group: u16, name: &str) -> u32 {
    GroupErrorRow::by_name(name).map_or(HMPL_ARG_OUT_OF_RANGE, |e| {
        compose(GROUP_CLASS, id_byte(group), e.value)
    })
}

/// A refusal about a parameter or an argument, in the class of what the call addressed.
fn invalid(subject: Subject) -> u32 {
    match subject {
        Subject::System => HMPL_ARG_OUT_OF_RANGE,
        Subject::Axis(a) => axis(a, "eERR_AXIS_CMD_INVALID_PARAMETER"),
        Subject::Group(g) => group(g, "eERR_CRD_CMD_LIN_INVALID_PARAM"),
    }
}

/// The code HMPL returns for engine refusal `e` of a call that addressed `subject`.
pub fn error_code(e: &EngineError, subject: Subject) -> u32 {
    use EngineError as E;
    let group_of_call = match subject {
        Subject::Group(g) => Some(g),
        _ => None,
    };
    match e {
        E::Item { error, .. } => error_code(error, subject),
        E::InvalidAxis { .. }
        | E::InvalidSlave { .. }
        | E::InvalidChannel { .. }
        | E::UnknownCommand { .. }
        | E::InvalidSampling { .. }
        | E::InvalidProtection { .. } => HMPL_ARG_OUT_OF_RANGE,
        E::UnknownParameter { .. } => HCV_ID_NOT_FOUND,
        E::ReadOnlyParameter { .. } => HCV_IS_READ_ONLY,
        E::Object { .. } => DATA_EXCEEDED,
        // A target beyond a software limit (`sw_limit_reject_targets`, digest 004 §3.3).
        E::InvalidArgument {
            name: "position", ..
        } if matches!(subject, Subject::Axis(_)) => match subject {
            Subject::Axis(a) => axis(a, "eERR_AXIS_CMD_INVALID_POS"),
            _ => invalid(subject),
        },
        E::InvalidParameter { .. } | E::InvalidArgument { .. } => invalid(subject),
        E::Unsupported { .. } => match subject {
            Subject::System => HMPL_NOT_SUPPORTED,
            Subject::Axis(a) => axis(a, "eERR_AXIS_CMD_UNKOWN"),
            Subject::Group(g) => group(g, "eERR_CRD_CMD_UNKNOWN"),
        },
        E::AxisDisabled { axis: a } => match group_of_call {
            Some(g) => group(g, "eERR_CRD_CMD_INVALID_DISABLED"),
            None => axis(*a, "eERR_AXIS_CMD_INVALID_DISABLED"),
        },
        E::AxisInError { axis: a, .. } | E::CauseStillPresent { axis: a, .. } => {
            axis(*a, "eERR_AXIS_CMD_INVALID_ERROR_STATE")
        }
        // The engine does not say which limit (hardware or software) holds the axis; the
        // hardware switch is the one the HIMC stops on by default (digest 004 §3.6).
        E::LimitActive { axis: a, direction } => match direction {
            Direction::Positive => axis(*a, "eERR_AXIS_HWRL"),
            Direction::Negative => axis(*a, "eERR_AXIS_HWLL"),
        },
        E::QueueFull { axis: a, .. } | E::StreamFull { axis: a, .. } => {
            axis(*a, "eERR_AXIS_CMD_QUEUE_FULL")
        }
        E::InvalidState { axis: a, state, .. } => match state {
            AxisState::Disabled => axis(*a, "eERR_AXIS_CMD_INVALID_DISABLED"),
            AxisState::Stopping => axis(*a, "eERR_AXIS_CMD_INVALID_STOPPING"),
            AxisState::ErrorStop => axis(*a, "eERR_AXIS_CMD_INVALID_ERROR_STATE"),
            AxisState::SynchronizedMotion => axis(*a, "eERR_AXIS_CMD_INVALID_IN_SYNC"),
            _ => axis(*a, "eERR_AXIS_CMD_INVALID_STATE"),
        },
        E::Homing(_) => match subject {
            Subject::Axis(a) => axis(a, "eERR_AXIS_DRIVE_HOME_FAILED"),
            _ => HMPL_ARG_OUT_OF_RANGE,
        },
        E::InvalidCompensation { axis: a, .. } => axis(
            u16::try_from(*a).unwrap_or(u16::MAX),
            "eERR_AXIS_COMP_NOT_CNFG",
        ),
        // TV 63 (digest 004 §2.13).
        E::CompensationLimit { axis: a, .. } => axis(
            u16::try_from(*a).unwrap_or(u16::MAX),
            "eERR_AXIS_COMP_LIMIT",
        ),
        E::UnknownGroup { group: g } | E::InvalidGroup { group: g, .. } => {
            group(*g, "eERR_CRD_CMD_GRP_AXIS_INVALID")
        }
        E::GroupState {
            group: g, state, ..
        } => match state {
            GroupState::Disabled => group(*g, "eERR_CRD_CMD_INVALID_DISABLED"),
            GroupState::Moving => group(*g, "eERR_CRD_CMD_INVALID_MOVING"),
            _ => group(*g, "eERR_CRD_CMD_INVALID_STATE"),
        },
        E::GroupMember {
            group: g, state, ..
        } => match state {
            AxisState::Disabled => group(*g, "eERR_CRD_CMD_INVALID_DISABLED"),
            _ => group(*g, "eERR_CRD_CMD_INVALID_STATE"),
        },
        E::GroupCauseStillPresent { group: g, .. } => group(*g, "eERR_CRD_CMD_INVALID_STATE"),
        // Adding an axis that is in a group already (TV 51) or moving one alone.
        E::AxisInGroup { axis: a, .. } => match group_of_call {
            Some(g) => group(g, "eERR_CRD_CMD_AXIS_DUPLICATED"),
            None => axis(*a, "eERR_AXIS_CMD_INVALID_GROUPED"),
        },
        E::GroupQueueFull { group: g, .. } => group(*g, "eERR_CRD_CMD_QUEUE_FULL"),
        E::InvalidPath { group: g, reason } => {
            let circular = ["arc", "circle", "radius", "centre", "center"]
                .iter()
                .any(|w| reason.contains(w));
            if circular {
                group(*g, "eERR_CRD_CMD_CIRC_INVALID_PARAM")
            } else {
                group(*g, "eERR_CRD_CMD_LIN_INVALID_PARAM")
            }
        }
        E::UndefinedCoordinateSystem { group: g, .. } => {
            group(*g, "eERR_CRD_CMD_COORD_SYS_UNKNOWN")
        }
        E::CoupledToItself { axis: a }
        | E::AlreadyCoupled { axis: a, .. }
        | E::CouplingLoop { slave: a, .. } => {
            axis(*a, "eERR_AXIS_CMD_INVALID_MASTER_SLAVE_CONNECTION")
        }
        E::AxisCoupled { axis: a, .. } => axis(*a, "eERR_AXIS_CMD_INVALID_IN_SYNC"),
        // Gantry set-up refused (digest 004 §5.3: 0x83□□00dc, the one gantry code).
        E::InvalidGantry { master: a, .. } | E::GantryExists { master: a } => {
            axis(*a, "eERR_AXIS_CMD_INVALID_GANTRY_MODE")
        }
        // HIMC has no handwheel (MPG) API: the nearest codes of the axis table.
        E::AxisOnHandwheel { axis: a } => axis(*a, "eERR_AXIS_CMD_INVALID_STATE"),
        E::UnknownHandwheelInput { .. } => invalid(subject),
        E::NotCoupled { axis: a, .. } => axis(*a, "eERR_AXIS_CMD_GEAR_DISABLED"),
        E::UnknownCamTable { .. } | E::InvalidCamTable { .. } | E::CamTableInUse { .. } => {
            match subject {
                Subject::Axis(a) => axis(a, "eERR_CAM_CMD_INVALID_CAMTABLE_ID"),
                _ => HMPL_ARG_OUT_OF_RANGE,
            }
        }
        E::InvalidTrigger { .. } => invalid(subject),
        // HIMC has no NMC Follow: the nearest codes of the axis table.
        E::InvalidFollow { .. } => invalid(subject),
        E::FollowFull { axis: a, .. } => axis(*a, "eERR_AXIS_CMD_QUEUE_FULL"),
        E::StreamPoint { axis: a, .. } => code_for(e).map_or_else(
            || invalid(subject),
            |c| compose(AXIS_CLASS, id_byte(*a), c.value),
        ),
    }
}

#[cfg(test)]
mod tests {
    use axes::AxisFlags;

    use super::*;

    #[test]
    fn axis_refusals_carry_the_axis_they_name() {
        let e = EngineError::AxisDisabled { axis: 2 };
        assert_eq!(error_code(&e, Subject::Axis(2)), 0x8302_0078);
        let e = EngineError::AxisInError {
            axis: 15,
            faults: AxisFlags::DRIVE_ALARM,
        };
        assert_eq!(error_code(&e, Subject::Axis(15)), 0x830f_0096);
        let e = EngineError::QueueFull { axis: 1, depth: 8 };
        assert_eq!(error_code(&e, Subject::System), 0x8301_001e);
    }

    #[test]
    fn a_target_beyond_a_soft_limit_is_invalid_pos() {
        let e = EngineError::InvalidArgument {
            name: "position",
            value: 20.0,
            reason: "beyond a software limit",
        };
        assert_eq!(error_code(&e, Subject::Axis(2)), 0x8302_0136);
    }

    #[test]
    fn group_refusals_are_group_codes() {
        let e = EngineError::AxisInGroup { axis: 1, group: 0 };
        assert_eq!(error_code(&e, Subject::Group(0)), 0x8200_0028, "TV 51");
        assert_eq!(error_code(&e, Subject::Axis(1)), 0x8301_00e6);
        let e = EngineError::GroupQueueFull {
            group: 3,
            capacity: 512,
        };
        assert_eq!(error_code(&e, Subject::Group(3)), 0x8203_0078);
        let e = EngineError::AxisDisabled { axis: 1 };
        assert_eq!(error_code(&e, Subject::Group(0)), 0x8200_0050);
    }

    #[test]
    fn refusals_without_a_subject_are_system_codes() {
        let e = EngineError::InvalidAxis { axis: 40, count: 4 };
        assert_eq!(error_code(&e, Subject::Axis(40)), HMPL_ARG_OUT_OF_RANGE);
        let e = EngineError::Unsupported { what: "x".into() };
        assert_eq!(error_code(&e, Subject::System), HMPL_NOT_SUPPORTED);
        let e = EngineError::item("axes", 1, EngineError::AxisDisabled { axis: 1 });
        assert_eq!(error_code(&e, Subject::System), 0x8301_0078);
    }
}
