#include "virtual_origami/curved/elastica.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <Eigen/Dense>

namespace virtual_origami::core
{
namespace
{
/// θ″ as a function of arc length and θ.
using Moment = std::function<double(double s, double theta)>;

/// RK4 on (x, z, θ, θ′) from the clamp (origin, θ = 0) with θ′(0) = start_curvature.
ElasticaCurve integrate(double length, double start_curvature, int steps, const Moment& moment)
{
  ElasticaCurve c;
  c.length = length;
  const int n = std::max(steps, 1);
  c.x.reserve(n + 1);
  c.z.reserve(n + 1);
  c.theta.reserve(n + 1);
  c.curvature.reserve(n + 1);
  Eigen::Vector4d y(0.0, 0.0, 0.0, start_curvature);
  const auto rate = [&](double s, const Eigen::Vector4d& v) {
    return Eigen::Vector4d(std::cos(v[2]), std::sin(v[2]), v[3], moment(s, v[2]));
  };
  const double h = length / n;
  const auto record = [&] {
    c.x.push_back(y[0]);
    c.z.push_back(y[1]);
    c.theta.push_back(y[2]);
    c.curvature.push_back(y[3]);
  };
  record();
  for (int k = 0; k < n; ++k)
  {
    const double s = k * h;
    const Eigen::Vector4d k1 = rate(s, y);
    const Eigen::Vector4d k2 = rate(s + h / 2, y + h / 2 * k1);
    const Eigen::Vector4d k3 = rate(s + h / 2, y + h / 2 * k2);
    const Eigen::Vector4d k4 = rate(s + h, y + h * k3);
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    record();
  }
  return c;
}

/// Newton on `residual`(u) = 0 with a forward-difference Jacobian (steps `scale`·1e-7) and
/// halving of steps that do not lower |r|. Returns |r| at the end.
template <int N>
double shoot(Eigen::Matrix<double, N, 1>& u, const Eigen::Matrix<double, N, 1>& scale,
             const std::function<Eigen::Matrix<double, N, 1>(const Eigen::Matrix<double, N, 1>&)>& residual,
             double tolerance, int max_iterations)
{
  Eigen::Matrix<double, N, 1> r = residual(u);
  for (int it = 0; it < max_iterations && r.norm() > tolerance; ++it)
  {
    Eigen::Matrix<double, N, N> jacobian;
    for (int i = 0; i < N; ++i)
    {
      Eigen::Matrix<double, N, 1> v = u;
      const double d = 1e-7 * scale[i];
      v[i] += d;
      jacobian.col(i) = (residual(v) - r) / d;
    }
    const Eigen::Matrix<double, N, 1> step = jacobian.fullPivLu().solve(-r);
    if (!step.allFinite())
      break;
    double t = 1.0;
    bool improved = false;
    for (int halvings = 0; halvings < 30; ++halvings, t /= 2)
    {
      const Eigen::Matrix<double, N, 1> trial = u + t * step;
      const Eigen::Matrix<double, N, 1> rt = residual(trial);
      if (rt.allFinite() && rt.norm() < r.norm())
      {
        u = trial;
        r = rt;
        improved = true;
        break;
      }
    }
    if (!improved)
      break;
  }
  return r.norm();
}
}  // namespace

Eigen::Vector2d ElasticaCurve::at(double s) const
{
  const int n = steps();
  const double h = length / n;
  const double f = std::clamp(s / h, 0.0, static_cast<double>(n));
  const int k = std::min(static_cast<int>(f), n - 1);
  const double t = f - k;
  const Eigen::Vector2d p0(x[k], z[k]), p1(x[k + 1], z[k + 1]);
  const Eigen::Vector2d m0 = h * Eigen::Vector2d(std::cos(theta[k]), std::sin(theta[k]));
  const Eigen::Vector2d m1 = h * Eigen::Vector2d(std::cos(theta[k + 1]), std::sin(theta[k + 1]));
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * p1 + (t3 - t2) * m1;
}

double ElasticaCurve::angleAt(double s) const
{
  const int n = steps();
  const double f = std::clamp(s / (length / n), 0.0, static_cast<double>(n));
  const int k = std::min(static_cast<int>(f), n - 1);
  const double t = f - k;
  return (1 - t) * theta[k] + t * theta[k + 1];
}

ElasticaCurve integrateHeldElastica(double length, double start_curvature, double a, double b, int steps)
{
  return integrate(length, start_curvature, steps,
                   [a, b](double, double theta) { return a * std::cos(theta) + b * std::sin(theta); });
}

Expected<HeldElastica> heldElastica(double length, const Eigen::Vector2d& end, double end_angle,
                                    const ElasticaOptions& options)
{
  using Failure = Expected<HeldElastica>;
  if (!(length > 0) || !std::isfinite(length) || !end.allFinite() || !std::isfinite(end_angle))
    return Failure::failure("the elastica needs a positive length and a finite end");
  if (end.norm() >= length)
    return Failure::failure("the end is out of reach of an inextensible rod (|end| ≥ length)");
  // The circular arc (no end force) that turns by end_angle: the easy case to start from.
  const double alpha = end_angle;
  const Eigen::Vector2d arc_end = std::abs(alpha) < 1e-12 ?
                                      Eigen::Vector2d(length, 0.0) :
                                      Eigen::Vector2d(length * std::sin(alpha) / alpha,
                                                      length * (1 - std::cos(alpha)) / alpha);
  Eigen::Vector3d u(alpha / length, 0.0, 0.0);  // θ′(0), a, b
  const Eigen::Vector3d scale(1.0 / length, 1.0 / (length * length), 1.0 / (length * length));
  const int stages = std::max(options.stages, 1);
  double left = 0.0;
  for (int k = 1; k <= stages; ++k)
  {
    const Eigen::Vector2d target = arc_end + (end - arc_end) * (static_cast<double>(k) / stages);
    const auto residual = [&](const Eigen::Vector3d& v) {
      const ElasticaCurve c = integrateHeldElastica(length, v[0], v[1], v[2], options.steps);
      return Eigen::Vector3d((c.x.back() - target.x()) / length, (c.z.back() - target.y()) / length,
                             c.theta.back() - alpha);
    };
    left = shoot<3>(u, scale, residual, options.tolerance, options.max_iterations);
    if (!(left <= options.tolerance))
      return Failure::failure("shooting for the elastica did not converge (end conditions off by " +
                              std::to_string(left) + " of the length at stage " + std::to_string(k) + ")");
  }
  HeldElastica solved;
  solved.curve = integrateHeldElastica(length, u[0], u[1], u[2], options.steps);
  solved.a = u[1];
  solved.b = u[2];
  solved.residual = left;
  return solved;
}

Expected<CantileverElastica> cantileverElastica(double length, double load, const ElasticaOptions& options)
{
  using Failure = Expected<CantileverElastica>;
  if (!(length > 0) || !std::isfinite(length) || !std::isfinite(load))
    return Failure::failure("the cantilever needs a positive length and a finite load");
  const auto curveFor = [&](double start_curvature, double w) {
    return integrate(length, start_curvature, options.steps,
                     [w, length](double s, double theta) { return w * (length - s) * std::cos(theta); });
  };
  // Small deflection: θ′(0) = −w·L²/2.
  const int stages = std::max(options.stages, 1);
  Eigen::Matrix<double, 1, 1> u(-load / stages * length * length / 2);
  const Eigen::Matrix<double, 1, 1> scale(1.0 / length);
  double left = 0.0;
  for (int k = 1; k <= stages; ++k)
  {
    const double w = load * k / stages;
    const auto residual = [&](const Eigen::Matrix<double, 1, 1>& v) {
      return Eigen::Matrix<double, 1, 1>(curveFor(v[0], w).curvature.back() * length);
    };
    left = shoot<1>(u, scale, residual, options.tolerance, options.max_iterations);
    if (!(left <= options.tolerance))
      return Failure::failure("shooting for the cantilever did not converge (θ′(L)·L = " + std::to_string(left) +
                              " at stage " + std::to_string(k) + ")");
  }
  CantileverElastica solved;
  solved.curve = curveFor(u[0], load);
  solved.residual = left;
  return solved;
}

}  // namespace virtual_origami::core
