// Test support shared by every test binary (see gpu_test_support.h).

#include "gpu_test_support.h"

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <system_error>

namespace gusuku::testing {

namespace {

std::unique_ptr<VulkanContext>& sharedContextSlot() {
    static std::unique_ptr<VulkanContext> context;
    return context;
}

// Destroys the shared context when the test run ends, inside main, not in a static destructor after it. The slot
// above is constructed before the first vkCreateInstance, so its destructor runs after the driver's own static
// destructors (the exit handlers run in reverse order of registration, and the driver registers its own while
// the instance and device are created): a SwiftShader thread that vkDestroyDevice joins then runs into the
// torn-down driver and the binary dies with SIGSEGV after all its tests passed (rc 139).
// tests/drivers/swiftshader_exit_order.cpp reproduces that without gusuku.
class SharedContextRelease : public ::testing::Environment {
public:
    void TearDown() override { sharedContextSlot().reset(); }
};

[[maybe_unused]] ::testing::Environment* const shared_context_release =
    ::testing::AddGlobalTestEnvironment(new SharedContextRelease);

}  // namespace

VulkanContext& sharedGpuContext() {
    // One context per binary: creating an instance with the validation layer takes a noticeable fraction of a
    // second on lavapipe. Built on first use, so pure-CPU tests never touch Vulkan. If creation throws, the
    // next call tries again and throws the same reason, so every GPU test reports it.
    std::unique_ptr<VulkanContext>& context = sharedContextSlot();
    if (!context) {
        VulkanContextOptions options = vulkanOptionsFromEnvironment();
        options.enable_validation = true;
        context = std::make_unique<VulkanContext>(options);
    }
    return *context;
}

void GpuTest::SetUp() {
    try {
        context_ = &sharedGpuContext();
    } catch (const std::exception& error) {
        FAIL() << "no Vulkan context for this GPU test: " << error.what();
    }
    messages_before_ = context_->validationMessageCount();
}

void GpuTest::TearDown() {
    if (context_ == nullptr) return;
    const std::vector<std::string> messages = context_->validationMessages();
    for (size_t index = messages_before_; index < messages.size(); ++index)
        ADD_FAILURE() << "Vulkan validation message during the test: " << messages[index];
    messages_before_ = messages.size();
}

std::vector<std::string> GpuTest::takeValidationMessages() {
    if (context_ == nullptr) return {};
    const std::vector<std::string> messages = context_->validationMessages();
    std::vector<std::string> taken(messages.begin() + static_cast<std::ptrdiff_t>(messages_before_), messages.end());
    messages_before_ = messages.size();
    return taken;
}

std::string sharedDataDir() {
    std::error_code error;
    const std::filesystem::path directory(GUSUKU_SHARED_DATA_DIR);
    if (!std::filesystem::is_directory(directory, error)) return "";
    const std::filesystem::path canonical = std::filesystem::canonical(directory, error);
    return error ? "" : canonical.string();
}

std::string makeTemporaryDirectory(const std::string& prefix) {
    // mkdtemp, not a generated name checked for existence: two test binaries run in parallel under CTest.
    std::string safe_prefix = prefix.empty() ? "gusuku_test" : prefix;
    for (char& character : safe_prefix)
        if (character == '/') character = '_';
    std::error_code error;
    std::filesystem::path base = std::filesystem::temp_directory_path(error);
    if (error) base = "/tmp";
    std::string pattern = (base / (safe_prefix + "_XXXXXX")).string();
    if (mkdtemp(pattern.data()) == nullptr)
        throw std::system_error(errno, std::generic_category(), "mkdtemp " + pattern);
    return pattern;
}

std::string bakeExecutablePath() { return GUSUKU_BAKE_EXECUTABLE; }

}  // namespace gusuku::testing
