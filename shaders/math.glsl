// Small vector helpers every stage uses.
#ifndef RT_MATH_GLSL
#define RT_MATH_GLSL

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

// The corners' weights at barycentric coordinates (u, v) of the second and
// third corner.
vec3 cornerWeights(vec2 barycentric) {
  return vec3(1.0 - barycentric.x - barycentric.y, barycentric);
}

#endif
