//! The task that carries out the watchdog and the E-stop inputs (`ax_state`) between requests:
//! while a guard is armed it looks at the engine every millisecond and applies what
//! `AxState::due` returns; unarmed, it looks every 20 ms whether one has been armed. The
//! decisions are the virtual clock's (the snapshot's tick); only the waking is real time.

use std::future::Future;
use std::sync::Arc;
use std::time::Duration;

use super::service::NmcService;

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
        let settings = service.settings().clone();
        let commands = service.ax().due(&snapshot, &settings);
        if !commands.is_empty() {
            // A refusal (an axis already stopped, disabled) changes nothing the next look
            // would not see again.
            let _ = service.engine.call_batch_async(commands).await;
        }
    }
}
