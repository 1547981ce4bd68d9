#include "calibrate/scenes/custom_config.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <set>

#include "calibrate/clumps/clump_source.hpp"
#include "solver/core/errors.hpp"
#include "solver/walls/box_shape.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/mesh_shape.hpp"
#include "solver/walls/motion_laws.hpp"
#include "solver/walls/surface_reader.hpp"

namespace seedcal {
namespace {
// Named: this file compiles in a unity batch with other files (cmake/build_speed.cmake), whose
// helpers in their anonymous namespaces must not clash with these.
namespace custom_config_reading {

const Range kCoord = Range::closed(-100.0, 100.0);
const Range kSize = Range::closed(1e-4, 100.0);
const Range kUnit = Range::closed(-1.0, 1.0);
const Range kSpeed = Range::closed(-100.0, 100.0);

// A size as read, or `fallback` where the reader recorded it as missing or out of range (the run
// stops on the recorded error; the shape is only built so that the rest can be checked).
double usable(double v, double fallback) { return std::isfinite(v) && v > 0.0 ? v : fallback; }

// A unit direction from `key` (required when `required`), or `fallback`.
Vec3 direction(TomlReader& t, const std::string& key, bool required, const Vec3& fallback) {
  const auto v = t.vec3(key, kUnit, required);
  if (!v) return fallback;
  if (v->norm() < 1e-9) {
    t.error(key, "must not be all zeros (a direction)");
    return fallback;
  }
  return v->normalized();
}

// An axis-aligned box from `<prefix>lo_m` and `<prefix>hi_m`, hi above lo on every axis.
BoxRegion box_region(TomlReader& t, const std::string& prefix) {
  BoxRegion r;
  r.lo_m = t.vec3(prefix + "lo_m", kCoord, true).value_or(Vec3::Zero());
  r.hi_m = t.vec3(prefix + "hi_m", kCoord, true).value_or(Vec3::Ones());
  if (!(r.hi_m.array() > r.lo_m.array()).all()) {
    t.error(prefix + "hi_m", "must be above " + prefix + "lo_m on every axis (x, y and z)");
    r.hi_m = r.lo_m + Vec3::Ones();
  }
  return r;
}

// The wall's shape and its lowest point (wall frame, before its origin is added).
std::shared_ptr<const WallShape> read_shape(TomlReader& w, const std::string& config_path, double& lowest_z) {
  const std::string shape = w.choice("shape", {"box", "cylinder", "plane", "mesh"});
  lowest_z = 0.0;
  if (shape == "box") {
    Vec3 size = w.vec3("size_m", kSize, true).value_or(Vec3::Ones());
    for (int k = 0; k < 3; ++k) size[k] = usable(size[k], 1.0);
    const bool open_top = w.boolean("open_top", false);
    const std::string facing = w.choice("facing", {"inside", "outside"}, "inside");
    return std::make_shared<BoxShape>(size, open_top,
                                      facing == "inside" ? BoxShape::Facing::inside : BoxShape::Facing::outside);
  }
  if (shape == "cylinder") {
    const double r = w.number("radius_m", kSize);
    const double l = w.number("length_m", kSize);
    const bool inside = w.boolean("inside", true);
    const bool cap_bottom = w.boolean("cap_bottom", false), cap_top = w.boolean("cap_top", false);
    return std::make_shared<CylinderShape>(usable(r, 1.0), usable(l, 1.0), inside, cap_bottom, cap_top);
  }
  if (shape == "plane") {
    const Vec3 n = direction(w, "normal", true, Vec3::UnitZ());
    // A plane that is not roughly horizontal bounds no drop height.
    if (std::abs(n.z()) < 0.5) lowest_z = std::numeric_limits<double>::infinity();
    return std::make_shared<PlaneShape>(n);
  }
  if (shape == "mesh") {
    const std::string file = w.string("file");
    const std::string unit = w.choice("unit", {"m", "mm"});
    const double scale = w.number("scale", Range::left_open(0.0, 1e6), 1.0);
    if (file.empty() || unit.empty() || !(scale > 0.0)) return nullptr;
    const std::string path = resolve_data_path(file, config_path);
    if (!std::filesystem::is_regular_file(path)) {
      w.error("file", "no such file (looked for " + path + "); the path is relative to the scene file");
      return nullptr;
    }
    try {
      const std::vector<Triangle> tris = read_surface(path, (unit == "mm" ? 1e-3 : 1.0) * scale);
      auto mesh = std::make_shared<TriangleMeshShape>(tris, path);
      lowest_z = std::numeric_limits<double>::infinity();
      for (const Vec3& v : mesh->vertices()) lowest_z = std::min(lowest_z, v.z());
      return mesh;
    } catch (const SettingError& e) {
      w.error("file", std::string("cannot be read: ") + e.what());
    } catch (const std::invalid_argument& e) {
      w.error("file", std::string("holds no usable surface: ") + e.what());
    }
    return nullptr;
  }
  return nullptr;
}

void read_motion(TomlReader& w, CustomWall& cw) {
  const std::string motion = w.choice("motion", {"none", "translate", "rotate"}, "none");
  if (motion == "none") return;
  cw.start_s = w.number("start_s", Range::closed(0.0, 1e4), 0.0);
  if (motion == "translate") {
    cw.motion = CustomWall::Motion::translate;
    cw.velocity_m_s = w.vec3("velocity_m_s", kSpeed, true).value_or(Vec3::Zero());
    cw.stop_s = w.number("stop_s", Range::left_open(0.0, 1e4), std::numeric_limits<double>::infinity());
    if (cw.stop_s <= cw.start_s) w.error("stop_s", "must be after start_s");
  } else {
    cw.motion = CustomWall::Motion::rotate;
    cw.axis = direction(w, "axis", true, Vec3::UnitZ());
    cw.axis_point_m = w.vec3("axis_point_m", kCoord, false).value_or(cw.wall.pose.origin_m);
    const double rpm = w.number("rate_rpm", Range::closed(-1e4, 1e4));
    if (rpm == 0.0) w.error("rate_rpm", "must not be 0 (a wall at rest needs no motion)");
    cw.rate_rad_s = Rotation::rpm_to_rad_s(std::isfinite(rpm) ? rpm : 0.0);
  }
}

std::vector<CustomWall> read_walls(TomlReader& custom, const SeedSceneConfig& cfg, const std::string& config_path) {
  std::vector<CustomWall> walls;
  std::set<std::string> names;
  for (TomlReader& w : custom.table_array("wall")) {
    CustomWall cw;
    cw.wall.name = w.string("name");
    if (!cw.wall.name.empty() && !names.insert(cw.wall.name).second)
      w.error("name", "is used by another [[custom.wall]]; every wall needs its own name");
    const std::string material = w.string("material");
    cw.wall.material = cfg.phys.material(w, "material", material);
    cfg.require_wall_interaction(w, "material", cw.wall.material, "the seeds touch wall \"" + cw.wall.name + "\"");
    cw.wall.pose.origin_m = w.vec3("origin_m", kCoord, false).value_or(Vec3::Zero());
    double lowest = 0.0;
    cw.wall.shape = read_shape(w, config_path, lowest);
    cw.lowest_z_m = cw.wall.pose.origin_m.z() + lowest;
    read_motion(w, cw);
    w.check_unknown_keys();
    if (cw.wall.shape) walls.push_back(std::move(cw));
  }
  return walls;
}

CustomFill read_fill(TomlReader& custom) {
  CustomFill f;
  auto t = custom.table("fill");
  if (!t) {
    custom.error("fill", "is required: a [custom.fill] table with the factory's region_lo_m and region_hi_m");
    return f;
  }
  f.region = box_region(*t, "region_");
  f.velocity_m_s = t->vec3("velocity_m_s", kSpeed, false).value_or(Vec3::Zero());
  f.random_orientation = t->boolean("random_orientation", true);
  f.batches = static_cast<int>(t->integer("batches", 1, 1000, f.batches));
  f.batch_interval_s = t->number("batch_interval_s", Range::left_open(0.0, 10.0), f.batch_interval_s);
  t->check_unknown_keys();
  return f;
}

std::vector<CustomMeasure> read_measures(TomlReader& custom, double seed_radius_m) {
  std::vector<CustomMeasure> out;
  std::set<std::string> names;
  for (TomlReader& t : custom.table_array("measure")) {
    CustomMeasure m;
    m.name = t.string("name");
    const bool word = !m.name.empty() && std::all_of(m.name.begin(), m.name.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    });
    if (!m.name.empty() && !word) t.error("name", "must be lower-case letters, digits and _ (it names keys and files)");
    if (word && !names.insert(m.name).second) t.error("name", "is used by another [[custom.measure]]");
    const std::string kind = t.choice("kind", {"mass_in_region", "discharge_rate", "surface_height"});
    if (kind == "mass_in_region") {
      m.kind = CustomMeasure::Kind::mass_in_region;
      m.region = box_region(t, "region_");
    } else if (kind == "discharge_rate") {
      m.kind = CustomMeasure::Kind::discharge_rate;
      m.point_m = t.vec3("point_m", kCoord, true).value_or(Vec3::Zero());
      m.normal = direction(t, "normal", true, -Vec3::UnitZ());
      m.fit_lo = t.number("fit_fraction_min", Range::closed(0.0, 0.9), m.fit_lo);
      m.fit_hi = t.number("fit_fraction_max", Range::closed(0.1, 1.0), m.fit_hi);
      if (m.fit_lo >= m.fit_hi) t.error("fit_fraction_min", "must be below fit_fraction_max");
    } else if (kind == "surface_height") {
      m.kind = CustomMeasure::Kind::surface_height;
      m.from_m = t.vec3("from_m", kCoord, true).value_or(Vec3::Zero());
      m.to_m = t.vec3("to_m", kCoord, true).value_or(Vec3::UnitX());
      if (m.from_m.z() != m.to_m.z()) t.error("to_m", "must be at the height of from_m (a horizontal line)");
      if ((m.to_m - m.from_m).norm() == 0.0) t.error("to_m", "must differ from from_m");
      m.points = static_cast<int>(t.integer("points", 2, 1000, m.points));
      m.probe_radius_m = t.number("probe_radius_m", Range::closed(0.0, 1.0), seed_radius_m);
    }
    t.check_unknown_keys();
    out.push_back(std::move(m));
  }
  if (out.empty()) custom.error("measure", "is required: at least one [[custom.measure]]");
  return out;
}

// The fidelity table: [custom.paper] or [custom.quick].
void read_fidelity(TomlReader& custom, const std::string& fidelity, CustomSpec& spec) {
  for (const std::string& f : {std::string("paper"), std::string("quick")})
    if (f != fidelity) custom.table(f);  // mark read: only the chosen one is validated
  auto t = custom.table(fidelity);
  if (!t) {
    custom.error(fidelity, "is required: [custom." + fidelity + "] with the fill's mass or count and run_time_s");
    return;
  }
  const bool has_mass = t->has("fill_mass_kg"), has_count = t->has("fill_count");
  if (has_mass == has_count) t->error("fill_mass_kg", "give exactly one of fill_mass_kg or fill_count");
  if (has_mass) spec.fill.mass_kg = t->number("fill_mass_kg", Range::left_open(0.0, 1e4));
  if (has_count) spec.fill.count = static_cast<std::size_t>(t->integer("fill_count", 1, 100000000));
  spec.settle_energy_ratio = t->number("settle_energy_ratio", Range::open(0.0, 1.0), spec.settle_energy_ratio);
  spec.settle_max_time_s = t->number("settle_max_time_s", Range::left_open(0.0, 100.0), spec.settle_max_time_s);
  spec.run_time_s = t->number("run_time_s", Range::left_open(0.0, 1000.0));
  if (!std::isfinite(spec.run_time_s)) spec.run_time_s = 1.0;
  spec.sample_interval_s = t->number("sample_interval_s", Range::left_open(0.0, 10.0), spec.sample_interval_s);
  if (spec.sample_interval_s > spec.run_time_s) t->error("sample_interval_s", "must not exceed run_time_s");
  spec.picture_time_s = t->number("picture_time_s", Range::closed(0.0, 1000.0), 0.5 * spec.run_time_s);
  if (spec.picture_time_s > spec.run_time_s) t->error("picture_time_s", "must not exceed run_time_s");
  t->check_unknown_keys();
}

}  // namespace custom_config_reading
}  // namespace

