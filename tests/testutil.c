#include "tests/testutil.h"

#include <stdio.h>

int zs_test_run(Suite *s) {
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_ENV);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed == 0 ? 0 : 1;
}

const char *zs_test_src(const char *rel) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s/%s", ZS_SOURCE_DIR, rel);
  return buf;
}

const char *zs_test_bin(const char *rel) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s/%s", ZS_BINARY_DIR, rel);
  return buf;
}

uint64_t zs_test_fnv1a(const void *data, size_t n) {
  const unsigned char *p = data;
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}
