/* mtn_lib20_err.h: the return codes of mcemu's nmc_lib20 (not in the manual: mcemu's,
 * stable). Generated from protocols/nmc/src/errors.rs: do not edit. */
#ifndef MTN_LIB20_ERR_H
#define MTN_LIB20_ERR_H

#define RTN_CMD_SUCCESS (0)
#define RTN_COMM_ERROR (-1) /* communication error: no reply within the timeout (NMC_SetCommPara) or the connection is lost */
#define RTN_INVALID_AXIS (1) /* no such axis */
#define RTN_UNKNOWN_PARAMETER (2) /* no such parameter */
#define RTN_INVALID_PARAMETER (3) /* parameter value out of range */
#define RTN_READ_ONLY_PARAMETER (4) /* the parameter is read-only */
#define RTN_INVALID_ARGUMENT (5) /* argument out of range */
#define RTN_AXIS_DISABLED (6) /* the axis is not enabled (servo off) */
#define RTN_AXIS_IN_ERROR (7) /* the axis has a latched error: NMC_MtClrError first */
#define RTN_LIMIT_ACTIVE (8) /* a limit blocks motion in this direction */
#define RTN_QUEUE_FULL (9) /* the command queue is full */
#define RTN_UNSUPPORTED (10) /* not supported by this axis or device */
#define RTN_INVALID_STATE (11) /* not allowed in the axis's present state */
#define RTN_CAUSE_STILL_PRESENT (12) /* the error's cause is still present */
#define RTN_UNKNOWN_COMMAND (13) /* unknown command */
#define RTN_HOMING (14) /* homing failed or is running */
#define RTN_OBJECT (15) /* object dictionary access failed */
#define RTN_INVALID_SLAVE (16) /* no such slave */
#define RTN_INVALID_CHANNEL (17) /* no such channel */
#define RTN_LIMIT_REACHED (18) /* a limit was reached */
#define RTN_FAULT (19) /* a fault stopped the command */
#define RTN_INVALID_GROUP (20) /* no such coordinate system */
#define RTN_GROUP_STATE (21) /* not allowed in the coordinate system's present state */
#define RTN_INVALID_HANDLE (30) /* the handle is not open */
#define RTN_WRONG_HANDLE_KIND (31) /* a handle of the wrong kind (an axis handle where a device handle is expected, or the reverse) */
#define RTN_NULL_POINTER (32) /* a pointer argument is NULL */
#define RTN_ARG_RANGE (33) /* an argument is outside its allowed range */
#define RTN_NO_DEVICE (34) /* no device with this index, ID or IP address */
#define RTN_NOT_ON_THIS_CARD (35) /* not available on this kind of card (e.g. NMC_DevOpenByIP on a PCIe card) */
#define RTN_PASSWORD (36) /* wrong system password (NMC_SetTime, NMC_ChangePassword, NMC_VerifyPassword) */
#define RTN_FILE (37) /* the file cannot be read or written, or is not an mcemu NMC configuration (NMC_LoadConfigFromFile, NMC_SaveConfigToFile, NMC_SetCmdDebug) */
#define RTN_UNKNOWN_FUNCTION (40) /* the server does not know this function */
#define RTN_VERSION (41) /* library and server share no protocol version */
#define RTN_BAD_PAYLOAD (42) /* malformed request or reply payload */
#define RTN_FRAME_TOO_LARGE (43) /* frame larger than the protocol allows */

#endif /* MTN_LIB20_ERR_H */
