#include "calibrate/export/liggghts_deck.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "calibrate/export/export_notes.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {
namespace {

// Atom types: the seed material is type 1, the others follow in the scene's order. Entry t - 1
// is the material of type t.
std::vector<std::uint16_t> type_order(const ExportedModel& m) {
  std::vector<std::uint16_t> order{m.seed_material};
  for (std::uint16_t k = 0; k < m.physics.materials.size(); ++k)
    if (k != m.seed_material) order.push_back(k);
  return order;
}

int type_of(const ExportedModel& m, std::uint16_t material) {
  const auto order = type_order(m);
  for (std::size_t t = 0; t < order.size(); ++t)
    if (order[t] == material) return static_cast<int>(t) + 1;
  return 1;
}

// pair_style gran arguments for the scene's contact options: Hertz with the tangential history
// (LIGGGHTS's Hertz-Mindlin), limitForce for a clipped normal force, and the rolling model.
std::string liggghts_contact(const ContactOptions& c) {
  std::string s = "model hertz tangential history";
  if (c.rolling == RollingModel::cdt) s += " rolling_friction cdt";
  if (c.rolling == RollingModel::epsd) s += " rolling_friction epsd";
  if (c.clip_attractive) s += " limitForce on";
  return s;
}

// One peratomtypepair table: `value` of each pair's interaction, `placeholder` where none.
std::string pair_table(const ExportedModel& m, double (*value)(const Interaction&), double placeholder) {
  const auto order = type_order(m);
  std::string s = std::to_string(order.size());
  for (std::uint16_t a : order)
    for (std::uint16_t b : order) {
      const Interaction* i = m.interaction(a, b);
      s += " " + exact_number_text(i ? value(*i) : placeholder);
    }
  return s;
}

double restitution_of(const Interaction& i) { return i.restitution; }
double friction_of(const Interaction& i) { return i.static_friction; }
double rolling_of(const Interaction& i) { return i.rolling_friction; }

double gravity_magnitude(const ExportedModel& m) { return m.physics.gravity_m_s2.norm(); }

std::vector<std::string> deck_header(const ExportedModel& m, const std::string& title) {
  std::vector<std::string> h{title};
  for (const std::string& line : provenance_lines(m)) h.push_back(line);
  return h;
}

std::vector<std::string> notes_block(const ExportedModel& m) {
  std::vector<std::string> h{"", "What does not carry over exactly:"};
  for (const std::string& note : carry_over_notes(m)) h.push_back("- " + note);
  const Vec3 g = m.physics.gravity_m_s2;
  if (g.x() != 0.0 || g.y() != 0.0 || !(g.z() < 0.0))
    h.push_back("- Gravity: the scene's gravity is (" + exact_number_text(g.x()) + ", " + exact_number_text(g.y()) + ", " +
                exact_number_text(g.z()) + ") m/s2; in.settle's box has its floor at z = 0 and takes gravity's magnitude "
                "along -z.");
  return h;
}

}  // namespace

SettleDeck default_settle_deck(const ExportedModel& m, int count) {
  SettleDeck d;
  d.count = count;
  const double diameter = 2.0 * m.bounding_radius_m();
  d.box_x_m = d.box_y_m = std::ceil(6.0 * diameter * 1000.0) / 1000.0;  // whole mm
  const double bed = count * m.volume_m3() / (0.5 * d.box_x_m * d.box_y_m);
  d.wall_height_m = 3.0 * bed;
  d.insert_lo_z_m = 0.3 * bed;
  d.insert_hi_z_m = d.wall_height_m;
  d.dt_s = exported_time_step_s(m, std::sqrt(2.0 * gravity_magnitude(m) * d.wall_height_m));
  return d;
}

