#include "scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "common/error.hpp"
#include "contact/rigid_plane_contact.hpp"
#include "contact/surface_contact.hpp"
#include "mesh/gmsh_io.hpp"
#include "mesh/grooved_block.hpp"
#include "mesh/structured_tube.hpp"
#include "nonlinear/load_schedule.hpp"
#include "scene/overrides.hpp"

namespace stiction::scene {

namespace {

using VT = ValueType;

// Every key of a scene file, with its type, default and a one-line doc.
struct Schemas {
  TableSpec scene_meta, material, size_field, mesh, body, dirichlet, traction, body_force, contact, phase, load, newton, output,
      root;
  Schemas() {
    // The defaults of the Newton and load-stepping keys are NewtonSettings' own.
    const nonlinear::NewtonSettings nd;
    scene_meta = {"scene",
                  {{"name", VT::String, "scene name (defaults to the file name)", false, std::string()},
                   {"description", VT::String, "one line on what the scene shows", false, std::string()},
                   {"basis", VT::String, "displacement basis", false, std::string("p2-hierarchical"),
                    {"p2-hierarchical", "p2-nodal", "p1"}},
                   {"level", VT::Integer, "uniform refinements of the level-0 meshes (--level overrides)", false,
                    std::int64_t{0}}}};
    material = {"material",
                {{"name", VT::String, "name bodies refer to", true},
                 {"model", VT::String, "constitutive law (neo-hookean: Wriggers' form, the paper's; neo-hookean-bonet: Bonet & Wood's)", true, {},
                  {"linear", "neo-hookean", "neo-hookean-bonet", "mooney-rivlin"}},
                 {"E", VT::Float, "Young's modulus (linear, neo-hookean)", false},
                 {"nu", VT::Float, "Poisson's ratio (linear, neo-hookean)", false},
                 {"mu10", VT::Float, "Mooney-Rivlin coefficient of I1", false},
                 {"mu01", VT::Float, "Mooney-Rivlin coefficient of I2", false},
                 {"kappa", VT::Float, "Mooney-Rivlin bulk modulus", false},
                 {"formulation", VT::String, "Mooney-Rivlin unknowns: mixed u-p (paper) or displacement only", false,
                  std::string("mixed"), {"mixed", "displacement"}}}};
    size_field = {"size_field",
                  {{"boundary", VT::String, "a side name of this body", true},
                   {"size", VT::Float, "element size on that boundary (<= h)", true},
                   {"distance", VT::Float, "distance from it at which the size has grown to h", true}}};
    mesh = {"mesh",
            {{"file", VT::String, "Gmsh .msh file (version 4), or a .geo script meshed through the Gmsh library (a level re-meshes it at sizes / 2^level)", false},
             {"generator", VT::String, "built-in geometry instead of a file", false, {}, {"box", "structured-box", "polygon", "sphere-octant", "tube", "grooved-block"}},
             {"points", VT::FloatArray, "'polygon': corners x0, y0, x1, y1, ... counter-clockwise", false},
             {"sides", VT::StringArray, "'polygon': boundary name of each side (side i joins point i to i+1)", false},
             {"thickness", VT::Float, "'polygon': extrusion along z for a 3D body (faces 'front', 'back'); 'tube': wall thickness", false},
             {"point_sizes", VT::FloatArray, "'polygon': element size at each point (grading; each <= h)", false},
             {"size_fields", VT::TableArray, "'polygon': sizes growing with the distance from named sides [{boundary, size, distance}, ...]", false, {}, {}, &size_field},
             {"arc_sides", VT::FloatArray, "'polygon': sides that are circular arcs (re-meshed per level)", false},
             {"arc_centers", VT::FloatArray, "'polygon': centre x, y of each arc side", false},
             {"size", VT::FloatArray, fmt::format("box side lengths [lx, ly] (2D) or [lx, ly, lz] (3D); 'grooved-block': [lx, ly, lz] (default the "
                                                "paper's [{}, {}, {}])", mesh::GroovedBlockSpec{}.size[0], mesh::GroovedBlockSpec{}.size[1],
                                                mesh::GroovedBlockSpec{}.size[2]), false},
             {"h", VT::Float, fmt::format("target element size for the 'box', 'polygon' and 'sphere-octant' generators (Gmsh); 'grooved-block': "
                                          "size at the top (default {})", mesh::GroovedBlockSpec{}.h), false},
             {"radius", VT::Float, "'sphere-octant': radius R (pole at the origin, ball above or below it: see pole)", false},
             {"contact_size", VT::Float, fmt::format("'sphere-octant': element size near the pole (<= h); 'grooved-block': size on the strip bottoms, "
                                                     "growing linearly in z to h at the top (default {})", mesh::GroovedBlockSpec{}.contact_size), false},
             {"contact_zone", VT::Float, "'sphere-octant': distance from the pole meshed at contact_size", false, 0.0},
             {"pole", VT::String, "'sphere-octant': 'bottom' (ball above the origin, flat face 'top') or 'top' (ball below it, flat face 'base')", false, std::string("bottom"), {"bottom", "top"}},
             {"cells", VT::FloatArray, "cells per side for 'structured-box'; 'tube': through the thickness, around, along", false},
             {"inner_radius", VT::Float, "'tube': inner radius", false},
             {"length", VT::Float, "'tube': length along the axis from center", false},
             {"axis", VT::String, "'tube': axis direction", false, std::string("z"), {"x", "y", "z"}},
             {"center", VT::FloatArray, "'tube': x, y, z of the axis point at the tube's start face", false},
             {"angles", VT::FloatArray, "'tube': first and last angle around the axis in degrees (from y, z or x for axis x, y or z)", false},
             {"inner_split", VT::Float, "'tube': an angle between the two at which the inner cylinder is named in two halves, 'inner0' and "
                                        "'inner1' (a self-contact pair for a tube that flattens)", false},
             {"grooves", VT::Integer, "'grooved-block': number of grooves along y in the bottom face (z = 0), evenly spaced between equal strips", false,
              std::int64_t{mesh::GroovedBlockSpec{}.grooves}},
             {"groove_width", VT::Float, "'grooved-block': groove width along x", false, mesh::GroovedBlockSpec{}.groove_width},
             {"groove_depth", VT::Float, "'grooved-block': groove depth along z (< lz); the groove ceilings are 'groove-floor'", false,
              mesh::GroovedBlockSpec{}.groove_depth}}};
    body = {"body",
            {{"name", VT::String, "body name (prefix of its boundary names: 'block/top')", true},
             {"material", VT::String, "name of a [[material]]", true},
             {"mesh", VT::Table, "where the level-0 mesh comes from", true, {}, {}, &mesh}}};
    dirichlet = {"dirichlet",
                 {{"body", VT::String, "body of the boundary (optional with one body)", false},
                  {"boundary", VT::String, "boundary name (physical group) of the body", true},
                  {"components", VT::StringArray, "constrained components", true, {}, {"x", "y", "z"}},
                  {"value", VT::FloatArray, "final prescribed displacement, one per listed component", false},
                  {"schedule", VT::FloatArray, "factor on value at each load step (default: the step's pseudo-time / the last's)", false},
                  {"table", VT::FloatRows, "rows [t, one value per listed component]: piecewise-linear in pseudo-time, instead of value and schedule", false}}};
    traction = {"traction",
                {{"body", VT::String, "body of the boundary (optional with one body)", false},
                 {"boundary", VT::String, "boundary name (physical group) of the body", true},
                 {"value", VT::FloatArray, "final dead-load traction per reference area, one per dimension", false},
                 {"schedule", VT::FloatArray, "factor on value at each load step (default: the step's pseudo-time / the last's)", false},
                 {"table", VT::FloatRows, "rows [t, one value per dimension]: piecewise-linear in pseudo-time, instead of value and schedule", false}}};
    body_force = {"body_force",
                  {{"value", VT::FloatArray, "final body force per reference volume", false},
                   {"schedule", VT::FloatArray, "factor on value at each load step (default: the step's pseudo-time / the last's)", false},
                   {"table", VT::FloatRows, "rows [t, one value per dimension]: piecewise-linear in pseudo-time, instead of value and schedule", false}}};
    contact = {"contact",
               {{"name", VT::String, "name in reports (default contact-<k>)", false, std::string()},
                {"body", VT::String, "slave body (optional with one body)", false},
                {"boundary", VT::String, "slave boundary name of the body (carries the multiplier)", true},
                {"master", VT::String, "what the slave touches: a rigid plane or a deformable surface", true, {},
                 {"plane", "surface"}},
                {"master_body", VT::String, "'surface': body of the master boundary (default: the slave body)", false},
                {"master_boundary", VT::String, "'surface': master boundary name of that body", false},
                {"search_radius", VT::Float, "'surface': farthest projection counted (default 2x longest master facet)",
                 false, 0.0},
                {"point", VT::FloatArray, "'plane': a point of the plane at step 0", false},
                {"normal", VT::FloatArray, "'plane': normal pointing towards the slave body", false},
                {"motion", VT::FloatArray, "'plane': final rigid translation of the plane", false},
                {"schedule", VT::FloatArray, "factor on motion at each load step (default: the step's pseudo-time / the last's)", false},
                {"motion_table", VT::FloatRows, "'plane': rows [t, translation per dimension], piecewise-linear in pseudo-time, instead of motion and schedule", false},
                {"friction", VT::Float, "Coulomb coefficient mu (0: frictionless)", false, 0.0},
                {"friction_table", VT::FloatRows, "instead of friction: rows [t, mu]; an increment ending at t uses the mu of the last row before t (the first row's until then)", false},
                {"gap_tolerance", VT::Float, "state machine: penetration tolerance, relative to the slave size",
                 false, 1e-9},
                {"force_tolerance", VT::Float, "state machine: tension tolerance on lambda_n, relative to E", false,
                 1e-9},
                {"tangential_penalty", VT::Float, "initial r_t of (19), in units of E / (h m_i)", false, 1.0},
                {"tangential_penalty_floor", VT::Float,
                 "smallest r_t the adaptation of Sec. 4.3 may reach, relative to the initial r_t (0: no floor)", false,
                 contact::ContactSettings{}.tangential_penalty_floor},
                {"normal_linearisation", VT::String,
                 "'surface': the nodal normals' variation in the Jacobian: always, never (the paper), or once the "
                 "states settled",
                 false, std::string("settled"), {"exact", "dropped", "settled"}},
                {"master_point", VT::String,
                 "'surface', 3D: the slave point's partner on the master: where the slave normal crosses it "
                 "(default) or the closest point (the paper's; 2D always uses the closest point)",
                 false, std::string("normal-crossing"), {"normal-crossing", "closest"}},
                {"mass_weighted_rows", VT::Boolean,
                 "rows in traction units (released nodes, slip tangential) times the lumped mass m_i", false,
                 false}}};
    phase = {"phase",
             {{"until", VT::Float, "pseudo-time at which the phase ends", true},
              {"steps", VT::Integer, "equal load steps in the phase", true}}};
    load = {"load",
            {{"steps", VT::Integer, "equal load steps over pseudo-time [0, 1] (without phases)", false, std::int64_t{1}},
             {"phases", VT::TableArray, "instead of steps: consecutive phases [{until = t, steps = n}, ...]", false, {},
              {}, &phase},
             {"max_cuts", VT::Integer, "halvings of a failed load increment before the run stops (0: off)", false,
              std::int64_t{nd.max_cuts}},
             {"max_regrow_wait", VT::Integer,
              "converged parts at a cut size before a size that failed again is retried: 2, doubled at each such "
              "failure up to this (2: always 2)",
              false, std::int64_t{nd.max_regrow_wait}},
             {"quick_until", VT::Float, "pseudo-time where the scene's short version (--quick) stops (default: the end)",
              false}}};
    newton = {"newton",
              {{"atol", VT::Float, "absolute tolerance on the free residual norm", false, nd.atol},
               {"rtol", VT::Float, "tolerance relative to the step's reference residual", false, nd.rtol},
               {"max_iterations", VT::Integer, "Newton iterations per load step", false, std::int64_t{nd.max_iterations}},
               {"max_backtracks", VT::Integer, "step halvings when a trial state inverts a cell", false,
                std::int64_t{nd.max_backtracks}},
               {"min_det_f_ratio", VT::Float,
                "an increment whose smallest det F falls below this fraction of its start's is cut (0: never)", false,
                nd.min_det_f_ratio},
               {"forcing", VT::String, "Krylov tolerance per Newton step (inexact Newton)", false, to_string(nd.forcing),
                {"fixed", "eisenstat-walker"}},
               {"krylov_rtol", VT::Float,
                "relative tolerance of every Krylov solve, in place of the backend's -ksp_rtol (0: the backend's; "
                "with eisenstat-walker, the cap on its forcing term under contact)",
                false, nd.krylov_rtol},
               {"krylov_restart", VT::Integer,
                "restart of every GMRES backend's Krylov solve, in place of its -ksp_gmres_restart (0: the backend's)",
                false, std::int64_t{nd.krylov_restart}},
               {"state_update_tolerance", VT::Float,
                "contact states change only at iterates that solve their states to this relative residual (0: after "
                "every solve, as the paper)",
                false, nd.active_set.update_tolerance},
               {"max_held_iterations", VT::Integer, "Newton iterations the contact states may be held before an update",
                false, std::int64_t{nd.active_set.max_held}},
               {"cycle_remedies", VT::Integer,
                "times a contact-state cycle tightens the update tolerance before the increment fails", false,
                std::int64_t{nd.active_set.cycle_remedies}},
               {"cycle_remedy_factor", VT::Float, "factor on state_update_tolerance per remedy", false,
                nd.active_set.remedy_factor}}};
    output = {"output",
              {{"vtu", VT::Boolean, "write a VTU per load step and a PVD collection", false, true},
               {"vtu_format", VT::String,
                "VTU arrays: zlib-compressed binary in the appended section (what ParaView writes), or ASCII "
                "(for diffing and debugging)",
                false, std::string("binary"), {"binary", "ascii"}},
               {"csv", VT::Boolean, "write per-step quantities as CSV", false, true}}};
    root = {"",
            {{"scene", VT::Table, "name and description", false, {}, {}, &scene_meta},
             {"material", VT::TableArray, "constitutive laws", true, {}, {}, &material},
             {"body", VT::TableArray, "deformable bodies", true, {}, {}, &body},
             {"dirichlet", VT::TableArray, "prescribed displacements", false, {}, {}, &dirichlet},
             {"traction", VT::TableArray, "prescribed tractions", false, {}, {}, &traction},
             {"body_force", VT::Table, "volume load", false, {}, {}, &body_force},
             {"contact", VT::TableArray, "contact pairs (paper Sec. 4)", false, {}, {}, &contact},
             {"load", VT::Table, "load stepping", false, {}, {}, &load},
             {"newton", VT::Table, "Newton settings", false, {}, {}, &newton},
             {"output", VT::Table, "what `stiction solve` writes", false, {}, {}, &output}}};
  }
};

const Schemas& schemas() {
  static const Schemas s;
  return s;
}

const toml::table& sub(const toml::table& t, const char* key) {
  static const toml::table empty;
  const toml::table* p = t[key].as_table();
  return p ? *p : empty;
}

std::vector<const toml::table*> tables(const toml::table& t, const char* key) {
  std::vector<const toml::table*> out;
  if (const auto* a = t[key].as_array())
    for (const auto& e : *a) out.push_back(e.as_table());
  return out;
}

std::unique_ptr<materials::Material> make_material(const toml::table& t, const std::string& file) {
  const auto& S = schemas().material;
  const std::string model = get_string(t, S, "model"), name = get_string(t, S, "name");
  // The keys a model needs (and may take), and none of another model's.
  const bool mooney = model == "mooney-rivlin";
  const std::vector<std::string> needs = mooney ? std::vector<std::string>{"mu10", "mu01", "kappa"}
                                                : std::vector<std::string>{"E", "nu"};
  std::vector<std::string> takes = needs;
  if (mooney) takes.push_back("formulation");
  for (const auto& k : needs)
    if (!t.contains(k)) throw Error(fmt::format("{}: material '{}': model '{}' needs key '{}'", file, name, model, k));
  for (const char* k : {"E", "nu", "mu10", "mu01", "kappa", "formulation"})
    if (t.contains(k) && std::find(takes.begin(), takes.end(), k) == takes.end())
      throw Error(fmt::format("{}: material '{}': key '{}' does not apply to model '{}'", file, name, k, model));
  try {
    if (model == "linear") return std::make_unique<materials::LinearElastic>(get_float(t, S, "E"), get_float(t, S, "nu"));
    if (model == "neo-hookean" || model == "neo-hookean-bonet")
      return std::make_unique<materials::NeoHookean>(get_float(t, S, "E"), get_float(t, S, "nu"),
                                                     model == "neo-hookean" ? materials::NeoHookean::Form::Wriggers
                                                                            : materials::NeoHookean::Form::Bonet);
    const auto form = get_string(t, S, "formulation") == "mixed" ? materials::MooneyRivlin::Form::Mixed
                                                                 : materials::MooneyRivlin::Form::Displacement;
    return std::make_unique<materials::MooneyRivlin>(get_float(t, S, "mu10"), get_float(t, S, "mu01"),
                                                     get_float(t, S, "kappa"), form);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: material '{}': {}", file, name, e.what()), e.kind());
  }
}

// The 'tube' generator's mesh at `level` (2^level times the level-0 cells: vertices stay on
// the cylinders).
mesh::Mesh make_tube_mesh(const toml::table& t, const std::string& file, const std::string& body, int level,
                          bool* refined) {
  const auto& S = schemas().mesh;
  for (const char* key : {"inner_radius", "thickness", "length", "center", "angles", "cells"})
    if (!t.contains(key)) throw Error(fmt::format("{}: body '{}': the 'tube' generator needs mesh.{}", file, body, key));
  mesh::TubeSpec spec;
  spec.inner_radius = get_float(t, S, "inner_radius");
  spec.thickness = get_float(t, S, "thickness");
  spec.length = get_float(t, S, "length");
  spec.axis = get_string(t, S, "axis")[0] - 'x';
  const auto center = get_floats(t, "center"), angles = get_floats(t, "angles"), cells = get_floats(t, "cells");
  if (center.size() != 3 || angles.size() != 2 || cells.size() != 3)
    throw Error(fmt::format("{}: body '{}': 'tube' needs 3 center coordinates, 2 angles and 3 cell counts", file, body));
  for (int k = 0; k < 3; ++k) {
    spec.center[k] = center[k];
    if (cells[k] < 1 || cells[k] != std::floor(cells[k]))
      throw Error(fmt::format("{}: body '{}': mesh.cells must be positive integers", file, body));
    spec.cells[k] = static_cast<int>(cells[k]) << level;
  }
  spec.angles_degrees = {angles[0], angles[1]};
  if (t.contains("inner_split")) spec.inner_split_degrees = get_float(t, S, "inner_split");
  *refined = true;
  try {
    return mesh::structured_tube(spec);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: body '{}': {}", file, body, e.what()), e.kind());
  }
}

// The 'grooved-block' generator's level-0 mesh (the paper's block with strips). Its faces
// are flat, so levels are uniform refinements of it (8x the tetrahedra per level, as the
// paper's Table 1), not new meshes. Absent keys keep GroovedBlockSpec's defaults.
mesh::Mesh make_grooved_block_mesh(const toml::table& t, const std::string& file, const std::string& body) {
  const auto& S = schemas().mesh;
  mesh::GroovedBlockSpec spec;
  if (t.contains("size")) {
    const auto size = get_floats(t, "size");
    if (size.size() != 3)
      throw Error(fmt::format("{}: body '{}': 'grooved-block' needs mesh.size = [lx, ly, lz]", file, body));
    spec.size = {size[0], size[1], size[2]};
  }
  const std::int64_t grooves = get_int(t, S, "grooves");
  if (grooves < 1 || grooves > 10000)
    throw Error(fmt::format("{}: body '{}': mesh.grooves = {} (1 to 10000)", file, body, grooves));
  spec.grooves = static_cast<int>(grooves);
  spec.groove_width = get_float(t, S, "groove_width");
  spec.groove_depth = get_float(t, S, "groove_depth");
  if (t.contains("h")) spec.h = get_float(t, S, "h");
  if (t.contains("contact_size")) spec.contact_size = get_float(t, S, "contact_size");
  try {
    return mesh::generate_grooved_block(spec);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: body '{}': {}", file, body, e.what()), e.kind());
  }
}

// `refined` is set when the generator already produced the mesh at `level`.
mesh::Mesh make_body_mesh(const toml::table& t, const std::string& file, const std::string& base_dir,
                          const std::string& body, int level, bool* refined) {
  const auto& S = schemas().mesh;
  const bool has_file = t.contains("file"), has_gen = t.contains("generator");
  if (has_file == has_gen)
    throw Error(fmt::format("{}: body '{}': give exactly one of mesh.file and mesh.generator", file, body));
  if (has_file) {
    std::filesystem::path p = get_string(t, S, "file");
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    if (p.extension() == ".geo") {
      *refined = true;  // re-meshed per level: curved boundaries stay on the geometry
      return mesh::mesh_geo(p.string(), std::ldexp(1.0, -level));
    }
    return mesh::read_msh(p.string());
  }
  const std::string gen = get_string(t, S, "generator");
  if (gen == "polygon") {
    if (!t.contains("h")) throw Error(fmt::format("{}: body '{}': the 'polygon' generator needs mesh.h", file, body));
    mesh::PolygonSpec spec;
    spec.xy = get_floats(t, "points");
    spec.names = get_strings(t, "sides");
    spec.h = get_float(t, S, "h");
    spec.thickness = t.contains("thickness") ? get_float(t, S, "thickness") : 0.0;
    spec.point_sizes = get_floats(t, "point_sizes");
    for (const auto* f : tables(t, "size_fields"))
      spec.size_fields.push_back({get_string(*f, schemas().size_field, "boundary"),
                                  get_float(*f, schemas().size_field, "size"),
                                  get_float(*f, schemas().size_field, "distance")});
    const auto arc_sides = get_floats(t, "arc_sides"), centres = get_floats(t, "arc_centers");
    if (centres.size() != 2 * arc_sides.size())
      throw Error(fmt::format("{}: body '{}': arc_centers needs x, y for each of the {} arc sides", file, body,
                              arc_sides.size()));
    for (size_t k = 0; k < arc_sides.size(); ++k)
      spec.arc_centers[static_cast<int>(arc_sides[k])] = {centres[2 * k], centres[2 * k + 1]};
    // Curved sides: a refined level is a new Gmsh mesh with sizes / 2^level, so the mesh
    // converges to the arcs themselves (red refinement would stay on the level-0 quadratic
    // arcs of the P2 cells).
    if (!spec.arc_centers.empty()) {
      spec.scale = std::ldexp(1.0, -level);
      *refined = true;
    }
    return mesh::generate_polygon(spec);
  }
  if (gen == "sphere-octant") {
    for (const char* key : {"h", "radius", "contact_size"})
      if (!t.contains(key)) throw Error(fmt::format("{}: body '{}': the 'sphere-octant' generator needs mesh.{}", file, body, key));
    mesh::SphereOctantSpec spec;
    spec.radius = get_float(t, S, "radius");
    spec.h = get_float(t, S, "h");
    spec.contact_size = get_float(t, S, "contact_size");
    spec.contact_zone = get_float(t, S, "contact_zone");
    spec.below = get_string(t, S, "pole") == "top";
    spec.scale = std::ldexp(1.0, -level);  // re-meshed per level: the sphere stays exact
    *refined = true;
    return mesh::generate_sphere_octant(spec);
  }
  if (gen == "tube") return make_tube_mesh(t, file, body, level, refined);
  if (gen == "grooved-block") return make_grooved_block_mesh(t, file, body);
  const auto size = get_floats(t, "size");
  if (size.size() != 2 && size.size() != 3)
    throw Error(fmt::format("{}: body '{}': mesh.size needs 2 (2D) or 3 (3D) lengths", file, body));
  const int dim = static_cast<int>(size.size());
  std::array<double, 3> L{size[0], size[1], dim == 3 ? size[2] : 0.0};
  if (gen == "box") {
    if (!t.contains("h")) throw Error(fmt::format("{}: body '{}': the 'box' generator needs mesh.h", file, body));
    return mesh::generate_box(dim, L, get_float(t, S, "h"));
  }
  const auto cells = get_floats(t, "cells");
  if (static_cast<int>(cells.size()) != dim)
    throw Error(fmt::format("{}: body '{}': 'structured-box' needs mesh.cells with {} entries", file, body, dim));
  std::array<int, 3> n{1, 1, 1};
  for (int k = 0; k < dim; ++k) {
    n[k] = static_cast<int>(cells[k]);
    if (n[k] < 1 || n[k] != cells[k]) throw Error(fmt::format("{}: body '{}': mesh.cells must be positive integers", file, body));
  }
  return mesh::structured_box(dim, L, n);
}

// The pseudo-time function of a load: `table` rows [t, v...] (n_values each after t), or
// `value_key` (n_values entries) times a factor per load step (`schedule`, default t_k / t_n),
// 0 at t = 0. Exactly one of the two forms.
nonlinear::PiecewiseLinear load_function(const toml::table& t, const std::vector<double>& step_times,
                                         const std::string& value_key, const std::string& table_key,
                                         std::vector<double> value, size_t n_values, const std::string& file,
                                         const std::string& what) {
  const bool has_table = t.contains(table_key), has_value = t.contains(value_key);
  if (has_table == has_value)
    throw Error(fmt::format("{}: {}: give exactly one of '{}' (with an optional schedule) and '{}'", file, what,
                            value_key, table_key));
  if (has_table) {
    if (t.contains("schedule"))
      throw Error(fmt::format("{}: {}: '{}' and 'schedule' exclude each other", file, what, table_key));
    std::vector<double> times;
    std::vector<std::vector<double>> rows;
    for (const auto& row : get_float_rows(t, table_key)) {
      if (row.size() != n_values + 1)
        throw Error(fmt::format("{}: {}: every '{}' row needs {} numbers (t and {} values), one has {}", file, what,
                                table_key, n_values + 1, n_values, row.size()));
      times.push_back(row[0]);
      rows.emplace_back(row.begin() + 1, row.end());
    }
    try {
      return nonlinear::PiecewiseLinear(times, rows);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}: {}", file, what, e.what()), e.kind());
    }
  }
  const int n_steps = static_cast<int>(step_times.size()) - 1;
  std::vector<double> factor = get_floats(t, "schedule");
  if (factor.empty())
    for (int k = 1; k <= n_steps; ++k) factor.push_back(step_times[k] / step_times.back());
  if (static_cast<int>(factor.size()) != n_steps)
    throw Error(fmt::format("{}: {}: schedule has {} entries for {} load steps", file, what, factor.size(), n_steps));
  factor.insert(factor.begin(), 0.0);  // t = 0: unloaded
  std::vector<std::vector<double>> rows;
  for (double f : factor) {
    rows.push_back(value);
    for (double& v : rows.back()) v *= f;
  }
  return nonlinear::PiecewiseLinear(step_times, rows);
}

nonlinear::TimeField constant_in_space(nonlinear::PiecewiseLinear f) {
  return [f = std::move(f)](const double*, double t, double* out) { f(t, out); };
}

// The pseudo-times of the load steps: `steps` equal steps over [0, 1], or phases.
std::vector<double> step_times_of(const toml::table& load, const std::string& file) {
  const auto& S = schemas();
  const auto phases = tables(load, "phases");
  if (phases.empty()) {
    const int n = static_cast<int>(get_int(load, S.load, "steps"));
    if (n < 1) throw Error(fmt::format("{}: load.steps must be at least 1", file));
    return nonlinear::uniform_step_times(n);
  }
  if (load.contains("steps")) throw Error(fmt::format("{}: give load.steps or load.phases, not both", file));
  std::vector<double> times{0.0};
  for (size_t k = 0; k < phases.size(); ++k) {
    const double until = get_float(*phases[k], S.phase, "until");
    const auto n = get_int(*phases[k], S.phase, "steps");
    if (n < 1 || !(until > times.back()))
      throw Error(fmt::format("{}: load.phases[{}]: needs steps >= 1 and until > {} (the previous end)", file, k,
                              times.back()));
    const double start = times.back();
    for (int j = 1; j <= n; ++j) times.push_back(j == n ? until : start + (until - start) * j / n);
  }
  return times;
}

struct Boundary {
  int tag;
  std::string name;  // "body/boundary"
};

// The boundary `boundary` of body `body` (empty: the only body).
Boundary find_boundary(const Scene& s, std::string body, const std::string& boundary, const std::string& file,
                       const std::string& what) {
  if (body.empty()) {
    if (s.body_names.size() != 1)
      throw Error(fmt::format("{}: {}: name the body (the scene has {} bodies)", file, what, s.body_names.size()));
    body = s.body_names[0];
  }
  const std::string key = body + "/" + boundary;
  auto it = s.mesh.facet_tag_names.find(key);
  if (it != s.mesh.facet_tag_names.end()) return {it->second, key};
  std::string known;
  for (const auto& [n, tag] : s.mesh.facet_tag_names)
    if (n.rfind(body + "/", 0) == 0) known += (known.empty() ? "" : ", ") + n.substr(body.size() + 1);
  throw Error(fmt::format("{}: {}: body '{}' has no boundary '{}' (it has: {})", file, what, body, boundary,
                          known.empty() ? "none" : known));
}

Boundary boundary_of(const Scene& s, const toml::table& t, const std::string& file, const std::string& what) {
  return find_boundary(s, t["body"].value<std::string>().value_or(""), t["boundary"].value<std::string>().value_or(""),
                       file, what);
}

std::array<double, 3> three(const std::vector<double>& v, int dim, const std::string& where) {
  if (static_cast<int>(v.size()) != dim) throw Error(fmt::format("{} needs {} entries", where, dim));
  std::array<double, 3> a{0, 0, 0};
  std::copy(v.begin(), v.end(), a.begin());
  return a;
}

contact::RigidPlane make_plane(const toml::table& t, int dim, const std::string& file, const std::string& what,
                               const std::vector<double>& step_times) {
  for (const char* key : {"point", "normal"})
    if (!t.contains(key)) throw Error(fmt::format("{}: {}: master 'plane' needs key '{}'", file, what, key));
  contact::RigidPlane plane;
  plane.point = three(get_floats(t, "point"), dim, fmt::format("{}: {}: point", file, what));
  plane.normal = three(get_floats(t, "normal"), dim, fmt::format("{}: {}: normal", file, what));
  if (t.contains("motion") || t.contains("motion_table")) {
    const auto motion = get_floats(t, "motion");
    if (t.contains("motion")) three(motion, dim, fmt::format("{}: {}: motion", file, what));
    auto f = load_function(t, step_times, "motion", "motion_table", motion, static_cast<size_t>(dim), file, what);
    plane.motion = [f = std::move(f)](double time, double* out) { f(time, out); };
  }
  return plane;
}

std::unique_ptr<nonlinear::MultiplierConstraint> make_contact(const Scene& s, const toml::table& t,
                                                              const std::string& file, const std::string& what,
                                                              const std::vector<const materials::Material*>& body_material,
                                                              const std::vector<double>& step_times) {
  const auto& S = schemas().contact;
  const Boundary slave = boundary_of(s, t, file, what);
  const std::string slave_body = slave.name.substr(0, slave.name.find('/'));
  std::string name = get_string(t, S, "name");
  if (name.empty()) name = what;
  const std::string master = get_string(t, S, "master");
  const std::vector<std::string> plane_keys{"point", "normal", "motion", "schedule", "motion_table"},
      surface_keys{"master_body", "master_boundary", "search_radius", "normal_linearisation", "master_point"};
  for (const std::string& key : master == "plane" ? surface_keys : plane_keys)
    if (t.contains(key))
      throw Error(fmt::format("{}: {}: key '{}' does not apply to master '{}'", file, what, key, master));
  contact::ContactSettings cs;
  cs.friction = get_float(t, S, "friction");
  if (t.contains("friction_table")) {
    if (t.contains("friction"))
      throw Error(fmt::format("{}: {}: give one of 'friction' and 'friction_table'", file, what));
    for (const auto& row : get_float_rows(t, "friction_table")) {
      if (row.size() != 2)
        throw Error(fmt::format("{}: {}: every 'friction_table' row needs 2 numbers (t and mu)", file, what));
      cs.friction_schedule.emplace_back(row[0], row[1]);
    }
    if (cs.friction_schedule.empty()) throw Error(fmt::format("{}: {}: 'friction_table' is empty", file, what));
  }
  cs.gap_tolerance = get_float(t, S, "gap_tolerance");
  cs.force_tolerance = get_float(t, S, "force_tolerance");
  cs.tangential_penalty = get_float(t, S, "tangential_penalty");
  cs.tangential_penalty_floor = get_float(t, S, "tangential_penalty_floor");
  cs.mass_weighted_rows = get_bool(t, S, "mass_weighted_rows");
  const std::string normals = get_string(t, S, "normal_linearisation");
  using NL = contact::ContactSettings::NormalLinearisation;
  cs.normal_linearisation = normals == "exact" ? NL::Exact : normals == "dropped" ? NL::Dropped : NL::Settled;
  const bool closest = get_string(t, S, "master_point") == "closest";
  if (!closest && t.contains("master_point") && s.mesh.dim == 2)
    throw Error(fmt::format("{}: {}: master_point 'normal-crossing' is 3D only (2D uses the closest point)", file,
                            what));
  cs.master_point = closest || s.mesh.dim == 2 ? contact::ContactSettings::MasterPoint::Closest
                                               : contact::ContactSettings::MasterPoint::NormalCrossing;
  if (cs.friction < 0 || cs.gap_tolerance < 0 || cs.force_tolerance < 0 || !(cs.tangential_penalty > 0) ||
      !(cs.tangential_penalty_floor >= 0 && cs.tangential_penalty_floor <= 1))
    throw Error(fmt::format("{}: {}: friction and tolerances must be >= 0, tangential_penalty > 0, "
                            "tangential_penalty_floor in [0, 1]",
                            file, what));
  // The slave body gives the stiffness scale.
  const auto it = std::find(s.body_names.begin(), s.body_names.end(), slave_body);
  cs.modulus = body_material[static_cast<size_t>(it - s.body_names.begin())]->reference_modulus();
  // make_plane names the file and pair in its own messages.
  std::optional<contact::RigidPlane> plane;
  if (master == "plane") plane = make_plane(t, s.mesh.dim, file, what, step_times);
  try {
    if (plane) return std::make_unique<contact::RigidPlaneContact>(name, *s.space, slave.tag, *plane, cs);
    if (!t.contains("master_boundary"))
      throw Error(fmt::format("master 'surface' needs key 'master_boundary'"));
    std::string master_body = t["master_body"].value<std::string>().value_or(slave_body);
    const Boundary m = find_boundary(s, master_body, get_string(t, S, "master_boundary"), file, what);
    return std::make_unique<contact::SurfaceContact>(name, *s.space, slave.tag, m.tag, cs,
                                                     get_float(t, S, "search_radius"));
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}: {}", file, what, e.what()), e.kind());
  }
}

}  // namespace

