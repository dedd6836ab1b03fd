/* exit_code: what every tarn command returns to the shell, one list for
 * all of them (the man page and `tarn help` print the same). */
#ifndef TARN_EXIT_CODE_H
#define TARN_EXIT_CODE_H

enum tarn_exit_code {
    TARN_EXIT_OK = 0,    /* all is well */
    TARN_EXIT_INPUT = 1, /* the input had errors (what could be done was done) */
    TARN_EXIT_USAGE = 2, /* bad usage: the message says what to give */
    TARN_EXIT_NO_GL = 3  /* no OpenGL context: the message says what to install */
};

#endif
