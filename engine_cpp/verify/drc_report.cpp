#include "verify/drc_report.hpp"

#include "io/atomic_file.hpp"

namespace xroute {

namespace {

void appendNet(std::string& out, int32_t net, const std::vector<std::string>& names) {
  out.push_back(' ');
  if (net < 0) out.push_back('-');
  else if (size_t(net) < names.size() && !names[net].empty()) out += names[net];
  else out += std::to_string(net);
}

}  // namespace

std::array<int64_t, kMarkerTypes> countMarkers(const std::vector<Marker>& markers) {
  std::array<int64_t, kMarkerTypes> counts{};
  for (const Marker& m : markers) ++counts[int(m.type)];
  return counts;
}

std::string drcReportText(const Tech& tech, const std::vector<Marker>& markers,
                          const std::vector<std::string>& netNames) {
  std::string out = "# markers " + std::to_string(markers.size());
  const auto counts = countMarkers(markers);
  for (int t = 0; t < kMarkerTypes; ++t) {
    out += ' ';
    out += markerTypeName(MarkerType(t));
    out += ' ' + std::to_string(counts[t]);
  }
  out.push_back('\n');
  for (const Marker& m : markers) {
    out += markerTypeName(m.type);
    out += ' ';
    out += m.layer.valid() && size_t(*m.layer) < tech.layers.size() ? tech.layer(m.layer).name : std::string("-");
    for (Dbu v : {m.box.xlo, m.box.ylo, m.box.xhi, m.box.yhi}) out += ' ' + std::to_string(v);
    appendNet(out, m.net1, netNames);
    appendNet(out, m.net2, netNames);
    out.push_back('\n');
  }
  return out;
}

void writeDrcReport(const std::string& path, const Tech& tech, const std::vector<Marker>& markers,
                    const std::vector<std::string>& netNames) {
  writeFileAtomically(path, drcReportText(tech, markers, netNames), "DRC report");
}

}  // namespace xroute
