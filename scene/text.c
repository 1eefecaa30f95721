#include "scene/text.h"

static int is_digit(char c) { return c >= '0' && c <= '9'; }

int zs_text_is_decimal(const char *s) {
  if (*s == '+' || *s == '-') s++;
  const char *start = s;
  while (is_digit(*s)) s++;
  int digits = s > start;
  if (*s == '.') {
    const char *frac = ++s;
    while (is_digit(*s)) s++;
    digits |= s > frac;
  }
  if (!digits) return 0;
  if (*s == 'e' || *s == 'E') {
    s++;
    if (*s == '+' || *s == '-') s++;
    if (!is_digit(*s)) return 0;
    while (is_digit(*s)) s++;
  }
  return *s == '\0';
}
