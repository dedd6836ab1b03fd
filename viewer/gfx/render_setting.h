/* render_setting: one of a pack's named settings (packs/NAME/bench.txt,
 * packset.h) applied to a loaded scene, the same way for the view
 * window's Setting combo, its `setting NAME` script action, a session
 * replay, `tarn render/view --setting NAME` and `--set`: every slider,
 * checkbox, colour and Define back to the pack's defaults, then the
 * setting's assignments in order (packset_apply, as `tarn bench` does on
 * a fresh load); a Define that changed rebuilds the programs. A
 * scene.Command=ARGS assignment applies when the renderer takes that
 * command at run time (render_set_world_override: WaterMesh), through a
 * reload of the scene; any other is reported as not applicable. */
#ifndef TARN_RENDER_SETTING_H
#define TARN_RENDER_SETTING_H

#include <stdbool.h>

#include "packset.h"
#include "render.h"

/* true when every assignment of s can be applied to a running scene
 * (its scene.X ones included); false names the first that cannot in why. */
bool render_setting_applicable(const packset_setting *s, char *why, int whylen);

/* Applies s on top of what r holds now (no reset first): the uniform and
 * Define assignments, then the scene ones (a reload when they change the
 * world). False, with a message a line in msg, when an assignment did not
 * apply as written (a missing entry, a clamped value, a scene command the
 * renderer does not take, a failed rebuild); the rest is applied. */
bool render_setting_assign(render *r, const packset_setting *s, char *msg, int msglen);

/* The pack's defaults, then s (NULL: the defaults alone, the implicit
 * `default` of a pack whose bench.txt has none): what choosing s in the
 * panel does. The world overrides of an earlier setting are dropped. */
bool render_setting_apply(render *r, const packset_setting *s, char *msg, int msglen);

/* render_setting_apply for the setting called name of the pack drawing r
 * (root/packs/PACK/bench.txt; root NULL: tarn_root()). "default" is the
 * pack's defaults when bench.txt has no such line. False with the reason
 * in msg when there is no such setting (the names it has are listed) or
 * r draws no pack. */
bool render_setting_apply_named(render *r, const char *root, const char *name, char *msg, int msglen);

#endif
