/* The three headers compile clean as C and as C++ (-Wall -Wextra -Werror -pedantic). */
#include "mtn_lib20.h"
#include "mtn_lib20_ext.h"
#include "mtn_lib20_err.h"

int main(void) {
    TPtpPara p = {0.5, 0.5, 0, 0, 0, {0, 0, 0}};
    HAND h = 0;
    (void)p;
    (void)h;
    return RTN_CMD_SUCCESS;
}
