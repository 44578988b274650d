#pragma once
// stiction's subcommands and their options (CLI11), each subcommand's filled into its
// options struct when the command line is parsed. Arguments of the form -name (one dash)
// are PETSc options and are taken out before parsing (main.cpp).
#include <CLI/CLI.hpp>

#include <string>

#include "atlas_command.hpp"
#include "bench_command.hpp"
#include "replay_command.hpp"
#include "solve_command.hpp"
#include "tradeoff_command.hpp"

namespace stiction::harness {

class CommandLine {
 public:
  CommandLine();  // declares every subcommand
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  CLI::App app;
  SolveOptions solve;
  bool no_vtu = false;  // solve --no-vtu
  ReplayOptions replay;
  bool schema = false;  // scenes --schema
  BenchOptions bench;
  TradeoffOptions tradeoff;
  AtlasOptions atlas;
  std::string report_dir;
  bool report_headline = false;  // report --headline
  CLI::App *solve_cmd = nullptr, *replay_cmd = nullptr, *scenes_cmd = nullptr, *solvers_cmd = nullptr,
           *bench_cmd = nullptr, *tradeoff_cmd = nullptr, *atlas_cmd = nullptr, *report_cmd = nullptr;

 private:
  void declare_solve();
  void declare_replay();
  void declare_bench();
  void declare_tradeoff();
  void declare_atlas();
};

}  // namespace stiction::harness
