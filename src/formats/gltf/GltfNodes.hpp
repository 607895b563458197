// The glTF node hierarchy: validation (references, strict trees), which
// nodes a scene starts from, and node transforms.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "formats/gltf/GltfContext.hpp"

namespace rt::gltf {

// Checks every node's children, mesh and camera indices, and that the nodes
// form disjoint trees (glTF 2.0 section 3.5.3): a node with two parents or a
// node that is its own ancestor is an error. Walking the result can neither
// loop nor visit a node twice.
void validateNodeGraph(const Context& context);

// The root nodes to draw: those of `scene` if given, else of scene 0, else
// (a file without scenes) every node without a parent, with a warning.
std::vector<int> sceneRoots(Context& context);

// A node's local transform: its matrix, or translation * rotation * scale.
// Fails unless every number is finite and the matrix is affine.
glm::dmat4 localTransform(const Context& context, int node);

// EXT_mesh_gpu_instancing: the transforms (translation * rotation * scale)
// that place the node's mesh once each, applied before the node's own world
// transform; a single identity when the node has no instancing.
std::vector<glm::dmat4> instanceTransforms(Context& context, int node);

}  // namespace rt::gltf
