// Particles from a CSV file: x, y, z, r [, vx, vy, vz] per line (m, m/s); lines that do not
// start with a number (headers, comments) are skipped.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "dem/insertion/inserter.hpp"

namespace gf::dem {
namespace {
class CsvInsertion final : public Inserter {
 public:
  explicit CsvInsertion(Params& p) : common_(p) {
    file_ = p.text({"file", "-", "csv_file: path (relative to the case file) of x,y,z,r[,vx,vy,vz] lines"}, "");
    if (p.documenting()) return;
    std::filesystem::path path(file_);
    if (path.is_relative()) path = std::filesystem::path(p.fileName()).parent_path() / path;
    std::ifstream in(path);
    if (!in) p.fail("file", "'" + file_ + "'", "a readable CSV file");
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line)) {
      ++lineNumber;
      const auto first = line.find_first_not_of(" \t");
      if (first == std::string::npos || !(std::isdigit(line[first]) || line[first] == '-' || line[first] == '+' ||
                                          line[first] == '.'))
        continue;
      for (char& c : line)
        if (c == ',' || c == ';') c = ' ';
      std::istringstream fields(line);
      std::vector<double> v;
      double x;
      while (fields >> x) v.push_back(x);
      if ((v.size() != 4 && v.size() != 7) || v[3] <= 0.0)
        p.fail("file", fmt::format("{} line {}: '{}'", file_, lineNumber, line), "x, y, z, r > 0 [, vx, vy, vz]");
      rows_.push_back(v);
    }
  }
  std::size_t insert(InsertionContext& ctx, double, double) override {
    if (done_) return 0;
    done_ = true;
    for (const auto& v : rows_) {
      const Vec3 vel = v.size() == 7 ? Vec3{v[4], v[5], v[6]} : common_.velocity;
      ctx.particles.add(ctx.nextId++, common_.material, v[3], common_.density, {v[0], v[1], v[2]}, vel);
    }
    return rows_.size();
  }
  SmallestInserted smallest() const override {
    SmallestInserted s;
    for (const auto& v : rows_)
      if (s.material < 0 || 2.0 * v[3] < s.diameter) s = {common_.material, 2.0 * v[3]};
    return s;
  }
  void save(BinaryWriter& out) const override { out.put<std::uint8_t>(done_); }
  void load(BinaryReader& in) override { done_ = in.get<std::uint8_t>() != 0; }

  double coarseGraining() const override { return common_.coarseGraining; }
  int material() const override { return common_.material; }

 private:
  InsertionCommon common_;
  std::string file_;
  std::vector<std::vector<double>> rows_;
  bool done_ = false;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Inserter, gf::dem::CsvInsertion, "csv_file", "particles listed in a CSV file")
