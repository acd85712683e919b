//! Vendor homing modes mapped onto CiA 402 methods with their quirks.
