//! HIMC group errors, Table 18.1.3.1 (digest 004 §5.3): codes 0x82NNVVVV, NN the group id.

use super::group::GroupError;

/// One row of the group error table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GroupErrorRow {
    /// VVVV, the low word of the code.
    pub value: u16,
    /// The manual's name, verbatim (the space in `eERR CRD_CMD_INVALID_FREQUENCY` included).
    pub name: &'static str,
    /// Its meaning, in English (digest 004 §5.3).
    pub meaning: &'static str,
}

impl GroupErrorRow {
    /// The row called `name`.
    pub fn by_name(name: &str) -> Option<&'static GroupErrorRow> {
        GROUP_ERRORS.iter().find(|e| e.name == name)
    }

    /// The row with low word `value`.
    pub fn by_value(value: u16) -> Option<&'static GroupErrorRow> {
        GROUP_ERRORS.iter().find(|e| e.value == value)
    }

    /// The row as the error a group function returns.
    pub const fn error(&self) -> GroupError {
        GroupError {
            value: self.value,
            name: self.name,
        }
    }
}

macro_rules! group_errors {
    ($(($value:literal, $name:literal, $meaning:literal),)*) => {
        /// The group errors, Table 18.1.3.1 (digest 004 §5.3), in the manual's order.
        pub const GROUP_ERRORS: &[GroupErrorRow] = &[
            $(GroupErrorRow { value: $value, name: $name, meaning: $meaning },)*
        ];
    };
}

