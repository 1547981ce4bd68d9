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

// The bodies' bounding spheres: centre the mean of a body's sphere centres, radius the farthest
// sphere surface from it; and each body's range of spheres (a body without spheres, removed, gets
// an empty range).
void bound_bodies(const SphereState& spheres, std::size_t bodies, BodyBounds& out) {
  const std::size_t n = spheres.size();
  out.first.assign(bodies + 1, static_cast<std::uint32_t>(n));
  out.centre_m.assign(bodies, Vec3::Zero());
  out.radius_m.assign(bodies, 0.0);
  for (std::size_t k = n; k-- > 0;) out.first[spheres.body[k]] = static_cast<std::uint32_t>(k);
  for (std::size_t b = bodies; b-- > 0;)
    if (out.first[b] == n) out.first[b] = out.first[b + 1];
  for (std::size_t b = 0; b < bodies; ++b) {
    const std::size_t lo = out.first[b], hi = out.first[b + 1];
    if (lo >= hi) continue;
    Vec3 c = Vec3::Zero();
    for (std::size_t k = lo; k < hi; ++k) c += spheres.position_m[k];
    c /= static_cast<double>(hi - lo);
    double r = 0.0;
    for (std::size_t k = lo; k < hi; ++k) r = std::max(r, (spheres.position_m[k] - c).norm() + spheres.radius_m[k]);
    out.centre_m[b] = c;
    out.radius_m[b] = r;
  }
}

struct TwoLevelScratch {
  std::vector<std::uint32_t> near, in_i, in_j;
};

// Body bi's pairs (its spheres s .. e) with the bodies after it, appended to `out` in list order;
// `grid` bins the bodies' bounding-sphere centres.
//
// Bounding sphere (c, R) of each body: a sphere pair (a of body i, b of body j) within the skin,
// |pa - pb| < ra + rb + skin, has |pa - cj| <= |pa - pb| + |pb - cj| < ra + Rj + skin (as
// |pb - cj| + rb <= Rj), and likewise |ci - cj| < Ri + Rj + skin: the bodies whose bounding
// spheres come within the skin, and of them the spheres within the other body's bounding sphere
// plus the skin, hold every pair the single-level search finds. The tests below are widened by
// a relative 1e-9 so that rounding never drops one; the pair test itself is the single-level
// one, in the same order (body j, then sphere i, then sphere j), so the list is the same.
void list_pairs_two_level(const SphereState& spheres, const CellGrid& grid, const BodyBounds& bodies, std::uint32_t bi,
                          std::size_t s, std::size_t e, double skin_m, TwoLevelScratch& w, Chunk& out) {
  constexpr double widen = 1.0 + 1e-9;
  const Vec3& ci = bodies.centre_m[bi];
  const double ri = bodies.radius_m[bi];
  w.near.clear();
  grid.for_each_near(ci, [&](std::uint32_t bj) {
    if (bj <= bi) return;
    const double lim = (ri + bodies.radius_m[bj] + skin_m) * widen;
    if ((bodies.centre_m[bj] - ci).squaredNorm() < lim * lim) w.near.push_back(bj);
  });
  std::sort(w.near.begin(), w.near.end());
  for (const std::uint32_t bj : w.near) {
    const Vec3& cj = bodies.centre_m[bj];
    const double rj = bodies.radius_m[bj];
    w.in_i.clear();
    for (std::size_t a = s; a < e; ++a) {
      const double lim = (spheres.radius_m[a] + rj + skin_m) * widen;
      if ((spheres.position_m[a] - cj).squaredNorm() < lim * lim) w.in_i.push_back(static_cast<std::uint32_t>(a));
    }
    if (w.in_i.empty()) continue;
    w.in_j.clear();
    for (std::uint32_t b = bodies.first[bj]; b < bodies.first[bj + 1]; ++b) {
      const double lim = (spheres.radius_m[b] + ri + skin_m) * widen;
      if ((spheres.position_m[b] - ci).squaredNorm() < lim * lim) w.in_j.push_back(b);
    }
    bool open = false;
    for (const std::uint32_t a : w.in_i) {
      const Vec3& pa = spheres.position_m[a];
      const double ra = spheres.radius_m[a];
      for (const std::uint32_t b : w.in_j) {
        const double cut = ra + spheres.radius_m[b] + skin_m;
        if ((spheres.position_m[b] - pa).squaredNorm() < cut * cut) {
          if (!open) out.group_sizes.push_back(0);
          open = true;
          ++out.group_sizes.back();
          out.si.push_back(a);
          out.sj.push_back(b);
        }
      }
    }
  }
}

}  // namespace

