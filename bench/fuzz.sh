#!/usr/bin/env bash
# Fuzzes the LEF, DEF and guide readers with libFuzzer (clang + AddressSanitizer).
#
#   bash bench/fuzz.sh [SECONDS_PER_TARGET]     (default 60)
#
# Needs clang with its libFuzzer runtime. On Debian/Ubuntu:
#   apt-get install clang-14 libclang-rt-14-dev
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
# Exit status: 0 when no target found anything, 1 otherwise, 2 on setup errors.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
secs=${1:-60}
data=${XROUTE_TESTCASES:-$root/../shared/testcases}
data=${data%%:*}
cxx=${CXX_FUZZ:-$(command -v clang++ || command -v clang++-14 || true)}
[ -n "$cxx" ] || { echo "fuzz.sh: clang++ not found (apt-get install clang-14 libclang-rt-14-dev)" >&2; exit 2; }
[ -d "$data/ispd18_sample" ] || { echo "fuzz.sh: testcases not found in $data" >&2; exit 2; }

build=$root/build/fuzz
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DXROUTE_PYTHON=OFF -DXROUTE_FUZZ=ON >/dev/null
ninja -C "$build" fuzz_lef fuzz_def fuzz_guide >/dev/null

s=$data/ispd18_sample/ispd18_sample.input
s2=$data/ispd18_sample2/ispd18_sample2.input
rm -rf "$build/seeds"
mkdir -p "$build"/seeds/{lef,def,guide} "$build"/corpus/{lef,def,guide} "$build/artifacts"
cp "$s.lef" "$s2.lef" "$root"/tests/data/lef/*.lef "$build/seeds/lef/"
cp "$s.def" "$s2.def" "$build/seeds/def/"
cp "$s.guide" "$build/seeds/guide/"
for t in lef def guide; do
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
exit $status
