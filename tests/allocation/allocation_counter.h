#pragma once
// Counts the host allocations that gusuku's own code makes on one thread, for the "a frame allocates nothing"
// promise (runtime.h). The test executable that links allocation_counter.cpp replaces malloc, calloc, realloc,
// aligned allocation and every operator new; while a thread has counting on, each allocation it makes is walked
// back (glibc backtrace) and counted unless a frame of its stack lies in the Vulkan side of the process (the
// loader, the validation layer, the driver and its LLVM: lavapipe's or SwiftShader's): those allocate per command
// and per submission by their own design (Mesa records each vkCmd* into a malloc'd list; SwiftShader's come from
// libvk_swiftshader.so itself, about 70 a frame), which no runtime can avoid. Everything else
// on the thread (gusuku, the C++ standard library called by it) counts. Other threads are never counted.
//
// Link it into exactly one executable (tests/CMakeLists.txt adds it to test_runtime_allocations alone): it
// defines the global allocation functions, so it lives outside tests/support, whose archive every test links.

#include <cstddef>
#include <string>

namespace gusuku::testing {

/// Starts counting this thread's allocations from zero.
void startCountingAllocations();
/// Stops counting; returns how many allocations this thread made from gusuku's side since the start.
size_t stopCountingAllocations();
/// The first few counted allocations' stacks, symbolised (call after stopCountingAllocations).
std::string countedAllocationStacks();

}  // namespace gusuku::testing
