//! NMT slave state machine (CiA 301 §7.3.2) and the services each state allows.

/// NMT states, with the value a heartbeat or guarding reply carries (CiA 301 §7.2.8.3.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum NmtState {
    /// Initialisation; an unconfigured LSS slave (node id 0xFF) stays here.
    Initialising,
    PreOperational,
    Operational,
    Stopped,
}

impl NmtState {
    /// The state byte of heartbeat and node guarding (0 is the boot-up message).
    pub const fn code(self) -> u8 {
        match self {
            NmtState::Initialising => 0x00,
            NmtState::Stopped => 0x04,
            NmtState::Operational => 0x05,
            NmtState::PreOperational => 0x7F,
        }
    }

    pub const fn from_code(code: u8) -> Option<NmtState> {
        match code {
            0x00 => Some(NmtState::Initialising),
            0x04 => Some(NmtState::Stopped),
            0x05 => Some(NmtState::Operational),
            0x7F => Some(NmtState::PreOperational),
            _ => None,
        }
    }

    /// Whether a communication service runs in this state (CiA 301 §7.3.2.2, Table 41).
    pub const fn allows(self, service: Service) -> bool {
        use NmtState::*;
        use Service::*;
        match (self, service) {
            (Initialising, _) => false,
            (_, Nmt | ErrorControl) => true,
            (Stopped, _) => false,
            (PreOperational, Pdo) => false,
            (PreOperational | Operational, Sdo | Sync | Emcy) => true,
            (Operational, Pdo) => true,
        }
    }
}

/// Communication services, for [`NmtState::allows`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Service {
    Nmt,
    /// Heartbeat and node guarding.
    ErrorControl,
    Sdo,
    Sync,
    Emcy,
    Pdo,
}

/// NMT node control commands (CiA 301 §7.2.8.3.1, COB-ID 0, byte 0 the command specifier).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NmtCommand {
    Start,
    Stop,
    EnterPreOperational,
    ResetNode,
    ResetCommunication,
}

impl NmtCommand {
    pub const fn from_specifier(cs: u8) -> Option<NmtCommand> {
        match cs {
            0x01 => Some(NmtCommand::Start),
            0x02 => Some(NmtCommand::Stop),
            0x80 => Some(NmtCommand::EnterPreOperational),
            0x81 => Some(NmtCommand::ResetNode),
            0x82 => Some(NmtCommand::ResetCommunication),
            _ => None,
        }
    }

    pub const fn specifier(self) -> u8 {
        match self {
            NmtCommand::Start => 0x01,
            NmtCommand::Stop => 0x02,
            NmtCommand::EnterPreOperational => 0x80,
            NmtCommand::ResetNode => 0x81,
            NmtCommand::ResetCommunication => 0x82,
        }
    }

    /// Parse an NMT frame's data for node `node_id`: two bytes, command and target (0 = all).
    pub fn parse(data: &[u8], node_id: u8) -> Option<NmtCommand> {
        match *data {
            [cs, target] if target == 0 || target == node_id => NmtCommand::from_specifier(cs),
            _ => None,
        }
    }

    /// The state a command leads to from a running state; resets pass through Initialising
    /// and end in Pre-operational after the boot-up message.
    pub const fn target(self) -> NmtState {
        match self {
            NmtCommand::Start => NmtState::Operational,
            NmtCommand::Stop => NmtState::Stopped,
            NmtCommand::EnterPreOperational
            | NmtCommand::ResetNode
            | NmtCommand::ResetCommunication => NmtState::PreOperational,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn service_table_matches_cia_301_table_41() {
        use NmtState::*;
        use Service::*;
        let rows = [
            (PreOperational, [true, true, true, true, true, false]),
            (Operational, [true, true, true, true, true, true]),
            (Stopped, [true, true, false, false, false, false]),
            (Initialising, [false; 6]),
        ];
        for (state, allowed) in rows {
            for (service, want) in [Nmt, ErrorControl, Sdo, Sync, Emcy, Pdo]
                .into_iter()
                .zip(allowed)
            {
                assert_eq!(state.allows(service), want, "{state:?} {service:?}");
            }
        }
    }

    #[test]
    fn commands_parse_for_own_id_and_broadcast_only() {
        assert_eq!(NmtCommand::parse(&[1, 0], 5), Some(NmtCommand::Start));
        assert_eq!(
            NmtCommand::parse(&[0x81, 5], 5),
            Some(NmtCommand::ResetNode)
        );
        assert_eq!(NmtCommand::parse(&[1, 6], 5), None);
        assert_eq!(NmtCommand::parse(&[3, 0], 5), None);
        assert_eq!(NmtCommand::parse(&[1], 5), None);
        assert_eq!(NmtCommand::parse(&[1, 0, 0], 5), None);
        for code in [0u8, 4, 5, 0x7F] {
            assert_eq!(NmtState::from_code(code).map(NmtState::code), Some(code));
        }
    }
}
