#pragma once

#include <cstddef>
#include <string>

namespace lucent {

struct GpuBudget {
    std::size_t bytes = 0;
    std::string source; // "asked for", "half of the 81559 MiB the GPU reports", ...
};

// The brick pool's budget: `asked` when non-zero, else half of the memory the
// driver reports (NVX_gpu_memory_info, ATI_meminfo), else 1 GiB. Needs a
// current context.
GpuBudget gpuBudget(std::size_t asked);

} // namespace lucent
