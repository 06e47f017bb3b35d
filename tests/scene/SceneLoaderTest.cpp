// The strict scene loader: defaults, effects present only when named, overrides by JSON path,
// mesh files (scale before transform), repair of degenerate triangles, and errors that name
// the JSON path. (Malformed scenes through the real binary are in tests/app.)

#include <support/SceneBuilder.h>
#include <support/TempDir.h>
#include <weft/core/Error.h>
#include <weft/mesh/GridMesh.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

using test::TempDir;

// Expects `fn` to throw an InputError at `path` whose reason contains `phrase`.
template <class Fn>
void expectInputError(Fn&& fn, const std::string& path, const std::string& phrase) {
  try {
    fn();
    ADD_FAILURE() << "no error; expected one at " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), path) << e.what();
    EXPECT_NE(e.reason().find(phrase), std::string::npos) << e.what();
  }
}

TEST(SceneLoader, MinimalSceneGetsDefaultsAndNoOptionalEffects) {
  const nlohmann::json doc = {{"time", {{"dt", 0.02}, {"steps", 7}}},
                              {"cloths",
                               {{{"mesh", {{"grid", {{"size", {1, 2}}, {"resolution", {2, 3}}}}}},
                                 {"material", {{"density", 0.3}, {"stretch", 50}}}}}}};
  const Scene s = test::parse(doc, "some/dir/hanging.json");
  EXPECT_EQ(s.name, "hanging");  // from the file name when the scene has none
  EXPECT_EQ(s.time.dt, 0.02);
  EXPECT_EQ(s.time.steps, 7);
  EXPECT_FALSE(s.gravity.has_value());
  EXPECT_FALSE(s.wind.has_value());
  EXPECT_FALSE(s.task.has_value());
  EXPECT_TRUE(s.obstacles.empty());
  EXPECT_FALSE(s.hasSelfCollision());
  ASSERT_EQ(s.cloths.size(), 1u);
  EXPECT_EQ(s.cloths[0].material.bend, 0.0);
  EXPECT_EQ(s.cloths[0].initialVelocity, Vec3::Zero());
  EXPECT_TRUE(s.cloths[0].attachments.empty());
  EXPECT_EQ(s.vertexCount(), 12);
  const SolverSettings defaults;
  EXPECT_EQ(s.solver.pdIterations, defaults.pdIterations);
  EXPECT_EQ(s.solver.pdTolerance, defaults.pdTolerance);
}

TEST(SceneLoader, ReadsEveryEffectItNames) {
  nlohmann::json doc = test::hangingClothScene(1.0, 4, 0.01, 10, 300.0, 0.002, 0.2);
  doc["wind"] = {{"direction", {1, 0, 0.5}}, {"strength", 2.0}, {"frequency", 3.0}, {"phase", 0.5}};
  doc["cloths"][0]["initial_velocity"] = {0.1, 0.2, 0.3};
  doc["cloths"][0]["forces"] = {{{"vertices", {7, 8}}, {"force", {0, 0, 1.5}}}};
  doc["cloths"][0]["attachments"].push_back(
      {{"vertices", {24}},
       {"kind", "handle"},
       {"stiffness", 500.0},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 1.0}, {"offset", {0, 0.5, 0}}}}}}}});
  const Scene s = test::parse(doc);
  ASSERT_TRUE(s.gravity.has_value());
  EXPECT_EQ(*s.gravity, Vec3(0, -9.8, 0));
  ASSERT_TRUE(s.wind.has_value());
  EXPECT_EQ(s.wind->direction, Vec3(1, 0, 0.5));
  EXPECT_EQ(s.wind->strength, 2.0);
  EXPECT_EQ(s.wind->frequency, 3.0);
  EXPECT_EQ(s.wind->phase, 0.5);
  const Cloth& c = s.cloths[0];
  EXPECT_EQ(c.material.density, 0.2);
  EXPECT_EQ(c.material.stretch, 300.0);
  EXPECT_EQ(c.material.bend, 0.002);
  EXPECT_EQ(c.initialVelocity, Vec3(0.1, 0.2, 0.3));
  ASSERT_EQ(c.forces.size(), 1u);
  EXPECT_EQ(c.forces[0].vertices, (std::vector<int>{7, 8}));
  ASSERT_EQ(c.attachments.size(), 2u);
  EXPECT_EQ(c.attachments[0].kind, Attachment::Kind::Fixed);
  EXPECT_EQ(c.attachments[0].vertices, (std::vector<int>{0, 4}));
  EXPECT_EQ(c.attachments[1].kind, Attachment::Kind::Handle);
  EXPECT_EQ(c.attachments[1].stiffness, 500.0);
  EXPECT_EQ(c.attachments[1].trajectory.offset(0.5), Vec3(0, 0.25, 0));
}

