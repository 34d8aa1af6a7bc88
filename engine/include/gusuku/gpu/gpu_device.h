#pragma once
// A non-owning view of a Vulkan device, and one-shot submissions on its queue. Everything in gusuku that runs
// on the GPU (the compute helpers, the baker's tracer, the runtime) takes a GpuDevice, so it runs equally on a
// device the AR app created and owns, or on the headless VulkanContext's (which owns one).
//
// Contract for an app's device: the instance, physical device, device and queue outlive every gusuku object
// built on them; the device was created with the queue family given; gusuku creates its own command pools,
// fences, buffers and pipelines on that device (nothing global: no instance, no debug messenger, no device)
// and destroys them with its objects.

#include <cstdint>
#include <functional>
#include <mutex>

#include <vulkan/vulkan.h>

namespace gusuku {

/// Handles and facts of one Vulkan device. Copyable and cheap to pass; owns nothing.
struct GpuDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;      ///< must support compute (and graphics, for the runtime's raster passes)
    uint32_t queue_family_index = 0;     ///< the family `queue` belongs to
    VkPhysicalDeviceProperties properties{};              ///< name, type, API version and `properties.limits`
    VkPhysicalDeviceMemoryProperties memory_properties{};  ///< memory types, for findMemoryType
    /// Vulkan requires external synchronisation of a queue. When the owner also submits to `queue` from other
    /// threads, it passes the mutex it holds around its own vkQueueSubmit calls, and gusuku holds it around
    /// its own. Null: the owner promises not to submit to `queue` while a gusuku call is submitting.
    std::mutex* queue_mutex = nullptr;
    /// The apiVersion the owner created `instance` with (VkApplicationInfo::apiVersion). Below 1.1, gusuku makes
    /// no Vulkan 1.1 query on it, and the runtime opens without its colour matches (they need 1.1's subgroups).
    uint32_t instance_api_version = VK_API_VERSION_1_1;

    /// Fills properties and memory_properties from the physical device (two Vulkan queries, no allocation).
    static GpuDevice describe(VkInstance instance, VkPhysicalDevice physical_device, VkDevice device, VkQueue queue,
                              uint32_t queue_family_index, std::mutex* queue_mutex = nullptr,
                              uint32_t instance_api_version = VK_API_VERSION_1_1);

    const VkPhysicalDeviceLimits& limits() const { return properties.limits; }
    /// Index of a memory type allowed by type_bits whose flags include `required`; std::runtime_error if none.
    uint32_t findMemoryType(uint32_t type_bits, VkMemoryPropertyFlags required) const;
    /// vkQueueSubmit on `queue`, holding queue_mutex (when given) around it, as the contract above asks.
    VkResult submitToQueue(const VkSubmitInfo& submit_info, VkFence fence) const;
    /// Like findMemoryType, but first tries required | preferred and returns -1 when even `required` is absent.
    int32_t findMemoryTypePreferring(uint32_t type_bits, VkMemoryPropertyFlags required,
                                     VkMemoryPropertyFlags preferred) const;
};

/// One-shot command submission on a GpuDevice's queue: owns a transient command pool and a fence on that
/// device. For setup work (uploads, baker dispatches), not for a frame loop: each call allocates a command
/// buffer, submits it and waits on the fence. Not copyable; thread-safe (calls are serialised).
class GpuSubmitter {
public:
    /// Creates the pool and fence on gpu.device; std::runtime_error on Vulkan failure. `gpu` must outlive this.
    explicit GpuSubmitter(const GpuDevice& gpu);
    ~GpuSubmitter();
    GpuSubmitter(const GpuSubmitter&) = delete;
    GpuSubmitter& operator=(const GpuSubmitter&) = delete;

    /// Records `record` into a fresh primary command buffer, submits it to gpu.queue and waits on the fence.
    /// Exceptions thrown by `record` propagate after the command buffer is freed.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record);

    const GpuDevice& gpu() const { return gpu_; }

private:
    const GpuDevice& gpu_;
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    std::mutex own_mutex_;  // serialises this submitter's pool and fence
};

/// Throws std::runtime_error naming the call when result is not VK_SUCCESS.
void checkVk(VkResult result, const char* what);

}  // namespace gusuku
