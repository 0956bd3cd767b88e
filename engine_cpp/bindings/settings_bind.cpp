// The engine's settings structs as Python classes: MazeCosts (route/maze.hpp), RouterSettings and
// IterationPlan (loop/router.hpp). Each field is bound once (SettingsClass::field); from that one
// list come the keyword-only constructor (each field defaulting to the C++ default), replace(),
// to_dict() (the plan in reports and metrics JSON), equality, repr, copies and pickling.
#include <nanobind/nanobind.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "loop/router.hpp"
#include "route/maze.hpp"

namespace nb = nanobind;
using namespace nb::literals;
using namespace xroute;

namespace {

// A field's type and default as a stub shows them.
template <class M>
std::string stubType() {
  if constexpr (std::is_same_v<M, bool>) return "bool";
  else if constexpr (std::is_integral_v<M>) return "int";
  else if constexpr (std::is_floating_point_v<M>) return "float";
  else return nb::cast<std::string>(nb::type<M>().attr("__name__"));
}

template <class M>
std::string stubDefault(const M& value) {
  if constexpr (std::is_same_v<M, bool>) return value ? "True" : "False";
  else if constexpr (std::is_integral_v<M>) return std::to_string(value);
  else if constexpr (std::is_floating_point_v<M>) return nb::cast<std::string>(nb::repr(nb::float_(value)));
  else return "...";
}

// A settings struct bound field by field (see the file comment).
template <class T>
class SettingsClass {
 public:
  SettingsClass(nb::module_& m, const char* name, const char* doc)
      : cls_(m, name, doc), name_(name), names_(std::make_shared<std::vector<std::string>>()) {}

  template <class M>
  SettingsClass& field(const char* name, M T::*member, const char* doc) {
    cls_.def_rw(name, member, doc);
    return named<M>(name, defaults_.*member);
  }

  // A field that is not a member of T itself (get and set: lambdas of T).
  template <class Get, class Set>
  SettingsClass& property(const char* name, const char* type, const char* defaultText, Get get, Set set,
                          const char* doc) {
    cls_.def_prop_rw(name, get, set, doc);
    names_->push_back(name);
    stubs_.push_back({std::string(name) + ": " + type, defaultText});
    return *this;
  }

  void finish() {
    auto names = names_;
    const std::string type = name_;
    std::string init, changes;  // the keyword-only parameters, with the defaults and with "..." (unchanged)
    for (const auto& [annotated, defaultText] : stubs_) {
      init += ", " + annotated + " = " + defaultText;
      changes += ", " + annotated + " = ...";
    }
    cls_.def(
            "__init__",
            [names, type](T* self, nb::kwargs fields) { new (self) T(changed(T(), fields, *names, type)); },
            nb::sig(("def __init__(self, *" + init + ") -> None").c_str()),
            "Each field by its keyword; a field left out has the engine's default.")
        .def(
            "replace",
            [names, type](const T& self, nb::kwargs fields) { return changed(self, fields, *names, type); },
            nb::sig(("def replace(self, *" + changes + ") -> " + type).c_str()),
            "A copy with the fields given by keyword changed.")
        .def("to_dict", [names](nb::handle_t<T> self) { return fieldDict(self, *names); },
             "The fields by name, in the engine's order.")
        .def("__eq__", [names](nb::handle_t<T> self, nb::handle other) -> nb::object {
               if (!nb::isinstance<T>(other)) return nb::borrow(Py_NotImplemented);
               return nb::bool_(fieldDict(self, *names).equal(fieldDict(other, *names)));
             }, "other"_a.none(), "Equal when every field is.")
        .def("__repr__", [names, type](nb::handle_t<T> self) {
               std::string text = type + "(";
               for (const std::string& n : *names) {
                 if (&n != &names->front()) text += ", ";
                 text += n + "=" + nb::cast<std::string>(nb::repr(nb::getattr(self, n.c_str())));
               }
               return text + ")";
             }, "The fields by name.")
        .def("__copy__", [](const T& self) { return T(self); }, "A copy.")
        .def("__deepcopy__", [](const T& self, nb::handle) { return T(self); }, "memo"_a, "A copy.")
        .def("__getstate__", [names](nb::handle_t<T> self) { return fieldDict(self, *names); }, "The fields (pickling).")
        .def("__setstate__", [names, type](T& self, nb::dict state) {
               new (&self) T(changed(T(), state, *names, type));
             }, "state"_a, "The fields (pickling).");
    cls_.attr("__hash__") = nb::none();  // mutable: equal by value, so not hashable
  }

