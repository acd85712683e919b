//! Vendor dialects, keyed by vendor and not by wire protocol (ARCHITECTURE §3.4, §5): each
//! module holds one controller family's tables, as pure functions of the engine's
//! vendor-neutral records.
