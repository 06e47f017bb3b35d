// `weft render` end to end through the real binary: scenes and run folders, overlays, the
// staged output folder, and the error contract (exit 2, `error: <file>: <option>: <what>`).

#include <support/Process.h>
#include <support/SceneBuilder.h>
#include <support/TempDir.h>

#include <weft/io/Npy.h>
#include <weft/render/ColorMap.h>
#include <weft/render/Image.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace weft::test {
namespace {

ProcessResult weft(const std::vector<std::string>& args, const std::string& workDir = "") {
  std::vector<std::string> argv = {WEFT_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  return runProcess(argv, workDir);
}

// A run folder as `weft simulate` writes it (the files `weft render` reads: scene.json,
// summary.json, positions.npy), with made-up motion: these tests are about rendering, and
// should not fail when the simulator does.
std::string writeRunFolder(const TempDir& dir, int steps) {
  const nlohmann::json doc = hangingClothScene(0.5, 6, 0.01, steps, 500.0);
  const Scene scene = parse(doc);
  const std::string run = dir.file("run");
  fs::create_directories(run);
  std::ofstream(run + "/scene.json") << doc.dump(2);
  std::ofstream(run + "/summary.json")
      << nlohmann::json{{"steps", steps}, {"scene_directory", dir.path()}}.dump(2);
  const TriangleMesh& rest = scene.cloths[0].mesh;
  std::vector<double> positions;
  for (int s = 0; s <= steps; ++s)
    for (Eigen::Index i = 0; i < rest.vertices.rows(); ++i)
      for (int c = 0; c < 3; ++c)
        positions.push_back(rest.vertices(i, c) + (c == 2 ? 0.02 * s * rest.vertices(i, 0) : 0.0));
  writeNpy(run + "/positions.npy", {std::size_t(steps + 1), std::size_t(rest.vertices.rows()), 3},
           positions.data());
  return run;
}

std::string hangingScene(const TempDir& dir, int steps) {
  return writeScene(dir.file("hanging.json"), hangingClothScene(0.5, 6, 0.01, steps, 500.0));
}

TEST(RenderCli, RendersTheRestStateOfASceneWithoutSimulating) {
  TempDir dir;
  nlohmann::json doc = hangingClothScene(0.5, 6, 0.01, 5, 500.0);
  // Obstacles cannot be simulated yet, but the rest state needs no simulation.
  doc["obstacles"] = {
      {{"sphere", {{"center", {0, 0.3, 0.3}}, {"radius", 0.2}}}, {"friction", 0.3}}};
  const std::string scene = writeScene(dir.file("sphere.json"), doc);
  const ProcessResult r =
      weft({"render", scene, "--frames", "0:0:1", "--size", "96x64", "--out", dir.file("frames")});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const render::Image image = render::readPng(dir.file("frames/frame_000000.png"));
  EXPECT_EQ(image.width, 96);
  EXPECT_EQ(image.height, 64);
  EXPECT_NE(r.err.find("GL_RENDERER"), std::string::npos) << "every headless run logs what drew it";
  EXPECT_NE(r.out.find("render: "), std::string::npos) << "one-line summary";
  std::ifstream meta(dir.file("frames/render.json"));
  const nlohmann::json j = nlohmann::json::parse(meta);
  EXPECT_EQ(j["frames"], nlohmann::json::array({0}));
  EXPECT_FALSE(j["gl_renderer"].get<std::string>().empty());
}

TEST(RenderCli, RendersARunFolderWithEachOverlay) {
  TempDir dir;
  const std::string run = writeRunFolder(dir, 4);
  for (const std::string overlay : {"none", "strain", "speed", "contacts"}) {
    const std::string out = dir.file("frames-" + overlay);
    const ProcessResult r =
        weft({"render", run, "--frames", "0:4:2", "--size", "64x48", "--overlay", overlay,
              "--camera", "front", "--out", out, "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << overlay << ": " << r.err;
    for (const char* f :
         {"frame_000000.png", "frame_000002.png", "frame_000004.png", "render.json"})
      EXPECT_TRUE(fs::exists(out + "/" + f)) << overlay << ": " << f;
    EXPECT_FALSE(fs::exists(out + "/frame_000001.png"));
  }
  // A run without per-node contact data says so instead of silently showing nothing.
  const ProcessResult r = weft({"render", run, "--frames", "4", "--size", "32x32", "--overlay",
                                "contacts", "--out", dir.file("c"), "--quiet"});
  EXPECT_NE(r.err.find("no per-node contact data"), std::string::npos) << r.err;
}

TEST(RenderCli, ReadsContactBranchesAndForcesOfARun) {
  TempDir dir;
  const std::string run = writeRunFolder(dir, 2);
  const std::size_t nodes = 49;
  std::vector<double> branches(3 * nodes, 0.0), forces(3 * nodes * 3, 0.0);
  for (std::size_t i = 0; i < nodes; ++i)
    branches[2 * nodes + i] = double(1 + i % 3);  // state 2 only
  for (std::size_t i = 0; i < nodes; ++i) forces[(2 * nodes + i) * 3 + 1] = 1.0;
  writeNpy(run + "/contact_branches.npy", {3, nodes}, branches.data());
  writeNpy(run + "/contact_forces.npy", {3, nodes, 3}, forces.data());
  const ProcessResult r = weft({"render", run, "--frames", "0:2:2", "--size", "96x64", "--overlay",
                                "contacts", "--camera", "front", "--out", dir.file("frames")});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("no per-node contact data"), std::string::npos) << r.err;
  // State 2 has contact nodes of every branch; state 0 has none.
  auto count = [&](const std::string& file, const render::Rgb& colour) {
    const render::Image image = render::readPng(file);
    int n = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width - 20; ++x)  // the legend swatches sit at the right edge
        n += image.at(x, y)[0] == std::lround(colour.x() * 255) &&
             image.at(x, y)[1] == std::lround(colour.y() * 255) &&
             image.at(x, y)[2] == std::lround(colour.z() * 255);
    return n;
  };
  const render::Rgb stick = render::branchColor(render::ContactBranch::Stick);
  EXPECT_EQ(count(dir.file("frames/frame_000000.png"), stick), 0);
  EXPECT_GT(count(dir.file("frames/frame_000002.png"), stick), 10);

  // A malformed contact file is an input error naming it.
  writeNpy(run + "/contact_branches.npy", {3, nodes - 1}, branches.data());
  const ProcessResult bad = weft({"render", run, "--out", dir.file("bad"), "--quiet"});
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("contact_branches.npy: shape"), std::string::npos) << bad.err;
}

TEST(RenderCli, DefaultOutputOfARunIsItsFramesFolder) {
  TempDir dir;
  const std::string run = writeRunFolder(dir, 2);
  ASSERT_EQ(weft({"render", run, "--size", "32x32", "--quiet"}).exitCode, 0);
  EXPECT_TRUE(fs::exists(run + "/frames/frame_000002.png"));
}

TEST(RenderCli, BadOptionsAreInputErrors) {
  TempDir dir;
  const std::string scene = hangingScene(dir, 2);
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"--size", "100"}, ": --size: expects WxH"},
      {{"--size", "8x8"}, ": --size: expects WxH"},
      {{"--frames", "3:1"}, ": --frames: last frame comes before the first"},
      {{"--frames", "0:2:0"}, ": --frames: stride must be at least 1"},
      {{"--frames", "a:b"}, ": --frames: expects A:B:S"},
      {{"--frames", "0:9"}, ": --frames: frame 9 is past the last state 2"},
      {{"--camera", "diagonal"}, ": --camera: must be front, side, top or auto"},
      {{"--overlay", "heat"}, ": --overlay: must be contacts, strain, speed or none"},
      {{"--backend", "vulkan"}, ": --backend: must be auto, osmesa or egl"},
      {{"--colour", "red"}, ": --colour: unknown option"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"render", scene, "--out", dir.file("never")};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const ProcessResult r = weft(args);
    EXPECT_EQ(r.exitCode, 2) << c.message << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir.file("never")));
  const ProcessResult missing = weft({"render", dir.file("nothing-here")});
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("no such file or folder"), std::string::npos) << missing.err;
}

