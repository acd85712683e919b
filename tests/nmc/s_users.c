/* Users, command debugging and NMC_UserPrint (digest 001 §2.20 (12), (22)-(24), (32), §4.9):
 * USER1's password and login beside the system password, the debug output written to a file. */
#include <string.h>
#include "check.h"

int main(void) {
    HAND dev = 0, ax = 0;
    short sts = 0;
    char user[] = "USER1", other[] = "USER2", pw[] = "123456", wrong[] = "654321";
    char fresh[] = "u5er", toolong[] = "0123456789abcdef", empty[] = "";
    char logname[] = "s_users_debug.txt", badlog[] = "/nonexistent-dir/debug.txt";
    char hello[] = "hello from s_users";
    char text[4096];
    size_t n;
    FILE *f;

    OK(NMC_DevOpen(0, &dev));
    OK(NMC_MtOpen(dev, 0, &ax));

    /* Login: only USER1, only with its password; logout only once logged in. */
    CHECK(NMC_UserLogout(dev, user) == RTN_INVALID_STATE, "logout before login");
    CHECK(NMC_UserLogin(dev, user, wrong) == RTN_PASSWORD, "wrong password");
    CHECK(NMC_UserLogin(dev, other, pw) == RTN_ARG_RANGE, "USER2");
    CHECK(NMC_UserLogin(dev, NULL, pw) == RTN_NULL_POINTER, "NULL user");
    CHECK(NMC_UserLogin(ax, user, pw) == RTN_WRONG_HANDLE_KIND, "axis handle");
    OK(NMC_UserLogin(dev, user, pw));
    OK(NMC_UserLogout(dev, user));
    CHECK(NMC_UserLogout(dev, user) == RTN_INVALID_STATE, "second logout");
    CHECK(NMC_UserLogout(dev, other) == RTN_ARG_RANGE, "logout USER2");

    /* USER1's password, apart from the system password. */
    CHECK(NMC_UserSetPassword(dev, user, wrong, fresh) == RTN_PASSWORD, "set with wrong");
    CHECK(NMC_UserSetPassword(dev, user, pw, toolong) == RTN_ARG_RANGE, "16 characters");
    CHECK(NMC_UserSetPassword(dev, user, pw, empty) == RTN_ARG_RANGE, "empty");
    CHECK(NMC_UserSetPassword(dev, other, pw, fresh) == RTN_ARG_RANGE, "set USER2");
    OK(NMC_UserSetPassword(dev, user, pw, fresh));
    CHECK(NMC_UserLogin(dev, user, pw) == RTN_PASSWORD, "old password");
    OK(NMC_UserLogin(dev, user, fresh));
    OK(NMC_UserLogout(dev, user));
    OK(NMC_VerifyPassword(dev, pw)); /* the system password did not change */

    /* Command debugging to a file: one line per call, NMC_UserPrint's text among them. */
    remove(logname);
    CHECK(NMC_SetCmdDebug(5, empty) == RTN_ARG_RANGE, "enable 5");
    CHECK(NMC_SetCmdDebug(2, NULL) == RTN_NULL_POINTER, "NULL file");
    CHECK(NMC_SetCmdDebug(2, badlog) == RTN_FILE, "file in a missing directory");
    CHECK(NMC_SetCmdDebug(2, empty) == RTN_FILE, "empty file name");
    OK(NMC_SetCmdDebug(2, logname));
    OK(NMC_MtGetSts(ax, &sts));
    CHECK(NMC_UserLogin(dev, user, wrong) == RTN_PASSWORD, "wrong password, logged");
    OK(NMC_UserPrint(hello));
    OK(NMC_SetCmdDebug(0, empty));
    OK(NMC_MtGetSts(ax, &sts)); /* not logged: debugging is off */
    CHECK(NMC_UserPrint(NULL) == RTN_NULL_POINTER, "NULL msg");

    f = fopen(logname, "r");
    CHECK(f != NULL, "no debug file");
    n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    CHECK(strstr(text, "NMC_MtGetSts(") != NULL, "no MtGetSts line in: %s", text);
    CHECK(strstr(text, "NMC_UserLogin(") != NULL && strstr(text, "= 36") != NULL,
          "no refused login line in: %s", text);
    CHECK(strstr(text, hello) != NULL, "no UserPrint text in: %s", text);
    {
        /* One MtGetSts line only: the second call came after debugging was turned off. */
        const char *first = strstr(text, "NMC_MtGetSts(");
        CHECK(strstr(first + 1, "NMC_MtGetSts(") == NULL, "MtGetSts logged twice: %s", text);
    }
    remove(logname);

    printf("ok\n");
    return 0;
}
