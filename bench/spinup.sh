# Sourced by the bubbling-bed scripts (bench/cfddem_fluidised_bed.sh, bench/idle_profile.sh,
# bench/phase_ab.sh; bench/issue_targets.py calls it through bash): the spin-up checkpoint their
# timed windows restart from.
#   ensure_spinup EXE DIR END_TIME [refresh]
# runs cases/cfddem_bubbling_fluidised_bed.yaml with EXE from t = 0 to END_TIME (not timed) and
# writes DIR/checkpoint.bin, unless that file exists; with "refresh", also when it is older than EXE.
# Always on 2 threads, whatever the timed part then uses: the scripts share the directory, and a
# run's bits depend on its thread count, so a fixed count gives every script the same checkpoint
# (and the same checkpoint md5s of the timed runs after it) whichever ran first.
ensure_spinup() {
  local exe=$1 dir=$2 end=$3 refresh=${4:-}
  local case_file
  case_file=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/cases/cfddem_bubbling_fluidised_bed.yaml
  if [ -f "$dir/checkpoint.bin" ] && { [ -z "$refresh" ] || ! [ "$dir/checkpoint.bin" -ot "$exe" ]; }; then
    return 0
  fi
  echo "spin-up to t = $end s with $exe on 2 threads (not timed) ..."
  "$exe" run "$case_file" --threads 2 --end-time "$end" --output "$dir" --overwrite --quiet
}