TEST(RenderCli, AFailedRenderLeavesAnExistingOutputUntouched) {
  TempDir dir;
  fs::create_directories(dir.file("frames"));
  const std::string keep = dir.write("frames/keep.txt", "earlier output");
  // An absurd initial velocity overflows in the simulation: a numerical failure (exit 3) after
  // the output folder was staged.
  nlohmann::json doc = hangingClothScene(0.5, 6, 0.01, 2, 500.0);
  doc["cloths"][0]["initial_velocity"] = {1e308, 0, 0};
  const std::string scene = writeScene(dir.file("overflow.json"), doc);
  const ProcessResult r = weft({"render", scene, "--size", "32x32", "--out", dir.file("frames")});
  EXPECT_EQ(r.exitCode, 3) << r.err;
  EXPECT_TRUE(fs::exists(keep));
  EXPECT_FALSE(fs::exists(dir.file("frames/frame_000000.png")));
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
        << "staging left behind";
}

TEST(RenderCli, VideoNeedsFfmpegAndSaysSo) {
  TempDir dir;
  const std::string scene = hangingScene(dir, 2);
  const ProcessResult r = weft({"render", scene, "--size", "32x32", "--out", dir.file("frames"),
                                "--video", dir.file("run.mp4"), "--quiet"});
  if (r.exitCode == 0) {
    EXPECT_TRUE(fs::exists(dir.file("run.mp4"))) << "ffmpeg is installed: the video must exist";
  } else {
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("--video: ffmpeg is not available"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("frames")))
        << "nothing rendered when the video cannot be made";
  }
}

