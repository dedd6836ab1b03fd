/* path: lexical path arithmetic, the one home of it. Nothing here touches
 * the file system but path_absolute, which asks for the current directory;
 * symlinks are not resolved (a caller that needs a file's identity asks
 * realpath). Every result is a heap string the caller frees. */
#ifndef TARN_PATH_H
#define TARN_PATH_H

/* `//`, `.` and `..` removed lexically, as Go's filepath.Clean does:
 * "a/./b/../c" -> "a/c", "/.." -> "/", "../a/.." -> "..", "" -> ".".
 * A relative path stays relative; its leading ".." are kept. */
char *path_clean(const char *path);

/* path_clean of path made absolute against the current directory. NULL
 * (errno set) when the current directory is gone. */
char *path_absolute(const char *path);

/* The folder part: "a/b.glib" -> "a", "b.glib" -> ".", "/x" -> "/". */
char *path_dir(const char *path);

/* name read from dir: name itself when absolute (or dir is "" or "."),
 * else dir/name; cleaned either way. */
char *path_join(const char *dir, const char *name);

#endif