group_errors! {
    (0x000a, "eERR_CRD_CMD_UNKNOWN", "Unknown group command."),
    (0x0014, "eERR_CRD_CMD_REACH_MAX_NUM_AXIS", "Group reached maximum number of axes."),
    (0x001e, "eERR_CRD_CMD_INVALID_KIN_SETTING", "Invalid kinematics type."),
    (0x001f, "eERR_CRD_CMD_INVALID_SPECIFIC_KIN", "Command invalid: group is in a special kinematics mode."),
    (0x0028, "eERR_CRD_CMD_AXIS_DUPLICATED", "Cannot add axis: axis already in group."),
    (0x0032, "eERR_CRD_CMD_GRP_SIZE_EMPTY", "Group is empty."),
    (0x003c, "eERR_CRD_CMD_GRP_SIZE_FULL", "Group is full; cannot add axis."),
    (0x0046, "eERR_CRD_CMD_INVALID_MOVING", "Command invalid while group is moving."),
    (0x0050, "eERR_CRD_CMD_INVALID_DISABLED", "Command invalid: group not enabled."),
    (0x005a, "eERR_CRD_CMD_INVALID_INPUTSHAPING_PARAMETER_INCOMPLETE", "Group input-shaping parameters incomplete."),
    (0x006e, "eERR_CRD_CMD_INVALID_STATE", "Group cannot execute this command in its current motion state."),
    (0x0078, "eERR_CRD_CMD_QUEUE_FULL", "Wait for the previous command to finish (queue full)."),
    (0x0082, "eERR_CRD_CMD_GRP_AXIS_INVALID", "Group invalid."),
    (0x008c, "eERR_CRD_CMD_QUEUE_IS_NOT_EMPTY", "Group command queue not empty."),
    (0x0096, "eERR_CRD_CMD_INVALID_QUEUE_SIZE", "Group command queue size invalid."),
    (0x00d2, "eERR_CRD_CMD_INVALID_POS", "Group target position or orientation out of allowed range."),
    (0x00dc, "eERR_CRD_CMD_INVALID_LIN_VEL", "Group linear velocity setting out of allowed range."),
    (0x00e6, "eERR_CRD_CMD_INVALID_LIN_ACC", "Group linear acceleration setting out of allowed range."),
    (0x00f0, "eERR_CRD_CMD_INVALID_LIN_DEC", "Group linear deceleration setting out of allowed range."),
    (0x00fa, "eERR_CRD_CMD_INVALID_LIN_JERK", "Group linear jerk setting out of allowed range."),
    (0x0104, "eERR_CRD_CMD_INVALID_LIN_SM_TIME", "Group linear smoothing time out of allowed range."),
    (0x010e, "eERR_CRD_CMD_INVALID_DAMPINGRATIO", "Group damping ratio setting out of allowed range."),
    (0x0118, "eERR CRD_CMD_INVALID_FREQUENCY", "Group frequency setting out of allowed range."),
    (0x0140, "eERR_CRD_CMD_INVALID_ANG_VEL", "Group angular velocity setting out of allowed range."),
    (0x014a, "eERR_CRD_CMD_INVALID_ANG_ACC", "Group angular acceleration setting out of allowed range."),
    (0x0154, "eERR_CRD_CMD_INVALID_ANG_DEC", "Group angular deceleration setting out of allowed range."),
    (0x015e, "eERR_CRD_CMD_INVALID_ANG_JERK", "Group angular jerk setting out of allowed range."),
    (0x0168, "eERR_CRD_CMD_INVALID_ANG_SM_TIME", "Group angular smoothing time out of allowed range."),
    (0x0190, "eERR_CRD_CMD_INVALID_VEL_SCALE", "Group velocity percentage out of allowed range."),
    (0x019a, "eERR_CRD_CMD_INVALID_TRANS_VEL", "Group transition velocity invalid."),
    (0x01a4, "eERR_CRD_CMD_INVALID_TRANS_DIS", "Group transition distance invalid."),
    (0x01a5, "eERR_CRD_CMD_INVALID_TRANS_DEV", "Group transition deviation invalid."),
    (0x01a6, "eERR_CRD_CMD_INVALID_TRANS_CURVE", "Group transition curvature invalid."),
    (0x01b8, "eERR_CRD_CMD_TRANS_MODE_UNKNOWN", "Unknown Transition mode."),
    (0x01c2, "eERR_CRD_CMD_COORD_SYS_UNKNOWN", "Unknown coordinate system."),
    (0x01cc, "eERR_CRD_CMD_BLEND_MODE_UNKNOWN", "Unknown Blending (buffer) mode."),
    (0x01fe, "eERR_CRD_CMD_LIN_INVALID_PARAM", "Linear path planning parameters invalid."),
    (0x0262, "eERR_CRD_CMD_CIRC_INVALID_PARAM", "Circular path planning parameters invalid."),
    (0x026c, "eERR_CRD_CMD_CIRC_INVALID_CENTER", "Arc center too close to start or end point."),
    (0x0276, "eERR_CRD_CMD_CIRC_ANGLE_SMALL", "Arc central angle too small."),
    (0x0280, "eERR_CRD_CMD_CIRC_INVALID_RADIUS", "Arc radius invalid."),
    (0x028a, "eERR_CRD_CMD_CIRC_INVALID_COORD", "Arc coordinate system invalid."),
    (0x02c6, "eERR_CRD_CMD_BEZIER_INVALID_PARAM", "Bezier path planning parameters invalid."),
    (0x02d0, "eERR_CRD_CMD_BSPLINE_INVALID_PARAM", "BSpline path planning parameters invalid."),
    (0x02da, "eERR_CRD_CMD_CURVE_INVALID_STARTPOS", "Curve path planning start position invalid."),
    (0x02e4, "eERR_CRD_CMD_COORD_INVALID_PARAM", "Coordinate transformation parameters invalid."),
    (0x02ee, "eERR_CRD_CMD_NURBS_INVALID_PARAM", "NURBS path planning parameters invalid."),
    (0x02f8, "eERR_CRD_CMD_LOOKAHEAD_INVALID_PARAM", "Group look-ahead parameters invalid."),
    (0x03f2, "eERR_CRD_AXIS_ABNORMALLY_DISABLED", "One or more group axes abnormally disabled."),
    (0x03fc, "eERR_CRD_AXIS_SWL", "A group axis exceeded a software limit."),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_group_table_is_the_manuals() {
        assert_eq!(GROUP_ERRORS.len(), 50, "digest 004 §5: 50 group entries");
        let mut values: Vec<u16> = GROUP_ERRORS.iter().map(|e| e.value).collect();
        values.sort_unstable();
        values.dedup();
        assert_eq!(values.len(), GROUP_ERRORS.len(), "values are unique");
        // TV 73: group 0's axis software-limit fault is 0x820003fc.
        let swl = GroupErrorRow::by_name("eERR_CRD_AXIS_SWL").map(|e| e.error().code(0));
        assert_eq!(swl, Some(0x8200_03fc));
        // TV 51: the duplicated-axis code.
        let dup = GroupErrorRow::by_value(0x0028).map(|e| e.name);
        assert_eq!(dup, Some("eERR_CRD_CMD_AXIS_DUPLICATED"));
    }
}
