#version 330 compatibility
// packs/natural, caustics on the GPU, pass 2: `WaterSurface points N` draws
// point k = j N + i for photon (i, j) of photon_pass.frag's target; this
// only fetches it and puts a 2 x 2 pixel point on its landing texel, whose
// four pixels are the texels of its bilinear splat (photon_splat.frag
// weighs them), added with Blend add. No geometry shader: on a CPU
// rasteriser it would run on one thread.
uniform sampler2D uPhotons;  // photon_pass.frag's target
uniform float uPointGrid;    // N (set by tarn)
uniform vec2 uTargetSize;    // the caustic target's size (set by tarn)
uniform float uTerrainHalfSize;
flat out vec2 vTexel;        // landing point in texels (texel centres at i + 0.5)
flat out float vWeight;      // weight per texel area: the ratio it adds

void main() {
    int n = int(uPointGrid + 0.5);
    vec4 ph = texelFetch(uPhotons, ivec2(gl_VertexID % n, gl_VertexID / n), 0);
    vec2 uv = ph.rg / uTerrainHalfSize * 0.5 + 0.5;
    vTexel = uv * uTargetSize;
    vec2 texel = 2.0 * uTerrainHalfSize / uTargetSize;
    vWeight = ph.b / (texel.x * texel.y);
    gl_PointSize = 2.0;
    bool valid = ph.a > 0.5 && !any(isnan(ph.rgb)) && !any(isinf(ph.rgb));
    gl_Position = valid ? vec4(uv * 2.0 - 1.0, 0.0, 1.0) : vec4(-4.0, -4.0, 0.0, 1.0);
}
