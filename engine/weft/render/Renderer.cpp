#include <weft/render/Renderer.h>

#include <weft/render/ColorMap.h>
#include <weft/render/GlFunctions.h>
#include <weft/render/GpuMesh.h>
#include <weft/render/Legend.h>
#include <weft/render/RenderError.h>
#include <weft/render/ShaderProgram.h>
#include <weft/render/ShapeTessellation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>

namespace weft::render {

// The obstacles' opacity when drawn over the cloth (RenderStyle::obstaclesInFront).
constexpr float kInFrontOpacity = 0.5f;

bool RendererOptions::defaultCheckEveryDrawPath() {
  const char* env = std::getenv("WEFT_GL_DEBUG");
  if (env && *env) return std::string(env) != "0";
#ifdef NDEBUG
  return false;
#else
  return true;
#endif
}

namespace {

// Attribute layouts shared with the shaders' layout(location = ...).
const std::vector<VertexAttribute> kSurfaceLayout = {
    {0, 3}, {1, 3}, {2, 1}};                                           // position, normal, scalar
const std::vector<VertexAttribute> kColoredLayout = {{0, 3}, {1, 3}};  // position, colour
const std::vector<VertexAttribute> kLegendLayout = {
    {0, 2}, {1, 3}, {2, 1}};  // pixel, colour, map value

void push(std::vector<float>& out, const Vec3f& v) {
  out.insert(out.end(), {v.x(), v.y(), v.z()});
}

void appendSurface(std::vector<float>& out, const LitMesh& mesh) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    push(out, mesh.positions[i]);
    push(out, mesh.normals[i]);
    out.push_back(0.0f);
  }
}

void appendLine(std::vector<float>& out, const Vec3f& a, const Vec3f& b, const Rgb& color) {
  push(out, a), push(out, color), push(out, b), push(out, color);
}

// 1, 2 or 5 times a power of ten, near `approx`: grid spacings people can read.
float niceSpacing(float approx) {
  const float decade = std::pow(10.0f, std::floor(std::log10(std::max(approx, 1e-6f))));
  const float m = approx / decade;
  return decade * (m < 1.5f ? 1.0f : m < 3.5f ? 2.0f : m < 7.5f ? 5.0f : 10.0f);
}

// Grid lines on the plane through `point` with normal `normal`, covering a square of
// half-size `halfSize` around the projection of `center`, anchored to multiples of `spacing`
// from `point` so they do not slide when the scene moves.
void appendGrid(std::vector<float>& out, const Vec3f& point, const Vec3f& normal,
                const Vec3f& center, float halfSize, float spacing, const Rgb& color) {
  Vec3f e1, e2;
  perpendicularFrame(normal.normalized(), e1, e2);
  const float c1 = (center - point).dot(e1), c2 = (center - point).dot(e2);
  auto at = [&](float u, float v) { return Vec3f(point + u * e1 + v * e2); };
  const int lines = static_cast<int>(std::ceil(halfSize / spacing));
  const float k1 = std::round(c1 / spacing), k2 = std::round(c2 / spacing);
  for (int k = -lines; k <= lines; ++k) {
    const float u = (k1 + float(k)) * spacing, v = (k2 + float(k)) * spacing;
    if (std::abs(u - c1) <= halfSize)
      appendLine(out, at(u, c2 - halfSize), at(u, c2 + halfSize), color);
    if (std::abs(v - c2) <= halfSize)
      appendLine(out, at(c1 - halfSize, v), at(c1 + halfSize, v), color);
  }
}

void appendRect(std::vector<float>& out, float x0, float y0, float x1, float y1, const Rgb& color,
                float valueTop = -1.0f, float valueBottom = -1.0f) {
  const std::array<std::array<float, 3>, 6> corners = {{{x0, y0, valueTop},
                                                        {x0, y1, valueBottom},
                                                        {x1, y1, valueBottom},
                                                        {x0, y0, valueTop},
                                                        {x1, y1, valueBottom},
                                                        {x1, y0, valueTop}}};
  for (const auto& c : corners)
    out.insert(out.end(), {c[0], c[1], color.x(), color.y(), color.z(), c[2]});
}

void requireIndices(const TriangleList& triangles, Eigen::Index vertices, const char* what) {
  if (triangles.size() > 0 && (triangles.minCoeff() < 0 || triangles.maxCoeff() >= vertices))
    throw std::invalid_argument(std::string("RenderScene: ") + what +
                                " has triangle indices outside its " + std::to_string(vertices) +
                                " vertices");
}

