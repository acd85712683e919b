//! Scenarios: scripted, deterministic runs in virtual time (`mcemu scenario FILE`).
