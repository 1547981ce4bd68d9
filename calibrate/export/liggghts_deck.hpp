#pragma once
// The LIGGGHTS-PUBLIC 3.x export (docs/export.md):
//   DIR/in.seedcal_model  a fragment: one atom type per material (the seeds' first), the materials
//                         and interactions as `fix property/global`, the closest contact and rolling
//                         model (pair_style gran and the variable seedcal_contact for wall/gran), and
//                         the clump as a multisphere template with its exact mass and inertia
//                         (particle distribution seedcal_seeds);
//   DIR/in.settle         a complete deck that includes the fragment, pours `count` clumps into an
//                         open box with plane walls, lets them settle (kinetic energy per body below
//                         settle_energy_ratio x m g d, seedcal's rule) and writes every body's centre
//                         and mass.
// Both headers state where the values come from and what does not carry over exactly.
#include <string>

#include "calibrate/export/exported_model.hpp"

namespace seedcal {

// in.settle's defaults; each is an `index` variable, so `liggghts -var NAME VALUE` overrides it.
struct SettleDeck {
  int count = 300;                  // clumps poured
  double box_x_m = 0.0, box_y_m = 0.0;
  double wall_height_m = 0.0;       // the box's side walls (open top)
  double insert_lo_z_m = 0.0, insert_hi_z_m = 0.0;  // the pour region: the box's plan, these heights
  double dt_s = 0.0;
  double settle_energy_ratio = 1e-4;
  double check_interval_s = 0.005;  // how often the kinetic energy is checked
  double max_time_s = 5.0;
  int seed = 10007;                 // the insertion's random seed (LIGGGHTS wants a prime > 10000)
};

// A pour of `count` clumps (seedcal's bulk-density protocol scaled to them): a square box six
// bounding diameters wide, side walls three bed heights tall (the bed height estimated at a solid
// fraction of 0.5), clumps placed at random between 0.3 and 3 bed heights, seedcal's time step for
// a fall from the top of the walls.
SettleDeck default_settle_deck(const ExportedModel& m, int count = 300);

std::string liggghts_fragment(const ExportedModel& m);
std::string liggghts_settle_deck(const ExportedModel& m, const SettleDeck& deck,
                                 const std::string& fragment_file = "in.seedcal_model");

// Writes DIR/in.seedcal_model and DIR/in.settle (each atomically; DIR is created).
void write_liggghts_export(const ExportedModel& m, const std::string& dir, const SettleDeck& deck);

}  // namespace seedcal
