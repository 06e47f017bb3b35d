#include <weft/diff/ParameterPartials.h>

#include <weft/diff/AdjointLinearSolver.h>

#include <weft/physics/BendingConstraint.h>
#include <weft/physics/StretchConstraint.h>
#include <weft/physics/WindForce.h>

#include <cmath>

namespace weft {

ParameterPartials::ParameterPartials(const Model& model,
                                     const std::vector<SceneParameter>& parameters)
    : scene_(model.scene()),
      model_(model.cloth()),
      parameters_(parameters),
      unit_(parameters.size()),
      h_(model.dt()) {
  using Kind = SceneParameter::Kind;
  for (std::size_t k = 0; k < parameters_.size(); ++k) {
    const SceneParameter& p = parameters_[k];
    if (p.kind != Kind::Stretch && p.kind != Kind::Bend) continue;
    const int t0 = model_.triangleOffset[p.cloth], t1 = model_.triangleOffset[p.cloth + 1];
    const TriangleIndices tris = model_.rest.triangles.middleRows(t0, t1 - t0);
    if (p.kind == Kind::Stretch)
      unit_[k].constraint = std::make_unique<StretchConstraint>(model_.rest.vertices, tris,
                                                                std::vector<double>(t1 - t0, 1.0));
    else
      unit_[k].constraint = std::make_unique<BendingConstraint>(
          buildHinges(model_.rest.vertices, tris, 1.0,
                      scene_.cloths[p.cloth].material.bendModel == Material::BendModel::Oriented),
          model_.nodeCount());
    unit_[k].gram = unit_[k].constraint->weightedGram();
  }
}

ParameterPartials::~ParameterPartials() = default;

void ParameterPartials::accumulate(const NodeMatrix& x0, const NodeMatrix& v0, const NodeMatrix& x1,
                                   double t1, const NodeMatrix& z,
                                   Eigen::VectorXd& gradient) const {
  using Kind = SceneParameter::Kind;
  const double h2 = h_ * h_;
  const Eigen::VectorXd& area = model_.lumpedArea;
  // Wind quantities shared by its parameters.
  double phi = 1.0, dphi = 0.0, areaZDotD = 0.0;
  Vec3 areaZ = Vec3::Zero();
  if (scene_.wind) {
    const Wind& w = *scene_.wind;
    if (!w.constant) {
      const double arg = 2.0 * M_PI * w.frequency * t1 + w.phase;
      phi = 0.5 * (std::sin(arg) + 1.0);
      dphi = 0.5 * std::cos(arg);  // d phi / d(argument)
    }
    areaZ = z.transpose() * windCoefficients(w, area);  // sum_i k_i z_i (k: area or falloff)
    areaZDotD = areaZ.dot(w.direction);
  }
  for (std::size_t k = 0; k < parameters_.size(); ++k) {
    const SceneParameter& p = parameters_[k];
    double d = 0.0;
    switch (p.kind) {
      case Kind::Stretch:
      case Kind::Bend: {
        const ProjectiveConstraint& c = *unit_[k].constraint;
        // dG/dk = h^2 (Gram x - A^T w_hat p(x)): Eq. 17 summed over the cloth's family at k = 1.
        work_ = unit_[k].gram * x1;
        if (!c.projectsToZero()) {
          // Projections set from the step's start (oriented bending) are those of x_n.
          if (c.dependsOnStart()) unit_[k].constraint->beginStep(t1, x0);
          rows_.resize(c.rowCount(), 3);
          c.project(x1, rows_);
          c.gather(rows_, -1.0, work_);
        }
        d = -h2 * blockDot(z, work_);
        break;
      }
      case Kind::Density: {
        const Vec3 g = scene_.gravity ? *scene_.gravity : Vec3::Zero();
        for (int i = model_.vertexOffset[p.cloth]; i < model_.vertexOffset[p.cloth + 1]; ++i) {
          const Vec3 inertia = (x1.row(i) - x0.row(i) - h_ * v0.row(i)).transpose() - h2 * g;
          d -= area[i] * z.row(i).dot(inertia.transpose());
        }
        break;
      }
      case Kind::WindStrength:
        d = h2 * phi * areaZDotD;
        break;
      case Kind::WindDirection:
        d = h2 * scene_.wind->strength * phi * areaZ[p.component];
        break;
      case Kind::WindFrequency:
        d = h2 * scene_.wind->strength * dphi * 2.0 * M_PI * t1 * areaZDotD;
        break;
      case Kind::WindPhase:
        d = h2 * scene_.wind->strength * dphi * areaZDotD;
        break;
      case Kind::NodalForce: {
        const PointForce& f = scene_.cloths[p.cloth].forces[p.index];
        for (int v : f.vertices) d += h2 * z(model_.vertexOffset[p.cloth] + v, p.component);
        break;
      }
      case Kind::Gravity:
        d = h2 * model_.mass.dot(z.col(p.component));
        break;
      case Kind::HandleOffset:
      case Kind::HandleTangent: {
        const Attachment& a = scene_.cloths[p.cloth].attachments[p.index];
        const auto control = p.kind == Kind::HandleOffset ? HandleTrajectory::Control::Offset
                                                          : HandleTrajectory::Control::Tangent;
        // -z . dG/dtheta = h^2 k sum_j z_j . d x_hat_j/dtheta, with d x_hat_j/dtheta = weight e_c.
        const double weight = a.trajectory.controlWeight(t1, control, p.knot);
        if (weight == 0.0) break;
        double zSum = 0.0;
        for (int v : a.vertices) zSum += z(model_.vertexOffset[p.cloth] + v, p.component);
        d = h2 * a.stiffness * weight * zSum;
        break;
      }
      case Kind::AttachmentStiffness: {
        const Attachment& a = scene_.cloths[p.cloth].attachments[p.index];
        const bool moves = a.kind == Attachment::Kind::Handle;
        for (int v : a.vertices) {
          const int node = model_.vertexOffset[p.cloth] + v;
          // The target as AttachmentConstraint sets it: the initial position, or the handle's
          // trajectory from it at the step's end time.
          const Vec3 rest = model_.rest.vertices.row(node).transpose();
          const Vec3 target = moves ? a.trajectory.target(rest, t1) : rest;
          d -= h2 * z.row(node).dot(x1.row(node) - target.transpose());
        }
        break;
      }
      case Kind::InitialVelocity:
        break;  // through v_0 only: accumulateInitial
      case Kind::ObstacleFriction:
      case Kind::SelfCollisionFriction:
        break;  // through the contact law only: ContactAdjoint
    }
    gradient[static_cast<int>(k)] += d;
  }
}

void ParameterPartials::accumulateInitial(const NodeMatrix& dLdv0,
                                          Eigen::VectorXd& gradient) const {
  for (std::size_t k = 0; k < parameters_.size(); ++k) {
    const SceneParameter& p = parameters_[k];
    if (p.kind != SceneParameter::Kind::InitialVelocity) continue;
    const int a = model_.vertexOffset[p.cloth], b = model_.vertexOffset[p.cloth + 1];
    gradient[static_cast<int>(k)] += dLdv0.col(p.component).segment(a, b - a).sum();
  }
}

}  // namespace weft
