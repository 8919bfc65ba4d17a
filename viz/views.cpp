#include "viz/views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkConeSource.h>
#include <vtkCubeSource.h>
#include <vtkDataSetMapper.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkHexahedron.h>
#include <vtkIntArray.h>
#include <vtkLight.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkStructuredGrid.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLStructuredGridWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "sim/base/input_error.h"
#include "sim/base/json_reader.h"
#include "sim/colour/cielab.h"
#include "sim/colour/tone_map.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "viz/render_capture.h"

namespace fs = std::filesystem;

namespace ambisim {
namespace {

// --- views.json ---------------------------------------------------------------------------

struct JsonCtx {
  const std::string& file;
  [[noreturn]] void fail(const std::string& pointer, const std::string& msg) const {
    throw InputError(file, pointer, msg);
  }
  const nlohmann::json& member(const nlohmann::json& o, const std::string& pointer,
                               const char* key) const {
    if (!o.is_object()) fail(pointer, "must be an object");
    auto it = o.find(key);
    if (it == o.end()) fail(pointer + "/" + key, "missing");
    return *it;
  }
  double number(const nlohmann::json& v, const std::string& pointer) const {
    if (!v.is_number()) fail(pointer, "must be a number");
    return v.get<double>();
  }
  glm::dvec3 vec3(const nlohmann::json& v, const std::string& pointer) const {
    if (!v.is_array() || v.size() != 3) fail(pointer, "must be an array of 3 numbers");
    glm::dvec3 out;
    for (int i = 0; i < 3; ++i)
      out[i] = number(v[static_cast<std::size_t>(i)], pointer + "/" + std::to_string(i));
    return out;
  }
  const nlohmann::json& array(const nlohmann::json& o, const std::string& pointer,
                              const char* key) const {
    const auto& a = member(o, pointer, key);
    if (!a.is_array()) fail(pointer + "/" + key, "must be an array");
    return a;
  }
};

std::string frame_tag(int frame) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "f%06d", frame);
  return buf;
}

// --- VTK data sets -------------------------------------------------------------------------

vtkSmartPointer<vtkUnsignedCharArray> rgb_array(const char* name) {
  auto a = vtkSmartPointer<vtkUnsignedCharArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  return a;
}

template <class A>
vtkSmartPointer<A> named(const char* name, int comps = 1) {
  auto a = vtkSmartPointer<A>::New();
  a->SetName(name);
  a->SetNumberOfComponents(comps);
  return a;
}

struct NodeArrays {
  vtkSmartPointer<vtkUnsignedCharArray> rgb = rgb_array("ambient_rgb");
  vtkSmartPointer<vtkIntArray> depth = named<vtkIntArray>("depth");
  vtkSmartPointer<vtkFloatArray> age = named<vtkFloatArray>("age_s");
  vtkSmartPointer<vtkUnsignedCharArray> flight = named<vtkUnsignedCharArray>("in_flight");
  vtkSmartPointer<vtkUnsignedCharArray> data = named<vtkUnsignedCharArray>("has_data");
  vtkSmartPointer<vtkFloatArray> half = named<vtkFloatArray>("half_extent_m", 3);

  void add(const ViewNode& n, double exposure) {
    const auto c = ambient_colour(n.sh, exposure);
    rgb->InsertNextTypedTuple(c.data());
    depth->InsertNextValue(n.depth);
    age->InsertNextValue(static_cast<float>(n.age_s));
    flight->InsertNextValue(n.in_flight ? 1 : 0);
    data->InsertNextValue(n.has_data ? 1 : 0);
    const float h[3] = {static_cast<float>(n.half_extent.x), static_cast<float>(n.half_extent.y),
                        static_cast<float>(n.half_extent.z)};
    half->InsertNextTypedTuple(h);
  }
  void attach(vtkDataSetAttributes* attrs) {
    attrs->AddArray(rgb);
    attrs->SetScalars(rgb);
    attrs->AddArray(depth);
    attrs->AddArray(age);
    attrs->AddArray(flight);
    attrs->AddArray(data);
    attrs->AddArray(half);
  }
};

vtkSmartPointer<vtkPolyData> points_with_verts(const std::vector<glm::dvec3>& pts) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> verts;
  for (const auto& p : pts) {
    const vtkIdType id = points->InsertNextPoint(p.x, p.y, p.z);
    verts->InsertNextCell(1, &id);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetVerts(verts);
  return pd;
}

