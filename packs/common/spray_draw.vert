#version 330 compatibility
// spray_draw.vert: a point a particle slot (gl_VertexID), read from the
// state texture; a dead slot is sent outside the clip volume. Its size is
// the droplet's diameter projected at its distance.
uniform sampler2D uSprayPos;   // (x, y, z, life left)
uniform int   uSprayRes;
uniform mat4  uSprayVP;        // the main camera's view-projection
uniform vec3  uSprayEye;
uniform float uSpraySize;      // diameter (m)
uniform vec2  uSprayViewport;  // pixels
out float vLife;

void main() {
    ivec2 ij = ivec2(gl_VertexID % uSprayRes, gl_VertexID / uSprayRes);
    vec4 p = texelFetch(uSprayPos, ij, 0);
    vLife = p.w;
    if (p.w <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        gl_PointSize = 1.0;
        return;
    }
    vec4 c = uSprayVP * vec4(p.xyz, 1.0);
    vec3 view = p.xyz - uSprayEye;
    vec3 side = cross(view, vec3(0.0, 1.0, 0.0));
    side = dot(side, side) > 1e-12 ? normalize(side) : vec3(1.0, 0.0, 0.0);
    vec4 c2 = uSprayVP * vec4(p.xyz + side * uSpraySize, 1.0);
    vec2 px = (c2.xy / c2.w - c.xy / c.w) * 0.5 * uSprayViewport;
    gl_PointSize = clamp(length(px), 1.5, 48.0);
    gl_Position = c;
}
