/* glib_pack.c: a scene names the pack that draws its water (`Pack
 * name`, or --pack from outside): the Pack command, the pack's pack.glib
 * read in place, and the packs there are when the name is wrong
 * (glib_internal.h).
 */
#include "glib_internal.h"
#include "packset.h"
#include "mem.h"
#include "strbuf.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* "basic, natural, raymarch" (the directories of dir holding a pack.glib)
 * into out, and the one closest to name into near (or ""). */
static void list_packs(const char *dir, const char *name, char *out, size_t outlen,
                       char near[GLIB_NAME_MAX]) {
    packset_name names[PACKSET_MAX];
    int n = packset_list_dir(dir, names, PACKSET_MAX);
    out[0] = near[0] = '\0';
    size_t len = 0;
    int best = 3;
    for (int i = 0; i < n; i++) {
        glib_append_cut(out, outlen, &len, i ? ", " : "");
        glib_append_cut(out, outlen, &len, names[i]);
        int dist = glib_edit_distance(name, names[i]);
        if (dist < best) {
            best = dist;
            msg_set(near, GLIB_NAME_MAX, "%s", names[i]);
        }
    }
}

/* The scene's pack is `name` (or the override): records the command and,
 * with a packs directory, reads the pack's pack.glib in place. */
static void use_pack(cmdctx *c, glib_cmd *cmd, const char *written) {
    parser *p = c->p;
    const char *name = p->pack_override ? p->pack_override : written;
    if (!packset_name_ok(name)) {
        glib_cerr(c, "Pack: '%.60s'%s is not a pack name: write the name of a directory under packs/, e.g. Pack basic",
             name, p->pack_override ? " (the pack chosen instead of the scene's)" : "");
        return;
    }
    p->pack_seen = true;
    p->pack_file = c->file;
    p->pack_line = c->line;
    snprintf(p->pack_name, sizeof p->pack_name, "%s", name);
    snprintf(cmd->name, sizeof cmd->name, "%s", name);
    glib_push_cmd(p, cmd);
    memset(cmd, 0, sizeof *cmd);        /* pushed: the caller frees nothing */
    if (!p->packs_dir || p->stop)
        return;
    char path[GLIB_PATH_MAX];
    if (snprintf(path, sizeof path, "%s/%s/pack.glib", p->packs_dir, name) >= (int)sizeof path) {
        glib_cerr(c, "Pack %s: the path of its pack.glib is too long (at most %d characters)", name,
             GLIB_PATH_MAX - 1);
        return;
    }
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) {
        char packs[160], near[GLIB_NAME_MAX], hint[GLIB_NAME_MAX + 24] = "";
        list_packs(p->packs_dir, name, packs, sizeof packs, near);
        if (near[0])
            snprintf(hint, sizeof hint, "; did you mean '%s'?", near);
        glib_cerr(c, "Pack: no pack '%s' in %s (no %s/pack.glib); the packs are: %s%s", name,
             p->packs_dir, name, packs[0] ? packs : "(none)", hint);
        return;
    }
    glib_include_file(c, path);
}

bool glib_h_pack(cmdctx *c, glib_cmd *cmd) {
    parser *p = c->p;
    if (c->nwords < 1) {
        glib_cerr(c, "Pack needs a name: %s", c->usage);
        return false;
    }
    glib_warn_extra(c, 1, "");
    if (p->pack_seen) {
        glib_cwarn(c, "Pack %.60s ignored: this scene's pack is already '%s' (%s:%d); a scene has one pack",
              c->words[0], p->pack_name, p->pack_file, p->pack_line);
        return false;
    }
    use_pack(c, cmd, c->words[0]);
    return false;               /* pushed by use_pack, before the pack's commands */
}

/* A pack chosen from outside for a scene that names none: as if the top
 * file ended with `Pack name` (at its line 0). */
void glib_override_pack_at_end(parser *p, const char *file) {
    /* A pack draws the water of a world (Terrain, Water, Sun, Sky...). A
     * plain glman scene draws its own floor and water: given a pack, it
     * would get the pack's world and water on top of its own. Refuse, and
     * say what to do instead. */
    bool world = false;
    for (int i = 0; i < p->sc->ncmds && !world; i++)
        world = p->sc->cmds[i].kind != GLIB_CMD_PACK && glib_cmd_describes_world(p->sc->cmds[i].kind);
    if (!world) {
        glib_report(p, DIAG_ERROR, file, 0,
               "--pack %.60s: this scene describes no world (no Terrain, Water, Sun or Sky command), so a pack "
               "has no water of its own to draw here: it would draw its world over the scene's. Give --pack a "
               "world scene (scenes/lake.glib, scenes/pool.glib), or open this one without --pack",
               p->pack_override);
        return;
    }
    cmdctx c = { .p = p, .file = file, .line = 0, .spec = glib_find_spec("Pack") };
    glib_build_usage(c.spec, c.usage, sizeof c.usage);
    glib_cmd cmd;
    memset(&cmd, 0, sizeof cmd);
    cmd.kind = GLIB_CMD_PACK;
    cmd.file = file;
    use_pack(&c, &cmd, p->pack_override);
}