 private:
  template <class M, class V>
  SettingsClass& named(const char* name, const V& defaultValue) {
    names_->push_back(name);
    stubs_.push_back({std::string(name) + ": " + stubType<M>(), stubDefault<M>(defaultValue)});
    return *this;
  }

  static nb::dict fieldDict(nb::handle self, const std::vector<std::string>& names) {
    nb::dict d;
    for (const std::string& n : names) d[n.c_str()] = nb::getattr(self, n.c_str());
    return d;
  }

  // `base` with `fields` set through the bound setters (so each value is converted as an attribute
  // assignment converts it); an unknown name is a TypeError.
  static T changed(const T& base, nb::dict fields, const std::vector<std::string>& names, const std::string& type) {
    nb::object copy = nb::cast(T(base));
    for (auto [key, value] : fields) {
      const std::string k = nb::cast<std::string>(nb::str(key));
      if (std::find(names.begin(), names.end(), k) == names.end()) {
        throw nb::type_error((type + " has no field '" + k + "'").c_str());
      }
      try {
        nb::setattr(copy, key, value);
      } catch (nb::python_error& e) {
        if (!e.matches(PyExc_TypeError)) throw;
        throw nb::type_error((type + "." + k + " cannot be " + nb::cast<std::string>(nb::repr(value))).c_str());
      }
    }
    return nb::cast<T>(copy);
  }