void validate(const RenderScene& scene) {
  const Eigen::Index n = scene.cloth.positions.rows();
  requireIndices(scene.cloth.triangles, n, "cloth");
  auto perVertex = [&](std::size_t size, const char* what) {
    if (size != static_cast<std::size_t>(n))
      throw std::invalid_argument(std::string("RenderScene: ") + what + " has " +
                                  std::to_string(size) + " entries for " + std::to_string(n) +
                                  " cloth vertices");
  };
  if (scene.scalars) perVertex(scene.scalars->values.size(), "scalars");
  if (scene.contacts) {
    perVertex(scene.contacts->branches.size(), "contact branches");
    if (!scene.contacts->forces.empty()) perVertex(scene.contacts->forces.size(), "contact forces");
  }
  for (const ObstacleShape& o : scene.obstacles)
    if (o.kind == ObstacleShape::Kind::Mesh)
      requireIndices(o.mesh.triangles, o.mesh.positions.rows(), "mesh obstacle");
  for (const GhostMesh& g : scene.ghosts)
    requireIndices(g.mesh.triangles, g.mesh.positions.rows(), "ghost mesh");
}

}  // namespace

struct Renderer::Resources {
  GlFunctions gl;
  std::unique_ptr<ShaderProgram> surface, line, point, legend;
  std::unique_ptr<GpuMesh> surfaceMesh, lineMesh, pointMesh, legendMesh;
  GLuint colorMaps[2] = {0, 0};  // Sequential, Diverging
  // Scratch buffers kept between frames: fresh multi-megabyte buffers every frame cost more in
  // page faults than filling them.
  std::vector<std::uint8_t> readback;
  std::vector<float> vertices;
  std::vector<unsigned> indices;
  LitMesh shapes;
};

namespace {

LitMesh& cleared(LitMesh& m) {
  m.positions.clear(), m.normals.clear(), m.indices.clear();
  return m;
}

}  // namespace

struct Renderer::Frame {
  Eigen::Matrix4f view, projection;
  int width = 0, height = 0;
  bool orthographic = false;
  Bounds bounds;
  Vec3f center;
  float radius = 1.0f;
  float pixelScale = 1.0f;  // sizes are designed for 720 rows and scale with the image
};

Renderer::Renderer(RenderContext& context, RendererOptions options)
    : context_(context), options_(options), r_(std::make_unique<Resources>()) {
  context_.makeCurrent();
  r_->gl.load([this](const char* name) { return context_.getProcAddress(name); });
  const GlFunctions& gl = r_->gl;
  version_ = gl.string(GL_VERSION);
  renderer_ = gl.string(GL_RENDERER);
  r_->surface =
      std::make_unique<ShaderProgram>(gl, std::vector<std::string>{"surface.vert", "surface.frag"});
  r_->line = std::make_unique<ShaderProgram>(
      gl, std::vector<std::string>{"line.vert", "line.geom", "line.frag"});
  r_->point =
      std::make_unique<ShaderProgram>(gl, std::vector<std::string>{"point.vert", "point.frag"});
  r_->legend =
      std::make_unique<ShaderProgram>(gl, std::vector<std::string>{"legend.vert", "legend.frag"});
  r_->surfaceMesh = std::make_unique<GpuMesh>(gl, kSurfaceLayout);
  r_->lineMesh = std::make_unique<GpuMesh>(gl, kColoredLayout);
  r_->pointMesh = std::make_unique<GpuMesh>(gl, kColoredLayout);
  r_->legendMesh = std::make_unique<GpuMesh>(gl, kLegendLayout);
  gl.GenTextures(2, r_->colorMaps);
  for (int k = 0; k < 2; ++k) {
    const std::vector<std::uint8_t> table =
        colorMapTable(k == 0 ? ColorMapKind::Sequential : ColorMapKind::Diverging);
    gl.BindTexture(GL_TEXTURE_2D, r_->colorMaps[k]);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, GLsizei(table.size() / 3), 1, 0, GL_RGB,
                  GL_UNSIGNED_BYTE, table.data());
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  gl.BindTexture(GL_TEXTURE_2D, 0);
  gl.check("creating the renderer's GL resources");
}

Renderer::~Renderer() {
  // GL objects belong to the context: make it current so they are freed from the right one.
  try {
    context_.makeCurrent();
  } catch (...) {
    return;
  }
  r_->gl.DeleteTextures(2, r_->colorMaps);
}

