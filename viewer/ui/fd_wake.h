/* fd_wake: wakes a window asleep in glfwWaitEventsTimeout when a file
 * descriptor becomes readable.
 *
 * A still window sleeps (issue #30: at most 5% of a core) in GLFW's wait,
 * which cannot wait on the file watcher's inotify fd; it woke every
 * 50 ms to look, so a save reached a paused window up to 50 ms
 * late. A thread of fd_wake polls the fd and calls wake (glfwPostEmptyEvent,
 * which any thread may call) once it is readable; it then waits until the
 * owner has read the fd (fd_wake_rearm) before it polls it again, so it
 * never spins on events the window has not taken yet.
 *
 *     fd_wake *fw = fd_wake_start(watch_fd(w), post_empty_event, NULL);
 *     ... each frame, after reading the fd (watch_poll): fd_wake_rearm(fw);
 *     fd_wake_stop(fw);
 *
 * No globals; one thread an fd_wake. */
#ifndef TARN_FD_WAKE_H
#define TARN_FD_WAKE_H

typedef struct fd_wake fd_wake;

/* Starts the thread. NULL where fd < 0 or no thread or eventfd can be made:
 * the caller's timed wait still finds the fd's news, only later. */
fd_wake *fd_wake_start(int fd, void (*wake)(void *user), void *user);

/* The owner has read what made the fd readable: wake again the next time it
 * is. Cheap when the thread is polling already (no system call). NULL is
 * fine. */
void fd_wake_rearm(fd_wake *fw);

/* Stops and joins the thread. NULL is fine. */
void fd_wake_stop(fd_wake *fw);

#endif
