// Small vector helpers every stage uses.
#ifndef RT_MATH_GLSL
#define RT_MATH_GLSL

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

#endif
