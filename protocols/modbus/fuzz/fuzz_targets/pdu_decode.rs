//! `pdu::decode_request` on arbitrary bytes: never panics; a decoded request keeps its function
//! code and the lengths its layout implies; a refusal encodes to a two-byte exception PDU; and
//! the response a server would give to a decoded request (echo for the writes and FC 8, data
//! of the requested size for the reads) encodes without panicking, within 253 bytes for the
//! functions whose requests bound it.

#![no_main]

use libfuzzer_sys::fuzz_target;
use mcemu_modbus::pdu::{
    decode_request, encode_response, fc, limits, Exception, Request, Response,
};

fuzz_target!(|data: &[u8]| {
    let mut out = Vec::new();
    let request = match decode_request(data) {
        Ok(request) => request,
        Err(refusal) => {
            encode_response(&Response::from(refusal), &mut out);
            assert_eq!(out.len(), 2);
            assert_eq!(out[0], refusal.function | 0x80);
            assert_eq!(Exception::from_code(out[1]), Some(refusal.exception));
            if let Some(&function) = data.first() {
                assert_eq!(refusal.function, function);
            }
            return;
        }
    };
    assert_eq!(request.function(), data[0]);

    // Every decoded request can be refused.
    encode_response(
        &Response::exception(request.function(), Exception::ServerDeviceFailure),
        &mut out,
    );
    assert_eq!(out, [data[0] | 0x80, 0x04]);
    out.clear();

    let pattern = |n: usize| (0..n).map(|i| i % 3 == 0).collect::<Vec<bool>>();
    let words = |n: usize| (0..n).map(|i| i as u16 ^ 0xA55A).collect::<Vec<u16>>();
    let response = match &request {
        Request::ReadCoils { quantity, .. } | Request::ReadDiscreteInputs { quantity, .. } => {
            Response::Bits {
                function: data[0],
                bits: pattern(usize::from(*quantity)),
            }
        }
        Request::ReadHoldingRegisters { quantity, .. }
        | Request::ReadInputRegisters { quantity, .. } => Response::Registers {
            function: data[0],
            words: words(usize::from(*quantity)),
        },
        Request::ReadWriteMultipleRegisters {
            read_quantity,
            write_quantity,
            values,
            ..
        } => {
            assert_eq!(values.len(), 2 * usize::from(*write_quantity));
            Response::Registers {
                function: fc::READ_WRITE_MULTIPLE_REGISTERS,
                words: words(usize::from(*read_quantity)),
            }
        }
        Request::WriteSingleCoil { address, value } => Response::WriteSingle {
            function: fc::WRITE_SINGLE_COIL,
            address: *address,
            value: if *value { 0xFF00 } else { 0 },
        },
        Request::WriteSingleRegister { address, value } => Response::WriteSingle {
            function: fc::WRITE_SINGLE_REGISTER,
            address: *address,
            value: *value,
        },
        Request::WriteMultipleCoils {
            address,
            quantity,
            values,
        } => {
            assert_eq!(values.len(), usize::from(*quantity).div_ceil(8));
            Response::WriteMultiple {
                function: fc::WRITE_MULTIPLE_COILS,
                address: *address,
                quantity: *quantity,
            }
        }
        Request::WriteMultipleRegisters {
            address,
            quantity,
            values,
        } => {
            assert_eq!(values.len(), 2 * usize::from(*quantity));
            Response::WriteMultiple {
                function: fc::WRITE_MULTIPLE_REGISTERS,
                address: *address,
                quantity: *quantity,
            }
        }
        Request::MaskWriteRegister {
            address,
            and_mask,
            or_mask,
        } => Response::MaskWrite {
            address: *address,
            and_mask: *and_mask,
            or_mask: *or_mask,
        },
        Request::Diagnostics { sub_function, data } => Response::Diagnostics {
            sub_function: *sub_function,
            data: data.to_vec(),
        },
        Request::ReportServerId => Response::ServerId {
            id: b"mcemu".to_vec(),
            running: true,
        },
        Request::ReadDeviceIdentification {
            read_code,
            object_id,
        } => {
            assert!((1..=4).contains(read_code));
            Response::DeviceIdentification {
                read_code: *read_code,
                conformity: 0x83,
                more_follows: false,
                next_object_id: 0,
                objects: vec![(*object_id, b"mcemu".to_vec())],
            }
        }
    };
    encode_response(&response, &mut out);
    assert_eq!(out[0], data[0]);
    match request {
        // The normal response of these is an echo of the request (FC 8: of sub-function 0).
        Request::WriteSingleCoil { .. }
        | Request::WriteSingleRegister { .. }
        | Request::MaskWriteRegister { .. }
        | Request::Diagnostics { .. } => assert_eq!(out, data),
        Request::WriteMultipleCoils { .. } | Request::WriteMultipleRegisters { .. } => {
            assert_eq!(out, data[..5])
        }
        // Quantity limits keep the largest read response inside one PDU.
        Request::ReadCoils { .. }
        | Request::ReadDiscreteInputs { .. }
        | Request::ReadHoldingRegisters { .. }
        | Request::ReadInputRegisters { .. }
        | Request::ReadWriteMultipleRegisters { .. } => {
            assert!(out.len() <= limits::MAX_PDU, "{} bytes", out.len());
            assert_eq!(usize::from(out[1]), out.len() - 2);
        }
        Request::ReportServerId | Request::ReadDeviceIdentification { .. } => {}
    }
});
