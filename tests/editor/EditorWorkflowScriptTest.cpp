// The editor's workflows as a person runs them, driven by scripts through the real binary
// (headless through OSMesa) and checked through state: importing a garment and adding obstacles,
// the vertex inspector against the simulator's own trajectory, the optimiser on the system
// identification scene (loss falls, apply, undo), final-frame targets (live loss, saved .npy,
// reopened), one viewport golden image, and the frame-time benchmark mode.

#include "../render/GoldenImage.h"
#include "EditorScriptRun.h"
#include "support/Process.h"
#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>
#include <weft/io/Npy.h>
#include <weft/physics/Simulator.h>
#include <weft/render/Image.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

namespace weft::test {
namespace {

namespace fs = std::filesystem;

Vec3 vec(const nlohmann::json& j) {
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

// A 2 x 1 strip of 6 vertices (4 triangles), in centimetres.
std::string stripObj() {
  return "v 200 0 100\nv 0 0 0\nv 100 0 100\nv 200 0 0\nv 0 0 100\nv 100 0 0\n"
         "f 2 5 6\nf 6 5 3\nf 6 3 4\nf 4 3 1\n";
}

TEST(EditorWorkflow, ImportGarmentAndAddObstacles) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("scene.json"), hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  fs::create_directories(dir.file("meshes"));
  const std::string garment = dir.write("meshes/strip.obj", stripObj());
  const std::string broken = dir.write("meshes/broken.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  const ProcessResult r = runEditor(
      dir, {{{"open", scene}},
            {{"import_garment", garment}, {"scale", 0.01}, {"translate", {0.0, 0.5, 0.3}}},
            {{"import_garment", broken}, {"expect_error", "degenerate"}},
            {{"write_state", dir.file("after-broken.json")}},
            {{"import_garment", dir.file("meshes/none.fbx")}, {"expect_error", "file not found"}},
            {{"add_obstacle", "sphere"}},
            {{"add_obstacle", "box"}},
            {{"add_obstacle", "cone"}, {"expect_error", "unknown obstacle shape"}},
            {{"add_mesh_obstacle", garment}, {"fit", 0.5}, {"translate", {0.0, -0.3, 0.0}}},
            {{"set", "obstacles.0.sphere.radius"}, {"value", 0.25}},
            {{"expect", {{"valid", true}}}},
            {{"save", true}},
            {{"undo", true}},
            {{"write_state", dir.file("after-undo.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  const nlohmann::json broke = readJson(dir.file("after-broken.json"));
  EXPECT_TRUE(broke["message_is_error"]) << "the refusal is shown as an error";
  EXPECT_NE(broke["message"].get<std::string>().find("broken.obj"), std::string::npos)
      << broke["message"];
  EXPECT_EQ(broke["document"]["cloths"].size(), 2u) << "the broken mesh added nothing";

  const nlohmann::json saved = readJson(scene);
  ASSERT_EQ(saved["cloths"].size(), 2u);
  const nlohmann::json& mesh = saved["cloths"][1]["mesh"];
  EXPECT_EQ(mesh["file"], "meshes/strip.obj") << "relative to the scene's folder";
  EXPECT_EQ(mesh["scale"], 0.01);
  EXPECT_EQ(mesh["transform"]["translate"], nlohmann::json::array({0.0, 0.5, 0.3}));
  ASSERT_EQ(saved["obstacles"].size(), 3u);
  EXPECT_EQ(saved["obstacles"][0]["sphere"]["radius"], 0.25);
  EXPECT_TRUE(saved["obstacles"][1].contains("box"));
  EXPECT_EQ(saved["obstacles"][2]["mesh"]["file"], "meshes/strip.obj");
  EXPECT_DOUBLE_EQ(saved["obstacles"][2]["mesh"]["scale"].get<double>(), 0.5 / 200.0);
  // The saved scene simulates as saved: 25 + 6 cloth vertices.
  const Scene loaded = loadScene(scene);
  EXPECT_EQ(loaded.vertexCount(), 31);
  // Nothing was selected: the sphere (radius 0.3 m when added) went under the cloths' centre,
  // its top 2 cm below their lowest vertex, not into the garment at the origin.
  double lowest = 1e300;
  for (const auto& cloth : loaded.cloths)
    lowest = std::min(lowest, cloth.mesh.vertices.col(1).minCoeff());
  EXPECT_NEAR(saved["obstacles"][0]["sphere"]["center"][1].get<double>(), lowest - 0.02 - 0.3,
              1e-9);

  const nlohmann::json undone = readJson(dir.file("after-undo.json"));
  EXPECT_EQ(undone["document"]["obstacles"][0]["sphere"]["radius"], 0.3)
      << "undo takes back the last edit";
  EXPECT_TRUE(undone["dirty"]);
}

// A garment picked, not typed: Ctrl+I opens the import dialog browsing the scene's folder; a
// click on a folder opens it, a click on the mesh puts its path in the field, Import adds it.
// The mesh lies where the folder was, clicked at once: not a double click that confirms it.
TEST(EditorWorkflow, ImportGarmentPickedInTheFileBrowser) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("scene.json"), hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  fs::create_directories(dir.file("meshes"));
  dir.write("meshes/strip.obj", stripObj());
  dir.write("meshes/notes.txt", "not a mesh");
  const ProcessResult r = runEditor(dir, {{{"open", scene}},
                                          {{"frames", 2}},
                                          {{"key", "ctrl+i"}},
                                          {{"frames", 3}},
                                          {{"write_state", dir.file("opened.json")}},
                                          {{"mouse_click", item("browser:entry:meshes")}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("in-meshes.json")}},
                                          {{"mouse_click", item("browser:entry:strip.obj")}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("picked.json")}},
                                          {{"mouse_click", item("dialog:confirm")}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("imported.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json opened = readJson(dir.file("opened.json"));
  ASSERT_TRUE(opened["browser"].is_object()) << opened["dialog"];
  EXPECT_EQ(fs::path(opened["browser"]["folder"].get<std::string>()),
            fs::path(dir.path()).lexically_normal());
  const auto has = [](const nlohmann::json& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  EXPECT_TRUE(has(opened["browser"]["entries"], "meshes/")) << opened["browser"];
  EXPECT_FALSE(has(opened["browser"]["entries"], "scene.json")) << "not a mesh";
  const nlohmann::json inMeshes = readJson(dir.file("in-meshes.json"));
  EXPECT_EQ(inMeshes["browser"]["entries"], nlohmann::json::array({"../", "strip.obj"}));
  const nlohmann::json picked = readJson(dir.file("picked.json"));
  EXPECT_EQ(picked["dialog"]["title"], "Import garment") << "a single click only picks";
  EXPECT_EQ(picked["document"]["cloths"].size(), 1u);
  const nlohmann::json imported = readJson(dir.file("imported.json"));
  EXPECT_TRUE(imported["dialog"].is_null()) << imported["message"];
  EXPECT_TRUE(imported["browser"].is_null());
  ASSERT_EQ(imported["document"]["cloths"].size(), 2u) << imported["message"];
  EXPECT_EQ(imported["document"]["cloths"][1]["mesh"]["file"], "meshes/strip.obj");
}

// A garment file in centimetres, 5 m to the side of the scene: picked in the browser it is
// checked at once, the dialog offers the units that give it a garment's size, a click on
// centimetres sets the scale, and after the import the camera frames the scene with it.
TEST(EditorWorkflow, ImportOffersTheFilesUnitAndFramesTheNewGarment) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("scene.json"), hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  dir.write("far-cm.obj",
            "v 700 0 100\nv 500 0 0\nv 600 0 100\nv 700 0 0\nv 500 0 100\nv 600 0 0\n"
            "f 2 5 6\nf 6 5 3\nf 6 3 4\nf 4 3 1\n");
  const ProcessResult r = runEditor(dir, {{{"open", scene}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("before.json")}},
                                          {{"key", "ctrl+i"}},
                                          {{"frames", 3}},
                                          {{"mouse_click", item("browser:entry:far-cm.obj")}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("checked.json")}},
                                          {{"mouse_click", item("units:centimetres")}},
                                          {{"frames", 2}},
                                          {{"mouse_click", item("dialog:confirm")}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("after.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json checked = readJson(dir.file("checked.json"));
  ASSERT_TRUE(checked["items"].contains("units:centimetres")) << checked["items"];
  EXPECT_TRUE(checked["items"].contains("units:millimetres"));
  const nlohmann::json after = readJson(dir.file("after.json"));
  ASSERT_EQ(after["document"]["cloths"].size(), 2u) << after["message"];
  EXPECT_EQ(after["document"]["cloths"][1]["mesh"]["scale"], 0.01);
  // The strip lies at x = 5..7 m: the camera's target moves from the old cloth toward it.
  const double before = readJson(dir.file("before.json"))["camera"]["target"][0];
  const double now = after["camera"]["target"][0];
  EXPECT_LT(std::abs(before), 0.6);
  EXPECT_GT(now, 2.5) << after["camera"];
  EXPECT_GT(after["camera"]["distance"].get<double>(),
            readJson(dir.file("before.json"))["camera"]["distance"].get<double>());
}

// Open by double click: Ctrl+O browses the scene's folder for scenes (.json only); a double
// click on one opens it.
TEST(EditorWorkflow, OpenSceneByDoubleClickInTheFileBrowser) {
  TempDir dir;
  const std::string first =
      writeScene(dir.file("first.json"), hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  writeScene(dir.file("second.json"), hangingClothScene(1.0, 3, 0.01, 5, 500.0));
  dir.write("strip.obj", stripObj());
  const ProcessResult r = runEditor(dir, {{{"open", first}},
                                          {{"frames", 2}},
                                          {{"key", "ctrl+o"}},
                                          {{"frames", 3}},
                                          {{"write_state", dir.file("browsing.json")}},
                                          {{"mouse_click", item("browser:entry:second.json")}},
                                          {{"mouse_click", item("browser:entry:second.json")}},
                                          {{"frames", 3}},
                                          {{"write_state", dir.file("opened.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  // The folder also holds the test's own script.json; the mesh is not listed.
  EXPECT_EQ(readJson(dir.file("browsing.json"))["browser"]["entries"],
            nlohmann::json::array({"../", "first.json", "script.json", "second.json"}));
  const nlohmann::json opened = readJson(dir.file("opened.json"));
  EXPECT_TRUE(opened["dialog"].is_null()) << opened["message"];
  EXPECT_EQ(fs::path(opened["file"].get<std::string>()).filename(), "second.json");
  EXPECT_EQ(opened["document"]["cloths"][0]["mesh"]["grid"]["resolution"],
            nlohmann::json::array({3, 3}));
}

// Esc closes the Open dialog once its path field is let go (a click in the file list lets it go),
// as it closes the import dialog; the document stays as it was.
TEST(EditorWorkflow, EscapeClosesTheOpenDialog) {
  TempDir dir;
  const std::string first =
      writeScene(dir.file("first.json"), hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  fs::create_directories(dir.file("sub"));
  const ProcessResult r = runEditor(dir, {{{"open", first}},
                                          {{"frames", 2}},
                                          {{"key", "ctrl+o"}},
                                          {{"frames", 3}},
                                          {{"mouse_click", item("browser:entry:sub")}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("open.json")}},
                                          {{"key", "escape"}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("closed.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_EQ(readJson(dir.file("open.json"))["dialog"]["title"], "Open scene");
  const nlohmann::json closed = readJson(dir.file("closed.json"));
  EXPECT_TRUE(closed["dialog"].is_null()) << closed["dialog"];
  EXPECT_EQ(fs::path(closed["file"].get<std::string>()).filename(), "first.json");
}

// A 0.6 m cloth of 8 x 8 quads dropped onto a sphere (the centre vertex lands on top).
nlohmann::json dropOnSphere(int steps) {
  nlohmann::json doc = gridScene(0.6, 8, 0.01, steps, 300.0, 1e-4, 0.2);
  doc["gravity"] = {0.0, -9.8, 0.0};
  doc["solver"] = {{"pd_iterations", 300}, {"pd_tolerance", 1e-6}};
  doc["cloths"][0]["mesh"]["transform"] = {{"translate", {0.0, 0.205, 0.0}}};
  doc["obstacles"] = {
      {{"sphere", {{"center", {0.0, 0.0, 0.0}}, {"radius", 0.2}}}, {"friction", 0.4}}};
  return doc;
}

TEST(EditorWorkflow, InspectorShowsTheCachedTrajectory) {
  TempDir dir;
  const int steps = 10, state = 9, centre = 40, edge = 4;
  const std::string scene = writeScene(dir.file("drop.json"), dropOnSphere(steps));
  const ProcessResult r = runEditor(dir, {{{"open", scene}},
                                          {{"simulate", true}},
                                          {{"scrub", state}},
                                          {{"panel", "inspect"}},
                                          {{"force_arrows", true}},
                                          {{"select", {centre}}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("centre.json")}},
                                          {{"select", {edge, centre}}},
                                          {{"write_state", dir.file("edge.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  const Scene parsed = parse(dropOnSphere(steps));
  Simulator simulator(parsed);
  Trajectory own;
  simulator.run(steps, own);
  for (const auto& [file, node] :
       {std::pair<std::string, int>{"centre.json", centre}, {"edge.json", edge}}) {
    SCOPED_TRACE(file);
    const nlohmann::json s = readJson(dir.file(file));
    EXPECT_EQ(s["focus"], node);
    EXPECT_EQ(s["panel"], "inspect");
    EXPECT_EQ(s["plotted_steps"], steps);
    const nlohmann::json& in = s["inspector"];
    ASSERT_TRUE(in.is_object()) << s.dump(1);
    EXPECT_EQ(in["node"], node);
    EXPECT_EQ(in["state"], state);
    EXPECT_LT((vec(in["position"]) - own.positions[state].row(node).transpose()).norm(), 1e-9);
    EXPECT_LT((vec(in["velocity"]) - own.velocities[state].row(node).transpose()).norm(), 1e-7);
    Vec3 impulse = Vec3::Zero();
    int contacts = 0;
    for (const ContactPoint& p : own.contacts[state - 1].points)
      if (p.node == node) impulse += p.impulse, ++contacts;
    ASSERT_EQ(in["contacts"].size(), std::size_t(contacts));
    EXPECT_LT((vec(in["contact_impulse"]) - impulse).norm(), 1e-9);
    EXPECT_LT((vec(in["contact_force"]) - impulse / parsed.time.dt).norm(), 1e-7);
    if (node == centre) {
      ASSERT_EQ(contacts, 1) << "the centre rests on the sphere";
      EXPECT_EQ(in["contacts"][0]["obstacle"], 0);
      EXPECT_EQ(in["branch"], in["contacts"][0]["branch"]);
      EXPECT_NE(in["branch"], 0);
    }
  }
}

TEST(EditorWorkflow, OptimiserLowersTheLossThenApplyAndUndo) {
  TempDir dir;
  const ProcessResult r = runEditor(
      dir, {{{"open", std::string(WEFT_ASSET_DIR) + "/scenes/wind_sysid.json"}},
            {{"panel", "optimise"}},
            {{"optimize", {{"method", "lbfgsb"}, {"paused", true}}}},
            {{"optimize_step", 4}},
            {{"write_state", dir.file("stepped.json")}},
            {{"optimize_apply", true}},
            {{"write_state", dir.file("applied.json")}},
            {{"undo", true}},
            {{"expect", {{"value", {{"path", "cloths.0.material.stretch"}, {"equals", 400.0}}}}}},
            {{"expect", {{"value", {{"path", "wind.strength"}, {"equals", 1.5}}}}}},
            {{"redo", true}},
            {{"optimize_revert", true}},
            {{"write_state", dir.file("reverted.json")}},
            {{"optimize_cancel", true}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  const nlohmann::json stepped = readJson(dir.file("stepped.json"));
  const nlohmann::json& opt = stepped["optimizer"];
  EXPECT_EQ(opt["status"], "paused");
  EXPECT_EQ(opt["method"], "lbfgsb");
  EXPECT_EQ(opt["parameters"],
            nlohmann::json::array({"cloths.0.material.stretch", "wind.strength"}));
  ASSERT_EQ(opt["evaluations"], 4);
  const double first = opt["losses"][0], best = opt["best_loss"];
  EXPECT_LT(best, 0.1 * first) << "the loss falls over four evaluations";
  EXPECT_EQ(stepped["document"]["cloths"][0]["material"]["stretch"], 400.0)
      << "nothing applied yet";

  const nlohmann::json applied = readJson(dir.file("applied.json"));
  EXPECT_EQ(applied["document"]["cloths"][0]["material"]["stretch"], opt["best_values"][0]);
  EXPECT_EQ(applied["document"]["wind"]["strength"], opt["best_values"][1]);
  EXPECT_NE(applied["document"]["wind"]["strength"], 1.5);
  EXPECT_TRUE(applied["can_undo"]);

  const nlohmann::json reverted = readJson(dir.file("reverted.json"));
  EXPECT_EQ(reverted["document"]["cloths"][0]["material"]["stretch"], 400.0);
  EXPECT_EQ(reverted["document"]["wind"]["strength"], 1.5);
}

// The gradient-free baselines run from the Optimise tab as L-BFGS-B does (on a worker, stepped
// by evaluations), sample new points, and the same seed gives the same samples.
TEST(EditorWorkflow, GradientFreeMethodsRunFromTheEditorAndFollowTheirSeed) {
  for (const char* method : {"cmaes", "es1p1"}) {
    SCOPED_TRACE(method);
    TempDir dir;
    const nlohmann::json actions = {
        {{"open", std::string(WEFT_ASSET_DIR) + "/scenes/wind_sysid.json"}},
        {{"optimize", {{"method", method}, {"seed", 7}}}},
        {{"optimize_step", 6}},
        {{"write_state", dir.file("state.json")}},
        {{"optimize_cancel", true}}};
    ASSERT_EQ(runEditor(dir, actions).exitCode, 0);
    const nlohmann::json first = readJson(dir.file("state.json"))["optimizer"];
    ASSERT_EQ(runEditor(dir, actions).exitCode, 0);
    const nlohmann::json second = readJson(dir.file("state.json"))["optimizer"];
    EXPECT_EQ(first["method"], method);
    ASSERT_GE(first["evaluations"].get<int>(), 6);
    EXPECT_EQ(first["losses"], second["losses"]) << "same seed, same samples";
    EXPECT_EQ(first["values"], second["values"]);
    std::set<double> stretches;
    for (const nlohmann::json& v : first["values"]) stretches.insert(v[0].get<double>());
    EXPECT_GT(stretches.size(), 3u) << "the strategy samples new points";
  }
}

TEST(EditorWorkflow, TargetsGiveALiveLossAndAreSavedNextToTheScene) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, 6, 500.0));
  const ProcessResult run = runEditor(
      dir, {{{"open", scene}},
            {{"simulate", true}},
            {{"scrub", 6}},
            {{"select", {20, 24}}},
            {{"set_targets", true}},
            {{"write_state", dir.file("set.json")}},
            {{"move_targets", {0.0, 0.1, 0.0}}},
            {{"target", 24}, {"position", {0.5, 0.6, 0.0}}},
            {{"panel", "targets"}},
            {{"frames", 1}},
            {{"write_state", dir.file("moved.json")}},
            {{"save", true}},
            {{"expect", {{"dirty", false}}}},
            {{"target", 99}, {"position", {0.0, 0.0, 0.0}}, {"expect_error", "not a cloth vertex"}},
            {{"undo", true}},
            {{"write_state", dir.file("undone.json")}},
            {{"open", scene}},
            {{"write_state", dir.file("reopened.json")}},
            {{"remove_targets", true}},
            {{"write_state", dir.file("removed.json")}}});
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;

  // Set at the shown (final) positions: the final term is zero.
  const nlohmann::json set = readJson(dir.file("set.json"));
  ASSERT_TRUE(set["loss"].is_number()) << set["loss_note"];
  EXPECT_EQ(set["loss"], 0.0);
  const Vec3 start20 = vec(set["targets"]["20"]);

  const nlohmann::json moved = readJson(dir.file("moved.json"));
  EXPECT_EQ(moved["panel"], "targets");
  const Vec3 target20 = vec(moved["targets"]["20"]), target24 = vec(moved["targets"]["24"]);
  EXPECT_TRUE(target20.isApprox(start20 + Vec3(0, 0.1, 0), 1e-12));
  EXPECT_EQ(target24, Vec3(0.5, 0.6, 0.0));
  // The live loss is the final term against the cached last state: 0.1^2 for vertex 20, plus
  // vertex 24's squared distance.
  const Vec3 end24 = vec(set["targets"]["24"]);
  const double expected = 0.01 + (end24 - target24).squaredNorm();
  ASSERT_TRUE(moved["loss"].is_number()) << moved["loss_note"];
  EXPECT_NEAR(moved["loss"].get<double>(), expected, 1e-12);
  EXPECT_FALSE(moved["cache_stale"]) << "targets do not change the motion";

  // Saved: the scene names the file, the file holds the targets (rest positions elsewhere).
  const nlohmann::json saved = readJson(scene);
  EXPECT_EQ(saved["task"]["loss"]["final"]["target"], "hang-final-target.npy");
  EXPECT_EQ(saved["task"]["loss"]["final"]["vertices"], nlohmann::json::array({20, 24}));
  const NpyArray npy = readNpy(dir.file("hang-final-target.npy"));
  ASSERT_EQ(npy.shape, (std::vector<std::size_t>{25, 3}));
  EXPECT_EQ(Vec3(npy.data[24 * 3], npy.data[24 * 3 + 1], npy.data[24 * 3 + 2]), target24);

  const nlohmann::json undone = readJson(dir.file("undone.json"));
  EXPECT_TRUE(vec(undone["targets"]["24"]).isApprox(end24 + Vec3(0, 0.1, 0), 1e-12))
      << "undo: the typed position goes";

  const nlohmann::json reopened = readJson(dir.file("reopened.json"));
  EXPECT_EQ(vec(reopened["targets"]["24"]), target24) << "targets come back from the saved file";
  EXPECT_EQ(reopened["targets"].size(), 2u);

  const nlohmann::json removed = readJson(dir.file("removed.json"));
  EXPECT_TRUE(removed["targets"].empty());
  EXPECT_FALSE(removed["document"].contains("task")) << "no term left: no task";
}

// Selection by region on the 1 m hanging cloth of 4 x 4 quads (row j at y = 1.5 - 0.25 j at
// rest): a band along y, the border loop through a clicked vertex, and what each refuses.
TEST(EditorWorkflow, SelectionByRegion) {
  TempDir dir;
  const ProcessResult r = runEditor(
      dir,
      {{{"open", writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, 4, 500.0))}},
       {{"select_loop", true}, {"expect_error", "click a vertex on the border first"}},
       {{"select_band", {{"axis", "y"}, {"min", 1.2}, {"max", 1.6}}}},
       {{"expect", {{"selected", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}}}}},
       {{"select_band", {{"axis", "x"}, {"min", 0.4}, {"max", 0.6}}}, {"add", true}},
       {{"expect", {{"selected", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 14, 19, 24}}}}},
       {{"select_band", {{"axis", "w"}, {"min", 0.0}, {"max", 1.0}}},
        {"expect_error", "x, y or z"}},
       {{"select", {12}}},
       {{"select_loop", true}, {"expect_error", "not on a border"}},
       {{"select", {9}}},
       {{"select_loop", true}},
       {{"expect", {{"selected", {0, 1, 2, 3, 4, 5, 9, 10, 14, 15, 19, 20, 21, 22, 23, 24}}}}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
}

// The vertex inspector's loss gradient dL/dx_n: at the last state it is the final term's own
// derivative, 2 (x - target); at an earlier one, what the engine's backward pass gives for the
// saved scene.
TEST(EditorWorkflow, InspectorShowsTheLossGradient) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, 6, 500.0));
  const ProcessResult r = runEditor(dir, {{{"open", scene}},
                                          {{"compute_gradient", true}, {"expect_error", "no task"}},
                                          {{"simulate", true}},
                                          {{"scrub", 6}},
                                          {{"select", {20, 24}}},
                                          {{"set_targets", true}},
                                          {{"move_targets", {0.0, 0.1, 0.0}}},
                                          {{"select", {24}}},
                                          {{"write_state", dir.file("before.json")}},
                                          {{"compute_gradient", true}},
                                          {{"write_state", dir.file("last.json")}},
                                          {{"scrub", 3}},
                                          {{"write_state", dir.file("middle.json")}},
                                          {{"save", true}},
                                          {{"move_targets", {0.0, 0.1, 0.0}}},
                                          {{"write_state", dir.file("moved.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  EXPECT_TRUE(readJson(dir.file("before.json"))["inspector"]["gradient"].is_null())
      << "not computed yet";
  const nlohmann::json last = readJson(dir.file("last.json"))["inspector"];
  ASSERT_EQ(last["state"], 6);
  ASSERT_TRUE(last["gradient"].is_array()) << last;
  EXPECT_TRUE(vec(last["gradient"]).isApprox(Vec3(0.0, -0.2, 0.0), 1e-9)) << last["gradient"];

  const nlohmann::json middle = readJson(dir.file("middle.json"))["inspector"];
  ASSERT_EQ(middle["state"], 3);
  const Scene saved = loadScene(scene);
  const ForwardPass pass = runForwardPass(saved);
  BackwardSettings exact = saved.solver.backward;
  exact.method = "direct";
  const GradientResult g = backpropagate(pass.trajectory, TaskLoss(saved), ParameterSet(), exact);
  const Vec3 engine = g.dLdx[3].row(24).transpose();
  EXPECT_GT(engine.norm(), 1e-3);
  EXPECT_TRUE(vec(middle["gradient"]).isApprox(engine, 1e-5))
      << middle["gradient"] << " vs " << engine.transpose();

  EXPECT_TRUE(readJson(dir.file("moved.json"))["inspector"]["gradient"].is_null())
      << "a target edit makes it stale";
}

// The Targets tab's other losses: a target shape from a mesh file (final targets at every vertex,
// placed as the cloth's own mesh) and the built-in hemline term at the selected vertices.
TEST(EditorWorkflow, TargetShapeFromAMeshAndTheHemline) {
  TempDir dir;
  // The 4 x 4 grid's own frame (XZ plane, vertex (i, j) = 5 j + i), moved 0.1 m along x.
  std::string obj;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i)
      obj +=
          "v " + std::to_string(-0.4 + 0.25 * i) + " 0 " + std::to_string(-0.5 + 0.25 * j) + "\n";
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int v = 5 * j + i + 1;  // OBJ counts from 1
      obj += "f " + std::to_string(v) + " " + std::to_string(v + 5) + " " + std::to_string(v + 1) +
             "\n";
      obj += "f " + std::to_string(v + 1) + " " + std::to_string(v + 5) + " " +
             std::to_string(v + 6) + "\n";
    }
  const std::string shape = dir.write("shape.obj", obj);
  const std::string small = dir.write("small.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const ProcessResult r = runEditor(
      dir,
      {{{"open", writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, 4, 500.0))}},
       {{"load_target_mesh", small}, {"expect_error", "3 vertices, but cloth 0 has 25"}},
       {{"load_target_mesh", shape}},
       {{"write_state", dir.file("shape.json")}},
       {{"set_hemline", 0.4}, {"expect_error", "select the hemline's vertices first"}},
       {{"select", {20, 21, 22, 23, 24}}},
       {{"set_hemline", 0.4}},
       {{"simulate", true}},
       {{"scrub", 4}},
       {{"write_state", dir.file("hemline.json")}},
       {{"remove_hemline", true}},
       {{"write_state", dir.file("removed.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  // Every vertex has a target: its rest position (the grid rotated 90 degrees about x, raised 1 m)
  // moved 0.1 m along x.
  const nlohmann::json targets = readJson(dir.file("shape.json"))["targets"];
  ASSERT_EQ(targets.size(), 25u);
  EXPECT_TRUE(vec(targets["0"]).isApprox(Vec3(-0.4, 1.5, 0.0), 1e-12)) << targets["0"];
  EXPECT_TRUE(vec(targets["24"]).isApprox(Vec3(0.6, 0.5, 0.0), 1e-12)) << targets["24"];

  const nlohmann::json hemline = readJson(dir.file("hemline.json"));
  EXPECT_EQ(hemline["document"]["task"]["loss"]["hemline"],
            (nlohmann::json{{"vertices", {20, 21, 22, 23, 24}}, {"height", 0.4}}));
  ASSERT_TRUE(hemline["loss_terms"].contains("hemline")) << hemline["loss_terms"];
  // The bottom row hangs at about y = 0.5 after four steps (it falls a few millimetres).
  EXPECT_NEAR(hemline["loss_terms"]["hemline"].get<double>(), 0.01, 0.003);
  EXPECT_TRUE(hemline["loss_terms"].contains("final"));

  const nlohmann::json removed = readJson(dir.file("removed.json"));
  EXPECT_FALSE(removed["document"]["task"]["loss"].contains("hemline"));
  EXPECT_TRUE(removed["document"]["task"]["loss"].contains("final")) << "the shape's targets stay";
}

// The Optimise tab's parameter list is edited in the editor: only the scene's differentiable
// numbers, only once the task has a loss, each add and remove one undo step.
TEST(EditorWorkflow, ParametersAreAddedAndRemovedInTheEditor) {
  TempDir dir;
  const ProcessResult r = runEditor(
      dir,
      {{{"open", writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, 4, 500.0))}},
       {{"add_parameter", "cloths.0.material.stretch"}, {"expect_error", "no loss yet"}},
       {{"simulate", true}},
       {{"scrub", 4}},
       {{"select", {20, 24}}},
       {{"set_targets", true}},
       {{"add_parameter", "time.dt"}, {"expect_error", "not differentiable"}},
       {{"add_parameter", "cloths.0.material.sheen"}, {"expect_error", "names no value"}},
       {{"add_parameter", "cloths.0.material.density"}},
       {{"add_parameter", "cloths.0.material.stretch"}},
       {{"add_parameter", "cloths.0.material.stretch"}, {"expect_error", "already a parameter"}},
       {{"expect",
         {{"value",
           {{"path", "task.parameters"},
            {"equals", {"cloths.0.material.density", "cloths.0.material.stretch"}}}}}}},
       {{"remove_parameter", "cloths.0.material.density"}},
       {{"remove_parameter", "cloths.0.material.density"},
        {"expect_error", "not a parameter of the task"}},
       {{"write_state", dir.file("removed.json")}},
       {{"undo", true}},
       {{"write_state", dir.file("undone.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_EQ(readJson(dir.file("removed.json"))["document"]["task"]["parameters"],
            nlohmann::json::array({"cloths.0.material.stretch"}));
  EXPECT_EQ(readJson(dir.file("undone.json"))["document"]["task"]["parameters"],
            nlohmann::json::array({"cloths.0.material.density", "cloths.0.material.stretch"}));
}

// docs/editor.md's first session (assets/editor/first-session.json), run as committed: import the
// skirt, pin its waist, drape it on a sphere, set targets at the hem where it hangs with stretch
// 100 N/m, start again from 400 N/m, add the parameter and step L-BFGS-B eight times. Only the
// file paths are rewritten (the garment from the source tree, the outputs into a temporary
// folder), and states are written along the way.
TEST(EditorWorkflow, FirstSessionFromReadmeConverges) {
  TempDir dir;
  const nlohmann::json committed =
      readJson(std::string(WEFT_ASSET_DIR) + "/editor/first-session.json");
  nlohmann::json actions = nlohmann::json::array();
  for (nlohmann::json a : committed["actions"]) {
    if (a.contains("import_garment"))
      a["import_garment"] = std::string(WEFT_ASSET_DIR) + "/meshes/dress.obj";
    if (a.contains("window_screenshot")) a["window_screenshot"] = dir.file("out/first-session.png");
    const bool optimised = a.contains("optimize_step");
    const bool targeted = a.contains("add_parameter");
    actions.push_back(a);
    if (targeted) actions.push_back({{"write_state", dir.file("targeted.json")}});
    if (optimised) actions.push_back({{"write_state", dir.file("optimised.json")}});
  }
  actions.push_back({{"write_state", dir.file("final.json")}});
  const ProcessResult r = runEditor(dir, actions);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  // Imported, pinned, draped: the skirt is the only cloth, its 32 waist vertices fixed, on a
  // sphere.
  const nlohmann::json targeted = readJson(dir.file("targeted.json"));
  const nlohmann::json& cloth = targeted["document"]["cloths"][0];
  EXPECT_EQ(targeted["document"]["cloths"].size(), 1u);
  EXPECT_EQ(loadScene(writeScene(dir.file("check.json"), targeted["document"])).vertexCount(), 288);
  EXPECT_EQ(cloth["attachments"][0]["vertices"],
            nlohmann::json::array({0,  1,  2,  3,  4,  5,  6,  7,  8,  9,  10, 11, 12, 13, 14, 15,
                                   16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31}))
      << "the waist: the border loop through vertex 0";
  EXPECT_TRUE(targeted["document"]["obstacles"][0].contains("sphere"));
  EXPECT_EQ(targeted["targets"].size(), 32u) << "the hem: the border loop through vertex 256";
  EXPECT_EQ(targeted["document"]["task"]["parameters"],
            nlohmann::json::array({"cloths.0.material.stretch"}));
  ASSERT_TRUE(targeted["loss"].is_number()) << targeted["loss_note"];
  const double start = targeted["loss"];
  EXPECT_GT(start, 1e-4) << "the hem hangs elsewhere at 400 N/m";

  // Eight evaluations bring the loss down by orders of magnitude and the stretch back to 100.
  const nlohmann::json opt = readJson(dir.file("optimised.json"))["optimizer"];
  ASSERT_EQ(opt["evaluations"], 8);
  EXPECT_NEAR(opt["losses"][0].get<double>(), start, 1e-3 * start)
      << "the first evaluation is the cached run";
  EXPECT_LT(opt["best_loss"].get<double>(), 1e-4 * start);
  EXPECT_NEAR(opt["best_values"][0].get<double>(), 100.0, 1.0);

  // Applied and simulated again: the shown run meets the targets.
  const nlohmann::json final = readJson(dir.file("final.json"));
  EXPECT_EQ(final["document"]["cloths"][0]["material"]["stretch"], opt["best_values"][0]);
  EXPECT_EQ(final["cache_frames"], 61);
  ASSERT_TRUE(final["loss"].is_number()) << final["loss_note"];
  EXPECT_LT(final["loss"].get<double>(), 1e-4 * start);
  EXPECT_TRUE(fs::exists(dir.file("out/first-session.png"))) << "the script makes its out/ folder";
}

// The golden viewport of the editing features: the rest state of a small hanging cloth with a
// sphere and a box added from the menu and two final-frame targets (the purple markers) raised
// above their vertices, from a fixed camera at 320x240. No simulation: the picture does not
// depend on the solver. Tolerance: the render tests' default (a pixel may differ by 16/255 per
// channel, within 1 pixel; at most 0.25 % of the pixels beyond that). Regenerate on purpose with
// `weft_tests_editor --bless --gtest_filter=EditorWorkflow.ViewportMatchesGolden` and look at it.
TEST(EditorWorkflow, ViewportMatchesGolden) {
  TempDir dir;
  const ProcessResult r = runEditor(
      dir,
      {{{"open", writeScene(dir.file("hang.json"), hangingClothScene(1.0, 6, 0.01, 5, 500.0))}},
       {{"add_obstacle", "sphere"}},
       {{"set", "obstacles.0.sphere.center"}, {"value", {0.0, 0.2, 0.4}}},
       {{"set", "obstacles.0.sphere.radius"}, {"value", 0.2}},
       {{"add_obstacle", "box"}},
       {{"set", "obstacles.1.box.center"}, {"value", {0.0, -0.2, 0.0}}},
       {{"set", "obstacles.1.box.size"}, {"value", {1.2, 0.2, 0.8}}},
       {{"select", {45, 48}}},
       {{"set_targets", true}},
       {{"move_targets", {0.0, 0.25, 0.3}}},
       {{"camera", {{"yaw", 35}, {"pitch", 15}, {"distance", 3.6}, {"target", {0.0, 0.45, 0.1}}}}},
       {{"frames", 1}},
       {{"screenshot", dir.file("viewport.png")}, {"size", {320, 240}}}});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(matchesGolden("editor_viewport_targets", render::readPng(dir.file("viewport.png"))));
}

TEST(EditorWorkflow, BenchmarkModePrintsFrameTimes) {
  TempDir dir;
  const ProcessResult r =
      runProcess({WEFT_EDITOR_BINARY, "--bench", "--bench-grid", "6", "--bench-steps", "3",
                  "--bench-frames", "4", "--size", "640x400", "--bench-out", dir.file("bench")},
                 dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("49 cloth vertices, 4 cached states"), std::string::npos) << r.out;
  for (const char* mode : {"| live |", "| scrub | 4 |", "| still | 4 |"})
    EXPECT_NE(r.out.find(mode), std::string::npos) << r.out;
  std::ifstream csv(dir.file("bench/editor-bench.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "mode,frame,ms,cpu_ms");
  const ProcessResult bad =
      runProcess({WEFT_EDITOR_BINARY, "--bench", "--bench-frames", "zero"}, dir.path());
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--bench-frames"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace weft::test
