// Counter-based random numbers: every value is a pure function of
// (pixel, sample index, dimension, seed), so a render can be split over
// dispatches, tiles or machines and still produce the same samples.
#ifndef RT_RNG_GLSL
#define RT_RNG_GLSL

#include "gpu_types.h"

// Random dimensions used by the kernels (each a pair of numbers).
#define RT_DIM_PIXEL 0u
#define RT_DIM_LENS 2u


// Dimensions drawn at a path vertex (a hit; depth 0 is the primary hit):
// each vertex has its own block, so no two vertices share a dimension.
#define RT_DIM_VERTEX_BASE 64u
#define RT_DIMS_PER_VERTEX 1024u
#define RT_VERTEX_DIM_BOUNCE 0u  // direction of a sampled diffuse bounce
#define RT_VERTEX_DIM_LOBE 2u    // which continuation the path takes (x), Fresnel choice (y)
#define RT_VERTEX_DIM_LIGHTS 4u  // + 2 * area light index: points on that light

uint vertexDimension(uint depth, uint offset) {
  return RT_DIM_VERTEX_BASE + depth * RT_DIMS_PER_VERTEX + offset;
}

// Four rounds of mixing of a 4-component counter (a PCG-style hash: every
// input bit affects every output bit after the second round).
uvec4 hashCounter(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  return v;
}

// Top 24 bits to a float in [0, 1): exact, never rounds up to 1.
float unitFloat(uint bits) { return float(bits >> 8u) * (1.0 / 16777216.0); }

vec2 randomPair(uint pixel, uint sampleIndex, uint dimension, uint seed) {
  uvec4 h = hashCounter(uvec4(pixel, sampleIndex, dimension, seed));
  return vec2(unitFloat(h.x), unitFloat(h.y));
}

// One round of keyed invertible mixing on [0, mask] (mask = 2^k - 1).
uint permuteRound(uint v, uint mask, uint key) {
  v ^= key & mask;
  v = (v * 0x2c1b3c6du) & mask;  // odd multiplier: bijective modulo 2^k
  v ^= (v & mask) >> 3u;
  v = (v * 0x297a2d39u) & mask;
  v ^= (v >> 5u) ^ ((key >> 16u) & mask);
  v = (v * 0x8ebc6af1u) & mask;
  v ^= v >> 7u;
  return v;
}

// A bijection of [0, n) keyed by `key`: permuteRound on the smallest
// power-of-two domain that holds n, walked until the value falls inside
// (cycle walking keeps it a permutation of exactly [0, n)). The walk is
// behind a branch: on a SIMD driver a loop costs its bookkeeping even when
// every lane leaves after the first round.
uint permuteIndex(uint index, uint n, uint key) {
  uint mask = n - 1u;
  mask |= mask >> 1u;
  mask |= mask >> 2u;
  mask |= mask >> 4u;
  mask |= mask >> 8u;
  mask |= mask >> 16u;
  uint v = permuteRound(index, mask, key);
  if (v >= n) {
    // n > mask / 2, so from a value inside [0, n) the walk meets the next
    // one within mask / 2 + 1 rounds: the bound never cuts a walk short.
    for (uint step = 1u; step <= mask / 2u && v >= n; ++step) v = permuteRound(v, mask, key);
  }
  return v;
}

// a / b for b >= 1 where the quotient is below 2^20 (here: a cell index over
// a column count near its square root). Vector hardware has no integer
// division (CPU drivers divide lane by lane): the float quotient is within
// 0.4 of the true one (Vulkan allows division 2.5 ulp of error), and one step
// on the exact integer remainder, which lies in (-b, 2b), corrects the
// truncation.
uint quotientOfSmall(uint a, uint b) {
  uint q = uint(float(a) / float(b));
  int remainder = int(a - q * b);
  return remainder < 0 ? q - 1u : (remainder >= int(b) ? q + 1u : q);
}

// Sample `s` of `count` in `cell` of a grid of columns x rows cells, at
// sub-column sub.x of rows and sub-row sub.y of columns (multi-jittered),
// offset inside that by a hash of the sample. Both jitteredPoint paths end
// here; on a power-of-two grid the divisions are exact scalings.
vec2 jitteredCellPoint(uint s, uint count, uint key, uvec2 cell, uvec2 sub, uvec2 grid) {
  uvec4 h = hashCounter(uvec4(s, count, key, 0x51ed27u));
  vec2 size = vec2(grid);
  float x = (float(cell.x) + (float(sub.x) + unitFloat(h.x)) / size.y) / size.x;
  float y = (float(cell.y) + (float(sub.y) + unitFloat(h.y)) / size.x) / size.y;
  return min(vec2(x, y), vec2(0.99999994));
}

