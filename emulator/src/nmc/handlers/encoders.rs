//! Encoder channels by number (digest 001 §2.4, §2.20): an axis's encoder by its NMC number
//! (local axes from 0, an `ecat` card's bus drives from 16, `ecat_bus`), 256 and 257 the
//! external encoders (the handwheel inputs that `handwheel_turn` turns).

use axes::command::{HandwheelTurn, HANDWHEEL_EXTERNAL_BASE};
use mcemu_nmc::table::{self, Function};

use super::axis_ext::set_enc_reading;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::GET_ENC_POS, get_enc_pos),
    (table::GET_ENC_VEL, get_enc_vel),
    (table::SET_ENC_POS, set_enc_pos),
];

/// An encoder channel.
enum Channel {
    Axis(usize),
    /// Index into `Snapshot::external_encoders`.
    External(usize),
}

fn channel(c: &Call<'_>, enc_id: i16) -> Result<Channel, Refusal> {
    let axes = c.snapshot.axes.len();
    let bus = c.service.bus();
    let external = c.snapshot.external_encoders.len();
    let base = usize::from(HANDWHEEL_EXTERNAL_BASE);
    let axis = u8::try_from(enc_id)
        .ok()
        .and_then(|n| bus.engine_axis(n, axes));
    match (axis, usize::try_from(enc_id)) {
        (Some(a), _) => Ok(Channel::Axis(a)),
        (None, Ok(e)) if e >= base && e < base + external => Ok(Channel::External(e - base)),
        _ => Err(Refusal::range(
            "encId",
            enc_id,
            &format!(
                "{} (an axis's encoder) or {HANDWHEEL_EXTERNAL_BASE} … {}",
                bus.numbers_text(axes),
                (base + external).saturating_sub(1)
            ),
        )),
    }
}

/// An axis's encoder reads as `NMC_MtGetEncPos` reads it: one counter, two ways to name it.
fn get_enc_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let enc_id = c.input.i16()?;
    let p = match channel(c, enc_id)? {
        Channel::Axis(a) => c.status(a).map_or(0, |s| c.service.ax().enc_pos(a, s)),
        Channel::External(e) => c.snapshot.external_encoders.get(e).copied().unwrap_or(0),
    };
    c.output.i64(p);
    Ok(())
}

/// pulse/ms. `encId` is an `unsigned char` as the manual writes it: axis encoders only.
fn get_enc_vel(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let enc_id = c.input.u8()?;
    let v = match channel(c, i16::from(enc_id))? {
        Channel::Axis(a) => c.status(a).map_or(0.0, |s| {
            mcemu_dialects::nmc::velocity_from_engine(c.scale(a), s.act_vel)
        }),
        Channel::External(_) => 0.0,
    };
    c.output.f64(v);
    Ok(())
}

/// An axis's encoder: its reading is set, as `NMC_MtSetEncPos` sets it (the plan and the
/// engine's actual position stay; the manual does not restrict this one to a still axis); an
/// external encoder's count is turned to `encPos`.
fn set_enc_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (enc_id, pos) = (c.input.i16()?, c.input.i64()?);
    match channel(c, enc_id)? {
        Channel::Axis(a) => set_enc_reading(c, a, pos),
        Channel::External(e) => {
            let now = c.snapshot.external_encoders.get(e).copied().unwrap_or(0);
            c.command(HandwheelTurn {
                input: HANDWHEEL_EXTERNAL_BASE + e as u16,
                counts: pos.wrapping_sub(now),
            });
        }
    }
    Ok(())
}
