/* image_io.cpp: the thin C++ bridge to OpenImageIO behind image_io.h.
 *
 * Only OpenImageIO calls and the little glue the C API needs live here;
 * nothing throws across the C boundary. */
#include "image_io.h"
#include "mem.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace OIIO;

namespace {

void set_err(char *err, int errlen, const char *path, const std::string &why) {
    if (!err || errlen <= 0) return;
    std::string msg = why;
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
    if (msg.empty()) msg = "unknown error";
    std::snprintf(err, (size_t)errlen, "%s: %s", path ? path : "(null)", msg.c_str());
}

bool size_ok(long w, long h, long d, long channels) {
    return w >= 1 && h >= 1 && d >= 1 && channels >= 1 && channels <= IMG_MAX_CHANNELS &&
           w <= IMG_MAX_SIDE && h <= IMG_MAX_SIDE && d <= IMG_MAX_SIDE &&
           w * h <= IMG_MAX_TEXELS && w * h * d <= IMG_MAX_TEXELS;
}

float *alloc_px(long w, long h, long d, long channels) {
    return (float *)mem_zalloc((size_t)(w * h * d) * (size_t)channels * sizeof(float));
}

/* The file type an extension asks for: 8-bit unless the format keeps more. */
TypeDesc format_for(const char *path, bool *rgb_only) {
    const char *dot = std::strrchr(path, '.');
    const char *slash = std::strrchr(path, '/');
    std::string ext = (dot && (!slash || dot > slash)) ? dot + 1 : "";
    for (char &c : ext) c = (char)std::tolower((unsigned char)c);
    *rgb_only = false;
    if (ext == "png" || ext == "bmp" || ext == "jpg" || ext == "jpeg") return TypeDesc::UINT8;
    if (ext == "exr") return TypeDesc::HALF;
    if (ext == "tif" || ext == "tiff") return TypeDesc::FLOAT;
    if (ext == "hdr") { *rgb_only = true; return TypeDesc::FLOAT; }
    return TypeDesc::UINT8;
}

/* The first subimage of an opened file into out (img_read's contract). */
bool decode(ImageInput &in, const char *path, img *out, char *err, int errlen) {
    const ImageSpec &spec = in.spec();
    if (!size_ok(spec.width, spec.height, spec.depth, spec.nchannels)) {
        set_err(err, errlen, path,
            "unsupported size " + std::to_string(spec.width) + "x" +
            std::to_string(spec.height) + "x" + std::to_string(spec.depth) + ", " +
            std::to_string(spec.nchannels) + " channels (at most " +
            std::to_string(IMG_MAX_SIDE) + " a side, 2^28 texels, " +
            std::to_string(IMG_MAX_CHANNELS) + " channels)");
        return false;
    }
    float *px = alloc_px(spec.width, spec.height, spec.depth, spec.nchannels);
    if (!in.read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, px)) {
        std::free(px);
        set_err(err, errlen, path, in.geterror());
        return false;
    }
    out->w = spec.width; out->h = spec.height; out->d = spec.depth;
    out->channels = spec.nchannels; out->px = px;
    return true;
}

} // namespace

extern "C" bool img_alloc(img *im, int w, int h, int channels) {
    if (!im) return false;
    *im = img{0, 0, 0, 0, nullptr};
    if (!size_ok(w, h, 1, channels)) return false;
    im->px = alloc_px(w, h, 1, channels);
    im->w = w; im->h = h; im->d = 1; im->channels = channels;
    return true;
}

extern "C" void img_free(img *im) {
    if (!im) return;
    std::free(im->px);
    *im = img{0, 0, 0, 0, nullptr};
}

extern "C" void img_flip_rows(img *im) {
    if (!im || !im->px || im->h < 2) return;
    size_t row = (size_t)im->w * (size_t)im->channels;
    for (int z = 0; z < im->d; z++) {
        float *slice = im->px + (size_t)z * (size_t)im->h * row;
        for (int a = 0, b = im->h - 1; a < b; a++, b--)
            for (size_t i = 0; i < row; i++) {
                float t = slice[(size_t)a * row + i];
                slice[(size_t)a * row + i] = slice[(size_t)b * row + i];
                slice[(size_t)b * row + i] = t;
            }
    }
}

