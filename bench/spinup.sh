# Sourced by the bubbling-bed scripts (bench/cfddem_fluidised_bed.sh, bench/idle_profile.sh,
# bench/phase_ab.sh): the spin-up checkpoint their timed windows restart from.
#   ensure_spinup EXE DIR END_TIME THREADS [refresh]
# runs cases/cfddem_bubbling_fluidised_bed.yaml with EXE from t = 0 to END_TIME (not timed) and
# writes DIR/checkpoint.bin, unless that file exists; with "refresh", also when it is older than EXE.
ensure_spinup() {
  local exe=$1 dir=$2 end=$3 threads=$4 refresh=${5:-}
  local case_file
  case_file=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/cases/cfddem_bubbling_fluidised_bed.yaml
  if [ -f "$dir/checkpoint.bin" ] && { [ -z "$refresh" ] || ! [ "$dir/checkpoint.bin" -ot "$exe" ]; }; then
    return 0
  fi
  echo "spin-up to t = $end s with $exe on $threads thread(s) (not timed) ..."
  "$exe" run "$case_file" --threads "$threads" --end-time "$end" --output "$dir" --overwrite --quiet
}
