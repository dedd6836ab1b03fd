#include "gl_program.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>

#include "strbuf.h"

static GLuint compile(GLenum kind, const char *text, const char *what, char *why, size_t whylen) {
    GLuint sh = glCreateShader(kind);
    glShaderSource(sh, 1, &text, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok) return sh;
    char log[200] = "";
    glGetShaderInfoLog(sh, sizeof log, NULL, log);
    snprintf(why, whylen, "%s: its %s shader did not compile: %s", what,
             kind == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
    glDeleteShader(sh);
    return 0;
}

unsigned gl_program_link(const char *vert, const char *frag, const char *what, char *why, size_t whylen) {
    GLuint vs = compile(GL_VERTEX_SHADER, vert, what, why, whylen);
    GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, frag, what, why, whylen) : 0;
    GLuint prg = 0;
    if (vs && fs) {
        prg = glCreateProgram();
        glAttachShader(prg, vs);
        glAttachShader(prg, fs);
        glBindAttribLocation(prg, 6, "Tangent");
        glLinkProgram(prg);
        GLint ok = 0;
        glGetProgramiv(prg, GL_LINK_STATUS, &ok);
        if (!ok) {
            char log[200] = "";
            glGetProgramInfoLog(prg, sizeof log, NULL, log);
            snprintf(why, whylen, "%s: it did not link: %s", what, log);
            glDeleteProgram(prg);
            prg = 0;
        }
    }
    if (vs) glDeleteShader(vs);
    if (fs) glDeleteShader(fs);
    return prg;
}

char *gl_program_fullscreen_vert(const char *version) {
    char *t = NULL;
    str_appendf(&t, "%s\nvoid main() {\n"
                "    vec2 p = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)) - 1.0;\n"
                "    gl_Position = vec4(p, 0.0, 1.0);\n}\n", version);
    return t;
}
