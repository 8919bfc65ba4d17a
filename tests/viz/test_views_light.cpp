// A run's ParaView receivers carry what the referee compared: the planner's and the reference's
// irradiance straight up and toward the camera, the displayed error between them toward the
// camera and the viewed pops; the .pvd timesteps are simulated seconds.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include "policies/registry/registry.h"
#include "sim/colour/ciede2000.h"
#include "sim/colour/tone_map.h"
#include "sim/run/reference_track.h"
#include "sim/run/run_output.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "viz/views.h"

namespace fs = std::filesystem;
using namespace ambisim;

namespace {

const std::string kDrive = std::string(AMBISIM_SOURCE_DIR) + "/tests/data/small_drive.json";

struct Written {
  fs::path dir;
  RunViews views;
  double exposure = 0.0;
};

Written run_and_view(const Scenario& sc, const World& world, const ReferenceTrack& ref,
                     const std::string& planner_name) {
  auto planner = make_planner(planner_name);
  const RunResult result = simulate(sc, world, ref, *planner);
  Written w;
  w.dir = fs::temp_directory_path() / ("ambisim_views_light_" + planner_name);
  fs::remove_all(w.dir);
  write_run_output(w.dir.string(), sc, {planner->name(), planner->params()}, result,
                   Overwrite::allow);
  ViewsOptions opt;
  opt.width = 320;
  opt.height = 200;
  opt.terrain_max_points = 48;
  opt.frames = {0};
  write_run_views(w.dir.string(), opt);
  w.views = load_views((w.dir / "views.json").string());
  w.exposure = result.exposure;
  return w;
}

vtkSmartPointer<vtkPolyData> receivers_of(const fs::path& dir, int frame) {
  char tag[32];
  std::snprintf(tag, sizeof tag, "f%06d", frame);
  auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  reader->SetFileName((dir / "views" / (std::string("receivers_") + tag + ".vtp")).c_str());
  reader->Update();
  return reader->GetOutput();
}

Rgb tuple3(vtkDataArray* a, vtkIdType i) {
  const double* t = a->GetTuple3(i);
  return Rgb(static_cast<float>(t[0]), static_cast<float>(t[1]), static_cast<float>(t[2]));
}

}  // namespace

TEST_CASE("viz: receivers carry planner and reference irradiance, viewed error and pops",
          "[viz][views]") {
  const Scenario sc = load_scenario(kDrive);
  const World world(sc.world);
  const auto ref = compute_reference_track(sc, world);

  const Written oracle = run_and_view(sc, world, *ref, "oracle");
  const Written nearest = run_and_view(sc, world, *ref, "nearest");
  REQUIRE(oracle.views.snapshots.size() >= 2);
  int receivers_seen = 0;
  double nearest_largest_de = 0.0;
  for (const Written* w : {&oracle, &nearest}) {
    const bool is_oracle = w == &oracle;
    for (const auto& s : w->views.snapshots) {
      INFO((is_oracle ? "oracle" : "nearest") << " frame " << s.frame);
      REQUIRE(s.light.size() == s.receivers.size());
      auto pd = receivers_of(w->dir, s.frame);
      REQUIRE(pd->GetNumberOfPoints() == static_cast<vtkIdType>(s.receivers.size()));
      vtkPointData* a = pd->GetPointData();
      for (const char* name :
           {"planner_up", "reference_up", "planner_view", "reference_view", "planner_view_rgb",
            "reference_view_rgb", "de2000_view", "viewed_pop"}) {
        INFO(name);
        REQUIRE(a->GetArray(name) != nullptr);
      }
      for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i) {
        ++receivers_seen;
        const Rgb pu = tuple3(a->GetArray("planner_up"), i);
        const Rgb ru = tuple3(a->GetArray("reference_up"), i);
        const Rgb pv = tuple3(a->GetArray("planner_view"), i);
        const Rgb rv = tuple3(a->GetArray("reference_view"), i);
        const double de = a->GetArray("de2000_view")->GetTuple1(i);
        // The sky lights every receiver from above.
        CHECK(ru.x + ru.y + ru.z > 0.0f);
        // The error is the displayed difference of the two colours toward the camera.
        CHECK(de == Approx(ciede2000(display_lab(pv, w->exposure), display_lab(rv, w->exposure)))
                        .margin(1e-3));
        // The displayed colours are those irradiances tone-mapped with the run's exposure.
        const auto shown = to_srgb8(rv, w->exposure);
        for (int c = 0; c < 3; ++c) {
          CHECK(a->GetArray("reference_view_rgb")->GetComponent(i, c) ==
                Approx(static_cast<double>(shown[static_cast<std::size_t>(c)])).margin(1.0));
        }
        if (is_oracle) {
          // The oracle is served the reference itself: nothing differs, nothing pops.
          CHECK(pu == ru);
          CHECK(pv == rv);
          CHECK(de == 0.0);
          CHECK(a->GetArray("viewed_pop")->GetTuple1(i) == 0.0);
        } else {
          nearest_largest_de = std::max(nearest_largest_de, de);
        }
      }
    }
  }
  CHECK(receivers_seen > 4);
  // A planner that is not the reference is visibly off somewhere: the arrays are not copies.
  CHECK(nearest_largest_de > 0.5);

  // The .pvd timesteps are the snapshots' simulated seconds, not frame numbers.
  std::ifstream in(nearest.dir / "views" / "receivers.pvd");
  std::stringstream text;
  text << in.rdbuf();
  const std::string pvd = text.str();
  const std::regex step("timestep=\"([^\"]+)\"");
  std::vector<double> steps;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), step); it != std::sregex_iterator();
       ++it) {
    steps.push_back(std::stod((*it)[1].str()));
  }
  REQUIRE(steps.size() == nearest.views.snapshots.size());
  for (std::size_t k = 0; k < steps.size(); ++k) {
    CHECK(steps[k] == Approx(nearest.views.snapshots[k].time));
  }
  CHECK(nearest.views.snapshots.back().frame > 1);
  CHECK(steps.back() < nearest.views.snapshots.back().frame);
  fs::remove_all(oracle.dir);
  fs::remove_all(nearest.dir);
}
