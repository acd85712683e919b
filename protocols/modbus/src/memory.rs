//! [`MemoryModel`]: a [`DataModel`] over four plain tables, for tests and benchmarks. Every
//! served unit sees the same tables.

use std::future::Future;
use std::ops::Range;
use std::sync::{Mutex, MutexGuard};

use crate::model::{DataModel, DeviceIdentity, ExecError, RequestContext};
use crate::pdu::{Exception, Request, Response};
use crate::tables::{self, TableAccess};

pub use crate::tables::Table;

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
}

impl TableAccess for MemoryModel {
    fn read(&self, table: Table, address: u16, count: u16) -> Result<Vec<u16>, ExecError> {
        let t = self.lock();
        let name = table.name();
        Ok(match table {
            Table::Coils => bits(&t.coils, name, address, count)?,
            Table::DiscreteInputs => bits(&t.discrete_inputs, name, address, count)?,
            Table::InputRegisters => {
                let r = t.input_registers.range(name, address, count)?;
                t.input_registers.values[r].to_vec()
            }
            Table::HoldingRegisters => {
                let r = t.holding_registers.range(name, address, count)?;
                t.holding_registers.values[r].to_vec()
            }
        })
    }

    fn check_read(&self, table: Table, address: u16, count: u16) -> Result<(), ExecError> {
        let t = self.lock();
        let name = table.name();
        match table {
            Table::Coils => t.coils.range(name, address, count).map(drop),
            Table::DiscreteInputs => t.discrete_inputs.range(name, address, count).map(drop),
            Table::InputRegisters => t.input_registers.range(name, address, count).map(drop),
            Table::HoldingRegisters => t.holding_registers.range(name, address, count).map(drop),
        }
    }

    fn write(
        &self,
        table: Table,
        address: u16,
        words: &[u16],
    ) -> impl Future<Output = Result<(), ExecError>> + Send {
        let mut t = self.lock();
        let name = table.name();
        let count = u16::try_from(words.len()).unwrap_or(u16::MAX);
        let written = match table {
            Table::Coils | Table::DiscreteInputs => {
                let area = if table == Table::Coils {
                    &mut t.coils
                } else {
                    &mut t.discrete_inputs
                };
                area.range(name, address, count).map(|r| {
                    for (slot, w) in area.values[r].iter_mut().zip(words) {
                        *slot = *w != 0;
                    }
                })
            }
            Table::InputRegisters | Table::HoldingRegisters => {
                let area = if table == Table::HoldingRegisters {
                    &mut t.holding_registers
                } else {
                    &mut t.input_registers
                };
                area.range(name, address, count)
                    .map(|r| area.values[r].copy_from_slice(words))
            }
        };
        std::future::ready(written)
    }
}

fn bits(area: &Area<bool>, name: &str, address: u16, count: u16) -> Result<Vec<u16>, ExecError> {
    let r = area.range(name, address, count)?;
    Ok(area.values[r].iter().map(|&b| u16::from(b)).collect())
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
        tables::execute(self, request)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(m: &MemoryModel, r: Request<'_>) -> Result<Response, Exception> {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .build()
            .map_err(|_| Exception::ServerDeviceFailure)?;
        runtime
            .block_on(tables::execute(m, &r))
            .map_err(|e| e.exception)
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