void Renderer::checkpoint(const char* where) const {
  if (options_.checkEveryDrawPath) r_->gl.check(where);
}

void Renderer::render(const RenderScene& scene, const Camera& camera, const RenderStyle& style) {
  validate(scene);
  context_.makeCurrent();
  const GlFunctions& gl = r_->gl;
  Frame f;
  f.width = context_.width();
  f.height = context_.height();
  f.view = camera.view();
  f.projection = camera.projection(float(f.width) / float(f.height));
  f.orthographic = camera.orthographic;
  f.bounds = sceneBounds(scene);
  f.center = f.bounds.empty() ? camera.target : f.bounds.center();
  f.radius = f.bounds.radius();
  f.pixelScale = float(f.height) / 720.0f;

  gl.BindFramebuffer(GL_FRAMEBUFFER, context_.framebuffer());
  gl.Viewport(0, 0, f.width, f.height);
  gl.ClearColor(style.background.x(), style.background.y(), style.background.z(), 1.0f);
  gl.DepthMask(GL_TRUE);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LEQUAL);
  gl.Disable(GL_BLEND);
  gl.Disable(GL_CULL_FACE);  // cloth is seen from both sides
  gl.Enable(GL_PROGRAM_POINT_SIZE);
  // Surfaces are pushed back a little so lines and markers drawn on them are not buried.
  gl.PolygonOffset(1.0f, 1.0f);
  gl.ActiveTexture(GL_TEXTURE0);
  checkpoint("frame set-up");

  drawGround(scene, style, f);
  drawObstacles(scene, style, f, false);
  drawCloth(scene, style, f);
  if (style.obstaclesInFront) drawObstacles(scene, style, f, true);
  drawArrows(scene, style, f);
  drawWireframe(scene, style, f);
  drawCurves(scene, style, f);
  drawPoints(scene, style, f);
  drawGhosts(scene, style, f);
  drawLegend(scene, style, f);

  gl.UseProgram(0);
  gl.Disable(GL_POLYGON_OFFSET_FILL);
  gl.Disable(GL_BLEND);
  gl.DepthMask(GL_TRUE);
  gl.check("drawing the frame");
}

void Renderer::useSurfaceProgram(const Frame& f, const Rgb& front, const Rgb& back, float opacity) {
  ShaderProgram& p = *r_->surface;
  p.use();
  p.set("viewMatrix", f.view);
  p.set("projectionMatrix", f.projection);
  p.set("frontColor", front);
  p.set("backColor", back);
  p.set("useColorMap", false);
  p.set("colorMap", 0);
  p.set("opacity", opacity);
  p.set("orthographic", f.orthographic);
}

void Renderer::drawLines(const std::vector<float>& vertices, float widthPixels, const Frame& f) {
  if (vertices.empty()) return;
  ShaderProgram& p = *r_->line;
  p.use();
  p.set("viewMatrix", f.view);
  p.set("projectionMatrix", f.projection);
  p.set("viewportSize", float(f.width), float(f.height));
  p.set("lineWidth", widthPixels);
  r_->lineMesh->upload(vertices);
  r_->lineMesh->draw(GL_LINES);
}

void Renderer::drawGround(const RenderScene& scene, const RenderStyle& style, const Frame& f) {
  const float halfSize = planeHalfSize(f.bounds);
  const float spacing = niceSpacing(0.25f * f.radius);
  LitMesh& fills = cleared(r_->shapes);
  std::vector<float>& lines = r_->vertices;
  lines.clear();
  bool anyPlane = false;
  for (const ObstacleShape& o : scene.obstacles) {
    if (o.kind != ObstacleShape::Kind::Plane) continue;
    anyPlane = true;
    fills.append(tessellatePlane(o.point, o.normal, f.center, halfSize));
    if (style.groundGrid)
      appendGrid(lines, o.point, o.normal, f.center, halfSize, spacing, style.grid);
  }
  if (!anyPlane && style.groundGrid && !f.bounds.empty())
    appendGrid(lines, Vec3f(0.0f, f.bounds.min.y(), 0.0f), Vec3f::UnitY(), f.center, halfSize,
               spacing, style.grid);
  if (!fills.positions.empty()) {
    std::vector<float> vertices;  // small: the lines keep the scratch buffer
    appendSurface(vertices, fills);
    useSurfaceProgram(f, style.ground, style.ground, 1.0f);
    r_->gl.Enable(GL_POLYGON_OFFSET_FILL);
    r_->surfaceMesh->upload(vertices, fills.indices);
    r_->surfaceMesh->draw(GL_TRIANGLES);
    r_->gl.Disable(GL_POLYGON_OFFSET_FILL);
  }
  drawLines(lines, std::max(1.0f, f.pixelScale), f);
  checkpoint("drawing the ground");
}