vtkSmartPointer<vtkPolyData> nodes_polydata(const ViewSnapshot& s, double exposure) {
  std::vector<glm::dvec3> pts;
  for (const auto& n : s.nodes) pts.push_back(n.centre);
  auto pd = points_with_verts(pts);
  NodeArrays arrays;
  for (const auto& n : s.nodes) arrays.add(n, exposure);
  arrays.attach(pd->GetPointData());
  return pd;
}

bool has_cell(const ViewNode& n) {
  return n.half_extent.x > 0.0 || n.half_extent.y > 0.0 || n.half_extent.z > 0.0;
}

vtkSmartPointer<vtkUnstructuredGrid> cells_grid(const ViewSnapshot& s, double exposure) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->Allocate();
  NodeArrays arrays;
  // VTK hexahedron order: bottom face counter-clockwise, then the top face.
  constexpr int kCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (const auto& n : s.nodes) {
    if (!has_cell(n)) continue;
    vtkIdType ids[8];
    for (int k = 0; k < 8; ++k) {
      ids[k] = points->InsertNextPoint(n.centre.x + kCorner[k][0] * n.half_extent.x,
                                       n.centre.y + kCorner[k][1] * n.half_extent.y,
                                       n.centre.z + kCorner[k][2] * n.half_extent.z);
    }
    grid->InsertNextCell(VTK_HEXAHEDRON, 8, ids);
    arrays.add(n, exposure);
  }
  grid->SetPoints(points);
  arrays.attach(grid->GetCellData());
  return grid;
}

vtkSmartPointer<vtkPolyData> receivers_polydata(const ViewSnapshot& s, double exposure) {
  auto pd = points_with_verts(s.receivers);
  auto snap = named<vtkIntArray>("snapshot_frame");
  for (std::size_t i = 0; i < s.receivers.size(); ++i) snap->InsertNextValue(s.frame);
  pd->GetPointData()->AddArray(snap);
  if (s.light.size() == s.receivers.size() && !s.light.empty()) {
    auto linear = [&](const char* name, glm::dvec3 ViewReceiverLight::*field) {
      auto a = named<vtkFloatArray>(name, 3);
      for (const auto& l : s.light) {
        const glm::dvec3& v = l.*field;
        const float t[3] = {static_cast<float>(v.x), static_cast<float>(v.y),
                            static_cast<float>(v.z)};
        a->InsertNextTypedTuple(t);
      }
      pd->GetPointData()->AddArray(a);
    };
    linear("planner_up", &ViewReceiverLight::planner_up);
    linear("reference_up", &ViewReceiverLight::reference_up);
    linear("planner_view", &ViewReceiverLight::planner_view);
    linear("reference_view", &ViewReceiverLight::reference_view);
    auto shown = [&](const char* name, glm::dvec3 ViewReceiverLight::*field) {
      auto a = rgb_array(name);
      for (const auto& l : s.light) {
        const auto c = to_srgb8(Rgb(l.*field), exposure);
        const unsigned char t[3] = {c[0], c[1], c[2]};
        a->InsertNextTypedTuple(t);
      }
      pd->GetPointData()->AddArray(a);
    };
    shown("planner_view_rgb", &ViewReceiverLight::planner_view);
    shown("reference_view_rgb", &ViewReceiverLight::reference_view);
    auto de = named<vtkFloatArray>("de2000_view");
    auto pop = named<vtkIntArray>("viewed_pop");
    for (const auto& l : s.light) {
      de->InsertNextValue(static_cast<float>(l.de2000_view));
      pop->InsertNextValue(l.viewed_pop ? 1 : 0);
    }
    pd->GetPointData()->AddArray(de);
    pd->GetPointData()->AddArray(pop);
  }
  return pd;
}

vtkSmartPointer<vtkPolyData> camera_path_polydata(const RunViews& v,
                                                  const std::vector<double>& times) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  auto frame = named<vtkIntArray>("frame");
  auto time = named<vtkDoubleArray>("time_s");
  std::vector<vtkIdType> ids;
  for (std::size_t i = 0; i < v.camera_path.size(); ++i) {
    const auto& p = v.camera_path[i];
    ids.push_back(points->InsertNextPoint(p.x, p.y, p.z));
    frame->InsertNextValue(static_cast<int>(i));
    time->InsertNextValue(i < times.size() ? times[i] : std::nan(""));
  }
  vtkNew<vtkCellArray> lines;
  if (ids.size() >= 2) lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetLines(lines);
  pd->GetPointData()->AddArray(frame);
  pd->GetPointData()->AddArray(time);
  return pd;
}

