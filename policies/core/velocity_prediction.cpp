#include "policies/core/velocity_prediction.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "sim/world/spline.h"

namespace ambisim {

glm::dvec3 predict_position(const FrameContext& ctx, double horizon_s, bool route,
                            double route_snap_m) {
  const glm::dvec3 straight = ctx.camera_position + horizon_s * ctx.camera_velocity;
  if (!route || ctx.world == nullptr || ctx.world->road == nullptr || ctx.world->road->empty()) {
    return straight;
  }
  const Spline3& road = *ctx.world->road;
  const double s = road.closest_s(ctx.camera_position);
  const glm::dvec3 on_road = road.at(s);
  if (glm::length(on_road - ctx.camera_position) > route_snap_m) return straight;
  // Travel the same distance along the road, keeping the camera's offset from the centre line.
  const glm::dvec3 tangent = road.tangent(s);
  const double speed_along = glm::dot(ctx.camera_velocity, tangent);
  const double s_ahead = s + speed_along * horizon_s;
  const glm::dvec3 offset = ctx.camera_position - on_road;
  return road.at(s_ahead) + offset;
}

std::vector<glm::dvec3> road_ahead(const FrameContext& ctx, double ahead_s, double spacing_m,
                                   double route_snap_m) {
  std::vector<glm::dvec3> out;
  if (ctx.world == nullptr || ctx.world->road == nullptr || ctx.world->road->empty()) return out;
  const Spline3& road = *ctx.world->road;
  const double s = road.closest_s(ctx.camera_position);
  const glm::dvec3 on_road = road.at(s);
  if (glm::length(on_road - ctx.camera_position) > route_snap_m) return out;
  const double speed_along = glm::dot(ctx.camera_velocity, road.tangent(s));
  const double length = std::abs(speed_along) * ahead_s;
  const double dir = speed_along < 0.0 ? -1.0 : 1.0;
  const glm::dvec3 offset = ctx.camera_position - on_road;
  const int steps = static_cast<int>(std::ceil(length / std::max(spacing_m, 1e-3)));
  for (int i = 0; i <= steps && i <= 4096; ++i) {
    const double along = std::min(length, i * spacing_m);
    out.push_back(road.at(std::clamp(s + dir * along, 0.0, road.length())) + offset);
  }
  return out;
}

Focus make_focus(const FrameContext& ctx, const PredictionSettings& s) {
  Focus f;
  f.now = ctx.camera_position;
  f.ahead = ctx.camera_position;
  if (!s.enabled || ctx.camera_cut) return f;
  const double latency = ctx.capture_latency_s();
  const double horizon = (std::isfinite(latency) ? latency : 0.0) + s.lookahead_s;
  f.ahead = predict_position(ctx, horizon, s.route, s.route_snap_m);
  return f;
}

}  // namespace ambisim
