#include "util/malloc_tuning.h"

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace vaegail {

bool retain_freed_memory() {
#if defined(__GLIBC__)
  static const bool ok = [] {
    // No mmap'd chunks at all (so no munmap on free), and never trim the heap's top.
    const bool no_mmap = mallopt(M_MMAP_MAX, 0) == 1;
    const bool no_trim = mallopt(M_TRIM_THRESHOLD, 0x7fffffff) == 1;
    return no_mmap && no_trim;
  }();
  return ok;
#else
  return true;
#endif
}

}  // namespace vaegail
