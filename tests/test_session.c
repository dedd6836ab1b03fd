/* test_session: the session file (ui/session.h) without a window or GL:
 * the parser keeps good lines and turns every bad one into a file:line
 * diag (never a crash, whatever the bytes); the recorder writes what
 * changed and reads back as the same events; the replay's simulated clock
 * is the header's time plus the seconds not paused (a closed form). */
#include <stdint.h>
#include <stdlib.h>

#include "check.h"
#include "session.h"
#include "support.h"

static const char good[] =
    "# a comment\n"
    "tarn-session 1\n"
    "scene /abs/pond.glib\n"
    "pack natural\n"
    "size 640 360\n"
    "time 2.5\n"
    "t=0.000 camera 0 0.5 0 12 0.3 0.4\n"
    "t=1.250 slider Water uWaveAmp 0.4   # the slider\n"
    "t=1.500 colour Water uDeep 0.1 0.2 0.3\n"
    "t=1.500 checkbox Water uFoam 0\n"
    "t=2 define Water STEPS 8\n"
    "t=2.5 drag Water uWind 1 -1\n"
    "t=3 pause 1\n"
    "t=4 pack basic\n"
    "t=4.5 setting paper\n"
    "t=5.5 end\n";

static bool has_diag(const diag_list *dl, int line, const char *text) {
    for (int i = 0; i < dl->n; i++)
        if (dl->d[i].line == line && strstr(dl->d[i].text, text) && strcmp(dl->d[i].file, "s.session") == 0)
            return true;
    return false;
}

static void test_parses_header_and_every_kind(void) {
    session s = {0};
    diag_list dl = {0};
    CHECK(session_parse(&s, good, "s.session", &dl));
    CHECK_EQ(dl.n, 0);
    CHECK_STR_EQ(s.scene, "/abs/pond.glib");
    CHECK_STR_EQ(s.pack, "natural");
    CHECK(s.width == 640 && s.height == 360);
    CHECK_NEAR(s.time_s, 2.5, 0);
    CHECK_EQ(s.n, 10);
    session_kind kinds[] = { SESSION_CAMERA, SESSION_SLIDER, SESSION_COLOUR, SESSION_CHECKBOX, SESSION_DEFINE,
                             SESSION_DRAG, SESSION_PAUSE, SESSION_PACK, SESSION_SETTING, SESSION_END };
    for (int i = 0; i < 10 && i < s.n; i++) CHECK_EQ(s.events[i].kind, kinds[i]);
    CHECK(s.n < 9 || strcmp(s.events[8].args, "paper") == 0);
    CHECK_NEAR(s.events[1].t, 1.25, 0);
    CHECK_EQ(s.events[1].line, 8);
    CHECK_STR_EQ(s.events[1].args, "Water uWaveAmp 0.4");
    CHECK_NEAR(session_duration(&s), 5.5, 0);
    session_free(&s);
    diag_list_free(&dl);
}

/* A relative scene is found beside the session file, not the cwd. */
static void test_relative_scene_is_beside_the_file(void) {
    session s = {0};
    diag_list dl = {0};
    CHECK(session_parse(&s, "tarn-session 1\nscene pond.glib\n", "dir/sub/s.session", &dl));
    CHECK_STR_EQ(s.scene, "dir/sub/pond.glib");
    CHECK(s.n == 0 && session_duration(&s) == 0);
    session_free(&s);
    diag_list_free(&dl);
}

static void test_bad_lines_are_diags_at_their_line(void) {
    static const char bad[] =
        "tarn-session 1\n"                       /* 1 */
        "scene a.glib\n"                         /* 2 */
        "size 10\n"                              /* 3 */
        "t=1 slider Water uA 0.5\n"              /* 4: kept */
        "t=0.5 slider Water uA 0.1\n"            /* 5: before line 4 */
        "t=x slider Water uA 1\n"                /* 6 */
        "t=2 wobble 3\n"                         /* 7 */
        "t=2 slider Water\n"                     /* 8 */
        "t=2 slider Water uA nan\n"              /* 9 */
        "t=2 camera 1 2 3\n"                     /* 10 */
        "t=2 pause maybe\n"                      /* 11 */
        "frobnicate\n"                           /* 12 */
        "t=2 camera 0 0 0 -1 0 0\n"              /* 13 */
        "t=2 setting a/b\n"                      /* 14 */
        "t=3 end\n";                             /* 15: kept */
    session s = {0};
    diag_list dl = {0};
    CHECK(!session_parse(&s, bad, "s.session", &dl));
    CHECK(has_diag(&dl, 3, "size wants W H"));
    CHECK(has_diag(&dl, 5, "comes before"));
    CHECK(has_diag(&dl, 6, "expected t=SECONDS"));
    CHECK(has_diag(&dl, 7, "unknown event"));
    CHECK(has_diag(&dl, 8, "expected PROGRAM NAME"));
    CHECK(has_diag(&dl, 9, "numbers"));
    CHECK(has_diag(&dl, 10, "camera wants"));
    CHECK(has_diag(&dl, 11, "pause wants"));
    CHECK(has_diag(&dl, 12, "unknown line"));
    CHECK(has_diag(&dl, 13, "distance > 0"));
    CHECK(has_diag(&dl, 14, "setting wants a setting's name"));
    CHECK_EQ(dl.nerrors, 11);
    CHECK_EQ(s.n, 2);
    CHECK(s.n == 2 && s.events[0].line == 4 && s.events[1].kind == SESSION_END);
    session_free(&s);
    diag_list_free(&dl);
}

