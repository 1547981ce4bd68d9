#include "solver/sim/work_split.hpp"

#include <algorithm>

namespace seedcal {

std::size_t group_at_or_after(const std::vector<std::uint32_t>& start, std::size_t groups,
                              std::size_t pair) {
  if (groups == 0) return 0;
  const auto end = start.begin() + static_cast<std::ptrdiff_t>(groups);
  return static_cast<std::size_t>(std::lower_bound(start.begin(), end, pair) - start.begin());
}

namespace {

// The first group of `l` whose body is at or after `body`.
std::size_t first_group_of(const GroupedList& l, std::size_t body) {
  std::size_t lo = 0, hi = l.groups;
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (l.body_of(mid) < body) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

double pairs_before(const GroupedList& l, std::size_t group) {
  return l.groups == 0 ? 0.0 : static_cast<double>(l.start[group]);
}

}  // namespace

std::vector<WorkShare> split_contact_work(const GroupedList& spheres, const GroupedList& walls,
                                          std::size_t bodies, std::size_t threads) {
  threads = std::max<std::size_t>(threads, 1);
  // Work on the bodies before `body`.
  const auto work_before = [&](std::size_t body) {
    return pairs_before(spheres, first_group_of(spheres, body)) +
           kWallPairWeight * pairs_before(walls, first_group_of(walls, body));
  };
  const double total = work_before(bodies);
  std::vector<std::size_t> cut(threads + 1, bodies);
  cut[0] = 0;
  for (std::size_t t = 1; t < threads; ++t) {
    // The first body at which the work before it reaches t / threads of the total.
    const double target = total * static_cast<double>(t) / static_cast<double>(threads);
    std::size_t lo = cut[t - 1], hi = bodies;
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (work_before(mid) < target) lo = mid + 1;
      else hi = mid;
    }
    cut[t] = lo;
  }
  std::vector<WorkShare> shares(threads);
  for (std::size_t t = 0; t < threads; ++t) {
    shares[t].sphere_begin = first_group_of(spheres, cut[t]);
    shares[t].sphere_end = t + 1 == threads ? spheres.groups : first_group_of(spheres, cut[t + 1]);
    shares[t].wall_begin = first_group_of(walls, cut[t]);
    shares[t].wall_end = t + 1 == threads ? walls.groups : first_group_of(walls, cut[t + 1]);
    shares[t].body_begin = cut[t];
    shares[t].body_end = cut[t + 1];
  }
  return shares;
}

void split_bodies_by_spheres(const std::vector<std::uint32_t>& first_sphere, std::size_t bodies,
                             std::vector<WorkShare>& shares) {
  const std::size_t n = shares.size();
  if (n == 0) return;
  const auto begin = first_sphere.begin();
  const auto end = begin + static_cast<std::ptrdiff_t>(bodies);
  const double spheres = bodies == 0 ? 0.0 : static_cast<double>(first_sphere[bodies]);
  std::size_t prev = 0;
  for (std::size_t t = 0; t < n; ++t) {
    shares[t].move_begin = prev;
    if (t + 1 == n) {
      shares[t].move_end = bodies;
    } else {
      // The first body whose first sphere is at or after (t + 1) / n of the spheres.
      const double target = spheres * static_cast<double>(t + 1) / static_cast<double>(n);
      const auto it = std::lower_bound(begin, end, target, [](std::uint32_t s, double x) {
        return static_cast<double>(s) < x;
      });
      shares[t].move_end = std::max(prev, static_cast<std::size_t>(it - begin));
    }
    prev = shares[t].move_end;
  }
}

}  // namespace seedcal
