#include "parallel/rebalance.hpp"

#include <fmt/format.h>
#include <zoltan.h>

#include <algorithm>
#include <cfloat>
#include <numeric>
#include <stdexcept>
#include <string>

#include "parallel/environment.hpp"
#include "parallel/exchange.hpp"

namespace gf::parallel {

double imbalance(const std::vector<double>& loads) {
  if (loads.empty()) return 1.0;
  const double total = std::accumulate(loads.begin(), loads.end(), 0.0);
  if (total <= 0.0) return 1.0;
  return *std::max_element(loads.begin(), loads.end()) / (total / static_cast<double>(loads.size()));
}

namespace {

/// The points of this rank in id order, as Zoltan's query functions read them.
struct Points {
  std::vector<std::int64_t> id;
  std::vector<Vec3> x;
  std::vector<float> weight;
};

int countObjects(void* data, int* ierr) {
  *ierr = ZOLTAN_OK;
  return static_cast<int>(static_cast<const Points*>(data)->id.size());
}

// Global ids: the 64-bit particle id as two 32-bit entries (ZOLTAN_ID_TYPE is unsigned int here);
// local ids: the index.
void listObjects(void* data, int gidEntries, int lidEntries, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids, int weightDim,
                 float* weights, int* ierr) {
  const Points& p = *static_cast<const Points*>(data);
  for (std::size_t i = 0; i < p.id.size(); ++i) {
    const auto id = static_cast<std::uint64_t>(p.id[i]);
    gids[gidEntries * i] = static_cast<ZOLTAN_ID_TYPE>(id & 0xffffffffu);
    gids[gidEntries * i + 1] = static_cast<ZOLTAN_ID_TYPE>(id >> 32);
    lids[lidEntries * i] = static_cast<ZOLTAN_ID_TYPE>(i);
    if (weightDim > 0) weights[i] = p.weight[i];
  }
  *ierr = ZOLTAN_OK;
}

int geometryDimension(void*, int* ierr) {
  *ierr = ZOLTAN_OK;
  return 3;
}

void geometry(void* data, int, int lidEntries, int count, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR lids, int dim, double* out,
              int* ierr) {
  const Points& p = *static_cast<const Points*>(data);
  for (int k = 0; k < count; ++k) {
    const Vec3& x = p.x[lids[lidEntries * k]];
    for (int a = 0; a < 3; ++a) out[dim * k + a] = x[a];
  }
  *ierr = ZOLTAN_OK;
}

void initialiseZoltan() {
  static bool done = false;
  if (done) return;
  Environment::instance();  // MPI first
  float version = 0.0f;
  if (Zoltan_Initialize(0, nullptr, &version) != ZOLTAN_OK) throw std::runtime_error("Zoltan_Initialize failed");
  done = true;
}

}  // namespace

std::vector<Box> bisect(const Domain& domain, const std::vector<std::int64_t>& ids, const std::vector<Vec3>& points,
                        const std::vector<double>& weights, int parts) {
  if (ids.size() != points.size() || weights.size() != points.size())
    throw std::invalid_argument("parallel::bisect: ids, points and weights differ in length");
  if (parts < 1) throw std::invalid_argument("parallel::bisect: at least one part");
  initialiseZoltan();
  const Environment& env = Environment::instance();
  Points p;
  std::vector<std::size_t> order(ids.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  for (std::size_t i : order) {
    p.id.push_back(ids[i]);
    p.x.push_back(points[i]);
    p.weight.push_back(static_cast<float>(weights[i]));
  }

  Zoltan_Struct* zz = Zoltan_Create(env.communicator());
  if (!zz) throw std::runtime_error("Zoltan_Create failed");
  auto set = [&](const char* name, const std::string& value) { Zoltan_Set_Param(zz, name, value.c_str()); };
  set("DEBUG_LEVEL", "0");
  set("LB_METHOD", "RCB");
  set("NUM_GID_ENTRIES", "2");
  set("NUM_LID_ENTRIES", "1");
  set("OBJ_WEIGHT_DIM", "1");
  set("NUM_GLOBAL_PARTS", std::to_string(parts));
  set("RETURN_LISTS", "NONE");  // the boxes are the answer; the caller moves its own particles
  set("KEEP_CUTS", "1");        // (for Zoltan_RCB_Box)
  set("RCB_REUSE", "0");        // no memory of an earlier call: the same points, the same cuts
  set("AVERAGE_CUTS", "1");     // cuts halfway between the closest points on either side
  set("RCB_OUTPUT_LEVEL", "0");
  set("IMBALANCE_TOL", "1.02");
  Zoltan_Set_Num_Obj_Fn(zz, countObjects, &p);
  Zoltan_Set_Obj_List_Fn(zz, listObjects, &p);
  Zoltan_Set_Num_Geom_Fn(zz, geometryDimension, &p);
  Zoltan_Set_Geom_Multi_Fn(zz, geometry, &p);

  int changes = 0, gidEntries = 0, lidEntries = 0, imports = 0, exports = 0;
  ZOLTAN_ID_PTR importGids = nullptr, importLids = nullptr, exportGids = nullptr, exportLids = nullptr;
  int *importProcs = nullptr, *importParts = nullptr, *exportProcs = nullptr, *exportParts = nullptr;
  const int status = Zoltan_LB_Partition(zz, &changes, &gidEntries, &lidEntries, &imports, &importGids, &importLids,
                                         &importProcs, &importParts, &exports, &exportGids, &exportLids, &exportProcs,
                                         &exportParts);
  Zoltan_LB_Free_Part(&importGids, &importLids, &importProcs, &importParts);
  Zoltan_LB_Free_Part(&exportGids, &exportLids, &exportProcs, &exportParts);
  std::vector<Box> boxes(static_cast<std::size_t>(parts));
  bool ok = status == ZOLTAN_OK;
  for (int part = 0; ok && part < parts; ++part) {
    int dim = 0;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    ok = Zoltan_RCB_Box(zz, part, &dim, &lo[0], &lo[1], &lo[2], &hi[0], &hi[1], &hi[2]) == ZOLTAN_OK;
    // Unbounded sides come as -DBL_MAX / DBL_MAX; the clipped boxes tile the domain, as the cut
    // tree tiles space.
    for (int a = 0; a < 3; ++a) {
      boxes[static_cast<std::size_t>(part)].lower[a] = std::clamp(lo[a], domain.min[a], domain.max[a]);
      boxes[static_cast<std::size_t>(part)].upper[a] = std::clamp(hi[a], domain.min[a], domain.max[a]);
    }
  }
  Zoltan_Destroy(&zz);
  if (env.size() > 1) ok = !anyOverRanks(!ok);
  if (!ok) throw std::runtime_error(fmt::format("Zoltan recursive coordinate bisection into {} parts failed", parts));
  if (env.size() == 1) return boxes;
  // One answer on every rank: rank 0's boxes.
  Bytes mine;
  Packer out(mine);
  for (const Box& b : boxes) out.put(b);
  const Bytes root = broadcastFromRoot(mine);
  Unpacker in(root);
  for (Box& b : boxes) b = in.get<Box>();
  return boxes;
}

}  // namespace gf::parallel
