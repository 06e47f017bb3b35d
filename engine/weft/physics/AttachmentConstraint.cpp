#include <weft/physics/AttachmentConstraint.h>

#include <weft/model/ClothModel.h>
#include <weft/scene/Scene.h>

namespace weft {

AttachmentConstraint::AttachmentConstraint(const char* name, std::vector<Row> rows,
                                           const NodeMatrix& initial)
    : name_(name), rows_(std::move(rows)) {
  const int n = static_cast<int>(rows_.size());
  weights_.resize(n);
  anchors_.resize(n, 3);
  std::vector<Eigen::Triplet<double>> sel;
  for (int r = 0; r < n; ++r) {
    weights_[r] = rows_[r].stiffness;
    anchors_.row(r) = initial.row(rows_[r].node);
    sel.emplace_back(r, rows_[r].node, 1.0);
  }
  targets_ = anchors_;
  driven_.assign(static_cast<std::size_t>(n), 0);
  driveOffsets_ = NodeMatrix::Zero(n, 3);
  setSelection(static_cast<int>(initial.rows()), sel);
}

void AttachmentConstraint::drive(int row, const Vec3& offset) {
  driven_.at(static_cast<std::size_t>(row)) = 1;
  driveOffsets_.row(row) = offset.transpose();
}

void AttachmentConstraint::beginStep(double time, const NodeMatrix& /*start*/) {
  for (int r = 0; r < rowCount(); ++r)
    if (driven_[r])
      targets_.row(r) = anchors_.row(r) + driveOffsets_.row(r);
    else if (rows_[r].trajectory)
      targets_.row(r) = rows_[r].trajectory->target(anchors_.row(r).transpose(), time).transpose();
}

double AttachmentConstraint::project(const NodeMatrix& x, NodeMatrix& wp) const {
  double energy = 0.0;
  for (int r = 0; r < rowCount(); ++r) {
    energy += 0.5 * weights_[r] * (x.row(rows_[r].node) - targets_.row(r)).squaredNorm();
    wp.row(r) = weights_[r] * targets_.row(r);
  }
  return energy;
}

AttachmentConstraint makeAttachmentConstraint(const Scene& scene, const ClothModel& model,
                                              bool handles) {
  std::vector<AttachmentConstraint::Row> rows;
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    for (const Attachment& a : scene.cloths[c].attachments) {
      if ((a.kind == Attachment::Kind::Handle) != handles) continue;
      for (int v : a.vertices)
        rows.push_back({model.vertexOffset[c] + v, a.stiffness, handles ? &a.trajectory : nullptr});
    }
  }
  return AttachmentConstraint(handles ? "handles" : "attachments", std::move(rows),
                              model.rest.vertices);
}

}  // namespace weft
