// Bad input through the real binary: every malformed scene, mesh or option exits 2 with
// `error: <file>: <json path or option>: <what>` naming the problem, writes nothing, and never
// touches an existing output folder.

#include "CliSupport.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace weft {
namespace {

using test::dataFile;
using test::describe;
using test::readFile;
using test::runWeft;
using test::TempDir;

struct BadCase {
  const char* name;
  const char* scene;              // under tests/data; the good scene for option errors
  std::vector<std::string> args;  // extra options
  const char* path;               // JSON path or option the message must name
  const char* phrase;             // what the message must say
  const char* file = nullptr;     // the file the message names, if not the scene
};

void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

const char* kGood = "scenes/hanging.json";

const BadCase kCases[] = {
    // Scene structure and values.
    {"UnknownKey", "bad/unknown_key.json", {}, "gravty", "unknown key (expected one of: name,"},
    {"MissingDt", "bad/missing_dt.json", {}, "time", "missing required key 'dt'"},
    {"VertexIndexOutOfRange",
     "bad/vertex_out_of_range.json",
     {},
     "cloths.0.attachments.0.vertices.1",
     "vertex index 25 out of range: the mesh has 25 vertices"},
    {"NegativeDensity",
     "bad/negative_density.json",
     {},
     "cloths.0.material.density",
     "must be > 0, got -0.1"},
    {"WrongVectorLength",
     "bad/wrong_vector_length.json",
     {},
     "gravity",
     "must be an array of 3 numbers"},
    {"NotANumber",
     "bad/not_a_number.json",
     {},
     "cloths.0.material.stretch",
     "must be a number, got \"stiff\""},
    {"BadJson", "bad/bad_json.json", {}, "<json>", "invalid JSON at line 4, column"},
    {"EmptyFile", "bad/empty_file.json", {}, "<json>", "invalid JSON at line 1, column 1"},
    {"OverflowingNumber",
     "bad/overflowing_number.json",
     {},
     "<json>",
     "invalid JSON at line 45, column 20: number overflow parsing '1e999'"},
    {"RootNotAnObject", "bad/root_not_object.json", {}, "<root>", "must be an object"},
    {"NoCloths", "bad/no_cloths.json", {}, "cloths", "needs at least one cloth"},
    {"TimeStepTooLarge", "bad/time_step_too_large.json", {}, "time.dt", "must be at most 1 s"},
    {"NegativeSteps",
     "bad/negative_steps.json",
     {},
     "time.steps",
     "must be an integer in [0, 10000000], got -5"},
    {"ZeroGridResolution",
     "bad/zero_resolution.json",
     {},
     "cloths.0.mesh.grid.resolution.0",
     "must be an integer in [1, 4096], got 0"},
    {"GridAndFile", "bad/grid_and_file.json", {}, "cloths.0.mesh", "has both 'grid' and 'file'"},
    {"ZeroWindDirection",
     "bad/zero_wind_direction.json",
     {},
     "wind.direction",
     "must be a nonzero vector"},
    {"HandleWithoutTrajectory",
     "bad/handle_without_trajectory.json",
     {},
     "cloths.0.attachments.0",
     "missing required key 'trajectory'"},
    {"FixedWithTrajectory",
     "bad/fixed_with_trajectory.json",
     {},
     "cloths.0.attachments.0.trajectory",
     "only a 'handle' attachment moves"},
    {"NonIncreasingKeyframeTimes",
     "bad/keyframes_not_increasing.json",
     {},
     "cloths.0.attachments.0.trajectory.keyframes",
     "times must be strictly increasing"},
    {"HermiteMissingTangent",
     "bad/hermite_missing_tangent.json",
     {},
     "cloths.0.attachments.0.trajectory.hermite.tangents",
     "needs one tangent per time (3)"},
    // Meshes.
    {"MissingMeshFile", "bad/missing_mesh_file.json", {}, "cloths.0.mesh.file", "no such file"},
    {"DegenerateTriangles",
     "bad/degenerate_triangles.json",
     {},
     "cloths.0.mesh",
     "degenerate (zero-area) triangles 1 (1)"},
    {"UnreferencedVertices",
     "bad/unreferenced_vertices.json",
     {},
     "cloths.0.mesh",
     "vertices in no triangle 1 (2)"},
    {"FaceIndexOutOfRange",
     "bad/face_index_out_of_range.json",
     {},
     "cloths.0.mesh",
     "triangles with out-of-range or repeated vertex indices: 1 (0)"},
    {"UnparsableCoordinate",
     "bad/bad_coordinate.json",
     {},
     "cloths.0.mesh.file",
     "line 3: vertex coordinate 'abc' is not a finite number"},
    {"GarbledPlyHeader",
     "bad/unreadable_ply.json",
     {},
     "cloths.0.mesh.file",
     "PLY: header line 5: unknown keyword 'this'"},
    // Debian's assimp 5.2 dies on this FBX file; it runs in a child process (AssimpReader.h).
    {"MeshThatCrashesAssimp",
     "bad/assimp_crash.json",
     {},
     "cloths.0.mesh.file",
     "cannot read mesh: assimp's reader "},
    // Options.
    {"SetUnknownPath",
     kGood,
     {"--set", "cloths.0.materia.stretch=5"},
     "--set cloths.0.materia.stretch",
     "unknown path"},
    {"SetUnknownKey", kGood, {"--set", "time.dtt=0.1"}, "--set time.dtt", "unknown key"},
    {"SetIndexOutOfRange",
     kGood,
     {"--set", "cloths.1.material.stretch=5"},
     "--set cloths.1.material.stretch",
     "unknown path"},
    {"SetNonNumber", kGood, {"--set", "time.dt=fast"}, "--set time.dt", "must be a number"},
    {"SetWrongVectorLength",
     kGood,
     {"--set", "gravity=[0,-9.8]"},
     "--set gravity",
     "must be an array of 3 values"},
    {"SetWithoutValue", kGood, {"--set", "time.dt"}, "--set", "expects PATH=VALUE"},
    {"SetValueOutOfRange", kGood, {"--set", "time.dt=-0.01"}, "time.dt", "must be > 0"},
    {"StepsNotANumber", kGood, {"--steps", "ten"}, "--steps", "must be an integer"},
    {"StepsNegative", kGood, {"--steps", "-3"}, "--steps", "must be an integer in [0,"},
    // Options are parsed before the scene is known, so this one names the program.
    {"UnknownOption", kGood, {"--stepz", "3"}, "--stepz", "unknown option", "weft"},
    {"MissingSceneFile", "bad/no_such_scene.json", {}, "<file>", "cannot open scene file"},
    {"TwoScenes", kGood, {"second.json"}, "SCENE", "exactly one scene file", "weft"},
};

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, ExitsTwoWithAUsefulMessageAndWritesNothing) {
  const BadCase& c = GetParam();
  TempDir dir;
  const std::string scene = dataFile(c.scene);
  const std::string out = dir.file("out");
  std::vector<std::string> args{"simulate", scene, "--out", out};
  args.insert(args.end(), c.args.begin(), c.args.end());
  const test::ProcessResult r = runWeft(args);
  EXPECT_EQ(r.exitCode, 2) << describe(r);
  EXPECT_EQ(r.signal, 0) << describe(r);
  const std::string file = c.file ? c.file : scene;
  const std::string prefix = "error: " + file + ": " + c.path + ": ";
  EXPECT_THAT(r.err, ::testing::StartsWith(prefix)) << describe(r);
  EXPECT_NE(r.err.find(c.phrase), std::string::npos) << "expected \"" << c.phrase << "\"\n"
                                                     << describe(r);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line\n" << describe(r);
  EXPECT_TRUE(r.out.empty()) << describe(r);
  EXPECT_TRUE(fs::is_empty(dir.path())) << "a failed run left files in " << dir.path();
}

