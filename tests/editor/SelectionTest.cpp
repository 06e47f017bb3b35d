// Picking and box selection against a flat square seen head-on, and pinning a selection into
// the document as per-cloth fixed attachments.

#include <EditorSession.h>
#include <Selection.h>

#include "support/SceneBuilder.h"

#include <gtest/gtest.h>

namespace weft::editor {
namespace {

// A 2 x 2 quad square in the plane z = 0, side 1 m centred at the origin; vertex (i, j) at
// index 3j + i, x = i/2 - 0.5, y = j/2 - 0.5.
render::SurfaceMesh square() {
  render::SurfaceMesh m;
  m.positions.resize(9, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      m.positions.row(3 * j + i) << i * 0.5f - 0.5f, j * 0.5f - 0.5f, 0.0f;
  m.triangles.resize(8, 3);
  int t = 0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 3 * j + i;
      m.triangles.row(t++) << a, a + 1, a + 4;
      m.triangles.row(t++) << a, a + 4, a + 3;
    }
  return m;
}

render::Camera front() {
  render::Camera c;  // on +Z looking at the origin
  c.distance = 3.0f;
  return c;
}

TEST(Picking, CentrePixelRayHitsTheCentreVertex) {
  const Ray ray = pixelRay(front(), 100.0f, 50.0f, 200, 100);
  EXPECT_NEAR(ray.direction.z(), -1.0f, 1e-5f);
  EXPECT_NEAR(ray.origin.x(), 0.0f, 1e-5f);
  const auto v = pickVertex(square(), ray);
  ASSERT_TRUE(v);
  EXPECT_EQ(*v, 4);
}

TEST(Picking, ProjectionAndRayAgree) {
  const render::Camera c = front();
  const render::SurfaceMesh m = square();
  for (int v = 0; v < 9; ++v) {
    const auto pixel = projectToPixel(c, m.positions.row(v).transpose(), 320, 240);
    ASSERT_TRUE(pixel);
    // Nudge towards the centre so the ray lands inside the mesh, near vertex v.
    const Eigen::Vector2f inward = (Eigen::Vector2f(160, 120) - *pixel) * 0.02f;
    const auto picked =
        pickVertex(m, pixelRay(c, pixel->x() + inward.x(), pixel->y() + inward.y(), 320, 240));
    ASSERT_TRUE(picked) << "vertex " << v;
    EXPECT_EQ(*picked, v);
  }
  // Top-left vertex (x -0.5, y +0.5) appears left of and above the centre.
  const auto topLeft = projectToPixel(c, m.positions.row(6).transpose(), 320, 240);
  EXPECT_LT(topLeft->x(), 160.0f);
  EXPECT_LT(topLeft->y(), 120.0f);
}

TEST(Picking, MissReturnsNothing) {
  EXPECT_FALSE(pickVertex(square(), pixelRay(front(), 2.0f, 2.0f, 320, 240)));
}

TEST(BoxSelect, SelectsVerticesInsideTheRectangleInAnyCornerOrder) {
  const render::Camera c = front();
  const render::SurfaceMesh m = square();
  // The left column (x = -0.5): from above the top-left to below the bottom-left vertex.
  const auto top = *projectToPixel(c, m.positions.row(6).transpose(), 320, 240);
  const auto bottom = *projectToPixel(c, m.positions.row(0).transpose(), 320, 240);
  const Eigen::Vector2f pad(5, 5);
  EXPECT_EQ(boxSelect(m, c, top - pad, bottom + pad, 320, 240), (std::vector<int>{0, 3, 6}));
  EXPECT_EQ(boxSelect(m, c, bottom + pad, top - pad, 320, 240), (std::vector<int>{0, 3, 6}));
  EXPECT_EQ(boxSelect(m, c, {0, 0}, {320, 240}, 320, 240).size(), 9u);
  EXPECT_TRUE(boxSelect(m, c, {0, 0}, {3, 3}, 320, 240).empty());
}

TEST(Selection, SortedUniqueAddAndToggle) {
  Selection s;
  s.set({5, 1, 5, 3});
  EXPECT_EQ(s.nodes(), (std::vector<int>{1, 3, 5}));
  s.add({2, 3});
  EXPECT_EQ(s.nodes(), (std::vector<int>{1, 2, 3, 5}));
  s.toggle(3);
  s.toggle(4);
  EXPECT_EQ(s.nodes(), (std::vector<int>{1, 2, 4, 5}));
  EXPECT_TRUE(s.contains(4));
  s.clear();
  EXPECT_TRUE(s.empty());
}

TEST(PinSelection, AddsOneFixedAttachmentPerClothWithLocalIndices) {
  nlohmann::json doc = test::gridScene(1.0, 2, 0.01, 5);
  doc["cloths"].push_back(doc["cloths"][0]);  // two cloths of 9 vertices each
  doc["cloths"][1].erase("attachments");
  addFixedAttachments(doc, {1, 0, 10, 17}, {0, 9, 18});
  ASSERT_TRUE(doc["cloths"][0].contains("attachments"));
  const nlohmann::json& a0 = doc["cloths"][0]["attachments"].back();
  const nlohmann::json& a1 = doc["cloths"][1]["attachments"].back();
  EXPECT_EQ(a0["vertices"], nlohmann::json::array({0, 1}));
  EXPECT_EQ(a0["kind"], "fixed");
  EXPECT_EQ(a1["vertices"], nlohmann::json::array({1, 8}));
  EXPECT_THROW(addFixedAttachments(doc, {18}, {0, 9, 18}), std::invalid_argument);
}

TEST(EditorSession, PinSelectionIsOneUndoableEditThatTheLoaderAccepts) {
  EditorSession session("");
  const int before = int(session.document().scene()->cloths[0].attachments.size());
  EXPECT_NE(session.selecting().pinSelection(), "") << "nothing selected";
  EXPECT_NE(session.selecting().selectNodes({0, 100000}, false), "");
  ASSERT_EQ(session.selecting().selectNodes({3, 5}, false), "");
  ASSERT_EQ(session.selecting().pinSelection(), "");
  ASSERT_TRUE(session.document().valid()) << session.document().validationError();
  const auto& attachments = session.document().scene()->cloths[0].attachments;
  ASSERT_EQ(int(attachments.size()), before + 1);
  EXPECT_EQ(attachments.back().vertices, (std::vector<int>{3, 5}));
  EXPECT_TRUE(session.document().undo());
  EXPECT_EQ(int(session.document().scene()->cloths[0].attachments.size()), before);
}

TEST(EditorSession, ViewportShowsTheRestStateThenTheCachedFrames) {
  EditorSession session("");
  ASSERT_EQ(session.document().setValue("time.steps", 4), "");
  const render::RenderScene* rest = session.viewport().scene();
  ASSERT_TRUE(rest);
  EXPECT_FALSE(session.viewport().showingCache());
  const float restY = rest->cloth.positions(288, 1);
  ASSERT_EQ(session.timeline().simulate(), "");
  session.cache().wait();
  session.playback().scrub(4, session.timeline().availableFrames());
  const render::RenderScene* last = session.viewport().scene();
  ASSERT_TRUE(last);
  EXPECT_TRUE(session.viewport().showingCache());
  EXPECT_LT(last->cloth.positions(288, 1), restY) << "the free corner has fallen";
  EXPECT_FALSE(session.timeline().cacheStale());
  session.document().setValue("cloths.0.material.stretch", 500.0);
  EXPECT_TRUE(session.timeline().cacheStale());
}

}  // namespace
}  // namespace weft::editor