static void test_not_a_session_stops_at_line_one(void) {
    const char *texts[] = { "##OpenGL GLIB\nscene x\n", "tarn-session 2\nscene x\n", "", "\n# only\n",
                            "tarn-session 1\nt=1 end\n" };
    const char *why[] = { "not a tarn session", "version 2", "empty", "empty", "no `scene" };
    for (int i = 0; i < 5; i++) {
        session s = {0};
        diag_list dl = {0};
        CHECK(!session_parse(&s, texts[i], "s.session", &dl));
        CHECK_EQ(dl.n, 1);
        CHECK_STR_CONTAINS(dl.n ? dl.d[0].text : "", why[i]);
        if (i < 4) CHECK_EQ(s.n, 0);
        session_free(&s);
        diag_list_free(&dl);
    }
}

/* Random bytes, cut good files and one over-long line: diags, no crash
 * (ASan watches the reads). */
static void test_any_bytes_never_crash(void) {
    uint32_t seed = 12345;
    char buf[600];
    for (int round = 0; round < 2000; round++) {
        size_t n = (size_t)(round % 500);
        if (round % 2) {
            memcpy(buf, good, n < sizeof good ? n : sizeof good);
            if (n > sizeof good - 1) n = sizeof good - 1;
            seed = seed * 1664525u + 1013904223u;
            if (n) buf[(seed >> 8) % n] = (char)(seed >> 16);   /* one byte changed */
        } else
            for (size_t i = 0; i < n; i++) {
                seed = seed * 1664525u + 1013904223u;
                static const char alphabet[] = " \n=t.0123456789-eslidrcamp#\t\x01";
                buf[i] = alphabet[(seed >> 16) % (sizeof alphabet - 1)];
            }
        buf[n] = '\0';
        session s = {0};
        diag_list dl = {0};
        session_parse(&s, buf, "s.session", &dl);
        for (int i = 1; i < s.n; i++) CHECK_GE(s.events[i].t, s.events[i - 1].t);
        session_free(&s);
        diag_list_free(&dl);
    }
    char *longline = malloc(5000);
    snprintf(longline, 5000, "tarn-session 1\nscene a\nt=1 slider P u ");
    size_t k = strlen(longline);
    while (k < 4990) longline[k++] = '1';
    longline[k] = '\0';
    session s = {0};
    diag_list dl = {0};
    CHECK(!session_parse(&s, longline, "s.session", &dl));
    CHECK(has_diag(&dl, 3, "longer than"));
    session_free(&s);
    diag_list_free(&dl);
    free(longline);
}

static void test_load_missing_file_is_a_diag(void) {
    session s = {0};
    diag_list dl = {0};
    CHECK(!session_load(&s, "/nonexistent/x.session", &dl));
    CHECK(dl.n == 1 && strstr(dl.d[0].text, "cannot read"));
    session_free(&s);
    diag_list_free(&dl);
}

/* ---- recording ---- */

static void entry(unif_set *set, const char *name, unif_widget w, bool define, int ncomp, float v) {
    unif_entry *e = &set->entries[set->n++];
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%s", name);
    e->widget = w;
    e->is_define = define;
    e->ncomp = ncomp;
    for (int i = 0; i < ncomp; i++) e->def[i] = e->value[i] = v;
}

/* Values changed before recording are its first events; afterwards only
 * what changes is written, with its kind; read back, the file is those
 * events in order, values exact to the float. */
