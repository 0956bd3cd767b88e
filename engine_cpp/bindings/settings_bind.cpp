// The router's settings structs as Python classes: MazeCosts (route/maze.hpp)
// and RouterSettings (loop/router.hpp), field by field, with the C++ defaults.
#include <nanobind/nanobind.h>

#include "loop/router.hpp"
#include "route/maze.hpp"

namespace nb = nanobind;
using namespace nb::literals;
using namespace xroute;

namespace {

void bindMazeCosts(nb::module_& m) {
  const MazeCosts d;
  nb::class_<MazeCosts>(m, "MazeCosts", "The maze's costs (cost units: DBU of wire), as in route/maze.hpp.")
      .def(nb::init<int64_t, int64_t, int64_t, int64_t, int64_t, int64_t, int64_t, int64_t, int64_t, int64_t,
                    int64_t, int64_t>(),
           "via_cost"_a = d.viaCost, "via_pitches"_a = d.viaPitches, "wrong_way_factor"_a = d.wrongWayFactor,
           "out_of_guide_factor"_a = d.outOfGuideFactor, "built_in_guide_factor"_a = d.builtInGuideFactor,
           "fixed_penalty"_a = d.fixedPenalty,
           "use_penalty"_a = d.usePenalty, "marker_unit"_a = d.markerUnit,
           "bottom_layer_factor"_a = d.bottomLayerFactor, "reserve_penalty"_a = d.reservePenalty,
           "landing_penalty"_a = d.landingPenalty, "crossing_pull"_a = d.crossingPull,
           "The costs; each defaults to the engine's.")
      .def_rw("via_cost", &MazeCosts::viaCost, "Cost units per via (at least via_pitches pitches).")
      .def_rw("via_pitches", &MazeCosts::viaPitches,
              "A via costs at least this many pitches of the second routing layer (the contest scorer's via "
              "weight); 0: via_cost alone.")
      .def_rw("wrong_way_factor", &MazeCosts::wrongWayFactor, "Wrong-way wire length multiplier.")
      .def_rw("out_of_guide_factor", &MazeCosts::outOfGuideFactor,
              "Wire length / via multiplier outside the net's guides.")
      .def_rw("built_in_guide_factor", &MazeCosts::builtInGuideFactor,
              "out_of_guide_factor where the guides are the built-in global router's.")
      .def_rw("fixed_penalty", &MazeCosts::fixedPenalty, "Entering a node a fixed shape of another net forbids.")
      .def_rw("use_penalty", &MazeCosts::usePenalty,
              "Per routed shape of another net a wire or via there would violate (iteration 0).")
      .def_rw("marker_unit", &MazeCosts::markerUnit, "Multiplier of the grid's marker costs.")
      .def_rw("bottom_layer_factor", &MazeCosts::bottomLayerFactor, "Wire length multiplier on routing layer 0.")
      .def_rw("reserve_penalty", &MazeCosts::reservePenalty,
              "Entering another net's access point or boundary terminal.")
      .def_rw("landing_penalty", &MazeCosts::landingPenalty,
              "Entering the landing above another net's access point while that net is unrouted.")
      .def_rw("crossing_pull", &MazeCosts::crossingPull,
              "Per DBU a free crossing lies off the range of the pins beyond it.");
}

void initRouterSettings(RouterSettings* self, int regionSize, int iterations, int threads, const MazeCosts& costs,
                        int64_t usePenaltyStep, int accessPointsPerPin, int64_t markerPenalty,
                        int64_t historyPenalty, bool stopAtZero, int repairRounds, int firstRepairRounds,
                        int64_t repairPenalty) {
  auto* s = new (self) RouterSettings();
  s->regionSize = regionSize;
  s->iterations = iterations;
  s->threads = threads;
  s->costs = costs;
  s->usePenaltyStep = usePenaltyStep;
  s->accessPointsPerPin = accessPointsPerPin;
  s->markerPenalty = markerPenalty;
  s->historyPenalty = historyPenalty;
  s->stopAtZero = stopAtZero;
  s->repairRounds = repairRounds;
  s->firstRepairRounds = firstRepairRounds;
  s->repairPenalty = repairPenalty;
}

void bindRouterSettings(nb::module_& m) {
  const RouterSettings d;
  nb::class_<RouterSettings>(m, "RouterSettings",
                             "The routing run's settings, as in loop/router.hpp (the schedule is route()'s argument).")
      .def("__init__", &initRouterSettings, "region_size"_a = d.regionSize, "iterations"_a = d.iterations,
           "threads"_a = d.threads, "costs"_a = d.costs, "use_penalty_step"_a = d.usePenaltyStep,
           "access_points_per_pin"_a = d.accessPointsPerPin, "marker_penalty"_a = d.markerPenalty,
           "history_penalty"_a = d.historyPenalty, "stop_at_zero"_a = d.stopAtZero,
           "repair_rounds"_a = d.repairRounds, "first_repair_rounds"_a = d.firstRepairRounds,
           "repair_penalty"_a = d.repairPenalty, "The settings; each defaults to the engine's.")
      .def_rw("region_size", &RouterSettings::regionSize, "GCells per region side (0: auto_region_size(db)).")
      .def_rw("iterations", &RouterSettings::iterations, "Iterations at most (1..max_iterations).")
      .def_rw("threads", &RouterSettings::threads, "Worker threads for the regions of one colour.")
      .def_rw("costs", &RouterSettings::costs, "Maze costs of iteration 0.")
      .def_rw("use_penalty_step", &RouterSettings::usePenaltyStep,
              "Added to costs.use_penalty at each later iteration.")
      .def_rw("access_points_per_pin", &RouterSettings::accessPointsPerPin, "Access points kept per pin.")
      .def_rw("marker_penalty", &RouterSettings::markerPenalty,
              "Cost units per node near a marker of the last iteration.")
      .def_rw("history_penalty", &RouterSettings::historyPenalty, "Cost units per node near any earlier marker.")
      .def_rw("stop_at_zero", &RouterSettings::stopAtZero, "Stop when an iteration ends without markers.")
      .def_rw("repair_rounds", &RouterSettings::repairRounds,
              "Check-and-reroute rounds inside each region in iterations after the first (route() clamps "
              "to 0..max_repair_rounds).")
      .def_rw("first_repair_rounds", &RouterSettings::firstRepairRounds,
              "The same in iteration 0 (clamped likewise).")
      .def_rw("repair_penalty", &RouterSettings::repairPenalty,
              "Cost units per node near a region marker, times the repair round.")
      .def_rw("rip_neighbours_of_persistent", &RouterSettings::ripNeighboursOfPersistent,
              "A marker that survived its nets' reroute also rips up the other nets with metal near it "
              "(farther the longer it lasts; an EndOfLine one of age 2+ also costs nodes farther out).")
      .def_rw("late_search_markers", &RouterSettings::lateSearchMarkers,
              "Once a check leaves this many markers or fewer (and some), the next iterations run the victims "
              "search (when the run's policy is the heuristic).")
      .def_rw("late_search_budget", &RouterSettings::lateSearchBudget,
              "Trial routings per region of that late search (0: never; at most max_search_budget).")
      .def_rw("trim_dangling", &RouterSettings::trimDangling,
              "After each iteration's routing, cut the routing of every net it rerouted back to what joins its pins.");
}

}  // namespace

void bindSettings(nb::module_& m) {
  bindMazeCosts(m);
  bindRouterSettings(m);
}
