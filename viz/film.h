#pragma once
// `ambisim film`: the camera's view of one or more runs of a scenario, side by side with the
// truth, as an H.264 MP4 (Debian ffmpeg, fed raw RGB frames through a pipe) and a contact-sheet
// PNG beside it.
//
// Each panel is the player's view (the scenario's horizontal field of view, the camera's look
// direction) of the terrain in the project's own lighting and of every live receiver as a
// sphere. A sphere's vertex of normal n shows the irradiance E(n) the panel's SH9 gives
// (sh_irradiance), tone-mapped with the run's exposure exactly as the metrics display it; the
// terrain shows pi x its radiance toward the sky (a white Lambertian receiver of irradiance E
// has radiance E / pi, so both are on one scale), tone-mapped with the same exposure. The
// truth panel shows the reference capture at each receiver in SH9 (what the oracle is served).
// A receiver that popped where the player sees it (pops.viewed) is ringed in red for
// `ring_s` after the pop.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sim/base/image.h"
#include "sim/base/output_file.h"
#include "sim/run/simulator.h"
#include "sim/sh/sh9.h"

namespace ambisim {

class World;

struct FilmSphere {
  std::uint64_t id = 0;
  glm::dvec3 centre{0.0};
  double radius_m = 1.0;
  Sh9Rgb sh;
  bool ringed = false;
};

struct FilmPanel {
  std::string caption;
  std::vector<FilmSphere> spheres;
};

struct FilmFrame {
  double time = 0.0;  // simulated seconds
  glm::dvec3 camera{0.0};
  glm::dvec3 look{1.0, 0.0, 0.0};
  std::vector<FilmPanel> panels;
};

// One scored run: its label (the planner) and its observed frames, in frame order.
struct FilmRun {
  std::string label;
  std::vector<FrameObservation> frames;
};

// How long a pop stays ringed, in simulated seconds.
inline constexpr double kFilmRingSeconds = 0.5;

// The film's frames: frame i shows the last simulated frame at or before from + i / fps, one
// panel per run (caption: label, time, that frame's viewed dE00 mean) and a last panel of the
// truth. Every run must hold the same frames (one scenario). n = round((to - from) * fps).
std::vector<FilmFrame> compose_film(const std::vector<FilmRun>& runs, double from_s, double to_s,
                                    int fps, double ring_s = kFilmRingSeconds);

struct FilmSettings {
  int panel_width = 640;
  int panel_height = 360;
  int fps = 30;
  double fov_deg = 70.0;  // horizontal
  double exposure = 1.0;
  double light_time_s = 0.0;  // the terrain is lit as at this time
  // The terrain drawn: a square around these camera positions (every frame's, usually).
  std::vector<glm::dvec3> camera_positions;
  double contact_every_s = 2.0;  // a contact-sheet tile this often (simulated seconds)
  Overwrite overwrite = Overwrite::refuse;
};

// Renders frames one at a time (VTK offscreen). The image is panels.size() x panel_width wide.
class FilmRenderer {
 public:
  FilmRenderer(const World& world, const FilmSettings& settings, int panels);
  ~FilmRenderer();
  FilmRenderer(const FilmRenderer&) = delete;
  FilmRenderer& operator=(const FilmRenderer&) = delete;
  ImageRgb8 render(const FilmFrame& frame);

 private:
  struct Impl;
  Impl* impl_;
};

// The ring around a sphere as drawn (pixel centre and radius in a panel), nullopt-like
// visible = false when the sphere is behind the camera.
struct ScreenCircle {
  bool visible = false;
  double x = 0.0, y = 0.0, radius = 0.0;  // pixels, y down from the panel's top
};
ScreenCircle project_sphere(const glm::dvec3& camera, const glm::dvec3& look, double fov_deg,
                            int width, int height, const glm::dvec3& centre, double radius_m);

// Renders every frame, pipes them to ffmpeg (libx264, yuv420p) into a temporary file renamed to
// `mp4_path`, and writes the contact sheet to `sheet_path` (also atomically). Both paths are
// checked before anything is rendered. Throws InputError naming the file on failure (ffmpeg
// missing or failing included); no partial file is left.
void write_film(const World& world, const FilmSettings& settings,
                const std::vector<FilmFrame>& frames, const std::string& mp4_path,
                const std::string& sheet_path);

}  // namespace ambisim
