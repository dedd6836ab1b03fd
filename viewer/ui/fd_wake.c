/* fd_wake: a thread that wakes a sleeping window when an fd is readable
 * (fd_wake.h). */
#include "fd_wake.h"

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/eventfd.h>
#include <unistd.h>

struct fd_wake {
    int fd;                   /* the fd watched (not owned) */
    int stop_fd, rearm_fd;    /* eventfds: the owner's two messages */
    void (*wake)(void *user);
    void *user;
    atomic_bool disarmed;     /* the thread woke the owner and waits for fd_wake_rearm */
    pthread_t thread;
};

static void drain(int efd) {
    uint64_t v;
    while (read(efd, &v, sizeof v) < 0 && errno == EINTR) {}
}

static void *run(void *arg) {
    fd_wake *fw = arg;
    bool armed = true;
    for (;;) {
        struct pollfd p[3] = { { .fd = fw->stop_fd, .events = POLLIN },
                               { .fd = fw->rearm_fd, .events = POLLIN },
                               { .fd = armed ? fw->fd : -1, .events = POLLIN } };   /* -1: not polled */
        if (poll(p, 3, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        if (p[0].revents) break;
        if (p[1].revents) {
            drain(fw->rearm_fd);
            armed = true;
            continue;   /* poll the fd again: news that came meanwhile wakes at once */
        }
        if (armed && p[2].revents) {
            armed = false;
            atomic_store(&fw->disarmed, true);
            fw->wake(fw->user);
        }
    }
    return NULL;
}

fd_wake *fd_wake_start(int fd, void (*wake)(void *user), void *user) {
    if (fd < 0 || !wake) return NULL;
    fd_wake *fw = calloc(1, sizeof *fw);
    if (!fw) return NULL;
    fw->fd = fd;
    fw->wake = wake;
    fw->user = user;
    fw->stop_fd = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
    fw->rearm_fd = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
    atomic_init(&fw->disarmed, false);
    if (fw->stop_fd < 0 || fw->rearm_fd < 0 || pthread_create(&fw->thread, NULL, run, fw) != 0) {
        if (fw->stop_fd >= 0) close(fw->stop_fd);
        if (fw->rearm_fd >= 0) close(fw->rearm_fd);
        free(fw);
        return NULL;
    }
    return fw;
}

static void signal_fd(int efd) {
    uint64_t one = 1;
    while (write(efd, &one, sizeof one) < 0 && errno == EINTR) {}
}

void fd_wake_rearm(fd_wake *fw) {
    if (fw && atomic_exchange(&fw->disarmed, false)) signal_fd(fw->rearm_fd);
}

void fd_wake_stop(fd_wake *fw) {
    if (!fw) return;
    signal_fd(fw->stop_fd);
    pthread_join(fw->thread, NULL);
    close(fw->stop_fd);
    close(fw->rearm_fd);
    free(fw);
}
