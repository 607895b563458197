#version 460
// The noise of every adaptive tile (noise_types.h), its pixels summed in a
// fixed order, so the sums (and the decisions the host makes from them) are
// the same every run.
#extension GL_GOOGLE_include_directive : require

#include "noise_types.h"

// One invocation per tile, summing its pixels in order: no shared memory and
// no barriers, which llvmpipe runs slowly (a 64-invocation reduction in
// shared memory made adaptive renders on lavapipe 1.1x slower than reading
// the sums back to the CPU); neighbouring lanes take neighbouring tiles.
layout(local_size_x = RT_NOISE_WORKGROUP_SIZE) in;

layout(push_constant) uniform TileNoiseParamsBlock { GpuTileNoiseParams params; };

layout(std430, set = 0, binding = RT_NOISE_BINDING_ACCUMULATION) readonly buffer Accumulation {
  vec4 allSums[];
};
layout(std430, set = 0, binding = RT_NOISE_BINDING_ACCUMULATION_ODD) readonly buffer OddAccumulation {
  vec4 oddSums[];
};
layout(std430, set = 0, binding = RT_NOISE_BINDING_TILES) writeonly buffer Tiles {
  GpuTileNoise tiles[];
};
layout(std430, set = 0, binding = RT_NOISE_BINDING_PIXEL_EXTRAS) readonly buffer PixelExtras {
  uint pixelExtras[];
};
// The tiles whose sums changed since the last measurement (params.listedTiles
// of them): an adaptive round after the first samples few of the tiles, and
// the others keep what the last measurement wrote.
layout(std430, set = 0, binding = RT_NOISE_BINDING_TILE_LIST) readonly buffer TileList {
  uint tileList[];
};

void main() {
  uvec2 grid = adaptiveTileGrid(params.size);
  uint index = gl_GlobalInvocationID.x;
  if (params.listedTiles != 0u) {
    if (index >= params.listedTiles) return;
    index = tileList[index];
  }
  if (index >= grid.x * grid.y) return;
  uvec2 corner = uvec2(index % grid.x, index / grid.x) * RT_ADAPTIVE_TILE_SIZE;
  uvec2 start = max(corner, params.regionStart);
  uvec2 end = min(corner + RT_ADAPTIVE_TILE_SIZE, params.regionEnd);
  GpuTileNoise tile;
  tile.varianceSum = 0.0;
  tile.squaredSum = 0.0;
  tile.inverseCountSum = 0.0;
  tile.measured = 0u;
  tile.unsampled = 0u;
  tile.pooled = 0u;
  tile.edgeVarianceSum = 0.0;
  tile.pad0 = 0u;
  for (uint y = start.y; y < end.y; ++y) {
    for (uint x = start.x; x < end.x; ++x) {
      uint pixel = y * params.size.x + x;
      vec4 sum = allSums[pixel];
      float squared = pixelSquaredError(sum, oddSums[pixel], params.exposure, params.toneCurve,
                                        params.srgbEncode);
      if (squared >= 0.0) {
        if (params.hasPixelExtras != 0u && pixelExtras[pixel] > 0u) {
          tile.edgeVarianceSum += squared * sum.w;
        } else {
          tile.varianceSum += squared * sum.w;
          tile.pooled += 1u;
        }
        tile.squaredSum += squared;
        tile.measured += 1u;
      } else if (sum.w > 0.0) {
        tile.inverseCountSum += 1.0 / sum.w;
      } else {
        tile.unsampled += 1u;
      }
    }
  }
  tiles[index] = tile;
}