std::string liggghts_fragment(const ExportedModel& m) {
  const auto order = type_order(m);
  const auto& mats = m.physics.materials;
  const ContactOptions& c = m.physics.contact;
  std::vector<std::string> h = deck_header(m, "seedcal export: LIGGGHTS-PUBLIC 3.x fragment (docs/export.md)");
  std::string types;
  for (std::size_t t = 0; t < order.size(); ++t)
    types += (t ? ", " : "") + std::to_string(t + 1) + " = " + mats[order[t]].name + (t == 0 ? " (the seeds)" : "");
  h.insert(h.end(),
           {"", "Include it after `create_box " + std::to_string(order.size()) +
                    " ...` (one atom type per material) and before the clumps are inserted:",
            "  atom types: " + types,
            "  a wall: fix ID all wall/gran ${seedcal_contact} primitive type " +
                std::to_string(type_of(m, m.wall_material)) + " zplane 0.0",
            "  the clumps: fix ID all insert/pack ... distributiontemplate seedcal_seeds ..., and fix ID all multisphere",
            "  (in.settle beside it does all of this)"});
  const auto notes = notes_block(m);
  h.insert(h.end(), notes.begin(), notes.end());
  std::ostringstream o;
  o << comment_block(h, "# ") << "\n";

  o << "# Materials, per atom type (Hertz: 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j)\n";
  o << "fix seedcal_youngs all property/global youngsModulus peratomtype";
  for (auto k : order) o << " " << exact_number_text(mats[k].youngs_modulus_pa);
  o << "\nfix seedcal_poisson all property/global poissonsRatio peratomtype";
  for (auto k : order) o << " " << exact_number_text(mats[k].poisson_ratio);
  o << "\n\n# Interactions, per pair of atom types, row by row:\n";
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a; b < order.size(); ++b) {
      const Interaction* i = m.interaction(order[a], order[b]);
      o << "#   " << a + 1 << "-" << b + 1 << " " << mats[order[a]].name << "-" << mats[order[b]].name << ": "
        << (i ? i->name + ": restitution " + exact_number_text(i->restitution) + ", static friction " +
                    exact_number_text(i->static_friction) + ", rolling friction " + exact_number_text(i->rolling_friction)
              : std::string("no [[interaction]]: placeholder values (these never touch in seedcal)"))
        << "\n";
    }
  o << "fix seedcal_restitution all property/global coefficientRestitution peratomtypepair "
    << pair_table(m, restitution_of, 0.5) << "\n";
  o << "fix seedcal_friction all property/global coefficientFriction peratomtypepair "
    << pair_table(m, friction_of, 0.5) << "\n";
  if (c.rolling != RollingModel::none)
    o << "fix seedcal_rolling_friction all property/global coefficientRollingFriction peratomtypepair "
      << pair_table(m, rolling_of, 0.0) << "\n";
  if (c.rolling == RollingModel::epsd) {
    // Ai et al. (2011) eq. 17: the rolling dashpot's damping ratio, the same for every pair.
    const std::string n = std::to_string(order.size());
    o << "fix seedcal_rolling_damping all property/global coefficientRollingViscousDamping peratomtypepair " << n;
    for (std::size_t k = 0; k < order.size() * order.size(); ++k) o << " " << exact_number_text(c.epsd_damping_ratio);
    o << "\n";
  }

  o << "\n# Contact: seedcal's " << to_string(c.normal) << " with rolling " << to_string(c.rolling)
    << " as the closest LIGGGHTS models (the header says what differs)\n";
  o << "variable seedcal_contact string \"" << liggghts_contact(c) << "\"\n";
  o << "pair_style gran ${seedcal_contact}\npair_coeff * *\n";

  const BodyDef& b = m.seeds.body;
  o << "\n# The clump: " << b.spheres.size() << " spheres (x y z r, m) in its principal frame, its mass (kg) and "
    << "principal inertia (kg m2) given exactly; density " << exact_number_text(m.seed().density_kg_m3)
    << " kg/m3, volume " << exact_number_text(m.volume_m3()) << " m3 (mass / density)\n";
  o << "variable seedcal_clump_mass_kg equal " << exact_number_text(b.mass_kg) << "\n";
  o << "variable seedcal_clump_spheres equal " << b.spheres.size() << "\n";
  o << "variable seedcal_largest_radius_m equal " << exact_number_text(m.largest_sphere_radius_m()) << "\n";
  o << "variable seedcal_bounding_radius_m equal " << exact_number_text(m.bounding_radius_m()) << "\n";
  o << "fix seedcal_clump all particletemplate/multisphere 15485863 atom_type 1 density constant "
    << exact_number_text(m.seed().density_kg_m3) << " nspheres " << b.spheres.size() << " ntry 1000000 spheres &\n";
  for (const SphereDef& s : b.spheres)
    o << "    " << exact_number_text(s.offset_m.x()) << " " << exact_number_text(s.offset_m.y()) << " "
      << exact_number_text(s.offset_m.z()) << " " << exact_number_text(s.radius_m) << " &\n";
  const Vec3& I = b.principal_inertia_kg_m2;
  o << "    type 1 mass " << exact_number_text(b.mass_kg) << " inertia_tensor " << exact_number_text(I.x()) << " 0 0 "
    << exact_number_text(I.y()) << " 0 " << exact_number_text(I.z()) << " use_density\n";
  o << "fix seedcal_seeds all particledistribution/discrete 32452843 1 seedcal_clump 1.0\n";
  return o.str();
}

