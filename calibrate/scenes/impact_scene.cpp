// `kind = "impact"`: schema in docs/scenes/impact.md.
#include <algorithm>
#include <cmath>

#include "calibrate/config/physics_config.hpp"
#include "calibrate/scenes/scene_registry.hpp"
#include "solver/clump/mass_properties.hpp"
#include "solver/scenes/impact.hpp"

namespace seedcal {
namespace {

nlohmann::json vec_json(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

}  // namespace

nlohmann::json run_impact_scene(TomlReader& root, const SceneContext& ctx) {
  ImpactSpec spec;
  root.string("kind");
  PhysicsConfig phys = read_physics(root);
  spec.physics = phys.physics;
  spec.time_step = phys.time_step;
  spec.duration_s = root.number("duration_s", Range::left_open(0.0, 1e4));
  spec.threads = ctx.threads;
  spec.seed = ctx.seed;
  spec.observer = ctx.observer;

  const Range coord = Range::closed(-1e3, 1e3);
  const Range speed = Range::closed(-1e4, 1e4);
  auto bodies = root.table_array("body");
  if (bodies.empty()) root.error("body", "is required: at least one [[body]]");
  std::vector<std::uint16_t> body_materials;  // per [[body]], kUnknown where unknown
  for (TomlReader& b : bodies) {
    const std::string mat_name = b.string("material");
    const std::uint16_t mat = phys.material(b, "material", mat_name);
    body_materials.push_back(mat);
    // Any two bodies can touch: each new pair of materials needs an interaction.
    for (std::size_t i = 0; i + 1 < body_materials.size(); ++i) {
      if (std::find(body_materials.begin(), body_materials.begin() + static_cast<std::ptrdiff_t>(i),
                    body_materials[i]) != body_materials.begin() + static_cast<std::ptrdiff_t>(i))
        continue;  // this material was checked against the new one already
      phys.require_interaction(b, "material", body_materials[i], mat,
                               "[[body]] " + std::to_string(body_materials.size()) + " can touch [[body]] " +
                                   std::to_string(i + 1));
    }
    const Vec3 pos = b.vec3("position_m", coord, true).value_or(Vec3::Zero());
    const Vec3 vel = b.vec3("velocity_m_s", speed, false).value_or(Vec3::Zero());
    const Vec3 spin = b.vec3("angular_velocity_rad_s", Range::closed(-1e6, 1e6), false).value_or(Vec3::Zero());
    Quat q = Quat::Identity();
    if (b.has("orientation_quat")) {
      const auto qv = b.numbers("orientation_quat", Range::closed(-1.0, 1.0), 4, 4);
      if (qv.size() == 4) {
        q = Quat(qv[0], qv[1], qv[2], qv[3]);
        if (q.norm() < 1e-6) b.error("orientation_quat", "must not be all zeros ([w, x, y, z])");
        else q.normalize();
      }
    }
    const bool has_r = b.has("radius_m"), has_s = b.has("spheres_m");
    if (has_r == has_s) {
      b.error("radius_m", "give exactly one of radius_m (a sphere) or spheres_m (a clump)");
      continue;
    }
    const double density = mat < phys.physics.materials.size() ? phys.physics.materials[mat].density_kg_m3 : 1000.0;
    BodyDef def;
    if (has_r) {
      const double r = b.number("radius_m", Range::open(0.0, 10.0));
      if (!std::isfinite(r) || r <= 0.0) continue;
      def = sphere_body(r, density, mat);
      def.position_m = pos;
      def.orientation = q;
    } else {
      const auto rows = b.number_rows("spheres_m", 4, 1, 5000);
      std::vector<SphereXYZR> spheres;
      bool ok = !rows.empty();
      for (const auto& row : rows) {
        if (!(row[3] > 0.0)) {
          b.error("spheres_m", "every sphere needs a radius > 0 ([x, y, z, r] in m)");
          ok = false;
          break;
        }
        spheres.push_back({Vec3(row[0], row[1], row[2]), row[3]});
      }
      if (!ok) continue;
      // spheres_m are given in the body's input frame, placed at position_m with orientation_quat;
      // the centre of mass and principal frame come from the union of the spheres.
      def = clump_body(spheres, density, mat, pos, q);
    }
    def.velocity_m_s = vel;
    def.angular_velocity_rad_s = spin;
    spec.bodies.push_back(def);
    b.check_unknown_keys();
  }
  for (TomlReader& w : root.table_array("wall")) {
    const std::string type = w.choice("type", {"plane"});
    ImpactWallSpec ws;
    ws.point_m = w.vec3("point_m", coord, true).value_or(Vec3::Zero());
    const Vec3 n = w.vec3("normal", Range::closed(-1e6, 1e6), true).value_or(Vec3::UnitZ());
    if (n.norm() < 1e-12) w.error("normal", "must not be the zero vector");
    else ws.normal = n.normalized();
    ws.material = phys.material(w, "material", w.string("material"));
    std::vector<std::uint16_t> checked;
    for (std::size_t i = 0; i < body_materials.size(); ++i) {
      if (std::find(checked.begin(), checked.end(), body_materials[i]) != checked.end()) continue;
      checked.push_back(body_materials[i]);
      phys.require_interaction(w, "material", body_materials[i], ws.material,
                               "[[body]] " + std::to_string(i + 1) + " can touch this wall");
    }
    w.check_unknown_keys();
    spec.walls.push_back(ws);
  }
  root.check_unknown_keys();
  root.diagnostics().throw_if_any();
  if (ctx.plan) *ctx.plan = plan_impact(spec);  // what the run will simulate (run_plan.hpp)
  if (ctx.check_only) {  // validated: run nothing
    return nlohmann::json::object();
  }

  const ImpactResult r = run_impact(spec);
  nlohmann::json j;
  j["contact_duration_s"] = r.contact_duration_s;
  j["first_touch_s"] = r.first_touch_s;
  j["max_overlap_m"] = r.max_overlap_m;
  j["max_normal_force_n"] = r.max_normal_force_n;
  j["max_contact_points"] = r.max_contact_points;
  nlohmann::json fin = nlohmann::json::array();
  for (const auto& f : r.final_states)
    fin.push_back({{"position_m", vec_json(f.position_m)},
                   {"velocity_m_s", vec_json(f.velocity_m_s)},
                   {"angular_velocity_rad_s", vec_json(f.angular_velocity_rad_s)}});
  j["final"] = fin;
  add_run_report(j, r.run);
  return j;
}

}  // namespace seedcal
