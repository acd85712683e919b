//! The handlers, one file per family of the function table, each listing its
//! `(row, handler)` pairs.

use mcemu_nmc::table::Function;

use super::service::Handler;

mod aliases;
mod analog;
mod axis;
mod axis_config;
mod crd;
mod crd_circle;
// Transforms, arc sections, break point, move protection (0x17xx).
mod crd_frames;
mod crd_lookahead;
// Buffered I/O, stops and packs, advanced buffered I/O (0x16xx).
mod adv_buf_io;
mod crd_buf_io;
mod crd_pack;
mod crd_segment;
mod crd_status;
mod device;
mod ecat;
mod ecat_drive;
mod home;
mod io;
mod mv_protect;
// The laser, SHIO and PWM families (stored, echoed on the I/O image).
mod laser;
mod laser_buf;
mod motion;
mod shio;
// The synchronised-motion families.
mod capture;
mod compare;
mod compensation;
mod gang;
mod gear;
mod pt;
mod sync_args;

mod user_para;
// I/O by type, encoders, extension modules, identity (0x12xx).
mod dev_services;
mod encoders;
mod identity;
mod io_extras;
mod io_modules;
mod io_typed;

// The axis-level additions (family 0x13xx).
mod ax_guards;
mod axis_ext;
mod closed_loop;
mod extras;
mod follow;

// The system family (0x18xx): data collection, users, the configuration text.
mod collect;
mod config_file;
mod exe_time;
mod users;

const FAMILIES: [&[(Function, Handler)]; 44] = [
    device::HANDLERS,
    axis::HANDLERS,
    motion::HANDLERS,
    home::HANDLERS,
    io::HANDLERS,
    gear::HANDLERS,
    pt::HANDLERS,
    capture::HANDLERS,
    compare::HANDLERS,
    gang::HANDLERS,
    compensation::HANDLERS,
    crd::HANDLERS,
    crd_segment::HANDLERS,
    crd_status::HANDLERS,
    axis_config::HANDLERS,
    aliases::HANDLERS,
    analog::HANDLERS,
    ecat::HANDLERS,
    user_para::HANDLERS,
    io_typed::HANDLERS,
    io_modules::HANDLERS,
    io_extras::HANDLERS,
    encoders::HANDLERS,
    identity::HANDLERS,
    dev_services::HANDLERS,
    laser::HANDLERS,
    shio::HANDLERS,
    laser_buf::HANDLERS,
    axis_ext::HANDLERS,
    ax_guards::HANDLERS,
    follow::HANDLERS,
    extras::HANDLERS,
    closed_loop::HANDLERS,
    crd_lookahead::HANDLERS,
    crd_circle::HANDLERS,
    collect::HANDLERS,
    users::HANDLERS,
    config_file::HANDLERS,
    exe_time::HANDLERS,
    crd_buf_io::HANDLERS,
    adv_buf_io::HANDLERS,
    crd_pack::HANDLERS,
    crd_frames::HANDLERS,
    mv_protect::HANDLERS,
];

/// The handler of function `id`.
pub fn find(id: u16) -> Option<Handler> {
    FAMILIES
        .iter()
        .flat_map(|f| f.iter())
        .find(|(f, _)| f.id == id)
        .map(|(_, h)| *h)
}

/// The ids that have a handler.
#[cfg(test)]
pub fn served() -> impl Iterator<Item = u16> {
    FAMILIES
        .into_iter()
        .flat_map(|f| f.iter())
        .map(|(f, _)| f.id)
}

#[cfg(test)]
mod tests {
    use mcemu_nmc::table::{Served, FUNCTIONS};

    /// Every row the server serves has exactly one handler, and no handler serves a row the
    /// library answers alone.
    #[test]
    fn every_served_row_has_one_handler() {
        let ids: Vec<u16> = super::served().collect();
        for f in FUNCTIONS {
            let n = ids.iter().filter(|id| **id == f.id).count();
            match f.served {
                Served::Server => assert_eq!(n, 1, "{}", f.name),
                Served::Library => assert_eq!(n, 0, "{}", f.name),
            }
        }
    }
}
