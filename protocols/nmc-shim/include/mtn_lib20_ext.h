/* mtn_lib20_ext.h: mcemu's additions to the NMC_* API.
 * Generated from protocols/nmc/src/table.rs by protocols/nmc/src/header.rs: do not edit. */
#ifndef MTN_LIB20_EXT_H
#define MTN_LIB20_EXT_H

#include "mtn_lib20.h"

#ifdef __cplusplus
extern "C" {
#endif

short NMC_DevClose(PHAND pDevHandle);
short NMC_DevGetConfigText(HAND devHandle, char *pText);
short NMC_DevSetConfigText(HAND devHandle, char *pText);
short NMC_CrdStartExeTimeCalcEx(HAND devHandle);
short NMC_CrdGetExeTimeEx(HAND devHandle, double *pTime);

#ifdef __cplusplus
}
#endif

#endif /* MTN_LIB20_EXT_H */
