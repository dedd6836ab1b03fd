// noversion.frag: no #version; glman assumes 330 compatibility
uniform float Timer;
void main() {
    gl_FragColor = vec4(Timer) * undefined_in_noversion;
}
