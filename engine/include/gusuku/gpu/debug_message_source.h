#pragma once
// Who sent a VK_EXT_debug_utils message. A debug messenger hears the validation layer and also the Vulkan loader:
// the loader reports through the same callback what it found while scanning the installed drivers (for example
// "loader_icd_scan: Failed loading library associated with ICD JSON ..." when another architecture's Mesa
// drivers are installed beside this one's, as multiarch cross-compiling machines have them). Those notes are about
// the machine, not about gusuku's use of Vulkan, so they must not fail a test; the validation layer's must.

#include <cstring>

#include <vulkan/vulkan.h>

namespace gusuku {

/// True for a note from the Vulkan loader: the loader names every message it sends "Loader Message"
/// (pMessageIdName) and sends it as a general message only. Everything else, the validation layer's messages
/// among them (validation and performance types, and the layer's own general messages), is false.
inline bool isVulkanLoaderMessage(VkDebugUtilsMessageTypeFlagsEXT types,
                                  const VkDebugUtilsMessengerCallbackDataEXT* data) {
    return types == VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT && data != nullptr &&
           data->pMessageIdName != nullptr && std::strcmp(data->pMessageIdName, "Loader Message") == 0;
}

/// The messenger every gusuku context and test device installs: warnings and errors of every type (the loader's
/// notes among them, which the callback tells apart with isVulkanLoaderMessage).
inline VkDebugUtilsMessengerCreateInfoEXT warningAndErrorMessengerInfo(PFN_vkDebugUtilsMessengerCallbackEXT callback,
                                                                       void* user) {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = callback;
    info.pUserData = user;
    return info;
}

}  // namespace gusuku
