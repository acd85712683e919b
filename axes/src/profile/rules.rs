//! Vendor profile rules as options of the generic planner.
