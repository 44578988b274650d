#pragma once
// The PETSc settings a bench run's backend ran with: the defaults of the stiction that made
// the run (its metrics.toml records them as backend_options) with the options the sweep gave
// on top. Two runs with the same settings ran the same Krylov method and preconditioner,
// whichever defaults each version had: a restart given on the command line at one level
// and made the default before another level ran is the same method at both.
#include <map>
#include <string>

namespace stiction::harness {

// The settings in a backend_options text, as "-key value" pairs sorted and joined by
// spaces. Keys are taken relative to the backend's prefix (the defaults are written
// relative, options from the command line carry the prefix:
// "-schur_amg_ksp_gmres_restart 50"); a later option replaces an earlier one of the same key
// (the command line, recorded after the defaults, won in the run); comments are dropped.
std::string effective_backend_settings(const std::string& backend_options, const std::string& solver);

// Those of the run a runs.csv row records, from <out_dir>/runs/<run>/metrics.toml; "" when
// the file, or its backend_options, is missing or unreadable.
std::string run_backend_settings(const std::string& out_dir, const std::map<std::string, std::string>& row);

}  // namespace stiction::harness
