# Sourced by bench/host_check.sh and bench/pinned_pairs.sh.
#   ns_per_step EXE BENCHMARK CPU
# runs `EXE bench BENCHMARK` on one thread pinned to CPU and prints its ns_per_particle_step
# counter (nothing if the run gave no figure). BENCHMARK is a name prefix such as BM_DemSettledBed/.
ns_per_step() {
  taskset -c "$3" "$1" bench "$2" --threads 1 2>/dev/null | awk -v name="$2" '
    /^Benchmark/ { for (i = 1; i <= NF; ++i) if ($i == "ns_per_particle_step") column = i + 2 }
    index($0, name) == 1 && column { value = $column; sub(/[a-zA-Z]+$/, "", value); print value }'
}
