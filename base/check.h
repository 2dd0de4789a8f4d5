#pragma once
// Internal invariants (programming errors, not user errors): THAW_CHECK(cond, msg) prints the
// condition, file:line and message and aborts. Safe inside OpenMP regions (nothing is thrown).
#include <cstdio>
#include <cstdlib>

#define THAW_CHECK(cond, msg)                                                                 \
  do {                                                                                        \
    if (!(cond)) [[unlikely]] {                                                               \
      std::fprintf(stderr, "thaw: internal check failed: %s at %s:%d: %s\n", #cond, __FILE__, \
                   __LINE__, msg);                                                            \
      std::abort();                                                                           \
    }                                                                                         \
  } while (0)
