#include "solver/walls/wall_contact_list.hpp"

#include <algorithm>
#include <tuple>

namespace seedcal {

void WallContactList::build(const SphereState& spheres, const std::vector<Wall>& walls,
                            double skin_m, bool keep_rolling) {
  std::vector<std::uint32_t> sphere, prim, gs{0};
  std::vector<std::uint16_t> wall;
  const std::size_t n = spheres.size();
  // Spheres are ordered by body; within a body, order candidates by (wall, sphere, primitive).
  struct Cand { std::uint16_t w; std::uint32_t s, p; };
  std::vector<Cand> cand;
  std::vector<int> prims;
  std::size_t s = 0;
  while (s < n) {
    const std::uint32_t b = spheres.body[s];
    std::size_t e = s;
    while (e < n && spheres.body[e] == b) ++e;
    cand.clear();
    for (std::size_t w = 0; w < walls.size(); ++w) {
      const Wall& wl = walls[w];
      for (std::size_t k = s; k < e; ++k) {
        const Vec3 c = to_wall_frame(wl.pose, spheres.position_m[k]);
        const double reach = spheres.radius_m[k] + skin_m;
        // Only the primitives the shape reports near (a mesh: from its grid), and each kept by the
        // test before the shared-boundary rule (WallShape::near), so a contact that the rule
        // assigns to another primitive now is still found if the sphere moves to where it owns it.
        wl.shape->candidates(c, reach, prims);
        for (int p : prims)
          if (wl.shape->near(p, c, reach))
            cand.push_back({static_cast<std::uint16_t>(w), static_cast<std::uint32_t>(k),
                            static_cast<std::uint32_t>(p)});
      }
    }
    std::stable_sort(cand.begin(), cand.end(), [](const Cand& x, const Cand& y) {
      return std::tie(x.w, x.s, x.p) < std::tie(y.w, y.s, y.p);
    });
    for (std::size_t k = 0; k < cand.size(); ++k) {
      if (k > 0 && cand[k].w != cand[k - 1].w) gs.push_back(static_cast<std::uint32_t>(sphere.size()));
      sphere.push_back(cand[k].s);
      wall.push_back(cand[k].w);
      prim.push_back(cand[k].p);
    }
    if (!cand.empty()) gs.push_back(static_cast<std::uint32_t>(sphere.size()));
    s = e;
  }

  // Carry history over: both lists are ordered by (body, wall, sphere, primitive).
  std::vector<Vec3> tangential(sphere.size(), Vec3::Zero());
  std::vector<Vec3> rolling(keep_rolling ? sphere.size() : 0, Vec3::Zero());
  auto key = [&](std::uint32_t sp, std::uint16_t w, std::uint32_t p) {
    return std::make_tuple(spheres.body[sp], w, sp, p);
  };
  std::size_t o = 0;
  for (std::size_t k = 0; k < sphere.size() && o < sphere_.size(); ++k) {
    const auto kn = key(sphere[k], wall[k], prim[k]);
    while (o < sphere_.size() && key(sphere_[o], wall_[o], primitive_[o]) < kn) ++o;
    if (o < sphere_.size() && key(sphere_[o], wall_[o], primitive_[o]) == kn) {
      tangential[k] = tangential_[o];
      if (keep_rolling && !rolling_.empty()) rolling[k] = rolling_[o];
    }
  }
  sphere_ = std::move(sphere);
  wall_ = std::move(wall);
  primitive_ = std::move(prim);
  group_start_ = std::move(gs);
  tangential_ = std::move(tangential);
  rolling_ = std::move(rolling);
}

void WallContactList::renumber(const std::vector<std::uint32_t>& new_of_old,
                               const SphereState& spheres) {
  struct Entry {
    std::uint32_t b, s, p;
    std::uint16_t w;
    Vec3 t, r;
  };
  const bool rolling = !rolling_.empty();
  std::vector<Entry> e;
  e.reserve(sphere_.size());
  for (std::size_t k = 0; k < sphere_.size(); ++k) {
    const std::uint32_t s = new_of_old[sphere_[k]];
    if (s == 0xffffffffu) continue;  // a removed sphere: history dropped
    e.push_back({spheres.body[s], s, primitive_[k], wall_[k], tangential_[k], rolling ? rolling_[k] : Vec3::Zero()});
  }
  std::sort(e.begin(), e.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.b, a.w, a.s, a.p) < std::tie(b.b, b.w, b.s, b.p);
  });
  sphere_.resize(e.size());
  primitive_.resize(e.size());
  wall_.resize(e.size());
  tangential_.resize(e.size());
  if (rolling) rolling_.resize(e.size());
  for (std::size_t k = 0; k < e.size(); ++k) {
    sphere_[k] = e[k].s;
    primitive_[k] = e[k].p;
    wall_[k] = e[k].w;
    tangential_[k] = e[k].t;
    if (rolling) rolling_[k] = e[k].r;
  }
}

}  // namespace seedcal
