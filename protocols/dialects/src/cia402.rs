//! CiA 301/402, the standard every CANopen drive speaks: the SDO abort code an engine refusal
//! becomes when a master's write is refused. The statusword itself is the drive model's
//! (`axes::cia402`), which runs the CiA 402 power state machine inside the engine.

use axes::command::EngineError;
use axes::status::CaptureStatus;

use crate::{cpu226h, modbus};

/// The touch probe status word 0x60B9 of two capture channels as touch probes 1 and 2 (digest
/// 000 §5 EtherCAT_CaptureGetStatus; HIMC IsTouchProbe1Enabled/Triggered, digest 004 §2.12):
/// bit 0 enabled (armed), bit 1 a rising edge latched, bit 2 a falling one; bits 8–10 the same
/// for probe 2. HMC vector 57: probe 1 armed and triggered on a rising edge reads 0x0003.
pub fn touch_probe_status(tp1: Option<&CaptureStatus>, tp2: Option<&CaptureStatus>) -> u16 {
    let bits = |c: Option<&CaptureStatus>| {
        c.map_or(0, |c| {
            let mut b = 0x1;
            if c.latches.iter().any(|l| l.rising) {
                b |= 0x2;
            }
            if c.latches.iter().any(|l| !l.rising) {
                b |= 0x4;
            }
            b
        })
    };
    bits(tp1) | bits(tp2) << 8
}

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

    #[test]
    fn touch_probe_status_hmc_vector_57() {
        let mut tp1 = CaptureStatus {
            axis: 0,
            channel: 0,
            source: axes::status::CaptureSource::Index,
            source_axis: 0,
            input: None,
            edge: axes::status::CaptureEdge::Rising,
            repeat: 1,
            continuous: false,
            window: None,
            state: axes::status::CaptureState::Waiting,
            count: 0,
            latches: vec![],
        };
        assert_eq!(touch_probe_status(Some(&tp1), None), 0x0001);
        tp1.latches.push(axes::status::Latch {
            rising: true,
            ..Default::default()
        });
        assert_eq!(touch_probe_status(Some(&tp1), None), 0x0003);
        let mut tp2 = tp1.clone();
        tp2.latches[0].rising = false;
        assert_eq!(touch_probe_status(None, Some(&tp2)), 0x0500);
    }
}
