// The test harness fails on the validation layer's messages only: a Vulkan driver JSON that cannot be loaded,
// installed beside a good one (a multiarch machine with another architecture's Mesa drivers), makes the loader
// report through the debug messenger, and that note must not fail a test.
//
// Each test sets VK_ICD_FILENAMES before its first Vulkan instance: ctest runs every test in its own process
// (gtest_discover_tests), so the driver list of the other tests is untouched.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app_owned_device.h"
#include "gpu_test_support.h"
#include "gusuku/gpu/debug_message_source.h"
#include "gusuku/gpu/vulkan_context.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;

// The installed driver JSONs of this machine, lavapipe's among them (CI installs mesa-vulkan-drivers).
std::vector<std::string> installedDriverJsons() {
    std::vector<std::string> jsons;
    for (const char* folder : {"/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d"}) {
        std::error_code error;
        for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
            if (entry.path().extension() == ".json") jsons.push_back(entry.path().string());
    }
    return jsons;
}

// A driver JSON whose library does not exist, as the loader meets an arm64 driver's JSON on an x86_64 machine.
std::string writeUnloadableDriverJson() {
    const std::string folder = testing::makeTemporaryDirectory("gusuku-bad-icd");
    const std::string path = folder + "/gusuku_missing_icd.json";
    std::ofstream(path) << R"({"file_format_version": "1.0.0", "ICD": {"library_path": ")" << folder
                        << R"(/libvulkan_gusuku_missing.so", "api_version": "1.3.0"}})" << '\n';
    return path;
}

// Points the loader at the bad JSON first, then every installed one.
std::string useBadDriverBesideGoodOnes() {
    const std::vector<std::string> good = installedDriverJsons();
    if (good.empty()) return "";
    const std::string bad = writeUnloadableDriverJson();
    std::string list = bad;
    for (const std::string& json : good) list += ":" + json;
    setenv("VK_ICD_FILENAMES", list.c_str(), 1);
    return bad;
}

struct CollectedMessages {
    std::vector<std::string> loader_notes;
    std::vector<std::string> others;
};

VKAPI_ATTR VkBool32 VKAPI_CALL collect(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT types,
                                       const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* messages = static_cast<CollectedMessages*>(user);
    (isVulkanLoaderMessage(types, data) ? messages->loader_notes : messages->others)
        .push_back(data && data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

TEST(VulkanLoaderMessages, AnUnloadableDriverJsonIsTheLoadersNoteNotAValidationMessage) {
    const std::string bad_json = useBadDriverBesideGoodOnes();
    if (bad_json.empty()) GTEST_SKIP() << "no Vulkan driver JSON installed in /usr/share/vulkan/icd.d";

    // The premise: with the bad JSON listed, the loader does send a warning through a messenger chained into
    // vkCreateInstance, and the classifier calls it the loader's.
    CollectedMessages messages;
    VkDebugUtilsMessengerCreateInfoEXT messenger_info = warningAndErrorMessengerInfo(&collect, &messages);
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkApplicationInfo application{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    application.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pNext = &messenger_info;
    instance_info.pApplicationInfo = &application;
    instance_info.enabledExtensionCount = 1;
    instance_info.ppEnabledExtensionNames = &extension;
    VkInstance instance = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateInstance(&instance_info, nullptr, &instance), VK_SUCCESS);
    vkDestroyInstance(instance, nullptr);
    bool names_the_bad_json = false;
    for (const std::string& note : messages.loader_notes)
        names_the_bad_json = names_the_bad_json || note.find("libvulkan_gusuku_missing.so") != std::string::npos;
    EXPECT_TRUE(names_the_bad_json) << messages.loader_notes.size() << " loader notes, none naming its library ("
                                    << bad_json << ")";
    EXPECT_TRUE(messages.others.empty()) << messages.others.front();

    // The harness's own context, validation on: it opens lavapipe (or whichever good driver) and counts nothing.
    VulkanContextOptions options;
    options.enable_validation = true;
    VulkanContext context(options);
    EXPECT_TRUE(context.validationEnabled());
    EXPECT_EQ(context.validationMessageCount(), 0u)
        << (context.validationMessages().empty() ? "" : context.validationMessages().front());
}

TEST(VulkanLoaderMessages, AnAppsOwnDeviceBesideAnUnloadableDriverJsonCollectsNoMessage) {
    if (useBadDriverBesideGoodOnes().empty())
        GTEST_SKIP() << "no Vulkan driver JSON installed in /usr/share/vulkan/icd.d";
    testing::AppOwnedDevice app;
    app.destroyDevice();
    const std::vector<std::string> messages = app.messages();
    EXPECT_TRUE(messages.empty()) << messages.front();
}

}  // namespace
}  // namespace gusuku
