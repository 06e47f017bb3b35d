#pragma once
// Attachments as stiff PD springs to a target (DiffCloth's attachment constraints): one row per
// attached node selecting it, projection = the target. Fixed attachments hold the node's
// initial position; handles follow their trajectory, evaluated once per step at its end time,
// unless a script drives them (drive(): a policy's action, DiffCloth Sec. 6.5).

#include <weft/physics/ProjectiveConstraint.h>
#include <weft/scene/HandleTrajectory.h>

#include <memory>
#include <vector>

namespace weft {

struct ClothModel;
struct Scene;

class AttachmentConstraint final : public ProjectiveConstraint {
 public:
  struct Row {
    int node;
    double stiffness;
    const HandleTrajectory* trajectory;  // null for a fixed attachment
  };
  AttachmentConstraint(const char* name, std::vector<Row> rows, const NodeMatrix& initial);
  const char* name() const override { return name_; }
  std::unique_ptr<ProjectiveConstraint> clone() const override {
    return std::make_unique<AttachmentConstraint>(*this);
  }
  void beginStep(double time, const NodeMatrix& start) override;
  double project(const NodeMatrix& x, NodeMatrix& weightedProjections) const override;
  const std::vector<Row>& rows() const { return rows_; }
  const NodeMatrix& targets() const { return targets_; }
  // From the next beginStep on, row r's target is its initial position + offset (a translation;
  // the row's trajectory, rotation included, no longer applies).
  void drive(int row, const Vec3& offset);

 private:
  const char* name_;
  std::vector<Row> rows_;
  std::vector<char> driven_;  // per row: targets from driveOffsets_, not the trajectory
  NodeMatrix driveOffsets_;
  NodeMatrix anchors_;  // initial positions of the attached nodes
  NodeMatrix targets_;  // current targets
};

// Fixed attachments ("attachments") or handles ("handles") of the whole scene; the scene must
// outlive the constraint (trajectories are referenced).
AttachmentConstraint makeAttachmentConstraint(const Scene& scene, const ClothModel& model,
                                              bool handles);

}  // namespace weft
