#pragma once
// What the player sees (SPEC section 5): the camera's view and the weights the viewed metrics
// give each receiver and normal.
// - A receiver is a sphere of the scenario's size. Its weight at a frame is the solid angle it
//   covers, 2 pi (1 - sqrt(1 - (r/d)^2)) steradians at distance d > r, when the sphere
//   intersects the view frustum (the standard sphere-against-side-planes test; the sphere counts
//   whole), else 0. A sphere the camera is inside (d <= r) weighs 0: engines cull it at the near
//   plane. Far objects weigh little: about pi r^2 / d^2, so twice the distance is a quarter.
// - A metric normal's weight is its visible share max(0, n . direction to the camera): the
//   normals facing away from the camera are never seen on the sphere.
#include <glm/vec3.hpp>

namespace ambisim {

// The camera's lens: horizontal field of view and aspect ratio (width / height).
struct ViewSpec {
  double fov_deg = 70.0;  // horizontal, in (0, 180)
  double aspect = 16.0 / 9.0;
};

// A posed view: the camera position and an orthonormal frame (forward, right, up).
class CameraView {
 public:
  // forward need not be unit; a zero forward looks along +x. up is the world's z, or y when
  // looking straight up or down.
  CameraView(const ViewSpec& spec, const glm::dvec3& position, const glm::dvec3& forward);

  const glm::dvec3& position() const { return position_; }
  const glm::dvec3& forward() const { return forward_; }
  const glm::dvec3& right() const { return right_; }
  const glm::dvec3& up() const { return up_; }
  double tan_half_width() const { return tan_half_w_; }
  double tan_half_height() const { return tan_half_h_; }

  // True when a sphere of `radius` at `centre` intersects the frustum (in front of the camera).
  bool sees_sphere(const glm::dvec3& centre, double radius) const;
  // The receiver weight above (steradians; 0 outside the frustum or with the camera inside).
  double screen_weight(const glm::dvec3& centre, double radius) const;

 private:
  glm::dvec3 position_, forward_, right_, up_;
  double tan_half_w_ = 0.0, tan_half_h_ = 0.0;
  glm::dvec3 plane_[4];  // inward unit normals of the four side planes through the camera
};

// Solid angle of a sphere of radius r seen from distance d (steradians; 0 when d <= r).
double sphere_solid_angle(double radius, double distance);

// max(0, n . to_camera) for unit vectors.
double normal_visible_share(const glm::dvec3& normal, const glm::dvec3& to_camera);

}  // namespace ambisim
