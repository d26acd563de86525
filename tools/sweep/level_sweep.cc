#include "tools/sweep/level_sweep.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>

namespace msb {
namespace {

// The index of an axis by name (-1: none).
int axisIndex(const SweepResults& results, const std::string& name) {
  const auto it = std::find(results.axes.begin(), results.axes.end(), name);
  return it == results.axes.end() ? -1 : int(it - results.axes.begin());
}

// The labels of an axis in the order their first run appears.
std::vector<std::string> labelsInOrder(const SweepResults& results, const std::string& axis) {
  std::vector<std::string> out;
  for (const ReportRun& r : results.runs) {
    const auto it = r.labels.find(axis);
    if (it != r.labels.end() && std::find(out.begin(), out.end(), it->second) == out.end()) out.push_back(it->second);
  }
  return out;
}

std::string fixed2(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", v);
  return b;
}

std::string ratioCell(const LevelCell& c) {
  return fixed2(c.ratio.value) + " [" + fixed2(c.ratio.ci.lo) + ", " + fixed2(c.ratio.ci.hi) + "]";
}

// A row's ratio to the reference row: paired on common seeds when at least two exist.
std::optional<LevelCell> compare(const ReportRow& row, const ReportRow& ref) {
  if (row.area_m2.count == 0 || ref.area_m2.count == 0 || !(ref.area_m2.mean > 0)) return std::nullopt;
  LevelCell c;
  const PairedAreas p = pairedAreas(row, ref);
  if (p.a.size() >= 2 && stats::mean(p.b) > 0) {
    c.ratio = stats::bootstrapPairedRatio(p.a, p.b);
    c.pairs = int(p.a.size());
  } else {
    c.ratio = stats::bootstrapRatio(row.area_m2.values, ref.area_m2.values);
  }
  return c;
}

}  // namespace

std::optional<LevelSweep> levelSweep(const SweepResults& results, const std::vector<ReportRow>& rows) {
  const int method_axis = axisIndex(results, "method"), world_axis = axisIndex(results, "world");
  int level_axis = -1;
  for (int i = 0; i < int(results.axes.size()); ++i) {
    if (i == method_axis || i == world_axis) continue;
    if (level_axis >= 0) return std::nullopt;  // two candidate level axes: not a level sweep
    level_axis = i;
  }
  if (method_axis < 0 || level_axis < 0) return std::nullopt;
  LevelSweep s;
  s.axis = results.axes[size_t(level_axis)];
  s.levels = labelsInOrder(results, s.axis);
  const std::vector<std::string> methods = labelsInOrder(results, "method");
  if (methods.size() < 2 || s.levels.size() < 2) return std::nullopt;
  s.reference_method = methods.front();
  // Rows by (world label, method label, level label); a sweep without a world axis has one world.
  std::map<std::tuple<std::string, std::string, std::string>, const ReportRow*> by;
  std::vector<std::string> worlds;
  for (const ReportRow& r : rows) {
    const std::string world = world_axis >= 0 ? r.labels[size_t(world_axis)] : r.world;
    by[{world, r.labels[size_t(method_axis)], r.labels[size_t(level_axis)]}] = &r;
    if (std::find(worlds.begin(), worlds.end(), world) == worlds.end()) worlds.push_back(world);
  }
  for (const std::string& world : worlds)
    for (size_t m = 1; m < methods.size(); ++m)
      for (size_t l = 0; l < s.levels.size(); ++l) {
        const auto row = by.find({world, methods[m], s.levels[l]});
        const auto ref = by.find({world, methods[0], s.levels[l]});
        if (row == by.end() || ref == by.end()) continue;
        std::optional<LevelCell> c = compare(*row->second, *ref->second);
        if (!c) continue;
        c->world = world;
        c->level = s.levels[l];
        c->level_index = int(l);
        c->method = methods[m];
        s.cells.push_back(*c);
      }
  if (s.cells.empty()) return std::nullopt;
  return s;
}

std::vector<ReportRow> rowsAtLevel(const SweepResults& results, const std::vector<ReportRow>& rows, const LevelSweep& s,
                                   size_t level) {
  const int axis = axisIndex(results, s.axis);
  std::vector<ReportRow> out;
  for (const ReportRow& r : rows)
    if (axis >= 0 && level < s.levels.size() && r.labels[size_t(axis)] == s.levels[level]) out.push_back(r);
  return out;
}

std::string levelSweepMarkdown(const LevelSweep& s) {
  std::ostringstream o;
  o << "\n## Ablations across levels of `" << s.axis << "`\n\nEach method's mean A over the mean A of "
    << s.reference_method
    << " at the same level, paired on common seeds (95 % percentile bootstrap; independent when fewer than two "
       "seeds are common). Below 1: the ablated part pays; the figure is ablation_levels_<world>.png. The paper's "
       "findings (below) are checked on the first level, `"
    << s.levels.front() << "`, only.\n";
  // Worlds and methods in cell order.
  std::vector<std::pair<std::string, std::string>> keys;
  for (const LevelCell& c : s.cells)
    if (std::find(keys.begin(), keys.end(), std::make_pair(c.world, c.method)) == keys.end())
      keys.emplace_back(c.world, c.method);
  std::string world;
  for (const auto& [w, m] : keys) {
    if (w != world) {
      world = w;
      o << "\n### " << w << "\n\n| method |";
      for (const auto& l : s.levels) o << " " << l << " |";
      o << " the lowest level at which it costs area |\n| --- |";
      for (size_t i = 0; i <= s.levels.size(); ++i) o << " --- |";
      o << "\n";
    }
    o << "| " << m << " |";
    std::string first_below = "none of these levels";
    for (const auto& l : s.levels) {
      const auto it = std::find_if(s.cells.begin(), s.cells.end(),
                                   [&](const LevelCell& c) { return c.world == w && c.method == m && c.level == l; });
      if (it == s.cells.end()) {
        o << " — |";
        continue;
      }
      o << " " << ratioCell(*it) << " |";
      if (first_below == "none of these levels" && it->ratio.ci.hi < 1.0) first_below = "`" + l + "`";
    }
    o << " " << first_below << " |\n";
  }
  return o.str();
}

std::string levelSweepCsv(const LevelSweep& s) {
  std::ostringstream o;
  o << "world,level_index,level,method,ratio,lo,hi,pairs\n";
  for (const LevelCell& c : s.cells) {
    char b[160];
    std::snprintf(b, sizeof b, ",%.6f,%.6f,%.6f,%d\n", c.ratio.value, c.ratio.ci.lo, c.ratio.ci.hi, c.pairs);
    o << c.world << "," << c.level_index << "," << c.level << "," << c.method << b;
  }
  return o.str();
}

}  // namespace msb
