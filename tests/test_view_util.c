/* test_view_util: what the windows share that needs no window: pass names
 * as the panel shows them. */
#include "check.h"
#include "view_util.h"

static void test_pass_names_read_as_the_glib(void) {
    char out[96];
    view_pass_name("pass:65 10", out, sizeof out);
    CHECK(strcmp(out, "RenderToTexture 10 (line 65)") == 0);
    view_pass_name("pass:21 8 9", out, sizeof out);
    CHECK(strcmp(out, "RenderToTexture 8 9 (line 21)") == 0);
    view_pass_name("screen:24", out, sizeof out);
    CHECK(strcmp(out, "to the screen (line 24)") == 0);
    view_pass_name("screen", out, sizeof out);      /* before any command */
    CHECK(strcmp(out, "screen") == 0);
    view_pass_name("pass:7 1 2 3 4 5 6 7 8", out, 12);   /* cut, never overrun */
    CHECK(strlen(out) == 11);
}

int main(void) {
    RUN(test_pass_names_read_as_the_glib);
    return check_summary();
}
