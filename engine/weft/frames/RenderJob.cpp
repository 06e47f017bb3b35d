#include <weft/frames/RenderJob.h>

#include <weft/frames/AsyncPngWriter.h>
#include <weft/frames/ClothFields.h>
#include <weft/frames/FrameBuilder.h>

#include <weft/render/Image.h>
#include <weft/render/RenderError.h>
#include <weft/render/Renderer.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <thread>

namespace weft {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

const char* viewName(render::NamedView v) {
  switch (v) {
    case render::NamedView::Front:
      return "front";
    case render::NamedView::Side:
      return "side";
    case render::NamedView::Top:
      return "top";
    case render::NamedView::Auto:
      return "auto";
  }
  return "?";
}

nlohmann::json toJson(const render::Vec3f& v) {
  return {v.x(), v.y(), v.z()};
}

// Per-vertex values of a scalar overlay for every rendered frame.
std::vector<std::vector<float>> scalarFields(Overlay overlay, const Scene& scene,
                                             const ClothModel& model,
                                             const std::vector<NodeMatrix>& states,
                                             const std::vector<int>& frames) {
  std::vector<std::vector<float>> fields;
  for (int s : frames) {
    Eigen::VectorXd v;
    if (overlay == Overlay::Strain) {
      v = vertexStrain(model.rest, states[std::size_t(s)]);
    } else {
      // Backward difference; the first state uses the first step.
      const int a = s > 0 ? s - 1 : 0, b = s > 0 ? s : std::min<int>(1, int(states.size()) - 1);
      v = a == b ? Eigen::VectorXd::Zero(model.nodeCount())
                 : vertexSpeed(states[std::size_t(a)], states[std::size_t(b)], scene.time.dt);
    }
    std::vector<float> f(std::size_t(v.size()));
    for (Eigen::Index i = 0; i < v.size(); ++i)
      f[std::size_t(i)] = std::isfinite(v[i]) ? float(v[i]) : 0.0f;
    fields.push_back(std::move(f));
  }
  return fields;
}

}  // namespace

bool parseOverlay(const std::string& text, Overlay& overlay) {
  if (text == "none")
    overlay = Overlay::None;
  else if (text == "contacts")
    overlay = Overlay::Contacts;
  else if (text == "strain")
    overlay = Overlay::Strain;
  else if (text == "speed")
    overlay = Overlay::Speed;
  else
    return false;
  return true;
}

const char* overlayName(Overlay overlay) {
  switch (overlay) {
    case Overlay::None:
      return "none";
    case Overlay::Contacts:
      return "contacts";
    case Overlay::Strain:
      return "strain";
    case Overlay::Speed:
      return "speed";
  }
  return "?";
}

std::string frameFileName(int state) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d.png", state);
  return name;
}