TEST(SceneLoader, SeveralClothsKeepLocalIndicesAndSceneOrder) {
  nlohmann::json doc = test::gridScene(1.0, 2, 0.01, 1);
  nlohmann::json second = doc["cloths"][0];
  second["mesh"]["grid"]["resolution"] = {3, 1};
  second["mesh"]["transform"] = {{"translate", {0, 2, 0}}};
  second["attachments"] = {{{"vertices", {7}}}};  // valid only in the second cloth (8 vertices)
  doc["cloths"].push_back(second);
  const Scene s = test::parse(doc);
  ASSERT_EQ(s.cloths.size(), 2u);
  EXPECT_EQ(s.cloths[0].mesh.vertexCount(), 9);
  EXPECT_EQ(s.cloths[1].mesh.vertexCount(), 8);
  EXPECT_EQ(s.vertexCount(), 17);
  EXPECT_EQ(s.cloths[1].attachments[0].vertices, std::vector<int>{7});
  EXPECT_DOUBLE_EQ(s.cloths[1].mesh.vertices(7, 1), 2.0);

  doc["cloths"][0]["attachments"] = {{{"vertices", {9}}}};  // out of range for the first
  expectInputError([&] { test::parse(doc); }, "cloths.0.attachments.0.vertices.0", "out of range");
}

// A pin group's name (the editor's) is text; the simulation never reads it.
TEST(SceneLoader, AnAttachmentMayBeNamedWithText) {
  nlohmann::json doc = test::hangingClothScene(1.0, 2, 0.01, 3, 100.0);
  doc["cloths"][0]["attachments"][0]["name"] = "shoulders";
  EXPECT_EQ(test::parse(doc).cloths[0].attachments[0].vertices, (std::vector<int>{0, 2}));
  doc["cloths"][0]["attachments"][0]["name"] = 5;
  expectInputError([&] { test::parse(doc); }, "cloths.0.attachments.0.name", "string");
}

TEST(SceneLoader, MeshFileIsScaledBeforeItIsTransformed) {
  TempDir dir;
  dir.write("tri.obj", "v 1 0 0\nv 2 0 0\nv 1 0 1\nf 1 3 2\n");
  nlohmann::json doc = test::gridScene(1.0, 1, 0.01, 1);
  doc["cloths"][0]["mesh"] = {
      {"file", "tri.obj"},
      {"scale", 2.0},
      {"transform", {{"translate", {1, 0, 0}}, {"rotate_deg", {0, 0, 90}}}}};
  const std::string file = test::writeScene(dir.file("scene.json"), doc);
  const Scene s = loadScene(file);
  const TriangleMesh& m = s.cloths[0].mesh;
  ASSERT_EQ(m.vertexCount(), 3);
  // (1,0,0) -> scale (2,0,0) -> rotate Z 90 (0,2,0) -> translate (1,2,0).
  EXPECT_NEAR((m.vertices.row(0) - Eigen::RowVector3d(1, 2, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.vertices.row(1) - Eigen::RowVector3d(1, 4, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.vertices.row(2) - Eigen::RowVector3d(1, 2, 2)).norm(), 0.0, 1e-15);
}

TEST(SceneLoader, RelativeMeshPathsResolveAgainstTheSceneFolder) {
  TempDir dir;
  dir.write("meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n");
  nlohmann::json doc = test::gridScene(1.0, 1, 0.01, 1);
  doc["cloths"][0]["mesh"] = {{"file", "../meshes/tri.obj"}};
  const std::string file = dir.write("scenes/scene.json", doc.dump(2));
  EXPECT_EQ(loadScene(file).cloths[0].mesh.vertexCount(), 3);
}

TEST(SceneLoader, RepairDropsDegenerateTrianglesWithAWarning) {
  TempDir dir;
  // Triangle 1 is collinear (vertices 0, 1, 4 on the X axis).
  dir.write("mesh.obj",
            "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 2 0 0\nf 1 3 2\nf 1 2 5\nf 1 4 3\nf 2 3 5\n");
  nlohmann::json doc = test::gridScene(1.0, 1, 0.01, 1);
  doc["cloths"][0]["mesh"] = {{"file", "mesh.obj"}};
  const std::string file = test::writeScene(dir.file("scene.json"), doc);
  expectInputError([&] { loadScene(file); }, "cloths.0.mesh",
                   "degenerate (zero-area) triangles 1 (1)");

  doc["cloths"][0]["mesh"]["repair"] = true;
  test::writeScene(file, doc);
  const Scene s = loadScene(file);
  EXPECT_EQ(s.cloths[0].mesh.vertexCount(), 5);  // order and count kept
  EXPECT_EQ(s.cloths[0].mesh.triangleCount(), 3);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("dropped degenerate triangles 1 (1)"), std::string::npos)
      << s.warnings[0];
}

TEST(SceneLoader, NonManifoldMeshLoadsWithAWarningNamingTheEdge) {
  TempDir dir;
  dir.write("fin.obj",
            "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.5 1 0.5\nf 1 3 2\nf 1 4 3\nf 1 3 5\n");
  nlohmann::json doc = test::gridScene(1.0, 1, 0.01, 1);
  doc["cloths"][0]["mesh"] = {{"file", "fin.obj"}};
  const Scene s = loadScene(test::writeScene(dir.file("scene.json"), doc));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("non-manifold edges (vertex pairs 2 (0, 2))"), std::string::npos)
      << s.warnings[0];
}

