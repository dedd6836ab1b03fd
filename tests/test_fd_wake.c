/* test_fd_wake: the thread that wakes a sleeping window when the file
 * watcher's fd is readable (ui/fd_wake), on a pipe: it wakes once per
 * readiness, never again until rearmed (no spinning on news the owner has
 * not read), at once when rearmed on news still unread, and stops. */
#include "check.h"
#include "fd_wake.h"

#include <stdatomic.h>
#include <time.h>
#include <unistd.h>

static void count_wake(void *user) { atomic_fetch_add((atomic_int *)user, 1); }

static void sleep_ms(int ms) {
    struct timespec ts = { ms / 1000, (long)(ms % 1000) * 1000000L };
    nanosleep(&ts, NULL);
}

/* Waits up to 2 s for the count to reach want; returns the count. */
static int wait_count(atomic_int *n, int want) {
    for (int i = 0; i < 400 && atomic_load(n) < want; i++) sleep_ms(5);
    return atomic_load(n);
}

static void test_wakes_once_per_readiness(void) {
    int p[2];
    CHECK(pipe(p) == 0);
    atomic_int n;
    atomic_init(&n, 0);
    fd_wake *fw = fd_wake_start(p[0], count_wake, &n);
    CHECK(fw != NULL);
    sleep_ms(50);
    CHECK_EQ(atomic_load(&n), 0);                 /* nothing to read: no wake */
    CHECK(write(p[1], "x", 1) == 1);
    CHECK_EQ(wait_count(&n, 1), 1);               /* news: one wake */
    sleep_ms(100);
    CHECK_EQ(atomic_load(&n), 1);                 /* unread, not rearmed: no more */
    fd_wake_rearm(fw);                            /* rearmed on news still unread: at once */
    CHECK_EQ(wait_count(&n, 2), 2);
    char c;
    CHECK(read(p[0], &c, 1) == 1);                /* the owner reads it */
    fd_wake_rearm(fw);
    sleep_ms(100);
    CHECK_EQ(atomic_load(&n), 2);                 /* nothing new */
    fd_wake_rearm(fw);                            /* armed already: nothing changes */
    CHECK(write(p[1], "y", 1) == 1);
    CHECK_EQ(wait_count(&n, 3), 3);
    fd_wake_stop(fw);
    close(p[0]);
    close(p[1]);
}

static void test_no_fd_no_thread(void) {
    atomic_int n;
    atomic_init(&n, 0);
    CHECK(fd_wake_start(-1, count_wake, &n) == NULL);
    fd_wake_rearm(NULL);
    fd_wake_stop(NULL);
}

int main(void) {
    RUN(test_wakes_once_per_readiness);
    RUN(test_no_fd_no_thread);
    return check_summary();
}
