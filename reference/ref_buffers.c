#include "ref_buffers.h"

#include <string.h>

const ref_buffer_info ref_buffers[REF_BUF_COUNT] = {
    { REF_BUF_COLOR, "color", ".exr", 3, REF_ERR_COLOR, false, 0, 0, "linear RGB radiance" },
    { REF_BUF_REFRACT_HIT, "refract_hit", ".refract_hit.exr", 4, REF_ERR_POINT, true, 0, REF_OUTPUT_REFRACT_HIT,
      "xyz the refracted ray meets, and what (A)" },
    { REF_BUF_REFLECT, "reflect", ".reflect.exr", 4, REF_ERR_POINT, true, REF_REFLECT_SKY, 0,
      "xyz the reflected ray meets (or its direction), and what (A)" },
    { REF_BUF_FRESNEL, "fresnel", ".fresnel.exr", 1, REF_ERR_SCALAR, true, 0, REF_OUTPUT_FRESNEL,
      "Fresnel reflectance at the water" },
    { REF_BUF_DEPTH, "depth", ".depth.exr", 1, REF_ERR_SCALAR, true, 0, REF_OUTPUT_DEPTH, "path length in water" },
    { REF_BUF_IRRADIANCE, "irradiance", ".irradiance.exr", 3, REF_ERR_SCALAR, true, 0, REF_OUTPUT_IRRADIANCE,
      "sun irradiance at the refraction hit" },
    { REF_BUF_SURFACE, "surface", ".surface.exr", 3, REF_ERR_POINT, true, 0, 0,
      "where the primary ray meets the water surface" },
    { REF_BUF_MASK, "mask", ".mask.exr", 1, REF_ERR_SCALAR, false, 0, 0, "what the pixel-centre ray met (REF_MASK_*)" },
};

const ref_buffer_info *ref_buffer_named(const char *name) {
    for (int i = 0; name && i < REF_BUF_COUNT; i++)
        if (strcmp(ref_buffers[i].name, name) == 0) return &ref_buffers[i];
    return NULL;
}

const ref_buffer_info *ref_buffer_for_output(int value) {
    for (int i = 0; value > 0 && i < REF_BUF_COUNT; i++)
        if ((int)ref_buffers[i].tarn_output == value) return &ref_buffers[i];
    return NULL;
}

const double *ref_buffer_data(const ref_render_result *r, ref_buffer_id id) {
    switch (id) {
    case REF_BUF_COLOR: return r->color;
    case REF_BUF_REFRACT_HIT: return r->refract_hit;
    case REF_BUF_REFLECT: return r->reflect;
    case REF_BUF_FRESNEL: return r->fresnel;
    case REF_BUF_DEPTH: return r->depth;
    case REF_BUF_IRRADIANCE: return r->irradiance;
    case REF_BUF_SURFACE: return r->surface;
    default: return NULL;
    }
}
