//! Modbus PDUs (Modbus Application Protocol Specification V1.1b3): requests decoded from bytes
//! and responses encoded to bytes. Sans-IO and total: any input decodes to a request or to the
//! exception the specification prescribes, never a panic.
//!
//! Decoding performs the first checks of the specification's order (anchors §26): the function
//! code is supported (else exception 01), then quantities, byte counts and values are in range
//! (else 03). The address check (02) needs the register map and happens in the service, before
//! execution (04 on failure).

/// Function codes this server implements.
pub mod fc {
    pub const READ_COILS: u8 = 0x01;
    pub const READ_DISCRETE_INPUTS: u8 = 0x02;
    pub const READ_HOLDING_REGISTERS: u8 = 0x03;
    pub const READ_INPUT_REGISTERS: u8 = 0x04;
    pub const WRITE_SINGLE_COIL: u8 = 0x05;
    pub const WRITE_SINGLE_REGISTER: u8 = 0x06;
    pub const DIAGNOSTICS: u8 = 0x08;
    pub const WRITE_MULTIPLE_COILS: u8 = 0x0F;
    pub const WRITE_MULTIPLE_REGISTERS: u8 = 0x10;
    pub const REPORT_SERVER_ID: u8 = 0x11;
    pub const MASK_WRITE_REGISTER: u8 = 0x16;
    pub const READ_WRITE_MULTIPLE_REGISTERS: u8 = 0x17;
    pub const ENCAPSULATED_INTERFACE: u8 = 0x2B;
    /// MEI type of Read Device Identification under FC 43.
    pub const MEI_READ_DEVICE_ID: u8 = 0x0E;
}

/// Quantity limits (specification §6; libmodbus `modbus.h`).
pub mod limits {
    pub const MAX_READ_BITS: u16 = 2000;
    pub const MAX_WRITE_BITS: u16 = 1968;
    pub const MAX_READ_REGISTERS: u16 = 125;
    pub const MAX_WRITE_REGISTERS: u16 = 123;
    pub const MAX_RW_WRITE_REGISTERS: u16 = 121;
    /// Largest PDU: 253 bytes (RTU ADU 256 − address − CRC; TCP ADU 260 − MBAP 7).
    pub const MAX_PDU: usize = 253;
}

/// Exception codes (specification §7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Exception {
    IllegalFunction = 0x01,
    IllegalDataAddress = 0x02,
    IllegalDataValue = 0x03,
    ServerDeviceFailure = 0x04,
    Acknowledge = 0x05,
    ServerDeviceBusy = 0x06,
    GatewayPathUnavailable = 0x0A,
    GatewayTargetFailed = 0x0B,
}

impl Exception {
    pub fn code(self) -> u8 {
        self as u8
    }

    pub fn from_code(code: u8) -> Option<Exception> {
        Some(match code {
            0x01 => Exception::IllegalFunction,
            0x02 => Exception::IllegalDataAddress,
            0x03 => Exception::IllegalDataValue,
            0x04 => Exception::ServerDeviceFailure,
            0x05 => Exception::Acknowledge,
            0x06 => Exception::ServerDeviceBusy,
            0x0A => Exception::GatewayPathUnavailable,
            0x0B => Exception::GatewayTargetFailed,
            _ => return None,
        })
    }
}

/// A decoded request. Write data borrow the frame: register values stay big-endian bytes and
/// coils stay packed, as on the wire.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Request<'a> {
    ReadCoils {
        address: u16,
        quantity: u16,
    },
    ReadDiscreteInputs {
        address: u16,
        quantity: u16,
    },
    ReadHoldingRegisters {
        address: u16,
        quantity: u16,
    },
    ReadInputRegisters {
        address: u16,
        quantity: u16,
    },
    WriteSingleCoil {
        address: u16,
        value: bool,
    },
    WriteSingleRegister {
        address: u16,
        value: u16,
    },
    /// FC 8 with its sub-function and data (echoed or interpreted by the diagnostics).
    Diagnostics {
        sub_function: u16,
        data: &'a [u8],
    },
    WriteMultipleCoils {
        address: u16,
        quantity: u16,
        /// `ceil(quantity / 8)` bytes, LSB first.
        values: &'a [u8],
    },
    WriteMultipleRegisters {
        address: u16,
        quantity: u16,
        /// `2 × quantity` bytes, big-endian words.
        values: &'a [u8],
    },
    ReportServerId,
    MaskWriteRegister {
        address: u16,
        and_mask: u16,
        or_mask: u16,
    },
    ReadWriteMultipleRegisters {
        read_address: u16,
        read_quantity: u16,
        write_address: u16,
        write_quantity: u16,
        values: &'a [u8],
    },
    /// FC 43 / MEI 14.
    ReadDeviceIdentification {
        read_code: u8,
        object_id: u8,
    },
}