// jitteredPoint for count = 2^k: 2^ceil(k/2) x 2^floor(k/2) cells (8 samples
// 4 x 2, not 3 x 3 with one left out), so that every permutation is one
// round with no walk and the cell's row and column a shift and a mask.
// Behind a branch that is the same for every lane (the count is the
// render's). A kernel without its walk, 64 samples a pixel: 1.75x the random
// sampler's time through the general grid's square root, quotients and walk
// loops, 1.15x through this path (bench/README.md).
vec2 jitteredPointPowerOfTwo(uint s, uint count, uint key) {
  uint k = uint(findMSB(count));
  uint columnBits = (k + 1u) / 2u, rowBits = k / 2u;
  uint columnMask = (1u << columnBits) - 1u, rowMask = (1u << rowBits) - 1u;
  uint cell = permuteRound(s, count - 1u, key);
  uvec2 cellXY = uvec2(cell & columnMask, cell >> columnBits);
  uint subX = permuteRound(cellXY.y, rowMask, key * 0x9e3779b9u + 1u);
  uint subY = permuteRound(cellXY.x, columnMask, key * 0x85ebca6bu + 2u);
  return jitteredCellPoint(s, count, key, cellXY, uvec2(subX, subY),
                           uvec2(columnMask, rowMask) + 1u);
}

// Stratified 2D point for sample `s` of `count`: the unit square is cut
// into columns x rows >= count cells, about square (columns the ceiling of
// the square root); each sample takes its own cell (a keyed permutation of
// all cells, so when there are more cells than samples the cells left out
// differ from pixel to pixel and no part of the square is always missed)
// and, inside it, its own sub-column and sub-row (multi-jittered), so both
// projections are stratified too. Works for any count, not only squares;
// s < count. Where the grid is not a power of two the permutations walk,
// which a SIMD driver runs until its slowest lane has found its value (when
// 32 samples still had 6 x 6 cells, the common scene took 1.23x the random
// sampler's render time, on 8 x 8 at 64 samples 1.09x; bench/README.md).
vec2 jitteredPoint(uint s, uint count, uint key) {
  if ((count & (count - 1u)) == 0u) return jitteredPointPowerOfTwo(s, count, key);
  uint columns = uint(ceil(sqrt(float(count))));
  uint rows = quotientOfSmall(count + columns - 1u, columns);
  uint cell = permuteIndex(s, columns * rows, key);
  uint cy = quotientOfSmall(cell, columns);
  uint cx = cell - cy * columns;
  uint subX = permuteIndex(cy, rows, key * 0x9e3779b9u + 1u);
  uint subY = permuteIndex(cx, columns, key * 0x85ebca6bu + 2u);
  return jitteredCellPoint(s, count, key, uvec2(cx, cy), uvec2(subX, subY), uvec2(columns, rows));
}

// --- Owen-scrambled Sobol points ---------------------------------------------
// An invertible hash in which output bit j depends only on input bits 0..j
// (additions, odd multiplications and x ^= x * even only carry upwards).
// Run on bit-reversed values it flips every bit by a hash of the bits above
// it: nested uniform (Owen) scrambling, approximated with a few multiplies.
uint carryHash(uint x, uint seed) {
  x += seed;
  x ^= x * 0x6e2a4c18u;
  x *= (seed >> 9u) | 1u;
  x ^= x * 0x3f58d0a2u;
  x += seed >> 17u;
  x ^= x * 0xb4c29e06u;
  x *= 0x2f7a1d93u;
  x ^= x * 0x91e36b5cu;
  return x;
}

uint owenScramble(uint value, uint seed) {
  return bitfieldReverse(carryHash(bitfieldReverse(value), seed));
}

