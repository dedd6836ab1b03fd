/* cmd: the commands of the tarn program, one file each (cmd_NAME.c). Each
 * parses the arguments after its command word (argv[0] is the first of
 * them) into its lower layer's desc struct and calls it; main.c's table
 * names them. Only this layer reads argv, each command through its option
 * table (cmd_opt_table.h). Every command returns an exit code (exit_code.h)
 * and prints its usage for -h/--help. */
#ifndef TARN_CMD_H
#define TARN_CMD_H

#include <stdbool.h>
#include <stdio.h>

#include "exit_code.h"

int cmd_view(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_validate(int argc, char **argv);
int cmd_reference(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_compare_view(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_assets(int argc, char **argv);
int cmd_record(int argc, char **argv);
int cmd_sheet(int argc, char **argv);

/* compare with the streams given (tests): the table and "-" outputs and
 * --help go to out, messages to err. */
int cmd_compare_io(int argc, char **argv, FILE *out, FILE *err);

/* The commands' tables (cmd_opt_table.h): options, usage and man page. */
struct cmd_spec;
extern const struct cmd_spec cmd_view_spec, cmd_render_spec, cmd_validate_spec, cmd_reference_spec,
    cmd_compare_spec, cmd_compare_view_spec, cmd_bench_spec, cmd_assets_spec, cmd_record_spec, cmd_sheet_spec;

/* The usage texts (`tarn help NAME`, `tarn NAME --help`), from the tables. */
const char *cmd_view_usage(void);
const char *cmd_render_usage(void);
const char *cmd_validate_usage(void);
const char *cmd_reference_usage(void);
const char *cmd_compare_usage(void);
const char *cmd_compare_view_usage(void);
const char *cmd_bench_usage(void);
const char *cmd_assets_usage(void);
const char *cmd_record_usage(void);
const char *cmd_sheet_usage(void);

/* ---- shared by the command files (cmd_opts.c) ---- */

/* Each command's options are a table (cmd_opt_table.h): its parser, its
 * usage text and its man-page entries. */
#include "cmd_opt_table.h"

/* True when any argument is -h or --help. */
bool cmd_wants_help(int argc, char **argv);

/* A number in lo..hi (NaN and trailing text rejected); a whole number in
 * lo..hi. */
bool cmd_opt_range(const char *s, double lo, double hi, double *out);
bool cmd_opt_int(const char *s, int lo, int hi, int *out);

/* --msaa N: anti-aliasing samples 0..16 into a render_desc.samples value
 * (0 and 1: off, which is 1 there; zero there means the default). */
bool cmd_opt_msaa(const char *s, int *samples);

/* Is name a pack of tarn's (packs/NAME/pack.glib under tarn_root())? False
 * with "no pack 'X' in ROOT/packs: the packs are ..." in why, for a usage error (exit 2). */
bool cmd_opt_pack(const char *name, char *why, size_t whylen);
/* Images and videos that are kept are anti-aliased on every renderer
 * (issue #25); a live window keeps CMD_OPTION_MSAA's default. */
#define CMD_MSAA_STILL_DEFAULT 4

/* Option table entries that several commands share (cmd_opt_table.h), off
 * the place of the value in the command's desc: --pack NAME (view, render,
 * sheet), --msaa N of a live window (view) and of what is kept (render,
 * record, sheet), --verbose (view, render). */
#define CMD_OPTION_PACK(off) \
    { "--pack", .metavar = "NAME", .kind = CMD_PACK, .offset = (off), \
      .help = "draw the water with packs/NAME instead of the scene's Pack\n", \
      .man = "draw the water with\n" \
             ".BI packs/ NAME\n" \
             "instead of the scene's\n" \
             ".BR Pack .\n" }
#define CMD_OPTION_MSAA(off) \
    { "--msaa", .metavar = "N", .kind = CMD_MSAA, .offset = (off), \
      .help = "anti-aliasing: N samples per pixel, 0 or 1 off (default 4 on\n" \
              "a GPU, off on a CPU rasteriser such as llvmpipe: 3-4.5x the time)\n", \
      .man = "anti\\-aliasing: the screen passes are drawn with\n" \
             ".I N\n" \
             "samples per pixel (MSAA) and resolved; 0 or 1 turns it off (default 4 on\n" \
             "a GPU, or as many as it allows; off on a CPU rasteriser such as llvmpipe,\n" \
             "where 4 samples cost 3 to 4.5 times the frame).\n" }
#define CMD_OPTION_MSAA_STILL(off) \
    { "--msaa", .metavar = "N", .kind = CMD_MSAA, .offset = (off), \
      .help = "anti-aliasing: N samples per pixel, 0 or 1 off (default 4 on\n" \
              "every renderer: what is written is anti-aliased; on a CPU\n" \
              "rasteriser such as llvmpipe an animated frame costs 3-4.5x)\n", \
      .man = "anti\\-aliasing: the screen passes are drawn with\n" \
             ".I N\n" \
             "samples per pixel (MSAA) and resolved; 0 or 1 turns it off (default 4 on\n" \
             "every renderer, or as many as it allows: what is written is anti\\-aliased;\n" \
             "on a CPU rasteriser such as llvmpipe 4 samples cost 3 to 4.5 times the frame).\n" }
#define CMD_OPTION_VERBOSE(off) \
    { "--verbose", .kind = CMD_FLAG, .offset = (off), \
      .help = "each uniform the shaders declare but do not use, a note at\n" \
              "its glib line (by default one summary line a load)\n", \
      .man = "each uniform of the glib that the shaders declare but do not use (compiled\n" \
             "out by a Define, or unused) as a note at its own glib line; by default a\n" \
             "load says them in one summary line.\n" }

/* Defines `const char *NAME(void)`, spec's usage text in static storage:
 * the cmd_X_usage() of each command. */
#define CMD_USAGE_FUNCTION(NAME, spec) \
    const char *NAME(void) { \
        static char text[CMD_USAGE_MAX]; \
        return cmd_usage(&(spec), text, sizeof text); \
    }

/* One --set assignment (PROGRAM.NAME=V, NAME=V for every Program, or
 * scene.Command=ARGS) applied to r as the panel would (render_setting_assign);
 * false, with "tarn: WHAT: why" on stderr, when it did not apply as written
 * (a missing uniform, a clamped value). render's and sheet's --set, sheet's --vary. */
struct render;
bool cmd_apply_set(struct render *r, const char *set, const char *what);

/* Splits a copy of list (in buf) at commas into at most max parts; the
 * number of parts, or -1 when there are more than max. */
int cmd_split(const char *list, char *buf, size_t buflen, const char **parts, int max);

#endif