impl Request<'_> {
    /// The function code this request came with.
    pub fn function(&self) -> u8 {
        match self {
            Request::ReadCoils { .. } => fc::READ_COILS,
            Request::ReadDiscreteInputs { .. } => fc::READ_DISCRETE_INPUTS,
            Request::ReadHoldingRegisters { .. } => fc::READ_HOLDING_REGISTERS,
            Request::ReadInputRegisters { .. } => fc::READ_INPUT_REGISTERS,
            Request::WriteSingleCoil { .. } => fc::WRITE_SINGLE_COIL,
            Request::WriteSingleRegister { .. } => fc::WRITE_SINGLE_REGISTER,
            Request::Diagnostics { .. } => fc::DIAGNOSTICS,
            Request::WriteMultipleCoils { .. } => fc::WRITE_MULTIPLE_COILS,
            Request::WriteMultipleRegisters { .. } => fc::WRITE_MULTIPLE_REGISTERS,
            Request::ReportServerId => fc::REPORT_SERVER_ID,
            Request::MaskWriteRegister { .. } => fc::MASK_WRITE_REGISTER,
            Request::ReadWriteMultipleRegisters { .. } => fc::READ_WRITE_MULTIPLE_REGISTERS,
            Request::ReadDeviceIdentification { .. } => fc::ENCAPSULATED_INTERFACE,
        }
    }

    /// Whether the request changes state (a broadcast may only carry these).
    pub fn is_write(&self) -> bool {
        matches!(
            self,
            Request::WriteSingleCoil { .. }
                | Request::WriteSingleRegister { .. }
                | Request::WriteMultipleCoils { .. }
                | Request::WriteMultipleRegisters { .. }
                | Request::MaskWriteRegister { .. }
        )
    }
}

/// A request that cannot be executed: the function code to answer with and the exception.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Refusal {
    pub function: u8,
    pub exception: Exception,
}

fn be16(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes([*b.get(at)?, *b.get(at + 1)?]))
}

