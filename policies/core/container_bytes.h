#pragma once
// What the planners add for a standard container's bookkeeping when they report their memory.
#include <cstddef>

namespace ambisim {

// A std::map node holds the value plus three links and a colour word.
inline constexpr std::size_t kMapNodeOverhead = 4 * sizeof(void*);

// A heap block of its own (std::make_unique): the allocator's size word and its rounding to
// 16 bytes, about 16 bytes on glibc for the sizes counted here.
inline constexpr std::size_t kHeapBlockOverhead = 2 * sizeof(void*);

}  // namespace ambisim
