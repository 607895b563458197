#include <doctest/doctest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "gpu/Buffer.hpp"
#include "support/TestSupport.hpp"

using namespace rt;

TEST_SUITE("gpu buffers") {
  TEST_CASE("reads of uncached device memory go through a staging buffer when large") {
    const VkMemoryPropertyFlags resizableBar = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT |
                                               VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                               VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    const VkMemoryPropertyFlags hostMemory = resizableBar | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    CHECK(readsThroughStaging(resizableBar, 1 << 20));
    CHECK_FALSE(readsThroughStaging(resizableBar, sizeof(uint32_t)));
    CHECK_FALSE(readsThroughStaging(hostMemory, 1 << 20));
    CHECK(readsThroughStaging(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, sizeof(uint32_t)));
  }

  TEST_CASE("a buffer reads back what was written, small and large, at an offset") {
    std::vector<uint32_t> values(1 << 18);  // 1 MiB: staged where memory is uncached
    std::iota(values.begin(), values.end(), 7u);
    Buffer buffer(test::gpu(), values.size() * sizeof(uint32_t),
                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    buffer.upload(values.data(), values.size() * sizeof(uint32_t));
    std::vector<uint32_t> whole(values.size());
    buffer.download(whole.data(), whole.size() * sizeof(uint32_t));
    CHECK(whole == values);
    uint32_t one = 0;
    buffer.download(&one, sizeof(one), 1000 * sizeof(uint32_t));
    CHECK(one == 1007u);
    std::vector<uint32_t> tail(1 << 16);
    buffer.download(tail.data(), tail.size() * sizeof(uint32_t),
                    (values.size() - tail.size()) * sizeof(uint32_t));
    CHECK(tail.front() == values[values.size() - tail.size()]);
    CHECK(tail.back() == values.back());
    test::checkNoValidationMessages();
  }
}