RenderReport renderFrames(const Scene& scene, const ClothModel& model,
                          const std::vector<NodeMatrix>& states, const ContactRecord& contacts,
                          const RenderJob& job, const std::string& folder) {
  const auto start = Clock::now();
  RenderReport report;
  FrameBuilder builder(scene, model, &report.warnings);

  // Scalar overlays share one colour range over the whole sequence, so colours compare
  // across frames: symmetric about zero for strain, from zero for speed.
  std::vector<std::vector<float>> fields;
  if (job.overlay == Overlay::Strain || job.overlay == Overlay::Speed) {
    fields = scalarFields(job.overlay, scene, model, states, job.frames);
    float extreme = 0.0f;
    for (const auto& f : fields)
      for (float v : f) extreme = std::max(extreme, std::abs(v));
    extreme = std::max(extreme, job.overlay == Overlay::Strain ? 1e-4f : 1e-6f);
    report.low = job.overlay == Overlay::Strain ? -extreme : 0.0f;
    report.high = extreme;
  }
  if (job.overlay == Overlay::Contacts && contacts.empty())
    report.warnings.push_back(
        "this run has no per-node contact data (contact_branches.npy); no contact nodes are shown");

  auto frameAt = [&](std::size_t k) {
    const int s = job.frames[k];
    render::RenderScene frame = builder.frame(states[std::size_t(s)], s);
    if (!fields.empty())
      frame.scalars =
          render::ScalarColoring{fields[k], report.low, report.high,
                                 job.overlay == Overlay::Strain ? render::ColorMapKind::Diverging
                                                                : render::ColorMapKind::Sequential};
    if (job.overlay == Overlay::Contacts) {
      render::ContactOverlay overlay;
      overlay.branches.assign(std::size_t(model.nodeCount()), render::ContactBranch::None);
      if (!contacts.empty()) {
        for (std::size_t i = 0; i < overlay.branches.size(); ++i)
          overlay.branches[i] =
              static_cast<render::ContactBranch>(contacts.branches[std::size_t(s)][i]);
        if (!contacts.forces.empty()) {
          const NodeMatrix& f = contacts.forces[std::size_t(s)];
          for (Eigen::Index i = 0; i < f.rows(); ++i)
            overlay.forces.push_back(f.row(i).transpose().cast<float>());
        }
      }
      frame.contacts = std::move(overlay);
    }
    return frame;
  };

  render::Bounds bounds;
  for (std::size_t k = 0; k < job.frames.size(); ++k)
    bounds.extend(render::sceneBounds(frameAt(k)));
  const float aspect = float(job.width) / float(job.height);
  const render::Camera camera = render::namedViewCamera(job.view, bounds, aspect);
  render::RenderStyle style;
  style.wireframe = job.wireframe;

  auto context = render::createHeadlessContext(job.width, job.height, job.backend, &std::cerr);
  render::Renderer renderer(*context);
  report.backend = context->backendName();
  report.glVersion = renderer.glVersion();
  report.glRenderer = renderer.glRenderer();

  const int every = std::max<int>(1, int(job.frames.size()) / 10);
  AsyncPngWriter writer(int(std::max(1u, std::thread::hardware_concurrency())));
  for (std::size_t k = 0; k < job.frames.size(); ++k) {
    auto t = Clock::now();
    render::Image image = renderer.renderImage(frameAt(k), camera, style);
    report.renderSeconds += since(t);
    t = Clock::now();
    writer.write(folder + "/" + frameFileName(job.frames[k]), std::move(image));
    report.writeSeconds += since(t);
    ++report.frames;
    if (!job.quiet && (k % std::size_t(every) == 0 || k + 1 == job.frames.size()))
      std::fprintf(stderr, "\rframe %zu/%zu", k + 1, job.frames.size());
  }
  auto t = Clock::now();
  writer.finish();
  report.writeSeconds += since(t);
  if (!job.quiet && !job.frames.empty()) std::fprintf(stderr, "\n");
  report.totalSeconds = since(start);

  nlohmann::json j;
  j["input"] = job.input;
  j["scene"] = scene.name;
  j["frames"] = job.frames;
  j["files"] = nlohmann::json::array();
  for (int s : job.frames) j["files"].push_back(frameFileName(s));
  j["times"] = nlohmann::json::array();
  for (int s : job.frames) j["times"].push_back(s * scene.time.dt);
  j["size"] = {job.width, job.height};
  j["camera"] = {{"view", viewName(job.view)},
                 {"eye", toJson(camera.eye())},
                 {"target", toJson(camera.target)},
                 {"up", toJson(camera.up())},
                 {"fov_y_deg", camera.fovYDeg}};
  j["overlay"] = overlayName(job.overlay);
  if (!fields.empty()) j["color_range"] = {report.low, report.high};
  j["wireframe"] = job.wireframe;
  j["backend"] = report.backend;
  j["gl_version"] = report.glVersion;
  j["gl_renderer"] = report.glRenderer;
  j["seconds"] = {{"render", report.renderSeconds},
                  {"write", report.writeSeconds},
                  {"total", report.totalSeconds}};
  j["warnings"] = report.warnings;
  std::ofstream out(folder + "/render.json");
  out << j.dump(2) << "\n";
  if (!out) throw render::ImageFileError(folder + "/render.json: write failed");
  return report;
}

}  // namespace weft