std::array<unsigned char, 3> albedo_srgb(const Rgb& a) {
  return {quantise_8bit(srgb_encode(a.x)), quantise_8bit(srgb_encode(a.y)),
          quantise_8bit(srgb_encode(a.z))};
}

// Samples of the surface on a regular grid over [lo, hi] with `n` points per axis.
struct TerrainSamples {
  int nx = 0, ny = 0;
  glm::dvec2 lo{0.0}, step{1.0};
  std::vector<double> z;
  std::vector<std::array<unsigned char, 3>> rgb;
  std::vector<int> biome;
  std::vector<std::array<unsigned char, 3>> quad_rgb;  // albedo at quad centres (rendering)
  double at(int i, int j) const { return z[static_cast<std::size_t>(j) * nx + i]; }
};

TerrainSamples sample_terrain(const World& w, glm::dvec2 lo, glm::dvec2 hi, int max_points,
                              bool quad_colours = false) {
  TerrainSamples t;
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  double step = std::max(w.cell_m(), extent / std::max(1, max_points - 1));
  step = w.cell_m() * std::ceil(step / w.cell_m() - 1e-9);
  t.nx = std::max(2, static_cast<int>(std::floor((hi.x - lo.x) / step)) + 1);
  t.ny = std::max(2, static_cast<int>(std::floor((hi.y - lo.y) / step)) + 1);
  t.lo = lo;
  t.step = {step, step};
  t.z.resize(static_cast<std::size_t>(t.nx) * t.ny);
  t.rgb.resize(t.z.size());
  t.biome.resize(t.z.size());
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      const double x = lo.x + i * step, y = lo.y + j * step;
      const std::size_t k = static_cast<std::size_t>(j) * t.nx + i;
      t.z[k] = w.surface_height(x, y);
      t.rgb[k] = albedo_srgb(w.albedo_at(x, y));
      t.biome[k] = static_cast<int>(w.biome_at(x, y));
    }
  }
  if (quad_colours) {
    for (int j = 0; j + 1 < t.ny; ++j) {
      for (int i = 0; i + 1 < t.nx; ++i) {
        t.quad_rgb.push_back(
            albedo_srgb(w.albedo_at(lo.x + (i + 0.5) * step, lo.y + (j + 0.5) * step)));
      }
    }
  }
  return t;
}

vtkSmartPointer<vtkStructuredGrid> terrain_grid(const TerrainSamples& t) {
  vtkNew<vtkPoints> points;
  auto rgb = rgb_array("albedo_rgb");
  auto height = named<vtkFloatArray>("height_m");
  auto biome = named<vtkIntArray>("biome");
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * t.nx + i;
      points->InsertNextPoint(t.lo.x + i * t.step.x, t.lo.y + j * t.step.y, t.z[k]);
      rgb->InsertNextTypedTuple(t.rgb[k].data());
      height->InsertNextValue(static_cast<float>(t.z[k]));
      biome->InsertNextValue(t.biome[k]);
    }
  }
  auto grid = vtkSmartPointer<vtkStructuredGrid>::New();
  grid->SetDimensions(t.nx, t.ny, 1);
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(rgb);
  grid->GetPointData()->SetScalars(rgb);
  grid->GetPointData()->AddArray(height);
  grid->GetPointData()->AddArray(biome);
  return grid;
}

// Renderable terrain: quads with smooth normals from the samples.
vtkSmartPointer<vtkPolyData> terrain_surface(const TerrainSamples& t) {
  vtkNew<vtkPoints> points;
  auto rgb = rgb_array("albedo_rgb");
  auto normals = named<vtkFloatArray>("normals", 3);
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * t.nx + i;
      points->InsertNextPoint(t.lo.x + i * t.step.x, t.lo.y + j * t.step.y, t.z[k]);
      rgb->InsertNextTypedTuple(t.rgb[k].data());
      const int i0 = std::max(0, i - 1), i1 = std::min(t.nx - 1, i + 1);
      const int j0 = std::max(0, j - 1), j1 = std::min(t.ny - 1, j + 1);
      const double dzdx = (t.at(i1, j) - t.at(i0, j)) / ((i1 - i0) * t.step.x);
      const double dzdy = (t.at(i, j1) - t.at(i, j0)) / ((j1 - j0) * t.step.y);
      const glm::dvec3 n = glm::normalize(glm::dvec3(-dzdx, -dzdy, 1.0));
      const float nf[3] = {static_cast<float>(n.x), static_cast<float>(n.y),
                           static_cast<float>(n.z)};
      normals->InsertNextTypedTuple(nf);
    }
  }
  vtkNew<vtkCellArray> quads;
  for (int j = 0; j + 1 < t.ny; ++j) {
    for (int i = 0; i + 1 < t.nx; ++i) {
      const vtkIdType a = static_cast<vtkIdType>(j) * t.nx + i;
      const vtkIdType q[4] = {a, a + 1, a + 1 + t.nx, a + t.nx};
      quads->InsertNextCell(4, q);
    }
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(quads);
  pd->GetPointData()->SetScalars(rgb);
  if (!t.quad_rgb.empty()) {
    auto qrgb = rgb_array("albedo_rgb");
    for (const auto& c : t.quad_rgb) qrgb->InsertNextTypedTuple(c.data());
    pd->GetCellData()->SetScalars(qrgb);
  }
  pd->GetPointData()->SetNormals(normals);
  return pd;
}

