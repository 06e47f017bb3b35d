#include <weft/optim/ParameterSpace.h>

#include <weft/core/Error.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace weft {

void applyDefaultBounds(SceneParameter& p) {
  const double inf = std::numeric_limits<double>::infinity();
  using K = SceneParameter::Kind;
  p.lower = -inf;
  p.upper = inf;
  p.logScale = false;
  switch (p.kind) {
    case K::Stretch:  // N/m; the loader's cap is 1e12, far beyond any cloth
      p.lower = 1e-3, p.upper = 1e9, p.logScale = true;
      break;
    case K::Bend:  // N m
      p.lower = 1e-9, p.upper = 1e3, p.logScale = true;
      break;
    case K::Density:  // kg/m^2: real fabrics are 0.05..1
      p.lower = 1e-4, p.upper = 1e3, p.logScale = true;
      break;
    case K::WindStrength:  // N/m^2, the loader's range
      p.lower = -1e6, p.upper = 1e6;
      break;
    case K::WindFrequency:  // Hz, >= 0 as the loader requires
      p.lower = 0.0, p.upper = 1e6;
      break;
    case K::WindPhase:
      p.lower = -1e6, p.upper = 1e6;
      break;
    case K::ObstacleFriction:
    case K::SelfCollisionFriction:  // a Coulomb coefficient: >= 0, and no fabric holds beyond 10
      p.lower = 0.0, p.upper = 10.0;
      break;
    case K::AttachmentStiffness:  // N/m, a spring: positive, spans decades like stretch
      p.lower = 1e-3, p.upper = 1e12, p.logScale = true;
      break;
    default:  // wind direction, gravity, initial velocity, nodal forces: any real value
      break;
  }
}

ParameterSpace::ParameterSpace(const Scene& scene, const ParameterSet& set)
    : parameters_(set.parameters()) {
  initial_ = set.values(scene);
  scale_.resize(size());
  for (int i = 0; i < size(); ++i) {
    SceneParameter& p = parameters_[i];
    applyDefaultBounds(p);
    std::string where = p.path;
    bool explicitBox = false;
    if (scene.task)
      for (const Task::Bound& b : scene.task->bounds)
        if (b.path == p.path) {
          p.lower = b.lower, p.upper = b.upper;
          where = "task.bounds." + p.path;
          explicitBox = true;
        }
    // A log-scaled parameter needs a positive box; explicit bounds reaching 0 or below switch
    // it to linear coordinates (the loader still rejects values it cannot use).
    if (p.logScale && !(p.lower > 0.0)) p.logScale = false;
    const double v = initial_[i];
    if (!(v >= p.lower && v <= p.upper)) {
      std::ostringstream s;
      s << "the starting value " << v << " of '" << p.path << "' lies outside its bounds ["
        << p.lower << ", " << p.upper << "]";
      throw InputError(scene.file, where, s.str());
    }
    // A handle knot's task box, else the start (header).
    using K = SceneParameter::Kind;
    const bool knot = p.kind == K::HandleOffset || p.kind == K::HandleTangent;
    const double halfWidth = 0.5 * (p.upper - p.lower);
    scale_[i] = knot && explicitBox && std::isfinite(halfWidth) ? halfWidth
                : v != 0.0                                      ? std::abs(v)
                                                                : 1.0;
  }
  initialCoordinates_ = toCoordinates(initial_);
}

Eigen::VectorXd ParameterSpace::toCoordinates(const Eigen::VectorXd& values) const {
  Eigen::VectorXd z(size());
  for (int i = 0; i < size(); ++i)
    z[i] = parameters_[i].logScale ? std::log(values[i]) : values[i] / scale_[i];
  return z;
}

Eigen::VectorXd ParameterSpace::toValues(const Eigen::VectorXd& z) const {
  Eigen::VectorXd v(size());
  for (int i = 0; i < size(); ++i)
    v[i] = z[i] == initialCoordinates_[i] ? initial_[i]  // the start, exactly (header)
           : parameters_[i].logScale      ? std::exp(z[i])
                                          : z[i] * scale_[i];
  return v;
}

Eigen::VectorXd ParameterSpace::gradientToCoordinates(const Eigen::VectorXd& z,
                                                      const Eigen::VectorXd& g) const {
  Eigen::VectorXd out(size());
  for (int i = 0; i < size(); ++i)
    out[i] = g[i] * (parameters_[i].logScale ? std::exp(z[i]) : scale_[i]);
  return out;
}

Eigen::VectorXd ParameterSpace::gradientToValues(const Eigen::VectorXd& z,
                                                 const Eigen::VectorXd& g) const {
  Eigen::VectorXd out(size());
  for (int i = 0; i < size(); ++i)
    out[i] = g[i] / (parameters_[i].logScale ? std::exp(z[i]) : scale_[i]);
  return out;
}

Eigen::VectorXd ParameterSpace::lowerValues() const {
  Eigen::VectorXd v(size());
  for (int i = 0; i < size(); ++i) v[i] = parameters_[i].lower;
  return v;
}

Eigen::VectorXd ParameterSpace::upperValues() const {
  Eigen::VectorXd v(size());
  for (int i = 0; i < size(); ++i) v[i] = parameters_[i].upper;
  return v;
}

}  // namespace weft
