#pragma once
// Test support shared by every test binary.
// - GPU tests derive from GpuTest: one VulkanContext per test binary with the Khronos validation layer forced
//   on; a test fails if any validation message appeared while it ran.
// - Tests that read ../shared/data call GUSUKU_REQUIRE_SHARED_DATA() first: it skips with a clear message
//   when the folder is absent (a fresh clone without the shared assets).

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/gpu/vulkan_context.h"

namespace gusuku::testing {

/// The test binary's one Vulkan context (validation on). Created on first use; throws if Vulkan or the
/// validation layer is missing, which fails the calling test with the reason.
VulkanContext& sharedGpuContext();

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override;     ///< creates/gets the context, remembers the validation message count
    void TearDown() override;  ///< ADD_FAILURE for every validation message that appeared during the test
    VulkanContext& context() { return *context_; }
    /// For tests that provoke validation messages on purpose: returns the messages that appeared since SetUp
    /// (or the previous call) and accepts them, so TearDown does not fail the test for them.
    std::vector<std::string> takeValidationMessages();

private:
    VulkanContext* context_ = nullptr;
    size_t messages_before_ = 0;
};

/// ../shared/data beside the repository (compile-time path), or "" when it does not exist.
std::string sharedDataDir();

/// A fresh empty temporary directory for one test (removed at process exit is not promised).
std::string makeTemporaryDirectory(const std::string& prefix);

/// Path of the built gusuku-bake executable, for tests that run the command line.
std::string bakeExecutablePath();

}  // namespace gusuku::testing

#define GUSUKU_REQUIRE_SHARED_DATA()                                                                   \
    do {                                                                                               \
        if (::gusuku::testing::sharedDataDir().empty())                                                \
            GTEST_SKIP() << "../shared/data is not beside the repository; skipping the test on shared " \
                            "assets";                                                                  \
    } while (0)
