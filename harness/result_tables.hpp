#pragma once
// The CSV tables a solve writes next to its VTU output, row by row and flushed, so a run
// that stops early keeps every finished row: steps.csv (one row per load step: Newton and
// Krylov totals, times, forces F1-F5, contact states) and iterations.csv (one row per Newton
// iteration: residuals, step length, contact state changes, the linear solve).
#include <fstream>
#include <string>

#include "nonlinear/newton.hpp"
#include "scene/scene.hpp"

namespace stiction::harness {

class StepTable {
public:
  StepTable(const std::string& path, const std::string& header_comment, const scene::Scene& s);
  void add(const nonlinear::StepResult& r, const scene::Scene& s);

private:
  std::ofstream out_;
};

class IterationTable {
public:
  IterationTable(const std::string& path, const std::string& header_comment, bool contact);
  void add(const nonlinear::StepResult& r);

private:
  std::ofstream out_;
  bool contact_;
};

}  // namespace stiction::harness
