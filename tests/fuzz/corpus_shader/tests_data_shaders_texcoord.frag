#version 330 compatibility
// texcoord.frag: reads gl_TexCoord and gl_Color
void main() {
    gl_FragColor = gl_Color * vec4(gl_TexCoord[0].st, 0.0, 1.0);
}
