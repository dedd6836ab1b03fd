/* check.h: the one tiny test harness every tests/test_*.c uses.
 *
 *   static void test_something(void) { CHECK(x == 1); CHECK_NEAR(a, b, 1e-9); }
 *   int main(void) { RUN(test_something); return check_summary(); }
 *
 * A failed CHECK prints file:line and the expression and marks the case
 * failed but keeps going, so one run shows every failure. SKIP(why) ends the
 * case as skipped; a program whose cases all skipped exits 77, which ctest
 * reports as skipped (SKIP_RETURN_CODE), never as a pass.
 */
#ifndef TARN_CHECK_H
#define TARN_CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int check_failed_cases, check_passed_cases, check_skipped_cases;
static int check_case_failed, check_case_skipped;

#define CHECK(expr) do { if (!(expr)) { \
    fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #expr); \
    check_case_failed = 1; } } while (0)

#define CHECK_MSG(expr, ...) do { if (!(expr)) { \
    fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #expr); \
    fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); \
    check_case_failed = 1; } } while (0)

#define CHECK_NEAR(a, b, tol) do { double check_a_ = (a), check_b_ = (b); \
    if (!(fabs(check_a_ - check_b_) <= (tol))) { \
    fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.12g, %s = %.12g, tol %g\n", \
            __FILE__, __LINE__, #a, check_a_, #b, check_b_, (double)(tol)); \
    check_case_failed = 1; } } while (0)

#define CHECK_STR_CONTAINS(hay, needle) do { const char *check_h_ = (hay); \
    if (!check_h_ || !strstr(check_h_, (needle))) { \
    fprintf(stderr, "%s:%d: expected \"%s\" in: %s\n", __FILE__, __LINE__, \
            (needle), check_h_ ? check_h_ : "(null)"); \
    check_case_failed = 1; } } while (0)

/* Ends the current case as skipped (use in the case function itself). */
#define SKIP(...) do { fprintf(stderr, "  skip: "); fprintf(stderr, __VA_ARGS__); \
    fputc('\n', stderr); check_case_skipped = 1; return; } while (0)

#define RUN(fn) do { check_case_failed = 0; check_case_skipped = 0; \
    fprintf(stderr, "[ RUN  ] %s\n", #fn); fn(); \
    if (check_case_failed) { check_failed_cases++; fprintf(stderr, "[ FAIL ] %s\n", #fn); } \
    else if (check_case_skipped) { check_skipped_cases++; fprintf(stderr, "[ SKIP ] %s\n", #fn); } \
    else { check_passed_cases++; fprintf(stderr, "[  OK  ] %s\n", #fn); } } while (0)

static inline int check_summary(void) {
    fprintf(stderr, "%d passed, %d failed, %d skipped\n",
            check_passed_cases, check_failed_cases, check_skipped_cases);
    if (check_failed_cases) return 1;
    if (check_passed_cases == 0 && check_skipped_cases > 0) return 77;
    return 0;
}

#endif
