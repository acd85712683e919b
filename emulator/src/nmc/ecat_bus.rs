//! The EtherCAT bus of an `ecat` card (digest 001 §2.1, C5§4(1)): which engine axes the NMC axis
//! numbers name, and what a drive's homing started by the front-end is waiting for.
//!
//! The bus drives are the machine's `[[drives]]` with `master = "engine"` in config order: drive
//! k is NMC axis 16 + k ("第一个驱动器(从站)轴序号从 16 开始 … 中间存在 IO 模块则不算在内") and
//! SDO slave `devId` k. The card's own (local) axes 0, 1, … are the engine axes no bus drive
//! moves, in order, at most 16. A card of another kind has no bus: every engine axis is local,
//! numbered as in the engine. Functions that take axis *numbers* as arguments (gear masters,
//! coordinate-system maps, packs, dedicated-input indices, encoder and collection indices)
//! read them as these NMC numbers through this map (`handlers::sync_args`; docs/decisions.md
//! "NMC EtherCAT bus axes").

use std::sync::{Mutex, MutexGuard, PoisonError};

use axes::cia402::{DriveConfig, DriveMaster};

use super::config::DeviceKind;

/// NMC axis number of the first bus drive.
pub const BUS_AXIS_FIRST: u8 = 16;

/// One drive on the bus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BusDrive {
    /// The engine's slave number (its place in `[[drives]]`).
    pub slave: u16,
    /// The engine axis it moves.
    pub axis: usize,
    /// Drive increments per axis user unit (pulses are user units on the NMC fixtures).
    pub increments_per_unit: f64,
}

/// The bus as the NMC front-end presents it.
#[derive(Debug, Default)]
pub struct EcatBus {
    drives: Vec<BusDrive>,
    io_slaves: u16,
    /// By bus drive: the engine tick at which the front-end last started its homing, until the
    /// drive has stepped since (`NMC_EcatGetHomeSts` reads "in progress" meanwhile: the drive
    /// starts homing in the tick after the request, digest 001 §3.14).
    homing_requested: Mutex<Vec<Option<u64>>>,
}

impl EcatBus {
    /// The bus of a card of `kind` on a machine with `drives`, with `io_slaves` I/O slaves.
    pub fn new(kind: DeviceKind, drives: &[DriveConfig], io_slaves: u16) -> EcatBus {
        if kind != DeviceKind::Ecat {
            return EcatBus::default();
        }
        let drives: Vec<BusDrive> = drives
            .iter()
            .enumerate()
            .filter(|(_, d)| d.master == DriveMaster::Engine)
            .filter_map(|(slave, d)| {
                Some(BusDrive {
                    slave: u16::try_from(slave).ok()?,
                    axis: usize::from(d.axis),
                    increments_per_unit: d.increments_per_unit,
                })
            })
            // Axis numbers 16 … 255 fit a handle's item.
            .take(usize::from(u8::MAX - BUS_AXIS_FIRST) + 1)
            .collect();
        EcatBus {
            homing_requested: Mutex::new(vec![None; drives.len()]),
            drives,
            io_slaves,
        }
    }

    pub fn drives(&self) -> &[BusDrive] {
        &self.drives
    }

    pub fn io_slaves(&self) -> u16 {
        self.io_slaves
    }

    /// Bus drive `k` (NMC axis 16 + k, SDO devId k).
    pub fn drive(&self, k: usize) -> Option<BusDrive> {
        self.drives.get(k).copied()
    }

    /// The bus drive moving engine axis `axis`: its place k on the bus and the drive.
    pub fn drive_of_axis(&self, axis: usize) -> Option<(usize, BusDrive)> {
        self.drives
            .iter()
            .enumerate()
            .find(|(_, d)| d.axis == axis)
            .map(|(k, d)| (k, *d))
    }

