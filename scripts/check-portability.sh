#!/usr/bin/env bash
# Check that the verdicts of the core's counting tests (CTest label "counts" of Testing/Core: they
# count eigenvalues, components, multiplets, bands, flips or operator applications, or compare a
# rounding-sized figure with a bound) do not depend on the machine's floating-point arithmetic.
#
# Builds the core's tests (Testing/Core, Release) for each of ARCHS (MANIFOLDHARMONICS_ARCH) and
# runs every "counts" test in each combination of
#   - the build: the x86-64 baseline and the build machine's own instructions (-march=native);
#   - the thread count: THREADS, for the core (MANIFOLDHARMONICS_TEST_THREADS, see
#     Testing/Core/Checks.h) and for OpenBLAS (OPENBLAS_NUM_THREADS);
#   - the input: as generated, and with every coordinate of the generated meshes times
#     1 + 1e-15 u for each seed of SEEDS (MANIFOLDHARMONICS_TEST_PERTURBATION, see
#     Testing/Core/Perturbation.h).
# The verdict of a run is its exit status and the sequence of ok/FAIL of its checks. The script
# prints a table of the runs and the tightest margins seen (checks "value <= bound"), and fails if
# the verdict of any test moves between runs, or if any run fails. It leaves the BLAS's own
# settings alone (OPENBLAS_CORETYPE and the like stay as the environment has them).
#
# Environment: BUILD_ROOT (default build/core: builds in build/core-<arch>, run logs in
# build/core-runs), ARCHS (default "x86-64 native"),
# THREADS (default "1 2"), SEEDS (default "1 2 3"), LABEL (default counts), EXCLUDE (a label
# to leave out, e.g. slow; default none), REGEX (only the tests whose names match), JOBS (parallel builds
# and test runs, default 2), TEST_TIMEOUT (seconds per run, default 600).
set -euo pipefail

source_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_root="${BUILD_ROOT:-build/core}"
case "${build_root}" in
  /*) ;;
  *) build_root="${source_dir}/${build_root}" ;;
esac
archs=(${ARCHS:-x86-64 native})
threads_list=(${THREADS:-1 2})
seeds=(none ${SEEDS:-1 2 3})
label="${LABEL:-counts}"
exclude="${EXCLUDE:-}"
regex="${REGEX:-}"
jobs="${JOBS:-2}"
test_timeout="${TEST_TIMEOUT:-600}"
start=${SECONDS}

for arch in "${archs[@]}"; do
  echo "=== Build for ${arch}: ${build_root}-${arch}"
  cmake -S "${source_dir}/Testing/Core" -B "${build_root}-${arch}" \
    -DCMAKE_BUILD_TYPE=Release -DMANIFOLDHARMONICS_ARCH="${arch}" > /dev/null
  cmake --build "${build_root}-${arch}" -j "${jobs}" > /dev/null
done
echo "=== Builds took $((SECONDS - start)) s"

# Test names Core.<executable>.<case>, from CTest's label.
mapfile -t tests < <(ctest --test-dir "${build_root}-${archs[0]}" -N -L "${label}" \
  ${exclude:+-LE "${exclude}"} ${regex:+-R "${regex}"} |
  sed -n 's/^ *Test *#[0-9]*: *//p')
echo "=== ${#tests[@]} tests labelled ${label}${exclude:+, not ${exclude}}"

# One run: <arch> <threads> <seed> <test>; its output goes to <BUILD_ROOT>-runs/<config>/<test>.log, its exit
# status to the last line.
run_one ()
{
  local arch=$1 threads=$2 seed=$3 test=$4
  local executable=${test#Core.}
  local case=${executable#*.}
  executable=${executable%%.*}
  local dir="${build_root}-runs/${arch}-t${threads}-s${seed}"
  local perturbation=""
  [ "${seed}" = none ] || perturbation=${seed}
  local status=0
  env OPENBLAS_NUM_THREADS="${threads}" MANIFOLDHARMONICS_TEST_THREADS="${threads}" \
    MANIFOLDHARMONICS_TEST_PERTURBATION="${perturbation}" \
    timeout "${test_timeout}" "${build_root}-${arch}/${executable}" "${case}" \
    > "${dir}/${test}.log" 2>&1 || status=$?
  echo "exit ${status}" >> "${dir}/${test}.log"
}
export -f run_one
export build_root test_timeout

rm -rf "${build_root}-runs"
run_start=${SECONDS}
for arch in "${archs[@]}"; do
  for threads in "${threads_list[@]}"; do
    for seed in "${seeds[@]}"; do
      mkdir -p "${build_root}-runs/${arch}-t${threads}-s${seed}"
      for test in "${tests[@]}"; do
        echo "${arch} ${threads} ${seed} ${test}"
      done
    done
  done
done | xargs -P "${jobs}" -L 1 bash -c 'run_one "$@"' _
echo "=== Runs took $((SECONDS - run_start)) s"

# Compare the verdicts of every test across the runs.
status=0
/usr/bin/python3 - "${build_root}-runs" "${tests[@]}" << 'EOF' || status=1
import os
import re
import sys

root, tests = sys.argv[1], sys.argv[2:]
configs = sorted(os.listdir(root))
check = re.compile(r"^\s*\[( ok |FAIL)\] (.*)$")
margin = re.compile(r": ([-+0-9.eE]+|nan|-?inf) <= ([-+0-9.eE]+)$")
moved, failed, tight = [], [], {}
print("%-54s %s" % ("test", " ".join("%s" % c for c in configs)))
for test in tests:
    verdicts = {}
    for config in configs:
        with open(os.path.join(root, config, test + ".log")) as log:
            lines = log.read().splitlines()
        marks = []
        for line in lines:
            m = check.match(line)
            if not m:
                continue
            marks.append(m.group(1) == " ok ")
            bound = margin.search(m.group(2))
            if bound and float(bound.group(2)) > 0.0:
                ratio = float(bound.group(1)) / float(bound.group(2))
                key = (test, re.sub(r"[-+0-9.eE]+ <= [-+0-9.eE]+$", "", m.group(2)))
                if ratio == ratio and ratio > tight.get(key, (-1.0, ""))[0]:
                    tight[key] = (ratio, config)
        status = lines[-1] if lines else "exit ?"
        verdicts[config] = (status, tuple(marks))
        if status != "exit 0":
            failed.append("%s [%s]: %s, %d failed check(s)" %
                          (test, config, status, marks.count(False)))
    reference = verdicts[configs[0]]
    same = all(v == reference for v in verdicts.values())
    if not same:
        moved.append(test)
    print("%-54s %s%s" % (test, " ".join(
        ("pass" if v[0] == "exit 0" else "FAIL").center(len(c)) for c, v in
        sorted(verdicts.items())), "" if same else "   <- MOVED"))
print("\nTightest margins (measured / bound, largest over the runs):")
for (test, what), (ratio, config) in sorted(tight.items(), key=lambda x: -x[1][0])[:15]:
    print("  %.2e  %s: %s[%s]" % (ratio, test, what, config))
for line in failed:
    print("FAILED: " + line)
if moved:
    print("MOVED: the verdicts of %s change between runs" % ", ".join(moved))
if moved or failed:
    sys.exit(1)
print("Every verdict is the same in all %d runs of %d tests" % (len(configs), len(tests)))
EOF
echo "=== check-portability took $((SECONDS - start)) s"
exit "${status}"
