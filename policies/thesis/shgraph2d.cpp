#include "policies/thesis/shgraph2d.h"

#include <memory>

namespace ambisim {

PlannerInfo ShGraph2dPlanner::info() {
  return {"shgraph2d",
          "ground sheet SHGraph: sets height_m above the terrain, 9-child cells, quadrant "
          "lookup (thesis 8.5/9.3)",
          shgraph_params(2, true, false),
          [](const PlannerParams& p) { return std::make_unique<ShGraph2dPlanner>(p); }};
}

ShGraph2dPlanner::ShGraph2dPlanner(const PlannerParams& params)
    : params_(params), core_(shgraph_settings_from(params, 2)) {}

}  // namespace ambisim
