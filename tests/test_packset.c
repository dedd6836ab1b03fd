/* test_packset: what the view's Setting combo reads from bench.txt —
 * each setting's comment (its tooltip) and the menu's order (default,
 * paper, the rest) — in text written here and in the packs' own files. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "packset.h"

#ifndef TARN_SOURCE_DIR
#define TARN_SOURCE_DIR "."
#endif

static const char *text =
    "# header: not any setting's\n"
    "colour #2ca02c\n"
    "\n"
    "fast     W.STEPS=8            # fewer steps\n"
    "# the paper's own: its method\n"
    "# and its constants\n"
    "paper    W.EXACT=0 W.uK=0.5\n"
    "default                       # the pack's defaults\n"
    "# a block that a blank line ends\n"
    "\n"
    "plain    W.uK=1\n"
    "hashes   W.uK=2   ## two hashes, trailing spaces   \n"
    "buffer fresnel W.DEBUG=1      # not a setting\n";

static void test_comments(void) {
    packset_bench b;
    char err[512] = "";
    CHECK_MSG(packset_bench_parse(text, "t/bench.txt", &b, err, sizeof err), "%s", err);
    CHECK_EQ(b.n, 5);
    const packset_setting *s;
    CHECK((s = packset_setting_named(&b, "fast")) && strcmp(s->comment, "fewer steps") == 0);
    CHECK((s = packset_setting_named(&b, "paper")) &&
          strcmp(s->comment, "the paper's own: its method and its constants") == 0 && s->nassign == 2);
    CHECK((s = packset_setting_named(&b, "default")) && strcmp(s->comment, "the pack's defaults") == 0);
    CHECK((s = packset_setting_named(&b, "plain")) && s->comment[0] == '\0');
    CHECK((s = packset_setting_named(&b, "hashes")) && strcmp(s->comment, "two hashes, trailing spaces") == 0);
    CHECK(packset_setting_named(&b, "fresnel") == NULL && packset_setting_named(&b, "nope") == NULL);
    CHECK(b.has_colour);
    packset_bench_free(&b);
}

static void test_menu_order(void) {
    packset_bench b;
    CHECK(packset_bench_parse(text, "t/bench.txt", &b, NULL, 0));
    int order[8];
    int n = packset_menu(&b, order);
    const char *want[] = { "default", "paper", "fast", "plain", "hashes" };
    CHECK_EQ(n, 5);
    for (int i = 0; i < n && i < 5; i++)
        CHECK_MSG(order[i] >= 0 && strcmp(b.settings[order[i]].name, want[i]) == 0, "row %d: %s", i,
                  order[i] >= 0 ? b.settings[order[i]].name : "(implicit default)");
    packset_bench_free(&b);

    /* no `default` line: the pack's defaults first, as index -1 */
    CHECK(packset_bench_parse("exact W.E=1\nschlick W.E=0\n", "x", &b, NULL, 0));
    n = packset_menu(&b, order);
    CHECK(n == 3 && order[0] == -1 && order[1] == 0 && order[2] == 1);
    packset_bench_free(&b);
}

/* Every pack's bench.txt parses cleanly; the three seeds keep the paper's
 * setting with a comment saying what it is, second in the menu. */
static void test_packs_files(void) {
    packset_name names[PACKSET_MAX];
    int np = packset_list(TARN_SOURCE_DIR, names, PACKSET_MAX);
    CHECK_GE(np, 4);
    int papers = 0;
    for (int p = 0; p < np; p++) {
        packset_bench b;
        char err[2048] = "";
        CHECK_MSG(packset_bench_load(TARN_SOURCE_DIR, names[p], &b, err, sizeof err), "%s: %s", names[p], err);
        int *order = calloc((size_t)b.n + 1, sizeof *order);
        int n = packset_menu(&b, order);
        CHECK(n == b.n || n == b.n + 1);
        CHECK(order[0] < 0 || strcmp(b.settings[order[0]].name, "default") == 0);
        const packset_setting *paper = packset_setting_named(&b, "paper");
        if (paper) {
            papers++;
            CHECK_MSG(paper->comment[0], "%s: the paper row says nothing about itself", names[p]);
            CHECK(n > 1 && order[1] >= 0 && &b.settings[order[1]] == paper);
        }
        free(order);
        packset_bench_free(&b);
    }
    CHECK_MSG(papers >= 3, "natural, raymarch and caustic_tex each keep a paper row (%d found)", papers);
}

int main(void) {
    RUN(test_comments);
    RUN(test_menu_order);
    RUN(test_packs_files);
    return check_summary();
}
