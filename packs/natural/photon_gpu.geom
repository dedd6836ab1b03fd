#version 330 compatibility
// packs/natural, caustics on the GPU: one photon in, its bilinear splat out
// (four points on the centres of the texels around it, weights summing to 1).
layout(points) in;
layout(points, max_vertices = 4) out;

uniform vec2 uTargetSize;   // the caustic target's size in texels (set by tarn)
in vec2 vTexel[];
in float vWeight[];
in float vValid[];
out float gWeight;

void main() {
    if (vValid[0] < 0.5) return;
    vec2 f = vTexel[0] - 0.5;
    vec2 i0 = floor(f);
    vec2 a = f - i0;
    for (int k = 0; k < 4; k++) {
        vec2 o = vec2(float(k & 1), float(k >> 1));
        vec2 wt = mix(1.0 - a, a, o);
        vec2 c = (i0 + o + 0.5) / uTargetSize * 2.0 - 1.0;
        gl_Position = vec4(c, 0.0, 1.0);
        gWeight = vWeight[0] * wt.x * wt.y;
        EmitVertex();
        EndPrimitive();
    }
}
