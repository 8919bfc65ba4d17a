#include "policies/thesis/shgraph.h"

#include <memory>

namespace ambisim {
namespace {

PlannerInfo make_info(const std::string& name, const std::string& description, bool predict,
                      bool route) {
  return {name, description, shgraph_params(3, predict, route),
          [name](const PlannerParams& p) { return std::make_unique<ShGraphPlanner>(name, p); }};
}

}  // namespace

PlannerInfo ShGraphPlanner::info() {
  return make_info("shgraph",
                   "thesis SHGraph: 27-child cells, centre sets, lifetime + fade anchors, "
                   "depth from speed, octant lookup",
                   false, false);
}

PlannerInfo ShGraphPlanner::info_vp() {
  return make_info("shgraph+vp", "SHGraph planning around the predicted camera (D15)", true, false);
}

PlannerInfo ShGraphPlanner::info_route() {
  return make_info("shgraph+route", "SHGraph predicting along the road spline (7.5.3)", true, true);
}

ShGraphPlanner::ShGraphPlanner(std::string name, const PlannerParams& params)
    : name_(std::move(name)), params_(params), core_(shgraph_settings_from(params, 3)) {}

}  // namespace ambisim
