/* test_view_util: what the windows share that needs no window: pass names
 * as the panel shows them, why a reload happened. */
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

static void test_reload_cause_names_the_files(void) {
    char out[128];
    const char *one[] = { "/home/s/scenes/water.frag" };
    view_reload_cause(one, 1, out, sizeof out);
    CHECK_MSG(strcmp(out, "water.frag changed") == 0, "%s", out);
    const char *two[] = { "/a/water.frag", "scenes/lake.glib" };
    view_reload_cause(two, 2, out, sizeof out);
    CHECK_MSG(strcmp(out, "water.frag and lake.glib changed") == 0, "%s", out);
    const char *three[] = { "a.frag", "b.frag", "c.glsl" };
    view_reload_cause(three, 3, out, sizeof out);
    CHECK_MSG(strcmp(out, "a.frag, b.frag and c.glsl changed") == 0, "%s", out);
    const char *five[] = { "a.frag", "b.frag", "c.glsl", "d.glsl", "e.glib" };
    view_reload_cause(five, 5, out, sizeof out);
    CHECK_MSG(strcmp(out, "a.frag, b.frag and 3 more changed") == 0, "%s", out);
    view_reload_cause(NULL, 0, out, sizeof out);
    CHECK(out[0] == '\0');
    view_reload_cause(five, 5, out, 9);   /* cut, never overrun */
    CHECK(strlen(out) == 8);
}

int main(void) {
    RUN(test_pass_names_read_as_the_glib);
    RUN(test_reload_cause_names_the_files);
    return check_summary();
}
