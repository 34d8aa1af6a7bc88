// The counting allocator of allocation_counter.h. glibc's __libc_* entry points do the allocating, so the
// replacements below never call themselves.

#include "allocation_counter.h"

#include <dlfcn.h>
#include <execinfo.h>

#include <cstdlib>
#include <cstring>
#include <new>

extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* pointer, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
void __libc_free(void* pointer);
}

namespace gusuku::testing {
namespace {

constexpr int kMaxFrames = 48;
constexpr int kKeptStacks = 4;

thread_local bool t_counting = false;
thread_local bool t_inside = false;  // an allocation made while examining one is not examined again
thread_local size_t t_count = 0;
thread_local void* t_stacks[kKeptStacks][kMaxFrames];
thread_local int t_stack_depths[kKeptStacks];

// A stack frame in one of these shared objects makes the allocation the Vulkan side's.
bool isVulkanSide(const char* object_path) {
    if (object_path == nullptr) return false;
    for (const char* marker : {"libvulkan", "VkLayer", "lvp", "LLVM", "gallium", "mesa", "vk_swiftshader"})
        if (std::strstr(object_path, marker) != nullptr) return true;
    return false;
}

void noteAllocation() {
    if (!t_counting || t_inside) return;
    t_inside = true;
    void* frames[kMaxFrames];
    const int depth = backtrace(frames, kMaxFrames);
    bool vulkan_side = false;
    for (int index = 0; index < depth && !vulkan_side; ++index) {
        Dl_info info{};
        if (dladdr(frames[index], &info) != 0) vulkan_side = isVulkanSide(info.dli_fname);
    }
    if (!vulkan_side) {
        if (t_count < size_t(kKeptStacks)) {
            std::memcpy(t_stacks[t_count], frames, sizeof(void*) * size_t(depth));
            t_stack_depths[t_count] = depth;
        }
        ++t_count;
    }
    t_inside = false;
}

}  // namespace

void startCountingAllocations() {
    // backtrace's first call loads the unwinder (which allocates): make it before counting.
    void* frames[4];
    backtrace(frames, 4);
    t_count = 0;
    t_counting = true;
}

size_t stopCountingAllocations() {
    t_counting = false;
    return t_count;
}

std::string countedAllocationStacks() {
    std::string text;
    const int kept = t_count < size_t(kKeptStacks) ? int(t_count) : kKeptStacks;
    for (int stack = 0; stack < kept; ++stack) {
        text += "allocation " + std::to_string(stack + 1) + ":\n";
        char** symbols = backtrace_symbols(t_stacks[stack], t_stack_depths[stack]);
        for (int index = 0; symbols != nullptr && index < t_stack_depths[stack]; ++index)
            text += std::string("  ") + symbols[index] + "\n";
        std::free(symbols);
    }
    return text;
}

}  // namespace gusuku::testing

using gusuku::testing::noteAllocation;

extern "C" {
void* malloc(size_t size) {
    noteAllocation();
    return __libc_malloc(size);
}
void* calloc(size_t count, size_t size) {
    noteAllocation();
    return __libc_calloc(count, size);
}
void* realloc(void* pointer, size_t size) {
    noteAllocation();
    return __libc_realloc(pointer, size);
}
void free(void* pointer) { __libc_free(pointer); }
void* memalign(size_t alignment, size_t size) {
    noteAllocation();
    return __libc_memalign(alignment, size);
}
void* aligned_alloc(size_t alignment, size_t size) {
    noteAllocation();
    return __libc_memalign(alignment, size);
}
int posix_memalign(void** result, size_t alignment, size_t size) {
    noteAllocation();
    *result = __libc_memalign(alignment, size);
    return *result != nullptr ? 0 : ENOMEM;
}
}

namespace {
void* allocateCounted(size_t size) {
    noteAllocation();
    void* pointer = __libc_malloc(size == 0 ? 1 : size);
    if (pointer == nullptr) throw std::bad_alloc();
    return pointer;
}
void* allocateCountedAligned(size_t size, std::align_val_t alignment) {
    noteAllocation();
    void* pointer = __libc_memalign(size_t(alignment), size == 0 ? 1 : size);
    if (pointer == nullptr) throw std::bad_alloc();
    return pointer;
}
}  // namespace

void* operator new(size_t size) { return allocateCounted(size); }
void* operator new[](size_t size) { return allocateCounted(size); }
void* operator new(size_t size, const std::nothrow_t&) noexcept {
    noteAllocation();
    return __libc_malloc(size == 0 ? 1 : size);
}
void* operator new[](size_t size, const std::nothrow_t&) noexcept {
    noteAllocation();
    return __libc_malloc(size == 0 ? 1 : size);
}
void* operator new(size_t size, std::align_val_t alignment) { return allocateCountedAligned(size, alignment); }
void* operator new[](size_t size, std::align_val_t alignment) { return allocateCountedAligned(size, alignment); }
void operator delete(void* pointer) noexcept { __libc_free(pointer); }
void operator delete[](void* pointer) noexcept { __libc_free(pointer); }
void operator delete(void* pointer, size_t) noexcept { __libc_free(pointer); }
void operator delete[](void* pointer, size_t) noexcept { __libc_free(pointer); }
void operator delete(void* pointer, std::align_val_t) noexcept { __libc_free(pointer); }
void operator delete[](void* pointer, std::align_val_t) noexcept { __libc_free(pointer); }
void operator delete(void* pointer, size_t, std::align_val_t) noexcept { __libc_free(pointer); }
void operator delete[](void* pointer, size_t, std::align_val_t) noexcept { __libc_free(pointer); }
