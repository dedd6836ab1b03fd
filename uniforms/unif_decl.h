/* unif_decl: a uniform as a scene file declares it, before any shader is
 * seen. The .glib parser (viewer/scene/glib) fills these from a Program
 * line; the uniform model (unif.h) turns them into panel entries. Keeping
 * the declaration here lets the model stand below the parser: uniforms/
 * never includes the scene layer. */
#ifndef TARN_UNIF_DECL_H
#define TARN_UNIF_DECL_H

#ifdef __cplusplus
extern "C" {
#endif

#define UNIF_NAME_MAX 64
#define UNIF_DECL_MAX_NUMS 16   /* numbers one declaration may carry */

typedef enum unif_decl_kind {
    UNIF_DECL_SCALAR = 1,       /* name 5       -> v[0]; also a sampler's unit */
    UNIF_DECL_ARRAY,            /* name [a b c] -> v[0..n-1] */
    UNIF_DECL_SLIDER,           /* name <min default max> -> v = {min, def, max} */
    UNIF_DECL_BOOL,             /* name <true>  -> v[0] = 1 or 0 */
    UNIF_DECL_COLOR             /* name {r g b [a]} -> v[0..3], n = 3 or 4 */
} unif_decl_kind;

typedef struct unif_decl {
    char name[UNIF_NAME_MAX];
    unif_decl_kind kind;
    double v[UNIF_DECL_MAX_NUMS];
    int n;                      /* count of numbers in v */
    int line;                   /* where it was written */
    const char *file;           /* the file it was written in (owned by the caller) */
} unif_decl;

/* A Program's declarations: its `Define` toggles and its uniforms. */
typedef struct unif_program_decl {
    const char *name;           /* the Program's name */
    const char *file;           /* where the Program line is, for messages */
    int line;
    const unif_decl *defines;
    int ndefines;
    const unif_decl *uniforms;
    int nuniforms;
} unif_program_decl;

#ifdef __cplusplus
}
#endif

#endif
