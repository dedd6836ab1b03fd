/* test_view_util: what the windows share that needs no window: pass names
 * as the panel shows them. */
#include "check.h"
#include "support.h"
#include "view_script.h"
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

/* A script is read whole, up to its line limit: a huge file is refused, not
 * held in memory. */
static void test_script_line_limit(void) {
    if (!scratch_create("script")) {
        CHECK(false);
        return;
    }
    const char *path = scratch_path("s.txt");
    char err[512] = "";
    for (int n = VIEW_SCRIPT_MAX_LINES; n <= VIEW_SCRIPT_MAX_LINES + 1; n++) {
        FILE *f = fopen(path, "w");
        CHECK(f != NULL);
        if (!f) break;
        for (int i = 0; i < n; i++) fputs("frames 1\n", f);
        fclose(f);
        view_script *s = view_script_load(path, err, sizeof err);
        CHECK_MSG((s != NULL) == (n == VIEW_SCRIPT_MAX_LINES), "%d lines: %s", n, err);
        view_script_free(s);
    }
    CHECK_STR_CONTAINS(err, "more than 65536 lines");
    scratch_remove();
}

int main(void) {
    RUN(test_pass_names_read_as_the_glib);
    RUN(test_script_line_limit);
    return check_summary();
}