template <class Writer, class Data>
void write_xml(const std::string& path, Data* data, Overwrite overwrite) {
  write_atomically(path, overwrite, [&](const std::string& tmp) {
    vtkNew<Writer> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(data);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    if (writer->Write() != 1) throw InputError(path, "", "VTK XML write failed");
  });
}

std::string pvd_text(const std::vector<std::pair<double, std::string>>& entries) {
  std::ostringstream o;
  o.precision(17);
  o << "<?xml version=\"1.0\"?>\n"
       "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       "  <Collection>\n";
  for (const auto& [t, f] : entries) {
    o << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << f << "\"/>\n";
  }
  o << "  </Collection>\n</VTKFile>\n";
  return o.str();
}

// --- rendering -----------------------------------------------------------------------------

struct SceneContext {
  const RunViews& views;
  const World& world;
  std::string heading;  // scenario / planner
};

glm::dvec3 forward_at(const RunViews& v, int frame) {
  const int n = static_cast<int>(v.camera_path.size());
  if (n >= 2) {
    for (int span : {15, 60, 240}) {
      const int a = std::clamp(frame - span / 3, 0, n - 1);
      const int b = std::clamp(frame + span, 0, n - 1);
      glm::dvec3 d =
          v.camera_path[static_cast<std::size_t>(b)] - v.camera_path[static_cast<std::size_t>(a)];
      d.z = 0.0;
      if (glm::length(d) > 0.5) return glm::normalize(d);
    }
  }
  return {0.0, 1.0, 0.0};
}

void add_text(vtkRenderer* r, const std::string& text, double x, double y, int size, bool bold,
              bool top) {
  vtkNew<vtkTextActor> a;
  a->SetInput(text.c_str());
  a->GetTextProperty()->SetFontSize(size);
  a->GetTextProperty()->SetBold(bold);
  a->GetTextProperty()->SetColor(1.0, 1.0, 1.0);
  a->GetTextProperty()->SetShadow(1);
  a->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
  a->GetTextProperty()->SetBackgroundOpacity(0.45);
  if (top) a->GetTextProperty()->SetVerticalJustificationToTop();
  a->SetPosition(x, y);
  r->AddActor2D(a);
}

