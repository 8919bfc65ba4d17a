#include "viz/film.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <map>
#include <numbers>
#include <stdexcept>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <glm/geometric.hpp>

#include "sim/base/input_error.h"
#include "sim/colour/tone_map.h"
#include "sim/render/ray_march.h"
#include "sim/world/illumination.h"
#include "sim/world/lighting_model.h"
#include "sim/world/world.h"
#include "viz/png_writer.h"

namespace ambisim {
namespace {

// The terrain drawn reaches this far beyond the camera's path, at most kTerrainPoints samples
// along each side (the grid the GPU draws every panel and frame).
constexpr double kTerrainMarginM = 1500.0;
constexpr int kTerrainPoints = 480;
constexpr int kTileQuads = 60;
constexpr double kFullDetailM = 400.0;
constexpr double kNearClipM = 0.3;
constexpr double kFarClipM = 4000.0;

std::string format_caption(const std::string& label, double time, double viewed_de) {
  char buf[160];
  if (std::isfinite(viewed_de)) {
    std::snprintf(buf, sizeof buf, "%s   t %.2f s   viewed dE00 %.2f", label.c_str(), time,
                  viewed_de);
  } else {
    std::snprintf(buf, sizeof buf, "%s   t %.2f s   viewed dE00 -", label.c_str(), time);
  }
  return buf;
}

double vertical_fov_deg(double horizontal_deg, int width, int height) {
  const double t = std::tan(horizontal_deg * std::numbers::pi / 360.0) * height / width;
  return 2.0 * std::atan(t) * 180.0 / std::numbers::pi;
}

glm::dvec3 view_up(const glm::dvec3& look) {
  const glm::dvec3 f = glm::normalize(look);
  return std::abs(f.z) > 0.999 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
}

std::array<unsigned char, 3> displayed(const Rgb& linear, double exposure) {
  const auto c = to_srgb8(linear, exposure);
  return {c[0], c[1], c[2]};
}

void draw_ring(ImageRgb8& img, int x_offset, int panel_width, const ScreenCircle& c) {
  // A 3-pixel red ring just outside the sphere's outline.
  const double r_in = c.radius + 3.0, r_out = c.radius + 6.0;
  const int x0 = std::max(0, static_cast<int>(std::floor(c.x - r_out)));
  const int x1 = std::min(panel_width - 1, static_cast<int>(std::ceil(c.x + r_out)));
  const int y0 = std::max(0, static_cast<int>(std::floor(c.y - r_out)));
  const int y1 = std::min(img.height - 1, static_cast<int>(std::ceil(c.y + r_out)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double d = std::hypot(x + 0.5 - c.x, y + 0.5 - c.y);
      if (d < r_in || d > r_out) continue;
      std::uint8_t* p = img.pixel(x_offset + x, y);
      p[0] = 255;
      p[1] = 0;
      p[2] = 0;
    }
  }
}

// Single quotes for /bin/sh.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

// Every k-th pixel's box average (k >= 1).
ImageRgb8 downsample(const ImageRgb8& in, int k) {
  ImageRgb8 out(in.width / k, in.height / k);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int dy = 0; dy < k; ++dy) {
          for (int dx = 0; dx < k; ++dx) sum += in.pixel(x * k + dx, y * k + dy)[c];
        }
        out.pixel(x, y)[c] = static_cast<std::uint8_t>((sum + k * k / 2) / (k * k));
      }
    }
  }
  return out;
}

ImageRgb8 contact_sheet(const std::vector<ImageRgb8>& tiles) {
  if (tiles.empty()) return ImageRgb8(2, 2);
  const int tw = tiles[0].width, th = tiles[0].height;
  const int gap = 4;
  const int columns = std::max(1, std::min(static_cast<int>(tiles.size()), 1280 / tw));
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  ImageRgb8 sheet(columns * tw + (columns + 1) * gap, rows * th + (rows + 1) * gap);
  std::fill(sheet.rgb.begin(), sheet.rgb.end(), std::uint8_t{32});
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    const int cx = gap + static_cast<int>(k % columns) * (tw + gap);
    const int cy = gap + static_cast<int>(k / columns) * (th + gap);
    for (int y = 0; y < th; ++y) {
      std::memcpy(sheet.pixel(cx, cy + y), tiles[k].pixel(0, y), static_cast<std::size_t>(tw) * 3);
    }
  }
  return sheet;
}

}  // namespace

