#pragma once
// The CSV tables a solve writes next to its VTU output, row by row and flushed, so a run
// that stops early keeps every finished row (a restarted run appends to them, its header
// repeated as comments): steps.csv (one row per load step: Newton and
// Krylov totals, times, forces F1-F5, contact states) and iterations.csv (one row per Newton
// iteration: residuals, step length, contact state changes, the linear solve).
#include <fstream>
#include <string>

#include "nonlinear/newton.hpp"
#include "scene/scene.hpp"
#include "scene/scene_view.hpp"

namespace stiction::harness {

class StepTable {
public:
  StepTable(const std::string& path, const std::string& header_comment, const scene::SceneView& s,
            bool append = false);
  void add(const nonlinear::StepResult& r, const scene::SceneView& s);

private:
  std::ofstream out_;
};

// contact.csv: one row per multiplier node of every contact pair at every completed load
// step: position, mean normal gap, multiplier (and its normal and tangential parts), state.
class ContactTable {
public:
  ContactTable(const std::string& path, const std::string& header_comment, int dim, bool append = false);
  // u need hold the contact surfaces' unknowns only (any process's ghosted storage does).
  void add(const nonlinear::StepResult& r, const scene::SceneView& s, fem::StateView u,
           const std::vector<double>& lambda);

private:
  std::ofstream out_;
  int dim_;
};

// The multiplier nodes of every constraint of p at (t, u, lambda), with each one's name.
std::vector<std::pair<std::string, std::vector<nonlinear::MultiplierNode>>> multiplier_nodes(
    const nonlinear::ElasticityProblem& p, double t, fem::StateView u, const std::vector<double>& lambda);

class IterationTable {
public:
  IterationTable(const std::string& path, const std::string& header_comment, bool contact, bool append = false);
  void add(const nonlinear::StepResult& r);

private:
  std::ofstream out_;
  bool contact_;
};

}  // namespace stiction::harness