void render_snapshot(const SceneContext& ctx, const ViewSnapshot& s, const std::string& path,
                     const ViewsOptions& o) {
  const RunViews& v = ctx.views;
  const glm::dvec3 cam = s.camera;
  const glm::dvec3 fwd = forward_at(v, s.frame);
  // Scene scale: 50 m, or enough to see the third-nearest probe with data (at most 120 m).
  std::vector<double> dist;
  for (const auto& n : s.nodes) {
    if (n.has_data) dist.push_back(glm::length(glm::dvec2(n.centre.x - cam.x, n.centre.y - cam.y)));
  }
  std::sort(dist.begin(), dist.end());
  const double reach =
      dist.empty() ? 50.0
                   : std::clamp(1.5 * dist[std::min<std::size_t>(2, dist.size() - 1)], 50.0, 120.0);
  const glm::dvec3 eye = cam - fwd * (0.9 * reach) + glm::dvec3(0, 0, 0.75 * reach);
  const glm::dvec3 focus = cam + fwd * (0.45 * reach);

  vtkNew<vtkRenderer> ren;
  ren->GradientBackgroundOn();
  ren->SetBackground(0.82, 0.88, 0.95);   // horizon
  ren->SetBackground2(0.38, 0.58, 0.85);  // zenith

  // Terrain: a patch around the view, clamped to the world.
  const double half = std::max(600.0, 8.0 * reach);
  const glm::dvec2 c2(focus.x + fwd.x * 0.6 * half, focus.y + fwd.y * 0.6 * half);
  glm::dvec2 lo = glm::max(c2 - glm::dvec2(half), ctx.world.min_xy());
  glm::dvec2 hi = glm::min(c2 + glm::dvec2(half), ctx.world.max_xy());
  if (hi.x <= lo.x || hi.y <= lo.y) {
    lo = ctx.world.min_xy();
    hi = ctx.world.max_xy();
  }
  const TerrainSamples ts = sample_terrain(ctx.world, lo, hi, 480, true);
  vtkNew<vtkPolyDataMapper> tmap;
  tmap->SetInputData(terrain_surface(ts));
  tmap->SetColorModeToDirectScalars();
  tmap->SetScalarModeToUseCellData();
  vtkNew<vtkActor> terrain;
  terrain->SetMapper(tmap);
  terrain->GetProperty()->SetAmbient(0.35);
  terrain->GetProperty()->SetDiffuse(0.75);
  terrain->GetProperty()->SetSpecular(0.0);
  ren->AddActor(terrain);

  // Probes with data: spheres in their ambient colour; nodes without data: small dark dots.
  const double radius = std::clamp(reach / 45.0, 0.6, 3.0);
  for (const bool with_data : {true, false}) {
    ViewSnapshot part;
    for (const auto& n : s.nodes) {
      if (n.has_data == with_data) part.nodes.push_back(n);
    }
    if (part.nodes.empty()) continue;
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(with_data ? radius : 0.3 * radius);
    sphere->SetThetaResolution(24);
    sphere->SetPhiResolution(16);
    vtkNew<vtkGlyph3DMapper> pmap;
    pmap->SetInputData(nodes_polydata(part, v.exposure));
    pmap->SetSourceConnection(sphere->GetOutputPort());
    pmap->ScalingOff();
    pmap->OrientOff();
    pmap->SetColorModeToDirectScalars();
    pmap->SetScalarModeToUsePointFieldData();
    pmap->SelectColorArray("ambient_rgb");
    if (!with_data) pmap->ScalarVisibilityOff();
    vtkNew<vtkActor> probes;
    probes->SetMapper(pmap);
    probes->GetProperty()->SetColor(0.15, 0.15, 0.15);
    probes->GetProperty()->SetAmbient(0.55);
    probes->GetProperty()->SetDiffuse(0.5);
    probes->GetProperty()->SetSpecular(0.25);
    probes->GetProperty()->SetSpecularPower(30);
    ren->AddActor(probes);
  }

  // Node cells as wireframes coloured by depth.
  auto cells = cells_grid(s, v.exposure);
  if (cells->GetNumberOfCells() > 0) {
    int max_depth = 0;
    for (const auto& n : s.nodes) max_depth = std::max(max_depth, n.depth);
    vtkNew<vtkLookupTable> lut;
    lut->SetHueRange(0.66, 0.0);
    lut->SetSaturationRange(0.9, 0.9);
    lut->SetValueRange(1.0, 1.0);
    lut->SetTableRange(0, std::max(1, max_depth));
    lut->Build();
    vtkNew<vtkDataSetMapper> cmap;
    cmap->SetInputData(cells);
    cmap->SetScalarModeToUseCellFieldData();
    cmap->SelectColorArray("depth");
    cmap->SetLookupTable(lut);
    cmap->UseLookupTableScalarRangeOn();
    vtkNew<vtkActor> wire;
    wire->SetMapper(cmap);
    wire->GetProperty()->SetRepresentationToWireframe();
    wire->GetProperty()->SetLineWidth(1.5f);
    wire->GetProperty()->SetOpacity(0.7);
    wire->GetProperty()->LightingOff();
    ren->AddActor(wire);
  }

  // Camera path and the camera itself.
  auto path_pd = camera_path_polydata(v, {});
  vtkNew<vtkPolyDataMapper> lmap;
  lmap->SetInputData(path_pd);
  lmap->ScalarVisibilityOff();
  vtkNew<vtkActor> path_actor;
  path_actor->SetMapper(lmap);
  path_actor->GetProperty()->SetColor(1.0, 0.45, 0.0);
  path_actor->GetProperty()->SetLineWidth(4.0f);
  path_actor->GetProperty()->RenderLinesAsTubesOn();
  path_actor->GetProperty()->LightingOff();
  ren->AddActor(path_actor);

  vtkNew<vtkConeSource> cone;
  cone->SetHeight(3.0 * radius);
  cone->SetRadius(1.1 * radius);
  cone->SetResolution(24);
  cone->SetCenter(cam.x, cam.y, cam.z);
  cone->SetDirection(fwd.x, fwd.y, fwd.z);
  vtkNew<vtkPolyDataMapper> cone_map;
  cone_map->SetInputConnection(cone->GetOutputPort());
  vtkNew<vtkActor> cone_actor;
  cone_actor->SetMapper(cone_map);
  cone_actor->GetProperty()->SetColor(0.9, 0.1, 0.1);
  cone_actor->GetProperty()->SetAmbient(0.4);
  ren->AddActor(cone_actor);

  // Receivers: small yellow cubes.
  auto recv = receivers_polydata(s, ctx.views.exposure);
  vtkNew<vtkCubeSource> cube;
  cube->SetXLength(1.2 * radius);
  cube->SetYLength(1.2 * radius);
  cube->SetZLength(1.2 * radius);
  vtkNew<vtkGlyph3DMapper> rmap;
  rmap->SetInputData(recv);
  rmap->SetSourceConnection(cube->GetOutputPort());
  rmap->ScalingOff();
  rmap->OrientOff();
  rmap->ScalarVisibilityOff();
  vtkNew<vtkActor> recv_actor;
  recv_actor->SetMapper(rmap);
  recv_actor->GetProperty()->SetColor(1.0, 0.85, 0.1);
  recv_actor->GetProperty()->SetAmbient(0.4);
  ren->AddActor(recv_actor);

  // Light: the sun if it is up, else from above.
  ren->RemoveAllLights();
  glm::dvec3 sun = ctx.world.lighting().sun_dir();
  if (!ctx.world.lighting().sun_on() || sun.z < 0.2)
    sun = glm::normalize(glm::dvec3(-0.3, -0.5, 1.0));
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(sun.x, sun.y, sun.z);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPositional(false);
  light->SetIntensity(0.9);
  ren->AddLight(light);
  vtkNew<vtkLight> fill;
  fill->SetLightTypeToHeadlight();
  fill->SetIntensity(0.3);
  ren->AddLight(fill);

  vtkCamera* camera = ren->GetActiveCamera();
  camera->SetPosition(eye.x, eye.y, eye.z);
  camera->SetFocalPoint(focus.x, focus.y, focus.z);
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetViewAngle(50.0);
  ren->ResetCameraClippingRange();
  camera->SetClippingRange(0.5, 6.0 * half);

  int cell_count = 0, no_data = 0, flight = 0;
  for (const auto& n : s.nodes) {
    cell_count += has_cell(n) ? 1 : 0;
    no_data += n.has_data ? 0 : 1;
    flight += n.in_flight ? 1 : 0;
  }
  char line1[256], line2[256];
  std::snprintf(line1, sizeof line1, "%s   frame %d, t = %.2f s", ctx.heading.c_str(), s.frame,
                s.time);
  std::snprintf(line2, sizeof line2,
                "%zu probe nodes (%d cells, %d in flight, %d without data), %zu receivers",
                s.nodes.size(), cell_count, flight, no_data, s.receivers.size());
  add_text(ren, line1, 12, o.height - 12, 22, true, true);
  add_text(ren, line2, 12, o.height - 46, 17, false, true);
  add_text(ren,
           "spheres: probes (ambient colour)   dots: no data   wireframes: cells by depth   "
           "orange: camera path   red: camera   yellow: receivers",
           12, 10, 15, false, false);

  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetSize(o.width, o.height);
  win->SetMultiSamples(8);
  win->AddRenderer(ren);
  render_window_to_png(win, path, o.overwrite);
}

}  // namespace