TEST(SceneLoader, OverridesSetScalarsAndVectorsByPath) {
  TempDir dir;
  nlohmann::json doc = test::hangingClothScene(1.0, 2, 0.01, 10, 100.0);
  doc["wind"] = {{"direction", {1, 0, 0}}, {"strength", 1.0}};
  const std::string file = test::writeScene(dir.file("scene.json"), doc);
  const Scene s = loadScene(file, {{"time.dt", "0.005"},
                                   {"gravity", "[0, 0, -1]"},
                                   {"wind.direction", "0,1,0"},
                                   {"cloths.0.material.stretch", "7.5"},
                                   {"cloths.0.attachments.0.vertices.1", "1"},
                                   {"wind.phase", "0.25"}});  // a key the file omits
  EXPECT_EQ(s.time.dt, 0.005);
  EXPECT_EQ(*s.gravity, Vec3(0, 0, -1));
  EXPECT_EQ(s.wind->direction, Vec3(0, 1, 0));
  EXPECT_EQ(s.cloths[0].material.stretch, 7.5);
  EXPECT_EQ(s.cloths[0].attachments[0].vertices, (std::vector<int>{0, 1}));
  EXPECT_EQ(s.wind->phase, 0.25);
  // The document records the overrides, so a run folder's scene.json replays the same run.
  EXPECT_EQ(s.document["time"]["dt"], 0.005);
}

TEST(SceneLoader, BadOverridesNameTheOption) {
  TempDir dir;
  const std::string file =
      test::writeScene(dir.file("scene.json"), test::hangingClothScene(1.0, 2, 0.01, 10, 100.0));
  expectInputError(
      [&] {
        loadScene(file, {{"cloths.0.materia.stretch", "1"}});
      },
      "--set cloths.0.materia.stretch", "unknown path");
  expectInputError(
      [&] {
        loadScene(file, {{"cloths.3.material.stretch", "1"}});
      },
      "--set cloths.3.material.stretch", "unknown path");
  expectInputError(
      [&] {
        loadScene(file, {{"cloths.0.material.stiffness", "1"}});
      },
      "--set cloths.0.material.stiffness", "unknown key");
  expectInputError(
      [&] {
        loadScene(file, {{"time.dt", "fast"}});
      },
      "--set time.dt", "must be a number");
  expectInputError(
      [&] {
        loadScene(file, {{"gravity", "[0, -9.8]"}});
      },
      "--set gravity", "must be an array of 3 values");
  expectInputError(
      [&] {
        loadScene(file, {{"cloths.0.material", "5"}});
      },
      "--set cloths.0.material", "not a scalar or vector");
  // A value of the right type is still validated like the file's own values.
  expectInputError([&] { loadScene(file, {{"time.dt", "-1"}}); }, "time.dt", "must be > 0");
  // Bytes that are not UTF-8 (found by the scene fuzzer: writing the value into the message, or
  // the scene into a run folder, threw nlohmann's type_error instead of an InputError).
  expectInputError(
      [&] {
        loadScene(file, {{"cloths.0.material.stretch", "1e\xFA"}});
      },
      "--set cloths.0.material.stretch", "not valid UTF-8");
  expectInputError(
      [&] {
        loadScene(file, {{"name\xC3", "x"}});
      },
      "--set name\xC3", "not valid UTF-8");
  expectInputError(
      [&] {
        loadScene(file, {{"name", "caf\xC3\xA9\xFF"}});
      },
      "--set name", "not valid UTF-8");
  EXPECT_EQ(loadScene(file, {{"name", "caf\xC3\xA9"}}).document["name"], "caf\xC3\xA9");
  // An override on a file that is not an object (found by the scene fuzzer: naming the parent
  // of a one-part path read before the start of the path's parts).
  dir.write("number.json", "5");
  expectInputError(
      [&] {
        loadScene(dir.file("number.json"), {{"name", "x"}});
      },
      "--set name", "unknown path (the document is not an object or array)");
}

