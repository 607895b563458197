// Small integer arithmetic the host code shares.
#pragma once

#include <cstdint>

namespace rt {

// a / b rounded up (b > 0): how many groups of b cover a items.
constexpr uint32_t divideRoundUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

}  // namespace rt