std::vector<FilmFrame> compose_film(const std::vector<FilmRun>& runs, double from_s, double to_s,
                                    int fps, double ring_s) {
  if (runs.empty()) throw std::invalid_argument("film: no runs");
  if (fps <= 0 || !(to_s > from_s)) throw std::invalid_argument("film: empty time range");
  const auto& base = runs[0].frames;
  for (const auto& r : runs) {
    if (r.frames.size() != base.size()) {
      throw std::invalid_argument("film: runs of different frames (" + r.label + ")");
    }
    for (std::size_t k = 0; k < base.size(); ++k) {
      if (r.frames[k].time != base[k].time) {
        throw std::invalid_argument("film: runs of different frame times (" + r.label + ")");
      }
    }
  }
  // Each run's viewed pops: receiver id -> the times it popped.
  std::vector<std::map<std::uint64_t, std::vector<double>>> pops(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    for (const auto& f : runs[k].frames) {
      for (const auto& r : f.receivers) {
        if (r.viewed_pop) pops[k][r.id].push_back(f.time);
      }
    }
  }
  const auto ringed = [&](std::size_t run, std::uint64_t id, double t) {
    const auto it = pops[run].find(id);
    if (it == pops[run].end()) return false;
    // A pop at or before t and less than ring_s before it.
    const auto after = std::upper_bound(it->second.begin(), it->second.end(), t + 1e-9);
    return after != it->second.begin() && *(after - 1) > t - ring_s;
  };

  const auto count = static_cast<std::int64_t>(std::llround((to_s - from_s) * fps));
  std::vector<FilmFrame> film;
  film.reserve(static_cast<std::size_t>(std::max<std::int64_t>(count, 0)));
  std::size_t at = 0;
  for (std::int64_t i = 0; i < count; ++i) {
    const double t = from_s + static_cast<double>(i) / fps;
    while (at + 1 < base.size() && base[at + 1].time <= t + 1e-9) ++at;
    if (base.empty()) break;
    const FrameObservation& b = base[at];
    FilmFrame f;
    f.time = b.time;
    f.camera = b.camera;
    f.look = b.look;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const FrameObservation& o = runs[k].frames[at];
      FilmPanel p;
      p.caption = format_caption(runs[k].label, o.time, o.row.de2000_viewed_mean);
      for (const auto& r : o.receivers) {
        p.spheres.push_back({r.id, r.position, 0.5 * r.size_m, r.planner_sh, ringed(k, r.id, t)});
      }
      f.panels.push_back(std::move(p));
    }
    FilmPanel truth;
    char buf[96];
    std::snprintf(buf, sizeof buf, "truth (reference in SH9)   t %.2f s", b.time);
    truth.caption = buf;
    for (const auto& r : b.receivers) {
      truth.spheres.push_back({r.id, r.position, 0.5 * r.size_m, r.reference_sh, false});
    }
    f.panels.push_back(std::move(truth));
    film.push_back(std::move(f));
  }
  return film;
}

ScreenCircle project_sphere(const glm::dvec3& camera, const glm::dvec3& look, double fov_deg,
                            int width, int height, const glm::dvec3& centre, double radius_m) {
  const glm::dvec3 f = glm::normalize(look);
  const glm::dvec3 right = glm::normalize(glm::cross(f, view_up(look)));
  const glm::dvec3 up = glm::cross(right, f);
  const glm::dvec3 v = centre - camera;
  const double z = glm::dot(v, f);
  ScreenCircle c;
  if (z <= kNearClipM) return c;
  const double tan_h = std::tan(fov_deg * std::numbers::pi / 360.0);
  const double tan_v = tan_h * height / width;
  const double xn = glm::dot(v, right) / z / tan_h;
  const double yn = glm::dot(v, up) / z / tan_v;
  c.visible = true;
  c.x = 0.5 * (xn + 1.0) * width;
  c.y = 0.5 * (1.0 - yn) * height;
  c.radius = radius_m / z / tan_v * 0.5 * height;
  return c;
}