TEST(SceneLoader, DocumentWithOverridesIsTheFileWithOverrides) {
  TempDir dir;
  nlohmann::json doc = test::hangingClothScene(1.0, 2, 0.01, 10, 100.0);
  doc["wind"] = {{"direction", {1, 0, 0}}, {"strength", 1.0}};
  const std::string file = test::writeScene(dir.file("scene.json"), doc);
  const std::vector<SceneOverride> overrides = {{"time.dt", "0.005"}, {"wind.phase", "0.25"}};
  const Scene fromFile = loadScene(file, overrides);
  const Scene fromDocument = loadSceneDocument(doc, "<dict>", ".", overrides);
  EXPECT_EQ(fromDocument.document, fromFile.document);
  EXPECT_EQ(fromDocument.file, "<dict>");
  EXPECT_EQ(fromDocument.time.dt, 0.005);
  EXPECT_EQ(fromDocument.wind->phase, 0.25);
  // Errors name the document as the file, and the option that wrote an unknown key.
  try {
    loadSceneDocument(doc, "<dict>", ".", {{"cloths.0.material.stiffness", "1"}});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "<dict>");
    EXPECT_EQ(e.path(), "--set cloths.0.material.stiffness");
  }
}

TEST(SceneLoader, OverrideTextSplitsAtTheFirstEquals) {
  const SceneOverride o = parseSceneOverride("task.loss.hemline.height=a=b", "scene.json");
  EXPECT_EQ(o.path, "task.loss.hemline.height");
  EXPECT_EQ(o.value, "a=b");
  EXPECT_EQ(parseSceneOverride("gravity=", "scene.json").value, "");
  for (const std::string bad : {"gravity", "=1", ""}) {
    try {
      parseSceneOverride(bad, "scene.json");
      ADD_FAILURE() << "no error for '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "scene.json: --set: expects PATH=VALUE, got '" + bad + "'");
    }
  }
}

TEST(SceneLoader, ErrorsNameTheJsonPath) {
  const nlohmann::json good = test::hangingClothScene(1.0, 2, 0.01, 10, 100.0);
  auto with = [&](const std::string& pointer, const nlohmann::json& value) {
    nlohmann::json d = good;
    d[nlohmann::json::json_pointer(pointer)] = value;
    return d;
  };
  expectInputError([&] { test::parse(with("/cloths/0/material/densty", 1)); },
                   "cloths.0.material.densty", "unknown key");
  expectInputError([&] { test::parse(with("/time/steps", 2.5)); }, "time.steps",
                   "must be an integer");
  expectInputError([&] { test::parse(with("/cloths/0/attachments/0/kind", "glued")); },
                   "cloths.0.attachments.0.kind", "must be one of fixed, handle");
  expectInputError([&] { test::parse(with("/solver/pd_tolerance", 0)); }, "solver.pd_tolerance",
                   "must be > 0");
  expectInputError([&] { test::parse(with("/solver/backward/preconditioner", "jacobi")); },
                   "solver.backward.preconditioner", "must be one of auto, p, hessian");
  EXPECT_EQ(test::parse(with("/solver/backward/preconditioner", "hessian"))
                .solver.backward.preconditioner,
            "hessian");
  expectInputError([&] { test::parse(with("/solver/backward/history", -1)); },
                   "solver.backward.history", "must be an integer in [0, 64]");
  EXPECT_EQ(test::parse(with("/solver/backward/history", 0)).solver.backward.history, 0);
  expectInputError([&] { test::parse(with("/cloths/0/material/bend_model", "signed")); },
                   "cloths.0.material.bend_model", "must be one of magnitude, oriented");
  EXPECT_EQ(test::parse(good).cloths[0].material.bendModel, Material::BendModel::Magnitude);
  EXPECT_EQ(
      test::parse(with("/cloths/0/material/bend_model", "oriented")).cloths[0].material.bendModel,
      Material::BendModel::Oriented);
  EXPECT_EQ(test::parse(good).solver.backward.history, 8);
  expectInputError(
      [&] { test::parse(with("/cloths/0/mesh/grid/size", nlohmann::json::array({1.0}))); },
      "cloths.0.mesh.grid.size", "must be [extent X, extent Z]");
  expectInputError([&] { test::parse(with("/cloths", nlohmann::json::array())); }, "cloths",
                   "needs at least one cloth");
  nlohmann::json noTime = good;
  noTime.erase("time");
  expectInputError([&] { test::parse(noTime); }, "<root>", "missing required key 'time'");
}

