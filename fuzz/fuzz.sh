#!/usr/bin/env bash
# Fuzzes the LEF, DEF and guide readers with libFuzzer (clang + AddressSanitizer), and the
# YAML configs (route --config, batch) with fuzz/fuzz_yaml.py (atheris when installed,
# `pip install atheris`; a built-in mutator otherwise).
#
#   bash fuzz/fuzz.sh [SECONDS_PER_TARGET]     (default 60)
#
# Needs clang (15 or later) with its libFuzzer runtime. On Debian/Ubuntu:
#   apt-get install clang-16 libclang-rt-16-dev
# (CXX_FUZZ=/path/to/clang++ picks another clang.)
#
# Seeds (rebuilt each run in build/fuzz/seeds/<target>/): the ispd18_sample and
# ispd18_sample2 inputs, the small LEFs in tests/data/lef/ and every file in
# tests/fuzz_regressions/<target>/. What libFuzzer finds is kept in
# build/fuzz/corpus/<target>/ and grows from run to run. Each target gets a
# keyword dictionary taken from the string literals of its reader, so mutations
# speak the format. Any input that crashes, hangs, leaks or runs out of memory
# lands in build/fuzz/artifacts/; minimize it
#   build/fuzz/fuzz_<target> -minimize_crash=1 -runs=20000 <artifact>
# (with XROUTE_FUZZ_LEF/XROUTE_FUZZ_DEF set as below), fix the reader and keep
# the input as tests/fuzz_regressions/<target>/<name> (tests/test_fuzz_regressions.py
# loads every file there through the Python API).
# Then fuzz/hostile_cli.py runs HOSTILE_CASES cases (default 100; HOSTILE_SEED picks the seed).
# Exit status: 0 when no target found anything, 1 otherwise, 2 on setup errors.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
secs=${1:-60}
data=${XROUTE_TESTCASES:-$root/../shared/testcases}
data=${data%%:*}
# clang 15 or later: clang 14 rejects a lambda capturing a structured binding (engine_cpp/drc).
cxx=${CXX_FUZZ:-$(command -v clang++-16 || command -v clang++-15 || command -v clang++ || true)}
[ -n "$cxx" ] || { echo "fuzz.sh: clang++ not found (apt-get install clang-16 libclang-rt-16-dev)" >&2; exit 2; }
[ -d "$data/ispd18_sample" ] || { echo "fuzz.sh: testcases not found in $data" >&2; exit 2; }

build=$root/build/fuzz
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DXROUTE_PYTHON=OFF -DXROUTE_FUZZ=ON -DCMAKE_CXX_SCAN_FOR_MODULES=OFF >/dev/null
ninja -C "$build" -j "${FUZZ_BUILD_JOBS:-2}" fuzz_lef fuzz_def fuzz_guide >/dev/null