struct FilmRenderer::Impl {
  FilmSettings s;
  int panels = 1;
  vtkNew<vtkRenderWindow> window;
  std::vector<vtkSmartPointer<vtkRenderer>> renderers;
  std::vector<vtkSmartPointer<vtkPolyData>> sphere_data;
  std::vector<vtkSmartPointer<vtkTextActor>> captions;
  // Unit spheres, fine to coarse (vertices = normals): a sphere a few pixels across needs
  // far fewer triangles than one filling the view.
  struct UnitSphere {
    std::vector<glm::dvec3> vertices;
    std::vector<std::array<vtkIdType, 3>> triangles;
  };
  std::array<UnitSphere, 3> unit_spheres;
  double vfov = 40.0;
};

FilmRenderer::FilmRenderer(const World& world, const FilmSettings& settings, int panels)
    : impl_(new Impl) {
  Impl& m = *impl_;
  m.s = settings;
  m.panels = panels;
  m.vfov = vertical_fov_deg(settings.fov_deg, settings.panel_width, settings.panel_height);

  // The terrain: a grid over the camera's surroundings, each vertex coloured by the radiance the
  // project's renderer gives the surface there (a ray straight down, so the column top's own
  // light, shadows included), as pi x radiance on the receivers' scale.
  glm::dvec2 lo(1e300), hi(-1e300);
  for (const auto& p : settings.camera_positions) {
    lo = glm::min(lo, glm::dvec2(p));
    hi = glm::max(hi, glm::dvec2(p));
  }
  if (settings.camera_positions.empty())
    lo = hi = world.min_xy() + 0.5 * (world.max_xy() - world.min_xy());
  lo = glm::max(lo - kTerrainMarginM, world.min_xy());
  hi = glm::min(hi + kTerrainMarginM, world.max_xy() - world.cell_m());
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  double step = std::max(world.cell_m(), extent / (kTerrainPoints - 1));
  step = world.cell_m() * std::ceil(step / world.cell_m() - 1e-9);
  const int nx = std::max(2, static_cast<int>(std::floor((hi.x - lo.x) / step)) + 1);
  const int ny = std::max(2, static_cast<int>(std::floor((hi.y - lo.y) / step)) + 1);
  LightingModel lighting(world);
  const Illumination il(world, lighting.state_at(settings.light_time_s));
  vtkNew<vtkPoints> points;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x = lo.x + i * step, y = lo.y + j * step;
      const double z = world.surface_height(x, y);
      points->InsertNextPoint(x, y, z);
      const glm::dvec3 o(x + 0.25 * world.cell_m(), y + 0.25 * world.cell_m(), z + 20.0);
      const Rgb l = trace_radiance(il, o, glm::dvec3(0.0, 0.0, -1.0), Marcher::accelerated);
      const auto c = displayed(l * static_cast<float>(std::numbers::pi), settings.exposure);
      colours->InsertNextTypedTuple(c.data());
    }
  }
  // Tiles of kTileQuads x kTileQuads quads, one actor each, so that the renderers' frustum
  // culling skips the tiles out of view; tiles far from the camera's path keep every 2nd or
  // 4th sample (llvmpipe's cost is in the triangles; there they are a pixel or less).
  const auto path_distance = [&](double x0, double y0, double x1, double y1) {
    double best = 1e300;
    for (std::size_t k = 0; k < settings.camera_positions.size(); k += 10) {
      const glm::dvec3& p = settings.camera_positions[k];
      const double dx = std::max({x0 - p.x, 0.0, p.x - x1});
      const double dy = std::max({y0 - p.y, 0.0, p.y - y1});
      best = std::min(best, std::hypot(dx, dy));
    }
    return best;
  };
  std::vector<vtkSmartPointer<vtkPolyDataMapper>> tile_mappers;
  for (int j0 = 0; j0 + 1 < ny; j0 += kTileQuads) {
    for (int i0 = 0; i0 + 1 < nx; i0 += kTileQuads) {
      const int i1 = std::min(nx - 1, i0 + kTileQuads), j1 = std::min(ny - 1, j0 + kTileQuads);
      const double d =
          path_distance(lo.x + i0 * step, lo.y + j0 * step, lo.x + i1 * step, lo.y + j1 * step);
      const int stride = d < kFullDetailM ? 1 : (d < 2.0 * kFullDetailM ? 2 : 4);
      std::vector<int> is, js;
      for (int i = i0; i < i1; i += stride) is.push_back(i);
      is.push_back(i1);
      for (int j = j0; j < j1; j += stride) js.push_back(j);
      js.push_back(j1);
      vtkNew<vtkPoints> tp;
      vtkNew<vtkUnsignedCharArray> tc;
      tc->SetNumberOfComponents(3);
      for (int j : js) {
        for (int i : is) {
          const vtkIdType k = static_cast<vtkIdType>(j) * nx + i;
          tp->InsertNextPoint(points->GetPoint(k));
          tc->InsertNextTypedTuple(colours->GetPointer(3 * k));
        }
      }
      const auto w = static_cast<vtkIdType>(is.size());
      vtkNew<vtkCellArray> tris;
      for (vtkIdType j = 0; j + 1 < static_cast<vtkIdType>(js.size()); ++j) {
        for (vtkIdType i = 0; i + 1 < w; ++i) {
          const vtkIdType a = j * w + i;
          const vtkIdType t1[3] = {a, a + 1, a + 1 + w};
          const vtkIdType t2[3] = {a, a + 1 + w, a + w};
          tris->InsertNextCell(3, t1);
          tris->InsertNextCell(3, t2);
        }
      }
      vtkNew<vtkPolyData> tile;
      tile->SetPoints(tp);
      tile->SetPolys(tris);
      tile->GetPointData()->SetScalars(tc);
      auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
      mapper->SetInputData(tile);
      mapper->SetColorModeToDirectScalars();
      tile_mappers.push_back(mapper);
    }
  }

  // The sky behind: its radiance toward the horizon and the zenith, on the same scale.
  const glm::dvec3 mid = settings.camera_positions.empty() ? glm::dvec3(lo + 0.5 * (hi - lo), 0.0)
                                                           : settings.camera_positions.front();
  const auto horizon = displayed(il.sky(mid, glm::normalize(glm::dvec3(1.0, 0.0, 0.05))) *
                                     static_cast<float>(std::numbers::pi),
                                 settings.exposure);
  const auto zenith =
      displayed(il.sky(mid, glm::dvec3(0.0, 0.0, 1.0)) * static_cast<float>(std::numbers::pi),
                settings.exposure);

  const std::array<std::array<int, 2>, 3> resolutions = {{{32, 20}, {16, 10}, {8, 6}}};
  for (std::size_t level = 0; level < resolutions.size(); ++level) {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(resolutions[level][0]);
    sphere->SetPhiResolution(resolutions[level][1]);
    sphere->SetRadius(1.0);
    sphere->Update();
    vtkPolyData* sp = sphere->GetOutput();
    Impl::UnitSphere& u = m.unit_spheres[level];
    for (vtkIdType k = 0; k < sp->GetNumberOfPoints(); ++k) {
      double p[3];
      sp->GetPoint(k, p);
      u.vertices.push_back(glm::normalize(glm::dvec3(p[0], p[1], p[2])));
    }
    vtkCellArray* polys = sp->GetPolys();
    polys->InitTraversal();
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    while (polys->GetNextCell(n, ids) != 0) {
      if (n == 3) u.triangles.push_back({ids[0], ids[1], ids[2]});
    }
  }

  m.window->SetOffScreenRendering(1);
  m.window->SetSize(settings.panel_width * panels, settings.panel_height);
  m.window->SetMultiSamples(0);
  for (int k = 0; k < panels; ++k) {
    vtkNew<vtkRenderer> ren;
    ren->SetViewport(static_cast<double>(k) / panels, 0.0, static_cast<double>(k + 1) / panels,
                     1.0);
    ren->GradientBackgroundOn();
    ren->SetBackground(horizon[0] / 255.0, horizon[1] / 255.0, horizon[2] / 255.0);
    ren->SetBackground2(zenith[0] / 255.0, zenith[1] / 255.0, zenith[2] / 255.0);
    for (const auto& mapper : tile_mappers) {
      vtkNew<vtkActor> t;
      t->SetMapper(mapper);
      t->GetProperty()->LightingOff();
      ren->AddActor(t);
    }

    auto data = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPolyDataMapper> sm;
    sm->SetInputData(data);
    sm->SetColorModeToDirectScalars();
    vtkNew<vtkActor> sa;
    sa->SetMapper(sm);
    sa->GetProperty()->LightingOff();
    ren->AddActor(sa);

    auto caption = vtkSmartPointer<vtkTextActor>::New();
    caption->GetTextProperty()->SetFontSize(std::max(10, settings.panel_height / 24));
    caption->GetTextProperty()->SetColor(1.0, 1.0, 1.0);
    caption->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
    caption->GetTextProperty()->SetBackgroundOpacity(0.55);
    caption->GetTextProperty()->SetVerticalJustificationToTop();
    caption->SetPosition(6, settings.panel_height - 6);
    ren->AddActor2D(caption);

    ren->GetActiveCamera()->SetViewAngle(m.vfov);
    m.window->AddRenderer(ren);
    m.renderers.push_back(ren);
    m.sphere_data.push_back(data);
    m.captions.push_back(caption);
  }
}

