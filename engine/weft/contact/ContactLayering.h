#pragma once
// Gauss-Seidel order of the self-collision pairs (notes Sec. 2.4, after DiffCloth and Ly et
// al.): pairs are grouped into layers in which no node appears twice, so a layer's pairs are
// independent and solved in parallel, and the layers run one after the other.
//
// Order: impulses should travel away from what holds the cloth, so pairs are visited by
// breadth-first distance, in the graph whose edges are the pairs, from the nodes in obstacle
// contact; components that touch no obstacle start from their chain ends (nodes in one pair
// only), and closed loops from any node. Each pair, in that order, goes to the first layer after
// the last layer of either of its nodes (greedy edge colouring), which keeps every node's pairs
// in visiting order; isolated pairs all land in layer 0, as in DiffCloth.

#include <weft/record/ContactPoint.h>

#include <vector>

namespace weft {

class ContactLayering {
 public:
  explicit ContactLayering(int nodeCount)
      : level_(nodeCount, -1), last_(nodeCount, -1), slot_(nodeCount, -1) {}

  // Reorders `pairs` layer by layer; layerStart gets the layer boundaries (size layers + 1).
  // `obstacleNodes`: nodes with an obstacle contact this step. No allocation once grown.
  void order(std::vector<ContactPoint>& pairs, const std::vector<int>& obstacleNodes,
             std::vector<int>& layerStart);

 private:
  std::vector<int> level_, last_, slot_;  // per node, reset after use
  std::vector<int> touched_, adjacencyStart_, adjacency_, queue_, pairKey_, pairLayer_,
      orderBuffer_;
  std::vector<ContactPoint> sorted_;
};

}  // namespace weft
