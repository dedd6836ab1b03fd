/* cli_reference: `tarn reference SCENE.glib -o ref.exr [options]`, the CPU
 * ground truth of a scene (reference/ref_render.h) written as a linear EXR,
 * an sRGB PNG and per-pixel buffers. See docs/reference.md, "The renderer". */
#ifndef TARN_CLI_REFERENCE_H
#define TARN_CLI_REFERENCE_H

/* argv holds the arguments after the command word (argv[0] is the first
 * option or the scene, as main.c passes argc - 2, argv + 2). Returns the
 * exit code: TARN_EXIT_OK, TARN_EXIT_INPUT (scene errors, render or write
 * failure), TARN_EXIT_USAGE. */
int cli_reference(int argc, char **argv);

/* The usage text (`tarn reference --help`, `tarn help reference`). */
const char *cli_reference_usage(void);

#endif