FilmRenderer::~FilmRenderer() { delete impl_; }

ImageRgb8 FilmRenderer::render(const FilmFrame& frame) {
  Impl& m = *impl_;
  if (static_cast<int>(frame.panels.size()) != m.panels) {
    throw std::invalid_argument("film: frame has the wrong number of panels");
  }
  const glm::dvec3 f = glm::normalize(frame.look);
  for (int k = 0; k < m.panels; ++k) {
    const FilmPanel& panel = frame.panels[static_cast<std::size_t>(k)];
    vtkCamera* cam = m.renderers[static_cast<std::size_t>(k)]->GetActiveCamera();
    cam->SetPosition(frame.camera.x, frame.camera.y, frame.camera.z);
    const glm::dvec3 focus = frame.camera + 10.0 * f;
    cam->SetFocalPoint(focus.x, focus.y, focus.z);
    const glm::dvec3 up = view_up(frame.look);
    cam->SetViewUp(up.x, up.y, up.z);
    cam->SetClippingRange(kNearClipM, kFarClipM);

    vtkNew<vtkPoints> points;
    vtkNew<vtkUnsignedCharArray> colours;
    colours->SetNumberOfComponents(3);
    vtkNew<vtkCellArray> tris;
    for (const auto& s : panel.spheres) {
      const glm::dvec3 v = s.centre - frame.camera;
      // Wholly behind the camera or beyond the far plane: not drawn.
      if (glm::dot(v, f) < -s.radius_m || glm::length(v) > kFarClipM + s.radius_m) continue;
      const double z = std::max(glm::dot(v, f), kNearClipM);
      const double radius_px =
          s.radius_m / z / std::tan(m.vfov * std::numbers::pi / 360.0) * 0.5 * m.s.panel_height;
      const Impl::UnitSphere& u = m.unit_spheres[radius_px > 24.0 ? 0 : (radius_px > 6.0 ? 1 : 2)];
      const vtkIdType first = points->GetNumberOfPoints();
      for (const auto& n : u.vertices) {
        const glm::dvec3 p = s.centre + s.radius_m * n;
        points->InsertNextPoint(p.x, p.y, p.z);
        const auto c = displayed(sh_irradiance(s.sh, n), m.s.exposure);
        colours->InsertNextTypedTuple(c.data());
      }
      for (const auto& t : u.triangles) {
        const vtkIdType ids[3] = {first + t[0], first + t[1], first + t[2]};
        tris->InsertNextCell(3, ids);
      }
    }
    vtkPolyData* data = m.sphere_data[static_cast<std::size_t>(k)];
    data->SetPoints(points);
    data->SetPolys(tris);
    data->GetPointData()->SetScalars(colours);
    data->Modified();
    m.captions[static_cast<std::size_t>(k)]->SetInput(panel.caption.c_str());
  }
  // One render, read back directly (vtkWindowToImageFilter would render the window again).
  m.window->Render();
  const int w = m.window->GetSize()[0], h = m.window->GetSize()[1];
  ImageRgb8 img(w, h);
  unsigned char* pixels = m.window->GetPixelData(0, 0, w - 1, h - 1, 0, 0);
  for (int y = 0; y < h; ++y) {
    // OpenGL's rows start at the bottom.
    std::memcpy(img.pixel(0, y), pixels + static_cast<std::size_t>(h - 1 - y) * w * 3,
                static_cast<std::size_t>(w) * 3);
  }
  delete[] pixels;
  for (int k = 0; k < m.panels; ++k) {
    for (const auto& s : frame.panels[static_cast<std::size_t>(k)].spheres) {
      if (!s.ringed) continue;
      const ScreenCircle c = project_sphere(frame.camera, frame.look, m.s.fov_deg, m.s.panel_width,
                                            m.s.panel_height, s.centre, s.radius_m);
      if (c.visible) draw_ring(img, k * m.s.panel_width, m.s.panel_width, c);
    }
  }
  return img;
}

