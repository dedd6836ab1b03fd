# Turns a GLSL file into a C header holding it as a string, so a shader
# that is part of the program (not a pack a person edits) is built into
# it: no file to find at run time, installed or not.
#   cmake -DIN=file.frag -DOUT=file_frag.h -DNAME=symbol -P embed.cmake
file(READ "${IN}" text)
string(REPLACE "\\" "\\\\" text "${text}")
string(REPLACE "\"" "\\\"" text "${text}")
string(REPLACE "\n" "\\n\"\n\"" text "${text}")
get_filename_component(base "${IN}" NAME)
file(WRITE "${OUT}" "/* generated from ${base} by embed.cmake: edit the .frag, not this */\nstatic const char ${NAME}[] =\n\"${text}\";\n")