std::array<std::uint8_t, 3> ambient_colour(const Sh9Rgb& sh, double exposure) {
  static const glm::dvec3 kAxes[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                      {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  Rgb sum(0.0f);
  for (const auto& a : kAxes) sum += sh_irradiance(sh, a);
  return to_srgb8(sum / 6.0f, exposure);
}

RunViews load_views(const std::string& path) {
  const nlohmann::json j = load_json_file(path);
  const JsonCtx c{path};
  RunViews v;
  if (!j.is_object()) c.fail("", "must be an object");
  if (auto it = j.find("format"); it == j.end() || *it != "ambisim-views") {
    c.fail("/format", "must be \"ambisim-views\"");
  }
  v.exposure = c.number(c.member(j, "", "exposure"), "/exposure");
  const auto& path_arr = c.array(j, "", "camera_path");
  for (std::size_t i = 0; i < path_arr.size(); ++i) {
    v.camera_path.push_back(c.vec3(path_arr[i], "/camera_path/" + std::to_string(i)));
  }
  const auto& snaps = c.array(j, "", "snapshots");
  for (std::size_t i = 0; i < snaps.size(); ++i) {
    const std::string sp = "/snapshots/" + std::to_string(i);
    const auto& sj = snaps[i];
    ViewSnapshot s;
    s.frame = static_cast<int>(c.number(c.member(sj, sp, "frame"), sp + "/frame"));
    s.time = c.number(c.member(sj, sp, "time"), sp + "/time");
    s.camera = c.vec3(c.member(sj, sp, "camera"), sp + "/camera");
    const auto& nodes = c.array(sj, sp, "nodes");
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      const std::string np = sp + "/nodes/" + std::to_string(k);
      const auto& nj = nodes[k];
      ViewNode n;
      n.centre = c.vec3(c.member(nj, np, "c"), np + "/c");
      n.half_extent = c.vec3(c.member(nj, np, "h"), np + "/h");
      n.depth = static_cast<int>(c.number(c.member(nj, np, "depth"), np + "/depth"));
      const auto& data = c.member(nj, np, "data");
      const auto& flight = c.member(nj, np, "flight");
      if (!data.is_boolean()) c.fail(np + "/data", "must be a boolean");
      if (!flight.is_boolean()) c.fail(np + "/flight", "must be a boolean");
      n.has_data = data.get<bool>();
      n.in_flight = flight.get<bool>();
      n.age_s = c.number(c.member(nj, np, "age"), np + "/age");
      const auto& sh = c.array(nj, np, "sh");
      if (sh.size() != static_cast<std::size_t>(kShCount))
        c.fail(np + "/sh", "must hold 9 RGB triples");
      for (int q = 0; q < kShCount; ++q) {
        const glm::dvec3 rgb =
            c.vec3(sh[static_cast<std::size_t>(q)], np + "/sh/" + std::to_string(q));
        n.sh.c[static_cast<std::size_t>(q)] = Rgb(rgb);
      }
      s.nodes.push_back(n);
    }
    const auto& recv = c.array(sj, sp, "receivers");
    for (std::size_t k = 0; k < recv.size(); ++k) {
      s.receivers.push_back(c.vec3(recv[k], sp + "/receivers/" + std::to_string(k)));
    }
    if (sj.contains("light")) {
      const auto& light = c.array(sj, sp, "light");
      if (light.size() != s.receivers.size()) {
        c.fail(sp + "/light", "must hold one entry per receiver");
      }
      for (std::size_t k = 0; k < light.size(); ++k) {
        const std::string lp = sp + "/light/" + std::to_string(k);
        const auto& lj = light[k];
        ViewReceiverLight l;
        l.planner_up = c.vec3(c.member(lj, lp, "pu"), lp + "/pu");
        l.reference_up = c.vec3(c.member(lj, lp, "ru"), lp + "/ru");
        l.planner_view = c.vec3(c.member(lj, lp, "pv"), lp + "/pv");
        l.reference_view = c.vec3(c.member(lj, lp, "rv"), lp + "/rv");
        l.de2000_view = c.number(c.member(lj, lp, "de"), lp + "/de");
        const auto& pop = c.member(lj, lp, "pop");
        if (!pop.is_boolean()) c.fail(lp + "/pop", "must be a boolean");
        l.viewed_pop = pop.get<bool>();
        s.light.push_back(l);
      }
    }
    v.snapshots.push_back(std::move(s));
  }
  return v;
}

std::vector<std::string> write_run_views(const std::string& run_dir, const ViewsOptions& o) {
  if (!fs::is_directory(run_dir))
    throw InputError(run_dir, "", "not a directory (expected a run output)");
  const std::string views_path = (fs::path(run_dir) / "views.json").string();
  const std::string result_path = (fs::path(run_dir) / "result.json").string();
  if (!fs::is_regular_file(views_path))
    throw InputError(views_path, "", "missing: not a run output directory");
  if (!fs::is_regular_file(result_path))
    throw InputError(result_path, "", "missing: not a run output directory");
  const RunViews v = load_views(views_path);
  if (v.snapshots.empty()) throw InputError(views_path, "/snapshots", "no snapshots to show");
  const nlohmann::json result = load_json_file(result_path);
  const JsonCtx rc{result_path};
  const auto& scenario_j = rc.member(result, "", "scenario");
  const auto& document = rc.member(scenario_j, "/scenario", "document");
  const Scenario scenario = parse_scenario(document, result_path);
  std::string planner = "planner";
  if (auto it = result.find("planner");
      it != result.end() && it->is_object() && it->contains("name")) {
    planner = (*it)["name"].get<std::string>();
  }
  std::vector<double> times;
  if (auto it = result.find("series");
      it != result.end() && it->is_object() && it->contains("time")) {
    for (const auto& t : (*it)["time"])
      times.push_back(t.is_number() ? t.get<double>() : std::nan(""));
  }

  // Snapshots to render.
  std::vector<std::size_t> chosen;
  if (o.frames.empty()) {
    chosen = {0, v.snapshots.size() / 2, v.snapshots.size() - 1};
  } else {
    const int last_frame =
        std::max(v.snapshots.back().frame, static_cast<int>(v.camera_path.size()) - 1);
    for (int f : o.frames) {
      if (f < 0 || f > last_frame) {
        throw InputError(views_path, "",
                         "frame " + std::to_string(f) + " is outside the run (0.." +
                             std::to_string(last_frame) + ")");
      }
      std::size_t best = 0;
      for (std::size_t i = 1; i < v.snapshots.size(); ++i) {
        if (std::abs(v.snapshots[i].frame - f) < std::abs(v.snapshots[best].frame - f)) best = i;
      }
      chosen.push_back(best);
    }
  }
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());

  // Every output path, checked before anything is written.
  const fs::path out = fs::path(run_dir) / "views";
  auto P = [&](const std::string& name) { return (out / name).string(); };
  std::vector<std::string> all = {P("nodes.pvd"), P("cells.pvd"), P("receivers.pvd"),
                                  P("terrain.vts"), P("camera_path.vtp")};
  for (const auto& s : v.snapshots) {
    const std::string tag = frame_tag(s.frame);
    all.push_back(P("nodes_" + tag + ".vtp"));
    all.push_back(P("cells_" + tag + ".vtu"));
    all.push_back(P("receivers_" + tag + ".vtp"));
  }
  for (std::size_t i : chosen)
    all.push_back(P("snapshot_" + frame_tag(v.snapshots[i].frame) + ".png"));
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw InputError(out.string(), "", "cannot create directory: " + ec.message());
  for (const auto& p : all) check_output_path(p, o.overwrite);

  const World world(scenario.world);
  std::vector<std::pair<double, std::string>> nodes_pvd, cells_pvd, recv_pvd;
  for (const auto& s : v.snapshots) {
    const std::string tag = frame_tag(s.frame);
    auto nodes = nodes_polydata(s, v.exposure);
    write_xml<vtkXMLPolyDataWriter>(P("nodes_" + tag + ".vtp"), nodes.Get(), o.overwrite);
    auto cells = cells_grid(s, v.exposure);
    write_xml<vtkXMLUnstructuredGridWriter>(P("cells_" + tag + ".vtu"), cells.Get(), o.overwrite);
    auto recv = receivers_polydata(s, v.exposure);
    write_xml<vtkXMLPolyDataWriter>(P("receivers_" + tag + ".vtp"), recv.Get(), o.overwrite);
    nodes_pvd.emplace_back(s.time, "nodes_" + tag + ".vtp");
    cells_pvd.emplace_back(s.time, "cells_" + tag + ".vtu");
    recv_pvd.emplace_back(s.time, "receivers_" + tag + ".vtp");
  }
  write_text_atomically(P("nodes.pvd"), pvd_text(nodes_pvd), o.overwrite);
  write_text_atomically(P("cells.pvd"), pvd_text(cells_pvd), o.overwrite);
  write_text_atomically(P("receivers.pvd"), pvd_text(recv_pvd), o.overwrite);
  {
    const TerrainSamples t =
        sample_terrain(world, world.min_xy(), world.max_xy(), o.terrain_max_points);
    auto grid = terrain_grid(t);
    write_xml<vtkXMLStructuredGridWriter>(P("terrain.vts"), grid.Get(), o.overwrite);
  }
  {
    auto path_pd = camera_path_polydata(v, times);
    write_xml<vtkXMLPolyDataWriter>(P("camera_path.vtp"), path_pd.Get(), o.overwrite);
  }
  const SceneContext ctx{v, world, scenario.name + " / " + planner};
  for (std::size_t i : chosen) {
    render_snapshot(ctx, v.snapshots[i], P("snapshot_" + frame_tag(v.snapshots[i].frame) + ".png"),
                    o);
  }
  return all;
}

}  // namespace ambisim