void write_film(const World& world, const FilmSettings& settings,
                const std::vector<FilmFrame>& frames, const std::string& mp4_path,
                const std::string& sheet_path) {
  check_output_path(mp4_path, settings.overwrite);
  check_output_path(sheet_path, settings.overwrite);
  if (frames.empty()) throw InputError(mp4_path, "", "no frames to film");
  const int panels = static_cast<int>(frames.front().panels.size());
  const int width = settings.panel_width * panels, height = settings.panel_height;
  if (width % 2 != 0 || height % 2 != 0) {
    throw InputError(mp4_path, "", "the frame size must be even (yuv420p)");
  }
  FilmRenderer renderer(world, settings, panels);
  const int tile_factor = std::max(1, (width + 639) / 640);
  std::vector<ImageRgb8> tiles;

  write_atomically(mp4_path, settings.overwrite, [&](const std::string& tmp) {
    // Bit-exact, single-threaded x264: the same frames give the same file.
    const std::string cmd =
        "ffmpeg -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " +
        std::to_string(width) + "x" + std::to_string(height) + " -r " +
        std::to_string(settings.fps) +
        " -i pipe:0 -an -c:v libx264 -preset veryfast -crf 20 -threads 1 "
        "-pix_fmt yuv420p -fflags +bitexact -flags:v +bitexact "
        "-map_metadata -1 -f mp4 " +
        shell_quote(tmp);
    // A dying ffmpeg must give an error here, not kill us with SIGPIPE.
    const auto old_pipe = std::signal(SIGPIPE, SIG_IGN);
    FILE* pipe = ::popen(cmd.c_str(), "w");
    if (pipe == nullptr) {
      std::signal(SIGPIPE, old_pipe);
      throw InputError(mp4_path, "", std::string("cannot start ffmpeg: ") + std::strerror(errno));
    }
    bool write_ok = true;
    double next_tile = frames.front().time;
    try {
      for (const auto& frame : frames) {
        const ImageRgb8 img = renderer.render(frame);
        if (frame.time >= next_tile - 1e-9) {
          tiles.push_back(downsample(img, tile_factor));
          next_tile += settings.contact_every_s;
        }
        if (std::fwrite(img.rgb.data(), 1, img.rgb.size(), pipe) != img.rgb.size()) {
          write_ok = false;
          break;
        }
      }
    } catch (...) {
      ::pclose(pipe);
      std::signal(SIGPIPE, old_pipe);
      throw;
    }
    const int status = ::pclose(pipe);
    std::signal(SIGPIPE, old_pipe);
    if (!write_ok || status != 0) {
      throw InputError(mp4_path, "",
                       "ffmpeg failed (status " + std::to_string(status) +
                           "; is Debian's ffmpeg with libx264 installed?)");
    }
    write_png(contact_sheet(tiles), sheet_path, settings.overwrite);
  });
}

}  // namespace ambisim