s=$data/ispd18_sample/ispd18_sample.input
s2=$data/ispd18_sample2/ispd18_sample2.input
rm -rf "$build/seeds"
mkdir -p "$build"/seeds/{lef,def,guide} "$build"/corpus/{lef,def,guide} "$build/artifacts"
cp "$s.lef" "$s2.lef" "$root"/tests/data/lef/*.lef "$build/seeds/lef/"
cp "$s.def" "$s2.def" "$build/seeds/def/"
cp "$s.guide" "$build/seeds/guide/"
mkdir -p "$build"/seeds/yaml "$build"/corpus/yaml
cp "$root"/configs/*.yaml "$build/seeds/yaml/"
for t in lef def guide yaml; do
  if [ -d "$root/tests/fuzz_regressions/$t" ]; then
    find "$root/tests/fuzz_regressions/$t" -maxdepth 1 -type f -exec cp {} "$build/seeds/$t/" \;
  fi
done

# Dictionaries: the upper-case keywords the readers compare against, plus the
# punctuation and the sample's layer names.
dict() {  # dict OUT SOURCES...
  local out=$1
  shift
  { { grep -ohE '"[A-Z][A-Z0-9_]*"' "$@" || true; } | sort -u | sed 's/^"\(.*\)"$/"\1 "/'
    printf '"%s"\n' "; " "( " ") " "+ " "- " "* " "0 " "-1 " "1e9 " "\\x22" "#"
    awk '$1 == "LAYER" && NF == 2 {printf "\"%s \"\n", $2}' "$s.lef" | sort -u
  } >"$out"
}
dict "$build/lef.dict" "$root"/engine_cpp/io/lef*.cpp
dict "$build/def.dict" "$root"/engine_cpp/io/def*.cpp
dict "$build/guide.dict" "$root"/engine_cpp/io/guide_reader.cpp

export XROUTE_FUZZ_LEF=$s.lef XROUTE_FUZZ_DEF=$s.def
export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
status=0
printf '%-6s %10s %8s %7s %8s  %s\n' target execs exec/s corpus seconds result
for t in lef def guide; do
  log=$build/fuzz_$t.log
  # max_len: a little above the largest seed (the 42 KB sample LEF), so
  # libFuzzer may grow inputs but does not waste time on megabyte files.
  if "$build/fuzz_$t" "$build/corpus/$t" "$build/seeds/$t" -dict="$build/$t.dict" \
      -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
      -print_final_stats=1 -artifact_prefix="$build/artifacts/$t-" >"$log" 2>&1; then
    result="no crash"
  else
    status=1
    result="FOUND SOMETHING (see $log)"
  fi
  execs=$(awk '/^stat::number_of_executed_units/ {print $2}' "$log")
  rate=$(awk '/^stat::average_exec_per_sec/ {print $2}' "$log")
  took=$(awk '/^Done [0-9]+ runs in/ {print $5}' "$log")
  printf '%-6s %10s %8s %7s %8s  %s\n' "$t" "${execs:-?}" "${rate:-?}" \
    "$(find "$build/corpus/$t" -type f | wc -l)" "${took:-?}" "$result"
  if [ "$result" != "no crash" ]; then
    grep -E 'ERROR|SUMMARY|Test unit written' "$log" | head -5 | sed 's/^/       /'
  fi
done
# The YAML-config target (Python, same columns).
py=${PYTHON:-python3}
log=$build/fuzz_yaml.log
{ printf '"%s"\n' "<<: " "&a " "*a" "!!python/name:" "!tag " "[" "]" "{" "}" ": " "- " "---" "2147483648" \
    "99999999999999999999" ".inf" ".nan" "2020-13-45" "null" "~"
  grep -ohE '^ *[a-z_]+:' "$root"/configs/*.yaml | tr -d ' :' | sort -u | sed 's/.*/"&: "/'
} >"$build/yaml.dict"
if "$py" -c "import atheris" 2>/dev/null; then
  how=atheris
  set +e
  PYTHONPATH=$root "$py" "$root/fuzz/fuzz_yaml.py" "$build/corpus/yaml" "$build/seeds/yaml" -dict="$build/yaml.dict" \
    -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/yaml-" >"$log" 2>&1
  rc=$?
  set -e
else
  how=plain
  set +e
  PYTHONPATH=$root "$py" "$root/fuzz/fuzz_yaml.py" --plain "$secs" "$build"/seeds/yaml/* >"$log" 2>&1
  rc=$?
  set -e
fi
if [ $rc -eq 0 ]; then result="no crash ($how)"; else status=1; result="FOUND SOMETHING (see $log)"; fi
execs=$(awk '/^stat::number_of_executed_units/ {print $2}' "$log")
rate=$(awk '/^stat::average_exec_per_sec/ {print $2}' "$log")
took=$(awk '/^Done [0-9]+ runs in/ {print $5}' "$log")
printf '%-6s %10s %8s %7s %8s  %s\n' yaml "${execs:-?}" "${rate:-?}" \
  "$(find "$build/corpus/yaml" -type f | wc -l)" "${took:-?}" "$result"
if [ $rc -ne 0 ]; then grep -E 'Error|CRASH|Traceback|Test unit written' "$log" | head -5 | sed 's/^/       /'; fi
# The hostile-use harness: special files, odd policies, numbers, deep JSON, kills.
log=$build/hostile_cli.log
set +e
PYTHONPATH=$root "$py" "$root/fuzz/hostile_cli.py" --cases "${HOSTILE_CASES:-100}" --seed "${HOSTILE_SEED:-$RANDOM}" \
  --keep "$build/artifacts/hostile" >"$log" 2>&1
rc=$?
set -e
if [ $rc -eq 0 ]; then result="no finding"; else status=1; result="FOUND SOMETHING (see $log)"; fi
printf '%-6s %10s %8s %7s %8s  %s\n' hostile "${HOSTILE_CASES:-100}" - - - "$result"
exit $status