std::string liggghts_settle_deck(const ExportedModel& m, const SettleDeck& d, const std::string& fragment_file) {
  const auto order = type_order(m);
  const double g = gravity_magnitude(m);
  const double margin = m.bounding_radius_m();
  std::vector<std::string> h =
      deck_header(m, "seedcal export: a LIGGGHTS-PUBLIC 3.x deck that pours clumps of this seed into an open box "
                "and settles them (docs/export.md)");
  h.insert(h.end(),
           {"", "Run it in this directory (it includes " + fragment_file + "):", "  liggghts -in in.settle",
            "(-screen /dev/null silences it; -screen none makes LIGGGHTS 3.8.0 crash when the first run sets up)",
            "Its variables (SI units; liggghts -var NAME VALUE overrides one):",
            "  count: clumps poured; box_x_m, box_y_m: the box's floor (plane walls at x = 0, box_x_m, y = 0, "
            "box_y_m, z = 0, of " + m.physics.materials[m.wall_material].name + "); wall_height_m: the box's height "
            "(the domain ends one bounding radius above it)",
            "  insert_lo_z_m, insert_hi_z_m: the clumps are placed at random, not overlapping, over the whole floor "
            "between these heights, at rest; dt_s: the time step (seedcal's default for this clump)",
            "  settle_energy_ratio, check_interval_s, max_time_s: settled when the kinetic energy per body "
            "(translation and rotation) falls below settle_energy_ratio x m g d (d: the largest sphere's "
            "diameter), checked every check_interval_s after the clumps have had the time to fall from "
            "insert_hi_z_m, or at max_time_s; seed: the insertion's random seed (a prime above 10000)",
            "  bodies_file: where every body's centre x y z (m) and mass (kg) are written once it has settled",
            "It ends with a line \"seedcal settle: STATE at t = ... s: N of COUNT clumps ...\"."});
  const auto notes = notes_block(m);
  h.insert(h.end(), notes.begin(), notes.end());
  std::ostringstream o;
  o << comment_block(h, "# ") << "\n";
  o << "variable count index " << d.count << "\n"
    << "variable box_x_m index " << exact_number_text(d.box_x_m) << "\n"
    << "variable box_y_m index " << exact_number_text(d.box_y_m) << "\n"
    << "variable wall_height_m index " << exact_number_text(d.wall_height_m) << "\n"
    << "variable insert_lo_z_m index " << exact_number_text(d.insert_lo_z_m) << "\n"
    << "variable insert_hi_z_m index " << exact_number_text(d.insert_hi_z_m) << "\n"
    << "variable dt_s index " << exact_number_text(d.dt_s) << "\n"
    << "variable settle_energy_ratio index " << exact_number_text(d.settle_energy_ratio) << "\n"
    << "variable check_interval_s index " << exact_number_text(d.check_interval_s) << "\n"
    << "variable max_time_s index " << exact_number_text(d.max_time_s) << "\n"
    << "variable seed index " << d.seed << "\n"
    << "variable bodies_file index settled_bodies.txt\n\n";
  o << "atom_style      granular\natom_modify     map array\nboundary        f f f\nnewton          off\n"
       "communicate     single vel yes\nunits           si\nhard_particles  yes\n\n";
  const std::string mg = exact_number_text(margin);
  o << "# The domain: the box and a margin of one bounding radius of the clump\n";
  o << "region          seedcal_domain block -" << mg << " $(v_box_x_m+" << mg << ") -" << mg << " $(v_box_y_m+"
    << mg << ") -" << mg << " $(v_wall_height_m+" << mg << ") units box\n";
  o << "create_box      " << order.size() << " seedcal_domain\n";
  o << "neighbor        " << exact_number_text(0.5 * m.largest_sphere_radius_m()) << " bin\n";
  o << "neigh_modify    delay 0\n\n";
  o << "include         " << fragment_file << "\n\n";
  o << "timestep        ${dt_s}\n";
  o << "fix seedcal_gravity all gravity " << exact_number_text(g) << " vector 0.0 0.0 -1.0\n";
  const std::string wall = "all wall/gran ${seedcal_contact} primitive type " + std::to_string(type_of(m, m.wall_material));
  o << "fix seedcal_floor " << wall << " zplane 0.0\n"
    << "fix seedcal_wall_x0 " << wall << " xplane 0.0\n"
    << "fix seedcal_wall_x1 " << wall << " xplane ${box_x_m}\n"
    << "fix seedcal_wall_y0 " << wall << " yplane 0.0\n"
    << "fix seedcal_wall_y1 " << wall << " yplane ${box_y_m}\n\n";
  o << "# The pour: every clump at once, at random poses, none overlapping, wholly inside the region\n";
  o << "region seedcal_pour block 0.0 ${box_x_m} 0.0 ${box_y_m} ${insert_lo_z_m} ${insert_hi_z_m} units box\n";
  o << "fix seedcal_pour all insert/pack seed ${seed} distributiontemplate seedcal_seeds maxattempt 1000 "
       "insert_every once overlapcheck yes all_in yes particles_in_region ${count} region seedcal_pour\n";
  o << "fix seedcal_integrate all multisphere\n";
  o << "compute seedcal_ke all ke/multisphere\ncompute seedcal_erot all erotate/multisphere\n";
  o << "variable seedcal_ke_j equal c_seedcal_ke+c_seedcal_erot\n";
  o << "thermo_style    custom step atoms c_seedcal_ke c_seedcal_erot\n";
  o << "thermo          $(round(0.05/v_dt_s))\n";
  o << "thermo_modify   lost error norm no\n";
  o << "run             1\nunfix           seedcal_pour\n\n";
  // seedcal's settle rule (solver/sim/settle.hpp): mean kinetic energy per body below
  // ratio x m g d, d twice the largest sphere radius.
  o << "# Settle: kinetic energy per body below settle_energy_ratio x m g d, m g d = "
    << exact_number_text(m.seeds.body.mass_kg * g * 2.0 * m.largest_sphere_radius_m()) << " J\n";
  o << "variable seedcal_ke_limit_j equal ${settle_energy_ratio}*${count}*"
    << exact_number_text(m.seeds.body.mass_kg * g * 2.0 * m.largest_sphere_radius_m()) << "\n";
  o << "variable seedcal_min_time_s equal sqrt(2.0*${insert_hi_z_m}/" << exact_number_text(g) << ")\n";
  o << "variable seedcal_check_steps equal round(${check_interval_s}/${dt_s})\n";
  o << "variable seedcal_state string settling\n";
  o << "label seedcal_settle\n";
  o << "run             ${seedcal_check_steps} post no\n";
  o << "if \"$(time) >= ${seedcal_min_time_s} && ${seedcal_ke_j} < ${seedcal_ke_limit_j}\" then "
       "\"variable seedcal_state string settled\" \"jump SELF seedcal_done\"\n";
  o << "if \"$(time) >= ${max_time_s}\" then \"variable seedcal_state string not_settled\" \"jump SELF seedcal_done\"\n";
  o << "jump SELF seedcal_settle\n";
  o << "label seedcal_done\n\n";
  o << "# Every body's centre and mass\n";
  o << "compute seedcal_xcm all multisphere property xcm\ncompute seedcal_mass all multisphere property masstotal\n";
  o << "run             0 post no\n";
  o << "write_dump all local ${bodies_file} c_seedcal_xcm[1] c_seedcal_xcm[2] c_seedcal_xcm[3] c_seedcal_mass\n";
  o << "variable seedcal_bodies equal atoms/${seedcal_clump_spheres}\n";
  o << "print \"seedcal settle: ${seedcal_state} at t = $(time) s: $(v_seedcal_bodies) of ${count} clumps, kinetic "
       "energy $(v_seedcal_ke_j) J (limit $(v_seedcal_ke_limit_j) J), bodies in ${bodies_file}\"\n";
  return o.str();
}

void write_liggghts_export(const ExportedModel& m, const std::string& dir, const SettleDeck& deck) {
  std::filesystem::create_directories(dir);
  write_file_atomic(dir + "/in.seedcal_model", liggghts_fragment(m));
  write_file_atomic(dir + "/in.settle", liggghts_settle_deck(m, deck));
}

}  // namespace seedcal
