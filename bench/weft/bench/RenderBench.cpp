#include <weft/bench/RenderBench.h>

#include <weft/core/Error.h>
#include <weft/frames/ClothFields.h>
#include <weft/frames/FrameBuilder.h>
#include <weft/frames/RenderJob.h>
#include <weft/frames/SyntheticDrape.h>
#include <weft/io/StagedDirectory.h>
#include <weft/render/RenderError.h>
#include <weft/render/Renderer.h>
#include <weft/scene/SceneLoader.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

namespace fs = std::filesystem;

namespace weft::bench {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// DiffCloth's Sphere set-up at the benchmark's resolution: a 48x48-quad square over a sphere,
// above a ground plane.
nlohmann::json sphereSceneDocument() {
  return nlohmann::json::parse(R"({
    "name": "bench-render-sphere",
    "time": { "dt": 0.01, "steps": 200 },
    "cloths": [ { "mesh": { "grid": { "size": [1.6, 1.6], "resolution": [48, 48] } },
                  "material": { "density": 0.2, "stretch": 800.0, "bend": 0.001 } } ],
    "obstacles": [ { "sphere": { "center": [0, 0, 0], "radius": 0.5 }, "friction": 0.5 },
                   { "plane": { "point": [0, -0.9, 0], "normal": [0, 1, 0] }, "friction": 0.3 } ]
  })");
}

struct Row {
  std::string name;
  int frames;
  double seconds;
};

}  // namespace