extern "C" bool img_read(const char *path, img *out, char *err, int errlen) {
    if (!out) return false;
    *out = img{0, 0, 0, 0, nullptr};
    if (!path || !*path) { set_err(err, errlen, path, "no file name"); return false; }
    try {
        /* OpenImageIO's own message for a missing file is vague; say why. */
        std::FILE *f = std::fopen(path, "rb");
        if (!f) { set_err(err, errlen, path, std::strerror(errno)); return false; }
        std::fclose(f);

        ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1); /* pixels as stored */
        auto in = ImageInput::open(path, &config);
        if (!in) {
            set_err(err, errlen, path, "cannot read (" + OIIO::geterror() + ")");
            return false;
        }
        return decode(*in, path, out, err, errlen);
    } catch (const std::exception &e) {
        img_free(out);
        set_err(err, errlen, path, e.what());
        return false;
    }
}

extern "C" bool img_read_bytes(const char *name, const void *bytes, size_t len, img *out, char *err, int errlen) {
    if (!out) return false;
    *out = img{0, 0, 0, 0, nullptr};
    if (!name || !*name) { set_err(err, errlen, name, "no file name"); return false; }
    try {
        Filesystem::IOMemReader proxy(bytes, len);
        ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1); /* pixels as stored */
        auto in = ImageInput::open(name, &config, &proxy);
        if (!in) {
            set_err(err, errlen, name, "cannot read (" + OIIO::geterror() + ")");
            return false;
        }
        return decode(*in, name, out, err, errlen);
    } catch (const std::exception &e) {
        img_free(out);
        set_err(err, errlen, name, e.what());
        return false;
    }
}

extern "C" bool img_reads_from_memory(const char *name) {
    try {
        auto in = ImageInput::create(name);
        return in && in->supports("ioproxy");
    } catch (const std::exception &) {
        return false;
    }
}

static bool write_image(const char *path, const img *im, bool full_float, char *err, int errlen) {
    if (!path || !*path) { set_err(err, errlen, path, "no file name"); return false; }
    if (!im || !im->px || !size_ok(im->w, im->h, im->d, im->channels)) {
        set_err(err, errlen, path, "no image or bad image size");
        return false;
    }
    try {
        bool rgb_only;
        TypeDesc fmt = format_for(path, &rgb_only);
        if (full_float && fmt == TypeDesc::HALF) fmt = TypeDesc::FLOAT;
        auto out = ImageOutput::create(path);
        if (!out) {
            set_err(err, errlen, path, "unsupported format (" + OIIO::geterror() + ")");
            return false;
        }
        if (im->d > 1 && !out->supports("volumes")) {
            set_err(err, errlen, path, std::string(out->format_name()) + " cannot store 3D images");
            return false;
        }
        int nch = im->channels;
        if (rgb_only && nch > 3) nch = 3;           /* .hdr: RGB, alpha dropped */
        if (rgb_only && nch < 3) {
            set_err(err, errlen, path, "hdr needs 3 or 4 channels");
            return false;
        }
        ImageSpec spec(im->w, im->h, nch, fmt);
        spec.depth = spec.full_depth = im->d;
        spec.attribute("oiio:UnassociatedAlpha", 1); /* write pixels as given */
        if (!out->open(path, spec)) {
            set_err(err, errlen, path, out->geterror());
            return false;
        }
        stride_t xstride = (stride_t)im->channels * (stride_t)sizeof(float);
        bool ok = out->write_image(TypeDesc::FLOAT, im->px, xstride);
        ok = out->close() && ok;
        if (!ok) { set_err(err, errlen, path, out->geterror()); return false; }
        return true;
    } catch (const std::exception &e) {
        set_err(err, errlen, path, e.what());
        return false;
    }
}

extern "C" bool img_write(const char *path, const img *im, char *err, int errlen) {
    return write_image(path, im, false, err, errlen);
}

extern "C" bool img_write_float(const char *path, const img *im, char *err, int errlen) {
    return write_image(path, im, true, err, errlen);
}
