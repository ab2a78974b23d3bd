#include "tools/memory.h"

#include <malloc.h>

namespace glint::cli {

void give_back_free_memory() { malloc_trim(0); }

}  // namespace glint::cli
