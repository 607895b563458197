// A storage buffer with its memory. Prefers memory the host can map (lavapipe,
// integrated GPUs, resizable BAR); otherwise transfers go through a staging
// buffer.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>

namespace rt {

class VulkanContext;

// Whether a read of `bytes` from memory of these properties goes through a
// host-cached staging buffer rather than the mapped pointer. Uncached
// host-visible memory, which is most of a discrete GPU's memory with
// resizable BAR, reads at PCIe uncached speed (about 20 MB/s measured on an
// H200: 1.5 s for a million ray hits), so large reads are staged (the staging
// buffer's allocation and copy cost about a millisecond); small ones, such as
// a counter, are read directly. Writes to such memory are write-combined and
// fast, so uploads stay direct.
bool readsThroughStaging(VkMemoryPropertyFlags memory, VkDeviceSize bytes);

class Buffer {
 public:
  Buffer(VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  // Needs VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT in `usage`.
  VkDeviceAddress deviceAddress() const;

  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void fillZero();

 private:
  void release();
  void copyThroughStaging(void* hostData, VkDeviceSize bytes, VkDeviceSize offset, bool toDevice);

  VulkanContext* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;  // persistently mapped when host visible
  VkMemoryPropertyFlags memoryFlags_ = 0;
};

}  // namespace rt
