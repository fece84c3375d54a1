# Compiles the gnuplot scripts of share/gnuplot/ into post: writes OUT, a C
# file defining plot_script() (post/plot.h).
#   cmake -DDIR=share/gnuplot -DSCRIPTS=a,b -DOUT=scripts.c -P embed.cmake
set(body "/* Generated from share/gnuplot/ by post/embed.cmake. */\n")
string(APPEND body "#include <string.h>\n\n#include \"post/plot.h\"\n\n")
set(table "")
string(REPLACE "," ";" SCRIPTS "${SCRIPTS}")
foreach(name ${SCRIPTS})
  file(READ ${DIR}/${name}.gp hex HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," hex "${hex}")
  string(APPEND body "static const unsigned char s_${name}[] = {${hex}0x00};\n")
  string(APPEND table "\t\t{\"${name}\", s_${name}},\n")
endforeach()
string(APPEND body "\nconst char *plot_script(const char *name)\n{\n")
string(APPEND body "\tstatic const struct {\n\t\tconst char *name;\n\t\tconst unsigned char *text;\n")
string(APPEND body "\t} scripts[] = {\n${table}\t};\n")
string(APPEND body "\tfor (size_t k = 0; k < sizeof scripts / sizeof scripts[0]; k++)\n")
string(APPEND body "\t\tif (strcmp(scripts[k].name, name) == 0)\n")
string(APPEND body "\t\t\treturn (const char *)scripts[k].text;\n\treturn NULL;\n}\n")
file(WRITE ${OUT}.new "${body}")
# Touch OUT only when it changes, so an unchanged script rebuilds nothing.
configure_file(${OUT}.new ${OUT} COPYONLY)