    /// The engine axes of the card's local axes 0, 1, … (of `engine_axes` in all).
    fn local_axes(&self, engine_axes: usize) -> impl Iterator<Item = usize> + '_ {
        let cap = if self.drives.is_empty() {
            usize::MAX
        } else {
            usize::from(BUS_AXIS_FIRST)
        };
        (0..engine_axes)
            .filter(|a| self.drive_of_axis(*a).is_none())
            .take(cap)
    }

    /// How many local axes the card has.
    pub fn local_count(&self, engine_axes: usize) -> usize {
        self.local_axes(engine_axes).count()
    }

    /// The engine axis NMC axis number `item` names (local, or bus from 16), if it exists.
    pub fn engine_axis(&self, item: u8, engine_axes: usize) -> Option<usize> {
        if !self.drives.is_empty() && item >= BUS_AXIS_FIRST {
            let d = self.drive(usize::from(item - BUS_AXIS_FIRST))?;
            return (d.axis < engine_axes).then_some(d.axis);
        }
        self.local_axes(engine_axes).nth(usize::from(item))
    }

    /// The NMC axis number of engine axis `axis` (the inverse of [`EcatBus::engine_axis`]).
    pub fn nmc_number(&self, axis: usize, engine_axes: usize) -> Option<u8> {
        if let Some((k, _)) = self.drive_of_axis(axis) {
            return u8::try_from(usize::from(BUS_AXIS_FIRST) + k).ok();
        }
        let place = self.local_axes(engine_axes).position(|a| a == axis)?;
        u8::try_from(place).ok()
    }

    /// The NMC axis numbers that exist, for range refusals: "[0, L−1]" and, with bus drives,
    /// "or [16, 15+D] (the bus drives)".
    pub fn numbers_text(&self, engine_axes: usize) -> String {
        let local = format!("[0, {}]", self.local_count(engine_axes).saturating_sub(1));
        match self.drives.len() {
            0 => local,
            d => format!(
                "{local} or [{BUS_AXIS_FIRST}, {}] (the bus drives)",
                usize::from(BUS_AXIS_FIRST) + d - 1
            ),
        }
    }

    fn requested(&self) -> MutexGuard<'_, Vec<Option<u64>>> {
        self.homing_requested
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// The front-end started bus drive `k`'s homing; the engine's snapshot was at `tick` after.
    pub fn homing_requested(&self, k: usize, tick: Option<u64>) {
        if let Some(r) = self.requested().get_mut(k) {
            *r = tick;
        }
    }

    /// Whether bus drive `k`'s homing was requested and the drive has not stepped since, as of
    /// a snapshot at `tick`.
    pub fn homing_pending(&self, k: usize, tick: u64) -> bool {
        let mut requested = self.requested();
        let Some(r) = requested.get_mut(k) else {
            return false;
        };
        match *r {
            Some(at) if tick <= at => true,
            _ => {
                *r = None;
                false
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn drive(axis: u16, master: DriveMaster) -> DriveConfig {
        DriveConfig {
            axis,
            master,
            ..DriveConfig::default()
        }
    }

    /// TV34: 4 local axes then two bus drives on engine axes 4 and 5 → 0 … 3, 16, 17.
    #[test]
    fn bus_drives_are_numbered_from_16_and_local_axes_skip_them() {
        let drives = [
            drive(4, DriveMaster::Engine),
            drive(1, DriveMaster::External),
            drive(5, DriveMaster::Engine),
        ];
        let bus = EcatBus::new(DeviceKind::Ecat, &drives, 1);
        assert_eq!(bus.drives().len(), 2);
        assert_eq!(bus.drive(1).map(|d| (d.slave, d.axis)), Some((2, 5)));
        assert_eq!(bus.local_count(6), 4);
        assert_eq!(bus.engine_axis(3, 6), Some(3));
        assert_eq!(bus.engine_axis(4, 6), None);
        assert_eq!(bus.engine_axis(16, 6), Some(4));
        assert_eq!(bus.engine_axis(17, 6), Some(5));
        assert_eq!(bus.engine_axis(18, 6), None);
        assert_eq!(bus.drive_of_axis(5).map(|(k, _)| k), Some(1));
        // Another kind of card: no bus, engine numbering.
        let pulse = EcatBus::new(DeviceKind::Network, &drives, 1);
        assert_eq!(pulse.engine_axis(4, 6), Some(4));
        assert_eq!(pulse.engine_axis(16, 6), None);
    }

    #[test]
    fn a_requested_homing_is_pending_until_a_later_tick() {
        let bus = EcatBus::new(DeviceKind::Ecat, &[drive(0, DriveMaster::Engine)], 0);
        assert!(!bus.homing_pending(0, 10));
        bus.homing_requested(0, Some(10));
        assert!(bus.homing_pending(0, 10));
        assert!(!bus.homing_pending(0, 11));
        assert!(!bus.homing_pending(0, 10), "cleared once seen");
    }
}
