//! The servo runtime (ARCHITECTURE §4): servo thread, bounded command queue with one-shot
//! replies, lock-free snapshots, and the realtime, virtual and scaled clocks.
