// The ground sheet (thesis 8.5/9.3, D12): sets height_m above the terrain, 9-child cells with 4
// paired links, one set per quadrant (1-4) by horizontal distance, D2 with k = 3.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "policies/registry/registry.h"
#include "policies/thesis/shgraph_core.h"

using namespace ambisim;

namespace {

double terrain(double x, double y) { return 10.0 + 0.2 * x - 0.1 * y; }

Sh9Rgb field2d(const glm::dvec3& p) {
  Sh9Rgb s;
  s.c[0] = Rgb(static_cast<float>(1.0 + 0.01 * p.x), static_cast<float>(1.0 + 0.01 * p.y), 1.0f);
  return s;
}

struct Sheet {
  ShGraphCore<2> core;
  WorldQueries world;
  std::int64_t frame = 0;
  glm::dvec3 camera{0.0, 0.0, terrain(0.0, 0.0) + 1.5};
  std::vector<std::pair<CaptureRequest, std::int64_t>> flights;
  std::map<std::uint64_t, glm::dvec3> captured;

  explicit Sheet(const ShGraphSettings& s) : core(s) {
    world.ground_height = terrain;
    world.surface_height = [](double x, double y) { return terrain(x, y) + 20.0; };  // canopy
  }
  void run(double seconds) {
    const double dt = 1.0 / 60.0;
    for (int i = 0; i < static_cast<int>(std::lround(seconds / dt)); ++i, ++frame) {
      FrameContext c;
      c.frame = frame;
      c.time = static_cast<double>(frame) * dt;
      c.dt = dt;
      c.camera_position = camera;
      c.faces_per_frame = 1.0;
      c.startable_captures = flights.empty() ? 1 : 0;
      c.world = &world;
      auto req = core.plan(c);
      for (std::size_t k = 0; k < req.size(); ++k) {
        if (static_cast<int>(k) < c.startable_captures) {
          core.started(req[k].tag);
          flights.push_back({req[k], frame + 5});
        } else {
          core.refused(req[k].tag);
        }
      }
      core.update(c);
      if (!flights.empty() && flights.front().second == frame) {
        const CaptureRequest r = flights.front().first;
        flights.clear();
        captured[r.tag] = r.position;
        core.deliver({r.tag, r.position, field2d(r.position), c.time - 5 * dt, c.time});
      }
    }
  }
};

ShGraphSettings sheet_settings() {
  ShGraphSettings s;
  s.root_size_m = 81.0;
  s.min_cell_m = 3.0;
  s.k = 3.0;
  s.skip_underground = false;
  return s;
}

}  // namespace

TEST_CASE("shgraph2d captures on a sheet height_m above the canopy, never inside it", "[shgraph]") {
  // The canopy is a solid 20 m above the terrain. The sheet follows its top (the default)...
  Sheet s(sheet_settings());
  s.run(6.0);
  REQUIRE(s.captured.size() > 20);
  for (const auto& [tag, p] : s.captured) {
    CHECK(p.z == Approx(terrain(p.x, p.y) + 20.0 + 2.0));
  }
  CHECK(s.core.dropped_in_solids() == 0);
  // ... or the terrain (D12's first reading): its cells stand 18 m inside the crowns, and only
  // those whose set may move up by that much (half a cell: the 81 m root) are captured, above
  // the canopy; the rest are never captured (L318).
  ShGraphSettings under = sheet_settings();
  under.sheet_over_surface = false;
  Sheet u(under);
  u.run(6.0);
  REQUIRE(!u.captured.empty());
  for (const auto& [tag, p] : u.captured) CHECK(p.z >= terrain(p.x, p.y) + 20.0 + 0.5 - 1e-9);
  CHECK(u.core.dropped_in_solids() > 0);
}

TEST_CASE("shgraph2d: 9 children, 4 links in pairs, one set per quadrant by horizontal distance",
          "[shgraph]") {
  Sheet s(sheet_settings());
  s.run(8.0);
  const auto& nodes = s.core.nodes();
  int expanded = 0;
  for (std::int32_t i = 0; i < static_cast<std::int32_t>(nodes.size()); ++i) {
    if (!s.core.node_live(i)) continue;
    const auto& n = nodes[i];
    if (n.first_child >= 0) {
      ++expanded;
      for (int c = 0; c < 9; ++c) CHECK(s.core.node_live(n.first_child + c));
      CHECK(nodes[n.first_child + 4].anchor == n.anchor);  // the centre child
    }
    for (int d = 0; d < 4; ++d) {
      if (n.link[d] < 0) continue;
      CHECK(nodes[n.link[d]].link[d ^ 1] == i);
      CHECK(nodes[n.link[d]].depth == n.depth);
      const glm::dvec3 delta = s.core.node_centre(n.link[d]) - s.core.node_centre(i);
      CHECK(std::abs(delta[d / 2]) == Approx(s.core.cell_size(n.depth)));
    }
  }
  CHECK(expanded >= 4);
  int four = 0;
  for (double x = -5.0; x <= 5.0; x += 1.1) {
    for (double y = -5.0; y <= 5.0; y += 1.3) {
      const glm::dvec3 p(x, y, terrain(x, y) + 1.0);
      const LookupResult r = s.core.lookup(p);
      REQUIRE_FALSE(r.fell_back);
      REQUIRE(r.contributor_count >= 1);
      REQUIRE(r.contributor_count <= 4);
      four += r.contributor_count == 4;
      std::set<int> quadrants;
      for (int k = 0; k < r.contributor_count; ++k) {
        const glm::dvec3 c = s.captured.at(r.contributors[k].tag);
        quadrants.insert((c.x >= p.x) | ((c.y >= p.y) << 1));
      }
      CHECK(static_cast<int>(quadrants.size()) == r.contributor_count);
      // Height does not enter: the same answer 40 m up.
      CHECK(s.core.lookup(p + glm::dvec3(0.0, 0.0, 40.0)).sh == r.sh);
      CHECK(std::abs(r.sh.c[0].x - field2d(p).c[0].x) < 0.03f);
    }
  }
  CHECK(four > 10);
}

TEST_CASE("shgraph2d: D2 with k = 3 and prediction on by default", "[shgraph]") {
  ShGraphSettings s;  // 243 m root, 3 m cells
  s.k = 3.0;
  // 60 fps, 1 face/frame: R = 10/s; 30 m/s needs >= 9 m cells on the sheet (27 m in 3D).
  CHECK(depth_for_speed(30.0, 60.0, 1.0, s) == 3);
  CHECK(depth_for_speed(40.0, 60.0, 1.0, s) == 2);  // 12 m: 27 m cells
  auto p = make_planner("shgraph2d");
  CHECK(p->name() == "shgraph2d");
  CHECK(p->params()["predict"] == true);
  CHECK(p->params()["height_m"] == 2.0);
  CHECK(p->params()["k"] == 3.0);
}
