/* test_obj: tarn's one OBJ reader (base/obj.h) against OBJ texts written
 * by hand, whose counts and indices are known: corner forms, negative
 * indices, polygons, colours, continued lines, a byte order mark and CRLF,
 * the options (positions only, the triangle limit, the largest number),
 * and errors that name the line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "obj.h"

static bool parse(obj_data *d, const char *text, const obj_opts *o, char *err, size_t errlen) {
    return obj_parse(d, text, strlen(text), "t.obj", o, err, errlen);
}

static void check_corner(const obj_data *d, int c, int v, int vt, int vn) {
    CHECK_MSG(d->corner[c].v == v && d->corner[c].vt == vt && d->corner[c].vn == vn,
              "corner %d: (%d %d %d), want (%d %d %d)", c, d->corner[c].v, d->corner[c].vt, d->corner[c].vn, v, vt,
              vn);
}

/* Four squares' worth of records, one face per corner form, then a
 * pentagon in negative indices. */
static void test_counts_and_indices(void) {
    const char *text =
        "# a hand-written OBJ\n"
        "mtllib m.mtl\no thing\ng a\ns 1\nusemtl x\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 2 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1 0\nvt 0.25\n"
        "vn 0 0 1\nvn 0 0 -2\n"
        "f 1 2 3\n"                    /* v */
        "f 1/1 3/3 4/4\n"              /* v/vt */
        "f 1//2 2//2 3//1\n"           /* v//vn */
        "f 2/2/1 3/3/1 4/4/2 1/1/1\n"  /* v/vt/vn, a quad */
        "f -5 -4 -3 -1 -2\n";          /* negative: 1 2 3 5 4, a pentagon */
    obj_data d;
    char err[256] = "";
    CHECK_MSG(parse(&d, text, NULL, err, sizeof err), "%s", err);
    CHECK_EQ(d.nv, 5);
    CHECK_EQ(d.nvt, 4);
    CHECK_EQ(d.nvn, 2);
    CHECK_EQ(d.nface, 5);
    CHECK_EQ(d.ncorner, 3 + 3 + 3 + 4 + 5);
    CHECK_EQ(d.ntri, 1 + 1 + 1 + 2 + 3);
    CHECK(d.color == NULL);
    int first[] = { 0, 3, 6, 9, 13, 18 };
    for (int f = 0; f <= 5; f++) CHECK_EQ(d.face_first[f], first[f]);
    check_corner(&d, 0, 0, -1, -1);
    check_corner(&d, 2, 2, -1, -1);
    check_corner(&d, 3, 0, 0, -1);
    check_corner(&d, 5, 3, 3, -1);
    check_corner(&d, 6, 0, -1, 1);
    check_corner(&d, 8, 2, -1, 0);
    check_corner(&d, 9, 1, 1, 0);
    check_corner(&d, 12, 0, 0, 0);
    int neg[5] = { 0, 1, 2, 4, 3 };
    for (int c = 0; c < 5; c++) check_corner(&d, 13 + c, neg[c], -1, -1);
    CHECK(d.v[3 * 4] == 0.5 && d.v[3 * 4 + 1] == 2 && d.v[3 * 4 + 2] == 0);
    CHECK(d.vt[2 * 2] == 1 && d.vt[2 * 2 + 1] == 1);         /* w dropped */
    CHECK(d.vt[2 * 3] == 0.25 && d.vt[2 * 3 + 1] == 0);      /* a missing v is 0 */
    CHECK(d.vn[3 * 1 + 2] == -2);                            /* as written, not normalised */
    obj_free(&d);
    CHECK(d.v == NULL && d.nv == 0 && d.corner == NULL);
    obj_free(&d);   /* twice: safe */
}

/* Negative indices count back from the last element defined so far, not
 * from the end of the file. */
static void test_negative_indices_are_relative(void) {
    const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf -3/-1 -2/-1 -1/-1\n"
                       "v 5 5 5\nvt 1 1\nf -4 -1 -2/-1\n";
    obj_data d;
    char err[256] = "";
    CHECK_MSG(parse(&d, text, NULL, err, sizeof err), "%s", err);
    CHECK_EQ(d.nface, 2);
    check_corner(&d, 0, 0, 0, -1);
    check_corner(&d, 2, 2, 0, -1);
    check_corner(&d, 3, 0, -1, -1);
    check_corner(&d, 4, 3, -1, -1);
    check_corner(&d, 5, 2, 1, -1);
    obj_free(&d);
}

/* Colours (x y z r g b), w, a continued line, a BOM, CRLF, a comment after
 * a statement, a face with empty vt and vn parts. */
