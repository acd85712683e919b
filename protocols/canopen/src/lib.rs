//! CANopen CiA 301 slave stack with the CiA 402 binding (ARCHITECTURE §5). Filled by the CANopen issue.