RenderBenchSummary runRenderBench(const RenderBenchOptions& options, const std::string& outDir) {
  const bool quick = options.quick;
  const int runFrames = options.runFrames;
  const int width = options.width, height = options.height;
  const render::HeadlessBackend backend = options.backend;
  StagedDirectory out(outDir);
  std::vector<Row> rows;
  // 1. Drawing speed: the draped 48x48 cloth and the sphere, per overlay, at width x height.
  const Scene sphereScene = parseScene(sphereSceneDocument(), "<bench render sphere>", ".");
  const ClothModel sphereModel = buildClothModel(sphereScene);
  DrapeSphere sphere;
  const NodeMatrix flat = sphereModel.rest.vertices;
  const NodeMatrix draped = drapeOverSphere(flat, sphere);
  FrameBuilder builder(sphereScene, sphereModel);
  render::RenderScene base = builder.frame(draped, 0);
  const render::Camera camera = render::namedViewCamera(
      render::NamedView::Auto, render::sceneBounds(base), float(width) / float(height));

  std::unique_ptr<render::RenderContext> context =
      render::createHeadlessContext(width, height, backend, &std::cerr);
  std::string glRenderer;
  {
    render::Renderer renderer(*context);
    glRenderer = renderer.glRenderer();
    const Eigen::VectorXd strain = vertexStrain(sphereModel.rest, draped);
    struct Case {
      std::string name;
      render::RenderScene scene;
      render::RenderStyle style;
    };
    std::vector<Case> cases;
    cases.push_back({"sphere48_plain", base, {}});
    Case strainCase{"sphere48_strain", base, {}};
    render::ScalarColoring coloring;
    for (Eigen::Index i = 0; i < strain.size(); ++i) coloring.values.push_back(float(strain[i]));
    coloring.low = -float(strain.cwiseAbs().maxCoeff());
    coloring.high = -coloring.low;
    coloring.map = render::ColorMapKind::Diverging;
    strainCase.scene.scalars = coloring;
    cases.push_back(strainCase);
    Case contactCase{"sphere48_contacts", base, {}};
    render::ContactOverlay contacts;
    for (Eigen::Index i = 0; i < draped.rows(); ++i) {
      const Vec3 d = draped.row(i).transpose() - sphere.center;
      const double height = d.y() / d.norm();  // cos of the angle from the top
      const auto branch = height > 0.7     ? render::ContactBranch::Stick
                          : height > 0.2   ? render::ContactBranch::Slip
                          : height > -0.05 ? render::ContactBranch::TakeOff
                                           : render::ContactBranch::None;
      contacts.branches.push_back(branch);
      contacts.forces.push_back(branch == render::ContactBranch::None
                                    ? render::Vec3f::Zero()
                                    : render::Vec3f(d.normalized().cast<float>()));
    }
    contactCase.scene.contacts = contacts;
    cases.push_back(contactCase);
    Case wireCase{"sphere48_wireframe", base, {}};
    wireCase.style.wireframe = true;
    cases.push_back(wireCase);

    const int frames = quick ? 10 : 100;
    for (const Case& c : cases) {
      renderer.renderImage(c.scene, camera, c.style);  // warm-up: first-use compilation in llvmpipe
      const auto t = Clock::now();
      for (int k = 0; k < frames; ++k) renderer.renderImage(c.scene, camera, c.style);
      rows.push_back({c.name, frames, since(t)});
      std::fprintf(stderr, "%s: %.1f frames/s\n", c.name.c_str(), frames / rows.back().seconds);
    }
  }
  context.reset();

  // 2. A run of runFrames states rendered to PNG, as `weft render RUNDIR` does it. The run is
  // the cloth settling from flat onto the sphere, made analytically: obstacle contact is not
  // simulated yet, and the simulator's speed is not what this measures.
  std::vector<NodeMatrix> states;
  const NodeMatrix lifted = flat.rowwise() + Eigen::RowVector3d(0.0, sphere.radius + 0.3, 0.0);
  for (int s = 0; s <= runFrames; ++s) {
    const double t = double(s) / runFrames, blend = t * t * (3.0 - 2.0 * t);
    states.push_back((1.0 - blend) * lifted + blend * draped);
  }
  RenderJob job;
  job.width = width;
  job.height = height;
  job.backend = backend;
  job.input = "bench render";
  job.quiet = true;
  for (int s = 1; s <= runFrames; ++s) job.frames.push_back(s);
  const std::string framesDir = out.path() + "/frames";
  fs::create_directories(framesDir);
  const RenderReport report =
      renderFrames(sphereScene, sphereModel, states, ContactRecord{}, job, framesDir);
  fs::remove_all(framesDir);  // the timing is the result, not the pictures
  rows.push_back({"run_to_png_total", report.frames, report.totalSeconds});
  rows.push_back({"run_to_png_draw", report.frames, report.renderSeconds});
  rows.push_back({"run_to_png_waiting_for_png", report.frames, report.writeSeconds});

  const unsigned cores = std::thread::hardware_concurrency();
  {
    std::ofstream csv(out.file("render.csv"));
    csv << "case,width,height,frames,seconds,frames_per_second,backend,gl_renderer,cores\n";
    for (const Row& r : rows)
      csv << r.name << "," << width << "," << height << "," << r.frames << "," << r.seconds << ","
          << (r.seconds > 0 ? r.frames / r.seconds : 0.0) << "," << report.backend << ",\""
          << glRenderer << "\"," << cores << "\n";
    std::ofstream md(out.file("render.md"));
    md << "# Headless rendering speed\n\n"
       << width << "x" << height << ", backend " << report.backend << " (" << glRenderer << "), "
       << cores
       << " cores. The sphere48 cases draw one frame repeatedly, reading the image back each "
          "time. The run renders every state of a 48x48 cloth settling on the sphere to PNG as "
          "`weft render` does: total wall time, time drawing, and time waiting for the PNG "
          "encoders, which run on background threads beside the drawing.\n\n"
       << "| case | frames | seconds | frames/s |\n|---|---:|---:|---:|\n";
    for (const Row& r : rows) {
      char line[256];
      std::snprintf(line, sizeof line, "| %s | %d | %.3f | %.1f |\n", r.name.c_str(), r.frames,
                    r.seconds, r.seconds > 0 ? r.frames / r.seconds : 0.0);
      md << line;
    }
    if (!csv || !md) throw InputError(outDir, "--out", "cannot write the benchmark tables");
  }
  out.commit();
  RenderBenchSummary summary;
  summary.backend = report.backend;
  summary.glRenderer = glRenderer;
  summary.plainFramesPerSecond = rows[0].frames / rows[0].seconds;
  summary.runFrames = report.frames;
  summary.runSeconds = report.totalSeconds;
  summary.drawSeconds = report.renderSeconds;
  summary.pngWaitSeconds = report.writeSeconds;
  return summary;
}

}  // namespace weft::bench