static void test_text_forms(void) {
    const char *text = "\xEF\xBB\xBFv 0 0 0 1\r\n"
                       "v 1 0 0 0.5 0.25 0.125\r\n"
                       "v 0 1 \\\r\n0 # continued\r\n"
                       "f 1/ 2// \\\n 3   # a comment\r\n"
                       "\n\n";
    obj_data d;
    char err[256] = "";
    CHECK_MSG(parse(&d, text, NULL, err, sizeof err), "%s", err);
    CHECK_EQ(d.nv, 3);
    CHECK_EQ(d.nface, 1);
    CHECK(d.color != NULL);
    if (d.color) {
        CHECK(d.color[0] == 1 && d.color[1] == 1 && d.color[2] == 1);   /* before the first colour: white */
        CHECK(d.color[3] == 0.5 && d.color[4] == 0.25 && d.color[5] == 0.125);
        CHECK(d.color[6] == 1 && d.color[7] == 1 && d.color[8] == 1);
    }
    CHECK(d.v[3 * 2 + 1] == 1 && d.v[3 * 2 + 2] == 0);
    check_corner(&d, 0, 0, -1, -1);
    check_corner(&d, 1, 1, -1, -1);
    check_corner(&d, 2, 2, -1, -1);
    obj_free(&d);

    /* not NUL-terminated: only len bytes are read */
    const char buf[] = { 'v', ' ', '1', ' ', '2', ' ', '3', '4', '5' };
    CHECK(obj_parse(&d, buf, 7, "t.obj", NULL, err, sizeof err) && d.nv == 1 && d.v[2] == 3);
    obj_free(&d);
    /* empty and NULL text: no faces, no error */
    CHECK(obj_parse(&d, NULL, 0, "t.obj", NULL, err, sizeof err) && d.nface == 0);
    CHECK(parse(&d, "# only a comment\n", NULL, err, sizeof err) && d.nface == 0 && d.nv == 0);
}

static void expect_error(const char *text, const obj_opts *o, int line, const char *phrase) {
    obj_data d;
    char err[512] = "";
    CHECK_MSG(!obj_parse(&d, text, strlen(text), "t.obj", o, err, sizeof err), "parsed: %s", text);
    CHECK(d.v == NULL && d.corner == NULL && d.nv == 0 && d.nface == 0);
    char want[64];
    if (line > 0) snprintf(want, sizeof want, "t.obj:%d: ", line);
    else snprintf(want, sizeof want, "t.obj: ");
    CHECK_STR_CONTAINS(err, want);
    CHECK_STR_CONTAINS(err, phrase);
}

