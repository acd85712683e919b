/* I/O by type, masked DO writes, encoder channels, extension modules and the device's identity
 * (digest 001 §2.8, §2.20, §3.10, §4.8): each function's effect and its bad arguments. */
#include <string.h>
#include "check.h"

int main(void) {
    HAND dev = 0, x = 0, z = 0;
    long v = -1, w = -1, io = 0;
    short sts = 0, type = -1, bit = -1;
    unsigned short u16 = 0;
    unsigned long u32 = 0, uid = 0;
    double vel = 0, peak = 0;
    char id[32];
    TCardInfo info;
    TmLibVersion version;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 0, &x));
    OK(NMC_MtOpen(dev, 2, &z));

    /* General DI by type = by group; raw = inverted-free. */
    OK(NMC_GetDIGroup(dev, &v, 0));
    OK(NMC_GetDIEx(dev, DI_TYPE_GPI, 0, &w));
    CHECK(v == w, "GetDIEx %#lx vs GetDIGroup %#lx", w, v);
    OK(NMC_GetDIRaw(dev, DI_TYPE_GPI, 1, &w));
    OK(NMC_GetDIGroup(dev, &v, 1));
    CHECK(v == w, "GetDIRaw %#lx vs GetDIGroup %#lx", w, v);
    CHECK(NMC_GetDIEx(dev, 5, 0, &v) == RTN_ARG_RANGE, "diType 5");
    CHECK(NMC_GetDIEx(dev, DI_TYPE_LMTN, 1, &v) == RTN_ARG_RANGE, "limit group 1");
    CHECK(NMC_GetDIEx(dev, DI_TYPE_GPI, 2, &v) == RTN_ARG_RANGE, "group 2 before its module");
    CHECK(NMC_GetDIRaw(dev, DI_TYPE_GPI, 0, NULL) == RTN_NULL_POINTER, "NULL");

    /* Home inputs: axis 0 at 0 sits on its home cam [0, 5000]. */
    OK(NMC_GetDIEx(dev, DI_TYPE_HOME, 0, &v));
    OK(NMC_MtGetMotionIO(x, &io));
    CHECK(((v >> 0) & 1) == ((io >> 2) & 1), "home DI %#lx vs MotionIO %#lx", v, io);

    /* Servo enable as a DO type: SetDOMask switches servos, GetDOEx reads them. */
    OK(NMC_SetDOMask(dev, 0x5, 0x5, DO_TYPE_MOTOR_ENABLE, 0));
    EVENTUALLY(NMC_GetDOEx(dev, DO_TYPE_MOTOR_ENABLE, 0, &v), (v & 0x5) == 0x5);
    OK(NMC_MtGetSts(x, &sts));
    CHECK(sts & BIT_AXIS_SVON, "axis 0 not on after SetDOMask: %#x", sts);
    OK(NMC_SetDOMask(dev, 0x1, 0x0, DO_TYPE_MOTOR_ENABLE, 0));
    EVENTUALLY(NMC_MtGetSts(x, &sts), !(sts & BIT_AXIS_SVON));
    OK(NMC_GetDOEx(dev, DO_TYPE_MOTOR_ENABLE, 0, &v));
    CHECK((v & 0x5) == 0x4, "enable DOs %#lx", v);

    /* Negative limit of axis 2 (z, at -1000) as DI type 1; encoder velocity while it moves. */
    OK(NMC_MtMovePtpAbs(z, 0.2, 0.2, 0, 0, 20, 0, -1500));
    do {
        OK(NMC_GetEncVel(dev, 2, &vel));
        if (-vel > peak) peak = -vel;
        OK(NMC_MtGetSts(z, &sts));
    } while (sts & BIT_AXIS_BUSY);
    CHECK(peak > 1.0 && peak < 20.5, "encoder velocity peak %f pulse/ms", peak);
    OK(NMC_GetDIEx(dev, DI_TYPE_LMTN, 0, &v));
    OK(NMC_MtGetMotionIO(z, &io));
    CHECK((v & 0x4) && (io & BIT_AXMTIO_LMTN), "neg limit DI %#lx MotionIO %#lx", v, io);
    OK(NMC_GetDIRaw(dev, DI_TYPE_LMTP, 0, &v));
    CHECK(!(v & 0x4), "pos limit DI %#lx", v);
    CHECK(NMC_GetEncVel(dev, 4, &vel) == RTN_ARG_RANGE, "encoder 4");

    /* General DOs under a mask; alarm clear (inactive high by default); high-speed outputs. */
    OK(NMC_SetDOGroup(dev, 0, 0));
    OK(NMC_SetDOMask(dev, 0x6, 0x2, DO_TYPE_GPDO, 0));
    OK(NMC_SetDOMask(dev, 0x4, 0x4, DO_TYPE_GPDO, 0));
    OK(NMC_SetDOMask(dev, 0x1, 0x0, DO_TYPE_GPDO, 0));
    OK(NMC_GetDOGroup(dev, &v, 0));
    OK(NMC_GetDOEx(dev, DO_TYPE_GPDO, 0, &w));
    CHECK(v == 0x6 && w == 0x6, "masked DO group %#lx / %#lx", v, w);
    OK(NMC_GetDOEx(dev, DO_TYPE_MOTOR_CLEAR, 0, &v));
    CHECK(v == 0xF, "alarm clear default %#lx", v);
    OK(NMC_SetDOMask(dev, 0x1, 0x0, DO_TYPE_MOTOR_CLEAR, 0));
    OK(NMC_GetDOEx(dev, DO_TYPE_MOTOR_CLEAR, 0, &v));
    CHECK(v == 0xE, "alarm clear %#lx", v);
    OK(NMC_SetDOMask(dev, 0x1, 0x1, DO_TYPE_HSIO, 0)); /* the manual's HSIO0 example */
    OK(NMC_GetDOEx(dev, DO_TYPE_HSIO, 0, &v));
    CHECK(v == 1, "HSIO %#lx", v);
    CHECK(NMC_SetDOMask(dev, 1, 1, 0, 0) == RTN_ARG_RANGE, "doType 0");
    CHECK(NMC_GetDOEx(dev, 5, 0, &v) == RTN_ARG_RANGE, "doType 5");
    CHECK(NMC_SetDOMask(dev, 1, 1, DO_TYPE_GPDO, 2) == RTN_ARG_RANGE, "group 2 before its module");

    /* Encoder channels: an axis's, and the external encoder 256. */
    OK(NMC_SetEncPos(dev, 0, 12345));
    EVENTUALLY(NMC_GetEncPos(dev, 0, &v), v == 12345);
    OK(NMC_SetEncPos(dev, 256, -777));
    EVENTUALLY(NMC_GetEncPos(dev, 256, &v), v == -777);
    OK(NMC_GetEncPos(dev, 257, &v));
    CHECK(v == 0, "encoder 257 %ld", v);
    CHECK(NMC_GetEncPos(dev, 4, &v) == RTN_ARG_RANGE, "encoder 4");
    CHECK(NMC_GetEncPos(dev, 258, &v) == RTN_ARG_RANGE, "encoder 258");
    CHECK(NMC_SetEncPos(dev, -1, 0) == RTN_ARG_RANGE, "encoder -1");

    /* Extension module 2 (the fixture's IO64: bits 64-95). */
    OK(NMC_GetIOModuleSts(dev, &u32));
    CHECK(u32 == 0, "module status before enabling %#lx", u32);
    OK(NMC_IOModuleGetType(dev, 2, &type));
    CHECK(type == 0, "type before enabling %d", type);
    CHECK(NMC_IOModuleRd16Bit(dev, 2, 0, &u16) == RTN_INVALID_STATE, "read before enabling");
    OK(NMC_IOModuleSetEn(dev, 2, IOMODULE_TYPE_IO64));
    OK(NMC_IOModuleGetType(dev, 2, &type));
    CHECK(type == IOMODULE_TYPE_IO64, "type %d", type);
    OK(NMC_GetIOModuleSts(dev, &u32));
    CHECK(u32 == 1, "module status %#lx", u32);
    OK(NMC_IOModuleWr16Bit(dev, 2, 1, 0xA5A5));
    EVENTUALLY(NMC_IOModuleRdOut32Bit(dev, 2, 0, &u32), u32 == 0xA5A50000UL);
    OK(NMC_GetDOGroup(dev, &v, 2));
    CHECK(v == 0xA5A50000L, "DO group 2 %#lx", v);
    OK(NMC_GetDOBit(dev, 64 + 16, &bit));
    CHECK(bit == 1, "DO bit 80 %d", bit);
    OK(NMC_IOModuleWr32Bit(dev, 2, 0, 0x12345678UL));
    EVENTUALLY(NMC_IOModuleRdOut16Bit(dev, 2, 0, &u16), u16 == 0x5678);
    OK(NMC_IOModuleRdOut16Bit(dev, 2, 1, &u16));
    CHECK(u16 == 0x1234, "high half %#x", u16);
    OK(NMC_IOModuleRd32Bit(dev, 2, 0, &u32));
    OK(NMC_GetDIGroup(dev, &v, 2));
    CHECK((long)u32 == v, "module inputs %#lx vs DI group 2 %#lx", u32, v);
    OK(NMC_IOModuleRd16Bit(dev, 2, 1, &u16));
    CHECK(u16 == ((u32 >> 16) & 0xFFFF), "inputs high half %#x", u16);
    CHECK(NMC_IOModuleSetEn(dev, 10, IOMODULE_TYPE_IO64) == RTN_ARG_RANGE, "module 10");
    CHECK(NMC_IOModuleSetEn(dev, 1, IOMODULE_TYPE_IO64) == RTN_ARG_RANGE, "module 1");
    CHECK(NMC_IOModuleSetEn(dev, 2, 3) == RTN_ARG_RANGE, "type 3");
    CHECK(NMC_IOModuleRd16Bit(dev, 2, 2, &u16) == RTN_ARG_RANGE, "offset 2");
    CHECK(NMC_IOModuleRd32Bit(dev, 2, 1, &u32) == RTN_ARG_RANGE, "32-bit offset 1");
    OK(NMC_IOModuleSetEn(dev, 3, IOMODULE_TYPE_IO64));
    CHECK(NMC_IOModuleRd16Bit(dev, 3, 0, &u16) == RTN_INVALID_CHANNEL, "module 3 absent");
    OK(NMC_GetIOModuleSts(dev, &u32));
    CHECK(u32 == 1, "module 3 absent yet answering: %#lx", u32);
    CHECK(NMC_IOModuleGetType(dev, 2, NULL) == RTN_NULL_POINTER, "NULL type");

    /* Identity. */
    OK(NMC_DevReadID(dev, id));
    CHECK(strcmp(id, "CARD1") == 0, "ID %s", id);
    OK(NMC_GetUID(dev, &uid));
    OK(NMC_GetCardInfo(dev, &info));
    CHECK(uid != 0 && uid == info.uid[0], "UID %#lx vs card %#lx", uid, info.uid[0]);
    OK(NMC_GetMtLibVersion(dev, &version));
    CHECK(strncmp(version.strVer, "mcemu ", 6) == 0, "version %s", version.strVer);
    CHECK(NMC_DevReadID(dev, NULL) == RTN_NULL_POINTER, "NULL ID");
    CHECK(NMC_GetUID(x, &uid) == RTN_WRONG_HANDLE_KIND, "axis handle");

    printf("ok\n");
    return 0;
}
