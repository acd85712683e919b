//! What the node tells the application (the CiA 402 binding) and the transport.

use crate::nmt::NmtState;
use crate::store::ParameterGroup;

/// How a lost master was noticed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LossCause {
    /// A monitored heartbeat (0x1016) did not come in time.
    Heartbeat,
    /// Node guarding RTRs stopped for the life time (0x100C × 0x100D).
    LifeGuarding,
}

/// An event for the application or the transport. Drain them with
/// [`Node::poll_event`](crate::Node::poll_event) after each call.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum NodeEvent {
    NmtStateChanged {
        from: NmtState,
        to: NmtState,
    },
    /// NMT reset node: the application resets its own state (the drive to power-on); the
    /// node has already reset the application area of the dictionary to power-on values.
    ResetNode,
    /// NMT reset communication (also after reset node).
    ResetCommunication,
    /// A SYNC was consumed (Pre-operational or Operational); synchronous RPDOs were applied
    /// just before this event.
    Sync {
        counter: Option<u8>,
    },
    /// RPDO `pdo` (0-based: 0x1400 + pdo) wrote its mapped objects.
    RpdoReceived {
        pdo: u16,
    },
    /// An SDO download stored a value.
    ObjectWritten {
        index: u16,
        subindex: u8,
    },
    /// The master (a heartbeat producer of 0x1016, or the guarding master) is gone. The node
    /// has sent EMCY 0x8130 and applied 0x1029:01; the CiA 402 binding calls the drive's
    /// `connection_lost` (0x6007).
    MasterLost {
        node_id: Option<u8>,
        cause: LossCause,
    },
    MasterRecovered {
        node_id: Option<u8>,
        cause: LossCause,
    },
    /// A monitored node sent its boot-up message.
    RemoteBootUp {
        node_id: u8,
    },
    /// 0x1010 "save": write `image` (the whole new parameter image) atomically, then call
    /// [`Node::finish_persist`](crate::Node::finish_persist).
    StoreRequested {
        group: ParameterGroup,
        image: Vec<u8>,
    },
    /// 0x1011 "load": write `image` (the stored image without `group`) atomically, then call
    /// `finish_persist`; the defaults apply from the next reset.
    RestoreRequested {
        group: ParameterGroup,
        image: Vec<u8>,
    },
    /// LSS store configuration: persist the node id and bit timing.
    LssStoreRequested {
        node_id: u8,
        bit_timing: u8,
    },
    /// LSS activate bit timing: switch the interface's bit rate after the delay.
    BitTimingActivated {
        table_index: u8,
        delay_ms: u16,
    },
}
