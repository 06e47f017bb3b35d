#pragma once
// A cloth draped over a sphere, built analytically: the renderer's tests and benchmark need a
// draped cloth before obstacle contact exists in the simulator. Each rest point of a flat
// horizontal cloth centred above the sphere keeps its distance from the cloth's centre as an
// arc length: it wraps the sphere down to the equator, then hangs straight down, with folds.

#include <weft/core/Types.h>
#include <weft/mesh/TriangleMesh.h>

namespace weft {

struct DrapeSphere {
  Vec3 center = Vec3::Zero();
  double radius = 0.5;
  double gap = 0.01;  // cloth rests this far outside the sphere
};

// Positions of `flat` (rest vertices in a horizontal plane, centred over the sphere) draped
// over `sphere`. `folds` azimuthal waves appear in the hanging part, `amplitude` relative to
// the hanging length.
NodeMatrix drapeOverSphere(const NodeMatrix& flat, const DrapeSphere& sphere, int folds = 8,
                           double amplitude = 0.25);

// A square grid cloth (scene contract `grid`, side `size`, `quads` per side) draped over a sphere.
TriangleMesh drapedGrid(double size, int quads, const DrapeSphere& sphere);

}  // namespace weft