// Spheres per body (on average) from which candidates are found body by body: a cell of the
// sphere grid is as wide as the largest sphere plus the skin, so with several spheres per body
// each sphere tests every sphere of the bodies in its 27 cells, most of them far from it (the
// nine-sphere clump bed lists its pairs in a quarter of the time in two levels, the 164-sphere
// bed in a fortieth; tests/bench/README.md). For lone spheres the two ways cost the same.
constexpr double kTwoLevelSpheresPerBody = 4.0;

void VerletList::build(const SphereState& spheres, double skin_m, bool keep_rolling, int threads) {
  const std::size_t n = spheres.size();
  skin_m_ = skin_m;
  const std::size_t body_count = n == 0 ? 0 : static_cast<std::size_t>(spheres.body[n - 1]) + 1;
  const bool two_level =
      body_count > 0 && (search_ == PairSearch::two_level ||
                         (search_ == PairSearch::automatic &&
                          static_cast<double>(n) >= kTwoLevelSpheresPerBody * static_cast<double>(body_count)));
  // Every pair that can come within the skin lies in adjacent cells of the grid: of the bodies'
  // bounding spheres or of the spheres, its cell the largest diameter plus the skin.
  if (two_level) bound_bodies(spheres, body_count, bodies_);
  const std::vector<double>& radii = two_level ? bodies_.radius_m : spheres.radius_m;
  double r_max = 0.0;
  for (double r : radii) r_max = std::max(r_max, r);
  grid_.build(two_level ? bodies_.centre_m : spheres.position_m, 2.0 * r_max + skin_m);

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
  // Filled by one thread once every chunk is listed: where each chunk's pairs and groups go.
  std::vector<std::size_t> pair_offset(static_cast<std::size_t>(threads) + 1, 0);
  std::vector<std::size_t> group_offset(static_cast<std::size_t>(threads) + 1, 0);
  std::vector<std::uint32_t> si, sj, gs;
  std::vector<Vec3> tangential, rolling;
  std::vector<std::uint8_t> live;
  const bool old_rolling = keep_rolling && !rolling_.empty();

#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    int t = 0, team = 1;
#ifdef _OPENMP
    t = omp_get_thread_num();
    team = omp_get_num_threads();
#endif
    // Chunks in turn, should the team be smaller than asked for.
    for (int c = t; c < threads; c += team) {
      Chunk& out = chunks[static_cast<std::size_t>(c)];
      std::vector<Candidate> cand;
      TwoLevelScratch scratch;
      std::size_t s = bounds[static_cast<std::size_t>(c)];
      const std::size_t s_end = bounds[static_cast<std::size_t>(c) + 1];
      while (s < s_end) {
        const std::uint32_t bi = spheres.body[s];
        std::size_t e = s;
        while (e < s_end && spheres.body[e] == bi) ++e;
        if (two_level) {
          list_pairs_two_level(spheres, grid_, bodies_, bi, s, e, skin_m, scratch, out);
          s = e;
          continue;
        }
        cand.clear();
        for (std::size_t a = s; a < e; ++a) {
          const Vec3& pa = spheres.position_m[a];
          const double ra = spheres.radius_m[a];
          grid_.for_each_near(pa, [&](std::uint32_t b) {
            if (spheres.body[b] <= bi) return;
            const double cut = ra + spheres.radius_m[b] + skin_m;
            if ((spheres.position_m[b] - pa).squaredNorm() < cut * cut)
              cand.push_back({spheres.body[b], static_cast<std::uint32_t>(a), b});
          });
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
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t c = 0; c < chunks.size(); ++c) {
        pair_offset[c + 1] = pair_offset[c] + chunks[c].si.size();
        group_offset[c + 1] = group_offset[c] + chunks[c].group_sizes.size();
      }
      const std::size_t pairs = pair_offset.back();
      si.resize(pairs);
      sj.resize(pairs);
      gs.resize(group_offset.back() + 1);
      gs.back() = static_cast<std::uint32_t>(pairs);
      tangential.resize(pairs);
      rolling.resize(keep_rolling ? pairs : 0);
      live.resize(pairs);
      built_at_.resize(n);
    }  // (implicit barrier)
    // Each chunk in place, in chunk order, with the old history of its pairs: both lists are
    // ordered by (body_i, body_j, sphere_i, sphere_j) and a chunk holds the pairs of one range of
    // bodies, so its part of the old list is one range too, merged linearly on the same key. The
    // arrays are zeroed here, by the thread that writes them next.
    auto key = [&](std::uint32_t a, std::uint32_t b) {
      return std::make_tuple(spheres.body[a], spheres.body[b], a, b);
    };
    for (int c = t; c < threads; c += team) {
      const Chunk& ch = chunks[static_cast<std::size_t>(c)];
      const std::size_t off = pair_offset[static_cast<std::size_t>(c)];
      std::copy(ch.si.begin(), ch.si.end(), si.begin() + static_cast<std::ptrdiff_t>(off));
      std::copy(ch.sj.begin(), ch.sj.end(), sj.begin() + static_cast<std::ptrdiff_t>(off));
      std::size_t g = group_offset[static_cast<std::size_t>(c)];
      std::size_t at = off;
      for (std::uint32_t size : ch.group_sizes) {
        gs[g++] = static_cast<std::uint32_t>(at);
        at += size;
      }
      // The old pairs whose first sphere belongs to this chunk's bodies.
      const std::size_t s_begin = bounds[static_cast<std::size_t>(c)];
      const std::size_t s_end = bounds[static_cast<std::size_t>(c) + 1];
      const auto old_at = [&](std::size_t sphere) {
        if (sphere >= n) return si_.size();
        const std::uint32_t body = spheres.body[sphere];
        return static_cast<std::size_t>(
            std::lower_bound(si_.begin(), si_.end(), body,
                             [&](std::uint32_t a, std::uint32_t b) { return spheres.body[a] < b; }) -
            si_.begin());
      };
      std::size_t o = s_begin < s_end ? old_at(s_begin) : si_.size();
      const std::size_t o_end = s_begin < s_end ? old_at(s_end) : si_.size();
      for (std::size_t k = off; k < off + ch.si.size(); ++k) {
        Vec3 tk = Vec3::Zero(), rk = Vec3::Zero();
        if (o < o_end) {
          const auto kn = key(si[k], sj[k]);
          while (o < o_end && key(si_[o], sj_[o]) < kn) ++o;
          if (o < o_end && si_[o] == si[k] && sj_[o] == sj[k]) {
            tk = tangential_[o];
            if (old_rolling) rk = rolling_[o];
          }
        }
        tangential[k] = tk;
        if (keep_rolling) rolling[k] = rk;
        live[k] = tk.isZero(0.0) && rk.isZero(0.0) ? 0 : 1;
      }
      for (std::size_t i = s_begin; i < s_end; ++i) built_at_[i] = spheres.position_m[i];
    }
  }

  si_ = std::move(si);
  sj_ = std::move(sj);
  group_start_ = std::move(gs);
  tangential_ = std::move(tangential);
  rolling_ = std::move(rolling);
  live_ = std::move(live);
  ++builds_;
}

void VerletList::mark_live() {
  live_.resize(tangential_.size());
  const bool rolling = !rolling_.empty();
  for (std::size_t k = 0; k < tangential_.size(); ++k)
    live_[k] = tangential_[k].isZero(0.0) && (!rolling || rolling_[k].isZero(0.0)) ? 0 : 1;
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
