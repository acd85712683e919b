//! Simulated hardware of one axis: pulse output, encoder, plant, switches; and the machine's
//! digital and analog I/O images (ARCHITECTURE §3.3 steps 3–6).
