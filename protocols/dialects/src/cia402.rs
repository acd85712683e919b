//! CiA 301/402, the standard every CANopen drive speaks: the SDO abort code an engine refusal
//! becomes when a master's write is refused. The statusword itself is the drive model's
//! (`axes::cia402`), which runs the CiA 402 power state machine inside the engine.

use axes::command::EngineError;

use crate::{cpu226h, modbus};

/// The SDO abort code (CiA 301 §7.2.4.3.17, Table 22) of an engine refusal: an object access
/// keeps its own code; a refused value is invalid value 0x06090030; any other refusal is
/// 0x08000022, data cannot be stored because of the present device state. The same codes a
/// map-backed node (the CT E10) gives for the same refusal through its register map.
pub fn sdo_abort_for(e: &EngineError) -> u32 {
    match e {
        EngineError::Object { error, .. } => error.sdo_abort_code(),
        _ => cpu226h::od_error_for_exception(modbus::exception_for(e), 0, 0, "").sdo_abort_code(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use axes::od::OdError;

    #[test]
    fn refusals_become_cia_301_aborts() {
        let value = EngineError::InvalidArgument {
            name: "velocity",
            value: -1.0,
            reason: "must be positive",
        };
        assert_eq!(sdo_abort_for(&value), 0x0609_0030);
        assert_eq!(
            sdo_abort_for(&EngineError::AxisDisabled { axis: 0 }),
            0x0800_0022
        );
        let object = EngineError::Object {
            slave: 1,
            error: OdError::ReadOnly {
                index: 0x6041,
                subindex: 0,
            },
        };
        assert_eq!(sdo_abort_for(&object), 0x0601_0002);
    }
}
