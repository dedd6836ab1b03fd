/* check.h: the one tiny test harness every tests/test_*.c uses.
 *
 *   static void test_something(void) { CHECK(x == 1); CHECK_NEAR(a, b, 1e-9); }
 *   int main(void) { RUN(test_something); return check_summary(); }
 *
 * A failed CHECK prints file:line and the expression and marks the case
 * failed but keeps going, so one run shows every failure. The comparisons
 * CHECK_EQ(a, b), CHECK_NE, CHECK_LT, CHECK_LE, CHECK_GT, CHECK_GE and
 * CHECK_STR_EQ(a, b) also print both values (each side evaluated once). SKIP(why) ends the
 * case as skipped; a program whose cases all skipped exits 77, which ctest
 * reports as skipped (SKIP_RETURN_CODE), never as a pass.
 */
#ifndef TARN_CHECK_H
#define TARN_CHECK_H

#include <math.h>
#include <stdbool.h>
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

/* One value of a failed comparison, in its own type's format. */
static inline void check_print_i_(long long v) { fprintf(stderr, "%lld", v); }
static inline void check_print_u_(unsigned long long v) { fprintf(stderr, "%llu", v); }
static inline void check_print_d_(double v) { fprintf(stderr, "%.9g", v); }
static inline void check_print_s_(const char *v) {
    if (v) fprintf(stderr, "\"%s\"", v);
    else fputs("(null)", stderr);
}
static inline void check_print_p_(const volatile void *v) { fprintf(stderr, "%p", (const void *)v); }
#define check_print_(x) _Generic((x), \
    _Bool: check_print_i_, char: check_print_i_, signed char: check_print_i_, short: check_print_i_, \
    int: check_print_i_, long: check_print_i_, long long: check_print_i_, \
    unsigned char: check_print_u_, unsigned short: check_print_u_, unsigned: check_print_u_, \
    unsigned long: check_print_u_, unsigned long long: check_print_u_, \
    float: check_print_d_, double: check_print_d_, long double: check_print_d_, \
    char *: check_print_s_, const char *: check_print_s_, default: check_print_p_)(x)

/* The sides keep their types, so the comparison is the one written; a
 * literal held in a variable is no longer known non-negative, so
 * -Wsign-compare would warn where `n == 5` did not. */
#define CHECK_CMP_(a, op, b) do { __auto_type check_x_ = (a); __auto_type check_y_ = (b); \
    _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wsign-compare\"") \
    bool check_ok_ = check_x_ op check_y_; \
    _Pragma("GCC diagnostic pop") \
    if (!check_ok_) { \
    fprintf(stderr, "%s:%d: CHECK failed: %s %s %s: ", __FILE__, __LINE__, #a, #op, #b); \
    check_print_(check_x_); fputs(" against ", stderr); check_print_(check_y_); fputc('\n', stderr); \
    check_case_failed = 1; } } while (0)
#define CHECK_EQ(a, b) CHECK_CMP_(a, ==, b)
#define CHECK_NE(a, b) CHECK_CMP_(a, !=, b)
#define CHECK_LT(a, b) CHECK_CMP_(a, <, b)
#define CHECK_LE(a, b) CHECK_CMP_(a, <=, b)
#define CHECK_GT(a, b) CHECK_CMP_(a, >, b)
#define CHECK_GE(a, b) CHECK_CMP_(a, >=, b)

/* Two strings equal (NULL equals only NULL). */
#define CHECK_STR_EQ(a, b) do { const char *check_x_ = (a), *check_y_ = (b); \
    if (!(check_x_ == check_y_ || (check_x_ && check_y_ && strcmp(check_x_, check_y_) == 0))) { \
    fprintf(stderr, "%s:%d: CHECK failed: %s equals %s: ", __FILE__, __LINE__, #a, #b); \
    check_print_s_(check_x_); fputs(" against ", stderr); check_print_s_(check_y_); fputc('\n', stderr); \
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
