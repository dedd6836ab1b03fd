/* util: the small things every layer needs once: a monotonic clock, qsort
 * comparators and the median, option parsing, and where tarn's data is. */
#ifndef TARN_UTIL_H
#define TARN_UTIL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* FNV-1a (64-bit), the one hash of tarn's content keys (file contents,
 * shader texts, a picture's inputs, the reference cache's keys): h
 * continued over n bytes; start from HASH_FNV1A_BASIS. */
#define HASH_FNV1A_BASIS 14695981039346656037ull
uint64_t hash_fnv1a(uint64_t h, const void *data, size_t n);

/* Seconds, and nanoseconds, on a monotonic clock (only differences mean
 * anything): the one clock for intervals and deadlines. (The wall clock
 * files are stamped with is file.c's; a process's CPU time bench_timing's.) */
double clock_now_s(void);
int64_t clock_now_ns(void);
/* Sleeps s seconds (again after a signal); nothing for s <= 0. */
void clock_sleep_s(double s);

/* qsort comparators: doubles ascending, `char *` elements by strcmp. */
int cmp_double(const void *a, const void *b);
int cmp_str_ptr(const void *a, const void *b);

/* The median of v[0..n-1] (sorts v); 0 when n is 0. */
double median_double(double *v, size_t n);

/* Command-line values. WxH with 1 <= W, H <= 16384; a whole string as a
 * double; -h or --help. */
bool opt_size(const char *s, int *w, int *h);
bool opt_double(const char *s, double *out);
bool opt_is_help(const char *a);

/* Where tarn's packs/ and scenes/ are: $TARN_ROOT when set, else the
 * data folder of the install tarn runs from (BINDIR/../share/tarn beside
 * the executable, so an install made with `cmake --install --prefix P` or
 * moved elsewhere still finds its own), else the configured install data
 * folder, else the source tree it was built from. One place decides; the
 * answer does not change while tarn runs. */
const char *tarn_root(void);

/* tarn's cache folder, per the XDG base directory spec: $XDG_CACHE_HOME/tarn
 * when that is an absolute path, else $HOME/.cache/tarn. False when neither
 * is set (nowhere to cache). Not created here. */
bool tarn_cache_dir(char *out, size_t len);

/* A reduced size's side (a frame's, a target's drawn smaller than the
 * scene says): k, or k + 1 when k is a power of two from 4 up and below
 * full. llvmpipe compiles a shader's texture sampling apart for
 * power-of-two sides, so a reduced frame that landed on one compiled the
 * shaders that read it again, on the frame; kept off them, every reduced
 * frame needs the same code as the first (and the window's compile job
 * can make it ahead). */
int side_off_pow2(int k, int full);

/* A reduced side of a texture the scene sizes (a target, the world's height
 * map) or of a count tied to one (natural's photons, one a texel), about k
 * of full, that keeps whether full is a power of two: llvmpipe's key for a
 * shader's variant holds, for each texture it samples, whether each side
 * is one, so a target of 1024 drawn at 379 in a reduced frame made every
 * shader reading it compile again for the still picture's 1024 (the
 * window's compile job compiled caustic_tex's water twice, 1-2 s each).
 * full a power of two: the power of two nearest k in ratio, at least min
 * and at most full; else side_off_pow2(max(k, min), full). */
int side_like_full(int k, int full, int min);

#endif
