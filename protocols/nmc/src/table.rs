//! THE function table: every `NMC_*` function the library exports, with the manual's name,
//! argument order and C types (digest 001 §2), its wire id, and who serves it. The C header
//! (`crate::header`), the shim's calls and the server's dispatch are all made from it; adding a
//! function is one row here, its export in the shim and its handler in the server.
//!
//! Ids are stable (a client and a server of different builds must agree): never reuse or
//! renumber one; families take a block of 256 (0x00xx library, 0x01xx device, 0x02xx axis
//! status and servo, 0x03xx PTP/JOG/stop, 0x04xx homing, 0x05xx I/O, 0x06xx coordinate
//! systems, 0x07xx basic axis configuration, 0x08xx Appendix A aliases, 0x09xx analog I/O,
//! 0x0Axx EtherCAT, 0x0Bxx user parameters, 0x0Cxx gear, 0x0Dxx PT/PVT, 0x0Exx capture, 0x0Fxx
//! compare, 0x10xx gantry and handwheel, 0x11xx compensation, 0x12xx I/O by type, encoders,
//! extension modules and controller services, 0x13xx axis-level additions: packed status and
//! moves, positions, E-stop inputs, watchdog, planning period, 0x14xx coordinate systems:
//! look-ahead, packed status, position waits, full circles, buffer length, 0x15xx laser, SHIO
//! and PWM, 0x16xx coordinate-system buffered I/O, stops and packs, advanced buffered I/O,
//! 0x17xx coordinate transforms, arc sections, break point and move protection, 0x18xx system:
//! data collection, users, the configuration file, execution time, command debugging).

/// A C argument kind, as the manual writes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CType {
    Short,
    UShort,
    Int,
    UInt,
    /// The platform's `long` (32 bits on Windows, 64 on Linux x86-64): i64 on the wire.
    Long,
    ULong,
    UChar,
    Double,
    /// `HAND`, a 16-bit handle (digest 001 §1.2); out: `PHAND`.
    Hand,
    /// `char *`: a NUL-terminated string in, or a caller's buffer out.
    Str,
    /// `unsigned char *pIPv4Array`: 4 bytes.
    Ipv4,
    /// `TSearchMode` (an enum: any value, digest 001 §2.2).
    SearchMode,
    /// A pointer to one of the manual's structs (`crate::structs`).
    Struct(&'static str),
    /// A pointer to an array of structs; its length is the previous out argument, for an in
    /// array the previous in argument (`count`), or what the function's row comment says. On
    /// the wire: u16 count, then the structs.
    StructArray(&'static str),
    /// `short *` (`short *pSyncAxArray`), in or out; its length another argument's value. On
    /// the wire: u16 count, then i16 each.
    ShortArray,
    /// `unsigned long *`: as [`CType::LongArray`], u16 count then u64 each.
    ULongArray,
    /// `long *`: an array of the platform's `long`, its length the function's (the crd's
    /// coordinates, a mask's bits, `cnts`) or another argument's value. On the wire: u16 count,
    /// then i64 each.
    LongArray,
    /// `double *`: an array of doubles, its length an in argument (`count`). On the wire: u16
    /// count, then f64 each.
    DoubleArray,
    /// `unsigned char *`: a byte buffer, its length an in argument (`len`). On the wire: u16
    /// count, then the bytes.
    Bytes,
}

/// Which way an argument goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dir {
    /// Passed by value (or a pointer the function only reads): in the request.
    In,
    /// A pointer the function writes: in the reply.
    Out,
}

/// Who carries a function out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Served {
    /// The library alone (error codes, timeouts, its version): never on the wire.
    Library,
    /// mcemu, through a request.
    Server,
}

/// Which header declares it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeaderFile {
    /// `mtn_lib20.h`: the manual's functions.
    Main,
    /// `mtn_lib20_ext.h`: mcemu's additions (`NMC_DevClose`).
    Ext,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Arg {
    pub name: &'static str,
    pub ty: CType,
    pub dir: Dir,
}

/// One row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Function {
    pub id: u16,
    pub name: &'static str,
    pub served: Served,
    pub header: HeaderFile,
    pub args: &'static [Arg],
}

impl Function {
    /// The arguments the request carries, in order.
    pub fn inputs(&self) -> impl Iterator<Item = &Arg> {
        self.args.iter().filter(|a| a.dir == Dir::In)
    }
    /// The arguments the reply carries, in order.
    pub fn outputs(&self) -> impl Iterator<Item = &Arg> {
        self.args.iter().filter(|a| a.dir == Dir::Out)
    }
}

/// The row of function `id`.
pub fn by_id(id: u16) -> Option<&'static Function> {
    FUNCTIONS.iter().find(|f| f.id == id)
}

/// The row named `name` (`NMC_MtGetSts`).
pub fn by_name(name: &str) -> Option<&'static Function> {
    FUNCTIONS.iter().find(|f| f.name == name)
}

macro_rules! functions {
    ($(
        $konst:ident = $id:literal $served:ident $hdr:ident $name:ident
            ( $( $dir:ident $ty:expr => $arg:ident ),* $(,)? );
    )*) => {
        $(
            #[doc = concat!("`", stringify!($name), "`")]
            pub const $konst: Function = Function {
                id: $id,
                name: stringify!($name),
                served: Served::$served,
                header: HeaderFile::$hdr,
                args: &[$( Arg { name: stringify!($arg), ty: $ty, dir: Dir::$dir } ),*],
            };
        )*
        /// Every row, in id order.
        pub const FUNCTIONS: &[Function] = &[$( $konst ),*];
    };
}

use CType::*;

