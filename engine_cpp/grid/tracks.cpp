#include "grid/tracks.hpp"

#include <algorithm>

#include "io/input_error.hpp"

namespace xroute {

namespace {

void sortUnique(std::vector<Dbu>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

TrackSet buildTracks(const Tech& tech, const Design& design) {
  TrackSet set;
  set.layers.resize(tech.routingLayers.size());
  for (size_t z = 0; z < tech.routingLayers.size(); ++z) {
    const Layer& l = tech.layer(tech.routingLayers[z]);
    LayerTracks& lt = set.layers[z];
    lt.layer = tech.routingLayers[z];
    lt.horizontal = l.direction != Direction::Vertical;
    lt.wireWidth = l.width;
  }
  for (const TrackPattern& t : design.tracks) {
    const Layer& l = tech.layer(t.layer);
    if (l.routingIndex < 0) continue;
    LayerTracks& lt = set.layers[l.routingIndex];
    // "TRACKS Y" lines are horizontal: they carry a horizontal layer's wires.
    const bool isPref = lt.horizontal ? !t.isX : t.isX;
    std::vector<Dbu>& dst = isPref ? lt.pref : lt.cross;
    for (int i = 0; i < t.count; ++i) dst.push_back(t.start + Dbu(i) * t.step);
  }
  for (LayerTracks& lt : set.layers) {
    sortUnique(lt.pref);
    sortUnique(lt.cross);
    if (lt.pref.empty()) {
      // The file and line of the layer's TRACKS (they run the other way), else of none.
      int line = 0;
      for (const TrackPattern& t : design.tracks) line = line == 0 && t.layer == lt.layer ? t.line : line;
      const std::string& name = tech.layer(lt.layer).name;
      throw InputError(design.path.empty() ? std::string("DEF") : design.path, line,
                       "routing layer " + name + " has no tracks in its preferred direction: routing needs a TRACKS " +
                           (lt.horizontal ? "Y" : "X") + " ... LAYER " + name + " statement");
    }
    lt.pitch = 0;
    for (size_t i = 1; i < lt.pref.size(); ++i) {
      const Dbu d = lt.pref[i] - lt.pref[i - 1];
      if (lt.pitch == 0 || d < lt.pitch) lt.pitch = d;
    }
  }
  return set;
}

std::vector<Dbu> tracksIn(const std::vector<Dbu>& tracks, Dbu lo, Dbu hi) {
  auto b = std::lower_bound(tracks.begin(), tracks.end(), lo);
  auto e = std::upper_bound(tracks.begin(), tracks.end(), hi);
  return std::vector<Dbu>(b, e);
}

bool onTrack(const std::vector<Dbu>& tracks, Dbu v) { return std::binary_search(tracks.begin(), tracks.end(), v); }

}  // namespace xroute