  nb::class_<T> cls_;
  std::string name_;
  std::shared_ptr<std::vector<std::string>> names_;
  std::vector<std::pair<std::string, std::string>> stubs_;  // per field: "name: type" and its default as a stub shows it
  const T defaults_{};
};

void bindMazeCosts(nb::module_& m) {
  SettingsClass<MazeCosts>(m, "MazeCosts", "The maze's costs (cost units: DBU of wire), as in route/maze.hpp.")
      .field("via_cost", &MazeCosts::viaCost, "Cost units per via (at least via_pitches pitches).")
      .field("via_pitches", &MazeCosts::viaPitches,
             "A via costs at least this many pitches of the second routing layer (the contest scorer's via "
             "weight); 0: via_cost alone.")
      .field("wrong_way_factor", &MazeCosts::wrongWayFactor, "Wrong-way wire length multiplier.")
      .field("out_of_guide_factor", &MazeCosts::outOfGuideFactor,
             "Wire length / via multiplier outside the net's guides.")
      .field("built_in_guide_factor", &MazeCosts::builtInGuideFactor,
             "out_of_guide_factor where the guides are the built-in global router's.")
      .field("fixed_penalty", &MazeCosts::fixedPenalty, "Entering a node a fixed shape of another net forbids.")
      .field("use_penalty", &MazeCosts::usePenalty,
             "Per routed shape of another net a wire or via there would violate (iteration 0).")
      .field("marker_unit", &MazeCosts::markerUnit, "Multiplier of the grid's marker costs.")
      .field("bottom_layer_factor", &MazeCosts::bottomLayerFactor, "Wire length multiplier on routing layer 0.")
      .field("reserve_penalty", &MazeCosts::reservePenalty, "Entering another net's access point or boundary terminal.")
      .field("landing_penalty", &MazeCosts::landingPenalty,
             "Entering the landing above another net's access point while that net is unrouted.")
      .field("sole_landing_penalty", &MazeCosts::soleLandingPenalty,
             "Entering the landing above the only via access point of another unrouted net's pin; -1 "
             "(the default): 8000 where at least half the design's net pins have one via point, else 0.")
      .field("crossing_pull", &MazeCosts::crossingPull, "Per DBU a free crossing lies off the range of the pins beyond it.")
      .finish();
}

using Steps = std::vector<std::pair<int, int>>;

void bindRouterSettings(nb::module_& m) {
  SettingsClass<RouterSettings>(m, "RouterSettings", "The routing run's settings, as in loop/router.hpp.")
      .field("region_size", &RouterSettings::regionSize, "GCells per region side (0: auto_region_size(db)).")
      .field("iterations", &RouterSettings::iterations, "Iterations at most (1..max_iterations).")
      .field("threads", &RouterSettings::threads, "Worker threads for the regions of one colour.")
      .property(
          "schedule", "list[tuple[int, int]]", "[]",
          [](const RouterSettings& s) {
            Steps steps;
            for (const ScheduleStep& step : s.schedule) steps.emplace_back(step.regionSize, step.offset);
            return steps;
          },
          [](RouterSettings& s, const Steps& steps) {
            s.schedule.clear();
            for (const auto& [size, offset] : steps) s.schedule.push_back(ScheduleStep{size, offset});
          },
          "Per-iteration (region size, offset) in GCells, cycled over the iterations; empty: region_size with "
          "offsets 0, C/3, 2C/3.")
      .field("costs", &RouterSettings::costs, "Maze costs of iteration 0.")
      .field("use_penalty_step", &RouterSettings::usePenaltyStep, "Added to costs.use_penalty at each later iteration.")
      .field("access_points_per_pin", &RouterSettings::accessPointsPerPin, "Access points kept per pin.")
      .field("marker_penalty", &RouterSettings::markerPenalty, "Cost units per node near a marker of the last iteration.")
      .field("history_penalty", &RouterSettings::historyPenalty, "Cost units per node near any earlier marker.")
      .field("stop_at_zero", &RouterSettings::stopAtZero, "Stop when an iteration ends without markers.")
      .field("repair_rounds", &RouterSettings::repairRounds,
             "Check-and-reroute rounds inside each region in iterations after the first (0..max_repair_rounds).")
      .field("first_repair_rounds", &RouterSettings::firstRepairRounds, "The same in iteration 0.")
      .field("repair_penalty", &RouterSettings::repairPenalty,
             "Cost units per node near a region marker, times the repair round.")
      .field("rip_neighbours_of_persistent", &RouterSettings::ripNeighboursOfPersistent,
             "A marker that survived its nets' reroute also rips up the other nets with metal near it "
             "(farther the longer it lasts; an EndOfLine one of age 2+ also costs nodes farther out).")
      .field("late_search_markers", &RouterSettings::lateSearchMarkers,
             "Once a check leaves this many markers or fewer (and some), the next iterations run the victims "
             "search (when the run's policy is the heuristic).")
      .field("late_search_budget", &RouterSettings::lateSearchBudget,
             "Trial routings per region of that late search (0: never; at most max_search_budget).")
      .field("trim_dangling", &RouterSettings::trimDangling,
             "After each iteration's routing, cut the routing of every net it rerouted back to what joins its pins.")
      .field("partial_check_share", &RouterSettings::partialCheckShare,
             "After the first iteration, an iteration that changed at most this share of the nets is checked again "
             "only where it changed (the same markers as a whole check); 0: every check is whole.")
      .field("check_band_shapes", &RouterSettings::checkBandShapes,
             "A whole-design check of more shapes than this runs in horizontal bands of about this many (the "
             "same markers, less memory); 0: at once.")
      .finish();
}

void bindIterationPlan(nb::module_& m) {
  const IterationPlan d;
  SettingsClass<IterationPlan>(m, "IterationPlan",
                               "What one iteration runs with, as in loop/router.hpp: the rule's plan, or a schedule "
                               "policy's. The maze's costs other than use_penalty are the run's.")
      .field("region_size", &IterationPlan::regionSize, "GCells per region side (1..max_region_size).")
      .field("offset", &IterationPlan::offset, "GCells, 0 <= offset < region_size.")
      .field("repair_rounds", &IterationPlan::repairRounds,
             "Check-and-reroute rounds inside each region (0..max_repair_rounds).")
      .field("marker_penalty", &IterationPlan::markerPenalty, "Cost units per node near a marker of the last iteration.")
      .field("history_penalty", &IterationPlan::historyPenalty,
             "What each marker this iteration leaves adds near it from then on.")
      .property(
          "use_penalty", "int", std::to_string(d.costs.usePenalty).c_str(),
          [](const IterationPlan& p) { return p.costs.usePenalty; },
          [](IterationPlan& p, int64_t v) { p.costs.usePenalty = v; },
          "Cost units per shape of another net that a step would violate (the maze's costs.use_penalty).")
      .field("stop", &IterationPlan::stop, "End the run instead of running this iteration (not the first).")
      .field("search_budget", &IterationPlan::searchBudget,
             "0: the run's net-order policy orders each region's nets; B >= 1: the victims search with B trial "
             "routings per region, in this iteration only.")
      .finish();
}

}  // namespace

void bindSettings(nb::module_& m) {
  bindMazeCosts(m);
  bindRouterSettings(m);
  bindIterationPlan(m);
}
