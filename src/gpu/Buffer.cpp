#include "gpu/Buffer.hpp"

#include <cstring>
#include <utility>

#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

struct RawBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  uint32_t memoryType = 0;
};

RawBuffer allocate(VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage,
                   VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
  RawBuffer raw;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  vkCheck(vkCreateBuffer(context.device(), &info, nullptr, &raw.buffer), "vkCreateBuffer");
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(context.device(), raw.buffer, &requirements);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  // Acceleration-structure inputs and storage are found by device address.
  VkMemoryAllocateFlagsInfo addressable{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  addressable.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  if (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) alloc.pNext = &addressable;
  try {
    raw.memoryType = context.findMemoryType(requirements.memoryTypeBits, required, preferred);
    alloc.memoryTypeIndex = raw.memoryType;
    vkCheck(vkAllocateMemory(context.device(), &alloc, nullptr, &raw.memory), "vkAllocateMemory");
    vkCheck(vkBindBufferMemory(context.device(), raw.buffer, raw.memory, 0), "vkBindBufferMemory");
  } catch (...) {
    if (raw.memory) vkFreeMemory(context.device(), raw.memory, nullptr);
    vkDestroyBuffer(context.device(), raw.buffer, nullptr);
    throw;
  }
  return raw;
}

constexpr VkBufferUsageFlags kTransferUsage =
    VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

constexpr VkDeviceSize kDirectUncachedReadLimit = 16 * 1024;

}  // namespace

bool readsThroughStaging(VkMemoryPropertyFlags memory, VkDeviceSize bytes) {
  if (!(memory & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)) return true;
  return !(memory & VK_MEMORY_PROPERTY_HOST_CACHED_BIT) && bytes > kDirectUncachedReadLimit;
}

Buffer::Buffer(VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage)
    : context_(&context), size_(size) {
  if (size == 0) throw Error("internal: zero-sized GPU buffer");
  RawBuffer raw =
      allocate(context, size, usage | kTransferUsage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
               VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  buffer_ = raw.buffer;
  memory_ = raw.memory;
  memoryFlags_ = context.memoryTypeFlags(raw.memoryType);
  if (memoryFlags_ & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    vkCheck(vkMapMemory(context.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
  }
}

Buffer::~Buffer() { release(); }

VkDeviceAddress Buffer::deviceAddress() const {
  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = buffer_;
  return vkGetBufferDeviceAddress(context_->device(), &info);
}

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
    memoryFlags_ = std::exchange(other.memoryFlags_, 0);
  }
  return *this;
}

void Buffer::release() {
  if (!context_) return;
  VkDevice device = context_->device();
  if (mapped_) vkUnmapMemory(device, memory_);
  if (buffer_) vkDestroyBuffer(device, buffer_, nullptr);
  if (memory_) vkFreeMemory(device, memory_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

void Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (offset + bytes > size_) throw Error("internal: upload past the end of a GPU buffer");
  if (!mapped_) {
    copyThroughStaging(const_cast<void*>(data), bytes, offset, true);
    return;
  }
  std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
  if (!(memoryFlags_ & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)) {
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, 0,
                              VK_WHOLE_SIZE};
    vkCheck(vkFlushMappedMemoryRanges(context_->device(), 1, &range), "vkFlushMappedMemoryRanges");
  }
}

void Buffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (offset + bytes > size_) throw Error("internal: download past the end of a GPU buffer");
  if (readsThroughStaging(memoryFlags_, bytes)) {
    copyThroughStaging(data, bytes, offset, false);
    return;
  }
  if (!(memoryFlags_ & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)) {
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, 0,
                              VK_WHOLE_SIZE};
    vkCheck(vkInvalidateMappedMemoryRanges(context_->device(), 1, &range),
            "vkInvalidateMappedMemoryRanges");
  }
  std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
}

void Buffer::fillZero() {
  context_->submitAndWait(
      [&](VkCommandBuffer commands) { vkCmdFillBuffer(commands, buffer_, 0, VK_WHOLE_SIZE, 0); });
}

void Buffer::copyThroughStaging(void* hostData, VkDeviceSize bytes, VkDeviceSize offset,
                                bool toDevice) {
  VkDevice device = context_->device();
  RawBuffer staging =
      allocate(*context_, bytes, kTransferUsage,
               VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
               VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
  void* mapped = nullptr;
  try {
    vkCheck(vkMapMemory(device, staging.memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    if (toDevice) std::memcpy(mapped, hostData, bytes);
    context_->submitAndWait([&](VkCommandBuffer commands) {
      VkBufferCopy region{toDevice ? 0 : offset, toDevice ? offset : 0, bytes};
      vkCmdCopyBuffer(commands, toDevice ? staging.buffer : buffer_,
                      toDevice ? buffer_ : staging.buffer, 1, &region);
    });
    if (!toDevice) std::memcpy(hostData, mapped, bytes);
  } catch (...) {
    vkFreeMemory(device, staging.memory, nullptr);
    vkDestroyBuffer(device, staging.buffer, nullptr);
    throw;
  }
  vkFreeMemory(device, staging.memory, nullptr);
  vkDestroyBuffer(device, staging.buffer, nullptr);
}

}  // namespace rt
