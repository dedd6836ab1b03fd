/* image_io: reading and writing images, a thin C API over OpenImageIO.
 *
 * Pixels are linear floats exactly as stored in the file: no colour space
 * conversion, no alpha (un)premultiplication; 8-bit files map 0..255 to 0..1.
 * Row 0 is the TOP of the image (file order); OpenGL wants row 0 at the
 * bottom, so call img_flip_rows() between the two. Pixel (x, y, z), channel
 * c is px[((z * h + y) * w + x) * channels + c].
 *
 * Errors are returned as "path: reason" in err (when err is not NULL).
 * The implementation is image_io.cpp (C++, because OpenImageIO is C++ only);
 * this header is plain C.
 */
#ifndef TARN_IMAGE_IO_H
#define TARN_IMAGE_IO_H

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest image accepted: any side, and the total texel count. */
#define IMG_MAX_SIDE 16384
#define IMG_MAX_TEXELS (1L << 28)
#define IMG_MAX_CHANNELS 64
#define IMG_MAX_FILE_BYTES (1L << 30)   /* what img_read_bytes' callers read at most */

typedef struct img {
    int w, h, d;        /* d = 1 for a 2D image, > 1 for a volume */
    int channels;
    float *px;          /* w * h * d * channels floats, heap (img_free) */
} img;

/* Reads the first subimage of any file OpenImageIO reads (PNG, JPEG, 24-bit
 * BMP, EXR, HDR, TIFF, ...); 3D when the file has depth. On failure out is
 * left empty and err says "path: reason" (missing, unreadable, unsupported
 * format, absurd size). */
bool img_read(const char *path, img *out, char *err, int errlen);

/* img_read of a file's bytes already in memory (file_cache.h), its format
 * told by name's extension (or, failing that, its first bytes); errors say
 * "name: reason". img_reads_from_memory: whether the format name implies
 * can be read so (PNG, JPEG, BMP, EXR, HDR, TIFF, TGA, GIF, PNM, DDS, WebP,
 * PSD; not SGI, ICO, FITS: those only through img_read). */
bool img_read_bytes(const char *name, const void *bytes, size_t len, img *out, char *err, int errlen);
bool img_reads_from_memory(const char *name);

/* Writes by the extension of path: .png (8-bit, clamped to 0..1 and
 * rounded), .exr (half float), .hdr (RGBE; 4 channels drop alpha), .tif /
 * .tiff (32-bit float), .bmp and .jpg / .jpeg (8-bit); any other extension
 * OpenImageIO knows is written 8-bit. Volumes (d > 1) need a format that
 * stores them (TIFF). */
bool img_write(const char *path, const img *im, char *err, int errlen);

/* img_write, but .exr is stored as 32-bit float instead of half (for data
 * such as the reference's hit points, where half's 11 bits are too few). */
bool img_write_float(const char *path, const img *im, char *err, int errlen);

/* Allocates a zeroed 2D image (d = 1). False (im emptied) for sizes out of
 * range or no memory. */
bool img_alloc(img *im, int w, int h, int channels);

/* Frees the pixels and empties the struct; safe on an empty img. */
void img_free(img *im);

/* Reverses the row order of every slice (file order <-> OpenGL order). */
void img_flip_rows(img *im);

#ifdef __cplusplus
}
#endif

#endif
