#include "solver/sim/memory_estimate.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "solver/core/body_state.hpp"
#include "solver/core/errors.hpp"

namespace seedcal {
namespace {

template <class V>
constexpr double elem(const V&) {
  return static_cast<double>(sizeof(typename V::value_type));
}

// First number on the line of /proc/meminfo that starts with `key`, in bytes (the file gives kB).
double meminfo_bytes(const std::string& key) {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) != 0) continue;
    std::istringstream s(line.substr(key.size()));
    double kb = 0.0;
    if (s >> kb) return kb * 1024.0;
  }
  return std::numeric_limits<double>::infinity();
}

// A single number from a cgroup v2 file ("max" or unreadable: infinity).
double cgroup_value(const std::string& file) {
  std::ifstream in("/sys/fs/cgroup/" + file);
  std::string word;
  if (!(in >> word) || word == "max") return std::numeric_limits<double>::infinity();
  try {
    return std::stod(word);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::infinity();
  }
}

}  // namespace

MemoryEstimate estimate_memory(std::size_t bodies, std::size_t spheres, int threads,
                               bool rolling_history) {
  MemoryEstimate m;
  m.bodies = bodies;
  m.spheres = spheres;
  const double nb = static_cast<double>(bodies), ns = static_cast<double>(spheres);
  const double t = static_cast<double>(std::max(1, threads));
  const double vec = static_cast<double>(sizeof(Vec3));
  const BodyState B;
  const SphereState S;

  // Bodies: the structure-of-arrays state (x2: vectors grown by push_back may hold twice their
  // size), the id map, the per-body contact count, the CDT spin direction and the two predicted
  // velocities, and one force and one torque accumulator per thread.
  const double body_state = elem(B.position_m) + elem(B.orientation) + elem(B.velocity_m_s) +
                            elem(B.angular_momentum) + elem(B.angular_velocity) + elem(B.mass_kg) +
                            elem(B.inv_mass) + elem(B.principal_inertia) + elem(B.inv_inertia) +
                            elem(B.isotropic) + elem(B.first_sphere) + elem(B.id) +
                            elem(B.force_n) + elem(B.torque_n_m) + sizeof(std::uint32_t);
  // What a seed scene returns per body for its pictures: the centre and the sphere list header.
  const double body_result = vec + sizeof(std::vector<int>);
  m.body_bytes = nb * (2.0 * body_state + sizeof(int) + 3.0 * vec + 2.0 * vec * t + body_result);

  // Spheres: their state (x2 as above), the Verlet list's positions at the last build, the cell
  // grid (cell of each sphere, the sorted ids, and at most 4 cells per sphere, cell_grid.cpp), the
  // particle factory's hash grid while it inserts (one node per sphere: key, centre, radius, link
  // and cached hash, plus a bucket pointer), and the returned world sphere for pictures.
  const double sphere_state = elem(S.body) + elem(S.offset_body_m) + elem(S.radius_m) +
                              elem(S.material) + elem(S.position_m);
  const double grid = 2.0 * sizeof(std::uint32_t) + 4.0 * sizeof(std::uint32_t);
  const double factory = sizeof(std::int64_t) + vec + sizeof(double) + 2.0 * sizeof(void*) +
                         sizeof(std::size_t) + sizeof(void*);
  m.sphere_bytes = ns * (2.0 * sphere_state + vec + grid + factory + vec + sizeof(double));

  // Pairs: sphere ids i, j, the group start, the touch count and the tangential (and rolling)
  // spring, twice while a rebuild holds the old and the new list, plus the per-thread chunk
  // (ids and group sizes, x2 growth). Wall contacts: at most one per sphere, the same way.
  m.neighbour_pairs = kPairsPerSphere * ns;
  const double history = vec * (rolling_history ? 2.0 : 1.0);
  const double pair = 2.0 * (4.0 * sizeof(std::uint32_t) + history) + 2.0 * 3.0 * sizeof(std::uint32_t);
  const double wall_pair = 2.0 * (3.0 * sizeof(std::uint32_t) + sizeof(std::uint16_t) + history);
  m.pair_bytes = m.neighbour_pairs * pair + ns * wall_pair;
  return m;
}

std::string MemoryEstimate::describe() const {
  std::ostringstream s;
  s.precision(3);
  s << static_cast<double>(bodies) << " bodies, " << static_cast<double>(spheres)
    << " spheres: about " << total_bytes() << " bytes (" << total_bytes() / 1073741824.0
    << " GiB: bodies " << body_bytes << ", spheres " << sphere_bytes << ", "
    << neighbour_pairs << " neighbour pairs and wall contacts " << pair_bytes << ")";
  return s.str();
}

double available_memory_bytes() {
  double avail = meminfo_bytes("MemAvailable:");
  const double limit = cgroup_value("memory.max");
  if (std::isfinite(limit)) {
    const double used = cgroup_value("memory.current");
    avail = std::min(avail, limit - (std::isfinite(used) ? used : 0.0));
  }
  return avail;
}

void check_memory(const MemoryEstimate& estimate, double available_bytes, const std::string& key,
                  const std::string& what) {
  if (!(estimate.total_bytes() > available_bytes)) return;
  std::ostringstream m;
  m.precision(3);
  m << what << ": the run would need " << estimate.describe() << ", but only "
    << available_bytes / 1073741824.0
    << " GiB is available (MemAvailable, or the cgroup limit); make the rig smaller or the "
       "particles larger";
  throw SettingError(key, m.str());
}

}  // namespace seedcal
