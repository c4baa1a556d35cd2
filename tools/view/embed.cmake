# Writes the pool-view page template (INPUT) as a C array (OUTPUT) for pool-sim --view, so the
# installed pool-sim needs no file beside it. Run as: cmake -DINPUT=... -DOUTPUT=... -P embed.cmake
file(READ ${INPUT} hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REGEX REPLACE "(0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,)" "\\1\n" bytes "${bytes}")
file(WRITE ${OUTPUT} "// Generated from tools/view/pool_view.html by tools/view/embed.cmake: do not edit.\n"
  "#include <stddef.h>\n"
  "const char pool_view_template[] = {\n${bytes}0x00};\n"
  "const size_t pool_view_template_size = sizeof pool_view_template - 1;\n")
