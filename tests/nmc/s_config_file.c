/* NMC_SaveConfigToFile / NMC_LoadConfigFromFile (digest 001 §1.5, §2.2 (9), §2.20 (14)): the
 * configuration as a file on the host, in the program's directory as the manual's example
 * has it ("GCN800.cfg"): limits, alarm, pulse mode, encoder mode saved, changed, loaded back.
 * Bad paths and files get RTN_FILE and change nothing. */
#include <string.h>
#include "check.h"

static void settings(HAND ax, short *v) {
    OK(NMC_MtGetLmtOnOff(ax, &v[0], &v[1]));
    OK(NMC_MtGetLmtSns(ax, &v[2], &v[3]));
    OK(NMC_MtGetAlarmOnOff(ax, &v[4]));
    OK(NMC_MtGetAlarmSns(ax, &v[5]));
    OK(NMC_MtGetStepMode(ax, &v[6], &v[7]));
}

int main(void) {
    HAND dev = 0, ax = 0;
    short saved[8], now[8];
    unsigned short enc = 0;
    char file[] = "s_config_file.cfg", garbage_file[] = "s_config_garbage.cfg";
    char missing[] = "s_config_missing.cfg", baddir[] = "/nonexistent-dir/x.cfg", empty[] = "";
    char head[2] = {0, 0};
    FILE *f;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 1, &ax));

    /* A configuration unlike the fixture's. */
    OK(NMC_MtSetLmtCfg(ax, 0, 1, 1, 0));
    OK(NMC_MtSetAlarmCfg(ax, 1, 1));
    OK(NMC_MtSetStepMode(ax, 1, 1));
    OK(NMC_SetEncMode(dev, 1, 0x0003));
    settings(ax, saved);
    remove(file);
    OK(NMC_SaveConfigToFile(dev, file));
    f = fopen(file, "r");
    CHECK(f != NULL, "%s not written", file);
    CHECK(fread(head, 1, 1, f) == 1 && head[0] == '{', "the file starts %s", head);
    fclose(f);

    /* Changed, then loaded back. */
    OK(NMC_MtSetLmtCfg(ax, 1, 0, 0, 1));
    OK(NMC_MtSetAlarmCfg(ax, 0, 0));
    OK(NMC_MtSetStepMode(ax, 0, 0));
    OK(NMC_SetEncMode(dev, 1, 0x0000));
    settings(ax, now);
    CHECK(memcmp(now, saved, sizeof now) != 0, "the changes did not change anything");
    OK(NMC_LoadConfigFromFile(dev, file));
    EVENTUALLY(NMC_MtGetLmtOnOff(ax, &now[0], &now[1]), now[0] == saved[0] && now[1] == saved[1]);
    settings(ax, now);
    CHECK(memcmp(now, saved, sizeof now) == 0,
          "loaded: lmt %d %d sns %d %d alarm %d %d step %d %d; saved: %d %d %d %d %d %d %d %d",
          now[0], now[1], now[2], now[3], now[4], now[5], now[6], now[7], saved[0], saved[1],
          saved[2], saved[3], saved[4], saved[5], saved[6], saved[7]);
    OK(NMC_GetEncMode(dev, 1, &enc));
    CHECK(enc == 0x0003, "encoder mode %#x", enc);

    /* Bad paths and files: RTN_FILE, nothing changed. */
    OK(NMC_MtSetStepMode(ax, 0, 0));
    remove(missing);
    CHECK(NMC_LoadConfigFromFile(dev, missing) == RTN_FILE, "missing file");
    CHECK(NMC_LoadConfigFromFile(dev, empty) == RTN_FILE, "empty path");
    CHECK(NMC_LoadConfigFromFile(dev, NULL) == RTN_NULL_POINTER, "NULL path");
    f = fopen(garbage_file, "w");
    CHECK(f != NULL, "cannot write %s", garbage_file);
    fputs("[GCN800]\naxis0.limit=1\n", f);
    fclose(f);
    CHECK(NMC_LoadConfigFromFile(dev, garbage_file) == RTN_FILE, "a GCS .cfg");
    f = fopen(garbage_file, "w");
    CHECK(f != NULL, "cannot write %s", garbage_file);
    fputs("{\"axes\":[{\"params\":{\"no_such_param\":1},\"step_inv\":1,\"step_mode\":1,"
          "\"step_filter\":0,\"vel_filter\":0}],\"enc_mode\":{}}", f);
    fclose(f);
    CHECK(NMC_LoadConfigFromFile(dev, garbage_file) == RTN_FILE, "unknown parameter");
    OK(NMC_MtGetStepMode(ax, &now[6], &now[7]));
    CHECK(now[6] == 0 && now[7] == 0, "a refused file changed the pulse mode: %d %d", now[6], now[7]);
    CHECK(NMC_SaveConfigToFile(dev, baddir) == RTN_FILE, "missing directory");
    CHECK(NMC_SaveConfigToFile(ax, file) == RTN_WRONG_HANDLE_KIND, "axis handle");
    CHECK(NMC_LoadConfigFromFile(ax, file) == RTN_WRONG_HANDLE_KIND, "axis handle (load)");
    remove(garbage_file);
    remove(file);

    printf("ok\n");
    return 0;
}
