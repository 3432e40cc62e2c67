// Every flight integrator once, with the facts the rest of the package derives from it: names
// for parameters and help texts, the "known: ..." of errors, the step limit, and the order and
// error constants bag_report bounds a recording with (docs/physics.md, "Error bounds").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "virtual_go/common/name_table.h"
#include "virtual_go/flight/integrator.h"

namespace virtual_go {

// Constants of the error bounds bag_report --strict holds a recording to (h = dt, w = the
// largest |omega| of a segment, T = its duration, p = order):
//   orientation error <= floor + k_orientation (h w)^p w T                 (rad)
//   energy drift      <= floor + k_energy (h w)^p (1 + w T)                (relative)
//   position error    <= floor + round-off + k_gravity |g| h T / 2         (m)
// k_orientation and k_energy are 4-10x the worst value measured for the default stone (both
// models, |w| 2..45 rad/s, h 1..5 ms, random axes, 5 s); k_gravity is the article's Euler's
// exact offset g h t / 2 with 1 % to spare.
struct ErrorBoundConstants {
  double k_orientation = 0.0;
  double k_energy = 0.0;
  double k_gravity = 0.0;
};

struct IntegratorInfo {
  std::string name;              // as in ~integrator, ~info and make_integrator()
  std::string summary;           // one line for help texts
  int order;                     // p: the global error is O(h^p); 0 for exact (no truncation error)
  double max_rotation_per_step;  // rad: largest h |omega| a step may take; infinity: any
  ErrorBoundConstants error_bound;
  std::unique_ptr<Integrator> (*make)(const IntegratorInfo& info, const MotionSetup& setup);
};

// euler, rk4, splitting, exact, in that order. An unknown name is an InvalidArgument with
// field "integrator".
const NameTable<IntegratorInfo>& integrators();
// nullptr for an unknown name.
const IntegratorInfo* find_integrator(const std::string& name);
std::vector<std::string> integrator_names();

// Throws InvalidArgument for an unknown name, or when the integrator cannot handle the setup
// (exact: a rigid_body whose inertia is not axisymmetric; any: a non-finite gravity).
std::unique_ptr<Integrator> make_integrator(const std::string& name, const MotionSetup& setup);

}  // namespace virtual_go
