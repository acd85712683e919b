//! The CiA 402 drive: controlword/statusword state machine and modes PP, PV, HM, CSP, CSV, CST,
//! bound to an axis of the engine (ARCHITECTURE §3.8).