void Renderer::drawObstacles(const RenderScene& scene, const RenderStyle& style, const Frame& f,
                             bool inFront) {
  LitMesh& all = cleared(r_->shapes);
  for (const ObstacleShape& o : scene.obstacles)
    if (o.kind != ObstacleShape::Kind::Plane) all.append(tessellateObstacle(o, f.center, 0.0f));
  if (all.positions.empty()) return;
  std::vector<float>& vertices = r_->vertices;
  vertices.clear();
  appendSurface(vertices, all);
  const GlFunctions& gl = r_->gl;
  if (inFront) {
    // Over the cloth, translucent: the depth test off, so what a garment covers shows.
    gl.Disable(GL_DEPTH_TEST);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  }
  useSurfaceProgram(f, style.obstacle, style.obstacle, inFront ? kInFrontOpacity : 1.0f);
  gl.Enable(GL_POLYGON_OFFSET_FILL);
  r_->surfaceMesh->upload(vertices, all.indices);
  r_->surfaceMesh->draw(GL_TRIANGLES);
  gl.Disable(GL_POLYGON_OFFSET_FILL);
  if (inFront) {
    gl.Disable(GL_BLEND);
    gl.Enable(GL_DEPTH_TEST);
  }
  checkpoint("drawing obstacles");
}

void Renderer::drawCloth(const RenderScene& scene, const RenderStyle& style, const Frame& f) {
  const SurfaceMesh& cloth = scene.cloth;
  if (cloth.positions.rows() == 0 || cloth.triangles.rows() == 0) return;
  const std::vector<Vec3f> normals = vertexNormals(cloth.positions, cloth.triangles);
  std::vector<float>& vertices = r_->vertices;
  vertices.clear();
  for (Eigen::Index i = 0; i < cloth.positions.rows(); ++i) {
    push(vertices, cloth.positions.row(i).transpose());
    push(vertices, normals[i]);
    vertices.push_back(scene.scalars ? scene.scalars->values[i] : 0.0f);
  }
  std::vector<unsigned>& indices = r_->indices;
  indices.assign(cloth.triangles.data(), cloth.triangles.data() + cloth.triangles.size());
  const bool overlay = scene.contacts.has_value();
  useSurfaceProgram(f, overlay ? style.overlayFront : style.clothFront,
                    overlay ? style.overlayBack : style.clothBack, 1.0f);
  if (scene.scalars) {
    ShaderProgram& p = *r_->surface;
    p.set("useColorMap", true);
    p.set("scalarLow", scene.scalars->low);
    p.set("scalarHigh", scene.scalars->high);
    r_->gl.BindTexture(GL_TEXTURE_2D,
                       r_->colorMaps[scene.scalars->map == ColorMapKind::Sequential ? 0 : 1]);
  }
  // Translucent cloth writes no depth: what lies behind it (obstacles, markers, contacts) shows.
  const float opacity = std::clamp(style.clothOpacity, 0.0f, 1.0f);
  const bool translucent = opacity < 1.0f;
  if (translucent) {
    r_->surface->set("opacity", opacity);
    r_->gl.Enable(GL_BLEND);
    r_->gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    r_->gl.DepthMask(GL_FALSE);
  }
  r_->gl.Enable(GL_POLYGON_OFFSET_FILL);
  r_->surfaceMesh->upload(vertices, indices);
  r_->surfaceMesh->draw(GL_TRIANGLES);
  r_->gl.Disable(GL_POLYGON_OFFSET_FILL);
  r_->gl.BindTexture(GL_TEXTURE_2D, 0);
  if (translucent) {
    r_->gl.DepthMask(GL_TRUE);
    r_->gl.Disable(GL_BLEND);
  }
  checkpoint("drawing the cloth");
}