// self_collision.model picks DiffCloth's node-node contacts ("node", the default), Liang et al.'s
// impact zones ("impact_zones"), or both; each model's keys are refused without it.
TEST(SceneLoader, SelfCollisionModelsAndTheirKeys) {
  const nlohmann::json good = test::hangingClothScene(1.0, 2, 0.01, 10, 100.0);
  auto with = [&](const nlohmann::json& selfCollision) {
    nlohmann::json d = good;
    d["cloths"][0]["self_collision"] = selfCollision;
    return test::parse(d);
  };
  const Scene node = with({{"radius", 0.004}});
  ASSERT_TRUE(node.cloths[0].selfCollision);
  EXPECT_TRUE(node.cloths[0].selfCollision->nodeModel);
  EXPECT_FALSE(node.cloths[0].selfCollision->impactZones);
  EXPECT_TRUE(node.hasSelfCollision());
  EXPECT_FALSE(node.hasImpactZones());

  const Scene zones = with({{"model", "impact_zones"}, {"thickness", 0.002}});
  EXPECT_FALSE(zones.cloths[0].selfCollision->nodeModel);
  EXPECT_TRUE(zones.cloths[0].selfCollision->impactZones);
  EXPECT_EQ(zones.cloths[0].selfCollision->thickness, 0.002);
  EXPECT_FALSE(zones.hasSelfCollision());  // no node contacts: no contact solve for it
  EXPECT_TRUE(zones.hasImpactZones());
  EXPECT_EQ(with({{"model", "impact_zones"}}).cloths[0].selfCollision->thickness,
            SelfCollision{}.thickness);

  const Scene both =
      with({{"model", {"node", "impact_zones"}}, {"radius", 0.005}, {"thickness", 0.001}});
  EXPECT_TRUE(both.hasSelfCollision());
  EXPECT_TRUE(both.hasImpactZones());
  EXPECT_EQ(both.cloths[0].selfCollision->radius, 0.005);

  expectInputError(
      [&] {
        with({{"model", "ccd"}});
      },
      "cloths.0.self_collision.model", "must be one of node, impact_zones");
  expectInputError(
      [&] {
        with({{"model", nlohmann::json::array()}});
      },
      "cloths.0.self_collision.model", "an empty list");
  expectInputError(
      [&] {
        with({{"model", {"node", "node"}}, {"radius", 0.004}});
      },
      "cloths.0.self_collision.model", "named twice");
  expectInputError(
      [&] {
        with({{"model", "impact_zones"}, {"radius", 0.004}});
      },
      "cloths.0.self_collision.radius", "only by the \"node\" model");
  expectInputError(
      [&] {
        with({{"radius", 0.004}, {"thickness", 0.001}});
      },
      "cloths.0.self_collision.thickness", "only by the \"impact_zones\" model");
  expectInputError(
      [&] {
        with({{"model", "impact_zones"}, {"thickness", 0}});
      },
      "cloths.0.self_collision.thickness", "must be > 0");
}

TEST(SceneLoader, TaskParametersMustNameNumbersInTheScene) {
  nlohmann::json doc = test::hangingClothScene(1.0, 2, 0.01, 10, 100.0);
  doc["task"] = {{"loss", {{"trajectory", {{"target", "run/positions.npy"}}}}},
                 {"parameters", {"cloths.0.material.stretch"}}};
  EXPECT_EQ(test::parse(doc).task->parameters,
            std::vector<std::string>{"cloths.0.material.stretch"});
  doc["task"]["parameters"] = {"cloths.0.material.friction"};
  expectInputError([&] { test::parse(doc); }, "task.parameters.0", "names no value");
  doc["task"]["parameters"] = {"cloths.0.mesh"};
  expectInputError([&] { test::parse(doc); }, "task.parameters.0", "is not a number");
}

}  // namespace
}  // namespace weft
