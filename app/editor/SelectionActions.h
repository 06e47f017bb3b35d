#pragma once
// What the editor does with the vertex selection (Selection.h): choosing vertices (by number,
// a click or a box in the viewport, the border loop through the inspected vertex, a band along
// an axis) and turning them into attachments (a fixed pin, a handle the gizmo then places).

#include "EditorDocument.h"
#include "ObjectPlacement.h"
#include "Selection.h"
#include "ViewportFrame.h"

#include <weft/render/Camera.h>

#include <optional>
#include <string>
#include <vector>

namespace weft::editor {

class SelectionActions {
 public:
  SelectionActions(EditorDocument& document, Selection& selection, ViewportFrame& viewport,
                   const render::Camera& camera, ObjectPlacement& placement);

  // Selection in viewport pixels of a width x height view (x right, y down).
  std::optional<int> clickSelect(float x, float y, int width, int height, bool add);
  void boxSelectPixels(float x0, float y0, float x1, float y1, int width, int height, bool add);
  // Selects global nodes; returns an error text for a node that is not a cloth vertex.
  std::string selectNodes(const std::vector<int>& nodes, bool add);
  // Selection by region. The border loop (mesh/BoundaryLoops.h) of the cloth's rest mesh that
  // holds the inspected vertex (a skirt's waist or hem, a cuff); or the cloth vertices whose
  // coordinate `axis` (0 x, 1 y, 2 z) lies in [low, high] as the viewport shows them (a band:
  // the top 2 cm, one side). Error text or "" (also when the band holds no vertex: the
  // selection is then empty, or unchanged when adding).
  std::string selectBoundaryLoop(bool add);
  std::string selectBand(int axis, double low, double high, bool add);
  // Adds a fixed attachment holding the selected vertices (one undo step). Error text or "".
  std::string pinSelection();
  // Adds a handle attachment holding the selected vertices (of one cloth), still until keyed,
  // and makes it the object the gizmo places (one undo step). Error text or "".
  std::string makeHandle();

 private:
  EditorDocument& document_;
  Selection& selection_;
  ViewportFrame& viewport_;
  const render::Camera& camera_;
  ObjectPlacement& placement_;
};

}  // namespace weft::editor
