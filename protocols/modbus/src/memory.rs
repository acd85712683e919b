//! [`MemoryModel`]: a [`DataModel`] over four plain tables, for tests and benchmarks. Every
//! served unit sees the same tables.

use std::future::Future;
use std::ops::Range;
use std::sync::{Mutex, MutexGuard};

use crate::model::{DataModel, DeviceIdentity, ExecError, RequestContext};
use crate::pdu::{fc, Exception, Request, Response};

/// The four Modbus tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Table {
    Coils,
    DiscreteInputs,
    InputRegisters,
    HoldingRegisters,
}

/// Addresses `start .. start + len` of one table.
#[derive(Clone, Debug)]
struct Area<T> {
    start: u16,
    values: Vec<T>,
}

impl<T: Copy + Default> Area<T> {
    fn new(start: u16, count: u32) -> Area<T> {
        // The address space ends at 0xFFFF.
        let count = count.min(0x1_0000 - u32::from(start)) as usize;
        Area {
            start,
            values: vec![T::default(); count],
        }
    }

    /// The indices of `quantity` points from `address`, or exception 02.
    fn range(&self, what: &str, address: u16, quantity: u16) -> Result<Range<usize>, ExecError> {
        let first = usize::from(address).checked_sub(usize::from(self.start));
        match first {
            Some(i) if i + usize::from(quantity) <= self.values.len() => {
                Ok(i..i + usize::from(quantity))
            }
            _ => Err(ExecError::new(
                Exception::IllegalDataAddress,
                format!(
                    "{what} {address}..{} outside {}..{}",
                    u32::from(address) + u32::from(quantity),
                    self.start,
                    usize::from(self.start) + self.values.len()
                ),
            )),
        }
    }
}

#[derive(Debug)]
struct Tables {
    coils: Area<bool>,
    discrete_inputs: Area<bool>,
    input_registers: Area<u16>,
    holding_registers: Area<u16>,
}

/// Plain in-memory Modbus data.
#[derive(Debug)]
pub struct MemoryModel {
    /// `None`: every unit.
    units: Option<[bool; 256]>,
    identity: DeviceIdentity,
    tables: Mutex<Tables>,
}

impl Default for MemoryModel {
    fn default() -> Self {
        MemoryModel::new()
    }
}

impl MemoryModel {
    /// Every unit; each table covers the whole address space 0–65535.
    pub fn new() -> MemoryModel {
        MemoryModel {
            units: None,
            identity: DeviceIdentity {
                server_id: b"mcemu".to_vec(),
                vendor_name: "mcemu".into(),
                product_code: "MemoryModel".into(),
                revision: env!("CARGO_PKG_VERSION").into(),
                ..DeviceIdentity::default()
            },
            tables: Mutex::new(Tables {
                coils: Area::new(0, 0x1_0000),
                discrete_inputs: Area::new(0, 0x1_0000),
                input_registers: Area::new(0, 0x1_0000),
                holding_registers: Area::new(0, 0x1_0000),
            }),
        }
    }

    /// Serve only these units.
    pub fn with_units(mut self, units: impl IntoIterator<Item = u8>) -> MemoryModel {
        let mut set = [false; 256];
        for u in units {
            set[usize::from(u)] = true;
        }
        self.units = Some(set);
        self
    }

    /// Give `table` the addresses `start .. start + count` (zeroed).
    pub fn with_range(self, table: Table, start: u16, count: u32) -> MemoryModel {
        {
            let mut t = self.lock();
            match table {
                Table::Coils => t.coils = Area::new(start, count),
                Table::DiscreteInputs => t.discrete_inputs = Area::new(start, count),
                Table::InputRegisters => t.input_registers = Area::new(start, count),
                Table::HoldingRegisters => t.holding_registers = Area::new(start, count),
            }
        }
        self
    }

    pub fn with_identity(mut self, identity: DeviceIdentity) -> MemoryModel {
        self.identity = identity;
        self
    }

