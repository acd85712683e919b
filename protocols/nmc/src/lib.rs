//! NMC wire protocol shared by the server and the `nmc_lib20` shim (ARCHITECTURE §5). Filled by the NMC issue.