void Renderer::drawArrows(const RenderScene& scene, const RenderStyle& style, const Frame& f) {
  if (!scene.contacts || scene.contacts->forces.empty()) return;
  const ContactOverlay& c = *scene.contacts;
  float longest = 0.0f;
  for (const Vec3f& force : c.forces)
    if (force.allFinite()) longest = std::max(longest, force.norm());
  if (!(longest > 0.0f)) return;
  const float scale = c.metersPerNewton > 0.0f ? c.metersPerNewton : 0.1f * f.radius / longest;
  LitMesh& arrows = cleared(r_->shapes);
  for (std::size_t i = 0; i < c.forces.size(); ++i)
    if (c.forces[i].allFinite())
      appendArrow(arrows, scene.cloth.positions.row(Eigen::Index(i)).transpose(),
                  scale * c.forces[i], 0.002f * f.radius);
  if (arrows.positions.empty()) return;
  std::vector<float>& vertices = r_->vertices;
  vertices.clear();
  appendSurface(vertices, arrows);
  useSurfaceProgram(f, style.arrow, style.arrow, 1.0f);
  r_->surfaceMesh->upload(vertices, arrows.indices);
  r_->surfaceMesh->draw(GL_TRIANGLES);
  checkpoint("drawing force arrows");
}

void Renderer::drawWireframe(const RenderScene& scene, const RenderStyle& style, const Frame& f) {
  if (!style.wireframe || scene.cloth.triangles.rows() == 0) return;
  const TriangleList& t = scene.cloth.triangles;
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(t.rows()) * 3);
  for (Eigen::Index i = 0; i < t.rows(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int a = t(i, k), b = t(i, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<float>& lines = r_->vertices;
  lines.clear();
  for (auto [a, b] : edges)
    appendLine(lines, scene.cloth.positions.row(a).transpose(),
               scene.cloth.positions.row(b).transpose(), style.wire);
  drawLines(lines, std::max(1.0f, f.pixelScale), f);
  checkpoint("drawing the wireframe");
}

void Renderer::drawCurves(const RenderScene& scene, const RenderStyle& style, const Frame& f) {
  std::vector<float> lines;
  for (const Curve& c : scene.curves)
    for (std::size_t i = 1; i < c.points.size(); ++i)
      appendLine(lines, c.points[i - 1], c.points[i], c.color);
  drawLines(lines, style.lineWidth > 0.0f ? style.lineWidth : std::max(2.0f, 3.0f * f.pixelScale),
            f);
  checkpoint("drawing curves");
}

void Renderer::drawPoints(const RenderScene& scene, const RenderStyle& style, const Frame& f) {
  const float markerSize =
      style.pointSize > 0.0f ? style.pointSize : std::max(4.0f, 12.0f * f.pixelScale);
  ShaderProgram& p = *r_->point;
  p.use();
  p.set("viewMatrix", f.view);
  p.set("projectionMatrix", f.projection);
  p.set("orthographic", f.orthographic);
  p.set("depthBias", 0.01f * f.radius);
  auto draw = [&](const std::vector<float>& vertices, float size, bool shaded) {
    if (vertices.empty()) return;
    p.set("pointSize", size);
    p.set("shaded", shaded);
    r_->pointMesh->upload(vertices);
    r_->pointMesh->draw(GL_POINTS);
  };
  std::vector<float> markers;
  auto addMarkers = [&](const std::vector<Vec3f>& points, const Rgb& color) {
    for (const Vec3f& q : points) push(markers, q), push(markers, color);
  };
  if (scene.fixedPointGroups.size() == scene.fixedPoints.size()) {
    for (std::size_t i = 0; i < scene.fixedPoints.size(); ++i)
      push(markers, scene.fixedPoints[i]),
          push(markers, pinGroupColor(scene.fixedPointGroups[i], style));
  } else {
    addMarkers(scene.fixedPoints, style.fixedPoint);
  }
  addMarkers(scene.handlePoints, style.handlePoint);
  addMarkers(scene.targetPoints, style.targetPoint);
  draw(markers, markerSize, true);
  if (scene.contacts) {
    std::vector<float> nodes;
    for (std::size_t i = 0; i < scene.contacts->branches.size(); ++i) {
      const ContactBranch b = scene.contacts->branches[i];
      if (b == ContactBranch::None) continue;
      push(nodes, scene.cloth.positions.row(Eigen::Index(i)).transpose());
      push(nodes, branchColor(b));
    }
    draw(nodes, std::max(3.0f, 0.6f * markerSize), false);
  }
  checkpoint("drawing points");
}

void Renderer::drawGhosts(const RenderScene& scene, const RenderStyle&, const Frame& f) {
  if (scene.ghosts.empty()) return;
  const GlFunctions& gl = r_->gl;
  // See-through after everything opaque; depth writes off so ghosts never hide each other.
  gl.Enable(GL_BLEND);
  gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl.DepthMask(GL_FALSE);
  for (const GhostMesh& g : scene.ghosts) {
    if (g.mesh.triangles.rows() == 0) continue;
    const LitMesh mesh = tessellateMesh(g.mesh, true);
    std::vector<float> vertices;
    appendSurface(vertices, mesh);
    useSurfaceProgram(f, g.color, g.color, std::clamp(g.opacity, 0.0f, 1.0f));
    r_->surfaceMesh->upload(vertices, mesh.indices);
    r_->surfaceMesh->draw(GL_TRIANGLES);
  }
  gl.DepthMask(GL_TRUE);
  gl.Disable(GL_BLEND);
  checkpoint("drawing ghosts");
}

void Renderer::drawLegend(const RenderScene& scene, const RenderStyle& style, const Frame& f) {
  if (!style.legend || (!scene.scalars && !scene.contacts)) return;
  // Sizes follow the image, with floors so the legend stays readable in small images.
  const float s = f.pixelScale, margin = std::max(8.0f, std::round(24.0f * s)),
              border = std::max(1.0f, std::round(2.0f * s));
  const float right = float(f.width) - margin;
  const Rgb dark(0.15f, 0.15f, 0.17f);
  std::vector<float> quads;
  if (scene.scalars) {
    // A vertical colour bar: high values at the top, with ticks at the ends and the middle.
    const float w = std::max(8.0f, std::round(18.0f * s)), top = std::round(0.25f * f.height),
                bottom = std::round(0.70f * f.height);
    const float left = right - w, tick = std::max(4.0f, std::round(8.0f * s));
    appendRect(quads, left - border, top - border, right + border, bottom + border, dark);
    appendRect(quads, left, top, right, bottom, dark, 1.0f, 0.0f);
    for (float y : {top, 0.5f * (top + bottom), bottom})
      appendRect(quads, left - border - tick, std::round(y) - 0.5f * border, left - border,
                 std::round(y) + 0.5f * border, dark);
  }
  if (scene.contacts) {
    // Swatches for take-off, stick and slip, bottom to top in the lower right corner (Legend.h:
    // the editor labels them by the same layout).
    for (const LegendSwatch& w : contactLegendSwatches(f.width, f.height)) {
      appendRect(quads, w.left - w.border, w.top - w.border, w.right + w.border,
                 w.bottom + w.border, dark);
      appendRect(quads, w.left, w.top, w.right, w.bottom, branchColor(w.branch));
    }
  }
  const GlFunctions& gl = r_->gl;
  gl.Disable(GL_DEPTH_TEST);
  ShaderProgram& p = *r_->legend;
  p.use();
  p.set("viewportSize", float(f.width), float(f.height));
  p.set("colorMap", 0);
  if (scene.scalars)
    gl.BindTexture(GL_TEXTURE_2D,
                   r_->colorMaps[scene.scalars->map == ColorMapKind::Sequential ? 0 : 1]);
  r_->legendMesh->upload(quads);
  r_->legendMesh->draw(GL_TRIANGLES);
  gl.BindTexture(GL_TEXTURE_2D, 0);
  gl.Enable(GL_DEPTH_TEST);
  checkpoint("drawing the legend");
}

Image Renderer::readPixels() const {
  context_.makeCurrent();
  const GlFunctions& gl = r_->gl;
  const int w = context_.width(), h = context_.height();
  // RGBA is the framebuffer's own layout: Mesa copies it directly, whereas RGB goes through a
  // per-pixel conversion several times slower. Alpha is dropped while flipping the rows.
  std::vector<std::uint8_t>& rgba = r_->readback;
  rgba.resize(static_cast<std::size_t>(w) * h * 4);
  gl.BindFramebuffer(GL_FRAMEBUFFER, context_.framebuffer());
  gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  gl.check("reading the framebuffer");
  Image image(w, h);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* src = &rgba[static_cast<std::size_t>(h - 1 - y) * w * 4];
    std::uint8_t* dst = image.at(0, y);
    for (int x = 0; x < w; ++x, src += 4, dst += 3)
      dst[0] = src[0], dst[1] = src[1], dst[2] = src[2];
  }
  return image;
}

}  // namespace weft::render