functions! {
    // ---- the library itself (digest 001 §2.20, §7) ----
    GET_DLL_VERSION = 0x0001 Library Main NMC_GetDllVersion(Out Str => pVersion);
    SET_COMM_PARA = 0x0002 Library Main NMC_SetCommPara(In Hand => devHandle, In ULong => waitTimeInUs, In ULong => retryTimes);
    GET_LAST_ERR = 0x0003 Library Main NMC_GetLastErr();
    GET_ERR_DESC = 0x0004 Library Main NMC_GetErrDesc(In Short => errCode, Out Str => errDesc);
    SET_ERR_CODE_MODE = 0x0005 Library Main NMC_SetErrCodeMode(In Short => mode);
    DEV_SEARCH = 0x0006 Library Main NMC_DevSearch(In SearchMode => mode, Out UShort => pDevNo, Out StructArray("TDevInfo") => pInfoList);
    DEV_CLOSE = 0x0007 Library Ext NMC_DevClose(Out Hand => pDevHandle);
    // ---- device (digest 001 §2.2, §2.20) ----
    DEV_OPEN = 0x0101 Server Main NMC_DevOpen(In Short => devNo, Out Hand => pDevHandle);
    DEV_OPEN_BY_ID = 0x0102 Server Main NMC_DevOpenByID(In Str => idStr, Out Hand => pDevHandle);
    DEV_OPEN_BY_IP = 0x0103 Server Main NMC_DevOpenByIP(In Ipv4 => pIPv4Array, Out Hand => pDevHandle);
    DEV_RESET = 0x0104 Server Main NMC_DevReset(In Hand => devHandle);
    GET_CARD_INFO = 0x0105 Server Main NMC_GetCardInfo(In Hand => devHandle, Out Struct("TCardInfo") => pInfo);
    GET_CLOCK = 0x0106 Server Main NMC_GetClock(In Hand => devHandle, Out ULong => pClock, Out ULong => pLoop);
    // ---- axis handles, status, servo (digest 001 §2.2, §2.4, §2.8) ----
    MT_OPEN = 0x0201 Server Main NMC_MtOpen(In Hand => devHandle, In Short => itemNo, Out Hand => pAxisHandle);
    MT_GET_STS = 0x0202 Server Main NMC_MtGetSts(In Hand => axisHandle, Out Short => pStsWord);
    MT_GET_STS_EX = 0x0203 Server Main NMC_MtGetStsEx(In Hand => axisHandle, Out Short => pStsWord);
    MT_CLR_ERROR = 0x0204 Server Main NMC_MtClrError(In Hand => axisHandle);
    MT_CLR_STS_BY_BITS = 0x0205 Server Main NMC_MtClrStsByBits(In Hand => axisHandle, In Short => stsMask);
    MT_GET_PRF_POS = 0x0206 Server Main NMC_MtGetPrfPos(In Hand => axisHandle, Out Long => pos);
    MT_GET_PRF_VEL = 0x0207 Server Main NMC_MtGetPrfVel(In Hand => axisHandle, Out Double => pVel);
    MT_GET_AXIS_POS = 0x0208 Server Main NMC_MtGetAxisPos(In Hand => axisHandle, Out Long => pos);
    MT_GET_CMD_POS = 0x0209 Server Main NMC_MtGetCmdPos(In Hand => axisHandle, Out Long => pos);
    MT_GET_ENC_POS = 0x020A Server Main NMC_MtGetEncPos(In Hand => axisHandle, Out Long => pPos);
    MT_SET_SV_ON = 0x020B Server Main NMC_MtSetSvOn(In Hand => axisHandle);
    MT_SET_SV_OFF = 0x020C Server Main NMC_MtSetSvOff(In Hand => axisHandle);
    MT_GET_MOTION_IO = 0x020D Server Main NMC_MtGetMotionIO(In Hand => axisHandle, Out Long => inValue);
    // ---- profile modes, PTP, JOG, stops (digest 001 §2.5) ----
    MT_SET_PRF_MODE = 0x0301 Server Main NMC_MtSetPrfMode(In Hand => axisHandle, In Short => mode);
    MT_GET_PRF_MODE = 0x0302 Server Main NMC_MtGetPrfMode(In Hand => axisHandle, Out Short => mode);
    MT_SET_PTP_PARA = 0x0303 Server Main NMC_MtSetPtpPara(In Hand => axisHandle, In Struct("TPtpPara") => pAxPara);
    MT_GET_PTP_PARA = 0x0304 Server Main NMC_MtGetPtpPara(In Hand => axisHandle, Out Struct("TPtpPara") => pAxPara);
    MT_SET_PTP_TGT_POS = 0x0305 Server Main NMC_MtSetPtpTgtPos(In Hand => axisHandle, In Long => pos);
    MT_GET_PTP_TGT_POS = 0x0306 Server Main NMC_MtGetPtpTgtPos(In Hand => axisHandle, Out Long => pos);
    MT_SET_VEL = 0x0307 Server Main NMC_MtSetVel(In Hand => axisHandle, In Double => vel);
    MT_GET_VEL = 0x0308 Server Main NMC_MtGetVel(In Hand => axisHandle, Out Double => vel);
    MT_SET_JOG_PARA = 0x0309 Server Main NMC_MtSetJogPara(In Hand => axisHandle, In Struct("TJogPara") => pAxPara);
    MT_GET_JOG_PARA = 0x030A Server Main NMC_MtGetJogPara(In Hand => axisHandle, Out Struct("TJogPara") => pAxPara);
    MT_UPDATE = 0x030B Server Main NMC_MtUpdate(In Hand => axisHandle);
    MT_UPDATE_MULTI = 0x030C Server Main NMC_MtUpdateMulti(In Hand => axisHandle, In Long => mask);
    MT_STOP = 0x030D Server Main NMC_MtStop(In Hand => axisHandle);
    MT_ABRUPT_STOP = 0x030E Server Main NMC_MtAbruptStop(In Hand => axisHandle);
    MT_STOP_MULTI = 0x030F Server Main NMC_MtStopMulti(In Hand => axisHandle, In Long => mask);
    MT_ESTP = 0x0310 Server Main NMC_MtEstp(In Hand => axisHandle);
    MT_MOVE_PTP_ABS = 0x0311 Server Main NMC_MtMovePtpAbs(In Hand => axisHandle, In Double => acc, In Double => dec, In Double => startVel, In Double => endVel, In Double => maxVel, In Short => smoothCoef, In Long => tgtPos);
    MT_MOVE_PTP_REL = 0x0312 Server Main NMC_MtMovePtpRel(In Hand => axisHandle, In Double => acc, In Double => dec, In Double => startVel, In Double => endVel, In Double => maxVel, In Short => smoothCoef, In Long => relPos);
    MT_MOVE_JOG = 0x0313 Server Main NMC_MtMoveJog(In Hand => axisHandle, In Double => acc, In Double => dec, In Double => maxVel, In Short => smoothCoef, In Short => clrStsFlag);
    // ---- homing (digest 001 §2.6, §3.13) ----
    MT_SET_HOME_PARA = 0x0401 Server Main NMC_MtSetHomePara(In Hand => axisHandle, In Struct("THomeSetting") => pHomePara);
    MT_GET_HOME_PARA = 0x0402 Server Main NMC_MtGetHomePara(In Hand => axisHandle, Out Struct("THomeSetting") => pHomePara);
    MT_HOME = 0x0403 Server Main NMC_MtHome(In Hand => axisHandle);
    MT_TRY_HOME = 0x0404 Server Main NMC_MtTryHome(In Hand => axisHandle);
    MT_HOME_STOP = 0x0405 Server Main NMC_MtHomeStop(In Hand => axisHandle);
    MT_GET_HOME_STS = 0x0406 Server Main NMC_MtGetHomeSts(In Hand => axisHandle, Out UShort => pStsWord);
    MT_GET_HOME_ERROR = 0x0407 Server Main NMC_MtGetHomeError(In Hand => axisHandle, Out Long => cmdPos);
    // ---- digital I/O (digest 001 §2.8) ----
    SET_DO_GROUP = 0x0501 Server Main NMC_SetDOGroup(In Hand => devHandle, In Long => value, In Short => groupID);
    GET_DO_GROUP = 0x0502 Server Main NMC_GetDOGroup(In Hand => devHandle, Out Long => pDoValue, In Short => groupID);
    SET_DO_BIT = 0x0503 Server Main NMC_SetDOBit(In Hand => devHandle, In Short => bitIndex, In Short => value);
    GET_DO_BIT = 0x0504 Server Main NMC_GetDOBit(In Hand => devHandle, In Short => bitIndex, Out Short => bitValue);
    GET_DI_GROUP = 0x0505 Server Main NMC_GetDIGroup(In Hand => devHandle, Out Long => pInValue, In Short => groupID);
    GET_DI_BIT = 0x0506 Server Main NMC_GetDIBit(In Hand => devHandle, In Short => bitIndex, Out Short => bitValue);
    // ---- coordinate systems (digest 001 §2.2, §2.7, §3.7-§3.10, §4.4) ----
    CRD_OPEN = 0x0601 Server Main NMC_CrdOpen(In Hand => devHandle, Out Hand => pCrdHandle);
    CRD_OPEN_EX = 0x0602 Server Main NMC_CrdOpenEx(In Hand => devHandle, In Short => itemNo, Out Hand => pCrdHandle);
    CRD_CLOSE = 0x0603 Server Main NMC_CrdClose(Out Hand => pCrdHandle);
    CRD_CONFIG = 0x0604 Server Main NMC_CrdConfig(In Hand => crdHandle, In Struct("TCrdConfig") => pConfig);
    CRD_GET_CONFIG = 0x0605 Server Main NMC_CrdGetConfig(In Hand => crdHandle, Out Struct("TCrdConfig") => pConfig);
    CRD_DELETE = 0x0606 Server Main NMC_CrdDelete(In Hand => crdHandle);
    CRD_SET_PARA = 0x0607 Server Main NMC_CrdSetPara(In Hand => crdHandle, In Struct("TCrdPara") => pCrdPara);
    CRD_GET_PARA = 0x0608 Server Main NMC_CrdGetPara(In Hand => crdHandle, Out Struct("TCrdPara") => pCrdPara);
    CRD_SET_EXT_PARA = 0x0609 Server Main NMC_CrdSetExtPara(In Hand => crdHandle, In Struct("TExtCrdPara") => extCrdPara);
    CRD_GET_EXT_PARA = 0x060A Server Main NMC_CrdGetExtPara(In Hand => crdHandle, Out Struct("TExtCrdPara") => extCrdPara);
    CRD_SET_SAFE_PARA = 0x060B Server Main NMC_CrdSetSafePara(In Hand => crdHandle, In Struct("TCrdSafePara") => pSafePara);
    CRD_SET_LOOK_AHEAD_CENTRI_ACC = 0x060C Server Main NMC_CrdSetLookAheadCentriAcc(In Hand => crdHandle, In Short => isUsingSetAcc, In Double => centriAcc);
    CRD_LINE_XYZ_EX = 0x0610 Server Main NMC_CrdLineXYZEx(In Hand => crdHandle, In Long => segNo, In Short => crdAxMask, In LongArray => pTgPosArray, In Double => endVel, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_LINE_XYZA = 0x0611 Server Main NMC_CrdLineXYZA(In Hand => crdHandle, In Long => segNo, In Short => crdAxMask, In LongArray => pTgPosArray, In Double => endVel, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_LINE_XYZ = 0x0612 Server Main NMC_CrdLineXYZ(In Hand => crdHandle, In Long => segNo, In Short => crdAxMask, In LongArray => pTgPosArray, In Double => endVel, In Double => vel, In Double => synAcc);
    CRD_LINE_XYZ_D8 = 0x0613 Server Main NMC_CrdLineXYZD8(In Hand => crdHandle, In Long => segNo, In Long => crdAxmask, In Long => extAxMask, In LongArray => pTgPosArray, In Double => endVel, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_LINE_XYZ_D8_PACK = 0x0614 Server Main NMC_CrdLineXYZD8Pack(In Hand => crdHandle, In Short => count, In StructArray("TCrdLineXYZD8Unit") => pCmdArray);
    CRD_ARC_CENTER_EX = 0x0618 Server Main NMC_CrdArcCenterEx(In Hand => crdHandle, In Long => segNo, In LongArray => pTgPosArray, In LongArray => pCenterPosArray, In Short => circleDir, In Double => endVel, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_ARC_CENTER_YZ_EX = 0x0619 Server Main NMC_CrdArcCenterYZEx(In Hand => crdHandle, In Long => segNo, In LongArray => pTgPos, In LongArray => pCenterPos, In Short => circleDir, In Double => velEnd, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_ARC_CENTER_ZX_EX = 0x061A Server Main NMC_CrdArcCenterZXEx(In Hand => crdHandle, In Long => segNo, In LongArray => pTgPos, In LongArray => pCenterPos, In Short => circleDir, In Double => velEnd, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_ARC_CENTER = 0x061B Server Main NMC_CrdArcCenter(In Hand => crdHandle, In Long => segNo, In LongArray => pTgPosArray, In LongArray => pCenterPosArray, In Short => circleDir, In Double => endVel, In Double => vel, In Double => synAcc);
    CRD_ARC_RADIUS_EX = 0x061C Server Main NMC_CrdArcRadiusEx(In Hand => crdHandle, In Long => segNo, In LongArray => pTgPosArray, In Double => radius, In Short => circleDir, In Double => endVel, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_ARC_RADIUS_YZ_EX = 0x061D Server Main NMC_CrdArcRadiusYZEx(In Hand => crdHandle, In Long => segNo, In LongArray => pTgPos, In Double => radius, In Short => circleDir, In Double => velEnd, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_ARC_RADIUS_ZX_EX = 0x061E Server Main NMC_CrdArcRadiusZXEx(In Hand => crdHandle, In Long => segNo, In LongArray => pTgPos, In Double => radius, In Short => circleDir, In Double => velEnd, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_ARC_PPP_EX = 0x061F Server Main NMC_CrdArcPPPEx(In Hand => crdHandle, In Long => segNo, In LongArray => pMidPosArray, In LongArray => pTgPosArray, In Double => endVel, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_HELIX_CENTER_EX = 0x0620 Server Main NMC_CrdHelixCenterEx(In Hand => crdHandle, In Long => segNo, In LongArray => pTgPosArray, In LongArray => pCenterPosArray, In Short => circleDir, In Double => rounds, In Double => endVel, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_ARC_3D_EX = 0x0621 Server Main NMC_CrdArc3DEx(In Hand => crdHandle, In Long => segNo, In LongArray => pMidPos, In LongArray => pTgPos, In Double => velEnd, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_ARC_3D = 0x0622 Server Main NMC_CrdArc3D(In Hand => crdHandle, In Long => segNo, In LongArray => pMidPos, In LongArray => pTgPos, In Double => velEnd, In Double => vel, In Double => synAcc);
    CRD_ELLIPSE = 0x0623 Server Main NMC_CrdEllipse(In Hand => crdHandle, In Long => segNo, In Double => abRatio, In LongArray => pCenterPos, In Short => ellipseDir, In Double => vel, In Double => synAcc);
    CRD_BUF_DO = 0x0628 Server Main NMC_CrdBufDo(In Hand => crdHandle, In Long => segNo, In Short => doType, In Long => ch, In Long => value);
    CRD_BUF_DO_EX = 0x0629 Server Main NMC_CrdBufDoEx(In Hand => crdHandle, In Long => segNo, In Short => group, In Long => doMask, In Long => doValue);
    CRD_BUF_DELAY = 0x062A Server Main NMC_CrdBufDelay(In Hand => crdHandle, In Long => segNo, In Short => scale, In Long => count);
    CRD_BUF_WAIT_DI = 0x062B Server Main NMC_CrdBufWaitDI(In Hand => crdHandle, In Long => segNo, In Short => index, In Short => diValue, In Long => waitLastTime);
    CRD_BUF_AX_MOVE_EX = 0x062C Server Main NMC_CrdBufAxMoveEx(In Hand => crdHandle, In Long => segNo, In Short => axisMask, In LongArray => pTgPos, In Double => vel, In Double => acc, In Short => blockEn, In Short => synEn);
    CRD_BUF_WAIT_ENC_IN_POSITION = 0x062D Server Main NMC_CrdBufWaitEncInPosition(In Hand => crdHandle, In Long => segNo, In Long => axisMask, In Long => overTime);
    CRD_BUF_SET_PTP_MOVE_PARA = 0x062E Server Main NMC_CrdBufSetPtpMovePara(In Hand => crdHandle, In Long => segNo, In Short => axisNo, In Double => vel, In Double => acc, In Short => soomthCoef);
    CRD_BUF_AX_MOVE_REL = 0x062F Server Main NMC_CrdBufAxMoveRel(In Hand => crdHandle, In Long => segNo, In Short => axisMask, In LongArray => pRelPos, In Short => blockEn, In Short => synEn);
    CRD_START_MTN = 0x0630 Server Main NMC_CrdStartMtn(In Hand => crdHandle);
    CRD_END_MTN = 0x0631 Server Main NMC_CrdEndMtn(In Hand => crdHandle);
    CRD_STOP_MTN = 0x0632 Server Main NMC_CrdStopMtn(In Hand => crdHandle);
    CRD_ESTOP_MTN = 0x0633 Server Main NMC_CrdEstopMtn(In Hand => crdHandle);
    CRD_CLR_ERROR = 0x0634 Server Main NMC_CrdClrError(In Hand => crdHandle);
    CRD_BUF_CLR = 0x0635 Server Main NMC_CrdBufClr(In Hand => crdHandle);
    CRD_SET_OVERRIDE = 0x0636 Server Main NMC_CrdSetOverride(In Hand => crdHandle, In Double => override);
    CRD_GET_OVERRIDE = 0x0637 Server Main NMC_CrdGetOverride(In Hand => crdHandle, Out Double => pOverride);
    CRD_SET_OVER_RIDE = 0x0638 Server Main NMC_CrdSetOverRide(In Hand => crdHandle, In Double => override);
    CRD_GET_OVER_RIDE = 0x0639 Server Main NMC_CrdGetOverRide(In Hand => crdHandle, Out Double => pOverride);
    CRD_GET_STS = 0x0640 Server Main NMC_CrdGetSts(In Hand => crdHandle, Out Short => pStsWord);
    CRD_GET_STS_EX = 0x0641 Server Main NMC_CrdGetStsEx(In Hand => crdHandle, Out Short => pSts, Out Long => pUserSeg);
    CRD_GET_INNER_STS = 0x0642 Server Main NMC_CrdGetInnerSts(In Hand => crdHandle, Out Long => pStsWord);
    CRD_GET_PRF_POS = 0x0643 Server Main NMC_CrdGetPrfPos(In Hand => crdHandle, In Short => cnts, Out LongArray => pPosArray);
    CRD_GE_PRFT_POS = 0x0644 Server Main NMC_CrdGePrftPos(In Hand => crdHandle, In Short => cnts, Out LongArray => pPosArray);
    CRD_GET_AXIS_POS = 0x0645 Server Main NMC_CrdGetAxisPos(In Hand => crdHandle, In Short => cnts, Out LongArray => pPosArray);
    CRD_GET_ENC_POS = 0x0646 Server Main NMC_CrdGetEncPos(In Hand => crdHandle, In Short => cnts, Out LongArray => pPosArray);
    CRD_GET_VEL = 0x0647 Server Main NMC_CrdGetVel(In Hand => crdHandle, Out Double => pVel);
    CRD_BUF_GET_FREE = 0x0648 Server Main NMC_CrdBufGetFree(In Hand => crdHandle, Out Long => pRes);
    CRD_BUF_GET_USED = 0x0649 Server Main NMC_CrdBufGetUsed(In Hand => crdHandle, Out Long => pLen);
    CRD_GET_USER_SEG_NO = 0x064A Server Main NMC_CrdGetUserSegNo(In Hand => crdHandle, Out Long => pSegNo);
    CRD_GET_BUF_ALL_CMD_CNT = 0x064B Server Main NMC_CrdGetBufAllCmdCnt(In Hand => crdHandle, Out Long => pCnt);
    CRD_GET_BUF_LEFT_LENGTH = 0x064C Server Main NMC_CrdGetBufLeftLength(In Hand => crdHandle, Out Double => pLen);
    // ---- basic axis configuration (digest 001 §2.3, §2.20) ----
    MT_SET_ALARM_CFG = 0x0701 Server Main NMC_MtSetAlarmCfg(In Hand => axisHandle, In Short => alarmEnable, In Short => alarmSns);
    MT_GET_ALARM_ON_OFF = 0x0702 Server Main NMC_MtGetAlarmOnOff(In Hand => axisHandle, Out Short => enable);
    MT_GET_ALARM_SNS = 0x0703 Server Main NMC_MtGetAlarmSns(In Hand => axisHandle, Out Short => swt);
    MT_SET_LMT_CFG = 0x0704 Server Main NMC_MtSetLmtCfg(In Hand => axisHandle, In Short => posLmtEnable, In Short => negLmtEnable, In Short => posLmtSns, In Short => negLmtSns);
    MT_GET_LMT_ON_OFF = 0x0705 Server Main NMC_MtGetLmtOnOff(In Hand => axisHandle, Out Short => posEn, Out Short => negEn);
    MT_GET_LMT_SNS = 0x0706 Server Main NMC_MtGetLmtSns(In Hand => axisHandle, Out Short => posSwt, Out Short => negSwt);
    MT_SW_LMT_ON_OFF = 0x0707 Server Main NMC_MtSwLmtOnOff(In Hand => axisHandle, In Short => enable);
    MT_GET_SW_LMT_ON_OFF = 0x0708 Server Main NMC_MtGetSwLmtOnOff(In Hand => axisHandle, Out Short => enable);
    MT_SW_LMT_VALUE = 0x0709 Server Main NMC_MtSwLmtValue(In Hand => axisHandle, In Long => posLmt, In Long => negLmt);
    MT_GET_SW_LMT_VALUE = 0x070A Server Main NMC_MtGetSwLmtValue(In Hand => axisHandle, Out Long => posLmt, Out Long => negLmt);
    MT_SET_STEP_MODE = 0x070B Server Main NMC_MtSetStepMode(In Hand => axisHandle, In Short => inv, In Short => mode);
    MT_GET_STEP_MODE = 0x070C Server Main NMC_MtGetStepMode(In Hand => axisHandle, Out Short => pInv, Out Short => pMode);
    SET_ENC_MODE = 0x070D Server Main NMC_SetEncMode(In Hand => devHandle, In UChar => encId, In UShort => encMode);
    GET_ENC_MODE = 0x070E Server Main NMC_GetEncMode(In Hand => devHandle, In UChar => encId, Out UShort => encMode);
    MT_SET_SAFE_PARA = 0x070F Server Main NMC_MtSetSafePara(In Hand => axisHandle, In Struct("TSafePara") => pPara);
    MT_GET_SAFE_PARA = 0x0710 Server Main NMC_MtGetSafePara(In Hand => axisHandle, Out Struct("TSafePara") => pPara);
    MT_SET_POS_ERR_LMT = 0x0711 Server Main NMC_MtSetPosErrLmt(In Hand => axisHandle, In Long => posErr);
    MT_GET_POS_ERR_LMT = 0x0712 Server Main NMC_MtGetPosErrLmt(In Hand => axisHandle, Out Long => posErr);
    MT_SET_AXIS_VEL_FILTER = 0x0713 Server Main NMC_MtSetAxisVelFilter(In Hand => axisHandle, In Short => filterCoef);
    MT_GET_AXIS_VEL_FILTER = 0x0714 Server Main NMC_MtGetAxisVelFilter(In Hand => axisHandle, Out Short => filterCoef);
    MT_SET_STEP_FILTER = 0x0715 Server Main NMC_MtSetStepFilter(In Hand => axisHandle, In UShort => coe);
    MT_GET_STEP_FILTER = 0x0716 Server Main NMC_MtGetStepFilter(In Hand => axisHandle, Out UShort => pCoe);
    MT_SET_POS_ERR_ACTION = 0x0717 Server Main NMC_MtSetPosErrAction(In Hand => axisHandle, In Short => actionsBits);
    MT_GET_POS_ERR_ACTION = 0x0718 Server Main NMC_MtGetPosErrAction(In Hand => axisHandle, Out Short => pActionsBits);
    MT_SET_AXIS_ARRIVAL_PARA = 0x0719 Server Main NMC_MtSetAxisArrivalPara(In Hand => axisHandle, In Long => arrivalBand, In Long => stableTime);
    MT_GET_AXIS_ARRIVAL_PARA = 0x071A Server Main NMC_MtGetAxisArrivalPara(In Hand => axisHandle, Out Long => pArrivalBand, Out Long => pStableTime);
    // ---- Appendix A: the summary table's misspellings, as aliases (digest 001 App. A) ----
    SET_DOG_GROUP = 0x0801 Server Main NMC_SetDOGGroup(In Hand => devHandle, In Long => value, In Short => groupID);
    GET_DOG_GROUP = 0x0802 Server Main NMC_GetDOGGroup(In Hand => devHandle, Out Long => pDoValue, In Short => groupID);
    // ---- analog I/O (digest 001 §2.8, §4.8) ----
    SET_DAC_MODE = 0x0901 Server Main NMC_SetDacMode(In Hand => devHandle, In Short => ch, In Short => mode);
    GET_DAC_MODE = 0x0902 Server Main NMC_GetDacMode(In Hand => devHandle, In Short => ch, Out Short => pMode);
    SET_ADC_MODE = 0x0903 Server Main NMC_SetAdcMode(In Hand => devHandle, In Short => ch, In Short => range, In Short => filterCoe);
    GET_ADC_MODE = 0x0904 Server Main NMC_GetAdcMode(In Hand => devHandle, In Short => ch, Out Short => pRange, Out Short => pFilterCoe);
    SET_DAC = 0x0905 Server Main NMC_SetDac(In Hand => devHandle, In Short => ch, In Short => dacValue);
    GET_DAC = 0x0906 Server Main NMC_GetDac(In Hand => devHandle, In Short => ch, Out Short => pDacValue);
    GET_ADC = 0x0907 Server Main NMC_GetAdc(In Hand => devHandle, In Short => ch, Out Short => pAdcValue);
    SET_DAC_BIAS = 0x0908 Server Main NMC_SetDacBias(In Hand => devHandle, In Short => ch, In Short => bias);
    GET_DAC_BIAS = 0x0909 Server Main NMC_GetDacBias(In Hand => devHandle, In Short => ch, Out Short => pBias);
    SET_DAC_LMT = 0x090A Server Main NMC_SetDacLmt(In Hand => devHandle, In Short => ch, In Short => maxVal, In Short => minVal);
    GET_DAC_LMT = 0x090B Server Main NMC_GetDacLmt(In Hand => devHandle, In Short => ch, Out Short => pMaxVal, Out Short => pMinVal);
    GET_ADC_VOLTAGE_MULTI = 0x090C Server Main NMC_GetAdcVoltageMulti(In Hand => devHandle, In Short => ch, In Short => count, Out DoubleArray => pAdcVolArray);
    SET_DAC_VOLTAGE_MULTI = 0x090D Server Main NMC_SetDacVoltageMulti(In Hand => devHandle, In Short => ch, In Short => count, In DoubleArray => pDacVolArray);
    GET_DAC_VOLTAGE_MULTI = 0x090E Server Main NMC_GetDacVoltageMulti(In Hand => devHandle, In Short => ch, In Short => count, Out DoubleArray => pDacVolArray);
    // ---- EtherCAT master, drives and SDO (digest 001 §2.1) ----
    ECAT_LOAD_CONFIG_FROM_FILE = 0x0A01 Server Main NMC_EcatLoadConfigFromFile(In Hand => devHandle, In Str => gmlFileName, In Short => masterIdx);
    ECAT_START = 0x0A02 Server Main NMC_EcatStart(In Hand => devHandle);
    ECAT_STOP = 0x0A03 Server Main NMC_EcatStop(In Hand => devHandle);
    ECAT_GET_STS = 0x0A04 Server Main NMC_EcatGetSts(In Hand => devHandle, Out UShort => pSts);
    ECAT_GET_RESOURCE = 0x0A05 Server Main NMC_EcatGetResource(In Hand => devHandle, Out Short => pSlaveCnt, Out Short => pDriverCnt, Out Short => pIoCnt);
    ECAT_START_HOME = 0x0A06 Server Main NMC_EcatStartHome(In Hand => axisHandle, In Int => method, In Int => velSwitch, In Int => velZero, In Int => acc, In Int => prmEx);
    ECAT_GET_HOME_STS = 0x0A07 Server Main NMC_EcatGetHomeSts(In Hand => axisHandle, Out UChar => pStatus);
    ECAT_STOP_HOME = 0x0A08 Server Main NMC_EcatStopHome(In Hand => axisHandle);
    ECAT_SDO_READ = 0x0A09 Server Main NMC_EcatSdoRead(In Hand => devHandle, In Short => devId, In UShort => idx, In UChar => sub_idx, In UInt => len, Out Bytes => val, Out UInt => abort_code);
    ECAT_SDO_WRITE = 0x0A0A Server Main NMC_EcatSdoWrite(In Hand => devHandle, In Short => devId, In UShort => idx, In UChar => sub_idx, In UInt => len, In Bytes => val, Out UInt => abort_code);
    ECAT_AXIS_GET_ERROR_CODE = 0x0A0B Server Main NMC_EcatAxisGetErrorCode(In Hand => axisHandle, Out UShort => pError);
    ECAT_AXIS_GET_DI = 0x0A0C Server Main NMC_EcatAxisGetDi(In Hand => axisHandle, Out Long => pDiVal);
    // ---- user parameter areas (digest 001 §2.20) ----
    USER_PARA_WR = 0x0B01 Server Main NMC_UserParaWr(In Hand => devHandle, In ULong => add, In ULong => len, In Bytes => pWrData);
    USER_PARA_RD = 0x0B02 Server Main NMC_UserParaRd(In Hand => devHandle, In ULong => add, In ULong => len, Out Bytes => pRdData);
    USER_PARA_WR_EX = 0x0B03 Server Main NMC_UserParaWrEx(In Hand => devHandle, In ULong => add, In ULong => len, In Bytes => pWrData);
    USER_PARA_RD_EX = 0x0B04 Server Main NMC_UserParaRdEx(In Hand => devHandle, In ULong => add, In ULong => len, Out Bytes => pRdData);
    // ---- electronic gear (digest 001 §2.16, §4.7) ----
    MT_GEAR_SET_DIR = 0x0C01 Server Main NMC_MtGearSetDir(In Hand => axisHandle, In Short => dir);
    MT_GEAR_GET_DIR = 0x0C02 Server Main NMC_MtGearGetDir(In Hand => axisHandle, Out Short => pdir);
    MT_GEAR_SET_MASTER = 0x0C03 Server Main NMC_MtGearSetMaster(In Hand => axisHandle, In Short => masterNo, In Short => masterType);
    MT_GEAR_GET_MASTER = 0x0C04 Server Main NMC_MtGearGetMaster(In Hand => axisHandle, Out Short => pmasterNo, Out Short => pmasterType);
    MT_GEAR_SET_RATIO = 0x0C05 Server Main NMC_MtGearSetRatio(In Hand => axisHandle, In Long => masterEven, In Long => slaveEven, In Long => masterSlope);
    MT_GEAR_GET_RATIO = 0x0C06 Server Main NMC_MtGearGetRatio(In Hand => axisHandle, Out Long => pMasterEven, Out Long => pSlaveEven, Out Long => pMasterSlope);
    MT_GEAR_START_MTN = 0x0C07 Server Main NMC_MtGearStartMtn(In Hand => axisHandle, In Short => syncAxCnts, In ShortArray => pSyncAxArray);
    // ---- PT and PVT (digest 001 §2.13, §2.14, §4.7) ----
    MT_PT_SET_STATIC = 0x0D01 Server Main NMC_MtPtSetStatic(In Hand => axisHandle, In Short => onOff, In Long => loopCount);
    MT_PT_GET_STATIC = 0x0D02 Server Main NMC_MtPtGetStatic(In Hand => axisHandle, Out Short => pOnOff, Out Long => pLoopCount);
    MT_PT_GET_SPACE = 0x0D03 Server Main NMC_MtPtGetSpace(In Hand => axisHandle, Out Short => pSpace, Out Short => pUsed);
    MT_PT_PUSH = 0x0D04 Server Main NMC_MtPtPush(In Hand => axisHandle, In Short => count, In DoubleArray => pPosArray, In LongArray => pTimeArray, In ShortArray => pTypeArray);
    MT_PT_BUF_CLR = 0x0D05 Server Main NMC_MtPtBufClr(In Hand => axisHandle);
    MT_PT_START_MTN = 0x0D06 Server Main NMC_MtPtStartMtn(In Hand => axisHandle, In Short => otherSynAxCnts, In ShortArray => pOtherSynAxArray);
    MT_PT_SET_PARA = 0x0D07 Server Main NMC_MtPtSetPara(In Hand => axisHandle, In Struct("TPtPara") => pPara);
    MT_PVT_SET_PARA = 0x0D11 Server Main NMC_MtPvtSetPara(In Hand => axisHandle, In Struct("TPvtPara") => pPara);
    MT_PVT_GET_PARA = 0x0D12 Server Main NMC_MtPvtGetPara(In Hand => axisHandle, Out Struct("TPvtPara") => pPara);
    MT_PVT_DATA = 0x0D13 Server Main NMC_MtPvtData(In Hand => axisHandle, In Short => count, In DoubleArray => pPosArray, In DoubleArray => pTimeArray, In DoubleArray => pVelArray);
    MT_PVT_BUF_GET_SPACE = 0x0D14 Server Main NMC_MtPvtBufGetSpace(In Hand => axisHandle, Out Short => pFreeSpace, Out Short => pUsedSpace);
    MT_PVT_BUF_CLR = 0x0D15 Server Main NMC_MtPvtBufClr(In Hand => axisHandle);
    MT_PVT_START_MTN = 0x0D16 Server Main NMC_MtPvtStartMtn(In Hand => axisHandle, In Short => otherSynAxCnts, In ShortArray => pOtherSynAxArray);
    // ---- capture (digest 001 §2.18, §3.15, §4.6) ----
    MT_SET_CAPT_SNS = 0x0E01 Server Main NMC_MtSetCaptSns(In Hand => axisHandle, In Short => mode, In Short => ioSrc, In Short => level);
    MT_GET_CAPT_SNS = 0x0E02 Server Main NMC_MtGetCaptSns(In Hand => axisHandle, Out Short => pMode, Out Short => pIoSrc, Out Short => pLevel);
    MT_SET_CAPT = 0x0E03 Server Main NMC_MtSetCapt(In Hand => axisHandle);
    MT_GET_CAPT_POS = 0x0E04 Server Main NMC_MtGetCaptPos(In Hand => axisHandle, Out Long => pPos);
    MT_CLR_CAPT_STS = 0x0E05 Server Main NMC_MtClrCaptSts(In Hand => axisHandle);
    MT_SET_ADV_CAPT_PARAM = 0x0E06 Server Main NMC_MtSetAdvCaptParam(In Hand => devHandle, In Struct("TAdvCaptureParam") => pParam, In Short => ch);
    MT_CLR_ADV_CAPT_STS = 0x0E07 Server Main NMC_MtClrAdvCaptSts(In Hand => devHandle, In Short => ch);
    MT_GET_ADV_CAPT_POS = 0x0E08 Server Main NMC_MtGetAdvCaptPos(In Hand => devHandle, Out Short => captSts, Out LongArray => pPosArray, In Short => ch);
    MT_SET_CAPT_REPEAT = 0x0E09 Server Main NMC_MtSetCaptRepeat(In Hand => axisHandle, In Short => count);
    MT_GET_CAPT_REPEAT_STATUS = 0x0E0A Server Main NMC_MtGetCaptRepeatStatus(In Hand => axisHandle, Out Short => pCount);
    MT_GET_CAPT_REPEAT_POS_MULTI = 0x0E0B Server Main NMC_MtGetCaptRepeatPosMulti(In Hand => axisHandle, Out LongArray => pPosArray, In Short => startNum, In Short => count);
    // ---- position compare, 1-D and 2-D (digest 001 §2.11, §3.16, §4.6) ----
    COMP_2DIMENS_SET_PARAM_EX = 0x0F01 Server Main NMC_Comp2DimensSetParamEx(In Hand => devHandle, In Short => group, In Struct("TComp2DimensParamEx") => param, In Short => chn);
    COMP_2DIMENS_GET_PARAM_EX = 0x0F02 Server Main NMC_Comp2DimensGetParamEx(In Hand => devHandle, In Short => group, Out Struct("TComp2DimensParamEx") => param, In Short => chn);
    COMP_2DIMENS_SET_DATA = 0x0F03 Server Main NMC_Comp2DimensSetData(In Hand => devHandle, In Short => group, In LongArray => pArrayPos, In Short => count, In Short => chn);
    COMP_2DIMENS_ONOFF = 0x0F04 Server Main NMC_Comp2DimensOnoff(In Hand => devHandle, In Short => group, In Short => onOff, In Short => chn);
    COMP_2DIMENS_STATUS_EX = 0x0F05 Server Main NMC_Comp2DimensStatusEx(In Hand => devHandle, In Short => group, Out Struct("TComp2DimensSts") => pStatus, In Short => chn);
    // ---- gantry and handwheel (digest 001 §2.9, §2.10, §4.7) ----
    SET_GANTRY_MASTER = 0x1001 Server Main NMC_SetGantryMaster(In Hand => axisHandle, In Short => group);
    SET_GANTRY_SLAVE = 0x1002 Server Main NMC_SetGantrySlave(In Hand => axisHandle, In Short => group, In Long => gantryErrLmt);
    DEL_GANTRY_GROUP = 0x1003 Server Main NMC_DelGantryGroup(In Hand => axisHandle, In Short => group);
    SET_HAND_WHEEL = 0x1011 Server Main NMC_SetHandWheel(In Hand => devHandle, In Short => axis, In Double => ratio, In Double => acc, In Double => vel);
    SET_HAND_WHEEL_INPUT = 0x1012 Server Main NMC_SetHandWheelInput(In Hand => devHandle, In Short => index);
    SET_HAND_WHEEL_RATIO = 0x1013 Server Main NMC_SetHandWheelRatio(In Hand => devHandle, In Double => ratio);
    CLR_HAND_WHEEL = 0x1014 Server Main NMC_ClrHandWheel(In Hand => devHandle);
    // ---- mechanical compensation (digest 001 §2.19, §3.17, §4.1) ----
    MT_SET_LEAD_SCREW_COMP_PARA = 0x1101 Server Main NMC_MtSetLeadScrewCompPara(In Hand => axisHandle, In Short => num, In Long => startPos, In Long => cmpLen, In ShortArray => pCompPos, In ShortArray => pCompNeg);
    MT_ENABLE_LEAD_SCREW = 0x1102 Server Main NMC_MtEnableLeadScrew(In Hand => axisHandle, In Short => enable);
    MT_SET_BACKLASH = 0x1103 Server Main NMC_MtSetBacklash(In Hand => axisHandle, In Long => compValue, In Double => compDelta, In Long => compDir);
    MT_GET_BACKLASH = 0x1104 Server Main NMC_MtGetBacklash(In Hand => axisHandle, Out Long => pCompValue, Out Double => pCompDelta, Out Long => pCompDir);
    SET_2D_COMPENSATION_TABLE = 0x1105 Server Main NMC_Set2DCompensationTable(In Hand => devHandle, In Short => tableIndex, In Struct("T2DCompensationTable") => pTable, In StructArray("TCompData") => pData);
    GET_2D_COMPENSATION_TABLE = 0x1106 Server Main NMC_Get2DCompensationTable(In Hand => devHandle, In Short => tableIndex, Out Struct("T2DCompensationTable") => pTable, Out StructArray("TCompData") => pData);
    SET_2D_COMPENSATION = 0x1107 Server Main NMC_Set2DCompensation(In Hand => devHandle, In Struct("T2DCompensation") => pComp);
    GET_2D_COMPENSATION = 0x1108 Server Main NMC_Get2DCompensation(In Hand => devHandle, Out Struct("T2DCompensation") => pComp);
    // ---- I/O by type, encoders, extension modules, device identity (digest 001 §2.8, §2.20, §4.8) ----
    GET_DI_EX = 0x1201 Server Main NMC_GetDIEx(In Hand => devHandle, In Short => diType, In Short => groupID, Out Long => pDiValue);
    GET_DI_RAW = 0x1202 Server Main NMC_GetDIRaw(In Hand => devHandle, In Short => diType, In Short => groupID, Out Long => pDiValue);
    GET_DO_EX = 0x1203 Server Main NMC_GetDOEx(In Hand => devHandle, In Short => doType, In Short => groupID, Out Long => pOutValue);
    SET_DO_MASK = 0x1204 Server Main NMC_SetDOMask(In Hand => devHandle, In Long => outMask, In Long => outValue, In Short => doType, In Short => groupID);
    GET_ENC_POS = 0x1205 Server Main NMC_GetEncPos(In Hand => devHandle, In Short => encId, Out Long => pPos);
    GET_ENC_VEL = 0x1206 Server Main NMC_GetEncVel(In Hand => devHandle, In UChar => encId, Out Double => vel);
    SET_ENC_POS = 0x1207 Server Main NMC_SetEncPos(In Hand => devHandle, In Short => encId, In Long => encPos);
    IO_MODULE_SET_EN = 0x1208 Server Main NMC_IOModuleSetEn(In Hand => devHandle, In UChar => chDevId, In Short => chDevType);
    IO_MODULE_GET_TYPE = 0x1209 Server Main NMC_IOModuleGetType(In Hand => devHandle, In UChar => chDevId, Out Short => pChDevType);
    IO_MODULE_RD_16BIT = 0x120A Server Main NMC_IOModuleRd16Bit(In Hand => devHandle, In UChar => chDevId, In UChar => offset, Out UShort => pData);
    IO_MODULE_RD_32BIT = 0x120B Server Main NMC_IOModuleRd32Bit(In Hand => devHandle, In UChar => chDevId, In UChar => offset, Out ULong => pData);
    IO_MODULE_RD_OUT_16BIT = 0x120C Server Main NMC_IOModuleRdOut16Bit(In Hand => devHandle, In UChar => chDevId, In UChar => offset, Out UShort => pData);
    IO_MODULE_RD_OUT_32BIT = 0x120D Server Main NMC_IOModuleRdOut32Bit(In Hand => devHandle, In UChar => chDevId, In UChar => offset, Out ULong => pData);
    IO_MODULE_WR_16BIT = 0x120E Server Main NMC_IOModuleWr16Bit(In Hand => devHandle, In UChar => chDevId, In UChar => offset, In UShort => data);
    IO_MODULE_WR_32BIT = 0x120F Server Main NMC_IOModuleWr32Bit(In Hand => devHandle, In UChar => chDevId, In UChar => offset, In ULong => data);
    GET_IO_MODULE_STS = 0x1210 Server Main NMC_GetIOModuleSts(In Hand => devHandle, Out ULong => sts);
    DEV_READ_ID = 0x1211 Server Main NMC_DevReadID(In Hand => devHandle, Out Str => pIdStr);
    GET_UID = 0x1212 Server Main NMC_GetUID(In Hand => devHandle, Out ULong => pUID);
    GET_MT_LIB_VERSION = 0x1213 Server Main NMC_GetMtLibVersion(In Hand => devHandle, Out Struct("TmLibVersion") => pVersion);
    // ---- the plain aliases, inversion, timed outputs, filters, edge counters, DIO mapping (digest 001 §2.8) ----
    GET_DI = 0x1220 Server Main NMC_GetDI(In Hand => devHandle, Out Long => pInValue, In Short => groupID);
    GET_DO = 0x1221 Server Main NMC_GetDO(In Hand => devHandle, Out Long => pDoValue, In Short => groupID);
    SET_DO = 0x1222 Server Main NMC_SetDO(In Hand => devHandle, In Long => value, In Short => groupID);
    SET_DI_BIT_REVS = 0x1223 Server Main NMC_SetDIBitRevs(In Hand => devHandle, In Short => bitIndex, In Short => revs);
    GET_DI_BIT_REVS = 0x1224 Server Main NMC_GetDIBitRevs(In Hand => devHandle, In Short => bitIndex, Out Short => pRevs);
    SET_DO_BIT_REVS = 0x1225 Server Main NMC_SetDOBitRevs(In Hand => devHandle, In Short => bitIndex, In Short => revs);
    GET_DO_BIT_REVS = 0x1226 Server Main NMC_GetDOBitRevs(In Hand => devHandle, In Short => bitIndex, Out Short => pRevs);
    SET_DO_BIT_REVS_EX = 0x1227 Server Main NMC_SetDOBitRevsEx(In Hand => devHandle, In Short => doType, In Short => group, In Short => bitIndex, In Short => revs);
    GET_DO_BIT_REVS_EX = 0x1228 Server Main NMC_GetDOBitRevsEx(In Hand => devHandle, In Short => doType, In Short => group, In Short => bitIndex, Out Short => pRevs);
    SET_DO_BIT_AUTO_REVERSE = 0x1229 Server Main NMC_SetDOBitAutoReverse(In Hand => devHandle, In Short => bitIndex, In Short => value, In Short => reverseTime);
    DO_BIT_PULSE_ENABLE = 0x122A Server Main NMC_DoBitPulseEnable(In Hand => devHandle, In Short => doType, In Short => doIndex, In Long => highLevelTime, In Long => lowLevelTime, In Long => outCount, In Short => initialLevel, In Short => ch);
    DO_BIT_PULSE_DISABLE = 0x122B Server Main NMC_DoBitPulseDisable(In Hand => devHandle, In Short => ch);
    SET_DI_FILTER = 0x122C Server Main NMC_SetDIFilter(In Hand => devHandle, In Short => diType, In Short => diGroup, In Short => diIndex, In Short => filtTime);
    GET_DI_FILTER = 0x122D Server Main NMC_GetDIFilter(In Hand => devHandle, In Short => diType, In Short => diGroup, In Short => diIndex, Out Short => pFiltTime);
    SET_DI_REVERSE_COUNT = 0x122E Server Main NMC_SetDiReverseCount(In Hand => devHandle, In Short => diType, In Short => diIndex, In ULongArray => pReverseCountArray, In Short => count);
    GET_DI_REVERSE_COUNT = 0x122F Server Main NMC_GetDiReverseCount(In Hand => devHandle, In Short => diType, In Short => diIndex, Out ULongArray => pReverseCountArray, In Short => count);
    SET_DIO_MAPPING = 0x1230 Server Main NMC_SetDioMapping(In Hand => devHandle, In Struct("TDioMappingCfg") => pDioCfg);
    GET_ALL_DIO_MAPPING = 0x1231 Server Main NMC_GetAllDioMapping(In Hand => devHandle, Out StructArray("TDioMappingCfg") => pDioCfg);
    CLR_ALL_DIO_MAPPING = 0x1232 Server Main NMC_ClrAllDioMapping(In Hand => devHandle);
    // ---- controller services: ID, system parameters, RTC, password, backed variables (digest 001 §2.20, §4.9) ----
    DEV_WRITE_ID = 0x1240 Server Main NMC_DevWriteID(In Hand => devHandle, In Str => pIdStr);
    DEV_GET_PARA = 0x1241 Server Main NMC_DevGetPara(In Hand => devHandle, In ULong => paraID, Out Long => pValue);
    DEV_SET_PARA = 0x1242 Server Main NMC_DevSetPara(In Hand => devHandle, In ULong => paraID, In Long => value);
    GET_TIME = 0x1243 Server Main NMC_GetTime(In Hand => devHandle, Out Struct("TNMCTime") => pTime);
    SET_TIME = 0x1244 Server Main NMC_SetTime(In Hand => devHandle, In Struct("TNMCTime") => pTime, In Str => pPassword);
    VERIFY_PASSWORD = 0x1245 Server Main NMC_VerifyPassword(In Hand => devHandle, In Str => pPassword);
    CHANGE_PASSWORD = 0x1246 Server Main NMC_ChangePassword(In Hand => devHandle, In Str => pPasswordOld, In Str => pPasswordNew);
    SET_BACKED_VAR_ON_OFF = 0x1247 Server Main NMC_SetBackedVarOnOff(In Hand => devHandle, In Short => en);
    GET_BACKED_VAR_ON_OFF = 0x1248 Server Main NMC_GetBackedVarOnOff(In Hand => devHandle, Out Short => pEn);
    GET_BACKED_VAR_GROUP2 = 0x1249 Server Main NMC_GetBackedVarGroup2(In Hand => devHandle, Out Struct("TBackGroup2") => pBackVar);
    // ---- axis-level additions: packed status and moves, positions, E-stop inputs, watchdog,
    // planning period (digest 001 §2.3-§2.5, §2.8, §2.20, §3.4, §3.6) ----
    MT_GET_STS_MULTI = 0x1301 Server Main NMC_MtGetStsMulti(In Hand => firstAxisHandle, Out ShortArray => pStsArray, In Short => count, Out ULong => pClock);
    MT_GET_STS_PACK12_EX = 0x1302 Server Main NMC_MtGetStsPack12Ex(In Hand => axisFirstHandle, Out Struct("TAxisStsPack12Ex") => pPackSts);
    MT_MOVE_PTP_ABS_PACK8 = 0x1303 Server Main NMC_MtMovePtpAbsPack8(In Hand => axisFirstHandle, In Struct("TMovePtpPack8") => pPackData);
    MT_MOVE_PTP_REL_PACK8 = 0x1304 Server Main NMC_MtMovePtpRelPack8(In Hand => axisFirstHandle, In Struct("TMovePtpPack8") => pPackData);
    MT_SET_AXIS_POS = 0x1305 Server Main NMC_MtSetAxisPos(In Hand => axisHandle, In Long => axisPos);
    MT_SET_ENC_POS = 0x1306 Server Main NMC_MtSetEncPos(In Hand => axisHandle, In Long => encPos);
    MT_ZERO_POS = 0x1307 Server Main NMC_MtZeroPos(In Hand => axisHandle);
    MT_SET_SV_CLR = 0x1308 Server Main NMC_MtSetSvClr(In Hand => axisHandle, In Short => swt);
    MT_HOME_SNS = 0x1309 Server Main NMC_MtHomeSns(In Hand => axisHandle, In Short => sns);
    MT_SET_ESTOP_DI = 0x130A Server Main NMC_MtSetEstopDI(In Hand => axisHandle, In Short => gpiIndex, In Short => sense);
    MT_GET_ESTOP_DI = 0x130B Server Main NMC_MtGetEstopDI(In Hand => axisHandle, Out Short => gpiIndex, Out Short => sense);
    MT_GET_MOTION_IO_LOGICAL = 0x130C Server Main NMC_MtGetMotionIOLogical(In Hand => axisHandle, Out Long => pIoValue);
    SET_PROFILE_PERIOD = 0x130D Server Main NMC_SetProfilePeriod(In Hand => devHandle, In Short => period);
    GET_PROFILE_PERIOD = 0x130E Server Main NMC_GetProfilePeriod(In Hand => devHandle, Out Short => pPeriod);
    SET_WATCH_DOG = 0x130F Server Main NMC_SetWatchDog(In Hand => devHandle, In Long => timeout, In Short => stopMode, In Short => groupID, In Long => doValue);
    SET_ESTOP_DI_EX = 0x1310 Server Main NMC_SetEstopDIEx(In Hand => devHandle, In Struct("TEstopExParam") => pParam, In Short => group);
    GET_ESTOP_DI_EX = 0x1311 Server Main NMC_GetEstopDIEx(In Hand => devHandle, Out Struct("TEstopExParam") => pParam, In Short => group);
    CLR_ESTOP_DI_EX = 0x1312 Server Main NMC_ClrEstopDIEx(In Hand => devHandle, In Short => group);
    // ---- electronic cam "Follow" (digest 001 §2.17, S-FOLLOW, TV59) ----
    MT_FOLLOW_SET_MASTER = 0x1320 Server Main NMC_MtFollowSetMaster(In Hand => axisHandle, In Short => masterNo, In Short => masterType);
    MT_FOLLOW_GET_MASTER = 0x1321 Server Main NMC_MtFollowGetMaster(In Hand => axisHandle, Out Short => pMasterNo, Out Short => pMasterType);
    MT_FOLLOW_SET_EVENT = 0x1322 Server Main NMC_MtFollowSetEvent(In Hand => axisHandle, In Short => eventType, In Short => masterDir, In Long => pos);
    MT_FOLLOW_GET_EVENT = 0x1323 Server Main NMC_MtFollowGetEvent(In Hand => axisHandle, Out Short => pEventType, Out Short => pMasterDir, Out Long => pPos);
    MT_FOLLOW_SET_DIR = 0x1324 Server Main NMC_MtFollowSetDir(In Hand => axisHandle, In Short => dir);
    MT_FOLLOW_GET_DIR = 0x1325 Server Main NMC_MtFollowGetDir(In Hand => axisHandle, Out Short => pDir);
    MT_FOLLOW_SET_LOOP_COUNT = 0x1326 Server Main NMC_MtFollowSetLoopCount(In Hand => axisHandle, In Long => loopCnt);
    MT_FOLLOW_GET_LOOP_COUNT = 0x1327 Server Main NMC_MtFollowGetLoopCount(In Hand => axisHandle, Out Long => pLoopCnt);
    MT_FOLLOW_PUSH_DATA = 0x1328 Server Main NMC_MtFollowPushData(In Hand => axisHandle, In Long => masterPos, In Double => slavePos, In Short => segType, In Short => fifoNo);
    MT_FOLLOW_GET_SPACE = 0x1329 Server Main NMC_MtFollowGetSpace(In Hand => axisHandle, Out Short => pSpace, In Short => fifoNo);
    MT_FOLLOW_CLEAR = 0x132A Server Main NMC_MtFollowClear(In Hand => axisHandle, In Short => fifoNo);
    MT_FOLLOW_START = 0x132B Server Main NMC_MtFollowStart(In Hand => axisHandle, In Short => syncAxCnts, In ShortArray => pSyncAxArray);
    MT_FOLLOW_SWITCH = 0x132C Server Main NMC_MtFollowSwitch(In Hand => axisHandle, In Short => syncAxCnts, In ShortArray => pSyncAxArray);
    // ---- PT start on an input, PT parameters read back, PTP compare, damping (digest 001
    // §2.3, §2.5, §2.8, §2.11, §2.13; Appendix A) ----
    MT_PT_START_MTN_EX = 0x1340 Server Main NMC_MtPtStartMtnEx(In Hand => axisHandle, In Short => diIndex, In Short => diSns);
    MT_PT_GET_PARA = 0x1341 Server Main NMC_MtPtGetPara(In Hand => axisHandle, Out Struct("TPtPara") => pPara);
    MT_SET_PTP_COMPARE_PARA = 0x1342 Server Main NMC_MtSetPtpComparePara(In Hand => axisHandle, In Short => dir, In Long => comparaPos, In Double => upDateVel);
    MT_GET_PTP_COMPARE_STS = 0x1343 Server Main NMC_MtGetPtpCompareSts(In Hand => axisHandle, Out Short => pIsCompareActive, Out Short => pIsCompareOut);
    COMP_2DIMENS_STATUS = 0x1344 Server Main NMC_Comp2DimensStatus(In Hand => devHandle, In Short => group, Out Struct("TComp2DimensSts") => pStatus, In Short => chn);
    MT_SET_AXIS_DAMP_COMP_PARAM = 0x1345 Server Main NMC_MtSetAxisDampCompParam(In Hand => axisHandle, In Short => enable, In Short => param1, In Short => param2);
    // ---- closed loop, profile configuration, saved motion configuration (digest 001 §1.5,
    // §2.2, §2.15, §2.20) ----
    MT_SET_CTRL_MODE = 0x1350 Server Main NMC_MtSetCtrlMode(In Hand => axisHandle, In Short => mode);
    MT_GET_CTRL_MODE = 0x1351 Server Main NMC_MtGetCtrlMode(In Hand => axisHandle, Out Short => pMode);
    MT_SET_PID_PARA = 0x1352 Server Main NMC_MtSetPIDPara(In Hand => axisHandle, In Short => index, In Struct("TPidPara") => pidPara);
    MT_GET_PID_PARA = 0x1353 Server Main NMC_MtGetPIDPara(In Hand => axisHandle, In Short => index, Out Struct("TPidPara") => pPidPara);
    MT_SET_PID_INDEX = 0x1354 Server Main NMC_MtSetPIDIndex(In Hand => axisHandle, In Short => index);
    MT_GET_PID_INDEX = 0x1355 Server Main NMC_MtGetPIDIndex(In Hand => axisHandle, Out Short => pIndex);
    MT_SET_CLOSE_LOOP_DAC = 0x1356 Server Main NMC_MtSetCloseLoopDac(In Hand => axisHandle, In Struct("TDacMotor") => pDacPara);
    MT_GET_CLOSE_LOOP_DAC = 0x1357 Server Main NMC_MtGetCloseLoopDac(In Hand => axisHandle, Out Struct("TDacMotor") => pDacPara);
    SET_CLOSE_LOOP_DAC = 0x1358 Server Main NMC_SetCloseLoopDac(In Hand => axisHandle, In Struct("TDacMotor") => pDacPara);
    MT_PRF_CONFIG = 0x1359 Server Main NMC_MtPrfConfig(In Hand => axisHandle, In Short => mapAxisNo, In Short => port, In Long => startPos);
    MT_GET_PRF_CONFIG = 0x135A Server Main NMC_MtGetPrfConfig(In Hand => axisHandle, Out Short => mapAxisNo, Out Short => port, Out Long => startPos);
    MT_SET_PRF_COE = 0x135B Server Main NMC_MtSetPrfCoe(In Hand => axisHandle, In Double => inCoe);
    MT_GET_PRF_COE = 0x135C Server Main NMC_MtGetPrfCoe(In Hand => axisHandle, Out Double => inCoe);
    MT_SET_ENC_COE = 0x135D Server Main NMC_MtSetEncCoe(In Hand => axisHandle, In Double => encCoe);
    MT_GET_ENC_COE = 0x135E Server Main NMC_MtGetEncCoe(In Hand => axisHandle, Out Double => pEncCoe);
    SAVE_MOTION_CONFIG = 0x1360 Server Main NMC_SaveMotionConfig(In Hand => devHandle, In Short => enable);
    // ---- coordinate systems, 0x14xx family (digest 001 §2.7, §3.4, §3.9) ----
    CRD_SET_LOOKAHEAD_PARA = 0x1401 Server Main NMC_CrdSetLookaheadPara(In Hand => crdHandle, In Struct("TLookaheadPara") => lkhPara);
    CRD_GET_LOOKAHEAD_PARA = 0x1402 Server Main NMC_CrdGetLookaheadPara(In Hand => crdHandle, Out Struct("TLookaheadPara") => lkhPara, In Short => defaultFlag);
    CRD_GET_STS_PACK4 = 0x1403 Server Main NMC_CrdGetStsPack4(In Hand => crdHandle, Out Struct("TPackedCrdSts4") => pPackSts);
    CRD_BUF_WAIT_POS = 0x1404 Server Main NMC_CrdBufWaitPos(In Hand => crdHandle, In Long => segNo, In Short => axisNo, In Short => condition, In Long => pos, In Short => posSrc, In Long => overTime);
    CRD_CIRCLE_3D_EX = 0x1405 Server Main NMC_CrdCircle3DEx(In Hand => crdHandle, In Long => segNo, In LongArray => pMidPos, In LongArray => pTgPos, In Double => velEnd, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_CIRCLE_PPP = 0x1406 Server Main NMC_CrdCirclePPP(In Hand => crdHandle, In Long => segNo, In Short => planeIdx, In LongArray => pStPos, In LongArray => pMidPosArray, In LongArray => pTgPosArray, In Double => endVel, In Double => vel, In Double => synAcc, In Short => lookaheadDis);
    CRD_SET_BUF_LENGTH_FLAG = 0x1407 Server Main NMC_CrdSetBufLengthFlag(In Hand => crdHandle, In Short => flag);
    CRD_GET_BUF_LENGTH = 0x1408 Server Main NMC_CrdGetBufLength(In Hand => crdHandle, Out Double => pLen);
    // ---- laser, SHIO and PWM (digest 001 §2.12, §3.20): N/A outputs, stored and echoed ----
    LASER_SET_MODE = 0x1501 Server Main NMC_LaserSetMode(In Hand => devHandle, In Short => mode, In Short => ch);
    LASER_SET_MODES = 0x1502 Server Main NMC_LaserSetModes(In Hand => devHandle, In Short => mode, In Short => ch);
    LASER_SET_OUTPUT_TYPE_EX = 0x1503 Server Main NMC_LaserSetOutputTypeEx(In Hand => devHandle, In Short => outputType, In Short => index, In Double => optionVal, In Short => ch);
    LASER_SET_OUTPUT_TYPE = 0x1504 Server Main NMC_LaserSetOutputType(In Hand => devHandle, In Short => outputType, In Short => index, In Long => optionVal, In Short => ch);
    LASER_SET_PARAM = 0x1505 Server Main NMC_LaserSetParam(In Hand => devHandle, In Long => onDelay, In Long => offDelay, In Long => minValue, In Long => maxValue, In Long => standbyPower, In Short => ch);
    LASER_GET_PARAM = 0x1506 Server Main NMC_LaserGetParam(In Hand => devHandle, Out Long => pOnDelay, Out Long => pOffDelay, Out Long => pMinValue, Out Long => pMaxValue, Out Long => pStandbyPower, In Short => ch);
    LASER_SET_POWER_EX = 0x1507 Server Main NMC_LaserSetPowerEx(In Hand => devHandle, In Double => outVal, In Short => ch);
    LASER_ON_OFF = 0x1508 Server Main NMC_LaserOnOff(In Hand => devHandle, In Short => onOff, In Short => ch);
    LASER_GET_POWER = 0x1509 Server Main NMC_LaserGetPower(In Hand => devHandle, Out Double => pVal, In Short => ch);
    LASER_GET_ON_OFF = 0x150A Server Main NMC_LaserGetOnOff(In Hand => devHandle, Out Short => pOnOffState, In Short => ch);
    LASER_SET_FOLLOW_PARAM = 0x150B Server Main NMC_LaserSetFollowParam(In Hand => devHandle, In Short => powerFilter, In Short => followAdvMode, In Short => ch);
    // pLaserCmpPower is `unsigned long *` (xCount·yCount values): a StructArray of that C type
    // puts the manual's spelling in the header; on the wire u16 count, then u64 each.
    SET_LASER_POWER_CMP_TABLE = 0x150C Server Main NMC_SetLaserPowerCmpTable(In Hand => devHandle, In Short => tableNo, In LongArray => pXCmpPos, In LongArray => pYCmpPos, In Short => xCount, In Short => yCount, In ULong => powerMin, In ULong => powerMax, In StructArray("unsigned long") => pLaserCmpPower, In Short => ch);
    START_LASER_POWER_COMP = 0x150D Server Main NMC_StartLaserPowerComp(In Hand => devHandle, In ShortArray => pAxisNo, In Short => ch);
    STOP_LASER_POWER_COMP = 0x150E Server Main NMC_StopLaserPowerComp(In Hand => devHandle, In Short => ch);
    LASER_SET_TIME_ARRAY_PARA = 0x150F Server Main NMC_LaserSetTimeArrayPara(In Hand => devHandle, In Struct("TTimeArrayPara") => pPara, In Short => ch);
    LASER_SET_TIME_ARRAY_POWER = 0x1510 Server Main NMC_LaserSetTimeArrayPower(In Hand => devHandle, In Short => group, In Struct("TLaserPower") => pLaserPower);
    LASER_TIME_ARRAY_EXE = 0x1511 Server Main NMC_LaserTimeArrayExe(In Hand => devHandle, In Short => group, In Short => ch);
    SHIO_CONFIG_PARA = 0x1521 Server Main NMC_SHIOConfigPara(In Hand => devHandle, In Struct("TSHIOPara") => pSHIOPara, In Short => ch);
    SHIO_ENABLE_MIN_FRQ = 0x1522 Server Main NMC_SHIOEnableMinFrq(In Hand => devHandle, In Long => minFrq, In Short => ch);
    SHIO_DISABLE_MIN_FRQ = 0x1523 Server Main NMC_SHIODisableMinFrq(In Hand => devHandle, In Short => ch);
    SHIO_ENABLE_MIN_FRG = 0x1524 Server Main NMC_SHIOEnableMinFrg(In Hand => devHandle, In Long => minFrq, In Short => ch);
    SHIO_DISABLE_MIN_FRG = 0x1525 Server Main NMC_SHIODisableMinFrg(In Hand => devHandle, In Short => ch);
    SHIO_CHANGE_AXIS_MASK = 0x1526 Server Main NMC_SHIOChangeAxisMask(In Hand => devHandle, In Short => axisMask, In Short => ch);
    SHIO_GATE_ON = 0x1527 Server Main NMC_SHIOGateOn(In Hand => devHandle, In Short => ch);
    SHIO_GATE_OFF = 0x1528 Server Main NMC_SHIOGateOff(In Hand => devHandle, In Short => ch);
    SHIO_TRIGGER_ON = 0x1529 Server Main NMC_SHIOTriggerOn(In Hand => devHandle, In Double => freq, In Double => width, In Short => ch);
    SHIO_TRIGGER_OFF = 0x152A Server Main NMC_SHIOTriggerOff(In Hand => devHandle, In Short => ch);
    SHIO_GATE_PULSE = 0x152B Server Main NMC_SHIOGatePulse(In Hand => devHandle, In Double => gateTime, In Double => gateFrq, In Long => outCount, In Short => ch);
    SET_PWM_TO_GATE = 0x152C Server Main NMC_SetPwmToGate(In Hand => devHandle, In Short => pwmCh, In Short => gateCh, In Short => onOff);
    PWM_PULSE_OUT = 0x152D Server Main NMC_PwmPulseOut(In Hand => devHandle, In Double => onTime, In Double => pwmFrq, In Long => outCount, In Short => ch);
    SET_PWM_PORT = 0x152E Server Main NMC_SetPWMPort(In Hand => devHandle, In Short => portType, In Short => portIdx, In Short => ch);
    GET_PWM_PORT = 0x152F Server Main NMC_GetPWMPort(In Hand => devHandle, Out Short => pPortType, Out Short => pGpoIdx, In Short => ch);
    CRD_BUF_LASER_ON_OFF = 0x1541 Server Main NMC_CrdBufLaserOnOff(In Hand => crdHandle, In Long => segNo, In Short => onOff, In Short => ch);
    CRD_BUF_LASER_POWER = 0x1542 Server Main NMC_CrdBufLaserPower(In Hand => crdHandle, In Long => segNo, In Long => power, In Short => ch);
    CRD_BUF_LASER_SET_FOLLOW = 0x1543 Server Main NMC_CrdBufLaserSetFollow(In Hand => crdHandle, In Long => segNo, In Double => overRide, In Short => followType, In Short => ch);
    CRD_BUF_LASER_SET_PARAM = 0x1544 Server Main NMC_CrdBufLaserSetParam(In Hand => crdHandle, In Long => segment, In Long => onDelay, In Long => offDelay, In Long => minValue, In Long => maxValue, In Long => standbyPower, In Short => ch);
    CRD_BUF_LASER_TIME_ARRAY_EXE = 0x1545 Server Main NMC_CrdBufLaserTimeArrayExe(In Hand => crdHandle, In Long => segNo, In Short => group, In Short => ch);
    CRD_BUF_SHIO_GATE_PULSE = 0x1546 Server Main NMC_CrdBufSHIOGatePulse(In Hand => crdHandle, In Long => segNo, In Double => gateTime, In Double => gateFrq, In Long => outCount, In Short => ch);
    CRD_BUF_SHIO_SET_PARAM = 0x1547 Server Main NMC_CrdBufSHIOSetParam(In Hand => crdHandle, In Long => segment, In Double => delay, In Double => gateTime, In Double => gateDistance, In Short => ch);
    CRD_BUF_SHIO_CHANGE_AXIS_MASK = 0x1548 Server Main NMC_CrdBufSHIOChangeAxisMask(In Hand => crdHandle, In Long => segment, In Short => axisMask, In Short => ch);
    CRD_BUF_SHIO_SET_MIN_FRQ = 0x1549 Server Main NMC_CrdBufSHIOSetMinFrq(In Hand => crdHandle, In Long => segment, In Long => minFrq, In Short => ch);
    CRD_BUF_SHIO_CLR_MIN_FRQ = 0x154A Server Main NMC_CrdBufSHIOClrMinFrq(In Hand => crdHandle, In Long => segment, In Short => ch);
    CRD_BUF_SHIO_SET_MIN_FRG = 0x154B Server Main NMC_CrdBufSHIOSetMinFrg(In Hand => crdHandle, In Long => segment, In Long => minFrq, In Short => ch);
    CRD_BUF_SHIO_CLR_MIN_FRG = 0x154C Server Main NMC_CrdBufSHIOClrMinFrg(In Hand => crdHandle, In Long => segment, In Short => ch);
    BUF_SHIO_GATE_ON = 0x154D Server Main NMC_BufSHIOGateOn(In Hand => crdHandle, In Long => segNo, In Short => ch);
    BUF_SHIO_GATE_OFF = 0x154E Server Main NMC_BufSHIOGateOff(In Hand => crdHandle, In Long => segNo, In Short => ch);
    // ---- coordinate-system buffered I/O, stops and packs; advanced buffered I/O (digest 001 §2.7, §3.11, §3.12) ----
    CRD_BUF_OUT = 0x1601 Server Main NMC_CrdBufOut(In Hand => crdHandle, In Long => segNo, In Short => group, In Short => ch, In Long => value);
    CRD_BUF_STOP_MTN = 0x1602 Server Main NMC_CrdBufStopMtn(In Hand => crdHandle, In Long => segNo, In Short => crdIdx);
    CRD_BUF_SET_ESTOP_DI = 0x1603 Server Main NMC_CrdBufSetEstopDI(In Hand => crdHandle, In Long => segNo, In Short => axis, In Short => gpiIndex, In Short => sense);
    CRD_BUF_ESTOP_DI_EX_ON_OFF = 0x1604 Server Main NMC_CrdBufEstopDIExOnOff(In Hand => crdHandle, In Long => segNo, In Short => onOff, In Short => group);
    CRD_BUF_DO_BIT_PULSE_ENABLE = 0x1605 Server Main NMC_CrdBufDoBitPulseEnable(In Hand => crdHandle, In Long => segNo, In Short => doType, In Short => doIndex, In Long => highLevelTime, In Long => lowLevelTime, In Long => outCount, In Short => initialLevel, In Short => ch);
    CRD_BUF_DO_BIT_PULSE_DISABLE = 0x1606 Server Main NMC_CrdBufDoBitPulseDisable(In Hand => crdHandle, In Long => segNo, In Short => ch);
    CRD_BUF_BEFORE_AX_SYNC_MOVE = 0x1607 Server Main NMC_CrdBufBeforeAxSyncMove(In Hand => crdHandle, In Long => segNo, In Short => axis, In Long => relDistance, In Double => vel);
    CRD_BUF_DATA_PACK = 0x1608 Server Main NMC_CrdBufDataPack(In Hand => crdHandle, In Bytes => pBufData, In Short => dataLen);
    ADV_BUF_IO_SET_PARAM = 0x1609 Server Main NMC_AdvBufIoSetParam(In Hand => devHandle, In Struct("TAdvBufIoParam") => pPrm, In Short => ch);
    ADV_BUF_IO_GET_PARAM = 0x160A Server Main NMC_AdvBufIoGetParam(In Hand => devHandle, Out Struct("TAdvBufIoParam") => pPrm, In Short => ch);
    ADV_BUF_IO_OUT = 0x160B Server Main NMC_AdvBufIoOut(In Hand => devHandle, In Long => value, In Short => ch);
    ADV_BUF_IO_GET_PULSE_CNT = 0x160C Server Main NMC_AdvBufIoGetPulseCnt(In Hand => devHandle, Out Long => pOutCout, In Short => ch);
    CRD_ADV_BUF_IO_ON_AFTER_LEN = 0x160D Server Main NMC_CrdAdvBufIoOnAfterLen(In Hand => crdHandle, In Long => segNo, In Long => outLength, In Long => value, In Short => ch);
    CRD_ADV_BUF_IO_OFF_BEFORE_LEN = 0x160E Server Main NMC_CrdAdvBufIoOffBeforeLen(In Hand => crdHandle, In Long => segNo, In Long => outLength, In Short => ch);
    // ---- coordinate transforms, arc sections, break point, move protection, 0x17xx family
    // (digest 001 §2.7, §2.20 C3§10.5, §3.7) ----
    CRD_SET_TRANS_ROTATE = 0x1701 Server Main NMC_CrdSetTransRotate(In Hand => crdHandle, In Short => rotAxisNo, In Double => angleRadEqual, In Long => firstAxisInitPos, In Long => secAxisInitPos);
    CRD_DEL_TRANS_ROTATE = 0x1702 Server Main NMC_CrdDelTransRotate(In Hand => crdHandle);
    CRD_SET_TRANS_POLAR = 0x1703 Server Main NMC_CrdSetTransPolar(In Hand => crdHandle, In Short => rotAxNo, In Short => transAxNo, In Double => rotEquiv);
    CRD_RUN_TO_POLAR_POS = 0x1704 Server Main NMC_CrdRunToPolarPos(In Hand => crdHandle, In Double => xPos, In Double => yPos, In Double => rotVel, In Double => transVel);
    CRD_RUN_TO_POLAR_THETA = 0x1705 Server Main NMC_CrdRunToPolarTheta(In Hand => crdHandle, In Double => theta, In Double => vel, In Short => clrRoundFlag);
    CRD_DEL_TRANS_POLAR = 0x1706 Server Main NMC_CrdDelTransPolar(In Hand => crdHandle);
    CRD_SET_TRANS_XYZA = 0x1707 Server Main NMC_CrdSetTransXYZA(In Hand => crdHandle, In ShortArray => pAxisMapArray);
    CRD_DEL_TRANS_XYZA = 0x1708 Server Main NMC_CrdDelTransXYZA(In Hand => crdHandle);
    CRD_SET_XYZA_TOOL_CALC = 0x1709 Server Main NMC_CrdSetXYZAToolCalc(In Hand => crdHandle, In Double => deltaTheta, In Long => deltaX, In Long => deltaY, Out Long => pToolX, Out Long => pToolY);
    CRD_SET_XYZA_PARA = 0x170A Server Main NMC_CrdSetXYZAPara(In Hand => crdHandle, In Double => pulse2Rad, In Long => toolX, In Long => toolY);
    CRD_GET_XYZA_PARA = 0x170B Server Main NMC_CrdGetXYZAPara(In Hand => crdHandle, Out Double => pPulse2Rad, Out Long => ToolX, Out Long => pToolY);
    CRD_SET_OFFSET = 0x170C Server Main NMC_CrdSetOffset(In Hand => crdHandle, In Short => count, In LongArray => pOffsetArray);
    CRD_SET_ARC_SEC_PARA = 0x170D Server Main NMC_CrdSetArcSecPara(In Hand => crdHandle, In Struct("TArcSecSetting") => pSetting);
    CRD_GET_ARC_SEC_PARA = 0x170E Server Main NMC_CrdGetArcSecPara(In Hand => crdHandle, Out Struct("TArcSecSetting") => pSetting);
    CRD_SET_FOURTH_AXIS_TO_TURN_VEL = 0x170F Server Main NMC_CrdSetFourthAxisToTurnVel(In Hand => crdHandle, In Double => tolVel);
    CRD_GOTO_BREAK = 0x1710 Server Main NMC_CrdGotoBreak(In Hand => crdHandle, In Double => acc, In Double => vel);
    SET_MV_PROTECT = 0x1711 Server Main NMC_SetMvProtect(In Hand => devHandle, In Short => groupNo, In Short => mode);
    DEL_MV_PROTECT = 0x1712 Server Main NMC_DelMvProtect(In Hand => devHandle, In Short => groupNo);
    SET_MV_PROTECT_MODE01_PARA = 0x1713 Server Main NMC_SetMvProtectMode01Para(In Hand => devHandle, In Short => groupNo, In Struct("TMvProtectPara") => pMvProtectPara);
    GET_MV_PROTECT_MODE01_PARA = 0x1714 Server Main NMC_GetMvProtectMode01Para(In Hand => devHandle, In Short => groupNo, Out Struct("TmvProtectPara") => pMvProtectPara);
    GET_MV_PROTECT_STS = 0x1715 Server Main NMC_GetMvProtectSts(In Hand => devHandle, In Short => groupNo, Out Short => pSts);
    // ---- system family 0x18xx (helper nmcsys): data collection (digest 001 §2.20, §3.19,
    // S-COLLECT), users (§4.9), the configuration file on the host (§1.5), the execution-time
    // calculation (§2.7), command debugging ----
    GET_COLLECT_DATA_ADDR = 0x1801 Server Main NMC_GetCollectDataAddr(In Hand => devHandle, In Short => index, In Short => dataType, Out ULong => pAddr, Out Short => pDataLen);
    CONFIG_COLLECT = 0x1802 Server Main NMC_ConfigCollect(In Hand => devHandle, In Struct("TCollectCfg") => pCollect, In Struct("TCollectTrig") => pTrig);
    COLLECT_ON_OFF = 0x1803 Server Main NMC_CollectOnOff(In Hand => devHandle, In Short => en);
    GET_COLLECT_STS = 0x1804 Server Main NMC_GetCollectSts(In Hand => devHandle, Out Short => pSts, Out Long => pDataLen);
    GET_COLLECT_DATA = 0x1805 Server Main NMC_GetCollectData(In Hand => devHandle, In Short => len, Out Bytes => pData);
    CLEAR_COLLECT_STS = 0x1806 Server Main NMC_ClearCollectSts(In Hand => devHandle);
    USER_SET_PASSWORD = 0x1810 Server Main NMC_UserSetPassword(In Hand => devHandle, In Str => pUserName, In Str => pPasswordOld, In Str => pPasswordNew);
    USER_LOGIN = 0x1811 Server Main NMC_UserLogin(In Hand => devHandle, In Str => pUserName, In Str => pPassword);
    USER_LOGOUT = 0x1812 Server Main NMC_UserLogout(In Hand => devHandle, In Str => pUserName);
    SET_CMD_DEBUG = 0x1813 Library Main NMC_SetCmdDebug(In Short => enable, In Str => debugOutputFile);
    USER_PRINT = 0x1814 Library Main NMC_UserPrint(In Str => msg);
    // The file lives on the host (the manual: "in the current project directory"): the
    // library reads and writes it and carries its text with the two Ext rows.
    SAVE_CONFIG_TO_FILE = 0x1820 Library Main NMC_SaveConfigToFile(In Hand => devHandle, In Str => pFilePath);
    LOAD_CONFIG_FROM_FILE = 0x1821 Library Main NMC_LoadConfigFromFile(In Hand => devHandle, In Str => pFilePath);
    DEV_GET_CONFIG_TEXT = 0x1822 Server Ext NMC_DevGetConfigText(In Hand => devHandle, Out Str => pText);
    DEV_SET_CONFIG_TEXT = 0x1823 Server Ext NMC_DevSetConfigText(In Hand => devHandle, In Str => pText);
    // No handle (the manual's host look-ahead): the library asks every device it has open
    // through the Ext rows. `_NMC_CrdGetExeTime` as the detailed text prints it (App. A).
    CRD_START_EXE_TIME_CALC = 0x1830 Library Main NMC_CrdStartExeTimeCalc();
    CRD_GET_EXE_TIME = 0x1831 Library Main NMC_CrdGetExeTime(Out Double => pTime);
    CRD_GET_EXE_TIME_SIC = 0x1832 Library Main _NMC_CrdGetExeTime(Out Double => pTime);
    CRD_START_EXE_TIME_CALC_EX = 0x1833 Server Ext NMC_CrdStartExeTimeCalcEx(In Hand => devHandle);
    CRD_GET_EXE_TIME_EX = 0x1834 Server Ext NMC_CrdGetExeTimeEx(In Hand => devHandle, Out Double => pTime);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_and_names_are_unique_and_ids_ascend() {
        for pair in FUNCTIONS.windows(2) {
            assert!(
                pair[0].id < pair[1].id,
                "{} ≥ {}",
                pair[0].name,
                pair[1].name
            );
        }
        let mut names: Vec<&str> = FUNCTIONS.iter().map(|f| f.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), FUNCTIONS.len());
        // `_NMC_CrdGetExeTime` as the manual prints it (digest 001 App. A).
        assert!(FUNCTIONS
            .iter()
            .all(|f| f.name.trim_start_matches('_').starts_with("NMC_")));
        assert!(by_id(0).is_none(), "id 0 is the hello");
    }

    #[test]
    fn lookups_find_rows() {
        assert_eq!(by_name("NMC_MtGetSts"), Some(&MT_GET_STS));
        assert_eq!(by_id(0x0202), Some(&MT_GET_STS));
        let outs: Vec<&str> = GET_DO_GROUP.outputs().map(|a| a.name).collect();
        assert_eq!(outs, ["pDoValue"]);
        let ins: Vec<&str> = GET_DO_GROUP.inputs().map(|a| a.name).collect();
        assert_eq!(ins, ["devHandle", "groupID"]);
    }
}
