#include <weft/contact/HandleObstacleCheck.h>
#include <weft/contact/HandleTargetSamples.h>

#include <algorithm>
#include <cstdio>

namespace weft {

std::vector<std::string> handlesEnteringObstacles(const Scene& scene) {
  // One message per (cloth, attachment, obstacle): the samples come grouped in that order.
  struct Entry {
    int cloth = -1, attachment = -1, obstacle = -1;
    double first = 0.0, deepest = 0.0;
    const char* shape = "";
  };
  std::vector<Entry> entries;
  forEachHandleTargetNearObstacle(scene, 0, 0.0, [&](const HandleTargetSample& s) {
    if (entries.empty() || entries.back().cloth != s.cloth ||
        entries.back().attachment != s.attachment || entries.back().obstacle != s.obstacle)
      entries.push_back({s.cloth, s.attachment, s.obstacle, s.time, 0.0, s.shape});
    entries.back().deepest = std::max(entries.back().deepest, -s.distance);
  });
  std::vector<std::string> messages;
  for (const Entry& e : entries) {
    char what[320];
    std::snprintf(
        what, sizeof what,
        "cloths.%d.attachments.%d: the handle's targets enter obstacles.%d (%s) from t = "
        "%.3g s, up to %.1f mm deep; the attachment will pull its vertices into the obstacle "
        "against the contact, and steps may not converge",
        e.cloth, e.attachment, e.obstacle, e.shape, e.first, 1e3 * e.deepest);
    messages.push_back(scene.file + ": " + what);
  }
  return messages;
}

}  // namespace weft