/// Decode a request PDU (function code first). Never panics.
pub fn decode_request(pdu: &[u8]) -> Result<Request<'_>, Refusal> {
    let Some(&function) = pdu.first() else {
        // Nothing to answer to; 0 keeps the exception well-formed.
        return Err(Refusal {
            function: 0,
            exception: Exception::IllegalFunction,
        });
    };
    let refuse = |exception| Refusal {
        function,
        exception,
    };
    let value = || refuse(Exception::IllegalDataValue);
    let body = &pdu[1..];
    // A request whose length does not match its function's layout is malformed: exception 03.
    let exact = |n: usize| {
        if body.len() == n {
            Ok(())
        } else {
            Err(value())
        }
    };
    let word = |at: usize| be16(body, at).ok_or_else(value);
    let quantity = |at: usize, max: u16| -> Result<u16, Refusal> {
        let q = word(at)?;
        if q == 0 || q > max {
            Err(value())
        } else {
            Ok(q)
        }
    };
    match function {
        fc::READ_COILS | fc::READ_DISCRETE_INPUTS => {
            exact(4)?;
            let address = word(0)?;
            let quantity = quantity(2, limits::MAX_READ_BITS)?;
            Ok(if function == fc::READ_COILS {
                Request::ReadCoils { address, quantity }
            } else {
                Request::ReadDiscreteInputs { address, quantity }
            })
        }
        fc::READ_HOLDING_REGISTERS | fc::READ_INPUT_REGISTERS => {
            exact(4)?;
            let address = word(0)?;
            let quantity = quantity(2, limits::MAX_READ_REGISTERS)?;
            Ok(if function == fc::READ_HOLDING_REGISTERS {
                Request::ReadHoldingRegisters { address, quantity }
            } else {
                Request::ReadInputRegisters { address, quantity }
            })
        }
        fc::WRITE_SINGLE_COIL => {
            exact(4)?;
            let address = word(0)?;
            // Only 0xFF00 (on) and 0x0000 (off) are values (specification §6.5).
            let value = match word(2)? {
                0xFF00 => true,
                0x0000 => false,
                _ => return Err(value()),
            };
            Ok(Request::WriteSingleCoil { address, value })
        }
        fc::WRITE_SINGLE_REGISTER => {
            exact(4)?;
            Ok(Request::WriteSingleRegister {
                address: word(0)?,
                value: word(2)?,
            })
        }
        fc::DIAGNOSTICS => {
            if body.len() < 2 {
                return Err(value());
            }
            Ok(Request::Diagnostics {
                sub_function: word(0)?,
                data: &body[2..],
            })
        }
        fc::WRITE_MULTIPLE_COILS => {
            let address = word(0)?;
            let quantity = quantity(2, limits::MAX_WRITE_BITS)?;
            let count = *body.get(4).ok_or_else(value)? as usize;
            let values = &body.get(5..).ok_or_else(value)?;
            if count != (quantity as usize).div_ceil(8) || values.len() != count {
                return Err(value());
            }
            Ok(Request::WriteMultipleCoils {
                address,
                quantity,
                values,
            })
        }
        fc::WRITE_MULTIPLE_REGISTERS => {
            let address = word(0)?;
            let quantity = quantity(2, limits::MAX_WRITE_REGISTERS)?;
            let count = *body.get(4).ok_or_else(value)? as usize;
            let values = &body.get(5..).ok_or_else(value)?;
            if count != 2 * quantity as usize || values.len() != count {
                return Err(value());
            }
            Ok(Request::WriteMultipleRegisters {
                address,
                quantity,
                values,
            })
        }
        fc::REPORT_SERVER_ID => {
            exact(0)?;
            Ok(Request::ReportServerId)
        }
        fc::MASK_WRITE_REGISTER => {
            exact(6)?;
            Ok(Request::MaskWriteRegister {
                address: word(0)?,
                and_mask: word(2)?,
                or_mask: word(4)?,
            })
        }
        fc::READ_WRITE_MULTIPLE_REGISTERS => {
            let read_address = word(0)?;
            let read_quantity = quantity(2, limits::MAX_READ_REGISTERS)?;
            let write_address = word(4)?;
            let write_quantity = quantity(6, limits::MAX_RW_WRITE_REGISTERS)?;
            let count = *body.get(8).ok_or_else(value)? as usize;
            let values = &body.get(9..).ok_or_else(value)?;
            if count != 2 * write_quantity as usize || values.len() != count {
                return Err(value());
            }
            Ok(Request::ReadWriteMultipleRegisters {
                read_address,
                read_quantity,
                write_address,
                write_quantity,
                values,
            })
        }
        fc::ENCAPSULATED_INTERFACE => {
            exact(3)?;
            if body.first() != Some(&fc::MEI_READ_DEVICE_ID) {
                // Other MEI types (e.g. 13, CANopen general reference) are not served.
                return Err(refuse(Exception::IllegalFunction));
            }
            let read_code = body[1];
            let object_id = body[2];
            if !(1..=4).contains(&read_code) {
                return Err(value());
            }
            Ok(Request::ReadDeviceIdentification {
                read_code,
                object_id,
            })
        }
        _ => Err(refuse(Exception::IllegalFunction)),
    }
}

/// A response, owned. Encoded by [`encode_response`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Response {
    /// FC 1/2: the bits read.
    Bits {
        function: u8,
        bits: Vec<bool>,
    },
    /// FC 3/4/23: the registers read.
    Registers {
        function: u8,
        words: Vec<u16>,
    },
    /// FC 5/6: echo of the request.
    WriteSingle {
        function: u8,
        address: u16,
        value: u16,
    },
    /// FC 15/16: address and quantity written.
    WriteMultiple {
        function: u8,
        address: u16,
        quantity: u16,
    },
    /// FC 22: echo.
    MaskWrite {
        address: u16,
        and_mask: u16,
        or_mask: u16,
    },
    /// FC 8: sub-function and data.
    Diagnostics {
        sub_function: u16,
        data: Vec<u8>,
    },
    /// FC 17: server id bytes, run indicator, additional data.
    ServerId {
        id: Vec<u8>,
        running: bool,
    },
    /// FC 43/14.
    DeviceIdentification {
        read_code: u8,
        conformity: u8,
        more_follows: bool,
        next_object_id: u8,
        objects: Vec<(u8, Vec<u8>)>,
    },
    Exception {
        function: u8,
        exception: Exception,
    },
}

