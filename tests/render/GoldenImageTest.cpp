// Golden images through OSMesa: fixed size, fixed camera, no MSAA, no text. Regenerate on
// purpose with `weft_tests_render --bless --gtest_filter='GoldenImage*'` and look at them.

#include "GoldenImage.h"
#include "RenderTestSupport.h"

#include <weft/frames/ClothFields.h>

#include <gtest/gtest.h>

namespace weft::test {
namespace {

constexpr int kWidth = 320, kHeight = 240;

TEST(GoldenImage, DrapedClothOnSphere) {
  const DrapedSphere d = drapedSphere(32);
  render::Renderer& r = osmesaRenderer(kWidth, kHeight);
  EXPECT_TRUE(matchesGolden("draped_cloth_sphere", r.renderImage(d.scene, goldenCamera())));
}

TEST(GoldenImage, ContactBranchOverlay) {
  DrapedSphere d = drapedSphere(32);
  d.scene.contacts = syntheticContacts(d, true);
  render::Renderer& r = osmesaRenderer(kWidth, kHeight);
  EXPECT_TRUE(matchesGolden("contact_branches", r.renderImage(d.scene, goldenCamera())));
}

TEST(GoldenImage, StrainColorMap) {
  DrapedSphere d = drapedSphere(32);
  const Eigen::VectorXd strain = vertexStrain(d.rest, d.draped);
  render::ScalarColoring coloring;
  coloring.values.assign(strain.data(), strain.data() + strain.size());
  coloring.high = float(strain.cwiseAbs().maxCoeff());
  coloring.low = -coloring.high;
  coloring.map = render::ColorMapKind::Diverging;
  d.scene.scalars = coloring;
  render::Renderer& r = osmesaRenderer(kWidth, kHeight);
  EXPECT_TRUE(matchesGolden("strain_colormap", r.renderImage(d.scene, goldenCamera())));
}

TEST(GoldenImage, Wireframe) {
  const DrapedSphere d = drapedSphere(16);
  render::RenderStyle style;
  style.wireframe = true;
  render::Renderer& r = osmesaRenderer(kWidth, kHeight);
  EXPECT_TRUE(matchesGolden("wireframe", r.renderImage(d.scene, goldenCamera(), style)));
}

}  // namespace
}  // namespace weft::test
