#pragma once
// What the planners add for a standard container's bookkeeping when they report their memory.
#include <cstddef>

namespace ambisim {

// A std::map node holds the value plus three links and a colour word.
inline constexpr std::size_t kMapNodeOverhead = 4 * sizeof(void*);

}  // namespace ambisim