    fn lock(&self) -> MutexGuard<'_, Tables> {
        // Every write completes before the guard drops; a poisoned lock holds whole values.
        self.tables.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A register of `table` (input or holding), if in range.
    pub fn register(&self, table: Table, address: u16) -> Option<u16> {
        let t = self.lock();
        let area = match table {
            Table::InputRegisters => &t.input_registers,
            Table::HoldingRegisters => &t.holding_registers,
            _ => return None,
        };
        let i = area.range("", address, 1).ok()?.start;
        area.values.get(i).copied()
    }

    /// Set a register of `table` (input or holding); false when out of range.
    pub fn set_register(&self, table: Table, address: u16, value: u16) -> bool {
        let mut t = self.lock();
        let area = match table {
            Table::InputRegisters => &mut t.input_registers,
            Table::HoldingRegisters => &mut t.holding_registers,
            _ => return false,
        };
        match area.range("", address, 1) {
            Ok(r) => area.values.get_mut(r.start).map(|v| *v = value).is_some(),
            Err(_) => false,
        }
    }

    /// A bit of `table` (coils or discrete inputs), if in range.
    pub fn bit(&self, table: Table, address: u16) -> Option<bool> {
        let t = self.lock();
        let area = match table {
            Table::Coils => &t.coils,
            Table::DiscreteInputs => &t.discrete_inputs,
            _ => return None,
        };
        let i = area.range("", address, 1).ok()?.start;
        area.values.get(i).copied()
    }

    /// Set a bit of `table` (coils or discrete inputs); false when out of range.
    pub fn set_bit(&self, table: Table, address: u16, value: bool) -> bool {
        let mut t = self.lock();
        let area = match table {
            Table::Coils => &mut t.coils,
            Table::DiscreteInputs => &mut t.discrete_inputs,
            _ => return false,
        };
        match area.range("", address, 1) {
            Ok(r) => area.values.get_mut(r.start).map(|v| *v = value).is_some(),
            Err(_) => false,
        }
    }

