// The Scene panel's self-collision choice: every switch between none, the node model, impact
// zones and both leaves a document that the real loader validates, with the model the choice
// names, and keeps the values the two choices share.

#include <EditorDocument.h>
#include <SelfCollisionChoice.h>

#include "support/SceneBuilder.h"

#include <gtest/gtest.h>

namespace weft::editor {
namespace {

constexpr SelfCollisionChoice kChoices[] = {SelfCollisionChoice::None, SelfCollisionChoice::Node,
                                            SelfCollisionChoice::ImpactZones,
                                            SelfCollisionChoice::Both};

TEST(EditorSelfCollisionChoice, EverySwitchValidatesWithTheNamedModel) {
  for (SelfCollisionChoice from : kChoices)
    for (SelfCollisionChoice to : kChoices) {
      EditorDocument doc(test::hangingClothScene(1.0, 4, 0.01, 10, 100.0));
      const std::string path = "cloths.0.self_collision";
      ASSERT_EQ(chooseSelfCollision(doc, 0, from), "");
      ASSERT_EQ(chooseSelfCollision(doc, 0, to), "") << int(from) << " -> " << int(to);
      ASSERT_TRUE(doc.valid()) << doc.validationError();
      EXPECT_EQ(selfCollisionChoice(doc.find(path)), to) << int(from) << " -> " << int(to);
      const auto& self = doc.scene()->cloths[0].selfCollision;
      ASSERT_EQ(self.has_value(), to != SelfCollisionChoice::None);
      if (self) {
        EXPECT_EQ(self->nodeModel, to != SelfCollisionChoice::ImpactZones);
        EXPECT_EQ(self->impactZones, to != SelfCollisionChoice::Node);
      }
      // One undo step back to `from`.
      if (from != to) {
        ASSERT_TRUE(doc.undo());
        EXPECT_EQ(selfCollisionChoice(doc.find(path)), from);
      }
    }
}

TEST(EditorSelfCollisionChoice, SharedValuesAreKept) {
  const nlohmann::json both = {{"model", {"node", "impact_zones"}},
                               {"radius", 0.006},
                               {"friction", 0.1},
                               {"thickness", 0.002}};
  EXPECT_EQ(selfCollisionChoice(&both), SelfCollisionChoice::Both);
  const nlohmann::json zones = selfCollisionFor(SelfCollisionChoice::ImpactZones, &both);
  EXPECT_EQ(zones, nlohmann::json({{"model", "impact_zones"}, {"thickness", 0.002}}));
  const nlohmann::json node = selfCollisionFor(SelfCollisionChoice::Node, &both);
  EXPECT_EQ(node, nlohmann::json({{"radius", 0.006}, {"friction", 0.1}}));
  // Back to both from impact zones alone: the node model's values are the defaults again.
  const nlohmann::json again = selfCollisionFor(SelfCollisionChoice::Both, &zones);
  EXPECT_DOUBLE_EQ(again["thickness"].get<double>(), 0.002);
  EXPECT_DOUBLE_EQ(again["radius"].get<double>(), 0.004);
  // A value without "model" is the node model, as in the scene format.
  const nlohmann::json plain = {{"radius", 0.004}};
  EXPECT_EQ(selfCollisionChoice(&plain), SelfCollisionChoice::Node);
  EXPECT_EQ(selfCollisionChoice(nullptr), SelfCollisionChoice::None);
}

}  // namespace
}  // namespace weft::editor
