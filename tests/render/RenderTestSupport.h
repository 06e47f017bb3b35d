#pragma once
// Shared pieces of the render tests: one OSMesa renderer for the whole test binary (shader
// compilation is the slow part), synthetic scenes, and exact colour helpers.

#include <weft/core/Types.h>
#include <weft/mesh/TriangleMesh.h>
#include <weft/render/Camera.h>
#include <weft/render/Renderer.h>

#include <weft/frames/SyntheticDrape.h>

#include <array>
#include <cstdint>

namespace weft::test {

// The shared renderer on an OSMesa context of width x height (golden images are OSMesa's),
// with GL errors checked after every draw path.
render::Renderer& osmesaRenderer(int width, int height);

// The 8-bit value GL writes for an exact colour.
std::array<std::uint8_t, 3> bytesOf(const render::Rgb& color);
bool pixelIs(const render::Image& image, int x, int y, const std::array<std::uint8_t, 3>& rgb);

// A 1.5 m square cloth of `quads` x `quads` quads draped over a sphere of radius 0.5 at the
// origin, above a ground plane at y = -0.9.
struct DrapedSphere {
  TriangleMesh rest;  // the flat cloth (a scene `grid`), for strain
  NodeMatrix draped;  // its draped positions
  DrapeSphere sphere;
  render::RenderScene scene;  // cloth, sphere and plane
};
DrapedSphere drapedSphere(int quads);

// Contact branches by height on the sphere: stick on the cap, slip around it, take-off near
// the equator, none where the cloth hangs; forces along the sphere's normal.
render::ContactOverlay syntheticContacts(const DrapedSphere& d, bool withForces);

// The fixed camera of the golden images (not auto-framed, so framing changes cannot move them).
render::Camera goldenCamera();

// A flat square cloth of side `size` in the plane z = 0, front side facing +Z.
render::SurfaceMesh flatSquare(int quads, float size);

}  // namespace weft::test