const TableSpec& scene_schema() { return schemas().root; }

std::unique_ptr<Scene> build_scene(const std::string& text, const std::string& origin, const std::string& base_dir,
                                   int level) {
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}: malformed TOML at line {}, column {}: {}", origin, e.source().begin.line,
                            e.source().begin.column, e.description()));
  }
  const Schemas& S = schemas();
  validate(root, S.root, origin);

  auto scene = std::make_unique<Scene>();
  Scene& s = *scene;
  const toml::table& meta = sub(root, "scene");
  s.origin = origin;
  s.name = get_string(meta, S.scene_meta, "name");
  if (s.name.empty()) s.name = std::filesystem::path(origin).stem().string();
  s.description = get_string(meta, S.scene_meta, "description");
  s.file_level = static_cast<int>(get_int(meta, S.scene_meta, "level"));
  s.level = level >= 0 ? level : s.file_level;
  if (s.level < 0 || s.level > 4) throw Error(fmt::format("{}: mesh level {} outside 0..4", origin, s.level));

  std::map<std::string, size_t> material_index;
  for (const auto* m : tables(root, "material")) {
    const std::string name = get_string(*m, S.material, "name");
    if (material_index.count(name)) throw Error(fmt::format("{}: material '{}' declared twice", origin, name));
    material_index[name] = s.materials.size();
    s.materials.push_back(make_material(*m, origin));
  }
  std::vector<const materials::Material*> body_material;
  for (const auto* b : tables(root, "body")) {
    const std::string name = get_string(*b, S.body, "name");
    const std::string mat = get_string(*b, S.body, "material");
    if (std::find(s.body_names.begin(), s.body_names.end(), name) != s.body_names.end())
      throw Error(fmt::format("{}: body '{}' declared twice", origin, name));
    auto mi = material_index.find(mat);
    if (mi == material_index.end()) throw Error(fmt::format("{}: body '{}' uses unknown material '{}'", origin, name, mat));
    bool refined = false;
    mesh::Mesh m = make_body_mesh(sub(*b, "mesh"), origin, base_dir, name, s.level, &refined);
    if (!refined) m = mesh::refine(m, s.level);
    s.levels_by_refinement = s.levels_by_refinement && !refined;
    mesh::check_validity(m, fmt::format("{}: body '{}' mesh", origin, name));
    mesh::append(s.mesh, m, name);
    s.body_of_cell.insert(s.body_of_cell.end(), m.n_cells(), static_cast<int>(s.body_names.size()));
    s.body_names.push_back(name);
    body_material.push_back(s.materials[mi->second].get());
    s.material_of_body.push_back(s.materials[mi->second]->describe());
  }

  const auto basis = fem::basis_kind_from_string(get_string(meta, S.scene_meta, "basis"));
  // A pressure field only on the vertices of bodies whose law is mixed (none otherwise).
  std::vector<char> has_pressure;
  for (int c = 0; c < s.mesh.n_cells(); ++c)
    if (body_material[s.body_of_cell[c]]->mixed_bulk_modulus() > 0) {
      has_pressure.resize(s.mesh.n_vertices(), 0);
      for (int k = 0; k <= s.mesh.dim; ++k) has_pressure[s.mesh.cell(c)[k]] = 1;
    }
  if (!has_pressure.empty() && basis != fem::BasisKind::P2Hierarchical && basis != fem::BasisKind::P2Nodal)
    throw Error(fmt::format("{}: a mixed (u-p) law needs a P2 displacement (Taylor-Hood); basis '{}' is not stable",
                            origin, fem::to_string(basis)));
  s.space = std::make_unique<fem::FieldSpace>(s.mesh, basis, has_pressure);
  auto& P = s.problem;
  P.space = s.space.get();
  for (int b : s.body_of_cell) P.cell_material.push_back(body_material[b]);
  P.step_times = step_times_of(sub(root, "load"), origin);
  const int dim = s.mesh.dim;

  int k = 0;
  for (const auto* d : tables(root, "dirichlet")) {
    const std::string what = fmt::format("dirichlet[{}]", k++);
    nonlinear::DirichletCondition bc;
    const Boundary where = boundary_of(s, *d, origin, what);
    bc.facet_tag = where.tag;
    bc.name = where.name;
    const auto comps = get_strings(*d, "components");
    const auto value = get_floats(*d, "value");
    if (d->contains("value") && comps.size() != value.size())
      throw Error(fmt::format("{}: {}: {} components but {} values", origin, what, comps.size(), value.size()));
    for (const auto& c : comps) {
      const int axis = c[0] - 'x';
      if (axis >= dim) throw Error(fmt::format("{}: {}: component '{}' in a {}D scene", origin, what, c, dim));
      bc.components.push_back(axis);
    }
    // Two conditions on one boundary (x in one, y in another) report their reactions apart:
    // the second and later take their components into their name ("indenter/top:y").
    const auto taken = [&](const std::string& name) {
      return std::any_of(P.dirichlet.begin(), P.dirichlet.end(), [&](const auto& o) { return o.name == name; });
    };
    if (taken(bc.name)) {
      std::string base = bc.name + ":";
      for (const auto& c : comps) base += c;
      bc.name = base;
      for (int n = 2; taken(bc.name); ++n) bc.name = fmt::format("{}#{}", base, n);
    }
    // The function gives the listed components; the field spreads them over all dim.
    auto listed = load_function(*d, P.step_times, "value", "table", value, comps.size(), origin, what);
    bc.value = [listed = std::move(listed), axes = bc.components, dim](const double*, double time, double* out) {
      double v[3];
      listed(time, v);
      std::fill(out, out + dim, 0.0);
      for (size_t c = 0; c < axes.size(); ++c) out[axes[c]] = v[c];
    };
    P.dirichlet.push_back(std::move(bc));
  }
  k = 0;
  for (const auto* t : tables(root, "traction")) {
    const std::string what = fmt::format("traction[{}]", k++);
    nonlinear::TractionLoad load;
    const Boundary where = boundary_of(s, *t, origin, what);
    load.facet_tag = where.tag;
    load.name = where.name;
    const auto value = get_floats(*t, "value");
    if (t->contains("value") && static_cast<int>(value.size()) != dim)
      throw Error(fmt::format("{}: {}: value needs {} entries", origin, what, dim));
    load.value = constant_in_space(load_function(*t, P.step_times, "value", "table", value, dim, origin, what));
    P.tractions.push_back(std::move(load));
  }
  if (root.contains("body_force")) {
    const toml::table& bf = sub(root, "body_force");
    const auto value = get_floats(bf, "value");
    if (bf.contains("value") && static_cast<int>(value.size()) != dim)
      throw Error(fmt::format("{}: body_force.value needs {} entries", origin, dim));
    P.body_force = constant_in_space(load_function(bf, P.step_times, "value", "table", value, dim, origin, "body_force"));
  }

  k = 0;
  for (const auto* c : tables(root, "contact")) {
    const std::string what = fmt::format("contact[{}]", k++);
    auto pair = make_contact(s, *c, origin, what, body_material, P.step_times);
    P.constraints.push_back(pair.get());
    s.contacts.push_back(std::move(pair));
  }

  const toml::table& nw = sub(root, "newton");
  s.newton.atol = get_float(nw, S.newton, "atol");
  s.newton.rtol = get_float(nw, S.newton, "rtol");
  s.newton.max_iterations = static_cast<int>(get_int(nw, S.newton, "max_iterations"));
  s.newton.max_backtracks = static_cast<int>(get_int(nw, S.newton, "max_backtracks"));
  s.newton.min_det_f_ratio = get_float(nw, S.newton, "min_det_f_ratio");
  s.newton.forcing = nonlinear::forcing_from_string(get_string(nw, S.newton, "forcing"));
  s.newton.krylov_rtol = get_float(nw, S.newton, "krylov_rtol");
  s.newton.krylov_restart = static_cast<int>(get_int(nw, S.newton, "krylov_restart"));
  auto& as = s.newton.active_set;
  as.update_tolerance = get_float(nw, S.newton, "state_update_tolerance");
  as.max_held = static_cast<int>(get_int(nw, S.newton, "max_held_iterations"));
  as.cycle_remedies = static_cast<int>(get_int(nw, S.newton, "cycle_remedies"));
  as.remedy_factor = get_float(nw, S.newton, "cycle_remedy_factor");
  s.newton.max_cuts = static_cast<int>(get_int(sub(root, "load"), S.load, "max_cuts"));
  s.newton.max_regrow_wait = static_cast<int>(get_int(sub(root, "load"), S.load, "max_regrow_wait"));
  if (const auto quick = sub(root, "load")["quick_until"].value<double>()) s.quick_until = *quick;
  if (!(s.newton.atol >= 0 && s.newton.rtol >= 0 && s.newton.max_iterations >= 1 && s.newton.krylov_rtol >= 0 &&
        s.newton.krylov_rtol < 1 && s.newton.min_det_f_ratio >= 0 && s.newton.min_det_f_ratio < 1 &&
        s.newton.krylov_restart >= 0))
    throw Error(fmt::format("{}: newton tolerances and krylov_restart must be >= 0 (krylov_rtol and min_det_f_ratio "
                            "below 1) and max_iterations >= 1",
                            origin));
  if (!(as.update_tolerance >= 0 && as.max_held >= 0 && as.cycle_remedies >= 0 && as.remedy_factor > 0 &&
        as.remedy_factor < 1 && s.newton.max_cuts >= 0 && s.newton.max_regrow_wait >= 2))
    throw Error(fmt::format("{}: newton.state_update_tolerance, max_held_iterations, cycle_remedies and load.max_cuts "
                            "must be >= 0, load.max_regrow_wait >= 2, cycle_remedy_factor in (0, 1)",
                            origin));
  const toml::table& out = sub(root, "output");
  s.output.vtu = get_bool(out, S.output, "vtu");
  s.output.vtu_format = get_string(out, S.output, "vtu_format") == "ascii" ? VtuFormat::Ascii : VtuFormat::Binary;
  s.output.csv = get_bool(out, S.output, "csv");
  return scene;
}

std::unique_ptr<Scene> load_scene_file(const std::string& path, int level, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("cannot open scene file '{}'", path));
  std::stringstream ss;
  ss << in.rdbuf();
  return build_scene(apply_overrides(ss.str(), overrides, path), path, std::filesystem::path(path).parent_path().string(),
                     level);
}

}  // namespace stiction::scene
