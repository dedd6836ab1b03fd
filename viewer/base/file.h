/* file: reading and writing whole files, and making folders. */
#ifndef TARN_FILE_H
#define TARN_FILE_H

#include <stdbool.h>
#include <stddef.h>

/* The whole file, NUL-terminated (len, may be NULL, excludes the NUL), or
 * NULL with the reason in err when it cannot be opened, is not a regular
 * file, or is larger than max_bytes (0: no limit). */
char *file_read(const char *path, size_t max_bytes, size_t *len, char *err, size_t errlen);

/* How file_read_text reads a text file; zero means no limit and the bytes
 * as they are. The one reader of the text formats (scenes, shaders, OBJ,
 * presets), so they all read a file written on Windows alike. */
typedef struct file_text_opts {
    size_t max_bytes; /* 0: no limit */
    bool strip_bom;   /* drop a leading UTF-8 byte order mark (Windows editors write one) */
    bool crlf_to_lf;  /* "\r\n" becomes "\n" (a lone \r stays) */
    bool reject_nul;  /* a NUL byte means binary, not text: NULL, and why names its line */
    bool settle;      /* a file a user may be saving right now (the viewer's reload): below */
} file_text_opts;

/* With `settle`, a read is taken only when the file did not change while it
 * was read (the same size, modification time and inode before and after,
 * and the size read) and no writer holds it open (file_writer_holds: the
 * save is over, at once, whatever its pauses). Where that cannot be asked
 * (a file not the user's own, a filesystem without leases), the file must
 * also have been last modified at least FILE_SETTLE_MS ago. An empty file
 * must be FILE_EMPTY_WAIT_MS old either way (`cat > f` truncates first,
 * and a writer may truncate by path before it opens the file: a file just
 * emptied is "still being written"). Else it is read again.
 * After FILE_SETTLE_MAX_MS the latest read is taken as it is. */
#define FILE_SETTLE_MS 30
#define FILE_EMPTY_WAIT_MS 100
#define FILE_SETTLE_MAX_MS 250

/* Does a process hold path open for writing? 1 yes, 0 no, -1 cannot tell.
 * Asked by a read lease (fcntl F_SETLEASE), which Linux refuses with
 * EAGAIN exactly while some open file description has the file open for
 * writing; it needs the file to be the caller's own (or CAP_LEASE) and a
 * filesystem that has leases. The lease is held for microseconds; a
 * writer opening the file then breaks it with a signal that is ignored
 * (SIGURG, not the default SIGIO, which would end the process). */
int file_writer_holds(const char *path);

/* The file as text, NUL-terminated (len, may be NULL, excludes the NUL;
 * counted after the options), or NULL with the reason alone in why, for the
 * caller's own message: "No such file or directory", "it is a directory",
 * "it is not a regular file", "it is larger than 8 MiB", "binary data (a NUL
 * byte at line 3), not text". o may be NULL: no options. */
char *file_read_text(const char *path, const file_text_opts *o, size_t *len, char *why, size_t whylen);

/* What a file was when it was read: a later stat that differs means it
 * changed since. Times in ns; the kernel stamps them from a coarse clock
 * (a few ms), so two writes that close together may leave the same stamp:
 * file_cache.h says how it copes. */
typedef struct file_stamp {
    unsigned long long dev, ino;
    long long size, mtime_ns, ctime_ns;
    double read_ms;   /* when the read began, on the files' clock (the wall clock): not compared */
} file_stamp;

/* file_read_text in two halves, for a reader that keeps the bytes
 * (file_cache): the file's bytes as read (with o's max_bytes and settle;
 * NUL-terminated, *len without the NUL) and its stamp then, or NULL with
 * why; then file_text_finish applies o's text options to them (it takes
 * bytes, and returns them changed in place, or frees them and returns NULL
 * with why). */
char *file_read_stamped(const char *path, const file_text_opts *o, size_t *len, file_stamp *stamp, char *why,
                        size_t whylen);
char *file_text_finish(char *bytes, size_t *len, const file_text_opts *o, char *why, size_t whylen);

/* The stamp of the regular file at path now (read_ms: now); false when
 * there is none. */
bool file_stamp_now(const char *path, file_stamp *out);
bool file_stamp_same(const file_stamp *a, const file_stamp *b);
/* How old the file was when the read that gave the stamp began (a
 * modification in the future, another machine's clock, counts as long ago). */
double file_stamp_age_ms(const file_stamp *st);

/* Writes n bytes to path (replacing it). False with the reason in err. */
bool file_write(const char *path, const void *data, size_t n, char *err, size_t errlen);

/* mkdir -p: every missing folder of path. False with the reason in err. */
bool file_mkdir_p(const char *path, char *err, size_t errlen);


bool file_exists(const char *path);
bool file_is_dir(const char *path);

#endif
