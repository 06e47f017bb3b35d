#pragma once
// Node-obstacle contact detection, once per step (DiffCloth Sec. 3.2; notes Sec. 2.3). Each
// node's predicted path x_n -> x_n + displacement is sampled at its start, middle and end (more
// samples when it is long compared with the margin); the first sample closer than the
// obstacle's skin plus the margin makes a contact, whose frame is frozen from that sample. The
// obstacle sees each sample together with the node's start-of-step position, so that a shape
// can give a point the obstacle moved onto the face it came in through (BoxShape::sampleMoved).
// A node has at most one contact per obstacle, and may touch several obstacles.

#include <weft/contact/ContactObstacle.h>
#include <weft/contact/ParallelContactCollector.h>
#include <weft/record/ContactPoint.h>

#include <vector>

namespace weft {

class ObstacleContactDetector {
 public:
  // `margin` (m): how far outside an obstacle's skin a node is already taken into the contact
  // set (where it is take-off unless it needs a force).
  ObstacleContactDetector(const std::vector<ContactObstacle>& obstacles, double margin)
      : obstacles_(obstacles), margin_(margin) {}

  // Appends the contacts, sorted by node then obstacle. Parallel over nodes, no allocation once
  // the buffers have grown.
  void detect(const NodeMatrix& x, const NodeMatrix& displacement, double h,
              std::vector<ContactPoint>& out);
  double margin() const { return margin_; }

 private:
  const std::vector<ContactObstacle>& obstacles_;
  double margin_;
  ParallelContactCollector collector_;
};

}  // namespace weft