static void test_errors_name_the_line(void) {
    const char *tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    /* after three vertices: what follows, the line it is on, what is said */
    static const struct { const char *text; int line; const char *phrase; } faces[] = {
        { "# fine\nf 0 1 2\n", 5, "index 0 (OBJ indices start at 1)" },
        { "f 1 2 4\n", 4, "vertex index 4 out of range" },
        { "f -1 -2 -4\n", 4, "does not exist (3 defined so far" },
        { "vt 0 0\nf 1/2 2/1 3/1\n", 5, "texture coordinate index 2 out of range" },
        { "f 1//1 2//1 3//1\n", 4, "normal index 1 out of range" },
        { "f 1/1/1/1 2 3\n", 4, "bad face vertex '1/1/1/1'" },
        { "f 1 2 3x\n", 4, "bad vertex index '3x'" },
        { "f 1 2 99999999999999999999999\n", 4, "bad vertex index" },
        { "f 1 2\n", 4, "at least 3 vertices, got 2" },
        { "f /1 2 3\n", 4, "empty vertex index" },
        { "f 1 \\\n2 \\\n7\nf 1 2 3\n", 4, "out of range" },   /* a continued statement: its first line */
    };
    for (size_t k = 0; k < sizeof faces / sizeof faces[0]; k++) {
        char buf[256];
        snprintf(buf, sizeof buf, "%s%s", tri, faces[k].text);
        expect_error(buf, NULL, faces[k].line, faces[k].phrase);
    }
    expect_error("v 0 0 0\nv 1 zero 0\n", NULL, 2, "bad number 'zero'");
    expect_error("v nan 0 0\n", NULL, 1, "bad number 'nan'");
    expect_error("v 1e999 0 0\n", NULL, 1, "bad number");
    expect_error("v 1 2\n", NULL, 1, "'v' needs 3 to 7 numbers, got 2");
    expect_error("v 1 2 3 4 5 6 7 8\n", NULL, 1, "'v' needs 3 to 7 numbers, got 8");
    expect_error("vn 1 2\n", NULL, 1, "'vn' needs 3 numbers, got 2");
    expect_error("vt\n", NULL, 1, "'vt' needs 1 to 3 numbers, got 0");
    expect_error("v 0 0 0\nthis is not obj\n", NULL, 2, "unknown statement 'this'");
    expect_error("v 0 0 0\r\n\r\nv 0 \x01 0\r\n", NULL, 3, "bad number '?'");
    const char nul[] = "v 0 0 0\nv 1 0 0\nv 0\0 1 0\n";
    obj_data d;
    char err[256] = "";
    CHECK(!obj_parse(&d, nul, sizeof nul - 1, "t.obj", NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, "t.obj:3: binary data (a NUL byte), not text");
    /* err may be NULL; name may be NULL */
    CHECK(!obj_parse(&d, "f 1 2 3\n", 8, "t.obj", NULL, NULL, 0));
    CHECK(!obj_parse(&d, "f 1 2 3\n", 8, NULL, NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, "(null):1: ");
    /* a long junk token is shown short */
    char big[3000];
    memset(big, 'x', sizeof big - 1);
    big[sizeof big - 1] = 0;
    CHECK(!parse(&d, big, NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, "t.obj:1: unknown statement 'xxxxxxxxxxxxxxxxxxxxxxxx...'");
}

static void test_options(void) {
    const char *text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/9/9 2/9/9 3/9/9 4/9/9\nf 1 2 3\n";
    obj_data d;
    char err[256] = "";
    /* texture coordinates and normals that do not exist: refused ... */
    CHECK(!parse(&d, text, NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, "t.obj:5: texture coordinate index 9 out of range");
    /* ... unless only positions are read */
    obj_opts po = { .positions_only = true };
    CHECK_MSG(parse(&d, text, &po, err, sizeof err), "%s", err);
    CHECK(d.nface == 2 && d.ntri == 3);
    for (int c = 0; c < d.ncorner; c++) CHECK(d.corner[c].vt == -1 && d.corner[c].vn == -1);
    obj_free(&d);
    /* the triangle limit: at the line that passes it */
    obj_opts lim = { .positions_only = true, .max_triangles = 2 };
    CHECK(!parse(&d, text, &lim, err, sizeof err));
    CHECK_STR_CONTAINS(err, "t.obj:6: more than 2 triangles");
    lim.max_triangles = 3;
    CHECK(parse(&d, text, &lim, err, sizeof err));
    obj_free(&d);
    /* the largest number */
    obj_opts fl = { .max_abs = 1e3 };
    CHECK(!parse(&d, "v 0 0 0\nv 0 -1001 0\n", &fl, err, sizeof err));
    CHECK_STR_CONTAINS(err, "t.obj:2: number '-1001' too large here");
    CHECK(parse(&d, "v 0 0 0\nv 0 -1000 0\n", &fl, err, sizeof err));
    obj_free(&d);
}

static void test_read_file(void) {
    char dir[] = "/tmp/tarn-test-obj-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char path[512];
    snprintf(path, sizeof path, "%s/q.obj", dir);
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    fputs("\xEF\xBB\xBFv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nf 1 2 3 4\r\nf 1 2 q\r\n", f);
    fclose(f);
    obj_data d;
    char err[512] = "", want[600];
    CHECK(!obj_read(&d, path, NULL, err, sizeof err));
    snprintf(want, sizeof want, "%s:6: bad vertex index 'q'", path);
    CHECK_STR_CONTAINS(err, want);
    CHECK(!obj_read(&d, dir, NULL, err, sizeof err));   /* a folder */
    snprintf(want, sizeof want, "%s: ", dir);
    CHECK_STR_CONTAINS(err, want);
    snprintf(want, sizeof want, "%s/missing.obj", dir);
    CHECK(!obj_read(&d, want, NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, want);
    CHECK(!obj_read(&d, NULL, NULL, err, sizeof err));
    CHECK_STR_CONTAINS(err, "no file name");
    f = fopen(path, "wb");
    if (f) {
        fputs("v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nf 1 2 3\r\n", f);
        fclose(f);
    }
    CHECK_MSG(obj_read(&d, path, NULL, err, sizeof err), "%s", err);
    CHECK(d.nface == 1 && d.nv == 3);
    obj_free(&d);
    unlink(path);
    rmdir(dir);
}

int main(void) {
    RUN(test_counts_and_indices);
    RUN(test_negative_indices_are_relative);
    RUN(test_text_forms);
    RUN(test_errors_name_the_line);
    RUN(test_options);
    RUN(test_read_file);
    return check_summary();
}
