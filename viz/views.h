#pragma once
// `ambisim viz`: ParaView files and headless PNG snapshots of one run (RUN_DIR/views.json,
// RUN_DIR/result.json), written to RUN_DIR/views/:
//   nodes.pvd      + nodes_fNNNNNN.vtp     probe nodes per snapshot: points (with vertex cells)
//                                          and arrays ambient_rgb (uchar x3, the tone-mapped
//                                          ambient colour), depth, age_s, in_flight, has_data,
//                                          half_extent_m;
//   cells.pvd      + cells_fNNNNNN.vtu     hexahedra of the nodes with a half extent > 0, with the
//                                          same arrays as cell data;
//   receivers.pvd  + receivers_fNNNNNN.vtp receivers per snapshot (points with vertex cells)
//                                          and, when views.json holds them, the arrays
//                                          planner_up, reference_up, planner_view,
//                                          reference_view (linear irradiance x3, straight up and
//                                          toward the camera; the reference in SH9),
//                                          planner_view_rgb, reference_view_rgb (displayed sRGB
//                                          uchar x3), de2000_view and viewed_pop;
//                                          the .pvd timesteps are simulated seconds;
//   terrain.vts                            the world's surface, downsampled, albedo_rgb (sRGB
//                                          uchar x3), height_m and biome arrays;
//   camera_path.vtp                        the camera path as one polyline, frame and time_s;
//   snapshot_fNNNNNN.png                   rendered views (terrain, probes as spheres in their
//                                          ambient colour, node wireframes, camera path,
//                                          receivers), seen from behind and above the camera.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/base/output_file.h"
#include "sim/sh/sh9.h"

namespace ambisim {

struct ViewsOptions {
  // Frames to render as PNG (each maps to the nearest snapshot); empty: first, middle, last.
  std::vector<int> frames;
  Overwrite overwrite = Overwrite::refuse;
  int width = 1200;
  int height = 800;
  int terrain_max_points = 384;  // terrain grid points along the longer side (file output)
};

struct ViewNode {
  glm::dvec3 centre{0.0};
  glm::dvec3 half_extent{0.0};
  int depth = 0;
  bool has_data = false;
  bool in_flight = false;
  double age_s = 0.0;
  Sh9Rgb sh;
};

// What the planner and the reference gave a receiver (views.json "light", optional).
struct ViewReceiverLight {
  glm::dvec3 planner_up{0.0}, reference_up{0.0};      // linear irradiance straight up
  glm::dvec3 planner_view{0.0}, reference_view{0.0};  // ... at the normal toward the camera
  double de2000_view = 0.0;                           // displayed, toward the camera
  bool viewed_pop = false;
};

struct ViewSnapshot {
  int frame = 0;
  double time = 0.0;
  glm::dvec3 camera{0.0};
  std::vector<ViewNode> nodes;
  std::vector<glm::dvec3> receivers;
  std::vector<ViewReceiverLight> light;  // empty, or one per receiver
};

struct RunViews {
  double exposure = 1.0;
  std::vector<glm::dvec3> camera_path;  // one per frame
  std::vector<ViewSnapshot> snapshots;
};

// Reads views.json; throws InputError naming the file and JSON path on bad content.
RunViews load_views(const std::string& path);

// The node's ambient colour: the mean irradiance over the six axis normals, tone-mapped to
// 8-bit sRGB with the run's exposure.
std::array<std::uint8_t, 3> ambient_colour(const Sh9Rgb& sh, double exposure);

// Writes RUN_DIR/views/; returns the paths written. Throws InputError (naming the file) for a
// missing run directory, views.json or result.json, or an existing output without
// Overwrite::allow (all outputs are checked before anything is written).
std::vector<std::string> write_run_views(const std::string& run_dir, const ViewsOptions& options);

}  // namespace ambisim
