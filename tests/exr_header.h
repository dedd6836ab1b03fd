/* exr_header.h: the pixel type an OpenEXR file's header declares, read
 * straight from the file (not through OpenImageIO, which converts on read
 * and so cannot tell half from float), for tests that check what a
 * command wrote. */
#ifndef TARN_TESTS_EXR_HEADER_H
#define TARN_TESTS_EXR_HEADER_H

#include <stdio.h>
#include <string.h>

#define EXR_TYPE_UINT 0
#define EXR_TYPE_HALF 1
#define EXR_TYPE_FLOAT 2

/* The pixel type shared by every channel of the file's "channels"
 * attribute (EXR_TYPE_*), -2 when channels differ, -1 on a file that is
 * not a scanline EXR or cannot be read. The header is: magic 76 2f 31 01,
 * 4 version bytes, then attributes (name\0 type\0 int32 size, value) up to
 * an empty name; a chlist value is (name\0 int32 type, 4 bytes, int32
 * xsampling, int32 ysampling) per channel, ended by \0. */
static inline int exr_pixel_type(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    unsigned char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    if (n < 8 || buf[0] != 0x76 || buf[1] != 0x2f || buf[2] != 0x31 || buf[3] != 0x01) return -1;
    size_t p = 8;
    while (p < n && buf[p]) {
        const char *name = (const char *)buf + p;
        size_t nl = strnlen(name, n - p);
        const char *type = name + nl + 1;
        size_t q = p + nl + 1;
        if (q >= n) return -1;
        size_t tl = strnlen(type, n - q);
        q += tl + 1;
        if (q + 4 > n) return -1;
        size_t size = buf[q] | (size_t)buf[q + 1] << 8 | (size_t)buf[q + 2] << 16 | (size_t)buf[q + 3] << 24;
        q += 4;
        if (q + size > n) return -1;
        if (strcmp(name, "channels") == 0 && strcmp(type, "chlist") == 0) {
            int common = -1;
            size_t c = q;
            while (c < q + size && buf[c]) {
                c += strnlen((const char *)buf + c, q + size - c) + 1;
                if (c + 16 > q + size) return -1;
                int t = buf[c] | buf[c + 1] << 8 | buf[c + 2] << 16 | buf[c + 3] << 24;
                if (common >= 0 && t != common) return -2;
                common = t;
                c += 16;
            }
            return common;
        }
        p = q + size;
    }
    return -1;
}

#endif
