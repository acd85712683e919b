//! `nmc_lib20`: drop-in C library exporting the `NMC_*` API, talking to mcemu (ARCHITECTURE §5).
//! Filled by the NMC issue.