    fn execute_now(&self, request: &Request<'_>) -> Result<Response, ExecError> {
        let mut t = self.lock();
        let words = |bytes: &[u8]| -> Vec<u16> {
            bytes
                .chunks_exact(2)
                .map(|w| u16::from_be_bytes([w[0], w[1]]))
                .collect()
        };
        match *request {
            Request::ReadCoils { address, quantity } => {
                let r = t.coils.range("coils", address, quantity)?;
                Ok(Response::Bits {
                    function: fc::READ_COILS,
                    bits: t.coils.values[r].to_vec(),
                })
            }
            Request::ReadDiscreteInputs { address, quantity } => {
                let r = t
                    .discrete_inputs
                    .range("discrete inputs", address, quantity)?;
                Ok(Response::Bits {
                    function: fc::READ_DISCRETE_INPUTS,
                    bits: t.discrete_inputs.values[r].to_vec(),
                })
            }
            Request::ReadHoldingRegisters { address, quantity } => {
                let r = t
                    .holding_registers
                    .range("holding registers", address, quantity)?;
                Ok(Response::Registers {
                    function: fc::READ_HOLDING_REGISTERS,
                    words: t.holding_registers.values[r].to_vec(),
                })
            }
            Request::ReadInputRegisters { address, quantity } => {
                let r = t
                    .input_registers
                    .range("input registers", address, quantity)?;
                Ok(Response::Registers {
                    function: fc::READ_INPUT_REGISTERS,
                    words: t.input_registers.values[r].to_vec(),
                })
            }
            Request::WriteSingleCoil { address, value } => {
                let r = t.coils.range("coils", address, 1)?;
                t.coils.values[r].fill(value);
                Ok(Response::WriteSingle {
                    function: fc::WRITE_SINGLE_COIL,
                    address,
                    value: if value { 0xFF00 } else { 0 },
                })
            }
            Request::WriteSingleRegister { address, value } => {
                let r = t.holding_registers.range("holding registers", address, 1)?;
                t.holding_registers.values[r].fill(value);
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
                let r = t.coils.range("coils", address, quantity)?;
                for (k, slot) in t.coils.values[r].iter_mut().enumerate() {
                    // Packed LSB first (§6.11).
                    *slot = values.get(k / 8).is_some_and(|b| b & (1 << (k % 8)) != 0);
                }
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
                let r = t
                    .holding_registers
                    .range("holding registers", address, quantity)?;
                for (slot, w) in t.holding_registers.values[r].iter_mut().zip(words(values)) {
                    *slot = w;
                }
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
                let r = t.holding_registers.range("holding registers", address, 1)?;
                for v in &mut t.holding_registers.values[r] {
                    // §6.16: (current AND and_mask) OR (or_mask AND NOT and_mask).
                    *v = (*v & and_mask) | (or_mask & !and_mask);
                }
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
                write_quantity,
                values,
            } => {
                let hr = &mut t.holding_registers;
                // Both ranges are checked before anything is written.
                let w = hr.range("holding registers", write_address, write_quantity)?;
                let r = hr.range("holding registers", read_address, read_quantity)?;
                // §6.17: the write is performed before the read.
                for (slot, v) in hr.values[w].iter_mut().zip(words(values)) {
                    *slot = v;
                }
                Ok(Response::Registers {
                    function: fc::READ_WRITE_MULTIPLE_REGISTERS,
                    words: hr.values[r].to_vec(),
                })
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
}

impl DataModel for MemoryModel {
    fn serves(&self, unit: u8) -> bool {
        self.units.is_none_or(|set| set[usize::from(unit)])
    }

    fn identity(&self, _unit: u8) -> Option<&DeviceIdentity> {
        Some(&self.identity)
    }

    fn execute<'a>(
        &'a self,
        _context: &'a RequestContext,
        request: &'a Request<'a>,
    ) -> impl Future<Output = Result<Response, ExecError>> + Send + 'a {
        std::future::ready(self.execute_now(request))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(m: &MemoryModel, r: Request<'_>) -> Result<Response, Exception> {
        m.execute_now(&r).map_err(|e| e.exception)
    }

    #[test]
    fn ranges_writes_and_read_write_order() {
        let m = MemoryModel::new().with_range(Table::HoldingRegisters, 100, 10);
        let read = |address, quantity| Request::ReadHoldingRegisters { address, quantity };
        assert!(run(&m, read(100, 10)).is_ok());
        assert_eq!(run(&m, read(99, 1)), Err(Exception::IllegalDataAddress));
        assert_eq!(run(&m, read(109, 2)), Err(Exception::IllegalDataAddress));
        assert_eq!(run(&m, read(0xFFFF, 1)), Err(Exception::IllegalDataAddress));
        m.set_register(Table::HoldingRegisters, 104, 0x0012);
        // §6.16 example: 0x12 with AND 0xF2, OR 0x25 gives 0x17.
        assert!(run(
            &m,
            Request::MaskWriteRegister {
                address: 104,
                and_mask: 0xF2,
                or_mask: 0x25
            }
        )
        .is_ok());
        assert_eq!(m.register(Table::HoldingRegisters, 104), Some(0x17));
        // FC 23 reads what it has just written.
        assert_eq!(
            run(
                &m,
                Request::ReadWriteMultipleRegisters {
                    read_address: 104,
                    read_quantity: 2,
                    write_address: 105,
                    write_quantity: 1,
                    values: &[0xAB, 0xCD]
                }
            ),
            Ok(Response::Registers {
                function: 23,
                words: vec![0x17, 0xABCD]
            })
        );
        // A refused FC 23 writes nothing.
        assert_eq!(
            run(
                &m,
                Request::ReadWriteMultipleRegisters {
                    read_address: 200,
                    read_quantity: 1,
                    write_address: 100,
                    write_quantity: 1,
                    values: &[0xFF, 0xFF]
                }
            ),
            Err(Exception::IllegalDataAddress)
        );
        assert_eq!(m.register(Table::HoldingRegisters, 100), Some(0));
    }

    #[test]
    fn coils_pack_lsb_first() {
        let m = MemoryModel::new();
        assert!(run(
            &m,
            Request::WriteMultipleCoils {
                address: 19,
                quantity: 10,
                values: &[0xCD, 0x01]
            }
        )
        .is_ok());
        let bits: Vec<bool> = (19..29).filter_map(|a| m.bit(Table::Coils, a)).collect();
        assert_eq!(
            bits,
            [true, false, true, true, false, false, true, true, true, false]
        );
        assert!(!MemoryModel::new().with_units([1, 2]).serves(3));
        assert!(MemoryModel::new().serves(0xFF));
    }
}
