/* zscan scene — the syntax of numbers in text inputs (OBJ files, generator
 * specs, command-line values), written once. */
#ifndef ZS_SCENE_TEXT_H
#define ZS_SCENE_TEXT_H

/* Whether s is a decimal number: [+-] digits [. digits] [e [+-] digits],
 * with digits on at least one side of the point.  strtod also reads
 * hexadecimal, "inf", "nan" and leading white space, which no input of
 * zscan means; check with this first, then convert with strtod. */
int zs_text_is_decimal(const char *s);

#endif