// Second dimension of the Sobol sequence (primitive polynomial x + 1),
// bit-reversed: its direction numbers are the rows of Pascal's triangle mod
// 2, so by Lucas' theorem bit r of the result is the XOR of the index bits k
// whose positions contain r's bits (r & k == r), a superset transform over
// the five bits of a position: one shift-and-mask per bit. (The first
// dimension, bit-reversed, is the index itself.)
uint sobolSecondReversed(uint index) {
  uint y = index;
  y ^= (y >> 1u) & 0x55555555u;
  y ^= (y >> 2u) & 0x33333333u;
  y ^= (y >> 4u) & 0x0f0f0f0fu;
  y ^= (y >> 8u) & 0x00ff00ffu;
  y ^= (y >> 16u) & 0x0000ffffu;
  return y;
}

// Point `index` of a 2D Sobol sequence under three keys: the index is Owen
// scrambled first (each prefix of 2^k indices lands on one aligned block of
// 2^k Sobol points, in shuffled order, so every power-of-two prefix is still
// a (0,k,2)-net), then each coordinate is Owen scrambled, which on the
// bit-reversed values is one carryHash.
vec2 sobolPoint(uint index, uvec3 keys) {
  uint shuffled = owenScramble(index, keys.x);
  uint x = bitfieldReverse(carryHash(shuffled, keys.y));
  uint y = bitfieldReverse(carryHash(sobolSecondReversed(shuffled), keys.z));
  return vec2(unitFloat(x), unitFloat(y));
}

// With RT_SAMPLER_REPLICATES, even and odd pixel samples are two
// independently randomised replicates of the stratified samplers: the error
// estimate (ImageError.hpp) compares their means, which is only unbiased if
// the two share no strata. It costs accuracy (two stratified sets of n/2
// are worse than one of n: README "Speed vs accuracy"), so it is only on
// while the error is estimated.
uvec2 replicateAndIndex(uint samplerKind, uint sampleIndex) {
  if ((samplerKind & RT_SAMPLER_REPLICATES) == 0u) return uvec2(0u, sampleIndex);
  return uvec2(sampleIndex & 1u, sampleIndex >> 1u);
}

uint replicateSamples(uint samplerKind, uint samplesTotal, uint replicate) {
  if ((samplerKind & RT_SAMPLER_REPLICATES) == 0u) return samplesTotal;
  return (samplesTotal + 1u - replicate) >> 1u;  // replicate 0 holds the odd one out
}

// Point `sub` of the `subCount` points that pixel sample `sampleIndex` takes
// from one dimension pair (e.g. several shadow rays per pixel sample): the
// render's samples x subCount points form one stratified set (per
// replicate). Each dimension pair gets its own keys (a padded sampler), so
// pairs are decorrelated. A pure function of (pixel, sample, sub, dimension,
// seed, sampler) and, for jittered, the totals.
vec2 sampleSubPair(uint samplerKind, uint pixel, uint sampleIndex, uint sub, uint subCount,
                   uint samplesTotal, uint dimension, uint seed) {
#ifdef RT_SAMPLER_KIND
  // Fixed by the host for the kernel's life: the other samplers' code is not
  // built (CPU drivers run every branch of an `if` for all lanes).
  const uint kind = RT_SAMPLER_KIND;
#else
  uint kind = samplerKind & ~RT_SAMPLER_REPLICATES;
#endif
  uvec2 replicated = replicateAndIndex(samplerKind, sampleIndex);
  uint replicate = replicated.x;
  uint local = replicated.y * subCount + sub;
  if (kind == RT_SAMPLER_SOBOL) {
    uvec4 keys = hashCounter(uvec4(pixel, dimension, seed, 0x5b0b01u + replicate));
    return sobolPoint(local, keys.xyz);
  }
  uint samples = replicateSamples(samplerKind, samplesTotal, replicate);
  bool countable = samples <= 0xffffffffu / max(subCount, 1u);
  uint replicateTotal = samples * subCount;
  if (kind == RT_SAMPLER_JITTERED && countable && local < replicateTotal) {
    uint key = hashCounter(uvec4(pixel, dimension, seed, 0x6a09e667u + replicate)).x;
    return jitteredPoint(local, replicateTotal, key);
  }
  return randomPair(pixel, sampleIndex * subCount + sub, dimension, seed);
}

// The 2D sample of one dimension pair for (pixel, sample, seed).
vec2 samplePair(uint samplerKind, uint pixel, uint sampleIndex, uint samplesTotal, uint dimension,
                uint seed) {
  return sampleSubPair(samplerKind, pixel, sampleIndex, 0u, 1u, samplesTotal, dimension, seed);
}

#endif
