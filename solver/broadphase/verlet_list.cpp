#include "solver/broadphase/verlet_list.hpp"

#include <algorithm>
#include <tuple>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace seedcal {
namespace {

struct Candidate {
  std::uint32_t body_j, si, sj;
  bool operator<(const Candidate& o) const {
    return std::tie(body_j, si, sj) < std::tie(o.body_j, o.si, o.sj);
  }
};

struct Chunk {
  std::vector<std::uint32_t> si, sj, group_sizes;
};

}  // namespace

void VerletList::build(const SphereState& spheres, double skin_m, bool keep_rolling, int threads) {
  const std::size_t n = spheres.size();
  skin_m_ = skin_m;
  double r_max = 0.0;
  for (double r : spheres.radius_m) r_max = std::max(r_max, r);
  grid_.build(spheres.position_m, 2.0 * r_max + skin_m);
  const auto dims = grid_.dims();
  const auto& start = grid_.start();
  const auto& sorted = grid_.sorted();

  // Spheres of one body are contiguous and bodies are ordered, so a sphere range per chunk maps
  // to a body range; chunks never split a body.
  threads = std::max(1, threads);
  std::vector<std::size_t> bounds(static_cast<std::size_t>(threads) + 1, n);
  bounds[0] = 0;
  for (int t = 1; t < threads; ++t) {
    std::size_t b = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
    while (b > 0 && b < n && spheres.body[b] == spheres.body[b - 1]) ++b;
    bounds[static_cast<std::size_t>(t)] = std::max(b, bounds[static_cast<std::size_t>(t) - 1]);
  }
  std::vector<Chunk> chunks(static_cast<std::size_t>(threads));

#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    int t = 0;
#ifdef _OPENMP
    t = omp_get_thread_num();
#endif
    Chunk& out = chunks[static_cast<std::size_t>(t)];
    std::vector<Candidate> cand;
    std::size_t s = bounds[static_cast<std::size_t>(t)];
    const std::size_t s_end = bounds[static_cast<std::size_t>(t) + 1];
    while (s < s_end) {
      const std::uint32_t bi = spheres.body[s];
      std::size_t e = s;
      while (e < s_end && spheres.body[e] == bi) ++e;
      cand.clear();
      for (std::size_t a = s; a < e; ++a) {
        const Vec3& pa = spheres.position_m[a];
        const double ra = spheres.radius_m[a];
        const auto c = grid_.cell_of(pa);
        for (int dz = -1; dz <= 1; ++dz) {
          const int z = c[2] + dz;
          if (z < 0 || z >= dims[2]) continue;
          for (int dy = -1; dy <= 1; ++dy) {
            const int y = c[1] + dy;
            if (y < 0 || y >= dims[1]) continue;
            for (int dx = -1; dx <= 1; ++dx) {
              const int x = c[0] + dx;
              if (x < 0 || x >= dims[0]) continue;
              const int cell = grid_.linear(x, y, z);
              for (std::uint32_t k = start[static_cast<std::size_t>(cell)];
                   k < start[static_cast<std::size_t>(cell) + 1]; ++k) {
                const std::uint32_t b = sorted[k];
                if (spheres.body[b] <= bi) continue;
                const double cut = ra + spheres.radius_m[b] + skin_m;
                if ((spheres.position_m[b] - pa).squaredNorm() < cut * cut)
                  cand.push_back({spheres.body[b], static_cast<std::uint32_t>(a), b});
              }
            }
          }
        }
      }
      std::sort(cand.begin(), cand.end());
      for (std::size_t k = 0; k < cand.size(); ++k) {
        if (k == 0 || cand[k].body_j != cand[k - 1].body_j) out.group_sizes.push_back(0);
        ++out.group_sizes.back();
        out.si.push_back(cand[k].si);
        out.sj.push_back(cand[k].sj);
      }
      s = e;
    }
  }

  // Concatenate in chunk order and merge the old history into the new list.
  std::vector<std::uint32_t> si, sj, gs;
  gs.push_back(0);
  for (const Chunk& c : chunks) {
    si.insert(si.end(), c.si.begin(), c.si.end());
    sj.insert(sj.end(), c.sj.begin(), c.sj.end());
    for (std::uint32_t g : c.group_sizes) gs.push_back(gs.back() + g);
  }
  std::vector<Vec3> tangential(si.size(), Vec3::Zero());
  std::vector<Vec3> rolling(keep_rolling ? si.size() : 0, Vec3::Zero());
  auto key = [&](std::uint32_t a, std::uint32_t b) {
    return std::make_tuple(spheres.body[a], spheres.body[b], a, b);
  };
  std::size_t o = 0;
  for (std::size_t k = 0; k < si.size() && o < si_.size(); ++k) {
    const auto kn = key(si[k], sj[k]);
    while (o < si_.size() && key(si_[o], sj_[o]) < kn) ++o;
    if (o < si_.size() && si_[o] == si[k] && sj_[o] == sj[k]) {
      tangential[k] = tangential_[o];
      if (keep_rolling && !rolling_.empty()) rolling[k] = rolling_[o];
    }
  }
  si_ = std::move(si);
  sj_ = std::move(sj);
  group_start_ = std::move(gs);
  tangential_ = std::move(tangential);
  rolling_ = std::move(rolling);
  mark_live();
  built_at_ = spheres.position_m;
  ++builds_;
}

void VerletList::mark_live() {
  live_.resize(tangential_.size());
  for (std::size_t k = 0; k < tangential_.size(); ++k)
    live_[k] = tangential_[k].isZero(0.0) ? 0 : 1;
}

void VerletList::renumber(const std::vector<std::uint32_t>& new_of_old, const SphereState& spheres) {
  struct Entry {
    std::uint32_t bi, bj, i, j;
    Vec3 t, r;
  };
  std::vector<Entry> e;
  e.reserve(si_.size());
  const bool rolling = !rolling_.empty();
  for (std::size_t k = 0; k < si_.size(); ++k) {
    std::uint32_t i = new_of_old[si_[k]], j = new_of_old[sj_[k]];
    if (i == 0xffffffffu || j == 0xffffffffu) continue;  // a removed sphere: history dropped
    Vec3 t = tangential_[k], r = rolling ? rolling_[k] : Vec3::Zero();
    if (spheres.body[i] > spheres.body[j]) {
      std::swap(i, j);
      t = -t;
      r = -r;
    }
    e.push_back({spheres.body[i], spheres.body[j], i, j, t, r});
  }
  std::sort(e.begin(), e.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.bi, a.bj, a.i, a.j) < std::tie(b.bi, b.bj, b.i, b.j);
  });
  si_.resize(e.size());
  sj_.resize(e.size());
  tangential_.resize(e.size());
  if (rolling) rolling_.resize(e.size());
  for (std::size_t k = 0; k < e.size(); ++k) {
    si_[k] = e[k].i;
    sj_[k] = e[k].j;
    tangential_[k] = e[k].t;
    if (rolling) rolling_[k] = e[k].r;
  }
  mark_live();
  built_at_.clear();  // forces the next skin check to rebuild
}

}  // namespace seedcal
