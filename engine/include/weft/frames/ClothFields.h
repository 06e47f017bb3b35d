#pragma once
// Per-vertex quantities of a cloth state that the renderer shows as colour: strain and speed.
// Pure geometry on positions; nothing here touches GL.

#include <weft/core/Types.h>
#include <weft/mesh/TriangleMesh.h>

#include <Eigen/Core>

namespace weft {

// Signed principal strain per vertex: for each triangle, the principal stretch (singular value
// of the deformation gradient from the rest triangle) farther from 1, minus 1: positive when
// stretched, negative when compressed. Vertices average their triangles weighted by rest area.
Eigen::VectorXd vertexStrain(const TriangleMesh& rest, const NodeMatrix& deformed);

// |next - previous| / dt per vertex.
Eigen::VectorXd vertexSpeed(const NodeMatrix& previous, const NodeMatrix& next, double dt);

}  // namespace weft