INSTANTIATE_TEST_SUITE_P(Cases, BadInput, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return std::string(info.param.name);
                         });

// An existing output folder survives a failing run untouched: a run that fails while loading,
// one that fails in the middle of simulating (after the staging folder exists), and a usage error.
TEST(BadInputOutputFolder, ExistingOutputIsUntouchedByAFailingRun) {
  TempDir dir;
  const std::string out = dir.file("results");
  dir.write("results/sentinel.txt", "keep me");
  dir.write("results/positions.npy", "an older run's data");
  // A scene that loads, starts writing into a staging folder, and blows up at step 1.
  const std::string blowUp = dir.write("blowup.json",
                                       R"({"time": {"dt": 0.01, "steps": 5},
          "cloths": [{"mesh": {"grid": {"size": [0.4, 0.4], "resolution": [2, 2]}},
                      "material": {"density": 0.1, "stretch": 100},
                      "initial_velocity": [1e6, 0, 0]}]})");
  const std::vector<std::vector<std::string>> runs = {
      {"simulate", dataFile("bad/negative_density.json"), "--out", out},
      {"simulate", dataFile("bad/degenerate_triangles.json"), "--out", out},
      {"simulate", blowUp, "--out", out},
      {"simulate", dataFile(kGood), "--out", out, "--set", "time.dtt=1"},
      {"simulate", dataFile(kGood), "--out", out, "--steps", "x"},
  };
  for (const auto& args : runs) {
    const test::ProcessResult r = runWeft(args);
    EXPECT_NE(r.exitCode, 0) << describe(r);
    EXPECT_TRUE(r.exitCode == 2 || r.exitCode == 3) << describe(r);
    EXPECT_EQ(readFile(out + "/sentinel.txt"), "keep me") << args[1];
    EXPECT_EQ(readFile(out + "/positions.npy"), "an older run's data") << args[1];
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(out)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"positions.npy", "sentinel.txt"})) << args[1];
    std::vector<std::string> siblings;
    for (const auto& e : fs::directory_iterator(dir.path()))
      siblings.push_back(e.path().filename().string());
    std::sort(siblings.begin(), siblings.end());
    EXPECT_EQ(siblings, (std::vector<std::string>{"blowup.json", "results"}))
        << "stray .tmp-* folder after " << args[1];
  }
}

}  // namespace
}  // namespace weft
