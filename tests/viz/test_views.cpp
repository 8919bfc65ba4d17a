// `ambisim viz` outputs read back with VTK's XML readers and checked against the views.json
// they came from; PNG snapshots must show a scene (many colours).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <vtkCellData.h>
#include <vtkCellTypes.h>
#include <vtkDataArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStructuredGrid.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLStructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <nlohmann/json.hpp>

#include "sim/base/input_error.h"
#include "sim/base/json_reader.h"
#include "tests/viz/image_checks.h"
#include "viz/png_writer.h"
#include "viz/views.h"

namespace fs = std::filesystem;
using nlohmann::json;

using ambisim::test::distinct_colours;

namespace {

fs::path fresh_dir(const std::string& name) {
  const auto dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_file(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

json sh_of(double r, double g, double b) {
  json sh = json::array();
  sh.push_back({r, g, b});
  for (int k = 1; k < 9; ++k) sh.push_back({0.0, k == 2 ? 0.3 * g : 0.0, 0.0});
  return sh;
}

json node(std::array<double, 3> c, double h, int depth, bool data, bool flight, double age,
          json sh) {
  return {{"c", c},           {"h", {h, h, h * 0.5}}, {"depth", depth}, {"data", data},
          {"flight", flight}, {"age", age},           {"sh", sh}};
}

// A synthetic run directory on the small test world: two snapshots, bare probes and cells.
fs::path make_run_dir() {
  const auto dir = fresh_dir("ambisim_test_views");
  json doc =
      ambisim::load_json_file(std::string(AMBISIM_SOURCE_DIR) + "/tests/data/small_drive.json");
  doc["world"]["size_m"] = {256, 256};
  json result = {{"format", "ambisim-run"},
                 {"scenario", {{"name", "small_drive"}, {"document", doc}}},
                 {"planner", {{"name", "synthetic"}, {"params", json::object()}}}};
  json path = json::array();
  json times = json::array();
  for (int f = 0; f < 40; ++f) {
    path.push_back({60.0 + 2.0 * f, 120.0 + 0.5 * f, 95.0});
    times.push_back(f / 20.0);
  }
  result["series"] = {{"time", times}};
  json s0 = {{"frame", 0},
             {"time", 0.0},
             {"camera", path[0]},
             {"nodes",
              {node({60, 120, 95}, 0, 0, true, false, 0.5, sh_of(1.5, 1.2, 1.0)),
               node({70, 122, 95}, 0, 0, false, true, 0.0, sh_of(0, 0, 0)),
               node({80, 124, 96}, 16, 1, true, false, 2.0, sh_of(0.4, 0.9, 2.0))}},
             {"receivers", {{61, 121, 94}}}};
  json s1 = {{"frame", 20},
             {"time", 1.0},
             {"camera", path[20]},
             {"nodes",
              {node({100, 130, 95}, 0, 0, true, false, 0.1, sh_of(2.0, 1.0, 0.5)),
               node({110, 130, 95}, 8, 2, true, false, 0.3, sh_of(0.3, 1.5, 0.3)),
               node({90, 126, 95}, 27, 1, true, true, 1.2, sh_of(1.0, 1.0, 3.0)),
               node({95, 126, 99}, 0, 0, true, false, 4.0, sh_of(0.8, 0.8, 0.8))}},
             {"receivers", {{101, 131, 94}, {108, 128, 94}}}};
  json views = {{"format", "ambisim-views"},
                {"exposure", 0.25},
                {"camera_path", path},
                {"snapshots", {s0, s1}}};
  write_file(dir / "result.json", result.dump());
  write_file(dir / "views.json", views.dump());
  return dir;
}

int count_datasets(const fs::path& pvd, std::vector<std::string>* files) {
  std::ifstream in(pvd);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  int n = 0;
  for (std::size_t at = text.find("file=\""); at != std::string::npos;
       at = text.find("file=\"", at + 1)) {
    const std::size_t b = at + 6, e = text.find('"', b);
    files->push_back(text.substr(b, e - b));
    ++n;
  }
  return n;
}

}  // namespace

TEST_CASE("viz writes ParaView files matching views.json, and PNG snapshots", "[viz][views]") {
  const fs::path dir = make_run_dir();
  ambisim::ViewsOptions opt;
  opt.width = 480;
  opt.height = 320;
  opt.terrain_max_points = 64;
  const auto written = ambisim::write_run_views(dir.string(), opt);
  const fs::path out = dir / "views";
  for (const auto& f : written) CHECK(fs::is_regular_file(f));

  const ambisim::RunViews v = ambisim::load_views((dir / "views.json").string());
  REQUIRE(v.snapshots.size() == 2);

  for (const char* kind : {"nodes", "cells", "receivers"}) {
    std::vector<std::string> files;
    CHECK(count_datasets(out / (std::string(kind) + ".pvd"), &files) == 2);
    for (const auto& f : files) CHECK(fs::is_regular_file(out / f));
  }

  for (const auto& s : v.snapshots) {
    char tag[16];
    std::snprintf(tag, sizeof tag, "f%06d", s.frame);
    // Nodes: one point (and vertex) per node with its arrays.
    vtkNew<vtkXMLPolyDataReader> nr;
    nr->SetFileName((out / (std::string("nodes_") + tag + ".vtp")).c_str());
    nr->Update();
    vtkPolyData* nodes = nr->GetOutput();
    REQUIRE(nodes->GetNumberOfPoints() == static_cast<vtkIdType>(s.nodes.size()));
    CHECK(nodes->GetNumberOfVerts() == static_cast<vtkIdType>(s.nodes.size()));
    auto* rgb = vtkUnsignedCharArray::SafeDownCast(nodes->GetPointData()->GetArray("ambient_rgb"));
    REQUIRE(rgb != nullptr);
    CHECK(rgb->GetNumberOfComponents() == 3);
    auto* depth = nodes->GetPointData()->GetArray("depth");
    auto* age = nodes->GetPointData()->GetArray("age_s");
    auto* flight = nodes->GetPointData()->GetArray("in_flight");
    REQUIRE(depth != nullptr);
    REQUIRE(age != nullptr);
    REQUIRE(flight != nullptr);
    for (std::size_t i = 0; i < s.nodes.size(); ++i) {
      const auto id = static_cast<vtkIdType>(i);
      const auto& n = s.nodes[i];
      double p[3];
      nodes->GetPoint(id, p);
      CHECK(p[0] == Approx(n.centre.x));
      CHECK(p[2] == Approx(n.centre.z));
      const auto want = ambisim::ambient_colour(n.sh, v.exposure);
      for (int c = 0; c < 3; ++c)
        CHECK(rgb->GetTypedComponent(id, c) == want[static_cast<std::size_t>(c)]);
      CHECK(depth->GetTuple1(id) == n.depth);
      CHECK(age->GetTuple1(id) == Approx(n.age_s));
      CHECK(flight->GetTuple1(id) == (n.in_flight ? 1 : 0));
    }
    // Cells: one hexahedron per node with a half extent, spanning centre +- half extent.
    vtkNew<vtkXMLUnstructuredGridReader> cr;
    cr->SetFileName((out / (std::string("cells_") + tag + ".vtu")).c_str());
    cr->Update();
    vtkUnstructuredGrid* cells = cr->GetOutput();
    std::vector<const ambisim::ViewNode*> boxed;
    for (const auto& n : s.nodes) {
      if (n.half_extent.x > 0) boxed.push_back(&n);
    }
    REQUIRE(cells->GetNumberOfCells() == static_cast<vtkIdType>(boxed.size()));
    for (std::size_t i = 0; i < boxed.size(); ++i) {
      const auto id = static_cast<vtkIdType>(i);
      CHECK(cells->GetCellType(id) == VTK_HEXAHEDRON);
      double b[6];
      cells->GetCell(id)->GetBounds(b);
      CHECK(b[0] == Approx(boxed[i]->centre.x - boxed[i]->half_extent.x));
      CHECK(b[5] == Approx(boxed[i]->centre.z + boxed[i]->half_extent.z));
      CHECK(cells->GetCellData()->GetArray("depth")->GetTuple1(id) == boxed[i]->depth);
    }
    CHECK(cells->GetCellData()->GetArray("ambient_rgb") != nullptr);
    // Receivers.
    vtkNew<vtkXMLPolyDataReader> rr;
    rr->SetFileName((out / (std::string("receivers_") + tag + ".vtp")).c_str());
    rr->Update();
    CHECK(rr->GetOutput()->GetNumberOfPoints() == static_cast<vtkIdType>(s.receivers.size()));
  }

  // Camera path: one polyline through every frame.
  vtkNew<vtkXMLPolyDataReader> pr;
  pr->SetFileName((out / "camera_path.vtp").c_str());
  pr->Update();
  CHECK(pr->GetOutput()->GetNumberOfPoints() == static_cast<vtkIdType>(v.camera_path.size()));
  CHECK(pr->GetOutput()->GetNumberOfLines() == 1);
  CHECK(pr->GetOutput()->GetPointData()->GetArray("time_s")->GetTuple1(20) == Approx(1.0));

  // Terrain: a structured surface with albedo colours, not flat, not one colour.
  vtkNew<vtkXMLStructuredGridReader> tr;
  tr->SetFileName((out / "terrain.vts").c_str());
  tr->Update();
  vtkStructuredGrid* terrain = tr->GetOutput();
  int dims[3];
  terrain->GetDimensions(dims);
  CHECK(dims[0] >= 32);
  CHECK(dims[0] <= 64);
  CHECK(dims[2] == 1);
  auto* albedo =
      vtkUnsignedCharArray::SafeDownCast(terrain->GetPointData()->GetArray("albedo_rgb"));
  REQUIRE(albedo != nullptr);
  CHECK(albedo->GetNumberOfTuples() == terrain->GetNumberOfPoints());

  // Default snapshots: first, middle, last (two distinct here), each showing a scene.
  for (const char* f : {"snapshot_f000000.png", "snapshot_f000020.png"}) {
    REQUIRE(fs::is_regular_file(out / f));
    const auto img = ambisim::read_png((out / f).string());
    CHECK(img.width == 480);
    CHECK(distinct_colours(img) > 200);
  }

  // No overwrite without permission, and nothing is written by the refused call.
  const auto before = fs::last_write_time(out / "nodes.pvd");
  CHECK_THROWS_AS(ambisim::write_run_views(dir.string(), opt), ambisim::InputError);
  CHECK(fs::last_write_time(out / "nodes.pvd") == before);
  fs::remove_all(dir);
}

TEST_CASE("viz picks the nearest snapshot for --frames and rejects bad input", "[viz][views]") {
  const fs::path dir = make_run_dir();
  ambisim::ViewsOptions opt;
  opt.width = 320;
  opt.height = 200;
  opt.terrain_max_points = 32;
  opt.frames = {17};
  ambisim::write_run_views(dir.string(), opt);
  CHECK(fs::is_regular_file(dir / "views" / "snapshot_f000020.png"));
  CHECK_FALSE(fs::exists(dir / "views" / "snapshot_f000000.png"));
  opt.overwrite = ambisim::Overwrite::allow;
  opt.frames = {400};
  CHECK_THROWS_AS(ambisim::write_run_views(dir.string(), opt), ambisim::InputError);

  try {
    ambisim::write_run_views((dir / "nope").string(), opt);
    FAIL("no error for a missing directory");
  } catch (const ambisim::InputError& e) {
    CHECK(std::string(e.what()).find("nope") != std::string::npos);
  }
  fs::remove(dir / "views.json");
  try {
    ambisim::write_run_views(dir.string(), opt);
    FAIL("no error for a missing views.json");
  } catch (const ambisim::InputError& e) {
    CHECK(std::string(e.what()).find("views.json") != std::string::npos);
  }
  write_file(dir / "views.json", R"({"format": "ambisim-views", "exposure": 1, "camera_path": [],
    "snapshots": [{"frame": 0, "time": 0, "camera": [0, 0], "nodes": [], "receivers": []}]})");
  try {
    ambisim::load_views((dir / "views.json").string());
    FAIL("no error for a bad camera");
  } catch (const ambisim::InputError& e) {
    CHECK(std::string(e.what()).find("/snapshots/0/camera") != std::string::npos);
  }
  fs::remove_all(dir);
}
