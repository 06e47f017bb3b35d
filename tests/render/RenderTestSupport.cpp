#include "RenderTestSupport.h"

#include <weft/mesh/GridMesh.h>
#include <weft/render/HeadlessContext.h>

#include <cmath>
#include <iostream>
#include <memory>

namespace weft::test {

render::Renderer& osmesaRenderer(int width, int height) {
  // Deliberately never destroyed: Mesa tears its state down in its own exit handlers, and an
  // OSMesa context released after them (static destruction) crashes.
  static render::RenderContext* context = nullptr;
  static render::Renderer* renderer = nullptr;
  if (!renderer) {
    context =
        render::createHeadlessContext(width, height, render::HeadlessBackend::OsMesa, &std::cerr)
            .release();
    render::RendererOptions options;
    options.checkEveryDrawPath = true;
    renderer = new render::Renderer(*context, options);
  }
  context->resize(width, height);
  return *renderer;
}

std::array<std::uint8_t, 3> bytesOf(const render::Rgb& c) {
  std::array<std::uint8_t, 3> b{};
  for (int k = 0; k < 3; ++k) b[k] = static_cast<std::uint8_t>(std::lround(c[k] * 255.0f));
  return b;
}

bool pixelIs(const render::Image& image, int x, int y, const std::array<std::uint8_t, 3>& rgb) {
  const std::uint8_t* p = image.at(x, y);
  return p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
}

DrapedSphere drapedSphere(int quads) {
  DrapedSphere d;
  d.rest = makeGrid(1.5, 1.5, quads, quads);
  d.draped = drapeOverSphere(d.rest.vertices, d.sphere);
  d.scene.cloth.positions = d.draped.cast<float>();
  d.scene.cloth.triangles = d.rest.triangles;
  render::ObstacleShape ball;
  ball.kind = render::ObstacleShape::Kind::Sphere;
  ball.center = d.sphere.center.cast<float>();
  ball.radius = float(d.sphere.radius);
  render::ObstacleShape ground;
  ground.kind = render::ObstacleShape::Kind::Plane;
  ground.point = render::Vec3f(0.0f, -0.9f, 0.0f);
  ground.normal = render::Vec3f::UnitY();
  d.scene.obstacles = {ball, ground};
  return d;
}

render::ContactOverlay syntheticContacts(const DrapedSphere& d, bool withForces) {
  render::ContactOverlay c;
  for (Eigen::Index i = 0; i < d.draped.rows(); ++i) {
    const Vec3 n = (d.draped.row(i).transpose() - d.sphere.center).normalized();
    const double up = n.y();  // cosine of the angle from the top of the sphere
    const auto branch = up > 0.8    ? render::ContactBranch::Stick
                        : up > 0.4  ? render::ContactBranch::Slip
                        : up > 0.05 ? render::ContactBranch::TakeOff
                                    : render::ContactBranch::None;
    c.branches.push_back(branch);
    if (withForces)
      c.forces.push_back(branch == render::ContactBranch::Stick ||
                                 branch == render::ContactBranch::Slip
                             ? render::Vec3f(n.cast<float>() * float(up))
                             : render::Vec3f::Zero());
  }
  return c;
}

render::Camera goldenCamera() {
  render::Camera c;
  c.target = render::Vec3f(0.0f, -0.2f, 0.0f);
  c.distance = 3.0f;
  c.yawDeg = 35.0f;
  c.pitchDeg = 20.0f;
  c.fovYDeg = 35.0f;
  c.nearPlane = 0.5f;
  c.farPlane = 12.0f;
  return c;
}

render::SurfaceMesh flatSquare(int quads, float size) {
  // The scene grid lies in XZ with normal +Y; turning it 90 degrees about X makes its
  // front face +Z.
  const TriangleMesh grid = makeGrid(size, size, quads, quads);
  render::SurfaceMesh m;
  m.positions.resize(grid.vertices.rows(), 3);
  for (Eigen::Index i = 0; i < grid.vertices.rows(); ++i)
    m.positions.row(i) << float(grid.vertices(i, 0)), float(-grid.vertices(i, 2)),
        float(grid.vertices(i, 1));
  m.triangles = grid.triangles;
  return m;
}

}  // namespace weft::test
