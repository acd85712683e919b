"""Drive mcemu's libnmc_lib20.so through ctypes: open, servo on, PTP to 5000, read back.

    MCEMU_NMC=127.0.0.1:7700 python nmc_ctypes.py target/release/libnmc_lib20.so
"""

import ctypes
import sys

lib = ctypes.CDLL(sys.argv[1])
HAND = ctypes.c_ushort
for name in ("NMC_DevOpen", "NMC_MtOpen", "NMC_MtSetSvOn", "NMC_MtMovePtpAbs",
             "NMC_MtGetSts", "NMC_MtGetPrfPos"):
    getattr(lib, name).restype = ctypes.c_short
lib.NMC_MtMovePtpAbs.argtypes = [HAND] + [ctypes.c_double] * 5 + [ctypes.c_short, ctypes.c_long]

dev, ax = HAND(), HAND()
assert lib.NMC_DevOpen(0, ctypes.byref(dev)) == 0
assert lib.NMC_MtOpen(dev, 3, ctypes.byref(ax)) == 0
assert lib.NMC_MtSetSvOn(ax) == 0
assert lib.NMC_MtMovePtpAbs(ax, 0.5, 0.5, 0, 0, 10, 0, 5000) == 0
sts = ctypes.c_short()
while True:
    assert lib.NMC_MtGetSts(ax, ctypes.byref(sts)) == 0
    if not sts.value & 0x1:
        break
pos = ctypes.c_long()
assert lib.NMC_MtGetPrfPos(ax, ctypes.byref(pos)) == 0
print(f"prfPos {pos.value}")
