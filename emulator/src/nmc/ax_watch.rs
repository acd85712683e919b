//! The task that carries out the watchdog and the E-stop inputs (`ax_state`) between requests:
//! while a guard is armed it looks at the engine every millisecond and applies what
//! `AxState::due` returns; unarmed, it looks every 20 ms whether one has been armed. The
//! decisions are the virtual clock's (the snapshot's tick); only the waking is real time.

use std::future::Future;
use std::sync::Arc;
use std::time::Duration;

use axes::status::Snapshot;

use super::ax_state::MoveSettings;
use super::service::{scale_of, NmcService};

/// `MT_JOG_PRF_MODE` (digest 001 §3.2).
const MT_JOG_PRF_MODE: i16 = 1;

/// Each axis's move as a passed PTP compare changes it.
fn moves(service: &NmcService, snapshot: &Snapshot) -> Vec<MoveSettings> {
    let settings = service.settings();
    settings
        .iter()
        .enumerate()
        .map(|(axis, s)| {
            let jog = s.prf_mode == MT_JOG_PRF_MODE;
            MoveSettings {
                jog,
                target: s.target,
                acc: if jog { s.jog.acc } else { s.ptp.acc },
                dec: if jog { s.jog.dec } else { s.ptp.dec },
                scale: scale_of(snapshot, axis),
            }
        })
        .collect()
}

const ARMED: Duration = Duration::from_millis(1);
const IDLE: Duration = Duration::from_millis(20);

/// Run until `stop` resolves.
pub async fn watch(service: Arc<NmcService>, stop: impl Future<Output = ()>) {
    tokio::pin!(stop);
    loop {
        let armed = service.ax().armed();
        tokio::select! {
            () = &mut stop => return,
            () = tokio::time::sleep(if armed { ARMED } else { IDLE }) => {}
        }
        if !armed {
            continue;
        }
        let snapshot = service.engine.snapshot();
        let moves = moves(&service, &snapshot);
        let commands = service.ax().due(&snapshot, &moves);
        if !commands.is_empty() {
            // A refusal (an axis already stopped, disabled) changes nothing the next look
            // would not see again.
            let _ = service.engine.call_batch_async(commands).await;
        }
    }
}