TEST(RenderCli, VideoIsAssembledByFfmpegFromTheCommittedFrames) {
  // A stand-in ffmpeg on PATH records its arguments as the "video": this checks what weft asks
  // of ffmpeg and that the video appears only under its final name.
  TempDir dir;
  const std::string scene = hangingScene(dir, 4);
  fs::create_directories(dir.file("bin"));
  const std::string fake =
      dir.write("bin/ffmpeg", "#!/bin/sh\nfor last; do :; done\necho \"$@\" > \"$last\"\n");
  fs::permissions(fake, fs::perms::owner_all);
  const ProcessResult r =
      runProcess({"/usr/bin/env", "PATH=" + dir.file("bin") + ":/usr/bin:/bin", WEFT_BINARY,
                  "render", scene, "--size", "32x32", "--frames", "0:4:2", "--out",
                  dir.file("frames"), "--video", dir.file("run.mp4"), "--quiet"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string args = readFile(dir.file("run.mp4"));
  EXPECT_NE(args.find("-framerate 50 "), std::string::npos) << args;  // dt 0.01 s, every 2nd state
  EXPECT_NE(args.find(dir.file("frames") + "/frame_*.png"), std::string::npos) << args;
  EXPECT_NE(args.find("-pix_fmt yuv420p"), std::string::npos) << args;
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
        << "partial video left behind";
}

TEST(RenderCli, WorksWithTheEglBackendWhenAsked) {
  TempDir dir;
  const std::string scene = hangingScene(dir, 2);
  const ProcessResult r = weft({"render", scene, "--frames", "0", "--size", "32x32", "--backend",
                                "egl", "--out", dir.file("frames"), "--quiet"});
  if (r.exitCode == 2 && r.err.find("EGL") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("backend egl"), std::string::npos) << r.err;
}

// WEFT_OSMESA_LIBRARY / WEFT_EGL_LIBRARY name the libraries to open; pointing them at nothing
// stands in for a machine without OSMesa (upstream Mesa has dropped it) or without any.
ProcessResult weftWithout(const std::vector<std::string>& variables,
                          const std::vector<std::string>& args) {
  std::vector<std::string> argv = {"/usr/bin/env"};
  for (const std::string& v : variables) argv.push_back(v + "=/nonexistent/lib.so");
  argv.push_back(WEFT_BINARY);
  argv.insert(argv.end(), args.begin(), args.end());
  return runProcess(argv);
}

TEST(RenderCli, FallsBackToEglWhereOsMesaIsMissing) {
  TempDir dir;
  const std::string scene = hangingScene(dir, 2);
  const ProcessResult r =
      weftWithout({"WEFT_OSMESA_LIBRARY"}, {"render", scene, "--frames", "0", "--size", "32x32",
                                            "--out", dir.file("frames"), "--quiet"});
  if (r.exitCode == 2 && r.err.find("EGL") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("backend egl"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir.file("frames/frame_000000.png")));
}

TEST(RenderCli, NoOpenGlAtAllIsAClearErrorNotACrash) {
  TempDir dir;
  const std::string scene = hangingScene(dir, 2);
  const ProcessResult r =
      weftWithout({"WEFT_OSMESA_LIBRARY", "WEFT_EGL_LIBRARY"},
                  {"render", scene, "--frames", "0", "--out", dir.file("frames")});
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("error: " + scene + ": --backend auto: no headless OpenGL"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("OSMesa is not available"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("EGL is not available"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("frames")));
  // The binary itself starts on such a machine: nothing links OSMesa or EGL at load time.
  EXPECT_EQ(weftWithout({"WEFT_OSMESA_LIBRARY", "WEFT_EGL_LIBRARY"}, {"--help"}).exitCode, 0);
}

}  // namespace
}  // namespace weft::test