CustomSpec read_custom_rig(TomlReader& root, const SeedSceneConfig& cfg, const std::string& config_path) {
  using namespace custom_config_reading;
  CustomSpec spec;
  auto custom = root.table("custom");
  if (!custom) {
    root.error("custom", "is required: a [custom] table with the rig ([[custom.wall]], [custom.fill], "
                         "[[custom.measure]], [custom." + cfg.fidelity + "])");
    return spec;
  }
  spec.walls = read_walls(*custom, cfg, config_path);
  spec.fill = read_fill(*custom);
  // The volume-equivalent radius of the mean seed: the surface probe's default radius.
  const double density = cfg.seed_material < cfg.phys.physics.materials.size()
                             ? cfg.phys.physics.materials[cfg.seed_material].density_kg_m3
                             : 1000.0;
  const double seed_radius = std::cbrt(3.0 * seed_volume_m3(cfg.seeds, density) / (4.0 * std::numbers::pi));
  spec.measures = read_measures(*custom, std::isfinite(seed_radius) ? seed_radius : 0.0);
  if (custom->has("sink_z_m")) spec.sink_z_m = custom->number("sink_z_m", kCoord);
  read_fidelity(*custom, cfg.fidelity, spec);
  custom->check_unknown_keys();
  return spec;
}

}  // namespace seedcal
