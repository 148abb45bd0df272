# SPDX-License-Identifier: BSD-3-Clause
# Wall-clock phases of a script, sourced by scripts/test.sh and .ci/run:
#   phase NAME        ends the phase running (if any) and starts NAME, printing "== NAME"
#   phases_report     ends the phase running and prints each phase's wall time and the total
#   phases_report_on_exit NAME   prints that report when the script exits, failed or not
#   slowest_tests LOG N   the N slowest tests of a ctest output saved in LOG
_phase_names=()
_phase_seconds=()
_phase_name=""
_phase_start=$SECONDS
_phases_start=$SECONDS

_phase_end() {
  if [ -n "$_phase_name" ]; then
    _phase_names+=("$_phase_name")
    _phase_seconds+=($((SECONDS - _phase_start)))
  fi
  _phase_name=""
}

phase() {
  _phase_end
  _phase_name=$1
  _phase_start=$SECONDS
  echo "== $1"
}

phases_report() {
  _phase_end
  echo "== wall time by phase ($1)"
  local i
  for i in "${!_phase_names[@]}"; do
    printf '  %6d s  %s\n' "${_phase_seconds[$i]}" "${_phase_names[$i]}"
  done
  printf '  %6d s  total (%d min)\n' $((SECONDS - _phases_start)) $(((SECONDS - _phases_start) / 60))
}

phases_report_on_exit() {
  # shellcheck disable=SC2064  # NAME is expanded now, on purpose
  trap "phases_report '$1'" EXIT
}

slowest_tests() {
  echo "== the $2 slowest tests of $1"
  # awk reads every line (head would close the pipe early: SIGPIPE fails the pipeline)
  sed -nE 's/.*Test +#[0-9]+: ([^ ]+) .* ([0-9.]+) sec.*/\2 \1/p' "$1" | sort -rn \
    | awk -v n="$2" 'NR <= n { printf "  %8.1f s  %s\n", $1, $2 }'
}