static void test_recorder_writes_what_changed(void) {
    if (!scratch_create("session")) { CHECK(0); return; }
    unif_entry entries[5];
    unif_set set = { .program = "Water", .entries = entries, .cap = 5 };
    entry(&set, "uAmp", UNIF_WIDGET_SLIDER, false, 1, 0.5f);
    entry(&set, "uDeep", UNIF_WIDGET_COLOR, false, 3, 0.2f);
    entry(&set, "uFoam", UNIF_WIDGET_CHECKBOX, false, 1, 1);
    entry(&set, "STEPS", UNIF_WIDGET_SLIDER, true, 1, 4);
    entry(&set, "uFixed", UNIF_WIDGET_NONE, false, 1, 7);
    entries[0].value[0] = 0.1f;                    /* before recording */
    orbit cam = { .center = { 0, 0, 0 }, .up = { 0, 1, 0 }, .distance = 10, .yaw = 0, .pitch = 0.2f };
    session_header h = { .scene = "/x/pond.glib", .pack = "basic", .width = 320, .height = 240, .time_s = 1.5 };
    char err[512];
    const char *path = scratch_path("r.session");
    session_rec *rec = session_rec_start(path, &h, &set, 1, &cam, false, 100.0, err, sizeof err);
    CHECK_NE(rec, NULL);
    if (!rec) return;
    session_rec_frame(rec, &set, 1, &cam, false, 100.5);       /* nothing changed */
    entries[0].value[0] = 0.123456789f;
    entries[4].value[0] = 8;                                   /* fixed: never written */
    session_rec_frame(rec, &set, 1, &cam, false, 101.25);
    entries[1].value[1] = 0.9f;
    entries[2].value[0] = 0;
    entries[3].value[0] = 6;
    cam.yaw = 0.5f;
    session_rec_frame(rec, &set, 1, &cam, true, 102.0);
    session_rec_pack(rec, "natural", 102.5);
    session_rec_setting(rec, "paper", 102.75);
    int n = 0;
    CHECK(session_rec_stop(rec, 103.0, &n, err, sizeof err));
    CHECK_EQ(n, 10);

    session s = {0};
    diag_list dl = {0};
    CHECK(session_load(&s, path, &dl));
    diag_print(&dl, stderr);
    CHECK(strcmp(s.scene, "/x/pond.glib") == 0 && strcmp(s.pack, "basic") == 0);
    CHECK(s.width == 320 && s.height == 240 && s.time_s == 1.5);
    struct { double t; session_kind k; const char *args; } want[] = {
        { 0, SESSION_SLIDER, "Water uAmp 0.100000001" },
        { 0, SESSION_CAMERA, "0 0 0 10 0 0.200000003" },
        { 1.25, SESSION_SLIDER, "Water uAmp 0.123456791" },
        { 2, SESSION_COLOUR, "Water uDeep 0.200000003 0.899999976 0.200000003" },
        { 2, SESSION_CHECKBOX, "Water uFoam 0" },
        { 2, SESSION_DEFINE, "Water STEPS 6" },
        { 2, SESSION_CAMERA, "0 0 0 10 0.5 0.200000003" },
        { 2, SESSION_PAUSE, "1" },
        { 2.5, SESSION_PACK, "natural" },
        { 2.75, SESSION_SETTING, "paper" },
        { 3, SESSION_END, "" },
    };
    CHECK_EQ(s.n, 11);
    for (int i = 0; i < 11 && i < s.n; i++) {
        CHECK_NEAR(s.events[i].t, want[i].t, 1e-9);
        CHECK_EQ(s.events[i].kind, want[i].k);
        CHECK_MSG(strcmp(s.events[i].args, want[i].args) == 0, "event %d: '%s'", i, s.events[i].args);
    }
    CHECK_EQ((float)strtod("0.123456791", NULL), 0.123456789f);   /* %.9g gives the float back */
    session_free(&s);
    diag_list_free(&dl);
    CHECK_EQ(session_rec_start("/nonexistent/dir/r.session", &h, &set, 1, &cam, false, 0, err, sizeof err), NULL);
    CHECK_STR_CONTAINS(err, "/nonexistent/dir/r.session");
    scratch_remove();
}

/* ---- replay: the clock and the camera (no GL: these need no scene) ---- */

static void test_replay_clock_stops_while_paused(void) {
    static const char text[] =
        "tarn-session 1\nscene a.glib\ntime 10\n"
        "t=1 pause 1\n"
        "t=3 camera 1 2 3 4 0.5 0.25\n"
        "t=4 pause 0\n"
        "t=6 end\n";
    session s = {0};
    diag_list dl = {0};
    CHECK(session_parse(&s, text, "s.session", &dl));
    render_view home = { .eye = { 0, 0, 5 }, .center = { 0, 0, 0 }, .up = { 0, 1, 0 } };
    session_player p;
    session_player_start(&p, &s, home);
    float home_distance = p.cam.distance;
    /* sim(t) = 10 + t for t <= 1, 11 while paused (1..4), 11 + (t - 4) after */
    double ts[] = { 0, 0.5, 1, 2, 2.999, 3.5, 4, 5.25, 6 };
    double want[] = { 10, 10.5, 11, 11, 11, 11, 11, 12.25, 13 };
    for (int i = 0; i < 9; i++) {
        CHECK_NEAR(session_player_advance(&p, NULL, ts[i]), want[i], 1e-12);
        if (ts[i] < 3) CHECK_EQ(p.cam.distance, home_distance);
    }
    CHECK(p.cam.center[0] == 1 && p.cam.center[1] == 2 && p.cam.center[2] == 3);
    CHECK(p.cam.distance == 4 && p.cam.yaw == 0.5f && p.cam.pitch == 0.25f);
    CHECK(p.failed == 0 && !p.paused);
    session_free(&s);
    diag_list_free(&dl);
}

int main(void) {
    RUN(test_parses_header_and_every_kind);
    RUN(test_relative_scene_is_beside_the_file);
    RUN(test_bad_lines_are_diags_at_their_line);
    RUN(test_not_a_session_stops_at_line_one);
    RUN(test_any_bytes_never_crash);
    RUN(test_load_missing_file_is_a_diag);
    RUN(test_recorder_writes_what_changed);
    RUN(test_replay_clock_stops_while_paused);
    return check_summary();
}
