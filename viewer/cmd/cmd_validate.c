/* cmd_validate: `tarn validate [PATH...]`, glslang over packs and scenes
 * (check/validate.h). */
#include "cmd.h"

#include "util.h"
#include "validate.h"

/* No options: every argument is a PATH (validate_run takes them as given). */
const cmd_spec cmd_validate_spec = {
    .name = "validate",
    .synopsis = "[PATH...]\n",
    .about = "Validates shaders with glslang, for every combination of each Program's\n"
             "Define toggles, and prints file:line: message for each error.\n"
             "A PATH is a .glib, a pack directory, a shader file or a directory of them.\n"
             "With no PATH: every pack under packs/ and every scene under scenes/.\n"
             "exit codes: 0 no errors, 1 errors\n",
};

CMD_USAGE_FUNCTION(cmd_validate_usage, cmd_validate_spec)

int cmd_validate(int argc, char **argv) {
    if (cmd_wants_help(argc, argv)) { fputs(cmd_validate_usage(), stdout); return TARN_EXIT_OK; }
    return validate_run((const char *const *)argv, argc, tarn_root(), stdout);
}