impl Response {
    pub fn exception(function: u8, exception: Exception) -> Response {
        Response::Exception {
            function,
            exception,
        }
    }
}

impl From<Refusal> for Response {
    fn from(r: Refusal) -> Response {
        Response::exception(r.function, r.exception)
    }
}

/// Append the PDU of `response` to `out`.
pub fn encode_response(response: &Response, out: &mut Vec<u8>) {
    let put16 = |out: &mut Vec<u8>, v: u16| out.extend_from_slice(&v.to_be_bytes());
    match response {
        Response::Bits { function, bits } => {
            out.push(*function);
            let n = bits.len().div_ceil(8);
            out.push(n as u8);
            let start = out.len();
            out.resize(start + n, 0);
            for (i, bit) in bits.iter().enumerate() {
                if *bit {
                    out[start + i / 8] |= 1 << (i % 8);
                }
            }
        }
        Response::Registers { function, words } => {
            out.push(*function);
            out.push((2 * words.len()) as u8);
            for w in words {
                put16(out, *w);
            }
        }
        Response::WriteSingle {
            function,
            address,
            value,
        } => {
            out.push(*function);
            put16(out, *address);
            put16(out, *value);
        }
        Response::WriteMultiple {
            function,
            address,
            quantity,
        } => {
            out.push(*function);
            put16(out, *address);
            put16(out, *quantity);
        }
        Response::MaskWrite {
            address,
            and_mask,
            or_mask,
        } => {
            out.push(fc::MASK_WRITE_REGISTER);
            put16(out, *address);
            put16(out, *and_mask);
            put16(out, *or_mask);
        }
        Response::Diagnostics { sub_function, data } => {
            out.push(fc::DIAGNOSTICS);
            put16(out, *sub_function);
            out.extend_from_slice(data);
        }
        Response::ServerId { id, running } => {
            out.push(fc::REPORT_SERVER_ID);
            out.push((id.len() + 1) as u8);
            out.extend_from_slice(id);
            out.push(if *running { 0xFF } else { 0x00 });
        }
        Response::DeviceIdentification {
            read_code,
            conformity,
            more_follows,
            next_object_id,
            objects,
        } => {
            out.push(fc::ENCAPSULATED_INTERFACE);
            out.push(fc::MEI_READ_DEVICE_ID);
            out.push(*read_code);
            out.push(*conformity);
            out.push(if *more_follows { 0xFF } else { 0x00 });
            out.push(*next_object_id);
            out.push(objects.len() as u8);
            for (id, value) in objects {
                out.push(*id);
                out.push(value.len() as u8);
                out.extend_from_slice(value);
            }
        }
        Response::Exception {
            function,
            exception,
        } => {
            out.push(function | 0x80);
            out.push(exception.code());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(pdu: &[u8]) -> Exception {
        decode_request(pdu).unwrap_err().exception
    }

    #[test]
    fn reads_decode_and_enforce_quantity_limits() {
        assert_eq!(
            decode_request(&[3, 0, 0x10, 0, 10]),
            Ok(Request::ReadHoldingRegisters {
                address: 0x10,
                quantity: 10
            })
        );
        for (f, max) in [(1u8, 2000u16), (2, 2000), (3, 125), (4, 125)] {
            let [hi, lo] = max.to_be_bytes();
            assert!(decode_request(&[f, 0, 0, hi, lo]).is_ok(), "{f} at max");
            let [hi, lo] = (max + 1).to_be_bytes();
            assert_eq!(refused(&[f, 0, 0, hi, lo]), Exception::IllegalDataValue);
            assert_eq!(
                refused(&[f, 0, 0, 0, 0]),
                Exception::IllegalDataValue,
                "quantity 0"
            );
            assert_eq!(
                refused(&[f, 0, 0, 0]),
                Exception::IllegalDataValue,
                "truncated"
            );
            assert_eq!(
                refused(&[f, 0, 0, 0, 1, 9]),
                Exception::IllegalDataValue,
                "too long"
            );
        }
    }

    #[test]
    fn writes_check_values_and_byte_counts() {
        assert_eq!(
            decode_request(&[5, 0, 1, 0xFF, 0]),
            Ok(Request::WriteSingleCoil {
                address: 1,
                value: true
            })
        );
        assert_eq!(refused(&[5, 0, 1, 0x12, 0x34]), Exception::IllegalDataValue);
        // 10 coils need 2 bytes.
        assert!(decode_request(&[15, 0, 0, 0, 10, 2, 0xFF, 0x03]).is_ok());
        assert_eq!(
            refused(&[15, 0, 0, 0, 10, 1, 0xFF]),
            Exception::IllegalDataValue
        );
        assert_eq!(
            refused(&[15, 0, 0, 0x07, 0xB1, 0]),
            Exception::IllegalDataValue,
            "1969 coils"
        );
        // CPU 226H network 3 (digest 003 §5).
        assert_eq!(
            decode_request(&[0x10, 0x01, 0x19, 0x00, 0x02, 0x04, 0, 0, 0, 1]),
            Ok(Request::WriteMultipleRegisters {
                address: 0x119,
                quantity: 2,
                values: &[0, 0, 0, 1]
            })
        );
        // CPU 226H network 5 as misprinted: quantity 4, byte count 0 → exception 03.
        assert_eq!(
            refused(&[0x10, 0x00, 0x71, 0x00, 0x04, 0x00, 0x00, 0x64, 0x00, 0xC8]),
            Exception::IllegalDataValue
        );
        assert_eq!(
            refused(&[16, 0, 0, 0, 124, 248]),
            Exception::IllegalDataValue,
            "124 registers"
        );
        assert!(decode_request(&[23, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 7]).is_ok());
        assert_eq!(
            refused(&[23, 0, 0, 0, 1, 0, 0, 0, 122, 244]),
            Exception::IllegalDataValue,
            "FC 23 writes at most 121"
        );
    }

    /// The codes the dialects give engine refusals (`mcemu_dialects::modbus`) are exceptions.
    #[test]
    fn the_dialects_exception_codes_are_these_exceptions() {
        use mcemu_dialects::modbus as d;
        for (code, exception) in [
            (d::ILLEGAL_DATA_ADDRESS, Exception::IllegalDataAddress),
            (d::ILLEGAL_DATA_VALUE, Exception::IllegalDataValue),
            (d::SERVER_DEVICE_FAILURE, Exception::ServerDeviceFailure),
            (d::SERVER_DEVICE_BUSY, Exception::ServerDeviceBusy),
        ] {
            assert_eq!(Exception::from_code(code), Some(exception));
        }
    }

    #[test]
    fn unknown_functions_are_exception_01() {
        assert_eq!(
            decode_request(&[0x42, 0, 0]).unwrap_err(),
            Refusal {
                function: 0x42,
                exception: Exception::IllegalFunction
            }
        );
        assert_eq!(
            refused(&[0x2B, 0x0D, 1, 0]),
            Exception::IllegalFunction,
            "MEI 13"
        );
        assert_eq!(refused(&[]), Exception::IllegalFunction);
    }

    #[test]
    fn responses_encode_as_the_specification_shows() {
        let mut out = vec![];
        encode_response(
            &Response::Bits {
                function: 1,
                bits: vec![
                    true, false, true, true, false, false, true, true, true, false,
                ],
            },
            &mut out,
        );
        // Specification §6.1 example: CD 01 for coils 20–29 = 1 0 1 1 0 0 1 1 | 1 0.
        assert_eq!(out, [1, 2, 0xCD, 0x01]);
        out.clear();
        encode_response(
            &Response::exception(3, Exception::IllegalDataAddress),
            &mut out,
        );
        assert_eq!(out, [0x83, 2]);
        out.clear();
        encode_response(
            &Response::Registers {
                function: 3,
                words: vec![0x022B, 0, 0x64],
            },
            &mut out,
        );
        assert_eq!(out, [3, 6, 0x02, 0x2B, 0, 0, 0, 0x64]);
    }
}
