// The work a World did, for tests and benchmarks: what a scene costs, and proof that a resting
// stone costs nothing (no flight step, no search, no contact step while it rests).
#pragma once

namespace virtual_go {

struct WorldCounters {
  long advance_calls = 0;         // World::advance_to calls
  long flight_steps = 0;          // exact-integrator steps (flight samples)
  long contact_searches = 0;      // time-of-impact searches
  long contact_search_steps = 0;  // their advancement and polishing steps
  long impacts = 0;               // impacts resolved (Stronge)
  long impact_slip_steps = 0;     // their slip-integration steps
  long impact_fallbacks = 0;      // impacts finished without friction (ImpactOptions::max_steps)
  long plane_contact_steps = 0;   // accepted integrator steps of plane contacts
  long plane_contact_rhs = 0;     // their right-hand-side evaluations
  long nonsmooth_steps = 0;       // committed sub-steps of the fallback
  long nonsmooth_impulses = 0;    // plastic impulses of the fallback
  // Of nonsmooth_impulses, those whose slip direction the local Coulomb law did not find (taken
  // frictionless; contact/coulomb_plastic_impulse.h).
  long nonsmooth_frictionless_impulses = 0;
  // Of nonsmooth_steps, those whose energy guard scaled the island's motion (its impulses made
  // more kinetic energy than its poses released) and those whose touching members kept their
  // previous poses, still (a lift not payable): where the islands take energy the contact laws
  // would not (nonsmooth_island.h, step 4 and "A still member stays still").
  long nonsmooth_energy_scalings = 0;
  long nonsmooth_holds = 0;
  // With NonsmoothContactOptions::joint_solve: its solves, their Gauss-Seidel iterations and the
  // solves that stopped at the iteration cap (NonsmoothCounters).
  long nonsmooth_joint_solves = 0;
  long nonsmooth_joint_iterations = 0;
  long nonsmooth_joint_capped_solves = 0;
  // Rests of islands that NonsmoothContactOptions::hold_check refused (their members not held):
  // the joint solve took over.
  long nonsmooth_hold_failures = 0;
  long events = 0;             // events reported
  long pair_searches = 0;      // stone-stone times of impact (pair_time_of_impact)
  long pair_search_steps = 0;  // their advancement and polishing steps
  long pair_gap_checks = 0;    // conservative stone-stone distances (a stone in contact)
  long broad_phase_tests = 0;  // pairs of bounds the broad phase compared (world/broad_phase.h)
  long pair_candidates = 0;    // pairs whose bounds met (each then gets a pair test)
  long pair_impacts = 0;       // stone-stone impacts resolved (of `impacts`)
  long islands_formed = 0;     // stone-stone islands formed (NonsmoothIsland)
  long obstacle_wakes = 0;     // resting stones an island woke by acting on them (obstacles)
  long largest_island = 0;     // the most stones one island was formed with
  long stages = 0;             // pipeline passes of advance_to (world.h)
  // Stones advance_to looked at: the awake ones (flight or contact), one visit each per call. A
  // resting stone is never visited, so a resting board adds nothing here (issue 15: O(1) in
  // resting stones).
  long stones_visited = 0;

  // The work a WorkBudget bounds (world.h): every step of a contact model, search or impact.
  // Flight samples are not counted: one per flying stone per call, in closed form.
  long work() const {
    return contact_searches + contact_search_steps + impacts + impact_slip_steps +
           plane_contact_steps + nonsmooth_steps + pair_searches + pair_search_steps +
           pair_gap_checks;
  }
};

}  // namespace virtual_go
