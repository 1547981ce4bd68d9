#pragma once
// Rig-to-seed checks: a rig only a few seeds across measures its walls more than the seeds. Every
// bulk scene compares its rig's sizes with the seed's length and warns (TomlReader::warn: on
// stderr before the run and in metrics.json `warnings`), naming the key to change. The thresholds
// and their sources are in rig_checks.cpp and docs/scenes/README.md ("Rig and seed size").
#include <string>

#include "calibrate/config/toml_reader.hpp"
#include "solver/scenes/seed_bed.hpp"

namespace seedcal {

// The seed's length: the clump's largest extent along its principal axes (the body frame its
// spheres are given in), times the mean of the size distribution.
double seed_length_m(const SeedSpec& seeds);

// The minimum sizes, in seed lengths.
struct RigMinimum {
  double lengths;          // the size must be at least this many seed lengths
  const char* reason;      // why, with its source
};
inline constexpr RigMinimum kShearBoxDiameter{
    6.0, "the rings' walls, not the sample, carry much of the shear in a box a few particles across; soil "
         "testing standards ask a box of 6 to 10 largest particles across (ASTM D3080, GB/T 50123)"};
inline constexpr RigMinimum kShearSampleHeight{
    2.0, "below two seed lengths no layer of seeds lies wholly on each side of the shear plane"};
inline constexpr RigMinimum kPilingTube{
    5.0, "a tube under about 5 particles across arches and empties in bursts as it lifts (clogging of an "
         "opening of under 5 particle diameters: Zuriguel et al. 2005, Phys. Rev. E 71, 051303)"};
inline constexpr RigMinimum kBulkContainer{
    5.0, "the packing is looser within about a particle size of a wall (Benenati & Brosilow 1962, AIChE J. "
         "8, 359), so a container a few seeds across reads a bulk density too low"};
inline constexpr RigMinimum kDrumBed{
    3.0, "the surface line is fitted to a bed a few seeds deep; below three seed lengths it fits single seeds"};
inline constexpr RigMinimum kDrumDepth{
    3.0, "a drum under three seeds deep is held by its end walls more than by the shell"};

// Warns on `rig` at `key` when `size_m` is under `min.lengths` seed lengths. `what` names the size
// (e.g. "the box's diameter"); `fix` says how to change it when `key` is not the size itself
// (default: raise `key`).
void warn_if_small_rig(TomlReader& rig, const std::string& key, const std::string& what, double size_m,
                       const SeedSpec& seeds, const RigMinimum& min, const std::string& fix = "");

}  // namespace seedcal
