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

// Spheres per body (on average) from which candidates are found body by body: a cell of the
// sphere grid is as wide as the largest sphere plus the skin, so with several spheres per body
// each sphere tests every sphere of the bodies in its 27 cells, most of them far from it (the
// nine-sphere clump bed lists its pairs in a quarter of the time in two levels, the 164-sphere
// bed in a fortieth; tests/bench/README.md). For lone spheres the two ways cost the same.
constexpr double kTwoLevelSpheresPerBody = 4.0;

void VerletList::build(const SphereState& spheres, double skin_m, bool keep_rolling, int threads) {
  const std::size_t n = spheres.size();
  skin_m_ = skin_m;
  double r_max = 0.0;
  for (double r : spheres.radius_m) r_max = std::max(r_max, r);
  const std::size_t body_count = n == 0 ? 0 : static_cast<std::size_t>(spheres.body[n - 1]) + 1;
  const bool two_level =
      body_count > 0 && (search_ == PairSearch::two_level ||
                         (search_ == PairSearch::automatic &&
                          static_cast<double>(n) >= kTwoLevelSpheresPerBody * static_cast<double>(body_count)));
  if (two_level) {
    bound_bodies(spheres, body_count);
    double big = 0.0;
    for (double r : body_radius_) big = std::max(big, r);
    grid_.build(body_centre_, 2.0 * big + skin_m);
  } else {
    grid_.build(spheres.position_m, 2.0 * r_max + skin_m);
  }
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
      std::vector<std::uint32_t> near, in_i, in_j;  // two-level scratch
      std::size_t s = bounds[static_cast<std::size_t>(c)];
      const std::size_t s_end = bounds[static_cast<std::size_t>(c) + 1];
      while (s < s_end) {
        const std::uint32_t bi = spheres.body[s];
        std::size_t e = s;
        while (e < s_end && spheres.body[e] == bi) ++e;
        if (two_level) {
          list_pairs_two_level(spheres, bi, s, e, skin_m, near, in_i, in_j, out.si, out.sj, out.group_sizes);
          s = e;
          continue;
        }
        cand.clear();
        for (std::size_t a = s; a < e; ++a) {
          const Vec3& pa = spheres.position_m[a];
          const double ra = spheres.radius_m[a];
          const auto cell_a = grid_.cell_of(pa);
          for (int dz = -1; dz <= 1; ++dz) {
            const int z = cell_a[2] + dz;
            if (z < 0 || z >= dims[2]) continue;
            for (int dy = -1; dy <= 1; ++dy) {
              const int y = cell_a[1] + dy;
              if (y < 0 || y >= dims[1]) continue;
              for (int dx = -1; dx <= 1; ++dx) {
                const int x = cell_a[0] + dx;
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

void VerletList::bound_bodies(const SphereState& spheres, std::size_t bodies) {
  const std::size_t n = spheres.size();
  body_first_.assign(bodies + 1, static_cast<std::uint32_t>(n));
  body_centre_.assign(bodies, Vec3::Zero());
  body_radius_.assign(bodies, 0.0);
  for (std::size_t k = n; k-- > 0;) body_first_[spheres.body[k]] = static_cast<std::uint32_t>(k);
  for (std::size_t b = bodies; b-- > 0;)  // a body without spheres (removed): an empty range
    if (body_first_[b] == n) body_first_[b] = body_first_[b + 1];
  for (std::size_t b = 0; b < bodies; ++b) {
    const std::size_t lo = body_first_[b], hi = body_first_[b + 1];
    if (lo >= hi) continue;
    Vec3 c = Vec3::Zero();
    for (std::size_t k = lo; k < hi; ++k) c += spheres.position_m[k];
    c /= static_cast<double>(hi - lo);
    double r = 0.0;
    for (std::size_t k = lo; k < hi; ++k) r = std::max(r, (spheres.position_m[k] - c).norm() + spheres.radius_m[k]);
    body_centre_[b] = c;
    body_radius_[b] = r;
  }
}

void VerletList::list_pairs_two_level(const SphereState& spheres, std::uint32_t bi, std::size_t s, std::size_t e,
                                      double skin_m, std::vector<std::uint32_t>& near, std::vector<std::uint32_t>& in_i,
                                      std::vector<std::uint32_t>& in_j, std::vector<std::uint32_t>& out_si,
                                      std::vector<std::uint32_t>& out_sj, std::vector<std::uint32_t>& group_sizes) const {
  // Bounding sphere (c, R) of each body: a sphere pair (a of body i, b of body j) within the skin,
  // |pa - pb| < ra + rb + skin, has |pa - cj| <= |pa - pb| + |pb - cj| < ra + Rj + skin (as
  // |pb - cj| + rb <= Rj), and likewise |ci - cj| < Ri + Rj + skin: the bodies whose bounding
  // spheres come within the skin, and of them the spheres within the other body's bounding sphere
  // plus the skin, hold every pair the single-level search finds. The tests below are widened by
  // a relative 1e-9 so that rounding never drops one; the pair test itself is the single-level
  // one, in the same order (body j, then sphere i, then sphere j), so the list is the same.
  constexpr double widen = 1.0 + 1e-9;
  const auto dims = grid_.dims();
  const Vec3& ci = body_centre_[bi];
  const double ri = body_radius_[bi];
  const auto cell_i = grid_.cell_of(ci);
  near.clear();
  for (int z = std::max(0, cell_i[2] - 1); z <= std::min(dims[2] - 1, cell_i[2] + 1); ++z)
    for (int y = std::max(0, cell_i[1] - 1); y <= std::min(dims[1] - 1, cell_i[1] + 1); ++y)
      for (int x = std::max(0, cell_i[0] - 1); x <= std::min(dims[0] - 1, cell_i[0] + 1); ++x) {
        const auto cell = static_cast<std::size_t>(grid_.linear(x, y, z));
        for (std::uint32_t k = grid_.start()[cell]; k < grid_.start()[cell + 1]; ++k) {
          const std::uint32_t bj = grid_.sorted()[k];
          if (bj <= bi) continue;
          const double lim = (ri + body_radius_[bj] + skin_m) * widen;
          if ((body_centre_[bj] - ci).squaredNorm() < lim * lim) near.push_back(bj);
        }
      }
  std::sort(near.begin(), near.end());
  for (const std::uint32_t bj : near) {
    const Vec3& cj = body_centre_[bj];
    const double rj = body_radius_[bj];
    in_i.clear();
    for (std::size_t a = s; a < e; ++a) {
      const double lim = (spheres.radius_m[a] + rj + skin_m) * widen;
      if ((spheres.position_m[a] - cj).squaredNorm() < lim * lim) in_i.push_back(static_cast<std::uint32_t>(a));
    }
    if (in_i.empty()) continue;
    in_j.clear();
    for (std::uint32_t b = body_first_[bj]; b < body_first_[bj + 1]; ++b) {
      const double lim = (spheres.radius_m[b] + ri + skin_m) * widen;
      if ((spheres.position_m[b] - ci).squaredNorm() < lim * lim) in_j.push_back(b);
    }
    bool open = false;
    for (const std::uint32_t a : in_i) {
      const Vec3& pa = spheres.position_m[a];
      const double ra = spheres.radius_m[a];
      for (const std::uint32_t b : in_j) {
        const double cut = ra + spheres.radius_m[b] + skin_m;
        if ((spheres.position_m[b] - pa).squaredNorm() < cut * cut) {
          if (!open) group_sizes.push_back(0);
          open = true;
          ++group_sizes.back();
          out_si.push_back(a);
          out_sj.push_back(b);
        }
      }
    }
  }
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
