// Quad corners as files give them: around the quad (0 1 2 3) or, in some
// student and exporter files, row by row (0 1 / 2 3), which read in order
// draws a bow tie.
#pragma once

#include "scene/Scene.hpp"

namespace rt {

// Whether the corners in the order given cross over (the triangles 0 1 2 and
// 0 2 3 face opposite ways).
bool isBowTie(const Quad& quad);

// The corners around the quad: as given, or in the order 0 1 3 2 when they
// were given row by row.
Quad cornersAroundTheQuad(const Quad& quad);

}  // namespace rt
