#pragma once
// The recorded sample of a sweep (`stiction bench --sample STEP:IT,...`): the whole run of
// the path backend records the chosen Newton systems of each scene and level, then every
// backend solves those same systems in a process of its own (`stiction replay`): every
// backend is compared on identical matrices without a whole run of its own. One row per
// (scene, level, backend) goes to samples.csv.
#include <map>
#include <string>
#include <vector>

#include "child_process.hpp"

namespace stiction::harness {

extern const char* const kSampleColumns;

// The sample's folders in a sweep directory: the recorded systems of a scene and level,
// and one backend's replay of them.
std::string sample_record_dir(const std::string& out_dir, const std::string& scene, int level);
std::string sample_run_dir(const std::string& out_dir, const std::string& scene, int level, const std::string& solver);

// The arguments a path run adds to its `stiction solve` to record the sample.
std::vector<std::string> record_arguments(const std::string& record_dir, const std::vector<std::string>& systems);
// `stiction replay` of the sample by `solver`, writing replay.csv into run_dir.
std::vector<std::string> replay_arguments(const std::string& exe, const std::string& record_dir,
                                          const std::string& solver, const std::string& run_dir);

// The row of samples.csv for one backend's replay (its replay.csv in run_dir, how its child
// ended), with the total that backend's solves would have given on the path run
// (`path_row`, its runs.csv row; empty when there is none) labelled as projected.
std::string sample_row(const std::string& scene, int level, const std::string& solver, const std::string& run_dir,
                       const ChildResult& child, const std::map<std::string, std::string>& path_row,
                       int systems_requested, const std::string& revision);
// The same row for a backend whose replay never ran: the path run recorded no system.
std::string unrecorded_sample_row(const std::string& scene, int level, const std::string& solver,
                                  const std::string& why, const std::string& revision);

// Whole-run seconds of a path run with its linear solves' time replaced by `linear_solves`
// solves of `seconds_per_solve` each: what another backend's solves would have cost on the
// same Newton path (0 when the path run gives no basis).
double projected_total_seconds(const std::map<std::string, std::string>& path_row, double seconds_per_solve);

}  // namespace stiction::harness
