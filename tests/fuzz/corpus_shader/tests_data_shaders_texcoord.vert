#version 330 compatibility
// texcoord.vert: passes gl_TexCoord and gl_FrontColor, glman's old way
void main() {
    gl_TexCoord[0] = gl_MultiTexCoord0;
    gl_FrontColor = gl_Color;
    gl_Position = ftransform();
}
