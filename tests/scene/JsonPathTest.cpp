// Dotted JSON paths: the addressing of --set, task parameters and error messages.

#include <weft/scene/JsonPath.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

const nlohmann::json kDoc = nlohmann::json::parse(R"({
  "time": {"dt": 0.01},
  "gravity": [0, -9.8, 0],
  "obstacles": [{"friction": 0.3}, {"friction": 0.5, "sphere": {"radius": 1}}],
  "name": "x"
})");

TEST(JsonPath, SplitsOnDots) {
  EXPECT_EQ(splitJsonPath("obstacles.1.friction"),
            (std::vector<std::string>{"obstacles", "1", "friction"}));
  EXPECT_EQ(splitJsonPath("gravity"), std::vector<std::string>{"gravity"});
}

TEST(JsonPath, FindsObjectKeysAndArrayIndices) {
  ASSERT_NE(findJsonPath(kDoc, "obstacles.1.friction"), nullptr);
  EXPECT_EQ(*findJsonPath(kDoc, "obstacles.1.friction"), 0.5);
  EXPECT_EQ(*findJsonPath(kDoc, "gravity.1"), -9.8);
  EXPECT_EQ(*findJsonPath(kDoc, "obstacles.1.sphere.radius"), 1);
  EXPECT_EQ(findJsonPath(kDoc, "obstacles.2.friction"), nullptr);
  EXPECT_EQ(findJsonPath(kDoc, "obstacles.x"), nullptr);
  EXPECT_EQ(findJsonPath(kDoc, "time.dt.more"), nullptr);
  EXPECT_EQ(findJsonPath(kDoc, "wind"), nullptr);
}

TEST(JsonPath, ParsesOverrideValues) {
  EXPECT_EQ(parseOverrideValue("0.2"), 0.2);
  EXPECT_EQ(parseOverrideValue("[0,-9.8,0]"), nlohmann::json::array({0, -9.8, 0}));
  EXPECT_EQ(parseOverrideValue("0,-9.8,0"), nlohmann::json::array({0, -9.8, 0}));
  EXPECT_EQ(parseOverrideValue("true"), true);
  EXPECT_EQ(parseOverrideValue("\"text\""), "text");
  EXPECT_EQ(parseOverrideValue("plain"), "plain");
  EXPECT_EQ(parseOverrideValue("a,b"), "a,b");  // not all numbers: a string
}

TEST(JsonPath, SetReplacesScalarsAndSameLengthVectors) {
  nlohmann::json doc = kDoc;
  EXPECT_EQ(setJsonPath(doc, "time.dt", 0.005), "");
  EXPECT_EQ(doc["time"]["dt"], 0.005);
  EXPECT_EQ(setJsonPath(doc, "gravity", nlohmann::json::array({0, 0, 0})), "");
  EXPECT_EQ(doc["gravity"], nlohmann::json::array({0, 0, 0}));
  EXPECT_EQ(setJsonPath(doc, "gravity.2", 1.5), "");
  EXPECT_EQ(doc["gravity"][2], 1.5);
  EXPECT_EQ(setJsonPath(doc, "obstacles.0.friction", 0.2), "");
  EXPECT_EQ(doc["obstacles"][0]["friction"], 0.2);
  // A key the file omitted is created; the scene validator decides whether it is known.
  EXPECT_EQ(setJsonPath(doc, "time.steps", 10), "");
  EXPECT_EQ(doc["time"]["steps"], 10);
}

TEST(JsonPath, SetRejectsUnknownPathsAndTypeChanges) {
  nlohmann::json doc = kDoc;
  EXPECT_NE(setJsonPath(doc, "tim.dt", 1), "");
  EXPECT_NE(setJsonPath(doc, "obstacles.5.friction", 1), "");
  EXPECT_NE(setJsonPath(doc, "gravity.3", 1), "");
  EXPECT_NE(setJsonPath(doc, "time.dt", "fast"), "");
  EXPECT_NE(setJsonPath(doc, "gravity", nlohmann::json::array({0, 0})), "");
  EXPECT_NE(setJsonPath(doc, "gravity", 1), "");
  EXPECT_NE(setJsonPath(doc, "time", 1), "");
  EXPECT_NE(setJsonPath(doc, "", 1), "");
  EXPECT_NE(setJsonPath(doc, "time..dt", 1), "");
  EXPECT_EQ(doc, kDoc) << "a rejected override must not change the document";
}

}  // namespace
}  // namespace weft
