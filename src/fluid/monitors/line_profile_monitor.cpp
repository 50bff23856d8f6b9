// Monitor "fluid_line_profile": the fluid fields along a grid line, one row per cell, at every
// sample time (as a CFD code's line sample: OpenFOAM's `sets` function object). The line runs
// along `line_axis` through `line_point`; each row holds the cell centre's coordinate on the axis,
// the cell-centred velocity, the pressure and the void fraction there, linear between the cell
// centres in the two other directions (as fluid_probe). The CSV is long-format: rows of one sample
// share its time, so `grainflow validate` (operation: profile) takes the rows of the last time.
// Sample it sparsely (its default interval is output.interval): each sample writes a row per cell.
#include <limits>

#include "core/monitor.hpp"
#include "fluid/sampling.hpp"

namespace gf::fluid {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class LineProfileMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit LineProfileMonitor(Params& p) {
    const std::string a = p.choice({"line_axis", "-", "fluid_line_profile: direction of the line (one row per cell along it)"},
                                   {"x", "y", "z"});
    axis_ = a[0] - 'x';
    point_ = p.vec3({"line_point", "m", "fluid_line_profile: a point on the line (fixes the two other coordinates)"});
  }
  std::vector<MonitorColumn> columns() const override {
    return {{std::string(1, static_cast<char>('x' + axis_)), "m"},
            {"velocity_x", "m/s"},
            {"velocity_y", "m/s"},
            {"velocity_z", "m/s"},
            {"pressure", "Pa"},
            {"void_fraction", "-"}};
  }
  std::vector<std::vector<double>> sampleRows(const RunState& s) override {
    if (!s.fluid) return {};
    const LineProfile line = lineProfile(*s.fluid, axis_, point_);
    std::vector<std::vector<double>> rows;
    rows.reserve(line.position.size());
    for (std::size_t c = 0; c < line.position.size(); ++c)
      rows.push_back({line.position[c], line.velocity[c][0], line.velocity[c][1], line.velocity[c][2], line.pressure[c],
                      line.voidFraction[c]});
    return rows;
  }
  /// One row, for callers that want a single one: the first cell's (the run writes every row).
  std::vector<double> sample(const RunState& s) override {
    const auto rows = sampleRows(s);
    return rows.empty() ? std::vector<double>(columns().size(), kNaN) : rows.front();
  }

 private:
  int axis_ = 0;
  Vec3 point_;
};

}  // namespace
}  // namespace gf::fluid

GF_REGISTER_MODEL(gf::Monitor, gf::fluid::LineProfileMonitor, "fluid_line_profile",
                  "fluid velocity, pressure and void fraction in every cell along a grid line (one row per cell)")
