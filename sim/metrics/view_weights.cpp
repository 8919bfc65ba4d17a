#include "sim/metrics/view_weights.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace ambisim {

double sphere_solid_angle(double radius, double distance) {
  if (!(distance > radius) || !(radius > 0.0)) return 0.0;
  const double s = radius / distance;
  // 2 pi (1 - sqrt(1 - s^2)), written as 2 pi s^2 / (1 + sqrt(1 - s^2)) so that far, tiny
  // spheres keep their digits (no cancellation).
  return 2.0 * std::numbers::pi * s * s / (1.0 + std::sqrt(1.0 - s * s));
}

double normal_visible_share(const glm::dvec3& normal, const glm::dvec3& to_camera) {
  return std::max(0.0, glm::dot(normal, to_camera));
}

CameraView::CameraView(const ViewSpec& spec, const glm::dvec3& position, const glm::dvec3& forward)
    : position_(position) {
  const double len = glm::length(forward);
  forward_ = len > 0.0 && std::isfinite(len) ? forward / len : glm::dvec3(1.0, 0.0, 0.0);
  glm::dvec3 world_up(0.0, 0.0, 1.0);
  if (std::abs(forward_.z) > 0.999999) world_up = glm::dvec3(0.0, 1.0, 0.0);
  right_ = glm::normalize(glm::cross(forward_, world_up));
  up_ = glm::cross(right_, forward_);
  tan_half_w_ = std::tan(0.5 * spec.fov_deg * std::numbers::pi / 180.0);
  tan_half_h_ = tan_half_w_ / spec.aspect;
  // Each side plane contains the camera and one frustum edge direction pair; its inward normal
  // is the edge plane's normal oriented toward the forward axis.
  plane_[0] = glm::normalize(forward_ * tan_half_w_ + right_);  // left plane (x' >= -t z')
  plane_[1] = glm::normalize(forward_ * tan_half_w_ - right_);  // right plane
  plane_[2] = glm::normalize(forward_ * tan_half_h_ + up_);     // bottom plane
  plane_[3] = glm::normalize(forward_ * tan_half_h_ - up_);     // top plane
}

bool CameraView::sees_sphere(const glm::dvec3& centre, double radius) const {
  const glm::dvec3 c = centre - position_;
  if (glm::dot(c, forward_) <= -radius) return false;  // wholly behind the camera
  for (const glm::dvec3& n : plane_) {
    if (glm::dot(c, n) < -radius) return false;
  }
  return true;
}

double CameraView::screen_weight(const glm::dvec3& centre, double radius) const {
  if (!sees_sphere(centre, radius)) return 0.0;
  return sphere_solid_angle(radius, glm::length(centre - position_));
}

}  // namespace ambisim
