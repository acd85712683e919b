//! The four Modbus data tables and the data function codes over them (Modbus Application
//! Protocol V1.1b3 §6.1–§6.6, §6.11, §6.12, §6.16, §6.17), once for every data model: a model
//! says how to read and write words of a table ([`TableAccess`]); [`execute`] turns a request
//! into those reads and writes and builds the response.

use std::future::Future;

use serde::Deserialize;

use crate::model::ExecError;
use crate::pdu::{fc, Exception, Request, Response};

/// The four Modbus data tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Table {
    Coils,
    DiscreteInputs,
    InputRegisters,
    HoldingRegisters,
}

impl Table {
    /// Bit tables hold one bool per address.
    pub fn is_bits(self) -> bool {
        matches!(self, Table::Coils | Table::DiscreteInputs)
    }

    /// Whether Modbus lets a client write the table at all.
    pub fn is_writable(self) -> bool {
        matches!(self, Table::Coils | Table::HoldingRegisters)
    }

    pub fn name(self) -> &'static str {
        match self {
            Table::Coils => "coils",
            Table::DiscreteInputs => "discrete_inputs",
            Table::InputRegisters => "input_registers",
            Table::HoldingRegisters => "holding_registers",
        }
    }
}

/// Word access to a model's tables; a bit is the word 0 or 1. Errors carry the exception
/// (02 for an address the model does not have, 03/04 for a value or a refusal).
pub trait TableAccess: Sync {
    /// `count` words from `address`.
    fn read(&self, table: Table, address: u16, count: u16) -> Result<Vec<u16>, ExecError>;

    /// Whether a read of `count` words from `address` would be served (FC 23 checks its read
    /// range before it writes).
    fn check_read(&self, table: Table, address: u16, count: u16) -> Result<(), ExecError>;

    /// Write `words` from `address`; checked as a whole before any of it happens.
    fn write(
        &self,
        table: Table,
        address: u16,
        words: &[u16],
    ) -> impl Future<Output = Result<(), ExecError>> + Send;
}

/// Execute a data request (FC 1–6, 15, 16, 22, 23) on `model`; other requests are the server's
/// own business and get exception 01 here.
pub async fn execute<M: TableAccess>(
    model: &M,
    request: &Request<'_>,
) -> Result<Response, ExecError> {
    let registers = |function, words| Response::Registers { function, words };
    let bits = |function, words: Vec<u16>| Response::Bits {
        function,
        bits: words.into_iter().map(|w| w != 0).collect(),
    };
    match *request {
        Request::ReadCoils { address, quantity } => Ok(bits(
            fc::READ_COILS,
            model.read(Table::Coils, address, quantity)?,
        )),
        Request::ReadDiscreteInputs { address, quantity } => Ok(bits(
            fc::READ_DISCRETE_INPUTS,
            model.read(Table::DiscreteInputs, address, quantity)?,
        )),
        Request::ReadHoldingRegisters { address, quantity } => Ok(registers(
            fc::READ_HOLDING_REGISTERS,
            model.read(Table::HoldingRegisters, address, quantity)?,
        )),
        Request::ReadInputRegisters { address, quantity } => Ok(registers(
            fc::READ_INPUT_REGISTERS,
            model.read(Table::InputRegisters, address, quantity)?,
        )),
        Request::WriteSingleCoil { address, value } => {
            model
                .write(Table::Coils, address, &[u16::from(value)])
                .await?;
            Ok(Response::WriteSingle {
                function: fc::WRITE_SINGLE_COIL,
                address,
                value: if value { 0xFF00 } else { 0 },
            })
        }
        Request::WriteSingleRegister { address, value } => {
            model
                .write(Table::HoldingRegisters, address, &[value])
                .await?;
            Ok(Response::WriteSingle {
                function: fc::WRITE_SINGLE_REGISTER,
                address,
                value,
            })
        }
        Request::WriteMultipleCoils {
            address,
            quantity,
            values,
        } => {
            model
                .write(Table::Coils, address, &unpack_bits(values, quantity))
                .await?;
            Ok(Response::WriteMultiple {
                function: fc::WRITE_MULTIPLE_COILS,
                address,
                quantity,
            })
        }
        Request::WriteMultipleRegisters {
            address,
            quantity,
            values,
        } => {
            model
                .write(Table::HoldingRegisters, address, &be_words(values))
                .await?;
            Ok(Response::WriteMultiple {
                function: fc::WRITE_MULTIPLE_REGISTERS,
                address,
                quantity,
            })
        }
        Request::MaskWriteRegister {
            address,
            and_mask,
            or_mask,
        } => {
            // §6.16: result = (current AND and_mask) OR (or_mask AND NOT and_mask).
            let current = model.read(Table::HoldingRegisters, address, 1)?;
            let value = (current[0] & and_mask) | (or_mask & !and_mask);
            model
                .write(Table::HoldingRegisters, address, &[value])
                .await?;
            Ok(Response::MaskWrite {
                address,
                and_mask,
                or_mask,
            })
        }
        Request::ReadWriteMultipleRegisters {
            read_address,
            read_quantity,
            write_address,
            values,
            ..
        } => {
            // §6.17: the write is performed before the read; both ranges are checked before
            // either happens.
            model.check_read(Table::HoldingRegisters, read_address, read_quantity)?;
            model
                .write(Table::HoldingRegisters, write_address, &be_words(values))
                .await?;
            Ok(registers(
                fc::READ_WRITE_MULTIPLE_REGISTERS,
                model.read(Table::HoldingRegisters, read_address, read_quantity)?,
            ))
        }
        // The server answers these itself.
        Request::Diagnostics { .. }
        | Request::ReportServerId
        | Request::ReadDeviceIdentification { .. } => Err(ExecError::new(
            Exception::IllegalFunction,
            "not a data request",
        )),
    }
}

/// Coil values packed LSB first (§6.11), as words 0/1.
fn unpack_bits(bytes: &[u8], count: u16) -> Vec<u16> {
    (0..usize::from(count))
        .map(|i| u16::from(bytes.get(i / 8).is_some_and(|b| b >> (i % 8) & 1 == 1)))
        .collect()
}

/// Register values as sent: big-endian words.
fn be_words(bytes: &[u8]) -> Vec<u16> {
    bytes
        .chunks_exact(2)
        .map(|c| u16::from_be_bytes([c[0], c[1]]))
        .collect()
}
